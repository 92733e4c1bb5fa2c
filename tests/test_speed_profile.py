"""The car along a speed profile (mbs/vehicle/speed.py, the drives of mbs/vehicle/car.py): the profile's
closed forms, the car's distance and its wheelsets' spin against them at a constant acceleration,
a profile that never changes speed as the constant-speed run, bit for bit, and bad profiles."""

import h5py
import numpy as np
import pytest
from scipy.integrate import quad

from axlebox import configs
from axlebox._params import ParameterError
from axlebox.mbs.vehicle import config as vconfig
from axlebox.mbs.solver import integrate
from axlebox.mbs.kernel.body import BI_POS, BI_VEL, SPIN_ANGLE, SPIN_RATE
from axlebox.mbs.kernel.speed import G_PROF, profile_at
from axlebox.mbs.vehicle.speed import SpeedProfile
from axlebox.pipelines import simulate as psim

ROWS = ((0.0, 20.0), (0.5, 20.0), (20.5, 92.0))     # 1 m/s^2 from 0.5 s


def test_the_profile_is_its_closed_form_in_python_and_in_the_kernel():
    """Distance ``v0 t + a t^2 / 2`` and speed ``v0 + a t`` of a constant acceleration (exact to
    rounding), the speed held outside the points, and the distance the integral of the speed
    (scipy's quad over the piecewise-linear speed); the kernel's look-up (``glob``) the same."""
    p = SpeedProfile.from_kmh(((0.0, 36.0), (2.0, 36.0), (6.0, 50.4), (7.0, 43.2)))
    t = np.linspace(0.0, 9.0, 181)
    x, v, a = p.at(t)
    v0 = 10.0
    acc = t[(t > 2) & (t < 6)]
    np.testing.assert_allclose(p.at(acc)[0], v0 * acc + 0.5 * 1.0 * (acc - 2) ** 2, rtol=1e-13)
    np.testing.assert_allclose(p.at(acc)[1], v0 + (acc - 2), rtol=1e-13)
    assert p.at(8.5)[1] == pytest.approx(12.0) and p.at(8.5)[2] == 0.0
    assert p.at(6.5)[2] == pytest.approx(-2.0)
    for tk in (1.0, 4.0, 6.5, 9.0):
        assert p.distance(tk) == pytest.approx(quad(p.speed, 0.0, tk, points=(2.0, 6.0, 7.0))[0],
                                               rel=1e-10)
    glob = np.concatenate([np.zeros(G_PROF), p.pack()])
    kern = np.array([profile_at(glob, tk) for tk in t])
    np.testing.assert_allclose(kern, np.column_stack([x, v, a]), rtol=1e-12, atol=1e-12)
    assert not SpeedProfile.from_kmh(((0.0, 48.0), (3.0, 48.0))).accelerates


@pytest.fixture(scope="module")
def rigid_car():
    base = vconfig.load(configs.path("vehicle"))
    return base.replace(bodies={"flexible": []})


def _run(cfg):
    model, y0 = psim.build_model(cfg, log=lambda *_: None)
    return model, integrate.simulate(model, cfg.run.duration, cfg.settings(), y0=y0)


