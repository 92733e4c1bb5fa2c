"""Run a :class:`~axlebox.mbs.solver.system.Model` in time: fixed-step RK4, leapfrog (explicit central
differences) or generalized-alpha, output at a
fixed rate, divergence caught and named, results kept when a run stops early.

The run goes in chunks (``chunk`` simulated seconds) so that progress can be shown and a
checkpoint written between them; each chunk is one call into numba.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from axlebox._params import ParameterError, check_ranges, choice, param
from axlebox._threads import Fitter

from ..kernel import integrate as ki
from ..kernel.exchange import HOLDS, exchange
from ..wheelrail import element_kernel as ek
from .system import Model

METHODS = ("rk4", "leapfrog", "imex", "imex2", "galpha")


@dataclass(frozen=True)
class Settings:
    """Integrator settings: the car config's ``[integrator]`` and ``[coupling]`` fields (declared
    here, once; mbs/vehicle/config.py takes them over) and the Newton's; ``dt`` must divide the output
    period.  Their cross-field checks live here alone (a car config runs them by building its
    settings)."""

    method: str = choice("leapfrog", METHODS, doc="'leapfrog' (explicit central differences), "
                         "'imex' (the leapfrog with the bearings' contact damping implicit), "
                         "'imex2' (their contact stiffness, by Newmark's average acceleration, "
                         "and friction too: experimental, benchmarks/README.md), 'rk4' or "
                         "'galpha'; leapfrog at 5e-5 s: the car's axle-box RMS within 0.1 % of "
                         "RK4 at 1.25e-5 s, faster than real time")
    dt: float = param(5e-5, 1e-8, 1e-2, unit="s", doc="fixed step; with bearings and a leapfrog "
                      "method, the bearings' sub-step")
    output_rate_hz: float = param(10_000.0, 1.0, 1e7, unit="Hz", doc="sensor output rate")
    state_rate_hz: float = param(500.0, 0.1, 1e7, unit="Hz", doc="rate of whole-state snapshots")
    rho_inf: float = param(0.8, 0.0, 1.0, unit="", doc="generalized-alpha spectral radius at infinity")
    max_iter: int = param(8, 2, 50, unit="", doc="Newton iterations before the Jacobian is refreshed")
    rtol: float = param(1e-9, 0.0, 1e-2, unit="", doc="Newton relative tolerance on the state")
    vmax: float = param(1e3, 1.0, 1e9, unit="m/s", doc="a velocity state beyond this is a runaway")
    exchange_dt: float = param(0.0, 0.0, 1e-2, unit="s", doc="the bodies' step and their exchange "
                               "with the bearings (mbs/kernel/exchange.py), a whole multiple of dt; 0: dt")
    body_substeps: int = param(1, 1, 1000, unit="", doc="the bodies' steps an exchange, the bearings' "
                               "loads held between (a co-simulation, mbs/kernel/exchange.py); 1: one")
    hold: str = choice("zoh", HOLDS, doc="how the co-simulation holds the bearings' loads between "
                       "exchanges: 'zoh', 'linear' or 'jacobian'")

    def __post_init__(self):
        check_ranges(self)
        if self.body_substeps > 1 and (self.exchange_dt <= 0.0 or self.method in ("rk4", "galpha")):
            raise ParameterError(f"coupling.body_substeps = {self.body_substeps} is not allowed with "
                                 f"integrator.method = {self.method!r} and coupling.exchange_dt = "
                                 f"{self.exchange_dt:g}: the bodies step between exchanges only in a "
                                 "leapfrog run with exchange_dt > 0; expected 1")
        if self.exchange_dt > 0.0:
            if self.method in ("rk4", "galpha") and self.exchange_dt != self.dt:
                raise ParameterError(f"coupling.exchange_dt = {self.exchange_dt:g} is not allowed with "
                                     f"integrator.method = {self.method!r}: only the leapfrog methods "
                                     f"step the bearings apart (0 or dt = {self.dt:g})")
            n = self.exchange_dt / self.dt
            if n < 1.0 - 1e-9 or abs(n - round(n)) > 1e-6 * n:
                raise ParameterError(f"coupling.exchange_dt = {self.exchange_dt:g} is not allowed: "
                                     f"expected a whole multiple of integrator.dt = {self.dt:g} s")
        step, name = ((self.exchange_dt, "coupling.exchange_dt") if self.exchange_dt > 0
                      else (self.dt, "integrator.dt"))
        ratio = 1.0 / (self.output_rate_hz * step)
        if ratio < 1.0 - 1e-9:
            raise ParameterError(f"integrator.output_rate_hz = {self.output_rate_hz:g} is not allowed: "
                                 f"above the step rate 1/{name} = {1 / step:g} Hz")
        if abs(ratio - round(ratio)) > 1e-6 * ratio:
            raise ParameterError(f"{name} = {step:g} is not allowed: "
                                 f"it must divide the output period 1/{self.output_rate_hz:g} s a "
                                 "whole number of times")
        if self.state_rate_hz > self.output_rate_hz:
            raise ParameterError(f"integrator.state_rate_hz = {self.state_rate_hz:g} is not allowed: "
                                 f"at most integrator.output_rate_hz = {self.output_rate_hz:g}")

    @property
    def step(self) -> float:
        """The bodies' step: ``exchange_dt``, or ``dt`` where that is 0."""
        return self.exchange_dt if self.exchange_dt > 0.0 else self.dt

    @property
    def n_exchange(self) -> int:
        """The bearings' sub-steps an exchange (1: single rate)."""
        return int(round(self.step / self.dt))

    @property
    def n_sub(self) -> int:
        """Steps of the bodies an output."""
        return int(round(1.0 / (self.output_rate_hz * self.step)))

    @property
    def state_every(self) -> int:
        return max(1, int(round(self.output_rate_hz / self.state_rate_hz)))


