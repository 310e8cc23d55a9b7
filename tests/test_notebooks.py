"""Execute every notebook in ``docs/notebooks`` and check what it computed.

Each notebook ends with a cell that asserts its own results and prints one
line ``HYPERROTOR_CHECKS {json}``; this test re-checks those numbers against
the bounds in :data:`CHECKS` (so a notebook that silently stops asserting is
caught too). That cell is plumbing for the tests: it carries the ``remove-cell``
tag, so myst-nb executes it but leaves it off the rendered page (the executed
copy in ``jupyter_execute`` keeps it, with its output).

Execution happens once per pytest session: when the session also runs the
documentation build (``tests/test_docs.py``, marked slow), the first of these
tests to need a notebook starts that build (myst-nb executes every notebook
and writes the executed copies next to the HTML) and the copies are checked,
whatever the test order; otherwise (e.g. ``pytest -m "not slow"``, a selection
of notebooks, or no Sphinx installed) the notebook is executed here with
nbclient, on a kernel running the current interpreter, with ``MPLBACKEND=Agg``.
Where ``HYPERROTOR_SKIP_DOCS_BUILD`` is set (``.ci/run``'s lowest-versions job; the
newest job executes the notebooks) these tests are skipped with its reason.
"""
from __future__ import annotations

import importlib.util
import json
import math
import sys
from pathlib import Path

import pytest
from test_docs import build_docs, docs_build_skipped  # tests/ is on sys.path (no __init__.py)

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOK_DIR = ROOT / "docs" / "notebooks"
NOTEBOOKS = sorted(NOTEBOOK_DIR.glob("*.ipynb"))
#: Where ``tests/test_docs.py`` builds the docs inside pytest's session basetemp.
DOCS_BUILD_DIRNAME = "docs-build"
CELL_TIMEOUT = 180  # seconds per cell
MARKER = "HYPERROTOR_CHECKS"

#: For each notebook: check name -> (relation, bound). "<=": value <= bound,
#: ">=": value >= bound, "==": value == bound (exact, for counts and booleans).
CHECKS: dict[str, dict[str, tuple[str, object]]] = {
    "01_paper_walkthrough": {
        "n_euler_equations": ("==", 10),
        "printed_eqs_28_37_match": ("==", True),
        "standard_equals_paper_components": ("==", True),
        "max_casimir_drift": ("<=", 1e-12),
        "lock_axis5_invariant_residual": ("<=", 1e-14),
        "textbook_3d_residual": ("<=", 1e-14),
    },
    "02_quartet_closed_form": {
        "closed_form_vs_numeric_max_err": ("<=", 1e-8),
        "frequency_vs_eigen_max_err": ("<=", 1e-12),
        "norm_v_drift": ("<=", 1e-12),
    },
    "03_scenes": {
        "n_frames": (">=", 10),
        "max_distance_drift": ("<=", 1e-9),
        "locked_axis_fixed_max": ("<=", 1e-12),
        "interactive_one_frame_per_time": ("==", True),
    },
    "04_tennis_racket": {
        "stable_planes_agree_with_rule": ("==", True),
        "unstable_growth_factor": (">=", 1e3),
        "stable_growth_factor": ("<=", 10.0),
    },
    "05_so5_representations": {
        "max_commutator_residual": ("<=", 1e-12),
        "max_casimir_residual": ("<=", 1e-10),
        "dims_match_weyl": ("==", True),
        "harmonic_gt_bridge_ok": ("==", True),
    },
    "06_quantum_rotor": {
        "spectrum_equal_moments_err": ("<=", 1e-9),
        "quartet_branching_err": ("<=", 1e-9),
        "ehrenfest_error_decreases": ("==", True),
        "ehrenfest_slope": ("<=", -0.7),
        "sesolve_vs_native": ("<=", 1e-6),
    },
    "07_work_precision": {
        "best_classical_error": ("<=", 1e-10),
        "best_quantum_error": ("<=", 1e-8),
    },
    "08_integrable_and_generic_rotors": {
        "n_sectors_so5": ("==", 16),
        "union_vs_dense_rel_err": ("<=", 1e-10),
        "spinor_degeneracy": ("==", 4),
        "spinor_levels_all_fourfold": ("==", True),
        "all_levels_counted": ("==", True),
        "synthetic_goe_r_ok": ("==", True),
        "generic_minus_manakov_r_in_se": (">=", 5.0),
        "lyapunov_median_ratio": (">=", 2.0),
        "generic_r_largest_irrep": ("<=", 0.5307),
        "manakov_r_minus_poisson_in_se": ("<=", 3.0),
        "manakov_lyapunov_all_regular": ("==", True),
    },
    "09_lyapunov_map": {
        "manakov_max_exponent": ("<=", 0.1),
        "generic_mean_exponent": (">=", 0.2),
        "generic_chaotic_fraction": (">=", 0.5),
        "regular_orbit_exponent": ("<=", 0.05),
        "chaotic_orbit_exponent": (">=", 0.3),
        "regular_thickness": ("<=", 0.05),
        "chaotic_thickness": (">=", 0.2),
        "section_casimir_drift": ("<=", 1e-12),
        "locked_components_max": ("==", 0.0),
        "sweep_matches_lyapunov": ("==", True),
    },
    "10_correspondence_in_time": {
        "lambda_manakov": ("<=", 0.1),
        "lambda_generic": (">=", 0.5),
        "manakov_tE_increasing": ("==", True),
        "generic_tE_increasing": ("==", True),
        "tE_all_found": ("==", True),
        "ehrenfest_vs_expm": ("<=", 1e-8),
        "otoc_vs_expm_rel": ("<=", 1e-9),
        "otoc_generic_rate": (">=", 1.0),
    },
}


