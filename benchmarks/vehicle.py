"""Vehicle benchmark: wall seconds per simulated second of the metro car at 48 km/h on FRA class 5,
rigid and flexible front bogie, for each integrator (RK4, generalized-alpha, leapfrog), and the
step each needs for 2 % convergence of the axle-box vertical RMS, against RK4 at 1.25e-5 s.

    python3 benchmarks/vehicle.py [--duration 1.0] [--bodies DIR]

Prints a table (wall s per simulated s, RHS us, peak memory) to paste into benchmarks/README.md.
"""
from __future__ import annotations

import argparse
import resource
import sys
import time

import numpy as np

from axlebox import configs
from axlebox.mbs.vehicle import config as vconfig
from axlebox.mbs.solver import integrate
from axlebox.pipelines import simulate as psim



def axlebox_rms(run, skip):
    return np.array([np.sqrt(np.mean(run.sensors[f"ws{i}_{s}"][skip:, 2] ** 2))
                     for i in range(1, 5) for s in "LR"])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--duration", type=float, default=1.0)
    ap.add_argument("--bodies", default="", help="reduced-body folder (default: built into the cache)")
    a = ap.parse_args()
    rows = []
    for label, flex in (("rigid", []), ("flexible front", None)):
        cfg = vconfig.load(configs.path("vehicle"))
        cfg = cfg.replace(bodies={"dir": a.bodies, **({"flexible": flex} if flex is not None else {})})
        model, y0 = psim.build_model(cfg, log=lambda *_: None)
        model.rhs(0.0, y0)                   # the first call loads the kernels: not timed
        rhs_us = float("inf")
        for _ in range(5):                   # best of 5 (the machine is shared)
            t0 = time.perf_counter()
            for _ in range(200):
                model.rhs(0.0, y0)
            rhs_us = min(rhs_us, (time.perf_counter() - t0) / 200 * 1e6)
        skip = int(0.5 * 1e4)
        ref = None                  # RK4 at its finest step: the converged run all rows are held to
        for method, steps in (("rk4", (1.25e-5, 2.5e-5, 5e-5)), ("galpha", (1e-4, 5e-5, 2.5e-5)),
                              ("leapfrog", (1e-4, 5e-5, 2.5e-5))):
            res = {}
            for dt in steps:
                s = integrate.Settings(method=method, dt=dt, output_rate_hz=1e4, state_rate_hz=100)
                integrate.simulate(model, 0.01, s, y0=y0)          # compile outside the timing
                run = integrate.simulate(model, a.duration, s, y0=y0)
                res[dt] = (run, run.wall_s / a.duration)
                print(f"  {label} {method} dt {dt:g}: {run.status}, {run.wall_s:.1f} wall s",
                      file=sys.stderr, flush=True)
            if ref is None and res[steps[0]][0].ok:
                ref = axlebox_rms(res[steps[0]][0], skip)
            for dt in steps:
                run, wps = res[dt]
                err = (np.abs(axlebox_rms(run, skip) / ref - 1).max() * 100
                       if run.ok and ref is not None else float("nan"))
                rows.append((label, model.n_states, method, dt, run.status, wps, rhs_us, err,
                             run.stats.get("newton", 0) / max(run.stats.get("steps", 1), 1)))
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print("| model | states | integrator | dt s | status | wall s per sim s | RHS us | "
          "axle-box RMS vs RK4 1.25e-5 s, max % | Newton it./step |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in rows:
        print(f"| {r[0]} | {r[1]} | {r[2]} | {r[3]:g} | {r[4]} | {r[5]:.1f} | {r[6]:.0f} | "
              f"{r[7]:.2f} | {r[8]:.2f} |")
    print(f"peak memory {peak:.0f} MB; duration {a.duration:g} s (the first 0.5 s, the track fade-in, "
          "is left out of the RMS)")


if __name__ == "__main__":
    main()
