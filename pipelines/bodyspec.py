"""The spec of a user's own body (``axlebox bodies build --geometry|--mesh FILE --spec SPEC.toml``):
a small TOML, every field declared here once with its type, default and meaning.

.. code-block:: toml

    [body]
    kind = "frame"              # wheelset, axlebox, frame (the car's), or flexible (any body)
    unit = "file"               # a STEP's or IGES's own; BREP and meshes: m unless mm, cm, in
    mass_kg = 1480.0            # expected mass, checked against the geometry's (0: not checked)

    [material]
    E = 2.1e11
    nu = 0.3
    rho = 7850.0

    [mesh]
    size = 0.05                 # m

    [reduction]
    method = "craig-bampton"
    modes = 20

    [interfaces.primary_1_L]    # one table an interface, by the name the car knows it by
    box = [1.0, 0.9, -0.19, 1.2, 1.1, -0.17]     # or name = "...", cylinder = [...], near = [...]
    coupling = "rbe3"
"""
from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from axlebox._params import ParameterError, choice, from_table, numbers, param, section, text
from axlebox.fem.assembly import Material
from axlebox.fem.interfaces import KINDS
from axlebox.fem.reduction import METHODS
from axlebox.geometry.select import Box, Cylinder, Named, Near

BODY_KINDS = ("wheelset", "axlebox", "frame", "flexible")
UNITS = ("file", "m", "cm", "mm", "in")
PLACES = ("name", "box", "cylinder", "near")


@section("body")
class BodyEntry:
    """What the body is."""

    kind: str = choice("flexible", BODY_KINDS, "the car's wheelset, axlebox or frame (its interfaces "
                       "are checked against the names the car attaches to), or any flexible body")
    name: str = text("", "the reduced-body file's name, <out>/<name>.h5; empty: the spec's file name")
    unit: str = choice("file", UNITS, "the file's length unit: 'file' takes a STEP's or an IGES's own "
                       "(and metres for a BREP or a mesh, which declare none)")
    mass_kg: float = param(0.0, 0.0, 1e6, "kg", "the mass expected; the geometry's must be within a "
                           "factor 1.5 of it (a part in millimetres read as metres is 1e9 too heavy); "
                           "0: not checked")


@section("mesh")
class MeshEntry:
    """How a CAD part is meshed (a mesh file is taken as it is)."""

    size: float = param(0.05, 1e-4, 10.0, "m", "the largest element edge")
    order: int = param(2, 1, 2, "-", "1: linear tetrahedra raised to quadratic after meshing; 2: "
                       "quadratic on the CAD surface")


@section("reduction")
class ReductionEntry:
    """The reduction (fem/reduction.py)."""

    method: str = choice("craig-bampton", METHODS, "Craig-Bampton (fixed-interface modes) or Guyan")
    modes: int = param(20, 0, 500, "-", "fixed-interface modes kept (Craig-Bampton)")
    fmax_hz: float = param(0.0, 0.0, 1e6, "Hz", "keep the fixed-interface modes below this instead of "
                           "a count; 0: by modes")
    zeta: float = param(0.01, 0.0, 0.5, "-", "modal damping ratio")
    n_reference: int = param(0, 0, 200, "-", "free-free modes of the full model computed to compare "
                             "the reduction with (0: none)")


