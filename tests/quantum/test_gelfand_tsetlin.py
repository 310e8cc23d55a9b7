"""Gelfand-Tsetlin irreps of so(N): brackets, Casimir, dimensions, weights, exact mode, bad input."""
from fractions import Fraction

import numpy as np
import pytest
import scipy.sparse as sps
import sympy as sp

import hyperrotor as hr
from hyperrotor.conventions import planes, structure_constants
from hyperrotor.quantum.gelfand_tsetlin import gt_index, gt_patterns, gt_size, irrep
from hyperrotor.quantum.weights import casimir_eigenvalue, weight_multiplicities, weyl_dimension
from tolerance import norm, row_length, scaled_tol

H = Fraction(1, 2)


def so5_weights(max_m1=4):
    out = []
    for twice in range(0, 2 * max_m1 + 1):
        m1 = Fraction(twice, 2)
        m2 = Fraction(twice % 2, 2)
        while m2 <= m1:
            out.append((m1, m2))
            m2 += 1
    return out


SAMPLES = [
    (2, (3,)), (2, (-H,)),
    (3, (0,)), (3, (H,)), (3, (1,)), (3, (7 * H,)), (3, (4,)),
    (4, (1, 0)), (4, (1, 1)), (4, (1, -1)), (4, (H, H)), (4, (H, -H)), (4, (5 * H, -3 * H)), (4, (3, 1)),
    (6, (1, 0, 0)), (6, (1, 1, 0)), (6, (H, H, H)), (6, (H, H, -H)), (6, (2, 1, -1)), (6, (3 * H, H, -H)),
    (7, (1, 0, 0)), (7, (H, H, H)), (7, (1, 1, 0)), (7, (2, 1, 0)), (7, (3 * H, H, H)),
    (8, (H, H, H, -H)), (8, (1, 1, 0, 0)),
    (10, (H, H, H, H, -H)), (12, (1, 1, 1, 0, 0, 0)),  # the latter uses the dict fallback of the pattern index
]
ALL = [(5, m) for m in so5_weights()] + SAMPLES


def _bracket_residual(rep):
    N = rep.N
    C = structure_constants(N)
    pl = planes(N)
    X = rep.generators()
    scale = max(1.0, max(float(abs(M).max()) if M.nnz else 0.0 for M in X.values())) ** 2
    worst = 0.0
    for a, pa in enumerate(pl):
        for b in range(a + 1, len(pl)):
            pb = pl[b]
            lhs = X[pa] @ X[pb] - X[pb] @ X[pa]
            for c in np.nonzero(C[a, b])[0]:
                lhs = lhs - int(C[a, b, c]) * X[pl[c]]
            if lhs.nnz:
                worst = max(worst, float(abs(lhs).max()))
    return worst / scale


def _bracket_tol(rep, terms=2):
    """Relative round-off bound of a sum of `terms` products of the sparse generators (residual / max|X|^2):
    each entry is an inner product of r = longest row terms of size <= max|X|^2 (tests/tolerance.py)."""
    r = row_length(*rep.generators().values())
    return scaled_tol(dim=r, k=4 * terms * r)


@pytest.fixture(scope="module")
def reps():
    return {}


def _rep(cache, N, m):
    key = (N, tuple(m))
    if key not in cache:
        cache[key] = irrep(N, m)
    return cache[key]


@pytest.mark.parametrize("N, m", ALL, ids=str)
def test_brackets_casimir_dimension(reps, N, m):
    rep = _rep(reps, N, m)
    assert rep.dim == weyl_dimension(N, m) == gt_size(N, m)
    assert _bracket_residual(rep) <= _bracket_tol(rep)
    c = float(casimir_eigenvalue(N, m))
    cas = rep.casimir()
    assert abs(cas + c * sps.identity(rep.dim)).max() <= scaled_tol(max(1.0, c), dim=row_length(*rep.generators().values()), k=4 * len(rep.planes))
    # anti-Hermitian generators, Hermitian L = -i X
    for p in rep.planes:
        X = rep.generator(p)
        assert abs(X + X.conj().T).max() <= scaled_tol(max(1.0, abs(X).max()), dim=row_length(X))
        L = rep.generator(p, form="hermitian", hbar=0.7)
        assert abs(L - L.conj().T).max() <= scaled_tol(max(1.0, abs(L).max()), dim=row_length(L))
        assert abs(L - (-0.7j) * X).max() == 0


