"""Condensation of named surfaces to 6-DOF master nodes (RBE2 rigid, RBE3 averaging).

Both couplings are written as one sparse transformation ``u = T q`` with
``q = [independent FE DOFs; 6 DOFs of each master]`` so that Guyan and
Craig-Bampton can treat the master DOFs as ordinary boundary DOFs.

* RBE2 (rigid spider): every surface node follows the master rigidly,
  ``u_s = u_m + theta_m x (x_s - x_m)``; the surface DOFs become dependent.
* RBE3 (distributing coupling, Nastran RBE3 / Abaqus distributing): the master
  moves with the weighted least-squares rigid fit of the surface,
  ``q_m = G u_s`` with ``G = (R^T W R)^-1 R^T W``; the surface stays
  deformable.  Six surface DOFs, chosen by column-pivoted QR of ``G`` for
  conditioning, are made dependent so the master DOFs become independent
  (Nastran's UM set).  Weights are the consistent nodal loads of a uniform
  traction (surface-area weights), so a master force spreads as a traction.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from axlebox._params import ParameterError

from .assembly import FEModel

KINDS = ("rbe2", "rbe3")


@dataclass
class Interface:
    name: str
    kind: str
    position: np.ndarray     # (3,) master node
    nodes: np.ndarray        # surface point indices
    weights: np.ndarray      # (len(nodes),) area weights, m^2


@dataclass
class Condensation:
    T: sp.csr_matrix          # (ndof, nq)
    n_boundary: int           # the last n_boundary columns of T are master DOFs
    interfaces: list[Interface]

    def master_slice(self, i: int) -> slice:
        start = self.T.shape[1] - self.n_boundary + 6 * i
        return slice(start, start + 6)


def facet_weights(points: np.ndarray, facets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Nodes of a facet set and their consistent loads for a unit uniform traction.

    For a 6-node triangle of area A the consistent loads are 0 at the corners
    and A/3 at the midside nodes; 3-node triangles get A/3 at each corner.
    """
    p = points[facets[:, :3]]
    area = 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)
    carriers = facets[:, 3:6] if facets.shape[1] == 6 else facets[:, :3]
    nodes = np.unique(facets)
    w = np.zeros(points.shape[0])
    np.add.at(w, carriers.ravel(), np.repeat(area / 3, 3))
    return nodes, w[nodes]


def make_interfaces(model: FEModel, kinds: dict[str, str],
                    positions: dict[str, np.ndarray] | None = None) -> list[Interface]:
    """Interfaces for the named surface groups; master at ``positions`` or the area centroid."""
    positions = positions or {}
    out = []
    for name, kind in kinds.items():
        if name not in model.mesh.groups:
            raise ParameterError(f"interface = {name!r} is not allowed: the body has "
                                 f"{sorted(model.mesh.groups)}")
        if kind not in KINDS:
            raise ParameterError(f"coupling of {name!r} = {kind!r} is not allowed: expected one of {KINDS}")
        nodes, w = facet_weights(model.points, model.mesh.groups[name])
        pos = positions.get(name)
        if pos is None:
            pos = (w[:, None] * model.points[nodes]).sum(0) / w.sum()
        out.append(Interface(name, kind, np.asarray(pos, float), nodes, w))
    return out


def _rigid_rows(r: np.ndarray) -> np.ndarray:
    """(3n, 6) matrix of u = u_m + theta x r for node offsets r (n, 3)."""
    n = len(r)
    R = np.zeros((n, 3, 6))
    R[:, :, :3] = np.eye(3)
    # theta x r = -r~ theta
    R[:, 0, 4], R[:, 0, 5] = r[:, 2], -r[:, 1]
    R[:, 1, 3], R[:, 1, 5] = -r[:, 2], r[:, 0]
    R[:, 2, 3], R[:, 2, 4] = r[:, 1], -r[:, 0]
    return R.reshape(3 * n, 6)


def condense(model: FEModel, interfaces: list[Interface]) -> Condensation:
    """Build ``T`` for all interfaces.  A node on two surfaces belongs to the first."""
    ndof = model.ndof
    taken = np.zeros(model.points.shape[0], bool)
    dependent = np.zeros(ndof, bool)
    rows, cols, vals = [], [], []        # entries of the dependent rows, in (dof, column key) form
    nb = 6 * len(interfaces)
    for i, itf in enumerate(interfaces):
        own = ~taken[itf.nodes]
        nodes, w = itf.nodes[own], itf.weights[own]
        taken[itf.nodes] = True
        if len(nodes) < 3:
            raise ParameterError(f"interface {itf.name!r} has {len(nodes)} free nodes: too few to couple")
        dof = model.dofs[nodes].ravel()                  # (3n,) node-major
        Rr = _rigid_rows(model.points[nodes] - itf.position)
        if itf.kind == "rbe2":
            dependent[dof] = True
            for k in range(6):
                nz = Rr[:, k] != 0
                rows.append(dof[nz]), cols.append(np.full(nz.sum(), -(6 * i + k) - 1)), vals.append(Rr[nz, k])
        else:
            W = np.repeat(w, 3)
            A = Rr.T @ (W[:, None] * Rr)
            if np.linalg.cond(A) > 1e12:
                raise ParameterError(f"interface {itf.name!r}: its nodes cannot carry a 6-DOF "
                                     "RBE3 (degenerate surface); use 'rbe2'")
            G = np.linalg.solve(A, Rr.T * W)             # (6, 3n)
            _, _, piv = sla.qr(G, pivoting=True, mode="economic")
            d = piv[:6]
            ind = np.setdiff1d(np.arange(len(dof)), d)
            Gd_inv = np.linalg.inv(G[:, d])
            coupling = -Gd_inv @ G[:, ind]               # (6, 3n-6)
            dependent[dof[d]] = True
            for j in range(6):
                rows.append(np.full(6, dof[d[j]])), cols.append(-(6 * i + np.arange(6)) - 1)
                vals.append(Gd_inv[j])
                rows.append(np.full(len(ind), dof[d[j]])), cols.append(dof[ind]), vals.append(coupling[j])
    indep = np.flatnonzero(~dependent)
    ni = len(indep)
    col_of = np.full(ndof, -1)
    col_of[indep] = np.arange(ni)
    rows = np.concatenate(rows) if rows else np.zeros(0, int)
    cols = np.concatenate(cols) if cols else np.zeros(0, int)
    vals = np.concatenate(vals) if vals else np.zeros(0)
    # negative column keys are master DOFs, the rest FE DOFs (must be independent)
    mc = cols < 0
    c = np.where(mc, ni + (-cols - 1), col_of[np.maximum(cols, 0)])
    if np.any(c < 0):
        raise RuntimeError("interfaces: an RBE3 depends on a DOF made dependent by another interface")
    T = sp.coo_matrix((np.concatenate([np.ones(ni), vals]),
                       (np.concatenate([indep, rows]), np.concatenate([np.arange(ni), c]))),
                      shape=(ndof, ni + nb)).tocsr()
    return Condensation(T=T, n_boundary=nb, interfaces=interfaces)
