"""One numba thread and two give the car the same bits, and so does a run whose thread count is
switched as it goes (axlebox/_threads.py: fitted to the cores free of other processes).

The car's bodies and its eight bearings run in numba's parallel loops, each iteration writing only
its own rows (mbs/kernel/system.py, mbs/kernel/bearings.py), and the bearings of an exchange
advance with no synchronisation inside it (mbs/kernel/exchange.py): the thread count must not change a
single bit.  The suite's workers have one thread each (tests/conftest.py), so the runs are made by
a child process given two (this file run as a script): the car of tests/test_coupled.py (rigid
bodies, eight DTRBs, the validation defect), 0.1 s from the same start, on one thread and on two,
for the leapfrog, the multirate exchange (bodies at 2e-5 s, bearings two sub-steps of 1e-5 s) and
imex; and for each a third run started on two threads whose watcher asks for 1, 2, 1, ... every
10 ms, so that the kernel switches many times inside each chunk.

The rest, in this process: the free-core estimate on synthetic ``/proc/stat`` readings, the count
it fits, the setting ``AXLEBOX_THREADS`` refused with its name, and the sweep's workers times
threads never above the cores.
"""
import itertools
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from axlebox import _threads
from axlebox._params import ParameterError
from axlebox.pipelines.sweep import shares

CASES = {"leapfrog": {"method": "leapfrog", "dt": 1e-5},
         "multirate": {"method": "leapfrog", "dt": 1e-5, "exchange_dt": 2e-5},
         "imex": {"method": "imex", "dt": 1e-5}}
SENSORS = ("ws2_R", "ws2_L")


def test_one_thread_and_two_give_the_car_the_same_bits(tmp_path):
    out = tmp_path / "runs.npz"
    env = {**os.environ, "NUMBA_NUM_THREADS": "2"}
    r = subprocess.run([sys.executable, __file__, str(out)], env=env, capture_output=True, text=True,
                       cwd=Path(__file__).parent)
    assert r.returncode == 0, r.stderr[-3000:]
    with np.load(out) as z:
        assert int(z["threads"]) == 2
        for case in CASES:
            # the fixed runs kept their count, the switched one switched inside its chunks
            assert int(z[f"{case}/1/switches"]) == 0 and int(z[f"{case}/2/switches"]) == 0, case
            assert int(z[f"{case}/switched/switches"]) >= 4, case
            for key in (*SENSORS, "y_end"):
                one = z[f"{case}/1/{key}"]
                assert one.size > 0 and np.isfinite(one).all(), (case, key)
                for other in (2, "switched"):
                    assert one.tobytes() == z[f"{case}/{other}/{key}"].tobytes(), (case, other, key)


def _runs(out: str) -> None:
    """The child: every case on one thread and on two, arrays saved to ``out``."""
    import numba

    from axlebox.mbs.solver import integrate
    from axlebox.pipelines import simulate as psim
    from test_coupled import coupled_config
    cfg = coupled_config(track={"irregularity": False})
    model, y0 = psim.build_model(cfg, log=lambda *_: None)
    arrays = {"threads": numba.config.NUMBA_NUM_THREADS}
    for case, kw in CASES.items():
        for threads in (1, 2, "switched"):
            numba.set_num_threads(2 if threads == "switched" else threads)
            if threads == "switched":         # others busy on every core, then on none, ...
                busy = itertools.cycle((1e3, 0.0))
                fitter = _threads.Fitter(measure=busy.__next__, interval=0.01)
            else:
                fitter = _threads.Fitter(fit=False)
            s = integrate.Settings(**kw, output_rate_hz=1e4, state_rate_hz=100)
            run = integrate.simulate(model, 0.1, s, y0=y0, threads=fitter)
            if not run.ok:
                raise SystemExit(f"{case} on {threads} threads: {run.message}")
            if numba.get_num_threads() != (2 if threads == "switched" else threads):
                raise SystemExit(f"{case} on {threads} threads: the count was not put back")
            for nm in SENSORS:
                arrays[f"{case}/{threads}/{nm}"] = run.sensors[nm]
            arrays[f"{case}/{threads}/y_end"] = run.y_end
            arrays[f"{case}/{threads}/switches"] = run.stats["thread_switches"]
    np.savez(out, **arrays)


# /proc/stat of a 4-CPU machine: user nice system idle iowait irq softirq steal guest guest_nice
STAT = """cpu  {t}
cpu0 {0} 0 {1} {2} 5 0 1 0 0 0
cpu1 100 0 0 900 0 0 0 0 0 0
cpu2 {3} 10 0 {4} 0 0 0 {5} 77 0
cpu3 0 0 0 1000 0 0 0 0 0 0
intr 1 2 3
"""


def _stat(c0=(100, 0, 900), c2=(50, 940, 0)):
    return STAT.format(c0[0], c0[1], c0[2], c2[0], c2[1], c2[2], t="1 2 3 4 5 6 7 8 9 10")


