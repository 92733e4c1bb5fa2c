"""Property-based fuzzing of the input entry points at full size (tests/test_fuzz.py with
AXLEBOX_FULL=1: 500 generated cases per entry point, 100 of diagnose's options): prints, per
entry point, the cases run, how many ran and the distinct kinds of refusal seen (file paths and
numbers taken out), and the wall time.  Every case must end in a run or a one-line refusal
(exit 2): a traceback, a crash or a hang fails the test.

    python3 benchmarks/fuzz.py
"""
from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main():
    with tempfile.TemporaryDirectory() as tmp:
        report = Path(tmp) / "fuzz.tsv"
        env = {**os.environ, "AXLEBOX_FULL": "1", "AXLEBOX_FUZZ_REPORT": str(report)}
        t0 = time.perf_counter()
        r = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                            str(ROOT / "tests" / "test_fuzz.py")], cwd=ROOT, env=env,
                           capture_output=True, text=True)
        wall = time.perf_counter() - t0
        print(r.stdout.strip().splitlines()[-1] if r.stdout.strip() else r.stderr[-2000:])
        print(f"wall {wall:.0f} s")
        print("| entry point | cases | ran | distinct refusals |")
        print("| --- | --- | --- | --- |")
        rows = [line.split("\t") for line in report.read_text().splitlines()] if report.exists() else []
        for entry, n, k, kinds in rows:
            ran = next((int(x.rsplit(" x", 1)[1]) for x in kinds.split(" | ") if x.startswith("(ran)")), 0)
            print(f"| {entry} | {n} | {ran} | {int(k) - (1 if ran else 0)} |")
        for entry, _, _, kinds in rows:
            print(f"\n{entry}:")
            for x in kinds.split(" | "):
                print(f"  {x}")
        sys.exit(r.returncode)


if __name__ == "__main__":
    main()
