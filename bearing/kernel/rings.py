"""A roller's contacts with a ring (numba), the parts every model's ``contacts`` is made of: a
raceway's line contact along the roller (paper Eqs. 1, 3, 4a, 15) and a rib's point contact on
the roller's end (Eqs. 3c, 4b, 8), each into the roller's record and, where the method asks,
its block rows.  A model supplies the geometry (the contact's normal, where it is, the
clearance) and, for a raceway, the integrals of its line law (the DTRB's closed form, the
DCRB's slices); the rest is here.
"""
from __future__ import annotations

from math import sqrt

from axlebox._numba import kernel

from .blocks import friction_rows, roller_grad, rows, tilt_grad, tilt_rows
from .contact import N_POINT, friction, line_load, load, normal, slip_damping
from .layout import M_R, R_B, V_S
from .vec import ZERO, ZERO6, add, cross, dot, lin, mul, sub


@kernel(inline="always")
def raceway_approach(fr, n, sigma, clearance, u, th, P):
    """A raceway's line contact along roller ``fr`` (bearing/kernel/roller.py ``Frame``), normal ``n``
    from the roller to the ring (``sigma`` +1 the outer raceway, -1 the inner, whose tilts
    enter ``kap`` with opposite signs), the ring's displacement ``u`` and small rotation ``th``:
    ``(d0, kap, r, rel)``, the approach at the line's middle less ``clearance``, its tilt along
    the line, the contact point from the roller's centre and from the ring's."""
    r = mul(P[R_B], n)
    rel = sub(add(fr.c, r), u)
    d0 = dot(sub(fr.disp, add(u, cross(th, rel))), n) - clearance
    return d0, sigma * fr.s * (fr.tht - dot(th, fr.et)), r, rel


@kernel(inline="always")
def raceway_load(ct, fr, n, sigma, r, rel, v_r, w_r, d0, kap, law, K, L, mu,
                 slot, P, want, h_k):
    """The raceway contact of :func:`raceway_approach` under its line law's ``law = (i0, i1,
    kdd, kdk, kkk)`` (``int delta^n``, ``int s delta^n`` over the line of length L and, for the
    "imex2" blocks, their derivatives; :func:`axlebox.bearing.kernel.contact.line_load`): the normal
    force, the tilted line's couple, friction ``mu Q`` against the slip, into the roller's record
    slot ``slot`` and, with ``want``, its block.  Returns the normal load."""
    i0, i1, kdd, kdk, kkk = law
    if not i0 > 0.0:
        return 0.0
    v = sub(add(fr.V, cross(fr.w, r)), add(v_r, cross(w_r, rel)))
    KL = K / L
    Q, m1, c = line_load(i0, i1, K, L, d0, kap, dot(v, n), P[M_R], P, KL * kdd, h_k)
    f = friction(v, n, mu * Q, P[V_S])
    fr_ = lin(-Q, n, 1.0, f)
    couple = mul(-sigma * fr.s * m1, fr.et)          # the tilted line's restoring moment
    load(ct.rec, slot, fr_, add(couple, cross(r, f)), mul(-1.0, add(cross(rel, fr_), couple)))
    if want and c > 0.0:
        blk, cblk, flag, jk = ct.blk, ct.cblk, ct.flag, ct.jk      # blocks.rows: why apart
        J = roller_grad(n, r, fr)
        rows(blk, cblk, flag, jk, c, J, ZERO6, False)
        if want and h_k > 0.0:
            tilt_rows(blk, cblk, flag, jk, h_k * KL * kdk, h_k * KL * kkk, J, tilt_grad(sigma * fr.s),
                      ZERO6, ZERO6, False)
            friction_rows(blk, cblk, flag, jk, slip_damping(v, n, mu * Q, P[V_S]), fr.et, n, r, fr,
                          ZERO, False)
    return Q


@kernel(inline="always")
def rib(ct, fr, n, ra, u, th, v_r, w_r, gap, K, mu, slot, P, want, h_k):
    """A rib's point contact ``K delta^(3/2)`` at ``ra`` from the centre of roller ``fr``, normal
    ``n`` from the roller to the rib, beyond the play ``gap``; the ring's displacement, small
    rotation, velocity and angular velocity ``u, th, v_r, w_r``: into the roller's record slot
    ``slot`` and, with ``want``, its block.  Returns the normal load."""
    p = add(fr.c, ra)
    rel = sub(p, u)
    d0 = dot(sub(add(fr.disp, cross(fr.theta, ra)), add(u, cross(th, rel))), n) - gap
    if not d0 > 0.0:
        return 0.0
    v = sub(add(fr.V, cross(fr.w, ra)), add(v_r, cross(w_r, rel)))
    Q, c = normal(K * d0 * sqrt(d0), K, N_POINT, dot(v, n), P[M_R], P, d0, 0.0, h_k)
    fr_ = lin(-Q, n, 1.0, friction(v, n, mu * Q, P[V_S]))
    load(ct.rec, slot, fr_, cross(ra, fr_), mul(-1.0, cross(rel, fr_)))
    if want and c > 0.0:
        blk, cblk, flag, jk = ct.blk, ct.cblk, ct.flag, ct.jk
        rows(blk, cblk, flag, jk, c, roller_grad(n, ra, fr), ZERO6, False)
        if h_k > 0.0:
            friction_rows(blk, cblk, flag, jk, slip_damping(v, n, mu * Q, P[V_S]), fr.et, n, ra, fr,
                          ZERO, False)
    return Q
