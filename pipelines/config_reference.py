"""The config reference: the unit and meaning of every config field, and the page of them.

:data:`FIELDS` gives each field of :data:`axlebox.mbs.config.SCHEMA` its unit and a one-line
meaning (the code's words; where a shipped config names the source of a default, it is said).
The free-form tables are read from the code that checks them: ``[bearing]`` from each bearing
model's parameters (:data:`axlebox.bearing.models.MODELS`), ``[[defects]]`` from
:class:`axlebox.bearing.defects.Defect` and :data:`axlebox.mbs.config.DEFECT_PLACE`,
``[[wheel_defects]]`` from :data:`axlebox.mbs.config.WHEEL_DEFECT`, the bearing rig's ``[rig]``
from :class:`axlebox.bearing.rig.RigConfig` and ``[sweep]`` from :mod:`axlebox.pipelines.sweep`.
Defaults and ranges are never written here: :func:`reference_markdown` takes them from those.

Units are SI strings (``"-"`` dimensionless, ``""`` for names and switches); the fields in other
units say so by name: ``speed_kmh`` (km/h), ``*_deg`` (degrees), ``amplitudes_um`` (micrometres)
and ``[sweep] widths_mm`` (millimetres).
"""
from __future__ import annotations

import dataclasses
import math

from axlebox.bearing import models as _models
from axlebox.bearing.defects import PROFILES, Defect
from axlebox.bearing.layout import KINDS

from axlebox.bearing.rig import RIG_METHODS, RIG_SECTIONS, RigConfig
from axlebox.mbs.config import (_WHEEL_FIELDS, B, BODY_KINDS, DEFECT_PLACE, F, I, L, N, S, SCHEMA,
                                WHEEL_DEFECT)

from .sweep import SIDES, SWEEP_FIELDS

# ---- formatting --------------------------------------------------------------------------------

def _num(v) -> str:
    """A number as TOML reads it: plain from 0.01 to below 1e4, else the shortest ``1.5e7``."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if v == 0 or 1e-2 <= abs(v) < 1e4:
        return repr(float(v))
    for p in range(17):
        s = f"{v:.{p}e}"
        if float(s) == v:
            break
    m, e = s.split("e")
    return f"{m}e{int(e)}"


def _value(v) -> str:
    """A value as it would be written in the TOML file."""
    if isinstance(v, str):
        return f'"{v}"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    return _num(v)


def _choices(choices) -> str:
    return ", ".join(f"`{_value(c)}`" for c in choices)


def _range(lo, hi, unit: str = "") -> str:
    text = f"{_num(lo)} … {_num(hi)}"
    if unit == "rad":
        text += f" ({math.degrees(lo):.6g} … {math.degrees(hi):.6g} deg)"
    return text


def _default(v, unit: str = "") -> str:
    text = f"`{_value(v)}`"
    if unit == "rad" and v:
        text += f" ({math.degrees(v):.6g} deg)"
    return text


def _steps(scheme: str) -> str:
    """Each model's methods and largest steps under ``scheme`` (bearing/models.py ``methods``)."""
    out = []
    for name, m in _models.MODELS.items():
        p = dataclasses.replace(m.Params(), model=scheme)
        out.append(f"{name.upper()}: " + ", ".join(f"{k} {_num(v)}" for k, v in _models.methods(p).items()))
    return "; ".join(out)


_DT_MAX = _steps("dynamic")
_QD_DT_MAX = _steps("quasi-dynamic")
ZHAI = "Zhai et al. 2004"

