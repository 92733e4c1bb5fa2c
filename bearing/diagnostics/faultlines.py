"""Fault-frequency lines in an envelope spectrum, against the local noise floor.

For each named line ``f0`` (BPFO, BPFI, FTF, ...):

* fundamental: search window ``|f - f0| <= hw = max(slip f0, df)`` (rollers slip, so the lines
  sit a few % below the kinematic values; at least one bin either side);
* noise floor: the median of the spectrum over the ring ``hw < |f - centre| <= hw + w_floor``
  beside a window (``w_floor = max(3 hw, 20 df)``; the median ignores the odd other line);
* ``snr_db = 20 log10(amplitude / floor)``; a bin *passes* when ``snr_db >= threshold_db``;
* harmonics ``k = 2..n_harmonics`` of a candidate fundamental ``f1`` (a local maximum of the
  fundamental window that passes, or the window's highest bin when none does; that bin passes
  only where it is a peak, not the skirt of a line beside the window) are searched in
  the narrow windows ``|f - k f1| <= k max(df, 0.005 f1)``: slip scales every harmonic alike, so
  they sit at ``k f1`` up to the bin quantisation of ``f1`` and 0.5 % of speed drift in the
  record.  Tying the harmonics to the fundamental keeps another family's lines, which fall
  inside the wide +-slip windows of higher harmonics (on the CWRU drive end, 3 BPFO lies within
  3 % of 2 BPFI, and BPFO + 2 f_shaft within 3 % of BPFI), from passing as this line's;
* of several candidates the one with the most passing harmonics (then the largest summed SNR)
  is kept;
* given the shaft frequency, a detected line whose fundamental is a shaft sideband
  ``k f_L +- m f_shaft`` of a stronger detected line ``L`` is masked (:func:`mask_sidebands`).

Threshold: settable in dB.  By default it is set per window from a false-alarm probability
``p_fa`` (the chance that noise alone passes that one window): for a Welch average of ``K``
segments the power of a noise bin is ``s chi2(2K) / 2K`` (Rayleigh amplitude for ``K = 1``), the
floor estimates its median, and the highest of the ``N`` bins of the window exceeds
``t`` with probability ``1 - F(t)^N``; solving for ``t`` gives
``threshold_db = 10 log10(chi2.ppf((1 - p_fa)^(1/N), 2K) / chi2.median(2K))``.
A fixed dB threshold would let wide windows (high harmonics, long records: many bins) pass on
noise far more often than narrow ones.  ``K`` is the equivalent number of independent averages of
a Welch estimate (:func:`welch_averages`; 50 %-overlapping Hann segments are correlated).
Measured on envelope spectra of noise (700 windows, 6 seeds): p_fa = 0.05 passes 6-7 %, 0.01
passes 2-3 % (the median of the ring is itself an estimate, so the tail is a little heavier).

A line is *detected* when its fundamental passes and at least ``n_required`` of its harmonics
``k >= 2`` pass too (the default, 2 of 2..3, asks for the fundamental and two harmonics: the
pattern of periodic impulses, not a lone peak).

A line may also carry sidebands that count as its components: a rolling element's defect (line
``2BSF``, twice the roller's spin frequency: it strikes the cup and the cone once per spin turn)
is carried round by the cage in and out of the load zone, so its impacts are modulated at the
cage frequency and its envelope spectrum holds ``2BSF +- FTF`` beside ``2BSF`` and its
harmonics (McFadden and Smith, J. Sound Vib. 98 (1985) 263-273; Randall and Antoni, MSSP 25
(2011) 485-520, sec. 2.2).  The sidebands are searched in narrow windows ``|f - (f1 +- d)| <=
max(df, 0.005 f1)`` beside the candidate fundamental ``f1``, their offset ``d`` the nominal one
scaled by ``f1 / f0`` (slip slows the cage and the spin alike); each that passes counts
towards ``n_required`` as a harmonic does.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy.stats import chi2

from axlebox._params import ParameterError


@dataclass(frozen=True)
class LineResult:
    """One fault line.  ``harmonics``: the passing harmonics as ``(k, f_Hz, amplitude, snr_db)``;
    ``searched``: every harmonic searched, the same tuple plus its threshold in dB;
    ``f_found``: the fundamental's peak (Hz) when it passes, else None; ``masked_by``: the
    stronger line whose shaft sideband this one's fundamental is (then not detected);
    ``sidebands``: the fundamental's sidebands searched, ``(sign, f_Hz, amplitude, snr_db,
    threshold_db)`` with sign -1 or +1 (module docstring; empty for lines without)."""

    name: str
    f_expected: float
    f_found: float | None
    harmonics: tuple[tuple[int, float, float, float], ...]
    searched: tuple[tuple[int, float, float, float, float], ...]
    detected: bool
    masked_by: str | None = None
    sidebands: tuple[tuple[int, float, float, float, float], ...] = ()

    @property
    def snr_db(self) -> float:
        """The fundamental's SNR in dB (searched, whether it passes or not)."""
        return float(self.searched[0][3])

    def to_dict(self) -> dict:
        """Plain JSON types; an infinite SNR (a floor of exactly 0) becomes None."""
        def fin(v):
            return v if math.isfinite(v) else None
        return {"name": self.name, "f_expected": self.f_expected, "f_found": self.f_found,
                "detected": self.detected, "masked_by": self.masked_by,
                "harmonics": [dict(k=k, f=f, amp=a, snr_db=fin(s)) for k, f, a, s in self.harmonics],
                "searched": [dict(k=k, f=f, amp=a, snr_db=fin(s), threshold_db=t)
                             for k, f, a, s, t in self.searched],
                "sidebands": [dict(sign=g, f=f, amp=a, snr_db=fin(s), threshold_db=t)
                              for g, f, a, s, t in self.sidebands]}


