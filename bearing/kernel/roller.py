"""A roller's and a cage's kinematics and Newton-Euler equations (numba), shared by every model
whose rollers have the six degrees of freedom of :mod:`.layout` (paper Eqs. 12, 13).

Frame: the bearing's, origin at the inner-ring centre and translating with it (not spinning);
x longitudinal, y along the axle, z vertical.  For a roller at azimuth phi:
``e_r = (sin phi, 0, cos phi)``, ``e_t = (cos phi, 0, -sin phi)``, ``e_r x e_t = e_y``.  Row j
of n sits at ``y_j`` (:func:`.layout.row_y`: two rows at ``-+ row_offset``, one at the centre), its
rollers leaning as its sign ``s`` says (:func:`.layout.row_sign`: +1 on the -y side, -1 on the
+y side).  The roller's axis ``a`` leans by the
angle ``alpha_m`` from the bearing axis in the axial plane (0 for a cylindrical roller), ``b``
is normal to it there; the small tilt ``theta_t`` turns the roller about ``e_t``, the skew
``theta_s`` about ``b``.

Eq. (2): with a kinematic cage (:data:`.layout.EQ2_CAGE`) the cage turns at
``omega_c = (1 - D_b/D_m) omega_w / 2`` and each roller sits at its pocket centre
``2 pi (k - 1) / Z + phi_c``; the quasi-dynamic bearing's cage (:data:`.layout.POCKET_CAGE`)
holds the rollers at their pockets too, its rotation a state carrying their orbital inertia
(bearing/kernel/quasidynamic.py); otherwise every roller's azimuth and the cage's angle are dynamic
states and the cage's slip follows from the contacts.
"""
from __future__ import annotations

from collections import namedtuple
from math import cos, pi, sin

from axlebox._numba import kernel

from .layout import (C_FORCE, C_LOAD, C_MOMENT, CAGE_SLOTS, CAM, CPHI, CTX, CTZ, CX, EQ2_CAGE, ETA,
                     FREE_CAGE, G_X, G_Y, G_Z, INNER, J_CD, J_CP, J_RA, J_RD, KINEMATIC, M_C, M_R, N_ROWS,
                     OUTER, PHI, POCKET_CAGE, PSI, R_M, RATE, RATIO, REC_F, REC_LOAD, REC_M, RHO, ROW, SAM,
                     TH_S, TH_T, TH_X, TH_Y, TH_Z, U_X, V_X, W_X, W_Y, Z, row_sign, row_y)
from .vec import EY, add, dot, get, lin, mul, sub

TWO_PI = 2.0 * pi

#: a roller's kinematics (:func:`roller_frame`): the row's sign ``s`` and axial place ``yj``,
#: the roller's azimuth ``phi`` and orbit rate ``phid``,
#: the centre's radius ``Rr = R + rho``, the frame ``er, et`` and the roller's axis ``ax`` and
#: its normal ``bx``, the centre ``c`` and its displacement ``disp`` from its nominal place, the
#: centre's velocity ``V``, the angular velocity ``w``, the small rotation ``theta`` and its
#: tilt and skew ``tht, ths``
Frame = namedtuple("Frame", ["s", "yj", "phi", "phid", "Rr", "er", "et", "ax", "bx", "c", "disp", "V",
                             "w", "theta", "tht", "ths"])
#: a row's cage (:func:`cage_frame`): centre, small tilt, angle, velocity, angular velocity
Cage = namedtuple("Cage", ["xc", "th", "phi", "v", "w"])
#: the rings' motion relative to the inner ring's centre (:func:`ring_frame`): displacement,
#: small tilt, velocity and angular velocity of each; the rings' angles about the axle and
#: the inner ring's spin relative to the outer
Rings = namedtuple("Rings", ["ui", "thi", "vi", "wi", "uo", "tho", "vo", "wo", "angle_i",
                             "angle_o", "omega"])


