"""What the kernels' grouped arguments cost (issue 68): the parts whose arguments travel as named
tuples, timed inside compiled loops, so that a call's overhead is not hidden behind Python's.

    python3 benchmarks/grouping.py [--calls 2000] [--repeats 7]

* the car's right-hand side (``axlebox.mbs.kernel.system.rhs``: its wheel-rail stage,
  ``wheel_forces``, whose grouping was tried and dropped), on the rigid car and with the front
  bogie flexible, at the statics' state and 0.6 s into a run (the irregularity faded in, the
  contacts creeping);
* FASTSIM's forces per contact (``fastsim_batch``: ``_fastsim`` with its maps None), the default
  grid, over the creepage sweep of benchmarks/fastsim.py;
* the car's whole runs are benchmarks/vehicle.py's and benchmarks/exchange.py's.

Only interfaces that the tree before the grouping has as well, so that ``benchmarks/ab.py REV
--script-of after -- grouping.py`` runs this one script on both.  Microseconds a call, best of
``--repeats`` loops of ``--calls`` calls, one thread.

``--instructions``: instructions instead, counted by valgrind's callgrind (the same count run to
run, whatever else the machine does): the cars' packed arrays saved, then one process that loads
them and makes ``--calls`` and ``3 --calls`` right-hand sides of each in a compiled loop, and one
kernel call of each integrator's run (its outputs, its guard, generalized-alpha's Newton: the
grouped arguments) on the rigid car over ``n`` and ``3 n`` steps, each after a warm one,
callgrind collecting around each alone (a toggle compiled from valgrind's callgrind.h).  The
figure is the difference of the two lengths over the calls or steps between, so that what a
call costs once (the dispatch, the first touch of memory) falls out.
"""
from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import time  # noqa: E402
from functools import partial  # noqa: E402

import numpy as np  # noqa: E402
from numba import njit  # noqa: E402

from axlebox import configs  # noqa: E402
from axlebox.mbs.kernel.system import rhs  # noqa: E402
from axlebox.mbs.wheelrail import fastsim_kernel as fk  # noqa: E402
from axlebox.mbs.wheelrail import tangential as tg  # noqa: E402
from axlebox.pipelines import simulate as psim  # noqa: E402


@njit
def _rhs_loop(n, t, y, dy, S, W, B):
    for _ in range(n):
        rhs(t, y, dy, S, W, B)


def rhs_calls(model, t, y):
    """``n -> n`` calls of the model's right-hand side at ``(t, y)``, in one compiled loop."""
    dy = np.zeros_like(y)
    return lambda n: _rhs_loop(n, t, y, dy, model.S, model.W, model.B)


def best_us(loop, calls: int, repeats: int) -> float:
    loop(1)                                     # compile or load
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        loop(calls)
        best = min(best, (time.perf_counter() - t0) / calls * 1e6)
    return best


def car(flexible):
    over = {"joint": {"model": "bushing"}, "defects": [], "coupling": {"exchange_dt": 0.0},
            "integrator": {"method": "leapfrog", "dt": 2.5e-5, "output_rate_hz": 2e4},
            "bodies": {"flexible": flexible}}
    cfg = psim.load_config(configs.path("validation_48kmh"), 0.6, over)
    model, y0 = psim.build_model(cfg, log=lambda *_: None)
    run = psim.integrate.simulate(model, 0.6, cfg.settings(), y0=y0)
    assert run.ok, run.message
    return model, {"statics": (0.0, y0), "0.6 s": (0.6, run.y_end)}


FRONT = ["frame1", "ws1", "ws2", "ab1L", "ab1R", "ab2L", "ab2R"]
CARS = (("rigid car", []), ("flexible front bogie", FRONT))


TOGGLE = """#include <valgrind/callgrind.h>
void axlebox_toggle(void) { CALLGRIND_TOGGLE_COLLECT; }
void axlebox_dump(void) { CALLGRIND_DUMP_STATS; }
"""
#: the runs counted: method, step (s), outputs at 1e4 Hz
RUNS = (("rk4", 2.5e-5, 20), ("leapfrog", 2.5e-5, 20), ("galpha", 5e-5, 20))


