"""The coaxial pseudo-fault of a result file's defect, side by side: RMS, the envelope spectrum's
fault line with its shaft sidebands against the local floor on each axle box of a wheelset, and
the impulse lag between them (bearing/diagnostics).

    axlebox simulate inner_48kmh --out inner.h5
    python3 benchmarks/pseudo_fault.py inner.h5 [--line BPFI] [--left ws2_L --right ws2_R]

Band by band (broadband 0.5-4.5 kHz, 1-4 kHz, 2-4.5 kHz), after the track's 0.5 s fade-in: the
line (largest bin within 3 % of the fault frequency), its sidebands at +- the shaft frequency,
the floor (median over 3-20 % beside the line), and the healthy side's line over the defect
side's.  The lag: `impulse_lag` at the line's period (the defect side given first).
"""
from __future__ import annotations

import argparse
from axlebox.mbs.vehicle import config as vconfig

import numpy as np

from axlebox.bearing.diagnostics.envelope import envelope_spectrum
from axlebox.bearing.diagnostics.lag import impulse_lag
from axlebox.bearing.frequencies import orders, shaft_hz
from axlebox.bearing.models.params import BearingParams
from axlebox.bearing.resultfile import open_result
from axlebox.pipelines.readers import TRACK_FADE_IN_S

BANDS = ((500.0, 4500.0), (1000.0, 4000.0), (2000.0, 4500.0))


def lines(x, fs: float, f0: float, f_s: float, band) -> dict:
    f, A = envelope_spectrum(x, fs, band=band)

    def at(fq):
        return float(A[np.abs(f - fq) <= max(0.03 * fq, f[1])].max())
    beside = (np.abs(f - f0) > 0.03 * f0) & (np.abs(f - f0) < 0.2 * f0)
    return {"line": at(f0), "floor": float(np.median(A[beside])), "minus": at(f0 - f_s),
            "plus": at(f0 + f_s)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("result")
    ap.add_argument("--line", default="BPFI", choices=["BPFO", "BPFI"])
    ap.add_argument("--left", default="ws2_L")
    ap.add_argument("--right", default="ws2_R", help="the defect side")
    a = ap.parse_args()
    with open_result(a.result) as f:
        cfg = vconfig.loads(str(f.attrs["config"]), a.result)
        fs = float(f.attrs.get("fs_hz", 1e4))
        t = f["time"][:]
        sig = {n: f[f"signals/{n}/acceleration"][:, 2][t >= TRACK_FADE_IN_S] for n in (a.left, a.right)}
    f_s = shaft_hz(cfg.run.speed_kmh, cfg.wheelset.r0)
    f0 = orders(BearingParams()).at(f_s)[a.line]
    print(f"{a.result}: {a.line} {f0:.2f} Hz, shaft {f_s:.2f} Hz, defect side {a.right}, "
          f"{sig[a.right].size / fs:g} s read")
    print(f"| band Hz | side | RMS m/s^2 | {a.line} line | floor | line / floor | -f_s | +f_s | "
          "healthy / defect line |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for band in BANDS:
        res = {n: lines(x, fs, f0, f_s, band) for n, x in sig.items()}
        for n in (a.right, a.left):
            r = res[n]
            ratio = res[a.left]["line"] / res[a.right]["line"] if n == a.left else 1.0
            print(f"| {band[0]:g}-{band[1]:g} | {n} | {sig[n].std():.3f} | {r['line']:.3f} | "
                  f"{r['floor']:.3f} | {r['line'] / r['floor']:.1f} | {r['minus']:.3f} | "
                  f"{r['plus']:.3f} | {ratio:.2f} |")
    lag = impulse_lag(sig[a.right], sig[a.left], fs, 1.0 / f0)
    side = a.right if lag.leading == "a" else a.left
    print(f"lag {lag.lag_s * 1e3:.1f} ms, {side} leads ({lag.n_impulses} impulses, "
          f"{100 * lag.agreement:.0f} % agree, spread {lag.spread_s * 1e3:.2f} ms)")


if __name__ == "__main__":
    main()
