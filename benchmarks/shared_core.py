"""The full car beside another process (issue 58, item 3): how the wait policy of the bearings'
parallel region turns a core shared with someone else into a stall.

    python3 benchmarks/shared_core.py [--duration 0.2] [--repeats 2] [--policies ...]

Each policy runs ``axlebox simulate validation_48kmh --duration D`` in a fresh process (warm: one
run first fills the kernel cache), alone and beside a plain busy loop in another process (one
core of the machine kept busy, as a sweep's worker, a CI run or a user's shell would), best of
``--repeats``; the figure is the integration's own wall time (the run's log).  The policies are
environment settings read by GNU OpenMP (libgomp, numba's ``omp`` layer) when it loads:

* ``default``: nothing set (libgomp spins 300 000 iterations before it sleeps);
* ``passive``: ``OMP_WAIT_POLICY=PASSIVE`` (waiting threads sleep at once);
* ``spin=N``: ``GOMP_SPINCOUNT=N``;
* ``1 thread``: ``NUMBA_NUM_THREADS=1`` (no parallel region to wait in);
* ``tbb``, ``workqueue``: numba's other threading layers (``NUMBA_THREADING_LAYER``).

Prints one row a policy: wall seconds alone, beside the busy loop, and their ratio.
"""
from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

POLICIES = {"default": {}, "passive": {"OMP_WAIT_POLICY": "PASSIVE"},
            "spin=10000": {"GOMP_SPINCOUNT": "10000"}, "1 thread": {"NUMBA_NUM_THREADS": "1"},
            "tbb": {"NUMBA_THREADING_LAYER": "tbb"}, "workqueue": {"NUMBA_THREADING_LAYER": "workqueue"}}
WALL = re.compile(r"simulated in ([0-9.]+) s wall")


def run(env_extra: dict, duration: float, folder: Path) -> float:
    out = folder / f"car{len(list(folder.iterdir()))}.h5"         # a fresh run, not a resumed one
    env = {k: v for k, v in os.environ.items()
           if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT", "NUMBA_NUM_THREADS",
                         "NUMBA_THREADING_LAYER", "NUMBA_THREADING_LAYER_PRIORITY")}
    env.update(env_extra)
    p = subprocess.run([sys.executable, "-m", "axlebox", "simulate", "validation_48kmh", "--duration",
                        str(duration), "--out", str(out), "--checkpoint-every", "0"],
                       env=env, capture_output=True, text=True)
    if p.returncode:
        raise RuntimeError((p.stdout + p.stderr).strip().splitlines()[-1])
    m = WALL.search(p.stdout + p.stderr)
    if m is None:
        raise RuntimeError(f"no wall time in the run's log: {p.stdout[-500:]} {p.stderr[-500:]}")
    return float(m.group(1))


def busy() -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-c", "while True: pass"])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--duration", type=float, default=0.2)
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--policies", nargs="*", default=list(POLICIES),
                    help=f"of {', '.join(POLICIES)}, or spin=N")
    a = ap.parse_args()
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as d:
        out = Path(d)
        run({}, 0.01, out)                                  # the kernel cache, warm
        rows = []
        for name in a.policies:
            env = POLICIES[name] if name in POLICIES else {"GOMP_SPINCOUNT": name.split("=", 1)[1]}
            try:
                run(env, 0.01, out)
            except RuntimeError as err:                      # a layer numba cannot load here
                print(f"{name}: not run ({err})", flush=True)
                continue
            alone = min(run(env, a.duration, out) for _ in range(a.repeats))
            b = busy()
            try:
                beside = min(run(env, a.duration, out) for _ in range(a.repeats))
            finally:
                b.kill()
                b.wait()
            rows.append((name, alone, beside))
            print(f"{name}: alone {alone:.1f} s, beside a busy loop {beside:.1f} s", flush=True)
    print("\n| policy | alone (s) | beside a busy loop (s) | ratio | wall s per simulated s alone |")
    print("| --- | --- | --- | --- | --- |")
    for name, alone, beside in rows:
        print(f"| {name} | {alone:.1f} | {beside:.1f} | {beside / alone:.2f} | {alone / a.duration:.1f} |")
    print(f"{os.cpu_count()} cores; {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
