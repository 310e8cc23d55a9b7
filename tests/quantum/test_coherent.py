"""Coherent states of so(N) irreps (hyperrotor.quantum.coherent) against independent facts.

* normalization and the moment map <L_a> = hbar |w| / |L| * L_a (space frame; body frame the
  negative), with the expectation values computed here from the generator matrices;
* minimal uncertainty: sum_a <L_a^2> - <L_a>^2 = hbar^2 (C(w) - |w|^2) = hbar^2 <w, 2 rho>, with
  the Casimir eigenvalue C(w) = <w, w + 2 rho> from the weight formulas, and the 1/l classical
  limit of the relative spread in the irreps (l, 0, ...);
* so(3): the state equals qutip.spin_coherent(j, theta, phi) up to a phase (qutip's own <J> is
  checked first), with the plane <-> spin-axis map read off the generator matrices;
* equivariance of apply_rotation, mu(U(Q) psi) = Q mu(psi) Q^T, and the refusals.

Tolerances are the scaled round-off bounds of tests/tolerance.py.
"""
from fractions import Fraction

import numpy as np
import pytest
import qutip
from scipy.stats import special_ortho_group

from hyperrotor.conventions import n_planes, planes, to_components, to_matrix
from hyperrotor.quantum import casimir_eigenvalue, irrep
from hyperrotor.quantum.coherent import apply_rotation, coherent_state, highest_weight_state, normal_form_rotation
from tolerance import norm, scaled_tol

H = Fraction(1, 2)


def _ket(psi):
    return psi.full().ravel() if isinstance(psi, qutip.Qobj) else np.asarray(psi, dtype=complex)


def _moments(rep, psi, hbar=1.0):
    """<psi| -i hbar X_a |psi> and <psi| (-i hbar X_a)^2 |psi>, from the dense generators."""
    v = _ket(psi)
    v = v / np.linalg.norm(v)
    first, second = [], []
    for p in planes(rep.N):
        L = -1j * hbar * rep.generator(p, format="dense")
        Lv = L @ v
        first.append(np.vdot(v, Lv).real)
        second.append(np.vdot(Lv, Lv).real)  # <L^2> = |L v|^2 (L Hermitian)
    return np.array(first), np.array(second)


def _simple_bivector(rng, N):
    """A random simple bivector u ^ v (one plane of rotation), as plane components."""
    u, v = rng.normal(size=(2, N))
    return to_components(np.outer(u, v) - np.outer(v, u), convention="standard")


