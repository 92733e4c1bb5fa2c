"""Time lag between the two sides of a shaft: which channel's fault impulses come first.

The paper (section "Difference analyses ...", Fig. 13) finds that the impulses transmitted to the
healthy side lag those of the defect side by 1.1-4.2 ms.  Two estimators, both on the Hilbert
envelopes (the envelope keeps the impulse timing and drops the carrier, whose phase the
transmission path, the wheelset's modes, changes):

* :func:`impulse_lag`, impulse by impulse: each fault impulse of the more impulsive channel is
  found, both envelopes are averaged over the impulses (synchronous averaging), and on each
  average the arrival is picked (where the envelope's level changes, by the Akaike information
  criterion); bootstrap resamples of the impulses give the spread and the share that agrees
  on the sign.  It names no leading side
  when fewer than ``min_impulses`` impulses are found or too few agree: on short records where
  both sides ring the same modes the whole-record correlation can lock onto the ringing instead
  of the arrivals and name the wrong side with a high correlation.
* :func:`time_lag`, the cross-correlation of the two envelopes over the whole record (mean
  removed), for records without separable impulses.

Sub-sample refinement: the integer peak of ``scipy.signal.correlate`` is refined by evaluating the
same cross-correlation between samples with its trigonometric (band-limited) interpolant, the
exact continuation of the zero-padded circular correlation, and maximising it within +-1 sample.
A parabola through three samples fits the peak's curvature only; on the test signals of
tests/test_diagnostics_pair.py (0.1 sample asked) the interpolant's error is at most 0.05
sample, up to 3x below the parabola's.  What remains comes from the envelope itself: ``|analytic signal|``
of a fractionally delayed record is not exactly the delayed samples of the envelope.
"""
from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
from scipy.fft import next_fast_len, rfft
from scipy.optimize import minimize_scalar
from scipy.signal import correlate, correlation_lags, find_peaks

from axlebox._params import ParameterError

from .envelope import check_fs, envelope


@dataclass(frozen=True)
class LagResult:
    """``lag_s``/``lag_samples`` >= 0: how much the trailing channel's envelope is behind;
    ``leading``: "a" or "b" (or "none" when the refined lag is below 1e-3 sample, or, by
    impulses, when the evidence is weak); ``delay_b_samples``: the signed delay of b behind a;
    ``peak``: the normalised cross-correlation (Pearson coefficient of the envelopes) at the
    lag; ``band_a``/``band_b``: the envelope bands used (None: broadband); ``method``:
    "correlation" or "impulses", with the latter's count, spread and agreement."""

    lag_s: float
    lag_samples: float
    leading: str
    delay_b_samples: float
    peak: float
    fs: float
    band_a: tuple[float, float] | None = None
    band_b: tuple[float, float] | None = None
    method: str = "correlation"
    n_impulses: int = 0             # impulse_lag: impulses averaged
    spread_s: float = 0.0           # impulse_lag: half the interquartile range of the bootstrap
    agreement: float = 1.0          # impulse_lag: share of the bootstrap with the lag's sign

    def to_dict(self) -> dict:
        return asdict(self)

    def sentence(self, names=("a", "b")) -> str:
        """Who leads, in words, ``names`` being channels a and b's: ``"ws2_L's impulses arrive
        1.4 ms after ws2_R's: ws2_R leads (45 impulses, 100 % of resamples agree)"``."""
        if self.leading not in ("a", "b"):
            return (f"lag: no side named ({self.n_impulses} impulses, {100 * self.agreement:.0f} % "
                    "agree)")
        lead, late = names if self.leading == "a" else names[::-1]
        return (f"{late}'s impulses arrive {self.lag_s * 1e3:.2g} ms after {lead}'s: {lead} leads "
                f"({self.n_impulses} impulses, {100 * self.agreement:.0f} % of resamples agree)")


def _pair(a, b, fs) -> tuple[np.ndarray, np.ndarray, float]:
    """Two 1-D channels of one length (>= 3) and their sampling rate, or a ParameterError."""
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    fs = check_fs(fs)
    if a.ndim != 1 or a.shape != b.shape or a.size < 3:
        raise ParameterError(f"channels of shapes {a.shape} and {b.shape} are not allowed: expected "
                             "two 1-D channels of the same length >= 3")
    return a, b, fs


