"""The wheel-rail force element in numba: one wheel on its rail, plain arrays and floats only.

:func:`wheel_rail_force` is what the multibody right-hand side calls for each wheel.  Its tables
come from :func:`axlebox.mbs.wheelrail.element.build_tables`; :func:`axlebox.mbs.wheelrail.element.
wheel_force_reference` is the same element in numpy, for the tests.

Frame: the track frame (inertial, track-fixed): x forward along the track, y left, z up, z = 0 at
the crown of the nominal rails (the side-local rail origin of :mod:`axlebox.mbs.wheelrail.geometry`); the
vehicle runs at +V along x.  Side 0 = left (s = +1), 1 = right (s = -1).

Method (up to NPT contact points per wheel, one per region of the wheel's surface: tread,
flange root, flange; elastic normal contact, table look-up):

1. Look-up.  The wheel's roll ``phi = atan2(e_z, hypot(e_x, e_y))`` (independent of yaw).  The
   table is indexed by the wheel's own lateral offset from its rail,
   ``u = c_y - s l0 - y_rail + k r0 sin(phi)``, per side on a uniform grid with linear
   interpolation, clamped at the ends: ``out[OUT_CLAMP] = CLAMP_FLANGE`` past ``P_UFL`` on the
   flange side, where the rigid wheelset's table ends (a flange climb), ``CLAMP_FIELD`` past the
   grid's end on the field side, which each wheel's table reaches ``y_field`` further (element.py
   step 1: the wheel run off its rail head).  ``k = 0`` (``index="centre"``)
   is the offset of the wheel centre; ``k = 1`` (``index="tread"``, the default) is the offset of
   the wheel's lowest taping-line point, i.e. of the wheel where it meets the rail.  Why: a wheel
   rolled by ``dphi`` more than the table's rigid solution (cross-level irregularity, wheelset
   bending) has its tread shifted by ``r0 dphi`` against its centre, about 0.8 mm per 2 mrad, and
   on S1002/60E1, whose contact point jumps across the tread, indexing by the centre then puts the
   reference contact on the wrong part of the profile: with 2 mrad of extra roll the centre index
   misses a 50 um penetration by up to 43 um on the tread (340 um at the flange), the tread index
   by under 2 um (``tests/test_wheelrail_element.py``).  Both coincide when the roll is the
   table's.  Limit: the table is 1-D, so 5 mrad of extra roll (7.5 mm of cross-level) still
   costs up to 44 um where the contact point jumps; a table in (u, roll) would remove that.
2. Penetration.  The table row is a touching configuration: reference wheel centre ``c0`` (from
   the wheelset's ``roll0, z0``) and, per region, its point ``p0`` on the rail closest to the
   wheel, its contact angle delta and its vertical ``gap`` there (0 for the region that holds
   the rigid contact; :func:`axlebox.mbs.wheelrail.geometry.contact_regions`).  The
   wheel's actual pose differs by the translation ``c - c0`` and the rotation ``dphi = phi -
   roll0`` about x; its surface point at ``p0`` moves by
   ``dp = (c - c0) + (R(dphi) - I)(p0 - c0)``, and the penetration is the approach along the
   contact normal less the region's gap along it, ``pen = -dp.n - gap cos(delta)`` (first
   order in the motion away from the touching row; exact for the vertical approach, which is
   all there is on a perfect track).  So where the profiles give two-point contact (S1002 on
   60E1: tread and flange root at 5 mm of lateral displacement, flange root and flange at 6.2
   mm) both regions carry load as soon as the wheel's approach closes the second one's gap,
   each with its own normal, Hertz patch and creep forces (steps 3-5), as in the multi-Hertzian
   methods (Pombo & Ambrosio, Multibody Syst. Dyn. 19 (2008) 91-114; Shabana, Zaazaa &
   Sugiyama, *Railroad Vehicle Dynamics*, CRC 2008, ch. 5).  Rail irregularities
   shift ``c0`` and ``p0`` by ``(0, y_rail, z_rail)``.  ``pen <= 0``: no force.
3. Normal force, Hunt & Crossley (1975) damping, which vanishes with the penetration so that the
   force is continuous at first touch: ``N = K_H pen^1.5 (1 + chi pen_dot)``, clipped at
   ``N >= 0``, with ``pen_dot = -(v_p - v_rail).n`` the normal approach rate and
   ``v_rail = (0, dy_rail, dz_rail)`` the rate of the irregularity under the moving contact.
   Hertz semi-axes ``a = a_hat sqrt(pen)``, ``b = b_hat sqrt(pen)`` (a along x).
4. Contact frame ``t1 = x``, ``n = (0, -s sin(delta), cos(delta))`` (the rail's outward normal,
   acting on the wheel: its lateral part pushes a flange back towards the track centre),
   ``t2 = n x t1 = (0, cos(delta), s sin(delta))``, so ``n = t1 x t2`` as in
   :mod:`axlebox.mbs.wheelrail.kalker`.  The contact point ``p`` has the table's ``y, z`` and
   lies where the wheel's surface of revolution has the normal n: in the meridian plane of the
   axle ``e`` and n, so ``p - c = alpha e + r m`` with ``m = -(n - (n.e) e) / sqrt(1 - (n.e)^2)``
   and ``p_x - c_x = alpha e_x + r (n.e) e_x / sqrt(1 - (n.e)^2)``, ``alpha = (p - c).e`` (its
   lateral and vertical parts): a yawed wheelset's flange contact leads or lags the axle by
   ``r tan(delta) psi``, which makes its lateral creepage ``(y'/V - psi) / cos(delta)``
   (Wickens, *Fundamentals of Rail Vehicle Dynamics*, 2003, ch. 2).  Creepages from the wheel's
   material velocity at the contact,
   ``v_p = v_c + omega x (p - c)``: ``xi = v_p.t1/V``, ``eta = v_p.t2/V``, spin
   ``omega.n/V`` (1/m).  The rail's material is at rest, so nothing is subtracted: a wheel that
   follows a lateral irregularity exactly (``v_y = V y_rail'``, yaw ``y_rail'``) has ``eta = 0``;
   ``dy_rail, dz_rail`` enter only the approach rate.  ``V`` is floored at ``v_min``.
5. Tangential forces ``Fx, Fy`` (on the wheel, along t1, t2) and spin moment ``Mz`` by the law
   code: FASTSIM (:mod:`axlebox.mbs.wheelrail.fastsim_kernel`, flexibilities
   ``L1 = 8a/(3 C11 G)``, ``L2 = 8a/(3 C22 G)``, ``L3 = pi a sqrt(a/b)/(4 C23 G)``), Kalker's
   linear law, or Shen-Hedrick-Elkins (formulas in :mod:`axlebox.mbs.wheelrail.kalker` and
   :func:`axlebox.mbs.wheelrail.tangential.shen_hedrick_elkins`).  None when ``N = 0``.
6. Per region ``F = N n + Fx t1 + Fy t2`` on the wheel at ``p`` and ``M = (p - c) x F + Mz n``
   about c; the wheel's force and moment are their sums.

Neglected: the change of the lateral clearance with yaw (``r tan(delta) psi^2``, second order),
the rail's slope in the contact frame, more than NPT regions; within a region the contact point's
jumps (the tread's at 0.1 mm) are smeared over ``smooth_y`` of lateral displacement (element.py,
step 3).
"""
from __future__ import annotations

