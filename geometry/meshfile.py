"""A user's own part from an FE mesh file (Abaqus ``.inp``, Nastran ``.bdf``, gmsh ``.msh``, Salome
``.med``, VTK ``.vtu``) through meshio.

Tetrahedra only: linear ones are raised to quadratic (a node at each edge's middle, so the faces
stay flat, as the file's own elements were), quadratic ones kept.  The interfaces are groups of
the mesh's boundary facets: a named set of the file (an Abaqus or Nastran node or element set, a
gmsh physical group, meshio's cell and point sets) or a place (geometry/select.py) that each of a
facet's nodes must lie in.  Meshes declare no length unit: the spec's (metres unless it says).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from axlebox._params import ParameterError

from .mesh import MeshData
from .select import Named

SUFFIXES = (".inp", ".bdf", ".nas", ".msh", ".med", ".vtu", ".vtk")
#: a tet's four faces as triangle6 (corners, then the edges' middles) in VTK's tet10 order
#: (corners 0-3, then the edges 01, 12, 20, 03, 13, 23)
_FACES6 = np.array([[0, 1, 2, 4, 5, 6], [0, 1, 3, 4, 8, 7], [1, 2, 3, 5, 9, 8], [0, 2, 3, 6, 9, 7]])
_EDGES = np.array([[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]])
_VOLUME = {"tetra": 4, "tetra10": 10}
_REFUSED = ("hexahedron", "hexahedron20", "hexahedron27", "wedge", "wedge15", "pyramid", "pyramid13")


def read(path, scale: float, selections: dict) -> MeshData:
    """The tet10 mesh of ``path`` in metres (its coordinates times ``scale``), with each of
    ``selections``'s interfaces as the boundary facets it selects."""
    import meshio
    p = Path(path)
    if p.suffix.lower() not in SUFFIXES:
        raise ParameterError(f"--mesh = {str(path)!r} is not allowed: expected a mesh file "
                             f"({', '.join(SUFFIXES)})")
    if not p.is_file():
        raise ParameterError(f"--mesh = {str(path)!r} is not allowed: no such file")
    try:
        m = meshio.read(p)
    except Exception as err:                     # meshio raises its own and plain errors alike
        raise ParameterError(f"{p.name}: meshio cannot read it ({type(err).__name__}: {err})") from None
    kinds = [b.type for b in m.cells]
    bad = sorted(set(kinds) & set(_REFUSED))
    if bad:
        raise ParameterError(f"{p.name}: its {', '.join(bad)} elements are not supported: expected "
                             "tetrahedra (4 or 10 nodes); remesh the part with tetrahedra")
    vol = [b for b in m.cells if b.type in _VOLUME]
    if not vol:
        held = ", ".join(sorted(set(kinds))) or "nothing"
        raise ParameterError(f"{p.name}: no volume elements (it holds {held}): expected tetrahedra")
    if len({b.type for b in vol}) > 1:
        raise ParameterError(f"{p.name}: linear and quadratic tetrahedra mixed: expected one kind")
    cells = np.vstack([b.data for b in vol]).astype(np.int64)
    points = np.asarray(m.points, float)[:, :3] * scale
    used = np.zeros(len(points), bool)
    used[cells.ravel()] = True
    index = np.cumsum(used) - 1                  # the file's node -> ours (unused nodes dropped)
    points, cells = points[used], index[cells]
    if cells.shape[1] == 4:
        points, cells = raise_order(points, cells)
    facets, owner = boundary(cells)
    groups = {}
    for iname, sel in selections.items():
        if isinstance(sel, Named):
            keep = _named(m, sel.name, used, index, facets, owner, p.name)
        else:
            keep = np.flatnonzero(sel.holds(points[facets]))
        if not len(keep):
            raise ParameterError(f"{p.name}: interface {iname!r} selects nothing: no {sel.looked_for()} "
                                 f"among its {len(facets)} boundary facets")
        groups[iname] = facets[keep]
    return MeshData(points=np.ascontiguousarray(points), cells=np.ascontiguousarray(cells), groups=groups,
                    path=p)


def raise_order(points: np.ndarray, tet4: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Linear tetrahedra as quadratic ones: a node at the middle of each edge (shared by the
    elements around it), VTK's tet10 order."""
    pairs = np.sort(tet4[:, _EDGES].reshape(-1, 2), axis=1)
    edges, which = np.unique(pairs, axis=0, return_inverse=True)
    mid = 0.5 * (points[edges[:, 0]] + points[edges[:, 1]])
    tet10 = np.hstack([tet4, len(points) + which.reshape(-1, 6)])
    return np.vstack([points, mid]), tet10


def boundary(tet10: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The faces that belong to one element only, as triangle6 (f, 6), and their elements (f,)."""
    faces = tet10[:, _FACES6].reshape(-1, 6)
    key = np.sort(faces[:, :3], axis=1)
    _, first, count = np.unique(key, axis=0, return_index=True, return_counts=True)
    once = np.sort(first[count == 1])
    return faces[once], once // 4


def _named(m, label, used, index, facets, owner, fname) -> np.ndarray:
    """Boundary facets of the file's set ``label``: all corners in a node set, or on an element
    set's elements (surface elements: those facets; volume elements: their boundary faces)."""
    corners = np.sort(facets[:, :3], axis=1)
    if label in (m.point_sets or {}):
        nodes = np.asarray(m.point_sets[label], np.int64)
        inside = np.zeros(len(used), bool)
        inside[nodes[nodes < len(used)]] = True
        mine = np.zeros(int(index.max()) + 1, bool)
        mine[index[inside & used]] = True
        return np.flatnonzero(mine[corners].all(axis=1))
    sets = dict(m.cell_sets or {})
    for name, (tag, _) in (getattr(m, "field_data", None) or {}).items():     # gmsh physical groups
        if name == label and "gmsh:physical" in m.cell_data:
            sets[label] = [np.flatnonzero(np.asarray(d) == tag) for d in m.cell_data["gmsh:physical"]]
    if label not in sets:
        have = sorted(set(m.point_sets or {}) | set(sets))
        raise ParameterError(f"{fname}: interface {label!r} selects nothing: the file has no set "
                             f"{label!r} (it has {', '.join(have) or 'no named sets'})")
    keep = np.zeros(len(facets), bool)
    n_vol = 0
    for block, idx in zip(m.cells, sets[label]):
        idx = np.asarray(idx, np.int64)
        if block.type in _VOLUME:
            if idx.size:
                keep |= np.isin(owner, n_vol + idx)
            n_vol += len(block.data)
        elif block.type in ("triangle", "triangle6") and idx.size:
            tri = np.sort(index[np.asarray(block.data)[idx][:, :3]], axis=1)
            keep |= _rows_in(corners, tri)
    return np.flatnonzero(keep)


def _rows_in(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Whether each row of ``a`` is a row of ``b`` (both sorted triples)."""
    view = lambda x: np.ascontiguousarray(x).view([("", x.dtype)] * x.shape[1]).ravel()   # noqa: E731
    return np.isin(view(a), view(b))
