"""Blanking a wheel's strikes before the bearing's lines are read.

A wheel flat strikes the rail once a wheel turn, and each strike rings both axle boxes of its
wheelset far harder than a bearing defect does (the car's 40 mm flat on ballasted track at
80 km/h: axle-box RMS 65-93 m/s^2 against the defect's 5-8); the envelope of either side is then
the flat's, and the healthy side's copy of the bearing's impulses is lost under it.  The strikes
are locked to the wheel's turn, the bearing's are not (its orders are not whole numbers), so
folding the two sides' summed envelope over the wheel's period ``1 / f_w`` piles the strikes up at
one phase and smears the bearing's impulses and the noise over all phases.

:func:`wheel_gate` folds the envelope (the magnitude of the analytic signal, broadband) of both
channels over the turn, in bins of one sample, averaging the record's N turns.  A strike once a
turn stands ``ratio`` = peak / median of the fold over the rest; what is not locked to the turn
averages out: for N >= 5 turns the fold of the car's records without a flat reads 1.1-1.9, and
so do the twelve two-sensor CWRU records (benchmarks/README.md "Wheel flats and polygons");
the car's flats 35-75.  From ``Criterion.gate_ratio`` (5) the strike's window is blanked (set to zero) on
both channels every turn: from the fold's peak back and forward to where the fold, smoothed over
5 ms (the modes a strike rings beat), first falls below twice its median (the strike and its
ring), widened by a millisecond each side, at most
``MAX_BLANK`` of the turn.  The blanked record keeps the bearing's impulses between the strikes;
:func:`.pair.analyse_pair` reads the lines, the lag and the indicators on it, and names the
wheel's lines from the record as it came.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from .thresholds import Criterion
from .envelope import envelope

MIN_TURNS = 5           # turns the fold must average: fewer leave non-locked impulses standing
MAX_BLANK = 0.3         # at most this share of each turn blanked
MARGIN_S = 1e-3         # s each side of the window: the strike's onset and the ring's tail
SMOOTH_S = 5e-3         # s: the fold smoothed over this before its level is read


@dataclass(frozen=True)
class Gate:
    """The blanked windows: one a turn, ``before_s`` ahead of the strike's peak at ``phase_s``
    into each turn and ``after_s`` after it; ``ratio`` the fold's peak over its median;
    ``kept`` the share of the record left."""

    phase_s: float
    before_s: float
    after_s: float
    turn_s: float
    ratio: float
    kept: float

    def mask(self, n: int, fs: float) -> np.ndarray:
        """Boolean (n,): True where the record is kept."""
        t = np.arange(n) / fs
        u = (t - self.phase_s + self.before_s) % self.turn_s
        return u >= self.before_s + self.after_s

    def to_dict(self) -> dict:
        return asdict(self)


def fold(x_left, x_right, fs: float, shaft_hz: float) -> np.ndarray:
    """The two channels' summed envelope folded over the wheel's turn (one bin a sample)."""
    e = envelope(x_left, fs) + envelope(x_right, fs)
    T = fs / shaft_hz
    nb = int(T)
    ph = np.minimum((np.arange(e.size) % T).astype(int), nb - 1)
    return np.bincount(ph, weights=e, minlength=nb) / np.maximum(np.bincount(ph, minlength=nb), 1)


def wheel_gate(x_left, x_right, fs: float, shaft_hz: float,
               ratio: float = Criterion.gate_ratio) -> Gate | None:
    """The strikes' windows of a wheel flat on the two channels, or None where the record holds
    no strike once a turn: the fold's peak under ``ratio`` times its median (module docstring;
    the criterion's ``gate_ratio``)."""
    n = min(np.size(x_left), np.size(x_right))
    if n / fs * shaft_hz < MIN_TURNS:
        return None
    f = fold(np.asarray(x_left, float)[:n], np.asarray(x_right, float)[:n], fs, shaft_hz)
    med = float(np.median(f))
    p0 = int(np.argmax(f))
    r = float(f[p0] / med) if med > 0 else 0.0
    if not r >= ratio:
        return None
    nb = f.size
    # the window's ends on the fold smoothed over SMOOTH_S (circular): the beating of the modes a
    # strike rings dips the raw fold below the level long before the ring has died
    w = max(1, int(SMOOTH_S * fs))
    sm = np.convolve(np.r_[f[-w:], f, f[:w]], np.ones(w) / w, mode="same")[w:w + nb]
    low = sm < 2.0 * med
    after = next((k for k in range(1, nb) if low[(p0 + k) % nb]), nb)
    before = next((k for k in range(1, nb) if low[(p0 - k) % nb]), nb)
    m = MARGIN_S * fs
    total = min(before + after + 2 * m, MAX_BLANK * nb)
    scale = total / (before + after + 2 * m)
    g = Gate(phase_s=p0 / fs, before_s=(before + m) * scale / fs, after_s=(after + m) * scale / fs,
             turn_s=1.0 / shaft_hz, ratio=r, kept=math.nan)
    return Gate(**{**asdict(g), "kept": float(g.mask(n, fs).mean())})
