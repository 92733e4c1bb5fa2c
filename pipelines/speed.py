"""The shaft's speed for ``axlebox diagnose``: where it comes from and when the record is read in
shaft turns (order tracking, :mod:`axlebox.bearing.diagnostics.ordertrack`).

Sources, one at a time:

* a result file of a car run along a speed profile: the wheelset's stored shaft angle
  (``shafts/ws<k>/angle``, the sensors' wheelset);
* ``--speed-channel NAME`` with ``--speed-unit`` (``km/h`` with ``--wheel-radius``, ``rpm``,
  ``Hz``): a channel of the same file, sample for sample, integrated to the angle;
* ``--tacho NAME``: a once-per-revolution pulse channel of the same file (pulses where it rises
  through ``--tacho-threshold``, default midway between its 1st and 99th percentiles; the angle
  the monotone cubic through them);
* ``--speed-csv FILE``: a speed profile, two columns (time s from the record's first sample,
  speed in ``--speed-unit``), read at each sample by linear interpolation; it must cover the
  record.

Where none is given (and the file is not a result file, whose run stores its speed), the speed
over the record is read from the record itself (:func:`from_record`, tacholess: the ridge of a
family of lines locked to the shaft, :mod:`axlebox.bearing.diagnostics.ias`), from the given
speed (``--speed-kmh``, ``--rpm``, ``--shaft-hz``: the record's mean) as the starting guess.  A
speed it finds constant within :data:`TRACK_SPREAD` (or no line to read it from) leaves the
record read at the given speed, as before; a speed it reads changing is the record's clock
(source ``estimated from the record (<family> ridge)``); a change it cannot read with trust (the
ridge fades, jumps, or two families disagree) makes the verdict "undecided" with the reason
(:func:`undecided`).

With ``--order-tracking auto`` (the default) a record is order-tracked when its speed's range
exceeds :data:`TRACK_SPREAD` of its mean: the fault-line search takes a drift of speed that small
(its harmonic windows, :mod:`axlebox.bearing.diagnostics.faultlines`), beyond it the lines smear
out of their windows.  Then the envelopes are read on the shaft's clock
(:mod:`axlebox.bearing.diagnostics.clock`): resampled to equal angle steps and labelled at the
mean speed, so the envelope spectra are in orders, the lines found at their orders and the
copy-or-source coherence taken on them; the bands, RMS, SPM and the impulses' lag stay in time,
where the structure's resonances and the path's delay are fixed.  Below it the record is read as
it came, at the mean speed (a result file of a constant-speed run at its config's speed, as
before).

A second look (:func:`axlebox.pipelines.diagnose.analyse_record`): an order-tracked reading that
calls both sides faulty (each side's own line, by the copy-or-source test) stands only where the
record read in time says so too; else the reading in time is the verdict, unless it finds no
line at all (the speed's change smears them in time; a window of the accelerating car read on the
speed from its record lost them so at a mean speed 0.2 % off the stored one): then both sides are
undecided (:func:`blind_in_time`), never healthy.  Kept, for two
measured causes (:mod:`axlebox.bearing.diagnostics.coherence`, "While the speed changes";
benchmarks/README.md "The copy under traction"), each a copy whose lines turn against its
source's while the speed changes, which on one speed ramp the copy test cannot tell from two
trains drifting apart: the accelerating car's healthy side, whose copy's 5th BPFO harmonic turns
by 3-4 rad as the drive's torque leaves its wheel and comes back (the 4 s run's window 1.18-3.07
s, 781-1094 Hz: 0.10, the one window of four that still needs it); and a path's delay ``tau``,
``f(t) tau`` of a turn on the shaft's clock, which turns harmonic ``k`` of order ``O`` by ``2 pi
k O (f1 - f0) tau`` (a copy through a 5 ms path over 20-80 km/h reads "faults on both sides" on
the clock: tests/test_second_look.py).  A healthy side called faulty is the worst error the
product can make.  The car's other windows no longer need it: there its copy's strength changed
with the speed, not its timing, which the test reads as one train since its reference is taken
segment by segment (issue 57).
"""
from __future__ import annotations

import csv
from dataclasses import dataclass

import numpy as np

from axlebox._params import ParameterError
from axlebox.bearing.diagnostics import ias, ordertrack

#: the speed's range over its mean above which a record is order-tracked (module docstring)
TRACK_SPREAD = 0.005
UNITS = ("km/h", "rpm", "Hz")
MODES = ("auto", "on", "off")


