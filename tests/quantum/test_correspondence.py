r"""Quantum <-> classical correspondence for the rigid rotor.

Sign relation (derived in :mod:`hyperrotor.quantum.hamiltonian`): for a representation
:math:`X_a` with :math:`[X_a, X_b] = C_{ab}^{\;c} X_c`, the Hermitian generators
:math:`\hat L_a = -i\hbar X_a` obey :math:`[\hat L_a, \hat L_b] = -i\hbar C_{ab}^{\;c}\hat L_c`
(space-frame sign), while the classical body-frame Lie-Poisson bracket is
:math:`\{L_a, L_b\} = +C_{ab}^{\;c} L_c`. Dirac's rule :math:`[\,,] = i\hbar\{\,,\}`
holds for the body-frame operators :math:`\hat L^{b}_a = -\hat L_a`, whose
Heisenberg equations are the symmetrized Euler equations forward in time:
classical :math:`L(t) \leftrightarrow \langle \hat L^{b}\rangle(t) = -\langle\hat L\rangle(t)`.
"""
from fractions import Fraction as F

import numpy as np
import pytest
import qutip
import sympy as sp
import scipy.linalg as sla
from scipy.integrate import solve_ivp

import hyperrotor
from hyperrotor.conventions import lie_poisson_bracket, plane_symbols, planes, structure_constants
from hyperrotor.quantum import irrep, spinor_rep, vector_rep
from hyperrotor.quantum.coherent import (
    apply_rotation,
    coherent_state,
    generator_expectations,
    highest_weight_state,
    normal_form_rotation,
)
from hyperrotor.quantum import evolve, rotor_hamiltonian
from tolerance import norm, scaled_tol


pytestmark = pytest.mark.usefixtures("one_blas_thread")  # (tests/quantum/conftest.py)


def _reps():
    return [
        pytest.param(lambda: vector_rep(3), id="vector3"),
        pytest.param(lambda: vector_rep(4), id="vector4"),
        pytest.param(lambda: vector_rep(6), id="vector6"),
        pytest.param(lambda: spinor_rep(4, 1), id="spinor4+"),
        pytest.param(lambda: spinor_rep(5), id="spinor5"),
        pytest.param(lambda: irrep(3, (sp.Rational(3, 2),)), id="so3-3/2"),
        pytest.param(lambda: irrep(4, (2, -1)), id="so4-(2,-1)"),
        pytest.param(lambda: irrep(5, (2, 1)), id="so5-(2,1)"),
    ]


def _dense(rep, hbar):
    """Hermitian (space-frame) generators -i hbar X_a as dense arrays, plane order."""
    return [rep.generator(p, form="hermitian", hbar=hbar).toarray() for p in planes(rep.N)]


# ----------------------------------------------------------------------------
# brackets
# ----------------------------------------------------------------------------
def test_classical_bracket_is_structure_constants():
    """{L_a, L_b} = sum_c C[a,b,c] L_c exactly (SymPy), for N = 3..5: f_ab^c(classical) = C_ab^c."""
    for N in (3, 4, 5):
        L = plane_symbols("L", N)
        C = structure_constants(N)
        for a in range(len(L)):
            for b in range(len(L)):
                expected = sum(int(C[a, b, c]) * L[c] for c in range(len(L)))
                assert sp.expand(lie_poisson_bracket(L[a], L[b], L) - expected) == 0


