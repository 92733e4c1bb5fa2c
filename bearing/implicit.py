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
rates (:func:`axlebox.bearing.kernel.dtrb_rhs_damped`).  This is the linearly implicit Euler
step on the damping forces (``-c J u``, with ``u+`` in place of ``u-``): unconditionally stable for
them, first order like the leapfrog's own velocity forces.  The rings' rates stay explicit (they
are bodies of the vehicle).  A row's 20 rollers couple only through its cage, so ``M + h C`` is
block-arrowhead: each roller's 6 x 6 block is eliminated onto the cage's (a Schur complement),
the cage's 6 x 6 system solved, and the rollers recovered; every block is symmetric positive
definite (``M`` > 0, ``C`` >= 0), solved by Cholesky.

``"imex2"`` puts more in ``C``, with the same solve: ``h_k K`` (``h_k = h / 4`` times the kick's h, K the
contacts' stiffness: ``k J^T J`` of a point contact, and of a line contact its exact tangent in
its approach and tilt, ``kernel.line_stiffness``, with the cross terms a roller touching along
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

import math

import numpy as np
from numba import njit

from .layout import J_CD, J_CP, J_RA, J_RD, KINEMATIC, M_C, M_R, N_CAGE, N_ROLLER, R_M, RHO, Z

NEWMARK_K = 0.25        # "imex2": h_k = NEWMARK_K h, Newmark's average acceleration (docstring)


@njit(inline="always")
def _cholesky(A, L):
    """``L L^T = A`` (6 x 6, lower triangle of L)."""
    for i in range(6):
        for j in range(i + 1):
            s = A[i, j]
            for q in range(j):
                s -= L[i, q] * L[j, q]
            L[i, j] = math.sqrt(s) if i == j else s / L[j, j]


@njit(inline="always")
def _forward(L, b, x):
    """``x = L^-1 b`` (``x`` may be ``b``)."""
    for i in range(6):
        s = b[i]
        for q in range(i):
            s -= L[i, q] * x[q]
        x[i] = s / L[i, i]


@njit(inline="always")
def _backward(L, b, x):
    """``x = L^-T b`` (``x`` may be ``b``)."""
    for i in range(5, -1, -1):
        s = b[i]
        for q in range(i + 1, 6):
            s -= L[q, i] * x[q]
        x[i] = s / L[i, i]


@njit(cache=True)
def damped_kick(y, a, G, P, hk, theta=1.0):
    """Advance the rates of one bearing's rollers and cages in ``y`` (its state, bearing/layout.py)
    by the kick ``hk`` from their explicit accelerations ``a`` (same layout) and the damping
    blocks ``G`` the right-hand side left (module docstring).  A kinematic cage's azimuths are
    not rates of the system: their rows stay explicit.

    Per roller k of a row, with ``A_k = M_k + hk C_k`` (its own block, ``L_k L_k^T``), ``B_k``
    its coupling to the cage and ``r_k`` its right-hand side: ``W_k = L_k^-1 B_k``,
    ``z_k = L_k^-1 r_k``; the cage's ``(D - sum W_k^T W_k) du_c = r_c - sum W_k^T z_k``; then
    ``du_k = L_k^-T (z_k - W_k du_c)``."""
    nz = int(P[Z])
    hm = theta * hk
    nr = 2 * nz * N_ROLLER
    kin = P[KINEMATIC] != 0.0
    mr = np.empty(6)
    mc = np.array([P[M_C], P[M_C], P[M_C], P[J_CD], P[J_CD], P[J_CP]])
    A = np.empty((6, 6))
    S = np.empty((6, 6))
    Ls = np.empty((nz, 6, 6))
    Ws = np.empty((nz, 6, 6))
    Zr = np.empty((nz, 6))
    coupled = np.zeros(nz, np.bool_)
    Lc = np.empty((6, 6))
    g = np.empty(6)
    for j in range(2):
        cb = nr + j * N_CAGE
        for p in range(6):
            g[p] = hk * mc[p] * a[cb + 6 + p]
            for q in range(6):
                S[p, q] = hm * G[j, nz, p, q]
            S[p, p] += mc[p]
        for k in range(nz):
            b0 = (j * nz + k) * N_ROLLER
            Rr = P[R_M] + y[b0 + RHO]
            mr[0], mr[1], mr[2] = P[M_R], P[M_R] * Rr * Rr, P[M_R]
            mr[3], mr[4], mr[5] = P[J_RD], P[J_RD], P[J_RA]
            for p in range(6):
                for q in range(6):
                    A[p, q] = hm * G[j, k, p, q]
                A[p, p] += mr[p]
                Zr[k, p] = hk * mr[p] * a[b0 + 6 + p]
            if kin:                           # the azimuth follows the cage: not a rate here
                for q in range(6):
                    A[1, q] = 0.0
                    A[q, 1] = 0.0
                A[1, 1] = mr[1]
            _cholesky(A, Ls[k])
            _forward(Ls[k], Zr[k], Zr[k])
            coupled[k] = False
            for p in range(6):
                for q in range(6):
                    if G[j, k, p, 6 + q] != 0.0:
                        coupled[k] = True
            if not coupled[k]:
                continue
            W = Ws[k]
            for q in range(6):                # W = L^-1 B, B = hk G[j, k, :, 6:], column by column
                for p in range(6):
                    W[p, q] = 0.0 if (kin and (p == 1 or q == 5)) else hm * G[j, k, p, 6 + q]
                for p in range(6):
                    s = W[p, q]
                    for r in range(p):
                        s -= Ls[k, p, r] * W[r, q]
                    W[p, q] = s / Ls[k, p, p]
            for p in range(6):                # S -= W^T W, g -= W^T z
                for q in range(p + 1):
                    s = 0.0
                    for r in range(6):
                        s += W[r, p] * W[r, q]
                    S[p, q] -= s
                    if q != p:
                        S[q, p] -= s
                s = 0.0
                for r in range(6):
                    s += W[r, p] * Zr[k, r]
                g[p] -= s
        if kin:
            for q in range(6):
                S[5, q] = 0.0
                S[q, 5] = 0.0
            S[5, 5] = mc[5]
            g[5] = hk * mc[5] * a[cb + 11]
        _cholesky(S, Lc)
        _forward(Lc, g, g)
        _backward(Lc, g, g)                   # the cage's rate increments
        for p in range(6):
            y[cb + 6 + p] += g[p]
        for k in range(nz):
            b0 = (j * nz + k) * N_ROLLER
            if coupled[k]:
                for p in range(6):
                    s = 0.0
                    for q in range(6):
                        s += Ws[k, p, q] * g[q]
                    Zr[k, p] -= s
            _backward(Ls[k], Zr[k], Zr[k])
            for p in range(6):
                y[b0 + 6 + p] += Zr[k, p]
