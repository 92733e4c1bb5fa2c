"""Computed order tracking: a record resampled to equal steps of its shaft's angle, so that a line
at a fixed multiple of the shaft speed (a bearing's BPFO is one: an order) stays one line however
the speed changes within the record (Fyfe and Munck, Mech. Syst. Signal Process. 11 (1997)
187-205; Randall, Vibration-based Condition Monitoring, Wiley 2011, sec. 3.6.4).

The shaft angle (in revolutions) comes from

* a speed record: its integral by the trapezoid rule (:func:`angle_from_speed`; exact for a
  speed linear in time between samples, as a constant acceleration is), or
* a once-per-revolution tacho: each pulse's time is where the signal rises through a threshold
  (:func:`tacho_times`; by default midway between its 1st and 99th percentiles), linearly
  interpolated between the two samples about it; between pulses the angle is the monotone cubic
  (PCHIP, Fritsch and Carlson 1980) through the pulses (:func:`angle_from_tacho`), so it never
  runs backwards.

Resampling (:func:`to_angle`): the record is first low-passed where the angle domain's Nyquist
order, taken at the lowest speed of the record, lies below the record's own Nyquist frequency
(8th-order Butterworth, run forwards and backwards: zero phase; cut-off 0.8 of that frequency),
then read at the instants the angle passes each ``1 / per_rev`` of a turn by a cubic spline
(scipy.interpolate.CubicSpline, not-a-knot).  Where the angle domain samples faster than the
record everywhere no filter is needed and none is applied: a constant-speed record resampled at
its own rate is itself.

A whole diagnosis while the speed changes reads the envelopes on the shaft's clock instead
(:mod:`.clock`): the record stays in time, only its envelopes are resampled.

The envelope in orders (:func:`envelope_orders`): a fault's impulses ring the structure's
resonances, fixed in Hz whatever the speed, so the band-pass and the Hilbert envelope are taken
in time (:func:`.envelope.envelope`) and the envelope, whose lines are the fault's orders, is
what is resampled to the angle (order-tracked envelope analysis: Borghesani, Ricci, Chatterton
and Pennacchi, Mech. Syst. Signal Process. 38 (2013) 23-35, sec. 2).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline, PchipInterpolator
from scipy.signal import butter, sosfiltfilt, welch

from axlebox._params import ParameterError

from .clock import invert
from .envelope import _signal, check_fs, envelope

#: the anti-alias filter's cut-off over the angle domain's Nyquist frequency at the lowest speed
CUTOFF = 0.8
#: a tacho interval this much longer or shorter than the median of its neighbours is a missing or
#: an extra pulse (a metro's speed changes by a few per cent a turn at most)
PULSE_JUMP = 1.5


def angle_from_speed(t, f_shaft) -> np.ndarray:
    """Shaft angle (revolutions, 0 at ``t[0]``) of a speed record ``f_shaft`` (Hz, > 0) at the
    strictly increasing instants ``t`` (s): the trapezoid rule's running integral."""
    t, f = np.asarray(t, float), np.asarray(f_shaft, float)
    if t.ndim != 1 or t.shape != f.shape or t.size < 2:
        raise ParameterError(f"speed record of shape {f.shape} at times of shape {t.shape} is not "
                             "allowed: expected two 1-D arrays of the same length, at least 2")
    step = np.diff(t)
    if not np.all(np.isfinite(t)) or not np.all(step > 0):
        i = int(np.flatnonzero(~(step > 0))[0]) if np.any(~(step > 0)) else 0
        raise ParameterError(f"speed time[{i + 1}] = {float(t[i + 1])!r} is not allowed: expected times "
                             "increasing without a gap back")
    bad = np.flatnonzero(~(np.isfinite(f) & (f > 0)))
    if bad.size:
        raise ParameterError(f"speed[{bad[0]}] = {float(f[bad[0]])!r} Hz is not allowed: expected a shaft "
                             f"speed > 0 ({bad.size} samples are not)")
    return np.concatenate([[0.0], np.cumsum(0.5 * (f[1:] + f[:-1]) * step)])


def tacho_times(x, fs: float, threshold: float | None = None) -> np.ndarray:
    """The instants (s) a once-per-revolution tacho ``x`` rises through ``threshold`` (default:
    midway between its 1st and 99th percentiles), each linearly interpolated between the two
    samples about it."""
    x, fs = _signal(x, "tacho"), check_fs(fs)
    if threshold is None:
        lo, hi = np.percentile(x, [1.0, 99.0])
        threshold = 0.5 * (lo + hi)
    i = np.flatnonzero((x[:-1] < threshold) & (x[1:] >= threshold))
    if i.size < 3:
        raise ParameterError(f"tacho has {i.size} pulses rising through {threshold:g}: expected at "
                             "least 3 (one a revolution)")
    return (i + (threshold - x[i]) / (x[i + 1] - x[i])) / fs


