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

The rib contact (Eq. 8, ``K_a = 2.15e5 delta*^-3/2 sum(rho)^-1/2`` in N and mm,
Harris and Kotzalas eq. 6.43; the paper prints the exponent of the curvature
sum as +1/2, a sign slip) is the roller's spherical large end on the flat rib
face: ``delta* = 1`` and ``sum(rho) = 2 / R_e``, which is Hertz's sphere on a
plane, ``K_a = (4/3) E* sqrt(R_e)`` in SI (:func:`k_point_sphere`).
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


def k_point_sphere(E_prime: float, R: float) -> float:
    """Hertz sphere of radius R on a plane, ``Q = K delta^(3/2)`` (N/m^(3/2)); ``E* = E'/2``."""
    return (4.0 / 3.0) * 0.5 * E_prime * R ** 0.5


def harris_point(sum_rho: float, delta_star: float = 1.0) -> float:
    """Eq. (8) with Harris's exponent: ``2.15e5 delta*^-1.5 sum_rho^-0.5`` (N, mm) in SI (N/m^1.5)."""
    return 2.15e5 * delta_star ** -1.5 * (sum_rho / _MM) ** -0.5 * _MM ** 1.5


def contacts(p) -> dict[str, float]:
    """All contact stiffnesses of ``p``: raceways (Eq. 10, steel), rib (Eq. 8), cage (Eqs. 10-11)."""
    E_s = e_prime(p.E_r, p.nu_r, p.E_r, p.nu_r)
    E_c = e_prime(p.E_r, p.nu_r, p.E_c, p.nu_c)
    K_o, K_i, K_n = roller_raceways(p)
    return {"K_ro": K_o, "K_ri": K_i, "K_n": K_n, "K_a": k_point_sphere(E_s, p.R_e),
            "K_cr": k_line(E_c, p.L_b)}
