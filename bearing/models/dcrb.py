"""The double-row cylindrical roller bearing (DCRB) of a metro axle box: the other bearing the
paper names for it.  Declared to the package in :mod:`.models`; everything but its contacts with
the rings is the shared parts' (the rollers' six degrees of freedom and the cage,
:mod:`.roller`, :mod:`.pocket`; the defects of :mod:`.defects`; the implicit and
quasi-dynamic steps).

**The bearing** (:class:`DcrbParams`).  The metro car's journal takes the DTRB's 130 mm bore; the
cylindrical roller pair axle-box bearings of that bore are 130 x 240 x 80 mm each, two side by
side, an NJ and an NJP (DIN 5412-11's WJ and WJP, "typically applied as sets of two single row
bearings": SKF, Railway technical handbook vol. 1, ch. 4), with a dynamic load rating of 540 kN
each (FAG, The Design of Rolling Bearing Mountings, the example "axle box roller bearings" for
intercity traffic: "FAG WJ130x240TVP and FAG WJP130x240P.TVP ... 130 x 240 x 80 mm ... 540 kN").
Published: the bore, the outside diameter, the width, the load rating.  No maker publishes the
rollers, so these are ASSUMED and checked against that rating: the pitch diameter (d + D) / 2 =
185 mm, 15 rollers a row of 28 x 50 mm (an effective length of 47 mm), which give ISO 281's
rating ``C_r = b_m f_c (L_we)^(7/9) Z^(3/4) D_we^(29/27)`` (b_m = 1.1, f_c = 88.2 at D_we / D_pw
= 0.151) = 529 kN, 2 % under the published 540 kN (tests/test_dcrb.py); rings 13.5 mm thick at
the raceways; the rows 40 mm either side of the centre (two 80 mm bearings).  Radial clearance:
70 um mounted (ASSUMED: the Normal group of a 120-140 mm bore, 60-105 um before mounting, less
what the inner ring's interference takes).  Masses: the roller a steel cylinder (7850 kg/m^3,
derived), the cage 0.2 kg a row (ASSUMED, glass-fibre polyamide, the "TVP" of the FAG example).
Ribs: each row's rings flanged on both sides, the play of a roller between a ring's ribs 0.1 mm
(ASSUMED; the NJP's loose rib taken as a rib), the contact on the roller's end face 10 mm from
its axis (ASSUMED), the end face a sphere of 0.5 m (ASSUMED).

**Line contact by slices** (:func:`slices`, replacing the DTRB's closed-form integral): the
contact line of effective length L is cut into n slices of width w = L / n; slice k at
``s_k`` along the roller is compressed by ``delta_k = delta_0 + kappa s_k - c(s_k) - h(s_k)``
(the approach at the middle, the tilt, the roller's crown, a defect's depth) and carries
``q_k = (K / n) delta_k^(10/9)``, K the pair's line stiffness of Palmgren's law
``delta = 3.84e-5 Q^0.9 / l^0.8`` (mm, N; Palmgren, Ball and Roller Bearing Engineering, 1959) in
the paper's Eq. (10) form (bearing/statics/stiffness.py): the whole roller's coefficient shared evenly,
so that an uncrowned roller pressed uniformly carries exactly Palmgren's load (applying the
whole-roller law to each slice's own length instead would overstate it by ``n^(1/9)``, 29 % at
10 slices).  Why slices: the crown.  The rollers are crowned to Johns and Gohar's logarithmic
profile as Fujiwara and Kawase modified it to end at a drop ``z_m`` (NTN Technical Review 75,
2007): ``c(s) = A ln(1 / (1 - (1 - exp(-z_m / A)) (2 s / L)^2))``, ``A = 2 Q_d / (pi E' L)``, which
presses evenly at the design load ``Q_d`` (ASSUMED 10 kN, about the heaviest roller's load
under the car; ``z_m`` ASSUMED 10 um); a closed form has no such profile.

**The ribs take the axial load**: a roller moving along its axis by more than half the play
meets a rib of the ring, a point contact on its end face (the DTRB's rib law, Eqs. 4b, 8:
Hertz's sphere on a plane), the outer ring's rib above its axis, the inner ring's below; the
raceways' normals are radial and carry none.
"""
from __future__ import annotations

from dataclasses import dataclass
from math import exp, pi

import numpy as np

from axlebox._numba import kernel
from axlebox._params import ParameterError, param, require