#: section -> one line on what it is
SECTION_NOTES: dict[str, str] = {
    "run": "What is run: how long and how fast.",
    "integrator": "The car's time integrator (mbs/integrate.py).",
    "coupling": "The bodies' step and their exchange with the DTRB bearings (mbs/exchange.py).",
    "track": "Track irregularity (FRA spectra, mbs/track.py), roughness (mbs/roughness.py) and the "
             "track under each wheel (mbs/trackbed.py; the ballasted seats per rail seat, assumed: "
             "Zhai, Wang and Lin, J. Sound Vib. 270 (2004) 673-683, 60 kg/m rail, as tabulated by "
             "the open TTB-2D model).",
    "wheelrail": "Wheel and rail profiles, their layout and the contact (mbs/wheelrail).",
    "bodies": "The reduced (flexible) bodies: where they come from and what they keep.",
    "carbody": "The carbody, rigid (Hangzhou Metro Line 1 B-type motor car, Math. Probl. Eng. 2020, "
               "1584624, Table 6).",
    "frame": "The bogie frames (two).",
    "wheelset": "The wheelsets (four).",
    "axlebox": "The axle-boxes (eight) and the assembly parts their housing mesh lacks.",
    "gearbox": "The gearboxes (four), hung between the axle and the frame; mass 0: none.",
    "geometry": "Where the bodies and suspension points sit (track frame: x forward, y left, z up).",
    "primary": "Primary suspension, per axle box: two coil springs, each half of these.",
    "secondary": "Secondary suspension: per air spring (two per bogie) and per bogie.",
    "joint": "The wheelset-axle-box joint: row bushings or the DTRB bearings.",
    "sensors": "The axle-box accelerometers and the acquisition (pipelines/sensor.py).",
}

_BODY = {"wheelset": "wheelset", "axlebox": "axle-box", "frame": "frame"}
_FMAX_WHY = {"wheelset": "up past its second bending pair and the 300-800 Hz band",
             "axlebox": "its lowest modes", "frame": "the frame's own modes"}

