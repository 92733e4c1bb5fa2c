"""What the exchange between the car's bodies and its bearings costs (mbs/kernel/exchange.py).

    python3 benchmarks/exchange.py [--duration 0.3] [--exchange 2e-5]

* One bearing's sub-step (bearing/kernel/advance.py ``advance``; the validation case's bearing at its
  static state under the car's 54 kN, 48 km/h) by each mode: microseconds a sub-step, best of 5.
* The validation case (front bogie flexible, coarse bodies) with the bodies at ``--exchange``
  and the bearings at 5e-6 s ("imex"), on one thread and on two: wall seconds per simulated
  second and the speed-up.  The eight bearings of an exchange run on numba's threads with no
  synchronisation inside it, and everything else (bodies, markers, wheels) on one.
"""
from __future__ import annotations

import argparse
import time

import numba
import numpy as np

from axlebox.bearing.kernel import dispatch
from axlebox.bearing import defects, models

from axlebox.bearing.statics import equilibrium
from axlebox.bearing.kernel.advance import MODES, advance
from axlebox.bearing.kernel.evaluate import work
from axlebox.bearing.kernel.implicit import scratch
from axlebox.bearing.kernel.quasidynamic import QD_WIDTH
from axlebox.bearing.models.params import BearingParams
from axlebox.mbs.solver import integrate

from coupled import FRONT, variant

OMEGA = 48 / 3.6 / 0.42


def substep_us(mode: int, n: int = 4, calls: int = 500, repeats: int = 5) -> float:
    p = BearingParams(damping="stiffness", beta=1e-4)
    P, tag = models.pack(p), dispatch.tag(p)
    D = defects.table((defects.Defect(W=2e-3),), p)
    y, uo = equilibrium.static_state(p, P, D, (0.0, 0.0, -54e3), OMEGA)
    ring = equilibrium.ring_motion(OMEGA, uo)
    sc = (work(p.Z, y.size, QD_WIDTH), scratch(p.Z, p.rows))
    out = (np.zeros((2, 6)), np.zeros((p.rows, p.Z, 6)), np.zeros((p.rows, 2)))

    def step():
        advance(tag, y, ring, ring, P, D, *sc, 0.0, 5e-6, n, False, mode, 1.0, *out)
    step()                                                                  # compile
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(calls):
            step()
        best = min(best, (time.perf_counter() - t0) / (calls * n) * 1e6)
    return best


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--duration", type=float, default=0.3, help="simulated s a car run")
    ap.add_argument("--exchange", type=float, default=2e-5, help="the bodies' step and exchange, s")
    a = ap.parse_args()
    print("| bearing sub-step | us (one thread) |\n| --- | --- |")
    for name, mode in MODES.items():
        print(f"| {name} | {substep_us(mode):.1f} |", flush=True)
    model, y0 = variant("", {"bodies": {"flexible": FRONT}})
    s = integrate.Settings(method="imex", dt=5e-6, exchange_dt=a.exchange, output_rate_hz=1e4,
                           state_rate_hz=100)
    n_all = numba.get_num_threads()
    wall = {}
    try:
        for threads in (1, n_all):
            numba.set_num_threads(threads)
            integrate.simulate(model, 0.001, s, y0=y0)
            wall[threads] = min(integrate.simulate(model, a.duration, s, y0=y0).wall_s for _ in range(2))
    finally:
        numba.set_num_threads(n_all)
    print(f"\n| threads | wall s per simulated s (exchange {a.exchange:g} s, bearings 5e-6 s) | "
          "speed-up |\n| --- | --- | --- |")
    for threads, w in wall.items():
        print(f"| {threads} | {w / a.duration:.1f} | {wall[1] / w:.2f} |")


if __name__ == "__main__":
    main()
