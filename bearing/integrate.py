"""Fixed-step integration of the standalone rig (numba): one DTRB between a spinning inner ring
held in place and an outer ring that is the axle-box mass on a spring-damper to ground.

Rig state ``Y = [bearing state, u_o (3), v_o (3)]``.  The outer ring carries the applied load
``F_ext`` and a spring-damper ``-k (u_o - u_eq) - c v_o`` about its static place ``u_eq`` (the
quasi-static solution), so that at rest the bearing alone carries ``F_ext``.

* :func:`run_rk4`: classical Runge-Kutta 4, every stage a full evaluation of the bearing
  (:func:`.evaluate.evaluate`; the dynamic scheme only).
* :func:`run_leapfrog`: the vehicle's kick-drift leapfrog (mbs/kernel/integrate.py), one
  evaluation a step, velocities half a step behind the positions; with ``mode`` 1 ("imex") the
  rollers' and cages' contact damping in the kick implicitly, with 2 ("imex2") their contact
  stiffness and friction too (bearing/kernel/implicit.py); the quasi-dynamic bearing takes its own
  step whatever the mode.  The outer ring stays explicit and exchanges with the bearing as the
  car's bodies do (:func:`.advance.advance`), here every step.

Both take the bearing by its tag (bearing/models/__init__.py) and are compiled for it alone.
"""
from __future__ import annotations

import numpy as np

from axlebox._numba import kernel

from .kernel.advance import advance
from .kernel.evaluate import evaluate
from .kernel.layout import (CAGE_ANGLE, CAGE_RATE, CPHI, F_X, INNER, LOAD, N_CAGE, OUTER, RING, RINGS,
                            TH_Y, U_X, V_X, W_Y)

# rig vector slots: the outer ring's mass, its springs and dampers to ground, the load on it,
# the inner ring's speed, the springs' zero (the static place)
R_MASS, R_KX, R_KY, R_KZ, R_CX, R_CY, R_CZ, R_FX, R_FY, R_FZ, R_OMEGA, R_UX, R_UY, R_UZ, R_N = range(15)
# the rig state after the bearing's: the outer ring's displacement (3) and velocity (3)
RIG_U, RIG_V, RIG = 0, 3, 6


@kernel
def _rings(t, Y, nb, rig, ring):
    """The ring motion of the rig at ``t``: the inner ring turning at its speed, the outer ring
    where the rig state ``Y`` (the bearing's ``nb`` states first) has it."""
    ring[:, :] = 0.0
    ring[INNER, TH_Y] = rig[R_OMEGA] * t
    ring[INNER, W_Y] = rig[R_OMEGA]
    for q in range(3):
        ring[OUTER, U_X + q] = Y[nb + RIG_U + q]
        ring[OUTER, V_X + q] = Y[nb + RIG_V + q]


@kernel
def _outer_ring(F, Y, nb, rig, q):
    """The outer ring's acceleration along axis q: the bearing's load ``F`` on it, the applied
    load and its spring-damper to ground."""
    return (F[OUTER, F_X + q] + rig[R_FX + q] - rig[R_KX + q] * (Y[nb + RIG_U + q] - rig[R_UX + q])
            - rig[R_CX + q] * Y[nb + RIG_V + q]) / rig[R_MASS]


@kernel
def _rig_rhs(tag, t, Y, P, D, rig, ring, dY, F, Qc, w):
    nb = Y.shape[0] - RIG
    _rings(t, Y, nb, rig, ring)
    evaluate(tag, t, Y[:nb], ring, P, D, dY[:nb], F, Qc, w, False, 0.0)
    for q in range(3):
        dY[nb + RIG_U + q] = Y[nb + RIG_V + q]
        dY[nb + RIG_V + q] = _outer_ring(F, Y, nb, rig, q)


