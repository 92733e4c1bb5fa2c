"""Numba: the wheel-rail force elements of all wheels, on the markers at the wheel treads.

Wheel ``w`` (``wh_i = [marker, side, body]``, ``wh_f = [r_c]``) acts at a marker on the tread
point of the nominal taping line (bottom of the wheel in the non-spinning frame).  The wheel
centre is ``c = p + r_c R e_z`` (the marker frame's z axis), the axle direction ``e = R e_y``;
the material angular velocity adds the body's spin to the frame rate.  The rails' irregularities
at ``s = c_x`` come from the track table ``trk (8, ns)``: ``zL, zR, yL, yR`` and their slopes,
cubic Hermite on a uniform periodic grid (C1, like :meth:`axlebox.mbs.track.TrackIrregularity.at`),
faded in over the first ``glob[G_RAMP]`` seconds (half-cosine) so that a run can start from the
equilibrium on smooth track without a jump.
The contact itself is :func:`axlebox.mbs.wheelrail.element_kernel.wheel_rail_force`.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from axlebox.mbs.wheelrail.element_kernel import wheel_rail_force

from .kernel_body import BI_SPIN, cross

G_GRAV, G_V, G_S0, G_DS, G_TRACK, G_RAMP = 0, 3, 4, 5, 6, 7   # glob slots
N_GLOB = 8
WH_MARKER, WH_SIDE, WH_BODY = 0, 1, 2


@njit(cache=True)
def track_at(trk, row, s, glob, t):
    """Value and slope of track row ``row`` (0..3) at ``s`` (periodic record) at time ``t``."""
    if glob[G_TRACK] == 0.0 or t <= 0.0:
        return 0.0, 0.0
    fade = 1.0
    if t < glob[G_RAMP]:
        fade = 0.5 - 0.5 * math.cos(math.pi * t / glob[G_RAMP])
    ns = trk.shape[1]
    ds = glob[G_DS]
    x = (s - glob[G_S0]) / ds
    x = x - math.floor(x / ns) * ns
    i = int(x)
    if i >= ns:
        i = ns - 1
    u = x - i
    j = i + 1 if i + 1 < ns else 0
    f0, f1 = trk[row, i], trk[row, j]
    d0, d1 = trk[4 + row, i] * ds, trk[4 + row, j] * ds
    u2 = u * u
    u3 = u2 * u
    val = (2 * u3 - 3 * u2 + 1) * f0 + (u3 - 2 * u2 + u) * d0 + (-2 * u3 + 3 * u2) * f1 + (u3 - u2) * d1
    der = ((6 * u2 - 6 * u) * f0 + (3 * u2 - 4 * u + 1) * d0 + (-6 * u2 + 6 * u) * f1
           + (3 * u2 - 2 * u) * d1) / ds
    return fade * val, fade * der


@njit(cache=True)
def wheel_forces(t, bi, wh_i, wh_f, wtab, wpar, trk, glob, Ab, omb, mkp, mkv, mkR, mkw, mkF, mkM,
                 whout):
    V = glob[G_V]
    c = np.empty(3)
    e = np.empty(3)
    vc = np.empty(3)
    om = np.empty(3)
    d = np.empty(3)
    tmp = np.empty(3)
    for w in range(wh_i.shape[0]):
        m, side, b = wh_i[w, WH_MARKER], wh_i[w, WH_SIDE], wh_i[w, WH_BODY]
        R = mkR[m]
        rc = wh_f[w, 0]
        ne = math.sqrt(R[0, 1] ** 2 + R[1, 1] ** 2 + R[2, 1] ** 2)
        for a in range(3):
            d[a] = rc * R[a, 2]
            c[a] = mkp[m, a] + d[a]
            e[a] = R[a, 1] / ne
            om[a] = mkw[m, a]
        cross(mkw[m], d, tmp)
        for a in range(3):
            vc[a] = mkv[m, a] + tmp[a]
        if bi[b, BI_SPIN] == 1:
            A = Ab[b]
            for a in range(3):
                om[a] += A[a, 1] * omb[b, 1]
        z_r, dz = track_at(trk, side, c[0], glob, t)
        y_r, dyr = track_at(trk, 2 + side, c[0], glob, t)
        out = whout[w]
        wheel_rail_force(side, c, e, vc, om, V, z_r, y_r, dz * vc[0], dyr * vc[0], wtab, wpar, out)
        # out[0:3] force on the wheel, out[3:6] moment about c: move to the marker
        for a in range(3):
            tmp[a] = out[a]
        cross(d, tmp, e)
        for a in range(3):
            mkF[m, a] += out[a]
            mkM[m, a] += out[3 + a] + e[a]
