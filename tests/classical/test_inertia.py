"""Tests of hyperrotor.Inertia: normalization, eq.-(3) tensor, bodies, named inertias, errors."""
import itertools

import numpy as np
import pytest
import sympy as sp
from scipy.stats import special_ortho_group

import hyperrotor as hr
from hyperrotor import Inertia
from hyperrotor.classical.mass_points import check_tensor_symmetries, inertia_tensor
from tolerance import scaled_tol


# ---------------------------------------------------------------- constructors
def test_from_planes_mapping_and_sequence_agree():
    m = {(1, 2): 3.0, (1, 3): 2.0, (2, 3): 1.5}
    a = Inertia.from_planes(m)
    b = Inertia.from_planes([3.0, 2.0, 1.5])
    assert a.N == b.N == 3
    assert a.planes == ((1, 2), (1, 3), (2, 3))
    np.testing.assert_array_equal(a.moments, [3.0, 2.0, 1.5])
    assert a == b
    assert a[(1, 3)] == 2.0
    assert a.moments.dtype == np.float64


def test_from_planes_mapping_order_irrelevant():
    ps = hr.planes(4)
    vals = {p: float(k + 1) for k, p in enumerate(ps)}
    shuffled = dict(reversed(list(vals.items())))
    np.testing.assert_array_equal(Inertia.from_planes(shuffled).moments, np.arange(1, 7))


def test_missing_plane_is_named():
    with pytest.raises(ValueError, match=r"missing moments for planes \[\(2, 3\)\]"):
        Inertia.from_planes({(1, 2): 1.0, (1, 3): 1.0})


@pytest.mark.parametrize("key", [(2, 1), (0, 1), (1, 1), "ab"])
def test_unknown_plane(key):
    with pytest.raises(ValueError, match="plane"):
        Inertia.from_planes({key: 1.0, (1, 2): 1.0})


def test_unknown_plane_for_given_N():
    with pytest.raises(ValueError, match="unknown planes"):
        Inertia.from_planes({(1, 2): 1.0, (1, 3): 1.0, (2, 3): 1.0, (3, 4): 1.0}, N=3)


@pytest.mark.parametrize("count", [2, 4, 5, 7])
def test_wrong_count(count):
    with pytest.raises(ValueError, match=f"moments has {count} plane moments"):
        Inertia.from_planes([1.0] * count)


@pytest.mark.parametrize("bad,exc,msg", [
    (0.0, ValueError, "> 0"), (-1.0, ValueError, "> 0"), (np.inf, ValueError, "finite"),
    (np.nan, ValueError, "finite"), ("x", TypeError, "real number"), (None, TypeError, "real number"),
    (1 + 2j, TypeError, "real number"), (True, TypeError, "real number"),
    (sp.Integer(-2), ValueError, "> 0"), (sp.oo, ValueError, "finite"),
])
def test_bad_moments(bad, exc, msg):
    with pytest.raises(exc, match=msg):
        Inertia.from_planes([1.0, bad, 1.0])


def test_bad_moment_names_the_plane():
    with pytest.raises(ValueError, match="I_13"):
        Inertia.from_planes([1.0, -3.0, 1.0])


@pytest.mark.parametrize("N", [0, 1])
def test_dimension_too_small(N):
    with pytest.raises(ValueError, match="N must be an integer >= 2"):
        Inertia.equal(N, 1.0)


def test_symbolic_moments_accepted_and_moments_refused():
    a, b = sp.symbols("a b", positive=True)
    I = Inertia.from_planes([a, b, a + b])
    assert I.is_symbolic
    assert I.symbolic_moments == (a, b, a + b)
    assert I[(2, 3)] == a + b
    with pytest.raises(TypeError, match="symbolic"):
        I.moments
    num = I.subs({a: 1, b: 2})
    assert not num.is_symbolic
    np.testing.assert_array_equal(num.moments, [1.0, 2.0, 3.0])