def test_busy_ticks_are_read_for_the_allowed_cpus_only():
    """Busy: user, nice, system, irq, softirq, steal (guest is inside user); all: busy, idle and
    iowait; only the CPUs asked for; None where one of them has no line."""
    text = _stat(c0=(200, 30, 700), c2=(50, 900, 40))
    assert _threads.cpu_jiffies(text, [0]) == (200 + 30 + 1, 200 + 30 + 1 + 700 + 5)
    assert _threads.cpu_jiffies(text, [2]) == (50 + 10 + 40, 50 + 10 + 40 + 900)
    assert _threads.cpu_jiffies(text, [0, 1, 3]) == (231 + 100, 936 + 1000 + 1000)
    assert _threads.cpu_jiffies(text, [0, 4]) is None


def test_the_cores_others_keep_busy_are_the_busy_ticks_less_this_process():
    """Two CPUs, 100 ticks each between the readings: 150 busy of which 60 ours is 0.9 of a core
    to others; ours above the busy (readings a tick apart) is none, not less than none."""
    before = (1000, 5000, 300)
    assert _threads.others_busy(before, (1150, 5200, 360), 2) == pytest.approx(0.9)
    assert _threads.others_busy(before, (1150, 5200, 460), 2) == 0.0
    assert _threads.others_busy(before, (1150, 5000, 360), 2) == 0.0        # no time between


def test_the_watcher_reads_proc_stat_and_its_own_cpu_time(tmp_path, monkeypatch):
    """The default measure: two readings of a synthetic /proc/stat on the CPUs of the affinity
    mask (0 and 2), this process's CPU time (os.times, seconds) in clock ticks subtracted: 150
    busy ticks of 200 (100 a CPU), 0.6 s of them ours at 100 ticks a second, is 0.9 cores."""
    stat = tmp_path / "stat"
    monkeypatch.setattr(_threads, "STAT", str(stat))
    monkeypatch.setattr(_threads, "cpus", lambda: [0, 2])
    monkeypatch.setattr(_threads, "TICK", 100)
    own = iter([1.0, 1.6, 1.6])
    monkeypatch.setattr(_threads.os, "times", lambda: os.times_result((next(own), 0.0, 0.0, 0.0, 0.0)))
    f = _threads.Fitter()
    f.n, f.ceiling = 2, 2
    stat.write_text(_stat(c0=(100, 0, 900), c2=(50, 940, 0)))
    assert f.measure() is None                            # one reading: no interval yet
    stat.write_text(_stat(c0=(180, 0, 920), c2=(120, 970, 0)))
    assert f.measure() == pytest.approx(0.9)
    f.step()                                               # a reading with the same own time
    assert f.counts == [2] and f.shared[_threads.WANT] == 2


@pytest.mark.parametrize("others, n, ceiling, want", [
    (0.0, 2, 2, 2), (0.29, 2, 2, 2), (0.3, 2, 2, 1), (0.67, 2, 2, 1), (1.0, 2, 2, 1), (2.0, 2, 2, 1),
    (0.0, 16, 4, 4), (12.5, 16, 8, 3), (15.9, 16, 8, 1), (0.0, 1, 1, 1)])
def test_the_threads_fit_the_cores_others_leave(others, n, ceiling, want):
    assert _threads.fitted(others, n, ceiling) == want


def test_the_setting_is_declared_once_and_a_bad_value_is_refused_by_name():
    assert _threads.ThreadSettings.from_env({}).mode == "fit"
    assert _threads.ThreadSettings.from_env({"AXLEBOX_THREADS": " fixed "}).mode == "fixed"
    with pytest.raises(ParameterError, match=r"AXLEBOX_THREADS = 'off' is not allowed: expected one "
                                             r"of fit, fixed"):
        _threads.ThreadSettings.from_env({"AXLEBOX_THREADS": "off"})


def test_a_fixed_run_starts_no_watcher_and_one_without_proc_stat_keeps_its_count(monkeypatch):
    import threading
    import numba
    with _threads.Fitter(fit=False) as f:
        assert "axlebox-threads" not in {t.name for t in threading.enumerate()}
    assert list(f.shared) == [0, numba.get_num_threads(), 0]
    monkeypatch.setattr(_threads, "STAT", "/nonexistent/stat")
    f = _threads.Fitter()
    f.ceiling = 2
    f.measure()
    f.step()
    assert f.shared[_threads.WANT] == 0 and f.counts == []


@pytest.mark.parametrize("cores", [1, 2, 3, 4, 7, 8, 16])
def test_the_sweeps_workers_times_threads_are_never_above_the_cores(cores):
    for cases, asked in itertools.product(range(1, 20), [None, *range(1, 20)]):
        n, threads = shares(asked, cases, cores)
        assert 1 <= n <= cases and threads >= 1 and n * threads <= cores, (cases, asked)
        if asked is None or asked >= min(cases, cores):      # as many workers as can be busy
            assert n == min(cases, cores)
        assert threads == cores // n                          # the cores left to them shared out


if __name__ == "__main__":
    _runs(sys.argv[1])
