"""``axlebox bodies export``: a reduced body for Exudyn and for MBDyn (issue 22, items 2-3).

Exudyn: the exported file is loaded by Exudyn itself (``FEMinterface.LoadFromFile``), built into
``ObjectFFRFreducedOrderInterface`` and integrated; nothing of ours is handed over in memory.
MBDyn: the ``.fem`` file is read back by a reader that follows MBDyn's ``ReadModal``; a run of
MBDyn itself where the ``mbdyn`` binary is on PATH.
"""
import contextlib
import io
import shutil
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

from axlebox.fem import bodyfile, export_mbdyn
from axlebox.pipelines.cli import main

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "docs" / "exudyn_example.py"


def cli(argv) -> tuple[int, str]:
    """``axlebox ARGV`` in this process: exit status and stderr."""
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            rc = main([str(a) for a in argv])
        except SystemExit as e:              # argparse
            rc = e.code
    return rc, err.getvalue()


def tiny_body(name: str = "tet", n: int = 6) -> bodyfile.ReducedBody:
    """One straight tet10 of steel (10 cm), its ``n`` lowest free-free elastic modes from the full
    FE eigenproblem: a complete reduced body in milliseconds, for the refusal and fuzz tests."""
    from scipy.linalg import eigh

    from axlebox.fem import assembly, massprops
    from axlebox.geometry.mesh import MeshData
    c = 0.1 * np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    pts = np.vstack([c] + [0.5 * (c[a] + c[b]) for a, b in ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))])
    fe = assembly.assemble(MeshData(pts, np.arange(10)[None]))
    perm = fe.dofs.ravel()
    w2, V = eigh(fe.K[perm][:, perm].toarray(), fe.M[perm][:, perm].toarray())
    w2, V = w2[6:6 + n], V[:, 6:6 + n]                     # past the six rigid-body modes
    mp = massprops.from_model(fe)
    w = np.sqrt(w2)
    nodes = {f"corner_{i}": {"position": c[i], "shapes": np.vstack([V[3 * i:3 * i + 3], np.zeros((3, n))]),
                             "coupling": "rbe2"} for i in range(4)}
    return bodyfile.ReducedBody(
        name=name, method="guyan", mass=mp.mass, center_of_mass=mp.center_of_mass, inertia=mp.inertia,
        frequencies_hz=w / (2 * np.pi), reduced_mass=np.eye(n), reduced_stiffness=np.diag(w2),
        reduced_damping=np.diag(0.02 * w), nodes=nodes, mesh_points=pts, mesh_cells=np.arange(10)[None],
        mode_shapes=V.T.reshape(n, 10, 3), meta={"material": vars(assembly.STEEL)})


@pytest.fixture(scope="module")
def wheelset(tmp_path_factory):
    """The coarse wheelset (70 mm mesh, Craig-Bampton with 6 fixed-interface modes: 42 free-free
    elastic modes up to 15.7 kHz) and its Exudyn export, made by the command line."""
    from axlebox.pipelines.bodies import build_body
    out = tmp_path_factory.mktemp("export")
    body, path = build_body("wheelset", mesh_size=0.07, n_modes=6, n_reference=0, out_dir=out,
                            log=lambda s: None)
    rc, err = cli(["bodies", "export", path, "--format", "exudyn", "--out", out / "wheelset.hdf5"])
    assert rc == 0, err
    return body, path, out / "wheelset.hdf5"


# ------------------------------------------------------------------------------------------ Exudyn


def test_exudyn_frequencies_are_the_body_files(wheelset):
    """Exudyn's docs, "Module: FEM": ``FEMinterface.LoadFromFile`` (HDF5 by the ``.hdf5`` ending)
    and ``ObjectFFRFreducedOrderInterface``, whose reduced mass and stiffness are
    ``Psi^T M Psi`` and ``Psi^T K Psi`` of the file's mode basis: their free-free frequencies are
    the body file's (1e-6 relative)."""
    pytest.importorskip("exudyn")
    from exudyn.FEM import FEMinterface, ObjectFFRFreducedOrderInterface
    body, _, hdf5 = wheelset
    fem = FEMinterface()
    fem.LoadFromFile(str(hdf5))
    cms = ObjectFFRFreducedOrderInterface(fem)
    M, K = np.asarray(cms.massMatrixReduced), np.asarray(cms.stiffnessMatrixReduced)
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(M, K)).real)
    f = np.sqrt(w2) / (2 * np.pi)
    rel = np.abs(f / body.frequencies_hz - 1).max()
    print(f"Exudyn vs body file: {len(f)} modes, max relative frequency difference {rel:.1e}")
    assert len(f) == body.n_modes and rel < 1e-6
    assert np.asarray(fem.nodes["Position"]).shape == body.mesh_points.shape
    assert fem.modeBasis["type"] == "NormalModes" and fem.modeBasis["matrix"].shape == (body.mesh_points.size,
                                                                                       body.n_modes)
    assert set(fem.metaData["interfaces"]) == set(body.nodes)


