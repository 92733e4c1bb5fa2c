"""How the cost grows, so that a user can plan a study: wall time and peak memory of one DTRB on
the rig (RK4 and the leapfrog), one wheelset with its two DTRBs in the car
(``joint.wheelsets = [2]``), the car without bearings, and the car with its eight, for 1, 2, 4
and 8 simulated seconds, the car as ``axlebox simulate`` runs it (outputs streamed to disk,
the acquisition chain, the result file) for 1 and 4, and the rig and the car on the
quasi-dynamic bearing (configs/study_fast's step, 5e-5 s) for 1 and 1, 2, 4.

    python3 benchmarks/growth.py [--durations 1 2 4 8] [--streamed 1 4] [--quasi 1 2 4] [--only-car]
                                 [--bodies DIR]

Every case runs in a fresh process (peak memory is a process's own): the shipped configs
(configs/validation_48kmh.toml with its integrator for the coupled cases, configs/vehicle.toml
for the car without bearings, the rig's defaults with the 2 mm defect), all cores numba has.
"Run" is the integration alone (the rig's includes loading its kernels from numba's cache, and
compiling them in the first process after a change to their source: run the table twice after
one); "process" adds the Python start, the model's build and statics and loading the compiled
kernels from numba's cache (the first run on a machine also compiles).
"""
from __future__ import annotations

import argparse
import json
import math
import resource
import subprocess
import sys
import time

CASES = ("rig: one DTRB", "car: wheelset 2 on two DTRBs", "car: no bearings (row bushings)",
         "car: eight DTRBs", "rig: one DTRB, leapfrog",
         "car: eight DTRBs, axlebox simulate (streamed)",
         "rig: one quasi-dynamic DTRB", "car: eight quasi-dynamic DTRBs (study_fast's step)")


def _steps(s) -> str:
    """The integrator and its step(s): the bodies' exchange step too where it is not dt."""
    return f"{s.method} {s.dt:g}" + (f", exchange {s.step:g}" if s.step != s.dt else "")


def one(case: str, duration: float, bodies: str) -> dict:
    t0 = time.perf_counter()
    if case in (CASES[0], CASES[4], CASES[6]):
        from axlebox.bearing.defects import Defect
        from axlebox.bearing.models.params import BearingParams
        from axlebox.bearing.rig import RigConfig, simulate
        quasi = {"bearing": BearingParams(model="quasi-dynamic"), "dt": 5e-5} if case == CASES[6] else {}
        c = RigConfig(duration=duration, defects=(Defect(W=2e-3),),
                      method="rk4" if case == CASES[0] else "leapfrog", **quasi)
        t1 = time.perf_counter()
        simulate(c)
        run_s, steps = time.perf_counter() - t1, f"{c.method} {c.dt:g}"
        states = None
    else:
        from axlebox import configs
        from axlebox.mbs.solver import integrate
        from axlebox.pipelines import simulate as psim
        over = {"bodies": {"dir": bodies}}
        name = "validation_48kmh"
        if case == CASES[1]:
            over["joint"] = {"wheelsets": [2]}
        elif case == CASES[7]:          # configs/study_fast's bearing and step
            over.update(bearing={"model": "quasi-dynamic"}, coupling={"exchange_dt": 0.0},
                        integrator={"method": "leapfrog", "dt": 5e-5, "output_rate_hz": 20000.0})
        elif case == CASES[2]:
            name = "vehicle"
            over["bodies"]["flexible"] = ["frame1", "ws1", "ws2", "ab1L", "ab1R", "ab2L", "ab2R"]
        # the track as long as the run needs (the shipped configs' 400 m hold about 28 s)
        short = psim.load_config(configs.path(name), overrides=over)
        over["track"] = {"length": max(short.track.length, math.ceil(short.track_needed(duration)))}
        cfg = psim.load_config(configs.path(name), duration=duration, overrides=over)
        s = cfg.settings()
        if case == CASES[5]:              # the command: outputs streamed, acquisition, file
            import tempfile
            with tempfile.TemporaryDirectory() as tmp:
                run = psim.run(configs.path(name), f"{tmp}/run.h5", duration=duration,
                               overrides=over, log=lambda *_: None)
            return {"case": case, "duration": duration, "run_s": run.wall_s,
                    "steps": _steps(s), "states": None,
                    "process_s": time.perf_counter() - t0,
                    "peak_MB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}
        model, y0 = psim.build_model(cfg, log=lambda *_: None)
        run = integrate.simulate(model, duration, s, y0=y0)
        if not run.ok:
            raise SystemExit(f"{case}: {run.message}")
        run_s, steps, states = run.wall_s, _steps(s), model.n_states
    return {"case": case, "duration": duration, "run_s": run_s, "steps": steps, "states": states,
            "process_s": time.perf_counter() - t0,
            "peak_MB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--durations", type=float, nargs="*", default=[1.0, 2.0, 4.0, 8.0],
                    help="simulated seconds of the eight-DTRB car")
    ap.add_argument("--streamed", type=float, nargs="*", default=[1.0, 4.0],
                    help="simulated seconds of the car run as `axlebox simulate` runs it (streamed)")
    ap.add_argument("--quasi", type=float, nargs="*", default=[1.0, 2.0, 4.0],
                    help="simulated seconds of the car on quasi-dynamic bearings")
    ap.add_argument("--only-car", action="store_true", help="leave out the rig and the partial cars")
    ap.add_argument("--bodies", default="", help="reduced-body folder (default: built into the cache)")
    ap.add_argument("--one", nargs=2, metavar=("CASE", "DURATION"), help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.one:
        print(json.dumps(one(CASES[int(a.one[0])], float(a.one[1]), a.bodies)))
        return
    todo = ([] if a.only_car else [(0, 1.0), (4, 1.0), (6, 1.0), (1, 1.0), (2, 1.0)]) + \
        [(3, d) for d in a.durations] + [(5, d) for d in a.streamed] + [(7, d) for d in a.quasi]
    print("| case | integrator, dt s | states | simulated s | run wall s | wall s per simulated s | "
          "process wall s | peak memory MB |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for c, d in todo:
        p = subprocess.run([sys.executable, __file__, "--one", str(c), str(d), "--bodies", a.bodies],
                           capture_output=True, text=True)
        if p.returncode:
            print(f"| {CASES[c]} | failed: {(p.stderr or p.stdout).strip().splitlines()[-1]} |")
            continue
        r = json.loads(p.stdout.strip().splitlines()[-1])
        print(f"| {r['case']} | {r['steps']} | {r['states'] or '-'} | {d:g} | {r['run_s']:.1f} | "
              f"{r['run_s'] / d:.2f} | {r['process_s']:.0f} | {r['peak_MB']:.0f} |", flush=True)


if __name__ == "__main__":
    main()
