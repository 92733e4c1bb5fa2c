"""Coupled car benchmark: wall seconds per simulated second of the car with its eight DTRBs
(configs/validation_48kmh.toml), and where the time goes.

    python3 benchmarks/coupled.py [--duration 0.3] [--bodies DIR]

The profile is by subtraction over model variants with the same bodies: the right-hand side of
the car with row bushings (no bearings), with the DTRBs, rigid and flexible front bogie, and
with Shen-Hedrick-Elkins in place of FASTSIM (the tangential contact's share).  Then RK4 runs
at two steps give the rate and the axle-box RMS change between them (step convergence).
"""
from __future__ import annotations

import argparse
import resource
import sys
import time
from pathlib import Path

# this folder holds bearing.py (a benchmark): keep it from shadowing the bearing package
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != Path(__file__).resolve().parent]

from mbs import integrate  # noqa: E402
from pipelines import simulate as psim  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
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


def variant(body_dir: str, over: dict):
    over = {**over, "bodies": {**over.get("bodies", {}), "dir": body_dir}}
    cfg, _ = psim.load_config(ROOT / "configs" / "validation_48kmh.toml", overrides=over)
    return psim.build_model(cfg, log=lambda *_: None)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--duration", type=float, default=0.3)
    ap.add_argument("--bodies", default="", help="reduced-body folder (default: built into the cache)")
    a = ap.parse_args()
    prof = {}
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
    skip = int(0.05 * 1e4)
    rms = {}
    print("| dt s | wall s per simulated s | ws2_R RMS m/s^2 | ws2_L RMS m/s^2 |")
    print("| --- | --- | --- | --- |")
    for dt in (2e-5, 1e-5):
        s = integrate.Settings(method="rk4", dt=dt, output_rate_hz=1e4, state_rate_hz=100)
        integrate.simulate(model, 0.001, s, y0=y0)                  # compile outside the timing
        run = integrate.simulate(model, a.duration, s, y0=y0)
        rms[dt] = [run.sensors[n][skip:, 2].std() for n in ("ws2_R", "ws2_L")]
        print(f"| {dt:g} | {run.wall_s / a.duration:.1f} | {rms[dt][0]:.3f} | {rms[dt][1]:.3f} |")
    d = max(abs(x / y - 1) for x, y in zip(rms[2e-5], rms[1e-5])) * 100
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"axle-box RMS, 2e-5 against 1e-5 s: {d:.2f} % at most; peak memory {peak:.0f} MB; "
          f"{a.duration:g} s simulated, the first 0.05 s left out")


if __name__ == "__main__":
    main()
