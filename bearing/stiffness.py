"""Contact stiffness of line contacts: Palmgren's law in the paper's Eq. (10)-(11) form.

Eq. (10): ``K = 0.356 E' L^(8/9)`` with ``Q = K delta^(10/9)``, in N and mm, and
Eq. (11): ``E' = 2 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2)``.  For steel on steel
this is Palmgren's ``delta = 3.84e-5 Q^0.9 / l^0.8`` (mm, N) within 1 %
(Palmgren, Ball and Roller Bearing Engineering, 1959; Harris and Kotzalas,
Rolling Bearing Analysis, eq. 7.2); :func:`palmgren` keeps that form.

The paper's Eq. (5) for the raceways, ``6.24e4 Le^0.82 Db^(10/9) [...]^-1.11``,
does not state its units and gives values about twenty times Palmgren's in
N/mm^(10/9); this package uses Eq. (10) with the raceway materials for the
raceways instead, which reproduces the paper's own closed-form references.
"""
from __future__ import annotations

_MM = 1e3                      # m -> mm
_SI = _MM ** (10 / 9)          # N/mm^(10/9) -> N/m^(10/9)


def e_prime(E1: float, nu1: float, E2: float, nu2: float) -> float:
    """Equivalent modulus, Eq. (11) (Pa)."""
    return 2.0 / ((1 - nu1 ** 2) / E1 + (1 - nu2 ** 2) / E2)


def k_line(E_prime: float, L: float) -> float:
    """Line-contact stiffness of Eq. (10) in SI, ``Q = K delta^(10/9)`` (N/m^(10/9))."""
    return 0.356 * (E_prime / 1e6) * (L * _MM) ** (8 / 9) * _SI


def palmgren(L: float) -> float:
    """Steel-on-steel line contact from ``delta = 3.84e-5 Q^0.9 / l^0.8`` (mm, N), in SI."""
    return ((L * _MM) ** 0.8 / 3.84e-5) ** (10 / 9) * _SI


def series(K1: float, K2: float, n: float = 10 / 9) -> float:
    """Two contacts ``Q = K_j delta_j^n`` in series: ``Q = K (delta_1 + delta_2)^n``."""
    return (K1 ** (-1 / n) + K2 ** (-1 / n)) ** (-n)


def roller_raceways(p) -> tuple[float, float, float]:
    """Outer, inner and combined (series) roller-raceway stiffness of ``p`` (N/m^(10/9))."""
    E = e_prime(p.E_r, p.nu_r, p.E_r, p.nu_r)
    K_o = k_line(E, p.L_e)
    K_i = k_line(E, p.L_e)
    return K_o, K_i, series(K_o, K_i)
