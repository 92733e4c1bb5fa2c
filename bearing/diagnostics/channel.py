"""All one-channel indicators of an axle-box signal: :func:`analyse` -> :class:`ChannelResult`.

* time ___domain (:mod:`.indicators`): RMS, peak, kurtosis, crest factor of the raw signal;
* FC, VF, MSF (:mod:`.spectral`, Eq. 18) on the Welch PSD of the raw signal;
* envelope spectrum (:mod:`.envelope`) in the user's band or the band of highest spectral
  kurtosis, no narrower than ``2 (n_harmonics + 1)`` times the highest fault line (so the
  envelope carries the harmonics searched); or, with ``guide``, the band where that fault line
  stands highest (:mod:`.guided`, thresholds corrected for the bands tried);
* fault lines (:mod:`.faultlines`): BPFO, BPFI, 2BSF (a rolling element's defect, with its cage
  sidebands) and FTF of this side's bearing; and, where the other side's bearing differs
  (``other``), that bearing's BPFO, BPFI and 2BSF wherever their search windows do not overlap
  this bearing's of the same kind (:func:`distinct`): a line at the other bearing's order is
  *carried* across,
  not this bearing's own.  All are searched in one spectrum, so that a line that is the other's
  shaft sideband, or the same peak, is masked (:func:`.faultlines.mask_sidebands`).  The
  envelope spectrum is a Welch average with a resolution of a tenth of the lowest line (FTF at
  48 km/h: 0.22 Hz, 4.5 s segments), or the whole record as one window when it is shorter; the
  record must hold at least two periods of the lowest line;
* SV and the SPM level and band (:mod:`.spm`, Eq. 17), on segments of ``spm_periods`` BPFO
  periods (the outer-ring defect this project studies; any fixed number of periods keeps SV
  independent of speed).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from axlebox._params import ParameterError

from ..frequencies import FaultOrders
from . import faultlines, spm
from .envelope import _signal, check_fs, envelope_spectrum, select_band
from .guided import guided_band
from .indicators import time_indicators
from .thresholds import Criterion
from .spectral import check_band, fc_vf
from .wheel import spectrum_orders, wheel_orders


def jsonable(v):
    """JSON-safe copy: numpy scalars to Python, non-finite floats to None, keys to str."""
    if isinstance(v, dict):
        return {str(k): jsonable(w) for k, w in v.items()}
    if isinstance(v, (list, tuple)):
        return [jsonable(w) for w in v]
    if isinstance(v, (np.floating, float)):
        return float(v) if np.isfinite(v) else None
    if isinstance(v, np.integer):
        return int(v)
    if isinstance(v, np.bool_):
        return bool(v)
    return v


@dataclass(frozen=True)
class ChannelResult:
    """One channel's indicators (SI: m/s^2, Hz, Hz^2, dB).  ``lines``: name -> LineResult;
    ``fault_hz``: the kinematic fault frequencies searched; ``band``: the envelope band (Hz) and
    ``band_source`` "given", "spectral kurtosis" or "guided by NAME"; ``p_fa``: the false-alarm
    probability of each line window (divided by the bands tried when guided);
    ``carried``/``carried_hz``: the other side's bearing's lines searched here (empty when the
    bearings' lines coincide); ``sideband_hz``: the sideband offsets searched with a line
    (``2BSF``: the cage frequency; a carried line's key starts with ``~``);
    ``env_f``/``env_A``: the envelope spectrum (for figures; not in :meth:`to_dict`);
    ``wheel_env``/``wheel_spec``: the whole shaft orders standing over their floors in the
    envelope spectrum and in the acceleration's own spectrum (:mod:`.wheel`: a wheel flat's
    comb, a polygon's line; never a bearing's), named at the false-alarm probability
    ``shaft_p_fa`` a record."""

    fs: float
    n_samples: int
    shaft_hz: float
    D: float
    rms: float
    peak: float
    kurtosis: float
    crest: float
    FC: float
    VF: float
    MSF: float
    SV: float
    spm_db: float
    spm_class: str
    band: tuple[float, float]
    band_source: str
    p_fa: float
    fault_hz: dict
    lines: dict
    env_f: np.ndarray = field(repr=False, compare=False)
    env_A: np.ndarray = field(repr=False, compare=False)
    carried_hz: dict = field(default_factory=dict)
    carried: dict = field(default_factory=dict)
    sideband_hz: dict = field(default_factory=dict)
    vf_band: tuple[float, float] | None = None
    nperseg: int | None = None
    wheel_env: tuple[int, ...] = ()
    wheel_spec: tuple[int, ...] = ()
    shaft_p_fa: float = Criterion.shaft_p_fa

    @property
    def duration_s(self) -> float:
        return self.n_samples / self.fs

    @property
    def detected(self) -> list[str]:
        """Names of this bearing's fault lines detected."""
        return [k for k, r in self.lines.items() if r.detected]

    @property
    def detected_carried(self) -> list[str]:
        """Names of the other bearing's lines detected here."""
        return [k for k, r in self.carried.items() if r.detected]

    def to_dict(self) -> dict:
        d = {k: getattr(self, k) for k in ("fs", "n_samples", "shaft_hz", "D", "rms", "peak",
                                           "kurtosis", "crest", "FC", "VF", "MSF", "SV", "spm_db",
                                           "spm_class", "band_source", "p_fa", "fault_hz",
                                           "carried_hz", "wheel_env", "wheel_spec", "shaft_p_fa")}
        d["duration_s"] = self.duration_s
        d["band"] = list(self.band)
        d["vf_band"] = None if self.vf_band is None else list(self.vf_band)
        d["lines"] = {k: r.to_dict() for k, r in self.lines.items()}
        d["detected"] = self.detected
        d["carried"] = {k: r.to_dict() for k, r in self.carried.items()}
        d["detected_carried"] = self.detected_carried
        return jsonable(d)


CARRIED = ("BPFO", "BPFI", "2BSF")      # the other bearing's lines searched on a side


def distinct(f_a: float, f_b: float, slip: float) -> bool:
    """Whether two lines' search windows (``+- slip`` of each) do not overlap."""
    return abs(f_a - f_b) > slip * (f_a + f_b)


def line_frequencies(shaft_hz: float, orders: FaultOrders, lines, other: FaultOrders | None,
                     slip: float) -> tuple[dict, dict, dict]:
    """``(fault_hz, carried_hz, sideband_hz)`` of a side with bearing ``orders`` whose other side
    has bearing ``other`` (None: the same): this bearing's ``lines``; the other's of
    :data:`CARRIED` whose window does not overlap this bearing's line of the same kind (where a
    window overlaps a line of another kind, the peak goes to the nearer,
    :func:`.faultlines.mask_sidebands`); the sideband offsets (``2BSF``: the cage frequency;
    carried keys start with ``~``)."""
    known = orders.at(shaft_hz)
    fault_hz = {n: float(known[n]) for n in lines}
    sideband_hz = {"2BSF": float(known["FTF"])} if "2BSF" in fault_hz else {}
    carried_hz = {}
    if other is not None and other != orders:
        theirs = other.at(shaft_hz)
        for n in CARRIED:
            if n in fault_hz and distinct(theirs[n], fault_hz[n], slip):
                carried_hz[n] = float(theirs[n])
        if "2BSF" in carried_hz:
            sideband_hz["~2BSF"] = float(theirs["FTF"])
    return fault_hz, carried_hz, sideband_hz


LINES = ("BPFO", "BPFI", "2BSF", "FTF")


def analyse(x, fs: float, shaft_hz: float, orders: FaultOrders, D: float,
            band: tuple[float, float] | None = None, *, lines=LINES,
            n_harmonics: int = 3, slip: float = 0.03, threshold_db: float | None = None,
            p_fa: float = 1e-3, n_required: int = 2, nperseg: int | None = None,
            spm_periods: float = 4.0, spm_segments: int = 16, max_imf: int = 4,
            guide: str | None = None, other: FaultOrders | None = None,
            vf_band: tuple[float, float] | None = None, keep=None,
            shaft_p_fa: float = Criterion.shaft_p_fa) -> ChannelResult:
    """Indicators of the 1-D acceleration ``x`` (m/s^2) sampled at ``fs`` Hz, on a bearing
    turning at ``shaft_hz`` with fault ``orders`` (multiples of the shaft frequency) and bore
    ``D`` (m).  ``band``: envelope band (Hz), default by spectral kurtosis.  ``guide``: instead,
    the band where this line (one of ``lines``) stands highest (:mod:`.guided`).  ``lines``:
    which of the orders to search.  ``other``: the other side's bearing, whose distinct lines
    are searched too (module docstring).  ``nperseg``: Welch segment of the PSD for FC/VF;
    ``vf_band``: their band ``(lo, hi)`` Hz (:func:`.spectral.fc_vf`), default the whole.  The
    rest go to :func:`.faultlines.detect` and :func:`.spm.shock_value` (``keep``: where the
    record was not blanked, :mod:`.gate`); ``shaft_p_fa`` to :mod:`.wheel` (the criterion's)."""
    x = _signal(x)
    fs = check_fs(fs)
    for name, v in (("shaft_hz", shaft_hz), ("D", D)):
        if isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) \
                or not math.isfinite(v) or not v > 0:
            raise ParameterError(f"{name} = {v!r} is not allowed: expected a finite number > 0")
    known = orders.at(shaft_hz)
    unknown = [n for n in lines if n not in known]
    if unknown or not lines:
        raise ParameterError(f"lines = {tuple(lines)!r} is not allowed: expected names among "
                             f"{sorted(known)}")
    fault_hz, carried_hz, sideband_hz = line_frequencies(shaft_hz, orders, lines, other, slip)
    f_lo = min(fault_hz.values())
    if x.size / fs < 2.0 / f_lo:
        raise ParameterError(f"x of {x.size / fs:g} s is too short: the {min(fault_hz, key=fault_hz.get)}"
                             f" line at {f_lo:g} Hz needs at least {2.0 / f_lo:g} s")
    freqs = dict(fault_hz=fault_hz, carried_hz=carried_hz, sideband_hz=sideband_hz)
    env = _band_and_lines(x, fs, shaft_hz, freqs, band, guide, n_harmonics, slip,
                          threshold_db, p_fa, n_required, shaft_p_fa)
    t = time_indicators(x)
    vf_band = check_band(vf_band, fs)
    FC, VF, MSF = fc_vf(x, fs, nperseg, vf_band)
    SV = spm.shock_value(x, fs, period_s=1.0 / (orders.BPFO * shaft_hz), n_periods=spm_periods,
                         n_segments=spm_segments, max_imf=max_imf, keep=keep)
    level = spm.spm_db(SV, shaft_hz, D)
    return ChannelResult(fs=fs, n_samples=int(x.size), shaft_hz=float(shaft_hz), D=float(D),
                         rms=t["rms"], peak=t["peak"], kurtosis=t["kurtosis"], crest=t["crest"],
                         FC=FC, VF=VF, MSF=MSF, SV=SV, spm_db=level,
                         spm_class=spm.classify(level), **freqs, **env,
                         vf_band=vf_band, nperseg=nperseg, shaft_p_fa=shaft_p_fa,
                         wheel_spec=spectrum_orders(x, fs, shaft_hz, p_fa=shaft_p_fa))


