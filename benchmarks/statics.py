"""A car's build, warm (kernels in numba's cache, bodies built): ``build_model`` of shipped configs,
split into the car's statics (mbs/vehicle/statics.py), the bearings' statics
(bearing/statics/equilibrium.py, each bearing's rollers by block Newton, as mbs/vehicle/bearings.py
calls it) and the rest, one
thread, best of ``--repeats``; with ``--bits FILE`` the start states are saved to FILE (first
time) or compared with it bit for bit (an optimisation must not move them).

    python3 benchmarks/statics.py [--repeats 3] [--bits start.npz] [config ...]
"""
from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from axlebox.mbs.vehicle import bearings as vbearings, statics as vstatics  # noqa: E402
from axlebox.pipelines import simulate as psim  # noqa: E402

CONFIGS = ("validation_48kmh", "accelerating_20_60kmh", "dcrb_48kmh", "vehicle", "curve_600m")


def _timed(module, name, spent):
    fn = getattr(module, name)

    def wrapped(*a, **k):
        t0 = time.perf_counter()
        try:
            return fn(*a, **k)
        finally:
            spent[name] = spent.get(name, 0.0) + time.perf_counter() - t0
    setattr(module, name, wrapped)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("configs", nargs="*", default=list(CONFIGS))
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--bits", help="an .npz of the start states: written if absent, else compared")
    a = ap.parse_args()
    spent: dict = {}
    _timed(vstatics, "equilibrium", spent)
    _timed(vbearings, "static_state", spent)
    starts = {}
    print(f"{'config':24s} {'build s':>8s} {'car statics':>12s} {'bearings':>9s} {'rest':>6s}")
    for name in a.configs:
        cfg = psim.load_config(name, duration=0.01)
        psim.build_model(cfg, log=lambda *_: None)          # the kernels loaded, the tables read
        best = None
        for _ in range(a.repeats):
            spent.clear()
            t0 = time.perf_counter()
            _, y0 = psim.build_model(cfg, log=lambda *_: None)
            row = (time.perf_counter() - t0, spent.get("equilibrium", 0.0), spent.get("static_state", 0.0))
            best = row if best is None or row[0] < best[0] else best
        starts[name] = np.asarray(y0)
        print(f"{name:24s} {best[0]:8.2f} {best[1]:12.2f} {best[2]:9.2f} {best[0] - best[1] - best[2]:6.2f}")
    if a.bits and os.path.exists(a.bits):
        ref = np.load(a.bits)
        for name, y0 in starts.items():
            same = name in ref and np.array_equal(ref[name], y0)
            print(f"{name}: start state {'the same bits' if same else 'DIFFERS'} as {a.bits}")
    elif a.bits:
        np.savez(a.bits, **starts)
        print(f"start states written to {a.bits}")


if __name__ == "__main__":
    main()
