"""The two-channel criterion on real recordings: every record of a manifest diagnosed (each end
with its own bearing) and scored against its ground truth.

    python3 benchmarks/real_records.py [MANIFEST]

MANIFEST: a CSV as :mod:`axlebox.pipelines.records` reads it; default the CWRU records of the
team's reference folder ($AXLEBOX_REFERENCE/cwru/manifest.csv, else ../shared/reference beside
the checkout).  The CWRU rig's ends: drive end SKF 6205, fan end SKF 6203 (the catalogue's
published orders), channels in g.  Prints one line a record and the confusion tables per fault
kind (faulty end and healthy end: real fault / faults on both sides / pseudo-fault / healthy /
undecided), and the wall time.
"""
from __future__ import annotations

import os
import sys
import time
from pathlib import Path

from axlebox.pipelines.records import score

CWRU_BEARINGS = {"DE": "6205", "FE": "6203"}
G = 9.80665                       # the CWRU channels are in g


def default_manifest() -> Path:
    env = os.environ.get("AXLEBOX_REFERENCE")
    root = Path(env) if env else Path(__file__).resolve().parents[2] / "shared" / "reference"
    return root / "cwru" / "manifest.csv"


def main(argv) -> int:
    manifest = Path(argv[0]) if argv else default_manifest()
    t0 = time.perf_counter()
    s = score(manifest, CWRU_BEARINGS, scale=G)
    print()
    print(s.markdown())
    print(f"\n{len(s.records)} records in {time.perf_counter() - t0:.1f} s; healthy ends called "
          f"real or both: {s.count('healthy', ('real fault', 'faults on both sides'))}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
