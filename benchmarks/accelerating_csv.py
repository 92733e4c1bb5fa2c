"""Benchmark (issue 57, item 2): the accelerating car's two axle-box channels as a user without a
speed channel has them, a CSV read with the record's mean speed alone.

A result file of ``axlebox simulate accelerating_20_60kmh --duration 4`` (the validation case's
car from 20 km/h at 1 m/s^2, the paper's outer-ring defect on wheelset 2, right): its sensors
ws2_L and ws2_R after the track's fade-in (0.5 s on, as `axlebox diagnose` reads the file) are
written to a CSV beside it and read with ``--speed-kmh`` the mean of the stored shaft angle
(26.3 km/h for the 4 s run), whole and in windows of 5.5 turns, 3/4 overlapping; each reading
beside the one on the stored shaft angle.  Printed: the speed read from the record
(bearing/diagnostics/ias.py) against the stored one, and for each window and the whole record
the words, the rule and the lines that decided.  Run: ``python benchmarks/accelerating_csv.py
RESULT.h5`` (the simulation costs minutes; pass a file made once).
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from axlebox.bearing.diagnostics.criterion import Criterion
from axlebox.bearing.frequencies import shaft_hz
from axlebox.pipelines.diagnose import analyse_file, read_input
from axlebox.pipelines.windows import analyse_windows

R_WHEEL = 0.42          # --wheel-radius's default, as a user would give the speed


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("result", help="a result file of accelerating_20_60kmh (axlebox simulate)")
    ap.add_argument("--turns", type=float, default=5.5)
    ap.add_argument("--overlap", type=float, default=0.75)
    ap.add_argument("--relative", action="store_true", help="the relative criterion (default absolute, "
                    "as axlebox diagnose)")
    a = ap.parse_args()
    crit = Criterion(mode="relative") if a.relative else Criterion()
    rec, speed = read_input(a.result)
    csv = Path(a.result).with_suffix(".csv")
    np.savetxt(csv, np.column_stack([rec.left, rec.right]), delimiter=",",
               header=f"{rec.names[0]},{rec.names[1]}", comments="")
    f_mean = (speed.angle[-1] - speed.angle[0]) * rec.fs / (speed.angle.size - 1)
    kmh = f_mean * 2 * np.pi * R_WHEEL * 3.6
    kmh = round(kmh, 1)
    print(f"{csv.name}: {rec.left.size} samples at {rec.fs:g} Hz ({rec.left.size / rec.fs:.2f} s), "
          f"shaft {np.gradient(speed.angle).min() * rec.fs:.3g}-{np.gradient(speed.angle).max() * rec.fs:.3g}"
          f" Hz stored; read with --speed-kmh {kmh:g} (shaft {shaft_hz(kmh, R_WHEEL):.4g} Hz)")
    opts = dict(left=rec.names[0], right=rec.names[1], fs=rec.fs, speed_kmh=kmh, criterion=crit)
    t0 = time.perf_counter()
    _, info, whole = analyse_file(csv, **opts)
    wall = time.perf_counter() - t0
    est = info["speed"]["estimate"]
    print(f"the speed from the record: {est['status']} ({est['family']}): {est['reason']} "
          f"[{wall:.1f} s wall, the whole diagnosis]")
    if info["speed"]["from"] != "given":
        from axlebox.pipelines import speed as sp
        from axlebox.pipelines.diagnose import side_bearings
        b = side_bearings(rec)
        mine, _ = sp.from_record(rec.left, rec.right, rec.fs, shaft_hz(kmh, R_WHEEL),
                                 (b["left"][0].orders, b["right"][0].orders), "wheel")
        f_true = np.gradient(speed.angle) * rec.fs
        f_est = np.gradient(mine.angle) * rec.fs
        dev = f_est / f_true * (f_true.mean() / f_est.mean()) - 1.0
        print(f"  against the stored speed (each over its mean): RMS {np.sqrt(np.mean(dev ** 2)):.2e}, "
              f"largest {np.max(np.abs(dev)):.2e}")
    _, _, stored = analyse_file(a.result, criterion=crit)
    print("| reading | left (healthy) | right (defect) | rule | lines |")
    print("| --- | --- | --- | --- | --- |")
    for name, p in (("whole, CSV, mean speed", whole), ("whole, stored angle", stored)):
        v = p.verdict
        print(f"| {name} | {v.words['left']} | {v.words['right']} | {v.rule} | {v.row()['lines']} |")
    w = analyse_windows(csv, a.turns, a.overlap, **opts)
    ws = analyse_windows(a.result, a.turns, a.overlap, criterion=crit)
    print(f"\nwindows of {a.turns:g} turns, {a.overlap:g} overlap")
    print("| window | s | shaft Hz | speed from | left | right | rule | lines | stored angle: left, right |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for r, q in zip(w.rows, ws.rows):
        words = ("not read", "not read") if "not_read" in r else (r["words"]["left"], r["words"]["right"])
        ref = ("not read",) * 2 if "not_read" in q else (q["words"]["left"], q["words"]["right"])
        print(f"| {r['window']} | {r['t0_s']:.2f}-{r['t1_s']:.2f} | "
              f"{r['speed_hz'][0]:.3g}-{r['speed_hz'][1]:.3g} | {r['speed_source']} | {words[0]} | "
              f"{words[1]} | {r.get('rule', '-')} | {r.get('lines', '-')} | {ref[0]}, {ref[1]} |")
    healthy = sum(1 for r in w.read if r["words"]["right"] == "healthy")
    print(f"defect side 'healthy' in {healthy} of {len(w.read)} windows read")


if __name__ == "__main__":
    main()
