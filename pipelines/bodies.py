"""Build modal bodies from geometry: gmsh -> scikit-fem -> Guyan / Craig-Bampton -> HDF5."""
from __future__ import annotations

import dataclasses
import hashlib
import json
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np

from axlebox._cache import package_dir, source_hash
from axlebox._params import ParameterError, number
from axlebox.fem import assembly, bodyfile, eigen, interfaces
from axlebox.fem.body import make_body
from axlebox.fem.reduction import METHODS
from axlebox.geometry import axlebox, frame, mesh, wheelset


@dataclass(frozen=True)
class BodySpec:
    """How to build one body: geometry, default mesh size, couplings, master positions."""

    params: type
    build: Callable
    mesh_size: float                       # m, the default ("default mesh")
    coarse_mesh_size: float                # m, used by ``axlebox demo``
    couplings: Callable                    # params -> {surface: "rbe2" | "rbe3"}
    positions: Callable                    # params -> {surface: (3,)}


def _ws_couplings(p):
    # RBE3 everywhere by default: an RBE2 spider on a 160 mm journal stiffens the
    # axle ends and raises the third bending pair by ~1.6 %; RBE3 adds no stiffness
    c = {f"journal_{s}_{r}": "rbe3" for s in wheelset.SIDES for r in ("row1", "row2")}
    c.update({f"tread_{s}": "rbe3" for s in wheelset.SIDES})
    if p.r_gear > 0:
        c["gear"] = "rbe3"
    return c


def _ws_positions(p):
    out = {}
    for s in wheelset.SIDES:
        sg = p.side_sign(s)
        q = p.journal_length / 4
        out[f"journal_{s}_row1"] = (0.0, sg * (p.journal_center - q), 0.0)
        out[f"journal_{s}_row2"] = (0.0, sg * (p.journal_center + q), 0.0)
        # nominal wheel-rail contact point: taping line, bottom of the wheel
        out[f"tread_{s}"] = (0.0, sg * (p.back_to_back / 2 + p.taping_offset), -p.r_wheel)
    return out


def _ab_couplings(p):
    # RBE3 on the bore: an RBE2 spider would make the housing ring rigid and
    # roughly double its free-free frequencies; the bearing cup is a separate part
    return {"bore_row1": "rbe3", "bore_row2": "rbe3", "spring_front": "rbe3",
            "spring_rear": "rbe3", "sensor_pad": "rbe3"}


def _ab_positions(p):
    x = p.wing_reach - p.seat_length / 2
    return {"bore_row1": (0.0, -p.length / 4, 0.0), "bore_row2": (0.0, p.length / 4, 0.0),
            "spring_front": (x, 0.0, p.seat_z), "spring_rear": (-x, 0.0, p.seat_z),
            "sensor_pad": (0.0, 0.0, p.r_outer + p.pad_height)}


def _fr_couplings(p):
    c = {f"primary_{a}_{s}": "rbe3" for a in frame.AXLES for s in frame.SIDES}
    c.update({f"secondary_{s}": "rbe3" for s in frame.SIDES})
    c["traction_centre"] = "rbe3"
    return c


BODIES: dict[str, BodySpec] = {
    "wheelset": BodySpec(wheelset.WheelsetParams, wheelset.build, 0.040, 0.060,
                         _ws_couplings, _ws_positions),
    "axlebox": BodySpec(axlebox.AxleboxParams, axlebox.build, 0.025, 0.040,
                        _ab_couplings, _ab_positions),
    "frame": BodySpec(frame.FrameParams, frame.build, 0.050, 0.080,
                      _fr_couplings, lambda p: {}),
}


def make_params(body: str, overrides: dict[str, float] | None = None):
    """Default parameters of ``body`` with ``overrides`` (field -> value) applied and validated."""
    if body not in BODIES:
        raise ParameterError(f"body = {body!r} is not allowed: expected one of {sorted(BODIES)}")
    cls = BODIES[body].params
    names = {f.name: f for f in dataclasses.fields(cls)}
    kw = {}
    for k, v in (overrides or {}).items():
        if k not in names:
            raise ParameterError(f"{cls.__name__}.{k} is not a parameter of the {body}: "
                                 f"expected one of {sorted(names)}")
        kw[k] = v if names[k].type in ("str", str) else number(f"{cls.__name__}.{k}", v)
    return cls(**kw)


