"""``axlebox demo``: the main job, end to end, in a few minutes on a laptop-class machine.

1. Modal bodies: the wheelset, axle-box and bogie frame meshed (coarse), reduced
   (Craig-Bampton) and written to ``OUT/bodies`` (reused when already there); their mode shapes
   rendered off-screen into ``OUT/modes``.
2. The paper's validation case (the shipped config ``validation_48kmh``: 48 km/h, FRA class 5, a
   50.4 x 2 x 2 mm outer-ring defect in row 2 of wheelset 2's gearbox-side bearing, all eight
   bearings DTRBs, the front bogie flexible), shortened to ``duration``: ``OUT/validation.h5``.
3. Both sides of wheelset 2 diagnosed (``axlebox diagnose``): ``OUT/diagnosis.json``.
4. The report (``axlebox report``) with the mode shapes: ``OUT/report/index.html``.
"""
from __future__ import annotations

import math
import time
from pathlib import Path

from axlebox import configs
from axlebox._params import ParameterError

from .bodies import BODIES, build_body

N_MODES = 12


def min_duration() -> float:
    """The shortest validation run the diagnosis takes, rounded up to 10 ms: the track's fade-in,
    then two periods of the cage (FTF) line, the lowest it resolves (1.41 s at 48 km/h)."""
    from axlebox.bearing.frequencies import orders, shaft_hz
    from axlebox.mbs import config as vconfig
    from axlebox.mbs import dtrb

    from .readers import TRACK_FADE_IN_S
    cfg, _ = vconfig.load(configs.path("validation_48kmh"))
    ftf = orders(dtrb.params(cfg)).FTF * shaft_hz(cfg["run"]["speed_kmh"], cfg["wheelset"]["r0"])
    return math.ceil(100 * (TRACK_FADE_IN_S + 2.0 / ftf)) / 100


def demo(out="axlebox-demo", duration: float = 1.6, log=print) -> Path:
    """Run the four steps into ``out``; returns the report page.  ``duration`` (s) of the
    validation case: at least :func:`min_duration`."""
    from . import diagnose, render, report, simulate
    shortest = min_duration()
    if not duration >= shortest:
        raise ParameterError(f"--duration = {duration!r} is not allowed: expected at least "
                             f"{shortest:g} s (the track's fade-in, then two cage periods for the "
                             "diagnosis)")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    for name, spec in BODIES.items():
        build_body(name, mesh_size=spec.coarse_mesh_size, n_modes=N_MODES, n_reference=0,
                   out_dir=out / "bodies", log=log)
    render.report(out / "bodies", out / "modes", max_modes=N_MODES, log=log)
    log(f"demo: modal bodies and mode shapes in {time.perf_counter() - t0:.0f} s")
    result = out / "validation.h5"
    simulate.run(configs.path("validation_48kmh"), result, duration=duration, log=log,
                 overrides={"bodies": {"dir": str(out / "bodies"), "modes": N_MODES}})
    pair = diagnose.run(result, json_out=out / "diagnosis.json", log=log)
    page = report.report(result, out / "report", modes_dir=out / "modes", log=log)
    log(f"demo: defect side (ws2_R) {pair.verdicts['right'][0]}, healthy side (ws2_L) "
        f"{pair.verdicts['left'][0]}; {time.perf_counter() - t0:.0f} s in all; open {page}")
    return page
