"""Free-free beam and simple-body mass properties against closed forms."""
import dataclasses

import numpy as np
import pytest

from axlebox import ParameterError
from axlebox.fem import assembly, eigen, interfaces, massprops, parts
from axlebox.fem.body import make_body
from axlebox.geometry import beam, mesh

E, RHO = 2.1e11, 7850.0
# cos(bL) cosh(bL) = 1 (Blevins, Formulas for Natural Frequency
# and Mode Shape, table 8-1, free-free beam)
BETA_L = np.array([4.73004074, 7.85320462, 10.99560784])


@pytest.fixture(scope="module")
def slender():
    # L / thickness = 50: shear and rotary inertia lower mode 3 by < 1 % (Timoshenko)
    p = beam.BeamParams(length=2.0, width=0.04, height=0.06)
    fe = assembly.assemble(mesh.mesh_model("beam", beam.build, p, 0.02))
    return p, fe, eigen.free_free_modes(fe, 12)


def _direction_fraction(fe, phi, axis):
    u = fe.field(phi)
    Ms = fe.scalar_mass()
    e = np.array([u[:, a] @ (Ms @ u[:, a]) for a in range(3)])
    return e[axis] / e.sum()


def test_free_free_bending_matches_euler_bernoulli(slender):
    p, fe, modes = slender
    # bending in y (the 40 mm direction): the modes whose motion is > 90 % along y
    fy = [f for f, phi in zip(modes.frequencies_hz, modes.shapes.T)
          if _direction_fraction(fe, phi, 1) > 0.9][:3]
    I, A = p.height * p.width ** 3 / 12, p.width * p.height
    exact = BETA_L ** 2 / (2 * np.pi * p.length ** 2) * np.sqrt(E * I / (RHO * A))
    np.testing.assert_allclose(fy, exact, rtol=0.02)
    assert fy[0] == pytest.approx(exact[0], rel=0.005)


def test_six_rigid_modes_identified(slender):
    _, fe, modes = slender
    assert len(modes.rigid_frequencies_hz) == 6
    assert modes.rigid_frequencies_hz.max() < 1e-3 * modes.frequencies_hz[0]
    assert modes.rigid_residual == pytest.approx(modes.rigid_frequencies_hz.max() / modes.frequencies_hz[0])
    # the six shapes: M-orthonormal, spanning the analytic rigid motions, M-orthogonal to the elastic
    Phi_r = modes.rigid_shapes
    np.testing.assert_allclose(Phi_r.T @ (fe.M @ Phi_r), np.eye(6), atol=1e-10)
    R = fe.rigid_modes(fe.points.mean(axis=0))
    E = R - Phi_r @ (Phi_r.T @ (fe.M @ R))
    outside = np.einsum("ij,ij->j", E, fe.M @ E) / np.einsum("ij,ij->j", R, fe.M @ R)
    assert np.sqrt(outside.max()) < 1e-10
    assert np.abs(Phi_r.T @ (fe.M @ modes.shapes)).max() < 1e-8
    assert modes.residual < 1e-4          # ||K phi - w^2 M phi|| / ||K phi|| of the elastic modes


def test_a_grounded_body_is_refused(slender):
    """Springs from one end face to the ground (a body constrained, not free): its rigid motions
    carry energy, and the solve says so rather than returning elastic modes of a fixed body."""
    import scipy.sparse as sp
    _, fe, _ = slender
    end = np.flatnonzero(np.isclose(fe.points[:, 0], fe.points[:, 0].min()))
    k = np.zeros(fe.ndof)
    k[fe.dofs[end].ravel()] = 1e9                       # N/m per DOF, 3 x 15 nodes or so
    grounded = dataclasses.replace(fe, K=(fe.K + sp.diags(k)).tocsr())
    with pytest.raises(eigen.RigidModeError, match="the rigid motions are not free"):
        eigen.free_free_modes(grounded, 4)


