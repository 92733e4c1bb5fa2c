"""Both sides of one wheelset (or both bearings of one shaft): :func:`analyse_pair` ->
:class:`PairResult` with each side's indicators (:mod:`.channel`, each side with its own
bearing), the lines' evidence (where each is seen; the copy-or-source test, :mod:`.coherence`;
the shares, :mod:`.own`), the time lag (:mod:`.lag`), the VF difference and the verdict
(:mod:`.criterion`, :mod:`.verdict`)."""
from __future__ import annotations

import math
import textwrap
from dataclasses import dataclass, field, replace

import numpy as np

from axlebox._params import ParameterError

from ..frequencies import FaultOrders
from . import acquisition
from .channel import LINE_OPTIONS, LINES, ChannelResult, analyse, reguide, welch_segment
from .coherence import line_timing
from .gate import wheel_gate
from .guided import band_scan
from .criterion import ANALYSIS, PAPER, Criterion, decide, vf_difference
from .clock import angle_clock
from .envelope import _signal, check_fs
from .lag import LagResult, impulse_lag, time_lag
from .spectral import fc_vf
from .own import shares as line_shares
from .verdict import ROTORS, SIDES, LineEvidence, Verdict, sentence


@dataclass(frozen=True)
class PairResult:
    """``left``/``right``: the channels' indicators; ``lag``: ``a`` = left; ``vf_diff``:
    ``|VF_L - VF_R|`` (Hz^2); ``m``: what the criterion compared (``vf_diff``, or relative);
    ``verdict``: the :class:`.verdict.Verdict`; ``evidence``: the lines'
    :class:`.verdict.LineEvidence` it read; ``names``: the channels' names in the source;
    ``bearings``: each side's bearing name; ``rotor``: what turns the shaft, ``"wheel"`` (a
    vehicle) or ``"shaft"`` (a machine; :data:`.verdict.ROTORS`); ``orders``: each side's
    FaultOrders; ``spread``: the shaft speed's range over its mean as the record was read;
    ``warnings``: what the acquisition spoiled but left readable (:mod:`.acquisition`: clipping);
    ``sizes``: side -> the defect's :class:`.size.SizeResult` where it was read
    (:func:`.size.side_sizes`)."""

    def _kinds_kw(self) -> dict:
        """What :func:`.criterion.decide` names the faults' kinds from."""
        return {"orders": dict(zip(SIDES, self.orders)) if self.orders else None,
                "spread": self.spread}

    left: ChannelResult
    right: ChannelResult
    lag: LagResult
    vf_diff: float
    m: float
    criterion: Criterion
    verdict: Verdict
    names: tuple[str, str] = ("left", "right")
    evidence: tuple = ()
    bearings: tuple[str, str] = ("", "")
    x_left: np.ndarray = field(default=None, repr=False, compare=False)
    x_right: np.ndarray = field(default=None, repr=False, compare=False)
    gate: object | None = None
    rotor: str = "wheel"
    orders: tuple = ()
    spread: float = 0.0
    warnings: tuple[str, ...] = ()
    sizes: dict = field(default_factory=dict, compare=False)

    @property
    def shares(self) -> dict:
        """line -> :class:`.own.LineShare` of the lines seen on both sides of one bearing type."""
        return {ev.line: ev.share for ev in self.evidence if ev.share is not None}

    def redecide(self, criterion: Criterion) -> Verdict:
        """The verdict under another criterion, from the same indicators and evidence (each
        side's FC and VF taken again from its signal where the criterion's ``vf_band`` differs).
        The thresholds the analysis reads (``Criterion.gate_ratio``, ``shaft_p_fa``) must be the
        analysis' own: another needs :func:`analyse_pair` again."""
        for name in ANALYSIS:
            if getattr(criterion, name) != getattr(self.criterion, name):
                raise ParameterError(f"Criterion.{name} = {getattr(criterion, name)!r} differs from "
                                     f"the analysis' {getattr(self.criterion, name)!r}: it is read "
                                     "by the analysis, not by the verdict; analyse the pair again")
        p = self if criterion.vf_band == self.criterion.vf_band else self.in_vf_band(criterion.vf_band)
        return decide(p.left, p.right, p.lag, criterion, list(p.evidence), gate=p.gate,
                      rotor=p.rotor, **p._kinds_kw())

    def in_vf_band(self, band) -> "PairResult":
        """This pair with both sides' FC, VF and MSF over ``band`` (Hz, None: the whole), from
        the kept signals, and the VF difference and verdict under its criterion with that band:
        what :func:`analyse_pair` gives with ``criterion.vf_band = band``, without the rest of
        the analysis again."""
        crit = replace(self.criterion, vf_band=band)
        left, right = (_in_vf_band(c, x, crit.vf_band, self.criterion)
                       for c, x in ((self.left, self.x_left), (self.right, self.x_right)))
        return replace(self, left=left, right=right, criterion=crit,
                       vf_diff=abs(left.VF - right.VF), m=vf_difference(left.VF, right.VF, crit),
                       verdict=decide(left, right, self.lag, crit, list(self.evidence),
                                      gate=self.gate, rotor=self.rotor, **self._kinds_kw()))

    def to_dict(self) -> dict:
        return {"names": {"left": self.names[0], "right": self.names[1]}, "gate": _gd(self.gate),
                "bearings": {"left": self.bearings[0], "right": self.bearings[1]},
                "left": self.left.to_dict(), "right": self.right.to_dict(),
                "lag": self.lag.to_dict(), "vf_diff_hz2": self.vf_diff,
                "criterion": {**self.criterion.to_dict(), "m": self.m}, "rotor": self.rotor,
                "verdict": self.verdict.to_dict(), "warnings": list(self.warnings),
                "verdicts": {s: {"verdict": self.verdict.words[s], "reason": sentence(self.verdict, s)}
                             for s in SIDES},
                "sizes": {s: r.to_dict() for s, r in self.sizes.items()}}

    def summary(self) -> str:
        """A few lines for a terminal."""
        out = []
        for s, c, n in (("left", self.left, self.names[0]), ("right", self.right, self.names[1])):
            carried = "".join(f", {k} of the other bearing" for k in c.detected_carried)
            out.append(f"{s:5s} {n}: RMS {c.rms:.4g}, kurtosis {c.kurtosis:.3g}, SPM {c.spm_db:.3g} dB "
                       f"({c.spm_class}), FC {c.FC:.4g} Hz, VF {c.VF:.4g} Hz^2, lines: "
                       f"{', '.join(c.detected) or 'none'}{carried} -> {self.verdict.words[s]}")
        lead = {"a": "left", "b": "right"}.get(self.lag.leading, "neither")
        lo, hi = self.criterion.range
        how = (f"{self.lag.n_impulses} impulses, {100 * self.lag.agreement:.0f} % agree, spread "
               f"{self.lag.spread_s * 1e3:.2g} ms; " if self.lag.method == "impulses" else "")
        out.append(f"VF difference {self.vf_diff:.4g} Hz^2 over {self.criterion.band_text} "
                   f"(criterion, {self.criterion.mode}: "
                   f"{self.m:.4g} against [{lo:.4g}, {hi:.4g}]); lag {self.lag.lag_s * 1e3:.3g} ms, "
                   f"{lead} leads ({how}envelope correlation {self.lag.peak:.2f})")
        for ev in self.evidence:
            if ev.timing is None:
                continue
            t, sh = ev.timing, ev.share
            c = "-" if t.c_min is None else f"{t.c_min:.2f}"
            out.append(f"{ev.line} on both sides: timing {t.decision} (least coherent fraction {c}"
                       f" over {len(t.pairs)} band pairs)" + ("" if sh is None else
                       f"; shares (this side's line over the other's, in the other's band) left "
                       f"{sh.share['left']:.3g}, right {sh.share['right']:.3g}"))
        out.append(f"rule: {self.verdict.rule}")
        for s, k in self.verdict.kinds.items():
            if k is not None:
                out.append(f"{s} fault: {k.text()}")
        out += [f"warning: {w}" for w in self.warnings]
        for s, r in self.sizes.items():
            if r.status != "not read":
                out.append(f"{s} defect size ({r.kind}, {r.line}): {r.text()}: {r.reason}")
        return "\n".join(out)

    def plot(self, path=None):
        """Both time signals, both envelope spectra with the fault lines (dashed: expected
        harmonics; dots: harmonics found over the floor) and the verdicts; saved to ``path``
        when given.  Returns the matplotlib figure."""
        from axlebox._figures import figure

        fig = figure(figsize=(12, 9), constrained_layout=True)
        gs = fig.add_gridspec(3, 2, height_ratios=[1, 1, 0.6])
        ax = [[fig.add_subplot(gs[i, j]) for j in range(2)] for i in range(2)]
        colours = {"BPFO": "tab:red", "BPFI": "tab:green", "FTF": "tab:purple", "2BSF": "tab:brown"}
        for j, (s, c, x, n) in enumerate((("left", self.left, self.x_left, self.names[0]),
                                          ("right", self.right, self.x_right, self.names[1]))):
            if x is not None:         # eight fault periods: the impulses, not a solid block
                k = min(x.size, int(8 * c.fs / c.fault_hz.get("BPFO", min(c.fault_hz.values()))))
                ax[0][j].plot(np.arange(k) / c.fs, x[:k], lw=0.5)
            ax[0][j].set(xlabel="time (s)", ylabel="acceleration",
                         title=f"{s}: {n} - {self.verdict.words[s]}")
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
        text = self.summary().splitlines() + [f"{s}: {self.verdict.words[s]}: "
                                              f"{sentence(self.verdict, s)}" for s in SIDES]
        wrapped = "\n".join(textwrap.fill(line, 150, subsequent_indent="    ") for line in text)
        t = axt.text(0.0, 1.0, wrapped, va="top", ha="left", fontsize=7, family="monospace",
                     transform=axt.transAxes)
        t.set_in_layout(False)        # long text must not squeeze the plots
        if path is not None:
            fig.savefig(path, dpi=110)
        return fig


