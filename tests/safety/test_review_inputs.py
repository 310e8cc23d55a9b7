"""Bad input found by the input review of session 38: each refused with a message naming it, no silent answer.

Small integer types wrapped around in the matrix maps, NaN and a NaN tolerance passed through them, overflow
gave NaN Casimirs and an infinite energy with a RuntimeWarning only, a ragged time grid reached NumPy's own
error, ``events=5`` a bare ``TypeError``, a body at rest divided by zero in the demo, and the harmonic
dimension lost all its digits for degrees near 1e15 (the budget let ``harmonic_rep(3, 10**15)`` run).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import hyperrotor as hr
import hyperrotor.quantum as hq
from hyperrotor._cost_models import _harmonic_dim
from hyperrotor.classical.solvers import casimir_shift


@pytest.mark.parametrize("dtype", [np.int8, np.uint8, np.int16, np.uint16, np.int32, np.uint32, np.int64])
def test_integer_components_give_the_exact_antisymmetric_matrix(dtype):
    comps = np.array([1, 2, 127], dtype=dtype)
    M = hr.to_matrix(comps)
    np.testing.assert_array_equal(M, -M.T)
    np.testing.assert_array_equal(M, hr.to_matrix(comps.astype(float)))
    np.testing.assert_array_equal(hr.to_components(M), [1, 2, 127])
    low = np.array([-128, 0, 0], dtype=np.int8)
    assert hr.to_matrix(low)[0, 1] == 128 and hr.to_matrix(low)[1, 0] == -128


def test_a_wrapped_unsigned_matrix_is_not_antisymmetric():
    M = np.array([[0, 255, 2], [1, 0, 253], [254, 3, 0]], dtype=np.uint8)  # M + M^T wraps to 0 in uint8
    with pytest.raises(ValueError, match="not antisymmetric"):
        hr.to_components(M)


@pytest.mark.parametrize("call, name", [
    (lambda: hr.to_matrix([np.nan, 0.2, 0.3]), "components"),
    (lambda: hr.to_components(np.array([[np.nan, 0.1, 0.2], [-0.1, 0, 0.3], [-0.2, -0.3, 0]])), "matrix"),
    (lambda: hr.lie_bracket([np.nan, 0.2, 0.3], [0.3, 0.1, 0.2]), "x"),
    (lambda: hr.lie_bracket([0.1, 0.2, 0.3], [0.3, np.inf, 0.2]), "y"),
])
def test_non_finite_components_are_refused_by_name(call, name):
    with pytest.raises(ValueError, match=rf"{name} must be finite"):
        call()


@pytest.mark.parametrize("atol, error", [(np.nan, ValueError), (-1.0, ValueError), (True, TypeError), (1j, TypeError)])
def test_the_antisymmetry_tolerance_must_be_a_non_negative_number(atol, error):
    M = np.array([[0.0, 0.1, 0.2], [0.4, 0.0, 0.3], [-0.2, -0.3, 0.0]])  # not antisymmetric
    with pytest.raises(error, match="atol"):
        hr.to_components(M, atol=atol)


def test_casimirs_and_energy_beyond_double_precision_raise_instead_of_nan_or_inf():
    body = hr.RigidBody([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])
    w = np.array([0.3, 0.2, 0.1, 0.5, 0.7, 0.1])
    L = body.angular_momentum(w)
    c2, c4 = body.casimirs(w)
    assert c2 == pytest.approx(float(np.sum(L**2)), rel=1e-14)
    pf = L[0] * L[5] - L[1] * L[4] + L[2] * L[3]  # Pf of the 4 x 4 matrix, planes 12 13 14 23 24 34
    assert c4 == pytest.approx(pf**2, rel=1e-12)
    with pytest.raises(ValueError, match="casimirs: values too large.*overflows double precision"):
        body.casimirs([1e160, 2, 3, 4, 5, 6])  # c_2 ~ 1e320
    with pytest.raises(ValueError, match="energy: omega too large.*computing it overflows"):
        body.energy([1e200, 2, 3, 4, 5, 6])
    assert body.energy([1e150, 0, 0, 0, 0, 0]) == pytest.approx(0.5e300, rel=1e-15)


def test_ragged_input_is_refused_by_name():
    with pytest.raises(TypeError, match="t must be a 1-D array of real output times"):
        hr.simulate([1.0, 2.0, 3.0], [0.1, 0.2, 0.3], [[1, 2], [3]])
    rep = hq.irrep(3, (1,))
    H = hq.rotor_hamiltonian(rep, [1.0, 2.0, 3.0])
    with pytest.raises(TypeError, match="t must be a 1-D array"):
        hq.evolve(H, np.ones(3) / 3**0.5, [[0.0, 1.0], [2.0]])
    with pytest.raises(TypeError, match="moments must be a numeric array"):
        casimir_shift([[1.0, 2.0], [3.0]])
    with pytest.raises(TypeError, match="moments must be real"):
        casimir_shift([1 + 1j, 2.0, 3.0])


def test_events_must_be_callables_or_a_list_of_them():
    with pytest.raises(TypeError, match="events must be a callable"):
        hr.simulate([1.0, 2.0, 3.0], [0.1, 0.2, 0.3], [0.0, 1.0], events=5)


@pytest.mark.parametrize("omega0", [np.zeros(10), np.r_[np.zeros(9), 1e-300]])
def test_the_demo_refuses_a_body_without_a_representable_energy(omega0):
    from hyperrotor.demo import compare_quartet_motion

    with pytest.raises(ValueError, match="omega0 must set the body in motion"):
        compare_quartet_motion(0.5, omega0=omega0)


def test_the_harmonic_dimension_keeps_its_digits_at_any_degree():
    for N in range(2, 9):
        for l in range(40):
            assert _harmonic_dim(N, l) == math.comb(l + N - 1, N - 1) - (math.comb(l + N - 3, N - 1) if l >= 2 else 0)
    for l in (10**6, 10**12, 10**15):
        assert _harmonic_dim(3, l) == float(2 * l + 1)
    assert _harmonic_dim(2, 10**20) == 2.0
    assert _harmonic_dim(1000, 500) == math.inf
    # near the switch to the closed form (1e5): both sides agree with the exact integer within a rounding
    for l in (99_990, 100_010):
        exact = math.comb(l + 3, 3) - math.comb(l + 1, 3)
        assert _harmonic_dim(4, l) == pytest.approx(exact, rel=1e-15)


@pytest.mark.parametrize("call", [lambda: hq.harmonic_rep(3, 10**15), lambda: hq.orthonormal_harmonic_basis(3, 10**12),
                                  lambda: hq.harmonic_polynomial_basis(3, 10**30)])
def test_huge_harmonic_degrees_are_refused_by_their_dimension(call):
    with pytest.raises(hr.BudgetError, match=r"quantum_max_harmonic_dim"):
        call()


def test_symbols_patterns_and_ambient_dimension_are_checked_by_name():
    import sympy as sp

    x = sp.symbols("x1 x2")
    with pytest.raises(ValueError, match="coordinates must name at least one"):
        hq.polynomial_to_dict(x[0] ** 2 + x[1], ())
    assert hq.polynomial_to_dict(x[0] ** 2 + x[1], x) == {(2, 0): 1, (0, 1): 1}
    with pytest.raises(TypeError, match="poly must be a mapping"):
        hq.dict_to_polynomial(5, x)
    pattern = hq.gt_patterns(4, (1, 0))[1]
    assert hq.gt_index(4, (1, 0), pattern) == 1
    with pytest.raises(TypeError, match="pattern must be real"):
        hq.gt_index(4, (1, 0), pattern + 0.5j)
    with pytest.raises(TypeError, match="pattern must be numeric, got booleans"):
        hq.gt_index(4, (1, 0), [True, False, True, True])
    for bad in (float("inf"), 3.5, 10**30):
        with pytest.raises(TypeError if isinstance(bad, float) else ValueError, match="ambient_dimension must be"):
            hr.RigidBody([1.0, 2.0, 3.0], ambient_dimension=bad)
    assert hr.RigidBody([1.0, 2.0, 3.0], ambient_dimension=4).ambient_dimension == 4


def test_a_text_function_argument_is_read_never_run(tmp_path):
    import sympy as sp

    from hyperrotor._parse import ParseError

    marker = tmp_path / "ran"
    payload = f"__import__('os').system('touch {marker}')"
    with pytest.raises(ParseError, match="function_of"):
        hr.plane_symbols("w", 3, function_of=payload)
    with pytest.raises(ParseError, match="function_of"):
        hr.RigidBody([1.0, 2.0, 3.0]).omega_symbols(function_of=payload)
    assert not marker.exists()
    t = sp.Symbol("t")
    assert hr.plane_symbols("w", 3, function_of="t") == hr.plane_symbols("w", 3, function_of=t)
    assert hr.RigidBody([1.0, 2.0, 3.0]).omega_symbols(function_of="t")[0] == sp.Function("omega_12")(t)


@pytest.mark.parametrize("text", ["1, 1_0", "١٢", "1/1,2x"])
def test_plane_labels_in_text_go_through_the_one_parser(text):
    with pytest.raises(ValueError, match="a plane is a pair"):
        hr.plane_index(text, 10)


def test_plane_labels_read_by_the_parser_and_scene_planes_and_axes_are_integers():
    from hyperrotor._parse import ParseError

    assert hr.plane_index("1,10", 10) == 8 and hr.plane_index(" 2 , 3 ", 4) == 3 and hr.plane_index("12", 5) == 0
    with pytest.raises(ParseError):
        hr._parse.expression("١٢", "x", symbols=False)  # (ASCII digits only)
    w0, t = [0.1, 0.2, 0.3], [0.0, 1.0]
    with pytest.raises(ValueError, match="a plane is a pair"):
        hr.Scene([1.0, 2.0, 3.0], w0, t, planes=[(1.9, 2.9)]).evaluate()
    ok = hr.Scene([1.0, 2.0, 3.0], w0, t, observables=("omega",), planes=[("1", "3")]).evaluate()
    ref = hr.Scene([1.0, 2.0, 3.0], w0, t, observables=("omega",), planes=[(1, 3)]).evaluate()
    np.testing.assert_array_equal(ok.omega, ref.omega)


def test_worker_threads_see_the_callers_block_even_when_it_sets_a_default_back():
    from hyperrotor import _parallel
    from hyperrotor._options import options

    default = options["max_steps"]
    options["max_steps"] = 7  # the session value
    try:
        with hr.options(max_steps=default):
            seen = _parallel.map_rows(lambda x: np.full(x.shape, float(options["max_steps"])), np.arange(8.0),
                                      workers=2, chunk_size=2)
    finally:
        options["max_steps"] = default
    np.testing.assert_array_equal(seen, float(default))
