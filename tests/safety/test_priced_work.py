"""Work that grows with something other than a dimension is priced too (review of session 38).

- ``sample_spectrum`` of a GOE/GUE matrix: its dense matrix and ``eigvalsh`` against the memory and time
  budgets (the dense-dimension limit alone let a 6000 x 6000 GUE run past ``max_seconds = 1``);
- propagation by products (``method="krylov"``, ``"expm_multiply"``): the number of products follows the
  phase :math:`\\sum_b \\|H_b\\| |t_\\text{end} - t_0| / \\hbar` of the stepped blocks, not the number of output
  times (a 201-dimensional rotor over ``t = [0, 10]`` ran 18 s under ``max_seconds = 1``);
- ``ehrenfest_time``: the loop over ``ls`` as a whole (each irrep was priced alone; ``ls = [1] * 10**6``
  started a four-hour loop).
"""
from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sps

import hyperrotor as hr
import hyperrotor.quantum as hq
from hyperrotor import _pricing
from hyperrotor.quantum import correspondence


def test_random_matrix_spectra_are_priced_by_memory_and_time():
    with hr.options(max_seconds=1.0), pytest.raises(hr.BudgetError, match=r"max_seconds"):
        hq.sample_spectrum("gue", 6000, rng=1)  # ~2.3e12 flops: ~180 s estimated
    with hr.options(max_memory_bytes=10**6), pytest.raises(hr.BudgetError, match=r"max_memory_bytes"):
        hq.sample_spectrum("goe", 400, rng=1)  # 6 x 8 x 400^2 bytes = 7.7e6
    with hr.options(max_memory_bytes=10**6):
        assert hq.sample_spectrum("poisson", 400, rng=1).shape == (400,)  # no matrix
        assert hq.sample_spectrum("goe", 100, rng=1).shape == (100,)  # 4.8e5 bytes: within


def _rotor(l=20):
    rep = hq.irrep(3, (l,))
    return rep, hq.rotor_hamiltonian(rep, [1.0, 2.0, 3.0])


@pytest.mark.parametrize("method, key", [("krylov", "krylov_phase"), ("expm_multiply", "expm_phase")])
def test_the_phase_of_stepped_blocks_is_their_row_bound_times_the_span(method, key):
    rep, H = _rotor()
    prop = hq.SectorPropagator(H, method=method, hbar=0.5)
    stepped = [b for b in prop._parts if b.engine is not None]
    assert stepped
    bound = sum(float(np.abs(sps.csr_matrix(b.matrix)).sum(axis=1).max()) for b in stepped)
    phases = prop._stepping_phases(np.array([0.25, 1.0, 3.25]))
    assert phases[key] == pytest.approx(bound * 3.0 / 0.5, rel=1e-12)
    assert phases[({"krylov_phase", "expm_phase"} - {key}).pop()] == 0.0
    assert prop._stepping_phases(np.array([1.0])) == {"krylov_phase": 0.0, "expm_phase": 0.0}
    # a block that is diagonalized costs the same at any span: no phase
    eig = hq.SectorPropagator(H, method="eigen")
    assert eig._stepping_phases(np.array([0.0, 1e6])) == {"krylov_phase": 0.0, "expm_phase": 0.0}


def test_a_long_span_of_lanczos_products_is_refused_before_the_run():
    rep, H = _rotor(100)
    psi = np.ones(rep.dim) / rep.dim**0.5
    with hr.options(max_seconds=1.0):
        with pytest.raises(hr.BudgetError, match=r"phase \|\|H\|\| t / hbar = .*max_seconds"):
            hq.evolve(H, psi, [0.0, 10.0], method="krylov")
        with pytest.raises(hr.BudgetError, match="max_seconds"):
            hq.SectorPropagator(H, method="expm_multiply").evolve(psi, [0.0, 100.0])
        # the same span diagonalized, and a short span of products, are within the budget
        res = hq.evolve(H, psi, [0.0, 10.0], method="eigen")
        short = hq.evolve(H, psi, [0.0, 1e-3], method="krylov")
    ref = hq.evolve(H, psi, [0.0, 1e-3], method="eigen")
    assert abs(res.states[-1].norm() - 1.0) < 1e-10
    assert np.abs(short.states[-1].full() - ref.states[-1].full()).max() < 1e-8


def test_the_irreps_of_an_ehrenfest_sweep_are_priced_together_before_any_run(monkeypatch):
    def no_run(*args, **kwargs):  # pragma: no cover - must not be reached
        raise AssertionError("the classical run started before the sweep was priced")

    monkeypatch.setattr(correspondence, "simulate", no_run)
    with pytest.raises(hr.BudgetError, match=r"1000000 irreps \(ls\).*max_seconds"):
        hq.ehrenfest_time([1.0, 2.0, 3.0], [0.3, 0.2, 1.0], [1] * 10**6, np.linspace(0.0, 1.0, 5))
    # fewer irreps, but large ones: the dimensions are priced before the run
    sizes = [2 * l + 1 for l in (3000, 3500, 4000)]
    seconds = _pricing.estimate("ehrenfest_time", irreps=3, dims=sum(sizes), dim_squares=sum(d * d for d in sizes),
                                n_times=5, n=3)[0].amount
    with hr.options(max_seconds=0.5 * seconds), pytest.raises(hr.BudgetError, match=r"3 irreps \(ls\) x 5 times"):
        hq.ehrenfest_time([1.0, 2.0, 3.0], [0.3, 0.2, 1.0], [3000, 3500, 4000], np.linspace(0.0, 1.0, 5))


def test_rotations_of_a_state_are_priced_by_their_phase_before_any_search(monkeypatch):
    from scipy.spatial.transform import Rotation

    from hyperrotor.quantum import coherent

    rep = hq.irrep(3, (400,))
    Q = Rotation.from_rotvec([0.9, -1.7, 1.1]).as_matrix()
    psi = np.ones(rep.dim) / rep.dim**0.5
    gens = rep.generators()

    def seconds(R):  # the model at sum |theta| max row sum of |X|, computed here from the dense generators
        factors = coherent._givens_angles(R)
        phase = sum(abs(th) * float(np.abs(gens[p].toarray()).sum(axis=1).max()) for p, th in factors)
        return _pricing.estimate("apply_rotation", dim=rep.dim, phase=phase, factors=len(factors))[0].amount

    L = [1.0, 2.0, 0.5]
    budget = 0.5 * min(seconds(Q), seconds(coherent.normal_form_rotation(np.array(L))[0]))
    assert budget > 0.0

    def no_search(*args, **kwargs):  # pragma: no cover - must not be reached
        raise AssertionError("the highest-weight search started before the rotation was priced")

    with hr.options(max_seconds=budget):
        with pytest.raises(hr.BudgetError, match=r"apply_rotation: 3 plane rotations .*max_seconds"):
            hq.apply_rotation(rep, Q, psi)
        monkeypatch.setattr(coherent, "highest_weight_state", no_search)
        with pytest.raises(hr.BudgetError, match=r"apply_rotation: .* plane rotations"):
            hq.coherent_state(rep, L)
        # the identity has no factor and no price: the state comes back unchanged
        np.testing.assert_array_equal(hq.apply_rotation(rep, np.eye(3), psi), psi)
