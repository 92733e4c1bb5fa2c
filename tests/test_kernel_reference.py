"""The bearing core rewritten in parts (issue 49) is numerically the same product: the rig and the
car give the states the old kernel (one 335-line ``dtrb_rhs_part``, commit b70473e) gave over the
first 0.01 s, to 1e-9 of each slot's size.

The reference, tests/data/kernel_reference.npz, was made with that code by
tests/data/make_kernel_reference.py: each case's start (stored, so that the quasi-static
start's Newton tolerance does not enter) and its state 0.01 s on.  Why 1e-9 means the same
arithmetic: the rollers' motion is chaotic, and measured on the rig a 1e-15 change of one
roller's radial place grows to 7e-7 of the states in 0.01 s (RK4) and to 1.5e-5 ("imex"), so
the dynamic cases pass only if every operation is the old one in the old order.  The
quasi-dynamic bearing holds its rollers in equilibrium (no chaos to grow) and is compared at the
same tolerance.

The car's part holds the old kernel's states no longer: when the car's wheel-rail contact changed
(issue 69, multi-point contact tables) its start and end were remade with that checkout (the old
kernel cannot run the new tables; the rig cases, untouched, still hold the old kernel's).  It
guards the car's bits against a change nobody meant.
"""
from pathlib import Path
import tomllib

import numpy as np
import pytest

from axlebox.bearing.kernel import layout

from axlebox.bearing import rig
from axlebox.bearing.integrate import RIG, RIG_U
from axlebox.bearing.kernel.layout import CAGE_OUT

REFERENCE = Path(__file__).parent / "data" / "kernel_reference.npz"
RTOL = 1e-9
# The car's model arrays (mbs/solver/system.py ``Model.S``: the wheel-rail tables, the track, the
# bodies) with which this checkout meets the reference, and what made them: numpy's vectorised
# transcendental functions give other last bits on other SIMD targets (measured: with numpy's
# AVX-512 paths off the tables differ, and 0.01 s of chaos takes the states 5e-6 apart).
CAR_INPUTS = {"sha256": "899b2c16958000cf", "numpy": "2.4.6", "scipy": "1.17.1",
              "simd": ["AVX512_ICL", "X86_V3", "X86_V4"]}


@pytest.fixture(scope="module")
def ref():
    return dict(np.load(REFERENCE))


def _assert_slots(got, want, what):
    """Every slot (the last axis) within RTOL of the reference's largest value in that slot."""
    got, want = np.asarray(got), np.asarray(want)
    assert got.shape == want.shape, what
    flat_g, flat_w = got.reshape(-1, got.shape[-1]), want.reshape(-1, want.shape[-1])
    for q in range(flat_w.shape[-1]):
        scale = np.abs(flat_w[:, q]).max()
        err = np.abs(flat_g[:, q] - flat_w[:, q]).max()
        assert err <= RTOL * scale or err == 0.0, (what, q, err, scale)


def _assert_each(got, want, what, floor=1e-15):
    """Each value within RTOL of itself (states of different sizes and units: the bodies')."""
    got, want = np.asarray(got), np.asarray(want)
    bad = np.abs(got - want) > RTOL * np.abs(want) + floor
    assert not bad.any(), (what, np.flatnonzero(bad)[:5], got[bad][:5], want[bad][:5])


def _rig_cases():
    with np.load(REFERENCE) as f:
        return sorted({k.split("/")[0] for k in f.files if k.startswith("rig_")})


