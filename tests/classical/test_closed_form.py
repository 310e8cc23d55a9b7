"""Closed forms of Sec. 3: equal moments, the quartet (any axis, any N), 3D Euler-Poinsot.

References are independent: a tight DOP853 run of the component Euler equations
(written here from the structure constants), SymPy derivations from the same
component equations, and an mpmath evaluation at 40 digits.
"""
import itertools

import mpmath
import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp

from hyperrotor.classical import (
    closed_form_solution,
    detect_closed_form,
    equal_moments_solution,
    euler_poinsot,
    euler_poinsot_period,
    quartet_frequencies,
    quartet_matrix,
    quartet_moments,
    quartet_polynomial_coefficients,
    quartet_solution,
    quartet_theta,
)
from hyperrotor.conventions import dimension_from_count, plane_index, plane_symbols, planes, structure_constants
from references import component_rhs
from tolerance import scaled_tol

TIGHT = dict(method="DOP853", rtol=1e-13, atol=1e-13)


def _reference(I, w0, t):
    sol = solve_ivp(component_rhs(I), (t[0], t[-1]), w0, t_eval=t, **TIGHT)
    assert sol.success
    return sol.y.T


def _sym_rhs(I, w):
    """Symbolic dw/dt for moment list I and symbol list w."""
    N = dimension_from_count(len(w))
    C = structure_constants(N)
    out = []
    for a in range(len(w)):
        s = sum(int(C[b, c, a]) * w[b] * I[c] * w[c] for b, c in zip(*np.nonzero(C[:, :, a])))
        out.append(sp.expand(s / I[a]))
    return out


# ----------------------------------------------------------------------------
# equal moments (82-83)
# ----------------------------------------------------------------------------
@pytest.mark.parametrize("N", [3, 4, 5, 7])
def test_equal_moments_constant(N):
    rng = np.random.default_rng(N)
    n = N * (N - 1) // 2
    w0 = rng.normal(size=n)
    t = np.linspace(0, 7, 9)
    I = np.full(n, 1.7)
    assert np.max(np.abs(component_rhs(I)(0, w0))) < 1e-14
    out = equal_moments_solution(w0, t)
    assert out.shape == (9, n)
    np.testing.assert_array_equal(out, np.broadcast_to(w0, (9, n)))
    np.testing.assert_allclose(_reference(I, w0, t), out, atol=1e-12, rtol=0)
    sol, kind = closed_form_solution(I, w0, t)
    assert kind == "equal"


# ----------------------------------------------------------------------------
# quartet: symbolic derivation of the linear system and of the paper's equations
# ----------------------------------------------------------------------------
@pytest.mark.parametrize("axis", [1, 2, 3, 4, 5])
def test_quartet_linear_system_is_exact(axis):
    """For every axis: constants have zero derivative; axis planes obey x' = Theta A x exactly."""
    k = sp.Symbol("kappa", positive=True)
    w = plane_symbols("w", 5)
    I = [1 + k**2 if axis in p else sp.Integer(2) for p in planes(5)]
    rhs = _sym_rhs(I, w)
    theta = (k**2 - 1) / (k**2 + 1)
    others = [i for i in range(1, 6) if i != axis]
    idx = [plane_index((min(i, axis), max(i, axis)), 5) for i in others]
    # the matrix A from quartet_matrix, rebuilt symbolically via unit vectors
    A = sp.zeros(4, 4)
    for q, p in enumerate(planes(5)):
        if axis in p:
            continue
        e = np.zeros(10)
        e[q] = 1.0
        A += sp.Matrix(quartet_matrix(e, axis).astype(int)) * w[q]
    x = sp.Matrix([w[i] for i in idx])
    lin = theta * A * x
    for q, p in enumerate(planes(5)):
        if axis not in p:
            assert rhs[q] == 0
    for r, q in enumerate(idx):
        assert sp.simplify(rhs[q] - lin[r]) == 0
    assert A.T == -A


