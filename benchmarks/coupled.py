"""Coupled car benchmark: wall seconds per simulated second of the car with its eight DTRBs
(configs/validation_48kmh.toml), and where the time goes.

    python3 benchmarks/coupled.py [--duration 0.3] [--bodies DIR]

The profile is by subtraction over model variants with the same bodies: the right-hand side of
the car with row bushings (no bearings), with the DTRBs, rigid and flexible front bogie, and
with Shen-Hedrick-Elkins in place of FASTSIM (the tangential contact's share).  Then runs of
the validation case, each over the longer of ``--duration`` and ``--step-duration``: the
configs' imex at 1e-5 s on all numba threads and on one (same numbers expected), at 5e-6 and
2.5e-6 s (the step halved twice); they give the rate and the convergence
of what the diagnosis reads after the 0.5 s fade-in: the defect-side (ws2_R) and healthy-side
RMS and the BPFO line of the defect side's envelope spectrum.  Last, the right-hand side at the
end of the first run taken apart by stage (each stage of :func:`axlebox.mbs.kernel.system.rhs` called
alone, in numba): at the start the bearings sit in their quasi-static state, with fewer
contacts active than running.
"""
from __future__ import annotations

import argparse
import resource
import time

import numba
import numpy as np
from numba import njit

from axlebox import configs
from axlebox.bearing.diagnostics.envelope import envelope_spectrum
from axlebox.bearing.frequencies import orders, shaft_hz
from axlebox.bearing.models.params import BearingParams
from axlebox.mbs.solver import integrate
from axlebox.mbs.kernel.bearings import bearing_forces
from axlebox.mbs.kernel.body import BI_N, frame_kinematics, gravity_load, position_rates
from axlebox.mbs.kernel.elements import element_forces
from axlebox.mbs.kernel.markers import marker_acceleration, marker_kinematics, marker_loads
from axlebox.mbs.kernel.system import _accelerations
from axlebox.mbs.kernel.wheels import G_GRAV, wheel_forces
from axlebox.pipelines import simulate as psim
from axlebox.pipelines.readers import TRACK_FADE_IN_S

FRONT = ["frame1", "ws1", "ws2", "ab1L", "ab1R", "ab2L", "ab2R"]


def rhs_us(model, y0, n=200, repeats=5) -> float:
    """Best of ``repeats`` batches of ``n`` calls (the machine is shared)."""
    model.rhs(0.0, y0)
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(n):
            model.rhs(0.0, y0)
        best = min(best, (time.perf_counter() - t0) / n * 1e6)
    return best


@njit
def _stage(which, nrep, t, y, dy, S, W, B):
    """``nrep`` calls of one stage of :func:`axlebox.mbs.kernel.system.rhs` (same order, same arrays)."""
    bi = S.bi
    nb = bi.shape[0]
    for _ in range(nrep):
        if which == 0:
            for b in range(nb):
                frame_kinematics(b, y, bi, W.Ab[b], W.rb[b], W.vb[b], W.omb[b], W.omfb[b])
                position_rates(b, y, bi, W.omfb[b], dy)
            marker_kinematics(y, bi, S.mk_i, S.mk_f, S.shp, W.Ab, W.rb, W.vb, W.omfb, W.mku, W.mkp,
                              W.mkv, W.mkR, W.mkw)
        elif which == 1:
            element_forces(t, S.el_i, S.el_f, S.glob, W.mkp, W.mkv, W.mkR, W.mkw, W.mkF, W.mkM, W.elout)
        elif which == 2:
            bearing_forces(B, t, y, dy, bi, W.mkp, W.mkv, W.mkR, W.mkw, W.mkF, W.mkM, W.elout)
        elif which == 3:
            wheel_forces(t, y, bi, S.wh_i, S.wh_f, S.wtab, S.wpar, S.trk, S.wrk, S.glob, W.Ab, W.omb,
                         W.omfb, W.mkp, W.mkv, W.mkR, W.mkw, W.mkF, W.mkM, W.whout, S.line, W.frm,
                         W.fr)
        elif which == 4:
            for b in range(nb):
                n, o = bi[b, BI_N], S.goff[b]
                gravity_load(b, bi, S.bf, S.inv, y, W.Ab[b], S.glob[G_GRAV:G_GRAV + 3], W.gen[o:o + 6 + n])
            marker_loads(bi, S.mk_i, S.shp, W.Ab, W.mku, W.mkF, W.mkM, W.gen, S.goff)
            for s in range(S.sens.shape[0]):
                marker_acceleration(S.sens[s], y, dy, bi, S.mk_i, S.mk_f, S.shp, W.Ab, W.omfb, W.mku,
                                    W.sensout[s])
        else:
            _accelerations(y, dy, bi, S.bf, S.inv, S.goff, S.lane, W.Ab, W.omb, W.omfb, W.gen)


STAGES = ("frames and markers", "suspension elements", "eight DTRBs (parallel)",
          "wheel-rail contacts", "gravity, marker loads, sensors", "bodies' accelerations (parallel)")


def stages_us(model, y, t, n=2000) -> dict:
    """Best of 5 batches of ``n`` calls of each stage at state ``y`` (after a full call there)."""
    dy = np.zeros_like(y)
    model.rhs(t, y)
    out = {}
    for k, name in enumerate(STAGES):
        _stage(k, 5, t, y, dy, model.S, model.W, model.B)
        best = float("inf")
        for _ in range(5):
            t0 = time.perf_counter()
            _stage(k, n, t, y, dy, model.S, model.W, model.B)
            best = min(best, (time.perf_counter() - t0) / n * 1e6)
        out[name] = best
    return out