def _in_vf_band(c: ChannelResult, x, band, was: Criterion) -> ChannelResult:
    """Side ``c`` with its FC, VF and MSF over ``band`` instead (its Welch segment as before)."""
    if x is None:
        raise ParameterError(f"Criterion.vf_band = {band!r} differs from the analysis' "
                             f"{was.vf_band!r} and the signal is not kept: analyse the pair again")
    FC, VF, MSF = fc_vf(x, c.fs, c.nperseg, band)
    return replace(c, FC=FC, VF=VF, MSF=MSF, vf_band=band)


def _pair_of(v, name: str) -> tuple:
    """``v`` for both sides, or the pair it is."""
    if isinstance(v, (tuple, list)):
        if len(v) != 2:
            raise ParameterError(f"{name} = {v!r} is not allowed: expected one value or a "
                                 "(left, right) pair")
        return tuple(v)
    return v, v


def _gd(g):
    return None if g is None else g.to_dict()


def analyse_pair(x_left, x_right, fs: float, shaft_hz: float, orders, D,
                 criterion: Criterion = PAPER, band=None, *, names=("left", "right"),
                 max_lag_s: float | None = None, guided: bool = True,
                 bearings: tuple[str, str] = ("", ""), gate: bool = True, rotor: str = "wheel",
                 _wheel: dict | None = None, angle=None, spread: float = 0.0,
                 **channel_kw) -> PairResult:
    """Analyse both channels (same rate ``fs``; ``shaft_hz`` as in :func:`.channel.analyse`;
    fault ``orders`` and bore ``D`` in m, one for both sides or a (left, right) pair: each side
    has its own bearing, whose lines it owns, and the other side's distinct lines are searched
    on it as carried; ``channel_kw`` passed on; ``bearings``: the sides' bearing names, for the
    report), the lines' evidence, their lag and the verdict.

    ``band``: the envelope band of both sides, default each side's own by spectral kurtosis
    (the pseudo-fault side rings other modes).  ``guided``: when one of the criterion's lines
    is detected on one side only, the other side is searched again in the band where that line
    stands highest (:mod:`.guided`, its thresholds corrected for the bands tried): the
    transmitted impulses need not lie in the healthy side's kurtosis band.  A line of one
    bearing type seen on both sides gets the copy-or-source test (:mod:`.coherence`) and its
    shares (:mod:`.own`).  The lag is read impulse by impulse (:func:`.lag.impulse_lag`),
    broadband, else in either side's band; only a record without impulses falls back to the
    envelopes' correlation within ``max_lag_s`` (default half a BPFO period: periodic impulses
    make the lag ambiguous by whole periods).  ``gate``: where a wheel flat strikes both sides
    once a turn (:func:`.gate.wheel_gate`, from the criterion's ``gate_ratio``), the strikes are
    blanked on both channels and everything is read on what is left, the wheel's lines named
    from the record as it came (``PairResult.gate`` holds the windows); lines at whole orders of
    the shaft are named at the criterion's ``shaft_p_fa``.  ``rotor``: what turns the shaft,
    ``"wheel"`` (a vehicle's wheelset, the default) or ``"shaft"`` (a machine's rotor): the
    words the verdict names those lines with.  ``angle``: the shaft's angle (turns) at each
    sample of a record whose speed changes: every envelope is read on the shaft's clock
    (:mod:`.clock`: bands, indicators and impulse onsets in time, the envelopes' lines at their
    orders times ``shaft_hz``, which is then the mean speed).  ``spread``: the shaft speed's
    range over its mean where the record is read at one speed although it changed (0: constant,
    or read on the shaft's clock): the faults' kinds are named knowing it (:mod:`.kind`)."""
    fs = check_fs(fs)
    if not (isinstance(spread, (int, float, np.floating)) and math.isfinite(spread) and spread >= 0):
        raise ParameterError(f"spread = {spread!r} is not allowed: expected the speed's range over "
                             "its mean, a number >= 0")
    if angle is not None:
        with angle_clock(angle, fs):
            return analyse_pair(x_left, x_right, fs, shaft_hz, orders, D, criterion, band, names=names,
                                max_lag_s=max_lag_s, guided=guided, bearings=bearings, gate=gate,
                                rotor=rotor, _wheel=_wheel, spread=spread, **channel_kw)
    if rotor not in ROTORS:
        raise ParameterError(f"rotor = {rotor!r} is not allowed: expected one of " + ", ".join(ROTORS))
    xs = []
    for side, x, n in (("left", x_left, names[0]), ("right", x_right, names[1])):
        xs.append(_signal(x, f"{side} channel {n!r}"))
    if xs[0].size != xs[1].size:
        raise ParameterError(f"channels of {xs[0].size} and {xs[1].size} samples are not allowed: "
                             "expected two channels of the same length")
    warnings = () if _wheel is not None else tuple(   # _wheel: the gated record of a call above
        w for side, x, n in (("left", xs[0], names[0]), ("right", xs[1], names[1]))
        for w in acquisition.check(x, f"{side} channel {n!r}"))
    if not (isinstance(shaft_hz, (int, float, np.floating)) and math.isfinite(shaft_hz) and shaft_hz > 0):
        raise ParameterError(f"shaft_hz = {shaft_hz!r} is not allowed: expected a frequency > 0 Hz")
    fo, bore = _pair_of(orders, "orders"), _pair_of(D, "D")
    for o in fo:
        if not isinstance(o, FaultOrders):
            raise ParameterError(f"orders = {o!r} is not allowed: expected FaultOrders")
    lines = channel_kw.pop("lines", LINES)
    f_line = {n: v for o in fo for n, v in o.at(shaft_hz).items() if n in lines}
    if f_line:
        name = min(f_line, key=f_line.get)
        need = 2.0 / f_line[name]
        T = xs[0].size / fs
        if T < need:
            raise ParameterError(f"record of {T:.4g} s ({xs[0].size} samples at {fs:g} Hz) is too "
                                 f"short for the asked resolution: the {name} line at "
                                 f"{f_line[name]:.4g} Hz needs two periods, {need:.4g} s")
    res = {}
    for i, (side, x, n) in enumerate((("left", xs[0], names[0]), ("right", xs[1], names[1]))):
        try:
            res[side] = analyse(x, fs, shaft_hz, fo[i], bore[i], band, lines=lines,
                                other=fo[1 - i], vf_band=criterion.vf_band,
                                shaft_p_fa=criterion.shaft_p_fa, **channel_kw)
        except ParameterError as err:
            raise ParameterError(f"{side} channel {n!r}: {err}") from None
    g = wheel_gate(xs[0], xs[1], fs, shaft_hz, ratio=criterion.gate_ratio) if gate else None
    if g is not None:               # a flat's strikes: read the bearings between them
        keep = g.mask(xs[0].size, fs)
        p = analyse_pair(xs[0] * keep, xs[1] * keep, fs, shaft_hz, orders, D, criterion, band,
                         names=names, max_lag_s=max_lag_s, guided=guided, bearings=bearings,
                         gate=False, rotor=rotor, lines=lines, keep=keep, spread=spread,
                         _wheel={s: (r.wheel_env, r.wheel_spec) for s, r in res.items()},
                         **channel_kw)
        return replace(p, gate=g, warnings=warnings,
                       verdict=decide(p.left, p.right, p.lag, criterion, list(p.evidence), gate=g,
                                      rotor=rotor, **p._kinds_kw()))
    if _wheel is not None:          # the wheel's lines as the record came, before the blanking
        res = {s: replace(r, wheel_env=_wheel[s][0], wheel_spec=_wheel[s][1]) for s, r in res.items()}
    line_kw = {k: v for k, v in channel_kw.items() if k in LINE_OPTIONS}
    if band is None and guided:
        for name in criterion.lines:
            seen = {s: name in r.lines and r.lines[name].detected for s, r in res.items()}
            if seen["left"] != seen["right"] and name not in res["left"].carried_hz:
                side = "left" if seen["right"] else "right"
                x = xs[0] if side == "left" else xs[1]
                res[side] = reguide(res[side], x, name, **line_kw)
                break
    lag = _lag(xs, fs, res, fo, shaft_hz, max_lag_s)
    evidence = _evidence(xs, res, criterion, line_kw)
    m = vf_difference(res["left"].VF, res["right"].VF, criterion)
    v = decide(res["left"], res["right"], lag, criterion, evidence, rotor=rotor,
               orders=dict(zip(SIDES, fo)), spread=spread)
    return PairResult(left=res["left"], right=res["right"], lag=lag,
                      vf_diff=abs(res["left"].VF - res["right"].VF), m=m, criterion=criterion,
                      verdict=v, names=tuple(names), evidence=tuple(evidence),
                      bearings=tuple(bearings), x_left=xs[0], x_right=xs[1], rotor=rotor,
                      orders=tuple(fo), spread=float(spread), warnings=warnings)


