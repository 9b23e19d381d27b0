"""Sphinx configuration of the floatmoor documentation (built in CI with warnings as errors).

Build: ``python -m sphinx -W --keep-going -b html docs OUT`` (``tests/test_docs.py`` does it).
The pages are MyST Markdown; the API reference is autodoc on numpy-style docstrings; the
examples gallery (``examples/plot_*.py``) is run by sphinx-gallery during the build.
"""

from __future__ import annotations

import floatmoor

project = "floatmoor"
author = "the floatmoor developers"
copyright = "the floatmoor developers"  # noqa: A001 (the name Sphinx reads)
release = floatmoor.__version__
version = release

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
]
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
myst_heading_anchors = 3
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
exclude_patterns = ["_build", "auto_examples/*.ipynb", "auto_examples/*.py", "auto_examples/*.zip",
                    "auto_examples/*.md5", "auto_examples/*.json"]

# -- API reference (autodoc + napoleon) -----------------------------------------------------
# The docstrings are numpy style; type hints are shown in the signatures, as written.
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
# Attributes as fields of their class: NamedTuple fields are members already (no duplicates).
napoleon_use_ivar = True
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_default_options = {"members": True, "show-inheritance": True}
# The array aliases read better than their expansions in signatures.
autodoc_type_aliases = {"ArrayLike": "ArrayLike", "NDArray": "NDArray"}

# -- HTML --------------------------------------------------------------------------------------
# The theme of xarray's and capytaine's sites (sphinx-book-theme builds on it).
html_theme = "pydata_sphinx_theme"
html_title = f"floatmoor {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version", "theme-version"],
}
html_static_path: list[str] = []

# -- Examples gallery --------------------------------------------------------------------------
# Every examples/plot_*.py runs during the build; a failing example fails the build.
sphinx_gallery_conf = {
    "examples_dirs": "../examples",
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "within_subsection_order": "FileNameSortKey",
    "remove_config_comments": True,
    "only_warn_on_example_error": False,
    "image_scrapers": ("matplotlib",),
    "matplotlib_animations": False,
}


def _drop_tuple_field_aliases(app, what, name, obj, options, lines):
    """Drop Python's "Alias for field number N", the docstring of a NamedTuple field without a
    ``#:`` comment: its class docstring describes the field."""
    if len(lines) <= 2 and lines and lines[0].startswith("Alias for field number"):
        lines.clear()


def setup(app):
    app.connect("autodoc-process-docstring", _drop_tuple_field_aliases)
