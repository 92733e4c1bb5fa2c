"""Benchmark: ``axlebox diagnose`` on records of 1, 10 and 60 minutes at 25.6 kHz (issue 57):
the peak resident memory and the wall time of the command, in a fresh process each, for a CSV
and an HDF5 file.  The whole-record diagnosis reads at most ``readers.MAX_SAMPLES`` samples a
channel, the middle of a longer record, the rest never held (a CSV parsed row by row after its
lines are counted; HDF5 read on that span), so the memory must not grow with the length.

The record: one minute of the synthetic outer-ring defect and its copy (the DTRB at 48 km/h,
bearing/diagnostics/synthetic.coaxial_pair) repeated to length, laid so that the middle of the
record is the middle of a copy (an even number of minutes starts with the minute's second half
and ends with its first): every length reads the same 41 s, without a join (a join's step
changes what the analysis does, not how much memory the record takes); the CSV's rows are the
minute's text.  Run: ``python benchmarks/long_record.py [MINUTES ...]`` (default 1 10
60; the 60-minute CSV is 2.2 GB, written to a temporary folder and removed).
"""
from __future__ import annotations

import json
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import h5py
import numpy as np

from axlebox.bearing.diagnostics.synthetic import coaxial_pair
from axlebox.bearing.frequencies import orders, shaft_hz
from axlebox.bearing.models.params import BearingParams
from axlebox.pipelines.readers import MAX_SAMPLES

FS = 25_600.0
KMH = 48.0

PROBE = """
import resource, subprocess, sys, time
t = time.perf_counter()
r = subprocess.run(sys.argv[1:], capture_output=True, text=True)
peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
print(r.returncode, time.perf_counter() - t, peak, repr(r.stderr[-300:]))
"""


def minute():
    a, b = coaxial_pair(60.0, FS, orders(BearingParams()).BPFO * shaft_hz(KMH), np.random.default_rng(0))
    return a.astype(np.float32), b.astype(np.float32)


def pieces(minutes: int, n: int) -> list[slice]:
    """The minute's pieces laid end to end (module docstring)."""
    h = n // 2
    if minutes % 2:
        return [slice(0, n)] * minutes
    return [slice(h, n)] + [slice(0, n)] * (minutes - 1) + [slice(0, h)]


def write(folder: Path, minutes: int, a, b) -> dict:
    csv = folder / f"r{minutes}.csv"
    rows = [f"{u:.6g},{v:.6g}\n" for u, v in zip(a.tolist(), b.tolist())]
    with open(csv, "w") as fh:
        fh.write("left,right\n")
        for sl in pieces(minutes, a.size):
            fh.write("".join(rows[sl]))
    h5 = folder / f"r{minutes}.h5"
    with h5py.File(h5, "w") as f:
        for name, x in (("left", a), ("right", b)):
            ds = f.create_dataset(name, shape=(minutes * x.size,), dtype=np.float32)
            k = 0
            for sl in pieces(minutes, x.size):
                ds[k:k + sl.stop - sl.start] = x[sl]
                k += sl.stop - sl.start
            ds.attrs["fs_hz"] = FS
    return {"CSV": csv, "HDF5": h5}


def run(path: Path, out: Path) -> tuple:
    cmd = [sys.executable, "-m", "axlebox", "diagnose", str(path), "--fs", str(FS), "--speed-kmh", str(KMH),
           "--left", "left", "--right", "right", "--json", str(out)]
    r = subprocess.run([sys.executable, "-c", PROBE, *cmd], capture_output=True, text=True)
    rc, wall, peak_kb, err = r.stdout.split(maxsplit=3)
    words = json.loads(out.read_text())["verdict"]["words"] if int(rc) == 0 else None
    return int(rc), float(wall), int(peak_kb) / 1024, words, err


def main():
    minutes = [int(m) for m in sys.argv[1:]] or [1, 10, 60]
    print(f"{platform.machine()}, Python {platform.python_version()}; MAX_SAMPLES {MAX_SAMPLES} "
          f"({MAX_SAMPLES / FS:.4g} s at {FS:g} Hz)")
    a, b = minute()
    print("| record | format | file size | exit | wall (s) | peak memory (MB) | verdict (left / right) |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for m in minutes:
        with tempfile.TemporaryDirectory() as tmp:
            t = time.perf_counter()
            files = write(Path(tmp), m, a, b)
            made = time.perf_counter() - t
            for fmt, path in files.items():
                rc, wall, peak, words, err = run(path, Path(tmp) / "out.json")
                verdict = f"{words['left']} / {words['right']}" if words else err
                print(f"| {m} min | {fmt} | {path.stat().st_size / 2**20:.0f} MB | {rc} | {wall:.0f} | "
                      f"{peak:.0f} | {verdict} |", flush=True)
            print(f"(written in {made:.0f} s)", file=sys.stderr)


if __name__ == "__main__":
    main()
