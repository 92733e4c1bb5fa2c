"""Parametric gmsh (OCC) models with named interface surfaces: wheelset, axle-box, bogie frame."""
from axlebox._params import ParameterError

__all__ = ["ParameterError"]
