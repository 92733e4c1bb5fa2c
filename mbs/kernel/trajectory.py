"""Numba: the track-following frames of a line (the trajectory coordinates), and the bodies'
states measured from them.

On a line (:class:`axlebox.mbs.track.line.Line`, packed by :meth:`~axlebox.mbs.track.line.Line.pack`
into ``line``) each body ``b`` is described from its own track frame, the frame of the line at
``s_b(t) = s_start + x(t) + X_b``: ``s_start`` where the car's reference point (the front bogie's
centre) starts, ``x(t)`` the distance the speed profile has run
(:mod:`axlebox.mbs.kernel.speed`), ``X_b`` the body's place along the car (``bf[b, BF_X]``).
The frame's axes ``A_F = Rz(psi) Rx(phi)`` (forward, left
in the canted plane, its normal), origin ``O`` on the centre line at rail level; it turns at
``omega_F = v (phi', kappa sin phi, kappa cos phi)`` in its own axes
(:func:`axlebox.mbs.track.line.frame_motion`, tested against finite differences).

A body's states there (Shabana, Zaazaa and Sugiyama, *Railroad Vehicle Dynamics: A Computational
Approach*, CRC 2008, ch. 4, the trajectory coordinate system): its position ``r`` and the
quaternion of its axes ``A_rel``, both relative to the frame; its inertial velocity resolved in
the frame's axes, ``u = A_F^T v_abs``; its inertial angular velocity in its own axes, as off a
line; the modal coordinates as they are.  So::

    r_abs = O + A_F r,   A = A_F A_rel,   v_abs = A_F u
    r' = u - v_0 - omega_F x r,   v_0 = (v, 0, 0)
    A_rel' = A_rel (omega_f - A_rel^T omega_F)~
    u' = A_F^T a_abs - omega_F x u

with ``omega_f`` the body frame's inertial rate (a spinning body's without its spin) and
``a_abs`` the inertial acceleration the equations of motion (:mod:`axlebox.mbs.kernel.body`) give from the
inertial kinematics, which the markers, force elements and bearings see as off a line.  The
moving frame's inertial terms are all there and exact: seen from the frame, ``-omega_F x u``
holds the centrifugal forces (steady in a curve, ``u = v_0 + omega_F x r`` and ``u' = 0``: the
inertial acceleration ``omega_F x u``, DYTSI's ``m v^2 cos(phi) / R`` and ``-m v^2 sin(phi) /
R``), the Coriolis and Euler terms follow from ``r'``; gravity acts in the inertial axes, so in
the canted plane; the wheelsets' gyroscopic moments take the frame's yaw rate with their own
inertial angular velocity.  Velocities are kept inertial (not ``r'``) because the frame's rate
steps where a cant ramp begins: the relative velocity of a body that moves on smoothly steps
there too, the inertial one does not.  A spinning body's spin angle advances at its rate against
its non-spinning frame, as off a line; that frame turns about the axle with the track frame (it
keeps its pitch on the track), not with the inertial axes.

The line's plan view is a table of ``x, y`` on a uniform grid of ``s`` with the heading's
``cos psi, sin psi`` as slopes (cubic Hermite, nodes 0.25 m apart: about ``ds^4 / (384 R^3)``,
under 1e-10 m on the 50 m curve, the smallest radius a layout takes); curvature, cant and
widening come from the segments in closed form.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

# the packed line: a header, then the segments' rows, then the plan grid's rows
L_NSEG, L_S0, L_START, L_NGRID, L_DS, L_LENGTH = range(6)
L_HEAD = 6
# a segment's row: its start, length, curvature, cant and widening at its start with their
# slopes along s, and the heading at its start
SG_START, SG_LEN, SG_K0, SG_DK, SG_E0, SG_DE, SG_W0, SG_DW, SG_PSI0 = range(9)
SG_WIDTH = 9
# a grid row: x, y, cos psi, sin psi at s = j ds
GR_X, GR_Y, GR_C, GR_S = range(4)
GR_WIDTH = 4

# a frame's row (the work array ``frm``, one a body; ``fr`` scratch for the wheels)
FR_S = 0           # chainage of the frame, m
FR_O = 1           # (3) origin, inertial, m
FR_A = 4           # (9) axes A_F, row-major (columns: forward, left, normal)
FR_W = 13          # (3) angular velocity, frame axes, rad/s
FR_V = 16          # the frame's speed along the line, m/s
FR_WR = 17         # (3) the body frame's rate relative to the track frame (body axes), rad/s
FR_DR = 20         # (3) the body's position rate r' relative to the frame, m/s
FR_WB = 23         # (3) A_rel^T omega_F: the track frame's rate in the body's axes, rad/s
FR_WID = 26        # gauge widening, m
FR_N = 27


def pack(line, start: float = 0.0, ds: float = 0.25) -> np.ndarray:
    """``line`` (:class:`axlebox.mbs.track.line.Line`) for the kernels: the header (``start``,
    where the car's reference point starts, m), the segments' rows and the plan view on a grid
    of ``ds`` (m) with the heading's direction as the Hermite slopes (module docstring)."""
    n = len(line.segments)
    ng = int(math.floor(line.length / ds)) + 2
    head = np.zeros(L_HEAD)
    head[[L_NSEG, L_S0, L_START, L_NGRID, L_DS, L_LENGTH]] = (n, line.s0, start, ng, ds,
                                                              line.length)
    seg = np.zeros((n, SG_WIDTH))
    psi0 = line.at(line.starts[:n]).psi
    for i, g in enumerate(line.segments):
        (k0, e0, w0), (k1, e1, w1) = line.ends[i]
        L = g.length
        seg[i, [SG_START, SG_LEN, SG_K0, SG_DK, SG_E0, SG_DE, SG_W0, SG_DW, SG_PSI0]] = (
            line.starts[i], L, k0, (k1 - k0) / L, e0, (e1 - e0) / L, w0, (w1 - w0) / L, psi0[i])
    sj = np.arange(ng) * ds
    inside = np.minimum(sj, line.length)
    xy = line.xy(inside)
    psi = line.at(inside).psi
    beyond = sj - inside                      # the last node past the end: straight on
    grid = np.stack([xy[0] + beyond * np.cos(psi), xy[1] + beyond * np.sin(psi),
                     np.cos(psi), np.sin(psi)], axis=1)
    return np.concatenate([head, seg.ravel(), grid.ravel()])


@njit(cache=True)
def _segment(line, s):
    """Index of the segment holding ``s`` (the first or last beyond the line's ends)."""
    n = int(line[L_NSEG])
    k = 0
    while k < n - 1 and s >= line[L_HEAD + (k + 1) * SG_WIDTH + SG_START]:
        k += 1
    return k


@njit(cache=True)
def geometry(line, s):
    """``(kappa, dkappa, e, de, widening, psi)`` of the line at ``s`` (segments' closed forms:
    curvature, cant and widening linear along a segment)."""
    o = L_HEAD + _segment(line, s) * SG_WIDTH
    u = s - line[o + SG_START]
    dk, de, dw = line[o + SG_DK], line[o + SG_DE], line[o + SG_DW]
    k0 = line[o + SG_K0]
    return (k0 + dk * u, dk, line[o + SG_E0] + de * u, de, line[o + SG_W0] + dw * u,
            line[o + SG_PSI0] + k0 * u + 0.5 * dk * u * u)


@njit(cache=True)
def plan_point(line, s):
    """``(x, y)`` of the centre line at ``s``: cubic Hermite on the grid with the heading's
    direction as slopes; straight on beyond the ends."""
    ds, ng = line[L_DS], int(line[L_NGRID])
    g0 = L_HEAD + int(line[L_NSEG]) * SG_WIDTH
    x = s / ds
    i = int(math.floor(x))
    if i < 0:
        return line[g0 + GR_X] + s * line[g0 + GR_C], line[g0 + GR_Y] + s * line[g0 + GR_S]
    if i >= ng - 1:
        o = g0 + (ng - 1) * GR_WIDTH
        d = s - (ng - 1) * ds
        return line[o + GR_X] + d * line[o + GR_C], line[o + GR_Y] + d * line[o + GR_S]
    u = x - i
    a = g0 + i * GR_WIDTH
    b = a + GR_WIDTH
    u2 = u * u
    u3 = u2 * u
    h00, h10, h01, h11 = 2 * u3 - 3 * u2 + 1, (u3 - 2 * u2 + u) * ds, -2 * u3 + 3 * u2, (u3 - u2) * ds
    return (h00 * line[a + GR_X] + h10 * line[a + GR_C] + h01 * line[b + GR_X] + h11 * line[b + GR_C],
            h00 * line[a + GR_Y] + h10 * line[a + GR_S] + h01 * line[b + GR_Y] + h11 * line[b + GR_S])


@njit(cache=True)
def frame_pose(line, s, F):
    """The track frame at ``s``: ``F[FR_S]``, its origin, axes and the widening."""
    k, dk, e, de, wid, psi = geometry(line, s)
    x, y = plan_point(line, s)
    r = e / line[L_S0]
    sf = -r                                   # phi = -asin(e / s0)
    cf = math.sqrt(1.0 - r * r)
    c, w = math.cos(psi), math.sin(psi)
    F[FR_S] = s
    F[FR_O] = x
    F[FR_O + 1] = y
    F[FR_O + 2] = 0.0
    A = FR_A
    F[A], F[A + 1], F[A + 2] = c, -w * cf, w * sf
    F[A + 3], F[A + 4], F[A + 5] = w, c * cf, -c * sf
    F[A + 6], F[A + 7], F[A + 8] = 0.0, sf, cf
    F[FR_WID] = wid
    return k, dk, e, de, sf, cf


@njit(cache=True)
def frame_motion(line, s, v, F):
    """:func:`frame_pose` and the frame's angular velocity travelling at ``v`` (module
    docstring; :func:`axlebox.mbs.track.line.frame_motion` in numba)."""
    k, dk, e, de, sf, cf = frame_pose(line, s, F)
    s0 = line[L_S0]
    r = e / s0
    F[FR_W] = -v * de / s0 / math.sqrt(1.0 - r * r)
    F[FR_W + 1] = v * k * sf
    F[FR_W + 2] = v * k * cf
    F[FR_V] = v


@njit(cache=True)
def to_frame(F, g, out):
    """``out = A_F^T g``: an inertial vector in the frame's axes (``out`` may be ``g``)."""
    g0, g1, g2 = g[0], g[1], g[2]
    for a in range(3):
        out[a] = F[FR_A + a] * g0 + F[FR_A + 3 + a] * g1 + F[FR_A + 6 + a] * g2


@njit(cache=True)
def to_inertial(F, g, out):
    """``out = A_F g``: a vector in the frame's axes, inertial (``out`` may be ``g``)."""
    g0, g1, g2 = g[0], g[1], g[2]
    for a in range(3):
        out[a] = F[FR_A + 3 * a] * g0 + F[FR_A + 3 * a + 1] * g1 + F[FR_A + 3 * a + 2] * g2


@njit(cache=True)
def body_on_line(F, spin, A, r, v, om, omf):
    """One body's kinematics from its states on its track frame ``F`` (:func:`frame_motion`
    filled) to inertial, in place (module docstring): ``A`` (A_rel -> A_F A_rel), ``r``
    (relative -> inertial), ``v`` (``u`` -> inertial); ``om`` is inertial already, and so is
    ``omf`` but on a ``spin``-ning body: its non-spinning frame keeps its pitch on the track
    frame (it turns about the axle with the frame's rate there, ``FR_WB``), so that its markers
    stay where the track has them (the tread point under the axle).  Keeps in ``F`` the rates of
    the relative position and axes."""
    w0, w1, w2 = F[FR_W], F[FR_W + 1], F[FR_W + 2]
    for a in range(3):
        F[FR_WB + a] = A[0, a] * w0 + A[1, a] * w1 + A[2, a] * w2
    if spin:
        omf[1] = F[FR_WB + 1]
    for a in range(3):
        F[FR_WR + a] = omf[a] - F[FR_WB + a]
    r0, r1, r2 = r[0], r[1], r[2]
    u0, u1, u2 = v[0], v[1], v[2]
    F[FR_DR] = u0 - F[FR_V] - (w1 * r2 - w2 * r1)
    F[FR_DR + 1] = u1 - (w2 * r0 - w0 * r2)
    F[FR_DR + 2] = u2 - (w0 * r1 - w1 * r0)
    for a in range(3):
        Aa0, Aa1, Aa2 = F[FR_A + 3 * a], F[FR_A + 3 * a + 1], F[FR_A + 3 * a + 2]
        r[a] = F[FR_O + a] + Aa0 * r0 + Aa1 * r1 + Aa2 * r2
        v[a] = Aa0 * u0 + Aa1 * u1 + Aa2 * u2
    for c in range(3):
        B0, B1, B2 = A[0, c], A[1, c], A[2, c]
        for a in range(3):
            A[a, c] = F[FR_A + 3 * a] * B0 + F[FR_A + 3 * a + 1] * B1 + F[FR_A + 3 * a + 2] * B2


@njit(cache=True)
def velocity_rates(F, y, iv, acc):
    """A body's inertial acceleration ``acc[0:3]`` turned into the rate of its velocity states
    ``u`` on its track frame ``F``, in place: ``u' = A_F^T a_abs - omega_F x u``."""
    w0, w1, w2 = F[FR_W], F[FR_W + 1], F[FR_W + 2]
    a0 = a1 = a2 = 0.0
    for c in range(3):
        a0 += F[FR_A + 3 * c] * acc[c]
        a1 += F[FR_A + 3 * c + 1] * acc[c]
        a2 += F[FR_A + 3 * c + 2] * acc[c]
    u0, u1, u2 = y[iv], y[iv + 1], y[iv + 2]
    acc[0] = a0 - (w1 * u2 - w2 * u1)
    acc[1] = a1 - (w2 * u0 - w0 * u2)
    acc[2] = a2 - (w0 * u1 - w1 * u0)


@njit(cache=True)
def ground_on_line(line, x, v, mk_i, mk_f, F, mkp, mkv, mkR, mkw):
    """On a line the ground is the track: a ground marker built at ``(X, y, z)`` is the point
    ``(0, y, z)`` of the track frame at ``s_start + x + X``, travelling with the car (the
    ballasted track's supports under the wheels); its kinematics overwrite the fixed ones."""
    for m in range(mk_i.shape[0]):
        if mk_i[m, 0] >= 0:
            continue
        frame_motion(line, line[L_START] + x + mk_f[m, 0], v, F)
        w0, w1, w2 = F[FR_W], F[FR_W + 1], F[FR_W + 2]
        p1, p2 = mk_f[m, 1], mk_f[m, 2]
        u0, u1, u2 = v + (w1 * p2 - w2 * p1), -w0 * p2, w0 * p1
        for a in range(3):
            Aa0, Aa1, Aa2 = F[FR_A + 3 * a], F[FR_A + 3 * a + 1], F[FR_A + 3 * a + 2]
            mkp[m, a] = F[FR_O + a] + Aa1 * p1 + Aa2 * p2
            mkv[m, a] = Aa0 * u0 + Aa1 * u1 + Aa2 * u2
            mkw[m, a] = Aa0 * w0 + Aa1 * w1 + Aa2 * w2
            for c in range(3):
                mkR[m, a, c] = (Aa0 * mk_f[m, 3 + c] + Aa1 * mk_f[m, 6 + c]
                                + Aa2 * mk_f[m, 9 + c])
