"""Small helpers over the gmsh OCC kernel: revolved solids and face look-up."""
from __future__ import annotations

import math

import numpy as np


def revolve_profile(profile: list[tuple[float, float]], sector_deg: float = 0.0) -> list[int]:
    """Solid of revolution about the y axis from a closed (y, r) profile.

    The profile lies in the half-plane below the axis (z = -r), so that a
    ``sector_deg`` > 0 splits off the bottom sector ``|angle| <= sector_deg/2``
    (where a wheel meets the rail) as its own volume, meshed conformally with
    the rest.  Returns the volume tags.
    """
    import gmsh
    occ = gmsh.model.occ

    def face():
        pts = [occ.addPoint(0.0, y, -r) for y, r in profile]
        lines = [occ.addLine(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))]
        return occ.addPlaneSurface([occ.addCurveLoop(lines)])

    if sector_deg <= 0:
        out = occ.revolve([(2, face())], 0, 0, 0, 0, 1, 0, 2 * math.pi)
        return [t for d, t in out if d == 3]
    half = math.radians(sector_deg) / 2
    f1 = face()
    occ.rotate([(2, f1)], 0, 0, 0, 0, 1, 0, -half)
    v1 = [t for d, t in occ.revolve([(2, f1)], 0, 0, 0, 0, 1, 0, 2 * half) if d == 3]
    f2 = face()
    occ.rotate([(2, f2)], 0, 0, 0, 0, 1, 0, half)
    v2 = [t for d, t in occ.revolve([(2, f2)], 0, 0, 0, 0, 1, 0, 2 * math.pi - 2 * half) if d == 3]
    out, _ = occ.fragment([(3, t) for t in v1], [(3, t) for t in v2])
    return [t for d, t in out if d == 3]


def boundary_faces() -> list[int]:
    """Tags of the faces on the outer boundary of all volumes (after synchronize)."""
    import gmsh
    vols = gmsh.model.getEntities(3)
    faces = gmsh.model.getBoundary(vols, combined=True, oriented=False)
    return sorted({abs(t) for _, t in faces})


def face_boxes(faces: list[int]) -> dict[int, np.ndarray]:
    """Bounding box (xmin, ymin, zmin, xmax, ymax, zmax) of each face."""
    import gmsh
    return {f: np.array(gmsh.model.getBoundingBox(2, f)) for f in faces}


def select(boxes: dict[int, np.ndarray], *, x=None, y=None, z=None,
           flat: str | None = None, tol: float = 1e-4) -> list[int]:
    """Faces whose bounding box lies inside every given ``(lo, hi)`` range.

    ``flat='x'|'y'|'z'`` keeps only faces of zero extent along that axis.
    """
    out = []
    for f, b in boxes.items():
        ok = True
        for i, rng in enumerate((x, y, z)):
            if rng is not None:
                ok &= b[i] >= rng[0] - tol and b[i + 3] <= rng[1] + tol
        if flat is not None:
            i = "xyz".index(flat)
            ok &= abs(b[i + 3] - b[i]) <= tol
        if ok:
            out.append(f)
    return out
