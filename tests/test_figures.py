"""The package draws its figures without touching its caller's matplotlib session (issue 70, item
4): no module chooses a backend or makes pyplot figures (axlebox/_figures.py says why), and the
backend in effect before a plotting call is the one after it, with no figure left registered in
pyplot."""
import ast
from pathlib import Path

import matplotlib
import numpy as np
import pytest

import axlebox
from axlebox import bearing, fem, geometry, mbs, pipelines

PACKAGES = (axlebox, geometry, fem, mbs, bearing, pipelines)


def _package_sources():
    for pkg in PACKAGES:
        root = Path(pkg.__path__[0])
        yield from sorted(p for p in root.rglob("*.py") if "__pycache__" not in p.parts)


def test_no_module_chooses_a_backend_or_draws_with_pyplot():
    """Every module of the package, parsed: no ``matplotlib.use`` (or ``pyplot.switch_backend``)
    and no import of ``matplotlib.pyplot``."""
    hits = []
    for path in _package_sources():
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                names = [f"{node.module}.{a.name}" for a in node.names]
            elif isinstance(node, ast.Attribute) and node.attr in ("use", "switch_backend"):
                names = [ast.unparse(node)]
            else:
                continue
            hits += [f"{path.name}:{node.lineno}: {n}" for n in names
                     if "pyplot" in n or n in ("matplotlib.use", "plt.switch_backend",
                                               "matplotlib.pyplot.switch_backend")]
    assert not hits, hits
    assert sum(1 for _ in _package_sources()) > 100            # the scan saw the package


@pytest.fixture
def caller_backend():
    """The caller's session: a backend other than Agg chosen before the call (svg draws off
    screen on any machine), and pyplot's figures counted."""
    import matplotlib.pyplot as plt
    before = matplotlib.get_backend()
    plt.switch_backend("svg")
    figs = set(plt.get_fignums())
    yield plt
    assert matplotlib.get_backend().lower() == "svg"
    assert set(plt.get_fignums()) == figs
    plt.switch_backend(before)


def test_plots_keep_the_callers_backend(caller_backend, tmp_path):
    """The library's plots of a profile, a contact table, a pair's diagnosis and a record read in
    windows, each drawn and saved: the backend is still the caller's, no pyplot figure made."""
    from axlebox.bearing.diagnostics.pair import analyse_pair
    from axlebox.bearing.diagnostics.synthetic import impulse_train, resonance
    from axlebox.bearing.frequencies import orders
    from axlebox.bearing.models.params import BearingParams
    from axlebox.mbs.wheelrail.geometry import contact_table
    from axlebox.mbs.wheelrail.standard import s1002, uic60
    from axlebox.pipelines.diagnose import DTRB_BORE
    from axlebox.pipelines.windows import Windowed

    ax = s1002().plot()
    ax.figure.savefig(tmp_path / "profile.png")
    contact_table(s1002(), uic60(), y_max=0.004, n=5).plot().savefig(tmp_path / "table.png")
    fs, shaft = 20000.0, 7.0
    o = orders(BearingParams())
    rng = np.random.default_rng(0)
    left = resonance(impulse_train(int(fs), fs, o.BPFO * shaft, rng), fs, 3000.0, 0.05)
    left = left / np.std(left) + 0.5 * rng.standard_normal(left.size)
    right = 0.3 * np.roll(left, 12) + 0.5 * rng.standard_normal(left.size)
    analyse_pair(left, right, fs, shaft, o, DTRB_BORE).plot(tmp_path / "pair.png")
    rows = [{"t0_s": 0.0, "t1_s": 1.0, "speed_hz": [6.0, 7.0],
             "words": {"left": "real fault", "right": "pseudo-fault"}}]
    Windowed(rows=rows, turns=8.0, overlap=0.5, info={"file": "x.h5"}).plot(tmp_path / "w.png")
    assert all((tmp_path / f).stat().st_size > 1000
               for f in ("profile.png", "table.png", "pair.png", "w.png"))
