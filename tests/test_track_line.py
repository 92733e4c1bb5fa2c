"""The line's design geometry (mbs/track/line.py) against closed forms: a clothoid's plan view
against Fresnel's integrals, an arc against its circle, the quasi-static curving formulas against
the worked example of EN 13803's cant deficiency; and every bad layout refused in one line."""
import math

import numpy as np
import pytest
from scipy.special import fresnel

from axlebox._params import ParameterError
from axlebox.mbs.track.line import (Line, Segment, cant_deficiency, equilibrium_speed,
                                    frame_motion, unbalanced_acceleration)

R, H, LT, LC = 300.0, 0.12, 80.0, 150.0


def s_curve(hand="left"):
    """Tangent, transition, a 300 m curve with 120 mm cant, transition, tangent."""
    return Line([Segment("tangent", 50.0), Segment("transition", LT),
                 Segment("curve", LC, radius=R, hand=hand, superelevation=H, widening=0.005),
                 Segment("transition", LT), Segment("tangent", 50.0)])


def test_a_transition_is_a_clothoid_fresnel():
    """From the tangent, curvature k1 u: x = sqrt(pi / k1) C(u sqrt(k1 / pi)), y = ... S(...)
    (the clothoid in Fresnel's integrals; Abramowitz and Stegun 7.3)."""
    line = s_curve()
    k1 = 1.0 / (R * LT)
    u = np.linspace(0.0, LT, 41)
    S, C = fresnel(u * math.sqrt(k1 / math.pi))
    xy = line.xy(50.0 + u)
    a = math.sqrt(math.pi / k1)
    np.testing.assert_allclose(xy[0], 50.0 + a * C, rtol=0, atol=1e-9)
    np.testing.assert_allclose(xy[1], a * S, rtol=0, atol=1e-9)
    g = line.at(50.0 + u)
    np.testing.assert_allclose(g.kappa, k1 * u, rtol=0, atol=1e-15)         # linear in s
    np.testing.assert_allclose(g.psi, 0.5 * k1 * u * u, rtol=0, atol=1e-15)
    np.testing.assert_allclose(g.e, H * u / LT, rtol=0, atol=1e-15)         # cant linear too
    np.testing.assert_allclose(g.widening, 0.005 * u / LT, rtol=0, atol=1e-15)


@pytest.mark.parametrize("hand", ["left", "right"])
def test_the_curve_is_an_arc_of_its_radius(hand):
    """Every point of the circular part lies R from one centre, which stands R from its start
    along the normal to the left (right) of the heading there; the heading turns by L / R."""
    line = s_curve(hand)
    sign = 1.0 if hand == "left" else -1.0
    s = 50.0 + LT + np.linspace(0.0, LC, 31)
    p = line.xy(s)
    g0 = line.at(s[0])
    centre = p[:, 0] + sign * R * np.array([-math.sin(g0.psi), math.cos(g0.psi)])
    np.testing.assert_allclose(np.hypot(*(p - centre[:, None])), R, rtol=0, atol=1e-9)
    g = line.at(s)
    np.testing.assert_allclose(g.psi - g0.psi, sign * (s - s[0]) / R, rtol=0, atol=1e-13)
    np.testing.assert_allclose(g.kappa, sign / R, rtol=0, atol=1e-15)
    np.testing.assert_allclose(np.sin(g.phi), -sign * H / 1.5, rtol=0, atol=1e-15)
    # the whole line is symmetric: the exit tangent's heading is the entry's turned by the total
    total = sign * (LC / R + LT / R)
    assert line.at(line.length).psi == pytest.approx(total, abs=1e-13)


def test_the_line_is_smooth_where_segments_meet():
    """Position and heading continuous at every join (C1 plan view), curvature and cant
    continuous (the clothoid's point)."""
    line = s_curve()
    for s in line.starts[1:-1]:
        a, b = line.at(s - 1e-7), line.at(s + 1e-7)
        assert abs(a.psi - b.psi) < 1e-9 and abs(a.kappa - b.kappa) < 1e-9 and abs(a.e - b.e) < 1e-9
        assert np.max(np.abs(line.xy(s - 1e-7) - line.xy(s + 1e-7))) < 1e-6


