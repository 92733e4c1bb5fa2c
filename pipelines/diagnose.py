"""``axlebox diagnose FILE``: the two axle-box channels of one wheelset (or the two bearings of
one shaft) from a file, the one-channel indicators of each side, the time lag, the VF
difference and the paper's criterion (bearing/diagnostics/); a JSON file and a figure.

Readers: :mod:`axlebox.pipelines.readers` (axlebox-result, HDF5, .mat v5 and v7.3, CSV).  Every refusal
is a ParameterError (exit status 2) whose one line names the option, variable or value at fault.
"""
from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import numpy as np

from axlebox._files import write_text
from axlebox._params import ParameterError
from axlebox.bearing.diagnostics.channel import jsonable
from axlebox.bearing.catalogue import custom, lookup
from axlebox.bearing.frequencies import FaultOrders, shaft_hz

from .readers import MAX_SAMPLES, Record, read

BOTH = "faults on both sides"

DTRB_BORE = lookup("dtrb").bore   # m: the DTRB's (bearing/models/dtrb.py BORE, catalogue "dtrb")


def parse_orders(text: str, option: str = "--orders") -> FaultOrders:
    """``"BPFO=3.5848,BPFI=5.4152,FTF=0.39828,BSF=2.357"`` (multiples of the shaft frequency)."""
    keys = ("BPFO", "BPFI", "FTF", "BSF")
    vals = {}
    for item in text.split(","):
        k, _, v = item.partition("=")
        k = k.strip().upper()
        try:
            x = float(v)
        except ValueError:
            x = float("nan")
        if k not in keys or not np.isfinite(x) or not x > 0:
            raise ParameterError(f"{option} item {item.strip()!r} is not allowed: expected "
                                 "NAME=ORDER > 0 with NAME one of " + ", ".join(keys))
        vals[k] = x
    missing = [k for k in keys if k not in vals]
    if missing:
        raise ParameterError(f"{option} lacks {', '.join(missing)}: expected all of "
                             + ", ".join(f"{k}=.." for k in keys))
    return FaultOrders(**vals)


def side_bearings(rec: Record, *, orders_text=None, bore=None, bearing=None, orders_left=None,
                  orders_right=None, bearing_left=None, bearing_right=None, bore_left=None,
                  bore_right=None) -> dict:
    """Each side's :class:`axlebox.bearing.catalogue.Bearing` and where it came from: a side's
    own option (``--orders-left``/``--bearing-left``, ...), else the option for both sides
    (``--orders``/``--bearing``), else the file's bearing (its config's ``[bearing]``), else the
    DTRB.
    Given orders need a bore (``--bore``, or the side's ``--bore-left``/``--bore-right``)."""
    out = {}
    for side, o_side, b_side, bore_side in (("left", orders_left, bearing_left, bore_left),
                                            ("right", orders_right, bearing_right, bore_right)):
        given = [(f"--orders-{side}", o_side), (f"--bearing-{side}", b_side)]
        if o_side is not None and b_side is not None:
            raise ParameterError(f"--orders-{side} and --bearing-{side} both given: expected one "
                                 f"bearing for the {side} side")
        if o_side is None and b_side is None:
            given = [("--orders", orders_text), ("--bearing", bearing)]
            if orders_text is not None and bearing is not None:
                raise ParameterError("--orders and --bearing both given: expected one bearing")
        opt, text = next(((o, v) for o, v in given if v is not None), (None, None))
        D = bore_side if bore_side is not None else bore
        if D is not None and not (np.isfinite(D) and D > 0):
            raise ParameterError(f"--bore{'-' + side if bore_side is not None else ''} = {D!r} is "
                                 "not allowed: expected a diameter > 0 m")
        if opt is not None and opt.startswith("--orders"):
            fo = parse_orders(text, opt)
            if D is None:
                raise ParameterError(f"--bore is missing: {opt} names a bearing by its orders; give "
                                     f"its bore diameter in m (--bore or --bore-{side}; SPM, Eq. 17)")
            b, src = custom(fo, D, name=f"{opt} bearing"), opt
        elif opt is not None:
            b, src = lookup(text, opt), f"{opt} {text}"
        elif rec.bearing is not None:
            b, src = rec.bearing, "the file's bearing"
            if D is not None:
                b = replace(b, bore=float(D))
        else:
            b, src = lookup("dtrb"), "the DTRB (bearing/models/params.py)"
        if D is not None and opt is not None and not opt.startswith("--orders"):
            b = replace(b, bore=float(D))
        out[side] = (b, src)
    return out


