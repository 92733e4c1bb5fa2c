"""Every threshold and setting that decides a verdict, declared once: :class:`Criterion` (each
field with its type, its default and where the default comes from), the paper's constants it
rests on, and :func:`check_band`.

This module imports nothing of the diagnosis, so that every module may read its defaults from
here: the indicators (:mod:`.channel`, :mod:`.coherence`, :mod:`.gate`, :mod:`.own`,
:mod:`.wheel`) take ``Criterion``'s fields as their keyword defaults, :mod:`.verdict` holds the
criterion that decided, and :mod:`.criterion` decides with it.  The imports run one way:
thresholds -> indicators -> verdict -> criterion -> pair.  Where the VF constants come from (the
paper's Fig. 12 and 14, its integration step): :mod:`.criterion`'s docstring.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from axlebox._params import ParameterError

VF_RANGE_PAPER = (0.8e4, 7.49e4)        # Hz^2, paper Fig. 14 and conclusion (3)
VF_METRO = 5.72e4                       # Hz^2, VF of a flat PSD on 0-200 and 300-800 Hz (Fig. 12)
VF_BAND_PAPER = (0.0, 1000.0)           # Hz: the band of the paper's spectra and integration (above)
PAPER_RK4_STEP = 1e-4                   # s: the paper's fixed Runge-Kutta step for the DTRB
REL_RANGE_DEFAULT = (round(VF_RANGE_PAPER[0] / VF_METRO, 2), 1.0)
MODES = ("absolute", "relative")
LAG_POLICIES = ("decide", "veto", "off")
SOURCE_RULES = ("ringing", "paper")
COMPARABLE = ("rms", "spm_db", "peak", "kurtosis", "crest", "SV")
FAULT_LINES = ("BPFO", "BPFI", "2BSF")


@dataclass(frozen=True)
class Criterion:
    """Every setting and threshold that decides a verdict (module docstring), each with where it
    comes from.

    The paper's criterion: ``mode`` (``"absolute"`` or ``"relative"``); ``vf_range``: Hz^2, used
    in absolute mode (the paper's Fig. 14 and conclusion 3); ``rel_range``: dimensionless, used in
    relative mode (the paper's lower bound over ``VF_METRO``, module docstring); ``compare``:
    ChannelResult fields that must all be larger on the real side (the paper: RMS and SPM);
    ``vf_band``: the band ``(lo, hi)`` Hz over which each side's FC and VF are taken
    (:func:`.spectral.fc_vf`), None for the record's whole band (the default).

    Which lines count and whose they are: ``lines``: fault lines whose detection counts as a
    fault; ``c_independent``: the coherent fraction at or under which a line seen on both sides
    is two impulse trains, a fault on each side (0.2: the synthetic family's copies read 0.98
    and over, the coupled car's down to 0.34; two faults 0.000-0.1 and in the car 0.004-0.09,
    :mod:`.coherence` "Where the thresholds come from"); ``rho_min_db``: the line-to-noise ratio
    both sides' line must reach at a harmonic for that harmonic to count (15 dB: at 10 dB the
    car's copies read down to 0.22 on single harmonics, ibid.); ``z_min``: how many standard
    deviations (Fisher transform) a harmonic's coherence must lie under a copy's (5: with up to
    five harmonics of a few hundred band pairs a copy's chance dip stays under it, ibid.).

    Two own lines (step 3): ``second_db``: how far over its floor each side's own line must
    stand for faults on both sides (15 dB: the model's healthy bearings' own lines reach 13 dB,
    benchmarks/README.md "Copy or source"); ``clearer_db``: how far one side's own line must
    stand over the other's for the clearer one to be real (3 dB: twice the scatter of a line's
    SNR read over a median floor of some 40 bins).  ``kind_db``: how far a faulty side's
    strongest line must stand over a line of another kind for its kind to be named alone (3 dB,
    the same scatter; :mod:`.kind`).

    The source of a copy (step 5): ``source``: ``"ringing"`` (the lag and the bands' votes, then
    the paper's criterion) or ``"paper"`` (the paper's criterion alone); ``source_ratio``: the
    votes a side needs over the other's (2); ``ringing_bands``: the fewest bands a side's votes
    must reach (3: a path resonance can lift a copy over its source in a band or two; a
    judgement, not a measurement); ``lag``: how the lag between the sides enters (one of
    ``LAG_POLICIES``); ``lag_min_peak``: envelope correlation needed to use a lag read by
    correlation (one read on the impulses carries its own test).

    Read in the analysis (:func:`.pair.analyse_pair`), not again by
    :meth:`.pair.PairResult.redecide`: ``gate_ratio``: the turn-folded envelope's peak over its
    median from which a wheel's strikes once a turn are blanked (5: the car's records without a
    flat and the twelve CWRU records fold to 1.1-1.9, the car's flats to 35-75, :mod:`.gate`);
    ``shaft_p_fa``: the false-alarm probability, over a record's whole orders, of naming a line
    at a whole multiple of the shaft's rate (the wheel's or the rotor's; 1e-3: noise alone names
    one in a record of a thousand, :mod:`.wheel`), which makes a record without a bearing line
    ``wheel lines only`` rather than ``no fault line``."""

    mode: str = "absolute"
    vf_range: tuple[float, float] = VF_RANGE_PAPER
    rel_range: tuple[float, float] = REL_RANGE_DEFAULT
    compare: tuple[str, ...] = ("rms", "spm_db")
    lines: tuple[str, ...] = ("BPFO", "BPFI", "2BSF")
    lag: str = "decide"
    lag_min_peak: float = 0.3
    source: str = "ringing"
    source_ratio: float = 2.0
    second_db: float = 15.0
    vf_band: tuple[float, float] | None = None
    clearer_db: float = 3.0
    kind_db: float = 3.0
    c_independent: float = 0.2
    rho_min_db: float = 15.0
    z_min: float = 5.0
    ringing_bands: int = 3
    gate_ratio: float = 5.0
    shaft_p_fa: float = 1e-3

    def __post_init__(self):
        if self.mode not in MODES:
            raise ParameterError(f"Criterion.mode = {self.mode!r} is not allowed: expected one of "
                                 + ", ".join(MODES))
        for name in ("vf_range", "rel_range"):
            r = getattr(self, name)
            ok = len(r) == 2 and all(np.isfinite(v) for v in r) and 0 <= r[0] < r[1]
            if not ok:
                raise ParameterError(f"Criterion.{name} = {r!r} is not allowed: expected (lo, hi) "
                                     "with 0 <= lo < hi")
        bad = [c for c in self.compare if c not in COMPARABLE]
        if bad or not self.compare:
            raise ParameterError(f"Criterion.compare = {self.compare!r} is not allowed: expected "
                                 "names among " + ", ".join(COMPARABLE))
        if not self.lines or any(n not in FAULT_LINES for n in self.lines):
            raise ParameterError(f"Criterion.lines = {self.lines!r} is not allowed: expected names "
                                 "among " + ", ".join(FAULT_LINES))
        if self.lag not in LAG_POLICIES:
            raise ParameterError(f"Criterion.lag = {self.lag!r} is not allowed: expected one of "
                                 + ", ".join(LAG_POLICIES))
        if not 0 <= self.lag_min_peak <= 1:
            raise ParameterError(f"Criterion.lag_min_peak = {self.lag_min_peak!r} is not allowed: "
                                 "expected a correlation in [0, 1]")
        _check(self, "second_db", lambda v: v >= 0, "a level >= 0 dB")
        _check(self, "clearer_db", lambda v: v >= 0, "a level >= 0 dB")
        _check(self, "kind_db", lambda v: v >= 0, "a level >= 0 dB")
        _check(self, "c_independent", lambda v: 0 <= v < 1, "a coherent fraction in [0, 1)")
        _check(self, "rho_min_db", lambda v: v >= 0, "a level >= 0 dB")
        _check(self, "z_min", lambda v: v >= 0, "a number of standard deviations >= 0")
        _check(self, "gate_ratio", lambda v: v > 1, "a ratio > 1 (inf: never blank)", finite=False)
        _check(self, "shaft_p_fa", lambda v: 0 < v < 1, "a probability in (0, 1)")
        if isinstance(self.ringing_bands, bool) or not isinstance(self.ringing_bands, (int, np.integer)) \
                or self.ringing_bands < 1:
            raise ParameterError(f"Criterion.ringing_bands = {self.ringing_bands!r} is not allowed: "
                                 "expected a whole number of bands >= 1")
        if self.vf_band is not None:
            object.__setattr__(self, "vf_band", check_band(self.vf_band, math.inf, "Criterion.vf_band"))
        if self.source not in SOURCE_RULES:
            raise ParameterError(f"Criterion.source = {self.source!r} is not allowed: expected one "
                                 "of " + ", ".join(SOURCE_RULES))
        if not (np.isfinite(self.source_ratio) and self.source_ratio > 1):
            raise ParameterError(f"Criterion.source_ratio = {self.source_ratio!r} is not allowed: "
                                 "expected a ratio > 1")

    @property
    def range(self) -> tuple[float, float]:
        return self.vf_range if self.mode == "absolute" else self.rel_range

    @property
    def band_text(self) -> str:
        """Where FC and VF are taken, in words: ``"the whole band"`` or ``"0-1000 Hz"``."""
        return "the whole band" if self.vf_band is None else f"{self.vf_band[0]:g}-{self.vf_band[1]:g} Hz"

    @property
    def unit(self) -> str:
        return "Hz^2" if self.mode == "absolute" else "(relative)"

    @property
    def coherence(self) -> dict:
        """The copy-or-source thresholds, as keywords of :meth:`.coherence.Timing.decide`."""
        return {"c_independent": self.c_independent, "rho_min_db": self.rho_min_db,
                "z_min": self.z_min}

    def to_dict(self) -> dict:
        d = asdict(self)
        d["range"] = list(self.range)
        return d


# the command-line option of each threshold `axlebox diagnose` sets (pipelines/cli.py)
OPTIONS = {"second_db": "--second-db", "clearer_db": "--clearer-db",
           "c_independent": "--c-independent", "gate_ratio": "--gate-ratio",
           "shaft_p_fa": "--shaft-p-fa"}
ANALYSIS = ("gate_ratio", "shaft_p_fa")     # read by the analysis, not by decide()


def _check(c: Criterion, name: str, ok, expected: str, finite: bool = True) -> None:
    """A ParameterError naming the field (and its option), the value and what is allowed,
    unless ``ok(value)`` holds for a real number (finite unless ``finite`` is False)."""
    v = getattr(c, name)
    real = isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool) \
        and not math.isnan(v) and (math.isfinite(v) or not finite)
    if not (real and ok(v)):
        opt = f" ({OPTIONS[name]})" if name in OPTIONS else ""
        raise ParameterError(f"Criterion.{name}{opt} = {v!r} is not allowed: expected {expected}")


PAPER = Criterion()                     # the paper's absolute range; the source by lag and ringing
PAPER_ALONE = Criterion(source="paper")  # the paper's criterion alone names the source


def check_band(band, fs: float, name: str = "vf_band (--vf-band)") -> tuple[float, float] | None:
    """``band`` as ``(lo, hi)`` Hz with ``0 <= lo < hi <= fs / 2``, or None (the full band)."""
    if band is None:
        return None
    ok = isinstance(band, (tuple, list)) and len(band) == 2 and all(
        isinstance(v, (int, float, np.floating, np.integer)) and not isinstance(v, bool)
        and math.isfinite(v) for v in band) and 0 <= band[0] < band[1]
    if not ok:
        raise ParameterError(f"{name} = {band!r} is not allowed: expected (lo, hi) in Hz with "
                             "0 <= lo < hi")
    if band[1] > 0.5 * fs * (1 + 1e-12):
        raise ParameterError(f"{name} = {tuple(band)!r} is not allowed: its upper edge is above the "
                             f"record's Nyquist frequency, {0.5 * fs:g} Hz")
    return float(band[0]), float(band[1])
