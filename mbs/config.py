"""The vehicle run configuration (TOML): schema, defaults, validation.

Every field has a default (the values of ``configs/vehicle.toml``), a type and an allowed range;
a user file overrides what it names.  An unknown section or field, a value of the wrong type or
out of range is refused with :class:`~axlebox._params.ParameterError` naming ``section.field``,
the value and what is allowed (the CLI turns it into one line and exit status 2).
"""
from __future__ import annotations

import copy
import math
import tomllib
from pathlib import Path

from axlebox._params import ParameterError
from axlebox.mbs.integrate import METHODS
from axlebox.mbs.trackbed import MODELS as TRACK_MODELS

BODY_NAMES = (["carbody", "frame1", "frame2"] + [f"ws{i}" for i in range(1, 5)]
              + [f"ab{i}{s}" for i in range(1, 5) for s in "LR"] + [f"gb{i}" for i in range(1, 5)])
# the bodies that have a reduced (FE) body to be flexible with: frames, wheelsets, axle-boxes
FLEXIBLE_NAMES = [n for n in BODY_NAMES if not n.startswith(("carbody", "gb"))]

BODY_KINDS = ("wheelset", "axlebox", "frame")
F, I, S, B, L, N = "float", "int", "str", "bool", "list", "numbers"
INF = math.inf
# section -> field -> (kind, default, lo, hi | choices)
SCHEMA: dict[str, dict[str, tuple]] = {
    "run": {"duration": (F, 5.0, 1e-4, 1e4), "speed_kmh": (F, 48.0, 1.0, 200.0),
            "seed": (I, 0, 0, 2**31 - 1)},
    "integrator": {"method": (S, "leapfrog", METHODS),
                   "dt": (F, 5e-5, 1e-7, 1e-3),
                   "output_rate_hz": (F, 1e4, 1.0, 1e6), "state_rate_hz": (F, 500.0, 0.1, 1e6),
                   "rho_inf": (F, 0.8, 0.0, 1.0)},
    # the bodies' step and their exchange with the bearings (mbs/exchange.py): a whole multiple
    # of integrator.dt, which is then the bearings' sub-step; 0: every step (single rate)
    "coupling": {"exchange_dt": (F, 0.0, 0.0, 1e-3), "body_substeps": (I, 1, 1, 1000),
                 "hold": (S, "zoh", ("zoh", "linear", "jacobian"))},
    "track": {"fra_class": (I, 5, 1, 6), "lambda_min": (F, 1.0, 0.5, 100.0),
              "lambda_max": (F, 80.0, 1.0, 1000.0), "length": (F, 400.0, 10.0, 1e5),
              "irregularity": (B, True),
              "rail_roughness": (S, "none", ("none", "iso3095", "network")),
              "wheel_roughness": (S, "none", ("none", "cast-iron", "composite", "disc")),
              "contact_filter": (B, True), "roughness_lambda_min": (F, 0.003, 0.001, 0.1),
              # the track under each wheel (mbs/trackbed.py); per rail seat, SI
              "model": (S, "rigid", TRACK_MODELS),
              "rail_mass": (F, 60.64, 10.0, 200.0), "rail_EI": (F, 6.624e6, 1e5, 1e8),
              "sleeper_spacing": (F, 0.6, 0.3, 1.5), "pad_k": (F, 6.5e7, 1e6, 1e10),
              "pad_c": (F, 7.5e4, 0.0, 1e7), "sleeper_mass": (F, 125.5, 10.0, 2000.0),
              "ballast_mass": (F, 531.4, 0.0, 5000.0), "ballast_k": (F, 1.3775e8, 1e6, 1e10),
              "ballast_c": (F, 5.88e4, 0.0, 1e7), "subgrade_k": (F, 7.75e7, 1e6, 1e10),
              "subgrade_c": (F, 3.115e4, 0.0, 1e7)},
    "wheelrail": {"wheel": (S, "S1002", None), "rail": (S, "UIC60", None),
                  "gauge": (F, 1.435, 0.9, 1.7), "back_to_back": (F, 1.360, 0.9, 1.6),
                  "cant": (F, 0.025, 0.0, 0.1), "mu": (F, 0.3, 0.0, 1.0),
                  "law": (S, "fastsim", ("fastsim", "kalker", "she")), "fastsim_grid": (I, 8, 2, 64),
                  "fastsim_update": (S, "cutback", ("cutback", "rotate")),
                  "smooth_y": (F, 1.0e-3, 0.0, 0.005)},
    "bodies": {"dir": (S, "", None), "modes": (I, 12, 1, 100),
               "fmax_wheelset_hz": (F, 1500.0, 1.0, 1e5), "fmax_axlebox_hz": (F, 2500.0, 1.0, 1e5),
               "fmax_frame_hz": (F, 600.0, 1.0, 1e5),
               **{f"method_{k}": (S, "craig-bampton", ("craig-bampton", "guyan")) for k in BODY_KINDS},
               **{f"zeta_{k}": (F, 0.01, 0.0, 0.5) for k in BODY_KINDS},
               "flexible": (L, ["frame1", "ws1", "ws2", "ab1L", "ab1R", "ab2L", "ab2R"], FLEXIBLE_NAMES)},
    "carbody": {"mass": (F, 37400.0, 1.0, 1e6), "inertia": (L, [35.3e3, 1447e3, 1435e3], (1e-3, 1e9)),
                "cg_height": (F, 1.45, 0.3, 5.0)},
    "frame": {"mass": (F, 3420.0, 1.0, 1e5), "inertia": (L, [1430.0, 1850.0, 2950.0], (1e-3, 1e7)),
              "cg_height": (F, 0.60, 0.2, 2.0)},
    "wheelset": {"mass": (F, 1539.0, 1.0, 1e5), "inertia": (L, [801.0, 104.0, 814.0], (1e-3, 1e6)),
                 "r0": (F, 0.42, 0.2, 0.7)},
    "axlebox": {"mass": (F, 78.7, 0.1, 1e4), "inertia": (L, [0.75, 2.36, 2.08], (1e-5, 1e4)),
                "cup_mass": (F, 0.0, 0.0, 1e3), "cover_mass": (F, 0.0, 0.0, 1e3),
                "adapter_mass": (F, 0.0, 0.0, 1e3)},
    "gearbox": {"mass": (F, 450.0, 0.0, 1e4), "inertia": (L, [20.0, 30.0, 20.0], (1e-4, 1e5)),
                "arm": (F, 0.35, 0.0, 1.5), "hanger_arm": (F, 0.6, 0.05, 2.0),
                "hanger_k": (F, 5e6, 1.0, 1e10), "hanger_c": (F, 2e4, 0.0, 1e8),
                "side": (S, "R", ("L", "R"))},
    "geometry": {"bogie_distance": (F, 12.6, 3.0, 30.0), "wheelbase": (F, 2.2, 1.0, 4.0),
                 "journal_y": (F, 1.0, 0.6, 1.5), "air_spring_y": (F, 1.0, 0.3, 1.5),
                 "air_spring_height": (F, 0.85, 0.3, 2.0)},
    "primary": {"kx": (F, 10.6e6, 0.0, 1e10), "ky": (F, 7.8e6, 0.0, 1e10), "kz": (F, 1.7e6, 1.0, 1e10),
                "cz": (F, 1e4, 0.0, 1e8)},
    "secondary": {"kx": (F, 0.21e6, 0.0, 1e9), "ky": (F, 0.2e6, 0.0, 1e9), "kz": (F, 0.35e6, 1.0, 1e9),
                  "cz": (F, 3e4, 0.0, 1e8), "cy": (F, 4e4, 0.0, 1e8), "anti_roll": (F, 1e6, 0.0, 1e9),
                  "traction_k": (F, 5e6, 0.0, 1e10), "bumpstop_clearance": (F, 0.03, 0.0, 0.2),
                  "bumpstop_k": (F, 2e6, 0.0, 1e10)},
    # "bearing": the rolling bearing of [bearing] (any model of bearing/models.py); "dtrb" its
    # old name, read the same
    "joint": {"model": (S, "bushing", ("bushing", "bearing", "dtrb")),
              "wheelsets": (L, [1, 2, 3, 4], (1, 2, 3, 4)),
              "k_radial": (F, 1e9, 1e3, 1e12), "k_axial": (F, 5e8, 1e3, 1e12), "c": (F, 2e4, 0.0, 1e8)},
    "sensors": {"node": (S, "sensor_pad", None), "model": (S, "ideal", ("ideal", "accelerometer")),
                "fs_hz": (F, 1e4, 100.0, 1e6), "resonance_hz": (F, 25e3, 100.0, 1e7),
                "resonance_q": (F, 30.0, 0.5, 1e3), "highpass_hz": (F, 0.5, 0.0, 1e3),
                "passband": (F, 0.45, 0.05, 0.49)},
}


