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
        from axlebox._figures import subplots
        fig, ax = subplots(2, 2, figsize=(10, 6.5), sharex=True)
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
            point, g = _point(sd, y, phi, r0, t)
            gaps.append(g)
            for name, v in point.items():
                cols[name][j, k] = v
        zc[j] = -0.5 * (gaps[0] + gaps[1]) - r0
    return ContactTable(y=ys, roll=roll, z=zc, layout=layout,
                        names=(wheel.name, rail.name), **cols)


def _point(sd: _Side, y, phi, r0, t) -> tuple[dict, float]:
    """The contact columns of :class:`ContactTable` at the wheel point ``t`` (side-local), and
    the vertical wheel-rail gap there."""
    g, yr = sd.gap(y, phi, np.array([t]), r0)
    yr = float(yr[0])
    r = r0 - float(sd.wheel.height(t))
    dw = math.atan(float(sd.wheel.height(t, 1)))
    return {"y_wheel": t, "y_rail": yr, "y_track": sd.s * (yr + sd.y_rail), "r": r,
            "delta": math.atan(float(sd.rail.height(yr, 1))), "delta_wheel": dw,
            "kappa_wheel_x": math.cos(dw) / r, "kappa_wheel_y": float(sd.wheel.curvature(t)),
            "kappa_rail_y": -float(sd.rail.curvature(yr))}, float(g[0])


def field_extension(wheel: Profile, rail: Profile, table: ContactTable, side: int, reach: float,
                    *, wheel_right: Profile | None = None, rail_right: Profile | None = None,
                    step: float = 2e-5) -> ContactTable:
    """``table`` continued for one wheel by ``reach`` of lateral displacement beyond its field-side
    end (left wheel: y below ``table.y[0]``; right: above ``table.y[-1]``), at the same row step.

    Why: the rigid wheelset's two-sided problem ends where the other wheel's flange climbs
    (``y_max``), but a wheel can run further onto its own field side than that, where the rails'
    gauge opens under a wheelset held against the outer rail of a curve (FRA class 5: gauge
    +9.8 mm within the first 14 m of a record; an inner wheel 7.9 + 4.9 mm off its rail).  There
    the wheel touches its rail alone: the roll is held at the table's end and the height is that
    wheel's own touch (the element's penetration starts from any touching pose).  The other
    side's columns repeat this side's; only ``side``'s are meant to be read."""
    layout = table.layout
    r0 = layout.r0
    sd = _sides(wheel, rail, layout, wheel_right, rail_right, step)[side]
    dy = table.y[1] - table.y[0]
    n = int(math.ceil(reach / dy))
    end = 0 if side == 0 else -1
    sign = -1.0 if side == 0 else 1.0
    ys = table.y[end] + sign * dy * np.arange(1, n + 1)
    phi = float(table.roll[end])
    cols = {k: np.zeros((n, 2)) for k in ("y_wheel", "y_rail", "y_track", "r", "delta",
                                          "delta_wheel", "kappa_wheel_x", "kappa_wheel_y",
                                          "kappa_rail_y")}
    zc = np.zeros(n)
    for j, y in enumerate(ys):
        _, i = sd.min_gap(y, phi, r0)
        t = sd.refine(y, phi, r0, i)
        point, g = _point(sd, y, phi, r0, t)
        zc[j] = -g - r0
        for name, v in point.items():
            cols[name][j, :] = v
    roll = np.full(n, phi)

    def join(old, new):                       # rows kept in ascending y
        return np.concatenate([new[::-1], old]) if side == 0 else np.concatenate([old, new])

    return ContactTable(y=join(table.y, ys), roll=join(table.roll, roll), z=join(table.z, zc),
                        layout=layout, names=table.names,
                        **{k: join(getattr(table, k), v) for k, v in cols.items()})


# ------------------------------------------------------------------------- multi-point contact
NPT = 3            # contact points per wheel at most: tread, flange root, flange


@dataclasses.dataclass
class ContactRegions:
    """Each wheel's surface cut into up to :data:`NPT` regions, tread first, and in each region
    its own closest point to the rail at every row of a :class:`ContactTable` (the rigid
    wheelset's roll and height there).  Columns as :class:`ContactTable`'s, shape ``(n, 2, NPT)``
    (row, side, region), plus ``gap``: the region's vertical wheel-rail gap at that point, 0 for
    the region that holds the rigid contact, capped at 1 m.  A region that lies wholly beside
    the rail head repeats its point of the nearest row where it does not, one the wheel does not
    have repeats region 0's, each with a gap of 1 m.

    Why: on S1002/60E1 the single contact point jumps from the tread (7 deg) to the flange root
    (18 deg) at 4.8-5.2 mm and from there to the flange (26 -> 70 deg) at 6.0-6.4 mm of lateral
    displacement.  One elastic contact smoothed across such a jump gives a normal half-way
    between tread and flange, too weak laterally and too stiff vertically; a real wheelset
    touches both at once (two-point contact), each patch its own normal and tangential problem
    (Shabana, Zaazaa & Sugiyama, *Railroad Vehicle Dynamics*, CRC 2008, ch. 5; Pombo & Ambrosio,
    Multibody Syst. Dyn. 19 (2008) 91-114).  The regions' borders are the middles of the
    single-point contact's jumps on the wheel where the contact angle changes by more than
    ``split_angle`` (the tread's own jump at 0.1 mm, 1.5 -> 3.8 deg, stays one region: the
    element smooths it, element.py step 3)."""

    splits: np.ndarray          # (2, NPT - 1) wheel side-local y of the borders, NaN: none
    y_wheel: np.ndarray
    y_rail: np.ndarray
    y_track: np.ndarray
    r: np.ndarray
    delta: np.ndarray
    delta_wheel: np.ndarray
    kappa_wheel_x: np.ndarray
    kappa_wheel_y: np.ndarray
    kappa_rail_y: np.ndarray
    gap: np.ndarray


