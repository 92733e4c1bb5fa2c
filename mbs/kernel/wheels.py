"""Numba: the wheel-rail force elements of all wheels, on the markers at the wheel treads.

Wheel ``w`` (``wh_i = [marker, side, body, track]``, ``wh_f = [r_c, ds_w]``) acts at a marker on
the tread point of the nominal taping line (bottom of the wheel in the non-spinning frame).  The
wheel centre is ``c = p + r_c R e_z`` (the marker frame's z axis), the axle direction ``e = R
e_y``; the material angular velocity adds the body's spin to the frame rate.  The rails'
irregularities at ``s = c_x`` come from the track table ``trk (8, ns)``: ``zL, zR, yL, yR`` and
their slopes, cubic Hermite on a uniform periodic grid (C1, like
:meth:`axlebox.mbs.track.irregularity.TrackIrregularity.at`), faded in over the first
``glob[G_RAMP]`` seconds (half-cosine) so that a run can start from the equilibrium on smooth
track without a jump.  A wheel's own roughness (``wrk[w] = values, slopes`` on the grid ``j
ds_w`` around its rolling circle, :func:`axlebox.mbs.track.roughness.wheel_record`) adds to its
rails' height, read at the arc ``beta r_c`` its spin angle beta has turned (on a body that does
not spin, at the distance rolled, ``c_x``), and fades in with the track; its rate is taken as
slope times the rolling speed, as the rails' (creep: 1e-3 of it).
On a ballasted track (``track >= 0``, :mod:`axlebox.mbs.track.bed`) the rail body's height and
vertical velocity add to the rail's, and the contact's vertical force acts on it (the track is
rigid laterally and along the rail).
The creepages' reference speed is the car's speed profile's at ``t`` (:mod:`axlebox.mbs.kernel.speed`).
The contact itself is :func:`axlebox.mbs.wheelrail.element_kernel.wheel_rail_force`; after its
outputs (``N_OUT`` of them) a wheel's row of ``whout`` has two of the car's: the wheel centre's
lateral place in the track frame at its contact (``WO_YC``, m; off a line the tangent track's y)
and the axle's yaw against that frame (``WO_YAW``, rad, about the frame's z: the angle of attack
with its sign), which the result file turns into each wheelset's lateral displacement and angle of
attack.  On a line the contact point's x (``OUT_P``) is its chainage from where the car's
reference started (the line's ``L_START``), as off a line it is the distance along the track.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from axlebox.mbs.wheelrail.element_kernel import N_OUT, OUT_P, wheel_rail_force

from .body import BI_POS, BI_SPIN, cross
from .speed import G_LINE, G_PROF, G_V, profile_at  # noqa: F401  (glob's slots, here with the rest)
from .trajectory import FR_A, FR_O, FR_S, FR_WID, L_START, frame_pose, to_frame, to_inertial

# glob slots (G_V, the constant speed, G_LINE, 1 on a line, and G_PROF, the speed profile's
# count with its points after it, are speed.py's)
G_GRAV, G_S0, G_DS, G_TRACK, G_RAMP = 0, 4, 5, 6, 7
N_GLOB = G_PROF + 1
WH_MARKER, WH_SIDE, WH_BODY, WH_TRACK = 0, 1, 2, 3   # WH_TRACK: the rail body's marker, -1 none
WF_RC, WF_DS = 0, 1                    # wh_f columns: r_c; the wheel record's grid step (0: none)
WO_YC, WO_YAW, N_WHOUT = N_OUT, N_OUT + 1, N_OUT + 2     # whout's columns after the contact's


@njit(cache=True)
def _fade(glob, t):
    """The irregularities' half-cosine fade-in over the first ``glob[G_RAMP]`` s."""
    if t < glob[G_RAMP]:
        return 0.5 - 0.5 * math.cos(math.pi * t / glob[G_RAMP])
    return 1.0


@njit(cache=True)
def hermite_at(v, d, s, ds):
    """Value and slope at ``s`` of the periodic record ``v`` (slopes ``d``) on the grid
    ``j ds``: cubic Hermite on the exact slopes."""
    ns = v.size
    x = s / ds
    x = x - math.floor(x / ns) * ns
    i = int(x)
    if i >= ns:
        i = ns - 1
    u = x - i
    j = i + 1 if i + 1 < ns else 0
    f0, f1 = v[i], v[j]
    d0, d1 = d[i] * ds, d[j] * ds
    u2 = u * u
    u3 = u2 * u
    val = (2 * u3 - 3 * u2 + 1) * f0 + (u3 - 2 * u2 + u) * d0 + (-2 * u3 + 3 * u2) * f1 + (u3 - u2) * d1
    der = ((6 * u2 - 6 * u) * f0 + (3 * u2 - 4 * u + 1) * d0 + (-6 * u2 + 6 * u) * f1
           + (3 * u2 - 2 * u) * d1) / ds
    return val, der


@njit(cache=True)
def track_at(trk, row, s, glob, t):
    """Value and slope of track row ``row`` (0..3) at ``s`` (periodic record) at time ``t``."""
    if glob[G_TRACK] == 0.0 or t <= 0.0:
        return 0.0, 0.0
    fade = _fade(glob, t)
    val, der = hermite_at(trk[row], trk[4 + row], s - glob[G_S0], glob[G_DS])
    return fade * val, fade * der