# free-form sections checked by their own classes: [bearing] (axlebox.bearing.params.BearingParams
# fields, SI) and [[defects]] (axlebox.bearing.defects.Defect fields, the angle in degrees, plus where)
DEFECT_PLACE = {"wheelset": (I, 2, 1, 4), "side": (S, "R", ("L", "R"))}


def defaults() -> dict:
    cfg = {sec: {k: copy.deepcopy(spec[1]) for k, spec in fields.items()}
           for sec, fields in SCHEMA.items()}
    cfg["bearing"] = {}
    cfg["defects"] = []
    cfg["wheel_defects"] = []
    return cfg


#: ``[[wheel_defects]]`` fields (mbs/wheel_defects.py): where, what, and its shape
WHEEL_DEFECT = {"wheelset": (I, 1, 1, 4), "side": (S, "R", ("L", "R")),
                "kind": (S, "flat", ("flat", "polygon")),
                "length": (F, 0.04, 1e-4, 0.2), "shape": (S, "rounded", ("rounded", "fresh")),
                "angle_deg": (F, 0.0, -360.0, 360.0), "orders": (N, [20.0], 1.0, 200.0),
                "amplitudes_um": (N, [50.0], 0.0, 5000.0), "phases_deg": (N, [], -360.0, 360.0),
                "name": (S, "", None)}
