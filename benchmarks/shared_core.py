"""The full car beside another process (issue 58, item 3): how the wait policy of the bearings'
parallel region turns a core shared with someone else into a stall, and what fitting the threads
to the free cores (axlebox/_threads.py) makes of it.

    python3 benchmarks/shared_core.py [--duration 0.2] [--repeats 2] [--policies ...] [--quiet S]

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
* ``fit at chunk ends``: the same estimate, applied only between the integrator's chunks (0.25 s
  simulated, ~6 s wall alone; the kernel wrapped here, ``AXLEBOX_THREADS=fixed``): the design
  the package did not take, for comparison (a run of one chunk never switches);
* ``1 thread``: ``NUMBA_NUM_THREADS=1`` (no parallel region to wait in);
* ``tbb``, ``workqueue``: numba's other threading layers (``NUMBA_THREADING_LAYER``), the count kept.

Each run's line gives the cores its process kept busy and the thread counts its watcher chose.
``--quiet S``: before each run wait up to S s for the rest of the machine to fall below 0.3 of a
core (a machine shared with others' work: "alone" must be alone).  Prints one row a policy: wall
seconds alone, beside the busy loop, and their ratio; then, where ``fixed``, ``fit`` and
``1 thread`` ran, item 3's bar: beside at most 1.8x the policy's own time alone and no slower
than one thread alone.
"""
from __future__ import annotations

import argparse
import itertools
import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

FIXED = {"AXLEBOX_THREADS": "fixed"}
AT_CHUNK_ENDS = "AXLEBOX_BENCH_AT_CHUNK_ENDS"           # this script's own: DRIVER wraps the kernel
POLICIES = {"fixed": FIXED, "fit": {}, "fit, passive": {"OMP_WAIT_POLICY": "PASSIVE"},
            "fit at chunk ends": {**FIXED, AT_CHUNK_ENDS: "1"},
            "passive": {**FIXED, "OMP_WAIT_POLICY": "PASSIVE"},
            "spin=10000": {**FIXED, "GOMP_SPINCOUNT": "10000"}, "1 thread": {"NUMBA_NUM_THREADS": "1"},
            "tbb": {**FIXED, "NUMBA_THREADING_LAYER": "tbb"},
            "workqueue": {**FIXED, "NUMBA_THREADING_LAYER": "workqueue"}}
BAR = 1.8               # item 3: beside a busy core at most this times the time alone
WALL = re.compile(r"simulated in ([0-9.]+) s wall")
# the command line, its run's thread counts told (the watcher's choices and the kernel's switches);
# with AT_CHUNK_ENDS the leapfrog kernel wrapped: before each chunk the estimate since the last chunk
# started (axlebox/_threads.py) sets numba's count, and inside the chunk nothing switches
DRIVER = """
import os, sys, numba
from axlebox import _threads
from axlebox.mbs.solver import integrate
from axlebox.mbs.kernel import integrate as ki
from axlebox.pipelines.cli import main
class Told(_threads.Fitter):
    def __exit__(self, *exc):
        print(f"threads: {self.switches} switches, chosen {''.join(map(str, self.counts))}", file=sys.stderr)
        return super().__exit__(*exc)
integrate.Fitter = Told
if os.environ.pop(%r, None):
    watch = _threads.Fitter()
    def at_chunk_ends(kernel):
        def chunk(*args):
            others = watch.measure()
            if others is not None:
                numba.set_num_threads(_threads.fitted(others, watch.n, numba.config.NUMBA_NUM_THREADS))
            return kernel(*args)
        return chunk
    ki.run_leapfrog = at_chunk_ends(ki.run_leapfrog)
sys.exit(main(sys.argv[1:]))
""" % AT_CHUNK_ENDS
TOLD = re.compile(r"threads: (\d+) switches, chosen (\d*)")


