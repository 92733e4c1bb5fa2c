"""The default-mesh wheelset: Craig-Bampton against the full FE model, Guyan's error,
and the bending modes the paper's pseudo-fault analysis rests on."""
import numpy as np
import pytest

from axlebox.fem import interfaces
from axlebox.fem.body import make_body
from axlebox.pipelines import modeid
from axlebox.pipelines.bodies import BODIES, compare_table


@pytest.fixture(scope="module")
def reduced(wheelset_fe):
    p, fe, modes = wheelset_fe
    spec = BODIES["wheelset"]
    itf = interfaces.make_interfaces(fe, spec.couplings(p), spec.positions(p))
    ref = modes.frequencies_hz
    cb, _ = make_body("wheelset", fe, itf, method="craig-bampton", fmax_hz=2000.0, reference_hz=ref)
    gy, _ = make_body("wheelset", fe, itf, method="guyan", reference_hz=ref)
    return ref, cb, gy


def test_craig_bampton_matches_full_model_below_cutoff(reduced):
    """Fixed-interface modes up to 2 kHz; every free-free mode below 1 kHz within 1 %."""
    ref, cb, _ = reduced
    k = int(np.sum(ref < 1000.0))
    assert k >= 15
    np.testing.assert_allclose(cb.frequencies_hz[:k], ref[:k], rtol=0.01)


def test_reduced_frequencies_never_below_full(reduced, capsys):
    """Rayleigh-Ritz: a reduction is a subspace, so its eigenvalues bound the full ones from above."""
    ref, cb, gy = reduced
    for body in (cb, gy):
        k = min(len(ref), body.n_modes)
        assert np.all(body.frequencies_hz[:k] >= ref[:k] * (1 - 1e-7))
    table = compare_table(gy)
    with capsys.disabled():
        print("\nGuyan reduction of the wheelset (7 interfaces, 42 master DOFs):\n" + table)
    assert "error %" in table
    # Guyan with 42 master DOFs is already worse than Craig-Bampton on the first modes
    assert gy.frequencies_hz[1] - ref[1] > cb.frequencies_hz[1] - ref[1]


def test_bending_modes_in_paper_range(wheelset_fe):
    """First bending 60-120 Hz; second bending 400-650 Hz (paper: about 546 Hz)."""
    _, fe, modes = wheelset_fe
    labels = modeid.classify(fe.points, fe.field(modes.shapes))
    f1 = modeid.first_of(labels, modes.frequencies_hz, "bending-1")
    f2 = modeid.first_of(labels, modes.frequencies_hz, "bending-2")
    print(f"\nwheelset: first bending {f1:.1f} Hz, second bending {f2:.1f} Hz (paper 546 Hz)")
    assert 60 <= f1 <= 120
    assert 400 <= f2 <= 650
    # the bending modes come in degenerate pairs (axisymmetric body)
    i = list(modes.frequencies_hz).index(f2)
    assert modes.frequencies_hz[i + 1] == pytest.approx(f2, rel=0.01)


def test_wheelset_mass_is_that_of_a_metro_wheelset(reduced):
    """Axle, wheels and gear only (no axle-boxes, gearbox housing or brake discs)."""
    _, cb, _ = reduced
    assert 900 < cb.mass < 1539            # REFERENCE_DATA: 1.539 t with all attachments
    assert abs(cb.center_of_mass[0]) < 1e-6 and abs(cb.center_of_mass[2]) < 1e-6
    # axisymmetric about y: Ixx = Izz
    assert cb.inertia[0, 0] == pytest.approx(cb.inertia[2, 2], rel=1e-3)


def test_interface_nodes_carry_shapes(reduced):
    _, cb, _ = reduced
    for side in "LR":
        for row in ("row1", "row2"):
            pos, shapes = cb.node(f"journal_{side}_{row}")
            assert shapes.shape == (6, cb.n_modes)
            assert abs(abs(pos[1]) - 1.0) < 0.05
        pos, _ = cb.node(f"tread_{side}")
        assert pos[2] == pytest.approx(-0.42)


# Regression (issue 36): the default-mesh wheelset's 30 free-free frequencies (Hz) as the solver
# gave them before it was made deterministic (7f63b63); they moved by under 1e-10 relative
BEFORE_HZ = [93.57759387, 98.65270883, 98.8011943, 145.7373944, 146.2215575, 233.3112515,
             241.0662676, 241.7079375, 318.8062359, 429.9077167, 429.9824202, 430.1241814,
             430.1700615, 449.0094675, 506.9423046, 507.7593114, 825.8768404, 828.4851814,
             1007.155468, 1056.298001, 1059.932744, 1164.79602, 1165.094506, 1165.204709,
             1165.308553, 1268.298886, 1272.51431, 1467.302566, 1506.090729, 1531.175917]


def test_the_wheelsets_frequencies_are_kept(wheelset_fe):
    _, _, modes = wheelset_fe
    np.testing.assert_allclose(modes.frequencies_hz, BEFORE_HZ, rtol=1e-6)