def test_symbolic_negative_expression_refused():
    a = sp.Symbol("a", positive=True)
    with pytest.raises(ValueError, match="> 0"):
        Inertia.from_planes([a, -a, 1])


def test_symbolic_constructor():
    I = Inertia.symbolic(4)
    assert I.symbolic_moments == hr.plane_symbols("I", 4, positive=True)
    assert [str(s) for s in I.symbolic_moments] == ["I_12", "I_13", "I_14", "I_23", "I_24", "I_34"]


# ---------------------------------------------------------------- mass tensor / physicality
def test_from_mass_tensor_and_back():
    J = [1.0, 2.0, 4.0, 8.0]
    I = Inertia.from_mass_tensor(J)
    for (i, j), v in zip(I.planes, I.moments):
        assert v == J[i - 1] + J[j - 1]
    np.testing.assert_array_equal(I.mass_tensor, J)
    assert I.is_physical()
    # the same moments given per plane: J is recovered by solving
    again = Inertia.from_planes(list(I.moments))
    np.testing.assert_allclose(again.mass_tensor, J, rtol=1e-15)


def test_mass_tensor_symbolic_solved():
    J = sp.symbols("J1:5", positive=True)
    I = Inertia.from_planes([J[i - 1] + J[j - 1] for i, j in hr.planes(4)])
    assert I.mass_tensor == J
    assert I.is_physical() is True


def test_generic_inertia_is_not_a_mass_tensor():
    assert Inertia.symbolic(4).mass_tensor is None
    assert Inertia.symbolic(4).is_physical() is False
    assert Inertia.from_planes([1.0, 2.0, 3.0, 4.0, 5.0, 7.0]).mass_tensor is None


def test_3d_triangle_inequality_is_physicality():
    # every 3D inertia has the form J_i + J_j; physical iff I_3 <= I_1 + I_2 (and cyclic)
    assert Inertia.from_planes({(1, 2): 1.0, (1, 3): 2.0, (2, 3): 3.0}).is_physical()  # flat: J_1 = 0
    bad = Inertia.from_planes({(1, 2): 1.0, (1, 3): 2.0, (2, 3): 3.5})
    # J_1 + J_2 = 1, J_1 + J_3 = 2, J_2 + J_3 = 3.5: J_1 = (1 + 2 - 3.5) / 2 < 0 (I_23 > I_12 + I_13)
    np.testing.assert_allclose(bad.mass_tensor, [-0.25, 1.25, 2.25], rtol=0, atol=scaled_tol(3.5, dim=3))
    assert not bad.is_physical()


def test_symbolic_physicality_undecidable():
    a, b, c = sp.symbols("a b c", positive=True)
    assert Inertia.from_planes([a, b, c]).is_physical() is None


# ---------------------------------------------------------------- continuous bodies
def test_box_3d_textbook():
    M, a, b, c = sp.symbols("M a b c", positive=True)
    I = Inertia.box(M, [a, b, c])
    I1, I2, I3 = I[(2, 3)], I[(1, 3)], I[(1, 2)]  # textbook map I_1 = I_23, ...
    assert sp.simplify(I1 - M * (b**2 + c**2) / 12) == 0
    assert sp.simplify(I2 - M * (a**2 + c**2) / 12) == 0
    assert sp.simplify(I3 - M * (a**2 + b**2) / 12) == 0


def test_ball_3d_textbook():
    M, R = sp.symbols("M R", positive=True)
    I = Inertia.ball(3, M, R)
    for v in I.symbolic_moments:
        assert sp.simplify(v - sp.Rational(2, 5) * M * R**2) == 0


