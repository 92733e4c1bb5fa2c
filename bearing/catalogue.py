"""A small catalogue of bearings by name: fault orders and bore, with where they come from.

Each side of a diagnosed pair has its own bearing (the two ends of a machine may differ: the
CWRU test motor carries an SKF 6205 at its drive end and a 6203 at its fan end), so that a line
at one bearing's own order can be told from a line carried over from the other bearing.

* ``dtrb``: the metro car's double-row tapered roller bearing of :mod:`.params` (the assumed
  130 x 230 x 160 mm unit), orders from its geometry by :func:`.frequencies.orders`.
* ``6205``, ``6203``: the SKF 6205-2RS JEM and 6203-2RS JEM deep-groove ball bearings of the
  Case Western Reserve University bearing test rig, with the fault orders (multiples of the shaft
  speed) the CWRU Bearing Data Center publishes for them ("Bearing information" page; also
  W. A. Smith and R. B. Randall, Mech. Syst. Signal Process. 64-65 (2015) 100-131, Table 2):
  6205 inner ring 5.4152, outer ring 3.5848, cage 0.39828, rolling element 4.7135; 6203 4.9469,
  3.0530, 0.3817, 3.9874.  The published "rolling element" order is the ball's defect frequency,
  twice the ball spin (2 BSF), so ``BSF`` is half of it.  Bores: 25 mm and 17 mm (ISO 15, the
  6205 and 6203 sizes).  Pitch and ball diameters (for a defect's size from its entry and exit
  events, bearing/diagnostics/size.py), from the same page: 6205 1.537 in and 0.3126 in
  (39.04 mm, 7.94 mm), 6203 1.122 in and 0.2656 in (28.50 mm, 6.75 mm); their cage orders agree
  with the published ``FTF`` to 1e-4.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cache

from axlebox._params import ParameterError

from . import models
from .frequencies import FaultOrders


@dataclass(frozen=True)
class Bearing:
    """A bearing's ``name``, fault ``orders`` (multiples of the shaft frequency), ``bore`` (m,
    for the SPM level, Eq. 17) and the ``source`` of those numbers; where known, its ``pitch``
    and ``roller`` diameters (m) and ``stiffness``, its most loaded roller's two raceway
    contacts in series (``Q = K delta^(10/9)``, N/m^(10/9); the defect's size,
    bearing/diagnostics/size.py)."""

    name: str
    orders: FaultOrders
    bore: float
    source: str
    pitch: float | None = None
    roller: float | None = None
    stiffness: float | None = None

    def to_dict(self) -> dict:
        return {"name": self.name, "orders": {**vars(self.orders), "2BSF": 2 * self.orders.BSF},
                "bore_m": self.bore, "source": self.source, "pitch_m": self.pitch,
                "roller_m": self.roller}


_CWRU = ("CWRU Bearing Data Center, 'Bearing information' (Smith and Randall, MSSP 64-65 (2015), "
         "Table 2)")


def of(p, source: str = "") -> Bearing:
    """The :class:`Bearing` of a bearing model's parameters ``p`` (bearing/models/__init__.py): its fault
    orders from its geometry and its bore."""
    from .statics.stiffness import e_prime, k_line, series
    name = models.name(p)
    k = k_line(e_prime(p.E_r, p.nu_r, p.E_r, p.nu_r), p.L_e)       # Eq. (10), steel on steel
    return Bearing(name, models.orders(p), models.bore(p),
                   source or f"axlebox's {name.upper()} ({models.module(p).__name__}), orders from "
                             "its geometry", pitch=p.D_m, roller=p.D_b, stiffness=series(k, k))


@cache
def catalogue() -> dict[str, Bearing]:
    """``{name: Bearing}`` of every bearing known by name: each model of bearing/models/__init__.py with
    its default parameters, and the test rig's bearings."""
    return {
        **{name: of(m.Params(), f"axlebox's {name.upper()} ({m.SUMMARY}; {m.DEFAULTS}), orders "
                                "from its geometry")
           for name, m in models.MODELS.items()},
        "6205": Bearing("6205", FaultOrders(FTF=0.39828, BPFO=3.5848, BPFI=5.4152,
                                            BSF=4.7135 / 2), 0.025, "SKF 6205-2RS JEM, " + _CWRU,
                        pitch=39.04e-3, roller=7.94e-3),
        "6203": Bearing("6203", FaultOrders(FTF=0.3817, BPFO=3.0530, BPFI=4.9469,
                                            BSF=3.9874 / 2), 0.017, "SKF 6203-2RS JEM, " + _CWRU,
                        pitch=28.50e-3, roller=6.75e-3),
    }


def lookup(name: str, field: str = "bearing") -> Bearing:
    """The catalogue's bearing ``name`` (case-insensitive), or a ParameterError naming ``field``."""
    known = catalogue()
    key = str(name).strip().lower()
    if key not in known:
        raise ParameterError(f"{field} {name!r} is not allowed: expected one of "
                             + ", ".join(sorted(known)))
    return known[key]


def custom(orders_: FaultOrders, bore: float, name: str = "custom") -> Bearing:
    """A bearing given by its orders and bore (``--orders``/``--bore``)."""
    return Bearing(name, orders_, float(bore), "given by the user")
