"""A user's own part from a CAD file (STEP, IGES, BREP) through gmsh's OCC kernel.

:func:`build` is a geometry builder for :func:`.mesh.mesh_model`: it imports the file into the
current gmsh model in metres (a STEP's or an IGES's own unit, converted by OpenCASCADE; a BREP
declares none: the spec's), heals it, glues touching solids into one conformal body (OCC's
fragment), and returns the faces of each named interface: a named surface of the file (a STEP
label, as gmsh imports it) or a place (geometry/select.py) that every sampled point of a face
must lie in.
"""
from __future__ import annotations

import contextlib
import hashlib
import os
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from axlebox._params import ParameterError

from ._occ import boundary_faces
from .select import Named

#: file suffix -> format; STEP and IGES carry their length unit, BREP does not
FORMATS = {".step": "step", ".stp": "step", ".iges": "iges", ".igs": "iges", ".brep": "brep",
           ".brp": "brep"}
#: a declared length unit -> metres
UNITS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "in": 0.0254}
#: points sampled along each boundary curve of a face to test a place selection
SAMPLES = 9


#: m, the largest extent a part of a railway vehicle plausibly has (a carbody is about 20 m)
LARGEST_M = 40.0
#: m, the smallest
SMALLEST_M = 0.005


@dataclass(frozen=True)
class CadSource:
    """The file (its path and content hash: the mesh cache's key), its unit, the interfaces'
    selections ``((name, selection), ...)``, and the density and mass expected (0: not checked)
    that tell a part in the wrong unit before it is meshed."""

    path: str
    sha256: str
    unit: str
    selections: tuple
    rho: float = 0.0
    mass_kg: float = 0.0


@contextlib.contextmanager
def occ_quiet():
    """OpenCASCADE's STEP writer prints its transfer statistics to the process's standard output
    (file descriptor 1), past gmsh's ``General.Terminal = 0``: sent to /dev/null meanwhile."""
    sys.stdout.flush()
    saved = os.dup(1)
    try:
        with open(os.devnull, "w") as null:
            os.dup2(null.fileno(), 1)
        yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)


def check_size(fname: str, extent: float, mass: float, mass_kg: float, unit: str) -> None:
    """Refuse a part in the wrong unit: its ``mass`` (kg) against the one expected ``mass_kg``
    (within a factor 1.5; 0: not checked), else its ``extent`` (m) against a vehicle part's."""
    if mass_kg > 0 and not 1 / 1.5 <= mass / mass_kg <= 1.5:
        raise ParameterError(f"{fname}: its mass is {mass:.4g} kg against body.mass_kg = {mass_kg:g} "
                             f"(it is {extent:.4g} m across): is its unit right? (body.unit = {unit!r})")
    if not SMALLEST_M <= extent <= LARGEST_M:
        guess = "millimetres" if extent > LARGEST_M else "metres"
        raise ParameterError(f"{fname}: it is {extent:.4g} m across, not a vehicle part's size "
                             f"({SMALLEST_M:g} to {LARGEST_M:g} m): is it in {guess}? (body.unit = "
                             f"{unit!r})")


def source(path, unit: str, selections: dict, rho: float = 0.0, mass_kg: float = 0.0,
           sha256: str = "") -> CadSource:
    """A :class:`CadSource` for ``path``, refusing a file that is not there or not a CAD format
    (``sha256``: its content's hash where the caller has read it already)."""
    p = Path(path)
    fmt = FORMATS.get(p.suffix.lower())
    if fmt is None:
        raise ParameterError(f"--geometry = {str(path)!r} is not allowed: expected a CAD file "
                             f"({', '.join(sorted(FORMATS))})")
    if not p.is_file():
        raise ParameterError(f"--geometry = {str(path)!r} is not allowed: no such file")
    if fmt != "brep" and unit != "file":
        raise ParameterError(f"body.unit = {unit!r} is not allowed for {p.name}: a {fmt.upper()} "
                             "file declares its own unit, read from it (leave unit = 'file')")
    sha = sha256 or hashlib.sha256(p.read_bytes()).hexdigest()
    return CadSource(str(p.resolve()), sha, unit, tuple(selections.items()), rho, mass_kg)


