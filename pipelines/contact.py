"""Contact geometry of a wheel-rail pair on the command line: table, plot and equivalent conicity."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from axlebox._files import replaced
from axlebox._params import ParameterError
from axlebox.mbs.wheelrail import standard
from axlebox.mbs.wheelrail.conicity import equivalent_conicity
from axlebox.mbs.wheelrail.geometry import ContactTable, TrackLayout, contact_table
from axlebox.mbs.wheelrail.profile import Profile, read_profile

WHEELS = {"S1002": standard.s1002}
RAILS = {"UIC60": standard.uic60, "60E1": standard.uic60, "CHN60": standard.chn60}


def profile(name_or_file: str, kind: str) -> Profile:
    """A built standard profile by name, or a profile file (SIMPACK .prw/.prr or two-column mm)."""
    table = WHEELS if kind == "wheel" else RAILS
    if name_or_file.upper() in table:
        return table[name_or_file.upper()]()
    if not Path(name_or_file).is_file():
        raise ParameterError(f"--{kind} = {name_or_file!r} is not allowed: expected one of "
                             f"{', '.join(table)} or an existing profile file")
    return read_profile(name_or_file, kind)


def _write_csv(path: Path, header: list[str], rows: np.ndarray) -> None:
    with replaced(path) as tmp:
        np.savetxt(tmp, rows, delimiter=",", header=",".join(header), comments="", fmt="%.9g")


def write_table(t: ContactTable, path: Path) -> None:
    """The table as CSV, SI units, one row per lateral displacement, L and R columns."""
    cols = ["y", "roll", "z"]
    data = [t.y, t.roll, t.z]
    for name in ("y_wheel", "y_rail", "y_track", "r", "delta", "delta_wheel", "kappa_wheel_x",
                 "kappa_wheel_y", "kappa_rail_y"):
        v = getattr(t, name)
        for k, side in enumerate("LR"):
            cols.append(f"{name}_{side}")
            data.append(v[:, k])
    _write_csv(path, cols, np.column_stack(data))


def run(wheel: str, rail: str, out: str | Path, *, layout: TrackLayout, y_max: float,
        amplitudes_mm: list[float], n: int = 241) -> dict:
    """Table, figure and conicity of ``wheel`` on ``rail``; returns the conicity per method."""
    out = Path(out)
    w, r = profile(wheel, "wheel"), profile(rail, "rail")
    t = contact_table(w, r, layout, y_max=y_max, n=n)
    out.mkdir(parents=True, exist_ok=True)
    write_table(t, out / "contact_table.csv")
    A = np.asarray(amplitudes_mm, dtype=float) * 1e-3
    con = {m: equivalent_conicity(t, A, m) for m in ("harmonic", "klingel")}
    _write_csv(out / "conicity.csv", ["amplitude", "harmonic", "klingel"],
               np.column_stack([A, con["harmonic"], con["klingel"]]))
    fig = t.plot()
    with replaced(out / "contact_table.png") as tmp:
        fig.savefig(tmp, dpi=120, format="png")
    return {"amplitude": A, **con, "table": t}
