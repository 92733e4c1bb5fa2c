"""Plain-numpy twin of the DTRB's numba right-hand side (bearing/kernel/evaluate.py with
bearing/models/dtrb.py:
the same equations, vectorised over rollers): the baseline for benchmarks/bearing.py and a
cross-check of the numba kernels.

Vectors are arrays ``(3, ...)``: the component first, then the (row, roller) axes, so that
``k * a`` with ``k (n, Z)`` scales a vector field and ring or cage vectors ``(3, 1, 1)`` /
``(3, n, 1)`` broadcast against roller vectors ``(3, n, Z)``, n the rows.  The row sign ``s`` is
``(n, 1)``.
"""
from __future__ import annotations

import numpy as np

from ..models.dtrb import C_O, CAF, CAI, CAO, H_R, K_A, K_I, K_O, L_E, MU_A, MU_R, SAF, SAI, SAO
from .layout import (BETA, CAC, CAM, CPHI, CTX, CTZ, CX, C_RULE, D_DEPTH, D_EDGE, D_KIND, D_RADIUS, D_RHO,
                     D_ROLLER, D_ROW, D_S1, D_S2, D_START, D_TAU, EQ2_CAGE, ETA, FREE_CAGE, G_X, G_Y, G_Z,
                     INNER, INNER_RING, J_CD, J_CP, J_RA, J_RD, KINEMATIC, K_CR, LAW, LOAD, L_B, MU_C, M_C,
                     M_R, N_CAGE, N_Q, N_ROLLER, OUTER, OUTER_RING, PHI, POCKET_CAGE, PSI, Q_A, Q_CR1,
                     Q_CR2, Q_I, Q_O, Q_SIDE, RATE, RATIO, RHO, RINGS, ROLLER_SURFACE, ROW, N_ROWS, R_B, R_M,
                     SAC, SAM, S_P, S_PA, TH_S, TH_T, TH_X, TH_Y, TH_Z, U_X, U_Z, V_S, V_X, V_Z, W_X, W_Y,
                     W_Z, Z, ZETA, row_sign, row_y)
from .vec import AX, AY, AZ

N_LINE = 10.0 / 9.0
N_POINT = 1.5
TWO_PI = 2.0 * np.pi
EY = np.array([0.0, 1.0, 0.0]).reshape(3, 1, 1)


def _dot(a, b):
    return a[AX] * b[AX] + a[AY] * b[AY] + a[AZ] * b[AZ]


def _cross(a, b):
    return np.stack(np.broadcast_arrays(a[AY] * b[AZ] - a[AZ] * b[AY], a[AZ] * b[AX] - a[AX] * b[AZ],
                                        a[AX] * b[AY] - a[AY] * b[AX]))


def _vec(x, y, z):
    """A vector field from three broadcastable components."""
    return np.stack(np.broadcast_arrays(x, y, z))


def line_integrals_numpy(d0, kap, a, b, n):
    """Vectorised :func:`axlebox.bearing.kernel.contact.line_integrals`: ``(int u^n ds, int s u^n ds)`` over
    ``[a, b]``, ``u = max(d0 + kap s, 0)``, with the same Taylor / closed-form branches."""
    d0, kap, a, b = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (d0, kap, a, b)))
    h = b - a
    m = 0.5 * (a + b)
    um = d0 + kap * m
    taylor = (um > 0.0) & (np.abs(kap) * h < 0.1 * um)
    # Taylor series about the midpoint (nearly uniform compression)
    ums = np.where(taylor, um, 1.0)
    r2 = (kap * h / ums) ** 2
    t0 = h * ums ** n * (1.0 + n * (n - 1.0) / 24.0 * r2
                         + n * (n - 1.0) * (n - 2.0) * (n - 3.0) / 1920.0 * r2 * r2)
    t1 = m * t0 + n * ums ** (n - 1.0) * kap * h ** 3 / 12.0 * (1.0 + (n - 1.0) * (n - 2.0) / 40.0 * r2)
    # closed form on the compressed part (zero where u <= 0 all along; kap = 0 lands in Taylor)
    ua = np.maximum(d0 + kap * a, 0.0)
    ub = np.maximum(d0 + kap * b, 0.0)
    ks = np.where(kap == 0.0, 1.0, kap)
    n1, n2 = n + 1.0, n + 2.0
    pa1, pb1 = ua ** n1, ub ** n1
    c0 = (pb1 - pa1) / (n1 * ks)
    c1 = ((ub * pb1 - ua * pa1) / n2 - d0 * (pb1 - pa1) / n1) / (ks * ks)
    off = (b <= a) | (~taylor & (ua <= 0.0) & (ub <= 0.0))
    return (np.where(off, 0.0, np.where(taylor, t0, c0)),
            np.where(off, 0.0, np.where(taylor, t1, c1)))


