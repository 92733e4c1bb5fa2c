"""The same bits before and after a change that should not move a number (a refactor): the car's
outputs of short runs by every integrator and coupling, kept in a file and compared bit for bit.

    python3 benchmarks/same_bits.py capture before.npz     # on the tree before the change
    python3 benchmarks/same_bits.py capture after.npz      # on the tree after it
    python3 benchmarks/same_bits.py compare before.npz after.npz

The runs (statics included, from the shipped validation case): the validation case itself (its
eight bearings, "imex", bodies at 1e-5 s exchanging with bearings at 5e-6 s) for 0.02 s; the
same car on row bushings by RK4, the leapfrog and generalized-alpha (rigid bodies); and the
co-simulation arrangement (two body steps an exchange, loads held on a line).  Every sensor,
wheel-rail, element and bearing output, every state snapshot and the last state.  Equal bits
need the same numpy, scipy and SIMD paths on both sides (tests/test_kernel_reference.py says
why); ``compare`` exits 1 naming the arrays that differ.
"""
from __future__ import annotations

import sys
import time

import numpy as np

from axlebox.pipelines import simulate as ps

BUSHINGS = {"joint": {"model": "bushing"}, "coupling": {"exchange_dt": 0.0}, "defects": []}
RUNS = {
    "validation": ({}, 0.02),
    "rk4": ({**BUSHINGS, "integrator": {"method": "rk4", "dt": 2.5e-5, "output_rate_hz": 2e4}}, 0.01),
    "leapfrog": ({**BUSHINGS, "integrator": {"method": "leapfrog", "dt": 1e-5, "output_rate_hz": 2e4}},
                 0.02),
    "galpha": ({**BUSHINGS, "integrator": {"method": "galpha", "dt": 5e-5, "output_rate_hz": 2e4},
                "bodies": {"flexible": []}}, 0.01),
    "cosim": ({"coupling": {"exchange_dt": 5e-5, "body_substeps": 2, "hold": "linear"},
               "integrator": {"output_rate_hz": 2e4}}, 0.01),
}


def capture(path: str) -> None:
    out = {}
    for tag, (over, duration) in RUNS.items():
        t0 = time.perf_counter()
        cfg = ps.load_config("validation_48kmh", duration, over or None)
        model, y0 = ps.build_model(cfg, log=lambda *_: None)
        r = ps.integrate.simulate(model, cfg.run.duration, cfg.settings(), y0=y0)
        if not r.ok:
            raise SystemExit(f"{tag}: {r.message}")
        out[f"{tag}/y0"] = y0
        out.update({f"{tag}/sens/{k}": v for k, v in r.sensors.items()})
        out.update({f"{tag}/{k}": getattr(r, k) for k in ("wheels", "elements", "states", "y_end")})
        if r.bearings is not None:
            out[f"{tag}/bearings"] = r.bearings
        print(f"{tag}: {time.perf_counter() - t0:.1f} s", file=sys.stderr, flush=True)
    np.savez(path, **out)


def compare(a: str, b: str) -> int:
    with np.load(a) as fa, np.load(b) as fb:
        names = sorted(set(fa.files) | set(fb.files))
        differ = [n for n in names if n not in fa.files or n not in fb.files
                  or not np.array_equal(fa[n], fb[n])]
    print(f"{len(names)} arrays, {len(differ)} differ" + (": " + ", ".join(differ) if differ else ""))
    return 1 if differ else 0


if __name__ == "__main__":
    args = sys.argv[1:]
    if args[:1] == ["capture"] and len(args) == 2:
        capture(args[1])
    elif args[:1] == ["compare"] and len(args) == 3:
        sys.exit(compare(args[1], args[2]))
    else:
        sys.exit("usage: same_bits.py capture OUT.npz | compare A.npz B.npz")
