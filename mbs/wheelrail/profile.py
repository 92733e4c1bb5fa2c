"""Wheel and rail profiles: the curve, its spline, and the reader for measured profiles.

Side-local frame, the same for the wheel and the rail of one side of the track:

- ``y`` lateral, positive towards the **field side** (away from the track centre), so a wheel's
  flange and a rail's gauge face lie at negative ``y``;
- ``z`` vertical, positive **up**;
- metres.

A rail profile is the height of the rail head, ``z = 0`` at the crown of the uncanted rail, ``y = 0``
on the rail's axis. A wheel profile is the height of the wheel's lowest generator above the running
(taping-line) point, so ``z = r0 - r(y)``: zero at the taping line, negative under the flange
(larger radius), ``y = 0`` at the taping line. ``flange_back`` is the side-local ``y`` of the wheel's
back face (-70 mm for S1002 and LM: the taping line lies 70 mm from the back face).

SIMPACK files (.prw wheel, .prr rail) use ``z`` down and millimetres; :func:`read_profile` applies
their header (units, shift, rotation, mirror, inversion) and turns them into this frame.
"""
from __future__ import annotations

import dataclasses
import math
import re
from functools import cached_property
from pathlib import Path

import numpy as np
from scipy.interpolate import CubicSpline

from axlebox._params import ParameterError

KINDS = ("wheel", "rail")


class ProfileError(ParameterError):
    """A profile (file or arrays) that cannot be used: not monotone, too short, not finite."""


@dataclasses.dataclass(frozen=True, eq=False)
class Profile:
    """A wheel or rail profile ``z(y)`` in the side-local frame (see the module docstring)."""

    y: np.ndarray
    z: np.ndarray
    kind: str
    name: str = ""
    source: str = ""
    flange_back: float | None = None

    def __post_init__(self):
        y = np.ascontiguousarray(self.y, dtype=float)
        z = np.ascontiguousarray(self.z, dtype=float)
        if self.kind not in KINDS:
            raise ProfileError(f"Profile.kind = {self.kind!r} is not allowed: expected one of {KINDS}")
        if y.ndim != 1 or y.shape != z.shape or y.size < 4:
            raise ProfileError(f"profile {self.name!r}: y and z must be 1-D of equal length >= 4, "
                               f"got shapes {y.shape} and {z.shape}")
        if not (np.all(np.isfinite(y)) and np.all(np.isfinite(z))):
            raise ProfileError(f"profile {self.name!r}: y and z must be finite")
        bad = np.flatnonzero(np.diff(y) <= 0.0)
        if bad.size:
            i = int(bad[0])
            raise ProfileError(
                f"profile {self.name!r} is not monotone: y[{i}] = {y[i]:.6g} m, y[{i + 1}] = "
                f"{y[i + 1]:.6g} m; y must increase strictly (vertical flanks only at the ends)")
        if self.kind == "wheel" and self.flange_back is None:
            object.__setattr__(self, "flange_back", -0.070)
        object.__setattr__(self, "y", y)
        object.__setattr__(self, "z", z)

    @cached_property
    def _spline(self) -> CubicSpline:
        return CubicSpline(self.y, self.z)

    def height(self, y, nu: int = 0):
        """``z(y)`` or its ``nu``-th derivative; outside the profile the end slopes continue."""
        yy = np.clip(y, self.y[0], self.y[-1])
        out = self._spline(yy, nu)
        if nu == 0:
            s = self._spline(yy, 1)
            out = out + s * (np.asarray(y) - yy)
        return out

    def curvature(self, y):
        """Signed curvature of the curve ``z(y)``: z'' / (1 + z'^2)^(3/2) (1/m, positive concave up)."""
        d1 = self._spline(y, 1)
        d2 = self._spline(y, 2)
        return d2 / (1.0 + d1 * d1) ** 1.5

    def radius(self, y, r0: float):
        """Wheel rolling radius ``r(y) = r0 - z(y)`` for a nominal radius ``r0``."""
        if self.kind != "wheel":
            raise ProfileError(f"profile {self.name!r} is a {self.kind} profile: it has no rolling radius")
        return r0 - self.height(y)

    def gauge_point(self, depth: float = 0.014) -> float:
        """Side-local ``y`` of the gauge point, ``depth`` below the rail's top (EN 13848-1: 14 mm)."""
        if self.kind != "rail":
            raise ProfileError(f"profile {self.name!r} is a wheel profile: it has no gauge point")
        level = self.z.max() - depth
        i = int(np.argmax(self.z))
        below = np.flatnonzero(self.z[:i] <= level)
        if below.size == 0:
            raise ProfileError(f"rail profile {self.name!r} does not reach {depth * 1e3:g} mm below "
                               f"its top on the gauge side")
        j = int(below[-1])
        # the gauge face is steep: interpolate y linearly in z between the two bracketing points
        return float(np.interp(level, self.z[j:j + 2], self.y[j:j + 2]))

    def canted(self, inclination: float = 1.0 / 40.0) -> "Profile":
        """The rail turned towards the track centre by ``atan(inclination)`` about its origin."""
        if self.kind != "rail":
            raise ProfileError(f"profile {self.name!r} is a wheel profile: only rails are canted")
        if not 0.0 <= inclination <= 0.1:
            raise ProfileError(f"rail cant = {inclination!r} is not allowed: expected a number in [0, 0.1]")
        t = math.atan(inclination)
        c, s = math.cos(t), math.sin(t)
        # counter-clockwise in (y outward, z up): the crown's normal leans towards the track centre
        y = c * self.y - s * self.z
        z = s * self.y + c * self.z
        y, z = _monotone_part(y, z)
        return dataclasses.replace(self, y=y, z=z, name=f"{self.name} canted 1:{1 / inclination:.0f}"
                                   if inclination else self.name)

    def resampled(self, step: float = 1e-4) -> "Profile":
        """The same curve on a uniform grid of ``step`` metres."""
        n = max(4, int(math.ceil((self.y[-1] - self.y[0]) / step)) + 1)
        y = np.linspace(self.y[0], self.y[-1], n)
        return dataclasses.replace(self, y=y, z=self._spline(y))

    def plot(self, ax=None):
        """Plot the profile in millimetres; returns the matplotlib Axes."""
        if ax is None:
            from axlebox._figures import figure
            ax = figure(figsize=(6, 3)).add_subplot()
        ax.plot(self.y * 1e3, self.z * 1e3, label=self.name or self.kind)
        ax.set_xlabel("y (mm, field side +)")
        ax.set_ylabel("z (mm, up)")
        ax.set_aspect("equal")
        ax.grid(True, lw=0.3)
        return ax


