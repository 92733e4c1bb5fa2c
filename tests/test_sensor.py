"""The accelerometer and acquisition chain (pipelines/sensor.py) against the closed forms of its
stages, and what it does to signals: in band untouched and on time, beyond fs/2 gone."""
import dataclasses
from types import SimpleNamespace

import numpy as np
import pytest

from axlebox.mbs.vehicle import config as vconfig
from axlebox.pipelines import sensor

S = vconfig.Sensors()


def test_mounted_resonance_and_high_pass_are_the_closed_forms():
    """Base-excited oscillator: |H| = Q at f_n, 1 far below it; first-order high-pass: -3 dB
    (1/sqrt 2) at its corner; both together near 1 in between."""
    fn, q, fc = 25e3, 30.0, 0.5
    assert abs(sensor.response(fn, fn, q, 0.0)) == pytest.approx(q, rel=1e-12)
    assert abs(sensor.response(fc, fn, q, fc)) == pytest.approx(2 ** -0.5, rel=1e-6)
    f = np.array([50.0, 1e3, 2.7e3])
    H = sensor.response(f, fn, q, fc)
    assert np.allclose(abs(H), 1 / np.abs(1 - (f / fn) ** 2), rtol=1e-3)


def test_antialias_filter_is_flat_in_band_and_stops_from_half_the_rate():
    h = sensor.antialias(40e3, 10e3, 0.45)
    w, g = __import__("scipy.signal", fromlist=["freqz"]).freqz(h, worN=2 ** 15, fs=40e3)
    db = 20 * np.log10(np.maximum(np.abs(g), 1e-300))
    assert np.abs(db[w <= 4.5e3]).max() < 0.01                 # flat to 0.45 fs
    assert db[w >= 5e3].max() < -sensor.STOPBAND_DB + 0.5      # no alias from fs/2 on


def test_in_band_tone_is_kept_on_time_and_an_out_of_band_tone_does_not_alias():
    fs_in, T = 40e3, 0.5
    t = np.arange(int(T * fs_in)) / fs_in
    tone = np.sin(2 * np.pi * 1000.0 * t)
    y = sensor.measure(np.c_[tone, np.sin(2 * np.pi * 7000.0 * t)], fs_in, S)
    mid = slice(500, -500)                                     # the filters' edge transients
    expect = np.abs(sensor.response(1000.0, S.resonance_hz, S.resonance_q, S.highpass_hz))
    ref = expect * np.sin(2 * np.pi * 1000.0 * t[::4])
    assert np.abs(y[mid, 0] - ref[mid]).max() < 2e-3          # gain and timing (no group delay)
    # 7 kHz would alias to 3 kHz at 10 kHz sampling; the chain leaves a 1e-4 trace at most
    assert np.abs(y[mid, 1]).max() < 1e-4


def test_sampling_rate_must_divide_the_run_output():
    with pytest.raises(ValueError, match="sensors.fs_hz"):
        sensor.measure(np.zeros((100, 3)), 15e3, S)
    cfg = {"sensors": {"model": "accelerometer"}}
    with pytest.raises(ValueError, match="integrator.output_rate_hz"):
        vconfig.validate(cfg)


def test_decimation_keeps_the_full_convolutions_samples_and_nothing_else():
    """The acquisition computes only the kept samples (polyphase): they are the full-rate
    filter's output at every k-th instant, delay taken out, as ``np.convolve`` gives it (to
    rounding); the result owns its memory, so a long record's 50 kHz intermediate is not kept
    alive by it (a 60 s run's eleven sensors held 760 MB that way)."""
    fs_in = 50e3
    a = np.random.default_rng(1).standard_normal((4001, 2))
    # stages 1-2 out (gain 1 - 1e-13): a resonance beyond what a config allows
    s = SimpleNamespace(**{**dataclasses.asdict(S), "resonance_hz": 1e16, "highpass_hz": 0.0})
    y = sensor.measure(a, fs_in, s)
    h = sensor.antialias(fs_in, s.fs_hz, s.passband)
    d, k = (h.size - 1) // 2, int(fs_in / s.fs_hz)
    ref = np.stack([np.convolve(a[:, j], h)[d:d + a.shape[0]][::k] for j in range(2)], axis=1)
    assert y.shape == ref.shape
    assert np.abs(y - ref).max() < 1e-12
    assert y.base is None
