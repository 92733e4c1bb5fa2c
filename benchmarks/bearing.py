"""Benchmark: one DTRB (2 rows x 20 rollers, 2 cages) on the standalone rig.

Prints: the numba right-hand side's time per call at the quasi-static start and in the running
rig (where centrifugal force keeps every roller on the cup, so more contacts are active), the
plain-numpy twin's time at the same states and the speed-up; simulated seconds per wall second
of the rig (RK4, dt = 1e-5 s, healthy and with a 2 mm defect) and the process's peak memory;
the contact damping ratios and explicit step limits under the default law and the paper's rule.
Run: ``python benchmarks/bearing.py``.
"""
from __future__ import annotations

import importlib.util
import platform
import resource
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from axlebox.bearing import equilibrium, kernel, layout, stiffness
from axlebox.bearing.defects import Defect
from axlebox.bearing.integrate import run_rk4
from axlebox.bearing.kernel_numpy import dtrb_rhs_numpy
from axlebox.bearing.params import BearingParams
from axlebox.bearing.rig import RigConfig, initial_state, simulate


def per_call(f, n, *args):
    f(*args)
    t = time.perf_counter()
    for _ in range(n):
        f(*args)
    return (time.perf_counter() - t) / n


def rig_states():
    """``(P, D, [(name, y, ring)])``: the kernel's inputs at the quasi-static start and in the
    running rig (0.1 s of RK4 from the start)."""
    p = BearingParams()
    cfg = RigConfig(defects=(Defect(W=2e-3),))
    Y, P, D, rig = initial_state(cfg)
    n = layout.n_state(p.Z)
    Yr = Y.copy()
    every = cfg.fs_out_every
    m = 10000 // every
    run_rk4(Yr, 0.0, cfg.dt, 10000, every, P, D, rig, np.zeros((10000, 3)), np.zeros((m, 2, 6)),
            np.zeros((m, 2, p.Z, 6)), np.zeros((m, 2, 2)))
    states = []
    for name, Ys in (("quasi-static start", Y), ("running rig, t = 0.1 s", Yr)):
        ring = equilibrium.ring_motion(cfg.omega_w, Ys[n:n + 3])
        ring[1, 6:9] = Ys[n + 3:n + 6]
        states.append((name, Ys[:n].copy(), ring))
    return P, D, states


def rhs_timings():
    P, D, states = rig_states()
    Z = int(P[layout.Z])
    rows = []
    for name, y, ring in states:
        yd, F, Q = np.zeros(y.size), np.zeros((2, 6)), np.zeros((2, Z, 6))
        t_nb = per_call(kernel.dtrb_rhs, 20000, 0.0, y, ring, P, D, yd, F, Q)
        t_np = per_call(dtrb_rhs_numpy, 300, 0.0, y, ring, P, D)
        kernel.dtrb_rhs(0.0, y, ring, P, D, yd, F, Q)
        rows.append((name, int((Q > 0).sum()), t_nb * 1e6, t_np * 1e6, t_np / t_nb))
    return rows


def fastmath_kernel():
    """The shipped kernel's source compiled again with ``fastmath=True`` (what it was before
    the in-process / cached bit difference, bearing/kernel.py's docstring), as a sibling module
    so that both run side by side in this process."""
    src = Path(kernel.__file__).read_text()
    src = src.replace('@njit(inline="always")', '@njit(inline="always", fastmath=True)')
    src = src.replace("@njit(cache=True)", "@njit(fastmath=True)")
    path = Path(tempfile.mkdtemp()) / "kernel_fastmath.py"
    path.write_text(src)
    name = "axlebox.bearing.kernel_fastmath"
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod


