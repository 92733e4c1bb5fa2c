"""B-type metro motor wheelset: axle, two 840 mm wheels and the gear wheel.

Axes: y along the axle (positive to the left in the running direction), z up,
origin at the axle centre.  The whole wheelset is a solid of revolution built
from one (y, r) profile; the bottom sector of the wheels (where the rails act)
is split off so each tread has a contact patch of its own.

Default dimensions follow Chinese B-type metro practice (typical values, not from one
published source; the seats fit the assumed 130 mm bore bearing of :mod:`axlebox.bearing.models.params`):
130 mm bearing seats centred at +-1.0 m, 840 mm wheels with 1353 mm back-to-back
and a 135 mm rim, 1:20 cone tread with a 27 mm flange (the LM profile replaces
the cone in the wheel-rail work).  Axle body, seat and gear sizes are typical
values for a 14 t axle-load motor axle, not from a drawing.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from axlebox._params import ParameterError, check_ranges, param, require

from ._occ import boundary_faces, face_boxes, revolve_profile, select

SIDES = ("L", "R")


@dataclass(frozen=True)
class WheelsetParams:
    """Dimensions of the wheelset (m); rows: 1 inboard, 2 outboard on each journal."""

    r_journal: float = param(0.065, 0.02, 0.2, doc="bearing seat radius (130 mm)")
    journal_length: float = param(0.160, 0.02, 0.5, doc="bearing seat length (two rows)")
    journal_center: float = param(1.0, 0.5, 1.5, doc="lateral position of the journal centres")
    r_dust_guard: float = param(0.0825, 0.02, 0.25, doc="dust-guard seat radius")
    r_wheel_seat: float = param(0.100, 0.02, 0.3, doc="wheel seat radius")
    wheel_seat_length: float = param(0.180, 0.05, 0.4)
    r_axle_body: float = param(0.090, 0.02, 0.3, doc="axle body radius between the wheels")
    r_wheel: float = param(0.420, 0.05, 0.7, doc="rolling radius at the taping line (840 mm)")
    back_to_back: float = param(1.353, 0.9, 1.6, doc="distance between the wheel back faces")
    rim_width: float = param(0.135, 0.08, 0.2)
    rim_thickness: float = param(0.065, 0.02, 0.15, doc="radial rim depth below the taping line")
    web_thickness: float = param(0.030, 0.01, 0.1)
    r_hub: float = param(0.125, 0.05, 0.35, doc="outer radius of the wheel hub")
    flange_height: float = param(0.027, 0.015, 0.04)
    flange_width: float = param(0.032, 0.02, 0.05)
    taping_offset: float = param(0.070, 0.04, 0.1, doc="taping line from the wheel back face")
    cone: float = param(0.05, 0.0, 0.2, unit="", doc="tread conicity (1:20)")
    r_gear: float = param(0.270, 0.0, 0.5, doc="gear wheel outer radius (0: no gear)")
    gear_width: float = param(0.075, 0.02, 0.2)
    gear_center: float = param(0.420, 0.0, 0.65, doc="lateral distance of the gear from the axle centre")
    gear_side: str = field(default="R", metadata={"doc": "side of the gear wheel, 'L' or 'R'"})
    contact_sector_deg: float = param(30.0, 5.0, 90.0, unit="deg",
                                      doc="angular width of the tread contact patch")

    def __post_init__(self):
        check_ranges(self)
        if self.gear_side not in SIDES:
            raise ParameterError(f"WheelsetParams.gear_side = {self.gear_side!r} is not allowed: "
                                 "expected 'L' or 'R'")
        require(self.r_wheel > self.r_axle_body and self.r_wheel > self.r_wheel_seat, self, "r_wheel",
                f"the wheel radius must exceed the axle radii (axle body {self.r_axle_body:g} m, "
                f"wheel seat {self.r_wheel_seat:g} m)")
        require(self.r_wheel - self.rim_thickness > self.r_hub, self, "r_wheel",
                f"the wheel radius less the rim ({self.r_wheel - self.rim_thickness:g} m) must exceed "
                f"the hub radius r_hub = {self.r_hub:g} m")
        require(self.r_hub > self.r_wheel_seat, self, "r_hub", "must exceed the wheel seat radius")
        for name in ("r_journal", "r_dust_guard", "r_axle_body"):
            require(getattr(self, name) < self.r_wheel_seat, self, name,
                    f"must be below the wheel seat radius r_wheel_seat = {self.r_wheel_seat:g} m")
        require(self.r_journal < self.r_dust_guard, self, "r_journal",
                "must be below the dust-guard seat radius")
        half = self.back_to_back / 2
        require(self.web_thickness < self.rim_width, self, "web_thickness", "must be below rim_width")
        require(self.flange_width + 0.02 < self.taping_offset < self.rim_width, self, "taping_offset",
                "must lie on the tread, between the flange and the rim's outer face")
        seat0, seat1 = self.wheel_seat_y
        require(seat0 > self.gear_center + self.gear_width / 2 + 0.01 or self.r_gear == 0, self,
                "gear_center", f"the gear must sit between the wheels (inboard of {seat0:g} m)")
        require(seat0 < half + self.rim_width / 2 < seat1, self, "wheel_seat_length",
                "the wheel seat must lie under the wheel")
        j0 = self.journal_center - self.journal_length / 2
        require(j0 > seat1 + 0.01, self, "journal_length",
                f"the journal ({j0:g} m inner end) must lie outboard of the wheel seat "
                f"({seat1:g} m) with room for the dust-guard seat")
        require(self.r_gear == 0 or self.r_gear > self.r_axle_body + 0.02, self, "r_gear",
                "must exceed the axle body radius (or be 0 for no gear)")

    @property
    def wheel_seat_y(self) -> tuple[float, float]:
        c = self.back_to_back / 2 + self.rim_width / 2
        return c - self.wheel_seat_length / 2, c + self.wheel_seat_length / 2

    @property
    def axle_end(self) -> float:
        return self.journal_center + self.journal_length / 2

    @property
    def tread_y(self) -> tuple[float, float]:
        """Inner and outer lateral limits of the tread (flange root to rim face)."""
        b = self.back_to_back / 2
        return b + self.flange_width, b + self.rim_width

    def side_sign(self, side: str) -> float:
        return 1.0 if side == "L" else -1.0


def _half_profile(p: WheelsetParams, gear: bool) -> list[tuple[float, float]]:
    """Outer contour for y >= 0, from the axle centre to the axle end (y, r)."""
    b = p.back_to_back / 2
    s0, s1 = p.wheel_seat_y
    web = b + p.rim_width / 2
    rim_in = p.r_wheel - p.rim_thickness
    tape = b + p.taping_offset
    tread_r = lambda y: p.r_wheel - p.cone * (y - tape)   # noqa: E731
    pts = [(0.0, p.r_axle_body)]
    if gear and p.r_gear > 0:
        g0, g1 = p.gear_center - p.gear_width / 2, p.gear_center + p.gear_width / 2
        pts += [(g0, p.r_axle_body), (g0, p.r_gear), (g1, p.r_gear), (g1, p.r_axle_body)]
    pts += [(s0, p.r_axle_body), (s0, p.r_hub),
            (web - p.web_thickness / 2, p.r_hub), (web - p.web_thickness / 2, rim_in),
            (b, rim_in), (b, p.r_wheel + p.flange_height - 0.008),
            (b + 0.010, p.r_wheel + p.flange_height),
            (b + 0.018, p.r_wheel + p.flange_height),
            (b + p.flange_width, tread_r(b + p.flange_width)),
            (b + p.rim_width, tread_r(b + p.rim_width)),
            (b + p.rim_width, rim_in),
            (web + p.web_thickness / 2, rim_in), (web + p.web_thickness / 2, p.r_hub),
            (s1, p.r_hub), (s1, p.r_dust_guard)]
    j0 = p.journal_center - p.journal_length / 2
    pts += [(j0, p.r_dust_guard), (j0, p.r_journal),
            (p.journal_center, p.r_journal), (p.axle_end, p.r_journal)]
    return pts


def profile(p: WheelsetParams) -> list[tuple[float, float]]:
    """Closed (y, r) profile of the whole wheelset, counter-clockwise."""
    left = _half_profile(p, gear=p.gear_side == "L")
    right = _half_profile(p, gear=p.gear_side == "R")
    outer = [(-y, r) for y, r in reversed(right[1:])] + left
    return outer + [(p.axle_end, 0.0), (-p.axle_end, 0.0)]


def build(p: WheelsetParams) -> dict[str, list[int]]:
    """Build the solid; named faces per side s in {L, R}:

    ``journal_<s>_row1`` / ``journal_<s>_row2`` (inboard / outboard bearing seat),
    ``tread_<s>`` (bottom contact patch of the tread), ``gear`` (gear rim, whole).
    """
    import gmsh
    revolve_profile(profile(p), sector_deg=p.contact_sector_deg)
    gmsh.model.occ.removeAllDuplicates()
    gmsh.model.occ.synchronize()
    boxes = face_boxes(boundary_faces())
    r = p.r_journal
    named = {}
    for side in SIDES:
        sg = p.side_sign(side)
        c, h = p.journal_center, p.journal_length / 2
        for row, (y0, y1) in (("row1", (c - h, c)), ("row2", (c, c + h))):
            ys = sorted((sg * y0, sg * y1))
            named[f"journal_{side}_{row}"] = select(boxes, y=ys, x=(-r, r), z=(-r, r))
        t0, t1 = sorted((sg * p.tread_y[0], sg * p.tread_y[1]))
        rw = p.r_wheel + p.flange_height
        named[f"tread_{side}"] = [f for f in select(boxes, y=(t0, t1), x=(-rw, rw), z=(-rw, 0.0))
                                  if boxes[f][5] < -0.5 * p.r_wheel]
    if p.r_gear > 0:
        sg = p.side_sign(p.gear_side)
        g = sorted((sg * (p.gear_center - p.gear_width / 2), sg * (p.gear_center + p.gear_width / 2)))
        # the whole rim, every sector the revolve made (its sides are flat in y): an RBE3 on the
        # rim less its bottom sector put the gear's master 24 mm above the axle
        named["gear"] = [f for f in select(boxes, y=g) if abs(boxes[f][4] - boxes[f][1]) > 1e-6]
    return named
