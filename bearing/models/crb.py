"""A single-row cylindrical roller bearing (CRB): one of the DCRB pair's two rows alone, the NJ 130
x 240 x 80 of :mod:`.dcrb` by itself, its rollers, rings, ribs, crown and cage the same.  It is
declared to the package here and in the registry (:mod:`.models`: its import and its entry in
``MODELS``), and nothing else:
the shared parts take their arrays' sizes and the rows' places from the model's ``rows``
(bearing/kernel/layout.py ``N_ROWS``, ``row_y``), so a bearing of one row runs through the same
kernel, quasi-static model, static start, rig and car as the two-row ones.

Its only parameter of its own is ``rows = 1``; its row sits at the bearing's centre (``row_offset``
0, where a single row's place falls whatever the offset).  Everything else, the defaults and their
sources (FAG's WJ 130 x 240, the rollers assumed to match its 540 kN rating), is the DCRB's.
"""
from __future__ import annotations

from dataclasses import dataclass

from axlebox._params import param

from . import dcrb

NAME = "crb"
BORE = dcrb.BORE
SUMMARY = ("a single-row cylindrical roller bearing: one row of the DCRB pair alone (an NJ 130 x 240 x "
           "80), line contacts by slices, ribs that take the axial load")
DEFAULTS = ("Defaults: the DCRB's (FAG's WJ 130 x 240 boundary dimensions and load rating, the rollers "
            "assumed to match that rating), one row; each field's source in bearing/models/dcrb.py.")
# the same rollers on the same raceways: the contact modes, and so the explicit steps' limits, are
# the DCRB's (measured on the rig, tests/test_dcrb.py)
DT_MAX = dcrb.DT_MAX


@dataclass(frozen=True)
class CrbParams(dcrb.DcrbParams):
    """The single-row CRB's parameters: the DCRB's, with one row at the centre."""

    row_offset: float = param(0.0, 0.0, 0.5, doc="axial place of the row (one row sits at the centre "
                              "whatever this is)")

    rows = 1


Params = CrbParams
pack = dcrb.pack
nominal_state = dcrb.nominal_state
contacts = dcrb.contacts
guess = dcrb.guess
orders = dcrb.orders
ring_stiffness = dcrb.ring_stiffness
