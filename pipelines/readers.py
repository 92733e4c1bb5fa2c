"""Reading two channels for ``axlebox diagnose`` / ``axlebox report``, the reader chosen by the
file's first bytes (not its name):

* ``axlebox-result`` HDF5 (``axlebox simulate`` / ``axlebox bearing simulate``): sensors ``ws2_L``
  and ``ws2_R`` by default, the vertical column (2) of ``signals/<sensor>/acceleration``, ``fs``
  from its ``fs_hz`` attribute; the shaft speed and bearing from the stored config, read through
  the loader that runs it (vehicle: :func:`axlebox.mbs.config.validate`, ``run.speed_kmh``,
  ``wheelset.r0`` and ``[bearing]``; rig: :func:`axlebox.bearing.rig.config_from_dict`,
  ``rig.speed_kmh``, ``rig.r_wheel`` and its ``[bearing]``), defaults filled in as a run fills
  them; the most loaded roller's load on each side (the 99th percentile of the sensor's
  bearing's ``bearings/bearing<k><L|R>/roller1_cup_force``, both rows, past the fade-in), for the
  defect's size (bearing/diagnostics/size.py: a loaded roller's contact approach).
* MATLAB ``.mat`` v5 (scipy.io.loadmat) and v7.3 (HDF5 after a 512-byte header; MATLAB stores
  arrays column-major, so h5py sees them transposed: a column vector reads as (1, n)).
* any other HDF5: ``--left``/``--right`` are dataset paths; ``fs`` from --fs or the datasets'
  ``fs_hz``/``fs`` attribute.
* CSV / text: two (or more) columns, an optional header line naming them; ``--fs`` is required.

Every refusal is a ParameterError (exit status 2) whose one line names the option, variable or
value at fault.
"""
from __future__ import annotations

import csv
import io
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import h5py
import numpy as np

from axlebox._params import ParameterError
from axlebox.bearing import catalogue, resultfile
from axlebox.bearing.frequencies import FaultOrders, shaft_hz
from axlebox.mbs.config import CarConfig, validate
from axlebox.mbs.system import TRACK_RAMP_S

HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"
DEFAULT_SENSORS = ("ws2_L", "ws2_R")
TRACK_FADE_IN_S = TRACK_RAMP_S   # vehicle runs start on smooth track (mbs/system.py)


@dataclass
class Record:
    """Two channels read from a file, with what the file says about its machine."""

    left: np.ndarray
    right: np.ndarray
    fs: float
    names: tuple[str, str]
    kind: str
    shaft_hz: float | None = None
    orders: FaultOrders | None = None
    bearing: object = None        # the file's bearing (catalogue.Bearing), where its config has one
    notes: list[str] = field(default_factory=list)
    angle: np.ndarray | None = None   # the shaft's angle (turns) at each sample, where the file has it
    roller_loads: tuple | None = None  # (left, right) most loaded roller's load (N), where stored


