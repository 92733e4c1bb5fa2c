"""Prismatic box beam along x: the free-vibration and mass-property reference body."""
from __future__ import annotations

from dataclasses import dataclass

from axlebox._params import check_ranges, param

from ._occ import boundary_faces, face_boxes, select


@dataclass(frozen=True)
class BeamParams:
    """Rectangular steel bar ``length`` x ``width`` (y) x ``height`` (z), centred at the origin."""

    length: float = param(1.0, 0.01, 100.0)
    width: float = param(0.04, 0.001, 10.0)
    height: float = param(0.06, 0.001, 10.0)

    def __post_init__(self):
        check_ranges(self)


def build(p: BeamParams) -> dict[str, list[int]]:
    """Named faces: ``end_a`` (x = -L/2) and ``end_b`` (x = +L/2)."""
    import gmsh
    occ = gmsh.model.occ
    occ.addBox(-p.length / 2, -p.width / 2, -p.height / 2, p.length, p.width, p.height)
    occ.synchronize()
    boxes = face_boxes(boundary_faces())
    a, b = -p.length / 2, p.length / 2
    return {"end_a": select(boxes, x=(a, a), flat="x"),
            "end_b": select(boxes, x=(b, b), flat="x")}
