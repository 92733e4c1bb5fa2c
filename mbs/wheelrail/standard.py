"""Standard wheel and rail profiles built from their published definitions.

Every dimension below names its source. Coordinates follow :mod:`axlebox.mbs.wheelrail.profile`
(side-local y towards the field side, z up, metres); the standards' own coordinates are in
millimetres and are converted once, at the end of each builder.

- :func:`s1002`: the S1002 wheel, EN 13715:2006 Annex C / UIC 510-2 Appendix B: eight sections A-H
  (polynomials and arcs) of the radius increase ``F(S)``, ``S`` from the taping line, negative
  towards the flange, back face at ``S = -70`` mm; flange height 28 mm, flange thickness 32.5 mm.
- :func:`uic60`: the 60E1 (UIC 60) rail head, EN 13674-1:2011 Annex A drawing: R300 crown over a
  width of 20.456 mm, R80 to a width of 52.053 mm, R13 until the head side reaches its 1:20 slope.
- :func:`chn60`: the Chinese 60 kg/m rail head, GB/T 2585-2007: R300 crown, R80, R13 gauge corners,
  73 mm head width (the standard's figures at second hand: it is not openly available). The widths
  over which the R300 and R80 arcs run are not in any openly available source we found; they are
  taken equal to 60E1's (20.456 mm for the crown), with the R13 corner meeting the 1:20 side at the
  73 mm width. This assumption is stated in :data:`CHN60_ASSUMED`.

The LM wheel (TB/T 449-2016) is defined in that standard by point coordinates (Appendix A) that
are not openly available; read them with :func:`axlebox.mbs.wheelrail.profile.read_profile` (two-column
``y z`` text, mm). No LM is built here rather than one made up.
"""
from __future__ import annotations

import math

import numpy as np

from axlebox.mbs.wheelrail.profile import Profile

# -------------------------------------------------------------------------------------- S1002 wheel
# EN 13715 Annex C (the UIC 510-2 definition): F(S) in mm, S in mm. Section B and C polynomial
# coefficients, and the breakpoints of every section, as printed there.
_S1002_B = (0.0, -3.358537058e-02, 1.565681624e-03, -2.810427944e-05, 5.844240864e-08,
            -1.562379023e-08, 5.309217349e-15, -5.957839843e-12, 2.646656573e-13)
_S1002_C = (4.320221063e+03, 1.038384026e+03, 1.065501873e+02, 6.051367875e+00,
            2.054332446e-01, 4.169739389e-03, 4.687195829e-05, 2.252755540e-07)
_S1002_BREAKS = (60.0, 32.15796, -26.0, -35.0, -38.426669071, -39.764473993, -49.662510381,
                 -62.764705882, -70.0)


def s1002_F(S):
    """Radius increase F(S) (mm) of the S1002 wheel at S (mm from the taping line), EN 13715 Annex C."""
    S = np.asarray(S, dtype=float)
    b = _S1002_BREAKS
    sections = [
        (S >= b[1], lambda s: 1.364323640 - 0.066666667 * s),                                   # A
        ((S >= b[2]) & (S < b[1]), lambda s: np.polyval(_S1002_B[::-1], s)),                    # B
        ((S >= b[3]) & (S < b[2]), lambda s: -np.polyval(_S1002_C[::-1], s)),                   # C
        ((S >= b[4]) & (S < b[3]),
         lambda s: 16.446 - np.sqrt(np.maximum(13.0 ** 2 - (s + 26.210665) ** 2, 0.0))),      # D
        ((S >= b[5]) & (S < b[4]), lambda s: -93.576667419 - 2.747477419 * s),                  # E
        ((S >= b[6]) & (S < b[5]),
         lambda s: 8.834924130 + np.sqrt(np.maximum(20.0 ** 2 - (s + 58.558326413) ** 2, 0.0))),  # F
        ((S >= b[7]) & (S < b[6]), lambda s: 16.0 + np.sqrt(np.maximum(12.0 ** 2 - (s + 55.0) ** 2, 0.0))),
        (S < b[7], lambda s: 9.519259302 + np.sqrt(np.maximum(20.5 ** 2 - (s + 49.5) ** 2, 0.0))),  # H
    ]
    out = np.full(S.shape, np.nan)
    for mask, f in sections:
        out = np.where(mask, f(S), out)
    return out


def s1002(step: float = 1e-4, S_min: float = -69.6) -> Profile:
    """The S1002 wheel from S = ``S_min`` mm (near the back face, whose tangent is vertical) to
    S = 60 mm, sampled every ``step`` m. Flange back at -70 mm (EN 13715: taping line 70 mm)."""
    S = np.arange(S_min, 60.0 + 1e-9, step * 1e3)
    return Profile(y=S * 1e-3, z=-s1002_F(S) * 1e-3, kind="wheel", name="S1002",
                   source="EN 13715:2006 Annex C (UIC 510-2)", flange_back=-0.070)


