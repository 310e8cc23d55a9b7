"""Issue #14: one vocabulary, QuTiP both ways, SymPy without traps.

Each test pins one finding of the issue; each failed before the change.
"""
from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import qutip
import scipy.sparse as sps
import sympy as sp

import hyperrotor as hr
import hyperrotor.quantum as hq
from hyperrotor.conventions import planes
from tolerance import scaled_tol

H2 = Fraction(1, 2)


# ----------------------------------------------------------------------------
# eq. 142 operators act on same-named symbols (was: silently 0)
# ----------------------------------------------------------------------------
def test_operators_act_on_plain_symbols_of_the_same_name():
    x1, x2, x3 = sp.symbols("x1:4")  # no real=True: not the default coordinates
    L12 = hq.angular_momentum_operator((1, 2), 3)
    # L^12 = x1 d/dx2 - x2 d/dx1 (module convention) on x1 x2 gives x1^2 - x2^2, in the caller's symbols
    assert L12(x1 * x2) == x1**2 - x2**2
    assert hq.angular_momentum_operator((1, 2), 3, coordinates=["x1", "x2", "x3"])(x1 * x2) == x1**2 - x2**2
    # the polynomial fast path and multiplication operators too
    assert sp.expand(L12.apply_to_polynomial(x1 * x2 + x3)) == x1**2 - x2**2
    M = hq.multiplication_operator(x1**2, 3)
    assert M(sp.Integer(1)) == sp.Symbol("x1", real=True) ** 2
    # a plain-symbol "scalar" that is really a coordinate is refused
    with pytest.raises(ValueError, match="coordinates"):
        L12 * x1


def test_two_symbols_with_one_coordinate_name_are_refused():
    xr = sp.Symbol("x1", real=True)
    xp = sp.Symbol("x1")
    with pytest.raises(ValueError, match="two different symbols named 'x1'"):
        hq.angular_momentum_operator((1, 2), 3)(xr * xp)


# ----------------------------------------------------------------------------
# one keyword for the form, keyword-only hbar; old spellings name the new one
# ----------------------------------------------------------------------------
def test_form_keyword_everywhere():
    rep = hq.irrep(4, (1, 0))
    X = rep.generator((1, 2), format="dense")
    L = rep.generator((1, 2), form="hermitian", hbar=0.5, format="dense")
    assert np.array_equal(L, -0.5j * X)
    assert np.array_equal(rep.generators(form="hermitian")[(1, 2)].toarray(), -1j * X)
    assert np.array_equal(rep.cartan_generators(form="hermitian", format="dense")[0], -1j * X)
    assert np.array_equal(rep.to_qobj((1, 2), form="antihermitian").full(), X)
    hb = sp.Symbol("hbar", positive=True)
    A = hq.angular_momentum_operator((1, 2), 3)
    assert hq.angular_momentum_operator((1, 2), 3, form="hermitian", hbar=hb) == -sp.I * hb * A
    assert hq.operator_matrix(3, form="hermitian")[0, 1] == -(-sp.I * A)  # paper sign (-1)^(1+2)
    assert A.as_form("hermitian", hbar=2) == -2 * sp.I * A


