"""The reduced-body file: versioned HDF5, SI units; the layout (as on the documentation's design
page):

==================================  =============================================
``attrs format, version``           "axlebox-reduced-body", :data:`VERSION`
``attrs name, method, ...``         body name, "guyan" | "craig-bampton", metadata
``mass``                            kg
``center_of_mass``                  (3,) m
``inertia``                         (3, 3) kg m^2 about the centre of mass
``frequencies_hz``                  (n,) free-free elastic frequencies, ascending
``reduced/mass|stiffness|damping``  (n, n) in the orthonormal elastic modal
                                    coordinates (mass = I, stiffness = diag w^2)
``component/mass|stiffness``        Craig-Bampton / Guyan matrices in [eta; u_b]
``component/fixed_frequencies_hz``  fixed-interface frequencies
``component/modes``                 (r, n) the elastic modes in [eta; u_b]
``nodes/<name>/position``           (3,) master / output node, m
``nodes/<name>/shapes``             (6, n) translations (m) and rotations (rad) per
                                    unit modal coordinate; attr ``coupling``
``invariants/<name>``               FFRF invariants (see :mod:`axlebox.fem.invariants`)
``mesh/points``, ``mesh/cells``     (p, 3) m, (c, 10) tet10 in VTK node order
``modes/shapes``                    (n, p, 3) full-field mode shapes
``reference/frequencies_hz``        full FE free-free frequencies, when computed
==================================  =============================================
"""
from __future__ import annotations

import json
import os
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

FORMAT = "axlebox-reduced-body"
VERSION = 1


class BodyFileError(ValueError):
    """The file is not a reduced body this version can read."""


