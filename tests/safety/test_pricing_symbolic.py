"""Symbolic and size-driven work that the budgets did not price (review of session 46).

- ``contraction_identity(N)`` and ``operator_product`` of operator matrices: their products grow like
  N^3 .. N^4 (N = 40: 6 s, N = 60: 30 s under ``max_seconds = 2``);
- ``RigidBody(...).symbolic_rhs()``: ~N^3 SymPy products (N = 60: 10 s), priced like ``euler_equations``;
- ``vector_rep(N)``: N(N-1)/2 sparse generators, and it built as many exact SymPy matrices eagerly
  (N = 400: 9.5 s under ``max_seconds = 1``); the exact generators are now built (and priced) on demand,
  as are those of ``adjoint_rep`` (276^3 SymPy entries for N = 24: 60 s);
- ``hypercube_vertices(N)``: 8 N 2^N bytes returned (N = 22: 738 MB under ``max_output_bytes = 1e6``).

Each refusal comes before the work (well under a second of CPU) and names the budget; a small call
still gives the right value.
"""
from __future__ import annotations

import pickle

import numpy as np
import pytest
import sympy as sp

import hyperrotor as hr
import hyperrotor.quantum as hq
from cpu_clock import call_cpu
from hyperrotor import _pricing

FAST = 0.5  # seconds of CPU for a refusal (arithmetic on the sizes)


def _refused(call, budget, match=""):
    """``call()`` raises a BudgetError naming ``budget`` (and ``match``) within FAST seconds of CPU."""
    with call_cpu() as clock, pytest.raises(hr.BudgetError, match=rf"{match}.*hr\.options\['{budget}'\]") as err:
        call()
    assert clock.seconds < FAST, f"refused after {clock.seconds:.2f} s of CPU: {err.value}"
    return str(err.value)


def test_contraction_identity_is_priced_by_its_products():
    with hr.options(max_seconds=2.0):
        msg = _refused(lambda: hq.contraction_identity(40), "max_seconds", r"contraction_identity: .*so\(40\)")
        _refused(lambda: hq.contraction_identity(60, form="eq144"), "max_seconds", r"so\(60\)")
        assert "raise it with hr.options(max_seconds=...)" in msg
        r = hq.contraction_identity(3)
    assert r.holds and r.factor == -1
    assert all(r.product[i, j] == -r.matrix[i, j] for i in range(3) for j in range(3))
    # the estimate grows like N^3 .. N^4 (the sums of the products get longer)
    small, large = (_pricing.estimate("contraction_identity", N=N)[0].amount for N in (20, 40))
    assert 8.0 < large / small < 20.0


def test_operator_product_is_priced_by_the_pairs_of_terms_it_composes():
    M = hq.operator_matrix(40)
    with hr.options(max_seconds=2.0):
        _refused(lambda: hq.operator_product(M, M.T.copy()), "max_seconds",
                 r"operator_product: the product of two 40 x 40 operator matrices")
        _refused(lambda: hq.operator_product(M, M.T.copy(), form="antisymmetrized"), "max_seconds")
        L = hq.operator_matrix(3)
        P = hq.operator_product(L, L.T.copy(), form="antisymmetrized")
    assert all(P[i, j] == -L[i, j] for i in range(3) for j in range(3))  # eq. (147)
    # zero operators compose no terms but still cost their N^3 compositions and sums
    few = _pricing.estimate("operator_product", N=40, pairs=0, coords=40)[0].amount
    many = _pricing.estimate("operator_product", N=40, pairs=10**6, coords=40)[0].amount
    assert 0.0 < few < many


def test_symbolic_rhs_is_priced_like_euler_equations():
    body = hr.RigidBody(hr.Inertia.symbolic(60))
    with hr.options(max_seconds=2.0):
        _refused(body.symbolic_rhs, "max_seconds", r"symbolic_rhs: the 1770 symbolic right-hand sides of so\(60\)")
        _refused(body.euler_equations, "max_seconds", r"euler_equations")
        rhs = hr.RigidBody(hr.Inertia.symbolic(3)).symbolic_rhs()
    I12, I13, I23 = sp.symbols("I_12 I_13 I_23", positive=True)
    w12, w13, w23 = sp.symbols("omega_12 omega_13 omega_23")
    assert sp.simplify(rhs[0] - (I13 - I23) * w13 * w23 / I12) == 0
    assert sp.simplify(rhs[2] - (I12 - I13) * w12 * w13 / I23) == 0


