"""What the line costs (issue 69, item 8): the same car run on tangent track (no layout: the
bodies described from the inertial frame) and on the 300 m curve (every body on its track
frame, every wheel on its rails in its contact's frame), side by side in one process, best of
``--repeat``; the figure is the wall time of the run alone (statics and compilation left out).

    python3 benchmarks/curve_cost.py [--bearings] [--duration S] [--repeat N]

Default: rigid bodies on row bushings, smooth track, leapfrog at 2e-5 s (what the curving tests
run); ``--bearings``: the validation case's eight DTRBs as shipped.
"""
from __future__ import annotations

import argparse
import time

from axlebox.pipelines import simulate as ps

LAYOUT = [{"kind": "tangent", "length": 20.0}, {"kind": "transition", "length": 45.0},
          {"kind": "curve", "length": 250.0, "radius": 300.0, "hand": "left",
           "superelevation": 0.015}]
BUSHINGS = {"joint": {"model": "bushing"}, "coupling": {"exchange_dt": 0.0}, "defects": [],
            "bodies": {"flexible": []}, "sensors": {"model": "ideal"},
            "integrator": {"method": "leapfrog", "dt": 2e-5, "output_rate_hz": 1000.0}}


def _model(on_line: bool, bearings: bool, duration: float):
    over = {} if bearings else dict(BUSHINGS)
    track = {"irregularity": False}
    if on_line:
        track.update(layout=LAYOUT, start=15.0)
    over["track"] = track
    cfg = ps.load_config("validation_48kmh", duration, over)
    model, y0 = ps.build_model(cfg, log=lambda *_: None)
    return cfg, model, y0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bearings", action="store_true")
    ap.add_argument("--duration", type=float, default=2.0)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    runs = {name: _model(on, a.bearings, a.duration) for name, on in (("tangent", False),
                                                                        ("curve", True))}
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