def _normal(q_el, K, n, ddot, m, P, dmax):
    """Normal force from the elastic part ``q_el``, the approach rate ``ddot`` and the largest
    compression ``dmax`` (see contact.normal)."""
    on = q_el > 0.0
    k = n * np.where(on, q_el / np.where(on, dmax, 1.0), 0.0)      # tangent stiffness
    if P[LAW] == 0.0:
        c = 2.0 * P[ZETA] * np.sqrt(m * k)
    elif P[LAW] == 1.0:
        c = P[C_RULE] * K
    else:
        c = P[BETA] * k
    return np.where(on, np.maximum(q_el + c * ddot, 0.0), 0.0)


def _line_contact(i0, i1, K, L, d0, kap, ddot, m, mu, vrel, nrm, P):
    """Normal force, elastic couple and friction of a line contact (see contact.line_load)."""
    Q = _normal(K / L * i0, K, N_LINE, ddot, m, P, d0 + 0.5 * L * np.abs(kap))
    return Q, np.where(Q > 0.0, K / L * i1, 0.0), _friction(vrel, nrm, mu * Q, P[V_S])


def _friction(v, nrm, muq, vs):
    """Regularised Coulomb friction on the body whose relative slip velocity is ``v``."""
    vt = v - _dot(v, nrm) * nrm
    return -muq / np.sqrt(_dot(vt, vt) + vs * vs) * vt


def _defect(D, kind, phi, theta):
    """``(h, s1, s2)`` per roller, Eq. (14): the first defect of ``kind`` (0 outer, 1 inner ring)
    on each roller's row, turning with its ring (rotation ``theta``)."""
    h, s1, s2 = np.zeros_like(phi), np.zeros_like(phi), np.zeros_like(phi)
    found = np.zeros(phi.shape, dtype=bool)
    row = np.arange(phi.shape[0])[:, None]
    for d in D:
        if d[D_KIND] != kind:
            continue
        x = np.mod(phi - theta - d[D_START], TWO_PI)
        tau = d[D_TAU]
        hit = ~found & (row == d[D_ROW]) & (x < tau)
        if d[D_RHO] == 0.0:                          # Eq. (14)'s half-sine
            depth = d[D_DEPTH] * np.sin(np.pi * x / tau)
        else:                                        # over the rounded edges (bearing/defects.py)
            rho = d[D_RHO]
            e = np.maximum(np.minimum(x, tau - x) * d[D_RADIUS] - d[D_EDGE], 0.0)
            depth = np.minimum(d[D_DEPTH], e * e / (rho + np.sqrt(np.maximum(rho * rho - e * e, 0.0))))
        h = np.where(hit, depth, h)
        s1 = np.where(hit, d[D_S1], s1)
        s2 = np.where(hit, d[D_S2], s2)
        found |= hit
    return h, s1, s2


def _roller_defect(D, psi):
    """``(h_cup, h_cone, s1, s2)`` per roller from the table's roller defects, turning with each
    roller's spin angle psi (see defects.roller_depths)."""
    ho, hi, s1, s2 = (np.zeros_like(psi) for _ in range(4))
    row = np.arange(psi.shape[0])[:, None]
    k = np.arange(psi.shape[1])[None, :]
    for d in D:
        if d[D_KIND] != ROLLER_SURFACE:
            continue
        on = (row == d[D_ROW]) & (k == d[D_ROLLER])
        tau = d[D_TAU]
        xo = np.mod(psi - d[D_START], TWO_PI)
        xi = np.mod(psi + np.pi - d[D_START], TWO_PI)
        ho = np.where(on & (xo < tau), d[D_DEPTH] * np.sin(np.pi * xo / tau), ho)
        hi = np.where(on & (xi < tau), d[D_DEPTH] * np.sin(np.pi * xi / tau), hi)
        s1 = np.where(on, d[D_S1], s1)
        s2 = np.where(on, d[D_S2], s2)
    return ho, hi, s1, s2


def _deeper(ring, roller):
    """Of a ring's defect ``(h, s1, s2)`` and a roller's at the same contact, the deeper."""
    (h_ring, _, _), (h_roller, _, _) = ring, roller
    use = h_roller > h_ring
    return tuple(np.where(use, b, a) for a, b in zip(ring, roller))


