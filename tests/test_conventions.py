"""Tests of hyperrotor.conventions: plane order, matrix maps, structure constants, brackets."""
import itertools

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import hyperrotor as hr
from hyperrotor.conventions import check_dimension
from tolerance import norm, scaled_tol


def _sign_matrix(N):
    return np.diag([(-1) ** i for i in range(1, N + 1)])


def test_planes_paper_order_n5():
    assert hr.planes(5) == ((1, 2), (1, 3), (1, 4), (1, 5), (2, 3), (2, 4), (2, 5), (3, 4), (3, 5), (4, 5))


@pytest.mark.parametrize("N", range(2, 12))
def test_planes_count_and_index(N):
    ps = hr.planes(N)
    assert len(ps) == hr.n_planes(N) == N * (N - 1) // 2
    assert list(ps) == sorted(ps)
    assert all(1 <= i < j <= N for i, j in ps)
    assert [hr.plane_index(p, N) for p in ps] == list(range(len(ps)))
    assert hr.dimension_from_count(len(ps)) == N


def test_paper_matrix_is_eq21():
    w = hr.plane_symbols("omega", 5)
    M = hr.to_matrix(w)
    o = dict(zip(hr.planes(5), w))
    # eq. (21), typed row by row from the paper
    expected = sp.Matrix([
        [0, -o[1, 2], o[1, 3], -o[1, 4], o[1, 5]],
        [o[1, 2], 0, -o[2, 3], o[2, 4], -o[2, 5]],
        [-o[1, 3], o[2, 3], 0, -o[3, 4], o[3, 5]],
        [o[1, 4], -o[2, 4], o[3, 4], 0, -o[4, 5]],
        [-o[1, 5], o[2, 5], -o[3, 5], o[4, 5], 0],
    ])
    assert M == expected


@pytest.mark.parametrize("convention", hr.CONVENTIONS)
@pytest.mark.parametrize("N", [2, 3, 4, 5, 7])
def test_round_trip_numpy_batched(N, convention):
    rng = np.random.default_rng(N)
    x = rng.normal(size=(3, 4, hr.n_planes(N)))
    M = hr.to_matrix(x, convention=convention)
    assert M.shape == (3, 4, N, N)
    assert np.array_equal(M, -np.swapaxes(M, -1, -2))
    assert np.array_equal(hr.to_components(M, convention=convention), x)


@pytest.mark.parametrize("convention", hr.CONVENTIONS)
def test_round_trip_sympy(convention):
    w = hr.plane_symbols("w", 4)
    M = hr.to_matrix(list(w), convention=convention)
    assert isinstance(M, sp.MatrixBase)
    assert list(hr.to_components(M, convention=convention)) == list(w)


@pytest.mark.parametrize("N", [3, 4, 5, 6])
def test_paper_is_sign_conjugate_of_standard(N):
    rng = np.random.default_rng(1)
    x = rng.normal(size=hr.n_planes(N))
    S = _sign_matrix(N)
    assert np.allclose(hr.to_matrix(x, convention="paper"), S @ hr.to_matrix(x, convention="standard") @ S, atol=0, rtol=0)


@given(arrays(np.float64, 10, elements=st.floats(-1e6, 1e6)))
@settings(max_examples=50, deadline=None)
def test_round_trip_property(x):
    for c in hr.CONVENTIONS:
        assert np.array_equal(hr.to_components(hr.to_matrix(x, convention=c), convention=c), x)


def _explicit_commutator_components(a, b, N, convention):
    A = hr.basis_matrix(a, N, convention=convention)
    B = hr.basis_matrix(b, N, convention=convention)
    return hr.to_components(A @ B - B @ A, convention=convention)


@pytest.mark.parametrize("convention", hr.CONVENTIONS)
@pytest.mark.parametrize("N", [2, 3, 4, 5, 6])
def test_structure_constants_match_matrix_commutators(N, convention):
    C = hr.structure_constants(N)
    for ia, a in enumerate(hr.planes(N)):
        for ib, b in enumerate(hr.planes(N)):
            assert np.array_equal(C[ia, ib], _explicit_commutator_components(a, b, N, convention))


@pytest.mark.parametrize("N", [3, 4, 5, 6])
def test_structure_constants_total_antisymmetry_and_jacobi(N):
    C = hr.structure_constants(N).astype(int)
    assert np.array_equal(C, -np.transpose(C, (1, 0, 2)))
    assert np.array_equal(C, np.transpose(C, (1, 2, 0)))  # cyclic: f_abc = f_bca
    # Jacobi: sum_d C_ab^d C_dc^e + cyclic = 0
    J = np.einsum("abd,dce->abce", C, C)
    assert not np.any(J + np.transpose(J, (1, 2, 0, 3)) + np.transpose(J, (2, 0, 1, 3)))