@pytest.mark.parametrize("make", _reps())
def test_commutators_match_lie_poisson(make):
    r"""[Lh_a, Lh_b] = -i hbar C_ab^c Lh_c and [Lb_a, Lb_b] = +i hbar C_ab^c Lb_c = i hbar {L_a, L_b}."""
    rep = make()
    hbar = 0.37
    Lh = _dense(rep, hbar)
    Lb = [-x for x in Lh]
    C = structure_constants(rep.N)
    n = len(Lh)
    tol = scaled_tol(max(norm(x) for x in Lh) ** 2, dim=rep.dim, k=8)  # commutator of d x d matrices
    for a in range(n):
        for b in range(n):
            rhs = sum(C[a, b, c] * Lh[c] for c in range(n) if C[a, b, c])
            comm = Lh[a] @ Lh[b] - Lh[b] @ Lh[a]
            np.testing.assert_allclose(comm, -1j * hbar * (rhs if np.ndim(rhs) else 0 * comm), rtol=0, atol=tol)
            rhs_b = sum(C[a, b, c] * Lb[c] for c in range(n) if C[a, b, c])
            comm_b = Lb[a] @ Lb[b] - Lb[b] @ Lb[a]
            np.testing.assert_allclose(comm_b, 1j * hbar * (rhs_b if np.ndim(rhs_b) else 0 * comm_b), rtol=0, atol=tol)


@pytest.mark.parametrize("make", _reps())
def test_heisenberg_equals_symmetrized_euler(make, rng):
    r"""(i/hbar)[H, Lb_a] = sum_{b,c} C[b,c,a] (w_b Lb_c + Lb_c w_b)/2, w_b = Lb_b/I_b (forward Euler);
    the space-frame generators obey the same equation with the opposite sign (time-reversed)."""
    rep = make()
    hbar = 0.6
    moments = rng.uniform(0.5, 2.5, size=len(planes(rep.N)))
    H = rotor_hamiltonian(rep, moments, hbar=hbar).full()
    Lh = _dense(rep, hbar)
    Lb = [-x for x in Lh]
    C = structure_constants(rep.N)
    n = len(Lh)
    # both sides: sums of ~n products of d x d matrices of size ||H|| ||L|| / hbar
    tol = scaled_tol(norm(H) * max(norm(x) for x in Lh) / hbar, dim=rep.dim, k=8 * n)
    for a in range(n):
        sym_b = sum(C[b, c, a] * (Lb[b] @ Lb[c] + Lb[c] @ Lb[b]) / (2 * moments[b]) for b in range(n) for c in range(n) if C[b, c, a])
        sym_h = sum(C[b, c, a] * (Lh[b] @ Lh[c] + Lh[c] @ Lh[b]) / (2 * moments[b]) for b in range(n) for c in range(n) if C[b, c, a])
        np.testing.assert_allclose((1j / hbar) * (H @ Lb[a] - Lb[a] @ H), sym_b, rtol=0, atol=tol)
        np.testing.assert_allclose((1j / hbar) * (H @ Lh[a] - Lh[a] @ H), -sym_h, rtol=0, atol=tol)


def test_classical_component_ode_matches_simulate(rng):
    """The component ODE used below, dL_a/dt = sum C[b,c,a] w_b L_c, is what hyperrotor.simulate integrates."""
    moments = np.array([1.0, 1.6, 2.3])
    L0 = rng.normal(size=3)
    t = np.linspace(0, 3, 7)
    ref = _classical(moments, L0, t)
    body = hyperrotor.RigidBody(hyperrotor.Inertia.from_planes(moments))
    traj = hyperrotor.simulate(body, L0 / moments, t, rtol=1e-12)
    np.testing.assert_allclose(traj.L, ref, atol=1e-8, rtol=0)


# ----------------------------------------------------------------------------
# coherent states
# ----------------------------------------------------------------------------
def _random_rotation(rng, N):
    Q, R = np.linalg.qr(rng.normal(size=(N, N)))
    Q = Q * np.sign(np.diag(R))
    if np.linalg.det(Q) < 0:
        Q[:, 0] *= -1
    return Q


def _components(A):
    return np.array([A[i - 1, j - 1] for i, j in planes(A.shape[0])])


def _bivector(Q, lam):
    N = Q.shape[0]
    B = np.zeros((N, N))
    for k, lk in enumerate(lam):
        B[2 * k, 2 * k + 1], B[2 * k + 1, 2 * k] = lk, -lk
    return _components(Q @ B @ Q.T)