def test_a_reverse_curve_passes_through_zero():
    """A left curve into a right one through one transition: curvature and cant pass through zero
    together, linearly."""
    line = Line([Segment("curve", 50.0, radius=300.0, hand="left", superelevation=0.1),
                 Segment("transition", 60.0),
                 Segment("curve", 50.0, radius=600.0, hand="right", superelevation=0.05)])
    g = line.at(np.array([50.0, 80.0, 110.0]))
    np.testing.assert_allclose(g.kappa, [1 / 300, 0.5 * (1 / 300 - 1 / 600), -1 / 600], atol=1e-15)
    np.testing.assert_allclose(g.e, [0.1, 0.025, -0.05], atol=1e-15)
    np.testing.assert_allclose(g.dkappa[1], (-1 / 600 - 1 / 300) / 60.0, rtol=1e-12)


def test_quasi_static_curving_closed_forms():
    """R 300 m, h 120 mm, s0 1.5 m, 60 km/h: a = v^2/R - g h/s0 = 0.141 m/s^2 (small angle),
    v_eq = sqrt(g h R / s0) = 55.2 km/h, cant deficiency s0 v^2 / (g R) - h = 21.6 mm (EN 13803's
    definition).  The exact forms differ from the small-angle ones by the roll's cosine and
    tangent only."""
    v = 60 / 3.6
    phi = -math.asin(H / 1.5)
    a = float(unbalanced_acceleration(v, 1 / R, phi))
    assert v * v / R - 9.81 * H / 1.5 == pytest.approx(0.141, abs=5e-4)
    assert a == pytest.approx(v * v / R * math.cos(phi) - 9.81 * H / 1.5, rel=1e-12)
    assert float(unbalanced_acceleration(v, -1 / R, -phi)) == pytest.approx(a, rel=1e-12)
    veq = equilibrium_speed(R, H)
    assert math.sqrt(9.81 * H * R / 1.5) * 3.6 == pytest.approx(55.2, abs=0.05)
    assert veq == pytest.approx(math.sqrt(9.81 * H * R / 1.5), rel=phi * phi)
    assert float(unbalanced_acceleration(veq, 1 / R, phi)) == pytest.approx(0.0, abs=1e-12)
    assert cant_deficiency(v, R, H) * 1e3 == pytest.approx(21.6, abs=0.05)


def test_tangent_track_is_one_straight_segment():
    line = Line([])
    assert line.tangent and line.length == 1e5
    g = line.at(np.array([0.0, 5e4]))
    assert not np.any(g.kappa) and not np.any(g.phi) and not np.any(g.psi)


@pytest.mark.parametrize("layout, message", [
    ([Segment("tangent", 50.0), Segment("curve", 100.0, radius=300.0, superelevation=0.1)],
     "track.layout[1] (curve) is not allowed straight after track.layout[0] (tangent): the cant "
     "would step by 0.1 m; put a kind = 'transition' between them"),
    ([Segment("tangent", 50.0), Segment("transition", 30.0), Segment("transition", 30.0)],
     "track.layout[2].kind = 'transition' is not allowed after another transition"),
    ([Segment("tangent", 50.0), Segment("tangent", 50.0, start=60.0)],
     "track.layout[1].start = 60 is not allowed: it leaves a gap of 10 m after track.layout[0], "
     "which ends at 50 m"),
    ([Segment("tangent", 50.0), Segment("tangent", 50.0, start=45.0)],
     "track.layout[1].start = 45 is not allowed: it leaves an overlap of 5 m"),
])
def test_bad_layouts_are_refused_in_one_line(layout, message):
    with pytest.raises(ParameterError) as err:
        Line(layout)
    assert str(err.value).startswith(message) and "\n" not in str(err.value)


@pytest.mark.parametrize("table, message", [
    ({"kind": "tangent", "length": 50.0, "radius": 300.0},
     "track.layout[3].radius is not a field of a tangent segment: expected one of kind, length, "
     "start"),
    ({"kind": "curve", "length": 50.0, "radius": 20.0},
     "track.layout[3].radius = 20.0 is not allowed: expected a number in [50, 100000] m"),
    ({"kind": "curve", "length": 50.0, "superelevation": 0.25},
     "track.layout[3].superelevation = 0.25 is not allowed: expected a number in [0, 0.18] m"),
    ({"kind": "bend"}, "track.layout[3].kind = 'bend' is not allowed: expected one of tangent, "
     "transition, curve"),
    ({"kind": "curve", "lenght": 5.0}, "track.layout[3].lenght is not a field of a curve segment: "
     "expected one of kind, length, start, radius, hand, superelevation, widening"),
])
def test_bad_segments_are_refused_in_one_line(table, message):
    with pytest.raises(ParameterError) as err:
        Segment.from_table(table, "track.layout[3]")
    assert str(err.value).startswith(message), str(err.value)