def test_exudyn_example_runs_on_the_export(wheelset):
    """docs/exudyn_example.py (Exudyn's ``FEMinterface`` / ``ObjectFFRFreducedOrderInterface`` /
    ``AddObjectFFRFreducedOrder``, "Module: FEM" in Exudyn's docs) loads the exported file,
    assembles the system and prints the frequencies next to the body file's."""
    pytest.importorskip("exudyn")
    body, _, hdf5 = wheelset
    r = subprocess.run([sys.executable, str(EXAMPLE), str(hdf5)], capture_output=True, text=True,
                       timeout=300, cwd=ROOT)
    assert r.returncode == 0, r.stderr[-2000:]
    rows = [ln.split() for ln in r.stdout.splitlines() if ln.startswith("mode")]
    assert len(rows) == body.n_modes
    assert all(a[3] == a[7] for a in rows), "Exudyn's and the body file's frequencies differ in print"
    assert "assembled" in r.stdout and "tread_L" in r.stdout


# the load history on the tread_L master node: Hann-windowed sines, off the resonances
T_LOAD, FX, FREQ_X, FZ, FREQ_Z = 0.05, 1.0e4, 87.0, 2.0e4, 105.0


def _force(t: float) -> np.ndarray:
    if not 0.0 <= t < T_LOAD:
        return np.zeros(3)
    return np.sin(np.pi * t / T_LOAD) ** 2 * np.array([FX * np.sin(2 * np.pi * FREQ_X * t), 0.0,
                                                       FZ * np.sin(2 * np.pi * FREQ_Z * t)])


