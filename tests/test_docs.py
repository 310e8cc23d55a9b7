"""The documentation: source checks (fast) and the full offline Sphinx build with -W (slow).

The build executes every notebook once (myst-nb, ``nb_execution_mode=force``)
and writes the executed copies to ``<basetemp>/docs-build/jupyter_execute``;
``tests/test_notebooks.py`` checks those copies instead of executing again.
``.ci/run`` sets ``HYPERROTOR_SKIP_DOCS_BUILD`` (its value is the reason) in its lowest-versions
job: there the build and the notebooks are skipped, the newest job runs them.
"""
from __future__ import annotations

import importlib
import importlib.util
import json
import os
import pkgutil
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
NOTEBOOKS = sorted((DOCS / "notebooks").glob("*.ipynb"))
DOCS_BUILD_DIRNAME = "docs-build"  # shared with tests/test_notebooks.py
PAGES = ["index", "installation", "tutorial", "conventions", "theory", "verification",
         "benchmarks", "api", "api/conventions", "api/classical", "api/quantum", "api/paper", "api/plotting"]


def _api_text() -> str:
    return "\n".join(p.read_text() for p in [DOCS / "api.md", *sorted((DOCS / "api").glob("*.md"))])


def _public_modules() -> list[str]:
    import hyperrotor

    names = []
    for info in pkgutil.walk_packages(hyperrotor.__path__, prefix="hyperrotor."):
        if any(part.startswith("_") for part in info.name.split(".")):
            continue
        if info.name.split(".")[:2] == ["hyperrotor", "cli"] or info.name.endswith("__main__"):
            continue  # the command line is documented by its --help
        names.append(info.name)
    return names


def test_every_public_module_is_in_the_api_reference():
    documented = set(re.findall(r"automodule::\s+(\S+)", _api_text()))
    missing = [m for m in _public_modules() if m not in documented]
    assert not missing, f"add these modules to docs/api/*.md: {missing}"
    for name in documented:  # and nothing documented that does not exist
        importlib.import_module(name)


def test_every_notebook_is_in_the_toctree_and_committed_without_outputs():
    index = (DOCS / "index.md").read_text()
    listed = set(re.findall(r"^notebooks/(\S+)$", index, flags=re.M))
    assert listed == {p.stem for p in NOTEBOOKS}
    for path in NOTEBOOKS:
        nb = json.loads(path.read_text())
        outputs = [c for c in nb["cells"] if c["cell_type"] == "code" and (c.get("outputs") or c.get("execution_count"))]
        assert not outputs, f"{path.name}: clear the outputs before committing (they are produced by the build)"


def _plots(path: Path) -> bool:
    cells = json.loads(path.read_text())["cells"]
    return any("matplotlib" in "".join(c["source"]) for c in cells if c["cell_type"] == "code")


def test_notebooks_that_plot_draw_on_the_page():
    """The build's kernels inherit MPLBACKEND=Agg (docs/conf.py, these tests), with which figures never
    reach the page: a notebook that plots selects the inline backend in its first code cell."""
    for path in NOTEBOOKS:
        first = next(c for c in json.loads(path.read_text())["cells"] if c["cell_type"] == "code")
        assert not _plots(path) or "%matplotlib inline" in "".join(first["source"]).splitlines(), path.name


#: Set by ``.ci/run`` for its lowest-versions job, with the reason as its value: that job skips the
#: documentation build and the notebooks' execution (the newest job does both); unset, as in a
#: plain ``python -m pytest``, the docs are built.
SKIP_DOCS_BUILD_ENV = "HYPERROTOR_SKIP_DOCS_BUILD"


def docs_build_skipped() -> str | None:
    """Why this session does not build the docs (and execute the notebooks), or None when it does."""
    reason = os.environ.get(SKIP_DOCS_BUILD_ENV, "").strip()
    return f"{SKIP_DOCS_BUILD_ENV} is set: {reason}" if reason else None


