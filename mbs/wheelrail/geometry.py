"""Contact geometry of a rigid wheelset on straight track: tables against lateral displacement.

Track frame: x forward, y to the left, z up (as the wheelset body, :mod:`axlebox.geometry.wheelset`).
Side ``L`` (index 0, sign s = +1) and ``R`` (index 1, s = -1). Each side has its own side-local
frame (:mod:`axlebox.mbs.wheelrail.profile`: y towards the field side, z up):

- the rail's side-local origin lies at track ``y = s * y_rail`` with ``y_rail`` such that the gauge
  measured between the gauge points (14 mm below the top of the canted rails, EN 13848-1) is
  ``gauge``;
- the wheel's side-local origin (its taping line) lies at ``y = s * y_wheel`` in the wheelset
  frame with ``y_wheel = back_to_back / 2 - flange_back``.

For a lateral displacement ``y`` of the wheelset the rigid contact problem is the classical 2-D one
(no yaw; the contact then lies in the vertical plane through the axle, where a rolled wheel's
cross-section is its generator turned by the roll angle): find the roll ``phi`` and height for
which both wheels touch their rails with zero gap. The contact point on each side is the point of
minimum vertical gap, so two-point contact shows as a jump of the contact point from tread to
flange.

Signs: the contact angle ``delta`` is the slope angle of the common tangent, positive when the
surface rises towards the field side (tread of a 1:40 canted rail: +0.025 rad; flange contact:
about +1.2 rad) on either side; curvatures are positive for a convex surface (rail crown, wheel
tread bulging towards the rail), negative for a concave one (wheel throat).
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from axlebox._params import ParameterError, check_ranges, param, require
from axlebox.mbs.wheelrail.profile import Profile

SIDES = ("L", "R")
_SIGN = (1.0, -1.0)


@dataclasses.dataclass(frozen=True)
class TrackLayout:
    """Where the wheels and rails sit (m); defaults: a Chinese B-type metro car as in W. Zhao et al.,
    Scientific Reports (2025), doi:10.1038/s41598-025-93857-x (typical values: 840 mm new wheels,
    standard gauge, 1:40 rail cant; the back-to-back of the built-in S1002/60E1 pair)."""

    r0: float = param(0.420, 0.2, 0.7, doc="nominal rolling radius at the taping line")
    gauge: float = param(1.435, 0.9, 1.7, doc="track gauge between the gauge points")
    back_to_back: float = param(1.360, 0.9, 1.6, doc="distance between the wheels' back faces "
                                "(the S1002/60E1 standard pair; the LM wheelset's is 1.353)")
    cant: float = param(1.0 / 40.0, 0.0, 0.1, unit="", doc="rail inclination (tan of the cant angle)")
    gauge_depth: float = param(0.014, 0.005, 0.02, doc="depth of the gauge point below the rail top")

    def __post_init__(self):
        check_ranges(self)
        require(self.back_to_back < self.gauge, self, "back_to_back",
                f"must be smaller than the gauge {self.gauge} m")


@dataclasses.dataclass
class _Side:
    """One wheel on one rail, both resampled for a vectorised gap search."""

    wheel: Profile
    rail: Profile
    s: float           # +1 left, -1 right
    y_wheel: float     # side-local wheel origin in the wheelset frame (|y|)
    y_rail: float      # side-local rail origin in the track frame (|y|)
    yw: np.ndarray     # wheel grid (side-local)
    zw: np.ndarray

    def _points(self, y, phi, yw, zw, r0):
        c, sn = math.cos(phi), math.sin(phi)
        Yw = self.s * (self.y_wheel + yw)
        Zw = zw - r0
        Y = y + Yw * c - Zw * sn
        Z = Yw * sn + Zw * c
        return Y, Z

    def gap(self, y, phi, yw, r0, zw=None):
        """Vertical gap wheel - rail at the wheel points ``yw`` (side-local), +inf off the rail;
        ``zw`` the wheel heights there when they are already known (the search grid)."""
        if zw is None:
            zw = self.wheel.height(yw)
        Y, Z = self._points(y, phi, yw, zw, r0)
        yr = self.s * Y - self.y_rail
        g = Z - self.rail.height(yr)
        off = (yr < self.rail.y[0]) | (yr > self.rail.y[-1])
        return np.where(off, np.inf, g), yr

    def min_gap(self, y, phi, r0):
        g, _ = self.gap(y, phi, self.yw, r0, self.zw)
        i = int(np.argmin(g))
        return g[i], i

    def refine(self, y, phi, r0, i):
        """Continuous minimum of the gap around grid point ``i``."""
        lo = self.yw[max(i - 1, 0)]
        hi = self.yw[min(i + 1, len(self.yw) - 1)]
        res = minimize_scalar(lambda t: float(self.gap(y, phi, np.array([t]), r0)[0][0]),
                              bounds=(lo, hi), method="bounded", options={"xatol": 1e-9})
        return float(res.x)


@dataclasses.dataclass
class ContactTable:
    """Contact geometry against the wheelset's lateral displacement ``y`` (columns L, R)."""

    y: np.ndarray               # (n,) lateral displacement of the wheelset, m (+ to the left)
    roll: np.ndarray            # (n,) wheelset roll, rad (right-handed about x: left side up)
    z: np.ndarray               # (n,) wheelset centre height above the nominal r0, m
    y_wheel: np.ndarray         # (n, 2) contact point on each wheel, side-local y, m
    y_rail: np.ndarray          # (n, 2) contact point on each rail, side-local y, m
    y_track: np.ndarray         # (n, 2) contact point, track-frame y, m
    r: np.ndarray               # (n, 2) rolling radius, m
    delta: np.ndarray           # (n, 2) contact angle in the track frame, rad
    delta_wheel: np.ndarray     # (n, 2) contact angle against the wheelset axis, rad
    kappa_wheel_x: np.ndarray   # (n, 2) wheel curvature in the rolling direction, 1/m
    kappa_wheel_y: np.ndarray   # (n, 2) wheel profile curvature (convex +), 1/m
    kappa_rail_y: np.ndarray    # (n, 2) rail profile curvature (convex +), 1/m
    layout: TrackLayout
    names: tuple

    @property
    def delta_r(self) -> np.ndarray:
        """Rolling radius difference r_L - r_R (m)."""
        return self.r[:, 0] - self.r[:, 1]

    @property
    def e0(self) -> float:
        """Half the lateral distance between the two contact points of the centred wheelset (m)."""
        i = int(np.argmin(np.abs(self.y)))
        return float(0.5 * (self.y_track[i, 0] - self.y_track[i, 1]))

    def at(self, y) -> dict:
        """Every column linearly interpolated at lateral displacement(s) ``y``."""
        y = np.asarray(y, dtype=float)
        if np.any(y < self.y[0]) or np.any(y > self.y[-1]):
            raise ParameterError(f"lateral displacement y = {y!r} m is outside the table "
                                 f"[{self.y[0]:g}, {self.y[-1]:g}] m")
        out = {}
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            if f.name == "y" or not isinstance(v, np.ndarray):
                continue
            if v.ndim == 1:
                out[f.name] = np.interp(y, self.y, v)
            else:
                out[f.name] = np.stack([np.interp(y, self.y, v[:, k]) for k in range(2)], axis=-1)
        return out

    def plot(self):
        """Rolling radius difference, contact angles, contact points and roll; returns the Figure."""
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(2, 2, figsize=(10, 6.5), sharex=True)
        ymm = self.y * 1e3
        ax[0, 0].plot(ymm, self.delta_r * 1e3)
        ax[0, 0].set_ylabel("r_L - r_R (mm)")
        for k, side in enumerate(SIDES):
            ax[0, 1].plot(ymm, np.degrees(self.delta[:, k]), label=side)
            ax[1, 0].plot(ymm, self.y_wheel[:, k] * 1e3, label=f"wheel {side}")
            ax[1, 0].plot(ymm, self.y_rail[:, k] * 1e3, "--", label=f"rail {side}")
        ax[0, 1].set_ylabel("contact angle (deg)")
        ax[1, 0].set_ylabel("contact point, side-local y (mm)")
        ax[1, 1].plot(ymm, self.roll * 1e3)
        ax[1, 1].set_ylabel("wheelset roll (mrad)")
        for a in ax.flat:
            a.grid(True, lw=0.3)
        for a in ax[1]:
            a.set_xlabel("wheelset lateral displacement (mm, + left)")
        ax[0, 1].legend()
        ax[1, 0].legend(fontsize=7)
        fig.suptitle(" on ".join(self.names))
        fig.tight_layout()
        return fig


