"""The pseudo-fault in curves (issue 69, item 6): the validation case (48 km/h, the 2 mm outer-ring
defect in the gearbox-side (right) bearing of wheelset 2, eight DTRBs, as shipped) on tangent
track and in the circular part of the shipped 300 m curves, left-hand (the defect on the
outer-rail side) and right-hand (on the inner-rail side), at the equilibrium speed (91 mm cant)
and with 0.49 m/s^2 unbalanced (15 mm), each diagnosed as ``axlebox diagnose`` does with the
criterion unchanged.  Each curve run starts with the whole car in the circular part (track.start
80 m: the rear wheelset 66 m along, past the 65 m of tangent and transition), where the statics
set it at rest on its track frames, so its whole record is the steady curve.

Printed per case: each side's verdict, the fault named and sized, the defect side's and the
other side's RMS, the lag and who leads; the defect bearing's rows' axial loads, radial loads and
load zone centres beside the healthy side's, and the leading wheelset's Y/Q margin to Nadal.

    python3 benchmarks/curve_pseudo_fault.py [--out DIR] [--duration S]

Results are kept in ``--out`` (default ./curve_pseudo_fault): a case whose file is complete is
read, not run again.
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from axlebox.bearing import resultfile
from axlebox.pipelines import curving
from axlebox.pipelines import simulate as ps
from axlebox.pipelines.report import case_parameters, diagnosed_case

CASES = [("tangent", "validation_48kmh", {}),
         ("300 m left, equilibrium", "curve_300m_left_equilibrium", {"track": {"start": 80.0}}),
         ("300 m left, 0.49 m/s^2", "curve_300m_left_unbalanced", {"track": {"start": 80.0}}),
         ("300 m right, equilibrium", "curve_300m_right_equilibrium", {"track": {"start": 80.0}}),
         ("300 m right, 0.49 m/s^2", "curve_300m_right_unbalanced", {"track": {"start": 80.0}})]


def _status(path: Path) -> tuple[str, str] | None:
    """A finished run's status and message (a run that stopped, say derailed, is finished too);
    None where there is no whole result file yet."""
    try:
        with resultfile.reading(path) as f:
            return str(f.attrs.get("status", "")), str(f.attrs.get("message", ""))
    except Exception:                                   # noqa: BLE001 - absent or partial: run it
        return None


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="curve_pseudo_fault")
    ap.add_argument("--duration", type=float, default=2.0)
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for label, config, over in CASES:
        path = out / f"{config}.h5"
        if _status(path) is None:
            t0 = time.perf_counter()
            ps.run(config, path, a.duration, log=lambda *_: None, overrides=over)
            print(f"{label}: {a.duration:g} s simulated in {time.perf_counter() - t0:.0f} s wall",
                  flush=True)
        status, message = _status(path)
        if status != "done":
            print(f"{label}: {status}: {message}", flush=True)
            continue
        speed, width, side = case_parameters(path)
        case = diagnosed_case(path, speed, width, side, lambda *_: None)
        r = case.row()
        c = curving.table(path)
        rb = {b.name: b for b in c.bearings}
        ws1 = min(w.margin for w in c.wheels if w.name.startswith("ws1_"))
        rows.append((label, r, rb["bearing2R"], rb["bearing2L"], ws1))
    print("\n| case | left (healthy) | right (defect) | fault, size | RMS right / left m/s^2 | lag, leads "
          "| defect bearing rows: axial kN, radial kN, zone deg | healthy side's | ws1 to Nadal |")
    print("|---|---|---|---|---|---|---|---|---|")
    for label, r, d, h, m in rows:
        def rows_of(b):
            return (f"{b.axial[0] / 1e3:+.1f} / {b.axial[1] / 1e3:+.1f}; {b.radial[0] / 1e3:.1f} / "
                    f"{b.radial[1] / 1e3:.1f}; {np.degrees(b.zone[0]):+.1f} / {np.degrees(b.zone[1]):+.1f}")
        size, lo, hi = r["right_width_mm"], r["right_width_lo_mm"], r["right_width_hi_mm"]
        print(f"| {label} | {r['left_verdict']} | {r['right_verdict']} | "
              f"{r['verdict_kind_right']}, {size:.2f} mm [{lo:.2f}, {hi:.2f}] | "
              f"{r['right_rms']:.2f} / {r['left_rms']:.2f} | {1e3 * r['lag_s']:.2f} ms, {r['leading']} | "
              f"{rows_of(d)} | {rows_of(h)} | {100 * m:.0f} % |")


if __name__ == "__main__":
    main()
