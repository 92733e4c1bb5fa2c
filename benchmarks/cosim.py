"""The paper's co-simulation: the study's 3 mm cases with the bearings exchanged every 1e-4 s.

    python3 benchmarks/cosim.py --out DIR [--hold zoh|linear] [--reference STUDY_DIR] [--workers 2]

The paper coupled its SIMPACK car to its Simulink DTRB through SIMAT, exchanging every 1e-4 s
(its Fig. 6; the DTRB by Runge-Kutta at 1e-4 s).  Here: the shipped study config with
``[coupling] exchange_dt = 1e-4``, the bodies in ten steps of 1e-5 s an exchange with the
bearings' loads held (``body_substeps = 10``, ``hold``; mbs/kernel/exchange.py "Co-simulation"), the
bearings in their own 5e-6 s sub-steps; outputs at 10 kHz through the ideal sensor (an exchange
of 1e-4 s cannot feed the sensor model's 50 kHz).  The cases run as ``axlebox sweep`` runs them
(``--widths 3``, the four speeds).  For each case and side: VF over the whole record and over
the paper's 0-1 kHz band, whether the healthy side's VF is above the defect side's in each
(the paper's Fig. 14 has it so at 3 mm), the absolute criterion's verdicts over both; with
``--reference``, the same for the study's own runs (exchange 1e-5 s, bodies at 1e-5 s) beside.
"""
from __future__ import annotations

import argparse
import subprocess
import sys
import tomllib
from pathlib import Path

import tomli_w

from axlebox import configs
from axlebox.bearing.diagnostics.criterion import VF_BAND_PAPER
from axlebox.pipelines.diagnose import analyse_file

SHORT = {"real fault": "real", "pseudo-fault": "pseudo", "healthy": "healthy", "undecided": "undec."}


def config(hold: str) -> dict:
    user = tomllib.loads(configs.path("study").read_text())
    user["coupling"] = {"exchange_dt": 1e-4, "body_substeps": 10, "hold": hold}
    user["sensors"] = {"model": "ideal"}
    user["integrator"]["output_rate_hz"] = 1e4
    return user


def row(path: Path) -> str:
    _, _, pair = analyse_file(path)
    band = pair.in_vf_band(VF_BAND_PAPER)
    cells = []
    for p in (pair, band):
        higher = "yes" if p.left.VF > p.right.VF else "no"
        cells += [f"{p.right.VF / 1e4:.2f} / {p.left.VF / 1e4:.2f}", higher,
                  f"{SHORT[p.verdict.words['right']]} / {SHORT[p.verdict.words['left']]}"]
    return " | ".join(cells)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("--hold", default="zoh", choices=("zoh", "linear"))
    ap.add_argument("--reference", help="the study's own sweep folder (exchange 1e-5 s), to compare")
    ap.add_argument("--workers", default="2")
    ap.add_argument("--speeds", nargs="+", default=["20", "40", "60", "80"])
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    cfg = out / f"study_cosim_{a.hold}.toml"
    cfg.write_text(tomli_w.dumps(config(a.hold)))
    subprocess.run([sys.executable, "-m", "axlebox", "sweep", str(cfg), "--widths", "3", "--speeds",
                    *a.speeds, "--workers", a.workers, "--out", str(out)], check=True)
    print("| case | run | whole: VF defect / healthy 1e4 Hz^2 | healthy > defect | absolute: R / L "
          "| 0-1 kHz: VF defect / healthy | healthy > defect | absolute over 0-1 kHz: R / L |")
    print("|" + " --- |" * 8)
    for v in a.speeds:
        name = f"v{float(v):g}_w3.h5"
        for label, d in ((f"co-simulation 1e-4 s, {a.hold}", out),
                         ("study (exchange 1e-5 s)", Path(a.reference) if a.reference else None)):
            if d is None:
                continue
            f = d / name
            if not f.exists():
                f = next(d.glob(f"v{v}*_w3*.h5"), None)
            print(f"| {v} km/h, 3 mm | {label} | {row(f) if f else 'missing | | | | |'} |")


if __name__ == "__main__":
    main()
