"""Files written so that nothing half-written is ever taken for whole and a full disk is an
error, not a crash.

Everything goes to ``<name>.tmp`` and is renamed when complete (``os.replace``: atomic on
POSIX), after an ``fsync`` so that a reboot does not leave a renamed but empty file.  An HDF5
file first reserves the space it may need (``fallocate`` beyond the end of the file), because
HDF5 2.0 through h5py 3.16 crashes the interpreter (SIGSEGV on close) when a write meets a full
disk; with the space reserved, a full disk is a :class:`DiskFullError` before anything is
written.  Locks are ``flock`` on a file: the kernel drops them when their process dies, so a
killed run never leaves a folder locked.
"""
from __future__ import annotations

import contextlib
import ctypes
import ctypes.util
import errno
import fcntl
import functools
import os
import shutil
from pathlib import Path

import h5py
import numpy as np

_FALLOC_FL_KEEP_SIZE = 1        # linux/falloc.h: reserve blocks, leave the size (HDF5 sees an empty file)


class DiskFullError(OSError):
    """No space for a file: raised before it is written (the temporary file is removed)."""

    def __init__(self, path, need: int | None = None):
        free = _free(Path(path).parent)
        what = f"needs up to {need / 1e6:.1f} MB, " if need else ""
        super().__init__(errno.ENOSPC, f"no space left on device for {str(path)!r} ({what}"
                                       f"{free / 1e6:.1f} MB free there): nothing was written")

    def __str__(self):
        return self.strerror


def _free(folder: Path) -> int:
    try:
        return shutil.disk_usage(folder).free
    except OSError:
        return 0


def tmp_path(path) -> Path:
    """Where ``path`` is written before it is renamed: ``<path>.tmp``."""
    path = Path(path)
    return path.with_name(path.name + ".tmp")


@contextlib.contextmanager
def replaced(path):
    """Yields ``<path>.tmp`` to write; when the block ends without error it is synced and renamed
    to ``path``, else removed (a full disk raised as :class:`DiskFullError`)."""
    path = Path(path)
    tmp = tmp_path(path)
    try:
        yield tmp
        with open(tmp, "rb") as f:
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException as err:
        tmp.unlink(missing_ok=True)
        if isinstance(err, OSError) and err.errno == errno.ENOSPC and not isinstance(err, DiskFullError):
            raise DiskFullError(path) from None
        raise


def h5_bound(arrays) -> int:
    """An upper bound on the bytes an HDF5 file of ``arrays`` takes, compressed or not: gzip
    stores an incompressible chunk with a few bytes per 64 KiB block more than it had; the rest
    is object headers and chunk indexes."""
    arrays = list(arrays)
    nbytes = sum(a.nbytes if hasattr(a, "nbytes") else np.asarray(a).nbytes for a in arrays)
    return int(1.01 * nbytes) + (1 << 20) + (64 << 10) * len(arrays)


@functools.cache
def _fallocate():
    """libc's ``fallocate``, or None where there is none (then free space is compared)."""
    try:
        fallocate = ctypes.CDLL(ctypes.util.find_library("c"), use_errno=True).fallocate
    except (OSError, AttributeError, TypeError):
        return None
    fallocate.argtypes = [ctypes.c_int, ctypes.c_int, ctypes.c_int64, ctypes.c_int64]
    return fallocate


def _reserve(fo, nbytes: int, path) -> None:
    """Reserve ``nbytes`` behind the (empty) file ``fo``, or raise DiskFullError."""
    fallocate = _fallocate()
    if fallocate is not None:
        if fallocate(fo.fileno(), _FALLOC_FL_KEEP_SIZE, 0, nbytes) == 0:
            return
        code = ctypes.get_errno()
        if code == errno.ENOSPC:
            raise DiskFullError(path, nbytes)
        if code not in (errno.EOPNOTSUPP, errno.ENOSYS, errno.EINVAL):
            raise OSError(code, f"{os.strerror(code)}: reserving {nbytes} bytes for {str(path)!r}")
    if _free(Path(path).parent) < nbytes:            # a file system that cannot reserve
        raise DiskFullError(path, nbytes)


@contextlib.contextmanager
def h5_reserved(path, nbytes: int):
    """An empty binary file object for an HDF5 writer (h5py, xarray's h5netcdf), with ``nbytes``
    (see :func:`h5_bound`) reserved behind it, renamed to ``path`` when the block ends without
    error."""
    with replaced(path) as tmp, open(tmp, "w+b") as fo:
        _reserve(fo, nbytes, path)
        yield fo


@contextlib.contextmanager
def h5_written(path, nbytes: int):
    """An ``h5py.File`` to fill, written as :func:`h5_reserved`."""
    with h5_reserved(path, nbytes) as fo, h5py.File(fo, "w") as f:   # closing truncates to what HDF5 used
        yield f


@contextlib.contextmanager
def locked(path, wait: bool = True, what: str = ""):
    """Hold an exclusive ``flock`` on ``path`` (created if missing) for the block.  ``wait``
    False: raise BlockingIOError at once when another process holds it, with the holder's note
    (``what``, written into the file by whoever holds it) as the message."""
    path = Path(path)
    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
        except BlockingIOError:
            holder = os.pread(fd, 4096, 0).decode(errors="replace").strip()
            raise BlockingIOError(errno.EWOULDBLOCK, holder or "held by another process") from None
        if what:
            os.ftruncate(fd, 0)
            os.pwrite(fd, what.encode(), 0)
        yield path
    finally:
        os.close(fd)                           # closing drops the lock


def is_locked(path) -> bool:
    """Whether another process holds the lock on ``path`` now."""
    try:
        fd = os.open(path, os.O_RDWR)
    except FileNotFoundError:
        return False
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        return False
    except BlockingIOError:
        return True
    finally:
        os.close(fd)


def write_text(path, text: str) -> Path:
    """``text`` to ``path`` through ``<path>.tmp`` and a rename."""
    with replaced(path) as tmp:
        tmp.write_text(text)
    return Path(path)
