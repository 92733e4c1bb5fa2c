"""``axlebox demo``: the main job, end to end, in a few minutes on a laptop-class machine.

1. Modal bodies: the wheelset, axle-box and bogie frame meshed (coarse), reduced
   (Craig-Bampton) and written to ``OUT/bodies`` (reused when already there); their mode shapes
   rendered off-screen into ``OUT/modes``.
2. The paper's validation case (``configs/validation_48kmh.toml``: 48 km/h, FRA class 5, a
   50.4 x 2 x 2 mm outer-ring defect in row 2 of wheelset 2's gearbox-side bearing, all eight
   bearings DTRBs, the front bogie flexible), shortened to ``duration``: ``OUT/validation.h5``.
3. Both sides of wheelset 2 diagnosed (``axlebox diagnose``): ``OUT/diagnosis.json``.
4. The report (``axlebox report``) with the mode shapes: ``OUT/report/index.html``.
"""
from __future__ import annotations

import time
from pathlib import Path

from geometry._params import ParameterError

from .bodies import BODIES, build_body

ROOT = Path(__file__).resolve().parents[1]
VALIDATION = ROOT / "configs" / "validation_48kmh.toml"
N_MODES = 12


def demo(out="axlebox-demo", duration: float = 1.6, log=print) -> Path:
    """Run the four steps into ``out``; returns the report page.  ``duration`` (s) must leave
    0.9 s after the 0.5 s track fade-in: two periods of the cage frequency, the lowest fault
    line the diagnosis resolves."""
    from . import diagnose, render, report, simulate
    if not duration >= 1.4:
        raise ParameterError(f"--duration = {duration!r} is not allowed: expected at least 1.4 s "
                             "(0.5 s of track fade-in, then two cage periods for the diagnosis)")
    if not VALIDATION.is_file():
        raise ParameterError(f"the validation config {str(VALIDATION)!r} is missing: install "
                             "axlebox from its source tree (pip install -e .)")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    for name, spec in BODIES.items():
        build_body(name, mesh_size=spec.coarse_mesh_size, n_modes=N_MODES, n_reference=0,
                   out_dir=out / "bodies", log=log)
    render.report(out / "bodies", out / "modes", max_modes=N_MODES, log=log)
    log(f"demo: modal bodies and mode shapes in {time.perf_counter() - t0:.0f} s")
    result = out / "validation.h5"
    simulate.run(VALIDATION, result, duration=duration, log=log,
                 overrides={"bodies": {"dir": str(out / "bodies"), "modes": N_MODES}})
    pair = diagnose.run(result, json_out=out / "diagnosis.json", log=log)
    page = report.report(result, out / "report", modes_dir=out / "modes", log=log)
    log(f"demo: defect side (ws2_R) {pair.verdicts['right'][0]}, healthy side (ws2_L) "
        f"{pair.verdicts['left'][0]}; {time.perf_counter() - t0:.0f} s in all; open {page}")
    return page
