"""The car's bearings as force elements with their own states (numba): each between the journal
marker of a wheelset (inner ring) and the bore marker of an axle-box (outer ring), any bearing
model (bearing/models/__init__.py).

:class:`Bearings` holds them all (:func:`axlebox.mbs.solver.system.System.assemble` packs it): the
kernels' ``tag`` of their model (one model for the car), a row of indices each (``idx``:
:data:`BR_MIN` ..., the two markers, the wheelset body for its spin angle and rate, where its
states start in ``y`` and how many, and its rows of the stacked defect table ``D``), a
parameter vector each (``P``), and every array an evaluation or an exchange writes, made once
(ring motion, marker angles, ring loads, contact forces, cage outputs, the steps' scratch): an
exchange allocates nothing.  A car without bearings has :class:`NoBearings`, for which these
kernels compile to nothing.

The bearing kernels work in a frame that translates with the inner ring and does not spin.
Here that frame is the track frame (x forward, y left, z up) turned by the inner ring's small
tilt: the outer ring's displacement and tilt are taken relative to the journal marker
(small-angle vectors of the markers' orientations), the inner ring's angle and rate about y are
the wheelset's spin coordinates, and the ring loads are turned back.  The roller and cage
equations leave out the frame's own acceleration (the journal's, tens of m/s^2 on track: on a
0.135 kg roller under 5-10 kN contact loads, 0.1 %).  The ring loads (paper Eq. 16, with
moments) go back to the two markers as inertial forces and moments.

Two ways in: :func:`bearing_forces` evaluates every bearing's rates at the state (the
right-hand side of RK4, of statics and of a plain evaluation); :func:`bearing_exchange` is the
exchange of a leapfrog run, where each bearing advances its own states over the interval since
the last exchange (:func:`axlebox.bearing.kernel.advance.advance`) and the bodies get its mean ring
loads.
"""
from __future__ import annotations

from collections import namedtuple

from math import atan2, sqrt

from numba import prange
from numba.extending import overload

from axlebox._numba import kernel
from axlebox.bearing.kernel import evaluate as bev
from axlebox.bearing.kernel import implicit
from axlebox.bearing.kernel.advance import advance
from axlebox.bearing.kernel.layout import (C_LOAD, CAGE_ANGLE, CAGE_RATE, F_X, INNER, LOAD, M_X,
                                           OUTER, OUTER_SLOTS, Q_O, REC_LOAD, TH_X, TH_Y, TH_Z, U_X,
                                           U_Y, U_Z, V_X, W_X, W_Y)
from axlebox.bearing.kernel.step import cage_outputs
from axlebox.bearing.kernel.vec import AX, AY, AZ, copy3

from .exchange import FIRST, HELD, JACOBIAN, LAST, THIS
from .body import BI_POS, BI_VEL, SPIN_ANGLE, SPIN_RATE

BR_MIN, BR_MOUT, BR_BODY, BR_OFF, BR_N, BR_D0, BR_ND, BR_WIDTH = range(8)
# output rows per bearing, after the elements' rows of ``elout``: the loads (force, moment) on the
# inner ring and on the outer ring; then roller 1's outer-raceway contact force in the first row
# and in the last (the same row in a single-row bearing), the cage angle of those two rows and
# their rates (BR_ANGLE + 0 the first row's, + 1 the last's; so BR_RATE); then each of those two
# rows' load on the outer ring at the last evaluation (its rollers' raceway and rib contacts):
# axial (track y), radial, and the load zone's centre (the radial load's direction, from the top
# towards the front)
BR_INNER, BR_OUTER, BR_MORE, BR_ROW, BR_ROWS = range(5)
BR_Q1, BR_QN, BR_ANGLE, BR_RATE = 0, 1, 2, 4
BR_AXIAL, BR_RADIAL, BR_ZONE = 0, 2, 4
TH_IN, TH_OUT, TH = 0, 3, 6            # the markers' small angles: the inner's, the outer's

Bearings = namedtuple("Bearings", ["tag", "idx", "P", "D", "ring", "th", "F", "Qc", "cages", "work",
                                   "kick"])
NoBearings = namedtuple("NoBearings", [])


@kernel
def bearing_forces(B, t, y, dy, bi, mkp, mkv, mkR, mkw, mkF, mkM, elout):
    """State derivatives of every bearing's rollers and cages, and their ring loads on the
    markers; bearing k's outputs fill ``BR_ROWS`` rows of ``elout`` from row ``ne + BR_ROWS k``
    (``ne``: the elements' rows)."""
    _forces_of(B, t, y, dy, bi, mkp, mkv, mkR, mkw, mkF, mkM, elout)


