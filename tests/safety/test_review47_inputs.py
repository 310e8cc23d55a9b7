"""Defects a review of the quantum side found (session 47; reproducers were /tmp/review47/quantum): side doors that
skipped the pricing or the checks of their main route, and errors that named the wrong thing."""

import numpy as np
import pytest
import qutip
import scipy.sparse as sps

import hyperrotor as hr
import hyperrotor.quantum as hq
from tolerance import scaled_tol


@pytest.fixture(scope="module")
def rotor():
    rep = hq.irrep(5, (2, 1))  # dim 35
    H = hq.rotor_hamiltonian(rep, np.linspace(1.0, 2.0, 10))
    return H, np.ones(rep.dim) / np.sqrt(rep.dim)


def test_states_is_priced_and_warned_like_evolve(rotor):
    """SectorPropagator.states returned 112 MB under max_output_bytes = 1e7, ran an unpriced Lanczos phase that
    evolve refuses at once, and returned rounded phases at t = 1e300 without the warning evolve gives."""
    H, psi = rotor
    t = np.linspace(0.0, 1.0, 200_000)
    with hr.options(max_output_bytes=10_000_000):
        for call in (lambda: hq.evolve(H, psi, t), lambda: hq.SectorPropagator(H).states(psi, t)):
            with pytest.raises(hr.BudgetError, match="max_output_bytes"):
                call()
    U = hq.SectorPropagator(H, method="krylov")
    with hr.options(max_seconds=1.0), pytest.raises(hr.BudgetError, match="max_seconds"):
        U.states(psi, [0.0, 1e7])
    with pytest.warns(hq.PhaseRoundingWarning):
        hq.SectorPropagator(H).states(psi, [0.0, 1e300])
    np.testing.assert_allclose(hq.SectorPropagator(H).states(psi, [0.0, 0.3])[-1],
                               hq.evolve(H, psi, [0.0, 0.3], options={"store_states": True}).states[-1].full().ravel(),
                               rtol=0, atol=1e-12)


def test_otoc_prices_the_density_matrix_eigh_before_it(monkeypatch):
    """A 1500 x 1500 density matrix's eigh ran 17 s under max_seconds = 0.5 (the dense_diagonalization model
    refuses the same eigh in sample_spectrum): refused before any eigh starts."""
    n = 1500
    rng = np.random.default_rng(0)
    H = sps.diags(rng.uniform(0.0, 1.0, n)).tocsr()
    W = (sps.eye(n, k=1) + sps.eye(n, k=-1)).tocsr()
    V = sps.diags(np.arange(n, dtype=float)).tocsr()
    A = rng.standard_normal((n, n))
    rho = A @ A.T

    def eigh(*args, **kwargs):
        raise AssertionError("an eigh ran before the budget refused it")

    monkeypatch.setattr(np.linalg, "eigh", eigh)
    with hr.options(max_seconds=0.5):
        with pytest.raises(hr.BudgetError, match="dense_diagonalization"):
            hq.otoc(H, W, V, [0.0, 1.0], state=rho)


def test_apply_checks_its_states_as_states_does():
    rep = hq.irrep(3, (2,))
    U = hq.SectorPropagator(hq.rotor_hamiltonian(rep, [1.0, 1.7, 2.9]))
    with pytest.raises(ValueError, match="X must be finite"):
        U.apply(np.array([np.nan, 0, 0, 0, 1.0]), 1.0)  # (returned NaN with a RuntimeWarning from NumPy)
    with pytest.raises(TypeError, match="X"):
        U.apply(np.ones(5, bool), 1.0)  # (booleans were read as 0 and 1)
    x = np.arange(5.0) + 1j
    np.testing.assert_array_equal(U.apply(qutip.Qobj(x.reshape(-1, 1)), 0.7), U.apply(x, 0.7))  # (was refused)
    cols = np.stack([x, 2 * x], axis=1)
    np.testing.assert_allclose(U.apply(cols, 0.7)[:, 1], 2 * U.apply(x, 0.7), rtol=0, atol=scaled_tol(2 * x, k=16))
    with pytest.raises(ValueError, match=r"or a \(5, k\) matrix"):
        U.apply(np.ones((5, 2, 2)), 0.7)


def _normal_form_211():
    M = np.zeros((6, 6))
    M[0, 1], M[2, 3], M[4, 5] = 2.0, 1.0, 1.0
    M -= M.T
    return np.array([M[i - 1, j - 1] for i, j in hr.planes(6)])


def test_body_frame_coherent_state_names_minus_L_and_the_irrep_that_fits():
    """In so(6) -L has the other chirality: L of normal form (2, 1, 1) has its body-frame coherent state in the
    irrep (2, 1, -1). The error said 'the normal form [2, 1, -1] of L', which is that of -L."""
    L = _normal_form_211()
    with pytest.raises(ValueError, match=r"of -L \(frame='body'.*highest weight \(2, 1, -1\) has a body-frame"):
        hq.coherent_state(hq.irrep(6, (2, 1, 1)), L, frame="body")
    psi = hq.coherent_state(hq.irrep(6, (2, 1, -1)), L, frame="body")
    assert isinstance(psi, qutip.Qobj)
    r = hq.ehrenfest_time(np.linspace(1.0, 2.0, 15), L, [1], [0.0, 0.1], weight=(2, 1, -1))  # (as documented now)
    np.testing.assert_allclose(r.quantum[0, 0], L, rtol=0, atol=1e-12)


def test_one_initial_momentum_only():
    """ehrenfest_time(L0=[[1, 0, 0]]) returned curves of shape (1, 2, 3) against the documented (len(t), 3);
    coherent_state flattened an L of shape (3, 1)."""
    with pytest.raises(ValueError, match=r"L0 must have shape \(3,\) \(3 plane components\), got shape \(1, 3\)"):
        hq.ehrenfest_time([1.0, 1.5, 2.0], [[1.0, 0.0, 0.0]], [2], [0.0, 0.1])
    with pytest.raises(ValueError, match=r"L must be one vector .* got shape \(3, 1\)"):
        hq.coherent_state(hq.irrep(3, (1,)), np.ones((3, 1)))


@pytest.mark.parametrize("label", [(True, 2), (1, np.True_), (None, 2), [2, None]])
def test_plane_labels_of_booleans_are_a_type_error(label):
    """docs/safety.md: booleans where numbers are expected are a TypeError; a plane (True, 2) was a ValueError."""
    rep = hq.irrep(3, (2,))
    for call in (lambda: rep.generator(label), lambda: hq.pi_rotation(rep, label), lambda: hr.plane_index(label, 3)):
        with pytest.raises(TypeError, match=r"a plane is a pair .* not plane indices"):
            call()