@kernel
def ring_frame(ring):
    """:class:`Rings` from a ring motion (:mod:`.layout`): the frame translates with the inner
    ring and does not spin, so the inner ring's displacement and velocity are nil there and
    only the rings' tilts about x and z enter their small rotations."""
    zero = (0.0, 0.0, 0.0)
    return Rings(zero, (ring[INNER, TH_X], 0.0, ring[INNER, TH_Z]), zero, get(ring[INNER], W_X),
                 sub(get(ring[OUTER], U_X), get(ring[INNER], U_X)),
                 (ring[OUTER, TH_X], 0.0, ring[OUTER, TH_Z]),
                 sub(get(ring[OUTER], V_X), get(ring[INNER], V_X)), get(ring[OUTER], W_X),
                 ring[INNER, TH_Y], ring[OUTER, TH_Y], ring[INNER, W_Y] - ring[OUTER, W_Y])


@kernel
def cage_frame(x, cb, P, omega_w):
    """:class:`Cage` of the row whose cage slots start at ``cb`` (Eq. 2's rate about the axle
    for a kinematic cage; ``omega_w`` the inner ring's spin relative to the outer)."""
    phid_c = x[cb + RATE + CPHI]
    if P[KINEMATIC] == EQ2_CAGE:
        phid_c = P[RATIO] * omega_w
    return Cage(get(x, cb + CX), (x[cb + CTX], 0.0, x[cb + CTZ]), x[cb + CPHI],
                get(x, cb + RATE + CX), (x[cb + RATE + CTX], phid_c, x[cb + RATE + CTZ]))


@kernel
def pocket_angles(phi_c, nz, sin_p, cos_p):
    """``sin_p[k], cos_p[k]`` of pocket k's azimuth ``phi_c + 2 pi k / Z``, by rotation."""
    sp, cp = sin(phi_c), cos(phi_c)
    sd, cd = sin(TWO_PI / nz), cos(TWO_PI / nz)
    for k in range(nz):
        sin_p[k] = sp
        cos_p[k] = cp
        sp, cp = sp * cd + cp * sd, cp * cd - sp * sd


@kernel(inline="always")
def roller_frame(x, b0, j, P, phi_p, sp, cp, phid_c):
    """:class:`Frame` of the roller of row j whose slots start at ``b0``; ``phi_p``, ``sp``,
    ``cp``: the azimuth of its pocket and its sine and cosine, where a kinematic cage puts it (at
    the rate ``phid_c``)."""
    nrow = int(P[N_ROWS])
    s, yj = row_sign(j, nrow), row_y(j, nrow, P[ROW])
    rho, eta = x[b0 + RHO], x[b0 + ETA]
    phi, phid = x[b0 + PHI], x[b0 + RATE + PHI]
    if P[KINEMATIC] != FREE_CAGE:
        phi, phid = phi_p, phid_c
    else:
        sp, cp = sin(phi), cos(phi)
    cam, sam = P[CAM], P[SAM]
    er = (sp, 0.0, cp)
    et = (cp, 0.0, -sp)
    ax = lin(s * cam, EY, -sam, er)              # roller axis, large end -> small end
    bx = lin(cam, er, s * sam, EY)               # normal to it in the axial plane
    Rr = P[R_M] + rho
    V = add(lin(x[b0 + RATE + RHO], er, Rr * phid, et), mul(x[b0 + RATE + ETA], EY))
    w = add(lin(phid, EY, x[b0 + RATE + PSI], ax),
            lin(x[b0 + RATE + TH_T], et, x[b0 + RATE + TH_S], bx))
    tht, ths = x[b0 + TH_T], x[b0 + TH_S]
    return Frame(s, yj, phi, phid, Rr, er, et, ax, bx, lin(Rr, er, yj + eta, EY),
                 lin(rho, er, eta, EY), V, w, lin(tht, et, ths, bx), tht, ths)


