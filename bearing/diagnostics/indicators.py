"""Time-___domain indicators of one channel: RMS, peak, kurtosis, crest factor.

All are taken about the mean (an accelerometer's offset, e.g. a MEMS sensor's gravity, is not
vibration): ``rms = sqrt(<(x - <x>)^2>)``, ``peak = max |x - <x>|``, ``crest = peak / rms``, and
Pearson's kurtosis ``<(x - <x>)^4> / rms^4`` (3 for Gaussian noise, 1.5 for a sine, large for
sparse impulses; scipy.stats.kurtosis with ``fisher=False``).
"""
from __future__ import annotations

import numpy as np
from scipy.stats import kurtosis

from .envelope import _signal


def time_indicators(x) -> dict[str, float]:
    """``{"rms", "peak", "kurtosis", "crest"}`` of the 1-D signal ``x`` (its units for rms and
    peak, m/s^2 for accelerations; kurtosis and crest are ratios).  A constant signal has no
    kurtosis or crest: both are NaN there."""
    x = _signal(x)
    d = x - x.mean()
    rms = float(np.sqrt(np.mean(d * d)))
    peak = float(np.max(np.abs(d)))
    if rms == 0.0:
        return {"rms": 0.0, "peak": 0.0, "kurtosis": float("nan"), "crest": float("nan")}
    return {"rms": rms, "peak": peak, "kurtosis": float(kurtosis(d, fisher=False, bias=True)),
            "crest": peak / rms}
