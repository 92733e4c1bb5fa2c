"""From an assembled FE model and its interfaces to a :class:`ReducedBody`."""
from __future__ import annotations

import numpy as np

from axlebox._params import ParameterError

from . import damping as damping_laws
from . import invariants, massprops
from .assembly import FEModel
from .bodyfile import ReducedBody
from .interfaces import Interface, condense
from .reduction import Reduction, reduce


def make_body(name: str, model: FEModel, interfaces: list[Interface], *,
              method: str = "craig-bampton", n_modes: int | None = 20,
              fmax_hz: float | None = None, damping: tuple = ("modal", 0.01),
              reference_hz: np.ndarray | None = None, meta: dict | None = None
              ) -> tuple[ReducedBody, Reduction]:
    """Reduce ``model`` and gather everything the reduced-body file holds.

    ``damping`` is ``("modal", zeta)`` or ``("rayleigh", alpha, beta)``.
    """
    red = reduce(model, condense(model, interfaces), method, n_modes=n_modes, fmax_hz=fmax_hz)
    X = red.X
    # deterministic signs: largest field component positive
    U = red.physical(X)
    flip = np.sign(U[np.abs(U).argmax(axis=0), np.arange(U.shape[1])])
    X, U = X * flip, U * flip
    Me = X.T @ red.M @ X
    Ke = X.T @ red.K @ X
    Me, Ke = 0.5 * (Me + Me.T), 0.5 * (Ke + Ke.T)

    kind = damping[0]
    if kind == "modal":
        D = damping_laws.modal(red.frequencies_hz, damping[1])
    elif kind == "rayleigh":
        D = damping_laws.rayleigh(Me, Ke, damping[1], damping[2])
    else:
        raise ParameterError(f"damping = {kind!r} is not allowed: expected 'modal' or 'rayleigh'")

    Rr = red.rigid_vectors()
    mp = massprops.from_rigid_mass(Rr.T @ red.M @ Rr)
    shapes = model.field(U)                                       # (n, p, 3)
    inv = invariants.compute(model.points, model.scalar_mass(), shapes)
    nodes = {itf.name: {"position": itf.position, "shapes": red.master_shapes(i, X),
                        "coupling": itf.kind}
             for i, itf in enumerate(red.condensation.interfaces)}
    component = {"mass": red.M, "stiffness": red.K, "modes": X,
                 "fixed_frequencies_hz": red.fixed_frequencies_hz,
                 "n_boundary": np.array(red.n_boundary)}
    meta = dict(meta or {})
    meta.update(n_dof=int(model.ndof), n_points=int(model.points.shape[0]),
                n_cells=int(model.mesh.cells.shape[0]), n_fixed_interface_modes=int(red.n_fixed),
                damping=list(damping), material=vars(model.material) if hasattr(model.material, "__dict__")
                else str(model.material))
    body = ReducedBody(
        name=name, method=method, mass=mp.mass, center_of_mass=mp.center_of_mass,
        inertia=mp.inertia, frequencies_hz=red.frequencies_hz, reduced_mass=Me,
        reduced_stiffness=Ke, reduced_damping=D, nodes=nodes, invariants=inv,
        component=component, mesh_points=model.points, mesh_cells=model.mesh.cells,
        mode_shapes=shapes, reference_frequencies_hz=reference_hz, meta=meta)
    return body, red
