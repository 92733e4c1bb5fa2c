"""The plain arrays every bearing model shares, slot by slot: the one place that says what each
slot holds (a model's own parameter slots are declared in its module, e.g.
:mod:`.dtrb`).

The numba kernels see only these arrays and read every slot by name; nothing outside this
module and the models' own layouts indexes a slot by number (tests/test_layout_names.py).

**State**, one bearing of ``n`` rows of ``Z`` rollers (``n_state(Z, n) = 12 n Z + 12 n``; ``n``
the model's own, its parameters' ``rows``, in the parameter slot ``N_ROWS``), rollers then cages:

* rollers ``(n, Z, N_ROLLER)``: ``RHO, PHI, ETA, TH_T, TH_S, PSI`` and their rates at ``RATE +``
  the slot.  ``RHO`` and ``ETA`` are the radial and axial displacement of the roller centre
  from its nominal place on the pitch circle, ``PHI`` its azimuth (from +z towards +x, paper
  Eq. 2), ``TH_T`` its tilt about the tangent ``e_t``, ``TH_S`` its skew about ``b`` (normal to
  the roller axis in the axial plane), ``PSI`` its spin about its own axis relative to the
  orbiting frame; the rate slot of ``PSI`` holds the spin speed ``omega_s``.
* cages ``(n, N_CAGE)``: ``CX, CY, CZ, CTX, CTZ, CPHI`` (translation, tilt about x and z,
  rotation) and their rates at ``RATE +`` the slot.

**Ring motion** ``(RINGS, RING)``, ring ``INNER`` or ``OUTER``: displacement ``U_X, U_Y, U_Z``, small
rotation ``TH_X, TH_Y, TH_Z``, velocity ``V_X ..`` and angular velocity ``W_X ..``, in the
bearing's frame (x forward, y along the axle, z up; origin at the inner ring's centre).
``TH_Y`` is the ring's angle about the bearing axis (the wheelset's spin for the inner ring)
and ``W_Y`` its spin speed.  **Ring loads** ``(RINGS, LOAD)``: force ``F_X, F_Y, F_Z`` and moment
``M_X, M_Y, M_Z`` about the ring's centre (paper Eq. 16 with moments).

**Contact forces** ``(n, Z, N_Q)``: the normal loads of a roller's contacts, ``Q_O`` (outer
raceway), ``Q_I`` (inner raceway), ``Q_A`` (rib), ``Q_CR1``, ``Q_CR2`` (pocket walls),
``Q_SIDE`` (the cage's side beams).  **Cage outputs** ``(n, CAGE_OUT)``: each row's cage angle
``CAGE_ANGLE`` and its rate ``CAGE_RATE``.

**Defect table** ``(n, D_WIDTH)``, one defect a row (:mod:`.defects`): ``D_KIND`` (a value of
:data:`KINDS`), ``D_ROW`` (the row's index, from 0), ``D_START`` and ``D_TAU`` (the window, rad),
``D_DEPTH`` (A of Eq. 14), ``D_S1, D_S2`` (the stretch of the contact line it covers),
``D_ROLLER`` (the roller's index for a roller defect), ``D_RHO, D_EDGE, D_RADIUS`` (the edges'
path: ``rho = r_b + r_e`` or 0 for the half-sine, ``r_e``, the raceway radius).

**Roller records** ``(n Z, REC)`` (:mod:`.evaluate`): what one roller's contacts do.  ``REC_F``
and ``REC_M`` (three slots each): the force on the roller (its weight first, then each contact's
in order) and the moment about its centre; then for each contact slot ``C_*`` the load it puts
on its other body (``REC_LOAD + C_LOAD * c``: force, then moment about that body's centre):
``C_OUTER`` the outer raceway and ``C_OUTER_RIB`` a rib of the outer ring (on the outer ring),
``C_INNER`` the inner raceway and ``C_INNER_RIB`` a rib of the inner ring (on the inner ring),
``C_WALL_1``, ``C_WALL_2`` the pocket walls and ``C_SIDE_1``, ``C_SIDE_2`` the side beams (on
the cage).  The sums add the slots roller by roller in this order (:data:`OUTER_SLOTS` ...),
the order of the paper's Eq. (16) as the kernel has always summed it, so that the loads do not
depend on how a model's parts are grouped.  ``REC_ORBIT``: the roller's pull on a
quasi-dynamic cage's rotation; ``REC_SPIN``: its pockets' damping of the cage's rotation (the
cage's block entry, for the quasi-dynamic spin step).

**Implicit blocks** ``(n Z, 6, BLK)`` (:mod:`.blocks`): a roller's contact damping (and
stiffness, friction) in its own rates (columns ``BLK_ROLLER +`` the rate slot), coupled to its
cage's rates (``BLK_CAGE +`` the cage slot) and in the cage's own (``BLK_CAGE_CAGE +``, the
roller's share; the row's whole cage block ``(n, 6, 6)`` is summed as the contacts come); rows
by the roller's rate slot.  ``BLK_NONE``, ``BLK_OWN``, ``BLK_COUPLED``: which of them a
roller's flag says it filled.

**Parameter vector**: the slots every model fills, ``Z .. N_COMMON - 1`` (the parts a model
shares: roller and cage dynamics, pockets, contact laws, :mod:`.roller`, :mod:`.pocket`,
:mod:`axlebox.bearing.kernel.contact`); a model's own slots follow from ``N_COMMON`` (its module).
"""
from __future__ import annotations

