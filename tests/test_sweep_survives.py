"""``axlebox sweep`` when things go wrong around it: a worker killed mid-case, two sweeps (and two
runners of one case) on one folder, a full disk.  Bearing-rig cases: seconds each."""
import json
import shutil
import subprocess
import sys
import threading
import time
from concurrent.futures import ProcessPoolExecutor
from multiprocessing import get_context
from pathlib import Path

import h5py
import numpy as np
import psutil
import pytest

from axlebox._files import DiskFullError, h5_bound, is_locked
from axlebox.bearing import resultfile
from axlebox.pipelines.sweep import LOCK, case_lock, is_finished, load_config, matrix, run_case, sweep

from test_sweep import ROOT, _complete, _config


def _warm():
    """Compile the rig's kernels into the session's cache (or load them) here, once, so that the
    workers load them (a worker compiling takes ~35 s, two at once longer)."""
    from axlebox.bearing.defects import Defect
    from axlebox.bearing.rig import RigConfig, simulate
    simulate(RigConfig(duration=0.01, defects=(Defect(W=1e-3),)))


def _tomls(cfg, speeds):
    return {c.name: c.toml for c in matrix(*load_config(cfg), speeds=speeds, widths=[1.0])}


def _valid(out: Path, tomls: dict) -> None:
    """Every case once, each a complete result of its own config; no temporary file left."""
    assert sorted(p.stem for p in out.glob("*.h5")) == sorted(tomls)
    for name, toml in tomls.items():
        assert _complete(out / f"{name}.h5") and is_finished(out / f"{name}.h5", toml), name
    assert not list(out.glob("*.tmp"))
    rows = (out / "summary.csv").read_text().splitlines()[1:]
    assert sorted(r.split(",")[0] for r in rows) == sorted(f"{n}.h5" for n in tomls)


def test_a_worker_killed_mid_case_has_its_case_rerun(tmp_path):
    """SIGKILL to the worker process that holds a case's lock (so is computing it), one second
    into the case: dask reruns the case on a worker (the restarted one or the other); the sweep
    ends with every case present once, complete, none failed, and the killed case's file written
    after the kill (no half file taken for it)."""
    _warm()
    cfg, out = _config(tmp_path, duration=1.2), tmp_path / "out"
    speeds = [40.0, 50.0, 60.0]
    killed = {}

    def kill_a_runner():
        deadline = time.monotonic() + 240
        while time.monotonic() < deadline:
            for proc in psutil.Process().children(recursive=True):
                try:
                    # a case's lock, .<case>.lock in the sweep's folder (not dask's own, such as
                    # its workspace's purge.lock, which a worker holds while it starts)
                    locks = [f.path for f in proc.open_files() if f.path.endswith(".lock")
                             and Path(f.path).parent == out and Path(f.path).name != LOCK
                             and Path(f.path).name.startswith(".")]
                except psutil.Error:
                    continue
                if locks:
                    time.sleep(1.0)
                    proc.kill()
                    killed.update(case=Path(locks[0]).name[1:-len(".lock")], at=time.time())
                    return
            time.sleep(0.05)
    th = threading.Thread(target=kill_a_runner, daemon=True)
    th.start()
    lines = []
    res = sweep(cfg, out, speeds=speeds, widths=[1.0], workers=2, log=lines.append)
    th.join(5)
    assert killed, "no runner was seen computing"
    assert res["failed"] == [] and sorted(res["ran"]) == sorted(_tomls(cfg, speeds)), lines
    _valid(out, _tomls(cfg, speeds))
    assert (out / f"{killed['case']}.h5").stat().st_mtime > killed["at"]