def _refine(X: np.ndarray, nfft: int, k0: int) -> tuple[float, float]:
    """``(tau, r)``: the lag (samples) maximising the band-limited interpolant ``r`` of
    ``irfft(X, nfft)`` within one sample of ``k0``, and ``r`` there."""
    k = np.arange(X.size)
    w = np.full(X.size, 2.0)             # one-sided spectrum: interior bins count twice
    w[0] = 1.0
    if nfft % 2 == 0:
        w[-1] = 1.0
    wX = w * X

    def neg_r(tau):
        return -float(np.real(np.sum(wX * np.exp(2j * np.pi * k * tau / nfft)))) / nfft
    best = minimize_scalar(neg_r, bounds=(k0 - 1.0, k0 + 1.0), method="bounded",
                           options={"xatol": 1e-4})
    at_k0 = neg_r(float(k0))
    # Brent need not visit k0 itself: keep the integer peak if the search ended lower
    return (float(best.x), -float(best.fun)) if best.fun <= at_k0 else (float(k0), -at_k0)


def time_lag(a, b, fs: float, band: tuple[float, float] | None = None,
             max_lag_s: float | None = None, *, band_b: tuple[float, float] | None = None) -> LagResult:
    """Delay between the envelopes of channels ``a`` and ``b`` (1-D, same length and rate ``fs``).

    ``band``: band-pass (Hz) before the envelope, as in :func:`.envelope.envelope` (zero-phase,
    so it moves no impulse); ``band_b``: a different band for ``b`` (default ``band``), e.g. each
    side's own resonance band.
    ``max_lag_s``: search only lags up to this (s).  Periodic impulses make the correlation
    periodic in the impulse period, so the lag is only defined modulo it: pass at most half the
    fault period (pair analysis passes ``0.5 / BPFO``).  Default: the whole record.
    """
    a, b, fs = _pair(a, b, fs)
    band_b = band if band_b is None else band_b
    ea = envelope(a, fs, band)
    eb = envelope(b, fs, band_b)
    # the band-pass and Hilbert edge transients sit at the same place in both channels and
    # would correlate by themselves: leave 2 % out at each end (the same samples in both)
    m = a.size // 50
    ea = ea[m:a.size - m] - ea[m:a.size - m].mean()
    eb = eb[m:b.size - m] - eb[m:b.size - m].mean()
    # sums, not np.dot: BLAS splits a long dot product by its thread count, so the last bit
    # would depend on the process (a dask worker runs BLAS on one thread)
    norm = np.sqrt(np.sum(ea * ea) * np.sum(eb * eb))
    if not norm > 0:
        raise ParameterError("time lag: an envelope is constant: expected channels with impulses")
    # correlate(eb, ea)[k] = sum_n eb[n + k] ea[n]: a peak at k > 0 means b is late (a leads)
    c = correlate(eb, ea, mode="full", method="fft")
    lags = correlation_lags(eb.size, ea.size, mode="full")
    if max_lag_s is not None:
        if not max_lag_s > 0:
            raise ParameterError(f"max_lag_s = {max_lag_s!r} s is not allowed: expected a time > 0")
        keep = np.abs(lags) <= max(1, int(np.floor(max_lag_s * fs)))
        c, lags = c[keep], lags[keep]
    i = int(np.argmax(c))
    nfft = next_fast_len(ea.size + eb.size - 1, real=True)
    X = rfft(eb, nfft) * np.conj(rfft(ea, nfft))
    tau, r = _refine(X, nfft, int(lags[i]))
    peak = float(r / norm)
    leading = "none" if abs(tau) < 1e-3 else ("a" if tau > 0 else "b")
    return LagResult(lag_s=abs(tau) / fs, lag_samples=abs(tau), leading=leading,
                     delay_b_samples=tau, peak=peak, fs=float(fs),
                     band_a=None if band is None else tuple(map(float, band)),
                     band_b=None if band_b is None else tuple(map(float, band_b)))


def _onset(x: np.ndarray) -> int:
    """Arrival of the impulse in ``x``, an envelope stretch ending at its peak: the Akaike
    information criterion picker, ``AIC(k) = k log var(x[:k]) + (n - k - 1) log var(x[k:])``,
    minimal where the level changes (Maeda, Zisin 38 (1985) 365-379; for acoustic-emission
    onsets Kurz et al., Ultrasonics 43 (2005) 538-546).  No threshold: the same rule reads a
    sharp and a slowly building arrival."""
    n = x.size
    if n < 8:
        return 0
    k = np.arange(2, n - 2)
    c1, c2 = np.cumsum(x), np.cumsum(x * x)
    v1 = (c2[k - 1] - c1[k - 1] ** 2 / k) / k
    v2 = ((c2[-1] - c2[k - 1]) - (c1[-1] - c1[k - 1]) ** 2 / (n - k)) / (n - k)
    aic = k * np.log(np.maximum(v1, 1e-300)) + (n - k - 1) * np.log(np.maximum(v2, 1e-300))
    return int(k[np.argmin(aic)])


