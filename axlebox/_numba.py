"""numba's process-wide settings, made before any kernel compiles or loads (``axlebox.bearing``
and ``axlebox.mbs`` import this first).

* The cache of compiled kernels goes in a folder named by a hash of every kernel source of
  ``bearing`` and ``mbs`` together.  Numba's own cache checks only the source file of the
  function it loads; a kernel that calls into another file keeps the callee it was compiled with.
  After an edit (or a ``git pull``, or an upgrade) that touches only the callee, the stale machine
  code runs, and can crash the interpreter.  ``NUMBA_CACHE_DIR``, when set, is left alone.
* Saves to the cache are serialised across processes (:func:`_serialise_cache_saves`): numba
  updates a function's index by load, modify, write, unlocked, so two processes compiling one
  function for two signatures at once (a sweep's workers, the suite's) can both name their
  machine code file 1, and a third process then runs one signature's code for the other's (a
  segmentation fault).
* The threading layer: OpenMP first.  Its idle threads spin a while before they sleep, so the
  bearings' parallel region, entered every right-hand side (~100 us apart), finds them awake
  (TBB's sleep: 132 against 115 us a call on 2 cores, benchmarks/README.md).  The user's own
  ``NUMBA_THREADING_LAYER`` (or ``..._PRIORITY``) stands.
"""
from __future__ import annotations

import hashlib
import os
from pathlib import Path

from numba import config

from ._cache import cache_dir, package_dir, source_hash

KERNEL_PACKAGES = ("bearing", "mbs")
# what marks a file whose code numba compiles: its own decorator, the kernels' (:func:`kernel`),
# and an overload (bearing/models.py's dispatch)
KERNEL_MARKS = (b"@njit", b"@kernel", b"@overload")


def kernel_hash(top: Path | None = None) -> str:
    """Hash of the kernel sources (the files marked by :data:`KERNEL_MARKS`) of ``bearing`` and
    ``mbs``: those of this installation, or the folders of those names under ``top``."""
    folders = [package_dir(p) if top is None else Path(top) / p for p in KERNEL_PACKAGES]
    # and this file: :func:`kernel`'s options are every kernel's
    own = hashlib.sha1(Path(__file__).read_bytes()).hexdigest()
    return hashlib.sha1((source_hash(folders, only_with=KERNEL_MARKS) + own).encode()).hexdigest()[:12]


def _serialise_cache_saves() -> None:
    """Each save of a compiled function to numba's cache holds an exclusive lock on a file beside
    the function's index (POSIX ``flock``), so that the index's load-modify-write is whole; loads
    need none (numba writes each file under a temporary name and renames it).  Where numba has
    moved its cache class, or there is no ``fcntl``, numba's own save stands."""
    try:
        import fcntl

        from numba.core.caching import IndexDataCacheFile
    except ImportError:
        return
    save = IndexDataCacheFile.save
    if getattr(save, "locked", False):
        return

    def locked_save(self, key, data):
        index = getattr(self, "_index_path", None)
        if index is None:
            return save(self, key, data)
        with open(index + ".lock", "a") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)         # released when the file closes
            return save(self, key, data)

    locked_save.locked = True
    IndexDataCacheFile.save = locked_save


def configure() -> None:
    _serialise_cache_saves()
    if not (os.environ.get("NUMBA_THREADING_LAYER") or os.environ.get("NUMBA_THREADING_LAYER_PRIORITY")):
        config.THREADING_LAYER_PRIORITY = ["omp", "tbb", "workqueue"]
    if os.environ.get("NUMBA_CACHE_DIR"):
        return
    where = cache_dir("numba", kernel_hash())
    try:
        where.mkdir(parents=True, exist_ok=True)
    except OSError:         # read-only home: numba's own __pycache__ places stay in use
        return
    config.CACHE_DIR = str(where)


configure()


def kernel(fn=None, **options):
    """``numba.njit`` as the bearing kernels use it (``@kernel``, or ``@kernel(option=...)``):

    * cached;
    * IEEE arithmetic, no ``fastmath``: a kernel compiled in this process and the same one
      loaded from the cache must give the same bits (bearing/evaluate.py);
    * numpy's error model: a division by zero gives inf or NaN, which the integrators' finite
      checks catch, instead of a branch to raise at every division;
    * no reference counting (numba's ``_nrt=False``) unless the kernel allocates
      (``allocates=True``): the kernels write into arrays they are given, and with counting on
      every array handed to a part that LLVM does not inline is counted up and down atomically,
      which cost half the bearing's evaluation (benchmarks/README.md, "The bearing core");
    * parts are plain functions; those a roller's evaluation is made of are inlined where they
      are called (``inline="always"``, marked at each): numba hands a call's tuples and arrays
      over argument by argument, and a roller's frame and its rings' motion are dozens of
      numbers.  The rest stays apart, which keeps the compile short (numba's inlining copies
      and retypes the callee at every call: the old one-function right-hand side took minutes).
    """
    from numba import njit
    if fn is None:
        return lambda f: kernel(f, **options)
    options = {"cache": True, "error_model": "numpy", **options}
    if not options.pop("allocates", False):
        options.setdefault("_nrt", False)
    return njit(**options)(fn)