def test_ellipsoid_moments_match_integral():
    # m_i = M a_i^2/(N+2): check the unit-ball average of x_1^2 by exact integration for N = 2..6
    for N in range(2, 7):
        r = sp.Symbol("r", positive=True)
        # <x_1^2> over the unit N-ball = (1/N) <r^2> = (1/N) * int r^{N+1} / int r^{N-1}
        avg = sp.integrate(r ** (N + 1), (r, 0, 1)) / sp.integrate(r ** (N - 1), (r, 0, 1)) / N
        assert avg == sp.Rational(1, N + 2)
        I = Inertia.ball(N, 1, 1)
        assert all(v == sp.Rational(2, N + 2) for v in I.symbolic_moments)


def test_from_points_box_sample_converges(rng):
    sides = np.array([1.0, 2.0, 3.0, 0.5])
    n = 400_000
    x = rng.uniform(-0.5, 0.5, (n, 4)) * sides
    I = Inertia.from_points(np.full(n, 2.0 / n), x)
    exact = Inertia.box(2.0, sides)
    # Monte-Carlo: relative standard error of <x^2> for a uniform variable ~ sqrt(4/5 / n) ~ 1.4e-3
    np.testing.assert_allclose(I.moments, exact.moments, rtol=8e-3)
    np.testing.assert_allclose(I.principal_axes, np.eye(4), atol=2e-2, rtol=0)


def test_from_points_rotated_ellipsoid(rng):
    N, n = 5, 300_000
    semi = np.array([1.0, 1.5, 2.0, 2.5, 3.0])
    g = rng.standard_normal((n, N))
    g /= np.linalg.norm(g, axis=1, keepdims=True)
    pts = g * rng.uniform(0, 1, (n, 1)) ** (1 / N) * semi  # uniform in the ellipsoid
    R = special_ortho_group.rvs(N, random_state=7)
    I = Inertia.from_points(np.full(n, 1.0 / n), pts @ R.T)
    exact = Inertia.ellipsoid(1.0, semi)
    P = I.principal_axes
    np.testing.assert_allclose(P.T @ P, np.eye(N), rtol=0, atol=scaled_tol(P, k=16))  # eigenvectors: ~ N eps
    assert np.linalg.det(P) == pytest.approx(1.0, abs=scaled_tol(P, k=16))
    # moments come out in some axis order: compare the sorted mass tensors
    np.testing.assert_allclose(np.sort(I.mass_tensor), np.sort(exact.mass_tensor), rtol=1e-2)
    # the principal axes diagonalize the second moments
    c = pts @ R.T
    c = c - c.mean(axis=0)
    D = P.T @ (c.T @ c / n) @ P
    # (D is a sum over the n points, here and in the package in another order: its round-off walks like sqrt(n))
    np.testing.assert_allclose(D - np.diag(np.diag(D)), 0, atol=scaled_tol(D, k=16, steps=n), rtol=0)
    np.testing.assert_allclose(np.diag(D), I.mass_tensor, rtol=1e-12)


def test_from_points_discrete_exact():
    # two unit masses at +-e_1 and two at +-2 e_2 in 3D: m = (2, 8, 0)
    pos = [[1, 0, 0], [-1, 0, 0], [0, 2, 0], [0, -2, 0]]
    I = Inertia.from_points([1, 1, 1, 1], pos)
    np.testing.assert_allclose(I.mass_tensor, [2, 8, 0], rtol=0, atol=scaled_tol(8.0, dim=len(pos)))
    np.testing.assert_allclose([I[(1, 2)], I[(1, 3)], I[(2, 3)]], [10, 2, 8], rtol=0, atol=scaled_tol(10.0, dim=len(pos)))


def test_from_points_in_high_dimension_builds_no_rank_4_tensor(rng):
    """from_points built the N^4 tensor of eq. (3) only to check its symmetries (12 GB at N = 200: a MemoryError
    from inside NumPy); the moments come from the second-moment matrix: its eigenvalues are the mass tensor."""
    N, n = 200, 400
    pos = rng.normal(size=(n, N)) * np.linspace(1.0, 2.0, N)
    I = Inertia.from_points(np.ones(n), pos)
    c = pos - pos.mean(axis=0)
    exact = np.linalg.eigvalsh(c.T @ c)
    np.testing.assert_allclose(np.sort(I.mass_tensor), exact, rtol=0, atol=scaled_tol(exact.max(), dim=N, k=16))
    with pytest.raises(hr.BudgetError, match="max_dimension"):
        Inertia.from_points(np.ones(3), np.ones((3, 1001)))


