"""numba's process-wide settings, made before any kernel compiles or loads (``axlebox.bearing``
and ``axlebox.mbs`` import this first).  Each is made through numba's public interface, its
environment variables, which numba re-reads at every compile (a ``NUMBA_*`` variable changed after
import resets every setting to the environment's), and also assigned to ``numba.config`` where
numba was imported before axlebox.

* The cache of compiled kernels goes in a folder named by a hash of every source numba compiles
  or reads a constant from (:func:`kernel_hash`): every ``*.py`` of ``bearing`` and ``mbs`` and
  every axlebox module they import.  Numba's own cache checks only the source file of the
  function it loads; a kernel keeps the callees and the module constants (slot numbers above
  all) it was compiled with.  After an edit, a ``git pull`` or an upgrade that touches only such
  a file, the stale machine code would run, and can crash the interpreter.  A
  ``NUMBA_CACHE_DIR`` the user set is left alone; the one an axlebox process set (marked in
  ``AXLEBOX_NUMBA_CACHE_DIR``) is chosen again by its child processes, whose axlebox may differ.
* Each kernel's machine code lies in that folder under its module's name (``axlebox.bearing...``),
  stamped with its file's content (:class:`KernelCacheLocator`), not under a hash of the file's
  path stamped with its time as numba's own locator does: a checkout, a wheel installed in another
  environment and a sweep's workers elsewhere, all of the same sources, share one compile.  It is
  given to numba through its public ``NUMBA_CACHE_LOCATOR_CLASSES``; a list the user set stands.
* Saves to the cache are serialised across processes (:func:`_serialise_cache_saves`): numba
  updates a function's index by load, modify, write, unlocked, so two processes compiling one
  function for two signatures at once (a sweep's workers, the suite's) can both name their
  machine code file 1, and a third process then runs one signature's code for the other's (a
  segmentation fault).  This is the one use of numba's private API: nothing public hooks the
  save; tests/test_jitcache.py fails where numba has moved what it patches.
* The threading layer: OpenMP first.  Its idle threads spin a while before they sleep, so the
  bearings' parallel region, entered every right-hand side (~100 us apart), finds them awake
  (TBB's sleep: 132 against 115 us a call on 2 cores, benchmarks/README.md).  The user's own
  ``NUMBA_THREADING_LAYER`` (or ``..._PRIORITY``) stands.  A spinning thread on a core another
  process keeps busy stalls every region; rather than a wait policy (a passive wait costs 40 %
  alone), a run fits its thread count to the cores free of other processes
  (axlebox/_threads.py).  ``OMP_WAIT_POLICY`` and ``GOMP_SPINCOUNT`` are left as they are.
"""
from __future__ import annotations

import hashlib
import os
from pathlib import Path

from numba import config
from numba.core.caching import UserProvidedCacheLocator

from ._cache import cache_dir, module_sources, modules_hash

KERNEL_PACKAGES = ("bearing", "mbs")
OURS = "AXLEBOX_NUMBA_CACHE_DIR"            # the NUMBA_CACHE_DIR an axlebox process chose
# numba's own locators, by their public names, after ours (numba.core.caching._CacheImpl's order)
NUMBA_LOCATORS = ("UserProvidedCacheLocator", "InTreeCacheLocator", "UserWideCacheLocator",
                  "IPythonCacheLocator", "ZipCacheLocator")
THREADING = ("omp", "tbb", "workqueue")


def kernel_sources(top: Path | None = None) -> dict[str, Path]:
    """Module name -> file of every source the kernels' machine code depends on: every ``*.py``
    of ``bearing`` and ``mbs`` and every axlebox module they import (this one among them: the
    options of :func:`kernel` are every kernel's); of this installation, or of the copy ``top``
    in the installed layout (``top/_numba.py``, ``top/bearing/...``)."""
    return module_sources(KERNEL_PACKAGES, top)


def kernel_hash(top: Path | None = None) -> str:
    """Hash of :func:`kernel_sources`, each file named by its module: a checkout and an installed
    package of the same sources agree."""
    return modules_hash(kernel_sources(top))


def _serialise_cache_saves() -> None:
    """Each save of a compiled function to numba's cache holds an exclusive lock on a file beside
    the function's index (POSIX ``flock``), so that the index's load-modify-write is whole; loads
    need none (numba writes each file under a temporary name and renames it).  Where numba has
    moved its cache class, or there is no ``fcntl``, numba's own save stands (and
    tests/test_jitcache.py fails)."""
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


class KernelCacheLocator(UserProvidedCacheLocator):
    """An axlebox kernel in ``NUMBA_CACHE_DIR/<its module>``, stamped by its file's sha256;
    anything else, or a cache folder axlebox did not choose, is left to numba's locators."""

    def __init__(self, py_func, py_file):
        super().__init__(py_func, py_file)
        self._cache_path = os.path.join(config.CACHE_DIR, py_func.__module__)

    def get_source_stamp(self):
        with open(self._py_file, "rb") as f:
            return hashlib.sha256(f.read()).hexdigest()

    @classmethod
    def from_function(cls, py_func, py_file):
        ours = os.environ.get(OURS)
        if not (ours and config.CACHE_DIR == ours and py_func.__module__.startswith(__package__ + ".")):
            return None
        return super().from_function(py_func, py_file)


def user_cache_dir() -> str | None:
    """The ``NUMBA_CACHE_DIR`` the user set (None where unset, or set by an axlebox process)."""
    chosen = os.environ.get("NUMBA_CACHE_DIR")
    return chosen if chosen and chosen != os.environ.get(OURS) else None


def configure() -> None:
    _serialise_cache_saves()
    env = os.environ
    if not (env.get("NUMBA_THREADING_LAYER") or env.get("NUMBA_THREADING_LAYER_PRIORITY")):
        env["NUMBA_THREADING_LAYER_PRIORITY"] = " ".join(THREADING)
        config.THREADING_LAYER_PRIORITY = list(THREADING)
    if user_cache_dir():
        return
    where = cache_dir("numba", kernel_hash())
    try:
        where.mkdir(parents=True, exist_ok=True)
    except OSError:         # read-only home: numba's own __pycache__ places stay in use
        for var in ("NUMBA_CACHE_DIR", OURS):
            env.pop(var, None)
        config.CACHE_DIR = ""
        return
    env["NUMBA_CACHE_DIR"] = env[OURS] = str(where)
    config.CACHE_DIR = str(where)
    if not env.get("NUMBA_CACHE_LOCATOR_CLASSES"):
        env["NUMBA_CACHE_LOCATOR_CLASSES"] = ",".join((f"{__name__}.KernelCacheLocator",) + NUMBA_LOCATORS)
        config.CACHE_LOCATOR_CLASSES = env["NUMBA_CACHE_LOCATOR_CLASSES"]


configure()


def kernel(fn=None, **options):
    """``numba.njit`` as the bearing kernels use it (``@kernel``, or ``@kernel(option=...)``):

    * cached;
    * IEEE arithmetic, no ``fastmath``: a kernel compiled in this process and the same one
      loaded from the cache must give the same bits (bearing/kernel/evaluate.py);
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