# name: a label that a sweep's [sweep] wheel_defects picks entries by (pipelines/sweep.py)
_WHEEL_FIELDS = {"flat": ("wheelset", "side", "kind", "length", "shape", "angle_deg", "name"),
                 "polygon": ("wheelset", "side", "kind", "orders", "amplitudes_um", "phases_deg",
                             "name")}


def _wheel_defects(items) -> list[dict]:
    """Each ``[[wheel_defects]]`` entry, every field checked (defaults from :data:`WHEEL_DEFECT`)."""
    if not isinstance(items, list) or not all(isinstance(d, dict) for d in items):
        raise ParameterError(f"wheel_defects = {items!r} is not allowed: expected [[wheel_defects]] tables")
    out = []
    for i, d in enumerate(items):
        sec = f"wheel_defects[{i}]"
        kind = _check(sec, "kind", d.get("kind", "flat"), WHEEL_DEFECT["kind"])
        for key in d:
            if key not in _WHEEL_FIELDS[kind]:
                raise ParameterError(f"{sec}.{key} is not a field of a {kind} wheel defect: expected one "
                                     f"of {', '.join(_WHEEL_FIELDS[kind])}")
        e = {k: _check(sec, k, d.get(k, WHEEL_DEFECT[k][1]), WHEEL_DEFECT[k]) for k in _WHEEL_FIELDS[kind]}
        if kind == "polygon":
            n = len(e["orders"])
            if len(e["amplitudes_um"]) != n or len(e["phases_deg"]) not in (0, n) \
                    or any(o != round(o) for o in e["orders"]):
                raise ParameterError(f"{sec}.orders = {e['orders']!r} is not allowed: expected whole "
                                     "orders, one amplitudes_um (and phases_deg, if given) each")
        out.append(e)
    return out


def _bearing(fields) -> dict:
    """``[bearing]``: ``type`` (the model, bearing/models.py) and that model's fields, checked
    by its parameters' class (which names the field and what is allowed)."""
    from axlebox.bearing import models
    models.from_table(fields, "bearing")
    return dict(fields)


def bearing_params(cfg: dict):
    """The parameters of a validated config's ``[bearing]`` (its model's ``Params``)."""
    from axlebox.bearing import models
    return models.from_table(cfg["bearing"], "bearing")


def has_bearings(cfg: dict) -> bool:
    """Whether the axle-boxes sit on rolling bearings (``joint.model`` not ``"bushing"``)."""
    return cfg["joint"]["model"] != "bushing"


def _defects(items) -> list[dict]:
    """Each ``[[defects]]`` entry: ``wheelset``, ``side`` and the Defect fields, angle in deg."""
    import dataclasses

    from axlebox.bearing.defects import Defect
    if not isinstance(items, list) or not all(isinstance(d, dict) for d in items):
        raise ParameterError(f"defects = {items!r} is not allowed: expected [[defects]] tables")
    allowed = list(DEFECT_PLACE) + [f.name for f in dataclasses.fields(Defect) if f.name != "angle"] \
        + ["angle_deg"]
    out = []
    for i, d in enumerate(items):
        for key in d:
            if key not in allowed:
                raise ParameterError(f"defects[{i}].{key} is not a field of [[defects]]: expected "
                                     f"one of {', '.join(allowed)}")
        e = {k: _check(f"defects[{i}]", k, d.get(k, spec[1]), spec) for k, spec in DEFECT_PLACE.items()}
        shape = {k: v for k, v in d.items() if k not in DEFECT_PLACE and k != "angle_deg"}
        # the angle in degrees, checked here: Defect would name its radians
        shape["angle"] = math.radians(_check(f"defects[{i}]", "angle_deg", d.get("angle_deg", 0.0),
                                             (F, 0.0, -360.0, 360.0)))
        try:
            e["defect"] = Defect(**shape)
        except ParameterError as err:
            raise ParameterError(f"defects[{i}]: {err}") from None
        out.append(e)
    return out


