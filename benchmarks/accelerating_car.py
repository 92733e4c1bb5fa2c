"""Benchmark (issue 51): the accelerating car's cost, wall s per simulated s, beside the same car at
a constant speed, each run in one process (best of ``--repeat``; the machine is shared).

The runs: configs/accelerating_20_60kmh.toml (the validation case's car from 20 km/h at 1 m/s^2,
traction torques at its wheelsets, eight DTRBs, the paper's defect) and the same config with its
profile removed (constant 20 km/h), ``--duration`` s each, the model built (and numba warmed)
before the clock starts.  Run: ``python benchmarks/accelerating_car.py --duration 1``.
"""
from __future__ import annotations

import argparse
import os
import platform
import time

from axlebox.mbs.solver import integrate
from axlebox.pipelines import simulate as psim


def wall(cfg, repeat: int) -> tuple[float, float]:
    model, y0 = psim.build_model(cfg, log=lambda *_: None)
    integrate.simulate(model, 0.01, cfg.settings(), y0=y0)          # numba warmed
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        run = integrate.simulate(model, cfg.run.duration, cfg.settings(), y0=y0)
        best = min(best, time.perf_counter() - t0)
        assert run.ok, run.message
    return best, cfg.run.duration


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--duration", type=float, default=1.0)
    ap.add_argument("--repeat", type=int, default=1)
    a = ap.parse_args()
    acc = psim.load_config("accelerating_20_60kmh", duration=a.duration)
    const = acc.replace(run={"profile": ()})
    print(f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores; {a.duration:g} s "
          "simulated each (imex, dt 5e-6 s, exchange 1e-5 s, 8 DTRBs)")
    print("| run | wall s | simulated s | wall s per simulated s |")
    print("| --- | --- | --- | --- |")
    for name, cfg in (("accelerating 20 km/h + 1 m/s^2", acc), ("constant 20 km/h", const)):
        w, T = wall(cfg, a.repeat)
        print(f"| {name} | {w:.1f} | {T:g} | {w / T:.1f} |")


if __name__ == "__main__":
    main()
