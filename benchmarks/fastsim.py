"""Benchmark: FASTSIM evaluations per second on one core, its discretisation error, and the
Shen-Hedrick-Elkins and linear laws for comparison.

Contact: a = 6 mm (rolling direction), b = 4 mm, N = 70 kN, mu = 0.3, G = 81 GPa, nu = 0.28;
a sweep of tread creepages xi, eta uniform in [-0.01, 0.01] and spin phi in [-1, 1] 1/m.
Discretisation error: largest |F - F_fine| over the sweep in units of mu N (and |Mz - Mz_fine|
in mu N c, c = sqrt(ab)) against nx = 800, ny = 200.  Speed: the numba kernel over the sweep
inside one compiled loop (``fastsim_batch``), one call of the Python wrapper per contact, and
the plain-numpy version (``tangential.fastsim_numpy``) per contact and over the whole sweep.
Peak memory: tracemalloc (Python heap) of each timed call, and the process's maximum RSS.
Run: ``python benchmarks/fastsim.py``.
"""
from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")      # one core for numpy too
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

import platform  # noqa: E402
import resource  # noqa: E402
import time  # noqa: E402
import tracemalloc  # noqa: E402
from functools import partial  # noqa: E402

import numba  # noqa: E402
import numpy as np  # noqa: E402

from axlebox.mbs.wheelrail import fastsim_kernel as fk  # noqa: E402
from axlebox.mbs.wheelrail import kalker  # noqa: E402
from axlebox.mbs.wheelrail import tangential as tg  # noqa: E402

A, B, N, MU, G, NU = 6e-3, 4e-3, 7e4, 0.3, 8.1e10, 0.28
N_SWEEP = 2000
FINE = dict(nx=800, ny=200)


def sweep(n: int = N_SWEEP, seed: int = 7):
    rng = np.random.default_rng(seed)
    return rng.uniform(-0.01, 0.01, n), rng.uniform(-0.01, 0.01, n), rng.uniform(-1.0, 1.0, n)


def rate(fn, evaluations: int, min_time: float = 0.4, repeats: int = 3):
    """Evaluations per second (best of ``repeats``) and peak traced memory of one call (MB)."""
    fn()                                              # warm-up (and numba compilation)
    tracemalloc.start()
    fn()
    peak = tracemalloc.get_traced_memory()[1] / 1e6
    tracemalloc.stop()
    best = np.inf
    for _ in range(repeats):
        calls, t0 = 0, time.perf_counter()
        while True:
            fn()
            calls += 1
            dt = time.perf_counter() - t0
            if dt >= min_time:
                break
        best = min(best, dt / calls)
    return evaluations / best, peak


def errors(xi, eta, phi, ref, **kw):
    F = np.array(tg.fastsim(xi, eta, phi, A, B, N, MU, G, NU, **kw))
    eF = np.max(np.hypot(F[0] - ref[0], F[1] - ref[1])) / (MU * N)
    eM = np.max(np.abs(F[2] - ref[2])) / (MU * N * np.sqrt(A * B))
    return eF, eM


def batch_args(xi, eta, phi):
    L1, L2, L3 = tg.flexibilities(A, B, G, NU)
    return [np.ascontiguousarray(v, dtype=float) for v in
            np.broadcast_arrays(xi, eta, phi, A, B, N, MU, L1, L2, L3)]


