"""Numba kernels of one body in the floating frame of reference: plain arrays in, arrays out.

Body table ``bi`` (int, one row a body) and ``bf`` (float) slots, and the flat invariant array
``inv`` (per flexible body, at ``bi[b, BI_INV]``: Ct (3 n), Q (9 n), R (9 n^2), Me, K, D, Me^-1
(n^2 each), all C order).  State ``y``: positions at ``bi[b, BI_POS]``: ``r (3), p (4)`` unit
quaternion (w, x, y, z), ``beta`` (spinning bodies only), ``q (n)``; velocities at
``bi[b, BI_VEL]``: ``v (3)`` inertial, ``omega (3)`` body frame, ``qd (n)``.

Equations of motion (Shabana, Dynamics of Multibody Systems, 4th ed., eqs. 5.106-5.122, written
with the body-frame angular velocity), ``M(q) [v; omega; qd]' = Q - h``::

    M = [[m I,      -A S~,   A Ct ],
         [.,         J(q),   C(q) ],
         [.,         .,      Me   ]]
    S = mc + Ct q,  W_k = int rho u Phi_k^T = Q_k + sum_l R_lk q_l,  u = x + Phi q,
    J = tr(P) I - P,  P = P0 + sum_k q_k (W_k + Q_k^T),  C[:, k] = eps : W_k,
    h_r = A (w x (w x S) + 2 w x Ct qd)
    h_w = w_f x (J w) + 2 sum_k qd_k (w tr W_k - W_k^T w)
    h_k = w^T W_k w - |w|^2 tr W_k + 2 sum_l qd_l w . (int rho Phi_l x Phi_k)

and ``Q`` the applied loads plus ``-K q - D qd`` on the modal rows.  The modal block ``Me`` is
constant, so ``M`` is solved by its Schur complement on the 6 frame rows,
``(M_rr - M_rf Me^-1 M_fr) a_r = Q_r - M_rf Me^-1 Q_f``, ``qdd = Me^-1 (Q_f - M_fr a_r)``:
a 6 x 6 solve and products with the stored ``Me^-1`` instead of factorising the
``(6 + n)``-square ``M`` at every call (a third of the right-hand side's time before).

For a spinning body the frame turns with ``w_f = (w_x, 0, w_z)``; the rigid gyroscopic term
uses the material rate ``J w`` with the frame rate ``w_f`` (Euler's equations in a Resal
frame), the elastic terms use ``w_f`` (see :mod:`axlebox.mbs.solver.body`).
"""
from __future__ import annotations

import numpy as np
from numba import njit

# body table slots
BI_POS, BI_VEL, BI_N, BI_SPIN, BI_INV = range(5)
# a spinning body's spin angle among its positions (after r and p) and its body-frame rate about
# the axle among its velocities (after v and omega_x)
SPIN_ANGLE, SPIN_RATE = 7, 4
BF_M, BF_MC, BF_P0, BF_JINV, BF_GRAV = 0, 1, 4, 13, 22
BF_X = 23          # on a line: the body's place along the car, m (its track frame's, trajectory.py)
BF_WIDTH = 24


@njit(cache=True, inline="always")
def quat_to_A(p0, p1, p2, p3, A):
    """Rotation matrix of the unit quaternion (w, x, y, z), normalised on the fly."""
    s = 1.0 / (p0 * p0 + p1 * p1 + p2 * p2 + p3 * p3)
    A[0, 0] = 1.0 - 2.0 * s * (p2 * p2 + p3 * p3)
    A[0, 1] = 2.0 * s * (p1 * p2 - p0 * p3)
    A[0, 2] = 2.0 * s * (p1 * p3 + p0 * p2)
    A[1, 0] = 2.0 * s * (p1 * p2 + p0 * p3)
    A[1, 1] = 1.0 - 2.0 * s * (p1 * p1 + p3 * p3)
    A[1, 2] = 2.0 * s * (p2 * p3 - p0 * p1)
    A[2, 0] = 2.0 * s * (p1 * p3 - p0 * p2)
    A[2, 1] = 2.0 * s * (p2 * p3 + p0 * p1)
    A[2, 2] = 1.0 - 2.0 * s * (p1 * p1 + p2 * p2)


@njit(cache=True, inline="always")
def cross(a, b, out):
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]


