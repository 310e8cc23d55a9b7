"""The documentation: source checks (fast) and the full offline Sphinx build with -W (slow).

The build executes every notebook once (myst-nb, ``nb_execution_mode=force``)
and writes the executed copies to ``<basetemp>/docs-build/jupyter_execute``;
``tests/test_notebooks.py`` checks those copies instead of executing again.
"""
from __future__ import annotations

import importlib
import json
import os
import pkgutil
import re
import subprocess
import sys
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
        if info.name == "hyperrotor.cli" or info.name.endswith("__main__"):
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


@pytest.fixture(scope="session")
def docs_build(tmp_path_factory):
    pytest.importorskip("sphinx")
    pytest.importorskip("myst_nb")
    pytest.importorskip("ipykernel")
    build = tmp_path_factory.getbasetemp() / DOCS_BUILD_DIRNAME
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
    return build, proc


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
