"""Hertz normal contact (mbs/wheelrail/hertz.py) against closed forms and a published table."""
import numpy as np
import pytest

from axlebox._params import ParameterError
from axlebox.mbs.wheelrail import hertz as hz

E_STEEL, NU_STEEL = 2.1e11, 0.3
E_STAR = hz.effective_modulus(E_STEEL, NU_STEEL)


def _theta_curvatures(theta_deg):
    """A <= B with A + B = 1 and cos(theta) = (B - A)/(A + B)."""
    c = np.cos(np.radians(theta_deg))
    return 0.5 * (1.0 - c), 0.5 * (1.0 + c)


def test_effective_modulus_of_two_steel_bodies():
    # 1/E* = 2 (1 - nu^2)/E
    assert E_STAR == pytest.approx(E_STEEL / (2.0 * (1.0 - NU_STEEL ** 2)), rel=1e-14)


def test_sphere_on_plane_matches_hertz_closed_form():
    # Johnson 1985 Sec. 4.2 (sphere): a = (3 N R / (4 E*))^(1/3), delta = a^2/R, p0 = 3N/(2 pi a^2)
    R, N = 0.02, 500.0
    r = hz.hertz(0.5 / R, 0.5 / R, N, E_STAR)
    a = (3.0 * N * R / (4.0 * E_STAR)) ** (1.0 / 3.0)
    assert r.a == pytest.approx(a, rel=1e-12) and r.b == pytest.approx(a, rel=1e-12)
    assert r.delta == pytest.approx(a * a / R, rel=1e-12)
    assert r.p0 == pytest.approx(3.0 * N / (2.0 * np.pi * a * a), rel=1e-12)
    assert r.K_H == pytest.approx(4.0 / 3.0 * E_STAR * np.sqrt(R), rel=1e-12)
    assert r.m == pytest.approx(1.0) and r.n == pytest.approx(1.0)
    assert r.theta == pytest.approx(np.pi / 2) and r.a_over_b == pytest.approx(1.0)


def test_crossed_equal_cylinders_at_90_degrees_are_a_sphere_on_a_plane():
    # two cylinders of radius R crossed at 90 deg: A = B = 1/(2R), the sphere of radius R
    R, N = 0.05, 2.0e4
    A, B, psi = hz.relative_curvatures(1.0 / R, 0.0, 1.0 / R, 0.0, omega=np.pi / 2)
    assert A == pytest.approx(0.5 / R, rel=1e-12) and B == pytest.approx(0.5 / R, rel=1e-12)
    r = hz.hertz(A, B, N, E_STAR)
    a = (3.0 * N * R / (4.0 * E_STAR)) ** (1.0 / 3.0)
    assert r.a == pytest.approx(a, rel=5e-3) and r.b == pytest.approx(a, rel=5e-3)
    assert r.delta == pytest.approx(a * a / R, rel=5e-3)


def test_relative_curvatures_agree_with_johnson_sum_and_difference():
    # Johnson 1985 Sec. 4.1: A + B = half the sum of the four curvatures, and |B - A| from omega
    k1x, k1y, k2x, k2y = 1 / 0.46, -1 / 0.35, 1e-6, 1 / 0.3
    for omega in (0.0, 0.2, 0.7, 1.3):
        A, B, psi = hz.relative_curvatures(k1x, k1y, k2x, k2y, omega)
        d1, d2 = k1x - k1y, k2x - k2y
        diff = 0.5 * np.sqrt(d1 ** 2 + d2 ** 2 + 2 * d1 * d2 * np.cos(2 * omega))
        assert A + B == pytest.approx(0.5 * (k1x + k1y + k2x + k2y), rel=1e-12)
        assert abs(B - A) == pytest.approx(diff, rel=1e-12)
        assert abs(psi) <= np.pi / 4 + 1e-15
    A, B, psi = hz.relative_curvatures(k1x, k1y, k2x, k2y)
    assert (A, B, psi) == pytest.approx((0.5 * (k1x + k2x), 0.5 * (k1y + k2y), 0.0))


def test_circle_has_m_equal_n_equal_one_at_theta_90():
    m, n = hz.hertz_mn(0.7, 0.7)
    assert m == pytest.approx(1.0, abs=1e-12) and n == pytest.approx(1.0, abs=1e-12)
    assert np.degrees(hz.auxiliary_angle(0.7, 0.7)) == pytest.approx(90.0)


# Timoshenko & Goodier, Theory of Elasticity, 3rd ed. (1970), Sec. 140, the table of m and n
# against theta (cos theta = (B - A)/(A + B)); printed to 3 decimals.
TG_THETA = [30, 35, 40, 45, 50, 55, 60, 65, 70, 75, 80, 85, 90]
TG_M = [2.731, 2.397, 2.136, 1.926, 1.754, 1.611, 1.486, 1.378, 1.284, 1.202, 1.128, 1.061, 1.0]
TG_N = [0.493, 0.530, 0.567, 0.604, 0.641, 0.678, 0.717, 0.759, 0.802, 0.846, 0.893, 0.944, 1.0]


