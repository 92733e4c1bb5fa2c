"""numba's threads fitted to the cores other processes leave free, as a run goes (issue 58, item 3).

The bearings' parallel region meets every right-hand side, 10-20 us apart.  A thread that shares
its core with another busy process is off the core for that process's whole time slice
(milliseconds), and every meeting waits for it: beside one busy loop on 2 cores the validation
car ran 3.3-3.7x slower on 2 threads, and 1.02x on one (benchmarks/README.md, "The car beside
another process").  So a run (:func:`axlebox.mbs.solver.integrate.simulate`) starts a :class:`Fitter`:
a watcher thread that every :data:`INTERVAL` s estimates the cores busy with other processes
(:func:`others_busy`, from ``/proc/stat`` less this process's own CPU time) and writes the
thread count that fits (:func:`fitted`) into a small array; the run's kernel reads it at every
output and calls numba's ``set_num_threads`` there (:func:`fit_threads`).  The switch falls
between two parallel regions and each bearing's work is the same on any thread, so the results
are the same bits on any count and with any switches (tests/test_threads.py).

The count stays between 1 and the one in effect when the run starts (``NUMBA_NUM_THREADS``, or
``numba.set_num_threads`` of the caller: a sweep's worker), so a user's setting is a ceiling;
``AXLEBOX_THREADS=fixed`` (:class:`ThreadSettings`) keeps it through the run.  Without
``/proc/stat`` (not Linux) the count stays too.
"""
from __future__ import annotations

import os
import threading
from dataclasses import dataclass

import numba
import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic

from . import _numba  # noqa: F401 - numba's settings made before its threads start
from ._params import _check_field, choice

ENV = "AXLEBOX_THREADS"
MODES = ("fit", "fixed")
INTERVAL = 0.25        # s between two estimates: a fraction of a 0.25 s chunk's ~6 s wall
# a core others keep busy this fraction of the time counts as theirs: two threads run 3.6x slower
# while the other process runs and one thread 1.75x two's time alone (benchmarks/README.md), so
# two are the faster while 1 + 2.6 f < 1.75, f < 0.29
TAKEN = 0.3
STAT = "/proc/stat"
# the array a run's kernel reads: the count wanted (0: leave it), the count in effect, switches made
WANT, NOW, SWITCHES = range(3)


@dataclass(frozen=True)
class ThreadSettings:
    """How a run's numba threads are chosen: the environment variable ``AXLEBOX_THREADS``."""

    mode: str = choice("fit", MODES, doc="'fit': the threads follow the cores free of other "
                       "processes, between 1 and the count in effect at the run's start; 'fixed': "
                       "that count throughout (a busy core beside it stalls every parallel region)")

    def __post_init__(self):
        for f in self.__dataclass_fields__.values():
            _check_field(ENV, f, getattr(self, f.name))

    @classmethod
    def from_env(cls, env=None) -> ThreadSettings:
        """The settings ``env`` (default ``os.environ``) holds; a bad value is a ParameterError
        naming ``AXLEBOX_THREADS``, the value and what is allowed."""
        value = (os.environ if env is None else env).get(ENV, "").strip()
        return cls(mode=value) if value else cls()