def test_a_second_sweep_on_the_folder_is_refused_and_nothing_is_computed_twice(tmp_path):
    """Sweep B started on the folder sweep A is running exits 2 with one line naming A's pid;
    A finishes every case; B run again afterwards computes nothing (every file keeps its inode
    and mtime)."""
    _warm()
    cfg, out = _config(tmp_path, duration=0.6), tmp_path / "out"
    args = [str(cfg), "--speeds", "40", "50", "--widths", "1", "--workers", "1", "--out", str(out)]
    cmd = [sys.executable, "-m", "axlebox", "sweep", *args]
    a = subprocess.Popen(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    deadline = time.monotonic() + 120
    while not is_locked(out / LOCK) and a.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    assert is_locked(out / LOCK), "sweep A never took the folder"
    b = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert b.returncode == 2
    assert b.stderr.count("\n") == 1 and "is in use by another sweep" in b.stderr \
        and f"pid {a.pid} " in b.stderr, b.stderr
    assert a.wait(timeout=300) == 0, a.stdout.read()
    tomls = _tomls(cfg, [40.0, 50.0])
    _valid(out, tomls)
    stamps = {p.name: (p.stat().st_ino, p.stat().st_mtime_ns) for p in out.glob("*.h5")}
    again = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0 and "2 skipped, 0 run, 0 failed" in again.stdout, again.stdout
    assert {p.name: (p.stat().st_ino, p.stat().st_mtime_ns) for p in out.glob("*.h5")} == stamps


def test_two_runners_of_one_case_compute_it_once(tmp_path):
    """Two processes run the same case at once (dask rerunning a case whose worker it lost while
    that worker still computes, or two sweeps): the case lock makes one compute it and the other
    wait and find it finished; the file is whole."""
    _warm()
    cfg = _config(tmp_path, duration=0.6)
    (c,) = matrix(*load_config(cfg), speeds=[40.0], widths=[1.0])
    out = str(tmp_path / f"{c.name}.h5")
    with ProcessPoolExecutor(2, mp_context=get_context("spawn")) as pool:
        runs = [f.result() for f in [pool.submit(run_case, c.kind, c.toml, out, 1) for _ in range(2)]]
    assert sorted(r["computed"] for r in runs) == [False, True]
    assert _complete(Path(out)) and is_finished(out, c.toml)
    assert not is_locked(case_lock(out)) and not list(tmp_path.glob("*.tmp"))


def test_the_h5_bound_holds_for_data_that_does_not_compress(tmp_path):
    """h5_bound is what the writer reserves: it must not be smaller than the file, even for
    white noise (gzip cannot shrink it) in many small datasets (headers dominate)."""
    rng = np.random.default_rng(0)
    for shape, n in (((200_000, 3), 4), ((10,), 200), ((1,), 1000)):
        arrays = {f"a{i}": rng.random(shape) for i in range(n)}
        p = resultfile.write_checkpoint(tmp_path / "c.h5", {"k": 1}, arrays)
        assert p.stat().st_size <= h5_bound(arrays.values()), (shape, n)
        q = resultfile.write(tmp_path / "r.h5", config_toml="", seed=0, time=arrays["a0"], fs_hz=1.0,
                             signals={"s": arrays})
        assert q.stat().st_size <= h5_bound([arrays["a0"], *arrays.values()]), (shape, n)
        with h5py.File(q) as f:
            assert np.array_equal(f["signals/s/a1"][()], arrays["a1"])


def test_a_file_that_does_not_fit_is_refused_before_it_is_written(tmp_path, monkeypatch):
    """Where the file system cannot reserve space (fallocate unsupported), the free space is
    compared with the bound: a refusal names the file, the need and what is free, and leaves
    nothing behind."""
    import axlebox._files as files
    monkeypatch.setattr(files, "_free", lambda folder: 1000)
    monkeypatch.setattr(files, "_fallocate", lambda: None)          # no fallocate in this libc
    with pytest.raises(DiskFullError, match=r"no space left on device for .*r\.h5.*needs up to "
                                            r"1\.\d MB, 0\.0 MB free there\): nothing was written"):
        resultfile.write(tmp_path / "r.h5", config_toml="", seed=0, time=np.zeros(10), fs_hz=1.0,
                         signals={"s": {"a": np.zeros(10)}})
    assert not list(tmp_path.iterdir())


DRIVER = """
import json, subprocess, sys, pathlib
out = pathlib.Path(sys.argv[1]); cmd = [sys.executable, "-m", "axlebox", "sweep", *sys.argv[2:]]
first = subprocess.run(cmd, capture_output=True, text=True)
left = sorted(p.name for p in out.iterdir())
subprocess.run(["mount", "-o", "remount,size=64m", str(out)], check=True)
second = subprocess.run(cmd, capture_output=True, text=True)
print(json.dumps({"first": [first.returncode, first.stdout, first.stderr], "left": left,
                  "second": [second.returncode, second.stdout, second.stderr],
                  "final": sorted(p.name for p in out.iterdir())}))
"""


def test_a_full_disk_fails_one_case_and_the_sweep_goes_on(tmp_path):
    """The sweep's folder on a tmpfs with room for one case, not two (a private mount namespace,
    ``unshare -rm``; skipped where the kernel refuses one): one case is written, the other fails
    with one line saying no space is left (no traceback, no crash of the worker: HDF5 would
    SIGSEGV on a full disk if the writer did not reserve first), nothing half-written is left,
    the summary has the finished case; with room again the rerun computes only the failed one."""
    if not shutil.which("unshare") or subprocess.run(
            ["unshare", "-rm", "sh", "-c", f"mount -t tmpfs -o size=1m tmpfs {tmp_path}"]).returncode:
        pytest.skip("no private mount namespace here (unshare -rm) for a small file system")
    cfg = _config(tmp_path, duration=0.6)
    ref = run_case(*[(c.kind, c.toml) for c in matrix(*load_config(cfg), speeds=[30.0], widths=[1.0])][0],
                   str(tmp_path / "ref.h5"), 0)
    with h5py.File(ref["path"]) as f:          # what one case's writer reserves
        arrays = []
        f.visititems(lambda k, o: arrays.append(o) if isinstance(o, h5py.Dataset) else None)
        need = h5_bound(np.empty(o.shape, o.dtype) for o in arrays)
    out = tmp_path / "out"
    out.mkdir()
    (tmp_path / "driver.py").write_text(DRIVER)
    size = need + (256 << 10)                  # one case fits; two do not (a case file is > 256 KiB)
    script = (f"mount -t tmpfs -o size={size} tmpfs {out} && cd {ROOT} && {sys.executable} "
              f"{tmp_path / 'driver.py'} {out} {cfg} --speeds 40 50 --widths 1 --workers 1 --out {out}")
    p = subprocess.run(["unshare", "-rm", "sh", "-c", script], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    r = json.loads(p.stdout)
    rc, stdout, stderr = r["first"]
    assert rc == 1 and stderr.count("\n") == 1 and "1 case(s) failed" in stderr, stderr
    failed = [ln for ln in stdout.splitlines() if ": failed: " in ln]
    assert len(failed) == 1 and "DiskFullError: no space left on device for" in failed[0] \
        and "nothing was written" in failed[0], stdout
    done = [ln for ln in stdout.splitlines() if ": done in " in ln]
    assert len(done) == 1, stdout
    name = done[0].split()[1].rstrip(":")
    left = sorted([".sweep.lock", ".v40_w1.lock", ".v50_w1.lock", f"{name}.h5", "summary.csv"])
    assert r["left"] == left, r["left"]
    rc, stdout, _ = r["second"]
    assert rc == 0 and "1 skipped, 1 run, 0 failed" in stdout, stdout
    assert [f for f in r["final"] if f.endswith(".h5")] == ["v40_w1.h5", "v50_w1.h5"]
