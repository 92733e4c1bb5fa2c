"""Wheel tread defects as radius deviations around the rolling circle: flats and polygons.

A defect is the wheel's radius deviation ``dr(s)`` (m, negative where material is missing) at arc
length ``s`` around the rolling circle of radius r0 (circumference ``C = 2 pi r0``), sampled with
its slope on the grid of a wheel record (:func:`axlebox.mbs.track.roughness.wheel_record`), so the
wheel-rail element reads it as it reads the wheel's roughness (mbs/kernel/wheels.py): a flat
lifts the rail under the wheel by ``dr``, and where ``dr`` drops faster than the wheel can
follow, the contact opens and closes again.

* **Flat**, length L (the chord), centred at arc ``s_f``.  Its depth is ``d = r0 - sqrt(r0^2 -
  L^2/4)`` (~ L^2 / (8 r0) = L^2 / (4 D), D the wheel diameter).

  - ``shape = "fresh"``: the chord itself, ``dr = (r0 - d) / cos(phi) - r0`` for
    ``|phi| <= phi_0``, phi the angle from the flat's centre, ``cos(phi_0) = (r0 - d) / r0``: sharp edges.
  - ``shape = "rounded"`` (a worn flat): ``dr = -(d / 2) (1 + cos(2 pi x / L))`` for
    ``|x| <= L/2``, x the arc from the centre, the haversine shape of a flat whose edges have worn round,
    with the chord's depth d for its length L.  The haversine form is the one commonly credited
    to Newton and Clark (J. Mech. Eng. Sci. 21, 1979) and used by Wu and Thompson (J. Sound
    Vib. 251, 2002, 115-139) and Pieringer, Kropp and Nielsen (Wear 314, 2014); some of that
    literature pairs a rounded flat's length with the depth L^2 / (16 r0), i.e. a rounded flat
    sqrt(2) longer than the fresh one it wore from (not checked here against the printed
    papers: give the length of the fresh flat to compare).  Pieringer et al. find the flat's
    longitudinal geometry matters more to the impact than the contact model, and a radius
    deviation fed to a point contact overstates the impact of a sharp edge: the wheel's own
    curvature rounds what the contact sees (Wu and Thompson).

* **Polygon**, orders n_k with amplitudes a_k (m) and phases psi_k: ``dr = sum a_k cos(n_k s /
  r0 + psi_k)``, the out-of-round wheel's harmonics around its circumference; at speed V it
  excites ``n_k V / C`` Hz, n_k times the wheel's rotation rate.
"""
from __future__ import annotations

import math

import numpy as np

from axlebox._params import ParameterError

SHAPES = ("fresh", "rounded")


def flat_depth(L: float, r0: float) -> float:
    """Depth of a flat of chord length L on a wheel of radius r0 (m)."""
    return r0 - math.sqrt(r0 * r0 - 0.25 * L * L)


def _arc(s: np.ndarray, s_c: float, C: float) -> np.ndarray:
    """Signed arc from ``s_c`` to ``s`` on a circle of circumference C, in [-C/2, C/2)."""
    return (np.asarray(s, float) - s_c + 0.5 * C) % C - 0.5 * C


def flat(s, L: float, r0: float, s_c: float = 0.0, shape: str = "rounded"):
    """``(dr, slope)`` of a flat (module docstring) at arc ``s`` (m)."""
    if shape not in SHAPES:
        raise ParameterError(f"wheel_defects.shape = {shape!r} is not allowed: expected one of "
                             f"{', '.join(SHAPES)}")
    if not (0.0 < L < r0):
        raise ParameterError(f"wheel_defects.length = {L!r} is not allowed: expected a flat between "
                             f"0 and the wheel radius, {r0:g} m")
    C = 2 * math.pi * r0
    x = _arc(s, s_c, C)
    d = flat_depth(L, r0)
    dr = np.zeros_like(x)
    slope = np.zeros_like(x)
    if shape == "fresh":
        phi = x / r0
        phi0 = math.acos((r0 - d) / r0)
        on = np.abs(phi) <= phi0
        c = np.cos(phi[on])
        dr[on] = (r0 - d) / c - r0
        slope[on] = (r0 - d) * np.sin(phi[on]) / (c * c) / r0
    else:
        on = np.abs(x) <= 0.5 * L
        k = 2 * math.pi / L
        dr[on] = -0.5 * d * (1 + np.cos(k * x[on]))
        slope[on] = 0.5 * d * k * np.sin(k * x[on])
    return dr, slope


def polygon(s, r0: float, orders, amplitudes, phases=None):
    """``(dr, slope)`` of a polygonal wheel (module docstring) at arc ``s`` (m)."""
    n = np.atleast_1d(np.asarray(orders))
    a = np.atleast_1d(np.asarray(amplitudes, float))
    ok = n.ndim == 1 and n.size > 0 and n.size == a.size and np.all(n == np.round(n)) and np.all(n >= 1)
    if not ok:
        raise ParameterError(f"wheel_defects.orders = {np.asarray(orders).tolist()!r} is not allowed: "
                             "expected whole orders >= 1, one amplitude each")
    if not np.all(np.isfinite(a)) or np.any(a < 0):
        raise ParameterError(f"wheel_defects.amplitudes = {a.tolist()!r} is not allowed: expected "
                             "amplitudes >= 0 m")
    psi = np.zeros(n.size) if phases is None else np.atleast_1d(np.asarray(phases, float))
    th = np.asarray(s, float)[..., None] / r0
    dr = (a * np.cos(n * th + psi)).sum(-1)
    slope = (-a * n / r0 * np.sin(n * th + psi)).sum(-1)
    return dr, slope
