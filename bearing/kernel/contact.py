"""Contact laws of a roller bearing (numba): the line contact along a roller (paper Eqs. 4a, 9)
integrated in closed form, the point contact (Eqs. 4b, 8), the damping laws, regularised
Coulomb friction, and a contact's load on the two bodies it joins.

A contact is described the same way whatever it joins (a raceway, a rib, a pocket wall): its
unit normal ``n`` pointing from the roller to the other body, the relative velocity ``v`` of the
roller's material point against the other body's there, and the normal approach ``delta``
(with, for a line contact, the tilt ``kap`` of the approach along the line).  The normal force
pushes the roller back, ``-Q n``; friction opposes the slip ``v`` in the contact plane; the
contact's load goes into the roller's record (:func:`load`).
"""
from __future__ import annotations

from math import sqrt

from axlebox._numba import kernel

from .layout import BETA, C_FORCE, C_LOAD, C_MOMENT, C_RULE, LAW, REC_F, REC_LOAD, REC_M, ZETA
from .vec import acc, dot, lin, mul, put

N_LINE = 10.0 / 9.0          # Palmgren's line contact, Q = K delta^(10/9) (Eq. 4a)
N_POINT = 1.5                # Hertz's point contact, Q = K delta^(3/2) (Eq. 4b)


@kernel
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


@kernel
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


@kernel
def normal(q_el, K, n, ddot, m, P, dmax, k_imp, h_k):
    """Normal force from the elastic part ``q_el`` and the approach rate ``ddot``.

    Law 0 (default): ``c = 2 zeta sqrt(m k)`` with the contact's tangent stiffness
    ``k = n q_el / dmax`` (exact for ``q_el = K delta^n`` at uniform compression dmax; a tilted
    line contact, whose largest compression is dmax, gets a little less), i.e. the damping
    ratio zeta of the contact oscillator of mass m at its current load.  Law 1: the paper's
    ``c = c_rule K`` (below Eq. 4).  Law 2: ``c = beta k``, the paper's rule made dimensionally
    consistent (the tangent stiffness k in N/m instead of the Hertz coefficient K in N/m^n).
    Returns ``(Q, c)``: the force (it never pulls), and the damping coefficient acting in it
    (0 out of contact or where the force is clipped) plus ``h_k`` times the contact's tangent
    stiffness (``k_imp`` where given, a line contact's exact one, :func:`line_stiffness`; else
    ``k``), for the implicit step's blocks (``h_k`` is 0 but under ``"imex2"``,
    bearing/kernel/implicit.py).
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
    if h_k == 0.0:
        return q, c
    return q, c + h_k * (k_imp if k_imp > 0.0 else n * q_el / dmax)


@kernel
def line_load(i0, i1, K, L, d0, kap, ddot, m, P, k_imp, h_k):
    """A line contact (Eqs. 4a, 9) from its integrals ``i0, i1`` over the line of length L:
    ``(Q, m1, c)``, the normal force, the elastic couple ``m1 = (K/L) int s delta^n`` (none once
    Q is clipped to 0) and the coefficient for the implicit blocks (damping, plus ``h_k k_imp``,
    :func:`normal`)."""
    dmax = d0 + 0.5 * L * abs(kap)
    Q, c = normal(K / L * i0, K, N_LINE, ddot, m, P, dmax, k_imp, h_k)
    return Q, (K / L * i1 if Q > 0.0 else 0.0), c


@kernel
def friction(v, n, muq, vs):
    """Regularised Coulomb friction ``-mu Q v_t / sqrt(|v_t|^2 + v_s^2)`` on the body whose slip
    velocity is ``v`` (``v_t`` its part in the contact plane of normal ``n``)."""
    vn = dot(v, n)
    vt = lin(1.0, v, -vn, n)
    g = -muq / sqrt(dot(vt, vt) + vs * vs)
    return mul(g, vt)


@kernel
def slip_damping(v, n, muq, vs):
    """The friction's secant damping ``mu Q / sqrt(|v_t|^2 + v_s^2)`` (:func:`friction`'s
    coefficient on the slip), for the implicit blocks."""
    vn = dot(v, n)
    vt = lin(1.0, v, -vn, n)
    return muq / sqrt(dot(vt, vt) + vs * vs)


@kernel
def load(rec, c, fr, m_roller, m_body):
    """A contact's load in the roller's record ``rec``: the force ``fr`` and the moment
    ``m_roller`` on the roller, and in its slot ``c`` (:data:`.layout.C_OUTER` ...) what it adds
    to the other body, ``-fr`` and the moment ``m_body`` about that body's centre."""
    acc(rec, REC_F, fr)
    acc(rec, REC_M, m_roller)
    o = REC_LOAD + C_LOAD * c
    put(rec, o + C_FORCE, mul(-1.0, fr))
    put(rec, o + C_MOMENT, m_body)
