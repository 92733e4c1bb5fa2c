"""Random track irregularities from the American (FRA) spectra, plus optional rail roughness.

**Spectra.**  One-sided PSDs, ``Omega`` the spatial angular frequency in rad/m, S in
cm^2/(rad/m) as published, with k = 0.25 and Omega_c = 0.8245 rad/m:

    vertical profile   S_v = k A_v Omega_c^2 / (Omega^2 (Omega^2 + Omega_c^2))
    alignment          S_a = k A_a Omega_c^2 / (Omega^2 (Omega^2 + Omega_c^2))
    cross-level, gauge S   = 4 k A_v Omega_c^2 / ((Omega^2 + Omega_c^2)(Omega^2 + Omega_s^2))

with A_v, A_a (cm^2 rad/m) and Omega_s (rad/m) per FRA track class 1 (worst) to 6 (best),
:data:`FRA_CLASSES`.  The spectra go back to the FRA's fits per track class: Hamid, Rasmussen,
Baluja and Yang, *Analytical Descriptions of Track Geometry Variations*, FRA report
DOT/FRA/ORD-83/03.1 (1983); see also Garg and Dukkipati, *Dynamics of Railway Vehicle Systems*,
Academic Press 1984.  This k = 0.25 form with its six-class table is the one quoted in the
vehicle-track dynamics literature (Lei, *High Speed Railway Track Dynamics*, Springer 2017,
ch. 5, doi:10.1007/978-981-10-2039-1_5; Zhai, *Vehicle-Track Coupled Dynamics*, Springer 2020).
The numbers are a transcription of that six-class table as the literature quotes it; they were
not checked here against the printed tables.  Another "American" formula circulates in public code,
S = 2 pi A_v Omega_c^2 / (Omega^2 (Omega^2 + Omega_c^2)) with Omega_c = 0.8242 and amplitudes
sqrt(4 S dOmega): it is not this one and must not be mixed with it.

**Units and signs.**  SI inside: :func:`psd` converts cm^2 to m^2 once (:data:`CM2`).  Axes as in
:mod:`axlebox.geometry.wheelset`: y along the axle, positive to the left, z up.  Cross-level ``c`` is
the height of the left rail above the right one (m), not an angle (some sources divide by the
rail distance), and ``g`` is the gauge widening (m): positive g moves the left rail left and
the right rail right.  So z_L = z_v + c/2, z_R = z_v - c/2, y_L = y_a + g/2, y_R = y_a - g/2.

**Sampling** (:mod:`.sampling`).  z(s) = sum_k sqrt(2 S_k dOmega) cos(Omega_k s + phi_k) with
uniform random phases from a seeded numpy Generator, one independent stream per component.  The
Omega_k are the bins of the FFT of the record, k dOmega with dOmega = 2 pi / P and P >=
``length`` the record's period, so the record does not repeat within its length and is
synthesised exactly on its grid by one inverse FFT; S_k is the mean of S over bin k cut to the
band.  Between grid points :meth:`TrackIrregularity.at`
interpolates with cubic Hermite polynomials on the exact slopes (also from the FFT), so the
lookup is C1 and its error is ~4e-4 of the shortest wave's amplitude at 10 points per
wavelength.

**Rail roughness** (off by default) is the ISO 3095:2013 Figure 2 limit (the same curve as
EN 15610:2009 Annex B.9.2 and the 2007 noise TSI): one-third-octave roughness levels, dB re
1 um, from 40 cm to 0.315 cm wavelength, :data:`ISO3095_LIMIT_DB` (extended to 100-0.08 cm as
the CNOSSOS-EU tables extend it, :mod:`axlebox.mbs.track.roughness`), or CNOSSOS-EU's average
network rail (``roughness_spectrum``); either through the contact filter at the static wheel
load ``contact_load``.  The ISO limit is the upper limit for a smooth reference test track, not
a typical rail: ``roughness_offset_db`` raises it.  It is sampled like the geometry and added
to the vertical irregularity of each rail, independently on the two rails (separate rail
heads; across 1.5 m their sub-0.4 m roughness is taken as uncorrelated).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import partial

import numpy as np
from scipy.fft import next_fast_len

from axlebox._params import ParameterError, check_ranges, param, require

from . import roughness
from . import sampling

KINDS = ("vertical", "alignment", "crosslevel", "gauge")
COMPONENTS = KINDS + ("roughness_L", "roughness_R")
RAILS = ("zL", "zR", "yL", "yR")
K_FRA = 0.25
OMEGA_C = 0.8245          # rad/m
CM2 = 1e-4                # cm^2 -> m^2
#: FRA class: (A_v, A_a in cm^2 rad/m, Omega_s in rad/m)
FRA_CLASSES = {1: (1.2107, 3.3634, 0.6046), 2: (1.0181, 1.2107, 0.9308),
               3: (0.6816, 0.4128, 0.8520), 4: (0.5376, 0.3027, 1.1312),
               5: (0.2095, 0.0762, 0.8209), 6: (0.0339, 0.0339, 0.4380)}
#: ISO 3095:2013 Fig. 2 roughness limit, dB re 1 um, one-third-octave bands n = 4..25 whose
#: exact centre wavelength is 10**(-n/10) m (nominal 40 cm, 31.5 cm, ..., 0.4 cm, 0.315 cm)
ISO3095_BANDS = np.arange(4, 26)
ISO3095_LIMIT_DB = np.array([17.1, 15.0, 13.0, 11.0, 9.0, 7.0, 4.9, 2.9, 0.9, -1.1, -3.2,
                             -5.0, -5.6, -6.2, -6.8, -7.4, -8.0, -8.6, -9.2, -9.8, -10.4, -11.0])
MAX_POINTS = 2 ** 24                                       # ~130 MB per array


def _is_int(x) -> bool:
    return isinstance(x, (int, np.integer)) and not isinstance(x, bool)


def _check_grade(grade, owner: str) -> None:
    if not _is_int(grade) or int(grade) not in FRA_CLASSES:
        raise ParameterError(f"{owner}.grade = {grade!r} is not allowed: expected an FRA track "
                             "class, an integer from 1 (worst) to 6 (best)")


def _positive(Omega, name: str) -> np.ndarray:
    W = np.asarray(Omega, dtype=float)
    bad = ~(np.isfinite(W) & (W > 0))
    if bad.any():
        raise ParameterError(f"{name} = {float(W[bad].flat[0])!r} is not allowed: expected finite "
                             "spatial angular frequencies > 0 rad/m")
    return W


def psd(kind: str, Omega, grade: int = 5) -> np.ndarray:
    """One-sided FRA PSD of ``kind`` (m^2/(rad/m)) at ``Omega`` (rad/m > 0) for class ``grade``."""
    if kind not in KINDS:
        raise ParameterError(f"psd.kind = {kind!r} is not allowed: expected one of {', '.join(KINDS)}")
    _check_grade(grade, "psd")
    W2 = _positive(Omega, "psd.Omega") ** 2
    A_v, A_a, Omega_s = FRA_CLASSES[int(grade)]
    c2 = OMEGA_C ** 2
    if kind in ("vertical", "alignment"):
        S = K_FRA * (A_v if kind == "vertical" else A_a) * c2 / (W2 * (W2 + c2))
    else:
        S = 4 * K_FRA * A_v * c2 / ((W2 + c2) * (W2 + Omega_s ** 2))
    return S * CM2


def roughness_psd(Omega, offset_db: float = 0.0) -> np.ndarray:
    """One-sided PSD (m^2/(rad/m)) of the ISO 3095 limit roughness raised by ``offset_db``,
    over the limit's own bands (:func:`axlebox.mbs.track.roughness.band_psd`)."""
    W = _positive(Omega, "roughness_psd.Omega")
    return roughness.band_psd(W, ISO3095_LIMIT_DB + offset_db, ISO3095_BANDS, owner="roughness_psd")


