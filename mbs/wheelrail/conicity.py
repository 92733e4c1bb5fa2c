"""Equivalent conicity of a wheel-rail pair against the amplitude of the wheelset's lateral motion.

Two methods, both from the rolling radius difference ``dr(y) = r_L - r_R`` of a contact table:

- ``"harmonic"``: the conicity of the cone that gives the same fundamental harmonic of ``dr`` for
  a sinusoidal motion ``y = A sin(theta)`` (UIC 519, "harmonic linearisation"; the same number as
  EN 15302's linear regression of ``dr`` weighted by the time the wheelset spends at each ``y``):

      lambda_e(A) = 1 / (2 pi A) * integral_0^(2 pi) dr(A sin theta) sin theta  d theta

- ``"klingel"``: the wavelength ``L`` of the free kinematic motion of amplitude ``A``,
  ``y'' = -dr(y) / (2 e0 r0)`` (Klingel 1883 with the nonlinear ``dr``; UIC 519's integration
  method), turned into a cone by Klingel's formula ``L = 2 pi sqrt(e0 r0 / lambda)``:

      lambda_e(A) = e0 r0 (2 pi / L)^2

For a true cone both give its slope at every amplitude.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from axlebox._params import ParameterError
from axlebox.mbs.wheelrail.geometry import ContactTable

METHODS = ("harmonic", "klingel")


def _check(table: ContactTable, amplitudes, method: str) -> np.ndarray:
    if method not in METHODS:
        raise ParameterError(f"conicity method = {method!r} is not allowed: expected one of {METHODS}")
    A = np.atleast_1d(np.asarray(amplitudes, dtype=float))
    reach = min(-table.y[0], table.y[-1])
    if np.any(~np.isfinite(A)) or np.any(A <= 0.0) or np.any(A > reach):
        raise ParameterError(f"conicity amplitudes = {A.tolist()!r} m are not allowed: expected "
                             f"numbers in (0, {reach:g}] m, the contact table's range")
    return A


def equivalent_conicity(table: ContactTable, amplitudes, method: str = "harmonic", *,
                        n_theta: int = 4096) -> np.ndarray:
    """Equivalent conicity at each amplitude ``A`` (m) of the lateral motion (see module docstring)."""
    A = _check(table, amplitudes, method)
    if method == "harmonic":
        # the periodic trapezoid rule: exact for trigonometric polynomials, robust at contact jumps
        theta = np.arange(n_theta) * (2.0 * math.pi / n_theta)
        s = np.sin(theta)
        dr = np.interp(A[:, None] * s[None, :], table.y, table.delta_r)
        return (dr * s).mean(axis=1) / A
    return np.array([_klingel(table, a) for a in A])


def klingel_wavelength(table: ContactTable, amplitude: float) -> float:
    """Wavelength (m) of the free kinematic motion ``y'' = -dr(y)/(2 e0 r0)`` starting at ``y = A``."""
    _check(table, amplitude, "klingel")
    e0, r0 = table.e0, table.layout.r0

    def rhs(s, q):
        return (q[1], -np.interp(q[0], table.y, table.delta_r) / (2.0 * e0 * r0))

    def down(s, q):
        return q[0]
    # an upper bound on the wavelength: the linearised motion at the smallest secant conicity
    lam = max(abs(np.interp(amplitude, table.y, table.delta_r)) / (2.0 * amplitude), 1e-4)
    span = 6.0 * 2.0 * math.pi * math.sqrt(e0 * r0 / lam)
    sol = solve_ivp(rhs, (0.0, span), (amplitude, 0.0), events=down, rtol=1e-8, atol=1e-11,
                    max_step=span / 400.0)
    s0 = sol.t_events[0]
    if len(s0) < 3:
        raise ParameterError(f"amplitude {amplitude:g} m: the kinematic motion does not oscillate "
                             f"(no restoring rolling radius difference)")
    return float(s0[2] - s0[0])


def _klingel(table: ContactTable, amplitude: float) -> float:
    L = klingel_wavelength(table, amplitude)
    return table.e0 * table.layout.r0 * (2.0 * math.pi / L) ** 2
