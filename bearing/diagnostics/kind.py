"""The kind of a faulty side's fault, named from the lines that made it faulty: the outer ring
(BPFO), the inner ring (BPFI) or a roller (2BSF, with its cage sidebands; :mod:`.faultlines`).

Each fault kind strikes at its own order of the shaft's rate (:class:`..frequencies.FaultOrders`),
so the line found names it: a line found at an order is that order's kind.  Two things make the
naming unsafe, and then both kinds are said, with "kind undecided", never one of them alone:

* *two lines alike*: the side carries lines of two kinds, the weaker within ``Criterion.kind_db``
  of the stronger (3 dB: twice the scatter of a line's SNR read over a median floor of some 40
  bins, as ``clearer_db``);
* *a speed that changed*: read at one speed ``f`` while the shaft's speed ranged over ``spread``
  of its mean, a line of kind K (order ``o_K``) stands at ``o_K f(t)``, anywhere in
  ``o_K f (1 +- spread / 2)``; so a line found in the window of order ``o`` may be K's wherever
  ``|o / o_K - 1| <= spread / 2``.  On the DTRB ``2 BSF / BPFO = 0.868`` and ``BPFO / BPFI =
  0.773``: a record whose speed ranged over 49 % of its mean (the accelerating car, 20-33 km/h,
  read at its mean speed) found its outer-ring defect's line in the roller's window, 2BSF, and
  named the roller.  A record read on the shaft's clock (order tracking) has ``spread = 0``.

A cage fault strikes at FTF, which is not among the criterion's lines (it sits under the wheel's
and the track's low orders on a vehicle), so it is never named.
"""
from __future__ import annotations

from .verdict import SIDES, FaultKind, LineReading

KIND_OF_LINE = {"BPFO": "outer ring", "BPFI": "inner ring", "2BSF": "roller", "FTF": "cage"}
UNDECIDED = "kind undecided"


def _strength(r: LineReading, side: str) -> float:
    """The line's SNR on ``side`` (dB): its best band's, else its own band's."""
    return float(r.line.best_snr_db.get(side, r.line.snr_db[side]))


def name_kind(lines: list[LineReading], side: str, orders, spread: float, kind_db: float,
              all_lines=()) -> FaultKind | None:
    """The :class:`.verdict.FaultKind` of ``side`` from ``lines``, the readings that make it
    faulty (the lines it owns, or the copies whose source it is); ``orders``: its bearing's
    :class:`..frequencies.FaultOrders` (None: no speed check); ``spread``: the speed's range over
    its mean as the record was read; ``all_lines``: the names of every line searched, the kinds a
    spread line may be caught as (module docstring).  None where ``lines`` is empty."""
    seen = sorted(((r.line.line, _strength(r, side)) for r in lines if r.line.seen[side]),
                  key=lambda t: -t[1])
    if not seen:
        return None
    best = {}
    for line, snr in seen:                  # a line of another bearing's orders counts once
        best.setdefault(line, snr)
    top, top_db = next(iter(best.items()))
    named = [top] + [n for n, db in best.items() if n != top and db >= top_db - kind_db]
    why = "two lines alike" if len(named) > 1 else ""
    if orders is not None and spread > 0:
        o_top = orders.at(1.0)[top]
        caught = [n for n in all_lines if n not in named and n in KIND_OF_LINE
                  and abs(o_top / orders.at(1.0)[n] - 1.0) <= spread / 2]
        if caught:
            named += caught
            why = why or "a speed that changed"
    kinds = tuple(dict.fromkeys(KIND_OF_LINE.get(n, n) for n in named))
    return FaultKind(kinds[0] if len(kinds) == 1 else UNDECIDED, kinds,
                     tuple((n, db) for n, db in best.items()), why, float(spread))


def kinds(ev, words: dict, real: str | None, orders, spread: float) -> dict:
    """side -> :class:`.verdict.FaultKind` of each side called faulty (``"real fault"`` or
    ``"faults on both sides"``), else None; ``orders``: side -> FaultOrders, or None."""
    out = {}
    copies = [r for r in ev.lines if all(r.line.seen.values()) and not r.sources]
    searched = tuple(dict.fromkeys(r.line.line for r in ev.lines))
    for s in SIDES:
        if words[s] not in ("real fault", "faults on both sides"):
            out[s] = None
            continue
        mine = ev.owned(s) + (copies if s == real else [])
        out[s] = name_kind(mine, s, None if orders is None else orders[s], spread,
                           ev.criterion.kind_db, searched)
    return out
