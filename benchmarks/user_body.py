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


def write_inputs(folder: Path, h: float) -> tuple[Path, Path]:
    """The built-in frame as STEP and a spec whose boxes are its named faces' bounding boxes."""
    import gmsh

    from axlebox.geometry import frame
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("frame")
        named = frame.build(frame.FrameParams())
        gmsh.model.occ.synchronize()
        lines = [f'[body]\nkind = "frame"\nname = "user_frame"\n\n[mesh]\nsize = {h}\n\n'
                 '[reduction]\nmodes = 12\nn_reference = 12\n']
        for name, tags in named.items():
            bb = np.array([gmsh.model.getBoundingBox(2, t) for t in tags])
            box = [round(float(v), 6) for v in (*bb[:, :3].min(0), *bb[:, 3:].max(0))]
            lines.append(f'[interfaces.{name}]\nbox = {box}\ncoupling = "rbe3"\n')
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        gmsh.write(str(folder / "frame.step"))
    finally:
        gmsh.option.setString("Geometry.OCCTargetUnit", "")
        gmsh.finalize()
    (folder / "frame.toml").write_text("\n".join(lines))
    return folder / "frame.step", folder / "frame.toml"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh-size", type=float, default=0.08)
    ap.add_argument("--repeats", type=int, default=2)
    a = ap.parse_args()
    from axlebox.pipelines.bodies import build_body, build_user_body
    work = Path(tempfile.mkdtemp(prefix="user-body-"))
    step, spec = write_inputs(work, a.mesh_size)
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
