"""The free-free solve's cost with MKL's reproducible mode on and off (issue 36).

fem/linsolve.py sets MKL_CBWR=AUTO before MKL loads, so two solves of one system give the same
bits; this measures what that costs.  Each row: a fresh process (the variable is read when MKL
loads) solving the default-mesh wheelset's 30 free-free modes, best of ``--repeat``, with the
mesh cached beforehand.

    python3 benchmarks/free_free.py [--repeat 2]
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


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=2)
    a = ap.parse_args()
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
