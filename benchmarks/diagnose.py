"""Benchmark: ``axlebox diagnose`` on 60 s of two 10 kHz channels.

The channels are synthetic (the one wheelset of a vehicle run, as ``axlebox simulate`` writes
it): the left side carries outer-ring impulses at the DTRB's BPFO at 48 km/h (1 % period jitter)
ringing a 600 Hz resonance, the right side a 1.2 ms later, 0.3 x, 546 Hz-resonance filtered copy;
both in independent 0-1 kHz noise.  They are written to an axlebox-result file in a temporary
folder; then the full command runs in a fresh process (imports, reading, both channels'
indicators with EMD and spectral kurtosis, the lag, the criterion, the JSON): its wall time and
peak resident memory are printed, and the stages are timed once more in this process.
Goal: <= 5 s.  Run: ``python benchmarks/diagnose.py``.
"""
from __future__ import annotations

import json
import os
import platform
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from axlebox.bearing import resultfile
from axlebox.bearing.diagnostics.channel import jsonable
from axlebox.bearing.diagnostics.synthetic import coaxial_pair
from axlebox.bearing.frequencies import orders, shaft_hz
from axlebox.bearing.models.params import BearingParams

FS = 10_000.0
DURATION = 60.0
SPEED_KMH = 48.0
CONFIG = f"[run]\nspeed_kmh = {SPEED_KMH}\n[wheelset]\nr0 = 0.42\n[track]\nfra_class = 5\n"


def channels(seed: int = 0, n: int = int(DURATION * FS)):
    rng = np.random.default_rng(seed)
    bpfo = orders(BearingParams()).BPFO * shaft_hz(SPEED_KMH)
    # left +6 dB over its noise; the right 0.3 x as strong, 1.2 ms later through 546 Hz
    return coaxial_pair(n / FS, FS, bpfo, rng, amplitude=1.0, noise=0.5, delay_s=1.2e-3, gain=0.3)


def main():
    left, right = channels()
    z = np.zeros((left.size, 3))
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "run.h5"
        acc_l, acc_r = z.copy(), z.copy()
        acc_l[:, 2], acc_r[:, 2] = left, right
        resultfile.write(path, config_toml=CONFIG, seed=0, time=np.arange(left.size) / FS, fs_hz=FS,
                         signals={"ws2_L": {"acceleration": acc_l}, "ws2_R": {"acceleration": acc_r}})
        out = Path(tmp) / "diag.json"
        cmd = [sys.executable, "-m", "axlebox", "diagnose", str(path), "--json", str(out)]
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        peak_mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
        if proc.returncode != 0:
            sys.exit(f"axlebox diagnose failed ({proc.returncode}): {proc.stderr.strip()}")
        res = json.loads(out.read_text())

        # the stages once more, in this process (imports already paid)
        from axlebox.bearing.diagnostics.pair import analyse_pair
        from axlebox.pipelines import diagnose
        t = time.perf_counter()
        rec = diagnose.read(path)
        t_read = time.perf_counter() - t
        t = time.perf_counter()
        pair = analyse_pair(rec.left, rec.right, rec.fs, rec.shaft_hz, orders(BearingParams()),
                            diagnose.DTRB_BORE, names=rec.names)
        t_pair = time.perf_counter() - t
        t = time.perf_counter()
        diagnose.write_json(Path(tmp) / "again.json", jsonable(pair.to_dict()))
        t_json = time.perf_counter() - t

    print(f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
          f"numpy {np.__version__}")
    print(f"input: 2 x {DURATION:g} s at {FS:g} Hz ({left.size} samples a channel), axlebox-result")
    print(f"axlebox diagnose (fresh process, full command): {wall:.2f} s wall, peak RSS "
          f"{peak_mb:.0f} MB; goal <= 5 s: {'met' if wall <= 5 else 'NOT met'}")
    print(f"  stages in-process: read {t_read:.2f} s, analyse_pair {t_pair:.2f} s, JSON {t_json:.3f} s")
    v = res["verdicts"]
    print(f"  verdicts: left {v['left']['verdict']}, right {v['right']['verdict']}; "
          f"VF difference {res['vf_diff_hz2']:.4g} Hz^2; lag {res['lag']['lag_s'] * 1e3:.3g} ms, "
          f"leading {res['lag']['leading']}")


if __name__ == "__main__":
    main()