def test_from_points_centre_of_mass():
    pos = np.array([[1.0, 0.0], [3.0, 0.0], [2.0, 1.0], [2.0, -1.0]])
    a = Inertia.from_points(np.ones(4), pos)
    b = Inertia.from_points(np.ones(4), pos - [2.0, 0.0], center=False)
    np.testing.assert_allclose(a.moments, b.moments, rtol=1e-14)
    c = Inertia.from_points(np.ones(4), pos, center=False)
    # one plane (1, 2): sum m |r|^2; about the centre (2, 0) the points are at distance 1: 4; about the origin
    # 1 + 9 + 5 + 5 = 20 = 4 + M d^2 with M = 4, d = 2 (parallel-axis theorem)
    np.testing.assert_allclose(a.moments, [4.0], rtol=0, atol=scaled_tol(20.0, dim=4))
    np.testing.assert_allclose(c.moments, [4.0 + 4 * 2.0 ** 2], rtol=0, atol=scaled_tol(20.0, dim=4))


@pytest.mark.parametrize("masses,positions,msg", [
    ([1, 1], [[0, 0, 0]], "masses must have shape"),
    ([1], [0, 0], "positions must have shape"),
    ([-1, 2], [[0, 0], [1, 1]], ">= 0"),
    ([1, 1], [[0, np.nan], [1, 1]], "finite"),
])
def test_from_points_bad_input(masses, positions, msg):
    with pytest.raises(ValueError, match=msg):
        Inertia.from_points(masses, positions)


# ---------------------------------------------------------------- the eq.-(3) tensor
def test_eq3_tensor_symmetries_and_normalization(rng):
    N = 5
    m = rng.uniform(0.1, 1, 40)
    x = rng.standard_normal((40, N))
    T = inertia_tensor(m, x)
    check_tensor_symmetries(T)
    # explicit symmetries (eq. 3)
    # each entry is a sum over the 40 points of products of coordinates: round-off ~ 40 eps max|T|
    tol = scaled_tol(np.abs(T).max(), dim=len(m))
    np.testing.assert_allclose(T, -T.transpose(1, 0, 2, 3), rtol=0, atol=tol)
    np.testing.assert_allclose(T, -T.transpose(0, 1, 3, 2), rtol=0, atol=tol)
    np.testing.assert_allclose(T, T.transpose(2, 3, 0, 1), rtol=0, atol=tol)
    np.testing.assert_allclose(T + T.transpose(0, 2, 3, 1) + T.transpose(0, 3, 1, 2), 0, rtol=0, atol=3 * tol)
    # rotate to principal axes
    I = Inertia.from_points(m, x)
    R = I.principal_axes
    Tp = np.einsum("ai,bj,ck,dl,abcd->ijkl", R, R, R, R, T)
    # four rotations of T: N^4 terms per entry whose absolute sum is <= N^2 max|T| (rows of R are unit vectors)
    np.testing.assert_allclose(Tp, I.tensor(), rtol=0, atol=scaled_tol(np.abs(T).max() * N**2, dim=N**2, k=16))
    Jm = I.mass_tensor
    for i, j in itertools.permutations(range(N), 2):
        assert Tp[i, j, i, j] == pytest.approx((Jm[i] + Jm[j]) / 2, rel=1e-12)  # I^{ijij} = (m_i+m_j)/2
    # full summation of eq. (4): L^ij = I^{ijkl} w_kl = I_ij w_ij = 2 I^{ijij} w_ij
    w = hr.to_matrix(rng.standard_normal(hr.n_planes(N)), convention="standard")
    L = np.einsum("ijkl,kl->ij", Tp, w)
    Lexp = hr.to_matrix(I.moments * hr.to_components(w, convention="standard"), convention="standard")
    np.testing.assert_allclose(L, Lexp, rtol=0, atol=scaled_tol(np.abs(Tp).max() * N**2 * np.abs(w).max(), dim=N**2, k=16))
    for (i, j), Iij in zip(I.planes, I.moments):
        assert Iij == pytest.approx(2 * Tp[i - 1, j - 1, i - 1, j - 1], rel=1e-12)
    # eq. (6) with full summation, 1/2 w_ij I^{ijkl} w_kl = 1/2 w_ij L^ij, counts each plane twice:
    # it is TWICE the kinetic energy 1/2 sum_{i<j} I_ij w_ij^2 (paper's factor-2 slip)
    W6 = 0.5 * np.einsum("ij,ijkl,kl->", w, Tp, w)
    body = hr.RigidBody(I)
    assert W6 == pytest.approx(2 * body.energy(hr.to_components(w, convention="standard")), rel=1e-12)


