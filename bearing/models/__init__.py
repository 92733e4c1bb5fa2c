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
scheme, the exchange window, the static start, the rig and the car.  tests/test_bearing_models.py
checks every model against this contract.
"""
from __future__ import annotations

import dataclasses

from axlebox._params import ParameterError
from axlebox._params import from_table as _table

from ..kernel import layout
from . import dcrb, dtrb

#: the models by the name ``[bearing] type`` gives them
MODELS = {"dtrb": dtrb, "dcrb": dcrb}
DEFAULT = "dtrb"
SCHEMES = ("dynamic", "quasi-dynamic")      # a model's ``model`` field, and its DT_MAX's keys


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
    return layout.n_state(p.Z)


def nominal_state(p, omega_w: float = 0.0):
    return module(p).nominal_state(p, omega_w)


def orders(p):
    """The fault orders (multiples of the shaft speed) of the bearing of parameters ``p``."""
    return module(p).orders(p)


def bore(p) -> float:
    return module(p).BORE


def ring_stiffness(p, F):
    """The bearing's tangent stiffness (3,) along x, y, z (N/m) at the load ``F`` (N, on the
    outer ring): the interface Jacobian of a co-simulation's "jacobian" hold (mbs/exchange.py)."""
    return module(p).ring_stiffness(p, F)
