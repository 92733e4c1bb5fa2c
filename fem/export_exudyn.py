"""A reduced body as the data of Exudyn's ``FEMinterface``, in the HDF5 layout its
``LoadFromFile`` reads, for ``ObjectFFRFreducedOrderInterface``.

Source of the format: Exudyn's documentation, "Module: FEM", class ``FEMinterface``
(``__init__`` lists the members; ``SaveToFile`` / ``LoadFromFile`` with ``mode='HDF5'`` store
them through ``exudyn.advancedUtilities.SaveDictToHDF5`` / ``LoadDictFromHDF5``), checked
against exudyn 1.13.6.  That layout: every dict is an HDF5 group with attribute
``datatype='dict'``, a list a group ``'list'`` of ``item_0, item_1, ...``, a scipy CSR matrix
a group ``'csr_matrix'`` (``data``, ``indices``, ``indptr``, ``shape``), an array a dataset
``'ndarray'``, a number or a string a dataset ``'float'`` / ``'int'`` / ``'str'``.  Exudyn
picks the reader by the file name: it must end in ``.hdf5``.

What the file holds (SI units; the FE origin is the body frame):

* ``nodes['Position']`` (p, 3) m, the tet10 mesh points;
* ``elements[0]['Tet10']`` (c, 10): the body file's VTK tet10 order is Abaqus C3D10's, which
  Exudyn uses (mid nodes on 0-1, 1-2, 2-0, 0-3, 1-3, 2-3);
* ``surface[0]['Trigs']`` / ``['Trigs6']``: the boundary faces for drawing (6-node: curved);
* ``massMatrix``, ``stiffnessMatrix``: the full FE matrices reassembled with scikit-fem from
  the body file's mesh and material (``meta['material']``), in node-wise DOF order
  [x0, y0, z0, x1, ...], as Exudyn's mode basis is;
* ``modeBasis`` {'matrix': (3p, n), 'type': 'NormalModes'}: the body's free-free elastic modes
  (``modes/shapes``), mass-orthonormal, so Exudyn's reduced mass is I and its stiffness
  diag(w^2), the body file's; ``eigenValues`` (n,) w^2 in (rad/s)^2;
* ``metaData``: where it came from, and what Exudyn's FEM data has no place for: the modal
  damping matrix (``'dampingMatrixReduced'``, for the object's parameter of that name), the
  frequencies, mass properties and the master/output nodes (``'interfaces'``: name ->
  position (3,), shapes (6, n), coupling) where loads and joints attach.

Before writing, the reassembled matrices are checked against the body: the modes must be
mass-orthonormal and give the body's frequencies (1e-8), else the mesh, material or modes in
the file do not belong together.
"""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from axlebox import __version__
from axlebox._files import h5_bound, h5_written
from axlebox._params import number

from .bodyfile import BodyFileError, ReducedBody

# faces of a tet (Exudyn's VolumeToSurfaceElements order) and the mid node of each edge (C3D10)
_FACES = np.array([[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]])
_MID = np.zeros((4, 4), int)
for (_a, _b), _m in {(0, 1): 4, (1, 2): 5, (0, 2): 6, (0, 3): 7, (1, 3): 8, (2, 3): 9}.items():
    _MID[_a, _b] = _MID[_b, _a] = _m
_TOL = 1e-8


def _check(body: ReducedBody) -> None:
    """Refuse a body whose arrays do not fit together (a damaged or foreign file)."""
    if body.mesh_points is None or body.mesh_cells is None or body.mode_shapes is None:
        raise BodyFileError(f"body {body.name!r} has no mesh or no full-field mode shapes "
                            "(read with fields=True; written by an axlebox that stores them)")
    n = body.n_modes
    pts, cells, shapes = (np.asarray(a) for a in (body.mesh_points, body.mesh_cells, body.mode_shapes))
    p = pts.shape[0] if pts.ndim == 2 else -1
    bad = [("mesh/points", pts.shape, "(p, 3)", pts.ndim == 2 and pts.shape[1] == 3),
           ("mesh/cells", cells.shape, "(c, 10) point numbers < p", cells.ndim == 2 and cells.shape[1] == 10
            and cells.dtype.kind in "iu" and cells.size > 0 and 0 <= cells.min() and cells.max() < p),
           ("modes/shapes", shapes.shape, f"({n}, {p}, 3)", shapes.shape == (n, p, 3)),
           ("reduced/damping", np.shape(body.reduced_damping), f"({n}, {n})",
            np.shape(body.reduced_damping) == (n, n))]
    bad += [(f"nodes/{k}/shapes", np.shape(v["shapes"]), f"(6, {n})", np.shape(v["shapes"]) == (6, n))
            for k, v in body.nodes.items()]
    for name, shape, want, ok in bad:
        if not ok:
            raise BodyFileError(f"body {body.name!r} has {name} of shape {shape}: expected {want}")
    for name, a in (("mesh/points", pts), ("modes/shapes", shapes), ("frequencies_hz", body.frequencies_hz),
                    ("reduced/damping", body.reduced_damping)):
        if not np.all(np.isfinite(np.asarray(a, float))):
            raise BodyFileError(f"body {body.name!r} holds non-finite numbers in {name}")
    if n == 0 or not np.all(np.asarray(body.frequencies_hz) > 0):
        raise BodyFileError(f"body {body.name!r} has frequencies_hz = {body.frequencies_hz!r}: expected "
                            "one or more elastic frequencies > 0")


