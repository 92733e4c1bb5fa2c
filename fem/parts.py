"""The separate parts of a mesh: connected components of its elements, two elements joined where
they share a node.

Exact and cheap (a sparse graph of the cells' nodes, scipy's ``connected_components``), and it
names the parts, where a spectrum only counts zero modes, and a Lanczos solve can miss members of
the cluster of twelve zeros that two loose parts make (issue 56).  A part that only touches
another at a node or an edge counts as joined here; the spectrum's gap finds that mechanism
(:mod:`.eigen`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components

from axlebox.geometry.mesh import MeshData


@dataclass(frozen=True)
class Part:
    """One connected part: its cells and nodes (indices into the mesh), its bounding box (m)."""

    cells: np.ndarray
    nodes: np.ndarray
    lower: np.ndarray          # (3,) m
    upper: np.ndarray          # (3,) m

    def describe(self, mass: float | None = None) -> str:
        box = ", ".join(f"{a} {lo:.4g}..{hi:.4g}" for a, lo, hi in zip("xyz", self.lower, self.upper))
        m = "" if mass is None else f", {mass:.4g} kg"
        return f"{len(self.cells)} elements, {len(self.nodes)} nodes{m}, {box} m"


def parts(mesh: MeshData) -> list[Part]:
    """The connected parts of ``mesh``, the largest (by elements) first."""
    cells = np.asarray(mesh.cells)
    n_cells, width = cells.shape
    n_points = len(mesh.points)
    # cell c joined to each of its nodes: a bipartite graph of cells (0..c-1) and nodes (c..)
    rows = np.repeat(np.arange(n_cells), width)
    graph = sp.coo_matrix((np.ones(rows.size, np.int8), (rows, n_cells + cells.ravel())),
                          shape=(n_cells + n_points,) * 2)
    _, label = connected_components(graph, directed=False)
    cell_label, node_label = label[:n_cells], label[n_cells:]
    used = np.zeros(n_points, bool)
    used[cells.ravel()] = True
    out = []
    for lab in np.unique(cell_label):
        nodes = np.flatnonzero((node_label == lab) & used)
        xyz = mesh.points[nodes]
        out.append(Part(np.flatnonzero(cell_label == lab), nodes, xyz.min(axis=0), xyz.max(axis=0)))
    return sorted(out, key=lambda p: (-len(p.cells), p.cells[0]))


def orphans(mesh: MeshData) -> np.ndarray:
    """Indices of the points no element uses (they carry no stiffness and no mass)."""
    used = np.zeros(len(mesh.points), bool)
    used[np.asarray(mesh.cells).ravel()] = True
    return np.flatnonzero(~used)