@dataclass
class ReducedBody:
    name: str
    method: str
    mass: float
    center_of_mass: np.ndarray
    inertia: np.ndarray
    frequencies_hz: np.ndarray
    reduced_mass: np.ndarray
    reduced_stiffness: np.ndarray
    reduced_damping: np.ndarray
    nodes: dict[str, dict] = field(default_factory=dict)
    invariants: dict[str, np.ndarray] = field(default_factory=dict)
    component: dict[str, np.ndarray] = field(default_factory=dict)
    mesh_points: np.ndarray | None = None
    mesh_cells: np.ndarray | None = None
    mode_shapes: np.ndarray | None = None
    reference_frequencies_hz: np.ndarray | None = None
    meta: dict = field(default_factory=dict)

    @property
    def n_modes(self) -> int:
        return len(self.frequencies_hz)

    def node(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        """Position (3,) and shape rows (6, n) of a master/output node."""
        if name not in self.nodes:
            raise KeyError(f"body {self.name!r} has no node {name!r}; it has {sorted(self.nodes)}")
        return self.nodes[name]["position"], self.nodes[name]["shapes"]


def write(body: ReducedBody, path: str | os.PathLike) -> Path:
    """Write ``body`` to ``path`` (via a temporary file renamed when complete)."""
    import h5py
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(suffix=".h5.part", dir=path.parent)
    os.close(fd)
    try:
        with h5py.File(tmp, "w") as f:
            f.attrs["format"] = FORMAT
            f.attrs["version"] = VERSION
            f.attrs["name"] = body.name
            f.attrs["method"] = body.method
            f.attrs["meta"] = json.dumps(body.meta, sort_keys=True, default=str)
            f["mass"] = body.mass
            f["center_of_mass"] = body.center_of_mass
            f["inertia"] = body.inertia
            f["frequencies_hz"] = body.frequencies_hz
            g = f.create_group("reduced")
            g["mass"], g["stiffness"], g["damping"] = (body.reduced_mass, body.reduced_stiffness,
                                                       body.reduced_damping)
            g = f.create_group("component")
            for k, v in body.component.items():
                g[k] = v
            g = f.create_group("nodes")
            for name, nd in body.nodes.items():
                h = g.create_group(name)
                h["position"], h["shapes"] = nd["position"], nd["shapes"]
                h.attrs["coupling"] = nd.get("coupling", "")
            g = f.create_group("invariants")
            for k, v in body.invariants.items():
                g[k] = v
            if body.mesh_points is not None:
                g = f.create_group("mesh")
                g.create_dataset("points", data=body.mesh_points, compression="gzip")
                g.create_dataset("cells", data=body.mesh_cells, compression="gzip")
            if body.mode_shapes is not None:
                f.create_group("modes").create_dataset("shapes", data=body.mode_shapes,
                                                       compression="gzip", chunks=True)
            if body.reference_frequencies_hz is not None:
                f.create_group("reference")["frequencies_hz"] = body.reference_frequencies_hz
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return path


def read(path: str | os.PathLike, *, fields: bool = True) -> ReducedBody:
    """Read a reduced body; refuses other formats and versions with a clear message.

    ``fields=False`` skips the mesh and full-field mode shapes (what a solver needs).
    """
    import h5py
    path = Path(path)
    if not path.is_file():
        raise BodyFileError(f"reduced body {str(path)!r}: no such file")
    try:
        f = h5py.File(path, "r")
    except OSError as err:
        raise BodyFileError(f"reduced body {str(path)!r} is not an HDF5 file ({err})") from None
    try:
        return _read(f, path, fields)
    except BodyFileError:
        raise
    except (KeyError, OSError, ValueError, TypeError, RuntimeError) as err:   # a damaged file
        why = " ".join(f"{type(err).__name__}: {err}".split())
        raise BodyFileError(f"reduced body {str(path)!r} cannot be read ({why})") from None
    finally:
        f.close()


def _read(f, path: Path, fields: bool) -> ReducedBody:
    fmt = f.attrs.get("format")
    fmt = fmt.decode() if isinstance(fmt, bytes) else fmt
    if fmt != FORMAT:
        raise BodyFileError(f"{str(path)!r} has format = {fmt!r}: expected {FORMAT!r}")
    ver = f.attrs.get("version")
    if ver is None or int(ver) != VERSION:
        raise BodyFileError(f"{str(path)!r} has version = {ver!r}: this axlebox reads "
                            f"version {VERSION} only")
    a = lambda k: f[k][()]   # noqa: E731
    nodes = {n: {"position": g["position"][()], "shapes": g["shapes"][()],
                 "coupling": str(g.attrs.get("coupling", ""))} for n, g in f["nodes"].items()}
    body = ReducedBody(
        name=str(f.attrs["name"]), method=str(f.attrs["method"]), mass=float(a("mass")),
        center_of_mass=a("center_of_mass"), inertia=a("inertia"),
        frequencies_hz=a("frequencies_hz"), reduced_mass=a("reduced/mass"),
        reduced_stiffness=a("reduced/stiffness"), reduced_damping=a("reduced/damping"),
        nodes=nodes, invariants={k: v[()] for k, v in f["invariants"].items()},
        component={k: v[()] for k, v in f["component"].items()},
        meta=json.loads(f.attrs.get("meta", "{}")))
    if fields and "mesh" in f:
        body.mesh_points, body.mesh_cells = a("mesh/points"), a("mesh/cells")
    if fields and "modes" in f:
        body.mode_shapes = a("modes/shapes")
    if "reference" in f:
        body.reference_frequencies_hz = a("reference/frequencies_hz")
    return body


def export_vtu(body: ReducedBody, path: str | os.PathLike) -> Path:
    """Mesh with one point vector per mode (``mode_01_93.6Hz`` ...) for ParaView (meshio)."""
    import meshio
    if body.mesh_points is None or body.mode_shapes is None:
        raise BodyFileError(f"body {body.name!r} was read without its mesh and mode shapes")
    data = {f"mode_{k + 1:02d}_{f:.1f}Hz": body.mode_shapes[k]
            for k, f in enumerate(body.frequencies_hz)}
    path = Path(path)
    fd, tmp = tempfile.mkstemp(suffix=".vtu", dir=path.parent)
    os.close(fd)
    meshio.write(tmp, meshio.Mesh(body.mesh_points, [("tetra10", body.mesh_cells)], point_data=data))
    os.replace(tmp, path)
    return path
