"""Lyapunov exponents: tangent map, integrable vs generic bodies, spectrum structure, scale-out."""
import math
import re

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import hyperrotor as hr
from hyperrotor._options import options
from hyperrotor.classical import chaos
from hyperrotor.classical.solvers import _tangent_kernels
from hyperrotor.classical.chaos import lyapunov, lyapunov_sweep
from interrupted_child import interrupted

from tolerance import EPS
N5, n5 = 5, 10


def generic_5d(seed, M, L_norm=3.0):
    """A 5D body with ten moments log-uniform in [0.3, 3] and M momenta of norm ~3 (random directions)."""
    g = np.random.default_rng(seed)
    moments = np.exp(g.uniform(math.log(0.3), math.log(3.0), n5))
    L = g.standard_normal((M, n5))
    L *= L_norm / np.linalg.norm(L, axis=1, keepdims=True)
    return moments, L / moments


# ----------------------------------------------------------------------------
# independent reference: Euler equations and their linearisation as matrices, scipy DOP853
# ----------------------------------------------------------------------------
def _mat(v, N):
    iu = np.triu_indices(N, 1)
    A = np.zeros(v.shape[:-1] + (N, N))
    A[..., iu[0], iu[1]] = v
    return A - np.swapaxes(A, -1, -2)


def scipy_benettin(moments, omega0, T, seed):
    """Maximal exponents of the orbits omega0 (M, n): dL/dt = Om L - L Om (plain matrices,
    Om_ij = L_ij / I_ij), tangent d(dL)/dt = dOm L + Om dL - dL Om - L dOm, renormalised
    every time unit (Benettin); all orbits stacked in one solve_ivp system."""
    n = moments.size
    N = int(round((1 + math.sqrt(1 + 8 * n)) / 2))
    iu = np.triu_indices(N, 1)
    Imat = np.abs(_mat(moments, N)) + np.eye(N)
    M = omega0.shape[0]

    def rhs(_t, y):
        Y = y.reshape(2, M, n)
        L, D = _mat(Y[0], N), _mat(Y[1], N)
        Om, dOm = L / Imat, D / Imat
        dL = Om @ L - L @ Om
        dD = dOm @ L + Om @ D - D @ Om - L @ dOm
        return np.stack([dL[..., iu[0], iu[1]], dD[..., iu[0], iu[1]]]).ravel()

    L = omega0 * moments
    D = np.random.default_rng(seed).standard_normal((M, n))
    D /= np.linalg.norm(D, axis=1, keepdims=True)
    acc = np.zeros(M)
    steps = int(round(T))
    for k in range(steps):
        sol = solve_ivp(rhs, (k, k + 1.0), np.stack([L, D]).ravel(), method="DOP853", rtol=1e-9, atol=1e-9)
        Y = sol.y[:, -1].reshape(2, M, n)
        L, D = Y[0], Y[1]
        nrm = np.linalg.norm(D, axis=1)
        acc += np.log(nrm)
        D = D / nrm[:, None]
    return acc / steps


