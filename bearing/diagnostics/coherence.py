"""Copy or source: is a fault line seen on both sides one impulse train, or two?

Beyond the paper (its criterion compares amplitudes and spectral dispersion).  The physics.  A
coaxial pseudo-fault is the defect's impulse train reaching the other axle box through a fixed
linear path (axle, bearings, housings): every impulse arrives a fixed delay later, with the
source's own jitter and slip.  Whatever band the copy is read in, its envelope is the source's
envelope through a fixed filter, so at each harmonic ``k f`` of the fault line the two sides'
envelopes are *coherent*, and stay so over the whole record.  A second defect has its own
timing: its own load and slip (its cage turns at its own speed), its own jitter, drifting
against the first over a record of seconds; and its own ringing, so it stands best in its own
band.  Its line is not coherent with the other side's, the less so the higher the harmonic and
the longer the record: a relative timing that wanders by ``sigma`` seconds leaves
``exp(-(2 pi k f sigma)^2)`` of the coherence at harmonic ``k``.

The estimate, for one line seen on both sides (:func:`line_timing`):

* each side's *own bands*: those of the band grid (:func:`.guided.band_scan`) where its line is
  detected within ``NEAR_DB`` (3 dB) of its best band (a second fault stands best in its own
  ringing band, but a path resonance can lift the other side's copy over it in one band);
* each side's envelope (:mod:`.envelope`) in each of its own bands; the Welch auto- and
  cross-spectra of every pair of the two sides' envelopes, Hann segments of ``n_periods`` line
  periods (at least 8, and a sixteenth of the record: about 30 segments with the 50 % overlap),
  ``K`` equivalent averages (:func:`.faultlines.welch_averages`);
* at each harmonic ``k`` (up to 5) that both envelopes carry (``k f`` under half the narrower
  band), the window of three bins at the cross-spectrum's peak near ``k f``; each side's line
  power ``P`` (the window's auto-spectrum) and noise ``N`` (the median of the bins 3-6 bins
  away on either side, times the window's bins); an inner ring's line, which the shaft turns
  through the load zone, is a comb of shaft sidebands as strong as itself: its window holds two
  teeth either side (segments of at least ``3 f / f_shaft`` periods part them) and its noise
  the bins out to 24 that lie off every tooth; its line-to-noise ratio
  ``rho = (P - N) / N``;
* the window's coherence ``g2 = (sum |S_ab|)^2 / (P_a P_b)``, and what a perfect copy in this
  noise would give, ``g2_copy``, taken segment by segment (:func:`_copy_g2`): each side's line
  power in segment ``j``, ``s_j = P_j - N_j`` (at least 0), and ``g2_copy = (sum_j sqrt(s_a,j
  s_b,j))^2 / (sum_j P_a,j sum_j P_b,j)``, the coherence of two lines in step whose strengths
  are what each side shows; where the lines keep their strength over the record it is
  ``rho_a / (1 + rho_a) rho_b / (1 + rho_b)`` (Bendat and Piersol, Random Data, 4th ed., sec.
  9.2.3: the coherence of two records of one signal in uncorrelated noise), where a copy's
  strength changes it is lower, by what the change alone takes (below, "While the speed
  changes"); their ratio, the *coherent fraction* ``c = g2 / g2_copy``, is the share of the two
  lines that is one train: 1 for a copy whatever its noise and its strength's course, less for
  two trains;
* a test of ``g2`` against ``g2_copy``: ``z = (atanh sqrt(g2_copy) - atanh sqrt(g2))
  sqrt(2 K - 2)``, the Fisher transform of the coherence magnitude, whose standard deviation is
  ``1 / sqrt(2 K - 2)`` (ibid.).  The noise beside the line holds some of the line's spread, so
  ``g2_copy`` is biased low and a copy's ``z`` mostly negative: the test errs on the copy's side.

The decision (:meth:`Timing.decide`, with the thresholds of the
:class:`.criterion.Criterion` that asks): a harmonic is *usable* when both sides' ``rho`` reach
``rho_min_db`` and *significant* when also ``z >= z_min``; the two lines are *independent* when
a significant harmonic of some pair has ``c <= c_independent``; *partly coherent* when the
lowest is under ``C_COPY``; *coherent* otherwise; *inconclusive* when no harmonic is usable (a
weak line is never shown to be its own: it is then read as a copy, the safe side).

Where the thresholds come from (synthetic families with known answers and the model, never the
real records; benchmarks/README.md "Copy or source"); they are fields of
:class:`.criterion.Criterion`, whose defaults these are:

* ``c_independent = 0.2``: copies of the synthetic family (one source, its copy through a delay
  of 0-5 ms and a path resonance of 300-3000 Hz, transmission 0.05-1, signal to noise 0-20 dB,
  10 s) read ``c`` of 0.98 and over on every usable harmonic of every pair; the coupled car's
  copies, whose path is not quite fixed (the wheelset turns; the healthy side's arrival is the
  build-up of its bending modes), down to 0.34 (one-sided outer-ring, inner-ring and roller
  defects of the study and the kinds-and-sides study, 20-80 km/h, 1.5-3.5 s); two faults of the
  synthetic family 0.000-0.1 (median 0.003), and in the car (its two cages wander against each
  other by a millisecond or so over a second) 0.004-0.09 once the record holds 2.5 s at 40 km/h
  (1.5 s reads 0.39 there: the drift needs seconds to show);
* ``rho_min_db = 15``: at 10 dB the car's copies read down to 0.22 on single harmonics in bands
  where the defect side's own line barely clears its floor;
* ``z_min = 5``: with up to five harmonics of a few hundred pairs, a chance dip of a copy's
  coherence stays under it;
* ``C_COPY = 0.8`` only labels the middle ground (partly coherent: a copy through a path that
  changes, or two trains locked together) for the report; it calls nothing.

These figures were measured with the stationary reference ``rho_a / (1 + rho_a) rho_b / (1 +
rho_b)``; the segments' reads copies the same or higher (the validation car at 48 km/h 0.55 ->
0.57; the 80 km/h one-sided copy of the kinds-and-sides study 0.60 -> no harmonic significantly
under a copy) and two faults the same (0.004, 0.008 at 80 km/h): benchmarks/copy_traction.py.

While the speed changes (the envelopes on the shaft's clock, :mod:`.clock`), measured on the
accelerating car (configs/accelerating_20_60kmh.toml: a 3 s run, 20-29 km/h read, and a 4 s
run, 20-33 km/h; the defect on wheelset 2's right side) and on the swept pair of
:mod:`.synthetic` (benchmarks/README.md "The copy under traction"):

* *The copy's strength changes with the running state* (mended here).  The healthy side carries
  the copy in step with its source (its lines locked to the defect row's roller passes), but its
  envelope's pulse changes as the car speeds up (3 s run, 312.5-625 Hz, 20-23 -> 26-29 km/h:
  peak 1.6 -> 3.3 ms after the impact, width 5.4 -> 7.7 ms; the defect side's holds), and its
  5th harmonic fades into the floor (117 -> 8 against a floor of 18 and 6) while the defect
  side's holds (62 -> 48); in the healthy side's other bands its 5th over 1st harmonic follows
  the drive's torque split between the wheels (the left wheel's creep force, partial
  correlations +0.44 to +0.66 at a given speed).  No fixed filter of the harmonic's frequency
  does that, the band's edge (at one frequency, 99-102 Hz, the sides' ratio reads 0.14-0.48
  late and 1.5-2.1 early), nor any fixed delay (the healthy side shifted by -20 to +20 ms before
  the clock: 0.63 at best).  The stationary reference took the change for a second train (0.58 at the 5th
  harmonic over the 3 s run's 2.5 s; 0.11 in the 4 s run's window 0.62-2.64 s); the segments'
  reads 0.90 and 0.17, no harmonic significantly under a copy, and the order-tracked reading is
  right there without the second look.
* *The copy's timing against its source changes with the running state* (not mended: the
  second look, pipelines/speed.py).  In the 4 s run's window 1.18-3.07 s the healthy side's 5th
  harmonic in 781-1094 Hz turns against the defect side's by 3-4 rad from 2.2 to 2.9 Hz of
  shaft speed and back where it nearly vanishes (its 5th over 1st harmonic 0.025 at 3.0 Hz),
  while its lower harmonics turn less (0.95, 0.85, 0.61, 0.18 at k = 1-4, none significantly
  under a copy; each harmonic's best fixed delay -5 to -10 ms for k = 1-4, +40 ms for k = 5: no
  one delay).  It comes with the drive's torque split between the wheels,
  the axle's torsion: there the left (healthy side's) wheel's longitudinal creep force falls
  from 6-9 kN to 0.3-1.3 kN and back, and the healthy side's 5th over 1st harmonic follows that
  force at a given speed (partial correlations over twelfths of the run +0.41 to +0.75 in 7 of
  its 11 own bands; 469-781 Hz +0.24, the three from 1250 Hz -0.26 to +0.03); in 312.5-625 Hz
  the speed leads (-0.85; in the 3 s run -0.96, the force's partial -0.13).  The copy is one
  train, but its relation to its source is not fixed, and on one speed ramp its turn and two
  trains' drift are not told apart: 0.10 there, significantly under a copy.
* *A path's delay turns the copy's lines* (not mended: the second look).  A delay ``tau`` in
  time is ``f(t) tau`` turns on the clock, so harmonic ``k`` of order ``O`` turns against its
  source by ``2 pi k O (f1 - f0) tau`` over the record (tests/test_diagnostics_coherence.py, to
  0.005 of the closed form): negligible for the car (0.99 at the 5th harmonic for 1.2 ms), 0.70
  for 1.2 ms over 20-80 km/h, and for 5 ms there the copy reads independent.  On one speed ramp
  that turn and two trains' drift both grow with ``k`` and nearly linearly in time, and the
  copy's lag read in time is not the delay that turns its lines (the path's ringing adds 1.4-2.2
  ms to it; taking it out took a copy with no delay from 1.06 to 0.56 at its 5th harmonic).

Not told apart: two inner-ring defects on one axle in the car read coherent (4 s at 40 and
80 km/h): the load zone's passage, once a turn of the shared axle, modulates both alike, and
their trains do not drift apart within the record.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view
from scipy.signal import get_window

from axlebox._params import ParameterError

from . import faultlines
from .thresholds import Criterion
from .envelope import _signal, check_fs, envelope

# the thresholds that decide (rho_min_db, z_min, c_independent) are Criterion's fields
C_COPY = 0.8            # over which (or not significantly under) they are one train (a label)
NEAR_DB = 3.0           # bands within 3 dB of a side's best for its line are its own bands
N_PERIODS = 8           # a segment holds at least 8 line periods ...
SEGMENTS = 16           # ... and the record at least 16 of them (31 with the overlap)
K_MAX = 5
COMB = {"BPFI": 2}      # shaft sidebands either side that belong to the line (a turning ring)
DECISIONS = ("independent", "partly coherent", "coherent", "inconclusive")


@dataclass(frozen=True)
class Harmonic:
    """One harmonic ``k`` at ``f`` Hz of one pair of bands: each side's line-to-noise ratio
    (dB), the window's coherence ``g2``, the copy's ``g2_copy``, the coherent fraction ``c`` and
    the test ``z`` (module docstring)."""

    k: int
    f: float
    rho_a_db: float
    rho_b_db: float
    g2: float
    g2_copy: float
    c: float
    z: float

    def is_usable(self, rho_min_db: float = Criterion.rho_min_db) -> bool:
        """Both sides' line-to-noise ratio at least ``rho_min_db``."""
        return min(self.rho_a_db, self.rho_b_db) >= rho_min_db

    def is_significant(self, rho_min_db: float = Criterion.rho_min_db,
                       z_min: float = Criterion.z_min) -> bool:
        """Usable, and its coherence ``z_min`` standard deviations under a copy's."""
        return self.is_usable(rho_min_db) and self.z >= z_min


