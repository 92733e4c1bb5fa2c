"""Reading two channels for ``axlebox diagnose`` / ``axlebox report``, the reader chosen by the
file's first bytes (not its name):

* ``axlebox-result`` HDF5 (``axlebox simulate`` / ``axlebox bearing simulate``): sensors ``ws2_L``
  and ``ws2_R`` by default, the vertical column (2) of ``signals/<sensor>/acceleration``, ``fs``
  from its ``fs_hz`` attribute; the shaft speed and bearing from the stored config, read through
  the loader that runs it (vehicle: :func:`axlebox.mbs.vehicle.config.validate`, ``run.speed_kmh``,
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

What an acquisition spoils (:mod:`axlebox.bearing.diagnostics.acquisition`): NaN or inf
samples (a lost packet, an empty CSV cell, a channel that ends before the other in a CSV) and
runs of one value longer than ``HOLD_S`` (a logger repeating its last reading while the sensor
is away) are read around: the record is cut to the longest stretch where both channels are
finite and moving, and a note says what was left out; where no stretch is left, or a channel is
constant throughout (a dropped sensor), the record is refused.  Gaps are not filled or spliced:
a fill or a splice every lost packet modulates the envelope at the packets' rate, a line a
fault could be read at.

A record longer than ``max_samples`` (:func:`read`; the whole-record diagnosis passes
:data:`MAX_SAMPLES`) is read on its middle ``max_samples`` samples, the rest never held in
memory: a CSV is parsed row by row and counted first, HDF5 and MATLAB v7.3 datasets are read on
that span alone (a MATLAB v5 file is loaded whole by scipy, then cut).  The analysis holds a few
kB a sample (the copy test's segment spectra, bearing/diagnostics/coherence.py), so its memory is
bounded by the span, not by the record (benchmarks/README.md, "Long records").
"""
from __future__ import annotations

import csv
import itertools
import math
import tomllib
from array import array
from dataclasses import dataclass, field
from pathlib import Path

import h5py
import numpy as np

from axlebox._params import ParameterError
from axlebox.bearing import catalogue, resultfile
from axlebox.bearing.diagnostics.acquisition import HOLD_S, held
from axlebox.bearing.frequencies import FaultOrders, shaft_hz
from axlebox.mbs.vehicle.config import CarConfig, validate
from axlebox.mbs.solver.system import TRACK_RAMP_S

HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"
DEFAULT_SENSORS = ("ws2_L", "ws2_R")
TRACK_FADE_IN_S = TRACK_RAMP_S   # vehicle runs start on smooth track (mbs/solver/system.py)
# samples a channel the whole-record diagnosis reads: 41 s at 25.6 kHz, 105 s at 10 kHz, 2.8 GB
# of memory at most for the analysis (benchmarks/README.md, "Long records"); a longer record is
# read on its middle (away from a sensor's settling at the start), or in windows (--window-turns)
MAX_SAMPLES = 2 ** 20


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
    start: int = 0                    # the file's index of the first sample read
    n_file: int = 0                   # samples a channel in the file
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


def _span(n: int, samples, max_samples) -> tuple[int, int]:
    """``[a, b)``: the samples asked (``samples``), else the middle ``max_samples`` of ``n``
    (all where None or more)."""
    if samples is not None:
        return max(0, int(samples[0])), min(n, int(samples[1]))
    if max_samples is None or n <= max_samples:
        return 0, n
    a = (n - int(max_samples)) // 2
    return a, a + int(max_samples)


def _length(data, name: str, side: str) -> int:
    """Samples of the numeric vector ``data`` (array or HDF5 dataset: a column or row vector)."""
    shape, dtype = tuple(data.shape), np.dtype(data.dtype)
    if dtype.kind not in "fiu" or len(shape) not in (1, 2) or (len(shape) == 2 and min(shape) != 1):
        raise ParameterError(f"--{side} {name!r} of shape {shape} and type {dtype} is not "
                             "allowed: expected a numeric vector")
    return int(max(shape))


def _channel(data, name: str, side: str, span=None, finite: bool = True) -> np.ndarray:
    """Samples ``span`` = ``[a, b)`` (default all) of the numeric vector ``data`` as a 1-D float
    channel (a column or row vector is flattened; an HDF5 dataset is read on the span alone);
    NaN/inf refused by name where ``finite``, else kept (the gaps :func:`condition` reads
    around)."""
    n = _length(data, name, side)
    a, b = (0, n) if span is None else span
    if len(data.shape) == 1:
        x = data[a:b]
    else:
        x = data[:, a:b] if data.shape[0] == 1 else data[a:b, :]
    x = np.asarray(x, float).ravel()
    if finite:
        bad = int(np.count_nonzero(~np.isfinite(x)))
        if bad:
            raise ParameterError(f"--{side} {name!r} holds {bad} NaN/inf samples of {x.size}: "
                                 "expected finite samples (clean or cut the record first)")
    return x


