"""Benchmark: the cost of computed order tracking (bearing/diagnostics/ordertrack.py) per minute
of two channels at 10 kHz, against the plain envelope spectrum in time of the same record.

The record: a car accelerating from 20 to 80 km/h over the minute (0.42 m wheels), each channel
outer-ring hits at the DTRB's BPFO order ringing a 2.5 kHz mode, in noise.  Timed (best of
``--repeat``, the machine is shared): the shaft angle from the speed record, and per channel the
band-passed Hilbert envelope, its resampling to 256 samples a turn (anti-alias filter, spline)
and its Welch spectrum in orders (64-turn segments); beside it the envelope spectrum in time of
the same channels (64 mean turns a segment).  Peak memory: tracemalloc of one tracked run.
With ``--pair``: the whole two-channel diagnosis (:func:`~axlebox.bearing.diagnostics.pair.analyse_pair`,
the relative criterion) of the same minute on the shaft's clock (``angle=``, every envelope
resampled to the angle: bearing/diagnostics/clock.py) against the same read at the mean speed.
Run: ``python benchmarks/ordertrack.py [--pair]``.
"""
from __future__ import annotations

import argparse
import platform
import time
import tracemalloc

import numpy as np

from axlebox.bearing import models
from axlebox.bearing.diagnostics import ordertrack as ot
from axlebox.bearing.diagnostics.envelope import envelope_spectrum
from axlebox.bearing.diagnostics.synthetic import resonance
from axlebox.bearing.frequencies import shaft_hz
from axlebox.bearing.models.params import BearingParams

FS = 10_000.0
BAND = (2000.0, 3000.0)


def record(T: float, seed: int):
    t = np.arange(int(T * FS)) / FS
    f0, f1 = shaft_hz(20.0), shaft_hz(80.0)
    f = f0 + (f1 - f0) / T * t
    theta = f0 * t + 0.5 * (f1 - f0) / T * t ** 2
    bpfo = models.orders(BearingParams()).BPFO
    rng = np.random.default_rng(seed)
    hits = np.zeros(t.size)
    hits[np.searchsorted(theta, np.arange(1, int(theta[-1] * bpfo)) / bpfo)] = 1.0
    x = resonance(hits, FS, 2500.0, 0.05)
    chans = [x / x.std() + 0.5 * rng.standard_normal(t.size) for _ in range(2)]
    return t, f, chans


def tracked(t, f, chans):
    angle = ot.angle_from_speed(t, f)
    return [ot.envelope_orders(x, FS, angle, band=BAND, turns=64) for x in chans]


def plain(t, f, chans):
    return [envelope_spectrum(x, FS, BAND, nperseg=int(64 / f.mean() * FS)) for x in chans]


def best(fn, args, repeat: int) -> float:
    out = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn(*args)
        out = min(out, time.perf_counter() - t0)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--minutes", type=float, default=1.0)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--pair", action="store_true", help="time the whole pair diagnosis, on the "
                    "shaft's clock and at the mean speed")
    a = ap.parse_args()
    args = record(60.0 * a.minutes, 1)
    if a.pair:
        return pair(args, a)
    w_t, w_p = best(tracked, args, a.repeat), best(plain, args, a.repeat)
    tracemalloc.start()
    tracked(*args)
    peak = tracemalloc.get_traced_memory()[1] / 2 ** 20
    tracemalloc.stop()
    print(f"{platform.processor() or platform.machine()}, numpy {np.__version__}; "
          f"{a.minutes:g} min of two channels at {FS:g} Hz, 20-80 km/h")
    print("| step | wall s (best of {}) | s per minute of two channels |".format(a.repeat))
    print("| --- | --- | --- |")
    print(f"| order-tracked envelope spectrum | {w_t:.3f} | {w_t / a.minutes:.3f} |")
    print(f"| envelope spectrum in time | {w_p:.3f} | {w_p / a.minutes:.3f} |")
    print(f"tracking costs {w_t / w_p:.2f}x the plain envelope spectrum; peak memory (tracemalloc) "
          f"{peak:.0f} MB")


def pair(args, a):
    from axlebox.bearing.diagnostics.criterion import Criterion
    from axlebox.bearing.diagnostics.pair import analyse_pair
    t, f, (xl, xr) = args
    angle = ot.angle_from_speed(t, f)
    f_mean = angle[-1] / t[-1]
    o, crit = models.orders(BearingParams()), Criterion(mode="relative")

    def run(clock):
        return analyse_pair(xl, xr, FS, f_mean, o, 0.13, crit, angle=angle if clock else None)
    w_c, w_m = best(run, (True,), a.repeat), best(run, (False,), a.repeat)
    print(f"{platform.processor() or platform.machine()}, numpy {np.__version__}; {a.minutes:g} min "
          f"of two channels at {FS:g} Hz, 20-80 km/h, analyse_pair")
    print("| reading | wall s (best of {}) | s per minute of two channels |".format(a.repeat))
    print("| --- | --- | --- |")
    print(f"| on the shaft's clock | {w_c:.2f} | {w_c / a.minutes:.2f} |")
    print(f"| at the mean speed | {w_m:.2f} | {w_m / a.minutes:.2f} |")
    print(f"the clock costs {w_c / w_m:.2f}x the reading at the mean speed")


if __name__ == "__main__":
    main()
