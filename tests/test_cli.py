"""Tests of the ``hyperrotor`` command line (``hyperrotor.cli.main``)."""
import argparse
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import hyperrotor as hr

from hyperrotor import Inertia, RigidBody
from hyperrotor.cli import EXIT_CODES, SUBCOMMANDS, main
from hyperrotor.cli.bench import bench_paths


def _run(capsys, argv):
    code = main(argv)
    out = capsys.readouterr()
    return code, out.out, out.err


def _value(text, label):
    m = re.search(re.escape(label) + r" = (\S+)", text)
    assert m, f"{label!r} not in output"
    return float(m.group(1))


def _vector(text, label):
    m = re.search(re.escape(label) + r" = \[([^\]]*)\]", text)
    assert m, f"{label!r} not in output"
    return np.array([float(v) for v in m.group(1).split(",")])


def test_demo_invariants_recomputed(capsys):
    code, out, _ = _run(capsys, ["demo", "--ascii", "--no-png"])
    assert code == 0
    omega = _vector(out, "omega")
    body = RigidBody(Inertia.quartet(sp.Rational(1, 2)))
    # numbers are printed with 12 significant digits
    assert _value(out, "energy E = 1/2 sum I_ij w_ij^2") == pytest.approx(float(body.energy(omega)), rel=1e-11)
    # independent: c_2 = sum of squared L components, c_4 from numpy's characteristic polynomial
    L = body.inertia.moments * omega
    assert _value(out, "Casimir c_2 = sum (L^ij)^2") == pytest.approx(float(np.sum(L**2)), rel=1e-12)
    poly = np.poly(body.matrix(L))
    assert _value(out, "Casimir c_4 (lambda^1 coefficient of det(lambda - L))") == pytest.approx(poly[4], rel=1e-10)
    np.testing.assert_allclose(_vector(out, "  L"), L, rtol=1e-11)
    np.testing.assert_allclose(_vector(out, "d omega/dt"), body.rhs(omega), rtol=1e-11)
    A = hr.to_matrix(L, convention="standard") + np.diag([1, 1, 1, 1, 0.25]) ** 2  # L + J^2, J = (1, 1, 1, 1, kappa^2)
    for k in range(2, 6):
        assert _value(out, f"Manakov tr((L + J^2)^{k})") == pytest.approx(
            np.trace(np.linalg.matrix_power(A, k)), rel=1e-10)


def test_demo_prints_equations_28_to_37_in_order(capsys):
    _, out, _ = _run(capsys, ["demo", "--ascii", "--no-png"])
    labels = re.findall(r"^\((\d+)\)  ", out, flags=re.M)
    assert labels == [str(n) for n in range(28, 38)]
    # the quartet body with kappa = 1/2: the 15-equation carries 5/4 (1 + kappa^2) and 3/4 (1 - kappa^2)
    block = out.split("(30)")[1].split("(32)")[0]  # the pretty block of (31) starts above its label
    assert "mtilde_15" in block and "3*omega_12(t)*omega_25(t)" in block and "5*--(omega_15(t))" in block
    assert "I_15 = 5/4" in out and "I_12 = 2" in out
    assert "(1, 1, 1, 1, 1/4)" in out


def test_demo_prints_the_equations_before_the_motion_is_computed(capsys, monkeypatch):
    """A fresh installation compiles numba's kernels inside the motion (~20 s): the equations come first, and with
    --progress a line on stderr says what is being computed (the rest of stdout as before)."""
    import hyperrotor.demo

    seen = []
    real = hyperrotor.demo.compare_quartet_motion

    def spy(*args, **kwargs):
        seen.append(dict(zip(("out", "err"), capsys.readouterr())))
        return real(*args, **kwargs)

    monkeypatch.setattr(hyperrotor.demo, "compare_quartet_motion", spy)
    code, out, err = _run(capsys, ["demo", "--ascii", "--no-png", "--t-end", "1", "--progress"])
    first = seen[0]
    assert code == 0 and err == ""
    assert first["out"].startswith("hyperrotor demo: Euler equations") and "(37)" in first["out"]
    assert "d omega/dt = " in first["out"] and "motion over" not in first["out"]
    assert first["err"] == ("computing the motion over t in [0, 1] (closed form, splitting8, DOP853); the first run "
                           "after installing compiles numba's kernels once (about 20 s)\n")
    assert out.startswith("motion over t in [0, 1]") and "summary: 10 coupled Euler equations" in out
    _, rest, err = _run(capsys, ["demo", "--ascii", "--no-png", "--t-end", "1", "--no-progress"])
    assert seen[1] == {"out": first["out"], "err": ""} and err == "" and rest.startswith("motion over t in [0, 1]")


def test_demo_options(capsys):
    code, out, _ = _run(capsys, ["demo", "--ascii", "--no-png", "--kappa", "2", "--axis", "1", "--convention",
                                 "standard", "--omega", "1,0,0,0,0,0,0,0,0,1"])
    assert code == 0
    assert "I_12 = 5" in out and "I_45 = 2" in out
    assert re.findall(r"^\[(\d+)\]  ", out, flags=re.M)[0] == "12"
    assert "(28)" not in out
    assert _value(out, "energy E = 1/2 sum I_ij w_ij^2") == pytest.approx(0.5 * (5 + 2), rel=1e-12)


@pytest.mark.parametrize("argv,msg", [
    (["demo", "--kappa", "abc"], "--kappa"),
    (["demo", "--omega", "1,2"], "--omega needs 10 comma-separated numbers, got 2"),
    (["demo", "--omega", "a,b"], "--omega"),
    (["demo", "--axis", "7"], "--axis must be an integer in 1..5, got 7"),
    (["demo", "--convention", "nope"], "argument --convention: invalid choice: 'nope'"),
])
def test_demo_bad_options(capsys, argv, msg):
    code, _, err = _run(capsys, argv)
    assert code == 2 and msg in err


def test_kappa_is_read_exactly_and_worded_alike_in_demo_and_scene(capsys):
    code, out, _ = _run(capsys, ["demo", "--ascii", "--no-png", "--t-end", "1", "--kappa", "(3/4)**2 - 0.1"])
    assert code == 0 and "kappa = 37/80," in out  # decimal literals are exact: 9/16 - 1/10
    assert "I_15 = 7769/6400" in out              # 1 + kappa^2 = 1 + 1369/6400, exact
    errors = []
    for cmd in ("demo", "scene"):
        code, out, err = _run(capsys, [cmd, "--kappa", "abc"])
        assert code == 2 and out == ""
        errors.append(err.split(": error: ", 1)[1])
    assert errors[0] == errors[1] and errors[0].startswith("--kappa='abc' cannot be read")


def test_choices_ignore_case_like_the_python_api():
    from hyperrotor.cli import build_parser

    parser = build_parser()
    assert parser.parse_args(["bench", "--method", "dop853", "--method", "Splitting8"]).method == ["DOP853",
                                                                                                  "splitting8"]
    assert parser.parse_args(["demo", "--convention", "STANDARD"]).convention == "standard"
    args = parser.parse_args(["scene", "--shape", "Simplex", "--inertia", "BOX"])
    assert (args.shape, args.inertia) == ("simplex", "box")


# Payloads (os.system, 9**9**9**9, dunders, ...) through every CLI option that takes text:
# tests/safety/test_payloads.py walks build_parser() (#21).


