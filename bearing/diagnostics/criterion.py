"""The paper's criterion for telling a real fault from a coaxial pseudo-fault on two channels.

Paper, section "Difference analyses of vibration characteristics ...", Fig. 14 and conclusions
(2)-(3): if the difference of the frequency variances (VF, Eq. 18) of the two axle-box signals of
a wheelset lies in 0.8e4-7.49e4 (Hz^2), a pseudo-fault is present on one side; the side with the
larger RMS and SPM (Eq. 17) is the real fault, the other the pseudo-fault.  Below that range the
two spectra are alike (the paper's healthy wheelset, Fig. 14a); above it lies outside what the
criterion was found on.

:func:`verdict` applies it in this order (each side gets "real fault", "pseudo-fault",
"healthy", "faults on both sides" or "undecided", with the reason in words):

1. fault evidence (ours): a side shows a fault when one of ``Criterion.lines`` (BPFO, the paper's
   outer-ring faults, and BPFI, inner-ring faults) is detected in its envelope spectrum
   (:mod:`.faultlines`: the fundamental and two harmonics over the noise floor).  No line on
   either side -> both healthy.  The paper's VF difference alone cannot say this: gearbox load
   transfer alone gives a VF difference (Fig. 14a), and in relative mode the VF levels no longer
   tell defects from none.
1b. faults on both sides (ours, beyond the paper): when each side *owns* a fault line
   (:mod:`.own`: in the band where the other side's line stands best, this side's line is at
   least ``Criterion.own_share`` of the other's; a transmitted copy is far weaker there), both
   sides are "faults on both sides", whatever the VF difference and the lag say (two faults'
   impulse trains coincide or interleave, so neither a lead nor a pseudo-fault pattern is to be
   expected).  Only with the shares given (:func:`.pair.analyse_pair` computes them).
2. the VF difference ``m`` against the range (paper): below -> both undecided (lines are seen,
   yet no pseudo-fault pattern: a fault not transmitted, or faults on both sides of unlike size,
   are outside the paper's criterion); above -> both undecided.
3. in the range (paper): the side where every indicator of ``Criterion.compare`` (RMS and SPM)
   is larger is the real fault, the other the pseudo-fault; if they disagree -> undecided.  If
   the larger side shows no fault line while the other does -> undecided.
4. the lag (the paper, Fig. 13 and conclusion 2: the healthy side lags by 1.1-4.2 ms, so the
   real side leads), by ``Criterion.lag`` (ours: the paper states the lag as a finding, not as
   part of its criterion):

   * ``"decide"`` (default): a lag read on the impulses (:func:`.lag.impulse_lag`, which names
     a side only with at least five impulses and 90 % of its bootstrap resamples agreeing)
     names the real side, on the side that shows fault lines, whatever RMS and SPM say; where
     they point the other way the reason says so.  The paper's conclusion (1) is that
     amplitude indicators alone cannot tell the two apart; the lag is the causal evidence:
     the impulses start at the defect.  A lag read by envelope correlation (records without
     separable impulses) only vetoes, as below;
   * ``"veto"``: a leading side that contradicts step 3 makes both undecided rather than a
     wrong call, and where RMS and SPM disagree the leading side is named real;
   * ``"off"`` (``--lag off``, ``--no-lag``): the paper's RMS and SPM alone; the lag is only
     quoted.

   A lag by correlation is used only when its correlation reaches ``lag_min_peak``.  And, in
   the reason, which side is more dispersed (the paper's healthy side has the larger VF).

Carrying the range to another machine.  VF is in Hz^2, so the paper's range belongs to the metro
car's frequencies: a machine whose resonances sit k times higher has VF (and VF differences) k^2
times larger.  Two settings:

* ``mode="absolute"``: ``m = |VF_L - VF_R|`` against ``vf_range`` (Hz^2; default the paper's);
  choose the range for the machine, e.g. the paper's scaled by the ratio of the VF of a flat
  spectrum over the band the machine's signals fill to ``VF_METRO`` below (the CWRU rig's
  accelerometers fill 0-6 kHz: 3e6 / 5.72e4 = 52, tests/test_diagnose_cli.py).
* ``mode="relative"``: ``m = |VF_L - VF_R| / max(VF_L, VF_R) = 1 - VF_min / VF_max``, in
  [0, 1): the share of the more dispersed side's variance the other lacks.  It is unchanged when
  all frequencies scale together and does not depend on the sampling rate once the band holds
  the signal (dividing by (fs/2)^2 instead would tie the threshold to the acquisition, not the
  machine: on the CWRU rig ``ΔVF / (fs/2)^2 = 0.023``, eight times the top of the paper's range
  mapped that way, 3.2e-4-3.0e-3, while its relative difference, 0.82, sits inside the range
  below).
  Mapping the paper's range: the paper gives the VF differences, not the levels; its healthy
  side's spectrum lies in 0-200 Hz and 300-800 Hz (Fig. 12), whose VF, for a flat PSD over those
  bands, is ``VF_METRO = 5.72e4 Hz^2``.  So the lower bound is ``0.8e4 / 5.72e4 = 0.14``.  The
  upper bound 7.49e4 / 5.72e4 = 1.31 exceeds what ``m`` can reach (``ΔVF <= VF_max``): it was the
  largest difference simulated, not a limit, so the relative upper bound is 1.
"""
from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from axlebox._params import ParameterError

