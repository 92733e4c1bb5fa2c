"""The standalone bearing rig: one DTRB, inner ring spinning at the speed of a 0.42 m wheel and
held in place, outer ring = axle-box mass on a spring-damper to ground, constant radial and axial
load; started from the quasi-static equilibrium; fixed-step RK4 or the leapfrog
(:mod:`axlebox.bearing.integrate`).

Python API::

    from axlebox.bearing.rig import RigConfig, simulate
    res = simulate(RigConfig(speed_kmh=48, defects=(Defect(W=2e-3),)), out="rig.h5")
    res.plot("rig.png")

The outer-ring acceleration is computed at every step and brought to the output rate (10 kHz,
like the on-board system) by a polyphase anti-aliasing resampler (scipy.signal.resample_poly);
contact forces, ring loads and cage motion are sampled at the output rate.  Long runs write a
checkpoint ``<out>.partial.h5`` as they go and resume from it when run again with the same
configuration.
"""
from __future__ import annotations

import dataclasses
import time as _time
from dataclasses import dataclass, field
from pathlib import Path

import h5py
import numpy as np
import tomli_w
from scipy.signal import resample_poly

from axlebox._params import ParameterError, check_ranges, from_table, param, require

from . import defects as _defects
from .kernel import dispatch
from . import models, resultfile
from .statics.equilibrium import static_state
from .kernel.evaluate import work
from .frequencies import shaft_hz
from .kernel.implicit import scratch
from .integrate import (R_CX, R_FX, R_KX, R_MASS, R_N, R_OMEGA, R_UX, RIG, RIG_U,
                        run_leapfrog, run_rk4)
from .kernel.layout import CAGE_ANGLE, CAGE_OUT, F_X, F_Z, LOAD, N_Q, OUTER, Q_A, Q_NAMES, Q_O, RINGS
from .models.params import BearingParams
from .kernel.quasidynamic import QD_WIDTH
from .kernel.step import MODES
from .kernel.vec import AZ

SENSOR = "outer_ring"
RIG_METHODS = ("rk4", "leapfrog", "imex", "imex2")


