"""Tests of hyperrotor.RigidBody: Euler equations, conventions, invariants, locking."""
import itertools

import numpy as np
import pytest
import sympy as sp

import hyperrotor as hr
from hyperrotor import Inertia, RigidBody
from hyperrotor.classical.rigid_body import TIME, _manakov_traces
from tolerance import assert_close, norm, scaled_tol


def _S(N):
    return np.diag([(-1) ** i for i in range(1, N + 1)])


def _random_body(rng, N, convention="paper"):
    return RigidBody(Inertia.from_planes(rng.uniform(0.5, 2.0, hr.n_planes(N))), convention=convention)


def _dt(F, body):
    """d/dt F(omega) = sum_a dF/dw_a * w_a' along the torque-free flow, expanded.

    Written as sum_a (dF/dw_a / I_a) * (I_a w_a'): both factors are polynomials
    (cancel divides exactly), so the result is a polynomial that is 0 iff F is conserved.
    """
    w = body.omega_symbols()
    r = body.symbolic_rhs()
    total = 0
    for wa, ra, Ia in zip(w, r, body.inertia.symbolic_moments):
        total += sp.cancel(sp.diff(F, wa) / Ia) * sp.cancel(Ia * ra)
    return sp.expand(total)


# ---------------------------------------------------------------- equations of motion
@pytest.mark.parametrize("N", [2, 3, 4, 5, 6])
@pytest.mark.parametrize("convention", ["paper", "standard"])
def test_rhs_is_matrix_commutator(rng, N, convention):
    """I w' = components of (W L - L W) with the matrices of the convention (eq. 24)."""
    body = _random_body(rng, N, convention)
    w = rng.standard_normal(hr.n_planes(N))
    W = hr.to_matrix(w, convention=convention)
    L = hr.to_matrix(body.inertia.moments * w, convention=convention)
    expected = hr.to_components(W @ L - L @ W, convention=convention) / body.inertia.moments
    # a commutator of N x N matrices of sizes |w| and |L|, divided by the moments
    np.testing.assert_allclose(body.rhs(w), expected, rtol=0, atol=scaled_tol(norm(W) * norm(L) / body.inertia.moments.min(), dim=N, k=8))


def test_rhs_components_identical_in_both_conventions(rng):
    I = Inertia.from_planes(rng.uniform(0.5, 2.0, 10))
    w = rng.standard_normal((7, 10))
    m = rng.standard_normal(10)
    a = RigidBody(I, convention="paper").rhs(w, m)
    b = RigidBody(I, convention="standard").rhs(w, m)
    np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("N", [3, 4, 5])
def test_paper_matrix_is_sign_conjugate_of_standard(rng, N):
    L = rng.standard_normal(hr.n_planes(N))
    S = _S(N)
    np.testing.assert_array_equal(hr.to_matrix(L, convention="paper"), S @ hr.to_matrix(L, convention="standard") @ S)
    body_p = _random_body(rng, N, "paper")
    body_s = RigidBody(body_p.inertia, convention="standard")
    np.testing.assert_array_equal(body_p.matrix(L), S @ body_s.matrix(L) @ S)
    np.testing.assert_array_equal(body_p.matrix(L), hr.to_matrix(L, convention="paper"))


def test_component_example_from_brief():
    body = RigidBody(Inertia.symbolic(5), convention="standard")
    I = dict(zip(hr.planes(5), body.inertia.symbolic_moments))
    w = dict(zip(hr.planes(5), body.omega_symbols()))
    expected = ((I[1, 3] - I[2, 3]) * w[1, 3] * w[2, 3] + (I[1, 4] - I[2, 4]) * w[1, 4] * w[2, 4]
                + (I[1, 5] - I[2, 5]) * w[1, 5] * w[2, 5]) / I[1, 2]
    assert sp.simplify(body.symbolic_rhs()[0] - expected) == 0


