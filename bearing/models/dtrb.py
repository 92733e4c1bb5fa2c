"""The double-row tapered roller bearing (DTRB) of the paper: its parameter vector, and its
rollers' contacts with the rings (numba): cup and cone raceways (Eqs. 1, 3a-b, 4a, 14, 15) and
the cone's rib on the roller's large end (Eqs. 3c, 4b, 8).  The pockets (:mod:`.pocket`), the
rollers' and cages' dynamics (:mod:`.roller`) and everything else are the shared parts; the
model is declared to the rest of the package in :mod:`.models`.

What the paper's equations become here (one vector form for both rows and both raceways):

* Eqs. (1), (3), (15): the normal approach of each contact is the relative displacement of the
  two bodies at the contact point along the contact normal ``n_o = cos a_o e_r + s sin a_o e_y``
  (cup), ``n_i`` (cone, same form), ``n_a = -sin a_f e_r + s cos a_f e_y`` (rib), less the
  clearance (on the cup contact) and a defect's depth ``h`` (Eq. 14: on the cup for an
  outer-ring defect, on the cone for an inner-ring one, each turning with its ring; on both,
  half a roller turn apart, for a defect on a roller, turning with its spin).  Row j sits at
  ``y = -s row_offset``: the back-to-back (O) arrangement, contact lines crossing the axis
  outside the bearing.
* Eq. (4a): raceway line contacts ``q(sigma) = (K / L_e) delta(sigma)^(10/9)`` integrated in
  closed form along the contact line, ``delta(sigma) = delta_0 + kappa sigma`` with the
  roller's tilt relative to the ring in kappa: the same law as Eq. (4a) for an untilted
  roller, and the tilt restoring moment the paper's Eq. (12d) lacks (slicing, done exactly).
* Eq. (4b), (8): rib point contact ``K_a delta^(3/2)`` at height h_r on the large end.
* Friction (the paper's "conventional friction model", f = mu Q): regularised Coulomb
  (:func:`axlebox.bearing.kernel.contact.friction`); damping by :func:`axlebox.bearing.kernel.contact.normal`.

Parameter vector: the shared slots (:mod:`.layout`, ``Z .. N_COMMON - 1``), then ``L_E`` the
effective contact length (Eq. 6), the cosines and sines of the cup, cone and rib angles,
``C_O`` the clearance along the cup normal, ``H_R`` the rib contact's height, the stiffnesses
``K_O, K_I, K_A`` and the friction coefficients ``MU_R`` (raceways) and ``MU_A`` (rib).
"""
from __future__ import annotations

from math import cos, sin

import numpy as np

from axlebox._numba import kernel

from ..kernel import layout as lo
from ..kernel.contact import (N_LINE, line_integrals, line_stiffness)
from ..defects import depth_under, roller_depths
from ..kernel.layout import (C_INNER, C_INNER_RIB, C_OUTER, INNER_RING, L_B, N_COMMON, OUTER_RING, Q_A,
                     Q_I, Q_O)
from .params import BearingParams, quasi_dynamic_steps
from ..kernel.rings import raceway_approach, raceway_load, rib
from ..statics.stiffness import contacts as stiffnesses
from ..kernel.vec import AX, AZ, EY, lin

NAME = "dtrb"
nominal_state = lo.nominal_state
Params = BearingParams
SUMMARY = ("the double-row tapered roller bearing of the paper (Zhao et al., Sci. Rep. 2025), "
           "rollers and cages with six degrees of freedom")
DEFAULTS = ("Defaults: the paper's Z = 20 rollers a row and an assumed 130 x 230 x 160 mm unit; "
            "each field's source in bearing/models/params.py.")
BORE = 0.130            # m: the assumed 130 x 230 x 160 mm unit (bearing/models/params.py)
# s: the explicit steps' limits on the rollers' tilt mode between the raceways (22.6 kHz,
# damping ratio 0.12): RK4's w h <= 2.8; the leapfrog's 2 (sqrt(1 + z^2) - z) = 1.77 less a
# margin for the loads; "imex" (contact damping implicit) keeps the undamped limit of the
# leapfrog on the tilt mode (benchmarks/README.md); "imex2" (stiffness and friction implicit too)
# runs the bearing alone at 2.5e-5 s, but the car's defect side is not yet right there: held to
# imex's limit until it is (benchmarks/README.md, "imex2")
DT_MAX = {"dynamic": {"rk4": 2.8e-5, "leapfrog": 1.2e-5, "imex": 1.2e-5, "imex2": 1.2e-5},
          "quasi-dynamic": quasi_dynamic_steps()}

# --- the DTRB's own parameter slots -------------------------------------------------------------
(L_E, CAO, SAO, CAI, SAI, CAF, SAF, C_O, H_R, K_O, K_I, K_A, MU_R, MU_A, N_P) = range(N_COMMON,
                                                                                  N_COMMON + 15)


def pack(p, gravity=(0.0, 0.0, -9.81)) -> np.ndarray:
    """The parameter vector of ``p`` (a :class:`.params.BearingParams`) for the kernels."""
    k = stiffnesses(p)
    v = np.zeros(N_P)
    lo.pack_common(v, p, gravity)
    v[L_E] = p.L_e
    v[[CAO, SAO, CAI, SAI]] = cos(p.alpha_o), sin(p.alpha_o), cos(p.alpha_i), sin(p.alpha_i)
    v[[CAF, SAF, C_O, H_R]] = cos(p.alpha_f), sin(p.alpha_f), p.clearance_n, p.h_r
    v[[K_O, K_I, K_A]] = k["K_ro"], k["K_ri"], k["K_a"]
    v[[MU_R, MU_A]] = p.mu_race, p.mu_rib
    return v