@pytest.mark.parametrize("N, m", ALL, ids=str)
def test_weights_equal_freudenthal(reps, N, m):
    rep = _rep(reps, N, m)
    assert rep.weight_multiplicities() == weight_multiplicities(N, m)


@pytest.mark.parametrize("N, m", [(5, (2, 1)), (5, (3 * H, 3 * H)), (6, (2, 1, -1)), (7, (2, 1, 0)), (4, (5 * H, -3 * H)), (3, (2,))], ids=str)
def test_contraction_identity(reps, N, m):
    # sum_{k != i,j} [X_(ik), X_(kj)] = (N - 2) X_(ij), with X_(ba) = -X_(ab)
    rep = _rep(reps, N, m)

    def X(a, b):
        return rep.generator((a, b)) if a < b else -rep.generator((b, a))

    for i in range(1, N + 1):
        for j in range(1, N + 1):
            if i == j:
                continue
            tot = sum((X(i, k) @ X(k, j) - X(k, j) @ X(i, k) for k in range(1, N + 1) if k not in (i, j)),
                      sps.csr_matrix((rep.dim, rep.dim)))
            assert abs(tot - (N - 2) * X(i, j)).max() <= _bracket_tol(rep, terms=2 * (N - 2)) * max(1.0, abs(X(i, j)).max()) ** 2


@pytest.mark.parametrize("N, m", [(5, (2, 1)), (6, (H, H, -H)), (7, (1, 1, 0)), (4, (1, 1))], ids=str)
def test_ladder_operators(reps, N, m):
    rep = _rep(reps, N, m)
    Hs = rep.cartan_generators(form="hermitian")
    for root, E in rep.ladder_operators().items():
        for k, Hk in enumerate(Hs):
            res = Hk @ E - E @ Hk - root[k] * E
            assert abs(res).max() <= scaled_tol(max(1.0, abs(E).max()) * max(1.0, abs(Hk).max()), dim=row_length(E, Hk), k=16)
    # [E_a, E_-a] lies in the Cartan subalgebra and is proportional to sum_k a_k H_k
    for root in rep.roots():
        Ep, Em = rep.ladder(root), rep.ladder(tuple(-x for x in root))
        comm = (Ep @ Em - Em @ Ep).toarray()
        target = sum(a * Hk.toarray() for a, Hk in zip(root, Hs))
        tol = scaled_tol(norm(Ep) * norm(Em), dim=row_length(Ep, Em), k=8)
        if np.abs(target).max() < 1e-12:  # this su(2) acts trivially (e.g. so(4) (1, 1))
            assert np.abs(comm).max() <= tol
            continue
        lam = np.vdot(target, comm) / np.vdot(target, target)
        assert abs(lam) > 0.1
        assert np.abs(comm - lam * target).max() <= tol


def test_so3_matches_spin_matrices():
    # so(3) GT basis = |j, m>, m = j, j-1, ..., -j: X_(12) = i m, and X_(23) is real with
    # <m+1| X_(23) |m> = +1/2 sqrt((j-m)(j+m+1)) (so -i X_(23) is the spin matrix J_y up to sign of i)
    for twice in range(1, 8):
        j = twice / 2
        rep = irrep(3, (Fraction(twice, 2),))
        m = j - np.arange(rep.dim)
        assert np.array_equal(rep.generator((1, 2), format="dense"), np.diag(1j * m))
        X23 = rep.generator((2, 3), format="dense")
        A = 0.5 * np.sqrt((j - m[1:]) * (j + m[1:] + 1))
        assert np.allclose(X23, np.diag(A, 1) - np.diag(A, -1), rtol=0, atol=scaled_tol(A.max(), dim=1))