def _same_length(names, n_left: int, n_right: int) -> None:
    if n_left != n_right:
        raise ParameterError(f"--left {names[0]!r} has {n_left} samples and --right {names[1]!r} "
                             f"{n_right}, not allowed: expected two channels sampled together (cut "
                             "them to their common span)")


def _pair(data, names, samples, max_samples) -> tuple[np.ndarray, np.ndarray, int, int]:
    """Both channels ``data`` (two numeric vectors, names ``names``) on the span of
    :func:`_span`: ``(left, right, first sample, samples in the file)``; vectors of different
    lengths refused (in a CSV a shorter column reads as trailing gaps instead)."""
    n = [_length(d, nm, s) for d, nm, s in zip(data, names, ("left", "right"))]
    _same_length(names, *n)
    span = _span(n[0], samples, max_samples)
    left, right = (_channel(d, nm, s, span, finite=False)
                   for d, nm, s in zip(data, names, ("left", "right")))
    return left, right, span[0], n[0]


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


def _read_result(path, left, right, fs, column: int, samples=None, max_samples=None) -> Record:
    with resultfile.open_result(path) as f:
        sensors = sorted(f["signals"]) if "signals" in f else []
        names = [_pick(sensors, n, s, d, "the result's signals/")
                 for n, s, d in ((left, "left", DEFAULT_SENSORS[0]), (right, "right", DEFAULT_SENSORS[1]))]
        ds = [f[f"signals/{n}/acceleration"] for n in names]
        for d, n in zip(ds, names):
            if len(d.shape) != 2 or not 0 <= column < d.shape[1]:
                raise ParameterError(f"--column {column} is not allowed: signals/{n}/acceleration "
                                     f"has columns 0..{d.shape[1] - 1 if len(d.shape) == 2 else -1}")
        fs = _need_fs(fs if fs is not None else ds[0].attrs.get("fs_hz"), "this result file")
        cfg = _file_config(f, path)
        vehicle = isinstance(cfg, CarConfig)
        _same_length(names, ds[0].shape[0], ds[1].shape[0])
        n = ds[0].shape[0]
        n0 = int(round(TRACK_FADE_IN_S * fs))
        n0 = n0 if vehicle and min(d.shape[0] for d in ds) > 2 * n0 else 0   # the track's fade-in
        a, b = (_span(n, samples, None) if samples is not None else
                tuple(n0 + i for i in _span(n - n0, None, max_samples)))
        left, right = (_channel(d[a:b, column], nm, s, finite=False)
                       for d, nm, s in zip(ds, names, ("left", "right")))
        angle = _stored_angle(f, cfg, names, n, (a, b))
        loads = _roller_loads(f, cfg, names)
    rec = Record(left, right, fs, tuple(names), "axlebox-result", angle=angle, start=a, n_file=n,
                 roller_loads=loads)
    if cfg is not None:                       # the run's own speed, wheel and bearing
        rec.shaft_hz = shaft_hz(*((cfg.run.speed_kmh, cfg.wheelset.r0) if vehicle
                                  else (cfg.speed_kmh, cfg.r_wheel)))
        rec.bearing = catalogue.of(cfg.bearing, "the file's [bearing]")
        rec.orders = rec.bearing.orders
    if n0 and samples is None:
        rec.notes.append(f"first {TRACK_FADE_IN_S:g} s (track fade-in) left out")
    return rec


def _stored_angle(f: h5py.File, cfg, names, n: int, span) -> np.ndarray | None:
    """The shaft angle (turns) of the sensors' wheelset (``ws<k>`` of ``ws<k>_L``) a car run along
    a speed profile stores, one a sample, on the samples ``span`` read; None for a constant-speed
    run (read at its config's speed, as it ran) or where the file has none."""
    if not isinstance(cfg, CarConfig) or not cfg.speed_profile().accelerates:
        return None
    ws = names[0].split("_")[0]
    ds = f.get(f"shafts/{ws}/angle")
    if ds is None or ds.shape[0] != n:
        return None
    return np.asarray(ds[span[0]:span[1]], float) / (2 * np.pi)


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
    :class:`~axlebox.bearing.rig.RigConfig` (``[rig]``), a :class:`~axlebox.mbs.vehicle.config.CarConfig`
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


