"""The rollers' and cages' rates of one DTRB advanced with their contact damping taken implicitly.

Why: a contact damping coefficient ``c`` on a body of mass ``m`` limits an explicit step to
about ``2 m / c``.  In the range the paper cites for bearing contacts (damping 2.5e-5 to 0.25 s
times the stiffness, below its Eq. 4) that is 1e-6 s and less on the rollers' tilt and the
cages (benchmarks/README.md), while the rings, two bodies of tens of kilograms, stay far from it.

The step: the leapfrog's velocity kick ``u+ = u- + h a(q, u-)`` becomes, for these rates,

    (M + h C) du = h M a(q, u-)

with ``M`` the rates' masses (roller: ``M_r``, ``M_r (R + rho)^2``, ``M_r``, ``J_d``, ``J_d``,
``J_a``; cage: ``M_c`` three times, ``J_cd``, ``J_cd``, ``J_cp``) and ``C = sum c J^T J`` over
the contacts in action, ``J`` the gradient of a contact's approach rate with respect to the
rates (bearing/kernel/blocks.py).  This is the linearly implicit Euler
step on the damping forces (``-c J u``, with ``u+`` in place of ``u-``): unconditionally stable for
them, first order like the leapfrog's own velocity forces.  The rings' rates stay explicit (they
are bodies of the vehicle).  A row's 20 rollers couple only through its cage, so ``M + h C`` is
block-arrowhead: each roller's 6 x 6 block is eliminated onto the cage's (a Schur complement),
the cage's 6 x 6 system solved, and the rollers recovered; every block is symmetric positive
definite (``M`` > 0, ``C`` >= 0), solved by Cholesky.  A roller that touched nothing in the
evaluation has no block (``C = 0``): its kick is the explicit one, ``du = h a``.

``"imex2"`` puts more in ``C``, with the same solve: ``h_k K`` (``h_k = h / 4`` times the kick's h, K the
contacts' stiffness: ``k J^T J`` of a point contact, and of a line contact its exact tangent in
its approach and tilt, ``contact.line_stiffness``, with the cross terms a roller touching along
part of its line has), which turns the kick into Newmark's average acceleration on the contact stiffness
(``(M + h^2 K / 4) du = h F(q_n)`` is ``q_{n+1} - 2 q_n + q_{n-1} = h^2 M^-1 F((q_{n+1} + 2 q_n +
q_{n-1}) / 4)`` linearised: unconditionally stable, second order, no numerical damping), and the
friction's secant damping ``mu Q / sqrt(|v_t|^2 + v_s^2)`` in each contact plane.

``theta`` weights the blocks (``M + theta h C``): 1, the shipped value, puts the damping at the
rates after the kick (first order); 1/2 would centre it (second order), but on the calibrated
bearing it is stable only to about 5e-6 s and ``theta = 0.8`` is needed at 1e-5 s
(benchmarks/README.md, "The implicit kick's order"), so it is kept for that measurement.
"""
from __future__ import annotations

from collections import namedtuple
from math import sqrt

import numpy as np

from axlebox._numba import kernel

from .layout import (BLK_CAGE, BLK_COUPLED, BLK_NONE, BLK_ROLLER, CPHI, FREE_CAGE, J_CD, J_CP, J_RA,
                     J_RD, KINEMATIC, M_C, M_R, N_CAGE, N_ROLLER, N_ROWS, PHI, R_M, RATE, RHO, Z)

NEWMARK_K = 0.25        # "imex2": h_k = NEWMARK_K h, Newmark's average acceleration (docstring)

#: the kick's scratch (:func:`scratch`): each roller's Cholesky factor ``L`` (n Z, 6, 6), its
#: coupling to the cage ``W`` (n Z, 6, 6) and right-hand side ``z`` (n Z, 6), n the rows; the cage's system
#: ``S``, factor ``Lc`` (6, 6) and right-hand side ``g`` (6)
Kick = namedtuple("Kick", ["L", "W", "z", "S", "Lc", "g"])


def scratch(Z_: int, rows: int, stack: tuple = ()) -> Kick:
    """The kick's :class:`Kick` scratch for a bearing of ``rows`` rows of ``Z_`` rollers."""
    n = rows * Z_
    return Kick(np.zeros(stack + (n, 6, 6)), np.zeros(stack + (n, 6, 6)), np.zeros(stack + (n, 6)),
                np.zeros(stack + (6, 6)), np.zeros(stack + (6, 6)), np.zeros(stack + (6,)))


@kernel
def one(K, b):
    """Bearing ``b``'s :class:`Kick` from a stack of them."""
    return Kick(K.L[b], K.W[b], K.z[b], K.S[b], K.Lc[b], K.g[b])


@kernel
def cholesky(A, L):
    """``L L^T = A`` (6 x 6, lower triangle of L)."""
    for i in range(6):
        for j in range(i + 1):
            s = A[i, j]
            for q in range(j):
                s -= L[i, q] * L[j, q]
            L[i, j] = sqrt(s) if i == j else s / L[j, j]


@kernel
def forward(L, b, x):
    """``x = L^-1 b`` (``x`` may be ``b``)."""
    for i in range(6):
        s = b[i]
        for q in range(i):
            s -= L[i, q] * x[q]
        x[i] = s / L[i, i]


@kernel
def backward(L, b, x):
    """``x = L^-T b`` (``x`` may be ``b``)."""
    for i in range(5, -1, -1):
        s = b[i]
        for q in range(i + 1, 6):
            s -= L[q, i] * x[q]
        x[i] = s / L[i, i]


