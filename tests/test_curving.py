"""The car on a curve (issue 69) against the closed forms of quasi-static curving.

The runs: the validation car (rigid bodies on row bushings, smooth rigid track: what curving
asks of the car, not of the bearings) on a 300 m curve at 48 km/h.  Full size (AXLEBOX_FULL=1):
from tangent track through a 30 m transition into the curve, the forces read once the whole car
has been in the circular part for 1.8 s.  In CI (the slow marker's smaller size) the car starts in
the circular part, where the statics set it at rest on its track frames, and runs 1 s: the
steady state the long run reaches, without its 6 s of approach."""
import numpy as np
import pytest
from conftest import full_size

from axlebox.mbs.track.line import G, unbalanced_acceleration
from axlebox.mbs.wheelrail.element_kernel import OUT_CLAMP, OUT_F
from axlebox.pipelines import simulate as ps

R = 300.0
V = 48.0 / 3.6
# s: the run, and where its steady part begins (full size: the rear wheelset is in the circular
# part from 3.7 s); m: the front bogie's centre at the start (small: the rear wheelset 56 m on,
# 6 m into the curve)
DURATION, STEADY, START = (7.0, 5.2, 14.0) if full_size() else (1.0, 0.5, 70.0)


def _layout(hand, h):
    return [{"kind": "tangent", "length": 20.0}, {"kind": "transition", "length": 30.0},
            {"kind": "curve", "length": 200.0, "radius": R, "hand": hand, "superelevation": h}]


def _run(hand, h, over=None):
    cfg = ps.load_config("validation_48kmh", DURATION, _overrides(hand, h, over))
    model, y0 = ps.build_model(cfg, log=lambda *_: None)
    run = ps.integrate.simulate(model, DURATION, cfg.settings(), y0=y0)
    assert run.ok, run.message
    return cfg, model, run


def _overrides(hand, h, over=None):
    base = {"joint": {"model": "bushing"}, "coupling": {"exchange_dt": 0.0}, "defects": [],
            "bodies": {"flexible": []},
            "track": {"irregularity": False, "layout": _layout(hand, h), "start": START},
            "integrator": {"method": "leapfrog", "dt": 2e-5, "output_rate_hz": 1000.0},
            "sensors": {"model": "ideal"}}
    for name, fields in (over or {}).items():
        base[name] = {**base.get(name, {}), **fields} if isinstance(fields, dict) else fields
    return base


def _sum_Y(run):
    """The sum over the eight wheels of the lateral force on the wheel in its track plane (each
    wheel's own frame at its contact), averaged over the steady part, N."""
    k = run.time >= STEADY
    return float(run.wheels[k, :, OUT_F + 1].sum(1).mean())


@pytest.fixture(scope="module")
def left_unbalanced():
    h = 0.015                          # 15 mm cant: 0.49 m/s^2 unbalanced at 48 km/h
    return h, _run("left", h)


@pytest.mark.slow
def test_the_wheels_lateral_forces_carry_the_unbalanced_acceleration(left_unbalanced):
    """Quasi-static curving: in the track plane the rails' lateral forces on the wheels hold the
    car's mass times the lateral acceleration the cant leaves unbalanced, ``a = (v^2 / R)
    cos(phi) - g sin|phi|`` (about ``v^2 / R - g h / s``; EN 13803 and Wickens, *Fundamentals of
    Rail Vehicle Dynamics*, 2003, sec. 6.1), within 1 %; towards the curve's centre (+y in a
    left-hand curve).  No wheel leaves its contact table (the S1002 / 60E1 pair's 12 mm on
    either side holds the 300 m curve's flange contact)."""
    h, (cfg, model, run) = left_unbalanced
    M = sum(b.mass for b in model.bodies)
    s0 = model.S.line[1]                           # the contact lines' distance the cant is over
    a = float(unbalanced_acceleration(V, 1.0 / R, -np.arcsin(h / s0)))
    assert 0.45 < a < 0.55
    assert _sum_Y(run) == pytest.approx(M * a, rel=0.01)
    # the outer (right) wheels carry more than the inner ones
    Q = run.wheels[run.time >= STEADY, :, OUT_F + 2].mean(0)
    assert (Q[1::2] > Q[0::2] + 5e3).all()
    assert run.wheels[:, :, OUT_CLAMP].max() == 0.0