from math import atan2, cos, sin, sqrt

import numpy as np
from numba import njit

from .fastsim_kernel import fastsim_forces
from .geometry import NPT

# ----------------------------------------------------------------------- tab: per-side columns
# tab has shape (n_grid, 2 NCOL): column side * NCOL + COL_*, rows on the uniform grid of u.
# First the rigid wheelset's touching pose, then NPT blocks of NPC columns, one per contact
# region of the wheel (tread, flange root, flange): region k's column is COL_* + k NPC.
COL_ROLL0 = 0      # wheelset roll of the rigid contact solution, rad
COL_Z0 = 1         # wheelset centre height above r0, m
COL_C0Y = 2        # reference wheel centre, lateral, relative to y_rail + s l0, m
COL_C0Z = 3        # reference wheel centre height, relative to z_rail, m
COL_PY = 4         # the region's contact point, track y, relative to y_rail, m
COL_PZ = 5         # contact point height, relative to z_rail, m
COL_DELTA = 6      # contact angle (geometry.py sign: + when the rail rises to the field side)
COL_R = 7          # rolling radius, m
COL_A = 8          # relative curvature along x, 1/m
COL_B = 9          # relative curvature along y (floored at B_min), 1/m
COL_KH = 10        # Hertz constant of N = K_H pen^1.5, N/m^1.5
COL_AHAT = 11      # a = a_hat sqrt(pen), m^0.5
COL_BHAT = 12      # b = b_hat sqrt(pen), m^0.5
COL_C11 = 13       # Kalker's coefficients at a/b = a_hat/b_hat and nu
COL_C22 = 14
COL_C23 = 15
COL_C33 = 16
COL_GAP = 17       # the region's vertical gap in the touching pose (0: the rigid contact), m
NPC = COL_GAP + 1 - COL_PY     # columns per region
NCOL = COL_PY + NPT * NPC

