"""Local raceway defects as extra clearance in the contact, paper Eqs. (14)-(15).

A defect of width W (along the raceway), length L (across it, along the contact line) and
depth H on the outer ring: while a roller's azimuth, measured in the ring's own frame, lies in
``[theta_o, theta_o + tau_o]`` the cup contact loses

``h_o = A sin(pi / tau_o (phi - theta_o))``,  ``A = min(H, r_b - sqrt(r_b^2 - (W/2)^2))``,
``tau_o = 2 arcsin(W / D_o)``,

over the stretch of the contact line the defect covers.  Two readings of the paper are made
explicit here: the window is the whole ``tau_o`` (the printed ``tau_o / 2`` would make the
depth jump from A to zero at the defect's middle), and A is capped by the depth H (a shallow
defect cannot let the roller drop further than its floor).  ``angle`` is the defect's centre,
so ``theta_o = angle - tau_o / 2``.

An inner-ring defect (``kind = "inner"``) is the same law on the cone contact with the cone's
raceway diameter ``D_i`` in ``tau_i = 2 arcsin(W / D_i)`` and its angle in the inner ring's own
frame: it turns with the shaft, so a roller at azimuth phi meets it while ``phi - theta_iy``
(``theta_iy`` the inner ring's rotation, the shaft angle) lies in the window: once per
``1 / BPFI``, and it meets it loaded only when the defect passes the load zone (the shaft-rate
modulation of the inner-ring fault signature).

A roller defect (``kind = "roller"``, on roller ``roller`` of the row) is the same law on the
roller's own surface, ``tau_r = 2 arcsin(W / D_b)`` of its circumference: it turns with the
roller's spin angle psi (the state about its axis, in the frame that orbits with it), and it
is under the cup contact while ``psi`` lies within ``tau_r / 2`` of ``angle`` and under the cone
contact half a turn later: each raceway meets it once a roller revolution, 2 BSF in all, hard
only while the roller crosses the load zone (once a cage turn).  Its depth A takes the roller's
curvature as Eq. (14) does; where a ring's defect and the roller's meet one contact, the deeper
counts.

**The defect's edges** (``profile = "edges"``, a documented alternative to Eq. (14)).  A
rigid roller of radius r_b crossing a pit narrower than itself pivots on the pit's edges: its
centre drops by ``r_b - sqrt(r_b^2 - d^2)`` at arc distance d from the nearer edge, the depth A
of Eq. (14) at the pit's middle, where it passes from the leading edge to the trailing one.  The
half-sine of Eq. (14) has the same depth but puts its slope breaks at the two edges; the exact
path is smooth there and breaks at the middle, the trailing edge's re-stressing that explicit
finite-element studies find to be the defect's impulse (Singh, Koepke, Howard and Petersen,
J. Sound Vib. 333 (2014) 5356-5377).  An edge rounded to radius ``edge_radius`` r_e moves the
pivot r_e into the pit and r_e below the surface: the centre drops by
``rho - sqrt(rho^2 - (d - r_e)^2)`` for d > r_e, rho = r_b + r_e, capped by H, which lowers the
slope break at the middle from ``W / (2 r_b)`` to ``(W / 2 - r_e) / rho`` (no published edge
radius for a spall was found: the radius is a sensitivity parameter, 0 a sharp edge).  Ring
defects only.

The table's columns are :mod:`.layout`'s ``D_*`` (one row a defect); :func:`depth_under` and
:func:`roller_depths` read it in the kernels.
"""
from __future__ import annotations

from dataclasses import dataclass
from math import asin, pi, sin, sqrt

import numpy as np

from axlebox._numba import kernel
from axlebox._params import ParameterError, check_ranges, param, require

from .kernel.layout import (D_DEPTH, D_EDGE, D_KIND, D_RADIUS, D_RHO, D_ROLLER, D_ROW, D_S1, D_S2,
                     D_START, D_TAU, D_WIDTH, KINDS, ROLLER_SURFACE)

WIDTH = D_WIDTH                            # columns of the kernel's defect table
PROFILES = ("half-sine", "edges")
TWO_PI = 2.0 * pi


