"""SectorPropagator (hyperrotor.quantum.sector_propagator): build once, apply to many states and times.

Checked against the dense exponential of the whole Hamiltonian (scipy.linalg.expm, or its dense eigh): the states of
every engine (eigen, Krylov, the rent-or-buy switch of "auto"), forwards and backwards
(``apply`` with negative times), for a generic so(5) rotor (symmetry sectors) and a quartet body
(sparsity blocks); the state normalization near the overflow and the underflow; the output budget.
"""
import numpy as np
import pytest
import scipy.linalg as sla

import hyperrotor as hr
from hyperrotor.quantum import SectorPropagator, evolve, irrep, rotor_hamiltonian
from tolerance import assert_close, scaled_tol


pytestmark = pytest.mark.usefixtures("one_blas_thread")  # (tests/quantum/conftest.py)


def _generic(rng, hw=(3, 1)):
    rep = irrep(5, hw)
    return rep, rotor_hamiltonian(rep, rng.uniform(1.0, 2.0, size=10))


def _exact(Hd, tau, X):
    """exp(-i tau Hd) X from the dense eigendecomposition of the whole Hd (no sectors)."""
    E, V = np.linalg.eigh(Hd)
    return V @ (np.exp(-1j * tau * E)[:, None] * (V.conj().T @ X.reshape(len(E), -1))).reshape(X.shape[0], -1)


def _state(rng, dim):
    v = rng.normal(size=dim) + 1j * rng.normal(size=dim)
    return v / np.linalg.norm(v)


@pytest.mark.parametrize("method", ["auto", "eigen", "krylov"])
def test_many_states_and_grids_match_expm(method, rng):
    rep, H = _generic(rng)
    Hd = H.full()
    with hr.options(quantum_eigen_max_block=20):  # the sectors of (3, 1) (dim 81) go to Krylov under "krylov"
        U = SectorPropagator(H, method=method)
    assert U.stats["sectors"] == 16
    t = np.array([0.0, 0.4, 1.3, 2.0])
    tol = scaled_tol(1.0, dim=rep.dim, k=1e4)  # Krylov atol 1e-12 per restart
    for _ in range(3):  # the same propagator, several states (eigendecompositions cached)
        psi = _state(rng, rep.dim)
        S = U.states(psi, t)
        for k, tk in enumerate(t):
            np.testing.assert_allclose(S[k], _exact(Hd, tk, psi).ravel(), rtol=0, atol=tol)
    X = np.column_stack([_state(rng, rep.dim) for _ in range(3)])
    for tau in (0.7, -1.1):  # backwards too: exp(+i H 1.1)
        np.testing.assert_allclose(U.apply(X, tau), _exact(Hd, tau, X), rtol=0, atol=tol)


def test_sector_blocks_restricted_in_groups_match_expm(rng, monkeypatch):
    """The sector blocks come from products of groups of side-by-side bases; groups of one or two
    sectors (a 10-column budget, as for a large irrep) give the same propagator."""
    import sys

    monkeypatch.setattr(sys.modules["hyperrotor.quantum._sector_blocks"], "_GROUP_COLUMNS", 10)
    rep, H = _generic(rng)
    psi = _state(rng, rep.dim)
    with hr.options(quantum_eigen_max_block=20):
        S = SectorPropagator(H, method="eigen").states(psi, [0.0, 0.8])
    np.testing.assert_allclose(S[1], _exact(H.full(), 0.8, psi).ravel(), rtol=0, atol=scaled_tol(1.0, dim=rep.dim, k=1e3))


def test_auto_diagonalizes_a_large_block_once_krylov_would_cost_more(rng):
    """Rent-or-buy: a short window stays in Krylov, a long one (or repeated use) ends in the cached eigh."""
    rep, H = _generic(rng, (6, 3))  # dim 770, sectors of ~48
    psi = _state(rng, rep.dim)
    with hr.options(quantum_eigen_max_block=2, quantum_krylov_dim=6):
        U = SectorPropagator(H)
        U.states(psi, [0.0, 1e-3])
        assert U.stats["block_methods"] == ["krylov"] and U.stats["n_eigh"] == 0
        S = U.states(psi, np.linspace(0.0, 50.0, 3))
        assert U.stats["block_methods"] == ["eigen"] and U.stats["n_eigh"] == 16
        U.states(psi, np.linspace(0.0, 50.0, 3))
        assert U.stats["n_eigh"] == 0  # cached
    np.testing.assert_allclose(S[-1], _exact(H.full(), 50.0, psi).ravel(), rtol=0, atol=scaled_tol(1.0, dim=rep.dim, k=1e4))