@dataclass(frozen=True)
class IrregularityParams:
    """What to sample (SI units); the record covers [0, period) with period >= ``length``."""

    grade: int = param(5, 1, 6, unit="", doc="FRA track class, 1 (worst) to 6 (best)")
    lambda_min: float = param(1.0, 0.5, 1000.0, doc="shortest FRA wavelength")
    lambda_max: float = param(80.0, 0.5, 1000.0, doc="longest FRA wavelength")
    length: float = param(400.0, 1.0, 1e6, doc="record length")
    seed: int = param(0, 0, 2 ** 63 - 1, unit="", doc="seed of the random phases")
    ds: float | None = field(default=None, metadata={"doc": "grid step; None: shortest wavelength / 10"})
    roughness: bool = field(default=False, metadata={"doc": "add roughness to both rails"})
    roughness_lambda_min: float = param(0.003, 0.001, 0.4, doc="shortest roughness wavelength")
    roughness_lambda_max: float = param(0.4, 0.001, 0.4, doc="longest roughness wavelength")
    roughness_offset_db: float = param(0.0, -40.0, 40.0, unit="dB", doc="level above the spectrum's")
    roughness_spectrum: str = field(default="iso3095", metadata={
        "doc": "rail roughness: 'iso3095' (the ISO 3095:2013 limit) or 'network' (CNOSSOS-EU's "
               "average network), mbs/track/roughness.py"})
    contact_load: float = param(0.0, 0.0, 1e5, unit="N", doc="static wheel load of the contact "
                                "filter (mbs/track/roughness.py); 0: no filter")

    def __post_init__(self):
        _check_grade(self.grade, "IrregularityParams")
        if not _is_int(self.seed):
            raise ParameterError(f"IrregularityParams.seed = {self.seed!r} is not allowed: expected "
                                 "an integer >= 0")
        if not isinstance(self.roughness, bool):
            raise ParameterError(f"IrregularityParams.roughness = {self.roughness!r} is not allowed: "
                                 "expected True or False")
        check_ranges(self)
        require(self.roughness_spectrum in roughness.RAIL_DB, self, "roughness_spectrum",
                f"expected one of {', '.join(roughness.RAIL_DB)}")
        require(self.contact_load == 0.0 or roughness.CONTACT_LOADS[0] <= self.contact_load
                <= roughness.CONTACT_LOADS[-1], self, "contact_load", "expected 0 (no contact "
                f"filter) or a wheel load the tables cover, {roughness.CONTACT_LOADS[0]:g} to "
                f"{roughness.CONTACT_LOADS[-1]:g} N")
        require(self.lambda_min < self.lambda_max, self, "lambda_min",
                f"must be shorter than lambda_max = {self.lambda_max:g} m")
        require(self.length >= self.lambda_max, self, "length",
                f"must be at least lambda_max = {self.lambda_max:g} m (the longest wave must fit)")
        if self.roughness:
            require(self.roughness_lambda_min < self.roughness_lambda_max, self, "roughness_lambda_min",
                    f"must be shorter than roughness_lambda_max = {self.roughness_lambda_max:g} m")
        if self.ds is not None:
            ok = isinstance(self.ds, (int, float)) and not isinstance(self.ds, bool) \
                and math.isfinite(self.ds) and 0 < self.ds <= self.shortest / 4
            require(ok, self, "ds", f"expected a grid step in (0, {self.shortest / 4:g}] m, "
                    "at least 4 points per shortest wavelength")
        require(self.length / self.step <= MAX_POINTS, self, "length",
                f"needs {self.length / self.step:.3g} grid points at ds = {self.step:g} m, "
                f"more than {MAX_POINTS}: shorten the record or coarsen ds")

    @property
    def shortest(self) -> float:
        """Shortest wavelength sampled (m)."""
        return min(self.lambda_min, self.roughness_lambda_min) if self.roughness else self.lambda_min

    @property
    def step(self) -> float:
        """Grid step (m)."""
        return self.ds if self.ds is not None else self.shortest / 10


