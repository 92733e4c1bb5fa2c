"""Fixed-step integration of the standalone rig (numba): one DTRB between a spinning inner ring
held in place and an outer ring that is the axle-box mass on a spring-damper to ground.

Rig state ``Y = [bearing state, u_o (3), v_o (3)]``.  The outer ring carries the applied load
``F_ext`` and a spring-damper ``-k (u_o - u_eq) - c v_o`` about its static place ``u_eq`` (the
quasi-static solution), so that at rest the bearing alone carries ``F_ext``.

* :func:`run_rk4`: classical Runge-Kutta 4, every stage a full evaluation of
  :func:`.kernel.dtrb_rhs`.
* :func:`run_leapfrog`: the vehicle's kick-drift leapfrog (mbs/kernel_integrate.py), one
  evaluation a step, velocities half a step behind the positions; with ``mode`` 1 ("imex") the
  rollers' and cages' contact damping in the kick implicitly, with 2 ("imex2") their contact
  stiffness and friction too (bearing/implicit.py).  The outer ring stays explicit and
  exchanges with the bearing as the car's bodies do (:func:`.advance.advance`), here every
  step.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .advance import advance
from .kernel import dtrb_rhs_damped
from .layout import N_CAGE, QUASI

# s: the explicit steps' limits on the rollers' tilt mode between the raceways (22.6 kHz,
# damping ratio 0.12): RK4's w h <= 2.8; the leapfrog's 2 (sqrt(1 + z^2) - z) = 1.77 less a
# margin for the loads; "imex" (contact damping implicit) keeps the undamped limit of the
# leapfrog on the tilt mode (benchmarks/README.md); "imex2" (stiffness and friction implicit too)
# runs the bearing alone at 2.5e-5 s, but the car's defect side is not yet right there: held to
# imex's limit until it is (benchmarks/README.md, "imex2")
DT_MAX = {"rk4": 2.8e-5, "leapfrog": 1.2e-5, "imex": 1.2e-5, "imex2": 1.2e-5}

# rig vector slots
R_MASS, R_KX, R_KY, R_KZ, R_CX, R_CY, R_CZ, R_FX, R_FY, R_FZ, R_OMEGA, R_UX, R_UY, R_UZ, R_N = range(15)


@njit(cache=True)
def _rig_rhs(t, Y, P, D, rig, ring, dY, F, Qc, G):
    n = Y.shape[0] - 6
    om = rig[R_OMEGA]
    ring[:, :] = 0.0
    ring[0, 4] = om * t
    ring[0, 10] = om
    for q in range(3):
        ring[1, q] = Y[n + q]
        ring[1, 6 + q] = Y[n + 3 + q]
    dtrb_rhs_damped(t, Y[:n], ring, P, D, dY[:n], F, Qc, G, 0.0)
    for q in range(3):
        f = (F[1, q] + rig[R_FX + q] - rig[R_KX + q] * (Y[n + q] - rig[R_UX + q])
             - rig[R_CX + q] * Y[n + 3 + q])
        dY[n + q] = Y[n + 3 + q]
        dY[n + 3 + q] = f / rig[R_MASS]


@njit(cache=True)
def run_rk4(Y, t0, dt, n_steps, every, P, D, rig, acc, Fout, Qout, cage):
    """Advance ``Y`` in place by ``n_steps`` steps of ``dt`` from ``t0``.

    Written as it goes: ``acc (n_steps, 3)`` outer-ring acceleration at every step start;
    every ``every`` steps ``Fout (., 2, 6)`` ring loads, ``Qout (., 2, Z, 6)`` contact forces,
    ``cage (., 2, 2)`` cage angle and speed.  Returns False if the state stops being finite.
    """
    n = Y.shape[0]
    nb = n - 6
    n_out = (n_steps + every - 1) // every
    if acc.shape[0] < n_steps or Fout.shape[0] < n_out or Qout.shape[0] < n_out or cage.shape[0] < n_out:
        raise ValueError("run_rk4: output arrays are shorter than the run")    # no bounds checks below
    nz = Qout.shape[2]
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    tmp = np.empty(n)
    ring = np.zeros((2, 12))
    F = np.zeros((2, 6))
    Qc = np.zeros((2, nz, 6))
    G = np.empty((0, 1, 6, 12))
    for i in range(n_steps):
        t = t0 + i * dt
        _rig_rhs(t, Y, P, D, rig, ring, k1, F, Qc, G)
        _record(i, every, Y, k1, F, Qc, nb, acc, Fout, Qout, cage)
        for q in range(n):
            tmp[q] = Y[q] + 0.5 * dt * k1[q]
        _rig_rhs(t + 0.5 * dt, tmp, P, D, rig, ring, k2, F, Qc, G)
        for q in range(n):
            tmp[q] = Y[q] + 0.5 * dt * k2[q]
        _rig_rhs(t + 0.5 * dt, tmp, P, D, rig, ring, k3, F, Qc, G)
        for q in range(n):
            tmp[q] = Y[q] + dt * k3[q]
        _rig_rhs(t + dt, tmp, P, D, rig, ring, k4, F, Qc, G)
        ok = True
        for q in range(n):
            Y[q] += dt / 6.0 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q])
            if not np.isfinite(Y[q]):
                ok = False
        if not ok:
            return False
    return True


@njit(cache=True)
def _record(i, every, Y, a, F, Qc, nb, acc, Fout, Qout, cage):
    """Step i's outer-ring acceleration; every ``every`` steps the loads, contacts and cages."""
    for q in range(3):
        acc[i, q] = a[nb + 3 + q]
    if i % every == 0:
        m = i // every
        Fout[m] = F
        Qout[m] = Qc
        cb = nb - 2 * N_CAGE
        for j in range(2):
            cage[m, j, 0] = Y[cb + N_CAGE * j + 5]
            cage[m, j, 1] = a[cb + N_CAGE * j + 5]