from collections import namedtuple
from math import cos, pi, sin

import numpy as np

from axlebox._numba import kernel

# --- state ------------------------------------------------------------------------------------
RHO, PHI, ETA, TH_T, TH_S, PSI = range(6)            # roller positions
CX, CY, CZ, CTX, CTZ, CPHI = range(6)                # cage positions
RATE = 6                                             # a position's rate: RATE + its slot
N_ROLLER = N_CAGE = 12

# --- the rings ----------------------------------------------------------------------------------
INNER, OUTER, RINGS = 0, 1, 2
U_X, U_Y, U_Z, TH_X, TH_Y, TH_Z, V_X, V_Y, V_Z, W_X, W_Y, W_Z, RING = range(13)
F_X, F_Y, F_Z, M_X, M_Y, M_Z, LOAD = range(7)

# --- contact forces and cage outputs --------------------------------------------------------------
Q_O, Q_I, Q_A, Q_CR1, Q_CR2, Q_SIDE, N_Q = range(7)
Q_NAMES = ("outer_raceway", "inner_raceway", "rib", "pocket_1", "pocket_2", "side_beams")
CAGE_ANGLE, CAGE_RATE, CAGE_OUT = 0, 1, 2

# --- defect table ------------------------------------------------------------------------------
(D_KIND, D_ROW, D_START, D_TAU, D_DEPTH, D_S1, D_S2, D_ROLLER, D_RHO, D_EDGE, D_RADIUS,
 D_WIDTH) = range(12)
OUTER_RING, INNER_RING, ROLLER_SURFACE = 0.0, 1.0, 2.0
KINDS = {"outer": OUTER_RING, "inner": INNER_RING, "roller": ROLLER_SURFACE}

# --- roller records and implicit blocks --------------------------------------------------------
C_OUTER, C_OUTER_RIB, C_INNER, C_INNER_RIB, C_WALL_1, C_WALL_2, C_SIDE_1, C_SIDE_2, N_C = range(9)
OUTER_SLOTS, INNER_SLOTS = (C_OUTER, C_OUTER_RIB), (C_INNER, C_INNER_RIB)
CAGE_SLOTS = (C_WALL_1, C_WALL_2, C_SIDE_1, C_SIDE_2)
C_FORCE, C_MOMENT, C_LOAD = 0, 3, 6                     # a contact's load: force, moment
REC_F, REC_M, REC_LOAD = 0, 3, 6
REC_ORBIT = REC_LOAD + C_LOAD * N_C
REC_SPIN, REC = REC_ORBIT + 1, REC_ORBIT + 2
BLK_ROLLER, BLK_CAGE, BLK_CAGE_CAGE, BLK = 0, 6, 12, 18
BLK_NONE, BLK_OWN, BLK_COUPLED = 0, 1, 2
#: what one roller's contacts write, passed as one (bearing/kernel/evaluate.py makes it a roller):
#: its record ``rec`` (REC,), the bearing's block rows ``blk`` (n Z, 6, BLK) and their flags
#: ``flag`` (n Z), its row's cage block ``cblk`` (6, 6), and ``jk``, its index in ``blk`` and
#: ``flag``
Touch = namedtuple("Touch", ["rec", "blk", "cblk", "flag", "jk"])

# --- the parameter slots every model fills ----------------------------------------------------------
# Z rollers a row; N_ROWS the rows; R_M pitch radius; R_B roller radius; L_B roller length; CAM,
# SAM the roller axis's angle from the bearing axis; ROW the rows' axial spacing (row_y); masses
# and inertias; the pockets (CAC, SAC slope, S_P, S_PA half clearances, K_CR their line
# stiffness), friction; the damping law; gravity; the cage's mode (KINEMATIC: 0 free, 1 Eq. 2,
# 2 the quasi-dynamic bearing's) and Eq. 2's ratio (RATIO)
(Z, N_ROWS, R_M, R_B, L_B, CAM, SAM, ROW, M_R, J_RA, J_RD, M_C, J_CP, J_CD, CAC, SAC, S_P, S_PA, K_CR,
 MU_C, V_S, LAW, ZETA, C_RULE, BETA, G_X, G_Y, G_Z, KINEMATIC, RATIO, N_COMMON) = range(31)
FREE_CAGE, EQ2_CAGE, POCKET_CAGE = 0.0, 1.0, 2.0         # KINEMATIC's values
DAMPING_LAWS = ("ratio", "paper", "stiffness")           # LAW's values, by index


