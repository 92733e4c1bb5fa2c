"""Benchmark (issue 57, item 5): why the copy decoheres at the 5th BPFO harmonic while the car
accelerates, traced; and the copy-or-source coherence before and after the mend.

The copy-or-source test (bearing/diagnostics/coherence.py) compares a line's coherence between
the two sides with what a copy would give.  Before: the copy's reference was Bendat and
Piersol's ``rho_a / (1 + rho_a) rho_b / (1 + rho_b)`` from the record's averaged spectra, which
holds where each side's line keeps its strength over the record; now: segment by segment
(coherence._copy_g2).  Printed, each figure beside the candidate causes:

1. **The angle resampling and a fixed delay** (``--synthetic``): the swept pair of
   bearing/diagnostics/synthetic.py (a source and its copy ``delay`` later, the DTRB's BPFO order)
   on the shaft's clock, the coherent fraction per harmonic ``k`` (median of the seeds), with a
   delay of 0 and 1.2 ms, at a constant speed and ramped: the car's 2.1-3.05 Hz over 2.5 s and
   20-80 km/h over 20 s; and the 1.2 ms delay taken out in time before the clock.  A delay
   ``tau`` in time is ``f(t) tau`` turns on the clock, so harmonic ``k`` of order ``O`` turns by
   ``2 pi k O (f1 - f0) tau`` over the record; printed beside it the coherence such a turn leaves
   (``|mean_j exp(i 2 pi k O f(t_j) tau)|^2`` over the segments).
2. **The car** (a result file of configs/accelerating_20_60kmh.toml, its stored shaft angle and
   cages; ``axlebox simulate accelerating_20_60kmh --duration 4 --out acc.h5``): in windows of
   5.5 turns, 3/4 overlapping, and whole, on the shaft's clock: per harmonic the least coherent
   fraction of the BPFO line over the pairs of the two sides' own bands with the stationary
   reference (before) and the segments' (now), the decision each gives, and the verdict (the
   product's, now without a second look).
3. **On the car, the candidates**: (a) a fixed delay: the healthy side shifted by ``tau`` in time
   before the clock, the best 5th harmonic's fraction over ``tau``; (b) the copy's strength: each
   side's envelope locked to the defect row's roller passes (``20 x`` its cage angle), harmonic
   ``k``'s amplitude in the first and last 40 % of the record, beside an order no train has; (c)
   per twelfth of the record, the healthy side's 5th over 1st harmonic against the shaft speed
   and the two wheels' longitudinal creep forces (the drive's torque split, the axle's torsion):
   their correlations; (d) the mean envelope pulse about each impact, early and late: its peak's
   delay, width and 5th over 1st harmonic; (e) whether the ratio of the sides' harmonics is a
   function of the harmonic's frequency (a fixed filter: the band's edge) or of time.

Run: ``python benchmarks/copy_traction.py acc.h5`` (``--synthetic`` adds part 1, ``--seeds``).
"""
from __future__ import annotations

import argparse
import math
import time

from dataclasses import replace

import h5py
import numpy as np

from axlebox.bearing import models
from axlebox.bearing.diagnostics import coherence as co
from axlebox.bearing.diagnostics.criterion import Criterion, decide
from axlebox.bearing.diagnostics.pair import analyse_pair
from axlebox.bearing.diagnostics.clock import angle_clock
from axlebox.bearing.diagnostics.envelope import envelope
from axlebox.bearing.diagnostics.lag import impulse_lag, time_lag
from axlebox.bearing.diagnostics.synthetic import swept_coaxial_pair
from axlebox.bearing.frequencies import shaft_hz
from axlebox.bearing.models.params import BearingParams

FS = 10_000.0


def stationary(h: co.Harmonic, K: float) -> tuple[float, float, float]:
    """``(c, z, g2_copy)`` of harmonic ``h`` with the stationary reference (before the mend)."""
    ra, rb = (10 ** (r / 10) if math.isfinite(r) else 0.0 for r in (h.rho_a_db, h.rho_b_db))
    g2c = ra / (1 + ra) * rb / (1 + rb)
    c = h.g2 / g2c if g2c > 0 else math.nan
    return c, (co._fisher(g2c) - co._fisher(h.g2)) * math.sqrt(max(2 * K - 2, 1.0)), g2c