@dataclass
class Speed:
    """The shaft's angle (turns) at each sample of a record, and where it came from."""

    angle: np.ndarray
    source: str
    rotor: str = "wheel"          # what turns: "wheel" (km/h, a car's result) or "shaft" (rpm, Hz, tacho)
    f_hz: float | None = None     # the speed where every sample gave the same (read as given)
    estimate: ias.SpeedEstimate | None = None   # where the speed was read from the record itself

    def hz(self, fs: float) -> np.ndarray:
        """Speed at each sample (Hz) of a record at ``fs``: the angle's central differences."""
        return np.gradient(self.angle) * fs

    def stats(self, fs: float) -> dict:
        """Mean, lowest and highest shaft speed (Hz) and the range over the mean."""
        f = self.hz(fs)
        mean = (self.f_hz if self.f_hz is not None
                else (self.angle[-1] - self.angle[0]) * fs / max(self.angle.size - 1, 1))
        return {"mean_hz": float(mean), "min_hz": float(f.min()), "max_hz": float(f.max()),
                "spread": float((f.max() - f.min()) / mean) if mean > 0 else float("inf")}


def to_hz(values, unit: str, wheel_radius: float, where: str) -> np.ndarray:
    """Shaft speed (Hz) of speeds in ``unit`` (km/h of a wheel of ``wheel_radius`` m, rev/min or
    Hz)."""
    if unit not in UNITS:
        raise ParameterError(f"--speed-unit {unit!r} is not allowed: expected one of {', '.join(UNITS)}")
    v = np.asarray(values, float)
    if unit == "km/h":
        if not (np.isfinite(wheel_radius) and wheel_radius > 0):
            raise ParameterError(f"--wheel-radius = {wheel_radius!r} is not allowed: expected a radius > 0 m")
        return v / 3.6 / (2 * np.pi * wheel_radius)
    return v / 60.0 if unit == "rpm" else v


def _checked_angle(f_hz, fs: float, where: str) -> np.ndarray:
    """The angle of a speed record at ``fs``; a gap (NaN) or a speed <= 0 named by its sample."""
    bad = np.flatnonzero(~np.isfinite(f_hz))
    if bad.size:
        raise ParameterError(f"{where} has a gap at sample {bad[0]} ({bad.size} samples NaN/inf): "
                             "expected a speed at every sample")
    bad = np.flatnonzero(f_hz <= 0)
    if bad.size:
        raise ParameterError(f"{where} sample {bad[0]} = {f_hz[bad[0]]:.6g} Hz is not allowed: expected "
                             f"a shaft speed > 0 ({bad.size} samples are not; a record of one "
                             "direction of travel)")
    t = np.arange(f_hz.size) / fs
    return ordertrack.angle_from_speed(t, f_hz)


def _made(f_hz, fs, where, source, unit) -> Speed:
    same = float(f_hz[0]) if f_hz.size and np.all(f_hz == f_hz[0]) else None
    return Speed(_checked_angle(f_hz, fs, where), source, "wheel" if unit == "km/h" else "shaft", same)


def from_channel(x, fs: float, unit: str, wheel_radius: float, name: str) -> Speed:
    where = f"--speed-channel {name!r}"
    return _made(to_hz(x, unit, wheel_radius, where), fs, where, f"speed channel {name} ({unit})", unit)


def from_tacho(x, fs: float, threshold: float | None, name: str) -> Speed:
    """The angle from a once-per-revolution tacho; the record must lie between its first and
    last pulses (the part outside is cut by the caller, :func:`cut`)."""
    try:
        pulses = ordertrack.tacho_times(x, fs, threshold)
        t = np.arange(np.asarray(x).size) / fs
        inside = (t >= pulses[0]) & (t <= pulses[-1])
        angle = np.full(t.size, np.nan)
        angle[inside] = ordertrack.angle_from_tacho(pulses, t[inside])
    except ParameterError as err:
        raise ParameterError(f"--tacho {name!r}: {err}") from None
    return Speed(angle, f"tacho {name} ({pulses.size} pulses)", "shaft")


