"""Envelope analysis: the standard demodulation for bearing fault impulses (Randall and Antoni,
Mech. Syst. Signal Process. 25 (2011) 485-520, sec. 3): band-pass around the resonance the
impulses excite, take the magnitude of the analytic signal (Hilbert), remove its mean, and take
the amplitude spectrum of what is left.

The band is the user's, or the one where the spectral kurtosis is highest (:func:`select_band`):
the STFT-based kurtogram of Antoni and Randall, Mech. Syst. Signal Process. 20 (2006) 308-331,
sec. 3 (the spectral kurtosis of Antoni, ibid. 282-307, Eq. 13: ``SK(f) = <|X|^4>/<|X|^2>^2 - 2``,
zero for stationary Gaussian noise, large where transients recur).
"""
from __future__ import annotations

import numpy as np
from scipy.signal import butter, hilbert, sosfiltfilt, stft, welch

from axlebox._params import ParameterError

from .clock import on_clock


def _signal(x, name: str = "x") -> np.ndarray:
    x = np.asarray(x, float)
    if x.ndim != 1 or x.size < 8:
        raise ParameterError(f"{name} of shape {x.shape} is not allowed: expected a 1-D signal of "
                             "at least 8 samples")
    bad = np.flatnonzero(~np.isfinite(x))
    if bad.size:
        raise ParameterError(f"{name}[{bad[0]}] = {float(x[bad[0]])!r} is not allowed: expected finite "
                             f"samples ({bad.size} are not)")
    return x


def check_fs(fs) -> float:
    if isinstance(fs, bool) or not isinstance(fs, (int, float, np.floating, np.integer)) \
            or not np.isfinite(fs) or not fs > 0:
        raise ParameterError(f"fs = {fs!r} Hz is not allowed: expected a sampling rate > 0")
    return float(fs)


def envelope(x: np.ndarray, fs: float, band: tuple[float, float] | None = None) -> np.ndarray:
    """Envelope of ``x`` (1-D) after an optional 4th-order Butterworth band-pass ``band`` (Hz),
    run forwards and backwards (zero phase, so impulse timing is kept)."""
    fs = check_fs(fs)
    x = np.asarray(x, float) - np.mean(x)
    if band is not None:
        lo, hi = band
        if not 0 < lo < hi < fs / 2:
            raise ParameterError(f"band = {tuple(band)!r} Hz is not allowed: expected 0 < low < high "
                                 f"< fs/2 = {fs / 2:g} Hz")
        if lo < 1e-9 * fs:          # a band from 0 Hz (up to rounding): a low-pass, which is stable
            x = sosfiltfilt(butter(4, hi, btype="low", fs=fs, output="sos"), x)
        else:
            x = sosfiltfilt(butter(4, [lo, hi], btype="band", fs=fs, output="sos"), x)
    return on_clock(np.abs(hilbert(x)))       # on the shaft's clock where one is active (clock.py)


def envelope_spectrum(x: np.ndarray, fs: float, band: tuple[float, float] | None = None,
                      nperseg: int | None = None):
    """``(f, A)``: single-sided amplitude spectrum of the envelope (mean removed), Hann window.

    ``nperseg=None``: one window over the whole record (finest resolution ``fs/len(x)``).
    A shorter ``nperseg``: Welch average of 50 %-overlapping segments, resolution ``fs/nperseg``,
    with a noise floor that scatters less (``A = sqrt(2 P)`` of ``welch(scaling="spectrum")``, so
    a line of amplitude ``a`` at a bin centre reads ``a`` either way)."""
    e = envelope(x, fs, band)
    n = e.size if nperseg is None else int(nperseg)
    if not 8 <= n <= e.size:
        raise ParameterError(f"nperseg = {nperseg!r} is not allowed: expected 8 <= nperseg <= "
                             f"len(x) = {e.size}")
    f, P = welch(e, fs, window="hann", nperseg=n, noverlap=n // 2, detrend="constant",
                 scaling="spectrum")
    return f, np.sqrt(2.0 * P)


def spectral_kurtosis(x: np.ndarray, fs: float, nperseg: int):
    """``(f, SK, m2)``: the spectral kurtosis of ``x`` from its STFT (Hann window of ``nperseg``
    samples, 75 % overlap) and the mean power of each bin; DC and Nyquist bins, where the STFT of
    a real signal is real and the Gaussian value is 1 instead of 0, are dropped."""
    f, _, Z = stft(x - np.mean(x), fs, window="hann", nperseg=nperseg, noverlap=3 * nperseg // 4,
                   boundary=None, padded=False, detrend=False)
    P = np.abs(Z[1:-1]) ** 2
    m2 = P.mean(axis=1)
    SK = np.where(m2 > 0, (P ** 2).mean(axis=1) / np.where(m2 > 0, m2, 1.0) ** 2 - 2.0, -2.0)
    return f[1:-1], SK, m2


def kurtogram_levels(n: int, fs: float, min_width_hz: float | None,
                     levels: tuple[int, ...]) -> list[int]:
    """Window lengths ``N = 2**level`` of an STFT kurtogram on ``n`` samples: at least 8 windows
    in the record, bands ``2 fs / N`` at least ``min_width_hz`` wide."""
    out = []
    for lev in levels:
        N = 2 ** int(lev)
        if N > n // 8 or (min_width_hz is not None and 2 * fs / N < min_width_hz):
            continue
        out.append(N)
    return out


def select_band(x: np.ndarray, fs: float, min_width_hz: float | None = None,
                fmin: float = 0.0, levels: tuple[int, ...] = (3, 4, 5, 6, 7, 8, 9),
                max_samples: int = 2 ** 19, min_power_db: float = -60.0) -> tuple[float, float]:
    """``(lo, hi)`` Hz: the band of highest spectral kurtosis over STFT windows of ``2**level``
    samples (an STFT kurtogram).  A bin centred at ``f`` of a Hann window of ``N`` samples stands
    for the band ``f +- fs/N`` (its main lobe to the -6 dB points is about ``2 fs/N`` wide).

    ``min_width_hz``: narrower bands are not considered; the envelope of a band of width ``B``
    carries modulations up to ``B/2`` only, so pass at least twice the highest fault harmonic
    you want to see (:func:`..channel.analyse` does).  ``fmin``: bands reaching below it are
    skipped (default 0: any).  ``max_samples``: longer records are analysed on their first
    ``max_samples`` samples (52 s at 10 kHz; the spectral kurtosis is a stationary statistic and
    its estimate is already tight there).  ``min_power_db``: bins whose mean power lies further
    below the strongest bin's are skipped: there the kurtosis of filter and window edges, or of
    numerical noise, is high but nothing of the machine is left to demodulate."""
    x = _signal(x)
    fs = check_fs(fs)
    x = x[:max_samples]
    best = None
    for N in kurtogram_levels(x.size, fs, min_width_hz, levels):
        bw = fs / N
        f, SK, m2 = spectral_kurtosis(x, fs, N)
        ok = (f - bw > max(fmin, 0.0)) & (f + bw < fs / 2) & (m2 >= m2.max() * 10 ** (min_power_db / 10))
        if not ok.any():
            continue
        i = int(np.argmax(np.where(ok, SK, -np.inf)))
        if best is None or SK[i] > best[0]:
            best = (SK[i], f[i] - bw, f[i] + bw)
    if best is None:
        raise ParameterError(f"min_width_hz = {min_width_hz!r} is not allowed for a record of "
                             f"{x.size} samples at fs = {fs:g} Hz: no STFT level gives a band that "
                             "wide within (fmin, fs/2)")
    return float(best[1]), float(best[2])
