"""Free-free eigenmodes with a negative shift; rigid modes identified and checked; the same bits
in every run (a fixed start vector, degenerate pairs in a canonical basis: :mod:`.modebasis`)."""
from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from scipy.sparse.linalg import eigsh

from . import modebasis
from .assembly import FEModel
from .linsolve import Factor


@dataclass
class Modes:
    """Eigenpairs ``K phi = omega^2 M phi``, M-orthonormal, ascending."""

    frequencies_hz: np.ndarray   # (n,) elastic modes only
    shapes: np.ndarray           # (ndof, n) elastic modes only
    rigid_frequencies_hz: np.ndarray   # (6,) the near-zero ones, as computed
    rigid_shapes: np.ndarray     # (ndof, 6) their span's basis closest to the analytic rigid motions
    rigid_residual: float        # how far the analytic rigid motions lie outside their span
    residual: float = 0.0        # max ||K phi - w^2 M phi|| / ||K phi|| over the elastic modes


class RigidModeError(RuntimeError):
    """The free-free spectrum does not show exactly six rigid-body modes."""


PROBE_HZ = 10.0       # the first probe's shift; moved to the body's own scale when far from it
GAP_MIN = 10.0        # the rigid cluster's top and the first elastic frequency: at least this ratio


def free_free_modes(model: FEModel, n_elastic: int = 20, *, shift_hz: float | None = None,
                    rigid_tol: float = 1e-3, residual_tol: float = 1e-4) -> Modes:
    """Lowest ``n_elastic`` elastic free-free modes of ``model`` (see :func:`_solve`), the same
    bits in every run.

    With ``shift_hz=None`` the shift is chosen from the body (:func:`probe_shift`): a shift far
    below the first elastic mode leaves ``K - sigma M`` badly conditioned (about 1e12 for steel
    parts at 1 Hz) and the modes inaccurate, one far above it crowds the rigid and the first
    elastic modes together; the real solve shifts to ``-(pi f1)^2`` (half of f1).
    ``Modes.residual`` reports the eigen-residual achieved; above ``residual_tol`` a warning is
    raised.
    """
    if shift_hz is None:
        shift_hz = probe_shift(model)
    modes = _solve(model, n_elastic, shift_hz, rigid_tol)
    if modes.residual > residual_tol:
        warnings.warn(f"free-free modes: eigen-residual {modes.residual:.1e} above {residual_tol:g}",
                      RuntimeWarning, stacklevel=2)
    return modes


def probe_shift(model: FEModel, first_hz: float = PROBE_HZ, tries: int = 4) -> float:
    """Half the body's first elastic frequency, from cheap probing solves: the first at
    ``first_hz``; while the first elastic mode it finds lies more than 30 times above or 3 times
    below the probe's shift (a 1 Hz plate, a 5 kHz block), again at half that mode."""
    s = first_hz
    for _ in range(tries):
        f, _ = _eigenpairs(model, 12 + 6, s)
        n_rigid = rigid_count(f)
        f1 = f[n_rigid] if n_rigid < len(f) else f[-1]
        if s / 3 <= f1 <= 30 * s:
            break
        s = 0.5 * f1
    return 0.5 * f1


def rigid_count(f: np.ndarray, look: int = 13) -> int:
    """How many of the ascending frequencies ``f`` form the rigid cluster: the modes below the
    largest ratio between neighbours among the lowest ``look`` (a gap of at least ``GAP_MIN``;
    0 without one)."""
    f = np.asarray(f)[:look]
    if len(f) < 2:
        return 0
    floor = max(f.max(), 1e-300) * 1e-12
    ratio = f[1:] / np.maximum(f[:-1], floor)
    k = int(np.argmax(ratio))
    return k + 1 if ratio[k] >= GAP_MIN else 0


