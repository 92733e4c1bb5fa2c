"""The seam between a bearing and what moves its rings: one bearing advanced in its own
sub-steps over the window of an exchange, returning its ring loads averaged over the window
(numba).

Whatever carries the rings (the car's journal and axle-box markers, mbs/kernel_bearings.py;
the rig's outer-ring mass, bearing/integrate.py) steps at its own step ``H = n h`` and calls
:func:`advance` once a step, at its exchange ``t_b``, with the ring motion (bearing/layout.py:
``ring[0]`` the inner ring's, ``ring[1]`` the outer ring's, each displacement, tilt, velocity
and rate) there and at the exchange before.  The rollers and cages step by the leapfrog
(:func:`kick_drift`; ``mode`` 0 explicit, 1 "imex": contact damping implicit, 2 "imex2":
contact stiffness and friction too, bearing/implicit.py).

The window is centred on the exchange: ``n`` samples at ``t_b + (j - (n + 1) / 2) h``,
``j = 1 .. n``, one a sub-step, the ring motion on the straight line (in position and in
velocity) through the two exchanges' (interpolated over the window's first half, carried on
by at most half a step over its second), and the caller gets the samples' mean.  Why centred:
a mean over the step just past, ``(t_b - H, t_b]``, acts on the bodies half a step late, and a
late stiff spring feeds energy in (a negative damping ratio of ``w H / 4`` on a mode of
frequency ``w``: on an axle box on its bearing, about 2 % at ``H`` = 2e-5 s); the car ran away
within 0.1 s so (measured, benchmarks/README.md "Multirate").  Centred, a load linear in the
ring motion averages to its value at the exchange, which is the single-rate leapfrog's: what
the exchange changes is only the nonlinear part (the impulses), which the sub-steps resolve
and the mean passes on whole (the window's impulse: momentum is conserved).  With ``n = 1``
this is exactly the single-rate step (the same evaluations in the same order: the same bits).

The samples of successive exchanges tile time: the bearings' states run on their own grid
(offset by half a sub-step from the bodies' where ``n`` is even).  On the first exchange of a
run (``first``) there is no earlier ring motion: the window's second half alone, the ring held
at the exchange's, from the initial rates with the leapfrog's half kick.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .implicit import NEWMARK_K, damped_kick
from .kernel import dtrb_rhs_damped
from .layout import KINEMATIC, N_CAGE, N_ROLLER, QUASI
from .quasidynamic import equilibrium, spin_step

EXPLICIT, IMEX, IMEX2 = 0, 1, 2
MODES = {"leapfrog": EXPLICIT, "imex": IMEX, "imex2": IMEX2}


@njit(cache=True)
def cage_outputs(x, dx, out):
    """The two cages' azimuth and azimuth rate (``out``: angle 1, angle 2, rate 1, rate 2) from
    the states ``x`` and their derivative ``dx`` (whose azimuth row is the rate: the state's for
    a free cage, Eq. 2's for a kinematic one)."""
    cb = x.shape[0] - 2 * N_CAGE
    out[0] = x[cb + 5]
    out[1] = x[cb + N_CAGE + 5]
    out[2] = dx[cb + 5]
    out[3] = dx[cb + N_CAGE + 5]


@njit(cache=True)
def kick_drift(y, a, P, hk, h, kick):
    """The leapfrog on one DTRB's states ``y`` (bearing/layout.py: rollers, then cages, each six
    positions and their six rates) from their accelerations ``a``: the rates kicked by ``hk``
    (unless ``kick`` is False: the implicit kick did it), then the positions drifted by ``h`` at
    the new rates; a kinematic cage drives the azimuths at the rate the right-hand side gave."""
    kin = P[KINEMATIC] != 0.0
    cages = y.shape[0] - 2 * N_CAGE
    for o in range(0, y.shape[0], N_ROLLER):
        for q in range(6):
            if kick:
                y[o + 6 + q] += hk * a[o + 6 + q]
            if kin and ((o < cages and q == 1) or (o >= cages and q == 5)):
                y[o + q] += h * a[o + q]
            else:
                y[o + q] += h * y[o + 6 + q]


@njit(cache=True)
def advance(x, ring_a, ring_b, P, D, t_b, h, n, first, mode, F_mean, Qc, cages, G, dx, ring, F, Qs,
            theta=1.0):
    """Advance one DTRB's states ``x`` (bearing/layout.py) by the ``n`` sub-steps of ``h`` of
    the window of the exchange at ``t_b`` (module docstring).  ``ring_a``/``ring_b``: the ring
    motion (2, 12) at the exchange before (``t_b - n h``) and at this one; ``P``, ``D``: the
    bearing's parameter vector and defect rows.

    Out: ``F_mean`` (2, 6) the ring loads averaged over the samples; ``Qc`` (2, Z, 6) the
    contact forces and ``cages`` (:func:`cage_outputs`) at the sample at the exchange (half a
    sub-step after it where ``n`` is even), before its step.  Scratch: ``G``
    (:func:`block_rows`, Z + 1, 6, 12); ``dx`` like ``x``; ``ring`` (2, 12); ``F`` (2, 6); ``Qs`` like
    ``Qc`` (:func:`scratch`).  ``theta``: the implicit kick's weight (bearing/implicit.py; 1 as
    shipped).  A quasi-dynamic bearing (``P[QUASI]``, bearing/quasidynamic.py) takes each
    sub-step by its own scheme whatever ``mode`` is."""
    h_k = NEWMARK_K * h / theta if mode == IMEX2 else 0.0
    quasi = P[QUASI] != 0.0
    Gb = G[0:2]                              # a quasi-dynamic bearing's blocks, then its scratch
    buf = G.reshape(G.size)[Gb.size:]
    F_mean[:, :] = 0.0
    c0 = 0.5 * (n + 1)                       # the window's centre, in samples
    j_out = n // 2 + 1                       # the sample at (or just after) the exchange
    j0 = j_out if first else 1
    for j in range(j0, n + 1):
        s = 1.0 + (j - c0) / n               # 0 at the exchange before, 1 at this one
        for r in range(2):
            for c in range(12):
                # (1 - s) a + s b: at s = 1 exactly b (a + s (b - a) is not, in floating point)
                ring[r, c] = (ring_b[r, c] if first
                              else (1.0 - s) * ring_a[r, c] + s * ring_b[r, c])
        if quasi:
            equilibrium(t_b + (j - c0) * h, x, ring, P, D, h, dx, F, Qs, Gb, buf)
        else:
            dtrb_rhs_damped(t_b + (j - c0) * h, x, ring, P, D, dx, F, Qs, G, h_k)
        for r in range(2):
            for c in range(6):
                F_mean[r, c] += F[r, c]
        if j == j_out:
            Qc[:, :, :] = Qs
            cage_outputs(x, dx, cages)
        if quasi:
            spin_step(x, P, h, dx, Gb, buf)
            continue
        hk = 0.5 * h if (first and j == j0) else h
        if mode != EXPLICIT:
            damped_kick(x, dx, G, P, hk, theta)
        kick_drift(x, dx, P, hk, h, mode == EXPLICIT)
    m = n - j0 + 1
    for r in range(2):
        for c in range(6):
            F_mean[r, c] /= m


def scratch(P: np.ndarray, n_state: int, mode: int):
    """``advance``'s scratch arrays for a bearing of ``n_state`` states: (G, dx, ring, F, Qs)."""
    nz = int(P[0])
    rows = block_rows(P, mode)
    G = np.zeros((rows, nz + 1, 6, 12)) if rows else np.empty((0, 1, 6, 12))
    return G, np.empty(n_state), np.zeros((2, 12)), np.zeros((2, 6)), np.zeros((2, nz, 6))


def block_rows(P: np.ndarray, mode: int) -> int:
    """The first dimension of :func:`advance`'s ``G`` for bearing(s) ``P`` (one row or a
    stack): 2 for the implicit kick's blocks, 4 for a quasi-dynamic bearing (its blocks and its
    scratch), 0 for the explicit leapfrog."""
    if np.any(np.atleast_2d(P)[:, QUASI] != 0.0):
        return 4
    return 0 if mode == EXPLICIT else 2