def build(src: CadSource) -> dict[str, list[int]]:
    """Import, heal and glue ``src``'s part in the current gmsh model; its interfaces' faces."""
    import gmsh
    occ = gmsh.model.occ
    name = Path(src.path).name
    fmt = FORMATS[Path(src.path).suffix.lower()]
    gmsh.option.setString("Geometry.OCCTargetUnit", "M" if fmt != "brep" else "")
    try:
        try:
            occ.importShapes(src.path, highestDimOnly=False)
        except Exception as err:                  # gmsh raises a bare Exception with its log line
            raise ParameterError(f"{name}: gmsh cannot read it as {fmt.upper()} ({err})") from None
    finally:
        gmsh.option.setString("Geometry.OCCTargetUnit", "")
    if fmt == "brep":
        scale = UNITS["m" if src.unit == "file" else src.unit]
        if scale != 1.0:
            occ.dilate(occ.getEntities(), 0.0, 0.0, 0.0, scale, scale, scale)
    occ.synchronize()
    if not occ.getEntities(3):                   # faces only: sew them and make solids
        shells = occ.getEntities(2)
        if shells:
            occ.healShapes(shells, sewFaces=True, makeSolids=True)
            occ.synchronize()
    vols = occ.getEntities(3)
    if not vols:
        raise ParameterError(f"{name}: gmsh cannot heal it into a closed solid (it holds "
                             f"{len(occ.getEntities(2))} faces and no volume); export the part as a "
                             "solid")
    if len(vols) > 1:                            # touching solids share their faces' nodes
        occ.fragment(vols[:1], vols[1:])
    occ.removeAllDuplicates()
    occ.synchronize()
    box = np.asarray(gmsh.model.getBoundingBox(-1, -1))
    volume = sum(occ.getMass(3, t) for _, t in occ.getEntities(3))
    check_size(name, float((box[3:] - box[:3]).max()), src.rho * volume, src.mass_kg, src.unit)
    faces = boundary_faces()
    out = {}
    for iname, sel in src.selections:
        tags = _named(faces, sel.name) if isinstance(sel, Named) else _placed(faces, sel)
        if not tags:
            raise ParameterError(f"{name}: interface {iname!r} selects nothing: no {sel.looked_for()} "
                                 f"among its {len(faces)} boundary faces")
        out[iname] = tags
    return out


def _named(faces: list[int], label: str) -> list[int]:
    """Faces in a physical group ``label`` or whose imported name is ``label`` or ends in
    ``/label`` (gmsh names a STEP's labelled faces by their path in its assembly)."""
    import gmsh
    out = set()
    for dim, tag in gmsh.model.getPhysicalGroups(2):
        if gmsh.model.getPhysicalName(dim, tag) == label:
            out.update(int(t) for t in gmsh.model.getEntitiesForPhysicalGroup(dim, tag))
    for f in faces:
        n = gmsh.model.getEntityName(2, f)
        if n == label or n.endswith("/" + label):
            out.add(f)
    return sorted(out & set(faces))


def _placed(faces: list[int], sel) -> list[int]:
    """Faces whose sampled boundary and centre of mass all lie where ``sel`` says."""
    return [f for f in faces if bool(sel.holds(_samples(f)[None])[0])]


def _samples(face: int) -> np.ndarray:
    """Points on face ``face``: the point of it nearest its centre of mass (which a curved face
    does not pass through) and SAMPLES along each of its boundary curves."""
    import gmsh
    com = gmsh.model.occ.getCenterOfMass(2, face)
    pts = [np.asarray(gmsh.model.getClosestPoint(2, face, com)[0]).reshape(1, 3)]
    for _, c in gmsh.model.getBoundary([(2, face)], combined=False, oriented=False):
        lo, hi = gmsh.model.getParametrizationBounds(1, abs(c))
        u = np.linspace(lo[0], hi[0], SAMPLES)
        pts.append(np.asarray(gmsh.model.getValue(1, abs(c), u)).reshape(-1, 3))
    return np.vstack(pts)
