"""Faults on both sides, or one fault and its copy, in the coupled car: the evidence the verdict
reads (bearing/diagnostics/coherence.py, criterion.py), one row per result file.

    axlebox sweep study_both --out DIR --workers 2
    python3 benchmarks/both_sides.py DIR/*.h5

Per file: each side's defect (from the stored config), RMS, the lines detected, for each line
seen on both sides the copy-or-source test (decision and least coherent fraction of a
significant harmonic) and the bands each side's line stands higher in, the impulse lag, the
relative criterion's verdicts and the rule that decided.
"""
from __future__ import annotations

import sys
from pathlib import Path

from axlebox.pipelines.readers import result_config
from axlebox.bearing.diagnostics.criterion import Criterion
from axlebox.pipelines.diagnose import analyse_file


def defects(path) -> dict:
    out = {"L": "-", "R": "-"}
    for d in result_config(path).defects:
        out[d.side] = f"{d.defect.kind} {1e3 * d.defect.W:g} mm"
    return out


def main(paths):
    print("| file | left / right defect | RMS m/s^2 | lines L / R | timing (c) | bands L / R | lag "
          "| verdicts | rule |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for p in paths:
        d = defects(p)
        _, _, r = analyse_file(p, criterion=Criterion(mode="relative"))
        both = [e for e in r.evidence if e.timing is not None]
        tim = "; ".join(f"{e.line} {e.timing.decision}"
                        + ("" if e.timing.c_min is None else f" ({e.timing.c_min:.2g})")
                        for e in both) or "-"
        votes = "; ".join(f"{e.votes['left']} / {e.votes['right']}" for e in both) or "-"
        lead = {"a": "left", "b": "right"}.get(r.lag.leading, "neither")
        print(f"| {Path(p).stem} | {d['L']} / {d['R']} | {r.left.rms:.2f} / {r.right.rms:.2f} | "
              f"{','.join(r.left.detected) or '-'} / {','.join(r.right.detected) or '-'} | {tim} | "
              f"{votes} | {lead} {r.lag.lag_s * 1e3:.2g} ms ({100 * r.lag.agreement:.0f} %) | "
              f"{r.verdict.words['left']} / {r.verdict.words['right']} | {r.verdict.rule} |")


if __name__ == "__main__":
    main(sys.argv[1:])