def two_bars(p):
    """Two 0.5 m steel bars 0.15 m apart, in one gmsh model: two parts."""
    import gmsh
    gmsh.model.occ.addBox(0, 0, 0, 0.5, 0.05, 0.05)
    gmsh.model.occ.addBox(0, 0.2, 0, 0.5, 0.05, 0.05)
    gmsh.model.occ.synchronize()
    return {}


def test_disconnected_body_is_refused_naming_its_parts():
    """Two separate bars have twelve zero modes: found from the mesh (not counted in a spectrum,
    where a Lanczos solve can miss members of the cluster), and each part named."""
    fe = assembly.assemble(mesh.mesh_model("two_bars", two_bars, beam.BeamParams(), 0.05, cache=False))
    pieces = parts.parts(fe.mesh)
    assert len(pieces) == 2
    assert sorted(np.concatenate([q.cells for q in pieces]).tolist()) == list(range(len(fe.mesh.cells)))
    assert not set(pieces[0].nodes) & set(pieces[1].nodes)
    lows = sorted(q.lower[1] for q in pieces)
    np.testing.assert_allclose(lows, [0.0, 0.2], atol=1e-12)
    mass = RHO * 0.5 * 0.05 * 0.05                                   # 9.8125 kg each
    with pytest.raises(eigen.DisconnectedBodyError,
                       match=r"2 separate parts \(12 rigid modes, expected 6\)") as e:
        eigen.free_free_modes(fe, 4)
    assert str(e.value).count(f"{mass:.4g} kg") == 2 and "y 0.2..0.25" in str(e.value)


def test_points_of_no_element_are_refused():
    m = mesh.mesh_model("beam", beam.build, beam.BeamParams(length=0.5, width=0.05, height=0.05), 0.05)
    m = dataclasses.replace(m, points=np.vstack([m.points, [[3.0, 0.0, 0.0]]]))
    assert parts.orphans(m).tolist() == [len(m.points) - 1]
    with pytest.raises(ParameterError, match=r"mesh.points: 1 of the \d+ points belong to no element "
                                             r"\(the first at \[3.0, 0.0, 0.0\] m\)"):
        assembly.assemble(m)


def hinged_boxes(p):
    """Two cubes sharing one edge and nothing else: one part by its nodes, a hinge by its
    mechanics (a seventh zero mode, turning about the edge)."""
    import gmsh
    a = gmsh.model.occ.addBox(0, 0, 0, 0.1, 0.1, 0.1)
    b = gmsh.model.occ.addBox(0.1, 0.1, 0, 0.1, 0.1, 0.1)
    gmsh.model.occ.fragment([(3, a)], [(3, b)])
    gmsh.model.occ.synchronize()
    return {}


def test_a_hinge_is_refused_by_the_spectrums_gap():
    fe = assembly.assemble(mesh.mesh_model("hinged", hinged_boxes, beam.BeamParams(), 0.04, cache=False))
    assert len(parts.parts(fe.mesh)) == 1
    with pytest.raises(eigen.RigidModeError, match="more than 6 rigid modes"):
        eigen.free_free_modes(fe, 4)


def test_mass_properties_of_offset_box_are_analytic():
    p = beam.BeamParams(length=0.8, width=0.1, height=0.2)
    m = mesh.mesh_model("beam", beam.build, p, 0.05)
    c = np.array([0.3, -0.2, 0.5])
    m.points = m.points + c
    mp = massprops.from_model(assembly.assemble(m))
    mass = RHO * p.length * p.width * p.height
    J = mass / 12 * np.diag([p.width ** 2 + p.height ** 2, p.length ** 2 + p.height ** 2,
                             p.length ** 2 + p.width ** 2])
    assert mp.mass == pytest.approx(mass, rel=0.005)
    np.testing.assert_allclose(mp.center_of_mass, c, atol=0.005 * p.length)
    np.testing.assert_allclose(mp.inertia, J, atol=0.005 * J.max())


