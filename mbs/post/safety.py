"""Running safety from the wheel-rail forces: each wheel's guiding and vertical forces Y and Q, the
derailment quotient Y/Q against Nadal's flange-climb limit, and each wheelset's sum of guiding
forces against Prud'homme's track-shift limit.

Forces (the result file's ``wheelrail/<wheel>/force``: on the wheel, in the track frame x forward,
y left, z up in the track plane): the rail's reaction on the wheel ``F``, so the wheel's force on
the rail is ``-F``.  For a wheel on side ``s`` (+1 left, -1 right),

* ``Q = F_z``, the vertical force (the rail holds the wheel up);
* ``Y = -s F_y``, the guiding force on the rail, positive towards the rail's field side (the
  flange pushing its rail outwards);
* ``sum Y = -(F_y,L + F_y,R)``, the wheelset's net lateral force on the track, in track y.

Limits:

* Nadal (1908), a flange on the point of climbing at contact angle ``delta`` with friction
  ``mu``: ``(Y/Q)_lim = (tan delta - mu) / (1 + mu tan delta)`` (:func:`nadal`); at the S1002
  flange's 70 deg (:func:`flange_angle`) and ``mu`` 0.36, 1.20, the limit EN 14363 takes;
* Prud'homme (1967), the lateral force a ballasted track resists without shifting:
  ``(sum Y)_lim = alpha (10 kN + 2 Q0 / 3)``, ``Q0`` the static wheel load (the track shift
  criterion of EN 14363, there written with the axle load ``P0 = 2 Q0``: ``alpha (10 + P0 / 3)``
  kN; ``alpha`` 1 for passenger vehicles) (:func:`prudhomme`).

EN 14363 judges both on their sliding means over 2 m of track (:func:`sliding_mean`): a peak
shorter than that (a rail joint's, a flange touching for an instant) neither climbs a flange nor
shifts a track.
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from axlebox._params import ParameterError

ALPHA_PASSENGER = 1.0           # Prud'homme's factor for passenger vehicles (EN 14363)
WINDOW = 2.0                    # m: EN 14363's sliding mean of Y/Q and sum Y


def nadal(delta, mu):
    """Nadal's flange-climb limit ``(tan delta - mu) / (1 + mu tan delta)`` at the flange contact
    angle ``delta`` (rad) and friction ``mu``."""
    t = np.tan(delta)
    return (t - mu) / (1.0 + mu * t)


def prudhomme(Q0, alpha: float = ALPHA_PASSENGER):
    """Prud'homme's track-shift limit of a wheelset's sum of guiding forces, N:
    ``alpha (10 kN + 2 Q0 / 3)``, ``Q0`` the static wheel load (N)."""
    return alpha * (1e4 + 2.0 * np.asarray(Q0, dtype=float) / 3.0)


def flange_angle(wheel) -> float:
    """The steepest contact angle of a wheel profile's flange flank, rad: ``atan |dz/dy|`` of
    its samples at the steepest between the flange's tip (the profile's lowest point, its largest radius) and
    the taping line (y = 0), where a flange meets its rail's gauge corner (not the back face
    beyond the tip)."""
    y, z = wheel.y, wheel.z
    tip = int(np.argmin(z))
    flank = (y >= y[tip]) & (y <= 0.0)
    if np.count_nonzero(flank) < 2:
        raise ParameterError(f"wheel profile {wheel.name!r} has no flange between its lowest point "
                             f"(y = {y[tip]:g} m) and the taping line (y = 0)")
    # chord slopes of the samples: each is the profile's slope somewhere between its two points
    # (mean value theorem), so none overshoots, as a spline's derivative does at a section's join
    slope = np.abs(np.diff(z[flank]) / np.diff(y[flank]))
    return float(math.atan(np.max(slope)))


def sliding_mean(x, s, window: float = WINDOW):
    """The mean of ``x`` (samples along its first axis) over ``window`` metres of track centred
    on each sample, ``s`` the distance run at each (non-decreasing): the integral of ``x ds``
    by the trapezoidal rule, interpolated at ``s +- window / 2`` (at the record's ends the window
    is cut to the record)."""
    x, s = np.asarray(x, dtype=float), np.asarray(s, dtype=float)
    if s.ndim != 1 or s.size != x.shape[0] or s.size < 2:
        raise ParameterError(f"sliding_mean: s has shape {s.shape}, expected ({x.shape[0]},) with "
                             "at least 2 samples")
    if np.any(np.diff(s) < 0.0):
        raise ParameterError("sliding_mean: s is not allowed to decrease: the distance run")
    ds = np.diff(s).reshape((-1,) + (1,) * (x.ndim - 1))
    c = np.concatenate([np.zeros((1,) + x.shape[1:]), np.cumsum(0.5 * (x[1:] + x[:-1]) * ds, axis=0)])
    lo = np.clip(s - 0.5 * window, s[0], s[-1])
    hi = np.clip(s + 0.5 * window, s[0], s[-1])
    flat = c.reshape(s.size, -1)
    cum = np.stack([np.interp(hi, s, col) - np.interp(lo, s, col) for col in flat.T], axis=1)
    span = (hi - lo)[:, None]
    out = np.where(span > 0.0, cum / np.where(span > 0.0, span, 1.0), flat)
    return out.reshape(x.shape)


class WheelForces(NamedTuple):
    """Y, Q and Y/Q of one wheel, and their 2 m sliding means (arrays over time)."""

    Y: np.ndarray
    Q: np.ndarray
    YQ: np.ndarray
    YQ_2m: np.ndarray


def wheel_forces(F, side: int, s) -> WheelForces:
    """Y, Q, Y/Q and its sliding mean over :data:`WINDOW` of one wheel from its force ``F``
    (``(n, 3)``, on the wheel, track frame) on side ``side`` (+1 left, -1 right), ``s`` the
    distance run.  Where the wheel has lifted (Q <= 0), Y/Q is not defined: NaN, and the sliding
    mean is taken over the rest of its window (NaN where the wheel is off its rail all through
    the window: a lifted wheel is not a safe one)."""
    F = np.asarray(F, dtype=float)
    Y, Q = -side * F[:, 1], F[:, 2]
    lifted = Q <= 0.0
    YQ = np.where(lifted, np.nan, Y / np.where(lifted, 1.0, Q))
    if not lifted.any():
        return WheelForces(Y, Q, YQ, sliding_mean(YQ, s))
    on = sliding_mean((~lifted).astype(float), s)               # the share of the window in contact
    total = sliding_mean(np.where(lifted, 0.0, YQ), s)
    return WheelForces(Y, Q, YQ, np.where(on > 0.0, total / np.where(on > 0.0, on, 1.0), np.nan))


def sum_Y(F_left, F_right):
    """A wheelset's net lateral force on the track, N: ``-(F_y,L + F_y,R)``."""
    return -(np.asarray(F_left, dtype=float)[:, 1] + np.asarray(F_right, dtype=float)[:, 1])
