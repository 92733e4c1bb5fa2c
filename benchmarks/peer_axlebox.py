"""Our side of the free-wheelset peer benchmark, compared with Exudyn (``peer_exudyn.py``).

The case is ``peer_case.build_case()``: the same reduced body (18 free-free modes, modal
damping diag(2 zeta w) from the body file, which Exudyn gets as its damping matrix too), the
same load history on the tread_L master node.  Our ``Load`` element is ``F0 + A sin(w t + ph)``
on [t_on, t_off), so the Hann-windowed history is written EXACTLY as a sum of such loads:

    sin^2(pi t / T) sin(w t + ph) = 1/2 sin(w t + ph) - 1/4 sin((w + W) t + ph) - 1/4 sin((w - W) t + ph)
    sin^2(pi t / T) C             = C/2 + C/2 sin(W t - pi/2),          W = 2 pi / T

(checked numerically through the kernel's own element outputs before anything runs).

Ours: first-order generalized-alpha (Jansen-Whiting-Hulbert), h = 1e-4 s, rho_inf = 0.9, like
Exudyn's (second-order form, rho_inf 0.9, h 1e-4); RK4 rows for reference.  Timing is the wall
of ``simulate`` (the numba run; build and assembly excluded, as Exudyn's solve_s excludes its
setup), best of ``--repeat`` after a short warm-up run that pays the numba compilation.

Run: ``python3 benchmarks/peer_axlebox.py [--exudyn peer_exudyn.npz] [--repeat 3]``; when the
.npz is missing it runs ``peer_exudyn.py`` to make it (if exudyn is importable).
"""
from __future__ import annotations

import argparse
import importlib.util
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from axlebox.mbs.solver.body import flexible  # noqa: E402
from axlebox.mbs.solver.elements import Load  # noqa: E402
from axlebox.mbs.solver.integrate import Settings, simulate  # noqa: E402
from axlebox.mbs.solver.system import System  # noqa: E402

from peer_case import LoadHistory, build_case  # noqa: E402


def hann_loads(load: LoadHistory, marker: int) -> list[Load]:
    """The load history as 10 ``Load`` elements (3 per windowed sine, 1 for the windowed constant)."""
    T, W = load.t_off, 2 * np.pi / load.t_off
    parts = [(0, load.Fx, 2 * np.pi * load.fx, 0.0), (1, load.Fy, 2 * np.pi * load.fy, 0.0),
             (2, load.Fz, 2 * np.pi * load.fz, load.phz)]
    out = []
    for axis, F, w, ph in parts:
        for c, om in ((0.5, w), (-0.25, w + W), (-0.25, w - W)):
            A = np.zeros(3)
            A[axis] = c * F
            out.append(Load(f"F{'xyz'[axis]}@{om / 2 / np.pi:.0f}Hz", marker, amplitude=tuple(A),
                            omega=om, phase=ph, t_on=0.0, t_off=T))
    C = 0.5 * load.Fz_dc
    out.append(Load("Fz_dc", marker, force=(0, 0, C), amplitude=(0, 0, C), omega=W, phase=-np.pi / 2,
                    t_on=0.0, t_off=T))
    return out


def build_model(case):
    body = flexible("ws", case.body, n_modes=case.n_modes)
    w = 2 * np.pi * case.body.frequencies_hz
    # damping must be the body file's modal damping, as on Exudyn's side (diag(2 zeta w), zeta 0.01)
    assert np.allclose(body.D, np.asarray(case.body.reduced_damping)), "damping differs from the case"
    zeta = np.diag(body.D) / (2 * w)
    sysm = System(gravity=(0.0, 0.0, 0.0))
    sysm.add_body(body)                       # at rest, frame = FE origin (Exudyn: positionRef 0)
    m = sysm.marker("ws", node=case.load.interface)
    for L in hann_loads(case.load, m):
        sysm.add(L)
    return sysm.assemble(), zeta


def check_loads(model, load: LoadHistory) -> float:
    """Max |sum of our Load elements' forces (the kernel's element outputs) - load(t)| / max |F|."""
    t = np.concatenate([np.linspace(0, 1, 2001), [load.t_off - 1e-12, load.t_off, 0.1234567]])
    F = np.zeros((t.size, 3))
    for i, ti in enumerate(t):
        model.rhs(ti, model.y0)                   # fills the element outputs W[13]: force per Load
        F[i] = model.W[13][:, :3].sum(0)
    return float(np.abs(F - load(t)).max() / np.abs(load(t)).max())


