"""Gaps found by a review: work priced by what drives it, tolerances in their range, every argument checked on
every route, text names that match the symbols an Inertia holds, and Casimirs of very different magnitudes.
"""
from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

import hyperrotor as hr
from hyperrotor.classical.simulate import estimate_cost
import hyperrotor.quantum as hq
from hyperrotor.quantum._sector_blocks import Block

EPS = float(np.finfo(float).eps)


# ---------------------------------------------------------------------------------------------------------------
# 1. otoc: priced by the columns, times and block sizes before any work (its work does not grow with |t|)
# ---------------------------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def so3_rotor():
    rep = hq.irrep(3, (2,))  # dim 5
    H = hq.rotor_hamiltonian(rep, [1.0, 1.7, 3.1], hbar=0.7)
    W = rep.generator((1, 2), form="hermitian")
    V = rep.generator((2, 3), form="hermitian")
    return rep, H, W, V


def test_otoc_is_refused_by_its_block_work_before_any_diagonalization(monkeypatch):
    rep = hq.irrep(3, (400,))  # dim 801: 4 sectors of ~200, each column costs ~1.6e5 per propagation
    H = hq.rotor_hamiltonian(rep, [1.0, 2.0, 3.5])
    W, V = rep.generator((1, 2), form="hermitian"), rep.generator((2, 3), form="hermitian")

    def no_work(self, *args, **kwargs):
        raise AssertionError("a block was diagonalized before the price was checked")

    monkeypatch.setattr(Block, "diagonalize", no_work)
    # the old price (times x columns only) was ~0.2 s for this call, which takes ~10 s
    with hr.options(max_seconds=1.0), pytest.raises(hr.BudgetError) as err:
        hq.otoc(H, W, V, np.linspace(0.0, 1.0, 20))
    msg = str(err.value)
    assert msg.startswith("otoc: 20 times (t) x 801 state columns")
    assert "sum n^2 = 1.6e+05" in msg and "hr.options(max_seconds=...)" in msg


# ---------------------------------------------------------------------------------------------------------------
# 2. relative tolerances: 0 < rtol < 1 (0 allowed where it means exact comparison)
# ---------------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("call", [
    pytest.param(lambda r: hr.detect_closed_form([1.0, 2.0, 3.0], rtol=r), id="detect_closed_form"),
    pytest.param(lambda r: hr.linear_stability([3.0, 2.0, 1.0], (1, 3), 1.0, rtol=r), id="linear_stability"),
    pytest.param(lambda r: hq.spectrum(np.diag([1.0, 2.0, 2.0]), rtol=r), id="spectrum"),
    pytest.param(lambda r: hq.real_form(hq.irrep(3, (1,)), rtol=r), id="real_form"),
    pytest.param(lambda r: hr.simulate([2.0, 3.0, 4.0], [0.6, 1.0, -0.5], [0.0, 1.0], rtol=r), id="simulate"),
    pytest.param(lambda r: hr.simulate([2.0, 3.0, 4.0], [0.6, 1.0, -0.5], [0.0, 1.0], method="DOP853", rtol=r),
                 id="simulate-scipy"),
    pytest.param(lambda r: estimate_cost([2.0, 3.0, 4.0], [0.6, 1.0, -0.5], [0.0, 1.0], rtol=r),
                 id="estimate_cost"),
    pytest.param(lambda r: hr.Scene([2.0, 3.0, 4.0], [0.6, 1.0, -0.5], [0.0, 1.0], rtol=r), id="Scene"),
])
@pytest.mark.parametrize("rtol", [1, 1.0, 2.5, -1e-3, float("inf")])
def test_a_relative_tolerance_outside_0_1_is_refused(call, rtol):
    with pytest.raises(ValueError, match=r"rtol must be a relative tolerance with 0 <?=? ?rtol < 1, got"):
        call(rtol)


