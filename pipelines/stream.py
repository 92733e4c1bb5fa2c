"""A car run's outputs streamed to disk while it goes, so that its memory does not grow with its
length (issue 32), and so that no kill, at any instant, makes what was written unreadable
(issue 50, item 5): the folder ``<out>.stream.d``, whose segments ``NNNNNNNNNNNN.h5`` (the first
output they hold, twelve digits) each hold the outputs of one checkpoint interval, one resizable
dataset per output (sensors one dataset each, so that the acquisition chain reads one sensor at
a time), appended after every chunk of :func:`axlebox.mbs.solver.integrate.simulate` (its ``sink``).

A segment is written as ``<segment>.tmp`` and committed (:meth:`Stream.commit`: closed, synced,
renamed) just before each checkpoint is written and when the run ends; a committed segment is
never opened for writing again.  So a kill in the middle of an append (or of anything else)
tears only the ``.tmp`` of outputs after the last checkpoint, never a committed segment: resume
removes the ``.tmp`` and the segments after the checkpoint (committed before a checkpoint the
kill stopped), and the resumed run appends the very values an uninterrupted one would, to the
same bits, without ``--restart`` (tests/test_stream_kill.py kills a run inside an append).

The checkpoint stays small and whole: ``<out>.partial.h5`` (written through a temporary name)
holds the config, the outputs done ``k``, the state and the wall time.  When the run ends,
:func:`finished` reads the segments back one sensor at a time through the acquisition chain and
gives the run as recorded, its wheel-rail, element, bearing and state outputs as :class:`Rows`
(read a block of rows at a time, from the segments that block lies in, when the result file is
written: the whole run is never in memory).
"""
from __future__ import annotations

import contextlib
import os
import shutil
import signal
from pathlib import Path

import h5py
import numpy as np

from axlebox._files import tmp_path
from axlebox._params import ParameterError
from axlebox.mbs.solver import integrate

from . import sensor

ROWS_PER_CHUNK = 4096          # HDF5 chunk rows: 1.5 MB for 16 sensors' x, y, z
# tests only: SIGKILL the run inside its n-th append (this process's), part of the chunk written
KILL_IN_APPEND = "AXLEBOX_TEST_KILL_IN_APPEND"


def stream_path(out) -> Path:
    """The streamed outputs of a run writing ``out``: the folder ``<out>.stream.d``."""
    return Path(str(out) + ".stream.d")


def remove(path) -> None:
    """The stream at ``path`` removed (once the result file is written)."""
    if Path(path).is_dir():
        shutil.rmtree(path)


def _segments(folder: Path) -> list[tuple[int, Path]]:
    """The committed segments in ``folder``: (first output, path), in order."""
    return sorted((int(p.stem), p) for p in folder.glob("*.h5") if p.stem.isdigit())


