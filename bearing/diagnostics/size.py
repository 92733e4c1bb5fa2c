"""How large: a local defect's width along the raceway from the rollers' entry and exit events.

**The events.**  A roller that meets a local defect it cannot bridge loses its load as it enters
(the de-stressing: the ring's force steps down, a low-frequency event) and takes it up again as
it leaves (the re-stressing: the force steps back, an impulse where the roller strikes the far
edge); the time between the two is the time the roller takes across the defect (Sawalhi and
Randall, Mech. Syst. Signal Process. 25 (2011) 846-870: the two events' separation read on the
prewhitened signal).  Where along the defect the roller leaves and meets the raceway depends on
its load and speed (Kogan, Bortman and Klein, Nonlinear Dyn. 87 (2017) 219-236), so the
conversion to a width below bounds it between the defect's edges and the quasi-static points.
A defect narrower than a loaded roller unloads in is ridden over: the load only dips, and the
dip's edges (the slope breaks of the clearance, Eq. 14) are then its only events.

**Reading the separation Δt** (:func:`event_lag`).

1. Prewhitening (Sawalhi and Randall, sec. 4): the record's linear prediction error under an AR
   model of order ``AR_ORDER_S x fs`` (Yule-Walker), fitted on the quieter half of the record
   only (windows of a quarter fault period, those of energy at most the median, :func:`whiten`):
   there the structure rings to the background (the track, the rolling contacts), so the model
   learns the path and not the events, whose echo an AR model longer than it would learn and
   take out where the events dominate the record (measured on spall_record: fitted on the whole
   record, entry and exit 7-10 samples apart read at twice that).  Band-limited to ``0.45 fs``
   (a converter's pass band; whitening lifts the empty transition band above it) and upsampled
   ``upsample`` times (band-limited, so the lag is read to a fraction of a sample).
2. The entry and the exit of each pass are two pulses Δt apart, so the product ``e(t) e(t + l)``
   recurs at the fault's rate ``alpha`` at ``l = Δt``.  The cyclic autocorrelation at the first
   :data:`N_HARMONICS` harmonics of ``alpha`` (Antoni, Bonnardot, Raad and El Badaoui, Mech.
   Syst. Signal Process. 18 (2004) 1285-1314),

   ``R_k(l) = (1/N) sum_t e(t) e(t + l) exp(-2 pi i k alpha t)``,   ``|R|(l) = sum_k |R_k(l)|``,

   keeps what recurs with the fault whatever the events' signs, and drops the stationary part
   (four harmonics: rollers slipping 2 % from period to period decohere the higher ones,
   tests/test_size.py).  ``alpha`` is the line's frequency refined on the record (the
   whitened signal's squared spectrum, within ``slip`` of the line as found).
3. Δt is the lag of the highest local maximum of ``|R|`` between :data:`RESOLUTION_SAMPLES` and
   0.45 of the fault period (a pair's separation is read modulo the period; a defect is
   narrower than the roller pitch, bearing/defects.py), refined by a parabola.  It must stand
   :data:`MIN_SNR` times over the median of ``|R|`` over those lags, and no recurrence under
   the resolution (past the pulse's own main lobe and first sidelobe,
   :data:`PEAK_FROM_SAMPLES`) may stand :data:`UNRESOLVED` times higher: a pair comes with the
   pulses' own lobes either side of its lag, so an unresolved pair shows past the resolution as
   its lag plus a lobe (spall_record's pairs 5 samples apart read at 10 without that test).
   Else no pair is read.

**The interval** comes from the spread over the impulses: the record is cut into blocks of one
fault period, each block's ``R_k(l)`` summed alone; :data:`N_BOOT` bootstrap resamples of the
blocks give Δt again, their :data:`PERCENTILES` widened by :data:`TIMING_SAMPLES` each way (the
events' shapes differ, entry a step and exit an impact, which moves the peak by up to about half
a sample on spall_record's pairs), then carried through the conversion and its bounds.

**Resolution** (:data:`RESOLUTION_SAMPLES`).  A single event leaves lobes of its own in ``|R|``
near zero lag, from the colour whitening leaves (the path's anti-resonances, which an AR model
cannot take out): on the model's axle box out to 6.5 samples (the quasi-dynamic car at 10 kHz),
on spall_record's one-mode path to 5; a lag inside them is not an echo.  So lags under 7 samples
are not read: where no pair is found past them, the side is "below resolution", the width a
roller crosses in 7 samples its upper bound, or "bridged" where the load is known and a loaded
roller would ride over a wider defect than that.  Through a path of several close modes
(spall_record's three, 700, 2300 and 3700 Hz) a pair's recurrence stands only 8-17 times its
floor and most pairs are not read (none is read wrong): benchmarks/README.md "How large".

**Conversion** (:func:`width_from_lag`, :func:`estimate`).  A roller rolls over a ring at the
rolling speed ``v = pi f_s D_m (1 - g^2) / 2`` (``g = (D_b/D_m) cos(alpha) = 1 - 2 FTF``: the
contact point's speed over either raceway and over the roller, ``omega_c D_o / 2``, ``(omega_s -
omega_c) D_i / 2``, ``omega_b D_b / 2`` with ``D_o = D_m (1 + g)``, ``D_i = D_m (1 - g)``; Harris
and Kotzalas, Rolling Bearing Analysis, 5th ed., vol. 1, sec. 8.2).  A defect of width W on a
surface of diameter D spans ``tau = 2 arcsin(W / D)`` (Eq. 14; bearing/defects.py), crossed in
``tau D / (2 v)``: the whole width ``W_0 = D sin(v Δt / D)``.  Over it the clearance is ``h = A
sin(pi x / tau)``, ``A = r - sqrt(r^2 - (W/2)^2)`` (a roller of radius r dropping into the gap;
the depth H, which caps it, taken as deeper), and a roller whose contact approach under its load
is ``delta`` unloads only where ``h > delta`` (quasi-static), from ``x_1 = (tau / pi)
arcsin(delta / A)`` to ``tau - x_1``: the events ``(tau - 2 x_1) D / (2 v)`` apart, solved for
``W_1`` (monotonic; :func:`event_angle`).  Where ``W_0`` is at most the bridged width
``W_delta = 2 sqrt(2 r delta - delta^2)`` (``A = delta``) the roller rides over the defect and
the events are its edges: ``W = W_0``.  Else the roller leaves the raceway between the edge and
the quasi-static point: ``W = (W_0 + W_1) / 2``, the interval from ``W_0`` at the spread's low
end to ``W_1`` at its high end.  ``delta = (Q / K)^(9/10)``, Q the most loaded roller's load and
K its two raceway contacts in series (Eq. 10; :func:`geometry_of`); where the load is unknown,
the whole width ``W_0`` and its spread alone, which a loaded roller's later unloading would make
too narrow by ``2 x_1``.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np
from scipy.linalg import solve_toeplitz
from scipy.optimize import brentq
from scipy.signal import butter, find_peaks, lfilter, resample_poly, sosfiltfilt

from axlebox._params import ParameterError

from ..frequencies import FaultOrders
from .envelope import _signal, check_fs

#: the shortest lag read as a pair of events, in samples of the record (module docstring)
RESOLUTION_SAMPLES = 7.0
#: the highest recurrence is looked for from this lag on (samples): past a band-limited pulse's
#: own main lobe and first sidelobe (to 0.45 fs: its first zero at 1.1 samples, the sidelobe at
#: 1.6)
PEAK_FROM_SAMPLES = 2.0
#: a pair past the resolution is read only where no recurrence under it stands this many times
#: higher: else the strongest is unresolved, and what stands past the resolution is its
#: companion (its lag plus one of the pulses' own lobes)
UNRESOLVED = 1.25
#: the echo's peak over the median of ``|R|`` over the lags searched (module docstring).  Set
#: from where no pair is, or none at the lag read: the highest recurrence past the resolution
#: stands at most 3.5 times that median on the model's healthy runs (study, 20-80 km/h, both
#: sides, at BPFO, BPFI and 2BSF: 30 readings); on spall_record (benchmarks/size.py
#: --synthetic) a single impact a pass's highest stands at most 9 times and a wrong lag (half
#: the true one, a three-mode path's ridden-over dip) at most 9; 10 is over both.  The model's
#: pairs stand 11-68 times (the median rises with the speed: at 80 km/h the pulses' own lobes
#: fill more of the 55 lags a period leaves), spall_record's 8-36 (benchmarks/README.md "How
#: large"; 15 before, which left the study's 3 and 5 mm at 80 km/h, 11 and 14, unread)
MIN_SNR = 10.0
#: the prediction filter's length (s): AR order ar_order_s x fs (16 at 10 kHz)
AR_ORDER_S = 1.6e-3
#: the converter's pass band over fs: the whitened signal is band-limited to it
PASSBAND = 0.45
#: the fault's harmonics summed in ``|R|``
N_HARMONICS = 4
#: the bootstrap's resamples and the interval's percentiles
N_BOOT = 200
PERCENTILES = (5.0, 95.0)
#: the events' timing on the sample grid: the interval is widened by this many samples each way
TIMING_SAMPLES = 0.5
#: the record read at most (samples), and the bootstrap's units at most: memory and time flat
#: in the record's length
MAX_SAMPLES = 1 << 20
MAX_BLOCKS = 400
#: kind of defect -> the line its impulses recur at
LINE_OF = {"outer": "BPFO", "inner": "BPFI", "roller": "2BSF"}
KIND_OF = {v: k for k, v in LINE_OF.items()}
STATUSES = ("sized", "bridged", "below resolution", "not read")


def whiten(x: np.ndarray, order: int, quiet: int | None = None) -> np.ndarray:
    """The prediction error of ``x`` (mean removed) under an AR model of ``order`` (Yule-Walker,
    Levinson through ``scipy.linalg.solve_toeplitz``); the first ``order`` samples, where the
    filter has no past, are dropped.  ``quiet``: the model is fitted on the quieter half of the
    record only, cut into windows of that many samples (those of energy at most the median):
    the structure's response to the background, without the events, whose echo an AR model
    longer than it would learn and take out."""
    x = np.asarray(x, float) - np.mean(x)
    if quiet is None or x.size < 4 * quiet:
        seg = x[None, :]
    else:
        seg = x[:x.size // quiet * quiet].reshape(-1, quiet)
        energy = np.einsum("ij,ij->i", seg, seg)
        seg = seg[energy <= np.median(energy)]
    m = seg.shape[1]
    nfft = 1 << int(np.ceil(np.log2(2 * m)))
    X = np.fft.rfft(seg, nfft, axis=1)
    r = np.fft.irfft(np.sum(X * np.conj(X), axis=0), nfft)[:order + 1] / seg.size
    if not r[0] > 0:
        raise ParameterError("the record is constant: expected a signal to read the events on")
    a = solve_toeplitz(r[:order], r[1:order + 1])
    return lfilter(np.r_[1.0, -a], [1.0], x)[order:]


def _band_limited(e: np.ndarray, fs: float) -> np.ndarray:
    """``e`` low-passed (zero phase) at the converter's pass band :data:`PASSBAND` ``x fs``."""
    return sosfiltfilt(butter(8, PASSBAND * fs, fs=fs, output="sos"), e)


