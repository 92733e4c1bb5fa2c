"""The bearing models: the one place that knows their list, and the one point where the kernels
pick a model's parts.

A model is a module (:mod:`.dtrb`) that declares, once: ``NAME``; its parameters ``Params`` (a
frozen dataclass with the shared fields the parts read: rollers, pitch, cage, masses,
friction, damping, ``model`` the scheme); how it packs them (``pack``) and its nominal state;
its rollers' contacts with the rings (``contacts``, numba); its first guess of the static
state (``guess``); its fault orders and bore (``orders``, ``BORE``); the steps its dynamic
scheme accepts by method (``DT_MAX``); and its rings' tangent stiffness (``ring_stiffness``).
Everything else is shared: the pockets, the rollers' and cages' dynamics, the implicit kick,
the quasi-dynamic scheme, the exchange window, the static start, the rig and the car.

Inside numba a bearing is named by a *tag* (:func:`tag`): an empty named tuple of a class of
its own for each model and scheme (:data:`TAGS`; flat and empty, so that numba's parallel
loops take it as they take a number).  :func:`contacts` (here) and bearing/advance.py's
``substep`` (by :func:`scheme_of`) are compiled for the tags' classes alone, so a run compiles
the model and scheme it uses and no other, and numba's cache keeps each apart.
"""
from __future__ import annotations

import dataclasses
from collections import namedtuple

from numba.extending import overload

from axlebox._params import ParameterError
from axlebox._params import from_table as _table

from . import dcrb, dtrb

#: the models by the name ``[bearing] type`` gives them
MODELS = {"dtrb": dtrb, "dcrb": dcrb}
DEFAULT = "dtrb"
SCHEMES = ("dynamic", "quasi-dynamic")      # a model's ``model`` field

# the tags' classes, one a model and scheme (module attributes, so numba's cache can pickle them)
DtrbDynamic = namedtuple("DtrbDynamic", [])
DtrbQuasiDynamic = namedtuple("DtrbQuasiDynamic", [])
DcrbDynamic = namedtuple("DcrbDynamic", [])
DcrbQuasiDynamic = namedtuple("DcrbQuasiDynamic", [])
TAGS = {("dtrb", "dynamic"): DtrbDynamic, ("dtrb", "quasi-dynamic"): DtrbQuasiDynamic,
        ("dcrb", "dynamic"): DcrbDynamic, ("dcrb", "quasi-dynamic"): DcrbQuasiDynamic}
_MODEL_OF = {cls: MODELS[name] for (name, _), cls in TAGS.items()}
_SCHEME_OF = {cls: scheme for (_, scheme), cls in TAGS.items()}
_QD_METHODS = ("leapfrog", "imex", "imex2")       # the quasi-dynamic step whatever the method


def module(p):
    """The model module of parameters ``p``."""
    for m in MODELS.values():
        if type(p) is m.Params:
            return m
    raise ParameterError(f"bearing = {p!r} is not allowed: expected the parameters of one of "
                         f"{', '.join(MODELS)}")


def name(p) -> str:
    return module(p).NAME


def tag(p):
    """The kernels' tag of parameters ``p``: its model's and scheme's."""
    return TAGS[(name(p), p.model)]()


def scheme_of(tag_class) -> str:
    """The scheme (``"dynamic"`` or ``"quasi-dynamic"``) of a tag's class."""
    return _SCHEME_OF[tag_class]


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
    m = module(p)
    if p.model == "quasi-dynamic":
        from .quasidynamic import DT_MAX
        return {k: DT_MAX for k in _QD_METHODS}
    return dict(m.DT_MAX)


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
    from .layout import n_state as n
    return n(p.Z)


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


# --- numba: the one point where a kernel picks a model's parts ----------------------------------------
def contacts(model, rec, Q, blk, cblk, flag, jk, j, k, fr, rings, psi, P, D, n_inner, n_roller, want,
             h_k):
    """A roller's contacts with the rings in the bearing model of tag ``model`` (numba only:
    the model's own ``contacts``)."""
    raise NotImplementedError("bearing.models.contacts runs in numba only")


@overload(contacts, jit_options={"cache": True, "error_model": "numpy"}, inline="always")
def _contacts(model, rec, Q, blk, cblk, flag, jk, j, k, fr, rings, psi, P, D, n_inner, n_roller, want,
              h_k):
    f = _MODEL_OF[model.instance_class].contacts

    def impl(model, rec, Q, blk, cblk, flag, jk, j, k, fr, rings, psi, P, D, n_inner, n_roller, want,
             h_k):
        f(rec, Q, blk, cblk, flag, jk, j, k, fr, rings, psi, P, D, n_inner, n_roller, want, h_k)
    return impl
