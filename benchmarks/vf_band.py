"""The paper's VF criterion by band: a study's cases diagnosed once, then FC and VF taken again
over each band (``PairResult.in_vf_band``, the rest of the diagnosis kept).

    python3 benchmarks/vf_band.py SWEEP_DIR [SWEEP_DIR ...] [--markdown OUT.md]

For each folder of vehicle results (``axlebox sweep study``, ``study_fast``, ...) and each band
(the paper's 0-1 kHz, criterion.py's reasoning; 0-0.8, 0-1.5, 0-2.5 kHz and the whole band as
its sensitivity), what pipelines/conclusions.py counts for the paper's conclusion (3) with the
paper's absolute range: both sides named right (defect side "real fault", healthy side
"pseudo-fault") in the cases the paper has a pseudo-fault in, with the lag deciding (the
default) and with RMS and SPM alone (``lag="off"``); no fault called in the no-defect cases;
and, per defect width, in how many cases the healthy side's VF is above the defect side's
(the paper's Fig. 14 statement, at 3 and 5 mm).  Then each case's VF pair and difference.
"""
from __future__ import annotations

import argparse
import dataclasses
import time
from pathlib import Path

from axlebox.bearing.diagnostics.criterion import VF_BAND_PAPER, VF_RANGE_PAPER, Criterion
from axlebox.pipelines.conclusions import (calls_no_fault, in_band, named_right,
                                          paper_expects_pseudo, sides)
from axlebox.pipelines.report import case_parameters, diagnosed_case, find_results

BANDS = {"0-0.8 kHz": (0.0, 800.0), "0-1 kHz (the paper's)": VF_BAND_PAPER,
         "0-1.5 kHz": (0.0, 1500.0), "0-2.5 kHz": (0.0, 2500.0), "whole band": None}


def cases_of(folder) -> list:
    """The folder's vehicle results diagnosed as ``axlebox report`` does (whole band)."""
    out = []
    for path in find_results(folder):
        speed, width, side = case_parameters(path)
        c = diagnosed_case(path, speed, width, side, lambda *_: None)
        if c.pair is not None:
            out.append(c)
    return sorted(out, key=lambda c: (c.width_mm, c.speed_kmh))


def counts(cases, band) -> dict:
    """conclusions.py's counts for claim (3) and (2c) with FC and VF over ``band``."""
    crit = Criterion(source="paper", vf_band=band)
    alone = dataclasses.replace(crit, lag="off")
    banded = [in_band(c, band) for c in cases]
    faulty = [c for c in banded if c.width_mm > 0 and c.defect_side in ("left", "right")]
    exp = [c for c in faulty if paper_expects_pseudo(c)]
    base = [c for c in banded if c.width_mm == 0]
    out = {"n_exp": len(exp), "right": sum(named_right(c, c.pair.redecide(crit)) for c in exp),
           "right_alone": sum(named_right(c, c.pair.redecide(alone)) for c in exp),
           "n_base": len(base), "quiet": sum(calls_no_fault(c.pair.redecide(crit)) for c in base),
           "in_range": sum(VF_RANGE_PAPER[0] <= c.pair.vf_diff <= VF_RANGE_PAPER[1] for c in exp)}
    for w in sorted({c.width_mm for c in faulty}):
        cs = [c for c in faulty if c.width_mm == w]
        out[f"healthy_more_{w:g}"] = (sum(sides(c)[1].VF > sides(c)[0].VF for c in cs), len(cs))
    # (no defect: ws2_R / ws2_L, the side the study's defects are on first)
    out["cases"] = [(c.label, *(s.VF for s in sides(c)), c.pair.vf_diff) for c in banded]
    return out


def table(name: str, cases) -> str:
    lines = [f"**{name}** ({len(cases)} cases; the paper's absolute range "
             f"[{VF_RANGE_PAPER[0]:.3g}, {VF_RANGE_PAPER[1]:.3g}] Hz^2, source by the paper's criterion)", "",
             "| band | both sides right, lag deciding | by RMS and SPM alone | VF difference in range | "
             "no fault called, no defect | healthy VF > defect VF at 1 / 3 / 5 mm |",
             "| --- | --- | --- | --- | --- | --- |"]
    per_case = {}
    for bname, band in BANDS.items():
        k = counts(cases, band)
        per_case[bname] = k["cases"]
        hm = " / ".join(f"{k[key][0]} of {k[key][1]}" for key in sorted(k)
                        if key.startswith("healthy_more_"))
        lines.append(f"| {bname} | {k['right']} of {k['n_exp']} | {k['right_alone']} of {k['n_exp']} | "
                     f"{k['in_range']} of {k['n_exp']} | {k['quiet']} of {k['n_base']} | {hm} |")
    head = " | ".join(f"{b}: VF defect / healthy, difference Hz^2" for b in BANDS)
    lines += ["", f"| case | {head} |", "| --- |" + " --- |" * len(BANDS)]
    for i, c in enumerate(cases):
        cells = []
        for bname in BANDS:
            _, vd, vh, diff = per_case[bname][i]
            cells.append(f"{vd:.3g} / {vh:.3g}, {diff:.3g}")
        lines.append(f"| {c.label} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folders", nargs="+", help="sweep folders of vehicle results")
    ap.add_argument("--markdown", help="also write the tables here")
    a = ap.parse_args()
    out = []
    for folder in a.folders:
        t0 = time.perf_counter()
        cases = cases_of(folder)
        out.append(table(Path(folder).name, cases))
        print(out[-1], flush=True)
        print(f"\n({time.perf_counter() - t0:.0f} s)\n", flush=True)
    if a.markdown:
        Path(a.markdown).write_text("\n\n".join(out) + "\n")


if __name__ == "__main__":
    main()
