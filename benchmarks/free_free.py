"""The free-free solve's cost: with MKL's reproducible mode on and off (issue 36), and against the
solver of an earlier commit (``--before REV``, issue 56).

fem/linsolve.py sets MKL_CBWR=AUTO before MKL loads, so two solves of one system give the same
bits; this measures what that costs.  Each row: a fresh process (the variable is read when MKL
loads) solving the default-mesh wheelset's 30 free-free modes, best of ``--repeat``, with the
mesh cached beforehand.  With ``--before REV``: REV's ``fem/eigen.py`` loaded beside this one in
one process (as ``axlebox.fem._eigen_before``, on this checkout's assembly and solvers), the two
solves alternating, and the Sturm count's factorisation timed apart.

    python3 benchmarks/free_free.py [--repeat 2] [--before e8a9aa0]
"""
import argparse
import os
import subprocess
import sys
import time

CHILD = """
import time, warnings
warnings.simplefilter("ignore")
from axlebox.fem import assembly, eigen
from axlebox.geometry import mesh, wheelset
from axlebox.pipelines.bodies import BODIES
fe = assembly.assemble(mesh.mesh_model("wheelset", wheelset.build, wheelset.WheelsetParams(),
                                       BODIES["wheelset"].mesh_size))
t = time.perf_counter()
m = eigen.free_free_modes(fe, 30)
print(fe.ndof, time.perf_counter() - t, m.frequencies_hz[0])
"""


def run(cbwr: str) -> tuple[int, float, float]:
    env = dict(os.environ, MKL_CBWR=cbwr)
    out = subprocess.run([sys.executable, "-c", CHILD], env=env, capture_output=True, text=True,
                         check=True).stdout.split()
    return int(out[0]), float(out[1]), float(out[2])


BESIDE = """
import importlib.util, sys, time, warnings
warnings.simplefilter("ignore")
import numpy as np
from axlebox.fem import assembly, eigen, linsolve
from axlebox.geometry import mesh, wheelset
from axlebox.pipelines.bodies import BODIES
spec = importlib.util.spec_from_file_location("axlebox.fem._eigen_before", sys.argv[1])
before = sys.modules[spec.name] = importlib.util.module_from_spec(spec)
spec.loader.exec_module(before)
fe = assembly.assemble(mesh.mesh_model("wheelset", wheelset.build, wheelset.WheelsetParams(),
                                       BODIES["wheelset"].mesh_size))
for _ in range(int(sys.argv[2])):
    for name, mod in (("before", before), ("now", eigen)):
        t = time.perf_counter()
        m = mod.free_free_modes(fe, 30)
        print(name, time.perf_counter() - t, m.frequencies_hz[0], m.frequencies_hz[-1], flush=True)
j, mu = eigen.sturm_cut(m.frequencies_hz, 27)     # (the solve cuts past its 30)
t = time.perf_counter()
n = linsolve.negative_eigenvalues((fe.K - (2 * np.pi * mu) ** 2 * fe.M).tocsr())
print("sturm", time.perf_counter() - t, n, fe.ndof)
"""


def beside(rev: str, repeat: int) -> None:
    import tempfile
    old = subprocess.run(["git", "show", f"{rev}:fem/eigen.py"], capture_output=True, text=True,
                         check=True, cwd=os.path.dirname(os.path.abspath(__file__))).stdout
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "eigen_before.py")
        with open(path, "w") as f:
            f.write(old)
        out = subprocess.run([sys.executable, "-c", BESIDE, path, str(repeat)], capture_output=True,
                             text=True, check=True).stdout.split("\n")
    rows, f = {}, {}
    for line in filter(None, out):
        name, *v = line.split()
        if name == "sturm":
            sturm, count, ndof = float(v[0]), int(v[1]), int(v[2])
        else:
            rows.setdefault(name, []).append(float(v[0]))
            f[name] = (float(v[1]), float(v[2]))
    print(f"{time.strftime('%Y-%m-%d')}, wheelset {ndof} DOF, 30 free-free modes, one process, alternating")
    print("| solver | best wall s | runs | first, 30th Hz |")
    print("| --- | --- | --- | --- |")
    for name, ts in rows.items():
        label = f"{rev} (before)" if name == "before" else "this checkout"
        print(f"| {label} | {min(ts):.2f} | {', '.join(f'{t:.2f}' for t in ts)} | "
              f"{f[name][0]:.6f}, {f[name][1]:.4f} |")
    print(f"the Sturm count's factorisation alone: {sturm:.2f} s ({count} eigenvalues below the cut)")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--before", metavar="REV", help="compare with REV's fem/eigen.py, one process")
    a = ap.parse_args()
    if a.before:
        run("AUTO")                               # mesh into the cache
        beside(a.before, a.repeat)
        return
    run("AUTO")                                   # mesh into the cache, kernels warm
    rows = {}
    for _ in range(a.repeat):                     # interleaved: the machine's load hits both
        for mode in ("AUTO", "OFF"):
            n, t, f1 = run(mode)
            rows.setdefault(mode, []).append(t)
    print(f"{time.strftime('%Y-%m-%d')}, wheelset {n} DOF, 30 free-free modes, first {f1:.4f} Hz")
    print("| MKL_CBWR | best wall s | runs |")
    print("| --- | --- | --- |")
    for mode, ts in rows.items():
        print(f"| {mode} | {min(ts):.2f} | {', '.join(f'{t:.2f}' for t in ts)} |")


if __name__ == "__main__":
    main()
