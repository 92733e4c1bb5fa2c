"""Frequency centre, mean-square frequency and frequency variance of a signal's PSD (paper Eq. 18).

With ``S(f)`` the one-sided Welch power spectral density (scipy.signal.welch, Hann, 50 % overlap,
segment mean removed):

* ``FC  = int f S df / int S df``                   (frequency centre, the paper's Ref. 25)
* ``MSF = int f^2 S df / int S df``                 (mean-square frequency)
* ``VF  = int (f - FC)^2 S df / int S df``          (Eq. 18, frequency variance)

The integrals are sums over the Welch bins (equal spacing, so ``df`` cancels); over a band
``[lo, hi]`` (``band``), over the bins with ``lo <= f <= hi`` alone: the moments of the
band-limited PSD, as an ideal band-pass would leave it (no filter's skirt in the moments).  VF is computed by
Eq. 18 itself, not as ``MSF - FC^2``: the identity holds for any quadrature that weights the
three integrals alike, but the difference loses digits when VF << FC^2 (a narrow band far from
0 Hz).  All three are independent of the signal's amplitude (``S`` scales out).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.signal import welch

from axlebox._params import ParameterError

from .envelope import _signal, check_fs
from .thresholds import check_band  # noqa: F401  (the band check lives with the thresholds)


def default_nperseg(fs: float, n: int) -> int:
    """The power of two nearest to ``fs`` (about 1 Hz resolution), halved until the record holds
    at least 8 segments (so that short records still get an averaged PSD)."""
    seg = 2 ** max(3, int(round(math.log2(fs))))
    while seg > 8 and 8 * seg > n:
        seg //= 2
    return seg


def psd(x, fs: float, nperseg: int | None = None):
    """``(f, S)``: the Welch PSD used by :func:`fc_vf` (units of x squared per Hz)."""
    x = _signal(x)
    fs = check_fs(fs)
    n = default_nperseg(fs, x.size) if nperseg is None else nperseg
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 8 <= n <= x.size:
        raise ParameterError(f"nperseg = {nperseg!r} is not allowed: expected an integer with 8 <= "
                             f"nperseg <= len(x) = {x.size} (the record is too short for that "
                             "resolution)")
    return welch(x, fs, window="hann", nperseg=int(n), noverlap=int(n) // 2, detrend="constant",
                 scaling="density")


def fc_vf(x, fs: float, nperseg: int | None = None,
          band: tuple[float, float] | None = None) -> tuple[float, float, float]:
    """``(FC, VF, MSF)`` in Hz, Hz^2, Hz^2 of the 1-D signal ``x`` sampled at ``fs`` Hz
    (Eq. 18 on the Welch PSD; ``nperseg`` samples a segment, default :func:`default_nperseg`);
    ``band`` ``(lo, hi)`` Hz: over the PSD's bins in it alone (module docstring), default all."""
    f, S = psd(x, fs, nperseg)
    band = check_band(band, fs)
    if band is not None:
        keep = (f >= band[0]) & (f <= band[1])
        if keep.sum() < 2:
            raise ParameterError(f"vf_band (--vf-band) = {band!r} is not allowed: it holds {int(keep.sum())} "
                                 f"bin(s) of the PSD ({f[1] - f[0]:.3g} Hz apart); expected a band "
                                 "of at least two")
        f, S = f[keep], S[keep]
    total = S.sum()
    if not total > 0:
        raise ParameterError("x is constant: expected a signal with a spectrum (FC and VF of "
                             "Eq. 18 divide by its power)")
    w = S / total
    FC = float(np.dot(f, w))
    VF = float(np.dot((f - FC) ** 2, w))
    MSF = float(np.dot(f * f, w))
    return FC, VF, MSF