def _check(sec: str, key: str, value, spec) -> object:
    kind, _default, *rng = spec
    name = f"{sec}.{key}"
    if kind == F:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) \
                or not rng[0] <= value <= rng[1]:
            raise ParameterError(f"{name} = {value!r} is not allowed: expected a number in "
                                 f"[{rng[0]:g}, {rng[1]:g}]")
        return float(value)
    if kind == I:
        if isinstance(value, bool) or not isinstance(value, int) or not rng[0] <= value <= rng[1]:
            raise ParameterError(f"{name} = {value!r} is not allowed: expected an integer in "
                                 f"[{rng[0]}, {rng[1]}]")
        return value
    if kind == B:
        if not isinstance(value, bool):
            raise ParameterError(f"{name} = {value!r} is not allowed: expected true or false")
        return value
    if kind == S:
        choices = rng[0]
        if not isinstance(value, str) or (choices is not None and value not in choices):
            raise ParameterError(f"{name} = {value!r} is not allowed: expected "
                                 + (f"one of {list(choices)}" if choices else "a string"))
        return value
    if kind == N:                           # a list of numbers in [lo, hi], any length
        lo, hi = rng
        if not isinstance(value, list) or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                  and lo <= v <= hi for v in value):
            raise ParameterError(f"{name} = {value!r} is not allowed: expected a list of numbers in "
                                 f"[{lo:g}, {hi:g}]")
        return [float(v) for v in value]
    # lists: of names (choices) or of 3 positive numbers (range)
    lim = rng[0]
    if not isinstance(value, list):
        raise ParameterError(f"{name} = {value!r} is not allowed: expected a list")
    if isinstance(lim, tuple) and len(lim) == 2 and not isinstance(lim[0], str):
        if len(value) != 3 or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                      and lim[0] <= v <= lim[1] for v in value):
            raise ParameterError(f"{name} = {value!r} is not allowed: expected 3 numbers in "
                                 f"[{lim[0]:g}, {lim[1]:g}]")
        return [float(v) for v in value]
    if not isinstance(lim[0], str):         # wheelset numbers
        if (not value or not all(type(v) is int and v in lim for v in value)
                or len(set(value)) != len(value)):
            raise ParameterError(f"{name} = {value!r} is not allowed: expected distinct wheelset "
                                 f"numbers from {list(lim)}, at least one")
        return sorted(value)
    for v in value:
        if v not in lim:
            what = ("has no FE body to be flexible with" if v in BODY_NAMES else "is not a body")
            raise ParameterError(f"{name} = {value!r} is not allowed: {v!r} {what} "
                                 f"(expected names from: {', '.join(lim)})")
    return list(value)


def track_needed(cfg: dict, duration: float) -> float:
    """Metres of track a validated config's car covers in ``duration`` s: the distance run
    plus its length (the bogie distance and 5 m)."""
    return cfg["run"]["speed_kmh"] / 3.6 * duration + cfg["geometry"]["bogie_distance"] + 5.0