def welch_averages(n: int, nperseg: int) -> float:
    """Equivalent independent averages of a Welch estimate from ``n`` samples in Hann segments of
    ``nperseg`` with 50 % overlap: ``K / (1 + 2 (K-1)/K rho^2)`` with ``K`` segments and the
    overlap correlation ``rho = 0.167`` of the Hann window at 50 % (Welch, IEEE Trans. Audio
    Electroacoust. 15 (1967) 70, Eq. 27; F. J. Harris, Proc. IEEE 66 (1978) 51, Table 1)."""
    K = 1 + (n - nperseg) // (nperseg - nperseg // 2) if n > nperseg else 1
    return K / (1 + 2 * (K - 1) / K * 0.167 ** 2)


def window_threshold_db(n_bins: int, n_avg: float = 1.0, p_fa: float = 1e-3) -> float:
    """dB over the median floor that the highest of ``n_bins`` noise bins exceeds with
    probability ``p_fa`` (power of a bin ~ chi2 with ``2 n_avg`` degrees of freedom)."""
    nu = 2 * max(1.0, float(n_avg))
    q = (1.0 - p_fa) ** (1.0 / max(1, int(n_bins)))
    return 10.0 * math.log10(chi2.ppf(q, nu) / chi2.median(nu))


def _snr(a, floor):
    """20 log10(a / floor), +-inf where the floor or the amplitude is 0."""
    with np.errstate(divide="ignore"):
        return 20 * np.log10(np.asarray(a, float) / floor) if floor > 0 else \
            np.where(np.asarray(a) > 0, np.inf, -np.inf)


def is_peak(A, i: int) -> bool:
    """Whether bin ``i`` of ``A`` is a local maximum (not lower than either neighbour)."""
    return bool(A[i] >= A[max(i - 1, 0)] and A[i] >= A[min(i + 1, A.size - 1)])


def _window(f, A, centre, hw, df, n_avg, p_fa, threshold_db):
    """``(indices, floor, threshold_db)`` of the window ``|f - centre| <= hw``."""
    dist = np.abs(f - centre)
    win = np.flatnonzero(dist <= hw)
    if win.size == 0:                                   # narrower than a bin: the nearest one
        win = np.array([int(np.argmin(dist))])
    ring = (dist > hw) & (dist <= hw + max(3 * hw, 20 * df)) & (f > 0)
    floor = float(np.median(A[ring])) if ring.any() else 0.0
    thr = window_threshold_db(win.size, n_avg, p_fa) if threshold_db is None else float(threshold_db)
    return win, floor, thr


def _peak(f, A, centre, hw, df, n_avg, p_fa, threshold_db) -> tuple[float, float, float, float]:
    """``(f, amplitude, snr_db, threshold_db)`` of the highest bin of the window ``|f - centre|
    <= hw``, against its own ring's floor."""
    w, fl, t = _window(f, A, centre, hw, df, n_avg, p_fa, threshold_db)
    i = w[int(np.argmax(A[w]))]
    return float(f[i]), float(A[i]), float(_snr(A[i], fl)), t


