"""Tests of hyperrotor.simulate (hyperrotor.classical.simulate), the Lie-Poisson splittings and the scipy peers.

Tolerances are stated as multiples of machine epsilon where the claim is "to round-off"
and as explicit error bounds against closed forms otherwise.
"""
import numpy as np
import pytest

import hyperrotor as hr
from hyperrotor import Inertia, RigidBody
from hyperrotor._jit import JIT_ENABLED
from hyperrotor.classical.solvers import _kernels
from hyperrotor.classical import euler_poinsot, quartet_attitude, quartet_moments, quartet_solution
from hyperrotor.classical.simulate import SIMULATION_METHODS, Trajectory, simulate
from hyperrotor.classical.solvers import SOLVERS
from hyperrotor.classical.solvers.splitting import casimir_shift, splitting_coefficients
from hyperrotor.classical.solvers.splitting import splitting_word as _splitting_word
from hyperrotor.conventions import n_planes, structure_constants, to_matrix
from tolerance import EPS, scaled_tol

SPLITTINGS = [m for m in SOLVERS if m.startswith("splitting")]
SCIPY = ["DOP853", "RK45", "LSODA", "Radau"]

MOM3 = np.array([2.0, 3.0, 4.0])  # I12, I13, I23
W3 = np.array([0.6, 1.0, -0.5])


def generic5(rng):
    """A physical asymmetric 5D body: I_ij = m_i + m_j with distinct m."""
    m = np.array([0.3, 0.55, 0.9, 1.4, 2.1])
    return Inertia.from_mass_tensor(m), rng.normal(size=10)


def casimirs(L):
    """tr(L^2), tr(L^4) of the plain matrix (the Casimirs of eq. 38 up to normalisation)."""
    M = to_matrix(L, convention="standard")
    M2 = M @ M
    return np.trace(M2, axis1=-2, axis2=-1), np.trace(M2 @ M2, axis1=-2, axis2=-1)


# ----------------------------------------------------------------------------- elementary flows
@pytest.mark.parametrize("compensated", [False, True], ids=["plain", "compensated"])
@pytest.mark.parametrize("N", [3, 4, 5, 6])
def test_elementary_flow_is_the_flow_of_one_plane_term(N, compensated, rng):
    """d/dh of the plane-a flow at h = 0 equals dL/dt = [W, L] with W = (L_a / I_a) E_a (structure constants)."""
    n = n_planes(N)
    C = structure_constants(N).astype(float)
    L0 = rng.normal(size=(1, n))
    mom = rng.uniform(1, 2, size=(1, n))
    tables = _kernels.rotation_tables(N)
    h = 1e-5
    for a in range(n):
        outs = []
        for tt in ([0.0, h], [0.0, -h]):
            outL = np.zeros((1, 2, n))
            outT = np.zeros((1, 2, N, N))
            # a negative step is the inverse flow: run on a reversed grid by flipping the coefficient
            plane, coef = np.array([a]), np.array([1.0 if tt[1] > 0 else -1.0])
            for arr in (plane, coef):  # read-only like the solver's cached words: the kernel it compiled
                arr.setflags(write=False)
            _kernels.split_run(L0, 1.0 / mom, plane, coef, *tables, np.array([h]), np.array([1]),
                               np.zeros((1, n)), np.eye(N)[None], True, compensated, outL, outT, np.zeros((1, 2, n)))
            outs.append((outL[0, 1], outT[0, 1]))
        w = np.zeros(n)
        w[a] = L0[0, a] / mom[0, a]
        dL = (outs[0][0] - outs[1][0]) / (2 * h)
        dT = (outs[0][1] - outs[1][1]) / (2 * h)
        np.testing.assert_allclose(dL, np.einsum("b,c,bca->a", w, L0[0], C), atol=1e-8, rtol=0)
        np.testing.assert_allclose(dT, to_matrix(w, convention="standard"), atol=1e-8, rtol=0)  # dT/dt = W T at T = 1
        assert outs[0][0][a] == L0[0, a]  # L_a is exactly invariant under its own flow


@pytest.mark.skipif(not JIT_ENABLED, reason="numba disabled: only the Python path exists")
@pytest.mark.parametrize("compensated", [False, True], ids=["plain", "compensated"])
def test_jitted_and_python_kernels_agree(compensated, rng, eps):
    N, n = 5, 10
    L0 = rng.normal(size=(3, n))
    mom = np.broadcast_to(rng.uniform(1, 3, size=n), (3, n)).copy()
    word = _splitting_word(4, tuple(range(n)))
    tables = _kernels.rotation_tables(N)
    t = np.array([0.0, 0.3, 0.7])
    nsub = np.array([5, 7])
    outs = []
    for fn in (_kernels.split_run, _kernels.split_run.py_func):
        outL = np.zeros((3, 3, n))
        outT = np.zeros((3, 3, N, N))
        fn(L0, 1.0 / mom, *word, *tables, np.diff(t) / nsub, nsub, np.zeros((3, n)), np.broadcast_to(np.eye(N), (3, N, N)).copy(),
           True, compensated, outL, outT, np.zeros((3, 2, n)))
        outs.append((outL, outT))
    np.testing.assert_allclose(outs[0][0], outs[1][0], rtol=0, atol=64 * eps * np.abs(L0).max())
    np.testing.assert_allclose(outs[0][1], outs[1][1], rtol=0, atol=64 * eps)