def test_patterns_and_index():
    m = (3, 1)
    P = gt_patterns(5, m)
    assert P.shape == (weyl_dimension(5, m), 6)
    assert np.all(P[:, :2] == [3, 1])
    # lexicographically decreasing, index inverse of the order
    keys = [tuple(r) for r in P.tolist()]
    assert keys == sorted(keys, reverse=True)
    assert gt_index(5, m, P[7]) == 7
    assert np.array_equal(gt_index(5, m, P[::-1]), np.arange(len(P))[::-1])
    # betweenness of every row
    for r in P:
        M5, M4, M3, M2 = r[0:2], r[2:4], r[4], r[5]
        assert M5[0] >= M4[0] >= M5[1] >= M4[1] >= -M5[1]
        assert M4[0] >= M3 >= abs(M4[1])
        assert M3 >= M2 >= -M3
    with pytest.raises(ValueError, match="not a Gelfand-Tsetlin pattern"):
        gt_index(5, m, [3, 1, 3, 1, 4, 0])
    with pytest.raises(ValueError, match="6 entries"):
        gt_index(5, m, [3, 1, 3])
    # X_(12) = i diag(M_2): the weight of H_1 is the last pattern entry
    rep = irrep(5, m)
    assert np.allclose(rep.generator((1, 2)).diagonal(), 1j * P[:, -1], rtol=0, atol=0)


def test_input_forms_agree():
    ref = irrep(5, (Fraction(3, 2), Fraction(1, 2)))
    for m in [(1.5, 0.5), (sp.Rational(3, 2), sp.Rational(1, 2)), (Fraction(3, 2), 0.5)]:
        rep = irrep(5, m)
        assert rep.highest_weight == (Fraction(3, 2), Fraction(1, 2))
        assert all(abs(rep.generator(p) - ref.generator(p)).max() == 0 for p in rep.planes)
    rep = irrep(5, dynkin=[1, 1])
    assert rep.highest_weight == (Fraction(3, 2), Fraction(1, 2))
    assert irrep(6, dynkin=[0, 1, 0]).highest_weight == (H, H, -H)


def test_dense_format():
    rep = irrep(5, (1, 1))
    D = rep.generator((2, 4), format="dense")
    assert isinstance(D, np.ndarray) and D.shape == (10, 10)
    assert np.array_equal(D, rep.generator((2, 4)).toarray())
    assert sps.isspmatrix_csr(rep.generator((2, 4)))
    dense = irrep(5, (1, 1), format="dense")
    assert isinstance(dense.generator((2, 4)), np.ndarray)
    assert np.array_equal(dense.generator((2, 4)), D)
    assert sps.isspmatrix_csr(dense.generator((2, 4), format="csr"))
    assert all(isinstance(M, np.ndarray) for M in dense.generators().values())
    with pytest.raises(ValueError, match="format"):
        irrep(5, (1, 1), format="coo")


