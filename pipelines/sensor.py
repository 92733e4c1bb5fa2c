"""The measurement chain of an axle-box accelerometer: what the on-board system records of the
housing's motion.

Three stages, each with the figures of typical hardware (``[sensors]`` of the vehicle config):

1. The accelerometer on its stud: a base-excited single-degree-of-freedom resonance, relative
   response ``H_r = 1 / (1 - (f/f_n)^2 + j f / (Q f_n))``, mounted resonance ``f_n`` about
   25 kHz for an industrial IEPE accelerometer (e.g. PCB 603C01 datasheet: 25 kHz mounted
   resonance, 0.5 Hz to 10 kHz within +-3 dB); ``Q`` of a lightly damped piezo element (30,
   assumed: +29.5 dB at resonance).
2. Its electrical low end: a first-order high-pass at ``highpass_hz`` (0.5 Hz, the same
   datasheet's -3 dB point), ``j f / f_c / (1 + j f / f_c)``.
3. The acquisition at ``fs_hz`` (the paper's on-board system: 10 kHz): a linear-phase FIR
   anti-alias filter flat to ``passband x fs`` and stopping from ``fs / 2`` (sigma-delta
   converters' decimation filters: pass band to about 0.45 of the output rate, stop band from
   half of it, e.g. TI ADS1278 0.453 f_DATA), then every k-th sample.  Its fixed group delay,
   the same on every channel, is taken out so the samples stay on the model's time axis.

Stages 1-2 are applied exactly on the FFT grid of the zero-padded record (no wrap-around: the
record is padded to at least twice its length); stage 3 by a Kaiser-window FIR (``scipy.signal``)
computed at the kept samples only.
"""
from __future__ import annotations

import dataclasses

import numpy as np
from scipy import signal

from axlebox._params import ParameterError
from axlebox.mbs.post.weighting import filtered

STOPBAND_DB = 80.0      # attenuation from fs/2 on: aliases below 1e-4 of what is filtered out


def response(f_hz, resonance_hz: float, q: float, highpass_hz: float) -> np.ndarray:
    """Complex gain of the mounted accelerometer (stages 1 and 2) at frequencies ``f_hz``."""
    r = np.asarray(f_hz, float) / resonance_hz
    H = 1.0 / (1.0 - r * r + 1j * r / q)
    if highpass_hz > 0:
        s = 1j * np.asarray(f_hz, float) / highpass_hz
        H = H * s / (1.0 + s)
    return H


def antialias(fs_in: float, fs_out: float, passband: float) -> np.ndarray:
    """Linear-phase low-pass FIR taps at ``fs_in``: flat to ``passband x fs_out``, at least
    ``STOPBAND_DB`` down from ``fs_out / 2``."""
    edge, stop = passband * fs_out, 0.5 * fs_out
    n, beta = signal.kaiserord(STOPBAND_DB, (stop - edge) / (0.5 * fs_in))
    n += 1 - n % 2                                   # odd: a whole-sample group delay
    return signal.firwin(n, 0.5 * (edge + stop), window=("kaiser", beta), fs=fs_in)


def measure(a: np.ndarray, fs_in: float, s) -> np.ndarray:
    """What the chain ``s`` (the ``[sensors]`` section, mbs/vehicle/config.py Sensors) records of the
    accelerations ``a`` ((t, ...) at ``fs_in``): the samples at ``s.fs_hz`` (every k-th instant
    of the input)."""
    a = np.asarray(a, float)
    k = fs_in / s.fs_hz
    if k < 2 or abs(k - round(k)) > 1e-9:
        raise ParameterError(f"sensors.fs_hz = {s.fs_hz:g} is not allowed: expected the run's "
                             f"output rate {fs_in:g} Hz over a whole number >= 2")
    k = int(round(k))
    n = a.shape[0]
    x = filtered(a, fs_in, lambda f: response(f, s.resonance_hz, s.resonance_q, s.highpass_hz))
    h = antialias(fs_in, s.fs_hz, s.passband)
    # the kept samples only (polyphase, k times less work and memory than filtering every one):
    # the full convolution's samples d, d + k, ... (d the group delay) are those k q, k (q + 1), ...
    # of the taps delayed by p, d + p = k q
    d = (h.size - 1) // 2
    p = (-d) % k
    q = (d + p) // k
    y = signal.upfirdn(np.r_[np.zeros(p), h], x, 1, k, axis=0)
    return y[q:q + (n + k - 1) // k].copy()       # a copy: the slice would keep all of y alive


def decimate_run(run, fs_in: float, s):
    """The run as the acquisition at ``s.fs_hz`` records it: its sensors through
    :func:`measure`, its time and other outputs at every k-th instant."""
    k = int(round(fs_in / s.fs_hz))
    sensors = {name: measure(a, fs_in, s) for name, a in run.sensors.items()}
    sub = {f: getattr(run, f)[::k] for f in ("time", "wheels", "elements", "bearings")
           if getattr(run, f) is not None}
    return dataclasses.replace(run, sensors=sensors, **sub)