@dataclass(frozen=True)
class BandPair:
    """The harmonics of the line between side a's envelope in ``band_a`` and b's in ``band_b``."""

    band_a: tuple[float, float]
    band_b: tuple[float, float]
    harmonics: tuple[Harmonic, ...]


@dataclass(frozen=True)
class Timing:
    """Whether the line on the two sides is one impulse train (module docstring).  ``line``;
    ``f``: its frequency (Hz); ``K``: equivalent averages; ``pairs``: every pair of the two
    sides' own bands, the first the pair of their best bands.  The thresholds of
    :meth:`decide` and :meth:`coherent_fraction` are the criterion's (default its defaults);
    :attr:`decision` and :attr:`c_min` are their readings under the defaults."""

    line: str
    f: float
    K: float
    pairs: tuple[BandPair, ...]

    def _least(self, rho_min_db: float, z_min: float):
        """``(c, pair, harmonic)`` of the significant harmonic with the lowest ``c``, or None."""
        sig = [(h.c, p, h) for p in self.pairs for h in p.harmonics
               if h.is_significant(rho_min_db, z_min)]
        return min(sig, key=lambda t: t[0]) if sig else None

    def coherent_fraction(self, rho_min_db: float = Criterion.rho_min_db,
                          z_min: float = Criterion.z_min) -> float | None:
        """The lowest coherent fraction of a significant harmonic (None: none is)."""
        t = self._least(rho_min_db, z_min)
        return None if t is None else float(t[0])

    def decide(self, c_independent: float = Criterion.c_independent,
               rho_min_db: float = Criterion.rho_min_db, z_min: float = Criterion.z_min) -> str:
        """One of :data:`DECISIONS` under these thresholds (module docstring)."""
        if not any(h.is_usable(rho_min_db) for p in self.pairs for h in p.harmonics):
            return "inconclusive"
        c = self.coherent_fraction(rho_min_db, z_min)
        if c is not None and c <= c_independent:
            return "independent"
        return "partly coherent" if c is not None and c <= C_COPY else "coherent"

    @property
    def c_min(self) -> float | None:
        """:meth:`coherent_fraction` under the default criterion."""
        return self.coherent_fraction()

    @property
    def decision(self) -> str:
        """:meth:`decide` under the default criterion."""
        return self.decide()

    def to_dict(self, c_independent: float = Criterion.c_independent,
                rho_min_db: float = Criterion.rho_min_db, z_min: float = Criterion.z_min) -> dict:
        t = self._least(rho_min_db, z_min)
        return {"line": self.line, "f": self.f, "K": self.K,
                "decision": self.decide(c_independent, rho_min_db, z_min),
                "c_min": None if t is None else float(t[0]), "n_pairs": len(self.pairs),
                "best_pair": asdict(self.pairs[0]) if self.pairs else None,
                "least_coherent": None if t is None else
                {"band_a": t[1].band_a, "band_b": t[1].band_b, **asdict(t[2])},
                "thresholds": {"rho_min_db": rho_min_db, "z_min": z_min,
                               "c_independent": c_independent, "c_copy": C_COPY,
                               "near_db": NEAR_DB}}