from .own import owned

VF_RANGE_PAPER = (0.8e4, 7.49e4)        # Hz^2, paper Fig. 14 and conclusion (3)
VF_METRO = 5.72e4                       # Hz^2, VF of a flat PSD on 0-200 and 300-800 Hz (Fig. 12)
REL_RANGE_DEFAULT = (round(VF_RANGE_PAPER[0] / VF_METRO, 2), 1.0)
MODES = ("absolute", "relative")
LAG_POLICIES = ("decide", "veto", "off")
COMPARABLE = ("rms", "spm_db", "peak", "kurtosis", "crest", "SV")
VERDICTS = ("real fault", "pseudo-fault", "healthy", "faults on both sides", "undecided")
SIDES = ("left", "right")
_LABEL = {"rms": "RMS", "spm_db": "SPM", "peak": "peak", "kurtosis": "kurtosis", "crest": "crest",
          "SV": "SV"}


@dataclass(frozen=True)
class Criterion:
    """Thresholds of the criterion (module docstring).  ``vf_range``: Hz^2, used in absolute
    mode; ``rel_range``: dimensionless, used in relative mode; ``compare``: ChannelResult fields
    that must all be larger on the real side; ``lines``: fault lines whose detection counts as a
    fault; ``lag``: how the lag between the sides enters (one of ``LAG_POLICIES``, module
    docstring, step 4); ``lag_min_peak``: envelope correlation needed to use a lag read by
    correlation (one read on the impulses carries its own test); ``own_share``: the share of the
    other side's line, in the other side's band, above which a side's line is its own (step 1b,
    :mod:`.own`)."""

    mode: str = "absolute"
    vf_range: tuple[float, float] = VF_RANGE_PAPER
    rel_range: tuple[float, float] = REL_RANGE_DEFAULT
    compare: tuple[str, ...] = ("rms", "spm_db")
    lines: tuple[str, ...] = ("BPFO", "BPFI")
    lag: str = "decide"
    lag_min_peak: float = 0.3
    own_share: float = 0.25

    def __post_init__(self):
        if self.mode not in MODES:
            raise ParameterError(f"Criterion.mode = {self.mode!r} is not allowed: expected one of "
                                 + ", ".join(MODES))
        for name in ("vf_range", "rel_range"):
            r = getattr(self, name)
            ok = len(r) == 2 and all(np.isfinite(v) for v in r) and 0 <= r[0] < r[1]
            if not ok:
                raise ParameterError(f"Criterion.{name} = {r!r} is not allowed: expected (lo, hi) "
                                     "with 0 <= lo < hi")
        bad = [c for c in self.compare if c not in COMPARABLE]
        if bad or not self.compare:
            raise ParameterError(f"Criterion.compare = {self.compare!r} is not allowed: expected "
                                 "names among " + ", ".join(COMPARABLE))
        if not self.lines:
            raise ParameterError("Criterion.lines = () is not allowed: expected at least one line "
                                 "name (e.g. BPFO)")
        if self.lag not in LAG_POLICIES:
            raise ParameterError(f"Criterion.lag = {self.lag!r} is not allowed: expected one of "
                                 + ", ".join(LAG_POLICIES))
        if not 0 <= self.lag_min_peak <= 1:
            raise ParameterError(f"Criterion.lag_min_peak = {self.lag_min_peak!r} is not allowed: "
                                 "expected a correlation in [0, 1]")
        if not (np.isfinite(self.own_share) and self.own_share > 0):
            raise ParameterError(f"Criterion.own_share = {self.own_share!r} is not allowed: "
                                 "expected a ratio > 0")

    @property
    def range(self) -> tuple[float, float]:
        return self.vf_range if self.mode == "absolute" else self.rel_range

    @property
    def unit(self) -> str:
        return "Hz^2" if self.mode == "absolute" else "(relative)"

    def to_dict(self) -> dict:
        d = asdict(self)
        d["range"] = list(self.range)
        return d


