"""Both sides of one wheelset (or both bearings of one shaft): :func:`analyse_pair` ->
:class:`PairResult` with each side's indicators (:mod:`.channel`), the time lag (:mod:`.lag`),
the VF difference and the criterion's verdicts (:mod:`.criterion`)."""
from __future__ import annotations

import math
import textwrap
from dataclasses import dataclass, field

import numpy as np

from axlebox._params import ParameterError

from ..frequencies import FaultOrders
from .channel import LINE_OPTIONS, ChannelResult, analyse, reguide
from .criterion import PAPER, Criterion, verdict, vf_difference
from .envelope import _signal, check_fs
from .lag import LagResult, impulse_lag, time_lag
from .own import shares as line_shares


@dataclass(frozen=True)
class PairResult:
    """``left``/``right``: the channels' indicators; ``lag``: ``a`` = left; ``vf_diff``:
    ``|VF_L - VF_R|`` (Hz^2); ``m``: what the criterion compared (``vf_diff``, or relative);
    ``verdicts``: side -> (verdict, reason); ``names``: the channels' names in the source."""

    left: ChannelResult
    right: ChannelResult
    lag: LagResult
    vf_diff: float
    m: float
    criterion: Criterion
    verdicts: dict
    names: tuple[str, str] = ("left", "right")
    shares: dict = field(default_factory=dict)
    x_left: np.ndarray = field(default=None, repr=False, compare=False)
    x_right: np.ndarray = field(default=None, repr=False, compare=False)

    def to_dict(self) -> dict:
        return {"names": {"left": self.names[0], "right": self.names[1]},
                "left": self.left.to_dict(), "right": self.right.to_dict(),
                "lag": self.lag.to_dict(), "vf_diff_hz2": self.vf_diff,
                "criterion": {**self.criterion.to_dict(), "m": self.m},
                "verdicts": {s: {"verdict": v, "reason": r} for s, (v, r) in self.verdicts.items()},
                "shares": {n: sh.to_dict() for n, sh in self.shares.items()}}

    def summary(self) -> str:
        """A few lines for a terminal."""
        out = []
        for s, c, n in (("left", self.left, self.names[0]), ("right", self.right, self.names[1])):
            out.append(f"{s:5s} {n}: RMS {c.rms:.4g}, kurtosis {c.kurtosis:.3g}, SPM {c.spm_db:.3g} dB "
                       f"({c.spm_class}), FC {c.FC:.4g} Hz, VF {c.VF:.4g} Hz^2, lines: "
                       f"{', '.join(c.detected) or 'none'} -> {self.verdicts[s][0]}")
        lead = {"a": "left", "b": "right"}.get(self.lag.leading, "neither")
        lo, hi = self.criterion.range
        how = (f"{self.lag.n_impulses} impulses, {100 * self.lag.agreement:.0f} % agree, spread "
               f"{self.lag.spread_s * 1e3:.2g} ms; " if self.lag.method == "impulses" else "")
        out.append(f"VF difference {self.vf_diff:.4g} Hz^2 (criterion, {self.criterion.mode}: "
                   f"{self.m:.4g} against [{lo:.4g}, {hi:.4g}]); lag {self.lag.lag_s * 1e3:.3g} ms, "
                   f"{lead} leads ({how}envelope correlation {self.lag.peak:.2f})")
        for n, sh in self.shares.items():        # bearing/diagnostics/own.py
            out.append(f"{n} share (this side's line over the other's, in the other's band): "
                       f"left {sh.share['left']:.3g}, right {sh.share['right']:.3g} (own from "
                       f"{self.criterion.own_share:g})")
        return "\n".join(out)

    def plot(self, path=None):
        """Both time signals, both envelope spectra with the fault lines (dashed: expected
        harmonics; dots: harmonics found over the floor) and the verdicts; saved to ``path``
        when given.  Returns the matplotlib figure."""
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig = plt.figure(figsize=(12, 9), constrained_layout=True)
        gs = fig.add_gridspec(3, 2, height_ratios=[1, 1, 0.6])
        ax = [[fig.add_subplot(gs[i, j]) for j in range(2)] for i in range(2)]
        colours = {"BPFO": "tab:red", "BPFI": "tab:green", "FTF": "tab:purple", "BSF": "tab:brown"}
        for j, (s, c, x, n) in enumerate((("left", self.left, self.x_left, self.names[0]),
                                          ("right", self.right, self.x_right, self.names[1]))):
            if x is not None:         # eight fault periods: the impulses, not a solid block
                k = min(x.size, int(8 * c.fs / c.fault_hz.get("BPFO", min(c.fault_hz.values()))))
                ax[0][j].plot(np.arange(k) / c.fs, x[:k], lw=0.5)
            ax[0][j].set(xlabel="time (s)", ylabel="acceleration",
                         title=f"{s}: {n} - {self.verdicts[s][0]}")
            f_top = 1.15 * max(len(r.searched) * r.f_expected for r in c.lines.values())
            keep = c.env_f <= f_top
            ax[1][j].plot(c.env_f[keep], c.env_A[keep], lw=0.7, color="k")
            for name, line in c.lines.items():
                col = colours.get(name, "tab:blue")
                for k in range(1, len(line.searched) + 1):
                    ax[1][j].axvline(k * line.f_expected, color=col, lw=0.6, ls="--",
                                     label=f"{name} {line.f_expected:.4g} Hz" if k == 1 else None)
                for _, fk, a, _ in line.harmonics:
                    ax[1][j].plot(fk, a, "o", ms=4, color=col)
            ax[1][j].set(xlabel="frequency (Hz)", ylabel="envelope amplitude",
                         title=f"envelope spectrum, {c.band[0]:.0f}-{c.band[1]:.0f} Hz "
                               f"({c.band_source}); dots: found")
            ax[1][j].legend(fontsize=7, loc="upper right")
        axt = fig.add_subplot(gs[2, :])
        axt.axis("off")
        text = self.summary().splitlines() + [f"{s}: {v}: {r}" for s, (v, r) in self.verdicts.items()]
        wrapped = "\n".join(textwrap.fill(line, 150, subsequent_indent="    ") for line in text)
        t = axt.text(0.0, 1.0, wrapped, va="top", ha="left", fontsize=7, family="monospace",
                     transform=axt.transAxes)
        t.set_in_layout(False)        # long text must not squeeze the plots
        if path is not None:
            fig.savefig(path, dpi=110)
        return fig


