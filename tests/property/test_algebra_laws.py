"""Property-based laws of so(N): operator brackets and contraction identities for random planes
and N (exact, SymPy normal form), and representation brackets and Casimirs of random irreps
(floating, with the scaled round-off tolerances of tests/tolerance.py).
"""
from fractions import Fraction

import numpy as np
import sympy as sp
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from hyperrotor.conventions import plane_index, planes, structure_constants
from hyperrotor.quantum import angular_momentum_operators, casimir_eigenvalue, commutator, irrep, weyl_dimension
from hyperrotor.quantum.operators import coordinate_symbols
from tolerance import norm, row_length, scaled_tol

SETTINGS = settings(max_examples=20, deadline=None)


def _ordered(L, a, b):
    """L^{ab} for an ordered pair a != b (L^{ba} = -L^{ab})."""
    return L[(a, b)] if a < b else -1 * L[(b, a)]


@st.composite
def plane_pairs(draw, max_N=6):
    N = draw(st.integers(2, max_N))
    ps = planes(N)
    return N, draw(st.sampled_from(ps)), draw(st.sampled_from(ps))


@SETTINGS
@given(plane_pairs())
def test_operator_commutator_has_the_structure_constants(data):
    """[L^a, L^b] = sum_c C_ab^c L^c exactly, C from hyperrotor.conventions (overall sign +1)."""
    N, pa, pb = data
    L = angular_momentum_operators(N)
    C = structure_constants(N)
    a, b = plane_index(pa, N), plane_index(pb, N)
    rhs = 0 * L[pa]
    for c in np.nonzero(C[a, b])[0]:
        rhs = rhs + int(C[a, b, c]) * L[planes(N)[c]]
    assert commutator(L[pa], L[pb]) == rhs
    assert commutator(L[pb], L[pa]) == -1 * rhs


@SETTINGS
@given(st.integers(3, 6), st.data())
def test_operator_contraction_identity_random_plane(N, data):
    """sum_{k != i,j} [L^{ik}, L^{kj}] = (N - 2) L^{ij} for a random ordered pair (i, j), i != j."""
    i = data.draw(st.integers(1, N))
    j = data.draw(st.integers(1, N).filter(lambda v: v != i))
    L = angular_momentum_operators(N)
    total = 0 * L[(1, 2)]
    for k in range(1, N + 1):
        if k not in (i, j):
            total = total + commutator(_ordered(L, i, k), _ordered(L, k, j))
    assert total == (N - 2) * _ordered(L, i, j)


@SETTINGS
@given(st.integers(2, 4), plane_pairs(max_N=4), st.data())
def test_operator_bracket_acts_on_random_polynomials(deg, data, draw):
    """The bracket identity as differential operators applied to a random polynomial (naive SymPy)."""
    N, pa, pb = data
    x = coordinate_symbols(N)
    coeffs = draw.draw(st.lists(st.integers(-3, 3), min_size=N, max_size=N))
    f = sum(c * v**deg for c, v in zip(coeffs, x)) + x[0] * x[-1] ** (deg - 1)
    L = angular_momentum_operators(N)
    C = structure_constants(N)
    a, b = plane_index(pa, N), plane_index(pb, N)
    lhs = L[pa](L[pb](f)) - L[pb](L[pa](f))
    rhs = sum((int(C[a, b, c]) * L[planes(N)[c]](f) for c in np.nonzero(C[a, b])[0]), sp.Integer(0))
    assert sp.expand(lhs - rhs) == 0


@st.composite
def highest_weights(draw, max_dim=64):
    """A random dominant so(N) highest weight (all integers or all half-integers), dim <= max_dim."""
    N = draw(st.integers(3, 7))
    r = N // 2
    half = draw(st.booleans())
    tail = sorted(draw(st.lists(st.integers(0, 3), min_size=r, max_size=r)), reverse=True)
    m = [Fraction(2 * v + 1, 2) if half else Fraction(v) for v in tail]
    if N % 2 == 0 and draw(st.booleans()):
        m[-1] = -m[-1]
    assume(weyl_dimension(N, tuple(m)) <= max_dim)
    return N, tuple(m)


@settings(max_examples=15, deadline=None)
@given(highest_weights())
def test_irrep_brackets_casimir_and_antihermiticity(data):
    N, m = data
    rep = irrep(N, m)
    assert rep.dim == weyl_dimension(N, m)
    G = rep.generators()
    pl = planes(N)
    C = structure_constants(N)
    r = row_length(*G.values())
    big = max(norm(X) for X in G.values())
    tol = scaled_tol(big**2, dim=r, k=8)  # a commutator of sparse generators with rows of length <= r
    for a, pa in enumerate(pl):
        X = G[pa]
        assert abs(X + X.conj().T).max() <= scaled_tol(norm(X), dim=r) if X.nnz else True
        for b in range(a + 1, len(pl)):
            res = X @ G[pl[b]] - G[pl[b]] @ X
            for c in np.nonzero(C[a, b])[0]:
                res = res - int(C[a, b, c]) * G[pl[c]]
            assert (abs(res).max() if res.nnz else 0.0) <= tol
    c = float(casimir_eigenvalue(N, m))
    cas = sum((X @ X for X in G.values()), 0 * G[pl[0]]).toarray()
    np.testing.assert_allclose(cas, -c * np.eye(rep.dim), rtol=0, atol=scaled_tol(big**2, dim=r, k=4 * len(pl)))