# ----------------------------------------------------------------------------
# the tangent map of one step is the derivative of the step map
# ----------------------------------------------------------------------------
@pytest.mark.parametrize("jitted", [True, False], ids=["jit", "python"])
@pytest.mark.parametrize("order", [2, 4])
def test_tangent_map_is_derivative_of_step_map(jitted, order):
    moments, w0 = generic_5d(11, 1)
    L0 = w0 * moments
    word = chaos.splitting_word(order, tuple(range(n5)))
    pp, pq, ps = chaos.rotation_tables(N5)[:3]
    rates = (1.0 / moments - chaos.casimir_shift(moments, L0)[0])[None]
    kernel = _tangent_kernels.tangent_run if jitted else getattr(_tangent_kernels.tangent_run, "py_func",
                                                                  _tangent_kernels.tangent_run)
    nsteps = 4 if not jitted else 40

    def run(L):
        out, Lo, Wo = np.zeros((1, 1, n5)), np.empty((1, n5)), np.empty((1, n5, n5))
        kernel(L, rates, np.eye(n5)[None], np.zeros((1, n5)), word[0], word[1], pp, pq, ps, np.array([0.05]),
               np.array([nsteps], dtype=np.int64), 1, 1, False, out, Lo, Wo)
        return Lo[0], Wo[0]

    _, J = run(L0)  # row j: derivative of the final L along e_j
    step = 1e-6
    J_fd = np.empty((n5, n5))
    for j in range(n5):
        d = np.zeros((1, n5))
        d[0, j] = step
        J_fd[j] = (run(L0 + d)[0] - run(L0 - d)[0]) / (2 * step)
    # central differences: truncation ~ step^2 |L'''| and round-off ~ eps |L| / step
    assert np.abs(J - J_fd).max() < 1e-7 * max(1.0, np.abs(J).max())
    # the map is volume-preserving: each plane flow's Jacobian is a rotation plus a nilpotent rank-one term
    assert abs(np.linalg.det(J) - 1.0) < 1e3 * EPS * np.linalg.norm(J) ** n5


def test_python_and_compiled_kernels_agree():
    if not hasattr(_tangent_kernels.tangent_run, "py_func"):
        pytest.skip("JIT disabled: one path only")
    moments, w0 = generic_5d(5, 2)
    L0 = w0 * moments
    word = chaos.splitting_word(4, tuple(range(n5)))
    tables = chaos.rotation_tables(N5)[:3]
    rates = 1.0 / moments - chaos.casimir_shift(moments, L0)[:, None]
    W0 = np.broadcast_to(np.eye(n5)[:3], (2, 3, n5)).copy()
    res = []
    for kern in (_tangent_kernels.tangent_run, _tangent_kernels.tangent_run.py_func):
        out, Lo, Wo = np.zeros((2, 2, 3)), np.empty((2, n5)), np.empty((2, 3, n5))
        kern(L0, rates, W0, np.zeros((2, 3)), word[0], word[1], *tables, np.array([0.02, 0.03]),
             np.array([5, 4], dtype=np.int64), 4, 2, True, out, Lo, Wo)
        res.append(out)
    assert np.allclose(res[0], res[1], rtol=0, atol=1e3 * EPS)


@pytest.mark.parametrize("k", [1, 4])
def test_lanes_kernel_is_bit_identical_to_one_body_kernel_and_to_time_segments(k):
    """The bodies-innermost kernel used for ensembles performs each orbit's arithmetic exactly
    as the one-body kernel (so grouping orbits into blocks cannot change a result)."""
    moments, w0 = generic_5d(17, 9)
    L0 = w0 * moments
    L0[:2] *= 15.0  # half-angles beyond 0.5 for some orbits: the libm branch of sincos
    word = chaos.splitting_word(8, tuple(range(n5)))
    tables = chaos.rotation_tables(N5)[:3]
    rates = 1.0 / moments - chaos.casimir_shift(moments, L0)[:, None]
    W0 = np.linalg.qr(np.random.default_rng(3).standard_normal((9, n5, k)))[0].transpose(0, 2, 1).copy()
    h, nsub = np.full(9, 0.04), np.full(9, 5, dtype=np.int64)
    results = []
    for kern, extra in ((_tangent_kernels.tangent_run, (True,)), (_tangent_kernels.tangent_run_lanes, (4,))):
        out, Lo, Wo = np.zeros((9, 3, k)), np.empty((9, n5)), np.empty((9, k, n5))
        kern(L0, rates, W0, np.zeros((9, k)), word[0], word[1], *tables, h, nsub, 6, 2, *extra, out, Lo, Wo)
        results.append((out, Lo, Wo))
        # the same run in two time segments (4 + 2 renormalisations), the second continuing from the first's
        # final states and sums: bit for bit the one call (a long orbit is cut like this, chaos._benettin)
        out1, Lo1, Wo1 = np.zeros((9, 2, k)), np.empty((9, n5)), np.empty((9, k, n5))
        kern(L0, rates, W0, np.zeros((9, k)), word[0], word[1], *tables, h, nsub, 4, 2, *extra, out1, Lo1, Wo1)
        out2, Lo2, Wo2 = np.zeros((9, 1, k)), np.empty((9, n5)), np.empty((9, k, n5))
        kern(Lo1, rates, Wo1, out1[:, -1].copy(), word[0], word[1], *tables, h, nsub, 2, 2, *extra, out2, Lo2, Wo2)
        for a, b in zip((out, Lo, Wo), (np.concatenate([out1, out2], axis=1), Lo2, Wo2)):
            assert np.array_equal(a, b)
    for a, b in zip(*results):
        assert np.array_equal(a, b)