def file_kind(path) -> str:
    """``"axlebox-result"``, ``"hdf5"``, ``"mat5"``, ``"mat73"`` or ``"csv"`` from the content."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"input file {str(path)!r} does not exist")
    try:
        with open(path, "rb") as fh:
            head = fh.read(2048 + 8)
    except OSError as err:
        raise ParameterError(f"input file {str(path)!r} is not readable: {err.strerror}") from None
    if head.startswith(b"MATLAB") and len(head) >= 128:
        # bytes 124-125: version 0x0100 (v5..v7) or 0x0200 (v7.3, an HDF5 file after 512 bytes)
        ver = int.from_bytes(head[124:126], "little" if head[126:128] == b"IM" else "big")
        return "mat73" if ver == 0x0200 else "mat5"
    # HDF5 looks for its signature at 0, 512, 1024, 2048, ... (a user block may precede it)
    if any(head[o:o + 8] == HDF5_SIGNATURE for o in (0, 512, 1024, 2048)):
        try:
            with h5py.File(path, "r") as f:
                return "axlebox-result" if f.attrs.get("format") == resultfile.FORMAT else "hdf5"
        except (OSError, RuntimeError, KeyError, ValueError) as err:      # a damaged file
            raise ParameterError(f"input file {str(path)!r} is not readable as HDF5: {err}") from None
    if b"\x00" not in head:
        return "csv"
    raise ParameterError(f"input file {str(path)!r} is of an unknown type: expected an "
                         "axlebox-result or other HDF5 file, a MATLAB .mat (v5 or v7.3) or a CSV "
                         "text file")


def _channel(data, name: str, side: str) -> np.ndarray:
    """A 1-D float channel (a column or row vector is flattened); NaNs refused by name."""
    x = np.asarray(data)
    if x.dtype.kind not in "fiu" or x.ndim > 2 or (x.ndim == 2 and min(x.shape) != 1):
        raise ParameterError(f"--{side} {name!r} of shape {x.shape} and type {x.dtype} is not "
                             "allowed: expected a numeric vector")
    x = x.astype(float).ravel()
    bad = int(np.count_nonzero(~np.isfinite(x)))
    if bad:
        raise ParameterError(f"--{side} {name!r} holds {bad} NaN/inf samples of {x.size}: "
                             "expected finite samples (clean or cut the record first)")
    return x


def _pick(available: list[str], asked: str | None, side: str, default: str | None, where: str) -> str:
    name = asked if asked is not None else default
    if name is None:
        raise ParameterError(f"--{side} is missing: name the {side} channel, one of "
                             f"{', '.join(available) or '(none)'} in {where}")
    if name not in available:
        raise ParameterError(f"--{side} {name!r} is not in {where}: expected one of "
                             f"{', '.join(available) or '(none)'}")
    return name


def _need_fs(fs, where: str) -> float:
    if fs is None:
        raise ParameterError(f"--fs is missing: {where} carries no sampling rate; give --fs HZ")
    if not np.isfinite(fs) or not fs > 0:
        raise ParameterError(f"--fs = {fs!r} is not allowed: expected a sampling rate > 0 Hz")
    return float(fs)


def _read_result(path, left, right, fs, column: int) -> Record:
    with resultfile.open_result(path) as f:
        sensors = sorted(f["signals"]) if "signals" in f else []
        names = [_pick(sensors, n, s, d, "the result's signals/")
                 for n, s, d in ((left, "left", DEFAULT_SENSORS[0]), (right, "right", DEFAULT_SENSORS[1]))]
        chans = []
        for n, side in zip(names, ("left", "right")):
            ds = f[f"signals/{n}/acceleration"]
            if not 0 <= column < ds.shape[1]:
                raise ParameterError(f"--column {column} is not allowed: signals/{n}/acceleration "
                                     f"has columns 0..{ds.shape[1] - 1}")
            chans.append(_channel(ds[:, column], n, side))
        fs_file = f[f"signals/{names[0]}/acceleration"].attrs.get("fs_hz")
        cfg = _file_config(f, path)
        angle = _stored_angle(f, cfg, names, chans[0].size)
        loads = _roller_loads(f, cfg, names)
    rec = Record(chans[0], chans[1], _need_fs(fs if fs is not None else fs_file, "this result file"),
                 tuple(names), "axlebox-result", angle=angle, roller_loads=loads)
    vehicle = isinstance(cfg, CarConfig)
    if cfg is not None:                       # the run's own speed, wheel and bearing
        rec.shaft_hz = shaft_hz(*((cfg.run.speed_kmh, cfg.wheelset.r0) if vehicle
                                  else (cfg.speed_kmh, cfg.r_wheel)))
        rec.bearing = catalogue.of(cfg.bearing, "the file's [bearing]")
        rec.orders = rec.bearing.orders
    if vehicle:                               # drop the track irregularity's fade-in
        n0 = int(round(TRACK_FADE_IN_S * rec.fs))
        if rec.left.size > 2 * n0:
            rec.left, rec.right = rec.left[n0:], rec.right[n0:]
            rec.angle = rec.angle[n0:] if rec.angle is not None else None
            rec.notes.append(f"first {TRACK_FADE_IN_S:g} s (track fade-in) left out")
    return rec


def _stored_angle(f: h5py.File, cfg, names, n: int) -> np.ndarray | None:
    """The shaft angle (turns) of the sensors' wheelset (``ws<k>`` of ``ws<k>_L``) a car run along
    a speed profile stores, one a sample; None for a constant-speed run (read at its config's
    speed, as it ran) or where the file has none."""
    if not isinstance(cfg, CarConfig) or not cfg.speed_profile().accelerates:
        return None
    ws = names[0].split("_")[0]
    ds = f.get(f"shafts/{ws}/angle")
    if ds is None or ds.shape[0] != n:
        return None
    return np.asarray(ds[()], float) / (2 * np.pi)


def _roller_loads(f: h5py.File, cfg, names) -> tuple | None:
    """Each sensor's bearing's most loaded roller's load (N) in a car run: the 99th percentile of
    its roller 1's cup force (both rows; roller 1 passes the load zone once a cage turn) after
    the track's fade-in; None where the file stores none."""
    if not isinstance(cfg, CarConfig):
        return None
    out = []
    for n in names:
        ds = f.get(f"bearings/bearing{n.removeprefix('ws').replace('_', '')}/roller1_cup_force")
        t = f.get("time")
        if ds is None or t is None or ds.shape[0] != t.shape[0]:
            out.append(None)
            continue
        q = np.asarray(ds[()], float)[np.asarray(t[()]) >= TRACK_FADE_IN_S]
        out.append(float(np.percentile(q, 99.0)) if q.size else None)
    return tuple(out)


