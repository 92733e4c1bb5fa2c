"""The system right-hand side ``y' = F(t, y)`` in numba, over the packed arrays of
:class:`axlebox.mbs.system.Model`.

``S`` (static arrays): ``bi, bf, inv, goff, mk_i, mk_f, shp, el_i, el_f, glob, wh_i, wh_f, wtab,
wpar, trk, sens``; ``W`` (work arrays, overwritten every call): frame quantities per body,
marker kinematics and loads, the generalised loads, element, wheel and sensor outputs.
Order of one evaluation: frames and position rates; marker kinematics; element and wheel-rail
forces on markers; gravity and marker loads per body; body accelerations; sensor accelerations.
The bearings (:mod:`.kernel_bearings`) and the bodies' accelerations (:func:`_accelerations`)
run on numba's threads, each writing only its own rows, so any number of threads gives the same
numbers; the rest runs on one.
"""
from __future__ import annotations

import numpy as np
from numba import njit, prange

from .kernel_bearings import bearing_forces
from .kernel_body import BI_N, BI_VEL, body_accelerations, frame_kinematics, gravity_load, position_rates
from .kernel_elements import element_forces
from .kernel_markers import marker_acceleration, marker_kinematics, marker_loads
from .kernel_wheels import G_GRAV, wheel_forces


@njit(cache=True)
def rhs(t, y, dy, S, W):
    bi, bf, inv, goff, mk_i, mk_f, shp, el_i, el_f, glob, wh_i, wh_f, wtab, wpar, trk, sens, \
        br_i, br_P, br_D = S
    Ab, rb, vb, omb, omfb, mku, mkp, mkv, mkR, mkw, mkF, mkM, gen, elout, whout, sensout, brG = W
    nb = bi.shape[0]
    for b in range(nb):
        frame_kinematics(b, y, bi, Ab[b], rb[b], vb[b], omb[b], omfb[b])
        position_rates(b, y, bi, omfb[b], dy)
    marker_kinematics(y, bi, mk_i, mk_f, shp, Ab, rb, vb, omfb, mku, mkp, mkv, mkR, mkw)
    mkF[:, :] = 0.0
    mkM[:, :] = 0.0
    element_forces(t, el_i, el_f, mkp, mkv, mkR, mkw, mkF, mkM, elout)
    bearing_forces(t, y, dy, bi, br_i, br_P, br_D, mkp, mkv, mkR, mkw, mkF, mkM, elout, brG)
    if wh_i.shape[0] > 0:
        wheel_forces(t, bi, wh_i, wh_f, wtab, wpar, trk, glob, Ab, omb, mkp, mkv, mkR, mkw,
                     mkF, mkM, whout)
    g = glob[G_GRAV:G_GRAV + 3]
    for b in range(nb):
        n = bi[b, BI_N]
        o = goff[b]
        gravity_load(b, bi, bf, inv, y, Ab[b], g, gen[o:o + 6 + n])
    marker_loads(bi, mk_i, shp, Ab, mku, mkF, mkM, gen, goff)
    _accelerations(y, dy, bi, bf, inv, goff, Ab, omb, omfb, gen)
    for s in range(sens.shape[0]):
        marker_acceleration(sens[s], y, dy, bi, mk_i, mk_f, shp, Ab, omfb, mku, sensout[s])


@njit(cache=True)
def lanes(bi, n_lanes):
    """Bodies dealt to ``n_lanes`` lanes of about equal work, largest first (a body's solve
    costs about ``(6 + n)^2``): ``lane[b]``."""
    nb = bi.shape[0]
    cost = np.empty(nb)
    for b in range(nb):
        cost[b] = (6.0 + bi[b, BI_N]) ** 2
    load = np.zeros(n_lanes)
    lane = np.empty(nb, np.int64)
    for b in np.argsort(-cost, kind="mergesort"):
        L = np.argmin(load)
        lane[b] = L
        load[L] += cost[b]
    return lane


@njit(cache=True, parallel=True)
def _accelerations(y, dy, bi, bf, inv, goff, Ab, omb, omfb, gen):
    """Every body's accelerations, in four lanes of equal work over numba's threads (even for 1,
    2 or 4 threads; each body writes only its own rows, so the result does not depend on the
    number of threads).  (``numba.get_num_threads`` here would keep numba from caching.)"""
    n_lanes = min(4, bi.shape[0])
    lane = lanes(bi, n_lanes)
    for L in prange(n_lanes):
        for b in range(bi.shape[0]):
            if lane[b] == L:
                n = bi[b, BI_N]
                o = goff[b]
                iv = bi[b, BI_VEL]
                body_accelerations(b, y, bi, bf, inv, Ab[b], omb[b], omfb[b], gen[o:o + 6 + n],
                                   dy[iv:iv + 6 + n])
