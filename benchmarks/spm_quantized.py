"""The SPM's EMD on segments with runs of equal samples (issue 57): PyEMD's parabolic extrema
(``EMD(extrema_detection="parabol")``, as the SPM used them) against the SPM's own
(:class:`axlebox.bearing.diagnostics.spm.SiftEMD`, extrema found on runs of equal samples), on
segments of 32-1200 samples of a resonance of 200-3200 Hz at 20 kHz with white noise, spoiled
five ways in turn: quantized to 1-100 steps of RMS, clipped at the 30-99 % quantile of |x|, a
stretch held, 8 bits on +-1 and clipped, quantized to half a step of RMS.  Prints, per spoiling
and detection, the segments whose decomposition raised (and what).

    python3 benchmarks/spm_quantized.py [N]      # N segments (default 1500)
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
          "8 bits on +-1, clipped", "quantized to half a step of RMS")


def segment(seed: int) -> tuple[str, np.ndarray]:
    rng = np.random.default_rng(seed)
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
        x = np.round(np.clip(x / x.std() / 4, -1, 1) * 127)
    else:
        x = np.round(x / x.std() * 2)
    return SPOILS[op], x


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 1500
    makers = {"PyEMD parabol": lambda: EMD(extrema_detection="parabol"), "SiftEMD (runs)": spm.SiftEMD}
    print(f"{n} segments, PyEMD as installed")
    print("| spoiling | segments | PyEMD parabol: raised | SiftEMD (runs): raised |")
    print("| --- | --- | --- | --- |")
    raised = {k: Counter() for k in makers}
    what = Counter()
    total = Counter()
    t = {k: 0.0 for k in makers}
    for seed in range(n):
        kind, x = segment(seed)
        total[kind] += 1
        for name, make in makers.items():
            spm.SiftEMD, keep = make, spm.SiftEMD
            t0 = time.perf_counter()
            try:
                spm._segment_level(x, 4)
            except Exception as err:  # noqa: BLE001 - counting what the library raises
                raised[name][kind] += 1
                what[name, f"{type(err).__name__}: {str(err)[:60]}"] += 1
            finally:
                spm.SiftEMD = keep
                t[name] += time.perf_counter() - t0
    a, b = raised["PyEMD parabol"], raised["SiftEMD (runs)"]
    for kind in SPOILS:
        print(f"| {kind} | {total[kind]} | {a[kind]} | {b[kind]} |")
    print(f"| all | {n} | {sum(a.values())} | {sum(b.values())} |")
    for (name, msg), c in what.most_common():
        print(f"  {name}: {msg} x{c}")
    print("time: " + ", ".join(f"{k} {v:.0f} s" for k, v in t.items()))


if __name__ == "__main__":
    main()
