"""Numba right-hand side of the DTRB: rollers and cages of both rows (paper Eqs. 1-16).

Plain arrays in, plain arrays out (slots in :mod:`.layout`); vectors are 3-tuples so that
nothing is allocated inside the loops.  Frame: the bearing's, origin at the inner-ring centre
and translating with it (not spinning); x longitudinal, y along the axle, z vertical.  For a
roller at azimuth phi: ``e_r = (sin phi, 0, cos phi)``, ``e_t = (cos phi, 0, -sin phi)``,
``e_r x e_t = e_y``.  Row j (0, 1) sits at ``y = -s row_offset`` with ``s = +1, -1``: the
back-to-back (O) arrangement, contact lines crossing the axis outside the bearing.

What the paper's equations become here (one vector form for both rows and both signs):

* Eqs. (1), (3), (15): the normal approach of each contact is the relative displacement of
  the two bodies at the contact point along the contact normal, ``n_o = cos a_o e_r +
  s sin a_o e_y`` (cup), ``n_i`` (cone, same form), ``n_a = -sin a_f e_r + s cos a_f e_y``
  (rib), less the clearance (on the cup contact) and a defect's depth ``h`` (Eq. 14: on the cup
  for an outer-ring defect, on the cone for an inner-ring one, each turning with its ring; on
  both, half a roller turn apart, for a defect on a roller, turning with its spin).
* Eq. (4a): raceway line contacts ``q(sigma) = (K / L_e) delta(sigma)^(10/9)`` integrated in
  closed form along the contact line, ``delta(sigma) = delta_0 + kappa sigma`` with the
  roller's tilt relative to the ring in kappa: the same law as Eq. (4a) for an untilted
  roller, and the tilt restoring moment the paper's Eq. (12d) lacks (slicing, done exactly).
* Eq. (4b), (8): rib point contact ``K_a delta^(3/2)`` at height h_r on the large end.
* Eq. (9)-(11): pocket walls (slope alpha_c) as line contacts along the roller, skew in kappa;
  side beams as the same law in the axial direction (the paper leaves them out; they keep the
  cage from drifting axially).
* Friction (the paper's "conventional friction model", f = mu Q): Coulomb on the slip
  velocity in the contact plane, regularised ``f = -mu Q v / sqrt(|v|^2 + v_s^2)``: raceway
  tangential and axial (f_r, f_r^a), rib (f_a), pocket (f_cr, f_cr^a).
* Damping (see :func:`_normal`): law 0, ``c = 2 zeta sqrt(m k_lin)`` with the contact's
  tangent stiffness, or law 1, the paper's ``c = c_rule K``.  The force never pulls.
* Eqs. (12), (13): Newton-Euler for each roller in polar form (centrifugal and Coriolis terms)
  and small tilt/skew with the orbiting frame's gyroscopic terms; for each cage, translation,
  small tilt and rotation.  Eq. (16): the reactions summed on the rings, with moments.
* Eq. (2): with ``KINEMATIC`` the cage turns at ``omega_c = (1 - D_b/D_m) omega_w / 2`` and each
  roller sits at its pocket centre ``2 pi (k - 1) / Z + phi_c``; otherwise the cage angle and
  every roller's azimuth are dynamic states and cage slip follows from the contacts.

IEEE arithmetic, no ``fastmath``: with it, LLVM fuses multiply-adds where the inlined callees
happen to meet, and a kernel compiled in this process and the same kernel loaded from numba's
cache differed in the last bit of some roller accelerations; the quasi-static start's 1e-12 m
difference steps and the contacts' chaos grow that to a different run (tests/test_sweep.py).
It costs 23 % of the kernel's time (6.2 against 5.0 us a call, benchmarks/README.md).
"""
from __future__ import annotations

from math import pi, sin, cos, sqrt

import numpy as np
from numba import njit

from .layout import (BETA, C_O, C_RULE, CAC, CAF, CAI, CAM, CAO, GX, GY, GZ, H_R, J_CD, J_CP, J_RA,
                     J_RD, K_A, K_CR, K_I, K_O, KINEMATIC, L_B, L_E, LAW, M_C, M_R, MU_A, MU_C,
                     MU_R, N_CAGE, N_ROLLER, R_B, R_M, RATIO, ROW, S_P, S_PA, SAC, SAF, SAI, SAM,
                     SAO, V_S, ZETA, Z)

N_LINE = 10.0 / 9.0
Z6 = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)       # no cage part in a raceway contact's gradients
N_POINT = 1.5
TWO_PI = 2.0 * pi


# --- small vector algebra on tuples --------------------------------------------------------
@njit(inline="always")
def _add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


@njit(inline="always")
def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


@njit(inline="always")
def _mul(k, a):
    return (k * a[0], k * a[1], k * a[2])


@njit(inline="always")
def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@njit(inline="always")
def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@njit(inline="always")
def _lin(ka, a, kb, b):
    return (ka * a[0] + kb * b[0], ka * a[1] + kb * b[1], ka * a[2] + kb * b[2])