#: section -> field -> (unit, meaning), for every field of SCHEMA
FIELDS: dict[str, dict[str, tuple[str, str]]] = {
    "run": {
        "duration": ("s", "simulated time; the track must be long enough (track.length)"),
        "speed_kmh": ("km/h", "vehicle speed, in km/h by name (the one run field not in SI)"),
        "seed": ("-", "seed of the track irregularity's random phases and the wheels' roughness"),
    },
    "integrator": {
        "method": ("", "'leapfrog' (explicit central differences), 'imex' / 'imex2' (the leapfrog "
                       "with the bearings' contact damping / stiffness implicit), 'rk4' or 'galpha' "
                       "(generalized-alpha); with bearings (joint.model) one their model accepts "
                       f"({_DT_MAX}; quasi-dynamic: {_QD_DT_MAX})"),
        "dt": ("s", "fixed step, dividing 1/output_rate_hz; with bearings and a leapfrog method "
                    "their sub-step; with bearings (joint.model) at most their model's step for the "
                    "method (s, as under method)"),
        "output_rate_hz": ("Hz", "sensor output rate (the field system's 10 kHz); with "
                                 "sensors.model = 'accelerometer' a whole multiple >= 2 of "
                                 "sensors.fs_hz"),
        "state_rate_hz": ("Hz", "rate of whole-state snapshots"),
        "rho_inf": ("-", "generalized-alpha spectral radius at infinity (method 'galpha' only)"),
    },
    "coupling": {
        "exchange_dt": ("s", "the bodies' step and their exchange with the DTRBs, a whole multiple "
                             "of integrator.dt (then the bearings' sub-step); 0: integrator.dt; "
                             "other than integrator.dt with the leapfrog methods only"),
        "body_substeps": ("-", "the bodies' steps per exchange, the bearings' loads held between "
                               "(the paper's co-simulation arrangement); 1: one; > 1 needs "
                               "exchange_dt > 0"),
        "hold": ("", "how the loads are held between exchanges: 'zoh' (constant), 'linear' "
                     "(extrapolated) or 'jacobian' (plus the bearings' tangent stiffness times "
                     "the rings' displacement, Kuebler and Schiehlen 2000)"),
    },
    "track": {
        "fra_class": ("-", "American (FRA) track class of the irregularity, 1 (worst) to 6 (best)"),
        "lambda_min": ("m", "shortest irregularity wavelength; below lambda_max"),
        "lambda_max": ("m", "longest irregularity wavelength"),
        "length": ("m", "periodic irregularity record; with irregularity at least the distance "
                        "run plus the car (geometry.bogie_distance + 5 m)"),
        "irregularity": ("", "false: smooth track (then rail_roughness must be 'none')"),
        "rail_roughness": ("", "short-wave rail roughness: 'iso3095' (the ISO 3095:2013 limit) or "
                               "'network' (CNOSSOS-EU's average network); 'none': none"),
        "wheel_roughness": ("", "each wheel's roughness by brake: 'cast-iron' or 'composite' brake "
                                "blocks, or 'disc'; 'none': none"),
        "contact_filter": ("", "the CNOSSOS-EU contact filter of the roughness at the static "
                               "wheel load"),
        "roughness_lambda_min": ("m", "shortest roughness wavelength (3 mm: 4.4 kHz at 48 km/h)"),
        "model": ("", "the track under each wheel: 'rigid' rails (the paper's car, its "
                      "calibration and field cases) or 'ballasted' (rail, sleeper and ballast "
                      "lumped under each wheel)"),
        "rail_mass": ("kg/m", f"rail mass per metre, ballasted track ({ZHAI}, 60 kg/m rail)"),
        "rail_EI": ("N m^2", f"rail bending stiffness, E 205.9 GPa, I 3217 cm^4 ({ZHAI})"),
        "sleeper_spacing": ("m", f"rail seat (sleeper) spacing ({ZHAI})"),
        "pad_k": ("N/m", f"rail pad stiffness, per rail seat ({ZHAI})"),
        "pad_c": ("N s/m", f"rail pad damping, per rail seat ({ZHAI})"),
        "sleeper_mass": ("kg", f"half a sleeper, per rail seat ({ZHAI})"),
        "ballast_mass": ("kg", f"the ballast block under a rail seat ({ZHAI})"),
        "ballast_k": ("N/m", f"ballast stiffness, per rail seat ({ZHAI})"),
        "ballast_c": ("N s/m", f"ballast damping, per rail seat ({ZHAI})"),
        "subgrade_k": ("N/m", f"subgrade stiffness, per rail seat ({ZHAI})"),
        "subgrade_c": ("N s/m", f"subgrade damping, per rail seat ({ZHAI})"),
    },
    "wheelrail": {
        "wheel": ("", "wheel profile: 'S1002' (built in, a stand-in for the LM profile) or a "
                      "profile file"),
        "rail": ("", "rail profile: 'UIC60' (60E1), '60E1' or 'CHN60' (built in) or a profile file"),
        "gauge": ("m", "track gauge"),
        "back_to_back": ("m", "distance between the wheels' back faces (the S1002/60E1 standard "
                              "pair; the LM wheelset's is 1.353 m)"),
        "cant": ("-", "rail inclination, the tan of the cant angle (0.025: 1:40)"),
        "mu": ("-", "wheel-rail friction coefficient"),
        "law": ("", "creep force law: 'fastsim' (Kalker's FASTSIM), 'kalker' (linear) or 'she' "
                    "(Shen-Hedrick-Elkins)"),
        "fastsim_grid": ("-", "FASTSIM elements per semi-axis of the contact patch"),
        "fastsim_update": ("", "FASTSIM slip step: 'cutback' (Kalker's, continuous in the "
                               "creepages, as the implicit Newton needs) or 'rotate' (second order, "
                               "jumps at stick-slip changes)"),
        "smooth_y": ("m", "lateral displacement the contact tables are smoothed over (the tread "
                          "contact jump of S1002 on 60E1 1:40); 0: exact tables"),
    },
    "bodies": {
        "dir": ("", "folder of reduced-body files (axlebox bodies build); empty: built at the "
                    "coarse mesh into the cache"),
        "modes": ("-", "Craig-Bampton fixed-interface modes when the bodies are built here (not "
                       "with dir)"),
        **{f"fmax_{k}_hz": ("Hz", f"a flexible {_BODY[k]} keeps its free-free modes below this "
                                  f"({_FMAX_WHY[k]}); the stiffest kept mode sets the explicit step")
           for k in BODY_KINDS},
        **{f"method_{k}": ("", f"reduction of the {_BODY[k]} body: Craig-Bampton or Guyan; must "
                               "match the file in dir")
           for k in BODY_KINDS},
        **{f"zeta_{k}": ("-", f"modal damping ratio of a flexible {_BODY[k]}'s modes (replaces "
                              "the file's)")
           for k in BODY_KINDS},
        "flexible": ("", "the bodies made flexible (default: the front bogie); the others are "
                         "rigid with the same FE mass properties; frames, wheelsets and axle-boxes "
                         "only (the carbody and gearboxes have no FE body)"),
    },
    "carbody": {
        "mass": ("kg", "carbody mass, rated load"),
        "inertia": ("kg m^2", "principal moments: roll, pitch, yaw (about x, y, z)"),
        "cg_height": ("m", "centre of mass above rail (assumed)"),
    },
    "frame": {
        "mass": ("kg", "frame mass; a flexible frame gets the difference to its FE mass as point "
                       "masses"),
        "inertia": ("kg m^2", "principal moments about x, y, z, used when no reduced body is given"),
        "cg_height": ("m", "centre of mass above rail (assumed)"),
    },
    "wheelset": {
        "mass": ("kg", "wheelset mass, used when no reduced body is given (and in the static "
                       "wheel load)"),
        "inertia": ("kg m^2", "principal moments about x, y (the axle), z, used when no reduced "
                              "body is given"),
        "r0": ("m", "nominal wheel rolling radius"),
    },
    "axlebox": {
        "mass": ("kg", "housing mass (the FE housing's), used when no reduced body is given"),
        "inertia": ("kg m^2", "principal moments about x, y, z, used when no reduced body is given"),
        "cup_mass": ("kg", "bearing cup: point masses on the housing's two bore spiders"),
        "cover_mass": ("kg", "end cover: a point mass on the outboard (row 2) bore spider"),
        "adapter_mass": ("kg", "adapter: point masses on the two spring seats"),
    },
    "gearbox": {
        "mass": ("kg", "gearbox mass (assumed); 0: no gearbox"),
        "inertia": ("kg m^2", "principal moments about x, y, z (assumed)"),
        "arm": ("m", "from the axle to the gearbox centre of mass, towards the bogie centre; "
                     "below hanger_arm"),
        "hanger_arm": ("m", "from the axle to the hanger on the frame"),
        "hanger_k": ("N/m", "hanger link stiffness (assumed)"),
        "hanger_c": ("N s/m", "hanger link damping (assumed)"),
        "side": ("", "the side the gear sits on (as the wheelset geometry's default: 'R')"),
    },
    "geometry": {
        "bogie_distance": ("m", "distance between the bogie centres"),
        "wheelbase": ("m", "bogie wheelbase"),
        "journal_y": ("m", "lateral position of the journal centres"),
        "air_spring_y": ("m", "lateral position of the air springs (assumed)"),
        "air_spring_height": ("m", "air spring height above rail (assumed)"),
    },
    "primary": {
        "kx": ("N/m", "longitudinal stiffness per axle box"),
        "ky": ("N/m", "lateral stiffness per axle box"),
        "kz": ("N/m", "vertical stiffness per axle box"),
        "cz": ("N s/m", "vertical damping per axle box (assumed)"),
    },
    "secondary": {
        "kx": ("N/m", "longitudinal stiffness per air spring"),
        "ky": ("N/m", "lateral stiffness per air spring (assumed)"),
        "kz": ("N/m", "vertical stiffness per air spring (assumed)"),
        "cz": ("N s/m", "vertical damper alongside each air spring (assumed)"),
        "cy": ("N s/m", "lateral damper, per bogie (assumed)"),
        "anti_roll": ("N m/rad", "anti-roll bar, per bogie (assumed)"),
        "traction_k": ("N/m", "traction rod (longitudinal link), per bogie (assumed)"),
        "bumpstop_clearance": ("m", "lateral bump stop clearance (assumed)"),
        "bumpstop_k": ("N/m", "lateral bump stop stiffness (assumed)"),
    },
    "joint": {
        "model": ("", "'bushing': one bushing per bearing row, spin free; 'dtrb': the DTRB model "
                      "([bearing]), which [[defects]] need"),
        "wheelsets": ("", "with model = 'dtrb': the wheelsets whose axle-boxes sit on DTRBs (the "
                          "rest keep the bushings)"),
        "k_radial": ("N/m", "row bushing radial stiffness (order of a DTRB row's)"),
        "k_axial": ("N/m", "row bushing axial stiffness"),
        "c": ("N s/m", "row bushing damping, each translation"),
    },
    "sensors": {
        "node": ("", "the housing node the sensor follows; a box without it: a point 0.175 m above "
                     "its centre"),
        "model": ("", "'ideal': the model's accelerations as they are; 'accelerometer': the "
                      "measurement chain"),
        "fs_hz": ("Hz", "acquisition rate (the paper's system: 10 kHz); model 'accelerometer' only"),
        "resonance_hz": ("Hz", "mounted resonance (an industrial IEPE accelerometer, e.g. PCB "
                               "603C01: 25 kHz)"),
        "resonance_q": ("-", "quality factor of the resonance (assumed)"),
        "highpass_hz": ("Hz", "first-order electrical high-pass (the datasheet's -3 dB point); 0: "
                              "none"),
        "passband": ("-", "anti-alias filter flat to passband x fs_hz, stopping from fs_hz / 2 "
                          "(e.g. TI ADS1278: 0.453)"),
    },
}

