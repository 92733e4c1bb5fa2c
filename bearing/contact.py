"""The DTRB's contacts (numba, inlined into bearing/kernel.py): small vector algebra on
3-tuples, the line and point contact laws (paper Eqs. 4a, 4b, 9), friction, the Eq. (14)
defects under a contact, and the rows the implicit steps take (a contact's damping, tangent
stiffness and friction in the rollers' and cages' rates).  What each law becomes is told in
bearing/kernel.py's docstring."""
from __future__ import annotations

from math import pi, sin, sqrt

from numba import njit

from .layout import BETA, C_RULE, LAW, V_S, ZETA

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
    if um != um:            # NaN, a diverged state: passed on to the integrator's finite check
        return um, um       # (the closed form below would divide by a zero kap)
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
    if um != um:            # NaN: as line_integrals
        return um, um, um
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
def _tilt_rows(G, j, k, nz, kdk, kkk, Jd, Jk, Jdc, Jkc, cage, qd):
    """A line contact's stiffness in its tilt ``kap`` (``kkk = dm1/dkap``) and between tilt and
    approach (``kdk = dQ/dkap = dm1/dd0``): ``kdk (Jd^T Jk + Jk^T Jd) + kkk Jk^T Jk`` in the
    blocks, ``Jd``/``Jk`` the gradients of the approach and of ``kap`` in the roller's rates,
    ``Jdc``/``Jkc`` in the cage's (``cage``: a pocket wall).  The cross term as the difference of
    two squares, ``(A + B)^T (A + B) - (A - B)^T (A - B) = 2 (A^T B + B^T A)``."""
    _damping_rows(G, j, k, nz, kkk, Jk, Jkc, cage, qd)
    if kdk != 0.0:
        _damping_rows(G, j, k, nz, 0.5 * kdk, _add6(Jd, Jk, 1.0), _add6(Jdc, Jkc, 1.0), cage, qd)
        _damping_rows(G, j, k, nz, -0.5 * kdk, _add6(Jd, Jk, -1.0), _add6(Jdc, Jkc, -1.0), cage,
                      qd)


@njit(inline="always")
def _add6(a, b, sb):
    return (a[0] + sb * b[0], a[1] + sb * b[1], a[2] + sb * b[2], a[3] + sb * b[3],
            a[4] + sb * b[4], a[5] + sb * b[5])


@njit(inline="always")
def _friction_rows(G, j, k, nz, muq, v, nrm, vs, t1, r, er, et, ey, ax, bx, Rr, cage, rel, qd):
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
                      _cage_rates(1.0, t, rel), cage, qd)


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
def _damping_rows(G, j, k, nz, c, Jr, Jc, cage, qd):
    """Add the contact's damping ``c J^T J`` to row j's implicit-damping blocks: roller k's own
    ``G[j, k, :, :6]``, its coupling to the cage ``G[j, k, :, 6:]`` and the cage's own
    ``G[j, nz, :, :6]`` (a contact's damping force is ``-c J u``, u the rates).  With ``qd``
    only the entries the quasi-dynamic step reads (:func:`_qd_rows`)."""
    if qd:
        _qd_rows(G, j, k, nz, c, Jr, Jc, cage)
        return
    for a in range(6):
        ca = c * Jr[a]
        for b in range(6):
            G[j, k, a, b] += ca * Jr[b]
        if cage:
            for b in range(6):
                G[j, k, a, 6 + b] += ca * Jc[b]
                G[j, nz, a, b] += c * Jc[a] * Jc[b]


@njit(inline="always")
def _qd_rows(G, j, k, nz, c, Jr, Jc, cage):
    """:func:`_damping_rows`' entries that bearing/quasidynamic.py reads, 16 of 108, each
    computed as there (the same bits): the block of ``(rho, eta, theta_t)`` for its Newton, and
    of the orbit and spin rates ``(phi', omega_s)`` with the cage's rotation for its spin step
    (the roller's orbit rate is the cage's there).  Writing the other entries cost 40 % of an
    evaluation (benchmarks/README.md)."""
    for a in (0, 2, 3):
        ca = c * Jr[a]
        G[j, k, a, 0] += ca * Jr[0]
        G[j, k, a, 2] += ca * Jr[2]
        G[j, k, a, 3] += ca * Jr[3]
    for a in (1, 5):
        ca = c * Jr[a]
        G[j, k, a, 1] += ca * Jr[1]
        G[j, k, a, 5] += ca * Jr[5]
        if cage:
            G[j, k, a, 11] += ca * Jc[5]
    if cage:
        G[j, nz, 5, 5] += c * Jc[5] * Jc[5]


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
            return _depth(D, d, x, tau), D[d, 5], D[d, 6]
    return 0.0, 0.0, 0.0


@njit(inline="always")
def _depth(D, d, x, tau):
    """Depth of ring defect d at ``x`` rad into its window: Eq. (14)'s half-sine, or (``rho``
    > 0) the roller's centre path over the two rounded edges (bearing/defects.py)."""
    rho = D[d, 8]
    if rho == 0.0:
        return D[d, 4] * sin(pi * x / tau)
    e = min(x, tau - x) * D[d, 10] - D[d, 9]       # past the nearer edge's pivot (m)
    if e <= 0.0:
        return 0.0
    return min(D[d, 4], e * e / (rho + sqrt(rho * rho - e * e)))   # rho - sqrt(..), no cancellation


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


