"""Ride comfort's cost: Sperling's W_z/W_y and EN 12299's N_MV of one floor sensor
(:func:`axlebox.mbs.post.comfort.ride_comfort`) on a 5 min record, at the comfort config's 1 kHz and the
validation config's 10 kHz; best of ``--repeat`` wall times and the peak memory it allocates
(tracemalloc).  The record: three axes of random floor motion (its content does not change the
cost: FFTs of fixed length).  Run: ``python3 benchmarks/comfort.py [--repeat N]``.
"""
from __future__ import annotations

import argparse
import time
import tracemalloc

import numpy as np

from axlebox.mbs.post.comfort import ride_comfort


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--seconds", type=float, default=300.5)
    a = ap.parse_args()
    rng = np.random.default_rng(0)
    print(f"{'fs Hz':>7} {'samples':>9} {'best s':>8} {'peak MB':>8}  W_z, W_y, N_MV")
    for fs in (1000.0, 10000.0):
        acc = rng.standard_normal((int(a.seconds * fs), 3)) * 0.05
        best = np.inf
        for _ in range(a.repeat):
            t0 = time.perf_counter()
            rc = ride_comfort(acc, fs, "floor", skip_s=0.5)
            best = min(best, time.perf_counter() - t0)
        tracemalloc.start()
        ride_comfort(acc, fs, "floor", skip_s=0.5)
        peak = tracemalloc.get_traced_memory()[1] / 2 ** 20
        tracemalloc.stop()
        print(f"{fs:7.0f} {acc.shape[0]:9d} {best:8.3f} {peak:8.0f}  "
              f"{rc.W_z:.2f}, {rc.W_y:.2f}, {rc.N_MV:.2f}")


if __name__ == "__main__":
    main()