def _kernel_env(tmp_dir: Path, monkeypatch) -> str:
    """A kernelspec that runs the current interpreter, first on JUPYTER_PATH."""
    name = "python3"
    spec_dir = tmp_dir / "kernels" / name
    spec_dir.mkdir(parents=True, exist_ok=True)
    (spec_dir / "kernel.json").write_text(json.dumps({
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": "hyperrotor test kernel",
        "language": "python",
    }))
    monkeypatch.setenv("JUPYTER_PATH", str(tmp_dir))
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setenv("PYDEVD_DISABLE_FILE_VALIDATION", "1")
    return name


#: Numbers the text of a notebook quotes from its run, which drift when the code changes (a review found notebooks
#: 09 and 10 quoting the Lyapunov exponents of an earlier lyapunov(): 1/lambda = 1.06 against 0.98 printed): for
#: each notebook, the text that must appear in its markdown, as a function of its check values.
QUOTED: dict[str, list] = {
    "09_lyapunov_map": [
        lambda v: f"$\\lambda(400) = {v['regular_orbit_exponent']:.3f}$",
        lambda v: f"$\\lambda = {v['chaotic_orbit_exponent']:.2f}$",
        lambda v: f"thickness about {v['chaotic_thickness']:.2f}",
        lambda v: f"between 0.02 and {math.ceil(100 * v['manakov_max_exponent']) / 100:.2f}",
    ],
    "10_correspondence_in_time": [
        lambda v: f"$1/\\lambda = {1 / v['lambda_generic']:.2f}$",
        lambda v: f"$2\\lambda = {2 * v['lambda_generic']:.2f}$",
        lambda v: f"$2\\lambda = {2 * v['lambda_manakov']:.2f}$",
        lambda v: f"grows at {v['otoc_generic_rate']:.2f} per unit time",
    ],
}


def _session_builds_the_docs(session) -> bool:
    return (not docs_build_skipped()
            and any(item.name == "test_docs_build_offline_without_warnings" for item in session.items)
            and all(importlib.util.find_spec(m) for m in ("sphinx", "myst_nb", "ipykernel")))