def test_help_lists_subcommands(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--help"])
    assert exc.value.code == 0
    out = capsys.readouterr().out
    for name in SUBCOMMANDS:
        assert name in out


def test_missing_subcommand_is_an_error(capsys):
    assert main([]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "the following arguments are required: COMMAND" in err


def test_demo_motion_matches_closed_form_and_writes_png(capsys, tmp_path):
    png = tmp_path / "motion.png"
    code, out, _ = _run(capsys, ["demo", "--ascii", "--t-end", "50", "--png", str(png)])
    assert code == 0
    errs = {m.group(1): float(m.group(2)) for m in
            re.finditer(r"(splitting8|DOP853)\s+rtol=\S+: max relative error vs closed form = (\S+),", out)}
    assert set(errs) == {"splitting8", "DOP853"}
    assert errs["splitting8"] < 1e-10 and errs["DOP853"] < 1e-7
    # the frequencies printed are the closed forms after eq. (118); recompute them from the eigenvalues
    from hyperrotor.classical import quartet_matrix, quartet_theta
    omega = _vector(out, "omega")
    lam = np.sort(np.abs(np.linalg.eigvals(quartet_theta(0.5) * quartet_matrix(omega, 5)).imag))[::-1]
    np.testing.assert_allclose(_vector(out, "frequencies Omega_1, Omega_2 (after eq. 118)"), lam[::2], rtol=1e-12)
    assert png.stat().st_size > 10_000 and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_demo_can_run_twice_and_owns_only_its_default_png(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # the README's command, pasted twice: the demo replaces its own picture
    for replaced in (False, True):
        code, out, err = _run(capsys, ["demo", "--ascii", "--t-end", "2"])
        assert code == 0, err
        assert ("PNG of the motion written to hyperrotor-demo.png (replacing the earlier one)" in out) == replaced
        assert _files(tmp_path) == ["hyperrotor-demo.png"]
    (tmp_path / "hyperrotor-demo.png").write_text("not a demo picture")  # not its own: kept
    code, out, err = _run(capsys, ["demo", "--ascii", "--t-end", "2"])
    assert code == 2 and "the demo's picture 'hyperrotor-demo.png' (the default of --png) exists; pass --force" in err
    assert (tmp_path / "hyperrotor-demo.png").read_text() == "not a demo picture"


def test_demo_bad_t_end(capsys):
    code, _, err = _run(capsys, ["demo", "--no-png", "--t-end", "-1"])
    assert code == 2 and "--t-end" in err


@pytest.mark.parametrize("argv,route", [
    (["--inertia", "quartet"], "closed-form:quartet"),
    (["--inertia", "box", "--lock", "5", "--shape", "simplex"], "reduced:axes(1,2,3,4)+integrate"),
    (["--inertia", "equal", "--shape", "ellipsoid", "--N", "4"], "closed-form:equal"),
])
def test_scene_writes_png_and_takes_the_minimal_route(capsys, tmp_path, argv, route):
    out_png = tmp_path / "scene.png"
    code, out, err = _run(capsys, ["scene", *argv, "--frames", "8", "--output", str(out_png)])
    assert code == 0, err
    assert f"route '{route}" in out
    assert out_png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_scene_html_is_the_library_page(capsys, tmp_path):
    page = tmp_path / "scene.html"
    code, out, err = _run(capsys, ["scene", "--frames", "5", "--output", str(page)])
    assert code == 0, err
    assert f"written: {page}" in out and _files(tmp_path) == ["scene.html"]
    html = page.read_text()
    # booleans, not the 3 MB page, in the assertions (pytest's diff of such a string takes minutes)
    starts_as_html = html.lstrip().lower().startswith(("<!doctype html>", "<html"))  # plotly 5 omits the doctype
    assert starts_as_html and ("Plotly.newPlot" in html) is True
    loads_nothing = (re.search(r"<script[^>]*\bsrc\s*=", html, re.I) is None
                     and re.search(r"<link[^>]*\bhref\s*=", html, re.I) is None)
    # self-contained: plotly.js is inside (the bundle's own text may say src="http)
    assert loads_nothing and len(html) > 3_000_000
    assert len(re.findall(r'"traces"\s*:\s*\[0,\s*1\]', html)) == 5  # one animation frame per time (--frames 5)


def _first_frame_extent(html: str) -> np.ndarray:
    """max |x|, |y|, |z| of the body points of a page's first frame (its "points" trace)."""
    data = html[html.index("Plotly.newPlot"):]
    assert re.search(r'"name"\s*:\s*"points"', data), "no points trace"
    extent = []
    for key in "xyz":  # (the first "x", "y", "z" arrays of the figure are the edges', over the same points)
        vals = re.search(r'"%s"\s*:\s*\[([^\]]*)\]' % key, data).group(1).split(",")
        extent.append(max(abs(float(v)) for v in vals if v.strip() not in ("null", "")))
    return np.array(extent)


@pytest.mark.parametrize("argv, extent", [
    # the box of sides 1..5 on axes 1, 4, 5: half-edges 0.2, 0.8, 1.0 (was the unit cube: 1, 1, 1)
    (["--inertia", "box", "--sides", "1,2,3,4,5", "--axes", "1,4,5"], [0.2, 0.8, 1.0]),
    # the quartet J = (1, 1, 1, 1, kappa^2): flattened to kappa = 0.5 along axis 5
    (["--kappa", "0.5", "--axes", "3,4,5"], [1.0, 1.0, 0.5]),
    (["--kappa", "0", "--axes", "1,2,5"], [1.0, 1.0, 0.0]),   # flat: every edge still drawn
    (["--inertia", "equal", "--axes", "1,2,3"], [1.0, 1.0, 1.0]),
])
def test_scene_draws_the_simulated_body_in_its_proportions(capsys, tmp_path, argv, extent):
    """The drawn cube is the body simulated (a review: a 1x2x3x4x5 box was drawn as the unit cube): at t ~ 0
    (t_end 1e-9) the page's points reach sqrt(J_i / max J) along each drawn axis."""
    page = tmp_path / "s.html"
    code, out, err = _run(capsys, ["scene", *argv, "--t-end", "1e-9", "--frames", "2", "--output", str(page)])
    assert code == 0, err
    assert "32 body points, 80 edges" in out
    assert np.allclose(_first_frame_extent(page.read_text()), extent, rtol=0, atol=1e-6)


def test_scene_body_stretch_gives_the_mass_tensor():
    """The stretched unit shapes (cube, simplex, sphere: second moments proportional to the identity) have the
    mass tensor of the body, up to a factor: their second moments sum_p x_pi^2 are proportional to J."""
    from hyperrotor import Inertia
    from hyperrotor.classical import ellipsoid_points, hypercube_vertices, simplex_vertices
    from hyperrotor.cli.scene import body_stretch

    for inertia in (Inertia.box(1.0, [1.0, 2.0, 3.0, 4.0, 5.0]), Inertia.quartet(0.3, axis=2), Inertia.equal(5)):
        J = np.asarray(inertia.mass_tensor, dtype=float)
        d = body_stretch(inertia)
        for pts in (hypercube_vertices(5), simplex_vertices(5)):
            second = np.sum((pts * d) ** 2, axis=0)
            assert np.allclose(second / second.max(), J / J.max(), rtol=1e-12, atol=0)
        sphere = ellipsoid_points(np.ones(5), 20000, rng=1) * d  # (a sample: moments to its ~1% noise)
        second = np.sum(sphere**2, axis=0)
        assert np.allclose(second / second.max(), J / J.max(), rtol=0.05, atol=0.02)


def test_scene_default_omega_is_one_size_at_every_n(capsys, tmp_path):
    """The default --omega, 0.1 ... 1 at N = 5, is scaled to max |omega| = 1 for more planes: its page at N = 115
    was refused ("--omega values too large for this body, max |omega| = 655.5") without any --omega given."""
    from hyperrotor.cli.scene import default_omega

    assert np.array_equal(default_omega(10), 0.1 * np.arange(1, 11))
    for n in (3, 6, 45, 6555):
        w = default_omega(n)
        assert w.max() == pytest.approx(min(1.0, 0.1 * n), rel=1e-15) and np.all(np.diff(w) > 0)
    page = tmp_path / "d.html"
    code, out, err = _run(capsys, ["scene", "--N", "115", "--shape", "simplex", "--frames", "2", "--output",
                                   str(page)])
    assert code == 0, err
    assert "116 body points, 6670 edges" in out


def test_scene_unreachable_accuracy_names_the_command_options(capsys, tmp_path):
    """A motion whose accuracy cannot be reached (the 3D quartet over 3e7: round-off) fails in the command's words,
    not with the library's advice of a larger rtol, which the command has no option for."""
    code, out, err = _run(capsys, ["scene", "--N", "3", "--t-end", "3e7", "--frames", "2", "--output",
                                   str(tmp_path / "x.png")])
    assert code == 1 and out == "" and _files(tmp_path) == []
    assert "the motion over --t-end 30000000 cannot be integrated to its accuracy" in err
    assert "choose a shorter --t-end" in err and "Ask for a larger rtol" not in err


def test_demo_unreachable_accuracy_names_the_command_options(capsys, tmp_path, monkeypatch):
    """A stiff quartet over a long run (--kappa 3000 --t-end 300: splitting8 at rtol 1e-12 meets round-off after
    three re-runs, 10 s) failed with the library's advice of a larger rtol, which the demo has no option for."""
    import hyperrotor.demo
    from hyperrotor.classical import UnreachableAccuracyError

    def unreachable(*args, **kwargs):
        raise UnreachableAccuracyError("simulate: rtol = 1e-12 was not reached after 3 re-runs at shorter steps "
                                       "(...); reachable accuracy about 1e-12 at reasonable cost. Ask for a larger "
                                       "rtol or a shorter run")

    monkeypatch.setattr(hyperrotor.demo, "compare_quartet_motion", unreachable)
    code, out, err = _run(capsys, ["demo", "--no-png", "--kappa", "3000", "--t-end", "300"])
    assert code == 1 and "(28)" in out  # (the equations were printed before the motion)
    assert ("the motion over --t-end 300 with --kappa 3000 cannot be integrated to its accuracy: simulate: rtol = "
            "1e-12 was not reached") in err
    assert "choose a smaller --kappa or a shorter --t-end" in err and "Ask for a larger rtol" not in err


def test_demo_price_follows_the_speed_of_the_motion(capsys):
    """The motion over t_end at omega0 is the one over s t_end at omega0 / s: omega0 of 1e-60 over 1e10 was refused
    as 5.8 days (a per-time constant that did not scale with omega0), and runs in about 2 s."""
    from hyperrotor.demo import DEMO_OMEGA, quartet_motion_seconds

    base = quartet_motion_seconds(0.5, DEMO_OMEGA, 200.0).seconds
    for s in (1e-60, 1e-3, 1e3):
        slow = quartet_motion_seconds(0.5, np.array(DEMO_OMEGA) * s, 200.0 / s).seconds
        assert slow == pytest.approx(base, rel=1e-9)
    code, out, err = _run(capsys, ["demo", "--no-png", "--omega=" + ",".join(f"{w * 1e-60:g}" for w in DEMO_OMEGA),
                                   "--t-end", "1e10"])
    assert code == 0, err


def test_library_budgets_are_raised_for_the_scene_s_points_and_edges(capsys, tmp_path):
    """The points and edges are built under the command's memory budget (--max-memory, default 2 GiB), as the
    motion is: with the library's budgets at 100 kB, the edges of the 8-cube (245 kB) were refused, naming a
    --max-memory that was not the limit."""
    with hr.options(max_memory_bytes=1e5, max_output_bytes=1e5):
        for out in ("c.png", "c.html"):
            code, _, err = _run(capsys, ["scene", "--N", "8", "--frames", "2", "--output", str(tmp_path / out)])
            assert code == 0, err


def test_a_warning_is_reported_when_raised_even_if_the_work_fails(capsys, tmp_path, monkeypatch):
    """A warning is one line on stderr as it is raised (the slow-run warning came after the run it announced, and
    none came when the work failed later)."""
    import hyperrotor.plotting as plotting

    def failing(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(plotting, "save_projection_frames", failing)
    with hr.options(slow_run_warning_seconds=1e-9):
        code, _, err = _run(capsys, ["scene", "--inertia", "box", "--frames", "4", "--output",
                                     str(tmp_path / "s.png")])
    assert code == 1
    lines = err.splitlines()
    warned = [k for k, line in enumerate(lines) if "warning: UserWarning: simulate: 'splitting8' at rtol" in line
              or "warning:" in line and "needs about" in line]
    failed = [k for k, line in enumerate(lines) if "failed: disk full" in line]
    assert warned and failed and warned[0] < failed[0], err


def test_scene_help_mentions_html(capsys):
    with pytest.raises(SystemExit):
        main(["scene", "--help"])
    assert "FILE.html (interactive page" in " ".join(capsys.readouterr().out.split())


def test_scene_gif(capsys, tmp_path):
    gif = tmp_path / "scene.gif"
    code, _, err = _run(capsys, ["scene", "--frames", "4", "--output", str(gif)])
    assert code == 0, err
    assert gif.read_bytes()[:6] == b"GIF89a"


@pytest.mark.parametrize("argv,msg", [
    (["scene", "--axes", "1,2"], "--axes must be three different axes"),
    (["scene", "--axes", "1,2,9"], "--axes must be three different axes in 1..5"),
    (["scene", "--lock", "0"], "--lock axes must be in 1..5"),
    (["scene", "--omega", "1,2,3"], "needs N(N-1)/2 = 10 components"),
    (["scene", "--output", "x.jpg"], "--output 'x.jpg' has extension '.jpg'; allowed: .png, .gif, .html"),
    (["scene", "--N", "2"], "--N must be an integer in 3..1000, got 2"),
    (["scene", "--frames", "1"], "--frames must be an integer >= 2, got 1"),
])
def test_scene_bad_options(capsys, argv, msg):
    code, _, err = _run(capsys, argv)
    assert code == 2 and msg in err and err.count("\n") == 1


def test_verify_json_matches_function(capsys):
    import json

    code, out, _ = _run(capsys, ["verify", "--json", "--section", "euler"])
    assert code == 0
    items = json.loads(out)
    direct = hr.verify_paper(["euler"])
    assert [(d["equation"], d["status"]) for d in items] == [(v.equation, v.status) for v in direct]
    assert {d["status"] for d in items} <= {"holds", "typo", "claim-false", "not-checkable"}
    status = {d["equation"]: d["status"] for d in items}
    assert all(status[str(n)] == "holds" for n in range(28, 38))  # eqs. (28)-(37) are right as printed
    assert status["38"] != "holds"                                # the -lambda^5 term is missing


def test_verify_bad_section(capsys):
    assert main(["verify", "--section", "nope"]) == 2
    err = capsys.readouterr().err
    assert "invalid choice: 'nope'" in err and err.count("\n") == 1


# ----------------------------------------------------------------------------
# The command line as a user meets it (issue #15): a subprocess per finding,
# asserting the exit status, a one-line stderr and the files present afterwards.
# ----------------------------------------------------------------------------
def _cli(args, cwd, timeout=300, **kw):
    """Run ``python -m hyperrotor.cli *args`` in ``cwd``; returns (status, stdout, stderr)."""
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONWARNINGS="ignore")
    p = subprocess.run([sys.executable, "-m", "hyperrotor.cli", *map(str, args)], cwd=cwd, env=env,
                       capture_output=True, text=True, timeout=timeout, **kw)
    return p.returncode, p.stdout, p.stderr


def _one_line(err):
    """stderr is exactly one line, with no traceback."""
    assert err.endswith("\n") and err.count("\n") == 1, repr(err)
    assert "Traceback" not in err
    return err


def _files(folder):
    return sorted(p.name for p in folder.iterdir())


#: The findings of issue #15 that used to end in a traceback, a wrong exit status or work done for nothing.
FINDINGS = [
    (["demo", "--png", "x.txt"], ["--png 'x.txt'", "'.txt'", "allowed: .png"]),
    (["demo", "--png", "/nonexistent/d/x.png"], ["'/nonexistent/d'", "does not exist"]),  # was exit 0
    (["verify", "--markdown", "-o", "/nonexistent/r.md"], ["'/nonexistent'", "does not exist"]),
    (["scene", "--output", "/nonexistent/x.png"], ["'/nonexistent'", "does not exist"]),
    (["bench", "--output", "/nonexistent/d/b"], ["'/nonexistent/d'", "does not exist"]),  # was: after the run
    (["scene", "--N", "40"], ["--N 40", "TiB of memory", "budget of 2 GiB", "--max-memory"]),  # was 8 TiB alloc
    (["bench", "--error", "-1"], ["--error must be finite and > 0, got -1.0"]),  # was accepted
]

#: More refusals, checked in-process (same code path, no interpreter start-up).
MORE = [
    (["verify", "--json", "-o", "r.md"], ["'.md'", "allowed: .json"]),
    (["scene", "--output", "x.jpg"], ["'.jpg'", "allowed: .png, .gif, .html"]),
    (["bench", "--repeats", "0"], ["--repeats must be an integer >= 1, got 0"]),
    (["bench", "--error", "2"], ["--error is a relative error level and must be < 1, got 2.0"]),
    (["scene", "--frames", "100000000", "--shape", "simplex"], ["GiB of memory", "budget", "fewer --frames"]),
    (["bench", "--repeats", "100000"], ["days", "budget of 10 min", "--max-seconds"]),
    (["demo", "--t-end", "1e9"], ["--t-end 1000000000", "budget"]),
    (["scene", "--inertia", "box", "--sides=-2,1,1,1,1"], ["--sides", "got [-2.0]"]),
    (["scene", "--sides=1,2"], ["--sides applies to --inertia box only"]),
    (["scene", "--kappa", "nan"], ["--kappa='nan' cannot be read", "names are not allowed"]),
    (["scene", "--frames", "x"], ["--frames='x' cannot be read"]),
    (["scene", "--N", "5.5"], ["--N must be an integer, got '5.5'"]),
    (["scene", "--colour-axis", "2"], ["--colour-axis 2 is one of the drawn --axes"]),
    (["scene", "--max-seconds", "-1"], ["--max-seconds must be finite and > 0, got -1.0"]),
    (["scene", "--max-memory", "lots"], ["--max-memory='lots' cannot be read", "a size is a number with an optional "
                                                                                "unit K, M, G or T"]),
    (["scene", "--kappa", "1e300"], ["--kappa must have magnitude <= 1e+100, got 1e+300"]),
    (["scene", "--N", "1000000000"], ["--N must be an integer in 3..1000, got 1000000000"]),  # the library's limit
    (["scene", "--inertia", "box", "--sides=1e100,1,1,1,1"], ["--sides values must be in [1e-50, 1e50]"]),
    (["scene", "--max-memory", "0.5"], ["--max-memory must be a size of at least one byte, got '0.5'"]),  # (was 0 B)
    (["demo", "--png", "q.png", "--no-png"], ["--png 'q.png' and --no-png contradict each other"]),
    (["demo", "--bogus"], ["unrecognized arguments: --bogus (see 'hyperrotor demo --help')"]),  # (was hyperrotor)
    (["scene", "--inertia", "box", "--sides=1e-200,1,1,1,1"], ["--sides values must be in [1e-50, 1e50]"]),
    # an integrated motion is priced before it runs (#22: this ran 506 s with --max-seconds 10)
    (["scene", "--inertia", "box", "--t-end", "1e6", "--max-seconds", "10"],
     ["scene --t-end 1000000 (", "integration steps of splitting8", "over the budget of 10 s (--max-seconds"]),
    (["scene", "--inertia", "box", "--t-end", "1e6", "--max-steps", "1000"],
     ["integration steps (splitting8), over the budget of 1000 (--max-steps", "raise --max-steps"]),
    (["scene", "--inertia", "box", "--max-steps", "5"], ["over the budget of 5 (--max-steps"]),
    # a body of 19 900 planes: the pricing's own probe is held to what the drawing leaves of --max-seconds (the
    # run's pricing took 42-48 s and 5 GB, session 46); the message names the budget typed, not the remainder
    (["scene", "--N", "200", "--shape", "simplex", "--frames", "2", "--inertia", "box", "--max-seconds", "12"],
     ["the step control's probe of", "that --max-seconds 12 s leaves after the drawing's", "raise --max-seconds"]),
    (["scene", "--N", "3", "--inertia", "box", "--max-seconds", "0.5"], ["would take about", "--max-seconds"]),
    # (session 48, a review of the scene route)
    (["scene", "--inertia", "equal", "--kappa", "garbage"], ["--kappa applies to --inertia quartet only"]),  # was run
    (["scene", "--inertia", "box", "--kappa", "7"], ["--kappa applies to --inertia quartet only"]),
    (["scene", "--lock", "1", "--omega", "1,0,0,0,0,0,0,0,0,0"],  # was zeroed, silently
     ["--omega gives planes of the --lock axes [1] nonzero values (omega_12 = 1):"]),
    (["scene", "--N", "3", "--lock", "3", "--omega", "0,0,0.5"], ["nonzero values (omega_23 = 0.5):"]),
    (["scene", "--t-end", "1e-320", "--frames", "10000"],  # was "failed: ValueError: t must be strictly increasing"
     ["is too short for --frames 10000", "choose a longer --t-end or fewer --frames"]),
    (["scene", "--N", "3", "--t-end", "1e-320", "--frames", "1000"], ["is too short for --frames 1000"]),
    (["scene", "--t-end", "1", "--frames", "16777216"], ["of memory", "fewer --frames"]),  # (no table of times first)
    (["scene", "--N", "3", "--t-end", "1e9", "--max-seconds", "100"],  # the 3D quartet integrates: was not priced
     ["integration steps", "--max-steps"]),
    (["demo", "--omega=1e100,1e100,1,1,1,1,1,1,1,1"], ["fastest frequency 8.49e+99, rate bound 1.79e+100",
                                                        "budget of 10 min"]),
    (["demo", "--kappa", "1e50"], ["fastest frequency 1.18, rate bound 1.11e+50", "budget"]),
    (["demo", "--omega=1e308,1,1,1,1,1,1,1,1,1"], ["--omega must have magnitude <= 1e+100, got 1e+308"]),
    (["demo", "--kappa", "9**9**9**9"], ["--kappa='9**9**9**9' cannot be read", "exponent"]),
    (["demo", "--kappa", "2**(1/2)"], ["--kappa='2**(1/2)' cannot be read", "exact fraction"]),
]


def _check_refusal(args, words, code, out, err, folder):
    assert code == EXIT_CODES["usage"] == 2
    assert out == ""
    _one_line(err)
    assert err.startswith(f"hyperrotor {args[0]}: error: ")
    for w in words:
        assert w in err
    assert "np.float64" not in err
    assert "simulate(" not in err and "hr.options(" not in err  # a CLI user is told the CLI's options
    assert _files(folder) == []  # nothing written, no temporary file left


@pytest.mark.parametrize("args,words", FINDINGS)
def test_bad_argument_or_path_is_one_line_before_any_work(tmp_path, args, words):
    code, out, err = _cli(args, tmp_path)
    _check_refusal(args, words, code, out, err, tmp_path)


@pytest.mark.parametrize("args,words", MORE)
def test_more_refusals_in_process(capsys, tmp_path, monkeypatch, args, words):
    monkeypatch.chdir(tmp_path)
    code, out, err = _run(capsys, args)
    _check_refusal(args, words, code, out, err, tmp_path)


def test_folder_that_is_a_file_or_unwritable(tmp_path):
    (tmp_path / "f").write_text("x")
    code, _, err = _cli(["scene", "--output", "f/x.png"], tmp_path)
    assert code == 2 and "'f' is not a folder" in _one_line(err)
    if os.geteuid() == 0:
        return  # root writes everywhere: no unwritable folder to test with
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        code, _, err = _cli(["verify", "-o", "ro/r.md"], tmp_path)
        assert code == 2 and "cannot write in the folder" in _one_line(err)
        assert _files(ro) == []
    finally:
        ro.chmod(0o700)


@pytest.mark.parametrize("args,target", [
    (["demo", "--ascii", "--png", "out.png"], "out.png"),
    (["verify", "--section", "euler", "-o", "out.md"], "out.md"),
    (["scene", "--frames", "4", "--output", "out.png"], "out.png"),
    (["bench", "--problem", "euler-poinsot", "--method", "splitting8", "--repeats", "1", "--output", "out"], "out.csv"),
])
def test_existing_output_is_kept_without_force(tmp_path, args, target):
    (tmp_path / target).write_text("old")
    code, out, err = _cli(args, tmp_path)
    assert code == 2 and out == ""
    assert f"'{target}' exists; pass --force to replace it" in _one_line(err)
    assert (tmp_path / target).read_text() == "old"
    assert _files(tmp_path) == [target]


def test_force_replaces_the_file(tmp_path):
    (tmp_path / "out.md").write_text("old")
    code, out, err = _cli(["verify", "--section", "euler", "-o", "out.md", "--force"], tmp_path)
    assert code == 0 and err == ""
    assert "written: out.md" in out
    from hyperrotor.paper.verify import render, verify

    assert (tmp_path / "out.md").read_text() == render(verify(["euler"]), format="markdown").rstrip("\n") + "\n"
    assert _files(tmp_path) == ["out.md"]
    assert (tmp_path / "out.md").stat().st_mode & 0o777 == 0o666 & ~_umask()


def _umask():
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def test_closed_pipe_ends_quietly(tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONWARNINGS="ignore")
    p = subprocess.Popen([sys.executable, "-m", "hyperrotor.cli", "demo", "--no-png"], cwd=tmp_path, env=env,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    p.stdout.close()  # the reader is gone before the first line (as 'hyperrotor demo | head -0')
    _, err = p.communicate(timeout=120)
    assert p.returncode == EXIT_CODES["broken-pipe"] == 141
    assert err == b""


BENCH_QUICK = ["bench", "--problem", "euler-poinsot", "--method", "splitting8", "--repeats", "1"]


def test_bench_output_stem_with_extension(tmp_path):
    code, out, err = _cli([*BENCH_QUICK, "--output", "b.png"], tmp_path)
    assert code == 0 and err == ""
    assert _files(tmp_path) == ["b.csv", "b.png"]  # not b.png.csv / b.png.png
    assert "relative error" in out


def test_bench_output_folder(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "d").mkdir()
    code, out, err = _run(capsys, [*BENCH_QUICK, "--output", "d/"])
    assert code == 0, err
    assert err == ""
    assert _files(tmp_path / "d") == ["hyperrotor-bench.csv", "hyperrotor-bench.png"]  # no hidden .csv/.png


def test_bench_paths_naming():
    assert bench_paths("b") == (Path("b.csv"), Path("b.png"))
    assert bench_paths("b.png") == bench_paths("b.CSV") == (Path("b.csv"), Path("b.png"))
    assert bench_paths("runs/x.2026") == (Path("runs/x.2026.csv"), Path("runs/x.2026.png"))
    assert bench_paths("new/") == (Path("new/hyperrotor-bench.csv"), Path("new/hyperrotor-bench.png"))


@pytest.mark.parametrize("stem,ext", [(".csv", ".csv"), (".png", ".png"), ("d/.csv", ".csv"), (".CSV", ".CSV"),
                                      (" .csv", ".csv"), ("..png", ".png")])
def test_bench_output_without_a_stem_is_refused_before_any_work(capsys, tmp_path, monkeypatch, stem, ext):
    """--output .csv wrote the hidden files .csv.csv and .csv.png (d/.csv: d/.csv.csv, ...): a stem with no name
    before the extension is refused with status 2 and one line, before the bench runs and with no file written."""
    import hyperrotor.bench

    monkeypatch.chdir(tmp_path)
    (tmp_path / "d").mkdir()
    ran = []
    monkeypatch.setattr(hyperrotor.bench, "work_precision", lambda *a, **kw: ran.append(a) or [])
    code, out, err = _run(capsys, [*BENCH_QUICK, "--output", stem])
    assert code == EXIT_CODES["usage"] == 2 and out == "" and ran == []
    assert _one_line(err) == (f"hyperrotor bench: error: --output needs a file stem or a folder, got {stem!r} "
                              f"(no name before {ext}); e.g. --output b writes b.csv and b.png\n")
    assert _files(tmp_path) == ["d"] and _files(tmp_path / "d") == []


def test_bench_paths_keep_the_documented_names(tmp_path, monkeypatch):
    """The refusal of a bare extension leaves every name of the --help as it was (a dot-stem included)."""
    from hyperrotor.cli._common import UsageError

    monkeypatch.chdir(tmp_path)
    (tmp_path / "d").mkdir()
    assert bench_paths("out/b") == (Path("out/b.csv"), Path("out/b.png"))
    assert bench_paths("b.PNG") == bench_paths("b") == (Path("b.csv"), Path("b.png"))
    assert bench_paths("d") == bench_paths("d/") == (Path("d/hyperrotor-bench.csv"), Path("d/hyperrotor-bench.png"))
    assert bench_paths(".") == (Path("hyperrotor-bench.csv"), Path("hyperrotor-bench.png"))
    assert bench_paths(".hidden") == (Path(".hidden.csv"), Path(".hidden.png"))  # a stem, asked for explicitly
    (tmp_path / ".csv").mkdir()
    assert bench_paths(".csv") == (Path(".csv/hyperrotor-bench.csv"), Path(".csv/hyperrotor-bench.png"))  # a folder
    with pytest.raises(UsageError, match=r"got '\.\.\.' \(a name of dots and spaces only\)"):
        bench_paths("...")
    with pytest.raises(UsageError, match="got an empty string"):
        bench_paths("")
    with pytest.raises(UsageError, match="got ' '"):
        bench_paths(" ")


def test_progress_only_when_asked_or_on_a_terminal(capsys, tmp_path):
    code, _, err = _cli(["scene", "--frames", "4", "--output", "b.png", "--progress"], tmp_path)
    assert code == 0 and "scene: drawing snapshots" in err and "/4 [" in err
    # in-process, stderr is pytest's capture (not a terminal): no bar unless asked
    code, _, err = _run(capsys, ["scene", "--frames", "4", "--output", str(tmp_path / "a.png")])
    assert code == 0 and err == ""
    code, _, err = _run(capsys, ["verify", "--section", "euler", "--progress"])
    assert code == 0 and "verify: sections" in err and "/1 [" in err  # the bar of 1 section (drawn at start)
    # an integrated motion (box inertia) shows the integration's own bar before the drawing
    code, _, err = _cli(["scene", "--inertia", "box", "--frames", "4", "--output", "c.png", "--progress"], tmp_path)
    assert code == 0 and "simulate:" in err and "step" in err
    assert err.index("simulate:") < err.index("scene: drawing snapshots")


def test_plain_numbers_in_output_and_messages(tmp_path):
    code, out, err = _cli(["demo", "--ascii", "--no-png"], tmp_path)
    assert code == 0
    # d omega_15/dt = (I_12 - I_25)/I_15 ... = -0.33 exactly in decimal; no float noise, no numpy reprs
    assert "d omega/dt = [0, 0, 0, -0.33, 0, 0, -0.606, 0, -0.222, 0.756]" in out
    assert "np." not in out and "0.32999999" not in out


def test_debug_shows_the_traceback(tmp_path):
    code, _, err = _cli(["scene", "--N", "40", "--debug"], tmp_path)
    assert code == 2 and "Traceback" in err and err.rstrip().splitlines()[-1].startswith("hyperrotor scene: error:")


def test_runtime_failure_exits_1_and_leaves_no_file(capsys, tmp_path, monkeypatch):
    import hyperrotor.plotting as plotting

    old = tmp_path / "s.png"
    old.write_bytes(b"old")

    def broken(path, *a, **k):
        with open(path, "wb") as fh:  # half a file, then a failure
            fh.write(b"\x89PNG partial")
        raise RuntimeError("disk full")

    monkeypatch.setattr(plotting, "save_projection_frames", broken)
    code, out, err = _run(capsys, ["scene", "--frames", "4", "--output", str(old), "--force"])
    assert code == EXIT_CODES["failed"] == 1
    assert err.count("\n") == 1 and "failed: disk full" in err
    assert old.read_bytes() == b"old" and _files(tmp_path) == ["s.png"]


def test_scene_estimate_of_the_40_cube():
    from hyperrotor._cost_models import SCENE_START_BYTES
    from hyperrotor._pricing import estimate

    memory, seconds = (c.amount for c in estimate("scene", shape="cube", N=40, frames=60))
    assert memory >= 2**40 * 40 * 8  # the vertex array alone: 8 TiB
    small, quick = (c.amount for c in estimate("scene", shape="cube", N=5, frames=60))
    assert small - SCENE_START_BYTES < 2**27 and quick < 10


@pytest.mark.slow
def test_scene_12_cube_shows_progress_and_finishes(tmp_path):
    # was: over a minute with no output (24576 edges drawn one plot call each); now one collection per frame
    code, out, err = _cli(["scene", "--N", "12", "--output", "c12.png", "--progress"], tmp_path)
    assert code == 0
    assert "4096 body points, 24576 edges" in out and "written: c12.png" in out
    assert "scene: drawing snapshots" in err and "Traceback" not in err
    assert _files(tmp_path) == ["c12.png"]
    assert (tmp_path / "c12.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_file_appearing_during_the_run_is_not_clobbered(capsys, tmp_path, monkeypatch):
    import hyperrotor.plotting as plotting

    target = tmp_path / "s.png"
    real = plotting.save_projection_frames

    def racing(path, *a, **k):
        out = real(path, *a, **k)
        target.write_bytes(b"written by someone else meanwhile")
        return out

    monkeypatch.setattr(plotting, "save_projection_frames", racing)
    code, out, err = _run(capsys, ["scene", "--frames", "4", "--output", str(target)])
    assert code == 1 and out == ""
    assert err.count("\n") == 1 and "appeared while this command ran" in err
    assert target.read_bytes() == b"written by someone else meanwhile" and _files(tmp_path) == ["s.png"]


def test_long_output_names(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    name = "r" * 246 + ".md"  # 249 characters: legal (the temporary name is shortened, not the target)
    code, out, err = _run(capsys, ["verify", "--section", "euler", "-o", name])
    assert code == 0, err
    assert _files(tmp_path) == [name] and out == f"written: {name} (" + out.split(" (", 1)[1]
    too_long = "r" * 257 + ".md"  # 260 characters: over NAME_MAX, a usage error before any work
    code, out, err = _run(capsys, ["verify", "--section", "euler", "-o", too_long])
    assert code == 2 and out == ""
    assert "is 260 bytes long; the file system allows at most 255" in _one_line(err)
    assert _files(tmp_path) == [name]


class _FullDisk:
    """A standard output that fails as /dev/full does."""

    def write(self, text):
        raise OSError(28, "No space left on device")

    def flush(self):
        pass


def test_stdout_failing_after_the_files_were_written_says_so(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(sys, "stdout", _FullDisk())
    code = main(["verify", "--section", "euler", "-o", "r.md"])
    err = capsys.readouterr().err
    assert code == EXIT_CODES["failed"] == 1
    assert "No space left on device" in _one_line(err)
    assert "(written before the failure, complete: r.md)" in err
    assert _files(tmp_path) == ["r.md"] and (tmp_path / "r.md").read_text().startswith("# Verification")


def test_force_replaces_a_symlink_never_writes_through_it(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # #21 §4: the report used to be written through a symlink
    (tmp_path / "target.md").write_text("someone else's file")
    (tmp_path / "r.md").symlink_to(tmp_path / "target.md")
    code, _, err = _run(capsys, ["verify", "--section", "euler", "-o", "r.md"])
    assert code == 2 and "'r.md' exists; pass --force" in err
    code, _, err = _run(capsys, ["verify", "--section", "euler", "-o", "r.md", "--force"])
    assert code == 0, err
    assert not (tmp_path / "r.md").is_symlink() and (tmp_path / "r.md").read_text().startswith("# Verification")
    assert (tmp_path / "target.md").read_text() == "someone else's file"
    (tmp_path / "dangling.md").symlink_to(tmp_path / "nowhere.md")  # a link to nothing: replaced too (was refused
    code, _, err = _run(capsys, ["verify", "--section", "euler", "-o", "dangling.md", "--force"])  # as not a file)
    assert code == 0, err
    assert not (tmp_path / "dangling.md").is_symlink() and not (tmp_path / "nowhere.md").exists()


def test_a_repeated_section_is_verified_once(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    outs = []
    for argv in (["--section", "euler"], ["--section", "euler", "--section", "euler"]):
        code, out, err = _run(capsys, ["verify", *argv, "-o", "r.md", "--force"])
        assert code == 0, err
        outs.append(re.search(r"\((\d+) items\)", out).group(1))
    assert outs[0] == outs[1]  # (62 items for 31)


def test_budget_refusals_are_usage_errors_in_cli_words(capsys, tmp_path, monkeypatch):
    """scene --N over the library's dimension limit, and a body whose Euler tables exceed the memory budget, were
    refused by the library during the work: exit 1 with hr.options(...) advice (the docs promise exit 2 and the
    command-line option). Now before any work; a refusal that still comes from the library is worded alike."""
    from hyperrotor import _pricing
    from hyperrotor.cli._common import budget_message

    monkeypatch.chdir(tmp_path)
    code, _, err = _run(capsys, ["scene", "--N", "5000", "--frames", "2", "--output", "a.png"])
    assert code == 2 and "--N must be an integer in 3..1000, got 5000" in err
    code, _, err = _run(capsys, ["scene", "--N=1e400", "--frames", "2", "--output", "a.png"])
    assert code == 2 and "--N must have magnitude <= 1e+100, got an integer of 401 digits" in err
    code, _, err = _run(capsys, ["scene", "--N", "460", "--shape", "simplex", "--frames", "2", "--output", "a.png"])
    assert code == 2 and "GiB of memory, over the budget of 2 GiB (--max-memory" in err and _files(tmp_path) == []
    with pytest.raises(hr.BudgetError) as info:
        _pricing.check("RigidBody", N=460)
    text = budget_message(info.value)
    assert "hr.options" not in text and "over the budget --max-memory = " in text
    assert text.endswith("; choose a smaller run or raise --max-memory")
    with pytest.raises(hr.BudgetError) as info:
        hr.conventions.check_dimension(5000)
    assert budget_message(info.value).endswith("the library's limit max_dimension = 1000; choose a smaller run")


def test_demo_refuses_a_body_at_rest_before_printing(capsys):
    for omega in ("0,0,0,0,0,0,0,0,0,0", "1e-170,0,0,0,0,0,0,0,0,0"):
        code, out, err = _run(capsys, ["demo", "--no-png", "--t-end", "1", f"--omega={omega}"])
        assert code == 2 and out == "" and "--omega must set the body in motion" in err


#: The end of the budget refusal of a demo: the options that drive its cost, the largest factor first.
_KAPPA_ADVICE = ("choose a --kappa of smaller magnitude (the cost grows as |kappa| there), a shorter --t-end "
                 "or a smaller --omega")


@pytest.mark.parametrize("kappa,shown,rate", [("1e7", "10000000", "1.11e+07"), ("1e8", "100000000", "1.11e+08"),
                                              ("-1e7", "-10000000", "1.11e+07")])
def test_demo_budget_refusal_names_kappa_when_kappa_drives_the_cost(capsys, tmp_path, monkeypatch, kappa, shown,
                                                                      rate):
    """A large --kappa with the default --t-end and --omega was refused with the advice 'choose a shorter --t-end or
    smaller --omega' only, although kappa is what makes the run expensive: the advice names --kappa first."""
    monkeypatch.chdir(tmp_path)
    code, out, err = _run(capsys, ["demo", f"--kappa={kappa}"])
    assert code == EXIT_CODES["usage"] == 2 and out == ""
    assert _one_line(err).startswith(f"hyperrotor demo: error: demo --kappa {shown} --t-end 200 (fastest frequency "
                                     f"1.18, rate bound {rate}) would take about ")
    assert ", over the budget of 10 min (--max-seconds, default hr.options['cli_max_seconds']); " in err
    assert err.endswith("; " + _KAPPA_ADVICE + "\n")
    assert _files(tmp_path) == []  # no PNG, no temporary file


def test_demo_budget_advice_follows_the_cost_model(capsys, tmp_path, monkeypatch):
    """The advice is true of the cost model: |kappa| far beyond 1 (the step control's rate bound), nothing between
    (the motion's frequency stays below ~|Theta| max|omega|, |Theta| < 1: kappa 3 or 1e-3 is not named, although
    the earlier model priced kappa = 3 at 2x the run, 10 at 15x); t_end and max|omega| linear (omega named unless
    the body hardly turns)."""
    from hyperrotor.demo import quartet_motion_seconds

    cost = [quartet_motion_seconds(k, t_end=1e6).seconds for k in (1e5, 1e6)]
    assert cost[1] / cost[0] == pytest.approx(10, rel=0.05)
    low = [quartet_motion_seconds(k, t_end=1e6).seconds for k in (1e-6, 1 / 2, 1, 3, 10)]
    assert max(low) / min(low) <= 25  # (kappa = 1 does not turn: the constant term alone)
    assert max(low[:2] + low[3:]) / min(low[:2] + low[3:]) <= 2
    monkeypatch.chdir(tmp_path)
    for argv, end in [(["--t-end", "1e9"], "; choose a shorter --t-end or a smaller --omega\n"),  # default kappa 1/2
                      (["--kappa", "1e-3", "--t-end", "1e9"], "; choose a shorter --t-end or a smaller --omega\n"),
                      (["--kappa", "3", "--t-end", "1e7"], "; choose a shorter --t-end or a smaller --omega\n"),
                      (["--kappa", "1e5", "--t-end", "1e4"], "; choose a --kappa of smaller magnitude (the cost grows "
                                                             "as |kappa| there), a shorter --t-end or a smaller "
                                                             "--omega\n"),
                      (["--omega=1e100,1e100,1,1,1,1,1,1,1,1"], "; choose a smaller --omega or a shorter --t-end\n"),
                      (["--omega=1e-3,0,0,0,0,0,0,0,0,0", "--t-end", "1e9"], "; choose a shorter --t-end\n")]:
        code, out, err = _run(capsys, ["demo", *argv])
        assert code == 2 and out == "" and _one_line(err).endswith(end), (argv, err)
        assert ("--kappa" in err) == ("--kappa" in end)  # the run and the advice name kappa only when it drives
    assert _files(tmp_path) == []


#: The library's budget keywords: a command-line user is told the options (--max-steps), never these.
_KEYWORDS = re.compile(r"(?<![\w-])(max_steps|max_seconds|max_memory_bytes|max_output_bytes)(?!\w)")


def test_budget_refusals_name_the_cli_option_never_the_python_keyword(capsys, tmp_path, monkeypatch):
    """#46: "the motion needs about 30 (max_steps), over the budget of 10 (--max-steps)", and a run beyond every
    budget was told "more than any budget max_steps allows; ... or raise --max-steps" (which cannot help)."""
    from hyperrotor.classical.solvers.base import nsub_for
    from hyperrotor.cli._common import budget_message

    monkeypatch.chdir(tmp_path)
    code, out, err = _run(capsys, ["scene", "--inertia", "box", "--max-steps", "10", "--output", "k.png"])
    assert code == 2 and out == "" and not _KEYWORDS.search(_one_line(err)), err
    assert "integration steps, over the budget of 10 (--max-steps); " in err and err.endswith("raise --max-steps\n")
    code, out, err = _run(capsys, ["scene", "--inertia", "box", "--t-end", "1e100", "--output", "k.png"])
    assert code == 2 and out == "" and not _KEYWORDS.search(_one_line(err)), err
    assert "more than any --max-steps value allows; choose a smaller run\n" in err and "raise" not in err
    assert _files(tmp_path) == []
    with pytest.raises(hr.BudgetError) as info:
        nsub_for(np.array([0.0, 1e300]), 1e-300)
    for args, words in [(None, "any --max-steps value allows"),  # a subcommand without --max-steps: what it counts
                        (argparse.Namespace(max_seconds=None), "any budget of integration steps allows")]:
        text = budget_message(info.value, args)
        assert words in text and text.endswith("; choose a smaller run") and not _KEYWORDS.search(text), text


def test_a_locked_scene_on_a_closed_form_route_is_not_priced_as_an_integration(capsys, tmp_path, monkeypatch):
    """#46: scene --lock 1 --t-end 1e8 runs by a closed form (reduced:axes(2,3,4,5)+closed-form:quartet) but was
    refused for 2.99e9 integration steps; the route the scene takes is priced. A locked box still integrates and is
    still priced."""
    monkeypatch.chdir(tmp_path)
    code, out, err = _run(capsys, ["scene", "--lock", "1", "--t-end", "1e8", "--frames", "2", "--output", "a.png"])
    assert code == 0, err
    assert "route 'reduced:axes(2,3,4,5)+closed-form:quartet'" in out
    code, out, err = _run(capsys, ["scene", "--lock", "1", "--inertia", "box", "--t-end", "1e8", "--frames", "2",
                                   "--output", "b.png"])
    assert code == 2 and "integration steps (splitting8), over the budget of 100000000 (--max-steps" in err, err
    assert _files(tmp_path) == ["a.png"]


def test_an_omega_whose_invariants_overflow_is_refused_before_any_work(capsys, tmp_path, monkeypatch):
    """#46: every --omega value within the stated 1e100, but the Casimirs (degree 4 in L) overflow: exit 1 "failed:
    ValueError: casimirs: values too large" after the work started. Now exit 2 before it, naming --omega and the
    range that fits (the library's own computation of the invariants decides)."""
    monkeypatch.chdir(tmp_path)
    omega = "--omega=1e99,1,1,1,1,1,1,1,1,1"
    code, out, err = _run(capsys, ["demo", "--no-png", "--t-end", "1e-100", omega])
    assert code == 2 and out == "" and _one_line(err).startswith("hyperrotor demo: error: --omega values too large "
                                                                 "for this body, max |omega| = 1e+99"), err
    assert "allowed for this body and these proportions: max |omega| <= about 1e76\n" in err
    code, out, err = _run(capsys, ["demo", "--no-png", "--t-end", "1e-100", "--omega=1e76,1,1,1,1,1,1,1,1,1"])
    assert code == 0 and "inf" not in out.replace("Manakov", "").lower(), err  # (the bound is one that works)
    code, out, err = _run(capsys, ["scene", omega, "--output", "ov.html"])
    assert code == 2 and out == "" and "--omega values too large for this body" in _one_line(err), err
    assert _files(tmp_path) == []


def test_max_memory_is_read_by_the_one_parser(capsys, tmp_path, monkeypatch):
    """#46: --max-memory had its own regex and float(): 2**31 refused, 1e400 "at least one byte", 1e308 accepted
    (over the documented 1e100). The number goes through the one parser; the units stay."""
    from hyperrotor.cli._common import byte_size

    assert [byte_size(t) for t in ("2**31", "2G", "2 GiB", "2gb", "500M", "1/2K", "1000000", "3*2**10")] == \
        [2**31, 2**31, 2**31, 2**31, 500 * 2**20, 512, 10**6, 3072]
    monkeypatch.chdir(tmp_path)
    code, out, err = _run(capsys, ["scene", "--max-memory", "2**31", "--frames", "2", "--output", "a.png"])
    assert code == 0, err
    for text, words in [("1e308", "--max-memory must have magnitude <= 1e+100, got 1e+308"),
                        ("1e400", "--max-memory='1e400' cannot be read: the value is too large for a float"),
                        ("1e400G", "--max-memory '1e400G': --max-memory='1e400' cannot be read"),
                        ("0", "--max-memory must be a size of at least one byte, got '0'"),
                        ("2X", "--max-memory='2X' cannot be read")]:
        code, out, err = _run(capsys, ["scene", "--max-memory", text, "--output", "b.png"])
        assert code == 2 and words in _one_line(err), (text, err)
    assert _files(tmp_path) == ["a.png"]


def test_values_double_precision_cannot_hold_are_named_as_typed(capsys):
    """#46: demo --kappa 1e400 said "--kappa must be finite, got inf", bench --error 1e-400 "got 0.0"."""
    for argv, words in [(["demo", "--no-png", "--kappa", "1e400"], "--kappa must have magnitude <= 1e+100, got 1e400"),
                        (["bench", "--error", "1e-400"], "--error 1e-400 is too close to 0 for double precision"),
                        (["demo", "--no-png", "--omega=1e-400,1,1,1,1,1,1,1,1,1"], "--omega 1e-400 is too close to 0")]:
        code, out, err = _run(capsys, argv)
        assert code == 2 and out == "" and words in _one_line(err), (argv, err)
        assert "inf" not in err and "0.0" not in err


@pytest.mark.parametrize("argv,words", [
    (["demo", "--no-png", "--omega=1,,2,3,4,5,6,7,8,9,10"], "--omega '1,,2,3,4,5,6,7,8,9,10': field 2 of 11 is empty"),
    (["demo", "--no-png", "--omega=1,2,3,4,5,6,7,8,9,10,"], "field 11 of 11 is empty"),
    (["scene", "--axes", "1,,2,3"], "--axes '1,,2,3': field 2 of 4 is empty"),
    (["scene", "--lock", ",1"], "--lock ',1': field 1 of 2 is empty"),
    (["scene", "--inertia", "box", "--sides=1,2,3, ,5"], "--sides '1,2,3, ,5': field 4 of 5 is empty"),
])
def test_an_empty_field_of_a_list_is_refused(capsys, tmp_path, monkeypatch, argv, words):
    """#46: demo --omega=1,,2,...,10 was read as 10 values, scene --axes 1,,2,3 as 1,2,3."""
    monkeypatch.chdir(tmp_path)
    code, out, err = _run(capsys, argv)
    assert code == 2 and out == "" and words in _one_line(err), err
    assert _files(tmp_path) == []


def test_verify_writes_its_report_in_one_call(monkeypatch, capsys):
    """#46: `verify | head -1` under pipefail exited 141 one time in three: print() wrote the report, then "\n",
    and a reader gone after the first line broke the second write."""
    class Recorder:
        encoding = "utf-8"

        def __init__(self):
            self.writes = []

        def write(self, text):
            self.writes.append(text)
            return len(text)

        def flush(self):
            pass

        def isatty(self):
            return False

    rec = Recorder()
    monkeypatch.setattr(sys, "stdout", rec)
    assert main(["verify", "--section", "euler"]) == 0
    assert len(rec.writes) == 1 and rec.writes[0].endswith("\n") and rec.writes[0].count("\n") > 5, rec.writes[:3]


def test_demo_summary_is_true_of_the_body_run(capsys):
    """#46: demo --kappa 1 (all ten moments equal) said "the six planes without axis 5 have constant omega" and
    listed ten planes."""
    code, out, _ = _run(capsys, ["demo", "--no-png", "--kappa", "1", "--t-end", "1"])
    summary = out.split("\nsummary: ")[1].split("\n")[0]
    assert code == 0 and "six planes" not in summary
    assert "all plane moments are equal" in summary and "dw/dt = 0 on all 10 planes" in summary
    code, out, _ = _run(capsys, ["demo", "--no-png", "--t-end", "1"])
    summary = out.split("\nsummary: ")[1].split("\n")[0]
    assert "the six planes without axis 5 have constant omega for this body (12, 13, 14, 23, 24, 34);" in summary
    code, out, _ = _run(capsys, ["demo", "--no-png", "--t-end", "1", "--omega=1,2,3,0,0,0,0,0,0,0"])
    summary = out.split("\nsummary: ")[1].split("\n")[0]
    assert summary.endswith("(12, 13, 14, 23, 24, 34); at this omega also 15, 25, 35, 45 (dw/dt = 0 here);")


def test_negative_values_follow_their_option(capsys):
    """argparse reads only '-12' and '-1.5' as values: '--kappa -1/2', '--t-end -1e3', '--kappa -inf' were refused as
    'expected one argument', without the value's name or what is allowed."""
    code, out, err = _run(capsys, ["demo", "--no-png", "--kappa", "-1/2", "--t-end", "1"])
    assert code == 0 and "(28)" in out, err
    code, _, err = _run(capsys, ["demo", "--no-png", "--t-end", "-1e3"])
    assert code == 2 and err == "hyperrotor demo: error: --t-end must be finite and > 0, got -1000.0\n"
    code, _, err = _run(capsys, ["demo", "--no-png", "--kappa", "-inf"])
    assert code == 2 and "--kappa='-inf' cannot be read" in err
    code, _, err = _run(capsys, ["bench", "--repeats", "-2e0"])
    assert code == 2 and "--repeats must be an integer >= 1, got -2" in err
    code, out, err = _run(capsys, ["demo", "--no-png", "--omega", "-1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1", "--t-end", "1"])
    assert code == 0, err


def test_a_huge_kappa_is_a_usage_error(capsys):
    """--kappa 1e80 failed with exit 1 and 'OverflowError' (the Manakov traces' own overflow check squared a Python
    float); it is refused as a usage error naming --kappa, as --kappa 1e60 was."""
    code, _, err = _run(capsys, ["demo", "--no-png", "--kappa", "1e80", "--t-end", "1e-100"])
    assert code == 2 and "choose a --kappa of smaller magnitude" in err and "OverflowError" not in err


def test_messages_name_what_was_given(capsys, tmp_path, monkeypatch):
    """The default picture's refusal named a --png that was not given; a blank --output was called empty; a huge
    --repeats printed its 100 digits."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hyperrotor-demo.png").mkdir()
    code, out, err = _run(capsys, ["demo"])
    assert code == 2 and out == ""
    assert err.startswith("hyperrotor demo: error: the demo's picture 'hyperrotor-demo.png' (the default of --png) "
                          "is a folder") and err.endswith(" (--png FILE.png or --no-png avoids it)\n")
    code, _, err = _run(capsys, ["bench", "--output", " "])
    assert code == 2 and "got ' '" in err
    code, _, err = _run(capsys, ["bench", "--repeats", "10**99"])
    assert code == 2 and "--repeats 1e+99 would take" in err