@dataclass(frozen=True)
class RigConfig:
    """Rig settings (SI).  Loads act on the outer ring: ``F_r`` downwards (-z), ``F_a`` along +y.

    Defaults: the radial load is the motor car's carbody (37.4 t, rated load) and frame (3.42 t)
    on four axle boxes of a bogie, ``(37.4/2 + 3.42) t g / 4 = 54 kN``; spring rates are the
    motor car's primary suspension per axle box (masses and springs: Hangzhou Metro Line 1 B-type
    car, Math. Probl. Eng. 2020, article 1584624, Table 6); the axle-box mass and the dampers are
    assumed.
    """

    speed_kmh: float = param(48.0, 0.0, 200.0, unit="km/h", doc="vehicle speed")
    r_wheel: float = param(0.42, 0.2, 0.7, doc="wheel rolling radius")
    F_r: float = param(54e3, 0.0, 1e6, unit="N", doc="radial load on the outer ring, downwards")
    F_a: float = param(0.0, -1e6, 1e6, unit="N", doc="axial load on the outer ring, along +y")
    m_box: float = param(60.0, 1.0, 1e4, unit="kg", doc="axle-box (outer ring) mass")
    k_x: float = param(10.6e6, 0.0, 1e10, unit="N/m", doc="spring to ground, longitudinal")
    k_y: float = param(7.8e6, 0.0, 1e10, unit="N/m", doc="spring to ground, lateral")
    k_z: float = param(1.7e6, 0.0, 1e10, unit="N/m", doc="spring to ground, vertical")
    c_x: float = param(1e4, 0.0, 1e8, unit="N s/m", doc="damper to ground, longitudinal")
    c_y: float = param(1e4, 0.0, 1e8, unit="N s/m", doc="damper to ground, lateral")
    c_z: float = param(1e4, 0.0, 1e8, unit="N s/m", doc="damper to ground, vertical")
    duration: float = param(1.0, 1e-3, 3600.0, unit="s", doc="simulated time")
    dt: float = param(1e-5, 1e-8, 1e-4, unit="s", doc="integration step")
    method: str = field(default="rk4", metadata={"doc": "'rk4'; 'leapfrog', one evaluation a step "
                                                    "(5x faster at 1e-5 s, about 1 % off RK4 in the "
                                                    "outer ring's RMS, unstable from 1.25e-5 s); "
                                                    "'imex' or 'imex2' (bearing/integrate.py, "
                                                    "benchmarks/README.md); each bearing model "
                                                    "says which it accepts and up to which dt"})
    fs_out: float = param(10e3, 100.0, 1e6, unit="Hz", doc="output rate")
    seed: int = 0
    bearing: object = field(default_factory=BearingParams,
                            metadata={"doc": "the bearing: any model's parameters (bearing/models/)"})
    defects: tuple = ()

    def __post_init__(self):
        if isinstance(self.seed, bool) or not isinstance(self.seed, int) or self.seed < 0:
            raise ParameterError(f"RigConfig.seed = {self.seed!r} is not allowed: expected an integer >= 0")
        if self.method not in RIG_METHODS:
            raise ParameterError(f"RigConfig.method = {self.method!r} is not allowed: expected one of "
                                 f"{', '.join(RIG_METHODS)}")
        check_ranges(self)
        require(self.speed_kmh > 0, self, "speed_kmh", "expected a speed > 0 km/h")
        require(self.F_r > 0 or self.F_a != 0, self, "F_r", "the bearing needs a load (F_r > 0 or F_a != 0)")
        every = self.fs_out_every
        require(every >= 1 and abs(every * self.dt * self.fs_out - 1) < 1e-9, self, "dt",
                f"the output period 1/fs_out = {1 / self.fs_out:g} s must be a whole number of steps")
        require(self.duration * self.fs_out >= 1, self, "duration", "shorter than one output sample")
        models.check_step(self.bearing, self.method, self.dt, "RigConfig.method", "RigConfig.dt")
        for d in self.defects:
            if not isinstance(d, _defects.Defect):
                raise ParameterError(f"RigConfig.defects: {d!r} is not allowed: expected Defect objects")
        _defects.table(self.defects, self.bearing)          # refuses what Eq. (14) cannot model

    @property
    def fs_out_every(self) -> int:
        return int(round(1.0 / (self.fs_out * self.dt)))

    @property
    def omega_w(self) -> float:
        return 2 * np.pi * shaft_hz(self.speed_kmh, self.r_wheel)

    def to_toml(self) -> str:
        rig = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)
               if f.name not in ("bearing", "defects")}
        out = {"rig": rig, "bearing": models.to_table(self.bearing)}
        defects = [dataclasses.asdict(x) for x in self.defects]
        if defects:
            out["defects"] = defects
        return tomli_w.dumps(out)