# --- contact laws ---------------------------------------------------------------------------
@njit(cache=True)
def line_integrals(d0, kap, a, b, n):
    """``(int u^n ds, int s u^n ds)`` over ``[a, b]`` where ``u = d0 + kap s > 0``.

    Closed form; when the compression is nearly uniform (``|kap| (b - a) < 0.1 u_mid``) a
    Taylor series about the midpoint instead, whose first neglected terms are below about
    1e-8 of the force and of ``max|s| x force`` (the closed form loses digits there).
    """
    if b <= a:
        return 0.0, 0.0
    h = b - a
    m = 0.5 * (a + b)
    um = d0 + kap * m
    if um > 0.0 and abs(kap) * h < 0.1 * um:
        r = kap * h / um
        r2 = r * r
        pm = um ** (n - 1.0)
        f = um * pm
        i0 = h * f * (1.0 + n * (n - 1.0) / 24.0 * r2
                      + n * (n - 1.0) * (n - 2.0) * (n - 3.0) / 1920.0 * r2 * r2)
        i1 = m * i0 + n * pm * kap * h ** 3 / 12.0 * (1.0 + (n - 1.0) * (n - 2.0) / 40.0 * r2)
        return i0, i1
    ua = d0 + kap * a
    ub = d0 + kap * b
    if ua <= 0.0 and ub <= 0.0:
        return 0.0, 0.0
    if ua < 0.0:
        ua = 0.0
    if ub < 0.0:
        ub = 0.0
    n1 = n + 1.0
    n2 = n + 2.0
    pa1 = ua ** n1
    pb1 = ub ** n1
    i0 = (pb1 - pa1) / (n1 * kap)
    i1 = ((ub * pb1 - ua * pa1) / n2 - d0 * (pb1 - pa1) / n1) / (kap * kap)
    return i0, i1


@njit(cache=True)
def line_stiffness(d0, kap, a, b, n):
    """``n (int u^(n-1) ds, int s u^(n-1) ds, int s^2 u^(n-1) ds)`` over ``[a, b]`` where
    ``u = d0 + kap s > 0``: a line contact's tangent stiffness over ``K / L`` in its approach
    and tilt, ``d(int u^n, int s u^n) / d(d0, kap)`` (symmetric), for the implicit kick's blocks.

    Closed form in ``u`` (``ds = du / kap``); where the compression is nearly uniform
    (``|kap| (b - a) < 0.1 u_mid``) the midpoint expansion to first order in ``kap``, whose
    neglected terms are below ``(kap (b - a) / u_mid)^2 / 24`` of each entry: blocks of an
    iteration matrix need no more.
    """
    if b <= a:
        return 0.0, 0.0, 0.0
    h = b - a
    m = 0.5 * (a + b)
    um = d0 + kap * m
    p = n - 1.0
    if um > 0.0 and abs(kap) * h < 0.1 * um:
        g = um ** p
        j0 = h * g
        t = p * g / um * kap * h ** 3 / 12.0
        return n * j0, n * (m * j0 + t), n * (m * m * j0 + 2.0 * m * t + g * h ** 3 / 12.0)
    ua = max(d0 + kap * a, 0.0)
    ub = max(d0 + kap * b, 0.0)
    if ua == 0.0 and ub == 0.0:
        return 0.0, 0.0, 0.0
    e1 = (ub ** (p + 1.0) - ua ** (p + 1.0)) / (p + 1.0)
    e2 = (ub ** (p + 2.0) - ua ** (p + 2.0)) / (p + 2.0)
    e3 = (ub ** (p + 3.0) - ua ** (p + 3.0)) / (p + 3.0)
    return (n * e1 / kap, n * (e2 - d0 * e1) / (kap * kap),
            n * (e3 - 2.0 * d0 * e2 + d0 * d0 * e1) / (kap * kap * kap))


@njit(cache=True)
def _normal(q_el, K, n, ddot, m, P, dmax, k_imp=0.0, h_k=0.0):
    """Normal force from the elastic part ``q_el`` and the approach rate ``ddot``.

    Law 0 (default): ``c = 2 zeta sqrt(m k)`` with the contact's tangent stiffness
    ``k = n q_el / dmax`` (exact for ``q_el = K delta^n`` at uniform compression dmax; a tilted
    line contact, whose largest compression is dmax, gets a little less), i.e. the damping
    ratio zeta of the contact oscillator of mass m at its current load.  Law 1: the paper's
    ``c = c_rule K`` (below Eq. 4).  Law 2: ``c = beta k``, the paper's rule made dimensionally
    consistent (the tangent stiffness k in N/m instead of the Hertz coefficient K in N/m^n).
    Returns ``(Q, c)``: the force, and the damping coefficient acting in it (0 out of contact
    or where the force is clipped) plus ``h_k`` times the contact's tangent stiffness
    (``k_imp`` where given, a line contact's exact one, :func:`line_stiffness`; else ``k``),
    for the implicit step's blocks (:func:`_damping_rows`; ``h_k`` is 0 but under ``"imex2"``,
    bearing/implicit.py).
    """
    if q_el <= 0.0:
        return 0.0, 0.0
    if P[LAW] == 0.0:
        c = 2.0 * P[ZETA] * sqrt(m * n * q_el / dmax)
    elif P[LAW] == 1.0:
        c = P[C_RULE] * K
    else:
        c = P[BETA] * n * q_el / dmax
    q = q_el + c * ddot
    if not q > 0.0:
        return 0.0, 0.0
    # (the same expressions as before "imex2", so that its h_k = 0 leaves every bit as it was)
    if h_k == 0.0:
        return q, c
    return q, c + h_k * (k_imp if k_imp > 0.0 else n * q_el / dmax)


