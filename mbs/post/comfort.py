"""Ride comfort of the carbody: Sperling's ride index and the EN 12299 mean comfort N_MV.

Sperling (Wertungsziffer) of one spectral line, acceleration peak ``b`` in cm/s^2 at ``f`` Hz:

    W = 0.896 (b^3 F(f) / f)^(1/10)                                           (S.1)

with the frequency weighting F(f) of :func:`sperling_F` (vertical: 0.325 f^2 to 5.9 Hz,
400 / f^2 to 20 Hz, 1 above; lateral: 0.8 f^2 to 5.4 Hz, 650 / f^2 to 26 Hz, 1 above), and of a
spectrum of lines

    W = (sum_i W_i^10)^(1/10)                                                  (S.2)

(Sperling 1941, in the form of Garg & Dukkipati, *Dynamics of Railway Vehicle Systems*, 1984,
and GB 5599; W_z from the vertical, W_y from the lateral acceleration).  :func:`sperling` takes
the lines from the FFT of the record (rectangular window, so a sinusoid of whole periods gives
its exact peak; a record's broadband W falls as its length^(-1/20), the known dependence of
the spectral form on the analysis length).

EN 12299:2009 mean comfort, standard method (clause 6.7.2), from the 95th percentiles
(clause 6.6.3) of the r.m.s. over consecutive 5 s windows (clause 6.6.2) of the floor
accelerations weighted by W_d (x, y) and W_b (z) (:mod:`axlebox.mbs.post.weighting`):

    N_MV = 6 sqrt((a_XP95^Wd)^2 + (a_YP95^Wd)^2 + (a_ZP95^Wb)^2)               (EN 12299 6.7.2)

The standard evaluates a 5 min record (60 windows).  A shorter simulated record gives fewer
windows; one shorter than a window is one window of its whole length, and the result says so
(:attr:`RideComfort.windows`): then N_MV is an indication, not the standard's figure.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import weighting

SPERLING_BAND_HZ = (0.5, 30.0)   # F(f) starts at 0.5 Hz; above 30 Hz a floor carries structure noise
WINDOW_S = 5.0                   # EN 12299 6.6.2: r.m.s. over 5 s
PERCENTILE = 95.0                # EN 12299 6.6.3

# (upper end of the range, F on it) per direction, ranges closed above (Garg & Dukkipati 1984)
_F = {"vertical": ((5.9, lambda f: 0.325 * f * f), (20.0, lambda f: 400.0 / (f * f)),
                   (math.inf, lambda f: np.ones_like(f))),
      "lateral": ((5.4, lambda f: 0.8 * f * f), (26.0, lambda f: 650.0 / (f * f)),
                  (math.inf, lambda f: np.ones_like(f)))}

# Sperling's comfort scale (vibration sensitivity): the value each description starts at
# (Urban Rail Transit 1, 2015, doi 10.1007/s40864-015-0007-8, Table 4)
SPERLING_SCALE = ((1.0, "just noticeable"), (2.0, "clearly noticeable"),
                  (2.5, "more pronounced but not unpleasant"),
                  (3.0, "strong, irregular, but still tolerable"), (3.25, "very irregular"),
                  (3.5, "extremely irregular, unpleasant"),
                  (4.0, "extremely unpleasant, harmful if prolonged"))
# EN 12299 mean comfort scale (clause 6.7.2), as open EN 12299 implementations give it (the
# standard's text was not available here): the value each class starts at
NMV_SCALE = ((0.0, "very comfortable"), (1.5, "comfortable"), (2.5, "medium"),
             (3.5, "uncomfortable"), (4.5, "very uncomfortable"))


def _words(scale, value: float, below: str) -> str:
    out = below
    for start, words in scale:
        if value >= start:
            out = words
    return out


def sperling_words(W: float) -> str:
    """Sperling's comfort scale for ride index ``W``."""
    return _words(SPERLING_SCALE, W, "not noticeable")