@pytest.mark.parametrize(
    "call, word",
    [
        (lambda: hq.irrep(3, (1,)).hermitian((1, 2), 2.0), "hermitian"),
        (lambda: hq.irrep(3, (1,)).cartan_generators(hermitian=True), "unexpected keyword argument 'hermitian'"),
        (lambda: hq.irrep(3, (1,)).to_qobj(hermitian=False), "unexpected keyword argument 'hermitian'"),
        (lambda: hq.angular_momentum_operators(3, hermitian=True), "unexpected keyword argument 'hermitian'"),
        (lambda: hq.angular_momentum_operator((1, 2), 3).hermitian(1), "hermitian"),
        (lambda: hq.operator_matrix(3, "paper"), "positional"),
        (lambda: hq.contraction_identity(3, "paper"), "positional"),
        (lambda: hq.rotor_hamiltonian(hq.vector_rep(3), [1, 2, 3], 2.0), "positional"),
        (lambda: hq.rotor_hamiltonian(generators=hq.vector_rep(3), body=[1, 2, 3]), "unexpected keyword argument"),
        (lambda: hq.rotor_hamiltonian(hq.vector_rep(3), inertia=[1, 2, 3]), "unexpected keyword argument 'inertia'"),
        (lambda: hq.real_form(hq.vector_rep(3), atol=1e-9), "unexpected keyword argument 'atol'"),
    ],
    ids=lambda v: v if isinstance(v, str) else "",
)
def test_old_spellings_get_pythons_own_errors(call, word):
    """The package is unreleased: old spellings are gone, not shimmed (VOCAB.md, #23)."""
    with pytest.raises((TypeError, AttributeError), match=word):
        call()


def test_hbar_defaults_to_the_exact_one_and_is_refused_with_the_antihermitian_form():
    rep = hq.irrep(3, (1,))
    X = rep.generator((1, 2), format="dense")
    assert np.array_equal(rep.generator((1, 2), hbar=1, format="dense"), X)  # the default, spelled out
    assert rep.generator((1, 2), form="hermitian", exact=True) == -sp.I * rep.generator((1, 2), exact=True)
    A = hq.angular_momentum_operator((1, 2), 3)
    assert hq.angular_momentum_operator((1, 2), 3, form="hermitian") == -sp.I * A  # exact, no Float 1.0
    for call in (lambda: rep.generator((1, 2), hbar=0.5), lambda: rep.to_qobj(hbar=2.0),
                 lambda: hq.angular_momentum_operators(3, hbar=sp.Symbol("hbar")),
                 lambda: hq.jmat_generators(1, hbar=0.5)):
        with pytest.raises(ValueError, match='form="hermitian"'):
            call()


@pytest.mark.parametrize("call", [
    lambda t: hq.angular_momentum_operators(3, form="hermitian", hbar=t),
    lambda t: hq.casimir_operator(3, form="hermitian", hbar=t),
    lambda t: hq.textbook_so3(hbar=t),
    lambda t: hq.operator_matrix(3, form="hermitian", hbar=t),
    lambda t: hq.irrep(3, (1,)).generator((1, 2), form="hermitian", hbar=t, exact=True),
    lambda t: hq.irrep(3, (1,)).generators(form="hermitian", hbar=t),
    lambda t: hq.irrep(3, (1,)).to_qobj(form="hermitian", hbar=t),
    lambda t: hq.jmat_generators(1, form="hermitian", hbar=t),
    lambda t: hq.rotor_hamiltonian(hq.vector_rep(3), [1.0, 2.0, 3.0], hbar=t),
])
@pytest.mark.parametrize("text", ["hbar", "__import__('os').system('touch PWNED')", "9**9**9**9"])
def test_text_hbar_is_refused_everywhere_without_evaluation(call, text, tmp_path, monkeypatch):
    """One behaviour for one input (#21): text for hbar is a TypeError naming hbar, never a Symbol or code."""
    monkeypatch.chdir(tmp_path)
    with pytest.raises(TypeError, match="hbar"):
        call(text)
    assert not (tmp_path / "PWNED").exists()


def test_text_expressions_are_refused_by_the_symbolic_layer():
    x1, x2, x3 = hq.coordinate_symbols(3)
    f = sp.Function("f")(x1, x2, x3)
    with pytest.raises(TypeError, match="expr"):
        hq.WeylElement.from_sympy("x1*Derivative(f(x1, x2, x3), x2)", f, (x1, x2, x3))
    with pytest.raises(TypeError, match="coefficient"):
        hq.dict_to_polynomial({(1, 0, 0): "__import__('os')"}, (x1, x2, x3))
    with pytest.raises(TypeError):
        hq.WeylElement(3, {((0, 0, 0), (0, 0, 0)): "2"})
    # the good inputs still work
    assert hq.WeylElement.from_sympy(x1 * sp.Derivative(f, x2) - x2 * sp.Derivative(f, x1), f, (x1, x2, x3)) == \
        hq.angular_momentum_operator((1, 2), 3).element