@pytest.mark.slow
def test_flange_climb_stays_below_nadals_limit_on_the_300m_curve(left_unbalanced, tmp_path):
    """Flange climb (Nadal, 1908; EN 14363:2016 5.6.2.2): every wheel's Y/Q below ``(tan delta -
    mu) / (1 + mu tan delta)`` at the wheel profile's flange angle and the config's friction, in
    the result file and the report's curving table, which says by how much."""
    from axlebox.pipelines import curving
    h, (cfg, model, run) = left_unbalanced
    path = ps.write(tmp_path / "curve.h5", run, model, cfg)
    table = curving.table(path)
    nadal = table.nadal
    assert 1.0 < nadal < 1.5                       # S1002: 70 deg flange, mu 0.3-0.36: 1.2-1.34
    worst = max(w.YQ_max for w in table.wheels)
    assert 0.0 < worst < nadal
    assert table.nadal_margin == pytest.approx(1.0 - worst / nadal)
    # the leading wheelset's outer (right) wheel is the one nearest to climbing
    assert max(table.wheels, key=lambda w: w.YQ_max).name == "ws1_R"
    page = curving.table_html(table)
    assert f"{100 * table.nadal_margin:.0f} % below it" in page and page.count("<tr>") == 8 + 4 + 2
    assert "largest Y/Q" in curving.summary(table)
    assert curving.figure(path, tmp_path / "along.png").stat().st_size > 20e3


@pytest.mark.slow
def test_at_the_equilibrium_speed_the_lateral_forces_cancel():
    """At ``v_eq = sqrt(g R tan|phi|)`` (about ``sqrt(g h R / s)``) nothing is left unbalanced:
    the wheels' lateral forces sum to about zero (within 5 % of the 0.5 m/s^2 case's, what the
    bogies' own steering forces and the last of the transient leave); a right-hand curve."""
    s0 = 1.5
    h = s0 * np.sin(np.arctan(V * V / (G * R)))          # the cant that makes 48 km/h v_eq
    cfg, model, run = _run("right", h)
    M = sum(b.mass for b in model.bodies)
    assert abs(_sum_Y(run)) < 0.05 * M * 0.5


def _cone_on_crowns(gamma=0.05, y_max=None):
    """Tables of wheels of cones ``gamma`` on rails of 40 mm crowns, r0 0.46 m, the Kalker linear
    law; with the contacts' half distance ``l0`` and ``r0``."""
    from axlebox.mbs.wheelrail.element import WheelRailParams, build_tables
    from axlebox.mbs.wheelrail.element_kernel import P_L0
    from axlebox.mbs.wheelrail.geometry import TrackLayout
    from axlebox.mbs.wheelrail.profile import Profile
    y = np.linspace(-0.07, 0.07, 701)
    wheel = Profile(y=y, z=gamma * y, kind="wheel", name="cone 1:20")
    yr = np.linspace(-0.036, 0.036, 721)
    rail = Profile(y=yr, z=-(0.04 - np.sqrt(0.04 ** 2 - yr ** 2)), kind="rail", name="R40 crown")
    params = WheelRailParams(law="kalker", **({} if y_max is None else {"y_max": y_max}))
    tab = build_tables(wheel, rail, TrackLayout(r0=0.46, cant=0.0), params, cache=False)
    return tab, float(tab.par[P_L0]), 0.46


def _rolling(tab, F):
    """A centred wheelset's height on its rails under the wheelset load ``F`` (N; Hertz's
    approach at each wheel), and its axle's height over the contacts (the spin's radius)."""
    from axlebox.mbs.wheelrail.element_kernel import COL_C0Z, COL_KH, COL_PZ
    ic = tab.tab.shape[0] // 2
    z = float(tab.tab[ic, COL_C0Z]) - (0.5 * F / float(tab.tab[ic, COL_KH])) ** (2 / 3)
    return z, z - float(tab.tab[ic, COL_PZ])


def _balanced_curve(R, V, l0):
    """A 500 m left-hand curve of radius R whose cant balances V."""
    from axlebox.mbs.track.line import Line, Segment
    h = 2 * l0 * np.sin(np.arctan(V * V / (G * R)))
    return Line([Segment("curve", 500.0, radius=R, hand="left", superelevation=h)], s0=2 * l0)


