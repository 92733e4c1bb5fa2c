"""A random record of a one-sided PSD on the grid of one inverse FFT: the track's
irregularities (:mod:`.irregularity`) and the wheels' roughness (:mod:`.roughness`) alike.

The record is ``z(s) = sum_k sqrt(2 S_k dOmega) cos(Omega_k s + phi_k)``, ``Omega_k = k dOmega``
the bins of the FFT of ``n`` points over the record's period ``2 pi / dOmega``, with uniform random
phases ``phi_k``.  ``S_k dOmega`` is the integral of S over bin k cut to the band, by 4-point
Gauss-Legendre (not S at the bin's centre: S falls as Omega^-2 to Omega^-4, and the centre
value would miss the band's variance by several per cent on short records).  One inverse FFT
gives the record and another its exact slope on the grid.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.fft import irfft

_GL_X, _GL_W = np.polynomial.legendre.leggauss(4)


def harmonics(spectrum, W_lo: float, W_hi: float, dW: float, rng: np.random.Generator):
    """FFT bins k overlapping [W_lo, W_hi] (rad/m), amplitudes sqrt(2 int_bin S) and random
    phases from ``rng``; ``spectrum(W)`` the one-sided PSD, vectorised."""
    k = np.arange(max(1, math.floor(W_lo / dW - 0.5)), math.ceil(W_hi / dW + 0.5) + 1)
    lo = np.maximum((k - 0.5) * dW, W_lo)
    hi = np.minimum((k + 0.5) * dW, W_hi)
    keep = hi > lo
    k, lo, hi = k[keep], lo[keep], hi[keep]
    mid, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
    power = half * (spectrum(mid[:, None] + half[:, None] * _GL_X) @ _GL_W)
    return k, np.sqrt(2 * power), rng.uniform(0.0, 2 * np.pi, k.size)


def record(k, amp, phase, n: int, dW: float):
    """``(values, slopes)`` on the ``n`` points of the grid: the harmonics ``k, amp, phase``
    (:func:`harmonics`) summed by inverse FFT, and their slope d/ds."""
    X = np.zeros(n // 2 + 1, dtype=complex)
    X[k] = 0.5 * n * amp * np.exp(1j * phase)    # irfft: x_j = (2/n) Re sum X_k e^(2 pi i jk/n)
    return irfft(X, n), irfft(1j * dW * np.arange(X.size) * X, n)