def n_state(Z_: int, rows: int) -> int:
    """The states of a bearing of ``rows`` rows of ``Z_`` rollers."""
    return rows * (Z_ * N_ROLLER + N_CAGE)


def rows_of(n: int, Z_: int) -> int:
    """The rows of a bearing of ``Z_`` rollers a row whose state has ``n`` entries."""
    return n // (Z_ * N_ROLLER + N_CAGE)


def views(y, Z_: int):
    """``(rollers (n, Z, N_ROLLER), cages (n, N_CAGE))`` views into the state vector ``y`` of a
    bearing of ``n`` rows (the rows counted from its size)."""
    rows = rows_of(y.shape[0], Z_)
    nr = rows * Z_ * N_ROLLER
    return y[:nr].reshape(rows, Z_, N_ROLLER), y[nr:nr + rows * N_CAGE].reshape(rows, N_CAGE)


@kernel
def row_sign(j, rows):
    """``s`` of row ``j`` of ``rows``: +1 for the rows on the -y side of the bearing's centre (and
    a middle one), -1 for those on the +y side, whose rollers lean the other way (the
    back-to-back arrangement, bearing/models/dtrb.py)."""
    return 1.0 if 2 * j < rows else -1.0


@kernel
def row_y(j, rows, spacing):
    """The axial place of row ``j`` of ``rows`` at ``spacing`` from the centre a row (``row_offset``):
    ``(2 j + 1 - rows) spacing``, so two rows at ``-+ spacing``, one at the centre."""
    return (2 * j + 1 - rows) * spacing


def pack_common(v, p, gravity) -> None:
    """Fill the shared slots of ``v`` from ``p`` (any model's parameters with the shared fields:
    rollers, pitch, the roller axis's angle ``alpha_m`` from the bearing axis, cage, pockets,
    masses, damping, friction)."""
    from ..statics.stiffness import e_prime, k_line
    J_ra, J_rd = p.J_r
    J_cp, J_cd = p.J_c
    v[[Z, N_ROWS, R_M, R_B, L_B, CAM, SAM, ROW]] = (p.Z, p.rows, 0.5 * p.D_m, p.r_b, p.L_b,
                                                    cos(p.alpha_m), sin(p.alpha_m), p.row_offset)
    v[[M_R, J_RA, J_RD, M_C, J_CP, J_CD]] = p.M_r, J_ra, J_rd, p.M_c, J_cp, J_cd
    v[[CAC, SAC, S_P, S_PA]] = cos(p.alpha_c), sin(p.alpha_c), 0.5 * p.s_p, 0.5 * p.s_pa
    v[K_CR] = k_line(e_prime(p.E_r, p.nu_r, p.E_c, p.nu_c), p.L_b)
    v[[MU_C, V_S]] = p.mu_cage, p.v_s
    v[[LAW, ZETA, C_RULE, BETA]] = DAMPING_LAWS.index(p.damping), p.zeta, p.c_rule, p.beta
    v[[G_X, G_Y, G_Z]] = gravity
    quasi = p.model == "quasi-dynamic"
    v[KINEMATIC] = EQ2_CAGE if p.cage == "kinematic" else (POCKET_CAGE if quasi else FREE_CAGE)
    v[RATIO] = 0.5 * (1.0 - p.gamma)      # paper Eq. (2): omega_c = (1 - D_b/D_m) omega_w / 2


def nominal_state(p, omega_w: float = 0.0) -> np.ndarray:
    """Rollers centred in their pockets on the pitch circle, rolling without slip at the
    inner-ring speed ``omega_w`` (rad/s) with the outer ring at rest; cages concentric (any
    model's parameters ``p``: ``Z, D_m, r_b`` and the contact angles ``alpha_o, alpha_i,
    alpha_m``)."""
    y = np.zeros(n_state(p.Z, p.rows))
    rol, cag = views(y, p.Z)
    R, r = 0.5 * p.D_m, p.r_b
    R_i, R_o = R - r * cos(p.alpha_i), R + r * cos(p.alpha_o)
    w_c = omega_w * R_i / (R_i + R_o)                 # epicyclic cage speed of this geometry
    k_cos = cos(p.alpha_o - p.alpha_m)
    for j in range(p.rows):
        s = row_sign(j, p.rows)
        rol[j, :, PHI] = 2 * pi * np.arange(p.Z) / p.Z
        rol[j, :, RATE + PHI] = w_c
        rol[j, :, RATE + PSI] = -s * w_c * R_o / (r * k_cos)     # no slip at the cup
        cag[j, RATE + CPHI] = w_c
    return y


def ring_motion(omega_w: float, uo=(0.0, 0.0, 0.0), t: float = 0.0):
    """A ring motion: the inner ring at the origin turning at ``omega_w`` (its angle at ``t``),
    the outer ring at rest displaced by ``uo``."""
    ring = np.zeros((RINGS, RING))
    ring[INNER, TH_Y] = omega_w * t
    ring[INNER, W_Y] = omega_w
    ring[OUTER, U_X:U_Z + 1] = uo
    return ring
