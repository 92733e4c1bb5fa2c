"""Axle-box housing around a 230 mm bearing bore, with primary spring seats and sensor pad.

Local axes: y along the axle, positive outboard; z up; origin at the bore
centre.  Row 1 of the bearing sits inboard (y < 0), row 2 outboard.  The
housing carries two wings (front/rear, +-x) whose top faces seat the primary
coil springs, and a flat pad on top where the on-board accelerometer is glued.
Dimensions are typical of a 130 x 230 x 160 mm axle-box unit, not from a drawing.
"""
from __future__ import annotations

from dataclasses import dataclass

from axlebox._params import check_ranges, param, require

from ._occ import boundary_faces, face_boxes, select


@dataclass(frozen=True)
class AxleboxParams:
    r_bore: float = param(0.115, 0.05, 0.3, doc="bearing bore radius (230 mm)")
    r_outer: float = param(0.155, 0.06, 0.4, doc="housing outer radius")
    length: float = param(0.200, 0.05, 0.5, doc="housing length along the axle")
    wing_reach: float = param(0.300, 0.1, 0.6, doc="x of the wing tips (spring seat outer edge)")
    wing_width: float = param(0.160, 0.05, 0.5, doc="wing extent along y")
    wing_thickness: float = param(0.060, 0.02, 0.2, doc="wing depth in z")
    seat_length: float = param(0.120, 0.05, 0.3, doc="spring seat extent along x")
    seat_boss: float = param(0.010, 0.002, 0.05, doc="height of the spring seat boss on the wing")
    pad_size: float = param(0.050, 0.02, 0.1, doc="sensor pad edge")
    pad_height: float = param(0.020, 0.005, 0.05, doc="pad height above the housing top")

    def __post_init__(self):
        check_ranges(self)
        require(self.r_outer > self.r_bore + 0.015, self, "r_outer",
                f"must exceed the bore radius r_bore = {self.r_bore:g} m by at least 15 mm")
        require(self.wing_reach - self.seat_length > self.r_outer - 0.02, self, "wing_reach",
                "the spring seat must lie outside the housing cylinder")
        require(self.wing_width <= self.length, self, "wing_width", "must not exceed the housing length")

    @property
    def seat_z(self) -> float:
        return self.wing_thickness / 2 + self.seat_boss


def build(p: AxleboxParams) -> dict[str, list[int]]:
    """Named faces: ``bore_row1``, ``bore_row2``, ``spring_front`` (+x),
    ``spring_rear`` (-x), ``sensor_pad``."""
    import gmsh
    occ = gmsh.model.occ
    L = p.length
    body = occ.addCylinder(0, -L / 2, 0, 0, L, 0, p.r_outer)
    wz = p.wing_thickness
    wing = occ.addBox(-p.wing_reach, -p.wing_width / 2, -wz / 2, 2 * p.wing_reach, p.wing_width, wz)
    pad = occ.addBox(-p.pad_size / 2, -p.pad_size / 2, p.r_outer - 0.01, p.pad_size, p.pad_size,
                     p.pad_height + 0.01)
    s0 = p.wing_reach - p.seat_length
    seats = [occ.addBox(x0, -p.wing_width / 2, wz / 2 - 0.005, p.seat_length, p.wing_width,
                        p.seat_boss + 0.005) for x0 in (s0, -p.wing_reach)]
    solid, _ = occ.fuse([(3, body)], [(3, wing), (3, pad)] + [(3, t) for t in seats])
    bore = occ.addCylinder(0, -L, 0, 0, 2 * L, 0, p.r_bore)
    solid, _ = occ.cut(solid, [(3, bore)])
    # split at y = 0 so that each bearing row has its own bore face
    big = 2 * p.wing_reach + 1
    cut = occ.addRectangle(-big / 2, -big / 2, 0, big, big)
    occ.rotate([(2, cut)], 0, 0, 0, 1, 0, 0, 1.5707963267948966)
    occ.fragment(solid, [(2, cut)])
    occ.synchronize()
    # drop the parts of the cutting plane outside the solid
    for d, t in gmsh.model.getEntities(2):
        if not gmsh.model.getAdjacencies(d, t)[0].size:
            occ.remove([(d, t)], recursive=True)
    occ.synchronize()
    boxes = face_boxes(boundary_faces())
    r, s0 = p.r_bore, p.wing_reach - p.seat_length
    top = p.r_outer + p.pad_height
    return {
        "bore_row1": select(boxes, x=(-r, r), y=(-L / 2, 0), z=(-r, r)),
        "bore_row2": select(boxes, x=(-r, r), y=(0, L / 2), z=(-r, r)),
        "spring_front": [f for f in select(boxes, x=(s0, p.wing_reach), z=(p.seat_z, p.seat_z), flat="z")],
        "spring_rear": [f for f in select(boxes, x=(-p.wing_reach, -s0), z=(p.seat_z, p.seat_z), flat="z")],
        "sensor_pad": select(boxes, z=(top, top), flat="z"),
    }
