"""Tests of the rotor Hamiltonian (hyperrotor.quantum.hamiltonian): Hamiltonians, evolution methods, symmetry blocks, spectra.

Independent references: tiny so(N) representations built here (the vector
representation E_(ij) = e_i e_j^T - e_j e_i^T and the so(3) spin-l matrices of
QuTiP mapped to planes by J1 = L^23, J2 = -L^13, J3 = L^12), dense ``expm``,
and closed-form spectra derived in the docstrings of the tests.
"""

import numpy as np
import pytest
import qutip
import scipy.linalg as sla
import scipy.sparse as sps

import hyperrotor

from hyperrotor.conventions import planes
from hyperrotor.quantum import evolve, rotor_hamiltonian, spectrum, symmetry_blocks
from tolerance import scaled_tol


# ----------------------------------------------------------------------------
# private tiny representations (duck-typed like hyperrotor.quantum.Representation)
# ----------------------------------------------------------------------------
class _Rep:
    def __init__(self, N, gens, highest_weight):
        self.N = N
        self._gens = {p: sps.csr_matrix(g) for p, g in gens.items()}
        self.dim = next(iter(self._gens.values())).shape[0]
        self.highest_weight = tuple(highest_weight)

    def generator(self, plane):
        return self._gens[tuple(plane)]

    def hermitian(self, plane, hbar=1.0):
        return (-1j * hbar) * self._gens[tuple(plane)]

    def generators(self):
        return dict(self._gens)


