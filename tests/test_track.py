"""Track irregularities from the FRA spectra (mbs/track/irregularity.py).

Outside references: the FRA PSD formulas and class table as given in
../shared/REFERENCE_DATA.md (Hamid et al., FRA DOT/FRA/ORD-83/03.1, 1983, in the k = 0.25 form),
and the ISO 3095:2013 Figure 2 rail roughness limit (= EN 15610:2009 Annex B.9.2).
"""
import dataclasses

import numpy as np
import pytest
from scipy import integrate, signal

from axlebox._params import ParameterError
from axlebox.mbs.track import irregularity as track
from axlebox.mbs.track.irregularity import IrregularityParams, generate, psd


@pytest.fixture(scope="module")
def long_record():
    """20 km of class 5 track, 1-80 m, 0.1 m grid (200 k points, ~0.05 s)."""
    return generate(IrregularityParams(grade=5, length=20000.0, ds=0.1, seed=3))


@pytest.fixture(scope="module")
def record():
    return generate(IrregularityParams(length=2000.0, seed=7))


# Class 5: A_v = 0.2095, A_a = 0.0762 cm^2 rad/m, Omega_s = 0.8209, Omega_c^2 = 0.67980025 (rad/m)^2.
# By hand, Omega = 0.5: S_v = 0.25*0.2095*0.67980025 / (0.25*(0.25+0.67980025)) = 0.153171 cm^2/(rad/m),
# S_a the same with 0.0762 = 0.0557117, S_c = S_g = 4*0.25*0.2095*0.67980025
# / ((0.25+0.67980025)(0.25+0.67387681)) = 0.165791.  Omega = 2: 0.00190203, 0.000691813, 0.00651120.
HAND_CM2 = {0.5: {"vertical": 0.153171, "alignment": 0.0557117, "crosslevel": 0.165791, "gauge": 0.165791},
            2.0: {"vertical": 0.00190203, "alignment": 0.000691813, "crosslevel": 0.00651120,
                  "gauge": 0.00651120}}


@pytest.mark.parametrize("Omega", sorted(HAND_CM2))
@pytest.mark.parametrize("kind", track.KINDS)
def test_psd_class5_matches_hand_values_in_si(kind, Omega):
    # 6 significant figures written above: rel 1e-5; 1 cm^2 = 1e-4 m^2
    assert psd(kind, Omega, 5) == pytest.approx(HAND_CM2[Omega][kind] * 1e-4, rel=1e-5)


def test_psd_orders_classes_and_is_vectorised():
    W = np.array([0.1, 0.5, 2.0])
    S = np.array([psd("vertical", W, g) for g in range(1, 7)])
    assert S.shape == (6, 3)
    assert np.all(np.diff(S, axis=0) < 0)   # A_v falls from class 1 to 6: better track, less power


@pytest.mark.parametrize("kind", track.KINDS)
def test_record_variance_equals_band_integral(long_record, kind):
    # one period of a harmonic sum has variance sum a_k^2 / 2 (Parseval) = integral of S over the
    # band by construction; 1 % (tighter than the 5 % asked) covers the 4-point Gauss rule per bin
    lo, hi = 2 * np.pi / 80.0, 2 * np.pi / 1.0
    target = integrate.quad(lambda W: psd(kind, W, 5), lo, hi, limit=200)[0]
    assert np.var(long_record.values[kind]) == pytest.approx(target, rel=0.01)


# octave bands of wavelength from 50 m down, the last one the 0.64-octave remainder down to 2 m
BANDS_M = [(25.0, 50.0), (12.5, 25.0), (6.25, 12.5), (3.125, 6.25), (2.0, 3.125)]


@pytest.mark.parametrize("kind", track.KINDS)
def test_welch_estimate_follows_target_in_octave_bands(long_record, kind):
    # Welch on 409.6 m Hann segments (~97 of them, 50 % overlap): >= 8 lines in the 25-50 m band.
    # scipy gives m^2/(cycle/m); per rad/m divide by 2 pi.  The band averages scatter by at most
    # 9 % over seeds 0-29 (measured), so +-25 % leaves room for any seed.
    f, P = signal.welch(long_record.values[kind], fs=1 / long_record.ds, nperseg=4096)
    W, S = 2 * np.pi * f, P / (2 * np.pi)
    for lam_short, lam_long in BANDS_M:
        lo, hi = 2 * np.pi / lam_long, 2 * np.pi / lam_short
        m = (W >= lo) & (W < hi)
        target = integrate.quad(lambda w: psd(kind, w, 5), lo, hi)[0] / (hi - lo)
        assert m.sum() >= 8
        assert S[m].mean() == pytest.approx(target, rel=0.25), (lam_short, lam_long)


