"""The fault-guided envelope band (bearing/diagnostics/guided.py) and its use on the healthy
side of a pair.

The case it is for, built with a known answer: the healthy side B receives the defect side's
impulses through the wheelset's bending (546 Hz, the paper's second bending mode), weakly, while
its own random shocks (wheel-rail, not periodic) ring a 3.5 kHz mode of its axle-box.  The
shocks own the spectral kurtosis, so the kurtosis band shows B no BPFO line; the band where the
BPFO line stands highest holds the 546 Hz response, and there the line is found.
"""
import numpy as np
import pytest

from axlebox._params import ParameterError
from axlebox.bearing.diagnostics.channel import analyse
from axlebox.bearing.diagnostics.criterion import Criterion
from axlebox.bearing.diagnostics.envelope import select_band
from axlebox.bearing.diagnostics.guided import band_grid, guided_band
from axlebox.bearing.diagnostics.pair import analyse_pair
from axlebox.bearing.diagnostics.synthetic import impulse_train, resonance, wheel_rail_noise
from axlebox.bearing.frequencies import orders, shaft_hz
from axlebox.bearing.models.params import BearingParams

FS = 10_000.0
SHAFT = shaft_hz(48.0)
ORDERS = orders(BearingParams())
BPFO = ORDERS.BPFO * SHAFT
BORE = 0.130
T = 4.0


def shocks(n, rng, rate_hz=30.0, f_ring=3500.0):
    """Random shocks at a Poisson rate (no period), random amplitudes, ringing ``f_ring``."""
    x = np.zeros(n)
    k = rng.random(n) < rate_hz / FS
    x[k] = rng.exponential(1.0, k.sum())
    return resonance(x, FS, f_ring, 0.03)


def sides(seed=0, gain=0.3, shock_level=1.0):
    """``(a, b)``: defect side A (impulses ringing 600 Hz in wheel-rail noise), healthy side B
    (A's impulses 1.2 ms later through 546 Hz at ``gain`` of A's RMS, its own noise and shocks at
    ``shock_level`` times that RMS)."""
    rng = np.random.default_rng(seed)
    n = int(T * FS)
    a = resonance(impulse_train(n, FS, BPFO, rng), FS, 600.0, 0.05)
    a /= a.std()
    b = resonance(np.roll(a, 12), FS, 546.0, 0.05)
    b *= gain / b.std()
    s = shocks(n, rng)
    b = b + 0.5 * gain * wheel_rail_noise(n, FS, rng) + shock_level * gain * s / s.std()
    return a + 0.3 * wheel_rail_noise(n, FS, rng), b


def test_the_grid_is_the_kurtograms_bands():
    """Levels 3-5 at 10 kHz for a 352 Hz minimum width (8 BPFO): N = 8, 16, 32 with bins
    f = k fs/N, k = 1 .. N/2 - 1, kept where f +- fs/N lies inside (0, fs/2)."""
    g = band_grid(FS, 40_000, 8 * BPFO)
    assert {round(hi - lo) for lo, hi in g} == {2500, 1250, 625}
    assert len(g) == 1 + 5 + 13
    assert all(0 < lo < hi < FS / 2 for lo, hi in g)
    assert not band_grid(FS, 40_000, 6000.0)


def test_guided_band_finds_the_transmitted_impulses_outside_the_kurtosis_band():
    _, b = sides()
    lo, hi = select_band(b, FS, min_width_hz=8 * ORDERS.BPFI * SHAFT)
    assert lo > 1000.0                            # the shocks own the kurtosis, not the 546 Hz
    blind = analyse(b, FS, SHAFT, ORDERS, BORE)
    assert "BPFO" not in blind.detected
    g = guided_band(b, FS, "BPFO", BPFO, nperseg=b.size)
    assert g.band[0] < 546.0 < g.band[1]
    assert g.p_fa == pytest.approx(1e-3 / g.n_bands)
    guided = analyse(b, FS, SHAFT, ORDERS, BORE, guide="BPFO")
    assert guided.band == g.band and guided.band_source == "guided by BPFO"
    assert guided.p_fa == pytest.approx(g.p_fa)
    assert "BPFO" in guided.detected
    assert abs(guided.lines["BPFO"].f_found / BPFO - 1) < 0.01
    # the band does not touch what does not depend on it
    for k in ("rms", "peak", "kurtosis", "VF", "SV"):
        assert getattr(guided, k) == getattr(blind, k)