def stationary_timing(t: co.Timing) -> co.Timing:
    """``t`` with every harmonic's reference, fraction and test as before the mend."""
    def one(h):
        c, z, g2c = stationary(h, t.K)
        return replace(h, c=c, z=z, g2_copy=g2c)
    return replace(t, pairs=tuple(replace(p, harmonics=tuple(one(h) for h in p.harmonics))
                                  for p in t.pairs))


def verdict_before(res):
    """The verdict of pair result ``res`` with the copy test as before the mend."""
    ev = [replace(e, timing=stationary_timing(e.timing)) if e.timing is not None else e
          for e in res.evidence]
    return decide(res.left, res.right, res.lag, res.criterion, ev, gate=res.gate, rotor=res.rotor)


def per_k(timing: co.Timing) -> dict:
    """Per harmonic k, the least fraction of a usable harmonic over the pairs of bands, and
    whether it is significant (z >= z_min)."""
    out = {}
    for p in timing.pairs:
        for h in p.harmonics:
            if h.is_usable() and (h.k not in out or h.c < out[h.k][0]):
                out[h.k] = (h.c, h.is_significant())
    return out


def fmt(pk) -> str:
    return " ".join(f"k{k} {pk[k][0]:.2f}{'*' if pk[k][1] else ' '}" if k in pk else f"k{k}  -   "
                    for k in range(1, 6))


