"""What axlebox caches is keyed by the sources that made it (axlebox/_cache.py, _numba.py).

numba's compiled kernels go in a folder keyed by all kernel sources together: numba checks only a
function's own file, and a caller compiled against an older callee in another file ran stale
machine code (a segmentation fault here, twice).  Meshes are keyed by every geometry source, so an
edited builder never hands back a mesh it would no longer make.  Both hashes name files by their
place inside the package, so a checkout and an installed wheel of the same sources agree
(test_install.py checks that on a real wheel)."""
import os
import shutil
from pathlib import Path

import numba
import pytest

import axlebox.mbs  # noqa: F401  (configures the cache)
from axlebox import _numba
from axlebox._cache import package_dir
from axlebox.geometry import mesh


@pytest.mark.skipif(bool(os.environ.get("NUMBA_CACHE_DIR")), reason="the user chose the cache")
def test_cache_folder_is_named_by_the_kernel_sources():
    assert Path(numba.config.CACHE_DIR).name == _numba.kernel_hash()


def test_kernel_hash_moves_with_any_kernel_source_and_only_with_kernels(tmp_path):
    for pkg in _numba.KERNEL_PACKAGES:
        shutil.copytree(package_dir(pkg), tmp_path / pkg, ignore=shutil.ignore_patterns("__pycache__"))
    h0 = _numba.kernel_hash(tmp_path)
    assert h0 == _numba.kernel_hash()
    cfg = tmp_path / "mbs" / "config.py"                 # no kernel: the cache stays
    cfg.write_text(cfg.read_text() + "\n# a comment\n")
    assert _numba.kernel_hash(tmp_path) == h0
    callee = tmp_path / "bearing" / "contact.py"         # called from mbs's kernels
    callee.write_text(callee.read_text() + "\n# a comment\n")
    assert _numba.kernel_hash(tmp_path) != h0


def test_mesh_key_moves_with_any_geometry_source(tmp_path):
    geo = tmp_path / "geometry"
    shutil.copytree(package_dir("geometry"), geo, ignore=shutil.ignore_patterns("__pycache__"))
    h0 = mesh.geometry_hash(geo)
    assert h0 == mesh.geometry_hash()
    for name in ("wheelset.py", "_occ.py"):              # a builder, and a helper builders share
        p = geo / name
        p.write_text(p.read_text() + "\n# a comment\n")
        assert mesh.geometry_hash(geo) != h0
        h0 = mesh.geometry_hash(geo)



_RIG_BITS = """
import hashlib
from axlebox.bearing.defects import Defect
from axlebox.bearing.rig import RigConfig, simulate
r = simulate(RigConfig(duration=0.02, defects=(Defect(W=2e-3),)))
print(hashlib.sha1(r.acceleration.tobytes() + r.Q.tobytes()).hexdigest())
"""


def test_a_kernel_compiled_here_and_one_loaded_from_the_cache_give_the_same_bits(tmp_path):
    """The same rig run in two fresh processes sharing an empty cache: the first compiles the
    bearing kernels (and writes them), the second loads them.  Their accelerations and contact
    forces agree to the bit.  With ``fastmath`` they did not (a last-bit difference in some
    roller accelerations, grown by the quasi-static start's 1e-12 m Newton steps into a rig
    RMS 5 % apart): bearing/evaluate.py's docstring."""
    import subprocess
    import sys
    env = {**os.environ, "AXLEBOX_CACHE": str(tmp_path / "cache")}
    env.pop("NUMBA_CACHE_DIR", None)
    bits = [subprocess.run([sys.executable, "-c", _RIG_BITS], env=env, capture_output=True,
                           text=True, check=True).stdout.split()[-1] for _ in range(2)]
    assert any((tmp_path / "cache" / "numba").rglob("*.nbi"))       # the second one did load
    assert bits[0] == bits[1]


_KERNEL = """
from numba import njit


@njit(cache=True)
def f(x):
    return x * 2 + 1
"""

_COMPILE = """
import sys, time
import numpy as np
if sys.argv[3] == "locked":
    import axlebox._numba  # noqa: F401  (serialises cache saves)
sys.path.insert(0, sys.argv[1])
import kern
time.sleep(max(0.0, float(sys.argv[2]) - time.time()))      # all start compiling together
kern.f(np.arange(3, dtype=sys.argv[4]))
"""

_LOAD = """
import sys
import numpy as np
sys.path.insert(0, sys.argv[1])
import kern
for dt in sys.argv[2:]:
    assert list(kern.f(np.arange(3, dtype=dt))) == [1, 3, 5], dt
print(len(kern.f.stats.cache_hits), sum(kern.f.stats.cache_misses.values()))
"""

DTYPES = ("int8", "int16", "int32", "int64", "uint8", "uint16", "uint32", "uint64", "float32", "float64")


def _compile_at_once(tmp_path, mode: str) -> tuple[int, int]:
    """Ten processes compile one cached function for ten signatures at the same instant into a
    fresh cache; a further process then calls all ten: (its cache hits, its misses)."""
    import subprocess
    import sys
    import time
    src = tmp_path / mode
    src.mkdir()
    (src / "kern.py").write_text(_KERNEL)
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / f"cache-{mode}")}
    go = time.time() + 4.0
    ps = [subprocess.Popen([sys.executable, "-c", _COMPILE, str(src), str(go), mode, dt], env=env)
          for dt in DTYPES]
    assert all(p.wait() == 0 for p in ps)
    r = subprocess.run([sys.executable, "-c", _LOAD, str(src), *DTYPES], env=env, capture_output=True,
                       text=True, check=True)
    hits, misses = (int(v) for v in r.stdout.split())
    return hits, misses


def test_processes_compiling_one_kernel_at_once_leave_a_whole_cache(tmp_path):
    """numba's save to its cache is an unlocked load-modify-write of the function's index: ten
    processes compiling one function for ten signatures at once lose entries (and two can
    name their code file alike, so that a later process runs one signature's code for
    another's: the segmentation faults of the suite's parallel workers).  Measured without
    the lock on this 2-core machine: 7 rounds of 9 lost entries (a later process found 6-9 of
    the ten) or ran the wrong code; with axlebox's lock (axlebox/_numba.py), 0 of 7: a later
    process finds all ten and runs each right."""
    hits, misses = _compile_at_once(tmp_path, "locked")
    assert (hits, misses) == (len(DTYPES), 0)
