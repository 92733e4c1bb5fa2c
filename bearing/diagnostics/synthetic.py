"""Synthetic axle-box signals with known answers, for tests, benchmarks and trying the criterion.

The bearing-signal model of Antoni and Randall (J. Vib. Acoust. 125 (2003) 282-289): an
outer-ring defect hits at the fault rate, each period jittered by 1-2 % (rollers slip), and every
hit rings a structural resonance.  The coaxial pseudo-fault (the paper's mechanism): the other
side of the wheelset receives the same hits later (the lag), through the wheelset's bending
(the paper: energy near its second bending mode, 546 Hz), attenuated.  Wheel-rail excitation is
broadband and low-frequency: Gaussian noise low-passed at 1 kHz.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.signal import butter, lfilter, resample_poly, sosfilt


def resonance(x, fs: float, f: float, zeta: float) -> np.ndarray:
    """``x`` through a single mode of frequency ``f`` (Hz) and damping ratio ``zeta``: the
    impulse response ``r^n sin(w_d n)`` with ``r = exp(-zeta w / fs)``."""
    w = 2 * math.pi * f / fs
    r = math.exp(-zeta * w)
    return lfilter([0.0, r * math.sin(w * math.sqrt(1 - zeta ** 2))],
                   [1.0, -2 * r * math.cos(w * math.sqrt(1 - zeta ** 2)), r * r], x)


def impulse_train(n: int, fs: float, f_fault: float, rng, jitter: float = 0.01,
                  slip: float = 0.0, start_s: float = 0.005) -> np.ndarray:
    """``n`` samples of unit hits at ``f_fault (1 - slip)`` Hz, each period scaled by
    ``1 + jitter N(0, 1)``."""
    x = np.zeros(n)
    period = 1.0 / (f_fault * (1 - slip))
    t = start_s
    while t < n / fs:
        x[int(t * fs)] += 1.0
        t += period * (1 + jitter * rng.standard_normal())
    return x


def wheel_rail_noise(n: int, fs: float, rng, f_cut: float = 1000.0) -> np.ndarray:
    """Unit-variance Gaussian noise through an 8th-order Butterworth low-pass at ``f_cut``."""
    x = sosfilt(butter(8, f_cut, fs=fs, output="sos"), rng.standard_normal(n))
    return x / x.std()


def coaxial_pair(T: float, fs: float, f_fault: float, rng, *, amplitude: float = 1.0,
                 f_res: float = 600.0, f_bend: float = 546.0, zeta: float = 0.05,
                 delay_s: float = 1.2e-3, gain: float = 0.3, noise: float = 0.5,
                 jitter: float = 0.01) -> tuple[np.ndarray, np.ndarray]:
    """``(defect side, healthy side)`` over ``T`` s: the defect side rings ``f_res`` with RMS
    ``amplitude`` at every hit; the healthy side carries the same response ``delay_s`` later,
    through the ``f_bend`` mode, at ``gain`` times its RMS; both sides get their own wheel-rail
    noise of RMS ``noise`` (``amplitude = 0``: noise only, a healthy wheelset)."""
    n = int(round(T * fs))
    a = resonance(impulse_train(n, fs, f_fault, rng, jitter), fs, f_res, zeta)
    a *= amplitude / max(a.std(), 1e-300)
    b = resonance(np.roll(a, int(round(delay_s * fs))), fs, f_bend, zeta)
    b *= gain * amplitude / max(b.std(), 1e-300)
    return (a + noise * wheel_rail_noise(n, fs, rng), b + noise * wheel_rail_noise(n, fs, rng))


def swept_coaxial_pair(T: float, fs: float, order: float, f0: float, f1: float, rng, **kw
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`coaxial_pair` while the shaft speeds up from ``f0`` to ``f1`` Hz at a constant rate
    over ``T`` s: a hit every ``1 / order`` of a turn (each ``jitter`` of a period off),
    ``(defect side, healthy side, angle)``, the shaft's angle in revolutions at each sample
    (:func:`angle_coaxial_pair` on that angle; ``kw`` as there)."""
    n = int(round(T * fs))
    t = np.arange(n) / fs
    angle = f0 * t + 0.5 * (f1 - f0) / T * t ** 2
    return (*angle_coaxial_pair(angle, fs, order, rng, **kw), angle)


