"""Sphinx configuration: the documentation site, built from the code.

    pip install -e ".[docs]" && sphinx-build -W -b html docs docs/_build/html

The gallery runs the scripts in ``examples/``.  By default it runs their short versions (the
ones the tests run, seconds each), so that a build takes a couple of minutes; the pictures of
the published resolutions come from

    ADHESIVE_PUNCH_EXAMPLES=full sphinx-build -W -b html docs docs/_build/html

(tens of minutes on two cores).  ``examples/_gallery.py`` reads the variable.  Sphinx-gallery
re-runs only the examples whose source changed since the last build in the same output tree,
so a short build after a full one keeps the full pictures of unchanged scripts: delete
``docs/auto_examples`` to rebuild them all.
"""

from __future__ import annotations

import os
import re
import sys
from importlib.metadata import version as _version
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
# the examples import as ``examples.<name>`` from the repository root (as the tests import them)
sys.path.insert(0, str(ROOT))
# the gallery's sort key is named as conf.GalleryOrder (a name, so that the build cache can store it)
sys.path.insert(0, str(DOCS))

os.environ.setdefault("ADHESIVE_PUNCH_EXAMPLES", "short")
# a full run also writes each picture as a file (as ``python examples/<name>.py`` does): keep
# them in the build tree, not among the sources
os.environ.setdefault("ADHESIVE_PUNCH_PICTURES", str(DOCS / "_build" / "pictures"))
Path(os.environ["ADHESIVE_PUNCH_PICTURES"]).mkdir(parents=True, exist_ok=True)
# the solvers' BLAS and FFTs on one thread, as in the tests (two examples share the machine badly)
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

project = "adhesive-punch"
author = "the adhesive-punch authors"
copyright = "the adhesive-punch authors, BSD-3-Clause"
release = _version("adhesive-punch")
version = ".".join(release.split(".")[:2])

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "myst_parser",
    "sphinx_click",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = [
    "_build",
    "Thumbs.db",
    ".DS_Store",
    "auto_examples/*.ipynb",
    "auto_examples/*.py",
    "auto_examples/*.zip",
    "auto_examples/*.json",
    "auto_examples/*.md5",
]
templates_path = ["_templates"]

# -- API reference -------------------------------------------------------------------------
# Each package's public names are its ``__all__`` (the pages in api/ list them through the
# autosummary template in _templates/); modules behind them are implementation and may move.
autosummary_generate = True
autosummary_ignore_module_all = False
autosummary_imported_members = True
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_typehints_format = "short"
# numpydoc: the class pages list their members through autodoc, not numpydoc's own tables
# (which would document every dataclass field twice)
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()

API_PACKAGES = ("contact_scene", "halfspace", "bem_griffith", "bem_energy", "fem_reference", "crossval")


def _reexported() -> dict[str, dict[str, str]]:
    """Per package, the public names it takes from another package (bem_griffith offers the
    half-space operator of :mod:`halfspace`): their page is the defining package's, the
    re-exporting one links to it (two full pages would describe one object twice)."""
    import importlib

    out = {}
    for pkg in API_PACKAGES:
        mod = importlib.import_module(pkg)
        out[pkg] = {}
        for name in mod.__all__:
            home = getattr(getattr(mod, name), "__module__", pkg).split(".")[0]
            if home in API_PACKAGES and home != pkg:
                out[pkg][name] = f"{home}.{name}"
    return out


autosummary_context = {"reexported": _reexported()}

_LITERAL = re.compile(r"(``.*?``)")


def _plain_text_bars(app, what, name, obj, options, lines):
    """The docstrings write mathematics as plain text, as the formula sheet does: ``|x|`` is a
    magnitude, which reStructuredText would read as a substitution.  Escape the bars outside
    inline literals."""
    for i, line in enumerate(lines):
        lines[i] = "".join(part if part.startswith("``") else part.replace("|", r"\|") for part in _LITERAL.split(line))


#: pages that benchmark scripts write when they are run (benchmarks/study_error_models.py,
#: benchmarks/mutation_study.py): listed under "Measured" when present
GENERATED_PAGES = ("error_models", "mutation_study")
_MEASURED_TOC = "accuracy\nperformance\n"


def _list_generated_pages(app, docname, source):
    """Add the generated pages that exist to the index's "Measured" contents (a toctree entry
    without its page would fail the build, a page in no toctree too)."""
    if docname != root_doc:
        return
    present = "".join(f"{name}\n" for name in GENERATED_PAGES if (DOCS / f"{name}.md").is_file())
    if _MEASURED_TOC not in source[0]:
        raise RuntimeError(f"docs/{root_doc}.md no longer lists {_MEASURED_TOC!r}: update docs/conf.py")
    source[0] = source[0].replace(_MEASURED_TOC, _MEASURED_TOC + present, 1)


def setup(app):
    app.connect("autodoc-process-docstring", _plain_text_bars)
    app.connect("source-read", _list_generated_pages)


# -- MyST (the Markdown pages as they are in the repository) -------------------------------
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3

# -- Gallery --------------------------------------------------------------------------------
sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples"),
    "gallery_dirs": "auto_examples",
    # every public script is an example; the private helpers (_gallery.py, __init__.py) are not
    "filename_pattern": r"/[^_][^/]*\.py$",
    "ignore_pattern": r"(^|/)_[^/]*\.py$",
    # the methods' own example first, then the paper's figures in its order, then the energy BEM's
    "within_subsection_order": "conf.GalleryOrder",
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "remove_config_comments": True,
    "download_all_examples": False,
    "capture_repr": (),
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
    "reset_modules": ("matplotlib",),
    "min_reported_time": 1,
    "show_memory": False,
    "plot_gallery": "True",
    "write_computation_times": True,
    # the examples are independent single-threaded solves: one process per core (joblib)
    "parallel": max(1, min(4, os.cpu_count() or 1)),
}


class GalleryOrder:
    """Sort key of the gallery: Kendall's punch, the paper's figures by number, the energy BEM."""

    FIRST, LAST = ("kendall_circle",), ("energy_zero_range",)

    def __init__(self, src_dir):
        self.src_dir = src_dir

    def __call__(self, filename: str):
        stem = Path(filename).stem
        if stem in self.FIRST:
            return (0, 0, stem)
        if stem in self.LAST:
            return (2, 0, stem)
        number = re.match(r"fig(\d+)", stem)
        return (1, int(number.group(1)) if number else 0, stem)

    def __repr__(self):
        return "GalleryOrder"


# -- HTML -----------------------------------------------------------------------------------
html_theme = "furo"
html_title = f"adhesive-punch {release}"
html_static_path: list[str] = []
html_show_sourcelink = False
