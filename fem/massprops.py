"""Rigid-body mass properties from a mass matrix."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class MassProperties:
    mass: float                 # kg
    center_of_mass: np.ndarray  # (3,) m
    inertia: np.ndarray         # (3, 3) kg m^2 about the centre of mass

    def as_array(self) -> np.ndarray:
        return np.concatenate([[self.mass], self.center_of_mass, self.inertia.ravel()])


def from_rigid_mass(Mrr: np.ndarray) -> MassProperties:
    """Mass properties from the 6 x 6 rigid-body mass ``R^T M R``.

    ``R`` holds the three translations and three small rotations about the
    origin (``u = theta x r``), so ``Mrr = [[m I, -m c~], [m c~, J_O]]``,
    and the inertia about the centre of mass is ``J_O - m (|c|^2 I - c c^T)``.
    """
    Mrr = 0.5 * (Mrr + Mrr.T)
    m = np.trace(Mrr[:3, :3]) / 3
    S = Mrr[3:, :3]                        # = m c~
    c = np.array([S[2, 1], S[0, 2], S[1, 0]]) / m
    J_O = Mrr[3:, 3:]
    J = J_O - m * (c @ c * np.eye(3) - np.outer(c, c))
    return MassProperties(mass=float(m), center_of_mass=c, inertia=J)


def from_model(model) -> MassProperties:
    """Mass properties of an assembled :class:`~axlebox.fem.assembly.FEModel`."""
    R = model.rigid_modes()
    return from_rigid_mass(R.T @ (model.M @ R))