def generate(p: IrregularityParams = IrregularityParams()) -> TrackIrregularity:
    """Sample the irregularities of ``p`` on the grid s_j = j ds (see the module docstring)."""
    ds = p.step
    n = next_fast_len(math.ceil(p.length / ds) + 1, real=True)
    dW = 2 * np.pi / (n * ds)
    bands = {kind: (partial(psd, kind, grade=p.grade), p.lambda_max, p.lambda_min) for kind in KINDS}
    if p.roughness:
        levels = roughness.levels_db("rail", p.roughness_spectrum, p.contact_load or None)
        rough = partial(roughness.band_psd, levels=levels + p.roughness_offset_db,
                        owner="rail roughness")
        for name in COMPONENTS[4:]:
            bands[name] = (rough, p.roughness_lambda_max, p.roughness_lambda_min)
    # one stream per component, spawned in a fixed order: on the same grid, switching roughness
    # on leaves the geometry unchanged
    seeds = dict(zip(COMPONENTS, np.random.SeedSequence(int(p.seed)).spawn(len(COMPONENTS))))
    values, slopes, harmonics = {}, {}, {}
    for name, (spectrum, lam_long, lam_short) in bands.items():
        k, amp, phase = sampling.harmonics(spectrum, 2 * np.pi / lam_long, 2 * np.pi / lam_short,
                                           dW, np.random.default_rng(seeds[name]))
        values[name], slopes[name] = sampling.record(k, amp, phase, n, dW)
        harmonics[name] = (k * dW, amp, phase)
    return TrackIrregularity(p, ds, values, slopes, harmonics)


