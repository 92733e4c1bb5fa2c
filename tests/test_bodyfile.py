"""Reduced-body file: exact round trip, refusal of other formats and versions, VTU export."""
import h5py
import meshio
import numpy as np
import pytest

from axlebox.fem import bodyfile
from axlebox.pipelines.bodies import build_body


@pytest.fixture(scope="module")
def axlebox_file(tmp_path_factory):
    out = tmp_path_factory.mktemp("bodies")
    body, path = build_body("axlebox", mesh_size=0.04, n_modes=8, n_reference=10, out_dir=out,
                            log=lambda s: None)
    return body, path


def _arrays(b):
    yield "mass", b.mass
    for k in ("center_of_mass", "inertia", "frequencies_hz", "reduced_mass", "reduced_stiffness",
              "reduced_damping", "mesh_points", "mesh_cells", "mode_shapes", "reference_frequencies_hz"):
        yield k, getattr(b, k)
    for n, d in b.nodes.items():
        yield f"nodes/{n}/position", d["position"]
        yield f"nodes/{n}/shapes", d["shapes"]
    for k, v in b.invariants.items():
        yield f"invariants/{k}", v
    for k, v in b.component.items():
        yield f"component/{k}", v


def test_round_trip_is_exact(axlebox_file):
    body, path = axlebox_file
    back = bodyfile.read(path)
    a, b = dict(_arrays(body)), dict(_arrays(back))
    assert a.keys() == b.keys()
    for k in a:
        assert np.array_equal(np.asarray(a[k]), np.asarray(b[k])), k
    assert back.meta["params"] == body.meta["params"]
    assert {n: d["coupling"] for n, d in back.nodes.items()} == \
           {n: d["coupling"] for n, d in body.nodes.items()}


def test_layout_follows_design(axlebox_file):
    _, path = axlebox_file
    with h5py.File(path) as f:
        assert f.attrs["format"] == "axlebox-reduced-body" and f.attrs["version"] == bodyfile.VERSION
        n = f["frequencies_hz"].shape[0]
        assert f["inertia"].shape == (3, 3) and f["center_of_mass"].shape == (3,)
        assert f["reduced/mass"].shape == (n, n)
        assert f["nodes/sensor_pad/shapes"].shape == (6, n)
        p = f["mesh/points"].shape[0]
        assert f["mesh/cells"].shape[1] == 10
        assert f["modes/shapes"].shape == (n, p, 3)
        assert np.all(np.diff(f["frequencies_hz"][()]) >= 0)


@pytest.mark.parametrize("attr,value,message", [("format", "something-else", "format"),
                                                ("version", 99, "version")])
def test_other_format_or_version_is_refused(axlebox_file, tmp_path, attr, value, message):
    _, path = axlebox_file
    bad = tmp_path / "bad.h5"
    bad.write_bytes(path.read_bytes())
    with h5py.File(bad, "a") as f:
        f.attrs[attr] = value
    with pytest.raises(bodyfile.BodyFileError, match=message):
        bodyfile.read(bad)


def test_not_hdf5_is_refused(tmp_path):
    bad = tmp_path / "x.h5"
    bad.write_text("not hdf5")
    with pytest.raises(bodyfile.BodyFileError, match="not an HDF5 file"):
        bodyfile.read(bad)


def test_vtu_export_carries_every_mode(axlebox_file, tmp_path):
    body, _ = axlebox_file
    m = meshio.read(bodyfile.export_vtu(body, tmp_path / "axlebox.vtu"))
    assert len(m.point_data) == body.n_modes
    first = sorted(m.point_data)[0]
    np.testing.assert_allclose(m.point_data[first], body.mode_shapes[0])