def refine_rate(e: np.ndarray, fs: float, f0: float, slip: float = 0.03,
                n_harmonics: int = N_HARMONICS) -> float:
    """The fault rate (Hz) within ``f0 (1 +- slip)`` at which the squared signal ``e^2`` recurs
    most: the highest sum of its spectrum's magnitude at the first ``n_harmonics`` multiples
    (zero-padded four times; a grid step of a quarter bin at the highest harmonic)."""
    s = e * e - np.mean(e * e)
    n = s.size
    nfft = 4 * n
    S = np.abs(np.fft.rfft(s, nfft))
    df = fs / nfft
    k = np.arange(1, n_harmonics + 1)
    grid = np.arange(f0 * (1 - slip), f0 * (1 + slip), df / n_harmonics)
    idx = np.rint(np.outer(grid, k) / df).astype(int)
    ok = idx < S.size
    score = np.where(ok, S[np.minimum(idx, S.size - 1)], 0.0).sum(axis=1)
    return float(grid[int(np.argmax(score))])


@dataclass(frozen=True)
class EventLag:
    """What :func:`event_lag` read: ``dt_s`` the events' separation (None: no pair found);
    ``boot_s`` the bootstrap's separations (NaN where a resample found none); ``snr`` the echo's
    peak over the floor of ``|R|``; ``alpha_hz`` the fault rate the correlation was taken at;
    ``n_blocks`` the fault periods summed; ``lags_s``/``R`` the normalised ``|R|`` over the lags
    searched (for figures)."""

    dt_s: float | None
    boot_s: np.ndarray
    snr: float
    alpha_hz: float
    n_blocks: int
    min_lag_s: float
    max_lag_s: float
    lags_s: np.ndarray
    R: np.ndarray

    def interval_s(self, q=PERCENTILES) -> tuple[float, float] | None:
        """The bootstrap's percentiles ``q`` of the separation (s), None where most resamples
        found no pair."""
        b = self.boot_s[np.isfinite(self.boot_s)]
        if self.dt_s is None or b.size < 0.5 * self.boot_s.size:
            return None
        lo, hi = np.percentile(b, q)
        return float(min(lo, self.dt_s)), float(max(hi, self.dt_s))