def test_evolve_rents_krylov_then_buys_the_sectors(rng):
    """Rent or buy across evolve calls ("auto", every sector small enough for eigh): a fresh H is first
    propagated by Lanczos on the whole space without building any sector; a grid whose predicted Krylov
    work exceeds the price of the sectors switches to them in its middle (from the state reached), and a
    later call of the same H uses them at once. Every state equals the dense exponential."""
    rep, H = _generic(rng)
    Hd = H.full()
    psi = _state(rng, rep.dim)
    tol = scaled_tol(1.0, dim=rep.dim, k=1e4)  # Krylov atol 1e-12 per restart

    def check(res, t):
        for k, tk in enumerate(t):
            np.testing.assert_allclose(res.states[k].full().ravel(), _exact(Hd, tk, psi).ravel(), rtol=0, atol=tol)

    # sparsity blocks of (3, 1) above 20: the sectors (of ~5) apply; Krylov spaces of 2 * 4 < dim 81
    with hr.options(quantum_eigen_max_block=20, quantum_krylov_dim=4):
        short = np.linspace(0.0, 0.5, 4)
        res = evolve(H, psi, short)
        assert res.stats["block_methods"] == ["krylov"] and "sectors" not in res.stats
        check(res, short)
        H2 = rotor_hamiltonian(rep, rng.uniform(1.0, 2.0, size=10))  # a fresh H: renting again
        Hd, psi = H2.full(), _state(rng, rep.dim)
        long = np.concatenate([[0.0, 0.05, 0.1], np.linspace(1.0, 400.0, 4)])
        res = evolve(H2, psi, long)
        assert res.stats["block_methods"] == ["eigen", "krylov"] and res.stats["sectors"] == 16
        assert 0 < res.stats["n_matvec"] and res.stats["n_eigh"] > 0
        check(res, long)
        res = evolve(H2, psi, short)
        assert res.stats["block_methods"] == ["eigen"] and res.stats["n_eigh"] == 0  # bought: cached
        check(res, short)
        res = evolve(rotor_hamiltonian(rep, rng.uniform(1.0, 2.0, size=10)), psi, short, progress=True)
        assert res.stats["sectors"] == 16  # a bar asked for: the blocks at once, no renting


def test_whole_space_krylov_without_reorthogonalization_matches_expm(rng):
    """A renting run whose Krylov spaces are small beside the dimension (30 in 625 here) is plain Lanczos,
    without re-orthogonalization: the Lanczos relation alone keeps the states accurate (Druskin, Greenbaum &
    Knizhnerman 1998), as the dense exponential shows (hbar = 0.7: the times scale)."""
    rep, H = _generic(rng, (6, 2))
    psi = _state(rng, rep.dim)
    t = np.linspace(0.0, 5.0, 5)
    tol = scaled_tol(1.0, dim=rep.dim, k=1e4)  # Krylov atol 1e-12 per restart
    with hr.options(quantum_eigen_max_block=100, quantum_krylov_dim=15):  # sparsity blocks of ~156 > 100
        res = evolve(H, psi, t, hbar=0.7)
    assert res.stats["block_methods"] == ["krylov"] and "sectors" not in res.stats, res.stats
    assert res.stats["n_krylov"] > 1, res.stats  # restarts too
    for k, tk in enumerate(t):
        np.testing.assert_allclose(res.states[k].full().ravel(), _exact(H.full(), tk / 0.7, psi).ravel(),
                                   rtol=0, atol=tol)


def test_quartet_sparsity_blocks_and_evolve_result(rng):
    """A quartet body is block diagonal in the GT basis: no sectors, the populated blocks only."""
    rep = irrep(5, (3, 1))
    kappa = 0.7
    moments = np.array([1 + kappa**2 if 5 in p else 2.0 for p in hr.conventions.planes(5)])
    H = rotor_hamiltonian(rep, moments)
    psi = np.zeros(rep.dim, complex)
    psi[:7] = _state(rng, 7)
    t = np.linspace(0.0, 3.0, 5)
    res = evolve(H, psi, t, e_ops=[H], options={"store_states": True})
    assert "sectors" not in res.stats
    for k, tk in enumerate(t):
        exact = sla.expm(-1j * tk * H.full()) @ psi
        np.testing.assert_allclose(res.states[k].full().ravel(), exact, rtol=0, atol=scaled_tol(1.0, dim=rep.dim, k=1e3))
    E0 = np.vdot(psi, H.full() @ psi).real
    np.testing.assert_allclose(res.expect[0], E0, rtol=0, atol=scaled_tol(abs(E0), dim=rep.dim, k=1e3))


@pytest.mark.parametrize("scale", [1e200, 1e-200, 1e-310])
def test_huge_and_tiny_states_keep_their_direction(scale, rng):
    H = np.diag([1.0, 2.0, 3.0])
    t = [0.0, 1.0]
    with pytest.warns(UserWarning, match="norm") as record:
        res = evolve(H, np.full(3, scale), t, options={"store_states": True})
    assert [w.filename for w in record] == [__file__]  # (attributed to the caller, not to the package)
    np.testing.assert_allclose(res.states[-1].full().ravel(), np.exp(-1j * np.diag(H)) / np.sqrt(3), rtol=0, atol=1e-14)
    with pytest.raises(ValueError, match="zero vector"):
        evolve(H, np.zeros(3), t)