def test_vector_rep_is_priced_and_builds_its_exact_generators_on_demand():
    with hr.options(max_seconds=1.0):
        _refused(lambda: hq.vector_rep(400), "max_seconds", r"vector_rep: the 79800 sparse generators")
    with hr.options(max_memory_bytes=10**6):
        _refused(lambda: hq.vector_rep(100), "max_memory_bytes", r"vector_rep")
    rep = hq.vector_rep(60)  # ~0.2 s: no SymPy matrix is made here
    assert rep.has_exact_generators and not isinstance(rep._exact, dict)
    with hr.options(max_seconds=0.01):  # the exact generators are priced when they are asked for
        _refused(rep.exact_generators, "max_seconds", r"exact SymPy generators of the vector rep of so\(60\)")
    small = hq.vector_rep(3)
    assert pickle.loads(pickle.dumps(small)) == small  # the on-demand recipe pickles (no closure)
    assert small.generator((1, 3), exact=True) == sp.Matrix([[0, 0, 1], [0, 0, 0], [-1, 0, 0]])
    assert np.array_equal(small.generator((1, 3), format="dense"), np.array([[0, 0, 1], [0, 0, 0], [-1, 0, 0.0]]))


def test_adjoint_rep_builds_and_prices_its_exact_generators_on_demand():
    with hr.options(max_seconds=1.0):
        rep = hq.adjoint_rep(24)  # sparse generators only (0.1 s); the exact ones were 60 s of SymPy
        _refused(rep.exact_generators, "max_seconds", r"adjoint_rep: the 276 exact SymPy generators")
    ad = hq.adjoint_rep(3)
    C = hr.structure_constants(3)
    for a, p in enumerate(ad.planes):
        assert ad.generator(p, exact=True) == sp.Matrix(3, 3, lambda c, b: int(C[a, b, c]))
        assert np.array_equal(np.asarray(ad.generator(p, exact=True), dtype=float), ad.generator(p, format="dense"))


def test_hypercube_vertices_are_priced_against_output_and_memory():
    with hr.options(max_output_bytes=10**6, max_memory_bytes=10**12):
        _refused(lambda: hr.hypercube_vertices(22), "max_output_bytes", r"hypercube_vertices: the 2\^22 vertices")
    with hr.options(max_output_bytes=10**12, max_memory_bytes=10**6):
        _refused(lambda: hr.hypercube_vertices(22), "max_memory_bytes", r"hypercube_vertices")
    _refused(lambda: hr.hypercube_vertices(24), "max_output_bytes")  # 3 GiB at the default 2 GiB
    with hr.options(max_dimension=10**7):  # 2^(10^6) rows: an infinite estimate, not an overflow
        _refused(lambda: hr.hypercube_vertices(10**6), "max_output_bytes", r"more than 1e308")
    with hr.options(max_output_bytes=10**6, max_memory_bytes=10**6):
        V = hr.hypercube_vertices(3)
        W = hr.hypercube_vertices(3, half_edge=0.5)
    assert V.shape == (8, 3) and V.dtype == float
    assert {tuple(v) for v in V} == {(x, y, z) for x in (-1.0, 1.0) for y in (-1.0, 1.0) for z in (-1.0, 1.0)}
    assert np.array_equal(V[0], [-1.0, -1.0, -1.0]) and np.array_equal(V[-1], [1.0, 1.0, 1.0])
    assert np.array_equal(W, 0.5 * V)
    assert np.array_equal(hr.hypercube_vertices(2, half_edge=1e308), 1e308 * hr.hypercube_vertices(2))


@pytest.mark.parametrize("entry", ["operator_product", "contraction_identity", "symbolic_rhs", "vector_rep",
                                   "adjoint_rep", "hypercube_vertices"])
def test_the_new_models_are_registered_and_documented(entry):
    from pathlib import Path

    assert entry in _pricing.MODELS
    table = (Path(__file__).resolve().parents[2] / "docs" / "safety.md").read_text()
    assert f"| {entry} |" in table, f"docs/safety.md has no measured row for {entry}"
