"""The SPM's EMD on segments with runs of equal samples (issue 57): PyEMD's parabolic extrema
(``EMD(extrema_detection="parabol")``, as the SPM used them) against the SPM's own
(:class:`axlebox.bearing.diagnostics.spm.SiftEMD`, extrema found on runs of equal samples), on
segments of 32-1200 samples of a resonance of 200-3200 Hz at 20 kHz with white noise, spoiled
five ways in turn: quantized to 1-100 steps of RMS, clipped at the 30-99 % quantile of |x|, a
stretch held, 8 bits on +-1 with most samples clipped at the rails, quantized to half a step of
RMS.  Then whole channels as the SPM reads them (``shock_value``: 16 segments of 4 periods of
236.4 Hz) of the real-style record of issue 57 (tests/test_diagnostics_channel.real_style, 1 s:
a 500 Hz resonance dominating, stored to 0.001 at RMS 0.06), the channel calls that raised.
Prints, per spoiling and detection, the calls that raised (and what).

    python3 benchmarks/spm_quantized.py [N [M]]   # N segments (default 1500), M channels (200)
"""
from __future__ import annotations

import sys
import time
from collections import Counter

import numpy as np
from PyEMD import EMD

from axlebox.bearing.diagnostics import spm
from axlebox.bearing.diagnostics.synthetic import resonance

FS = 20e3
SPOILS = ("quantized to 1-100 steps of RMS", "clipped at the 30-99 % quantile", "a stretch held",
          "8 bits on +-1, mostly clipped", "quantized to half a step of RMS")
REAL = "real-style channels (1 s, 0.001 steps at RMS 0.06)"


def segment(seed: int) -> tuple[str, np.ndarray]:
    rng = np.random.default_rng(seed if seed >= 0 else [1, -seed])
    if seed < 0:                                   # a real-style channel
        n = 20000
        low = resonance(rng.standard_normal(n), FS, 500.0, 0.02)
        high = resonance(rng.standard_normal(n), FS, 3000.0, 0.05)
        x = low / low.std() + 0.1 * high / high.std() + 0.02 * rng.standard_normal(n)
        return REAL, np.round(0.06 * x / x.std(), 3)
    n = int(rng.integers(32, 1200))
    x = resonance(rng.standard_normal(n + 400), FS, 200 + 3000 * rng.random(), 0.02)[400:]
    x = x + rng.random() * x.std() * rng.standard_normal(n)
    op = seed % 5
    if op == 0:
        x = np.round(x / x.std() * rng.uniform(1, 100))
    elif op == 1:
        c = np.quantile(np.abs(x), rng.uniform(0.3, 0.99))
        x = np.clip(x, -c, c)
    elif op == 2:
        i = int(rng.integers(0, n))
        x[i:i + int(rng.integers(1, n))] = x[i]
    elif op == 3:
        x = np.round(np.clip(x, -1, 1) * 127)        # RMS 5-12 against a range of +-1
    else:
        x = np.round(x / x.std() * 2)
    return SPOILS[op], x


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 1500
    m = int(sys.argv[2]) if len(sys.argv) > 2 else 200
    makers = {"PyEMD parabol": lambda: EMD(extrema_detection="parabol"), "SiftEMD (runs)": spm.SiftEMD}
    print(f"{n} segments, {m} channels, PyEMD as installed")
    print("| spoiling | calls | PyEMD parabol: raised | SiftEMD (runs): raised |")
    print("| --- | --- | --- | --- |")
    raised = {k: Counter() for k in makers}
    what = Counter()
    total = Counter()
    t = {k: 0.0 for k in makers}
    for seed in [*range(n), *range(-1, -m - 1, -1)]:
        kind, x = segment(seed)
        total[kind] += 1
        for name, make in makers.items():
            spm.SiftEMD, keep = make, spm.SiftEMD
            t0 = time.perf_counter()
            try:
                if seed < 0:
                    spm.shock_value(x, FS, period_s=1 / 236.4)
                else:
                    spm._segment_level(x, 4)
            except Exception as err:  # noqa: BLE001 - counting what the library raises
                raised[name][kind] += 1
                what[name, f"{type(err).__name__}: {str(err)[:60]}"] += 1
            finally:
                spm.SiftEMD = keep
                t[name] += time.perf_counter() - t0
    a, b = raised["PyEMD parabol"], raised["SiftEMD (runs)"]
    for kind in (*SPOILS, REAL):
        print(f"| {kind} | {total[kind]} | {a[kind]} | {b[kind]} |")
    for (name, msg), c in what.most_common():
        print(f"  {name}: {msg} x{c}")
    print("time: " + ", ".join(f"{k} {v:.0f} s" for k, v in t.items()))


if __name__ == "__main__":
    main()
