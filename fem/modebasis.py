"""Deterministic eigensolver starts and canonical bases of (near-)degenerate eigenvector clusters.

ARPACK (``scipy.sparse.linalg.eigsh``) starts from a random vector unless given one, so the same
body gave other eigenvectors, and sometimes another count of near-zero modes, from run to run.
And where eigenvalues coincide (an axisymmetric wheelset's bending pairs, a square plate's or a
square bar's), any rotation of the pair is as good an answer, so the solver's is arbitrary.  Here:

* :func:`start_vector` — a fixed start with no symmetry of any mesh: the Weyl sequence
  ``frac(k * g)``, g the golden ratio's fractional part, centred (the same vector in every run,
  process and machine; it is not orthogonal to any mode but by accident of measure zero);
* :func:`canonical` — each cluster of eigenvalues within ``rel_tol`` of each other is rotated to
  the M-orthonormal basis of its subspace closest to fixed reference vectors (the polar factor of
  their projections), so the basis depends on the subspace only, not on the solver's rotation
  or signs; a single mode's sign is fixed the same way.
"""
from __future__ import annotations

import inspect

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import eigsh

GOLDEN = 0.6180339887498949          # (sqrt 5 - 1) / 2: the most irrational step
DEGENERATE = 1e-6     # eigenvalues this close (relative) form one subspace, returned canonically


def start_vector(n: int, offset: int = 0) -> np.ndarray:
    """``n`` values of the centred Weyl sequence ``frac((k + offset) g) - 1/2``, k = 1..n."""
    k = np.arange(1, n + 1, dtype=np.float64) + offset
    return np.modf(k * GOLDEN)[0] - 0.5


# ARPACK draws a new vector when a restart finds an invariant subspace (a cluster of equal
# eigenvalues: the rigid modes): SciPy's own generator since it took ARPACK into C (the `rng`
# argument), a per-process seed before
_SEEDS_RESTARTS = "rng" in inspect.signature(eigsh).parameters


def fixed_start(n: int) -> dict:
    """``eigsh`` keywords for the same start and the same restarts in every call and run."""
    kw = {"v0": start_vector(n)}
    if _SEEDS_RESTARTS:
        kw["rng"] = np.random.default_rng(0)
    return kw


def references(n: int, count: int) -> np.ndarray:
    """``(n, count)`` fixed reference vectors: Weyl sequences of distinct offsets."""
    return np.column_stack([start_vector(n, offset=7919 * (j + 1)) for j in range(count)])


def clusters(values: np.ndarray, rel_tol: float) -> list[np.ndarray]:
    """Index groups of ascending ``values`` whose neighbours lie within ``rel_tol`` of the
    larger (each group contiguous)."""
    groups, start = [], 0
    for i in range(1, len(values) + 1):
        if i == len(values) or abs(values[i] - values[i - 1]) > rel_tol * max(abs(values[i]),
                                                                               abs(values[i - 1])):
            groups.append(np.arange(start, i))
            start = i
    return groups


def canonical(phi: np.ndarray, values: np.ndarray, M: sp.spmatrix, rel_tol: float = DEGENERATE,
              W: np.ndarray | None = None) -> np.ndarray:
    """``phi`` (M-orthonormal columns, ``values`` ascending) with every cluster of values within
    ``rel_tol`` replaced by the basis of its span closest to the references ``W`` (default
    :func:`references`): ``phi_c U V^T`` where ``phi_c^T M W_c = U S V^T``.  The span, and each
    mode's M-orthonormality, are unchanged."""
    out = np.array(phi, dtype=np.float64, copy=True)
    groups = clusters(np.asarray(values), rel_tol)
    width = max(len(g) for g in groups) if groups else 0
    if W is None:
        W = references(phi.shape[0], width)
    MW = M @ W
    for g in groups:
        c = len(g)
        A = out[:, g].T @ MW[:, :c]
        U, _, Vt = np.linalg.svd(A)
        out[:, g] = out[:, g] @ (U @ Vt)
    return out
