"""Benchmark (issue 51, the baseline; issue 57, item 2): what the product says of a record taken
while the train accelerates, read with one mean speed.

Each seed: a source and its copy (the coaxial family of bearing/diagnostics/synthetic.py) while
the car accelerates from 20 to 80 km/h at a constant rate over ``--duration`` s: outer-ring hits
every 1/BPFO of a shaft turn (the DTRB's order; 1 % jitter) ringing a 600 Hz mode on the defect
side (right), the same response 1.2 ms later through the 546 Hz bending mode at 0.3 of its RMS
on the healthy side (left), each side in its own wheel-rail noise; read by ``analyse_pair`` (the
relative criterion) with the sweep's mean shaft speed, as ``axlebox diagnose --speed-kmh 50``
would.  Printed: the confusion of each side's verdict over the seeds (the defect side should be
"real fault", the healthy side "pseudo-fault"; a healthy side called "real fault" or "faults on
both sides" is the worst error), and the wall time.  Run: ``python benchmarks/speed_sweep.py``.

Readings (``--reading``): ``record`` (the default), as ``axlebox diagnose --speed-kmh 50`` reads
it now (:func:`axlebox.pipelines.diagnose.analyse_record`: the speed read from the record itself,
bearing/diagnostics/ias.py, and the record read on that clock, or "undecided" with the reason;
the estimate's status and its error against the true speed printed too); ``given``: at the mean
speed alone, as before issue 57 (``analyse_pair`` without a clock); ``tracked``: on the true
shaft angle (``--tracked``, the same).
"""
from __future__ import annotations

import argparse
import time
from collections import Counter

import numpy as np

from axlebox.bearing import models
from axlebox.bearing.diagnostics.criterion import Criterion
from axlebox.bearing.diagnostics.pair import analyse_pair
from axlebox.bearing.diagnostics.synthetic import swept_coaxial_pair
from axlebox.bearing.frequencies import shaft_hz
from axlebox.bearing.models.params import BearingParams
from axlebox.pipelines import speed as sp
from axlebox.pipelines.diagnose import analyse_record
from axlebox.pipelines.readers import Record

FS = 10_000.0
VERDICTS = ("real fault", "pseudo-fault", "faults on both sides", "healthy", "undecided")


def swept_pair(T: float, seed: int, v0: float = 20.0, v1: float = 80.0):
    """``(defect side, healthy side, angle)`` of one seed (module docstring)."""
    return swept_coaxial_pair(T, FS, models.orders(BearingParams()).BPFO, shaft_hz(v0), shaft_hz(v1),
                              np.random.default_rng(seed))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=100)
    ap.add_argument("--first", type=int, default=0, help="the first seed")
    ap.add_argument("--duration", type=float, default=20.0)
    ap.add_argument("--reading", choices=("record", "given", "tracked"), default="record",
                    help="record: the product's (the speed read from the record); given: at the "
                    "mean speed alone (before issue 57); tracked: on the true angle")
    ap.add_argument("--tracked", action="store_true", help="read with the speed: the envelopes on "
                    "the shaft's clock (bearing/diagnostics/clock.py); --reading tracked")
    ap.add_argument("--kmh", type=float, nargs=2, default=(20.0, 80.0), metavar=("FROM", "TO"),
                    help="the sweep's speeds (equal: a constant-speed control)")
    a = ap.parse_args()
    reading = "tracked" if a.tracked else a.reading
    o = models.orders(BearingParams())
    crit = Criterion(mode="relative")
    tally = {"defect": Counter(), "healthy": Counter()}
    status, errors, reasons = Counter(), [], Counter()
    t0 = time.perf_counter()
    for seed in range(a.first, a.first + a.seeds):
        right, left, angle = swept_pair(a.duration, seed, *a.kmh)
        f_mean = (angle[-1] - angle[0]) * FS / (angle.size - 1)      # the mean speed, turns/s
        if reading == "record":
            # as analyse_windows does: the speed read once, then the record read with it
            rec = Record(left, right, FS, ("healthy", "defect"), "csv")
            speed, est = sp.from_record(left, right, FS, f_mean, (o, o), "shaft")
            _, p = analyse_record(rec, speed, shaft=f_mean, criterion=crit, estimate=est)
            status[est.status] += 1
            if est.status == "untrusted":
                reasons[est.reason] += 1
            if speed is not None:
                err = np.gradient(speed.angle) / np.gradient(angle) - 1.0
                errors.append((float(np.sqrt(np.mean(err ** 2))), float(np.max(np.abs(err)))))
        else:
            p = analyse_pair(left, right, FS, f_mean, o, 0.13, crit,
                             angle=angle if reading == "tracked" else None)
        tally["defect"][p.verdict.words["right"]] += 1
        tally["healthy"][p.verdict.words["left"]] += 1
    wall = time.perf_counter() - t0
    how = {"tracked": "on the shaft's clock (the true angle)", "given": "read at the mean speed alone",
           "record": "read with the mean speed, the speed over the record read from the record"}[reading]
    print(f"{a.seeds} seeds ({a.first}-{a.first + a.seeds - 1}), {a.duration:g} s at {FS:g} Hz, "
          f"{a.kmh[0]:g}-{a.kmh[1]:g} km/h, {how} ({wall:.1f} s wall, {wall / a.seeds:.2f} s a record)")
    print("| side | " + " | ".join(VERDICTS) + " |")
    print("| --- |" + " --- |" * len(VERDICTS))
    for side, c in tally.items():
        print(f"| {side} | " + " | ".join(str(c.get(v, 0)) for v in VERDICTS) + " |")
    if reading == "record":
        print("the estimate: " + ", ".join(f"{k} {v}" for k, v in sorted(status.items())))
        for r, n in reasons.items():
            print(f"  untrusted ({n}): {r}")
        if errors:
            e = np.array(errors)
            print("its speed against the true one, relative: RMS over a record median "
                  f"{np.median(e[:, 0]):.2e} (worst {e[:, 0].max():.2e}); largest at a sample median "
                  f"{np.median(e[:, 1]):.2e} "
                  f"(worst {e[:, 1].max():.2e})")


if __name__ == "__main__":
    main()
