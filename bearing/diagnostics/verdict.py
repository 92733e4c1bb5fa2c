"""The verdict as data: what :func:`.criterion.decide` returns, and the sentence that says it.

A :class:`Verdict` holds each side's word (one of :data:`VERDICTS`), the rule that decided
(one of :data:`RULES`) and the :class:`Evidence` it read, made once by
:func:`.criterion.decide` and frozen: every fault line (:class:`LineReading`) with where it was
seen, its source side(s) and how they were found (bearing order, one side only, own timing, or
a copy: coherent / partly coherent / inconclusive), its copy-or-source test
(:mod:`.coherence`) and shares (:mod:`.own`); the VF difference against the range
(:class:`VFReading`); the indicators of each side; the lag (:class:`LagReading`); the whole
orders of the shaft standing on each side (:class:`ShaftOrders`) and what turns the shaft, a
vehicle's wheel or a machine's rotor (``rotor``: the words the sentence uses for them); the
criterion whose thresholds decided.  :func:`sentence` renders one side's reason from it;
nothing is decided there.  :meth:`Verdict.row` flattens the rule and the evidence into one row
of scalars (the dataset's labels, the report's table, the real records' scores).
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import TYPE_CHECKING

from .wheel import text as wheel_text

if TYPE_CHECKING:       # annotations only: the indicators below need nothing of this module
    from .coherence import Timing
    from .gate import Gate
    from .own import LineShare
    from .thresholds import Criterion

SIDES = ("left", "right")
VERDICTS = ("real fault", "pseudo-fault", "healthy", "faults on both sides", "undecided")
ROTORS = ("wheel", "shaft")     # what turns the shaft: a vehicle's wheel, a machine's rotor
RULES = {
    "no fault line": "no fault line on either side",
    "wheel lines only": "no bearing fault: the lines on the pair stand at whole multiples of the "
                        "shaft's rate, the wheel's (a wheel flat, an out-of-round wheel; on a "
                        "rotor rig its unbalance and misalignment), not at a bearing's orders",
    "shaft lines only": "no bearing fault: the lines on the pair stand at whole multiples of the "
                        "shaft's rate (the rotor's unbalance and misalignment), not at a "
                        "bearing's orders",
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
    "speed not read": "the shaft's speed changes over the record and the record does not tell it "
                      "(bearing/diagnostics/ias.py): no line can be read without it",
}
LINES_ONLY = {"wheel": "wheel lines only", "shaft": "shaft lines only"}    # the rule, by rotor
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
    seen: dict[str, bool]
    snr_db: dict[str, float]
    timing: Timing | None = None
    share: LineShare | None = None
    best_snr_db: dict[str, float] = field(default_factory=dict)
    votes: dict[str, int] = field(default_factory=dict)

    @property
    def key(self) -> str:
        return self.line if self.bearing == "both" else f"{self.line} ({self.bearing} bearing)"

    def to_dict(self, **coherence) -> dict:
        """JSON-ready; ``coherence``: the thresholds its timing is read with
        (:meth:`.coherence.Timing.to_dict`; default the criterion's defaults)."""
        return {"line": self.line, "key": self.key, "bearing": self.bearing,
                "seen": dict(self.seen),
                "snr_db": {s: (v if math.isfinite(v) else None) for s, v in self.snr_db.items()},
                "best_snr_db": dict(self.best_snr_db), "votes": dict(self.votes),
                "timing": None if self.timing is None else self.timing.to_dict(**coherence),
                "share": None if self.share is None else self.share.to_dict()}


@dataclass(frozen=True)
class LineReading:
    """How :func:`.criterion.decide` read one line (its step 2): ``line``, the
    :class:`LineEvidence`; ``sources``: the side(s) whose fault it is (none: not seen, or one
    fault and its copy); ``how``: ``bearing order``, ``one side only``, ``own timing``, or the
    copy's timing decision (``coherent``, ``partly coherent``, ``inconclusive``) under the
    criterion's thresholds; ``c_min``: the least coherent fraction of a significant harmonic
    under them (None: no timing, or no harmonic significant)."""

    line: LineEvidence
    sources: tuple[str, ...]
    how: str
    c_min: float | None = None

    def to_dict(self, **coherence) -> dict:
        return {**self.line.to_dict(**coherence), "sources": list(self.sources), "how": self.how,
                "c_min": self.c_min}

    def text(self) -> str:
        """``"BPFO seen left, right: left, right by own timing"``, one line for a table."""
        seen = ", ".join(s for s in SIDES if self.line.seen[s]) or "nowhere"
        src = ", ".join(self.sources) or "none"
        return f"{self.line.key} seen {seen}: {src} by {self.how}"


@dataclass(frozen=True)
class FaultKind:
    """What a faulty side's fault is (:mod:`.kind`): ``kind``, one of ``named`` or ``"kind
    undecided"`` where ``named`` holds more than one; ``named``: the kinds the lines fit (outer
    ring, inner ring, roller), the best first; ``lines``: each line the side's verdict read, with
    its SNR there (dB), the strongest first; ``why``: what left the kind undecided (``"two lines
    alike"``, ``"a speed that changed"``; empty where decided); ``spread``: the speed's range over
    its mean as the record was read."""

    kind: str
    named: tuple[str, ...]
    lines: tuple[tuple[str, float], ...]
    why: str = ""
    spread: float = 0.0

    @property
    def decided(self) -> bool:
        return len(self.named) == 1

    def text(self) -> str:
        """``"outer ring (BPFO 36.5 dB)"`` or ``"kind undecided: outer ring or roller (a speed
        that changed, 49 % of its mean; 2BSF 20.1 dB)"``."""
        lines = ", ".join(f"{n} {db:.3g} dB" for n, db in self.lines)
        if self.decided:
            return f"{self.kind} ({lines})"
        why = self.why + (f", {100 * self.spread:.0f} % of its mean" if self.why ==
                          "a speed that changed" else "")
        return f"kind undecided: {' or '.join(self.named)} ({why}; {lines})"

    def to_dict(self) -> dict:
        return {"kind": self.kind, "named": list(self.named),
                "lines": [{"line": n, "snr_db": db} for n, db in self.lines], "why": self.why,
                "spread": self.spread}


@dataclass(frozen=True)
class VFReading:
    """The VF difference as the criterion compared it: each side's VF (Hz^2, over the
    criterion's ``vf_band``), ``m`` the difference (Hz^2, or relative), the criterion's
    ``range`` and its ``unit``."""

    left: float
    right: float
    m: float
    range: tuple[float, float]
    unit: str

    @property
    def in_range(self) -> bool:
        return bool(self.range[0] <= self.m <= self.range[1])

    @property
    def where(self) -> str:
        """``"in"``, ``"below"`` or ``"above"`` the range."""
        return "in" if self.in_range else ("below" if self.m < self.range[0] else "above")

    def to_dict(self) -> dict:
        return {"left": self.left, "right": self.right, "m": self.m, "range": list(self.range),
                "unit": self.unit, "in_range": self.in_range}


@dataclass(frozen=True)
class LagReading:
    """The lag as the verdict reads it (:class:`.lag.LagResult`): ``leading``, the side whose
    impulses come first where the lag may be used (read on the impulses, or by an envelope
    correlation of at least the criterion's ``lag_min_peak``), else None; ``lag_s``;
    ``method`` (``impulses`` or ``correlation``); ``n_impulses`` and ``agreement`` (the share
    of the bootstrap agreeing) of a lag read on the impulses; ``peak``: the envelopes'
    correlation at the lag."""

    leading: str | None
    lag_s: float
    method: str
    n_impulses: int
    agreement: float
    peak: float

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass(frozen=True)
class ShaftOrders:
    """The whole orders of the shaft's rate standing on one side (:mod:`.wheel`): in its
    envelope spectrum (a wheel flat's comb) and in its own spectrum (a polygon's line; on a
    machine its rotor's unbalance and misalignment).  False where there are none."""

    envelope: tuple[int, ...] = ()
    spectrum: tuple[int, ...] = ()

    def __bool__(self) -> bool:
        return bool(self.envelope or self.spectrum)

    def text(self) -> str:
        """``"1x, 2x, 3x in the envelope; 20x in the spectrum"``, empty where there are none
        (:func:`.wheel.text`)."""
        return wheel_text(self.envelope, self.spectrum)

    def to_dict(self) -> dict:
        return {"envelope": [int(k) for k in self.envelope], "spectrum": [int(k) for k in self.spectrum]}


@dataclass(frozen=True)
class Evidence:
    """What :func:`.criterion.decide` read, made once there and frozen (module docstring).

    ``lines``: each line's :class:`LineReading`; ``vf``: the :class:`VFReading`;
    ``indicators``: each of the criterion's ``compare`` (RMS, SPM ...) -> side -> value;
    ``larger``: each of them -> the side where it is larger; ``lag``: the :class:`LagReading`
    (None: no lag given); ``orders``: side -> its :class:`ShaftOrders`; ``rotor``: what turns
    the shaft, ``"wheel"`` (a vehicle) or ``"shaft"`` (a machine's rotor; :data:`ROTORS`), the
    words the sentence names the whole orders with; ``criterion``: the
    :class:`.criterion.Criterion` whose thresholds decided; ``gate``: the :class:`.gate.Gate`
    blanked before reading (None: none); ``strength_db``: where each side owns a line, side ->
    its own lines' best SNR over the floor in its best band (dB; step 3), else None;
    ``ringing``: the side where the copies' lines ring higher (step 5, ``source="ringing"``),
    else None."""

    lines: tuple[LineReading, ...]
    vf: VFReading
    indicators: dict[str, dict[str, float]]
    larger: dict[str, str]
    lag: LagReading | None
    orders: dict[str, ShaftOrders]
    rotor: str
    criterion: Criterion
    gate: Gate | None = None
    strength_db: dict[str, float] | None = None
    ringing: str | None = None

    def owned(self, side: str) -> list[LineReading]:
        """The lines whose source is ``side``."""
        return [r for r in self.lines if side in r.sources]

    def shown(self, side: str) -> list[LineReading]:
        """The lines seen on ``side``."""
        return [r for r in self.lines if r.line.seen[side]]

    @property
    def copies(self) -> list[LineEvidence]:
        """The lines seen on both sides and owned by neither: one fault and its copy."""
        return [r.line for r in self.lines if all(r.line.seen.values()) and not r.sources]

    @property
    def shaft_lines(self) -> bool:
        """Whether whole orders of the shaft's rate stand on either side."""
        return any(self.orders.values())

    def to_dict(self) -> dict:
        return {"lines": [r.to_dict(**self.criterion.coherence) for r in self.lines],
                "vf": self.vf.to_dict(),
                "indicators": {c: dict(d) for c, d in self.indicators.items()},
                "larger": dict(self.larger),
                "lag": None if self.lag is None else self.lag.to_dict(),
                "gate": None if self.gate is None else self.gate.to_dict(),
                "shaft_orders": {s: o.to_dict() for s, o in self.orders.items()},
                "rotor": self.rotor, "strength_db": self.strength_db, "ringing": self.ringing}

    def row(self) -> dict:
        """The evidence as one row of scalars (a table's, a dataset's labels): every field
        present whatever the rule (NaN, ``"none"`` or ``""`` where it does not apply), so that
        rows of many verdicts make columns of one type."""
        nan = math.nan
        r = {"lines": "; ".join(x.text() for x in self.lines if any(x.line.seen.values())),
             "vf_left": self.vf.left, "vf_right": self.vf.right, "vf_m": self.vf.m,
             "vf_lo": float(self.vf.range[0]), "vf_hi": float(self.vf.range[1]),
             "vf_where": self.vf.where}
        for c, d in self.indicators.items():
            r.update({f"{c}_left": d["left"], f"{c}_right": d["right"], f"{c}_larger": self.larger[c]})
        lag = self.lag
        r.update(lag_leading="none" if lag is None or lag.leading is None else lag.leading,
                 lag_s=nan if lag is None else lag.lag_s, lag_method="" if lag is None else lag.method)
        st = self.strength_db or {}
        r.update(strength_db_left=st.get("left", nan), strength_db_right=st.get("right", nan),
                 ringing=self.ringing or "none", rotor=self.rotor,
                 orders_left=self.orders["left"].text(), orders_right=self.orders["right"].text(),
                 gate_ratio=nan if self.gate is None else self.gate.ratio,
                 gate_kept=nan if self.gate is None else self.gate.kept)
        return r


@dataclass(frozen=True)
class Verdict:
    """``words``: side -> verdict; ``rule``: the key of :data:`RULES` that decided; ``real``:
    the side named the source (None where none is); ``evidence``: the :class:`Evidence` the
    rule read; ``kinds``: side -> the :class:`FaultKind` of a side called faulty, else None;
    ``note``: what the rule's words leave out and the reader needs first (the speed's change
    that made the verdict undecided).  Each side's reason: :meth:`sentence`."""

    words: dict[str, str]
    rule: str
    real: str | None
    evidence: Evidence
    kinds: dict = field(default_factory=lambda: dict.fromkeys(SIDES))
    note: str = ""

    def sentence(self, side: str) -> str:
        """``side``'s reason (:func:`sentence`)."""
        return sentence(self, side)

    def to_dict(self) -> dict:
        return {"words": dict(self.words), "rule": self.rule, "rule_text": RULES[self.rule],
                "note": self.note, "real": self.real, "evidence": self.evidence.to_dict(),
                "kinds": {s: None if k is None else k.to_dict() for s, k in self.kinds.items()},
                "sentences": {s: sentence(self, s) for s in SIDES}}

    def row(self, prefix: str = "") -> dict:
        """The rule, the real side and the evidence's fields (:meth:`Evidence.row`) as one row of
        scalars, each key after ``prefix``."""
        r = {"rule": self.rule, "real": self.real or "none", **self.evidence.row()}
        for s in SIDES:
            k = self.kinds.get(s)
            r[f"kind_{s}"] = "none" if k is None else k.kind
            r[f"kinds_{s}"] = "" if k is None else " or ".join(k.named)
        return {prefix + k: v for k, v in r.items()}


def _g(v) -> str:
    return f"{v:.3g}"


def _lines_text(v: Verdict, side: str) -> str:
    """What the lines say of ``side``: each line seen here, and how its source was found."""
    out = []
    for r in v.evidence.lines:
        ln = r.line
        if not ln.seen[side]:
            continue
        how = _HOW.get(r.how, r.how)
        if r.c_min is not None and r.how != "bearing order":
            how += f", coherent fraction {_g(r.c_min)}"
        sh = ln.share
        if sh is not None and r.how not in ("bearing order", "one side only"):
            how += (f", shares {_g(sh.share['left'])} / {_g(sh.share['right'])} "
                    "(each side's line in the other's band over the other's)")
        src = list(r.sources) or ([v.real] if v.real is not None else [])
        tag = "its own" if side in src else ("the other side's" if src else "source unknown")
        key = ln.line if ln.bearing == "both" else f"{ln.line} of the {ln.bearing} bearing"
        out.append(f"{key}: {tag}, {how}")
    return "; ".join(out)


def sentence(v: Verdict, side: str) -> str:
    """One side's reason, rendered from the verdict's rule and evidence."""
    ev = v.evidence
    parts = [v.note, RULES[v.rule]] if v.note else [RULES[v.rule]]
    k = v.kinds.get(side)
    if k is not None:
        parts.append(f"fault: {k.text()}")
    lines = _lines_text(v, side)
    parts.append(f"lines here: {lines}" if lines else "no fault line here")
    orders = ev.orders.get(side)
    if orders:
        parts.append(f"{ev.rotor}: {orders.text()} (the {ev.rotor}'s lines, not a bearing's)")
    g = ev.gate
    if g is not None:
        ms = 1e3 * (g.before_s + g.after_s)
        who = "the wheel's strikes once a turn" if ev.rotor == "wheel" else "strikes once a shaft turn"
        parts.append(f"{who} blanked first ({ms:.3g} ms of each {1e3 * g.turn_s:.3g} ms turn, "
                     f"{100 * g.kept:.0f} % of the record kept; fold ratio {g.ratio:.3g})")
    st = ev.strength_db
    if st:
        parts.append(f"own lines {st['left']:.3g} / {st['right']:.3g} dB over their floors in their "
                     f"best bands (left / right), a second fault needs {ev.criterion.second_db:.3g}")
    vf = ev.vf
    parts.append(f"VF difference {_g(vf.m)} {vf.unit} {vf.where} "
                 f"[{_g(vf.range[0])}, {_g(vf.range[1])}]")
    if ev.indicators and v.rule not in ("no fault line", *LINES_ONLY.values()):
        parts.append(", ".join(f"{_LABEL.get(c, c)} {_g(d['left'])} / {_g(d['right'])}"
                               for c, d in ev.indicators.items()) + " (left / right)")
    lag = ev.lag
    if lag is not None and lag.leading is not None:
        how = (f"{lag.n_impulses} impulses, {100 * lag.agreement:.0f} % of resamples agree"
               if lag.method == "impulses" else f"envelope correlation {lag.peak:.2f}")
        parts.append(f"{lag.leading} leads by {lag.lag_s * 1e3:.3g} ms ({how})")
    return "; ".join(parts)