def _read_hdf5(path, left, right, fs, kind: str, samples=None, max_samples=None) -> Record:
    where = Path(path).name
    with h5py.File(path, "r") as f:
        ds = _h5_datasets(f)
        # MATLAB v7.3 keeps its bookkeeping under #refs#/#subsystem#: not user variables
        avail = sorted(n for n in ds if not n.startswith("#"))
        names = [_pick(avail, n, s, None, where) for n, s in ((left, "left"), (right, "right"))]
        x_l, x_r, a, n = _pair([ds[nm] for nm in names], names, samples, max_samples)
        if fs is None:                        # an fs attribute on the datasets, or a scalar fs
            for key in ("fs_hz", "fs"):
                if key in ds[names[0]].attrs:
                    fs = float(np.ravel(ds[names[0]].attrs[key])[0])
                    break
                if key in ds and ds[key].size == 1:
                    fs = float(np.ravel(ds[key][()])[0])
                    break
    return Record(x_l, x_r, _need_fs(fs, f"{where} (no fs_hz attribute or fs variable)"),
                  tuple(names), kind, start=a, n_file=n)


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


def _read_mat5(path, left, right, fs, samples=None, max_samples=None) -> Record:
    try:
        m = _loadmat_isolated(path)
    except ParameterError:
        raise
    except Exception as err:  # noqa: BLE001 - scipy raises several types for a broken file
        first = str(err).splitlines()[0] if str(err) else type(err).__name__
        raise ParameterError(f"input file {str(path)!r} is not a readable MATLAB v5 file: {first}") from None
    avail = sorted(k for k in m if not k.startswith("__"))
    names = [_pick(avail, n, s, None, Path(path).name) for n, s in ((left, "left"), (right, "right"))]
    x_l, x_r, a, n = _pair([np.asarray(m[nm]) for nm in names], names, samples, max_samples)
    if fs is None:
        for key in ("fs", "Fs", "fs_hz"):
            if key in m and np.size(m[key]) == 1:
                fs = float(np.ravel(m[key])[0])
                break
    return Record(x_l, x_r, _need_fs(fs, f"{Path(path).name} (no fs variable)"),
                  tuple(names), "mat5", start=a, n_file=n)


def _cell(v: str) -> float:
    """A CSV cell as a number; an empty cell is a gap (NaN)."""
    return float(v) if v.strip() else math.nan


def _numeric(row) -> bool:
    try:
        [_cell(v) for v in row]
        return True
    except ValueError:
        return False


def _count_lines(path) -> int:
    """Lines of a text file (the last one without its newline counted), in 1 MiB blocks."""
    n, last = 0, b"\n"
    with open(path, "rb") as fh:
        while block := fh.read(1 << 20):
            n += block.count(b"\n")
            last = block[-1:]
    return n + (last != b"\n")


def _read_csv(path, left, right, fs, samples=None, max_samples=None) -> Record:
    """Parsed row by row: only the rows of the span read are kept (:func:`_span`; a longer file
    is counted first, its blank lines with the rows).  An empty cell, or a row shorter than the
    header (a channel that ended first), is a gap (NaN), read around by :func:`condition`."""
    with open(path, newline="", errors="replace") as fh:
        try:
            delim = csv.Sniffer().sniff(fh.read(4096), delimiters=",;\t ").delimiter
        except csv.Error:
            delim = ","
        fh.seek(0)
        rows = (r for r in csv.reader(fh, delimiter=delim, skipinitialspace=True) if r)
        first = next(rows, None)
        if first is None:
            raise ParameterError(f"input file {str(path)!r} is empty: expected two columns of samples")
        header = None if _numeric(first) else [h.strip() for h in first]
        if header is None:
            rows = itertools.chain([first], rows)
            ncol = len(first)
        else:
            second = next(rows, None)
            ncol = len(second) if second is not None else 0
            rows = itertools.chain([second] if second is not None else [], rows)
        cols = header or [str(i) for i in range(ncol)]
        if ncol < 2:
            raise ParameterError(f"input file {str(path)!r} has {ncol} column(s): expected two channels")
        names = [_pick(cols, n, s, d, f"{Path(path).name} (columns)")
                 for n, s, d in ((left, "left", cols[0]), (right, "right", cols[1]))]
        idx = [cols.index(n) for n in names]
        a, b, n = 0, None, None
        if samples is not None or max_samples is not None:
            n = _count_lines(path) - (header is not None)
            a, b = _span(n, samples, max_samples)
        out = (array("d"), array("d"))
        for k, row in enumerate(itertools.islice(rows, a, b)):
            for j, o in zip(idx, out):
                try:
                    o.append(_cell(row[j]) if j < len(row) else math.nan)
                except ValueError:
                    raise ParameterError(f"input file {str(path)!r} row {a + k + 1 + (header is not None)} "
                                         f"column {cols[j]!r} holds {row[j][:20]!r}: expected numbers "
                                         "in every row (an empty cell or NaN is a gap)") from None
    x_l, x_r = (np.frombuffer(o, float) if len(o) else np.zeros(0) for o in out)
    return Record(x_l, x_r, _need_fs(fs, "a CSV file"), tuple(names), "csv", start=a,
                  n_file=n if n is not None else x_l.size)