# ----------------------------------------------------------------------------
# integrable bodies: exponents ~ log T / T
# ----------------------------------------------------------------------------
def _integrable_cases():
    g = np.random.default_rng(2026)
    tops = [(hr.Inertia(g.uniform(0.5, 3.0, 3)), g.standard_normal((6, 3))) for _ in range(2)]
    manakov = []
    for _ in range(2):
        body = hr.Inertia.from_mass_tensor(g.uniform(0.2, 1.5, 5))
        L = g.standard_normal((6, n5))
        L *= 3.0 / np.linalg.norm(L, axis=1, keepdims=True)
        manakov.append((body, L / body.moments))
    return tops + manakov


@pytest.mark.parametrize("case", range(4), ids=["top-a", "top-b", "manakov-a", "manakov-b"])
def test_integrable_exponents_decay_like_log_t_over_t(case):
    body, w0 = _integrable_cases()[case]
    T = 400.0
    res = lyapunov(body, w0, T, history=True, rng=case)
    t, lam = res.t, res.history
    assert lam.shape == (w0.shape[0], t.size)
    assert np.all(lam[:, -1] < 0.03)
    # linear growth of tangent vectors, |dL(t)| ~ a t: lambda(t) t = log t + c(t) with c bounded
    # (quasi-periodic wobble of a few units); a chaotic orbit adds lambda * t (next test)
    late = t >= 25.0
    drift = lam[:, late] * t[late] - np.log(t[late])
    assert np.all(drift.max(axis=1) < 2.0), drift.max(axis=1)
    assert np.all(np.ptp(drift, axis=1) < 4.0), np.ptp(drift, axis=1)
    assert np.all(lam[:, -1] * T / math.log(T) < 1.5)


def test_generic_body_is_not_log_t_over_t():
    moments, w0 = generic_5d(1, 8)
    res = lyapunov(moments, w0, 200.0, history=True, rng=0)
    t, lam = res.t, res.history
    late = t >= 25.0
    drift = lam[:, late] * t[late] - np.log(t[late])
    assert np.median(np.ptp(drift, axis=1)) > 20.0


# ----------------------------------------------------------------------------
# generic bodies: positive exponents, mean agrees with an independent variational computation
# ----------------------------------------------------------------------------
@pytest.mark.slow
def test_generic_mean_agrees_with_scipy_variational():
    moments, w0 = generic_5d(3, 32)
    T = 100.0
    ours = lyapunov(moments, w0, T, rng=4).exponents
    ref = scipy_benettin(moments, w0, T, seed=5)
    assert np.mean(ours) > 0.2 and np.mean(ref) > 0.2
    # the two estimates of each orbit's finite-time exponent differ by the choice of tangent
    # vector and by the decorrelation of chaotic orbits: compare the means with their standard error
    diff = ours - ref
    se = np.std(diff, ddof=1) / math.sqrt(diff.size)
    assert abs(np.mean(diff)) < 4.0 * se + 0.02, (np.mean(ours), np.mean(ref), se)
    # and the distributions: same median within the spread
    assert abs(np.median(ours) - np.median(ref)) < 0.5 * np.std(ref)


