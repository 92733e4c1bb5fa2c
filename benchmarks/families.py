"""The verdicts on the synthetic families with known answers (bearing/diagnostics/families.py):
what the copy-or-source test and the verdict were designed on.

    python3 benchmarks/families.py [N] [T]

N cases of each family (default 200), records of T s (default 10).  Prints, per family, the
verdicts (left = the first fault's side) with the rules that gave them, the copy-or-source
test's decisions and the spread of its least coherent fraction, the cases that miss their answer
with their parameters, and the wall time.
"""
from __future__ import annotations

import sys
import time
from collections import Counter

import numpy as np

from axlebox.bearing.catalogue import lookup
from axlebox.bearing.diagnostics.criterion import Criterion
from axlebox.bearing.diagnostics.families import copy_case, two_source_case
from axlebox.bearing.diagnostics.pair import analyse_pair

B = lookup("6205")


def run(make, n, T):
    words, rules, decisions, c_min, misses = Counter(), Counter(), Counter(), [], []
    for seed in range(n):
        case = make(seed, T=T)
        res = analyse_pair(case.a, case.b, case.fs, case.params["f_fault"] / B.orders.BPFO,
                           B.orders, B.bore, Criterion(mode="relative"))
        w = (res.verdict.words["left"], res.verdict.words["right"])
        words[w] += 1
        rules[res.verdict.rule] += 1
        for ev in res.evidence:
            if ev.timing is not None:
                decisions[ev.timing.decision] += 1
                if ev.timing.c_min is not None:
                    c_min.append(ev.timing.c_min)
        ok = w[1] in ("pseudo-fault", "healthy") if case.faults == ("a",) else \
            w == ("faults on both sides",) * 2
        if not ok:
            misses.append((seed, w, res.verdict.rule,
                           {k: round(v, 4) for k, v in case.params.items()}))
    return words, rules, decisions, np.array(c_min), misses


def main(argv) -> int:
    n = int(argv[0]) if argv else 200
    T = float(argv[1]) if len(argv) > 1 else 10.0
    for name, make in (("copy (answer: left real, right pseudo-fault or healthy)", copy_case),
                       ("two sources (answer: faults on both sides)", two_source_case)):
        t0 = time.perf_counter()
        words, rules, decisions, c, misses = run(make, n, T)
        print(f"\n{name}: {n} cases of {T:g} s, {time.perf_counter() - t0:.0f} s")
        print("| left | right | cases |\n| --- | --- | --- |")
        for (lw, rw), k in words.most_common():
            print(f"| {lw} | {rw} | {k} |")
        print("rules: " + ", ".join(f"{r} {k}" for r, k in rules.most_common()))
        print("timing: " + ", ".join(f"{d} {k}" for d, k in decisions.most_common()))
        if c.size:
            print(f"least coherent fraction of a significant harmonic: min {c.min():.3f}, "
                  f"median {np.median(c):.3f}, max {c.max():.3f} ({c.size} lines)")
        print(f"missed: {len(misses)} of {n}")
        for m in misses:
            print("  ", m)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
