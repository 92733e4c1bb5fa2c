"""Where numba keeps the compiled kernels: a folder named by a hash of every kernel's source.

Numba's own cache checks only the source file of the function it loads; a kernel that calls
into another file keeps the callee it was compiled with.  After an edit (or a ``git pull``)
that touches only the callee, the stale machine code runs, and can crash the interpreter.
Keying the whole cache on all kernel sources of ``bearing`` and ``mbs`` together makes any
edit start a fresh folder.  ``NUMBA_CACHE_DIR``, when set, is left alone.
"""
from __future__ import annotations

import hashlib
import os
from pathlib import Path

from numba import config

_ROOTS = ("bearing", "mbs")


def kernel_hash(top: Path | None = None) -> str:
    """SHA-1 (12 hex digits) of the kernel sources (the files with ``@njit``) of ``bearing``
    and ``mbs`` under ``top`` (default: where this package is), in path order."""
    top = Path(__file__).resolve().parents[1] if top is None else Path(top)
    h = hashlib.sha1()
    for root in _ROOTS:
        for p in sorted((top / root).rglob("*.py")):
            text = p.read_bytes()
            if b"@njit" in text:
                h.update(str(p.relative_to(top)).encode() + b"\0" + text)
    return h.hexdigest()[:12]


def configure() -> None:
    if os.environ.get("NUMBA_CACHE_DIR"):
        return
    base = Path(os.environ.get("AXLEBOX_CACHE", Path.home() / ".cache" / "axlebox"))
    where = base / "numba" / kernel_hash()
    try:
        where.mkdir(parents=True, exist_ok=True)
    except OSError:         # read-only home: numba's own __pycache__ places stay in use
        return
    config.CACHE_DIR = str(where)


configure()