# ----------------------------------------------------------------------------
# full spectrum: +/- pairs and four zeros (two Casimirs, flow and energy) for so(5)
# ----------------------------------------------------------------------------
def test_spectrum_pairs_and_zeros():
    moments, w0 = generic_5d(7, 3)
    T = 400.0
    spec = lyapunov(moments, w0, T, spectrum=True, rng=8).exponents
    assert spec.shape == (3, n5)
    # volume preservation: the exponents sum to zero up to round-off of the log-sums
    assert np.all(np.abs(spec.sum(axis=1)) < 1e3 * EPS * n5 * np.abs(spec).max())
    pair_sums = spec + spec[:, ::-1]
    assert np.all(np.abs(pair_sums) < 4 * math.log(T) / T), pair_sums
    middle = spec[:, 3:7]
    assert np.all(np.abs(middle) < 4 * math.log(T) / T), middle
    # mixed phase space: a regular orbit has all exponents ~0; at least one of these is chaotic
    assert spec[:, 0].max() > 10 * math.log(T) / T


def test_spectrum_k_leading_matches_full_spectrum_start():
    moments, w0 = generic_5d(9, 2)
    full = lyapunov(moments, w0, 50.0, spectrum=True, rng=1).exponents
    three = lyapunov(moments, w0, 50.0, spectrum=3, rng=1).exponents
    assert three.shape == (2, 3)
    # Gram-Schmidt: the first vectors do not see the later ones, so the three are the full spectrum's first three,
    # but from other random starts (the same seed draws other vectors for another k): finite-time exponents from
    # different frames differ by O(log / T) (the projections of the start on the Oseledets directions)
    T = 50.0
    np.testing.assert_array_less(np.abs(three - full[:, :3]), 2 * math.log(T) / T)
    assert np.all(np.diff(three, axis=1) <= 0) and np.all(three[:, 0] > 0.1)  # ordered; a chaotic orbit leads


# ----------------------------------------------------------------------------
# shapes, reproducibility, sweeps, errors
# ----------------------------------------------------------------------------
def test_shapes_and_seeded_reproducibility():
    moments, w0 = generic_5d(2, 4)
    one = lyapunov(moments, w0[0], 20.0, rng=3)
    assert isinstance(one, chaos.LyapunovResult) and one.exponents.shape == () and one.history is None
    assert float(one) == one.exponents and one.t.tolist() == [20.0] and one.k == 1
    # reproducible by default: the documented default seed 0, rng= varies the tangent vectors
    assert np.array_equal(lyapunov(moments, w0, 20.0).exponents, lyapunov(moments, w0, 20.0, rng=0).exponents)
    assert not np.array_equal(lyapunov(moments, w0, 20.0).exponents, lyapunov(moments, w0, 20.0, rng=1).exponents)
    many = lyapunov(moments, w0.reshape(2, 2, n5), 20.0, rng=3).exponents
    assert many.shape == (2, 2)
    again = lyapunov(moments, w0.reshape(2, 2, n5), 20.0, rng=3).exponents
    assert np.array_equal(many, again)
    res = lyapunov(moments, w0, 20.0, history=True, renorm_interval=2.0, rng=3)
    t, hist = res.t, res.history
    np.testing.assert_array_equal(t, np.arange(2.0, 21.0, 2.0))  # (sums of 2.0: exact)
    assert hist.shape == (4, 10)


@pytest.mark.parametrize("workers,chunk_size", [(1, None), (2, 1), (2, 3), (None, 7)])
def test_chunking_is_bit_identical(monkeypatch, workers, chunk_size):
    moments, w0 = generic_5d(4, 12)
    ref = lyapunov(moments, w0, 40.0, rng=6, chunk_size=12).exponents
    if workers is not None:
        monkeypatch.setattr(chaos._parallel, "default_workers", lambda: workers)
    out = lyapunov(moments, w0, 40.0, rng=6, chunk_size=chunk_size).exponents
    assert np.array_equal(out, ref)