@njit(cache=True)
def inv_views(inv, off, n):
    """Views of one body's invariants in the flat array."""
    o = off
    Ct = inv[o:o + 3 * n].reshape((3, n))
    o += 3 * n
    Q = inv[o:o + 9 * n].reshape((3, 3, n))
    o += 9 * n
    R = inv[o:o + 9 * n * n].reshape((3, 3, n, n))
    o += 9 * n * n
    Me = inv[o:o + n * n].reshape((n, n))
    o += n * n
    K = inv[o:o + n * n].reshape((n, n))
    o += n * n
    D = inv[o:o + n * n].reshape((n, n))
    o += n * n
    Mei = inv[o:o + n * n].reshape((n, n))
    return Ct, Q, R, Me, K, D, Mei


@njit(cache=True)
def frame_kinematics(b, y, bi, A, r, v, om, omf):
    """Frame rotation ``A (3, 3)``, position, velocity, material and frame angular velocity."""
    ip, iv = bi[b, BI_POS], bi[b, BI_VEL]
    quat_to_A(y[ip + 3], y[ip + 4], y[ip + 5], y[ip + 6], A)
    for a in range(3):
        r[a] = y[ip + a]
        v[a] = y[iv + a]
        om[a] = y[iv + 3 + a]
        omf[a] = om[a]
    if bi[b, BI_SPIN] == 1:
        omf[1] = 0.0


@njit(cache=True)
def position_rates(b, y, bi, omf, dy):
    """``dr = v``, quaternion rate ``p' = p (x) (0, w_f) / 2``, spin angle and modal rates."""
    ip, iv, n = bi[b, BI_POS], bi[b, BI_VEL], bi[b, BI_N]
    for a in range(3):
        dy[ip + a] = y[iv + a]
    p0, p1, p2, p3 = y[ip + 3], y[ip + 4], y[ip + 5], y[ip + 6]
    w0, w1, w2 = omf[0], omf[1], omf[2]
    dy[ip + 3] = 0.5 * (-p1 * w0 - p2 * w1 - p3 * w2)
    dy[ip + 4] = 0.5 * (p0 * w0 + p2 * w2 - p3 * w1)
    dy[ip + 5] = 0.5 * (p0 * w1 + p3 * w0 - p1 * w2)
    dy[ip + 6] = 0.5 * (p0 * w2 + p1 * w1 - p2 * w0)
    s = bi[b, BI_SPIN]
    if s == 1:
        dy[ip + 7] = y[iv + 4]
    for k in range(n):
        dy[ip + 7 + s + k] = y[iv + 6 + k]


@njit(cache=True)
def gravity_load(b, bi, bf, inv, y, A, g, Qg):
    """Generalised gravity load (6 + n) of body ``b``: ``m g``, ``S x A^T g``, ``Ct^T A^T g``."""
    n = bi[b, BI_N]
    m = bf[b, BF_M]
    # scalars, not small arrays: an allocation costs about as much as this whole load
    g0 = A[0, 0] * g[0] + A[1, 0] * g[1] + A[2, 0] * g[2]
    g1 = A[0, 1] * g[0] + A[1, 1] * g[1] + A[2, 1] * g[2]
    g2 = A[0, 2] * g[0] + A[1, 2] * g[1] + A[2, 2] * g[2]
    for a in range(3):
        Qg[a] = m * g[a]
    S0, S1, S2 = bf[b, BF_MC], bf[b, BF_MC + 1], bf[b, BF_MC + 2]
    if n > 0:
        Ct = inv_views(inv, bi[b, BI_INV], n)[0]
        q0 = bi[b, BI_POS] + 7 + bi[b, BI_SPIN]
        for k in range(n):
            S0 += Ct[0, k] * y[q0 + k]
            S1 += Ct[1, k] * y[q0 + k]
            S2 += Ct[2, k] * y[q0 + k]
            Qg[6 + k] = Ct[0, k] * g0 + Ct[1, k] * g1 + Ct[2, k] * g2
    Qg[3] = S1 * g2 - S2 * g1
    Qg[4] = S2 * g0 - S0 * g2
    Qg[5] = S0 * g1 - S1 * g0


