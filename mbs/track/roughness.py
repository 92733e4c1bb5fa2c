"""Wheel and rail roughness with the contact filter, the CNOSSOS-EU railway source tables.

Short-wave roughness (0.3-40 cm) is what excites a wheel-rail contact at 1-5 kHz: at 48 km/h a
3 mm wave passes the contact at 4.4 kHz.  Levels are one-third-octave band levels in dB re 1 um,
in bands whose exact centre wavelength is ``10**(-n/10)`` m, n = 0..31 (nominal 100 cm to
0.08 cm), as tabulated for the European noise-mapping method:

    S. Kephalopoulos, M. Paviotti, F. Anfosso-Ledee, *Common noise assessment methods in Europe
    (CNOSSOS-EU)*, JRC Reference Report EUR 25379 EN, 2012, railway source model (the IMAGINE
    tables), as distributed with its source-model software V1.10 (catalogues of 2014-03-26,
    vehicles, and 2014-04-27, track).

* **Wheel roughness** (:data:`WHEEL_DB`): "cast-iron" (standard cast-iron tread brake blocks),
  "composite" (k-block composite brake blocks) and "disc" (disc-braked wheels, no tread brake;
  the tables assign it to disc-braked urban subway cars too).  It turns with the wheel: a
  record periodic on the rolling circle 2 pi r0, read at the distance the wheel has rolled.
* **Rail roughness** (:data:`RAIL_DB`): "iso3095", the ISO 3095:2013 limit (a smooth test
  track; the same curve as :data:`axlebox.mbs.track.irregularity.ISO3095_LIMIT_DB`, extended), and
  "network", the "average network, normally maintained smooth" rail of the 2012 report.  (The
  later revision in Directive (EU) 2015/996 changes this rail spectrum and the contact filters
  by 4-8 dB at 1-2 cm; the 2012 tables are the ones used here.)
* **Contact filter** (:func:`contact_filter_db`): the patch averages roughness shorter than it
  is long.  The tables give it for a 920 mm wheel at 25, 50 and 100 kN (:data:`CONTACT_DB`);
  between them it is interpolated linearly in log(load).  The 2012 tables label the load "axle
  load", the 2015 revision "wheel load"; the patch length depends on the wheel's own load, so
  the wheel's static load is used.  A metro wheel of 840 mm has a patch about 3 % shorter than
  a 920 mm one at the same load (Hertz, a ~ D^(1/3)): taken as the 920 mm column.

Each band level L spreads a mean square (1 um)^2 10^(L/10) over the band's width in spatial
angular frequency Omega = 2 pi / lambda; log S is interpolated linearly in log Omega between band
centres (:func:`band_psd`, as :func:`.irregularity.roughness_psd`).  The wheel's and the
rail's roughness are independent, so filtering each by the contact filter equals the tables'
rule of filtering their energetic sum.
"""
from __future__ import annotations

import math

import numpy as np

from axlebox._params import ParameterError

from . import sampling