def test_tensor_symmetries_for_generalized_inertia():
    I = Inertia.from_planes([1.0, 2.0, 3.0, 4.0, 5.0, 7.0])  # not a mass tensor
    check_tensor_symmetries(I.tensor())
    T = I.tensor()
    assert T[0, 1, 0, 1] == 0.5 and T[0, 1, 1, 0] == -0.5


def test_tensor_symmetry_violation_detected():
    T = np.zeros((3, 3, 3, 3))
    T[0, 1, 0, 1] = 1.0
    with pytest.raises(ValueError, match="violates"):
        check_tensor_symmetries(T)


def test_symbolic_tensor():
    T = Inertia.symbolic(3).tensor()
    assert T[0, 1, 0, 1] == sp.Symbol("I_12", positive=True) / 2


# ---------------------------------------------------------------- named inertias
def test_equal_eq82():
    I = Inertia.equal(5, 3.0)
    np.testing.assert_array_equal(I.moments, np.full(10, 3.0))


@pytest.mark.parametrize("axis,eq", [(5, "84-85"), (4, "111"), (3, "112"), (2, "113"), (1, "114")])
def test_quartet_eqs_84_85_111_114(axis, eq):
    k = sp.Symbol("kappa", positive=True)
    I = Inertia.quartet(k, axis=axis)
    # typed from the paper: the four planes containing the distinguished axis get 1 + kappa^2
    printed_distinct = {
        5: [(1, 5), (2, 5), (3, 5), (4, 5)],
        4: [(1, 4), (2, 4), (3, 4), (4, 5)],
        3: [(1, 3), (2, 3), (3, 4), (3, 5)],
        2: [(1, 2), (2, 3), (2, 4), (2, 5)],
        1: [(1, 2), (1, 3), (1, 4), (1, 5)],
    }[axis]
    for p in I.planes:
        assert I[p] == (1 + k**2 if p in printed_distinct else 2), (eq, p)
    assert I.is_physical() is True
    assert I.mass_tensor == tuple(k**2 if a == axis else 1 for a in range(1, 6))


def test_quartet_general_N_and_exact():
    I = Inertia.quartet(sp.Rational(1, 2), axis=2, N=4)
    assert I.symbolic_moments == (sp.Rational(5, 4), 2, 2, sp.Rational(5, 4), sp.Rational(5, 4), 2)
    np.testing.assert_array_equal(Inertia.quartet(0.5, N=4, axis=4).moments, [2, 2, 1.25, 2, 1.25, 1.25])


@pytest.mark.parametrize("kw,exc", [({"axis": 6}, ValueError), ({"axis": 0}, ValueError),
                                    ({"kappa": np.inf}, ValueError), ({"kappa": "a"}, TypeError)])