def nmv_words(N: float) -> str:
    """EN 12299's verbal scale for mean comfort ``N``."""
    return _words(NMV_SCALE, N, "very comfortable")


def sperling_F(f_hz, direction: str) -> np.ndarray:
    """Sperling's frequency weighting F(f) for ``direction`` "vertical" or "lateral"."""
    if direction not in _F:
        raise ValueError(f"direction = {direction!r} is not allowed: expected 'vertical' or 'lateral'")
    f = np.asarray(f_hz, float)
    out = np.empty_like(f)
    lo = np.zeros_like(f, bool)
    for top, F in _F[direction]:
        sel = ~lo & (f <= top)
        out[sel] = F(f[sel])
        lo |= sel
    return out


def sperling_line(b_peak, f_hz, direction: str) -> np.ndarray:
    """Eq. (S.1): W of a sinusoid of peak ``b_peak`` (m/s^2) at ``f_hz``."""
    b = 100.0 * np.asarray(b_peak, float)                 # cm/s^2
    f = np.asarray(f_hz, float)
    return 0.896 * (b ** 3 * sperling_F(f, direction) / f) ** 0.1


def amplitude_lines(a, fs: float) -> tuple[np.ndarray, np.ndarray]:
    """``(f, b)``: the FFT lines of record ``a`` (mean removed, rectangular window) and the peak
    amplitude of each, in ``a``'s unit (a sinusoid of whole periods gives its exact peak)."""
    a = np.asarray(a, float)
    return np.fft.rfftfreq(a.size, 1.0 / fs), 2.0 * np.abs(np.fft.rfft(a - a.mean())) / a.size


def sperling_lines(f_hz, b_peak, direction: str, band=SPERLING_BAND_HZ) -> float:
    """Eq. (S.2) over the lines (``f_hz``, peaks ``b_peak`` in m/s^2) inside ``band``."""
    f, b = np.asarray(f_hz, float), np.asarray(b_peak, float)
    sel = (f >= band[0]) & (f <= band[1])
    if not sel.any():
        return math.nan
    return float(np.sum(sperling_line(b[sel], f[sel], direction) ** 10) ** 0.1)


def sperling(a, fs: float, direction: str, band=SPERLING_BAND_HZ) -> float:
    """Eq. (S.2) over the FFT lines of record ``a`` (m/s^2 at ``fs`` Hz) inside ``band``."""
    return sperling_lines(*amplitude_lines(a, fs), direction, band)


def window_rms(a, fs: float, window: float = WINDOW_S) -> np.ndarray:
    """R.m.s. of ``a`` over consecutive ``window`` s (EN 12299 6.6.2); one window of the whole
    record when it is shorter."""
    a = np.asarray(a, float)
    m = int(round(window * fs))
    k = a.size // m if m > 0 else 0
    if k == 0:
        return np.array([np.sqrt(np.mean(a * a))])
    return np.sqrt(np.mean(a[:k * m].reshape(k, m) ** 2, axis=1))


def mean_comfort(a_xyz, fs: float, window: float = WINDOW_S) -> tuple[float, np.ndarray, int]:
    """EN 12299 6.7.2: ``(N_MV, (a_XP95, a_YP95, a_ZP95), windows)`` of floor accelerations
    ``a_xyz`` ((n, 3), m/s^2, x along the track, z up) at ``fs`` Hz."""
    a = np.asarray(a_xyz, float)
    aw = np.column_stack([weighting.weigh(a[:, :2], fs, "Wd"), weighting.weigh(a[:, 2], fs, "Wb")])
    rms = [window_rms(aw[:, j], fs, window) for j in range(3)]
    p95 = np.array([np.percentile(r, PERCENTILE) for r in rms])
    return float(6.0 * np.sqrt(np.sum(p95 ** 2))), p95, len(rms[0])


