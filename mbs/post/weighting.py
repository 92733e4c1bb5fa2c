"""Frequency weightings of whole-body vibration: the ISO 2631 / EN 12299 transfer functions.

Every weighting is one analogue transfer function of ``s = j 2 pi f`` (ISO 2631-1:1997 Annex A,
Eqs. A.1-A.5; the same form in ISO 2631-4:2001 Annex A, ISO 8041 and EN 12299:2009 Annex A):

    H(s) = K Hh(s) Hl(s) Ht(s) Hs(s)
    Hh = s^2 / (s^2 + w1 s / Q1 + w1^2)                  band limit, high pass (Q1 = 1/sqrt 2)
    Hl = w2^2 / (s^2 + w2 s / Q2 + w2^2)                 band limit, low pass (Q2 = 1/sqrt 2)
    Ht = (1 + s / w3) / (1 + s / (Q4 w4) + s^2 / w4^2)   acceleration-velocity transition
    Hs = (s^2 + w5 s / Q5 + w5^2) / (s^2 + w6 s / Q6 + w6^2)   upward step (gain 1 at high f)

with ``w_i = 2 pi f_i``; an infinite ``f_i`` leaves its factor out.  Parameters (:data:`PARAMS`):

* ``Wk`` (vertical, seated), ``Wd`` (horizontal), ``Wc`` (seat back): ISO 2631-1:1997
  Table A.2, tabulated as gains in its Tables 3 and 4 (tests/test_comfort.py checks them);
* ``Wb_iso``: vertical comfort in fixed-guideway transport, ISO 2631-4:2001 Table A.1 (the
  parameters of BS 6841's W_b; ISO 8041 lists the same);
* ``Wb``: the vertical weighting EN 12299:2009 Annex A uses for its comfort indices (Q4 0.63,
  Q5 = Q6 0.8, K 0.4 on a step normalised to 1 at low frequency, i.e. 0.4 (4/2.5)^2 = 1.024 on
  the form above), as its open implementations give it; the standard's own table was not
  available here.  It differs from ``Wb_iso`` by -8 % at 4 Hz and +13 % at 16 Hz.

:func:`weigh` applies a weighting to a record exactly on the FFT grid of the record padded to
at least twice its length (no wrap-around, no bilinear warping, any sampling rate); the result is the
causal filter's response.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import fft as sp_fft

INF = math.inf


@dataclass(frozen=True)
class Weighting:
    """ISO 2631-1 Table A.2 parameters: corner frequencies (Hz), quality factors and gain."""

    f1: float
    f2: float
    f3: float
    f4: float
    Q4: float
    f5: float = INF
    Q5: float = 1.0
    f6: float = INF
    Q6: float = 1.0
    K: float = 1.0


Q_BAND = 1.0 / math.sqrt(2.0)       # Q1 = Q2: second-order Butterworth band limits

PARAMS = {
    "Wk": Weighting(0.4, 100.0, 12.5, 12.5, 0.63, 2.37, 0.91, 3.35, 0.91),
    "Wd": Weighting(0.4, 100.0, 2.0, 2.0, 0.63),
    "Wc": Weighting(0.4, 100.0, 8.0, 8.0, 0.63),
    "Wb_iso": Weighting(0.4, 100.0, 16.0, 16.0, 0.55, 2.5, 0.9, 4.0, 0.95, 1.024),
    "Wb": Weighting(0.4, 100.0, 16.0, 16.0, 0.63, 2.5, 0.8, 4.0, 0.8, 0.4 * (4.0 / 2.5) ** 2),
}


def _params(name: str) -> Weighting:
    if name not in PARAMS:
        raise ValueError(f"weighting = {name!r} is not allowed: expected one of {sorted(PARAMS)}")
    return PARAMS[name]


def response(name: str, f_hz) -> np.ndarray:
    """Complex gain H(j 2 pi f) of weighting ``name`` at ``f_hz`` (ISO 2631-1 Eqs. A.1-A.5)."""
    p = _params(name)
    s = 2j * np.pi * np.asarray(f_hz, float)
    w = {k: 2 * np.pi * getattr(p, k) for k in ("f1", "f2", "f3", "f4", "f5", "f6")}
    H = p.K * s * s / (s * s + w["f1"] * s / Q_BAND + w["f1"] ** 2)
    if math.isfinite(w["f2"]):
        H = H * w["f2"] ** 2 / (s * s + w["f2"] * s / Q_BAND + w["f2"] ** 2)
    if math.isfinite(w["f4"]):
        num = 1.0 + s / w["f3"] if math.isfinite(w["f3"]) else 1.0
        H = H * num / (1.0 + s / (p.Q4 * w["f4"]) + s * s / w["f4"] ** 2)
    if math.isfinite(w["f6"]):
        H = H * (s * s + w["f5"] * s / p.Q5 + w["f5"] ** 2) / (s * s + w["f6"] * s / p.Q6 + w["f6"] ** 2)
    return H


def gain(name: str, f_hz) -> np.ndarray:
    """``|H|`` of weighting ``name`` at ``f_hz``: the factor ISO 2631-1 Tables 3 and 4 tabulate."""
    return np.abs(response(name, f_hz))


def filtered(a, fs: float, H) -> np.ndarray:
    """The record ``a`` ((n, ...) at ``fs`` Hz, along axis 0) through the linear filter of
    complex gain ``H(f_hz)``, applied exactly on the FFT grid of the record padded to at least
    twice its length, so the output is the filter's response to the record preceded by rest (no
    wrap-around, no bilinear warping, any sampling rate)."""
    a = np.asarray(a, float)
    n = a.shape[0]
    # padded to a length of small factors: 2n itself can be a poor one (a 60 s, 50 kHz record's
    # 6,000,120 has the factor 2381 and transforms ten times slower than 6,075,000)
    m = sp_fft.next_fast_len(2 * n, real=True)
    f = np.fft.rfftfreq(m, 1.0 / fs)
    G = np.asarray(H(f))
    out = np.empty_like(a)
    # a column at a time: a long record's padded spectra are the memory (an 8 s, 50 kHz (n, 3)
    # record: 46 MB above it at once, 31 MB by column)
    for src, dst in zip(a.reshape(n, -1).T, out.reshape(n, -1).T):
        dst[:] = sp_fft.irfft(sp_fft.rfft(src, m) * G, m)[:n]
    return out


def weigh(a, fs: float, name: str) -> np.ndarray:
    """The record ``a`` ((n, ...) at ``fs`` Hz, along axis 0) weighted by ``name``
    (:func:`filtered` with :func:`response`)."""
    _params(name)
    return filtered(a, fs, lambda f: response(name, f))