def test_quartet_bad(kw, exc):
    args = {"kappa": 0.5, **kw}
    with pytest.raises(exc):
        Inertia.quartet(**args)


def test_repr_and_hash():
    I = Inertia.equal(3, 1)
    assert "12: 1" in repr(I)
    assert hash(I) == hash(Inertia.equal(3, 1))
    assert I[(1, 2)] == 1.0


def test_subs_reads_text_safely(tmp_path, monkeypatch):
    """#21: Inertia.subs never sympifies: text goes through hyperrotor._parse (names, numbers, arithmetic)."""
    monkeypatch.chdir(tmp_path)
    a = sp.Symbol("a")
    inertia = hr.Inertia([a, 2, 3])
    for payload in ("__import__('os').system('touch pwned')", "().__class__.__mro__", "9**9**9**9"):
        with pytest.raises(hr.ParseError):
            inertia.subs("a", payload)
        with pytest.raises(hr.ParseError):
            inertia.subs({"a": payload})
    assert not (tmp_path / "pwned").exists()
    assert inertia.subs("a", "1/2").moments.tolist() == [0.5, 2.0, 3.0]
    assert inertia.subs({a: sp.Rational(1, 2)}).symbolic_moments[0] == sp.Rational(1, 2)
    assert inertia.subs([(a, 5)]).symbolic_moments[0] == 5
    with pytest.raises(TypeError, match="subs takes"):
        inertia.subs("a")


def test_numeric_moments_fast_path_and_price():
    """Plain numbers are checked at once with the same results (exact ints, Floats) and messages;
    a huge body is refused by its price (model 'Inertia') before any SymPy number is made."""
    I = hr.Inertia(np.array([1, 2, 3]))
    assert I.symbolic_moments == (1, 2, 3) and all(isinstance(v, sp.Integer) for v in I.symbolic_moments)
    J = hr.Inertia([1.5, 2, np.float64(3.25)])
    assert J.symbolic_moments == (sp.Float(1.5), 2, sp.Float(3.25)) and J.moments.tolist() == [1.5, 2.0, 3.25]
    with pytest.raises(ValueError, match="moment I_13 must be > 0, got -2"):
        hr.Inertia([1, -2, 3])
    with pytest.raises(ValueError, match="moment I_23 must be finite"):
        hr.Inertia(np.array([1.0, 2.0, np.inf]))
    with hr.options(max_seconds=1.0):
        with pytest.raises(hr.BudgetError, match="Inertia"):
            hr.Inertia(np.ones(hr.n_planes(1000)))


@pytest.mark.parametrize("J", [[1, 2, 3], [1.5, 0, 2], np.array([0.3, 1.1, 2.0, 0.0]), [1, 2.5, 0],
                               np.array([1, 2, 3, 4], dtype=np.int64), [2**60, 1.0, 3], [1, 2**60 + 1, 3]],
                         ids=["ints", "floats", "array", "mixed", "int-array", "huge-int-float", "huge-ints"])
def test_plain_mass_tensors_take_the_fast_path_with_the_same_moments(J):
    """from_mass_tensor sums plain numbers at once (32 s of SymPy at N = 900 before, one number per plane):
    the same SymPy values and types, moments and mass tensor as the per-plane path, which SymPy entries take."""
    fast = Inertia.from_mass_tensor(J)
    slow = Inertia.from_mass_tensor([sp.Integer(0) + (sp.Integer(int(v)) if isinstance(v, (int, np.integer))
                                                      else sp.Float(float(v))) for v in J])
    assert fast.symbolic_moments == slow.symbolic_moments
    assert [type(v) for v in fast.symbolic_moments] == [type(v) for v in slow.symbolic_moments]
    np.testing.assert_array_equal(fast.moments, slow.moments)
    np.testing.assert_array_equal(fast.mass_tensor, slow.mass_tensor)
    assert fast.is_physical() == slow.is_physical()