def test_lie_bracket_numpy_matches_matrix():
    rng = np.random.default_rng(7)
    x, y = rng.normal(size=(2, 2, 10))
    z = hr.lie_bracket(x, y)
    X, Y = hr.to_matrix(x, convention="standard"), hr.to_matrix(y, convention="standard")
    assert np.allclose(z, hr.to_components(X @ Y - Y @ X, convention="standard"), rtol=0, atol=scaled_tol(norm(x) * norm(y), dim=5))


def test_lie_poisson_gives_euler_equations_n5():
    L = hr.plane_symbols("L", 5)
    I = hr.plane_symbols("I", 5, positive=True)
    H = sum(l**2 / (2 * i) for l, i in zip(L, I))
    w = [l / i for l, i in zip(L, I)]
    # Euler equations from explicit matrices: dL/dt = W L - L W (standard and paper alike)
    for c in hr.CONVENTIONS:
        W, Lm = hr.to_matrix(w, convention=c), hr.to_matrix(L, convention=c)
        rhs = hr.to_components(W * Lm - Lm * W, convention=c)
        for a, La in enumerate(L):
            assert sp.simplify(hr.lie_poisson_bracket(La, H, L) - rhs[a]) == 0


def test_lie_poisson_3d_textbook_bracket():
    # map M1 = L23, M2 = -L13, M3 = L12: body-frame bracket {M_i, M_j} = -eps_ijk M_k
    L12, L13, L23 = hr.plane_symbols("L", 3)
    M = [L23, -L13, L12]
    for i, j, k in itertools.permutations(range(3)):
        eps = sp.LeviCivita(i, j, k)
        assert sp.expand(hr.lie_poisson_bracket(M[i], M[j], [L12, L13, L23]) + eps * M[k]) == 0


def test_casimir_commutes_with_everything():
    L = hr.plane_symbols("L", 5)
    C2 = sum(l**2 for l in L)
    assert all(hr.lie_poisson_bracket(C2, l, L) == 0 for l in L)


def test_bivector_table_same_in_both_conventions():
    assert hr.bivector_product_table(5, convention="paper") == hr.bivector_product_table(5, convention="standard")


def test_bivector_table_entries_n4():
    T = hr.bivector_product_table(4)
    e = dict(zip(hr.planes(4), hr.plane_symbols("e", 4)))
    idx = {p: k for k, p in enumerate(hr.planes(4))}
    # [E12, E23] = E13 and [E12, E13] = -E23 from E_ab = e_a e_b^T - e_b e_a^T
    assert T[idx[1, 2], idx[2, 3]] == e[1, 3]
    assert T[idx[1, 2], idx[1, 3]] == -e[2, 3]
    assert T[idx[1, 2], idx[3, 4]] == 0
    assert T == -T.T


@pytest.mark.parametrize("bad", [1, 0, -3])
def test_bad_dimension_value(bad):
    with pytest.raises(ValueError, match=f"got {bad}"):
        hr.planes(bad)


@pytest.mark.parametrize("bad", [2.5, "5", None, True])
def test_bad_dimension_type(bad):
    with pytest.raises(TypeError, match="integer"):
        check_dimension(bad)


def test_bad_component_count():
    with pytest.raises(ValueError, match="7 plane components"):
        hr.to_matrix(np.zeros(7))


def test_unknown_convention():
    with pytest.raises(ValueError, match="unknown convention 'textbook'"):
        hr.to_matrix([1, 2, 3], convention="textbook")


def test_non_antisymmetric_matrix():
    M = np.eye(3)
    with pytest.raises(ValueError, match="not antisymmetric"):
        hr.to_components(M)
    with pytest.raises(ValueError, match="not antisymmetric"):
        hr.to_components(sp.Matrix([[0, 1], [1, 0]]))


def test_non_square_matrix():
    with pytest.raises(ValueError, match=r"shape \(3, 4\)"):
        hr.to_components(np.zeros((3, 4)))


def test_unknown_plane():
    with pytest.raises(ValueError, match=r"unknown plane \(2, 1\)"):
        hr.plane_index((2, 1), 4)
    with pytest.raises(ValueError, match="1 <= i < j <= 3"):
        hr.plane_index((1, 4), 3)


def test_mismatched_bracket_lengths():
    with pytest.raises(ValueError, match="different length"):
        hr.lie_bracket(np.zeros(3), np.zeros(6))


def test_docstring_examples():
    import doctest

    import hyperrotor.conventions as mod

    result = doctest.testmod(mod, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted >= 3 and result.failed == 0


def test_dimensions_over_the_budget_are_refused_by_name_and_the_budget_can_be_raised():
    """options['max_dimension'] (one check, _validate.dimension) bounds every so(N) constructor."""
    limit = hr.options["max_dimension"]
    for f in (hr.planes, hr.n_planes, hr.structure_constants):
        with pytest.raises(ValueError, match=rf"N = {limit + 1} .* over the budget hr\.options\['max_dimension'\] = {limit};"):
            f(limit + 1)
    with hr.options(max_dimension=limit + 1):
        assert hr.n_planes(limit + 1) == (limit + 1) * limit // 2
