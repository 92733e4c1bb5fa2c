"""A car run's outputs streamed to disk while it goes, so that its memory does not grow with its
length (issue 32): ``<out>.stream.h5``, one resizable chunked dataset per output (sensors one
dataset each, so that the acquisition chain reads one sensor at a time), appended after every
chunk of :func:`axlebox.mbs.integrate.simulate` (its ``sink``).

The checkpoint stays small and whole: ``<out>.partial.h5`` (written through a temporary name)
holds the config, the outputs done ``k``, the state and the wall time; the stream beyond ``k``
(outputs of a chunk after the last checkpoint) is cut off on resume, so a resumed run appends
the very values an uninterrupted one would.  When the run ends, :func:`finished` reads the stream
back one sensor at a time through the acquisition chain and gives the run as recorded, its
wheel-rail, element, bearing and state outputs as :class:`Rows` (read a block of rows at a time
when the result file is written: the whole run is never in memory).
"""
from __future__ import annotations

import contextlib
from pathlib import Path

import h5py
import numpy as np

from axlebox._params import ParameterError
from axlebox.mbs import integrate

from . import sensor

ROWS_PER_CHUNK = 4096          # HDF5 chunk rows: 1.5 MB for 16 sensors' x, y, z


def stream_path(out) -> Path:
    """The streamed outputs of a run writing ``out``: ``<out>.stream.h5``."""
    return Path(str(out) + ".stream.h5")


