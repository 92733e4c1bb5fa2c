"""Free-free eigenmodes with a negative shift, the rigid motions deflated and the count checked;
the same bits in every run (a fixed start vector, degenerate pairs in a canonical basis:
:mod:`.modebasis`).

A Lanczos solve (ARPACK) finds one vector of an eigenvalue from each start; the members of a
cluster of equal eigenvalues it finds only through rounding, and which of them depends on the last
bits of the BLAS kernel: two loose bars (twelve zero modes) showed all twelve with OpenBLAS's
default kernels and seven with ``OPENBLAS_CORETYPE=Haswell`` (issue 56).  Nothing here rests on
that: the parts are found from the mesh (:mod:`.parts`), the rigid motions of each part, known in
closed form, are deflated from the solve (it works in their M-orthogonal complement), and a Sturm
count (:func:`.linsolve.negative_eigenvalues`) checks that no eigenvalue below the last one
returned was skipped.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from scipy.sparse.linalg import LinearOperator, eigsh

from axlebox._params import ParameterError

from . import modebasis
from .assembly import FEModel
from .linsolve import Factor, negative_eigenvalues
from .parts import Part, parts


@dataclass
class Modes:
    """Eigenpairs ``K phi = omega^2 M phi``, M-orthonormal, ascending."""

    frequencies_hz: np.ndarray   # (n,) elastic modes only
    shapes: np.ndarray           # (ndof, n) elastic modes only
    rigid_frequencies_hz: np.ndarray   # (6 parts,) the rigid motions' (Rayleigh quotients: numerical zeros)
    rigid_shapes: np.ndarray     # (ndof, 6 parts) their span's basis closest to the analytic rigid motions
    rigid_residual: float        # bound on the angle between the rigid motions and K's null space
    residual: float = 0.0        # max ||K phi - w^2 M phi|| / ||K phi|| over the elastic modes


class RigidModeError(RuntimeError):
    """The free-free spectrum does not show exactly six rigid-body modes."""


class DisconnectedBodyError(RigidModeError):
    """The mesh is more than one part (twelve or more rigid modes)."""


class SpectrumError(RuntimeError):
    """The eigensolver's answer fails the Sturm count: an eigenvalue was skipped."""


PROBE_HZ = 10.0       # the first probe's shift; moved to the body's own scale when far from it
SHIFT_MIN_HZ = 0.01   # the lowest shift: a zero mode beyond the rigid motions (a mechanism) would
                      # draw the probe towards a singular K - sigma M; the solve refuses it instead
GAP_MIN = 10.0        # the rigid motions' frequency and the first elastic one: at least this ratio


def free_free_modes(model: FEModel, n_elastic: int = 20, *, shift_hz: float | None = None,
                    rigid_tol: float = 0.1, residual_tol: float = 1e-4,
                    allow_parts: bool = False) -> Modes:
    """Lowest ``n_elastic`` elastic free-free modes of ``model`` (see :func:`_solve`), the same
    bits in every run.

    A mesh of more than one part is refused (:class:`DisconnectedBodyError`, naming each part)
    unless ``allow_parts``, when each part brings its own six rigid motions.  With
    ``shift_hz=None`` the shift is chosen from the body (:func:`probe_shift`): a shift far below
    the first elastic mode leaves ``K - sigma M`` badly conditioned (about 1e12 for steel parts at
    1 Hz) and the modes inaccurate, one far above it crowds the rigid and the first elastic modes
    together; the real solve shifts to ``-(pi f1)^2`` (half of f1).  ``Modes.residual`` reports
    the eigen-residual achieved; above ``residual_tol`` a warning is raised.
    """
    pieces = body_parts(model)
    if len(pieces) > 1 and not allow_parts:
        raise DisconnectedBodyError(
            f"the body is {len(pieces)} separate parts ({6 * len(pieces)} rigid modes, expected 6): "
            + describe(model, pieces) + "; a body must be one connected mesh")
    available = model.ndof - 6 * len(pieces) - 2
    if not 1 <= n_elastic < available:
        raise ParameterError(f"n_elastic = {n_elastic!r} is not allowed: expected 1 to {available - 1} "
                             f"(the mesh's {model.ndof} DOF less its rigid motions and the count's margin)")
    W = rigid_motions(model, pieces)
    if shift_hz is None:
        shift_hz = probe_shift(model, R=m_orthonormal(model, W))
    modes = _solve(model, n_elastic, shift_hz, rigid_tol, W)
    if modes.residual > residual_tol:
        warnings.warn(f"free-free modes: eigen-residual {modes.residual:.1e} above {residual_tol:g}",
                      RuntimeWarning, stacklevel=2)
    return modes