def test_a_position_off_the_line_is_refused():
    with pytest.raises(ParameterError, match=r"track position .* the line runs from 0 to 410 m"):
        s_curve().at(411.0)


def test_segments_round_trip_through_their_tables():
    line = s_curve()
    again = Line([Segment.from_table(t, f"track.layout[{i}]") for i, t in enumerate(line.to_tables())])
    assert again.segments == line.segments


@pytest.mark.parametrize("s_mid, hand", [(90.0, "left"), (90.0, "right"), (200.0, "left"), (370.0, "right")])
def test_the_frame_motion_is_the_derivative_of_the_frame(s_mid, hand):
    """The track frame carried along the line at s(t) = s_mid + v t + vdot t^2 / 2: its angular
    velocity (A^T dA/dt), angular acceleration and origin acceleration (A^T d^2 O / dt^2) by
    central differences of :meth:`Line.frame` agree with the closed forms of :func:`frame_motion`
    (in the transitions, where curvature and cant change, as in the curve)."""
    line, v, vdot, h = s_curve(hand), 15.0, 0.8, 0.01

    def frame(t):
        return line.frame(s_mid + v * t + 0.5 * vdot * t * t)

    def omega(t, dt=1e-3):
        (_, a), (_, b) = frame(t - dt), frame(t + dt)
        _, A = frame(t)
        W = A.T @ (b - a) / (2 * dt)
        return np.array([W[2, 1], W[0, 2], W[1, 0]])

    O = [frame(t)[0] for t in (-h, 0.0, h)]
    _, A = frame(0.0)
    m = frame_motion(line.at(s_mid), line.s0, v, vdot)
    np.testing.assert_allclose(omega(0.0), m.omega, rtol=1e-5, atol=1e-9)
    np.testing.assert_allclose((omega(h) - omega(-h)) / (2 * h), m.alpha, rtol=1e-3, atol=1e-7)
    np.testing.assert_allclose(A.T @ (O[2] - 2 * O[1] + O[0]) / h ** 2, m.a0, rtol=1e-5, atol=1e-7)
    np.testing.assert_allclose(m.gravity, A.T @ np.array([0.0, 0.0, -9.81]), rtol=0, atol=1e-15)


def _car_on(radius, h, speed_kmh=48.0):
    from axlebox.pipelines import simulate as ps
    layout = [{"kind": "tangent", "length": 20.0}, {"kind": "transition", "length": 30.0},
              {"kind": "curve", "length": 200.0, "radius": radius, "superelevation": h}]
    return ps.load_config("validation_48kmh", 1.0, {"run": {"speed_kmh": speed_kmh},
                                                     "track": {"layout": layout, "start": 15.0}})


@pytest.mark.parametrize("radius, h, speed, message", [
    (120.0, 0.12, 30.0, "track.layout[2].radius = 120 is not allowed for this car: expected at least "
     "150 m, the smallest radius a B-type metro car's bogies and couplers are built for "
     "(GB 50157-2013, Table 6.2.2"),
    (300.0, 0.015, 80.0, "track.layout[2] at 80 km/h is not allowed: its cant deficiency would be "
     "237 mm (1.55 m/s^2 unbalanced); expected at most 150 mm (EN 13803:2017's largest limit)"),
])
def test_a_curve_the_car_cannot_take_is_refused_in_one_line(radius, h, speed, message):
    """Issue 69, item 7: a radius below what the car is built for, and a cant deficiency beyond
    the published limit at the run's highest speed; the limits each name their source."""
    with pytest.raises(ParameterError) as err:
        _car_on(radius, h, speed)
    assert str(err.value).startswith(message), str(err.value)
    assert "\n" not in str(err.value)
    _car_on(150.0, 0.12, 30.0)                        # at the limits: accepted
    _car_on(300.0, 0.015, 48.0)
