"""The quasi-dynamic DTRB (``[bearing] model = "quasi-dynamic"``): the rollers without radial,
axial and tilt inertia, for studies and datasets; the dynamic model stays the reference.

Kept from the paper's model: the same line contacts of the raceways and pockets (Eqs. 1, 3-4,
9-11), the rib contact (Eqs. 3c, 4b, 8), the Eq. (14) defects (outer, inner, roller), gravity,
the orbit's centrifugal and gyroscopic loads (Eq. 12's), and the traction law (regularised
Coulomb) that sets the slip.  Dropped: the rollers' radial, axial and tilt inertia (their modes
between the raceways, 21-23 kHz, hold the dynamic model's step near 1e-5 s), the cage's
translation and tilt (held centred on the inner ring), the rollers' skew (held at zero: inside
the pocket's clearance only the friction's small moments act on it, so a quasi-static skew has
no equilibrium short of the pocket walls) and their play in the pockets.  This is the
quasi-dynamic analysis of Harris and Kotzalas (Advanced Concepts of Bearing Technology, 5th ed.,
CRC 2006, ch. 3: each rolling element's equilibrium with its inertial loads at the bearing's
speeds) with the cage and spins kept as states, as Gupta's dynamic models keep them; the paper
(its introduction) says a quasi-dynamic model cannot show a defect's mechanism, and
benchmarks/README.md measures how much this one misses against the dynamic model.

A step of ``h`` (:func:`equilibrium`, then :func:`spin_step`):

1. **Contact equilibrium.**  Every roller's radial place ``rho``, axial place ``eta`` and tilt
   ``theta_t`` solve ``a_rho = a_eta = a_theta_t = 0``: the dynamic model's accelerations
   (kernel.py, Eq. 12) with those rates the step's backward differences (the contacts' damping
   then sees the roller follow the rings: implicit Euler on a massless, damped roller), so that
   the centrifugal and gyroscopic loads stay and the inertia of those DOFs goes.  Newton's
   method, each roller's 3 x 3 block the kernel's exact contact stiffness and damping,
   ``K + C / h`` (the rows :func:`.kernel.dtrb_rhs_damped` makes for the "imex2" kick, at
   ``h_k = h``), so an evaluation gives the residual and the next Jacobian at once; a roller
   touches only the rings and its own pocket, so the blocks do not couple and each roller
   iterates on its own: an evaluation takes only the rollers that moved
   (:func:`.kernel.dtrb_rhs_part`; the others keep their loads).  A roller whose residual
   grows takes half its step back (a line search per roller).  The step of an
   iteration is capped (a roller out of contact has no stiffness to divide by) and a block with
   no stiffness in a direction gets a floor there (:data:`J_FLOOR`).
2. **Spins and cage.**  The rollers sit centred in their pockets (roller k at the cage's
   ``phi_c + 2 pi k / Z``) and the cage's rotation carries their orbital inertia,
   ``(J_cp + Z M_r R^2) phi_c'' = sum_k F_t,k (R + rho_k)`` plus the pockets' and side beams'
   moment (bearing/layout.py ``KINEMATIC`` 2).  The traction drives the spins ``omega_s`` and
   the cage rate stiffly (the friction's secant damping ``mu Q / v_s`` on a roller's axial
   inertia is a rate of about 4e4 /s), so they take a linearly implicit Euler step, their
   Jacobian the friction's secant damping from the same blocks (:func:`spin_step`).  A row's
   system is an arrowhead (a spin couples only to its own cage) and is solved in O(Z).
3. ``psi += h omega_s``, ``phi_c += h phi_c'``.

Cost: about 1.25 evaluations of the whole right-hand side a step (one of every roller, then the
quarter of them that Newton moved; measured on the rig with a 1 um, 600 Hz ring vibration at
5e-5 s: 1.24 on average, and 1.2-1.35 on the validation car's eight bearings); solved as one
system, the rollers took 2.05 evaluations a step on the rig and 3-5 on the car, where a roller
at a contact's kink held the whole bearing's iterations (benchmarks/README.md).  No roller mode
limits the step, only accuracy (:data:`DT_MAX`).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .kernel import N_PART, dtrb_rhs_part
from .layout import (ETA, J_CP, J_RA, J_RD, KINEMATIC, L_B, M_R, N_CAGE, N_ROLLER, PHI, PSI, R_M,
                     RHO, TH_S, TH_T, Z)

DT_MAX = 1e-4           # s: the step is held by accuracy (the defect's passage), not stability
MAX_IT = 8              # Newton iterations at most a step
MAX_HALVE = 12          # halvings of a roller's Newton step at most
SLOTS = (RHO, ETA, TH_T)                 # the positions solved, and their accelerations' slots
TOL = (1e-10, 1e-10, 1e-8)               # converged when every update is below these,
F_TOL = 30.0            # N: or every roller's residual force is below this (a roller off a
                        # raceway, pushed by its centrifugal force and weight alone, 3-8 N, need
                        # not find it: the kink at first touch stalls Newton, and it carries
                        # nothing; a loaded roller carries 1e3-1e4 N)
CAP = (5e-6, 5e-6, 5e-4)                 # an iteration moves a roller at most this far
J_FLOOR = 1e6           # 1/s^2: the least stiffness a direction is given (over mass), far below
                        # a loaded contact's (about 1e9 N/m over 0.135 kg)
TWO_PI = 2.0 * np.pi


def n_buffer(nz: int, n_state: int) -> int:
    """Floats of scratch :func:`equilibrium` and :func:`spin_step` need (bearing/advance.py's
    ``G`` holds them)."""
    return _B_END * nz


# where equilibrium's and spin_step's scratch lie in ``buf``, in units of Z floats (the first
# six hold one roller's 3 x 3 block, residual and step, 15 floats: Z is at least 3)
_B_W, _B_DQ, _B_LAM, _B_M0, _B_ARROW, _B_Q0, _B_ACT, _B_NIT, _B_NH, _B_DONE, _B_PARTS = (
    0, 6, 12, 14, 16, 20, 26, 28, 30, 32, 34)
_B_END = _B_PARTS + 2 * N_PART


@njit(cache=True)
def _hold(x, nz):
    """The held DOFs: rollers centred in their pockets (azimuth, orbit rate), no skew; the cages
    centred on the inner ring.  (The solved positions' rates are :func:`equilibrium`'s.)"""
    nr = 2 * nz * N_ROLLER
    for j in range(2):
        cb = nr + j * N_CAGE
        for q in range(5):
            x[cb + q] = 0.0
            x[cb + 6 + q] = 0.0
        for k in range(nz):
            b0 = (j * nz + k) * N_ROLLER
            x[b0 + PHI] = x[cb + 5] + TWO_PI * k / nz
            x[b0 + TH_S] = 0.0
            x[b0 + 6 + PHI] = x[cb + 11]
            x[b0 + 6 + TH_S] = 0.0


@njit(cache=True)
def _solve3(J, r, dq):
    """``dq = -J^-1 r`` for a 3 x 3 block (Cramer; the floor keeps it regular)."""
    a, b, c = J[0], J[1], J[2]
    d, e, f = J[3], J[4], J[5]
    g, h, i = J[6], J[7], J[8]
    A = e * i - f * h
    B = -(d * i - f * g)
    C = d * h - e * g
    det = a * A + b * B + c * C
    if not abs(det) > 1e-300:                        # degenerate: the diagonal alone (floored)
        dq[0], dq[1], dq[2] = -r[0] / a, -r[1] / e, -r[2] / i
        return
    inv = -1.0 / det
    dq[0] = inv * (A * r[0] + (c * h - b * i) * r[1] + (b * f - c * e) * r[2])
    dq[1] = inv * (B * r[0] + (a * i - c * g) * r[1] + (c * d - a * f) * r[2])
    dq[2] = inv * (C * r[0] + (b * g - a * h) * r[1] + (a * e - b * d) * r[2])


@njit(cache=True)
def _merit(dx, b0, w_t):
    """A roller's squared residual, its tilt row turned into a force at the roller's end."""
    a, b, c = dx[b0 + 6 + RHO], dx[b0 + 6 + ETA], dx[b0 + 6 + TH_T] * w_t
    return a * a + b * b + c * c


@njit(cache=True)
def _block(Gb, P, h, J, j, kk):
    """Roller kk of row j's 3 x 3 block of d(a_rho, a_eta, a_theta_t) / d(rho, eta, theta_t),
    the rates the backward differences ``(q - q_0) / h``, from the kernel's rows
    ``Gb = C + h K``: ``-(K + C / h) / m`` with m the DOF's mass or inertia, floored."""
    m = (P[M_R], P[M_R], P[J_RD])
    rows = (0, 2, 3)                       # rho, eta, theta_t among a roller's six rates
    for q in range(3):
        for c in range(3):
            J[3 * q + c] = -Gb[j, kk, rows[q], rows[c]] / (m[q] * h)
        if J[4 * q] > -J_FLOOR:
            J[4 * q] = -J_FLOOR