from ..kernel import layout as lo
from ..kernel.contact import N_LINE
from ..defects import depth_under, roller_depths
from ..kernel.layout import (C_INNER, C_INNER_RIB, C_OUTER, C_OUTER_RIB, INNER_RING, L_B, N_COMMON,
                     OUTER_RING, Q_A, Q_I, Q_O)
from .params import RollerBearing, quasi_dynamic_steps
from ..kernel.rings import raceway_approach, raceway_load, rib
from ..statics.stiffness import e_prime, k_line, k_point_sphere
from ..kernel.vec import EY, lin, mul

NAME = "dcrb"
BORE = 0.130            # m: the journal's, as the DTRB's (module docstring)
SUMMARY = ("the double-row cylindrical roller bearing of a metro axle box (an NJ + NJP pair, "
           "130 x 240 x 80 mm each), line contacts by slices, ribs that take the axial load")
DEFAULTS = ("Defaults: the boundary dimensions and load rating of FAG's WJ/WJP 130 x 240 axle-box "
            "pair, the rollers assumed to match that rating; each field's source in bearing/models/dcrb.py.")
# s: the explicit steps' limits on the rollers' contact modes, measured on the rig as the DTRB's
# were (tests/test_dcrb.py; benchmarks/README.md "The DCRB")
DT_MAX = {"dynamic": {"rk4": 2.8e-5, "leapfrog": 1.2e-5, "imex": 1.2e-5, "imex2": 1.2e-5},
          "quasi-dynamic": quasi_dynamic_steps()}
RHO_STEEL = 7850.0      # kg/m^3

# --- the DCRB's own parameter slots: the contact line's length, the outer raceway's clearance,
# the raceways' line stiffness, the ribs' (point stiffness, contact height, half play), the
# friction coefficients, the slices and each slice's crown drop (N_S of them from CROWN) -------
(L_E, C_O, K_LINE, K_A, H_R, PLAY, MU_R, MU_A, N_S, CROWN) = range(N_COMMON, N_COMMON + 10)


@dataclass(frozen=True)
class DcrbParams(RollerBearing):
    """The DCRB's parameters (module docstring: what is published, what is derived, what is
    assumed)."""

    Z: int = param(15, 3, 80, unit="", doc="rollers a row (assumed, to match the pair's published "
                   "rating)")
    D_m: float = param(0.185, 0.02, 1.0, doc="pitch diameter, (d + D) / 2 of the 130 x 240 mm "
                       "boundary (assumed)")
    D_b: float = param(0.028, 0.002, 0.2, doc="roller diameter (assumed)")
    L_b: float = param(0.050, 0.002, 0.3, doc="roller length (assumed)")
    M_r: float = param(0.242, 1e-4, 10.0, unit="kg", doc="roller mass: a 28 x 50 mm steel cylinder")
    M_c: float = param(0.20, 1e-3, 20.0, unit="kg", doc="cage mass, each row (assumed, glass-fibre "
                       "polyamide)")
    h_r: float = param(0.010, 0.0, 0.1, doc="the ribs' contact on the roller's end face, from its "
                       "axis (assumed)")
    L_we: float = param(0.047, 0.002, 0.3, doc="effective contact length, the roller's straight "
                        "length (assumed)")
    u_r: float = param(0.07e-3, 0.0, 1e-3, doc="radial (diametral) clearance, mounted (assumed)")
    u_ax: float = param(0.10e-3, 0.0, 3e-3, doc="play of a roller between its ring's ribs, both "
                        "ends together (assumed)")
    n_slices: int = param(10, 2, 200, unit="", doc="slices of a raceway's contact line")
    crown_drop: float = param(10e-6, 0.0, 1e-3, doc="the crown's drop at the contact line's ends "
                              "(assumed)")
    crown_load: float = param(10e3, 1.0, 1e7, unit="N", doc="the load the logarithmic crown presses "
                              "evenly at (assumed)")

    def __post_init__(self):
        if isinstance(self.n_slices, bool) or not isinstance(self.n_slices, int):
            raise ParameterError(f"DcrbParams.n_slices = {self.n_slices!r} is not allowed: expected "
                                 "an integer >= 2")
        super().__post_init__()
        require(self.L_we <= self.L_b, self, "L_we", f"expected at most the roller length "
                f"L_b = {self.L_b:g} m")

    rows = 2                                   # an NJ and an NJP side by side
    alpha_o = alpha_i = alpha_m = 0.0          # a cylindrical roller's: radial contacts, axis

    @property
    def L_e(self) -> float:
        """The contact line's length (``L_we``)."""
        return self.L_we

    @property
    def D_o(self) -> float:
        """Outer raceway diameter."""
        return self.D_m + self.D_b

    @property
    def D_i(self) -> float:
        """Inner raceway diameter."""
        return self.D_m - self.D_b

    @property
    def clearance_n(self) -> float:
        """Radial clearance of one roller, rings concentric: ``u_r / 2`` (m)."""
        return 0.5 * self.u_r