def test_quartet_paper_equations_89_to_99():
    """(89), (94), (96)-(99) are right; (92) and (95) have the wrong sign (vs eqs. 34, 37)."""
    k = sp.Symbol("kappa", positive=True)
    w = plane_symbols("w", 5)
    w12, w13, w14, w15, w23, w24, w25, w34, w35, w45 = w
    I = quartet_moments(0.0, 5)  # pattern only
    Isym = [1 + k**2 if v == 1.0 else sp.Integer(2) for v in I]
    rhs = dict(zip(planes(5), _sym_rhs(Isym, w)))
    a = 1 + k**2
    printed = {
        "89": (a * rhs[(1, 5)] + (1 - k**2) * (w12 * w25 + w13 * w35 + w14 * w45)),
        "92": (a * rhs[(2, 5)] + (1 - k**2) * (w12 * w15 - w23 * w35 - w24 * w45)),
        "94": (a * rhs[(3, 5)] - (1 - k**2) * (w13 * w15 + w23 * w25 - w34 * w45)),
        "95": (a * rhs[(4, 5)] + (1 - k**2) * (w14 * w15 + w24 * w25 + w34 * w35)),
    }
    assert sp.simplify(printed["89"]) == 0
    assert sp.simplify(printed["94"]) == 0
    assert sp.simplify(printed["92"]) != 0
    assert sp.simplify(printed["95"]) != 0
    # corrected (92), (95): flip the sign of the (1 - kappa^2) term
    assert sp.simplify(a * rhs[(2, 5)] - (1 - k**2) * (w12 * w15 - w23 * w35 - w24 * w45)) == 0
    assert sp.simplify(a * rhs[(4, 5)] - (1 - k**2) * (w14 * w15 + w24 * w25 + w34 * w35)) == 0
    # (96)-(99) with c1..c6 = w12, w13, w14, w23, w24, w34
    th = (k**2 - 1) / (k**2 + 1)
    c1, c2, c3, c4, c5, c6 = w12, w13, w14, w23, w24, w34
    eq96 = rhs[(1, 5)] - th * c1 * w25 - th * c2 * w35 - th * c3 * w45
    eq97 = rhs[(2, 5)] + th * c1 * w15 - th * c4 * w35 - th * c5 * w45
    eq98 = rhs[(3, 5)] + th * c2 * w15 + th * c4 * w25 - th * c6 * w45
    eq99 = rhs[(4, 5)] + th * c3 * w15 + th * c5 * w25 + th * c6 * w35
    for e in (eq96, eq97, eq98, eq99):
        assert sp.simplify(e) == 0
    # (105) as printed (-Theta c5 C25) contradicts (99); (106) entry (2,4) +Theta c5 is not antisymmetric
    O = sp.Symbol("Omega")
    C15, C25, C35, C45 = sp.symbols("C15 C25 C35 C45")
    eq105_printed = sp.I * O * C45 + th * c3 * C15 - th * c5 * C25 + th * c6 * C35
    eq105_from_99 = sp.I * O * C45 + th * c3 * C15 + th * c5 * C25 + th * c6 * C35
    assert sp.simplify(eq105_printed - eq105_from_99) != 0
    M_printed = sp.Matrix([[0, -th * c1, -th * c2, -th * c3], [th * c1, 0, -th * c4, th * c5],
                           [th * c2, th * c4, 0, -th * c6], [th * c3, th * c5, th * c6, 0]])
    assert sp.simplify(M_printed + M_printed.T) != sp.zeros(4, 4)


def test_theta_inverse_eq100():
    """(100): kappa = sqrt(1 - Theta^2)/(1 - Theta); the printed (Theta - 1) gives -kappa."""
    for kappa in (0.3, 0.5, 1.0, 2.0, 7.0):
        th = quartet_theta(kappa)
        assert -1 <= th < 1
        assert np.sqrt(1 - th**2) / (1 - th) == pytest.approx(kappa, rel=1e-14)
        assert np.sqrt(1 - th**2) / (th - 1) == pytest.approx(-kappa, rel=1e-14)
    assert quartet_theta(0.0) == -1.0


def test_characteristic_polynomial_107_to_110():
    """(107)-(109) hold identically; the strict inequalities of (108), (110) fail on explicit cases."""
    th = sp.Symbol("Theta", real=True)
    c = sp.symbols("c1:7", real=True)
    c1, c2, c3, c4, c5, c6 = c
    A = sp.Matrix([[0, c1, c2, c3], [-c1, 0, c4, c5], [-c2, -c4, 0, c6], [-c3, -c5, -c6, 0]])
    O = sp.Symbol("Omega")
    det = sp.expand((sp.I * O * sp.eye(4) - th * A).det())
    l2 = -th**2 * sum(v**2 for v in c)
    l0 = th**4 * (c1 * c6 - c2 * c5 + c3 * c4) ** 2
    assert sp.expand(det - (O**4 + l2 * O**2 + l0)) == 0
    fact = th**4 * ((c5 - c2) ** 2 + (c3 + c4) ** 2 + (c1 + c6) ** 2) * ((c5 + c2) ** 2 + (c3 - c4) ** 2 + (c1 - c6) ** 2)
    assert sp.expand(l2**2 - 4 * l0 - fact) == 0
    # counterexamples: Pfaffian zero -> l0 = 0 and l2^2 = l2^2 - 4 l0; self-dual -> l2^2 - 4 l0 = 0
    pf0 = {c1: 1, c2: 0, c3: 0, c4: 0, c5: 0, c6: 0, th: sp.Rational(1, 3)}
    assert l0.subs(pf0) == 0
    assert (l2**2).subs(pf0) == (l2**2 - 4 * l0).subs(pf0)
    sd = {c1: 1, c6: 1, c3: 2, c4: 2, c2: 3, c5: -3, th: sp.Rational(1, 3)}
    assert (l2**2 - 4 * l0).subs(sd) == 0
    assert l2.subs(th, 0) == 0  # kappa = 1


