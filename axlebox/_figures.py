"""Figures by matplotlib's object API (``matplotlib.figure.Figure``), for every plot the package
draws.  Why: ``matplotlib.use`` in a library function switches its caller's backend (a notebook's
inline one, a desktop's window), and pyplot's figures stay registered until closed; a bare
``Figure`` needs no backend to be drawn or saved (``savefig`` picks the canvas from the file's
format) and goes when its last reference does.  A caller who wants a window shows the returned
figure with their own pyplot."""
from __future__ import annotations

from matplotlib.figure import Figure

_FIGURE = ("figsize", "dpi", "constrained_layout", "layout", "facecolor")


def figure(**kw) -> Figure:
    """A ``Figure`` of ``figsize``, ``dpi``, ``constrained_layout``/``layout``, ``facecolor``."""
    return Figure(**kw)


def subplots(nrows: int = 1, ncols: int = 1, **kw):
    """``(fig, axes)`` as ``pyplot.subplots`` gives them, without pyplot: the keywords of
    :func:`figure` go to the figure, the rest (``sharex``, ``squeeze``, ``height_ratios``...)
    to ``Figure.subplots``."""
    fig = Figure(**{k: kw.pop(k) for k in _FIGURE if k in kw})
    return fig, fig.subplots(nrows, ncols, **kw)
