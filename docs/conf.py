"""Sphinx configuration of the sunwind documentation site.

Build it with ``sphinx-build -W --keep-going -b html docs <out>`` (what ``tests/test_docs.py`` runs): every
warning is an error. The site is Markdown (MyST) and reST; the API pages are written from
``sunwind._PUBLIC`` by ``_ext/sunwind_api.py``, the validation and performance tables are rendered from
``_data/*.json`` by ``_ext/sunwind_artefacts.py``, and the gallery runs ``examples/plot_*.py``.
Nothing here fetches anything from the network.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # the gallery's scripts draw off-screen

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
os.environ.setdefault("MPLBACKEND", "Agg")

import sunwind  # noqa: E402  (after the backend is chosen)

# -- project ----------------------------------------------------------------------------------------------

project = "sunwind"
author = "the sunwind authors"
copyright = "the sunwind authors"
release = sunwind.__version__
version = ".".join(release.split(".")[:2])

# -- extensions -------------------------------------------------------------------------------------------

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "numpydoc",
    "sphinx.ext.mathjax",
    "sphinx_click",
    "sphinx_gallery.gen_gallery",
    "sunwind_cli",  # _ext/: click's help texts kept plain text in the CLI reference
    "sunwind_api",  # _ext/: the API pages from sunwind._PUBLIC and the subpackages' __all__
    "sunwind_artefacts",  # _ext/: the validation and benchmark tables from _data/*.json
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = [
    "_build",
    "Thumbs.db",
    ".DS_Store",
    "_data/README.md",  # the artefacts' own note, not a page
    "examples/**",  # the gallery's sources; sphinx-gallery writes the pages under gallery/
]
templates_path: list[str] = []
nitpicky = False
# `text` in a docstring or a click help string is code (as in Markdown), not italics
default_role = "literal"
# quotes and ellipses only: "--flag" in the CLI reference and docstrings stays two hyphens, not a dash
smartquotes_action = "qe"

# -- MyST -------------------------------------------------------------------------------------------------

myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
myst_dmath_double_inline = True

# -- autodoc, autosummary, numpydoc -----------------------------------------------------------------------

autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"member-order": "bysource"}
autodoc_typehints = "none"  # numpydoc's Parameters sections carry the types; signatures stay short
autodoc_preserve_defaults = False  # True would print some defaults as source the signature parser refuses
numpydoc_show_class_members = False  # autodoc's :members: lists them; numpydoc's tables would repeat them
numpydoc_show_inherited_class_members = False
numpydoc_class_members_toctree = False
numpydoc_attributes_as_param_list = True
numpydoc_xref_param_type = False

# -- sphinx-gallery ---------------------------------------------------------------------------------------

sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "gallery",
    "filename_pattern": r"plot_",
    "download_all_examples": False,
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
    "reset_modules": ("matplotlib",),
    "remove_config_comments": True,
    "plot_gallery": "True",
    "within_subsection_order": "FileNameSortKey",
    "write_computation_times": False,  # no sg_execution_times pages in the source tree
}

# -- HTML -------------------------------------------------------------------------------------------------

html_theme = "pydata_sphinx_theme"
html_title = f"sunwind {release}"
html_static_path = ["_static"]
html_show_sourcelink = False
html_theme_options = {
    "navbar_align": "left",
    "show_toc_level": 2,
    "navigation_with_keys": False,
    "use_edit_page_button": False,
    "icon_links": [],
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version"],
}
html_context = {"default_mode": "light"}
# single pages with no children: no empty section navigation beside them
html_sidebars = {page: [] for page in ("index", "cli", "method", "validation", "performance")}