def condition(rec: Record) -> Record:
    """``rec`` read around what the acquisition lost (module docstring): a channel constant
    throughout refused (a dropped sensor); NaN/inf samples and runs of one value of ``HOLD_S``
    or longer in either channel left out by cutting both to the longest stretch without them
    (``rec.angle`` and ``rec.start`` with them, a note saying what); no such stretch refused."""
    n = rec.left.size
    if n == 0:
        return rec
    for side, x, name in (("left", rec.left, rec.names[0]), ("right", rec.right, rec.names[1])):
        ok = x[np.isfinite(x)]
        if ok.size and ok.min() == ok.max():
            raise ParameterError(f"--{side} {name!r} is constant ({ok[0]:g} in all {ok.size} finite "
                                 f"samples of {n}): a dropped sensor (or a range far too coarse); "
                                 "expected a signal on both sides")
    bad = ~(np.isfinite(rec.left) & np.isfinite(rec.right))
    n_nan = int(np.count_nonzero(bad))
    n_gaps = int(np.count_nonzero(np.diff(np.r_[0, bad.astype(np.int8)]) == 1))
    n_hold = max(2, int(math.ceil(HOLD_S * rec.fs)))
    holds = [r for x in (rec.left, rec.right) for r in held(x, n_hold)]
    for a, b in holds:
        bad[a:b] = True
    if not bad.any():
        return rec
    edges = np.flatnonzero(np.diff(np.r_[1, bad.astype(np.int8), 1]))   # good runs: [edges[2k], edges[2k+1])
    starts, stops = edges[0::2], edges[1::2]
    what = []
    if n_nan:
        what.append(f"{n_nan} NaN/inf samples in {n_gaps} gap(s)")
    if holds:
        what.append(f"{len(holds)} stretch(es) of one value held {HOLD_S:g} s or longer (a dropped "
                    f"sensor), {sum(b - a for a, b in holds)} samples")
    if starts.size == 0:
        raise ParameterError(f"--left {rec.names[0]!r} / --right {rec.names[1]!r}: no sample is left "
                             f"to read, not allowed: the record holds {' and '.join(what)}")
    i = int(np.argmax(stops - starts))
    a, b = int(starts[i]), int(stops[i])
    rec.left, rec.right = rec.left[a:b], rec.right[a:b]
    rec.angle = rec.angle[a:b] if rec.angle is not None else None
    rec.notes.append(f"read samples {rec.start + a}-{rec.start + b} ({(b - a) / rec.fs:.4g} s), the longest "
                     f"stretch without {' or '.join(what)}")
    rec.start += a
    return rec


def read(path, left=None, right=None, fs=None, column: int = 2, *, samples=None,
         max_samples=None, clean: bool = True) -> Record:
    """The two channels of ``path`` (see the module docstring for the formats): the samples
    ``samples`` = ``[a, b)`` of the file, else its middle ``max_samples`` (all where None);
    ``clean``: read around gaps and held values (:func:`condition`), else NaN/inf refused."""
    kind = file_kind(path)
    try:
        if kind == "axlebox-result":
            rec = _read_result(path, left, right, fs, column, samples, max_samples)
        elif kind in ("hdf5", "mat73"):
            rec = _read_hdf5(path, left, right, fs, kind, samples, max_samples)
        elif kind == "mat5":
            rec = _read_mat5(path, left, right, fs, samples, max_samples)
        else:
            rec = _read_csv(path, left, right, fs, samples, max_samples)
    except ParameterError:
        raise
    except (OSError, RuntimeError, KeyError, ValueError, TypeError, IndexError, MemoryError) as err:
        # h5py and scipy report a damaged file by any of these (a bad header, a message of an
        # unknown version, a size it cannot allocate): one line naming the file
        first = str(err).splitlines()[0] if str(err) else type(err).__name__
        raise ParameterError(f"input file {str(path)!r} is not readable as {kind}: {first}") from None
    if samples is None and max_samples is not None and rec.left.size == max_samples < rec.n_file:
        rec.notes.append(f"read samples {rec.start}-{rec.start + rec.left.size}, the middle "
                         f"{rec.left.size / rec.fs:.4g} s of {rec.n_file / rec.fs:.4g} s (longer records: "
                         "--window-turns)")
    if clean:
        return condition(rec)
    for side, x, name in (("left", rec.left, rec.names[0]), ("right", rec.right, rec.names[1])):
        _channel(x, name, side)               # refuses NaN/inf by name
    return rec
