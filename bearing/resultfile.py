"""The simulation result file (``format = "axlebox-result"``), shared by the bearing rig and,
later, the vehicle: writing through a temporary name, reading with a version check.

Layout (as on the documentation's design page): attrs ``format``, ``version``, ``config``
(TOML text, SI units: the whole validated config, every default filled in), ``seed``,
``package_version`` (the axlebox that wrote it); ``time`` (t,) s;
``signals/<sensor>/acceleration`` (t, 3) m/s^2 with attr ``fs_hz``; further channels under
``signals/<sensor>/`` and model internals under other groups.
"""
from __future__ import annotations

import contextlib
from pathlib import Path

import h5py
import numpy as np

from axlebox._files import h5_bound, h5_written
from axlebox._params import ParameterError

FORMAT = "axlebox-result"
VERSION = 1


class ResultFileError(ValueError):
    """A file that is not an axlebox result this version can read."""


BLOCK_BYTES = 32 << 20         # rows copied at a time from a streamed output
# gzip (any HDF5 reader has it) at level 1 after the byte shuffle: a 2.8 s car run's 108 MB of
# float64 outputs to 71.8 MB in 1.37 s, where level 4 without the shuffle took 1.80 s for 73.1 MB
# (benchmarks/README.md): the outputs are noise-like doubles, little gained past level 1
GZIP = {"compression": "gzip", "compression_opts": 1, "shuffle": True}


def _array(item):
    """A group's array: given alone or as ``(array, attributes)``."""
    data, _ = item if isinstance(item, tuple) else (item, None)
    return data


def package_version() -> str:
    """The installed axlebox's version (stored in every result: which code made it)."""
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("axlebox")
    except PackageNotFoundError:
        return "unknown"


def write(path, *, config_toml: str, seed: int, time: np.ndarray, fs_hz: float,
          signals: dict, groups: dict | None = None, attrs: dict | None = None) -> Path:
    """Write ``signals`` (sensor -> {channel: array}) and ``groups`` (name -> {dataset: array or
    (array, attrs)}) to ``path`` via ``path.tmp`` and an atomic rename (space reserved first:
    a full disk is a :class:`axlebox._files.DiskFullError`, nothing written); ``attrs`` are
    further file attributes (run status and the like).  A group's array may be read a block of
    rows at a time (an object with ``shape``, ``dtype``, ``nbytes`` and ``rows(r0, r1)``, as
    axlebox.pipelines.stream.Rows): a long run's outputs never all in memory."""
    arrays = [time, *(a for ch in signals.values() for a in ch.values()),
              *(_array(i) for g in (groups or {}).values() for i in g.values())]
    with h5_written(path, h5_bound(arrays)) as f:
        f.attrs.update(format=FORMAT, version=VERSION, config=config_toml, seed=int(seed),
                       package_version=package_version())
        f.attrs.update(attrs or {})
        f.create_dataset("time", data=time)
        for sensor, channels in signals.items():
            g = f.create_group(f"signals/{sensor}")
            for name, data in channels.items():
                ds = g.create_dataset(name, data=data, **GZIP)
                ds.attrs["fs_hz"] = fs_hz
        for gname, items in (groups or {}).items():
            g = f.require_group(gname)
            for name, item in items.items():
                data, attrs = item if isinstance(item, tuple) else (item, {})
                if hasattr(data, "rows"):
                    ds = g.create_dataset(name, shape=data.shape, dtype=data.dtype, **GZIP)
                    # rows a block by what reading them costs (a view of a wider source reads it whole)
                    row = getattr(data, "source_row_nbytes", data.nbytes // max(1, data.shape[0]))
                    step = max(1, BLOCK_BYTES // max(1, row))
                    for r0 in range(0, data.shape[0], step):
                        ds[r0:r0 + step] = data.rows(r0, r0 + step)
                else:
                    ds = g.create_dataset(name, data=data, **GZIP)
                ds.attrs.update(attrs)
    return Path(path)


def write_checkpoint(path, attrs: dict, arrays: dict) -> Path:
    """A run's checkpoint (``<out>.partial.h5``): ``attrs`` and ``arrays`` (name -> array) to
    ``path`` via ``path.tmp`` and an atomic rename, so a kill leaves the last one whole."""
    with h5_written(path, h5_bound(arrays.values())) as f:
        f.attrs.update(attrs)
        for name, arr in arrays.items():
            f.create_dataset(name, data=arr)
    return Path(path)


# what h5py raises on a damaged file: a bad header, a message of an unknown version, an address
# past the end, a size it cannot allocate
DAMAGED = (OSError, RuntimeError, KeyError, ValueError, TypeError, IndexError, MemoryError)


@contextlib.contextmanager
def reading(path):
    """:func:`open_result` for a ``with`` block whose reads of a damaged file are one
    :class:`ResultFileError` naming the file (a ValueError: exit 2 on the CLI), whatever h5py
    (or the parser of its config text) raised; the caller's own ParameterError passes."""
    try:
        with open_result(path) as f:
            yield f
    except (ResultFileError, ParameterError, FileNotFoundError):
        raise
    except DAMAGED as err:
        first = " ".join(str(err).split()) or type(err).__name__
        raise ResultFileError(f"{str(path)!r} is a damaged result file: {first}") from None


def open_result(path) -> h5py.File:
    """Open a result file for reading; refuses other formats and newer versions."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"result file {str(path)!r} does not exist")
    f = h5py.File(path, "r")
    fmt, ver = f.attrs.get("format"), f.attrs.get("version")
    if fmt != FORMAT or ver is None or int(ver) > VERSION:
        f.close()
        raise ResultFileError(f"{str(path)!r} is not an {FORMAT} file of version <= {VERSION} "
                              f"(format {fmt!r}, version {ver!r})")
    return f