@dataclass
class Run:
    """What a run produced (also when it stopped early: ``status`` and ``message`` say why)."""

    time: np.ndarray                 # (t,) s
    sensors: dict[str, np.ndarray]   # name -> (t, 3) m/s^2, inertial x, y, z
    wheels: np.ndarray               # (t, n_wheels, n_out) wheel-rail outputs
    elements: np.ndarray             # (t, n_elements, 6) element outputs
    state_time: np.ndarray
    states: np.ndarray               # (ts, n_states)
    y_end: np.ndarray
    bearings: np.ndarray = None      # (t, n_bearings, BR_ROWS, 6): mbs/kernel/bearings.py
    exchange: np.ndarray = None      # the bearings' ring motion at the last exchange (mbs/kernel/exchange.py)
    status: str = "done"
    message: str = ""
    wall_s: float = 0.0
    stats: dict = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return self.status == "done"


_STATUS = {ki.NOT_FINITE: "not finite", ki.RUNAWAY: "runaway", ki.NO_CONVERGENCE: "no convergence",
           ki.DERAILED: "derailed"}


OUTPUTS = ("out_t", "out_sens", "out_wh", "out_el", "out_y")       # what a checkpoint holds, with y


def split_outputs(model: Model, out_wh: np.ndarray, out_el: np.ndarray) -> dict:
    """A run's wheel-rail and element output rows as :class:`Run` holds them: ``wheels``,
    ``elements`` and ``bearings`` (the element rows after the model's own elements,
    mbs/kernel/bearings.py ``BR_ROWS`` a bearing)."""
    from ..kernel.bearings import BR_ROWS
    nw, ne, nbr = len(model.wheel_names), model.S.el_i.shape[0], len(model.bearing_names)
    return {"wheels": out_wh[:, :nw], "elements": out_el[:, :ne],
            "bearings": out_el[:, ne:ne + BR_ROWS * nbr].reshape(out_el.shape[0], nbr, BR_ROWS, 6)}