# ----------------------------------------------------------------------------------- par slots
P_U0 = 0           # first grid point of u, m
P_DU = 1           # grid step, m
P_NGRID = 2        # number of grid points
P_R0 = 3           # nominal rolling radius, m
P_L0 = 4           # half the distance between the nominal wheel centres (taping-line planes), m
P_INDEX = 5        # k of the look-up: 0 centre, 1 tread
P_UFL = 6          # the flange side's end of the table, s u, m (the grid reaches further only on
                   # each wheel's field side)
P_MU = 7           # friction coefficient
P_G = 8            # shear modulus, Pa
P_NU = 9           # Poisson ratio (already in the tables; kept for the record)
P_LAW = 10         # 0 FASTSIM, 1 Kalker linear, 2 Shen-Hedrick-Elkins
P_NX = 11          # FASTSIM elements per strip
P_NY = 12          # FASTSIM strips
P_ELLIPTIC = 13    # FASTSIM traction bound: 0 parabolic, 1 elliptic
P_ROTATE = 14      # FASTSIM slip step: 0 cut-back, 1 rotate
P_CHI = 15         # Hunt-Crossley damping, s/m
P_VMIN = 16        # floor of the reference speed in the creepages, m/s
N_PAR = 17

LAW_FASTSIM = 0
LAW_KALKER = 1
LAW_SHE = 2

# ----------------------------------------------------------------------------------- out slots
# the scalars OUT_N ... OUT_R are those of the region carrying the largest normal force (of the
# one nearest to touching when none does); F and M are the sums over the regions
OUT_F = 0          # (3) force on the wheel, track frame, N
OUT_M = 3          # (3) moment on the wheel about c, N m
OUT_N = 6          # normal force, N
OUT_PEN = 7        # penetration along the normal (negative: gap), m
OUT_XI = 8         # longitudinal creepage
OUT_ETA = 9        # lateral creepage
OUT_SPIN = 10      # spin creepage, 1/m
OUT_FX = 11        # tangential force along t1, N
OUT_FY = 12        # tangential force along t2, N
OUT_P = 13         # (3) contact point, track frame, m
OUT_A = 16         # semi-axis along x, m
OUT_B = 17         # semi-axis along t2, m
OUT_DELTA = 18     # contact angle, rad
OUT_MZ = 19        # spin moment about n, N m
OUT_PENDOT = 20    # normal approach rate, m/s
OUT_R = 21         # rolling radius, m
OUT_CLAMP = 22     # 0 on the table, else which end u was clamped at:
CLAMP_FLANGE = 1.0  # past the flange side's end (P_UFL)
CLAMP_FIELD = 2.0   # past the field side's end
OUT_NPT = 23       # (NPT) each region's normal force, tread first, N
OUT_DPT = OUT_NPT + NPT        # (NPT) each region's contact angle, rad
OUT_YPT = OUT_DPT + NPT        # (NPT) each region's contact point, track y, m
N_OUT = OUT_YPT + NPT


@njit(cache=True, inline="always")
def _lerp(tab, i, w, j):
    return tab[i, j] + w * (tab[i + 1, j] - tab[i, j])