def _eigenpairs(model: FEModel, k: int, shift_hz: float, ncv: int | None = None):
    """``k`` eigenpairs nearest ``-(2 pi shift_hz)^2``, ascending, from the fixed start vector
    (frequencies Hz, M-orthonormal vectors)."""
    sigma = -(2 * np.pi * shift_hz) ** 2
    n = model.ndof
    k = min(k, n - 2)
    fac = Factor((model.K - sigma * model.M).tocsr())
    try:
        lam, phi = eigsh(model.K, k=k, M=model.M, sigma=sigma, OPinv=fac.operator(), which="LM",
                         tol=1e-10, ncv=None if ncv is None else min(ncv, n - 1),
                         **modebasis.fixed_start(n))
    finally:
        fac.free()
    order = np.argsort(lam, kind="stable")
    lam, phi = lam[order], phi[:, order]
    return np.sqrt(np.abs(lam)) / (2 * np.pi), phi


def _solve(model: FEModel, n_elastic: int, shift_hz: float, rigid_tol: float) -> Modes:
    """One shift-invert solve for the lowest ``n_elastic`` elastic free-free modes.

    The shift ``sigma = -(2 pi shift_hz)^2`` makes ``K - sigma M`` positive definite, so the
    singular free-free stiffness can be factored.  The rigid modes are not assumed: a few more
    pairs than asked for are computed, the rigid cluster is found by its gap to the first
    elastic mode (:func:`rigid_count`; there must be six) and the six analytic rigid motions
    must lie in its span (M-norm residual below ``rigid_tol``).  Where a solve finds fewer than
    six (a member lost in a tight cluster), it is solved again with the shift at a quarter of
    the first elastic mode it found and a wider Krylov space, rather than failing.
    """
    pad = max(6, n_elastic // 4)
    ncv = None
    for attempt in range(3):
        f, phi = _eigenpairs(model, n_elastic + 6 + pad, shift_hz, ncv)
        n_rigid = rigid_count(f)
        if n_rigid > 6:
            break                       # a mechanism or a disconnected body: no retry helps
        residual = rigid_residual(model, phi[:, :6]) if n_rigid == 6 else np.inf
        if n_rigid == 6 and residual <= rigid_tol:
            break
        if n_rigid:
            shift_hz = 0.25 * f[n_rigid]
        ncv = 2 * (n_elastic + 6 + pad) + 20 * (attempt + 1)
    if n_rigid != 6:
        raise RigidModeError(f"free-free spectrum shows {n_rigid} rigid modes, expected 6 "
                             f"(lowest frequencies {np.round(f[:8], 4)} Hz): the body may be "
                             "disconnected or constrained")
    if residual > rigid_tol:
        raise RigidModeError(f"the six near-zero modes do not span the rigid motions "
                             f"(residual {residual:.2e} > {rigid_tol:g})")
    f_el, P = f[6:6 + n_elastic], phi[:, 6:6 + n_elastic]
    # pairs of equal frequencies (axisymmetric or square bodies): one basis of their span
    P = modebasis.canonical(P, f_el, model.M)
    R = model.rigid_modes(model.points.mean(axis=0))
    rigid = modebasis.canonical(phi[:, :6], np.zeros(6), model.M, W=R)
    lam = (2 * np.pi * f_el) ** 2
    KP = model.K @ P
    res = np.linalg.norm(KP - (model.M @ P) * lam, axis=0) / np.linalg.norm(KP, axis=0)
    return Modes(frequencies_hz=f_el, shapes=P, rigid_frequencies_hz=f[:6],
                 rigid_shapes=rigid, rigid_residual=residual, residual=float(res.max()))


def rigid_residual(model: FEModel, phi_r: np.ndarray) -> float:
    """Largest relative M-norm part of an analytic rigid motion outside ``span(phi_r)``."""
    R = model.rigid_modes(model.points.mean(axis=0))
    MR = model.M @ R
    proj = phi_r @ (phi_r.T @ MR)          # phi_r is M-orthonormal
    E = R - proj
    num = np.einsum("ij,ij->j", E, model.M @ E)
    den = np.einsum("ij,ij->j", R, MR)
    return float(np.sqrt(np.max(num / den)))
