"""The bearing models: the one place that knows their list (Python; the kernels pick a model's
parts through bearing/kernel/dispatch.py, which reads this list).

A model is a module (:mod:`.dtrb`) that declares, once: ``NAME``, ``SUMMARY``, ``DEFAULTS``;
its parameters ``Params`` (a frozen dataclass on :class:`.params.RollerBearing`, whose fields
and properties are what the shared parts read: rollers, pitch, cage, masses, friction, damping,
the contact angles ``alpha_*``, ``clearance_n``, ``L_e``, ``D_o``, ``D_i``, ``model`` the
scheme); how it packs them (``pack``) and its nominal state; its rollers' contacts with the
rings (``contacts``, numba); its first guess of the static state (``guess``); its fault orders
and bore (``orders``, ``BORE``); the largest step of each scheme by method (``DT_MAX``, keyed
by :data:`SCHEMES`); and its rings' tangent stiffness (``ring_stiffness``).  Everything else is
shared: the pockets, the rollers' and cages' dynamics, the implicit kick, the quasi-dynamic
scheme, the exchange window, the static start, the rig and the car.

The module's part is :data:`CONTRACT` (each name with its kind and a line on what it is), checked
for every model when this registry is imported (:func:`check`: a model that lacks a name, or
gives it of the wrong kind, is refused naming both); the parameters' part is
:class:`.params.RollerBearing`'s fields and the properties it declares for each model to give
(:data:`.params.GIVEN_BY_MODEL`).  tests/test_bearing_models.py checks that what the shared
parts read from a model or its parameters is declared in one of the two.
"""
from __future__ import annotations

import dataclasses
import math
from typing import NamedTuple

from axlebox._params import ParameterError
from axlebox._params import from_table as _table

from ..kernel import layout
from . import crb, dcrb, dtrb
from .params import GIVEN_BY_MODEL, SCHEMES, RollerBearing

DEFAULT = "dtrb"
# SCHEMES (params.py): a model's ``model`` field's choices, and its DT_MAX's keys


class Part(NamedTuple):
    """One name a model module declares: its ``kind`` (``"str"``, ``"number"``, ``"dict"``,
    ``"class"``, ``"callable"``) and what it is."""

    name: str
    kind: str
    doc: str


#: what a model module declares, each once (:func:`check`)
CONTRACT = (
    Part("NAME", "str", "the model's name, the [bearing] type that picks it (its key in MODELS)"),
    Part("SUMMARY", "str", "one line on what the model is (the config reference, the catalogue)"),
    Part("DEFAULTS", "str", "one line on where its parameters' defaults come from"),
    Part("BORE", "number", "its bore in m (the SPM level, Eq. 17; the catalogue)"),
    Part("DT_MAX", "dict", "the largest step in s of each method, a dict for each scheme of SCHEMES"),
    Part("Params", "class", "its parameters: a frozen dataclass on params.RollerBearing"),
    Part("pack", "callable", "pack(p, gravity): the kernels' parameter vector of p (1-D floats)"),
    Part("nominal_state", "callable", "nominal_state(p, omega_w): the rollers and cages rolling "
                                      "without slip (kernel/layout.py's state)"),
    Part("contacts", "callable", "a roller's contacts with the rings (numba; kernel/dispatch.py)"),
    Part("guess", "callable", "guess(p, F_outer): the static start's first guess "
                              "(statics/equilibrium.py)"),
    Part("orders", "callable", "orders(p): its fault orders (frequencies.FaultOrders)"),
    Part("ring_stiffness", "callable", "ring_stiffness(p, F): the rings' tangent stiffness (3,) in "
                                       "N/m at the load F (mbs/kernel/exchange.py)"),
)


class ModelError(TypeError):
    """A model module that does not keep :data:`CONTRACT`."""


def _kind_ok(kind: str, v) -> bool:
    if kind == "str":
        return isinstance(v, str) and bool(v.strip())
    if kind == "number":
        return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v > 0
    if kind == "dict":
        return isinstance(v, dict)
    if kind == "class":
        return isinstance(v, type) and issubclass(v, RollerBearing) and dataclasses.is_dataclass(v)
    return callable(v)


_EXPECTED = {"str": "a non-empty string", "number": "a number > 0", "dict": "a dict",
             "class": "a dataclass on params.RollerBearing", "callable": "a function"}