def detect(f, A, lines: dict[str, float], n_harmonics: int = 3, slip: float = 0.03,
           threshold_db: float | None = None, p_fa: float = 1e-3, n_required: int = 2,
           n_avg: float = 1.0, shaft_hz: float | None = None,
           sidebands: dict[str, float] | None = None) -> dict[str, LineResult]:
    """Search each line of ``lines`` (name -> Hz) and its harmonics in the amplitude spectrum
    ``(f, A)`` (equally spaced ``f`` from 0 Hz, e.g. :func:`.envelope.envelope_spectrum`).

    ``slip``: relative half-width of the search window; ``threshold_db``: fixed threshold over
    the floor, or None for the false-alarm rule with ``p_fa`` per window (module docstring);
    ``n_avg``: independent averages in ``A`` (1 for a single periodogram; a Welch average:
    :func:`welch_averages`); ``n_required``: harmonics ``k >= 2`` that must pass besides the
    fundamental; ``shaft_hz``: when given, a detected line whose fundamental is a shaft
    sideband of a stronger detected line is masked (:func:`mask_sidebands`); ``sidebands``:
    name -> nominal offset (Hz) of the sidebands that count as that line's components (module
    docstring), e.g. ``{"2BSF": FTF}``."""
    f = np.asarray(f, float)
    A = np.asarray(A, float)
    if f.ndim != 1 or f.shape != A.shape or f.size < 16:
        raise ParameterError(f"spectrum of shapes {f.shape}, {A.shape} is not allowed: expected "
                             "f and A of the same 1-D shape, at least 16 bins")
    df = f[1] - f[0]
    if not 0 <= slip < 0.5:
        raise ParameterError(f"slip = {slip!r} is not allowed: expected 0 <= slip < 0.5")
    if not (isinstance(n_harmonics, int) and n_harmonics >= 1):
        raise ParameterError(f"n_harmonics = {n_harmonics!r} is not allowed: expected an integer >= 1")
    sidebands = {} if sidebands is None else dict(sidebands)
    if not (isinstance(n_required, int) and 0 <= n_required <= n_harmonics - 1):
        raise ParameterError(f"n_required = {n_required!r} is not allowed: expected an integer in "
                             f"[0, n_harmonics - 1 = {n_harmonics - 1}]")
    for name, d in sidebands.items():
        if name not in lines or not (np.isfinite(d) and 0 < d < lines[name]):
            raise ParameterError(f"sidebands[{name!r}] = {d!r} Hz is not allowed: expected the offset "
                                 "of a searched line's sidebands, 0 < offset < its frequency")
    if not 0 < p_fa < 1:
        raise ParameterError(f"p_fa = {p_fa!r} is not allowed: expected 0 < p_fa < 1")
    out = {}
    for name, f0 in lines.items():
        if not (np.isfinite(f0) and f0 > 0):
            raise ParameterError(f"lines[{name!r}] = {f0!r} Hz is not allowed: expected a frequency > 0")
        if n_harmonics * f0 * (1 + slip) > f[-1]:
            raise ParameterError(f"lines[{name!r}] = {f0:g} Hz is not allowed: its harmonic "
                                 f"{n_harmonics} lies above the spectrum's {f[-1]:g} Hz")
        if f0 < 2 * df:
            raise ParameterError(f"lines[{name!r}] = {f0:g} Hz is not allowed with a resolution of "
                                 f"{df:g} Hz: the record is too short, expected at least "
                                 f"{2 / f0:g} s")
        hw = max(slip * f0, df)
        win, floor, thr = _window(f, A, f0, hw, df, n_avg, p_fa, threshold_db)
        snr = _snr(A[win], floor)
        local = (A[win] >= A[np.maximum(win - 1, 0)]) & (A[win] >= A[np.minimum(win + 1, A.size - 1)])
        cands = win[(snr >= thr) & local]
        if cands.size == 0:
            cands = win[[int(np.argmax(A[win]))]]
        best = None
        for c in cands:
            rows = [(1, float(f[c]), float(A[c]), float(_snr(A[c], floor)), thr)]
            for k in range(2, n_harmonics + 1):
                rows.append((k, *_peak(f, A, k * f[c], k * max(df, 0.005 * f[c]), df, n_avg,
                                       p_fa, threshold_db)))
            side = [(g, *_peak(f, A, f[c] + g * sidebands[name] * f[c] / f0,
                                max(df, 0.005 * f[c]), df, n_avg, p_fa, threshold_db))
                    for g in (-1, 1)] if name in sidebands else []
            ok = [r for r in rows + side if r[3] >= r[4]]
            score = (rows[0][3] >= thr, len(ok), sum(r[3] for r in ok))
            if best is None or score > best[0]:
                best = (score, rows, side, c)
        searched, side = tuple(best[1]), tuple(best[2])
        # a line is a peak: the window's highest bin on the skirt of a line outside it (a shaft
        # harmonic next to the window, a wheel flat's comb) is not this line's fundamental
        peak = is_peak(A, best[3])
        passing = tuple((k, fk, a, s) for k, fk, a, s, t in searched if s >= t and (k > 1 or peak))
        fund = bool(passing) and passing[0][0] == 1
        n_pass = sum(1 for h in passing if h[0] >= 2) + sum(1 for r in side if r[3] >= r[4])
        detected = fund and n_pass >= n_required
        out[name] = LineResult(name=name, f_expected=float(f0),
                               f_found=passing[0][1] if fund else None, harmonics=passing,
                               searched=searched, detected=detected, sidebands=side)
    return out if shaft_hz is None else mask_sidebands(out, shaft_hz, df, n_required=n_required)