def test_components_have_independent_phases(long_record):
    # cross-level and gauge share one spectrum; independent phases leave them uncorrelated
    # (measured |rho| <= 0.025 over seeds 0-29 on 20 km; 0.1 is four times that)
    rho = np.corrcoef(long_record.values["crosslevel"], long_record.values["gauge"])[0, 1]
    assert abs(rho) < 0.1


def test_same_seed_same_record_other_seed_other_record():
    a, b = (generate(IrregularityParams(length=500.0, seed=11)) for _ in range(2))
    c = generate(IrregularityParams(length=500.0, seed=12))
    for k in track.KINDS:
        assert np.array_equal(a.values[k], b.values[k])
        assert not np.allclose(a.values[k], c.values[k])


def test_rails_compose_from_the_components(record):
    v, a, c, g = (record.values[k] for k in track.KINDS)
    zL, zR, yL, yR = record.grid()
    for got, want in [((zL + zR) / 2, v), (zL - zR, c), ((yL + yR) / 2, a), (yL - yR, g)]:
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-15)
    # and at arbitrary positions, through the lookup (interpolation is linear in the data)
    s = np.linspace(3.3, 1900.7, 501)
    zL, zR, yL, yR = record.at(s)
    for got, kind in [(zL - zR, "crosslevel"), (yL - yR, "gauge")]:
        exact = record.harmonic_sum(kind, s)   # within the lookup's error, see the next test
        np.testing.assert_allclose(got, exact, rtol=0, atol=4e-4 * np.std(exact))


def test_lookup_matches_the_exact_harmonic_sum(record):
    # cubic Hermite on exact slopes, 10 points per shortest wavelength: value error <=
    # (2 pi/10)^4/384 ~ 4e-4 of the shortest wave's amplitude; slope error ~ (2 pi/10)^3/24 ~ 1e-2
    # of its slope amplitude; both are bounds relative to the rms, which longer waves dominate
    s = np.random.default_rng(1).uniform(-50.0, 3000.0, 300)   # wraps around the period too
    exact = record.harmonic_sum("vertical", s) + 0.5 * record.harmonic_sum("crosslevel", s)
    assert np.max(np.abs(record.at(s)[0] - exact)) < 4e-4 * np.std(exact)
    h = 1e-4

    def zL(x):
        return record.harmonic_sum("vertical", x) + 0.5 * record.harmonic_sum("crosslevel", x)
    slope = (zL(s + h) - zL(s - h)) / (2 * h)
    assert np.max(np.abs(record.at(s, derivative=True)[0] - slope)) < 1e-2 * np.std(slope)
    assert record.period >= record.params.length
    np.testing.assert_allclose(record.at(s + record.period), record.at(s), rtol=0, atol=1e-12)


def test_following_wheelsets_see_the_track_delayed(record):
    # B-type metro car: 2.5 m wheelbase, bogie centres 12.6 m apart -> axles 0, 2.5, 12.6, 15.1 m back
    V, s0 = 22.0, 40.0
    offsets = np.array([0.0, 2.5, 12.6, 15.1])
    t = np.linspace(0.0, 30.0, 2001)
    seen = record.for_wheelsets(s0 + V * t, offsets)
    assert seen.shape == (t.size, 4, 4)
    for k, d in enumerate(offsets):
        earlier = np.stack(record.at(s0 + V * (t - d / V)), axis=-1)   # wheelset 1 at t - d/V
        np.testing.assert_allclose(seen[:, k], earlier, rtol=0, atol=1e-12)
    assert np.max(np.abs(seen[:, 1] - seen[:, 0])) > 1e-4             # they do see different track


def test_roughness_is_off_by_default_and_leaves_the_geometry_alone():
    assert not IrregularityParams().roughness
    # a 1 mm grid: 4 points on a 1 cm shortest roughness wavelength
    p = IrregularityParams(length=100.0, lambda_max=50.0, seed=5, ds=1e-3, roughness_lambda_min=0.01)
    plain = generate(p)
    rough = generate(dataclasses.replace(p, roughness=True))
    assert "roughness_L" not in plain.values
    # one random stream per component: on the same grid the geometry is unchanged by roughness
    for k in track.KINDS:
        np.testing.assert_array_equal(plain.values[k], rough.values[k])
    zL, zR, _, _ = rough.grid()
    v, c = rough.values["vertical"], rough.values["crosslevel"]
    np.testing.assert_allclose(zL - (v + c / 2), rough.values["roughness_L"], rtol=0, atol=1e-15)
    np.testing.assert_allclose(zR - (v - c / 2), rough.values["roughness_R"], rtol=0, atol=1e-15)
    assert not np.allclose(rough.values["roughness_L"], rough.values["roughness_R"])   # independent


