"""The cost of writing safely: a result file (gzip) and a checkpoint (raw) through
``axlebox._files`` (space reserved with fallocate, h5py on a Python file object, fsync, rename)
against the plain way it was written before (h5py's own driver to ``NAME.tmp``, rename, no
fsync).  Side by side in one run, best of ``--repeat``.

    python3 benchmarks/write.py [--mb 240] [--repeat 3] [--dir DIR]
"""
from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

import h5py
import numpy as np

from axlebox._files import h5_bound, h5_written


def arrays(mb: float) -> dict:
    """Smooth float64 signals (random walks: they compress as measured signals do) of ``mb`` MB."""
    rng = np.random.default_rng(0)
    n = int(mb * 1e6 / 8 / 3 / 16)
    return {f"s{i}": rng.standard_normal((n, 3)).cumsum(0) for i in range(16)}


def plain(path: Path, data: dict, gzip: bool) -> None:
    tmp = path.with_name(path.name + ".tmp")
    with h5py.File(tmp, "w") as f:
        for k, a in data.items():
            f.create_dataset(k, data=a, **({"compression": "gzip", "compression_opts": 4} if gzip else {}))
    os.replace(tmp, path)


def safe(path: Path, data: dict, gzip: bool) -> None:
    with h5_written(path, h5_bound(data.values())) as f:
        for k, a in data.items():
            f.create_dataset(k, data=a, **({"compression": "gzip", "compression_opts": 4} if gzip else {}))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mb", type=float, default=240.0, help="data size, MB (default 240: a simulated "
                    "second of the validation case's outputs)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--dir", default=None, help="where to write (default: a temporary folder)")
    a = ap.parse_args()
    data = arrays(a.mb)
    with tempfile.TemporaryDirectory(dir=a.dir) as tmp:
        print(f"{sum(x.nbytes for x in data.values()) / 1e6:.0f} MB of float64 in {len(data)} datasets, "
              f"best of {a.repeat}, in {tmp}")
        print(f"{'file':<22} {'plain s':>8} {'safe s':>8} {'safe/plain':>10} {'size MB':>8}")
        for what, gzip in (("result (gzip 4)", True), ("checkpoint (raw)", False)):
            best = {}
            for _ in range(a.repeat):
                for name, fn in (("plain", plain), ("safe", safe)):
                    p = Path(tmp) / f"{name}.h5"
                    t0 = time.perf_counter()
                    fn(p, data, gzip)
                    best[name] = min(best.get(name, np.inf), time.perf_counter() - t0)
                    size = p.stat().st_size
                    p.unlink()
            print(f"{what:<22} {best['plain']:>8.2f} {best['safe']:>8.2f} "
                  f"{best['safe'] / best['plain']:>10.2f} {size / 1e6:>8.1f}")


if __name__ == "__main__":
    main()
