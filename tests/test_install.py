"""axlebox installs as one import root, ``axlebox``, with its shipped configs inside, and runs from
any folder after a plain (non-editable) install.

The wheel is built from this checkout by the test environment's own interpreter and setuptools
(``--no-build-isolation``: no download; the ``test`` extra pins a setuptools that builds wheels
without the ``wheel`` package). The fresh venv is given that wheel alone: it sees the test
environment's packages through a ``.pth`` file, not the base interpreter's (``--system-site-packages``
would show the base's, which on a fresh machine has only what Python ships)."""
import os
import re
import subprocess
import zipfile
from pathlib import Path

import pytest

import installed

from axlebox import _numba, configs
from axlebox._cache import source_hash
from axlebox.geometry import mesh

ROOT = Path(__file__).resolve().parents[1]
SUBPACKAGES = ("geometry", "fem", "mbs", "bearing", "pipelines", "configs")

pytestmark = pytest.mark.skipif(not installed.available(), reason="needs the checkout")


_run = installed.run


@pytest.fixture(scope="module")
def wheel() -> Path:
    return installed.wheel()


def _sources(folder: Path) -> set[str]:
    return {p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.suffix in (".py", ".toml")
            and "__pycache__" not in p.parts}


def test_wheel_installs_axlebox_alone_with_every_source_and_the_configs(wheel, tmp_path):
    with zipfile.ZipFile(wheel) as z:
        names = z.namelist()
        z.extractall(tmp_path)
    top = {n.split("/")[0] for n in names if not n.split("/")[0].endswith(".dist-info")}
    assert top == {"axlebox"}
    for name in ("vehicle", "validation_48kmh", "study", "study_rig"):
        assert f"axlebox/configs/{name}.toml" in names
    installed = tmp_path / "axlebox"
    assert _sources(installed) == _sources(ROOT / "axlebox") \
        | {f"{sub}/{f}" for sub in SUBPACKAGES for f in _sources(ROOT / sub)}
    # the cache keys find the same files, under the same names, in the installed package
    assert _numba.kernel_hash(installed) == _numba.kernel_hash()
    assert mesh.geometry_hash(installed / "geometry") == mesh.geometry_hash()
    assert source_hash([installed / "configs"]) == source_hash([configs.folder()])
    entry = next(n for n in names if n.endswith(".dist-info/entry_points.txt"))
    with zipfile.ZipFile(wheel) as z:
        assert "axlebox = axlebox.pipelines.cli:main" in z.read(entry).decode()


@pytest.mark.slow
def test_plain_install_runs_the_demo_from_another_folder():
    """``pip install`` of the wheel (not editable) into a fresh venv; from a folder outside the
    checkout: ``axlebox configs``, ``python -m axlebox --help`` and ``axlebox demo`` (at the demo's
    own duration: its result is test_validation.py's, tests/installed.py) work, and the code that
    ran is the venv's copy; its kernels are the checkout's machine code where that was compiled
    first in the session (same sources)."""
    v = installed.venv()
    py, exe, elsewhere, env = v["py"], v["exe"], v["elsewhere"], v["env"]
    where = _run([py, "-c", "import axlebox.pipelines, axlebox.configs as c; "
                  "print(axlebox.pipelines.__file__); print(c.folder())"], cwd=elsewhere, env=env)
    for line in where.stdout.split():
        assert Path(line).resolve().is_relative_to(v["venv"].resolve()), line
    listing = _run([exe, "configs"], cwd=elsewhere, env=env).stdout
    for name in configs.names():
        assert name in listing
    shown = _run([exe, "configs", "show", "validation_48kmh"], cwd=elsewhere, env=env).stdout
    assert shown == configs.path("validation_48kmh").read_text()
    assert "demo" in _run([py, "-m", "axlebox", "--help"], cwd=elsewhere, env=env).stdout
    bad = subprocess.run([exe, "simulate", "no_such_config", "--out", "x.h5"], cwd=elsewhere, env=env,
                         capture_output=True, text=True)
    assert bad.returncode == 2 and "no_such_config" in bad.stderr and len(bad.stderr.splitlines()) == 1
    out = installed.demo(installed.DEMO_DURATION)
    assert (out / "report" / "index.html").is_file()
    assert (out / "diagnosis.json").is_file()
    assert (out / "validation.h5").is_file()
    # the venv's copy kept its kernels beside the checkout's, under their modules' names, none under
    # numba's own folders named by a hash of their path (axlebox/_numba.py KernelCacheLocator)
    if not _numba.user_cache_dir():
        folders = [p.name for p in Path(os.environ["NUMBA_CACHE_DIR"]).iterdir()]
        assert folders and not [n for n in folders if re.search(r"_[0-9a-f]{40}$", n)], folders