# ----------------------------------------------------------------------------
# QuTiP both ways
# ----------------------------------------------------------------------------
@pytest.mark.parametrize("kind", ["qobj", "sparse", "dense"])
def test_rotor_hamiltonian_accepts_mappings(kind):
    rep = hq.irrep(5, (1, 1))
    I = hr.Inertia.from_mass_tensor([1.0, 1.4, 2.1, 2.9, 3.7])
    ref = hq.rotor_hamiltonian(rep, I, hbar=0.7)
    q = rep.to_qobj(form="antihermitian")
    conv = {"qobj": lambda Q: Q, "sparse": lambda Q: Q.to("CSR").data.as_scipy(), "dense": lambda Q: Q.full()}[kind]
    gens = {p: conv(Q) for p, Q in q.items()}
    moments = dict(zip(planes(5), I.moments))
    H = hq.rotor_hamiltonian(gens, moments, hbar=0.7)
    tol = scaled_tol(ref.full(), dim=rep.dim, k=4 * len(moments))
    assert np.abs(H.full() - ref.full()).max() <= tol
    # the Hermitian form of the same operators, declared as such
    Lh = {p: conv(Q) for p, Q in rep.to_qobj(form="hermitian", hbar=0.7).items()}
    H2 = hq.rotor_hamiltonian(Lh, moments, form="hermitian", hbar=0.7)
    assert np.abs(H2.full() - ref.full()).max() <= tol


def test_hermitian_generators_declared_antihermitian_are_refused():
    gens = hq.irrep(3, (1,)).to_qobj(form="hermitian")
    with pytest.raises(ValueError, match='form="hermitian"'):
        hq.rotor_hamiltonian(gens, [1.0, 2.0, 3.0])  # would silently be -H


@pytest.mark.parametrize("rep", [hq.irrep(3, (H2,)), hq.irrep(4, (1, -1)), hq.spinor_rep(5), hq.harmonic_rep(4, 2)],
                         ids=["so3-1/2", "so4-(1,-1)", "spinor5", "harmonic4-2"])
@pytest.mark.parametrize("form", ["antihermitian", "hermitian"])
def test_from_qobj_round_trip(rep, form):
    kw = {"hbar": 0.3} if form == "hermitian" else {}
    back = hq.Representation.from_qobj(rep.to_qobj(form=form, **kw), form=form, **kw)
    assert back.N == rep.N and back.dim == rep.dim
    for p in rep.planes:
        A, B = back.generator(p, format="dense"), rep.generator(p, format="dense")
        assert np.abs(A - B).max() <= scaled_tol(B, dim=1, k=4)


def test_from_qobj_checks_the_brackets():
    J = {a: qutip.jmat(1, a) for a in "xyz"}
    # a non-cyclic relabelling is not a representation of so(3) with the plane brackets
    bad = {(1, 2): 1j * J["y"], (1, 3): 1j * J["x"], (2, 3): 1j * J["z"]}
    with pytest.raises(ValueError, match="brackets"):
        hq.Representation.from_qobj(bad)
    with pytest.raises(ValueError, match="misses the planes|N\\(N-1\\)/2|plane"):
        hq.Representation.from_qobj({(1, 2): 1j * J["z"], (1, 3): 1j * J["x"]})


