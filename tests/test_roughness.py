"""Wheel and rail roughness (mbs/track/roughness.py): the CNOSSOS-EU tables, the contact filter, the
sampled records and the wheel-rail element reading a wheel's own roughness.

Reference: Kephalopoulos, Paviotti, Anfosso-Ledee, CNOSSOS-EU, JRC EUR 25379 EN (2012), railway
source tables (wheel roughness, contact filters, ISO 3095:2013 limit)."""

import numpy as np
import pytest
from scipy.interpolate import CubicHermiteSpline

from axlebox import configs
from axlebox._params import ParameterError
from axlebox.mbs.vehicle import config as vconfig
from axlebox.mbs.track import roughness as R
from axlebox.mbs.track import irregularity as track
from axlebox.mbs.kernel.wheels import hermite_at
from axlebox.mbs.wheelrail import element_kernel as ek
from axlebox.pipelines import simulate as psim


def test_the_tables_are_the_published_ones():
    # composite (k-block) wheel at 1 cm: -7.14 dB; cast iron at 5 cm: 11.11 dB; disc at 0.5 cm:
    # -10.81 dB; contact filter 50 kN/920 mm at 1 cm: -12 dB, 100 kN at 0.5 cm: -17 dB
    n = {lam: int(round(-10 * np.log10(lam))) for lam in (0.01, 0.05, 0.005)}
    assert R.WHEEL_DB["composite"][n[0.01]] == -7.14
    assert R.WHEEL_DB["cast-iron"][n[0.05]] == 11.11
    assert R.WHEEL_DB["disc"][n[0.005]] == -10.81
    assert R.CONTACT_DB[1][n[0.01]] == -12 and R.CONTACT_DB[2][n[0.005]] == -17
    # the ISO 3095 column is track.py's limit where that one is defined
    np.testing.assert_array_equal(np.asarray(R.RAIL_DB["iso3095"])[track.ISO3095_BANDS],
                                  track.ISO3095_LIMIT_DB)
    for table in (*R.WHEEL_DB.values(), *R.RAIL_DB.values(), *R.CONTACT_DB):
        assert len(table) == R.BANDS.size


def test_the_contact_filter_is_the_tables_at_their_loads_and_between_them_in_log_load():
    np.testing.assert_array_equal(R.contact_filter_db(50e3), R.CONTACT_DB[1])
    np.testing.assert_array_equal(R.contact_filter_db(100e3), R.CONTACT_DB[2])
    mid = R.contact_filter_db(float(np.sqrt(50e3 * 100e3)))      # half way in log(load)
    np.testing.assert_allclose(mid, 0.5 * (R.CONTACT_DB[1] + R.CONTACT_DB[2]), atol=1e-12)
    assert np.all(R.contact_filter_db(64.8e3) <= 0.0)
    for bad in (10e3, 2e5, "heavy"):
        with pytest.raises(ParameterError, match="contact filter load = .* is not allowed: the tables"):
            R.contact_filter_db(bad)


def test_a_wheel_record_is_periodic_on_its_circle_and_carries_the_filtered_band_levels():
    """Its one-third-octave levels from the FFT are the filtered table's within 0.35 dB (the
    log-log interpolation between band centres) in every band with 40 or more FFT bins (6.3 cm
    and shorter on a 0.42 m wheel) that the record covers whole."""
    r0, lam_min, load = 0.42, 0.003, 64.8e3
    v, d, ds = R.wheel_record("composite", r0, lam_min, load, np.random.default_rng(3))
    assert v.size * ds == pytest.approx(2 * np.pi * r0, rel=1e-14)
    L = R.third_octave_levels(v, ds)
    ref = R.levels_db("wheel", "composite", load)
    whole = [n for n in range(12, R.BANDS.size) if R.LAMBDA[n] / 10 ** 0.05 > lam_min]
    assert whole[-1] == 24
    np.testing.assert_allclose(L[whole], ref[whole], atol=0.35)
    # the slopes are the record's derivative: a central difference agrees to its O(h^2) error
    fd = (np.roll(v, -1) - np.roll(v, 1)) / (2 * ds)
    assert np.abs(fd - d).max() < 0.05 * np.abs(d).max()


