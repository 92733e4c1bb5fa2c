"""A reduced body as MBDyn's modal element database (the ``.fem`` file), and a reader of it.

Source of the format: MBDyn input manual, "Modal Element", section "FEM File Format"
(www.mbdyn.org, Documentation; the same records the ``femgen`` NASTRAN post-processor and
mboct's ``mbdyn_pre_write_fem_data`` write), checked against the reader ``ReadModal`` in
MBDyn's ``mbdyn/struct/modal.cc``.  A record group starts at a line ``** RECORD GROUP k,
<comment>``; the numbers that follow are read as a stream of whitespace-separated tokens,
except in group 8, where each mode is introduced by one ``**`` line:

====  ======================================================================================
 1    header: REV, number of FEM nodes, normal, attachment, constraint, rejected modes
 2    FEM node labels (strings without blanks)
 3/4  initial modal displacements / velocities (n each)
5-7   node X / Y / Z coordinates, m (one per node)
 8    mode shapes: per mode a ``**`` line, then per node x y z rx ry rz (m, rad per unit q)
9/10  generalized mass / stiffness (n x n, row after row)
 12   rigid-body inertia: mass (kg), centre of mass (3, m), inertia about it (3 x 3, kg m^2)
 13   generalized damping (n x n, N s/m per unit q; MBDyn reads it with ``damping from file``)
====  ======================================================================================

The FEM nodes are the body's master/output nodes (``nodes/<name>``), labelled by name, in the
body frame (the FE origin), so ``origin node`` is not needed.  Group 11 (lumped nodal masses)
is left out: it would replace the exact inertia of group 12 by the masses of the few
interface nodes.  The inertia invariants of the floating frame (groups 14-18 of recent MBDyn)
are not written either: for free-free modes the first-order ones (Inv3 = int rho Phi dV,
Inv4 = int rho x x Phi dV) vanish; the second-order ones stay in the body file.  Numbers are
written ``%.17e``, so reading them back gives the same doubles.
"""
from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np

from axlebox._files import write_text

from .bodyfile import BodyFileError, ReducedBody

_NUM = "%.17e"
_LABEL = re.compile(r"^[^\s\"]+$")      # MBDyn reads a label as one token


def _row(values) -> str:
    return " ".join(_NUM % v for v in np.asarray(values, float).ravel())


def _check(body: ReducedBody) -> list[str]:
    """The node names, after refusing what MBDyn could not read back."""
    names = list(body.nodes)
    if not names:
        raise BodyFileError(f"body {body.name!r} has no master/output nodes: MBDyn's modal element "
                            "needs at least one FEM node to attach to")
    for k in names:
        if not _LABEL.match(k):
            raise BodyFileError(f"node name {k!r} of body {body.name!r} is not allowed in a .fem file: "
                                "expected a label without blanks or quotes")
    n = body.n_modes
    if n == 0:
        raise BodyFileError(f"body {body.name!r} has no elastic modes: nothing for a modal element")
    shapes = [(f"reduced/{k}", np.shape(a), (n, n)) for k, a in (
        ("mass", body.reduced_mass), ("stiffness", body.reduced_stiffness),
        ("damping", body.reduced_damping))]
    shapes += [("center_of_mass", np.shape(body.center_of_mass), (3,)),
               ("inertia", np.shape(body.inertia), (3, 3))]
    for k, v in body.nodes.items():
        shapes += [(f"nodes/{k}/position", np.shape(v["position"]), (3,)),
                   (f"nodes/{k}/shapes", np.shape(v["shapes"]), (6, n))]
    for key, got, want in shapes:
        if got != want:
            raise BodyFileError(f"body {body.name!r} has {key} of shape {got}: expected {want}")
    arrays = {"mass": body.mass, "center_of_mass": body.center_of_mass, "inertia": body.inertia,
              "reduced/mass": body.reduced_mass, "reduced/stiffness": body.reduced_stiffness,
              "reduced/damping": body.reduced_damping,
              **{f"nodes/{k}": np.r_[v["position"], np.ravel(v["shapes"])] for k, v in body.nodes.items()}}
    for k, v in arrays.items():
        if not np.all(np.isfinite(v)):          # a C++ stream cannot read 'nan' back
            raise BodyFileError(f"body {body.name!r} holds non-finite numbers in {k}")
    return names