LINE_OPTIONS = ("n_harmonics", "slip", "threshold_db", "p_fa", "n_required")   # of reguide


def reguide(res: ChannelResult, x, guide: str, *, n_harmonics: int = 3, slip: float = 0.03,
            threshold_db: float | None = None, p_fa: float = 1e-3,
            n_required: int = 2) -> ChannelResult:
    """``res`` (of :func:`analyse` on ``x``) with its envelope band, spectrum and lines redone in
    the band guided by line ``guide``: the same as ``analyse(x, ..., guide=guide)`` without
    computing again what does not depend on the band (time indicators, FC/VF, SPM)."""
    env = _band_and_lines(_signal(x), res.fs, res.shaft_hz, _freqs(res), None, guide,
                          n_harmonics, slip, threshold_db, p_fa, n_required, res.shaft_p_fa)
    return replace(res, **env)


def in_band(res: ChannelResult, x, band: tuple[float, float], *, n_harmonics: int = 3,
            slip: float = 0.03, threshold_db: float | None = None, p_fa: float = 1e-3,
            n_required: int = 2) -> ChannelResult:
    """``res`` (of :func:`analyse` on ``x``) with its envelope spectrum and lines redone in the
    given ``band``: the same as ``analyse(x, ..., band=band)`` without the band-free parts."""
    env = _band_and_lines(_signal(x), res.fs, res.shaft_hz, _freqs(res), band, None,
                          n_harmonics, slip, threshold_db, p_fa, n_required, res.shaft_p_fa)
    return replace(res, **env)