@pytest.mark.parametrize("N", [3, 4, 5])
def test_rhs_matches_symbolic_rhs(rng, N):
    body = _random_body(rng, N)
    w = rng.standard_normal(hr.n_planes(N))
    m = rng.standard_normal(hr.n_planes(N))
    sym = body.symbolic_rhs(torque=list(m))
    vals = [float(e.subs(dict(zip(body.omega_symbols(), w)))) for e in sym]
    np.testing.assert_allclose(body.rhs(w, m), vals, rtol=1e-12, atol=1e-14)


def test_rhs_vectorized_over_leading_axes(rng):
    body = _random_body(rng, 5)
    w = rng.standard_normal((3, 4, 10))
    m = rng.standard_normal(10)
    out = body.rhs(w, m)
    assert out.shape == (3, 4, 10)
    for i, j in itertools.product(range(3), range(4)):
        np.testing.assert_allclose(out[i, j], body.rhs(w[i, j], m), rtol=1e-15)


def test_rhs_bad_input(rng):
    body = _random_body(rng, 4)
    with pytest.raises(ValueError, match="6 plane components"):
        body.rhs(np.zeros(10))
    with pytest.raises(ValueError, match="6 plane components"):
        body.rhs(np.zeros(6), np.zeros(5))
    with pytest.raises(TypeError, match="numeric"):
        body.rhs(["a"] * 6)
    with pytest.raises(TypeError, match="numeric moments"):
        RigidBody(Inertia.symbolic(3)).rhs(np.zeros(3))


def test_constructor_inputs():
    assert RigidBody([1.0, 2.0, 3.0]).N == 3
    assert RigidBody({(1, 2): 1.0}).N == 2
    with pytest.raises(ValueError, match="unknown convention"):
        RigidBody(Inertia.equal(3), convention="checkerboard")
    with pytest.raises(TypeError, match="Inertia"):
        RigidBody(3.0)


# ---------------------------------------------------------------- euler_equations
def test_euler_equations_paper_form_signs():
    body = RigidBody(Inertia.symbolic(4))
    eqs = body.euler_equations()
    rhs = body.symbolic_rhs(omega=body.omega_symbols(function_of=TIME))
    for (i, j), eq, r, I, w, mt in zip(body.planes, eqs, rhs, body.inertia.symbolic_moments,
                                       body.omega_symbols(function_of=TIME), body.torque_symbols()):
        assert str(mt) == f"mtilde_{i}{j}"
        assert eq.rhs == mt
        # sign_ij * (I w' - I * (w' from the solved form)) with sign_ij = (-1)^(i+j)
        assert sp.simplify(eq.lhs - (-1) ** (i + j) * (I * sp.Derivative(w, TIME) - I * r)) == 0


def test_euler_equations_standard_form_and_torques():
    body = RigidBody(Inertia.symbolic(3), convention="standard")
    m = sp.symbols("a b c")
    eqs = body.euler_equations(torque=m)
    rhs = body.symbolic_rhs(omega=body.omega_symbols(function_of=TIME))
    for eq, r, I, w, mm in zip(eqs, rhs, body.inertia.symbolic_moments, body.omega_symbols(function_of=TIME), m):
        assert eq.rhs == mm
        assert sp.simplify(eq.lhs - (I * sp.Derivative(w, TIME) - I * r)) == 0
    assert [str(e.rhs) for e in body.euler_equations()] == ["m_12", "m_13", "m_23"]
    assert all(e.rhs == 0 for e in body.euler_equations(0))
    # paper convention: a component torque m appears as the matrix entry (-1)^(i+j) m
    paper = RigidBody(Inertia.symbolic(3)).euler_equations(torque=m)
    assert [e.rhs for e in paper] == [-m[0], m[1], -m[2]]
    with pytest.raises(ValueError, match="3 components"):
        body.euler_equations(torque=[1, 2])