def orders(p):
    """Fault orders at the cup's contact angle (bearing/frequencies.py)."""
    from ..frequencies import orders as at_angle
    return at_angle(p, p.alpha_o)


def guess(p, F_outer):
    """A first guess of the static state under the load ``F_outer`` on the outer ring: the
    series-spring solution (bearing/statics/quasistatic.py): the outer ring's displacement (3) and each
    roller's radial and axial displacement (2, Z) x 2, half the cup normal's approach each."""
    from ..statics import quasistatic
    e = quasistatic.solve(p, -np.asarray(F_outer, float), (0.0, 0.0))
    d = np.clip(e.delta, 0.0, None)
    s = np.array([1.0, -1.0])[:, None]
    return -e.q[quasistatic.QX:quasistatic.QZ + 1], -0.5 * d * cos(p.alpha_o), -0.5 * d * s * sin(p.alpha_o)


def ring_stiffness(p, F):
    """Tangent stiffness (3,) along x, y (axial), z (N/m) at the load ``F`` on the outer ring,
    from the quasi-static model (bearing/statics/quasistatic.py): the load moved by 1 % of its size
    along each axis over the displacement that follows."""
    from ..statics import quasistatic
    F = np.asarray(F, float)[AX:AZ + 1]
    q0 = quasistatic.solve(p, F).q
    dF = 0.01 * np.linalg.norm(F)
    out = np.zeros(3)
    for a in range(3):
        F1 = F.copy()
        F1[a] += dF
        out[a] = dF / (quasistatic.solve(p, F1).q[a] - q0[a])
    return out


# --- the rollers' contacts with the rings (numba) -------------------------------------------------
@kernel(inline="always")
def contacts(ct, Q, j, k, fr, rings, psi, P, D, n_inner, n_roller, want, h_k):
    """Roller k of row j (:class:`.roller.Frame` ``fr``; ``psi`` its spin angle) against the cup,
    the cone and the cone's rib (``rings``: :class:`.roller.Rings`): their loads into the roller's
    record ``ct.rec`` (``ct``: its bearing/kernel/layout.py ``Touch``), their normal loads into
    its outputs ``Q`` and, with ``want``, their rows into its block (bearing/kernel/blocks.py).
    ``n_inner``, ``n_roller``: the defect table's inner-ring and roller defects (none: not looked
    up)."""
    s = fr.s
    stiff = want and h_k > 0.0
    h, s1, s2 = depth_under(D, OUTER_RING, j, fr.phi, rings.angle_o)
    hr_o, hr_i, r1, r2 = roller_depths(D, j, k, psi) if n_roller > 0 else (0.0, 0.0, 0.0, 0.0)
    if hr_o > h:
        h, s1, s2 = hr_o, r1, r2
    n = lin(P[CAO], fr.er, s * P[SAO], EY)                     # cup, Eqs. (1), (3a), (4a), (14)
    d0, kap, r, rel = raceway_approach(fr, n, 1.0, P[C_O], rings.uo, rings.tho, P)
    Q[Q_O] = raceway_load(ct, fr, n, 1.0, r, rel, rings.vo, rings.wo, d0, kap,
                          line_with_defect(d0, kap, h, s1, s2, P[L_E], stiff), P[K_O], P[L_E],
                          P[MU_R], C_OUTER, P, want, h_k)
    h, s1, s2 = depth_under(D, INNER_RING, j, fr.phi, rings.angle_i) if n_inner > 0 else (0.0, 0.0, 0.0)
    if hr_i > h:
        h, s1, s2 = hr_i, r1, r2
    n = lin(-P[CAI], fr.er, -s * P[SAI], EY)                   # cone, Eqs. (1), (3b), (4a)
    d0, kap, r, rel = raceway_approach(fr, n, -1.0, 0.0, rings.ui, rings.thi, P)
    Q[Q_I] = raceway_load(ct, fr, n, -1.0, r, rel, rings.vi, rings.wi, d0, kap,
                          line_with_defect(d0, kap, h, s1, s2, P[L_E], stiff), P[K_I], P[L_E],
                          P[MU_R], C_INNER, P, want, h_k)
    # the cone's rib on the large end, at h_r above the roller's axis, Eqs. (3c), (4b), (8)
    Q[Q_A] = rib(ct, fr, lin(P[SAF], fr.er, -s * P[CAF], EY),
                 lin(-0.5 * P[L_B], fr.ax, -P[H_R], fr.bx), rings.ui, rings.thi, rings.vi, rings.wi,
                 0.0, P[K_A], P[MU_A], C_INNER_RIB, P, want, h_k)


@kernel
def line_with_defect(d0, kap, h, s1, s2, Le, stiff):
    """A raceway line contact's integrals (and, when ``stiff``, its tangent stiffness over
    ``K / L``, :func:`axlebox.bearing.kernel.contact.line_stiffness`), with a defect of depth h
    over ``[s1, s2]`` of
    the line where ``h > 0`` (Eq. 14)."""
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