def build_body(body: str, *, method: str = "craig-bampton", n_modes: int | None = 20,
               fmax_hz: float | None = None, mesh_size: float | None = None,
               params=None, coupling: str | None = None, damping: tuple = ("modal", 0.01),
               n_reference: int = 30, out_dir: str | Path | None = None, force: bool = False,
               log: Callable[[str], None] = print) -> tuple[bodyfile.ReducedBody, Path | None]:
    """Mesh, assemble, reduce and (if ``out_dir``) write ``<out_dir>/<body>.h5``.

    ``coupling`` forces one interface kind ("rbe2" or "rbe3") on every surface.
    ``n_reference`` full-model free-free modes are computed for comparison (0: none).
    An existing ``<out_dir>/<body>.h5`` built from the same request is kept
    (so an interrupted ``--body all`` resumes where it stopped) unless ``force``.
    """
    if body not in BODIES:
        raise ParameterError(f"body = {body!r} is not allowed: expected one of {sorted(BODIES)}")
    if method not in METHODS:
        raise ParameterError(f"method = {method!r} is not allowed: expected one of {METHODS}")
    if coupling not in (None, "rbe2", "rbe3"):
        raise ParameterError(f"coupling = {coupling!r} is not allowed: expected 'rbe2' or 'rbe3'")
    spec = BODIES[body]
    p = params if params is not None else spec.params()
    h = spec.mesh_size if mesh_size is None else mesh_size
    request = {"body": body, "params": dataclasses.asdict(p), "mesh_size": h, "method": method,
               "n_modes": n_modes, "fmax_hz": fmax_hz, "coupling": coupling,
               "damping": list(damping), "n_reference": n_reference, "sources": sources_hash()}
    if out_dir is not None and not force:
        done = _up_to_date(Path(out_dir) / f"{body}.h5", request)
        if done is not None:
            log(f"{body}: {Path(out_dir) / f'{body}.h5'} is up to date (same request); --force rebuilds")
            return done, Path(out_dir) / f"{body}.h5"
    t0 = time.perf_counter()
    msh = mesh.mesh_model(body, spec.build, p, h)
    fe = assembly.assemble(msh)
    log(f"{body}: mesh {h * 1e3:g} mm, {msh.cells.shape[0]} tet10, {fe.ndof} DOF "
        f"({time.perf_counter() - t0:.1f} s)")
    ref = None
    if n_reference:
        modes = eigen.free_free_modes(fe, n_reference)
        ref = modes.frequencies_hz
        log(f"{body}: full model: six rigid modes below {modes.rigid_frequencies_hz.max():.2e} Hz, "
            f"rigid-span residual {modes.rigid_residual:.1e}")
    kinds = spec.couplings(p)
    if coupling:
        kinds = {k: coupling for k in kinds}
    itf = interfaces.make_interfaces(fe, kinds, spec.positions(p))
    meta = {"body": body, "params": dataclasses.asdict(p), "mesh_size": h,
            "mesh_file": str(msh.path) if msh.path else "", "request": request}
    rb, _ = make_body(body, fe, itf, method=method, n_modes=n_modes, fmax_hz=fmax_hz,
                      damping=damping, reference_hz=ref, meta=meta)
    wall = time.perf_counter() - t0
    rb.meta["build_seconds"] = wall
    log(f"{body}: {method}, {rb.n_modes} elastic modes, mass {rb.mass:.1f} kg ({wall:.1f} s)")
    if ref is not None:
        log(compare_table(rb))
    path = None
    if out_dir is not None:
        path = bodyfile.write(rb, Path(out_dir) / f"{body}.h5")
        log(f"{body}: wrote {path}")
    return rb, path


def sources_hash() -> str:
    """Hash of what a body is made by: every source of geometry/ and fem/, and this module (the
    built-in bodies' interfaces).  Part of every build's request, so a body built before an
    edit or an upgrade (the car's cache of coarse bodies above all) is built again, not kept."""
    h = hashlib.sha256(source_hash([package_dir("geometry"), package_dir("fem")]).encode())
    h.update(Path(__file__).read_bytes())
    return h.hexdigest()[:16]


def _up_to_date(path: Path, request: dict) -> bodyfile.ReducedBody | None:
    if not path.is_file():
        return None
    try:
        body = bodyfile.read(path)
    except bodyfile.BodyFileError:
        return None
    # JSON round trip so tuples and lists compare alike
    same = json.loads(json.dumps(body.meta.get("request"), default=str)) == \
        json.loads(json.dumps(request, default=str))
    return body if same else None


def compare_table(rb: bodyfile.ReducedBody, n: int = 12) -> str:
    """Reduced against full-model free-free frequencies (the reduction error)."""
    ref = rb.reference_frequencies_hz
    lines = [f"  mode   full FE Hz   {rb.method} Hz   error %"]
    for k in range(min(n, len(ref), rb.n_modes)):
        e = 100 * (rb.frequencies_hz[k] - ref[k]) / ref[k]
        lines.append(f"  {k + 1:4d} {ref[k]:12.2f} {rb.frequencies_hz[k]:14.2f} {e:9.3f}")
    return "\n".join(lines)