def exchange_of(model: Model, s: Settings, ring=None):
    """The exchange of ``model``'s bearings a run under ``s`` makes (:func:`axlebox.mbs.kernel.exchange.exchange`;
    ``ring``: the last one's ring motion of a run this one continues)."""
    return exchange(model, s.method if s.method in ("leapfrog", "imex", "imex2") else "leapfrog", s.dt,
                    s.n_exchange, ring, m=s.body_substeps, hold=s.hold,
                    K=getattr(model, "bearing_stiffness", None))


def _kernel_call(s, run_args, X, guard, O, start: bool, newton, shared):
    """The run kernel of ``s.method`` and its arguments: one place for :func:`simulate`, which
    calls it, and :func:`compile_run`, which compiles it for the same argument types."""
    if s.method == "rk4":
        return ki.run_rk4, (*run_args, guard, O, shared)
    if s.method in ("leapfrog", "imex", "imex2"):
        return ki.run_leapfrog, (*run_args, X, guard, O, start, shared)
    return ki.run_galpha, (*run_args, guard, O, newton, shared)


def run_signature(model: Model, settings: Settings | None = None):
    """``(kernel, types)``: the run kernel :func:`simulate` calls for ``model`` under ``settings``
    and its arguments' types there (its arrays made one output long, which their types do not
    depend on); None for galpha, whose kernel is left to the run."""
    import numba
    s = settings or Settings()
    if s.method == "galpha":
        return None
    W = model.W
    O = ki.Outputs(t=np.zeros(1), sens=np.zeros((1, W.sensout.shape[0], 3)),
                   wh=np.zeros((1,) + W.whout.shape), el=np.zeros((1, W.elout.shape[0], 6)),
                   y=np.zeros((1, model.y0.size)), state_every=s.state_every, base=0)
    guard = ki.Guard(nq=model.nq, nend=model.n_body_states, vmax=s.vmax)
    y = np.array(model.y0, float)
    kernel, args = _kernel_call(s, (y, 0.0, s.step, s.n_sub, 1, 0, 0, model.S, W, model.B),
                                exchange_of(model, s), guard, O, True, None, np.zeros(3, np.int64))
    return kernel, tuple(numba.typeof(a) for a in args)


def compile_run(model: Model, settings: Settings | None = None) -> None:
    """Compile (or load from numba's cache) the run kernel :func:`simulate` calls for ``model``
    under ``settings``, without running it (:func:`run_signature`): what a process that
    compiles ahead of a run calls (pipelines/ahead.py)."""
    found = run_signature(model, settings)
    if found is not None:
        found[0].compile(found[1])


