"""The DTRB as a force element with its own states (numba): between the journal marker of a
wheelset (inner ring) and the bore marker of an axle-box (outer ring).

Each bearing row ``br_i = [m_in, m_out, b_in, off, n, d0, nd]``: the two markers, the wheelset
body (for its spin angle and rate), where its roller and cage states start in ``y`` and how
many, and its rows ``d0 .. d0 + nd`` of the stacked defect table ``br_D``; ``br_P`` holds one
parameter vector (bearing/layout.py) a bearing.

The bearing kernel (bearing/kernel.py) works in a frame that translates with the inner ring and
does not spin.  Here that frame is the track frame (x forward, y left, z up) turned by the inner
ring's small tilt: the outer ring's displacement and tilt are taken relative to the journal
marker (small-angle vectors of the markers' orientations), the inner ring's angle and rate
about y are the wheelset's spin coordinates, and the ring loads are turned back.  The roller and cage
equations leave out the frame's own acceleration (the journal's, tens of m/s^2 on track: on a
0.135 kg roller under 5-10 kN contact loads, 0.1 %).  The ring loads (paper Eq. 16, with
moments) go back to the two markers as inertial forces and moments.

Two ways in: :func:`bearing_forces` evaluates every bearing's rates at the state (the
right-hand side of RK4, of statics and of a plain evaluation); :func:`bearing_exchange` is the
exchange of a leapfrog run, where each bearing advances its own states over the interval since
the last exchange (:func:`axlebox.bearing.advance.advance`) and the bodies get its mean ring
loads.
"""
from __future__ import annotations

import numpy as np
from numba import njit, prange

from axlebox.bearing.advance import advance, cage_outputs
from axlebox.bearing.kernel import dtrb_rhs

from .kernel_body import BI_POS, BI_VEL

BR_MIN, BR_MOUT, BR_BODY, BR_OFF, BR_N, BR_D0, BR_ND = range(7)
BR_WIDTH = 7
# output rows per bearing, after the elements' rows of ``elout``: force (3) and moment (3) on the
# inner ring; on the outer ring; roller 1's cup contact force in rows 1 and 2, then both cages'
# angle and rate
BR_ROWS = 3


@njit(cache=True, inline="always")
def _small_angles(R, out, o):
    """Small rotation vector of the orientation ``R`` (its skew part)."""
    out[o] = 0.5 * (R[2, 1] - R[1, 2])
    out[o + 1] = 0.5 * (R[0, 2] - R[2, 0])
    out[o + 2] = 0.5 * (R[1, 0] - R[0, 1])


@njit(cache=True)
def bearing_forces(t, y, dy, bi, br_i, br_P, br_D, mkp, mkv, mkR, mkw, mkF, mkM, elout):
    """State derivatives of every bearing's rollers and cages, and their ring loads on the
    markers; bearing k's outputs fill ``BR_ROWS`` rows of ``elout`` from row
    ``ne + BR_ROWS k`` (``ne``: the elements' rows)."""
    if br_i.shape[0] == 0:
        return
    ring, th, F, Qc, cages = _ring_motions(y, bi, br_i, br_P, mkp, mkv, mkR, mkw)
    _all_dtrbs(t, y, dy, br_i, br_P, br_D, ring, F, Qc, cages)
    _all_loads_back(br_i, mkF, mkM, elout, F, Qc, th, cages)


@njit(cache=True)
def _ring_motions(y, bi, br_i, br_P, mkp, mkv, mkR, mkw):
    """Every bearing's ring motion and marker angles (:func:`_ring_motion`), and the arrays
    its loads, contacts and cage outputs go to: ``(ring, th, F, Qc, cages)``."""
    nbr = br_i.shape[0]
    ring = np.zeros((nbr, 2, 12))
    th = np.zeros((nbr, 6))
    for k in range(nbr):
        _ring_motion(k, y, bi, br_i, mkp, mkv, mkR, mkw, ring[k], th[k])
    return ring, th, np.zeros((nbr, 2, 6)), np.zeros((nbr, 2, int(br_P[0, 0]), 6)), np.zeros((nbr, 4))


