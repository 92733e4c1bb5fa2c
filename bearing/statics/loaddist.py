"""Harris-Stribeck load distribution integrals for rolling bearings.

Load on the roller at azimuth psi from the load line (Harris and Kotzalas,
Rolling Bearing Analysis, 5th ed., vol. 1, sec. 7.2):
``Q(psi) = Q_max [1 - (1 - cos psi) / (2 eps)]^n`` inside the loaded zone,
``n = 10/9`` for line contact, 3/2 for point contact.  The radial integral

``J_r(eps) = 1 / (2 pi) int_{-psi_l}^{psi_l} [1 - (1 - cos psi)/(2 eps)]^n cos psi dpsi``

gives ``F_r = Z Q_max J_r(eps) cos(alpha)``; ``cos psi_l = 1 - 2 eps``.
Harris's table 7.1: J_r(0.5) = 0.2453 for line contact, 0.2288 for point contact;
the table's line-contact column is computed with n = 1.1 (its Stribeck constant
1/0.2453 = 4.08), this package's contacts follow Palmgren's n = 10/9
(J_r(0.5) = 0.2448, 0.2 % apart).
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import quad


def J_r(eps: float, n: float = 10 / 9) -> float:
    """Radial load integral for the load-zone parameter ``eps`` in (0, 1]."""
    if not 0 < eps <= 1:
        raise ValueError(f"eps = {eps!r} is not allowed: expected 0 < eps <= 1")
    psi_l = np.arccos(np.clip(1 - 2 * eps, -1, 1))
    f = lambda psi: (1 - (1 - np.cos(psi)) / (2 * eps)) ** n * np.cos(psi)   # noqa: E731
    value, _ = quad(f, -psi_l, psi_l, limit=200)
    return value / (2 * np.pi)


def eps_radial(delta_r: float, u_r: float) -> float:
    """Load-zone parameter from the ring's radial approach and diametral clearance:
    ``eps = (1 - u_r / (2 delta_r)) / 2`` (Harris eq. 7.21)."""
    return 0.5 * (1 - u_r / (2 * delta_r))


def radial_rollers(delta_r: float, P_d: float, K_n: float, Z: int, n: float = 10 / 9):
    """A radially loaded row's roller loads in Harris's closed form with clearance (Harris and
    Kotzalas, Essential Concepts of Bearing Technology, 2007, sec. 7.2, eqs. 7.19-7.21):
    ``(Q_max, Q, eps)``, the heaviest roller's ``K_n (delta_r - P_d / 2)^n``, each roller's at
    ``psi_k = 2 pi k / Z`` from the load line ``Q_max (1 - (1 - cos psi_k) / (2 eps))^n`` (0
    outside the loaded zone) and the load-zone parameter :func:`eps_radial`; ``delta_r`` the
    ring's radial approach, ``P_d`` the diametral clearance, ``K_n`` a roller's two raceway
    contacts in series."""
    eps = eps_radial(delta_r, P_d)
    Q_max = K_n * (delta_r - 0.5 * P_d) ** n
    psi = 2 * np.pi * np.arange(Z) / Z
    return Q_max, Q_max * np.clip(1 - (1 - np.cos(psi)) / (2 * eps), 0, None) ** n, eps