def _free_wheelset(R, V, gamma=0.05, push=0.0):
    """A rigid wheelset of 1:20 cones on 40 mm crowns, loaded by 60 kN at its axle, alone on a
    curve of radius R whose cant balances V; the steady running of the statics (issue 69: the
    wheelset at rest on its track frame, spin free); ``push``: a lateral force at its axle too,
    N (after the statics: the statics hold it without)."""
    from axlebox.mbs.solver.body import rigid
    from axlebox.mbs.solver.elements import Load
    from axlebox.mbs.solver.system import System
    from axlebox.mbs.vehicle.statics import equilibrium
    tab, l0, r0 = _cone_on_crowns(gamma)
    z, rho = _rolling(tab, 60e3 + 1500 * G)
    s = System(speed=V)
    s.set_wheel_rail(tab.tab, tab.par)
    s.add_body(rigid("ws", 1500.0, (800.0, 100.0, 800.0), spin=True), r=(0.0, 0.0, z),
               v=(V, 0.0, 0.0), omega=(0.0, V / rho, 0.0))
    for name, sg in (("L", 1.0), ("R", -1.0)):
        s.wheel(name, s.marker("ws", at=(0.0, sg * l0, -r0)), 0 if sg > 0 else 1, r0)
    s.add(Load("axle load", s.marker("ws"), force=(0.0, 0.0, -60e3)))
    if push:
        s.add(Load("push", s.marker("ws"), force=(0.0, push, 0.0)))
    s.on_line(_balanced_curve(R, V, l0), 100.0)
    model = s.assemble()
    yq = equilibrium(model, tol=1e-9) if not push else model.y0
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


def test_a_wheelset_pushed_off_its_rails_stops_the_run_as_derailed():
    """Flange climb or derailment is a failed computation (issue 69, item 7): a wheelset pushed
    sideways by a force of its axle load's size leaves the lateral range its contact was computed
    for; the run stops there, status "derailed", naming the wheel, with every output up to the
    one that showed it kept and finite (never extrapolated contact, never non-finite numbers)."""
    from axlebox.mbs.solver.integrate import Settings, simulate
    from axlebox.mbs.wheelrail.element_kernel import CLAMP_FLANGE, OUT_CLAMP
    model, y, _ = _free_wheelset(1500.0, 10.0, push=60e3)
    run = simulate(model, 0.5, Settings(method="rk4", dt=2e-5, output_rate_hz=2000.0), y0=y)
    assert run.status == "derailed" and not run.ok
    assert "left its contact table" in run.message and "flange climb" in run.message
    assert any(repr(name) in run.message for name in model.wheel_names)
    assert 0.0 < run.time[-1] < 0.5
    assert np.isfinite(run.wheels).all() and np.isfinite(run.states).all()
    assert run.wheels[-1, :, OUT_CLAMP].max() == CLAMP_FLANGE and run.wheels[:-1, :, OUT_CLAMP].max() == 0.0


@pytest.mark.slow
def test_the_axle_boxes_carry_the_wheelsets_net_lateral_force():
    """Quasi-static curving of a wheelset on its two DTRBs (issue 69, 5d; Newton's second law in
    the track frame, Shabana, Zaazaa and Sugiyama 2008, ch. 4): the two bearings' axial loads on
    their outer rings sum to the wheelset's net lateral wheel-rail force less its own inertial
    force in the track plane, ``sum Y - m a`` with ``a`` the unbalanced lateral acceleration,
    within 1 % over the steady part (no gearbox: the gear's bearing would be a third path).  Each
    bearing's rows' axial loads (the result's row outputs) sum to its ring load within 2 % (they
    are the exchange's last evaluation, the ring load the exchange's mean)."""
    from axlebox.mbs.kernel import bearings as kb
    from axlebox.mbs.kernel.wheels import WH_BODY
    h, T, t0 = 0.015, 0.4, 0.2
    over = {"joint": {"model": "dtrb", "wheelsets": [1]}, "gearbox": {"mass": 0.0},
            "integrator": {"method": "imex", "dt": 5e-6, "output_rate_hz": 10000.0},
            "coupling": {"exchange_dt": 1e-5}}
    cfg = ps.load_config("validation_48kmh", T, _overrides("left", h, over) | {"track": {
        "irregularity": False, "layout": _layout("left", h), "start": 70.0}})
    model, y0 = ps.build_model(cfg, log=lambda *_: None)
    run = ps.integrate.simulate(model, T, cfg.settings(), y0=y0)
    assert run.ok, run.message
    k = run.time >= t0
    b = [i for i, bd in enumerate(model.bodies) if bd.name == "ws1"][0]
    wheels = [w for w in range(len(model.wheel_names)) if model.S.wh_i[w, WH_BODY] == b]
    sum_Y = run.wheels[k][:, wheels, OUT_F + 1].sum(1).mean()
    a = float(unbalanced_acceleration(V, 1.0 / R, -np.arcsin(h / model.S.line[1])))
    net = sum_Y - model.bodies[b].mass * a
    axial = run.bearings[k][:, :, kb.BR_OUTER, 1].sum(1).mean()
    assert abs(net) > 2e3                          # the leading wheelset steers the car: kN
    assert axial == pytest.approx(net, rel=0.01)
    rows = run.bearings[k][:, :, kb.BR_ROW, [kb.BR_AXIAL, kb.BR_AXIAL + 1]].sum(2).mean(0)
    np.testing.assert_allclose(rows, run.bearings[k][:, :, kb.BR_OUTER, 1].mean(0), rtol=0.02)


