import os
import shutil
import tempfile
from pathlib import Path

import pytest

# meshes and numba's machine code go to a per-session cache (removed at the end) unless the user
# points AXLEBOX_CACHE elsewhere
_SESSION_CACHE = None if os.environ.get("AXLEBOX_CACHE") else tempfile.mkdtemp(prefix="axlebox-test-cache-")
if _SESSION_CACHE:
    os.environ["AXLEBOX_CACHE"] = _SESSION_CACHE
os.environ.pop("DISPLAY", None)     # every rendering test runs with no display
# what the session's processes make once and share (tests/installed.py), made by the first
# process (pytest-xdist's controller, whose environment its workers get) and removed by it
_SESSION_SHARED = (None if os.environ.get("AXLEBOX_TEST_SHARED")
                   else tempfile.mkdtemp(prefix="axlebox-test-shared-"))
if _SESSION_SHARED:
    os.environ["AXLEBOX_TEST_SHARED"] = _SESSION_SHARED

# On a pytest-xdist worker (pyproject's addopts run one per core) numba, OpenBLAS and MKL get one
# thread each, as do the processes a test starts: the bearings' parallel loops meet 1e5 times a
# simulated second, and threads of two workers sharing the cores wait at every meeting for one
# that is not running.  tests/test_threads.py gives its own child process two threads.  Set here,
# before any test module imports numba (the worker sets PYTEST_XDIST_WORKER before it loads this).
if os.environ.get("PYTEST_XDIST_WORKER"):
    for _var in ("NUMBA_NUM_THREADS", "OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(_var, "1")


# The order modules are handed out in (pytest-xdist's loadfile, ``--no-loadscope-reorder``).  A
# worker asks for its next module while it still has two tests to run, so a long module handed
# out near the end can hold one worker for minutes after the other has finished (CI timelines,
# 2026-11-29 and 2026-12-04): the long modules go first, longest first, and the short ones fill
# the end.  test_install opens (its demo, from a wheel in a venv of its own, compiles the car's
# kernels cold in two processes: axlebox/_numba.py shares them with every other process of the
# session); the other worker begins with long modules that never run the car, so that the car's
# kernels are compiled once, by the demo, and not at the same time by a second process.
FIRST = ("test_install.py", "test_wheelset.py", "test_eigen_determinism.py", "test_families.py",
         "test_bearing_implicit.py")
#: the modules' own seconds (sum of ``--durations=0`` of one ``.ci/run``, 2026-12-04, 2 cores):
#: they set the order after FIRST; a module not listed follows, the most tests first
LONG_S = {"test_accelerating_car.py": 232, "test_both_sides_car.py": 215, "test_dcrb.py": 137,
          "test_docs.py": 135, "test_coupled.py": 107, "test_vehicle.py": 104,
          "test_user_bodies.py": 88, "test_inner_ring_car.py": 85, "test_checkpoint.py": 69,
          "test_quasidynamic.py": 61, "test_sweep_survives.py": 53, "test_jitcache.py": 50,
          "test_sweep.py": 45, "test_threads.py": 37}


def pytest_collection_modifyitems(session, config, items):
    modules: dict = {}
    for item in items:
        modules.setdefault(item.path.name, []).append(item)

    def rank(m):
        if m in FIRST:
            return (0, FIRST.index(m))
        return (1, -LONG_S[m]) if m in LONG_S else (2, -len(modules[m]))
    order = sorted(modules, key=rank)
    items[:] = [item for m in order for item in modules[m]]


def pytest_sessionfinish(session, exitstatus):
    for folder in (_SESSION_CACHE, _SESSION_SHARED):
        if folder:
            shutil.rmtree(folder, ignore_errors=True)


def reference_dir() -> Path:
    """../shared/reference beside the checkout, or $AXLEBOX_REFERENCE (read-only test data)."""
    env = os.environ.get("AXLEBOX_REFERENCE")
    return Path(env) if env else Path(__file__).resolve().parents[2] / "shared" / "reference"


def full_size() -> bool:
    """Slow tests run at full size with AXLEBOX_FULL=1, at a smaller size otherwise (CI)."""
    return os.environ.get("AXLEBOX_FULL") == "1"


def h5_arrays(path) -> dict:
    """Every dataset of an HDF5 file, by its path in the file, read into memory."""
    import h5py
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda n, o: out.__setitem__(n, o[()]) if isinstance(o, h5py.Dataset) else None)
    return out