# ---- 1: the swept pair of synthetic.py ---------------------------------------------------------
def synthetic(seeds: int) -> None:
    order = models.orders(BearingParams()).BPFO
    band = (300.0, 900.0)
    cases = [("constant 2.58 Hz, 2.5 s", 2.5, 2.58, 2.58), ("car 2.1-3.05 Hz, 2.5 s", 2.5, 2.1, 3.05),
             ("constant 50 km/h, 20 s", 20.0, shaft_hz(50.0), shaft_hz(50.0)),
             ("20-80 km/h, 20 s", 20.0, shaft_hz(20.0), shaft_hz(80.0))]
    print(f"1. the swept pair (synthetic.py: BPFO order {order:.3f}, 600 Hz ring, copy through 546 Hz "
          f"at 0.3, noise 0.1), both sides' envelopes in {band[0]:g}-{band[1]:g} Hz on the shaft's "
          f"clock; coherent fraction per harmonic, median of {seeds} seeds [the coherence a fixed "
          "delay's turn leaves]")
    for name, T, f0, f1 in cases:
        variants = [(0.0, None), (1.2e-3, None), (1.2e-3, "true"), (5e-3, None), (5e-3, "true")]
        if f1 != f0:
            variants[1:1] = [(0.0, "lag")]
        for delay, undo in variants:
            cs = []
            for s in range(seeds):
                a, b, ang = swept_coaxial_pair(T, FS, order, f0, f1, np.random.default_rng(s),
                                               delay_s=delay, noise=0.1)
                if f1 == f0:
                    ang = f0 * np.arange(a.size) / FS
                if undo == "true":             # the copy's delay taken out in time, before the clock
                    b = np.roll(b, -int(round(delay * FS)))
                elif undo == "lag":            # the envelopes' lag, as read in time, taken out
                    lag = time_lag(a, b, FS, band, 0.5 / (order * f0)).delay_b_samples / FS
                    b = _shift(b, lag, FS)
                f_mean = (ang[-1] - ang[0]) * FS / (ang.size - 1)
                with angle_clock(ang, FS):
                    t = co.timing(a, b, FS, order * f_mean, [band], [band], line="BPFO")
                cs.append([h.c for h in t.pairs[0].harmonics])
            n = min(len(c) for c in cs)
            med = np.median(np.array([c[:n] for c in cs]), axis=0)
            # the turn a fixed delay leaves on the clock, over Welch's segments of t (Hann, 50 %)
            nper = int(round(max(8, int(T * order * f_mean) // 16) * FS / (order * f_mean)))
            tj = (np.arange(1 + (a.size - nper) // (nper // 2)) * (nper // 2) + nper / 2) / FS
            fj = f0 + (f1 - f0) * tj / T
            tau = delay if undo is None else 0.0
            pred = [abs(np.mean(np.exp(2j * np.pi * k * order * fj * tau))) ** 2 for k in range(1, n + 1)]
            lab = f"delay {delay * 1e3:.1f} ms" + {None: "", "true": ", taken out",
                                                    "lag": ", its lag out"}[undo]
            print(f"   {name:24s} {lab:24s} " + " ".join(f"k{k + 1} {med[k]:.2f} [{pred[k]:.2f}]"
                                                       for k in range(n)))
    row = []
    for d in (0.0, 1.2e-3, 5e-3):
        a, b, _ = swept_coaxial_pair(20.0, FS, order, shaft_hz(20.0), shaft_hz(80.0),
                                     np.random.default_rng(0), delay_s=d, noise=0.1)
        period = 1.0 / (order * shaft_hz(50.0))
        c = time_lag(a, b, FS, band, 0.5 * period).delay_b_samples / FS
        m = impulse_lag(a, b, FS, period, band).delay_b_samples / FS
        row.append(f"{d * 1e3:.1f} ms: {c * 1e3:.1f} and {m * 1e3:.1f} ms")
    print("   the path's delay against the copy's lag as read in time, 20-80 km/h (the envelopes' "
          "correlation, the impulses' onsets): " + "; ".join(row))
    from axlebox.pipelines.diagnose import analyse_record
    from axlebox.pipelines.readers import Record
    from axlebox.pipelines.speed import Speed
    print("   the product (`axlebox diagnose` with the speed: the DTRB, the paper's criterion) on the "
          "whole pair at noise 0.5, 20-80 km/h over 8 s, healthy side left:")
    for delay in (1.2e-3, 5e-3):
        tally = {}
        for s in range(seeds):
            right, left, ang = swept_coaxial_pair(8.0, FS, order, shaft_hz(20.0), shaft_hz(80.0),
                                                  np.random.default_rng(s), delay_s=delay)
            rec = Record(left, right, FS, ("healthy", "defect"), "csv")
            info, res = analyse_record(rec, Speed(ang, "the sweep's angle", "shaft"))
            clock = verdict_on_clock(rec, ang)
            key = (f"on the clock {clock['left']}/{clock['right']}",
                   f"second look {'fired' if info['speed'].get('second_look') else 'silent'}",
                   f"verdict {res.verdict.words['left']}/{res.verdict.words['right']}")
            tally[key] = tally.get(key, 0) + 1
        for key, n in tally.items():
            print(f"      path delay {delay * 1e3:.1f} ms: {n} of {seeds}: " + ", ".join(key))


def verdict_on_clock(rec, angle) -> dict:
    """The words of the order-tracked reading alone (no second look)."""
    from axlebox.bearing.catalogue import lookup
    from axlebox.bearing.diagnostics.criterion import Criterion
    b = lookup("dtrb")
    f_mean = (angle[-1] - angle[0]) * rec.fs / (angle.size - 1)
    return analyse_pair(rec.left, rec.right, rec.fs, f_mean, b.orders, b.bore, Criterion(),
                        names=rec.names, rotor="shaft", angle=angle).verdict.words


# ---- 2: the car, before and after ---------------------------------------------------------------
def car(path: str) -> None:
    from axlebox.pipelines.diagnose import analyse_record, read_input, side_bearings
    from axlebox.pipelines.speed import Speed
    from axlebox.pipelines.windows import bounds
    rec, speed = read_input(path)
    fs = rec.fs
    L, R, ang = rec.left, rec.right, speed.angle
    b = side_bearings(rec)["left"][0]
    wins = [(i0, i1, f"window {k}") for k, (i0, i1) in enumerate(bounds(ang, 5.5, 0.75))]
    wins.append((0, ang.size, "whole"))
    print(f"\n2. {path}: {rec.names[0]} (healthy) and {rec.names[1]} (defect), {L.size / fs:.2f} s read, "
          f"shaft {np.gradient(ang).min() * fs:.3f}-{np.gradient(ang).max() * fs:.3f} Hz; on the "
          "shaft's clock alone (no second look), the BPFO line's least coherent fraction per "
          "harmonic over the pairs of own bands (* significant), with the stationary reference "
          "(before) and the segments' (now), and the verdict each gives; then the product's")
    worst = None
    healthy_bands = set()
    for i0, i1, name in wins:
        a = ang[i0:i1]
        f = np.gradient(a) * fs
        f_mean = (a[-1] - a[0]) * fs / (a.size - 1)
        res = analyse_pair(L[i0:i1], R[i0:i1], fs, f_mean, b.orders, b.bore, Criterion(),
                           names=rec.names, angle=a)
        rec.left, rec.right = L[i0:i1], R[i0:i1]
        info, prod = analyse_record(rec, Speed(a, speed.source, speed.rotor), order_tracking="on")
        rec.left, rec.right = L, R
        ev = next((e for e in res.evidence if e.line == "BPFO" and e.timing is not None), None)
        if ev is not None:
            healthy_bands.update(p.band_a for p in ev.timing.pairs)
        print(f"   {name}: {i0 / fs:.2f}-{i1 / fs:.2f} s, shaft {f.min():.2f}-{f.max():.2f} Hz")
        if ev is not None:
            old = verdict_before(res)
            print(f"      before: {fmt(per_k(stationary_timing(ev.timing)))} -> "
                  f"{stationary_timing(ev.timing).decision}: left {old.words['left']}, right "
                  f"{old.words['right']} ({old.rule})")
            print(f"      now   : {fmt(per_k(ev.timing))} -> {ev.timing.decision}: left "
                  f"{res.verdict.words['left']}, right {res.verdict.words['right']} ({res.verdict.rule})")
            for p in ev.timing.pairs:
                for h in p.harmonics:
                    c_old = stationary(h, ev.timing.K)[0]
                    if h.k == 5 and h.is_usable() and (worst is None or c_old < worst[0]):
                        worst = (c_old, h.c, p.band_a, p.band_b, name, i0, i1, ev.timing.f)
        else:
            print(f"      BPFO not on both sides: left {res.verdict.words['left']}, right "
                  f"{res.verdict.words['right']} ({res.verdict.rule})")
        print(f"      the product: second look {'fired' if info['speed'].get('second_look') else 'silent'}; "
              f"left {prod.verdict.words['left']}, right {prod.verdict.words['right']}")
    if worst is not None:
        c_old, c_new, ba, bb, name, i0, i1, f_line = worst
        print(f"   the least 5th harmonic before: {c_old:.2f} ({name}, {rec.names[0]} in {ba[0]:.0f}-"
              f"{ba[1]:.0f} Hz, {rec.names[1]} in {bb[0]:.0f}-{bb[1]:.0f} Hz); now {c_new:.2f}")
        candidates(path, rec, speed, worst, sorted(healthy_bands))


def _shift(x: np.ndarray, tau: float, fs: float) -> np.ndarray:
    """``x(t + tau)`` (Fourier, the record zero-padded to twice its length)."""
    n = x.size
    X = np.fft.rfft(x, 2 * n)
    return np.fft.irfft(X * np.exp(2j * np.pi * np.fft.rfftfreq(2 * n, 1 / fs) * tau), 2 * n)[:n]


def candidates(path, rec, speed, worst, healthy_bands) -> None:
    _, _, ba, bb, name, i0, i1, f_line = worst
    fs = rec.fs
    L, R, ang = rec.left[i0:i1], rec.right[i0:i1], speed.angle[i0:i1]
    print(f"\n3. the candidates, on that pair of bands ({name})")
    best = {}
    row = []
    for tau_ms in (-20, -10, -5, -2, 0, 2, 5, 10, 20, 30, 40):
        with angle_clock(ang, fs):
            t = co.timing(_shift(L, tau_ms * 1e-3, fs), R, fs, f_line, [ba], [bb], line="BPFO")
        cs = {h.k: stationary(h, t.K)[0] for h in t.pairs[0].harmonics}
        row.append(f"{tau_ms:+d} ms " + " ".join(f"{cs[k]:.2f}" for k in sorted(cs)))
        for k, c in cs.items():
            best[k] = max(best.get(k, (-1.0, 0)), (c, tau_ms))
    print("   (a) the healthy side advanced by tau in time before the clock, the fraction of k = 1.. "
          "(stationary reference):\n      " + "; ".join(row) + "\n      best: " +
          "; ".join(f"k{k} {c:.2f} at {tau:+d} ms" for k, (c, tau) in sorted(best.items())))
    with h5py.File(path, "r") as f:
        t = f["time"][()]
        n0 = t.size - rec.left.size                  # the reader cuts the fade-in off the start
        ws = rec.names[1].split("_")[0]
        side = rec.names[1].split("_")[1]
        Z = 20
        cages = f[f"bearings/bearing{ws[2:]}{side}/cage"][n0:, :2]
        sh = f[f"shafts/{ws}/angle"][n0:] / (2 * np.pi)
        creep = {s: f[f"wheelrail/{ws}_{s}/force"][n0:, 0] for s in "LR"}
    eR_hi = envelope(rec.right, fs, bb)
    # the defect row: the cage whose roller passes the defect side's impulses keep in step with
    conc = []
    for c in range(2):
        ph = Z * np.abs(cages[:, c]) / (2 * np.pi)
        conc.append(abs(np.mean((eR_hi - eR_hi.mean()) * np.exp(-2j * np.pi * ph))))
    row_c = int(np.argmax(conc))
    ph = Z * np.abs(cages[:, row_c]) / (2 * np.pi)
    order = (ph[-1] - ph[0]) / (sh[-1] - sh[0])
    m = 500
    env = {"healthy": envelope(rec.left, fs, ba), "defect": eR_hi}
    n = rec.left.size
    print(f"   (b) each side's envelope locked to the roller passes of the defect row's cage (column "
          f"{row_c} of the cage record, order {order:.3f}), |harmonic k| x 1e3 in the first and last "
          "40 % of the record; beside it the same 1.5 orders higher (no train there: the floor)")
    for sname, e in env.items():
        for lab, sl in (("first 40 %", slice(m, int(0.4 * n))), ("last 40 %", slice(int(0.6 * n), n - m))):
            ee = e[sl] - e[sl].mean()
            amp = [abs(np.mean(ee * np.exp(-2j * np.pi * k * ph[sl]))) * 1e3 for k in range(1, 6)]
            flo = [abs(np.mean(ee * np.exp(-2j * np.pi * (k * order + 1.5) * sh[sl]))) * 1e3
                   for k in range(1, 6)]
            print(f"      {sname} side, {lab}: " + " ".join(f"k{k + 1} {a:6.2f} ({b:5.2f})"
                                                            for k, (a, b) in enumerate(zip(amp, flo))))
    def resid(y, x):
        return y - np.polyval(np.polyfit(x, y, 1), x)
    print("   (c) per twelfth of the record: shaft Hz, longitudinal creep force left/right kN, the "
          "healthy side's 5th/1st harmonic and its 5th's phase against the defect side's (rad), in "
          "each of the healthy side's own bands")
    for band in healthy_bands:
        eh = envelope(rec.left, fs, band)
        rows = []
        for idx in np.array_split(np.arange(m, n - m), 12):
            e = eh[idx] - eh[idx].mean()
            z1, z5 = (np.mean(e * np.exp(-2j * np.pi * k * ph[idx])) for k in (1, 5))
            d5 = np.mean((env["defect"][idx] - env["defect"][idx].mean()) * np.exp(-10j * np.pi * ph[idx]))
            rows.append((np.mean(np.gradient(sh)[idx]) * fs, creep["L"][idx].mean() / 1e3,
                         creep["R"][idx].mean() / 1e3, abs(z5) / abs(z1), np.angle(z5 / d5)))
        r = np.array(rows)
        partial = np.corrcoef(resid(r[:, 3], r[:, 0]), resid(r[:, 1], r[:, 0]))[0, 1]
        print(f"      {band[0]:.0f}-{band[1]:.0f} Hz: " +
              "; ".join(f"{a:.2f} Hz {b:+.1f}/{c:+.1f} kN {d:.3f} {g:+.2f}" for a, b, c, d, g in rows))
        print(f"         5th/1st's correlation with the speed {np.corrcoef(r[:, 3], r[:, 0])[0, 1]:+.2f}, "
              f"with the left wheel's creep force {np.corrcoef(r[:, 3], r[:, 1])[0, 1]:+.2f}; with that "
              f"force at a given speed (partial) {partial:+.2f}")
    print("   (d) the mean envelope pulse about each impact (the defect row's roller passes), early "
          "and late: peak after the impact, width over half its height, 5th/1st harmonic")
    hits = np.searchsorted(ph, np.arange(np.ceil(ph[m]), np.floor(ph[n - m])))
    for sname, e in env.items():
        out = []
        for lab, lo, hi in (("first 40 %", 0, 0.4 * n), ("last 40 %", 0.6 * n, n)):
            hh = hits[(hits > lo) & (hits < hi)]
            per = int(np.median(np.diff(hh)))
            W = np.array([e[h - per // 4:h - per // 4 + per] for h in hh
                          if h - per // 4 >= 0 and h - per // 4 + per <= n])
            avg = W.mean(axis=0)
            base = np.median(avg)
            pk = int(np.argmax(avg))
            width = np.count_nonzero(avg > base + 0.5 * (avg[pk] - base)) / fs
            A = np.abs(np.fft.rfft(avg - avg.mean()))
            peak = (pk - per // 4) / fs
            out.append(f"{lab}: {peak * 1e3:+.1f} ms, {width * 1e3:.1f} ms, {A[5] / A[1]:.2f}")
        print(f"      {sname} side: " + "; ".join(out))
    # (e) the sides' ratio per harmonic and eighth of the record, against the harmonic's frequency
    pts = []
    for j, idx in enumerate(np.array_split(np.arange(m, n - m), 8)):
        rate = (ph[idx[-1]] - ph[idx[0]]) / (idx.size - 1) * fs
        for k in range(1, 6):
            z = np.exp(-2j * np.pi * k * ph[idx])
            hL = np.mean((env["healthy"][idx] - env["healthy"][idx].mean()) * z)
            hR = np.mean((env["defect"][idx] - env["defect"][idx].mean()) * z)
            pts.append((k * rate, k, j, abs(hL / hR)))
    near = [(p, q) for p in pts for q in pts if p[1] < q[1] and abs(p[0] - q[0]) < 4.0]
    print("   (e) |healthy/defect| of harmonic k in eighth j of the record at the same frequency (within "
          "4 Hz), where a fixed filter (the band's edge) would give one value:\n      " +
          "; ".join(f"{p[0]:.0f} Hz: k{p[1]} j{p[2]} {p[3]:.2f} vs k{q[1]} j{q[2]} {q[3]:.2f}"
                    for p, q in near))


def constant(paths) -> None:
    """Records at a constant speed: each line's least coherent fraction and the verdict, before
    and now (the product's reading of the file, the paper's criterion and the relative one)."""
    from axlebox.pipelines.diagnose import analyse_file
    print("\n4. constant-speed records (read in time, as `axlebox diagnose FILE`): the least coherent "
          "fraction of each line seen on both sides and the verdict, before -> now")
    for path in paths:
        for crit in (Criterion(), Criterion(mode="relative")):
            _, _, res = analyse_file(path, criterion=crit)
            old = verdict_before(res)
            lines = []
            for e in res.evidence:
                if e.timing is not None:
                    c0, c1 = stationary_timing(e.timing).c_min, e.timing.c_min
                    lines.append(f"{e.key} {'-' if c0 is None else f'{c0:.3f}'} -> "
                                 f"{'-' if c1 is None else f'{c1:.3f}'}")
            w0, w1 = old.words, res.verdict.words
            print(f"   {path.split('/')[-1]} ({crit.mode}): {'; '.join(lines) or 'no line on both sides'}; "
                  f"left {w0['left']}, right {w0['right']} -> left {w1['left']}, right {w1['right']}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("result", nargs="?", help="a result file of accelerating_20_60kmh")
    ap.add_argument("--synthetic", action="store_true")
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--constant", nargs="*", default=(), metavar="FILE",
                    help="records at a constant speed to read before and now")
    a = ap.parse_args()
    t0 = time.perf_counter()
    if a.synthetic:
        synthetic(a.seeds)
    if a.result:
        car(a.result)
    if a.constant:
        constant(a.constant)
    print(f"\nwall {time.perf_counter() - t0:.1f} s")


if __name__ == "__main__":
    main()