KY = 2e6                # N/m: the bogie's primary springs' lateral stiffness, each


def _bogie(kx, R, V, a=1.25, b1=1.0, ky=KY):
    """A two-axle bogie alone on a curve of radius R whose cant balances V: a 2 t frame carrying
    100 kN (in its mass), on two rigid wheelsets of 1:20 cones on 40 mm crowns (:func:`_free_wheelset`'s pair,
    the Kalker linear law) at ``+-a``, each held by two primary springs at ``+-b1`` of
    longitudinal stiffness ``kx`` and lateral ``ky`` (the wheelset's yaw stiffness ``k_psi = 2
    kx b1^2``); the steady running of the statics."""
    from axlebox.mbs.solver.body import rigid
    from axlebox.mbs.solver.elements import Bushing
    from axlebox.mbs.solver.system import System
    from axlebox.mbs.vehicle.statics import equilibrium
    tab, l0, r0 = _cone_on_crowns(y_max=0.02)
    z, rho = _rolling(tab, 0.5 * (100e3 + 2000 * G) + 1500 * G)
    s = System(speed=V)
    s.set_wheel_rail(tab.tab, tab.par)
    # the frame's load as its mass (a dead load would miss its centrifugal force: 0.8 kN)
    s.add_body(rigid("frame", 2000.0 + 100e3 / G, (9000.0, 6000.0, 15000.0)),
               r=(0.0, 0.0, z + 0.2), v=(V, 0.0, 0.0))
    spin = V / rho
    for i, x in ((1, a), (2, -a)):
        ws = f"ws{i}"
        s.add_body(rigid(ws, 1500.0, (800.0, 100.0, 800.0), spin=True), r=(x, 0.0, z),
                   v=(V, 0.0, 0.0), omega=(0.0, spin, 0.0))
        for name, sg in (("L", 1.0), ("R", -1.0)):
            s.wheel(f"{ws}_{name}", s.marker(ws, at=(0.0, sg * l0, -r0)), 0 if sg > 0 else 1, r0)
            s.add(Bushing(f"primary{i}{name}", s.marker("frame", at=(x, sg * b1, -0.2)),
                          s.marker(ws, at=(0.0, sg * b1, 0.0)), k=(kx, ky, 2e6, 0, 0, 0)))
    s.on_line(_balanced_curve(R, V, l0), 100.0)
    model = s.assemble()
    return model, equilibrium(model, tol=1e-9), tab, (a, b1, l0, r0)


def _steady_curving_theory(k_psi, k_y, f11, f22, lam, r0, l0, a, R):
    """Linear steady curving of a two-axle bogie with no flange contact (Boocock, J. Mech. Eng.
    Sci. 11 (1969); Wickens, *Fundamentals of Rail Vehicle Dynamics*, 2003, sec. 6.3): the
    wheelsets' lateral displacements ``y_i`` and angles of attack ``psi_i`` against their own
    track axes (front i = 1 at ``+a``, rear at ``-a``; a left-hand curve, y to the left, yaw
    about z) and the frame's ``y_b``, ``psi_b``, from each wheelset's lateral balance (lateral
    creep ``2 f22 psi_i`` against the primary's shear), its yaw balance (the longitudinal creep's
    ``-(2 f11 l0 lambda / r0)(y_i - y0)``, ``y0 = -r0 l0 / (lambda R)``, against the primary's yaw
    ``-k_psi (psi_i + s_i a / R - psi_b)``: the local track turns by ``s_i a / R``) and the frame's
    two; balanced cant, spin and gravitational stiffness left out."""
    y0 = -r0 * l0 / (lam * R)
    kc = 2.0 * f11 * l0 * lam / r0
    A, rhs = np.zeros((6, 6)), np.zeros(6)       # unknowns y1, psi1, y2, psi2, y_b, psi_b
    for n, s in ((0, 1.0), (1, -1.0)):
        iy, ip = 2 * n, 2 * n + 1
        A[iy, [iy, ip, 4, 5]] = -k_y, 2 * f22, k_y, s * a * k_y          # wheelset lateral
        A[ip, [iy, ip, 5]] = -kc, -k_psi, k_psi                          # wheelset yaw
        rhs[ip] = -kc * y0 + k_psi * s * a / R
        A[4, [iy, 4, 5]] += k_y, -k_y, -s * a * k_y                       # frame lateral
        A[5, [iy, ip, 4, 5]] += s * a * k_y, k_psi, -s * a * k_y, -k_psi - a * a * k_y
        rhs[5] -= k_psi * s * a / R
    return np.linalg.solve(A, rhs), y0


