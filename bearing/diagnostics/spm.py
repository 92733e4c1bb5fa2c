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
   has only a few samples a cycle at 10 kHz) and scaled back, so SV is exactly proportional to
   the amplitude (PyEMD's stopping thresholds are absolute numbers);
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


def _segment_level(seg: np.ndarray, max_imf: int) -> float:
    seg = seg - seg.mean()
    s = seg.std()
    if s == 0.0:
        return 0.0
    emd = EMD(extrema_detection="parabol")
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