def from_csv(path, n: int, fs: float, unit: str, wheel_radius: float) -> Speed:
    """A speed profile from a CSV of (time s, speed), a header line allowed, read at each of the
    ``n`` samples."""
    where = f"--speed-csv {str(path)!r}"
    rows = []
    try:
        with open(path, newline="") as fh:
            for i, row in enumerate(csv.reader(fh)):
                if not row or not "".join(row).strip():
                    continue
                try:
                    rows.append((float(row[0]), float(row[1])))
                except (ValueError, IndexError):
                    if rows or i > 0:
                        raise ParameterError(f"{where} line {i + 1} {','.join(row)!r} is not allowed: "
                                             "expected two numbers, time s and speed") from None
    except OSError as err:
        raise ParameterError(f"{where} is not readable: {err.strerror}") from None
    if len(rows) < 2:
        raise ParameterError(f"{where} has {len(rows)} rows: expected at least 2 (time s, speed)")
    tp, vp = np.array(rows).T
    if np.any(np.diff(tp) <= 0):
        k = int(np.flatnonzero(np.diff(tp) <= 0)[0]) + 1
        raise ParameterError(f"{where} time {tp[k]:g} s (row {k + 1}) is not allowed: expected times "
                             "increasing")
    t = np.arange(n) / fs
    if tp[0] > t[0] + 1e-9 or tp[-1] < t[-1] - 1e-9:
        raise ParameterError(f"{where} covers {tp[0]:g} to {tp[-1]:g} s, not allowed: the record runs "
                             f"0 to {t[-1]:.6g} s; expected a profile over all of it")
    f_hz = np.interp(t, tp, to_hz(vp, unit, wheel_radius, where))
    return _made(f_hz, fs, where, f"speed profile {path} ({unit})", unit)


#: what a user gives where the record's own speed cannot be trusted
GIVE = "give --speed-channel, --tacho or --speed-csv"


def from_record(left, right, fs: float, nominal_hz: float, orders, rotor: str):
    """The speed over a record of two channels from the record itself, from ``nominal_hz`` (the
    given speed, the record's mean) and the sides' bearing ``orders`` (a (left, right) pair of
    :class:`axlebox.bearing.frequencies.FaultOrders`): ``(Speed | None, SpeedEstimate)``, the
    :class:`Speed` where the estimate reads a changing speed it trusts (module docstring)."""
    est = ias.estimate(left, right, fs, nominal_hz, orders, spread_limit=TRACK_SPREAD)
    if est.status != "changing":
        return None, est
    return Speed(est.angle, est.source, rotor, estimate=est), est


def _both_undecided(res, note: str, **fields):
    """``res`` (a :class:`axlebox.bearing.diagnostics.pair.PairResult`) with both sides
    "undecided", no side named real and no kind, and ``note`` saying why (``fields``: more of
    the verdict's, its rule)."""
    from dataclasses import replace

    from axlebox.bearing.diagnostics.verdict import SIDES
    v = replace(res.verdict, words=dict.fromkeys(SIDES, "undecided"), real=None, note=note,
                kinds=dict.fromkeys(SIDES), **fields)
    return replace(res, verdict=v)


def undecided(res, est):
    """``res`` read at the given speed with both sides "undecided": the speed changes and the
    record does not tell it with trust (``est``, an untrusted
    :class:`axlebox.bearing.diagnostics.ias.SpeedEstimate`)."""
    return _both_undecided(res, f"{est.reason}; {GIVE}", rule="speed not read")


def blind_in_time(res):
    """``res`` (order-tracked, each side owning a fault line) with both sides "undecided" where
    the second look in time finds no line at all (module docstring): the clock's lines stand, a
    second fault and a copy are not told apart."""
    return _both_undecided(res, "on the shaft's clock each side carries a fault line of its own, "
                                "but read in time (the second look) neither shows a line, smeared "
                                "by the speed's change: a second fault is not told from a copy")


def wants_tracking(mode: str, speed: Speed | None, fs: float) -> bool:
    """Whether ``mode`` (auto, on, off) order-tracks a record of ``speed``."""
    if mode not in MODES:
        raise ParameterError(f"--order-tracking {mode!r} is not allowed: expected one of {', '.join(MODES)}")
    if speed is None:
        if mode == "on":
            raise ParameterError("--order-tracking on needs the shaft's speed over the record: give "
                                 "--speed-channel, --tacho or --speed-csv (or a result file of a run "
                                 "along a speed profile)")
        return False
    return mode == "on" or (mode == "auto" and speed.stats(fs)["spread"] > TRACK_SPREAD)
