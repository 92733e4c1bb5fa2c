"""What an acquisition spoils in a channel, found before the diagnosis reads it: a dropped sensor
(a constant channel, or stretches held at one value), a quantization step as large as the signal,
and clipping at the range.

Each check is measured on the synthetic pair of :func:`.synthetic.coaxial_pair` (an outer-ring
defect and its copy, and a healthy wheelset; benchmarks/fuzz.py, "Spoiled records"), and chosen
so that no spoiling turns a healthy side faulty, the worst error:

* **constant** (:func:`check`): a channel with one value throughout carries nothing of its
  bearing: refused, "a dropped sensor".
* **quantization** (:func:`quantum`): the step ``q`` between the values a channel takes.  While
  its RMS is at least one step the quantization error is close to uniform noise of power
  ``q^2 / 12`` independent of the signal (Widrow and Kollar, *Quantization Noise*, Cambridge
  2008, ch. 4-5: the quantization theorem holds to a close approximation for a Gaussian input
  from ``sigma = q``), 10.8 dB under it, and the diagnosis reads the record as it reads noise: the
  verdicts of the synthetic pair are unchanged from 1 step of RMS up (at 0.6 step the defect is
  missed, at 0.3 the channel is mostly zeros).  Under one step the record is refused: the error
  then follows the signal, and what stays of an impulse is a few codes.
* **clipping** (:func:`clipped`): samples piled up at the channel's extreme values.  Clipping
  caps exactly what the sides are compared by, the impulses' heights (SPM's peak envelope,
  RMS, kurtosis).  The synthetic defect side clipped at 50 % of its samples still reads right, at
  70 % undecided, at 90 % the healthy side is called the real fault.  The tops of a fault's
  impulses are about a sample or two an impulse (1-3 % of the samples at BPFO of 45-300 Hz and
  10-20 kHz), so a record clipped in more than :data:`CLIP_SHARE_MAX` (1 %) of its samples has
  the clip level inside the impulses' bodies: refused; less is read, with a warning.
* **held values** (:func:`held`): a run of equal samples longer than :data:`HOLD_S` (a logger
  repeating its last reading while the sensor is away) is no vibration: the readers read around
  such runs as around NaN gaps (:mod:`axlebox.pipelines.readers`).  A live channel quantized to
  at least a step of its RMS holds a value far shorter: measured 3.5 ms for the synthetic
  wheel-rail noise at one step, 9 ms for a channel dominated by a 500 Hz resonance at 20 kHz.

DC offsets and slow drifts are not refused: every indicator is taken about the mean, the
envelope after a band-pass, the SPM's EMD puts a trend in its residue, and the synthetic pair's
verdicts hold with an offset 100 times its RMS and a drift of 10 units a second (the time
indicators then carry the drift: RMS is taken about the mean, not about a trend).
"""
from __future__ import annotations

import numpy as np

from axlebox._params import ParameterError

CLIP_SHARE_MAX = 0.01   # share of samples at the range above which a channel is refused
HOLD_S = 0.1            # s: a run of one value this long is a dropped sensor, not vibration
MIN_PILE = 3            # samples at an extreme value that make a pile-up (clipping)


def quantum(x: np.ndarray) -> float:
    """The smallest step between the distinct values of ``x`` (0 for a constant channel): a
    quantized channel's least significant bit, an unquantized one's rounding (tiny)."""
    u = np.unique(x)
    return float(np.min(np.diff(u))) if u.size > 1 else 0.0


def clipped(x: np.ndarray) -> int:
    """How many samples of ``x`` sit at a clipped extreme: at its maximum (minimum) value where
    at least :data:`MIN_PILE` samples pile up there, more than at the next value inward (an
    unclipped channel thins out towards its extremes, one sample at each where it is not
    quantized)."""
    n = 0
    u, counts = np.unique(x, return_counts=True)
    if u.size < 3:
        return 0
    for end, inward in ((-1, -2), (0, 1)):
        if counts[end] >= MIN_PILE and counts[end] > counts[inward]:
            n += int(counts[end])
    return n


def held(x: np.ndarray, n_min: int) -> np.ndarray:
    """``(k, 2)`` array of the ``[start, stop)`` sample ranges where ``x`` keeps one value for at
    least ``n_min`` samples."""
    change = np.flatnonzero(np.r_[True, x[1:] != x[:-1], True])
    starts, stops = change[:-1], change[1:]
    long = stops - starts >= max(int(n_min), 2)
    return np.c_[starts[long], stops[long]]


def check(x: np.ndarray, name: str) -> list[str]:
    """Refuses ``x`` (finite samples; ``name`` says which channel in the message) that is constant,
    quantized to a step over its RMS or clipped in more than :data:`CLIP_SHARE_MAX` of its
    samples (module docstring); returns the warnings for what is read (some clipping)."""
    lo, hi = float(np.min(x)), float(np.max(x))
    if lo == hi:
        raise ParameterError(f"{name} is constant ({lo:g} in all {x.size} samples): a dropped sensor "
                             "(or a range far too coarse); expected a signal on both sides")
    d = x - x.mean()
    rms = float(np.sqrt(np.mean(d * d)))
    q = quantum(x)
    if rms < q:
        raise ParameterError(f"{name} takes values {q:.3g} apart for an RMS of {rms:.3g}: quantized "
                             "to a step over its RMS, not allowed; expected an RMS of at least one "
                             "step (a finer range or more decimals)")
    n = clipped(x)
    if n / x.size > CLIP_SHARE_MAX:
        raise ParameterError(f"{name} is clipped at its range in {n} of {x.size} samples "
                             f"({100 * n / x.size:.2g} %, from {lo:.4g} to {hi:.4g}), not allowed: "
                             f"expected at most {100 * CLIP_SHARE_MAX:g} % (clipping cuts the "
                             "impulses' heights the sides are compared by; a wider range)")
    if n:
        return [f"{name} is clipped at its range in {n} of {x.size} samples ({100 * n / x.size:.2g} %): "
                "its impulses' heights (RMS, peak, SPM) may read low"]
    return []
