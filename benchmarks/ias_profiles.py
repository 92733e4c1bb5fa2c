"""Benchmark (issue 57, item 2): the shaft's speed read from the record itself
(bearing/diagnostics/ias.py) against known speed profiles, and how often a constant speed is read
as changing.

Profiles (a source and its copy, synthetic.angle_coaxial_pair: the DTRB's BPFO, each hit 1 % of a
period off its place; given the record's mean speed): a ramp 30 -> 45 km/h over 6 s; a constant
40 km/h; a step 40 -> 46 km/h at 6 s of 12 s; two records spliced end to end (30 and 48 km/h);
the ramp with a second impulse train at a constant rate where BPFI sits at the mean speed.
Printed: the status, the family, the speed's error against the true one (95th percentile and
largest, relative; for the step, more than two final frames from it), the CPU time.  Then the
constant-speed records of the coaxial family (synthetic.coaxial_pair: each hit 1 % of a period
off the last, a line that wanders as a slipping bearing's) at 20, 50 and 80 km/h, 4 and 20 s,
``--seeds`` seeds each: how many read "constant", the spread against its threshold.
Run: ``python benchmarks/ias_profiles.py``.
"""
from __future__ import annotations

import argparse
import re
import time

import numpy as np

from axlebox.bearing import models
from axlebox.bearing.diagnostics import ias
from axlebox.bearing.diagnostics.ordertrack import angle_from_speed
from axlebox.bearing.diagnostics.synthetic import (angle_coaxial_pair, coaxial_pair, impulse_train,
                                                   resonance)
from axlebox.bearing.frequencies import shaft_hz
from axlebox.bearing.models.params import BearingParams

FS = 10_000.0
O = models.orders(BearingParams())


def profiles():
    """``(name, duration s, speed Hz at each sample, extra signal or None)``."""
    t6 = np.arange(int(6 * FS)) / FS
    t12 = np.arange(int(12 * FS)) / FS
    ramp = shaft_hz(30.0) + (shaft_hz(45.0) - shaft_hz(30.0)) * t6 / 6.0
    other = resonance(impulse_train(t6.size, FS, O.BPFI * float(ramp.mean()), np.random.default_rng(7)),
                      FS, 600.0, 0.05)
    return [("ramp 30-45 km/h, 6 s", t6, ramp, None),
            ("constant 40 km/h, 6 s", t6, np.full(t6.size, shaft_hz(40.0)), None),
            ("step 40-46 km/h at 6 s, 12 s", t12, np.where(t12 < 6, shaft_hz(40.0), 1.15 * shaft_hz(40.0)),
             None),
            ("spliced 30 and 48 km/h, 6 s", t6, np.where(t6 < 3, shaft_hz(30.0), shaft_hz(48.0)), None),
            ("ramp + constant-rate train at BPFI", t6, ramp, 0.3 * other / other.std())]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=4)
    a = ap.parse_args()
    print("| profile | status | family | error p95 | error max | CPU s | reason |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for name, t, f, extra in profiles():
        angle = angle_from_speed(t, f)
        d, h = angle_coaxial_pair(angle, FS, O.BPFO, np.random.default_rng(0))
        if extra is not None:
            d, h = d + extra, h + extra
        c0 = time.process_time()
        e = ias.estimate(h, d, FS, float(angle[-1] / t[-1]), O)
        cpu = time.process_time() - c0
        p95 = mx = "-"
        if e.angle is not None:
            err = np.gradient(e.angle) * FS / f - 1.0
            if name.startswith("step"):
                err = err[np.abs(t - 6.0) > 2 * ias.LADDER[-1][0] / f]
            p95, mx = f"{np.percentile(np.abs(err), 95):.2e}", f"{np.max(np.abs(err)):.2e}"
        print(f"| {name} | {e.status} | {e.family} | {p95} | {mx} | {cpu:.2f} | {e.reason} |")
    print()
    counts, spreads, limits, cpu = {}, [], [], 0.0
    for kmh in (20.0, 50.0, 80.0):
        f0 = shaft_hz(kmh)
        for T in (4.0, 20.0):
            for seed in range(a.seeds):
                x, y = coaxial_pair(T, FS, O.BPFO * f0, np.random.default_rng(seed), amplitude=0.3)
                c0 = time.process_time()
                e = ias.estimate(y, x, FS, f0, O)
                cpu += time.process_time() - c0
                counts[e.status] = counts.get(e.status, 0) + 1
                if e.status in ("constant", "changing"):
                    spreads.append(e.spread)
                    m = re.search(r"resolved: ([0-9.]+)%", e.reason)
                    if m:
                        limits.append(float(m.group(1)) / 100)
    n = 6 * a.seeds
    print(f"constant-speed coaxial records (20, 50, 80 km/h; 4 and 20 s; {a.seeds} seeds): "
          + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())) + f" of {n}; spread "
          f"{min(spreads):.2%}-{max(spreads):.2%}, thresholds {min(limits):.2%}-{max(limits):.2%}; "
          f"{cpu / n:.2f} s CPU a record")


if __name__ == "__main__":
    main()
