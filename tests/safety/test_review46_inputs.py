"""Bad and extreme input found by the API review of session 46: each refused by name or answered right.

Ragged lists reached NumPy's "inhomogeneous shape" in the quantum validators (states, L, ``ls``) and a boolean
entry of ``ls`` was read as 1; ``Scene(observables=None)`` and ``planes=3`` raised bare Python errors;
``basis_matrix("12", 3)`` validated the text label and then subtracted from it; finite input overflowed to
``inf`` / ``NaN`` silently (angular momenta, Manakov integrals, expectation values of a state with an amplitude
of 1e308) or underflowed to a Hamiltonian of zeros (``hbar = 1e-320``); the normal form of ``L`` near the
overflow failed with a ``RuntimeError``; an exact integer beyond the floats raised ``OverflowError`` (a spin
``10**400``, a step of ``1e-320`` in ``lyapunov``); an abstract solver class ran into ``NotImplementedError``.
"""
from __future__ import annotations

import numpy as np
import pytest

import hyperrotor as hr
import hyperrotor.quantum as hq
from hyperrotor.classical.solvers import FixedStepSolver, Splitting

BODY3 = hr.RigidBody(hr.Inertia([1.0, 2.0, 3.5]))
R3 = hq.irrep(3, (1,))


@pytest.mark.parametrize("call", [
    lambda: hq.coherent_state(R3, [0.1, 0.2, [1.0]]),
    lambda: hq.normal_form_rotation([0.1, 0.2, [1.0]]),
    lambda: hq.generator_expectations(R3, [1, 0, [0]]),
    lambda: hq.evolve(hq.rotor_hamiltonian(R3, BODY3), [1, 0, [0]], [0.0, 1.0]),
    lambda: hq.ehrenfest_time(BODY3, [0.1, 0.2, 1.0], [1, [2]], [0.0, 1.0]),
    lambda: hr.locked_axes([0.1, [1.0], 0.0]),
], ids=["coherent_state", "normal_form_rotation", "generator_expectations", "evolve", "ehrenfest_time",
        "locked_axes"])
def test_ragged_lists_are_refused_by_name(call):
    with pytest.raises(TypeError, match=r"^(L|psi|psi0|ls|omega0) must be a") as info:
        call()
    assert "inhomogeneous" not in str(info.value)


def test_ehrenfest_degrees_are_integers_named_as_given():
    with pytest.raises(TypeError, match=r"ls\[1\] = True"):
        hq.ehrenfest_time(BODY3, [0.1, 0.2, 1.0], [1, True], [0.0, 1.0])
    with pytest.raises(TypeError, match=r"ls\[1\] must be an integer >= 1, got 2.5"):
        hq.ehrenfest_time(BODY3, [0.1, 0.2, 1.0], [1, 2.5], [0.0, 1.0])
    assert list(hq.ehrenfest_time(BODY3, [0.1, 0.2, 1.0], (1, 2), [0.0, 1.0]).ls) == [1, 2]


@pytest.mark.parametrize("kw, name", [(dict(observables=None), "observables"), (dict(observables=1), "observables"),
                                      (dict(planes=3), "planes"), (dict(planes=True), "planes")])
def test_scene_lists_that_are_not_sequences_are_refused_by_name(kw, name):
    with pytest.raises(TypeError, match=rf"^{name} must be a sequence of"):
        hr.Scene(BODY3, [0.1, 0.2, 0.3], [0.0, 1.0], **kw).evaluate()
    with pytest.raises(ValueError, match="observables is empty; allowed: omega"):
        hr.Scene(BODY3, [0.1, 0.2, 0.3], [0.0, 1.0], observables=[]).evaluate()
    one = hr.Scene(BODY3, [0.1, 0.2, 0.3], [0.0, 1.0], planes=np.array([[1, 2]])).evaluate()
    assert one.omega.shape == (2, 1)


def test_basis_matrix_reads_text_labels_as_plane_index_does():
    for label in ("12", "1,2", (1, 2)):
        np.testing.assert_array_equal(hr.basis_matrix(label, 3), hr.to_matrix([1, 0, 0]))
    with pytest.raises(ValueError, match="a plane is a pair"):
        hr.basis_matrix("13x", 3)


