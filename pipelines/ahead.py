"""Compiling ahead: a run's numba kernels compiled in a second process while this one does
what it must do first (mesh and reduce the bodies, find the statics), so that a first run on a
fresh machine uses two cores where numba uses one (it compiles in one thread per process).

The second process saves what it compiles to numba's cache (axlebox/_numba.py), where this one
finds it.  A kernel is compiled for its arguments' types only, and those do not depend on the
bodies' sizes nor on which bodies are flexible (tests/test_ahead.py), so the second process
builds the car its own quick way: the bodies read where they are built already, rigid where
they are still being built, no statics, every bearing at one nominal load.

Its work comes in phases, each announced once done (:data:`PHASES`): ``statics`` the car's
right-hand side without bearings (what the statics evaluates; only when this process is busy
with the bodies, otherwise this process compiles it itself), ``bearings`` one bearing's
evaluation (the bearings' statics) and the bearings' exchange of the run, ``run`` the run's
kernel (after this process says the statics' kernels are in the cache, :meth:`Ahead.go`, so that
nothing is compiled twice).  Before each step that needs a phase this process waits for it; a
second process that failed or ran out of time costs that wait alone, after which this one
compiles what is missing itself.  The numbers are the same either way: a kernel loaded from
the cache is the one compiled here (tests/test_jitcache.py).
"""
from __future__ import annotations

import dataclasses
import multiprocessing
import os
import time
from pathlib import Path

PHASES = ("statics", "bearings", "run")
WAIT_S = 900.0              # at most this long for one phase (a cold compile takes about two minutes)
ENV = "AXLEBOX_COMPILE_AHEAD"   # "0": never (a run compiles all it needs itself)


def wanted() -> bool:
    """Whether a run should compile ahead: more than one core, not switched off (``$AXLEBOX_COMPILE_AHEAD
    = 0``), and the run's kernel not yet in numba's cache (any signature of it: a warm cache
    has nothing to gain), the cache being the one axlebox chose (axlebox/_numba.py)."""
    chosen = os.environ.get(ENV, "1")
    if chosen not in ("0", "1"):
        from axlebox._params import ParameterError
        raise ParameterError(f"{ENV} = {chosen!r} is not allowed: expected 1 (compile ahead where "
                             "numba's cache lacks the run's kernels; the default) or 0 (never)")
    if chosen == "0" or (os.cpu_count() or 1) < 2:
        return False
    from axlebox._numba import OURS
    where = os.environ.get(OURS)
    if not where:       # the user's cache folder (or numba's own places): no telling warm from cold
        return False
    folder = Path(where) / "axlebox.mbs.kernel.integrate"
    return not (folder.is_dir() and any(".run_leapfrog-" in p.name for p in folder.iterdir()))


class Ahead:
    """The second process, its phases' events and who compiles the statics' kernels (the
    first of the two to reach them: this process where the bodies are ready, else the second,
    while this one builds them)."""

    def __init__(self, cfg):
        ctx = multiprocessing.get_context("spawn")   # no fork of a process with threads
        self.events = {p: ctx.Event() for p in PHASES + ("go",)}
        self.owner = ctx.Value("i", 0)               # the statics' kernels: 0 nobody yet, 1 this, 2 it
        self.process = ctx.Process(target=_work, args=(cfg, self.events, self.owner), daemon=True,
                                   name="axlebox-compile-ahead")
        self.process.start()

    def take(self, phase: str) -> bool:
        """Whether this process compiles ``phase`` itself (only the statics' can be taken)."""
        return phase == "statics" and _take(self.owner, 1)

    def wait(self, phase: str) -> bool:
        """Until ``phase`` is done, the second process has stopped, or :data:`WAIT_S`; whether
        it was done."""
        ev = self.events[phase]
        end = time.monotonic() + WAIT_S
        while not ev.wait(0.2):
            if not self.process.is_alive() or time.monotonic() > end:
                return ev.is_set()
        return True

    def go(self) -> None:
        """The statics' kernels are in the cache: the second process may compile the run's."""
        self.events["go"].set()

    def close(self) -> None:
        self.go()
        if self.process.is_alive():
            self.process.terminate()
        self.process.join(5.0)


