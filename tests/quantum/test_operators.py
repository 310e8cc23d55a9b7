"""Tests of the so(N) angular-momentum operators (paper Section 5, eqs. 141-147)."""
from __future__ import annotations

import itertools

import numpy as np
import pytest
import sympy as sp

from hyperrotor.conventions import plane_index, planes, structure_constants
from hyperrotor.quantum.operators import (
    DifferentialOperator,
    angular_momentum_operator,
    angular_momentum_operators,
    casimir_operator,
    commutator,
    coordinate_symbols,
    euler_operator,
    laplacian_operator,
    multiplication_operator,
    operator_matrix,
    textbook_so3,
)
from hyperrotor.quantum.operator_products import contraction_identity, operator_product

HBAR = sp.Symbol("hbar", positive=True)


def _delta(a, b):
    return int(a == b)


def _L(L, a, b):
    """L^{ab} for any ordered pair (L^{ba} = -L^{ab}, L^{aa} = 0)."""
    if a == b:
        return 0 * L[(1, 2)]
    return L[(a, b)] if a < b else -L[(b, a)]


def _expected(L, i, j, k, l):
    """delta_jk L^il + delta_il L^jk - delta_jl L^ik - delta_ik L^jl (derived for x_i d_j - x_j d_i)."""
    return (_delta(j, k) * _L(L, i, l) + _delta(i, l) * _L(L, j, k)
            - _delta(j, l) * _L(L, i, k) - _delta(i, k) * _L(L, j, l))


# --------------------------------------------------------------------------- definitions
def test_eq142_paper_coordinates():
    L = angular_momentum_operators(5, coordinates="paper")
    x, y, z, w, v = sp.symbols("x y z w v", real=True)
    f = sp.Function("f")(x, y, z, w, v)
    assert L[(1, 2)].coordinates == (x, y, z, w, v)
    assert sp.expand(L[(1, 2)](f) - (x * sp.diff(f, y) - y * sp.diff(f, x))) == 0
    assert sp.expand(L[(3, 5)](f) - (z * sp.diff(f, v) - v * sp.diff(f, z))) == 0
    assert sp.expand(L[(4, 5)].apply(f) - (w * sp.diff(f, v) - v * sp.diff(f, w))) == 0
    assert list(L) == list(planes(5))


def test_custom_coordinates_and_single_generator():
    a, b, c = sp.symbols("a b c")
    L = angular_momentum_operators(3, coordinates=[a, "b", c])
    assert L[(1, 3)](a * c) == sp.expand(a**2 - c**2)
    assert angular_momentum_operator((3, 1), 3, coordinates=L[(1, 2)].coordinates) == -L[(1, 3)]
    assert L[(1, 2)].coordinates[1] == sp.Symbol("b", real=True)
    assert angular_momentum_operator((1, 2), 3, form="hermitian", hbar=HBAR) == -sp.I * HBAR * angular_momentum_operators(3)[(1, 2)]


def test_operator_arithmetic_and_order():
    L = angular_momentum_operators(3)
    A, B = L[(1, 2)], L[(2, 3)]
    x1, x2, x3 = coordinate_symbols(3)
    f = sp.Function("f")(x1, x2, x3)
    assert (A * B).order == 2 and commutator(A, B).order == 1
    assert sp.expand((A * B)(f) - A(B(f))) == 0
    assert sp.expand((2 * A - B / 2 + 3)(f) - (2 * A(f) - B(f) / 2 + 3 * f)) == 0
    assert (A**2) == A * A and (A**0)(f) == f
    assert A - A == 0 and (A * HBAR) == (HBAR * A)
    assert DifferentialOperator.from_sympy(A.to_sympy(f), f, (x1, x2, x3)) == A