def fe_matrices(body: ReducedBody) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """Full FE mass and stiffness of ``body`` in node-wise DOF order, reassembled with
    scikit-fem (:func:`axlebox.fem.assembly.assemble`) from its mesh and material."""
    from axlebox.geometry.mesh import MeshData

    from .assembly import Material, assemble
    _check(body)
    mat = body.meta.get("material")
    if not isinstance(mat, dict) or not {"E", "nu", "rho"} <= set(mat):
        raise BodyFileError(f"body {body.name!r} has material = {mat!r} in its meta: expected "
                            "{'E': Pa, 'nu': -, 'rho': kg/m^3} to reassemble its FE matrices")
    fe = assemble(MeshData(np.asarray(body.mesh_points, float), np.asarray(body.mesh_cells)),
                  Material(**{k: number(f"material.{k}", mat[k]) for k in ("E", "nu", "rho")}))
    perm = fe.dofs.ravel()               # row 3i + a of the new matrices is FE DOF dofs[i, a]
    return fe.M[perm][:, perm].tocsr(), fe.K[perm][:, perm].tocsr()


def mode_basis(body: ReducedBody) -> np.ndarray:
    """The elastic modes as columns (3p, n) in node-wise order."""
    return np.ascontiguousarray(np.asarray(body.mode_shapes, float).reshape(body.n_modes, -1).T)


def check_basis(body: ReducedBody, M, K, Psi) -> dict:
    """How far ``Psi^T M Psi`` is from I and its frequencies from the body's; refuses > 1e-8."""
    w2 = (2 * np.pi * np.asarray(body.frequencies_hz, float)) ** 2
    Mr, Kr = Psi.T @ (M @ Psi), Psi.T @ (K @ Psi)
    from scipy.linalg import eigh
    f = np.sqrt(np.abs(eigh(0.5 * (Kr + Kr.T), 0.5 * (Mr + Mr.T), eigvals_only=True))) / (2 * np.pi)
    out = {"mass_orthonormality": float(np.abs(Mr - np.eye(len(w2))).max()),
           "frequency_rel": float(np.abs(f / body.frequencies_hz - 1).max())}
    if out["mass_orthonormality"] > _TOL or out["frequency_rel"] > _TOL:
        raise BodyFileError(f"body {body.name!r}: its modes on the FE matrices reassembled from its mesh "
                            f"and material give |Psi'M Psi - I| = {out['mass_orthonormality']:.1e}, "
                            f"frequencies off by {out['frequency_rel']:.1e} (allowed {_TOL:g}): "
                            "the mesh, material or modes in the file do not belong together")
    return out


