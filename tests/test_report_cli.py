"""Off-screen report with no display, and the command line's handling of bad input."""
import os
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from axlebox.pipelines.bodies import build_body
from axlebox.pipelines.render import report


@pytest.fixture(scope="module")
def body_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("bodies")
    build_body("wheelset", mesh_size=0.07, n_modes=6, n_reference=0, out_dir=out, log=lambda s: None)
    return out


def test_report_pictures_exist_and_are_not_blank(body_dir, tmp_path):
    assert "DISPLAY" not in os.environ
    index = report(body_dir, tmp_path, max_modes=3, log=lambda s: None)
    pngs = sorted(tmp_path.glob("wheelset_mode*.png"))
    assert len(pngs) == 3
    for png in pngs:
        img = np.asarray(Image.open(png).convert("L"), dtype=float)
        # a blank (single-colour) render has zero variance; a body with a colour map has a lot
        assert img.var() > 100, png
        assert (img < 200).mean() > 0.02, png        # the body covers part of the picture
    text = index.read_text()
    for png in pngs:
        assert png.name in text
    assert "Hz" in text and "wheelset" in text


def test_each_picture_is_its_own_mode_whatever_came_before(body_dir, tmp_path):
    """One render a picture (pipelines/render.py): a mode's picture is the same rendered alone
    as after others (no camera, actor or image left over from the one before), and two modes'
    pictures differ."""
    from axlebox.fem import bodyfile
    from axlebox.pipelines.render import render_modes
    body = bodyfile.read(body_dir / "wheelset.h5")
    seq = render_modes(body, tmp_path / "seq", modes=[0, 1, 2])
    (alone,) = render_modes(body, tmp_path / "alone", modes=[2])
    pixels = [np.asarray(Image.open(p)) for p in seq]
    assert np.array_equal(np.asarray(Image.open(alone)), pixels[2])
    assert not np.array_equal(pixels[0], pixels[2]) and not np.array_equal(pixels[1], pixels[2])


def _cli(*args):
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    return subprocess.run([sys.executable, "-m", "axlebox", *args], capture_output=True,
                          text=True, env=env, timeout=300)


@pytest.mark.parametrize("args,names", [
    (["bodies", "build", "--body", "wheelset", "--mesh-size", "0", "--out", "x"], "--mesh-size"),
    (["bodies", "build", "--body", "wheelset", "--mesh-size", "-0.01", "--out", "x"], "--mesh-size"),
    (["bodies", "build", "--body", "wheelset", "--param", "r_wheel=0.08", "--out", "x"], "r_wheel"),
    (["bodies", "build", "--body", "wheelset", "--param", "journal_length=2.5", "--out", "x"],
     "journal_length"),
    (["bodies", "build", "--body", "wheelset", "--param", "journal_length=0.45", "--out", "x"],
     "journal_length"),
    (["bodies", "build", "--body", "bogie", "--out", "x"], "--body"),
    (["bodies", "build", "--body", "axlebox", "--modes", "0", "--out", "x"], "--modes"),
    (["bodies", "report", "/nonexistent/dir", "--out", "x"], "/nonexistent/dir"),
])
def test_bad_input_exits_2_with_one_line(args, names, tmp_path):
    r = _cli(*[a if a != "x" else str(tmp_path / "o") for a in args])
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    assert names in lines[0]
    assert "Traceback" not in r.stderr + r.stdout


def test_cli_builds_a_body(tmp_path):
    r = _cli("bodies", "build", "--body", "axlebox", "--mesh-size", "0.05", "--modes", "4",
             "--method", "guyan", "--out", str(tmp_path), "--vtu")
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "axlebox.h5").exists() and (tmp_path / "axlebox.vtu").exists()
    assert "error %" in r.stdout            # Guyan's error against the full model is printed


def test_build_resumes_instead_of_rebuilding(tmp_path):
    """A second identical request keeps the finished file; a changed request rebuilds."""
    args = ("bodies", "build", "--body", "axlebox", "--mesh-size", "0.05", "--modes", "4",
            "--no-reference", "--out", str(tmp_path))
    assert _cli(*args).returncode == 0
    mtime = (tmp_path / "axlebox.h5").stat().st_mtime_ns
    r = _cli(*args)
    assert r.returncode == 0 and "up to date" in r.stdout
    assert (tmp_path / "axlebox.h5").stat().st_mtime_ns == mtime
    r = _cli(*[a if a != "4" else "5" for a in args])
    assert r.returncode == 0 and "up to date" not in r.stdout
    assert not list(tmp_path.glob("*.part"))


def test_a_body_built_by_other_sources_is_built_again(tmp_path, monkeypatch):
    """A body file whose request names other geometry/fem sources (built before an edit or an
    upgrade: the car's cache of coarse bodies) is not kept: the same request today rebuilds it."""
    from axlebox.pipelines import bodies
    kw = dict(mesh_size=0.05, n_modes=4, n_reference=0, out_dir=tmp_path)
    with monkeypatch.context() as m:
        m.setattr(bodies, "sources_hash", lambda: "an older build")
        bodies.build_body("axlebox", log=lambda *_: None, **kw)
    lines = []
    bodies.build_body("axlebox", log=lines.append, **kw)
    assert not any("up to date" in line for line in lines), lines
    lines = []
    bodies.build_body("axlebox", log=lines.append, **kw)
    assert any("up to date" in line for line in lines), lines
