"""Make ``kernel_reference.npz``: the states of the bearing kernel of axlebox 0.1.0 as it was at
commit b70473e (one 335-line ``dtrb_rhs_part``), before issue 49 rewrote it in parts, for
tests/test_kernel_reference.py.

Run with that commit checked out (``git worktree add /tmp/b70473e b70473e`` and an environment
where ``axlebox`` imports from there)::

    python3 tests/data/make_kernel_reference.py tests/data/kernel_reference.npz

What it stores, each case's start and its state after 0.01 s (the rollers' motion is chaotic, but
over 0.01 s a difference in the last bit grows by far less than 1e-9):

* the rig (bearing/rig.py): the 2 mm outer-ring defect of the paper's validation case under
  54 kN at 48 km/h, by RK4, the explicit leapfrog, "imex" and "imex2", and the quasi-dynamic
  bearing; an inner-ring and a roller defect by "imex".  The rig's config as TOML; the states
  as rollers (2, Z, 12), cages (2, 12) and the outer ring's displacement and velocity (6).
* the car: configs/validation_48kmh.toml with every body rigid (``bodies.flexible = []``: the
  reduced bodies' last bits follow the FE solver's threads, the rigid car's masses are the
  config's), its start (statics and the bearings' quasi-static start) and its state after
  0.01 s of "imex" at 5e-6 s with the bodies' exchange at 1e-5 s; the body states and each
  bearing's rollers and cages apart.

The car's part was remade with the checkout of its day when the car's wheel-rail contact changed
(issue 69: multi-point contact tables, TABLE_VERSION 2): the old kernel cannot run the new
tables, and the rig cases still hold the old kernel's states.  With that checkout::

    python3 tests/data/make_kernel_reference.py tests/data/kernel_reference.npz --car

keeps the rig cases of the file and writes the car's anew.
"""
from __future__ import annotations

import sys

import numpy as np

from axlebox.bearing import rig
from axlebox.bearing.defects import Defect
from axlebox.bearing.models.params import BearingParams

DURATION = 0.01
OUTER = Defect(W=2e-3, L=50.4e-3, H=2e-3, row=2)
CALIBRATED = {"damping": "stiffness", "beta": 1e-4}


def rig_cases():
    c = dict(speed_kmh=48.0, duration=DURATION, fs_out=1e4)
    yield "rig_rk4", rig.RigConfig(method="rk4", dt=1e-5, defects=(OUTER,), **c)
    yield "rig_leapfrog", rig.RigConfig(method="leapfrog", dt=1e-5, defects=(OUTER,), **c)
    yield "rig_imex", rig.RigConfig(method="imex", dt=5e-6, bearing=BearingParams(**CALIBRATED),
                                    defects=(OUTER,), **c)
    yield "rig_imex2", rig.RigConfig(method="imex2", dt=1e-5, bearing=BearingParams(**CALIBRATED),
                                     defects=(OUTER,), **c)
    yield "rig_quasi", rig.RigConfig(method="imex", dt=2.5e-5,
                                     bearing=BearingParams(model="quasi-dynamic", **CALIBRATED),
                                     defects=(OUTER,), **c)
    yield "rig_inner_roller", rig.RigConfig(
        method="imex", dt=5e-6, bearing=BearingParams(**CALIBRATED), seed=3,
        defects=(Defect(kind="inner", W=1e-3, L=30e-3, H=1e-3, row=1, angle=0.3),
                 Defect(kind="roller", W=1e-3, L=20e-3, H=1e-3, row=2, roller=4)), **c)


def split(y, Z):
    """(rollers (2, Z, 12), cages (2, 12)) of one bearing's state."""
    nr = 2 * Z * 12
    return y[:nr].reshape(2, Z, 12).copy(), y[nr:nr + 24].reshape(2, 12).copy()


def run_rig(c):
    from axlebox.bearing.integrate import run_leapfrog, run_rk4
    Y, P, D, vec = rig.initial_state(c)
    Y0 = Y.copy()
    every = c.fs_out_every
    n_out = int(round(c.duration * c.fs_out))
    n = n_out * every
    Z = c.bearing.Z
    outs = (np.zeros((n, 3)), np.zeros((n_out, 2, 6)), np.zeros((n_out, 2, Z, 6)), np.zeros((n_out, 2, 2)))
    if c.method == "rk4":
        ok = run_rk4(Y, 0.0, c.dt, n, every, P, D, vec, *outs)
    else:
        ok = run_leapfrog(Y, 0.0, c.dt, n, every, P, D, vec, *outs,
                          rig.RIG_METHODS.index(c.method) - 1, True)
    assert ok
    return Y0, Y


def main(out, car_only=False):
    data = {"duration": DURATION}
    if car_only:
        with np.load(out) as f:
            data.update({k: f[k] for k in f.files if not k.startswith("car/")})
    for name, c in ([] if car_only else rig_cases()):
        Y0, Y = run_rig(c)
        Z = c.bearing.Z
        data[f"{name}/config"] = np.array(c.to_toml())
        for when, y in (("start", Y0), ("end", Y)):
            rol, cag = split(y, Z)
            data[f"{name}/{when}/rollers"] = rol
            data[f"{name}/{when}/cages"] = cag
            data[f"{name}/{when}/ring"] = y[-6:].copy()
        print(name, "done", flush=True)

    from axlebox import configs
    from axlebox.mbs.solver import integrate
    from axlebox.pipelines import simulate as psim
    cfg = psim.load_config(configs.path("validation_48kmh"), duration=DURATION,
                              overrides={"bodies": {"flexible": []}})
    model, y0 = psim.build_model(cfg, log=lambda *_: None)
    run = integrate.simulate(model, DURATION, cfg.settings(), y0=y0)
    assert run.ok, run.message
    nb = model.n_body_states
    Z = BearingParams().Z
    data["car/bearings"] = np.array(model.bearing_names)
    for when, y in (("start", np.asarray(y0, float)), ("end", run.y_end)):
        data[f"car/{when}/bodies"] = y[:nb].copy()
        rc = [split(y[nb + k * (24 * Z + 24):], Z) for k in range(len(model.bearing_names))]
        data[f"car/{when}/rollers"] = np.stack([r for r, _ in rc])
        data[f"car/{when}/cages"] = np.stack([c for _, c in rc])
    print("car done")
    np.savez_compressed(out, **data)
    _print_inputs(model)


def _print_inputs(model):
    """The car's inputs the test's CAR_INPUTS names: the hash of its model arrays and what made them."""
    import hashlib

    import scipy
    h = hashlib.sha256()
    for name, v in zip(model.S._fields, model.S):
        h.update(name.encode() + b"\0" + np.ascontiguousarray(v).tobytes())
    print({"sha256": h.hexdigest()[:16], "numpy": np.__version__, "scipy": scipy.__version__,
           "simd": sorted(np.show_config(mode="dicts")["SIMD Extensions"]["found"])})


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--car"]
    main(args[0] if args else "kernel_reference.npz", car_only="--car" in sys.argv[1:])