def surface(cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Boundary faces of a tet10 mesh: corner triangles (f, 3) and 6-node triangles (f, 6)
    (corners, then the mid nodes of edges 0-1, 1-2, 2-0), the faces that belong to one tet."""
    cells = np.asarray(cells)
    tri = cells[:, _FACES].reshape(-1, 3)                       # (4c, 3), orientation kept
    key = np.sort(tri, axis=1)
    _, first, count = np.unique(key, axis=0, return_index=True, return_counts=True)
    keep = np.sort(first[count == 1])
    local = np.tile(_FACES, (len(cells), 1))[keep]              # local corner numbers of each face
    owner = cells[keep // 4]
    rows = np.arange(len(keep))
    mids = [owner[rows, _MID[local[:, a], local[:, b]]] for a, b in ((0, 1), (1, 2), (2, 0))]
    return tri[keep], np.column_stack([tri[keep], *mids])


def fem_data(body: ReducedBody, M=None, K=None) -> dict:
    """The FEMinterface members (``GetDictionary`` plus ``fileVersion`` and ``type``)."""
    _check(body)
    if M is None or K is None:
        M, K = fe_matrices(body)
    Psi = mode_basis(body)
    checks = check_basis(body, M, K, Psi)
    trigs, trigs6 = surface(body.mesh_cells)
    interfaces = {k: {"position": np.asarray(v["position"], float), "shapes": np.asarray(v["shapes"], float),
                      "coupling": str(v.get("coupling", ""))} for k, v in body.nodes.items()}
    meta = {"source": f"axlebox {__version__} bodies export (reduced body {body.name!r}, {body.method})",
            "units": "SI: m, kg, s, N, rad", "body": body.name, "method": body.method,
            "frequencies_hz": np.asarray(body.frequencies_hz, float),
            "dampingMatrixReduced": np.asarray(body.reduced_damping, float),
            "mass": float(body.mass), "center_of_mass": np.asarray(body.center_of_mass, float),
            "inertia": np.asarray(body.inertia, float), "interfaces": interfaces,
            "check_mass_orthonormality": checks["mass_orthonormality"],
            "check_frequency_rel": checks["frequency_rel"]}
    return {"metaData": meta,
            "nodes": {"Position": np.asarray(body.mesh_points, float)},
            "elements": [{"Name": body.name, "Tet10": np.asarray(body.mesh_cells, np.int64)}],
            "massMatrix": M, "stiffnessMatrix": K,
            "surface": [{"Name": body.name, "Trigs": trigs.astype(np.int64),
                         "Trigs6": trigs6.astype(np.int64)}],
            "nodeSets": [], "elementSets": [],
            "modeBasis": {"matrix": Psi, "type": "NormalModes"},
            "eigenValues": (2 * np.pi * np.asarray(body.frequencies_hz, float)) ** 2,
            "postProcessingModes": {}, "fileVersion": 4, "type": "FEMinterface"}


def _put(group, key: str, item) -> None:
    """``item`` under ``group[key]`` as ``SaveDictToHDF5`` stores it."""
    import h5py
    if isinstance(item, dict):
        g = group.create_group(key)
        g.attrs["datatype"] = "dict"
        for k, v in item.items():
            _put(g, k, v)
    elif isinstance(item, list):
        g = group.create_group(key)
        g.attrs["datatype"] = "list"
        for i, v in enumerate(item):
            _put(g, f"item_{i}", v)
    elif sp.issparse(item):
        item = sp.csr_matrix(item)
        g = group.create_group(key)
        g.attrs["datatype"] = "csr_matrix"
        for k, v in (("data", item.data), ("indices", item.indices), ("indptr", item.indptr),
                     ("shape", np.array(item.shape))):
            g.create_dataset(k, data=v)
    elif isinstance(item, np.ndarray):
        group.create_dataset(key, data=item)
        group[key].attrs["datatype"] = "ndarray"
    elif isinstance(item, str):
        group.create_dataset(key, data=item, dtype=h5py.string_dtype(encoding="utf-8"))
        group[key].attrs["datatype"] = "str"
    elif isinstance(item, (bool, int, float)):
        group.create_dataset(key, data=item)
        group[key].attrs["datatype"] = type(item).__name__
    else:
        raise TypeError(f"{key}: {type(item).__name__} has no place in Exudyn's HDF5 layout")


def _arrays(item):
    """Every array in ``item`` (for the space to reserve)."""
    if isinstance(item, dict):
        for v in item.values():
            yield from _arrays(v)
    elif isinstance(item, list):
        for v in item:
            yield from _arrays(v)
    elif sp.issparse(item):
        yield from (item.data, item.indices, item.indptr)
    elif isinstance(item, np.ndarray):
        yield item


def write(body: ReducedBody, path: str | os.PathLike) -> Path:
    """Write ``body`` for ``FEMinterface.LoadFromFile(path)`` (``path`` ends in ``.hdf5``)."""
    path = Path(path)
    if path.suffix.lower() != ".hdf5":
        raise ValueError(f"{str(path)!r}: Exudyn's LoadFromFile reads HDF5 only from a name ending "
                         "in .hdf5")
    data = fem_data(body)
    with h5_written(path, h5_bound(_arrays(data))) as f:
        for k, v in data.items():
            _put(f, k, v)
    return path
