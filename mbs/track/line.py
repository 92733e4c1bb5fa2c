"""The line's design geometry: consecutive tangents, transitions and circular curves, each with
its cant (superelevation) and gauge widening, the irregularities riding on top.

A line is a list of :class:`Segment` (the config's ``[[track.layout]]``), one after another along
the distance ``s`` from the line's start:

* a ``tangent``: curvature, cant and widening zero;
* a ``curve``: a circular arc of ``radius``, ``hand`` left or right, with its ``superelevation``
  ``h`` (the outer rail's height over the inner) and ``widening`` of the gauge, all constant;
* a ``transition``: a clothoid, curvature and cant linear in ``s`` from the segment before it to
  the one after it (the linear ramp of EN 13803; a reverse curve's transition passes through zero
  with both), the widening likewise.  A transition at the line's start or end meets tangent track.

Signs (the track frame of :mod:`axlebox.mbs.wheelrail.element_kernel`: x forward, y left, z up):
the curvature ``kappa = 1 / R`` is positive in a left-hand curve; the signed superelevation ``e``
is the right rail's height over the left's (``+h`` in a left-hand curve, where the right rail is
the outer one); the track plane's roll about the forward axis is ``phi = -asin(e / s0)``, ``s0``
the distance the cant is measured over (the rails' contact points, 1.500 m on 1435 mm gauge).  A
left-hand curve's plane rolls to the left (phi < 0) and its gravity then pulls the car towards
the curve's centre, against the centrifugal force.

The plan view: the heading ``psi(s) = psi_0 + int kappa ds`` (quadratic in s on a transition) and
the position ``x = int cos psi ds``, ``y = int sin psi ds`` by composite Gauss-Legendre
quadrature on each segment, panels of at most 0.25 rad of heading change (16 points each: the
integrand is analytic, the error below 1e-12 of the length; tests check it against Fresnel's
integrals for a clothoid and the circle for an arc).

Closed forms of the quasi-static curving (:func:`unbalanced_acceleration`,
:func:`equilibrium_speed`, :func:`cant_deficiency`): in the track plane the lateral acceleration
left unbalanced by the cant is ``a = (v^2 / R) cos(phi) - g sin|phi|``, about ``v^2 / R - g h /
s0``; it vanishes at the equilibrium speed ``v_eq = sqrt(g R tan|phi|)``, about ``sqrt(g h R /
s0)``; the cant deficiency is ``I = s0 v^2 / (g R) - h`` (EN 13803).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from axlebox._params import ParameterError, check_ranges, choice, kinded_from_table, param

G = 9.81                                  # m/s^2, as the car's gravity
KINDS = ("tangent", "transition", "curve")
HANDS = ("left", "right")
#: the fields each kind of segment takes (the others do not apply to it)
KIND_FIELDS = {"tangent": ("kind", "length", "start"),
               "transition": ("kind", "length", "start"),
               "curve": ("kind", "length", "start", "radius", "hand", "superelevation", "widening")}
JOIN_TOL = 1e-3                           # m: a segment's start given as chainage meets the last end
_GL_X, _GL_W = np.polynomial.legendre.leggauss(16)
_PANEL = 0.25                             # rad: heading change at most, per quadrature panel


@dataclass(frozen=True)
class Segment:
    """A ``[[track.layout]]`` entry: one tangent, transition or circular curve of the line; each
    kind takes its fields of :data:`KIND_FIELDS`."""

    SECTION = "track.layout"
    kind: str = choice("tangent", KINDS, "'tangent', 'transition' (a clothoid: curvature and cant "
                       "linear from the segment before to the one after) or 'curve' (circular)")
    length: float = param(100.0, 0.1, 1e5, "m", "length along the line")
    start: float = param(-1.0, -1.0, 1e6, "m", "where on the line it begins (chainage), to check the "
                         "layout against a line's table; -1: where the segment before ends")
    radius: float = param(300.0, 50.0, 1e5, "m", "curve only: radius (the car's own limit, "
                          "150 m for the B-type car of GB 50157-2013, and the cant deficiency at the "
                          "run's top speed, at most EN 13803's 150 mm, are checked with the run)")
    hand: str = choice("left", HANDS, "curve only: the side the line turns to, looking forward")
    superelevation: float = param(0.0, 0.0, 0.18, "m", "curve only: cant h, the outer rail's height "
                                  "over the inner (EN 13803's largest limit, ballasted track: "
                                  "180 mm; metro codes keep to about 120 mm)")
    widening: float = param(0.0, 0.0, 0.02, "m", "curve only: gauge widening, the rails moved apart "
                            "symmetrically")

    def __post_init__(self):
        check_ranges(self)
        if self.start != -1.0 and self.start < 0.0:
            raise ParameterError(f"track.layout.start = {self.start!r} is not allowed: expected a "
                                 "number in [0, 1e+06] m, or -1 (where the segment before ends)")

    @classmethod
    def from_table(cls, d, where: str) -> Segment:
        """The entry of a config table ``d`` at ``where`` (``track.layout[i]``), refusing a field
        its kind does not take."""
        return kinded_from_table(cls, d, where, KIND_FIELDS, "segment")

    def to_table(self) -> dict:
        return {k: getattr(self, k) for k in KIND_FIELDS[self.kind]
                if not (k == "start" and self.start == -1.0)}

    @property
    def curvature(self) -> float:
        """Signed curvature of a curve, 1/m (left +)."""
        return (1.0 if self.hand == "left" else -1.0) / self.radius

    @property
    def cant(self) -> float:
        """Signed superelevation of a curve, m: the right rail's over the left's."""
        return math.copysign(self.superelevation, self.curvature)


class At(NamedTuple):
    """The line's design geometry at distances ``s`` (arrays like ``s``)."""

    kappa: np.ndarray            # curvature, 1/m (left +)
    dkappa: np.ndarray           # its rate along the line, 1/m^2
    e: np.ndarray                # signed superelevation, m (the right rail's over the left's)
    phi: np.ndarray              # the track plane's roll about the forward axis, rad
    dphi: np.ndarray             # its rate along the line, rad/m
    widening: np.ndarray         # gauge widening, m
    psi: np.ndarray              # heading in the plan view, rad (0 at the line's start)


