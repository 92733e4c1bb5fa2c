"""What a wheel flat and a polygonal wheel do to the diagnosis: the confounders sweep's verdicts
and envelope spectra.

    axlebox sweep confounders --workers 2 --out DIR
    python3 benchmarks/confounders.py DIR [--figure PNG]

Prints one row per case (speed, bearing defect, wheel defect): both sides' verdicts, the rule,
the bearing lines and the wheel's lines each side shows, the wheel's strikes blanked
(bearing/diagnostics/gate.py), the RMS of what was read; and whether it meets the issue's
test (no bearing fault called without the bearing defect; defect side real and the other
pseudo with it).  The figure: the cases with the bearing defect, each side's envelope spectrum
in shaft orders (0-40), BPFO's harmonics dashed, the wheel's orders named by the diagnosis
dotted.
"""
from __future__ import annotations

import argparse
from axlebox.mbs.vehicle import config as vconfig
from pathlib import Path


from axlebox.bearing import resultfile
from axlebox.pipelines.diagnose import analyse_file

FAULTY = ("real fault", "pseudo-fault", "faults on both sides")


def case_of(path: Path) -> tuple[float, bool, str]:
    with resultfile.reading(path) as f:
        cfg = vconfig.loads(str(f.attrs["config"]), str(path))
    wd = cfg.wheel_defects
    return (cfg.run.speed_kmh, bool(cfg.defects), (wd[0].name or wd[0].kind) if wd else "none")


def blanked(g) -> str:
    if g is None:
        return "-"
    return (f"{1e3 * (g.before_s + g.after_s):.3g} of {1e3 * g.turn_s:.3g} ms a turn "
            f"(fold {g.ratio:.3g})")


def meets(defect: bool, words: dict) -> bool:
    if defect:
        return (words["right"], words["left"]) == ("real fault", "pseudo-fault")
    return not any(w in FAULTY for w in words.values())


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("folder")
    ap.add_argument("--figure", default="benchmarks/figures/confounders.png")
    a = ap.parse_args()
    rows = []
    for p in sorted(Path(a.folder).glob("v*.h5")):
        if ".partial" in p.name or ".stream" in p.name:
            continue
        speed, defect, wheel = case_of(p)
        _, _, pair = analyse_file(p)
        rows.append((speed, defect, wheel, pair))
    order = {"none": 0}
    rows.sort(key=lambda r: (r[1], r[0], order.get(r[2], 1), r[2]))
    print("| km/h | bearing defect | wheel | verdict R / L | rule | bearing lines R / L | "
          "wheel lines R / L | strikes blanked | RMS R / L m/s^2 read | meets |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    from axlebox.bearing.diagnostics.wheel import text
    for speed, defect, wheel, p in rows:
        w = p.verdict.words
        print(f"| {speed:g} | {'yes' if defect else 'no'} | {wheel} | {w['right']} / {w['left']} | "
              f"{p.verdict.rule} | {' '.join(p.right.detected) or '-'} / "
              f"{' '.join(p.left.detected) or '-'} | "
              f"{text(p.right.wheel_env, p.right.wheel_spec) or '-'} / "
              f"{text(p.left.wheel_env, p.left.wheel_spec) or '-'} | {blanked(p.gate)} | "
              f"{p.right.rms:.3g} / {p.left.rms:.3g} | {'yes' if meets(defect, w) else '**no**'} |")
    shown = [r for r in rows if r[1]]
    if not shown:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    speeds = sorted({r[0] for r in shown})
    wheels = sorted({r[2] for r in shown}, key=lambda n: (order.get(n, 1), n))
    fig, axes = plt.subplots(len(speeds), len(wheels), figsize=(4.2 * len(wheels), 3.0 * len(speeds)),
                             squeeze=False, sharex=True)
    for speed, _, wheel, p in shown:
        ax = axes[speeds.index(speed), wheels.index(wheel)]
        fw = p.right.shaft_hz
        for c, label in ((p.right, "defect side R"), (p.left, "healthy side L")):
            k = c.env_f / fw <= 40
            ax.semilogy(c.env_f[k] / fw, c.env_A[k], lw=0.7, label=label)
        bpfo = p.right.fault_hz["BPFO"] / fw
        for h in range(1, 5):
            ax.axvline(h * bpfo, color="k", ls="--", lw=0.5)
        for k in sorted(set(p.right.wheel_env + p.right.wheel_spec + p.left.wheel_env + p.left.wheel_spec)):
            ax.axvline(k, color="tab:red", ls=":", lw=0.8)
        w = p.verdict.words
        ax.set_title(f"{speed:g} km/h, wheel: {wheel}\nR {w['right']}, L {w['left']}", fontsize=8)
        ax.tick_params(labelsize=7)
    for ax in axes[-1]:
        ax.set_xlabel("envelope frequency / wheel rate", fontsize=8)
    axes[0, 0].legend(fontsize=7)
    fig.suptitle("with the bearing defect: the envelope spectra as read (a flat's strikes blanked "
                 "first); dashed: BPFO (8.72) and its harmonics, dotted: the wheel's lines named",
                 fontsize=9)
    fig.tight_layout()
    Path(a.figure).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(a.figure, dpi=90)
    print(f"wrote {a.figure}")


if __name__ == "__main__":
    main()