def test_latex():
    L = angular_momentum_operators(3)
    s = sp.latex(L[(1, 2)])
    assert s == r"x_{1} \frac{\partial}{\partial x_{2}} - x_{2} \frac{\partial}{\partial x_{1}}"
    assert L[(1, 2)]._repr_latex_().startswith("$") and r"\partial^{2}" in sp.latex(L[(1, 2)] ** 2)
    assert sp.latex(L[(1, 2)] - L[(1, 2)]) == "0"


# --------------------------------------------------------------------------- commutators
@pytest.mark.parametrize("N", range(2, 9))
def test_commutation_relations_normal_form(N):
    """[L^ij, L^kl] for every pair of planes, as exact operator identities."""
    L = angular_momentum_operators(N)
    C = structure_constants(N)
    ps = planes(N)
    for (i, j), (k, l) in itertools.product(ps, ps):
        lhs = commutator(L[(i, j)], L[(k, l)])
        assert lhs == _expected(L, i, j, k, l)
        # same structure constants as hyperrotor.conventions, overall sign +1
        a, b = plane_index((i, j), N), plane_index((k, l), N)
        rhs = 0 * L[ps[0]]
        for c in np.nonzero(C[a, b])[0]:
            rhs = rhs + int(C[a, b, c]) * L[ps[c]]
        assert lhs == rhs


@pytest.mark.parametrize("N", [2, 3, 4, 5, 6, pytest.param(7, marks=pytest.mark.slow),
                               pytest.param(8, marks=pytest.mark.slow)])
def test_commutation_relations_naive_sympy(N):
    """Independent check: apply both sides to a generic function f(x1..xN)."""
    xs = coordinate_symbols(N)
    f = sp.Function("f")(*xs)
    L = angular_momentum_operators(N)

    def act(i, j, g):  # naive x_i d_j - x_j d_i, no normal form involved
        if i == j:
            return sp.Integer(0)
        return xs[i - 1] * sp.diff(g, xs[j - 1]) - xs[j - 1] * sp.diff(g, xs[i - 1])

    ps = planes(N)
    for n, ((i, j), (k, l)) in enumerate(itertools.combinations(ps, 2)):
        lhs = act(i, j, act(k, l, f)) - act(k, l, act(i, j, f))
        rhs = (_delta(j, k) * act(i, l, f) + _delta(i, l) * act(j, k, f)
               - _delta(j, l) * act(i, k, f) - _delta(i, k) * act(j, l, f))
        assert sp.expand(lhs - rhs) == 0
        # and the normal-form commutator acts the same way
        if n % 7 == 0:
            assert sp.expand(commutator(L[(i, j)], L[(k, l)])(f) - rhs) == 0


@pytest.mark.parametrize("N", [3, 4, 5])
def test_hermitian_commutation_relations(N):
    """[Lh^ij, Lh^kl] = i hbar (d_ik Lh^jl + d_jl Lh^ik - d_il Lh^jk - d_jk Lh^il) for Lh = -i hbar L."""
    Lh = angular_momentum_operators(N, form="hermitian", hbar=HBAR)
    ps = planes(N)
    for (i, j), (k, l) in itertools.product(ps, ps):
        rhs = sp.I * HBAR * (_delta(i, k) * _L(Lh, j, l) + _delta(j, l) * _L(Lh, i, k)
                             - _delta(i, l) * _L(Lh, j, k) - _delta(j, k) * _L(Lh, i, l))
        assert commutator(Lh[(i, j)], Lh[(k, l)]) == rhs


