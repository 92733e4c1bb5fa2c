"""The configs axlebox ships, installed with the package: ``axlebox configs`` lists them,
``axlebox configs show NAME`` prints one to copy and edit, and ``axlebox simulate`` and
``axlebox sweep`` take a name (``validation_48kmh``) wherever they take a path.

* ``vehicle``: the B-type metro motor car at 48 km/h on FRA class 5 track, stiff bushings for
  the bearings (the defaults of :mod:`axlebox.mbs.vehicle.config`)
* ``validation_48kmh``: the paper's validation case, eight DTRBs, a 50.4 x 2 x 2 mm defect
* ``field_64kmh``: the same case at 64.5 km/h, the paper's other field record (its Fig. 1b)
* ``inner_48kmh``: the same case with the defect on the inner ring (beyond the paper)
* ``accelerating_20_60kmh``: the same case accelerating from 20 to 60 km/h at 1 m/s^2, driven by
  traction torques at its wheelsets (beyond the paper)
* ``study``: the paper's study matrix (speeds x defect widths) of the car, for ``axlebox sweep``
* ``study_rig``: the same matrix on the standalone bearing rig
* ``study_fast``: the same matrix on the quasi-dynamic bearing (bearing/kernel/quasidynamic.py), for
  datasets and quick studies
* ``study_both``: defect kinds (outer, inner, roller) and sides (one, both) x speeds, beyond the paper
"""
from __future__ import annotations

import re

from importlib import resources
from pathlib import Path

from axlebox._params import ParameterError


def folder() -> Path:
    """Where the shipped configs lie (inside the installed package)."""
    return Path(str(resources.files(__name__)))


def names() -> list[str]:
    """The shipped configs' names (file names without ``.toml``), sorted."""
    return sorted(p.stem for p in folder().glob("*.toml"))


def path(name: str) -> Path:
    """The file of the shipped config ``name`` (``.toml`` may be given or left off)."""
    stem = name[:-5] if name.endswith(".toml") else name
    p = folder() / f"{stem}.toml"
    if stem not in names():
        raise ParameterError(f"config {name!r} is not a shipped config: expected one of "
                             f"{', '.join(names())} (axlebox configs), or a path to a TOML file")
    return p


def resolve(config) -> Path:
    """``config`` as a file: the path itself when it names a file, else the shipped config of
    that name; refused (naming both) when it is neither."""
    p = Path(config)
    if p.is_file():
        return p
    if p.parent == Path("."):          # a folder of that name (a sweep's --out) is no config
        try:
            return path(p.name)
        except ParameterError:
            pass
    what = "a folder" if p.is_dir() else "no such file"
    raise ParameterError(f"config = {str(config)!r} is not allowed: {what}, and not a shipped "
                         f"config ({', '.join(names())}; axlebox configs)")


def summary(name: str) -> str:
    """The first sentence of the shipped config's opening comment."""
    text = []
    for line in path(name).read_text().splitlines():
        if not line.startswith("#"):
            break
        text.append(line.lstrip("# ").rstrip())
    head = " ".join(text)
    # a sentence ends at ". " before a capital, not after an abbreviation ("Fig. 1b", "Eq. 14")
    first = re.split(r"(?<!\bFig)(?<!\bEq)(?<!\bEqs)(?<!\bet al)(?<!\bRef)\.\s+(?=[A-Z(])", head)[0]
    return first.rstrip(".") + "." if head else ""