class Stream:
    """The open stream file: :meth:`append` is the integrator's ``sink``."""

    def __init__(self, path, model, state_every: int, resume_k: int | None = None,
                 every: int = 1):
        self.path = Path(path)
        self.se = state_every
        self.every = every              # wheel and element outputs: every k-th (the acquisition's)
        self.names = list(model.sensor_names)
        if resume_k is None:
            self.f = h5py.File(self.path, "w")
            self._create(model)
        else:
            try:
                self.f = h5py.File(self.path, "r+")
                n = self.f["out_t"].shape[0]
            except (OSError, KeyError) as err:
                raise ParameterError(f"stream {str(self.path)!r} is not readable ({err}): "
                                     "--restart to start over") from None
            if n < resume_k:
                self.f.close()
                raise ParameterError(f"stream {str(self.path)!r} holds {n} outputs, fewer than "
                                     f"its checkpoint's {resume_k}: --restart to start over")
            self._cut(resume_k)

    def _create(self, model):
        W = model.W

        def make(name, tail):
            self.f.create_dataset(name, shape=(0, *tail), maxshape=(None, *tail), dtype="f8",
                                  chunks=(ROWS_PER_CHUNK, *tail))
        make("out_t", ())
        for i in range(len(self.names)):
            make(f"out_sens/{i}", (3,))
        make("out_wh", W.whout.shape)
        make("out_el", (W.elout.shape[0], 6))
        self.f.create_dataset("out_y", shape=(0, model.n_states), maxshape=(None, model.n_states),
                              dtype="f8", chunks=(64, model.n_states))

    def _datasets(self):
        """(output name, column of it or None, keeps every n-th output, dataset)."""
        yield "out_t", None, 1, self.f["out_t"]
        for i in range(len(self.names)):
            yield "out_sens", i, 1, self.f[f"out_sens/{i}"]
        yield "out_wh", None, self.every, self.f["out_wh"]
        yield "out_el", None, self.every, self.f["out_el"]
        yield "out_y", None, self.se, self.f["out_y"]

    def _cut(self, k: int):
        """Keep outputs ``0 .. k - 1`` (of a dataset keeping every n-th: ceil(k / n) rows)."""
        for _, _, n, ds in self._datasets():
            ds.resize((k + n - 1) // n, axis=0)

    def append(self, k0: int, arrays: dict) -> None:
        """Outputs ``k0 ..`` (the integrator's ``sink``); flushed, so a kill loses at most the
        chunk being written (cut off on resume: it lies after the last checkpoint).  The chunks
        come in order from where the stream ends (cut to the checkpoint when resumed)."""
        for name, col, n, ds in self._datasets():
            a = arrays[name] if col is None else arrays[name][:, col]
            if name != "out_y":          # out_y holds the chunk's snapshots already
                a = a[(-k0) % n::n]
            r0 = ds.shape[0]
            ds.resize(r0 + a.shape[0], axis=0)
            ds[r0:] = a
        self.f.flush()

    def close(self):
        self.f.close()


def kept_every(settings: integrate.Settings, sensors_cfg: dict) -> int:
    """Every how many outputs the acquisition keeps one: 1 with an ideal sensor."""
    if sensors_cfg["model"] == "ideal":
        return 1
    return int(round(settings.output_rate_hz / sensors_cfg["fs_hz"]))


class Rows:
    """Rows of a dataset in the open stream, read only a block at a time: indexing that keeps
    every row (``rows[:, i]``, ``rows[:, 2, :2]``) and :meth:`reshape` are recorded and applied to
    each block, so ``resultfile.write`` can copy a long run's outputs block by block."""

    def __init__(self, ds, ops=()):
        self.ds, self.ops = ds, tuple(ops)
        one = self._apply(ds[:1]) if ds.shape[0] else self._apply(np.zeros((1, *ds.shape[1:])))
        self.shape = (ds.shape[0], *one.shape[1:])
        self.dtype = one.dtype
        self.nbytes = int(np.prod(self.shape)) * self.dtype.itemsize
        # what a block of rows reads: the stream's whole rows, whatever part of them is kept
        self.source_row_nbytes = int(np.prod(ds.shape[1:])) * ds.dtype.itemsize

    def _apply(self, block):
        for op in self.ops:
            block = op(block)
        return block

    def __getitem__(self, key):
        key = key if isinstance(key, tuple) else (key,)
        if key[0] != slice(None):
            raise IndexError("Rows: only indexing that keeps every row ([:, ...]) is recorded")
        return Rows(self.ds, self.ops + ((lambda b, k=key: b[k]),))

    def reshape(self, n, *shape):
        if n != self.shape[0]:
            raise ValueError(f"Rows.reshape: {n} rows, expected {self.shape[0]}")
        return Rows(self.ds, self.ops + ((lambda b, sh=shape: b.reshape(b.shape[0], *sh)),))

    def rows(self, r0: int, r1: int) -> np.ndarray:
        """Rows ``r0 .. r1 - 1``, every recorded operation applied."""
        return self._apply(self.ds[r0:r1])

    def __array__(self, dtype=None, copy=None):
        a = self.rows(0, self.shape[0])          # the whole of it: for small runs and tests
        return a if dtype is None else a.astype(dtype)


@contextlib.contextmanager
def finished(path, run: integrate.Run, model, settings: integrate.Settings, sensors_cfg: dict):
    """The run as recorded (:func:`.sensor.decimate_run`, or every output with an ideal sensor)
    from the stream at ``path``, for the ``with`` block: time and sensors in memory (one sensor
    read at a time through the acquisition chain), wheel-rail, element, bearing and state outputs
    as :class:`Rows` of the open stream; ``run``: the integrator's own (status, wall time,
    final state, statistics)."""
    fs_in = settings.output_rate_hz
    ideal = sensors_cfg["model"] == "ideal"
    k = kept_every(settings, sensors_cfg)
    with h5py.File(path, "r") as f:
        t = f["out_t"][()]
        sensors = {}
        for i, name in enumerate(model.sensor_names):
            a = f[f"out_sens/{i}"][()]
            sensors[name] = a if ideal else sensor.measure(a, fs_in, sensors_cfg)
        wh, el = Rows(f["out_wh"]), Rows(f["out_el"])          # kept every k-th already
        states = Rows(f["out_y"])
        yield integrate.Run(time=t[::k], sensors=sensors, **integrate.split_outputs(model, wh, el),
                            state_time=t[::settings.state_every][:states.shape[0]],
                            states=states, y_end=run.y_end, exchange=run.exchange, status=run.status,
                            message=run.message, wall_s=run.wall_s, stats=run.stats)

