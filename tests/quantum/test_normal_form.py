"""Tests of the exact Weyl-algebra normal form (hyperrotor.quantum.normal_form)."""
from __future__ import annotations

import random
from fractions import Fraction

import pytest
import sympy as sp

from hyperrotor.quantum.normal_form import WeylElement, dict_to_polynomial, polynomial_to_dict


def _coords(N):
    return sp.symbols(f"x1:{N + 1}", real=True)


def _random_element(N, rng, n_terms=3, max_exp=2):
    terms = {}
    for _ in range(n_terms):
        m = tuple(rng.randint(0, max_exp) for _ in range(N))
        a = tuple(rng.randint(0, max_exp) for _ in range(N))
        terms[(m, a)] = Fraction(rng.randint(-5, 5), rng.randint(1, 3))
    return WeylElement(N, terms)


@pytest.mark.parametrize("N", [1, 2, 3, 4])
def test_canonical_commutation_relations(N):
    for i in range(N):
        for j in range(N):
            d, x = WeylElement.derivative(N, i), WeylElement.coordinate(N, j)
            assert d.commutator(x) == WeylElement.scalar(N, int(i == j))
            assert d.commutator(WeylElement.derivative(N, j)) == 0
            assert x.commutator(WeylElement.coordinate(N, i)) == 0


@pytest.mark.parametrize("N", [1, 2, 3])
def test_product_matches_sympy_composition(N):
    """The Leibniz-rule product agrees with composing the actions on a generic function."""
    rng = random.Random(1234 + N)
    xs = _coords(N)
    f = sp.Function("f")(*xs)
    for _ in range(4):
        A, B = _random_element(N, rng), _random_element(N, rng)
        lhs = (A * B).apply(f, xs)
        rhs = A.apply(B.apply(f, xs), xs)
        assert sp.expand(lhs - rhs) == 0


def test_associativity_and_distributivity():
    rng = random.Random(7)
    for _ in range(5):
        A, B, C = (_random_element(3, rng) for _ in range(3))
        assert (A * B) * C == A * (B * C)
        assert A * (B + C) == A * B + A * C
        assert (A - B) + B == A
        # Jacobi identity
        jac = A.commutator(B.commutator(C)) + B.commutator(C.commutator(A)) + C.commutator(A.commutator(B))
        assert jac.is_zero()


def test_symbolic_coefficients_normalize():
    hbar = sp.Symbol("hbar", positive=True)
    L = WeylElement.rotation(3, 0, 1)
    H = L.scale(-sp.I * hbar)
    assert H * H == (L * L).scale(-hbar**2)
    assert (H - H).is_zero()
    assert H.is_symbolic() and not L.is_symbolic()
    assert L.scale(sp.Rational(1, 2)).terms[((1, 0, 0), (0, 1, 0))] == Fraction(1, 2)


@pytest.mark.parametrize("N", [2, 3])
def test_sympy_round_trip(N):
    rng = random.Random(99 + N)
    xs = _coords(N)
    f = sp.Function("f")(*xs)
    for _ in range(3):
        A = _random_element(N, rng)
        assert WeylElement.from_sympy(A.to_sympy(f, xs), f, xs) == A
        # parsing the *evaluated* action gives the same operator
        assert WeylElement.from_sympy(A.apply(f, xs), f, xs) == A


def test_apply_to_poly_matches_sympy():
    rng = random.Random(5)
    xs = _coords(3)
    poly = sp.expand((xs[0] + 2 * xs[1] - xs[2]) ** 3 + xs[0] * xs[2] ** 2)
    pd = polynomial_to_dict(poly, xs)
    for _ in range(4):
        A = _random_element(3, rng)
        fast = dict_to_polynomial(A.apply_to_poly(pd), xs)
        assert sp.expand(fast - A.apply(poly, xs)) == 0


def test_polynomial_dict_round_trip_and_errors():
    xs = _coords(2)
    h = sp.Symbol("h")
    p = 3 * xs[0] ** 2 * xs[1] - h * xs[1] + sp.Rational(1, 3)
    d = polynomial_to_dict(p, xs)
    assert d[(2, 1)] == 3 and d[(0, 0)] == Fraction(1, 3) and d[(0, 1)] == -h
    assert sp.expand(dict_to_polynomial(d, xs) - p) == 0
    with pytest.raises(ValueError, match="not a polynomial"):
        polynomial_to_dict(1 / xs[0], xs)
    with pytest.raises(TypeError):
        polynomial_to_dict("x1", xs)


def test_bad_input():
    A, B = WeylElement.rotation(3, 0, 1), WeylElement.rotation(4, 0, 1)
    with pytest.raises(ValueError, match="3 and 4 variables"):
        A * B
    with pytest.raises(ValueError, match="3 and 4 variables"):
        A + B
    with pytest.raises(ValueError, match="exponent tuples"):
        WeylElement(2, {((1,), (0, 1)): 1})
    with pytest.raises(TypeError):
        WeylElement(2.5)
    with pytest.raises(ValueError, match="two different indices"):
        WeylElement.rotation(3, 1, 1)
    xs = _coords(3)
    with pytest.raises(TypeError, match="SymPy expressions"):
        A.apply([1, 2], xs)
    with pytest.raises(TypeError, match="coefficient"):
        A.scale("two")
    f = sp.Function("f")(*xs)
    with pytest.raises(ValueError, match="not linear"):
        WeylElement.from_sympy(f**2, f, xs)
    with pytest.raises(ValueError, match="not a polynomial"):
        WeylElement.from_sympy(sp.sin(xs[0]) * f, f, xs)
