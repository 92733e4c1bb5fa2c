"""The ballasted track under each wheel (mbs/track/bed.py): the lumping against the beam on elastic
foundation, the car standing on it, a flat's impact on it against rigid rails."""


import numpy as np
import pytest

from axlebox.mbs.track import bed as trackbed
from axlebox.mbs.vehicle.config import Track

ZHAI = dict(rail_mass=60.64, rail_EI=6.624e6, sleeper_spacing=0.6, pad_k=6.5e7, pad_c=7.5e4,
            sleeper_mass=125.5, ballast_mass=531.4, ballast_k=1.3775e8, ballast_c=5.88e4,
            subgrade_k=7.75e7, subgrade_c=3.115e4)
SEATS = Track(model="ballasted", **ZHAI)       # the config's [track] with these seats


def test_the_lumped_track_keeps_the_beam_on_elastic_foundation_stiffness():
    """Rayleigh-Ritz with the Winkler deflection shape: the Ritz length int (w/w0)^2 dx is 3 / (2
    beta) (checked by quadrature), and the lumped chain's static stiffness is Hetenyi's 2 k_f /
    beta to rounding; with these seats 81 MN/m, 0.86 mm under a 70 kN wheel (ballasted track
    under a metro wheel deflects 0.5-1.5 mm)."""
    m = trackbed.lumped(SEATS)
    x = np.linspace(0.0, 40.0 / m.beta, 400001)
    w = np.exp(-m.beta * x) * (np.cos(m.beta * x) + np.sin(m.beta * x))
    assert 2 * np.trapezoid(w * w, x) == pytest.approx(m.L, rel=1e-6)
    wpp = 2 * m.beta ** 2 * np.exp(-m.beta * x) * (np.sin(m.beta * x) - np.cos(m.beta * x))
    assert ZHAI["rail_EI"] * 2 * np.trapezoid(wpp * wpp, x) == pytest.approx(m.k_bend, rel=1e-5)
    K = trackbed.static_stiffness(m)
    assert K == pytest.approx(trackbed.winkler_stiffness(SEATS), rel=1e-12)
    assert K == pytest.approx(81.3e6, rel=1e-3)
    assert m.m_rail == pytest.approx(ZHAI["rail_mass"] * 1.5 / m.beta, rel=1e-12)


@pytest.fixture(scope="module")
def ballasted_car():
    """The shipped car (row bushings) at 40 km/h on smooth ballasted track, with a 40 mm rounded
    flat on wheelset 2's right wheel; 0.4 s (the flat's first strike near 0.24 s)."""
    from axlebox import configs
    from axlebox.mbs.vehicle import config as vconfig
    from axlebox.mbs.solver import integrate
    from axlebox.mbs.kernel.wheels import G_RAMP
    from axlebox.pipelines import simulate as psim
    cfg = vconfig.load(configs.path("vehicle")).replace(
        run={"speed_kmh": 40.0}, track={"irregularity": False, "model": "ballasted"},
        wheel_defects=[{"wheelset": 2, "side": "R", "kind": "flat", "length": 0.04}])
    model, y0 = psim.build_model(cfg, log=lambda *_: None)
    model.S.glob[G_RAMP] = 0.02
    run = integrate.simulate(model, 0.4, cfg.settings(), y0=y0)
    return cfg, model, y0, run


def test_the_car_stands_on_the_track_as_the_beam_theory_says(ballasted_car):
    """At the start (static equilibrium on smooth track) every rail under a wheel has sunk by its
    wheel's vertical load over the track's static stiffness (0.1 %: the rest is the equilibrium's
    tolerance)."""
    from axlebox.mbs.wheelrail import element_kernel as ek
    cfg, model, y0, run = ballasted_car
    K = trackbed.static_stiffness(trackbed.lumped(cfg.track))
    for w, name in enumerate(model.wheel_names):
        z = model.body_state(model.system.index(f"rail_{name}"), y0)["r"][2]
        Q = run.wheels[0, w, ek.OUT_F + 2]
        assert Q > 0.5 * 9.81 * cfg.carbody.mass / 8
        assert z == pytest.approx(-Q / K, rel=1e-3), name


def test_a_flat_strikes_a_ballasted_track_less_hard_than_rigid_rails(ballasted_car):
    """The 40 mm flat at 40 km/h still lifts the wheel and strikes once a turn, but on the
    track's pads and ballast the strike is below the 470-530 kN it reaches on rigid rails
    (tests/test_wheel_defects.py) and the run stays finite."""
    from axlebox.mbs.wheelrail import element_kernel as ek
    cfg, model, y0, run = ballasted_car
    assert run.ok, run.message
    w = model.wheel_names.index("ws2_R")
    N = run.wheels[run.time > 0.1, w, ek.OUT_N]
    assert N.min() == 0.0 and N.max() > 1.5 * np.median(N)
    assert N.max() < 400e3