@pytest.mark.parametrize("N, l", [(3, 1), (3, 4), (4, 2), (5, 1), (5, 3), (6, 2)])
@pytest.mark.parametrize("hbar", [1.0, 0.37])
def test_moment_map_points_along_L(N, l, hbar, rng):
    rep = irrep(N, (l,) + (0,) * (N // 2 - 1))
    L = _simple_bivector(rng, N)
    psi = coherent_state(rep, L, hbar=hbar)
    v = _ket(psi)
    assert psi.dims == [[rep.dim], [1]]
    assert abs(np.linalg.norm(v) - 1.0) <= scaled_tol(1.0, dim=rep.dim)
    first, _ = _moments(rep, psi, hbar)
    # <L_a> = hbar |w| / |L| L_a with |w| = l (the highest weight (l, 0, ...))
    X = max(norm(rep.generator(p, format="dense")) for p in planes(N))
    tol = scaled_tol(hbar * X * l, dim=rep.dim, k=64)
    np.testing.assert_allclose(first, hbar * l * L / np.linalg.norm(L), rtol=0, atol=tol)
    # body frame: the body-frame generators are the negatives, so <L_a> = -c L_a
    first_b, _ = _moments(rep, coherent_state(rep, L, hbar=hbar, frame="body"), hbar)
    np.testing.assert_allclose(first_b, -hbar * l * L / np.linalg.norm(L), rtol=0, atol=tol)


@pytest.mark.parametrize("N, m", [(3, (2,)), (4, (2, 0)), (4, (1, 1)), (5, (2, 0)), (5, (2, 1)), (5, (3 * H, H)),
                                  (6, (1, 0, 0)), (7, (1, 0, 0))], ids=str)
def test_minimal_uncertainty_equals_casimir_minus_weight_squared(N, m, rng):
    """sum_a Var(L_a) = hbar^2 (C(w) - |w|^2) for a coherent state (Perelomov), any irrep."""
    rep = irrep(N, m)
    w = np.array([float(x) for x in m])
    # L with normal form proportional to w: rotate the Cartan bivector sum_k w_k E_{2k-1,2k}
    B = np.zeros((N, N))
    for k, wk in enumerate(w):
        B[2 * k, 2 * k + 1], B[2 * k + 1, 2 * k] = wk, -wk
    Q = special_ortho_group.rvs(N, random_state=int(rng.integers(1 << 30)))
    L = to_components(Q @ B @ Q.T, convention="standard")
    hbar = 0.8
    psi = coherent_state(rep, L, hbar=hbar)
    first, second = _moments(rep, psi, hbar)
    C = float(casimir_eigenvalue(N, m))
    var = second.sum() - (first**2).sum()
    scale = hbar**2 * C
    assert abs(second.sum() - scale) <= scaled_tol(scale, dim=rep.dim, k=8 * n_planes(N))  # the Casimir itself
    assert abs(var - hbar**2 * (C - w @ w)) <= scaled_tol(scale, dim=rep.dim, k=8 * n_planes(N))
    np.testing.assert_allclose(first, hbar * L, rtol=0, atol=scaled_tol(hbar * norm(L), dim=rep.dim, k=64))


@pytest.mark.parametrize("N", [3, 4, 5])
def test_classical_limit_relative_spread_falls_like_one_over_l(N, rng):
    """In (l, 0, ...): Var / |<L>|^2 = <w, 2 rho> / |w|^2 = (N - 2) / l -> 0 (the classical limit)."""
    L = _simple_bivector(rng, N)
    ratios = []
    for l in (1, 2, 4, 8):
        rep = irrep(N, (l,) + (0,) * (N // 2 - 1))
        first, second = _moments(rep, coherent_state(rep, L))
        ratios.append((second.sum() - first @ first) / (first @ first))
        assert ratios[-1] == pytest.approx((N - 2) / l, rel=1e-9)
    assert np.all(np.diff(ratios) < 0)


@pytest.mark.parametrize("twice_j", [1, 2, 3, 6])
def test_so3_coherent_state_is_qutip_spin_coherent(twice_j, rng):
    j = twice_j / 2
    rep = irrep(3, (Fraction(twice_j, 2),))
    J = {a: qutip.jmat(j, a).full() for a in "xyz"}
    # which spin axis (and sign) each plane's Hermitian generator is, read off the matrices
    axis_of = {}
    for p in planes(3):
        Lp = -1j * rep.generator(p, format="dense")
        hits = [(a, s) for a in "xyz" for s in (1, -1) if np.allclose(Lp, s * J[a], atol=scaled_tol(J[a]), rtol=0)]
        assert len(hits) == 1, (p, hits)
        axis_of[p] = hits[0]
    for _ in range(3):
        theta, phi = rng.uniform(0.1, np.pi - 0.1), rng.uniform(0, 2 * np.pi)
        n = {"x": np.sin(theta) * np.cos(phi), "y": np.sin(theta) * np.sin(phi), "z": np.cos(theta)}
        ref = qutip.spin_coherent(j, theta, phi)
        # qutip's state points along n: <J> = j n (independent of hyperrotor)
        np.testing.assert_allclose([qutip.expect(qutip.jmat(j, a), ref) for a in "xyz"],
                                   [j * n[a] for a in "xyz"], rtol=0, atol=scaled_tol(j, dim=rep.dim, k=16))
        L = np.array([axis_of[p][1] * n[axis_of[p][0]] for p in planes(3)])
        ours = coherent_state(rep, L)
        overlap = abs(np.vdot(ref.full().ravel(), _ket(ours)))
        assert abs(overlap - 1.0) <= scaled_tol(1.0, dim=rep.dim, k=16)


@pytest.mark.parametrize("N, m", [(3, (1,)), (4, (H, -H)), (5, (1, 1)), (5, (H, H))], ids=str)
def test_apply_rotation_is_equivariant(N, m, rng):
    """mu(U(Q) psi) = Q mu(psi) Q^T (the moment map of a random state, not only of coherent ones)."""
    rep = irrep(N, m)
    psi = rng.normal(size=rep.dim) + 1j * rng.normal(size=rep.dim)
    psi /= np.linalg.norm(psi)
    Q = special_ortho_group.rvs(N, random_state=int(rng.integers(1 << 30)))
    phi = apply_rotation(rep, Q, psi)
    assert abs(np.linalg.norm(phi) - 1.0) <= scaled_tol(1.0, dim=rep.dim, k=64)  # U(Q) is unitary
    mu0, _ = _moments(rep, psi)
    mu1, _ = _moments(rep, phi)
    expected = to_components(Q @ to_matrix(mu0, convention="standard") @ Q.T, convention="standard")
    X = max(norm(rep.generator(p, format="dense")) for p in planes(N))
    np.testing.assert_allclose(mu1, expected, rtol=0, atol=scaled_tol(X, dim=rep.dim, k=64 * N))


def test_highest_weight_state_has_the_highest_weight():
    for N, m in [(3, (2,)), (4, (1, -1)), (5, (2, 1)), (6, (1, 1, 0))]:
        rep = irrep(N, m)
        psi, w = highest_weight_state(rep)
        np.testing.assert_allclose(w, [float(x) for x in m], rtol=0, atol=scaled_tol(max(1.0, float(m[0])), dim=rep.dim, k=64))
        assert abs(np.linalg.norm(psi) - 1.0) <= scaled_tol(1.0, dim=rep.dim)


def test_refusals_name_the_problem(rng):
    rep = irrep(5, (2, 0))
    with pytest.raises(ValueError, match=r"^L has 2 plane components, which matches no so\(N\)"):
        normal_form_rotation([1.0, 2.0])  # (named to_matrix's "count")
    with pytest.raises(ValueError, match="non-zero"):
        coherent_state(rep, np.zeros(10))
    with pytest.raises(ValueError, match="10 components"):
        coherent_state(rep, np.ones(6))
    # a generic (non-simple) bivector has a normal form (l1, l2), l2 != 0: not proportional to (2, 0)
    B = np.zeros((5, 5))
    B[0, 1], B[1, 0], B[2, 3], B[3, 2] = 2.0, -2.0, 1.0, -1.0
    with pytest.raises(ValueError, match="not a positive multiple"):
        coherent_state(rep, to_components(B, convention="standard"))
    with pytest.raises(ValueError, match="frame"):
        coherent_state(rep, _simple_bivector(rng, 5), frame="lab")
    with pytest.raises((ValueError, TypeError), match="hbar"):
        coherent_state(rep, _simple_bivector(rng, 5), hbar=-1.0)
