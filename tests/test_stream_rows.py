"""A streamed run's outputs reach the result file a block of rows at a time (pipelines/stream.py
``Rows``, bearing/resultfile.py ``write``): what is written equals the arrays indexed in memory,
whatever the block size."""
import h5py
import numpy as np
import pytest

from axlebox.bearing import resultfile
from axlebox.pipelines.stream import Rows


@pytest.fixture
def stream(tmp_path):
    rng = np.random.default_rng(3)
    a = rng.standard_normal((1003, 12, 6))                 # rows, element rows, columns
    with h5py.File(tmp_path / "s.h5", "w") as f:
        f.create_dataset("out_el", data=a, chunks=(64, 12, 6))
    f = h5py.File(tmp_path / "s.h5", "r")
    yield a, f["out_el"]
    f.close()


def test_recorded_indexing_and_reshape_are_the_arrays(stream):
    a, ds = stream
    r = Rows(ds)
    assert r.shape == a.shape and r.nbytes == a.nbytes
    assert r[:, 3].source_row_nbytes == a[0].nbytes        # a block reads the stream's whole rows
    np.testing.assert_array_equal(np.asarray(r[:, 3]), a[:, 3])
    np.testing.assert_array_equal(np.asarray(r[:, 3][:, [0, 4, 5]]), a[:, 3][:, [0, 4, 5]])
    b = r[:, 6:12].reshape(1003, 2, 3, 6)
    assert b.shape == (1003, 2, 3, 6)
    np.testing.assert_array_equal(b[:, 1][:, 2, 2:6].rows(10, 500),
                                  a[:, 6:12].reshape(1003, 2, 3, 6)[:, 1][:, 2, 2:6][10:500])
    with pytest.raises(IndexError):
        r[5]                                              # a row pick is not recorded
    with pytest.raises(ValueError):
        r.reshape(7, 12, 6)


@pytest.mark.parametrize("block", [1000, 1 << 20])
def test_the_result_file_gets_the_rows_block_by_block(stream, tmp_path, monkeypatch, block):
    """Blocks of one to a few rows (1000 bytes) and one block (1 MiB): the same datasets."""
    a, ds = stream
    monkeypatch.setattr(resultfile, "BLOCK_BYTES", block)
    r = Rows(ds)
    groups = {"bearings": {"b/ring_loads": (r[:, :2], {"unit": "N"}), "b/cage": r[:, 2, 2:6]},
              "states": {"y": r.reshape(1003, 72)}}
    out = resultfile.write(tmp_path / "r.h5", config_toml="", seed=0, time=np.arange(1003.0), fs_hz=1.0,
                           signals={}, groups=groups)
    with h5py.File(out, "r") as f:
        np.testing.assert_array_equal(f["bearings/b/ring_loads"][()], a[:, :2])
        assert f["bearings/b/ring_loads"].attrs["unit"] == "N"
        np.testing.assert_array_equal(f["bearings/b/cage"][()], a[:, 2, 2:6])
        np.testing.assert_array_equal(f["states/y"][()], a.reshape(1003, 72))
