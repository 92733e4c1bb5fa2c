"""One numba thread and two give the car the same bits.

The car's bodies and its eight bearings run in numba's parallel loops, each iteration writing only
its own rows (mbs/kernel_system.py, mbs/kernel_bearings.py), and the bearings of an exchange
advance with no synchronisation inside it (mbs/exchange.py): the thread count must not change a
single bit.  The suite's workers have one thread each (tests/conftest.py), so the runs are made by
a child process given two (this file run as a script): the car of tests/test_coupled.py (rigid
bodies, eight DTRBs, the validation defect), 0.1 s from the same start, on one thread and on two,
for the leapfrog, the multirate exchange (bodies at 2e-5 s, bearings two sub-steps of 1e-5 s) and
imex.
"""
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

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
            for key in (*SENSORS, "y_end"):
                one, two = z[f"{case}/1/{key}"], z[f"{case}/2/{key}"]
                assert one.size > 0 and np.isfinite(one).all(), (case, key)
                np.testing.assert_array_equal(one, two, err_msg=f"{case} {key}")


def _runs(out: str) -> None:
    """The child: every case on one thread and on two, arrays saved to ``out``."""
    import numba

    from axlebox.mbs import integrate
    from axlebox.pipelines import simulate as psim
    from test_coupled import coupled_config
    cfg = coupled_config(track={"irregularity": False})
    model, y0 = psim.build_model(cfg, log=lambda *_: None)
    arrays = {"threads": numba.config.NUMBA_NUM_THREADS}
    for case, kw in CASES.items():
        for threads in (1, 2):
            numba.set_num_threads(threads)
            s = integrate.Settings(**kw, output_rate_hz=1e4, state_rate_hz=100)
            run = integrate.simulate(model, 0.1, s, y0=y0)
            if not run.ok:
                raise SystemExit(f"{case} on {threads} threads: {run.message}")
            for nm in SENSORS:
                arrays[f"{case}/{threads}/{nm}"] = run.sensors[nm]
            arrays[f"{case}/{threads}/y_end"] = run.y_end
    np.savez(out, **arrays)


if __name__ == "__main__":
    _runs(sys.argv[1])