@kernel(allocates=True)
def run_rk4(tag, Y, t0, dt, n_steps, every, P, D, rig, w, acc, Fout, Qout, cage):
    """Advance ``Y`` in place by ``n_steps`` steps of ``dt`` from ``t0`` (the bearing of tag
    ``tag``, its scratch ``w``, bearing/kernel/evaluate.py ``Work``).

    Written as it goes: ``acc (n_steps, 3)`` outer-ring acceleration at every step start;
    every ``every`` steps ``Fout (., RINGS, LOAD)`` ring loads, ``Qout (., n, Z, N_Q)`` contact
    forces, ``cage (., n, CAGE_OUT)`` cage angle and speed (n the rows).  Returns False if the
    state stops being finite.
    """
    n = Y.shape[0]
    n_out = (n_steps + every - 1) // every
    if acc.shape[0] < n_steps or Fout.shape[0] < n_out or Qout.shape[0] < n_out or cage.shape[0] < n_out:
        raise ValueError("run_rk4: output arrays are shorter than the run")    # no bounds checks below
    k1, k2, k3, k4, tmp = np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    ring = np.zeros((RINGS, RING))
    F = np.zeros((RINGS, LOAD))
    Qc = np.zeros(Qout.shape[1:])
    for i in range(n_steps):
        t = t0 + i * dt
        _rig_rhs(tag, t, Y, P, D, rig, ring, k1, F, Qc, w)
        _record(i, every, Y, k1, F, Qc, acc, Fout, Qout, cage)
        for q in range(n):
            tmp[q] = Y[q] + 0.5 * dt * k1[q]
        _rig_rhs(tag, t + 0.5 * dt, tmp, P, D, rig, ring, k2, F, Qc, w)
        for q in range(n):
            tmp[q] = Y[q] + 0.5 * dt * k2[q]
        _rig_rhs(tag, t + 0.5 * dt, tmp, P, D, rig, ring, k3, F, Qc, w)
        for q in range(n):
            tmp[q] = Y[q] + dt * k3[q]
        _rig_rhs(tag, t + dt, tmp, P, D, rig, ring, k4, F, Qc, w)
        ok = True
        for q in range(n):
            Y[q] += dt / 6.0 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q])
            if not np.isfinite(Y[q]):
                ok = False
        if not ok:
            return False
    return True


@kernel(allocates=True)
def _record(i, every, Y, a, F, Qc, acc, Fout, Qout, cage):
    """Step i's outer-ring acceleration; every ``every`` steps the loads, contacts and cages."""
    nb = Y.shape[0] - RIG
    for q in range(3):
        acc[i, q] = a[nb + RIG_V + q]
    if i % every == 0:
        m = i // every
        Fout[m] = F
        Qout[m] = Qc
        rows = cage.shape[1]
        cb = nb - rows * N_CAGE
        for j in range(rows):
            cage[m, j, CAGE_ANGLE] = Y[cb + N_CAGE * j + CPHI]
            cage[m, j, CAGE_RATE] = a[cb + N_CAGE * j + CPHI]


@kernel(allocates=True)
def run_leapfrog(tag, Y, t0, dt, n_steps, every, P, D, rig, w, K, acc, Fout, Qout, cage, mode,
                 start, theta=1.0):
    """:func:`run_rk4`'s contract by the leapfrog (module docstring): the outer ring and the
    bearing exchange every step (:func:`.advance.advance` with one sub-step, ``mode`` 0
    explicit, 1 contact damping implicit, 2 contact stiffness and friction too; ``K`` the
    kick's scratch, bearing/kernel/implicit.py); ``start``: ``Y`` holds the initial velocities (the
    first kick is half a step), else the half-step velocities an earlier call left.  Returns
    False if the state stops being finite."""
    n = Y.shape[0]
    nb = n - RIG
    n_out = (n_steps + every - 1) // every
    if acc.shape[0] < n_steps or Fout.shape[0] < n_out or Qout.shape[0] < n_out or cage.shape[0] < n_out:
        raise ValueError("run_leapfrog: output arrays are shorter than the run")
    ring_b = np.zeros((RINGS, RING))
    F = np.zeros((RINGS, LOAD))
    Qc = np.zeros(Qout.shape[1:])
    cages = np.zeros(cage.shape[1:])
    x = Y[:nb]
    for i in range(n_steps):
        t = t0 + i * dt
        first = start and i == 0
        _rings(t, Y, nb, rig, ring_b)
        # one sub-step: its one sample is at this exchange, so the last exchange's ring motion
        # does not enter (ring_b stands for it)
        advance(tag, x, ring_b, ring_b, P, D, w, K, t, dt, 1, first, mode, theta, F, Qc, cages)
        for q in range(3):
            acc[i, q] = _outer_ring(F, Y, nb, rig, q)
        if i % every == 0:
            m = i // every
            Fout[m] = F
            Qout[m] = Qc
            cage[m] = cages
        hk = 0.5 * dt if first else dt
        for q in range(3):
            Y[nb + RIG_V + q] += hk * acc[i, q]
            Y[nb + RIG_U + q] += dt * Y[nb + RIG_V + q]
        ok = True
        for q in range(n):
            if not np.isfinite(Y[q]):
                ok = False
        if not ok:
            return False
    return True
