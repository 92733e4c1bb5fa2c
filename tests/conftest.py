import os
import tempfile
from pathlib import Path

import pytest

# meshes go to a per-session cache unless the user points AXLEBOX_CACHE elsewhere
os.environ.setdefault("AXLEBOX_CACHE", tempfile.mkdtemp(prefix="axlebox-test-cache-"))
os.environ.pop("DISPLAY", None)     # every rendering test runs with no display


def reference_dir() -> Path:
    """../shared/reference beside the checkout, or $AXLEBOX_REFERENCE (read-only test data)."""
    env = os.environ.get("AXLEBOX_REFERENCE")
    return Path(env) if env else Path(__file__).resolve().parents[2] / "shared" / "reference"


def full_size() -> bool:
    """Slow tests run at full size with AXLEBOX_FULL=1, at a smaller size otherwise (CI)."""
    return os.environ.get("AXLEBOX_FULL") == "1"


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