BANDS = np.arange(32)                                   # centre wavelength 10**(-n/10) m
LAMBDA = 10.0 ** (-BANDS / 10)                           # m, 1.0 .. 7.9e-4
_EDGE = 10.0 ** 0.05                                     # base-ten third-octave half width
WHEEL_DB = {
    "cast-iron": [2.17, 2.17, 2.17, 2.17, 2.17, 2.17, 2.17, 2.17, 2.37, 0.61, 2.61, 5.76, 8.78, 11.11,
                  10.96, 9.79, 7.49, 5.15, 3.02, 1.29, 0.17, -0.70, -1.17, -1.02, 0.27, 0.24, 1.32,
                  3.10, 3.10, 3.10, 3.10, 3.10],
    "composite": [-3.95] * 11 + [-4.34, -4.62, -4.90, -5.22, -6.31, -6.80, -7.24, -7.27, -7.27, -7.14,
                                 -6.94, -6.68, -5.99, -3.75, -2.38, -2.59, -2.46, -2.46, -2.46, -2.46,
                                 -2.46],
    "disc": [-5.93] * 6 + [2.32, 2.82, 2.56, 1.22, 2.06, 0.92, -0.25, -1.57, -2.85, -4.94, -7.00, -8.58,
                           -9.32, -9.51, -10.12, -10.25, -10.33, -10.81, -10.91, -9.52, -9.52, -9.52,
                           -9.52, -9.52, -9.52, -9.52],
}
RAIL_DB = {
    "iso3095": [17.1] * 5 + [15.0, 13.0, 11.0, 9.0, 7.0, 4.9, 2.9, 0.9, -1.1, -3.2, -5.0, -5.6, -6.2,
                             -6.8, -7.4, -8.0, -8.6, -9.2, -9.8, -10.4, -11.0, -11.6, -12.2, -12.8,
                             -13.4, -14.0, -14.0],
    "network": [11.0, 11.0, 11.0, 11.0, 11.0, 10.0, 9.0, 8.0, 7.0, 6.0, 5.0, 4.0, 3.0, 2.0, 1.0, 0.0,
                -1.0, -2.0, -3.0, -4.0, -5.0, -6.0, -7.0, -8.0, -9.0, -10.0, -11.0, -12.0, -13.0,
                -14.0, -15.0, -15.0],
}
#: contact filter (dB) of a 920 mm wheel at 25, 50 and 100 kN
CONTACT_LOADS = np.array([25e3, 50e3, 100e3])
CONTACT_DB = np.array([
    [0] * 11 + [-0.2, -0.5, -0.9, -1.6, -2.5, -3.8, -5.8, -8.5, -11.4, -12, -13.5, -14.5, -16, -16.5,
                -17.7, -18.6, -19.6, -20.6, -21.6, -22.6, -23.6],
    [0] * 12 + [-0.2, -0.5, -0.9, -1.6, -2.5, -3.8, -5.8, -8.5, -12, -12.6, -13.5, -14.5, -16, -16.5,
                -17.7, -18.6, -19.6, -20.6, -21.6, -22.6],
    [0] * 11 + [-0.2, -0.6, -1.3, -2.2, -3.7, -5.8, -9, -11.5, -12.5, -12, -14, -15, -17, -18.4, -19.5,
                -20.5, -21.5, -22.4, -23.5, -24.5, -25.4]], dtype=float)
LAMBDA_MIN = LAMBDA[-1] / _EDGE                           # m, the tables' shortest band edge
LAMBDA_MAX = LAMBDA[0] * _EDGE


def _choice(table: dict, name, field: str) -> np.ndarray:
    if name not in table:
        raise ParameterError(f"{field} = {name!r} is not allowed: expected one of {', '.join(table)}")
    return np.asarray(table[name], dtype=float)


def contact_filter_db(load: float) -> np.ndarray:
    """The contact filter per band (dB, <= 0) at a static wheel load ``load`` (N, 25-100 kN)."""
    if not (isinstance(load, (int, float)) and CONTACT_LOADS[0] <= load <= CONTACT_LOADS[-1]):
        raise ParameterError(f"contact filter load = {load!r} N is not allowed: the tables cover "
                             f"{CONTACT_LOADS[0]:g} to {CONTACT_LOADS[-1]:g} N of wheel load")
    x = np.log(CONTACT_LOADS)
    i = min(int(np.searchsorted(x, math.log(load), side="right")) - 1, x.size - 2)
    u = (math.log(load) - x[i]) / (x[i + 1] - x[i])
    return (1 - u) * CONTACT_DB[i] + u * CONTACT_DB[i + 1]


def levels_db(kind: str, name: str, load: float | None = None) -> np.ndarray:
    """Band levels (dB re 1 um) of wheel (``kind = "wheel"``) or rail roughness ``name``,
    through the contact filter at ``load`` (N) unless it is None."""
    table, field = (WHEEL_DB, "track.wheel_roughness") if kind == "wheel" else \
        (RAIL_DB, "track.rail_roughness")
    L = _choice(table, name, field)
    return L if load is None else L + contact_filter_db(load)