def run(env_extra: dict, duration: float, folder: Path) -> tuple[float, float, str]:
    """One run in a fresh process: its integration's wall time (s), the CPU time of the whole
    process over its wall time (cores), and the counts its watcher chose (e.g. ``2x1 1x7``)."""
    out = folder / f"car{len(list(folder.iterdir()))}.h5"         # a fresh run, not a resumed one
    env = {k: v for k, v in os.environ.items()
           if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT", "NUMBA_NUM_THREADS", "AXLEBOX_THREADS",
                         "NUMBA_THREADING_LAYER", "NUMBA_THREADING_LAYER_PRIORITY")}
    env.update(env_extra)
    r0, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
    p = subprocess.run([sys.executable, "-c", DRIVER, "simulate", "validation_48kmh", "--duration",
                        str(duration), "--out", str(out), "--checkpoint-every", "0"],
                       env=env, capture_output=True, text=True)
    r1, t1 = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
    if p.returncode:
        raise RuntimeError((p.stdout + p.stderr).strip().splitlines()[-1])
    m = WALL.search(p.stdout + p.stderr)
    if m is None:
        raise RuntimeError(f"no wall time in the run's log: {p.stdout[-500:]} {p.stderr[-500:]}")
    told = TOLD.search(p.stderr)
    chosen = "" if told is None else " ".join(f"{len(list(g))}x{c}"
                                              for c, g in itertools.groupby(told.group(2)))
    cpu = (r1.ru_utime + r1.ru_stime - r0.ru_utime - r0.ru_stime) / (t1 - t0)
    return float(m.group(1)), cpu, chosen


def busy() -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-c", "while True: pass"])


def load() -> str:
    try:
        return " ".join(Path("/proc/loadavg").read_text().split()[:3])
    except OSError:
        return "n/a"


def quiet(ours: float, most: float, patience: float) -> float:
    """Wait until the machine's busy cores over 1 s are at most ``ours`` (this script's busy loop)
    plus ``most`` (on a machine shared with others' work, "alone" means alone), or ``patience``
    s have passed; returns the seconds waited (where /proc/stat is missing: none)."""
    from axlebox import _threads
    t0 = time.perf_counter()
    cpus = _threads.cpus()
    while time.perf_counter() - t0 < patience:
        try:
            a = _threads.cpu_jiffies(Path("/proc/stat").read_text(), cpus)
            time.sleep(1.0)
            b = _threads.cpu_jiffies(Path("/proc/stat").read_text(), cpus)
        except OSError:
            break
        if a is None or b is None or b[1] <= a[1]:
            break
        if (b[0] - a[0]) / ((b[1] - a[1]) / len(cpus)) <= ours + most:
            break
    return time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--duration", type=float, default=0.2)
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--policies", nargs="*", default=["fixed", "fit", "1 thread"],
                    help=f"of {', '.join(POLICIES)}, or spin=N")
    ap.add_argument("--quiet", type=float, default=0.0, metavar="S",
                    help="before each run wait up to S s for the machine's other work to fall below "
                         "0.3 of a core (a machine shared with others' work; default: no wait)")
    a = ap.parse_args()
    t0 = time.perf_counter()
    envs = {name: POLICIES[name] if name in POLICIES else {**FIXED, "GOMP_SPINCOUNT": name.split("=", 1)[1]}
            for name in a.policies}
    print(f"load average at the start {load()}", flush=True)
    runs = {(name, where): [] for name in envs for where in ("alone", "beside")}
    waited = 0.0
    with tempfile.TemporaryDirectory() as d:
        out = Path(d)
        run({}, 0.01, out)                                  # the kernel cache, warm
        for name, env in list(envs.items()):
            try:
                run(env, 0.01, out)
            except RuntimeError as err:                      # a layer numba cannot load here
                print(f"{name}: not run ({err})", flush=True)
                del envs[name]
        for where in ("alone", "beside"):
            b = busy() if where == "beside" else None
            try:
                for _ in range(a.repeats):
                    for name, env in envs.items():
                        waited += quiet(1.0 if b else 0.0, 0.3, a.quiet) if a.quiet > 0 else 0.0
                        wall, cpu, chosen = run(env, a.duration, out)
                        runs[name, where].append(wall)
                        print(f"{name}: {where} {wall:.1f} s, {cpu:.2f} cores busy"
                              + (f", threads chosen {chosen} (0.25 s each)" if chosen else "")
                              + f" (load {load()})", flush=True)
            finally:
                if b is not None:
                    b.kill()
                    b.wait()
    rows = [(name, min(runs[name, "alone"]), min(runs[name, "beside"])) for name in envs]
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
    print(f"{os.cpu_count()} cores; load average at the end {load()}; waited {waited:.0f} s for a quiet "
          f"machine; {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