Params = DcrbParams


def crown(p: DcrbParams, s):
    """The crown's drop at ``s`` along the contact line (module docstring)."""
    E = e_prime(p.E_r, p.nu_r, p.E_r, p.nu_r)
    A = 2.0 * p.crown_load / (pi * E * p.L_we)
    if p.crown_drop == 0.0:
        return np.zeros_like(np.asarray(s, float))
    x = (2.0 * np.asarray(s, float) / p.L_we) ** 2
    return A * np.log(1.0 / (1.0 - (1.0 - exp(-p.crown_drop / A)) * x))


def slice_centres(p: DcrbParams):
    w = p.L_we / p.n_slices
    return -0.5 * p.L_we + (np.arange(p.n_slices) + 0.5) * w


def pack(p: DcrbParams, gravity=(0.0, 0.0, -9.81)) -> np.ndarray:
    """The parameter vector of ``p`` for the kernels (the crown's drop at each slice last)."""
    v = np.zeros(CROWN + p.n_slices)
    lo.pack_common(v, p, gravity)
    E = e_prime(p.E_r, p.nu_r, p.E_r, p.nu_r)
    v[[L_E, C_O, K_LINE]] = p.L_we, p.clearance_n, k_line(E, p.L_we)
    v[[K_A, H_R, PLAY]] = k_point_sphere(E, p.R_e), p.h_r, 0.5 * p.u_ax
    v[[MU_R, MU_A, N_S]] = p.mu_race, p.mu_rib, p.n_slices
    v[CROWN:] = crown(p, slice_centres(p))
    return v


nominal_state = lo.nominal_state


def orders(p: DcrbParams):
    """Fault orders, radial contacts (bearing/frequencies.py)."""
    from ..frequencies import orders as at_angle
    return at_angle(p, 0.0)


def guess(p: DcrbParams, F_outer):
    """A first guess of the static state under ``F_outer`` on the outer ring: the radial
    series-spring solution (bearing/statics/quasistatic.py, contact angle 0) under its radial part, the
    ring put against its ribs on the axial part's side; the rollers halfway between."""
    from ..statics import quasistatic
    F = np.asarray(F_outer, float)
    radial = F.copy()
    radial[lo.F_Y] = 0.0
    e = quasistatic.solve(p, -radial, (0.0, 0.0))
    d = np.clip(e.delta, 0.0, None)
    uo = -e.q[quasistatic.QX:quasistatic.QZ + 1]
    uo[lo.F_Y] = 0.0 if F[lo.F_Y] == 0.0 else np.sign(F[lo.F_Y]) * p.u_ax
    return uo, -0.5 * d, np.zeros_like(d) + 0.5 * uo[lo.F_Y]


def ring_stiffness(p: DcrbParams, F):
    """Tangent stiffness (3,) along x, y (axial), z (N/m) at the load ``F`` on the outer ring:
    radially the quasi-static model's (bearing/statics/quasistatic.py, the load moved by 1 % of its
    size over the displacement that follows), axially the ribs' in series with the rollers
    (each row's Z rollers on one rib of each ring)."""
    from ..statics import quasistatic
    F = np.asarray(F, float)[lo.F_X:lo.F_Z + 1].copy()
    F[lo.F_Y] = 0.0
    q0 = quasistatic.solve(p, F).q
    dF = 0.01 * np.linalg.norm(F)
    out = np.zeros(3)
    for a in (lo.F_X, lo.F_Z):
        F1 = F.copy()
        F1[a] += dF
        out[a] = dF / (quasistatic.solve(p, F1).q[a] - q0[a])
    # axial: the rib contacts at a hundredth of the radial load, two in series a roller
    E = e_prime(p.E_r, p.nu_r, p.E_r, p.nu_r)
    K = k_point_sphere(E, p.R_e)
    q = 0.01 * np.linalg.norm(F) / (p.rows * p.Z)
    k_one = 1.5 * K ** (2 / 3) * q ** (1 / 3)
    out[lo.F_Y] = p.rows * p.Z * 0.5 * k_one
    return out