@dataclass
class RigResult:
    """Outputs at ``fs`` Hz: outer-ring acceleration (t, 3), ring loads (t, 2, 6) on inner/outer,
    contact forces Q (t, rows, Z, 6: cup, cone, rib, pocket walls, side beams), cage angle and
    speed (t, rows, 2)."""

    config: RigConfig
    time: np.ndarray
    acceleration: np.ndarray
    ring_loads: np.ndarray
    Q: np.ndarray
    cage: np.ndarray

    @property
    def fs(self) -> float:
        return self.config.fs_out

    def cage_hz(self, t_from: float = 0.0) -> float:
        """Mean cage rotation frequency from ``t_from`` on (every row's; slope of the angle)."""
        m = self.time >= t_from
        slope = [np.polyfit(self.time[m], self.cage[m, j, CAGE_ANGLE], 1)
                 for j in range(self.cage.shape[1])]
        return float(np.mean([b for b, _ in slope]) / (2 * np.pi))

    def save(self, path) -> Path:
        groups = {"bearing": {"Q": (self.Q.astype(np.float32), {"columns": Q_NAMES, "unit": "N"}),
                              "ring_loads": (self.ring_loads, {"rows": ["inner", "outer"],
                                                               "columns": "Fx Fy Fz Mx My Mz",
                                                               "unit": "N, N m"}),
                              "cage": (self.cage, {"columns": "angle (rad), speed (rad/s)"})}}
        return resultfile.write(path, config_toml=self.config.to_toml(), seed=self.config.seed,
                                time=self.time, fs_hz=self.fs,
                                signals={SENSOR: {"acceleration": self.acceleration,
                                                  "force": self.ring_loads[:, OUTER, F_X:F_Z + 1]}},
                                groups=groups)

    def plot(self, path=None, t_from: float = 0.05):
        """Acceleration, its envelope spectrum with the fault orders marked, and one roller's
        cup load; saved to ``path`` when given.  Returns the matplotlib figure."""
        from axlebox._figures import subplots

        from .spectra import envelope_spectrum
        m = self.time >= min(t_from, 0.5 * self.time[-1])
        t, a = self.time[m], self.acceleration[m, AZ]
        f_s = shaft_hz(self.config.speed_kmh, self.config.r_wheel)
        o = models.orders(self.config.bearing).at(f_s)
        fig, (top, mid, bottom) = subplots(3, 1, figsize=(9, 9), constrained_layout=True)
        top.plot(t, a, lw=0.5)
        top.set(xlabel="time (s)", ylabel="outer ring a_z (m/s²)", title=f"{self.config.speed_kmh:g} km/h, "
                  f"{len(self.config.defects)} defect(s)")
        f, A = envelope_spectrum(a, self.fs, band=(1000.0, 4000.0))
        keep = f < 8 * o["BPFO"]
        mid.plot(f[keep], A[keep], lw=0.8)
        for h in range(1, 8):
            mid.axvline(h * o["BPFO"], color="r", lw=0.5, ls="--")
        mid.set(xlabel="frequency (Hz)", ylabel="envelope amplitude (m/s²)",
                  title=f"envelope spectrum, BPFO = {o['BPFO']:.2f} Hz (dashed)")
        first = 0                                      # roller 1 of row 2
        bottom.plot(self.time, self.Q[:, OUTER, first, Q_O], lw=0.6, label="roller 1, row 2, outer raceway")
        bottom.plot(self.time, self.Q[:, OUTER, first, Q_A], lw=0.6, label="rib")
        bottom.set(xlabel="time (s)", ylabel="contact force (N)")
        bottom.legend()
        if path is not None:
            fig.savefig(path, dpi=110)
        return fig


RIG_SECTIONS = ("rig", "bearing", "defects")


def config_from_dict(d: dict) -> RigConfig:
    """A :class:`RigConfig` from a parsed rig TOML (the layout :meth:`RigConfig.to_toml`
    writes); unknown sections and fields are named."""

    for sec in d:
        if sec not in RIG_SECTIONS:
            raise ParameterError(f"[{sec}] is not a section of a rig config: expected one of "
                                 f"{', '.join(RIG_SECTIONS)}")
    defects = d.get("defects", [])
    if not isinstance(defects, list):
        raise ParameterError(f"defects = {defects!r} is not allowed: expected [[defects]] tables")
    return from_table(RigConfig, d.get("rig", {}), "rig",
                      bearing=models.from_table(d.get("bearing", {}), "bearing"),
                      defects=tuple(from_table(_defects.Defect, e, "defects") for e in defects))


def load(path) -> RigResult:
    """Read a rig result written by :meth:`RigResult.save` (the configuration is kept as TOML
    text in the file; the returned ``config`` is rebuilt from it)."""
    import tomllib
    with resultfile.reading(path) as f:
        config = config_from_dict(tomllib.loads(f.attrs["config"]))
        return RigResult(config=config, time=f["time"][:],
                         acceleration=f[f"signals/{SENSOR}/acceleration"][:],
                         ring_loads=f["bearing/ring_loads"][:], Q=f["bearing/Q"][:].astype(float),
                         cage=f["bearing/cage"][:])


def _rig_vector(c: RigConfig, u_eq) -> np.ndarray:
    r = np.zeros(R_N)
    r[R_MASS] = c.m_box
    r[R_KX:R_KX + 3] = c.k_x, c.k_y, c.k_z
    r[R_CX:R_CX + 3] = c.c_x, c.c_y, c.c_z
    r[R_FX:R_FX + 3] = 0.0, c.F_a, -c.F_r
    r[R_OMEGA] = c.omega_w
    r[R_UX:R_UX + 3] = u_eq
    return r


def initial_state(c: RigConfig):
    """``(Y0, P, D, rig)``: the quasi-static start, the kernel's parameter vector, defect table
    and rig vector.  The seed turns the roller set by a random fraction of the roller pitch,
    moved on until no roller sits in a defect; the equilibrium is the healthy bearing's there
    (a roller inside a defect has none)."""
    p = c.bearing
    P, D = models.pack(p), _defects.table(c.defects, p)
    shift = np.random.default_rng(c.seed).uniform(0, 2 * np.pi / p.Z) if c.seed else 0.0
    y, uo = static_state(p, P, np.zeros((0, _defects.WIDTH)), (0.0, c.F_a, -c.F_r), c.omega_w,
                         phase=_defects.phase_clear_of(D, p.Z, shift))
    Y = np.concatenate([y, np.zeros(RIG)])
    Y[y.size + RIG_U:y.size + RIG_U + 3] = uo
    return Y, P, D, _rig_vector(c, uo)