class NoAhead:
    """A run that compiles everything itself: it takes every phase, waits for none, and has no
    second process to tell or to stop (:class:`Ahead`'s interface, for callers that need not ask
    which they hold)."""

    def take(self, phase: str) -> bool:
        return True

    def wait(self, phase: str) -> bool:
        return False

    def go(self) -> None:
        """Nobody to tell."""

    def close(self) -> None:
        """Nothing to stop."""


def start(cfg):
    """:class:`Ahead` where :func:`wanted`, else :class:`NoAhead`."""
    return Ahead(cfg) if wanted() else NoAhead()


def _take(owner, me: int) -> bool:
    with owner.get_lock():
        if owner.value == 0:
            owner.value = me
        return owner.value == me


def stand_in(cfg, red: dict | None = None):
    """The car of ``cfg`` as the second process builds it, for its kernels' types: its bodies
    ``red`` (reduced, :func:`.simulate.reduced_bodies`; none: every body rigid), no statics, every
    bearing at one nominal load (:func:`_nominal`)."""
    from axlebox.mbs.vehicle import bearings as car_bearings

    from . import simulate
    if not red:
        cfg = cfg.replace(bodies=dict(dataclasses.asdict(cfg.bodies), flexible=[], dir="", wheelset="",
                                      axlebox="", frame=""))
        red = {}
    tabs, trk = simulate.tables(cfg), simulate.track_record(cfg)
    model = simulate._car(cfg, tabs, trk, red)
    if not cfg.has_bearings:
        return model
    keys = [(k, side) for k in cfg.joint.wheelsets for side in ("L", "R")]
    p = car_bearings.params(cfg)
    one = car_bearings.start(cfg, {keys[0]: _nominal(model)}, 50.0, log=lambda *_: None)[keys[0]]
    return simulate._car(cfg, tabs, trk, red, bearings={
        k: (one.tag, one.P, car_bearings.defect_table(cfg, *k, p), one.y0) for k in keys})


def compile_statics(model) -> None:
    """The statics' kernels for ``model``'s types (what :meth:`Model.rhs` calls without
    bearings), compiled or loaded from the cache now, so that whoever compiles them can tell the
    second process to go on before the statics' solve (4 s of Newton on the car) rather than
    after it."""
    import numba
    import numpy as np

    from axlebox.mbs.kernel import system as ks
    y = np.array(model.y0, float)
    for fn in (ks.kinematics, ks.dynamics):
        fn.compile(tuple(numba.typeof(a) for a in (0.0, y, y, model.S, model.W)))


def _work(cfg, events, owner) -> None:
    """The second process (module docstring): the bearings' kernels, the statics' where this
    process gets there first, the run's once the statics' are in the cache."""
    import numba
    import numpy as np

    from axlebox.mbs.kernel import bearings as kb
    from axlebox.mbs.solver import integrate
    model = stand_in(cfg)                # bodies rigid: the flexible car's kernel types
    s = cfg.settings()
    S, W, B = model.S, model.W, model.B
    y = np.array(model.y0, float)
    if cfg.has_bearings and s.method in ("leapfrog", "imex", "imex2"):
        X = integrate.exchange_of(model, s)
        for fn, args in ((kb.bearing_exchange, (B, X, 0.0, y, S.bi, W.mkp, W.mkv, W.mkR, W.mkw, W.mkF,
                                                W.mkM, W.elout)),
                         (kb.held_loads, (B, X, y, S.bi, W.mkp, W.mkv, W.mkR, W.mkw, W.mkF, W.mkM, 0.0))):
            fn.compile(tuple(numba.typeof(a) for a in args))
    events["bearings"].set()
    if _take(owner, 2):
        compile_statics(model)
        events["statics"].set()
        events["go"].set()
    events["go"].wait(WAIT_S)
    integrate.compile_run(model, s)
    events["run"].set()


def _nominal(model):
    """The load (N, track frame) the axle-box puts on a bearing's outer ring with the car's
    weight resting evenly on eight: a stand-in for the statics' (no kernel's types depend on
    it)."""
    import numpy as np
    mass = sum(b.mass for b in model.bodies)
    return np.array([0.0, 0.0, -mass * 9.81 / 8.0])
