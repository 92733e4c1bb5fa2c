"""Numba: the car's speed profile (:class:`axlebox.mbs.vehicle.speed.SpeedProfile`) read from ``glob``.

From slot :data:`G_PROF` the profile packs ``[n, t_0..t_{n-1}, v_0..v_{n-1}, x_0..x_{n-1}]``
(times s, speeds m/s, distances m at the points); ``n = 0``: no profile, the constant speed
``glob[G_V]``.
"""
from __future__ import annotations

from numba import njit

G_V = 3          # the constant speed (m/s), glob's slot (wheels.py lists them all)
G_LINE = 8       # 1 on a line (the bodies on their track frames, :mod:`.trajectory`), else 0
G_PROF = 9       # the profile's point count, its points after it


@njit(cache=True)
def profile_at(glob, t):
    """``(x, v, a)`` at ``t``: distance run (m, 0 at t = 0), speed (m/s), acceleration (m/s^2)."""
    n = int(glob[G_PROF])
    if n == 0:
        return glob[G_V] * t, glob[G_V], 0.0
    o = G_PROF + 1
    k = 0
    while k < n - 1 and t >= glob[o + k + 1]:
        k += 1
    tk, vk, xk = glob[o + k], glob[o + n + k], glob[o + 2 * n + k]
    a = 0.0
    if k < n - 1 and t >= tk:
        a = (glob[o + n + k + 1] - vk) / (glob[o + k + 1] - tk)
    d = t - tk
    return xk + vk * d + 0.5 * a * d * d, vk + a * d, a