# ----------------------------------------------------------------------------
# so(3) basis vs qutip.jmat: the exact map
# ----------------------------------------------------------------------------
@pytest.mark.parametrize("j", [H2, 1, Fraction(3, 2), 2, Fraction(5, 2), 3])
def test_so3_irrep_is_jmat_rotated_about_z(j):
    rep = hq.irrep(3, (j,))
    hbar = 0.8
    for (i, k), (axis, sign) in hq.JMAT_PLANES.items():
        L = rep.generator((i, k), form="hermitian", hbar=hbar, format="dense")
        assert np.array_equal(L, sign * hbar * qutip.jmat(float(j), axis).full()) or \
            np.abs(L - sign * hbar * qutip.jmat(float(j), axis).full()).max() <= scaled_tol(float(j) * hbar, dim=1, k=4)
    # the statement of the issue: L^23 = J_y (a 90-degree rotation about z of the textbook map L^23 = J_x)
    assert np.abs(rep.generator((2, 3), form="hermitian", format="dense") - qutip.jmat(float(j), "y").full()).max() \
        <= scaled_tol(float(j), dim=1, k=4)
    # and the function gives the same generators, usable the other way
    J = hq.jmat_generators(j)
    back = hq.Representation.from_qobj(J)
    for p in rep.planes:
        assert np.abs(back.generator(p, format="dense") - rep.generator(p, format="dense")).max() <= scaled_tol(float(j), dim=1, k=4)


