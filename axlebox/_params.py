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


def check_ranges(obj) -> None:
    """Refuse any field whose value is not finite or lies outside its range, or is not one of
    its choices."""
    name = type(obj).__name__
    for f in dataclasses.fields(obj):
        value = getattr(obj, f.name)
        options = f.metadata.get("choices")
        if options is not None and (not isinstance(value, str) or value not in options):
            raise ParameterError(f"{name}.{f.name} = {value!r} is not allowed: expected one of "
                                 f"{', '.join(options)}")
        rng = f.metadata.get("range")
        if rng is None:
            continue
        lo, hi = rng
        unit = f.metadata.get("unit", "")
        if isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not math.isfinite(value) or not lo <= value <= hi:
            raise ParameterError(
                f"{name}.{f.name} = {value!r} is not allowed: "
                f"expected a number in [{lo:g}, {hi:g}] {unit}".rstrip())


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
    try:
        return cls(**fields, **objects)
    except TypeError as err:
        raise ParameterError(f"[{where}] {fields!r} is not allowed: {err}") from None


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
