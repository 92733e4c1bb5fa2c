"""The floating-frame equations of one body in plain numpy (einsum), the twin of
:mod:`axlebox.mbs.kernel.body`: the mass matrix, the quadratic velocity vector, kinetic energy and
momenta.  Used by the tests (energy and momentum invariants, a cross-check of the numba
kernel) and by the benchmark's speed-up figure; the same equations as the kernel's docstring.
"""
from __future__ import annotations

import numpy as np

from .body import Body

EPS = np.zeros((3, 3, 3))
EPS[0, 1, 2] = EPS[1, 2, 0] = EPS[2, 0, 1] = 1.0
EPS[0, 2, 1] = EPS[2, 1, 0] = EPS[1, 0, 2] = -1.0


def skew(a):
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def quat_to_A(p):
    w, x, y, z = np.asarray(p, float) / np.linalg.norm(p)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def terms(body: Body, A, q):
    """``S``, ``W (3, 3, n)``, ``P`` and the inertia tensor ``J`` at modal coordinates ``q``."""
    S = body.mc + body.Ct @ q
    W = body.Q + np.einsum("abln,l->abn", body.R, q)
    P = body.P0 + np.einsum("k,abk->ab", q, W + body.Q.transpose(1, 0, 2))
    J = np.trace(P) * np.eye(3) - P
    return S, W, P, J


def mass_matrix(body: Body, A, q):
    n = body.n_modes
    S, W, P, J = terms(body, A, q)
    M = np.zeros((6 + n, 6 + n))
    M[:3, :3] = body.mass * np.eye(3)
    M[:3, 3:6] = -A @ skew(S)
    M[:3, 6:] = A @ body.Ct
    M[3:6, 3:6] = J
    M[3:6, 6:] = np.einsum("abc,bck->ak", EPS, W)
    M[6:, 6:] = body.Me
    U = np.triu(M)          # upper triangle filled above: mirror it
    return U + np.triu(U, 1).T


def quadratic_velocity(body: Body, A, q, om, qd):
    """``h`` (6 + n): centrifugal, Coriolis and gyroscopic terms (frame rate = material rate
    unless the body spins, then the frame rate has no y component)."""
    S, W, P, J = terms(body, A, q)
    w = om.copy()
    if body.spin:
        w[1] = 0.0
    h_r = A @ (np.cross(w, np.cross(w, S)) + 2 * np.cross(w, body.Ct @ qd))
    trW = np.einsum("aak->k", W)
    h_w = np.cross(w, J @ om) + 2 * (np.outer(w, trW) - np.einsum("abk,a->bk", W, w)) @ qd
    G = np.einsum("abc,bclk->alk", EPS, body.R)          # int rho Phi_l x Phi_k
    h_f = np.einsum("a,abk,b->k", w, W, w) - (w @ w) * trW + 2 * np.einsum("a,alk,l->k", w, G, qd)
    return np.concatenate([h_r, h_w, h_f])


def kinetic_energy(body: Body, A, q, v, om, qd) -> float:
    u = np.concatenate([v, om, qd])
    return 0.5 * u @ mass_matrix(body, A, q) @ u


def momenta(body: Body, r, A, q, v, om, qd):
    """Linear momentum and angular momentum about the inertial origin (both inertial)."""
    S, W, P, J = terms(body, A, q)
    C = np.einsum("abc,bck->ak", EPS, W)
    p = body.mass * v + A @ (np.cross(om, S) + body.Ct @ qd)
    H = np.cross(r, p) + A @ (np.cross(S, A.T @ v) + J @ om + C @ qd)
    return p, H