def bpfo_line(x, fs: float, bpfo: float) -> float:
    """The envelope spectrum's (broadband, one window) highest amplitude within 3 % of BPFO."""
    f, A = envelope_spectrum(x, fs)
    sel = np.abs(f / bpfo - 1.0) < 0.03
    return float(A[sel].max())


def variant(body_dir: str, over: dict):
    over = {**over, "bodies": {**over.get("bodies", {}), "dir": body_dir}}
    cfg = psim.load_config(configs.path("validation_48kmh"), overrides=over)
    return psim.build_model(cfg, log=lambda *_: None)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--duration", type=float, default=0.3)
    ap.add_argument("--step-duration", type=float, default=1.5,
                    help="simulated time of the step-convergence runs (s, > 0.5)")
    ap.add_argument("--bodies", default="", help="reduced-body folder (default: built into the cache)")
    a = ap.parse_args()
    T = max(a.duration, a.step_duration)
    if T <= TRACK_FADE_IN_S + 0.1:
        ap.error(f"--step-duration {a.step_duration:g} is not allowed: expected more than "
                 f"{TRACK_FADE_IN_S + 0.1:g} s (the first {TRACK_FADE_IN_S:g} s are left out)")
    prof = {}
    n_all = numba.config.NUMBA_NUM_THREADS
    numba.set_num_threads(1)          # by subtraction: one thread, or the parallel parts overlap
    for label, over in (("rigid, bushings", {"joint": {"model": "bushing"}, "defects": [],
                                             "bodies": {"flexible": []}}),
                        ("rigid, DTRBs", {"bodies": {"flexible": []}}),
                        ("flexible front, bushings", {"joint": {"model": "bushing"}, "defects": [],
                                                      "bodies": {"flexible": FRONT}}),
                        ("flexible front, DTRBs", {"bodies": {"flexible": FRONT}}),
                        ("flexible front, DTRBs, SHE", {"bodies": {"flexible": FRONT},
                                                        "wheelrail": {"law": "she"}})):
        model, y0 = variant(a.bodies, over)
        prof[label] = (model.n_states, rhs_us(model, y0))
    numba.set_num_threads(n_all)
    print("right-hand side at the start, one thread:")
    print("| model | states | RHS us |")
    print("| --- | --- | --- |")
    for k, (n, us) in prof.items():
        print(f"| {k} | {n} | {us:.0f} |")
    f = prof["flexible front, DTRBs"][1]
    print(f"where it goes (flexible front, DTRBs, {f:.0f} us): bearings "
          f"{f - prof['flexible front, bushings'][1]:.0f} us, flexible bodies "
          f"{prof['flexible front, bushings'][1] - prof['rigid, bushings'][1]:.0f} us, FASTSIM over SHE "
          f"{f - prof['flexible front, DTRBs, SHE'][1]:.0f} us, rigid car with its contacts "
          f"{prof['rigid, bushings'][1]:.0f} us")

    model, y0 = variant(a.bodies, {"bodies": {"flexible": FRONT}})
    fs = 1e4
    skip = int(TRACK_FADE_IN_S * fs)
    bpfo = orders(BearingParams()).BPFO * shaft_hz(48.0, 0.42)
    ind = {}
    print("| method | dt s | threads | wall s per simulated s | ws2_R RMS m/s^2 | ws2_L RMS m/s^2 | "
          "ws2_R BPFO envelope line m/s^2 |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for method, dt, threads in (("imex", 1e-5, n_all), ("imex", 1e-5, 1),
                                ("imex", 5e-6, n_all), ("imex", 2.5e-6, n_all)):
        numba.set_num_threads(threads)
        s = integrate.Settings(method=method, dt=dt, output_rate_hz=fs, state_rate_hz=100)
        integrate.simulate(model, 0.001, s, y0=y0)                  # compile outside the timing
        run = integrate.simulate(model, T, s, y0=y0)
        rate = run.wall_s / T
        R, L = (run.sensors[n][skip:, 2] for n in ("ws2_R", "ws2_L"))
        ind[method, dt, threads] = (R.std(), L.std(), bpfo_line(R, fs, bpfo))
        x = ind[method, dt, threads]
        print(f"| {method} | {dt:g} | {threads} ({numba.threading_layer()}) | {rate:.1f} | "
              f"{x[0]:.3f} | {x[1]:.3f} | {x[2]:.3f} |", flush=True)
        if (method, dt, threads) == ("imex", 1e-5, n_all):
            running = run.y_end.copy()
    numba.set_num_threads(n_all)
    st = stages_us(model, running, T)
    total = rhs_us(model, running)
    print(f"the right-hand side at t = {T:g} s (the bearings running, more contacts active than at "
          f"the start), {n_all} threads: {total:.0f} us a call")
    print("| stage | us | share |")
    print("| --- | --- | --- |")
    for k, us in st.items():
        print(f"| {k} | {us:.1f} | {100 * us / total:.0f} % |")

    def change(a, b):
        return ", ".join(f"{nm} {abs(x / y - 1) * 100:.2f} %" for nm, x, y in
                         zip(("defect-side RMS", "healthy-side RMS", "BPFO line"), ind[a], ind[b]))
    print(f"imex 1e-5 against 5e-6 s: {change(('imex', 1e-5, n_all), ('imex', 5e-6, n_all))}")
    print(f"imex 5e-6 against 2.5e-6 s: {change(('imex', 5e-6, n_all), ('imex', 2.5e-6, n_all))}")
    print(f"imex 1e-5 s, 1 thread against {n_all}: identical = "
          f"{ind['imex', 1e-5, 1] == ind['imex', 1e-5, n_all]}")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"({T:g} s simulated, the first {TRACK_FADE_IN_S:g} s left out); peak memory {peak:.0f} MB")


if __name__ == "__main__":
    main()