@njit(cache=True)
def body_accelerations(b, y, bi, bf, inv, A, om, omf, Qb, acc):
    """Solve ``M acc = Qb - h`` for body ``b``; ``Qb`` (6 + n) holds the applied loads (gravity,
    markers).  Adds the elastic ``-K q - D qd``.  ``acc`` gets ``[v'; omega'; qdd]``."""
    n = bi[b, BI_N]
    m = bf[b, BF_M]
    if n == 0:
        # rigid: with the frame at c = S/m from the centre of mass, in body coordinates
        # (a_b = A^T v'),  m a_b - S x w' = f,  S x a_b + J_o w' = g,  which solve in closed form
        # with the inertia about the centre of mass J_c = J_o - (|S|^2 I - S S^T)/m:
        # w' = J_c^-1 (g - c x f),  a_b = f/m + c x w'
        # written with scalars (3 x 3 products and small arrays cost more than the algebra)
        P = bf[b, BF_P0:BF_P0 + 9]
        tr = P[0] + P[4] + P[8]
        o0, o1, o2 = om[0], om[1], om[2]
        Jw0 = tr * o0 - (P[0] * o0 + P[1] * o1 + P[2] * o2)
        Jw1 = tr * o1 - (P[3] * o0 + P[4] * o1 + P[5] * o2)
        Jw2 = tr * o2 - (P[6] * o0 + P[7] * o1 + P[8] * o2)
        w0, w1, w2 = omf[0], omf[1], omf[2]
        g0 = Qb[3] - (w1 * Jw2 - w2 * Jw1)
        g1 = Qb[4] - (w2 * Jw0 - w0 * Jw2)
        g2 = Qb[5] - (w0 * Jw1 - w1 * Jw0)
        S0, S1, S2 = bf[b, BF_MC], bf[b, BF_MC + 1], bf[b, BF_MC + 2]
        u0, u1, u2 = w1 * S2 - w2 * S1, w2 * S0 - w0 * S2, w0 * S1 - w1 * S0     # w x S
        v0, v1, v2 = w1 * u2 - w2 * u1, w2 * u0 - w0 * u2, w0 * u1 - w1 * u0     # w x (w x S)
        f0 = A[0, 0] * Qb[0] + A[1, 0] * Qb[1] + A[2, 0] * Qb[2] - v0
        f1 = A[0, 1] * Qb[0] + A[1, 1] * Qb[1] + A[2, 1] * Qb[2] - v1
        f2 = A[0, 2] * Qb[0] + A[1, 2] * Qb[1] + A[2, 2] * Qb[2] - v2
        c0, c1, c2 = S0 / m, S1 / m, S2 / m
        h0 = g0 - (c1 * f2 - c2 * f1)
        h1 = g1 - (c2 * f0 - c0 * f2)
        h2 = g2 - (c0 * f1 - c1 * f0)
        Ji = bf[b, BF_JINV:BF_JINV + 9]
        wd0 = Ji[0] * h0 + Ji[1] * h1 + Ji[2] * h2
        wd1 = Ji[3] * h0 + Ji[4] * h1 + Ji[5] * h2
        wd2 = Ji[6] * h0 + Ji[7] * h1 + Ji[8] * h2
        a0 = c1 * wd2 - c2 * wd1 + f0 / m
        a1 = c2 * wd0 - c0 * wd2 + f1 / m
        a2 = c0 * wd1 - c1 * wd0 + f2 / m
        for a in range(3):
            acc[a] = A[a, 0] * a0 + A[a, 1] * a1 + A[a, 2] * a2
        acc[3] = wd0
        acc[4] = wd1
        acc[5] = wd2
        return
    Ct, Qi, R, _, K, D, Mei = inv_views(inv, bi[b, BI_INV], n)
    q0 = bi[b, BI_POS] + 7 + bi[b, BI_SPIN]
    v0 = bi[b, BI_VEL] + 6
    q = y[q0:q0 + n]
    qd = y[v0:v0 + n]
    S = np.empty(3)
    Cq = np.zeros(3)
    for a in range(3):
        S[a] = bf[b, BF_MC + a]
        for k in range(n):
            S[a] += Ct[a, k] * q[k]
            Cq[a] += Ct[a, k] * qd[k]
    # W[a, c, k] = Q[a, c, k] + sum_l R[a, c, l, k] q_l
    W = Qi.copy()
    for a in range(3):
        for c in range(3):
            for l in range(n):
                ql = q[l]
                if ql != 0.0:
                    for k in range(n):
                        W[a, c, k] += R[a, c, l, k] * ql
    P = np.empty((3, 3))
    for a in range(3):
        for c in range(3):
            s = bf[b, BF_P0 + 3 * a + c]
            for k in range(n):
                s += q[k] * (W[a, c, k] + Qi[c, a, k])
            P[a, c] = s
    trP = P[0, 0] + P[1, 1] + P[2, 2]
    # frame block M_rr (6 x 6) and coupling M_rf (6 x n)
    Mrr = np.zeros((6, 6))
    for a in range(3):
        Mrr[a, a] = m
    # -A S~ : column c of S~ is e_c x S
    St = np.array([[0.0, -S[2], S[1]], [S[2], 0.0, -S[0]], [-S[1], S[0], 0.0]])
    for a in range(3):
        for c in range(3):
            s = 0.0
            for e in range(3):
                s -= A[a, e] * St[e, c]
            Mrr[a, 3 + c] = s
            Mrr[3 + c, a] = s
            Mrr[3 + a, 3 + c] = -P[a, c]
        Mrr[3 + a, 3 + a] += trP
    Mrf = np.empty((6, n))
    for k in range(n):
        for a in range(3):
            Mrf[a, k] = A[a, 0] * Ct[0, k] + A[a, 1] * Ct[1, k] + A[a, 2] * Ct[2, k]
        # C[:, k] = eps_abc W[b, c, k]
        Mrf[3, k] = W[1, 2, k] - W[2, 1, k]
        Mrf[4, k] = W[2, 0, k] - W[0, 2, k]
        Mrf[5, k] = W[0, 1, k] - W[1, 0, k]
    # quadratic velocity vector
    w = omf
    rhs = Qb.copy()
    t1 = np.empty(3)
    t2 = np.empty(3)
    cross(w, S, t1)
    cross(w, t1, t2)
    cross(w, Cq, t1)
    for a in range(3):
        t2[a] += 2.0 * t1[a]
    for a in range(3):
        rhs[a] -= A[a, 0] * t2[0] + A[a, 1] * t2[1] + A[a, 2] * t2[2]
    Jw = np.empty(3)
    for a in range(3):
        Jw[a] = trP * om[a] - (P[a, 0] * om[0] + P[a, 1] * om[1] + P[a, 2] * om[2])
    cross(w, Jw, t1)
    for a in range(3):
        rhs[3 + a] -= t1[a]
    ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2]
    for k in range(n):
        trW = W[0, 0, k] + W[1, 1, k] + W[2, 2, k]
        for a in range(3):
            WTw = W[0, a, k] * w[0] + W[1, a, k] * w[1] + W[2, a, k] * w[2]
            rhs[3 + a] -= 2.0 * qd[k] * (w[a] * trW - WTw)
        wWw = 0.0
        for a in range(3):
            for c in range(3):
                wWw += w[a] * W[a, c, k] * w[c]
        hk = wWw - ww * trW
        # 2 sum_l qd_l w . eps_abc R[b, c, l, k]
        s = 0.0
        for l in range(n):
            if qd[l] != 0.0:
                g0 = R[1, 2, l, k] - R[2, 1, l, k]
                g1 = R[2, 0, l, k] - R[0, 2, l, k]
                g2 = R[0, 1, l, k] - R[1, 0, l, k]
                s += qd[l] * (w[0] * g0 + w[1] * g1 + w[2] * g2)
        hk += 2.0 * s
        e = 0.0
        for l in range(n):
            e += K[k, l] * q[l] + D[k, l] * qd[l]
        rhs[6 + k] -= hk + e
    # Schur complement on the frame rows (module docstring): X = Me^-1 M_fr, z = Me^-1 Q_f
    X = np.empty((n, 6))
    z = np.empty(n)
    for k in range(n):
        zk = 0.0
        for l in range(n):
            zk += Mei[k, l] * rhs[6 + l]
        z[k] = zk
        for a in range(6):
            s = 0.0
            for l in range(n):
                s += Mei[k, l] * Mrf[a, l]
            X[k, a] = s
    r = np.empty(6)
    for a in range(6):
        s = rhs[a]
        for k in range(n):
            s -= Mrf[a, k] * z[k]
        r[a] = s
        for c in range(6):
            s = Mrr[a, c]
            for k in range(n):
                s -= Mrf[a, k] * X[k, c]
            Mrr[a, c] = s
    solve6(Mrr, r)
    for a in range(6):
        acc[a] = r[a]
    for k in range(n):
        s = z[k]
        for a in range(6):
            s -= X[k, a] * r[a]
        acc[6 + k] = s


@njit(cache=True)
def solve6(M, r):
    """``r <- M^-1 r`` for a symmetric positive definite 6 x 6 ``M`` (overwritten): Cholesky,
    ``M = L L^T`` in the lower triangle, then the two triangular solves."""
    for j in range(6):
        d = M[j, j]
        for k in range(j):
            d -= M[j, k] * M[j, k]
        d = np.sqrt(d)
        M[j, j] = d
        for i in range(j + 1, 6):
            s = M[i, j]
            for k in range(j):
                s -= M[i, k] * M[j, k]
            M[i, j] = s / d
    for i in range(6):
        s = r[i]
        for k in range(i):
            s -= M[i, k] * r[k]
        r[i] = s / M[i, i]
    for i in range(5, -1, -1):
        s = r[i]
        for k in range(i + 1, 6):
            s -= M[k, i] * r[k]
        r[i] = s / M[i, i]