def _vector_rep(N):
    gens = {}
    for i, j in planes(N):
        E = np.zeros((N, N))
        E[i - 1, j - 1], E[j - 1, i - 1] = 1.0, -1.0
        gens[(i, j)] = E
    return _Rep(N, gens, (1,) + (0,) * (N // 2 - 1))


def _spin_rep(l):
    J1, J2, J3 = (qutip.jmat(l, c).full() for c in "xyz")
    # G = i L_hat / hbar with L^23 = J1, L^13 = -J2, L^12 = J3
    return _Rep(3, {(1, 2): 1j * J3, (1, 3): -1j * J2, (2, 3): 1j * J1}, (l,))


def _direct_sum(*reps):
    N = reps[0].N
    gens = {p: sps.block_diag([r.generator(p) for r in reps], format="csr") for p in planes(N)}
    return _Rep(N, gens, reps[0].highest_weight)


def _random_state(rng, dim):
    v = rng.normal(size=dim) + 1j * rng.normal(size=dim)
    return v / np.linalg.norm(v)


def _states(result):
    return np.array([s.full().ravel() for s in result.states])


def _exact(H, psi, times, hbar=1.0):
    Hd = H.full() if isinstance(H, qutip.Qobj) else np.asarray(H)
    return np.array([sla.expm(-1j * Hd * (t - times[0]) / hbar) @ psi for t in times])


# ----------------------------------------------------------------------------
# rotor_hamiltonian
# ----------------------------------------------------------------------------
@pytest.mark.parametrize("N", [3, 4, 5, 6])
def test_vector_rep_hamiltonian_is_diagonal_closed_form(N, rng):
    """Vector rep: -E_ij^2 projects on span(e_i, e_j), so H = diag_k sum_{j != k} 1/(2 I_kj)."""
    moments = rng.uniform(0.5, 3.0, size=N * (N - 1) // 2)
    H = rotor_hamiltonian(_vector_rep(N), moments, hbar=1.0).full()
    I = {p: m for p, m in zip(planes(N), moments)}
    expected = [sum(1 / (2 * I[tuple(sorted((k, j)))]) for j in range(1, N + 1) if j != k) for k in range(1, N + 1)]
    # a sum of N(N-1)/2 products of N x N generators: round-off ~ (number of planes) N eps max|H|
    np.testing.assert_allclose(H, np.diag(expected), atol=scaled_tol(max(expected), dim=N, k=4 * len(moments)), rtol=0)


def test_hamiltonian_scales_with_hbar_squared(rng):
    moments = rng.uniform(1, 2, size=3)
    rep = _spin_rep(2)
    H1 = rotor_hamiltonian(rep, moments).full()
    H2 = rotor_hamiltonian(rep, moments, hbar=0.3).full()
    np.testing.assert_allclose(H2, 0.09 * H1, rtol=0, atol=scaled_tol(H1, k=4 * len(moments)))
    assert np.allclose(H1, H1.conj().T, rtol=0, atol=scaled_tol(H1, k=4 * len(moments)))


def test_hamiltonian_bad_input():
    rep = _vector_rep(4)
    with pytest.raises(ValueError, match=r"so\(4\) needs 6"):
        rotor_hamiltonian(rep, [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="> 0"):
        rotor_hamiltonian(rep, [1, 1, 1, 1, -1, 1])
    with pytest.raises(ValueError, match="> 0"):
        rotor_hamiltonian(rep, [1, 1, 1, 1, 0, 1])
    with pytest.raises(ValueError, match="hbar"):
        rotor_hamiltonian(rep, [1] * 6, hbar=-1)
    with pytest.raises(TypeError, match=r"body must be numeric, got a boolean entry in \[True, 2"):
        rotor_hamiltonian(rep, [True, 2, 3, 4, 5, 6])  # (read as I_12 = 1)

    class _Other:  # an Inertia-like object of another N
        N, moments = 3, np.ones(3)

    with pytest.raises(ValueError, match=r"so\(3\).*so\(4\)"):
        rotor_hamiltonian(rep, _Other())


# ----------------------------------------------------------------------------
# evolve
# ----------------------------------------------------------------------------
@pytest.mark.parametrize("method", ["eigen", "krylov", "expm_multiply", "auto"])
@pytest.mark.parametrize("case", ["spin5", "vector5", "spin_sum"])
def test_native_methods_match_dense_expm(method, case, rng):
    if case == "spin5":
        rep = _spin_rep(5)
    elif case == "vector5":
        rep = _vector_rep(5)
    else:
        rep = _direct_sum(_spin_rep(3), _spin_rep(2.5))
    moments = rng.uniform(0.6, 2.0, size=rep.N * (rep.N - 1) // 2)
    hbar = 0.7
    H = rotor_hamiltonian(rep, moments, hbar=hbar)
    psi = _random_state(rng, rep.dim)
    times = np.concatenate([[0.0], np.sort(rng.uniform(0.01, 4.0, size=12))])
    res = evolve(H, psi, times, method=method, hbar=hbar)
    np.testing.assert_allclose(_states(res), _exact(H, psi, times, hbar), atol=1e-10, rtol=0)
    assert res.times == list(times)


def test_krylov_many_restarts_and_uniform_grid(rng):
    """Small Krylov spaces force many restarts and bisected sub-steps; still exact to 1e-10."""
    rep = _spin_rep(10)
    H = rotor_hamiltonian(rep, rng.uniform(0.3, 1.0, size=3))
    psi = _random_state(rng, rep.dim)
    times = np.linspace(0, 5, 6)
    res = evolve(H, psi, times, method="krylov", options={"krylov_dim": 8, "blocks": False})
    assert res.stats["n_krylov"] > 5
    np.testing.assert_allclose(_states(res), _exact(H, psi, times), atol=1e-10, rtol=0)
    res2 = evolve(H, psi, times, method="expm_multiply", options={"blocks": False})
    np.testing.assert_allclose(_states(res2), _exact(H, psi, times), atol=1e-10, rtol=0)


def test_sesolve_and_expectations(rng):
    rep = _spin_rep(3)
    H = rotor_hamiltonian(rep, [1.0, 1.7, 2.9])
    psi = _random_state(rng, rep.dim)
    times = np.linspace(0, 2, 11)
    ops = [qutip.Qobj(rep.hermitian(p).toarray()) for p in planes(3)] + [H]
    ref = evolve(H, psi, times, e_ops=ops, method="eigen")
    ses = evolve(H, psi, times, e_ops=ops, method="sesolve", options={"atol": 1e-12, "rtol": 1e-10})
    ex = _exact(H, psi, times)
    for k, op in enumerate(ops):
        direct = np.einsum("ti,ij,tj->t", ex.conj(), op.full(), ex).real
        np.testing.assert_allclose(ref.expect[k], direct, atol=1e-10, rtol=0)
        np.testing.assert_allclose(ses.expect[k], direct, atol=1e-7, rtol=0)
    # energy is conserved
    np.testing.assert_allclose(ref.expect[-1], ref.expect[-1][0], atol=1e-11, rtol=0)
    assert not ref.states  # qutip convention: with e_ops, states are not stored by default
    assert ref.final_state is not None


def test_mesolve_with_dephasing_conserves_energy_and_loses_purity(rng):
    """c_op = sqrt(g) H: energy populations are constant, coherences decay (purity < 1)."""
    rep = _spin_rep(1)
    H = rotor_hamiltonian(rep, [1.0, 1.5, 2.5])
    psi = qutip.Qobj(_random_state(rng, 3))
    times = np.linspace(0, 3, 7)
    g = 0.5
    res = evolve(H, psi, times, e_ops=[H], c_ops=[np.sqrt(g) * H], options={"store_states": True})
    np.testing.assert_allclose(res.expect[0], res.expect[0][0], atol=1e-6, rtol=0)
    # in H's eigenbasis rho_ij(t) = rho_ij(0) exp(-i (E_i - E_j) t - g (E_i - E_j)^2 t / 2): the purity of a pure
    # start is sum_ij p_i p_j exp(-g (E_i - E_j)^2 t), p_i = |<E_i|psi>|^2 (to the solver's tolerance)
    E, vecs = H.eigenstates()
    p = np.array([abs(v.overlap(psi)) ** 2 for v in vecs])
    dE2 = (E[:, None] - E[None, :]) ** 2
    exact = [float(np.sum(np.outer(p, p) * np.exp(-g * dE2 * tau))) for tau in times]
    purity = [(rho ** 2).tr().real for rho in res.states]
    np.testing.assert_allclose(purity, exact, rtol=0, atol=1e-5)
    assert exact[-1] < 0.95  # (the coherences have decayed: a check of the check)


def test_progress_bar(capsys, rng):
    rep = _spin_rep(2)
    H = rotor_hamiltonian(rep, [1.0, 1.5, 2.5])
    evolve(H, _random_state(rng, 5), np.linspace(0, 1, 5), progress=True)
    assert "evolve" in capsys.readouterr().err  # the package's one progress bar (tqdm, stderr)


def test_evolve_bad_input(rng):
    rep = _spin_rep(2)
    H = rotor_hamiltonian(rep, [1.0, 1.5, 2.5])
    psi = _random_state(rng, 5)
    t = np.linspace(0, 1, 3)
    with pytest.raises(ValueError, match="dimension 4 but H has dimension 5"):
        evolve(H, psi[:4], t)
    with pytest.raises(ValueError, match="zero vector"):
        evolve(H, np.zeros(5), t)
    with pytest.warns(UserWarning, match="norm 2"):
        res = evolve(H, 2 * psi, t, method="eigen")
    np.testing.assert_allclose(np.linalg.norm(res.states[-1].full()), 1.0, atol=1e-13, rtol=0)
    with pytest.raises(ValueError, match="Hermitian"):
        evolve(qutip.Qobj(np.triu(np.ones((5, 5)))), psi, t)
    # e_ops and c_ops are checked here (their errors came from inside QuTiP)
    for method in ("auto", "sesolve"):
        with pytest.raises(ValueError, match=r"e_ops\[0\] has dimension 4, but H has dimension 5"):
            evolve(H, psi, t, e_ops=[qutip.qeye(4)], method=method)
    with pytest.raises(TypeError, match="e_ops must be a qutip.Qobj"):
        evolve(H, psi, t, e_ops="x")
    with pytest.raises(ValueError, match=r"e_ops\['a'\] must be finite"):
        evolve(H, psi, t, e_ops={"a": np.full((5, 5), np.nan)})
    with pytest.raises(TypeError, match="c_ops must be a list of collapse operators"):
        evolve(H, psi, t, c_ops=qutip.qeye(5))
    with pytest.raises(ValueError, match=r"c_ops\[0\] has dimension 4, but H has dimension 5"):
        evolve(H, psi, t, c_ops=[qutip.qeye(4)])
    with pytest.raises(ValueError, match="dimension >= 1, got a 0 x 0 matrix"):
        evolve(np.zeros((0, 0)), np.zeros(0), t)
    with pytest.raises(ValueError, match="strictly monotonic"):
        evolve(H, psi, [0.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="strictly monotonic"):
        evolve(H, psi, [0.0, 2.0, 1.0])
    with pytest.raises(ValueError, match="unknown method 'rk4'"):
        evolve(H, psi, t, method="rk4")
    with pytest.raises(ValueError, match="mesolve"):
        evolve(H, psi, t, method="krylov", c_ops=[H])
    with pytest.raises(ValueError, match="unknown option"):
        evolve(H, psi, t, method="krylov", options={"nstep": 5})
    with pytest.raises(ValueError, match="quantum_max_dense_dim"):
        evolve(H, psi, t, method="eigen", options={"max_dense_dim": 3, "blocks": False})
    with hyperrotor.options(quantum_max_dense_dim=3), pytest.raises(ValueError, match="quantum_max_dense_dim"):
        evolve(H, psi, t, method="eigen", options={"blocks": False})
    with pytest.raises(ValueError, match="ket"):
        evolve(H, qutip.ket2dm(qutip.Qobj(psi)), t)
    with pytest.raises(ValueError, match="hbar"):
        evolve(H, psi, t, hbar=0)


#: Bad QuTiP options of evolve: (options, exception, message); each was passed on unchecked (scipy's int() error,
#: a zvode warning and a wrong result, or silently accepted: "1e-8" and True read as numbers).
_BAD_QUTIP_OPTIONS = [
    ({"nsteps": "x"}, TypeError, r"options\['nsteps'\] must be an integer in 1..2147483647, got 'x' of type str"),
    ({"nsteps": -5}, ValueError, r"options\['nsteps'\] must be an integer in 1..2147483647, got -5"),
    ({"nsteps": True}, TypeError, r"options\['nsteps'\] must be an integer in 1..2147483647, got True of type bool"),
    ({"nsteps": 2.5}, TypeError, r"options\['nsteps'\] must be an integer in 1..2147483647, got 2.5 of type float"),
    ({"atol": "1e-8"}, TypeError, r"options\['atol'\] must be a positive real number, got '1e-8' of type str"),
    ({"atol": True}, TypeError, r"options\['atol'\] must be a positive real number, got True of type bool"),
    ({"atol": -1.0}, ValueError, r"options\['atol'\] must be finite and >= 0, got -1.0"),
    ({"rtol": float("nan")}, ValueError, r"options\['rtol'\] must be finite and >= 0, got nan"),
    ({"method": "krylov"}, ValueError, r"QuTiP's 'krylov' integrator needs options\['krylov_dim'\]"),
    ({"atol": 0, "rtol": 0.0}, ValueError, r"options\['atol'\] and options\['rtol'\] are both 0"),
    ({"nsteps": 1e20}, ValueError, r"options\['nsteps'\] must be an integer in 1..2147483647, got 1000000000000"),
    ({"max_step": np.array([np.inf, 1.0])}, TypeError, r"options\['max_step'\] must be a positive real number"),
    ({"max_step": -1}, ValueError, r"options\['max_step'\] must be finite and >= 0, got -1.0"),
    ({"order": 13}, ValueError, r"options\['order'\] must be an integer in 1..12, got 13"),
    ({"method": "bdf", "order": 6}, ValueError, r"options\['order'\] must be an integer in 1..5, got 6"),
    ({"normalize_output": "no"}, TypeError, r"options\['normalize_output'\] must be True or False, got 'no'"),
    ({"method": "rk4"}, ValueError,
     r"unknown options\['method'\] \(QuTiP's ODE integrator\) 'rk4'; allowed: .*'adams'"),
    ({"progress_bar": "fancy"}, ValueError, r"options\['progress_bar'\] must be True, False, None or one of QuTiP's "
                                            r"bars 'enhanced'.*'tqdm'.*, got 'fancy'"),
    ({"progress_kwargs": 3}, TypeError, r"options\['progress_kwargs'\] must be a mapping .*, got 3 of type int"),
    ({"nstep": 10}, hyperrotor.UnknownOptionError, r"unknown option 'nstep'; allowed: .*'nsteps'"),
    ({"krylov_dim": 5}, hyperrotor.UnknownOptionError,
     r"integrator 'adams' \('krylov_dim' is an option of the integrator\(s\) 'krylov': choose one with "
     r"options\['method'\]\): unknown option 'krylov_dim'; allowed: .*'nsteps'"),
]


@pytest.mark.parametrize("method", ["sesolve", "mesolve"])
@pytest.mark.parametrize("options, exc, match", _BAD_QUTIP_OPTIONS)
def test_evolve_checks_qutip_options_before_any_work(method, options, exc, match):
    solver = qutip.SESolver if method == "sesolve" else qutip.MESolver
    owned = any("krylov_dim" in getattr(i, "integrator_options", {}) for i in solver.avail_integrators().values())
    if "krylov_dim" in options and not owned:  # (QuTiP 5.0's MESolver has no 'krylov' integrator: no owner to name)
        match = r"evolve options of method 'mesolve': unknown option 'krylov_dim'; allowed: .*'nsteps'"
    if options.get("method") == "krylov" and "krylov" not in solver.avail_integrators():  # (the same)
        match = r"unknown options\['method'\] \(QuTiP's ODE integrator\) 'krylov'"
    H = rotor_hamiltonian(_spin_rep(1), [1.0, 1.5, 2.5])
    with pytest.raises(exc, match=match):
        evolve(H, np.zeros(3), np.linspace(0, 1, 3), method=method, options=options)  # (psi0 = 0: not reached)


@pytest.mark.parametrize("method", ["sesolve", "mesolve"])
def test_evolve_takes_the_qutip_options_qutip_takes(method, rng):
    """None is QuTiP's "its default" for every key; nsteps=1e5 is an integer; rtol=0 (pure absolute control),
    atol=0 (pure relative, vern7) and max_step=inf are the integrators' to take: the same states as the exact ones."""
    H = rotor_hamiltonian(_spin_rep(1), [1.0, 1.5, 2.5])
    psi = _random_state(rng, 3)
    t = np.linspace(0, 1, 4)
    for opts in ({"atol": None, "rtol": None, "method": None, "order": None, "nsteps": None, "progress_bar": None,
                  "normalize_output": None},
                 {"nsteps": 1e5, "rtol": 0.0, "atol": 1e-11, "max_step": np.inf},
                 {"method": "vern7", "atol": 0.0, "rtol": 1e-10}):
        res = evolve(H, psi, t, method=method, options={**opts, "store_states": True})
        np.testing.assert_allclose(_states(res), _exact(H, psi, t), atol=1e-6, rtol=0)  # (mesolve without c_ops: kets)


def test_evolve_qutip_options_good_values_and_progress(rng, capsys):
    rep = _spin_rep(2)
    H = rotor_hamiltonian(rep, [1.0, 1.5, 2.5])
    psi = _random_state(rng, 5)
    t = np.linspace(0, 1, 4)
    opts = {"method": "bdf", "order": np.int64(5), "nsteps": 5000, "atol": np.float64(1e-11), "rtol": 1e-9,
            "store_states": True, "progress_bar": False}
    res = evolve(H, psi, t, method="sesolve", options=opts, progress=False)
    np.testing.assert_allclose(_states(res), _exact(H, psi, t), atol=1e-7, rtol=0)
    res = evolve(H, psi, t, method="sesolve", options={"method": "krylov", "krylov_dim": 5, "store_states": True})
    np.testing.assert_allclose(_states(res), _exact(H, psi, t), atol=1e-6, rtol=0)
    evolve(H, psi, t, method="sesolve", options={"progress_bar": "text"})  # (progress=None: QuTiP's text bar)
    assert "Total run time" in capsys.readouterr().out
    capsys.readouterr()
    evolve(H, psi, t, method="sesolve", options={"progress_bar": None}, progress=True)  # (None: as if not given)
    assert "100%" in capsys.readouterr().err  # (hyperrotor's tqdm bar, on stderr)
    for progress, bar in ((False, "text"), (True, ""), (True, False)):
        with pytest.raises(ValueError, match=rf"progress={progress} contradicts options\['progress_bar'\] = "):
            evolve(H, psi, t, method="sesolve", options={"progress_bar": bar}, progress=progress)


def test_mesolve_time_dependent_dephasing_closed_form_and_qutip(rng):
    """c_op = [H, f] with f(t) = sqrt(g t): in H's eigenbasis rho_ij decays by exp(-(E_i - E_j)^2 g t^2 / 4), so the
    purity of a pure start is sum_ij p_i p_j exp(-g (E_i - E_j)^2 t^2 / 2); the array form of f gives QuTiP's result."""
    rep = _spin_rep(1)
    H = rotor_hamiltonian(rep, [1.0, 1.5, 2.5])
    psi = qutip.Qobj(_random_state(rng, 3))
    times = np.linspace(0, 2, 9)
    g = 2.0
    opts = {"store_states": True, "atol": 1e-10, "rtol": 1e-8}
    res = evolve(H, psi, times, e_ops=[H], c_ops=[[H, lambda t: np.sqrt(g * t)]], options=opts)
    np.testing.assert_allclose(res.expect[0], res.expect[0][0], atol=1e-6, rtol=0)
    E, vecs = H.eigenstates()
    p = np.array([abs(v.overlap(psi)) ** 2 for v in vecs])
    dE2 = (E[:, None] - E[None, :]) ** 2
    exact = [float(np.sum(np.outer(p, p) * np.exp(-g * dE2 * tau ** 2 / 2))) for tau in times]
    purity = [(rho ** 2).tr().real for rho in res.states]
    np.testing.assert_allclose(purity, exact, rtol=0, atol=1e-6)
    assert exact[-1] < 0.9  # (the coherences have decayed: a check of the check)
    # an array coefficient (one value per output time, interpolated) as QuTiP's own mesolve does it
    coeff = np.sqrt(g * times)
    res2 = evolve(H, psi, times, c_ops=(np.asarray(H.full()), [H, coeff]), method="mesolve", options=opts)
    ref = qutip.mesolve(H, psi, times, c_ops=[H, [H, coeff]], options={"atol": 1e-10, "rtol": 1e-8})
    for a, b in zip(res2.states, ref.states):
        np.testing.assert_allclose(a.full(), b.full(), atol=1e-7, rtol=0)


def test_evolve_refuses_bad_time_dependent_c_ops_and_e_ops(rng):
    rep = _spin_rep(2)
    H = rotor_hamiltonian(rep, [1.0, 1.5, 2.5])
    psi = _random_state(rng, 5)
    t = np.linspace(0, 1, 3)
    bad_c_ops = [
        ([[H, "0.5"]], TypeError, r"c_ops\[0\]\[1\] \(a coefficient\) must be a function of t, a qutip.Coefficient "
                                r"or an array of one value per output time, got the text '0.5'"),
        ([[H, 0.5]], TypeError, r"c_ops\[0\]\[1\] \(a coefficient\) must be .*got 0.5 of type float; for a constant "
                              r"rate g pass sqrt\(g\) \* op"),
        ([[H, np.ones(4)]], ValueError, r"c_ops\[0\]\[1\] \(a coefficient\) must have one value per output time, "
                                      r"shape \(3,\), got shape \(4,\)"),
        ([[H, np.array([1.0, np.nan, 1.0])]], ValueError, r"c_ops\[0\]\[1\] must be finite; "
                                              r"c_ops\[0\]\[1\]\[1\] = nan"),
        ([[H, np.ones(3, bool)]], TypeError, r"c_ops\[0\]\[1\] must be numeric, got booleans"),
        ([[qutip.qeye(4), lambda t: 1.0]], ValueError, r"c_ops\[0\]\[0\] has dimension 4, but H has dimension 5"),
        ([[H, [H, "t"]]], TypeError, r"c_ops\[0\]\[1\]\[1\] \(a coefficient\) must be .*got the text 't'"),
        ([[]], TypeError, r"c_ops\[0\] must be .*, got an empty list"),
        ([()], TypeError, r"c_ops\[0\] must be .*, got an empty tuple"),
        ([[H, qutip.QobjEvo([H, lambda t: 0.5])]], TypeError, r"c_ops\[0\]\[1\] must be a constant operator .*may also "
                                                             r"be a pair \[op, coeff\]\), got a qutip.QobjEvo: give "
                                                             r"the whole operator as one"),
        ([[H, np.ones((3, 1))]], ValueError, r"c_ops\[0\]\[1\] must have 1 dimension\(s\), got shape \(3, 1\)"),
        ([[H, [H, H, H]]], TypeError, r"c_ops\[0\]\[1\] must be a pair \[op, coeff\] \(a term of QuTiP's list "
                                    r"format; .*\), got a list of length 3"),
        ([[H, np.cos]], TypeError, r"c_ops\[0\]\[1\] \(a coefficient\) must be .*; QuTiP cannot use <ufunc 'cos'>"),
        ([[qutip.QobjEvo(H), lambda t: 1.0]], TypeError, r"c_ops\[0\]\[0\] must be a constant operator .*got a "
                                                       r"qutip.QobjEvo: give the product as one"),
        ([H, lambda t: 0.5], TypeError, r"c_ops\[1\] is a function, so it must be QuTiP's f\(t\) -> Qobj"),
        ([qutip.QobjEvo(qutip.qeye([5, 1]))], ValueError, r"c_ops\[0\] has dims \[\[5, 1\], \[5, 1\]\], but H has "
                                                        r"dims \[\[5\], \[5\]\]"),
    ]
    for c_ops, exc, match in bad_c_ops:
        with pytest.raises(exc, match=match):
            evolve(H, psi, t, c_ops=c_ops)
    # QuTiP's list format of one collapse operator, [op0, [op1, coeff1], ...]: QuTiP's own mesolve gives the same
    sm = qutip.Qobj(np.diag(np.ones(4), 1), dims=H.dims)
    for c_op in ([sm, [sm.dag() * sm, lambda t: 0.5 + t]],
                 [sm, [sm, np.linspace(0.0, 1.0, 3)], [sm.dag(), 0.2 + 0j * t]]):
        got = evolve(H, psi, t, c_ops=[c_op], e_ops=[H], options={"atol": 1e-10, "rtol": 1e-8})
        want = qutip.mesolve(H, qutip.Qobj(psi, dims=[H.dims[0], [1]]), t, c_ops=[qutip.QobjEvo(c_op, tlist=t)],
                             e_ops=[H], options={"atol": 1e-10, "rtol": 1e-8})
        np.testing.assert_allclose(got.expect[0], want.expect[0], rtol=0, atol=1e-8)
    for method in ("auto", "sesolve"):  # QuTiP's e_ops take no [op, coeff] pairs: a QobjEvo is the time-dependent form
        with pytest.raises(TypeError, match=r"e_ops\[0\] must be .*, got a list of length 2 \(a time-dependent e_ops "
                                            r"entry is a qutip.QobjEvo, e.g. QobjEvo\(\[op, f\]\)\)"):
            evolve(H, psi, t, e_ops=[[H, lambda t: 1.0]], method=method)
        res = evolve(H, psi, t, e_ops=[qutip.QobjEvo([H, lambda t: 2.0])], method=method)
        np.testing.assert_allclose(res.expect[0], 2 * qutip.expect(H, qutip.Qobj(psi)), atol=1e-6, rtol=0)


# ----------------------------------------------------------------------------
# symmetry blocks
# ----------------------------------------------------------------------------
def test_blocks_of_direct_sum_and_populated_only(rng):
    """H of spin 2 (+) spin 3 splits; a state in one summand evolves only that block (== full to 1e-12)."""
    rep = _direct_sum(_spin_rep(2), _spin_rep(3))
    H = rotor_hamiltonian(rep, [1.0, 1.4, 2.3])
    blocks = symmetry_blocks(H)
    # the D2 symmetry of the asymmetric top also splits each summand (parity of m in the J3 basis)
    assert sorted(np.concatenate(blocks).tolist()) == list(range(12))
    assert all(set(b) <= set(range(5)) or set(b) <= set(range(5, 12)) for b in blocks)
    psi = np.zeros(12, complex)
    psi[5:] = _random_state(rng, 7)
    t = np.linspace(0, 3, 9)
    split = evolve(H, psi, t, method="krylov")
    full = evolve(H, psi, t, method="krylov", options={"blocks": False})
    assert split.stats["populated_dim"] == 7 and full.stats["populated_dim"] == 12
    np.testing.assert_allclose(_states(split), _states(full), atol=1e-12, rtol=0)
    np.testing.assert_allclose(_states(split), _exact(H, psi, t), atol=1e-12, rtol=0)


def test_equal_moments_blocks_are_trivial(rng):
    """Equal moments: H = C2/(2I) is a multiple of the identity on an irrep (up to round-off)."""
    rep = _spin_rep(4)
    H = rotor_hamiltonian(rep, [1.3] * 3)
    assert len(symmetry_blocks(H)) == rep.dim
    psi = _random_state(rng, rep.dim)
    t = np.linspace(0, 2, 5)
    res = evolve(H, psi, t)
    assert res.stats["block_methods"] == ["diagonal"]
    np.testing.assert_allclose(_states(res), _exact(H, psi, t), atol=1e-12, rtol=0)


# ----------------------------------------------------------------------------
# spectra against closed forms
# ----------------------------------------------------------------------------
def _casimir(hw, N):
    r"""<w, w + 2 rho>, rho_k = N/2 - k (k = 1..floor(N/2)): so(3): l(l+1); vector so(N): N - 1."""
    return sum(w * (w + N - 2 * k) for k, w in enumerate(hw, start=1))


@pytest.mark.parametrize("rep, N", [(_spin_rep(2), 3), (_spin_rep(3.5), 3), (_vector_rep(5), 5), (_vector_rep(6), 6)])
def test_equal_moment_spectrum_is_casimir(rep, N):
    levels, deg = spectrum(rotor_hamiltonian(rep, [0.8] * (N * (N - 1) // 2)))
    assert deg.tolist() == [rep.dim]
    np.testing.assert_allclose(levels, [_casimir(rep.highest_weight, N) / 1.6], atol=1e-10, rtol=0)


def _asym_constants(moments):
    I12, I13, I23 = moments
    return 1 / (2 * I23), 1 / (2 * I13), 1 / (2 * I12)  # A, B, C for I_1 = I_23, I_2 = I_13, I_3 = I_12


def test_asymmetric_top_l1_l2(rng):
    r"""Closed forms (hbar = 1, A_k = 1/(2 I_k)).

    l = 1: H = sum_k A_k J_k^2 and (J_k^2) = 1 - |e_k><e_k| in the Cartesian basis, so the
    levels are B + C, A + C, A + B.
    l = 2: 4A + B + C, A + 4B + C, A + B + 4C and
    2(A + B + C) +- 2 sqrt((A - B)^2 + (A - C)(B - C)); their sum 10(A + B + C) = tr H and
    the symmetric-top limit A = B reproduces A J(J+1) + (C - A) K^2.
    """
    for _ in range(3):
        moments = rng.uniform(0.5, 3.0, size=3)
        A, B, C = _asym_constants(moments)
        E1 = np.sort(np.linalg.eigvalsh(rotor_hamiltonian(_spin_rep(1), moments).full()))
        np.testing.assert_allclose(E1, np.sort([B + C, A + C, A + B]), atol=1e-10, rtol=0)
        E1v = np.sort(np.linalg.eigvalsh(rotor_hamiltonian(_vector_rep(3), moments).full()))
        np.testing.assert_allclose(E1v, E1, atol=1e-12, rtol=0)
        root = np.sqrt((A - B) ** 2 + (A - C) * (B - C))
        expected = [4 * A + B + C, A + 4 * B + C, A + B + 4 * C, 2 * (A + B + C) + 2 * root, 2 * (A + B + C) - 2 * root]
        levels, deg = spectrum(rotor_hamiltonian(_spin_rep(2), moments))
        np.testing.assert_allclose(levels, np.sort(expected), atol=1e-10, rtol=0)
        assert deg.tolist() == [1] * 5


def test_symmetric_top_degeneracies():
    """I_13 = I_23 (A = B): levels A J(J+1) + (C - A) K^2 with degeneracy 2 for K != 0."""
    Iab, Ic = 1.0, 2.5
    A, C = 1 / (2 * Iab), 1 / (2 * Ic)
    J = 3
    levels, deg = spectrum(rotor_hamiltonian(_spin_rep(J), [Ic, Iab, Iab]))
    exp = sorted((A * J * (J + 1) + (C - A) * K**2, 1 if K == 0 else 2) for K in range(J + 1))
    np.testing.assert_allclose(levels, [e for e, _ in exp], atol=1e-10, rtol=0)
    assert deg.tolist() == [d for _, d in exp]


def quartet_levels(m1, m2, kappa):
    r"""Closed-form quartet levels (axis 5) in the so(5) irrep (m1, m2), hbar = 1.

    Planes containing axis 5 have I = 1 + kappa^2, the six so(4) planes I = 2, so
    H = C4/4 + (C5 - C4)/(2(1 + kappa^2)) with C5 = sum of all L^2 and C4 = the so(4) part:
    H = C5/(2(1+kappa^2)) + C4 (1/4 - 1/(2(1+kappa^2))).
    so(5) > so(4) branching: (p1, p2) with m1 >= p1 >= m2 >= |p2|, p - m integer, each once;
    C4(p) = p1(p1 + 2) + p2^2, dim(p) = (p1 + p2 + 1)(p1 - p2 + 1).
    """
    C5 = _casimir((m1, m2), 5)
    a = 1 / (2 * (1 + kappa**2))
    out = {}
    p1 = m1
    while p1 >= m2 - 1e-9:
        p2 = -m2
        while p2 <= m2 + 1e-9:
            E = C5 * a + (p1 * (p1 + 2) + p2**2) * (0.25 - a)
            key = round(E, 9)
            E0, d0 = out.get(key, (E, 0))
            out[key] = (E0, d0 + int(round((p1 + p2 + 1) * (p1 - p2 + 1))))
            p2 += 1
        p1 -= 1
    keys = sorted(out)
    return np.array([out[k][0] for k in keys]), np.array([out[k][1] for k in keys])


@pytest.mark.parametrize("kappa", [0.3, 1.7])
def test_quartet_vector_rep(kappa):
    """so(5) vector rep (1, 0): levels from the branching rule match the matrix spectrum."""
    moments = [2.0 if 5 not in p else 1 + kappa**2 for p in planes(5)]
    levels, deg = spectrum(rotor_hamiltonian(_vector_rep(5), moments))
    el, ed = quartet_levels(1, 0, kappa)
    np.testing.assert_allclose(levels, el, atol=1e-10, rtol=0)
    assert deg.tolist() == ed.tolist()


def test_spectrum_tolerance_and_errors(rng):
    H = np.diag([1.0, 1.0 + 1e-12, 2.0, 2.0 + 1e-6])
    levels, deg = spectrum(H)
    assert deg.tolist() == [2, 1, 1]
    levels, deg = spectrum(H, atol=1e-5)
    assert deg.tolist() == [2, 2]
    assert spectrum(H, rtol=1e-5)[1].tolist() == [2, 2]
    with pytest.raises(ValueError, match="Hermitian"):
        spectrum(np.array([[0.0, 1.0], [0.0, 0.0]]))
    with pytest.raises(ValueError, match="dimension >= 1, got a 0 x 0 matrix"):
        spectrum(np.zeros((0, 0)))  # (was max() of an empty sequence)
    with hyperrotor.options(quantum_max_dense_dim=2), pytest.raises(ValueError, match="quantum_max_dense_dim"):
        spectrum(np.ones((4, 4)))


# ----------------------------------------------------------------------------
# Gelfand-Tsetlin irreps (hyperrotor.quantum.irrep)
# ----------------------------------------------------------------------------
def _quartet_moments(kappa, axis=5):
    return [1 + kappa**2 if axis in p else 2.0 for p in planes(5)]


@pytest.mark.parametrize("hw", [(2, 1), (3, 0), (3, 3), (2.5, 1.5), (4, 2)])
def test_quartet_gt_irreps_branching(hw):
    """Quartet levels and degeneracies of so(5) irreps from the so(5) > so(4) branching rule (1e-10)."""
    from hyperrotor.quantum import irrep

    kappa = 0.45
    H = rotor_hamiltonian(irrep(5, hw), _quartet_moments(kappa))
    levels, deg = spectrum(H)
    el, ed = quartet_levels(hw[0], hw[1], kappa)
    np.testing.assert_allclose(levels, el, atol=1e-10, rtol=0)
    assert deg.tolist() == ed.tolist()
    # the GT basis of so(5) > so(4) diagonalizes the so(4) Casimir, hence H (axis 5)
    assert len(symmetry_blocks(H)) == H.shape[0]
    # another distinguished axis: same spectrum, H no longer diagonal in this basis
    H3 = rotor_hamiltonian(irrep(5, hw), _quartet_moments(kappa, axis=3))
    l3, d3 = spectrum(H3)
    np.testing.assert_allclose(l3, el, atol=1e-10, rtol=0)
    assert d3.tolist() == ed.tolist()


@pytest.mark.parametrize("N, hw", [(4, (2, 1)), (5, (2, 1)), (6, (1, 1, 0)), (5, (1.5, 0.5))])
def test_equal_moments_gt_casimir(N, hw):
    from hyperrotor.quantum import irrep

    rep = irrep(N, hw)
    levels, deg = spectrum(rotor_hamiltonian(rep, [1.25] * (N * (N - 1) // 2), hbar=0.5))
    assert deg.tolist() == [rep.dim]
    np.testing.assert_allclose(levels, [0.25 * _casimir(hw, N) / 2.5], atol=1e-10, rtol=0)


@pytest.mark.parametrize("method", ["auto", "krylov", "eigen"])
def test_symmetry_adapted_quartet_equals_full_evolution(method, rng):
    """Quartet inertia in the GT basis: H is diagonal; block evolution == full Krylov evolution (1e-12)."""
    from hyperrotor.quantum import irrep

    rep = irrep(5, (4, 2))
    H = rotor_hamiltonian(rep, _quartet_moments(0.8))
    psi = np.zeros(rep.dim, complex)
    sel = rng.choice(rep.dim, size=40, replace=False)
    psi[sel] = rng.normal(size=40) + 1j * rng.normal(size=40)
    psi /= np.linalg.norm(psi)
    t = np.linspace(0, 2.5, 11)
    ops = [H, qutip.Qobj(rep.generator((1, 5), form="hermitian").toarray())]
    sym = evolve(H, psi, t, e_ops=ops, method=method, options={"store_states": True})
    full = evolve(H, psi, t, e_ops=ops, method="krylov", options={"blocks": False, "atol": 1e-14, "store_states": True})
    assert sym.stats["populated_dim"] == 40
    np.testing.assert_allclose(_states(sym), _states(full), atol=1e-12, rtol=0)
    for a, b in zip(sym.expect, full.expect):
        np.testing.assert_allclose(a, b, atol=1e-12, rtol=0)


def test_krylov_tolerance_below_round_off_floor(rng):
    """atol far below m eps ||H|| switches the error estimate to Pade; the result stays exact."""
    rep = _spin_rep(20)
    H = rotor_hamiltonian(rep, [1.0, 1.3, 2.1])
    psi = _random_state(rng, rep.dim)
    t = np.linspace(0, 0.5, 6)
    res = evolve(H, psi, t, method="krylov", options={"atol": 1e-15, "krylov_dim": 40, "blocks": False})
    np.testing.assert_allclose(_states(res), _exact(H, psi, t), atol=1e-12, rtol=0)


def test_evolve_accepts_sparse_and_arrays(rng):
    rep = _spin_rep(2)
    Hq = rotor_hamiltonian(rep, [1.0, 1.5, 2.5])
    Hs = sps.csr_matrix(Hq.full())
    psi = _random_state(rng, 5)
    t = np.linspace(0, 1, 4)
    op = rep.hermitian((1, 2))
    a = evolve(Hs, psi.reshape(-1, 1), t, e_ops={"L12": op}, method="krylov")
    b = evolve(Hq, qutip.Qobj(psi), t, e_ops=[qutip.Qobj(op.toarray())], method="eigen")
    np.testing.assert_allclose(a.e_data["L12"], b.expect[0], atol=1e-12, rtol=0)
    with pytest.raises(TypeError, match="Qobj"):
        evolve([[1, 0], [0, 1]], psi, t)


def test_hamiltonian_with_hyperrotor_inertia():
    """The classical Inertia (same plane order) drives rotor_hamiltonian; N and symbols are checked."""
    import sympy

    import hyperrotor
    from hyperrotor.quantum import irrep, vector_rep

    rep = irrep(5, (2, 1))
    H = rotor_hamiltonian(rep, hyperrotor.Inertia.quartet(0.45))
    np.testing.assert_allclose(H.full(), rotor_hamiltonian(rep, _quartet_moments(0.45)).full(), rtol=0, atol=scaled_tol(H.full(), k=40))
    with pytest.raises(ValueError, match=r"so\(4\).*so\(5\)"):
        rotor_hamiltonian(vector_rep(5), hyperrotor.Inertia.equal(4, 1.3))
    with pytest.raises(TypeError, match="symbolic"):
        rotor_hamiltonian(vector_rep(3), hyperrotor.Inertia.from_planes([sympy.Symbol("a")] * 3))