@njit(inline="always")
def _line_contact(i0, i1, K, L, d0, kap, ddot, m, mu, vrel, nrm, P, k_imp, h_k):
    """A line contact (Eqs. 4a, 9) from its integrals ``i0, i1`` over the line of length L:
    normal force Q, elastic couple ``m1 = (K/L) int s delta^n`` (none once Q is clipped to 0),
    the friction ``mu Q`` against the slip ``vrel``, and the coefficient for the implicit blocks
    (damping, plus ``h_k k_imp``, :func:`_normal`)."""
    dmax = d0 + 0.5 * L * abs(kap)
    Q, c = _normal(K / L * i0, K, N_LINE, ddot, m, P, dmax, k_imp, h_k)
    m1 = K / L * i1 if Q > 0.0 else 0.0
    return Q, m1, _friction(vrel, nrm, mu * Q, P[V_S]), c


@njit(inline="always")
def _tilt_rows(G, j, k, nz, kdk, kkk, Jd, Jk, Jdc, Jkc, cage):
    """A line contact's stiffness in its tilt ``kap`` (``kkk = dm1/dkap``) and between tilt and
    approach (``kdk = dQ/dkap = dm1/dd0``): ``kdk (Jd^T Jk + Jk^T Jd) + kkk Jk^T Jk`` in the
    blocks, ``Jd``/``Jk`` the gradients of the approach and of ``kap`` in the roller's rates,
    ``Jdc``/``Jkc`` in the cage's (``cage``: a pocket wall).  The cross term as the difference of
    two squares, ``(A + B)^T (A + B) - (A - B)^T (A - B) = 2 (A^T B + B^T A)``."""
    _damping_rows(G, j, k, nz, kkk, Jk, Jkc, cage)
    if kdk != 0.0:
        _damping_rows(G, j, k, nz, 0.5 * kdk, _add6(Jd, Jk, 1.0), _add6(Jdc, Jkc, 1.0), cage)
        _damping_rows(G, j, k, nz, -0.5 * kdk, _add6(Jd, Jk, -1.0), _add6(Jdc, Jkc, -1.0), cage)


@njit(inline="always")
def _add6(a, b, sb):
    return (a[0] + sb * b[0], a[1] + sb * b[1], a[2] + sb * b[2], a[3] + sb * b[3],
            a[4] + sb * b[4], a[5] + sb * b[5])


@njit(inline="always")
def _friction_rows(G, j, k, nz, muq, v, nrm, vs, t1, r, er, et, ey, ax, bx, Rr, cage, rel):
    """The friction's secant damping ``mu Q / sqrt(|v_t|^2 + v_s^2)`` in the contact plane
    (spanned by the unit ``t1`` and ``t1 x n``) on roller k's rates and, for a pocket
    (``cage``, the contact ``rel`` from the cage centre), the cage's, for the implicit kick: the
    regularised friction is stiff in the slip (the roller spin's eigenvalue near -1.3e5 1/s
    holds an explicit step under 1.5e-5 s)."""
    vn = _dot(v, nrm)
    vt = _lin(1.0, v, -vn, nrm)
    cf = muq / sqrt(_dot(vt, vt) + vs * vs)
    t2 = _cross(t1, nrm)
    for t in (t1, t2):
        _damping_rows(G, j, k, nz, cf, _rates(1.0, t, r, er, et, ey, ax, bx, Rr),
                      _cage_rates(1.0, t, rel), cage)


@njit(inline="always")
def _friction(v, nrm, muq, vs):
    """Regularised Coulomb friction on the body whose relative slip velocity is ``v``."""
    vn = _dot(v, nrm)
    vt = _lin(1.0, v, -vn, nrm)
    g = -muq / sqrt(_dot(vt, vt) + vs * vs)
    return _mul(g, vt)


