"""Where an interface is: a selection of a body's surface by place, for a user's own part.

A selection holds for a piece of surface (a CAD face, a mesh facet) when every point of it that
is given (a face's boundary sampled and its centre, a facet's nodes) lies in the region: inside a
box, on a cylinder (by axis, radius and length), or within a distance of a point.  SI units: the
part is in metres by the time it is selected (geometry/cad.py, geometry/meshfile.py).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Box:
    """Inside the box ``lower .. upper`` (m), give or take ``tol``."""

    lower: tuple
    upper: tuple
    tol: float = 1e-4

    def holds(self, points: np.ndarray) -> np.ndarray:
        """Whether each of the (n, k, 3) pieces' k points lie inside (n,)."""
        lo, hi = np.asarray(self.lower) - self.tol, np.asarray(self.upper) + self.tol
        return ((points >= lo) & (points <= hi)).all(axis=(-1, -2))

    def looked_for(self) -> str:
        return f"faces inside the box {list(self.lower)} .. {list(self.upper)} m"


@dataclass(frozen=True)
class Cylinder:
    """On the cylinder of ``radius`` about the axis through ``point`` along ``axis``, from
    ``point`` to ``length`` along it (m), give or take ``tol``."""

    point: tuple
    axis: tuple
    radius: float
    length: float
    tol: float = 1e-4

    def holds(self, points: np.ndarray) -> np.ndarray:
        e = np.asarray(self.axis, float)
        e = e / np.linalg.norm(e)
        r = points - np.asarray(self.point)
        along = r @ e
        off = np.linalg.norm(r - along[..., None] * e, axis=-1)
        ok = (np.abs(off - self.radius) <= self.tol) & (along >= -self.tol)
        return (ok & (along <= self.length + self.tol)).all(axis=-1)

    def looked_for(self) -> str:
        return (f"faces on the cylinder of radius {self.radius:g} m about {list(self.axis)} through "
                f"{list(self.point)}, {self.length:g} m long")


@dataclass(frozen=True)
class Near:
    """Within ``distance`` of ``point`` (m)."""

    point: tuple
    distance: float

    def holds(self, points: np.ndarray) -> np.ndarray:
        return (np.linalg.norm(points - np.asarray(self.point), axis=-1) <= self.distance).all(axis=-1)

    def looked_for(self) -> str:
        return f"faces within {self.distance:g} m of {list(self.point)}"


@dataclass(frozen=True)
class Named:
    """A named surface of the file: a STEP label, a gmsh physical group, an Abaqus or Nastran set."""

    name: str

    def looked_for(self) -> str:
        return f"a surface named {self.name!r}"
