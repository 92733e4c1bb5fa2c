"""Property-based fuzzing of the input entry points at full size (tests/test_fuzz.py with
AXLEBOX_FULL=1: 500 generated cases per entry point, 100 of diagnose's options, 40 per class of
spoiled record): prints, per entry point, the cases run, how many ran and the distinct kinds of
refusal seen (file paths and numbers taken out), and the wall time.  Every case must end in a
run or a one-line refusal (exit 2): a traceback, a crash or a hang fails the test.

The spoiled records (issue 57: quantized, clipped, offset and drifting, held, with NaN gaps, a
channel all zeros, channels of different lengths, too short; on a healthy wheelset and on an
outer-ring defect and its copy) get a table of their own: per class and path (``axlebox
diagnose`` on a CSV, ``analyse_pair`` on the arrays) the cases read with the right verdict
(the defect side a real fault and the other not faulty, or both sides healthy), read with
another verdict (listed; a healthy side called faulty fails the test), refused in one line, and
crashed.

    python3 benchmarks/fuzz.py [--spoiled]      # --spoiled: the spoiled records alone
"""
from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def spoiled_table(rows) -> None:
    """The spoiled records' outcomes by class and path (module docstring)."""
    print("\n| spoiled record | path | cases | read, right | read, other verdict | refused (exit 2) "
          "| crashed |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    other = {}
    for entry, n, _, kinds in rows:
        if not entry.startswith("spoiled: ") or entry.endswith("(command)"):
            continue
        path = "analyse_pair" if entry.endswith("(analyse_pair)") else "command"
        name = entry[len("spoiled: "):].replace(" (analyse_pair)", "")
        counts = {}
        for x in kinds.split(" | "):
            k, c = x.rsplit(" x", 1)
            counts[k] = int(c)
        right = counts.pop("read, right", 0)
        crashed = sum(c for k, c in counts.items() if k.startswith("crashed"))
        wrong = {k: c for k, c in counts.items() if k.startswith("read, ")}
        refused = int(n) - right - crashed - sum(wrong.values())
        other[name, path] = wrong
        print(f"| {name} | {path} | {n} | {right} | {sum(wrong.values())} | {refused} | {crashed} |")
    for (name, path), wrong in other.items():
        for k, c in wrong.items():
            print(f"  {name} ({path}): {k} x{c}")


def main():
    only_spoiled = "--spoiled" in sys.argv[1:]
    with tempfile.TemporaryDirectory() as tmp:
        report = Path(tmp) / "fuzz.tsv"
        env = {**os.environ, "AXLEBOX_FULL": "1", "AXLEBOX_FUZZ_REPORT": str(report)}
        t0 = time.perf_counter()
        select = ["-k", "spoiled"] if only_spoiled else []
        r = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-n", "0",
                            str(ROOT / "tests" / "test_fuzz.py"), *select],
                           cwd=ROOT, env=env, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        print(r.stdout.strip().splitlines()[-1] if r.stdout.strip() else r.stderr[-2000:])
        if r.returncode:
            print(r.stdout[-6000:])
        print(f"wall {wall:.0f} s")
        rows = [line.split("\t") for line in report.read_text().splitlines()] if report.exists() else []
        print("| entry point | cases | ran | distinct refusals |")
        print("| --- | --- | --- | --- |")
        for entry, n, k, kinds in rows:
            if entry.startswith("spoiled: ") and not entry.endswith("(command)"):
                continue
            ran = next((int(x.rsplit(" x", 1)[1]) for x in kinds.split(" | ") if x.startswith("(ran)")), 0)
            print(f"| {entry} | {n} | {ran} | {int(k) - (1 if ran else 0)} |")
        spoiled_table(rows)
        for entry, _, _, kinds in rows:
            print(f"\n{entry}:")
            for x in kinds.split(" | "):
                print(f"  {x}")
        sys.exit(r.returncode)


if __name__ == "__main__":
    main()
