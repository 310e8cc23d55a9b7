"""Tests of simulate(method="moser-veselov"): the discrete Moser-Veselov algorithm for so(N).

Bounds: order 2 against the closed forms (fitted slope within 0.3); the defining relations
h L_k = J Q - Q^T J and h L_{k+1} = Q J - J Q^T to 1e-13; Casimirs, energy and orthogonality
within 10 eps sqrt(steps) (round-off random walk).
"""
import numpy as np
import pytest

import hyperrotor as hr

from hyperrotor import Inertia, RigidBody, simulate
from hyperrotor._jit import JIT_ENABLED
from hyperrotor.classical.solvers import moser_veselov
from hyperrotor.classical.solvers._kernels import rotation_tables
from hyperrotor.classical import euler_poinsot, quartet_solution
from hyperrotor.conventions import to_matrix
from tolerance import EPS

MOM3 = np.array([2.0, 3.0, 4.0])  # J = (0.5, 1.5, 2.5)
W3 = np.array([0.6, 1.0, -0.5])
J5 = np.array([0.3, 0.55, 0.9, 1.4, 2.1])


def slope(dts, errs):
    return np.polyfit(np.log(dts), np.log(errs), 1)[0]


def test_order_two_against_the_elliptic_solution():
    t = np.linspace(0, 10, 11)
    exact = euler_poinsot(MOM3, W3, t)
    dts = [0.1, 0.05, 0.025, 0.0125]
    errs = [np.abs(simulate(MOM3, W3, t, method="moser-veselov", dt=dt).omega - exact).max() for dt in dts]
    assert abs(slope(dts, errs) - 2) < 0.3, errs
    assert errs[-1] < 2e-4


def test_order_two_against_the_quartet_closed_form():
    w0 = np.random.default_rng(3).normal(size=10)
    t = np.linspace(0, 10, 11)
    exact = quartet_solution(0.5, w0, t)
    body = RigidBody(Inertia.quartet(0.5))
    dts = [0.05, 0.025, 0.0125]
    errs = [np.abs(simulate(body, w0, t, method="moser-veselov", dt=dt).omega - exact).max() for dt in dts]
    assert abs(slope(dts, errs) - 2) < 0.3, errs


def test_the_moser_veselov_relations_hold_step_by_step(rng):
    """With one step per output interval, Q_k = T_{k+1} T_k^T must solve h L_k = J Q - Q^T J and
    give h L_{k+1} = Q J - J Q^T (the discrete Euler-Lagrange equations)."""
    J = np.diag(J5)
    w0 = rng.normal(size=10)
    h = 0.05
    t = np.arange(0, 41) * h
    body = RigidBody(Inertia.from_mass_tensor(J5), convention="standard")
    tr = simulate(body, w0, t, method="moser-veselov", dt=h, attitude=True)
    assert tr.stats["steps"] == 40
    L = to_matrix(tr.L, convention="standard")
    T = tr.attitude
    scale = np.abs(L).max() * h
    for k in range(40):
        Q = T[k + 1] @ T[k].T
        np.testing.assert_allclose(h * L[k], J @ Q - Q.T @ J, rtol=0, atol=1e-13 * scale)
        np.testing.assert_allclose(h * L[k + 1], Q @ J - J @ Q.T, rtol=0, atol=1e-13 * scale)


def test_casimirs_orthogonality_and_energy_to_round_off(rng):
    body = RigidBody(Inertia.from_mass_tensor(J5))
    w0 = rng.normal(size=10)
    t = np.linspace(0, 500, 501)
    tr = simulate(body, w0, t, method="moser-veselov", dt=0.02, attitude=True)  # 25,000 steps
    M = to_matrix(tr.L, convention="standard")
    M2 = M @ M
    c2 = np.trace(M2, axis1=-2, axis2=-1)
    c4 = np.trace(M2 @ M2, axis1=-2, axis2=-1)
    bound = EPS * np.sqrt(tr.stats["steps"]) * 10
    assert np.abs(c2 / c2[0] - 1).max() < bound
    assert np.abs(c4 / c4[0] - 1).max() < 2 * bound
    T = tr.attitude
    assert np.abs(np.swapaxes(T, -1, -2) @ T - np.eye(5)).max() < bound
    assert np.abs(tr.energy() / tr.energy()[0] - 1).max() < bound