@njit(cache=True)
def run_leapfrog(Y, t0, dt, n_steps, every, P, D, rig, acc, Fout, Qout, cage, mode, start,
                 theta=1.0):
    """:func:`run_rk4`'s contract by the leapfrog (module docstring): the outer ring and the
    bearing exchange every step (:func:`.advance.advance` with one sub-step, ``mode`` 0
    explicit, 1 contact damping implicit, 2 contact stiffness and friction too); ``start``:
    ``Y`` holds the initial velocities (the first kick is half a step), else the half-step
    velocities an earlier call left.  Returns False if the state stops being finite."""
    n = Y.shape[0]
    nb = n - 6
    n_out = (n_steps + every - 1) // every
    if acc.shape[0] < n_steps or Fout.shape[0] < n_out or Qout.shape[0] < n_out or cage.shape[0] < n_out:
        raise ValueError("run_leapfrog: output arrays are shorter than the run")
    nz = Qout.shape[2]
    om = rig[R_OMEGA]
    ring_b = np.zeros((2, 12))
    F = np.zeros((2, 6))
    Qc = np.zeros((2, nz, 6))
    cages = np.zeros(4)
    G = np.zeros((4 if P[QUASI] != 0.0 else (2 if mode > 0 else 0), nz + 1, 6, 12))   # advance.block_rows
    dx, ring, Fs, Qs = np.empty(nb), np.zeros((2, 12)), np.zeros((2, 6)), np.zeros((2, nz, 6))
    a = np.empty(3)
    x = Y[:nb]
    for i in range(n_steps):
        t = t0 + i * dt
        first = start and i == 0
        ring_b[0, 4] = om * t
        ring_b[0, 10] = om
        for q in range(3):
            ring_b[1, q] = Y[nb + q]
            ring_b[1, 6 + q] = Y[nb + 3 + q]
        # one sub-step: its one sample is at this exchange, so the last exchange's ring motion
        # does not enter (ring_b stands for it)
        advance(x, ring_b, ring_b, P, D, t, dt, 1, first, mode, F, Qc, cages, G, dx, ring, Fs, Qs, theta)
        for q in range(3):
            a[q] = (F[1, q] + rig[R_FX + q] - rig[R_KX + q] * (Y[nb + q] - rig[R_UX + q])
                    - rig[R_CX + q] * Y[nb + 3 + q]) / rig[R_MASS]
            acc[i, q] = a[q]
        if i % every == 0:
            m = i // every
            Fout[m] = F
            Qout[m] = Qc
            for j in range(2):
                cage[m, j, 0] = cages[j]
                cage[m, j, 1] = cages[2 + j]
        hk = 0.5 * dt if first else dt
        for q in range(3):
            Y[nb + 3 + q] += hk * a[q]
            Y[nb + q] += dt * Y[nb + 3 + q]
        ok = True
        for q in range(n):
            if not np.isfinite(Y[q]):
                ok = False
        if not ok:
            return False
    return True