def check(m, key: str | None = None):
    """``m`` if the model module keeps :data:`CONTRACT` (under the name ``key`` in
    :data:`MODELS`, when given), else a :class:`ModelError` naming the model and what it lacks."""
    who = f"bearing model {key or getattr(m, 'NAME', '?')!r} ({getattr(m, '__name__', m)!r})"
    for part in CONTRACT:
        if not hasattr(m, part.name):
            raise ModelError(f"{who} does not declare {part.name}: {part.doc}")
        v = getattr(m, part.name)
        if not _kind_ok(part.kind, v):
            raise ModelError(f"{who}: {part.name} = {v!r} is not allowed: expected "
                             f"{_EXPECTED[part.kind]} ({part.doc})")
    if key is not None and m.NAME != key:
        raise ModelError(f"{who}: NAME = {m.NAME!r} is not allowed: expected {key!r}, its name in "
                         "MODELS")
    if set(m.DT_MAX) != set(SCHEMES):
        raise ModelError(f"{who}: DT_MAX's keys {tuple(m.DT_MAX)!r} are not allowed: expected "
                         f"{', '.join(SCHEMES)}, the schemes")
    for scheme, steps in m.DT_MAX.items():
        if not isinstance(steps, dict) or not steps or not all(
                isinstance(k, str) and _kind_ok("number", v) for k, v in steps.items()):
            raise ModelError(f"{who}: DT_MAX[{scheme!r}] = {steps!r} is not allowed: expected a "
                             "dict of each method's name and its largest step (s, > 0)")
    p = m.Params()
    for name in GIVEN_BY_MODEL:
        try:
            v = getattr(p, name)
        except NotImplementedError as err:
            raise ModelError(f"{who}: {err}") from None
        if not (isinstance(v, (int, float)) and math.isfinite(v)):
            raise ModelError(f"{who}: {m.Params.__name__}().{name} = {v!r} is not allowed: "
                             "expected a number")
    if isinstance(p.rows, bool) or not isinstance(p.rows, int) or p.rows < 1:
        raise ModelError(f"{who}: {m.Params.__name__}().rows = {p.rows!r} is not allowed: expected "
                         "an integer >= 1")
    return m


#: the models by the name ``[bearing] type`` gives them, each checked against :data:`CONTRACT`
MODELS = {name: check(m, name) for name, m in (("dtrb", dtrb), ("dcrb", dcrb), ("crb", crb))}


def module(p):
    """The model module of parameters ``p``."""
    for m in MODELS.values():
        if type(p) is m.Params:
            return m
    raise ParameterError(f"bearing = {p!r} is not allowed: expected the parameters of one of "
                         f"{', '.join(MODELS)}")


def name(p) -> str:
    return module(p).NAME


def from_table(fields, where: str = "bearing"):
    """The parameters of a ``[bearing]`` table: ``type`` (default ``"dtrb"``) names the model,
    the other keys its ``Params`` fields; a refusal names ``where.key``."""
    if not isinstance(fields, dict):
        raise ParameterError(f"{where} = {fields!r} is not allowed: expected a [{where}] table")
    fields = dict(fields)
    kind = fields.pop("type", DEFAULT)
    if kind not in MODELS:
        raise ParameterError(f"{where}.type = {kind!r} is not allowed: expected one of "
                             f"{', '.join(MODELS)}")
    return _table(MODELS[kind].Params, fields, where)


def to_table(p) -> dict:
    """``p`` as a ``[bearing]`` table (:func:`from_table` reads it back)."""
    return {"type": name(p), **dataclasses.asdict(p)}


def methods(p) -> dict:
    """The methods the bearing of parameters ``p`` steps by, and the largest step of each (s)."""
    return dict(module(p).DT_MAX[p.model])


def check_step(p, method: str, dt: float, method_field: str = "method", dt_field: str = "dt") -> None:
    """Refuse a method or step the bearing of parameters ``p`` does not accept, naming the
    field, the value and what is allowed."""
    allowed = methods(p)
    what = f"the {'quasi-dynamic ' if p.model == 'quasi-dynamic' else ''}{name(p).upper()} bearing"
    if method not in allowed:
        raise ParameterError(f"{method_field} = {method!r} is not allowed with {what}: expected one "
                             f"of {', '.join(allowed)}")
    if dt > allowed[method]:
        why = "its accuracy" if p.model == "quasi-dynamic" else "the roller contacts"
        raise ParameterError(f"{dt_field} = {dt:g} is not allowed with {what} and method "
                             f"{method!r}: expected at most {allowed[method]:g} s ({why})")


def pack(p, gravity=(0.0, 0.0, -9.81)):
    return module(p).pack(p, gravity)


def n_state(p) -> int:
    return layout.n_state(p.Z, p.rows)


def nominal_state(p, omega_w: float = 0.0):
    return module(p).nominal_state(p, omega_w)


def orders(p):
    """The fault orders (multiples of the shaft speed) of the bearing of parameters ``p``."""
    return module(p).orders(p)


def bore(p) -> float:
    return module(p).BORE


def ring_stiffness(p, F):
    """The bearing's tangent stiffness (3,) along x, y, z (N/m) at the load ``F`` (N, on the
    outer ring): the interface Jacobian of a co-simulation's "jacobian" hold (mbs/kernel/exchange.py)."""
    return module(p).ring_stiffness(p, F)