def test_textbook_3d():
    Lx, Ly, Lz = textbook_so3(hbar=HBAR)
    x, y, z = coordinate_symbols(3)
    f = sp.Function("f")(x, y, z)
    # L = r x p with p = -i hbar grad
    assert sp.expand(Lz(f) - (-sp.I * HBAR) * (x * sp.diff(f, y) - y * sp.diff(f, x))) == 0
    assert sp.expand(Lx(f) - (-sp.I * HBAR) * (y * sp.diff(f, z) - z * sp.diff(f, y))) == 0
    assert sp.expand(Ly(f) - (-sp.I * HBAR) * (z * sp.diff(f, x) - x * sp.diff(f, z))) == 0
    assert commutator(Lx, Ly) == sp.I * HBAR * Lz
    assert commutator(Ly, Lz) == sp.I * HBAR * Lx
    assert commutator(Lz, Lx) == sp.I * HBAR * Ly
    # as_form is the same map; text is never turned into a symbol (#21)
    L = angular_momentum_operators(3)
    assert L[(1, 2)].as_form("hermitian", hbar=HBAR) == Lz
    with pytest.raises(TypeError, match="hbar"):
        L[(1, 2)].as_form("hermitian", hbar="hbar")


# --------------------------------------------------------------------------- Casimir
@pytest.mark.parametrize("N", range(2, 9))
def test_casimir_identity(N):
    """sum_{i<j} (L^ij)^2 = r^2 Laplacian - E (E + N - 2), exactly."""
    xs = coordinate_symbols(N)
    C2 = casimir_operator(N)
    r2 = multiplication_operator(sum(x**2 for x in xs), N)
    E = euler_operator(N)
    assert C2 == r2 * laplacian_operator(N) - E * (E + (N - 2))
    # commutes with every generator
    for op in angular_momentum_operators(N).values():
        assert commutator(C2, op) == 0


def test_casimir_hermitian_scaling():
    assert casimir_operator(4, form="hermitian", hbar=HBAR) == -HBAR**2 * casimir_operator(4)


# --------------------------------------------------------------------------- eqs. 143-147
def test_operator_matrix_checkerboard():
    L = angular_momentum_operators(5)
    M = operator_matrix(5)
    S = operator_matrix(5, convention="standard")
    for i, j in planes(5):
        assert M[i - 1, j - 1] == (-1) ** (i + j) * L[(i, j)]
        assert M[j - 1, i - 1] == -M[i - 1, j - 1]
        assert S[i - 1, j - 1] == L[(i, j)]
    assert M[0, 1] == -L[(1, 2)] and M[0, 2] == L[(1, 3)]  # eq. (143), first row
    assert all(M[i, i].is_zero() for i in range(5))
    H = operator_matrix(3, form="hermitian", hbar=HBAR)
    M3 = operator_matrix(3)
    assert all(H[i, j] == -sp.I * HBAR * M3[i, j] for i in range(3) for j in range(3))  # eq. (141)


@pytest.mark.parametrize("N", range(3, 9))
@pytest.mark.parametrize("convention", ["paper", "standard"])
def test_contraction_identity(N, convention):
    """(L Om)_ij - (L Om)_ji = -(N-2) L_ij for Om = L^T (eqs. 145-147 for N = 5, 4, 3)."""
    res = contraction_identity(N, convention=convention)
    assert res.holds and res.factor == -(N - 2)
    assert all(res.product[i, j].order <= 1 for i in range(N) for j in range(N))
    if N <= 5:
        # eq. (144) pattern: +(N-2) L for Om = L^T, -(N-2) L for Om = L
        r2 = contraction_identity(N, convention=convention, form="eq144")
        r3 = contraction_identity(N, convention=convention, form="eq144", transpose=False)
        assert r2.holds and r2.factor == N - 2
        assert r3.holds and r3.factor == -(N - 2)


def test_paper_values_145_147():
    assert [contraction_identity(N).factor for N in (5, 4, 3)] == [-3, -2, -1]


