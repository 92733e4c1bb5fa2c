"""The full car beside another process (issue 58, item 3): how the wait policy of the bearings'
parallel region turns a core shared with someone else into a stall, and what fitting the threads
to the free cores (axlebox/_threads.py) makes of it.

    python3 benchmarks/shared_core.py [--duration 0.2] [--repeats 2] [--policies ...]

Each policy runs ``axlebox simulate validation_48kmh --duration D`` in a fresh process (warm: one
run first fills the kernel cache), alone and beside a plain busy loop in another process (one
core of the machine kept busy, as a sweep's worker, a CI run or a user's shell would), best of
``--repeats``, the policies' runs interleaved (drift on a shared machine falls on all alike);
the figure is the integration's own wall time (the run's log).  The policies are environment
settings: ``AXLEBOX_THREADS`` (``fit``, the package's default: the threads follow the cores free
of other processes; ``fixed``: main's behaviour before it, the count kept) and those read by GNU
OpenMP (libgomp, numba's ``omp`` layer) when it loads:

* ``fixed``: the count kept, nothing else set (libgomp spins 300 000 iterations before it sleeps);
* ``fit``: nothing set (the package's default);
* ``fit, passive``: ``OMP_WAIT_POLICY=PASSIVE`` with the fitting;
* ``passive``: ``OMP_WAIT_POLICY=PASSIVE`` (waiting threads sleep at once), the count kept;
* ``spin=N``: ``GOMP_SPINCOUNT=N``, the count kept;
* ``1 thread``: ``NUMBA_NUM_THREADS=1`` (no parallel region to wait in);
* ``tbb``, ``workqueue``: numba's other threading layers (``NUMBA_THREADING_LAYER``), the count kept.

Prints one row a policy: wall seconds alone, beside the busy loop, and their ratio; then, where
``fixed``, ``fit`` and ``1 thread`` ran, item 3's bar: beside at most 1.8x the policy's own time
alone and no slower than one thread alone.
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

FIXED = {"AXLEBOX_THREADS": "fixed"}
POLICIES = {"fixed": FIXED, "fit": {}, "fit, passive": {"OMP_WAIT_POLICY": "PASSIVE"},
            "passive": {**FIXED, "OMP_WAIT_POLICY": "PASSIVE"},
            "spin=10000": {**FIXED, "GOMP_SPINCOUNT": "10000"}, "1 thread": {"NUMBA_NUM_THREADS": "1"},
            "tbb": {**FIXED, "NUMBA_THREADING_LAYER": "tbb"},
            "workqueue": {**FIXED, "NUMBA_THREADING_LAYER": "workqueue"}}
BAR = 1.8               # item 3: beside a busy core at most this times the time alone
WALL = re.compile(r"simulated in ([0-9.]+) s wall")


def run(env_extra: dict, duration: float, folder: Path) -> float:
    out = folder / f"car{len(list(folder.iterdir()))}.h5"         # a fresh run, not a resumed one
    env = {k: v for k, v in os.environ.items()
           if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT", "NUMBA_NUM_THREADS", "AXLEBOX_THREADS",
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


def load() -> str:
    try:
        return " ".join(Path("/proc/loadavg").read_text().split()[:3])
    except OSError:
        return "n/a"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--duration", type=float, default=0.2)
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--policies", nargs="*", default=["fixed", "fit", "1 thread"],
                    help=f"of {', '.join(POLICIES)}, or spin=N")
    a = ap.parse_args()
    t0 = time.perf_counter()
    envs = {name: POLICIES[name] if name in POLICIES else {**FIXED, "GOMP_SPINCOUNT": name.split("=", 1)[1]}
            for name in a.policies}
    print(f"load average at the start {load()}", flush=True)
    with tempfile.TemporaryDirectory() as d:
        out = Path(d)
        run({}, 0.01, out)                                  # the kernel cache, warm
        for name, env in list(envs.items()):
            try:
                run(env, 0.01, out)
            except RuntimeError as err:                      # a layer numba cannot load here
                print(f"{name}: not run ({err})", flush=True)
                del envs[name]
        alone = {name: [] for name in envs}
        beside = {name: [] for name in envs}
        for _ in range(a.repeats):
            for name, env in envs.items():
                alone[name].append(run(env, a.duration, out))
                print(f"{name}: alone {alone[name][-1]:.1f} s (load {load()})", flush=True)
        b = busy()
        try:
            for _ in range(a.repeats):
                for name, env in envs.items():
                    beside[name].append(run(env, a.duration, out))
                    print(f"{name}: beside a busy loop {beside[name][-1]:.1f} s (load {load()})", flush=True)
        finally:
            b.kill()
            b.wait()
    rows = [(name, min(alone[name]), min(beside[name])) for name in envs]
    print("\n| policy | alone (s) | beside a busy loop (s) | ratio | wall s per simulated s alone |")
    print("| --- | --- | --- | --- | --- |")
    for name, al, bs in rows:
        print(f"| {name} | {al:.1f} | {bs:.1f} | {bs / al:.2f} | {al / a.duration:.1f} |")
    best = {name: (al, bs) for name, al, bs in rows}
    if {"fixed", "fit", "1 thread"} <= best.keys():
        one = best["1 thread"][0]
        print(f"\n| | alone, 2 threads (s) | 1 thread alone (s) | beside a busy loop (s) | beside / alone "
              f"(bar {BAR}) | beside / 1 thread alone (bar 1) |")
        print("| --- | --- | --- | --- | --- | --- |")
        for name, what in (("fixed", "before (AXLEBOX_THREADS=fixed)"), ("fit", "after (fit, the default)")):
            al, bs = best[name]
            print(f"| {what} | {al:.1f} | {one:.1f} | {bs:.1f} | {bs / al:.2f} | {bs / one:.2f} |")
    print(f"{os.cpu_count()} cores; load average at the end {load()}; {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
