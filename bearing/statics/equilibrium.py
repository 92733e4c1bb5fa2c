"""Quasi-static start of the dynamic model: rings and rollers in equilibrium under the load.

Unknowns: the outer ring's displacement relative to the inner ring (3) and, for every roller,
its radial and axial displacement and tilt (3 each).  Equations: the ring carries the applied
load, and every roller's radial, axial and tilt accelerations vanish, all taken from the same
kernel that integrates the dynamics (:func:`.evaluate.evaluate`, any model), with the rollers
rolling at the epicyclic speeds so that centrifugal forces and rib sliding are included.  Solved
by Newton's method nested in two levels (the rollers, each a 3 x 3 block with backtracking, for
given rings; the ring's 3 unknowns outside), started from the model's own guess (the DTRB's:
the series-spring solution of :mod:`.quasistatic`).
What is left (the rollers' orbital and spin balance against rib friction, which the cage takes)
settles in the first milliseconds and hardly moves the ring.
"""
from __future__ import annotations

import numpy as np

from ..kernel import dispatch
from .. import models
from ..kernel.evaluate import rates
from ..kernel.layout import CPHI, ETA, F_X, F_Z, OUTER, PHI, Q_I, Q_O, RATE, RHO, TH_T, ring_motion, views

__all__ = ["ring_motion", "static_state"]
FLOOR = 1e-6            # a direction with no stiffness: this fraction of the block's stiffest


def floored(J):
    """``J`` (blocks ``(..., 3, 3)``) with every diagonal entry below :data:`FLOOR` of its
    block's largest raised to it, with that entry's sign: a direction that nothing holds (a
    cylindrical roller's axial place inside its ribs' play, the DCRB's ring axially in it)
    moves by the residual over that small stiffness, toward what holds it, instead of making the
    block singular; a block held in every direction (the DTRB's) is left as it is."""
    d = np.diagonal(J, axis1=-2, axis2=-1)
    big = np.abs(d).max(axis=-1, keepdims=True)
    low = np.abs(d) < FLOOR * big
    if not low.any():
        return J
    J = J.copy()
    sign = np.where(np.take_along_axis(d, np.abs(d).argmax(axis=-1)[..., None], -1) < 0, -1.0, 1.0)
    idx = np.nonzero(low)
    J[idx + (idx[-1],)] = (sign * FLOOR * big * np.ones_like(d))[idx]
    return J


