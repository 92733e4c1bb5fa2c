"""A frame of your own against the built-in one (issue 59, item 5e): the built-in bogie frame
(geometry/frame.py) written by gmsh as STEP, read back through ``axlebox bodies build --geometry
--spec`` with its interfaces given by boxes, against the built-in path at the same mesh size, in
one run, alternating, best of ``--repeats``: wall time, degrees of freedom, free-free and
Craig-Bampton frequencies.  Every build meshes afresh (a private mesh cache per build).

    python3 benchmarks/user_body.py [--mesh-size 0.08] [--repeats 2]
"""
from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

import numpy as np


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh-size", type=float, default=0.08)
    ap.add_argument("--repeats", type=int, default=2)
    a = ap.parse_args()
    from axlebox.pipelines.bodies import build_body, build_user_body, write_template
    work = Path(tempfile.mkdtemp(prefix="user-body-"))
    step, spec = write_template("frame", work, mesh_size=a.mesh_size, n_reference=12)
    best = {"built-in": np.inf, "your own (STEP)": np.inf}
    bodies = {}
    for r in range(a.repeats):
        for name in best:
            os.environ["AXLEBOX_CACHE"] = str(work / f"cache-{name[:4]}-{r}")      # mesh afresh
            t0 = time.perf_counter()
            if name == "built-in":
                rb, _ = build_body("frame", mesh_size=a.mesh_size, n_modes=12, n_reference=12,
                                   log=lambda *_: None)
            else:
                rb, _ = build_user_body(spec, geometry=step, out_dir=work / f"out-{r}", force=True,
                                        log=lambda *_: None)
            best[name] = min(best[name], time.perf_counter() - t0)
            bodies[name] = rb
    print(f"frame at mesh size {a.mesh_size} m, best of {a.repeats}")
    print("| path | DOF | wall s | free-free Hz (modes 1, 6, 12) | Craig-Bampton Hz (1, 6, 12) |")
    print("| --- | --- | --- | --- | --- |")
    for name, rb in bodies.items():
        ff, cb = rb.reference_frequencies_hz, rb.frequencies_hz
        print(f"| {name} | {rb.meta['n_dof']} | {best[name]:.1f} | {ff[0]:.2f}, {ff[5]:.2f}, {ff[11]:.2f} | "
              f"{cb[0]:.2f}, {cb[5]:.2f}, {cb[11]:.2f} |")
    u, b = bodies["your own (STEP)"], bodies["built-in"]
    ff = np.abs(u.reference_frequencies_hz / b.reference_frequencies_hz - 1).max()
    cb = np.abs(u.frequencies_hz[:12] / b.frequencies_hz[:12] - 1).max()
    print(f"largest difference: free-free {ff:.2e}, Craig-Bampton (12) {cb:.2e}, "
          f"mass {abs(u.mass / b.mass - 1):.1e}")


if __name__ == "__main__":
    main()