def main() -> None:
    print(f"machine: {platform.machine()}, {os.cpu_count()} cores (one used), Python "
          f"{platform.python_version()}, numpy {np.__version__}, numba {numba.__version__}")
    xi, eta, phi = sweep()
    print(f"contact a = {A * 1e3:g} mm, b = {B * 1e3:g} mm, N = {N / 1e3:g} kN, mu = {MU}, "
          f"G = {G / 1e9:g} GPa, nu = {NU}; {N_SWEEP} creepages, |xi|, |eta| <= 0.01, "
          f"|phi| <= 1 1/m")

    print("\nDiscretisation error against nx x ny = 800 x 200 (parabolic bound):\n")
    print("| slip update | nx x ny | max abs(F - F_fine) / (mu N) | max abs(Mz - Mz_fine) / (mu N c) |")
    print("| --- | --- | --- | --- |")
    ref = {u: np.array(tg.fastsim(xi, eta, phi, A, B, N, MU, G, NU, update=u, **FINE))
           for u in tg.UPDATES}
    for update, grids in (("rotate", ((8, 8), (12, 12), (16, 16), (24, 24))),
                          ("cutback", ((16, 16), (40, 20), (80, 20)))):
        for nx, ny in grids:
            eF, eM = errors(xi, eta, phi, ref[update], update=update, nx=nx, ny=ny)
            mark = " (default)" if (update, nx, ny) == (tg.UPDATE, tg.NX, tg.NY) else ""
            print(f"| {update}{mark} | {nx} x {ny} | {eF * 100:.2f} % | {eM * 100:.2f} % |")
    gap = np.max(np.hypot(*(ref["rotate"] - ref["cutback"])[:2])) / (MU * N)
    print(f"\nThe two slip updates' fine-grid results differ by {gap * 100:.3f} % of mu N "
          f"(both converge to the same simplified theory).")

    rows = []
    for update, nx, ny in (("rotate", tg.NX, tg.NY), ("cutback", 40, 20)):
        kw = dict(update=update, nx=nx, ny=ny)
        out = np.empty((N_SWEEP, 3))
        kernel = partial(fk.fastsim_batch, *batch_args(xi, eta, phi), 0, tg.UPDATES[update],
                         nx, ny, out)
        one = (float(xi[0]), float(eta[0]), float(phi[0]), A, B, N, MU, G, NU)
        r_nb, m_nb = rate(kernel, N_SWEEP)
        r_wr, m_wr = rate(partial(tg.fastsim, *one, **kw), 1)
        r_np1, m_np1 = rate(partial(tg.fastsim_numpy, *one, **kw), 1)
        r_npv, m_npv = rate(partial(tg.fastsim_numpy, xi, eta, phi, A, B, N, MU, G, NU, **kw),
                            N_SWEEP)
        eF, _ = errors(xi, eta, phi, ref[update], **kw)
        grid = f"FASTSIM {update} {nx} x {ny} ({eF * 100:.2f} %)"
        rows += [(grid, "numba kernel, batch loop", r_nb, r_nb / r_npv, m_nb),
                 (grid, "numba via Python wrapper, 1 call/contact", r_wr, r_wr / r_np1, m_wr),
                 (grid, "numpy, 1 call/contact (strips vectorised)", r_np1, 1.0, m_np1),
                 (grid, "numpy, whole sweep vectorised", r_npv, 1.0, m_npv)]
    r, m = rate(lambda: tg.shen_hedrick_elkins(xi, eta, phi, A, B, N, MU, G, NU), N_SWEEP)
    rows.append(("Shen-Hedrick-Elkins", "numpy, whole sweep vectorised", r, np.nan, m))
    r, m = rate(lambda: tg.shen_hedrick_elkins(1e-3, 1e-3, 0.1, A, B, N, MU, G, NU), 1)
    rows.append(("Shen-Hedrick-Elkins", "numpy, 1 call/contact", r, np.nan, m))
    r, m = rate(lambda: kalker.linear_creep_forces(xi, eta, phi, A, B, G, NU), N_SWEEP)
    rows.append(("Kalker linear", "numpy, whole sweep vectorised", r, np.nan, m))
    r, m = rate(lambda: kalker.linear_creep_forces(1e-3, 1e-3, 0.1, A, B, G, NU), 1)
    rows.append(("Kalker linear", "numpy, 1 call/contact", r, np.nan, m))

    print("\nEvaluations per second, one core (speed-up: numba over the numpy row of the same "
          "calling style):\n")
    print("| law (grid, error / mu N) | implementation | evaluations/s | speed-up | "
          "peak traced MB |")
    print("| --- | --- | --- | --- | --- |")
    for law, impl, r, s, m in rows:
        sp = "" if np.isnan(s) or s == 1.0 else f"{s:.1f}x"
        print(f"| {law} | {impl} | {r:,.0f} | {sp} | {m:.3f} |")
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"\npeak resident memory of the process: {rss:.0f} MB")
    goal = rows[0][2]
    print(f"goal >= 20 000 FASTSIM evaluations/s on one core: "
          f"{'met' if goal >= 2e4 else 'NOT met'} ({goal:,.0f}/s at the default grid)")


if __name__ == "__main__":
    main()