def test_roughness_band_levels_match_iso3095_limit():
    # ISO 3095:2013 Fig. 2 (EN 15610:2009 B.9.2): 10 cm band 4.9 dB, 2 cm band -6.2 dB, 0.63 cm
    # band -9.2 dB re 1 um.  The record's one-third-octave mean square from its FFT: 0.3 dB covers
    # the log-log interpolation between band centres (<= 0.16 dB) and bins cut at band edges.
    r = generate(IrregularityParams(length=20.0, lambda_max=20.0, roughness=True,
                                    roughness_lambda_min=0.005, seed=1))
    x = r.values["roughness_L"]
    X = np.fft.rfft(x)
    W = 2 * np.pi * np.fft.rfftfreq(x.size, r.ds)
    mean_square = 2 * np.abs(X) ** 2 / x.size ** 2
    for wavelength, level in [(0.1, 4.9), (0.02, -6.2), (0.0063, -9.2)]:
        centre = 2 * np.pi / 10 ** (round(10 * np.log10(wavelength)) / 10)   # exact base-ten centre
        m = (W >= centre / 10 ** 0.05) & (W < centre * 10 ** 0.05)
        assert 10 * np.log10(mean_square[m].sum() / 1e-12) == pytest.approx(level, abs=0.3)


def test_plot_returns_a_figure(record):
    from matplotlib.figure import Figure
    fig = record.plot(0.0, 200.0)
    assert isinstance(fig, Figure) and len(fig.axes) == 2
    zL = fig.axes[0].lines[0].get_ydata()
    np.testing.assert_allclose(zL, 1e3 * record.at(np.arange(0.0, 200.0, record.ds))[0])


@pytest.mark.parametrize("kwargs, match", [
    ({"grade": 7}, r"grade = 7 is not allowed.*1 \(worst\) to 6"),
    ({"grade": 0}, r"grade = 0 is not allowed"),
    ({"grade": 2.5}, r"grade = 2.5 is not allowed"),
    ({"grade": True}, r"grade = True is not allowed"),
    ({"lambda_min": 80.0, "lambda_max": 1.0}, r"lambda_min = 80.0 is not allowed: must be shorter"),
    ({"lambda_min": 50.0, "lambda_max": 50.0}, r"lambda_min = 50.0 is not allowed"),
    ({"lambda_min": -1.0}, r"lambda_min = -1.0 is not allowed: expected a number in \[0.5, 1000\]"),
    ({"lambda_max": 0.0}, r"lambda_max = 0.0 is not allowed"),
    ({"length": 50.0}, r"length = 50.0 is not allowed: must be at least lambda_max = 80"),
    ({"length": 1e6, "ds": 0.01}, r"length = 1000000.0 is not allowed: needs 1e\+08 grid points"),
    ({"ds": 0.5}, r"ds = 0.5 is not allowed: expected a grid step in \(0, 0.25\]"),
    ({"ds": -0.1}, r"ds = -0.1 is not allowed"),
    ({"seed": -1}, r"seed = -1 is not allowed"),
    ({"seed": 1.5}, r"seed = 1.5 is not allowed: expected an integer"),
    ({"roughness": "yes"}, r"roughness = 'yes' is not allowed"),
    ({"roughness_lambda_min": 0.0005}, r"roughness_lambda_min = 0.0005 is not allowed"),
    ({"roughness_spectrum": "smooth"}, r"roughness_spectrum = 'smooth' is not allowed: expected one "
     "of iso3095, network"),
    ({"contact_load": 2e5}, r"contact_load = 200000.0 is not allowed"),
    ({"contact_load": 1e4}, r"contact_load = 10000.0 is not allowed: expected 0 \(no contact"),
    ({"roughness": True, "roughness_lambda_min": 0.2, "roughness_lambda_max": 0.1},
     r"roughness_lambda_min = 0.2 is not allowed: must be shorter"),
])
def test_bad_parameters_are_refused_naming_the_field(kwargs, match):
    with pytest.raises(ParameterError, match=r"IrregularityParams\." + match):
        IrregularityParams(**kwargs)


def test_bad_calls_are_refused(record):
    with pytest.raises(ParameterError, match=r"psd.kind = 'twist' is not allowed: expected one of vertical"):
        psd("twist", 1.0, 5)
    with pytest.raises(ParameterError, match=r"psd.grade = 7 is not allowed"):
        psd("vertical", 1.0, 7)
    with pytest.raises(ParameterError, match=r"psd.Omega = 0.0 is not allowed"):
        psd("vertical", np.array([1.0, 0.0]), 5)
    with pytest.raises(ParameterError, match=r"roughness_psd.Omega = .* the bands cover"):
        track.roughness_psd(1.0)
    with pytest.raises(ParameterError, match=r"component = 'roughness_L' is not allowed"):
        record.harmonic_sum("roughness_L", 0.0)      # roughness is off in this record
    with pytest.raises(ParameterError, match=r"for_wheelsets.offsets"):
        record.for_wheelsets(0.0, [0.0, -2.5])
