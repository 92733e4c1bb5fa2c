"""The wheel-flat impact in the car: the peak normal force of a flat wheel at 20-80 km/h, on rigid
rails and on the ballasted track (mbs/track/bed.py), against its static load.

    python3 benchmarks/wheel_flat_impact.py [--lengths 0.04 0.05] [--speeds 20 40 60 80]
        [--shape rounded] [--json OUT]

The shipped car with its row bushings (no DTRBs: the impact is the wheel-rail contact's), smooth
track, the flat on wheelset 2's right wheel; each run lasts three wheel turns after a 20 ms
fade-in, the peak is taken over the last two.  Prints a table (kN) and the wall time.
"""
from __future__ import annotations

import argparse
import json
import math
import time


def run(length: float, speed: float, track: str, shape: str) -> dict:

    from axlebox import configs
    from axlebox.mbs.vehicle import config as vconfig
    from axlebox.mbs.solver import integrate
    from axlebox.mbs.kernel.wheels import G_RAMP
    from axlebox.mbs.wheelrail import element_kernel as ek
    from axlebox.pipelines import simulate as psim
    cfg = vconfig.load(configs.path("vehicle")).replace(
        run={"speed_kmh": speed}, track={"irregularity": False, "model": track},
        wheel_defects=[{"wheelset": 2, "side": "R", "kind": "flat", "length": length, "shape": shape}])
    model, y0 = psim.build_model(cfg, log=lambda *_: None)
    model.S.glob[G_RAMP] = 0.02
    turn = 2 * math.pi * cfg.wheelset.r0 / (speed / 3.6)
    t0 = time.perf_counter()
    r = integrate.simulate(model, 0.02 + 3 * turn, cfg.settings(), y0=y0)
    wall = time.perf_counter() - t0
    w = model.wheel_names.index("ws2_R")
    N = r.wheels[:, w, ek.OUT_N]
    late = r.time > 0.02 + turn
    return {"length_m": length, "speed_kmh": speed, "track": track, "shape": shape, "ok": r.ok,
            "static_kN": float(N[0]) / 1e3, "peak_kN": float(N[late].max()) / 1e3,
            "lost_contact": bool(N[late].min() == 0.0), "wall_s": wall}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lengths", type=float, nargs="+", default=[0.04, 0.05])
    ap.add_argument("--speeds", type=float, nargs="+", default=[20.0, 40.0, 60.0, 80.0])
    ap.add_argument("--shape", default="rounded")
    ap.add_argument("--json")
    a = ap.parse_args(argv)
    rows = []
    print("| flat mm | km/h | track | static kN | peak kN | peak / static | contact lost | wall s |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for L in a.lengths:
        for v in a.speeds:
            for track in ("rigid", "ballasted"):
                r = run(L, v, track, a.shape)
                rows.append(r)
                print(f"| {1e3 * L:g} | {v:g} | {track} | {r['static_kN']:.1f} | {r['peak_kN']:.0f} | "
                      f"{r['peak_kN'] / r['static_kN']:.2f} | {'yes' if r['lost_contact'] else 'no'} | "
                      f"{r['wall_s']:.1f} |", flush=True)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
