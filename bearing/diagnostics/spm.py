"""Shock pulse method (SPM) level of a bearing, paper Eq. 17, with the shock value from EMD.

Eq. 17:  ``SPM = 20 log10(2000 SV / (n_b D^0.6))``  dB, ``n_b`` the shaft (wheelset) speed and
``D`` the bearing's inside (bore) diameter.  This is the SPM Instrument normalisation
``dBn = dBsv - dBi`` with ``dBsv = 20 log10 SV`` and the "initial value" ``dBi`` that the
instruments compute from the rpm and the shaft diameter in millimetres (SPM T30 manual, "Normalized
and unnormalized readings"; SPM BDM-40 manual: d = 20 mm at 1100 rpm gives dBi = 10, and
``20 log10(1100 * 20^0.6 / 2000) = 10.4``).  So the empirical constants take ``n_b`` in rev/min
and ``D`` in mm; the API keeps SI (``n_b_hz`` in Hz, ``D`` in m) and converts once, in
:func:`spm_db`.  Bands (the paper, after its Ref. 40; the instruments' green/yellow/red zones):
below 21 dB normal, 21-35 dB mild fault, above 35 dB serious fault (:func:`classify`).

Shock value SV (m/s^2 for an acceleration in m/s^2): the paper demodulates the intrinsic mode
functions (IMFs) of the empirical mode decomposition (PyEMD).  Here, on each of ``n_segments``
segments spread evenly over the record, each ``n_periods`` fault periods long (``period_s``,
:func:`..channel.analyse` passes 1/BPFO; without it ``seg_s`` seconds):

1. the segment (mean removed) is scaled to unit standard deviation, decomposed into at most
   ``max_imf`` IMFs (extrema refined by parabolic interpolation, since a resonance of a few kHz
   has only a few samples a cycle at 10 kHz; found on runs of equal samples, :class:`SiftEMD`)
   and scaled back, so SV is exactly proportional to the amplitude (PyEMD's stopping thresholds
   are absolute numbers);
2. IMFs are kept from the first up to the most impulsive one (highest Pearson kurtosis):
   EMD sorts content from high to low frequency, the impulses ring the structure's
   high-frequency resonances, so they land in the first IMF(s) (split over two when modes
   mix), while the later IMFs carry the large but smooth low-frequency motion (shaft, track,
   body modes) that would swamp the shock level;
3. the shock level of the segment is the maximum of the Hilbert envelope of the sum of those
   IMFs (the SPM "maximum value" is the strongest pulse in the measuring time), over the
   segment less 10 % at each end (EMD and Hilbert edge effects).

SV is the median of the segment levels (robust to a single rail-joint hit).  Segments of a fixed
number of fault periods hold the same number of impulses at any speed, so the maximum does not
grow with the impulse rate: SV measures the impulse height, and Eq. 17's ``1/n_b`` is the only
speed term (tests: -6.02 dB when the speed doubles).  EMD cost is bounded: 16 segments of 4
BPFO periods (900 samples at 48 km/h and 10 kHz) whatever the record length, segments capped
at 1 s.  The absolute dB depend on the sensor: the SPM instruments' dBsv come from their own
32 kHz transducer, an accelerometer's m/s^2 are not that unit, so compare sides and conditions
rather than reading the bands as an instrument would.
"""
from __future__ import annotations

import math

import numpy as np
from PyEMD import EMD
from scipy.signal import hilbert
from scipy.stats import kurtosis

from axlebox._params import ParameterError

from .envelope import _signal, check_fs

NORMAL_BELOW_DB = 21.0
SERIOUS_ABOVE_DB = 35.0