def fastmath_cost(repeats=7, n=20000):
    """Best of ``repeats`` timings of ``n`` calls at the running state, IEEE against fastmath,
    interleaved so that the shared machine's load falls on both alike."""
    P, D, states = rig_states()
    _, y, ring = states[1]                    # the running rig
    Z = int(P[layout.Z])
    fm = fastmath_kernel()
    best = {"IEEE (shipped)": np.inf, "fastmath": np.inf}
    out = {}
    for _ in range(repeats):
        for label, mod in (("IEEE (shipped)", kernel), ("fastmath", fm)):
            yd, F, Q = np.zeros(y.size), np.zeros((2, 6)), np.zeros((2, Z, 6))
            best[label] = min(best[label], per_call(mod.dtrb_rhs, n, 0.0, y, ring, P, D, yd, F, Q))
            out[label] = yd
    diff = np.max(np.abs(out["fastmath"] - out["IEEE (shipped)"]) /
                  (np.abs(out["IEEE (shipped)"]) + 1e-300))
    return best, diff


def rig_speed(duration=1.0):
    rows = []
    for label, defects in (("healthy", ()), ("2 mm defect", (Defect(W=2e-3),))):
        cfg = RigConfig(duration=duration, defects=defects)
        t = time.perf_counter()
        simulate(cfg)
        wall = time.perf_counter() - t
        rows.append((label, cfg.dt, duration, wall, duration / wall))
    return rows


def damping_table():
    """Damping ratio of each contact as an oscillator of the roller (or roller-cage) mass at a
    typical load, and the RK4 step limit (2.78/omega underdamped, 2.78 m/c overdamped)."""
    rows = []
    for law in ("ratio", "paper"):
        p = BearingParams(damping=law)
        k = stiffness.contacts(p)
        m_cage = p.M_r * p.M_c / (p.M_r + p.M_c)
        for name, K, n, Q, m in (("cup/cone", k["K_ro"], 10 / 9, 7e3, p.M_r),
                                 ("rib", k["K_a"], 1.5, 300.0, p.M_r),
                                 ("pocket", k["K_cr"], 10 / 9, 20.0, m_cage)):
            delta = (Q / K) ** (1 / n)
            k_lin = n * Q / delta
            c = 2 * p.zeta * np.sqrt(m * k_lin) if law == "ratio" else p.c_rule * K
            zeta = c / (2 * np.sqrt(m * k_lin))
            w = np.sqrt(k_lin / m)
            limit = 2.78 / w if zeta < 1 else 2.78 * m / c
            rows.append((law, name, Q, k_lin, zeta, limit))
    return rows


def main():
    print(f"# {time.strftime('%Y-%m-%d')}, {platform.machine()}, Python {platform.python_version()}, "
          f"numpy {np.__version__}")
    print("\n| state | active contacts | numba us/call | numpy us/call | speed-up |\n"
          "| --- | --- | --- | --- | --- |")
    for name, nc, a, b, s in rhs_timings():
        print(f"| {name} | {nc} | {a:.1f} | {b:.0f} | {s:.0f}x |")
    best, diff = fastmath_cost()
    print("\n| kernel flags (running rig, t = 0.1 s) | us/call, best of 7 |\n| --- | --- |")
    for label, t in best.items():
        print(f"| {label} | {t * 1e6:.2f} |")
    print(f"fastmath / IEEE: {best['fastmath'] / best['IEEE (shipped)']:.3f}; "
          f"largest relative difference of the state derivative {diff:.1e}")
    print("\n| rig run | dt s | simulated s | wall s | simulated s per wall s |\n"
          "| --- | --- | --- | --- | --- |")
    for label, dt, dur, wall, rate in rig_speed():
        print(f"| {label} | {dt:g} | {dur:g} | {wall:.2f} | {rate:.3f} |")
    print(f"\npeak resident memory: {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB")
    print("\n| damping law | contact | load N | k_lin N/m | damping ratio | RK4 step limit s |\n"
          "| --- | --- | --- | --- | --- | --- |")
    for law, name, Q, k, z, lim in damping_table():
        print(f"| {law} | {name} | {Q:g} | {k:.2e} | {z:.3g} | {lim:.1e} |")


if __name__ == "__main__":
    main()
