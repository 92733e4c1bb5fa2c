"""The shared case of the peer benchmark: one free flexible wheelset and one load history.

Both sides of the comparison (ours and Exudyn, ``benchmarks/peer_exudyn.py``) read
this module, so they integrate the same body under the same load:

* the wheelset at the coarse 60 mm mesh, Craig-Bampton on the pipeline's RBE3
  interfaces with 20 fixed-interface modes (``n_fixed``; the pipeline's default);
  with 7 interfaces that gives 20 + 7*6 - 6 = 56 free-free elastic modes of the
  reduced body, of which the lowest ``n_modes`` (18: up to the third bending pair,
  843/846 Hz; the next mode is at 1094 Hz) are kept.  The kept modes are exact
  columns of the body's M-orthonormal modal basis, so the truncated body is still
  mass = I, stiffness = diag(w^2), and every per-mode array is a slice;
* the full FE stiffness and mass in node-wise DOF order [x0, y0, z0, x1, ...]
  (scikit-fem numbers its P2 DOFs otherwise; ``FEModel.dofs`` gives the map), and
  the kept modes in that order, ``modes`` (3p, n) = ``body.mode_shapes`` flattened;
* the interface node sets with their RBE3 area weights;
* a deterministic force on the tread_L master node, inertial frame, no gravity,
  body at rest at t = 0, no spin (see :class:`LoadHistory`).

Run ``python benchmarks/peer_case.py`` to build it and print its numbers.
"""
from __future__ import annotations

import dataclasses
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from axlebox.fem import assembly, bodyfile, interfaces
from axlebox.fem.body import make_body
from axlebox.geometry import mesh as gmesh
from axlebox.pipelines.bodies import BODIES


@dataclass(frozen=True)
class LoadHistory:
    """Force (N, inertial frame) on ``interface``'s master node, zero from ``t_off`` on.

    ``F(t) = w(t) [Fx sin(2 pi fx t), Fy sin(2 pi fy t), Fz sin(2 pi fz t + phz) + Fz_dc]``
    with the Hann window ``w = sin^2(pi t / t_off)`` on [0, t_off): the window
    starts and ends the load smoothly, so no step excites the modes above the
    kept 18 (which neither side has) and the response is set by the modes the
    load aims at: Fx at 87 Hz drives the first torsion (93.7 Hz, the two wheels
    twisting against each other), Fz at 105 Hz and Fy at 37 Hz the first
    bending pair (99 Hz) and the wheel umbrella modes (148 Hz).  The forcing is
    off resonance so a small difference in damping or period does not blow up.
    The small constant part Fz_dc gives a clear net impulse (about 25 N s: the
    body drifts at 2 cm/s and rolls by about 0.03 rad by t = 1 s) for the
    momentum check, while the rigid rotation stays small.  Peak elastic
    displacement at the treads about 0.6 mm (torsion): linear.
    """

    interface: str = "tread_L"
    t_off: float = 0.5
    Fx: float = 1.0e4
    fx: float = 87.0
    Fy: float = 5.0e3
    fy: float = 37.0
    Fz: float = 2.0e4
    fz: float = 105.0
    phz: float = 0.3
    Fz_dc: float = 100.0

    def __call__(self, t):
        """F(t): (3,) for a scalar t, (len(t), 3) for an array."""
        ta = np.asarray(t, float)
        w = np.where((ta >= 0) & (ta < self.t_off), np.sin(np.pi * ta / self.t_off) ** 2, 0.0)
        F = np.stack([self.Fx * np.sin(2 * np.pi * self.fx * ta),
                      self.Fy * np.sin(2 * np.pi * self.fy * ta),
                      self.Fz * np.sin(2 * np.pi * self.fz * ta + self.phz) + self.Fz_dc], axis=-1)
        return F * w[..., None]

    def scalar(self, t: float) -> list[float]:
        """F(t) as a plain list, cheap for a per-step callback (no array machinery)."""
        if not 0.0 <= t < self.t_off:
            return [0.0, 0.0, 0.0]
        s = np.sin(np.pi * t / self.t_off)
        w = s * s
        tp = 2 * np.pi * t
        return [w * self.Fx * np.sin(tp * self.fx), w * self.Fy * np.sin(tp * self.fy),
                w * (self.Fz * np.sin(tp * self.fz + self.phz) + self.Fz_dc)]

    def impulse(self, t_end: float | None = None) -> np.ndarray:
        """int_0^t_end F dt (N s), by 200-point Gauss-Legendre on each of 200 pieces (exact to 1e-12)."""
        b = min(self.t_off, self.t_off if t_end is None else t_end)
        x, wq = np.polynomial.legendre.leggauss(200)
        edges = np.linspace(0.0, b, 201)
        a0, a1 = edges[:-1, None], edges[1:, None]
        t = (0.5 * (a1 - a0) * x + 0.5 * (a1 + a0)).ravel()
        wt = (0.5 * (a1 - a0) * wq).ravel()
        return wt @ self(t)


@dataclass
class PeerCase:
    body: bodyfile.ReducedBody        # truncated to n_modes elastic modes
    body_path: Path                   # the same body written as a reduced-body file
    K: sp.csr_matrix                  # full FE stiffness, node-wise DOF order
    M: sp.csr_matrix                  # full FE consistent mass, node-wise DOF order
    points: np.ndarray                # (p, 3) m, FE origin = body frame origin
    cells: np.ndarray                 # (c, 10) tet10 (VTK order)
    modes: np.ndarray                 # (3p, n) kept elastic modes, node-wise, = body.mode_shapes
    interfaces: dict[str, dict]       # name -> nodes, weights (m^2), position (3,), kind
    load: LoadHistory
    mesh_size: float
    n_fixed: int
    checks: dict = field(default_factory=dict)

    @property
    def n_modes(self) -> int:
        return self.body.n_modes

    def modal_force(self, F: np.ndarray) -> np.ndarray:
        """Generalized modal force of a force F (body frame) on the load's master node."""
        return self.body.node(self.load.interface)[1][:3].T @ np.asarray(F)