@pytest.mark.parametrize("history", [False, True])
@pytest.mark.parametrize("spectrum", [False, 3])
@pytest.mark.parametrize("chunk_seconds", [1e-4, 3e-7], ids=["renormalisations", "pieces"])
def test_a_long_orbit_runs_in_time_segments_bit_for_bit(monkeypatch, history, spectrum, chunk_seconds):
    """An orbit longer than options["chunk_seconds"] goes on in segments of whole renormalisations, and a
    renormalisation longer than that in pieces of its steps (Ctrl-C and progress between them): the same exponents
    and history as one call, for one orbit and for several."""
    moments, w0 = generic_5d(4, 3)
    kw = dict(spectrum=spectrum, history=history, renorm_interval=0.5, rng=6)
    for omega0 in (w0[0], w0):
        ref = lyapunov(moments, omega0, 20.0, **kw)
        calls = []  # (renormalisations, whether the call ends with the Gram-Schmidt step) of every call
        real = chaos._parallel.map_rows
        monkeypatch.setattr(chaos._parallel, "map_rows",
                            lambda *a, **k: calls.append((k["args"][5], k["args"][-1])) or real(*a, **k))
        with hr.options(chunk_seconds=chunk_seconds):  # 1e-4: ~1.5e4 work units per segment, a few renormalisations
            cut = lyapunov(moments, omega0, 20.0, **kw)
        monkeypatch.setattr(chaos._parallel, "map_rows", real)
        assert len(calls) > 3 and sum(r for r, last in calls if last) == 40  # all 40 renormalisations, once each
        if chunk_seconds < 1e-6:  # 45 work units per piece: every renormalisation in pieces of a few steps
            assert sum(not last for _, last in calls) >= 40 and all(r == 1 for r, _ in calls)
        else:
            assert all(last for _, last in calls)
        assert np.array_equal(cut.exponents, ref.exponents) and np.array_equal(cut.t, ref.t)
        assert (cut.history is None) == (not history)
        if history:
            assert np.array_equal(cut.history, ref.history)


@pytest.mark.parametrize("spectrum", [False, True])
def test_tangent_vectors_leaving_double_precision_are_an_error_not_nan(spectrum):
    """A chaotic orbit (lambda ~ 0.6) renormalised every 2000 time units: the tangent vectors grow like
    exp(1200) (and the contracting ones shrink like exp(-1200)) between renormalisations. Before: NaN exponents,
    silently. Now a ValueError naming renorm_interval and a length that works; that length gives finite exponents."""
    m = np.exp(np.random.default_rng(1).uniform(math.log(0.3), math.log(3.0), n5))
    with pytest.raises(ValueError, match=r"renorm_interval = 2000\.0.*about 100 / w_max = ([0-9.]+) or less") as err:
        lyapunov(m, np.ones(n5), 4000.0, renorm_interval=2000.0, spectrum=spectrum)
    hint = float(re.search(r"100 / w_max = ([0-9.e+-]+)", str(err.value)).group(1))
    ok = lyapunov(m, np.ones(n5), 4 * hint, renorm_interval=hint, spectrum=spectrum).exponents
    assert np.all(np.isfinite(ok)) and np.max(ok) > 0.1  # the chaotic orbit's positive exponent


@pytest.mark.slow
def test_ctrl_c_interrupts_one_long_orbit_promptly():
    """SIGINT during the Benettin run of ONE long orbit (one compiled call before the time segments: the signal
    waited for its end, 39 s): KeyboardInterrupt within about one segment (options["chunk_seconds"] = 0.25 s)."""
    code = (
        "import numpy as np, signal, sys, time, hyperrotor as hr\n"
        "m = np.exp(np.random.default_rng(1).uniform(np.log(0.3), np.log(3.0), 10))\n"
        "hr.lyapunov(m, np.ones(10), 1.0)  # JIT\n"
        "got = []\n"
        "signal.signal(signal.SIGINT, lambda *a: (got.append(time.perf_counter()), signal.default_int_handler(*a)))\n"
        "print('running', flush=True)\n"
        "try:\n"
        "    hr.lyapunov(m, np.ones(10), 2e5, spectrum=True)\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', f'{time.perf_counter() - got[0]:.3f}', flush=True)\n"
        "    sys.exit(3)\n"
    )
    word, delay = interrupted(code, wait=1.5).split()
    assert word == "interrupted"
    assert float(delay) < 2.0, delay  # generous for a loaded machine: the segment is 0.25 s of work