def build_docs(basetemp: Path) -> tuple[Path, subprocess.CompletedProcess]:
    """The session's one documentation build (it executes every notebook), run on first use.

    Used by the fixture below and by tests/test_notebooks.py, which reads the executed
    notebooks from it when this session runs the build test (so each notebook runs once per
    session, whatever the test order). The result is kept in files under ``basetemp``, so a
    second call in the session returns it without building again.
    """
    build = basetemp / DOCS_BUILD_DIRNAME
    done = build / "BUILD_DONE.json"
    if done.exists():
        saved = json.loads(done.read_text())
        return build, subprocess.CompletedProcess(saved["args"], saved["returncode"], saved["stdout"], saved["stderr"])
    build.mkdir(exist_ok=True)
    # a kernelspec "python3" that runs this interpreter, found first on JUPYTER_PATH
    spec = build / "jupyter" / "kernels" / "python3"
    spec.mkdir(parents=True, exist_ok=True)
    (spec / "kernel.json").write_text(json.dumps({
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": "hyperrotor docs kernel", "language": "python",
    }))
    env = dict(os.environ, JUPYTER_PATH=str(build / "jupyter"), MPLBACKEND="Agg",
               PYDEVD_DISABLE_FILE_VALIDATION="1")
    cmd = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-b", "html",
           "-D", "nb_execution_mode=force", "-d", str(build / "doctrees"),
           str(DOCS), str(build / "html")]
    proc = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True, timeout=1200)
    if proc.returncode == 0:
        (build / "BUILD_OK").write_text("ok\n")
    done.write_text(json.dumps({"args": cmd, "returncode": proc.returncode, "stdout": proc.stdout,
                                "stderr": proc.stderr}))
    return build, proc


@pytest.fixture(scope="session")
def docs_build(tmp_path_factory):
    if docs_build_skipped():
        pytest.skip(docs_build_skipped())
    pytest.importorskip("sphinx")
    pytest.importorskip("myst_nb")
    pytest.importorskip("ipykernel")
    return build_docs(tmp_path_factory.getbasetemp())


@pytest.mark.slow
def test_docs_build_offline_without_warnings(docs_build):
    build, proc = docs_build
    assert proc.returncode == 0, f"sphinx-build -W failed:\n{proc.stderr[-6000:]}"
    # Sphinx/docutils messages ("path:line: WARNING: ..."), not the kernels' "[IPKernelApp] WARNING | ..."
    problems = re.findall(r"^.*(?:WARNING|ERROR|CRITICAL): .*$", proc.stderr, flags=re.M)
    assert not problems, "\n".join(problems)
    for page in PAGES:
        assert (build / "html" / f"{page}.html").exists(), page
    for path in NOTEBOOKS:
        assert (build / "html" / "notebooks" / f"{path.stem}.html").exists(), path.name
        assert (build / "jupyter_execute" / "notebooks" / path.name).exists(), path.name


@pytest.mark.slow
def test_docs_content(docs_build):
    build, proc = docs_build
    assert proc.returncode == 0, proc.stderr[-3000:]
    html = build / "html"
    # the API reference really contains the documented objects (autodoc imported them)
    classical = (html / "api" / "classical.html").read_text()
    for anchor in ["hyperrotor.classical.inertia.Inertia", "hyperrotor.classical.rigid_body.RigidBody",
                   "hyperrotor.classical.simulate.simulate"]:
        assert f'id="{anchor}"' in classical, anchor
    assert 'id="hyperrotor.conventions.to_matrix"' in (html / "api" / "conventions.html").read_text()
    # conventions: the N = 5 sign row of eq. (21) as rendered
    conventions = (html / "conventions.html").read_text()
    cell = '<td><p><span class="math notranslate nohighlight">\\({}\\)</span></p></td>'
    assert conventions.count(cell.format("-")) == 6 and conventions.count(cell.format("+")) == 4
    # every benchmark plot that exists was copied into the site
    images = {p.name for p in (html / "_images").glob("*.png")} if (html / "_images").exists() else set()
    for png in sorted((ROOT / "benchmarks" / "results").glob("*.png")):
        assert png.name in images, png.name
    # each notebook's checks cell ran (tests/test_notebooks.py reads it) but is not on the page; figures are
    for path in NOTEBOOKS:
        page = (html / "notebooks" / f"{path.stem}.html").read_text()
        assert "HYPERROTOR_CHECKS" not in page, f"{path.name}: the checks cell shows on the page"
        assert not _plots(path) or "<img" in page, f"{path.name}: no figure on the page"
    # the interactive scene is on the scenes notebook's page and the tutorial's scenes section, with
    # plotly.js inside: nothing fetched from a CDN; its set-up cell is not on the page
    for page in ("notebooks/03_scenes.html", "tutorial.html"):
        scenes = (html / page).read_text()
        assert "plotly-graph-div" in scenes and "Plotly.newPlot" in scenes, page
        assert not re.findall(r"<script[^>]*\bsrc=\"https?://[^\"]*(?:plot\.ly|mathjax/3\.2)", scenes), page
        assert "PageHTML" not in scenes, page


