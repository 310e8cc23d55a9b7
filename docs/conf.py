"""Sphinx configuration for the hyperrotor documentation.

Build (offline, warnings are errors)::

    pip install ".[docs]"
    sphinx-build -W --keep-going -b html docs docs/_build/html

The notebooks in ``docs/notebooks`` are committed without outputs and are
executed by myst-nb during the build (``nb_execution_mode = "cache"``: a rebuild
re-executes only notebooks that changed; the cache lives in ``docs/_build``).
Nothing is fetched from the network while building: no intersphinx, and the
MathJax script is only *referenced* by the HTML pages (the browser loads it when
a page is viewed).
"""
from __future__ import annotations

import csv
import fnmatch
import os
import sys
from pathlib import Path

from docutils import nodes
from docutils.parsers.rst import Directive, directives

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
# Document the checkout, also when an older hyperrotor is installed elsewhere.
sys.path.insert(0, str(ROOT / "src"))
# Notebooks draw with matplotlib: never try to open a window.
os.environ.setdefault("MPLBACKEND", "Agg")

import hyperrotor  # noqa: E402

# -- project ----------------------------------------------------------------
project = "hyperrotor"
author = "hyperrotor developers"
copyright = "2026, hyperrotor developers"
release = hyperrotor.__version__
version = ".".join(release.split(".")[:2])

# -- general ----------------------------------------------------------------
extensions = [
    "myst_nb",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
root_doc = "index"
exclude_patterns = ["_build", "**.ipynb_checkpoints", "Thumbs.db", ".DS_Store"]
templates_path: list[str] = []
nitpicky = False
suppress_warnings: list[str] = []

# -- MyST -------------------------------------------------------------------
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
myst_dmath_double_inline = True

# -- notebooks (myst-nb) ----------------------------------------------------
# Cells tagged "remove-cell" are executed but left off the page (myst-nb's default behaviour,
# relied on here): each notebook's last cell, which asserts its results and prints the
# HYPERROTOR_CHECKS line for tests/test_notebooks.py, is one of them. The executed copies
# in <build>/jupyter_execute keep every cell and output. The kernels inherit MPLBACKEND=Agg
# from above, so a notebook that plots selects "%matplotlib inline" itself (tests/test_docs.py).
nb_execution_mode = "cache"
nb_execution_timeout = 180  # per cell, seconds
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_merge_streams = True

# -- autodoc / napoleon -----------------------------------------------------
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_typehints_format = "short"
autoclass_content = "both"
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
napoleon_use_ivar = True

# -- math -------------------------------------------------------------------
# Only referenced from the pages (loaded by the browser at view time).
mathjax3_config = {
    "tex": {
        "macros": {
            "so": r"\mathfrak{so}",
            "tr": r"\operatorname{tr}",
        }
    }
}

# -- HTML -------------------------------------------------------------------
html_theme = "alabaster"
html_static_path = ["_static"] if (DOCS / "_static").is_dir() else []
html_title = f"hyperrotor {release}"
html_theme_options = {
    "description": "Rigid rotation in N dimensions, classical and quantum",
    "fixed_sidebar": True,
    "page_width": "1100px",
    "sidebar_width": "230px",
}
html_sidebars = {"**": ["about.html", "navigation.html", "relations.html", "searchbox.html"]}


# -- the benchmark results directive -----------------------------------------
class BenchmarkResults(Directive):
    """Insert every CSV table and PNG figure found in ``benchmarks/results``.

    The benchmark scripts write their numbers (CSV) and work-precision plots
    (PNG) there; this directive shows whatever the last run produced, so the
    page never quotes numbers that did not come from a real run.  Each file
    ``name.csv``/``name.png`` becomes a section titled by its stem.
    """

    has_content = False
    optional_arguments = 1  # a glob pattern of stems, default "*"
    option_spec = {"exclude": directives.unchanged}  # space-separated stem patterns

    def run(self):
        results = ROOT / "benchmarks" / "results"
        pattern = self.arguments[0] if self.arguments else "*"
        env = self.state.document.settings.env
        docdir = Path(env.doc2path(env.docname)).parent
        stems = sorted({p.stem for p in results.glob(pattern + ".csv")}
                       | {p.stem for p in results.glob(pattern + ".png")})
        excluded = self.options.get("exclude", "").split()
        stems = [s for s in stems if not any(fnmatch.fnmatch(s, e) for e in excluded)]
        if not stems:
            para = nodes.paragraph()
            para += nodes.emphasis(text=f"No results matching '{pattern}' in benchmarks/results "
                                        "(run the scripts in benchmarks/ to produce them).")
            return [para]
        out = []
        for stem in stems:
            env.note_dependency(str(results))
            box = nodes.container(classes=["benchmark-result"])
            box += nodes.rubric(text=stem)
            png = results / f"{stem}.png"
            if png.exists():
                env.note_dependency(str(png))
                rel = os.path.relpath(png, docdir).replace(os.sep, "/")
                box += nodes.image(uri=rel, alt=f"benchmark {stem}", width="90%")
            table_file = results / f"{stem}.csv"
            if table_file.exists():
                env.note_dependency(str(table_file))
                box += _csv_table(table_file)
            out.append(box)
        return out


def _csv_table(path: Path, max_rows: int = 300) -> nodes.Node:
    with path.open(newline="") as handle:
        rows = list(csv.reader(handle))
    if not rows:
        return nodes.paragraph(text=f"{path.name}: empty")
    header, body = rows[0], rows[1:]
    truncated = len(body) > max_rows
    body = body[:max_rows]
    ncol = max(len(header), *(len(r) for r in body)) if body else len(header)
    table = nodes.table(classes=["benchmark-table"])
    group = nodes.tgroup(cols=ncol)
    table += group
    for _ in range(ncol):
        group += nodes.colspec(colwidth=1)

    def _row(cells):
        row = nodes.row()
        for k in range(ncol):
            entry = nodes.entry()
            text = cells[k] if k < len(cells) else ""
            entry += nodes.paragraph(text=_fmt(text))
            row += entry
        return row

    thead = nodes.thead()
    thead += _row(header)
    group += thead
    tbody = nodes.tbody()
    for r in body:
        tbody += _row(r)
    group += tbody
    items = [table]
    caption = f"{path.name}" + (f" (first {max_rows} rows)" if truncated else "")
    cont = nodes.container()
    cont += nodes.paragraph(text=caption, classes=["caption"])
    cont += items
    return cont


def _fmt(text: str) -> str:
    """Shorten long floats for display (the CSV keeps full precision)."""
    try:
        value = float(text)
    except ValueError:
        return text
    if text.strip().lstrip("-").isdigit():
        return text
    return f"{value:.4g}"


def setup(app):
    app.add_directive("benchmark-results", BenchmarkResults)
    return {"parallel_read_safe": True}