def test_a_mass_tensor_is_priced_and_checked_as_moments_are():
    with hr.options(max_seconds=1e-3):
        with pytest.raises(hr.BudgetError, match="Inertia: the moments of 4950 planes"):
            Inertia.from_mass_tensor(np.ones(100))
    with pytest.raises(ValueError, match=r"moment I_12 = J_1 \+ J_2 must be > 0, got 0"):
        Inertia.from_mass_tensor([0, 0, 1])
    with pytest.raises(ValueError, match="J_2 must be >= 0"):
        Inertia.from_mass_tensor([1.0, -1.0, 2.0])
    with pytest.raises(TypeError):
        Inertia.from_mass_tensor(np.array([True, False, True]))


def test_plain_mass_tensors_whose_moments_overflow_are_refused_by_name():
    """Plain numbers J_1 + J_2 = 3.4e308 make no float: the fast path built a moment SymPy oo with numpy's
    overflow warning; refused now, naming the plane and the entries. (SymPy entries stay SymPy: a body of
    moments 4e599 has exact Euler equations, as before.)"""
    with pytest.raises(ValueError, match=r"J: moment I_12 = J_1 \+ J_2 = 1.7e\+308 \+ 1.7e\+308 overflows"):
        Inertia.from_mass_tensor([1.7e308, 1.7e308, 1.0])
    big = Inertia.from_mass_tensor([sp.Float(1.7e308), sp.Float(1.7e308), sp.Integer(1)])
    assert big.symbolic_moments[0] == sp.Float(1.7e308) + sp.Float(1.7e308)


@pytest.mark.parametrize("maker", ["box", "ellipsoid"])
def test_a_box_of_floats_takes_the_numpy_sums_and_the_same_moments(maker):
    """Float sides made a mass tensor of SymPy Floats, summed plane by plane in SymPy (5 s at N = 200): they go to
    from_mass_tensor as Python floats now, the same numbers (IEEE doubles rounded once either way); exact sides
    stay exact."""
    import sympy as sp

    sides = [0.3, 1.0, 1.7, 2.25, 0.9]
    fast = getattr(Inertia, maker)(1.5, sides)
    d = 12 if maker == "box" else len(sides) + 2
    slow = Inertia.from_mass_tensor([sp.Float(1.5) * sp.Float(x) ** 2 / d for x in sides])  # (the per-plane path)
    assert fast == slow and np.array_equal(fast.moments, slow.moments)
    assert all(type(a) is type(b) and a == b for a, b in zip(fast.symbolic_moments, slow.symbolic_moments))
    exact = getattr(Inertia, maker)(1, [1, 2, 3])
    assert all(isinstance(v, sp.Rational) for v in exact.symbolic_moments)


def test_points_of_any_scale():
    """Positions of 1e160 gave a bare LinAlgError from eigh (inertia_tensor: NaN) and 1e-170 a zero moment blamed on
    J; the points are scaled by powers of two now, so a body scaled by 2^k has its moments scaled by exactly 4^k and
    the same principal axes, and what leaves the double range is refused naming the points."""
    g = np.random.default_rng(3)
    r, m = g.normal(size=(40, 4)), g.uniform(0.5, 2.0, 40)
    base = Inertia.from_points(m, r)
    for k, j in ((300, 0), (-200, -500), (0, 900)):
        other = Inertia.from_points(m * 2.0 ** j, r * 2.0 ** k)
        np.testing.assert_array_equal(np.asarray(other.moments, float), np.asarray(base.moments, float) * 2.0 ** (2 * k + j))
        np.testing.assert_array_equal(other.principal_axes, base.principal_axes)
    with pytest.raises(ValueError, match="second moments .* exceed double precision .* positions up to"):
        Inertia.from_points(m, r * 1e160)
    with pytest.raises(ValueError, match="second moments .* exceed double precision"):
        hr.inertia_tensor(m, r * 1e160)
    with pytest.raises(ValueError, match="second moments .* underflow double precision"):
        Inertia.from_points(m, r * 1e-170)
    with pytest.raises(ValueError, match=r"J_1 = .*beyond double precision"):
        Inertia.from_mass_tensor([10**400, 1])  # (a bare OverflowError before)


