"""Before and after in one run: a benchmark script of this checkout and of an earlier commit, run
alternately on the same machine, each figure of their tables best of several.

    python3 benchmarks/ab.py REV [--runs 3] -- exchange.py --duration 0.3

REV (any git revision) is exported to a temporary folder; each tree is imported through a folder
of links in the installed layout (``axlebox/`` with ``mbs/``, ``bearing/``, ...) put first on
``PYTHONPATH``, so an editable install of this checkout does not mask the other.  The script
(a path under ``benchmarks/``) runs from each tree's own ``benchmarks/``, once per tree to compile
(each tree's kernels go in their own cache folder, named by their sources: axlebox/_numba.py),
then ``--runs`` times each, in the order before after, after before, ... so that the machine's drift falls on
both alike.  Every row of a markdown table the script prints (``| label | x | y |``) is a
figure per number column after the first ``--key`` cells, which name it: printed with its best
(lowest) and worst value in each tree and the ratio of the bests, after / before.  For a figure
where higher is better (a speed-up) read the worst column.
"""
from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tarfile
import tempfile
from io import BytesIO
from pathlib import Path

HERE = Path(__file__).resolve().parents[1]
SUBPACKAGES = ("geometry", "fem", "mbs", "bearing", "pipelines", "configs")
ROW = re.compile(r"^\|(.+)\|\s*$")
NUMBER = re.compile(r"^[-+]?\d+(\.\d+)?([eE][-+]?\d+)?$")


def export(rev: str, dest: Path) -> Path:
    """The tree of ``rev`` in ``dest/tree``."""
    data = subprocess.run(["git", "archive", rev], cwd=HERE, check=True, capture_output=True).stdout
    tree = dest / "tree"
    tree.mkdir(parents=True)
    with tarfile.open(fileobj=BytesIO(data)) as tar:
        tar.extractall(tree, filter="data")
    return tree


def layout(tree: Path, dest: Path) -> Path:
    """A folder holding ``axlebox/`` in the installed layout, of links into ``tree``."""
    top = dest / "axlebox"
    top.mkdir(parents=True)
    for f in (tree / "axlebox").iterdir():
        if f.suffix == ".py":
            (top / f.name).symlink_to(f)
    for sub in SUBPACKAGES:
        (top / sub).symlink_to(tree / sub, target_is_directory=True)
    return dest


def figures(text: str, key: int = 1) -> dict:
    """``(row name, column) -> number`` of every markdown table row in ``text``: the row named
    by its first ``key`` cells, a number column after them."""
    out = {}
    for line in text.splitlines():
        m = ROW.match(line.strip())
        if not m:
            continue
        cells = [c.strip() for c in m.group(1).split("|")]
        for j, c in enumerate(cells[key:], key):
            if NUMBER.match(c):
                out[(" / ".join(cells[:key]), j)] = float(c)
    return out


def run(tree: Path, path: Path, script: list[str]) -> str:
    """The script's output, run in ``tree/benchmarks`` with ``path`` first on PYTHONPATH."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(path)] + os.environ.get("PYTHONPATH", "").split(
        os.pathsep))}
    p = subprocess.run([sys.executable, script[0], *script[1:]], cwd=tree / "benchmarks", env=env,
                       capture_output=True, text=True)
    if p.returncode:
        raise SystemExit(f"{script[0]} in {tree} failed ({p.returncode}):\n{p.stderr[-3000:]}")
    return p.stdout


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("rev", help="the earlier commit (before)")
    ap.add_argument("--runs", type=int, default=3, help="timed runs of each tree (default 3)")
    ap.add_argument("--key", type=int, default=1, help="the cells that name a table row (default 1)")
    ap.add_argument("--script-of", choices=("each", "after"), default="each",
                    help="each tree's own script (default), or this checkout's in both (a script "
                         "that only uses what both trees have)")
    ap.usage = "%(prog)s REV [--runs N] [--key N] [--script-of each|after] -- SCRIPT [ARGS]"
    argv = sys.argv[1:] if argv is None else list(argv)
    if "--" not in argv or argv.index("--") == len(argv) - 1:
        ap.error("expected -- SCRIPT [ARGS] (a script of benchmarks/) after the options")
    cut = argv.index("--")
    a, script = ap.parse_args(argv[:cut]), argv[cut + 1:]
    if a.runs < 1 or a.key < 1:
        ap.error(f"--runs {a.runs} --key {a.key} is not allowed: expected at least 1 each")
    with tempfile.TemporaryDirectory(prefix="axlebox-ab-") as tmp:
        tmp = Path(tmp)
        before = export(a.rev, tmp / "before")
        scripts = before if a.script_of == "each" else HERE
        trees = {"before": (scripts, layout(before, tmp / "before" / "path")),
                 "after": (HERE, layout(HERE, tmp / "after" / "path"))}
        for name, (tree, path) in trees.items():              # compile, not timed
            print(f"{name}: compiling ({tree})", file=sys.stderr, flush=True)
            run(tree, path, script)
        got = {name: [] for name in trees}
        for i in range(a.runs):
            for name in (("before", "after") if i % 2 == 0 else ("after", "before")):
                print(f"run {i + 1}/{a.runs}: {name}", file=sys.stderr, flush=True)
                got[name].append(figures(run(*trees[name], script), a.key))
    keys = [k for k in got["before"][0] if all(k in g for runs in got.values() for g in runs)]
    print(f"| figure ({' '.join(script)}) | before best | before worst | after best | after worst "
          "| after / before |\n| --- | --- | --- | --- | --- | --- |")
    for k in keys:
        b = [g[k] for g in got["before"]]
        f = [g[k] for g in got["after"]]
        ratio = f"{min(f) / min(b):.3f}" if min(b) else "-"
        print(f"| {k[0]} [{k[1]}] | {min(b):g} | {max(b):g} | {min(f):g} | {max(f):g} | {ratio} |")


if __name__ == "__main__":
    main()
