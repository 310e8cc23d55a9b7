"""Property-based laws of the plane conventions (hyperrotor.conventions), for random N and data.

Exact laws (integer or sign data, pure index maps) are compared exactly; floating laws that
multiply matrices use the scaled round-off tolerance of tests/tolerance.py.
"""
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import hyperrotor as hr
from tolerance import norm, scaled_tol

SETTINGS = settings(max_examples=40, deadline=None)
dims = st.integers(2, 7)
conventions = st.sampled_from(hr.CONVENTIONS)
finite = st.floats(-1e6, 1e6, allow_nan=False, allow_infinity=False, allow_subnormal=False)


@st.composite
def components(draw, N=None, batch=False):
    N = draw(dims) if N is None else N
    shape = (draw(st.integers(1, 3)), hr.n_planes(N)) if batch else (hr.n_planes(N),)
    return N, draw(arrays(np.float64, shape, elements=finite))


def _sign_matrix(N):
    return np.diag([(-1.0) ** i for i in range(1, N + 1)])


@SETTINGS
@given(components(batch=True), conventions)
def test_components_matrix_round_trip(data, convention):
    N, x = data
    M = hr.to_matrix(x, convention=convention)
    assert M.shape == x.shape[:-1] + (N, N)
    assert np.array_equal(M, -np.swapaxes(M, -1, -2))  # antisymmetric, exactly
    assert np.array_equal(hr.to_components(M, convention=convention), x)  # a pure index/sign map: exact


@SETTINGS
@given(dims, st.data())
def test_matrix_components_round_trip(N, data):
    A = data.draw(arrays(np.float64, (N, N), elements=finite))
    M = A - A.T  # any antisymmetric matrix
    for c in hr.CONVENTIONS:
        assert np.array_equal(hr.to_matrix(hr.to_components(M, convention=c), convention=c), M)


@SETTINGS
@given(components())
def test_paper_and_standard_differ_by_the_checkerboard(data):
    """eq. (21): paper entry (i, j) = (-1)^(i+j) standard entry = S M S with S = diag((-1)^i)."""
    N, x = data
    S = _sign_matrix(N)
    assert np.array_equal(hr.to_matrix(x, convention="paper"), S @ hr.to_matrix(x, convention="standard") @ S)
    signs = hr.plane_signs(N, convention="paper")
    assert np.array_equal(signs, [(-1) ** (i + j) for i, j in hr.planes(N)])
    assert np.array_equal(hr.plane_signs(N, convention="standard"), np.ones(hr.n_planes(N)))
    # the map between the conventions' components is the sign vector (an involution)
    assert np.array_equal(hr.to_components(hr.to_matrix(x, convention="paper"), convention="standard"), signs * x)
    assert np.array_equal(hr.to_components(hr.to_matrix(signs * x, convention="standard"), convention="paper"), x)


@SETTINGS
@given(dims, conventions, st.data())
def test_basis_matrix_is_to_matrix_of_a_unit_vector(N, convention, data):
    k = data.draw(st.integers(0, hr.n_planes(N) - 1))
    p = hr.planes(N)[k]
    assert hr.plane_index(p, N) == k
    e = np.zeros(hr.n_planes(N), dtype=int)
    e[k] = 1
    assert np.array_equal(hr.basis_matrix(p, N, convention=convention), hr.to_matrix(e, convention=convention))
    assert hr.dimension_from_count(hr.n_planes(N)) == N


@SETTINGS
@given(dims, conventions, st.data())
def test_lie_bracket_is_the_matrix_commutator_in_both_conventions(N, convention, data):
    x = data.draw(arrays(np.float64, hr.n_planes(N), elements=st.floats(-100, 100)))
    y = data.draw(arrays(np.float64, hr.n_planes(N), elements=st.floats(-100, 100)))
    X, Y = hr.to_matrix(x, convention=convention), hr.to_matrix(y, convention=convention)
    z = hr.lie_bracket(x, y)
    tol = scaled_tol(norm(X) * norm(Y), dim=N)
    np.testing.assert_allclose(z, hr.to_components(X @ Y - Y @ X, convention=convention, atol=2 * tol), rtol=0, atol=tol)
    np.testing.assert_allclose(z, -hr.lie_bracket(y, x), rtol=0, atol=tol)


@SETTINGS
@given(st.integers(3, 6), st.data())
def test_jacobi_identity_of_lie_bracket(N, data):
    x, y, z = (data.draw(arrays(np.float64, hr.n_planes(N), elements=st.floats(-10, 10))) for _ in range(3))
    br = hr.lie_bracket
    jac = br(x, br(y, z)) + br(y, br(z, x)) + br(z, br(x, y))
    np.testing.assert_allclose(jac, 0, rtol=0, atol=scaled_tol(norm(x) * norm(y) * norm(z), dim=hr.n_planes(N), k=12))


@SETTINGS
@given(dims, st.data())
def test_structure_constants_are_integer_and_totally_antisymmetric(N, data):
    C = hr.structure_constants(N)
    a, b, c = (data.draw(st.integers(0, hr.n_planes(N) - 1)) for _ in range(3))
    assert C[a, b, c] == -C[b, a, c] == C[b, c, a] == C[c, a, b]
    assert C[a, b, c] in (-1, 0, 1)
