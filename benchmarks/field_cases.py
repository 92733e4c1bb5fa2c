"""The paper's two field records as the model gives them: both axle boxes of wheelset 2.

    python3 benchmarks/field_cases.py VALIDATION_48KMH.h5 FIELD_64KMH.h5 [--figure PNG]

The files are ``axlebox simulate validation_48kmh`` and ``axlebox simulate field_64kmh`` (2 s
each).  For each: the defect side (ws2_R) and the healthy side (ws2_L) over 0.1 s after the
fade-in, as the paper's Figs. 1 and 8 show them, and each side's Welch PSD with the paper's
band (0-1 kHz, ``criterion.VF_BAND_PAPER``) shaded; the printed lines give RMS, VF over the
band and over the whole record, and their differences beside the paper's (1.43e4 Hz^2 at
48 km/h, its Fig. 8; 2.65e4 at 64.5 km/h, its Fig. 1).
"""
from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from scipy.signal import welch

from axlebox.bearing.diagnostics.criterion import VF_BAND_PAPER
from axlebox.pipelines.diagnose import analyse_file

PAPER = {48.0: 1.43e4, 64.5: 2.65e4}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("files", nargs=2, help="the 48 and the 64.5 km/h result files")
    ap.add_argument("--figure", default="benchmarks/figures/field_cases.png")
    a = ap.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(12, 6.5))
    for row, (path, speed) in enumerate(zip(a.files, PAPER)):
        rec, _, pair = analyse_file(Path(path))
        band = pair.in_vf_band(VF_BAND_PAPER)
        t = np.arange(rec.right.size) / rec.fs
        w = (t >= 1.0) & (t < 1.1)
        ax = axes[row, 0]
        ax.plot(t[w], rec.right[w], lw=0.7, label=f"defect side ws2_R, RMS {rec.right.std():.2f}")
        ax.plot(t[w], rec.left[w], lw=0.7, label=f"healthy side ws2_L, RMS {rec.left.std():.2f}")
        ax.set_title(f"{speed:g} km/h: vertical axle-box acceleration")
        ax.set_ylabel("m/s^2")
        ax.legend(fontsize=7, loc="upper right")
        ax = axes[row, 1]
        for x, side in ((rec.right, "defect"), (rec.left, "healthy")):
            f, P = welch(x - x.mean(), rec.fs, nperseg=4096)
            ax.semilogy(f, P, lw=0.8, label=side)
        ax.axvspan(*VF_BAND_PAPER, color="0.9", zorder=0)
        ax.set_title(f"0-1 kHz VF difference {band.vf_diff:.3g} Hz^2 (paper: {PAPER[speed]:.3g})")
        ax.set_ylim(1e-8, None)
        ax.set_ylabel("(m/s^2)^2/Hz")
        ax.legend(fontsize=7)
        print(f"{speed:g} km/h: RMS defect / healthy {rec.right.std():.2f} / {rec.left.std():.2f} m/s^2; "
              f"VF over 0-1 kHz {band.right.VF:.3g} / {band.left.VF:.3g}, difference {band.vf_diff:.3g}; "
              f"whole record {pair.right.VF:.3g} / {pair.left.VF:.3g}, difference {pair.vf_diff:.3g} "
              f"(the paper's difference {PAPER[speed]:.3g}); verdicts R / L {pair.verdict.words['right']} / "
              f"{pair.verdict.words['left']}")
    axes[1, 0].set_xlabel("s")
    axes[1, 1].set_xlabel("Hz")
    fig.tight_layout()
    Path(a.figure).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(a.figure, dpi=100)
    print(f"wrote {a.figure}")


if __name__ == "__main__":
    main()