# -- every page's code runs as written ----------------------------------------------------------
#: The pages whose code a reader copies: the README and every page of docs/ (the notebooks are
#: executed by tests/test_notebooks.py).
CODE_PAGES = [ROOT / "README.md", *sorted(DOCS.glob("*.md"))]
#: Modules of a page block that only a real cluster provides (a batch system, Kubernetes): such a
#: block is compiled (syntax checked) instead of run, when the module is not installed here.
CLUSTER_MODULES = ("dask_jobqueue", "dask_kubernetes")
_FENCE = re.compile(r"^(?P<indent>[ \t]*)(?P<fence>`{3,}|~{3,})\s*(?P<info>[^\n`]*)$")


def page_code(path: Path) -> list[tuple[int, str]]:
    """The ```python blocks and ``{code-cell}`` cells of a page, in order, as (first line, code).

    A code cell's option lines (``:tags: ...`` or a ``---`` block) are dropped, and so are
    IPython magics (``%...``, ``!...``), which plain Python cannot run.
    """
    lines = path.read_text(encoding="utf-8").splitlines()
    blocks, k = [], 0
    while k < len(lines):
        opening = _FENCE.match(lines[k])
        if not opening:
            k += 1
            continue
        fence, info = opening["fence"], opening["info"].strip()
        end = k + 1
        while end < len(lines) and not re.match(rf"^[ \t]*{fence[0]}{{{len(fence)},}}\s*$", lines[end]):
            end += 1
        body = list(range(k + 1, end))
        word = info.split()[0] if info else ""
        if word.startswith("{code-cell}") or word == "{code-cell}":
            if body and lines[body[0]].strip() == "---":      # a YAML options block
                stop = next(i for i in body[1:] if lines[i].strip() == "---")
                body = [i for i in body if i > stop]
            while body and lines[body[0]].lstrip().startswith(":"):  # ":tags: [...]" options
                body = body[1:]
            word = "python"
        if word in ("python", "python3", "py"):
            code = [("" if lines[i].lstrip().startswith(("%", "!")) else lines[i]) for i in body]
            blocks.append((body[0] + 1 if body else k + 2, textwrap.dedent("\n".join(code))))
        k = end + 1
    return blocks


def _needs_a_cluster(code: str) -> str | None:
    for name in CLUSTER_MODULES:
        if re.search(rf"^\s*(from|import)\s+{name}\b", code, flags=re.M) and importlib.util.find_spec(name) is None:
            return name
    return None


def _page_script(path: Path) -> str:
    """One script for the page: each block at its own line numbers (tracebacks point into the page)."""
    out: list[str] = []
    for first, code in page_code(path):
        if _needs_a_cluster(code):
            compile(code, f"{path.name}:{first}", "exec")            # at least it is valid Python
            continue
        out += [""] * (first - 1 - len(out))
        out += code.splitlines()
    return "\n".join(out) + "\n"


def test_page_code_is_read_in_order_with_magics_and_options_dropped(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("text\n```python\nx = 1\n```\n\n```{code-cell} ipython3\n:tags: [hide-input]\n"
                    "%matplotlib inline\ny = x + 1\n```\n````{code-cell} ipython3\n---\ntags: [a]\n---\n"
                    "z = y\n````\n```bash\nls\n```\n```text\nw = 0\n```\n")
    assert page_code(page) == [(3, "x = 1"), (8, "\ny = x + 1"), (15, "z = y")]
    script = _page_script(page).splitlines()
    assert script[2] == "x = 1" and script[8] == "y = x + 1" and script[14] == "z = y"


@pytest.mark.parametrize("path", [p for p in CODE_PAGES if page_code(p)],
                         ids=[p.name for p in CODE_PAGES if page_code(p)])
def test_page_runs_as_written(path, tmp_path):
    """Every Python block of the page, in order, in a fresh interpreter (warnings are errors)."""
    script = tmp_path / "page.py"
    script.write_text(_page_script(path), encoding="utf-8")
    # compiled under the page's own name: a traceback quotes the page's line
    runner = ("import sys, pathlib; "
              "exec(compile(pathlib.Path(sys.argv[1]).read_text(), sys.argv[2], 'exec'), {'__name__': '__main__'})")
    env = dict(os.environ, MPLBACKEND="Agg")
    proc = subprocess.run([sys.executable, "-W", "error", "-c", runner, str(script), str(path)], cwd=tmp_path,
                          env=env, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, f"{path.relative_to(ROOT)} does not run as written:\n{proc.stderr[-4000:]}"