def validate(user: dict) -> dict:
    """Defaults overridden by ``user`` (a parsed TOML dict), every value checked."""
    cfg = defaults()
    for sec, fields in user.items():
        if sec == "bearing":
            cfg[sec] = _bearing(fields)
            continue
        if sec == "defects":
            cfg[sec] = _defects(fields)
            continue
        if sec == "wheel_defects":
            cfg[sec] = _wheel_defects(fields)
            continue
        if sec not in SCHEMA:
            raise ParameterError(f"[{sec}] is not a section of the vehicle config: expected one of "
                                 f"{', '.join(SCHEMA)}, bearing, defects, wheel_defects")
        if not isinstance(fields, dict):
            raise ParameterError(f"{sec} = {fields!r} is not allowed: expected a [{sec}] table")
        for key, value in fields.items():
            if key not in SCHEMA[sec]:
                raise ParameterError(f"{sec}.{key} is not a field of [{sec}]: expected one of "
                                     f"{', '.join(SCHEMA[sec])}")
            cfg[sec][key] = _check(sec, key, value, SCHEMA[sec][key])
    t = cfg["track"]
    if t["lambda_min"] >= t["lambda_max"]:
        raise ParameterError(f"track.lambda_min = {t['lambda_min']:g} is not allowed: expected less "
                             f"than track.lambda_max = {t['lambda_max']:g}")
    if not t["irregularity"] and t["rail_roughness"] != "none":
        raise ParameterError(f"track.rail_roughness = {t['rail_roughness']!r} is not allowed with "
                             "track.irregularity = false: expected 'none' (the rails' roughness "
                             "rides on their irregular record)")
    run = cfg["run"]
    need = track_needed(cfg, run["duration"])
    if t["irregularity"] and t["length"] < need:
        raise ParameterError(f"track.length = {t['length']:g} is not allowed: the car runs "
                             f"{need:.0f} m (distance plus its length); expected at least that")
    if has_bearings(cfg):
        from axlebox.bearing import models
        ig = cfg["integrator"]
        models.check_step(bearing_params(cfg), ig["method"], ig["dt"], "integrator.method",
                          "integrator.dt")
        for d in cfg["defects"]:
            if d["wheelset"] not in cfg["joint"]["wheelsets"]:
                raise ParameterError(f"defects: wheelset = {d['wheelset']} is not allowed: its "
                                     f"axle-boxes sit on row bushings (joint.wheelsets = "
                                     f"{cfg['joint']['wheelsets']}); expected one of those")
    elif cfg["defects"]:
        raise ParameterError("defects need joint.model = 'bearing': with the bushing joint there is "
                             "no bearing to hold them")
    ig = cfg["integrator"]
    H = cfg["coupling"]["exchange_dt"]
    if H > 0.0:
        n = H / ig["dt"]
        if ig["method"] not in ("leapfrog", "imex", "imex2") and H != ig["dt"]:
            raise ParameterError(f"coupling.exchange_dt = {H:g} is not allowed with integrator.method = "
                                 f"{ig['method']!r}: only the leapfrog methods step the bearings apart "
                                 f"(expected 0 or integrator.dt = {ig['dt']:g})")
        if round(n) < 1 or abs(n - round(n)) > 1e-6 * n:
            raise ParameterError(f"coupling.exchange_dt = {H:g} is not allowed: expected a whole multiple "
                                 f"of integrator.dt = {ig['dt']:g} s (the bearings' sub-step)")
    m = cfg["coupling"]["body_substeps"]
    if m > 1 and (H <= 0.0 or ig["method"] not in ("leapfrog", "imex", "imex2")):
        raise ParameterError(f"coupling.body_substeps = {m} is not allowed with integrator.method = "
                             f"{ig['method']!r} and coupling.exchange_dt = {H:g}: the bodies step "
                             "between exchanges only in a leapfrog run with exchange_dt > 0; expected 1")
    step, name = (H, "coupling.exchange_dt") if H > 0.0 else (ig["dt"], "integrator.dt")
    per_output = 1.0 / ig["output_rate_hz"] / step
    if round(per_output) < 1 or abs(per_output - round(per_output)) > 1e-6 * per_output:
        raise ParameterError(f"{name} = {step:g} is not allowed: expected the output period "
                             f"1/integrator.output_rate_hz = {1.0 / ig['output_rate_hz']:g} s over a "
                             "whole number")
    sn = cfg["sensors"]
    if sn["model"] != "ideal":
        ratio = cfg["integrator"]["output_rate_hz"] / sn["fs_hz"]
        if ratio < 2 or abs(ratio - round(ratio)) > 1e-9:
            raise ParameterError(f"integrator.output_rate_hz = {cfg['integrator']['output_rate_hz']:g} is "
                                 f"not allowed with sensors.model = {sn['model']!r}: expected a whole "
                                 f"multiple, at least 2, of sensors.fs_hz = {sn['fs_hz']:g} (the "
                                 "acquisition filters and decimates what the run writes)")
    g = cfg["gearbox"]
    if g["mass"] > 0 and g["arm"] >= g["hanger_arm"]:
        raise ParameterError(f"gearbox.arm = {g['arm']:g} is not allowed: expected less than "
                             f"gearbox.hanger_arm = {g['hanger_arm']:g} (the hanger carries the far end)")
    return cfg


def loads(text: str, where: str = "config text") -> tuple[dict, str]:
    """Validate a config given as TOML text (``where`` names it in a refusal); returns the
    config and the text."""
    try:
        user = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ParameterError(f"{where} is not valid TOML: {err}") from None
    return validate(user), text


def load(path) -> tuple[dict, str]:
    """Read and validate a config file; returns the config and its text."""
    path = Path(path)
    if not path.is_file():
        raise ParameterError(f"config = {str(path)!r} is not allowed: no such file")
    return loads(path.read_text(), f"config {str(path)!r}")