def time_run(model, settings, repeat):
    simulate(model, 10 * settings.dt * settings.n_sub, settings)      # numba compile / cache load
    runs = [simulate(model, 1.0, settings) for _ in range(repeat)]
    for r in runs:
        if not r.ok:
            raise RuntimeError(f"{settings.method}: {r.message}")
    return min(runs, key=lambda r: r.wall_s), [r.wall_s for r in runs]


def rhs_cost(model, y, n=20000) -> float:
    """Seconds per call of the numba rhs at state ``y``, called from numba (no Python call
    overhead).  Take a state from the run: at rest (q = 0) the kernel skips its R q loops."""
    from numba import njit

    from axlebox.mbs.kernel.system import rhs

    @njit
    def loop(y, dy, S, W, n):
        for i in range(n):
            rhs(1e-5 * i, y, dy, S, W)
    y, dy = np.array(y, float), np.zeros(model.n_states)
    loop(y, dy, model.S, model.W, 10)
    t0 = time.perf_counter()
    loop(y, dy, model.S, model.W, n)
    return (time.perf_counter() - t0) / n


def exudyn_results(path: Path) -> dict | None:
    if not path.exists():
        if importlib.util.find_spec("exudyn") is None:
            print(f"{path} is missing and exudyn is not importable: no comparison (pip install exudyn)")
            return None
        print(f"{path} is missing: running peer_exudyn.py (about 1 min)")
        subprocess.run([sys.executable, str(HERE / "peer_exudyn.py"), str(path)], check=True)
    return dict(np.load(path, allow_pickle=False))