@njit(inline="always")
def _balanced(m, P):
    """Whether a roller of residual ``m`` (:func:`_merit`, in accelerations) is balanced: its
    residual force below :data:`F_TOL` (then Newton leaves it where it is)."""
    return m * P[M_R] * P[M_R] < F_TOL * F_TOL


@njit(cache=True)
def equilibrium(t, x, ring, P, D, h, dx, F, Qc, Gb, buf):
    """Step 1 (module docstring): every roller's ``rho, eta, theta_t`` in contact equilibrium
    with the rings ``ring`` (2, 12) at the end ``t`` of a step of ``h``, their rates the
    step's backward differences (implicit Euler: the contacts' damping sees the roller move with
    the rings; with the rates held at zero it saw the rings' whole velocity, and a flexible axle
    box's vibration stalled Newton on the damping's kinks); ``dx`` left with the state's
    derivative there (the spins' and cages' accelerations), ``F`` (2, 6) the ring loads, ``Qc``
    (2, Z, 6) the contact forces, ``Gb`` the kernel's blocks (:func:`spin_step` takes its
    friction rows).  ``buf``: :func:`n_buffer` floats.

    Newton's method roller by roller: the rollers do not couple (each touches the rings and its
    own pocket), so each iterates on its own, and an evaluation of the right-hand side takes
    only the rollers that moved (:func:`.kernel.dtrb_rhs_part`; the others keep their loads):
    a roller balanced at the step's first evaluation costs nothing more, and a roller that
    stalls at a contact's kink costs only itself.  A roller whose residual grew takes half its
    step back, up to :data:`MAX_HALVE` times (a roller off a raceway has only the floor's
    stiffness, and its full step would carry it deep into the raceway); it stops when it is
    :func:`_balanced`, when its update was below :data:`TOL` (once evaluated there) or after
    :data:`MAX_IT` updates.  Returns the evaluations taken, counted in whole bearings (the
    rollers evaluated over 2 Z)."""
    nz = int(P[Z])
    nr = 2 * nz
    dq = buf[_B_DQ * nz:(_B_DQ + 6) * nz]
    lam = buf[_B_LAM * nz:(_B_LAM + 2) * nz]
    m0 = buf[_B_M0 * nz:(_B_M0 + 2) * nz]
    q0 = buf[_B_Q0 * nz:(_B_Q0 + 6) * nz]        # the positions at the step's start
    active = buf[_B_ACT * nz:(_B_ACT + 2) * nz]
    n_it = buf[_B_NIT * nz:(_B_NIT + 2) * nz]    # Newton updates a roller has taken
    n_h = buf[_B_NH * nz:(_B_NH + 2) * nz]       # its halvings in this line search
    done = buf[_B_DONE * nz:(_B_DONE + 2) * nz]  # its last update was below TOL
    parts = buf[_B_PARTS * nz:(_B_PARTS + 2 * N_PART) * nz].reshape(2, nz, N_PART)
    J = buf[_B_W * nz:_B_W * nz + 9]               # scratch in buf: no allocation a step
    r = buf[_B_W * nz + 9:_B_W * nz + 12]
    d = buf[_B_W * nz + 12:_B_W * nz + 15]
    w_t = 2.0 * P[J_RD] / (P[M_R] * P[L_B])
    _hold(x, nz)
    for k in range(nr):
        for q in range(3):
            q0[3 * k + q] = x[k * N_ROLLER + SLOTS[q]]
            x[k * N_ROLLER + 6 + SLOTS[q]] = 0.0
        active[k] = 1.0
        lam[k] = 0.0
        n_it[k] = 0.0
        n_h[k] = 0.0
        done[k] = 0.0
    # each evaluation gives the residual and the evaluated rollers' exact contact stiffness and
    # damping (the "imex2" rows at h_k = h: C + h K)
    dtrb_rhs_part(t, x, ring, P, D, dx, F, Qc, Gb, h, None, parts)
    evaluated = nr
    for _pass in range(MAX_IT * (MAX_HALVE + 1)):
        n_active = 0
        for k in range(nr):
            if active[k] == 0.0:
                continue
            b0 = k * N_ROLLER
            m = _merit(dx, b0, w_t)
            if lam[k] > 0.0:                            # its last update's line search
                if m > m0[k] and n_h[k] < MAX_HALVE:
                    lam[k] *= 0.5
                    n_h[k] += 1.0
                    for q in range(3):
                        x[b0 + SLOTS[q]] -= lam[k] * dq[3 * k + q]
                        x[b0 + 6 + SLOTS[q]] = (x[b0 + SLOTS[q]] - q0[3 * k + q]) / h
                    n_active += 1
                    continue
                lam[k] = 0.0                            # accepted
            if done[k] != 0.0 or _balanced(m, P) or n_it[k] >= MAX_IT:
                active[k] = 0.0
                continue
            for q in range(3):
                r[q] = dx[b0 + 6 + SLOTS[q]]
            _block(Gb, P, h, J, k // nz, k % nz)
            _solve3(J, r, d)
            small = True
            for q in range(3):
                dq[3 * k + q] = min(max(d[q], -CAP[q]), CAP[q])
                x[b0 + SLOTS[q]] += dq[3 * k + q]
                x[b0 + 6 + SLOTS[q]] = (x[b0 + SLOTS[q]] - q0[3 * k + q]) / h
                if abs(dq[3 * k + q]) > TOL[q]:
                    small = False
            done[k] = 1.0 if small else 0.0
            m0[k] = m
            lam[k] = 1.0
            n_h[k] = 0.0
            n_it[k] += 1.0
            n_active += 1
        if n_active == 0:
            break
        dtrb_rhs_part(t, x, ring, P, D, dx, F, Qc, Gb, h, active, parts)
        evaluated += n_active
    return evaluated / nr


@njit(cache=True)
def spin_step(x, P, h, dx, Gb, buf):
    """Steps 2 and 3 (module docstring): the spins and cage rates by a linearly implicit Euler
    step of ``h`` from the accelerations ``dx`` and the blocks ``Gb`` :func:`equilibrium` left,
    then the spin angles and cage azimuths.

    The step's Jacobian is the friction's secant damping the kernel put in ``Gb`` (the rows
    of the implicit kick, bearing/implicit.py: a contact's ``c J^T J`` over a roller's rates
    ``(rho', phi', eta', theta_t', theta_s', omega_s)`` and the cage's ``(..., phi_c')``; the
    normal contacts add nothing to the spin and orbit rows, whose rates do not move a raceway
    contact's approach).  With the roller's orbit rate the cage's, a row's unknowns are its
    spins ``omega_k`` and cage rate ``Omega``::

        J_a  d(omega_k)/dt:  d/d omega_k = -G_k[5, 5],  d/d Omega = -(G_k[5, 1] + G_k[5, 11])
        J_orb d(Omega)/dt:   d/d omega_k = -(G_k[1, 5] + G_k[5, 11]),
                             d/d Omega = -(sum_k G_k[1, 1] + 2 G_k[1, 11]) - G_cage[5, 5]

    (``J_orb = J_cp + Z M_r R^2``): the secant, not the tangent, of the regularised Coulomb law,
    as the dynamic model's "imex2" kick takes it: at least as damped, so the step stays stable
    at any slip.  A row's system is an arrowhead (a spin couples only to its own cage), solved in
    O(Z); no further evaluation of the right-hand side."""
    nz = int(P[Z])
    nr = 2 * nz * N_ROLLER
    free = P[KINEMATIC] == 2.0                       # the cage's rotation a state (else Eq. 2's)
    arrow = buf[_B_ARROW * nz:(_B_ARROW + 4) * nz]   # per roller: 1 - h d_k, b_k
    Ja = P[J_RA]
    J_orb = P[J_CP] + nz * P[M_R] * P[R_M] * P[R_M]
    for j in range(2):
        cb = nr + j * N_CAGE
        e = -Gb[j, nz, 5, 5]
        for k in range(nz):
            e -= Gb[j, k, 1, 1] + 2.0 * Gb[j, k, 1, 11]
        e = e / J_orb if free else 0.0
        lhs = 1.0 - h * e
        rhs = h * dx[cb + 11] if free else 0.0
        for k in range(nz):
            b0 = (j * nz + k) * N_ROLLER
            w = b0 + 6 + PSI
            d = -Gb[j, k, 5, 5] / Ja
            b = -(Gb[j, k, 5, 1] + Gb[j, k, 5, 11]) / Ja
            c = -(Gb[j, k, 1, 5] + Gb[j, k, 5, 11]) / J_orb if free else 0.0
            p = 1.0 - h * d
            arrow[2 * (j * nz + k)] = p
            arrow[2 * (j * nz + k) + 1] = b
            lhs -= h * h * c * b / p
            rhs += h * h * c * dx[w] / p
        dc = rhs / lhs if free else 0.0
        x[cb + 11] += dc
        for k in range(nz):
            b0 = (j * nz + k) * N_ROLLER
            w = b0 + 6 + PSI
            p, b = arrow[2 * (j * nz + k)], arrow[2 * (j * nz + k) + 1]
            x[w] += (h * dx[w] + h * b * dc) / p
            x[b0 + PSI] += h * x[w]
        if free:
            x[cb + 5] += h * x[cb + 11]
        else:
            x[cb + 5] += h * dx[cb + 5]              # Eq. 2's rate, as the kernel gave it