@pytest.mark.parametrize("case", _rig_cases())
def test_the_rig_gives_the_old_kernels_states(ref, case):
    """RK4, the explicit leapfrog, "imex", "imex2" and the quasi-dynamic bearing, with outer-,
    inner-ring and roller defects: 0.01 s from the stored start."""
    c = rig.config_from_dict(tomllib.loads(str(ref[f"{case}/config"])))
    p = c.bearing
    Y, P, D, _ = rig.initial_state(c)
    nb = Y.size - RIG
    Y[:nb] = np.concatenate([ref[f"{case}/start/rollers"].ravel(), ref[f"{case}/start/cages"].ravel()])
    Y[nb:] = ref[f"{case}/start/ring"]
    vec = rig._rig_vector(c, Y[nb + RIG_U:nb + RIG_U + 3])
    n_out = int(round(c.duration * c.fs_out))
    n = n_out * c.fs_out_every
    outs = (np.zeros((n, 3)), np.zeros((n_out, layout.RINGS, layout.LOAD)),
            np.zeros((n_out, p.rows, p.Z, layout.N_Q)), np.zeros((n_out, p.rows, CAGE_OUT)))
    assert rig.stepper(c, P, D, vec)(Y, 0.0, n, outs, True)
    rollers, cages = layout.views(Y[:nb], p.Z)
    _assert_slots(rollers, ref[f"{case}/end/rollers"], "rollers")
    _assert_slots(cages, ref[f"{case}/end/cages"], "cages")
    _assert_slots(Y[nb:].reshape(2, 3).T, ref[f"{case}/end/ring"].reshape(2, 3).T, "outer ring")


def _same_inputs_or_skip(model) -> None:
    """Skip where the car's model arrays differ from the reference's because numpy or scipy, or
    the SIMD targets numpy runs, differ from those that made them (a bit comparison after 0.01 s
    of chaos needs the same inputs to the bit; the rig cases, whose inputs are stored, still
    run).  Where they are the same, the arrays must be too: the comparison runs, and a change
    of the model fails it."""
    import hashlib

    import scipy
    h = hashlib.sha256()
    for name, v in zip(model.S._fields, model.S):
        h.update(name.encode() + b"\0" + np.ascontiguousarray(v).tobytes())
    here = {"numpy": np.__version__, "scipy": scipy.__version__,
            "simd": sorted(np.show_config(mode="dicts")["SIMD Extensions"]["found"])}
    there = {k: CAR_INPUTS[k] for k in here}
    if h.hexdigest()[:16] != CAR_INPUTS["sha256"] and here != there:
        pytest.skip(f"the car's model arrays differ in their last bits from those the reference was "
                    f"run with: made here with {here}, there with {there}")


def test_the_car_gives_its_reference_states(ref):
    """The validation case with rigid bodies (eight DTRBs, "imex" at 5e-6 s with the bodies'
    exchange at 1e-5 s; the flexible bodies' last bits follow the FE solver's threads): 0.01 s
    from the stored start, as the car with the multi-point contact tables gave it.  (The start
    itself is not compared: the car's statics stops at a residual of 5.6e-4 of the weight,
    where the linear algebra's threads move its last digits.)"""
    from axlebox import configs
    from axlebox.mbs.solver import integrate
    from axlebox.pipelines import simulate as psim
    T = float(ref["duration"])
    cfg = psim.load_config(configs.path("validation_48kmh"), duration=T,
                              overrides={"bodies": {"flexible": []}})
    model, y0 = psim.build_model(cfg, log=lambda *_: None)
    _same_inputs_or_skip(model)
    nb = model.n_body_states
    Z = ref["car/start/rollers"].shape[2]
    y = np.concatenate([ref["car/start/bodies"]]
                       + [np.concatenate([r.ravel(), c.ravel()])
                          for r, c in zip(ref["car/start/rollers"], ref["car/start/cages"])])
    assert list(model.bearing_names) == [str(n) for n in ref["car/bearings"]] and y.size == y0.size
    run = integrate.simulate(model, T, cfg.settings(), y0=y)
    assert run.ok, run.message
    _assert_each(run.y_end[:nb], ref["car/end/bodies"], "bodies")
    n = layout.n_state(Z, 2)
    for k, name in enumerate(model.bearing_names):
        rollers, cages = layout.views(run.y_end[nb + k * n:nb + (k + 1) * n], Z)
        _assert_slots(rollers, ref["car/end/rollers"][k], f"{name} rollers")
        _assert_slots(cages, ref["car/end/cages"][k], f"{name} cages")
