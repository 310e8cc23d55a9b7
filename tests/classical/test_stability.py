"""Linear stability of planar rotation (Sec. 4, corrected) and the N-D tennis-racket instability."""
import itertools

import numpy as np
import pytest
import sympy as sp

import hyperrotor
from hyperrotor.classical.stability import linear_stability, linearization, perturbation_growth, stability_condition
from hyperrotor.conventions import plane_index, plane_symbols, planes, structure_constants
from references import component_rhs


# eq. (131): J1..J10 = I_12, I_13, I_14, I_23, I_24, I_34, I_15, I_25, I_35, I_45 (NOT plane order)
PAPER_J = [(1, 2), (1, 3), (1, 4), (2, 3), (2, 4), (3, 4), (1, 5), (2, 5), (3, 5), (4, 5)]


def _from_J(Jvals):
    """Plane-order moment array from the paper's J1..J10 of eq. (131)."""
    out = np.empty(10)
    for p, v in zip(PAPER_J, Jvals):
        out[plane_index(p, 5)] = v
    return out


def _physical(m):
    """I_ij = m_i + m_j."""
    N = len(m)
    return np.array([m[i - 1] + m[j - 1] for i, j in planes(N)])


@pytest.mark.parametrize("N", [3, 4, 5, 6])
def test_jacobian_matches_finite_differences(N):
    rng = np.random.default_rng(N)
    I = rng.uniform(1, 3, size=N * (N - 1) // 2)
    rhs = component_rhs(I)

    def f(w):
        return rhs(0.0, w)

    for plane in planes(N)[:: max(1, N - 2)]:
        Om = 1.3
        w0 = np.zeros(I.size)
        w0[plane_index(plane, N)] = Om
        J = linearization(I, plane, Om)
        h = 1e-6
        fd = np.stack([(f(w0 + h * e) - f(w0 - h * e)) / (2 * h) for e in np.eye(I.size)], axis=1)
        np.testing.assert_allclose(J, fd, atol=1e-8, rtol=0)


@pytest.mark.parametrize("N", [3, 4, 5, 6])
def test_eigenvalues_match_numerical_eigenvalues(N):
    rng = np.random.default_rng(10 + N)
    I = rng.uniform(1, 3, size=N * (N - 1) // 2)
    for plane in planes(N):
        r = linear_stability(I, plane, -0.8)
        ev = np.linalg.eigvals(r.jacobian)
        key = lambda z: (round(z.real, 8), round(z.imag, 8))  # noqa: E731
        np.testing.assert_allclose(sorted(r.eigenvalues, key=key), sorted(ev, key=key), atol=1e-10, rtol=0)
        assert r.stable == bool(np.all(np.abs(ev.real) < 1e-10))
        assert r.stable == all(p.nu2 > 0 for p in r.pairs)
        assert len(r.pairs) == N - 2
        np.testing.assert_allclose(np.sort(r.frequencies), np.sort([0.8 * np.sqrt(p.nu2) for p in r.pairs if p.nu2 > 0]),
                                   rtol=1e-13, atol=0)


def test_5d_plane_12_pairs_and_nu2():
    I = dict(zip(planes(5), np.array([5.0, 2.0, 3.0, 1.5, 4.0, 2.5, 1.0, 3.5, 2.2, 1.7])))
    r = linear_stability(np.array(list(I.values())), (1, 2), 2.0)
    assert [p.planes for p in r.pairs] == [((1, 3), (2, 3)), ((1, 4), (2, 4)), ((1, 5), (2, 5))]
    for p, k in zip(r.pairs, (3, 4, 5)):
        a, b = I[(1, k)], I[(2, k)]
        assert p.nu2 == pytest.approx((I[(1, 2)] - a) * (I[(1, 2)] - b) / (a * b), rel=1e-15)
    assert r.stable  # I_12 = 5 is the largest of every triple
    assert "(I_12 - I_13)*(I_12 - I_23) > 0" in r.condition


def test_paper_121_to_132_symbolic():
    """(121)-(127) are right; (132) is wrong: planes 12, 34, 35, 45 are constant, 24 is not."""
    W = plane_symbols("w", 5)
    J = sp.symbols("J1:11", positive=True)  # eq. (131)
    Ip = [None] * 10
    for p, Jk in zip(PAPER_J, J):
        Ip[plane_index(p, 5)] = Jk
    Om, eps = sp.symbols("Omega epsilon")
    C = structure_constants(5)
    rhs = []
    for a in range(10):
        s = sum(int(C[b, c, a]) * W[b] * Ip[c] * W[c] for b, c in zip(*np.nonzero(C[:, :, a])))
        rhs.append(s / Ip[a])
    v = sp.symbols("v1:11")  # varpi_1..varpi_10 = w12, w13, ..., w45 in plane order (eqs. 119-120)
    sub = {W[a]: (Om if a == 0 else 0) + eps * v[a] for a in range(10)}
    lin = [sp.expand(sp.series(r.subs(sub), eps, 0, 2).removeO().coeff(eps, 1)) for r in rhs]
    dv = sp.symbols("dv1:11")  # stands for d varpi / dt
    # printed (122)-(127), each as sign * (J dv - rhs) = 0
    printed = {  # J_k -> J[k-1], varpi_k -> v[k-1]
        1: J[1] * dv[1] + Om * (J[0] - J[3]) * v[4],  # (122)
        2: -J[2] * dv[2] + Om * (J[4] - J[0]) * v[5],  # (123)
        3: J[6] * dv[3] + Om * (J[0] - J[7]) * v[6],  # (124)
        4: -J[3] * dv[4] + Om * (J[0] - J[1]) * v[1],  # (125)
        5: J[4] * dv[5] + Om * (J[2] - J[0]) * v[2],  # (126)
        6: -J[7] * dv[6] + Om * (J[0] - J[6]) * v[3],  # (127)
    }
    for a, expr in printed.items():
        assert sp.simplify(expr.subs(dv[a], lin[a])) == 0
    for a in (0, 7, 8, 9):  # planes 12, 34, 35, 45: constant (121), (128)-(130)
        assert lin[a] == 0
    assert lin[5] != 0  # varpi_6 (plane 24) is NOT constant, contrary to (132)


def test_paper_133_to_138_corrected_solutions():
    """The corrected pair solutions satisfy (122)-(127); the printed sign of varpi_6 (J1 - J5) does not."""
    J = sp.symbols("J1:11", positive=True)
    Om, t, C1, C2 = sp.symbols("Omega t C1 C2")

    nu1 = sp.sqrt((J[0] - J[1]) * (J[0] - J[3]) / (J[1] * J[3]))
    x = C1 * sp.sin(Om * nu1 * t) + C2 * sp.cos(Om * nu1 * t)
    y = J[1] * nu1 / (J[3] - J[0]) * (C1 * sp.cos(Om * nu1 * t) - C2 * sp.sin(Om * nu1 * t))
    assert sp.simplify(J[1] * x.diff(t) + Om * (J[0] - J[3]) * y) == 0  # (122)
    assert sp.simplify(-J[3] * y.diff(t) + Om * (J[0] - J[1]) * x) == 0  # (125)
    nu2 = sp.sqrt((J[0] - J[2]) * (J[0] - J[4]) / (J[2] * J[4]))
    x = C1 * sp.sin(Om * nu2 * t) + C2 * sp.cos(Om * nu2 * t)
    good = J[2] * nu2 / (J[4] - J[0]) * (C1 * sp.cos(Om * nu2 * t) - C2 * sp.sin(Om * nu2 * t))
    bad = J[2] * nu2 / (J[0] - J[4]) * (C1 * sp.cos(Om * nu2 * t) - C2 * sp.sin(Om * nu2 * t))
    eq123 = lambda y: -J[2] * x.diff(t) + Om * (J[4] - J[0]) * y  # noqa: E731
    eq126 = lambda y: J[4] * y.diff(t) + Om * (J[2] - J[0]) * x  # noqa: E731
    assert sp.simplify(eq123(good)) == 0 and sp.simplify(eq126(good)) == 0
    assert sp.simplify(eq123(bad)) != 0
    nu3 = sp.sqrt((J[0] - J[6]) * (J[0] - J[7]) / (J[6] * J[7]))
    x = C1 * sp.sin(Om * nu3 * t) + C2 * sp.cos(Om * nu3 * t)
    y = J[6] * nu3 / (J[7] - J[0]) * (C1 * sp.cos(Om * nu3 * t) - C2 * sp.sin(Om * nu3 * t))
    assert sp.simplify(J[6] * x.diff(t) + Om * (J[0] - J[7]) * y) == 0  # (124)
    assert sp.simplify(-J[7] * y.diff(t) + Om * (J[0] - J[6]) * x) == 0  # (127)


def test_paper_139_140_total_orderings():
    """(139) with equalities is not sufficient; a total ordering is not necessary."""
    # J1 = J2 > J3 >= ... (139 satisfied with equality): defective zero eigenvalue -> not linearly stable
    Jv = _from_J([5.0, 5.0, 4.0, 3.0, 2.9, 2.0, 1.9, 1.8, 1.5, 1.0])
    r = linear_stability(Jv, (1, 2), 1.0)
    assert not r.stable and r.pairs[0].kind == "secular"
    Jm = linearization(Jv, (1, 2), 1.0)
    a, b = plane_index((1, 3), 5), plane_index((2, 3), 5)
    block = Jm[np.ix_([a, b], [a, b])]
    assert np.all(block @ block == 0) and np.any(block != 0)  # nilpotent, non-zero: linear growth
    # no total ordering, still stable: only the triples of plane 12 matter
    Jv = _from_J([5.0, 1.0, 4.5, 2.0, 4.0, 9.0, 1.5, 3.0, 8.0, 6.0])  # J6, J9, J10 > J1; J2 < J3
    assert linear_stability(Jv, (1, 2), 1.0).stable
    # (139)/(140) with strict inequalities: largest / smallest moment -> stable
    assert linear_stability(_from_J(np.arange(10.0, 0.0, -1.0)), (1, 2), 1.0).stable
    assert linear_stability(_from_J(np.arange(1.0, 11.0)), (1, 2), 1.0).stable


def test_stability_condition_sympy_agrees():
    rng = np.random.default_rng(5)
    for N in (4, 5):
        Is = plane_symbols("I", N)
        for plane in planes(N):
            cond = stability_condition(plane, N)
            for _ in range(5):
                I = rng.uniform(1, 3, size=len(Is))
                val = bool(cond.subs(dict(zip(Is, I))))
                assert val == linear_stability(I, plane, 0.7).stable


def test_physical_body_mass_criterion():
    """I_ij = m_i + m_j: rotation in (i, j) is stable iff no m_k lies between m_i and m_j."""
    rng = np.random.default_rng(8)
    for _ in range(10):
        m = rng.uniform(0.5, 3.0, size=5)
        I = _physical(m)
        for i, j in planes(5):
            lo, hi = sorted((m[i - 1], m[j - 1]))
            between = any(lo < m[k - 1] < hi for k in range(1, 6) if k not in (i, j))
            assert linear_stability(I, (i, j), 1.0).stable == (not between)


def _perturbed_growth(I, plane, omega0, t_end, eps=1e-8, rng=0):
    return perturbation_growth(I, plane, omega0, np.linspace(0.0, t_end, 201), eps=eps, rng=rng)


def test_tennis_racket_5d_nonlinear():
    """Intermediate moment within a triple: 1e-8 perturbation grows by orders of magnitude; else stays small."""
    m = np.array([1.0, 3.0, 2.0, 0.5, 4.0])  # m3 lies between m1 and m2 -> plane 12 unstable (triple k = 3)
    I = _physical(m)
    r = linear_stability(I, (1, 2), 1.0)
    assert not r.stable
    assert [p.k for p in r.pairs if p.kind == "unstable"] == [3]
    rate = r.growth_rates[0]
    t_end = 14.0 / rate
    growth = _perturbed_growth(I, (1, 2), 1.0, t_end)
    assert growth[-1] > 1e-3 and growth[0] < 1e-7  # >= 4 orders of magnitude
    # early growth follows the linear rate: log-slope within 10%
    k1, k2 = 60, 120
    t = np.linspace(0.0, t_end, 201)
    slope = np.log(growth[k2] / growth[k1]) / (t[k2] - t[k1])
    assert slope == pytest.approx(rate, rel=0.1)
    # the plane (2, 5): m2 = 3, m5 = 4 and no m_k between -> stable; stays of order 1e-8
    assert linear_stability(I, (2, 5), 1.0).stable
    growth = _perturbed_growth(I, (2, 5), 1.0, t_end)
    assert np.max(growth) < 1e-6


def test_bad_input():
    I = np.arange(1.0, 11.0)
    with pytest.raises(ValueError, match="unknown plane"):
        linear_stability(I, (2, 1), 1.0)
    with pytest.raises(ValueError, match="unknown plane"):
        linear_stability(I, (1, 6), 1.0)
    with pytest.raises(ValueError, match="finite"):
        linear_stability(I, (1, 2), np.inf)
    with pytest.raises(TypeError, match="omega0"):
        linear_stability(I, (1, 2), "fast")
    with pytest.raises(TypeError, match="unexpected keyword argument 'Omega'"):
        linear_stability(I, (1, 2), Omega=1.0)
    with pytest.raises(TypeError, match="unexpected keyword argument 'seed'"):
        perturbation_growth(I, (1, 2), 1.0, [0.0, 1.0], seed=1)
    with pytest.raises(ValueError, match="> 0"):
        linear_stability(-I, (1, 2), 1.0)
    with pytest.raises(ValueError, match="N\\(N-1\\)/2"):
        linear_stability(np.ones(7), (1, 2), 1.0)
    r = linear_stability(I, (1, 2), 0.0)
    assert r.stable and np.all(r.eigenvalues == 0)


def test_accepts_rigid_body_and_inertia():
    inertia = hyperrotor.Inertia.quartet(0.5, axis=5, N=5)
    I = inertia.moments
    for obj in (inertia, hyperrotor.RigidBody(inertia)):
        for plane in itertools.islice(planes(5), 4):
            a, b = linear_stability(obj, plane, 1.1), linear_stability(I, plane, 1.1)
            np.testing.assert_array_equal(a.eigenvalues, b.eigenvalues)
            assert a.stable == b.stable


def test_locked_body_keeps_labels():
    """A body from RigidBody.lock uses its original axis labels for planes, pairs and k."""
    body = hyperrotor.RigidBody(np.arange(1.0, 11.0))
    red = body.lock(1)  # axes (2, 3, 4, 5)
    r = linear_stability(red, (2, 3), 1.0)
    assert r.plane == (2, 3)
    assert [p.k for p in r.pairs] == [4, 5]
    assert [p.planes for p in r.pairs] == [((2, 4), (3, 4)), ((2, 5), (3, 5))]
    I = dict(zip(planes(5), np.arange(1.0, 11.0)))
    assert r.pairs[0].nu2 == pytest.approx((I[(2, 3)] - I[(2, 4)]) * (I[(2, 3)] - I[(3, 4)]) / (I[(2, 4)] * I[(3, 4)]),
                                           rel=1e-12)
    assert "I_23 - I_24" in r.condition
    with pytest.raises(ValueError, match="unknown plane"):
        linear_stability(red, (1, 2), 1.0)


def test_condition_at_large_n_is_priced_and_uses_only_the_planes_it_needs():
    """stability_condition builds the 2N - 3 symbols through the plane (named as plane_symbols names them)
    and is priced (model 'stability_condition'): N = 1000 is refused under a 1 s budget in milliseconds."""
    cond = stability_condition((1, 3), 4)
    I = dict(zip(planes(4), hyperrotor.plane_symbols("I", 4)))
    assert cond == sp.And((I[1, 3] - I[1, 2]) * (I[1, 3] - I[2, 3]) > 0, (I[1, 3] - I[1, 4]) * (I[1, 3] - I[3, 4]) > 0)
    with hyperrotor.options(max_seconds=1.0):
        with pytest.raises(hyperrotor.BudgetError, match="stability_condition"):
            stability_condition((1, 2), 1000)


def test_linearization_reads_a_locked_body_in_its_own_axis_labels():
    """linearization took (2, 3) of a body locked on axis 1 (axes 2..5) as its local plane (3, 4), silently, and
    refused (4, 5); linear_stability read the labels. The Jacobian is the unlocked body's, restricted."""
    body = hyperrotor.RigidBody(hyperrotor.Inertia.from_mass_tensor([1.0, 2.0, 3.0, 4.0, 5.0]))
    locked = body.lock(1)
    kept = [plane_index(q, 5) for q in planes(5) if 1 not in q]
    for plane in [(2, 3), (4, 5), (2, 5)]:
        J = linearization(locked, plane, 1.3)
        np.testing.assert_array_equal(J, linear_stability(locked, plane, 1.3).jacobian)
        np.testing.assert_array_equal(J, linearization(body, plane, 1.3)[np.ix_(kept, kept)])
    with pytest.raises(ValueError, match=r"unknown plane \(1, 2\).*axes \(2, 3, 4, 5\)"):
        linearization(locked, (1, 2), 1.0)


@pytest.mark.parametrize("N", range(2, 9))
def test_the_slice_of_one_plane_is_the_table_s(N):
    """linearization builds the brackets of its plane alone (the whole n^3 table was 5.2 GB at N = 60)."""
    from hyperrotor.conventions import _structure_constants_slice

    C = structure_constants(N)
    n = C.shape[0]
    for b, plane in enumerate(planes(N)):
        d, a, c = _structure_constants_slice(N, plane)
        S = np.zeros((n, n), dtype=np.int64)
        S[d, a] = c
        np.testing.assert_array_equal(S, C[:, b, :])
        assert len(set(zip(d.tolist(), a.tolist()))) == d.size == 2 * (N - 2)  # (each neighbour once)


def test_large_bodies_and_large_moments():
    """N = 60 was refused (the n^3 table, 5.2 GB, for a Jacobian of 25 MB); moments of 1e200 gave nu^2 = inf."""
    rng = np.random.default_rng(60)
    I = rng.uniform(1.0, 3.0, 60 * 59 // 2)
    r = linear_stability(I, (3, 7), 0.5)
    assert r.jacobian.shape == (I.size, I.size) and np.count_nonzero(r.jacobian) <= 2 * 58
    p = plane_index((3, 7), 60)
    for pair in r.pairs:  # the Jacobian's entries carry the pair's nu^2: J[P1, P2] J[P2, P1] = -Omega^2 nu^2
        a, b = (plane_index(q, 60) for q in pair.planes)
        assert r.jacobian[a, b] * r.jacobian[b, a] == pytest.approx(-0.25 * pair.nu2, rel=1e-12)
        assert pair.nu2 == pytest.approx((I[p] - I[a]) * (I[p] - I[b]) / (I[a] * I[b]), rel=1e-12)
    big = linear_stability([1e200, 1.0, 2.0], (1, 2), 1.0)
    small = linear_stability([1.0, 1e-200, 2e-200], (1, 2), 1.0)  # (the same ratios of differences to moments)
    assert np.isfinite(big.frequencies).all() and np.isfinite(big.eigenvalues).all()
    assert big.pairs[0].nu2 == np.inf  # (5e399: beyond the double range; its root is not)
    np.testing.assert_allclose(big.frequencies, [np.sqrt(1e200 - 1.0) * np.sqrt((1e200 - 2.0) / 2.0)], rtol=1e-14, atol=0)
    assert big.stable and small.stable


def test_equal_moments_are_judged_against_the_two_compared():
    """rtol * max(I) over the whole body made every difference of order 1 an 'equality' beside a moment of 1e14: an
    oscillating pair (eigenvalues +-0.707i, numpy's of the Jacobian) was reported secular with eigenvalues 0."""
    I = [1.0, 2.0, 1e14]
    r = linear_stability(I, (1, 2), 1.0)
    assert [p.kind for p in r.pairs] == ["oscillating"] and r.stable
    ev = np.linalg.eigvals(r.jacobian)
    np.testing.assert_allclose(np.sort(ev.imag), np.sort(r.eigenvalues.imag), rtol=0, atol=1e-12)
    near = linear_stability([1.0, 1.0 + 1e-13, 3.0], (1, 2), 1.0)  # (a difference within rtol of the two: equal)
    assert near.pairs[0].kind == "secular"
