"""Benchmark: one DTRB (2 rows x 20 rollers, 2 cages) on the standalone rig.

Prints: the numba right-hand side's time per call at the quasi-static start and in the running
rig (where centrifugal force keeps every roller on the cup, so more contacts are active), the
plain-numpy twin's time at the same states and the speed-up; simulated
seconds per wall second of the rig by each integrator (RK4, the leapfrog, imex2 at several steps,
1 s, the 2 mm defect and healthy) with the outer ring's RMS and BPFO envelope line against RK4 at
1e-5 s; the implicit kick's order on the calibrated bearing (steps and weights theta against the
explicit leapfrog at 2.5e-7 s); the process's peak memory; the contact damping ratios and
explicit step limits under the default law and the paper's rule.
Run: ``python benchmarks/bearing.py``.
"""
from __future__ import annotations

import platform
import resource
import time

import numpy as np

from axlebox.bearing.statics import equilibrium, stiffness

from axlebox.bearing.kernel import layout

from axlebox.bearing.kernel import dispatch
from axlebox.bearing.defects import Defect
from axlebox.bearing.kernel.evaluate import evaluate, work
from axlebox.bearing.kernel.implicit import scratch
from axlebox.bearing.integrate import run_leapfrog, run_rk4
from axlebox.bearing.kernel.numpy_twin import dtrb_rhs_numpy
from axlebox.bearing.models.params import BearingParams
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
    run_rk4(dispatch.tag(p), Yr, 0.0, cfg.dt, 10000, every, P, D, rig, work(p.Z, Y.size),
            np.zeros((10000, 3)), np.zeros((m, 2, 6)), np.zeros((m, p.rows, p.Z, 6)),
            np.zeros((m, p.rows, 2)))
    states = []
    for name, Ys in (("quasi-static start", Y), ("running rig, t = 0.1 s", Yr)):
        ring = equilibrium.ring_motion(cfg.omega_w, Ys[n:n + 3])
        ring[1, 6:9] = Ys[n + 3:n + 6]
        states.append((name, Ys[:n].copy(), ring))
    return P, D, states


def rhs_timings():
    P, D, states = rig_states()
    Z = int(P[layout.Z])
    tag = dispatch.tag(BearingParams())
    rows = []
    for name, y, ring in states:
        yd, F, Q, w = np.zeros(y.size), np.zeros((2, 6)), np.zeros((2, Z, 6)), work(Z, y.size)
        t_nb = per_call(evaluate, 20000, tag, 0.0, y, ring, P, D, yd, F, Q, w, False, 0.0)
        t_np = per_call(dtrb_rhs_numpy, 300, 0.0, y, ring, P, D)
        rows.append((name, int((Q > 0).sum()), t_nb * 1e6, t_np * 1e6, t_np / t_nb))
    return rows


def bpfo_line(res, t0=0.05) -> tuple[float, float]:
    """The outer ring's vertical RMS after ``t0`` and its envelope spectrum's largest line within
    two bins of BPFO (band 1-4 kHz)."""
    from axlebox.bearing.frequencies import orders, shaft_hz
    from axlebox.bearing.spectra import envelope_spectrum
    a = res.acceleration[res.time >= t0, 2]
    f, A = envelope_spectrum(a, res.fs, band=(1000.0, 4000.0))
    k = int(np.argmin(abs(f - orders(res.config.bearing).at(shaft_hz(res.config.speed_kmh,
                                                                      res.config.r_wheel))["BPFO"])))
    return float(np.sqrt(np.mean(a ** 2))), float(A[max(0, k - 2):k + 3].max())


RIG_RUNS = (("rk4", 1e-5), ("rk4", 5e-6), ("leapfrog", 1e-5), ("leapfrog", 1.25e-5),
            ("imex2", 1e-5), ("imex2", 2e-5), ("imex2", 2.5e-5), ("imex2", 5e-5))


def rig_speed(duration=1.0):
    """Each integrator on the rig (2 mm defect, 48 km/h, one thread) against RK4 at 1e-5 s: wall
    time, the outer ring's RMS and BPFO envelope line; and both RK4 and the leapfrog healthy."""
    rows = []
    for label, defects in (("2 mm defect", (Defect(W=2e-3),)), ("healthy", ())):
        runs = RIG_RUNS if defects else RIG_RUNS[:1] + RIG_RUNS[2:3]
        for method, dt in runs:
            cfg = RigConfig(duration=duration, defects=defects, method=method, dt=dt)
            simulate(RigConfig(duration=0.001, method=method, dt=dt))         # compile
            t = time.perf_counter()
            try:
                res = simulate(cfg)
            except FloatingPointError:
                rows.append((label, method, dt, None, None, None))
                continue
            rows.append((label, method, dt, time.perf_counter() - t, *bpfo_line(res)))
    return rows