def _lag(xs, fs, res, fo, shaft_hz, max_lag_s) -> LagResult:
    """Impulse by impulse, broadband first: an onset needs bandwidth (a band-pass smears it by
    about one over its width, and weighs each side's modes differently); then in either side's
    band on both.  A side is named only where the impulses agree (:func:`.lag.impulse_lag`).
    Without impulses to read: the best-correlated envelopes, either side's band on both, each
    its own, or none, within ``max_lag_s`` (periodic impulses: the lag is ambiguous by
    periods)."""
    period = 1.0 / (max(o.BPFO for o in fo) * shaft_hz)
    bl, br = res["left"].band, res["right"].band
    lag = None
    for ba in dict.fromkeys([None, bl, br]):
        r = impulse_lag(xs[0], xs[1], fs, period, ba)
        lag = lag or r
        if r.leading != "none":
            lag = r
            break
    if lag.n_impulses == 0:
        max_lag_s = 0.5 * period if max_lag_s is None else max_lag_s
        lag = max((time_lag(xs[0], xs[1], fs, ba, max_lag_s, band_b=bb)
                   for ba, bb in dict.fromkeys([(bl, bl), (br, br), (bl, br), (None, None)])),
                  key=lambda r: r.peak)
    return lag


def band_votes(scan_l, scan_r) -> dict[str, int]:
    """In how many bands of the grid each side's line stands higher (the summed amplitudes of
    its fundamental and harmonics, :mod:`.own`), counting the bands where either side detects
    it: a copy is its source through a path that passes some bands and stops others, so the
    source's line is the higher in most."""
    out = {"left": 0, "right": 0}
    for a, b in zip(scan_l.lines, scan_r.lines):
        if a.detected or b.detected:
            amp = [sum(h[2] for h in r.searched) for r in (a, b)]
            out["left" if amp[0] > amp[1] else "right"] += 1
    return out