@pytest.mark.parametrize("kx", [2e3, 2e5, 2e6, 1e9])
def test_a_bogie_curves_as_the_linear_steady_curving_theory_says(kx):
    """A bogie on a 3000 m curve (no flange contact): each wheelset's angle of attack and lateral
    displacement within 5 % of the linear theory (Boocock 1969; Wickens 2003, sec. 6.3), solved
    with the creep coefficients the model's contacts have (Kalker's ``G a b C_ij``); soft
    primary yaw stiffness: the wheelsets radial (``psi = 0``, ``y = y0``), a rigid bogie: ``psi =
    -+a / R`` (front, rear), the limits the theory gives."""
    from axlebox.mbs.wheelrail.element_kernel import OUT_A, OUT_B, OUT_P, OUT_R
    from axlebox.mbs.wheelrail.kalker import creep_coefficients
    R, V = 3000.0, 15.0
    model, y, tab, (a, b1, l0, r0) = _bogie(kx, R, V)
    model.rhs(0.0, y)
    out = model.W.whout[:4]
    p = tab.params
    G_mod = p.E / (2 * (1 + p.nu))
    f = [G_mod * o[OUT_A] * o[OUT_B] * np.array(creep_coefficients(o[OUT_A] / o[OUT_B], p.nu)[:2])
         for o in out]
    f11, f22 = np.mean(f, axis=0)
    got = []
    for k in (1, 2):
        st = model.body_state(k, y)
        got.append((st["r"][1], np.arctan2(st["A"][1, 0], st["A"][0, 0])))
    (gy1, gp1), (gy2, gp2) = got
    # the pair's own conicity, the equivalent one of the linear theory (Wickens 2003, sec. 5.3):
    # the rolling radius difference over twice the displacement where the wheelsets roll (the
    # cones' 1:20 and the wheelset's roll on the crowns), with the rolling radius and the
    # contacts' half distance there, as in the Redtenbacher test
    lam = np.mean([(out[2 * i + 1, OUT_R] - out[2 * i, OUT_R]) / (2 * abs(yi))
                   for i, yi in enumerate((gy1, gy2))])
    assert lam == pytest.approx(0.05, rel=0.06)
    r_mean = out[:, OUT_R].mean()
    b = 0.25 * (out[0, OUT_P + 1] - out[1, OUT_P + 1] + out[2, OUT_P + 1] - out[3, OUT_P + 1])
    (y1, p1, y2, p2, _, _), y0 = _steady_curving_theory(2 * kx * b1 ** 2, 2 * KY, f11, f22, lam,
                                                         r_mean, b, a, R)
    scale_psi = a / R                                  # the angles' own scale
    assert gy1 == pytest.approx(y1, rel=0.05) and gy2 == pytest.approx(y2, rel=0.05)
    # the angles within 5 % of the theory's, or of a / R where the theory's is near zero
    assert abs(gp1 - p1) < 0.05 * max(abs(p1), scale_psi)
    assert abs(gp2 - p2) < 0.05 * max(abs(p2), scale_psi)
    print(f"\nkx {kx:g}: y {gy1 * 1e3:.3f} {gy2 * 1e3:.3f} mm (theory {y1 * 1e3:.3f} {y2 * 1e3:.3f}), "
          f"psi {gp1 * 1e3:.4f} {gp2 * 1e3:.4f} mrad (theory {p1 * 1e3:.4f} {p2 * 1e3:.4f})")
    if kx <= 2e3:                                      # soft: radial
        assert abs(p1) < 0.05 * scale_psi and y1 == pytest.approx(y0, rel=0.05)
    if kx >= 1e9:                                      # rigid: the wheelsets at -+ a / R
        assert p1 == pytest.approx(-scale_psi, rel=0.02) and p2 == pytest.approx(scale_psi, rel=0.02)