@pytest.mark.parametrize("N, m", [(3, (1,)), (4, (H, H)), (5, (1, 0)), (5, (H, H)), (5, (1, 1)), (6, (H, H, -H))], ids=str)
def test_exact_generators(N, m):
    rep = irrep(N, m)
    G = rep.generators(exact=True)
    pl = planes(N)
    C = structure_constants(N)
    for p in pl:
        num = np.array(G[p].evalf(30), dtype=complex)
        assert np.abs(num - rep.generator(p, format="dense")).max() <= scaled_tol(np.abs(num).max(), dim=1)
    # exact brackets and Casimir
    for a, pa in enumerate(pl):
        for b, pb in enumerate(pl):
            rhs = sp.zeros(rep.dim, rep.dim)
            for c in np.nonzero(C[a, b])[0]:
                rhs += int(C[a, b, c]) * G[pl[c]]
            diff = (G[pa] * G[pb] - G[pb] * G[pa] - rhs).applyfunc(sp.expand)
            assert diff == sp.zeros(rep.dim, rep.dim)
    cas = sum((G[p] * G[p] for p in pl), sp.zeros(rep.dim, rep.dim)).applyfunc(sp.expand)
    c = casimir_eigenvalue(N, m)
    assert cas == -sp.Rational(c.numerator, c.denominator) * sp.eye(rep.dim)


def test_large_so5_irrep():
    rep = irrep(5, (20, 10))
    assert rep.dim == 52976 == weyl_dimension(5, (20, 10))
    # brackets of the chain generators with their neighbours and a Casimir check on random vectors
    rng = np.random.default_rng(5)
    v = rng.standard_normal(rep.dim) + 1j * rng.standard_normal(rep.dim)
    c = float(casimir_eigenvalue(5, (20, 10)))
    Cv = sum(X @ (X @ v) for X in rep.generators().values())
    assert np.abs(Cv + c * v).max() <= 1e-10 * c * np.abs(v).max()
    X = rep.generators()
    for (a, b), (cc, d), (e, f), s in [((1, 2), (2, 3), (1, 3), 1), ((2, 4), (4, 5), (2, 5), 1), ((1, 5), (3, 5), (1, 3), -1)]:
        lhs = X[(a, b)] @ (X[(cc, d)] @ v) - X[(cc, d)] @ (X[(a, b)] @ v)
        assert np.abs(lhs - s * (X[(e, f)] @ v)).max() <= 1e-10 * 900 * np.abs(v).max()


@pytest.mark.parametrize(
    "kwargs, exc, match",
    [
        (dict(N=5, highest_weight=(1, 2)), ValueError, "not dominant"),
        (dict(N=5, highest_weight=(1, 0.5)), ValueError, "all integers or all half-integers"),
        (dict(N=5, highest_weight=(1, 0, 0)), ValueError, "2 entries"),
        (dict(N=1, highest_weight=(1,)), ValueError, "N must be an integer >= 2"),
        (dict(N=5), ValueError, "highest_weight"),
        (dict(N=5, highest_weight=(1, 0), dynkin=[1, 0]), ValueError, "either"),
        (dict(N=5, highest_weight=(20, 10), max_dim=50_000), ValueError, r"irrep: the so\(5\) irrep .*MiB.* would need ~52976 \(dimension\), over the budget max_dim = 50000; raise it with .*max_dim=52976"),
        (dict(N=5, highest_weight=(1, 0), max_dim=0), ValueError, r"max_dim must be an integer >= 1, got 0"),
        (dict(N=5, highest_weight=(1, 0), max_dim=-1), ValueError, r"max_dim must be an integer >= 1, got -1"),
        (dict(N=5, highest_weight=(1, 0), max_dim=2.5), TypeError, r"max_dim must be an integer >= 1, got 2.5"),
        (dict(N=5, highest_weight=(1, 0), max_dim=True), TypeError, r"max_dim .* got True of type bool"),
    ],
)
def test_bad_input(kwargs, exc, match):
    with pytest.raises(exc, match=match):
        irrep(**kwargs)


