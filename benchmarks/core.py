"""The bearing core's costs, before and after a change, side by side in one run (issue 49).

    python3 benchmarks/core.py [--before PYTHON] [--car-duration 0.3] [--repeats 3]

``--before``: an interpreter whose ``axlebox`` is the code to compare with (a checkout of the
earlier commit installed in its own environment, e.g. ``git worktree add /tmp/old b70473e``,
``python3 -m venv --system-site-packages /tmp/oldvenv``, ``/tmp/oldvenv/bin/pip install --no-deps
-e /tmp/old``); each figure is measured on both, alternating, best of ``--repeats``:

* the bearing's sub-step (``advance``; the validation bearing, the calibrated damping, under the
  car's 54 kN at 48 km/h, four sub-steps a call from Python as benchmarks/exchange.py takes
  them): microseconds a sub-step on one thread, by the explicit leapfrog, "imex" and "imex2";
* the full car (configs/validation_48kmh.toml: front bogie flexible, eight DTRBs, "imex" at
  5e-6 s, the bodies' exchange at 1e-5 s): wall seconds per simulated second on 1 and 2
  numba threads, and the serial share by Amdahl's law from the two
  (``s = (2 t_2 / t_1 - 1)``, the fraction of the one-thread time that does not divide);
* the cold start: ``axlebox simulate validation_48kmh --duration 0.01`` with an empty kernel
  cache against the same command with the cache full (the reduced bodies cached in both): the
  difference is the compile time.

Each measurement runs in a fresh process of the interpreter named (the numba threads and the
cache are per process).
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

SUBSTEP = r"""
import json, time
import numpy as np
from axlebox.bearing import defects
from axlebox.bearing.statics import equilibrium
from axlebox.bearing.models.params import BearingParams
OMEGA = 48 / 3.6 / 0.42
p = BearingParams(damping="stiffness", beta=1e-4)
D = defects.table((defects.Defect(W=2e-3),), p)
try:                                               # the bearing core of issue 49
    from axlebox.bearing.kernel import dispatch
    from axlebox.bearing import models
    from axlebox.bearing.kernel.advance import MODES, advance
    from axlebox.bearing.kernel.evaluate import work
    from axlebox.bearing.kernel.implicit import scratch
    from axlebox.bearing.kernel.quasidynamic import QD_WIDTH
    P = models.pack(p)
    tag = dispatch.tag(p)
    from axlebox.bearing.kernel import layout as _lo
    rows_sized = hasattr(_lo, "RINGS")             # the rows the model's own (issue 58)
    def step(mode):
        sc = (work(p.Z, len(y), QD_WIDTH), scratch(p.Z, p.rows) if rows_sized else scratch(p.Z))
        cages = np.zeros((p.rows, 2)) if rows_sized else np.zeros(4)
        out = (np.zeros((2, 6)), np.zeros((2, p.Z, 6)), cages)
        return lambda: advance(tag, y, ring, ring, P, D, *sc, 0.0, 5e-6, 4, False, mode, 1.0, *out)
except ImportError:                                # before it (b70473e)
    from axlebox.bearing.kernel import layout
    from axlebox.bearing.kernel.advance import MODES, advance, scratch
    P = layout.pack(p)
    def step(mode):
        sc = scratch(P, len(y), mode)
        out = (np.zeros((2, 6)), np.zeros((2, p.Z, 6)), np.zeros(4))
        return lambda: advance(y, ring, ring, P, D, 0.0, 5e-6, 4, False, mode, *out, *sc)
y0, uo = equilibrium.static_state(p, P, D, (0.0, 0.0, -54e3), OMEGA)
ring = equilibrium.ring_motion(OMEGA, uo)
res = {}
for name, mode in MODES.items():
    y = y0.copy()
    f = step(mode)
    f()
    best = float("inf")
    for _ in range(5):
        t0 = time.perf_counter()
        for _ in range(500):
            f()
        best = min(best, (time.perf_counter() - t0) / (500 * 4) * 1e6)
    res[name] = best
print(json.dumps(res))
"""

CAR = r"""
import json, sys
from axlebox import configs
from axlebox.mbs.solver import integrate
from axlebox.pipelines import simulate as psim
T = float(sys.argv[1])
cfg = psim.load_config(configs.path("validation_48kmh"), duration=T)
model, y0 = psim.build_model(cfg, log=lambda *_: None)
s = cfg.settings()
integrate.simulate(model, 0.002, s, y0=y0)                   # loads (or compiles) the kernels
print(json.dumps(min(integrate.simulate(model, T, s, y0=y0).wall_s for _ in range(2)) / T))
"""


def run(python: str, code: str, *args, threads: int | None = None) -> dict | float:
    env = dict(os.environ)
    if threads is not None:
        env["NUMBA_NUM_THREADS"] = str(threads)
    out = subprocess.run([python, "-c", code, *args], env=env, capture_output=True, text=True,
                         check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def cold_start(python: str) -> tuple[float, float]:
    """(cold, warm) wall seconds of the 0.01 s validation run, an empty kernel cache first."""
    with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as out:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        cmd = [python, "-m", "axlebox", "simulate", "validation_48kmh", "--duration", "0.01",
               "--out", os.path.join(out, "v.h5")]
        times = []
        for _ in range(2):
            t0 = time.perf_counter()
            subprocess.run(cmd, env=env, capture_output=True, check=True)
            times.append(time.perf_counter() - t0)
            os.remove(os.path.join(out, "v.h5"))
        return times[0], times[1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--before", help="an interpreter whose axlebox is the code before the change")
    ap.add_argument("--car-duration", type=float, default=0.3, help="simulated s a car run")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--skip", nargs="*", default=[], choices=("substep", "car", "cold"))
    a = ap.parse_args()
    sides = {"after": sys.executable}
    if a.before:
        sides = {"before": a.before, **sides}
    res = {k: {} for k in sides}
    for _ in range(a.repeats):
        for k, py in sides.items():
            r = res[k]
            if "substep" not in a.skip:
                for m, us in run(py, SUBSTEP).items():
                    r[f"substep {m} us"] = min(r.get(f"substep {m} us", 1e9), us)
            if "car" not in a.skip:
                for th in (1, 2):
                    w = run(py, CAR, str(a.car_duration), threads=th)
                    r[f"car {th} thread(s) wall s/s"] = min(r.get(f"car {th} thread(s) wall s/s", 1e9), w)
            print(k, json.dumps(r), flush=True)
    if "cold" not in a.skip:
        for k, py in sides.items():
            cold, warm = cold_start(py)
            res[k]["cold start s"] = cold
            res[k]["warm start s"] = warm
            res[k]["compile s"] = cold - warm
    for r in res.values():
        if "car 1 thread(s) wall s/s" in r:
            t1, t2 = r["car 1 thread(s) wall s/s"], r["car 2 thread(s) wall s/s"]
            r["serial share (Amdahl, 1 vs 2 threads)"] = 2 * t2 / t1 - 1
    keys = list(dict.fromkeys(k for r in res.values() for k in r))
    print("\n| figure | " + " | ".join(sides) + " |\n| --- |" + " --- |" * len(sides))
    for key in keys:
        print(f"| {key} | " + " | ".join(f"{res[s].get(key, float('nan')):.3g}" for s in sides) + " |")


if __name__ == "__main__":
    main()