def body_parts(model: FEModel) -> list[Part]:
    """The connected parts of ``model``'s mesh (:func:`.parts.parts`)."""
    return parts(model.mesh)


def describe(model: FEModel, pieces: list[Part], most: int = 5) -> str:
    """The parts, one phrase each (elements, nodes, mass, bounding box), the first ``most``."""
    Mx = model.scalar_mass()
    out = []
    for i, piece in enumerate(pieces[:most]):
        t = np.zeros(len(model.points))
        t[piece.nodes] = 1.0
        out.append(f"part {i + 1}: {piece.describe(float(t @ (Mx @ t)))}")
    if len(pieces) > most:
        out.append(f"and {len(pieces) - most} more")
    return "; ".join(out)


def rigid_motions(model: FEModel, pieces: list[Part]) -> np.ndarray:
    """``(ndof, 6 len(pieces))``: each part's three translations and three rotations (about its
    own centre), zero on the other parts."""
    blocks = []
    for piece in pieces:
        R = model.rigid_modes(model.points[piece.nodes].mean(axis=0))
        off = np.ones(len(model.points), bool)
        off[piece.nodes] = False
        R[model.dofs[off].ravel()] = 0.0
        blocks.append(R)
    return np.hstack(blocks)


def m_orthonormal(model: FEModel, R: np.ndarray) -> np.ndarray:
    """A basis of ``span(R)`` with ``B^T M B = I`` (``R L^-T``, ``L L^T = R^T M R``)."""
    G = R.T @ (model.M @ R)
    L = np.linalg.cholesky(0.5 * (G + G.T))
    return np.linalg.solve(L, R.T).T


def probe_shift(model: FEModel, first_hz: float = PROBE_HZ, tries: int = 4, *,
                R: np.ndarray | None = None) -> float:
    """Half the body's first elastic frequency, from cheap probing solves: the first at
    ``first_hz``; while the first elastic mode it finds lies more than 30 times above or 3 times
    below the probe's shift (a 1 Hz plate, a 5 kHz block), again at half that mode (at least
    ``SHIFT_MIN_HZ``)."""
    if R is None:
        R = m_orthonormal(model, rigid_motions(model, body_parts(model)))
    s = first_hz
    for _ in range(tries):
        f, _ = _eigenpairs(model, 6, s, R)
        f1 = max(f[0], 2 * SHIFT_MIN_HZ)
        if s / 3 <= f1 <= 30 * s:
            break
        s = 0.5 * f1
    return 0.5 * f1


def rigid_count(f: np.ndarray, look: int = 13) -> int:
    """How many of the ascending frequencies ``f`` form the rigid cluster: the modes below the
    largest ratio between neighbours among the lowest ``look`` (a gap of at least ``GAP_MIN``;
    0 without one)."""
    f = np.sort(np.asarray(f))[:look]
    if len(f) < 2:
        return 0
    floor = max(f.max(), 1e-300) * 1e-12
    ratio = f[1:] / np.maximum(f[:-1], floor)
    k = int(np.argmax(ratio))
    return k + 1 if ratio[k] >= GAP_MIN else 0


def _eigenpairs(model: FEModel, k: int, shift_hz: float, R: np.ndarray, ncv: int | None = None):
    """``k`` eigenpairs nearest ``-(2 pi shift_hz)^2`` in the M-orthogonal complement of the
    rigid motions ``R`` (M-orthonormal), ascending, from the fixed start vector (frequencies Hz,
    M-orthonormal vectors).

    The shift-invert operator ``(K - sigma M)^-1 M`` with the projection ``P = I - R R^T M``
    after it: the rigid motions are its eigenvectors (``K R = 0``), so ``P`` commutes with it, and
    ``P (K - sigma M)^-1 M`` has the elastic spectrum and zeros, which ARPACK's largest-magnitude
    search never returns."""
    sigma = -(2 * np.pi * shift_hz) ** 2
    n = model.ndof
    k = min(k, n - R.shape[1] - 2)
    MR = model.M @ R
    fac = Factor((model.K - sigma * model.M).tocsr())

    def deflated(x):
        y = fac.solve(x)
        return y - R @ (MR.T @ y)

    start = modebasis.fixed_start(n)
    start["v0"] = start["v0"] - R @ (MR.T @ start["v0"])
    try:
        lam, phi = eigsh(model.K, k=k, M=model.M, sigma=sigma, which="LM", tol=1e-10,
                         OPinv=LinearOperator((n, n), matvec=deflated, matmat=deflated, dtype=np.float64),
                         ncv=None if ncv is None else min(ncv, n - R.shape[1] - 1), **start)
    finally:
        fac.free()
    order = np.argsort(lam, kind="stable")
    lam, phi = lam[order], phi[:, order]
    return np.sqrt(np.abs(lam)) / (2 * np.pi), phi


