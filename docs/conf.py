"""Sphinx configuration of the shaketable documentation site.

Build (from the repository root)::

    python -m pip install -e ".[docs]"
    python -m sphinx -W -b html docs docs/_build/html

The gallery (``examples/plot_*.py``) is executed at every build; its figures and
files go into ``docs/auto_examples/`` and temporary folders, never into tracked files.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the checkout's package when it is not installed
os.environ.setdefault("MPLBACKEND", "Agg")

import shaketable  # noqa: E402

project = "shaketable"
author = "shaketable developers"
copyright = "shaketable developers, MIT licence"
release = shaketable.__version__
version = ".".join(release.split(".")[:2])

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.intersphinx",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "figures/*.md", "auto_examples/*.ipynb", "auto_examples/*.py",
                    "auto_examples/*.zip", "auto_examples/*.json", "auto_examples/*.md5",
                    "sg_execution_times.rst"]

# -- Markdown pages (myst) ----------------------------------------------------
myst_enable_extensions = ["dollarmath"]
myst_heading_anchors = 3
# The Markdown pages link the repository's files (../shaketable/..., ../benchmarks/...)
# as GitHub would show them; those are not pages of the site.
suppress_warnings = ["myst.xref_missing", "myst.header", "config.cache",
                     # a module's References list citations its functions cite, not the
                     # module docstring itself
                     "ref.citation"]

# -- API reference ------------------------------------------------------------
# The summary tables cut a docstring's first sentence at ". ": the report's abbreviations
# (Eqs. (2-13)/(2-14), Fig. 3.4, Sec.) do not end it.
import sphinx.ext.autosummary as _autosummary  # noqa: E402

_autosummary.WELL_KNOWN_ABBREVIATIONS = (*_autosummary.WELL_KNOWN_ABBREVIATIONS, "Eq.", "Eqs.",
                                         "Fig.", "Figs.", "Sec.", "Secs.")
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_typehints = "none"          # the numpydoc sections carry types and units
autodoc_member_order = "bysource"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()

intersphinx_mapping = {
    "python": ("https://docs.python.org/3", None),
    "numpy": ("https://numpy.org/doc/stable", None),
    "obspy": ("https://docs.obspy.org", None),
}
# the site builds offline too (CI machines without network): intersphinx is optional
if os.environ.get("SHAKETABLE_DOCS_OFFLINE", "1") == "1":
    intersphinx_mapping = {}

# -- Gallery ------------------------------------------------------------------
sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "ignore_pattern": r"__init__\.py",
    "within_subsection_order": "FileNameSortKey",
    "download_all_examples": False,
    "remove_config_comments": True,
    "image_scrapers": ("matplotlib",),
    "matplotlib_animations": False,
    "show_memory": False,
    "plot_gallery": "True",
    "reset_modules": ("matplotlib",),
    "doc_module": ("shaketable",),
    "backreferences_dir": None,
    "min_reported_time": 1,
}

# -- HTML ---------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = f"shaketable {release}"
html_theme_options = {
    "github_url": "https://github.com/shaketable/shaketable",
    "navigation_with_keys": False,
    "show_toc_level": 2,
}
html_static_path = ["_static"]
# wrapped code blocks and outputs (nothing cut at the right edge: docs/tools/check_site.py)
html_css_files = ["shaketable.css"]
# The pages of the top-level toctrees (user guide, reference pages) have no section of their
# own to navigate: no primary sidebar there, rather than an empty "Section Navigation"
# column; the API reference and the gallery keep theirs (their module and example lists).
# ("*" matches the top-level pages only, not api/... or auto_examples/...)
html_sidebars = {"*": []}


# -- Docstrings: plain-text notation that reStructuredText would misread -------
# The docstrings write absolute values as |theta| and cite the report as [1]_ (numpydoc).
# In reST |theta| is a substitution and [1]_ needs a References section in the same
# docstring; escape the first and unlink the second where that section is absent,
# before numpydoc reads the docstring (priority < 500).
import re  # noqa: E402

_BARS = re.compile(r"(?<![\\`|])\|(\S(?:[^|\n`]*?\S)?)\|(?![_|])")
_CITATION = re.compile(r"\[(\d+)\]_")


def _plain_notation(app, what, name, obj, options, lines):
    has_references = any(line.strip() == "References" for line in lines)
    for index, line in enumerate(lines):
        stripped = line.lstrip()
        if stripped.startswith(("+-", "+=", "| ", "..", "==")):
            continue  # tables and directives
        line = _BARS.sub(r"\\|\1\\|", line)
        if not has_references:
            line = _CITATION.sub(r"[\1]", line)
        lines[index] = line


def setup(app):
    app.connect("autodoc-process-docstring", _plain_notation, priority=400)