@pytest.mark.parametrize("J", [[1.0, 2.0, 3.5], [0.2, 1.0, 1.7, 3.0], list(J5)])
def test_energy_is_conserved_to_round_off_even_at_large_steps(J, rng):
    """The discrete Moser-Veselov system conserves H = sum L_a^2 / (2 I_a) itself (not a modified
    energy): at dt = 0.1 over 1e4 steps the energy moves by round-off only, while the phase error
    is large (~1e-1)."""
    inertia = Inertia.from_mass_tensor(J)
    w0 = rng.normal(size=inertia.moments.size)
    t = np.linspace(0, 1000, 101)
    tr = simulate(inertia, w0, t, method="moser-veselov", dt=0.1)
    E = tr.energy()
    assert np.abs(E / E[0] - 1).max() < 10 * EPS * np.sqrt(tr.stats["steps"])


def test_attitude_and_paper_convention_agree_with_dop853(rng):
    w0 = rng.normal(size=10)
    t = np.linspace(0, 2, 5)
    body = RigidBody(Inertia.from_mass_tensor(J5), convention="paper")
    a = simulate(body, w0, t, method="moser-veselov", dt=1e-3, attitude=True)
    b = simulate(body, w0, t, method="DOP853", rtol=1e-12, attitude=True)
    np.testing.assert_allclose(a.omega, b.omega, atol=1e-4, rtol=0)
    np.testing.assert_allclose(a.attitude, b.attitude, atol=1e-4, rtol=0)
    a2 = simulate(body, w0, t, method="moser-veselov", dt=5e-4, attitude=True)
    # order 2: halving the step divides the error by ~4
    ratio = np.abs(a.attitude - b.attitude).max() / np.abs(a2.attitude - b.attitude).max()
    assert 3.0 < ratio < 5.0


def test_rtol_step_rule_reaches_the_requested_accuracy():
    t = np.linspace(0, 20, 21)
    exact = euler_poinsot(MOM3, W3, t)
    for rtol in (1e-4, 1e-6):
        tr = simulate(MOM3, W3, t, method="moser-veselov", rtol=rtol)
        err = np.abs(tr.omega - exact).max() / np.abs(W3).max()
        assert err <= rtol, (rtol, err)
        assert err > rtol / 100  # and does not waste steps by orders of magnitude


def test_ensemble_equals_single_runs(rng):
    w0 = rng.normal(size=(3, 10))
    t = np.linspace(0, 1, 3)
    inertia = Inertia.from_mass_tensor(J5)
    ens = simulate(inertia, w0, t, method="moser-veselov", dt=0.01, attitude=True)
    for b in range(3):
        one = simulate(inertia, w0[b], t, method="moser-veselov", dt=0.01, attitude=True)
        np.testing.assert_array_equal(ens.omega[b], one.omega)
        np.testing.assert_array_equal(ens.attitude[b], one.attitude)


@pytest.mark.skipif(not JIT_ENABLED, reason="numba disabled: only the Python path exists")
def test_jitted_and_python_kernels_agree(rng):
    J = J5
    m = Inertia.from_mass_tensor(J).moments
    L0 = (rng.normal(size=10) * m)[None]
    t = np.array([0.0, 0.1, 0.3])
    nsub = np.array([3, 4])
    pi, pj = rotation_tables(5)[3:]  # the solver's own (cached, read-only) tables: its compiled kernel
    np.testing.assert_array_equal(pi, [i - 1 for i in (1, 1, 1, 1, 2, 2, 2, 3, 3, 4)])
    np.testing.assert_array_equal(pj, [j - 1 for j in (2, 3, 4, 5, 3, 4, 5, 4, 5, 5)])
    outs = []
    for fn in (moser_veselov.mv_run, moser_veselov.mv_run_serial, moser_veselov.mv_run.py_func):
        outL = np.zeros((1, 3, 10))
        outT = np.zeros((1, 3, 5, 5))
        status = np.zeros(1, dtype=np.int64)
        fn(L0, J, m, pi, pj, np.diff(t) / nsub, nsub, np.eye(5)[None], True, outL, outT, status, np.zeros((1, 11)))
        assert status[0] == 0
        outs.append((outL, outT))
    np.testing.assert_array_equal(outs[0][0], outs[1][0])  # threaded and serial kernels: the same arithmetic
    np.testing.assert_array_equal(outs[0][1], outs[1][1])
    np.testing.assert_allclose(outs[0][0], outs[2][0], rtol=0, atol=1e-13 * np.abs(L0).max())
    np.testing.assert_allclose(outs[0][1], outs[2][1], rtol=0, atol=1e-13)


