"""The car's speed along the track over time: phases of constant acceleration between the points of
a table of (time, speed), the speed held before the first point and after the last.

``SpeedProfile(t, v)`` (s, m/s): the speed is linear between points, so the distance run is the
exact integral, piecewise quadratic: ``x(t) = x_k + v_k (t - t_k) + a_k (t - t_k)^2 / 2`` with
``a_k = (v_{k+1} - v_k) / (t_{k+1} - t_k)``.  The kernels read it from the system's ``glob`` array
(:meth:`SpeedProfile.pack`, :func:`axlebox.mbs.kernel.speed.profile_at`): the wheel-rail
contact's reference speed (the creepages' denominator) and the traction of
:class:`axlebox.mbs.solver.elements.Drive` follow it.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axlebox._params import ParameterError


@dataclass(frozen=True)
class SpeedProfile:
    """Points ``(t[k], v[k])``: times (s, from 0, increasing) and speeds (m/s, > 0)."""

    t: tuple
    v: tuple

    def __post_init__(self):
        t, v = np.asarray(self.t, float), np.asarray(self.v, float)
        if t.ndim != 1 or t.shape != v.shape or t.size < 1:
            raise ParameterError(f"run.profile of {t.size} times and {v.size} speeds is not allowed: "
                                 "expected rows of (time s, speed km/h), at least one")
        if t[0] != 0.0:
            raise ParameterError(f"run.profile[0] time = {t[0]:g} is not allowed: expected 0 s "
                                 "(the profile starts with the run)")
        if np.any(np.diff(t) <= 0):
            k = int(np.flatnonzero(np.diff(t) <= 0)[0]) + 1
            raise ParameterError(f"run.profile[{k}] time = {t[k]:g} is not allowed: expected times "
                                 f"increasing (after {t[k - 1]:g} s)")
        if not np.all(np.isfinite(v) & (v > 0)):
            k = int(np.flatnonzero(~(np.isfinite(v) & (v > 0)))[0])
            raise ParameterError(f"run.profile[{k}] speed = {v[k] * 3.6:g} km/h is not allowed: "
                                 "expected a speed > 0")

    @classmethod
    def constant(cls, v: float) -> SpeedProfile:
        return cls((0.0,), (float(v),))

    @classmethod
    def from_kmh(cls, rows) -> SpeedProfile:
        """From config rows ``(time s, speed km/h)``."""
        rows = [tuple(r) for r in rows]
        return cls(tuple(float(r[0]) for r in rows), tuple(float(r[1]) / 3.6 for r in rows))

    @property
    def accelerates(self) -> bool:
        """Whether the speed ever changes (a profile that does not is a constant-speed run)."""
        return len(set(self.v)) > 1

    def _arrays(self):
        t, v = np.asarray(self.t, float), np.asarray(self.v, float)
        a = np.diff(v) / np.diff(t) if t.size > 1 else np.zeros(0)
        x = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])
        return t, v, a, x

    def at(self, time):
        """``(x, v, a)`` at ``time`` (s; scalar or array): distance run (m), speed (m/s) and
        acceleration (m/s^2)."""
        t, v, a, x = self._arrays()
        time = np.asarray(time, float)
        k = np.clip(np.searchsorted(t, time, side="right") - 1, 0, t.size - 1)
        inside = (k < t.size - 1) & (time >= t[k])
        ak = np.where(inside, np.append(a, 0.0)[k], 0.0)
        d = time - t[k]
        return x[k] + v[k] * d + 0.5 * ak * d * d, v[k] + ak * d, ak

    def distance(self, time) -> float:
        return self.at(time)[0]

    def speed(self, time) -> float:
        return self.at(time)[1]

    def pack(self) -> np.ndarray:
        """The kernels' form: ``[n, t_0..t_{n-1}, v_0.., x_0..]`` (:mod:`axlebox.mbs.kernel.speed`)."""
        t, v, _, x = self._arrays()
        return np.concatenate([[float(t.size)], t, v, x])