@dataclass(frozen=True)
class InterfaceEntry:
    """An interface: where it is (exactly one of name, box, cylinder, near), how it couples."""

    coupling: str = choice("rbe3", KINDS, "RBE3 (the surface stays deformable) or RBE2 (rigid spider)")
    name: str = text("", "a named surface of the file: a STEP label, a gmsh physical group, an Abaqus "
                     "or Nastran node or element set")
    box: tuple = numbers((), -1e4, 1e4, "m", "xmin, ymin, zmin, xmax, ymax, zmax: the faces inside")
    cylinder: tuple = numbers((), -1e4, 1e4, "m", "x, y, z of a point on the axis, the axis' "
                              "direction, radius, length from the point: the faces on it")
    near: tuple = numbers((), -1e4, 1e4, "m", "x, y, z, distance: the faces within the distance")
    tol: float = param(1e-4, 0.0, 1.0, "m", "how far off its place a point may lie")
    position: tuple = numbers((), -1e4, 1e4, "m", "x, y, z of the master node; empty: the surface's "
                              "area centroid")

    def __post_init__(self):
        from axlebox._params import check_ranges
        check_ranges(self)

    def selection(self, where: str):
        """The place (geometry/select.py) this entry gives, refusing none or more than one."""
        given = [k for k in PLACES if getattr(self, k)]
        if len(given) != 1:
            raise ParameterError(f"{where} = {given or 'nothing'} is not allowed: expected exactly one "
                                 f"of {', '.join(PLACES)}")
        sizes = {"box": 6, "cylinder": 8, "near": 4}
        k = given[0]
        v = getattr(self, k)
        if k in sizes and len(v) != sizes[k]:
            raise ParameterError(f"{where}.{k} = {list(v)} is not allowed: expected {sizes[k]} numbers "
                                 f"({_doc(k)})")
        if len(self.position) not in (0, 3):
            raise ParameterError(f"{where}.position = {list(self.position)} is not allowed: expected "
                                 "3 numbers or none")
        if k == "name":
            return Named(v)
        if k == "box":
            if any(a > b for a, b in zip(v[:3], v[3:])):
                raise ParameterError(f"{where}.box = {list(v)} is not allowed: expected each min <= max")
            return Box(v[:3], v[3:], self.tol)
        if k == "cylinder":
            if not (v[6] > 0 and v[7] > 0 and any(v[3:6])):
                raise ParameterError(f"{where}.cylinder = {list(v)} is not allowed: expected a nonzero "
                                     "axis, a radius > 0 and a length > 0")
            return Cylinder(v[:3], v[3:6], v[6], v[7], self.tol)
        if not v[3] > 0:
            raise ParameterError(f"{where}.near = {list(v)} is not allowed: expected a distance > 0")
        return Near(v[:3], v[3])


def _doc(name: str) -> str:
    from dataclasses import fields
    return next(f.metadata["doc"] for f in fields(InterfaceEntry) if f.name == name)


@dataclass(frozen=True)
class BodySpec:
    """A whole spec: its sections and interfaces, by name."""

    body: BodyEntry = field(default_factory=BodyEntry)
    material: Material = field(default_factory=Material)
    mesh: MeshEntry = field(default_factory=MeshEntry)
    reduction: ReductionEntry = field(default_factory=ReductionEntry)
    interfaces: dict = field(default_factory=dict)      # name -> InterfaceEntry
    path: str = ""

    def selections(self) -> dict:
        return {n: e.selection(f"interfaces.{n}") for n, e in self.interfaces.items()}

    def couplings(self) -> dict:
        return {n: e.coupling for n, e in self.interfaces.items()}

    def positions(self) -> dict:
        return {n: e.position for n, e in self.interfaces.items() if e.position}

    @property
    def name(self) -> str:
        return self.body.name or Path(self.path).stem


def _interface(name: str, table) -> InterfaceEntry:
    try:
        return from_table(InterfaceEntry, table, f"interfaces.{name}")
    except ParameterError as err:               # the class's checks name it, the user knows the table
        raise ParameterError(str(err).replace("InterfaceEntry.", f"interfaces.{name}.")) from None


def load(path) -> BodySpec:
    """The spec at ``path``; a missing file, bad TOML, an unknown section or field, or a value its
    declaration refuses is one :class:`ParameterError` naming the file and the field."""
    p = Path(path)
    if not p.is_file():
        raise ParameterError(f"--spec = {str(path)!r} is not allowed: no such file")
    try:
        t = tomllib.loads(p.read_text())
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as err:
        raise ParameterError(f"{p.name}: not valid TOML ({err})") from None
    known = ("body", "material", "mesh", "reduction", "interfaces")
    for k in t:
        if k not in known:
            raise ParameterError(f"{p.name}: [{k}] is not a section of a body spec: expected "
                                 f"{', '.join(known)}")
    try:
        itf = t.get("interfaces", {})
        if not isinstance(itf, dict) or not itf:
            raise ParameterError("interfaces = {} is not allowed: expected at least one "
                                 "[interfaces.NAME] table")
        spec = BodySpec(from_table(BodyEntry, t.get("body", {}), "body"),
                        from_table(Material, t.get("material", {}), "material"),
                        from_table(MeshEntry, t.get("mesh", {}), "mesh"),
                        from_table(ReductionEntry, t.get("reduction", {}), "reduction"),
                        {n: _interface(n, e) for n, e in itf.items()},
                        str(p))
        spec.selections()
    except ParameterError as err:
        raise ParameterError(f"{p.name}: {err}") from None
    return spec
