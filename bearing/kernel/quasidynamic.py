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
   ``K + C / h`` (the rows bearing/kernel/blocks.py makes for the "imex2" kick, at ``h_k = h``), so an
   evaluation gives the residual and the next Jacobian at once; a roller touches only the
   rings and its own pocket, so the blocks do not couple and each roller iterates on its own:
   an evaluation takes only the rollers that moved (:func:`.evaluate.roller`, the same part the
   dynamic model's evaluation calls; the others keep their records), and the sums are made from
   the records once Newton is done.  A roller whose residual
   grows takes half its step back (a line search per roller).  The step of an
   iteration is capped (a roller out of contact has no stiffness to divide by) and a block with
   no stiffness in a direction gets a floor there (:data:`J_FLOOR`).
2. **Spins and cage.**  The rollers sit centred in their pockets (roller k at the cage's
   ``phi_c + 2 pi k / Z``) and the cage's rotation carries their orbital inertia,
   ``(J_cp + Z M_r R^2) phi_c'' = sum_k F_t,k (R + rho_k)`` plus the pockets' and side beams'
   moment (bearing/kernel/layout.py ``POCKET_CAGE``).  The traction drives the spins ``omega_s`` and
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
limits the step, only accuracy (bearing/models/params.py ``QD_DT_MAX``).
"""
from __future__ import annotations

from math import pi

from axlebox._numba import kernel

from ..defects import count
from .blocks import BLK_NONE
from .evaluate import ring_loads, roller
from .layout import (
    BLK_CAGE,
    BLK_CAGE_CAGE,
    BLK_COUPLED,
    BLK_ROLLER,
    CPHI,
    CTZ,
    ETA,
    INNER_RING,
    J_RA,
    J_RD,
    KINEMATIC,
    L_B,
    M_R,
    N_CAGE,
    N_ROLLER,
    PHI,
    POCKET_CAGE,
    PSI,
    RATE,
    REC_ORBIT,
    RHO,
    N_ROWS,
    ROLLER_SURFACE,
    TH_S,
    TH_T,
    Z,
)
from .roller import cage_frame, cage_rates, orbital_inertia, pocket_angles, ring_frame
from .step import cage_outputs
from .vec import copy3

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
TWO_PI = 2.0 * pi

# each roller's scratch (:data:`.evaluate.Work` ``qd``, one row a roller): its solved positions
# at the step's start (three slots), its last Newton update (three), the line search's step
# and the merit before it, its updates and halvings so far, whether its last update was below
# TOL, whether it is still iterating; the spin step's arrowhead entries
(QD_Q0, QD_DQ, QD_LAM, QD_M0, QD_NIT, QD_NH, QD_DONE, QD_ACTIVE, QD_P, QD_B, QD_WIDTH) = (
    0, 3, 6, 7, 8, 9, 10, 11, 12, 13, 14)


@kernel
def hold(x, nz, nrow):
    """The held DOFs: rollers centred in their pockets (azimuth, orbit rate), no skew; the cages
    centred on the inner ring.  (The solved positions' rates are :func:`equilibrium`'s.)"""
    for j in range(nrow):
        cb = nrow * nz * N_ROLLER + j * N_CAGE
        for q in range(CTZ + 1):                 # every cage position but its angle, CPHI
            x[cb + q] = 0.0
            x[cb + RATE + q] = 0.0
        for k in range(nz):
            b0 = (j * nz + k) * N_ROLLER
            x[b0 + PHI] = x[cb + CPHI] + TWO_PI * k / nz
            x[b0 + TH_S] = 0.0
            x[b0 + RATE + PHI] = x[cb + RATE + CPHI]
            x[b0 + RATE + TH_S] = 0.0


@kernel
def _merit(dx, b0, w_t):
    """A roller's squared residual, its tilt row turned into a force at the roller's end."""
    a, b, c = dx[b0 + RATE + RHO], dx[b0 + RATE + ETA], dx[b0 + RATE + TH_T] * w_t
    return a * a + b * b + c * c


@kernel
def _entry(blk, flag, jk, a, b, m, h):
    """Entry ``(a, b)`` of roller ``jk``'s Newton block, ``-(K + C / h) / m`` from the kernel's
    rows ``C + h K`` (none where the roller touched nothing)."""
    return 0.0 if flag[jk] == BLK_NONE else -blk[jk, a, BLK_ROLLER + b] / (m * h)


@kernel
def _step(blk, flag, jk, dx, b0, P, h):
    """Roller ``jk``'s Newton update of ``(rho, eta, theta_t)``: ``-J^-1 r`` with ``J`` its
    block of ``d(a_rho, a_eta, a_theta_t) / d(rho, eta, theta_t)`` (the rates the backward
    differences), each diagonal entry floored at ``-J_FLOOR``; Cramer's rule."""
    m_r, m_e, m_t = P[M_R], P[M_R], P[J_RD]
    a = min(_entry(blk, flag, jk, RHO, RHO, m_r, h), -J_FLOOR)
    b = _entry(blk, flag, jk, RHO, ETA, m_r, h)
    c = _entry(blk, flag, jk, RHO, TH_T, m_r, h)
    d = _entry(blk, flag, jk, ETA, RHO, m_e, h)
    e = min(_entry(blk, flag, jk, ETA, ETA, m_e, h), -J_FLOOR)
    f = _entry(blk, flag, jk, ETA, TH_T, m_e, h)
    g = _entry(blk, flag, jk, TH_T, RHO, m_t, h)
    k = _entry(blk, flag, jk, TH_T, ETA, m_t, h)
    i = min(_entry(blk, flag, jk, TH_T, TH_T, m_t, h), -J_FLOOR)
    r0, r1, r2 = dx[b0 + RATE + RHO], dx[b0 + RATE + ETA], dx[b0 + RATE + TH_T]
    A = e * i - f * k
    B = -(d * i - f * g)
    C = d * k - e * g
    det = a * A + b * B + c * C
    if not abs(det) > 1e-300:                        # degenerate: the diagonal alone (floored)
        return -r0 / a, -r1 / e, -r2 / i
    inv = -1.0 / det
    return (inv * (A * r0 + (c * k - b * i) * r1 + (b * f - c * e) * r2),
            inv * (B * r0 + (a * i - c * g) * r1 + (c * d - a * f) * r2),
            inv * (C * r0 + (b * g - a * k) * r1 + (a * e - b * d) * r2))


@kernel
def _balanced(m, P):
    """Whether a roller of residual ``m`` (:func:`_merit`, in accelerations) is balanced: its
    residual force below :data:`F_TOL` (then Newton leaves it where it is)."""
    return m * P[M_R] * P[M_R] < F_TOL * F_TOL


@kernel
def equilibrium(model, t, x, ring, P, D, h, w):
    """Step 1 (module docstring): every roller's ``rho, eta, theta_t`` in contact equilibrium
    with the rings ``ring`` at the end ``t`` of a step of ``h`` of the bearing ``model``, their
    rates the step's backward differences (implicit Euler: the contacts' damping sees the roller
    move with the rings; with the rates held at zero it saw the rings' whole velocity, and a
    flexible axle box's vibration stalled Newton on the damping's kinks); ``w`` (its
    :class:`.evaluate.Work`) left with the state's derivative ``dx`` (the spins' and cages'
    accelerations), the ring loads ``F``, the contact forces ``Qs`` and the blocks
    (:func:`spin_step` takes their friction rows).

    Newton's method roller by roller (:func:`_newton`).  Returns the evaluations taken,
    counted in whole bearings (the rollers evaluated over n Z, n the rows)."""
    nz, nrow = int(P[Z]), int(P[N_ROWS])
    hold(x, nz, nrow)
    rings = ring_frame(ring)
    n_inner, n_roller = count(D, INNER_RING), count(D, ROLLER_SURFACE)
    J_orb = orbital_inertia(P)
    cb = nrow * nz * N_ROLLER
    for j in range(nrow):      # the cages stay where hold put them while the rollers move
        pocket_angles(cage_frame(x, cb + j * N_CAGE, P, rings.omega).phi, nz, w.sin_p[j], w.cos_p[j])
    for jk in range(nrow * nz):
        s = w.qd[jk]
        b0 = jk * N_ROLLER
        for q in range(3):
            s[QD_Q0 + q] = x[b0 + SLOTS[q]]
            s[QD_DQ + q] = 0.0
            x[b0 + RATE + SLOTS[q]] = 0.0
        s[QD_ACTIVE] = 1.0
        s[QD_LAM] = s[QD_NIT] = s[QD_NH] = s[QD_DONE] = 0.0
    evaluated = 0
    passes = MAX_IT * (MAX_HALVE + 1)
    for it in range(passes + 1):
        n = 0
        for j in range(nrow):
            cage = cage_frame(x, cb + j * N_CAGE, P, rings.omega)    # once a row and pass
            for k in range(nz):
                if w.qd[j * nz + k, QD_ACTIVE] != 0.0:
                    roller(model, x, w.dx, j, k, rings, cage, P, D, n_inner, n_roller, w.Qs, w, True,
                           h, J_orb)
                    n += 1
        evaluated += n
        if n == 0 or it == passes or _newton(x, w, P, h, nz, nrow) == 0:
            break
    ring_loads(w.rec, w.F)
    for j in range(nrow):
        orbit = 0.0
        for k in range(nz):
            orbit += w.rec[j * nz + k, REC_ORBIT]
        cage_rates(x, w.dx, cb + j * N_CAGE, P, w.rec[j * nz:(j + 1) * nz], nz,
                   cage_frame(x, cb + j * N_CAGE, P, rings.omega), orbit, J_orb)
    return evaluated / (nrow * nz)


@kernel
def _newton(x, w, P, h, nz, nrow):
    """One pass over the rollers still iterating, each evaluated at its last move: a roller whose
    residual grew takes half its step back, up to :data:`MAX_HALVE` times (a roller off a
    raceway has only the floor's stiffness, and its full step would carry it deep into the
    raceway); it stops when it is :func:`_balanced`, when its update was below :data:`TOL`
    (once evaluated there) or after :data:`MAX_IT` updates; else it takes its next update
    (capped at :data:`CAP`).  Returns how many rollers moved (to be evaluated again)."""
    w_t = 2.0 * P[J_RD] / (P[M_R] * P[L_B])
    moved = 0
    for jk in range(nrow * nz):
        s = w.qd[jk]
        if s[QD_ACTIVE] == 0.0:
            continue
        b0 = jk * N_ROLLER
        m = _merit(w.dx, b0, w_t)
        if s[QD_LAM] > 0.0:                             # its last update's line search
            if m > s[QD_M0] and s[QD_NH] < MAX_HALVE:
                s[QD_LAM] *= 0.5
                s[QD_NH] += 1.0
                for q in range(3):
                    x[b0 + SLOTS[q]] -= s[QD_LAM] * s[QD_DQ + q]
                    x[b0 + RATE + SLOTS[q]] = (x[b0 + SLOTS[q]] - s[QD_Q0 + q]) / h
                moved += 1
                continue
            s[QD_LAM] = 0.0                             # accepted
        if s[QD_DONE] != 0.0 or _balanced(m, P) or s[QD_NIT] >= MAX_IT:
            s[QD_ACTIVE] = 0.0
            continue
        d = _step(w.blk, w.flag, jk, w.dx, b0, P, h)
        small = True
        for q in range(3):
            dq = min(max(d[q], -CAP[q]), CAP[q])
            s[QD_DQ + q] = dq
            x[b0 + SLOTS[q]] += dq
            x[b0 + RATE + SLOTS[q]] = (x[b0 + SLOTS[q]] - s[QD_Q0 + q]) / h
            if abs(dq) > TOL[q]:
                small = False
        s[QD_DONE] = 1.0 if small else 0.0
        s[QD_M0] = m
        s[QD_LAM] = 1.0
        s[QD_NH] = 0.0
        s[QD_NIT] += 1.0
        moved += 1
    return moved


@kernel
def _friction_entry(blk, flag, jk, a, col):
    """Entry ``(a, col)`` of roller ``jk``'s block (0 where it holds none; the cage's columns 0
    where it touched no pocket)."""
    if flag[jk] == BLK_NONE or (col >= BLK_CAGE and flag[jk] != BLK_COUPLED):
        return 0.0
    return blk[jk, a, col]


@kernel
def spin_step(x, P, h, w):
    """Steps 2 and 3 (module docstring): the spins and cage rates by a linearly implicit Euler
    step of ``h`` from the accelerations ``w.dx`` and the blocks :func:`equilibrium` left, then
    the spin angles and cage azimuths.

    The step's Jacobian is the friction's secant damping the kernel put in the blocks (the rows
    of the implicit kick, bearing/kernel/blocks.py: a contact's ``c J^T J`` over a roller's rates
    ``(rho', phi', eta', theta_t', theta_s', omega_s)`` and the cage's ``(..., phi_c')``; the
    normal contacts add nothing to the spin and orbit rows, whose rates do not move a raceway
    contact's approach).  With the roller's orbit rate the cage's, a row's unknowns are its
    spins ``omega_k`` and cage rate ``Omega``::

        J_a  d(omega_k)/dt:  d/d omega_k = -G_k[psi, psi],  d/d Omega = -(G_k[psi, phi] + G_k[psi, phi_c])
        J_orb d(Omega)/dt:   d/d omega_k = -(G_k[phi, psi] + G_k[psi, phi_c]),
                             d/d Omega = -(sum_k G_k[phi, phi] + 2 G_k[phi, phi_c]) - G_cage[phi_c, phi_c]

    (``J_orb = J_cp + Z M_r R^2``): the secant, not the tangent, of the regularised Coulomb law,
    as the dynamic model's "imex2" kick takes it: at least as damped, so the step stays stable
    at any slip.  A row's system is an arrowhead (a spin couples only to its own cage), solved in
    O(Z); no further evaluation of the right-hand side."""
    nz = int(P[Z])
    free = P[KINEMATIC] == POCKET_CAGE             # the cage's rotation a state (else Eq. 2's)
    Ja = P[J_RA]
    J_orb = orbital_inertia(P)
    blk, flag, dx = w.blk, w.flag, w.dx
    ps, ph, pc = BLK_ROLLER + PSI, BLK_ROLLER + PHI, BLK_CAGE + CPHI
    nrow = int(P[N_ROWS])
    for j in range(nrow):
        cb = nrow * nz * N_ROLLER + j * N_CAGE
        e = 0.0
        for k in range(nz):
            e -= _friction_entry(blk, flag, j * nz + k, CPHI, BLK_CAGE_CAGE + CPHI)
        for k in range(nz):
            jk = j * nz + k
            e -= _friction_entry(blk, flag, jk, PHI, ph) + 2.0 * _friction_entry(blk, flag, jk, PHI, pc)
        e = e / J_orb if free else 0.0
        lhs = 1.0 - h * e
        rhs = h * dx[cb + RATE + CPHI] if free else 0.0
        for k in range(nz):
            jk = j * nz + k
            wr = jk * N_ROLLER + RATE + PSI
            d = -_friction_entry(blk, flag, jk, PSI, ps) / Ja
            b = -(_friction_entry(blk, flag, jk, PSI, ph) + _friction_entry(blk, flag, jk, PSI, pc)) / Ja
            c = (-(_friction_entry(blk, flag, jk, PHI, ps) + _friction_entry(blk, flag, jk, PSI, pc))
                 / J_orb if free else 0.0)
            p = 1.0 - h * d
            w.qd[jk, QD_P] = p
            w.qd[jk, QD_B] = b
            lhs -= h * h * c * b / p
            rhs += h * h * c * dx[wr] / p
        dc = rhs / lhs if free else 0.0
        x[cb + RATE + CPHI] += dc
        for k in range(nz):
            jk = j * nz + k
            wr = jk * N_ROLLER + RATE + PSI
            x[wr] += (h * dx[wr] + h * w.qd[jk, QD_B] * dc) / w.qd[jk, QD_P]
            x[jk * N_ROLLER + PSI] += h * x[wr]
        if free:
            x[cb + CPHI] += h * x[cb + RATE + CPHI]
        else:
            x[cb + CPHI] += h * dx[cb + CPHI]           # Eq. 2's rate, as the kernel gave it


@kernel
def substep(model, x, ring, P, D, w, K, t, h, hk, mode, theta, out, Qc, cages):
    """One step of ``h`` of the quasi-dynamic bearing ``model`` (bearing/kernel/step.py's contract;
    ``hk``, ``mode``, ``theta`` and ``K`` are the dynamic step's and unused here): the contact
    equilibrium at the step's end, its loads to ``w.F`` (and with ``out`` its contact forces
    and cages), then the spins and cage."""
    equilibrium(model, t, x, ring, P, D, h, w)
    if out:
        copy3(Qc, w.Qs)
        cage_outputs(x, w.dx, cages)
    spin_step(x, P, h, w)