def test_quartet_frequencies_match_eigenvalues_and_paper_formula():
    rng = np.random.default_rng(1)
    for axis in (1, 2, 3, 4, 5):
        for kappa in (0.2, 0.5, 3.0):
            w0 = rng.normal(size=10)
            f = quartet_frequencies(kappa, w0, axis)
            ev = np.linalg.eigvals(quartet_theta(kappa) * quartet_matrix(w0, axis))
            A = quartet_theta(kappa) * quartet_matrix(w0, axis)
            assert np.max(np.abs(ev.real)) < scaled_tol(A, k=16)  # eigenvalues: backward error ~ n eps ||A||
            np.testing.assert_allclose(np.sort(np.abs(ev.imag)), np.sort(np.repeat(f, 2)), rtol=1e-12, atol=scaled_tol(A, k=16))
            l2, l0 = quartet_polynomial_coefficients(kappa, w0, axis)
            assert l2 <= 0 and l0 >= 0
            D = np.sqrt(l2**2 - 4 * l0)
            # the formula printed after (118)
            np.testing.assert_allclose(0.5 * np.sqrt(2 * D - 2 * l2), f[0], rtol=1e-12)
            np.testing.assert_allclose(0.5 * np.sqrt(max(-2 * D - 2 * l2, 0.0)), f[1], rtol=1e-6, atol=1e-12)
    # self-dual data: both frequencies equal; Pfaffian zero: one frequency vanishes
    w = np.zeros(10)
    w[[0, 1, 2, 4, 5, 7]] = [1.0, 3.0, 2.0, -2.0, 3.0, -1.0]  # c1=-c6, c3=-c4, c2=c5 -> (109) first factor 0
    f = quartet_frequencies(0.5, w)
    assert f[0] == pytest.approx(f[1], rel=1e-14)
    w = np.zeros(10)
    w[0] = 2.0
    assert quartet_frequencies(0.5, w)[1] == 0.0


@pytest.mark.parametrize("axis", [1, 2, 3, 4, 5])
def test_quartet_solution_against_dop853(axis):
    rng = np.random.default_rng(10 + axis)
    kappa = 0.5
    w0 = rng.normal(size=10)
    t = np.linspace(0, 30, 61)
    out = quartet_solution(kappa, w0, t, axis=axis)
    ref = _reference(quartet_moments(kappa, axis), w0, t)
    np.testing.assert_allclose(out, ref, rtol=0, atol=5e-11)
    np.testing.assert_allclose(out[0], w0, rtol=0, atol=scaled_tol(w0))
    sol, kind = closed_form_solution(quartet_moments(kappa, axis), w0, t)
    assert kind == "quartet"
    np.testing.assert_allclose(sol, out, rtol=0, atol=scaled_tol(w0, k=16))