def _family(L: LineResult, shaft_hz: float, max_order: int):
    """The frequencies of line ``L``'s family: ``k f_L + m f_shaft``, ``k = 1..3``."""
    return [k * L.f_found + m * shaft_hz for k in (1, 2, 3) for m in range(-max_order, max_order + 1)]


def mask_sidebands(found: dict[str, LineResult], shaft_hz: float, df: float,
                   max_order: int = 3, n_required: int = 2) -> dict[str, LineResult]:
    """Un-detect what another cause explains, the strongest detected line first (higher
    fundamental SNR; two lines whose windows hold the same peak tie on SNR, and the one whose
    expected frequency lies nearer the peak keeps it):

    * a line found within ``max(2 df, 0.3 %)`` of a shaft harmonic ``n f_shaft`` (the Hann window's
      main lobe is two bins either side: nearer, the two cannot be told apart) that is either
      expected within 1 % of it or found nearer it than its own expected frequency (``masked_by``
      "shaft"): unbalance, misalignment and the rotor's own orders put lines there in the
      envelope too, and a line there cannot be told from them (the CWRU fan end's 2 BSF, 3.9874
      orders, lies 0.3 % from 4 f_shaft; its BPFO, 3.053 orders, 1.8 % from 3, is masked when the
      slip window's peak is the 3 f_shaft line, kept when the peak is at 3.053; a DTRB BPFO found
      at its expected 8.72 orders stays, however coarse the spectrum);
    * a line whose fundamental lies within that tolerance of ``k f_L + m f_shaft`` (``k =
      1..3``, ``|m| <= max_order``) of a stronger kept line ``L``: a localised fault's impulses
      are modulated by the shaft (load zone, run-out), so its envelope spectrum holds ``k f_L +-
      m f_shaft``; with a few % of slip allowed, one of those can fall in another line's window
      and bring its own harmonics along (CWRU drive end: BPFO + 2 f_shaft = 167.2 Hz, within
      3.1 % of BPFI = 162.1 Hz);
    * a line detected with sidebands (2BSF) whose harmonics and sidebands that pass, less those
      lying on a stronger kept line's family, fall under ``n_required``: its cage sidebands
      (``+- FTF``, 0.4 orders) are near enough to another line's shaft sidebands to borrow them
      (CWRU drive end: 2 BSF - FTF = 4.3152 orders = BPFI - f_shaft)."""
    order = sorted((r for r in found.values() if r.detected),
                   key=lambda r: (-r.searched[0][3], abs(r.f_found / r.f_expected - 1.0)))
    out = dict(found)
    kept = []
    for r in order:
        f1 = r.f_found
        tol = max(2 * df, 0.005 * f1)
        n = round(f1 / shaft_hz)
        near = n >= 1 and abs(f1 - n * shaft_hz) <= max(2 * df, 0.003 * f1)
        # the peak is the shaft's when the line cannot be told from the harmonic (expected
        # within 1 %), or when it sits nearer the harmonic than the line's own frequency
        at_shaft = near and (abs(r.f_expected / (n * shaft_hz) - 1.0) <= 0.01
                             or abs(f1 - n * shaft_hz) < abs(f1 - r.f_expected))
        hit = "shaft" if at_shaft else next(
            (L.name for L in kept if any(abs(f1 - g) <= tol for g in _family(L, shaft_hz, max_order))),
            None)
        if hit is None and r.sidebands:
            parts = [(fk, s >= t) for k, fk, _, s, t in r.searched[1:]] + \
                    [(fk, s >= t) for _, fk, _, s, t in r.sidebands]
            claimed = {L.name for L in kept for fk, ok in parts if ok
                       for g in _family(L, shaft_hz, max_order)
                       if abs(fk - g) <= max(2 * df, 0.005 * fk)}
            free = [fk for fk, ok in parts if ok and not any(
                abs(fk - g) <= max(2 * df, 0.005 * fk)
                for L in kept for g in _family(L, shaft_hz, max_order))]
            if len(free) < n_required:
                hit = sorted(claimed)[0] if claimed else None
        if hit is None:
            kept.append(r)
        else:
            out[r.name] = replace(r, detected=False, masked_by=hit)
    return out
