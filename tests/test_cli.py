"""Tests of the ``hyperrotor`` command line (``hyperrotor.cli.main``)."""
import re

import numpy as np
import pytest
import sympy as sp

import hyperrotor as hr

from hyperrotor import Inertia, RigidBody
from hyperrotor.cli import SUBCOMMANDS, main


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
    assert _value(out, "energy E = 1/2 sum I_ij w_ij^2") == pytest.approx(float(body.energy(omega)), rel=1e-15)
    # independent: c_2 = sum of squared L components, c_4 from numpy's characteristic polynomial
    L = body.inertia.moments * omega
    assert _value(out, "Casimir c_2 = sum (L^ij)^2") == pytest.approx(float(np.sum(L**2)), rel=1e-12)
    poly = np.poly(body.matrix(L))
    assert _value(out, "Casimir c_4 (lambda^1 coefficient of det(lambda - L))") == pytest.approx(poly[4], rel=1e-10)
    np.testing.assert_allclose(_vector(out, "  L"), L, rtol=1e-15)
    np.testing.assert_allclose(_vector(out, "d omega/dt"), body.rhs(omega), rtol=1e-15)
    A = hr.to_matrix(L, "standard") + np.diag([1, 1, 1, 1, 0.25]) ** 2  # L + J^2, J = (1, 1, 1, 1, kappa^2)
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


def test_demo_options(capsys):
    code, out, _ = _run(capsys, ["demo", "--ascii", "--no-png", "--kappa", "2", "--axis", "1", "--convention", "standard",
                                 "--omega", "1,0,0,0,0,0,0,0,0,1"])
    assert code == 0
    assert "I_12 = 5" in out and "I_45 = 2" in out
    assert re.findall(r"^\[(\d+)\]  ", out, flags=re.M)[0] == "12"
    assert "(28)" not in out
    assert _value(out, "energy E = 1/2 sum I_ij w_ij^2") == pytest.approx(0.5 * (5 + 2))


@pytest.mark.parametrize("argv,msg", [
    (["demo", "--kappa", "abc"], "--kappa"),
    (["demo", "--omega", "1,2"], "10 components"),
    (["demo", "--omega", "a,b"], "--omega"),
    (["demo", "--axis", "7"], "axis"),
])
def test_demo_bad_options(capsys, argv, msg):
    code, _, err = _run(capsys, argv)
    assert code == 2 and msg in err


def test_help_lists_subcommands(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--help"])
    assert exc.value.code == 0
    out = capsys.readouterr().out
    for name in SUBCOMMANDS:
        assert name in out


def test_missing_subcommand_is_an_error(capsys):
    with pytest.raises(SystemExit) as exc:
        main([])
    assert exc.value.code == 2


def test_demo_motion_matches_closed_form_and_writes_png(capsys, tmp_path):
    png = tmp_path / "motion.png"
    code, out, _ = _run(capsys, ["demo", "--ascii", "--t-end", "50", "--png", str(png)])
    assert code == 0
    errs = {m.group(1): float(m.group(2)) for m in
            re.finditer(r"(splitting8|DOP853)\s+rtol=\S+: max relative error vs closed form = (\S+),", out)}
    assert set(errs) == {"splitting8", "DOP853"}
    assert errs["splitting8"] < 1e-10 and errs["DOP853"] < 1e-7
    # the frequencies printed are the closed forms after eq. (118); recompute them from the eigenvalues
    from hyperrotor.classical.closed_form import quartet_matrix, quartet_theta
    omega = _vector(out, "omega")
    lam = np.sort(np.abs(np.linalg.eigvals(quartet_theta(0.5) * quartet_matrix(omega, 5)).imag))[::-1]
    np.testing.assert_allclose(_vector(out, "frequencies Omega_1, Omega_2 (after eq. 118)"), lam[::2], rtol=1e-12)
    assert png.stat().st_size > 10_000 and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


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
    (["scene", "--output", "x.jpg"], "--output must end in .png or .gif"),
    (["scene", "--N", "2"], "--N must be >= 3"),
    (["scene", "--frames", "1"], "--frames must be >= 2"),
])
def test_scene_bad_options(capsys, argv, msg):
    code, _, err = _run(capsys, argv)
    assert code == 2 and msg in err


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
    with pytest.raises(SystemExit) as exc:
        main(["verify", "--section", "nope"])
    assert exc.value.code == 2
    assert "invalid choice: 'nope'" in capsys.readouterr().err
