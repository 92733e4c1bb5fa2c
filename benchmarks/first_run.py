"""A first run on a fresh machine: ``axlebox simulate validation_48kmh --duration 0.01`` with numba's
cache empty (the bodies, meshes and contact tables already built: the compile alone), with and
without compiling ahead in a second process (pipelines/ahead.py; ``AXLEBOX_COMPILE_AHEAD=0``), and
once more warm; with ``--demo`` also ``axlebox demo`` with every cache empty, cold and warm.
Each cold case in a cache folder of its own (the built bodies copied in), the cases side by side,
best of ``--repeats``.

    python3 benchmarks/first_run.py [--repeats 2] [--demo]
"""
from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

from axlebox._cache import cache_dir

KEEP = ("bodies", "meshes", "wheelrail")          # what a cold compile finds built


def _run(cmd, env) -> tuple[float, str]:
    t0 = time.perf_counter()
    r = subprocess.run(cmd, env=env, capture_output=True, text=True, cwd=tempfile.gettempdir())
    if r.returncode:
        raise SystemExit(f"{' '.join(cmd)} exited {r.returncode}: {r.stderr[-2000:]}")
    return time.perf_counter() - t0, r.stdout + r.stderr


def _ready(text: str) -> str:
    m = re.search(r"model ready in ([0-9.]+) s", text)
    return m.group(1) if m else "-"


def simulate_case(ahead: bool, warm_too: bool) -> tuple[float, str, float | None]:
    root = Path(tempfile.mkdtemp(prefix="axlebox-first-run-"))
    try:
        for part in KEEP:
            src = cache_dir(part)
            if src.is_dir():
                shutil.copytree(src, root / part)
        env = dict(os.environ, AXLEBOX_CACHE=str(root), AXLEBOX_COMPILE_AHEAD="1" if ahead else "0")
        env.pop("NUMBA_CACHE_DIR", None)
        cmd = ["axlebox", "simulate", "validation_48kmh", "--duration", "0.01", "--out",
               str(root / "run.h5")]
        cold, text = _run(cmd, env)
        warm = _run(cmd, env)[0] if warm_too else None
        return cold, _ready(text), warm
    finally:
        shutil.rmtree(root, ignore_errors=True)


def demo_case() -> tuple[float, float]:
    root = Path(tempfile.mkdtemp(prefix="axlebox-first-demo-"))
    try:
        env = dict(os.environ, AXLEBOX_CACHE=str(root / "cache"))
        env.pop("NUMBA_CACHE_DIR", None)
        cmd = ["axlebox", "demo", "--out", str(root / "demo")]
        cold = _run(cmd, env)[0]
        return cold, _run(cmd, env)[0]
    finally:
        shutil.rmtree(root, ignore_errors=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--demo", action="store_true", help="time the demo too (empty caches)")
    a = ap.parse_args()
    print(f"{os.cpu_count()} cores; best of {a.repeats}")
    rows = {"compiled ahead": [], "one process": []}
    warm = []
    for r in range(a.repeats):
        for name, ahead in (("compiled ahead", True), ("one process", False)):
            cold, ready, w = simulate_case(ahead, warm_too=ahead)
            rows[name].append((cold, ready))
            if w is not None:
                warm.append(w)
            print(f"  run {r + 1}: {name}: cold {cold:.1f} s (model ready in {ready} s)"
                  + (f", warm {w:.1f} s" if w is not None else ""), flush=True)
    print("simulate validation_48kmh --duration 0.01, numba's cache empty:")
    for name, got in rows.items():
        best = min(got)
        print(f"  {name:15s} {best[0]:6.1f} s wall (model ready in {best[1]} s)")
    print(f"  warm            {min(warm):6.1f} s wall")
    if a.demo:
        cold, w = demo_case()
        print(f"demo, every cache empty: {cold:.1f} s cold, {w:.1f} s warm")


if __name__ == "__main__":
    main()
