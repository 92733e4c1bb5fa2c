"""Where axlebox keeps what it can rebuild (meshes, reduced bodies, wheel-rail tables, numba's
machine code), and the hash of a subpackage's sources that names what would go stale."""
from __future__ import annotations

import hashlib
import importlib.util
import os
from collections.abc import Iterable
from pathlib import Path


def cache_dir(*parts: str) -> Path:
    """``$AXLEBOX_CACHE/<parts>``, or ``~/.cache/axlebox/<parts>`` when that is unset."""
    root = os.environ.get("AXLEBOX_CACHE") or Path.home() / ".cache" / "axlebox"
    return Path(root, *parts)


def package_dir(sub: str) -> Path:
    """The folder of ``axlebox.<sub>`` wherever it is: a source checkout (``pyproject.toml`` maps
    the top-level folder) or an installed package.  The subpackage is located, not imported."""
    spec = importlib.util.find_spec(f"axlebox.{sub}")
    if spec is None or not spec.submodule_search_locations:
        raise ModuleNotFoundError(f"axlebox.{sub} is not a package of this installation")
    return Path(next(iter(spec.submodule_search_locations))).resolve()


def source_hash(folders: Iterable[Path], *, only_with: bytes | tuple[bytes, ...] | None = None) -> str:
    """SHA-1 (12 hex digits) of the ``*.py`` files under ``folders`` (those containing
    ``only_with``, or one of them, when given), each named by its folder's name and its path
    inside it, so the same sources hash alike in a checkout and in an installed package."""
    marks = (only_with,) if isinstance(only_with, bytes) else only_with
    h = hashlib.sha1()
    for folder in folders:
        folder = Path(folder)
        for p in sorted(folder.rglob("*.py")):
            text = p.read_bytes()
            if marks is None or any(m in text for m in marks):
                name = (Path(folder.name) / p.relative_to(folder)).as_posix()
                h.update(name.encode() + b"\0" + text)
    return h.hexdigest()[:12]