def test_euler_equations_numeric_inertia_are_exact():
    eqs = RigidBody(Inertia.quartet(sp.Rational(1, 2))).euler_equations(0)
    w = hr.plane_symbols("omega", 5, function_of=TIME)
    # (89)-type check: the (1,5) equation of the quartet body is
    # 5/4 w15' + (3/4)(w12 w25 + w13 w35 + w14 w45) = 0 (paper sign +1 for plane 15)
    expected = sp.Rational(5, 4) * sp.Derivative(w[3], TIME) + sp.Rational(3, 4) * (
        w[0] * w[6] + w[1] * w[8] + w[2] * w[9])
    assert sp.expand(eqs[3].lhs - expected) == 0


# ---------------------------------------------------------------- invariants
@pytest.mark.parametrize("N", [3, 4, 5])
def test_energy_and_casimirs_conserved_symbolically(N):
    body = RigidBody(Inertia.symbolic(N))
    w = body.omega_symbols()
    assert _dt(body.energy(w), body) == 0
    cas = body.casimirs(w)
    assert len(cas) == N // 2
    for c in cas:
        assert _dt(c, body) == 0


def test_energy_is_not_a_casimir():
    """The paper (after eq. 38) calls k_3 the energy; it is sum L^2, not 1/2 sum I w^2."""
    body = RigidBody(Inertia.symbolic(5))
    w = body.omega_symbols()
    c2 = body.casimirs(w)[0]
    L = body.angular_momentum(w)
    assert sp.expand(c2 - sum(x**2 for x in L)) == 0
    assert sp.expand(c2 - 2 * body.energy(w)) != 0