#: the BearingParams fields without a ``param`` range: (choices, meaning)

#: the Defect fields without a ``param`` range: (choices, meaning)
DEFECT_CHOICES: dict[str, tuple[tuple, str]] = {
    "kind": (tuple(KINDS), "'outer' (on the cup), 'inner' (on the cone, turning with the shaft) "
                           "or 'roller' (on one roller, turning with its spin)"),
    "profile": (PROFILES, "'half-sine' (Eq. 14) or 'edges' (the roller's path over the pit's "
                          "edges; ring defects only)"),
}

#: the vehicle's [[defects]] fields that are not Defect's: (unit, meaning)
DEFECT_PLACE_DOCS: dict[str, tuple[str, str]] = {
    "wheelset": ("-", "vehicle only: the wheelset whose bearing has it, one of joint.wheelsets"),
    "side": ("", "vehicle only: its bearing's side (the gearbox side is gearbox.side)"),
    "angle_deg": ("deg", "vehicle only: centre of the defect from the top (the load zone's "
                         "middle), in degrees by name; the rig's is angle, in rad"),
}

#: [[wheel_defects]] field -> (unit, meaning)
WHEEL_DEFECT_DOCS: dict[str, tuple[str, str]] = {
    "wheelset": ("-", "the wheelset"),
    "side": ("", "its wheel"),
    "kind": ("", "'flat' or 'polygon' (mbs/wheel_defects.py)"),
    "length": ("m", "the flat's chord (depth about length^2 / (8 r0)); below the wheel radius"),
    "shape": ("", "'rounded' (a worn flat's haversine) or 'fresh' (the chord, sharp edges)"),
    "angle_deg": ("deg", "the flat's centre around the rolling circle"),
    "orders": ("-", "whole harmonic orders around the circumference (times the wheel's rate)"),
    "amplitudes_um": ("µm", "radius amplitude of each order, in micrometres by name"),
    "phases_deg": ("deg", "phase of each order; empty: all 0"),
    "name": ("", "a label that a sweep's [sweep] wheel_defects picks entries by"),
}