def region_splits(table: ContactTable, split_angle: float) -> np.ndarray:
    """Per side, the borders between the wheel's contact regions (side-local wheel y, tread to
    flange, NaN-padded to ``NPT - 1``): the middles of the single-point contact's jumps of more
    than 1 mm on the wheel with a contact-angle change over ``split_angle`` (rad); where there
    are more, the ``NPT - 1`` largest in angle."""
    out = np.full((2, NPT - 1), np.nan)
    for k in range(2):
        yw, d = table.y_wheel[:, k], table.delta[:, k]
        jump = np.flatnonzero((np.abs(np.diff(yw)) > 1e-3) & (np.abs(np.diff(d)) > split_angle))
        jump = jump[np.argsort(-np.abs(np.diff(d))[jump])][:NPT - 1]
        mids = np.sort(0.5 * (yw[jump] + yw[jump + 1]))[::-1]     # tread (field side) first
        out[k, :mids.size] = mids
    return out


def contact_regions(wheel: Profile, rail: Profile, table: ContactTable, *,
                    wheel_right: Profile | None = None, rail_right: Profile | None = None,
                    step: float = 2e-5, split_angle: float = 0.1,
                    splits: np.ndarray | None = None, side: int | None = None) -> ContactRegions:
    """The :class:`ContactRegions` of ``table`` (built from the same profiles and layout).  A
    region's closest point is the minimum of the vertical gap on the search grid ``step`` inside
    it, refined by a parabola through its neighbours (the global one is the table's own point).
    ``side`` (0 left, 1 right) computes that wheel's columns alone, the other's left zero (a
    :func:`field_extension` table is meant for one side)."""
    layout = table.layout
    r0 = layout.r0
    sides = _sides(wheel, rail, layout, wheel_right, rail_right, step)
    splits = region_splits(table, split_angle) if splits is None else splits
    n = table.y.size
    cols = {f.name: np.zeros((n, 2, NPT)) for f in dataclasses.fields(ContactRegions)
            if f.name != "splits"}
    for k, sd in enumerate(sides):
        if side is not None and k != side:
            continue
        edges = np.concatenate([[np.inf], splits[k][~np.isnan(splits[k])], [-np.inf]])
        masks = [(sd.yw <= edges[p]) & (sd.yw > edges[p + 1]) for p in range(edges.size - 1)]
        for j in range(n):
            y, phi = table.y[j], table.roll[j]
            g, _ = sd.gap(y, phi, sd.yw, r0, sd.zw)
            g0 = float(np.min(g))
            for p in range(NPT):
                idx = np.flatnonzero(masks[p]) if p < len(masks) else np.zeros(0, int)
                i = idx[int(np.argmin(g[idx]))] if idx.size else -1
                if i < 0 or not np.isfinite(g[i]):    # no such region, or it lies beside the
                    for name in cols:                 # rail head: filled below, never touching
                        cols[name][j, k, p] = np.nan
                    cols["gap"][j, k, p] = 1.0
                    continue
                rigid = edges[p] >= table.y_wheel[j, k] > edges[p + 1]
                if rigid:
                    t = table.y_wheel[j, k]                   # the rigid contact itself
                else:
                    t = sd.yw[i]
                    if idx[0] < i < idx[-1]:
                        gm, gc, gq = g[i - 1], g[i], g[i + 1]
                        den = gm - 2.0 * gc + gq
                        if den > 0.0:
                            t += 0.5 * step * (gm - gq) / den
                point, gp = _point(sd, y, phi, r0, t)
                for name, v in point.items():
                    cols[name][j, k, p] = v
                if rigid:
                    gp = 0.0
                else:
                    gp = min(max(gp - g0, 0.0), 1.0) if np.isfinite(gp) else 1.0
                cols["gap"][j, k, p] = gp
        # a region without a point of its own keeps that of its nearest row on the rail head,
        # or region 0's (a region the wheel lacks): continuous columns for the element's
        # smoothing
        for p in range(1, NPT):
            off = np.isnan(cols["y_wheel"][:, k, p])
            if not off.any():
                continue
            rows = np.arange(n)
            if off.all():
                src, p_src = rows, 0
            else:
                on = np.flatnonzero(~off)
                hi = on[np.clip(np.searchsorted(on, rows), 0, on.size - 1)]
                lo = on[np.clip(np.searchsorted(on, rows) - 1, 0, on.size - 1)]
                src, p_src = np.where(np.abs(hi - rows) <= np.abs(lo - rows), hi, lo), p
            for name in cols:
                if name != "gap":
                    cols[name][off, k, p] = cols[name][src[off], k, p_src]
    return ContactRegions(splits=splits, **cols)