@dataclass
class RideComfort:
    """The comfort indices of one floor sensor, and the spectra they come from."""

    sensor: str
    W_z: float                 # Sperling, vertical
    W_y: float                 # Sperling, lateral
    N_MV: float                # EN 12299 mean comfort, standard method
    a_P95: np.ndarray          # (3,) m/s^2: a_XP95^Wd, a_YP95^Wd, a_ZP95^Wb
    windows: int               # 5 s windows the percentiles are of (the standard: 60)
    duration_s: float          # the record evaluated
    f_hz: np.ndarray           # spectra: frequencies
    spectra: dict              # name -> amplitude spectrum (m/s^2 peak per line)

    COLUMNS = ("W_z", "W_y", "N_MV", "a_XP95", "a_YP95", "a_ZP95")

    def values(self) -> np.ndarray:
        return np.array([self.W_z, self.W_y, self.N_MV, *self.a_P95])

    def summary(self) -> str:
        short = (f"; {self.duration_s:.2g} s record: N_MV from {self.windows} window(s) "
                 f"of at most {WINDOW_S:g} s (the standard: 5 min), an indication"
                 if self.windows < 60 else "")
        return (f"{self.sensor}: W_z {self.W_z:.2f} ({sperling_words(self.W_z)}), W_y {self.W_y:.2f} "
                f"({sperling_words(self.W_y)}), N_MV {self.N_MV:.2f} ({nmv_words(self.N_MV)}){short}")

    def plot(self, ax=None):
        """The floor's amplitude spectra, raw and weighted (W_d lateral, W_b vertical)."""
        if ax is None:
            from axlebox._figures import figure
            ax = figure(figsize=(7, 4)).add_subplot()
        sel = (self.f_hz >= 0.3) & (self.f_hz <= 80)
        for name, spec in self.spectra.items():
            ax.loglog(self.f_hz[sel], spec[sel], label=name, lw=1.0,
                      ls="-" if "weighted" in name else ":")
        ax.set(xlabel="frequency [Hz]", ylabel="amplitude [m/s$^2$]",
               title=f"{self.sensor}: W_z {self.W_z:.2f}, W_y {self.W_y:.2f}, N_MV {self.N_MV:.2f}")
        ax.legend(fontsize=7)
        return ax


def ride_comfort(a_xyz, fs: float, sensor: str = "floor", skip_s: float = 0.0) -> RideComfort:
    """All indices of one floor sensor's accelerations ``a_xyz`` ((n, 3), m/s^2, x along the
    track, y lateral, z up) at ``fs`` Hz, from ``skip_s`` on (a run's start-up left out)."""
    a = np.asarray(a_xyz, float)[int(round(skip_s * fs)):]
    if a.ndim != 2 or a.shape[1] != 3 or a.shape[0] < 2:
        raise ValueError(f"accelerations of shape {np.shape(a_xyz)} from {skip_s:g} s: expected "
                         "(n, 3) with at least two samples left")
    N, p95, windows = mean_comfort(a, fs)
    f, lat = amplitude_lines(a[:, 1], fs)
    _, vert = amplitude_lines(a[:, 2], fs)
    spectra = {"lateral": lat, "vertical": vert,
               "lateral, weighted Wd": lat * weighting.gain("Wd", f),
               "vertical, weighted Wb": vert * weighting.gain("Wb", f)}
    return RideComfort(sensor, sperling_lines(f, vert, "vertical"), sperling_lines(f, lat, "lateral"),
                       N, p95, windows, a.shape[0] / fs, f, spectra)


def floor_comfort(time, sensors: dict, skip_s: float, prefix: str = "carbody") -> list[RideComfort]:
    """:func:`ride_comfort` of each sensor named ``prefix...`` in ``sensors`` (name -> (n, 3)
    accelerations at the instants ``time``), from ``skip_s`` on; none when less than 0.5 s is
    left after it (too short for a line of the band's lowest frequency)."""
    t = np.asarray(time, float)
    if t.size < 2 or t[-1] - t[0] <= skip_s + 0.5:
        return []
    fs = 1.0 / np.median(np.diff(t))
    return [ride_comfort(a, fs, name, skip_s) for name, a in sensors.items() if name.startswith(prefix)]