def _evidence(xs, res, criterion, line_kw) -> list[LineEvidence]:
    """Each of the criterion's lines on the pair: one entry where both sides' bearings have it
    (with the copy-or-source test and the shares when seen on both sides), else one entry per
    bearing (its own side's line and the other side's carried one).  Wherever a line is seen,
    the band grid is scanned for it (:func:`.guided.band_scan`): its best SNR there, and each
    side's own bands for the copy-or-source test."""
    x = dict(zip(SIDES, xs))
    scans = {}

    def scan(side, key):
        if (side, key) not in scans:
            r = res[side]
            f0 = (r.carried_hz if key.startswith("~") else r.fault_hz)[key.lstrip("~")]
            seg = welch_segment(x[side].size, r.fs, min(r.fault_hz.values()))
            scans[side, key] = band_scan(x[side], r.fs, key, f0, nperseg=seg,
                                         sideband_hz=r.sideband_hz.get(key),
                                         **{k: v for k, v in line_kw.items() if k != "threshold_db"})
        return scans[side, key]

    def best(side, key):
        sc = scan(side, key)
        return float(sc.lines[sc.best].snr_db)
    out = []
    for n in criterion.lines:
        L, R = res["left"], res["right"]
        if n not in L.lines or n not in R.lines:
            continue
        if n in L.carried_hz:                       # the two bearings' lines differ
            for b, o in (("left", "right"), ("right", "left")):
                own, car = res[b].lines[n], res[o].carried.get(n)
                seen = {b: own.detected, o: car is not None and car.detected}
                snr = {b: own.snr_db, o: car.snr_db if car is not None else float("nan")}
                keys = {b: n, o: "~" + n}
                out.append(LineEvidence(n, b, seen, snr,
                                        best_snr_db={s: best(s, keys[s]) for s in SIDES if seen[s]}))
            continue
        seen = {s: res[s].lines[n].detected for s in SIDES}
        snr = {s: res[s].lines[n].snr_db for s in SIDES}
        timing = share = None
        votes = {}
        if all(seen.values()):
            timing = line_timing(xs[0], xs[1], L.fs, scan("left", n), scan("right", n), n,
                                 shaft_hz=L.shaft_hz)
            share = line_shares(xs[0], xs[1], L, R, (n,), **line_kw).get(n)
            votes = band_votes(scan("left", n), scan("right", n))
        out.append(LineEvidence(n, "both", seen, snr, timing, share,
                                best_snr_db={s: best(s, n) for s in SIDES if seen[s]},
                                votes=votes))
    return out
