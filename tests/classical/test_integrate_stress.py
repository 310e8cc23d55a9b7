"""Stress tests of simulate(): long runs, stiff moments, separatrices, extreme speeds, torques.

Stated bounds (relative): Casimirs of the splitting methods <= 1e-13 even after 1e6
steps (runs of more than 1e6 plane flows add the rotation increments with error-free
TwoSum, so round-off does not random-walk; shorter runs stay below eps sqrt(flows));
attitude orthogonality max|T^T T - 1| <= 1e-11 after 1e6 steps; energy error bounded,
not drifting.
"""
import numpy as np
import pytest

from hyperrotor import Inertia, RigidBody
from hyperrotor.classical import euler_poinsot
from hyperrotor.classical.simulate import simulate
from hyperrotor.conventions import to_matrix
from hyperrotor.classical.solvers import step_control
from hyperrotor.classical.solvers.step_control import rate_bound
from tolerance import EPS

MOM3 = np.array([2.0, 3.0, 4.0])


def invariants(L):
    M = to_matrix(L, convention="standard")
    M2 = M @ M
    return np.trace(M2, axis1=-2, axis2=-1), np.trace(M2 @ M2, axis1=-2, axis2=-1)


def rel_drift(x):
    x = np.asarray(x)
    return np.abs(x / x[..., :1] - 1).max()


def roundoff_bound(tr):
    """Bound on the Casimirs' relative round-off drift of a splitting run: a few eps with compensated
    storage of L (runs of > 1e6 plane flows), else a random walk of a few eps per plane flow,
    4 eps sqrt(flows) (each flow rounds its 2(N-2) rotated components in about four operations; a body
    with moments over 12 decades drifted 3.7 eps sqrt(flows) over 5e4 flows)."""
    flows = tr.stats["steps"] * tr.stats["flows_per_step"]
    return 64 * EPS if tr.stats["compensated"] else 4 * EPS * np.sqrt(flows)


def orthogonality(T):
    return np.abs(np.swapaxes(T, -1, -2) @ T - np.eye(T.shape[-1])).max()


@pytest.mark.slow
def test_million_steps_5d_with_attitude():
    body = RigidBody(Inertia.from_mass_tensor([0.3, 0.55, 0.9, 1.4, 2.1]))
    w0 = np.random.default_rng(7).normal(size=10)
    t = np.linspace(0, 1e4, 201)
    tr = simulate(body, w0, t, method="splitting2", dt=0.01, attitude=True)
    assert tr.stats["steps"] == 10**6
    assert np.all(np.isfinite(tr.omega)) and np.all(np.isfinite(tr.attitude))
    c2, c4 = invariants(tr.L)
    assert rel_drift(c2) < 1e-13 and rel_drift(c4) < 1e-13
    cas = np.asarray(body.casimirs(tr.omega), dtype=float)
    assert np.all(np.abs(cas - cas[:1]) <= 1e-13 * np.abs(cas[:1]))  # (K, 2) characteristic-polynomial coefficients
    E = tr.energy()
    err = np.abs(E / E[0] - 1)
    assert err.max() < 1e-3
    assert err[-20:].max() < 3 * err[:40].max()  # no drift over 1e6 steps
    assert orthogonality(tr.attitude) < 1e-11
    Lb = body.matrix(tr.L)
    Ls = np.swapaxes(tr.attitude, -1, -2) @ Lb @ tr.attitude
    assert np.abs(Ls - Ls[0]).max() < 1e-9 * np.abs(Lb).max()


def test_splitting8_long_run_3d_stays_on_the_elliptic_solution():
    t = np.linspace(0, 2000, 401)
    w0 = np.array([0.6, 1.0, -0.5])
    tr = simulate(MOM3, w0, t, method="splitting8", dt=0.1)  # 2e4 steps
    exact = euler_poinsot(MOM3, w0, t)
    assert np.abs(tr.omega - exact).max() < 1e-9
    c2, _ = invariants(tr.L)
    assert rel_drift(c2) < roundoff_bound(tr)


