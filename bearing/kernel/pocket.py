"""A roller in its cage pocket (numba): the pocket walls (paper Eqs. 9-11) as line contacts along
the roller, the roller's skew in their tilt, and the side beams in the axial direction (the
paper leaves them out; they keep the cage from drifting axially), with the same law.  The cage
is roller-guided: it touches nothing else.  Every model whose rollers sit in such a cage shares
these contacts (:mod:`.models`).
"""
from __future__ import annotations

from axlebox._numba import kernel

from .blocks import cage_grad, friction_rows, roller_grad, rows, tilt_rows
from .contact import (N_LINE, friction, line_integrals, line_load, line_stiffness, load, normal,
                      slip_damping)
from .layout import (C_SIDE_1, C_SIDE_2, C_WALL_1, C_WALL_2, CAC, K_CR, L_B, M_C, M_R, MU_C, Q_CR1,
                     Q_CR2, Q_SIDE, R_B, R_M, S_P, S_PA, SAC, V_S)
from .vec import EY, ZERO, add, cross, dot, lin, mul, sub


@kernel(inline="always")
def pockets(ct, Q, fr, cage, sp, cp, P, want, h_k):
    """The pocket of roller ``fr`` (bearing/kernel/roller.py ``Frame``) in ``cage`` (its ``Cage``),
    the pocket's azimuth of sine ``sp`` and cosine ``cp``: both walls and the side beams into
    the roller's record ``ct.rec`` (``ct``: its :data:`.layout.Touch`), their normal loads into
    its contact outputs ``Q``, and with ``want`` their rows into its block and its cage's
    ``ct.cblk`` (bearing/kernel/blocks.py; ``h_k``: bearing/contact.normal)."""
    erp = (sp, 0.0, cp)
    etp = (cp, 0.0, -sp)
    P0 = lin(P[R_M], erp, fr.yj, EY)
    dd = sub(fr.c, add(cage.xc, add(P0, cross(cage.th, P0))))    # from the pocket's centre
    m = P[M_R] * P[M_C] / (P[M_R] + P[M_C])                       # the contact's reduced mass
    Q[Q_CR1] = _wall(ct, fr, cage, dd, lin(P[CAC], etp, P[SAC], erp), 1.0,
                     C_WALL_1, m, P, want, h_k)
    Q[Q_CR2] = _wall(ct, fr, cage, dd, lin(-P[CAC], etp, P[SAC], erp), -1.0,
                     C_WALL_2, m, P, want, h_k)
    Q[Q_SIDE] = _side_beams(ct, fr, cage, dd, m, P, want, h_k)


@kernel(inline="always")
def _wall(ct, fr, cage, dd, nw, sw, slot, m, P, want, h_k):
    """One pocket wall of normal ``nw`` (side ``sw``, record slot ``slot``): its line contact along
    the roller, the roller's skew relative to the cage in the tilt.  Returns its normal load."""
    Lb = P[L_B]
    d0 = dot(dd, nw) - P[S_P]
    gs = -sw * fr.s * P[CAC]                       # the tilt's gradient in the skew
    bx_x, _, bx_z = fr.bx
    kap = gs * (fr.ths - dot(cage.th, fr.bx))
    i0, i1 = line_integrals(d0, kap, -0.5 * Lb, 0.5 * Lb, N_LINE)
    if not i0 > 0.0:
        return 0.0
    stiff = want and h_k > 0.0
    kdd, kdk, kkk = line_stiffness(d0, kap, -0.5 * Lb, 0.5 * Lb, N_LINE) if stiff else (0.0, 0.0, 0.0)
    KL = P[K_CR] / Lb
    r = mul(P[R_B], nw)
    rel = sub(add(fr.c, r), cage.xc)
    v = sub(add(fr.V, cross(fr.w, r)), add(cage.v, cross(cage.w, rel)))
    Q, m1, c = line_load(i0, i1, P[K_CR], Lb, d0, kap, dot(v, nw), m, P, KL * kdd, h_k)
    f = friction(v, nw, P[MU_C] * Q, P[V_S])
    fr_ = lin(-Q, nw, 1.0, f)
    couple = mul(m1, cross(fr.ax, nw))               # the roller's skew against the wall
    load(ct.rec, slot, fr_, sub(cross(r, f), couple), sub(couple, cross(rel, fr_)))
    if want and c > 0.0:
        blk, cblk, flag, jk = ct.blk, ct.cblk, ct.flag, ct.jk      # blocks.rows: why apart
        Jw, Jwc = roller_grad(nw, r, fr), cage_grad(nw, rel)
        rows(blk, cblk, flag, jk, c, Jw, Jwc, True)
        if stiff:
            friction_rows(blk, cblk, flag, jk, slip_damping(v, nw, P[MU_C] * Q, P[V_S]), EY, nw, r,
                          fr, rel, True)
            tilt_rows(blk, cblk, flag, jk, h_k * KL * kdk, h_k * KL * kkk, Jw,
                      (0.0, 0.0, 0.0, 0.0, gs, 0.0), Jwc, (0.0, 0.0, 0.0, -gs * bx_x, -gs * bx_z, 0.0),
                      True)
    return Q


@kernel(inline="always")
def _side_beams(ct, fr, cage, dd, m, P, want, h_k):
    """The side beams at the roller's two ends: the axial play ``chi`` of the roller in its
    pocket beyond the clearance, the same line law along the end's diameter.  Returns their
    normal load."""
    _, chi, _ = dd
    _, v_roller, _ = fr.V
    _, v_cage, _ = cage.v
    _, v_turn, _ = cross(cage.w, sub(fr.c, cage.xc))
    chid = v_roller - v_cage - v_turn
    Qs = 0.0
    for slot, sw in ((C_SIDE_1, 1.0), (C_SIDE_2, -1.0)):
        d0 = sw * chi - P[S_PA]
        if not d0 > 0.0:
            continue
        Q, c = normal(P[K_CR] * d0 ** N_LINE, P[K_CR], N_LINE, sw * chid, m, P, d0, 0.0, h_k)
        n = mul(sw, EY)
        if want and c > 0.0:
            rows(ct.blk, ct.cblk, ct.flag, ct.jk, c, roller_grad(n, ZERO, fr),
                 cage_grad(n, sub(fr.c, cage.xc)), True)
        fr_ = mul(-sw * Q, EY)
        rel = sub(lin(1.0, fr.c, 0.5 * sw * P[L_B], EY), cage.xc)     # from the roller's end
        load(ct.rec, slot, fr_, ZERO, mul(-1.0, cross(rel, fr_)))
        Qs += Q
    return Qs