@njit(cache=True)
def tangential_law(law, xi, eta, spin, a, b, N, mu, G, C11, C22, C23, C33, elliptic, rotate,
                   nx, ny):
    """``(Fx, Fy, Mz)`` on the wheel by law code (module docstring, step 5)."""
    if N <= 0.0:
        return 0.0, 0.0, 0.0
    if law == LAW_FASTSIM:
        L1 = 8.0 * a / (3.0 * C11 * G)
        L2 = 8.0 * a / (3.0 * C22 * G)
        L3 = np.pi * a * sqrt(a / b) / (4.0 * C23 * G)
        return fastsim_forces(xi, eta, spin, a, b, N, mu, L1, L2, L3, elliptic, rotate, nx, ny)
    c = sqrt(a * b)
    Gc2 = G * a * b
    Fx = -Gc2 * C11 * xi
    Fy = -Gc2 * (C22 * eta + c * C23 * spin)
    Mz = Gc2 * c * (C23 * eta - c * C33 * spin)
    if law == LAW_SHE:
        # Shen, Hedrick & Elkins 1983: |F| -> mu N (beta - beta^2/3 + beta^3/27), beta < 3
        muN = mu * N
        FR = sqrt(Fx * Fx + Fy * Fy)
        if muN <= 0.0:
            eps = 0.0
        elif FR > 1e-12 * muN:
            beta = min(FR / muN, 3.0)
            eps = (beta - beta * beta / 3.0 + beta * beta * beta / 27.0) * muN / FR
        else:
            eps = 1.0 - FR / muN / 3.0
        Fx *= eps
        Fy *= eps
        Mz *= eps
    return Fx, Fy, Mz


@njit(cache=True)
def _region(tab, i, w, col, par, s, c, e, v_c, omega, Vr, y_rail, z_rail, dy_rail, dz_rail,
            c0y, c0z, cd, sd):
    """One contact region (module docstring, steps 2-5), its columns ``col + COL_*``.  Returns
    ``(N, pen, xi, eta, spin, Fx, Fy, Mz, a, b, delta, pen_dot, lx, ly, lz, r)``."""
    py = _lerp(tab, i, w, col + COL_PY)
    pz = _lerp(tab, i, w, col + COL_PZ)
    delta = _lerp(tab, i, w, col + COL_DELTA)
    r = _lerp(tab, i, w, col + COL_R)
    # the wheel's surface point at p0 moved from the touching row to the actual pose
    ry = py - c0y
    rz = pz - c0z
    dpy = (cd - 1.0) * ry - sd * rz + (c[1] - y_rail - c0y)
    dpz = sd * ry + (cd - 1.0) * rz + (c[2] - z_rail - c0z)
    sdl = sin(delta)
    cdl = cos(delta)
    ny_ = -s * sdl                                       # n = (0, ny_, nz_)
    nz_ = cdl
    pen = -(ny_ * dpy + nz_ * dpz) - _lerp(tab, i, w, col + COL_GAP) * cdl
    # the contact point: where the wheel's surface of revolution has the normal n (its
    # meridian plane holds e and n), ahead of the axle by r (n.e) e_x / sqrt(1 - (n.e)^2)
    ly = y_rail + py - c[1]
    lz = z_rail + pz - c[2]
    ne = ny_ * e[1] + nz_ * e[2]
    lx = (ly * e[1] + lz * e[2]) * e[0] + r * ne * e[0] / sqrt(1.0 - ne * ne)
    vx = v_c[0] + omega[1] * lz - omega[2] * ly
    vy = v_c[1] + omega[2] * lx - omega[0] * lz
    vz = v_c[2] + omega[0] * ly - omega[1] * lx
    pen_dot = -((vy - dy_rail) * ny_ + (vz - dz_rail) * nz_)
    xi = vx / Vr
    eta = (vy * cdl + vz * s * sdl) / Vr
    spin = (omega[1] * ny_ + omega[2] * nz_) / Vr
    N = 0.0
    a = 0.0
    b = 0.0
    Fx = 0.0
    Fy = 0.0
    Mz = 0.0
    if pen > 0.0:
        sp = sqrt(pen)
        N = max(_lerp(tab, i, w, col + COL_KH) * pen * sp * (1.0 + par[P_CHI] * pen_dot),
                0.0)
        a = _lerp(tab, i, w, col + COL_AHAT) * sp
        b = _lerp(tab, i, w, col + COL_BHAT) * sp
        Fx, Fy, Mz = tangential_law(
            int(par[P_LAW]), xi, eta, spin, a, b, N, par[P_MU], par[P_G],
            _lerp(tab, i, w, col + COL_C11), _lerp(tab, i, w, col + COL_C22),
            _lerp(tab, i, w, col + COL_C23), _lerp(tab, i, w, col + COL_C33),
            int(par[P_ELLIPTIC]), int(par[P_ROTATE]), int(par[P_NX]), int(par[P_NY]))
    return N, pen, xi, eta, spin, Fx, Fy, Mz, a, b, delta, pen_dot, lx, ly, lz, r


