"""The config reference: the page of every config field, generated from the declarations.

Each car config section is a dataclass of :mod:`axlebox.mbs.vehicle.config` whose fields carry their
default, range or choices, unit and one-line meaning (:mod:`axlebox._params`); the bearing
models' parameters (:data:`axlebox.bearing.models.MODELS`), the defects
(:class:`axlebox.bearing.defects.Defect`, :class:`axlebox.mbs.vehicle.config.BearingDefect`,
:class:`axlebox.mbs.vehicle.config.WheelDefect`) and the bearing rig's ``[rig]``
(:class:`axlebox.bearing.rig.RigConfig`) are declared the same way; ``[sweep]`` is
:mod:`axlebox.pipelines.sweep`'s.  Nothing about a field is written here: the page is made from
those declarations, so it cannot drift from what the loader accepts.

Units are SI strings (``"-"`` dimensionless, ``""`` for names and switches); the fields in other
units say so by name: ``speed_kmh`` (km/h), ``*_deg`` (degrees), ``amplitudes_um`` (micrometres)
and ``[sweep] widths_mm`` (millimetres).
"""
from __future__ import annotations

import dataclasses
import math

from axlebox.bearing import models as _models
from axlebox.bearing.defects import PROFILES, Defect
from axlebox.bearing.kernel.layout import KINDS

from axlebox.bearing.rig import RIG_METHODS, RIG_SECTIONS, RigConfig
from axlebox.mbs.vehicle import config as vconfig

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
    """Each model's methods and largest steps under ``scheme`` (bearing/models/__init__.py ``methods``)."""
    out = []
    for name, m in _models.MODELS.items():
        p = dataclasses.replace(m.Params(), model=scheme)
        out.append(f"{name.upper()}: " + ", ".join(f"{k} {_num(v)}" for k, v in _models.methods(p).items()))
    return "; ".join(out)


_DT_MAX = _steps("dynamic")
_QD_DT_MAX = _steps("quasi-dynamic")
#: the BearingParams fields without a ``param`` range: (choices, meaning)

#: the Defect fields without a ``param`` range: (choices, meaning)
DEFECT_CHOICES: dict[str, tuple[tuple, str]] = {
    "kind": (tuple(KINDS), "'outer' (on the cup), 'inner' (on the cone, turning with the shaft) "
                           "or 'roller' (on one roller, turning with its spin)"),
    "profile": (PROFILES, "'half-sine' (Eq. 14) or 'edges' (the roller's path over the pit's "
                          "edges; ring defects only)"),
}