PAPER = Criterion()                     # the paper's absolute range, RMS and SPM compared


def vf_difference(vf_left: float, vf_right: float, criterion: Criterion = PAPER) -> float:
    """The criterion's ``m``: ``|VF_L - VF_R|`` (Hz^2) or, in relative mode, that over the larger VF."""
    d = abs(vf_left - vf_right)
    if criterion.mode == "absolute":
        return float(d)
    top = max(vf_left, vf_right)
    return float(d / top) if top > 0 else 0.0


def _fmt(v: float) -> str:
    return f"{v:.3g}"


def _both_sides(left, right, shares: dict, criterion: Criterion) -> str | None:
    """The reason for "faults on both sides" when each side owns a line (:mod:`.own`), else None."""
    own = owned(left, right, shares, criterion.lines, criterion.own_share)
    if not (own["left"] and own["right"]):
        return None
    how = []
    for s in SIDES:
        for n in own[s]:
            if n in shares:
                sh = shares[n]
                o = "right" if s == "left" else "left"
                b = getattr(sh, f"band_{o}")
                how.append(f"{s}'s {n} is {sh.share[s]:.2g} of {o}'s in {o}'s band "
                           f"{b[0]:.0f}-{b[1]:.0f} Hz")
            else:
                how.append(f"{s}'s {n} is found on {s} only")
    return (f"each side carries its own fault line ({'; '.join(how)}; a copy carried across "
            f"would be under {criterion.own_share:g} of its source there)")