def _peak(R: np.ndarray, i0: int, i1: int) -> float | None:
    """The sub-sample index of the highest local maximum of ``R`` inside ``(i0, i1)`` (a parabola
    through it and its neighbours), None where there is none (``R`` falling throughout: the
    zero-lag lobe's tail)."""
    pk, _ = find_peaks(R[i0:i1 + 1])
    if not pk.size:
        return None
    i = i0 + int(pk[np.argmax(R[i0 + pk])])
    y0, y1, y2 = R[i - 1], R[i], R[i + 1]
    den = y0 - 2 * y1 + y2
    return i + (0.5 * (y0 - y2) / den if den < 0 else 0.0)


def event_lag(x, fs: float, f_line: float, *, slip: float = 0.03, min_lag_s: float | None = None,
              max_lag_s: float | None = None, ar_order_s: float = AR_ORDER_S, upsample: int = 4,
              n_harmonics: int = N_HARMONICS, n_boot: int = N_BOOT, seed: int = 0) -> EventLag:
    """The separation of the entry and exit events of the impulses recurring near ``f_line``
    (Hz) in the record ``x`` at ``fs`` (module docstring): ``min_lag_s`` default
    :data:`RESOLUTION_SAMPLES` samples, ``max_lag_s`` default 0.45 of the fault period."""
    x = _signal(x)
    fs = check_fs(fs)
    if not (isinstance(f_line, (int, float, np.floating)) and math.isfinite(f_line) and f_line > 0):
        raise ParameterError(f"f_line = {f_line!r} is not allowed: expected a fault rate > 0 Hz")
    if isinstance(upsample, bool) or not isinstance(upsample, (int, np.integer)) or upsample < 1:
        raise ParameterError(f"upsample = {upsample!r} is not allowed: expected a whole number >= 1")
    x = x[:MAX_SAMPLES]
    order = max(2, int(round(ar_order_s * fs)))
    if x.size < 8 * order or x.size < 4 * fs / f_line:
        raise ParameterError(f"record of {x.size} samples is too short to read the events: expected "
                             f"at least four fault periods ({4 * fs / f_line:.0f} samples) and "
                             f"{8 * order} samples")
    quiet = max(4 * order, int(0.25 * fs / f_line))
    e = _band_limited(whiten(x, order, quiet), fs)
    alpha = refine_rate(e, fs, f_line, slip, n_harmonics)
    U = int(upsample)
    fu = U * fs
    eu = resample_poly(e, U, 1)
    lo = RESOLUTION_SAMPLES / fs if min_lag_s is None else float(min_lag_s)
    hi = 0.45 / alpha if max_lag_s is None else float(max_lag_s)
    if not 0 <= lo < hi:
        raise ParameterError(f"lags {lo:g}-{hi:g} s are not allowed: expected 0 <= min_lag_s < max_lag_s")
    i0, i1 = int(np.floor(lo * fu)), int(np.ceil(hi * fu))
    L = i1 + 2
    P = int(round(fu / alpha))                       # a block: one fault period
    nb = (eu.size - L) // P
    if nb < 4:
        raise ParameterError(f"record of {x.size} samples holds {max(nb, 0)} fault periods past the "
                             "longest lag: expected at least 4")
    N = 1 << int(np.ceil(np.log2(P + L)))
    k = np.arange(1, n_harmonics + 1)
    # the bootstrap's units: single periods, or runs of consecutive ones where there are more
    # than MAX_BLOCKS (memory flat in the record's length)
    G = min(nb, MAX_BLOCKS)
    group = np.arange(nb) * G // nb
    Rb = np.zeros((G, n_harmonics, L), complex)
    t = np.arange(P)
    step = max(1, (1 << 22) // (n_harmonics * N))      # blocks a pass: arrays of 4 M at most
    for c0 in range(0, nb, step):
        b = np.arange(c0, min(nb, c0 + step))
        start = b * P
        seg = eu[start[:, None] + t]                                   # (blocks, P)
        ext = np.zeros((b.size, N))
        ext[:, :P + L] = eu[start[:, None] + np.arange(P + L)]
        w = np.exp(-2j * np.pi * alpha / fu * k[None, :, None] * (start[:, None, None] + t))
        C = np.fft.fft(np.conj(seg[:, None, :] * w), N)                 # (blocks, K, N)
        R = np.fft.ifft(np.fft.fft(ext, N)[:, None, :] * np.conj(C), N)[:, :, :L]
        np.add.at(Rb, group[b], R)
    n = nb * P

    def curve(R):            # |R|(l), summed over the harmonics
        return np.abs(R).sum(axis=-2) / n

    # the highest recurrence past the pulse's own main lobe and first sidelobe; one under the
    # resolution is an unresolved pair (or the pulse's own lobe), whose companions past it
    # (the pair's lag plus a lobe) must not be read as the pair
    j0 = min(i0, int(np.floor(PEAK_FROM_SAMPLES * U)))

    def pair_lag(R):
        p = _peak(R, i0, i1)
        q = _peak(R, j0, i0) if j0 < i0 else None
        if p is None or (q is not None and R[int(round(q))] > UNRESOLVED * R[int(round(p))]):
            return None
        return p

    Rsum = curve(Rb.sum(axis=0))
    top = pair_lag(Rsum)
    floor = float(np.median(Rsum[i0:i1 + 1]))
    snr = float(Rsum[int(round(top))] / floor) if top is not None and floor > 0 else 0.0
    dt = top / fu if top is not None and snr >= MIN_SNR else None
    rng = np.random.default_rng(seed)
    counts = rng.multinomial(G, np.full(G, 1.0 / G), size=n_boot).astype(float)
    boots = curve((counts @ Rb.reshape(G, -1)).reshape(n_boot, n_harmonics, L))
    boot = np.array([np.nan if (p := pair_lag(r)) is None else p / fu for r in boots])
    lags = np.arange(i0, i1 + 1)
    return EventLag(dt_s=dt, boot_s=boot, snr=snr, alpha_hz=alpha, n_blocks=nb, min_lag_s=lo,
                    max_lag_s=hi, lags_s=lags / fu, R=Rsum[i0:i1 + 1] / max(Rsum[0], 1e-300))


# --- the kinematics and the conversion to a width ---------------------------------------------
def rolling_speed(orders: FaultOrders, shaft_hz: float, pitch: float) -> float:
    """The rollers' rolling speed over the raceways (m/s), ``pi f_s D_m (1 - g^2) / 2`` with
    ``g = 1 - 2 FTF`` (module docstring)."""
    g = 1.0 - 2.0 * orders.FTF
    return math.pi * shaft_hz * pitch * (1.0 - g * g) / 2.0


def surface_diameter(kind: str, orders: FaultOrders, pitch: float, roller: float) -> float:
    """Diameter (m) of the surface a defect of ``kind`` is on: the outer raceway ``D_m (1 + g)``,
    the inner one ``D_m (1 - g)``, or the roller ``D_b``."""
    g = 1.0 - 2.0 * orders.FTF
    return {"outer": pitch * (1 + g), "inner": pitch * (1 - g), "roller": roller}[kind]


def drop(W: float, r: float) -> float:
    """A roller of radius r over a gap W: how far its centre drops, ``r - sqrt(r^2 - (W/2)^2)``
    (Eq. 14's A; W >= 2r: r)."""
    return r - math.sqrt(max(r * r - 0.25 * W * W, 0.0))


def bridged_width(r: float, delta: float) -> float:
    """The widest defect a roller of radius r whose contact approach is ``delta`` crosses without
    unloading: ``A(W) = delta``, ``W = 2 sqrt(2 r delta - delta^2)``."""
    d = min(delta, r)
    return 2.0 * math.sqrt(2 * r * d - d * d)


def event_angle(W: float, D: float, r: float, delta: float) -> float:
    """The angle (rad of the surface of diameter D) between the events of a roller of radius r
    and approach ``delta`` over a defect of width W: ``tau (1 - (2/pi) arcsin(delta / A))``,
    ``tau = 2 arcsin(W / D)``; 0 where it bridges the defect (``A <= delta``)."""
    tau = 2.0 * math.asin(min(W / D, 1.0))
    A = drop(W, r)
    if A <= delta:
        return 0.0
    return tau * (1.0 - 2.0 / math.pi * math.asin(delta / A))


def width_from_lag(dt: float, v: float, D: float, r: float | None = None,
                   delta: float | None = None) -> float:
    """The width W (m) whose events a roller rolling at ``v`` over a surface of diameter D
    (roller radius r, contact approach ``delta``) passes ``dt`` apart (module docstring):
    ``event_angle(W) = 2 v dt / D`` solved for W; without ``delta`` (or r), the whole width,
    ``W = D sin(v dt / D)``."""
    target = 2.0 * v * dt / D
    if delta is None or r is None or delta <= 0:
        return D * math.sin(min(0.5 * target, 0.5 * math.pi))
    lo, hi = bridged_width(r, delta), 2.0 * r
    if event_angle(hi, D, r, delta) <= target:     # wider than the roller: beyond Eq. 14's defects,
        return D * math.sin(min(0.5 * target, 0.5 * math.pi))    # the whole width, a lower bound
    return brentq(lambda W: event_angle(W, D, r, delta) - target, lo * (1 + 1e-12), hi, xtol=1e-9)


# --- a side's size --------------------------------------------------------------------------
@dataclass(frozen=True)
class Geometry:
    """What the conversion needs of a bearing: its pitch diameter ``pitch`` and roller
    diameter ``roller`` (m), and the contact approach ``delta`` (m) of its most loaded roller
    (None where the load is unknown)."""

    pitch: float
    roller: float
    delta: float | None = None


@dataclass(frozen=True)
class SizeResult:
    """One side's defect size: ``status`` one of :data:`STATUSES`; ``kind`` of defect and the
    ``line`` its impulses recur at; ``width_m`` the estimate and ``interval_m`` its interval
    (``sized``), or the interval alone (``bridged``, ``below resolution``: ``(0, upper)``);
    ``dt_s``/``dt_interval_s`` the events' separation; ``speed_m_s`` the rolling speed;
    ``surface_m`` the defect's surface diameter; ``limit_s``/``limit_m`` the resolution (the
    width crossed in it); ``bridged_m`` the widest defect crossed without unloading (None: load
    unknown); ``snr`` the echo over its floor; ``n_periods`` the fault periods read; ``reason``
    in words."""

    status: str
    kind: str | None = None
    line: str | None = None
    width_m: float | None = None
    interval_m: tuple[float, float] | None = None
    dt_s: float | None = None
    dt_interval_s: tuple[float, float] | None = None
    speed_m_s: float | None = None
    surface_m: float | None = None
    limit_s: float | None = None
    limit_m: float | None = None
    bridged_m: float | None = None
    snr: float | None = None
    n_periods: int = 0
    reason: str = ""

    def to_dict(self) -> dict:
        d = asdict(self)
        for k in ("interval_m", "dt_interval_s"):
            d[k] = None if d[k] is None else list(d[k])
        return d

    def text(self) -> str:
        """A few words for a table cell."""
        if self.status == "sized":
            lo, hi = self.interval_m
            return f"{1e3 * self.width_m:.2f} mm ({1e3 * lo:.2f}-{1e3 * hi:.2f})"
        if self.interval_m is not None:
            return f"{self.status} (< {1e3 * self.interval_m[1]:.2f} mm)"
        return self.status


def estimate(x, fs: float, shaft_hz: float, orders: FaultOrders, kind: str, geometry: Geometry | None,
             *, f_line: float | None = None, angle=None, **kw) -> SizeResult:
    """The size of a ``kind`` defect (``"outer"``, ``"inner"``, ``"roller"``) whose impulses are
    in the record ``x`` at ``fs`` of a shaft turning at ``shaft_hz``, in a bearing of fault
    ``orders`` and ``geometry`` (module docstring).  ``f_line``: the line's frequency as found
    (Hz; default the kinematic one); ``angle``: the shaft's angle (turns) at each sample where
    the speed changes: the record is read at equal steps of it (:mod:`.clock`), as at its mean
    speed, which ``shaft_hz`` then is; ``kw`` to :func:`event_lag`."""
    if kind not in LINE_OF:
        raise ParameterError(f"kind = {kind!r} is not allowed: expected one of {', '.join(LINE_OF)}")
    line = LINE_OF[kind]
    if geometry is None:
        return SizeResult("not read", kind, line, reason="the bearing's pitch and roller diameters "
                          "are unknown (a bearing given by its orders alone): name it, e.g. --bearing")
    fs = check_fs(fs)
    if angle is not None:
        from scipy.interpolate import CubicSpline

        from .clock import make
        x = _signal(x)
        if np.size(angle) != x.size:
            raise ParameterError(f"angle of {np.size(angle)} samples is not allowed: the record has "
                                 f"{x.size}; expected one angle a sample")
        ck = make(angle, fs)
        x = CubicSpline(ck.t, x)(ck.t_k)
        shaft_hz = ck.f_mean
    f0 = orders.at(shaft_hz)[line] if f_line is None else float(f_line)
    v = rolling_speed(orders, shaft_hz, geometry.pitch)
    D = surface_diameter(kind, orders, geometry.pitch, geometry.roller)
    r = 0.5 * geometry.roller
    delta = geometry.delta
    limit = RESOLUTION_SAMPLES / fs
    limit_m = width_from_lag(limit, v, D)
    W_b = bridged_width(r, delta) if delta is not None else None
    common = dict(kind=kind, line=line, speed_m_s=v, surface_m=D, limit_s=limit, limit_m=limit_m,
                  bridged_m=W_b)
    try:
        ev = event_lag(x, fs, f0, **kw)
    except ParameterError as err:
        return SizeResult("not read", reason=str(err), **common)
    if ev.dt_s is None:
        if W_b is not None and W_b > limit_m:
            return SizeResult("bridged", interval_m=(0.0, W_b), snr=ev.snr, n_periods=ev.n_blocks,
                              reason=f"no pair of entry and exit events: a loaded roller crosses a "
                                     f"defect narrower than {1e3 * W_b:.2f} mm without unloading "
                                     f"(its contact approach {1e6 * delta:.1f} um)", **common)
        up = max(limit_m, W_b or 0.0)
        why = ("" if W_b is not None else "; or the roller bridges it without unloading (the load "
               "is not known)")
        return SizeResult("below resolution", interval_m=(0.0, up), snr=ev.snr, n_periods=ev.n_blocks,
                          reason=f"no pair of entry and exit events {RESOLUTION_SAMPLES:g} samples "
                                 f"({1e3 * limit:.2g} ms) or more apart: narrower than "
                                 f"{1e3 * limit_m:.2f} mm at {v:.3g} m/s{why}", **common)
    ci = ev.interval_s() or (ev.dt_s, ev.dt_s)
    ci = (max(ci[0] - TIMING_SAMPLES / fs, 0.0), ci[1] + TIMING_SAMPLES / fs)
    whole = [width_from_lag(t, v, D) for t in (ev.dt_s, *ci)]
    if delta is None:
        W, ci_m = whole[0], (whole[1], whole[2])
        how = "the load unknown: read as the whole width, a roller unloading at its edges"
    elif whole[0] <= W_b:
        # narrower than a loaded roller unloads in: the roller rides over it, and its only
        # events are the clearance's edges (Eq. 14's slope breaks), the whole width apart
        W, ci_m = whole[0], (whole[1], whole[2])
        how = (f"narrower than the {1e3 * W_b:.2f} mm a roller of approach {1e6 * delta:.1f} um "
               "unloads in: the events are its edges")
    else:
        # the roller leaves the raceway between the defect's edge (the whole width) and where
        # the clearance passes its approach under load (quasi-static): the dynamics decide where
        # (Kogan et al.); the estimate is the middle, the interval spans both and the spread
        loaded = [width_from_lag(t, v, D, r, delta) for t in (ev.dt_s, *ci)]
        W, ci_m = 0.5 * (whole[0] + loaded[0]), (whole[1], loaded[2])
        how = f"a roller unloading between the edges and its approach {1e6 * delta:.1f} um"
    return SizeResult("sized", width_m=W, interval_m=ci_m, dt_s=ev.dt_s, dt_interval_s=ci,
                      snr=ev.snr, n_periods=ev.n_blocks,
                      reason=f"entry and exit {1e3 * ev.dt_s:.3g} ms apart ({ev.dt_s * fs:.1f} "
                             f"samples, {ev.n_blocks} periods, echo {ev.snr:.3g} x its floor) at "
                             f"{v:.3g} m/s; {how}", **common)


FAULTY = ("real fault", "faults on both sides")


def size_columns(r: SizeResult | None, prefix: str = "") -> dict:
    """A side's size as table columns after ``prefix``: ``size`` (its status), ``width_mm``,
    ``width_lo_mm``, ``width_hi_mm`` (NaN where there is none) and ``events_ms``, the events'
    separation (the report's summary, the dataset's labels)."""
    nan = float("nan")
    if r is None:
        r = SizeResult("not read")
    lo, hi = r.interval_m if r.interval_m is not None else (nan, nan)
    return {f"{prefix}size": r.status,
            f"{prefix}width_mm": 1e3 * r.width_m if r.width_m is not None else nan,
            f"{prefix}width_lo_mm": 1e3 * lo, f"{prefix}width_hi_mm": 1e3 * hi,
            f"{prefix}events_ms": 1e3 * r.dt_s if r.dt_s is not None else nan}


def geometry_of(bearing, roller_load: float | None = None) -> Geometry | None:
    """The :class:`Geometry` of a catalogue bearing (:class:`axlebox.bearing.catalogue.Bearing`)
    and its most loaded roller's load (N; the approach ``(Q / K)^(9/10)`` where its contacts'
    stiffness is known), None where its diameters are not known."""
    if bearing is None or bearing.pitch is None or bearing.roller is None:
        return None
    delta = None
    if roller_load is not None and bearing.stiffness is not None and roller_load > 0:
        delta = (roller_load / bearing.stiffness) ** 0.9
    return Geometry(float(bearing.pitch), float(bearing.roller), delta)


def side_kind(channel) -> tuple[str | None, float | None]:
    """The defect kind a side's own lines name (:class:`.channel.ChannelResult`): of its detected
    BPFO, BPFI and 2BSF the one standing highest over its floor, and that line's frequency as
    found; ``(None, None)`` where none is detected (a cage line has no width)."""
    seen = [(r.snr_db, n) for n, r in channel.lines.items() if n in KIND_OF and r.detected]
    if not seen:
        return None, None
    _, name = max(seen)
    return KIND_OF[name], channel.lines[name].f_found


def side_sizes(pair, orders, geometry=(None, None), angle=None, kinds=None) -> dict[str, SizeResult]:
    """Each side's :class:`SizeResult` for a :class:`.pair.PairResult`: a side called faulty
    (:data:`FAULTY`) is sized on its own record for the kind its lines name (:func:`side_kind`;
    ``kinds``: side -> kind, where the kind was named otherwise); any other side is ``"not
    read"``.  ``orders``: the sides' :class:`FaultOrders` (one for both or a (left, right)
    pair); ``geometry``: the sides' :class:`Geometry` (None: unknown); ``angle``: the
    shaft's angle (turns) a sample where the speed changes: the record is then read at equal
    steps of it, at the mean speed (:mod:`.clock`)."""
    out = {}
    for i, side in enumerate(("left", "right")):
        c = getattr(pair, side)
        word = pair.verdict.words[side]
        if word not in FAULTY:
            out[side] = SizeResult("not read", reason=f"the side is not called faulty ({word})")
            continue
        kind, f_found = side_kind(c)
        if kinds is not None and kinds.get(side) is not None:
            kind, f_found = kinds[side], None
        if kind is None:
            out[side] = SizeResult("not read", reason="no bearing line of a width (BPFO, BPFI, 2BSF) "
                                                      "is seen on this side")
            continue
        x = pair.x_left if side == "left" else pair.x_right
        if x is None:
            out[side] = SizeResult("not read", kind, LINE_OF[kind], reason="the signal is not kept")
            continue
        o = orders[i] if isinstance(orders, (tuple, list)) else orders
        out[side] = estimate(x, c.fs, c.shaft_hz, o, kind, geometry[i], f_line=f_found, angle=angle)
    return out