def _sides(wheel, rail, layout, wheel_right, rail_right, step):
    rails = [rail.canted(layout.cant), (rail_right or rail).canted(layout.cant)]
    wheels = [wheel, wheel_right or wheel]
    out = []
    for k in range(2):
        w, r = wheels[k], rails[k]
        if w.kind != "wheel":
            raise ParameterError(f"wheel profile {w.name!r} is a {w.kind} profile")
        if r.kind != "rail":
            raise ParameterError(f"rail profile {r.name!r} is a {r.kind} profile")
        y_rail = 0.5 * layout.gauge - r.gauge_point(layout.gauge_depth)
        y_wheel = 0.5 * layout.back_to_back - w.flange_back
        yw = np.arange(w.y[0], w.y[-1], step)
        out.append(_Side(w, r, _SIGN[k], y_wheel, y_rail, yw, w.height(yw)))
    return out


def contact_table(wheel: Profile, rail: Profile, layout: TrackLayout | None = None, *,
                  y_max: float = 0.012, n: int = 241, wheel_right: Profile | None = None,
                  rail_right: Profile | None = None, step: float = 2e-5) -> ContactTable:
    """Contact geometry for lateral displacements ``y`` in ``[-y_max, y_max]`` (``n`` points).

    ``wheel`` and ``rail`` are the left-side profiles; the right side uses the same ones unless
    ``wheel_right`` / ``rail_right`` are given (worn or measured pairs). Rails are canted by
    ``layout.cant``. ``step`` is the grid on which the minimum gap is searched before it is refined.
    """
    layout = layout or TrackLayout()
    if not 0.0 < y_max <= 0.03:
        raise ParameterError(f"y_max = {y_max!r} m is not allowed: expected a number in (0, 0.03] m")
    if not 3 <= int(n) <= 10001:
        raise ParameterError(f"n = {n!r} is not allowed: expected an integer in [3, 10001]")
    sides = _sides(wheel, rail, layout, wheel_right, rail_right, step)
    r0 = layout.r0
    ys = np.linspace(-y_max, y_max, int(n))
    cols = {k: np.zeros((len(ys), 2)) for k in ("y_wheel", "y_rail", "y_track", "r", "delta",
                                                 "delta_wheel", "kappa_wheel_x", "kappa_wheel_y",
                                                 "kappa_rail_y")}
    roll = np.zeros(len(ys))
    zc = np.zeros(len(ys))

    def f(phi, y):
        return sides[0].min_gap(y, phi, r0)[0] - sides[1].min_gap(y, phi, r0)[0]

    for j, y in enumerate(ys):
        try:
            phi = brentq(f, -0.05, 0.05, args=(y,), xtol=1e-12)
        except ValueError:
            raise ParameterError(f"no two-sided contact at lateral displacement y = {y:g} m: "
                                 f"reduce y_max (flange climb or profiles that do not meet)") from None
        roll[j] = phi
        gaps = []
        for k, sd in enumerate(sides):
            _, i = sd.min_gap(y, phi, r0)
            t = sd.refine(y, phi, r0, i)
            g, yr = sd.gap(y, phi, np.array([t]), r0)
            gaps.append(g[0])
            yr = float(yr[0])
            dzw = float(sd.wheel.height(t, 1))
            dzr = float(sd.rail.height(yr, 1))
            r = r0 - float(sd.wheel.height(t))
            dw = math.atan(dzw)
            cols["y_wheel"][j, k] = t
            cols["y_rail"][j, k] = yr
            cols["y_track"][j, k] = sd.s * (yr + sd.y_rail)
            cols["r"][j, k] = r
            cols["delta"][j, k] = math.atan(dzr)
            cols["delta_wheel"][j, k] = dw
            cols["kappa_wheel_x"][j, k] = math.cos(dw) / r
            cols["kappa_wheel_y"][j, k] = float(sd.wheel.curvature(t))
            cols["kappa_rail_y"][j, k] = -float(sd.rail.curvature(yr))
        zc[j] = -0.5 * (gaps[0] + gaps[1]) - r0
    return ContactTable(y=ys, roll=roll, z=zc, layout=layout,
                        names=(wheel.name, rail.name), **cols)
