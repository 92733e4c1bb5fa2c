"""What the line costs (issue 69, item 8): the same car run on tangent track (no layout: the
bodies described from the inertial frame) and on the 300 m curve (every body on its track
frame, every wheel on its rails in its contact's frame), side by side in one process, best of
``--repeat``; the figure is the wall time of the run alone (statics and compilation left out).

    python3 benchmarks/curve_cost.py [--bearings] [--duration S] [--repeat N] [--start M]
    python3 benchmarks/curve_cost.py --stages


Default: rigid bodies on row bushings, smooth track, leapfrog at 2e-5 s (what the curving tests
run); ``--bearings``: the validation case's eight DTRBs as shipped.  ``--start``: where the car
starts on the line (m; the transition runs from 20 to 65 m, the circular curve on from there),
so that 15 m times the run through the transition and 100 m the circular curve alone.

``--stages``: where the difference goes, on the car on row bushings 0.5 s into each run (the
curve's leading outer wheels on their flanges): one evaluation of the bodies' frames, of the
wheels' contact, of the bodies' dynamics (the wheels within) and of the whole right-hand side,
in us (best of 5 loops of 20000), on tangent track, on a line that is straight (the line's
machinery alone: every frame looked up, every vector turned) and in the 300 m curve.
"""
from __future__ import annotations

import argparse
import time

import numpy as np
from numba import njit

from axlebox.mbs.kernel import system as ks
from axlebox.mbs.kernel.wheels import wheel_forces
from axlebox.pipelines import simulate as ps

LAYOUT = [{"kind": "tangent", "length": 20.0}, {"kind": "transition", "length": 45.0},
          {"kind": "curve", "length": 250.0, "radius": 300.0, "hand": "left",
           "superelevation": 0.015}]
BUSHINGS = {"joint": {"model": "bushing"}, "coupling": {"exchange_dt": 0.0}, "defects": [],
            "bodies": {"flexible": []}, "sensors": {"model": "ideal"},
            "integrator": {"method": "leapfrog", "dt": 2e-5, "output_rate_hz": 1000.0}}


STRAIGHT = [{"kind": "tangent", "length": 400.0}]


def _model(layout, bearings: bool, duration: float, start: float):
    over = {} if bearings else dict(BUSHINGS)
    track = {"irregularity": False}
    if layout:
        track.update(layout=layout, start=start)
    over["track"] = track
    cfg = ps.load_config("validation_48kmh", duration, over)
    model, y0 = ps.build_model(cfg, log=lambda *_: None)
    return cfg, model, y0


@njit
def _frames(n, t, y, dy, S, W, B):
    for _ in range(n):
        ks.frames(t, y, dy, S, W)


@njit
def _wheels(n, t, y, dy, S, W, B):
    for _ in range(n):
        wheel_forces(t, y, S.bi, S.wh_i, S.wh_f, S.wtab, S.wpar, S.trk, S.wrk, S.glob, W.Ab, W.omb,
                     W.omfb, W.mkp, W.mkv, W.mkR, W.mkw, W.mkF, W.mkM, W.whout, S.line, W.frm, W.fr)


@njit
def _dynamics(n, t, y, dy, S, W, B):
    for _ in range(n):
        ks.dynamics(t, y, dy, S, W)


@njit
def _rhs(n, t, y, dy, S, W, B):
    for _ in range(n):
        ks.rhs(t, y, dy, S, W, B)


def stages(n: int = 20000, repeat: int = 5) -> None:
    """The ``--stages`` table (module docstring)."""
    t = 0.5
    print(f"{'us an evaluation':16s} {'frames':>8s} {'wheels':>8s} {'dynamics':>9s} {'rhs':>8s}")
    for name, layout in (("tangent", None), ("straight line", STRAIGHT), ("300 m curve", LAYOUT)):
        cfg, model, y0 = _model(layout, False, t, 100.0)
        run = ps.integrate.simulate(model, t, cfg.settings(), y0=y0)
        assert run.ok, run.message
        y = np.asarray(run.y_end, float)
        args = (t, y, np.zeros_like(y), model.S, model.W, model.B)
        row = []
        for f in (_frames, _wheels, _dynamics, _rhs):
            f(10, *args)
            best = float("inf")
            for _ in range(repeat):
                t0 = time.perf_counter()
                f(n, *args)
                best = min(best, time.perf_counter() - t0)
            row.append(best / n * 1e6)
        print(f"{name:16s} " + " ".join(f"{v:8.2f}" for v in row), flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bearings", action="store_true")
    ap.add_argument("--duration", type=float, default=2.0)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--start", type=float, default=15.0)
    ap.add_argument("--stages", action="store_true")
    a = ap.parse_args()
    if a.stages:
        return stages()
    runs = {name: _model(layout, a.bearings, a.duration, a.start)
            for name, layout in (("tangent", None), ("curve", LAYOUT))}
    best = {name: float("inf") for name in runs}
    for cfg, model, y0 in runs.values():                 # compile both before timing
        ps.integrate.simulate(model, 0.01, cfg.settings(), y0=y0)
    for _ in range(a.repeat):
        for name, (cfg, model, y0) in runs.items():
            t0 = time.perf_counter()
            r = ps.integrate.simulate(model, a.duration, cfg.settings(), y0=y0)
            best[name] = min(best[name], time.perf_counter() - t0)
            assert r.ok, r.message
    for name, w in best.items():
        print(f"{name:8s} {w:7.2f} s wall for {a.duration:g} s simulated "
              f"({a.duration / w:.3f} simulated s per wall s)")
    print(f"curve / tangent: {best['curve'] / best['tangent']:.3f}")


if __name__ == "__main__":
    main()
