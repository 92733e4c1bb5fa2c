"""The paper's result figures (Figs. 9-14) in its style, drawn with matplotlib off-screen.

Each function takes :class:`axlebox.pipelines.report.Case` objects (a run's case parameters and its
:class:`axlebox.bearing.diagnostics.pair.PairResult`) and writes one PNG.  Sides are drawn the same way
everywhere: the left sensor solid, the right sensor dashed; defect widths by colour.
"""
from __future__ import annotations

from pathlib import Path

import matplotlib
import numpy as np

from axlebox._figures import subplots
from axlebox.bearing.diagnostics.spectral import psd

SIDES = (("left", "-"), ("right", "--"))
SPM_BANDS = ((0.0, 21.0, "#e8f5e9", "normal"), (21.0, 35.0, "#fff8e1", "mild"),
             (35.0, 60.0, "#ffebee", "serious"))          # paper, below Eq. 17
LAG_PAPER_S = (1.1e-3, 4.2e-3)                            # paper, Fig. 13
DPI = 110


def _save(fig, path: Path) -> Path:
    fig.savefig(path, dpi=DPI)
    return path


def _colour(widths, w):
    cmap = matplotlib.colormaps["viridis"]
    ws = sorted(widths)
    return cmap(0.85 * ws.index(w) / max(len(ws) - 1, 1))


def _width_label(w_mm: float) -> str:
    return "no defect" if w_mm == 0 else f"{w_mm:g} mm"


def _side_title(case, side: str) -> str:
    name = case.pair.names[0 if side == "left" else 1]
    return f"{side} ({name}): {case.pair.verdict.words[side]}"


def _signal(case, side):
    return case.pair.x_left if side == "left" else case.pair.x_right


def _fault_period(case) -> float:
    c = case.pair.left
    return 1.0 / c.fault_hz.get("BPFO", min(c.fault_hz.values()))


def time_signals(cases, path: Path, n_periods: float = 8.0) -> Path:
    """Fig. 9: both sides' acceleration over ``n_periods`` fault periods, a row per case."""
    fig, ax = subplots(len(cases), 2, figsize=(11, 2.2 * len(cases) + 0.6), squeeze=False,
                           sharex=True, constrained_layout=True)
    for i, case in enumerate(cases):
        fs = case.pair.left.fs
        k = min(case.pair.left.n_samples, int(n_periods * _fault_period(case) * fs))
        ylim = 1.05 * max(np.abs(_signal(case, s)[:k]).max() for s, _ in SIDES)
        for j, (side, _) in enumerate(SIDES):
            ax[i, j].plot(np.arange(k) / fs, _signal(case, side)[:k], lw=0.5, color="k")
            ax[i, j].set_ylim(-ylim, ylim)
            ax[i, j].set_title(f"{case.label}; {_side_title(case, side)}", fontsize=8)
            ax[i, j].set_ylabel("a (m/s$^2$)")
    for j in range(2):
        ax[-1, j].set_xlabel("time (s)")
    fig.suptitle("Axle-box vertical acceleration on both sides (cf. paper Fig. 9)", fontsize=10)
    return _save(fig, path)


def envelope_spectra(cases, path: Path, n_harmonics: int = 4) -> Path:
    """Fig. 10: envelope spectra normalised to their largest value, with the BPFO harmonics
    (dashed) and the FTF (dotted) marked."""
    fig, ax = subplots(len(cases), 2, figsize=(11, 2.2 * len(cases) + 0.6), squeeze=False,
                           constrained_layout=True)
    for i, case in enumerate(cases):
        for j, (side, _) in enumerate(SIDES):
            c = getattr(case.pair, side)
            f_o = c.fault_hz.get("BPFO", max(c.fault_hz.values()))
            keep = (c.env_f > 0) & (c.env_f <= (n_harmonics + 0.5) * f_o)
            A = c.env_A[keep]
            ax[i, j].plot(c.env_f[keep], A / max(A.max(), 1e-300), lw=0.7, color="k")
            for k in range(1, n_harmonics + 1):
                ax[i, j].axvline(k * f_o, color="tab:red", lw=0.6, ls="--",
                                 label=f"k x BPFO ({f_o:.4g} Hz)" if k == 1 else None)
            if "FTF" in c.fault_hz:
                ax[i, j].axvline(c.fault_hz["FTF"], color="tab:purple", lw=0.6, ls=":",
                                 label=f"FTF ({c.fault_hz['FTF']:.3g} Hz)")
            ax[i, j].set_title(f"{case.label}; {_side_title(case, side)}; band "
                               f"{c.band[0]:.0f}-{c.band[1]:.0f} Hz", fontsize=8)
            ax[i, j].set_ylabel("normalised")
            ax[i, j].legend(fontsize=6, loc="upper right")
    for j in range(2):
        ax[-1, j].set_xlabel("frequency (Hz)")
    fig.suptitle("Normalised envelope spectra with the fault frequencies (cf. paper Fig. 10)",
                 fontsize=10)
    return _save(fig, path)


def _by_width(cases):
    out = {}
    for c in sorted(cases, key=lambda c: (c.width_mm, c.speed_kmh)):
        out.setdefault(c.width_mm, []).append(c)
    return out