def angle_from_tacho(pulses, t) -> np.ndarray:
    """Shaft angle (revolutions, 0 at the first pulse) at instants ``t`` (s) within the pulses'
    span, one turn a pulse; a missing or an extra pulse (an interval :data:`PULSE_JUMP` times
    longer or shorter than the median of its neighbours) is refused, naming it."""
    p = np.asarray(pulses, float)
    gaps = np.diff(p)
    for k in range(gaps.size):
        near = np.median(gaps[max(0, k - 3):k + 4])
        if not (near / PULSE_JUMP <= gaps[k] <= near * PULSE_JUMP):
            what = "missing" if gaps[k] > near else "an extra"
            raise ParameterError(f"tacho pulse {k + 1} at {p[k + 1]:.6g} s is not allowed: its "
                                 f"interval {gaps[k]:.4g} s against {near:.4g} s about it says a "
                                 f"pulse is {what}")
    t = np.asarray(t, float)
    if t.min() < p[0] or t.max() > p[-1]:
        raise ParameterError(f"time {t.min() if t.min() < p[0] else t.max():.6g} s is not allowed: "
                             f"outside the tacho's pulses, {p[0]:.6g} to {p[-1]:.6g} s")
    return PchipInterpolator(p, np.arange(p.size, dtype=float))(t)


@dataclass(frozen=True)
class AngleRecord:
    """A record at equal shaft-angle steps: ``x`` (samples ``1 / per_rev`` of a turn apart, the
    first at ``angle0`` revolutions) and ``t`` (s, the instant of each)."""

    x: np.ndarray
    per_rev: int
    angle0: float
    t: np.ndarray

    @property
    def turns(self) -> float:
        return self.x.size / self.per_rev


def to_angle(x, fs: float, angle, per_rev: int) -> AngleRecord:
    """``x`` (sampled at ``fs``, its shaft at ``angle`` revolutions at each sample, increasing)
    resampled to ``per_rev`` samples a turn (module docstring: the anti-alias filter and the
    interpolation)."""
    x, fs = _signal(x), check_fs(fs)
    a = np.asarray(angle, float)
    if a.shape != x.shape or not np.all(np.diff(a) > 0):
        raise ParameterError(f"angle of shape {a.shape} is not allowed: expected one increasing "
                             f"angle a sample of the record ({x.shape})")
    if isinstance(per_rev, bool) or not isinstance(per_rev, (int, np.integer)) or per_rev < 8:
        raise ParameterError(f"per_rev = {per_rev!r} is not allowed: expected a whole number of "
                             "samples a turn, at least 8")
    t = np.arange(x.size) / fs
    f_min = float(np.min(np.diff(a))) * fs             # the lowest speed, turns/s
    nyquist = 0.5 * per_rev * f_min                     # the angle domain's there, in Hz
    if nyquist < 0.5 * fs * (1.0 - 1e-9):              # (rounding of the angle's steps aside)
        x = sosfiltfilt(butter(8, CUTOFF * nyquist, fs=fs, output="sos"), x)
    k = np.arange(np.ceil(a[0] * per_rev), np.floor(a[-1] * per_rev) + 1)
    t_k = np.interp(k / per_rev, a, t)                  # a is increasing: its inverse, piecewise
    # the instants refined on the angle's own spline, then the record read there
    t_k = invert(CubicSpline(t, a), k / per_rev, t_k, t)
    return AngleRecord(CubicSpline(t, x)(t_k), int(per_rev), float(k[0] / per_rev), t_k)


def envelope_orders(x, fs: float, angle, band: tuple[float, float] | None = None,
                    per_rev: int = 256, turns: float | None = None):
    """``(orders, A)``: the amplitude spectrum, in shaft orders, of ``x``'s envelope (band-pass
    ``band`` Hz and Hilbert magnitude in time) resampled to ``per_rev`` samples a turn; Welch
    average of 50 %-overlapping Hann segments of ``turns`` turns (None: one over the record;
    resolution ``1 / turns`` orders), ``A = sqrt(2 P)`` as :func:`.envelope.envelope_spectrum`."""
    rec = to_angle(envelope(_signal(x), check_fs(fs), band), fs, angle, per_rev)
    n = rec.x.size if turns is None else int(round(turns * per_rev))
    if not 8 <= n <= rec.x.size:
        raise ParameterError(f"turns = {turns!r} is not allowed: expected at most the record's "
                             f"{rec.turns:.4g} turns and at least 8 samples")
    o, P = welch(rec.x, per_rev, window="hann", nperseg=n, noverlap=n // 2, detrend="constant",
                 scaling="spectrum")
    return o, np.sqrt(2.0 * P)
