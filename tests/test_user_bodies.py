"""A user's own body (issue 59): a CAD file or a mesh file and a spec, reduced as the built-in
bodies are.

The built-in axle box (geometry/axlebox.py) is written by gmsh as STEP and as BREP in
millimetres, and its mesh by meshio as Abaqus ``.inp`` (with node sets) and gmsh ``.msh``; each
read back through ``axlebox bodies build --geometry|--mesh FILE --spec SPEC`` with its interfaces
given by place (a cylinder, boxes, a point's neighbourhood) or by the file's sets, and its
free-free and Craig-Bampton frequencies compared with the built-in path's at the same mesh size:
within 0.5 % (issue 59's figure; a CAD round trip meshes the same solid again, a mesh round trip
is the same mesh).  The built-in wheelset goes the same way through ``axlebox bodies template``,
the frame into the car.  A bar made by another CAD kernel (cadquery's OCP) meets Euler-Bernoulli.
Bad geometry is refused in one line naming the file and what is wrong.
"""
import meshio
import numpy as np
import pytest

from axlebox._params import ParameterError
from axlebox.geometry import axlebox as ab_geometry
from axlebox.geometry import mesh as gmesh
from axlebox.pipelines import cli
from axlebox.pipelines.bodies import BODIES, build_body, build_user_body, car_interfaces, write_template

H = BODIES["axlebox"].coarse_mesh_size         # 0.04 m: the demo's
N_REF = 12
P = ab_geometry.AxleboxParams()


def _spec(path, interfaces: dict, kind="axlebox", unit="file", extra=""):
    lines = [f'[body]\nkind = "{kind}"\nunit = "{unit}"\n{extra}', f"[mesh]\nsize = {H}\n",
             f"[reduction]\nmodes = 12\nn_reference = {N_REF}\n"]
    for name, entry in interfaces.items():
        lines.append(f"[interfaces.{name}]\n" + "".join(f"{k} = {v!r}\n".replace("'", '"')
                                                        for k, v in entry.items()))
    path.write_text("\n".join(lines))
    return path


def _places(scale=1.0):
    """The built-in axle box's interfaces by place (geometry/axlebox.py's own faces), in metres
    times ``scale``: the bore's halves on the cylinder, the seats in flat boxes, the pad near its
    centre."""
    L, r = P.length * scale, P.r_bore * scale
    s0, reach, zs = (P.wing_reach - P.seat_length) * scale, P.wing_reach * scale, P.seat_z * scale
    w = P.wing_width * scale / 2
    top = (P.r_outer + P.pad_height) * scale
    return {"bore_row1": {"cylinder": [0.0, -L / 2, 0.0, 0.0, 1.0, 0.0, r, L / 2]},
            "bore_row2": {"cylinder": [0.0, 0.0, 0.0, 0.0, 1.0, 0.0, r, L / 2]},
            "spring_front": {"box": [s0, -w, zs, reach, w, zs]},
            "spring_rear": {"box": [-reach, -w, zs, -s0, w, zs]},
            "sensor_pad": {"near": [0.0, 0.0, top, P.pad_size * scale]}}


def _write_cad(path, scale=1.0):
    """The built-in axle box as gmsh writes it (STEP in its own unit, millimetres; BREP as is,
    its coordinates times ``scale``)."""
    import gmsh
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("ab")
        ab_geometry.build(P)
        occ = gmsh.model.occ
        if scale != 1.0:
            occ.dilate(occ.getEntities(), 0, 0, 0, scale, scale, scale)
        occ.synchronize()
        gmsh.option.setString("Geometry.OCCTargetUnit", "M" if path.suffix == ".step" else "")
        gmsh.write(str(path))
    finally:
        gmsh.option.setString("Geometry.OCCTargetUnit", "")
        gmsh.finalize()
    return path


@pytest.fixture(scope="module")
def builtin():
    rb, _ = build_body("axlebox", mesh_size=H, n_modes=12, n_reference=N_REF, log=lambda *_: None)
    return rb