class Line:
    """A line of consecutive segments (module docstring), checked on construction: a refusal
    names ``track.layout[i]``, the value and what is allowed.

    ``s0``: the distance the cant is measured over (the rails' contact points), m."""

    def __init__(self, segments, s0: float = 1.5):
        segs = tuple(segments) or (Segment("tangent", 1e5),)
        if not all(isinstance(g, Segment) for g in segs):
            raise ParameterError(f"track.layout = {segments!r} is not allowed: expected "
                                 "[[track.layout]] tables")
        self.segments, self.s0 = segs, float(s0)
        n = len(segs)
        start = np.zeros(n + 1)
        for i, g in enumerate(segs):
            if g.start != -1.0 and abs(g.start - start[i]) > JOIN_TOL:
                gap = g.start - start[i]
                raise ParameterError(
                    f"track.layout[{i}].start = {g.start:g} is not allowed: it leaves "
                    f"{'a gap' if gap > 0 else 'an overlap'} of {abs(gap):g} m after "
                    f"track.layout[{i - 1}], which ends at {start[i]:g} m" if i else
                    f"track.layout[0].start = {g.start:g} is not allowed: the line starts at 0 m")
            start[i + 1] = start[i] + g.length
        self.starts = start
        # each segment's values at its two ends: (kappa, e, widening)
        ends = np.zeros((n, 2, 3))
        for i, g in enumerate(segs):
            if g.kind == "curve":
                ends[i] = (g.curvature, g.cant, g.widening)
        for i, g in enumerate(segs):
            if g.kind != "transition":
                continue
            for j, k in ((i - 1, 0), (i + 1, 1)):
                if 0 <= j < n and segs[j].kind == "transition":
                    raise ParameterError(f"track.layout[{max(i, j)}].kind = 'transition' is not "
                                         "allowed after another transition: put the tangent or "
                                         "curve they lead to between them")
                ends[i, k] = ends[j, 1 - k] if 0 <= j < n else 0.0
        for i in range(1, n):
            a, b = ends[i - 1, 1], ends[i, 0]
            if abs(a[1] - b[1]) > 1e-9 or abs(a[2] - b[2]) > 1e-9:
                what = "cant" if abs(a[1] - b[1]) > 1e-9 else "gauge widening"
                raise ParameterError(
                    f"track.layout[{i}] ({segs[i].kind}) is not allowed straight after "
                    f"track.layout[{i - 1}] ({segs[i - 1].kind}): the {what} would step by "
                    f"{abs(a[1] - b[1]) if what == 'cant' else abs(a[2] - b[2]):g} m; put a "
                    "kind = 'transition' between them")
        self.ends = ends
        # heading and plan position at each segment's start
        psi, xy = np.zeros(n + 1), np.zeros((n + 1, 2))
        for i in range(n):
            k0, k1 = ends[i, 0, 0], (ends[i, 1, 0] - ends[i, 0, 0]) / segs[i].length
            u = np.array([segs[i].length])
            psi[i + 1] = psi[i] + k0 * u[0] + 0.5 * k1 * u[0] ** 2
            xy[i + 1] = xy[i] + _plan(psi[i], k0, k1, u)[:, 0]
        self._psi, self._xy = psi, xy

    @property
    def length(self) -> float:
        """The line's length, m."""
        return float(self.starts[-1])

    @property
    def tangent(self) -> bool:
        """True where the line is straight and level throughout (the tangent track)."""
        return all(g.kind == "tangent" for g in self.segments)

    def _locate(self, s):
        s = np.asarray(s, dtype=float)
        if np.any(s < -JOIN_TOL) or np.any(s > self.length + JOIN_TOL):
            raise ParameterError(f"track position {float(np.min(s)):g}..{float(np.max(s)):g} m is "
                                 f"not allowed: the line runs from 0 to {self.length:g} m")
        i = np.clip(np.searchsorted(self.starts, s, side="right") - 1, 0, len(self.segments) - 1)
        return s, i, s - self.starts[i]

    def at(self, s) -> At:
        """The design geometry at ``s`` (m, scalar or array)."""
        s, i, u = self._locate(s)
        L = self.starts[i + 1] - self.starts[i]
        a, b = self.ends[i, 0], self.ends[i, 1]
        w = (u / L)[..., None]
        kappa, e, wid = np.moveaxis(a + (b - a) * w, -1, 0)
        dkappa, de = (b[..., 0] - a[..., 0]) / L, (b[..., 1] - a[..., 1]) / L
        r = e / self.s0
        phi = -np.arcsin(r)
        dphi = -de / self.s0 / np.sqrt(1.0 - r * r)
        psi = self._psi[i] + a[..., 0] * u + 0.5 * dkappa * u * u
        return At(kappa, dkappa, e, phi, dphi, wid, psi)

    def xy(self, s) -> np.ndarray:
        """Plan-view position of the line's centre at ``s``, m, shape ``(2,) + s.shape``: x along
        the first segment, y to its left."""
        s, i, u = self._locate(s)
        flat_i, flat_u = np.ravel(i), np.ravel(u)
        out = np.empty((2, flat_u.size))
        for k in np.unique(flat_i):
            m = flat_i == k
            k0 = self.ends[k, 0, 0]
            k1 = (self.ends[k, 1, 0] - k0) / self.segments[k].length
            out[:, m] = self._xy[k][:, None] + _plan(self._psi[k], k0, k1, flat_u[m])
        return out.reshape((2,) + np.shape(s))

    def frame(self, s) -> tuple[np.ndarray, np.ndarray]:
        """The track frame at ``s`` (scalar): its origin on the line's centre at rail level
        ``O = (x, y, 0)`` and its axes ``A = Rz(psi) Rx(phi)`` (columns: forward, left in the
        canted plane, its normal), in the plan frame of :meth:`xy`.  The cant turns the plane
        about the centre line."""
        g = self.at(s)
        c, w = math.cos(float(g.psi)), math.sin(float(g.psi))
        cf, sf = math.cos(float(g.phi)), math.sin(float(g.phi))
        A = np.array([[c, -w * cf, w * sf], [w, c * cf, -c * sf], [0.0, sf, cf]])
        return np.array([*self.xy(float(s)), 0.0]), A

    def to_tables(self) -> list[dict]:
        return [g.to_table() for g in self.segments]