def save(path: Path, model, t, y) -> None:
    """What a counting process needs of ``model`` at ``(t, y)``."""
    pattern, groups, n_groups = model.coupling_pattern()
    scale, atol = model.state_scales()
    np.savez(path, t=t, y=y, nq=model.nq, nend=model.n_body_states, pattern=pattern, groups=groups,
             n_groups=n_groups, scale=scale, atol=atol,
             **{f"S/{k}": v for k, v in model.S._asdict().items()},
             **{f"W/{k}": v for k, v in model.W._asdict().items()})


def run_chunk(f, S, W, B, method: str, h: float, n_out: int) -> None:
    """One kernel call of ``method`` over ``n_out`` outputs from the saved state, with this tree's
    signature (the arguments grouped or one by one)."""
    from axlebox.mbs.kernel import integrate as ki
    from axlebox.mbs.kernel.exchange import exchange
    y = f["y"].copy()
    n_sub = int(round(1e-4 / h))
    bufs = (np.zeros(n_out), np.zeros((n_out,) + W.sensout.shape), np.zeros((n_out,) + W.whout.shape),
            np.zeros((n_out,) + W.elout.shape), np.zeros((n_out, y.size)))
    guard = (int(f["nq"]), int(f["nend"]), 1e3)
    newton = (0.8, f["groups"], int(f["n_groups"]), f["pattern"], f["scale"], f["atol"], 1e-9, 8,
              np.zeros(5, np.int64))
    threads = np.zeros(3, np.int64)                  # axlebox/_threads.py: no count wanted
    head = (y, 0.0, h, n_sub, n_out, 0, n_out - 1, S, W, B)
    X = exchange(type("M", (), {"bearing_names": []}), "leapfrog", h, 1)
    if hasattr(ki, "Outputs"):                       # grouped (issue 68)
        G, O, N = ki.Guard(*guard), ki.Outputs(*bufs, 1, 0), ki.Newton(*newton)
        if method == "rk4":
            ki.run_rk4(*head, G, O, threads)
        elif method == "leapfrog":
            ki.run_leapfrog(*head, X, G, O, True, threads)
        else:
            ki.run_galpha(*head, G, O, N, threads)
    elif method == "rk4":
        ki.run_rk4(*head, *guard, *bufs, 1, 0, threads)
    elif method == "leapfrog":
        ki.run_leapfrog(*head, X, *guard, *bufs, 1, True, 0, threads)
    else:
        ki.run_galpha(*head, *guard, *bufs, 1, *newton, 0, threads)


def count(cases: list[Path], calls: int, lib: str | None = None) -> None:
    """The counting process (:func:`instructions`): for each saved case ``calls`` and ``3 calls``
    right-hand sides in a compiled loop, then, for the first, each of :data:`RUNS` over its
    outputs and three times as many; each after a warm one, callgrind collecting around it alone
    and dumping its count (``lib``: the toggle)."""
    import ctypes

    from axlebox.mbs.kernel.bearings import NoBearings
    from axlebox.mbs.kernel.system import Arrays, Work, lanes
    c = ctypes.CDLL(lib) if lib else None

    def counted(*fns):
        fns[0]()
        for fn in fns:
            if c:
                c.axlebox_toggle()
            fn()
            if c:
                c.axlebox_toggle()
                c.axlebox_dump()
    for k, case in enumerate(cases):
        f = dict(np.load(case))
        S = Arrays(*(f[f"S/{n}"] if f"S/{n}" in f else lanes(f["S/bi"]) for n in Arrays._fields))
        W = Work(*(f[f"W/{n}"] for n in Work._fields))
        B = NoBearings()
        loop = rhs_calls(type("M", (), {"S": S, "W": W, "B": B}), float(f["t"]), f["y"])
        counted(partial(loop, calls), partial(loop, 3 * calls))
        if k == 0:
            for method, h, n_out in RUNS:
                counted(*(partial(run_chunk, f, S, W, B, method, h, n) for n in (n_out, 3 * n_out)))


