"""``axlebox bodies export``: a reduced-body file for another multibody code.

* ``exudyn``: the FEMinterface data that Exudyn's ``ObjectFFRFreducedOrderInterface`` is built
  from (:mod:`axlebox.fem.export_exudyn`), read with ``FEMinterface.LoadFromFile`` (``.hdf5``);
* ``mbdyn``: the modal element's ``.fem`` database (:mod:`axlebox.fem.export_mbdyn`).

``--out`` is the file to write, or an existing folder (then ``<folder>/<body file stem>.<ext>``).
"""
from __future__ import annotations

import os
from pathlib import Path

from axlebox._params import ParameterError
from axlebox.fem import bodyfile

FORMATS = {"exudyn": ".hdf5", "mbdyn": ".fem"}


def target(src: str | os.PathLike, fmt: str, out: str | os.PathLike) -> Path:
    """The file ``export`` writes, or a ParameterError naming what is wrong."""
    if fmt not in FORMATS:
        raise ParameterError(f"--format = {fmt!r} is not allowed: expected one of {', '.join(FORMATS)}")
    out = Path(out)
    if out.is_dir():
        out = out / (Path(src).stem + FORMATS[fmt])
    elif not out.parent.is_dir():
        raise ParameterError(f"--out = {str(out)!r} is not allowed: its folder {str(out.parent)!r} does not "
                             "exist (expected a file in an existing folder, or an existing folder)")
    if fmt == "exudyn" and out.suffix.lower() != ".hdf5":
        # FEMinterface.LoadFromFile chooses its reader by the name: .hdf5 is HDF5, anything else NPZ
        raise ParameterError(f"--out = {str(out)!r} is not allowed for --format exudyn: expected a name "
                             "ending in .hdf5 (Exudyn's LoadFromFile reads HDF5 by that ending)")
    if out.exists() and Path(src).exists() and out.samefile(src):
        raise ParameterError(f"--out = {str(out)!r} is not allowed: it is the body file itself")
    return out


def export(src: str | os.PathLike, fmt: str, out: str | os.PathLike) -> Path:
    """Write the reduced body ``src`` in format ``fmt`` ('exudyn' or 'mbdyn') to ``out``."""
    path = target(src, fmt, out)
    if fmt == "exudyn":
        from axlebox.fem import export_exudyn
        return export_exudyn.write(bodyfile.read(src, fields=True), path)
    from axlebox.fem import export_mbdyn
    return export_mbdyn.write(bodyfile.read(src, fields=False), path)
