"""The car's axle-box bearings, any model of bearing/models/__init__.py (``[bearing] type``): their
kernel parameters, defect tables and a start in equilibrium, for
:func:`axlebox.mbs.vehicle.car.build` (``joint.model = "bearing"``).

The start: the car is first put in equilibrium with stiff row bushings in place of the bearings
(:mod:`axlebox.mbs.vehicle.statics`; the bearings' roller states would make that Newton solve forty times
larger); each bushing pair's load is then the load its bearing carries, and the bearing's own
quasi-static solution (:func:`axlebox.bearing.statics.equilibrium.static_state`, of the healthy bearing, with
the roller set turned half a pitch when a roller would sit in a defect) gives its roller and
cage states and the outer ring's displacement, which the axle-box is moved to (micrometres).
The row bushings leave the rings free to tilt against each other; the bearings do not, so the
front (flexible) wheelsets start with the axle's bending tilt and a load transient of about
15 % in the first milliseconds.

Rows: the kernel's row 1 lies at -y of the bearing centre, row 2 at +y (bearing/kernel/roller.py),
and the bearing frame here is the track frame.  A defect's ``row`` counts from the inboard row
(1) to the outboard row (2) (bearing/defects.py): on the left (+y) bearings that is the
kernel's numbering, on the right ones it is mirrored.
"""
from __future__ import annotations

import dataclasses
from collections import namedtuple
from typing import TYPE_CHECKING

import numpy as np

from axlebox.bearing import defects as bdefects
from axlebox.bearing.kernel import dispatch
from axlebox.bearing import models
from axlebox.bearing.statics.equilibrium import static_state
from axlebox.bearing.kernel.layout import F_X, F_Z
from axlebox.bearing.kernel.vec import AZ

from ..kernel.bearings import BR_MIN, BR_MOUT
from ..kernel.markers import MK_BODY
from ..kernel.body import BI_POS
from .car import SIDES

if TYPE_CHECKING:
    from .config import CarConfig

#: one bearing's start (:func:`start`): its kernel tag, parameter vector and defect table, its
#: roller and cage states and the outer ring's displacement from the inner ring's centre
Start = namedtuple("Start", ["tag", "P", "D", "y0", "uo"])


def params(cfg: CarConfig):
    """The bearings' parameters of a config (its model's ``Params``)."""
    return cfg.bearing


def defect_table(cfg: CarConfig, k: int, side: str, p) -> np.ndarray:
    """Defect table of the bearing of wheelset ``k`` on ``side`` (rows mirrored on the right)."""
    mine = [e.defect for e in cfg.defects if e.wheelset == k and e.side == side]
    if side == "R":
        mine = [dataclasses.replace(d, row=3 - d.row) for d in mine]
    return bdefects.table(mine, p)


def joint_loads(model, y) -> dict:
    """``(k, side) -> F``: the load (N, track frame) the axle-box puts on each bearing's outer
    ring, from the row bushings of a bushing-joint model at state ``y``."""
    model.rhs(0.0, y)
    out = model.W.elout
    names = [getattr(e, "name", "") for e in model.system.elements]
    loads = {}
    for k in range(1, 5):
        for side, _ in SIDES:
            rows = [names.index(f"joint{k}{side}_{r}") for r in ("row1", "row2")]
            loads[(k, side)] = out[rows, F_X:F_Z + 1].sum(axis=0)     # on the journal marker (m2)
    return loads


def start(cfg: CarConfig, loads: dict, omega_w: float, log=print) -> dict:
    """``(k, side) -> Start``: each bearing's kernel tag and arrays, its equilibrium roller and
    cage states under ``loads`` and the outer ring's displacement from the inner ring's
    centre."""
    p = params(cfg)
    P = models.pack(p)
    tag = dispatch.tag(p)
    out = {}
    for key, F in loads.items():
        D = defect_table(cfg, *key, p)
        # the healthy bearing's equilibrium: a roller that starts inside a defect has none
        # (3 and 5 mm defects at the top), and the first passes over the defect are the run's
        # (tolerances: 0.06 N on the rings, 11 N on a roller under a 56 kN load, one at the edge
        # of the loaded zone where Newton stalls: nothing to the run, whose first 0.5 s are the
        # track's fade-in; 80 km/h on the ballasted track stalled at 5.7 N, 1.0e-4 of the load)
        yb, uo = static_state(p, P, np.zeros((0, bdefects.WIDTH)), F, omega_w, tol=1e-6,
                              roller_tol=2e-4, phase=bdefects.phase_clear_of(D, p.Z))
        out[key] = Start(tag, P, D, yb, np.asarray(uo, float))
    log(f"bearings: {len(out)} {models.name(p).upper()}s in equilibrium, outer-ring loads "
        f"{min(-F[AZ] for F in loads.values()) / 1e3:.1f}-{max(-F[AZ] for F in loads.values()) / 1e3:.1f} kN")
    return out


def stiffness(cfg: CarConfig, loads: dict, names) -> np.ndarray:
    """Each named bearing's tangent stiffness (n, 3) along x, y (axial), z (N/m) at its static
    load (its model's ``ring_stiffness``): the interface Jacobian of a co-simulation's
    "jacobian" hold (mbs/kernel/exchange.py)."""
    p = params(cfg)
    return np.array([models.ring_stiffness(p, loads[_key(name)]) for name in names]).reshape(-1, 3)


def place_axleboxes(model, y, start_states: dict) -> np.ndarray:
    """``y`` (body states of the bearing model) with each axle-box moved so that its bore marker
    sits at the bearing's equilibrium displacement from the journal marker, followed by the
    bearings' roller and cage states."""
    nb = model.n_body_states
    y = np.concatenate([np.asarray(y, float)[:nb]] + [start_states[_key(n)].y0 for n in model.bearing_names])
    model.kinematics(0.0, y)                  # the markers' places (the bearings' rates unused)
    mkp = model.W.mkp
    idx = model.B.idx
    bi = model.S.bi
    mk_i = model.S.mk_i
    for k, name in enumerate(model.bearing_names):
        mi, mo = int(idx[k, BR_MIN]), int(idx[k, BR_MOUT])
        d = start_states[_key(name)].uo - (mkp[mo] - mkp[mi])
        b = int(mk_i[mo, MK_BODY])
        y[bi[b, BI_POS]:bi[b, BI_POS] + 3] += d        # its centre: the first three positions
    return y


def _key(name: str) -> tuple[int, str]:
    return int(name[len("bearing"):-1]), name[-1]