def verdict(left, right, lag=None, criterion: Criterion = PAPER,
            shares: dict | None = None) -> dict[str, tuple[str, str]]:
    """``{"left": (verdict, reason), "right": (...)}`` from two :class:`.channel.ChannelResult`
    (``FC``/``VF``, ``rms``, ``spm_db``, ``lines``), an optional :class:`.lag.LagResult`
    whose channel ``a`` is ``left`` and the fault lines' shares (:func:`.own.shares`; without
    them step 1b is left out)."""
    ch = {"left": left, "right": right}
    other = {"left": "right", "right": "left"}
    m = vf_difference(left.VF, right.VF, criterion)
    lo, hi = criterion.range
    m_txt = f"VF difference {_fmt(m)} {criterion.unit}"
    rng_txt = f"[{_fmt(lo)}, {_fmt(hi)}]"

    def both(v, why):
        return {s: (v, why) for s in SIDES}
    seen = {s: [n for n in criterion.lines if n in ch[s].lines and ch[s].lines[n].detected]
            for s in SIDES}
    names = "/".join(criterion.lines)
    if not seen["left"] and not seen["right"]:
        return both("healthy", f"no {names} line (fundamental and harmonics over the noise floor) "
                               f"on either side; {m_txt}")
    where = " and ".join(f"{s} ({', '.join(seen[s])})" for s in SIDES if seen[s])
    both_txt = None if shares is None else _both_sides(left, right, shares, criterion)
    if both_txt is not None:
        return both("faults on both sides", f"fault lines on {where}: {both_txt}; {m_txt}")
    if m < lo:
        return both("undecided", f"fault lines on {where}, but the {m_txt} is below the range "
                                 f"{rng_txt}: no pseudo-fault pattern (a fault not transmitted, or "
                                 "faults on both sides of unlike size, are outside the paper's "
                                 "criterion)")
    if m > hi:
        return both("undecided", f"{m_txt} is above the range {rng_txt} the criterion was "
                                 f"found on; fault lines on {where}")
    larger = {c: ("left" if getattr(left, c) > getattr(right, c) else "right")
              for c in criterion.compare}
    vals = ", ".join(f"{_LABEL[c]} {_fmt(getattr(left, c))} / {_fmt(getattr(right, c))}"
                     for c in criterion.compare)
    lead, sure = None, False    # the side the lag names, where it is sure enough to quote
    if lag is not None and lag.leading in ("a", "b"):
        sure = getattr(lag, "method", "correlation") == "impulses"
        if sure or lag.peak >= criterion.lag_min_peak:
            lead = "left" if lag.leading == "a" else "right"
            how = (f"{lag.n_impulses} impulses, {100 * lag.agreement:.0f} % of resamples agree"
                   if sure else f"envelope correlation {lag.peak:.2f}")
            lag_txt = f"{lead} leads by {lag.lag_s * 1e3:.3g} ms ({how})"
    split = len(set(larger.values())) > 1
    by_indicators = None if split else next(iter(larger.values()))
    split_txt = "; ".join(f"{_LABEL[c]} larger on {s}" for c, s in larger.items())
    notes = []
    if lead is not None and criterion.lag != "off" and seen[lead] and (
            (sure and criterion.lag == "decide") or split):
        real = lead             # the paper's conclusion (2): the real side's impulses come first
        if split:
            notes.append(f"the indicators disagree ({split_txt}); {lag_txt} names the real side")
        elif by_indicators != real:
            notes.append(f"{lag_txt} names the real side; "
                         f"{' and '.join(_LABEL[c] for c in criterion.compare)} point to the other "
                         "(the transmitted response can be the larger: the paper's conclusion 1)")
        else:
            notes.append(f"{lag_txt}; agrees")
    elif split:
        return both("undecided", f"{m_txt} in {rng_txt} (a pseudo-fault is present), but the "
                                 f"indicators disagree: {split_txt} (left / right: {vals})")
    else:
        real = by_indicators
        if lead is not None:
            agree = lead == real
            notes.append(f"{lag_txt}; {'agrees' if agree else 'contradicts'}")
            if not agree and criterion.lag != "off":
                return both("undecided", f"{m_txt} in {rng_txt} and {vals} (left / right) point "
                                         f"to {real}, but {notes[-1]}")
    pseudo = other[real]
    if not seen[real]:
        return both("undecided", f"{m_txt} in {rng_txt} and {vals} (left / right) point to {real}, "
                                 f"but only {pseudo} shows fault lines")
    wider = "left" if left.VF > right.VF else "right"
    notes.append(f"{wider} more dispersed (VF {_fmt(left.VF)} / {_fmt(right.VF)} Hz^2; the paper's "
                 f"pseudo-fault side is: {'agrees' if wider == pseudo else 'contradicts'})")
    common = f"{m_txt} in {rng_txt}: a pseudo-fault is present (paper, conclusion 3); " \
             f"{vals} (left / right); " + "; ".join(notes)
    own = {real: f"{', '.join(seen[real])} detected",
           pseudo: f"{', '.join(seen[pseudo])} detected here too" if seen[pseudo]
           else "no fault line found here"}
    return {real: ("real fault", f"{own[real]}; {common}"),
            pseudo: ("pseudo-fault", f"{own[pseudo]}; {common}")}