def test_contraction_identity_naive_3d():
    """Independent 3D check by applying the definition to a generic f with plain SymPy."""
    xs = coordinate_symbols(3)
    f = sp.Function("f")(*xs)

    def Lij(a, b, g):  # paper-convention matrix entry (-1)^(a+b) (x_a d_b - x_b d_a), 1-based
        if a == b:
            return sp.Integer(0)
        s = (-1) ** (a + b)
        return s * (xs[a - 1] * sp.diff(g, xs[b - 1]) - xs[b - 1] * sp.diff(g, xs[a - 1]))

    for i, j in [(1, 2), (1, 3), (2, 3), (3, 1)]:
        # Om = L^T: Om_kj = L_jk; sum_k L_ik(Om_kj f) - L_jk(Om_ki f)
        val = sum(Lij(i, k, Lij(j, k, f)) - Lij(j, k, Lij(i, k, f)) for k in (1, 2, 3))
        assert sp.expand(val + Lij(i, j, f)) == 0


def test_eq144_commuting_limit_and_printed_typos():
    """With commuting (scalar) entries the eq-144 product is omega L - L omega (eq. 24/25)."""
    N = 5
    xs = coordinate_symbols(N)
    Ls = {p: sp.Symbol(f"L{p[0]}{p[1]}") for p in planes(N)}
    Ws = {p: sp.Symbol(f"w{p[0]}{p[1]}") for p in planes(N)}
    one = multiplication_operator(1, N)

    def mat(syms):
        M = np.empty((N, N), dtype=object)
        Ms = sp.zeros(N, N)
        for i in range(N):
            M[i, i] = 0 * one
        for (i, j), s in syms.items():
            e = (-1) ** (i + j) * s
            M[i - 1, j - 1], M[j - 1, i - 1] = e * one, -e * one
            Ms[i - 1, j - 1], Ms[j - 1, i - 1] = e, -e
        return M, Ms

    A, As = mat(Ls)
    B, Bs = mat(Ws)
    P = operator_product(A, B)
    Q = operator_product(A, B, form="antisymmetrized")
    ref = Bs * As - As * Bs
    f = sp.Function("f")(*xs)
    for i in range(N):
        for j in range(N):
            assert sp.expand(P[i, j](f) - ref[i, j] * f) == 0
            assert Q[i, j] == -P[i, j]
    # printed eqs. (25)/(144) read with unordered labels (w31 = w13, as eq. (28) requires);
    # three entries carry index typos: (12), (25) and (45)
    L, w = Ls, Ws
    printed = {
        (1, 2): (-L[(1, 3)] * w[(2, 3)] - L[(1, 4)] * w[(2, 4)] - L[(1, 5)] * w[(2, 5)]
                 + L[(2, 3)] * w[(1, 3)] + L[(2, 4)] * w[(3, 4)] + L[(2, 5)] * w[(3, 5)]),
        (2, 5): (-L[(1, 2)] * w[(1, 5)] + L[(3, 5)] * w[(1, 2)] + L[(2, 3)] * w[(3, 5)]
                 + L[(2, 4)] * w[(4, 5)] - L[(3, 5)] * w[(2, 3)] - L[(4, 5)] * w[(2, 4)]),
        (4, 5): (-L[(1, 3)] * w[(1, 5)] + L[(1, 5)] * w[(1, 4)] - L[(2, 4)] * w[(2, 5)]
                 + L[(2, 5)] * w[(2, 4)] - L[(3, 4)] * w[(3, 5)] + L[(3, 5)] * w[(3, 4)]),
    }
    corrections = {  # printed term -> correct term
        (1, 2): [(L[(2, 4)] * w[(3, 4)], L[(2, 4)] * w[(1, 4)]), (L[(2, 5)] * w[(3, 5)], L[(2, 5)] * w[(1, 5)])],
        (2, 5): [(L[(3, 5)] * w[(1, 2)], L[(1, 5)] * w[(1, 2)])],
        (4, 5): [(-L[(1, 3)] * w[(1, 5)], -L[(1, 4)] * w[(1, 5)])],
    }
    for (i, j), expr in printed.items():
        assert sp.expand(ref[i - 1, j - 1] - expr) != 0
        fixed = expr
        for bad, good in corrections[(i, j)]:
            fixed = fixed - bad + good
        assert sp.expand(ref[i - 1, j - 1] - fixed) == 0
    # an entry printed correctly (same unordered reading): (13)
    e13 = (-L[(1, 2)] * w[(2, 3)] + L[(1, 4)] * w[(3, 4)] + L[(1, 5)] * w[(3, 5)] + L[(2, 3)] * w[(1, 2)]
           - L[(3, 4)] * w[(1, 4)] - L[(3, 5)] * w[(1, 5)])
    assert sp.expand(ref[0, 2] - e13) == 0


