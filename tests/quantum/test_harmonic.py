"""Tests of harmonic polynomial bases and sphere integrals (hyperrotor.quantum.harmonic)."""
from __future__ import annotations

from fractions import Fraction
from math import comb

import numpy as np
import pytest
import sympy as sp
from cpu_clock import call_cpu

from hyperrotor.quantum.harmonic import (
    apply_to_polynomial,
    harmonic_dimension,
    harmonic_polynomial_basis,
    orthogonal_harmonic_basis,
    orthonormal_harmonic_basis,
    sphere_inner_product,
    sphere_monomial_integral,
)
from hyperrotor.quantum.normal_form import polynomial_to_dict
from hyperrotor.quantum.operators import (
    angular_momentum_operators,
    casimir_operator,
    coordinate_symbols,
    laplacian_operator,
)


def _n_monomials(N, l):
    return comb(l + N - 1, N - 1) if l >= 0 else 0


@pytest.mark.parametrize("N", range(2, 8))
def test_dimension_formula(N):
    for l in range(6):
        basis = harmonic_polynomial_basis(N, l, as_dict=True)
        # dim H_l = #monomials(l) - #monomials(l-2)  (P_l = H_l + r^2 P_{l-2})
        assert len(basis) == harmonic_dimension(N, l) == _n_monomials(N, l) - _n_monomials(N, l - 2)
    if N == 2:
        assert [harmonic_dimension(2, l) for l in range(4)] == [1, 2, 2, 2]
    if N == 3:
        assert all(harmonic_dimension(3, l) == 2 * l + 1 for l in range(8))
    if N == 4:
        assert all(harmonic_dimension(4, l) == (l + 1) ** 2 for l in range(8))


@pytest.mark.parametrize("N", range(2, 7))
def test_basis_is_harmonic_homogeneous_independent(N):
    lap = laplacian_operator(N)
    for l in range(5):
        basis = harmonic_polynomial_basis(N, l, as_dict=True)
        monos = sorted({m for p in basis for m in p})
        assert all(sum(m) == l for m in monos)
        for p in basis:
            assert apply_to_polynomial(lap, p) == {}
        A = np.array([[float(p.get(m, 0)) for m in monos] for p in basis])
        assert np.linalg.matrix_rank(A) == len(basis)


@pytest.mark.parametrize("N", [3, 4, 5, 6])
def test_casimir_eigenvalue(N):
    """sum (L^ij)^2 h = -l(l+N-2) h on every basis polynomial, l = 0..4."""
    C2 = casimir_operator(N)
    for l in range(5):
        lam = -l * (l + N - 2)
        for p in harmonic_polynomial_basis(N, l, as_dict=True):
            out = apply_to_polynomial(C2, p)
            assert out == {m: lam * c for m, c in p.items() if lam * c}


def test_casimir_eigenvalue_sympy_path():
    xs = coordinate_symbols(3)
    C2 = casimir_operator(3)
    for p in harmonic_polynomial_basis(3, 3):
        assert sp.expand(C2(p) + 12 * p) == 0
    # paper coordinates for N = 5
    C5 = casimir_operator(5, coordinates="paper")
    for p in harmonic_polynomial_basis(5, 2, coordinates="paper"):
        assert sp.expand(C5(p) + 2 * (2 + 3) * p) == 0
    assert xs[0] in harmonic_polynomial_basis(3, 1)


def test_sphere_integrals_against_sympy():
    t, ph = sp.symbols("theta phi", real=True)
    # circle
    for a in [(0, 0), (2, 0), (2, 2), (4, 2), (1, 1), (3, 0)]:
        direct = sp.integrate(sp.cos(t) ** a[0] * sp.sin(t) ** a[1], (t, 0, 2 * sp.pi))
        assert sp.simplify(sphere_monomial_integral(a) - direct) == 0
    # 2-sphere
    x, y, z = sp.sin(t) * sp.cos(ph), sp.sin(t) * sp.sin(ph), sp.cos(t)
    for a in [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 0, 4), (2, 2, 2), (1, 0, 1)]:
        integrand = x ** a[0] * y ** a[1] * z ** a[2] * sp.sin(t)
        direct = sp.integrate(sp.integrate(sp.expand(integrand), (ph, 0, 2 * sp.pi)), (t, 0, sp.pi))
        assert sp.simplify(sphere_monomial_integral(a) - direct) == 0
        area = 4 * sp.pi
        assert sp.simplify(sphere_monomial_integral(a, normalized=True) * area - direct) == 0


def test_sphere_inner_product_gamma_formula():
    # 2 prod Gamma((a_i+1)/2) / Gamma((|a|+N)/2) with all a_i even
    for a in [(2, 0, 0, 0), (2, 2, 0, 0), (4, 0, 2, 0, 2)]:
        N = len(a)
        ref = 2 * sp.Mul(*[sp.gamma(sp.Rational(e + 1, 2)) for e in a]) / sp.gamma(sp.Rational(sum(a) + N, 2))
        assert sp.simplify(sphere_monomial_integral(a) - ref) == 0
    xs = coordinate_symbols(4)
    assert sphere_inner_product(xs[0], xs[0], 4, normalized=True) == sp.Rational(1, 4)
    assert sphere_inner_product(xs[0], xs[1], 4) == 0
    assert sp.simplify(sphere_inner_product(1, 1, 4) - 2 * sp.pi**2) == 0