def parse_pair(text: str, option: str) -> tuple[float, float]:
    """``"LO,HI"`` -> (lo, hi) with 0 <= lo < hi."""
    try:
        lo, hi = (float(v) for v in text.split(","))
    except ValueError:
        raise ParameterError(f"{option} {text!r} is not allowed: expected LO,HI") from None
    if not (np.isfinite(lo) and np.isfinite(hi) and 0 <= lo < hi):
        raise ParameterError(f"{option} {text!r} is not allowed: expected 0 <= LO < HI")
    return lo, hi


def rotor_of(shaft=None, rpm=None) -> str:
    """What turns the shaft, in the verdict's words: ``"shaft"`` for a machine, whose speed is
    given as ``--shaft-hz`` or ``--rpm``; ``"wheel"`` for a vehicle (``--speed-kmh``, or the
    speed a result file stores)."""
    return "shaft" if shaft is not None or rpm is not None else "wheel"


def shaft_speed(rec: Record, shaft=None, speed_kmh=None, wheel_radius=0.42, rpm=None) -> float:
    """Shaft frequency (Hz): --shaft-hz, --rpm, --speed-kmh with --wheel-radius, else the file's."""
    given = [o for o, v in (("--shaft-hz", shaft), ("--rpm", rpm), ("--speed-kmh", speed_kmh))
             if v is not None]
    if len(given) > 1:
        raise ParameterError(f"{' and '.join(given)} both given: expected one shaft speed")
    if shaft is not None:
        if not shaft > 0:
            raise ParameterError(f"--shaft-hz = {shaft!r} is not allowed: expected a frequency > 0 Hz")
        return float(shaft)
    if rpm is not None:
        if not rpm > 0:
            raise ParameterError(f"--rpm = {rpm!r} is not allowed: expected a speed > 0 rev/min")
        return rpm / 60.0
    if speed_kmh is not None:
        return shaft_hz(speed_kmh, wheel_radius)
    if rec.shaft_hz is None:
        raise ParameterError("the shaft speed is missing: give --shaft-hz, --rpm or --speed-kmh "
                             "(the file does not store one)")
    return rec.shaft_hz


def write_json(path, data: dict) -> Path:
    """JSON through ``path.tmp`` and an atomic rename (a reader never sees half a file)."""
    path = Path(path)
    if not path.parent.is_dir():
        raise FileNotFoundError(f"--json: folder {str(path.parent)!r} does not exist")
    return write_text(path, json.dumps(data, indent=2, allow_nan=False) + "\n")


def read_input(path, *, left=None, right=None, fs=None, column: int = 2, speed_channel=None,
               speed_unit: str = "km/h", tacho=None, tacho_threshold=None, speed_csv=None,
               wheel_radius: float = 0.42, max_samples: int | None = None):
    """The record and its shaft speed over time (:mod:`axlebox.pipelines.speed`; None where nothing gives it):
    ``(Record, Speed | None)``; a tacho's record is cut to the span of its pulses.  The record
    is read on its middle ``max_samples`` (all where None; :func:`.readers.read`) and around its
    gaps (:func:`.readers.condition`); a speed channel or profile on the same samples."""
    from . import speed as sp
    given = [o for o, v in (("--speed-channel", speed_channel), ("--tacho", tacho),
                            ("--speed-csv", speed_csv)) if v is not None]
    if len(given) > 1:
        raise ParameterError(f"{' and '.join(given)} both given: expected one source of the speed")
    rec = read(path, left, right, fs, column, max_samples=max_samples)
    if given and rec.kind == "axlebox-result":
        raise ParameterError(f"{given[0]} is not allowed on a result file: it stores its own shaft "
                             "angle (a run along a speed profile) or speed (its config)")
    speed = None
    for name, make in ((speed_channel, lambda x: sp.from_channel(x, rec.fs, speed_unit, wheel_radius,
                                                                 speed_channel)),
                       (tacho, lambda x: sp.from_tacho(x, rec.fs, tacho_threshold, tacho))):
        if name is None:
            continue
        opt = "--speed-channel" if name is speed_channel else "--tacho"
        try:
            x = read(path, name, name, rec.fs, column, samples=(rec.start, rec.start + rec.left.size),
                     clean=False).left
        except ParameterError as err:
            raise ParameterError(str(err).replace("--left", opt)) from None
        if x.size != rec.left.size:
            raise ParameterError(f"{opt} {name!r} has {x.size} samples, not allowed: the channels "
                                 f"have {rec.left.size}; expected one a sample")
        speed = make(x)
    if speed_csv is not None:
        speed = sp.from_csv(speed_csv, rec.start + rec.left.size, rec.fs, speed_unit, wheel_radius)
        speed = replace(speed, angle=speed.angle[rec.start:])     # times from the file's first sample
    if rec.angle is not None:
        speed = sp.Speed(rec.angle, f"the file's shaft angle ({rec.names[0].split('_')[0]})")
    if speed is not None and not np.all(np.isfinite(speed.angle)):      # a tacho's pulses' span
        keep = np.flatnonzero(np.isfinite(speed.angle))
        sl = slice(keep[0], keep[-1] + 1)
        rec.left, rec.right = rec.left[sl], rec.right[sl]
        speed = sp.Speed(speed.angle[sl], speed.source, speed.rotor)
        k0, k1 = rec.start + int(keep[0]), rec.start + int(keep[-1])
        rec.notes.append(f"cut to the tacho's pulses: samples {k0} to {k1}")
        rec.start = k0
    return rec, speed