def car_interfaces(kind: str) -> tuple[str, ...]:
    """The interfaces the car attaches to a body of ``kind`` (mbs/vehicle/car.py): the built-in
    body's own names (:data:`BODIES`), which a user's body of that kind must have too."""
    spec = BODIES[kind]
    return tuple(sorted(spec.couplings(spec.params())))


def write_template(kind: str, out_dir, *, mesh_size: float | None = None, modes: int = 12,
                   n_reference: int = 0) -> tuple[Path, Path]:
    """The built-in ``kind`` as a body of your own would come: ``<out_dir>/<kind>.step`` (its
    solid, in metres) and ``<out_dir>/<kind>.toml`` (its spec, at the car's coarse mesh unless
    ``mesh_size``): every interface the car attaches to by its name, each by the box around the
    built-in surface (the gear rim by its cylinder: a box round it holds the gear's sides too),
    coupled as built in, at the built-in reference point where there is one.  Built through
    :func:`build_user_body` it is the built-in body again (tests/test_user_bodies.py): a
    starting point to edit in CAD and in the spec (``axlebox bodies template``)."""
    import gmsh

    from axlebox.geometry import cad

    from .bodyspec import MeshEntry
    if kind not in BODIES:
        raise ParameterError(f"body = {kind!r} is not allowed: expected one of {sorted(BODIES)}")
    spec = BODIES[kind]
    p = spec.params()
    h = MeshEntry(size=spec.coarse_mesh_size if mesh_size is None else mesh_size).size    # its range
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    couplings, positions = spec.couplings(p), spec.positions(p)
    lines = [f'# the built-in {kind} (axlebox bodies template), as a spec of your own\n'
             f'[body]\nkind = "{kind}"\nname = "my_{kind}"\n',
             f"[mesh]\nsize = {h}\n", f"[reduction]\nmodes = {modes}\nn_reference = {n_reference}\n"]
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add(kind)
        named = spec.build(p)
        gmsh.model.occ.synchronize()
        for name, tags in named.items():
            if kind == "wheelset" and name == "gear":
                s = p.side_sign(p.gear_side)
                y0 = min(s * (p.gear_center - p.gear_width / 2), s * (p.gear_center + p.gear_width / 2))
                place = f"cylinder = {[0.0, round(y0, 9), 0.0, 0.0, 1.0, 0.0, p.r_gear, p.gear_width]}"
            else:
                bb = np.array([gmsh.model.getBoundingBox(2, t) for t in tags])
                place = f"box = {[round(float(v), 6) + 0.0 for v in (*bb[:, :3].min(0), *bb[:, 3:].max(0))]}"
            at = f"\nposition = {[float(v) for v in positions[name]]}" if name in positions else ""
            lines.append(f'[interfaces.{name}]\n{place}\ncoupling = "{couplings[name]}"{at}\n')
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        step = out / f"{kind}.step"
        tmp = step.with_name(step.name + ".part.step")
        with cad.occ_quiet():
            gmsh.write(str(tmp))
        tmp.replace(step)
    finally:
        gmsh.option.setString("Geometry.OCCTargetUnit", "")
        gmsh.finalize()
    toml = out / f"{kind}.toml"
    toml.with_name(toml.name + ".part").write_text("\n".join(lines))
    toml.with_name(toml.name + ".part").replace(toml)
    return step, toml


