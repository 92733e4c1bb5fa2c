"""One bearing's right-hand side from its parts (numba): for each roller its kinematics
(:mod:`.roller`), its contacts with the rings (the model's, :func:`.models.contacts`) and with
its pocket (:mod:`.pocket`) into its record, then its Newton-Euler equations; the records summed
into each cage's loads and its equations, and into the ring loads (paper Eq. 16 with moments).

Each roller's record holds everything it puts on the other bodies (:mod:`.layout`, ``REC_*``),
and its rows of the implicit blocks go to its own block: a roller can be evaluated on its own
(:func:`roller`; the quasi-dynamic bearing's Newton moves them one by one) and the sums made from
the records afterwards (:func:`ring_loads`, :func:`.roller.cage_rates`).

IEEE arithmetic, no ``fastmath``: with it, LLVM fuses multiply-adds where the inlined callees
happen to meet, and a kernel compiled in this process and the same kernel loaded from numba's
cache differed in the last bit of some roller accelerations; the quasi-static start's 1e-12 m
difference steps and the contacts' chaos grow that to a different run (tests/test_sweep.py).
"""
from __future__ import annotations

from collections import namedtuple
from math import pi

import numpy as np

from axlebox._numba import kernel

from ..defects import count
from .dispatch import contacts
from .layout import (
    BLK,
    BLK_NONE,
    C_LOAD,
    F_X,
    G_X,
    G_Y,
    G_Z,
    INNER,
    INNER_RING,
    INNER_SLOTS,
    LOAD,
    M_R,
    N_CAGE,
    N_Q,
    N_ROLLER,
    OUTER,
    OUTER_SLOTS,
    PSI,
    REC,
    REC_F,
    REC_LOAD,
    REC_ORBIT,
    N_ROWS,
    RING,
    RINGS,
    ROLLER_SURFACE,
    Z,
    Touch,
    rows_of,
)
from .pocket import pockets
from .roller import (
    cage_frame,
    cage_rates,
    orbital_inertia,
    pocket_angles,
    ring_frame,
    roller_frame,
    roller_rates,
)
from .vec import mul, put

TWO_PI = 2.0 * pi

#: one bearing's scratch (:func:`work`), n rows of Z rollers: the rollers' records ``rec`` (n Z,
#: REC), their block rows ``blk`` (n Z, 6, BLK) and flags ``flag`` (n Z), each row's cage block
#: ``cblk`` (n, 6, 6), the pockets' azimuths' sines and cosines (n, Z), and what a step needs besides
#: (bearing/kernel/advance.py): the state's derivative ``dx``, the ring motion ``ring`` and loads ``F``
#: of a sub-step, its contact forces ``Qs`` and the quasi-dynamic Newton's per-roller scratch
#: ``qd`` (bearing/kernel/quasidynamic.py)
Work = namedtuple("Work", ["rec", "blk", "flag", "cblk", "sin_p", "cos_p", "dx", "ring", "F", "Qs",
                           "qd"])


def work(Z_: int, n_state: int, qd_width: int = 0, stack: tuple = ()) -> Work:
    """A bearing's :class:`Work` (``Z_`` rollers a row, ``n_state`` states, which count its rows;
    ``stack``: leading dimensions, one bearing each)."""
    z = lambda *shape: np.zeros(stack + shape)      # noqa: E731
    n = rows_of(n_state, Z_)
    return Work(z(n * Z_, REC), z(n * Z_, 6, BLK), np.zeros(stack + (n * Z_,), np.int64),
                z(n, 6, 6), z(n, Z_), z(n, Z_), z(n_state), z(RINGS, RING), z(RINGS, LOAD),
                z(n, Z_, N_Q), z(n * Z_, qd_width))


@kernel
def one(W, b):
    """Bearing ``b``'s :class:`Work` from a stack of them."""
    return Work(W.rec[b], W.blk[b], W.flag[b], W.cblk[b], W.sin_p[b], W.cos_p[b], W.dx[b], W.ring[b],
                W.F[b], W.Qs[b], W.qd[b])