def _close(rb, ref, tol=5e-3):
    f, g = rb.frequencies_hz[:N_REF], ref.frequencies_hz[:N_REF]
    assert np.abs(f / g - 1).max() < tol, (f, g)
    f, g = rb.reference_frequencies_hz, ref.reference_frequencies_hz
    assert np.abs(f / g - 1).max() < tol, (f, g)
    assert rb.mass == pytest.approx(ref.mass, rel=1e-3)
    assert set(rb.nodes) == set(ref.nodes)


def test_a_step_of_the_builtin_axle_box_has_its_frequencies(tmp_path, builtin, capsys):
    step = _write_cad(tmp_path / "ab.step")
    spec = _spec(tmp_path / "my_box.toml", _places())
    assert cli.main(["bodies", "build", "--geometry", str(step), "--spec", str(spec), "--out",
                     str(tmp_path / "out")]) == 0
    from axlebox.fem import bodyfile
    rb = bodyfile.read(tmp_path / "out" / "my_box.h5")
    _close(rb, builtin)
    for name in ("bore_row1", "bore_row2"):           # masters at the selected bore halves' centroids
        y = rb.nodes[name]["position"][1]
        assert abs(abs(y) - P.length / 4) < 0.1 * P.length
    # its exports for other multibody codes and its mode-shape report, as a built-in body's
    out = tmp_path / "out"
    assert cli.main(["bodies", "export", str(out / "my_box.h5"), "--format", "exudyn", "--out",
                     str(tmp_path / "my_box.hdf5")]) == 0
    assert cli.main(["bodies", "export", str(out / "my_box.h5"), "--format", "mbdyn", "--out", str(out)]) == 0
    assert (tmp_path / "my_box.hdf5").stat().st_size > 0 and (out / "my_box.fem").stat().st_size > 0
    assert cli.main(["bodies", "report", str(out / "my_box.h5"), "--out", str(tmp_path / "modes")]) == 0
    assert (tmp_path / "modes" / "index.html").is_file()
    # the same file and spec again: kept, not rebuilt
    capsys.readouterr()
    build_user_body(spec, geometry=step, out_dir=tmp_path / "out")
    assert "is up to date" in capsys.readouterr().out