@pytest.mark.parametrize("seed", [0, 1])
def test_stiff_moment_ratios_1e_minus6_to_1e6(seed):
    """A physical body (I_ij = J_i + J_j) with plane moments from 1e-6 to 2e6."""
    rng = np.random.default_rng(seed)
    inertia = Inertia.from_mass_tensor(rng.permutation([1e-7, 9e-7, 1.0, 1e3, 1e6]))
    moments = inertia.moments
    assert moments.min() == pytest.approx(1e-6, rel=1e-15) and moments.max() > 1e6
    # (a) comparable momenta: rotation rates up to 1e6 in the light planes
    L0 = rng.normal(size=10)
    w0 = L0 / moments
    t = np.linspace(0, 2e-3, 5)
    tr = simulate(inertia, w0, t, rtol=1e-9, attitude=True)
    assert np.all(np.isfinite(tr.omega))
    c2, c4 = invariants(tr.L)
    assert rel_drift(c2) < roundoff_bound(tr) and rel_drift(c4) < 2 * roundoff_bound(tr)
    assert rel_drift(tr.energy()) < 1e-8
    # round-off random walk over ~3e5 plane rotations of T: 16 eps sqrt(rotations) ~ 2e-12
    assert orthogonality(tr.attitude) < 16 * np.finfo(float).eps * np.sqrt(tr.stats["steps"] * tr.stats["flows_per_step"])
    # the promise (#22): whole-run error <= rtol max|L|, against a converged run (splitting8 at a step of
    # 1e-8, compensated: within 1.3e-10 of DOP853 at rtol 1e-13); before the step was capped at a half
    # turn of the fastest reachable rate (step_control.MAX_TURN) this missed it 4-10-fold (orders 8, 10: ~100-fold)
    ref = simulate(inertia, w0, t, method="splitting8", dt=1e-8, options={"compensated": True})
    assert np.abs(tr.L - ref.L).max() <= 1e-9 * np.abs(ref.L).max()
    assert tr.stats["dt"] * rate_bound(moments, L0[None])[0] <= step_control.MAX_TURN * (1 + 1e-9)
    tr10 = simulate(inertia, w0, t, rtol=1e-9, method="splitting10")
    assert np.abs(tr10.L - ref.L).max() <= 1e-9 * np.abs(ref.L).max()
    # (b) comparable rates: momenta spread over 12 decades; the light planes can be spun up to
    # rates ~ sqrt(2 E / I_min) (energy bound), which the step rule takes into account
    w0 = rng.normal(size=10)
    t = np.linspace(0, 1e-3, 5)
    a = simulate(inertia, w0, t, method="splitting8", rtol=1e-10, attitude=True)
    assert np.all(np.isfinite(a.omega))
    c2, c4 = invariants(a.L)
    assert rel_drift(c2) < roundoff_bound(a) and rel_drift(c4) < 2 * roundoff_bound(a)
    assert rel_drift(a.energy()) < 1e-9
    assert orthogonality(a.attitude) < 1e-12
    ref = simulate(inertia, w0, t, method="DOP853", rtol=1e-12)
    assert np.abs(a.L - ref.L).max() < 1e-8 * np.linalg.norm(a.L[0])


def test_non_physical_stiff_moments_are_recognised_by_the_step_rule():
    """Moments violating I_ij <= I_ik + I_jk have linearised frequencies far above the rates.

    Here I_12 = 1e6 >> I_13 + I_23 = 2.2e-6: about steady rotation in plane 12 at rate 1 the
    perturbations oscillate at lambda = sqrt((I12 - I13)(I12 - I23) / (I13 I23)) ~ 9e11, although
    every rate is ~1. The step rule must resolve lambda (dt < 2 / lambda), and then the splitting
    agrees with the implicit Radau method.
    """
    moments = np.array([1e6, 1e-6, 1.2e-6])
    w0 = np.array([1.0, 1e-9, 1e-9])
    t = np.linspace(0, 1e-9, 3)
    tr = simulate(moments, w0, t, method="splitting4", rtol=1e-8)
    lam = np.sqrt((1e6 - 1e-6) * (1e6 - 1.2e-6) / (1e-6 * 1.2e-6))
    assert tr.stats["dt"] * lam < 2.0  # the step resolves the fast oscillation
    ref = simulate(moments, w0, t, method="Radau", rtol=1e-12)
    assert np.all(np.isfinite(tr.omega))
    np.testing.assert_allclose(tr.omega, ref.omega, rtol=0, atol=1e-8 * 1.0)  # the requested rtol


def test_near_and_on_the_separatrix_3d():
    # tennis racket: rotation about the intermediate plane (13) slightly perturbed
    t = np.linspace(0, 60, 241)
    w0 = np.array([1e-3, 1.0, 1e-3])
    tr = simulate(MOM3, w0, t, method="splitting8", rtol=1e-11)
    exact = euler_poinsot(MOM3, w0, t)
    assert np.abs(exact[:, 1]).min() < 0.5  # the flip happens inside the window
    assert np.abs(tr.omega - exact).max() < 1e-7  # sensitivity ~ 1/eps near the separatrix
    c2, _ = invariants(tr.L)
    assert rel_drift(c2) < roundoff_bound(tr) and rel_drift(tr.energy()) < 1e-11
    # exactly on the separatrix (L^2 = 2 E I_13): I12 w12^2 (I12 - I13) + I23 w23^2 (I23 - I13) = 0
    w0 = np.array([np.sqrt(2.0) * 0.5, 0.3, 0.5])
    L = MOM3 * w0
    assert abs(L @ L - 2 * 3.0 * 0.5 * (MOM3 * w0) @ w0) < 1e-14
    t = np.linspace(0, 8, 33)
    tr = simulate(MOM3, w0, t, method="splitting8", rtol=1e-12)
    np.testing.assert_allclose(tr.omega, euler_poinsot(MOM3, w0, t), atol=1e-8, rtol=0)
    assert np.all(np.isfinite(tr.omega))


