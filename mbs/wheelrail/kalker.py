"""Kalker's creep coefficients C11, C22, C23, C33 and the linear creep law.

Table E.3 of J.J. Kalker, *Three-Dimensional Elastic Bodies in Rolling Contact*, Kluwer 1990
(the coefficients of the linear theory for elliptical contact areas) for Poisson's ratio
nu = 0, 1/4, 1/2 and a/b = 0.1 ... 1, b/a = 0.1 ... 1.  C11, C22, C23 as typed into the
open-source CONTACT code (E.A.H. Vollebregt, Apache-2.0, ``src/m_hertz.f90``, ``linrol``);
C33 (which CONTACT does not carry) from the same Table E.3.  The nu = 1/4 column of all four
agrees at every row with a second, independent transcription of Table E.3 (nu = 1/4,
a/b = 0.1 to 10, nine rows); the C33 columns for nu = 0 and 1/2 have no second open copy to
check them against.

Interpolation (:func:`creep_coefficients`):

* in the axis ratio: a cubic spline ("not-a-knot") of ``ln C`` against ``s = ln(a/b)``
  through all 19 nodes of both branches at once.  One spline across a/b = 1 makes the result
  twice continuously differentiable there (two splines, one per branch, would meet with a
  kink), and the log-log variables suit the coefficients' power-law behaviour (C23 ~ sqrt(a/b)
  and, by the table's own slope, C33 ~ b/a for slender ellipses with a << b; C11, C22 ~
  (a/b)/ln(a/b) for a >> b), so the spline bends little: it stays within 1 % of log-log
  linear interpolation and does not leave the range of two neighbouring nodes by more than
  0.1 % (only where the nu = 1/2 C11 column is itself not monotone).
* in nu: quadratic (Lagrange) through nu = 0, 1/4, 1/2 of ``1/C``, the way CONTACT's
  ``linrol`` does it.  ``1/C`` rather than C because the slender-ellipse limit
  ``C11 = pi^2 / (4 (1 - nu))`` makes ``1/C11`` exactly linear in nu; a quadratic then only
  has to carry the remainder, and it reproduces the three tabulated columns exactly.
* outside 0.1 <= a/b <= 10 (g = min(a/b, b/a) < 0.1): Kalker's asymptotic expansions for
  slender ellipses (Kalker 1990, as coded in CONTACT's ``linrol``) for C11, C22 and
  C23, multiplied by a correction that is ``C_table / C_asymptote`` at g = 0.1 and fades
  linearly to 1 as g -> 0, so that the result is continuous at the edge of the table (the
  bare asymptotes differ from the g = 0.1 row by up to 5 %).  No asymptote for C33 was
  found: ``ln C33`` is extended linearly in ``ln(a/b)`` with the slope of the last table
  interval (about -0.95 at the a << b end, i.e. close to C33 ~ b/a; about -0.19 at the
  a >> b end).  This is an extrapolation, not Kalker's result.

Linear law (:func:`linear_creep_forces`), the law the coefficients of Table E.3 belong to
(Kalker 1990, App. E)::

    Fx = -G c^2 C11 xi
    Fy = -G c^2 C22 eta - G c^3 C23 phi,       c = sqrt(a b)
    Mz =  G c^3 C23 eta - G c^4 C33 phi

Sign convention: creepages are the velocity of the wheel's material point minus that of the
rail's at the contact, divided by the reference speed V, in the contact frame (t1 rolling
direction, t2 lateral in the tangent plane, n = t1 x t2 the normal pointing into the wheel):
``xi = dv.t1/V``, ``eta = dv.t2/V``, spin ``phi = (omega_wheel - omega_rail).n / V`` (1/m).
Fx, Fy are the tangential force *on the wheel* along t1, t2 and Mz its moment about n: the
force opposes the creepage.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.interpolate import CubicSpline

from axlebox._params import ParameterError

__all__ = ["NU_NODES", "AB_NODES", "TABLE_E3", "creep_coefficients", "linear_creep_forces"]

NU_NODES = np.array([0.0, 0.25, 0.5])

# rows: a/b = 0.1, 0.2, ..., 1.0 then b/a = 0.9, 0.8, ..., 0.1; columns nu = 0, 1/4, 1/2
_AB_BRANCH = np.round(np.arange(1, 11) / 10.0, 1)
AB_NODES = np.concatenate([_AB_BRANCH, 1.0 / _AB_BRANCH[-2::-1]])

TABLE_E3 = {
    "C11": np.array([
        [2.51, 3.31, 4.85], [2.59, 3.37, 4.81], [2.68, 3.44, 4.80], [2.78, 3.53, 4.82],
        [2.88, 3.62, 4.83], [2.98, 3.72, 4.91], [3.09, 3.81, 4.97], [3.19, 3.91, 5.05],
        [3.29, 4.01, 5.12], [3.40, 4.12, 5.20],
        [3.51, 4.22, 5.30], [3.65, 4.36, 5.42], [3.82, 4.54, 5.58], [4.06, 4.78, 5.80],
        [4.37, 5.10, 6.11], [4.84, 5.57, 6.57], [5.57, 6.34, 7.34], [6.96, 7.78, 8.82],
        [10.7, 11.7, 12.9]]),
    "C22": np.array([
        [2.51, 2.52, 2.53], [2.59, 2.63, 2.66], [2.68, 2.75, 2.81], [2.78, 2.88, 2.98],
        [2.88, 3.01, 3.14], [2.98, 3.14, 3.31], [3.09, 3.28, 3.48], [3.19, 3.41, 3.65],
        [3.29, 3.54, 3.82], [3.40, 3.67, 3.98],
        [3.51, 3.81, 4.16], [3.65, 3.99, 4.39], [3.82, 4.21, 4.67], [4.06, 4.50, 5.04],
        [4.37, 4.90, 5.56], [4.84, 5.48, 6.31], [5.57, 6.40, 7.51], [6.96, 8.14, 9.79],
        [10.7, 12.8, 16.0]]),
    "C23": np.array([
        [0.334, 0.473, 0.731], [0.483, 0.603, 0.809], [0.607, 0.715, 0.889],
        [0.720, 0.823, 0.977], [0.827, 0.929, 1.07], [0.930, 1.03, 1.18], [1.03, 1.14, 1.29],
        [1.13, 1.25, 1.40], [1.23, 1.36, 1.51], [1.33, 1.47, 1.63],
        [1.44, 1.59, 1.77], [1.58, 1.75, 1.94], [1.76, 1.95, 2.18], [2.01, 2.23, 2.50],
        [2.35, 2.62, 2.96], [2.88, 3.24, 3.70], [3.79, 4.32, 5.01], [5.72, 6.63, 7.89],
        [12.2, 14.6, 18.0]]),
    "C33": np.array([
        [6.42, 8.28, 11.7], [3.46, 4.27, 5.66], [2.49, 2.96, 3.72], [2.02, 2.32, 2.77],
        [1.74, 1.93, 2.22], [1.56, 1.68, 1.86], [1.43, 1.50, 1.60], [1.34, 1.37, 1.42],
        [1.27, 1.27, 1.27], [1.21, 1.19, 1.16],
        [1.16, 1.11, 1.06], [1.10, 1.04, 0.954], [1.05, 0.965, 0.852], [1.01, 0.892, 0.751],
        [0.958, 0.819, 0.650], [0.912, 0.747, 0.549], [0.868, 0.674, 0.446],
        [0.828, 0.601, 0.341], [0.795, 0.526, 0.228]]),
}
_NAMES = ("C11", "C22", "C23", "C33")
_S_NODES = np.log(AB_NODES)
# one spline per (coefficient, nu column): values of shape (19, 4, 3)
_SPLINE = CubicSpline(_S_NODES, np.log(np.stack([TABLE_E3[k] for k in _NAMES], axis=1)),
                      bc_type="not-a-knot")
_G_EDGE = 0.1
_LN4 = np.log(4.0)


def _refuse(field: str, value, allowed: str):
    raise ParameterError(f"kalker.{field} = {value!r} is not allowed: {allowed}")


def _is_number(x) -> bool:
    return isinstance(x, (float, int)) and not isinstance(x, bool) and math.isfinite(x)


def _nu_weights(nu):
    """Lagrange weights of nu = 0, 1/4, 1/2 (quadratic through the three columns)."""
    return np.stack([(nu - 0.25) * (nu - 0.5) * 8.0, -nu * (nu - 0.5) * 16.0,
                     nu * (nu - 0.25) * 8.0], axis=-1)


def _table(s, nu):
    """Interpolated table values (..., 4) at ``s = ln(a/b)`` inside [ln 0.1, ln 10]."""
    C = np.exp(_SPLINE(s))                            # (..., 4, 3)
    return 1.0 / np.einsum("...ij,...j->...i", 1.0 / C, _nu_weights(nu))


def _asymptotes(g, nu, slender_x):
    """Kalker's C11, C22, C23 for g = min(a/b, b/a) -> 0 (Kalker 1990, via CONTACT linrol).

    ``slender_x``: True where a << b (the ellipse is narrow in the rolling direction).
    """
    q = 1.0 - nu
    c11_a = np.pi ** 2 / (4.0 * q)
    c22_a = np.full_like(g, np.pi ** 2 / 4.0)
    c23_a = np.pi * np.sqrt(g) / (3.0 * q) * (1.0 + nu * (np.log(16.0 / g) - 5.0))
    al = np.log(16.0 / g ** 2)
    c11_b = 2.0 * np.pi / ((al - 2.0 * nu) * g) * (1.0 + (3.0 - _LN4) / (al - 2.0 * nu))
    d = q * al + 2.0 * nu
    c22_b = 2.0 * np.pi / g * (1.0 + q * (3.0 - _LN4) / d) / d
    c23_b = 2.0 * np.pi / (3.0 * g ** 1.5 * (q * al - 2.0 + 4.0 * nu))
    return np.stack([np.where(slender_x, c11_a, c11_b), np.where(slender_x, c22_a, c22_b),
                     np.where(slender_x, c23_a, c23_b)], axis=-1)


def creep_coefficients(a_over_b, nu):
    """Kalker's ``(C11, C22, C23, C33)`` for axis ratio a/b (a along the rolling direction).

    Vectorised over a/b and nu (broadcast).  Inside 0.1 <= a/b <= 10 the table is
    interpolated, outside it the asymptotes are used: see the module docstring.
    ``a/b > 0``, ``0 <= nu <= 0.5``.
    """
    if _is_number(a_over_b) and _is_number(nu) and 0.1 <= a_over_b <= 10.0 and 0.0 <= nu <= 0.5:
        # scalar inside the table (the common case): the same arithmetic without broadcasting
        inv = 1.0 / np.exp(_SPLINE(math.log(a_over_b)))                 # (4, 3)
        w = ((nu - 0.25) * (nu - 0.5) * 8.0, -nu * (nu - 0.5) * 16.0, nu * (nu - 0.25) * 8.0)
        return tuple(float(1.0 / (inv[i, 0] * w[0] + inv[i, 1] * w[1] + inv[i, 2] * w[2]))
                     for i in range(4))
    r = np.asarray(a_over_b, dtype=float)
    if not np.all(np.isfinite(r)) or np.any(r <= 0.0):
        _refuse("a_over_b", a_over_b, "expected finite axis ratios a/b > 0")
    nu_ = np.asarray(nu, dtype=float)
    if not np.all(np.isfinite(nu_)) or np.any(nu_ < 0.0) or np.any(nu_ > 0.5):
        _refuse("nu", nu, "expected a Poisson ratio in [0, 0.5]")
    r, nu_ = np.broadcast_arrays(r, nu_)
    s = np.log(r)
    s_in = np.clip(s, _S_NODES[0], _S_NODES[-1])
    C = _table(s_in, nu_)
    outside = s != s_in
    if np.any(outside):
        g = np.exp(-np.abs(s))                            # min(a/b, b/a) < 0.1 here
        slender_x = s < 0.0
        edge = np.where(slender_x, _G_EDGE, 1.0 / _G_EDGE)
        # C11, C22, C23: asymptote x (table/asymptote at the edge, fading to 1 as g -> 0)
        ratio = C[..., :3] / _asymptotes(np.full_like(g, _G_EDGE), nu_, slender_x)
        fade = (g / _G_EDGE)[..., None]
        asym = _asymptotes(np.minimum(g, _G_EDGE), nu_, slender_x) * (1.0 + (ratio - 1.0) * fade)
        # C33: ln C33 extended linearly in ln(a/b) with the slope of the last interval
        i0, i1 = np.where(slender_x, 0, -1), np.where(slender_x, 1, -2)
        c0 = _table(_S_NODES[i0], nu_)[..., 3]
        c1 = _table(_S_NODES[i1], nu_)[..., 3]
        slope = np.log(c1 / c0) / (_S_NODES[i1] - _S_NODES[i0])
        c33 = C[..., 3] * np.exp(slope * (s - np.log(edge)))
        C = np.where(outside[..., None], np.concatenate([asym, c33[..., None]], axis=-1), C)
    return tuple(np.asarray(C[..., i])[()] for i in range(4))


def linear_creep_forces(xi, eta, phi, a, b, G, nu):
    """Kalker's linear creep law: ``(Fx, Fy, Mz)`` on the wheel (sign convention above).

    ``a`` (rolling direction) and ``b`` the semi-axes (m), ``G`` the combined shear modulus
    (Pa), creepages xi, eta (-) and spin phi (1/m).  Vectorised.
    """
    a_, b_ = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    for field, v, arr in (("a", a, a_), ("b", b, b_), ("G", G, np.asarray(G, dtype=float))):
        if not np.all(np.isfinite(arr)) or np.any(arr <= 0.0):
            _refuse(field, v, "expected finite numbers > 0")
    C11, C22, C23, C33 = creep_coefficients(a_ / b_, nu)
    c = np.sqrt(a_ * b_)
    Gc2 = G * c * c
    Fx = -Gc2 * C11 * xi
    Fy = -Gc2 * C22 * eta - Gc2 * c * C23 * phi
    Mz = Gc2 * c * C23 * eta - Gc2 * c * c * C33 * phi
    return Fx, Fy, Mz