def run_extrema(T: np.ndarray, S: np.ndarray):
    """``(max_pos, max_val, min_pos, min_val, indzer)`` of ``S`` sampled at ``T``, as PyEMD's
    ``EMD.find_extrema`` returns them, found on the runs of equal samples.

    An extremum is a run of equal samples (one sample or more, not at either end) above both
    neighbouring runs (a maximum) or below both (a minimum).  A one-sample extremum at ``k`` is
    refined by the parabola through ``k - 1``, ``k``, ``k + 1``, with PyEMD's own arithmetic
    (``EMD._find_extrema_parabol``), so that on a record without equal neighbours the extrema
    are PyEMD's to the last bit; its vertex lies within half a sample of ``k`` (the middle
    sample is above or below both others), clipped there against rounding.  A run of two or
    more samples stands at its middle with its value: the samples of a quantized signal near
    its peak lie within half a step of it, and nothing in them says on which side the peak is.

    Why not PyEMD's parabolic detection (``extrema_detection="parabol"``): it fits a parabola
    to every three consecutive samples and keeps its vertex where it falls within half a sample
    of the middle one.  Two equal neighbours put the vertex exactly on that half-sample border,
    so every step of a quantized record (values stored to 0.001 of a unit whose RMS is 0.06:
    about 2 % of the samples equal their neighbour) becomes an extremum, on a rising or falling
    slope too, once or (by rounding) twice, a maximum and a minimum at one time.  Maxima and
    minima then no longer alternate, and PyEMD's mirroring of the extrema at the record's ends
    (``EMD.prepare_points_parabol``, which assumes they do) leaves knots out of order or short
    of the ends: scipy's spline refuses them (``ValueError: `x` must be strictly increasing
    sequence``, a real record's SPM stopped on it) or the envelopes come out shorter than the
    record (a broadcast error).  Here maxima and minima alternate by construction, one a run,
    each within its own run's span, so the positions increase strictly; PyEMD's
    ``extrema_detection="simple"`` finds plateaus so too but gives up the parabolic refinement.

    ``indzer``: the zero crossings, as PyEMD counts them (for its stopping rule)."""
    S1, S2 = S[:-1], S[1:]
    indzer = np.nonzero(S1 * S2 < 0)[0]
    if np.any(S == 0):                     # PyEMD's: a run of zeros is one crossing, at its middle
        indz = np.nonzero(S == 0)[0]
        if np.any(np.diff(indz) == 1):
            dz = np.diff(np.concatenate(([0], S == 0, [0])))
            indz = np.round((np.nonzero(dz == 1)[0] + np.nonzero(dz == -1)[0] - 1) / 2.0)
        indzer = np.sort(np.append(indzer, indz))
    first = np.flatnonzero(np.r_[True, S[1:] != S[:-1]])          # each run's first sample
    last = np.r_[first[1:] - 1, S.size - 1]
    v = S[first]
    mid = slice(1, -1)                                             # the end runs are not extrema
    is_max = (v[mid] > v[:-2]) & (v[mid] > v[2:])
    is_min = (v[mid] < v[:-2]) & (v[mid] < v[2:])
    f, la = first[mid], last[mid]
    pos = 0.5 * (T[f] + T[la])                                     # runs of two or more samples
    val = v[mid].copy()
    one = np.flatnonzero((f == la) & (is_max | is_min))
    if one.size:
        k = f[one]
        Tp, T0, Tn = T[k - 1], T[k], T[k + 1]
        Sp, S0, Sn = S[k - 1], S[k], S[k + 1]
        # EMD._find_extrema_parabol's arithmetic, term by term
        TnTp, T0Tn, TpT0 = Tn - Tp, T0 - Tn, Tp - T0
        scale = Tp * Tn * Tn + Tp * Tp * T0 + T0 * T0 * Tn - Tp * Tp * Tn - Tp * T0 * T0 - T0 * Tn * Tn
        a = (T0Tn * Sp + TnTp * S0 + TpT0 * Sn) / scale
        b = ((S0 - Sn) * Tp**2 + (Sn - Sp) * T0**2 + (Sp - S0) * Tn**2) / scale
        c = (T0 * Tn * T0Tn * Sp + Tn * Tp * TnTp * S0 + Tp * T0 * TpT0 * Sn) / scale
        a[a == 0] = 1e-14
        t = np.clip(-0.5 * b / a, T0 - 0.5 * (T0 - Tp), T0 + 0.5 * (Tn - T0))
        pos[one], val[one] = t, a * t * t + b * t + c
    return pos[is_max], val[is_max], pos[is_min], val[is_min], indzer


class SiftEMD(EMD):
    """PyEMD's EMD (cubic-spline envelopes, its mirroring at the ends and stopping rules) with
    the parabolic extrema of :func:`run_extrema`, which hold on records with runs of equal
    samples (quantized, clipped or held)."""

    def __init__(self, **kw):
        super().__init__(extrema_detection="parabol", **kw)    # parabol: the mirroring of points off the grid

    def find_extrema(self, T, S):
        """The extrema of ``S`` at times ``T``: :func:`run_extrema`."""
        return run_extrema(T, S)


