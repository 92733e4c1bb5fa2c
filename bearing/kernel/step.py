"""The dynamic bearing's sub-step (numba): the leapfrog of the paper's model, every roller and
cage with its six degrees of freedom.

One evaluation (:func:`.evaluate.evaluate`), then the kick of the rates and the drift of the
positions (:func:`kick_drift`): ``mode`` :data:`EXPLICIT` the explicit leapfrog, :data:`IMEX`
the contact damping in the kick implicitly, :data:`IMEX2` the contacts' stiffness (Newmark's
average acceleration) and friction too (bearing/kernel/implicit.py).
"""
from __future__ import annotations

from axlebox._numba import kernel

from .evaluate import evaluate
from .implicit import NEWMARK_K, damped_kick
from .layout import CAGE_ANGLE, CAGE_RATE, CPHI, FREE_CAGE, KINEMATIC, N_CAGE, N_ROLLER, N_ROWS, PHI, RATE
from .vec import copy3

EXPLICIT, IMEX, IMEX2 = 0, 1, 2
MODES = {"leapfrog": EXPLICIT, "imex": IMEX, "imex2": IMEX2}


@kernel
def cage_outputs(x, dx, out):
    """Each row's cage azimuth and its rate (``out`` (rows, CAGE_OUT): :data:`.layout.CAGE_ANGLE`,
    ``CAGE_RATE``) from the state ``x`` and its derivative ``dx`` (whose azimuth row is the rate:
    the state's for a free cage, Eq. 2's for a kinematic one)."""
    rows = out.shape[0]
    cb = x.shape[0] - rows * N_CAGE
    for j in range(rows):
        out[j, CAGE_ANGLE] = x[cb + j * N_CAGE + CPHI]
        out[j, CAGE_RATE] = dx[cb + j * N_CAGE + CPHI]


@kernel
def kick_drift(y, a, P, hk, h, kick):
    """The leapfrog on one bearing's states ``y`` (rollers, then cages, each six positions and
    their six rates) from their accelerations ``a``: the rates kicked by ``hk`` (unless ``kick``
    is False: the implicit kick did it), then the positions drifted by ``h`` at the new rates; a
    kinematic cage drives the azimuths at the rate the right-hand side gave."""
    kin = P[KINEMATIC] != FREE_CAGE
    cages = y.shape[0] - int(P[N_ROWS]) * N_CAGE
    for o in range(0, y.shape[0], N_ROLLER):
        for q in range(RATE):
            if kick:
                y[o + RATE + q] += hk * a[o + RATE + q]
            if kin and ((o < cages and q == PHI) or (o >= cages and q == CPHI)):
                y[o + q] += h * a[o + q]
            else:
                y[o + q] += h * y[o + RATE + q]


@kernel(inline="always")
def substep(model, x, ring, P, D, w, K, t, h, hk, mode, theta, out, Qc, cages):
    """One sub-step of ``h`` of the dynamic bearing ``model`` (a tag of bearing/models/__init__.py) at
    ring motion ``ring``: its ring loads there to ``w.F``, and with ``out`` its contact forces to
    ``Qc`` and cages to ``cages``, before the step; the kick by ``hk`` (h, or h / 2 from initial
    rates), weighted by ``theta`` where implicit.  ``w``, ``K``: its scratch."""
    h_k = NEWMARK_K * h / theta if mode == IMEX2 else 0.0
    evaluate(model, t, x, ring, P, D, w.dx, w.F, w.Qs, w, mode != EXPLICIT, h_k)
    if out:
        copy3(Qc, w.Qs)
        cage_outputs(x, w.dx, cages)
    if mode != EXPLICIT:
        damped_kick(x, w.dx, w.blk, w.cblk, w.flag, P, hk, theta, K)
    kick_drift(x, w.dx, P, hk, h, mode == EXPLICIT)