def test_the_element_reads_a_periodic_record_by_cubic_hermite_as_scipy_does():
    rng = np.random.default_rng(0)
    v, d, ds = R.wheel_record("cast-iron", 0.42, 0.01, None, rng)
    s = np.concatenate([np.arange(v.size) * ds, [v.size * ds]])
    ref = CubicHermiteSpline(s, np.append(v, v[0]), np.append(d, d[0]))
    for x in rng.uniform(0.0, s[-1], 50):
        val, der = hermite_at(v, d, x, ds)
        assert val == pytest.approx(float(ref(x)), abs=1e-12 * np.abs(v).max())
        assert der == pytest.approx(float(ref(x, 1)), abs=1e-9 * np.abs(d).max())
        # a wheel turn later it is the same point of the tread
        assert hermite_at(v, d, x + 3 * s[-1], ds)[0] == pytest.approx(val, abs=1e-12 * np.abs(v).max())


@pytest.fixture(scope="module")
def car():
    cfg = vconfig.load(configs.path("vehicle"))
    model, y0 = psim.build_model(cfg, log=lambda *_: None)
    return cfg, model, y0


def test_a_wheels_roughness_acts_as_its_rail_lifted_as_much(car):
    """A constant 20 um on every left wheel's record and the left rail raised 20 um give the
    same forces (after the fade-in); and the wheels feel it (several kN on a Hertz contact)."""
    cfg, model, y0 = car
    S = model.S
    delta, t = 20e-6, 1.0
    smooth = S._replace(trk=np.zeros_like(S.trk))            # the track y0 rests on
    left = S.wh_i[:, 1] == 0
    wrk = np.zeros((S.wh_f.shape[0], 2, 16))
    wrk[left, 0] = delta
    wh_f = S.wh_f.copy()
    wh_f[left, 1] = 0.01
    trk = smooth.trk.copy()
    trk[0] += delta
    try:
        model.S = smooth
        base = model.rhs(t, y0)
        N0 = model.W.whout[:, ek.OUT_N].copy()
        model.S = smooth._replace(wrk=wrk, wh_f=wh_f)
        by_wheel = model.rhs(t, y0)
        N_wheel = model.W.whout[:, ek.OUT_N].copy()
        model.S = smooth._replace(trk=trk)
        by_rail = model.rhs(t, y0)
    finally:
        model.S = S
    np.testing.assert_allclose(by_wheel, by_rail, rtol=1e-9, atol=1e-9 * np.abs(base).max())
    assert np.all(N_wheel[left] - N0[left] > 1e3)
    np.testing.assert_array_equal(N_wheel[~left], N0[~left])


def test_the_config_gives_every_wheel_its_own_record(car):
    cfg, model, _ = car
    cfg = cfg.replace(track={"wheel_roughness": "composite"})
    names = model.wheel_names
    recs = psim.wheel_records(cfg, names)
    assert set(recs) == set(names)
    sysm = model.system
    try:
        sysm.wheel_records = recs
        S = sysm.assemble().S
    finally:
        sysm.wheel_records = {}
    for w, name in enumerate(names):
        np.testing.assert_array_equal(S.wrk[w, 0], recs[name][0])
        assert S.wh_f[w, 1] == recs[name][2]
    assert not np.allclose(S.wrk[0, 0], S.wrk[1, 0])          # independent phases
    np.testing.assert_array_equal(psim.wheel_records(cfg, names)[names[0]][0], recs[names[0]][0])


@pytest.mark.parametrize("fields, match", [
    ({"wheel_roughness": "steel"}, r"track.wheel_roughness = 'steel' is not allowed: expected one of "
                                   r"none, cast-iron, composite, disc"),
    ({"rail_roughness": "network", "irregularity": False},
     r"track.rail_roughness = 'network' is not allowed with track.irregularity = false"),
    ({"roughness_lambda_min": 0.5}, r"track.roughness_lambda_min = 0.5 is not allowed"),
])
def test_bad_roughness_settings_are_refused_naming_the_field(fields, match):
    with pytest.raises(ParameterError, match=match):
        vconfig.validate({"track": fields})