# ---------------------------------------------------------------------------------------- rail heads

def _three_arc_head(R_crown, R_mid, R_corner, w_crown, side_slope, *, w_mid=None, half_width=None,
                    depth=0.025, step=1e-4):
    """A symmetric rail head of three tangent arcs and a straight side, z up from the crown (mm).

    The crown arc (centre on the axis) runs to ``w_crown/2``; the middle arc, tangent to it, to
    ``w_mid/2``; the corner arc, tangent to that, until the side's slope (1 : ``side_slope``,
    widening downwards) is reached; the side then runs down to ``depth`` mm. Give either ``w_mid``
    (60E1's drawing) or ``half_width`` (the head's width where corner meets side, CHN 60).
    Returns y, z (mm) for y >= 0.
    """
    c1 = np.array([0.0, -R_crown])
    a1 = math.asin(0.5 * w_crown / R_crown)
    u1 = np.array([math.sin(a1), math.cos(a1)])
    c2 = c1 + (R_crown - R_mid) * u1                      # tangent internally to the crown
    side_dir = np.array([1.0, -side_slope]) / math.hypot(1.0, side_slope)
    n_end = np.array([side_dir[1] * -1.0, side_dir[0]])   # outward normal where the corner meets the side
    n_end = n_end if n_end[0] > 0 else -n_end
    if w_mid is not None:
        a2 = math.asin((0.5 * w_mid - c2[0]) / R_mid)
        u2 = np.array([math.sin(a2), math.cos(a2)])
        c3 = c2 + (R_mid - R_corner) * u2
    else:
        # corner centre on the vertical y = half_width - R_corner * n_end[0], at distance R_mid - R_corner
        yc3 = half_width - R_corner * n_end[0]
        dz = math.sqrt((R_mid - R_corner) ** 2 - (yc3 - c2[0]) ** 2)
        c3 = np.array([yc3, c2[1] + dz])
        u2 = (c3 - c2) / (R_mid - R_corner)
    p1 = c1 + R_crown * u1
    p2 = c2 + R_mid * u2
    p3 = c3 + R_corner * n_end
    y3_side = p3[0] + (p3[1] + depth) / side_slope          # side line down to z = -depth
    y = np.arange(0.0, y3_side, step * 1e3)
    y = np.union1d(y, [p1[0], p2[0], p3[0]])
    z = np.empty_like(y)
    for lo, hi, c, R in ((0.0, p1[0], c1, R_crown), (p1[0], p2[0], c2, R_mid), (p2[0], p3[0], c3, R_corner)):
        m = (y >= lo) & (y <= hi)
        z[m] = c[1] + np.sqrt(R * R - (y[m] - c[0]) ** 2)
    m = y > p3[0]
    z[m] = p3[1] - side_slope * (y[m] - p3[0])
    return y, z, {"crown_end": p1, "mid_end": p2, "corner_end": p3, "c_mid": c2, "c_corner": c3}


def _symmetric(y, z):
    return np.concatenate([-y[:0:-1], y]), np.concatenate([z[:0:-1], z])


def uic60(step: float = 1e-4) -> Profile:
    """The 60E1 (UIC 60) rail head, uncanted, EN 13674-1:2011: R300 over 20.456 mm, R80 to 52.053 mm,
    R13 to the 1:20 head side (head 72.0 mm wide where the R13 meets the side, 14.3 mm below the top)."""
    y, z, _ = _three_arc_head(300.0, 80.0, 13.0, 20.456, 20.0, w_mid=52.053, step=step)
    y, z = _symmetric(y, z)
    return Profile(y=y * 1e-3, z=z * 1e-3, kind="rail", name="60E1 (UIC60)",
                   source="EN 13674-1:2011 Annex A (60E1)")


CHN60_ASSUMED = ("R300 crown width 20.456 mm (taken from 60E1; GB/T 2585 not openly available)",
                 "head side slope 1:20 below the R13 corner (as 60E1)")


def chn60(step: float = 1e-4) -> Profile:
    """The Chinese 60 kg/m rail head, uncanted: R300 crown, R80, R13 corners, 73 mm head width
    (GB/T 2585-2007, at second hand); see :data:`CHN60_ASSUMED` for the two assumed values."""
    y, z, _ = _three_arc_head(300.0, 80.0, 13.0, 20.456, 20.0, half_width=36.5, step=step)
    y, z = _symmetric(y, z)
    return Profile(y=y * 1e-3, z=z * 1e-3, kind="rail", name="CHN60",
                   source="GB/T 2585-2007 (R300/R80/R13, 73 mm); arc widths assumed, see CHN60_ASSUMED")