@njit(inline="always")
def _rates(sd, nrm, r, er, et, ey, ax, bx, Rr):
    """Gradient of a contact's approach rate ``sd (v_roller(r) - ...) . nrm`` with respect to
    the roller's rates ``(rho', phi', eta', theta_t', theta_s', omega_s)``, for a contact at
    ``r`` from the roller centre."""
    return (sd * _dot(er, nrm), sd * (Rr * _dot(et, nrm) + _dot(_cross(ey, r), nrm)),
            sd * _dot(ey, nrm), sd * _dot(_cross(et, r), nrm), sd * _dot(_cross(bx, r), nrm),
            sd * _dot(_cross(ax, r), nrm))


@njit(inline="always")
def _cage_rates(sd, nrm, rel):
    """The same gradient with respect to the cage's rates ``(v_x, v_y, v_z, omega_x, omega_z,
    phi_c')`` for a contact at ``rel`` from the cage centre (the cage side of the contact)."""
    m = _cross(rel, nrm)
    return (-sd * nrm[0], -sd * nrm[1], -sd * nrm[2], -sd * m[0], -sd * m[2], -sd * m[1])


@njit(inline="always")
def _damping_rows(G, j, k, nz, c, Jr, Jc, cage):
    """Add the contact's damping ``c J^T J`` to row j's implicit-damping blocks: roller k's own
    ``G[j, k, :, :6]``, its coupling to the cage ``G[j, k, :, 6:]`` and the cage's own
    ``G[j, nz, :, :6]`` (a contact's damping force is ``-c J u``, u the rates)."""
    for a in range(6):
        ca = c * Jr[a]
        for b in range(6):
            G[j, k, a, b] += ca * Jr[b]
        if cage:
            for b in range(6):
                G[j, k, a, 6 + b] += ca * Jc[b]
                G[j, nz, a, b] += c * Jc[a] * Jc[b]


@njit(cache=True)
def _defect(D, kind, j, phi, theta):
    """Depth ``h`` of a defect of ``kind`` (0 outer ring, 1 inner ring) under a roller of row j
    at azimuth phi, Eq. (14), and the stretch ``[s1, s2]`` of the contact line it covers.
    Defects turn with their ring, whose rotation about the axle is ``theta``."""
    for d in range(D.shape[0]):
        if D[d, 0] != kind or D[d, 1] != j:
            continue
        x = (phi - theta - D[d, 2]) % TWO_PI
        tau = D[d, 3]
        if x < tau:
            return D[d, 4] * sin(pi * x / tau), D[d, 5], D[d, 6]
    return 0.0, 0.0, 0.0


@njit(cache=True)
def _roller_defect(D, j, k, psi):
    """Depths ``(h_cup, h_cone)`` of a defect on roller k of row j at its spin angle psi, Eq. (14)
    on the roller's surface (bearing/defects.py): under the cup within ``tau / 2`` of the
    defect's angle, under the cone half a turn on; and its stretch ``[s1, s2]`` of the line."""
    for d in range(D.shape[0]):
        if D[d, 0] != 2.0 or D[d, 1] != j or D[d, 7] != k:
            continue
        tau = D[d, 3]
        x = (psi - D[d, 2]) % TWO_PI
        h_o = D[d, 4] * sin(pi * x / tau) if x < tau else 0.0
        x = (psi + pi - D[d, 2]) % TWO_PI
        h_i = D[d, 4] * sin(pi * x / tau) if x < tau else 0.0
        return h_o, h_i, D[d, 5], D[d, 6]
    return 0.0, 0.0, 0.0, 0.0


@njit(inline="always")
def _raceway(d0, kap, h, s1, s2, Le, stiff):
    """A raceway line contact's integrals (and, when ``stiff``, its tangent stiffness over
    ``K / L``, :func:`line_stiffness`), with a defect of depth h over ``[s1, s2]`` of the line
    where ``h > 0`` (Eq. 14)."""
    kdd, kdk, kkk = 0.0, 0.0, 0.0
    if not h > 0.0:
        i0, i1 = line_integrals(d0, kap, -0.5 * Le, 0.5 * Le, N_LINE)
        if stiff and i0 > 0.0:
            kdd, kdk, kkk = line_stiffness(d0, kap, -0.5 * Le, 0.5 * Le, N_LINE)
        return i0, i1, kdd, kdk, kkk
    a0, a1 = line_integrals(d0, kap, -0.5 * Le, s1, N_LINE)
    b0, b1 = line_integrals(d0 - h, kap, s1, s2, N_LINE)
    c0, c1 = line_integrals(d0, kap, s2, 0.5 * Le, N_LINE)
    i0, i1 = a0 + b0 + c0, a1 + b1 + c1
    if stiff and i0 > 0.0:
        for d_, sa, sb in ((d0, -0.5 * Le, s1), (d0 - h, s1, s2), (d0, s2, 0.5 * Le)):
            e0, e1, e2 = line_stiffness(d_, kap, sa, sb, N_LINE)
            kdd, kdk, kkk = kdd + e0, kdk + e1, kkk + e2
    return i0, i1, kdd, kdk, kkk