@pytest.mark.parametrize("method", ["guyan", "craig-bampton"])
def test_reduced_rigid_mass_properties_equal_full(slender, method):
    _, fe, _ = slender
    itf = interfaces.make_interfaces(fe, {"end_a": "rbe2", "end_b": "rbe3"})
    body, _ = make_body("beam", fe, itf, method=method, n_modes=8)
    full = massprops.from_model(fe)
    assert body.mass == pytest.approx(full.mass, rel=1e-6)
    np.testing.assert_allclose(body.center_of_mass, full.center_of_mass, atol=1e-6 * 2.0)
    np.testing.assert_allclose(body.inertia, full.inertia, rtol=1e-6, atol=1e-6 * np.abs(full.inertia).max())


def test_ffrf_invariants_of_free_free_modes(slender):
    """Elastic modes are M-orthogonal to the rigid motions: Ct = Cr = 0, Me = I, m = mass."""
    _, fe, _ = slender
    itf = interfaces.make_interfaces(fe, {"end_a": "rbe3", "end_b": "rbe3"})
    body, _ = make_body("beam", fe, itf, n_modes=8)
    inv = body.invariants
    scale = np.sqrt(body.mass)          # |int rho phi| <= sqrt(m) for mass-normalised phi
    assert np.abs(inv["Ct"]).max() < 1e-8 * scale
    assert np.abs(inv["Cr"]).max() < 1e-8 * scale * 2.0
    np.testing.assert_allclose(inv["Me"], np.eye(body.n_modes), atol=1e-8)
    assert float(inv["m"]) == pytest.approx(body.mass, rel=1e-9)
    np.testing.assert_allclose(body.reduced_stiffness, np.diag((2 * np.pi * body.frequencies_hz) ** 2),
                               rtol=1e-8, atol=1e-6 * body.reduced_stiffness.max())


def test_rbe3_adds_no_stiffness_rbe2_does(slender):
    """RBE3 only averages: the reduced free-free modes converge to the full ones.
    An RBE2 spider rigidifies its face: frequencies may only rise."""
    _, fe, modes = slender
    for kind in ("rbe3", "rbe2"):
        itf = interfaces.make_interfaces(fe, {"end_a": kind, "end_b": kind})
        body, _ = make_body("beam", fe, itf, n_modes=20)
        f = body.frequencies_hz[:6]
        assert np.all(f >= modes.frequencies_hz[:6] * (1 - 1e-7))
        if kind == "rbe3":
            np.testing.assert_allclose(f, modes.frequencies_hz[:6], rtol=2e-3)


@pytest.mark.parametrize("size,order", [(0.02, 2), (0.03, 1)])
def test_stiffness_and_mass_are_scikit_fems_vector_forms(size, order):
    """fem/assembly.py builds K and M from the scalar element's blocks; scikit-fem's own vector
    forms (``linear_elasticity`` and ``rho u . v`` on ``ElementVector``) give the same matrices to
    round-off, on tet10 and on tet4."""
    from skfem import Basis, BilinearForm, ElementTetP1, ElementTetP2, ElementVector, MeshTet1, MeshTet2
    from skfem.helpers import dot
    from skfem.models.elasticity import lame_parameters, linear_elasticity
    msh = mesh.mesh_model("beam", beam.build, beam.BeamParams(length=0.5, width=0.04, height=0.06),
                          size, order=order)
    fe = assembly.assemble(msh)
    cls, elem = (MeshTet2, ElementTetP2) if order == 2 else (MeshTet1, ElementTetP1)
    m = cls(msh.points.T.copy(), msh.cells.T.copy())
    K = linear_elasticity(*lame_parameters(E, 0.3)).assemble(Basis(m, ElementVector(elem()),
                                                                   intorder=2 if order == 2 else 1))
    M = BilinearForm(lambda u, v, w: RHO * dot(u, v)).assemble(Basis(m, ElementVector(elem()), intorder=4))
    for ours, theirs in ((fe.K, K), (fe.M, M)):
        assert ours.shape == theirs.shape
        assert abs(ours - theirs).max() <= 1e-13 * abs(theirs).max()