def _exudyn_run(hdf5: Path, node: str, h: float, t_end: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The exported body in Exudyn, free, at rest, its modal damping from the file; the force on the
    master node ``node`` (position and shapes from the file's metaData) applied as its generalized
    forces: F on the frame, (A (x_m + S q)) x F as a torque, S^T A^T F on the modes."""
    import importlib.util

    import exudyn as exu
    import exudyn.itemInterface as eii
    spec = importlib.util.spec_from_file_location("exudyn_example", EXAMPLE)
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    fem, cms, meta = example.load(str(hdf5))
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ids = example.add_body(mbs, fem, cms)
    n_ref, n_gen = ids["nRigidBody"], ids["nGenericODE2"]
    xm = np.asarray(meta["interfaces"][node]["position"])
    S = np.asarray(meta["interfaces"][node]["shapes"])[:3]
    m_ref = mbs.AddMarker(eii.MarkerNodeRigid(nodeNumber=n_ref))
    l_force = mbs.AddLoad(eii.LoadForceVector(markerNumber=m_ref))
    l_torque = mbs.AddLoad(eii.LoadTorqueVector(markerNumber=m_ref))
    l_modes = [mbs.AddLoad(eii.LoadCoordinate(markerNumber=mbs.AddMarker(
        eii.MarkerNodeCoordinate(nodeNumber=n_gen, coordinate=k)))) for k in range(S.shape[1])]
    OV = exu.OutputVariableType

    def prestep(mbs, t):                     # Exudyn calls it with t_{n+1}, the time it solves for
        A = np.asarray(mbs.GetNodeOutput(n_ref, OV.RotationMatrix)).reshape(3, 3)
        q = np.asarray(mbs.GetNodeOutput(n_gen, OV.Coordinates))
        f = _force(t)
        mbs.SetLoadParameter(l_force, "loadVector", f.tolist())
        mbs.SetLoadParameter(l_torque, "loadVector", np.cross(A @ (xm + S @ q), f).tolist())
        for ld, v in zip(l_modes, (S.T @ (A.T @ f)).tolist()):
            mbs.SetLoadParameter(ld, "load", v)
        return True
    mbs.SetPreStepUserFunction(prestep)
    sens = [mbs.AddSensor(eii.SensorNode(nodeNumber=nd, outputVariableType=ov, storeInternal=True,
                                         writeToFile=False))
            for nd, ov in ((n_gen, OV.Coordinates), (n_ref, OV.Position))]
    mbs.Assemble()
    s = exu.SimulationSettings()
    ti = s.timeIntegration
    ti.endTime, ti.numberOfSteps = t_end, int(round(t_end / h))
    ti.generalizedAlpha.spectralRadius = 0.9
    ti.adaptiveStep, ti.verboseMode = False, 0
    s.solution.file.write = False
    s.solution.sensors.writePeriod = 1e-3
    assert exu.SolveDynamic(mbs, s, solverType=exu.DynamicSolverType.GeneralizedAlpha)
    q, r = (np.asarray(mbs.GetSensorStoredData(k)) for k in sens)
    return q[:, 0], q[:, 1:], r[:, 1:]


def _axlebox_run(path: Path, node: str, h: float, t_end: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The body file in axlebox's solver: the same history as Load elements (F0 + A sin(w t + ph) on
    [t_on, t_off)), by sin^2(pi t/T) sin(w t) = sin(w t)/2 - sin((w+W) t)/4 - sin((w-W) t)/4."""
    from axlebox.mbs.solver.body import flexible
    from axlebox.mbs.solver.elements import Load
    from axlebox.mbs.solver.integrate import Settings, simulate
    from axlebox.mbs.solver.system import System
    sysm = System(gravity=(0.0, 0.0, 0.0))
    sysm.add_body(flexible("ws", bodyfile.read(path, fields=False)))
    m = sysm.marker("ws", node=node)
    W = 2 * np.pi / T_LOAD
    for axis, F, w in ((0, FX, 2 * np.pi * FREQ_X), (2, FZ, 2 * np.pi * FREQ_Z)):
        for c, om in ((0.5, w), (-0.25, w + W), (-0.25, w - W)):
            A = np.zeros(3)
            A[axis] = c * F
            sysm.add(Load(f"F{axis}_{om:.0f}", m, amplitude=tuple(A), omega=om, t_on=0.0, t_off=T_LOAD))
    model = sysm.assemble()
    run = simulate(model, t_end, Settings(method="galpha", dt=h, rho_inf=0.9, output_rate_hz=1000,
                                          state_rate_hz=1000))
    assert run.ok, run.message
    ip, n = int(model.S.bi[0, 0]), int(model.S.bi[0, 2])
    return run.state_time, run.states[:, ip + 7:ip + 7 + n], run.states[:, ip:ip + 3]


def test_exudyn_response_is_axleboxs(wheelset):
    """Exudyn's ``ObjectFFRFreducedOrder`` (docs: "ObjectFFRFreducedOrder", built by
    ``ObjectFFRFreducedOrderInterface.AddObjectFFRFreducedOrder``; its ``dampingMatrixReduced``)
    built from the exported file alone, under a load history on the tread_L master node, moves as
    axlebox moves the body file: modal coordinates and frame position within 1 %.  Both:
    generalized-alpha, spectral radius 0.9, h = 1e-4 s, 0.1 s (the benchmarks/peer_*.py case,
    shortened)."""
    pytest.importorskip("exudyn")
    _, path, hdf5 = wheelset
    h, t_end = 1e-4, 0.1
    te, qe, re = _exudyn_run(hdf5, "tread_L", h, t_end)
    ta, qa, ra = _axlebox_run(path, "tread_L", h, t_end)
    assert qe.shape == qa.shape and np.allclose(te, ta, atol=1e-9)
    rms = np.sqrt((qe ** 2).mean(0))
    big = np.flatnonzero(rms > 0.01 * rms.max())
    q_rel = np.linalg.norm(qa - qe) / np.linalg.norm(qe)
    per_mode = max(np.linalg.norm(qa[:, k] - qe[:, k]) / np.linalg.norm(qe[:, k]) for k in big)
    r_rel = np.linalg.norm(ra - re) / np.linalg.norm(re)
    print(f"axlebox vs Exudyn: q {q_rel:.2e} (largest per mode {per_mode:.2e}, {len(big)} modes), "
          f"frame position {r_rel:.2e}; max |q| {np.abs(qe).max():.2e}")
    assert np.abs(qe).max() > 1e-6                         # the load did move the modes
    assert q_rel < 0.01 and per_mode < 0.01 and r_rel < 0.01


# ------------------------------------------------------------------------------------------- MBDyn


def test_mbdyn_fem_file_reads_back_exactly(wheelset, tmp_path):
    """MBDyn input manual, "Modal Element" - "FEM File Format" (record groups 1-13 as MBDyn's
    ``ReadModal`` in mbdyn/struct/modal.cc parses them): the ``.fem`` file read back gives the
    body's mass, centre of mass, inertia, modal mass, stiffness and damping and its interface
    nodes' positions and (6, n) shapes, to 1e-12 (``%.17e``: the same doubles)."""
    body, path, _ = wheelset
    rc, err = cli(["bodies", "export", path, "--format", "mbdyn", "--out", tmp_path])
    assert rc == 0, err
    d = export_mbdyn.read(tmp_path / "wheelset.fem")
    n = body.n_modes

    def close(a, b):
        a, b = np.asarray(a, float), np.asarray(b, float)
        return a.shape == b.shape and np.abs(a - b).max() <= 1e-12 * max(1.0, np.abs(b).max())
    assert sorted(d["labels"]) == sorted(body.nodes)
    assert close(d["mass"], body.mass) and close(d["center_of_mass"], body.center_of_mass)
    assert close(d["inertia"], body.inertia)
    assert close(d["mass_matrix"], body.reduced_mass) and close(d["stiffness"], body.reduced_stiffness)
    assert close(d["damping"], body.reduced_damping)
    assert close(d["q0"], np.zeros(n)) and close(d["qd0"], np.zeros(n)) and d["lumped"] is None
    for i, k in enumerate(d["labels"]):
        assert close(d["positions"][i], body.nodes[k]["position"]), k
        assert close(d["shapes"][i], body.nodes[k]["shapes"]), k
    # ReadModal's own expectations of the layout: the header right after its comment line, one
    # '**' line and no blank line before each mode, the record groups in order
    text = (tmp_path / "wheelset.fem").read_text().splitlines()
    groups = [int(ln.split()[3].rstrip(",")) for ln in text if ln.startswith("** RECORD GROUP")]
    assert groups == [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 12, 13]
    i = text.index(next(ln for ln in text if ln.startswith("** RECORD GROUP 1,")))
    assert text[i + 2].split() == ["REV0", str(len(body.nodes)), str(n), "0", "0", "0"]
    assert "" not in text


@pytest.mark.skipif(shutil.which("mbdyn") is None, reason="the mbdyn binary is not on PATH (not "
                    "installable here: no Debian bookworm package, no PyPI package)")
def test_mbdyn_runs_the_exported_body(wheelset, tmp_path):
    """MBDyn itself reads the ``.fem`` file: a free modal element (input manual, "Modal Element":
    ``joint: ..., modal, <modal node>, <modes>, <FEM nodes>, damping from file, "<file>", <interface
    nodes>``) with a force on the tread_L interface node runs 10 steps without error."""
    body, path, _ = wheelset
    fem = tmp_path / "wheelset.fem"
    assert cli(["bodies", "export", path, "--format", "mbdyn", "--out", fem])[0] == 0
    x = [float(v) for v in body.nodes["tread_L"]["position"]]
    (tmp_path / "free.mbd").write_text(f"""
begin: data; problem: initial value; end: data;
begin: initial value;
    initial time: 0.; final time: 1.e-3; time step: 1.e-4;
    method: ms, .6; tolerance: 1.e-6; max iterations: 20;
end: initial value;
begin: control data;
    structural nodes: 2; joints: 1; forces: 1;
end: control data;
begin: nodes;
    structural: 1, modal, null, eye, null, null;
    structural: 2, static, {x[0]!r}, {x[1]!r}, {x[2]!r}, eye, null, null;
end: nodes;
begin: elements;
    joint: 1, modal, 1, {body.n_modes}, {len(body.nodes)}, damping from file, "{fem}",
        1, "tread_L", 2, null;
    force: 1, absolute, 2, position, null, 0., 0., 1., const, 1.e4;
end: elements;
""")
    r = subprocess.run(["mbdyn", "-f", str(tmp_path / "free.mbd"), "-o", str(tmp_path / "free")],
                       capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert r.returncode == 0, (r.stdout[-2000:], r.stderr[-2000:])


# --------------------------------------------------------------------------------------- bad input


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    d = tmp_path_factory.mktemp("tiny")
    return bodyfile.write(tiny_body(), d / "tet.h5")


def test_tiny_body_exports_to_both(tiny, tmp_path):
    """The one-element body the refusal and fuzz tests use is a valid reduced body: both exports
    run (Exudyn's check of its modes against the reassembled matrices included)."""
    for fmt in ("exudyn", "mbdyn"):
        rc, err = cli(["bodies", "export", tiny, "--format", fmt, "--out", tmp_path])
        assert rc == 0, err
    with h5py.File(tmp_path / "tet.hdf5") as f:
        assert f.attrs.get("datatype") is None and f["modeBasis"].attrs["datatype"] == "dict"
        assert f["massMatrix"].attrs["datatype"] == "csr_matrix"
    assert export_mbdyn.read(tmp_path / "tet.fem")["shapes"].shape == (4, 6, 6)


def _not_a_body(tmp: Path, kind: str, tiny: Path) -> Path:
    if kind == "text":
        (tmp / "x.h5").write_text("a text file, not HDF5\n")
    elif kind == "other-hdf5":
        with h5py.File(tmp / "x.h5", "w") as f:
            f.attrs["format"] = "axlebox-result"
            f["time"] = np.arange(3.0)
    elif kind == "no-mesh":                     # a body without mesh and modes: nothing for Exudyn
        b = bodyfile.read(tiny)
        b.mesh_points = b.mesh_cells = b.mode_shapes = None
        bodyfile.write(b, tmp / "x.h5")
    return tmp / "x.h5"                         # "missing": no file there at all


@pytest.mark.parametrize("case,argv,names", [
    ("unknown format", ["--format", "adams", "--out", "{tmp}"], ["--format", "adams", "exudyn"]),
    ("out folder missing", ["--format", "mbdyn", "--out", "{tmp}/nowhere/x.fem"], ["--out", "nowhere"]),
    ("exudyn without .hdf5", ["--format", "exudyn", "--out", "{tmp}/x.h5"], ["--out", ".hdf5"]),
    ("out is the body file", ["--format", "mbdyn", "--out", "{body}"], ["--out", "body file"]),
])
def test_bad_options_exit_2_in_one_line(tiny, tmp_path, case, argv, names):
    """Exit status 2 and exactly one line on stderr naming the option, the value and what is
    allowed (DESIGN.md, "Exit status ... 2 on bad input")."""
    argv = [a.format(tmp=tmp_path, body=tiny) for a in argv]
    rc, err = cli(["bodies", "export", tiny, *argv])
    assert rc == 2 and len(err.strip().splitlines()) == 1 and "Traceback" not in err, (case, err)
    assert all(n in err for n in names), (case, err)


@pytest.mark.parametrize("kind,fmt,names", [
    ("text", "mbdyn", ["not an HDF5 file"]), ("other-hdf5", "exudyn", ["format", "axlebox-result",
                                                                          "axlebox-reduced-body"]),
    ("no-mesh", "exudyn", ["no mesh"]), ("missing", "mbdyn", ["no such file"]),
])
def test_not_a_reduced_body_exits_2_in_one_line(tiny, tmp_path, kind, fmt, names):
    """A file that is not a reduced body (a text file, an HDF5 file of another format, a body
    without the mesh Exudyn needs, no file): BodyFileError, exit 2, one line naming it."""
    src = _not_a_body(tmp_path, kind, tiny)
    rc, err = cli(["bodies", "export", src, "--format", fmt, "--out", tmp_path / "out.hdf5"
                   if fmt == "exudyn" else tmp_path / "out.fem"])
    assert rc == 2 and len(err.strip().splitlines()) == 1 and "Traceback" not in err, (kind, err)
    assert all(n in err for n in names), (kind, err)
    assert not list(tmp_path.glob("out.*")), "nothing is written on a refusal"