def sturm_cut(f: np.ndarray, first: int) -> tuple[int, float]:
    """``(j, mu_hz)``: where to count, at or past mode ``first`` of the ascending ``f``: between
    the neighbours ``f[j] < f[j + 1]`` farthest apart (by ratio), ``mu`` their geometric mean, so
    that no eigenvalue lies near the count's shift."""
    ratio = f[first + 1:] / np.maximum(f[first:-1], 1e-300)
    j = first + int(np.argmax(ratio))
    return j, float(np.sqrt(f[j] * f[j + 1]))


def _solve(model: FEModel, n_elastic: int, shift_hz: float, rigid_tol: float, W: np.ndarray) -> Modes:
    """One shift-invert solve for the lowest ``n_elastic`` elastic free-free modes, checked.

    The shift ``sigma = -(2 pi shift_hz)^2`` makes ``K - sigma M`` positive definite, so the
    singular free-free stiffness can be factored; the solve runs in the complement of the rigid
    motions ``W`` (:func:`rigid_motions`, :func:`_eigenpairs`).  A few more pairs than asked for
    are computed, and the Sturm count below a cut among them (:func:`sturm_cut`) must equal the
    rigid motions plus the modes found below it; where it is larger (a member of a cluster
    skipped) the solve is repeated with a wider Krylov space.  Nothing but the rigid motions may
    be free (the spectrum's largest gap right above them, at least ``GAP_MIN``: else a mechanism,
    :func:`rigid_count`), and they must be: their Rayleigh frequencies at most ``rigid_tol`` times
    the first elastic one (the ratio bounds the sine of their angle to K's null space; ``K R`` is
    zero but for rounding, which reaches 0.006 Hz against 1.7 Hz on a thin plate, and a
    constraint would give them frequencies like the elastic ones).
    """
    R = m_orthonormal(model, W)
    r = R.shape[1]
    f_rigid = np.sqrt(np.abs(np.linalg.eigvalsh(R.T @ (model.K @ R)))) / (2 * np.pi)
    pad = max(6, n_elastic // 4)
    k = n_elastic + pad
    ncv = None
    for attempt in range(3):
        f, phi = _eigenpairs(model, k, shift_hz, R, ncv)
        # free: the rigid motions far below the elastic modes (a constraint gives them energy);
        # and nothing else free (a mechanism: a further zero, the rigid cluster's gap above it)
        n_free = rigid_count(np.concatenate([f_rigid, f[:7]]), look=r + 7)
        residual = float(f_rigid.max() / f[0])
        if f_rigid.max() > rigid_tol * f[:7].max() or (residual > rigid_tol and n_free <= r):
            raise RigidModeError(f"the rigid motions are not free: their frequencies reach "
                                 f"{f_rigid.max():.3g} Hz against the first elastic mode's {f[0]:.4g} Hz "
                                 f"(ratio {residual:.2e} > {rigid_tol:g}): the body is constrained")
        if n_free != r:
            raise RigidModeError(f"free-free spectrum shows more than {r} rigid modes (the rigid motions "
                                 f"up to {f_rigid.max():.2g} Hz, the lowest others {np.round(f[:8], 4)} "
                                 "Hz): a mechanism, or parts joined only at a node or an edge")
        j, mu = sturm_cut(f, n_elastic - 1)
        below = negative_eigenvalues((model.K - (2 * np.pi * mu) ** 2 * model.M).tocsr())
        if below == r + j + 1:
            break
        ncv = 2 * k + 20 * (attempt + 1)
    else:
        raise SpectrumError(f"free-free modes: {below} eigenvalues lie below {mu:.6g} Hz, the solve "
                            f"found {r} rigid and {j + 1} elastic ones (lowest {np.round(f[:8], 4)} Hz)")
    f_el, P = f[:n_elastic], phi[:, :n_elastic]
    # pairs of equal frequencies (axisymmetric or square bodies): one basis of their span
    P = modebasis.canonical(P, f_el, model.M)
    rigid = modebasis.canonical(R, np.zeros(r), model.M, W=W)
    lam = (2 * np.pi * f_el) ** 2
    KP = model.K @ P
    res = np.linalg.norm(KP - (model.M @ P) * lam, axis=0) / np.linalg.norm(KP, axis=0)
    return Modes(frequencies_hz=f_el, shapes=P, rigid_frequencies_hz=np.sort(f_rigid),
                 rigid_shapes=rigid, rigid_residual=residual, residual=float(res.max()))
