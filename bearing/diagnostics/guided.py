"""Fault-guided envelope band: the band in which a known fault line stands highest.

The band of highest spectral kurtosis (:func:`.envelope.select_band`) is the right blind choice,
but on the pseudo-fault side of a wheelset it often holds that side's own shocks (wheel-rail
impacts, its own axle-box ring), while the impulses transmitted from the other side arrive
through the wheelset's bending, in a lower band (the paper, Fig. 12: 300-800 Hz).  When the
fault is known, from the other side's spectrum, the band can be chosen for it: the band that
maximises the envelope spectrum's signal-to-noise at the fault's cyclic frequency, the
objective of targeted band selection (e.g. Schmidt, Heyns and Gryllias, "Generalised envelope
spectrum-based signal-to-noise objectives", arXiv:2405.00727, 2024; there by filter
optimisation, here over a grid).

Grid: the STFT kurtogram's bands, ``f +- fs/N`` for every bin ``f`` of windows of ``N = 2**level``
samples, no narrower than ``min_width_hz``.  Score of a band: the line's detection by
:func:`.faultlines.detect` (fundamental and ``n_required`` harmonics over the floor), then the
number of passing harmonics, then the summed SNR in dB of the fundamental and harmonics.

Trying ``n`` bands gives noise ``n`` chances to pass: each band's threshold is set for a
false-alarm probability ``p_fa / n`` (Bonferroni), so that noise passes in any band with
probability at most ``p_fa``, the same as one band at ``p_fa``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axlebox._params import ParameterError

from . import faultlines
from .envelope import _signal, check_fs, envelope_spectrum, kurtogram_levels


@dataclass(frozen=True)
class GuidedBand:
    """``band`` (Hz), the number of bands tried and the per-band false-alarm probability that
    detection in ``band`` must use (``p_fa / n_bands``); ``line``: the guide line's result there."""

    band: tuple[float, float]
    n_bands: int
    p_fa: float
    line: faultlines.LineResult


def band_grid(fs: float, n: int, min_width_hz: float,
              levels: tuple[int, ...] = (3, 4, 5, 6, 7, 8, 9)) -> list[tuple[float, float]]:
    """The kurtogram's bands ``(f - fs/N, f + fs/N)`` within ``(0, fs/2)`` for a record of ``n``
    samples, at least ``min_width_hz`` wide."""
    out = []
    for N in kurtogram_levels(n, fs, min_width_hz, levels):
        bw = fs / N
        for k in range(1, N // 2):
            f = k * fs / N
            if f - bw > 0 and f + bw < fs / 2:
                out.append((f - bw, f + bw))
    return out


@dataclass(frozen=True)
class BandScan:
    """Line ``name`` in every band of the grid: ``bands``, the line's result in each
    (``lines``), the per-band false-alarm probability ``p_fa`` (``p_fa / n_bands``) and each
    band's score (detected, harmonics passing, summed SNR)."""

    name: str
    bands: tuple[tuple[float, float], ...]
    lines: tuple[faultlines.LineResult, ...]
    p_fa: float

    def score(self, i: int) -> tuple:
        r = self.lines[i]
        snr = [s for *_, s, _t in r.searched if np.isfinite(s)]
        return (r.detected, len(r.harmonics), sum(snr))

    @property
    def best(self) -> int:
        return max(range(len(self.bands)), key=self.score)

    def near_best(self, within_db: float) -> list[int]:
        """The bands where the line is detected with a fundamental within ``within_db`` of the
        best detecting band's (best first); empty when no band detects it."""
        det = [i for i, r in enumerate(self.lines) if r.detected]
        if not det:
            return []
        top = max(self.lines[i].snr_db for i in det)
        keep = [i for i in det if self.lines[i].snr_db >= top - within_db]
        return sorted(keep, key=self.score, reverse=True)


def band_scan(x, fs: float, name: str, f_line: float, *, nperseg: int, n_harmonics: int = 3,
              slip: float = 0.03, p_fa: float = 1e-3, n_required: int = 2,
              levels: tuple[int, ...] = (3, 4, 5, 6, 7, 8, 9), max_samples: int = 2 ** 19,
              sideband_hz: float | None = None) -> BandScan:
    """Line ``name`` at ``f_line`` Hz searched in the envelope spectrum of ``x`` in every band of
    the grid (module docstring; arguments as :func:`guided_band`)."""
    x = _signal(x)[:max_samples]
    fs = check_fs(fs)
    if not (np.isfinite(f_line) and f_line > 0):
        raise ParameterError(f"f_line = {f_line!r} Hz is not allowed: expected a frequency > 0")
    bands = band_grid(fs, x.size, 2 * (n_harmonics + 1) * f_line, levels)
    if not bands:
        raise ParameterError(f"f_line = {f_line:g} Hz is not allowed at fs = {fs:g} Hz: no band of "
                             f"the grid is {2 * (n_harmonics + 1) * f_line:g} Hz wide")
    seg = min(int(nperseg), x.size)
    n_avg = faultlines.welch_averages(x.size, seg)
    p = p_fa / len(bands)
    found = []
    for b in bands:
        f, A = envelope_spectrum(x, fs, b, nperseg=seg)
        found.append(faultlines.detect(
            f, A, {name: f_line}, n_harmonics=n_harmonics, slip=slip, p_fa=p,
            n_required=n_required, n_avg=n_avg,
            sidebands=None if sideband_hz is None else {name: sideband_hz})[name])
    return BandScan(name, tuple((float(lo), float(hi)) for lo, hi in bands), tuple(found), p)


def guided_band(x, fs: float, name: str, f_line: float, *, nperseg: int, n_harmonics: int = 3,
                slip: float = 0.03, p_fa: float = 1e-3, n_required: int = 2,
                levels: tuple[int, ...] = (3, 4, 5, 6, 7, 8, 9),
                max_samples: int = 2 ** 19, sideband_hz: float | None = None) -> GuidedBand:
    """The band of the grid (module docstring) where line ``name`` at ``f_line`` Hz stands
    highest in the envelope spectrum of ``x`` (Welch segments of ``nperseg``); the search uses
    the first ``max_samples`` samples.  Bands are at least ``2 (n_harmonics + 1) f_line`` wide,
    so that the envelope carries the harmonics searched.  ``sideband_hz``: the offset of the
    line's sidebands that count as its components (:func:`.faultlines.detect`)."""
    scan = band_scan(x, fs, name, f_line, nperseg=nperseg, n_harmonics=n_harmonics, slip=slip,
                     p_fa=p_fa, n_required=n_required, levels=levels, max_samples=max_samples,
                     sideband_hz=sideband_hz)
    i = scan.best
    return GuidedBand(band=scan.bands[i], n_bands=len(scan.bands), p_fa=scan.p_fa,
                      line=scan.lines[i])