@pytest.mark.parametrize("fn", ["rotation", "rotation_poly"])
def test_plane_rotation_is_accurate(fn, eps):
    """``(sin 2x, 1 - cos 2x)`` within 2 ulps of 40-digit values (mpmath), relative to each: the polynomials up to
    ``SMALL_HALF_ANGLE`` (their range's end included), libm beyond (``rotation``)."""
    import mpmath

    th = _kernels.SMALL_HALF_ANGLE
    x = np.concatenate([np.linspace(-th, th, 4001), [th, -th, np.nextafter(th, 1.0), 1e-300, -1e-17, 0.0, 3e-9]])
    if fn == "rotation":
        x = np.concatenate([x, np.linspace(-4.0, 4.0, 2001), [40.0, -1e3]])
    f = getattr(_kernels, fn)
    got = np.array([f(float(v)) for v in x])
    with mpmath.workdps(40):
        want = np.array([(float(mpmath.sin(2 * mpmath.mpf(float(v)))), float(2 * mpmath.sin(mpmath.mpf(float(v))) ** 2))
                         for v in x])
    assert np.all(np.abs(got - want) <= 2 * eps * np.abs(want) + 1e-300)
    # the vectorised kernels' test for the lanes to redo by libm is rotation's own (the same pair for every lane)
    assert np.array_equal(np.abs(x) > th, np.array([not abs(float(v)) <= th for v in x]))


def test_the_polynomials_truncation_is_below_half_an_ulp_at_their_range_end():
    """The first omitted Taylor terms at ``SMALL_HALF_ANGLE``, relative to the leading ones, are below 2^-56:
    ``(2x)^14 / 15!`` for ``sin 2x / 2x`` and ``2 (2x)^14 / 16!`` for ``(1 - cos 2x) / 2x^2``."""
    from math import factorial

    y = 2.0 * _kernels.SMALL_HALF_ANGLE
    assert y ** 14 / factorial(15) < 2.0 ** -56
    assert 2.0 * y ** 14 / factorial(16) < 2.0 ** -56
    # the coefficients are the series' (-4)^k / (2k+1)! and (-1)^(k+1) 4^k / (2 (2k)!)
    A = [getattr(_kernels, f"_A{k}") for k in range(1, 7)]
    B = [getattr(_kernels, f"_B{k}") for k in range(2, 8)]
    assert A == [(-4.0) ** k / factorial(2 * k + 1) for k in range(1, 7)]
    assert B == [(-1.0) ** (k + 1) * 4.0 ** k / (2.0 * factorial(2 * k)) for k in range(2, 8)]


@pytest.mark.parametrize("compensated", [False, True], ids=["plain", "compensated"])
@pytest.mark.parametrize("use_py", [False, True], ids=["jit", "py_func"])
def test_ensemble_kernel_equals_per_body_kernel(use_py, compensated, rng):
    """Bodies-innermost kernel (vectorised, chunked) == per-body kernel, bit for bit, incl. kicks
    and angles beyond the polynomial range."""
    N, n, B = 4, 6, 37
    L0 = rng.normal(size=(B, n)) * np.where(rng.random((B, 1)) < 0.3, 30.0, 1.0)
    mom = rng.uniform(0.5, 3, size=(B, n))
    tq = rng.normal(size=(B, n))
    word = _splitting_word(4, tuple(range(n)), kick=True)
    tables = _kernels.rotation_tables(N)
    t = np.array([0.0, 0.2, 0.5])
    nsub = np.array([3, 4])
    ens = _kernels.split_run_ensemble
    if use_py:
        if not JIT_ENABLED:
            pytest.skip("numba disabled: the kernels are already plain Python")
        ens = ens.py_func
    a = np.zeros((B, 3, n))
    ens(L0, 1.0 / mom, *word, *tables[:3], np.diff(t) / nsub, nsub, tq, 8, compensated, a, np.zeros((B, 2, n)))
    b = np.zeros((B, 3, n))
    _kernels.split_run_serial(L0, 1.0 / mom, *word, *tables, np.diff(t) / nsub, nsub, tq, np.zeros((1, N, N)), False,
                              compensated, b, np.zeros((B, 1, N, N)), np.zeros((B, 2, n)))
    np.testing.assert_array_equal(a, b)


def test_coefficient_sets_are_symmetric_and_consistent():
    for order, stages in [(2, 1), (4, 3), (6, 9), (8, 17), (10, 35)]:
        g = splitting_coefficients(order)
        assert g.size == stages
        np.testing.assert_array_equal(g, g[::-1])
        assert abs(g.sum() - 1) < 4e-16
        # a symmetric composition of order p needs sum gamma^k = 0 for k = 3, 5, ..., p - 1 (its first order
        # conditions), to the round-off of the k-th powers: k eps per term (measured: 0.03-0.47 of k eps sum |g|^k)
        for k in range(3, order, 2):
            assert abs(np.sum(g ** k)) <= 4 * k * EPS * np.sum(np.abs(g) ** k), (order, k)
    with pytest.raises(ValueError, match="2, 4, 6, 8, 10"):
        splitting_coefficients(3)