SEGMENT_S = 1.5         # s: the longest Welch segment of a fault-line spectrum (see below)


def welch_segment(n: int, fs: float, f_lo: float) -> int:
    """Samples of the Welch segment of the envelope spectrum the lines are searched in: a
    resolution of a tenth of the lowest line, but segments no longer than ``SEGMENT_S`` where
    that still resolves the lowest line (two bins under it): a bearing's lines wander with its
    slip (a roller's spin, the cages) by a few tenths of a hertz over seconds (the car's roller
    defect: 2 BSF found 31.3-32.4 Hz in one run), and a longer segment spreads them over more
    bins than the noise floor gains by them; at most the record."""
    seg_s = 10.0 / f_lo
    if seg_s > SEGMENT_S:
        seg_s = max(SEGMENT_S, 2.2 / f_lo)
    return min(n, int(round(fs * seg_s)))


def _freqs(res: ChannelResult) -> dict:
    return dict(fault_hz=res.fault_hz, carried_hz=res.carried_hz, sideband_hz=res.sideband_hz)


def _band_and_lines(x, fs, shaft_hz, freqs, band, guide, n_harmonics, slip, threshold_db,
                    p_fa, n_required, shaft_p_fa) -> dict:
    """The band-dependent fields of a :class:`ChannelResult`: the envelope band (given, by
    spectral kurtosis, or guided by line ``guide``, a key of this bearing's lines or ``~`` and
    a carried line's), its spectrum and the fault lines in it."""
    every = {**freqs["fault_hz"], **{"~" + n: f for n, f in freqs["carried_hz"].items()}}
    f_lo, f_hi = min(every.values()), max(every.values())
    seg = welch_segment(x.size, fs, f_lo)
    if guide is not None:
        if band is not None:
            raise ParameterError(f"guide = {guide!r} and band = {tuple(band)!r} are not allowed "
                                 "together: a given band leaves nothing to guide")
        if guide not in every:
            raise ParameterError(f"guide = {guide!r} is not allowed: expected one of the lines "
                                 f"searched, {sorted(every)}")
        g = guided_band(x, fs, guide, every[guide], nperseg=seg, n_harmonics=n_harmonics,
                        slip=slip, p_fa=p_fa, n_required=n_required,
                        sideband_hz=freqs["sideband_hz"].get(guide))
        band, source, p_fa = g.band, f"guided by {guide}", g.p_fa
    elif band is None:
        band = select_band(x, fs, min_width_hz=2 * (n_harmonics + 1) * f_hi)
        source = "spectral kurtosis"
    else:
        source = "given"
    f, A = envelope_spectrum(x, fs, band, nperseg=seg)
    found = faultlines.detect(f, A, every, n_harmonics=n_harmonics, slip=slip,
                              threshold_db=threshold_db, p_fa=p_fa, n_required=n_required,
                              n_avg=faultlines.welch_averages(x.size, seg), shaft_hz=shaft_hz,
                              sidebands=freqs["sideband_hz"])
    lines = {n: r for n, r in found.items() if not n.startswith("~")}
    carried = {n[1:]: replace(r, name=n[1:]) for n, r in found.items() if n.startswith("~")}
    return dict(band=(float(band[0]), float(band[1])), band_source=source, p_fa=float(p_fa),
                lines=lines, carried=carried, env_f=f, env_A=A,
                wheel_env=wheel_orders(f, A, shaft_hz, faultlines.welch_averages(x.size, seg),
                                       p_fa=shaft_p_fa,
                                       taken=[k * r.f_found for r in found.values() if r.detected
                                              for k in range(1, int(f[-1] / r.f_found) + 1)]))
