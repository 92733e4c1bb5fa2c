"""Run a gmsh (OCC) model builder, mesh it with quadratic tetrahedra and cache it.

A builder is a function ``build(params) -> dict[str, list[int]]`` that creates
the solid(s) in the current gmsh model (OCC kernel, synchronised) and returns the
OCC surface tags of each named interface.  :func:`mesh_model` turns those into
gmsh physical groups, meshes, writes ``<name>-<hash>.msh`` into the cache and
returns plain arrays.  The hash covers the builder name, every parameter, the
mesh size and order, gmsh's version and every source file of :mod:`axlebox.geometry`
(:func:`geometry_hash`), so a change of any of them regenerates the mesh.
"""
from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np
from threadpoolctl import threadpool_limits

from axlebox._cache import cache_dir, package_dir, source_hash
from axlebox._params import ParameterError, digest

# gmsh node order -> VTK/meshio node order (tet10: last two edges swapped)
_GMSH_TO_VTK_TET10 = np.array([0, 1, 2, 3, 4, 5, 6, 7, 9, 8])


@dataclass
class MeshData:
    """A quadratic tetrahedral mesh with named surface node sets (SI units)."""

    points: np.ndarray                 # (p, 3) m
    cells: np.ndarray                  # (c, 10) tet10, VTK node order
    groups: dict[str, np.ndarray] = field(default_factory=dict)   # name -> (f, 6) triangle6 facets
    path: Path | None = None           # the cached .msh file

    def group_nodes(self, name: str) -> np.ndarray:
        """Sorted unique point indices of the named surface."""
        return np.unique(self.groups[name])


def geometry_hash(folder: Path | None = None) -> str:
    """Hash of every source file of :mod:`axlebox.geometry` (or of ``folder``): an edit to a
    builder, or an upgrade, makes new meshes instead of reading ones it would no longer make."""
    return source_hash([package_dir("geometry") if folder is None else folder])


def mesh_model(name: str, build: Callable, params, mesh_size: float, *,
               order: int = 2, cache: bool = True, verbose: bool = False) -> MeshData:
    """Mesh ``build(params)`` at characteristic size ``mesh_size`` (m), cached by hash."""
    import gmsh

    if not isinstance(mesh_size, (int, float)) or not mesh_size > 0 or not np.isfinite(mesh_size):
        raise ParameterError(f"mesh_size = {mesh_size!r} is not allowed: expected a length > 0 m")
    if order not in (1, 2):
        raise ParameterError(f"order = {order!r} is not allowed: expected 1 or 2")
    key = digest(name, params, float(mesh_size), order, geometry_hash(), gmsh.__version__)
    path = cache_dir("meshes") / f"{name}-{key}.msh"

    # gmsh sets the OpenMP threads to its own count (General.NumThreads, below) in whichever
    # OpenMP runtime is loaded: MKL's, when a body was solved before, which then ran PARDISO on
    # one thread for the rest of the process, and a body built after a fresh mesh differed in
    # the last bits from one built from the cached mesh; the counts are put back after
    with threadpool_limits(limits=None):
        initialised = gmsh.isInitialized()
        if not initialised:
            gmsh.initialize(interruptible=False)
        try:
            gmsh.option.setNumber("General.Terminal", 1 if verbose else 0)
            gmsh.clear()
            if cache and path.exists():
                gmsh.open(str(path))
            else:
                gmsh.model.add(name)
                surfaces = build(params)
                gmsh.model.occ.synchronize()
                _physical_groups(surfaces)
                _mesh(mesh_size, order)
                if cache:
                    path.parent.mkdir(parents=True, exist_ok=True)
                    fd, tmp = tempfile.mkstemp(suffix=".msh", dir=path.parent)
                    os.close(fd)
                    gmsh.write(tmp)
                    os.replace(tmp, path)    # complete files only
            data = _extract()
            data.path = path if cache else None
            return data
        finally:
            gmsh.clear()
            if not initialised:
                gmsh.finalize()


def _physical_groups(surfaces: dict[str, list[int]]) -> None:
    import gmsh
    vols = [t for _, t in gmsh.model.getEntities(3)]
    gmsh.model.addPhysicalGroup(3, vols, name="body")
    for gname, tags in surfaces.items():
        if not tags:
            raise RuntimeError(f"geometry: interface {gname!r} matched no surface")
        gmsh.model.addPhysicalGroup(2, list(tags), name=gname)


def _mesh(h: float, order: int) -> None:
    import gmsh
    opt = gmsh.option.setNumber
    opt("General.NumThreads", 1)               # threaded HXT is not reproducible
    opt("Mesh.MeshSizeMax", h)
    opt("Mesh.MeshSizeMin", h / 8)
    opt("Mesh.MeshSizeFromCurvature", 12)     # >= 12 elements per full circle
    opt("Mesh.MeshSizeExtendFromBoundary", 1)
    opt("Mesh.Algorithm", 6)                  # Frontal-Delaunay surfaces
    opt("Mesh.Algorithm3D", 10)               # HXT: fast, parallel
    opt("Mesh.Optimize", 1)
    opt("Mesh.ElementOrder", order)
    opt("Mesh.SecondOrderLinear", 0)          # midside nodes on the CAD surface
    opt("Mesh.Binary", 1)
    gmsh.model.mesh.generate(3)


def _extract() -> MeshData:
    """Points, tet cells and named triangle facets from the current gmsh model."""
    import gmsh
    tags, coords, _ = gmsh.model.mesh.getNodes()
    index = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(len(tags))
    points = coords.reshape(-1, 3)

    etype = {10: 11, 4: 4}            # gmsh element types: tet10 = 11, tet4 = 4
    cells = []
    for _, vol in gmsh.model.getEntities(3):
        types, _, nodes = gmsh.model.mesh.getElements(3, vol)
        for t, n in zip(types, nodes):
            nn = 10 if t == 11 else 4
            if t not in etype.values():
                continue
            cells.append(index[n.astype(np.int64)].reshape(-1, nn))
    cells = np.concatenate(cells)
    if cells.shape[1] == 10:
        cells = cells[:, _GMSH_TO_VTK_TET10]

    groups = {}
    for dim, ptag in gmsh.model.getPhysicalGroups(2):
        gname = gmsh.model.getPhysicalName(dim, ptag)
        facets = []
        for ent in gmsh.model.getEntitiesForPhysicalGroup(dim, ptag):
            types, _, nodes = gmsh.model.mesh.getElements(2, ent)
            for t, n in zip(types, nodes):
                nn = {9: 6, 2: 3}.get(int(t))
                if nn:
                    facets.append(index[n.astype(np.int64)].reshape(-1, nn))
        groups[gname] = np.concatenate(facets)

    # drop points not used by any cell (geometry vertices of removed entities)
    used = np.zeros(len(points), bool)
    used[cells.ravel()] = True
    if not used.all():
        new = np.cumsum(used) - 1
        points = points[used]
        cells = new[cells]
        groups = {k: new[v] for k, v in groups.items()}
    return MeshData(points=np.ascontiguousarray(points), cells=cells, groups=groups)