@njit(cache=True)
def _all_loads_back(br_i, mkF, mkM, elout, F, Qc, th, cages):
    for k in range(br_i.shape[0]):
        _loads_back(k, br_i, mkF, mkM, elout, F[k], Qc[k], th[k], cages[k])


@njit(cache=True, parallel=True)
def _all_dtrbs(t, y, dy, br_i, br_P, br_D, ring, F, Qc, cages):
    """:func:`axlebox.bearing.kernel.dtrb_rhs` of every bearing, in parallel (numba threads):
    each writes only its own states and scratch rows, so the result does not depend on the
    number of threads."""
    for k in prange(br_i.shape[0]):
        off, n = br_i[k, BR_OFF], br_i[k, BR_N]
        d0, nd = br_i[k, BR_D0], br_i[k, BR_ND]
        dtrb_rhs(t, y[off:off + n], ring[k], br_P[k], br_D[d0:d0 + nd], dy[off:off + n], F[k], Qc[k])
        cage_outputs(y[off:off + n], dy[off:off + n], cages[k])


@njit(cache=True)
def bearing_exchange(t, y, bi, br_i, br_P, br_D, mkp, mkv, mkR, mkw, mkF, mkM, elout, X):
    """The exchange at ``t`` of a leapfrog run (module docstring): every bearing's states
    advanced over the exchange's window (``X``: :class:`axlebox.mbs.exchange.Exchange`;
    :func:`axlebox.bearing.advance.advance`), the ring motion on the line through the last
    exchange's (``X.ring``) and this one's, which then becomes the last; the mean ring loads go
    onto the markers and into the outputs as in :func:`bearing_forces`.  The bearings' rows of
    ``dy`` are not written: their states are already advanced."""
    if br_i.shape[0] == 0:
        return
    ring, th, F, Qc, cages = _ring_motions(y, bi, br_i, br_P, mkp, mkv, mkR, mkw)
    _all_advances(t, y, br_i, br_P, br_D, X.ring, ring, X.h, X.n, X.flags[0] != 0, X.mode, F, Qc,
                  cages, X.G)
    X.ring[:, :, :] = ring
    X.flags[0] = 0
    _all_loads_back(br_i, mkF, mkM, elout, F, Qc, th, cages)
    if X.m > 1:                                     # the co-simulation's held loads
        X.held[1] = X.held[0] if X.flags[1] != 0 else F
        X.held[0] = F
        X.flags[1] = 1
        for k in range(br_i.shape[0]):
            for a in range(3):
                X.r0[k, a] = ring[k, 1, a]


@njit(cache=True)
def held_loads(y, bi, br_i, mkp, mkv, mkR, mkw, mkF, mkM, X, u):
    """The last exchange's ring loads on the markers, carried ``u`` exchange steps on along the
    line through the last two (``u = 0``: held); with the "jacobian" hold (``X.hold == 2``) plus
    ``-K`` times the outer ring's displacement from the inner since the exchange on the outer
    ring, its opposite on the inner."""
    ring = np.zeros((2, 12))
    th = np.zeros(6)
    for k in range(br_i.shape[0]):
        mi, mo = br_i[k, BR_MIN], br_i[k, BR_MOUT]
        if X.hold == 2:
            _ring_motion(k, y, bi, br_i, mkp, mkv, mkR, mkw, ring, th)
            for a in range(3):
                dF = -X.K[k, a] * (ring[1, a] - X.r0[k, a])
                mkF[mo, a] += dF
                mkF[mi, a] -= dF
        for a in range(3):
            for r, mk in ((0, mi), (1, mo)):
                F0, F1 = X.held[0, k, r, a], X.held[1, k, r, a]
                M0, M1 = X.held[0, k, r, 3 + a], X.held[1, k, r, 3 + a]
                mkF[mk, a] += F0 + u * (F0 - F1)
                mkM[mk, a] += M0 + u * (M0 - M1)