def _segment_level(seg: np.ndarray, max_imf: int) -> float:
    seg = seg - seg.mean()
    s = seg.std()
    if s == 0.0:
        return 0.0
    emd = SiftEMD()
    emd.emd(seg / s, max_imf=max_imf)
    imfs, _ = emd.get_imfs_and_residue()
    if imfs.shape[0] == 0:
        imfs = (seg / s)[None, :]
    k = np.array([kurtosis(m, fisher=False) if m.std() > 0 else 0.0 for m in imfs])
    j = int(np.argmax(k))
    env = np.abs(hilbert(imfs[: j + 1].sum(axis=0)))
    m = int(0.1 * seg.size)
    return float(s * env[m: seg.size - m].max())


def shock_value(x, fs: float, period_s: float | None = None, n_periods: float = 4.0,
                n_segments: int = 16, max_imf: int = 4, seg_s: float = 0.25, keep=None) -> float:
    """SV (units of ``x``, m/s^2 for acceleration): median over ``n_segments`` segments of
    ``n_periods * period_s`` s (or ``seg_s`` s without ``period_s``; at most 1 s) of the peak
    Hilbert envelope of the impulsive IMFs (module docstring).  Records shorter than the
    segments get fewer of them, or one of the whole record.  ``keep`` (bool, like ``x``): the
    segments lie wholly where it is True (a record whose wheel strikes were blanked,
    :mod:`.gate`: EMD has no extrema to follow in a run of zeros)."""
    x = _signal(x)
    fs = check_fs(fs)
    for name, v in (("period_s", period_s), ("n_periods", n_periods), ("seg_s", seg_s)):
        if v is not None and not (np.isfinite(v) and v > 0):
            raise ParameterError(f"{name} = {v!r} is not allowed: expected a number > 0")
    if not (isinstance(n_segments, int) and n_segments >= 1):
        raise ParameterError(f"n_segments = {n_segments!r} is not allowed: expected an integer >= 1")
    if not (isinstance(max_imf, int) and max_imf >= 1):
        raise ParameterError(f"max_imf = {max_imf!r} is not allowed: expected an integer >= 1")
    T = seg_s if period_s is None else n_periods * period_s
    L = min(x.size, max(32, int(round(min(T, 1.0) * fs))))
    n = max(1, min(n_segments, x.size // L))
    starts = np.linspace(0, x.size - L, n).astype(int)
    if keep is not None:
        gaps = np.r_[0, np.cumsum(~np.asarray(keep, bool))]
        whole = np.flatnonzero(gaps[L:] - gaps[:-L] == 0)       # starts of gap-free segments
        if whole.size:
            n = max(1, min(n_segments, int(np.count_nonzero(keep)) // L))
            starts = whole[np.linspace(0, whole.size - 1, n).astype(int)]
    return float(np.median([_segment_level(x[i:i + L], max_imf) for i in starts]))


def spm_db(SV: float, n_b_hz: float, D: float) -> float:
    """Eq. 17: ``20 log10(2000 SV / (n_b D^0.6))`` with ``n_b = 60 n_b_hz`` rev/min and
    ``D = 1000 D`` mm, the units of the SPM constants (module docstring).  ``SV`` in m/s^2,
    ``n_b_hz`` the shaft speed in Hz, ``D`` the bearing bore in m."""
    for name, v in (("SV", SV), ("n_b_hz", n_b_hz), ("D", D)):
        if isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) \
                or not math.isfinite(v) or not v > 0:
            raise ParameterError(f"{name} = {v!r} is not allowed: expected a finite number > 0")
    n_rpm = 60.0 * n_b_hz
    D_mm = 1000.0 * D
    return 20.0 * math.log10(2000.0 * SV / (n_rpm * D_mm ** 0.6))


def classify(db: float) -> str:
    """The paper's bands: ``db < 21`` "normal" (readings below 0 dB too), ``21 <= db <= 35``
    "mild", ``db > 35`` "serious" (the paper's scale ends at 60 dB; above it is serious too)."""
    if isinstance(db, bool) or not isinstance(db, (int, float, np.floating, np.integer)) \
            or math.isnan(db):
        raise ParameterError(f"SPM = {db!r} dB is not allowed: expected a number")
    if db < NORMAL_BELOW_DB:
        return "normal"
    return "mild" if db <= SERIOUS_ABOVE_DB else "serious"