def _monotone_part(y: np.ndarray, z: np.ndarray):
    """Keep the run of strictly increasing ``y`` that holds the highest point (drops overhangs)."""
    ok = np.diff(y) > 0.0
    i = int(np.argmax(z))
    lo = i
    while lo > 0 and ok[lo - 1]:
        lo -= 1
    hi = i
    while hi < len(ok) and ok[hi]:
        hi += 1
    return y[lo:hi + 1], z[lo:hi + 1]


# --------------------------------------------------------------------------------------------- reader

_NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


def _parse_simpack(text: str, path: str):
    """Header values and points of a SIMPACK profile (``!`` starts a comment)."""
    keys: dict[str, str] = {}
    points = []
    inside = False
    block = ""
    for lineno, raw in enumerate(text.splitlines(), 1):
        line = raw.split("!", 1)[0].strip()
        if not line:
            continue
        low = line.lower()
        if low in ("header.begin", "spline.begin"):
            block = low.split(".")[0] + "."     # 'type' is in both blocks with different meanings
            continue
        if low == "point.begin":
            inside = True
            continue
        if low == "point.end":
            inside = False
            continue
        if inside:
            parts = line.replace(",", " ").split()
            if len(parts) < 2 or not all(_NUMBER.match(p) for p in parts[:2]):
                raise ProfileError(f"{path}: line {lineno} is not a point 'y z [weight]': {raw.strip()!r}")
            points.append((float(parts[0]), float(parts[1])))
        elif "=" in line:
            k, v = line.split("=", 1)
            keys[block + k.strip().lower()] = v.strip().strip("'\"")
    return keys, np.array(points, dtype=float).reshape(-1, 2)


def _parse_columns(text: str, path: str):
    points = []
    for lineno, raw in enumerate(text.splitlines(), 1):
        line = re.split(r"[!#%]", raw, maxsplit=1)[0].strip()
        if not line:
            continue
        parts = line.replace(",", " ").replace(";", " ").split()
        if len(parts) < 2 or not all(_NUMBER.match(p) for p in parts[:2]):
            raise ProfileError(f"{path}: line {lineno} is not two numbers 'y z': {raw.strip()!r}")
        points.append((float(parts[0]), float(parts[1])))
    return np.array(points, dtype=float).reshape(-1, 2)