@kernel(inline="always")
def bearing_exchange(B, X, t, y, bi, mkp, mkv, mkR, mkw, mkF, mkM, elout):
    """The exchange at ``t`` of a leapfrog run (module docstring): every bearing's states
    advanced over the exchange's window (``X``: :class:`axlebox.mbs.kernel.exchange.Exchange`;
    :func:`axlebox.bearing.kernel.advance.advance`), the ring motion on the line through the last
    exchange's (``X.ring``) and this one's, which then becomes the last; the mean ring loads go
    onto the markers and into the outputs as in :func:`bearing_forces`.  The bearings' rows of
    ``dy`` are not written: their states are already advanced."""
    _exchange_of(B, X, t, y, bi, mkp, mkv, mkR, mkw, mkF, mkM, elout)


@kernel(inline="always")
def held_loads(B, X, y, bi, mkp, mkv, mkR, mkw, mkF, mkM, u):
    """The last exchange's ring loads on the markers, carried ``u`` exchange steps on along the
    line through the last two (``u = 0``: held); with the "jacobian" hold (``X.hold``) plus
    ``-K`` times the outer ring's displacement from the inner since the exchange on the outer
    ring, its opposite on the inner."""
    _held_of(B, X, y, bi, mkp, mkv, mkR, mkw, mkF, mkM, u)


# each of the three compiled for the bearings' own model, or to nothing for NoBearings
def _forces_of(B, t, y, dy, bi, mkp, mkv, mkR, mkw, mkF, mkM, elout):
    raise NotImplementedError("numba only")


def _exchange_of(B, X, t, y, bi, mkp, mkv, mkR, mkw, mkF, mkM, elout):
    raise NotImplementedError("numba only")


def _held_of(B, X, y, bi, mkp, mkv, mkR, mkw, mkF, mkM, u):
    raise NotImplementedError("numba only")


_JIT = {"cache": True, "error_model": "numpy"}


@overload(_forces_of, jit_options=_JIT)
def _forces(B, t, y, dy, bi, mkp, mkv, mkR, mkw, mkF, mkM, elout):
    if B.instance_class is NoBearings:
        return lambda B, t, y, dy, bi, mkp, mkv, mkR, mkw, mkF, mkM, elout: None

    def impl(B, t, y, dy, bi, mkp, mkv, mkR, mkw, mkF, mkM, elout):
        _ring_motions(B, y, bi, mkp, mkv, mkR, mkw)
        _all_rates(B.tag, B.idx, B.P, B.D, B.ring, B.F, B.Qc, B.cages, B.work, t, y, dy)
        _all_loads_back(B, mkF, mkM, elout)
    return impl


@overload(_exchange_of, jit_options=_JIT)
def _exchange(B, X, t, y, bi, mkp, mkv, mkR, mkw, mkF, mkM, elout):
    if B.instance_class is NoBearings:
        return lambda B, X, t, y, bi, mkp, mkv, mkR, mkw, mkF, mkM, elout: None

    def impl(B, X, t, y, bi, mkp, mkv, mkR, mkw, mkF, mkM, elout):
        _ring_motions(B, y, bi, mkp, mkv, mkR, mkw)
        _all_advances(B.tag, B.idx, B.P, B.D, X.ring, B.ring, B.F, B.Qc, B.cages, B.work, B.kick, t, y,
                      X.h, X.n, X.flags[FIRST] != 0, X.mode)
        copy3(X.ring, B.ring)
        X.flags[FIRST] = 0
        _all_loads_back(B, mkF, mkM, elout)
        if X.m > 1:                                 # the co-simulation's held loads
            _hold(B, X)
    return impl


@overload(_held_of, jit_options=_JIT)
def _held(B, X, y, bi, mkp, mkv, mkR, mkw, mkF, mkM, u):
    if B.instance_class is NoBearings:
        return lambda B, X, y, bi, mkp, mkv, mkR, mkw, mkF, mkM, u: None

    def impl(B, X, y, bi, mkp, mkv, mkR, mkw, mkF, mkM, u):
        for k in range(B.idx.shape[0]):
            mi, mo = B.idx[k, BR_MIN], B.idx[k, BR_MOUT]
            if X.hold == JACOBIAN:
                _ring_motion(k, y, bi, B.idx, mkp, mkv, mkR, mkw, B.ring[k], B.th[k])
                for a in range(3):
                    dF = -X.K[k, a] * (B.ring[k, OUTER, U_X + a] - X.r0[k, a])
                    mkF[mo, a] += dF
                    mkF[mi, a] -= dF
            for a in range(3):
                for r, mk in ((INNER, mi), (OUTER, mo)):
                    F0, F1 = X.held[THIS, k, r, F_X + a], X.held[LAST, k, r, F_X + a]
                    M0, M1 = X.held[THIS, k, r, M_X + a], X.held[LAST, k, r, M_X + a]
                    mkF[mk, a] += F0 + u * (F0 - F1)
                    mkM[mk, a] += M0 + u * (M0 - M1)
    return impl


