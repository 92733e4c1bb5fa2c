"""Floating-frame (FFRF) inertia invariants from the consistent mass matrix.

With the scalar consistent mass ``Ms`` (one displacement component), every
volume integral of a product of two FE fields is exact:
``int rho f g dV = f^T Ms g``.  For the body frame at the FE origin, unit
vectors ``x_a`` (position components) and mode shapes ``Phi_k`` (k = 1..n):

=========  ==========================================  =========================
name       definition                                  SID / Shabana equivalent
=========  ==========================================  =========================
``m``      int rho dV                                  I1, mass
``mc``     int rho x dV (3,)                           I2, first moment
``J``      int rho ((x.x) I - x x^T) dV (3, 3)         inertia about the origin
``Ct``     int rho Phi_k dV (3, n)                     SID Ct, Shabana I3
``Cr``     int rho x x Phi_k dV (3, n)                 SID Cr, Shabana I5
``Me``     int rho Phi_k . Phi_l dV (n, n)             modal mass
``Q``      int rho x_a Phi_kb dV (3, 3, n)             builds Ikl / dJ/dq (Ck)
``R``      int rho Phi_ka Phi_lb dV (3, 3, n, n)       builds Ikl, Gr (gyroscopic)
=========  ==========================================  =========================

Derived, for the equations of motion: the first-order change of the inertia
tensor with ``q_k`` is ``J_k = 2 tr(Q_k) I - Q_k - Q_k^T`` (symmetric part),
and the gyroscopic coupling ``int rho Phi_k x Phi_l dV`` is
``eps_abc R[b, c, k, l]``.  Shabana, Dynamics of Multibody Systems, 4th ed.,
ch. 5; Schwertassek and Wallrapp, Dynamik flexibler Mehrkoerpersysteme, ch. 5.
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

_EPS = np.zeros((3, 3, 3))
_EPS[0, 1, 2] = _EPS[1, 2, 0] = _EPS[2, 0, 1] = 1.0
_EPS[0, 2, 1] = _EPS[2, 1, 0] = _EPS[1, 0, 2] = -1.0


def compute(points: np.ndarray, Ms: sp.spmatrix, shapes: np.ndarray) -> dict[str, np.ndarray]:
    """Invariants for point coordinates (p, 3), scalar mass (p, p), shapes (n, p, 3)."""
    one = np.ones(points.shape[0])
    Mx = Ms @ points                         # (p, 3)
    M1 = Ms @ one
    m = float(one @ M1)
    mc = points.T @ M1
    P = points.T @ Mx                         # int rho x_a x_b
    J = np.trace(P) * np.eye(3) - P
    n = shapes.shape[0]
    Phi = np.moveaxis(shapes, 0, -1)          # (p, 3, n)
    Ct = np.einsum("p,pan->an", M1, Phi)
    Q = np.einsum("pa,pbn->abn", Mx, Phi)
    MPhi = np.stack([Ms @ Phi[:, b, :] for b in range(3)], axis=1)   # (p, 3, n)
    R = np.einsum("pak,pbl->abkl", Phi, MPhi)
    Cr = np.einsum("abc,bck->ak", _EPS, Q)
    Me = np.einsum("aakl->kl", R)
    return {"m": np.array(m), "mc": mc, "J": J, "Ct": Ct, "Cr": Cr, "Me": Me, "Q": Q, "R": R,
            "n_modes": np.array(n)}