def static_state(p, P, D, F_outer, omega_w: float, tol: float = 1e-9, roller_tol: float = 1e-7,
                 phase: float = 0.0):
    """``(y, uo)``: the bearing state and the outer ring's displacement at which the bearing
    carries ``F_outer`` (N, the load applied to the outer ring) with no radial, axial or tilt
    acceleration of any roller.  ``tol``: the ring residual, and ``roller_tol`` the rollers'
    (and the ring's) accepted once Newton stalls, both relative to the load.  ``phase`` (rad) turns the roller
    set and cages from their nominal places first.  Raises RuntimeError when it does not
    converge."""
    F_outer = np.asarray(F_outer, float)
    Fn = float(np.linalg.norm(F_outer))
    y = models.nominal_state(p, omega_w)
    rol, cag = views(y, p.Z)
    rol[:, :, PHI] += phase
    cag[:, CPHI] += phase
    model = dispatch.tag(p)

    # start: the model's guess
    uo0, rol[:, :, RHO], rol[:, :, ETA] = models.module(p).guess(p, F_outer)
    cols = (RHO, ETA, TH_T)
    steps = np.array([1e-12, 1e-12, 1e-10])              # m, m, rad: below barely-touching rollers
    _, J_rd = p.J_r
    weights = np.array([p.M_r, p.M_r, J_rd])             # accelerations -> forces, moment
    Fs = max(Fn, 1.0)

    out = {}
    at_rate = RATE + np.array(cols)
    last = {"key": None}        # the last evaluation: its state and ring place, and its result

    def roller_residual(uo):
        # Newton asks again where it stands after an accepted step or a roller put back: the
        # same state gives the same numbers, so the last evaluation's are returned
        key = y.tobytes() + np.asarray(uo, float).tobytes()
        if key != last["key"]:
            yd, F, Q, _ = rates(model, 0.0, y, ring_motion(omega_w, uo), P, D)
            acc, _ = views(yd, p.Z)
            last.update(key=key, result=(acc[:, :, at_rate] * weights, F[OUTER, F_X:F_Z + 1].copy(), Q))
        r, Fo, out["Q"] = last["result"]
        return r, Fo

    def norm(r):
        f_rho, f_eta, m_tht = np.moveaxis(r, -1, 0)        # the columns of ``cols``
        return np.sqrt(f_rho ** 2 + f_eta ** 2 + (m_tht / p.L_b) ** 2)

    def residual(uo):
        r, _ = roller_residual(uo)
        return r

    nominal, _ = views(models.nominal_state(p, omega_w), p.Z)
    nominal[:, :, PHI] += phase

    def solve_rollers(uo):
        """Block Newton with backtracking: every roller is independent once the rings are placed.

        A roller that touches neither raceway carries nothing; it is put back at its nominal
        place (touching cone and rib without load) and left there."""
        for _ in range(100):
            r, Fo = roller_residual(uo)
            free = out["Q"][:, :, Q_O] + out["Q"][:, :, Q_I] == 0.0
            rol[free] = nominal[free]
            r, Fo = roller_residual(uo)
            r0 = norm(r)
            r0[free] = 0.0
            if r0.max() < 1e-8 * Fs:
                return Fo
            J = np.empty(r.shape + (3,))
            for a, c in enumerate(cols):
                rol[:, :, c] += steps[a]
                J[..., a] = (residual(uo) - r) / steps[a]
                rol[:, :, c] -= steps[a]
            J[free] = np.eye(3)
            dx = -np.squeeze(np.linalg.solve(floored(J), r[..., None]), axis=-1)
            dx[free] = 0.0
            x0 = np.stack([rol[:, :, c] for c in cols], axis=-1)
            t = np.ones(r0.shape)
            for _ in range(40):                      # halve each roller's step until it helps
                for a, c in enumerate(cols):
                    rol[:, :, c] = x0[..., a] + t * dx[..., a]
                worse = (norm(residual(uo)) > (1 - 1e-4 * t) * r0) & (r0 > 0)
                if not worse.any():
                    break
                t[worse] *= 0.5
        if r0.max() < roller_tol * Fs:  # a roller at the edge of the loaded zone, barely touching
            return Fo
        raise RuntimeError(f"quasi-static start: the rollers did not settle (largest residual "
                           f"{r0.max():.1e} N)")

    uo = uo0.copy()
    best_res, best_y, best_uo = np.inf, None, None
    for _ in range(50):
        res = solve_rollers(uo) + F_outer
        if np.linalg.norm(res) < tol * Fs:
            return y.copy(), uo
        if np.linalg.norm(res) < best_res:
            best_res, best_y, best_uo = np.linalg.norm(res), y.copy(), uo.copy()
        J = np.empty((3, 3))
        saved = y.copy()
        for a in range(3):
            du = np.zeros(3)
            du[a] = 1e-9
            J[:, a] = (solve_rollers(uo + du) + F_outer - res) / 1e-9
            y[:] = saved
        Jf = floored(J)
        free = np.diagonal(Jf) != np.diagonal(J)
        # a direction nothing holds (the DCRB's ring axially inside its ribs' play) is balanced
        # once its residual is the rollers' own (friction's last digits): any place in the play is
        if free.any() and np.linalg.norm(res[~free]) < tol * Fs \
                and np.linalg.norm(res[free]) < roller_tol * Fs:
            return y.copy(), uo
        uo = uo - np.linalg.solve(Jf, res)
    if best_res < roller_tol * Fs:       # stalled where a roller at the loaded zone's edge
        return best_y, best_uo           # touches and lets go by turns: its load is the rest
    raise RuntimeError(f"quasi-static start did not converge (ring residual {np.linalg.norm(res):.1e} N)")