@pytest.mark.parametrize("N", [3, 4, 5, 6])
def test_casimirs_are_charpoly_coefficients(rng, N):
    body = _random_body(rng, N)
    w = rng.standard_normal((4, hr.n_planes(N)))
    c = body.casimirs(w)
    assert c.shape == (4, N // 2)
    for k in range(4):
        poly = np.poly(body.matrix(body.angular_momentum(w[k])))  # det(lambda - L), both conventions
        np.testing.assert_allclose(poly[1::2], 0, atol=1e-10, rtol=0)
        np.testing.assert_allclose(c[k], poly[2::2], rtol=1e-10)
    np.testing.assert_allclose(body.casimirs(body.angular_momentum(w), of="L"), c, rtol=1e-14)
    # symbolic evaluation agrees
    sym = body.casimirs([sp.Float(x) for x in w[0]])
    np.testing.assert_allclose([float(s) for s in sym], c[0], rtol=1e-10)
    with pytest.raises(ValueError, match="of must be"):
        body.casimirs(w, of="Omega")


@pytest.mark.parametrize("N", [3, 4])
def test_manakov_integrals_conserved_symbolically(N):
    J = sp.symbols(f"J1:{N + 1}", positive=True)
    lam = sp.Symbol("lambda")
    body = RigidBody(Inertia.from_mass_tensor(J))
    w = body.omega_symbols()
    for F in body.manakov_integrals(w, lam):
        assert _dt(F, body) == 0


@pytest.mark.parametrize("N", [3, 4, 5])
def test_manakov_integrals_conserved_symbolically_L_form(N):
    """Same check with the gradient in L: sum_a dF/dL_a * dL_a/dt (all polynomial, faster)."""
    J = sp.symbols(f"J1:{N + 1}", positive=True)
    lam = sp.Symbol("lambda")
    body = RigidBody(Inertia.from_mass_tensor(J))
    w, I = body.omega_symbols(), body.inertia.symbolic_moments
    Ls = hr.plane_symbols("L", N)
    Ldot = [sp.cancel(Ia * ra) for Ia, ra in zip(I, body.symbolic_rhs())]  # I_a w_a' (polynomial)
    on_shell = {L: Ia * wa for L, Ia, wa in zip(Ls, I, w)}
    Fs = body.manakov_integrals(Ls, lam, of="L")
    assert len(Fs) == N - 1
    for F in Fs:
        assert sp.expand(sum(sp.diff(F, L).subs(on_shell) * ld for L, ld in zip(Ls, Ldot))) == 0


def test_manakov_not_conserved_for_generic_inertia(rng):
    body = RigidBody(Inertia.symbolic(4))
    with pytest.raises(ValueError, match="mass-tensor"):
        body.manakov_integrals(np.ones(6))
    # with any J, tr((L + J^2)^3) drifts for a generic (non J_i + J_j) inertia
    J = sp.symbols("J1:5", positive=True)
    w = body.omega_symbols()
    F = _manakov_traces(list(body.angular_momentum(w)), J, 1)[1]
    dF = _dt(F, body)
    point = {s: sp.Rational(int(v), 7) for s, v in zip(
        [*w, *J, *body.inertia.symbolic_moments], rng.integers(1, 20, 6 + 4 + 6))}
    assert dF.subs(point) != 0


def test_manakov_numeric_matches_symbolic(rng):
    body = RigidBody(Inertia.quartet(0.5))
    w = rng.standard_normal(10)
    num = body.manakov_integrals(w, 0.3)
    sym = body.manakov_integrals([sp.Float(x) for x in w], sp.Float(0.3))
    np.testing.assert_allclose(num, [float(s) for s in sym], rtol=1e-10)
    assert num.shape == (4,)
    # same in the standard convention
    np.testing.assert_allclose(RigidBody(body.inertia, convention="standard").manakov_integrals(w, 0.3), num, rtol=1e-14)


def test_energy_and_momentum_numeric(rng):
    body = _random_body(rng, 4)
    w = rng.standard_normal((5, 6))
    np.testing.assert_array_equal(body.angular_momentum(w), w * body.inertia.moments)
    assert_close(body.energy(w), 0.5 * np.sum(body.inertia.moments * w**2, axis=-1), dim=6)


# ---------------------------------------------------------------- lock
@pytest.mark.parametrize("N", [4, 5])
def test_lock_frozen_set_is_invariant_and_reduced_flow_matches(N):
    full = RigidBody(Inertia.symbolic(N))
    w = full.omega_symbols()
    rhs = full.symbolic_rhs()
    for r in range(1, N - 1):
        for locked in itertools.combinations(range(1, N + 1), r):
            frozen = {wa: 0 for wa, p in zip(w, full.planes) if set(p) & set(locked)}
            reduced = full.lock(locked)
            assert reduced.locked_axes == locked
            assert reduced.axes == tuple(a for a in range(1, N + 1) if a not in locked)
            red_rhs = dict(zip(reduced.planes, reduced.symbolic_rhs()))
            for wa, p, ra in zip(w, full.planes, rhs):
                val = sp.simplify(ra.subs(frozen))
                if wa in frozen:
                    assert val == 0, (locked, p)  # invariant subspace
                else:
                    assert sp.simplify(val - red_rhs[p]) == 0, (locked, p)


def test_lock_keeps_original_labels_and_signs():
    red = RigidBody(Inertia.symbolic(5)).lock(2)
    assert red.N == 4 and red.axes == (1, 3, 4, 5)
    assert red.planes == ((1, 3), (1, 4), (1, 5), (3, 4), (3, 5), (4, 5))
    assert [str(s) for s in red.inertia.symbolic_moments] == ["I_13", "I_14", "I_15", "I_34", "I_35", "I_45"]
    eqs = red.euler_equations()
    assert [str(e.rhs) for e in eqs] == ["mtilde_13", "mtilde_14", "mtilde_15", "mtilde_34", "mtilde_35", "mtilde_45"]
    # sign of the derivative term is (-1)^(i+j) with the ORIGINAL labels: + for 13, - for 14, ...
    for e, (i, j), I in zip(eqs, red.planes, red.inertia.symbolic_moments):
        d = [a for a in e.lhs.atoms(sp.Derivative)][0]
        assert e.lhs.coeff(d) == (-1) ** (i + j) * I
    # successive locks compose
    assert red.lock(5).axes == (1, 3, 4) and red.lock(5).locked_axes == (2, 5)
    # the matrix of the reduced body uses the original checkerboard
    L = np.arange(1.0, 7.0)
    M = red.matrix(L)
    assert M[0, 1] == L[0] and M[0, 2] == -L[1]  # entries (1,3) -> +, (1,4) -> -


def test_lock_errors():
    body = RigidBody(Inertia.equal(4))
    with pytest.raises(ValueError, match="at least two"):
        body.lock([1, 2, 3, 4])
    with pytest.raises(ValueError, match="at least two"):
        body.lock([1, 2, 3])
    with pytest.raises(ValueError, match="cannot lock axis 5"):
        body.lock(5)
    with pytest.raises(ValueError, match="cannot lock axis 1"):
        body.lock(1).lock(1)
    with pytest.raises(TypeError, match="cannot lock axis True: axis labels are integers"):
        body.lock([True])
    # text is not a sequence of axis labels (its characters were read as axes: a ValueError about '1')
    with pytest.raises(TypeError, match="axes must be an axis label or an iterable of them, got '12'"):
        body.lock("12")
    with pytest.raises(TypeError, match="axes must be a sequence of 4 increasing positive integers, got '1234'"):
        RigidBody(Inertia.equal(4), axes="1234")


def test_lock_keeps_mass_tensor():
    red = RigidBody(Inertia.quartet(0.5)).lock(3)
    np.testing.assert_array_equal(red.inertia.mass_tensor, [1, 1, 1, 0.25])
    assert red.manakov_integrals(np.ones(6)).shape == (3,)


# ---------------------------------------------------------------- 3D textbook
def _textbook_check(body3):
    """Under W1 = w_bc, W2 = -w_ac, W3 = w_ab (axes a<b<c), I1 W1' = (I2 - I3) W2 W3 and cyclic."""
    (ab, ac, bc) = range(3)
    w = body3.omega_symbols()
    r = body3.symbolic_rhs()
    Im = body3.inertia.symbolic_moments
    W = [w[bc], -w[ac], w[ab]]
    Wdot = [r[bc], -r[ac], r[ab]]
    I = [Im[bc], Im[ac], Im[ab]]
    for k in range(3):
        i, j = (k + 1) % 3, (k + 2) % 3
        assert sp.simplify(I[k] * Wdot[k] - (I[i] - I[j]) * W[i] * W[j]) == 0


@pytest.mark.parametrize("convention", ["paper", "standard"])
def test_3d_body_is_textbook(convention):
    _textbook_check(RigidBody(Inertia.symbolic(3), convention=convention))


def test_standard_3d_equations_textbook_explicit():
    """Standard convention, N = 3: the Eq objects themselves are I1 dW1/dt = (I2 - I3) W2 W3 (and cyclic)."""
    body = RigidBody(Inertia.symbolic(3), convention="standard")
    e12, e13, e23 = body.euler_equations(0)
    I12, I13, I23 = body.inertia.symbolic_moments
    w12, w13, w23 = body.omega_symbols(function_of=TIME)
    I1, I2, I3 = I23, I13, I12
    W1, W2, W3 = w23, -w13, w12
    d = lambda f: sp.diff(f, TIME)  # noqa: E731
    assert sp.expand(e23.lhs - (I1 * d(W1) - (I2 - I3) * W2 * W3)) == 0
    assert sp.expand(-e13.lhs - (I2 * d(W2) - (I3 - I1) * W3 * W1)) == 0
    assert sp.expand(e12.lhs - (I3 * d(W3) - (I1 - I2) * W1 * W2)) == 0


@pytest.mark.parametrize("remaining", list(itertools.combinations(range(1, 6), 3)))
def test_every_3d_reduction_of_5d_is_textbook(remaining):
    locked = [a for a in range(1, 6) if a not in remaining]
    red = RigidBody(Inertia.symbolic(5)).lock(locked)
    assert red.axes == remaining
    _textbook_check(red)


# ---------------------------------------------------------------- stability delegation
def test_stability_delegates(monkeypatch):
    import hyperrotor.classical.stability as st

    calls = []

    def fake(body, plane, Omega):
        calls.append((body, plane, Omega))
        return "sentinel"

    monkeypatch.setattr(st, "linear_stability", fake, raising=False)
    body = RigidBody(Inertia.equal(3))
    assert body.stability((1, 2), 2.5) == "sentinel"
    assert calls == [(body, (1, 2), 2.5)]


def test_two_dimensional_body_is_trivial():
    body = RigidBody(Inertia.equal(2, 3.0))
    np.testing.assert_array_equal(body.rhs(np.array([[2.0], [5.0]])), [[0.0], [0.0]])
    np.testing.assert_array_equal(body.rhs([2.0], [6.0]), [2.0])  # I w' = m
    np.testing.assert_array_equal(body.casimirs([2.0]), [36.0])
    assert body.manakov_integrals([2.0]).shape == (1,)
    eq, = body.euler_equations(0)
    assert sp.expand(eq.lhs + 3 * sp.Derivative(body.omega_symbols(function_of=TIME)[0], TIME)) == 0


def test_lock_numeric_rhs_matches_full_flow(rng):
    N = 6
    full = _random_body(rng, N)
    for locked in [(2,), (1, 6), (2, 3, 5)]:
        red = full.lock(locked)
        keep = [k for k, p in enumerate(full.planes) if not set(p) & set(locked)]
        w = np.zeros(hr.n_planes(N))
        w[keep] = rng.standard_normal(len(keep))
        r = full.rhs(w)
        np.testing.assert_array_equal(np.delete(r, keep), 0.0)  # frozen components stay frozen
        np.testing.assert_allclose(red.rhs(w[keep]), r[keep], rtol=1e-14)
        assert red.planes == tuple(full.planes[k] for k in keep)


@pytest.mark.parametrize("axes", [(1, 1, 2), (0, 1, 2), (3, 2, 1), (1, 2)])
def test_bad_axes_labels(axes):
    with pytest.raises(ValueError, match="increasing positive integers"):
        RigidBody(Inertia.equal(3), axes=axes)


@pytest.mark.parametrize("N", [4, 5, 6])
def test_invariants_conserved_along_numerical_flow(rng, N):
    """Numerical complement of the symbolic proofs: DOP853 at rtol 1e-12 keeps E, c_2k, Manakov to ~1e-9."""
    from scipy.integrate import solve_ivp

    J = rng.uniform(0.2, 1.0, N)
    body = RigidBody(Inertia.from_mass_tensor(J))
    w0 = rng.standard_normal(hr.n_planes(N))
    sol = solve_ivp(lambda t, w: body.rhs(w), (0, 5), w0, method="DOP853", rtol=1e-12, atol=1e-12,
                    t_eval=[5.0])
    w1 = sol.y[:, -1]
    assert np.max(np.abs(w1 - w0)) > 1e-2  # the motion is not trivial
    for f in (body.energy, body.casimirs, lambda w: body.manakov_integrals(w, 0.7)):
        a, b = np.atleast_1d(f(w0)), np.atleast_1d(f(w1))
        np.testing.assert_allclose(b, a, rtol=1e-8, atol=1e-9 * np.max(np.abs(a)))


@pytest.mark.parametrize("where", ["torque", "omega"])
def test_text_is_never_evaluated(tmp_path, monkeypatch, where):
    """#21: a string component is refused with a TypeError naming the argument (never sympified)."""
    monkeypatch.chdir(tmp_path)
    payload = "__import__('os').system('touch pwned')"
    body = hr.RigidBody([1, 2, 3])
    x = sp.Symbol("x")
    with pytest.raises(TypeError, match=rf"{where}\[1\] must be a number or a SymPy expression, not text"):
        if where == "torque":
            body.euler_equations(torque=[x, payload, 1])
        else:
            body.symbolic_rhs([x, payload, 1])
    assert not (tmp_path / "pwned").exists()
    # numbers and SymPy expressions still work, exactly
    eqs = body.euler_equations(torque=[1, 0, sp.Rational(1, 2)])
    assert eqs[2].rhs == -sp.Rational(1, 2)


@pytest.mark.parametrize("N", [3, 4, 5, 7])
def test_euler_tables_are_the_structure_constants(N):
    """The tables built from plane pairs hold exactly the nonzero C[b, c, a], b < c, of every plane a."""
    from hyperrotor.classical.rigid_body import _rhs_tables

    C = hr.structure_constants(N)
    left, right, sign = _rhs_tables(N)
    for a in range(hr.n_planes(N)):
        expected = [(b, c, int(C[b, c, a])) for b in range(C.shape[0]) for c in range(b + 1, C.shape[0]) if C[b, c, a]]
        assert list(zip(left[a].tolist(), right[a].tolist(), sign[a].tolist())) == expected


def test_large_bodies_are_priced():
    """so(60) is built without the n^3 table; so(400)'s tables (3.2e7 entries, ~2.9 GB with temporaries)
    are refused under a 1 GiB budget before any work."""
    N = 60
    body = RigidBody(np.linspace(1.0, 2.0, hr.n_planes(N)))
    assert body.rhs_tables[0].shape == (hr.n_planes(N), N - 2)
    with hr.options(max_memory_bytes=2**30):
        with pytest.raises(hr.BudgetError, match="RigidBody"):
            RigidBody(hr.Inertia(np.ones(hr.n_planes(400))))


def test_symbolic_invariants_are_priced_before_sympy_runs(monkeypatch):
    """The symbolic Casimirs (sums of squared Pfaffians) and Manakov traces grow faster than exponentially with N:
    so(10)'s Casimirs took 484 s and so(7)'s traces minutes, unpriced (a review). Refused before any SymPy work now,
    naming the model; within the budget they still run (and are exact: the tests above)."""
    from hyperrotor.classical import rigid_body
    from hyperrotor.conventions import plane_symbols

    def no_work(*args, **kwargs):
        raise AssertionError("SymPy work started before the budget refused it")

    for N, call in ((8, lambda b, L: b.casimirs(L, of="L")), (6, lambda b, L: b.manakov_integrals(L, of="L"))):
        body = RigidBody(Inertia.equal(N, 1))
        with monkeypatch.context() as m, hr.options(max_seconds=0.5):
            m.setattr(rigid_body, "_pfaffian", no_work)
            m.setattr(rigid_body.sp, "diag", no_work)  # (the Manakov matrix L + lam J^2 is the first step)
            with pytest.raises(hr.BudgetError, match="symbolic_(casimirs|manakov)") as info:
                call(body, plane_symbols("L", N))
        assert "max_seconds" in str(info.value)
    c = RigidBody(Inertia.equal(4, 1)).casimirs(plane_symbols("L", 4), of="L")  # (a small one runs)
    assert len(c) == 2


def test_the_symbolic_price_itself_does_not_overflow():
    """The model's term count passed 1e308 at N ~ 172 and raised a bare OverflowError (a review): a BudgetError
    now, as for any run beyond the budget."""
    from hyperrotor.conventions import plane_symbols

    with pytest.raises(hr.BudgetError, match=r"symbolic_casimirs: .*so\(180\) \(inf products"):
        RigidBody(Inertia.equal(180, 1)).casimirs(plane_symbols("L", 180), of="L")
