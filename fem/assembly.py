"""3-D linear elasticity with scikit-fem: stiffness and consistent mass.

Quadratic tetrahedra (``ElementTetP2`` on the curved ``MeshTet2`` from gmsh) by
default.  The stiffness uses a degree-2 rule (exact on straight-sided quadratic
tetrahedra, as C3D10 elements do), the mass a degree-4 rule (exact for P2 x P2).

Both are assembled from the scalar element (the isotropic elasticity form written in
components, as in Hughes, *The Finite Element Method*, Dover 2000, ch. 2): with
``u = phi_j e_b`` and ``v = phi_i e_a``, ``int lam div u div v + 2 mu eps(u):eps(v)`` is
``lam G_ab + mu G_ba + mu delta_ab (G_11 + G_22 + G_33)`` with ``G_ab = int d_a(phi_i)
d_b(phi_j)``, and the mass ``delta_ab int rho phi_i phi_j``.  scikit-fem's vector form of the
same integrals evaluates 30 x 30 pairs of 3 x 3 gradients a tet10 where these six scalar forms
evaluate 10 x 10 products: the same matrices to round-off (tests/test_beam.py), about nine
times faster (the demo's frame 10.3 -> 1.1 s).
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
    from skfem.models.elasticity import lame_parameters

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
        scalar = ElementTetP2()
    else:
        m = MeshTet1(mesh.points.T.copy(), mesh.cells.T.copy())
        scalar = ElementTetP1()
    vector = Basis(m, ElementVector(scalar), intorder=1)      # its DOF numbering only
    kb = Basis(m, scalar, intorder=2 if quadratic else 1)
    mb = Basis(m, scalar, intorder=4)
    lam, mu = lame_parameters(material.E, material.nu)
    # the nine blocks G_ab = int d_a(phi_i) d_b(phi_j) of the scalar element, six assembled
    G = {}
    for a in range(3):
        for b in range(a, 3):
            G[a, b] = BilinearForm(lambda u, v, w, a=a, b=b: v.grad[a] * u.grad[b]).assemble(kb).tocsr()
            G[b, a] = G[a, b].T.tocsr()
    trace = G[0, 0] + G[1, 1] + G[2, 2]
    rho = material.rho
    Ms = BilinearForm(lambda u, v, w: rho * u * v).assemble(mb)
    # into the vector element's numbering: the scalar DOF k of component a is vector DOF comp[a][k]
    order = _component_dofs(kb, 0)
    comp = []
    for a in range(3):
        c = np.empty(order.size, dtype=np.int64)
        c[order] = _component_dofs(vector, a)
        comp.append(c)
    K = _blocks({(a, b): lam * G[a, b] + mu * G[b, a] + (mu * trace if a == b else 0.0)
                 for a in range(3) for b in range(3)}, comp, vector.N)
    M = _blocks({(a, a): Ms for a in range(3)}, comp, vector.N)
    dofs = _point_dofs(vector, mesh.points)
    return FEModel(mesh=mesh, material=material, K=K, M=M, dofs=dofs)


def _blocks(blocks: dict, comp: list, n: int) -> sp.csr_matrix:
    """The ``n x n`` matrix whose rows of component ``a`` and columns of ``b`` are the scalar
    matrix ``blocks[a, b]``, scattered by ``comp`` (scalar DOF -> vector DOF per component)."""
    rows, cols, data = [], [], []
    for (a, b), blk in blocks.items():
        blk = blk.tocoo()
        rows.append(comp[a][blk.row])
        cols.append(comp[b][blk.col])
        data.append(blk.data)
    return sp.csr_matrix((np.concatenate(data), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(n, n))


def _component_dofs(basis, a: int) -> np.ndarray:
    """The DOF numbers of component ``a`` of ``basis``: at the vertices, then at the edges."""
    idx = [basis.nodal_dofs[a]]
    if basis.edge_dofs.size:
        idx.append(basis.edge_dofs[a])
    return np.concatenate(idx)


def _point_dofs(basis, points: np.ndarray) -> np.ndarray:
    """Map every mesh point to its three DOF numbers by location (robust to renumbering)."""
    comps = [_component_dofs(basis, a) for a in range(3)]
    loc = basis.doflocs[:, comps[0]].T
    dist, which = cKDTree(loc).query(points)
    scale = np.ptp(points, axis=0).max()
    if len(loc) != len(points) or dist.max() > 1e-9 * scale:
        raise RuntimeError("fem: mesh points and finite-element DOFs do not match one to one")
    return np.stack([c[which] for c in comps], axis=1)