@pytest.mark.parametrize("build", ["irrep", "gt_patterns"])
def test_a_raised_max_dim_still_meets_the_memory_budget(build):
    """max_dim is the dimension guard only: past it, the patterns and generators are priced against
    max_memory_bytes before anything is allocated (numpy's MemoryError of 268 GiB came first), and a budget that
    allows them builds the irrep."""
    import hyperrotor.quantum as hq

    fn = getattr(hq, build)
    with pytest.raises(hr.BudgetError, match=rf"{build}: .* over the budget hr.options\['max_memory_bytes'\]"):
        fn(5, (3000, 3000), max_dim=10**13)
    dim = hq.weyl_dimension(3, (150_000,))  # 300 001, beyond DEFAULT_MAX_DIM
    with hr.options(max_memory_bytes=10**6):
        with pytest.raises(hr.BudgetError, match="max_memory_bytes"):
            fn(3, (150_000,), max_dim=10**6)
        # within the default max_dim too (was let through: so(8) (6, 4, 4, 3) peaked at 6 GB under 4 GiB): the
        # patterns (7.6 MB here) before they are built, the generators as they are
        with pytest.raises(hr.BudgetError, match="max_memory_bytes"):
            fn(5, (20, 10))
    with hr.options(max_memory_bytes=2 * 10**9):
        small = fn(5, (20, 10))
    assert (small.dim if build == "irrep" else small.shape[0]) == hq.weyl_dimension(5, (20, 10))
    out = fn(3, (150_000,), max_dim=dim)
    assert (out.dim if build == "irrep" else out.shape[0]) == dim


def test_exact_guard():
    rep = irrep(5, (4, 2))  # dim 220
    with pytest.raises(ValueError, match="exact"):
        rep.generator((1, 2), exact=True)
    with pytest.raises(ValueError, match="exact"):
        irrep(5, (4, 2), exact=True)


def test_bad_plane_and_format():
    rep = irrep(5, (1, 0))
    for bad in [(2, 1), (1, 6), (0, 1), (3, 3), (1,), (1, 2, 3)]:
        with pytest.raises(ValueError, match="plane"):
            rep.generator(bad)
    with pytest.raises(ValueError, match="format"):
        rep.generator((1, 2), format="coo")
    with pytest.raises(ValueError, match="not a root"):
        rep.ladder((2, 0))


# ----------------------------------------------------------------------------
# rotations by pi as monomial matrices (the trusted cores behind the symmetry sectors)
# ----------------------------------------------------------------------------
@pytest.mark.parametrize("N, m", [(3, (2,)), (4, (2, -1)), (5, (2, 1)), (5, (Fraction(3, 2), Fraction(1, 2))),
                                  (6, (1, 1, 0)), (6, (2, 1, -1)), (7, (1, 1, 0))])
def test_pi_rotations_are_the_exponentials(N, m):
    import scipy.linalg as sla

    from hyperrotor.quantum._gt_monomials import gt_rotations

    rep = irrep(N, m)
    D = gt_rotations(rep, list(range(1, N)))
    for k in range(1, N):
        E = sla.expm(np.pi * rep.generator((k, k + 1), format="dense"))
        assert np.abs(D[k].matrix().toarray() - E).max() <= scaled_tol(E, dim=rep.dim, k=4 * rep.dim)


def test_pi_rotation_of_a_large_so3_irrep_is_built_without_dense_work():
    """irrep(3, (99999,)): exp(pi X_23) |j, m> = (-1)^(j-m) |j, -m> from the trace, under a 100 MB budget."""
    import hyperrotor as hr
    from hyperrotor.quantum._gt_monomials import gt_rotations

    rep = irrep(3, (99999,))
    with hr.options(max_memory_bytes=10**8):  # a dense block would need 596 GiB
        D = gt_rotations(rep, [1, 2])
    a = np.arange(rep.dim)  # basis index a <-> m = j - a
    assert np.array_equal(D[2].perm, rep.dim - 1 - a)
    assert np.array_equal(D[2].phase, np.where(a % 2 == 0, 1.0, -1.0))
    assert np.array_equal(D[1].perm, a) and np.array_equal(D[1].phase, np.where(a % 2 == 0, -1.0, 1.0))