@pytest.mark.parametrize("m", [1, 3, 10, 21])
def test_the_kernels_lu_solve_agrees_with_lapack(m, rng):
    """The kernel's own LU (partial pivoting, as LAPACK's getrf/getrs): A^{-1} B within eps cond(A) of
    numpy's solve, on random matrices and on one whose leading pivot is zero; a singular matrix is refused."""
    for A in (rng.normal(size=(m, m)), np.roll(np.eye(m), 1, axis=0) + 0.1 * np.triu(rng.normal(size=(m, m)), 2)):
        B = rng.normal(size=(m, 3))
        LU, X, piv = A.copy(), B.copy(), np.empty(m, dtype=np.int64)
        assert moser_veselov._lu_factor(LU, piv)
        moser_veselov._lu_solve(LU, piv, X)
        ref = np.linalg.solve(A, B)
        bound = 10 * m * EPS * np.linalg.cond(A) * np.abs(ref).max()
        np.testing.assert_allclose(X, ref, rtol=0, atol=bound)
        np.testing.assert_allclose(A @ X, B, rtol=0, atol=10 * m * EPS * np.abs(A).max() * np.abs(X).max())
    singular = np.outer(rng.normal(size=m), rng.normal(size=m)) if m > 1 else np.zeros((1, 1))
    singular[:, 0] = 0.0
    assert not moser_veselov._lu_factor(singular, np.empty(m, dtype=np.int64))


def test_the_kernels_cayley_map_is_a_rotation(rng):
    """Q = (1 - X/2)^{-1} (1 + X/2) of an antisymmetric X: orthogonal, det 1, and Ainv the inverse of 1 - X/2."""
    N = 6
    X = rng.normal(size=(N, N))
    X = X - X.T
    eye = np.eye(N)
    LU, Ainv, Q = (np.empty((N, N)) for _ in range(3))
    assert moser_veselov._cayley(X, eye, LU, np.empty(N, dtype=np.int64), Ainv, Q)
    np.testing.assert_allclose(Q.T @ Q, eye, rtol=0, atol=100 * N * EPS)
    assert np.linalg.det(Q) == pytest.approx(1.0, abs=100 * N * EPS)
    np.testing.assert_allclose(Ainv @ (eye - X / 2), eye, rtol=0, atol=100 * N * EPS)
    np.testing.assert_allclose(Q, np.linalg.solve(eye - X / 2, eye + X / 2), rtol=0, atol=100 * N * EPS)


@pytest.mark.parametrize("moments", [[3.0, 0.1, 1.1], [3.0, 0.01, 1.01]])
def test_a_negative_mass_tensor_entry_converges_at_every_step(moments):
    """3D bodies may have a negative J_i (J = (1, 2, -0.9) here): Newton's update then stalls at round-off times
    max|J| / min I (20, 200), above the old test 4 eps |X|, and every step size failed with 'use a smaller dt'.
    Now order 2 against DOP853 at rtol 1e-13, and the energy kept to round-off."""
    w0, t = [1.0, -0.5, 0.3], [0.0, 2.0]
    assert np.any(Inertia(moments).mass_tensor < 0)
    ref = simulate(moments, w0, t, method="DOP853", rtol=1e-13).omega[-1]
    errs = [np.abs(simulate(moments, w0, t, method="moser-veselov", dt=dt).omega[-1] - ref).max()
            for dt in (1e-2, 1e-3, 1e-4)]
    assert slope([1e-2, 1e-3, 1e-4], errs) == pytest.approx(2.0, abs=0.1)
    tr = simulate(moments, w0, np.linspace(0.0, 2.0, 5), method="moser-veselov", dt=1e-3)
    E = 0.5 * np.sum(np.asarray(moments) * tr.omega**2, axis=-1)
    np.testing.assert_allclose(E, E[0], rtol=100 * EPS * np.sqrt(2000))


def test_bad_input():
    w0 = np.ones(10)
    t = [0.0, 1.0]
    generic = np.arange(1.0, 11.0)  # not of the form J_i + J_j
    with pytest.raises(ValueError, match="I_ij = J_i \\+ J_j"):
        simulate(generic, w0, t, method="moser-veselov", dt=0.1)
    with pytest.raises(ValueError, match="free body only"):
        simulate(Inertia.from_mass_tensor(J5), w0, t, method="moser-veselov", dt=0.1, torque=np.ones(10))
    with pytest.raises(ValueError, match="free body only"):
        simulate(MOM3, W3, t, method="moser-veselov", dt=0.1, torque=lambda tt, w: -w)
    with pytest.raises(hr.UnknownOptionError, match="'moser-veselov': unknown option 'compensated'; allowed: none"):
        simulate(Inertia.from_mass_tensor(J5), w0, t, method="moser-veselov", dt=0.1, options={"compensated": True})
    # a step far beyond the motion's time scale: the implicit equation has no solution near Q = 1
    with pytest.raises(RuntimeError, match="smaller dt"):
        simulate(MOM3, 50 * W3, [0.0, 10.0], method="moser-veselov", dt=10.0)
