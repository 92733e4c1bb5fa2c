"""The verdict as data: what :func:`.criterion.decide` returns, and the sentence that says it.

A :class:`Verdict` holds each side's word (one of :data:`VERDICTS`), the rule that decided
(one of :data:`RULES`) and the evidence it read: every fault line with where it was seen, its
source side(s) and how they were found (bearing order, one side only, own timing, own timing and
ringing, or a copy: coherent / partly coherent / inconclusive), its copy-or-source test
(:mod:`.coherence`) and shares (:mod:`.own`); the VF difference against the range; RMS and SPM
of each side; the lag.  :func:`sentence` renders one side's reason from it; nothing is decided
there.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from .wheel import text as wheel_text

SIDES = ("left", "right")
VERDICTS = ("real fault", "pseudo-fault", "healthy", "faults on both sides", "undecided")
RULES = {
    "no fault line": "no fault line on either side",
    "wheel lines only": "no bearing fault: the lines on the pair stand at whole multiples of the "
                        "shaft's rate, the wheel's (a wheel flat, an out-of-round wheel; on a "
                        "rotor rig its unbalance and misalignment), not at a bearing's orders",
    "each side owns a line": "each side carries a fault line of its own",
    "one side owns the lines": "one side carries the fault line(s) as its own",
    "one side only, spectra alike": "a fault line on one side only, nothing on the other, and "
                                    "the two spectra alike (VF difference below the range): a "
                                    "bearing's own pass line, not shown to be a fault",
    "one side only, not the louder": "a fault line on one side only, nothing on the other, "
                                     "and that side not the louder by RMS and SPM: a bearing's "
                                     "own pass line, not shown to be a fault",
    "both lines faint": "each side carries a line of its own, the weaker no higher over its "
                        "floor than a healthy bearing's own lines can stand, the two alike",
    "second line faint": "each side carries a line of its own, but the weaker side's stands "
                         "no higher over its floor than a healthy bearing's own lines can, and "
                         "the other's clearly higher",
    "ringing": "one fault and its copy; the source's line stands higher in most bands (a "
               "copy is its source through a path that passes some bands and stops others)",
    "lag and ringing disagree": "one fault and its copy, but the impulses' lag and where the "
                                "lines ring name different sources",
    "RMS and SPM": "one fault and its copy; the paper's criterion names the source",
    "lag": "one fault and its copy; the impulses' lag names the source",
    "VF below the range": "one fault and its copy, but the VF difference is below the range",
    "VF above the range": "one fault and its copy, but the VF difference is above the range",
    "indicators disagree": "one fault and its copy, but RMS and SPM disagree",
    "lag contradicts": "one fault and its copy, but the lag contradicts RMS and SPM",
    "no line on the source": "the side the indicators name shows no fault line",
}
_HOW = {"bearing order": "at its bearing's own order",
        "one side only": "seen on this side only",
        "own timing": "its impulse train is not the other side's (own timing)",
        "own timing and ringing": "its train only partly follows the other side's and it rings "
                                  "its own band",
        "coherent": "the same impulse train on both sides (a copy)",
        "partly coherent": "partly the same train on both sides, not its own band",
        "inconclusive": "too weak to show its own timing (read as a copy)"}
_LABEL = {"rms": "RMS", "spm_db": "SPM", "peak": "peak", "kurtosis": "kurtosis", "crest": "crest",
          "SV": "SV"}


@dataclass(frozen=True)
class LineEvidence:
    """One fault line on the pair: ``line`` (BPFO, BPFI, 2BSF); ``bearing`` whose order it is:
    ``"both"`` when both sides' bearings have this line, else the side whose bearing it belongs
    to; ``seen``/``snr_db``: side -> detected there, its fundamental's SNR (dB); ``timing``:
    :class:`.coherence.Timing` when seen on both sides of one bearing type; ``share``:
    :class:`.own.LineShare` likewise."""

    line: str
    bearing: str
    seen: dict
    snr_db: dict
    timing: object | None = None
    share: object | None = None
    best_snr_db: dict = field(default_factory=dict)
    votes: dict = field(default_factory=dict)

    @property
    def key(self) -> str:
        return self.line if self.bearing == "both" else f"{self.line} ({self.bearing} bearing)"

    def to_dict(self) -> dict:
        return {"line": self.line, "key": self.key, "bearing": self.bearing,
                "seen": dict(self.seen),
                "snr_db": {s: (v if math.isfinite(v) else None) for s, v in self.snr_db.items()},
                "best_snr_db": dict(self.best_snr_db), "votes": dict(self.votes),
                "timing": None if self.timing is None else self.timing.to_dict(),
                "share": None if self.share is None else self.share.to_dict()}


@dataclass(frozen=True)
class Verdict:
    """``words``: side -> verdict; ``rule``: the key of :data:`RULES` that decided; ``real``:
    the side named the source (None where none is); ``evidence``: what the rule read (module
    docstring)."""

    words: dict
    rule: str
    real: str | None = None
    evidence: dict = field(default_factory=dict)

    def __getitem__(self, side: str) -> tuple[str, str]:
        """``(word, sentence)`` of ``side``: the old ``{side: (verdict, reason)}`` reading."""
        return self.words[side], sentence(self, side)

    def items(self):
        return ((s, self[s]) for s in SIDES)

    def values(self):
        return (self[s] for s in SIDES)

    def to_dict(self) -> dict:
        return {"words": dict(self.words), "rule": self.rule, "rule_text": RULES[self.rule],
                "real": self.real, "evidence": self.evidence,
                "sentences": {s: sentence(self, s) for s in SIDES}}


def _g(v) -> str:
    return f"{v:.3g}"


def _lines_text(v: Verdict, side: str) -> str:
    """What the lines say of ``side``: each line seen here, and how its source was found."""
    out = []
    for ln in v.evidence.get("lines", []):
        if not ln["seen"][side]:
            continue
        how = _HOW.get(ln["how"], ln["how"])
        t = ln.get("timing")
        if t and t.get("c_min") is not None and ln["how"] != "bearing order":
            how += f", coherent fraction {_g(t['c_min'])}"
        sh = ln.get("share")
        if sh and ln["how"] not in ("bearing order", "one side only"):
            how += (f", shares {_g(sh['share']['left'])} / {_g(sh['share']['right'])} "
                    "(each side's line in the other's band over the other's)")
        src = ln["sources"] or ([v.real] if v.real is not None else [])
        tag = "its own" if side in src else ("the other side's" if src else "source unknown")
        key = ln["line"] if ln["bearing"] == "both" else f"{ln['line']} of the {ln['bearing']} bearing"
        out.append(f"{key}: {tag}, {how}")
    return "; ".join(out)


def sentence(v: Verdict, side: str) -> str:
    """One side's reason, rendered from the verdict's rule and evidence."""
    ev = v.evidence
    parts = [RULES[v.rule]]
    lines = _lines_text(v, side)
    parts.append(f"lines here: {lines}" if lines else "no fault line here")
    wheel = ev.get("wheel", {}).get(side)
    if wheel and (wheel["envelope"] or wheel["spectrum"]):
        parts.append("wheel: " + wheel_text(wheel["envelope"], wheel["spectrum"])
                     + " (the wheel's lines, not a bearing's)")
    g = ev.get("gate")
    if g:
        ms = 1e3 * (g["before_s"] + g["after_s"])
        parts.append(f"the wheel's strikes once a turn blanked first ({ms:.3g} ms of each "
                     f"{1e3 * g['turn_s']:.3g} ms turn, {100 * g['kept']:.0f} % of the record kept; "
                     f"fold ratio {g['ratio']:.3g})")
    st = ev.get("strength_db")
    if st:
        parts.append(f"own lines {st['left']:.3g} / {st['right']:.3g} dB over their floors in their "
                     f"best bands (left / right), a second fault needs {ev['second_db']:.3g}")
    vf = ev.get("vf")
    if vf:
        where = "in" if vf["in_range"] else ("below" if vf["m"] < vf["range"][0] else "above")
        parts.append(f"VF difference {_g(vf['m'])} {vf['unit']} {where} "
                     f"[{_g(vf['range'][0])}, {_g(vf['range'][1])}]")
    ind = ev.get("indicators")
    if ind and v.rule not in ("no fault line", "wheel lines only"):
        parts.append(", ".join(f"{_LABEL.get(c, c)} {_g(d['left'])} / {_g(d['right'])}"
                               for c, d in ind.items()) + " (left / right)")
    lag = ev.get("lag")
    if lag and lag["leading"] is not None:
        how = (f"{lag['n_impulses']} impulses, {100 * lag['agreement']:.0f} % of resamples agree"
               if lag["method"] == "impulses" else f"envelope correlation {lag['peak']:.2f}")
        parts.append(f"{lag['leading']} leads by {lag['lag_s'] * 1e3:.3g} ms ({how})")
    return "; ".join(parts)
