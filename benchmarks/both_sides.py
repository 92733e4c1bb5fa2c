"""Faults on both sides, or one fault and its copy: the figures the rule rests on
(bearing/diagnostics/own.py), one row per result file.

    axlebox sweep validation_48kmh --speeds 48 80 --widths 2 --sides R LR --duration 1.6 --out DIR
    python3 benchmarks/both_sides.py DIR/*.h5 [CWRU .mat options as axlebox diagnose's: none]

Per file: each side's defect (from the stored config), RMS, the BPFO/BPFI lines detected, each
side's share (its line over the other side's, in the other side's envelope band; * where the
line is not detected there), the impulse lag, and the relative criterion's verdicts.
"""
from __future__ import annotations

import sys
import tomllib
from pathlib import Path

from axlebox.bearing import resultfile
from axlebox.bearing.diagnostics.criterion import Criterion
from axlebox.pipelines.diagnose import analyse_file


def defects(path) -> dict:
    with resultfile.open_result(path) as f:
        cfg = tomllib.loads(str(f.attrs.get("config", "")))
    out = {"L": "-", "R": "-"}
    for d in cfg.get("defects", []):
        out[d.get("side", "R")] = f"{d.get('kind', 'outer')} {1e3 * d.get('W', 2e-3):g} mm"
    return out


def main(paths):
    print("| file | left / right defect | RMS m/s^2 | lines L / R | share L / R | lag | verdicts |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for p in paths:
        d = defects(p)
        _, _, r = analyse_file(p, criterion=Criterion(mode="relative"))
        sh = "; ".join(f"{n} {x.share['left']:.3g}{'' if x.seen['left'] else '*'} / "
                       f"{x.share['right']:.3g}{'' if x.seen['right'] else '*'}"
                       for n, x in r.shares.items()) or "-"
        lead = {"a": "left", "b": "right"}.get(r.lag.leading, "neither")
        print(f"| {Path(p).stem} | {d['L']} / {d['R']} | {r.left.rms:.2f} / {r.right.rms:.2f} | "
              f"{','.join(r.left.detected) or '-'} / {','.join(r.right.detected) or '-'} | {sh} | "
              f"{lead} {r.lag.lag_s * 1e3:.2g} ms ({100 * r.lag.agreement:.0f} %) | "
              f"{r.verdicts['left'][0]} / {r.verdicts['right'][0]} |")


if __name__ == "__main__":
    main(sys.argv[1:])