#: [rig] constraints beyond each field's range (RigConfig.__post_init__)
RIG_CONSTRAINTS: dict[str, str] = {
    "speed_kmh": "> 0",
    "F_r": "F_r > 0 or F_a != 0",
    "duration": "at least one output sample",
    "dt": f"1/fs_out a whole number of steps; at most the bearing model's step for the method "
          f"({_DT_MAX}; quasi-dynamic: {_QD_DT_MAX})",
    "seed": "an integer >= 0",
}

#: ``[sweep]`` field -> (type, default, unit, allowed, meaning); the allowed values are
#: pipelines/sweep.py's (``_numbers`` with ``zero_ok``, ``KINDS``, ``SIDES``)
SWEEP_DOCS: dict[str, tuple[str, str, str, str, str]] = {
    "speeds_kmh": ("list of float", "the config's own speed_kmh", "km/h", "numbers > 0",
                   "the cases' speeds, in km/h by name"),
    "widths_mm": ("list of float", "the config's [[defects]] as they are", "mm", "numbers >= 0",
                  "defect widths in mm by name: 0 removes the [[defects]], > 0 sets their W"),
    "kinds": ("list of str", "the defects' own kind", "", _choices(tuple(KINDS)),
              "sets every defect's kind"),
    "sides": ("list of str", "the defects' own side", "", _choices(SIDES),
              "vehicle only: puts every defect on that side, 'LR' on both"),
    "wheel_defects": ("list of str", "the config's [[wheel_defects]]", "",
                      "'none' or names of [[wheel_defects]] entries",
                      "vehicle only: keeps the entries of that name; 'none': none of them"),
}


_TYPES = {F: "float", I: "int", S: "str", B: "bool", N: "list of float"}


