"""Randomised families of two-channel records with known answers: what the copy-or-source test
(:mod:`.coherence`) and the verdicts (:mod:`.criterion`) are designed and judged on.

Each case draws its parameters uniformly from the ranges below (a ratio log-uniformly) with its
own seed, and builds both channels from :mod:`.synthetic`'s parts (the bearing-signal model of
Antoni and Randall, J. Vib. Acoust. 125 (2003) 282-289: hits at the fault rate, each period
scaled by ``1 + jitter N(0, 1)`` so that the timing wanders as a real cage's does, each hit ringing
a structural resonance).

* :func:`copy_case`, one fault and its coaxial pseudo-fault: side A rings its own resonance at
  every hit; side B receives A's response ``delay`` later through a path resonance, scaled to
  ``transmission`` times A's RMS.  The answer: A real, B pseudo-fault or healthy, never "faults
  on both sides".
* :func:`two_source_case`, a fault on each side: A and B each their own slip, jitter and
  ringing, B's RMS ``ratio`` times A's; each one's response reaches the other side as a copy
  does (its own delay and path, transmission ``cross``).  The answer: faults on both sides.

Noise: each side its own, wheel-rail noise (low-passed at 1 kHz) plus a white floor half as
strong (sensor and structure), its RMS set by ``snr_db`` against the side's own source (the copy
side: against the source side's source, so the copy's own SNR is lower by the transmission).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .synthetic import impulse_train, resonance, wheel_rail_noise

COPY_RANGES = {"f_fault": (20.0, 90.0), "slip": (0.005, 0.02), "jitter": (0.005, 0.02),
               "f_ring": (1000.0, 4000.0), "zeta": (0.02, 0.1), "delay_s": (0.0, 5e-3),
               "f_path": (300.0, 3000.0), "zeta_path": (0.02, 0.1),
               "transmission": (0.05, 1.0), "snr_db": (0.0, 20.0)}
TWO_RANGES = {"f_fault": (20.0, 90.0), "slip": (0.005, 0.02), "jitter": (0.005, 0.02),
              "f_ring": (1000.0, 4000.0), "zeta": (0.02, 0.1), "delay_s": (0.0, 5e-3),
              "f_path": (300.0, 3000.0), "zeta_path": (0.02, 0.1), "ratio": (0.3, 3.0),
              "cross": (0.05, 0.5), "snr_db": (0.0, 20.0)}


@dataclass(frozen=True)
class Case:
    """Two channels (``a`` the first fault's side), their rate, the drawn parameters and the
    answer: ``faults`` the sides with a fault of their own ("a", "b")."""

    a: np.ndarray
    b: np.ndarray
    fs: float
    params: dict
    faults: tuple[str, ...]


def _draw(rng, lo, hi, log=False):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))) if log else rng.uniform(lo, hi))


def _source(n, fs, f_fault, rng, slip, jitter, f_ring, zeta):
    """A fault's response, unit RMS: hits at ``f_fault (1 - slip)`` from a random start, each
    period jittered and each hit's size scattered by 10 %, ringing ``f_ring``."""
    hits = impulse_train(n, fs, f_fault, rng, jitter=jitter, slip=slip,
                         start_s=rng.uniform(0.0, 1.0 / f_fault))
    hits[hits > 0] *= 1.0 + 0.1 * rng.standard_normal(np.count_nonzero(hits))
    x = resonance(hits, fs, f_ring, zeta)
    return x / max(x.std(), 1e-300)


def _path(x, fs, delay_s, f_path, zeta_path, gain):
    """``x`` delayed by ``delay_s`` through a path resonance, at ``gain`` times its RMS."""
    k = int(round(delay_s * fs))
    y = np.zeros_like(x)
    y[k:] = x[:x.size - k]
    y = resonance(y, fs, f_path, zeta_path)
    return gain * x.std() * y / max(y.std(), 1e-300)


def _noise(n, fs, rng, rms):
    x = wheel_rail_noise(n, fs, rng) + 0.5 * rng.standard_normal(n)
    return rms * x / x.std()


def copy_case(seed: int, T: float = 10.0, fs: float = 10000.0) -> Case:
    """One fault (side a) and its transmitted copy (side b), parameters from ``COPY_RANGES``."""
    rng = np.random.default_rng(seed)
    p = {k: _draw(rng, *r) for k, r in COPY_RANGES.items()}
    n = int(round(T * fs))
    a = _source(n, fs, p["f_fault"], rng, p["slip"], p["jitter"], p["f_ring"], p["zeta"])
    b = _path(a, fs, p["delay_s"], p["f_path"], p["zeta_path"], p["transmission"])
    s = 10 ** (-p["snr_db"] / 20)
    return Case(a + _noise(n, fs, rng, s), b + _noise(n, fs, rng, s), fs, p, ("a",))


def two_source_case(seed: int, T: float = 10.0, fs: float = 10000.0) -> Case:
    """A fault on each side, each with its own timing and ringing, each carried to the other
    side, parameters from ``TWO_RANGES`` (``_a``/``_b`` each side's own draw)."""
    rng = np.random.default_rng(seed)
    own = ("slip", "jitter", "f_ring", "zeta", "delay_s", "f_path", "zeta_path", "cross",
           "snr_db")
    p = {"f_fault": _draw(rng, *TWO_RANGES["f_fault"]),
         "ratio": _draw(rng, *TWO_RANGES["ratio"], log=True)}
    for side in "ab":
        p.update({f"{k}_{side}": _draw(rng, *TWO_RANGES[k]) for k in own})
    n = int(round(T * fs))
    src = {s: _source(n, fs, p["f_fault"], rng, p[f"slip_{s}"], p[f"jitter_{s}"],
                      p[f"f_ring_{s}"], p[f"zeta_{s}"]) for s in "ab"}
    src["b"] = src["b"] * p["ratio"]
    copy = {s: _path(src[s], fs, p[f"delay_s_{s}"], p[f"f_path_{s}"], p[f"zeta_path_{s}"],
                     p[f"cross_{s}"]) for s in "ab"}
    rms = {s: src[s].std() * 10 ** (-p[f"snr_db_{s}"] / 20) for s in "ab"}
    return Case(src["a"] + copy["b"] + _noise(n, fs, rng, rms["a"]),
                src["b"] + copy["a"] + _noise(n, fs, rng, rms["b"]), fs, p, ("a", "b"))


#: what carries each kind's impacts in and out of the load zone (Randall and Antoni, MSSP 25
#: (2011) 485-520, sec. 2.2): the outer ring stands still (no modulation), the inner ring turns
#: with the shaft, a roller goes round with the cage; and the line each kind strikes at
KIND_LINES = {"outer": "BPFO", "inner": "BPFI", "roller": "2BSF"}
KIND_RANGES = {**COPY_RANGES, "depth": (0.3, 1.0)}


def kind_case(seed: int, kind: str, orders, T: float = 10.0, fs: float = 10000.0) -> Case:
    """One fault of ``kind`` (``"outer"``, ``"inner"``, ``"roller"``) on side a and its copy on
    side b, as :func:`copy_case`, at the kind's order of ``orders``
    (:class:`...frequencies.FaultOrders`): the shaft turns at ``f_fault / BPFO`` (``f_fault``
    drawn from ``COPY_RANGES``), the hits come at the kind's line and are scaled by the load zone
    ``1 + depth cos(2 pi f_mod t + phase)``, ``f_mod`` the shaft's rate (inner ring) or the
    cage's (roller), none for the outer ring.  The answer: a's fault of ``kind``."""
    if kind not in KIND_LINES:
        raise ValueError(f"kind = {kind!r}: expected one of {', '.join(KIND_LINES)}")
    rng = np.random.default_rng(seed)
    p = {k: _draw(rng, *r) for k, r in KIND_RANGES.items()}
    n = int(round(T * fs))
    f_shaft = p["f_fault"] / orders.BPFO
    lines = orders.at(f_shaft)
    f_hit = lines[KIND_LINES[kind]]
    hits = impulse_train(n, fs, f_hit, rng, jitter=p["jitter"], slip=p["slip"],
                         start_s=rng.uniform(0.0, 1.0 / f_hit))
    hits[hits > 0] *= 1.0 + 0.1 * rng.standard_normal(np.count_nonzero(hits))
    f_mod = {"outer": 0.0, "inner": f_shaft, "roller": lines["FTF"]}[kind]
    if f_mod:
        t = np.arange(n) / fs
        hits *= 1.0 + p["depth"] * np.cos(2 * math.pi * f_mod * t + rng.uniform(0, 2 * math.pi))
    a = resonance(hits, fs, p["f_ring"], p["zeta"])
    a /= max(a.std(), 1e-300)
    b = _path(a, fs, p["delay_s"], p["f_path"], p["zeta_path"], p["transmission"])
    s = 10 ** (-p["snr_db"] / 20)
    p.update(kind=kind, f_shaft=f_shaft)
    return Case(a + _noise(n, fs, rng, s), b + _noise(n, fs, rng, s), fs, p, ("a",))