@pytest.mark.parametrize("key", ["simulate_rtol", "scene_rtol"])
@pytest.mark.parametrize("rtol", [1.0, 2.5, 0.0])
def test_the_default_rtol_options_are_relative_tolerances_too(key, rtol):
    with pytest.raises(ValueError, match=rf"{key} must be a relative tolerance with 0 < {key} < 1, got"):
        with hr.options(**{key: rtol}):
            pass
    with hr.options(**{key: 1e-7}):
        assert hr.options[key] == 1e-7


def test_tolerances_inside_the_range_keep_their_meaning():
    assert hr.detect_closed_form([1.0, 1.4, 1.0], rtol=0.5) == {"kind": "equal"}  # ptp 0.4 <= 0.5 * 1.4
    assert hr.detect_closed_form([1.0, 1.4, 1.0], rtol=0.2) == {"kind": "euler-poinsot"}
    assert hr.detect_closed_form([2.0, 2.0, 2.0], rtol=0) == {"kind": "equal"}  # 0: exact comparison
    levels, deg = hq.spectrum(np.diag([1.0, 1.3, 2.0]), rtol=0.2)  # threshold 0.2 * 2.0 = 0.4
    np.testing.assert_array_equal(deg, [2, 1])
    np.testing.assert_allclose(levels, [1.15, 2.0], rtol=1e-15)


def test_spectrum_checks_rtol_and_atol_on_every_route():
    with pytest.raises(TypeError, match="rtol must be a relative tolerance"):
        hq.spectrum(np.diag([1.0, 2.0]), atol=1e-3, rtol="abc")  # rtol unused when atol is given
    with pytest.raises(ValueError, match="atol must be finite and >= 0, got -1.0"):
        hq.spectrum(np.diag([1.0, 2.0]), atol=-1.0)


# ---------------------------------------------------------------------------------------------------------------
# 3. arguments checked on the routes that do not use them
# ---------------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("kwargs, error, match", [
    (dict(rtol=-1), ValueError, r"rtol must be a relative tolerance with 0 < rtol < 1, got -1"),
    (dict(rtol=1.0), ValueError, r"rtol must be a relative tolerance with 0 < rtol < 1, got 1.0"),
    (dict(rtol="abc"), TypeError, r"rtol must be a relative tolerance, a real number with 0 < rtol < 1, got 'abc'"),
    (dict(method="bogus"), ValueError, r"unknown method 'bogus'; allowed: 'auto', 'splitting2'"),
    (dict(method=5), TypeError, r"method must be one of 'auto'"),
])
def test_scene_checks_rtol_and_method_with_a_closed_form_body(kwargs, error, match):
    with pytest.raises(error, match=match):
        hr.Scene([2.0, 2.0, 2.0], [0.1, 0.2, 0.3], [0.0, 1.0], **kwargs)  # equal moments: never integrated
    scene = hr.Scene([2.0, 2.0, 2.0], [0.1, 0.2, 0.3], [0.0, 1.0])
    setattr(scene, *next(iter(kwargs.items())))  # changed after construction: refused by evaluate
    with pytest.raises(error, match=match):
        scene.evaluate()


def test_real_form_checks_rtol_for_a_real_representation():
    rep = hq.vector_rep(3)
    assert rep.is_real and hq.real_form(rep) is rep
    with pytest.raises(TypeError, match="rtol must be a relative tolerance.*got 'abc' of type str"):
        hq.real_form(rep, rtol="abc")


@pytest.mark.parametrize("kwargs", [{}, {"state": np.ones(5)}], ids=["trace", "ket"])
def test_otoc_checks_rng_without_samples(so3_rotor, kwargs):
    _, H, W, V = so3_rotor
    with pytest.raises(TypeError, match="rng must be None, an integer seed.*got 'abc'"):
        hq.otoc(H, W, V, [0.0, 1.0], rng="abc", hbar=0.7, **kwargs)
    with pytest.raises(ValueError, match="rng seed must be a non-negative integer, got -3"):
        hq.otoc(H, W, V, [0.0, 1.0], rng=-3, hbar=0.7, **kwargs)