@dataclass(frozen=True)
class Defect:
    """A local defect; SI units, ``angle`` in rad from +z towards +x (the load zone's middle is 0)."""

    W: float = param(2e-3, 1e-6, 0.1, doc="width along the raceway")
    L: float = param(50.4e-3, 1e-6, 1.0, doc="length across the raceway (along the roller)")
    H: float = param(2e-3, 1e-7, 0.05, doc="depth")
    row: int = param(2, 1, 16, unit="", doc="bearing row, from 1 (inboard) to the bearing's rows "
                     "(2: a double-row bearing's outboard row)")
    angle: float = param(0.0, -2 * pi, 2 * pi, unit="rad", doc="centre of the defect (a roller "
                                                                  "defect: the roller's spin angle at "
                                                                  "which it is at the cup contact)")
    offset: float = param(0.0, -0.5, 0.5, doc="centre of the defect along the contact line")
    kind: str = "outer"
    roller: int = param(1, 1, 1000, unit="", doc="the roller of the row that carries a roller "
                                                  "defect, 1..Z")
    profile: str = "half-sine"
    edge_radius: float = param(0.0, 0.0, 0.01, doc="radius of the defect's edges (profile 'edges')")

    def __post_init__(self):
        if not isinstance(self.kind, str) or self.kind not in KINDS:
            raise ParameterError(f"Defect.kind = {self.kind!r} is not allowed: expected one of "
                                 f"{', '.join(KINDS)}")
        if not isinstance(self.profile, str) or self.profile not in PROFILES:
            raise ParameterError(f"Defect.profile = {self.profile!r} is not allowed: expected one of "
                                 f"{', '.join(PROFILES)}")
        for name in ("row", "roller"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int):
                raise ParameterError(f"Defect.{name} = {v!r} is not allowed: expected a whole number")
        check_ranges(self)
        if self.profile == "edges":
            require(self.kind != "roller", self, "profile", "the edges' path is a ring defect's "
                    "under a roller; expected 'half-sine' for a roller defect")
            require(self.edge_radius < 0.5 * self.W, self, "edge_radius",
                    f"expected less than half the width, W / 2 = {0.5 * self.W:g} m")
        else:
            require(self.edge_radius == 0.0, self, "edge_radius", "an edge radius needs "
                    "profile = 'edges'; expected 0 with the half-sine")

    def depth(self, p) -> float:
        """The deepest drop (m), capped by H: A of Eq. (14), or with rounded edges the drop at
        the middle, ``rho - sqrt(rho^2 - (W/2 - r_e)^2)``."""
        r = p.r_b + self.edge_radius
        return min(self.H, r - sqrt(r * r - (0.5 * self.W - self.edge_radius) ** 2))

    def raceway(self, p) -> float:
        """Diameter of the surface the defect is on (m): ``D_o`` (cup), ``D_i`` (cone) or ``D_b``
        (roller)."""
        return {"outer": p.D_o, "inner": p.D_i, "roller": p.D_b}[self.kind]

    def tau(self, p) -> float:
        """tau_o of Eq. (14) (rad), on the defect's own raceway."""
        return 2 * asin(self.W / self.raceway(p))


def table(defects, p) -> np.ndarray:
    """The kernel's defect table for ``defects`` in a bearing of parameters ``p`` (any model's:
    ``Z``, ``D_b``, ``r_b``, ``D_o``, ``D_i`` and the contact line's length ``L_e``); refuses
    defects the model cannot represent."""
    rows = []
    spans = []
    for d in defects:
        require(d.row <= p.rows, d, "row", f"the bearing has {p.rows} row{'s' if p.rows > 1 else ''}")
        require(d.W < p.D_b, d, "W", f"a defect wider than the roller diameter D_b = {p.D_b:g} m "
                "is not a local defect of Eq. (14) (the roller would meet its floor)")
        tau = d.tau(p)
        if d.kind == "roller":
            require(d.roller <= p.Z, d, "roller", f"a row has Z = {p.Z} rollers")
        else:
            require(tau < 2 * pi / p.Z, d, "W", f"the defect spans more than the roller pitch "
                    f"({pi * d.raceway(p) / p.Z:.4g} m on the {'cup' if d.kind == 'outer' else 'cone'})")
        half = 0.5 * p.L_e
        require(abs(d.offset) < half, d, "offset", f"must lie on the contact line, |offset| < {half:g} m")
        s1, s2 = max(-half, d.offset - 0.5 * d.L), min(half, d.offset + 0.5 * d.L)
        start = (d.angle - 0.5 * tau) % (2 * pi)
        surface = (d.row, d.kind, d.roller if d.kind == "roller" else 0)
        for other_start, other_tau, other in spans:
            gap = (start - other_start) % (2 * pi)
            if other == surface and (gap < other_tau or (2 * pi - gap) < tau):
                raise ParameterError(f"Defect.angle = {d.angle!r} is not allowed: the defect overlaps "
                                     f"another one on the same surface ({d.kind}, row {d.row})")
        spans.append((start, tau, surface))
        row = np.zeros(D_WIDTH)
        row[D_KIND], row[D_ROW], row[D_START], row[D_TAU] = KINDS[d.kind], d.row - 1, start, tau
        row[D_DEPTH], row[D_S1], row[D_S2] = d.depth(p), s1, s2
        row[D_ROLLER] = d.roller - 1 if d.kind == "roller" else 0.0
        row[D_RHO] = p.r_b + d.edge_radius if d.profile == "edges" else 0.0
        row[D_EDGE], row[D_RADIUS] = d.edge_radius, 0.5 * d.raceway(p)
        rows.append(row)
    return np.array(rows, dtype=float).reshape(-1, D_WIDTH)


