"""Make ``size_excerpts.npz``: the defect side's axle-box signal of car runs, the model's known
answers for the defect's size (tests/test_size.py).  The cases kept: v20_w1 and v40_w3 of the
quasi-dynamic car (below), v80_w3 and v80_w5 of the full car (``axlebox sweep study --out DIR``,
the dynamic DTRB, 2.8 s: DIR/v80_w3.h5, DIR/v80_w5.h5), added to the file as it was.

Each run is configs/study_fast.toml (the quasi-dynamic DTRB in the car, the sensor model at
10 kHz) without its [sweep] table, 1.5 s, at a speed and an outer-ring defect width W (row 2 of
wheelset 2's right bearing, 50.4 mm long, 2 mm deep)::

    axlebox simulate RUN.toml --out RUN.h5 --checkpoint-every 0

and this script keeps, past the track's 0.5 s fade-in, 1 s of ``signals/ws2_R/acceleration``
(vertical), rounded to a 16-bit grid of 2^-9 m/s^2 (the 64 m/s^2 range of a 16-bit converter;
the rounding's 5.6e-4 m/s^2 RMS is about 1e-4 of the signal's), with the run's speed, W, shaft rate and
the most loaded roller's load as :mod:`axlebox.pipelines.readers` reads it::

    python3 tests/data/make_size_excerpts.py OUT.npz v20_w1=RUN1.h5 v40_w3=RUN2.h5

An OUT that exists keeps its cases; those named again are replaced.
"""
from __future__ import annotations

import sys

import numpy as np

from axlebox.pipelines.readers import read, result_config

LSB = 2.0 ** -9


def main(out, *cases):
    data = {}
    try:
        with np.load(out) as old:
            data = {k: old[k] for k in old.files if k != "lsb"}
    except FileNotFoundError:
        pass
    for item in cases:
        name, path = item.split("=", 1)
        rec = read(path)
        cfg = result_config(path)
        x = rec.right[:int(round(rec.fs))]
        data[f"{name}_x"] = np.round(x / LSB).astype(np.int16)
        data[f"{name}_meta"] = np.array([rec.fs, rec.shaft_hz, cfg.run.speed_kmh, cfg.defects[0].defect.W,
                                         rec.roller_loads[1]])
    np.savez_compressed(out, lsb=LSB, **data)


if __name__ == "__main__":
    main(*sys.argv[1:])
