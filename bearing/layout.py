"""Plain-array layout of the DTRB model: the parameter vector, the state vector, the defect table.

The numba kernel (:mod:`.kernel`) sees only float arrays; this module is the one place that
says what each slot holds, and packs a :class:`BearingParams` into them.

State, one bearing (``n_state(Z) = 24 Z + 24``):

* rollers ``(2, Z, 12)``: ``rho, phi, eta, theta_t, theta_s, psi`` and their rates.  ``rho`` and
  ``eta`` are the radial and axial displacement of the roller centre from its nominal place on
  the pitch circle, ``phi`` its azimuth (from +z towards +x, paper Eq. 2), ``theta_t`` its tilt
  about the tangent ``e_t``, ``theta_s`` its skew about ``b`` (normal to the roller axis in the
  axial plane), ``psi`` its spin about its own axis relative to the orbiting frame.  The rate
  slot of ``psi`` holds the spin speed ``omega_s``.
* cages ``(2, 12)``: ``x, y, z, theta_x, theta_z, phi_c`` and their rates.

Ring motion, one ring a row of ``ring (2, 12)`` (0 inner, 1 outer):
``u_x, u_y, u_z, theta_x, theta_y, theta_z, v_x, v_y, v_z, omega_x, omega_y, omega_z``;
``theta_y`` is the ring's angle about the bearing axis (the wheelset spin for the inner ring)
and ``omega_y`` its spin speed.

Defect table ``(n, 8)``: ``kind, row, start, tau, A, s1, s2, spare`` (see :mod:`.defects`).
"""
from __future__ import annotations

from math import cos, pi, sin

import numpy as np

from .params import DAMPING_LAWS
from .stiffness import contacts

# --- parameter vector slots ---------------------------------------------------------------
(Z, R_M, R_B, L_E, L_B, CAO, SAO, CAI, SAI, CAF, SAF, CAM, SAM, CAC, SAC, ROW, C_O, H_R,
 K_O, K_I, K_A, K_CR, S_P, S_PA, M_R, J_RA, J_RD, M_C, J_CP, J_CD, MU_R, MU_A, MU_C, V_S,
 LAW, ZETA, C_RULE, BETA, KINEMATIC, RATIO, GX, GY, GZ, QUASI, N_P) = range(45)

# --- state slots ------------------------------------------------------------------------------
RHO, PHI, ETA, TH_T, TH_S, PSI = range(6)           # roller positions; +6 for the rates
CX, CY, CZ, CTX, CTZ, CPHI = range(6)               # cage positions; +6 for the rates
N_ROLLER, N_CAGE = 12, 12

# --- contact-force output slots (2, Z, N_Q) ------------------------------------------------
Q_O, Q_I, Q_A, Q_CR1, Q_CR2, Q_SIDE, N_Q = range(7)

KINDS = {"outer": 0, "inner": 1, "roller": 2}   # defect kinds: the table's first column


def n_state(Z_: int) -> int:
    return 2 * Z_ * N_ROLLER + 2 * N_CAGE


def pack(p, gravity=(0.0, 0.0, -9.81)) -> np.ndarray:
    """The parameter vector of ``p`` (a :class:`BearingParams`) for the kernel."""
    k = contacts(p)
    J_ra, J_rd = p.J_r
    J_cp, J_cd = p.J_c
    v = np.zeros(N_P)
    v[[Z, R_M, R_B, L_E, L_B]] = p.Z, 0.5 * p.D_m, p.r_b, p.L_e, p.L_b
    v[[CAO, SAO, CAI, SAI]] = cos(p.alpha_o), sin(p.alpha_o), cos(p.alpha_i), sin(p.alpha_i)
    v[[CAF, SAF, CAM, SAM]] = cos(p.alpha_f), sin(p.alpha_f), cos(p.alpha_m), sin(p.alpha_m)
    v[[CAC, SAC, ROW, C_O, H_R]] = cos(p.alpha_c), sin(p.alpha_c), p.row_offset, p.clearance_n, p.h_r
    v[[K_O, K_I, K_A, K_CR]] = k["K_ro"], k["K_ri"], k["K_a"], k["K_cr"]
    v[[S_P, S_PA]] = 0.5 * p.s_p, 0.5 * p.s_pa
    v[[M_R, J_RA, J_RD, M_C, J_CP, J_CD]] = p.M_r, J_ra, J_rd, p.M_c, J_cp, J_cd
    v[[MU_R, MU_A, MU_C, V_S]] = p.mu_race, p.mu_rib, p.mu_cage, p.v_s
    v[[LAW, ZETA, C_RULE, BETA]] = DAMPING_LAWS.index(p.damping), p.zeta, p.c_rule, p.beta
    quasi = p.model == "quasi-dynamic"
    # KINEMATIC: 0 a free cage, 1 Eq. 2's, 2 the quasi-dynamic bearing's (rollers centred in their
    # pockets, the cage's rotation a state carrying their orbital inertia: bearing/quasidynamic.py)
    v[KINEMATIC] = 1.0 if p.cage == "kinematic" else (2.0 if quasi else 0.0)
    v[QUASI] = quasi
    v[RATIO] = 0.5 * (1.0 - p.gamma)         # paper Eq. (2): omega_c = (1 - D_b/D_m) omega_w / 2
    v[[GX, GY, GZ]] = gravity
    return v


def views(y: np.ndarray, Z_: int):
    """``(rollers (2, Z, 12), cages (2, 12))`` views into a state vector."""
    nr = 2 * Z_ * N_ROLLER
    return y[:nr].reshape(2, Z_, N_ROLLER), y[nr:nr + 2 * N_CAGE].reshape(2, N_CAGE)


def nominal_state(p, omega_w: float = 0.0) -> np.ndarray:
    """Rollers centred in their pockets on the pitch circle, rolling without slip at the
    inner-ring speed ``omega_w`` (rad/s) with the outer ring at rest; cages concentric."""
    y = np.zeros(n_state(p.Z))
    rol, cag = views(y, p.Z)
    R, r = 0.5 * p.D_m, p.r_b
    R_i, R_o = R - r * cos(p.alpha_i), R + r * cos(p.alpha_o)
    w_c = omega_w * R_i / (R_i + R_o)                 # epicyclic cage speed of this geometry
    k_cos = cos(p.alpha_o - p.alpha_m)
    for j, s in enumerate((1.0, -1.0)):
        rol[j, :, PHI] = 2 * pi * np.arange(p.Z) / p.Z
        rol[j, :, 6 + PHI] = w_c
        rol[j, :, 6 + PSI] = -s * w_c * R_o / (r * k_cos)     # no slip at the cup
        cag[j, 6 + CPHI] = w_c
    return y