def analyse_pair(x_left, x_right, fs: float, shaft_hz: float, orders: FaultOrders, D: float,
                 criterion: Criterion = PAPER, band=None, *, names=("left", "right"),
                 max_lag_s: float | None = None, guided: bool = True, **channel_kw) -> PairResult:
    """Analyse both channels (same rate ``fs``; ``shaft_hz``, fault ``orders``, bore ``D`` in m
    as in :func:`.channel.analyse`, ``channel_kw`` passed on), their lag and the criterion.

    ``band``: the envelope band of both sides, default each side's own by spectral kurtosis
    (the pseudo-fault side rings other modes).  ``guided``: when one of the criterion's lines
    is detected on one side only, the other side is searched again in the band where that line
    stands highest (:mod:`.guided`, its thresholds corrected for the bands tried): the
    transmitted impulses need not lie in the healthy side's kurtosis band.  The lag is read
    impulse by impulse (:func:`.lag.impulse_lag`), broadband, else in either side's band; only
    a record without impulses falls back to the envelopes' correlation within ``max_lag_s``
    (default half a BPFO period: periodic impulses make the lag ambiguous by whole periods)."""
    fs = check_fs(fs)
    xs = []
    for side, x, n in (("left", x_left, names[0]), ("right", x_right, names[1])):
        xs.append(_signal(x, f"{side} channel {n!r}"))
    if xs[0].size != xs[1].size:
        raise ParameterError(f"channels of {xs[0].size} and {xs[1].size} samples are not allowed: "
                             "expected two channels of the same length")
    if not (isinstance(shaft_hz, (int, float, np.floating)) and math.isfinite(shaft_hz) and shaft_hz > 0):
        raise ParameterError(f"shaft_hz = {shaft_hz!r} is not allowed: expected a frequency > 0 Hz")
    lines = channel_kw.get("lines", ("BPFO", "BPFI", "FTF"))
    f_line = {n: v for n, v in orders.at(shaft_hz).items() if n in lines}
    if f_line:
        name = min(f_line, key=f_line.get)
        need = 2.0 / f_line[name]
        T = xs[0].size / fs
        if T < need:
            raise ParameterError(f"record of {T:.4g} s ({xs[0].size} samples at {fs:g} Hz) is too "
                                 f"short for the asked resolution: the {name} line at "
                                 f"{f_line[name]:.4g} Hz needs two periods, {need:.4g} s")
    res = {}
    for side, x, n in (("left", xs[0], names[0]), ("right", xs[1], names[1])):
        try:
            res[side] = analyse(x, fs, shaft_hz, orders, D, band, **channel_kw)
        except ParameterError as err:
            raise ParameterError(f"{side} channel {n!r}: {err}") from None
    line_kw = {k: v for k, v in channel_kw.items() if k in LINE_OPTIONS}
    if band is None and guided:
        for name in criterion.lines:
            seen = {s: name in r.lines and r.lines[name].detected for s, r in res.items()}
            if seen["left"] != seen["right"]:
                side = "left" if seen["right"] else "right"
                x = xs[0] if side == "left" else xs[1]
                res[side] = reguide(res[side], x, name, **line_kw)
                break
    period = 1.0 / (orders.BPFO * shaft_hz)
    bl, br = res["left"].band, res["right"].band
    # impulse by impulse, broadband first: an onset needs bandwidth (a band-pass smears it by
    # about one over its width, and weighs each side's modes differently); then in either
    # side's band on both.  A side is named only where the impulses agree (lag.impulse_lag).
    lag = None
    for ba in dict.fromkeys([None, bl, br]):
        r = impulse_lag(xs[0], xs[1], fs, period, ba)
        lag = lag or r
        if r.leading != "none":
            lag = r
            break
    if lag.n_impulses == 0:
        # no impulses to read: the best-correlated envelopes, either side's band on both, each
        # its own, or none, within max_lag_s (periodic impulses: the lag is ambiguous by periods)
        max_lag_s = 0.5 * period if max_lag_s is None else max_lag_s
        lag = max((time_lag(xs[0], xs[1], fs, ba, max_lag_s, band_b=bb)
                   for ba, bb in dict.fromkeys([(bl, bl), (br, br), (bl, br), (None, None)])),
                  key=lambda r: r.peak)
    m = vf_difference(res["left"].VF, res["right"].VF, criterion)
    sh = line_shares(xs[0], xs[1], res["left"], res["right"], criterion.lines, **line_kw)
    v = verdict(res["left"], res["right"], lag, criterion, sh)
    return PairResult(left=res["left"], right=res["right"], lag=lag,
                      vf_diff=abs(res["left"].VF - res["right"].VF), m=m, criterion=criterion,
                      verdicts=v, names=tuple(names), shares=sh, x_left=xs[0], x_right=xs[1])
