"""The axle-box and frame models: named interfaces, rigid modes, reduction consistency."""
import numpy as np
import pytest

from axlebox._params import ParameterError
from axlebox.fem import assembly, massprops
from axlebox.geometry import axlebox, frame, mesh, wheelset
from axlebox.pipelines.bodies import BODIES, build_body, make_params


# Regression (issue 36): the bodies' frequencies (Hz) as the solver gave them before its start
# vector, rigid-cluster test and degenerate bases were made deterministic (7f63b63); they moved
# by under 4e-10 relative.  (reduced: the first 12 of the reduced body; full: the full FE model's)
BEFORE = {
    "axlebox": ([1021.95098, 1125.516182, 1222.059313, 1490.236316, 2134.689363, 2344.905878,
                 2738.030264, 3218.07781, 3545.361585, 3640.247056, 4334.613129, 4378.759767],
                [1019.475645, 1123.587001, 1221.256498, 1486.449872, 2133.34205, 2329.680921,
                 2702.101274, 3197.846798]),
    "frame": ([35.3754238, 80.20554584, 81.38854253, 84.62535095, 114.2729601, 143.393027,
               144.287442, 187.4988656, 201.4733522, 207.9465576, 236.5752323, 272.098567],
              [35.34875222, 80.08333609, 81.3519989, 84.54914944, 114.1294747, 142.9868921,
               143.8859175, 186.4169398]),
}


@pytest.mark.parametrize("name,size", [("axlebox", 0.04), ("frame", 0.08)])
def test_coarse_body_builds_and_matches_full(name, size):
    body, _ = build_body(name, mesh_size=size, n_modes=12, n_reference=8, log=lambda s: None)
    ref = body.reference_frequencies_hz
    assert np.all(body.frequencies_hz[:8] >= ref * (1 - 1e-7))
    np.testing.assert_allclose(body.frequencies_hz[:4], ref[:4], rtol=0.01)
    assert set(body.nodes) == set(BODIES[name].couplings(BODIES[name].params()))
    reduced, full = BEFORE[name]
    np.testing.assert_allclose(body.frequencies_hz[:12], reduced, rtol=1e-6)
    np.testing.assert_allclose(ref, full, rtol=1e-6)


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
