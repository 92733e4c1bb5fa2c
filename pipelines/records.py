"""Diagnose a manifest of labelled two-channel recordings and score the verdicts against their
ground truth: one confusion table per fault kind, for the faulty end and for the healthy end.

The manifest is a CSV with one record a row: ``file`` (beside the manifest), ``faulty_end`` and
``healthy_end`` (the ends' names, e.g. DE and FE), ``fault`` (its kind: outer race, inner race,
ball ...), ``rpm`` (the shaft speed), ``fs_hz``, and a channel column per end,
``<end>_channel`` with the end spelled as in :data:`END_COLUMNS` (``drive_end_channel``,
``fan_end_channel``).  Each end's bearing is given by name (:mod:`axlebox.bearing.catalogue`),
or by an optional column ``<end>_bearing``.  The first end of :data:`END_COLUMNS` is the left
channel.

Every record is read and diagnosed as ``axlebox diagnose`` does (:func:`.diagnose.analyse_file`,
each end with its own bearing); the verdict words of each end are counted under its role
(faulty or healthy) and the record's fault kind.
"""
from __future__ import annotations

import csv
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

from axlebox._params import ParameterError
from axlebox.bearing.diagnostics.verdict import VERDICTS

from .diagnose import analyse_file

END_COLUMNS = {"DE": "drive_end", "FE": "fan_end"}
WORDS = ("real fault", "faults on both sides", "pseudo-fault", "healthy", "undecided")
REQUIRED = ("file", "faulty_end", "healthy_end", "fault", "rpm", "fs_hz")


@dataclass
class Scored:
    """One record: its manifest row, each end's verdict word, the rule that decided, the end it
    named real (None: neither), the evidence's fields (:meth:`.verdict.Verdict.row`: the VF
    difference, the lag, the lines and how each was read, ...; its sides ``left`` and
    ``right`` are the channels, the first end of :data:`END_COLUMNS` the left) and each end's
    sentence."""

    row: dict
    words: dict
    rule: str
    real: str | None = None
    evidence: dict = field(default_factory=dict)
    sentences: dict = field(default_factory=dict)
    kind: str = "not named"         # the faulty end's fault kind as named (or "kind undecided: ...")
    sizes: dict = field(default_factory=dict)       # end -> its defect size (size.SizeResult)

    def to_dict(self) -> dict:
        """JSON-ready: the manifest row, the words, the rule, the real end, the evidence, the
        sentences and each end's defect size."""
        return {"row": dict(self.row), "words": dict(self.words), "rule": self.rule,
                "real": self.real, "evidence": dict(self.evidence),
                "sentences": dict(self.sentences), "kind": self.kind,
                "sizes": {e: r.to_dict() for e, r in self.sizes.items()}}

    @property
    def faulty(self) -> str:
        return self.words[self.row["faulty_end"]]

    @property
    def healthy(self) -> str:
        return self.words[self.row["healthy_end"]]


