"""3-D linear elasticity with scikit-fem: stiffness and consistent mass.

Quadratic tetrahedra (``ElementTetP2`` on the curved ``MeshTet2`` from gmsh) by
default.  The stiffness uses a degree-2 rule (exact on straight-sided quadratic
tetrahedra, as C3D10 elements do), the mass a degree-4 rule (exact for P2 x P2).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree

from axlebox._params import ParameterError, check_ranges, param, require
from axlebox.geometry.mesh import MeshData

from .parts import orphans


@dataclass(frozen=True)
class Material:
    """Isotropic linear-elastic material (SI); defaults: wheel and axle steel."""

    E: float = param(2.1e11, 1e6, 1e13, unit="Pa", doc="Young's modulus")
    nu: float = param(0.3, 0.0, 0.499, unit="", doc="Poisson's ratio")
    rho: float = param(7850.0, 1.0, 1e5, unit="kg/m^3", doc="density")

    def __post_init__(self):
        check_ranges(self)


STEEL = Material()


@dataclass
class FEModel:
    """Assembled model: ``K u'' ... `` with DOF ``dofs[i, a]`` for point i, component a."""

    mesh: MeshData
    material: Material
    K: sp.csr_matrix
    M: sp.csr_matrix
    dofs: np.ndarray        # (p, 3) int

    @property
    def ndof(self) -> int:
        return self.K.shape[0]

    @property
    def points(self) -> np.ndarray:
        return self.mesh.points

    def scalar_mass(self) -> sp.csr_matrix:
        """The consistent mass of one displacement component, ``int rho N_i N_j dV`` (p x p).

        The vector mass is this block on each component, so every mass-weighted
        integral of two fields in the FE space is ``f_a^T Ms g_b``.
        """
        d = self.dofs[:, 0]
        return self.M[d][:, d].tocsr()

    def field(self, u: np.ndarray) -> np.ndarray:
        """A DOF vector (or (ndof, n) array) as point vectors (p, 3) (or (n, p, 3))."""
        u = np.asarray(u)
        if u.ndim == 1:
            return u[self.dofs]
        return np.moveaxis(u[self.dofs], -1, 0)

    def rigid_modes(self, origin=(0.0, 0.0, 0.0)) -> np.ndarray:
        """The six rigid-body DOF vectors about ``origin``: 3 translations, 3 rotations."""
        r = self.points - np.asarray(origin)
        R = np.zeros((self.ndof, 6))
        for a in range(3):
            R[self.dofs[:, a], a] = 1.0
        # rotation theta about axis b: u = e_b x r
        for b in range(3):
            e = np.zeros(3)
            e[b] = 1.0
            u = np.cross(e, r)
            for a in range(3):
                R[self.dofs[:, a], 3 + b] = u[:, a]
        return R


def assemble(mesh: MeshData, material: Material = STEEL) -> FEModel:
    """Stiffness and consistent mass of ``mesh`` (tet10) with scikit-fem."""
    from skfem import Basis, BilinearForm, ElementTetP1, ElementTetP2, ElementVector, MeshTet1, MeshTet2
    from skfem.helpers import dot
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    quadratic = mesh.cells.shape[1] == 10
    require(quadratic or mesh.cells.shape[1] == 4, mesh, "cells", "expected tet4 or tet10 cells")
    loose = orphans(mesh)
    if len(loose):
        raise ParameterError(f"mesh.points: {len(loose)} of the {len(mesh.points)} points belong to no "
                             f"element (the first at {np.round(mesh.points[loose[0]], 6).tolist()} m), "
                             "where they would carry no stiffness and no mass; expected every point "
                             "in an element")
    if quadratic:
        m = MeshTet2(mesh.points.T.copy(), mesh.cells.T.copy())
        elem = ElementVector(ElementTetP2())
    else:
        m = MeshTet1(mesh.points.T.copy(), mesh.cells.T.copy())
        elem = ElementVector(ElementTetP1())
    kb = Basis(m, elem, intorder=2 if quadratic else 1)
    mb = Basis(m, elem, intorder=4)
    K = linear_elasticity(*lame_parameters(material.E, material.nu)).assemble(kb)
    rho = material.rho

    @BilinearForm
    def mass(u, v, w):
        return rho * dot(u, v)

    M = mass.assemble(mb)
    dofs = _point_dofs(kb, mesh.points)
    return FEModel(mesh=mesh, material=material, K=K.tocsr(), M=M.tocsr(), dofs=dofs)


def _point_dofs(basis, points: np.ndarray) -> np.ndarray:
    """Map every mesh point to its three DOF numbers by location (robust to renumbering)."""
    comps = []
    for a in range(3):
        idx = [basis.nodal_dofs[a]]
        if basis.edge_dofs.size:
            idx.append(basis.edge_dofs[a])
        comps.append(np.concatenate(idx))
    loc = basis.doflocs[:, comps[0]].T
    dist, which = cKDTree(loc).query(points)
    scale = np.ptp(points, axis=0).max()
    if len(loc) != len(points) or dist.max() > 1e-9 * scale:
        raise RuntimeError("fem: mesh points and finite-element DOFs do not match one to one")
    return np.stack([c[which] for c in comps], axis=1)