def _raceway(d0, kap, h, s1, s2, Le):
    """A raceway line contact's integrals, with a defect of depth h (> 0) over ``[s1, s2]``."""
    i0, i1 = line_integrals_numpy(d0, kap, -0.5 * Le, 0.5 * Le, N_LINE)
    dent = h > 0.0
    if dent.any():
        a0, a1 = line_integrals_numpy(d0, kap, -0.5 * Le, s1, N_LINE)
        b0, b1 = line_integrals_numpy(d0 - h, kap, s1, s2, N_LINE)
        e0, e1 = line_integrals_numpy(d0, kap, s2, 0.5 * Le, N_LINE)
        i0 = np.where(dent, a0 + b0 + e0, i0)
        i1 = np.where(dent, a1 + b1 + e1, i1)
    return i0, i1


def dtrb_rhs_numpy(t, y, ring, P, D) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(ydot, F (RINGS, LOAD), Qc (n, Z, N_Q))`` as bearing/kernel/evaluate.py's ``evaluate``
    writes them."""
    nz = int(P[Z])
    R, rb, Le, Lb = P[R_M], P[R_B], P[L_E], P[L_B]
    cao, sao, cai, sai = P[CAO], P[SAO], P[CAI], P[SAI]
    caf, saf, cam, sam = P[CAF], P[SAF], P[CAM], P[SAM]
    cac, sac = P[CAC], P[SAC]
    Mr, Ja, Jd = P[M_R], P[J_RA], P[J_RD]
    Mc, Jcp, Jcd = P[M_C], P[J_CP], P[J_CD]
    vs = P[V_S]
    m_cage = Mr * Mc / (Mr + Mc)
    g = np.array([P[G_X], P[G_Y], P[G_Z]])
    kinematic = P[KINEMATIC] != FREE_CAGE
    pockets = P[KINEMATIC] == POCKET_CAGE         # the quasi-dynamic bearing's cage (roller.py)
    J_orb = Jcp + nz * Mr * R * R
    nrow = int(P[N_ROWS])
    nr = nrow * nz * N_ROLLER
    rol = y[:nr].reshape(nrow, nz, N_ROLLER)
    cag = y[nr:nr + nrow * N_CAGE].reshape(nrow, N_CAGE)

    # rings relative to the inner-ring centre (ui = vi = 0)
    th_i = np.array([ring[INNER, TH_X], 0.0, ring[INNER, TH_Z]]).reshape(3, 1, 1)
    wi = ring[INNER, W_X:W_Z + 1].reshape(3, 1, 1)
    uo = (ring[OUTER, U_X:U_Z + 1] - ring[INNER, U_X:U_Z + 1]).reshape(3, 1, 1)
    th_o = np.array([ring[OUTER, TH_X], 0.0, ring[OUTER, TH_Z]]).reshape(3, 1, 1)
    vo = (ring[OUTER, V_X:V_Z + 1] - ring[INNER, V_X:V_Z + 1]).reshape(3, 1, 1)
    wo = ring[OUTER, W_X:W_Z + 1].reshape(3, 1, 1)
    theta_oy = ring[OUTER, TH_Y]
    omega_w = ring[INNER, W_Y] - ring[OUTER, W_Y]

    s = np.array([[row_sign(j, nrow)] for j in range(nrow)])           # each row's sign, place
    yj = np.array([[row_y(j, nrow, P[ROW])] for j in range(nrow)])
    pocket = TWO_PI * np.arange(nz) / nz

    # cages (3, n, 1)
    xc = cag[:, CX:CX + 3].T[:, :, None]
    th_c = _vec(cag[:, CTX], 0.0, cag[:, CTZ])[:, :, None]
    phi_c = cag[:, CPHI][:, None]
    vc = cag[:, RATE + CX:RATE + CX + 3].T[:, :, None]
    wcx, wcz, phid_c = cag[:, RATE + CTX], cag[:, RATE + CTZ], cag[:, RATE + CPHI]
    if P[KINEMATIC] == EQ2_CAGE:
        phid_c = np.full(nrow, P[RATIO] * omega_w)
    wc = _vec(wcx, phid_c, wcz)[:, :, None]

    # rollers (n, Z)
    rho, phi, eta, tht, ths = (rol[..., q] for q in (RHO, PHI, ETA, TH_T, TH_S))
    rhod, phid, etad, thtd, thsd, ws = (rol[..., RATE + q] for q in (RHO, PHI, ETA, TH_T, TH_S, PSI))
    if kinematic:
        phi = phi_c + pocket
        phid = np.broadcast_to(phid_c[:, None], phi.shape)
    sp, cp = np.sin(phi), np.cos(phi)
    er = _vec(sp, 0.0, cp)
    et = _vec(cp, 0.0, -sp)
    ax = s * cam * EY - sam * er                      # roller axis, large end -> small end
    bx = cam * er + s * sam * EY
    no = cao * er + s * sao * EY
    ni = cai * er + s * sai * EY
    na = -saf * er + s * caf * EY
    c = (R + rho) * er + (yj + eta) * EY
    disp = rho * er + eta * EY
    Vc = rhod * er + (R + rho) * phid * et + etad * EY
    wr = phid * EY + ws * ax + thtd * et + thsd * bx
    thr = tht * et + ths * bx
    Fr = np.zeros((3, 2, nz)) + Mr * g[:, None, None]
    Mr_ = np.zeros((3, 2, nz))

    # --- cup, Eqs. (1), (3a), (4a), (14), (15) ---
    po = c + rb * no
    d0 = _dot(disp - (uo + _cross(th_o, po - uo)), no) - P[C_O]
    kap = s * (tht - _dot(th_o, et))
    ho_r, hi_r, r1, r2 = _roller_defect(D, rol[..., PSI])
    i0, i1 = _raceway(d0, kap, *_deeper(_defect(D, OUTER_RING, phi, theta_oy), (ho_r, r1, r2)), Le)
    vrel = Vc + _cross(wr, rb * no) - (vo + _cross(wo, po - uo))
    Qo, m1, f = _line_contact(i0, i1, P[K_O], Le, d0, kap, _dot(vrel, no), Mr, P[MU_R],
                               vrel, no, P)
    fr = -Qo * no + f
    Fr += fr
    Mr_ += -s * m1 * et + _cross(rb * no, f)
    Fo = -fr.sum(axis=(1, 2))
    Mo = -(_cross(po - uo, fr) - s * m1 * et).sum(axis=(1, 2))

    # --- cone, Eqs. (1), (3b), (4a) ---
    pi_ = c - rb * ni
    d0 = _dot(_cross(th_i, pi_) - disp, ni)
    kap = s * (_dot(th_i, et) - tht)
    i0, i1 = _raceway(d0, kap, *_deeper(_defect(D, INNER_RING, phi, ring[INNER, TH_Y]), (hi_r, r1, r2)), Le)
    vrel = Vc + _cross(wr, -rb * ni) - _cross(wi, pi_)
    Qi, m1, f = _line_contact(i0, i1, P[K_I], Le, d0, kap, -_dot(vrel, ni), Mr, P[MU_R],
                               vrel, ni, P)
    fr = Qi * ni + f
    Fr += fr
    Mr_ += s * m1 * et + _cross(-rb * ni, f)
    Fi = -fr.sum(axis=(1, 2))
    Mi = -(_cross(pi_, fr) + s * m1 * et).sum(axis=(1, 2))

    # --- rib on the large end, Eqs. (3c), (4b), (8) ---
    ra = -0.5 * Lb * ax - P[H_R] * bx
    pa = c + ra
    d0 = _dot(_cross(th_i, pa) - (disp + _cross(thr, ra)), na)
    vrel = Vc + _cross(wr, ra) - _cross(wi, pa)
    dp = np.maximum(d0, 0.0)
    Qa = _normal(P[K_A] * dp * np.sqrt(dp), P[K_A], N_POINT, -_dot(vrel, na), Mr, P, d0)
    f = _friction(vrel, na, P[MU_A] * Qa, vs)
    fr = Qa * na + f
    Fr += fr
    Mr_ += _cross(ra, fr)
    Fi -= fr.sum(axis=(1, 2))
    Mi -= _cross(pa, fr).sum(axis=(1, 2))

    # --- cage pocket walls (Eqs. 9-11) and side beams ---
    php = phi_c + pocket
    erp = _vec(np.sin(php), 0.0, np.cos(php))
    etp = _vec(np.cos(php), 0.0, -np.sin(php))
    P0 = R * erp + yj * EY
    dd = c - (xc + P0 + _cross(th_c, P0))
    skew = ths - _dot(th_c, bx)
    Fc = np.zeros((3, 2))
    Mcg = np.zeros((3, 2))
    Qw = []
    for sw in (1.0, -1.0):
        nw = sw * cac * etp + sac * erp
        d0 = _dot(dd, nw) - P[S_P]
        kap = -sw * s * cac * skew
        i0, i1 = line_integrals_numpy(d0, kap, -0.5 * Lb, 0.5 * Lb, N_LINE)
        pw = c + rb * nw
        vrel = Vc + _cross(wr, rb * nw) - (vc + _cross(wc, pw - xc))
        Q, m1, f = _line_contact(i0, i1, P[K_CR], Lb, d0, kap, _dot(vrel, nw), m_cage, P[MU_C],
                                  vrel, nw, P)
        fr = -Q * nw + f
        couple = m1 * _cross(ax, nw)
        Fr += fr
        Mr_ += _cross(rb * nw, f) - couple
        Fc -= fr.sum(axis=2)
        Mcg += (couple - _cross(pw - xc, fr)).sum(axis=2)
        Qw.append(Q)
    chi = dd[AY]
    chid = Vc[AY] - vc[AY] - _cross(wc, c - xc)[AY]
    Qs = np.zeros_like(chi)
    for sw in (1.0, -1.0):
        d0 = sw * chi - P[S_PA]
        Q = _normal(P[K_CR] * np.maximum(d0, 0.0) ** N_LINE, P[K_CR], N_LINE, sw * chid, m_cage, P, d0)
        fr = -sw * Q * EY
        pe = c + 0.5 * sw * Lb * EY
        Fr += fr
        Fc -= fr.sum(axis=2)
        Mcg -= _cross(pe - xc, fr).sum(axis=2)
        Qs = Qs + Q

    # --- Newton-Euler of the rollers, Eq. (12) in polar form ---
    ydot = np.zeros(nr + nrow * N_CAGE)
    yr = ydot[:nr].reshape(nrow, nz, N_ROLLER)
    yc = ydot[nr:].reshape(nrow, N_CAGE)
    Rr = R + rho
    for q, v in ((RHO, rhod), (ETA, etad), (TH_T, thtd), (TH_S, thsd), (PSI, ws), (PHI, phid)):
        yr[..., q] = v
    yr[..., RATE + RHO] = _dot(Fr, er) / Mr + Rr * phid * phid
    yr[..., RATE + ETA] = Fr[AY] / Mr
    if kinematic:
        phidd = np.zeros_like(rho)
        yr[..., RATE + PHI] = _dot(Fr, et) * Rr / J_orb if pockets else 0.0
    else:
        phidd = (_dot(Fr, et) / Mr - 2.0 * rhod * phid) / Rr
        yr[..., RATE + PHI] = phidd
    wa = ws + phid * s * cam
    yr[..., RATE + TH_T] = (_dot(Mr_, et) + Ja * wa * phid * sam - Jd * phid * phid * s * sam * cam
                            - Jd * phid * thsd * cam + s * Ja * wa * thsd) / Jd
    yr[..., RATE + TH_S] = (_dot(Mr_, bx) - Jd * phidd * s * sam + Jd * phid * thtd * cam
                            - s * Ja * wa * thtd) / Jd
    yr[..., RATE + PSI] = _dot(Mr_, ax) / Ja - s * cam * phidd

    # --- the cages, Eq. (13) ---
    yc[:, CX:CX + 3] = cag[:, RATE + CX:RATE + CX + 3]
    yc[:, RATE + CX:RATE + CX + 3] = Fc.T / Mc + g
    yc[:, CTX], yc[:, CTZ], yc[:, CPHI] = wcx, wcz, phid_c
    Mc_x, Mc_y, Mc_z = Mcg
    yc[:, RATE + CTX] = (Mc_x + Jcp * phid_c * wcz) / Jcd
    yc[:, RATE + CTZ] = (Mc_z - Jcp * phid_c * wcx) / Jcd
    if pockets:
        yc[:, RATE + CPHI] = Mc_y / J_orb + yr[..., RATE + PHI].sum(axis=1)
    else:
        yc[:, RATE + CPHI] = 0.0 if kinematic else Mc_y / Jcp

    F = np.zeros((RINGS, LOAD))
    F[INNER] = np.concatenate([Fi, Mi])
    F[OUTER] = np.concatenate([Fo, Mo])
    Qc = np.zeros((nrow, nz, N_Q))
    Qw1, Qw2 = Qw
    for q, v in ((Q_O, Qo), (Q_I, Qi), (Q_A, Qa), (Q_CR1, Qw1), (Q_CR2, Qw2), (Q_SIDE, Qs)):
        Qc[..., q] = v
    return ydot, F, Qc