def _schema_row(name: str, spec: tuple, unit: str, meaning: str) -> tuple[str, ...]:
    """A table row from a SCHEMA-style spec ``(kind, default, lo, hi)`` or ``(kind, default,
    choices)``."""
    kind, default, *rng = spec
    if kind in (F, I, N):
        typ, allowed = _TYPES[kind], _range(*rng)
        if kind == N:
            allowed = f"numbers in {allowed}"
    elif kind == B:
        typ, allowed = "bool", "`true`, `false`"
    elif kind == S:
        typ, allowed = "str", _choices(rng[0]) if rng[0] is not None else "any string"
    elif kind == L:                         # lists: 3 numbers, wheelset numbers or body names
        lim = rng[0]
        if len(lim) == 2 and not isinstance(lim[0], str):
            typ, allowed = "list of 3 float", f"3 numbers in {_range(*lim)}"
        elif not isinstance(lim[0], str):
            typ, allowed = "list of int", f"distinct, at least one, of {', '.join(map(str, lim))}"
        else:
            typ, allowed = "list of str", f"names among {_choices(lim)}"
    else:
        raise ValueError(f"{name}: no documentation for a field of kind {kind!r}")
    return name, typ, _default(default), unit, allowed, meaning


def _dataclass_rows(cls, choices: dict, skip=(), constraints: dict | None = None) -> list[tuple]:
    """Rows of a parameter dataclass: ranges, units and meanings from each field's ``param``
    metadata, the string fields' choices and meanings from ``choices``."""
    rows = []
    for f in dataclasses.fields(cls):
        if f.name in skip:
            continue
        md = f.metadata
        typ = {"float": "float", "int": "int", "str": "str"}.get(str(f.type), str(f.type))
        if "range" in md:
            unit = md.get("unit", "") or "-"
            allowed, doc = _range(*md["range"], unit), md.get("doc", "")
        elif f.name in choices:
            unit, (opts, doc) = "", choices[f.name]
            allowed = _choices(opts)
        elif "choices" in md:                   # declared with its choices (axlebox._params.choice)
            unit, allowed, doc = "", _choices(md["choices"]), md.get("doc", "")
        else:
            unit, allowed, doc = ("-" if typ in ("int", "float") else ""), "", md.get("doc", "")
        extra = (constraints or {}).get(f.name)
        allowed = "; ".join(x for x in (allowed, extra) if x)
        rows.append((f.name, typ, _default(f.default, unit), unit, allowed, doc))
    return rows


# ---- the sections ------------------------------------------------------------------------------

def bearing_rows(model: str = _models.DEFAULT) -> list[tuple]:
    """``[bearing]`` of ``model``: ``type``, then every field of its parameters."""
    m = _models.MODELS[model]
    rows = _dataclass_rows(m.Params, {})
    kind = ("type", "str", _default(_models.DEFAULT), "", _choices(tuple(_models.MODELS)),
            "the bearing model (bearing/models.py): " + "; ".join(
                f"'{n}' {mm.SUMMARY}" for n, mm in _models.MODELS.items()))
    return [kind] + [r for r in rows if r[0] != "type"]


def defect_rows() -> list[tuple]:
    """``[[defects]]``: DEFECT_PLACE's fields, Defect's (the vehicle's angle in degrees)."""
    rows = [_schema_row(k, spec, *DEFECT_PLACE_DOCS[k]) for k, spec in DEFECT_PLACE.items()]
    for r in _dataclass_rows(Defect, DEFECT_CHOICES):
        if r[0] == "angle":                  # the rig's; the vehicle's is angle_deg, its range
            r = r[:5] + ("rig only (the vehicle's is angle_deg): " + r[5],)
        rows.append(r)
    angle = next(f for f in dataclasses.fields(Defect) if f.name == "angle")
    deg = (F, math.degrees(angle.default), *map(math.degrees, angle.metadata["range"]))
    rows.append(_schema_row("angle_deg", deg, *DEFECT_PLACE_DOCS["angle_deg"]))
    return rows


