"""Lines at whole multiples of the shaft's rate: the wheel's (or the rotor's), never a bearing's.

A wheel flat strikes the rail once a wheel turn, so both axle boxes of its wheelset see an impulse
train at the wheel's rate ``f_w``: its envelope spectrum holds ``f_w, 2 f_w, 3 f_w ...`` (a comb).
A polygonal wheel of order ``n`` shakes them at ``n f_w``, a line in the acceleration's own
spectrum (metro wheels' dominant orders: 6-8, Shock and Vibration 2019, 1538273; 7-9, Machines 13
(2025) 587; shorter-wave polygons reach higher orders). On a rotor rig the same orders come from
unbalance and misalignment. The DTRB's orders are not whole numbers (BPFO 8.72, BPFI 11.28, 2 BSF
7.57 times the shaft; FTF 0.436), nor are a ball bearing's (CWRU 6205: 3.585, 5.415, 4.714), so a
line at a whole order is never read as a bearing's: :func:`.faultlines.mask_sidebands` un-detects
a fault line found on a shaft harmonic, and this module names what stands there.

:func:`wheel_orders` searches ``k f_shaft`` for ``k = 1..K`` in one amplitude spectrum, each in the
window ``|f - k f_shaft| <= max(df, 0.005 k f_shaft)`` (the wheel turns at the shaft's rate: no
slip, only the record's speed drift), against the median floor of the ring beside it and the
false-alarm threshold of :func:`.faultlines.window_threshold_db` at ``p_fa / K`` per window (so
that noise alone names a wheel line in at most ``p_fa`` of records, over all ``K`` windows;
``p_fa`` is the criterion's ``shaft_p_fa``, 1e-3 by default: one record in a thousand).
The window's highest bin must be a narrow peak, ``NARROW`` times the bins two away on either
side (a steady line's Hann main lobe falls at least threefold there, whatever its offset from
the bin; the crest of a structural resonance does not: the healthy car's spectra hold such crests
at whole orders by chance), not the skirt of a line beside the window, and lie
nearer ``k f_shaft`` than any harmonic of a bearing line detected in the same spectrum (BPFO's
fourth harmonic, 34.88 orders, lies within a bin of 35 at 40 km/h): those keep their peaks.
Orders closer than five bins apart cannot be told from their neighbours' lobes: then nothing
is searched.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.signal import welch

from .thresholds import Criterion
from .faultlines import _window, is_peak, welch_averages

MAX_ORDER = 40          # a polygon's orders reach 30 (module docstring); a flat's comb, its first 40
NARROW = 2.0            # a line's peak over the bins two away: a Hann main lobe's is 3 or more


def wheel_orders(f, A, shaft_hz: float, n_avg: float = 1.0, max_order: int = MAX_ORDER,
                 p_fa: float = Criterion.shaft_p_fa, taken=()) -> tuple[int, ...]:
    """The orders ``k`` (1..``max_order``, up to the spectrum's top) whose line ``k shaft_hz``
    stands over its floor in the amplitude spectrum ``(f, A)`` (equally spaced from 0 Hz) of
    ``n_avg`` independent averages (module docstring): the window's highest bin must be a peak
    (not the skirt of a line beside the window) and lie nearer ``k shaft_hz`` than any of
    ``taken`` (Hz: the bearing's detected lines and harmonics, which keep their peaks)."""
    f = np.asarray(f, float)
    A = np.asarray(A, float)
    df = f[1] - f[0]
    if shaft_hz < 5 * df:
        return ()
    K = min(int(max_order), int((f[-1] - shaft_hz) // shaft_hz))
    out = []
    for k in range(1, K + 1):
        fk = k * shaft_hz
        win, floor, thr = _window(f, A, fk, max(df, 0.005 * fk), df, n_avg, p_fa / max(K, 1), None)
        i = int(win[np.argmax(A[win])])
        peak = is_peak(A, i) and A[i] >= NARROW * max(A[max(i - 2, 0)], A[min(i + 2, A.size - 1)])
        mine = all(abs(f[i] - fk) < abs(f[i] - g) for g in taken)
        if peak and mine and floor > 0 and 20 * math.log10(max(A[i], 1e-300) / floor) >= thr:
            out.append(k)
    return tuple(out)


def spectrum_orders(x, fs: float, shaft_hz: float, max_order: int = MAX_ORDER,
                    p_fa: float = Criterion.shaft_p_fa) -> tuple[int, ...]:
    """:func:`wheel_orders` in the acceleration's own amplitude spectrum (Welch, Hann segments of
    ten shaft turns, or the whole record where shorter): a polygon's line."""
    n = int(np.asarray(x).size)
    seg = min(n, int(round(10.0 * fs / shaft_hz)))
    f, P = welch(x, fs, nperseg=seg)
    return wheel_orders(f, np.sqrt(P), shaft_hz, welch_averages(n, seg), max_order, p_fa)


def text(envelope: tuple[int, ...], spectrum: tuple[int, ...]) -> str:
    """``"1x, 2x, 3x in the envelope; 20x in the spectrum"``, empty where there are none."""
    parts = []
    for orders, where in ((envelope, "in the envelope"), (spectrum, "in the spectrum")):
        if orders:
            parts.append(", ".join(f"{k}x" for k in orders) + " " + where)
    return "; ".join(parts)
