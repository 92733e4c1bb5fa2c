"""Fixed-step integration of the standalone rig (numba): one DTRB between a spinning inner ring
held in place and an outer ring that is the axle-box mass on a spring-damper to ground.

Rig state ``Y = [bearing state, u_o (3), v_o (3)]``.  The outer ring carries the applied load
``F_ext`` and a spring-damper ``-k (u_o - u_eq) - c v_o`` about its static place ``u_eq`` (the
quasi-static solution), so that at rest the bearing alone carries ``F_ext``.  Classical
Runge-Kutta 4: every stage is a full evaluation of :func:`.kernel.dtrb_rhs`.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .kernel import dtrb_rhs

# rig vector slots
R_MASS, R_KX, R_KY, R_KZ, R_CX, R_CY, R_CZ, R_FX, R_FY, R_FZ, R_OMEGA, R_UX, R_UY, R_UZ, R_N = range(15)


@njit(cache=True)
def _rig_rhs(t, Y, P, D, rig, ring, dY, F, Qc):
    n = Y.shape[0] - 6
    om = rig[R_OMEGA]
    ring[:, :] = 0.0
    ring[0, 4] = om * t
    ring[0, 10] = om
    for q in range(3):
        ring[1, q] = Y[n + q]
        ring[1, 6 + q] = Y[n + 3 + q]
    dtrb_rhs(t, Y[:n], ring, P, D, dY[:n], F, Qc)
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
    cb = nb - 24
    for i in range(n_steps):
        t = t0 + i * dt
        _rig_rhs(t, Y, P, D, rig, ring, k1, F, Qc)
        for q in range(3):
            acc[i, q] = k1[nb + 3 + q]
        if i % every == 0:
            m = i // every
            Fout[m] = F
            for j in range(2):
                for k in range(nz):
                    for c in range(6):
                        Qout[m, j, k, c] = Qc[j, k, c]
                cage[m, j, 0] = Y[cb + 12 * j + 5]
                cage[m, j, 1] = k1[cb + 12 * j + 5]
        for q in range(n):
            tmp[q] = Y[q] + 0.5 * dt * k1[q]
        _rig_rhs(t + 0.5 * dt, tmp, P, D, rig, ring, k2, F, Qc)
        for q in range(n):
            tmp[q] = Y[q] + 0.5 * dt * k2[q]
        _rig_rhs(t + 0.5 * dt, tmp, P, D, rig, ring, k3, F, Qc)
        for q in range(n):
            tmp[q] = Y[q] + dt * k3[q]
        _rig_rhs(t + dt, tmp, P, D, rig, ring, k4, F, Qc)
        ok = True
        for q in range(n):
            Y[q] += dt / 6.0 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q])
            if not np.isfinite(Y[q]):
                ok = False
        if not ok:
            return False
    return True