def wheel_defect_rows() -> list[tuple]:
    """``[[wheel_defects]]``: WHEEL_DEFECT's fields, each marked with the kinds that take it."""
    rows = []
    for k, spec in WHEEL_DEFECT.items():
        unit, doc = WHEEL_DEFECT_DOCS[k]
        kinds = [kind for kind, names in _WHEEL_FIELDS.items() if k in names]
        if len(kinds) < len(_WHEEL_FIELDS):
            doc = f"{' and '.join(kinds)} only: {doc}"
        rows.append(_schema_row(k, spec, unit, doc))
    return rows


def rig_rows() -> list[tuple]:
    """``[rig]``: the :class:`~axlebox.bearing.rig.RigConfig` fields that are not sections."""
    method = next(f for f in dataclasses.fields(RigConfig) if f.name == "method")
    choices = {"method": (RIG_METHODS, method.metadata["doc"])}
    rows = _dataclass_rows(RigConfig, choices, skip=RIG_SECTIONS, constraints=RIG_CONSTRAINTS)
    return [r[:5] + ("turns the roller set by a random phase",) if r[0] == "seed" else r
            for r in rows]


def sweep_rows() -> list[tuple]:
    """``[sweep]``: pipelines/sweep.py's SWEEP_FIELDS."""
    return [(k, *SWEEP_DOCS[k]) for k in SWEEP_FIELDS]


def sections() -> list[tuple[str, str, list[tuple]]]:
    """``(heading, note, rows)`` of every section; a row is ``(field, type, default, unit,
    allowed, meaning)``."""
    out = [(f"[{sec}]", SECTION_NOTES[sec],
            [_schema_row(k, spec, *FIELDS[sec][k]) for k, spec in fields.items()])
           for sec, fields in SCHEMA.items()]
    out += [(("[bearing]" if name == _models.DEFAULT else f"[bearing] type = \"{name}\""),
             f"The axle-box bearings of the vehicle (with joint.model = 'bearing') and of the rig, "
             f"type = '{name}': {m.SUMMARY} ({m.Params.__module__}.{m.Params.__name__}; SI, angles "
             f"in rad). {m.DEFAULTS}", bearing_rows(name))
            for name, m in _models.MODELS.items()]
    out += [
        ("[[defects]]", "Local bearing defects, paper Eqs. (14)-(15): axlebox.bearing.defects.Defect "
                        "(SI). The vehicle config places each on a bearing (wheelset, side) and "
                        "gives its angle in degrees (angle_deg); the rig config takes the Defect "
                        "fields as they are (angle in rad).", defect_rows()),
        ("[[wheel_defects]]", "Wheel tread defects, each a radius deviation turning with its wheel "
                              "(vehicle config; axlebox.mbs.config.WHEEL_DEFECT).",
         wheel_defect_rows()),
        ("[rig]", "The standalone bearing rig's config (configs/study_rig.toml; "
                  "axlebox.bearing.rig.RigConfig, SI): sections [rig], [bearing] and [[defects]]. "
                  "Defaults: F_r the carbody (rated load) and a frame on a bogie's four axle "
                  "boxes, the springs the car's primary suspension per axle box; m_box and the "
                  "dampers assumed.",
         rig_rows()),
        ("[sweep]", "The study matrix of axlebox sweep (pipelines/sweep.py), in a rig or vehicle "
                    "config; the command's options override it.", sweep_rows()),
    ]
    return out


HEADER = ("field", "type", "default", "unit", "allowed", "meaning")


def _cell(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ").strip()


def reference_markdown() -> str:
    """The config reference as MyST Markdown: a ``#`` title, one ``##`` section per config table,
    each a table of field, type, default, unit, allowed values and meaning."""
    lines = ["# Config reference", "",
             "Every field of the configs, generated from `axlebox.mbs.config.SCHEMA` (and, for the "
             "free-form tables, from the dataclasses and constants that check them): defaults and "
             "ranges are the code's own. SI units, except the fields named in other units "
             "(`speed_kmh` in km/h, `*_deg` in degrees, `amplitudes_um` in µm, `widths_mm` in mm). "
             "Unit `-`: dimensionless. A range `lo … hi` includes both ends.", ""]
    for heading, note, rows in sections():
        lines += [f"## {heading}", "", note, "",
                  "| " + " | ".join(HEADER) + " |", "|" + "---|" * len(HEADER)]
        for name, *rest in rows:
            lines.append("| " + " | ".join(_cell(c) for c in (f"`{name}`", *rest)) + " |")
        lines.append("")
    return "\n".join(lines)
