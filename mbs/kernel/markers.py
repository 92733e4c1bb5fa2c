"""Numba kernels for markers: points on bodies where force elements act and sensors read.

A marker sits at ``x0`` in its body's frame with a constant orientation ``R0`` there (its axes,
``mk_f[m, 3:12]`` row-major); on a flexible body it may follow a node, whose shape
rows ``Phi (6, n)`` (translation; small rotation) are stored flat in ``shp`` at ``mk_i[m, MK_SHP]``.
Body ``-1`` is the ground (inertial, fixed).  Marker kinematics are those of the body's
reference frame plus the node's elastic motion:

    u = x0 + Phi_t q,   p = r + A u,   v = r' + A (w_f x u + Phi_t qd),
    R = A (I + (Phi_r q)~) R0,   w = A (w_f + Phi_r qd)

with ``w_f`` the frame's angular velocity (it differs from the material's only on a spinning body,
whose markers are frame points: journals, gear seat, tread point in the non-spinning frame).
A force ``F`` and moment ``M`` (inertial) at a marker load its body with
``[F; u x A^T F + A^T M; Phi_t^T A^T F + Phi_r^T A^T M]`` (virtual work of the material point).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .body import BI_N, BI_POS, BI_SPIN, BI_VEL, cross

MK_BODY, MK_SHP = 0, 1


@njit(cache=True)
def marker_kinematics(y, bi, mk_i, mk_f, shp, Ab, rb, vb, omfb, mku, mkp, mkv, mkR, mkw):
    """Fill position, velocity, orientation and angular velocity (inertial) of every marker;
    ``mku`` gets the deformed local position ``u``."""
    nm = mk_i.shape[0]
    u = np.empty(3)
    ud = np.empty(3)
    th = np.empty(3)
    thd = np.empty(3)
    t = np.empty(3)
    for m in range(nm):
        b = mk_i[m, MK_BODY]
        if b < 0:
            for a in range(3):
                mkp[m, a] = mk_f[m, a]
                mkv[m, a] = 0.0
                mkw[m, a] = 0.0
                mku[m, a] = mk_f[m, a]
                for c in range(3):
                    mkR[m, a, c] = mk_f[m, 3 + 3 * a + c]
            continue
        for a in range(3):
            u[a] = mk_f[m, a]
            ud[a] = 0.0
            th[a] = 0.0
            thd[a] = 0.0
        so = mk_i[m, MK_SHP]
        if so >= 0:
            n = bi[b, BI_N]
            q0 = bi[b, BI_POS] + 7 + bi[b, BI_SPIN]
            v0 = bi[b, BI_VEL] + 6
            for k in range(n):
                qk = y[q0 + k]
                qdk = y[v0 + k]
                for a in range(3):
                    ft = shp[so + a * n + k]
                    fr = shp[so + (3 + a) * n + k]
                    u[a] += ft * qk
                    ud[a] += ft * qdk
                    th[a] += fr * qk
                    thd[a] += fr * qdk
        A = Ab[b]
        w = omfb[b]
        cross(w, u, t)
        for a in range(3):
            t[a] += ud[a]
        for a in range(3):
            mku[m, a] = u[a]
            mkp[m, a] = rb[b, a] + A[a, 0] * u[0] + A[a, 1] * u[1] + A[a, 2] * u[2]
            mkv[m, a] = vb[b, a] + A[a, 0] * t[0] + A[a, 1] * t[1] + A[a, 2] * t[2]
            mkw[m, a] = (A[a, 0] * (w[0] + thd[0]) + A[a, 1] * (w[1] + thd[1])
                         + A[a, 2] * (w[2] + thd[2]))
        # R = A (I + th~) R0
        for a in range(3):
            B0 = A[a, 0] + A[a, 1] * th[2] - A[a, 2] * th[1]
            B1 = A[a, 1] - A[a, 0] * th[2] + A[a, 2] * th[0]
            B2 = A[a, 2] + A[a, 0] * th[1] - A[a, 1] * th[0]
            for c in range(3):
                mkR[m, a, c] = B0 * mk_f[m, 3 + c] + B1 * mk_f[m, 6 + c] + B2 * mk_f[m, 9 + c]


@njit(cache=True)
def marker_loads(bi, mk_i, shp, Ab, mku, mkF, mkM, gen, goff):
    """Add every marker's force and moment to its body's generalised load ``gen[goff[b]:]``."""
    Fb = np.empty(3)
    Mb = np.empty(3)
    t = np.empty(3)
    for m in range(mk_i.shape[0]):
        b = mk_i[m, MK_BODY]
        if b < 0:
            continue
        F0, F1, F2 = mkF[m, 0], mkF[m, 1], mkF[m, 2]
        M0, M1, M2 = mkM[m, 0], mkM[m, 1], mkM[m, 2]
        if F0 == 0.0 and F1 == 0.0 and F2 == 0.0 and M0 == 0.0 and M1 == 0.0 and M2 == 0.0:
            continue
        A = Ab[b]
        for a in range(3):
            Fb[a] = A[0, a] * F0 + A[1, a] * F1 + A[2, a] * F2
            Mb[a] = A[0, a] * M0 + A[1, a] * M1 + A[2, a] * M2
        g = goff[b]
        gen[g] += F0
        gen[g + 1] += F1
        gen[g + 2] += F2
        cross(mku[m], Fb, t)
        for a in range(3):
            gen[g + 3 + a] += t[a] + Mb[a]
        so = mk_i[m, MK_SHP]
        if so >= 0:
            n = bi[b, BI_N]
            for k in range(n):
                s = 0.0
                for a in range(3):
                    s += shp[so + a * n + k] * Fb[a] + shp[so + (3 + a) * n + k] * Mb[a]
                gen[g + 6 + k] += s


@njit(cache=True)
def marker_acceleration(m, y, dy, bi, mk_i, mk_f, shp, Ab, omfb, mku, out):
    """Inertial acceleration of marker ``m`` from the state and its rate ``dy``:
    ``r'' + A (w' x u + w x (w x u) + 2 w x Phi_t qd + Phi_t qdd)`` (frame rates ``w_f``)."""
    b = mk_i[m, MK_BODY]
    if b < 0:
        out[:] = 0.0
        return
    iv = bi[b, BI_VEL]
    w0, w1, w2 = omfb[b, 0], omfb[b, 1], omfb[b, 2]
    d0, d1, d2 = dy[iv + 3], dy[iv + 4], dy[iv + 5]
    if bi[b, BI_SPIN] == 1:
        d1 = 0.0
    u0, u1, u2 = mku[m, 0], mku[m, 1], mku[m, 2]
    # scalars, not small arrays: eleven sensors' allocations cost more than their algebra
    ud0 = ud1 = ud2 = udd0 = udd1 = udd2 = 0.0
    so = mk_i[m, MK_SHP]
    if so >= 0:
        n = bi[b, BI_N]
        for k in range(n):
            qd, qdd = y[iv + 6 + k], dy[iv + 6 + k]
            f0, f1, f2 = shp[so + k], shp[so + n + k], shp[so + 2 * n + k]
            ud0 += f0 * qd
            ud1 += f1 * qd
            ud2 += f2 * qd
            udd0 += f0 * qdd
            udd1 += f1 * qdd
            udd2 += f2 * qdd
    t0, t1, t2 = w1 * u2 - w2 * u1, w2 * u0 - w0 * u2, w0 * u1 - w1 * u0            # w x u
    l0 = d1 * u2 - d2 * u1 + (w1 * t2 - w2 * t1) + udd0 + 2.0 * (w1 * ud2 - w2 * ud1)
    l1 = d2 * u0 - d0 * u2 + (w2 * t0 - w0 * t2) + udd1 + 2.0 * (w2 * ud0 - w0 * ud2)
    l2 = d0 * u1 - d1 * u0 + (w0 * t1 - w1 * t0) + udd2 + 2.0 * (w0 * ud1 - w1 * ud0)
    A = Ab[b]
    for a in range(3):
        out[a] = dy[iv + a] + A[a, 0] * l0 + A[a, 1] * l1 + A[a, 2] * l2