def angle_coaxial_pair(angle, fs: float, order: float, rng, *, f_res: float = 600.0,
                       f_bend: float = 546.0, zeta: float = 0.05, delay_s: float = 1.2e-3,
                       gain: float = 0.3, noise: float = 0.5, jitter: float = 0.01,
                       amplitude: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """:func:`coaxial_pair` on a shaft at ``angle`` (revolutions, increasing) at each sample, any
    speed profile: a hit every ``1 / order`` of a turn, each ``jitter`` of a period off its place
    (not accumulated: the defect is fixed on the ring), ``(defect side, healthy side)``."""
    angle = np.asarray(angle, float)
    n = angle.size
    k = np.arange(1, int(angle[-1] * order))
    hits = np.zeros(n)
    hits[np.clip(np.searchsorted(angle, (k + jitter * rng.standard_normal(k.size)) / order), 0,
                 n - 1)] = 1.0
    a = resonance(hits, fs, f_res, zeta)
    a = a / max(a.std(), 1e-300) * amplitude
    b = resonance(np.roll(a, int(round(delay_s * fs))), fs, f_bend, zeta)
    b *= gain * amplitude / max(b.std(), 1e-300)
    return a + noise * wheel_rail_noise(n, fs, rng), b + noise * wheel_rail_noise(n, fs, rng)


def both_sides_pair(T: float, fs: float, f_fault: float, rng, *, amplitude=(1.0, 1.0),
                    offset_s: float = 0.0, **kw) -> tuple[np.ndarray, np.ndarray]:
    """``(left, right)`` of a wheelset with a fault on each side (beyond the paper): each side
    rings its own hits (RMS ``amplitude[side]``) and carries the other's as :func:`coaxial_pair`
    does, the right side's hits ``offset_s`` after the left's; ``kw`` as :func:`coaxial_pair`
    (the noise is added once per side)."""
    noise = kw.pop("noise", 0.5)
    n = int(round(T * fs))
    own_l, copy_r = coaxial_pair(T, fs, f_fault, rng, amplitude=amplitude[0], noise=0.0, **kw)
    own_r, copy_l = coaxial_pair(T, fs, f_fault, rng, amplitude=amplitude[1], noise=0.0, **kw)
    k = int(round(offset_s * fs))
    own_r, copy_l = np.roll(own_r, k), np.roll(copy_l, k)
    return (own_l + copy_l + noise * wheel_rail_noise(n, fs, rng),
            own_r + copy_r + noise * wheel_rail_noise(n, fs, rng))


# ------------------------------------------------------------------ what an acquisition spoils
# The ways a real acquisition spoils a record (issue 57, item 1), each a function of the channel
# and its parameters, for the property-based tests and benchmarks/fuzz.py.


def quantize(x, step: float) -> np.ndarray:
    """``x`` rounded to a multiple of ``step``: an ADC's least significant bit, or samples
    stored to a few decimals (``step = 10**-decimals``)."""
    return np.round(np.asarray(x, float) / step) * step


def adc(x, bits: int, full_scale: float) -> np.ndarray:
    """``x`` through an ideal ADC of ``bits`` bits on ``+- full_scale``: clipped at the range
    (the codes' ends) and quantized to ``2 full_scale / 2**bits``."""
    step = 2.0 * full_scale / 2 ** bits
    return np.clip(quantize(x, step), -full_scale, full_scale - step)


def clip(x, level: float) -> np.ndarray:
    """``x`` clipped at ``+- level`` (an amplifier or ADC saturating)."""
    return np.clip(np.asarray(x, float), -level, level)


def drift(x, fs: float, offset: float, slope: float = 0.0, amplitude: float = 0.0,
          period_s: float = 60.0) -> np.ndarray:
    """``x`` plus a DC ``offset``, a linear drift of ``slope`` units a second and a slow
    sinusoidal wander of ``amplitude`` and period ``period_s`` (a sensor's bias settling, a
    temperature's swing)."""
    t = np.arange(np.asarray(x).size) / fs
    return np.asarray(x, float) + offset + slope * t + amplitude * np.sin(2 * np.pi * t / period_s)


def hold(x, start: int, n: int, value: float | None = None) -> np.ndarray:
    """``x`` with samples ``start .. start + n`` held at ``value`` (default: the sample before,
    a logger repeating its last reading while the sensor is away)."""
    y = np.array(x, float)
    start = int(np.clip(start, 0, y.size))
    y[start:start + n] = y[max(start - 1, 0)] if value is None else value
    return y


def gaps(x, starts, length: int) -> np.ndarray:
    """``x`` with ``length`` samples from each of ``starts`` set to NaN (a logger's lost
    packets)."""
    y = np.array(x, float)
    for s in np.atleast_1d(starts):
        y[int(s):int(s) + length] = np.nan
    return y


#: structural modes (Hz, damping ratio) of :func:`spall_record`: three housing modes in the
#: band a 10 kHz acquisition keeps
SPALL_MODES = ((700.0, 0.05), (2300.0, 0.03), (3700.0, 0.02))
SPALL_EVENTS = ("steps", "dip", "single")


def spall_record(T: float, fs: float, f_fault: float, dt_s: float, rng, *, events: str = "steps",
                 up: int = 20, rise_s: float = 5e-5, impact: float = 0.5,
                 modes=SPALL_MODES, background: float = 1.0, noise: float = 0.3, white: float = 0.02,
                 jitter: float = 0.01, start_s: float = 0.01) -> tuple[np.ndarray, np.ndarray]:
    """``(x, entries)``: ``T`` s at ``fs`` of a ring carrying a local defect the rollers cross in
    ``dt_s``, one pass a fault period ``1 / f_fault`` (each ``jitter`` of a period off), and
    the instants (s) each pass begins.  The ring's force, built at ``up x fs``:

    * ``"steps"``: the roller's load drops as it enters and comes back as it leaves (Sawalhi and
      Randall, MSSP 25 (2011) 846-870): ``-[s(t - t_k) - s(t - t_k - dt_s)]``, ``s`` a
      raised-cosine step over ``rise_s``, and at the exit a half-sine impact of ``impact`` over
      ``rise_s`` (the roller striking the far edge);
    * ``"dip"``: a roller that bridges the defect without unloading: a half-sine dip of the load
      over ``dt_s`` (no entry or exit event, only the dip's edges);
    * ``"single"``: one impact a pass (no pair of events).

    The structure (its ``modes``, Hz and damping ratio, acceleration response summed) carries
    the defect's force and a broadband background force (the rolling contacts' and the
    track's), whose response has ``background`` times the defect's RMS; then to ``fs`` through
    ``scipy.signal.resample_poly``'s anti-alias filter, scaled to the defect's unit RMS, plus
    :func:`wheel_rail_noise` (the body's low-frequency motion) of RMS ``noise`` and the sensor's
    white noise of RMS ``white``."""
    if events not in SPALL_EVENTS:
        raise ValueError(f"events = {events!r} is not allowed: expected one of {SPALL_EVENTS}")
    fh = fs * up
    n = int(round(T * fh))
    t = np.arange(n) / fh
    F = np.zeros(n)
    period = 1.0 / f_fault
    w = max(int(round(rise_s * fh)), 1)
    entries = []
    tk = start_s
    while tk + dt_s + 4 * rise_s < T - 0.002:
        entries.append(tk)
        i0, i1 = int(tk * fh), min(n, int((tk + dt_s + 4 * rise_s) * fh) + 2)
        tt = t[i0:i1] - tk
        if events == "steps":
            s1 = 0.5 - 0.5 * np.cos(np.pi * np.clip(tt / rise_s, 0.0, 1.0))
            s2 = 0.5 - 0.5 * np.cos(np.pi * np.clip((tt - dt_s) / rise_s, 0.0, 1.0))
            F[i0:i1] += s2 - s1
            j = int(round((tk + dt_s) * fh))
            F[j:j + w] += impact * np.sin(np.pi * np.arange(w) / w)[:max(0, n - j)]
        elif events == "dip":
            F[i0:i1] -= np.where(tt < dt_s, np.sin(np.pi * np.clip(tt / dt_s, 0.0, 1.0)), 0.0)
        else:
            F[i0:i0 + w] += np.sin(np.pi * np.arange(w) / w)[:n - i0]
        tk += period * (1 + jitter * rng.standard_normal())
    nfft = 1 << int(np.ceil(np.log2(2 * n)))
    om = 2 * np.pi * np.fft.rfftfreq(nfft, 1 / fh)
    H = sum(-om ** 2 / ((2 * np.pi * f) ** 2 - om ** 2 + 2j * z * (2 * np.pi * f) * om) for f, z in modes)

    def response(force):
        return resample_poly(np.fft.irfft(np.fft.rfft(force, nfft) * H, nfft)[:n], 1, up)
    x = response(F)
    x /= max(x.std(), 1e-300)
    b = response(rng.standard_normal(n))
    x += background * b / max(b.std(), 1e-300)
    m = x.size
    return (x + noise * wheel_rail_noise(m, fs, rng) + white * rng.standard_normal(m),
            np.array(entries))