def phase_clear_of(D: np.ndarray, Z: int, phase: float = 0.0) -> float:
    """``phase`` (rad), moved on by eighths of the roller pitch until no roller of a set at
    ``2 pi k / Z + phase`` sits inside a defect of the table ``D``: a start in the healthy
    bearing's equilibrium is then also the defective bearing's (defects are narrower than the
    pitch, :func:`table`, so a clear place exists)."""
    pitch = 2 * pi / Z
    for k in range(8):
        phi = pitch * np.arange(Z) + phase + k * pitch / 8
        if not any(np.any(np.mod(phi - d[D_START], 2 * pi) < d[D_TAU]) for d in D
                   if d[D_KIND] != ROLLER_SURFACE):   # a roller's defect is not at an azimuth
            return phase + k * pitch / 8
    return phase + 0.5 * pitch


# --- the kernels' lookups ------------------------------------------------------------------------
@kernel
def depth_under(D, kind, j, phi, theta):
    """Depth ``h`` of a ring defect of ``kind`` (:data:`.layout.OUTER_RING` or ``INNER_RING``)
    under a roller of row j at azimuth phi, Eq. (14), and the stretch ``[s1, s2]`` of the
    contact line it covers.  Defects turn with their ring, whose rotation about the axle is
    ``theta``."""
    for d in range(D.shape[0]):
        if D[d, D_KIND] != kind or D[d, D_ROW] != j:
            continue
        x = (phi - theta - D[d, D_START]) % TWO_PI
        tau = D[d, D_TAU]
        if x < tau:
            return _depth(D, d, x, tau), D[d, D_S1], D[d, D_S2]
    return 0.0, 0.0, 0.0


@kernel
def _depth(D, d, x, tau):
    """Depth of ring defect d at ``x`` rad into its window: Eq. (14)'s half-sine, or (``rho``
    > 0) the roller's centre path over the two rounded edges (module docstring)."""
    rho = D[d, D_RHO]
    if rho == 0.0:
        return D[d, D_DEPTH] * sin(pi * x / tau)
    e = min(x, tau - x) * D[d, D_RADIUS] - D[d, D_EDGE]     # past the nearer edge's pivot (m)
    if e <= 0.0:
        return 0.0
    return min(D[d, D_DEPTH], e * e / (rho + sqrt(rho * rho - e * e)))  # rho - sqrt(..), exact


@kernel
def roller_depths(D, j, k, psi):
    """Depths ``(h_outer, h_inner)`` of a defect on roller k of row j at its spin angle psi,
    Eq. (14) on the roller's surface: under the outer raceway within ``tau / 2`` of the defect's
    angle, under the inner one half a turn on; and its stretch ``[s1, s2]`` of the line."""
    for d in range(D.shape[0]):
        if D[d, D_KIND] != ROLLER_SURFACE or D[d, D_ROW] != j or D[d, D_ROLLER] != k:
            continue
        tau = D[d, D_TAU]
        x = (psi - D[d, D_START]) % TWO_PI
        h_o = D[d, D_DEPTH] * sin(pi * x / tau) if x < tau else 0.0
        x = (psi + pi - D[d, D_START]) % TWO_PI
        h_i = D[d, D_DEPTH] * sin(pi * x / tau) if x < tau else 0.0
        return h_o, h_i, D[d, D_S1], D[d, D_S2]
    return 0.0, 0.0, 0.0, 0.0


@kernel
def count(D, kind):
    """How many defects of ``kind`` the table holds."""
    n = 0
    for d in range(D.shape[0]):
        if D[d, D_KIND] == kind:
            n += 1
    return n
