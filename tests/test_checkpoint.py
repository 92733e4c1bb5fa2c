"""``axlebox simulate`` survives a kill (issue 21, item 1): the outputs stream to
``<out>.stream.d`` while the run goes (issue 32, item 4: memory flat in the run's length),
every ``--checkpoint-every`` simulated seconds the run's state goes to ``<out>.partial.h5``
through a temporary name; the same command run again resumes from them and writes the same
arrays as a run never stopped, which are the arrays of the run kept in memory; another config
is refused, naming what changed, unless ``--restart``.

The validation case (eight DTRBs), 0.35 s with a checkpoint at 0.25 s (the end of the first
0.25 s chunk), killed with SIGKILL once the checkpoint is there.
"""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import h5py
import numpy as np
import pytest

from axlebox.mbs.post import comfort
from axlebox.mbs.solver import integrate
from axlebox.pipelines import cli, sensor
from axlebox.pipelines import simulate as psim
from axlebox.pipelines.stream import stream_path
from conftest import h5_arrays

ROOT = Path(__file__).resolve().parents[1]
ARGS = ["validation_48kmh", "--duration", "0.35", "--checkpoint-every", "0.25"]


@pytest.mark.slow
def test_a_killed_run_resumes_to_the_same_arrays(tmp_path, capsys):
    ref = tmp_path / "ref.h5"
    psim.run("validation_48kmh", ref, duration=0.35, checkpoint_every=0.25, log=lambda *_: None)
    assert not psim.partial_path(ref).exists()             # removed once the result is written
    assert not stream_path(ref).exists()

    # streamed, the result is the run kept in memory's (and the acquisition chain's), bit for bit
    cfg = psim.load_config("validation_48kmh", duration=0.35)
    model, y0 = psim.build_model(cfg, log=lambda *_: None)
    s = cfg.settings()
    kept = sensor.decimate_run(integrate.simulate(model, 0.35, s, y0=y0), s.output_rate_hz,
                               cfg.sensors)
    psim.write(tmp_path / "kept.h5", kept, model, cfg,
               comfort.floor_comfort(kept.time, kept.sensors, model.system.track_ramp))
    a, b = h5_arrays(ref), h5_arrays(tmp_path / "kept.h5")
    assert a.keys() == b.keys()
    for k in a:
        assert np.array_equal(a[k], b[k]), k

    out = tmp_path / "run.h5"
    partial = psim.partial_path(out)
    p = subprocess.Popen([sys.executable, "-m", "axlebox", "simulate", *ARGS, "--out", str(out)],
                         cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                         start_new_session=True)
    deadline = time.monotonic() + 600
    try:
        while not partial.exists() and p.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
    finally:
        os.killpg(p.pid, signal.SIGKILL)
        p.wait()
    assert partial.exists() and not out.exists(), "the run ended before its checkpoint"
    with h5py.File(partial, "r") as f:            # the first chunk: 0.25 s at 50 kHz
        assert int(f.attrs["k"]) == 12_500 and "out_t" not in f      # the state, not the outputs
    # the outputs: those done, in a segment committed before the checkpoint (tests/test_stream_kill.py)
    with h5py.File(stream_path(out) / "000000000000.h5", "r") as f:
        assert f["out_t"].shape[0] == 12_500

    # another config: refused in one line naming the field, the checkpoint kept
    capsys.readouterr()                               # (the reference run's progress)
    bad = ["simulate", "validation_48kmh", "--duration", "0.3", "--checkpoint-every", "0.25",
           "--out", str(out)]
    assert cli.main(bad) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "run.duration" in err and "--restart" in err, err
    assert partial.exists()

    # the same command: resumes, and the result is the uninterrupted run's, array for array
    assert cli.main(["simulate", *ARGS, "--out", str(out)]) == 0
    assert "resuming at 0.25 s" in capsys.readouterr().out
    assert not partial.exists() and not stream_path(out).exists()
    a, b = h5_arrays(ref), h5_arrays(out)
    assert a.keys() == b.keys()
    for k in a:
        assert np.array_equal(a[k], b[k]), k


def test_restart_drops_a_checkpoint_of_another_config(tmp_path):
    """``--restart``: a checkpoint left by another config is removed, not read (checked before
    the model is built: a broken one is refused at once)."""
    out = tmp_path / "run.h5"
    partial = psim.partial_path(out)
    partial.write_bytes(b"not a checkpoint")
    with pytest.raises(Exception, match="checkpoint .* is not readable"):
        psim.run("validation_48kmh", out, duration=0.01, log=lambda *_: None)
    with pytest.raises(Exception, match="checkpoint-every"):
        psim.run("validation_48kmh", out, duration=0.01, checkpoint_every=-1.0, log=lambda *_: None)
    psim.run("validation_48kmh", out, duration=0.01, restart=True, log=lambda *_: None)
    assert out.is_file() and not partial.exists()
