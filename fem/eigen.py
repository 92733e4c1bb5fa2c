"""Free-free eigenmodes with a negative shift; rigid modes identified and checked."""
from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from scipy.sparse.linalg import eigsh

from .assembly import FEModel
from .linsolve import Factor


@dataclass
class Modes:
    """Eigenpairs ``K phi = omega^2 M phi``, M-orthonormal, ascending."""

    frequencies_hz: np.ndarray   # (n,) elastic modes only
    shapes: np.ndarray           # (ndof, n) elastic modes only
    rigid_frequencies_hz: np.ndarray   # (6,) the near-zero ones, as computed
    rigid_shapes: np.ndarray     # (ndof, 6)
    rigid_residual: float        # how far the analytic rigid motions lie outside their span
    residual: float = 0.0        # max ||K phi - w^2 M phi|| / ||K phi|| over the elastic modes


class RigidModeError(RuntimeError):
    """The free-free spectrum does not show exactly six rigid-body modes."""


def free_free_modes(model: FEModel, n_elastic: int = 20, *, shift_hz: float | None = None,
                    rigid_tol: float = 1e-3, residual_tol: float = 1e-4) -> Modes:
    """Lowest ``n_elastic`` elastic free-free modes of ``model`` (see :func:`_solve`).

    With ``shift_hz=None`` the shift is chosen from the body: a shift far below
    the first elastic mode leaves ``K - sigma M`` badly conditioned (about 1e12
    for steel parts at 1 Hz) and the modes inaccurate, so a cheap first solve at
    10 Hz for six elastic modes estimates the first elastic frequency f1, and the
    real solve shifts to ``-(pi f1)^2`` (half of f1).  ``Modes.residual`` reports
    the eigen-residual achieved; above ``residual_tol`` a warning is raised.
    """
    if shift_hz is None:
        shift_hz = 0.5 * _solve(model, 6, 10.0, rigid_tol).frequencies_hz[0]
    modes = _solve(model, n_elastic, shift_hz, rigid_tol)
    if modes.residual > residual_tol:
        warnings.warn(f"free-free modes: eigen-residual {modes.residual:.1e} above {residual_tol:g}",
                      RuntimeWarning, stacklevel=2)
    return modes


def _solve(model: FEModel, n_elastic: int, shift_hz: float, rigid_tol: float) -> Modes:
    """One shift-invert solve for the lowest ``n_elastic`` elastic free-free modes.

    The shift ``sigma = -(2 pi shift_hz)^2`` makes ``K - sigma M`` positive
    definite, so the singular free-free stiffness can be factored.  The rigid
    modes are not assumed: the modes below ``rigid_tol`` times the first elastic
    frequency are counted (there must be six) and the six analytic rigid motions
    must lie in their span (M-norm residual below ``rigid_tol``).
    """
    sigma = -(2 * np.pi * shift_hz) ** 2
    fac = Factor((model.K - sigma * model.M).tocsr())
    try:
        lam, phi = eigsh(model.K, k=n_elastic + 6, M=model.M, sigma=sigma,
                         OPinv=fac.operator(), which="LM", tol=1e-10)
    finally:
        fac.free()
    order = np.argsort(lam)
    lam, phi = lam[order], phi[:, order]
    f = np.sqrt(np.abs(lam)) / (2 * np.pi)
    n_rigid = int(np.sum(f < rigid_tol * f[6])) if len(f) > 6 else 0
    if n_rigid != 6:
        raise RigidModeError(f"free-free spectrum shows {n_rigid} rigid modes, expected 6 "
                             f"(lowest frequencies {np.round(f[:8], 4)} Hz): the body may be "
                             "disconnected or constrained")
    residual = rigid_residual(model, phi[:, :6])
    if residual > rigid_tol:
        raise RigidModeError(f"the six near-zero modes do not span the rigid motions "
                             f"(residual {residual:.2e} > {rigid_tol:g})")
    P = phi[:, 6:]
    KP = model.K @ P
    res = np.linalg.norm(KP - (model.M @ P) * lam[6:], axis=0) / np.linalg.norm(KP, axis=0)
    return Modes(frequencies_hz=f[6:], shapes=P, rigid_frequencies_hz=f[:6],
                 rigid_shapes=phi[:, :6], rigid_residual=residual, residual=float(res.max()))


def rigid_residual(model: FEModel, phi_r: np.ndarray) -> float:
    """Largest relative M-norm part of an analytic rigid motion outside ``span(phi_r)``."""
    R = model.rigid_modes(model.points.mean(axis=0))
    MR = model.M @ R
    proj = phi_r @ (phi_r.T @ MR)          # phi_r is M-orthonormal
    E = R - proj
    num = np.einsum("ij,ij->j", E, model.M @ E)
    den = np.einsum("ij,ij->j", R, MR)
    return float(np.sqrt(np.max(num / den)))