def test_zero_angular_velocity_is_a_fixed_point():
    body = RigidBody(Inertia.quartet(0.5))
    for method in ("auto", "splitting8", "DOP853"):
        tr = simulate(body, np.zeros((2, 10)), np.linspace(0, 100, 11), method=method, attitude=True)
        assert np.all(tr.omega == 0)
        assert np.all(tr.attitude == np.eye(5))


@pytest.mark.parametrize("scale", [1e-8, 1e8])
def test_tiny_and_huge_angular_velocity_scale_exactly(scale):
    """omega -> lam omega(lam t) is a symmetry; the step rule must follow the time scale."""
    w0 = np.array([0.6, 1.0, -0.5])
    t = np.linspace(0, 20, 11)
    base = simulate(MOM3, w0, t, method="splitting8", rtol=1e-11)
    scaled = simulate(MOM3, scale * w0, t / scale, method="splitting8", rtol=1e-11, attitude=True)
    np.testing.assert_allclose(scaled.omega / scale, base.omega, atol=1e-10, rtol=0)
    assert orthogonality(scaled.attitude) < 1e-13
    exact = euler_poinsot(MOM3, w0, t)
    assert np.abs(base.omega - exact).max() < 2e-11


def test_time_dependent_torque_energy_and_casimir_balance():
    """dE/dt = omega . tau and d|L|^2/dt = 2 L . tau (body frame), checked by quadrature."""
    body = RigidBody(Inertia.from_mass_tensor([0.3, 0.55, 0.9, 1.4, 2.1]))
    rng = np.random.default_rng(11)
    w0 = rng.normal(size=10)
    A = rng.normal(size=10)

    def torque(t, w):
        return A * np.sin(3 * t) - 0.2 * body.inertia.moments * w

    t = np.linspace(0, 10, 4001)
    tr = simulate(body, w0, t, torque=torque, rtol=1e-11)
    assert tr.stats["method"] == "DOP853" and np.all(np.isfinite(tr.omega))
    tau = np.array([torque(tt, w) for tt, w in zip(t, tr.omega)])
    from scipy.integrate import simpson

    dE = simpson(np.sum(tr.omega * tau, axis=1), x=t)
    assert abs(tr.energy()[-1] - tr.energy()[0] - dE) < 1e-8 * abs(tr.energy()).max()
    dC = simpson(2 * np.sum(tr.L * tau, axis=1), x=t)
    c2 = np.sum(tr.L**2, axis=1)
    assert abs(c2[-1] - c2[0] - dC) < 1e-8 * c2.max()


@pytest.mark.slow
def test_constant_torque_long_splitting_run():
    """A constant body torque with the symmetric kick composition over 1e5 steps vs DOP853."""
    body = RigidBody(Inertia.from_mass_tensor([0.3, 0.55, 0.9, 1.4, 2.1]))
    rng = np.random.default_rng(5)
    w0 = rng.normal(size=10)
    tau = 0.05 * rng.normal(size=10)
    t = np.linspace(0, 100, 51)
    tr = simulate(body, w0, t, method="splitting6", dt=1e-3, torque=tau, attitude=True)
    ref = simulate(body, w0, t, method="DOP853", rtol=1e-13, torque=tau)
    assert np.all(np.isfinite(tr.omega))
    assert np.abs(tr.omega - ref.omega).max() < 1e-8 * np.abs(ref.omega).max()
    assert orthogonality(tr.attitude) < 1e-12


def test_a_moment_ratio_of_1e300_runs():
    """Moments (1e300, 2, 3.5): the step control's rate bound multiplied (I_c - I_a)(I_c - I_b) = 1e600 to inf,
    the probe's step became 0 and simulate raised a bare ZeroDivisionError (a review, through ehrenfest_time). The
    two ratios are taken apart now; the run agrees with DOP853."""
    t = np.linspace(0.0, 10.0, 11)
    a = simulate([1e300, 2.0, 3.5], [3e-301, 0.5, 0.05], t, rtol=1e-9)
    b = simulate([1e300, 2.0, 3.5], [3e-301, 0.5, 0.05], t, method="DOP853", rtol=1e-12, atol=1e-14)
    bound = step_control._coupled_rates(np.array([1e300, 2.0, 3.5]), np.array([[0.3, 1.0, 0.175]]),
                                        *step_control._triples(3))
    assert 0.5 < bound[0] < 10.0  # (the linearised frequency of the triple, finite; was inf)
    np.testing.assert_allclose(a.omega, b.omega, rtol=0, atol=1e-9 * np.abs(b.omega).max())
