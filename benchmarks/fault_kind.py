"""Benchmark (issue 57, item 3): the fault's kind named on the faulty side, against the known
answer, over the synthetic kinds (bearing/diagnostics/families.py ``kind_case``: one fault of
each kind and its copy) and any result files of the car given on the command line (the kind and
side from each run's stored config).

    python3 benchmarks/fault_kind.py [--n N] [--T S] [RESULT.h5 ...]

Printed: per kind, how often the faulty side's kind is named right, named wrong, left
"kind undecided" with the right kind among those named, or not named (the side not called
faulty); each case that names a wrong kind; the wall time.
"""
from __future__ import annotations

import argparse
import time
from collections import Counter, defaultdict
from pathlib import Path

from axlebox.bearing.catalogue import lookup
from axlebox.bearing.diagnostics.criterion import Criterion
from axlebox.bearing.diagnostics.families import KIND_LINES, kind_case
from axlebox.bearing.diagnostics.kind import KIND_OF_LINE
from axlebox.bearing.diagnostics.pair import analyse_pair

B = lookup("6205")
WORD = {k: KIND_OF_LINE[line] for k, line in KIND_LINES.items()}   # "outer" -> "outer ring"
OUTCOMES = ("right", "undecided, right among", "wrong", "not named")


def outcome(fk, truth: str) -> str:
    if fk is None:
        return "not named"
    if fk.decided:
        return "right" if fk.kind == truth else "wrong"
    return "undecided, right among" if truth in fk.named else "wrong"


def synthetic(n: int, T: float, table, wrong):
    for kind in KIND_LINES:
        for seed in range(n):
            c = kind_case(seed, kind, B.orders, T=T)
            res = analyse_pair(c.a, c.b, c.fs, c.params["f_shaft"], B.orders, B.bore,
                               Criterion(mode="relative"))
            o = outcome(res.verdict.kinds["left"], WORD[kind])
            table[f"synthetic {kind}"][o] += 1
            if o == "wrong":
                wrong.append(f"synthetic {kind} seed {seed}: {res.verdict.kinds['left'].text()}")


def results(paths, table, wrong):
    from axlebox.pipelines.dataset import case_labels
    from axlebox.pipelines.diagnose import analyse_file
    for p in map(Path, paths):
        lab, _ = case_labels(p)
        _, _, res = analyse_file(p)
        for s in ("left", "right"):
            if lab[f"{s}_kind"] == "none":
                continue
            o = outcome(res.verdict.kinds[s], WORD[lab[f"{s}_kind"]])
            table[f"car {lab[f'{s}_kind']}"][o] += 1
            fk = res.verdict.kinds[s]
            print(f"{p.name} {s}: truth {lab[f'{s}_kind']}, {res.verdict.words[s]}: "
                  f"{fk.text() if fk else 'no kind'} -> {o}", flush=True)
            if o == "wrong":
                wrong.append(f"{p.name} {s}: {fk.text()}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=50, help="synthetic cases a kind (default 50)")
    ap.add_argument("--T", type=float, default=4.0, help="synthetic record length, s (default 4)")
    ap.add_argument("results", nargs="*", help="car result files (their configs give the answer)")
    a = ap.parse_args()
    t0 = time.perf_counter()
    table, wrong = defaultdict(Counter), []
    synthetic(a.n, a.T, table, wrong)
    results(a.results, table, wrong)
    print(f"{'family':22s}" + "".join(f"{o:>24s}" for o in OUTCOMES) + "   right or undecided-with")
    for fam, c in table.items():
        tot = sum(c.values())
        named = tot - c["not named"]
        ok = c["right"] + c["undecided, right among"]
        print(f"{fam:22s}" + "".join(f"{c[o]:24d}" for o in OUTCOMES)
              + f"   {ok}/{named} named ({100 * ok / max(named, 1):.0f} %), right alone {c['right']}")
    for w in wrong:
        print("WRONG:", w)
    print(f"wall {time.perf_counter() - t0:.1f} s")


if __name__ == "__main__":
    main()