def band_psd(Omega, levels, bands=BANDS, owner: str = "band_psd") -> np.ndarray:
    """One-sided PSD (m^2/(rad/m)) at ``Omega`` (rad/m) of one-third-octave band ``levels`` (dB
    re 1 um) in the bands ``bands`` (centre wavelength ``10**(-n/10)`` m, ascending n)."""
    W = np.asarray(Omega, dtype=float)
    centre = 2 * np.pi * 10.0 ** (np.asarray(bands) / 10)
    lo, hi = centre[0] / _EDGE, centre[-1] * _EDGE
    if not np.all(np.isfinite(W)) or W.min() < lo * (1 - 1e-12) or W.max() > hi * (1 + 1e-12):
        raise ParameterError(f"{owner}.Omega = {W.min():g}..{W.max():g} is not allowed: the bands "
                             f"cover {lo:g} to {hi:g} rad/m (wavelengths {2 * np.pi / hi:.3g} to "
                             f"{2 * np.pi / lo:.3g} m)")
    mean_square = 1e-12 * 10.0 ** (np.asarray(levels, dtype=float) / 10)
    S = mean_square / (centre * (_EDGE - 1 / _EDGE))
    return np.exp(np.interp(np.log(W), np.log(centre), np.log(S)))


def wheel_grid(r0: float, lambda_min: float, points_per_wave: int = 10) -> int:
    """Points of a wheel record around the rolling circle: ``points_per_wave`` on the shortest
    wave, an even number."""
    n = int(math.ceil(points_per_wave * 2 * np.pi * r0 / lambda_min))
    return n + n % 2


def wheel_record(name: str, r0: float, lambda_min: float, load: float | None,
                 rng: np.random.Generator, n: int | None = None):
    """``(values, slopes, ds)``: one wheel's roughness (m) and its slope on the grid
    ``s_j = j ds`` of ``n`` points (default :func:`wheel_grid`) around the rolling circle
    (``n ds = 2 pi r0`` exactly, so the record is periodic in a wheel turn), from the longest
    band that fits the circle down to ``lambda_min``.
    Each FFT bin carries sqrt(2 int_bin S) with a random phase from ``rng``."""
    circle = 2 * np.pi * r0
    if not (LAMBDA_MIN <= lambda_min < LAMBDA_MAX):
        raise ParameterError(f"track.roughness_lambda_min = {lambda_min!r} is not allowed: expected "
                             f"{LAMBDA_MIN:.3g} to {LAMBDA_MAX:.3g} m (the tables' bands)")
    L = levels_db("wheel", name, load)
    n = wheel_grid(r0, lambda_min) if n is None else n
    ds = circle / n
    dW = 2 * np.pi / circle
    W_lo = max(2 * np.pi / LAMBDA_MAX, dW)
    k, amp, phase = sampling.harmonics(lambda W: band_psd(W, L, owner="wheel roughness"), W_lo,
                                       2 * np.pi / lambda_min, dW, rng)
    values, slopes = sampling.record(k, amp, phase, n, dW)
    return values, slopes, ds


def third_octave_levels(x: np.ndarray, ds: float, bands=BANDS) -> np.ndarray:
    """Band levels (dB re 1 um) of a periodic record ``x`` (m) on step ``ds``: its FFT's power
    summed over each band's bins (what a roughness analysis of a measured record does)."""
    n = x.size
    X = np.fft.rfft(x) / n
    power = 2 * np.abs(X) ** 2                          # mean square of each harmonic
    power[0] = 0.0
    W = 2 * np.pi * np.arange(X.size) / (n * ds)
    centre = 2 * np.pi * 10.0 ** (np.asarray(bands) / 10)
    out = np.empty(len(centre))
    for i, c in enumerate(centre):
        inside = (W >= c / _EDGE) & (W < c * _EDGE)
        out[i] = 10 * np.log10(power[inside].sum() / 1e-12) if inside.any() else -np.inf
    return out
