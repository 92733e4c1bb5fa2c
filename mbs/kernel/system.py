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
from .body import (BF_X, BI_N, BI_POS, BI_SPIN, BI_VEL, SPIN_ANGLE, body_accelerations,
                   frame_kinematics, gravity_load, position_rates)
from .elements import element_forces
from .markers import MK_BODY, marker_acceleration, marker_kinematics, marker_loads
from .speed import G_LINE, profile_at
from .trajectory import (FR_DR, FR_O, FR_WB, FR_WR, L_START, body_on_line, frame_motion, ground_on_line,
                         to_frame, to_inertial, velocity_rates)
from .wheels import G_GRAV, wheel_forces


Arrays = namedtuple("Arrays", ["bi", "bf", "inv", "goff", "mk_i", "mk_f", "shp", "el_i", "el_f", "glob",
                               "wh_i", "wh_f", "wtab", "wpar", "trk", "wrk", "sens", "line", "brm", "lane"])
Work = namedtuple("Work", ["Ab", "rb", "vb", "omb", "omfb", "mku", "mkp", "mkv", "mkR", "mkw", "mkF",
                           "mkM", "gen", "elout", "whout", "sensout", "frm", "fr", "brs"])


@njit(cache=True)
def rhs(t, y, dy, S, W, B):
    """``dy = F(t, y)``, the bearings' rates included (:func:`.bearings.bearing_forces`)."""
    kinematics(t, y, dy, S, W)
    _rings_to_frames(S, W)
    bearing_forces(B, t, y, dy, S.bi, W.mkp, W.mkv, W.mkR, W.mkw, W.mkF, W.mkM, W.elout)
    _ring_loads_to_inertial(S, W)
    dynamics(t, y, dy, S, W)


@njit(cache=True, inline="always")
def rhs_exchange(t, y, dy, S, W, B, X):
    """The bodies' ``dy`` at ``t`` with the bearings exchanged (:func:`.bearings.bearing_exchange`:
    their states advanced to ``t``, their mean ring loads on the markers); the bearings' rows
    of ``dy`` are left as they were."""
    kinematics(t, y, dy, S, W)
    _rings_to_frames(S, W)
    bearing_exchange(B, X, t, y, S.bi, W.mkp, W.mkv, W.mkR, W.mkw, W.mkF, W.mkM, W.elout)
    _ring_loads_to_inertial(S, W)
    dynamics(t, y, dy, S, W)


@njit(cache=True, inline="always")
def rhs_held(t, y, dy, S, W, B, X, u):
    """The bodies' ``dy`` at ``t`` between exchanges of a co-simulation: the bearings' loads
    those of the last exchange, carried ``u`` exchange steps on (:func:`.bearings.held_loads`)."""
    kinematics(t, y, dy, S, W)
    _rings_to_frames(S, W)
    held_loads(B, X, y, S.bi, W.mkp, W.mkv, W.mkR, W.mkw, W.mkF, W.mkM, u)
    _ring_loads_to_inertial(S, W)
    dynamics(t, y, dy, S, W)


@njit(cache=True)
def _rings_to_frames(S, W):
    """On a line: each bearing's two ring markers resolved in its wheelset's track frame, in
    place, for the bearing models, which work in the track's axes (small ring angles); their
    angular velocities stay inertial, so the rollers and cages feel the frame's rotation.  The
    markers' loads so far are kept in ``W.brs``."""
    if S.glob[G_LINE] == 0.0:
        return
    for k in range(S.brm.shape[0]):
        F = W.frm[S.brm[k, 2]]
        for j in range(2):
            m = S.brm[k, j]
            for a in range(3):
                W.brs[k, j, a] = W.mkF[m, a]
                W.brs[k, j, 3 + a] = W.mkM[m, a]
                W.mkp[m, a] -= F[FR_O + a]
            to_frame(F, W.mkp[m], W.mkp[m])
            to_frame(F, W.mkv[m], W.mkv[m])
            to_frame(F, W.mkw[m], W.mkw[m])
            for c in range(3):
                to_frame(F, W.mkR[m, :, c], W.mkR[m, :, c])


@njit(cache=True)
def _ring_loads_to_inertial(S, W):
    """On a line: what the bearings added to their markers' loads, from the track frame's axes
    back to the inertial (:func:`_rings_to_frames`)."""
    if S.glob[G_LINE] == 0.0:
        return
    for k in range(S.brm.shape[0]):
        F = W.frm[S.brm[k, 2]]
        for j in range(2):
            m = S.brm[k, j]
            for a in range(3):
                W.mkF[m, a] -= W.brs[k, j, a]
                W.mkM[m, a] -= W.brs[k, j, 3 + a]
            to_inertial(F, W.mkF[m], W.mkF[m])
            to_inertial(F, W.mkM[m], W.mkM[m])
            for a in range(3):
                W.mkF[m, a] += W.brs[k, j, a]
                W.mkM[m, a] += W.brs[k, j, 3 + a]