def _file_config(f: h5py.File, path):
    """The config the open result file ``f`` stores, through the loader that ran it: a
    :class:`~axlebox.bearing.rig.RigConfig` (``[rig]``), a :class:`~axlebox.mbs.config.CarConfig`
    (a vehicle run: its config has ``[run]`` or the file wheel-rail outputs) or None (neither);
    a config this version refuses is one line naming the file and the field."""
    from axlebox.bearing.rig import config_from_dict
    try:
        raw = tomllib.loads(str(f.attrs.get("config", "")))
    except tomllib.TOMLDecodeError as err:
        raise ParameterError(f"input file {str(path)!r}: its stored config is not valid TOML "
                             f"({err})") from None
    try:
        if "rig" in raw:
            return config_from_dict(raw)
        return validate(raw) if "run" in raw or "wheelrail" in f else None
    except ParameterError as err:
        raise ParameterError(f"input file {str(path)!r}: its stored config is not one this version "
                             f"runs ({err})") from None


def result_config(path):
    """The config an axlebox-result file stores, as its run had it (:func:`_file_config`): a
    rig's, a car's, or None for a file of neither."""
    with resultfile.reading(path) as f:
        return _file_config(f, path)


def _h5_datasets(f: h5py.File) -> dict[str, h5py.Dataset]:
    out = {}
    f.visititems(lambda n, o: out.__setitem__(n, o) if isinstance(o, h5py.Dataset) else None)
    return out


def _read_hdf5(path, left, right, fs, kind: str) -> Record:
    where = Path(path).name
    with h5py.File(path, "r") as f:
        ds = _h5_datasets(f)
        # MATLAB v7.3 keeps its bookkeeping under #refs#/#subsystem#: not user variables
        avail = sorted(n for n in ds if not n.startswith("#"))
        names = [_pick(avail, n, s, None, where) for n, s in ((left, "left"), (right, "right"))]
        chans = [_channel(ds[n][()], n, s) for n, s in zip(names, ("left", "right"))]
        if fs is None:                        # an fs attribute on the datasets, or a scalar fs
            for key in ("fs_hz", "fs"):
                if key in ds[names[0]].attrs:
                    fs = float(np.ravel(ds[names[0]].attrs[key])[0])
                    break
                if key in ds and ds[key].size == 1:
                    fs = float(np.ravel(ds[key][()])[0])
                    break
    return Record(chans[0], chans[1], _need_fs(fs, f"{where} (no fs_hz attribute or fs variable)"),
                  tuple(names), kind)


def _loadmat(path: str) -> dict:
    from scipy.io import loadmat
    return loadmat(path)


