"""Benchmark: build each modal body at its default mesh; wheelset bending convergence.

Prints wall time, peak resident memory (of a fresh process per body) and DOF
count for each body, then the wheelset's first and second bending frequencies
at three mesh sizes.  Run: ``python benchmarks/bodies.py``.
"""
from __future__ import annotations

import json
import os
import platform
import subprocess
import sys
import tempfile
import time

CHILD = r"""
import json, resource, sys, time
from axlebox.pipelines.bodies import build_body
from axlebox.pipelines import modeid
name, h = sys.argv[1], (float(sys.argv[2]) if sys.argv[2] != "default" else None)
t = time.perf_counter()
body, _ = build_body(name, mesh_size=h, n_modes=20, n_reference=30 if name == "wheelset" else 0,
                     log=lambda s: None)
wall = time.perf_counter() - t
out = {"body": name, "mesh_size": body.meta["mesh_size"], "dof": body.meta["n_dof"], "wall_s": wall,
       "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
       "f1_hz": float(body.frequencies_hz[0])}
if name == "wheelset":
    f = body.reference_frequencies_hz
    from axlebox.fem import bodyfile
    lab = modeid.classify(body.mesh_points, body.mode_shapes)
    out["bending1_hz"] = modeid.first_of(lab, body.frequencies_hz, "bending-1")
    out["bending2_hz"] = modeid.first_of(lab, body.frequencies_hz, "bending-2")
print(json.dumps(out))
"""


def run(name: str, h: str, cache: str) -> dict:
    env = dict(os.environ, AXLEBOX_CACHE=cache)   # fresh cache: meshing is timed too
    r = subprocess.run([sys.executable, "-c", CHILD, name, h], capture_output=True, text=True,
                       env=env, check=True)
    return json.loads(r.stdout.strip().splitlines()[-1])


def main() -> None:
    print(f"machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}")
    with tempfile.TemporaryDirectory() as cache:
        print(f"{'body':10s} {'mesh mm':>8s} {'DOF':>8s} {'wall s':>8s} {'peak MB':>8s} {'f1 Hz':>8s}")
        for name in ("wheelset", "axlebox", "frame"):
            r = run(name, "default", cache)
            print(f"{name:10s} {r['mesh_size'] * 1e3:8.0f} {r['dof']:8d} {r['wall_s']:8.1f} "
                  f"{r['peak_rss_mb']:8.0f} {r['f1_hz']:8.1f}")
        print("\nwheelset bending frequencies (Craig-Bampton, 20 fixed-interface modes)")
        print(f"{'mesh mm':>8s} {'DOF':>8s} {'wall s':>8s} {'bending 1 Hz':>13s} {'bending 2 Hz':>13s}")
        for h in ("0.06", "0.04", "0.03"):
            r = run("wheelset", h, cache)
            print(f"{float(h) * 1e3:8.0f} {r['dof']:8d} {r['wall_s']:8.1f} {r['bending1_hz']:13.2f} "
                  f"{r['bending2_hz']:13.2f}")


if __name__ == "__main__":
    t = time.perf_counter()
    main()
    print(f"\ntotal {time.perf_counter() - t:.0f} s")
