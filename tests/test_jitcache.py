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
    callee = tmp_path / "bearing" / "kernel.py"          # called from mbs's kernels
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
    RMS 5 % apart): bearing/kernel.py's docstring."""
    import subprocess
    import sys
    env = {**os.environ, "AXLEBOX_CACHE": str(tmp_path / "cache")}
    env.pop("NUMBA_CACHE_DIR", None)
    bits = [subprocess.run([sys.executable, "-c", _RIG_BITS], env=env, capture_output=True,
                           text=True, check=True).stdout.split()[-1] for _ in range(2)]
    assert any((tmp_path / "cache" / "numba").rglob("*.nbi"))       # the second one did load
    assert bits[0] == bits[1]
