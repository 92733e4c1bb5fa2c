"""numba's compiled kernels are cached in a folder keyed by all kernel sources together
(bearing/_jitcache.py): numba checks only a function's own file, and a caller compiled against
an older callee in another file ran stale machine code (a segmentation fault here, twice)."""
import os
import shutil
from pathlib import Path

import numba
import pytest

import mbs  # noqa: F401  (configures the cache)
from bearing import _jitcache

ROOT = Path(__file__).parents[1]


@pytest.mark.skipif(bool(os.environ.get("NUMBA_CACHE_DIR")), reason="the user chose the cache")
def test_cache_folder_is_named_by_the_kernel_sources():
    assert Path(numba.config.CACHE_DIR).name == _jitcache.kernel_hash()


def test_hash_moves_with_any_kernel_source_and_only_with_kernels(tmp_path):
    for pkg in ("bearing", "mbs"):
        shutil.copytree(ROOT / pkg, tmp_path / pkg, ignore=shutil.ignore_patterns("__pycache__"))
    h0 = _jitcache.kernel_hash(tmp_path)
    assert h0 == _jitcache.kernel_hash(ROOT)
    cfg = tmp_path / "mbs" / "config.py"                 # no kernel: the cache stays
    cfg.write_text(cfg.read_text() + "\n# a comment\n")
    assert _jitcache.kernel_hash(tmp_path) == h0
    callee = tmp_path / "bearing" / "kernel.py"          # called from mbs's kernels
    callee.write_text(callee.read_text() + "\n# a comment\n")
    assert _jitcache.kernel_hash(tmp_path) != h0