def test_operator_product_is_exact_for_operators_order_matters():
    M = operator_matrix(4)
    P1 = operator_product(M, M.T.copy(), form="antisymmetrized")
    P2 = operator_product(M, M.T.copy(), form="eq144")
    for i in range(4):
        for j in range(4):
            assert P1[i, j] == -P2[i, j]


# --------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("N, exc", [(1, ValueError), (0, ValueError), (2.5, TypeError), ("3", TypeError), (True, TypeError)])
def test_bad_dimension(N, exc):
    with pytest.raises(exc, match="N must be an integer"):
        angular_momentum_operators(N)


def test_bad_coordinates():
    with pytest.raises(ValueError, match="unknown coordinates 'cartesian'"):
        angular_momentum_operators(3, coordinates="cartesian")
    with pytest.raises(ValueError, match="expected 4 coordinates"):
        angular_momentum_operators(4, coordinates=["x", "y", "z"])
    with pytest.raises(ValueError, match="distinct"):
        angular_momentum_operators(2, coordinates=["x", "x"])
    with pytest.raises(TypeError, match="Symbol or a name"):
        angular_momentum_operators(2, coordinates=[1, 2])
    with pytest.raises(ValueError, match="paper"):
        angular_momentum_operators(6, coordinates="paper")
    with pytest.raises(TypeError):
        angular_momentum_operators(3, coordinates=5)


def test_mixed_dimensions_and_coordinates():
    A = angular_momentum_operators(3)[(1, 2)]
    B = angular_momentum_operators(4)[(1, 2)]
    C = angular_momentum_operators(3, coordinates=["x", "y", "z"])[(1, 2)]
    for other in (B, C):
        with pytest.raises(ValueError, match="different coordinates"):
            A * other
        with pytest.raises(ValueError, match="different coordinates"):
            A + other
        with pytest.raises(ValueError, match="different coordinates"):
            commutator(A, other)


def test_bad_arguments():
    A = angular_momentum_operators(3)[(1, 2)]
    for bad in ([1, 2], np.ones(3), "x1", None):
        with pytest.raises(TypeError, match="applies to SymPy expressions"):
            A(bad)
    with pytest.raises(TypeError):
        A * "two"
    with pytest.raises(ValueError, match="depends on the coordinates"):
        A * coordinate_symbols(3)[0]
    with pytest.raises(TypeError, match="hbar"):
        A.as_form("hermitian", hbar=[1])
    with pytest.raises(ValueError, match="unknown form"):
        operator_product(operator_matrix(3), operator_matrix(3), form="bogus")
    with pytest.raises(ValueError, match="invalid plane"):
        angular_momentum_operator((2, 2), 3)
    with pytest.raises(ValueError, match="unknown convention"):
        operator_matrix(3, convention="weird")
    with pytest.raises(TypeError, match="DifferentialOperators"):
        commutator(A, 3)


@pytest.mark.parametrize("N", [3, 4, 5])
def test_contraction_identity_hermitian_form(N):
    """For the Hermitian matrix of eq. (141) the antisymmetrized contraction is i hbar (N-2) L."""
    H = operator_matrix(N, form="hermitian", hbar=HBAR)
    P = operator_product(H, H.T.copy(), form="antisymmetrized")
    for i in range(N):
        for j in range(N):
            assert P[i, j] == sp.I * HBAR * (N - 2) * H[i, j]