# ----------------------------------------------------------------------------
# harmonic_rep exactly antisymmetric
# ----------------------------------------------------------------------------
@pytest.mark.parametrize("N, l", [(3, 4), (4, 3), (5, 3), (6, 2)])
def test_harmonic_rep_exactly_antisymmetric(N, l):
    rep = hq.harmonic_rep(N, l)
    for X in rep.generators().values():
        assert (X + X.T).count_nonzero() == 0  # bit for bit
    H = hq.rotor_hamiltonian(rep, np.linspace(1.0, 2.0, N * (N - 1) // 2)).data.as_scipy()
    assert (H - H.T).count_nonzero() == 0
    # and still the same operators: exact SymPy matrices agree to round-off
    if rep.dim <= 20:
        for p in rep.planes:
            ex = np.array(rep.generator(p, exact=True).evalf(), dtype=float)
            assert np.abs(rep.generator(p, format="dense") - ex).max() <= scaled_tol(ex, dim=rep.dim, k=8)


# ----------------------------------------------------------------------------
# evolve: one registry, per-method option tables
# ----------------------------------------------------------------------------
@pytest.mark.parametrize("method", list(hq.PROPAGATORS))
def test_every_registered_method_evolves_and_refuses_unknown_options(method):
    rep = hq.irrep(3, (2,))
    H = hq.rotor_hamiltonian(rep, [1.0, 1.7, 2.9])
    psi = np.arange(1, rep.dim + 1, dtype=complex)
    psi /= np.linalg.norm(psi)
    t = np.linspace(0.0, 1.0, 5)
    table = hq.evolve_options(method)
    assert {"store_states", "store_final_state"} <= set(table)
    opts = {"atol": 1e-12, "rtol": 1e-10} if method in ("sesolve", "mesolve") else {}
    res = hq.evolve(H, psi, t, method=method, options={"store_states": True, **opts})
    E, V = np.linalg.eigh(H.full())
    exact = V @ (np.exp(-1j * E * t[-1]) * (V.conj().T @ psi))
    err = np.linalg.norm(res.states[-1].full().ravel() - exact)
    assert err <= (1e-7 if method in ("sesolve", "mesolve") else 1e-10)
    with pytest.raises(ValueError, match="allowed: .*store_states"):
        hq.evolve(H, psi, t, method=method, options={"no_such_option": 1})


def test_krylov_atol_means_the_krylov_tolerance_and_defaults_come_from_options():
    table = hq.evolve_options("krylov")
    assert table["atol"][0] is None and "quantum_krylov_atol" in table["atol"][1]
    assert "ODE" in hq.PROPAGATORS["sesolve"].__doc__  # QuTiP's atol is the ODE tolerance, documented there
    assert "max_dense_dim" not in hq.evolve_options("eigen")  # one home: hr.options
    assert hr.options["quantum_max_dense_dim"] == 6000


def test_tolerances_are_read_from_the_option_table():
    H = np.diag([1.0, 2.0])
    psi = np.array([1.0, 1e-9])  # norm off 1 by 5e-19: silent
    with hr.options(quantum_psi0_norm_rtol=0.0), pytest.warns(UserWarning, match="quantum_psi0_norm_rtol"):
        hq.evolve(H, np.array([1.0, 1e-6]), [0.0, 1.0])
    hq.evolve(H, psi, [0.0, 1.0])
    nearly = np.array([[1.0, 1e-11], [0.0, 1.0]])
    with pytest.raises(ValueError, match="quantum_hermiticity_rtol"):
        hq.spectrum(nearly)
    with hr.options(quantum_hermiticity_rtol=1e-10):
        hq.spectrum(nearly + nearly.T)
    with hr.options(quantum_level_rtol=1e-3):
        assert hq.spectrum(np.diag([1.0, 1.0005]))[1].tolist() == [2]
    for key in ("quantum_harmonic_drop", "quantum_real_form_drop", "quantum_real_form_rtol",
                "quantum_krylov_dim", "quantum_eigen_max_block", "quantum_block_rtol", "quantum_bracket_rtol"):
        assert key in hr.options and len(hr.options.describe(key)) > 40


def test_rotor_hamiltonian_records_rep_for_sectors():
    rep = hq.irrep(3, (1,))
    H = hq.rotor_hamiltonian(rep, [1.0, 2.0, 3.0])
    assert H._hyperrotor_rep is rep
    assert not hasattr(H + H, "_hyperrotor_rep")
    sp_H = sps.csr_matrix(H.full())
    assert np.allclose(hq.spectrum(sp_H, rep=rep)[0], hq.spectrum(H)[0], rtol=0, atol=scaled_tol(3.0, dim=3))


@pytest.mark.parametrize("N, hw", [(4, (3, 1)), (5, (2, 1))])
def test_spectrum_through_symmetry_sectors_matches_dense(N, hw):
    rep = hq.irrep(N, hw)
    H = hq.rotor_hamiltonian(rep, np.linspace(1.0, 2.0, N * (N - 1) // 2))
    E = np.linalg.eigvalsh(H.full())
    with hr.options(quantum_eigen_max_block=1):  # force the sector path (issue #16 hook)
        levels, deg = hq.spectrum(H)
    assert deg.sum() == rep.dim
    assert np.abs(np.repeat(levels, deg) - E).max() <= scaled_tol(E, dim=rep.dim, k=16)


def test_sphere_inner_product_and_weyl_action_on_plain_symbols():
    x1, x2, x3 = sp.symbols("x1:4")
    # <x1, x1> on S^2 (normalized measure) is 1/3; plain x1 was a constant before (gave x1**2)
    assert hq.sphere_inner_product(x1, x1, 3, normalized=True) == sp.Rational(1, 3)
    L = hq.angular_momentum_operator((1, 2), 3)
    assert hq.apply_to_polynomial(L.element, x1 * x2) == x1**2 - x2**2


def test_irrep_messages_print_weights_as_numbers():
    with pytest.raises(ValueError, match=r"irrep \(200, 100\) \(its 10 sparse generators") as exc:
        hq.irrep(5, (200, 100))
    assert "'200'" not in str(exc.value)
    with pytest.raises(ValueError, match=r"irrep \(401/2, 201/2\) \(its 10 sparse generators"):
        hq.irrep(5, (200.5, 100.5))
    assert "(5/2, 1/2)" in hq.irrep(5, (2.5, 0.5)).name


def test_operator_division_by_a_scalar_and_never_by_text():
    A = hq.angular_momentum_operator((1, 2), 3)
    h = sp.Symbol("h", positive=True)
    assert (A / h) * h == A and A / 2 == A * sp.Rational(1, 2)
    with pytest.raises(TypeError):
        A / "__import__('os')"