def test_the_pair_searches_the_healthy_side_again_for_the_other_sides_line():
    """With the relative criterion (the paper's absolute range in Hz^2 belongs to its car, not
    to these resonances): B's shocks make it the more dispersed side, A's impulses the louder."""
    a, b = sides()
    rel = Criterion(mode="relative")
    res = analyse_pair(a, b, FS, SHAFT, ORDERS, BORE, rel)
    assert res.left.band_source == "spectral kurtosis"
    assert res.right.band_source == "guided by BPFO" and "BPFO" in res.right.detected
    assert res.right == analyse(b, FS, SHAFT, ORDERS, BORE, guide="BPFO")   # only the band redone
    assert res.verdict.words["left"] == "real fault" and res.verdict.words["right"] == "pseudo-fault"
    bpfo = res.verdict.evidence.lines[0].line
    assert bpfo.key == "BPFO" and bpfo.seen == {"left": True, "right": True}
    assert res.lag.leading == "a" and res.verdict.rule == "lag"
    off = analyse_pair(a, b, FS, SHAFT, ORDERS, BORE, rel, guided=False)
    assert off.right.band_source == "spectral kurtosis" and "BPFO" not in off.right.detected
    assert off.verdict.rule == "one side owns the lines" and off.verdict.real == "left"
    assert "no fault line here" in off.verdict.sentence("right")
    # with no line on either side nothing is searched again
    rng = np.random.default_rng(5)
    n = int(T * FS)
    quiet = [wheel_rail_noise(n, FS, rng) + shocks(n, rng) for _ in range(2)]
    h = analyse_pair(*quiet, FS, SHAFT, ORDERS, BORE, rel)
    assert {h.left.band_source, h.right.band_source} == {"spectral kurtosis"}
    assert h.verdict.words["left"] == h.verdict.words["right"] == "healthy"


def test_trying_many_bands_keeps_the_false_alarm_rate_of_one():
    """Noise and random shocks, no period, 30 records: the fundamental's window passes in the
    guided band in at most about p_fa of the records (Bonferroni: at most p_fa whatever the
    bands' correlation; the bands overlap, so fewer).  Without the correction (each band at
    p_fa) it passes far more often: that is what the correction is for.  p_fa = 0.2 keeps the
    counts large enough to compare: the limit 0.3 is the bound plus 1.4 binomial standard
    deviations of 30 records."""
    rng = np.random.default_rng(11)
    n = int(2.0 * FS)
    fixed, loose = [], []
    for _ in range(30):
        x = wheel_rail_noise(n, FS, rng) + shocks(n, rng)
        g = guided_band(x, FS, "BPFO", BPFO, nperseg=n, p_fa=0.2)
        fixed.append(g.line.searched[0][3] >= g.line.searched[0][4])
        u = guided_band(x, FS, "BPFO", BPFO, nperseg=n, p_fa=0.2 * g.n_bands)
        loose.append(u.line.searched[0][3] >= u.line.searched[0][4])
    assert np.mean(fixed) <= 0.3
    assert np.mean(loose) >= 2 * max(np.mean(fixed), 0.1)


def test_guide_refuses_what_it_cannot_do():
    _, b = sides()
    with pytest.raises(ParameterError, match="guide = 'BSF'"):
        analyse(b, FS, SHAFT, ORDERS, BORE, guide="BSF")
    with pytest.raises(ParameterError, match="not allowed together"):
        analyse(b, FS, SHAFT, ORDERS, BORE, band=(300.0, 800.0), guide="BPFO")
    with pytest.raises(ParameterError, match="f_line"):
        guided_band(b, FS, "BPFO", 1500.0, nperseg=b.size)