@kernel
def evaluate(model, t, x, ring, P, D, dx, F, Qc, w, want, h_k):
    """State derivative ``dx``, ring loads ``F`` (RINGS, LOAD) and contact forces ``Qc`` (n, Z, N_Q)
    of the bearing ``model`` (a tag of :mod:`.models`) at state ``x`` and ring motion ``ring``;
    with ``want`` every roller's block rows too (``h_k``: bearing/contact.normal).  ``w``: its
    :class:`Work`."""
    nz, nrow = int(P[Z]), int(P[N_ROWS])
    rings = ring_frame(ring)
    n_inner, n_roller = count(D, INNER_RING), count(D, ROLLER_SURFACE)
    J_orb = orbital_inertia(P)
    for j in range(nrow):
        cb = nrow * nz * N_ROLLER + j * N_CAGE
        cage = cage_frame(x, cb, P, rings.omega)
        pocket_angles(cage.phi, nz, w.sin_p[j], w.cos_p[j])
        w.cblk[j, :, :] = 0.0
        orbit = 0.0
        for k in range(nz):
            roller(model, x, dx, j, k, rings, cage, P, D, n_inner, n_roller, Qc, w, want, h_k, J_orb)
            orbit += w.rec[j * nz + k, REC_ORBIT]
        cage_rates(x, dx, cb, P, w.rec[j * nz:(j + 1) * nz], nz, cage, orbit, J_orb)
    ring_loads(w.rec, F)


@kernel(inline="always")
def roller(model, x, dx, j, k, rings, cage, P, D, n_inner, n_roller, Qc, w, want, h_k, J_orb):
    """Roller k of row j: its record (its contacts' loads), its contact forces, its block rows
    (with ``want``) and its rows of ``dx``."""
    nz = w.sin_p.shape[1]
    jk = j * nz + k
    b0 = jk * N_ROLLER
    _, phid_c, _ = cage.w
    sp, cp = w.sin_p[j, k], w.cos_p[j, k]
    fr = roller_frame(x, b0, j, P, cage.phi + TWO_PI * k / nz, sp, cp, phid_c)
    rec = w.rec[jk]
    rec[:] = 0.0
    put(rec, REC_F, mul(P[M_R], (P[G_X], P[G_Y], P[G_Z])))          # its weight, then its contacts
    w.flag[jk] = BLK_NONE
    ct = Touch(rec, w.blk, w.cblk[j], w.flag, jk)
    contacts(model, ct, Qc[j, k], j, k, fr, rings, x[b0 + PSI], P, D, n_inner, n_roller, want, h_k)
    pockets(ct, Qc[j, k], fr, cage, sp, cp, P, want, h_k)
    rec[REC_ORBIT] = roller_rates(x, dx, b0, fr, rec, P, phid_c, J_orb)


@kernel
def ring_loads(rec, F):
    """The rings' loads ``F`` (RINGS, LOAD): every roller's record summed (paper Eq. 16), roller by
    roller and contact slot by slot (bearing/kernel/layout.py)."""
    F[:, :] = 0.0
    for jk in range(rec.shape[0]):
        for c in INNER_SLOTS:
            for q in range(C_LOAD):
                F[INNER, F_X + q] += rec[jk, REC_LOAD + C_LOAD * c + q]
        for c in OUTER_SLOTS:
            for q in range(C_LOAD):
                F[OUTER, F_X + q] += rec[jk, REC_LOAD + C_LOAD * c + q]


def rates(model, t, y, ring, P, D, want: bool = False, h_k: float = 0.0):
    """:func:`evaluate` from Python, allocating: ``(dx, F, Qc, w)`` of the bearing of tag
    ``model`` (bearing/models/__init__.py ``tag(p).model``) at state ``y`` and ring motion ``ring``;
    ``w`` (:class:`Work`) holds the records and, with ``want``, the blocks."""
    nz, nrow = int(P[Z]), int(P[N_ROWS])
    y = np.ascontiguousarray(y, float)
    w = work(nz, y.size)
    dx, F, Qc = np.zeros(y.size), np.zeros((RINGS, LOAD)), np.zeros((nrow, nz, N_Q))
    evaluate(model, float(t), y, np.ascontiguousarray(ring, float), P, np.ascontiguousarray(D, float),
             dx, F, Qc, w, want, float(h_k))
    return dx, F, Qc, w