class FrameMotion(NamedTuple):
    """The motion of a track frame that travels the line at ``v`` (:func:`frame_motion`), each
    resolved in the frame's own axes."""

    omega: np.ndarray            # angular velocity, rad/s
    alpha: np.ndarray            # angular acceleration, rad/s^2
    a0: np.ndarray               # the origin's acceleration, m/s^2
    gravity: np.ndarray          # gravity's acceleration, m/s^2


def frame_motion(g: At, s0: float, v: float, vdot: float = 0.0) -> FrameMotion:
    """The track frame's motion at the geometry ``g`` (scalars, :meth:`Line.at`), travelling at
    ``v`` with ``vdot``: with ``A = Rz(psi) Rx(phi)`` and ``ds/dt = v``,

    ``omega = v (phi', kappa sin(phi), kappa cos(phi))``,
    ``alpha = vdot (phi', kappa sin(phi), kappa cos(phi)) + v^2 (phi'', kappa' sin(phi) + kappa
    cos(phi) phi', kappa' cos(phi) - kappa sin(phi) phi')``,
    ``a0 = (vdot, v^2 kappa cos(phi), -v^2 kappa sin(phi))``, gravity ``-g (0, sin(phi), cos(phi))``:
    what a body described from the frame feels as the centrifugal forces ``-m a0`` (DYTSI's ``m v^2
    cos(phi) / R`` and ``-m v^2 sin(phi) / R``), gravity in the canted plane, and the frame's yaw
    rate ``v kappa cos(phi)`` in the wheelsets' gyroscopic moments (Shabana, Zaazaa and Sugiyama,
    *Railroad Vehicle Dynamics: A Computational Approach*, CRC 2008, the trajectory coordinates).
    ``phi''`` from the cant linear in s: ``-(e' / s0)^2 r / (1 - r^2)^1.5``, ``r = e / s0``."""
    k, dk, phi, dphi = float(g.kappa), float(g.dkappa), float(g.phi), float(g.dphi)
    r = float(g.e) / s0
    de = -dphi * s0 * math.sqrt(1.0 - r * r)
    ddphi = -(de / s0) ** 2 * r / (1.0 - r * r) ** 1.5
    sf, cf = math.sin(phi), math.cos(phi)
    rate = np.array([dphi, k * sf, k * cf])
    omega = v * rate
    alpha = vdot * rate + v * v * np.array([ddphi, dk * sf + k * cf * dphi, dk * cf - k * sf * dphi])
    a0 = np.array([vdot, v * v * k * cf, -v * v * k * sf])
    return FrameMotion(omega, alpha, a0, -G * np.array([0.0, sf, cf]))