def fem_text(body: ReducedBody) -> str:
    """The ``.fem`` database of ``body`` as text."""
    names = _check(body)
    n = body.n_modes
    pos = np.array([body.nodes[k]["position"] for k in names], float)          # (N, 3)
    shp = np.array([body.nodes[k]["shapes"] for k in names], float)            # (N, 6, n)
    out = [f"** MBDyn MODAL DATA FILE: axlebox reduced body {body.name!r} ({body.method}), SI units",
           f"** {n} free-free elastic modes, {body.frequencies_hz[0]:.6g}..{body.frequencies_hz[-1]:.6g} Hz;"
           " FEM nodes = the body's master/output nodes",
           "** RECORD GROUP 1, HEADER",
           "**   REVISION, NODES, NORMAL, ATTACHMENT, CONSTRAINT, REJECTED MODES",
           f"REV0 {len(names)} {n} 0 0 0",
           "** RECORD GROUP 2, FINITE ELEMENT NODE LIST",
           " ".join(names),
           "** RECORD GROUP 3, INITIAL MODAL DISPLACEMENTS",
           _row(np.zeros(n)),
           "** RECORD GROUP 4, INITIAL MODAL VELOCITIES",
           _row(np.zeros(n))]
    for a, axis in enumerate("XYZ"):
        out += [f"** RECORD GROUP {5 + a}, NODAL {axis} COORDINATES", *(_NUM % x for x in pos[:, a])]
    out.append("** RECORD GROUP 8, MODE SHAPES")
    for k in range(n):
        # ReadModal takes exactly one '**' line before each mode: no blank line may follow it
        out.append(f"**    NORMAL MODE SHAPE # {k + 1} ({body.frequencies_hz[k]:.9g} Hz)")
        out += [_row(shp[i, :, k]) for i in range(len(names))]
    out.append("** RECORD GROUP 9, MODAL MASS MATRIX")
    out += [_row(r) for r in body.reduced_mass]
    out.append("** RECORD GROUP 10, MODAL STIFFNESS MATRIX")
    out += [_row(r) for r in body.reduced_stiffness]
    out += ["** RECORD GROUP 12, RIGID BODY INERTIA: MASS, CENTRE OF MASS, INERTIA ABOUT IT",
            _NUM % body.mass, _row(body.center_of_mass), *(_row(r) for r in body.inertia)]
    out.append("** RECORD GROUP 13, MODAL DAMPING MATRIX")
    out += [_row(r) for r in body.reduced_damping]
    out.append("** END OF FILE")
    return "\n".join(out) + "\n"


def write(body: ReducedBody, path: str | os.PathLike) -> Path:
    """Write ``body`` as an MBDyn ``.fem`` file (temporary name, renamed when complete)."""
    return write_text(path, fem_text(body))


def read(path: str | os.PathLike) -> dict:
    """Read a ``.fem`` file the way MBDyn's ``ReadModal`` does (records 1-13; 14-18 refused).

    Returns ``labels`` (list), ``q0``, ``qd0`` (n,), ``positions`` (N, 3), ``shapes``
    (N, 6, n), ``mass_matrix``, ``stiffness``, ``damping`` (n, n; damping None when record 13
    is absent), ``lumped`` (N, 6) or None, ``mass``, ``center_of_mass`` (3,), ``inertia``
    (3, 3) or None without record 12.
    """
    lines = Path(path).read_text().splitlines()
    out: dict = {"damping": None, "lumped": None, "mass": None, "center_of_mass": None, "inertia": None}
    i, N, n = 0, None, None

    def numbers(start: int, count: int) -> tuple[np.ndarray, int]:
        vals, j = [], start
        while len(vals) < count:
            if j >= len(lines):
                raise ValueError(f"{path}: end of file inside a record ({len(vals)} of {count} numbers)")
            if not lines[j].startswith("**"):
                vals += lines[j].split()
            j += 1
        if len(vals) != count:
            raise ValueError(f"{path}: line {j}: {len(vals)} numbers where {count} were expected")
        return np.array(vals, float), j

    while i < len(lines):
        m = re.match(r"\*\* RECORD GROUP (\d+),", lines[i])
        i += 1
        if not m:
            continue
        g = int(m.group(1))
        if g != 1 and N is None:
            raise ValueError(f"{path}: record group {g} before the header (record group 1)")
        if g == 1:
            tok = lines[i + 1].split()              # one comment line, then the header
            N, n = int(tok[1]), int(tok[2]) + int(tok[3]) + int(tok[4]) - int(tok[5])
            i += 2
        elif g == 2:
            out["labels"] = lines[i].split()
            i += 1
        elif g in (3, 4):
            out["q0" if g == 3 else "qd0"], i = numbers(i, n)
        elif g in (5, 6, 7):
            out.setdefault("positions", np.zeros((N, 3)))[:, g - 5], i = numbers(i, N)
        elif g == 8:
            shapes = np.zeros((N, 6, n))
            for k in range(n):
                if not lines[i].startswith("**"):
                    raise ValueError(f"{path}: line {i + 1}: '**' expected before mode {k + 1}")
                vals, i = numbers(i + 1, 6 * N)
                shapes[:, :, k] = vals.reshape(N, 6)
            out["shapes"] = shapes
        elif g in (9, 10, 13):
            key = {9: "mass_matrix", 10: "stiffness", 13: "damping"}[g]
            vals, i = numbers(i, n * n)
            out[key] = vals.reshape(n, n)            # row after row (ReadModal's Put(row, col))
        elif g == 11:
            vals, i = numbers(i, 6 * N)
            out["lumped"] = vals.reshape(N, 6)
        elif g == 12:
            vals, i = numbers(i, 13)
            out.update(mass=float(vals[0]), center_of_mass=vals[1:4], inertia=vals[4:].reshape(3, 3))
        else:
            raise ValueError(f"{path}: record group {g} is not read here (1-13 only)")
    missing = [k for k in ("labels", "positions", "shapes", "mass_matrix", "stiffness") if k not in out]
    if N is None or missing:
        raise ValueError(f"{path}: incomplete .fem file (missing {missing or 'record group 1'})")
    return out
