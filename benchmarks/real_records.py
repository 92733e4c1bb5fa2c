"""The two-channel criterion on real recordings: every record of a manifest diagnosed (each end
with its own bearing) and scored against its ground truth.

    python3 benchmarks/real_records.py [MANIFEST] [--json OUT]

MANIFEST: a CSV as :mod:`axlebox.pipelines.records` reads it; default
``$AXLEBOX_REFERENCE/cwru/manifest.csv``.  The records are not shipped: they are two-sensor
recordings of the Case Western Reserve University (CWRU) Bearing Data Center
(https://engineering.case.edu/bearingdatacenter; described in W. A. Smith and R. B. Randall,
"Rolling element bearing diagnostics using the Case Western Reserve University data: A benchmark
study", Mech. Syst. Signal Process. 64-65 (2015) 100-131), one .mat file a row of the manifest.
The CWRU rig's ends: drive end SKF 6205, fan end SKF 6203 (the catalogue's published orders),
channels in g.  Prints one line a record and the confusion tables per fault
kind (faulty end and healthy end: real fault / faults on both sides / pseudo-fault / healthy /
undecided), and the wall time.  ``--json OUT`` also writes every record's verdict: the words,
the rule, the end named real, the evidence's fields (the VF difference, the lag, each line and
how its source was found, the whole shaft orders ...), the sentences, and the criterion with
every threshold.
"""
from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

from axlebox.pipelines.records import score

CWRU_BEARINGS = {"DE": "6205", "FE": "6203"}
G = 9.80665                       # the CWRU channels are in g


MISSING = ("No manifest of CWRU records: give its path (python3 benchmarks/real_records.py "
           "MANIFEST) or set AXLEBOX_REFERENCE to a folder holding cwru/manifest.csv.  The records "
           "are those of the Case Western Reserve University Bearing Data Center "
           "(https://engineering.case.edu/bearingdatacenter; Smith and Randall, Mech. Syst. Signal "
           "Process. 64-65 (2015) 100-131); the manifest's columns are described in "
           "axlebox.pipelines.records.")


def default_manifest() -> Path | None:
    """``$AXLEBOX_REFERENCE/cwru/manifest.csv``, or None when the variable is not set."""
    env = os.environ.get("AXLEBOX_REFERENCE")
    return Path(env) / "cwru" / "manifest.csv" if env else None


def main(argv) -> int:
    argv = list(argv)
    json_out = None
    if "--json" in argv:
        i = argv.index("--json")
        if i + 1 >= len(argv):
            print("--json needs a file name: --json OUT", file=sys.stderr)
            return 2
        json_out = Path(argv[i + 1])
        del argv[i:i + 2]
    manifest = Path(argv[0]) if argv else default_manifest()
    if manifest is None or not manifest.is_file():
        print((f"{manifest}: not found.  " if manifest is not None else "") + MISSING,
              file=sys.stderr)
        return 2
    from axlebox.bearing.diagnostics.channel import jsonable
    from axlebox.bearing.diagnostics.criterion import Criterion
    t0 = time.perf_counter()
    criterion = Criterion(mode="relative")          # score()'s default, written with the records
    s = score(manifest, CWRU_BEARINGS, scale=G, criterion=criterion)
    print()
    print(s.markdown())
    print(f"\n{len(s.records)} records in {time.perf_counter() - t0:.1f} s; healthy ends called "
          f"real or both: {s.count('healthy', ('real fault', 'faults on both sides'))}")
    if json_out is not None:
        json_out.write_text(json.dumps(jsonable({"manifest": str(manifest),
                                                 "criterion": criterion.to_dict(),
                                                 "records": [r.to_dict() for r in s.records]}),
                                       indent=1, allow_nan=False) + "\n")
        print(f"wrote {json_out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
