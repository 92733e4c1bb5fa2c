"""Envelope spectrum: the standard demodulation for bearing fault impulses (Randall and Antoni,
Mech. Syst. Signal Process. 25 (2011) 485-520, sec. 3): band-pass around the resonance the
impulses excite, take the magnitude of the analytic signal (Hilbert), remove its mean, and
take the amplitude spectrum of what is left."""
from __future__ import annotations

import numpy as np
from scipy.signal import butter, hilbert, sosfiltfilt


def envelope(x: np.ndarray, fs: float, band: tuple[float, float] | None = None) -> np.ndarray:
    """Envelope of ``x`` (1-D) after an optional 4th-order Butterworth band-pass ``band`` (Hz)."""
    x = np.asarray(x, float) - np.mean(x)
    if band is not None:
        lo, hi = band
        if not 0 < lo < hi < fs / 2:
            raise ValueError(f"band = {band!r} is not allowed: expected 0 < low < high < fs/2 "
                             f"= {fs / 2:g} Hz")
        x = sosfiltfilt(butter(4, [lo, hi], btype="band", fs=fs, output="sos"), x)
    return np.abs(hilbert(x))


def envelope_spectrum(x: np.ndarray, fs: float, band: tuple[float, float] | None = None):
    """``(f, A)``: single-sided amplitude spectrum of the envelope (mean removed), Hann window."""
    e = envelope(x, fs, band)
    e = e - e.mean()
    w = np.hanning(len(e))
    A = 2 * np.abs(np.fft.rfft(e * w)) / w.sum()
    return np.fft.rfftfreq(len(e), 1 / fs), A