def analyse_record(rec: Record, speed, *, scale: float = 1.0, shaft=None, speed_kmh=None,
                   wheel_radius: float = 0.42, rpm=None, orders_text=None, bore=None, band=None,
                   criterion=None, nperseg=None, guided: bool = True, bearing=None, orders_left=None,
                   orders_right=None, bearing_left=None, bearing_right=None, bore_left=None,
                   bore_right=None, order_tracking: str = "auto", estimate=None):
    """Analyse both sides of ``rec``: ``(input info, PairResult)``.  The shaft speed comes from
    the options, else from ``speed`` (its mean; the record order-tracked where
    :func:`.speed.wants_tracking` says so), else from the file; each side's bearing as
    :func:`side_bearings` says.  Without ``speed`` (and not a result file, whose run stores its
    speed), the speed over the record is read from the record (:func:`.speed.from_record`, the
    given speed its start; ``estimate``: one already read over the whole record, a
    :class:`axlebox.bearing.diagnostics.ias.SpeedEstimate`, for a window of it): a changing speed
    read with trust is its clock, one that is not makes the verdict undecided; not with
    ``order_tracking="off"``."""
    from axlebox.bearing.diagnostics.criterion import Criterion
    from axlebox.bearing.diagnostics.pair import analyse_pair

    from . import speed as sp
    criterion = Criterion() if criterion is None else criterion
    if not (np.isfinite(scale) and scale > 0):
        raise ParameterError(f"--scale = {scale!r} is not allowed: expected a factor > 0")
    given = [o for o, v in (("--shaft-hz", shaft), ("--rpm", rpm), ("--speed-kmh", speed_kmh))
             if v is not None]
    if given and speed is not None and rec.kind != "axlebox-result" and speed.estimate is None:
        raise ParameterError(f"{given[0]} is not allowed with a speed over time (--speed-channel, "
                             "--tacho or --speed-csv): expected one source of the speed")
    sides = side_bearings(rec, orders_text=orders_text, bore=bore, bearing=bearing,
                          orders_left=orders_left, orders_right=orders_right,
                          bearing_left=bearing_left, bearing_right=bearing_right,
                          bore_left=bore_left, bore_right=bore_right)
    (bl, src_l), (br, src_r) = sides["left"], sides["right"]
    rotor = rotor_of(shaft, rpm)
    est = None
    if speed is None and rec.kind != "axlebox-result" and order_tracking in ("auto", "on"):
        est = estimate
        if est is None:
            speed, est = sp.from_record(rec.left * scale, rec.right * scale, rec.fs,
                                        shaft_speed(rec, shaft, speed_kmh, wheel_radius, rpm),
                                        (bl.orders, br.orders), rotor)
    own = speed is not None and (not given or speed.estimate is not None)   # the speed over time's
    tracked = sp.wants_tracking(order_tracking, speed, rec.fs) and own
    stats = speed.stats(rec.fs) if speed is not None else None
    if own:
        f_shaft = stats["mean_hz"]
    else:
        f_shaft = shaft_speed(rec, shaft, speed_kmh, wheel_radius, rpm)

    def pair(angle):
        return analyse_pair(rec.left * scale, rec.right * scale, rec.fs, f_shaft,
                            (bl.orders, br.orders), (bl.bore, br.bore), criterion, band,
                            names=rec.names, nperseg=nperseg, guided=guided,
                            bearings=(bl.name, br.name),
                            rotor=speed.rotor if own else rotor, angle=angle,
                            spread=0.0 if angle is not None or stats is None else stats["spread"])
    res = pair(speed.angle if tracked else None)
    res = _sized(res, rec, (bl, br), speed.angle if tracked else None)
    second = None
    if tracked and res.verdict.real is None and BOTH in res.verdict.words.values():
        # a healthy side called faulty is the worst error: under a changing speed a copy's path
        # delay turns its lines against its source's as two trains drift (speed.py docstring),
        # so both sides faulty stands only where the record read in time says so too
        in_time = pair(None)
        second = in_time.verdict.rule
        if BOTH not in in_time.verdict.words.values():
            # a reading in time that finds no line at all is blind where the speed's change
            # smears them, not evidence that both sides are healthy: undecided, not healthy
            seen = any(in_time.verdict.evidence.shown(s) for s in ("left", "right"))
            res = _sized(in_time, rec, (bl, br), None) if seen else sp.blind_in_time(res)
    if est is not None and est.status == "untrusted":
        res = sp.undecided(res, est)
    if speed is not None:
        sp_info = {"from": speed.source, **stats, "order_tracked": tracked,
                   **({"second_look": second} if second else {})}
    elif est is not None:
        sp_info = {"from": "given", "mean_hz": f_shaft, "order_tracked": False}
    else:
        sp_info = None
    if sp_info is not None and (est is not None or speed.estimate is not None):
        sp_info["estimate"] = (est or speed.estimate).to_dict()
    info = {"kind": rec.kind, "left": rec.names[0], "right": rec.names[1],
            "fs_hz": rec.fs, "n_samples": int(rec.left.size), "scale": scale,
            "shaft_hz": f_shaft, "rotor": res.rotor, "speed": sp_info,
            "bearings": {"left": {**bl.to_dict(), "from": src_l},
                         "right": {**br.to_dict(), "from": src_r}},
            "band": list(band) if band is not None else
            "spectral kurtosis" + (", guided on the side without the other's fault line" if guided else ""),
            "notes": rec.notes}
    return info, res