@pytest.mark.parametrize("N,axis", [(3, 1), (3, 3), (4, 2), (6, 1), (6, 4), (7, 7)])
def test_quartet_any_N(N, axis):
    rng = np.random.default_rng(100 * N + axis)
    n = N * (N - 1) // 2
    w0 = rng.normal(size=n)
    t = np.linspace(0, 15, 31)
    kappa = 1.7
    out = quartet_solution(kappa, w0, t, axis=axis)
    np.testing.assert_allclose(out, _reference(quartet_moments(kappa, axis, N), w0, t), atol=5e-11, rtol=0)
    ev = np.linalg.eigvals(quartet_theta(kappa) * quartet_matrix(w0, axis))
    f = quartet_frequencies(kappa, w0, axis)
    assert f.shape == ((N - 1) // 2,)
    top = np.sort(np.abs(ev.imag))[::-1][: 2 * f.size : 2]
    np.testing.assert_allclose(top, f, rtol=1e-12)


def test_quartet_scaled_moments_and_batch():
    """Any common scale of the two moment values (detect_closed_form), and batched omega0."""
    rng = np.random.default_rng(7)
    I = np.array([3.0 if 2 in p else 0.8 for p in planes(5)])
    info = detect_closed_form(I)
    assert info["kind"] == "quartet" and info["axis"] == 2
    assert info["theta"] == pytest.approx(1 - 0.8 / 3.0, rel=1e-15)
    w0 = rng.normal(size=(2, 3, 10))
    t = np.linspace(0, 10, 11)
    sol, kind = closed_form_solution(I, w0, t)
    assert sol.shape == (2, 3, 11, 10)
    np.testing.assert_allclose(sol[1, 2], _reference(I, w0[1, 2], t), atol=5e-11, rtol=0)
    one = quartet_solution(0.5, w0, t, axis=3)
    np.testing.assert_allclose(one[0, 1], quartet_solution(0.5, w0[0, 1], t, axis=3), atol=1e-15, rtol=0)
    assert detect_closed_form(np.arange(1.0, 11.0)) is None
    with pytest.raises(ValueError, match="no closed form"):
        closed_form_solution(np.arange(1.0, 11.0), np.ones(10), t)


def test_quartet_bad_input():
    with pytest.raises(ValueError, match="axis"):
        quartet_solution(0.5, np.ones(10), [0.0, 1.0], axis=6)
    with pytest.raises(ValueError, match="axis"):
        quartet_solution(0.5, np.ones(10), [0.0, 1.0], axis=0)
    with pytest.raises(ValueError, match="N = 5"):
        quartet_solution(0.5, np.ones(10), [0.0, 1.0], N=4)
    with pytest.raises(ValueError, match="N\\(N-1\\)/2"):
        quartet_solution(0.5, np.ones(7), [0.0, 1.0])
    with pytest.raises(ValueError, match="finite"):
        quartet_solution(0.5, [np.nan] + [0.0] * 9, [0.0])


# ----------------------------------------------------------------------------
# 3D Euler-Poinsot
# ----------------------------------------------------------------------------
def _regime(I, w):
    """sign of L^2 - 2 E I_mid (textbook map)."""
    Itb = np.array([I[2], I[1], I[0]])
    Wtb = np.array([w[2], -w[1], w[0]])
    E2 = np.sum(Itb * Wtb**2)
    L2 = np.sum((Itb * Wtb) ** 2)
    return np.sign(L2 - E2 * np.sort(Itb)[1])


ORDERINGS = [np.array(p, float) for p in itertools.permutations([1.0, 2.0, 3.5])]


@pytest.mark.parametrize("I", ORDERINGS, ids=lambda I: "I=" + ",".join(f"{v:g}" for v in I))
def test_euler_poinsot_both_regimes_many_periods(I):
    rng = np.random.default_rng(int(I @ [1, 10, 100]))
    seen = set()
    for _ in range(60):
        w0 = rng.normal(size=3)
        reg = _regime(I, w0)
        if reg in seen:
            continue
        seen.add(reg)
        T = euler_poinsot_period(I, w0)
        t = np.linspace(0, 8 * T, 161)
        out = euler_poinsot(I, w0, t)
        scale = np.max(np.abs(w0))
        np.testing.assert_allclose(out[0], w0, rtol=0, atol=1e-14 * scale)  # phase and sign at t = 0
        np.testing.assert_allclose(out[-1], w0, rtol=0, atol=1e-12 * scale)  # periodicity
        np.testing.assert_allclose(out, _reference(I, w0, t), rtol=0, atol=2e-10 * scale)
        if len(seen) == 2:
            break
    assert seen == {1.0, -1.0}


def _mp_euler_poinsot(I, w0, t, dps=40, period=False):
    """Same formulas at 40 digits (``dps``) with mpmath, textbook map, I sorted ascending, regime by sign (and the
    period 4 K(m) / nu with ``period``)."""
    mpmath.mp.dps = dps
    Itb = [mpmath.mpf(I[2]), mpmath.mpf(I[1]), mpmath.mpf(I[0])]
    W = [mpmath.mpf(w0[2]), -mpmath.mpf(w0[1]), mpmath.mpf(w0[0])]
    assert Itb[0] < Itb[1] < Itb[2]
    I1, I2, I3 = Itb
    E2 = sum(i * x**2 for i, x in zip(Itb, W))
    L2 = sum((i * x) ** 2 for i, x in zip(Itb, W))
    assert L2 > E2 * I2  # the regime with W3 = dn (Landau & Lifshitz, Mechanics, Sec. 37)
    A = mpmath.sqrt((E2 * I3 - L2) / (I1 * (I3 - I1)))
    B = mpmath.sqrt((E2 * I3 - L2) / (I2 * (I3 - I2)))
    C = mpmath.sqrt((L2 - E2 * I1) / (I3 * (I3 - I1)))
    nu = mpmath.sqrt((I3 - I2) * (L2 - E2 * I1) / (I1 * I2 * I3))
    m = (I2 - I1) * (E2 * I3 - L2) / ((I3 - I2) * (L2 - E2 * I1))
    s3 = mpmath.sign(W[2])
    s1 = mpmath.sign(W[0] * s3)
    # (W1, W2, W3) = (s1 s3 A cn, s1 B sn, s3 C dn)
    u0 = mpmath.ellipf(mpmath.atan2(s1 * W[1] / B, s1 * s3 * W[0] / A), m)
    out = []
    for tk in t:
        u = u0 + nu * mpmath.mpf(tk)
        cn, sn, dn = (mpmath.ellipfun(k, u, m=m) for k in ("cn", "sn", "dn"))
        Wt = [s1 * s3 * A * cn, s1 * B * sn, s3 * C * dn]
        out.append([float(Wt[2]), float(-Wt[1]), float(Wt[0])])
    return (np.array(out), float(4 * mpmath.ellipk(m) / nu)) if period else np.array(out)


def test_euler_poinsot_against_mpmath_1e13():
    I = np.array([3.5, 2.0, 1.0])  # I_12 > I_13 > I_23, i.e. textbook I1 < I2 < I3
    rng = np.random.default_rng(3)
    done = 0
    while done < 3:
        w0 = rng.normal(size=3)
        if _regime(I, w0) < 0:
            continue
        T = euler_poinsot_period(I, w0)
        t = np.linspace(0, 5 * T, 23)
        ref = _mp_euler_poinsot(I, w0, t)
        scale = np.max(np.abs(w0))
        np.testing.assert_allclose(euler_poinsot(I, w0, t), ref, rtol=0, atol=2e-13 * scale)
        done += 1


@pytest.mark.parametrize("tilt", [1e-4, 1e-8, 1e-12, 1e-16])
def test_euler_poinsot_close_to_the_separatrix_against_mpmath(tilt):
    """A spin about the middle axis tilted by ``tilt`` (the tennis-racket flip): 1 - m ~ tilt^2 was carried by the
    float m with an absolute error eps (the period 0.5% off at 1e-8; at 1e-10 m = 1, a constant omega while the body
    flips) and u0 = F(atan2(...)) lost cos(phi0) ~ tilt to the rounded angle. Now 1 - m exact, K = ellipkm1,
    u0 from the components (Carlson R_F), sn/cn/dn from 1 - m: omega within 2e-13 over three periods and the
    period within 1e-13 of mpmath at 60 digits."""
    I = np.array([3.0, 2.0, 1.0])  # textbook I1 = 1 < I2 = 2 < I3 = 3
    w0 = np.array([tilt, -1.0, tilt])  # (W1, W2, W3) = (tilt, 1, tilt): L^2 - 2 E I2 = 2 tilt^2 > 0
    T = euler_poinsot_period(I, w0)
    t = np.linspace(0.0, 3 * T, 25)
    ref, T_ref = _mp_euler_poinsot(I, w0, t, dps=60, period=True)
    assert T == pytest.approx(T_ref, rel=1e-13)
    np.testing.assert_allclose(euler_poinsot(I, w0, t), ref, rtol=0, atol=2e-13)
    assert np.ptp(ref[:, 1]) > 1.9  # (the middle-axis component flips sign: -1 -> +1)


def test_euler_poinsot_flips_for_a_subnormal_distance_to_the_separatrix():
    """Tilt 1e-160: 1 - m ~ 1e-320 (subnormal) and F(pi/2 | m) = K = ellipkm1(1 - m), finite (R_F(0, 1 - m, 1)
    overflowed: a constant omega although the period is finite); half a period later w13 has flipped."""
    I, w0 = np.array([3.0, 2.0, 1.0]), np.array([1e-160, -1.0, 0.0])
    T = euler_poinsot_period(I, w0)
    assert np.isfinite(T)
    half = euler_poinsot(I, w0, [0.5 * T])[0]
    assert half[1] == pytest.approx(1.0, abs=1e-12) and abs(half[0]) < 1e-150 and abs(half[2]) < 1e-150


def test_euler_poinsot_separatrix_and_steady():
    # textbook I = (1, 2, 3): separatrix when 3 * 1 * W3^2 = 1 * 1 * W1^2 (L^2 = 2 E I2)
    I = np.array([3.0, 2.0, 1.0])  # (I12, I13, I23) -> I1=1, I2=2, I3=3
    W = np.array([np.sqrt(3.0), 0.3, 1.0])  # (W1, W2, W3)
    w0 = np.array([W[2], -W[1], W[0]])
    assert euler_poinsot_period(I, w0) > 50  # (numerically) on the separatrix
    t = np.linspace(0, 6, 31)
    out = euler_poinsot(I, w0, t)
    np.testing.assert_allclose(out, _reference(I, w0, t), atol=1e-10, rtol=0)
    # asymptotically the unstable middle-axis rotation: w13 -> -B (W2 -> +B), w12, w23 -> 0
    # B^2 = (2 E I3 - L^2) / (I2 (I3 - I2)), textbook I1 = I[2], I2 = I[1], I3 = I[0]
    B = np.sqrt((I[2] * (I[0] - I[2]) * W[0] ** 2 + I[1] * (I[0] - I[1]) * W[1] ** 2) / (I[1] * (I[0] - I[1])))
    late = euler_poinsot(I, w0, [20.0])[0]  # sech(20) ~ 4e-9; the rounded input leaves the separatrix only later
    np.testing.assert_allclose(late, [0.0, -B, 0.0], atol=1e-7, rtol=0)
    # the double-precision input lies within 1 ulp of the separatrix: compare with mpmath-free tanh/sech
    nu = np.sqrt((I[0] - I[1]) * (I[1] * (I[1] - I[2]) * W[1] ** 2 + I[0] * (I[0] - I[2]) * W[2] ** 2) / np.prod(I))
    A = np.sqrt(W[0] ** 2 + I[1] * (I[0] - I[1]) / (I[2] * (I[0] - I[2])) * W[1] ** 2)
    C = np.sqrt(I[1] * (I[1] - I[2]) / (I[0] * (I[0] - I[2])) * W[1] ** 2 + W[2] ** 2)
    u0 = np.arctanh(W[1] / B)
    tt = np.linspace(0, 8, 17)
    sep = np.stack([C / np.cosh(u0 + nu * tt), -B * np.tanh(u0 + nu * tt), A / np.cosh(u0 + nu * tt)], axis=-1)
    np.testing.assert_allclose(euler_poinsot(I, w0, tt), sep, atol=1e-12, rtol=0)
    # steady rotations about each principal axis and rest stay constant
    for k in range(3):
        e = np.zeros(3)
        e[k] = 1.3
        np.testing.assert_array_equal(euler_poinsot(I, e, t), np.broadcast_to(e, (31, 3)))
    np.testing.assert_array_equal(euler_poinsot(I, np.zeros(3), t), 0.0)


@pytest.mark.parametrize("I", [np.array([3.0, 1.0, 1.0]), np.array([1.0, 3.0, 3.0]), np.array([2.0, 2.0, 2.0])])
def test_euler_poinsot_symmetric_top(I):
    """Two equal moments: the odd axis component is constant, the other two rotate uniformly."""
    w0 = np.array([0.7, -0.4, 1.1])
    t = np.linspace(0, 20, 41)
    out = euler_poinsot(I, w0, t)
    np.testing.assert_allclose(out, _reference(I, w0, t), atol=1e-11, rtol=0)
    if np.ptp(I) == 0:
        np.testing.assert_array_equal(out, np.broadcast_to(w0, out.shape))
        return
    odd = int(np.argmax(np.array([np.sum(I == v) for v in I]) == 1))
    np.testing.assert_allclose(out[:, odd], w0[odd], rtol=0, atol=scaled_tol(w0))
    # the explicit rotation: for I12 = I3 odd (w12 = W3 constant), W1' = -lam W2, W2' = lam W1
    if odd == 0:
        I1, I3 = I[2], I[0]
        lam = (I3 - I1) * w0[0] / I1
        W1 = w0[2] * np.cos(lam * t) - (-w0[1]) * np.sin(lam * t)
        W2 = -w0[1] * np.cos(lam * t) + w0[2] * np.sin(lam * t)
        np.testing.assert_allclose(out[:, 2], W1, atol=1e-13, rtol=0)
        np.testing.assert_allclose(-out[:, 1], W2, atol=1e-13, rtol=0)


def test_euler_poinsot_initial_signs_all_octants():
    rng = np.random.default_rng(11)
    for I in ORDERINGS:
        for signs in itertools.product((-1.0, 1.0), repeat=3):
            w0 = np.array(signs) * np.abs(rng.normal(size=3))
            t = np.array([0.0, 0.37, 1.1])
            out = euler_poinsot(I, w0, t)
            np.testing.assert_allclose(out[0], w0, rtol=0, atol=1e-15 * np.max(np.abs(w0)) * 4)
            np.testing.assert_allclose(out, _reference(I, w0, t), atol=1e-12, rtol=0)


def test_euler_poinsot_bad_input():
    with pytest.raises(ValueError, match="3 plane moments"):
        euler_poinsot(np.ones(6), np.ones(3), [0.0])
    with pytest.raises(ValueError, match="3 plane components"):
        euler_poinsot(np.ones(3) * [1, 2, 3], np.ones(4), [0.0])
    with pytest.raises(ValueError, match="> 0"):
        euler_poinsot([1.0, -2.0, 3.0], np.ones(3), [0.0])
    with pytest.raises(TypeError):
        euler_poinsot(object(), np.ones(3), [0.0])


@pytest.mark.parametrize("moment_scale, omega_scale", [(1e-310, 1.0), (1e300, 1.0), (1.0, 1e-200), (1.0, 1e150),
                                                       (2.0**1021, 1.0), (1.0, 1e308)])
def test_euler_poinsot_extreme_scales(moment_scale, omega_scale):
    """The motion is unchanged by I -> c I and is w(t) = s w~(s t) for w0 -> s w0: tiny or huge scales
    (moments of 1e-310 gave NaN, #21) give the unit-scale solution, to the precision of the input. Values of
    2^1023 and more (I_max = 2^1023, |omega| = 1e308) were divided by 2^1024 = inf: zero moments, a frozen motion."""
    I, w0 = np.array([2.0, 3.0, 4.0]), np.array([0.6, 1.0, -0.5])
    t = np.linspace(0.0, 10.0, 7)
    ref = euler_poinsot(I, w0, t)
    got = euler_poinsot(I * moment_scale, w0 * omega_scale, t / omega_scale) / omega_scale
    # subnormal moments keep only ~52 - (1074 - 1030) bits: the ratios I_a / I_b are that precise
    rel = 2.0**-40 if moment_scale < 1e-300 else 1e-14
    np.testing.assert_allclose(got, ref, rtol=0, atol=scaled_tol(1.0, k=64) + 64 * rel)
    period = euler_poinsot_period(I * moment_scale, w0 * omega_scale) * omega_scale
    assert period == pytest.approx(euler_poinsot_period(I, w0), rel=64 * rel)


@pytest.mark.parametrize("big, other, axis", [(1e308, 1e-300, 0), (1e300, 1e-300, 0), (1e300, 1e-300, 2)])
def test_euler_poinsot_period_of_components_that_underflow_when_scaled(big, other, axis):
    """omega0 = (1e308, 1e-300, 1e-300): the small components underflow in the scaled frame (a ratio beyond the
    floats), which read it as a steady rotation and gave inf; about an extreme axis the period is the limit of small
    oscillations, the period of the same body at a small tilt divided by the scale."""
    w, ref = np.full(3, other), np.full(3, 1e-10)
    w[axis], ref[axis] = big, 1.0
    I = [1.0, 2.0, 3.0]
    assert euler_poinsot_period(I, w) == pytest.approx(euler_poinsot_period(I, ref) / big, rel=1e-14)
    assert euler_poinsot_period(I, np.where(np.arange(3) == 1, big, other)) == np.inf  # (the middle axis)
    assert euler_poinsot_period(I, np.where(np.arange(3) == axis, big, 0.0)) == np.inf  # (exactly steady)


@pytest.mark.parametrize("convention,axis,N", [("paper", 5, 5), ("standard", 2, 5), ("paper", 1, 4), ("standard", 6, 6)])
def test_quartet_attitude_against_simulate(convention, axis, N):
    """T(t) = exp(Theta W_r t) exp((W0 - Theta W_r) t) T0 solves dT/dt = W(t) T."""
    import hyperrotor
    from hyperrotor.classical import quartet_attitude

    rng = np.random.default_rng(axis + 10 * N)
    n = N * (N - 1) // 2
    w0 = rng.normal(size=n)
    Q, _ = np.linalg.qr(rng.normal(size=(N, N)))
    t = np.linspace(0.0, 10.0, 21)
    body = hyperrotor.RigidBody(quartet_moments(0.5, axis, N), convention=convention)
    ref = hyperrotor.simulate(body, w0, t, method="DOP853", rtol=1e-12, attitude=Q).attitude
    T = quartet_attitude(0.5, w0, t, axis, attitude0=Q, convention=convention)
    np.testing.assert_allclose(T, ref, atol=1e-10, rtol=0)
    np.testing.assert_allclose(np.einsum("kji,kjl->kil", T, T), np.broadcast_to(np.eye(N), T.shape), rtol=0, atol=scaled_tol(T, k=16))
    # equal moments (kappa = 1, Theta = 0): T = expm(W0 t)
    from scipy.linalg import expm

    W0 = body.matrix(w0)
    np.testing.assert_allclose(quartet_attitude(1.0, w0, t[:3], axis, convention=convention)[2], expm(W0 * t[2]), rtol=0,
                               atol=scaled_tol(np.linalg.norm(W0) * t[2], dim=N, k=32))  # two eigen/Pade routes


def test_quartet_attitude0_is_checked_like_simulates_attitude():
    """attitude0 was np.asarray(..., float): text parsed, a non-orthogonal matrix and NaN accepted, complex cut."""
    from hyperrotor.classical import quartet_attitude

    w0 = np.arange(1, 11) * 0.1
    for bad, exc, msg in ((np.ones((5, 5)), ValueError, r"attitude0 must be orthogonal \(max\|T\^T T - 1\| = 5\)"),
                          ([["1"] * 5] * 5, TypeError, "attitude0 must be numeric, got text"),
                          (np.eye(5) * 1j, TypeError, "attitude0 must be real"),
                          (np.full((5, 5), np.nan), ValueError, "attitude0 must be finite"),
                          (np.eye(4), ValueError, r"attitude0 must have shape \(5, 5\)")):
        with pytest.raises(exc, match=msg):
            quartet_attitude(2.0, w0, [0.0, 1.0], attitude0=bad)


def test_detect_closed_form_tolerance_is_an_option():
    """rtol=None reads hr.options["closed_form_rtol"]: moments 1e-12 apart are a quartet only when it allows."""
    import hyperrotor as hr

    I = np.array(hr.Inertia.quartet(0.5, axis=4, N=4).moments)
    I[0] *= 1 + 1e-12
    assert detect_closed_form(I) is None
    with hr.options(closed_form_rtol=1e-11):
        assert detect_closed_form(I)["kind"] == "quartet"
    assert detect_closed_form(I, rtol=1e-11)["kind"] == "quartet"


def test_quartet_frequencies_priced_and_quartet_matrix_vectorised():
    """quartet_matrix (vectorised) equals its definition A_rc = s_r s_c w_(others[r], others[c]);
    quartet_frequencies is priced as (N-1)-dimensional eigenproblems (model 'quartet_frequencies')."""
    import hyperrotor as hr

    N, axis = 7, 3
    w = np.random.default_rng(3).normal(size=(2, N * (N - 1) // 2))
    A = quartet_matrix(w, axis)
    others = [i for i in range(1, N + 1) if i != axis]
    for r, i in enumerate(others):
        for c, j in enumerate(others):
            expected = (1 if i < axis else -1) * (1 if j < axis else -1) * (
                w[:, plane_index((min(i, j), max(i, j)), N)] * (1 if i < j else -1)) if i != j else 0.0
            np.testing.assert_array_equal(A[:, r, c], expected)
    with hr.options(max_seconds=1e-8):  # 2 eigenproblems of dimension 6: ~2e-7 s estimated
        with pytest.raises(hr.BudgetError, match="quartet_frequencies"):
            quartet_frequencies(0.5, w, axis)


def test_the_quartet_closed_forms_are_priced_and_bounded_in_dimension():
    """The eigendecompositions behind quartet_solution, quartet_attitude and closed_form_solution (dimension
    N - 1, N, N - 1) are priced against max_seconds before they run, and N is held to max_dimension like every
    so(N) constructor (N = 3000 ran 33 s unpriced under max_seconds = 0.01); small cases are untouched."""
    import hyperrotor as hr
    from hyperrotor import _pricing
    from hyperrotor.classical import closed_form_solution, quartet_attitude, quartet_frequencies

    N = 60
    w = np.random.default_rng(0).normal(size=N * (N - 1) // 2)
    need = _pricing.estimate("quartet_solution", d=N - 1)[1].amount
    body = hr.Inertia.quartet(0.5, N=N)
    with hr.options(max_seconds=0.5 * need):
        with pytest.raises(hr.BudgetError, match=r"quartet_solution: 1 Hermitian eigenproblem\(s\) of dimension 59"):
            quartet_solution(0.5, w, [0.0, 1.0])
        with pytest.raises(hr.BudgetError,
                           match=r"quartet_attitude: 2 Hermitian eigenproblem\(s\) of dimension 60 "
                                 r"and exp\(W t\) at 2 times"):
            quartet_attitude(0.5, w, [0.0, 1.0])
        with pytest.raises(hr.BudgetError, match=r"closed_form_solution: .* dimension 59"):
            closed_form_solution(body, w, [0.0, 1.0])
    with hr.options(max_dimension=N - 1):
        for f in (quartet_solution, quartet_attitude):
            with pytest.raises(hr.BudgetError, match=r"max_dimension"):
                f(0.5, w, [0.0, 1.0])
        with pytest.raises(hr.BudgetError, match=r"max_dimension"):
            quartet_frequencies(0.5, w)
    # within the budgets: the closed form and the dispatcher agree, and the flow conserves |x|
    a = quartet_solution(0.5, w, [0.0, 1.0, 2.0])
    b, kind = closed_form_solution(body, w, [0.0, 1.0, 2.0])
    assert kind == "quartet"
    np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * np.abs(w).max() * N)
    np.testing.assert_allclose(np.linalg.norm(a, axis=-1), np.linalg.norm(w), rtol=1e-12 * N)


def test_quartet_attitude_prices_the_matrices_at_every_time():
    """exp(W t) at n_t times is n_t N x N matrices (peak 498 MiB for N = 60 and 3000 times, of which the model
    counted 1 MiB): refused under a memory budget that peak exceeds, built under one it does not."""
    import hyperrotor as hr
    from hyperrotor.classical import quartet_attitude

    N = 60
    w = np.random.default_rng(1).normal(size=N * (N - 1) // 2)
    with hr.options(max_memory_bytes=300 * 2**20):
        with pytest.raises(hr.BudgetError, match="quartet_attitude: .* at 3000 times"):
            quartet_attitude(0.5, w, np.linspace(0.0, 1.0, 3000))
        assert quartet_attitude(0.5, w, np.linspace(0.0, 1.0, 300)).shape == (300, N, N)
