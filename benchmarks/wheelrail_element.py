"""Benchmark: wheel-rail force element calls per second on one core (S1002 on 60E1 1:40).

One wheel, 2000 random states around the centred contact (lateral offset within +-6 mm, roll
+-1 mrad off the table, penetration 20-100 um, tread creepages of a few 1e-3, spin, yaw rate),
evaluated by :func:`axlebox.mbs.wheelrail.element_kernel.wheel_rail_force` with FASTSIM 16 x 16 and
8 x 8 (rotate slip step, parabolic bound), Kalker's linear law and Shen-Hedrick-Elkins:

* inside one compiled loop (how the multibody right-hand side calls it);
* one call from Python per state (dispatch overhead included);
* the numpy reference (:func:`axlebox.mbs.wheelrail.element.wheel_force_reference`), for scale.

Table build time (uncached and cached) is printed first.  Run:
``python benchmarks/wheelrail_element.py``.
"""
from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")      # one core for numpy too
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

import platform  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402

import numba  # noqa: E402
import numpy as np  # noqa: E402
from numba import njit  # noqa: E402

from axlebox.mbs.wheelrail import element as el  # noqa: E402
from axlebox.mbs.wheelrail import element_kernel as ek  # noqa: E402
from axlebox.mbs.wheelrail.standard import s1002, uic60  # noqa: E402

from fastsim import rate  # noqa: E402  (benchmarks/fastsim.py: best-of-N calls per second)

N_STATES = 2000


@njit(cache=True)
def loop(side, C, E, VC, W, V, tab, par, out):
    """All states of one wheel in one compiled loop; returns the sum of F_z (kept live)."""
    acc = 0.0
    for k in range(C.shape[0]):
        ek.wheel_rail_force(side, C[k], E[k], VC[k], W[k], V[k], 0.0, 0.0, 0.0, 0.0, tab, par,
                            out)
        acc += out[ek.OUT_F + 2]
    return acc


def states(T, n=N_STATES, seed=1):
    rng = np.random.default_rng(seed)
    l0, r0 = T.par[ek.P_L0], T.par[ek.P_R0]
    u = rng.uniform(-6e-3, 6e-3, n)
    roll = np.interp(u, T.u, T.column(ek.COL_ROLL0, 0)) + rng.uniform(-1e-3, 1e-3, n)
    psi = rng.uniform(-3e-3, 3e-3, n)
    E = np.stack([-np.sin(psi) * np.cos(roll), np.cos(psi) * np.cos(roll), np.sin(roll)], 1)
    cz = np.interp(u, T.u, T.column(ek.COL_C0Z, 0)) - rng.uniform(2e-5, 1e-4, n)
    C = np.stack([np.zeros(n), u + l0 - r0 * np.sin(roll), cz], 1)
    V = rng.uniform(5.0, 30.0, n)
    VC = np.stack([V * (1 + rng.uniform(-3e-3, 3e-3, n)), V * rng.uniform(-3e-3, 3e-3, n),
                   np.zeros(n)], 1)
    W = np.stack([np.zeros(n), V / r0 * (1 + rng.uniform(-3e-3, 3e-3, n)),
                  rng.uniform(-0.5, 0.5, n)], 1)
    return C, E, VC, W, V


def main() -> None:
    print(f"machine: {platform.machine()}, {os.cpu_count()} cores (one used), Python "
          f"{platform.python_version()}, numpy {np.__version__}, numba {numba.__version__}")
    os.environ["AXLEBOX_CACHE"] = tempfile.mkdtemp(prefix="axlebox-bench-")
    t0 = time.perf_counter()
    T = el.build_tables(s1002(), uic60())
    t1 = time.perf_counter()
    el._MEMO.clear()
    el.build_tables(s1002(), uic60())
    t2 = time.perf_counter()
    print(f"tables {T.tab.shape} ({T.tab.nbytes / 1e3:.0f} kB): built in {t1 - t0:.2f} s, "
          f"read back from the disk cache in {(t2 - t1) * 1e3:.1f} ms")
    C, E, VC, W, V = states(T)
    out = np.zeros(ek.N_OUT)
    print(f"\n{N_STATES} states of one wheel (left), S1002 on 60E1, default WheelRailParams\n")
    print("| law | compiled loop, calls/s | from Python, calls/s | numpy reference, calls/s |")
    print("| --- | --- | --- | --- |")
    cases = (("FASTSIM 16 x 16", dict(law="fastsim", nx=16, ny=16)),
             ("FASTSIM 8 x 8", dict(law="fastsim", nx=8, ny=8)),
             ("Kalker linear", dict(law="kalker")),
             ("Shen-Hedrick-Elkins", dict(law="she")))
    for name, kw in cases:
        Tk = T.with_params(el.WheelRailParams(**kw))
        r_loop, _ = rate(lambda tab=Tk.tab, par=Tk.par: loop(0, C, E, VC, W, V, tab, par, out),
                      N_STATES)

        def python_calls(tab=Tk.tab, par=Tk.par):
            for k in range(200):
                ek.wheel_rail_force(0, C[k], E[k], VC[k], W[k], V[k], 0.0, 0.0, 0.0, 0.0, tab,
                                    par, out)

        def reference_calls(Tk=Tk):
            for k in range(20):
                el.wheel_force_reference(0, C[k], E[k], VC[k], W[k], V[k], 0.0, 0.0, 0.0, 0.0, Tk)
        r_py, _ = rate(python_calls, 200)
        r_ref, _ = rate(reference_calls, 20, min_time=0.2, repeats=1)
        print(f"| {name} | {r_loop:,.0f} | {r_py:,.0f} | {r_ref:,.0f} |")


if __name__ == "__main__":
    main()