# ---------------------------------------------------------------------------------------------------------------
# 4. Inertia.subs: text names are the symbols the inertia holds
# ---------------------------------------------------------------------------------------------------------------
def test_inertia_subs_text_names_match_the_positive_symbols():
    inertia = hr.Inertia.symbolic(3)  # positive I_12, I_13, I_23
    I12, I13, I23 = inertia.symbolic_moments
    assert I12.is_positive
    assert inertia.subs("I_12", 2).symbolic_moments == (2, I13, I23)
    assert inertia.subs({"I_12": 1, "I_13": "3/2", "I_23": 2}).moments.tolist() == [1.0, 1.5, 2.0]
    # names in the new value are the inertia's symbols too (the same objects, assumptions kept)
    doubled = inertia.subs("I_12", "2*I_13").symbolic_moments[0]
    assert doubled == 2 * I13 and doubled.free_symbols == {I13}
    assert inertia.subs(I12, 5).symbolic_moments[0] == 5  # SymPy objects as before


def test_inertia_subs_refuses_names_it_does_not_hold():
    with pytest.raises(hr.ParseError, match=r"unknown name 'I_45' .*allowed names: I_12, I_13, I_23"):
        hr.Inertia.symbolic(3).subs("I_45", 1)
    with pytest.raises(hr.ParseError, match=r"unknown name 'a' .*allowed names: none"):
        hr.Inertia([1.0, 2.0, 3.0]).subs("a", 1)
    a, a_pos = sp.Symbol("a"), sp.Symbol("a", positive=True)
    with pytest.raises(ValueError, match="holds 2 symbols named 'a'.*pass the SymPy symbol itself"):
        hr.Inertia([a, a_pos, 3]).subs("a", 1)


# ---------------------------------------------------------------------------------------------------------------
# 5. form and store_states checked
# ---------------------------------------------------------------------------------------------------------------
def test_rotor_hamiltonian_checks_form_for_a_representation():
    rep = hq.irrep(3, (1,))
    with pytest.raises(ValueError, match="unknown form 'bogus'; allowed: 'antihermitian', 'hermitian'"):
        hq.rotor_hamiltonian(rep, [1.0, 2.0, 3.0], form="bogus")
    with pytest.raises(TypeError, match="form must be one of 'antihermitian', 'hermitian', got 1"):
        hq.rotor_hamiltonian(rep, [1.0, 2.0, 3.0], form=1)
    same = hq.rotor_hamiltonian(rep, [1.0, 2.0, 3.0], form="hermitian")  # a Representation has its own form
    np.testing.assert_array_equal(same.full(), hq.rotor_hamiltonian(rep, [1.0, 2.0, 3.0]).full())


@pytest.mark.parametrize("key, value, match", [
    ("store_states", "no", r"store_states must be True, False or None, got 'no' of type str"),
    ("store_states", 0, r"store_states must be True, False or None, got 0 of type int"),
    ("store_final_state", 1, r"store_final_state must be True or False, got 1 of type int"),
])
@pytest.mark.parametrize("method", ["auto", "eigen", "sesolve"])
def test_evolve_result_options_are_switches(so3_rotor, key, value, match, method):
    _, H, _, _ = so3_rotor
    with pytest.raises(TypeError, match=match):
        hq.evolve(H, np.ones(5) / np.sqrt(5), [0.0, 1.0], method=method, options={key: value})


def test_sector_propagator_evolve_checks_its_switches(so3_rotor):
    _, H, _, _ = so3_rotor
    U = hq.SectorPropagator(H)
    with pytest.raises(TypeError, match="store_states must be True, False or None, got 'yes'"):
        U.evolve(np.ones(5) / np.sqrt(5), [0.0, 1.0], store_states="yes")
    result = U.evolve(np.ones(5) / np.sqrt(5), [0.0, 0.5, 1.0], e_ops=[H], store_states=False)
    assert len(result.states) == 0 and len(result.expect[0]) == 3