@kernel
def _hold(B, X):
    """This exchange's and the last one's ring loads kept for the co-simulation's hold, and
    each outer ring's place at it (the "jacobian" hold's reference)."""
    copy3(X.held[LAST], X.held[THIS] if X.flags[HELD] != 0 else B.F)
    copy3(X.held[THIS], B.F)
    X.flags[HELD] = 1
    for k in range(B.idx.shape[0]):
        for a in range(3):
            X.r0[k, a] = B.ring[k, OUTER, U_X + a]


@kernel
def _ring_motions(B, y, bi, mkp, mkv, mkR, mkw):
    """Every bearing's ring motion and marker angles (:func:`_ring_motion`) into ``B``."""
    for k in range(B.idx.shape[0]):
        _ring_motion(k, y, bi, B.idx, mkp, mkv, mkR, mkw, B.ring[k], B.th[k])


@kernel
def _all_loads_back(B, mkF, mkM, elout):
    for k in range(B.idx.shape[0]):
        _loads_back(k, B.idx, mkF, mkM, elout, B.F[k], B.Qc[k], B.th[k], B.cages[k])
        _row_loads(k, B.idx, elout, B.work.rec[k], B.Qc.shape[2], B.th[k])


# the parallel loops take their arguments flat (numba's parallel loops take arrays, numbers, an
# empty tag and flat named tuples of arrays, not tuples of tuples)
@kernel(parallel=True, allocates=True)
def _all_rates(tag, idx, P, D, ring, F, Qc, cages, work, t, y, dy):
    """Every bearing's rates (bearing/kernel/evaluate.py), in parallel (numba threads): each writes only
    its own states and scratch, so the result does not depend on the number of threads."""
    for k in prange(idx.shape[0]):
        off, n = idx[k, BR_OFF], idx[k, BR_N]
        d0, nd = idx[k, BR_D0], idx[k, BR_ND]
        bev.evaluate(tag, t, y[off:off + n], ring[k], P[k], D[d0:d0 + nd], dy[off:off + n], F[k],
                     Qc[k], bev.one(work, k), False, 0.0)
        cage_outputs(y[off:off + n], dy[off:off + n], cages[k])


@kernel(parallel=True, allocates=True)
def _all_advances(tag, idx, P, D, ring_last, ring, F, Qc, cages, work, kick, t, y, h, n, first, mode):
    """:func:`axlebox.bearing.kernel.advance.advance` of every bearing, in parallel with no
    synchronisation inside an exchange: each works on its own states and scratch alone."""
    for k in prange(idx.shape[0]):
        off, ns = idx[k, BR_OFF], idx[k, BR_N]
        d0, nd = idx[k, BR_D0], idx[k, BR_ND]
        advance(tag, y[off:off + ns], ring_last[k], ring[k], P[k], D[d0:d0 + nd], bev.one(work, k),
                implicit.one(kick, k), t, h, n, first, mode, 1.0, F[k], Qc[k], cages[k])


@kernel
def _small_angles(R, out, o):
    """Small rotation vector of the orientation ``R`` (its skew part)."""
    out[o + AX] = 0.5 * (R[AZ, AY] - R[AY, AZ])
    out[o + AY] = 0.5 * (R[AX, AZ] - R[AZ, AX])
    out[o + AZ] = 0.5 * (R[AY, AX] - R[AX, AY])


