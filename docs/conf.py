"""Sphinx configuration of the viscontact documentation (``make docs``).

Generated at build time, never by hand: the API reference (one page per public module, found by
walking the package), the case-key reference (from the pydantic models of ``viscontact.io.case``), the
result-variable table (from ``viscontact.io.results``), the command-line help (from the ``viscontact``
command itself) and the gallery (the scripts in ``examples/``, run by sphinx-gallery).
"""
from __future__ import annotations

import pkgutil
import sys
from pathlib import Path

import matplotlib

import viscontact

matplotlib.use("Agg")
HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

project = "viscontact"
author = "viscontact developers"
copyright = "viscontact developers, BSD-3-Clause"
release = viscontact.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
    "viscontact_docs",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "**.ipynb_checkpoints", "auto_examples/*.ipynb", "auto_examples/*.py",
                    "auto_examples/*.zip", "auto_examples/*.md5", "auto_examples/*.json"]
templates_path = ["_templates"]
myst_enable_extensions = ["dollarmath", "deflist"]
myst_heading_anchors = 3

html_theme = "furo"
html_title = f"viscontact {release}"

autosummary_generate = True
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_typehints_format = "short"
napoleon_numpy_docstring = True
napoleon_google_docstring = False
napoleon_use_rtype = False
# pydantic internals and dataclass machinery add nothing to a reader's view of the classes
autodoc_default_options = {"exclude-members": "model_config, model_fields, model_computed_fields"}

sphinx_gallery_conf = {
    "examples_dirs": str(HERE.parent / "examples"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "abort_on_example_error": True,
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "matplotlib_animations": False,
}


def _modules(packages: bool) -> list[str]:
    """Every module (``packages=False``) or sub-package (``True``) of viscontact, found by walking it;
    a name with a part starting with an underscore is private and left out."""
    found = pkgutil.walk_packages(viscontact.__path__, "viscontact.")
    return sorted(m.name for m in found if m.ispkg == packages
                  and not any(part.startswith("_") for part in m.name.split(".")))


def _layers() -> list[tuple[str, tuple[str, ...]]]:
    """The internals' sections, in the order of the layers: (layer, package prefixes) of the layer table
    of architecture.md (which ``tests/unit/test_architecture.py`` checks against the imports), the
    package itself left out (its names are the public API)."""
    table = (HERE / "architecture.md").read_text(encoding="utf-8").split("<!-- layer-table")[1]
    rows = []
    for line in table.split("<!-- /layer-table -->")[0].splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) >= 3 and cells[1].startswith("`") and cells[1] != "`viscontact`":
            rows.append((cells[0], tuple(p.strip(" `") for p in cells[1].split(","))))
    return rows


def _write_api_page() -> None:
    """docs/api.rst: the public API (what ``import viscontact as vc`` offers) first, then the internals
    layer by layer (one autosummary entry per module)."""
    lines = ["API reference", "=============", "",
             "Generated from the docstrings of the package at build time.", "",
             "Public API", "----------", "",
             "``import viscontact as vc`` gives these names; they are what scripts use, and they stay stable.", "",
             ".. autosummary::", ""]
    for name in viscontact.__all__:
        obj = getattr(viscontact, name)
        home = getattr(obj, "__module__", None)
        if name.startswith("__") or home is None:
            continue
        lines.append(f"   {obj.__name__}" if isinstance(obj, type(viscontact)) else f"   {home}.{obj.__qualname__}")
    lines += ["", "Internals", "---------", "",
              "The modules behind the public API, by layer (:doc:`architecture`): for developers and for scripts",
              "that need more than the public names; they may change between releases.", ""]
    for title, prefixes in _layers():
        lines += [title, "~" * len(title), ""]
        # a package's page is its docstring (its modules have their own); a module's lists its members
        for packages, template in ((True, ["   :template: autosummary/package.rst"]), (False, [])):
            names = [m for m in _modules(packages) if any(m == p or m.startswith(p + ".") for p in prefixes)]
            if names:
                lines += [".. autosummary::", "   :toctree: generated", *template, ""]
                lines += [f"   {name}" for name in names] + [""]
    text = "\n".join(lines) + "\n"
    path = HERE / "api.rst"
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


_write_api_page()