def truncate(body: bodyfile.ReducedBody, n: int) -> bodyfile.ReducedBody:
    """The lowest ``n`` elastic modes of ``body`` (columns of an orthonormal modal basis)."""
    if not 1 <= n <= body.n_modes:
        raise ValueError(f"n_modes = {n!r} is not allowed: expected 1..{body.n_modes}")
    per_mode = {"Ct": (slice(None), slice(0, n)), "Cr": (slice(None), slice(0, n)),
                "Me": (slice(0, n), slice(0, n)), "Q": (Ellipsis, slice(0, n)),
                "R": (Ellipsis, slice(0, n), slice(0, n))}
    inv = {k: (v[per_mode[k]] if k in per_mode else v) for k, v in body.invariants.items()}
    inv["n_modes"] = np.array(n)
    comp = dict(body.component)
    comp["modes"] = comp["modes"][:, :n]
    nodes = {k: dict(v, shapes=v["shapes"][:, :n]) for k, v in body.nodes.items()}
    meta = dict(body.meta, truncated_from=body.n_modes)
    return dataclasses.replace(
        body, frequencies_hz=body.frequencies_hz[:n], reduced_mass=body.reduced_mass[:n, :n],
        reduced_stiffness=body.reduced_stiffness[:n, :n], reduced_damping=body.reduced_damping[:n, :n],
        nodes=nodes, invariants=inv, component=comp, mode_shapes=body.mode_shapes[:n], meta=meta)


def build_case(mesh_size: float = 0.06, n_modes: int = 18, *, n_fixed: int = 20,
               out_dir: str | Path | None = None, load: LoadHistory | None = None,
               zeta: float = 0.01) -> PeerCase:
    """Mesh (cached), assemble, reduce and truncate the wheelset; write ``<out_dir>/wheelset.h5``.

    ``zeta``: the body's modal damping ratio (both sides use the body file's
    ``reduced/damping`` = diag(2 zeta w)).  About 11 s at the 60 mm mesh.
    """
    spec = BODIES["wheelset"]
    p = spec.params()
    msh = gmesh.mesh_model("wheelset", spec.build, p, mesh_size)
    fe = assembly.assemble(msh)
    itf = interfaces.make_interfaces(fe, spec.couplings(p), spec.positions(p))
    meta = {"body": "wheelset", "params": dataclasses.asdict(p), "mesh_size": mesh_size,
            "peer_case": {"n_fixed": n_fixed, "n_modes": n_modes}}
    full, _ = make_body("wheelset", fe, itf, method="craig-bampton", n_modes=n_fixed,
                        damping=("modal", zeta), meta=meta)
    body = truncate(full, n_modes)
    out_dir = Path(out_dir) if out_dir is not None else Path(tempfile.mkdtemp(prefix="peer-case-"))
    path = bodyfile.write(body, out_dir / "wheelset.h5")

    # node-wise order: row 3i + a of the new matrices is FE DOF dofs[i, a]
    perm = fe.dofs.ravel()
    K = fe.K[perm][:, perm].tocsr()
    M = fe.M[perm][:, perm].tocsr()
    modes = body.mode_shapes.reshape(n_modes, -1).T.copy()       # (3p, n), [x0, y0, z0, x1, ...]
    # the kept modes must be M-orthonormal and K-diagonal in these matrices (same body both sides)
    w2 = (2 * np.pi * body.frequencies_hz) ** 2
    Mr, Kr = modes.T @ (M @ modes), modes.T @ (K @ modes)
    checks = {"mass_orthonormality": float(np.abs(Mr - np.eye(n_modes)).max()),
              "stiffness_diagonal": float(np.abs(Kr - np.diag(w2)).max() / w2.max()),
              "fixed_interface_hz": full.component["fixed_frequencies_hz"].tolist(),
              "next_mode_hz": float(full.frequencies_hz[n_modes]) if full.n_modes > n_modes else None}
    itfs = {i.name: {"nodes": i.nodes, "weights": i.weights, "position": i.position, "kind": i.kind}
            for i in itf}
    return PeerCase(body=body, body_path=path, K=K, M=M, points=fe.points, cells=msh.cells,
                    modes=modes, interfaces=itfs, load=load or LoadHistory(), mesh_size=mesh_size,
                    n_fixed=n_fixed, checks=checks)


if __name__ == "__main__":
    case = build_case()
    b = case.body
    print(f"wheelset: {case.points.shape[0]} points, {case.K.shape[0]} DOF, mass {b.mass:.1f} kg, "
          f"{case.n_fixed} fixed-interface modes -> {b.n_modes} kept elastic modes; {case.body_path}")
    print("frequencies Hz:", np.round(b.frequencies_hz, 2).tolist())
    print(f"next mode {case.checks['next_mode_hz']:.1f} Hz; |Psi'M Psi - I| = "
          f"{case.checks['mass_orthonormality']:.1e}, |Psi'K Psi - W^2|/w2max = "
          f"{case.checks['stiffness_diagonal']:.1e}")
    print("load impulse N s:", case.load.impulse())
    for name, d in case.interfaces.items():
        print(f"  {name:15s} {len(d['nodes']):4d} nodes, area {d['weights'].sum() * 1e4:7.1f} cm^2, "
              f"master {np.round(d['position'], 4).tolist()}")