@kernel
def roller_masses(P, Rr):
    """The masses of a roller's six rates (``Rr``: its centre's radius)."""
    return (P[M_R], P[M_R] * Rr * Rr, P[M_R], P[J_RD], P[J_RD], P[J_RA])


@kernel
def cage_masses(P):
    """The masses of a cage's six rates."""
    return (P[M_C], P[M_C], P[M_C], P[J_CD], P[J_CD], P[J_CP])


@kernel
def damped_kick(y, a, blk, cblk, flag, P, hk, theta, K):
    """Advance the rates of one bearing's rollers and cages in ``y`` (its state) by the kick
    ``hk`` from their explicit accelerations ``a`` (same layout) and the blocks ``blk`` (with
    their flags) and ``cblk`` (the rows' cages) the evaluation left (module docstring); ``K``:
    :class:`Kick` scratch.  A kinematic cage's azimuths are not rates of the system: their rows
    stay explicit.

    Per roller k of a row with a block, ``A_k = M_k + hk C_k`` (``L_k L_k^T``), ``B_k`` its
    coupling to the cage and ``r_k`` its right-hand side: ``W_k = L_k^-1 B_k``,
    ``z_k = L_k^-1 r_k``; the cage's ``(D - sum W_k^T W_k) du_c = r_c - sum W_k^T z_k``; then
    ``du_k = L_k^-T (z_k - W_k du_c)``."""
    nz = int(P[Z])
    hm = theta * hk
    kin = P[KINEMATIC] != FREE_CAGE
    mc = cage_masses(P)
    nrow = int(P[N_ROWS])
    for j in range(nrow):
        cb = nrow * nz * N_ROLLER + j * N_CAGE
        _cage_system(cblk[j], mc, a, cb, hm, hk, K.S, K.g)
        for k in range(nz):
            jk = j * nz + k
            b0 = jk * N_ROLLER
            if flag[jk] == BLK_NONE:
                _free_kick(y, a, b0, P, hk)
                continue
            _roller_system(y, a, blk, flag, jk, b0, P, hm, hk, kin, K)
        if kin:
            for q in range(6):
                K.S[CPHI, q] = 0.0
                K.S[q, CPHI] = 0.0
            K.S[CPHI, CPHI] = mc[CPHI]
            K.g[CPHI] = hk * mc[CPHI] * a[cb + RATE + CPHI]
        cholesky(K.S, K.Lc)
        forward(K.Lc, K.g, K.g)
        backward(K.Lc, K.g, K.g)              # the cage's rate increments
        for p in range(6):
            y[cb + RATE + p] += K.g[p]
        for k in range(nz):
            jk = j * nz + k
            if flag[jk] == BLK_NONE:
                continue
            if flag[jk] == BLK_COUPLED:
                for p in range(6):
                    s = 0.0
                    for q in range(6):
                        s += K.W[jk, p, q] * K.g[q]
                    K.z[jk, p] -= s
            backward(K.L[jk], K.z[jk], K.z[jk])
            for p in range(6):
                y[jk * N_ROLLER + RATE + p] += K.z[jk, p]


@kernel
def _cage_system(C, mc, a, cb, hm, hk, S, g):
    """The cage's own system before the rollers' Schur complements, ``M_c + hm C`` (``C`` the
    row's cage block), and its right-hand side."""
    for p in range(6):
        g[p] = hk * mc[p] * a[cb + RATE + p]
        for q in range(6):
            S[p, q] = hm * C[p, q]
        S[p, p] += mc[p]


@kernel
def _free_kick(y, a, b0, P, hk):
    """The kick of a roller that touched nothing (no damping: the explicit kick), as the
    Cholesky factor of its masses gives it (``M = L L^T``, ``L = sqrt(M)``), to the bit."""
    mr = roller_masses(P, P[R_M] + y[b0 + RHO])
    for p in range(6):
        d = sqrt(mr[p])
        y[b0 + RATE + p] += hk * mr[p] * a[b0 + RATE + p] / d / d


@kernel
def _roller_system(y, a, blk, flag, jk, b0, P, hm, hk, kin, K):
    """Roller ``jk``'s factor and right-hand side, and its Schur complement on the cage's system
    (:func:`damped_kick`)."""
    mr = roller_masses(P, P[R_M] + y[b0 + RHO])
    A = K.W[jk]                              # scratch for A until W is made
    L = K.L[jk]
    z = K.z[jk]
    for p in range(6):
        for q in range(6):
            A[p, q] = hm * blk[jk, p, BLK_ROLLER + q]
        A[p, p] += mr[p]
        z[p] = hk * mr[p] * a[b0 + RATE + p]
    if kin:                                   # the azimuth follows the cage: not a rate here
        for q in range(6):
            A[PHI, q] = 0.0
            A[q, PHI] = 0.0
        A[PHI, PHI] = mr[PHI]
    cholesky(A, L)
    forward(L, z, z)
    if flag[jk] != BLK_COUPLED:
        return
    W = K.W[jk]
    for q in range(6):                        # W = L^-1 B, B = hm blk[jk, :, BLK_CAGE:], by column
        for p in range(6):
            W[p, q] = 0.0 if (kin and (p == PHI or q == CPHI)) else hm * blk[jk, p, BLK_CAGE + q]
        for p in range(6):
            s = W[p, q]
            for r in range(p):
                s -= L[p, r] * W[r, q]
            W[p, q] = s / L[p, p]
    for p in range(6):                        # S -= W^T W, g -= W^T z
        for q in range(p + 1):
            s = 0.0
            for r in range(6):
                s += W[r, p] * W[r, q]
            K.S[p, q] -= s
            if q != p:
                K.S[q, p] -= s
        s = 0.0
        for r in range(6):
            s += W[r, p] * z[r]
        K.g[p] -= s
