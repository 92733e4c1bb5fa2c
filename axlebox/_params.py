"""Validated, frozen parameter dataclasses.

Every parameter field carries its allowed range in ``metadata`` so that a bad
value is refused with a message naming the field, the value and the range.
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import math


class ParameterError(ValueError):
    """A parameter is outside what the model allows (exit status 2 on the CLI)."""


def param(default: float, lo: float, hi: float, unit: str = "m", doc: str = ""):
    """A dataclass field with an inclusive allowed range ``[lo, hi]``."""
    return dataclasses.field(default=default,
                             metadata={"range": (lo, hi), "unit": unit, "doc": doc})


def choice(default: str, choices, doc: str = ""):
    """A dataclass field that takes one of ``choices`` (strings), declared once with them."""
    return dataclasses.field(default=default, metadata={"choices": tuple(choices), "doc": doc})


def flag(default: bool, doc: str = ""):
    """A true/false dataclass field."""
    return dataclasses.field(default=default, metadata={"flag": True, "doc": doc})


def text(default: str, doc: str = ""):
    """A dataclass field that takes any string (a name, a path)."""
    return dataclasses.field(default=default, metadata={"text": True, "doc": doc})


def vector(default, lo: float, hi: float, unit: str = "", doc: str = ""):
    """A dataclass field of ``len(default)`` numbers, each in ``[lo, hi]`` (a tuple)."""
    return dataclasses.field(default=tuple(float(v) for v in default),
                             metadata={"range": (lo, hi), "length": len(default), "unit": unit,
                                       "doc": doc})


def numbers(default, lo: float, hi: float, unit: str = "", doc: str = ""):
    """A dataclass field of any number of numbers, each in ``[lo, hi]`` (a tuple)."""
    return dataclasses.field(default=tuple(float(v) for v in default),
                             metadata={"range": (lo, hi), "numbers": True, "unit": unit, "doc": doc})


def rows(default, columns, doc: str = ""):
    """A dataclass field of a table: any number of rows (a tuple of tuples), each with one number
    a column; ``columns``: ``(name, lo, hi, unit)`` for each, its range inclusive."""
    return dataclasses.field(default=tuple(tuple(float(v) for v in r) for r in default),
                             metadata={"rows": tuple(columns), "doc": doc})


def members(default, allowed, doc: str = "", at_least: int = 1):
    """A dataclass field of distinct items of ``allowed`` (names or numbers), ``at_least`` of
    them (a tuple)."""
    return dataclasses.field(default=tuple(default), metadata={"members": tuple(allowed),
                                                               "at_least": at_least, "doc": doc})


def like(cls, name: str, doc: str | None = None):
    """The field ``name`` of dataclass ``cls`` again: its default, range or choices and unit
    (declared there, once), with ``doc`` saying what it means here."""
    f = next(f for f in dataclasses.fields(cls) if f.name == name)
    md = dict(f.metadata)
    if doc is not None:
        md["doc"] = doc
    return dataclasses.field(default=f.default, metadata=md)


def section(name: str):
    """A config section ``[name]``: a frozen dataclass whose fields are checked on construction
    (:func:`check_ranges`, refusals naming ``name.field``)."""
    def wrap(cls):
        cls.SECTION = name
        if "__post_init__" not in cls.__dict__:
            cls.__post_init__ = check_ranges
        return dataclasses.dataclass(frozen=True)(cls)
    return wrap


def _label(obj) -> str:
    return getattr(obj, "SECTION", type(obj).__name__)


def _is_number(v) -> bool:
    return not isinstance(v, bool) and isinstance(v, (int, float)) and math.isfinite(v)


def _check_field(where: str, f, value) -> None:
    """Refuse ``value`` of field ``f`` unless its declaration allows it."""
    md = f.metadata
    if "choices" in md:
        if not isinstance(value, str) or value not in md["choices"]:
            raise ParameterError(f"{where} = {value!r} is not allowed: expected one of "
                                 f"{', '.join(md['choices'])}")
    elif "flag" in md:
        if not isinstance(value, bool):
            raise ParameterError(f"{where} = {value!r} is not allowed: expected true or false")
    elif "text" in md:
        if not isinstance(value, str):
            raise ParameterError(f"{where} = {value!r} is not allowed: expected a string")
    elif "members" in md:
        allowed = md["members"]
        n = md["at_least"]
        if (not isinstance(value, tuple) or len(value) < n
                or not all(type(v) is type(allowed[0]) and v in allowed for v in value)
                or len(set(value)) != len(value)):
            raise ParameterError(f"{where} = {list(value) if isinstance(value, tuple) else value!r} "
                                 "is not allowed: expected distinct items of "
                                 f"{', '.join(map(str, allowed))}" + (f", at least {n}" if n else ""))
    elif "rows" in md:
        cols = md["rows"]
        heads = ", ".join(f"{n} in [{lo:g}, {hi:g}] {u}".rstrip() for n, lo, hi, u in cols)
        if not isinstance(value, tuple):
            raise ParameterError(f"{where} = {value!r} is not allowed: expected rows of ({heads})")
        for i, r in enumerate(value):
            if (not isinstance(r, tuple) or len(r) != len(cols)
                    or not all(_is_number(v) and lo <= v <= hi for v, (_, lo, hi, _) in zip(r, cols))):
                raise ParameterError(f"{where}[{i}] = {list(r) if isinstance(r, tuple) else r!r} is "
                                     f"not allowed: expected ({heads})")
    elif "range" in md:
        lo, hi = md["range"]
        unit = md.get("unit", "")
        if "length" in md or "numbers" in md:
            n = md.get("length")
            if (not isinstance(value, tuple) or (n is not None and len(value) != n)
                    or not all(_is_number(v) and lo <= v <= hi for v in value)):
                count = f"{n} numbers" if n is not None else "a list of numbers"
                raise ParameterError(f"{where} = {list(value) if isinstance(value, tuple) else value!r}"
                                     f" is not allowed: expected {count} in [{lo:g}, {hi:g}] {unit}"
                                     .rstrip())
            return
        integer = f.type in ("int", int)
        if not _is_number(value) or not lo <= value <= hi or (integer and not isinstance(value, int)):
            what = "an integer" if integer else "a number"
            raise ParameterError(f"{where} = {value!r} is not allowed: expected {what} in "
                                 f"[{lo:g}, {hi:g}] {unit}".rstrip())


def check_ranges(obj) -> None:
    """Refuse any field whose value its declaration does not allow (a number outside its range
    or not finite, a string not among its choices, ...), naming ``section.field`` (or
    ``Class.field``), the value and what is allowed."""
    name = _label(obj)
    for f in dataclasses.fields(obj):
        _check_field(f"{name}.{f.name}", f, getattr(obj, f.name))


def _coerce(f, value):
    """A value as read from a file (TOML) in its field's Python form: a list as a tuple, an
    integer as a float where the field is a float."""
    if isinstance(value, list) and "rows" in f.metadata:
        return tuple(tuple(float(v) if _is_number(v) else v for v in r) if isinstance(r, list) else r
                     for r in value)
    if isinstance(value, list):
        return tuple(float(v) if ("length" in f.metadata or "numbers" in f.metadata) and _is_number(v)
                     else v for v in value)
    if f.type in ("float", float) and isinstance(value, int) and not isinstance(value, bool):
        return float(value)
    return value


def from_table(cls, fields, where: str, **objects):
    """``cls(**fields, **objects)`` from a config table ``[where]``: a table that is not one, an
    unknown key or a value the dataclass refuses is a :class:`ParameterError` naming
    ``where.key``, the value and what is allowed (never a TypeError from the constructor)."""
    if not isinstance(fields, dict):
        raise ParameterError(f"{where} = {fields!r} is not allowed: expected a [{where}] table")
    known = [f.name for f in dataclasses.fields(cls) if f.name not in objects]
    for k in fields:
        if k not in known:
            raise ParameterError(f"{where}.{k} is not a field of [{where}]: expected one of "
                                 f"{', '.join(known)}")
    types = {f.name: f for f in dataclasses.fields(cls)}
    fields = {k: _coerce(types[k], v) for k, v in fields.items()}
    try:
        return cls(**fields, **objects)
    except TypeError as err:
        raise ParameterError(f"[{where}] {fields!r} is not allowed: {err}") from None


def kinded_from_table(cls, d, where: str, kind_fields: dict, noun: str):
    """An entry of a list of tables (``[[cls.SECTION]]``) whose ``kind`` decides the fields it
    takes (``kind_fields``: kind -> its fields; a missing kind is the field's default), from the
    table ``d`` at ``where`` (``section[i]``): a kind not known or a field its kind does not take
    is refused naming ``where.key`` and what is allowed (``noun``: what an entry is, "wheel
    defect"), and so is any value the dataclass refuses."""
    if not isinstance(d, dict):
        raise ParameterError(f"{where} = {d!r} is not allowed: expected a [[{cls.SECTION}]] table")
    kind = d.get("kind", next(f.default for f in dataclasses.fields(cls) if f.name == "kind"))
    if kind not in kind_fields:
        raise ParameterError(f"{where}.kind = {kind!r} is not allowed: expected one of "
                             f"{', '.join(kind_fields)}")
    for key in d:
        if key not in kind_fields[kind]:
            raise ParameterError(f"{where}.{key} is not a field of a {kind} {noun}: expected one of "
                                 f"{', '.join(kind_fields[kind])}")
    try:
        return from_table(cls, d, where)
    except ParameterError as err:
        raise ParameterError(str(err).replace(f"{cls.SECTION}.", f"{where}.", 1)) from None


def number(name: str, value) -> float:
    """``value`` (text or a number) as a float, or a ParameterError naming ``name``."""
    try:
        return float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} = {value!r} is not allowed: expected a number") from None


def require(cond: bool, obj, field: str, message: str) -> None:
    """Cross-field check: refuse ``obj.field`` with ``message`` unless ``cond``."""
    if not cond:
        raise ParameterError(
            f"{type(obj).__name__}.{field} = {getattr(obj, field)!r} is not allowed: {message}")


def digest(*items) -> str:
    """A stable short hash of dataclasses and plain values (mesh cache key)."""
    def plain(x):
        if dataclasses.is_dataclass(x):
            return {"__type__": type(x).__name__, **dataclasses.asdict(x)}
        return x
    text = json.dumps([plain(i) for i in items], sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:16]
