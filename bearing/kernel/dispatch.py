"""Where a kernel picks a model's parts (numba): the models' *tags* and the overload of a
roller's contacts with the rings.

Inside numba a bearing is named by a tag (:func:`tag`): an empty named tuple of a class of its
own for each model and scheme (:data:`TAGS`, built from bearing/models/__init__.py's
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


#: ``(model, scheme) -> tag class``; each class is a module attribute (``DtrbDynamic`` ...), so
#: that numba's cache can pickle it
TAGS = {}
for _model in MODELS:
    for _scheme in SCHEMES:
        _cls = namedtuple(_class_name(_model, _scheme), [])
        _cls.__module__ = __name__
        globals()[_cls.__name__] = _cls
        TAGS[(_model, _scheme)] = _cls
_MODEL_OF = {cls: MODELS[m] for (m, _), cls in TAGS.items()}
_SCHEME_OF = {cls: s for (_, s), cls in TAGS.items()}


def tag(p):
    """The kernels' tag of parameters ``p``: its model's and scheme's."""
    return TAGS[(_name(p), p.model)]()


def scheme_of(tag_class) -> str:
    """The scheme (``"dynamic"`` or ``"quasi-dynamic"``) of a tag's class."""
    return _SCHEME_OF[tag_class]


def contacts(model, rec, Q, blk, cblk, flag, jk, j, k, fr, rings, psi, P, D, n_inner, n_roller, want,
             h_k):
    """A roller's contacts with the rings in the bearing model of tag ``model`` (numba only:
    the model's own ``contacts``)."""
    raise NotImplementedError("bearing.kernel.dispatch.contacts runs in numba only")


@overload(contacts, jit_options={"cache": True, "error_model": "numpy"}, inline="always")
def _contacts(model, rec, Q, blk, cblk, flag, jk, j, k, fr, rings, psi, P, D, n_inner, n_roller, want,
              h_k):
    f = _MODEL_OF[model.instance_class].contacts

    def impl(model, rec, Q, blk, cblk, flag, jk, j, k, fr, rings, psi, P, D, n_inner, n_roller, want,
             h_k):
        f(rec, Q, blk, cblk, flag, jk, j, k, fr, rings, psi, P, D, n_inner, n_roller, want, h_k)
    return impl
