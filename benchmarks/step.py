"""The coupled car's step against the scheme: stability and what the diagnosis reads.

    python3 benchmarks/step.py [--duration 1.5] [--runs imex:5e-6 imex:5e-6:5e-5 imex2:1e-5 qd:5e-5 ...]

The validation case (configs/validation_48kmh.toml, front bogie flexible, coarse bodies; the
integrator's own 10 kHz output, no sensor model) by each ``method:dt[:exchange_dt]`` (the
bearings' step, and the bodies' step and exchange, mbs/kernel/exchange.py; default dt), bypassing the
configs' step limits: whether it runs, wall seconds per simulated second, and after the 0.5 s
fade-in the defect-side (ws2_R) and healthy-side RMS, the defect side's BPFO envelope line, its
largest |a|, the healthy side's lag behind it (impulse by impulse, broadband: what the
diagnosis' lag reads first) and both sides' FC and VF (paper Eq. 17-18, 0-5 kHz; and VF over the
paper's band, 0-1 kHz, bearing/diagnostics/criterion.py), each against
the first run's, and the defect bearing's cage slip (its row 2 against the rolling speed of Eq. 2).
``qd:dt``: the quasi-dynamic bearing (bearing/kernel/quasidynamic.py) stepped by the leapfrog at dt.
``--perturb EPS``: each run again with +-EPS added to one roller's first
state (the rollers' chaos: what any change of the scheme moves by itself).
"""
from __future__ import annotations

import argparse

import numpy as np

from axlebox.bearing.frequencies import orders, shaft_hz
from axlebox.bearing.diagnostics.lag import impulse_lag
from axlebox.bearing.diagnostics.criterion import VF_BAND_PAPER
from axlebox.bearing.diagnostics.spectral import fc_vf
from axlebox.bearing.models.params import BearingParams
from axlebox.mbs.solver import integrate
from axlebox.pipelines.readers import TRACK_FADE_IN_S

from coupled import FRONT, bpfo_line, variant


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--duration", type=float, default=1.5, help="simulated s a run (>= 1.3)")
    ap.add_argument("--runs", nargs="+", default=["imex:5e-6", "imex:5e-6:2e-5", "imex:5e-6:5e-5",
                                                  "imex:5e-6:1e-4"])
    ap.add_argument("--bodies", default="", help="reduced-body folder (default: built into the cache)")
    ap.add_argument("--perturb", type=float, default=0.0,
                    help="also run each with +-this added to one roller's first state")
    a = ap.parse_args()
    if not a.duration >= TRACK_FADE_IN_S + 0.8:     # the BPFO line needs 0.8 s after the fade-in
        ap.error(f"--duration {a.duration:g} is not allowed: expected at least "
                 f"{TRACK_FADE_IN_S + 0.8:g} s")
    try:
        runs = [(r.split(":")[0], float(r.split(":")[1]), float(r.split(":")[2]) if r.count(":") == 2
                 else 0.0) for r in a.runs]
    except (IndexError, ValueError):
        ap.error(f"--runs {' '.join(a.runs)!r} is not allowed: expected method:dt[:exchange_dt], e.g. "
                 "imex:5e-6:5e-5")
    models = {}

    def model_for(quasi):
        if quasi not in models:
            over = {"bodies": {"flexible": FRONT}}
            if quasi:
                over["bearing"] = {"model": "quasi-dynamic"}
            models[quasi] = variant(a.bodies, over)
        return models[quasi]
    model, y0 = model_for(False)
    bp, f_s = BearingParams(), shaft_hz(48.0, 0.42)
    f_cage = 0.5 * (1 - bp.gamma) * f_s                  # paper Eq. 2 (bearing/kernel/layout.py RATIO), Hz
    i_defect = model.bearing_names.index("bearing2R")
    fs = 1e4
    skip = int(TRACK_FADE_IN_S * fs)
    bpfo = orders(bp).BPFO * f_s
    print("| method | dt s | exchange s | status | wall s per simulated s | ws2_R RMS | ws2_L RMS | "
          "ws2_R BPFO line | ws2_R peak | lag ms | FC R / L Hz | VF R / L Hz^2 | cage slip % | "
          "against the first | VF R / L over 0-1 kHz, difference Hz^2 |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    ref = None
    first = int(model.S.br_i[0, 3])                  # the first bearing's first roller state
    for (method, dt, H), eps in ((run, e) for run in runs
                                 for e in ((0.0, a.perturb, -a.perturb) if a.perturb else (0.0,))):
        model, y0 = model_for(method == "qd")
        s = integrate.Settings(method="leapfrog" if method == "qd" else method, dt=dt, output_rate_hz=fs,
                               state_rate_hz=100, exchange_dt=H)
        integrate.simulate(model, 0.001, s, y0=y0)                  # compile outside the timing
        y = y0.copy()
        y[first] += eps
        r = integrate.simulate(model, a.duration, s, y0=y)
        if eps:
            method = f"{method} ({eps:+g})"
        if r.status != "done":
            print(f"| {method} | {dt:g} | {H or dt:g} | {r.status}: {r.message} | | | | | | | | | | |",
                  flush=True)
            continue
        R, L = (r.sensors[n][skip:, 2] for n in ("ws2_R", "ws2_L"))
        lag = impulse_lag(R, L, fs, 1.0 / bpfo).delay_b_samples / fs * 1e3
        (fcR, vfR, _), (fcL, vfL, _) = fc_vf(R, fs), fc_vf(L, fs)
        bR, bL = fc_vf(R, fs, None, VF_BAND_PAPER)[1], fc_vf(L, fs, None, VF_BAND_PAPER)[1]
        rate = r.bearings[skip:, i_defect, 2, 5].mean() / (2 * np.pi)     # row 2's cage, Hz
        slip = (1 - rate / f_cage) * 100
        x = (R.std(), L.std(), bpfo_line(R, fs, bpfo), abs(R).max(), lag, fcR, fcL, vfR, vfL)
        ref = ref or x
        diff = ", ".join(f"{(v / w - 1) * 100:+.1f} %" for v, w in zip(x, ref))
        print(f"| {method} | {dt:g} | {H or dt:g} | done | {r.wall_s / a.duration:.1f} | {x[0]:.3f} | "
              f"{x[1]:.3f} | {x[2]:.3f} | {x[3]:.1f} | {x[4]:.3f} | {fcR:.0f} / {fcL:.0f} | "
              f"{vfR:.3g} / {vfL:.3g} | {slip:.2f} | {diff} | {bR:.3g} / {bL:.3g}, {abs(bR - bL):.3g} |",
              flush=True)


if __name__ == "__main__":
    main()
