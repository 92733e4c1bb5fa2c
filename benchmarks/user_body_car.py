"""The car on bodies of your own (issue 59, item 5a): the built-in wheelset, axle box and bogie
frame written by gmsh as STEP with their specs (``axlebox bodies template``: each interface by
the box around the built-in surface, the gear rim by its cylinder, at the built-in reference
point), read back through ``axlebox bodies build --geometry --spec`` and put in the car as
``bodies.wheelset / axlebox / frame``.  The validation case (the defect on wheelset 2, right)
runs on them (each kind alone, then all three) and on the built-in bodies: the defect side's RMS
and its envelope's BPFO line, and the healthy side's RMS, against the 2 % that halving the
shipped step moves them (benchmarks/README.md, "The shipped (calibrated) validation case") and
against the built-in car with one ulp added to its start (the contacts' chaos: another
realisation of the same car).

    python3 benchmarks/user_body_car.py [--duration 1.5]
"""
from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

from axlebox import configs
from axlebox.bearing.frequencies import orders, shaft_hz
from axlebox.bearing.models.params import BearingParams
from axlebox.mbs.solver import integrate
from axlebox.pipelines import simulate as psim
from axlebox.pipelines.bodies import build_user_body, write_template
from axlebox.pipelines.readers import TRACK_FADE_IN_S
from coupled import bpfo_line          # benchmarks/coupled.py: the step-halving reference's line

KINDS = ("wheelset", "axlebox", "frame")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=1.5, help="simulated s (the first "
                    f"{TRACK_FADE_IN_S:g} s are left out)")
    a = ap.parse_args()
    work = Path(tempfile.mkdtemp(prefix="user-car-"))
    own = {}
    for kind in KINDS:
        t0 = time.perf_counter()
        step, spec = write_template(kind, work)
        rb, own[kind] = build_user_body(spec, geometry=step, out_dir=work, log=lambda *_: None)
        print(f"{kind}: {rb.meta['n_dof']} DOF, {len(rb.frequencies_hz)} modes, built in "
              f"{time.perf_counter() - t0:.0f} s", flush=True)
    bpfo = orders(BearingParams()).BPFO * shaft_hz(48.0, 0.42)
    mine = {k: str(v) for k, v in own.items()}
    variants = {"built-in": ({}, False),
                "built-in, one ulp on (the chaos floor)": ({}, True),
                "your own frame": ({"frame": mine["frame"]}, False),
                "your own wheelsets": ({"wheelset": mine["wheelset"]}, False),
                "your own axle boxes": ({"axlebox": mine["axlebox"]}, False),
                "all three your own": (mine, False)}
    rows = {}
    print(f"the validation case, {a.duration:g} s ({TRACK_FADE_IN_S:g}-{a.duration:g} s read)")
    print("| bodies | ws2_R RMS m/s^2 | ws2_R BPFO envelope line m/s^2 | ws2_L RMS m/s^2 | against built-in "
          "(defect RMS, BPFO line, healthy RMS) | wall s |")
    print("| --- | --- | --- | --- | --- | --- |")
    for label, (bodies, nudge) in variants.items():
        cfg = psim.load_config(configs.path("validation_48kmh"), duration=a.duration,
                               overrides={"bodies": bodies} if bodies else None)
        model, y0 = psim.build_model(cfg, log=lambda *_: None)
        if nudge:           # one ulp on the largest state: another realisation of the contacts' chaos
            y0 = y0.copy()
            i = int(np.argmax(np.abs(y0)))
            y0[i] = np.nextafter(y0[i], np.inf)
        s = cfg.settings()
        integrate.simulate(model, 0.001, s, y0=y0)                  # compile outside the timing
        run = integrate.simulate(model, a.duration, s, y0=y0)
        fs = s.output_rate_hz
        skip = int(TRACK_FADE_IN_S * fs)
        R, L = (run.sensors[n][skip:, 2] for n in ("ws2_R", "ws2_L"))
        rows[label] = r = (R.std(), bpfo_line(R, fs, bpfo), L.std())
        d = ", ".join(f"{abs(x / y - 1) * 100:.2f} %" for x, y in zip(r, rows["built-in"]))
        print(f"| {label} | {r[0]:.3f} | {r[1]:.3f} | {r[2]:.3f} | {d} | {run.wall_s:.0f} |", flush=True)
    print("halving the shipped step moves them 1.80 %, 1.25 %, 0.12 % (benchmarks/README.md)")


if __name__ == "__main__":
    main()