def build_user_body(spec_path, *, geometry=None, mesh_file=None, out_dir="bodies", force: bool = False,
                    log: Callable[[str], None] = print) -> tuple[bodyfile.ReducedBody, Path]:
    """A user's own part, from a CAD file (``geometry``: STEP, IGES, BREP) or a mesh file
    (``mesh_file``: Abaqus, Nastran, gmsh, Salome MED, VTK), reduced as its spec says
    (pipelines/bodyspec.py) into ``<out_dir>/<name>.h5``, as the built-in bodies are.  An
    existing file built from the same request (file content and spec) is kept unless ``force``."""
    from axlebox.geometry import cad, meshfile

    from . import bodyspec
    if (geometry is None) == (mesh_file is None):
        raise ParameterError("--geometry and --mesh: expected exactly one (a CAD file or a mesh file)")
    spec = bodyspec.load(spec_path)
    b, red = spec.body, spec.reduction
    missing = [n for n in car_interfaces(b.kind) if n not in spec.interfaces] if b.kind in BODIES else []
    if missing:
        raise ParameterError(f"{Path(spec_path).name}: a {b.kind} needs the interfaces the car attaches "
                             f"to: {', '.join(missing)} missing (it has {', '.join(spec.interfaces)})")
    src = Path(geometry if geometry is not None else mesh_file)
    flag = "--geometry" if geometry is not None else "--mesh"
    sha = _sha256(src, flag)
    request = {"source": src.name, "sha256": sha, "spec": _plain(spec), "sources": sources_hash()}
    path = Path(out_dir) / f"{spec.name}.h5"
    if not force:
        done = _up_to_date(path, request)
        if done is not None:
            log(f"{spec.name}: {path} is up to date (same file and spec); --force rebuilds")
            return done, path
    t0 = time.perf_counter()
    sel = spec.selections()
    if geometry is not None:
        source = cad.source(geometry, b.unit, sel, spec.material.rho, b.mass_kg, sha)
        msh = mesh.mesh_model(f"cad-{spec.name}", cad.build, source, spec.mesh.size, order=spec.mesh.order)
        if msh.cells.shape[1] == 4:
            pts, cells = meshfile.raise_order(msh.points, msh.cells)
            msh = mesh.MeshData(pts, cells, {k: _raised(v, msh.cells, cells) for k, v in msh.groups.items()})
    else:
        scale = cad.UNITS["m" if b.unit == "file" else b.unit]
        msh = meshfile.read(mesh_file, scale, sel)
    _check_shared(msh, src.name)
    fe = assembly.assemble(msh, spec.material)
    ones = np.ones(len(fe.points))
    cad.check_size(src.name, float(np.ptp(fe.points, axis=0).max()), float(ones @ (fe.scalar_mass() @ ones)),
                   b.mass_kg, b.unit)
    log(f"{spec.name}: {msh.cells.shape[0]} tet10, {fe.ndof} DOF ({time.perf_counter() - t0:.1f} s)")
    pieces = eigen.body_parts(fe)
    if len(pieces) > 1:
        raise ParameterError(f"{src.name}: the body is {len(pieces)} separate parts ({6 * len(pieces)} "
                             f"rigid modes, expected 6): {eigen.describe(fe, pieces)}; expected one "
                             "connected solid")
    ref = eigen.free_free_modes(fe, red.n_reference).frequencies_hz if red.n_reference else None
    itf = interfaces.make_interfaces(fe, spec.couplings(), spec.positions())
    meta = {"body": b.kind, "source": str(src), "request": request, "mesh_size": spec.mesh.size}
    n_modes = None if red.method == "guyan" or red.fmax_hz > 0 else red.modes
    rb, _ = make_body(spec.name, fe, itf, method=red.method, n_modes=n_modes,
                      fmax_hz=red.fmax_hz or None, damping=("modal", red.zeta), reference_hz=ref,
                      meta=meta)
    rb.meta["build_seconds"] = time.perf_counter() - t0
    log(f"{spec.name}: {red.method}, {rb.n_modes} elastic modes, mass {rb.mass:.1f} kg "
        f"({rb.meta['build_seconds']:.1f} s)")
    if ref is not None:
        log(compare_table(rb))
    path = bodyfile.write(rb, path)
    log(f"{spec.name}: wrote {path}")
    return rb, path


def _sha256(path: Path, flag: str) -> str:
    if not Path(path).is_file():
        raise ParameterError(f"{flag} = {str(path)!r} is not allowed: no such file")
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def _plain(spec) -> dict:
    d = dataclasses.asdict(spec)
    d.pop("path")
    return d


def _raised(facets3: np.ndarray, tet4: np.ndarray, tet10: np.ndarray) -> np.ndarray:
    """Triangle facets of a linear mesh as triangle6 of its raised mesh (the edges' new nodes)."""
    from axlebox.geometry.meshfile import boundary
    faces, _ = boundary(tet10)
    key = {tuple(sorted(f[:3])): f for f in faces}
    return np.array([key[tuple(sorted(f[:3]))] for f in facets3])


def _check_shared(msh: mesh.MeshData, fname: str) -> None:
    """Refuse two interfaces that select the same piece of surface (overlapping selections).
    Adjacent ones share the nodes of their common edge, as the built-in bodies' do: those couple
    to the first (fem/interfaces.condense)."""
    keys = {n: {tuple(sorted(f[:3])) for f in facets} for n, facets in msh.groups.items()}
    names = list(keys)
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            both = keys[a] & keys[b]
            if both:
                at = msh.points[list(min(both))].mean(axis=0)
                raise ParameterError(f"{fname}: interfaces {a!r} and {b!r} select the same {len(both)} "
                                     f"facets (the first at {np.round(at, 4).tolist()} m): expected "
                                     "separate surfaces")
