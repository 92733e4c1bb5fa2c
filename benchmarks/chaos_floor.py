"""The bearing's chaos floor: how far two rig runs drift apart when their initial states differ
by one unit in the last place, and how much the figures the tests assert move with it (issue 58
item 2: the tolerances of a kernel's physical equivalence are taken from this, not from the last
bits of an older build).

    python3 benchmarks/chaos_floor.py [--runs 4]

The rig of tests/test_bearing_dynamics.py (the DTRB under 54 kN at 48 km/h, RK4 at 1e-5 s):
healthy for 1 s and with the 2 mm outer-ring defect for 0.4 s.  Run 0 starts at the quasi-static
start; run n > 0 from the same start with roller 3 n's azimuth moved by one ulp (an ulp of its
radial place vanishes in ``R + rho``).  Printed: the relative RMS difference of the outer ring's
vertical acceleration from run 0 in 2 ms windows, and each run's RMS, BPFO line (its envelope
spectrum, 500-4500 Hz, after 0.05 s) and BPFI line over the spectrum's median.
"""
from __future__ import annotations

import argparse

import numpy as np

from axlebox.bearing import rig
from axlebox.bearing.defects import Defect
from axlebox.bearing.frequencies import orders, shaft_hz
from axlebox.bearing.models.params import BearingParams
from axlebox.bearing.spectra import envelope_spectrum

F_S = shaft_hz(48.0, 0.42)
BPFO, BPFI = orders(BearingParams()).BPFO * F_S, orders(BearingParams()).BPFI * F_S
BAND, T0 = (500.0, 4500.0), 0.05
WINDOWS = (0.001, 0.002, 0.005, 0.01, 0.05, 0.1, 0.3)       # s: where the drift is read


def run(cfg: rig.RigConfig, nudge: int) -> rig.RigResult:
    """The rig from its quasi-static start, roller ``3 nudge``'s azimuth one ulp on (none for 0)."""
    start = rig.initial_state

    def nudged(c):
        Y, P, D, r = start(c)
        if nudge:
            i = 12 * 3 * nudge + 1                 # bearing/kernel/layout.py: roller 3 n's PHI
            Y[i] = np.nextafter(Y[i], np.inf)
        return Y, P, D, r
    rig.initial_state = nudged
    try:
        return rig.simulate(cfg)
    finally:
        rig.initial_state = start


def figures(res: rig.RigResult) -> dict:
    a = res.acceleration[res.time >= T0, 2]
    f, A = envelope_spectrum(a, res.fs, BAND)
    floor = np.median(A[(f > 1) & (f < 300)])

    def line(fq):
        return A[np.abs(f - fq) <= 1.5 * f[1]].max()
    return {"rms": a.std(), "bpfo": line(BPFO), "bpfo_floor": line(BPFO) / floor,
            "bpfi_floor": line(BPFI) / floor}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=4, help="runs a case, the first not nudged")
    n = ap.parse_args().runs
    cases = {"healthy": rig.RigConfig(duration=1.0),
             "outer-ring defect": rig.RigConfig(duration=0.4, defects=(Defect(W=2e-3),))}
    for name, cfg in cases.items():
        res = [run(cfg, k) for k in range(n)]
        t, a0 = res[0].time, res[0].acceleration[:, 2]
        print(f"## {name}\n\nrelative RMS difference from run 0 in 2 ms windows at "
              + ", ".join(f"{w * 1e3:g}" for w in WINDOWS) + " ms:")
        for k in range(1, n):
            d = res[k].acceleration[:, 2] - a0
            rel = []
            for w in WINDOWS:
                m = (t >= w) & (t < w + 0.002)
                rel.append(np.sqrt(np.mean(d[m] ** 2) / np.mean(a0[m] ** 2)))
            print(f"  run {k}: " + " ".join(f"{r:.1e}" for r in rel))
        print("\n| run | RMS m/s^2 | BPFO line m/s^2 | BPFO / floor | BPFI / floor |")
        print("| --- | --- | --- | --- | --- |")
        for k, r in enumerate(res):
            g = figures(r)
            print(f"| {k} | {g['rms']:.4f} | {g['bpfo']:.4f} | {g['bpfo_floor']:.1f} | "
                  f"{g['bpfi_floor']:.2f} |")
        print()


if __name__ == "__main__":
    main()
