"""The package as a user installs it, made once per test session and shared by the modules that
use it, whichever pytest-xdist worker asks first (the others wait for it): the wheel built from
this checkout, a fresh venv with it installed, and ``axlebox demo`` run by that venv from a folder
outside the checkout.  test_install.py checks the install and the demo's files;
test_validation.py checks the paper's validation case in the demo's result (the demo simulates
that case: the suite's longest single run, once instead of twice)."""
import fcntl
import json
import os
import shutil
import subprocess
import sys
import sysconfig
from contextlib import contextmanager
from pathlib import Path

from axlebox.pipelines.demo import DURATION

ROOT = Path(__file__).resolve().parents[1]
SHARED = "AXLEBOX_TEST_SHARED"       # the session's shared folder (tests/conftest.py makes it)
# the demo's own duration (2.0 s with AXLEBOX_FULL=1: test_validation.py's full size)
DEMO_DURATION = 2.0 if os.environ.get("AXLEBOX_FULL") == "1" else DURATION


def available() -> bool:
    """A checkout to build the wheel from (not a user's installed package)."""
    return (ROOT / "pyproject.toml").is_file() and bool(os.environ.get(SHARED))


def run(cmd, **kw):
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, **kw)
    assert r.returncode == 0, \
        f"{' '.join(map(str, cmd))} exited {r.returncode}:\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}"
    return r


@contextmanager
def _once(name: str):
    """``(folder, done)`` of ``name`` in the shared folder, under an exclusive lock: ``done`` when an
    earlier holder made it whole (it then wrote ``done.json``)."""
    folder = Path(os.environ[SHARED]) / name
    folder.mkdir(parents=True, exist_ok=True)
    with open(folder.with_suffix(".lock"), "a") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        yield folder, (folder / "done.json").is_file()


def wheel() -> Path:
    """The wheel of this checkout, built from a copy (setuptools builds in the source tree, where
    it would leave ``build/`` behind, and an earlier ``build/`` would carry removed files in)."""
    with _once("wheel") as (folder, done):
        if not done:
            src = folder / "src" / "axlebox"
            shutil.rmtree(src.parent, ignore_errors=True)
            shutil.copytree(ROOT, src, ignore=shutil.ignore_patterns(
                ".git", "build", "*.egg-info", "__pycache__", "axlebox-demo", ".pytest_cache", ".ci"))
            out = folder / "dist"
            run([sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "--no-build-isolation", "-w",
                 out, src])
            (whl,) = out.glob("axlebox-*.whl")
            (folder / "done.json").write_text(json.dumps({"wheel": str(whl)}))
        return Path(json.loads((folder / "done.json").read_text())["wheel"])


def venv() -> dict:
    """A fresh venv (``--without-pip``) given the wheel alone (not editable); it sees the test
    environment's packages through a ``.pth`` file, not the base interpreter's.  ``py``, ``exe``
    (its ``axlebox``), ``elsewhere`` (a folder outside the checkout) and ``env`` (without
    ``PYTHONPATH``)."""
    whl = wheel()
    with _once("venv") as (folder, done):
        if not done:
            env_dir = folder / "venv"
            shutil.rmtree(env_dir, ignore_errors=True)
            run([sys.executable, "-m", "venv", "--without-pip", env_dir])
            py = env_dir / "bin" / "python"
            # dependencies and pip from the test environment, as path entries (a path entry runs
            # no .pth of its own, so the environment's editable axlebox stays out of sight)
            site = Path(run([py, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"])
                        .stdout.strip())
            here = dict.fromkeys(sysconfig.get_paths()[k] for k in ("purelib", "platlib"))
            (site / "test_environment.pth").write_text("\n".join(here) + "\n")
            run([py, "-m", "pip", "install", "-q", "--no-deps", "--no-index", "--ignore-installed", whl])
            (folder / "elsewhere").mkdir(exist_ok=True)
            (folder / "done.json").write_text(json.dumps({"venv": str(env_dir)}))
        env_dir = Path(json.loads((folder / "done.json").read_text())["venv"])
    return {"venv": env_dir, "py": env_dir / "bin" / "python", "exe": env_dir / "bin" / "axlebox",
            "elsewhere": folder / "elsewhere",
            "env": {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}}


def demo(duration: float) -> Path:
    """The folder ``axlebox demo --duration <duration>`` wrote, run by the venv's ``axlebox`` from
    a folder outside the checkout."""
    v = venv()
    with _once(f"demo-{duration:g}s") as (folder, done):
        if not done:
            run([v["exe"], "demo", "--out", folder / "demo", "--duration", duration], cwd=v["elsewhere"],
                env=v["env"])
            (folder / "done.json").write_text("{}")
    return folder / "demo"
