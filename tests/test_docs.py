"""The documentation site builds with no warning, its gallery runs, its references are generated
from the code, and the figures it quotes have one source.

The build is the one the README documents (`python3 -m sphinx -W --keep-going -b html docs
OUT`), on a copy of docs/ and of what it includes (benchmarks/README.md and its figures), so the
checkout is left as it was."""
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
pytest.importorskip("sphinx", reason="the docs extra is not installed (pip install -e '.[docs]')")
pytest.importorskip("sphinx_gallery", reason="the docs extra is not installed")
pytest.importorskip("myst_parser", reason="the docs extra is not installed")

# written by the build itself, never sources
GENERATED = ("_build", "auto_examples", "reference", "sg_execution_times.rst")


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    src = tmp_path_factory.mktemp("docs-src")
    shutil.copytree(ROOT / "docs", src / "docs", ignore=shutil.ignore_patterns(*GENERATED, "__pycache__"))
    (src / "benchmarks").mkdir()
    shutil.copy2(ROOT / "benchmarks" / "README.md", src / "benchmarks" / "README.md")
    shutil.copytree(ROOT / "benchmarks" / "figures", src / "benchmarks" / "figures")
    out = src / "html"
    proc = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-b", "html",
                           str(src / "docs"), str(out)], capture_output=True, text=True, timeout=1500)
    return proc, out, src


def test_the_site_builds_with_warnings_as_errors(site):
    proc, out, _ = site
    log = proc.stdout + proc.stderr
    assert proc.returncode == 0, log[-4000:]
    assert "WARNING" not in log and "ERROR" not in log, log[-4000:]
    for page in ("index", "getting_started", "design", "guide/diagnose", "results/validation",
                 "results/performance", "results/measurements", "reference/cli", "reference/config",
                 "reference/api/bearing"):
        assert (out / f"{page}.html").is_file(), page


def test_the_gallery_ran_at_build_time(site):
    _, out, src = site
    examples = sorted(p.stem for p in (ROOT / "docs" / "examples").glob("plot_*.py"))
    assert len(examples) >= 2
    for name in examples:
        html = (out / "auto_examples" / f"{name}.html").read_text()
        # sphinx-gallery writes the run's stdout and its figures only when the script ran
        assert "sphx-glr-script-out" in html, name
        assert (out / "_images" / f"sphx_glr_{name}_001.png").is_file(), name
    beam = (out / "auto_examples" / "plot_free_free_beam.html").read_text()
    assert "Euler-Bernoulli" in beam and "rigid modes: 6" in beam


def test_the_references_are_generated_from_the_code(site):
    import dataclasses

    from axlebox.mbs.vehicle.config import SECTIONS
    from axlebox.pipelines.cli import parser
    _, out, src = site
    config = (src / "docs" / "reference" / "config.md").read_text()
    for sec, cls in SECTIONS.items():
        assert f"## [{sec}]" in config, sec
        for f in dataclasses.fields(cls):
            assert f"`{f.name}`" in config, f"{sec}.{f.name}"
    cli = (src / "docs" / "reference" / "cli.md").read_text()
    sub = next(a for a in parser()._actions if hasattr(a, "choices") and isinstance(a.choices, dict))
    for name in sub.choices:
        assert f"## `axlebox {name}" in cli, name
    assert "--bearing-left" in cli and "--checkpoint-every" in cli
    api = (out / "reference" / "api" / "bearing.html").read_text()
    assert 'id="axlebox.bearing.diagnostics.pair.analyse_pair"' in api


# A speed or memory figure ("26.6 wall s per simulated s", "386 MB", "142 s wall") written by hand
# in the README or a docs page is a second copy of a measurement that benchmarks/README.md holds
# with its date; the docs include that file's tables instead (issue 35: README and benchmarks once
# disagreed on the car's speed).
SPEED = re.compile(r"\d[\d.,]*\s*(?:-\s*\d[\d.]*\s*)?(?:x\s+)?(?:wall\s+s\b|wall\s+seconds|"
                   r"s\s+wall|min\s+wall|simulated\s+s\s+per\s+wall|MB\b|GB\b|evaluations/s|"
                   r"times\s+faster|x\s+faster)")


def _hand_written_pages():
    docs = ROOT / "docs"
    pages = [ROOT / "README.md"] + [p for p in docs.rglob("*.md")
                                    if not any(g in p.relative_to(docs).parts for g in GENERATED)]
    return pages + sorted((docs / "examples").glob("*.py"))


def test_speed_figures_have_one_source():
    found = [f"{p.relative_to(ROOT)}: {m.group(0)!r}" for p in _hand_written_pages()
             for m in SPEED.finditer(p.read_text())]
    assert not found, found
    assert SPEED.search("the car ran 26.6 wall s per simulated s") is not None   # the check bites
    assert SPEED.search("peaks at 931 MB") is not None


def test_nothing_points_at_the_teams_private_folder():
    """A user who installs or clones the package has no ../shared: cite sources instead."""
    folders = ["geometry", "fem", "mbs", "bearing", "pipelines", "axlebox", "configs", "docs",
               "benchmarks"]
    files = [ROOT / "README.md", ROOT / "pyproject.toml"]
    for f in folders:
        files += [p for p in (ROOT / f).rglob("*") if p.suffix in (".py", ".toml", ".md", ".rst")
                  and not any(g in p.parts for g in GENERATED)]
    bad = re.compile(r"\.\./shared|shared/(?:reference|seed)|REFERENCE_DATA\.md|DESIGN\.md")
    hits = [f"{p.relative_to(ROOT)}:{i}" for p in files
            for i, line in enumerate(p.read_text().splitlines(), 1) if bad.search(line)]
    assert not hits, hits