@njit(cache=True)
def dtrb_rhs(t, y, ring, P, D, ydot, F, Qc):
    """State derivative ``ydot`` and ring loads ``F (2, 6)`` of one DTRB.

    ``F[0]``/``F[1]``: force (3) and moment (3) on the inner/outer ring, moments about each
    ring's centre (paper Eq. 16 plus moments).  ``Qc (2, Z, 6)``: normal contact forces
    (cup, cone, rib, pocket wall 1, pocket wall 2, side beams).
    """
    dtrb_rhs_damped(t, y, ring, P, D, ydot, F, Qc, np.empty((0, 1, 6, 12)), 0.0)


@njit(cache=True)
def dtrb_rhs_damped(t, y, ring, P, D, ydot, F, Qc, G, h_k):
    """:func:`dtrb_rhs`, and, when ``G`` has rows (``(2, Z + 1, 6, 12)``), the contacts'
    damping in the rollers' and cages' rates (:func:`_damping_rows`): ``G[j, k]`` roller k's
    own block and its coupling to the cage of row j, ``G[j, Z, :, :6]`` the cage's own, for a
    step that treats the contact damping implicitly (:mod:`.implicit`); ``h_k`` (s^2, 0 but
    under ``"imex2"``, where it is ``NEWMARK_K h`` times the kick's ``h``) puts the contacts'
    tangent stiffness in those blocks too."""
    acc = G.shape[0] > 0
    stiff = acc and h_k > 0.0                     # "imex2": the stiffness in the blocks too
    if acc:
        G[:, :, :, :] = 0.0
    nz = int(P[Z])
    R = P[R_M]
    rb = P[R_B]
    Le = P[L_E]
    Lb = P[L_B]
    cao, sao, cai, sai = P[CAO], P[SAO], P[CAI], P[SAI]
    caf, saf, cam, sam = P[CAF], P[SAF], P[CAM], P[SAM]
    cac, sac = P[CAC], P[SAC]
    Mr, Ja, Jd = P[M_R], P[J_RA], P[J_RD]
    Mc, Jcp, Jcd = P[M_C], P[J_CP], P[J_CD]
    vs = P[V_S]
    m_cage = Mr * Mc / (Mr + Mc)
    g = (P[GX], P[GY], P[GZ])
    kinematic = P[KINEMATIC] != 0.0
    # the quasi-dynamic bearing's cage (KINEMATIC 2, bearing/quasidynamic.py): rollers centred in
    # their pockets, the cage's rotation a state with the rollers' orbital inertia
    pockets = P[KINEMATIC] == 2.0
    J_orb = Jcp + nz * Mr * R * R

    # ring motion relative to the inner-ring centre
    ui = (0.0, 0.0, 0.0)
    th_i = (ring[0, 3], 0.0, ring[0, 5])
    vi = (0.0, 0.0, 0.0)
    wi = (ring[0, 9], ring[0, 10], ring[0, 11])
    uo = (ring[1, 0] - ring[0, 0], ring[1, 1] - ring[0, 1], ring[1, 2] - ring[0, 2])
    th_o = (ring[1, 3], 0.0, ring[1, 5])
    vo = (ring[1, 6] - ring[0, 6], ring[1, 7] - ring[0, 7], ring[1, 8] - ring[0, 8])
    wo = (ring[1, 9], ring[1, 10], ring[1, 11])
    theta_oy = ring[1, 4]
    theta_iy = ring[0, 4]
    n_inner = 0                                      # inner-ring and roller defects in the table
    n_roller = 0
    for d in range(D.shape[0]):
        if D[d, 0] == 1.0:
            n_inner += 1
        elif D[d, 0] == 2.0:
            n_roller += 1
    omega_w = ring[0, 10] - ring[1, 10]

    Fi = (0.0, 0.0, 0.0)
    Mi = (0.0, 0.0, 0.0)
    Fo = (0.0, 0.0, 0.0)
    Mo = (0.0, 0.0, 0.0)
    ey = (0.0, 1.0, 0.0)
    nr = 2 * nz * N_ROLLER

    for j in range(2):
        s = 1.0 if j == 0 else -1.0
        yj = -s * P[ROW]
        cb = nr + j * N_CAGE
        xc = (y[cb], y[cb + 1], y[cb + 2])
        th_c = (y[cb + 3], 0.0, y[cb + 4])
        phi_c = y[cb + 5]
        vc = (y[cb + 6], y[cb + 7], y[cb + 8])
        wcx, wcz, phid_c = y[cb + 9], y[cb + 10], y[cb + 11]
        if kinematic and not pockets:
            phid_c = P[RATIO] * omega_w
        wc = (wcx, phid_c, wcz)
        Fc = (0.0, 0.0, 0.0)
        Mcg = (0.0, 0.0, 0.0)
        orbit = 0.0                                   # the rollers' pull on the cage (pockets)
        spc, cpc = sin(phi_c), cos(phi_c)             # pocket k at phi_c + 2 pi k / Z, by rotation
        sd, cd = sin(TWO_PI / nz), cos(TWO_PI / nz)

        for k in range(nz):
            b0 = (j * nz + k) * N_ROLLER
            rho, phi, eta, tht, ths = y[b0], y[b0 + 1], y[b0 + 2], y[b0 + 3], y[b0 + 4]
            rhod, phid, etad, thtd, thsd, ws = (y[b0 + 6], y[b0 + 7], y[b0 + 8], y[b0 + 9],
                                                y[b0 + 10], y[b0 + 11])
            if kinematic:
                phi = phi_c + TWO_PI * k / nz
                phid = phid_c
                sp, cp = spc, cpc
            else:
                sp, cp = sin(phi), cos(phi)
            er = (sp, 0.0, cp)
            et = (cp, 0.0, -sp)
            ax = _lin(s * cam, ey, -sam, er)          # roller axis, large end -> small end
            bx = _lin(cam, er, s * sam, ey)           # normal to it in the axial plane
            no = _lin(cao, er, s * sao, ey)
            ni = _lin(cai, er, s * sai, ey)
            na = _lin(-saf, er, s * caf, ey)
            c = _lin(R + rho, er, yj + eta, ey)
            disp = _lin(rho, er, eta, ey)
            Vc = _add(_lin(rhod, er, (R + rho) * phid, et), _mul(etad, ey))
            wr = _add(_lin(phid, ey, ws, ax), _lin(thtd, et, thsd, bx))
            thr = _lin(tht, et, ths, bx)
            Fr = _mul(Mr, g)
            Mr_ = (0.0, 0.0, 0.0)

            # --- cup (outer raceway), Eqs. (1), (3a), (4a), (14), (15) ---
            po = _lin(1.0, c, rb, no)
            d0 = _dot(_sub(disp, _add(uo, _cross(th_o, _sub(po, uo)))), no) - P[C_O]
            kap = s * (tht - _dot(th_o, et))
            h, s1, s2 = _defect(D, 0.0, j, phi, theta_oy)
            hr_o, hr_i, r1, r2 = (0.0, 0.0, 0.0, 0.0) if n_roller == 0 else _roller_defect(D, j, k, y[b0 + 5])
            if hr_o > h:
                h, s1, s2 = hr_o, r1, r2
            i0, i1, kdd, kdk, kkk = _raceway(d0, kap, h, s1, s2, Le, stiff)
            Qo = 0.0
            if i0 > 0.0:
                vrel = _sub(_add(Vc, _cross(wr, _mul(rb, no))), _add(vo, _cross(wo, _sub(po, uo))))
                KL = P[K_O] / Le
                Qo, m1, f, cdmp = _line_contact(i0, i1, P[K_O], Le, d0, kap, _dot(vrel, no),
                                                Mr, P[MU_R], vrel, no, P, KL * kdd, h_k)
                if acc and cdmp > 0.0:
                    Jr = _rates(1.0, no, _mul(rb, no), er, et, ey, ax, bx, R + rho)
                    _damping_rows(G, j, k, nz, cdmp, Jr, Jr, False)
                    if stiff:
                        _tilt_rows(G, j, k, nz, h_k * KL * kdk, h_k * KL * kkk, Jr,
                                   (0.0, 0.0, 0.0, s, 0.0, 0.0), Z6, Z6, False)
                        _friction_rows(G, j, k, nz, P[MU_R] * Qo, vrel, no, vs, et, _mul(rb, no),
                                       er, et, ey, ax, bx, R + rho, False, ey)
                fr = _lin(-Qo, no, 1.0, f)
                Fr = _add(Fr, fr)
                Mr_ = _add(Mr_, _add(_mul(-s * m1, et), _cross(_mul(rb, no), f)))
                Fo = _sub(Fo, fr)
                Mo = _sub(Mo, _add(_cross(_sub(po, uo), fr), _mul(-s * m1, et)))

            # --- cone (inner raceway), Eqs. (1), (3b), (4a) ---
            pi_ = _lin(1.0, c, -rb, ni)
            d0 = _dot(_sub(_add(ui, _cross(th_i, pi_)), disp), ni)
            kap = s * (_dot(th_i, et) - tht)
            h, s1, s2 = (0.0, 0.0, 0.0) if n_inner == 0 else _defect(D, 1.0, j, phi, theta_iy)
            if hr_i > h:
                h, s1, s2 = hr_i, r1, r2
            i0, i1, kdd, kdk, kkk = _raceway(d0, kap, h, s1, s2, Le, stiff)
            Qi = 0.0
            if i0 > 0.0:
                vrel = _sub(_add(Vc, _cross(wr, _mul(-rb, ni))), _add(vi, _cross(wi, _sub(pi_, ui))))
                KL = P[K_I] / Le
                Qi, m1, f, cdmp = _line_contact(i0, i1, P[K_I], Le, d0, kap, -_dot(vrel, ni),
                                                Mr, P[MU_R], vrel, ni, P, KL * kdd, h_k)
                if acc and cdmp > 0.0:
                    Jr = _rates(-1.0, ni, _mul(-rb, ni), er, et, ey, ax, bx, R + rho)
                    _damping_rows(G, j, k, nz, cdmp, Jr, Jr, False)
                    if stiff:
                        _tilt_rows(G, j, k, nz, h_k * KL * kdk, h_k * KL * kkk, Jr,
                                   (0.0, 0.0, 0.0, -s, 0.0, 0.0), Z6, Z6, False)
                        _friction_rows(G, j, k, nz, P[MU_R] * Qi, vrel, ni, vs, et, _mul(-rb, ni),
                                       er, et, ey, ax, bx, R + rho, False, ey)
                fr = _lin(Qi, ni, 1.0, f)
                Fr = _add(Fr, fr)
                Mr_ = _add(Mr_, _add(_mul(s * m1, et), _cross(_mul(-rb, ni), f)))
                Fi = _sub(Fi, fr)
                Mi = _sub(Mi, _add(_cross(_sub(pi_, ui), fr), _mul(s * m1, et)))

            # --- rib of the cone on the large end, Eqs. (3c), (4b), (8) ---
            ra = _lin(-0.5 * Lb, ax, -P[H_R], bx)
            pa = _add(c, ra)
            d0 = _dot(_sub(_add(ui, _cross(th_i, pa)), _add(disp, _cross(thr, ra))), na)
            Qa = 0.0
            if d0 > 0.0:
                vrel = _sub(_add(Vc, _cross(wr, ra)), _add(vi, _cross(wi, _sub(pa, ui))))
                Qa, cdmp = _normal(P[K_A] * d0 * sqrt(d0), P[K_A], N_POINT, -_dot(vrel, na), Mr, P, d0,
                                0.0, h_k)
                if acc and cdmp > 0.0:
                    Jr = _rates(-1.0, na, ra, er, et, ey, ax, bx, R + rho)
                    _damping_rows(G, j, k, nz, cdmp, Jr, Jr, False)
                    if h_k > 0.0:
                        _friction_rows(G, j, k, nz, P[MU_A] * Qa, vrel, na, vs, et, ra, er, et,
                                       ey, ax, bx, R + rho, False, ey)
                f = _friction(vrel, na, P[MU_A] * Qa, vs)
                fr = _lin(Qa, na, 1.0, f)
                Fr = _add(Fr, fr)
                Mr_ = _add(Mr_, _cross(ra, fr))
                Fi = _sub(Fi, fr)
                Mi = _sub(Mi, _cross(_sub(pa, ui), fr))

            # --- cage pocket: walls (Eqs. 9-11) and side beams ---
            erp = (spc, 0.0, cpc)
            etp = (cpc, 0.0, -spc)
            spc, cpc = spc * cd + cpc * sd, cpc * cd - spc * sd
            P0 = _lin(R, erp, yj, ey)
            dd = _sub(c, _add(xc, _add(P0, _cross(th_c, P0))))
            skew = ths - _dot(th_c, bx)
            Qw1 = 0.0
            Qw2 = 0.0
            for w in range(2):
                sw = 1.0 if w == 0 else -1.0
                nw = _lin(sw * cac, etp, sac, erp)
                d0 = _dot(dd, nw) - P[S_P]
                kap = -sw * s * cac * skew
                i0, i1 = line_integrals(d0, kap, -0.5 * Lb, 0.5 * Lb, N_LINE)
                if i0 > 0.0:
                    kdd, kdk, kkk = 0.0, 0.0, 0.0
                    if stiff:
                        kdd, kdk, kkk = line_stiffness(d0, kap, -0.5 * Lb, 0.5 * Lb, N_LINE)
                    KL = P[K_CR] / Lb
                    pw = _lin(1.0, c, rb, nw)
                    vrel = _sub(_add(Vc, _cross(wr, _mul(rb, nw))), _add(vc, _cross(wc, _sub(pw, xc))))
                    Qw, m1, f, cdmp = _line_contact(i0, i1, P[K_CR], Lb, d0, kap, _dot(vrel, nw),
                                                    m_cage, P[MU_C], vrel, nw, P, KL * kdd, h_k)
                    if acc and cdmp > 0.0:
                        Jw = _rates(1.0, nw, _mul(rb, nw), er, et, ey, ax, bx, R + rho)
                        Jwc = _cage_rates(1.0, nw, _sub(pw, xc))
                        _damping_rows(G, j, k, nz, cdmp, Jw, Jwc, True)
                        if stiff:
                            _friction_rows(G, j, k, nz, P[MU_C] * Qw, vrel, nw, vs, ey,
                                           _mul(rb, nw), er, et, ey, ax, bx, R + rho, True,
                                           _sub(pw, xc))
                            gs = -sw * s * cac    # the skew in the pocket: kap's gradient
                            _tilt_rows(G, j, k, nz, h_k * KL * kdk, h_k * KL * kkk, Jw,
                                       (0.0, 0.0, 0.0, 0.0, gs, 0.0), Jwc,
                                       (0.0, 0.0, 0.0, -gs * bx[0], -gs * bx[2], 0.0), True)
                    fr = _lin(-Qw, nw, 1.0, f)
                    couple = _mul(m1, _cross(ax, nw))
                    Fr = _add(Fr, fr)
                    Mr_ = _add(Mr_, _sub(_cross(_mul(rb, nw), f), couple))
                    Fc = _sub(Fc, fr)
                    Mcg = _add(Mcg, _sub(couple, _cross(_sub(pw, xc), fr)))
                    if w == 0:
                        Qw1 = Qw
                    else:
                        Qw2 = Qw
            chi = dd[1]
            chid = Vc[1] - vc[1] - _cross(wc, _sub(c, xc))[1]
            Qs = 0.0
            for w in range(2):
                sw = 1.0 if w == 0 else -1.0
                d0 = sw * chi - P[S_PA]
                if d0 > 0.0:
                    Q, cdmp = _normal(P[K_CR] * d0 ** N_LINE, P[K_CR], N_LINE, sw * chid, m_cage, P, d0,
                                     0.0, h_k)
                    if acc and cdmp > 0.0:
                        _damping_rows(G, j, k, nz, cdmp,
                                      _rates(sw, ey, (0.0, 0.0, 0.0), er, et, ey, ax, bx, R + rho),
                                      _cage_rates(sw, ey, _sub(c, xc)), True)
                    fr = _mul(-sw * Q, ey)
                    pe = _lin(1.0, c, 0.5 * sw * Lb, ey)
                    Fr = _add(Fr, fr)
                    Fc = _sub(Fc, fr)
                    Mcg = _sub(Mcg, _cross(_sub(pe, xc), fr))
                    Qs += Q

            # --- Newton-Euler of the roller, Eq. (12) in polar form ---
            Rr = R + rho
            ydot[b0] = rhod
            ydot[b0 + 2] = etad
            ydot[b0 + 3] = thtd
            ydot[b0 + 4] = thsd
            ydot[b0 + 5] = ws
            ydot[b0 + 6] = _dot(Fr, er) / Mr + Rr * phid * phid
            ydot[b0 + 8] = _dot(Fr, ey) / Mr
            if kinematic:
                phidd = 0.0
                ydot[b0 + 1] = phid_c
                ydot[b0 + 7] = 0.0
                if pockets:                           # roller k's share of the cage's acceleration
                    ydot[b0 + 7] = _dot(Fr, et) * Rr / J_orb
                    orbit += ydot[b0 + 7]
            else:
                phidd = (_dot(Fr, et) / Mr - 2.0 * rhod * phid) / Rr
                ydot[b0 + 1] = phid
                ydot[b0 + 7] = phidd
            wa = ws + phid * s * cam
            # gyroscopic terms: the spinning axis turned by the orbit and by tilt/skew rates
            ydot[b0 + 9] = (_dot(Mr_, et) + Ja * wa * phid * sam - Jd * phid * phid * s * sam * cam
                            - Jd * phid * thsd * cam + s * Ja * wa * thsd) / Jd
            ydot[b0 + 10] = (_dot(Mr_, bx) - Jd * phidd * s * sam + Jd * phid * thtd * cam
                             - s * Ja * wa * thtd) / Jd
            ydot[b0 + 11] = _dot(Mr_, ax) / Ja - s * cam * phidd
            Qc[j, k, 0] = Qo
            Qc[j, k, 1] = Qi
            Qc[j, k, 2] = Qa
            Qc[j, k, 3] = Qw1
            Qc[j, k, 4] = Qw2
            Qc[j, k, 5] = Qs

        # --- the cage, Eq. (13) ---
        for q in range(3):
            ydot[cb + q] = y[cb + 6 + q]
            ydot[cb + 6 + q] = Fc[q] / Mc + g[q]
        ydot[cb + 3] = wcx
        ydot[cb + 4] = wcz
        ydot[cb + 9] = (Mcg[0] + Jcp * phid_c * wcz) / Jcd
        ydot[cb + 10] = (Mcg[2] - Jcp * phid_c * wcx) / Jcd
        ydot[cb + 5] = phid_c
        if pockets:
            ydot[cb + 11] = Mcg[1] / J_orb + orbit
        else:
            ydot[cb + 11] = 0.0 if kinematic else Mcg[1] / Jcp

    for q in range(3):
        F[0, q] = Fi[q]
        F[0, 3 + q] = Mi[q]
        F[1, q] = Fo[q]
        F[1, 3 + q] = Mo[q]
