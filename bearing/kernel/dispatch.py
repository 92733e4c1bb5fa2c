"""Where a kernel picks a model's parts (numba): the models' *tags* and the overload of a
roller's contacts with the rings.

Inside numba a bearing is named by a tag (:func:`tag`): an empty named tuple of a class of its
own for each contact law and scheme (:data:`TAGS`, built from bearing/models/__init__.py's
``MODELS`` and ``SCHEMES``; flat and empty, so that numba's parallel loops take it as they take
a number).  :func:`contacts` (here) and bearing/kernel/advance.py's ``substep`` (by
:func:`scheme_of`) are compiled for the tags' classes alone, so a run compiles the model and
scheme it uses and no other, and numba's cache keeps each apart.
"""
from __future__ import annotations

from collections import namedtuple

from numba.extending import overload

from ..models import MODELS, SCHEMES
from ..models import name as _name


def _class_name(model: str, scheme: str) -> str:
    return "".join(w.capitalize() for w in f"{model} {scheme}".replace("-", " ").split())


#: ``(model, scheme) -> tag class``: one class for each contact law (a model's ``contacts``) and
#: scheme, named by the first model that declares the law (``DtrbDynamic`` ...), so that models
#: that differ only in their numbers (the single-row CRB and the DCRB: the rows are a parameter
#: slot) share their machine code; each class is a module attribute, so that numba's cache can
#: pickle it
TAGS = {}
_BY_LAW = {}
for _model, _module in MODELS.items():
    for _scheme in SCHEMES:
        _law = (_module.contacts, _scheme)
        if _law not in _BY_LAW:
            _cls = namedtuple(_class_name(_model, _scheme), [])
            _cls.__module__ = __name__
            globals()[_cls.__name__] = _cls
            _BY_LAW[_law] = _cls
        TAGS[(_model, _scheme)] = _BY_LAW[_law]
_CONTACTS_OF = {cls: law for (law, _), cls in _BY_LAW.items()}
_SCHEME_OF = {cls: s for (_, s), cls in _BY_LAW.items()}


def tag(p):
    """The kernels' tag of parameters ``p``: its model's and scheme's."""
    return TAGS[(_name(p), p.model)]()


def scheme_of(tag_class) -> str:
    """The scheme (``"dynamic"`` or ``"quasi-dynamic"``) of a tag's class."""
    return _SCHEME_OF[tag_class]


def contacts(model, ct, Q, j, k, fr, rings, psi, P, D, n_inner, n_roller, want, h_k):
    """A roller's contacts with the rings in the bearing model of tag ``model`` (numba only:
    the model's own ``contacts``)."""
    raise NotImplementedError("bearing.kernel.dispatch.contacts runs in numba only")


@overload(contacts, jit_options={"cache": True, "error_model": "numpy"}, inline="always")
def _contacts(model, ct, Q, j, k, fr, rings, psi, P, D, n_inner, n_roller, want, h_k):
    f = _CONTACTS_OF[model.instance_class]

    def impl(model, ct, Q, j, k, fr, rings, psi, P, D, n_inner, n_roller, want, h_k):
        f(ct, Q, j, k, fr, rings, psi, P, D, n_inner, n_roller, want, h_k)
    return impl