@pytest.mark.slow
def test_ctrl_c_stops_one_long_renormalisation_promptly():
    """SIGINT during ONE renormalisation of ONE orbit (a regular orbit, renorm_interval = T, ~7 s of work): the
    caller gets KeyboardInterrupt at once (map_rows waits interruptibly) and the process exits within about one
    piece of the renormalisation (0.25 s of work); before the pieces, the compiled call went on to its end in the
    background and the interpreter waited for it at exit (5.6 s after the signal)."""
    code = (
        "import atexit, numpy as np, signal, sys, time, hyperrotor as hr\n"
        "m, w = np.array([2.0, 3.0, 4.0]), np.array([0.6, 1.0, -0.5])\n"
        "hr.lyapunov(m, w, 1.0)  # JIT\n"
        "got = []\n"
        "signal.signal(signal.SIGINT, lambda *a: (got.append(time.perf_counter()), signal.default_int_handler(*a)))\n"
        "atexit.register(lambda: print('exited', f'{time.perf_counter() - got[0]:.3f}', flush=True))  # (after the "
        "threads)\n"
        "print('running', flush=True)\n"
        "try:\n"
        "    hr.lyapunov(m, w, 2e6, renorm_interval=2e6, spectrum=True)\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', f'{time.perf_counter() - got[0]:.3f}', flush=True)\n"
        "    sys.exit(3)\n"
    )
    word, delay, ended, exit_delay = interrupted(code, wait=1.5).split()
    assert (word, ended) == ("interrupted", "exited")
    assert float(delay) < 1.0 and float(exit_delay) < 2.0, (delay, exit_delay)  # generous for a loaded machine


def test_sweep_rows_equal_single_body_calls():
    g = np.random.default_rng(12)
    bodies = np.exp(g.uniform(math.log(0.3), math.log(3.0), (3, n5)))
    _, w0 = generic_5d(13, 4)
    sweep = lyapunov_sweep(bodies, w0, 10.0, rng=2).exponents
    assert sweep.shape == (3, 4)
    # the first body's orbits draw the first tangent vectors of the same generator
    first = lyapunov(bodies[0], w0, 10.0, rng=2).exponents
    assert np.allclose(sweep[0], first, rtol=1e-9, atol=0)
    per_body = lyapunov_sweep([hr.Inertia(b) for b in bodies], np.stack([w0] * 3), 10.0, rng=2).exponents
    assert np.array_equal(per_body, sweep)


@pytest.mark.parametrize("kwargs, exc, words", [
    (dict(omega0=np.ones(9)), ValueError, r"omega0 must have shape \(10,\)"),
    (dict(omega0=[np.nan] * 10), ValueError, "finite"),
    (dict(T=-1.0), ValueError, "T must be finite and > 0"),
    (dict(method="RK45"), ValueError, "splitting6"),
    (dict(spectrum=11), ValueError, "spectrum"),
    (dict(spectrum=2.5), TypeError, "spectrum"),
    (dict(dt=0.0), ValueError, "dt"),
    (dict(client=object()), TypeError, "dask.distributed.Client"),
])
def test_bad_arguments_are_named(kwargs, exc, words):
    moments, w0 = generic_5d(0, 1)
    args = dict(omega0=w0[0], T=1.0)
    args.update(kwargs)
    with pytest.raises(exc, match=words):
        lyapunov(moments, args.pop("omega0"), args.pop("T"), **args)


