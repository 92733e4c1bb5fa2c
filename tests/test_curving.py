"""The car on a curve (issue 69) against the closed forms of quasi-static curving.

The runs: the validation car (rigid bodies on row bushings, smooth rigid track: what curving
asks of the car, not of the bearings) from tangent track through a 30 m transition into a 300 m
curve at 48 km/h, the forces read once the whole car has been in the circular part for 1.8 s."""
import numpy as np
import pytest

from axlebox.mbs.track.line import G, unbalanced_acceleration
from axlebox.mbs.wheelrail.element_kernel import OUT_F
from axlebox.pipelines import simulate as ps

R = 300.0
V = 48.0 / 3.6
DURATION, STEADY = 7.0, 5.2          # s; the rear wheelset is in the circular part from 3.7 s


def _layout(hand, h):
    return [{"kind": "tangent", "length": 20.0}, {"kind": "transition", "length": 30.0},
            {"kind": "curve", "length": 200.0, "radius": R, "hand": hand, "superelevation": h}]


def _run(hand, h, duration=DURATION):
    over = {"joint": {"model": "bushing"}, "coupling": {"exchange_dt": 0.0}, "defects": [],
            "bodies": {"flexible": []},
            "track": {"irregularity": False, "layout": _layout(hand, h), "start": 14.0},
            "integrator": {"method": "leapfrog", "dt": 2e-5, "output_rate_hz": 1000.0},
            "sensors": {"model": "ideal"}}
    cfg = ps.load_config("validation_48kmh", duration, over)
    model, y0 = ps.build_model(cfg, log=lambda *_: None)
    run = ps.integrate.simulate(model, duration, cfg.settings(), y0=y0)
    assert run.ok, run.message
    return cfg, model, run


def _sum_Y(run):
    """The sum over the eight wheels of the lateral force on the wheel in its track plane (each
    wheel's own frame at its contact), averaged over the steady part, N."""
    k = run.time >= STEADY
    return float(run.wheels[k, :, OUT_F + 1].sum(1).mean())


@pytest.fixture(scope="module")
def left_unbalanced():
    h = 0.015                          # 15 mm cant: 0.49 m/s^2 unbalanced at 48 km/h
    return h, _run("left", h)


def test_the_wheels_lateral_forces_carry_the_unbalanced_acceleration(left_unbalanced):
    """Quasi-static curving: in the track plane the rails' lateral forces on the wheels hold the
    car's mass times the lateral acceleration the cant leaves unbalanced, ``a = (v^2 / R)
    cos(phi) - g sin|phi|`` (about ``v^2 / R - g h / s``; EN 13803 and Wickens, *Fundamentals of
    Rail Vehicle Dynamics*, 2003, sec. 6.1), within 1 %; towards the curve's centre (+y in a
    left-hand curve)."""
    h, (cfg, model, run) = left_unbalanced
    M = sum(b.mass for b in model.bodies)
    s0 = model.S.line[1]                           # the contact lines' distance the cant is over
    a = float(unbalanced_acceleration(V, 1.0 / R, -np.arcsin(h / s0)))
    assert 0.45 < a < 0.55
    assert _sum_Y(run) == pytest.approx(M * a, rel=0.01)
    # the outer (right) wheels carry more than the inner ones
    Q = run.wheels[run.time >= STEADY, :, OUT_F + 2].mean(0)
    assert (Q[1::2] > Q[0::2] + 5e3).all()


def test_at_the_equilibrium_speed_the_lateral_forces_cancel():
    """At ``v_eq = sqrt(g R tan|phi|)`` (about ``sqrt(g h R / s)``) nothing is left unbalanced:
    the wheels' lateral forces sum to about zero (within 5 % of the 0.5 m/s^2 case's, what the
    bogies' own steering forces and the last of the transient leave); a right-hand curve."""
    s0 = 1.5
    h = s0 * np.sin(np.arctan(V * V / (G * R)))          # the cant that makes 48 km/h v_eq
    cfg, model, run = _run("right", h)
    M = sum(b.mass for b in model.bodies)
    assert abs(_sum_Y(run)) < 0.05 * M * 0.5