@njit(cache=True)
def _on_rails(line, s_b, c, e, vc, om, mkp, mkv, mt, fr, loc):
    """A wheel on a line: the track frame at its contact's chainage into ``fr`` (the frame at its
    body's chainage ``s_b`` moved on by the centre's lead along it, then taken there again), and
    in that frame's axes the wheel centre ``loc[0]``, axle ``loc[1]``, centre velocity ``loc[2]``
    and angular velocity ``loc[3]``, the rail body's (``mt``) height and vertical rate
    ``loc[4, :2]``.  The rails are at rest, so the contact is the tangent track's there (cant and
    curvature enter through the frame's axes and the wheelset's own motion: the creepages'
    curvature terms, ``b / R`` in ``xi`` and the yaw rate in the spin).  Returns the chainage
    from the run's start."""
    frame_pose(line, s_b, fr)
    for _ in range(2):
        lead = 0.0
        for a in range(3):
            lead += fr[FR_A + 3 * a] * (c[a] - fr[FR_O + a])
        frame_pose(line, fr[FR_S] + lead, fr)
    for a in range(3):
        loc[4, a] = c[a] - fr[FR_O + a]
    to_frame(fr, loc[4], loc[0])
    to_frame(fr, e, loc[1])
    to_frame(fr, vc, loc[2])
    to_frame(fr, om, loc[3])
    loc[4, 0] = 0.0
    loc[4, 1] = 0.0
    if mt >= 0:
        for a in range(3):
            loc[4, 0] += fr[FR_A + 3 * a + 2] * (mkp[mt, a] - fr[FR_O + a])
            loc[4, 1] += fr[FR_A + 3 * a + 2] * mkv[mt, a]
    return fr[FR_S] - line[L_START]


@njit(cache=True)
def wheel_forces(t, y, bi, wh_i, wh_f, wtab, wpar, trk, wrk, glob, Ab, omb, omfb, mkp, mkv, mkR,
                 mkw, mkF, mkM, whout, line, frm, fr):
    """Every wheel's contact force and moment at ``t`` on its marker (and on its rail body's),
    its outputs in ``whout`` (module docstring).  The arrays one by one, not the system's ``S``
    and ``W`` whole: those cost 457-489 instructions a right-hand side more, 0.1-0.3 %
    (benchmarks/README.md, "Grouped arguments").  On a line (``glob[G_LINE]``) each wheel meets
    its rails in the track frame at its contact's chainage (:func:`_on_rails`), ``frm`` the
    bodies' frames and ``fr`` scratch."""
    V = profile_at(glob, t)[1]        # the creepages' reference speed: the profile's at t
    on = glob[G_LINE] != 0.0
    c = np.empty(3)
    e = np.empty(3)
    vc = np.empty(3)
    om = np.empty(3)
    d = np.empty(3)
    tmp = np.empty(3)
    loc = np.empty((5, 3))
    for w in range(wh_i.shape[0]):
        m, side, b = wh_i[w, WH_MARKER], wh_i[w, WH_SIDE], wh_i[w, WH_BODY]
        R = mkR[m]
        rc = wh_f[w, WF_RC]
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
            # the spin against the body's frame (off a line that frame does not turn about y)
            A = Ab[b]
            for a in range(3):
                om[a] += A[a, 1] * (omb[b, 1] - omfb[b, 1])
        mt = wh_i[w, WH_TRACK]
        ch = c[0]                                 # the chainage from the run's start
        sy = 0.0
        if on:
            ch = _on_rails(line, frm[b, FR_S], c, e, vc, om, mkp, mkv, mt, fr, loc)
            sy = (0.5 if side == 0 else -0.5) * fr[FR_WID]
        z_r, dz = track_at(trk, side, ch, glob, t)
        y_r, dyr = track_at(trk, 2 + side, ch, glob, t)
        y_r += sy                                 # the gauge widening moves each rail out
        if wh_f[w, WF_DS] > 0.0 and t > 0.0:      # the wheel's own roughness, turning with it
            fade = _fade(glob, t)
            s_w = y[bi[b, BI_POS] + 7] * rc if bi[b, BI_SPIN] == 1 else ch
            r, dr = hermite_at(wrk[w, 0], wrk[w, 1], s_w, wh_f[w, WF_DS])
            z_r += fade * r
            dz += fade * dr
        zt = 0.0
        vt = 0.0
        if mt >= 0:                               # the rail body under the wheel (track/bed.py)
            zt = loc[4, 0] if on else mkp[mt, 2]
            vt = loc[4, 1] if on else mkv[mt, 2]
        out = whout[w]
        cw, ew, vw, ow = (loc[0], loc[1], loc[2], loc[3]) if on else (c, e, vc, om)
        wheel_rail_force(side, cw, ew, vw, ow, V, z_r + zt, y_r, dz * vw[0] + vt, dyr * vw[0], wtab,
                         wpar, out)
        out[WO_YC] = cw[1]
        out[WO_YAW] = math.atan2(-ew[0], ew[1])
        if on:
            out[OUT_P] += ch                      # the contact's x: its chainage from the start
        # out[0:3] force on the wheel, out[3:6] moment about c (on a line in the track frame's
        # axes, as the outputs keep them): move to the marker
        for a in range(3):
            tmp[a] = out[a]
            om[a] = out[3 + a]
        if on:
            to_inertial(fr, tmp, tmp)
            to_inertial(fr, om, om)
        if mt >= 0:                               # its normal force on the rail
            if on:
                for a in range(3):
                    mkF[mt, a] -= out[2] * fr[FR_A + 3 * a + 2]
            else:
                mkF[mt, 2] -= out[2]
        cross(d, tmp, e)
        for a in range(3):
            mkF[m, a] += tmp[a]
            mkM[m, a] += om[a] + e[a]