@pytest.mark.parametrize("k", [-600, -3, 5, 900])
def test_scale_invariance_is_exact_for_powers_of_two(k):
    """omega -> s omega, t -> t / s leaves the motion unchanged, so lambda -> s lambda; the kernel
    works on each orbit scaled by a power of two, so this holds bit for bit, without overflow or
    underflow even for |omega| ~ 1e270 or 1e-180."""
    moments, w0 = generic_5d(19, 3)
    s = 2.0 ** k
    ref = lyapunov(moments, w0, 20.0, rng=5).exponents
    scaled = lyapunov(moments, s * w0, 20.0 / s, renorm_interval=1.0 / s, rng=5).exponents
    assert np.array_equal(scaled, s * ref)


def test_huge_angular_velocity_is_refused_by_the_budget():
    moments, w0 = generic_5d(0, 1)
    with pytest.raises(ValueError, match="lyapunov_max_work"):
        lyapunov(moments, 1e300 * w0[0], 1.0)
    with pytest.raises(ValueError, match="max_steps"):
        hr.poincare_section(moments, 1e300 * w0[0], 1.0)


def test_budget_refuses_with_estimate():
    moments, w0 = generic_5d(0, 2)
    with options(lyapunov_max_work=1e5):
        with pytest.raises(ValueError, match="lyapunov_max_work"):
            lyapunov(moments, w0, 100.0)


def test_a_refusal_comes_before_the_casimir_shift(monkeypatch):
    """The budget is checked with the fewest planes a shift can leave before the shift rule runs (a review: 2e6
    identical orbits took 11.6 s to be refused, in np.unique and the shift rule)."""
    def shift_not_allowed(*args, **kwargs):
        raise AssertionError("the Casimir shift ran before the budget was checked")

    moments, w0 = generic_5d(0, 2)
    monkeypatch.setattr(chaos, "casimir_shift", shift_not_allowed)
    with options(lyapunov_max_work=1e5):
        with pytest.raises(ValueError, match="lyapunov_max_work"):
            lyapunov(moments, w0, 100.0)
        with pytest.raises(ValueError, match="lyapunov_max_work"):
            lyapunov_sweep(np.stack([moments, moments[::-1]]), w0, 100.0)


@pytest.mark.parametrize("moments, fewest", [
    (np.full(10, 2.0), 0),                       # a sphere: every plane drops out
    (hr.Inertia.quartet(0.5).moments, 4),        # six planes of one moment
    (np.arange(1.0, 11.0), 9),                   # all distinct
    (np.array([1.0, 2.0, 2.0, 3.0, 3.0, 3.0]), 3),
])
def test_fewest_planes_is_n_minus_the_most_planes_of_one_rate(moments, fewest):
    rates = 1.0 / moments
    assert chaos._fewest_planes(moments[None, :]) == fewest == moments.size - max(np.sum(rates == r) for r in rates)
    # several bodies: the largest of their counts (a lower bound on the planes of the ensemble's one word)
    assert chaos._fewest_planes(np.stack([np.full(moments.size, 2.0), moments])) == fewest


def test_too_short_a_run_is_refused_not_round_off():
    """T * w_max below LEAST_TURN: the growth 1 + O(T w_max) drowns in round-off (T = 1e-17 gave -11.1 where the
    exponent is ~1.13); at the shortest T the message advises, the exponent is still resolved."""
    moments, w0 = generic_5d(0, 1)
    w_top = float(np.max(chaos.rate_bound(moments[None, :], w0 * moments)))
    with pytest.raises(ValueError, match=r"T = 1e-17 is too short .* use T >= 1e-09 / w_max = "):
        lyapunov(moments, w0[0], 1e-17)
    with pytest.raises(ValueError) as shorter:
        lyapunov(moments, w0[0], 1e-12)
    T_least = float(re.search(r"w_max = ([0-9.e+-]+)$", str(shorter.value)).group(1))
    assert T_least == pytest.approx(chaos.LEAST_TURN / w_top, rel=1e-2)
    short, longer = float(lyapunov(moments, w0[0], T_least)), float(lyapunov(moments, w0[0], 1000 * T_least))
    assert abs(short - longer) <= 1e-4 * w_top, (short, longer, w_top)
    with pytest.raises(ValueError, match="too short"):  # the sweep: the fastest orbit decides
        lyapunov_sweep(moments[None, :], w0, T_least / 10)


