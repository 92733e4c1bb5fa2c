"""sphinx-gallery's scraper of the figures an example holds (docs/conf.py)."""
import weakref

_SHOWN = weakref.WeakSet()


def returned_figures(block, block_vars, gallery_conf):
    """The figures an example's code holds (the package draws by matplotlib's object API, which
    pyplot's scraper does not see): each new ``Figure`` among its globals saved and shown."""
    from matplotlib.figure import Figure
    from sphinx_gallery.scrapers import figure_rst
    paths = []
    for value in list(block_vars["example_globals"].values()):
        if isinstance(value, Figure) and value not in _SHOWN and value.canvas.manager is None:
            _SHOWN.add(value)
            path = next(block_vars["image_path_iterator"])
            value.savefig(path)
            paths.append(path)
    return figure_rst(paths, gallery_conf["src_dir"])