def test_overflowing_moments_and_integrals_are_refused_not_inf():
    with pytest.raises(ValueError, match=r"angular_momentum: omega too large, max \|omega\| = 1e\+308"):
        BODY3.angular_momentum([0.1, 0.2, 1e308])
    with pytest.raises(ValueError, match=r"manakov_integrals: lam too large"):
        BODY3.manakov_integrals([0.1, 0.2, 0.3], 1e308)
    with pytest.raises(ValueError, match=r"manakov_integrals: omega too large, max \|omega\| = 1e\+200"):
        BODY3.manakov_integrals([0.1, 0.2, 1e200])
    np.testing.assert_allclose(BODY3.angular_momentum([0.1, 0.2, 0.3]), [0.1, 0.4, 1.05], rtol=1e-15)


def test_expectation_values_do_not_depend_on_the_scale_of_the_state():
    """<L> = <psi|L|psi> / <psi|psi> is homogeneous of degree 0: amplitudes near the overflow and the underflow
    give the values of the unit state (they gave NaN: |psi|^2 was inf or 0)."""
    ref = hq.generator_expectations(R3, [1.0, 0.0, 0.5])
    for s in (1e300, 1e-300, 2.0**-1070):
        np.testing.assert_allclose(hq.generator_expectations(R3, np.array([1.0, 0.0, 0.5]) * s), ref,
                                   rtol=0, atol=8 * np.finfo(float).eps)
    np.testing.assert_allclose(hq.generator_expectations(R3, [1.0, 0.0, 1e308]), [-1.0, 0.0, 0.0], atol=1e-15, rtol=0)


@pytest.mark.parametrize("hbar", [1e-320, 1e-160])
def test_an_underflowing_hbar_is_refused(hbar):
    for call in (lambda: hq.rotor_hamiltonian(R3, BODY3, hbar=hbar),
                 lambda: hq.sector_spectra(hq.irrep(3, (2,)), BODY3, hbar=hbar)):
        with pytest.raises(ValueError, match="the Hamiltonian underflows the float range"):
            call()
    H = hq.rotor_hamiltonian(R3, BODY3, hbar=1e-150)  # (hbar^2 / 2I still normal: the exact scaling of hbar = 1)
    np.testing.assert_allclose(H.full() * 1e300, hq.rotor_hamiltonian(R3, BODY3).full(), rtol=1e-14)


def test_the_normal_form_does_not_depend_on_the_scale_of_L():
    L = np.array([0.3, -1.0, 0.5, 0.2, 0.7, -0.4])
    Q, lam = hq.normal_form_rotation(L)
    A = hr.to_matrix(L, convention="standard")
    for s in (1e300, 1e-300):
        Qs, lams = hq.normal_form_rotation(L * s)
        np.testing.assert_allclose(lams, lam * s, rtol=1e-14)
        B = Qs.T @ A @ Qs  # (Q is fixed up to a rotation inside each 2-plane: compare the normal form it gives)
        np.testing.assert_allclose(B[[0, 2], [1, 3]], lam, rtol=1e-13)
        assert np.abs(B[[0, 0, 1, 1], [2, 3, 2, 3]]).max() < 1e-14 and np.linalg.det(Qs) > 0
    Q3, lam3 = hq.normal_form_rotation([0.1, 0.2, 1e308])
    assert lam3[0] == pytest.approx(1e308, rel=1e-15)
    with pytest.raises(ValueError, match="overflows double precision"):
        hq.normal_form_rotation([1.7e308, 1.7e308, 1.7e308])
    psi = hq.coherent_state(R3, [0.1, 0.2, 1e308]).full().ravel()
    assert abs(np.vdot(psi, hq.coherent_state(R3, [0.0, 0.0, 1.0]).full().ravel())) == pytest.approx(1.0, abs=1e-12)


def test_exact_numbers_beyond_the_floats_are_refused_by_name():
    with pytest.raises(ValueError, match=r"spin j must be finite, got ~1e\+400 \(an integer\), beyond double"):
        hq.jmat_generators(10**400)
    with pytest.raises(ValueError, match=r"dt must be finite"):
        hr.simulate(BODY3, [0.1, 0.2, 0.3], [0.0, 1.0], dt=10**400)
    quartet = hr.RigidBody(hr.Inertia.quartet(0.5))
    for kw in (dict(dt=1e-320), dict(renorm_interval=1e-320)):
        with pytest.raises(hr.BudgetError, match=r"inf units of work"):
            hr.lyapunov(quartet, np.linspace(0.1, 1.0, 10), 5.0, **kw)


@pytest.mark.parametrize("cls", [hr.Solver, FixedStepSolver, Splitting])
def test_abstract_solver_classes_are_not_methods(cls):
    with pytest.raises(TypeError, match=f"method {cls.__name__} is an abstract base class"):
        hr.simulate(BODY3, [0.1, 0.2, 0.3], [0.0, 1.0], method=cls, dt=0.1)