def _sized(res, rec: Record, bearings, angle):
    """``res`` with each faulty side's defect size (bearing/diagnostics/size.py), from each
    side's bearing's diameters and, where the file stores it, its most loaded roller's load."""
    from axlebox.bearing.diagnostics.size import geometry_of, side_sizes
    loads = rec.roller_loads or (None, None)
    geometry = tuple(geometry_of(b, q) for b, q in zip(bearings, loads))
    return replace(res, sizes=side_sizes(res, tuple(b.orders for b in bearings), geometry, angle))


READ_OPTIONS = ("left", "right", "fs", "column", "speed_channel", "speed_unit", "tacho",
                "tacho_threshold", "speed_csv", "wheel_radius")


def analyse_file(path, **options):
    """Read ``path`` (:func:`read_input`, the options of :data:`READ_OPTIONS`; at most
    :data:`.readers.MAX_SAMPLES` a channel, the middle of a longer record) and analyse both
    sides (:func:`analyse_record`, the rest): ``(record, input info, PairResult)``."""
    rec, speed = read_input(path, max_samples=MAX_SAMPLES,
                            **{k: v for k, v in options.items() if k in READ_OPTIONS})
    rest = {k: v for k, v in options.items() if k not in READ_OPTIONS or k == "wheel_radius"}
    try:
        info, res = analyse_record(rec, speed, **rest)
    except ParameterError as err:
        if not rec.notes:
            raise
        # what was read says why a record is too short, say: the stretch between its gaps
        raise ParameterError(f"{err} ({'; '.join(rec.notes)})") from None
    return rec, {"file": str(path), **info}, res


def run(path, *, json_out=None, figures=None, log=print, **options):
    """The whole command: :func:`analyse_file` with ``options``, a printed summary, the JSON and
    the figure.  Returns the :class:`axlebox.bearing.diagnostics.pair.PairResult`."""
    if json_out is not None and not Path(json_out).parent.is_dir():
        raise FileNotFoundError(f"--json: folder {str(Path(json_out).parent)!r} does not exist")
    rec, info, res = analyse_file(path, **options)
    b = info["bearings"]
    bear = "; ".join(f"{s} {b[s]['name']}: BPFO {b[s]['orders']['BPFO'] * info['shaft_hz']:.4g} Hz "
                     f"({b[s]['from']})" for s in ("left", "right"))
    log(f"{Path(path).name} ({rec.kind}): {rec.left.size} samples at {rec.fs:g} Hz, shaft "
        f"{info['shaft_hz']:.4g} Hz; {bear}" + "".join(f"; {n}" for n in rec.notes))
    est = (info["speed"] or {}).get("estimate")
    if est is not None:
        log(f"speed from the record: {est['status']}: {est['reason']}")
    log(res.summary())
    for s in ("left", "right"):
        log(f"{s}: {res.verdict.words[s]}: {res.verdict.sentence(s)}")
    if json_out is not None:
        log(f"wrote {write_json(json_out, jsonable({'input': info, **res.to_dict()}))}")
    if figures is not None:
        out = Path(figures)
        out.mkdir(parents=True, exist_ok=True)
        res.plot(out / f"{Path(path).stem}_diagnose.png")
        log(f"wrote {out / (Path(path).stem + '_diagnose.png')}")
    return res