def _fisher(g2: float) -> float:
    return math.atanh(min(math.sqrt(max(g2, 0.0)), 1.0 - 1e-12))


def _segments(e: np.ndarray, nper: int) -> np.ndarray:
    """The Hann-windowed FFTs of the 50 %-overlapping segments of ``e`` (means removed), the
    terms of a Welch estimate: (segments, bins)."""
    seg = sliding_window_view(e, nper)[::nper - nper // 2]
    seg = seg - seg.mean(axis=1, keepdims=True)
    return np.fft.rfft(seg * get_window("hann", nper), axis=1)


LN2 = math.log(2.0)      # an exponential variable's median over its mean (a noise bin's power)
HALF = 24                # bins each side of a harmonic kept: the window and its noise ring


def _bins(sideband_bins: float | None, comb: int) -> tuple[np.ndarray, np.ndarray]:
    """``(window, ring)``: the line's bins and the noise ring's (offsets from the harmonic).
    Without shaft sidebands (or with them beyond the ring): the three bins at the line, and 3-6
    bins either side.  A fault the
    shaft modulates (an inner ring turning through the load zone) makes its line a comb
    ``sideband_bins`` apart, the sidebands as strong as the line: the window holds the ``comb``
    teeth either side with the line, a bin either side of each, and the ring the bins out to
    ``HALF`` more than a bin from every tooth beyond them."""
    near = np.r_[-6:-2, 3:7]
    if not sideband_bins or comb == 0 and sideband_bins > 7:
        return np.arange(-1, 2), near
    teeth = np.arange(-comb, comb + 1) * sideband_bins
    win = np.unique(np.clip(np.round(teeth[:, None] + np.arange(-1, 2)[None, :]), -HALF, HALF)
                    .astype(int))
    off = np.r_[-HALF:-2, 3:HALF + 1]
    m = np.arange(1, int(HALF / sideband_bins) + 2)
    side = np.r_[-m, m] * sideband_bins
    far = np.abs(off) > (comb + 0.5) * sideband_bins + 1
    keep = off[far & (np.min(np.abs(off[:, None] - side[None, :]), axis=1) > 1.0)]
    return win, (keep if keep.size >= 8 else near)


def _copy_g2(Za, Zb, win, ring) -> float:
    """What a perfect copy would give the window's coherence, segment by segment: each side's
    line power in segment ``j``, ``s_j = P_j - N_j`` (the window's bins ``win`` less the noise,
    the median of the ring's bins ``ring`` over ``ln 2``, an exponential variable's median over
    its mean; at least 0), and ``g2_copy = (sum_j sqrt(s_a,j s_b,j))^2 / (sum_j P_a,j sum_j
    P_b,j)``: the Cauchy-Schwarz bound of the segments' cross-spectrum for two lines in step
    whose strengths are what each side shows.  Where the lines hold their strength over the
    record it is Bendat and Piersol's ``rho_a / (1 + rho_a) rho_b / (1 + rho_b)``; where a
    copy's strength changes (the accelerating car: module docstring) it is lower, by what the
    change alone takes from the coherence, so ``c`` reads the lines' timing alone."""
    P = [np.sum(np.abs(Z[:, win]) ** 2, axis=1) for Z in (Za, Zb)]
    s = [np.maximum(p - win.size * np.median(np.abs(Z[:, ring]) ** 2, axis=1) / LN2, 0.0)
         for p, Z in zip(P, (Za, Zb))]
    return float(np.sum(np.sqrt(s[0] * s[1])) ** 2 / max(float(np.sum(P[0]) * np.sum(P[1])), 1e-300))


def _harmonic(Za, Zb, k, f_bin, K, win, ring) -> Harmonic:
    """The statistics of one harmonic from the two sides' segment FFTs over the bins centred on
    it; ``win``/``ring``: the line's and the noise's bin offsets (:func:`_bins`)."""
    Saa = np.mean(np.abs(Za) ** 2, axis=0)
    Sbb = np.mean(np.abs(Zb) ** 2, axis=0)
    Sab = np.mean(Za * np.conj(Zb), axis=0)
    i = Za.shape[1] // 2                                    # the cross-spectrum's peak
    Pa, Pb = float(Saa[i + win].sum()), float(Sbb[i + win].sum())
    n = win.size
    Na, Nb = n * float(np.median(Saa[i + ring])), n * float(np.median(Sbb[i + ring]))
    ra = max(Pa - Na, 0.0) / max(Na, 1e-300)
    rb = max(Pb - Nb, 0.0) / max(Nb, 1e-300)
    g2 = float(np.abs(Sab[i + win]).sum() ** 2 / max(Pa * Pb, 1e-300))
    g2c = _copy_g2(Za, Zb, i + win, i + ring)
    c = g2 / g2c if g2c > 0 else math.nan
    z = (_fisher(g2c) - _fisher(g2)) * math.sqrt(max(2 * K - 2, 1.0))
    db = [10 * math.log10(r) if r > 0 else -math.inf for r in (ra, rb)]
    return Harmonic(k, float(f_bin[i]), db[0], db[1], g2, g2c, c, z)


def timing(xa, xb, fs: float, f_line: float, bands_a, bands_b, *, line: str = "line",
           n_periods: int | None = None, k_max: int = K_MAX, fine_df: float | None = None,
           shaft_hz: float | None = None, comb: int = 0) -> Timing:
    """:class:`Timing` of the line at ``f_line`` Hz between channels ``xa`` and ``xb`` (same
    length and rate ``fs``), their envelopes taken in each of ``bands_a`` and ``bands_b`` (Hz;
    the first of each the side's best band) and compared pair by pair.  ``shaft_hz``: the
    shaft's frequency, whose sidebands of the line are kept out of the noise ring; ``comb``:
    how many of them either side belong to the line (:func:`_bins`; then segments of at least
    ``3 f_line / shaft_hz`` periods part them)."""
    xa, xb = _signal(xa, "xa"), _signal(xb, "xb")
    fs = check_fs(fs)
    if xa.size != xb.size:
        raise ParameterError(f"channels of {xa.size} and {xb.size} samples are not allowed: "
                             "expected the same length")
    if not (np.isfinite(f_line) and 0 < f_line < fs / 4):
        raise ParameterError(f"f_line = {f_line!r} Hz is not allowed: expected 0 < f < fs/4")
    if not bands_a or not bands_b:
        raise ParameterError("bands_a and bands_b are not allowed empty: expected each side's "
                             "bands")
    if n_periods is None:                   # about 30 segments, each at least 8 periods
        n_periods = max(N_PERIODS, int(xa.size * f_line / fs) // SEGMENTS,
                        math.ceil(3 * f_line / shaft_hz) if shaft_hz and comb else 0)
    nper = min(xa.size, int(round(n_periods * fs / f_line)))
    K = faultlines.welch_averages(xa.size, nper)
    f_bin = np.fft.rfftfreq(nper, 1.0 / fs)
    df = f_bin[1]
    win, ring = _bins(shaft_hz / df if shaft_hz else None, comb)
    half = int(max(np.abs(win).max(), np.abs(ring).max())) + 1
    spread = 0.01 * f_line if fine_df is None else 0.5 * fine_df   # uncertainty of f_line
    Z = {}
    for side, x, bands in (("a", xa, bands_a), ("b", xb, bands_b)):
        for b in bands:
            Z[side, tuple(b)] = _segments(envelope(x, fs, b), nper)
    pairs = []
    for ba in bands_a:
        for bb in bands_b:
            top = min(ba[1] - ba[0], bb[1] - bb[0]) / 2
            hs = []
            for k in range(1, k_max + 1):
                i0 = int(round(k * f_line / df))
                w = 1 + int(k * spread / df)        # f_line known to half a fine bin
                if (i0 + w + half) * df > top or i0 + w + half >= f_bin.size:
                    break
                if i0 - w - half < 0:               # the ring reaches below 0 Hz: the next
                    continue
                Sab = np.mean(Z["a", tuple(ba)][:, i0 - w:i0 + w + 1]
                              * np.conj(Z["b", tuple(bb)][:, i0 - w:i0 + w + 1]), axis=0)
                i = i0 - w + int(np.argmax(np.abs(Sab)))
                sl = slice(i - half, i + half + 1)
                hs.append(_harmonic(Z["a", tuple(ba)][:, sl], Z["b", tuple(bb)][:, sl], k,
                                    f_bin[sl], K, win, ring))
            pairs.append(BandPair(tuple(map(float, ba)), tuple(map(float, bb)), tuple(hs)))
    return Timing(line, float(f_line), float(K), tuple(pairs))


def own_bands(scan, near_db: float = NEAR_DB) -> list[tuple[float, float]]:
    """A side's own bands for a line, from its :class:`.guided.BandScan`: where the line is
    detected within ``near_db`` of its best, best first (the best band alone when none
    detects it)."""
    idx = scan.near_best(near_db) or [scan.best]
    return [scan.bands[i] for i in idx]


def line_timing(xa, xb, fs: float, scan_a, scan_b, name: str, *,
                near_db: float = NEAR_DB, shaft_hz: float | None = None) -> Timing:
    """:func:`timing` of line ``name`` seen on both channels, from each side's
    :class:`.guided.BandScan` of it: each side's own bands (:func:`own_bands`), at the
    frequency found in the best band of the side where the line stands higher; an inner ring's
    line (BPFI) with its first two shaft sidebands either side (``COMB``)."""
    tops = [sc.lines[sc.best] for sc in (scan_a, scan_b)]
    best = max(tops, key=lambda r: r.snr_db)
    f1 = best.f_found if best.f_found is not None else best.searched[0][1]
    return timing(xa, xb, fs, f1, own_bands(scan_a, near_db), own_bands(scan_b, near_db),
                  line=name, shaft_hz=shaft_hz, comb=COMB.get(name, 0))
