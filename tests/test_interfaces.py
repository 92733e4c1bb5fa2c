"""RBE2 / RBE3 kinematics and the damping laws, checked as invariants."""
import numpy as np
import pytest

from axlebox.fem import assembly, damping, interfaces
from axlebox.fem.body import make_body
from axlebox.geometry import beam, mesh


@pytest.fixture(scope="module")
def bar():
    p = beam.BeamParams(length=0.6, width=0.05, height=0.08)
    fe = assembly.assemble(mesh.mesh_model("beam", beam.build, p, 0.03))
    itf = interfaces.make_interfaces(fe, {"end_a": "rbe2", "end_b": "rbe3"})
    body, red = make_body("bar", fe, itf, n_modes=6)
    return fe, itf, body, red


def _rigid(r, q):
    """u = u_m + theta x r for offsets r (n, 3) and master DOFs q (6,)."""
    return q[:3] + np.cross(q[3:], r)


def test_rbe2_face_moves_rigidly_with_its_master(bar):
    fe, itf, body, red = bar
    U = body.mode_shapes                               # (n, p, 3)
    a = itf[0]
    r = fe.points[a.nodes] - a.position
    for k in range(body.n_modes):
        q = body.nodes["end_a"]["shapes"][:, k]
        np.testing.assert_allclose(U[k][a.nodes], _rigid(r, q), atol=1e-9 * np.abs(U[k]).max())


def test_rbe3_master_is_the_weighted_rigid_fit_of_its_face(bar):
    """q_m minimises sum w_i |u_i - (u_m + theta x r_i)|^2 (weighted least squares)."""
    fe, itf, body, red = bar
    U = body.mode_shapes
    b = itf[1]
    r = fe.points[b.nodes] - b.position
    R = interfaces._rigid_rows(r)
    W = np.repeat(b.weights, 3)
    for k in range(body.n_modes):
        q = body.nodes["end_b"]["shapes"][:, k]
        fit = np.linalg.lstsq(np.sqrt(W)[:, None] * R, np.sqrt(W) * U[k][b.nodes].ravel(), rcond=None)[0]
        np.testing.assert_allclose(q, fit, atol=1e-8 * np.abs(q).max())
    # and the face is not rigid: it deforms in the bending modes
    q = body.nodes["end_b"]["shapes"][:, 0]
    dev = U[0][b.nodes] - _rigid(r, q)
    assert np.abs(dev).max() > 1e-4 * np.abs(U[0][b.nodes]).max()


def test_rbe3_weights_sum_to_the_face_area(bar):
    fe, itf, _, _ = bar
    assert itf[1].weights.sum() == pytest.approx(0.05 * 0.08, rel=1e-9)


def test_rayleigh_from_two_frequencies_gives_zeta_at_both():
    a, b = damping.rayleigh_from_two(10.0, 500.0, 0.02)
    for f in (10.0, 500.0):
        w = 2 * np.pi * f
        assert a / (2 * w) + b * w / 2 == pytest.approx(0.02, rel=1e-12)


def test_modal_damping_is_diagonal_2_zeta_omega():
    D = damping.modal(np.array([100.0, 200.0]), 0.05)
    np.testing.assert_allclose(np.diag(D), 2 * 0.05 * 2 * np.pi * np.array([100.0, 200.0]))
    with pytest.raises(ValueError, match="zeta"):
        damping.modal(np.array([1.0]), 1.5)
