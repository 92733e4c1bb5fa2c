"""Guyan and Craig-Bampton reduction on the master DOFs, then orthogonalisation.

With ``q = [u_i; u_b]`` (interior FE DOFs; master DOFs) after the interface
condensation ``u = T q``:

* constraint modes ``Psi_i = -K_ii^-1 K_ib`` (static shapes for unit master DOFs);
* Guyan: ``q = [Psi_i; I] u_b``;
* Craig-Bampton: ``q = [[Phi_i, Psi_i], [0, I]] [eta; u_b]`` with ``Phi_i`` the
  fixed-interface normal modes (``K_ii phi = omega^2 M_ii phi``), kept by count
  or up to a frequency cutoff.

The reduced pair is then solved as a small dense eigenproblem; its six zero
modes are the rigid motions (exactly representable, since the constraint modes
contain them) and its elastic modes are the reduced body's own free-free modes,
the basis the floating-frame formulation uses.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
from scipy.sparse.linalg import eigsh

from axlebox._params import ParameterError

from . import modebasis
from .assembly import FEModel
from .interfaces import Condensation
from .linsolve import Factor, negative_eigenvalues

METHODS = ("guyan", "craig-bampton")


@dataclass
class Reduction:
    method: str
    K: np.ndarray              # (r, r) reduced stiffness in [eta; u_b]
    M: np.ndarray              # (r, r) reduced mass
    n_fixed: int               # number of fixed-interface modes eta
    fixed_frequencies_hz: np.ndarray
    basis_interior: np.ndarray  # (n_i, r): u_i = basis_interior @ [eta; u_b]
    condensation: Condensation
    # orthogonalised free-free modes of the reduced body
    frequencies_hz: np.ndarray  # (n,) elastic
    X: np.ndarray               # (r, n) elastic eigenvectors, M-orthonormal
    X_rigid: np.ndarray         # (r, 6)
    rigid_frequencies_hz: np.ndarray

    @property
    def n_boundary(self) -> int:
        return self.condensation.n_boundary

    def physical(self, x: np.ndarray) -> np.ndarray:
        """FE DOF vectors (ndof, k) of reduced vectors ``x`` (r, k)."""
        ui = self.basis_interior @ x
        q = np.vstack([ui, x[-self.n_boundary:]])
        return self.condensation.T @ q

    def master_shapes(self, i: int, x: np.ndarray | None = None) -> np.ndarray:
        """(6, n) displacement and rotation of master ``i`` in each mode of ``x``."""
        x = self.X if x is None else x
        start = x.shape[0] - self.n_boundary + 6 * i
        return x[start:start + 6]

    def rigid_vectors(self) -> np.ndarray:
        """(r, 6) reduced coordinates of the six rigid motions about the origin."""
        out = np.zeros((self.K.shape[0], 6))
        for i, itf in enumerate(self.condensation.interfaces):
            x = itf.position
            R = np.zeros((6, 6))
            R[:3, :3] = np.eye(3)
            R[3:, 3:] = np.eye(3)
            R[:3, 3:] = -np.array([[0, -x[2], x[1]], [x[2], 0, -x[0]], [-x[1], x[0], 0]])
            start = out.shape[0] - self.n_boundary + 6 * i
            out[start:start + 6] = R
        return out


def reduce(model: FEModel, cond: Condensation, method: str = "craig-bampton", *,
           n_modes: int | None = 20, fmax_hz: float | None = None) -> Reduction:
    """Reduce ``model`` on the master DOFs of ``cond``.

    Craig-Bampton keeps ``n_modes`` fixed-interface modes, or all below
    ``fmax_hz`` when that is given.
    """
    if method not in METHODS:
        raise ParameterError(f"method = {method!r} is not allowed: expected one of {METHODS}")
    T = cond.T
    Kq = (T.T @ model.K @ T).tocsr()
    Mq = (T.T @ model.M @ T).tocsr()
    nb = cond.n_boundary
    ni = Kq.shape[0] - nb
    Kii, Kib, Kbb = Kq[:ni, :ni], Kq[:ni, ni:].toarray(), Kq[ni:, ni:].toarray()
    Mii, Mib, Mbb = Mq[:ni, :ni], Mq[:ni, ni:].toarray(), Mq[ni:, ni:].toarray()

    fac = Factor(Kii.tocsr())
    try:
        Psi = -fac.solve(Kib)                               # (ni, nb)
        if method == "guyan":
            Phi, lam = np.zeros((ni, 0)), np.zeros(0)
        else:
            Phi, lam = _fixed_interface_modes(Kii, Mii, fac, n_modes, fmax_hz)
    finally:
        fac.free()

    # reduced matrices in [eta; u_b]
    MPsi = Mii @ Psi + Mib
    Kbb_r = Kbb + Kib.T @ Psi
    Mbb_r = Mbb + Mib.T @ Psi + Psi.T @ MPsi
    nf = Phi.shape[1]
    Kr = np.zeros((nf + nb, nf + nb))
    Mr = np.zeros_like(Kr)
    # exact Galerkin projections, not the eigensolver's idealised diag(lam) and I:
    # then the reduced eigenvalues are Ritz values, bounded below by the full model's
    Kr[:nf, :nf] = Phi.T @ (Kii @ Phi)
    Kr[:nf, nf:] = Phi.T @ (Kii @ Psi + Kib)
    Kr[nf:, :nf] = Kr[:nf, nf:].T
    Kr[nf:, nf:] = Kbb_r
    Mr[:nf, :nf] = Phi.T @ (Mii @ Phi)
    Mr[:nf, nf:] = Phi.T @ MPsi
    Mr[nf:, :nf] = Mr[:nf, nf:].T
    Mr[nf:, nf:] = Mbb_r
    Kr, Mr = 0.5 * (Kr + Kr.T), 0.5 * (Mr + Mr.T)

    w2, X = sla.eigh(Kr, Mr)
    f = np.sqrt(np.abs(w2)) / (2 * np.pi)
    n_rigid = int(np.sum(f < 1e-3 * f[6])) if len(f) > 6 else 0
    if n_rigid != 6:
        raise RuntimeError(f"reduced body shows {n_rigid} rigid modes, expected 6 "
                           f"(lowest {np.round(f[:8], 3)} Hz)")
    return Reduction(method=method, K=Kr, M=Mr, n_fixed=nf,
                     fixed_frequencies_hz=np.sqrt(np.maximum(lam, 0)) / (2 * np.pi),
                     basis_interior=np.hstack([Phi, Psi]), condensation=cond,
                     frequencies_hz=f[6:], X=X[:, 6:], X_rigid=X[:, :6],
                     rigid_frequencies_hz=f[:6])


def _count_below(Kii: sp.csr_matrix, Mii: sp.csr_matrix, lam_max: float) -> int | None:
    """The number of fixed-interface eigenvalues below ``lam_max`` (Sylvester's law of inertia,
    :func:`.linsolve.negative_eigenvalues`), or None where the factorisation cannot tell."""
    try:
        return negative_eigenvalues((Kii - lam_max * Mii).tocsr())
    except RuntimeError:
        return None


def _fixed_interface_modes(Kii: sp.csr_matrix, Mii: sp.csr_matrix, fac: Factor,
                           n_modes: int | None, fmax_hz: float | None):
    """Lowest fixed-interface modes (M-orthonormal), by count or up to ``fmax_hz``."""
    op = fac.operator()
    # the same start and restarts every run: the same modes, bit for bit (fem/modebasis.py)
    fixed = modebasis.fixed_start(Kii.shape[0])
    if fmax_hz is None:
        if n_modes is None or n_modes < 1:
            raise ParameterError(f"modes = {n_modes!r} is not allowed: expected an integer >= 1")
        lam, Phi = eigsh(Kii, k=n_modes, M=Mii, sigma=0.0, OPinv=op, which="LM", tol=1e-10,
                         **fixed)
    else:
        if not fmax_hz > 0:
            raise ParameterError(f"fmax = {fmax_hz!r} is not allowed: expected a frequency > 0 Hz")
        lam_max = (2 * np.pi * fmax_hz) ** 2
        # how many lie below the cutoff, from the inertia of K_ii - lam_max M_ii (Sturm; one
        # factorisation), so that one Lanczos run asks for them all: growing the request by
        # doubling ran it three or four times, each from scratch (72 s of the default wheelset's
        # 2 kHz reduction, 25 s this way).  Two more than the count: a pair of equal frequencies
        # at the cutoff is not split by the request.
        below = _count_below(Kii, Mii, lam_max)
        k = 12 if below is None else below + 2
        while True:   # grow the request until the cutoff is passed (where the count is unknown)
            lam, Phi = eigsh(Kii, k=min(k, Kii.shape[0] - 2), M=Mii, sigma=0.0, OPinv=op,
                             which="LM", tol=1e-10, **fixed)
            if lam.max() > lam_max or k >= Kii.shape[0] - 2:
                keep = lam <= lam_max
                if below is None or int(keep.sum()) == below:
                    lam, Phi = lam[keep], Phi[:, keep]
                    break
                below = None    # the run missed some the count says are there: grow as before
            k *= 2
    order = np.argsort(lam, kind="stable")
    lam, Phi = lam[order], Phi[:, order]
    # equal frequencies (an axisymmetric body's pairs): one basis of their span, every run
    return modebasis.canonical(Phi, lam, Mii), lam
