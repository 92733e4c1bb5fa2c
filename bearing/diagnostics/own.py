"""How strongly each side's fault line stands in the other side's band: the *shares*, one input of
the verdict's evidence (:mod:`.verdict`).

Beyond the paper (issue 20).  A local defect rings its own housing, bearing and sensor over a
band the path across the axle carries badly, so in the band where one side's fault line stands
best (its envelope band, :mod:`.channel`: by spectral kurtosis, or guided to the line) a
transmitted copy on the other side is weaker.  For each fault line found on both sides:

``share(s) = a_s(B_o) / a_o(B_o)``

the line's amplitude on side ``s`` over that on the other side ``o``, both in ``o``'s envelope
band ``B_o`` (``a``: the summed amplitudes of the fundamental and its harmonics searched,
:mod:`.faultlines`; both sensors in the same unit); ``seen(s)``: whether the line is detected on
``s`` in ``B_o`` (a ratio of two noise floors means nothing).

Measured (benchmarks/README.md "Copy or source"): the copy of a one-sided defect in the coupled
car keeps 0.005-0.04 of its source, two like defects 0.8-1.2; but the copies of the CWRU motor,
whose casing carries its bearings' band well, keep up to 0.95 when both ends are read with one
bearing's orders, and a copy through a resonant path can exceed its source in that path's band.
So a share cannot tell a copy from a second fault: that is the timing's job
(:mod:`.coherence`); the shares are reported with the verdict.
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
