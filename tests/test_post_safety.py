"""Running safety (mbs/post/safety.py) against its closed forms: Nadal's limit at the published
values, the S1002 flange's 70 degrees (EN 13715's section E, slope 2.747477419), Prud'homme's
limit, the sliding mean against a sinusoid's exact mean, the forces' signs by a flange's push."""
import math

import numpy as np
import pytest

from axlebox._params import ParameterError
from axlebox.mbs.post import safety
from axlebox.mbs.wheelrail.standard import s1002


@pytest.mark.parametrize("mu, limit", [(0.25, 1.48), (0.30, 1.34), (0.36, 1.20)])
def test_nadal_at_70_degrees(mu, limit):
    """Nadal's (Y/Q)_lim at a 70 degree flange (the published table, two decimals)."""
    assert safety.nadal(math.radians(70.0), mu) == pytest.approx(limit, abs=0.005)


def test_nadal_without_friction_is_the_flange_slope():
    """mu = 0: the wheel slides down its flange until Y/Q = tan(delta) (the normal force's own
    ratio)."""
    assert safety.nadal(0.9, 0.0) == pytest.approx(math.tan(0.9), rel=1e-15)


def test_the_s1002_flange_is_70_degrees():
    """EN 13715 Annex C: the S1002 flange flank (section E) is the straight line of slope
    2.747477419, atan of which is 70.000 deg; the back face beyond the tip, vertical, is not the
    flank."""
    assert math.degrees(safety.flange_angle(s1002())) == pytest.approx(
        math.degrees(math.atan(2.747477419)), abs=0.01)
    assert math.degrees(math.atan(2.747477419)) == pytest.approx(70.0, abs=1e-3)


def test_prudhomme_is_the_axle_load_form():
    """EN 14363's track-shift limit alpha (10 + P0 / 3) kN, P0 the static axle load: 140 kN ->
    56.67 kN; written with the wheel load Q0 = P0 / 2."""
    assert safety.prudhomme(70e3) == pytest.approx(1e3 * (10.0 + 140.0 / 3.0), rel=1e-12)
    assert safety.prudhomme(70e3, alpha=0.85) == pytest.approx(0.85 * 56666.67, rel=1e-6)


def test_the_sliding_mean_of_a_sinusoid():
    """Over a window w centred on s the mean of sin(k s) is sin(k s) sin(k w / 2) / (k w / 2);
    a constant and a line stay as they are (away from the ends); non-uniform spacing (a varying
    speed) changes nothing."""
    rng = np.random.default_rng(1)
    s = np.cumsum(rng.uniform(0.5e-3, 1.5e-3, 40000))
    k = 2 * math.pi / 5.0
    m = safety.sliding_mean(np.sin(k * s), s)
    inner = (s > s[0] + 1.0) & (s < s[-1] - 1.0)
    np.testing.assert_allclose(m[inner], (np.sin(k * s) * math.sin(k) / k)[inner], rtol=0, atol=2e-6)
    two = safety.sliding_mean(np.stack([np.full_like(s, 3.0), 2.0 * s], axis=1), s)
    np.testing.assert_allclose(two[:, 0], 3.0, rtol=1e-12)
    # the cumulative integral is interpolated linearly: off by up to ds^2 x' / 8 (ds <= 1.5 mm)
    np.testing.assert_allclose(two[inner, 1], 2.0 * s[inner], rtol=0, atol=1e-6)


def test_the_sliding_mean_refuses_a_distance_that_runs_back():
    with pytest.raises(ParameterError, match="s is not allowed to decrease"):
        safety.sliding_mean(np.ones(3), np.array([0.0, 1.0, 0.5]))


def test_a_flange_pushing_its_rail_outwards_is_positive_Y():
    """A left wheel's flange against its rail: the rail pushes the wheel right (F_y < 0), Y > 0;
    the right wheel's mirror image likewise; the wheelset's sum of Y is the force on the track
    in track y."""
    s = np.linspace(0.0, 10.0, 101)
    F_L = np.tile([0.0, -30e3, 60e3], (101, 1))
    F_R = np.tile([0.0, 10e3, 50e3], (101, 1))
    left, right = safety.wheel_forces(F_L, +1, s), safety.wheel_forces(F_R, -1, s)
    assert left.Y[0] == 30e3 and left.Q[0] == 60e3 and left.YQ[0] == 0.5
    assert right.Y[0] == 10e3 and right.YQ_2m[50] == pytest.approx(0.2)
    assert safety.sum_Y(F_L, F_R)[0] == pytest.approx(20e3)


def test_a_lifted_wheel_has_no_quotient():
    s = np.linspace(0.0, 10.0, 101)
    F = np.tile([0.0, -10e3, 50e3], (101, 1))
    F[40:45, 2] = 0.0
    w = safety.wheel_forces(F, +1, s)
    assert np.all(np.isnan(w.YQ[40:45])) and np.all(np.isfinite(w.YQ_2m))
    np.testing.assert_allclose(w.YQ_2m, 0.2, rtol=1e-12)


def test_a_wheel_off_its_rail_through_a_whole_window_has_no_mean():
    """Lifted over more than the 2 m window: its sliding mean there is NaN, never a 0 that reads
    as safe; the rest of the record keeps its mean."""
    s = np.linspace(0.0, 20.0, 2001)
    F = np.tile([0.0, -10e3, 50e3], (2001, 1))
    F[800:1200, 2] = 0.0                               # 8 m .. 12 m: off the rail
    w = safety.wheel_forces(F, +1, s)
    assert np.all(np.isnan(w.YQ_2m[950:1050]))
    np.testing.assert_allclose(w.YQ_2m[:700], 0.2, rtol=1e-12)
    np.testing.assert_allclose(safety.wheel_forces(np.tile([0.0, 0.0, -1.0], (5, 1)), 1,
                                                   np.arange(5.0)).YQ_2m, np.nan)
