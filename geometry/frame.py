"""H-shaped bogie frame of a B-type metro motor bogie.

Axes: x forward (wheelset 1 at +x), y to the left, z up; origin at the frame
centre on the side-beam axis.  Two hollow box side beams over the journals,
two tubular cross beams, primary spring seats under the side beams above each
axle-box, air-spring (secondary) seats on top at mid-length and a traction
centre block between the cross beams.  Motor and gearbox brackets are left out
(their mass belongs to those components).  Dimensions are typical for a
2.2-2.3 m wheelbase metro bogie, not from a drawing.
"""
from __future__ import annotations

from dataclasses import dataclass

from axlebox._params import check_ranges, param, require

from ._occ import boundary_faces, face_boxes, select

AXLES = (1, 2)
SIDES = ("L", "R")


@dataclass(frozen=True)
class FrameParams:
    wheelbase: float = param(2.2, 1.5, 3.0)
    side_beam_y: float = param(1.0, 0.6, 1.3, doc="lateral position of the side beams (over the journals)")
    side_beam_length: float = param(2.9, 1.8, 4.0)
    side_beam_width: float = param(0.22, 0.08, 0.5)
    side_beam_height: float = param(0.30, 0.1, 0.6)
    wall: float = param(0.020, 0.005, 0.06, doc="plate thickness of the box and tube sections")
    cross_beam_x: float = param(0.30, 0.1, 0.8, doc="x of the two cross beams")
    cross_beam_radius: float = param(0.090, 0.03, 0.2, doc="outer radius of the cross-beam tubes")
    seat_size: float = param(0.18, 0.05, 0.4, doc="edge of the primary spring seat pads")
    air_seat_length: float = param(0.40, 0.1, 0.8, doc="air-spring seat pad length along x")
    pad: float = param(0.030, 0.005, 0.1, doc="thickness of the seat pads")

    def __post_init__(self):
        check_ranges(self)
        require(self.side_beam_length / 2 > self.wheelbase / 2 + self.seat_size / 2, self,
                "wheelbase", f"the primary seats at x = +-{self.wheelbase / 2:g} m must lie on the "
                f"side beams (side_beam_length = {self.side_beam_length:g} m)")
        require(2 * self.wall < min(self.side_beam_width, self.side_beam_height) / 2, self, "wall",
                "must be below a quarter of the side-beam section")
        require(self.wall < self.cross_beam_radius / 2, self, "wall", "must be below half the tube radius")
        require(self.cross_beam_radius < self.side_beam_height / 2, self, "cross_beam_radius",
                "the tubes must fit the side-beam height")
        require(self.cross_beam_x + self.cross_beam_radius < self.wheelbase / 2 - self.seat_size / 2, self,
                "cross_beam_x", "the cross beams must lie between the primary seats")


def build(p: FrameParams) -> dict[str, list[int]]:
    """Named faces: ``primary_<axle>_<side>`` (axle 1 at +x, side L at +y),
    ``secondary_<side>``, ``traction_centre``."""
    import gmsh
    occ = gmsh.model.occ
    h, b, t = p.side_beam_height, p.side_beam_width, p.wall
    L = p.side_beam_length
    parts, holes = [], []
    for s in (1, -1):
        y = s * p.side_beam_y
        parts.append(occ.addBox(-L / 2, y - b / 2, -h / 2, L, b, h))
        holes.append(occ.addBox(-L / 2 + t, y - b / 2 + t, -h / 2 + t, L - 2 * t, b - 2 * t, h - 2 * t))
    span = 2 * p.side_beam_y
    for x in (p.cross_beam_x, -p.cross_beam_x):
        parts.append(occ.addCylinder(x, -p.side_beam_y, 0, 0, span, 0, p.cross_beam_radius))
        holes.append(occ.addCylinder(x, -p.side_beam_y + b / 2, 0, 0, span - b, 0,
                                     p.cross_beam_radius - t))
    # traction centre: a block joining the two cross beams
    tc = (p.cross_beam_x, 0.15, h / 2)
    parts.append(occ.addBox(-tc[0], -tc[1], -tc[2], 2 * tc[0], 2 * tc[1], tc[2] + p.cross_beam_radius / 2))
    ss = p.seat_size
    for x in (p.wheelbase / 2, -p.wheelbase / 2):
        for s in (1, -1):
            parts.append(occ.addBox(x - ss / 2, s * p.side_beam_y - ss / 2, -h / 2 - p.pad,
                                    ss, ss, p.pad + 0.005))
    for s in (1, -1):
        parts.append(occ.addBox(-p.air_seat_length / 2, s * p.side_beam_y - b / 2, h / 2 - 0.005,
                                p.air_seat_length, b, p.pad + 0.005))
    solid, _ = occ.fuse([(3, parts[0])], [(3, q) for q in parts[1:]])
    occ.cut(solid, [(3, q) for q in holes])
    occ.synchronize()
    boxes = face_boxes(boundary_faces())
    named = {}
    zb = -h / 2 - p.pad
    for axle, x in zip(AXLES, (p.wheelbase / 2, -p.wheelbase / 2)):
        for side, s in zip(SIDES, (1, -1)):
            y = s * p.side_beam_y
            named[f"primary_{axle}_{side}"] = select(boxes, x=(x - ss / 2, x + ss / 2),
                                                     y=(y - ss / 2, y + ss / 2), z=(zb, zb), flat="z")
    zt = h / 2 + p.pad
    for side, s in zip(SIDES, (1, -1)):
        y = s * p.side_beam_y
        named[f"secondary_{side}"] = select(boxes, y=(y - b / 2, y + b / 2), z=(zt, zt), flat="z")
    named["traction_centre"] = select(boxes, x=(-tc[0], tc[0]), y=(-tc[1], tc[1]), z=(-tc[2], -tc[2]),
                                      flat="z")
    return named
