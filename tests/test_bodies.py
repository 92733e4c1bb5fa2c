"""The axle-box and frame models: named interfaces, rigid modes, reduction consistency."""
import numpy as np
import pytest

from axlebox._params import ParameterError
from axlebox.fem import assembly, massprops
from axlebox.geometry import axlebox, frame, mesh, wheelset
from axlebox.pipelines.bodies import BODIES, build_body, make_params


@pytest.mark.parametrize("name,size", [("axlebox", 0.04), ("frame", 0.08)])
def test_coarse_body_builds_and_matches_full(name, size):
    body, _ = build_body(name, mesh_size=size, n_modes=12, n_reference=8, log=lambda s: None)
    ref = body.reference_frequencies_hz
    assert np.all(body.frequencies_hz[:8] >= ref * (1 - 1e-7))
    np.testing.assert_allclose(body.frequencies_hz[:4], ref[:4], rtol=0.01)
    assert set(body.nodes) == set(BODIES[name].couplings(BODIES[name].params()))


def test_named_groups_exist_for_every_model():
    for name, spec in BODIES.items():
        p = spec.params()
        m = mesh.mesh_model(name, spec.build, p, spec.coarse_mesh_size)
        assert set(spec.couplings(p)) <= set(m.groups), name
        for g, facets in m.groups.items():
            assert len(np.unique(facets)) >= 6, (name, g)


def test_mesh_cache_is_keyed_by_parameters():
    p1, p2 = axlebox.AxleboxParams(), axlebox.AxleboxParams(r_outer=0.16)
    a = mesh.mesh_model("axlebox", axlebox.build, p1, 0.05)
    b = mesh.mesh_model("axlebox", axlebox.build, p1, 0.05)
    c = mesh.mesh_model("axlebox", axlebox.build, p2, 0.05)
    assert a.path == b.path and a.path != c.path
    assert np.array_equal(a.points, b.points)


def test_axlebox_mass_is_that_of_the_housing():
    m = mesh.mesh_model("axlebox", axlebox.build, axlebox.AxleboxParams(), 0.04)
    mp = massprops.from_model(assembly.assemble(m))
    p = axlebox.AxleboxParams()
    ring = 7850 * np.pi * (p.r_outer ** 2 - p.r_bore ** 2) * p.length
    assert ring < mp.mass < 2.5 * ring            # ring + wings + pad


@pytest.mark.parametrize("body,field,value", [
    ("wheelset", "r_wheel", 0.08),            # below the axle radius: cross-field check
    ("wheelset", "r_wheel", 0.18),            # above the axle, but the rim would cut the hub
    ("wheelset", "journal_length", 0.45),     # runs into the wheel seat
    ("axlebox", "r_outer", 0.12),             # thinner than the bore allows
    ("frame", "wheelbase", 2.95),             # seats beyond the side beams
])
def test_inconsistent_parameters_name_the_field(body, field, value):
    with pytest.raises(ParameterError, match=field):
        make_params(body, {field: value})


def test_unknown_parameter_is_named():
    with pytest.raises(ParameterError, match="r_whee"):
        make_params("wheelset", {"r_whee": 0.4})


def test_wheelset_profile_is_closed_and_positive():
    prof = wheelset.profile(wheelset.WheelsetParams())
    r = np.array([q[1] for q in prof])
    assert np.all(r >= 0) and r.max() == pytest.approx(0.42 + 0.027)
    assert frame.FrameParams().wheelbase == 2.2