# ---------------------------------------------------------------------------------------------------------------
# 6. Casimirs of plane components of very different magnitudes
# ---------------------------------------------------------------------------------------------------------------
def _elementary(values: list[Fraction], k: int) -> Fraction:
    e = [Fraction(1)] + [Fraction(0)] * len(values)
    for v in values:
        for j in range(len(values), 0, -1):
            e[j] += v * e[j - 1]
    return e[k]


@pytest.mark.parametrize("N, components", [
    (4, {(1, 2): 1e8, (3, 4): 1e-4}),
    (5, {(1, 2): 1e8, (3, 4): 1e-4}),  # axis 5 at rest
    (6, {(1, 2): 1e8, (3, 4): 1.0, (5, 6): 1e-4}),
    (7, {(1, 3): 3e6, (2, 5): 1e-5, (4, 7): 2.5}),  # block diagonal after a permutation of the axes
])
def test_casimirs_of_a_normal_form_with_very_different_magnitudes(N, components):
    """c_2k = e_k(a_1^2, ..., a_m^2) exactly for L in normal form; each is a sum of positive terms, so the tolerance
    is relative: a few N eps. (Newton's identities on tr(L^k) gave c_4 = 0 or -1e16 here instead of 1e8.)"""
    planes = hr.planes(N)
    L = np.zeros(len(planes))
    for p, a in components.items():
        L[planes.index(p)] = a
    squares = [Fraction(a) ** 2 for a in components.values()]
    exact = np.array([float(_elementary(squares, k)) for k in range(1, N // 2 + 1)])
    body = hr.RigidBody(np.ones(len(planes)))
    c = body.casimirs(L, of="L")
    np.testing.assert_allclose(c, exact, rtol=4 * N * EPS, atol=0)
    batch = body.casimirs(np.broadcast_to(L, (2, 3, L.size)), of="L")
    assert batch.shape == (2, 3, N // 2)
    np.testing.assert_allclose(batch, np.broadcast_to(exact, batch.shape), rtol=4 * N * EPS, atol=0)


# ----------------------------------------------------------------------------
# times so long that double precision rounds the phases E t / hbar (evolve at t = 1e300 returned a state, silently)
# ----------------------------------------------------------------------------
@pytest.mark.parametrize("entry", ["evolve", "otoc", "SectorPropagator.evolve", "SectorPropagator.apply"])
def test_phases_rounded_beyond_1e_minus_6_are_named(so3_rotor, entry):
    from hyperrotor.quantum._krylov import row_bound
    from hyperrotor.quantum.sector_propagator import PHASE_ROUNDING_WARN

    rep, H, W, V = so3_rotor  # hbar = 0.7
    bound = row_bound(H.data.as_scipy() if hasattr(H.data, "as_scipy") else H.full())
    t_star = PHASE_ROUNDING_WARN * 0.7 / (np.finfo(float).eps * bound)  # where eps ||H|| t / hbar = 1e-6
    psi = np.ones(rep.dim) / np.sqrt(rep.dim)
    call = {"evolve": lambda t: hq.evolve(H, psi, [0.0, t], hbar=0.7, method="eigen"),
            "otoc": lambda t: hq.otoc(H, W, V, [0.0, t], hbar=0.7),
            "SectorPropagator.evolve": lambda t: hq.SectorPropagator(H, hbar=0.7).evolve(psi, [0.0, t]),
            "SectorPropagator.apply": lambda t: hq.SectorPropagator(H, hbar=0.7).apply(psi, -t)}[entry]
    call(0.5 * t_star)  # below: silent (warnings are errors in the tests)
    with pytest.warns(hq.PhaseRoundingWarning, match=r"rounded by up to ~2e-06 radians") as record:
        call(2.0 * t_star)
    assert len(record) == 1 and f"{entry.split('.')[-1]}:" in str(record[0].message)