def implicit_order(duration=0.3):
    """The implicit kick's order on the calibrated bearing (damping 1e-4 s x stiffness): the rig
    by ``imex`` at several steps and weights theta (bearing/kernel/implicit.py) against the explicit
    leapfrog at 2.5e-7 s, its stable step there."""
    from scipy.signal import resample_poly
    cfg = RigConfig(duration=duration, defects=(Defect(W=2e-3),),
                    bearing=BearingParams(damping="stiffness", beta=1e-4))
    out = []
    for mode, dt, theta in ((0, 2.5e-7, 1.0), (1, 2.5e-6, 1.0), (1, 5e-6, 1.0), (1, 1e-5, 1.0),
                            (1, 2e-5, 1.0), (1, 2.5e-6, 0.5), (1, 5e-6, 0.5), (1, 1e-4 / 15, 0.5),
                            (1, 1e-5, 0.5), (1, 1e-4 / 15, 0.6), (1, 1e-5, 0.6), (1, 1e-5, 0.8)):
        Y, P, D, rig = initial_state(cfg)
        Z = int(P[layout.Z])
        n, every = int(round(duration / dt)), int(round(1e-4 / dt))
        acc = np.zeros((n, 3))
        m = n // every
        t = time.perf_counter()
        ok = run_leapfrog(dispatch.tag(cfg.bearing), Y, 0.0, dt, n, every, P, D, rig, work(Z, Y.size),
                          scratch(Z, 2), acc, np.zeros((m, 2, 6)), np.zeros((m, 2, Z, 6)),
                          np.zeros((m, 2, 2)), mode, True, theta)
        wall = time.perf_counter() - t
        a = resample_poly(acc[:, 2], 1, every) if every > 1 else acc[:, 2]

        class R:                                   # what bpfo_line reads
            acceleration = np.stack([a, a, a], axis=1)
            time = np.arange(a.size) * 1e-4
            fs = 1e4
            config = cfg
        out.append(("leapfrog" if mode == 0 else "imex", dt, theta, wall,
                    *(bpfo_line(R) if ok and np.all(np.isfinite(a)) else (None, None))))
    return out


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
    dur = 1.0
    print(f"\n| rig, {dur:g} s | method | dt s | wall s | simulated s per wall s | RMS m/s^2 | "
          "vs RK4 1e-5 | BPFO line m/s^2 | vs RK4 1e-5 |\n" + "| --- " * 9 + "|")
    ref = {}
    for label, method, dt, wall, rms, line in rig_speed(dur):
        if wall is None:
            print(f"| {label} | {method} | {dt:g} | diverged | | | | | |")
            continue
        ref.setdefault(label, (rms, line))
        r0, l0 = ref[label]
        print(f"| {label} | {method} | {dt:g} | {wall:.2f} | {dur / wall:.2f} | {rms:.3f} | "
              f"{100 * (rms / r0 - 1):+.1f} % | {line:.3f} | {100 * (line / l0 - 1):+.1f} % |", flush=True)
    print("\nthe implicit kick's order, calibrated damping (1e-4 s x stiffness), 0.3 s:\n"
          "| method | dt s | theta | wall s per simulated s | RMS vs reference | BPFO line vs reference |\n"
          "| --- | --- | --- | --- | --- | --- |")
    rows = implicit_order()
    r0, l0 = rows[0][4], rows[0][5]
    for method, dt, theta, wall, rms, line in rows:
        tail = ("runs away | |" if rms is None else
                f"{100 * (rms / r0 - 1):+.2f} % | {100 * (line / l0 - 1):+.2f} % |")
        print(f"| {method} | {dt:.3g} | {theta:g} | {wall / 0.3:.1f} | {tail}", flush=True)
    print(f"\npeak resident memory: {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB")
    print("\n| damping law | contact | load N | k_lin N/m | damping ratio | RK4 step limit s |\n"
          "| --- | --- | --- | --- | --- | --- |")
    for law, name, Q, k, z, lim in damping_table():
        print(f"| {law} | {name} | {Q:g} | {k:.2e} | {z:.3g} | {lim:.1e} |")


if __name__ == "__main__":
    main()