def _free_wheelset(R, V, gamma=0.05):
    """A rigid wheelset of 1:20 cones on 40 mm crowns, loaded by 60 kN at its axle, alone on a
    curve of radius R whose cant balances V; the steady running of the statics (issue 69: the
    wheelset at rest on its track frame, spin free)."""
    from axlebox.mbs.solver.body import rigid
    from axlebox.mbs.solver.elements import Load
    from axlebox.mbs.solver.system import System
    from axlebox.mbs.track.line import Line, Segment
    from axlebox.mbs.vehicle.statics import equilibrium
    from axlebox.mbs.wheelrail.element import WheelRailParams, build_tables
    from axlebox.mbs.wheelrail.element_kernel import COL_C0Z, COL_KH, COL_PZ, P_L0
    from axlebox.mbs.wheelrail.geometry import TrackLayout
    from axlebox.mbs.wheelrail.profile import Profile
    y = np.linspace(-0.07, 0.07, 701)
    wheel = Profile(y=y, z=gamma * y, kind="wheel", name="cone 1:20")
    yr = np.linspace(-0.036, 0.036, 721)
    rail = Profile(y=yr, z=-(0.04 - np.sqrt(0.04 ** 2 - yr ** 2)), kind="rail", name="R40 crown")
    tab = build_tables(wheel, rail, TrackLayout(r0=0.46, cant=0.0), WheelRailParams(law="kalker"),
                       cache=False)
    ic = tab.tab.shape[0] // 2
    l0, r0 = float(tab.par[P_L0]), 0.46
    F = 60e3 + 1500 * G
    z = float(tab.tab[ic, COL_C0Z]) - (0.5 * F / float(tab.tab[ic, COL_KH])) ** (2 / 3)
    h = 2 * l0 * np.sin(np.arctan(V * V / (G * R)))
    s = System(speed=V)
    s.set_wheel_rail(tab.tab, tab.par)
    s.add_body(rigid("ws", 1500.0, (800.0, 100.0, 800.0), spin=True), r=(0.0, 0.0, z),
               v=(V, 0.0, 0.0), omega=(0.0, V / (z - float(tab.tab[ic, COL_PZ])), 0.0))
    for name, sg in (("L", 1.0), ("R", -1.0)):
        s.wheel(name, s.marker("ws", at=(0.0, sg * l0, -r0)), 0 if sg > 0 else 1, r0)
    s.add(Load("axle load", s.marker("ws"), force=(0.0, 0.0, -60e3)))
    s.on_line(Line([Segment("curve", 500.0, radius=R, hand="left", superelevation=h)],
                   s0=2 * l0), 100.0)
    model = s.assemble()
    yq = equilibrium(model, tol=1e-9)
    return model, yq, tab


def test_a_free_wheelset_rolls_at_redtenbachers_offset():
    """Pure rolling on a curve (Redtenbacher, 1855; Wickens 2003, sec. 6.2): a wheelset of
    conicity lambda rolls without creep where its rolling radii differ as the rails' lengths do,
    at the offset ``y0 = r0 b / (lambda R)`` outwards, radial (no yaw): within 2 %.  ``b`` is
    half the distance of the contact points, ``r0`` the mean rolling radius and ``lambda`` the
    pair's conicity at the offset, ``(r_out - r_in) / 2 y`` where it rolls (a 1:20 cone on a
    crowned rail is linear to 5 %: the wheelset's roll moves the contacts)."""
    from axlebox.mbs.wheelrail.element_kernel import COL_R, OUT_P, OUT_R, OUT_XI
    R, V = 1500.0, 10.0
    model, y, tab = _free_wheelset(R, V)
    st = model.body_state(0, y)
    model.rhs(0.0, y)
    out = model.W.whout
    # a left-hand curve: outwards is to the right (-y); the wheelset's offset on its frame, the
    # rolling radii and contact points where it rolls
    off = -st["r"][1]
    r_in, r_out = out[0, OUT_R], out[1, OUT_R]
    b, r0 = 0.5 * (out[0, OUT_P + 1] - out[1, OUT_P + 1]), 0.5 * (r_in + r_out)
    lam = (r_out - r_in) / (2 * off)
    lam_linear = abs(np.polyfit(tab.u[np.abs(tab.u) < 1e-3],
                                (tab.column(COL_R, 0) - tab.column(COL_R, 1))[np.abs(tab.u) < 1e-3],
                                1)[0]) / 2
    assert lam == pytest.approx(lam_linear, rel=0.05) and lam == pytest.approx(0.05, rel=0.05)
    y0 = r0 * b / (lam * R)
    assert y0 > 3e-3
    assert off == pytest.approx(y0, rel=0.02)
    assert abs(st["A"][1, 0]) < 1e-2 * y0 / b               # radial: yaw well under y0 / b
    # pure rolling: no longitudinal creep left, against the b / R a wheelset centred would have
    assert np.abs(out[:2, OUT_XI]).max() < 1e-2 * b / R