def test_m_n_from_elliptic_integrals_match_timoshenko_goodier_table():
    # tolerance 3 %: printed tables are rounded and partly hand-computed (REFERENCE_DATA notes
    # 1-3 % disagreement between tables at small angles); here the worst is about 0.3 %
    A, B = _theta_curvatures(np.array(TG_THETA, dtype=float))
    m, n = hz.hertz_mn(A, B)
    np.testing.assert_allclose(m, TG_M, rtol=0.03)
    np.testing.assert_allclose(n, TG_N, rtol=0.03)
    np.testing.assert_allclose(np.degrees(hz.auxiliary_angle(A, B)), TG_THETA, rtol=1e-10)


def test_semi_axes_follow_the_curvatures_when_a_and_b_are_swapped():
    N, A, B = 7e4, 1.0 / (2 * 0.42), 1.0 / (2 * 0.3)        # wheel radius 0.42, rail crown 0.3
    r1 = hz.hertz(A, B, N, E_STAR)
    r2 = hz.hertz(B, A, N, E_STAR)
    assert r1.a > r1.b                                      # longer axis along the smaller A
    assert (r2.a, r2.b) == pytest.approx((r1.b, r1.a), rel=1e-12)
    assert (r2.m, r2.n) == pytest.approx((r1.n, r1.m), rel=1e-12)
    assert r2.a_over_b == pytest.approx(1.0 / r1.a_over_b, rel=1e-12)
    assert (r2.delta, r2.p0, r2.K_H) == pytest.approx((r1.delta, r1.p0, r1.K_H), rel=1e-12)


def test_ellipse_satisfies_hertz_equations():
    # back-substitution into Johnson 1985 Sec. 4.2 (elliptical contact) with the semi-axes found
    from scipy.special import ellipe, ellipk
    A, B, N = 1.7, 6.1, 3e4
    r = hz.hertz(A, B, N, E_STAR)
    e2 = 1.0 - (r.b / r.a) ** 2
    K, E = ellipk(e2), ellipe(e2)
    pre = r.p0 * r.b / (E_STAR * e2 * r.a ** 2)
    assert A == pytest.approx(pre * (K - E), rel=1e-9)
    assert B == pytest.approx(pre * ((r.a / r.b) ** 2 * E - K), rel=1e-9)
    assert r.delta == pytest.approx(r.p0 * r.b * K / E_STAR, rel=1e-9)
    assert N == pytest.approx(2.0 / 3.0 * np.pi * r.a * r.b * r.p0, rel=1e-12)


def test_line_contact_limit():
    # as B/A -> infinity: K(e) ~ ln(4/k) (A&S 17.3.26), so B/A ~ 1/(k^2 (ln(4/k) - 1)), k = b/a,
    # and the centre section tends to 2-D Hertz, p0 = E* b / (2 R_y) = E* B b (Johnson 1985,
    # Sec. 4.3, with R_y = 1/(2B))
    ratios = np.array([1.0, 3.0, 10.0, 1e2, 1e3, 1e4, 1e6])
    r = hz.hertz(1.0 / ratios, 1.0, 1e4, E_STAR)
    assert np.all(np.diff(r.a_over_b) > 0) and np.all(np.diff(r.m) > 0) and np.all(np.diff(r.n) < 0)
    k = 1.0 / r.a_over_b[-1]
    assert ratios[-1] * k * k * (np.log(4.0 / k) - 1.0) == pytest.approx(1.0, rel=1e-3)
    assert r.p0[-1] / (E_STAR * r.b[-1] * 1.0) == pytest.approx(1.0, rel=1e-4)


def test_force_penetration_law_inverts():
    A, B = 1.0 / (2 * 0.42), 1.0 / (2 * 0.3)
    N = np.array([1e3, 3e4, 7e4, 1.2e5])
    r = hz.hertz(A, B, N, E_STAR)
    np.testing.assert_allclose(r.K_H * r.delta ** 1.5, N, rtol=1e-12)
    np.testing.assert_allclose(hz.normal_load(r.delta, A, B, E_STAR), N, rtol=1e-12)
    np.testing.assert_allclose(hz.penetration(N, A, B, E_STAR), r.delta, rtol=1e-12)
    assert hz.normal_load(-1e-6, A, B, E_STAR) == 0.0         # no tension


@pytest.mark.parametrize("call, field", [
    (lambda: hz.hertz(1.0, 1.0, -10.0, E_STAR), "N"),
    (lambda: hz.hertz(0.0, 1.0, 10.0, E_STAR), "A"),
    (lambda: hz.hertz(1.0, -1.0, 10.0, E_STAR), "B"),
    (lambda: hz.hertz(1.0, 1.0, 10.0, 0.0), "E_star"),
    (lambda: hz.effective_modulus(2.1e11, 0.6), "nu1"),
    (lambda: hz.effective_modulus(2.1e11, 0.3, 2.1e11, -0.1), "nu2"),
    (lambda: hz.penetration(-1.0, 1.0, 1.0, E_STAR), "N"),
])
def test_bad_input_is_refused_naming_the_field(call, field):
    with pytest.raises(ParameterError, match=rf"\b{field} = "):
        call()
