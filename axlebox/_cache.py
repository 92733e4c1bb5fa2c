"""Where axlebox keeps what it can rebuild (meshes, reduced bodies, wheel-rail tables, numba's
machine code), and the hash of a subpackage's sources that names what would go stale."""
from __future__ import annotations

import functools
import hashlib
import importlib.util
import os
import re
from collections.abc import Iterable
from pathlib import Path

OWN = Path(__file__).resolve().parent     # axlebox's own folder: its top-level modules


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


def source_hash(folders: Iterable[Path]) -> str:
    """SHA-1 (12 hex digits) of the ``*.py`` files under ``folders``, each named by its folder's
    name and its path inside it, so the same sources hash alike in a checkout and in an
    installed package."""
    h = hashlib.sha1()
    for folder in folders:
        folder = Path(folder)
        for p in sorted(folder.rglob("*.py")):
            name = (Path(folder.name) / p.relative_to(folder)).as_posix()
            h.update(name.encode() + b"\0" + p.read_bytes())
    return h.hexdigest()[:12]


# ``from X import (a, b)`` / ``from X import a, b`` / ``import X, Y`` at the start of a line.  A
# text scan, not a parse: ten times faster (it runs at every import of the kernels), and where it
# errs (an import written in a docstring) it only adds a file to the key.
_IMPORT = re.compile(rb"^[ \t]*(?:from[ \t]+(\.*[\w.]*)[ \t]+import[ \t]+(\([^)]*\)|[^\n]*)"
                     rb"|import[ \t]+([^\n]*))", re.M)


@functools.lru_cache(maxsize=None)
def _subpackage(head: str) -> Path:
    """The folder of ``axlebox.<head>`` in this installation (where a subpackage of that name
    would be in axlebox's own folder, if it is none)."""
    try:
        return package_dir(head)
    except ModuleNotFoundError:
        return OWN / head


def _locate(name: str, top: Path | None) -> Path | None:
    """The file of module ``name`` (``axlebox.<...>``): in this installation, or in the package
    folder ``top`` (an installed layout: ``top/_numba.py``, ``top/bearing/...``); None if it is
    not a module of axlebox."""
    parts = name.split(".")
    if parts[0] != "axlebox":
        return None
    own = OWN if top is None else Path(top)
    if len(parts) == 1:
        return own / "__init__.py"
    head, rest = parts[1], parts[2:]
    folder = own / head if top is not None else _subpackage(head)
    p = folder.joinpath(*rest)
    for f in (p / "__init__.py", p.with_suffix(".py")):
        if f.is_file():
            return f
    return None


def _imports(name: str, path: Path) -> set[str]:
    """The axlebox modules the file ``path`` of module ``name`` imports (each ``from P import x``
    gives ``P.x`` where that is a module, else ``P``), with the packages on their way."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    out = set()
    for frm, names, plain in _IMPORT.findall(path.read_bytes()):
        if plain:
            mods = [m.split()[0] for m in plain.decode().split(",") if m.strip()]
        else:
            frm = frm.decode()
            dots = len(frm) - len(frm.lstrip("."))
            if dots:
                base = package.split(".")[:len(package.split(".")) - dots + 1]
                frm = ".".join(base + ([frm[dots:]] if frm[dots:] else []))
            names = names.decode().strip("()").replace("\\", " ")
            mods = [frm] + [f"{frm}.{n.split()[0]}" for n in names.split(",") if n.split()]
        for m in mods:
            parts = m.split(".")
            out.update(".".join(parts[:k]) for k in range(1, len(parts) + 1))
    return {m for m in out if m.split(".")[0] == "axlebox"}


def module_sources(packages: Iterable[str], top: Path | None = None) -> dict[str, Path]:
    """Module name -> file: every ``*.py`` of the subpackages ``packages`` (``axlebox.<p>``) and,
    transitively, every axlebox module they import, the packages' ``__init__`` on the way
    included (importing ``axlebox.fem.bodyfile`` runs ``axlebox/fem/__init__.py``).  ``top``: a
    copy in the installed layout instead of this installation."""
    found: dict[str, Path] = {}
    for pkg in packages:
        folder = _locate(f"axlebox.{pkg}", top).parent
        for p in sorted(folder.rglob("*.py")):
            rel = p.relative_to(folder).with_suffix("").parts
            rel = rel[:-1] if rel[-1] == "__init__" else rel
            found[".".join(("axlebox", pkg) + rel)] = p
    tried = set(found)
    todo = list(found)
    while todo:
        name = todo.pop()
        for m in _imports(name, found[name]) - tried:
            tried.add(m)
            path = _locate(m, top)
            if path is not None:        # else a name imported from a module, not a module
                found[m] = path
                todo.append(m)
    return dict(sorted(found.items()))


def modules_hash(sources: dict[str, Path]) -> str:
    """SHA-1 (12 hex digits) of ``sources`` (:func:`module_sources`), each file named by its
    module, so the same sources hash alike in a checkout and in an installed package."""
    h = hashlib.sha1()
    for name, path in sources.items():
        h.update(name.encode() + b"\0" + path.read_bytes() + b"\0")
    return h.hexdigest()[:12]
