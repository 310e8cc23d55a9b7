"""Tests of hyperrotor.demo: the quartet demo's physics as library functions (what `hyperrotor demo` prints)."""
import numpy as np
import pytest
import sympy as sp

import hyperrotor as hr
from hyperrotor.classical import quartet_matrix, quartet_theta
from hyperrotor.demo import (DEMO_OMEGA, DEMO_RUNS, compare_quartet_motion, quartet_invariants,
                             quartet_motion_seconds, save_quartet_motion)


def test_invariants_against_independent_formulas():
    body = hr.RigidBody(hr.Inertia.quartet(sp.Rational(1, 2), axis=5, N=5))
    omega = np.array(DEMO_OMEGA)
    inv = quartet_invariants(body, omega)
    L = np.array([2, 2, 2, 1.25, 2, 2, 1.25, 2, 1.25, 1.25]) * omega  # I = 1 + kappa^2 on the planes with axis 5
    np.testing.assert_allclose(inv.L, L, rtol=1e-15)
    assert inv.energy == pytest.approx(0.5 * float(np.dot(L, omega)), rel=1e-14)
    assert inv.casimirs[0] == pytest.approx(float(np.sum(L**2)), rel=1e-14)
    assert inv.casimirs[1] == pytest.approx(np.poly(body.matrix(L))[4], rel=1e-12)  # lambda^1 coefficient
    A = hr.to_matrix(L, convention="standard") + np.diag([1, 1, 1, 1, 0.25]) ** 2  # L + J^2
    np.testing.assert_allclose(inv.manakov, [np.trace(np.linalg.matrix_power(A, k)) for k in range(2, 6)],
                               rtol=1e-12)
    assert np.all(inv.rhs[[0, 1, 2, 4, 5, 7]] == 0.0)  # planes without axis 5: constant omega
    with pytest.raises(TypeError, match="body must be a hyperrotor.RigidBody"):
        quartet_invariants([1.0] * 10, omega)


def test_motion_against_the_closed_form_and_its_picture(tmp_path):
    m = compare_quartet_motion(sp.Rational(1, 2), DEMO_OMEGA, 40.0, axis=4, n_times=401)
    assert [name for name, _ in DEMO_RUNS] == list(m.runs)
    for run in m.runs.values():  # the reported error is the one of the returned motion
        assert run.error == np.max(np.abs(run.omega - m.exact)) / np.max(np.abs(DEMO_OMEGA))
    assert m.runs["splitting8"].error < 1e-10 and m.runs["DOP853"].error < 1e-7
    assert m.runs["splitting8"].energy_drift < 1e-12
    # the frequencies after eq. (118): the imaginary parts of the eigenvalues of theta * M(omega)
    lam = np.sort(np.abs(np.linalg.eigvals(quartet_theta(0.5) * quartet_matrix(np.array(DEMO_OMEGA), 4)).imag))
    np.testing.assert_allclose(np.sort(m.frequencies), lam[::2], rtol=1e-12)
    path = save_quartet_motion(m, tmp_path / "m.png")
    assert (tmp_path / "m.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and path.endswith("m.png")


def test_priced_before_it_runs():
    short, long = (quartet_motion_seconds(0.5, DEMO_OMEGA, t) for t in (10.0, 1e6))
    assert long.seconds > 1000 * short.seconds > 0
    assert short.rate == long.rate == pytest.approx(1.0 * 2 / 1.25)  # max|omega0| max(I) / min(I)
    with hr.options(max_seconds=60.0), pytest.raises(hr.BudgetError, match="max_seconds"):
        compare_quartet_motion(0.5, DEMO_OMEGA, 1e6)