#: the car sections' constraints beyond each field's range (the bearing models' steps)
CAR_CONSTRAINTS: dict[str, dict[str, str]] = {
    "integrator": {"method": f"with bearings, the methods and largest dt: {_DT_MAX}; quasi-dynamic: "
                             f"{_QD_DT_MAX}"},
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


def _type(f) -> str:
    md, typ = f.metadata, str(f.type)
    if "length" in md:
        return f"list of {md['length']} float"
    if "numbers" in md:
        return "list of float"
    if "rows" in md:
        return f"list of [{', '.join(c[0] for c in md['rows'])}]"
    if "members" in md:
        return f"list of {type(md['members'][0]).__name__}"
    return {"float": "float", "int": "int", "str": "str", "bool": "bool"}.get(typ, typ)


def _dataclass_rows(cls, choices: dict | None = None, skip=(), constraints: dict | None = None,
                    only=None) -> list[tuple]:
    """Rows of a parameter dataclass, each from its field's declaration (:mod:`axlebox._params`):
    its default, range or choices, unit and meaning; ``choices``: (choices, meaning) of string
    fields declared without them; ``only``: these fields alone."""
    rows = []
    for f in dataclasses.fields(cls):
        if f.name in skip or (only is not None and f.name not in only):
            continue
        md, typ = f.metadata, _type(f)
        doc = md.get("doc", "")
        unit = md.get("unit", "") or ("-" if "range" in md else "")
        if "range" in md:
            allowed = _range(*md["range"], unit)
            if "length" in md or "numbers" in md:
                allowed = f"{md.get('length', 'any number of')} numbers in {allowed}"
        elif f.name in (choices or {}):
            opts, doc = choices[f.name]
            allowed = _choices(opts)
        elif "choices" in md:
            allowed = _choices(md["choices"])
        elif "flag" in md:
            allowed = "`true`, `false`"
        elif "text" in md:
            allowed = "any string"
        elif "rows" in md:
            allowed = "rows of " + ", ".join(f"{n} in {_range(lo, hi)} {u}".rstrip()
                                             for n, lo, hi, u in md["rows"])
        elif "members" in md:
            allowed = (f"distinct, at least {md['at_least']}, of " if md["at_least"] else "distinct, of ") \
                + _choices(md["members"])
        else:
            unit, allowed = ("-" if typ in ("int", "float") else ""), ""
        extra = (constraints or {}).get(f.name)
        allowed = "; ".join(x for x in (allowed, extra) if x)
        default = f.default if f.default is not dataclasses.MISSING else f.default_factory()
        rows.append((f.name, typ, _default(default, unit), unit, allowed, doc))
    return rows


# ---- the sections ------------------------------------------------------------------------------

def bearing_rows(model: str = _models.DEFAULT) -> list[tuple]:
    """``[bearing]`` of ``model``: ``type``, then every field of its parameters."""
    m = _models.MODELS[model]
    rows = _dataclass_rows(m.Params, {})
    kind = ("type", "str", _default(_models.DEFAULT), "", _choices(tuple(_models.MODELS)),
            "the bearing model (bearing/models/__init__.py): " + "; ".join(
                f"'{n}' {mm.SUMMARY}" for n, mm in _models.MODELS.items()))
    return [kind] + [r for r in rows if r[0] != "type"]


def defect_rows() -> list[tuple]:
    """``[[defects]]``: where on the car (:class:`~axlebox.mbs.vehicle.config.BearingDefect`), then the
    Defect's fields (the car's angle in degrees, angle_deg; the rig's in rad, angle)."""
    place = _dataclass_rows(vconfig.BearingDefect, skip=("shape", "angle_deg"))
    shape = [r[:5] + ("rig only (the vehicle's is angle_deg): " + r[5],) if r[0] == "angle" else r
             for r in _dataclass_rows(Defect, DEFECT_CHOICES)]
    return place + shape + _dataclass_rows(vconfig.BearingDefect, only=("angle_deg",))


def wheel_defect_rows() -> list[tuple]:
    """``[[wheel_defects]]``: :class:`~axlebox.mbs.vehicle.config.WheelDefect`'s fields, each marked with
    the kinds that take it."""
    kinds_of = vconfig.WHEEL_DEFECT_FIELDS
    rows = []
    for r in _dataclass_rows(vconfig.WheelDefect):
        kinds = [kind for kind, names in kinds_of.items() if r[0] in names]
        if len(kinds) < len(kinds_of):
            r = r[:5] + (f"{' and '.join(kinds)} only: {r[5]}",)
        rows.append(r)
    return rows


def track_layout_rows() -> list[tuple]:
    """``[[track.layout]]``: :class:`~axlebox.mbs.track.line.Segment`'s fields, each marked with the
    kinds that take it."""
    from axlebox.mbs.track.line import KIND_FIELDS, Segment
    rows = []
    for r in _dataclass_rows(Segment):
        kinds = [kind for kind, names in KIND_FIELDS.items() if r[0] in names]
        if len(kinds) < len(KIND_FIELDS):
            r = r[:5] + (f"{' and '.join(kinds)} only: {r[5]}",)
        rows.append(r)
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
    out = [(f"[{name}]", " ".join(cls.__doc__.split()),
            _dataclass_rows(cls, constraints=CAR_CONSTRAINTS.get(name)))
           for name, cls in vconfig.SECTIONS.items()]
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
                              "(vehicle config; axlebox.mbs.vehicle.config.WheelDefect).",
         wheel_defect_rows()),
        ("[[track.layout]]", "The line the car runs on (vehicle config; "
                             "axlebox.mbs.track.line.Segment): tangents, transitions (clothoids, "
                             "curvature and cant linear from the segment before to the one after) "
                             "and circular curves with their cant and gauge widening, one after "
                             "another from chainage 0; track.start places the car on it. None: "
                             "tangent track.", track_layout_rows()),
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
             "Every field of the configs, generated from the dataclasses that declare them "
             "(`axlebox.mbs.vehicle.config`, the bearing models, the defects, the rig): defaults and "
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
