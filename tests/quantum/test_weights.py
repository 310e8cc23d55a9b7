"""Weights of so(N) irreps: Weyl dimension, Freudenthal multiplicities, Dynkin labels, validation."""
from fractions import Fraction
from itertools import permutations, product

import numpy as np
import pytest
import sympy as sp

from hyperrotor.quantum.weights import (
    casimir_eigenvalue,
    check_highest_weight,
    dominates,
    dynkin_to_orthogonal,
    is_dominant,
    orthogonal_to_dynkin,
    positive_roots,
    simple_roots,
    weight_multiplicities,
    weyl_dimension,
)

H = Fraction(1, 2)


def so5_weights(max_m1=4):
    """All dominant so(5) weights (m1, m2) with m1 <= max_m1, integer and half-integer."""
    out = []
    for twice in range(0, 2 * max_m1 + 1):
        m1 = Fraction(twice, 2)
        m2 = Fraction(twice % 2, 2)  # smallest allowed m2 of the same type
        while m2 <= m1:
            out.append((m1, m2))
            m2 += 1
    return out


@pytest.mark.parametrize("m", so5_weights(), ids=str)
def test_weyl_dimension_so5_closed_form(m):
    m1, m2 = m
    closed = (2 * m1 + 3) * (2 * m2 + 1) * (m1 - m2 + 1) * (m1 + m2 + 2) / 6
    assert weyl_dimension(5, m) == closed


def test_weyl_dimension_small_algebras():
    for twice_j in range(0, 9):
        j = Fraction(twice_j, 2)
        assert weyl_dimension(3, (j,)) == 2 * j + 1
        assert casimir_eigenvalue(3, (j,)) == j * (j + 1)
    # so(4) = su(2) + su(2): (m1, m2) -> spins (m1+m2)/2, (m1-m2)/2
    for m1, m2 in [(1, 0), (1, 1), (1, -1), (H, H), (3 * H, -H), (3, 2)]:
        assert weyl_dimension(4, (m1, m2)) == (m1 + m2 + 1) * (m1 - m2 + 1)
    # so(6) = su(4): vector 6, adjoint 15, spinors 4, symmetric traceless 20, self-dual 3-forms 10
    for m, d in [((1, 0, 0), 6), ((1, 1, 0), 15), ((H, H, H), 4), ((H, H, -H), 4), ((2, 0, 0), 20), ((1, 1, 1), 10)]:
        assert weyl_dimension(6, m) == d
    # so(N) vector, adjoint, spinor
    for N in range(3, 11):
        n = N // 2
        assert weyl_dimension(N, (1,) + (0,) * (n - 1)) == N
        if N >= 5:
            assert weyl_dimension(N, (1, 1) + (0,) * (n - 2)) == N * (N - 1) // 2
        assert weyl_dimension(N, (H,) * n) == 2 ** (n if N % 2 else n - 1)
        assert casimir_eigenvalue(N, (1,) + (0,) * (n - 1)) == N - 1
    assert weyl_dimension(2, (7,)) == 1


def _weyl_orbit(N, w):
    n = len(w)
    out = set()
    for perm in permutations(range(n)):
        for signs in product((1, -1), repeat=n):
            if N % 2 == 0 and signs.count(-1) % 2:
                continue
            out.add(tuple(signs[k] * w[perm[k]] for k in range(n)))
    return out


@pytest.mark.parametrize(
    "N, m",
    [(5, (2, 1)), (5, (3 * H, H)), (5, (4, 4)), (6, (2, 1, -1)), (7, (H, H, H)), (7, (2, 1, 0)), (4, (5 * H, 3 * H)), (8, (1, 1, 0, 0))],
    ids=str,
)
def test_freudenthal_sum_and_weyl_invariance(N, m):
    mult = weight_multiplicities(N, m)
    assert sum(mult.values()) == weyl_dimension(N, m)
    for w, k in mult.items():
        assert dominates(N, m, w)
        for v in _weyl_orbit(N, w):
            assert mult.get(v) == k


def test_freudenthal_known_cases():
    # so(5) adjoint (1,1): 8 roots of multiplicity 1, zero weight of multiplicity 2 (= rank)
    mult = weight_multiplicities(5, (1, 1))
    assert mult[(0, 0)] == 2 and len(mult) == 9
    assert weight_multiplicities(5, (1, 0)) == {(1, 0): 1, (-1, 0): 1, (0, 1): 1, (0, -1): 1, (0, 0): 1}
    assert set(weight_multiplicities(5, (H, H))) == {(s * H, t * H) for s in (1, -1) for t in (1, -1)}
    # so(3): spin j has weights j, j-1, ..., -j once
    assert weight_multiplicities(3, (3 * H,)) == {(Fraction(k, 2),): 1 for k in (3, 1, -1, -3)}
    # so(7) adjoint: zero weight multiplicity 3
    assert weight_multiplicities(7, (1, 1, 0))[(0, 0, 0)] == 3
    # chiral spinors of so(6): even / odd number of minus signs
    plus = weight_multiplicities(6, (H, H, H))
    assert all(sum(1 for x in w if x < 0) % 2 == 0 for w in plus)


