"""Hertz normal contact: the contact ellipse from the relative curvatures, and the force law.

Notation (Johnson, *Contact Mechanics*, 1985, Sec. 4.1-4.2; Timoshenko & Goodier, *Theory of
Elasticity*, 3rd ed. 1970, Sec. 140): the gap between the undeformed bodies near the contact
point is ``h = A x^2 + B y^2`` with the relative principal curvatures ``A, B > 0``; x is the
rolling direction.  ``A + B`` is half the sum of the four principal curvatures of the two
bodies and ``B - A`` follows from the angle between their principal planes
(:func:`relative_curvatures`).

The ellipse has semi-axis ``a`` along x (curvature A) and ``b`` along y (curvature B); the
longer semi-axis lies along the smaller curvature.  Its eccentricity e, ``e^2 = 1 - (minor /
major)^2``, solves Hertz's equation (Johnson Sec. 4.2; Timoshenko & Goodier Sec. 140)::

    B/A = [(1/k^2) E(e) - K(e)] / [K(e) - E(e)],    k = minor/major   (here for A <= B)

with the complete elliptic integrals from ``scipy.special`` (scipy's parameter is
``m = e^2``; near the line-contact limit ``K`` comes from ``ellipkm1(1 - m) = ellipkm1(k^2)``
so that nothing is lost to rounding).  Then (Johnson Sec. 4.2)::

    major^3 = 3 N (K - E) / (2 pi E* e^2 min(A, B))
    delta   = 3 N K / (2 pi E* major)       (approach of distant points)
    p0      = 3 N / (2 pi a b)

written with the effective modulus ``1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2``.  This is the
same as Timoshenko & Goodier's form ``a = m (3 pi N (k1 + k2) / (4 (A + B)))^(1/3)``,
``b = n (...)^(1/3)`` with ``k_i = (1 - nu_i^2)/(pi E_i)``, because ``pi (k1 + k2) = 1/E*``;
the coefficients ``m, n`` returned here are those of that form, for the semi-axis along A
(m) and along B (n): ``m >= 1 >= n`` when ``A <= B`` and the other way round when ``A > B``.
The auxiliary angle theta of the printed tables is ``cos(theta) = |B - A| / (A + B)``.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
from scipy.special import ellipe, ellipkm1

from axlebox._params import ParameterError

__all__ = ["HertzContact", "relative_curvatures", "auxiliary_angle", "effective_modulus",
           "eccentricity", "hertz_mn", "hertz", "contact_stiffness", "normal_load",
           "penetration"]


class HertzContact(NamedTuple):
    """Result of :func:`hertz` (SI units; arrays where the inputs were arrays)."""

    a: np.ndarray        # semi-axis along x, the rolling direction (curvature A), m
    b: np.ndarray        # semi-axis along y (curvature B), m
    m: np.ndarray        # Hertz coefficient of a (Timoshenko & Goodier form), -
    n: np.ndarray        # Hertz coefficient of b, -
    e: np.ndarray        # eccentricity of the ellipse, e^2 = 1 - (minor/major)^2, -
    theta: np.ndarray    # auxiliary angle, cos(theta) = |B - A| / (A + B), rad
    delta: np.ndarray    # approach of distant points (penetration), m
    K_H: np.ndarray      # Hertz constant of N = K_H delta^(3/2), N/m^1.5
    p0: np.ndarray       # maximum pressure 3N / (2 pi a b), Pa
    a_over_b: np.ndarray


def _refuse(field: str, value, allowed: str):
    raise ParameterError(f"hertz.{field} = {value!r} is not allowed: {allowed}")


def _positive(field: str, x) -> np.ndarray:
    arr = np.asarray(x, dtype=float)
    if not np.all(np.isfinite(arr)) or np.any(arr <= 0.0):
        _refuse(field, x, "expected finite numbers > 0")
    return arr


def relative_curvatures(k1x, k1y, k2x, k2y, omega=0.0):
    """Relative principal curvatures ``(A, B, psi)`` of two bodies in contact.

    Body 1 has principal curvatures ``k1x`` (in the x-z plane, x the rolling direction) and
    ``k1y`` (y-z plane); body 2 has ``k2x, k2y`` in principal planes turned by ``omega`` (rad)
    about the common normal.  Curvatures are positive for convex surfaces, 1/m.  The sum of the
    two curvature tensors, halved, has eigenvalues A and B with (Johnson 1985, Sec. 4.1)::

        A + B = (k1x + k1y + k2x + k2y) / 2
        B - A = +-1/2 sqrt((k1x - k1y)^2 + (k2x - k2y)^2 + 2 (k1x - k1y)(k2x - k2y) cos 2 omega)

    A is the eigenvalue whose principal direction is nearer body 1's x axis (so for
    ``omega = 0``: ``A = (k1x + k2x)/2``, ``B = (k1y + k2y)/2``) and ``psi`` (``|psi| <= pi/4``) is
    the angle from x to that direction.  Works on arrays.
    """
    k1x, k1y, k2x, k2y, omega = np.broadcast_arrays(*(np.asarray(v, dtype=float)
                                                      for v in (k1x, k1y, k2x, k2y, omega)))
    c, s = np.cos(omega), np.sin(omega)
    # half the sum of the two curvature tensors in body 1's axes
    kxx = 0.5 * (k1x + k2x * c * c + k2y * s * s)
    kyy = 0.5 * (k1y + k2x * s * s + k2y * c * c)
    kxy = 0.5 * (k2x - k2y) * s * c
    mean = 0.5 * (kxx + kyy)
    half = np.hypot(0.5 * (kxx - kyy), kxy)
    psi = 0.5 * np.arctan2(2.0 * kxy, kxx - kyy)       # direction of the larger eigenvalue
    x_like = np.abs(psi) <= 0.25 * np.pi
    A = np.where(x_like, mean + half, mean - half)
    B = np.where(x_like, mean - half, mean + half)
    psi = np.where(x_like, psi, psi - np.copysign(0.5 * np.pi, psi))
    return A, B, psi


def auxiliary_angle(A, B):
    """Auxiliary angle theta (rad), ``cos(theta) = |B - A| / (A + B)``; 90 deg for a circle."""
    A, B = _positive("A", A), _positive("B", B)
    return np.arccos(np.abs(B - A) / (A + B))


def effective_modulus(E1, nu1, E2=None, nu2=None):
    """``E*`` with ``1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2`` (body 2 defaults to body 1)."""
    E2 = E1 if E2 is None else E2
    nu2 = nu1 if nu2 is None else nu2
    for field, v in (("E1", E1), ("E2", E2)):
        _positive(field, v)
    for field, v in (("nu1", nu1), ("nu2", nu2)):
        arr = np.asarray(v, dtype=float)
        if not np.all(np.isfinite(arr)) or np.any(arr < 0.0) or np.any(arr > 0.5):
            _refuse(field, v, "expected a Poisson ratio in [0, 0.5]")
    return 1.0 / ((1.0 - np.square(nu1)) / E1 + (1.0 - np.square(nu2)) / E2)


def _ratio(p):
    """``B/A`` (>= 1) of an ellipse with ``p = 1 - e^2 = (minor/major)^2``."""
    m = 1.0 - p
    K, E = ellipkm1(p), ellipe(m)
    # K - E loses digits to cancellation for tiny m: its series (A&S 17.3.11-12) instead
    k_minus_e = np.where(m < 1e-6, 0.25 * np.pi * m * (1.0 + 0.375 * m), K - E)
    top = np.where(m < 1e-6, 0.25 * np.pi * m * (1.0 + 1.125 * m), E / p - K)
    ratio = np.where(m > 0.0, top / np.where(m > 0.0, k_minus_e, 1.0), 1.0)
    return ratio, K, E, k_minus_e


def eccentricity(A, B):
    """Eccentricity e of the Hertz ellipse (``e^2 = 1 - (minor/major)^2``), vectorised.

    Solves Hertz's equation (module docstring) for ``x = ln p``, ``p = 1 - e^2``: ``ln(B/A)``
    is smooth and monotone in x with slope between -3/4 (circle) and -1 (line contact), so a
    secant iteration from ``b/a ~ (A/B)^(2/3)`` converges in about five steps.  Each element
    stops when its step falls below 1e-15 of x or stops shrinking (the rounding floor of
    ``K - E`` near the circle); any left after 40 steps goes to a bisection of ``[-700, 0]``.
    """
    A, B = np.broadcast_arrays(_positive("A", A), _positive("B", B))
    rho = np.maximum(A, B) / np.minimum(A, B)
    target = np.log(rho)
    round_ = rho == 1.0

    def resid(x):
        return np.log(_ratio(np.exp(x))[0]) - target

    x_prev = np.where(round_, -1.0, -4.0 / 3.0 * target)
    x = 0.9 * x_prev
    f_prev, f = resid(x_prev), resid(x)
    active = ~round_
    last = np.full(rho.shape, np.inf)
    for it in range(40):
        df = f - f_prev
        step = np.where(active & (df != 0.0), f * (x - x_prev) / np.where(df != 0.0, df, 1.0),
                        0.0)
        done = (np.abs(step) <= 1e-15 * np.abs(x)) | ((it >= 2) & (np.abs(step) >= last))
        active &= ~done
        if not active.any():
            break
        step = np.where(active, step, 0.0)
        x_prev, f_prev = x, f
        x = np.clip(x - step, -700.0, -1e-300)
        f = resid(x)
        last = np.where(active, np.abs(step), last)
    else:
        x = np.where(active, _bisect(resid, rho.shape), x)
    p = np.where(round_, 1.0, np.exp(x))
    return np.sqrt(1.0 - p)


def _bisect(resid, shape):
    lo, hi = np.full(shape, -700.0), np.zeros(shape)
    for _ in range(64):
        mid = 0.5 * (lo + hi)
        too_round = resid(mid) < 0.0             # the ratio falls as p grows
        hi = np.where(too_round, mid, hi)
        lo = np.where(too_round, lo, mid)
    return 0.5 * (lo + hi)


def _shape(A, B):
    """``(e, rho, f, K)``: eccentricity, ``rho = max/min`` curvature, ``f = (K - E)/e^2``
    (``pi/4`` for the circle) so that ``major^3 = 3 N f / (2 pi E* min(A, B))``, and K(e)."""
    e = eccentricity(A, B)
    rho = np.maximum(A, B) / np.minimum(A, B)
    m = e * e
    _, K, _, k_minus_e = _ratio(1.0 - m)
    f = np.where(m > 0.0, k_minus_e / np.where(m > 0.0, m, 1.0), 0.25 * np.pi)
    return e, rho, f, np.where(m > 0.0, K, 0.5 * np.pi)


def _mn(A, B, e, rho, f):
    major = np.cbrt(2.0 * f * (1.0 + rho) / np.pi)
    minor = major * np.sqrt(1.0 - e * e)
    return np.where(A <= B, major, minor), np.where(A <= B, minor, major)


def _stiffness(A, E_star, f, K, B):
    major1 = np.cbrt(3.0 * f / (2.0 * np.pi * E_star * np.minimum(A, B)))   # at N = 1 N
    return (3.0 * K / (2.0 * np.pi * E_star * major1)) ** -1.5


def hertz_mn(A, B):
    """Hertz coefficients ``(m, n)`` of the semi-axes along A and along B.

    ``a = m (3 N / (4 E* (A + B)))^(1/3)``, ``b = n (...)^(1/3)`` (Timoshenko & Goodier's
    ``3 pi N (k1 + k2) / (4 (A + B))`` with ``pi (k1 + k2) = 1/E*``).  From the module's
    equations, for the semi-major axis: ``m^3 = 2 (K - E)(1 + rho) / (pi e^2)``,
    ``rho = max(A, B)/min(A, B)``; the minor one is ``sqrt(1 - e^2)`` times it.
    """
    A, B = np.broadcast_arrays(_positive("A", A), _positive("B", B))
    e, rho, f, _ = _shape(A, B)
    return _mn(A, B, e, rho, f)


def hertz(A, B, N, E_star) -> HertzContact:
    """The Hertz contact of relative curvatures A (along x), B (along y) under normal load N.

    ``E_star`` from :func:`effective_modulus`.  ``N >= 0`` (N = 0 gives a point: a = b = 0).
    Vectorised over arrays.  Equations in the module docstring; ``K_H = N / delta^(3/2)``.
    """
    A, B = _positive("A", A), _positive("B", B)
    Nf = np.asarray(N, dtype=float)
    if not np.all(np.isfinite(Nf)) or np.any(Nf < 0.0):
        _refuse("N", N, "expected a normal load >= 0 N (a negative load means the bodies "
                "have separated)")
    E_star = _positive("E_star", E_star)
    A, B, Nf, E_star = np.broadcast_arrays(A, B, Nf, E_star)
    e, rho, f, K = _shape(A, B)
    major = np.cbrt(3.0 * Nf * f / (2.0 * np.pi * E_star * np.minimum(A, B)))
    minor = major * np.sqrt(1.0 - e * e)
    a = np.where(A <= B, major, minor)
    b = np.where(A <= B, minor, major)
    m, n = _mn(A, B, e, rho, f)
    loaded = major > 0.0
    delta = np.where(loaded, 3.0 * Nf * K / (2.0 * np.pi * E_star * np.where(loaded, major, 1.0)),
                     0.0)
    p0 = np.where(loaded, 3.0 * Nf / (2.0 * np.pi * np.where(loaded, a * b, 1.0)), 0.0)
    theta = np.arccos(np.abs(B - A) / (A + B))
    ratio = np.where(A <= B, 1.0 / np.sqrt(1.0 - e * e), np.sqrt(1.0 - e * e))
    K_H = _stiffness(A, E_star, f, K, B)
    # 0-d arrays become numpy scalars so that scalar input gives scalar output
    return HertzContact(*(np.asarray(v)[()] for v in (a, b, m, n, e, theta, delta, K_H, p0,
                                                      ratio)))


def contact_stiffness(A, B, E_star):
    """``K_H`` of ``N = K_H delta^(3/2)``: delta at N = 1 N raised to the power -3/2."""
    A, B = np.broadcast_arrays(_positive("A", A), _positive("B", B))
    E_star = _positive("E_star", E_star)
    e, rho, f, K = _shape(A, B)
    return _stiffness(A, E_star, f, K, B)


def normal_load(delta, A, B, E_star):
    """Normal load ``N = K_H max(delta, 0)^(3/2)`` for a penetration delta (m)."""
    d = np.asarray(delta, dtype=float)
    if not np.all(np.isfinite(d)):
        _refuse("delta", delta, "expected finite numbers (m)")
    return contact_stiffness(A, B, E_star) * np.maximum(d, 0.0) ** 1.5


def penetration(N, A, B, E_star):
    """Penetration ``delta = (N / K_H)^(2/3)``, the inverse of :func:`normal_load`."""
    Nf = np.asarray(N, dtype=float)
    if not np.all(np.isfinite(Nf)) or np.any(Nf < 0.0):
        _refuse("N", N, "expected a normal load >= 0 N")
    return (Nf / contact_stiffness(A, B, E_star)) ** (2.0 / 3.0)