@pytest.fixture(scope="session")
def wheelset_fe():
    """The default-mesh wheelset: FE model and its full free-free modes (built once)."""
    from axlebox.fem import assembly, eigen
    from axlebox.geometry import mesh, wheelset
    from axlebox.pipelines.bodies import BODIES
    p = wheelset.WheelsetParams()
    m = mesh.mesh_model("wheelset", wheelset.build, p, BODIES["wheelset"].mesh_size)
    fe = assembly.assemble(m)
    return p, fe, eigen.free_free_modes(fe, 30)


def craig_bampton_bar(n_modes: int):
    """A 1 m steel bar 40 x 60 mm, Craig-Bampton with ``n_modes`` fixed-interface modes, undamped:
    end_a clamped-ready (RBE2), end_b loaded (RBE3); ``(fe, interfaces, reduced body)``."""
    from axlebox.fem import assembly, interfaces
    from axlebox.fem.body import make_body
    from axlebox.geometry import beam, mesh
    p = beam.BeamParams(length=1.0, width=0.04, height=0.06)
    fe = assembly.assemble(mesh.mesh_model("beam", beam.build, p, 0.02))
    itf = interfaces.make_interfaces(fe, {"end_a": "rbe2", "end_b": "rbe3"},
                                     {"end_a": (-0.5, 0, 0), "end_b": (0.5, 0, 0)})
    rb, _ = make_body("bar", fe, itf, method="craig-bampton", n_modes=n_modes, damping=("modal", 0.0))
    return fe, itf, rb


def write_pair_result(path, left, right, config_toml: str, fs: float, seed: int = 0, more=None):
    """Two axle-box signals as a vehicle result file (vertical column of ws2_L / ws2_R);
    ``more``: further sensors, name -> (n, 3) accelerations."""
    import numpy as np

    from axlebox.bearing import resultfile
    z = np.zeros_like(left)
    return resultfile.write(path, config_toml=config_toml, seed=seed, time=np.arange(left.size) / fs,
                            fs_hz=fs, signals={"ws2_L": {"acceleration": np.c_[z, z, left]},
                                               "ws2_R": {"acceleration": np.c_[z, z, right]},
                                               **{n: {"acceleration": a} for n, a in (more or {}).items()}})


def assert_windows_are_the_source(ds, folder) -> None:
    """Every window of an ``axlebox dataset`` equals its source file's slice, bit for bit."""
    import h5py
    import numpy as np
    n = ds.sizes["sample"]
    for k in range(ds.sizes["window"]):
        w = ds.isel(window=k)
        with h5py.File(folder / str(w.file.values), "r") as f:
            i = int(w.start_index)
            for side in ("left", "right"):
                sensor = f"ws{int(w.wheelset)}_{side[0].upper()}"
                src = f[f"signals/{sensor}/acceleration"][i:i + n, 2]
                assert np.array_equal(w[side].values, src), (k, side)


def assert_sized(size, W, rel=0.25):
    """A side's defect size (bearing/diagnostics/size.py SizeResult) against the model's true
    width ``W`` (m), the issue-57 criterion for one case: sized, its interval holding ``W``, the
    estimate within ``rel`` of it."""
    assert size is not None and size.status == "sized", size
    assert size.interval_m[0] <= W <= size.interval_m[1], (size.interval_m, W)
    assert abs(size.width_m / W - 1.0) <= rel, (size.width_m, W)