def test_dynkin_round_trip_and_examples():
    assert dynkin_to_orthogonal(5, [1, 0]) == (1, 0)
    assert dynkin_to_orthogonal(5, [0, 1]) == (H, H)
    assert dynkin_to_orthogonal(5, [2, 3]) == (2 + 3 * H, 3 * H)
    assert dynkin_to_orthogonal(3, [3]) == (3 * H,)
    assert dynkin_to_orthogonal(8, [0, 0, 0, 1]) == (H, H, H, H)
    assert dynkin_to_orthogonal(8, [0, 0, 1, 0]) == (H, H, H, -H)
    assert dynkin_to_orthogonal(4, [1, 0]) == (H, -H)
    for N in (3, 4, 5, 6, 7, 8):
        n = N // 2
        for a in product(range(3), repeat=n):
            m = dynkin_to_orthogonal(N, a)
            assert is_dominant(N, m)
            assert orthogonal_to_dynkin(N, m) == a
            # Dynkin label a_i = 2 (m, alpha_i) / (alpha_i, alpha_i)
            for ai, al in zip(a, simple_roots(N)):
                assert 2 * sum(x * y for x, y in zip(m, al)) / sum(y * y for y in al) == ai


def test_roots_count():
    for N in range(3, 10):
        n = N // 2
        # number of roots = dim so(N) - rank
        assert 2 * len(positive_roots(N)) == N * (N - 1) // 2 - n


def test_input_types_accepted():
    for m in [(1, 0.5)]:
        with pytest.raises(ValueError, match="all integers or all half-integers"):
            check_highest_weight(5, m)
    ref = (Fraction(3, 2), Fraction(1, 2))
    assert check_highest_weight(5, (1.5, 0.5)) == ref
    assert check_highest_weight(5, (Fraction(3, 2), Fraction(1, 2))) == ref
    assert check_highest_weight(5, (sp.Rational(3, 2), sp.Rational(1, 2))) == ref
    assert check_highest_weight(5, [sp.Integer(2), 1]) == (2, 1)


@pytest.mark.parametrize(
    "N, m, exc, match",
    [
        (5, (1, 2), ValueError, "not dominant"),
        (5, (1, -1), ValueError, "not dominant"),
        (6, (1, 2, 0), ValueError, "not dominant"),
        (6, (1, 1, -2), ValueError, "not dominant"),
        (5, (1, 0.5), ValueError, "all integers or all half-integers"),
        (5, (1,), ValueError, "2 entries"),
        (5, (1, 0, 0), ValueError, "2 entries"),
        (5, (0.3, 0), ValueError, "integer or a half-integer"),
        (5, (Fraction(1, 3), 0), ValueError, "integers or half-integers"),
        (5, "10", TypeError, "sequence"),
        (5, ("a", 0), TypeError, "int, float"),
        (1, (1,), ValueError, "N must be an integer >= 2"),
        (5.0, (1, 0), TypeError, "N must be an integer"),
    ],
)
def test_bad_highest_weights(N, m, exc, match):
    with pytest.raises(exc, match=match):
        check_highest_weight(N, m)


def test_bad_dynkin():
    with pytest.raises(ValueError, match="2 Dynkin labels"):
        dynkin_to_orthogonal(5, [1])
    with pytest.raises(ValueError, match="non-negative integers"):
        dynkin_to_orthogonal(5, [1, -1])
    with pytest.raises(ValueError, match="N must be an integer >= 3"):
        dynkin_to_orthogonal(2, [1])


def test_dominance_order():
    assert dominates(5, (2, 1), (1, 1))
    assert dominates(5, (2, 1), (0, 0))
    assert not dominates(5, (1, 1), (2, 1))
    assert not dominates(5, (1, 0), (H, H))  # different lattices
    assert dominates(6, (1, 1, 1), (1, 1, -1)) is False  # differ by 2 e_3, not in the root lattice span with >= 0
    assert dominates(6, (1, 1, 0), (0, 0, 0))


def test_weyl_dimension_of_a_large_algebra_is_priced_and_exact():
    """Exact integer products (balanced tree); refused before any list is built when over max_seconds (#21 §2)."""
    import hyperrotor as hr

    m = tuple(range(50, 0, -1))  # so(100), 2450 positive roots
    # the hook-length-like closed form for so(2n) with m_i = n + 1 - i: product over roots, checked with Fractions
    from fractions import Fraction as F
    n = 50
    rho = [F(100 - 2 * i, 2) for i in range(1, n + 1)]
    exact = F(1)
    for i in range(n):
        for j in range(i + 1, n):
            for s in (-1, 1):
                exact *= ((m[i] + rho[i]) + s * (m[j] + rho[j])) / (rho[i] + s * rho[j])
    assert weyl_dimension(100, m) == int(exact)
    with hr.options(max_seconds=1), pytest.raises(hr.BudgetError, match="weyl_product"):
        weyl_dimension(1000, tuple(range(500, 0, -1)))


def test_weight_count_is_the_number_of_distinct_weights():
    """weight_count (the pricing of weight_multiplicities) counts the dominant weights below the highest one and
    their Weyl orbits: exactly the weights Freudenthal's recursion finds, integer and half-integer, both signs of
    the last entry for even N (the box (bound + 1)^rank it replaced was 51-373x high for rank 4-5)."""
    from hyperrotor.quantum.weights import weight_count

    g = np.random.default_rng(48)
    for _ in range(40):
        N = int(g.integers(3, 11))
        n = N // 2
        m = sorted(g.integers(0, 4, size=n).tolist(), reverse=True)
        half = H if g.random() < 0.3 else 0
        w = tuple(Fraction(x) + half for x in m)
        if N % 2 == 0 and g.random() < 0.5:
            w = w[:-1] + (-w[-1],)
        top = tuple(int(2 * x) for x in w)
        assert weight_count(N, top) == len(weight_multiplicities(N, w)), (N, w)
    assert weight_count(9, (20, 16, 12, 8), most=10) is None  # (too many dominant weights to count: the caller's box)