def _fsync_dir(folder: Path) -> None:
    fd = os.open(folder, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


class Stream:
    """The stream being written: :meth:`append` is the integrator's ``sink``, :meth:`commit` comes
    before each checkpoint, :meth:`close` at the end.  ``resume_k``: the checkpoint's outputs
    done; the segments after it and a torn ``.tmp`` are removed, the rest must hold exactly
    outputs ``0 .. resume_k - 1``."""

    def __init__(self, path, model, state_every: int, resume_k: int | None = None,
                 every: int = 1):
        self.path = Path(path)
        self.model = model
        self.se = state_every
        self.every = every              # wheel and element outputs: every k-th (the acquisition's)
        self.names = list(model.sensor_names)
        self.f = None                   # the segment being written (``.tmp``), None between
        self.seg = None
        self._torn = False              # an append that raised midway: its segment is not committed
        self._appends = 0
        self._kill = int(os.environ.get(KILL_IN_APPEND, "0") or 0)
        if resume_k is None:
            remove(self.path)                                   # a run started (over)
            if self.path.name.endswith(".stream.d"):          # an earlier version's one file
                self.path.with_name(self.path.name[:-2] + ".h5").unlink(missing_ok=True)
            self.path.mkdir()
            self.k = 0
        else:
            self.k = self._cut(resume_k)

    def _cut(self, k: int) -> int:
        """Resume at output ``k``: drop what was written after the checkpoint, check the rest."""
        if not self.path.is_dir():
            raise ParameterError(f"stream {str(self.path)!r} is missing: --restart to start over")
        for p in self.path.glob("*.tmp"):       # the segment being written when the run stopped
            p.unlink()
        end = 0
        for k0, p in _segments(self.path):
            if k0 >= k:                          # committed, but its checkpoint was never written
                p.unlink()
                continue
            try:
                with h5py.File(p, "r") as f:
                    n = f["out_t"].shape[0]
            except (OSError, KeyError) as err:
                raise ParameterError(f"stream segment {str(p)!r} is not readable ({err}): "
                                     "--restart to start over") from None
            if k0 != end:
                break
            end = k0 + n
        if end != k:
            raise ParameterError(f"stream {str(self.path)!r} holds outputs 0 .. {end - 1}, not its "
                                 f"checkpoint's 0 .. {k - 1}: --restart to start over")
        return k

    def _open(self, k0: int):
        model, W = self.model, self.model.W
        self.seg = self.path / f"{k0:012d}.h5"
        self.f = h5py.File(tmp_path(self.seg), "w")

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

    def append(self, k0: int, arrays: dict) -> None:
        """Outputs ``k0 ..`` (the integrator's ``sink``), in order from where the stream ends, to
        the segment being written (opened at the first append after a commit); not flushed: a
        kill loses the segment, which holds only outputs after the last checkpoint."""
        if k0 != self.k:
            raise ValueError(f"Stream.append: outputs from {k0}, expected {self.k}")
        if self.f is None:
            self._open(k0)
        self._appends += 1
        kill = self._appends == self._kill
        self._torn = True
        for j, (name, col, n, ds) in enumerate(self._datasets()):
            if kill and j == 1 + len(self.names) // 2:       # tests: time and half the sensors written
                self.f.flush()
                os.kill(os.getpid(), signal.SIGKILL)
            a = arrays[name] if col is None else arrays[name][:, col]
            if name != "out_y":          # out_y holds the chunk's snapshots already
                a = a[(-k0) % n::n]
            r0 = ds.shape[0]
            ds.resize(r0 + a.shape[0], axis=0)
            ds[r0:] = a
        self._torn = False
        self.k = k0 + arrays["out_t"].shape[0]

    def commit(self, k: int | None = None) -> None:
        """The segment being written closed, synced and renamed to its own name: outputs up to
        here (``k``, checked where given) are the stream's for good.  Called before the
        checkpoint of ``k`` is written."""
        if k is not None and k != self.k:
            raise ValueError(f"Stream.commit: {k} outputs, the stream holds {self.k}")
        if self.f is None:
            return
        self.f.close()
        self.f = None
        tmp = tmp_path(self.seg)
        with open(tmp, "rb") as fo:
            os.fsync(fo.fileno())
        os.replace(tmp, self.seg)       # after the close: a committed segment is whole
        _fsync_dir(self.path)

    def close(self):
        """The end of the run: the last segment committed (dropped after an append that raised;
        an empty one for a run that gave no output, so that there is always one to read)."""
        if self._torn and self.f is not None:
            self.f.close()
            self.f = None
            tmp_path(self.seg).unlink(missing_ok=True)
        elif self.f is None and self.k == 0 and not _segments(self.path):
            self._open(0)
        self.commit()


def kept_every(settings: integrate.Settings, sensors_cfg) -> int:
    """Every how many outputs the acquisition keeps one: 1 with an ideal sensor."""
    if sensors_cfg.model == "ideal":
        return 1
    return int(round(settings.output_rate_hz / sensors_cfg.fs_hz))


class Joined:
    """One output of the stream, its segments' datasets end to end, read as an h5py dataset is
    (``shape``, ``dtype``, ``[r0:r1]``, ``[()]``): each read opens only the segments it needs."""

    def __init__(self, parts: list[tuple[Path, int]], name: str, tail: tuple, dtype):
        self.parts, self.name = parts, name           # (segment, its rows of this output)
        self.starts = np.concatenate([[0], np.cumsum([n for _, n in parts], dtype=np.int64)])
        self.shape = (int(self.starts[-1]), *tail)
        self.dtype = np.dtype(dtype)
        self.ndim = len(self.shape)

    def __len__(self):
        return self.shape[0]

    def __getitem__(self, key):
        if (isinstance(key, tuple) and key == ()) or key is Ellipsis:
            r0, r1 = 0, self.shape[0]
        elif isinstance(key, slice) and key.step in (None, 1):
            r0, r1, _ = key.indices(self.shape[0])
        else:
            raise IndexError(f"Joined: only a slice of rows is read, not {key!r}")
        out = np.empty((max(0, r1 - r0), *self.shape[1:]), self.dtype)
        for (p, _), s0, s1 in zip(self.parts, self.starts[:-1], self.starts[1:]):
            a, b = max(r0, s0), min(r1, s1)
            if a < b:
                with h5py.File(p, "r") as f:
                    f[self.name].read_direct(out, np.s_[a - s0:b - s0], np.s_[a - r0:b - r0])
        return out


def _dataset_names(f) -> list[str]:
    names = []
    f.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
    return names


def joined(path) -> dict:
    """Every output of the stream at ``path`` as a :class:`Joined`, by dataset name."""
    rows, first = {}, None
    for _, p in _segments(Path(path)):
        with h5py.File(p, "r") as f:
            names = _dataset_names(f)
            first = first or {n: (f[n].shape[1:], f[n].dtype) for n in names}
            for n in names:
                rows.setdefault(n, []).append((p, f[n].shape[0]))
    if first is None:
        raise ParameterError(f"stream {str(path)!r} holds no committed segment")
    return {n: Joined(rows[n], n, *first[n]) for n in first}


class Rows:
    """Rows of an output of the stream (a :class:`Joined`; or an h5py dataset), read only a
    block at a time: indexing that keeps every row (``rows[:, i]``, ``rows[:, 2, :2]``) and
    :meth:`reshape` are recorded and applied to each block, so ``resultfile.write`` can copy a
    long run's outputs block by block."""

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
def finished(path, run: integrate.Run, model, settings: integrate.Settings, sensors_cfg):
    """The run as recorded (:func:`.sensor.decimate_run`, or every output with an ideal sensor)
    from the stream at ``path``, for the ``with`` block: time and sensors in memory (one sensor
    read at a time through the acquisition chain), wheel-rail, element, bearing and state outputs
    as :class:`Rows` of the stream's segments; ``run``: the integrator's own (status, wall time,
    final state, statistics)."""
    fs_in = settings.output_rate_hz
    ideal = sensors_cfg.model == "ideal"
    k = kept_every(settings, sensors_cfg)
    f = joined(path)
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