def _plan(psi0: float, k0: float, k1: float, u: np.ndarray) -> np.ndarray:
    """``(x, y)`` of ``int_0^u (cos, sin)(psi0 + k0 t + k1 t^2 / 2) dt`` for each ``u`` (shape
    ``(2, len(u))``): composite 16-point Gauss-Legendre, panels of at most ``_PANEL`` rad."""
    u = np.asarray(u, dtype=float)
    turn = abs(k0) * u.max(initial=0.0) + 0.5 * abs(k1) * u.max(initial=0.0) ** 2
    panels = max(1, math.ceil(turn / _PANEL))
    # nodes on [0, 1] in each panel, scaled by each u
    edges = np.arange(panels) / panels
    t01 = (edges[:, None] + (0.5 * (_GL_X + 1.0))[None, :] / panels).ravel()
    w01 = np.tile(0.5 * _GL_W / panels, panels)
    t = u[:, None] * t01[None, :]
    ang = psi0 + k0 * t + 0.5 * k1 * t * t
    return np.stack([(np.cos(ang) * w01).sum(1) * u, (np.sin(ang) * w01).sum(1) * u])


def unbalanced_acceleration(v, kappa, phi):
    """The lateral acceleration the cant leaves unbalanced, in the track plane, towards the
    curve's outside whichever its hand, m/s^2: ``(v^2 / R) cos(phi) - g sin|phi|`` for the roll
    ``phi`` leaning into the curve (module docstring); negative: a cant excess."""
    v, kappa, phi = np.asarray(v, float), np.asarray(kappa, float), np.asarray(phi, float)
    return v * v * np.abs(kappa) * np.cos(phi) + G * np.sin(phi) * np.sign(kappa)


def equilibrium_speed(R: float, h: float, s0: float = 1.5) -> float:
    """The speed at which a curve of radius ``R`` with cant ``h`` leaves no lateral acceleration
    unbalanced, m/s: ``sqrt(g R tan(asin(h / s0)))``."""
    return math.sqrt(G * R * math.tan(math.asin(h / s0)))


def cant_deficiency(v: float, R: float, h: float, s0: float = 1.5) -> float:
    """The cant a curve would need at speed ``v`` beyond what it has, m (EN 13803):
    ``s0 v^2 / (g R) - h``; negative: a cant excess."""
    return s0 * v * v / (G * R) - h