def test_product_ratio_does_not_overflow_and_rounds_like_the_plain_product():
    """The matrix elements' ratios of ~N factors of size l^2 overflowed for so(N >= 100) (inf / inf = NaN): carried
    as mantissa and power of two, they match the exact ratio, and the plain product wherever that is finite."""
    from hyperrotor.quantum.gelfand_tsetlin import _product_ratio

    g = np.random.default_rng(3)
    for scale in (1.0, 1e3, 1e8):  # the plain products: ~1e+1 ... 1e+130 ... inf
        a = np.rint(g.uniform(1, 2, (5, 40)) * scale)
        b = np.rint(g.uniform(1, 2, (5, 38)) * scale)
        got = _product_ratio([a[:, :20], a[:, 20:]], [b], exact=False)
        exact = [np.prod([Fraction(int(x)) for x in ra]) / np.prod([Fraction(int(x)) for x in rb])
                 for ra, rb in zip(a, b)]
        assert np.allclose(got, [float(e) for e in exact], rtol=100 * np.finfo(float).eps, atol=0)
        with np.errstate(over="ignore", invalid="ignore"):
            plain = np.prod(a, axis=1) / np.prod(b, axis=1)
        finite = np.isfinite(plain)
        assert np.array_equal(got[finite], plain[finite])
        assert scale < 1e8 or not finite.any()  # (the largest scale is the case that overflowed)