def compare(case, model, run, ex: dict) -> dict:
    bi = model.S[0]
    ip, n = int(bi[0, 0]), int(bi[0, 2])
    Y = run.states
    q, r = Y[:, ip + 7:ip + 7 + n], Y[:, ip:ip + 3]
    A = np.array([model.body_state(0, y)["A"] for y in Y])
    qe = ex["q"]
    assert q.shape == qe.shape and np.allclose(run.state_time, ex["t"], atol=1e-9), "time grids differ"
    rms_e = np.sqrt((qe ** 2).mean(0))
    big = np.flatnonzero(rms_e > 0.01 * rms_e.max())
    per_mode = {int(k): float(np.linalg.norm(q[:, k] - qe[:, k]) / np.linalg.norm(qe[:, k])) for k in big}
    xR, SR = case.body.node("tread_R")
    tread_R = r + np.einsum("kab,kb->ka", A, xR + q @ SR[:3].T)
    dR = np.einsum("kba,kbc->kac", A, ex["ref_rotation"])         # A_ours^T A_exu
    ang = np.arccos(np.clip((np.trace(dR, axis1=1, axis2=2) - 1) / 2, -1, 1))
    P = model.momentum(run.y_end)[0]
    J = case.load.impulse(1.0)
    return dict(
        q=q, q_rel=float(np.linalg.norm(q - qe) / np.linalg.norm(qe)), per_mode=per_mode, rms_e=rms_e,
        dr=float(np.abs(r - ex["ref_position"]).max()), r_max=float(np.abs(ex["ref_position"]).max()),
        dang=float(ang.max()), tread=float(np.abs(tread_R - ex["tread_R"]).max()),
        P=P, J=J, P_exu=ex.get("momentum_end"))


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exudyn", type=Path, default=Path("peer_exudyn.npz"), help="peer_exudyn.py output")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-rk4", action="store_true")
    a = ap.parse_args(argv)

    case = build_case()
    model, zeta = build_model(case)
    print(f"case: {case.n_modes} modes ({case.body.frequencies_hz[0]:.1f}..{case.body.frequencies_hz[-1]:.1f}"
          f" Hz), modal damping zeta {zeta.min():.4f}..{zeta.max():.4f}, {model.n_states} states, "
          f"{len(model.system.elements)} Load elements")
    err = check_loads(model, case.load)
    print(f"sum of Load elements vs Hann history: max rel. difference {err:.1e}")
    assert err < 1e-12, "the Load decomposition is wrong"

    def out_1khz(**kw):                       # Exudyn's sensors write every 1 ms: the same 1001 samples
        return Settings(output_rate_hz=1000, state_rate_hz=1000, **kw)
    rows = [("galpha", out_1khz(method="galpha", dt=1e-4, rho_inf=0.9))]
    if not a.no_rk4:     # RK4 at 2e-5 is the converged reference; at 1e-4 it is stable (w h <= 0.53)
        rows += [("rk4", out_1khz(method="rk4", dt=2e-5)), ("rk4", out_1khz(method="rk4", dt=1e-4))]
    results = []
    for name, s in rows:
        run, walls = time_run(model, s, a.repeat)
        results.append((name, s, run))
        st = run.stats
        extra = ""
        if name == "galpha":
            extra = (f"; per step: {st['newton'] / st['steps']:.2f} Newton iterations, "
                     f"{st['rhs'] / st['steps']:.2f} rhs calls; {st['jacobians']} Jacobians")
        print(f"ours {name} dt {s.dt:g}: wall {', '.join(f'{w:.3f}' for w in walls)} s{extra}")
    g = results[0][2]
    c_rhs = rhs_cost(model, g.states[250])
    print(f"rhs: {c_rhs * 1e6:.2f} us per call (numba loop, state at t = 0.25 s)")
    print(f"galpha: rhs share of the wall {g.stats['rhs'] * c_rhs / g.wall_s:.0%} "
          f"({g.stats['rhs']} calls)")

    ex = exudyn_results(a.exudyn)
    if ex is None:
        return 0
    if str(ex.get("load", "")) != repr(case.load):
        print(f"warning: {a.exudyn} was made with another load: {ex.get('load')}")
    fo, fe = case.body.frequencies_hz, ex["frequencies_hz"]
    print(f"frequencies: max |ours - Exudyn| = {np.abs(fe - fo).max():.1e} Hz"
          f" ({np.abs((fe - fo) / fo).max():.1e} relative)")
    ex_s = float(ex["solve_s"])
    print("\n| run | h s | wall s / sim s | speed-up vs Exudyn | q rel. RMS diff | max per-mode diff |")
    print("| --- | --- | --- | --- | --- | --- |")
    print(f"| Exudyn GeneralizedAlpha (rho 0.9) | 1e-4 | {ex_s:.3f} | 1.0 | - | - |")
    cmp = []
    for name, s, run in results:
        c = compare(case, model, run, ex)
        cmp.append(c)
        print(f"| ours {name}{' (rho 0.9)' if name == 'galpha' else ''} | {s.dt:g} | {run.wall_s:.3f} | "
              f"{ex_s / run.wall_s:.1f} | {c['q_rel']:.2%} | {max(c['per_mode'].values()):.2%} |")
    c = cmp[0]
    print("\ngalpha vs Exudyn, modes with RMS > 1 % of the largest (mode: RMS exu m, rel diff):")
    print("  " + ", ".join(f"{k + 1}: {c['rms_e'][k]:.2e} {v:.2%}" for k, v in c["per_mode"].items()))
    for (name, s, _), c in zip(results, cmp):
        print(f"{name} dt {s.dt:g}: frame position max diff {c['dr']:.2e} m (max |r| {c['r_max']:.2e}), "
              f"rotation max diff {c['dang']:.2e} rad, tread_R max diff {c['tread']:.2e} m")
    J = c["J"]
    for (name, s, _), c in zip(results, cmp):
        print(f"{name} dt {s.dt:g}: momentum at 1 s {np.round(c['P'], 5).tolist()} N s vs impulse "
              f"{np.round(J, 5).tolist()}: rel. diff {np.linalg.norm(c['P'] - J) / np.linalg.norm(J):.1e}")
    if c["P_exu"] is not None:
        print(f"Exudyn: momentum rel. diff {np.linalg.norm(c['P_exu'] - J) / np.linalg.norm(J):.1e}")
    if len(cmp) > 1:     # discretisation error of each run: distance from RK4 at 2e-5 (converged)
        ref = cmp[1]["q"]
        labels = [(f"ours {nm} dt {s.dt:g}", c["q"]) for (nm, s, _), c in zip(results, cmp)]
        for lab, qq in labels[:1] + labels[2:] + [("Exudyn galpha dt 1e-4", ex["q"])]:
            d = np.linalg.norm(qq - ref) / np.linalg.norm(ref)
            print(f"{lab} vs ours RK4 2e-5: q rel. RMS diff {d:.2e}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