def test_output_budget_refuses_before_work():
    """10^6 output times of a 3-level system are priced (max_output_bytes) and refused at once."""
    H = np.diag([1.0, 2.0, 3.0])
    t = np.linspace(0.0, 1.0, 10**6)
    with hr.options(max_output_bytes=10**8), pytest.raises(hr.BudgetError, match="max_output_bytes"):
        evolve(H, np.ones(3) / np.sqrt(3), t)


def test_keyword_only_after_t_and_progress_refuses_non_flags():
    H = np.diag([1.0, 2.0])
    with pytest.raises(TypeError):
        evolve(H, np.ones(2), [0.0, 1.0], None)  # e_ops is keyword-only
    with pytest.raises((TypeError, ValueError), match="progress"):
        evolve(H, np.ones(2) / np.sqrt(2), [0.0, 1.0], progress="yes")


def test_threads_give_the_same_states_as_one_thread(rng):
    """The blocks are independent tasks (map_rows): 2 threads == 1 thread, bit for bit."""
    rep, H = _generic(rng)
    psi = _state(rng, rep.dim)
    t = [0.0, 0.3, 0.9]
    with hr.options(quantum_eigen_max_block=20):
        one = SectorPropagator(H, method="krylov", workers=1).states(psi, t)
        two = SectorPropagator(H, method="krylov", workers=2).states(psi, t)
    np.testing.assert_array_equal(one, two)


def test_client_gives_the_same_states_as_the_serial_run(rng):
    """client=: the blocks are dask tasks (an in-process cluster, one worker of two threads); every state
    equals the serial run bit for bit, for the cached eigendecompositions and for Krylov."""
    dd = pytest.importorskip("dask.distributed")
    rep, H = _generic(rng)
    psi = _state(rng, rep.dim)
    t = [0.0, 0.3, 0.9]
    with dd.Client(processes=False, n_workers=1, threads_per_worker=2, dashboard_address=":0") as client, \
            hr.options(quantum_eigen_max_block=20):  # the 16 sectors of (3, 1) go to Krylov under "krylov"
        for method in ("eigen", "krylov"):
            serial = SectorPropagator(H, method=method).states(psi, t)
            U = SectorPropagator(H, method=method, client=client)
            np.testing.assert_array_equal(U.states(psi, t), serial)
            np.testing.assert_array_equal(U.states(psi, t), serial)  # again, with what came back from the workers


def test_evolve_reuses_the_propagator_of_an_unchanged_H(rng):
    """A second evolve of the same H reuses its blocks (no new eigh); H changed in place is rebuilt."""
    rep, H = _generic(rng)
    psi = _state(rng, rep.dim)
    first = evolve(H, psi, [0.0, 1.0])
    again = evolve(H, psi, [0.0, 1.0])
    assert first.stats["n_eigh"] > 0 and again.stats["n_eigh"] == 0
    np.testing.assert_array_equal(first.states[-1].full(), again.states[-1].full())
    A = H.full()
    a = evolve(A, psi, [0.0, 1.0])
    A *= 2.0  # the same object, other entries: exp(-i 2H t/2) must equal exp(-i H t)
    b = evolve(A, psi, [0.0, 0.5])
    np.testing.assert_allclose(b.states[-1].full(), a.states[-1].full(), rtol=0, atol=scaled_tol(1.0, dim=rep.dim, k=1e3))


def test_the_blocks_a_state_needs_are_diagonalized_under_one_price():
    """apply() priced each block as it came to it: 30 blocks of 200 passed a budget of a few blocks' time; now the
    blocks the state touches are priced together before the first is diagonalized."""
    import scipy.sparse as sps

    from hyperrotor._pricing import estimate

    g = np.random.default_rng(5)
    A = g.normal(size=(200, 200))
    H = sps.block_diag([A + A.T] * 30, format="csr")
    U = SectorPropagator(H, method="eigen")
    one = sum(c.amount for c in estimate("dense_diagonalization", dim=200, complex=False) if c.unit == "seconds")
    X = np.ones(H.shape[0], dtype=complex)
    with hr.options(max_seconds=5 * one):
        with pytest.raises(hr.BudgetError, match="and the others"):
            U.apply(X, 1.0)
        x = np.zeros(H.shape[0], dtype=complex)
        x[:400] = 1.0  # (two blocks: within the budget)
        y = U.apply(x, 1.0)
    assert_close(np.linalg.norm(y), np.linalg.norm(x), np.linalg.norm(x), dim=200, k=16)  # (unitary, two blocks of 200)