def test_budget_counts_only_the_threads_a_run_can_use(monkeypatch):
    """An orbit runs on one thread: one orbit on 8 worker threads gets one thread's budget (a review: an 8-thread
    cluster let a single orbit through for 8x the budget); 8 orbits in chunks of one get all eight."""
    from hyperrotor import _parallel

    monkeypatch.setattr(_parallel, "default_workers", lambda: 8)
    moments, w0 = generic_5d(0, 8)
    with options(lyapunov_max_work=1.0):
        with pytest.raises(ValueError) as one:
            lyapunov(moments, w0[0], 50.0)
    work = one.value.needed  # (one orbit: its whole work, on one thread)
    assert "1 worker thread(s)" in str(one.value)
    with options(lyapunov_max_work=work / 2):
        with pytest.raises(ValueError, match="1 worker thread"):
            lyapunov(moments, w0[0], 50.0)
    with options(lyapunov_max_work=1.0):
        with pytest.raises(ValueError) as eight:
            lyapunov(moments, w0, 50.0, chunk_size=1)
    assert "8 worker thread(s)" in str(eight.value)
    with options(lyapunov_max_work=1.0):
        with pytest.raises(ValueError, match="2 worker thread"):  # (8 orbits in 2 chunks)
            lyapunov(moments, w0, 50.0, chunk_size=4)
    with pytest.raises(ValueError, match="chunk_size"):
        lyapunov(moments, w0, 50.0, chunk_size=0)


def test_sweep_rejects_mixed_dimensions():
    with pytest.raises(ValueError, match="same dimension"):
        lyapunov_sweep([[1.0, 2.0, 3.0], np.ones(10)], np.ones((1, 3)), 1.0)


# ----------------------------------------------------------------------------
# scale-out: a LocalCluster of two worker processes gives the in-process numbers
# ----------------------------------------------------------------------------
def test_client_equals_in_process(dask_client):
    client = dask_client
    moments, w0 = generic_5d(21, 10)
    T = 30.0
    local = lyapunov(moments, w0, T, rng=9).exponents
    remote = lyapunov(moments, w0, T, rng=9, client=client, chunk_size=3).exponents
    assert np.array_equal(remote, local)
    spec_local = lyapunov(moments, w0[:3], T, spectrum=True, rng=9).exponents
    spec_remote = lyapunov(moments, w0[:3], T, spectrum=True, rng=9, client=client).exponents
    assert np.array_equal(spec_remote, spec_local)


def test_sweep_on_client_equals_in_process(dask_client):
    client = dask_client
    g = np.random.default_rng(22)
    bodies = np.exp(g.uniform(math.log(0.3), math.log(3.0), (2, n5)))
    _, w0 = generic_5d(23, 5)
    local = lyapunov_sweep(bodies, w0, 20.0, rng=1).exponents
    remote = lyapunov_sweep(bodies, w0, 20.0, rng=1, client=client).exponents
    assert remote.shape == (2, 5)
    assert np.array_equal(remote, local)


def test_methods_come_from_the_solver_registry():
    """LYAPUNOV_METHODS is derived from hr.SOLVERS (the solvers with tangent maps), with their orders."""
    expected = tuple(name for name, cls in hr.SOLVERS.items() if cls.tangent)
    assert chaos.LYAPUNOV_METHODS == expected == ("splitting2", "splitting4", "splitting6", "splitting8", "splitting10")
    assert lyapunov(*generic_5d(0, 1), 1.0, method="SPLITTING4").method == "splitting4"  # any case
