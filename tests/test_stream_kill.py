"""No kill loses a run (issue 50, item 5): the outputs stream to ``<out>.stream.d``, a segment file
per checkpoint interval written as ``.tmp`` and renamed whole just before its checkpoint
(pipelines/stream.py), so a kill at any instant, in the middle of an append included, tears only
outputs after the last checkpoint; the same command resumes without ``--restart`` to the
uninterrupted run's arrays, bit for bit.

The car with rigid bodies (configs/vehicle.toml, leapfrog at 5e-5 s, 10 kHz outputs), 0.6 s in
0.25 s chunks with a checkpoint at the end of each: killed with SIGKILL inside its third append
(the test-only hook ``AXLEBOX_TEST_KILL_IN_APPEND``), after its time and half its sensors are
written; then the Stream itself, without the car, through the same cases and those between.
"""
import os
import signal
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import h5py
import numpy as np
import pytest

from axlebox._params import ParameterError
from axlebox.pipelines import cli, stream
from axlebox.pipelines import simulate as psim
from conftest import h5_arrays

ROOT = Path(__file__).resolve().parents[1]
CONFIG = """[run]
duration = 0.6

[bodies]
flexible = []
"""


def _cli(config, out, **env):
    return subprocess.run([sys.executable, "-m", "axlebox", "simulate", str(config), "--checkpoint-every",
                           "0.25", "--out", str(out)], cwd=ROOT, env={**os.environ, **env},
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, timeout=600)


def test_a_run_killed_inside_an_append_resumes_to_the_same_bits(tmp_path, capsys):
    config = tmp_path / "rigid.toml"
    config.write_text(CONFIG)
    ref = tmp_path / "ref.h5"
    assert cli.main(["simulate", str(config), "--checkpoint-every", "0.25", "--out", str(ref)]) == 0
    assert not stream.stream_path(ref).exists() and not psim.partial_path(ref).exists()

    out = tmp_path / "run.h5"
    folder, partial = stream.stream_path(out), psim.partial_path(out)
    p = _cli(config, out, **{stream.KILL_IN_APPEND: "3"})
    assert p.returncode == -signal.SIGKILL, p.stderr
    assert not out.exists()
    with h5py.File(partial, "r") as f:                  # two chunks of 2500 outputs at 10 kHz
        assert int(f.attrs["k"]) == 5000
    # committed: the two checkpoints' segments; torn: the third chunk's, never renamed
    assert sorted(p.name for p in folder.iterdir()) == ["000000000000.h5", "000000002500.h5",
                                                        "000000005000.h5.tmp"]

    capsys.readouterr()
    assert cli.main(["simulate", str(config), "--checkpoint-every", "0.25", "--out", str(out)]) == 0
    assert "resuming at 0.5 s" in capsys.readouterr().out
    assert not folder.exists() and not partial.exists()
    a, b = h5_arrays(ref), h5_arrays(out)
    assert a.keys() == b.keys() and len(a) > 10
    for k in a:
        assert np.array_equal(a[k], b[k]), k


# -- the Stream alone: a model's shapes, made-up outputs ------------------------------------------

MODEL = SimpleNamespace(sensor_names=["s0", "s1", "s2"], n_states=5,
                        W=SimpleNamespace(whout=np.zeros((2, 4)), elout=np.zeros((3, 6))))
SE, EVERY, PER = 7, 2, 25              # state snapshots every 7th output, wheels every 2nd, chunks


