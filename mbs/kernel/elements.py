"""Numba force laws of the force elements between markers (see :mod:`axlebox.mbs.solver.elements`).

Each element row ``el_i = [kind, m1, m2, aux]`` and ``el_f`` (parameters) adds forces and moments
(inertial) to its markers' accumulators ``mkF``, ``mkM``.  Action and reaction are exact: the
reaction on marker 1 includes the couple ``(p2 - p1) x F2`` so that momentum is conserved when
the two markers do not coincide.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .body import cross
from .speed import G_LINE, profile_at

BUSHING, SPRING, BUMPSTOP, LOAD, DRIVE = 1, 2, 3, 4, 5
EL_KIND, EL_M1, EL_M2, EL_AUX = range(4)
# parameter slots
B_K, B_C, B_F0, B_D0 = 0, 6, 12, 18      # bushing: k (6), c (6), preload (6), offset (3)
S_K, S_C, S_L0, S_F0, S_NPT, S_TAB = 0, 1, 2, 3, 4, 8   # spring: table (x, f) pairs from S_TAB
P_GAP, P_K, P_EXP, P_C = 0, 1, 2, 3       # bump stop along axis aux of marker 1
L_F0, L_A, L_OM, L_PH, L_T0, L_T1, L_M0 = 0, 3, 6, 7, 8, 9, 10   # load on marker 1
D_M, D_R, D_J, D_KD = 0, 1, 2, 3       # drive: mass, radius, spin inertia, speed gain
EL_WIDTH = 48


@njit(cache=True, inline="always")
def _apply_pair(m1, m2, F2, M2, mkp, mkF, mkM, d, c):
    """``d``, ``c``: scratch (3,), passed in so that no element allocates."""
    for a in range(3):
        d[a] = mkp[m2, a] - mkp[m1, a]
    cross(d, F2, c)
    for a in range(3):
        mkF[m2, a] += F2[a]
        mkM[m2, a] += M2[a]
        mkF[m1, a] -= F2[a]
        mkM[m1, a] -= M2[a] + c[a]


@njit(cache=True, inline="always")
def _dot_cols(R1, i, R2, j):
    """``(R1^T R2)[i, j]``."""
    return R1[0, i] * R2[0, j] + R1[1, i] * R2[1, j] + R1[2, i] * R2[2, j]


@njit(cache=True)
def _table(x, tab, npt):
    """Piecewise-linear characteristic through ``npt`` (x, f) pairs, extrapolated linearly."""
    j = 0
    while j < npt - 2 and x > tab[2 * (j + 1)]:
        j += 1
    x0, f0, x1, f1 = tab[2 * j], tab[2 * j + 1], tab[2 * j + 2], tab[2 * j + 3]
    return f0 + (f1 - f0) * (x - x0) / (x1 - x0)


@njit(cache=True)
def _drive(t, m1, m2, aux, P, glob, mkv, mkR, mkF, mkM, out):
    """Traction or braking along the speed profile (:class:`axlebox.mbs.solver.elements.Drive`): the
    force ``F = M a(t) + kd (v(t) - v_aux)`` the profile asks of mass ``M`` (feed-forward, and
    a gain on marker ``aux``'s speed along the track against the profile's); with a radius
    ``r > 0`` a torque ``F r + J a / r`` about marker 1's y axis (the axle), its reaction on
    marker 2, else the force along x on marker 1 (reaction on the ground)."""
    _, v, a = profile_at(glob, t)
    if glob[G_LINE] != 0.0:
        # on a line: along the track, the aux marker's forward axis (its body's heading)
        Ra = mkR[aux]
        F = P[D_M] * a + P[D_KD] * (v - (mkv[aux, 0] * Ra[0, 0] + mkv[aux, 1] * Ra[1, 0]
                                         + mkv[aux, 2] * Ra[2, 0]))
    else:
        F = P[D_M] * a + P[D_KD] * (v - mkv[aux, 0])
    if P[D_R] > 0.0:
        T = F * P[D_R] + P[D_J] * a / P[D_R]
        R1 = mkR[m1]
        for c in range(3):
            mkM[m1, c] += T * R1[c, 1]
            mkM[m2, c] -= T * R1[c, 1]
        out[0] = T
    elif glob[G_LINE] != 0.0:
        R1 = mkR[m1]
        for c in range(3):
            mkF[m1, c] += F * R1[c, 0]
        out[0] = 0.0
    else:
        mkF[m1, 0] += F
        out[0] = 0.0
    out[1] = F


@njit(cache=True)
def element_forces(t, el_i, el_f, glob, mkp, mkv, mkR, mkw, mkF, mkM, elout):
    """Evaluate all elements; ``elout (ne, 6)`` gets each element's local force/moment on m2;
    ``glob``: the system's globals (the speed profile, for the drives)."""
    F2 = np.empty(3)
    M2 = np.empty(3)
    dp = np.empty(3)
    dv = np.empty(3)
    dl = np.empty(3)
    vl = np.empty(3)
    f = np.empty(6)
    w1 = np.empty(3)
    c = np.empty(3)
    sd = np.empty(3)
    sc = np.empty(3)
    for e in range(el_i.shape[0]):
        kind, m1, m2 = el_i[e, EL_KIND], el_i[e, EL_M1], el_i[e, EL_M2]
        P = el_f[e]
        if kind == DRIVE:
            _drive(t, m1, m2, el_i[e, EL_AUX], P, glob, mkv, mkR, mkF, mkM, elout[e])
            continue
        if kind == LOAD:
            on = P[L_T0] <= t < P[L_T1]
            s = math.sin(P[L_OM] * t + P[L_PH]) if on else 0.0
            for a in range(3):
                F = (P[L_F0 + a] + P[L_A + a] * s) if on else 0.0
                mkF[m1, a] += F
                mkM[m1, a] += P[L_M0 + a] if on else 0.0
                elout[e, a] = F
            continue
        R1 = mkR[m1]
        for a in range(3):
            dp[a] = mkp[m2, a] - mkp[m1, a]
            dv[a] = mkv[m2, a] - mkv[m1, a]
        if kind == SPRING:
            L = math.sqrt(dp[0] ** 2 + dp[1] ** 2 + dp[2] ** 2)
            Ld = (dp[0] * dv[0] + dp[1] * dv[1] + dp[2] * dv[2]) / L
            x = L - P[S_L0]
            npt = int(P[S_NPT])
            fs = _table(x, P[S_TAB:], npt) if npt >= 2 else -P[S_K] * x
            fn = P[S_F0] + fs - P[S_C] * Ld            # > 0 pushes the markers apart
            for a in range(3):
                F2[a] = fn * dp[a] / L
                M2[a] = 0.0
            elout[e, 0] = fn
            elout[e, 1] = x
            _apply_pair(m1, m2, F2, M2, mkp, mkF, mkM, sd, sc)
            continue
        # relative motion in marker 1's frame: d = R1^T dp, d' = R1^T dv - w1 x d
        for a in range(3):
            dl[a] = R1[0, a] * dp[0] + R1[1, a] * dp[1] + R1[2, a] * dp[2]
            vl[a] = R1[0, a] * dv[0] + R1[1, a] * dv[1] + R1[2, a] * dv[2]
            w1[a] = R1[0, a] * mkw[m1, 0] + R1[1, a] * mkw[m1, 1] + R1[2, a] * mkw[m1, 2]
        cross(w1, dl, c)
        for a in range(3):
            vl[a] -= c[a]
        if kind == BUSHING:
            R2 = mkR[m2]
            # small relative rotation: vee of the skew part of R1^T R2 (only its three
            # off-diagonal pairs, written out: a matrix product here was a third of the
            # elements' time); rate R1^T (w2 - w1)
            th0 = 0.5 * (_dot_cols(R1, 2, R2, 1) - _dot_cols(R1, 1, R2, 2))
            th1 = 0.5 * (_dot_cols(R1, 0, R2, 2) - _dot_cols(R1, 2, R2, 0))
            th2 = 0.5 * (_dot_cols(R1, 1, R2, 0) - _dot_cols(R1, 0, R2, 1))
            for a in range(3):
                wr = (R1[0, a] * (mkw[m2, 0] - mkw[m1, 0]) + R1[1, a] * (mkw[m2, 1] - mkw[m1, 1])
                      + R1[2, a] * (mkw[m2, 2] - mkw[m1, 2]))
                th = th0 if a == 0 else (th1 if a == 1 else th2)
                f[a] = P[B_F0 + a] - P[B_K + a] * (dl[a] - P[B_D0 + a]) - P[B_C + a] * vl[a]
                f[3 + a] = P[B_F0 + 3 + a] - P[B_K + 3 + a] * th - P[B_C + 3 + a] * wr
            for a in range(3):
                F2[a] = R1[a, 0] * f[0] + R1[a, 1] * f[1] + R1[a, 2] * f[2]
                M2[a] = R1[a, 0] * f[3] + R1[a, 1] * f[4] + R1[a, 2] * f[5]
            for a in range(6):
                elout[e, a] = f[a]
            _apply_pair(m1, m2, F2, M2, mkp, mkF, mkM, sd, sc)
        elif kind == BUMPSTOP:
            ax = el_i[e, EL_AUX]
            d = dl[ax]
            over = abs(d) - P[P_GAP]
            fa = 0.0
            if over > 0.0:
                sg = 1.0 if d > 0.0 else -1.0
                fa = -sg * P[P_K] * over ** P[P_EXP] - P[P_C] * vl[ax]
                if fa * sg > 0.0:          # damping must not pull the stop shut
                    fa = 0.0
            for a in range(3):
                F2[a] = R1[a, ax] * fa
                M2[a] = 0.0
            elout[e, 0] = fa
            elout[e, 1] = d
            _apply_pair(m1, m2, F2, M2, mkp, mkF, mkM, sd, sc)