@dataclass
class Score:
    """All records' verdicts and the confusion tables: ``tables[role][fault][word]`` counts."""

    records: list[Scored]

    @property
    def tables(self) -> dict:
        out = {"faulty": {}, "healthy": {}}
        for r in self.records:
            for role, word in (("faulty", r.faulty), ("healthy", r.healthy)):
                out[role].setdefault(r.row["fault"], Counter())[word] += 1
        return out

    @property
    def kinds(self) -> dict:
        """fault (the manifest's) -> Counter of the kind named at the faulty end."""
        out = {}
        for r in self.records:
            out.setdefault(r.row["fault"], Counter())[r.kind] += 1
        return out

    def count(self, role: str, words, fault: str | None = None) -> int:
        """How many ends of ``role`` (of ``fault``, default every kind) got one of ``words``."""
        words = (words,) if isinstance(words, str) else tuple(words)
        return sum(c[w] for f, c in self.tables[role].items() if fault in (None, f) for w in words)

    def markdown(self) -> str:
        """Both confusion tables and one line a record, as Markdown."""
        out = []
        for role in ("faulty", "healthy"):
            out += [f"{role} end | " + " | ".join(WORDS) + " | records",
                    "--- | " + " | ".join("---" for _ in WORDS) + " | ---"]
            for fault, c in sorted(self.tables[role].items()):
                out.append(f"{fault} | " + " | ".join(str(c[w]) for w in WORDS)
                           + f" | {sum(c.values())}")
            out.append("")
        named = sorted({k for c in self.kinds.values() for k in c})
        out += ["fault | " + " | ".join(f"named {k}" for k in named) + " | records",
                "--- | " + " | ".join("---" for _ in named) + " | ---"]
        for fault, c in sorted(self.kinds.items()):
            out.append(f"{fault} | " + " | ".join(str(c[k]) for k in named) + f" | {sum(c.values())}")
        out += ["", "| file | faulty end | fault | faulty end called | its kind | healthy end called "
                "| rule | faulty end's size |", "| --- | --- | --- | --- | --- | --- | --- | --- |"]
        for r in self.records:
            sz = r.sizes.get(r.row["faulty_end"])
            out.append(f"| {r.row['file']} | {r.row['faulty_end']} | {r.row['fault']} | {r.faulty} "
                       f"| {r.kind} | {r.healthy} | {r.rule} | {sz.text() if sz is not None else '-'} |")
        return "\n".join(out)


def read_manifest(path) -> list[dict]:
    """The manifest's rows, every required column present (a ParameterError names the first
    missing one)."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"manifest {str(path)!r} does not exist")
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    if not rows:
        raise ParameterError(f"manifest {str(path)!r} has no records")
    for i, r in enumerate(rows, 2):
        for col in REQUIRED + tuple(f"{c}_channel" for c in END_COLUMNS.values()):
            if not (r.get(col) or "").strip():
                raise ParameterError(f"manifest {path.name} line {i}: column {col!r} is missing or "
                                     "empty")
        for end in ("faulty_end", "healthy_end"):
            if r[end] not in END_COLUMNS:
                raise ParameterError(f"manifest {path.name} line {i}: {end} = {r[end]!r} is not "
                                     f"allowed: expected one of {', '.join(END_COLUMNS)}")
    return rows


def score(manifest, bearings: dict, *, scale: float = 1.0, criterion=None,
          log=print) -> Score:
    """Diagnose every record of ``manifest`` (each end's bearing from ``bearings``, end ->
    catalogue name, unless the row names it; ``scale`` multiplies the samples, e.g. 9.80665 for
    records in g) and count the verdicts."""
    from axlebox.bearing.diagnostics.criterion import Criterion
    criterion = Criterion(mode="relative") if criterion is None else criterion
    path = Path(manifest)
    ends = list(END_COLUMNS)            # the first end is the left channel
    out = []
    for row in read_manifest(path):
        bear = {e: (row.get(f"{END_COLUMNS[e]}_bearing") or bearings[e]).strip() for e in ends}
        _, _, pair = analyse_file(
            path.parent / row["file"], left=row[f"{END_COLUMNS[ends[0]]}_channel"],
            right=row[f"{END_COLUMNS[ends[1]]}_channel"], fs=float(row["fs_hz"]),
            rpm=float(row["rpm"]), scale=scale, criterion=criterion,
            bearing_left=bear[ends[0]], bearing_right=bear[ends[1]])
        v = pair.verdict
        end = {"left": ends[0], "right": ends[1]}
        words = {end[s]: v.words[s] for s in end}
        assert all(w in VERDICTS for w in words.values())
        side = {e: s for s, e in end.items()}[row["faulty_end"]]
        fk = v.kinds[side]
        out.append(Scored(row, words, v.rule, end.get(v.real), v.row(),
                          {end[s]: v.sentence(s) for s in end},
                          kind="not named" if fk is None else fk.kind if fk.decided else
                          "kind undecided: " + " or ".join(fk.named),
                          sizes={end[s]: r for s, r in pair.sizes.items()}))
        log(f"{row['file']}: {row['fault']} at {row['faulty_end']}: {ends[0]} {words[ends[0]]}, "
            f"{ends[1]} {words[ends[1]]} ({v.rule})")
    return Score(out)