def cpus() -> list[int]:
    """The CPUs this process may run on (its affinity mask; every CPU where there is none)."""
    try:
        return sorted(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return list(range(os.cpu_count() or 1))


def cores() -> int:
    """How many cores this process may run on: the size of its affinity mask."""
    return len(cpus())


def cpu_jiffies(text: str, which) -> tuple[int, int] | None:
    """``(busy, all)`` clock ticks of the CPUs ``which`` since boot from the text of
    ``/proc/stat`` (lines ``cpuN user nice system idle iowait irq softirq steal ...``; busy: all
    but idle and iowait; ``guest`` is already in ``user``), or None where a CPU has no line."""
    want = {f"cpu{c}" for c in which}
    busy = total = seen = 0
    for line in text.splitlines():
        parts = line.split()
        if parts and parts[0] in want:
            v = [int(x) for x in parts[1:9]] + [0] * (9 - len(parts))
            idle = v[3] + v[4]
            b = v[0] + v[1] + v[2] + v[5] + v[6] + v[7]
            busy += b
            total += b + idle
            seen += 1
    return (busy, total) if seen == len(want) else None


def others_busy(before, after, n: int) -> float:
    """Cores kept busy by other processes between two readings ``(busy, all, own)`` in clock
    ticks (:func:`cpu_jiffies` of ``n`` CPUs and this process's CPU time): the busy ticks less
    this process's own, over the ticks one core had."""
    span = (after[1] - before[1]) / n
    if span <= 0:
        return 0.0
    return max(0.0, (after[0] - before[0] - (after[2] - before[2])) / span)


def fitted(others: float, n: int, ceiling: int) -> int:
    """The threads for ``n`` cores of which other processes keep ``others`` busy: a core counts
    as taken from a :data:`TAKEN` share of it on (a waiting thread loses a whole time slice to
    each of its turns); at least 1, at most ``ceiling``."""
    taken = int(others + 1.0 - TAKEN)
    return max(1, min(ceiling, n - taken))


class Fitter:
    """The watcher of a run: every ``interval`` s, the count :func:`fitted` to the cores free of
    other processes into ``shared[WANT]``, which the run's kernel applies (:func:`fit_threads`).
    A context manager around the run, entered in the thread that runs the kernels (numba's count
    is that thread's): inside it the watcher runs, between 1 and the count in effect at the
    entry (the ceiling), which is put back at the exit.  ``measure()``: the cores kept busy by
    other processes since its last call, or None where it cannot tell (default: from
    ``/proc/stat``, :func:`others_busy`); ``fit`` False: no watcher, the count stays."""

    def __init__(self, measure=None, interval: float = INTERVAL, fit: bool = True):
        self.measure = measure if measure is not None else self._proc_stat
        self.interval = interval
        self.fit = fit
        self.n = cores()
        self.ceiling = 1
        self.shared = np.zeros(3, np.int64)
        self.counts: list[int] = []          # each count written (what the benchmarks report)
        self._stop = threading.Event()
        self._thread = None
        self._last = None

    @classmethod
    def from_env(cls, env=None) -> Fitter:
        """The fitter ``AXLEBOX_THREADS`` (:class:`ThreadSettings`) asks for."""
        return cls(fit=ThreadSettings.from_env(env).mode == "fit")

    def _reading(self):
        try:
            with open(STAT) as f:
                cpu = cpu_jiffies(f.read(), cpus())
        except OSError:
            return None
        if cpu is None:
            return None
        t = os.times()
        return (*cpu, round((t.user + t.system) * TICK))

    def _proc_stat(self) -> float | None:
        now = self._reading()
        before, self._last = self._last, now
        if before is None or now is None:
            return None
        return others_busy(before, now, self.n)

    def step(self) -> None:
        """One estimate, and the count it gives into ``shared[WANT]``."""
        others = self.measure()
        if others is not None:
            n = fitted(others, self.n, self.ceiling)
            self.shared[WANT] = n
            self.counts.append(n)

    def _watch(self):
        while not self._stop.wait(self.interval):
            self.step()

    def __enter__(self) -> Fitter:
        self.ceiling = numba.get_num_threads()        # also loads the threading layer's symbols
        self.shared[:] = (0, self.ceiling, 0)
        self._stop.clear()
        if self.fit and self.ceiling > 1:
            self._last = None
            self.measure()                    # the first reading: the next one has an interval
            self._thread = threading.Thread(target=self._watch, name="axlebox-threads", daemon=True)
            self._thread.start()
        return self

    def __exit__(self, *exc):
        if self._thread is not None:
            self._stop.set()
            self._thread.join()
            self._thread = None
        if self.shared[NOW] != self.ceiling:
            numba.set_num_threads(self.ceiling)
        return False

    @property
    def switches(self) -> int:
        """The switches the last run's kernel made."""
        return int(self.shared[SWITCHES])


try:
    TICK = os.sysconf("SC_CLK_TCK")          # /proc/stat's clock ticks a second
except (AttributeError, ValueError, OSError):
    TICK = 100


@intrinsic
def _set_num_threads(typingctx, n):
    """numba's ``set_num_threads`` by its symbol (the threading layer's C function): numba's
    own jitted one calls it through a ctypes pointer, which keeps the caller out of the cache."""
    from numba.np.ufunc.parallel import _launch_threads
    _launch_threads()                          # registers the symbol with LLVM

    def codegen(context, builder, sig, args):
        fnty = ir.FunctionType(ir.VoidType(), [ir.IntType(32)])
        fn = cgutils.get_or_insert_function(builder.module, fnty, "set_num_threads")
        builder.call(fn, [builder.trunc(args[0], ir.IntType(32))])
        return context.get_dummy_value()
    return types.void(types.int64), codegen


@njit(cache=True)
def fit_threads(shared):
    """The count a :class:`Fitter` wrote into ``shared[WANT]``, made this thread's count of numba
    threads (between two parallel regions: called where none runs)."""
    n = shared[WANT]
    if n > 0 and n != shared[NOW]:
        _set_num_threads(n)
        shared[NOW] = n
        shared[SWITCHES] += 1

