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

from math import sin, cos, sqrt

import numpy as np
from numba import njit

from .contact import (N_LINE, N_POINT, TWO_PI, Z6, _add, _cage_rates, _cross, _damping_rows,
                      _defect, _dot, _friction, _friction_rows, _lin, _line_contact, _mul,
                      _normal, _raceway, _rates, _roller_defect, _sub, _tilt_rows, line_integrals,
                      line_stiffness)
from .layout import (C_O, CAC, CAF, CAI, CAM, CAO, GX, GY, GZ, H_R, J_CD, J_CP, J_RA, J_RD, K_A,
                     K_CR, K_I, K_O, KINEMATIC, L_B, L_E, M_C, M_R, MU_A, MU_C, MU_R, N_CAGE,
                     N_ROLLER, R_B, R_M, RATIO, ROW, S_P, S_PA, SAC, SAF, SAI, SAM, SAO, V_S, Z)

__all__ = ["dtrb_rhs", "dtrb_rhs_damped", "dtrb_rhs_part", "line_integrals", "line_stiffness"]

# a roller's share of the loads (dtrb_rhs_part's ``parts``): on the inner ring (force, moment),
# on the outer ring, on the cage (force, moment), its pull on a quasi-dynamic cage's rotation, and
# its entry in the cage's block of the rotation
N_PART = 20


@njit(inline="always")
def _share(out, o, v, v0):
    for a in range(3):
        out[o + a] = v[a] - v0[a]


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
    damping in the rollers' and cages' rates (:func:`.contact._damping_rows`): ``G[j, k]``
    roller k's own block and its coupling to the cage of row j, ``G[j, Z, :, :6]`` the cage's
    own, for a step that treats the contact damping implicitly (:mod:`.implicit`); ``h_k`` (s^2,
    0 but under ``"imex2"``, where it is ``NEWMARK_K h`` times the kick's ``h``) puts the
    contacts' tangent stiffness in those blocks too."""
    dtrb_rhs_part(t, y, ring, P, D, ydot, F, Qc, G, h_k, None, None)


@njit(cache=True)
def dtrb_rhs_part(t, y, ring, P, D, ydot, F, Qc, G, h_k, active, parts):
    """:func:`dtrb_rhs_damped` for some rollers only, for a solver that moves them one by one
    (the quasi-dynamic bearing's Newton, bearing/quasidynamic.py).  ``parts`` (2, Z,
    :data:`N_PART`), unless None, gets each evaluated roller's share of the loads on the
    rings and the cage (:data:`N_PART`); ``active`` (2 Z), unless None, says which
    rollers to evaluate (nonzero): the others keep their rows of ``ydot``, ``Qc`` and ``G``
    and put their stored ``parts`` into the sums, so ``F`` and the cages' rows are always the
    whole bearing's.  With ``parts``, ``G`` gets only the entries the quasi-dynamic step reads
    (:func:`.contact._qd_rows`), the rest stay 0.  With both None this is
    :func:`dtrb_rhs_damped`, bit for bit and as fast: numba compiles the None case apart and
    prunes the branches on them (``is None`` tests on the arguments themselves)."""
    acc = G.shape[0] > 0
    stiff = acc and h_k > 0.0                     # "imex2": the stiffness in the blocks too
    qd = parts is not None                        # only the blocks' entries the QD step reads
    if acc:
        if active is not None:
            G[:, G.shape[1] - 1, :, :] = 0.0
        else:
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
            if active is not None:
                if active[j * nz + k] == 0.0:          # not moved: its stored share
                    pk = parts[j, k]
                    Fi = _add(Fi, (pk[0], pk[1], pk[2]))
                    Mi = _add(Mi, (pk[3], pk[4], pk[5]))
                    Fo = _add(Fo, (pk[6], pk[7], pk[8]))
                    Mo = _add(Mo, (pk[9], pk[10], pk[11]))
                    Fc = _add(Fc, (pk[12], pk[13], pk[14]))
                    Mcg = _add(Mcg, (pk[15], pk[16], pk[17]))
                    orbit += pk[18]
                    if acc:
                        G[j, nz, 5, 5] += pk[19]
                    spc, cpc = spc * cd + cpc * sd, cpc * cd - spc * sd
                    continue
                if acc:
                    G[j, k, :, :] = 0.0
            if parts is not None:                                   # the sums before this roller
                Fi0, Mi0, Fo0, Mo0, Fc0, Mcg0, orbit0 = Fi, Mi, Fo, Mo, Fc, Mcg, orbit
                g0 = G[j, nz, 5, 5] if acc else 0.0
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
                    _damping_rows(G, j, k, nz, cdmp, Jr, Jr, False, qd)
                    if stiff:
                        _tilt_rows(G, j, k, nz, h_k * KL * kdk, h_k * KL * kkk, Jr,
                                   (0.0, 0.0, 0.0, s, 0.0, 0.0), Z6, Z6, False, qd)
                        _friction_rows(G, j, k, nz, P[MU_R] * Qo, vrel, no, vs, et, _mul(rb, no),
                                       er, et, ey, ax, bx, R + rho, False, ey, qd)
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
                    _damping_rows(G, j, k, nz, cdmp, Jr, Jr, False, qd)
                    if stiff:
                        _tilt_rows(G, j, k, nz, h_k * KL * kdk, h_k * KL * kkk, Jr,
                                   (0.0, 0.0, 0.0, -s, 0.0, 0.0), Z6, Z6, False, qd)
                        _friction_rows(G, j, k, nz, P[MU_R] * Qi, vrel, ni, vs, et, _mul(-rb, ni),
                                       er, et, ey, ax, bx, R + rho, False, ey, qd)
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
                    _damping_rows(G, j, k, nz, cdmp, Jr, Jr, False, qd)
                    if h_k > 0.0:
                        _friction_rows(G, j, k, nz, P[MU_A] * Qa, vrel, na, vs, et, ra, er, et,
                                       ey, ax, bx, R + rho, False, ey, qd)
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
                        _damping_rows(G, j, k, nz, cdmp, Jw, Jwc, True, qd)
                        if stiff:
                            _friction_rows(G, j, k, nz, P[MU_C] * Qw, vrel, nw, vs, ey,
                                           _mul(rb, nw), er, et, ey, ax, bx, R + rho, True,
                                           _sub(pw, xc), qd)
                            gs = -sw * s * cac    # the skew in the pocket: kap's gradient
                            _tilt_rows(G, j, k, nz, h_k * KL * kdk, h_k * KL * kkk, Jw,
                                       (0.0, 0.0, 0.0, 0.0, gs, 0.0), Jwc,
                                       (0.0, 0.0, 0.0, -gs * bx[0], -gs * bx[2], 0.0), True, qd)
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
                                      _cage_rates(sw, ey, _sub(c, xc)), True, qd)
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
            if parts is not None:
                _share(parts[j, k], 0, Fi, Fi0)
                _share(parts[j, k], 3, Mi, Mi0)
                _share(parts[j, k], 6, Fo, Fo0)
                _share(parts[j, k], 9, Mo, Mo0)
                _share(parts[j, k], 12, Fc, Fc0)
                _share(parts[j, k], 15, Mcg, Mcg0)
                parts[j, k, 18] = orbit - orbit0
                parts[j, k, 19] = G[j, nz, 5, 5] - g0 if acc else 0.0

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
