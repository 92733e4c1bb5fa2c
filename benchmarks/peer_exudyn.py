"""The peer side of the free-wheelset benchmark: the shared case (``peer_case.py``) in Exudyn.

Exudyn's ``ObjectFFRFreducedOrder`` (built by ``exudyn.FEM.FEMinterface`` and
``ObjectFFRFreducedOrderInterface``) is fed OUR full M and K (node-wise DOF order)
and OUR kept free-free elastic modes as its mode basis, no rigid modes, so its
modal coordinates are the body file's (same order, same signs) and its reduced
mass and stiffness are I and diag(w^2) by construction; its FFRF inertia terms
are its own, from M, the node positions and the basis.  Damping: the body
file's reduced/damping (modal, diag(2 zeta w)), set as the object's damping matrix.
Integrator: Exudyn's generalized-alpha (spectral radius 0.9, its default;
modified Newton, its default), fixed step h; it enforces the equations at
t_{n+1}, and its load and pre-step functions are called with t_{n+1}.

The load acts on our tread_L RBE3 master node, 33 mm beside and 28 mm below the
centroid of the tread_L nodes.  A force on a MarkerSuperElementPosition with the
RBE3 area weights would act at that centroid and miss the offset's moment: that
changes q by 21 % RMS (torsion 7 %, the bending pair by more than half), so
``load_mode`` chooses how to add it:

* ``master`` (default, fastest): one MarkerSuperElementPosition on the tread_L
  nodes whose weights are chosen so the marker moves exactly like the master
  node (:func:`master_weights`); one force, set once per step;
* ``hybrid``: the force on the area-weighted MarkerSuperElementPosition, the
  offset's moment (A d) x F as a torque on the reference node and, on the modes,
  Theta^T (d x F_local) with Theta our master's rotation rows (20 loads a step);
* ``markers``: force and torque on one MarkerSuperElementRigid with the area
  weights (its rotation is the weighted least-squares rotation of the nodes, as
  in our RBE3): Exudyn's own way, but this marker costs ~0.5 ms per evaluation.

The three agree to 1e-5 in q.  Run: ``python benchmarks/peer_exudyn.py OUT.npz``
(needs ``pip install exudyn``); ``--load-mode``, ``--repeat N`` (best of N timings).
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from peer_case import PeerCase, build_case  # noqa: E402

LOAD_MODES = ("master", "hybrid", "markers", "none")


def _area_weights(case: PeerCase, name: str) -> np.ndarray:
    w = case.interfaces[name]["weights"]
    return w / w.sum()


def master_weights(case: PeerCase, name: str) -> np.ndarray:
    """Weights w on interface ``name``'s nodes with sum w = 1, sum w x_i = the master
    position and sum w_i Psi_i = the master's translation rows of the kept modes:
    the area weights changed as little as possible (least squares) to meet them.
    They range about -3..3 (|w| sums to ~130), exact within the kept modes."""
    itf = case.interfaces[name]
    nodes, n = itf["nodes"], case.n_modes
    w0 = _area_weights(case, name)
    Psi = case.modes.reshape(-1, 3, n)[nodes]                        # (m, 3, n)
    C = np.vstack([np.ones(len(nodes)), case.points[nodes].T, Psi.transpose(1, 2, 0).reshape(3 * n, -1)])
    b = np.concatenate([[1.0], itf["position"], case.body.node(name)[1][:3].ravel()])
    w = w0 + np.linalg.lstsq(C, b - C @ w0, rcond=None)[0]
    res = np.abs(C @ w - b).max() / np.abs(b).max()
    if res > 1e-9:
        raise RuntimeError(f"master weights for {name!r}: residual {res:.1e}")
    return w


def _add_load(exu, eii, mbs, case: PeerCase, obj, n_ref, n_gen, mode: str) -> None:
    """The load history on the tread_L master node, in one of :data:`LOAD_MODES`."""
    name = case.load.interface
    nodes = [int(i) for i in case.interfaces[name]["nodes"]]
    d = case.interfaces[name]["position"] - _area_weights(case, name) @ case.points[nodes]
    F = case.load.scalar
    ROT = exu.OutputVariableType.RotationMatrix

    def rotation():
        return np.asarray(mbs.GetNodeOutput(n_ref, ROT)).reshape(3, 3)

    def position_marker(w):
        return mbs.AddMarker(eii.MarkerSuperElementPosition(
            bodyNumber=obj, meshNodeNumbers=nodes, weightingFactors=np.asarray(w).tolist(),
            visualization=eii.VMarkerSuperElementPosition(show=False)))

    if mode == "master":
        lF = mbs.AddLoad(eii.LoadForceVector(markerNumber=position_marker(master_weights(case, name))))

        def prestep(mbs, t):
            mbs.SetLoadParameter(lF, "loadVector", F(t))
            return True
    elif mode == "hybrid":
        lF = mbs.AddLoad(eii.LoadForceVector(markerNumber=position_marker(_area_weights(case, name))))
        mNode = mbs.AddMarker(eii.MarkerNodeRigid(nodeNumber=n_ref))
        lM = mbs.AddLoad(eii.LoadTorqueVector(markerNumber=mNode))
        Theta = case.body.node(name)[1][3:]                              # (3, n) RBE3 rotation rows
        lq = [mbs.AddLoad(eii.LoadCoordinate(markerNumber=mbs.AddMarker(
            eii.MarkerNodeCoordinate(nodeNumber=n_gen, coordinate=k)))) for k in range(case.n_modes)]

        def prestep(mbs, t):
            A, f = rotation(), F(t)          # A at t_n: it turns by ~1e-5 rad in a step
            m_loc = np.cross(d, A.T @ f)
            mbs.SetLoadParameter(lF, "loadVector", f)
            mbs.SetLoadParameter(lM, "loadVector", (A @ m_loc).tolist())
            for k, v in zip(lq, (m_loc @ Theta).tolist()):
                mbs.SetLoadParameter(k, "load", v)
            return True
    elif mode == "markers":
        m = mbs.AddMarker(eii.MarkerSuperElementRigid(
            bodyNumber=obj, meshNodeNumbers=nodes, weightingFactors=_area_weights(case, name).tolist(),
            useAlternativeApproach=True, visualization=eii.VMarkerSuperElementRigid(show=False)))
        mbs.AddLoad(eii.LoadForceVector(markerNumber=m, loadVectorUserFunction=lambda mbs, t, v: F(t)))
        mbs.AddLoad(eii.LoadTorqueVector(markerNumber=m, loadVectorUserFunction=lambda mbs, t, v:
                                         np.cross(rotation() @ d, F(t)).tolist()))
        return
    elif mode == "none":
        return
    else:
        raise ValueError(f"load_mode = {mode!r} is not allowed: expected one of {LOAD_MODES}")
    mbs.SetPreStepUserFunction(prestep)


def run_exudyn(case: PeerCase, h: float = 1e-4, t_end: float = 1.0, *, out_step: float = 1e-3,
               spectral_radius: float = 0.9, load_mode: str = "master",
               node_type: str = "NodeType.RotationEulerParameters") -> dict:
    """Integrate the free wheelset under ``case.load`` with Exudyn's generalized-alpha.

    Returns, sampled every ``out_step`` (row 0 at t = 0): t (k,); q, q_t (k, n)
    modal coordinates and velocities; ref_position, ref_velocity, ref_omega (k, 3)
    and ref_rotation (k, 3, 3) of the floating frame (global); tread_R (k, 3) the
    tread_R master node p_r + A (x_m + S q); tread_R_centroid (k, 3) from Exudyn's
    area-weighted MarkerSuperElementPosition on the tread_R nodes, and
    tread_R_centroid_check, the same point from the frame and q.  Also setup_s,
    solve_s (wall of exu.SolveDynamic only), frequencies_hz from Exudyn's reduced
    mass and stiffness, and the settings.
    """
    import exudyn as exu
    import exudyn.itemInterface as eii
    from exudyn.FEM import FEMinterface, ObjectFFRFreducedOrderInterface

    t0 = time.perf_counter()
    body = case.body
    fem = FEMinterface()
    fem.nodes = {"Position": case.points}
    fem.massMatrix, fem.stiffnessMatrix = case.M, case.K
    fem.modeBasis = {"matrix": case.modes, "type": "NormalModes"}
    fem.eigenValues = (2 * np.pi * body.frequencies_hz) ** 2
    cms = ObjectFFRFreducedOrderInterface(fem, rigidBodyNodeType=node_type)

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ids = cms.AddObjectFFRFreducedOrder(mbs, positionRef=[0, 0, 0], initialVelocity=[0, 0, 0],
                                        initialAngularVelocity=[0, 0, 0], gravity=[0, 0, 0])
    obj, n_ref, n_gen = ids["oFFRFreducedOrder"], ids["nRigidBody"], ids["nGenericODE2"]
    D = exu.MatrixContainer()
    D.SetWithDenseMatrix(np.asarray(body.reduced_damping), useDenseMatrix=False)
    mbs.SetObjectParameter(obj, "dampingMatrixReduced", D)
    _add_load(exu, eii, mbs, case, obj, n_ref, n_gen, load_mode)

    nodes_R = [int(i) for i in case.interfaces["tread_R"]["nodes"]]
    mR = mbs.AddMarker(eii.MarkerSuperElementPosition(
        bodyNumber=obj, meshNodeNumbers=nodes_R, weightingFactors=_area_weights(case, "tread_R").tolist(),
        visualization=eii.VMarkerSuperElementPosition(show=False)))
    OV = exu.OutputVariableType
    spec = {"ref_position": (n_ref, OV.Position), "ref_velocity": (n_ref, OV.Velocity),
            "ref_omega": (n_ref, OV.AngularVelocity), "ref_rotation": (n_ref, OV.RotationMatrix),
            "q": (n_gen, OV.Coordinates), "q_t": (n_gen, OV.Coordinates_t)}
    sensors = {k: mbs.AddSensor(eii.SensorNode(nodeNumber=nd, outputVariableType=ov, storeInternal=True,
                                               writeToFile=False)) for k, (nd, ov) in spec.items()}
    sensors["tread_R_centroid"] = mbs.AddSensor(eii.SensorMarker(
        markerNumber=mR, outputVariableType=OV.Position, storeInternal=True, writeToFile=False))
    mbs.Assemble()

    s = exu.SimulationSettings()
    ti = s.timeIntegration
    ti.endTime, ti.numberOfSteps = t_end, int(round(t_end / h))
    ti.generalizedAlpha.spectralRadius = spectral_radius
    ti.adaptiveStep = False                 # exactly the step h, or a failure
    ti.verboseMode = 0
    s.solution.file.write = False
    s.solution.sensors.writePeriod = out_step
    setup_s = time.perf_counter() - t0

    t1 = time.perf_counter()
    ok = exu.SolveDynamic(mbs, s, solverType=exu.DynamicSolverType.GeneralizedAlpha)
    solve_s = time.perf_counter() - t1
    if not ok:
        raise RuntimeError("exudyn: SolveDynamic failed")

    data = {k: np.asarray(mbs.GetSensorStoredData(v)) for k, v in sensors.items()}
    out = {k: v[:, 1:] for k, v in data.items()}
    out["ref_rotation"] = out["ref_rotation"].reshape(-1, 3, 3)
    A, p, q = out["ref_rotation"], out["ref_position"], out["q"]
    xR, SR = body.node("tread_R")
    out["tread_R"] = p + np.einsum("kab,kb->ka", A, xR + q @ SR[:3].T)
    wR = _area_weights(case, "tread_R")
    Psi_R = np.einsum("i,iak->ak", wR, case.modes.reshape(-1, 3, body.n_modes)[nodes_R])
    out["tread_R_centroid_check"] = p + np.einsum("kab,kb->ka", A, wR @ case.points[nodes_R] + q @ Psi_R.T)

    Mr, Kr = np.asarray(cms.massMatrixReduced), np.asarray(cms.stiffnessMatrixReduced)
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(Mr, Kr)).real)
    out.update(t=data["q"][:, 0], setup_s=setup_s, solve_s=solve_s,
               frequencies_hz=np.sqrt(np.abs(w2)) / (2 * np.pi),
               settings=dict(h=h, t_end=t_end, spectral_radius=spectral_radius, node_type=node_type,
                             load_mode=load_mode, newton="modified (Exudyn default)",
                             exudyn=exu.__version__))
    return out


def momentum(case: PeerCase, res: dict) -> np.ndarray:
    """Linear momentum (k, 3): m v + w x A (mc + Ct q) + A Ct q_t (Ct = 0 for our modes)."""
    inv = case.body.invariants
    A, v, w = res["ref_rotation"], res["ref_velocity"], res["ref_omega"]
    mc = inv["mc"] + res["q"] @ inv["Ct"].T
    return (float(inv["m"]) * v + np.cross(w, np.einsum("kab,kb->ka", A, mc))
            + np.einsum("kab,kb->ka", A, res["q_t"] @ inv["Ct"].T))


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", nargs="?", default="peer_exudyn.npz", help="result arrays (.npz)")
    ap.add_argument("--load-mode", default="master", choices=LOAD_MODES[:3])
    ap.add_argument("--repeat", type=int, default=1, help="runs; the best solve time is reported")
    ap.add_argument("--t-end", type=float, default=1.0)
    a = ap.parse_args(argv)
    case = build_case()
    b = case.body
    print(f"case: {case.K.shape[0]} DOF, {b.n_modes} modes, body file {case.body_path}")

    rest = run_exudyn(case, t_end=0.05, load_mode="none")
    drift = max(np.abs(rest["q"]).max(), np.abs(rest["ref_position"]).max())
    print(f"no load, 0.05 s: max |q|, |frame position| = {drift:.1e} (must stay 0)")

    runs = [run_exudyn(case, t_end=a.t_end, load_mode=a.load_mode) for _ in range(a.repeat)]
    res = min(runs, key=lambda r: r["solve_s"])
    times = ", ".join(f"{r['solve_s']:.2f}" for r in runs)
    print(f"exudyn {res['settings']['exudyn']}, load mode {a.load_mode!r}: setup {res['setup_s']:.2f} s, "
          f"solve {res['solve_s']:.2f} s (runs: {times}) "
          f"-> {res['solve_s'] / a.t_end:.2f} wall s per simulated s (h = {res['settings']['h']:g} s)")
    print(" mode   ours Hz   exudyn Hz   rel diff")
    for k, (fo, fe) in enumerate(zip(b.frequencies_hz, res["frequencies_hz"])):
        print(f" {k + 1:4d} {fo:9.3f} {fe:11.3f} {(fe - fo) / fo:10.1e}")

    J = case.load.impulse(a.t_end)
    p = momentum(case, res)[-1]
    err = np.linalg.norm(p - J) / np.linalg.norm(J)
    print(f"impulse int F dt = {np.round(J, 5).tolist()} N s; momentum at {a.t_end:g} s = "
          f"{np.round(p, 5).tolist()} N s; relative difference {err:.1e} (want < 1e-3)")
    gap = np.abs(res["tread_R_centroid"] - res["tread_R_centroid_check"]).max()
    print(f"tread_R centroid: Exudyn's marker vs frame + modes q: max difference {gap:.1e} m")
    rms = np.sqrt((res["q"] ** 2).mean(axis=0))
    print("RMS q per mode:", np.array2string(rms, precision=2, max_line_width=120))

    keep = ["t", "q", "q_t", "ref_position", "ref_velocity", "ref_omega", "ref_rotation", "tread_R",
            "tread_R_centroid", "frequencies_hz"]
    np.savez(a.out, **{k: res[k] for k in keep}, ours_frequencies_hz=b.frequencies_hz,
             solve_s=res["solve_s"], setup_s=res["setup_s"], impulse=J, momentum_end=p,
             rest_drift=drift, settings=str(res["settings"]), load=repr(case.load))
    print(f"wrote {a.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