def _loadmat_isolated(path) -> dict:
    """``scipy.io.loadmat`` in a child process: on some damaged files (sizes in the header that
    disagree with the data) it crashes the interpreter (SIGSEGV, found by tests/test_fuzz.py);
    a crash of the child is a refusal here, not the end of the command."""
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor
    from concurrent.futures.process import BrokenProcessPool
    ctx = mp.get_context("fork" if "fork" in mp.get_all_start_methods() else "spawn")
    with ProcessPoolExecutor(1, mp_context=ctx) as ex:
        try:
            return ex.submit(_loadmat, str(path)).result()
        except BrokenProcessPool:
            raise ParameterError(f"input file {str(path)!r} is not a readable MATLAB v5 file: the "
                                 "reader crashed on it (a damaged file)") from None


def _read_mat5(path, left, right, fs) -> Record:
    try:
        m = _loadmat_isolated(path)
    except ParameterError:
        raise
    except Exception as err:  # noqa: BLE001 - scipy raises several types for a broken file
        first = str(err).splitlines()[0] if str(err) else type(err).__name__
        raise ParameterError(f"input file {str(path)!r} is not a readable MATLAB v5 file: {first}") from None
    avail = sorted(k for k in m if not k.startswith("__"))
    names = [_pick(avail, n, s, None, Path(path).name) for n, s in ((left, "left"), (right, "right"))]
    chans = [_channel(m[n], n, s) for n, s in zip(names, ("left", "right"))]
    if fs is None:
        for key in ("fs", "Fs", "fs_hz"):
            if key in m and np.size(m[key]) == 1:
                fs = float(np.ravel(m[key])[0])
                break
    return Record(chans[0], chans[1], _need_fs(fs, f"{Path(path).name} (no fs variable)"),
                  tuple(names), "mat5")


def _read_csv(path, left, right, fs) -> Record:
    text = Path(path).read_text(errors="replace")
    sample = text[:4096]
    try:
        delim = csv.Sniffer().sniff(sample, delimiters=",;\t ").delimiter
    except csv.Error:
        delim = ","
    rows = [r for r in csv.reader(io.StringIO(text), delimiter=delim, skipinitialspace=True) if r]
    if not rows:
        raise ParameterError(f"input file {str(path)!r} is empty: expected two columns of samples")

    def numeric(row):
        try:
            [float(v) for v in row]
            return True
        except ValueError:
            return False
    header = None if numeric(rows[0]) else [h.strip() for h in rows[0]]
    body = rows[1:] if header else rows
    ncol = len(body[0]) if body else 0
    cols = header or [str(i) for i in range(ncol)]
    if ncol < 2:
        raise ParameterError(f"input file {str(path)!r} has {ncol} column(s): expected two channels")
    names = [_pick(cols, n, s, d, f"{Path(path).name} (columns)")
             for n, s, d in ((left, "left", cols[0]), (right, "right", cols[1]))]
    try:
        data = np.array([[float(v) for v in r] for r in body], float)
    except ValueError as err:
        raise ParameterError(f"input file {str(path)!r}: {err}: expected numbers in every row") from None
    chans = [_channel(data[:, cols.index(n)], n, s) for n, s in zip(names, ("left", "right"))]
    return Record(chans[0], chans[1], _need_fs(fs, "a CSV file"), tuple(names), "csv")


def read(path, left=None, right=None, fs=None, column: int = 2) -> Record:
    """The two channels of ``path`` (see the module docstring for the formats)."""
    kind = file_kind(path)
    try:
        if kind == "axlebox-result":
            return _read_result(path, left, right, fs, column)
        if kind in ("hdf5", "mat73"):
            return _read_hdf5(path, left, right, fs, kind)
        if kind == "mat5":
            return _read_mat5(path, left, right, fs)
        return _read_csv(path, left, right, fs)
    except ParameterError:
        raise
    except (OSError, RuntimeError, KeyError, ValueError, TypeError, IndexError, MemoryError) as err:
        # h5py and scipy report a damaged file by any of these (a bad header, a message of an
        # unknown version, a size it cannot allocate): one line naming the file
        first = str(err).splitlines()[0] if str(err) else type(err).__name__
        raise ParameterError(f"input file {str(path)!r} is not readable as {kind}: {first}") from None
