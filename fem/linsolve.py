"""Sparse symmetric factorisation: MKL PARDISO when available, SuperLU otherwise.

PARDISO (through pypardiso) factors the 100k-DOF quadratic-tetrahedron systems of
this package about six times faster than SuperLU on two cores; SuperLU keeps the
package working where MKL is not available (non-x86 machines).
"""
from __future__ import annotations

import os

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import LinearOperator, splu

# MKL's results otherwise depend on the alignment of the arrays it is handed, so two solves of one
# system could differ in the last bits and two builds of one body in their modes; AUTO makes every
# run on this machine give the same bits.  Read when MKL loads: set before pypardiso loads it.
os.environ.setdefault("MKL_CBWR", "AUTO")
try:  # pragma: no cover - depends on the platform
    import pypardiso
except Exception:  # noqa: BLE001 - any import failure means "not available"
    pypardiso = None


class Factor:
    """Factor a symmetric positive definite matrix once; solve for any number of right-hand sides.

    Every system this package factors is SPD (shifted free-free stiffness,
    fixed-interface stiffness), so PARDISO runs as an exact Cholesky (mtype 2)
    rather than the indefinite solver, whose pivot perturbation costs accuracy.
    """

    def __init__(self, A: sp.spmatrix, *, backend: str | None = None):
        self.shape = A.shape
        self.backend = backend or ("pardiso" if pypardiso is not None else "superlu")
        if self.backend == "pardiso":
            # real SPD (2): upper triangle only
            self._A = sp.triu(A, format="csr").astype(np.float64)
            self._A.sort_indices()
            self._s = pypardiso.PyPardisoSolver(mtype=2)
            self._s.set_phase(12)
            self._s._call_pardiso(self._A, np.zeros(self.shape[0]))
        elif self.backend == "superlu":
            self._lu = splu(sp.csc_matrix(A), permc_spec="COLAMD")
        else:
            raise ValueError(f"backend = {backend!r} is not allowed: expected 'pardiso' or 'superlu'")

    def solve(self, b: np.ndarray) -> np.ndarray:
        b = np.asarray(b, dtype=np.float64)
        if self.backend == "superlu":
            return self._lu.solve(b)
        self._s.set_phase(33)   # solve only; skips pypardiso's per-call matrix hashing
        return self._s._call_pardiso(self._A, np.asfortranarray(b) if b.ndim == 2 else b)

    def operator(self) -> LinearOperator:
        return LinearOperator(self.shape, matvec=self.solve, matmat=self.solve, dtype=np.float64)

    def free(self) -> None:
        if self.backend == "pardiso":
            self._s.free_memory(everything=True)


def negative_eigenvalues(A: sp.spmatrix, *, backend: str | None = None) -> int:
    """How many eigenvalues of the symmetric ``A`` are negative: the negative pivots of its
    ``L D L^T`` (Sylvester's law of inertia).  With ``A = K - mu M`` it counts the eigenvalues of
    ``(K, M)`` below ``mu``: the Sturm sequence check of FE eigensolvers (Bathe, *Finite Element
    Procedures*, 2nd ed., section 11.4.3), which no Lanczos solve can fool.

    PARDISO's symmetric indefinite factor (mtype -2) reports the inertia; it is taken only where
    no pivot was perturbed (a perturbed tiny pivot may have the wrong sign).  Else SuperLU with
    diagonal pivots and one symmetric ordering, where ``U = D L^T``; refused where it had to pivot
    off the diagonal."""
    n = A.shape[0]
    backend = backend or ("pardiso" if pypardiso is not None else "superlu")
    if backend == "pardiso":
        s = pypardiso.PyPardisoSolver(mtype=-2)
        upper = sp.triu(A, format="csr").astype(np.float64)
        upper.sort_indices()
        s.set_phase(12)
        try:
            s._call_pardiso(upper, np.zeros(n))
            positive, negative, perturbed = int(s.iparm[21]), int(s.iparm[22]), int(s.iparm[13])
        finally:
            s.free_memory(everything=True)
        if perturbed == 0 and positive + negative == n:
            return negative
        backend = "superlu"
    if backend != "superlu":
        raise ValueError(f"backend = {backend!r} is not allowed: expected 'pardiso' or 'superlu'")
    lu = splu(sp.csc_matrix(A), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
              options={"SymmetricMode": True})
    if not np.array_equal(lu.perm_r, lu.perm_c):
        raise RuntimeError("inertia: SuperLU pivoted off the diagonal; the signs of U's diagonal "
                           "do not give the inertia of this matrix")
    return int(np.count_nonzero(lu.U.diagonal() < 0.0))