def test_point_clouds_are_priced_before_their_products(monkeypatch):
    """N over max_dimension was refused only after the eigh and the assignment (51 s at N = 3000), and
    second_moment_matrix had no check (3.2 GB from two points at N = 20000)."""
    from hyperrotor.classical import mass_points

    def no_work(*args, **kwargs):
        raise AssertionError("work started before the refusal")

    monkeypatch.setattr(mass_points.np.linalg, "eigh", no_work)
    with pytest.raises(hr.BudgetError, match="max_dimension"):
        Inertia.from_points(np.ones(2), np.ones((2, 3000)))
    with pytest.raises(hr.BudgetError, match="max_dimension"):
        hr.second_moment_matrix(np.ones(2), np.ones((2, 20000)))
    with hr.options(max_seconds=0.01), pytest.raises(hr.BudgetError, match="principal_axes"):
        Inertia.from_points(np.ones(3), np.eye(3, 600))
    with hr.options(max_memory_bytes=10**6), pytest.raises(hr.BudgetError, match="second_moment_matrix"):
        hr.second_moment_matrix(np.ones(10**5), np.zeros((10**5, 5)))


def test_second_moments_that_fit_are_returned():
    """The range was first judged on the scale factor alone: a 1e300 mass at the origin with a unit mass at 1e100
    (moments 1e200), a cloud at 1e160 of spread 1e146 (~1e292), coincident points at 1e160 (exactly 0) and
    positions of 1e-160 (2e-320, subnormal) were refused although they fit (a review of the session's change)."""
    np.testing.assert_array_equal(hr.second_moment_matrix([1e300, 1.0], [[0.0, 0.0], [1e100, 0.0]], center=False),
                                  [[1e200, 0.0], [0.0, 0.0]])
    np.testing.assert_array_equal(hr.second_moment_matrix(np.ones(3), np.full((3, 2), 1e160)), np.zeros((2, 2)))
    np.testing.assert_array_equal(hr.second_moment_matrix(np.ones(2), [[1e-160, 0.0], [-1e-160, 0.0]]),
                                  [[2e-320, 0.0], [0.0, 0.0]])
    g = np.random.default_rng(0)
    r = g.normal(size=(20, 3))
    far = Inertia.from_points(np.ones(20), 2.0 ** 500 + 2.0 ** 490 * r)  # (at 3e150, a spread of 3e147)
    near = Inertia.from_points(np.ones(20), r)
    np.testing.assert_allclose(np.asarray(far.moments, float), np.asarray(near.moments, float) * 2.0 ** 980,
                               rtol=1e-9, atol=0)  # (the centre rounds the positions to ~2e-13 of the spread)


def test_masses_beyond_the_range_of_each_other_are_refused():
    """Scaled by the heaviest, a mass below 2^-1022 of it lost its share silently (0 where m r^2 = 1e100; digits
    lost at 3.3e-160 beside 1e160); principal moments up to the trace overflowed in from_points after a range check
    on the largest entry only ('J_2 must be finite, got inf')."""
    with pytest.raises(ValueError, match=r"masses span more than double precision: 1e-300 beside 1e\+300"):
        hr.second_moment_matrix([1e300, 1e-300], [[0.0, 0.0], [1e200, 0.0]])
    with pytest.raises(ValueError, match="masses span more than double precision"):
        hr.second_moment_matrix([1e160, 3.3e-160], [[0.0, 0.0], [1e150, 0.0]])
    with pytest.raises(ValueError, match="second moments .* exceed double precision"):
        Inertia.from_points([0.5, 0.5], [[1e154, 1e154], [-1e154, -1e154]])
