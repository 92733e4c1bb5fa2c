"""The system right-hand side ``y' = F(t, y)`` in numba, over the packed arrays of
:class:`axlebox.mbs.solver.system.Model`.

``S`` (:class:`Arrays`, static): the bodies, markers, elements, wheels, track and sensors
packed; ``B`` the bearings (:class:`.bearings.Bearings`, or ``NoBearings``: the
kernels that take it are compiled for its model alone); ``W`` (:class:`Work`, overwritten
every call): frame quantities per body,
marker kinematics and loads, the generalised loads, element, wheel and sensor outputs (numba
compiles these named tuples: fields by name, no positions to keep in step).
Order of one evaluation: frames and position rates; marker kinematics; element and wheel-rail
forces on markers; gravity and marker loads per body; body accelerations; sensor accelerations.
The bearings (:mod:`axlebox.mbs.kernel.bearings`) and the bodies' accelerations (:func:`_accelerations`)
run on numba's threads, each writing only its own rows, so any number of threads gives the same
numbers; the rest runs on one.
"""
from __future__ import annotations

from collections import namedtuple

import numpy as np
from numba import njit, prange

from .bearings import bearing_exchange, bearing_forces, held_loads
from .body import BI_N, BI_VEL, body_accelerations, frame_kinematics, gravity_load, position_rates
from .elements import element_forces
from .markers import marker_acceleration, marker_kinematics, marker_loads
from .wheels import G_GRAV, wheel_forces


Arrays = namedtuple("Arrays", ["bi", "bf", "inv", "goff", "mk_i", "mk_f", "shp", "el_i", "el_f", "glob",
                               "wh_i", "wh_f", "wtab", "wpar", "trk", "wrk", "sens"])
Work = namedtuple("Work", ["Ab", "rb", "vb", "omb", "omfb", "mku", "mkp", "mkv", "mkR", "mkw", "mkF",
                           "mkM", "gen", "elout", "whout", "sensout"])


@njit(cache=True)
def rhs(t, y, dy, S, W, B):
    """``dy = F(t, y)``, the bearings' rates included (:func:`.bearings.bearing_forces`)."""
    kinematics(t, y, dy, S, W)
    bearing_forces(B, t, y, dy, S.bi, W.mkp, W.mkv, W.mkR, W.mkw, W.mkF, W.mkM, W.elout)
    _dynamics(t, y, dy, S, W)


@njit(cache=True)
def rhs_exchange(t, y, dy, S, W, B, X):
    """The bodies' ``dy`` at ``t`` with the bearings exchanged (:func:`.bearings.bearing_exchange`:
    their states advanced to ``t``, their mean ring loads on the markers); the bearings' rows
    of ``dy`` are left as they were."""
    kinematics(t, y, dy, S, W)
    bearing_exchange(B, X, t, y, S.bi, W.mkp, W.mkv, W.mkR, W.mkw, W.mkF, W.mkM, W.elout)
    _dynamics(t, y, dy, S, W)


@njit(cache=True)
def rhs_held(t, y, dy, S, W, B, X, u):
    """The bodies' ``dy`` at ``t`` between exchanges of a co-simulation: the bearings' loads
    those of the last exchange, carried ``u`` exchange steps on (:func:`.bearings.held_loads`)."""
    kinematics(t, y, dy, S, W)
    held_loads(B, X, y, S.bi, W.mkp, W.mkv, W.mkR, W.mkw, W.mkF, W.mkM, u)
    _dynamics(t, y, dy, S, W)


@njit(cache=True)
def kinematics(t, y, dy, S, W):
    """Frames, position rates and marker kinematics; the element forces on the markers."""
    bi = S.bi
    for b in range(bi.shape[0]):
        frame_kinematics(b, y, bi, W.Ab[b], W.rb[b], W.vb[b], W.omb[b], W.omfb[b])
        position_rates(b, y, bi, W.omfb[b], dy)
    marker_kinematics(y, bi, S.mk_i, S.mk_f, S.shp, W.Ab, W.rb, W.vb, W.omfb, W.mku, W.mkp, W.mkv,
                      W.mkR, W.mkw)
    W.mkF[:, :] = 0.0
    W.mkM[:, :] = 0.0
    element_forces(t, S.el_i, S.el_f, S.glob, W.mkp, W.mkv, W.mkR, W.mkw, W.mkF, W.mkM, W.elout)


@njit(cache=True)
def _dynamics(t, y, dy, S, W):
    """Wheel-rail forces, gravity and the marker loads per body; the bodies' and the sensors'
    accelerations."""
    bi, goff, Ab = S.bi, S.goff, W.Ab
    if S.wh_i.shape[0] > 0:
        wheel_forces(t, y, bi, S.wh_i, S.wh_f, S.wtab, S.wpar, S.trk, S.wrk, S.glob, Ab, W.omb, W.mkp,
                     W.mkv, W.mkR, W.mkw, W.mkF, W.mkM, W.whout)
    g = S.glob[G_GRAV:G_GRAV + 3]
    for b in range(bi.shape[0]):
        n = bi[b, BI_N]
        o = goff[b]
        gravity_load(b, bi, S.bf, S.inv, y, Ab[b], g, W.gen[o:o + 6 + n])
    marker_loads(bi, S.mk_i, S.shp, Ab, W.mku, W.mkF, W.mkM, W.gen, goff)
    _accelerations(y, dy, bi, S.bf, S.inv, goff, Ab, W.omb, W.omfb, W.gen)
    for s in range(S.sens.shape[0]):
        marker_acceleration(S.sens[s], y, dy, bi, S.mk_i, S.mk_f, S.shp, Ab, W.omfb, W.mku,
                            W.sensout[s])


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