@pytest.mark.slow
def test_vector_irrep_of_so100_is_finite_with_its_casimir():
    """irrep(100, (1, 0, ...)) failed ("generator of plane (99, 100) must be a finite numeric matrix"): its Casimir
    sum_P X_P^2 is -(N - 1) on the vector irrep, every plane's generator finite."""
    N = 100
    rep = irrep(N, (1,) + (0,) * (N // 2 - 1))
    assert rep.dim == N
    C = sps.csr_matrix((N, N))
    for X in rep.generators(format="csr").values():
        assert np.all(np.isfinite(X.data))
        C = C + X @ X
    assert np.allclose(C.toarray(), -(N - 1) * np.eye(N), rtol=0, atol=scaled_tol(N - 1, dim=N))


def test_gt_index_is_priced_like_gt_patterns():
    """gt_index listed every pattern without a size check (2e6 patterns for a weight whose gt_patterns is refused;
    a TypeError deep in NumPy for 10**30)."""
    for m in ((10**6,), (10**30,)):
        with pytest.raises(ValueError, match="max_dim"):
            gt_index(3, m, (m[0], 0))


@pytest.mark.parametrize("weight", [{0: 1}, {1}, np.array(1), np.array([[1]])])
def test_highest_weight_that_is_no_sequence_is_refused(weight):
    """A dict gave its keys ({0: 1} built the trivial irrep), a set its members in no order; a 0-d array raised a
    bare "len() of unsized object"."""
    with pytest.raises(TypeError, match=r"highest_weight must be a sequence of 1 numbers for so\(3\)"):
        irrep(3, weight)


def test_real_form_and_intertwiner_are_priced_with_their_planes():
    """Their time grows like planes x dim^3 (a review: so(30) (2, 0, ...), dim 464, real form 35 s against an
    estimate of 1.5 s): with a budget between the old estimate and the new one, both are refused before work."""
    import hyperrotor.quantum as hq
    from hyperrotor._pricing import estimate

    rep = irrep(30, (2,) + (0,) * 14)
    seconds = sum(c.amount for c in estimate("real_form", dim=rep.dim, planes=len(rep.planes)) if c.unit == "seconds")
    assert seconds > 10 * sum(c.amount for c in estimate("real_form", dim=rep.dim, planes=3) if c.unit == "seconds")
    with hr.options(max_seconds=3.0):
        with pytest.raises(ValueError, match="435 planes"):
            hq.real_form(rep)
        with pytest.raises(ValueError, match="435 planes"):
            hq.intertwiner(rep, rep)


def test_the_generators_are_held_to_the_memory_budget_as_they_are_built():
    """Patterns within budget, generators not: the commutator that would pass max_memory_bytes is refused, naming
    its plane (a review: so(8) (6, 4, 4, 3) took 6 GB under 4 GiB; here a small irrep under a budget just above
    its patterns)."""
    from hyperrotor.quantum.gelfand_tsetlin import _pattern_bytes

    m = (6, 3)  # so(5), dim 770
    with hr.options(max_memory_bytes=2 * _pattern_bytes(weyl_dimension(5, m), 5)):
        with pytest.raises(hr.BudgetError, match=r"the commutator that builds plane \(\d, \d\)"):
            irrep(5, m)
    assert irrep(5, m).dim == 770


def test_hashed_pattern_lookup_of_long_patterns():
    """Patterns too long for one integer key (so(20): 100 entries) are found by a 64-bit hash checked digit by digit
    (a Python dict of tuples before: 56 s for so(40) (1, 1, 1, 0, ...)): every pattern at its place, a non-pattern
    refused, and the irrep's Casimir -c on every basis vector."""
    from hyperrotor.quantum.gelfand_tsetlin import PatternIndex, patterns

    N, m = 20, (2, 1) + (0,) * 8
    P = gt_patterns(N, m)
    index = PatternIndex(patterns(N, tuple(Fraction(x) for x in m)), tuple(Fraction(x) for x in m))
    assert not index.use_keys
    assert np.array_equal(gt_index(N, m, P[::-1]), np.arange(len(P))[::-1])
    Q = P[:5].copy()
    Q[:, -1] += 7.0  # (off the irrep's range)
    assert np.all(index.lookup(Q) == -1)
    rep = irrep(N, m)
    C = sum(X @ X for X in rep.generators(format="csr").values())
    c = float(casimir_eigenvalue(N, m))
    assert np.allclose(C.toarray(), -c * np.eye(rep.dim), rtol=0, atol=scaled_tol(c, dim=N))


def test_building_the_generators_is_priced():
    """The generators' time (so(40) (1, 1, 1, 0, ...): ~8 s, 56 s before the hashed lookups) is checked against
    max_seconds before the patterns are built."""
    with hr.options(max_seconds=1.0):
        with pytest.raises(hr.BudgetError, match=r"gt_generators: the sparse generators of a dimension-9880 irrep"):
            irrep(40, (1, 1, 1) + (0,) * 17)


def test_gt_index_refuses_entries_that_are_no_half_integers_and_takes_max_dim():
    """0.8 was rounded to the digit of 1 (the pattern [1, 1] found for [1, 0.8]); an irrep beyond the default
    max_dim is indexed with max_dim= as gt_patterns builds it (gt_index had no max_dim)."""
    with pytest.raises(ValueError, match=r"\[1.0, 0.8\] is not a Gelfand-Tsetlin pattern .* integers or half-integers"):
        gt_index(3, (1,), [1, 0.8])
    N, m = 20, (2, 1) + (0,) * 8  # (the hashed lookup)
    P = gt_patterns(N, m)
    Q = P[5].copy()
    Q[np.flatnonzero(Q == 1)[0]] = 0.8
    with pytest.raises(ValueError, match="integers or half-integers"):
        gt_index(N, m, Q)
    m3 = (100_000,)  # dim 200 001, beyond DEFAULT_MAX_DIM
    with pytest.raises(ValueError, match=r"its 200001 patterns: .* max_dim=200001"):
        gt_index(3, m3, (100_000, 5))
    assert gt_index(3, m3, (100_000, 5), max_dim=200_001) == 100_000 - 5


@pytest.mark.parametrize("dynkin", [{0: 2}, {1, 0}, np.array(2)])
def test_dynkin_labels_that_are_no_sequence_are_refused(dynkin):
    with pytest.raises(TypeError, match="dynkin must be a sequence of"):
        irrep(3 if not isinstance(dynkin, set) else 5, dynkin=dynkin)