@kernel
def _ring_motion(k, y, bi, idx, mkp, mkv, mkR, mkw, ring, th):
    """Bearing k's ring motion (bearing/kernel/layout.py) from its two markers, and the small angles
    ``th`` of the markers' orientations."""
    mi, mo, b = idx[k, BR_MIN], idx[k, BR_MOUT], idx[k, BR_BODY]
    _small_angles(mkR[mi], th, TH_IN)
    _small_angles(mkR[mo], th, TH_OUT)
    tx, ty, tz = th[TH_IN + AX], th[TH_IN + AY], th[TH_IN + AZ]
    # the bearing frame follows the inner ring's tilt (the journal bends with the axle by
    # about a milliradian, which on the rollers' 40 mm would be 20 um of misalignment):
    # the outer ring's displacement and tilt are taken relative to it
    d0, d1, d2 = mkp[mo, AX] - mkp[mi, AX], mkp[mo, AY] - mkp[mi, AY], mkp[mo, AZ] - mkp[mi, AZ]
    ring[:, :] = 0.0
    ring[OUTER, U_X] = d0 - (ty * d2 - tz * d1)
    ring[OUTER, U_Y] = d1 - (tz * d0 - tx * d2)
    ring[OUTER, U_Z] = d2 - (tx * d1 - ty * d0)
    ring[OUTER, TH_X] = th[TH_OUT + AX] - tx
    ring[OUTER, TH_Y] = th[TH_OUT + AY]
    ring[OUTER, TH_Z] = th[TH_OUT + AZ] - tz
    for a in range(3):
        ring[OUTER, V_X + a] = mkv[mo, a] - mkv[mi, a]
        ring[INNER, W_X + a] = mkw[mi, a]
        ring[OUTER, W_X + a] = mkw[mo, a]
    # the wheelset's spin: its own angle, and the body-frame rate about the axle
    ring[INNER, TH_Y] = y[bi[b, BI_POS] + SPIN_ANGLE]
    ring[INNER, W_Y] = y[bi[b, BI_VEL] + SPIN_RATE]


@kernel
def _loads_back(k, idx, mkF, mkM, elout, F, Qc, th, cages):
    """Bearing k's ring loads ``F`` turned back to the track frame onto its markers, and its
    output rows (``cages``: :func:`axlebox.bearing.kernel.step.cage_outputs`)."""
    nbr = idx.shape[0]
    mi, mo = idx[k, BR_MIN], idx[k, BR_MOUT]
    tx, ty, tz = th[TH_IN + AX], th[TH_IN + AY], th[TH_IN + AZ]
    for r in (INNER, OUTER):                 # back to the track frame: rotate by the tilt
        for o in (F_X, M_X):
            f0, f1, f2 = F[r, o + AX], F[r, o + AY], F[r, o + AZ]
            F[r, o + AX] = f0 + ty * f2 - tz * f1
            F[r, o + AY] = f1 + tz * f0 - tx * f2
            F[r, o + AZ] = f2 + tx * f1 - ty * f0
    for a in range(3):
        mkF[mi, a] += F[INNER, F_X + a]
        mkM[mi, a] += F[INNER, M_X + a]
        mkF[mo, a] += F[OUTER, F_X + a]
        mkM[mo, a] += F[OUTER, M_X + a]
    r = elout.shape[0] - BR_ROWS * (nbr - k)
    for c in range(LOAD):
        elout[r + BR_INNER, c] = F[INNER, c]
        elout[r + BR_OUTER, c] = F[OUTER, c]
    first, last, roller1 = 0, Qc.shape[0] - 1, 0       # the first and last rows
    elout[r + BR_MORE, BR_Q1] = Qc[first, roller1, Q_O]
    elout[r + BR_MORE, BR_QN] = Qc[last, roller1, Q_O]
    for i, j in enumerate((first, last)):
        elout[r + BR_MORE, BR_ANGLE + i] = cages[j, CAGE_ANGLE]
        elout[r + BR_MORE, BR_RATE + i] = cages[j, CAGE_RATE]


@kernel
def _row_loads(k, idx, elout, rec, nz, th):
    """Bearing k's :data:`BR_ROW` outputs from its rollers' records ``rec`` (rows of ``nz``
    rollers; bearing/kernel/evaluate.py): of its first and last row the load on the outer ring
    from that row's raceway and rib contacts, turned to the track frame by the inner ring's tilt
    as the ring loads are, as axial (y), radial (in x-z) and the load zone's centre
    ``atan2(F_x, F_z)`` (0 at the top, positive towards the front)."""
    nbr = idx.shape[0]
    r = elout.shape[0] - BR_ROWS * (nbr - k) + BR_ROW
    tx, ty, tz = th[TH_IN + AX], th[TH_IN + AY], th[TH_IN + AZ]
    last = rec.shape[0] // nz - 1
    for i, j in enumerate((0, last)):
        f0 = f1 = f2 = 0.0
        for jk in range(j * nz, (j + 1) * nz):
            for c in OUTER_SLOTS:
                o = REC_LOAD + C_LOAD * c
                f0 += rec[jk, o + AX]
                f1 += rec[jk, o + AY]
                f2 += rec[jk, o + AZ]
        fx, fy, fz = f0 + ty * f2 - tz * f1, f1 + tz * f0 - tx * f2, f2 + tx * f1 - ty * f0
        elout[r, BR_AXIAL + i] = fy
        elout[r, BR_RADIAL + i] = sqrt(fx * fx + fz * fz)
        elout[r, BR_ZONE + i] = atan2(fx, fz)