def simulate(model: Model, duration: float, settings: Settings | None = None, *, y0=None,
             t0: float = 0.0, chunk: float = 0.25, progress=None, continued: bool = False,
             checkpoint=None, checkpoint_every: float = 0.0, resume: dict | None = None,
             sink=None, exchange_ring=None, threads: Fitter | None = None) -> Run:
    """Integrate ``model`` for ``duration`` s from ``y0`` (default: the model's initial state).

    ``continued``: ``y0`` is the ``y_end`` of an earlier leapfrog run with the same step, whose
    velocities are half a step behind (the run then goes on as if it had not stopped), and
    ``exchange_ring`` its :attr:`Run.exchange` where it had bearings.
    ``checkpoint(snapshot)``: called at the first end of a chunk after ``checkpoint_every``
    simulated seconds since the last (the chunks are the same with and without checkpoints:
    where a chunk ends moves the last bits of the step times), with ``{"k": outputs done, "y":
    the state, "wall_s", and the output arrays OUTPUTS up to k}``; ``resume``: such a
    snapshot, from which the run goes on as the uninterrupted one would (the same steps at the
    same times: bit for bit).

    ``sink(k0, arrays)``: the outputs streamed instead of kept (memory flat in the run's
    length): called after every chunk with its first output ``k0`` and the arrays OUTPUTS of its
    outputs (``out_y``: the state snapshots among them, those of ``k % state_every == 0``), in
    order, the same values as the kept run's; the returned run's output arrays are then empty,
    and the snapshots ``checkpoint`` gets and ``resume`` takes hold only ``k``, ``y`` and
    ``wall_s``.

    ``threads``: what fits numba's threads to the cores other processes leave free as the run
    goes (:class:`axlebox._threads.Fitter`, applied inside the chunks: the chunks stay as they
    are); default: as the environment's ``AXLEBOX_THREADS`` says.  The results are the same bits
    on any thread count."""
    s = settings or Settings()
    fitter = threads if threads is not None else Fitter.from_env()
    if not (math.isfinite(duration) and duration > 0):
        raise ParameterError(f"duration = {duration!r} is not allowed: expected a time > 0 s")
    h = s.step
    n_out = int(round(duration * s.output_rate_hz)) + 1
    y = np.array(model.y0 if y0 is None else y0, float)
    W = model.W
    S = model.S
    if resume is not None:
        exchange_ring = resume.get("exchange")
    if s.hold == "jacobian" and s.body_substeps > 1 and model.bearing_names \
            and getattr(model, "bearing_stiffness", None) is None:
        raise ParameterError("coupling.hold = 'jacobian' is not allowed for this model: it has no "
                             "bearing_stiffness (pipelines/simulate.build_model sets it; "
                             "mbs/bearings.stiffness); expected 'zoh' or 'linear'")
    X = exchange_of(model, s, exchange_ring if (continued or resume is not None) else None)
    se = s.state_every
    per = max(1, int(round(chunk * s.output_rate_hz)))
    rows = n_out if sink is None else min(per, n_out)        # the whole run, or one chunk
    out_t = np.zeros(rows)
    out_sens = np.zeros((rows, W.sensout.shape[0], 3))
    out_wh = np.zeros((rows, W.whout.shape[0], W.whout.shape[1]))
    out_el = np.zeros((rows, W.elout.shape[0], 6))
    out_y = np.zeros(((rows - 1) // se + 1 + (sink is not None), y.size))
    stats = np.zeros(5, np.int64)
    nbr = len(model.bearing_names)
    nend = model.n_body_states
    if s.method == "galpha" and nbr:
        raise ParameterError("integrator.method = 'galpha' is not allowed with roller bearings: "
                             "their roller and cage states are not in the Jacobian's coupling "
                             "pattern; use 'leapfrog' or 'rk4'")
    if s.method == "galpha":
        pattern, groups, n_groups = model.coupling_pattern()
        scale, atol = model.state_scales()
        newton = ki.Newton(rho_inf=s.rho_inf, groups=groups, n_groups=n_groups, pattern=pattern,
                           scale=scale, atol=atol, rtol=s.rtol, max_iter=s.max_iter, stats=stats)
    guard = ki.Guard(nq=model.nq, nend=nend, vmax=s.vmax)
    outs = {"out_t": out_t, "out_sens": out_sens, "out_wh": out_wh, "out_el": out_el, "out_y": out_y}
    k, status, bad, wall_before = 0, ki.OK, -1, 0.0
    if resume is not None:
        k = int(resume["k"])
        y[:] = resume["y"]
        if sink is None:
            for name, arr in outs.items():
                n = resume[name].shape[0]
                arr[:n] = resume[name]
        wall_before = float(resume.get("wall_s", 0.0))

    def first_state(k):                 # the index of the first snapshot at or after output k
        return (k + se - 1) // se

    def flush(k0, k1):                  # the chunk's outputs k0 .. k1 - 1 to the sink
        if sink is not None and k1 > k0:
            sink(k0, {"out_t": out_t[:k1 - k0], "out_sens": out_sens[:k1 - k0],
                      "out_wh": out_wh[:k1 - k0], "out_el": out_el[:k1 - k0],
                      "out_y": out_y[:first_state(k1) - first_state(k0)]})
    wall0 = time.perf_counter()
    k_saved = k
    with fitter:
        while k < n_out:
            k1 = min(n_out, k + per)
            tk = t0 + k * s.n_sub * h
            O = ki.Outputs(t=out_t, sens=out_sens, wh=out_wh, el=out_el, y=out_y, state_every=se,
                           base=0 if sink is None else k)
            kernel, args = _kernel_call(s, (y, tk, h, s.n_sub, k1, k, n_out - 1, S, W, model.B),
                                        X, guard, O, k == 0 and not continued,
                                        newton if s.method == "galpha" else None, fitter.shared)
            try:
                status, k_done, bad = kernel(*args)
            except (ZeroDivisionError, FloatingPointError):
                # a state blown up between two outputs can meet a division by zero in a kernel
                # before the output's finiteness check: the same divergence, caught a little later
                status, k_done, bad = ki.NOT_FINITE, k, -1
            if status != ki.OK:
                # the output that showed the divergence is kept too (as the kept run's n_keep)
                flush(k, min(n_out, k_done + (1 if status in ki.KEEP_LAST else 0)))
                k = k_done
                break
            flush(k, k1)
            k = k1
            if progress is not None:
                progress((k - 1) * s.n_sub * h, duration)
            due = (k - k_saved) >= checkpoint_every * s.output_rate_hz - 0.5
            if checkpoint is not None and k < n_out and due:
                snap = {"k": k, "y": y, "exchange": X.ring,
                        "wall_s": wall_before + time.perf_counter() - wall0}
                if sink is None:
                    ks = (k - 1) // se + 1
                    snap.update({"out_t": out_t[:k], "out_sens": out_sens[:k], "out_wh": out_wh[:k],
                                 "out_el": out_el[:k], "out_y": out_y[:ks]})
                checkpoint(snap)
                k_saved = k
    wall = wall_before + time.perf_counter() - wall0
    n_keep = k + (1 if status in ki.KEEP_LAST else 0)
    n_keep = min(n_keep, n_out)
    msg = ""
    st = "done"
    if status != ki.OK:
        st = _STATUS[status]
        tbad = t0 + k * s.n_sub * h
        where = model.state_owner(bad) if bad >= 0 else "the coupled system"
        if status == ki.NO_CONVERGENCE:
            msg = (f"Newton did not converge at t = {tbad:.6f} s (step {h:g} s); try a smaller dt "
                   f"or method 'rk4'")
        elif status == ki.DERAILED:
            if W.whout[bad, ek.OUT_CLAMP] == ek.CLAMP_FLANGE:
                why = ("past its flange side's end: a flange climb (the wheelset beyond the "
                       "lateral range where both wheels touch, wheelrail y_max)")
            else:
                why = ("past its field side's end: the wheel run off its rail head (beyond "
                       "wheelrail y_max + y_field, a gauge opening wider than the table reaches)")
            msg = (f"wheel {model.wheel_names[bad]!r} left its contact table at t = {tbad:.6f} s, "
                   f"{why}; what was computed is kept")
        else:
            msg = f"the run diverged at t = {tbad:.6f} s: {st} in {where}"
    ks = (n_keep - 1) // se + 1 if n_keep else 0
    if sink is not None:                # streamed: nothing kept here
        n_keep = ks = 0
    return Run(time=out_t[:n_keep], sensors={nm: out_sens[:n_keep, i] for i, nm in
                                            enumerate(model.sensor_names)},
               **split_outputs(model, out_wh[:n_keep], out_el[:n_keep]),
               state_time=out_t[:n_keep][::se][:ks], states=out_y[:ks], y_end=y, exchange=X.ring,
               status=st,
               message=msg, wall_s=wall,
               stats={"steps": int(stats[0]), "newton": int(stats[1]), "jacobians": int(stats[2]),
                      "rhs": int(stats[3]), "halved": int(stats[4]), "dt": h, "method": s.method,
                      "thread_switches": fitter.switches})
