"""The seam between a bearing and what moves its rings: one bearing advanced in its own
sub-steps over the window of an exchange, returning its ring loads averaged over the window
(numba).

Whatever carries the rings (the car's journal and axle-box markers, mbs/kernel/bearings.py;
the rig's outer-ring mass, bearing/integrate.py) steps at its own step ``H = n h`` and calls
:func:`advance` once a step, at its exchange ``t_b``, with the ring motion (bearing/kernel/layout.py:
``ring[0]`` the inner ring's, ``ring[1]`` the outer ring's, each displacement, tilt, velocity
and rate) there and at the exchange before.  The rollers and cages step by the leapfrog
(:func:`kick_drift`; ``mode`` 0 explicit, 1 "imex": contact damping implicit, 2 "imex2":
contact stiffness and friction too, bearing/kernel/implicit.py).

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

from numba.extending import overload

from axlebox._numba import kernel

from . import quasidynamic, step
from .dispatch import scheme_of
from .layout import LOAD, RING, RINGS
from .step import EXPLICIT, IMEX, IMEX2, MODES  # noqa: F401  (the modes, by name, for callers)

_SCHEMES = {"dynamic": step.substep, "quasi-dynamic": quasidynamic.substep}


def substep(tag, x, ring, P, D, w, K, t, h, hk, mode, theta, out, Qc, cages):
    """One sub-step of the bearing of tag ``tag`` (bearing/models/__init__.py; numba only) by its
    scheme: bearing/kernel/step.py's or bearing/kernel/quasidynamic.py's ``substep``."""
    raise NotImplementedError("bearing.advance.substep runs in numba only")


@overload(substep, jit_options={"cache": True, "error_model": "numpy"})
def _substep(tag, x, ring, P, D, w, K, t, h, hk, mode, theta, out, Qc, cages):
    f = _SCHEMES[scheme_of(tag.instance_class)]

    def impl(tag, x, ring, P, D, w, K, t, h, hk, mode, theta, out, Qc, cages):
        f(tag, x, ring, P, D, w, K, t, h, hk, mode, theta, out, Qc, cages)
    return impl


@kernel
def advance(tag, x, ring_a, ring_b, P, D, w, K, t_b, h, n, first, mode, theta, F_mean, Qc, cages):
    """Advance one bearing's states ``x`` (tag ``tag``, bearing/models/__init__.py) by the ``n`` sub-steps
    of ``h`` of the window of the exchange at ``t_b`` (module docstring).  ``ring_a`` /
    ``ring_b``: the ring motion (RINGS, RING) at the exchange before (``t_b - n h``) and at this
    one; ``P``, ``D``: the bearing's parameter vector and defect rows; ``w``, ``K``: its scratch
    (bearing/kernel/evaluate.py ``Work``, bearing/kernel/implicit.py ``Kick``).

    Out: ``F_mean`` (RINGS, LOAD) the ring loads averaged over the samples; ``Qc`` (rows, Z,
    N_Q) the contact forces and ``cages`` (rows, CAGE_OUT; bearing/kernel/layout.py) at the
    sample at the exchange (half a sub-step after it where ``n`` is even), before its step.
    ``theta``: the implicit kick's weight (bearing/kernel/implicit.py; 1 as shipped)."""
    F_mean[:, :] = 0.0
    c0 = 0.5 * (n + 1)                       # the window's centre, in samples
    j_out = n // 2 + 1                       # the sample at (or just after) the exchange
    j0 = j_out if first else 1
    for j in range(j0, n + 1):
        s = 1.0 + (j - c0) / n               # 0 at the exchange before, 1 at this one
        for r in range(RINGS):
            for c in range(RING):
                # (1 - s) a + s b: at s = 1 exactly b (a + s (b - a) is not, in floating point)
                w.ring[r, c] = ring_b[r, c] if first else (1.0 - s) * ring_a[r, c] + s * ring_b[r, c]
        hk = 0.5 * h if (first and j == j0) else h
        substep(tag, x, w.ring, P, D, w, K, t_b + (j - c0) * h, h, hk, mode, theta, j == j_out, Qc,
                cages)
        for r in range(RINGS):
            for c in range(LOAD):
                F_mean[r, c] += w.F[r, c]
    m = n - j0 + 1
    for r in range(RINGS):
        for c in range(LOAD):
            F_mean[r, c] /= m