def test_at_a_constant_acceleration_the_car_runs_the_closed_form(rigid_car, tmp_path):
    """The rigid car at 20 km/h, then 1 m/s^2 for 2.5 s: the carbody's distance within 0.5 % of
    ``v0 t + a (t - 0.5)^2 / 2`` and each wheelset's spin angle within 0.5 % of that distance
    over the rolling radius (``V(0) / omega(0)``, the free rolling at the start), its spin rate
    at the end within 0.5 % of ``V / r`` (the creep the traction needs is about 1e-3)."""
    cfg = rigid_car.replace(run={"duration": 3.0, "speed_kmh": 20.0, "profile": ROWS})
    model, run = _run(cfg)
    assert run.ok, run.message
    prof = cfg.speed_profile()
    Y, ts = np.asarray(run.states[:]), np.asarray(run.state_time)
    bi, sysm = model.S.bi, model.system
    T = ts[-1]
    dist = prof.distance(T)
    cb = sysm.index("carbody")
    assert Y[-1, bi[cb, BI_POS]] - Y[0, bi[cb, BI_POS]] == pytest.approx(dist, rel=0.005)
    assert Y[-1, bi[cb, BI_VEL]] == pytest.approx(prof.speed(T), rel=0.005)
    for k in range(1, 5):
        j = sysm.index(f"ws{k}")
        beta, w = Y[:, bi[j, BI_POS] + SPIN_ANGLE], Y[:, bi[j, BI_VEL] + SPIN_RATE]
        r_roll = prof.speed(0.0) / w[0]
        assert beta[-1] - beta[0] == pytest.approx(dist / r_roll, rel=0.005)
        assert w[-1] == pytest.approx(prof.speed(T) / r_roll, rel=0.005)
    assert dist > 1.15 * prof.speed(0.0) * T         # it did accelerate (by 2.5 x 2.5 / 2 m)
    # issue 57: the drives' torques in the result file, each wheelset's share of the car's
    # inertia and its own spin inertia over the steady acceleration (1.5-3 s: a = 1 m/s^2),
    # T = (M / 4) a r + J a / r (mbs/vehicle/car.py: the profile's feed-forward; its speed gain
    # adds the creep's share, ~1e-3 of the speed)
    path = psim.write(tmp_path / "profile.h5", run, model, cfg)
    steady = (run.time >= 1.5) & (run.time <= 3.0)
    with h5py.File(path, "r") as f:
        for k in range(1, 5):
            e = sysm.elements[[x.name for x in sysm.elements].index(f"drive{k}")]
            torque = f[f"drives/drive{k}/torque"][()]
            assert f[f"drives/drive{k}/torque"].attrs["on"] == f"ws{k}"
            assert torque.shape == run.time.shape
            expect = e.mass * 1.0 * e.radius + e.inertia * 1.0 / e.radius     # e.mass: M / 4
            assert np.mean(torque[steady]) == pytest.approx(expect, rel=0.02)


def test_a_profile_that_never_changes_speed_is_the_constant_speed_run(rigid_car):
    """No drive, the same reference speed: every output the same to the bit."""
    const = rigid_car.replace(run={"duration": 0.2, "speed_kmh": 48.0})
    flat = const.replace(run={"profile": ((0.0, 48.0), (0.1, 48.0), (5.0, 48.0))})
    _, a = _run(const)
    _, b = _run(flat)
    for name in a.sensors:
        np.testing.assert_array_equal(a.sensors[name], b.sensors[name])
    np.testing.assert_array_equal(a.wheels, b.wheels)
    np.testing.assert_array_equal(a.y_end, b.y_end)


@pytest.mark.parametrize("run, field", [
    ({"speed_kmh": 20.0, "profile": ((1.0, 20.0), (2.0, 30.0))}, "run.profile[0] time"),
    ({"speed_kmh": 20.0, "profile": ((0.0, 20.0), (2.0, 30.0), (2.0, 40.0))}, "run.profile[2] time"),
    ({"speed_kmh": 20.0, "profile": ((0.0, 20.0), (2.0, -30.0))}, "run.profile[1]"),
    ({"speed_kmh": 48.0, "profile": ((0.0, 20.0), (2.0, 30.0))}, "run.speed_kmh"),
    ({"speed_kmh": 20.0, "profile": ((0.0, 20.0, 3.0),)}, "run.profile[0]"),
])
def test_a_bad_profile_is_one_line_naming_the_field(run, field):
    with pytest.raises(ParameterError) as err:
        vconfig.CarConfig().replace(run=run)
    assert str(err.value).startswith(field) and "\n" not in str(err.value)


def test_the_track_covers_the_distance_the_profile_runs():
    """The irregularity's record must hold the distance run (the profile's) plus the car."""
    cfg = vconfig.CarConfig().replace(run={"speed_kmh": 20.0, "duration": 20.0,
                                           "profile": ((0.0, 20.0), (20.0, 92.0))})
    assert cfg.track_needed() == pytest.approx(20.0 / 3.6 * 20 + 0.5 * 20 ** 2
                                               + cfg.geometry.bogie_distance + 5.0)
    with pytest.raises(ParameterError, match="^track.length"):
        cfg.replace(track={"length": 300.0})
