"""What axlebox caches is keyed by the sources that made it (axlebox/_cache.py, _numba.py).

numba's compiled kernels go in a folder keyed by all kernel sources together: numba checks only a
function's own file, and a caller compiled against an older callee in another file ran stale
machine code (a segmentation fault here, twice).  Meshes are keyed by every geometry source, so an
edited builder never hands back a mesh it would no longer make.  Both hashes name files by their
place inside the package, so a checkout and an installed wheel of the same sources agree
(test_install.py checks that on a real wheel)."""
import os
import re
import shutil
from pathlib import Path

import numba
import pytest

import axlebox
import axlebox.mbs  # noqa: F401  (configures the cache)
from axlebox import _numba
from axlebox._cache import package_dir
from axlebox.geometry import mesh

SUBPACKAGES = ("geometry", "fem", "mbs", "bearing", "pipelines", "configs")


@pytest.mark.skipif(bool(_numba.user_cache_dir()), reason="the user chose the cache")
def test_cache_folder_is_named_by_the_kernel_sources():
    assert Path(numba.config.CACHE_DIR).name == _numba.kernel_hash()
    assert os.environ["NUMBA_CACHE_DIR"] == numba.config.CACHE_DIR      # what numba reloads from


def _installed_copy(dest: Path) -> Path:
    """A copy of this installation's axlebox in the installed layout (``dest/axlebox/_numba.py``,
    ``dest/axlebox/bearing/...``), importable with ``dest`` on ``PYTHONPATH``."""
    top = dest / "axlebox"
    shutil.copytree(Path(axlebox.__file__).parent, top, ignore=shutil.ignore_patterns("__pycache__"))
    for sub in SUBPACKAGES:
        shutil.copytree(package_dir(sub), top / sub, ignore=shutil.ignore_patterns("__pycache__"))
    return top


def _edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert text.count(old) == 1, (path, old)
    path.write_text(text.replace(old, new))


def test_the_kernel_key_covers_every_module_numba_reads(tmp_path):
    """Every ``*.py`` of bearing/ and mbs/ and the axlebox modules they import (issue 56: an edit
    to a slot number in bearing/kernel/layout.py, a file without a kernel, left the key as it was)."""
    top = _installed_copy(tmp_path)
    names = _numba.kernel_sources(top)
    for pkg in _numba.KERNEL_PACKAGES:
        for p in (top / pkg).rglob("*.py"):
            rel = p.relative_to(top).with_suffix("").parts
            assert ".".join(("axlebox",) + (rel[:-1] if rel[-1] == "__init__" else rel)) in names, p
    # what they import from the rest of axlebox, the packages on the way included
    assert {"axlebox", "axlebox._numba", "axlebox._params", "axlebox.fem",
            "axlebox.fem.bodyfile"} <= set(names)
    assert not any(n.startswith(("axlebox.pipelines", "axlebox.geometry")) for n in names)
    h0 = _numba.kernel_hash(top)
    assert h0 == _numba.kernel_hash()                   # a copy hashes as the installation
    edits = [("bearing/kernel/layout.py", "REC_SPIN, REC = REC_ORBIT + 1, REC_ORBIT + 2",
              "REC_SPIN, REC = REC_ORBIT + 1, REC_ORBIT + 3"),          # the edit
             ("mbs/kernel/exchange.py", "THIS, LAST = 0, 1", "THIS, LAST = 1, 0"),
             ("_params.py", "class ParameterError", "# read by the kernels' modules\nclass ParameterError"),
             ("fem/bodyfile.py", "\nclass ReducedBody", "\n# imported by mbs\nclass ReducedBody")]
    for rel, old, new in edits:
        _edit(top / rel, old, new)
        h1 = _numba.kernel_hash(top)
        assert h1 != h0, rel
        h0 = h1
    for rel in ("pipelines/cli.py", "geometry/wheelset.py", "fem/eigen.py"):     # nothing numba reads
        (top / rel).write_text((top / rel).read_text() + "\n# a comment\n")
        assert _numba.kernel_hash(top) == h0, rel


# a kernel of bearing/kernel/blocks.py that writes a constant of bearing/kernel/layout.py: ``_touch`` marks a
# roller's block ``BLK_OWN`` when it first writes it
_TOUCH = """
import numpy as np, numba
from axlebox.bearing.kernel import blocks, layout
flag = np.full(1, layout.BLK_NONE, np.int64)
blocks._touch(np.ones((1, 6, layout.BLK)), flag, 0, False)
print(int(flag[0]), len(blocks._touch.stats.cache_hits), numba.config.CACHE_DIR)
"""


def test_a_kernel_loaded_after_an_edit_to_a_constant_it_reads_runs_the_new_constant(tmp_path):
    """A fresh process loads ``blocks._touch`` from the cache; bearing/kernel/layout.py's ``BLK_OWN`` is
    changed (blocks.py is not); the next fresh process runs the new value.  Under numba's own
    check alone (the old folder, given as the user's NUMBA_CACHE_DIR) the old machine code runs:
    the hazard this key is for."""
    import subprocess
    import sys
    _installed_copy(tmp_path / "src")
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", _numba.OURS)}
    env.update(PYTHONPATH=str(tmp_path / "src"), AXLEBOX_CACHE=str(tmp_path / "cache"))

    def touch(**extra):
        out = subprocess.run([sys.executable, "-c", _TOUCH], env={**env, **extra}, capture_output=True,
                             text=True, check=True, cwd=tmp_path).stdout.split()
        return int(out[0]), int(out[1]), out[2]

    own, hits, folder = touch()
    assert own == 1 and hits == 0 and str(tmp_path / "cache") in folder     # compiled, in the copy's cache
    assert touch() == (1, 1, folder)                                          # loaded from it
    user = str(tmp_path / "user")
    assert touch(NUMBA_CACHE_DIR=user) == (1, 0, user)        # numba's own locator and check
    _edit(tmp_path / "src/axlebox/bearing/kernel/layout.py", "BLK_NONE, BLK_OWN, BLK_COUPLED = 0, 1, 2",
          "BLK_NONE, BLK_OWN, BLK_COUPLED = 0, 5, 2")
    own, hits, new_folder = touch()
    assert (own, hits) == (5, 0) and new_folder != folder
    assert touch(NUMBA_CACHE_DIR=user)[:2] == (1, 1)          # numba's own check: stale code