@pytest.mark.parametrize("N, l", [(2, 3), (3, 0), (3, 2), (3, 3), (4, 2), (5, 2)])
def test_orthonormal_basis(N, l):
    B = orthonormal_harmonic_basis(N, l)
    assert len(B) == harmonic_dimension(N, l)
    G = sp.Matrix(len(B), len(B), lambda a, b: sphere_inner_product(B[a], B[b], N, normalized=True))
    assert G == sp.eye(len(B))
    Bf = orthonormal_harmonic_basis(N, l, exact=False)
    Gf = np.array([[float(sphere_inner_product(p, q, N, normalized=True)) for q in Bf] for p in Bf])
    assert np.allclose(Gf, np.eye(len(B)), atol=1e-12, rtol=0)


@pytest.mark.parametrize("N, l", [(3, 2), (4, 3), (5, 2), (6, 4)])
def test_generators_antisymmetric_on_orthogonal_basis(N, l):
    """<u_a, L u_b> = -<L u_a, u_b>: L^ij is anti-Hermitian for the sphere inner product."""
    polys, norms = orthogonal_harmonic_basis(N, l)
    assert all(n > 0 for n in norms)
    from hyperrotor.quantum.harmonic import _inner_dicts  # exact dict inner product

    for a in range(len(polys)):
        for b in range(a):
            assert _inner_dicts(polys[a], polys[b], N) == 0
    L = angular_momentum_operators(N)
    op = L[(1, 2)]
    n = min(len(polys), 12)
    M = [[_inner_dicts(polys[a], apply_to_polynomial(op, polys[b]), N) for b in range(n)] for a in range(n)]
    assert all(M[a][b] == -M[b][a] for a in range(n) for b in range(n))
    assert any(M[a][b] != 0 for a in range(n) for b in range(n))


def test_apply_to_polynomial_paths():
    L = angular_momentum_operators(3)
    x1, x2, x3 = coordinate_symbols(3)
    p = x1**2 * x3 + 3 * x2
    assert sp.expand(apply_to_polynomial(L[(1, 2)], p) - L[(1, 2)](p)) == 0
    d = apply_to_polynomial(L[(1, 2)].element, polynomial_to_dict(p, (x1, x2, x3)))
    assert d == {(1, 0, 0): 3, (1, 1, 1): -2}
    assert apply_to_polynomial(L[(1, 2)].element, p) == sp.expand(L[(1, 2)](p))
    with pytest.raises(TypeError, match="DifferentialOperator"):
        apply_to_polynomial("L12", p)


def test_bad_input():
    with pytest.raises(ValueError, match="l must be"):
        harmonic_polynomial_basis(3, -1)
    with pytest.raises(TypeError, match="l must be"):
        harmonic_polynomial_basis(3, 1.5)
    with pytest.raises(ValueError, match="N must be"):
        harmonic_polynomial_basis(1, 2)
    with pytest.raises(ValueError, match="exponents"):
        sphere_monomial_integral((-1, 2))
    xs = coordinate_symbols(3)
    with pytest.raises(ValueError, match="not a polynomial"):
        sphere_inner_product(1 / xs[0], 1, 3)
    assert Fraction(1, 3) == sphere_monomial_integral((2, 0, 0), normalized=True)


def test_sphere_integrals_are_priced_before_any_big_integer_work():
    """#21 §2: huge exponents / expansions are refused at once; small ones keep their exact values."""
    import hyperrotor as hr
    from hyperrotor.quantum import sphere_inner_product, sphere_monomial_integral

    x, y, z = sp.symbols("x1:4")
    assert sphere_inner_product((x + y + z) ** 2, x * y, 3, normalized=True) == sp.Rational(2, 15)
    with hr.options(max_seconds=1):
        for call in (lambda: sphere_monomial_integral((10**9,) * 3),
                     lambda: sphere_inner_product(x**10**6, y**10**6, 3),
                     lambda: sphere_inner_product((x + y + z) ** 10**4, 1, 3)):
            with call_cpu() as clock, pytest.raises(hr.BudgetError, match="sphere_integral"):
                call()
            assert clock.seconds < 1.0


def test_harmonic_rep_is_priced_by_its_own_name_with_its_planes():
    """harmonic_rep's planes (each the operator on every polynomial and a dense change of basis) are priced with
    its basis, and a refusal names harmonic_rep (it named orthogonal_harmonic_basis, whose model was 27x high at
    N = 40, l = 2, and the planes' 45 s were not counted)."""
    import hyperrotor as hr
    import hyperrotor.quantum as hq
    from hyperrotor._pricing import estimate

    def seconds(entry, **sizes):
        return sum(c.amount for c in estimate(entry, **sizes) if c.unit == "seconds")

    assert seconds("harmonic_rep", N=40, l=2) > 2 * seconds("orthogonal_harmonic_basis", N=40, l=2)
    with hr.options(max_seconds=0.5 * seconds("harmonic_rep", N=20, l=2)):
        with pytest.raises(hr.BudgetError, match=r"^harmonic_rep: so\(20\) on the 209 harmonic polynomials"):
            hq.harmonic_rep(20, 2)