def instructions(calls: int) -> list:
    """Instructions a right-hand side of each car 0.6 s into its run, and a step of each
    method's run on the rigid car from there: callgrind collecting only around each, one length
    and three times it, their difference over the calls or steps between (module docstring)."""
    with tempfile.TemporaryDirectory(prefix="axlebox-grouping-") as tmp:
        tmp = Path(tmp)
        lib = tmp / "toggle.so"
        (tmp / "toggle.c").write_text(TOGGLE)
        subprocess.run(["gcc", "-O2", "-shared", "-fPIC", "-o", str(lib), str(tmp / "toggle.c")], check=True)
        cases = []
        for k, (_, flexible) in enumerate(CARS):
            model, states = car(flexible)
            cases.append(tmp / f"case{k}.npz")
            save(cases[-1], model, *states["0.6 s"])
        me = [sys.executable, __file__, "--calls", str(calls), "--count", *map(str, cases)]
        subprocess.run(me, check=True)                    # the kernels of these types cached
        p = subprocess.run(["valgrind", "--tool=callgrind", "--collect-atstart=no",
                            f"--callgrind-out-file={tmp}/cg.out", *me, "--toggle", str(lib)],
                           capture_output=True, text=True)
        parts = sorted(tmp.glob("cg.out.*"), key=lambda q: int(q.suffix[1:]))
        totals = [int(re.search(r"^(?:totals|summary): (\d+)", q.read_text(), re.M).group(1)) for q in parts]
        if p.returncode or len(totals) != 2 * (len(CARS) + len(RUNS)):
            raise SystemExit(f"callgrind failed ({p.returncode}, {len(totals)} counts):\n{p.stderr[-2000:]}")
    # the dumps in count()'s order, two each: the first car's right-hand side, its runs, the others'
    order = [("rhs", CARS[0][0])] + [("run", r) for r in RUNS] + [("rhs", label) for label, _ in CARS[1:]]
    rows = []
    for (what, which), (short, long) in zip(order, zip(totals[::2], totals[1::2])):
        if what == "rhs":
            rows.append((f"rhs, {which}, 0.6 s: instructions a call", (long - short) / (2 * calls)))
        else:
            m, h, n_out = which
            steps = n_out * int(round(1e-4 / h))
            rows.append((f"{m} run, rigid car, steps of {h:g} s: instructions a step",
                         (long - short) / (2 * steps)))
            rows.append((f"{m} run, rigid car: instructions of one call of {steps} steps", short))
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--calls", type=int, default=2000)
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--instructions", action="store_true", help="count instructions by callgrind")
    ap.add_argument("--count", type=Path, nargs="+", help=argparse.SUPPRESS)   # callgrind's process
    ap.add_argument("--toggle", help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.count:
        return count(a.count, a.calls, a.toggle)
    if a.instructions:
        rows = instructions(a.calls)
        print("| part | instructions |\n| --- | --- |")
        for name, n in rows:
            print(f"| {name} | {n:.0f} |")
        return
    rows = []
    for label, flexible in CARS:
        model, states = car(flexible)
        for when, (t, y) in states.items():
            us = best_us(rhs_calls(model, t, y), a.calls, a.repeats)
            rows.append((f"rhs, {label}, {when}", us))
    rng = np.random.default_rng(7)
    xi, eta = rng.uniform(-0.01, 0.01, (2, 2000))
    phi = rng.uniform(-1.0, 1.0, 2000)
    L1, L2, L3 = tg.flexibilities(6e-3, 4e-3, 8.1e10, 0.28)
    args = [np.ascontiguousarray(v, dtype=float) for v in
            np.broadcast_arrays(xi, eta, phi, 6e-3, 4e-3, 7e4, 0.3, L1, L2, L3)]
    out = np.empty((xi.size, 3))

    def batches(n):
        for _ in range(n):
            fk.fastsim_batch(*args, 0, 0, tg.NX, tg.NY, out)
    per = best_us(batches, max(1, a.calls // 200), a.repeats) / xi.size
    rows.append((f"FASTSIM forces per contact, {tg.NX} x {tg.NY}", per))
    print("| part | us a call |\n| --- | --- |")
    for name, us in rows:
        print(f"| {name} | {us:.3f} |")


if __name__ == "__main__":
    main()
