"""The report page in a real browser: ``index.html`` opened from file:// in headless Chromium
(Debian's ``chromium``, driven by Playwright), as a reader opens it.  Its images must load, the
verdicts' summary must open it (at a desktop's and a phone's width), then the verdict and
conclusions tables, the browser must log no error, and the page must read the same with
JavaScript off (it is static).  A full-page screenshot at desktop width is kept
for a person to look at; its path is given in the warnings summary of ``pytest -q``.

The report is the demo's (one vehicle case at 48 km/h with a defect, the relative criterion, mode
pictures beside it) on the synthetic result of tests/test_report_results.py: seconds, where the
demo's simulation takes minutes.
"""
import os
import shutil
import subprocess
import warnings
from pathlib import Path

import numpy as np
import pytest

from axlebox.bearing.diagnostics.criterion import Criterion
from axlebox.pipelines import report

from test_report_results import write_case

DESKTOP = {"width": 1366, "height": 900}
PHONE = {"width": 390, "height": 844}          # a common phone's CSS viewport (iPhone 12-15)


def _find_chromium():
    return shutil.which("chromium") or shutil.which("chromium-browser")


def _root() -> bool:
    return hasattr(os, "geteuid") and os.geteuid() == 0


@pytest.fixture(scope="module")
def browser():
    """Headless Debian chromium under Playwright; installed once with apt-get when missing and
    we are root (as .ci/run does), else the module is skipped with the reason."""
    sync_api = pytest.importorskip("playwright.sync_api",
                                   reason="playwright is not installed (pip install -e '.[test]')")
    exe = _find_chromium()
    if exe is None and _root() and shutil.which("apt-get"):
        env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
        install = ["apt-get", "install", "-y", "-q", "chromium"]
        try:
            # a fresh machine has no package lists: update only when the plain install fails
            if subprocess.run(install, env=env, capture_output=True, timeout=600).returncode:
                subprocess.run(["apt-get", "update", "-q"], env=env, capture_output=True, timeout=300)
                subprocess.run(install, env=env, capture_output=True, timeout=600)
        except subprocess.TimeoutExpired:
            pass
        exe = _find_chromium()
    if exe is None:
        pytest.skip("no chromium: install Debian's package (apt-get install chromium) to run the "
                    "report in a browser")
    with sync_api.sync_playwright() as p:
        # Playwright's own browser builds are not downloadable here; the system one speaks the
        # same DevTools protocol.  Chromium refuses its sandbox to root.
        b = p.chromium.launch(executable_path=exe, args=["--no-sandbox"] if _root() else [])
        yield b
        b.close()


@pytest.fixture(scope="module")
def demo_report(tmp_path_factory):
    """The demo's report on one synthetic case (48 km/h, 5 mm defect on the left) with two mode
    pictures: every part the demo's page has (verdicts, comfort, conclusions, figures, modes)."""
    root = tmp_path_factory.mktemp("browser")
    runs = root / "runs"
    runs.mkdir()
    write_case(runs, 48.0, 5.0, seed=1)
    modes = root / "modes"
    modes.mkdir()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    for k in (1, 2):
        plt.imsave(modes / f"wheelset_mode{k:02d}.png", np.random.default_rng(k).random((8, 8)))
    return report.report(runs, root / "report", modes_dir=modes, log=lambda *_: None,
                         criterion=Criterion(mode="relative"))


def inspect(browser, page_path: Path, *, javascript=True, screenshot: Path | None = None,
            viewport=DESKTOP) -> dict:
    """What a reader's browser makes of ``page_path``: every image's load state, the text of the
    summary and of the verdict and conclusions tables (None when absent), where each begins on
    the page, what the page's first section is, each figure's caption, console errors and
    uncaught page errors."""
    ctx = browser.new_context(viewport=viewport, java_script_enabled=javascript,
                              is_mobile=viewport is PHONE)
    try:
        page = ctx.new_page()
        console, errors = [], []
        page.on("console", lambda m: console.append(m.text) if m.type == "error" else None)
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.goto(page_path.resolve().as_uri(), wait_until="load")

        def text(selector):
            el = page.query_selector(selector)
            return el.inner_text() if el else None
        # Playwright's evaluate runs in the page even with the page's own scripts off
        images = page.evaluate("""() => Array.from(document.images, i => ({
            src: i.getAttribute('src'), complete: i.complete, width: i.naturalWidth}))""")
        found = {"images": images, "console": console, "errors": errors,
                 "summary": text("section#summary"),
                 "verdicts": text("table#verdicts"), "conclusions": text("table.claims"),
                 "scroll_width": page.evaluate("document.documentElement.scrollWidth"),
                 "top": page.evaluate("""() => Object.fromEntries(
                     ['section#summary', 'table#verdicts', 'table.claims', 'figure'].map(s => {
                       const e = document.querySelector(s);
                       return [s, e ? e.getBoundingClientRect().top + window.scrollY : null]; }))"""),
                 "first_section": page.evaluate("""() => {
                     const h = document.querySelector('h1');
                     const e = h ? h.nextElementSibling : null;
                     return e ? e.tagName.toLowerCase() + '#' + e.id : null; }"""),
                 "captions": page.evaluate("""() => Array.from(
                     document.querySelectorAll('figure:not(.modes figure)'),
                     f => f.querySelector('figcaption') ? f.querySelector('figcaption').innerText
                     : '')"""),
                 "badges": page.evaluate("""() => Array.from(
                     document.querySelectorAll('#summary .badge'),
                     b => [b.innerText, getComputedStyle(b).backgroundColor])""")}
        if found["summary"] is not None:        # the reasons, opened as a phone's reader taps them
            page.evaluate("document.querySelectorAll('#summary details').forEach(d => d.open = true)")
            found["reasons"] = text("section#summary")
        if screenshot is not None:
            page.screenshot(path=str(screenshot), full_page=True)
        return found
    finally:
        ctx.close()