def test_two_copies_of_the_same_sources_in_two_places_share_one_compile(tmp_path):
    """A kernel compiled by one copy of axlebox is loaded by another copy of the same sources
    elsewhere (a checkout and the wheel installed from it, a sweep's workers in two environments):
    its machine code lies under its module's name, stamped by its file's content
    (axlebox/_numba.py KernelCacheLocator), not under a hash of its path with the file's time."""
    import subprocess
    import sys
    for copy in ("a", "b"):
        _installed_copy(tmp_path / copy)
    env = {k: v for k, v in os.environ.items()
           if k not in ("NUMBA_CACHE_DIR", _numba.OURS, "NUMBA_CACHE_LOCATOR_CLASSES")}
    env["AXLEBOX_CACHE"] = str(tmp_path / "cache")

    def touch(copy):
        out = subprocess.run([sys.executable, "-c", _TOUCH], env={**env, "PYTHONPATH": str(tmp_path / copy)},
                             capture_output=True, text=True, check=True, cwd=tmp_path).stdout.split()
        return int(out[0]), int(out[1]), out[2]

    own, hits, folder = touch("a")
    assert (own, hits) == (1, 0)
    assert touch("b") == (1, 1, folder)
    names = {p.name for p in Path(folder).iterdir()}       # _touch and the kernels it calls
    assert "axlebox.bearing.kernel.blocks" in names and all(n.startswith("axlebox.bearing.") for n in names)


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
    RMS 5 % apart): bearing/kernel/evaluate.py's docstring."""
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


# --- numba's interfaces axlebox relies on (issue 56): each test fails on a numba where the
# interface no longer does what axlebox uses it for ---------------------------------------------

_SAVE = """
import sys
import numpy as np
import axlebox._numba  # noqa: F401  (patches the save)
from numba.core.caching import IndexDataCacheFile
sys.path.insert(0, sys.argv[1])
import kern
kern.f(np.arange(3))
print(getattr(IndexDataCacheFile.save, "locked", False))
"""


def test_the_cache_save_is_the_locked_one(tmp_path):
    """The private part: ``numba.core.caching.IndexDataCacheFile.save`` replaced, and the index
    path it locks beside (``_index_path``) still where axlebox reads it: a save leaves the lock
    file beside the function's index."""
    import subprocess
    import sys
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "kern.py").write_text(_KERNEL)
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    out = subprocess.run([sys.executable, "-c", _SAVE, str(tmp_path / "src")], env=env,
                         capture_output=True, text=True, check=True).stdout.split()
    assert out[-1] == "True"
    (index,) = (tmp_path / "cache").rglob("*.nbi")
    assert index.with_name(index.name + ".lock").is_file()


_RELOAD = """
import os, sys
import numpy as np
import numba
import axlebox.mbs  # noqa: F401
from numba import njit
ours = numba.config.CACHE_DIR
os.environ["NUMBA_OPT"] = "2"            # any NUMBA_* change: numba resets its settings at the next compile
njit(lambda x: x + 1)(1)
sys.path.insert(0, sys.argv[1])
import kern                              # decorated after the reset: cached where it says
kern.f(np.arange(3))
print(ours, numba.config.CACHE_DIR, " ".join(numba.config.THREADING_LAYER_PRIORITY))
"""


def test_the_settings_survive_numbas_reload_of_its_config(tmp_path):
    """numba re-reads every setting from the environment at a compile where a ``NUMBA_*``
    variable changed: the cache folder and the threading layers axlebox chose stay, and a kernel
    decorated after the reset caches into that folder."""
    import subprocess
    import sys
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "kern.py").write_text(_KERNEL)
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_") and k != _numba.OURS}
    env["AXLEBOX_CACHE"] = str(tmp_path / "cache")
    out = subprocess.run([sys.executable, "-c", _RELOAD, str(tmp_path / "src")], env=env,
                         capture_output=True, text=True, check=True).stdout.split()
    ours, after, layers = out[0], out[1], out[2:]
    assert Path(ours).parent == tmp_path / "cache" / "numba" and after == ours
    assert layers == list(_numba.THREADING)
    assert any(Path(ours).rglob("kern.f-*.nbi"))


def test_kernels_count_no_references_unless_they_allocate():
    """``kernel()`` compiles without reference counting (numba's private ``_nrt`` option): no call
    to ``NRT_incref`` or ``NRT_decref`` in a kernel that hands an array view to another; with
    ``allocates=True`` the same code counts."""
    import numpy as np

    def inner(a):
        return a[0] + a.size

    def outer(a):
        s = 0.0
        for i in range(3):
            s += callee(a[i:])
        return s

    callee = _numba.kernel(inner, cache=False)        # (numba inspects no code it cached)
    plain, counted = _numba.kernel(outer, cache=False), _numba.kernel(outer, cache=False, allocates=True)
    a = np.arange(10.0)
    assert plain(a) == counted(a) == 30.0
    counts = {f: len(re.findall(r"call void @NRT_(?:incref|decref)\(", "".join(f.inspect_llvm().values())))
              for f in (plain, counted)}
    assert counts[plain] == 0 and counts[counted] > 0, counts