def _executed(path: Path, request, tmp_path_factory, monkeypatch):
    """The executed notebook: from this session's docs build if it runs one, else nbclient."""
    if docs_build_skipped():  # .ci/run's lowest-versions job: the newest job executes the notebooks
        pytest.skip(docs_build_skipped())
    if _session_builds_the_docs(request.session):
        build_docs(tmp_path_factory.getbasetemp())
    build = tmp_path_factory.getbasetemp() / DOCS_BUILD_DIRNAME
    built = build / "jupyter_execute" / "notebooks" / path.name
    if built.exists():  # executed by the build (a failing notebook stops the build: no copy of it)
        return nbformat.read(built, as_version=4), "docs build"
    nb = nbformat.read(path, as_version=4)
    kernel = _kernel_env(tmp_path_factory.mktemp("jupyter"), monkeypatch)
    client = nbclient.NotebookClient(
        nb, timeout=CELL_TIMEOUT, kernel_name=kernel,
        resources={"metadata": {"path": str(path.parent)}},
    )
    client.execute()
    return nb, "nbclient"


def _checks(nb) -> dict:
    found = []
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        for out in cell.get("outputs", []):
            text = out.get("text", "") if out.get("output_type") == "stream" else ""
            for line in text.splitlines():
                if line.startswith(MARKER):
                    found.append(json.loads(line[len(MARKER):]))
    # the same line can reach the outputs twice (a kernel's stdout stream forwarded twice, seen once
    # in CI for notebook 08); identical copies are one result, different ones are an error
    distinct = [f for i, f in enumerate(found) if f not in found[:i]]
    assert len(distinct) == 1, f"expected exactly one '{MARKER} {{...}}' line, found {len(distinct)} different"
    return distinct[0]


def _errors(nb) -> list[str]:
    return [
        f"{out.get('ename')}: {out.get('evalue')}"
        for cell in nb.cells if cell.cell_type == "code"
        for out in cell.get("outputs", []) if out.get("output_type") == "error"
    ]


def test_every_notebook_has_checks():
    assert NOTEBOOKS, "no notebooks found in docs/notebooks"
    assert {p.stem for p in NOTEBOOKS} <= set(CHECKS), (
        "add the checks of each new notebook to CHECKS: "
        f"{sorted({p.stem for p in NOTEBOOKS} - set(CHECKS))}"
    )


def test_the_checks_cell_is_the_last_code_cell_and_hidden_from_readers():
    for path in NOTEBOOKS:
        nb = nbformat.read(path, as_version=4)
        code = [c for c in nb.cells if c.cell_type == "code"]
        printing = [k for k, c in enumerate(code) if MARKER in c.source]
        assert printing == [len(code) - 1], f"{path.name}: only the last code cell prints the {MARKER} line"
        assert "remove-cell" in code[-1].metadata.get("tags", []), (
            f"{path.name}: tag the {MARKER} cell 'remove-cell' (executed, not shown on the page)")
        prose = "\n".join(c.source for c in nb.cells if c.cell_type == "markdown")
        assert MARKER not in prose and "check line" not in prose, f"{path.name}: the text refers to the hidden cell"


@pytest.mark.filterwarnings("ignore::DeprecationWarning:zmq.*")
@pytest.mark.filterwarnings("ignore::DeprecationWarning:tornado.*")
@pytest.mark.filterwarnings("ignore::DeprecationWarning:nbclient.*")
@pytest.mark.filterwarnings("ignore::ResourceWarning")
@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_executes_and_checks_hold(path, request, tmp_path_factory, monkeypatch):
    nb, source = _executed(path, request, tmp_path_factory, monkeypatch)
    assert not _errors(nb), f"{path.name} ({source}): {_errors(nb)}"
    values = _checks(nb)
    spec = CHECKS[path.stem]
    assert set(spec) <= set(values), f"{path.name}: missing checks {sorted(set(spec) - set(values))}"
    for key, (relation, bound) in spec.items():
        value = values[key]
        if relation == "==":
            assert value == bound, f"{path.name}: {key} = {value!r}, expected {bound!r}"
        else:
            assert isinstance(value, (int, float)) and math.isfinite(value), f"{path.name}: {key} = {value!r}"
            ok = value <= bound if relation == "<=" else value >= bound
            assert ok, f"{path.name}: {key} = {value:.3e}, expected {relation} {bound:.1e}"
    prose = " ".join(" ".join(c.source.split()) for c in nb.cells if c.cell_type == "markdown")
    for quote in QUOTED.get(path.stem, []):
        assert quote(values) in prose, f"{path.name}: the text should quote {quote(values)!r} (its run's value)"