def _outputs(n):
    rng = np.random.default_rng(0)
    return {"out_t": np.arange(n) * 1e-3, "out_sens": rng.standard_normal((n, 3, 3)),
            "out_wh": rng.standard_normal((n, 2, 4)), "out_el": rng.standard_normal((n, 3, 6)),
            "out_y": rng.standard_normal(((n - 1) // SE + 1, 5))}


def _append(s, full, k0, k1):
    """Outputs k0 .. k1 - 1 as the integrator gives them (out_y: the chunk's snapshots)."""
    s.append(k0, {"out_t": full["out_t"][k0:k1], "out_sens": full["out_sens"][k0:k1],
                  "out_wh": full["out_wh"][k0:k1], "out_el": full["out_el"][k0:k1],
                  "out_y": full["out_y"][(k0 + SE - 1) // SE:(k1 + SE - 1) // SE]})


def _check(folder, full):
    j = stream.joined(folder)
    assert np.array_equal(j["out_t"][()], full["out_t"])
    for i in range(3):
        assert np.array_equal(j[f"out_sens/{i}"][()], full["out_sens"][:, i])
    assert np.array_equal(j["out_wh"][()], full["out_wh"][::EVERY])
    assert np.array_equal(j["out_el"][3:40], full["out_el"][::EVERY][3:40])       # across segments
    assert np.array_equal(np.asarray(stream.Rows(j["out_el"])[:, 1]), full["out_el"][::EVERY, 1])
    assert np.array_equal(j["out_y"][()], full["out_y"])


@pytest.mark.parametrize("when", ["in an append", "after a commit, before its checkpoint"])
def test_the_stream_resumes_past_what_a_kill_left(tmp_path, when):
    """Outputs 0 .. 99, chunks of 25, a checkpoint (commit) after each of the first two; the
    kill: in the third append (its ``.tmp`` left torn: part written, and then bytes no HDF5
    reader takes), or after the third chunk's segment was committed but before its checkpoint
    was written.  Resumed at the checkpoint's 50: the stream is the uninterrupted one's."""
    full, folder = _outputs(100), tmp_path / "run.h5.stream.d"
    s = stream.Stream(folder, MODEL, SE, every=EVERY)
    for k0 in (0, 25):
        _append(s, full, k0, k0 + 25)
        s.commit(k0 + 25)
    _append(s, full, 50, 75)
    if when == "in an append":
        s.f.close()
        with open(folder / "000000000050.h5.tmp", "r+b") as f:    # torn: garbage over its superblock
            f.write(b"\xff" * 64)
    else:
        s.commit(75)
    del s                                            # killed: nothing more happens
    s = stream.Stream(folder, MODEL, SE, resume_k=50, every=EVERY)
    assert sorted(p.name for p in folder.iterdir()) == ["000000000000.h5", "000000000025.h5"]
    for k0 in (50, 75):
        _append(s, full, k0, k0 + 25)
    s.close()
    _check(folder, full)


def test_a_stream_that_does_not_reach_its_checkpoint_is_refused(tmp_path):
    full, folder = _outputs(100), tmp_path / "run.h5.stream.d"
    s = stream.Stream(folder, MODEL, SE, every=EVERY)
    _append(s, full, 0, 25)
    s.commit(25)
    _append(s, full, 25, 50)
    s.close()
    (folder / "000000000025.h5").unlink()             # removed by hand: outputs 25 .. 49 gone
    with pytest.raises(ParameterError, match=r"holds outputs 0 \.\. 24, not its checkpoint's .*--restart"):
        stream.Stream(folder, MODEL, SE, resume_k=50, every=EVERY)


def test_an_earlier_versions_stream_asks_for_restart(tmp_path):
    """A checkpoint beside a one-file stream (``<out>.stream.h5``, the earlier version's): one
    line asking for ``--restart``, before the model is built."""
    out = tmp_path / "run.h5"
    text = psim.load_config("vehicle", duration=0.6).to_toml()
    psim.write_checkpoint(psim.partial_path(out), text, {"k": 2500, "wall_s": 1.0, "y": np.zeros(3),
                                                         "exchange": np.zeros(3)})
    Path(str(out) + ".stream.h5").write_bytes(b"")
    with pytest.raises(ParameterError, match=r"has no stream .*earlier version.*--restart") as err:
        psim.run("vehicle", out, duration=0.6, log=lambda *_: None)
    assert "\n" not in str(err.value)


def test_a_run_without_outputs_leaves_an_empty_stream(tmp_path):
    """A run that stops before its first output (Newton failing at once): one empty segment."""
    folder = tmp_path / "run.h5.stream.d"
    stream.Stream(folder, MODEL, SE, every=EVERY).close()
    j = stream.joined(folder)
    assert j["out_t"].shape == (0,) and j["out_el"].shape == (0, 3, 6)
    assert stream.Rows(j["out_el"])[:, 1].shape == (0, 6)
