"""DTRB kinematics and quasi-static load distribution against closed forms (issue 3, part)."""
import numpy as np
import pytest

from axlebox._params import ParameterError
from axlebox.bearing import frequencies
from axlebox.bearing.statics import loaddist, quasistatic, stiffness
from axlebox.bearing.models.params import BearingParams


def test_fault_orders_match_reference_table():
    """Z = 20, Db/Dm = 0.13, alpha = 10 deg (REFERENCE_DATA.md, Harris sec. 8.2 formulas)."""
    p = BearingParams(D_m=0.180, D_b=0.13 * 0.180)
    o = frequencies.orders(p, np.radians(10.0))
    assert o.FTF == pytest.approx(0.4360, abs=1e-3)
    assert o.BPFO == pytest.approx(8.7197, abs=1e-3)
    assert o.BPFI == pytest.approx(11.2803, abs=1e-3)
    assert o.BSF == pytest.approx(3.7831, abs=1e-3)


@pytest.mark.parametrize("kmh,bpfo_hz", [(48, 43.93), (40, 36.60)])
def test_paper_outer_ring_fault_frequency(kmh, bpfo_hz):
    """The paper's 43.93 Hz at 48 km/h and 36.60 Hz at 40 km/h (0.42 m wheels), within 1 %."""
    o = frequencies.orders(BearingParams())
    assert o.BPFO * frequencies.shaft_hz(kmh, 0.42) == pytest.approx(bpfo_hz, rel=0.01)


def test_paper_cage_frequency_at_48kmh():
    o = frequencies.orders(BearingParams())
    assert o.FTF * frequencies.shaft_hz(48, 0.42) == pytest.approx(2.196, rel=0.01)


def test_eq10_is_palmgren_for_steel():
    """Eq. (10)-(11) for steel on steel against delta = 3.84e-5 Q^0.9 / l^0.8 (Palmgren)."""
    E = stiffness.e_prime(2.08e11, 0.3, 2.08e11, 0.3)
    for L in (0.01, 0.04, 0.1):
        assert stiffness.k_line(E, L) == pytest.approx(stiffness.palmgren(L), rel=0.015)


def test_series_contacts_add_deflections():
    K1, K2, Q = 3e9, 5e9, 7e3
    d = (Q / K1) ** 0.9 + (Q / K2) ** 0.9
    assert stiffness.series(K1, K2) * d ** (10 / 9) == pytest.approx(Q, rel=1e-12)


def test_harris_integral_table_value():
    """Harris and Kotzalas table 7.1: J_r(0.5) = 0.2453 (line contact, n = 1.1), 0.2288 (point)."""
    assert loaddist.J_r(0.5, n=1.1) == pytest.approx(0.2453, abs=1e-4)
    assert loaddist.J_r(0.5) == pytest.approx(0.2453, rel=0.003)      # Palmgren's n = 10/9
    assert loaddist.J_r(0.5, n=1.5) == pytest.approx(0.2288, abs=1e-4)


def test_zero_clearance_radial_load_gives_stribeck_4_08():
    p = BearingParams(u_r=0.0, u_a=0.0)
    Fr = 60e3
    e = quasistatic.solve(p, (0.0, 0.0, Fr))
    ratio = e.Q.max() * p.Z * np.cos(p.alpha_o) / (Fr / 2)       # each row carries Fr / 2
    assert ratio == pytest.approx(4.08, rel=0.03)
    assert e.loaded_zone(0) <= np.pi / 2 + 1e-9                   # half the bearing at most


def test_clearance_shrinks_loaded_zone_as_harris_predicts():
    """F_row = Z Q_max J_r(eps) cos(alpha), eps from the solved ring approach (Harris eq. 7.21)."""
    Fr, eps = 60e3, []
    for u_r in (0.05e-3, 0.10e-3):
        p = BearingParams(u_r=u_r, u_a=0.0)
        e = quasistatic.solve(p, (0.0, 0.0, Fr))
        eps.append(loaddist.eps_radial(e.q[2], u_r))
        measured = (Fr / 2) / (p.Z * e.Q.max() * np.cos(p.alpha_o))
        assert measured == pytest.approx(loaddist.J_r(eps[-1]), rel=0.03)
        # the rollers that carry load all lie inside Harris's zone
        assert e.loaded_zone(0) <= np.arccos(1 - 2 * eps[-1]) + 1e-9
    assert eps[1] < eps[0] < 0.5


def test_roller_loads_balance_a_combined_load():
    """Sum of roller forces and moments, recomputed here from Q and the geometry, equals the load."""
    p = BearingParams()
    F, M = np.array([4e3, 9e3, 65e3]), np.array([800.0, -500.0])
    e = quasistatic.solve(p, F, M)
    R = 0.5 * p.D_m
    total_f, total_m = np.zeros(3), np.zeros(3)
    for j, (s, y) in enumerate(((1, -p.row_offset), (-1, p.row_offset))):
        for k, psi in enumerate(e.psi):
            er = np.array([np.sin(psi), 0.0, np.cos(psi)])
            n = np.cos(p.alpha_o) * er + s * np.sin(p.alpha_o) * np.array([0, 1.0, 0])
            f = e.Q[j, k] * n
            total_f += f
            total_m += np.cross(R * er + np.array([0, y, 0]), f)
    np.testing.assert_allclose(total_f, F, rtol=1e-6, atol=1e-6 * np.linalg.norm(F))
    np.testing.assert_allclose(total_m[[0, 2]], M, rtol=1e-6, atol=1e-6 * np.linalg.norm(F) * R)
    assert e.Q[0].sum() > e.Q[1].sum()     # +y load goes to row 1 (s = +1)


@pytest.mark.parametrize("kw,field", [({"u_r": -1e-5}, "u_r"), ({"Z": 2}, "Z"), ({"Z": 20.5}, "Z"),
                                      ({"D_b": 0.1}, "D_b"), ({"Z": 40}, "Z")])
def test_bad_bearing_parameters_are_named(kw, field):
    with pytest.raises(ParameterError, match=field):
        BearingParams(**kw)


def test_bad_speed_is_named():
    with pytest.raises(ParameterError, match="speed"):
        frequencies.shaft_hz(0.0)