@njit(cache=True)
def frames(t, y, dy, S, W):
    """Every body's frame kinematics (inertial) and position rates.  On a line the bodies'
    states are on their track frames (:mod:`.trajectory`): their rates come from those, the
    kinematics handed on are inertial."""
    bi = S.bi
    if S.glob[G_LINE] == 0.0:
        for b in range(bi.shape[0]):
            frame_kinematics(b, y, bi, W.Ab[b], W.rb[b], W.vb[b], W.omb[b], W.omfb[b])
            position_rates(b, y, bi, W.omfb[b], dy)
        return
    x, v, _ = profile_at(S.glob, t)
    for b in range(bi.shape[0]):
        frame_kinematics(b, y, bi, W.Ab[b], W.rb[b], W.vb[b], W.omb[b], W.omfb[b])
        F = W.frm[b]
        frame_motion(S.line, S.line[L_START] + x + S.bf[b, BF_X], v, F)
        spin = bi[b, BI_SPIN] == 1
        body_on_line(F, spin, W.Ab[b], W.rb[b], W.vb[b], W.omb[b], W.omfb[b])
        position_rates(b, y, bi, F[FR_WR:FR_WR + 3], dy)
        ip = bi[b, BI_POS]
        for a in range(3):
            dy[ip + a] = F[FR_DR + a]
        if spin:                   # the spin against the non-spinning frame, which turns too
            dy[ip + SPIN_ANGLE] -= F[FR_WB + 1]


@njit(cache=True)
def kinematics(t, y, dy, S, W):
    """Frames, position rates and marker kinematics; the element forces on the markers."""
    bi = S.bi
    frames(t, y, dy, S, W)
    marker_kinematics(y, bi, S.mk_i, S.mk_f, S.shp, W.Ab, W.rb, W.vb, W.omfb, W.mku, W.mkp, W.mkv,
                      W.mkR, W.mkw)
    if S.glob[G_LINE] != 0.0:
        x, v, _ = profile_at(S.glob, t)
        ground_on_line(S.line, x, v, S.mk_i, S.mk_f, W.fr, W.mkp, W.mkv, W.mkR, W.mkw)
    W.mkF[:, :] = 0.0
    W.mkM[:, :] = 0.0
    element_forces(t, S.el_i, S.el_f, S.glob, W.mkp, W.mkv, W.mkR, W.mkw, W.mkF, W.mkM, W.elout)


@njit(cache=True)
def dynamics(t, y, dy, S, W):
    """Wheel-rail forces, gravity and the marker loads per body; the bodies' and the sensors'
    accelerations."""
    bi, goff, Ab = S.bi, S.goff, W.Ab
    if S.wh_i.shape[0] > 0:
        wheel_forces(t, y, bi, S.wh_i, S.wh_f, S.wtab, S.wpar, S.trk, S.wrk, S.glob, Ab, W.omb,
                     W.omfb, W.mkp, W.mkv, W.mkR, W.mkw, W.mkF, W.mkM, W.whout, S.line, W.frm, W.fr)
    g = S.glob[G_GRAV:G_GRAV + 3]
    for b in range(bi.shape[0]):
        n = bi[b, BI_N]
        o = goff[b]
        gravity_load(b, bi, S.bf, S.inv, y, Ab[b], g, W.gen[o:o + 6 + n])
    marker_loads(bi, S.mk_i, S.shp, Ab, W.mku, W.mkF, W.mkM, W.gen, goff)
    _accelerations(y, dy, bi, S.bf, S.inv, goff, S.lane, Ab, W.omb, W.omfb, W.gen)
    for s in range(S.sens.shape[0]):
        marker_acceleration(S.sens[s], y, dy, bi, S.mk_i, S.mk_f, S.shp, Ab, W.omfb, W.mku,
                            W.sensout[s])
    if S.glob[G_LINE] != 0.0:
        _on_line(y, dy, S, W)


@njit(cache=True)
def _on_line(y, dy, S, W):
    """On a line: the sensors' accelerations in their body's track axes (forward, lateral in the
    canted plane, normal: what an accelerometer on the axle box reads, less gravity, in a curve
    whose heading turns), and the bodies' inertial accelerations turned into their velocity
    states' rates (:func:`.trajectory.velocity_rates`)."""
    bi = S.bi
    for s in range(S.sens.shape[0]):
        b = S.mk_i[S.sens[s], MK_BODY]
        if b >= 0:
            to_frame(W.frm[b], W.sensout[s], W.sensout[s])
    for b in range(bi.shape[0]):
        iv = bi[b, BI_VEL]
        velocity_rates(W.frm[b], y, iv, dy[iv:iv + 3])


def lanes(bi) -> np.ndarray:
    """Bodies dealt to ``min(4, bodies)`` lanes of about equal work, largest first (a body's solve
    costs about ``(6 + n)^2``): ``lane[b]``.  Made once, when the model is assembled
    (:data:`Arrays`' ``lane``)."""
    nb = bi.shape[0]
    cost = (6.0 + bi[:, BI_N]) ** 2
    load = np.zeros(min(4, nb))
    lane = np.empty(nb, np.int64)
    for b in np.argsort(-cost, kind="mergesort"):
        L = int(np.argmin(load))
        lane[b] = L
        load[L] += cost[b]
    return lane


@njit(cache=True, parallel=True)
def _accelerations(y, dy, bi, bf, inv, goff, lane, Ab, omb, omfb, gen):
    """Every body's accelerations, in the four lanes of equal work ``lane`` (:func:`lanes`) over
    numba's threads (even for 1, 2 or 4 threads; each body writes only its own rows, so the
    result does not depend on the number of threads).  (``numba.get_num_threads`` here would
    keep numba from caching.)"""
    n_lanes = min(4, bi.shape[0])
    for L in prange(n_lanes):
        for b in range(bi.shape[0]):
            if lane[b] == L:
                n = bi[b, BI_N]
                o = goff[b]
                iv = bi[b, BI_VEL]
                body_accelerations(b, y, bi, bf, inv, Ab[b], omb[b], omfb[b], gen[o:o + 6 + n],
                                   dy[iv:iv + 6 + n])