def _against_speed(ax, cases, value, ylabel):
    groups = _by_width(cases)
    for w, cs in groups.items():
        v = [c.speed_kmh for c in cs]
        for side, ls in SIDES:
            ax.plot(v, [value(c, side) for c in cs], ls, marker="o", ms=4,
                    color=_colour(groups, w), label=f"{_width_label(w)}, {side}")
    ax.set_xlabel("speed (km/h)")
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=6, ncol=2)


def indicators(cases, path: Path) -> Path:
    """Fig. 11: RMS (a) and SPM (b) of both sides against speed, a curve per defect width;
    (b) shades the SPM bands (normal < 21 dB <= mild <= 35 dB < serious)."""
    fig, ax = subplots(1, 2, figsize=(11, 4.2), constrained_layout=True)
    _against_speed(ax[0], cases, lambda c, s: getattr(c.pair, s).rms, "RMS (m/s$^2$)")
    ax[0].set_title("(a) RMS", fontsize=9)
    for lo, hi, colour, name in SPM_BANDS:
        ax[1].axhspan(lo, hi, color=colour, zorder=0)
        ax[1].text(0.01, (lo + hi) / 2, name, transform=ax[1].get_yaxis_transform(), fontsize=7,
                   va="center", color="0.4")
    _against_speed(ax[1], cases, lambda c, s: getattr(c.pair, s).spm_db, "SPM (dB)")
    lo = min(0.0, min(getattr(c.pair, s).spm_db for c in cases for s, _ in SIDES) - 3)
    hi = max(60.0, max(getattr(c.pair, s).spm_db for c in cases for s, _ in SIDES) + 3)
    ax[1].set_ylim(lo, hi)
    ax[1].set_title("(b) SPM, Eq. 17", fontsize=9)
    fig.suptitle("Fault-severity indicators on both sides (cf. paper Fig. 11)", fontsize=10)
    return _save(fig, path)


def comparison(case, path: Path, n_periods: float = 3.0) -> Path:
    """Fig. 12: both sides overlaid over a few fault periods (the lag shows as a shift of the
    impulses) and their Welch PSDs overlaid, with FC of each side marked."""
    fig, ax = subplots(1, 2, figsize=(11, 3.8), constrained_layout=True)
    fs = case.pair.left.fs
    k = min(case.pair.left.n_samples, int(n_periods * _fault_period(case) * fs))
    for side, ls in SIDES:
        x = _signal(case, side)
        ax[0].plot(np.arange(k) / fs, x[:k], ls, lw=0.6, label=side)
        f, S = psd(x, fs)
        line, = ax[1].semilogy(f, S, ls, lw=0.7, label=f"{side}, FC {getattr(case.pair, side).FC:.0f} Hz")
        ax[1].axvline(getattr(case.pair, side).FC, color=line.get_color(), lw=0.6, ls=":")
    lag = case.pair.lag
    lead = {"a": "left", "b": "right"}.get(lag.leading, "neither")
    ax[0].set(xlabel="time (s)", ylabel="a (m/s$^2$)",
              title=f"{case.label}: {lead} leads by {lag.lag_s * 1e3:.2f} ms")
    ax[1].set(xlabel="frequency (Hz)", ylabel="PSD ((m/s$^2$)$^2$/Hz)",
              title=f"VF difference {case.pair.vf_diff:.3g} Hz$^2$ over {case.pair.criterion.band_text}")
    if case.pair.criterion.vf_band is not None:
        ax[1].axvspan(*case.pair.criterion.vf_band, color="0.9", zorder=0, label="FC, VF band")
    for a in ax:
        a.legend(fontsize=7)
        a.title.set_fontsize(9)
    fig.suptitle("Time and frequency comparison of both sides (cf. paper Fig. 12)", fontsize=10)
    return _save(fig, path)


def lags(cases, path: Path) -> Path:
    """Fig. 13: the lag of the trailing side against speed, a curve per defect width, with the
    paper's range (1.1-4.2 ms) shaded; cases whose envelopes do not correlate are left out."""
    fig, ax = subplots(figsize=(6.5, 4.2), constrained_layout=True)
    ax.axhspan(*(1e3 * v for v in LAG_PAPER_S), color="0.92", zorder=0, label="paper, 1.1-4.2 ms")
    groups = _by_width([c for c in cases if c.width_mm > 0])
    for w, cs in groups.items():
        ok = [c for c in cs if c.pair.lag.peak >= c.pair.criterion.lag_min_peak]
        ax.plot([c.speed_kmh for c in ok], [1e3 * c.pair.lag.lag_s for c in ok], "-o", ms=4,
                color=_colour(groups, w), label=_width_label(w))
    ax.set(xlabel="speed (km/h)", ylabel="lag (ms)",
           title="Lag of the trailing side (cf. paper Fig. 13)")
    ax.title.set_fontsize(10)
    ax.legend(fontsize=7)
    return _save(fig, path)