def _delay(stack_a: np.ndarray, stack_b: np.ndarray) -> int:
    """Arrival on b's averaged envelope less that on a's (samples), each picked on the stretch
    of one length that ends at its own peak (:func:`_onset`; equal lengths keep the pick's
    bias the same on both, so a shifted copy reads as its shift)."""
    avg = [st.mean(axis=0) for st in (stack_a, stack_b)]
    top = [int(np.argmax(v)) for v in avg]
    n = min(top)
    out = [t - n + _onset(v[t - n:t + 1]) for v, t in zip(avg, top)]
    return out[1] - out[0]


def impulse_lag(a, b, fs: float, period_s: float, band: tuple[float, float] | None = None, *,
                band_b: tuple[float, float] | None = None, min_impulses: int = 5,
                min_agreement: float = 0.9, n_boot: int = 200, seed: int = 0) -> LagResult:
    """Delay of ``b`` behind ``a`` read on their impulses (module docstring).

    The impulses are the peaks, at least 0.6 ``period_s`` apart and 4 median absolute
    deviations over the median, of the more impulsive envelope (99th percentile over median);
    both envelopes are cut +-0.45 ``period_s`` around each and averaged over the impulses
    (synchronous averaging: what recurs with the fault adds up, the noise averages out), and
    the arrival on each average is picked.  ``n_boot`` bootstrap resamples of the impulses give
    the spread (half their interquartile range) and the agreement (the share with the same
    sign).  ``leading`` is named only with at least ``min_impulses`` impulses,
    ``min_agreement`` and a delay of at least one sample."""
    a, b, fs = _pair(a, b, fs)
    if not (np.isfinite(period_s) and period_s > 0):
        raise ParameterError(f"period_s = {period_s!r} s is not allowed: expected a fault period > 0")
    band_b = band if band_b is None else band_b
    env = (envelope(a, fs, band), envelope(b, fs, band_b))
    m = a.size // 50                       # filter and Hilbert edge transients, as time_lag
    inner = [e[m:a.size - m] for e in env]
    score = [np.percentile(e, 99.0) / max(np.median(e), 1e-300) for e in inner]
    ref = env[int(np.argmax(score))]
    core = ref[m:a.size - m]
    med = np.median(core)
    mad = np.median(np.abs(core - med))
    w = int(0.45 * period_s * fs)
    peaks, _ = find_peaks(ref, distance=max(1, int(0.6 * period_s * fs)), height=med + 4.0 * mad)
    peaks = peaks[(peaks - w >= m) & (peaks + w < a.size - m)]
    n = int(peaks.size)
    bands = dict(band_a=None if band is None else tuple(map(float, band)),
                 band_b=None if band_b is None else tuple(map(float, band_b)))
    if n < 2 or w < 8:
        return LagResult(0.0, 0.0, "none", 0.0, 0.0, fs, method="impulses", n_impulses=n,
                         agreement=0.0, **bands)
    idx = peaks[:, None] + np.arange(-w, w)
    stacks = env[0][idx], env[1][idx]
    tau = float(_delay(*stacks))
    rng = np.random.default_rng(seed)
    boot = np.array([_delay(stacks[0][r], stacks[1][r])
                     for r in rng.integers(0, n, size=(n_boot, n))], float)
    q1, q3 = np.percentile(boot, [25.0, 75.0])
    agree = float(np.mean(np.sign(boot) == np.sign(tau))) if tau != 0 else 0.0
    sure = n >= min_impulses and agree >= min_agreement and abs(tau) >= 1
    k = int(tau)
    ea, eb = (e[m:a.size - m] - e[m:a.size - m].mean() for e in env)
    x, y = (ea[:ea.size - k], eb[k:]) if k >= 0 else (ea[-k:], eb[:eb.size + k])
    r = float(np.sum(x * y) / max(np.sqrt(np.sum(x * x) * np.sum(y * y)), 1e-300))  # as above
    return LagResult(lag_s=abs(tau) / fs, lag_samples=abs(tau),
                     leading=("a" if tau > 0 else "b") if sure else "none", delay_b_samples=tau,
                     peak=r, fs=fs, method="impulses", n_impulses=n,
                     spread_s=0.5 * float(q3 - q1) / fs, agreement=agree, **bands)