def _strip_vertical_ends(y: np.ndarray, z: np.ndarray):
    """Drop the vertical flanks at the ends (equal ``y``), keeping the point nearest the top."""
    lo, hi = 0, len(y) - 1
    while lo < hi and y[lo + 1] == y[lo]:
        lo += 1
    while hi > lo and y[hi - 1] == y[hi]:
        hi -= 1
    return y[lo:hi + 1], z[lo:hi + 1]


def read_profile(path, kind: str | None = None, *, units: str = "mm", z_down: bool = True,
                 mirror_y: bool = False, flange_back: float | None = None,
                 name: str | None = None) -> Profile:
    """Read a measured or published profile.

    SIMPACK ``.prw`` / ``.prr`` files carry their kind, units and transformations in the header
    (``type`` 0 rail / 1 wheel, ``units.len.f``, ``shift.y/z``, ``rotate``, ``mirror.y/z``,
    ``inversion``; the points lie between ``point.begin`` and ``point.end``). Two-column text files
    (``y z`` per line, ``#``, ``%`` or ``!`` comments) take ``units`` ("mm" or "m") and ``z_down``
    (SIMPACK and MiniProf convention: z positive down) from the arguments. ``mirror_y`` turns the
    profile around after reading (use it when the flange or gauge face comes out on the field side).

    The points must run monotonically in ``y`` (either way); vertical flanks at the ends are
    dropped. Anything else (a point going back, a non-number) raises :class:`ProfileError` that
    names the file, the line or point and the values.
    """
    p = Path(path)
    if not p.is_file():
        raise FileNotFoundError(f"profile file {str(p)!r} does not exist")
    text = p.read_text(errors="replace")
    simpack = re.search(r"^\s*point\.begin", text, flags=re.M | re.I) is not None
    if simpack:
        keys, pts = _parse_simpack(text, str(p))
        ftype = keys.get("header.type")
        file_kind = {"0": "rail", "1": "wheel"}.get(ftype or "")
        if kind is None:
            kind = file_kind
        elif file_kind is not None and kind != file_kind:
            raise ProfileError(f"{p}: header says type = {ftype} ({file_kind}), "
                               f"but kind = {kind!r} was asked")
        f_len = float(keys.get("spline.units.len.f", "1000"))
        f_ang = float(keys.get("spline.units.ang.f", "1"))
        y, z = pts[:, 0] / f_len, pts[:, 1] / f_len
        y = y + float(keys.get("spline.shift.y", 0.0)) / f_len
        z = z + float(keys.get("spline.shift.z", 0.0)) / f_len
        rot = float(keys.get("spline.rotate", 0.0)) / f_ang
        if rot:
            c, s = math.cos(rot), math.sin(rot)
            y, z = c * y - s * z, s * y + c * z
        for axis, arr in (("y", y), ("z", z)):
            lo = float(keys.get(f"spline.bound.{axis}.min", 1.0)) / f_len
            hi = float(keys.get(f"spline.bound.{axis}.max", 0.0)) / f_len
            if lo < hi:     # SIMPACK: min > max means "no bound"
                keep = (arr >= lo) & (arr <= hi)
                y, z = y[keep], z[keep]
        if keys.get("spline.mirror.y", "0").strip() == "1":
            y = -y
        if keys.get("spline.mirror.z", "0").strip() == "1":
            z = -z
        z = -z      # SIMPACK's z points down
        comment = keys.get("spline.comment", "")
    else:
        if units not in ("mm", "m"):
            raise ProfileError(f"units = {units!r} is not allowed: expected 'mm' or 'm'")
        pts = _parse_columns(text, str(p))
        scale = 1e-3 if units == "mm" else 1.0
        y, z = pts[:, 0] * scale, pts[:, 1] * scale
        if z_down:
            z = -z
        comment = ""
    if kind not in KINDS:
        raise ProfileError(f"kind = {kind!r} is not allowed for {p}: expected 'wheel' or 'rail' "
                           f"(a two-column file does not say which)")
    if len(y) < 4:
        raise ProfileError(f"{p}: {len(y)} points, a profile needs at least 4")
    if mirror_y:
        y = -y
    if y[-1] < y[0]:
        y, z = y[::-1], z[::-1]
    y, z = _strip_vertical_ends(y, z)
    d = np.diff(y)
    bad = np.flatnonzero(d <= 0.0)
    if bad.size:
        i = int(bad[0])
        raise ProfileError(f"{p} is not monotone in y: points {i} and {i + 1} (after ordering) have "
                           f"y = {y[i] * 1e3:.6g} mm and {y[i + 1] * 1e3:.6g} mm")
    return Profile(y=y, z=z, kind=kind, name=name or (comment or p.stem), source=str(p),
                   flange_back=flange_back)
