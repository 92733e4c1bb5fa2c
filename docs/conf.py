"""Sphinx configuration of axlebox's documentation site.

Build (warnings are errors; the gallery's examples run during the build):

    python3 -m pip install -e ".[docs]"
    python3 -m sphinx -W --keep-going -b html docs docs/_build/html

The config reference, the command-line reference and the API pages are generated from the code
(docs/_generate.py) before Sphinx reads the sources, so they cannot drift from it.
"""
import logging
import os
import sys
from datetime import date
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import _generate  # noqa: E402

_generate.write_all(HERE / "reference")

project = "axlebox"
author = "the axlebox developers"
copyright = f"{date.today().year}, {author}"
release = "0.1.0"

extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.mathjax", "sphinx.ext.viewcode",
              "sphinx_gallery.gen_gallery"]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3
exclude_patterns = ["_build", "examples/*", "auto_examples/*.ipynb",
                    "auto_examples/*.py", "auto_examples/*.zip", "auto_examples/*.md5",
                    "auto_examples/*.json"]
suppress_warnings = ["myst.xref_missing"] if os.environ.get("AXLEBOX_DOCS_LOOSE") else []

# the docstrings are plain prose with equation numbers, not numpydoc: shown as written
autodoc_default_options = {"members": True, "undoc-members": False, "member-order": "bysource"}
autodoc_typehints = "description"
autodoc_mock_imports = []

html_theme = "furo"
html_title = "axlebox"
html_static_path = []

# scikit-fem logs every assembly at INFO: kept out of the gallery's output
logging.getLogger("skfem").setLevel(logging.WARNING)

# pyvista renders off-screen in the gallery (no display), its scenes as pictures
os.environ.setdefault("PYVISTA_OFF_SCREEN", "true")
sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    # pyvista scenes are shown as screenshots; the package's own figures by _scrapers.py
    "image_scrapers": ("matplotlib", "_scrapers.returned_figures"),
    "remove_config_comments": True,
    "abort_on_example_error": True,
    "plot_gallery": "True",
    "within_subsection_order": "FileNameSortKey",
}
