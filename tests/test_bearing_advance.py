"""The bearing behind its seam (bearing/kernel/advance.py): one sub-step an exchange is the single-rate
leapfrog step bit for bit, sub-steps between still rings are repeated single steps, the ring
motion over the window is the line through the two exchanges', and the loads are the samples'
mean."""
import numpy as np
import pytest

from axlebox.bearing.kernel import dispatch
from axlebox.bearing import defects, models

from axlebox.bearing.statics import equilibrium

from axlebox.bearing.kernel import layout
from axlebox.bearing.kernel.advance import EXPLICIT, IMEX, IMEX2, advance
from axlebox.bearing.kernel.evaluate import evaluate, work
from axlebox.bearing.kernel.implicit import NEWMARK_K, damped_kick, scratch
from axlebox.bearing.models.params import BearingParams
from axlebox.bearing.kernel.quasidynamic import QD_WIDTH
from axlebox.bearing.kernel.step import cage_outputs, kick_drift

LOAD, OMEGA, H = (0.0, 0.0, -54e3), 48 / 3.6 / 0.42, 5e-6     # N (the car's bearing), rad/s (48 km/h), s


@pytest.fixture(scope="module")
def bearing():
    """The shipped calibration (contact damping 1e-4 s x stiffness) with the 2 mm defect, at its
    static state, the inner ring turning at 48 km/h."""
    p = BearingParams(damping="stiffness", beta=1e-4)
    P = models.pack(p)
    D = defects.table((defects.Defect(W=2e-3),), p)
    y, uo = equilibrium.static_state(p, P, D, LOAD, OMEGA)
    return p, P, D, y, equilibrium.ring_motion(OMEGA, uo)


TAG = dispatch.tag(BearingParams())


def _single_rate_step(x, ring, P, D, t, h, mode, first):
    """The leapfrog step the car and the rig took before the seam: evaluate, (implicit) kick,
    drift (bearing/kernel/implicit.py, bearing/kernel/step.py kick_drift)."""
    Z = int(P[layout.Z])
    w = work(Z, x.size)
    dx, F, Qc = np.empty(x.size), np.zeros((layout.RINGS, layout.LOAD)), np.zeros((2, Z, layout.N_Q))
    evaluate(TAG, t, x, ring, P, D, dx, F, Qc, w, mode != EXPLICIT, NEWMARK_K * h if mode == IMEX2 else 0.0)
    cages = np.empty((2, layout.CAGE_OUT))
    cage_outputs(x, dx, cages)
    hk = 0.5 * h if first else h
    if mode != EXPLICIT:
        damped_kick(x, dx, w.blk, w.cblk, w.flag, P, hk, 1.0, scratch(Z, 2))
    kick_drift(x, dx, P, hk, h, mode == EXPLICIT)
    return F, Qc, cages


def _advance(x, ring_a, ring_b, P, D, t, h, n, first, mode):
    Z = int(P[layout.Z])
    F, Qc = np.zeros((layout.RINGS, layout.LOAD)), np.zeros((2, Z, layout.N_Q))
    cages = np.empty((2, layout.CAGE_OUT))
    advance(TAG, x, ring_a, ring_b, P, D, work(Z, x.size, QD_WIDTH), scratch(Z, 2), t, h, n, first, mode,
            1.0, F, Qc, cages)
    return F, Qc, cages


@pytest.mark.parametrize("mode", [EXPLICIT, IMEX, IMEX2])
def test_one_substep_an_exchange_is_the_single_rate_step_bit_for_bit(bearing, mode):
    """20 exchanges of one sub-step each, the first from the initial rates (half kick), the rings
    moving between exchanges (the outer ring 1 um a step down, the inner ring turning): states,
    loads, contacts and cages equal the single-rate steps' to the bit."""
    p, P, D, y, ring = bearing
    x_ref, x = y.copy(), y.copy()
    ring_a = ring.copy()
    for i in range(20):
        t = i * H
        ring_b = ring.copy()
        ring_b[layout.INNER, layout.TH_Y] = OMEGA * t
        ring_b[layout.OUTER, layout.U_Z] -= 1e-6 * i
        ref = _single_rate_step(x_ref, ring_b, P, D, t, H, mode, i == 0)
        got = _advance(x, ring_a, ring_b, P, D, t, H, 1, i == 0, mode)
        ring_a = ring_b
        for a, b in zip(ref, got):
            np.testing.assert_array_equal(a, b)
        np.testing.assert_array_equal(x_ref, x)


def test_substeps_between_still_rings_are_repeated_steps_and_the_loads_their_mean(bearing):
    """Rings that do not move (turning at a fixed angle: the interpolation has nothing to do):
    an exchange of 4 sub-steps is 4 single steps (to rounding: the interpolated ring motion
    ``(1 - s) a + s a`` differs from ``a`` in the last bit), and its loads are the mean of the 4
    steps' loads."""
    p, P, D, y, ring = bearing
    x_ref, x = y.copy(), y.copy()
    F_steps = []
    for j in range(4):
        F, _, _ = _single_rate_step(x_ref, ring, P, D, j * H, H, IMEX, False)
        F_steps.append(F.copy())
    F, _, _ = _advance(x, ring, ring.copy(), P, D, 2.5 * H, H, 4, False, IMEX)
    np.testing.assert_allclose(x, x_ref, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(F, np.mean(F_steps, axis=0), rtol=1e-9, atol=1e-6)


@pytest.mark.parametrize("n", [5, 4])
def test_the_window_is_centred_on_the_exchange_on_the_line_through_two_ring_motions(bearing, n):
    """An exchange of n sub-steps with the outer ring moving from a (the exchange before) to b
    (this one) samples it at ``a + s (b - a)``, ``s = 1 + (j - (n + 1) / 2) / n``: centred on
    this exchange, interpolated before it and carried on after; the same as n single steps at
    those ring positions, and the loads their mean."""
    p, P, D, y, ring = bearing
    ring_a, ring_b = ring.copy(), ring.copy()
    ring_a[layout.OUTER, layout.U_Z] += 1e-6
    ring_b[layout.OUTER, layout.U_Z] -= 1e-6
    ring_b[layout.OUTER, layout.V_Z] = -0.4     # and its velocity, m/s
    x_ref, x = y.copy(), y.copy()
    F_steps = []
    for j in range(1, n + 1):
        s = 1 + (j - (n + 1) / 2) / n
        r = (1 - s) * ring_a + s * ring_b
        F, _, _ = _single_rate_step(x_ref, r, P, D, (j - (n + 1) / 2) * H, H, IMEX, False)
        F_steps.append(F.copy())
    F, _, _ = _advance(x, ring_a, ring_b, P, D, 0.0, H, n, False, IMEX)
    np.testing.assert_array_equal(x, x_ref)
    np.testing.assert_allclose(F, np.mean(F_steps, axis=0), rtol=1e-12, atol=1e-9)