@njit(cache=True)
def wheel_rail_force(side, c, e, v_c, omega, V, z_rail, y_rail, dz_rail, dy_rail, tab, par,
                     out):
    """Force and moment of the rail on one wheel (module docstring); fills ``out[:N_OUT]``.

    ``side`` 0 left / 1 right; ``c`` wheel centre (on the axle, in the taping-line plane),
    ``e`` unit axle direction (to the left), ``v_c`` its velocity, ``omega`` the wheel's
    material angular velocity (with spin), all (3,) in the track frame; ``V`` the running
    speed (> 0); ``z_rail, y_rail`` this rail's irregularity at the contact and
    ``dz_rail, dy_rail`` their time rates; ``tab, par`` from ``build_tables``.
    """
    s = 1.0 if side == 0 else -1.0
    base = side * NCOL
    r0 = par[P_R0]
    l0 = par[P_L0]
    phi = atan2(e[2], sqrt(e[0] * e[0] + e[1] * e[1]))
    u = c[1] - s * l0 - y_rail + par[P_INDEX] * r0 * sin(phi)
    n_grid = int(par[P_NGRID])
    t = (u - par[P_U0]) / par[P_DU]
    clamp = CLAMP_FLANGE if s * u > par[P_UFL] else 0.0
    if t < 0.0 or t > n_grid - 1.0:         # only a field side is left at the grid's ends
        t = min(max(t, 0.0), n_grid - 1.0)
        if clamp == 0.0:
            clamp = CLAMP_FIELD
    i = min(int(t), n_grid - 2)
    w = t - i
    c0y = s * l0 + _lerp(tab, i, w, base + COL_C0Y)      # relative to y_rail
    c0z = _lerp(tab, i, w, base + COL_C0Z)               # relative to z_rail
    dphi = phi - _lerp(tab, i, w, base + COL_ROLL0)
    cd = cos(dphi)
    sd = sin(dphi)
    Vr = max(V, par[P_VMIN])
    for j in range(6):
        out[OUT_F + j] = 0.0
    best = -1
    for k in range(NPT):
        (N, pen, xi, eta, spin, Fx, Fy, Mz, a, b, delta, pen_dot, lx, ly, lz,
         r) = _region(tab, i, w, base + k * NPC, par, s, c, e, v_c, omega, Vr, y_rail,
                      z_rail, dy_rail, dz_rail, c0y, c0z, cd, sd)
        # F = N n + Fx t1 + Fy t2,  t1 = x, t2 = (0, cos delta, s sin delta)
        sdl = sin(delta)
        cdl = cos(delta)
        Fxw = Fx
        Fyw = -N * s * sdl + Fy * cdl
        Fzw = N * cdl + Fy * s * sdl
        out[OUT_F] += Fxw
        out[OUT_F + 1] += Fyw
        out[OUT_F + 2] += Fzw
        out[OUT_M] += ly * Fzw - lz * Fyw
        out[OUT_M + 1] += lz * Fxw - lx * Fzw - Mz * s * sdl
        out[OUT_M + 2] += lx * Fyw - ly * Fxw + Mz * cdl
        out[OUT_NPT + k] = N
        out[OUT_DPT + k] = delta
        out[OUT_YPT + k] = c[1] + ly
        if best < 0 or N > out[OUT_N] or (N == out[OUT_N] and pen > out[OUT_PEN]):
            best = k
            out[OUT_N] = N
            out[OUT_PEN] = pen
            out[OUT_XI] = xi
            out[OUT_ETA] = eta
            out[OUT_SPIN] = spin
            out[OUT_FX] = Fx
            out[OUT_FY] = Fy
            out[OUT_P] = c[0] + lx
            out[OUT_P + 1] = c[1] + ly
            out[OUT_P + 2] = c[2] + lz
            out[OUT_A] = a
            out[OUT_B] = b
            out[OUT_DELTA] = delta
            out[OUT_MZ] = Mz
            out[OUT_PENDOT] = pen_dot
            out[OUT_R] = r
    out[OUT_CLAMP] = clamp