# ------------------------------------------------------------------ found by the review of the session's diff
def test_manakov_integrals_of_a_symbolic_mass_tensor_with_numeric_L_stay_symbolic():
    import sympy as sp

    J = sp.symbols("J1:5", positive=True)
    body = hr.RigidBody(hr.Inertia.from_mass_tensor(J))
    out = body.manakov_integrals(np.arange(1.0, 7.0), 0.5, of="L")
    assert len(out) == 3 and all(isinstance(x, sp.Expr) for x in out)
    values = dict(zip(J, (1, 2, 3, 4)))
    numeric = hr.RigidBody(hr.Inertia.from_mass_tensor([1.0, 2.0, 3.0, 4.0])).manakov_integrals(
        np.arange(1.0, 7.0), 0.5, of="L")
    np.testing.assert_allclose([float(x.subs(values)) for x in out], numeric, rtol=1e-13)


def test_a_small_time_budget_still_runs_a_small_body():
    """The set-up model of simulate had a floor of 0.1 s: under max_seconds = 0.05 every call was refused."""
    with hr.options(max_seconds=0.05):
        tr = hr.simulate(BODY3, [0.1, 0.2, 0.3], np.linspace(0.0, 1.0, 5), method="splitting8", dt=0.1)
        assert tr.omega.shape == (5, 3)
        assert hr.casimir_shift([1.0, 2.0, 3.0]) > 0


def test_ehrenfest_degrees_may_be_sympy_integers():
    import sympy as sp

    res = hq.ehrenfest_time(BODY3, [0.1, 0.2, 1.0], [sp.Integer(1), sp.Integer(2)], [0.0, 1.0])
    assert list(res.ls) == [1, 2]


def test_the_same_run_in_a_different_number_of_chunks_is_equal(monkeypatch):
    """stats["chunks"] follows the machine's speed (chunks are sized from measured times), like the wall time."""
    from hyperrotor.classical.solvers import chunks

    t = np.linspace(0.0, 2.0, 3)
    one = hr.simulate(BODY3, [0.1, 0.2, 0.3], t, method="splitting8", dt=0.01)
    monkeypatch.setattr(chunks, "FIRST_CHUNK_FLOWS", 500)  # (a short first chunk, then chunks of ~1 us)
    with hr.options(chunk_seconds=1e-6):
        many = hr.simulate(BODY3, [0.1, 0.2, 0.3], t, method="splitting8", dt=0.01)
    assert many.stats["chunks"] != one.stats["chunks"] and many == one


def test_equal_symbolic_bodies_hash_alike():
    import sympy as sp

    a, b = sp.symbols("a b", positive=True)
    one, two = hr.RigidBody([(a + b) ** 2, a, b]), hr.RigidBody([a**2 + 2 * a * b + b**2, a, b])
    assert one == two and hash(one) == hash(two) and len({one, two}) == 1


def test_estimate_cost_checks_its_time_budget_first():
    from hyperrotor.classical.simulate import estimate_cost

    for bad, kind in (("abc", TypeError), (-1.0, ValueError), (float("nan"), ValueError)):
        with pytest.raises(kind, match="max_seconds"):
            estimate_cost(BODY3, [0.1, 0.2, 0.3], [0.0], method="DOP853", rtol=1e-6, max_seconds=bad)


def test_refusals_carry_their_figures_through_a_pickle():
    """A caller that words a refusal its own way (the command line) reads the figures, not the text: every refusal
    built by _pricing.refuse carries what, needed, unit, budget and option, also after a pickle round trip."""
    import pickle

    with hr.options(max_seconds=1e-9), pytest.raises(hr.BudgetError) as info:
        hr.simulate(np.ones(4950), np.ones(4950), [0.0, 1.0], dt=0.1)
    with pytest.raises(hr.StepBudgetError) as steps:
        hr.simulate(BODY3, [0.1, 0.2, 0.3], np.linspace(0.0, 1e6, 3), dt=1e-3, max_steps=10)
    for err, option, unit in ((info.value, "max_seconds", "seconds"), (steps.value, "max_steps", "integration steps")):
        back = pickle.loads(pickle.dumps(err))
        for e in (err, back):
            assert (e.option, e.unit, e.budget) == (option, unit, 1e-9 if option == "max_seconds" else 10)
            assert e.needed > e.budget and e.what and f"{e.what} would need ~" in str(e)
