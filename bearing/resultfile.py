"""The simulation result file (``format = "axlebox-result"``), shared by the bearing rig and,
later, the vehicle: writing through a temporary name, reading with a version check.

Layout (DESIGN.md): attrs ``format``, ``version``, ``config`` (TOML text, SI units), ``seed``;
``time`` (t,) s; ``signals/<sensor>/acceleration`` (t, 3) m/s^2 with attr ``fs_hz``; further
channels under ``signals/<sensor>/`` and model internals under other groups.
"""
from __future__ import annotations

import os
from pathlib import Path

import h5py
import numpy as np

FORMAT = "axlebox-result"
VERSION = 1


class ResultFileError(ValueError):
    """A file that is not an axlebox result this version can read."""


def write(path, *, config_toml: str, seed: int, time: np.ndarray, fs_hz: float,
          signals: dict, groups: dict | None = None, attrs: dict | None = None) -> Path:
    """Write ``signals`` (sensor -> {channel: array}) and ``groups`` (name -> {dataset: array or
    (array, attrs)}) to ``path`` via ``path.tmp`` and an atomic rename; ``attrs`` are further
    file attributes (run status and the like)."""
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp")
    with h5py.File(tmp, "w") as f:
        f.attrs.update(format=FORMAT, version=VERSION, config=config_toml, seed=int(seed))
        f.attrs.update(attrs or {})
        f.create_dataset("time", data=time)
        for sensor, channels in signals.items():
            g = f.create_group(f"signals/{sensor}")
            for name, data in channels.items():
                ds = g.create_dataset(name, data=data, compression="gzip", compression_opts=4)
                ds.attrs["fs_hz"] = fs_hz
        for gname, items in (groups or {}).items():
            g = f.require_group(gname)
            for name, item in items.items():
                data, attrs = item if isinstance(item, tuple) else (item, {})
                ds = g.create_dataset(name, data=data, compression="gzip", compression_opts=4)
                ds.attrs.update(attrs)
    os.replace(tmp, path)
    return path


def write_checkpoint(path, attrs: dict, arrays: dict) -> Path:
    """A run's checkpoint (``<out>.partial.h5``): ``attrs`` and ``arrays`` (name -> array) to
    ``path`` via ``path.tmp`` and an atomic rename, so a kill leaves the last one whole."""
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp")
    with h5py.File(tmp, "w") as f:
        f.attrs.update(attrs)
        for name, arr in arrays.items():
            f.create_dataset(name, data=arr)
    os.replace(tmp, path)
    return path


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