def vf(cases, path: Path) -> Path:
    """Fig. 14: VF of both sides against speed, a panel per defect width, the VF difference
    written over each pair of bars and the criterion's range quoted."""
    groups = _by_width(cases)
    # at least 8 in wide: one width's panel alone is too narrow for the figure's title
    fig, ax = subplots(1, len(groups), figsize=(max(4.2 * len(groups), 8.0), 4.0),
                           squeeze=False, constrained_layout=True)
    for p, (w, cs) in enumerate(groups.items()):
        a = ax[0, p]
        x = np.arange(len(cs))
        for o, (side, _) in zip((-0.2, 0.2), SIDES):
            a.bar(x + o, [getattr(c.pair, side).VF for c in cs], 0.4, label=side)
        for i, c in enumerate(cs):
            top = max(c.pair.left.VF, c.pair.right.VF)
            a.text(i, 1.02 * top, f"{c.pair.vf_diff:.2g}", ha="center", fontsize=7)
        a.set_xticks(x, [f"{c.speed_kmh:g}" for c in cs])
        crit = cs[0].pair.criterion
        a.set(xlabel="speed (km/h)", ylabel="VF (Hz$^2$)",
              title=f"({'abcdefgh'[p % 8]}) {_width_label(w)}; criterion {crit.mode} "
                    f"[{crit.range[0]:.3g}, {crit.range[1]:.3g}] {crit.unit}")
        a.title.set_fontsize(8)
        a.set_ylim(0, 1.25 * max(max(c.pair.left.VF, c.pair.right.VF) for c in cs))
        a.legend(fontsize=7, loc="upper center", ncol=2)
    fig.suptitle(f"Frequency variance VF (Eq. 18) of both sides over {crit.band_text};\n"
                 "numbers: the VF difference (cf. paper Fig. 14)", fontsize=10)
    return _save(fig, path)


def comfort_spectra(cases, path: Path, sensor: str = "carbody_centre") -> Path:
    """The carbody floor's weighted spectra (W_d lateral, W_b vertical; EN 12299) at ``sensor``,
    a panel per speed, a curve per defect width, Sperling's and EN 12299's indices in the
    legend."""
    speeds = sorted({c.speed_kmh for c in cases})
    fig, ax = subplots(len(speeds), 2, figsize=(11, 2.6 * len(speeds) + 0.6), squeeze=False,
                           constrained_layout=True)
    widths = {c.width_mm for c in cases}
    for i, v in enumerate(speeds):
        for c in (c for c in cases if c.speed_kmh == v):
            rc = next((r for r in c.ride if r.sensor == sensor), None)
            if rc is None:
                continue
            sel = (rc.f_hz >= 0.3) & (rc.f_hz <= 80)
            for j, (key, idx) in enumerate((("lateral, weighted Wd", f"W_y {rc.W_y:.2f}"),
                                            ("vertical, weighted Wb", f"W_z {rc.W_z:.2f}"))):
                ax[i, j].loglog(rc.f_hz[sel], rc.spectra[key][sel], lw=0.8,
                                color=_colour(widths, c.width_mm),
                                label=f"{_width_label(c.width_mm)}: {idx}, N_MV {rc.N_MV:.2f}")
        for j, d in enumerate(("lateral (W_d)", "vertical (W_b)")):
            ax[i, j].set(xlabel="frequency (Hz)", ylabel="weighted amplitude (m/s$^2$)",
                         title=f"{v:g} km/h, {sensor}, {d}")
            ax[i, j].title.set_fontsize(9)
            ax[i, j].legend(fontsize=7)
    fig.suptitle("Carbody floor spectra weighted as EN 12299 / ISO 2631 weigh them", fontsize=10)
    return _save(fig, path)


def comfort_indices(cases, path: Path) -> Path:
    """Sperling's W_z and W_y and EN 12299's N_MV against speed, a curve per floor sensor and
    defect width, with the scales' bands (Sperling 2.5 'more pronounced but not unpleasant',
    N_MV 1.5 / 2.5 comfortable / medium)."""
    fig, ax = subplots(1, 3, figsize=(13, 4.0), constrained_layout=True)
    groups = _by_width([c for c in cases if c.ride])
    sensors = sorted({r.sensor for c in cases for r in c.ride})
    for k, (field, label, marks) in enumerate((("W_z", "Sperling W_z (vertical)", (2.5, 3.0)),
                                               ("W_y", "Sperling W_y (lateral)", (2.5, 3.0)),
                                               ("N_MV", "EN 12299 N_MV", (1.5, 2.5)))):
        for w, cs in groups.items():
            for s, ls in zip(sensors, ("-o", "--s", ":^")):
                pts = [(c.speed_kmh, getattr(r, field)) for c in cs for r in c.ride if r.sensor == s]
                if pts:
                    ax[k].plot(*zip(*pts), ls, ms=4, color=_colour(groups, w),
                               label=f"{s}, {_width_label(w)}")
        for m in marks:
            ax[k].axhline(m, color="0.6", lw=0.6, ls=":")
        ax[k].set(xlabel="speed (km/h)", ylabel=field, title=label)
    ax[0].legend(fontsize=7)
    fig.suptitle("Ride comfort of the carbody floor against speed", fontsize=10)
    return _save(fig, path)