# --- the rollers' contacts with the rings (numba) -----------------------------------------------
@kernel(inline="always")
def contacts(ct, Q, j, k, fr, rings, psi, P, D, n_inner, n_roller, want, h_k):
    """Roller k of row j (:class:`.roller.Frame` ``fr``; ``psi`` its spin angle) on both raceways
    (their line contacts by slices) and against the ribs of both rings: their loads into the
    roller's record ``ct.rec`` (``ct``: its bearing/kernel/layout.py ``Touch``), their normal
    loads into its outputs ``Q`` (``Q_A`` the two ribs' together) and, with ``want``, their rows
    into its block."""
    stiff = want and h_k > 0.0
    h, s1, s2 = depth_under(D, OUTER_RING, j, fr.phi, rings.angle_o)
    hr_o, hr_i, r1, r2 = roller_depths(D, j, k, psi) if n_roller > 0 else (0.0, 0.0, 0.0, 0.0)
    if hr_o > h:
        h, s1, s2 = hr_o, r1, r2
    n = fr.er                                                      # to the outer ring
    d0, kap, r, rel = raceway_approach(fr, n, 1.0, P[C_O], rings.uo, rings.tho, P)
    Q[Q_O] = raceway_load(ct, fr, n, 1.0, r, rel, rings.vo, rings.wo, d0, kap,
                          slices(d0, kap, h, s1, s2, P, stiff), P[K_LINE], P[L_E], P[MU_R], C_OUTER,
                          P, want, h_k)
    h, s1, s2 = depth_under(D, INNER_RING, j, fr.phi, rings.angle_i) if n_inner > 0 else (0.0, 0.0, 0.0)
    if hr_i > h:
        h, s1, s2 = hr_i, r1, r2
    n = mul(-1.0, fr.er)                                           # to the inner ring
    d0, kap, r, rel = raceway_approach(fr, n, -1.0, 0.0, rings.ui, rings.thi, P)
    Q[Q_I] = raceway_load(ct, fr, n, -1.0, r, rel, rings.vi, rings.wi, d0, kap,
                          slices(d0, kap, h, s1, s2, P, stiff), P[K_LINE], P[L_E], P[MU_R], C_INNER,
                          P, want, h_k)
    Q[Q_A] = (_ribs(ct, fr, 1.0, rings.uo, rings.tho, rings.vo, rings.wo,
                    C_OUTER_RIB, P, want, h_k)
              + _ribs(ct, fr, -1.0, rings.ui, rings.thi, rings.vi, rings.wi,
                      C_INNER_RIB, P, want, h_k))


@kernel
def _ribs(ct, fr, side, u, th, v_r, w_r, slot, P, want, h_k):
    """The ribs of one ring (``side`` +1 the outer ring's, whose ribs meet the roller's end face
    above its axis, -1 the inner ring's, below): the one at the end the roller has moved toward
    along the bearing's axis, beyond half the play.  Returns its normal load."""
    _, eta, _ = fr.disp
    _, u_y, _ = u
    lead = 1.0 if eta - u_y >= 0.0 else -1.0          # the roller moves toward +y or -y
    # the end face toward it (the roller's axis is s e_y), at h_r from the axis toward the ring
    ra = lin(0.5 * lead * fr.s * P[L_B], fr.ax, side * P[H_R], fr.er)
    return rib(ct, fr, mul(lead, EY), ra, u, th, v_r, w_r, P[PLAY], P[K_A],
               P[MU_A], slot, P, want, h_k)


@kernel
def slices(d0, kap, h, s1, s2, P, stiff):
    """A raceway line contact's integrals by slices (module docstring): ``(i0, i1, kdd, kdk,
    kkk)`` in the closed form's units (bearing/kernel/rings.py ``raceway_load``), ``i0 = w sum
    delta_k^n``, ``i1 = w sum s_k delta_k^n`` and, when ``stiff``, ``n w sum delta_k^(n-1)``
    times 1, ``s_k``, ``s_k^2``; a defect of depth h over ``[s1, s2]`` of the line."""
    L = P[L_E]
    n = int(P[N_S])
    w = L / n
    i0 = i1 = kdd = kdk = kkk = 0.0
    for q in range(n):
        s = -0.5 * L + (q + 0.5) * w
        u = d0 + kap * s - P[CROWN + q]
        if h > 0.0 and s1 <= s <= s2:
            u -= h
        if u > 0.0:
            t = u ** (N_LINE - 1.0)
            f = w * u * t
            i0 += f
            i1 += s * f
            if stiff:
                g = N_LINE * w * t
                kdd += g
                kdk += g * s
                kkk += g * s * s
    return i0, i1, kdd, kdk, kkk
