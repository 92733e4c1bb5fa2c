"""The shaft's clock: envelopes read at equal steps of the shaft's angle while the speed changes.

A fault's impulses ring the structure's resonances, fixed in Hz whatever the speed, so a record's
bands (spectral kurtosis), its band-passes and Hilbert envelopes, its RMS, SPM and impulse
onsets stay in time; only the envelope, whose lines are the fault's orders, is resampled to the
angle (order-tracked envelope analysis: Borghesani, Ricci, Chatterton and Pennacchi, Mech. Syst.
Signal Process. 38 (2013) 23-35, sec. 2).  Resampling the raw record instead moves each resonance
with the speed, so a band picked on the whole record holds it only part of the time and a copy's
impulses lose their coherence with their source (the accelerating car, benchmarks/README.md).

Inside ``with angle_clock(angle, fs):`` every envelope of a record of that many samples
(:func:`axlebox.bearing.diagnostics.envelope.envelope`) comes back resampled to as many samples
at equal angle steps over the record's angle span, the same rate ``fs``: a record the shaft would
have given at its mean speed ``f_mean`` throughout, so every line at an order ``k`` of the shaft
lies at ``k f_mean`` and the analysis reads it as at a constant speed.  Interpolation: cubic spline
(scipy CubicSpline, not-a-knot) at the instants the angle passes each step (the angle's own spline
inverted by Newton); anti-alias: where the lowest speed samples the angle slower than the record
(``f_min < f_mean``), an 8th-order zero-phase Butterworth low-pass at :data:`CUTOFF` of
``f_min / f_mean`` times the record's Nyquist frequency first.
"""
from __future__ import annotations

from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.signal import butter, sosfiltfilt

from axlebox._params import ParameterError

#: the anti-alias filter's cut-off over the lowest speed's Nyquist frequency
CUTOFF = 0.8


@dataclass(frozen=True)
class Clock:
    n: int
    t: np.ndarray          # the record's instants (s)
    t_k: np.ndarray        # the instants of equal angle steps
    sos: np.ndarray | None  # the anti-alias filter, None where none is needed
    f_mean: float          # turns/s


_CLOCK: ContextVar[Clock | None] = ContextVar("angle_clock", default=None)


def invert(spline, target, t0, t, iters: int = 3) -> np.ndarray:
    """Newton on ``spline(t) = target`` from ``t0`` (the piecewise-linear inverse), kept inside
    the record."""
    d = spline.derivative()
    tk = t0
    for _ in range(iters):
        tk = np.clip(tk - (spline(tk) - target) / d(tk), t[0], t[-1])
    return tk


def make(angle, fs: float) -> Clock:
    """The clock of a record at ``fs`` whose shaft is at ``angle`` (turns, increasing) at each
    sample."""
    a = np.asarray(angle, float)
    if a.ndim != 1 or a.size < 8 or not np.all(np.diff(a) > 0):
        raise ParameterError(f"angle of shape {a.shape} is not allowed: expected one increasing angle "
                             "a sample, at least 8")
    n = a.size
    t = np.arange(n) / fs
    f_mean = (a[-1] - a[0]) * fs / (n - 1)
    target = np.linspace(a[0], a[-1], n)
    t_k = invert(CubicSpline(t, a), target, np.interp(target, a, t), t)
    ratio = float(np.min(np.diff(a))) * fs / f_mean
    sos = butter(8, CUTOFF * ratio * fs / 2, fs=fs, output="sos") if ratio < 1.0 - 1e-9 else None
    return Clock(n, t, t_k, sos, float(f_mean))


@contextmanager
def angle_clock(angle, fs: float):
    """Envelopes of records of ``len(angle)`` samples on the shaft's clock within (module
    docstring); yields the :class:`Clock`."""
    token = _CLOCK.set(make(angle, fs))
    try:
        yield _CLOCK.get()
    finally:
        _CLOCK.reset(token)


def on_clock(env: np.ndarray) -> np.ndarray:
    """``env`` resampled to the active clock (unchanged where none is active or its length is not
    the clock's record's)."""
    c = _CLOCK.get()
    if c is None or env.size != c.n:
        return env
    if c.sos is not None:
        env = sosfiltfilt(c.sos, env)
    return CubicSpline(c.t, env)(c.t_k)