def test_a_brep_in_millimetres_reads_with_its_declared_unit_and_is_refused_as_metres(tmp_path, builtin,
                                                                                   capsys):
    brep = _write_cad(tmp_path / "ab_mm.brep", scale=1e3)
    spec = _spec(tmp_path / "mm.toml", _places(), unit="mm")
    rb, _ = build_user_body(spec, geometry=brep, out_dir=tmp_path / "out", log=lambda *_: None)
    _close(rb, builtin)
    # declared as metres: the places (in metres) select nothing, so select by place in mm, and
    # the size gives it away
    wrong = _spec(tmp_path / "wrong.toml", _places(1e3), unit="m")
    assert cli.main(["bodies", "build", "--geometry", str(brep), "--spec", str(wrong), "--out",
                     str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "ab_mm.brep" in err and "millimetres" in err, err
    # and an expected mass catches it first
    heavy = _spec(tmp_path / "heavy.toml", _places(1e3), unit="m", extra="mass_kg = 40.0\n")
    assert cli.main(["bodies", "build", "--geometry", str(brep), "--spec", str(heavy), "--out",
                     str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert "body.mass_kg = 40" in err and "unit" in err, err


def _builtin_mesh():
    return gmesh.mesh_model("axlebox", ab_geometry.build, P, H)


@pytest.mark.parametrize("suffix", [".inp", ".msh"])
def test_the_builtin_mesh_through_a_mesh_file_has_its_frequencies(tmp_path, builtin, suffix):
    """Abaqus: the interfaces as node sets of the file; gmsh: by place."""
    msh = _builtin_mesh()
    cells = [("tetra10", msh.cells)]
    path = tmp_path / f"ab{suffix}"
    if suffix == ".inp":
        sets = {name: msh.group_nodes(name) for name in msh.groups}
        meshio.Mesh(msh.points, cells, point_sets=sets).write(path)
        places = {name: {"name": name} for name in sets}
    else:
        meshio.Mesh(msh.points, cells).write(path, file_format="gmsh22", binary=False)
        places = _places()
    spec = _spec(tmp_path / "m.toml", places)
    rb, _ = build_user_body(spec, mesh_file=path, out_dir=tmp_path / "out", log=lambda *_: None)
    _close(rb, builtin, tol=1e-6 if suffix == ".inp" else 5e-3)


def test_linear_tetrahedra_are_raised_to_quadratic(tmp_path):
    """The built-in mesh's corners alone (tet4), raised: every element kept, the mass the tets'
    volumes' (closed form), and the free-free frequencies scikit-fem's own quadratic element gives
    on the linear mesh (the raised nodes are its edge DOFs): 1e-6."""
    import scipy.sparse.linalg as sla
    from skfem import Basis, BilinearForm, ElementTetP2, ElementVector, MeshTet1
    from skfem.helpers import dot
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    from axlebox.fem.assembly import STEEL
    msh = _builtin_mesh()
    corners = msh.cells[:, :4]
    used = np.unique(corners)
    index = np.full(len(msh.points), -1)
    index[used] = np.arange(len(used))
    pts, tet4 = msh.points[used], index[corners]
    path = tmp_path / "ab4.vtu"
    meshio.Mesh(pts, [("tetra", tet4)]).write(path)
    places = _places()
    for name in ("bore_row1", "bore_row2"):     # the edges' middles lie on the chords: 1.7 mm inside
        places[name]["tol"] = 3e-3
    rb, _ = build_user_body(_spec(tmp_path / "lin.toml", places), mesh_file=path, out_dir=tmp_path / "out",
                            log=lambda *_: None)
    assert rb.meta["n_cells"] == len(msh.cells)
    e = pts[tet4]
    d = e[:, 1:] - e[:, :1]
    volume = np.abs(np.einsum("ij,ij->i", np.cross(d[:, 0], d[:, 1]), d[:, 2])).sum() / 6
    assert rb.mass == pytest.approx(STEEL.rho * volume, rel=1e-9)
    basis = Basis(MeshTet1(pts.T.copy(), tet4.T.copy()), ElementVector(ElementTetP2()), intorder=4)
    K = linear_elasticity(*lame_parameters(STEEL.E, STEEL.nu)).assemble(basis)
    M = BilinearForm(lambda u, v, w: STEEL.rho * dot(u, v)).assemble(basis)
    lam = np.sort(sla.eigsh(K, 6 + N_REF, M, sigma=-(2 * np.pi * 100.0) ** 2, which="LM")[0])
    f = np.sqrt(np.abs(lam[6:])) / (2 * np.pi)
    assert np.abs(rb.reference_frequencies_hz / f - 1).max() < 1e-6, (rb.reference_frequencies_hz, f)


def _refused(capsys, *args) -> str:
    assert cli.main(["bodies", "build", *args]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    return err


def test_bad_geometry_is_refused_in_one_line(tmp_path, capsys):
    import gmsh
    step = _write_cad(tmp_path / "ab.step")
    out = str(tmp_path / "out")
    places = _places()
    # an interface that selects nothing: its name and what it looked for
    spec = _spec(tmp_path / "a.toml", {**places, "spring_front": {"box": [5.0, 5.0, 5.0, 6.0, 6.0, 6.0]}})
    err = _refused(capsys, "--geometry", str(step), "--spec", str(spec), "--out", out)
    assert "ab.step" in err and "'spring_front' selects nothing" in err and "box [5.0" in err
    # two interfaces selecting the same surface
    spec = _spec(tmp_path / "b.toml", {**places, "bore_row2": {"cylinder": [0.0, -0.1, 0.0, 0.0, 1.0, 0.0,
                                                                            P.r_bore, P.length]}})
    err = _refused(capsys, "--geometry", str(step), "--spec", str(spec), "--out", out)
    assert "'bore_row1' and 'bore_row2' select the same" in err
    # an interface the car needs that the body lacks: the list of what it has
    less = {k: v for k, v in places.items() if k != "spring_rear"}
    err = _refused(capsys, "--geometry", str(step), "--spec", str(_spec(tmp_path / "c.toml", less)),
                   "--out", out)
    assert "spring_rear missing" in err and "it has bore_row1" in err
    # an interface given two places, or none
    spec = _spec(tmp_path / "d.toml", {**places, "sensor_pad": {"near": [0.0, 0.0, 0.2, 0.05],
                                                               "box": [0, 0, 0, 1, 1, 1]}})
    err = _refused(capsys, "--geometry", str(step), "--spec", str(spec), "--out", out)
    assert "interfaces.sensor_pad" in err and "exactly one of" in err
    # two separate parts: which they are
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.occ.addBox(0, 0, 0, 0.2, 0.2, 0.2)
        gmsh.model.occ.addBox(0.5, 0, 0, 0.2, 0.2, 0.2)
        gmsh.model.occ.synchronize()
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        gmsh.write(str(tmp_path / "two.step"))
        gmsh.clear()
        gmsh.model.occ.addRectangle(0, 0, 0, 0.2, 0.2)          # a face alone: no solid
        gmsh.model.occ.synchronize()
        gmsh.write(str(tmp_path / "sheet.step"))
    finally:
        gmsh.option.setString("Geometry.OCCTargetUnit", "")
        gmsh.finalize()
    one = _spec(tmp_path / "e.toml", {"end": {"box": [-0.01, -0.01, -0.01, 0.01, 0.21, 0.21]}},
                kind="flexible")
    err = _refused(capsys, "--geometry", str(tmp_path / "two.step"), "--spec", str(one), "--out", out)
    assert "two.step" in err and "2 separate parts" in err and "part 2:" in err
    # a STEP gmsh cannot heal into a closed solid
    err = _refused(capsys, "--geometry", str(tmp_path / "sheet.step"), "--spec", str(one), "--out", out)
    assert "sheet.step" in err and "closed solid" in err
    # a mesh without volume elements; hexahedra
    tri = tmp_path / "skin.vtu"
    meshio.Mesh(np.eye(3), [("triangle", np.array([[0, 1, 2]]))]).write(tri)
    err = _refused(capsys, "--mesh", str(tri), "--spec", str(one), "--out", out)
    assert "skin.vtu" in err and "no volume elements" in err
    hexa = tmp_path / "brick.vtu"
    pts = np.array([[i, j, k] for k in (0, 1) for j in (0, 1) for i in (0, 1)], float) * 0.1
    meshio.Mesh(pts, [("hexahedron", np.array([[0, 1, 3, 2, 4, 5, 7, 6]]))]).write(hexa)
    err = _refused(capsys, "--mesh", str(hexa), "--spec", str(one), "--out", out)
    assert "brick.vtu" in err and "hexahedron" in err and "tetrahedra" in err
    # a file that is not there, a spec field that is not one, the built-in options beside a spec
    err = _refused(capsys, "--geometry", str(tmp_path / "none.step"), "--spec", str(one), "--out", out)
    assert "no such file" in err
    bad = tmp_path / "f.toml"
    bad.write_text('[body]\nkind = "bogie"\n[interfaces.a]\nname = "x"\n')
    err = _refused(capsys, "--geometry", str(step), "--spec", str(bad), "--out", out)
    assert "f.toml" in err and "body.kind = 'bogie'" in err
    err = _refused(capsys, "--geometry", str(step), "--spec", str(one), "--modes", "5", "--out", out)
    assert "--modes is not allowed with --spec" in err


def test_each_car_body_kind_names_the_interfaces_the_car_attaches_to():
    """The car (mbs/vehicle/car.py) attaches to these names; a user body of the kind must have them."""
    assert set(car_interfaces("frame")) == {"primary_1_L", "primary_1_R", "primary_2_L", "primary_2_R",
                                            "secondary_L", "secondary_R", "traction_centre"}
    assert {"bore_row1", "bore_row2", "spring_front", "spring_rear"} <= set(car_interfaces("axlebox"))
    assert {f"journal_{s}_row{r}" for s in "LR" for r in (1, 2)} <= set(car_interfaces("wheelset"))


def _frame_places():
    """The built-in frame's interfaces by place (geometry/frame.py's own faces)."""
    from axlebox.geometry import frame as fr_geometry
    p = fr_geometry.FrameParams()
    h, b, ss = p.side_beam_height, p.side_beam_width, p.seat_size
    zb, zt = -h / 2 - p.pad, h / 2 + p.pad
    out = {}
    for axle, x in zip(fr_geometry.AXLES, (p.wheelbase / 2, -p.wheelbase / 2)):
        for side, s in zip(fr_geometry.SIDES, (1, -1)):
            y = s * p.side_beam_y
            out[f"primary_{axle}_{side}"] = {"box": [x - ss / 2, y - ss / 2, zb, x + ss / 2, y + ss / 2, zb]}
    for side, s in zip(fr_geometry.SIDES, (1, -1)):
        y = s * p.side_beam_y
        out[f"secondary_{side}"] = {"box": [-p.side_beam_length / 2, y - b / 2, zt, p.side_beam_length / 2,
                                            y + b / 2, zt]}
    out["traction_centre"] = {"box": [-p.cross_beam_x, -0.15, -h / 2, p.cross_beam_x, 0.15, -h / 2]}
    return out


def test_the_car_runs_on_a_frame_of_your_own(tmp_path, capsys):
    """The built-in frame as STEP, its interfaces by box, reduced through the user's path and put
    in the car as ``bodies.frame``: the statics converge and the bearings couple (a short run of
    the validation case), and a frame without a traction centre is refused in one line."""
    from axlebox import configs
    from axlebox._cache import cache_dir
    from axlebox.fem import bodyfile
    from axlebox.mbs.solver import integrate
    from axlebox.pipelines import simulate as psim
    places = _frame_places()
    write_template("frame", tmp_path)               # its STEP; the spec here is a user's own boxes
    spec = tmp_path / "my_frame.toml"
    spec.write_text(_spec(tmp_path / "x.toml", places, kind="frame").read_text()
                    .replace(f"size = {H}", f"size = {BODIES['frame'].coarse_mesh_size}")
                    .replace(f"n_reference = {N_REF}", "n_reference = 0"))     # modes = 12, as the car's
    rb, path = build_user_body(spec, geometry=tmp_path / "frame.step", out_dir=tmp_path, log=lambda *_: None)
    # the built-in frame as the car builds it (cached by the car's other tests)
    ref, _ = build_body("frame", mesh_size=BODIES["frame"].coarse_mesh_size, n_modes=12, n_reference=0,
                        out_dir=cache_dir("bodies", "coarse-12"), log=lambda *_: None)
    assert rb.mass == pytest.approx(ref.mass, rel=1e-3)
    assert np.abs(rb.frequencies_hz[:6] / ref.frequencies_hz[:6] - 1).max() < 5e-3
    cfg = psim.load_config(configs.path("validation_48kmh"), duration=0.01,
                           overrides={"bodies": {"frame": str(path), "flexible": ["frame1"]}})
    model, y0 = psim.build_model(cfg, log=lambda *_: None)
    run = integrate.simulate(model, 0.01, cfg.settings(), y0=y0)
    assert run.ok, run.message
    assert np.isfinite(run.y_end).all()
    # a frame that lacks an interface the car attaches to: refused, naming what it has
    bare = bodyfile.read(path)
    del bare.nodes["traction_centre"]
    bare_path = bodyfile.write(bare, tmp_path / "bare.h5")
    with pytest.raises(ParameterError) as err:
        psim.reduced_bodies(psim.load_config(configs.path("validation_48kmh"), duration=0.01,
                                             overrides={"bodies": {"frame": str(bare_path)}}))
    assert "traction_centre" in str(err.value) and "it has primary_1_L" in str(err.value)


# cos(bL) cosh(bL) = 1 (Blevins, Formulas for Natural Frequency and Mode Shape, table 8-1, free-free beam)
BETA_L = np.array([4.73004074, 7.85320462, 10.99560784])


def test_a_step_from_another_cad_kernel_is_a_free_free_beam(tmp_path):
    """A steel bar 2000 x 40 x 60 mm made by cadquery's kernel (OCP: OpenCASCADE 8, not gmsh's
    own) and written as STEP in millimetres, its unit read from the file: its first five free-free
    frequencies, the two bending planes' (the 40 mm one first) interleaved, within 2 % of
    Euler-Bernoulli's (L / depth >= 33: shear and rotary inertia lower them by under 1 %, the
    P2 mesh at 20 mm raises them by less; tests/test_beam.py is the same bar through gmsh)."""
    pytest.importorskip("OCP", reason="cadquery-ocp (the test extra) is not installed")
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.Interface import Interface_Static
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer
    L, b, h = 2000.0, 40.0, 60.0                       # mm
    writer = STEPControl_Writer()
    Interface_Static.SetCVal_s("write.step.unit", "MM")
    writer.Transfer(BRepPrimAPI_MakeBox(L, b, h).Shape(), STEPControl_AsIs)
    step = tmp_path / "bar.step"
    assert writer.Write(str(step)) == IFSelect_RetDone
    assert "SI_UNIT(.MILLI.,.METRE.)" in step.read_text()
    E, rho, nu = 2.1e11, 7850.0, 0.3
    spec = tmp_path / "bar.toml"
    spec.write_text(f'[body]\nkind = "flexible"\n[material]\nE = {E}\nnu = {nu}\nrho = {rho}\n'
                    '[mesh]\nsize = 0.02\n[reduction]\nmodes = 6\nn_reference = 6\n'
                    '[interfaces.end_a]\nbox = [0, 0, 0, 0, 0.04, 0.06]\n'
                    '[interfaces.end_b]\nbox = [2, 0, 0, 2, 0.04, 0.06]\n')
    rb, _ = build_user_body(spec, geometry=step, out_dir=tmp_path / "out", log=lambda *_: None)
    Lm, bm, hm = L / 1e3, b / 1e3, h / 1e3
    assert rb.mass == pytest.approx(rho * Lm * bm * hm, rel=1e-9)
    bending = [BETA_L ** 2 / (2 * np.pi * Lm ** 2) * np.sqrt(E * (d * w ** 3 / 12) / (rho * bm * hm))
               for w, d in ((bm, hm), (hm, bm))]
    exact = np.sort(np.concatenate(bending))[:5]
    f = rb.reference_frequencies_hz[:5]
    np.testing.assert_allclose(f, exact, rtol=0.02)


def test_the_builtin_wheelset_as_a_template_of_your_own_is_the_builtin_wheelset(tmp_path, capsys):
    """``axlebox bodies template --body wheelset``: the built-in wheelset as STEP and the spec that
    builds it again (each interface by the box around the built-in surface, the gear rim by its
    cylinder, at the built-in reference points), built through the user's path at the car's mesh:
    free-free and Craig-Bampton frequencies within 0.5 % of the built-in path (issue 59's figure),
    the mass within 1e-3, the master nodes where the built-in body has them."""
    out = tmp_path / "tpl"
    assert cli.main(["bodies", "template", "--body", "wheelset", "--out", str(out)]) == 0
    assert f"wrote {out / 'wheelset.step'}" in capsys.readouterr().out
    spec = out / "wheelset.toml"
    spec.write_text(spec.read_text().replace("n_reference = 0", "n_reference = 6"))
    rb, _ = build_user_body(spec, geometry=out / "wheelset.step", out_dir=tmp_path, log=lambda *_: None)
    h = BODIES["wheelset"].coarse_mesh_size
    ref, _ = build_body("wheelset", mesh_size=h, n_modes=12, n_reference=6, log=lambda *_: None)
    assert rb.mass == pytest.approx(ref.mass, rel=1e-3)
    for f, g in ((rb.reference_frequencies_hz, ref.reference_frequencies_hz),
                 (rb.frequencies_hz[:12], ref.frequencies_hz[:12])):
        assert np.abs(f / g - 1).max() < 5e-3, (f, g)
    assert set(rb.nodes) == set(ref.nodes) == set(car_interfaces("wheelset"))
    for name in rb.nodes:
        assert np.allclose(rb.nodes[name]["position"], ref.nodes[name]["position"], atol=2e-3), name
    assert np.allclose(ref.nodes["gear"]["position"][[0, 2]], 0.0, atol=1e-4)     # the whole rim: on the axle
    # a template at a mesh size no spec takes: refused in one line, nothing written
    assert cli.main(["bodies", "template", "--body", "frame", "--mesh-size", "-1", "--out",
                     str(tmp_path / "no")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "mesh.size = -1.0 is not allowed" in err, err
    assert not (tmp_path / "no").exists()
