"""Quasi-static equilibrium of a roller bearing of one or more rows under ring loads (Newton's
method): any model's, by its rows, contact angle ``alpha_o`` and clearance ``clearance_n`` (the
DCRB's radial: 0).

Unknowns: the inner ring's displacement relative to the outer ring,
``q = (x, y, z, theta_x, theta_z)`` (the spin rotation theta_y is free).  For
the roller k of row j at azimuth ``psi_k = 2 pi (k - 1) / Z`` (measured from
+z towards +x, the paper's Eq. 2 convention) and axial position ``y_j``
(bearing/kernel/layout.py ``row_y``: two rows at ``-+ row_offset``, one at the
centre), the inner ring moves ``d = t + theta x r`` at the roller, and Eqs. (1)
and (3) give the normal approach along the contact normal
``n = cos(alpha) e_r + s_j sin(alpha) e_y`` (``s_j``: ``row_sign``, +1 on the -y
side, -1 on the +y side):

``delta_n = d . n - c_n``, ``c_n = max(u_r cos(alpha), u_a sin(alpha)) / 2``
(:attr:`RollerBearing.clearance_n`, each model's own).

The clearance is taken about the concentric position (Harris's form).  The
paper's ``h = u_r (1 - cos psi) / 2`` (below Eq. 1) is the same law with the
origin moved by u_r / 2 along a vertical load; the concentric form holds for
a load in any direction.  Each roller carries ``Q = K_n delta_n^(10/9)``
(Eq. 4a, quasi-static: no damping), with K_n the outer and inner raceway
contacts in series; the rib and cage carry no load at equilibrium in this
model (the roller's own force balance between the two raceway angles is
closed by the rib, which the dynamic model resolves).

Equilibrium: ``F = sum Q n`` and ``M = sum r x (Q n)`` for the external load
(F, M) on the inner ring.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axlebox._params import ParameterError

from ..kernel.layout import row_sign, row_y
from ..models.params import RollerBearing
from .stiffness import roller_raceways

N_EXP = 10 / 9
QX, QY, QZ, QTX, QTZ, N_QS = range(6)     # q: the inner ring's displacement and tilt


@dataclass
class Equilibrium:
    q: np.ndarray            # (5,) x, y, z (m), theta_x, theta_z (rad) of the inner ring
    psi: np.ndarray          # (Z,) roller azimuths, rad
    delta: np.ndarray        # (rows, Z) normal approach, m (negative: no contact)
    Q: np.ndarray            # (rows, Z) roller loads, N
    load: np.ndarray         # (5,) the applied Fx, Fy, Fz, Mx, Mz
    iterations: int
    residual: float          # |load - roller resultant| / |load|

    def loaded_zone(self, row: int) -> float:
        """Half-angle of the loaded zone of ``row`` (from 0), rad: the largest ``|psi|`` carrying load."""
        psi = np.angle(np.exp(1j * self.psi))
        loaded = self.Q[row] > 0
        return float(np.abs(psi[loaded]).max()) if loaded.any() else 0.0


def _geometry(p: RollerBearing, psi: np.ndarray):
    """Per roller: generalised normal ``g = [n; r x n]`` restricted to q (rows, Z, 5) and clearance."""
    R = 0.5 * p.D_m
    ca, sa = np.cos(p.alpha_o), np.sin(p.alpha_o)
    er = np.stack([np.sin(psi), np.zeros_like(psi), np.cos(psi)], axis=-1)        # (Z, 3)
    G = np.zeros((p.rows, len(psi), N_QS))
    for j in range(p.rows):
        n = ca * er + row_sign(j, p.rows) * sa * np.array([0.0, 1.0, 0.0])
        r = R * er + np.array([0.0, row_y(j, p.rows, p.row_offset), 0.0])
        m_x, _, m_z = np.cross(r, n).T
        G[j, :, QX:QZ + 1] = n
        G[j, :, QTX] = m_x
        G[j, :, QTZ] = m_z
    return G, p.clearance_n


def solve(p: RollerBearing, F, M=(0.0, 0.0), *, tol: float = 1e-10, max_iter: int = 100,
          psi0: float = 0.0) -> Equilibrium:
    """Equilibrium under the external load ``F = (Fx, Fy, Fz)`` (N) and moments
    ``M = (Mx, Mz)`` (N m) on the inner ring; Newton with backtracking."""
    load = np.concatenate([np.asarray(F, float).ravel(), np.asarray(M, float).ravel()])
    if load.shape != (N_QS,) or not np.all(np.isfinite(load)):
        raise ParameterError(f"load = {load.tolist()!r} is not allowed: expected F (3,) and M (2,) finite")
    if not np.any(load[QX:QZ + 1]):
        raise ParameterError("load F = (0, 0, 0) is not allowed: the rings are free within the clearance")
    _, _, K = roller_raceways(p)
    psi = psi0 + 2 * np.pi * np.arange(p.Z) / p.Z
    G, c = _geometry(p, psi)

    def state(q):
        delta = G @ q - c
        dp = np.maximum(delta, 0.0)
        Q = K * dp ** N_EXP
        dQ = N_EXP * K * dp ** (N_EXP - 1)          # 0 at delta = 0: no jump (N_EXP > 1)
        res = load - np.einsum("jk,jkc->c", Q, G)
        J = np.einsum("jk,jka,jkb->ab", dQ, G, G)     # d(sum Q g)/dq
        return delta, Q, res, J

    # start: rigid shift along the force, deep enough to engage a few rollers
    f = load[QX:QZ + 1]
    Fn = np.linalg.norm(f)
    guess = (Fn / (0.25 * p.Z * K)) ** (1 / N_EXP) + c
    q = np.zeros(N_QS)
    q[QX:QZ + 1] = f / Fn * guess * 2
    scale = np.abs(load).max()
    it = 0
    while it < max_iter:
        it += 1
        delta, Q, res, J = state(q)
        r0 = np.linalg.norm(res / scale)
        if r0 < tol:
            break
        J = J + 1e-12 * np.trace(J) * np.eye(N_QS)         # keep it invertible if a DOF is unloaded
        step = np.linalg.solve(J, res)
        t = 1.0
        while t > 1e-6:                                    # backtracking on the residual norm
            _, _, res_t, _ = state(q + t * step)
            if np.linalg.norm(res_t / scale) < (1 - 1e-4 * t) * r0:
                break
            t *= 0.5
        q = q + t * step
    delta, Q, res, _ = state(q)
    rel = float(np.linalg.norm(res) / np.linalg.norm(load))
    if rel > 1e-6:
        raise RuntimeError(f"quasi-static equilibrium did not converge (residual {rel:.1e} "
                           f"after {max_iter} Newton steps)")
    return Equilibrium(q=q, psi=psi, delta=delta, Q=Q, load=load, iterations=it, residual=rel)