@kernel(inline="always")
def roller_rates(x, dx, b0, fr, rec, P, phid_c, J_orb):
    """Newton-Euler of roller ``fr`` (:class:`Frame`, its slots from ``b0``) under the load of
    its record ``rec`` (its weight and its contacts), Eq. (12) in polar form with the orbiting
    frame's centrifugal, Coriolis and gyroscopic terms: its rows of ``dx``.  Returns its pull on
    a quasi-dynamic cage's rotation (its tangential force over the cage's orbital inertia
    ``J_orb``; 0 for other cages)."""
    s, phid, Rr = fr.s, fr.phid, fr.Rr
    Mr, Ja, Jd, cam, sam = P[M_R], P[J_RA], P[J_RD], P[CAM], P[SAM]
    F = get(rec, REC_F)
    M = get(rec, REC_M)
    rhod, thtd, thsd = x[b0 + RATE + RHO], x[b0 + RATE + TH_T], x[b0 + RATE + TH_S]
    for q in (RHO, ETA, TH_T, TH_S, PSI):
        dx[b0 + q] = x[b0 + RATE + q]
    dx[b0 + RATE + RHO] = dot(F, fr.er) / Mr + Rr * phid * phid
    dx[b0 + RATE + ETA] = dot(F, EY) / Mr
    orbit = 0.0
    if P[KINEMATIC] != FREE_CAGE:
        phidd = 0.0
        dx[b0 + PHI] = phid_c
        dx[b0 + RATE + PHI] = 0.0
        if P[KINEMATIC] == POCKET_CAGE:            # its share of the cage's acceleration
            orbit = dot(F, fr.et) * Rr / J_orb
            dx[b0 + RATE + PHI] = orbit
    else:
        phidd = (dot(F, fr.et) / Mr - 2.0 * rhod * phid) / Rr
        dx[b0 + PHI] = phid
        dx[b0 + RATE + PHI] = phidd
    wa = x[b0 + RATE + PSI] + phid * s * cam
    # gyroscopic terms: the spinning axis turned by the orbit and by tilt/skew rates
    dx[b0 + RATE + TH_T] = (dot(M, fr.et) + Ja * wa * phid * sam - Jd * phid * phid * s * sam * cam
                            - Jd * phid * thsd * cam + s * Ja * wa * thsd) / Jd
    dx[b0 + RATE + TH_S] = (dot(M, fr.bx) - Jd * phidd * s * sam + Jd * phid * thtd * cam
                            - s * Ja * wa * thtd) / Jd
    dx[b0 + RATE + PSI] = dot(M, fr.ax) / Ja - s * cam * phidd
    return orbit


@kernel
def cage_rates(x, dx, cb, P, rec_row, nz, cage, orbit, J_orb):
    """Eq. (13) for the cage of a row (:class:`Cage`, its slots from ``cb``): translation,
    small tilt (with the gyroscopic coupling of its spin) and rotation under the loads its
    ``nz`` rollers' records put on it; a quasi-dynamic cage's rotation carries the rollers'
    orbital inertia (``orbit``: their pulls summed)."""
    Fc = (0.0, 0.0, 0.0)
    Mc = (0.0, 0.0, 0.0)
    for k in range(nz):
        for c in CAGE_SLOTS:
            Fc = add(Fc, get(rec_row[k], REC_LOAD + C_LOAD * c + C_FORCE))
            Mc = add(Mc, get(rec_row[k], REC_LOAD + C_LOAD * c + C_MOMENT))
    Mc_x, Mc_y, Mc_z = Mc
    w_x, phid_c, w_z = cage.w
    Jcp, Jcd = P[J_CP], P[J_CD]
    g = (P[G_X], P[G_Y], P[G_Z])
    for q in range(3):
        dx[cb + CX + q] = x[cb + RATE + CX + q]
        dx[cb + RATE + CX + q] = Fc[q] / P[M_C] + g[q]
    dx[cb + CTX] = w_x
    dx[cb + CTZ] = w_z
    dx[cb + RATE + CTX] = (Mc_x + Jcp * phid_c * w_z) / Jcd
    dx[cb + RATE + CTZ] = (Mc_z - Jcp * phid_c * w_x) / Jcd
    dx[cb + CPHI] = phid_c
    if P[KINEMATIC] == POCKET_CAGE:
        dx[cb + RATE + CPHI] = Mc_y / J_orb + orbit
    elif P[KINEMATIC] == FREE_CAGE:
        dx[cb + RATE + CPHI] = Mc_y / Jcp
    else:
        dx[cb + RATE + CPHI] = 0.0


@kernel
def orbital_inertia(P):
    """The quasi-dynamic cage's rotational inertia with its rollers' orbits,
    ``J_cp + Z M_r R^2`` (bearing/kernel/quasidynamic.py)."""
    return P[J_CP] + P[Z] * P[M_R] * P[R_M] * P[R_M]
