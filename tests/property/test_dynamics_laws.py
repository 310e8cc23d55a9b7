"""Property-based conservation laws of the free rigid body (Lie-Poisson dynamics on so(N)*).

For random bodies and initial conditions, short ``hyperrotor.simulate`` runs keep

* the Casimirs c_2k (coefficients of det(lambda - L), eq. 38) with a Lie-Poisson splitting
  method, for ANY positive plane moments: each flow is an exact coadjoint rotation, so only
  round-off moves them, a random walk of ~ eps sqrt(flows) |L|^2k;
* the energy and the Casimirs with the Moser-Veselov discretization, for physical bodies
  (I_ij = J_i + J_j): it conserves both exactly in exact arithmetic (at any step size).

Tolerances come from tests/tolerance.py: k eps N |L|^(2k) sqrt(number of round-off steps).
"""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import hyperrotor as hr
from tolerance import norm, scaled_tol

SETTINGS = settings(max_examples=12, deadline=None)


@st.composite
def free_bodies(draw, physical):
    N = draw(st.integers(3, 5))
    n = hr.n_planes(N)
    if physical:
        J = draw(arrays(np.float64, N, elements=st.floats(0.2, 3.0, allow_subnormal=False)))
        inertia = hr.Inertia.from_mass_tensor(J)
    else:
        inertia = hr.Inertia.from_planes(draw(arrays(np.float64, n, elements=st.floats(0.3, 5.0, allow_subnormal=False))))
    # no subnormals: (I w) / I is exact to a few ulps only for normal numbers
    omega0 = draw(arrays(np.float64, n, elements=st.floats(-2.0, 2.0, allow_subnormal=False)))
    convention = draw(st.sampled_from(hr.CONVENTIONS))
    return hr.RigidBody(inertia, convention=convention), omega0


def _round_off_steps(tr, n_planes, fallback_steps):
    """Number of rounding steps of a run: plane flows of a splitting method (from its stats)."""
    stats = getattr(tr, "stats", {}) or {}
    steps = stats.get("steps", fallback_steps)
    return int(steps) * int(stats.get("flows_per_step", 2 * n_planes))


def _casimir_tol(body, omega0, steps):
    L0 = body.angular_momentum(omega0)
    # c_2k is homogeneous of degree 2k in L: its round-off scale is |L|^2k (not c_2k itself,
    # which can be ~0 for a low-rank L)
    return np.array([scaled_tol(norm(L0) ** (2 * k), dim=body.N, steps=steps, k=16)
                     for k in range(1, body.N // 2 + 1)])


@SETTINGS
@given(free_bodies(physical=False), st.sampled_from(["splitting4", "splitting8"]))
def test_splitting_keeps_casimirs_to_round_off_for_any_moments(data, method):
    body, omega0 = data
    t = np.linspace(0.0, 2.0, 5)
    tr = hr.simulate(body, omega0, t, method=method, dt=0.02)
    c = body.casimirs(tr.omega)
    steps = _round_off_steps(tr, hr.n_planes(body.N), fallback_steps=100)
    assert np.all(np.abs(c - body.casimirs(omega0)) <= _casimir_tol(body, omega0, steps))
    np.testing.assert_allclose(tr.omega[0], omega0, rtol=4 * np.finfo(float).eps, atol=np.finfo(float).tiny)  # (I w) / I


@SETTINGS
@given(free_bodies(physical=True))
def test_moser_veselov_keeps_energy_and_casimirs_for_physical_bodies(data):
    body, omega0 = data
    t = np.linspace(0.0, 2.0, 5)
    tr = hr.simulate(body, omega0, t, method="moser-veselov", dt=0.05)
    steps = int((getattr(tr, "stats", {}) or {}).get("steps", 40))
    E0 = body.energy(omega0)
    # energy sum_a I_a w_a^2 / 2: scale |L| |w|; each step solves an N x N matrix equation
    tolE = scaled_tol(norm(body.angular_momentum(omega0)) * norm(omega0), dim=body.N, steps=steps, k=32)
    assert np.abs(body.energy(tr.omega) - E0).max() <= tolE
    c = body.casimirs(tr.omega)
    assert np.all(np.abs(c - body.casimirs(omega0)) <= 2 * _casimir_tol(body, omega0, steps * body.N))


@SETTINGS
@given(free_bodies(physical=False))
def test_energy_and_casimirs_are_invariants_of_the_vector_field(data):
    """dE/dt = grad E . rhs = 0 and dc_2/dt = 0 pointwise (the laws behind the conservation)."""
    body, omega0 = data
    f = body.rhs(omega0)
    I = np.asarray(body.inertia.moments, dtype=float)
    L = I * omega0
    # dE/dt = sum I w w' ; dc2/dt = 2 sum L L' = 2 sum I^2 w w'
    scale = norm(L) * norm(omega0) ** 2 * max(I.max(), 1.0)
    assert abs(np.dot(I * omega0, f)) <= scaled_tol(scale, dim=body.N, k=16 * body.N)
    assert abs(np.dot(I * L, f)) <= scaled_tol(scale * I.max(), dim=body.N, k=16 * body.N)


def test_reference_bound_is_not_vacuous():
    """The Casimir bound of these tests is ~1e-12 relative for a 200-step run: it is tight enough
    to catch a wrong flow (an O(dt) error would exceed it by orders of magnitude)."""
    body = hr.RigidBody(hr.Inertia.from_planes(np.linspace(1.0, 2.0, 10)))
    w0 = np.linspace(-1.0, 1.0, 10)
    tol = _casimir_tol(body, w0, 200 * 20)
    c0 = body.casimirs(w0)
    assert np.all(tol < 1e-10 * np.maximum(c0, 1.0))
    wrong = w0 + 1e-6 * np.arange(10)  # a perturbation far below any integrator accuracy claim
    assert np.any(np.abs(body.casimirs(wrong) - c0) > tol)


def test_moser_veselov_near_underflow_angular_velocity():
    """Found by the property test above: omega0 = 2.2e-308 (normal, not subnormal) made the
    rescaled Moser-Veselov run fail with RuntimeError 'no solution near Q = 1' (1e-200 worked)."""
    body = hr.RigidBody(hr.Inertia.from_mass_tensor([1.0, 1.0, 1.0]))
    w0 = np.full(3, 2.2250738585072014e-308)
    tr = hr.simulate(body, w0, np.linspace(0.0, 2.0, 5), method="moser-veselov", dt=0.05)
    np.testing.assert_allclose(tr.omega[-1], w0, rtol=1e-12)  # equal moments: omega is constant
