"""Whose fault line is it: a side's own fault, or the copy of the other side's?

Beyond the paper (issue 20).  A wheelset whose two bearings are both damaged shows fault lines on
both axle boxes, as one with a coaxial pseudo-fault does.  What tells them apart is where each
side's line stands: a local defect rings its own housing, bearing and sensor over a band the path
across the axle does not carry well, so in the band where one side's fault line stands best (its
envelope band, :mod:`.channel`: by spectral kurtosis, or guided to the line) a transmitted copy
on the other side is much weaker, while the other side's own fault of like size shows there as
strongly.  For each fault line found on both sides:

``share(s) = a_s(B_o) / a_o(B_o)``

the line's amplitude on side ``s`` over that on the other side ``o``, both in ``o``'s envelope
band ``B_o`` (``a``: the summed amplitudes of the fundamental and its harmonics searched,
:mod:`.faultlines`; both sensors in the same unit).  Side ``s`` *owns* the line when it is
detected on ``s`` in its own band and in ``B_o`` (a ratio of two noise floors means nothing),
with ``share(s) >= own_share`` (:class:`.criterion.Criterion`, default 0.25); a line found on
one side only is that side's own.  :func:`.criterion.verdict` calls "faults on both sides"
when each side owns a line.

The threshold, from the coupled car (benchmarks/README.md "Faults on both sides", 1.6 s runs)
and the CWRU record: the copy of a one-sided defect reaches 0.005-0.015 of its source
(outer ring, 1 and 2 mm, 40-80 km/h; 0.04 beside an inner-ring defect on the other side: the
car's axle carries little above 1 kHz), the fan end of the CWRU motor 0.15 (one faulty drive
end, 0.3 m along one shaft); two 2 mm defects 0.89-1.13 each, a 1 mm defect beside a 2 mm one
0.35.  0.25 lies between the CWRU copy and the 1 mm defect, 1.6 times above the one and 1.4
times below the other.  Below it (a fault under a quarter of the other side's, in that side's
band) two faults read as one fault and its copy.  Timing cannot tell them either: the impulse
lag (:mod:`.lag`) of two coincident trains names no side or one transmission lag, and in 5 of
6 synthetic two-fault pairs (tests/test_diagnostics_own.py) it names a leading side.
"""
from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from .channel import ChannelResult, in_band


@dataclass(frozen=True)
class LineShare:
    """One fault line found on both sides: ``band_left``/``band_right`` the sides' envelope
    bands (Hz); ``a_left``/``a_right``: (amplitude on the left, on the right) in that side's
    band; ``share``: side -> its share (module docstring); ``seen``: side -> whether its line
    is detected in the other side's band too."""

    line: str
    band_left: tuple[float, float]
    band_right: tuple[float, float]
    a_left: tuple[float, float]
    a_right: tuple[float, float]
    share: dict
    seen: dict

    def to_dict(self) -> dict:
        return asdict(self)


def _amplitude(res: ChannelResult, line: str) -> float:
    """The line's summed harmonic amplitudes in the side's envelope band."""
    return float(sum(a for _, _, a, _, _ in res.lines[line].searched))


def shares(x_left, x_right, left: ChannelResult, right: ChannelResult, lines,
           **line_kw) -> dict[str, LineShare]:
    """``{line: LineShare}`` for each of ``lines`` detected on both sides (``left``/``right``:
    :func:`.channel.analyse` of ``x_left``/``x_right``; ``line_kw``: as there)."""
    both = [n for n in lines if n in left.lines and n in right.lines
            and left.lines[n].detected and right.lines[n].detected]
    if not both:
        return {}
    bl, br = left.band, right.band
    # each signal's lines in the other side's band (one envelope spectrum each, for every line)
    l_in_r = in_band(left, x_left, br, **line_kw)
    r_in_l = in_band(right, x_right, bl, **line_kw)
    out = {}
    for n in both:
        a_l = (_amplitude(left, n), _amplitude(r_in_l, n))          # in the left's band
        a_r = (_amplitude(l_in_r, n), _amplitude(right, n))         # in the right's band
        share = {"left": a_r[0] / a_r[1] if a_r[1] > 0 else np.inf,
                 "right": a_l[1] / a_l[0] if a_l[0] > 0 else np.inf}
        seen = {"left": l_in_r.lines[n].detected, "right": r_in_l.lines[n].detected}
        out[n] = LineShare(n, bl, br, a_l, a_r, share, seen)
    return out


def owned(left: ChannelResult, right: ChannelResult, line_shares: dict, lines,
          own_share: float) -> dict[str, list[str]]:
    """``{side: [lines it owns]}`` (module docstring)."""
    ch = {"left": left, "right": right}
    out = {}
    for s, o in (("left", "right"), ("right", "left")):
        out[s] = [n for n in lines if n in ch[s].lines and ch[s].lines[n].detected
                  and (n in line_shares and line_shares[n].seen[s]
                       and line_shares[n].share[s] >= own_share
                       or not (n in ch[o].lines and ch[o].lines[n].detected))]
    return out