def stepper(c: RigConfig, P, D, rig):
    """``step(Y, t0, n_steps, outs, start) -> ok``: the rig's integrator for ``c`` (its method,
    its bearing's tag and scratch), advancing ``Y`` in place and writing ``outs`` (acceleration,
    ring loads, contact forces, cages: :func:`axlebox.bearing.integrate.run_rk4`)."""
    p = c.bearing
    tag = dispatch.tag(p)
    n = models.n_state(p)
    w = work(p.Z, n, QD_WIDTH)
    every = c.fs_out_every
    if c.method == "rk4":
        return lambda Y, t0, n_steps, outs, start: run_rk4(tag, Y, t0, c.dt, n_steps, every, P, D, rig,
                                                          w, *outs)
    K = scratch(p.Z, p.rows)
    mode = MODES[c.method]
    return lambda Y, t0, n_steps, outs, start: run_leapfrog(tag, Y, t0, c.dt, n_steps, every, P, D,
                                                           rig, w, K, *outs, mode, start)


def simulate(c: RigConfig, out=None, progress=None, chunk_s: float = 0.05,
             checkpoint_every_s: float = 30.0) -> RigResult:
    """Run the rig; write ``out`` (HDF5) when given, resuming from ``<out>.partial.h5``."""
    p = c.bearing
    every = c.fs_out_every
    n_out = int(round(c.duration * c.fs_out))
    n_steps = n_out * every
    partial = Path(str(out) + ".partial.h5") if out is not None else None
    toml = c.to_toml()
    Y, P, D, rig = initial_state(c)
    step = stepper(c, P, D, rig)
    acc = np.zeros((n_steps, 3))
    Fout = np.zeros((n_out, RINGS, LOAD))
    Qout = np.zeros((n_out, p.rows, p.Z, N_Q))
    cage = np.zeros((n_out, p.rows, CAGE_OUT))
    done = 0
    if partial is not None and partial.is_file():
        with h5py.File(partial, "r") as f:
            if f.attrs.get("config") == toml:
                done = int(f.attrs["done"])
                Y[:] = f["Y"][:]
                acc[:done * every] = f["acc"][:]
                for name, arr in (("F", Fout), ("Q", Qout), ("cage", cage)):
                    arr[:done] = f[name][:]
    chunk = max(1, int(round(chunk_s * c.fs_out)))
    last = _time.monotonic()
    while done < n_out:
        m = min(chunk, n_out - done)
        outs = (acc[done * every:(done + m) * every], Fout[done:done + m], Qout[done:done + m],
                cage[done:done + m])
        # a checkpoint's Y holds the leapfrog's half-step velocities: no half kick then
        ok = step(Y, done / c.fs_out, m * every, outs, done == 0)
        if not ok:
            t_end = (done + m) / c.fs_out
            raise FloatingPointError(f"the rig state stopped being finite near t = {t_end:.4f} s: "
                                     f"dt = {c.dt:g} s is too large for these contacts")
        done += m
        if progress is not None:
            progress(done / n_out)
        if partial is not None and (_time.monotonic() - last > checkpoint_every_s) and done < n_out:
            _checkpoint(partial, toml, done, Y, acc[:done * every], Fout[:done], Qout[:done], cage[:done])
            last = _time.monotonic()
    a_out = resample_poly(acc, 1, every, axis=0)[:n_out] if every > 1 else acc
    res = RigResult(config=c, time=np.arange(n_out) / c.fs_out, acceleration=a_out, ring_loads=Fout,
                    Q=Qout, cage=cage)
    if out is not None:
        res.save(out)
        if partial.is_file():
            partial.unlink()
    return res


def _checkpoint(path: Path, toml, done, Y, acc, F, Q, cage):
    resultfile.write_checkpoint(path, {"config": toml, "done": done},
                                {"Y": Y, "acc": acc, "F": F, "Q": Q, "cage": cage})