@njit(cache=True, parallel=True)
def _all_advances(t, y, br_i, br_P, br_D, ring_a, ring_b, h, n, first, mode, F, Qc, cages, G):
    """:func:`axlebox.bearing.advance.advance` of every bearing, in parallel with no
    synchronisation inside an exchange: each works on its own states and rows alone."""
    for k in prange(br_i.shape[0]):
        off, ns = br_i[k, BR_OFF], br_i[k, BR_N]
        d0, nd = br_i[k, BR_D0], br_i[k, BR_ND]
        Gk = G[k] if G.shape[0] > 0 else np.empty((0, 1, 6, 12))
        advance(y[off:off + ns], ring_a[k], ring_b[k], br_P[k], br_D[d0:d0 + nd], t, h, n, first, mode,
                F[k], Qc[k], cages[k], Gk, np.empty(ns), np.zeros((2, 12)), np.zeros((2, 6)),
                np.zeros(Qc[k].shape))


@njit(cache=True)
def _ring_motion(k, y, bi, br_i, mkp, mkv, mkR, mkw, ring, th):
    """Bearing k's ring motion (bearing/layout.py) from its two markers, and the small angles
    ``th`` of the markers' orientations."""
    mi, mo, b = br_i[k, BR_MIN], br_i[k, BR_MOUT], br_i[k, BR_BODY]
    _small_angles(mkR[mi], th, 0)
    _small_angles(mkR[mo], th, 3)
    # the bearing frame follows the inner ring's tilt (the journal bends with the axle by
    # about a milliradian, which on the rollers' 40 mm would be 20 um of misalignment):
    # the outer ring's displacement and tilt are taken relative to it
    d0, d1, d2 = mkp[mo, 0] - mkp[mi, 0], mkp[mo, 1] - mkp[mi, 1], mkp[mo, 2] - mkp[mi, 2]
    ring[:, :] = 0.0
    ring[1, 0] = d0 - (th[1] * d2 - th[2] * d1)
    ring[1, 1] = d1 - (th[2] * d0 - th[0] * d2)
    ring[1, 2] = d2 - (th[0] * d1 - th[1] * d0)
    ring[1, 3] = th[3] - th[0]
    ring[1, 4] = th[4]
    ring[1, 5] = th[5] - th[2]
    for a in range(3):
        ring[1, 6 + a] = mkv[mo, a] - mkv[mi, a]
        ring[0, 9 + a] = mkw[mi, a]
        ring[1, 9 + a] = mkw[mo, a]
    # the wheelset's spin: its own angle, and the body-frame rate about the axle
    ring[0, 4] = y[bi[b, BI_POS] + 7]
    ring[0, 10] = y[bi[b, BI_VEL] + 4]


@njit(cache=True)
def _loads_back(k, br_i, mkF, mkM, elout, F, Qc, th, cages):
    """Bearing k's ring loads ``F`` turned back to the track frame onto its markers, and its
    output rows (``cages``: :func:`axlebox.bearing.advance.cage_outputs`)."""
    nbr = br_i.shape[0]
    mi, mo = br_i[k, BR_MIN], br_i[k, BR_MOUT]
    for r in range(2):                      # back to the track frame: rotate by the tilt
        for o in (0, 3):
            f0, f1, f2 = F[r, o], F[r, o + 1], F[r, o + 2]
            F[r, o] = f0 + th[1] * f2 - th[2] * f1
            F[r, o + 1] = f1 + th[2] * f0 - th[0] * f2
            F[r, o + 2] = f2 + th[0] * f1 - th[1] * f0
    for a in range(3):
        mkF[mi, a] += F[0, a]
        mkM[mi, a] += F[0, 3 + a]
        mkF[mo, a] += F[1, a]
        mkM[mo, a] += F[1, 3 + a]
    r = elout.shape[0] - BR_ROWS * (nbr - k)
    for c in range(6):
        elout[r, c] = F[0, c]
        elout[r + 1, c] = F[1, c]
    elout[r + 2, 0] = Qc[0, 0, 0]
    elout[r + 2, 1] = Qc[1, 0, 0]
    for c in range(4):
        elout[r + 2, 2 + c] = cages[c]