def broken_images(found) -> list[str]:
    return [i["src"] for i in found["images"] if not (i["complete"] and i["width"] > 0)]


def screenshot_path(tmp_path) -> Path:
    folder = Path(os.environ.get("AXLEBOX_SCREENSHOT_DIR") or tmp_path)
    folder.mkdir(parents=True, exist_ok=True)
    return folder / "report_desktop.png"


def test_report_page_in_chromium(browser, demo_report, tmp_path, record_property):
    shot = screenshot_path(tmp_path)
    found = inspect(browser, demo_report, screenshot=shot)
    # figures 9-14, the two comfort figures and the two mode pictures, each decoded
    assert len(found["images"]) == demo_report.read_text().count("<img ") >= 10, found["images"]
    assert not broken_images(found), broken_images(found)
    assert found["verdicts"] and "verdict" in found["verdicts"], found["verdicts"]
    assert "real fault" in found["verdicts"] or "pseudo-fault" in found["verdicts"]
    assert found["conclusions"] and "the paper" in found["conclusions"], found["conclusions"]
    assert found["console"] == [] and found["errors"] == [], (found["console"], found["errors"])
    assert found["scroll_width"] <= DESKTOP["width"]     # no sideways scrolling on a desktop
    assert shot.stat().st_size > 50_000                 # a page was drawn, not a blank canvas
    # where a person finds the picture: the junit XML's properties, and (since an xdist worker's
    # stdout is dropped) a warning, which pytest -q summarises from every worker
    record_property("screenshot", str(shot))
    print(f"report screenshot: {shot}", flush=True)
    warnings.warn(UserWarning(f"report screenshot: {shot}"), stacklevel=1)


@pytest.mark.parametrize("viewport", [DESKTOP, PHONE], ids=["desktop", "phone"])
def test_the_verdicts_come_first_and_read_at_a_desktop_and_a_phone(browser, demo_report, viewport,
                                                                   tmp_path):
    """What a maintainer acts on opens the page: right under the title, each side's verdict in
    words and as a coloured badge (the fault's red against the copy's amber), the fault's kind and
    size, and who leads by how much; the reasons readable without a mouse's hover (a phone has
    none); then the tables, each figure captioned; no sideways scrolling of the page at either
    width (a wide table scrolls in its own box)."""
    found = inspect(browser, demo_report, viewport=viewport,
                    screenshot=tmp_path / f"report_{viewport['width']}.png")
    assert found["first_section"] == "section#summary", found["first_section"]
    top = found["top"]
    assert top["section#summary"] < top["table#verdicts"] < top["table.claims"] < top["figure"], top
    assert top["section#summary"] < viewport["height"] / 2      # on the first screen, high up
    s = found["summary"]
    # the synthetic case: a BPFO defect on the left, its copy on the right, the left leading
    left, right = (line for line in s.splitlines() if "(ws2_" in line)
    assert "real fault" in left and "outer ring" in left and "size:" in left, left
    assert "pseudo-fault" in right and "not this bearing's" in right, right
    assert "ws2_L leads" in s and "ms after" in s, s
    badges = dict(found["badges"])
    assert set(badges) == {"real fault", "pseudo-fault"} and len(set(badges.values())) == 2, badges
    assert "lines here" in found["reasons"] and "lines here" not in s   # a tap away, not hidden
    assert found["captions"] and all(len(c) > 20 for c in found["captions"]), found["captions"]
    assert found["scroll_width"] <= viewport["width"], found["scroll_width"]
    assert not broken_images(found) and found["errors"] == []


def test_report_page_reads_without_javascript(browser, demo_report):
    on = inspect(browser, demo_report)
    off = inspect(browser, demo_report, javascript=False)
    assert off["verdicts"] == on["verdicts"] and off["conclusions"] == on["conclusions"]
    assert len(off["images"]) == len(on["images"]) and not broken_images(off)


def test_inspect_flags_a_missing_image_and_a_script_error(browser, tmp_path):
    """The checks can fail: a page with an image that is not there and a script that throws."""
    import matplotlib.pyplot as plt
    plt.imsave(tmp_path / "there.png", np.zeros((4, 4)))
    page = tmp_path / "index.html"
    page.write_text("<!doctype html><html><body><table id='verdicts'><tr><td>verdict</td></tr>"
                    "</table><img src='there.png'><img src='gone.png'>"
                    "<script>console.error('logged'); undefinedCall();</script></body></html>")
    found = inspect(browser, page)
    assert broken_images(found) == ["gone.png"]
    assert found["verdicts"] == "verdict" and found["conclusions"] is None
    assert "logged" in found["console"]
    assert any("undefinedCall" in e for e in found["errors"]), found["errors"]
