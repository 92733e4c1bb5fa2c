"""How much faster a sweep runs on two local workers than on one (``axlebox sweep --workers``).

    python3 benchmarks/sweep.py [--duration 3.0]

Four equal rig cases (the same duration and step: the same work) on one worker process and on
two, timed from the cluster's start to its shutdown (the summary after is serial): ideal 2,
less dask's start-up (about 2 s), one numba cache load per worker and the imbalance of the last
pair.  The numba cache is warmed first.  Best of ``--repeats``: another job on the machine pulls
the ratio towards 1.
"""
from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from axlebox.bearing.defects import Defect
from axlebox.bearing.rig import RigConfig, simulate
from axlebox.pipelines.sweep import load_config, matrix, run_cases

RIG = """
[rig]
duration = {duration}
seed = 0

[[defects]]
W = 0.001
angle = 0.15707963267948966
"""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--duration", type=float, default=3.0, help="simulated s a case")
    ap.add_argument("--repeats", type=int, default=2)
    a = ap.parse_args()
    simulate(RigConfig(duration=0.01, defects=(Defect(W=1e-3),)))          # compile or load the cache
    with tempfile.TemporaryDirectory() as tmp:
        cfg = Path(tmp) / "rig.toml"
        cfg.write_text(RIG.format(duration=a.duration))
        cases = matrix(*load_config(cfg), speeds=[40.0, 50.0, 60.0, 70.0], widths=[1.0])
        best = {}
        for r in range(a.repeats):
            for n in (1, 2):
                out = Path(tmp) / f"r{r}_w{n}"
                out.mkdir()
                t0 = time.perf_counter()
                assert run_cases(cases, out, workers=n, log=lambda *_: None) == []
                best[n] = min(best.get(n, float("inf")), time.perf_counter() - t0)
    print("| cases | simulated s a case | 1 worker s | 2 workers s | speed-up |\n"
          "| --- | --- | --- | --- | --- |\n"
          f"| 4 | {a.duration:g} | {best[1]:.1f} | {best[2]:.1f} | {best[1] / best[2]:.2f} |")


if __name__ == "__main__":
    main()