@pytest.mark.parametrize("N", [3, 4, 5, 6, 7])
def test_normal_form_rotation(N, rng):
    Q0 = _random_rotation(rng, N)
    lam0 = np.sort(rng.uniform(0.5, 2, size=N // 2))[::-1]
    L = _bivector(Q0, lam0)
    Q, lam = normal_form_rotation(L)
    tol = scaled_tol(lam0, dim=N, k=16)  # a backward-stable decomposition of an N x N matrix of size |lam|
    assert abs(np.linalg.det(Q) - 1) < scaled_tol(dim=N, k=16)
    np.testing.assert_allclose(lam, lam0, rtol=0, atol=tol)
    np.testing.assert_allclose(_bivector(Q, lam), L, rtol=0, atol=tol)
    if N % 2 == 0:  # opposite orientation: last lambda negative
        P = np.eye(N)
        P[0, 0] = -1
        Lr = _bivector(P @ Q0, lam0)  # P Q0 has det -1: the mirror-image bivector
        _, lam_r = normal_form_rotation(Lr)
        np.testing.assert_allclose(lam_r, np.r_[lam0[:-1], -lam0[-1]], rtol=0, atol=tol)


@pytest.mark.parametrize("N", [3, 4, 5])
def test_apply_rotation_is_the_group_action(N, rng):
    """U(Q) Lh(X) U(Q)^dagger = Lh(Q X Q^T): the vector rep gives U(Q) = Q itself."""
    rep = vector_rep(N)
    Q = _random_rotation(rng, N)
    psi = rng.normal(size=N) + 1j * rng.normal(size=N)
    np.testing.assert_allclose(apply_rotation(rep, Q, psi), Q @ psi, rtol=0, atol=scaled_tol(psi, dim=N, k=16))


@pytest.mark.parametrize(
    "make, hw",
    [
        (lambda: irrep(3, (5,)), (5,)),
        (lambda: irrep(3, (sp.Rational(7, 2),)), (3.5,)),
        (lambda: vector_rep(4), (1, 0)),
        (lambda: irrep(4, (3, 0)), (3, 0)),
        (lambda: vector_rep(5), (1, 0)),
        (lambda: irrep(5, (4, 0)), (4, 0)),
        (lambda: irrep(6, (2, 0, 0)), (2, 0, 0)),
    ],
)
def test_coherent_state_simple_bivector(make, hw, rng):
    r"""<Lh> = hbar l L/|L| ("space"), <Lb> = -<Lh> = hbar l L/|L| ("body"), and minimal uncertainty
    sum_a Var(Lh_a) = hbar^2 <w, 2 rho> (rho_k = N/2 - k), e.g. hbar^2 l for so(3)."""
    rep = make()
    N = rep.N
    hbar = 0.8
    _, w = highest_weight_state(rep)
    np.testing.assert_allclose(w, hw, atol=1e-10, rtol=0)
    Q = _random_rotation(rng, N)
    L = _bivector(Q, [1.7] + [0.0] * (N // 2 - 1))  # a simple bivector of norm 1.7
    l = hw[0]
    for frame, sign in (("space", 1), ("body", -1)):
        psi = coherent_state(rep, L, hbar=hbar, frame=frame)
        assert isinstance(psi, qutip.Qobj) and abs(psi.norm() - 1) < 1e-12
        ex = generator_expectations(rep, psi, hbar=hbar)
        np.testing.assert_allclose(sign * ex, hbar * l * L / 1.7, atol=1e-9, rtol=0)
        v = psi.full().ravel()
        second = sum(np.vdot(v, (x @ (x @ v))).real for x in (rep.generator(p, form="hermitian", hbar=hbar) for p in planes(N)))
        rho = [N / 2 - k for k in range(1, N // 2 + 1)]
        np.testing.assert_allclose(second - ex @ ex, hbar**2 * 2 * np.dot(hw, rho), atol=1e-9, rtol=0)


def test_coherent_state_general_so5(rng):
    """General L in so(5) with normal form proportional to (m1, m2) = (3, 1) (also (2, 2))."""
    for hw in [(3, 1), (2, 2), (sp.Rational(5, 2), sp.Rational(1, 2))]:
        rep = irrep(5, hw)
        Q = _random_rotation(rng, 5)
        w = np.array([float(x) for x in hw])
        L = _bivector(Q, 0.4 * w)
        psi = coherent_state(rep, L)
        np.testing.assert_allclose(generator_expectations(rep, psi), L / 0.4, atol=1e-9, rtol=0)
        psi_b = coherent_state(rep, L, hbar=2.0, frame="body")
        np.testing.assert_allclose(-generator_expectations(rep, psi_b, hbar=2.0), 2 * L / 0.4, atol=1e-9, rtol=0)


def test_coherent_state_errors(rng):
    rep = irrep(5, (3, 0))
    L_general = _bivector(_random_rotation(rng, 5), [2.0, 1.0])
    with pytest.raises(ValueError, match="not a positive multiple"):
        coherent_state(rep, L_general)
    with pytest.raises(ValueError, match="10 components"):
        coherent_state(rep, [1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="non-zero"):
        coherent_state(rep, np.zeros(10))
    with pytest.raises(ValueError, match="frame"):
        coherent_state(rep, np.eye(10)[0], frame="lab")
    chiral = spinor_rep(4, 1)  # (1/2, 1/2): self-dual bivectors only
    Q = _random_rotation(rng, 4)
    coherent_state(chiral, _bivector(Q, [1.0, 1.0]))
    P = np.diag([-1.0, 1, 1, 1])
    with pytest.raises(ValueError, match="not a positive multiple"):
        coherent_state(chiral, _bivector(P @ Q, [1.0, 1.0]))


# ----------------------------------------------------------------------------
# Ehrenfest / classical limit
# ----------------------------------------------------------------------------
def _classical(moments, L0, t):
    N = hyperrotor.dimension_from_count(len(moments))
    C = structure_constants(N).astype(float)

    def rhs(_, L):
        return np.einsum("bca,b,c->a", C, L / moments, L)

    sol = solve_ivp(rhs, (t[0], t[-1]), L0, t_eval=t, method="DOP853", rtol=1e-12, atol=1e-13)
    return sol.y.T


def _ehrenfest_errors(N, ls, moments, L0, times):
    r"""max_t |<Lb>(t) - L(t)| for coherent states in (l, 0, ...), hbar = 1/l (so |<Lb>(0)| = |L0|)."""
    ref = _classical(moments, L0, times)
    back = _classical(moments, L0, -times)  # L(-t): the time-reversed flow, for the sign check
    rows = []
    for l in ls:
        rep = irrep(3, (l,)) if N == 3 else irrep(N, (l,) + (0,) * (N // 2 - 1))
        hbar = 1.0 / l
        H = rotor_hamiltonian(rep, moments, hbar=hbar)
        psi = coherent_state(rep, L0, hbar=hbar, frame="body")
        e_ops = [qutip.Qobj(-rep.generator(p, form="hermitian", hbar=hbar)) for p in planes(N)]
        res = evolve(H, psi, times, e_ops=e_ops, hbar=hbar)
        q = np.array(res.expect).T.real
        rows.append((l, rep.dim, np.abs(q - ref).max(), np.abs(q - back).max()))
    return rows


def _report(title, rows):
    print(f"\n{title}\n   l    dim   max|<Lb>/(l hbar) - L_cl|   vs time-reversed flow")
    for l, dim, err, rev in rows:
        print(f"{l:4d} {dim:6d}   {err:.3e}                  {rev:.3e}")
    ls = np.array([r[0] for r in rows], float)
    errs = np.array([r[2] for r in rows])
    slope = np.polyfit(np.log(ls), np.log(errs), 1)[0]
    print(f"log-log slope: {slope:.3f}")
    return slope, errs, np.array([r[3] for r in rows])


def test_ehrenfest_so3_error_shrinks_like_one_over_l():
    moments = np.array([1.0, 1.6, 2.3])  # I_12, I_13, I_23
    L0 = np.array([0.5, -0.3, 0.81])
    L0 = L0 / np.linalg.norm(L0)
    times = np.linspace(0, 4.0, 41)
    rows = _ehrenfest_errors(3, [2, 4, 8, 16, 32], moments, L0, times)
    slope, errs, rev = _report("so(3) asymmetric top, coherent states (l), hbar = 1/l", rows)
    assert -1.3 < slope < -0.7
    assert errs[-1] < 0.05
    assert np.all(rev > 0.3)  # the body-frame expectation does not follow the reversed flow


def test_ehrenfest_so5_error_shrinks_like_one_over_l():
    moments = np.array([1.0, 1.3, 1.7, 2.2, 1.1, 1.9, 2.6, 1.4, 2.0, 1.2])
    L0 = _bivector(_random_rotation(np.random.default_rng(3), 5), [1.0, 0.0])  # unit simple bivector
    times = np.linspace(0, 3.0, 31)
    rows = _ehrenfest_errors(5, [2, 4, 8, 16, 32], moments, L0, times)
    slope, errs, rev = _report("so(5) rotor, coherent states (l, 0), hbar = 1/l", rows)
    assert -1.3 < slope < -0.7
    assert np.all(rev > 0.3)


def test_ehrenfest_time_against_brute_force():
    r"""ehrenfest_time == dense expm of H (quantum), solve_ivp (classical) and the first crossing found here."""
    moments = np.array([1.0, 1.6, 2.3])
    L0 = np.array([0.5, -0.3, 0.81]) * 1.7
    t = np.linspace(0.0, 6.0, 61)
    res = hyperrotor.quantum.ehrenfest_time(moments, L0, [2, 5], t, threshold=0.15)
    ref_cl = _classical(moments, L0, t)
    np.testing.assert_allclose(res.classical, ref_cl, rtol=0, atol=1e-7 * np.linalg.norm(L0))
    for row, l in enumerate((2, 5)):
        rep = irrep(3, (l,))
        hbar = np.linalg.norm(L0) / l
        assert res.hbar[row] == pytest.approx(hbar, rel=1e-15) and res.dims[row] == 2 * l + 1
        Hd = rotor_hamiltonian(rep, moments, hbar=hbar).full()
        psi = coherent_state(rep, L0, hbar=hbar, frame="body").full().ravel()
        ops = [-rep.generator(p, form="hermitian", hbar=hbar).toarray() for p in planes(3)]
        q = []
        for tk in t:
            v = sla.expm(-1j * tk * Hd / hbar) @ psi
            q.append([np.vdot(v, o @ v).real for o in ops])
        q = np.array(q)
        np.testing.assert_allclose(res.quantum[row], q, rtol=0, atol=1e-9 * np.linalg.norm(L0))
        dev = np.linalg.norm(q - ref_cl, axis=1) / np.linalg.norm(L0)
        k = int(np.argmax(dev >= 0.15))
        assert dev[k] >= 0.15 > dev[k - 1]  # crosses inside the window
        assert t[k - 1] <= res.t_E[row] <= t[k]
        expected = t[k - 1] + (0.15 - dev[k - 1]) / (dev[k] - dev[k - 1]) * (t[k] - t[k - 1])
        assert res.t_E[row] == pytest.approx(expected, abs=1e-6)
    assert res.t_E[1] > res.t_E[0]  # smaller hbar_eff: the state follows the classical orbit longer


def test_ehrenfest_time_takes_a_highest_weight_as_the_package_gives_it():
    """weight= in exact numbers (a representation's highest_weight is Fractions; sympy.Rational too) gives the
    irreps and levels of the same weight as floats: (1/2) for l = 2, 4 is the so(3) irreps j = 1, 2. Weights that are
    not integers or half-integers are refused with the entry named."""
    moments = np.array([1.0, 1.6, 2.3])
    L0 = np.array([0.5, -0.3, 0.81])
    t = np.linspace(0.0, 2.0, 5)
    half = irrep(3, (F(1, 2),)).highest_weight
    ref = hyperrotor.quantum.ehrenfest_time(moments, L0, [2, 4], t, weight=(0.5,))
    for w in (half, (sp.Rational(1, 2),), [F(1, 2)]):
        res = hyperrotor.quantum.ehrenfest_time(moments, L0, [2, 4], t, weight=w)
        assert res.dims.tolist() == ref.dims.tolist() == [3, 5]
        np.testing.assert_array_equal(res.quantum, ref.quantum)
        np.testing.assert_array_equal(res.t_E, ref.t_E)
    # floats as before: l * w must be (half-)integers, checked after the multiplication
    quarter = hyperrotor.quantum.ehrenfest_time(moments, L0, [4], t, weight=(0.25,))
    one = hyperrotor.quantum.ehrenfest_time(moments, L0, [1], t, weight=(1,))
    assert quarter.dims.tolist() == one.dims.tolist() == [3]
    np.testing.assert_array_equal(quarter.quantum, one.quantum)
    with pytest.raises(ValueError, match=r"l \* weight must be integers or half-integers .* got the entry 0.6"):
        hyperrotor.quantum.ehrenfest_time(moments, L0, [2], t, weight=(0.3,))
    third = hyperrotor.quantum.ehrenfest_time(moments, L0, [3], t, weight=(F(1, 3),))  # (exact: l * w = 1)
    np.testing.assert_array_equal(third.quantum, one.quantum)
    with pytest.raises(ValueError, match="integers or half-integers"):
        hyperrotor.quantum.ehrenfest_time(moments, L0, [2], t, weight=(F(1, 3),))
    with pytest.raises(ValueError, match="not all zero"):
        hyperrotor.quantum.ehrenfest_time(moments, L0, [2], t, weight=(F(0),))
    with pytest.raises(TypeError, match="weight must be a sequence"):
        hyperrotor.quantum.ehrenfest_time(moments, L0, [2], t, weight="1/2")


def test_expectations_and_ehrenfest_inputs_at_the_edges(monkeypatch):
    """generator_expectations multiplied by -1j hbar in complex arithmetic: hbar = 5e307 gave inf and 1e308 nan
    where the values are ~9e307; ehrenfest_time took method='sesolve' as far as the first irrep (its message then
    advised evolve), and weight = (1e308,) raised a bare OverflowError from fractions (a review)."""
    from hyperrotor.quantum import correspondence, ehrenfest_time, generator_expectations, irrep

    rep = irrep(3, (1,))
    psi = np.array([1.0, 1j, 0.3])
    one = generator_expectations(rep, psi)
    assert np.any(one != 0)
    for hbar in (0.37, 5e307, 1e308):  # (hbar last and real: the same rounding at every scale)
        np.testing.assert_array_equal(generator_expectations(rep, psi, hbar=hbar), one * hbar)

    def no_run(*args, **kwargs):
        raise AssertionError("the classical run started before the arguments were checked")

    monkeypatch.setattr(correspondence, "simulate", no_run)
    args = ([1.0, 2.0, 3.0], [0.3, 0.2, 1.0], [2], np.linspace(0.0, 1.0, 5))
    with pytest.raises(ValueError, match=r"'sesolve' is QuTiP's solver; ehrenfest_time propagates in the symmetry "
                                         r"sectors: one of 'auto', 'eigen', 'krylov', 'expm_multiply'"):
        ehrenfest_time(*args, method="sesolve")
    with pytest.raises(ValueError, match=r"unknown method 'foo'; allowed: 'auto', 'eigen', 'krylov', 'expm_multiply'$"):
        ehrenfest_time(*args, method="foo")
    with pytest.raises(ValueError, match="beyond double precision"):
        ehrenfest_time(*args, weight=(1e308,))