@dataclass(frozen=True, eq=False)
class TrackIrregularity:
    """A sampled record: components on the grid, their slopes d/ds and their harmonics.

    ``values[name]`` for ``name`` in :data:`COMPONENTS` (the roughness ones only when switched
    on) on the grid ``s``; ``zL, zR, yL, yR`` are the rails (m).  The harmonics are exactly
    periodic in ``period``, so positions outside [0, period) wrap around seamlessly."""

    params: IrregularityParams
    ds: float
    values: dict
    slopes: dict
    harmonics: dict

    @property
    def n(self) -> int:
        return self.values["vertical"].size

    @property
    def period(self) -> float:
        return self.n * self.ds

    @property
    def s(self) -> np.ndarray:
        return np.arange(self.n) * self.ds

    def _name(self, name: str) -> str:
        if name not in self.values:
            raise ParameterError(f"TrackIrregularity component = {name!r} is not allowed: expected "
                                 f"one of {', '.join(self.values)}")
        return name

    @staticmethod
    def _rails(get) -> tuple:
        v, a, c, g, rL, rR = (get(k) for k in COMPONENTS)
        rL, rR = (0.0 if r is None else r for r in (rL, rR))
        return v + 0.5 * c + rL, v - 0.5 * c + rR, a + 0.5 * g, a - 0.5 * g

    def grid(self) -> tuple:
        """(zL, zR, yL, yR) on the grid ``s`` (m)."""
        return self._rails(self.values.get)

    zL = property(lambda self: self.grid()[0])
    zR = property(lambda self: self.grid()[1])
    yL = property(lambda self: self.grid()[2])
    yR = property(lambda self: self.grid()[3])

    def at(self, s, derivative: bool = False) -> tuple:
        """(zL, zR, yL, yR) at positions ``s`` (any shape, m), or their slopes d/ds."""
        u = np.mod(np.asarray(s, dtype=float), self.period) / self.ds
        i = np.minimum(u.astype(np.intp), self.n - 1)
        t = u - i
        j = (i + 1) % self.n
        h = self.ds
        if derivative:          # d/ds of the cubic Hermite basis
            w = ((6 * t * t - 6 * t) / h, 3 * t * t - 4 * t + 1, (6 * t - 6 * t * t) / h, 3 * t * t - 2 * t)
        else:
            w = ((1 + 2 * t) * (1 - t) ** 2, h * t * (1 - t) ** 2, t * t * (3 - 2 * t), h * t * t * (t - 1))

        def get(name):
            if name not in self.values:
                return None
            y, m = self.values[name], self.slopes[name]
            return w[0] * y[i] + w[1] * m[i] + w[2] * y[j] + w[3] * m[j]
        return self._rails(get)

    def for_wheelsets(self, s, offsets) -> np.ndarray:
        """Rails under wheelsets ``offsets`` (m, >= 0) behind the one at ``s``: each sees the
        same track, delayed by its distance.  Shape ``np.shape(s) + (len(offsets), 4)``."""
        offsets = np.asarray(offsets, dtype=float)
        if offsets.ndim != 1 or not np.all(np.isfinite(offsets) & (offsets >= 0)):
            raise ParameterError(f"for_wheelsets.offsets = {offsets!r} is not allowed: expected a "
                                 "1-D list of distances >= 0 m behind the leading wheelset")
        return np.stack(self.at(np.asarray(s, dtype=float)[..., None] - offsets), axis=-1)

    def harmonic_sum(self, name: str, s, chunk: int = 2 ** 22) -> np.ndarray:
        """Component ``name`` at ``s`` by the explicit sum of its harmonics (exact, slow:
        vectorised in chunks of ~``chunk`` terms); a check on the FFT and the lookup."""
        W, amp, phase = self.harmonics[self._name(name)]
        s = np.asarray(s, dtype=float)
        flat = s.ravel()
        out = np.empty(flat.size)
        step = max(1, chunk // max(W.size, 1))
        for a in range(0, flat.size, step):
            out[a:a + step] = np.cos(np.outer(flat[a:a + step], W) + phase) @ amp
        return out.reshape(s.shape)

    def plot(self, start: float = 0.0, stop: float | None = None):
        """Vertical and lateral rail irregularities (mm) over [start, stop]; a matplotlib Figure
        drawn on the Agg canvas (no display needed)."""
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
        stop = self.params.length if stop is None else stop
        s = np.arange(start, stop, self.ds)
        zL, zR, yL, yR = (1e3 * r for r in self.at(s))
        fig = Figure(figsize=(9, 5), constrained_layout=True)
        FigureCanvasAgg(fig)
        ax = fig.subplots(2, 1, sharex=True)
        ax[0].plot(s, zL, lw=0.6, label="left")
        ax[0].plot(s, zR, lw=0.6, label="right")
        ax[0].set(ylabel="vertical z (mm)", title=f"FRA class {self.params.grade}, "
                  f"{self.params.lambda_min:g}-{self.params.lambda_max:g} m, seed {self.params.seed}")
        ax[1].plot(s, yL, lw=0.6, label="left")
        ax[1].plot(s, yR, lw=0.6, label="right")
        ax[1].set(xlabel="s (m)", ylabel="lateral y (mm)")
        ax[0].legend()
        return fig
