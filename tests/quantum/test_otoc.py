"""hyperrotor.quantum.otoc against the brute-force Heisenberg operator W(t) = expm(iHt) W expm(-iHt).

A generic so(5) rotor (its symmetry sectors are the blocks; W, V generators that move between
sectors, and a random dense operator), at infinite temperature (exact trace), for a ket and for a
mixed density matrix, to 1e-10 relative; the stochastic trace estimate within a few standard errors.
"""
import numpy as np
import pytest
import qutip
import scipy.linalg as sla

import hyperrotor as hr
from hyperrotor.quantum import irrep, otoc, rotor_hamiltonian


pytestmark = pytest.mark.usefixtures("one_blas_thread")  # (tests/quantum/conftest.py)


@pytest.fixture(scope="module")
def problem():
    rng = np.random.default_rng(7)
    rep = irrep(5, (2, 1))  # dim 35
    H = rotor_hamiltonian(rep, rng.uniform(1.0, 2.0, size=10), hbar=0.5)
    W = rep.generator((1, 2), form="hermitian")  # sparse
    A = rng.normal(size=(rep.dim, rep.dim)) + 1j * rng.normal(size=(rep.dim, rep.dim))
    V = qutip.Qobj(A + A.conj().T)  # dense, mixes the sectors
    return rep, H, W, V, rng


def _brute(H, W, V, t, rho, hbar):
    Hd, Wd = H.full(), W.toarray()
    Vd = V.full()
    out = []
    for tk in t:
        U = sla.expm(-1j * tk * Hd / hbar)
        Wt = U.conj().T @ Wd @ U
        C = Wt @ Vd - Vd @ Wt
        out.append(np.trace(rho @ C.conj().T @ C).real)
    return np.array(out)


def test_infinite_temperature_ket_and_density_matrix(problem):
    rep, H, W, V, rng = problem
    t = np.array([0.0, 0.35, 1.2, -0.8])
    d = rep.dim
    ref = _brute(H, W, V, t, np.eye(d) / d, 0.5)
    got = otoc(H, W, V, t, hbar=0.5)
    assert got.stderr is None and got.samples is None
    np.testing.assert_allclose(got.values, ref, rtol=1e-10, atol=1e-10 * ref.max())
    with hr.options(quantum_eigen_max_block=4):  # through the 16 symmetry sectors instead of the sparsity blocks
        np.testing.assert_allclose(otoc(H, W, V, t, hbar=0.5).values, ref, rtol=1e-10, atol=1e-10 * ref.max())
    psi = rng.normal(size=d) + 1j * rng.normal(size=d)
    psi /= np.linalg.norm(psi)
    ref = _brute(H, W, V, t, np.outer(psi, psi.conj()), 0.5)
    np.testing.assert_allclose(otoc(H, W, V, t, state=qutip.Qobj(psi), hbar=0.5).values, ref, rtol=1e-10,
                               atol=1e-10 * ref.max())
    B = rng.normal(size=(d, 3)) + 1j * rng.normal(size=(d, 3))
    rho = B @ B.conj().T
    rho /= np.trace(rho).real
    ref = _brute(H, W, V, t, rho, 0.5)
    np.testing.assert_allclose(otoc(H, W, V, t, state=7.0 * rho, hbar=0.5).values, ref, rtol=1e-10,
                               atol=1e-10 * ref.max())


def test_a_long_time_costs_a_short_one_and_is_right(problem):
    """otoc works in the eigenbases of H's blocks: its price does not grow with |t| (a phase price would refuse
    t = 1e4 here), and the values stay those of the dense Heisenberg operator (to the conditioning of exp at
    phase ~ |t| ||H|| / hbar)."""
    rep, H, W, V, _ = problem
    far = np.array([0.0, 1e4])
    ref = _brute(H, W, V, far, np.eye(rep.dim) / rep.dim, 0.5)
    with hr.options(max_seconds=1.0):
        got = otoc(H, W, V, far, hbar=0.5).values
    np.testing.assert_allclose(got, ref, rtol=1e-7)


def test_stochastic_trace_is_within_its_standard_error(problem):
    rep, H, W, V, _ = problem
    t = np.array([0.5, 1.5])
    exact = otoc(H, W, V, t, hbar=0.5).values
    est = otoc(H, W, V, t, samples=64, hbar=0.5)
    assert est.samples == 64 and np.all(est.stderr > 0)
    assert np.all(np.abs(est.values - exact) <= 5 * est.stderr)
    np.testing.assert_array_equal(est.values, otoc(H, W, V, t, samples=64, hbar=0.5).values)  # rng=0 default


def test_refusals(problem):
    rep, H, W, V, _ = problem
    with pytest.raises(ValueError, match="W has shape"):
        otoc(H, np.eye(3), V, [0.0])
    with pytest.raises(ValueError, match="samples"):
        otoc(H, W, V, [0.0], state=np.ones(rep.dim), samples=4)
    with pytest.raises(ValueError, match="positive semi-definite"):
        otoc(H, W, V, [0.0], state=-np.eye(rep.dim))
