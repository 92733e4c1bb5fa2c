"""Bodies of the multibody system: rigid (6 DOF) and flexible in the floating frame of reference.

A body has a reference frame with position ``r`` (inertial) and orientation ``A`` (body to
inertial, a unit quaternion), and ``n`` modal coordinates ``q`` (none for a rigid body).  A
material point at ``x`` (body frame, undeformed) sits at ``r + A (x + Phi(x) q)``.  Everything the
equations of motion need is a volume integral over the body, precomputed once (the FFRF inertia
invariants of :mod:`axlebox.fem.invariants`, Shabana ch. 5):

* ``mass``, ``mc`` (first moment about the frame origin), ``P0 = int rho x x^T`` (3, 3);
* ``Ct = int rho Phi`` (3, n), ``Q[a, b, k] = int rho x_a Phi_kb``, ``R[a, b, k, l] =
  int rho Phi_ka Phi_lb``, ``Me`` (n, n) modal mass, ``K``, ``D`` modal stiffness and damping.

A rigid body is the same with ``n = 0``; its frame origin is its centre of mass.

**Spinning bodies** (the wheelset; the documentation's design page): the reference frame follows
translation, roll and yaw but not the spin about the body ``y`` axis, which is a coordinate of its
own.  The angular velocity slot ``omega[1]`` then holds the spin rate of the material; the frame
itself turns with ``(omega[0], 0, omega[2])``.  For an axisymmetric body this keeps the rigid
inertia exact; the coupling of spin with the elastic coordinates (gyroscopic splitting of the
bending modes, of order spin/bending frequency: 5 Hz / 90 Hz at 48 km/h) is left out.

Nodes of a flexible body (the reduced body's master and output nodes) carry shape rows
``(6, n)``: the translation and small rotation of the node per unit modal coordinate.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from axlebox._params import ParameterError
from axlebox.fem.bodyfile import ReducedBody


@dataclass
class Body:
    name: str
    mass: float
    mc: np.ndarray                  # (3,) first moment about the frame origin, kg m
    P0: np.ndarray                  # (3, 3) int rho x x^T about the frame origin, kg m^2
    Ct: np.ndarray                  # (3, n)
    Q: np.ndarray                   # (3, 3, n)
    R: np.ndarray                   # (3, 3, n, n)
    Me: np.ndarray                  # (n, n)
    K: np.ndarray                   # (n, n)
    D: np.ndarray                   # (n, n)
    nodes: dict[str, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)
    spin: bool = False
    frequencies_hz: np.ndarray = field(default_factory=lambda: np.zeros(0))
    source: str = ""

    @property
    def n_modes(self) -> int:
        return self.K.shape[0]

    @property
    def flexible(self) -> bool:
        return self.n_modes > 0

    @property
    def inertia_origin(self) -> np.ndarray:
        """Inertia tensor about the frame origin (undeformed), kg m^2."""
        return np.trace(self.P0) * np.eye(3) - self.P0

    def node(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        if name not in self.nodes:
            raise ParameterError(f"body {self.name!r} has no node {name!r}: expected one of "
                                 f"{sorted(self.nodes)}")
        return self.nodes[name]


def _positive(name: str, what: str, value: float) -> None:
    if not (np.isfinite(value) and value > 0):
        raise ParameterError(f"{name}.{what} = {value!r} is not allowed: expected a number > 0")


def rigid(name: str, mass: float, inertia, *, spin: bool = False) -> Body:
    """A rigid body, frame origin at its centre of mass; ``inertia`` (3,) principal or (3, 3)."""
    _positive(name, "mass", mass)
    J = np.asarray(inertia, float)
    J = np.diag(J) if J.shape == (3,) else J
    if J.shape != (3, 3) or not np.allclose(J, J.T):
        raise ParameterError(f"{name}.inertia = {inertia!r} is not allowed: expected 3 principal "
                             "values or a symmetric 3 x 3 tensor, kg m^2")
    ev = np.linalg.eigvalsh(J)
    # triangle inequality of principal moments: any real mass distribution meets it
    if ev.min() <= 0 or ev[2] > ev[0] + ev[1] + 1e-9 * ev[2]:
        raise ParameterError(f"{name}.inertia = {inertia!r} is not allowed: principal moments must be "
                             "> 0 and each at most the sum of the other two")
    P0 = 0.5 * np.trace(J) * np.eye(3) - J
    z = np.zeros
    return Body(name, float(mass), z(3), P0, z((3, 0)), z((3, 3, 0)), z((3, 3, 0, 0)), z((0, 0)),
                z((0, 0)), z((0, 0)), {}, spin, source="rigid")


def flexible(name: str, rb: ReducedBody, *, n_modes: int | None = None, spin: bool = False,
             rigid_only: bool = False) -> Body:
    """A flexible body from a reduced-body file (:func:`axlebox.fem.bodyfile.read`).

    The frame origin is the FE origin.  ``n_modes`` keeps the lowest modes (all by default);
    ``rigid_only`` keeps none, giving the rigid body with the FE mass properties and the same
    nodes (to switch a body rigid by config).
    """
    inv = rb.invariants
    n_all = int(rb.n_modes)
    n = 0 if rigid_only else (n_all if n_modes is None else int(n_modes))
    if not 0 <= n <= n_all:
        raise ParameterError(f"{name}.modes = {n_modes!r} is not allowed: expected 0..{n_all}")
    m = float(inv["m"])
    J = np.asarray(inv["J"], float)
    P0 = 0.5 * np.trace(J) * np.eye(3) - J
    nodes = {k: (np.asarray(v["position"], float), np.asarray(v["shapes"], float)[:, :n].copy())
             for k, v in rb.nodes.items()}
    return Body(name, m, np.asarray(inv["mc"], float), P0,
                np.ascontiguousarray(inv["Ct"][:, :n]), np.ascontiguousarray(inv["Q"][:, :, :n]),
                np.ascontiguousarray(inv["R"][:, :, :n, :n]),
                np.ascontiguousarray(inv["Me"][:n, :n]),
                np.ascontiguousarray(rb.reduced_stiffness[:n, :n]),
                np.ascontiguousarray(rb.reduced_damping[:n, :n]), nodes, spin,
                np.asarray(rb.frequencies_hz[:n], float), source=f"{rb.method}:{rb.name}")


def add_point_masses(body: Body, masses: dict[str, float]) -> Body:
    """Attach point masses (kg) at nodes: mounted equipment the FE model leaves out (motors,
    brackets).  Each adds its exact share to every invariant (``m``, ``mc``, ``P0``, ``Ct``,
    ``Q``, ``R``, ``Me``) through the node's translation shapes; its own rotary inertia is
    neglected.  The modal mass is then no longer the identity, which the equations allow."""
    for node, m in masses.items():
        if not (np.isfinite(m) and m >= 0):
            raise ParameterError(f"{body.name}.point_mass[{node!r}] = {m!r} is not allowed: expected kg >= 0")
        x, sh = body.node(node)
        Pt = sh[:3]
        body.mass += m
        body.mc = body.mc + m * x
        body.P0 = body.P0 + m * np.outer(x, x)
        body.Ct = body.Ct + m * Pt
        body.Q = body.Q + m * np.einsum("a,bk->abk", x, Pt)
        body.R = body.R + m * np.einsum("ak,bl->abkl", Pt, Pt)
        body.Me = body.Me + m * Pt.T @ Pt
    return body


def mode_count(rb: ReducedBody, fmax_hz: float) -> int:
    """How many of a reduced body's free-free modes lie below ``fmax_hz``."""
    return int(np.sum(np.asarray(rb.frequencies_hz) <= fmax_hz))