# ----------------------------------------------------------------------------- Casimir shift, plane order
def test_casimir_shift_is_the_weighted_median_rate():
    # quartet: the six inside planes share 1/I = 1/2 and drop out of the step
    q = quartet_moments(0.5)
    assert casimir_shift(q) == 0.5
    assert casimir_shift(q, np.ones(10)) == 0.5
    # generic body, equal weights: a median rate (10 rates: the 5th or 6th smallest)
    m = Inertia.from_mass_tensor([0.3, 0.55, 0.9, 1.4, 2.1]).moments
    r = np.sort(1 / m)
    assert casimir_shift(m) in (r[4], r[5])
    # moments over 12 decades: the weights |L_a| <= sqrt(2 E I_a) keep c among the heavy
    # planes (tiny rates) when they carry the momentum, instead of the rate median
    stiff = Inertia.from_mass_tensor([1e-7, 9e-7, 1.0, 1e3, 1e6]).moments
    L = np.where(stiff > 1e5, 1e6, 1.0)
    assert casimir_shift(stiff, L) <= 1e-6 + 1e-12
    assert casimir_shift(stiff) >= 1e-4


def test_casimir_shift_of_a_large_body_builds_its_table_in_blocks(monkeypatch):
    """The |1/I_a - value| table of the shift rule (n planes x V candidate values) is kept whole only up to
    _SHIFT_TABLE_ENTRIES entries (3.2 GB at N = 200): beyond, blocks of candidates give the same choice, for
    bodies with shared and distinct moments, single and ensemble rows, and it is still the weighted median
    rate of the example above."""
    from hyperrotor.classical.solvers import splitting

    rng = np.random.default_rng(5)
    cases = [(Inertia.from_mass_tensor([0.3, 0.55, 0.9, 1.4, 2.1]).moments, np.ones((1, 10)))]
    for n, B in ((10, 1), (45, 4), (190, 3)):
        m = np.exp(rng.uniform(np.log(0.3), np.log(3.0), n))
        m[: n // 3] = m[0]  # a third of the planes share one moment
        cases.append((m, rng.normal(size=(B, n))))
    whole = [splitting.shift_rule(m, L) for m, L in cases]
    splitting._shift_candidates.cache_clear()
    monkeypatch.setattr(splitting, "_SHIFT_TABLE_ENTRIES", 7)  # (blocks of one candidate and more)
    try:
        for (m, L), c in zip(cases, whole):
            assert splitting._shift_candidates(m.tobytes())[2] is None  # (no table kept)
            np.testing.assert_array_equal(splitting.shift_rule(m, L), c)
    finally:
        splitting._shift_candidates.cache_clear()
    r = np.sort(1 / cases[0][0])
    assert whole[0][0] in (r[4], r[5])


def test_casimir_shift_leaves_L_unchanged_and_drops_planes():
    """The shifted splitting integrates the same L(t) (checked against the quartet's closed
    form), with only the four axis-5 planes left in the step."""
    w0 = np.random.default_rng(3).normal(size=10)
    t = np.linspace(0, 20, 21)
    tr = simulate(RigidBody(Inertia.quartet(0.5)), w0, t, method="splitting8", dt=0.1, attitude=True)
    assert tr.stats["casimir_shift"] == 0.5
    assert tr.stats["flows_per_step"] == 17 * 6 + 1  # Strang over 4 planes: 7 flows, 6 after merging
    np.testing.assert_allclose(tr.omega, quartet_solution(0.5, w0, t), rtol=0, atol=1e-11)
    # the attitude is put back exactly (T = T' exp(c (t - t0) Lambda)): quartet closed form
    np.testing.assert_allclose(tr.attitude, quartet_attitude(0.5, w0, t), rtol=0, atol=1e-10)


def test_equal_moments_nothing_to_split(rng):
    """All planes drop out: L is exactly constant and T(t) = T0 exp(W0 t) (plain), with no step."""
    w0 = rng.normal(size=10)
    t = np.linspace(0, 7, 8)
    Q, _ = np.linalg.qr(rng.normal(size=(5, 5)))
    tr = simulate(np.full(10, 1.7), w0, t, method="splitting8", attitude=Q, rtol=1e-12)
    assert tr.stats["flows_per_step"] == 0
    np.testing.assert_array_equal(tr.L, np.broadcast_to(1.7 * w0, tr.L.shape))
    ref = simulate(np.full(10, 1.7), w0, t, method="DOP853", attitude=Q, rtol=1e-13)
    np.testing.assert_allclose(tr.attitude, ref.attitude, rtol=0, atol=1e-10)
    orth = np.abs(np.swapaxes(tr.attitude, -1, -2) @ tr.attitude - np.eye(5)).max()
    assert orth < 32 * np.finfo(float).eps  # one eigen-decomposition, no accumulation


def test_casimir_shift_per_member_and_member_independence(rng):
    """One shift per ensemble member: at fixed dt a member's result does not depend on the others
    (up to round-off: planes another member needs are exact identities for it)."""
    inertia = Inertia.from_mass_tensor([0.05, 0.3, 1.0, 4.0, 10.0])
    m = inertia.moments
    spin45 = np.full(10, 0.02)
    spin45[9] = 1.0
    spin12 = np.full(10, 0.02)
    spin12[0] = 1.0
    c = casimir_shift(m, np.array([spin45, spin12]) * m)
    assert c.shape == (2,) and c[0] != c[1]
    assert c[0] == casimir_shift(m, spin45 * m) and c[1] == casimir_shift(m, spin12 * m)
    t = np.linspace(0, 5, 6)
    alone = simulate(inertia, spin45, t, method="splitting4", dt=0.01)
    both = simulate(inertia, np.array([spin45, spin12]), t, method="splitting4", dt=0.01)
    np.testing.assert_allclose(both.omega[0], alone.omega, rtol=0, atol=1e-13)
    np.testing.assert_array_equal(both.stats["casimir_shift"], c)
    # a torque: no shift (the weights describe the initial state only)
    tq = simulate(inertia, spin45, t, method="splitting4", dt=0.01, torque=np.ones(10))
    assert tq.stats["casimir_shift"] == 0.0


@pytest.mark.parametrize("kw, exc, match", [
    (dict(L=np.ones(4)), ValueError, r"shape \(10,\) or \(B, 10\)"),
    (dict(L=np.ones((2, 2, 10))), ValueError, "shape"),
    (dict(L=np.full(10, np.nan)), ValueError, "finite"),
    (dict(L="x"), TypeError, "numeric"),
    (dict(moments=np.r_[0.0, np.ones(9)]), ValueError, "finite and > 0"),
])
def test_casimir_shift_bad_input(kw, exc, match):
    args = dict(moments=np.arange(1.0, 11.0), L=None)
    args.update(kw)
    with pytest.raises(exc, match=match):
        casimir_shift(args["moments"], args["L"])


def test_empty_ensemble_gives_empty_results():
    for kw in (dict(method="splitting4", rtol=1e-6), dict(method="moser-veselov", rtol=1e-6),
               dict(method="splitting8", dt=0.1, attitude=True), dict(method="DOP853")):
        tr = simulate(MOM3, np.zeros((0, 3)), [0.0, 1.0, 2.0], **kw)
        assert tr.omega.shape == (0, 3, 3)


def test_step_rule_catches_the_run_away_of_an_unstable_rotation():
    """Near steady rotation in plane 13 of a physical 5D body the perturbation grows faster than
    linearly; a probe over the first part of the run sees almost no error. The check over the
    whole run keeps the error within rtol (it missed by 60-300x without it)."""
    m = Inertia.from_mass_tensor([3.1197, 0.2223, 0.0738, 0.158, 2.9083]).moments
    w = np.zeros(10)
    w[1] = 1.0
    w += 0.02 * np.random.default_rng(0).normal(size=10)
    t = np.linspace(0, 30, 31)
    ref = simulate(m, w, t, method="DOP853", rtol=1e-13)
    for method in ("splitting4", "splitting8"):
        for rtol in (1e-6, 1e-9):
            tr = simulate(m, w, t, method=method, rtol=rtol)
            err = max(np.abs(tr.omega - ref.omega).max() / np.abs(w).max(),
                      np.abs(tr.L - ref.L).max() / np.linalg.norm(w * m))
            assert err <= rtol, (method, rtol, err)


# ----------------------------------------------------------------------------- convergence order
ORDER_CASES = {
    # method: (nominal order, dts on the 3D case, dts on the 5D quartet, the quartet's T); the
    # quartet's dts divide the output spacing 1 (the step used is gap / ceil(gap / dt)) and keep
    # the errors well above round-off (the Casimir shift drops six of its ten planes). Order 10
    # goes from 3e-7 to round-off within a factor 2.5 of the step on the 3D top, before its error
    # follows h^10 (fitted slopes 12-16): no 3D case; on the quartet over T = 40 the fit gives 10.1
    "splitting2": (2, [0.1, 0.05, 0.025, 0.0125], [0.1, 0.05, 0.025, 0.0125], 10),
    "splitting4": (4, [0.2, 0.1, 0.05, 0.025], [0.2, 0.1, 0.05, 0.025], 10),
    "splitting6": (6, [0.5, 0.25, 0.125, 0.0625], [0.5, 0.25, 0.125, 0.0625], 10),
    "splitting8": (8, [1.0, 0.7, 0.5, 0.35], [0.5, 1 / 3, 0.25, 0.2], 10),
    "splitting10": (10, None, [0.5, 1 / 3, 0.25, 0.2], 40),
}


@pytest.mark.parametrize("method", SPLITTINGS)
def test_empirical_order_3d_against_elliptic_solution(method):
    p, dts, _, _ = ORDER_CASES[method]
    if dts is None:
        pytest.skip(f"{method}: round-off before the asymptotic regime on this 3D top (see ORDER_CASES)")
    t = np.linspace(0, 10, 11)
    exact = euler_poinsot(MOM3, W3, t)
    errs = [np.abs(simulate(MOM3, W3, t, method=method, dt=dt).omega - exact).max() for dt in dts]
    assert min(errs) > 1e-13, "error at round-off level: the fit would be meaningless"
    slope = np.polyfit(np.log(dts), np.log(errs), 1)[0]
    assert abs(slope - p) < 0.5, (method, slope, errs)


@pytest.mark.parametrize("method", SPLITTINGS)
def test_empirical_order_5d_quartet_against_closed_form(method, rng):
    p, _, dts, T = ORDER_CASES[method]
    kappa = 0.5
    w0 = np.random.default_rng(3).normal(size=10)
    t = np.linspace(0, T, T + 1)
    exact = quartet_solution(kappa, w0, t)
    body = RigidBody(Inertia.quartet(kappa))
    # compensated storage: the truncation error alone (splitting10's 3.5e-13 at dt = 0.2 carried +-1.5e-13 of
    # plain round-off, which moved the fitted slope from 10.1 to 10.7 with an equally accurate rotation formula)
    errs = [np.abs(simulate(body, w0, t, method=method, dt=dt, options={"compensated": True}).omega - exact).max()
            for dt in dts]
    assert min(errs) > 1e-13, "error at round-off level: the fit would be meaningless"
    slope = np.polyfit(np.log(dts), np.log(errs), 1)[0]
    assert abs(slope - p) < 0.5, (method, slope, errs)


def test_quartet_body_matches_closed_form_moments():
    np.testing.assert_array_equal(Inertia.quartet(0.5).moments, quartet_moments(0.5))


# ----------------------------------------------------------------------------- invariants
@pytest.mark.parametrize("method", SPLITTINGS)
@pytest.mark.parametrize("compensated", [False, True], ids=["plain", "compensated"])
def test_casimirs_kept_to_round_off(method, compensated, rng, eps):
    """Compensated storage: the Casimirs stay within a few eps. Plain arithmetic (runs of up to 1e6
    flows by default): the round-off random walk stays below eps sqrt(flows) (measured ~0.15 of it)."""
    inertia, w0 = generic5(rng)
    body = RigidBody(inertia)
    tr = simulate(body, w0, np.linspace(0, 50, 101), method=method, dt=0.01, options={"compensated": compensated})  # 5000 steps
    assert tr.stats["compensated"] is compensated
    c2, c4 = casimirs(tr.L)
    bound = 64 * eps if compensated else eps * np.sqrt(tr.stats["steps"] * tr.stats["flows_per_step"])
    assert np.abs(c2 / c2[0] - 1).max() < bound
    assert np.abs(c4 / c4[0] - 1).max() < 2 * bound
    # and the package's own Casimirs (characteristic polynomial coefficients, eq. 38)
    cas = np.asarray(body.casimirs(tr.omega), dtype=float)
    cas0 = np.asarray(body.casimirs(w0), dtype=float)
    assert cas.shape == (101, 2)
    assert np.all(np.abs(cas - cas0) <= max(1e-13, 4 * bound) * np.abs(cas0))


def test_compensation_rule_and_its_round_off_floor(rng):
    """Automatic choice: plain arithmetic for short runs, compensated beyond 1e6 flows or for
    rtol < 1e-12; compensated storage lowers the round-off floor of the trajectory itself."""
    t = np.linspace(0, 100, 11)
    exact = euler_poinsot(MOM3, W3, t)
    short = simulate(MOM3, W3, t, method="splitting8", dt=0.05)  # 2000 steps x 5 flows
    assert short.stats["compensated"] is False
    long_ = simulate(MOM3, W3, t, method="splitting2", dt=2e-4)  # 5e5 steps x 3 flows > 1e6
    assert long_.stats["compensated"] is True
    assert simulate(MOM3, W3, t[:3], rtol=1e-13).stats["compensated"] is True
    assert simulate(MOM3, W3, t[:3], rtol=1e-10).stats["compensated"] is False
    # splitting8 at dt = 0.05 is converged (truncation << 1e-15): what is left is round-off
    plain = np.abs(short.omega - exact).max()
    comp = np.abs(simulate(MOM3, W3, t, method="splitting8", dt=0.05, options={"compensated": True}).omega - exact).max()
    # compensated: at the reference's own floor (its phase rounds like eps |omega| t), far below plain
    assert comp < 4 * np.finfo(float).eps * (1 + np.abs(W3).max() * t[-1]) * np.abs(exact).max() and comp < plain
    assert plain < 1e-12


def test_energy_error_bounded_without_drift(rng):
    """Symplectic on the orbit: the energy error oscillates, it does not grow (2e5 steps, T = 2000)."""
    inertia, w0 = generic5(rng)
    t = np.linspace(0, 2000, 2001)
    tr = simulate(inertia, w0, t, method="splitting2", dt=0.01)
    rel = np.abs(tr.energy() / tr.energy()[0] - 1)
    early, late = rel[:200].max(), rel[-200:].max()
    assert rel.max() < 1e-3
    assert late < 3 * early, (early, late)


def test_attitude_orthogonal_and_space_momentum_conserved(rng, eps):
    inertia, w0 = generic5(rng)
    for convention in ("paper", "standard"):
        body = RigidBody(inertia, convention=convention)
        tr = simulate(body, w0, np.linspace(0, 30, 61), method="splitting6", dt=0.005, attitude=True)
        T = tr.attitude
        assert T.shape == (61, 5, 5)
        I = np.eye(5)
        assert np.abs(np.swapaxes(T, -1, -2) @ T - I).max() < 2000 * eps  # 6000 steps
        np.testing.assert_allclose(np.linalg.det(T), 1.0, atol=1e-12, rtol=0)
        Lb = body.matrix(tr.L)  # body-frame matrices in the body's convention
        Ls = np.swapaxes(T, -1, -2) @ Lb @ T  # L_space = T^T L_body T
        assert np.abs(Ls - Ls[0]).max() < 1e-12 * np.abs(Lb).max()


def test_attitude_obeys_dT_equals_W_T_in_the_body_convention(rng):
    inertia, w0 = generic5(rng)
    h = 1e-4
    t = np.array([0.0, 1.0 - h, 1.0, 1.0 + h])
    for convention in ("paper", "standard"):
        body = RigidBody(inertia, convention=convention)
        tr = simulate(body, w0, t, method="splitting8", dt=1e-3, attitude=True)
        dT = (tr.attitude[3] - tr.attitude[1]) / (2 * h)
        W = to_matrix(tr.omega[2], convention=convention)
        np.testing.assert_allclose(dT, W @ tr.attitude[2], atol=1e-6, rtol=0)
    # paper = S standard S
    S = np.diag([(-1.0) ** i for i in range(1, 6)])
    Tp = simulate(RigidBody(inertia, convention="paper"), w0, t, method="splitting4", dt=1e-2, attitude=True).attitude
    Ts = simulate(RigidBody(inertia, convention="standard"), w0, t, method="splitting4", dt=1e-2, attitude=True).attitude
    np.testing.assert_allclose(Tp, S @ Ts @ S, atol=1e-15, rtol=0)


def test_initial_attitude_is_used(rng):
    inertia, w0 = generic5(rng)
    Q, _ = np.linalg.qr(rng.normal(size=(5, 5)))
    t = np.linspace(0, 2, 5)
    run = simulate(inertia, w0, t, method="splitting8", dt=0.01, attitude=True)
    a = run.attitude
    b = simulate(inertia, w0, t, method="splitting8", dt=0.01, attitude=Q).attitude
    # dT/dt = W T is linear in T from the right: equal to the round-off of the run's flows
    flows = run.stats["steps"] * run.stats["flows_per_step"]
    np.testing.assert_allclose(b, a @ Q, rtol=0, atol=scaled_tol(1.0, k=4, dim=5, steps=flows))
    c = simulate(inertia, w0, t, method="DOP853", rtol=1e-12, attitude=Q).attitude
    np.testing.assert_allclose(c, b, atol=1e-8, rtol=0)


# ----------------------------------------------------------------------------- batches
@pytest.mark.parametrize("method", ["splitting4", "DOP853"])
def test_batch_equals_loop_over_single_runs(method, rng):
    inertia, _ = generic5(rng)
    w0 = rng.normal(size=(2, 3, 10))
    torque = rng.normal(size=(3, 10)) * 0.1  # broadcasts over the first batch axis
    t = np.linspace(0, 3, 7)
    kw = dict(dt=0.01) if method.startswith("splitting") else dict(rtol=1e-10)
    tr = simulate(inertia, w0, t, method=method, attitude=True, torque=torque, **kw)
    assert tr.omega.shape == (2, 3, 7, 10) and tr.attitude.shape == (2, 3, 7, 5, 5)
    for i in range(2):
        for j in range(3):
            one = simulate(inertia, w0[i, j], t, method=method, attitude=True, torque=torque[j], **kw)
            np.testing.assert_array_equal(tr.omega[i, j], one.omega)
            np.testing.assert_array_equal(tr.attitude[i, j], one.attitude)


def test_threaded_kernels_for_large_ensembles_equal_single_runs(rng):
    """>= 32 bodies: threaded per-body kernel (attitude) and bodies-innermost kernel (no attitude)."""
    inertia, _ = generic5(rng)
    w0 = rng.normal(size=(40, 10))
    t = np.linspace(0, 1, 3)
    with_att = simulate(inertia, w0, t, method="splitting6", dt=0.02, attitude=True)
    without = simulate(inertia, w0, t, method="splitting6", dt=0.02)
    for i in (0, 17, 39):
        one = simulate(inertia, w0[i], t, method="splitting6", dt=0.02, attitude=True)
        np.testing.assert_array_equal(with_att.omega[i], one.omega)
        np.testing.assert_array_equal(with_att.attitude[i], one.attitude)
        np.testing.assert_array_equal(without.omega[i], one.omega)


def test_step_rule_on_an_ensemble_follows_the_fastest_member(rng):
    t = np.linspace(0, 20, 5)
    w0 = np.stack([np.array([0.6, 1.0, -0.5]) * s for s in (0.1, 1.0, 5.0)])
    tr = simulate(MOM3, w0, t, method="splitting8", rtol=1e-9)
    exact = np.stack([euler_poinsot(MOM3, w, t) for w in w0])
    err = np.abs(tr.omega - exact).max(axis=(1, 2)) / np.abs(w0).max(axis=1)
    assert np.all(err < 2e-9), err


# ----------------------------------------------------------------------------- scipy peers
@pytest.mark.parametrize("method", SCIPY)
def test_scipy_methods_agree_with_splitting(method, rng):
    inertia, w0 = generic5(rng)
    body = RigidBody(inertia)
    t = np.linspace(0, 5, 11)
    ref = simulate(body, w0, t, method="splitting8", dt=0.005, attitude=True)
    tr = simulate(body, w0, t, method=method, rtol=1e-10, attitude=True)
    assert tr.stats["method"] == method and tr.stats["nfev"] > 0
    scale = np.abs(w0).max()
    tol = 1e-7 if method in ("DOP853", "RK45") else 1e-5  # LSODA/Radau control the error more loosely
    assert np.abs(tr.omega - ref.omega).max() < tol * scale
    assert np.abs(tr.attitude - ref.attitude).max() < tol * 10


def test_scipy_without_rigidbody_uses_equivalent_rhs(rng):
    inertia, w0 = generic5(rng)
    t = np.linspace(0, 4, 5)
    a = simulate(RigidBody(inertia), w0, t, method="DOP853", rtol=1e-12)
    b = simulate(inertia.moments, w0, t, method="DOP853", rtol=1e-12)
    np.testing.assert_allclose(a.omega, b.omega, atol=1e-10, rtol=0)


# ----------------------------------------------------------------------------- step rule / auto
# order 2 at rtol 1e-11 would need ~1e8 steps: that combination is left out
@pytest.mark.parametrize("method, rtol", [(m, r) for m in SPLITTINGS for r in (1e-5, 1e-8, 1e-11)
                                          if not (m == "splitting2" and r < 1e-8)])
def test_step_rule_reaches_requested_accuracy(method, rtol, eps):
    t = np.linspace(0, 40, 41)
    exact = euler_poinsot(MOM3, W3, t)
    tr = simulate(MOM3, W3, t, method=method, rtol=rtol)
    err = np.abs(tr.omega - exact).max() / np.abs(W3).max()
    assert err <= 2 * rtol + 1e-13, (err, tr.stats)
    # and the rule is not wastefully conservative: error within 1e-4 of the target, or at round-off (a regular
    # orbit's rounding errors grow like eps sqrt(flows), times a few here: splitting10's 5680 flows at rtol 1e-8
    # end 0.8e-13 ... 1.8e-13 away with two rotation formulas equally accurate per flow), or one step per output
    # interval (no fewer are possible: order 10 at rtol 1e-5 gets 1e-10 there)
    roundoff = 16 * eps * np.sqrt(tr.stats["steps"] * tr.stats["flows_per_step"])
    assert err >= 1e-4 * rtol or err < roundoff or tr.stats["steps"] == t.size - 1, (err, roundoff, tr.stats)


def test_auto_method_choice(rng):
    inertia, w0 = generic5(rng)
    t = [0.0, 1.0]
    tr = simulate(inertia, w0, t, rtol=0.1)  # (run to 1e-3, LOOSEST_RTOL, where order 4 is the cheaper)
    assert tr.stats["method"] == "splitting4" and tr.stats["rtol"] == 0.1
    assert simulate(inertia, w0, t, rtol=1e-3).stats["method"] == "splitting4"
    assert simulate(inertia, w0, t, rtol=1e-6).stats["method"] == "splitting8"
    assert simulate(inertia, w0, t, rtol=1e-9).stats["method"] == "splitting8"
    assert simulate(inertia, w0, t).stats["method"] == "splitting8"  # default rtol 1e-9
    assert simulate(inertia, w0, t, rtol=1e-11).stats["method"] == "splitting10"
    assert simulate(inertia, w0, t, dt=0.1).stats["method"] == "splitting4"
    tr = simulate(inertia, w0, t, torque=lambda tt, w: -0.1 * w)
    assert tr.stats["method"] == "DOP853"


# ----------------------------------------------------------------------------- torque
def test_damping_torque_against_time_reparametrised_free_motion():
    """tau = -g L gives L(t) = exp(-g t) L_free(s(t)), s = (1 - exp(-g t))/g (exact)."""
    g = 0.3
    t = np.linspace(0, 6, 13)
    tr = simulate(MOM3, W3, t, method="auto", rtol=1e-11, torque=lambda tt, w: -g * MOM3 * w)
    s = (1 - np.exp(-g * t)) / g
    order = np.argsort(s)
    exact = np.exp(-g * t)[:, None] * euler_poinsot(MOM3, W3, s[order])
    np.testing.assert_allclose(tr.omega, exact, atol=1e-9, rtol=0)


@pytest.mark.parametrize("method", ["splitting2", "splitting4", "splitting8"])
def test_constant_torque_kick_composition(method, rng):
    inertia, w0 = generic5(rng)
    tau = rng.normal(size=10)
    t = np.linspace(0, 3, 4)
    ref = simulate(inertia, w0, t, method="DOP853", rtol=1e-13, torque=tau)
    p = int(method[-1])
    errs = []
    dts = [0.02, 0.01] if p < 8 else [0.5, 0.25]  # order 8: errors ~1e-7 .. 1e-10, far above round-off
    for dt in dts:
        errs.append(np.abs(simulate(inertia, w0, t, method=method, dt=dt, torque=tau).omega - ref.omega).max())
    assert min(errs) > 1e-12, errs
    rate = np.log2(errs[0] / errs[1])
    assert abs(rate - p) < 0.6, (errs, rate)  # the symmetric kick keeps the order


# ----------------------------------------------------------------------------- API and bad input
def test_trajectory_contents(rng):
    inertia, w0 = generic5(rng)
    t = np.linspace(0, 1, 6)
    tr = simulate(RigidBody(inertia), w0, t, method="splitting2", dt=0.05)
    assert isinstance(tr, Trajectory)
    np.testing.assert_array_equal(tr.t, t)
    np.testing.assert_array_equal(tr.omega[0], w0)
    np.testing.assert_allclose(tr.L, tr.omega * inertia.moments, rtol=1e-15)
    assert tr.attitude is None
    assert tr.stats["steps"] == 20 and tr.stats["order"] == 2 and tr.stats["wall_time"] > 0
    assert "splitting2" in repr(tr)
    # a single output time returns the initial state
    one = simulate(inertia, w0, [2.0], method="splitting4")
    np.testing.assert_array_equal(one.omega, w0[None])


def test_moments_from_every_body_kind(rng):
    inertia, w0 = generic5(rng)
    for body in (inertia, RigidBody(inertia), inertia.moments, list(inertia.moments)):
        tr = simulate(body, w0, [0.0], dt=0.1)
        np.testing.assert_array_equal(tr.moments, inertia.moments)


def test_non_uniform_output_grid_hits_output_times():
    t = np.array([0.0, 0.013, 0.5, 0.51, 3.0])
    tr = simulate(MOM3, W3, t, method="splitting8", dt=0.05)
    np.testing.assert_allclose(tr.omega, euler_poinsot(MOM3, W3, t), atol=1e-10, rtol=0)


BAD = [
    (dict(omega0=[np.nan, 1, 2]), ValueError, "finite"),
    (dict(omega0=[1, 2]), ValueError, r"batch \+ \(3,\)"),
    (dict(omega0=3.0), ValueError, "shape"),
    (dict(omega0="abc"), TypeError, "numeric"),
    (dict(method="euler"), ValueError, "allowed: 'auto', 'splitting2'"),
    (dict(t=[0, 1, 1]), ValueError, "strictly monotonic"),
    (dict(t=[0, 2, 1]), ValueError, "strictly monotonic"),
    (dict(t=[[0, 1]]), ValueError, "1-D"),
    (dict(t=[0, np.inf]), ValueError, "finite"),
    (dict(dt=0.0), ValueError, "dt must be finite and > 0"),
    (dict(dt=-1.0), ValueError, "dt must be finite and > 0"),
    (dict(rtol=0.0), ValueError, "rtol"),
    (dict(rtol="tight"), TypeError, "rtol"),
    (dict(method="splitting4", dt=0.1, rtol=1e-6), ValueError, "not both"),
    (dict(method="DOP853", dt=0.1), ValueError, "takes rtol and atol"),
    (dict(method="DOP853", options={"compensated": True}), hr.UnknownOptionError, "unknown option 'compensated'; allowed: 'first_step', 'max_step'"),
    (dict(options={"compensated": "yes"}), TypeError, "True, False or None"),
    (dict(options=["compensated"]), TypeError, "options must be a mapping"),
    (dict(method="splitting4", torque=lambda t, w: w), ValueError, "callable torque"),
    (dict(torque=[1.0, 2.0]), ValueError, "constant torque"),
    (dict(omega0=np.ones((4, 3)), torque=np.ones((3, 3))), ValueError, "inconsistent"),
    (dict(omega0=np.ones((4, 3)), attitude=np.broadcast_to(np.eye(3), (2, 3, 3))), ValueError, "inconsistent"),
    (dict(attitude=np.ones((3, 3))), ValueError, "orthogonal"),
    (dict(attitude=np.eye(4)), ValueError, r"\(3, 3\)"),
    (dict(body=[1.0, 2.0]), ValueError, "N\\(N-1\\)/2"),
    (dict(body=[1.0, -2.0, 3.0]), ValueError, "finite and > 0"),
    (dict(body="rod"), TypeError, "RigidBody"),
]


@pytest.mark.parametrize("kw, exc, match", BAD, ids=[f"bad{i}" for i in range(len(BAD))])
def test_bad_input_gives_clear_errors(kw, exc, match):
    args = dict(body=MOM3, omega0=W3, t=[0.0, 1.0])
    args.update(kw)
    with pytest.raises(exc, match=match):
        simulate(args.pop("body"), args.pop("omega0"), args.pop("t"), **args)


def test_method_list_is_the_registry():
    assert SIMULATION_METHODS == ("auto", *SOLVERS)


@pytest.mark.parametrize("N", [2, 3, 4, 5, 7, 12])
def test_rotation_tables_pair_every_other_axis_with_the_plane_and_its_sign(N):
    """The flow of plane (i, j) rotates the pairs (L_ik, L_jk), k != i, j ascending, with the sign of the matrix
    entries (r, c) -> +-L_(min, max) (built with NumPy since session 46: 4.7 s -> 0.8 s at N = 200); checked against
    the entries of to_matrix of a vector of distinct components."""
    from hyperrotor.classical.solvers._kernels import rotation_tables
    from hyperrotor.conventions import planes, to_matrix

    pair_p, pair_q, pair_s, plane_i, plane_j = rotation_tables(N)
    n = N * (N - 1) // 2
    comps = np.arange(1.0, n + 1.0)  # component a has the value a + 1
    M = to_matrix(comps, convention="standard")
    for a, (i, j) in enumerate(planes(N)):
        assert (plane_i[a], plane_j[a]) == (i - 1, j - 1)
        ks = [k for k in range(N) if k not in (i - 1, j - 1)]
        for col, k in enumerate(ks):
            assert comps[pair_p[a, col]] == abs(M[i - 1, k]) and comps[pair_q[a, col]] == abs(M[j - 1, k])
            assert pair_s[a, col] == np.sign(M[i - 1, k]) * np.sign(M[j - 1, k])
    assert pair_p.shape == (n, N - 2) and all(not x.flags.writeable for x in (pair_p, pair_q, pair_s))


@pytest.mark.parametrize("N", [3, 4, 6])
def test_the_coupled_triples_of_the_rate_bound_are_every_triangle_of_planes(N):
    """Each triple {ij, ik, jk}, i < j < k, once with each of its planes as c (the other two as a, b; built with
    NumPy since session 46: 2 s -> 0.5 s at N = 200)."""
    import itertools

    from hyperrotor.classical.solvers.step_control import _triples
    from hyperrotor.conventions import plane_index

    c, a, b = _triples(N)
    want = []
    for i, j, k in itertools.combinations(range(1, N + 1), 3):
        t = [plane_index(p, N) for p in ((i, j), (i, k), (j, k))]
        want += [(t[0], t[1], t[2]), (t[1], t[0], t[2]), (t[2], t[0], t[1])]
    assert list(zip(c.tolist(), a.tolist(), b.tolist())) == want
