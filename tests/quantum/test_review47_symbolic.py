"""Defects a review of the symbolic layer found (session 47, /tmp/review47/symbolic)."""
from fractions import Fraction

import pytest
import sympy as sp

import hyperrotor.quantum as hq
from hyperrotor.paper import printed_solutions as ps
from hyperrotor.paper.sections import quantum as sq


def test_coordinates_must_have_distinct_names():
    """a and a (real) were two coordinates: L^12 became a d/da - a d/da and gave 2 a^2 on x1^2 (the operators find
    their coordinates by name)."""
    with pytest.raises(ValueError, match="distinct names"):
        hq.angular_momentum_operators(3, coordinates=[sp.Symbol("a"), sp.Symbol("a", real=True), "c"])


@pytest.fixture(scope="module")
def L12():
    L = hq.angular_momentum_operators(3)
    return L[(1, 2)] if isinstance(L, dict) else L[0]


@pytest.mark.parametrize("bad", [sp.nan, sp.zoo, sp.oo, -sp.oo, float("nan"), float("inf"), complex("nan")])
def test_scalars_must_be_finite(L12, bad):
    """L12 * nan gave (nan)*dx2 + (nan)*dx1 (the x-dependence lost), L12 / 0.0 zoo coefficients."""
    with pytest.raises(ValueError, match="must be finite"):
        L12 * bad
    with pytest.raises(ValueError, match="must be finite"):
        bad * L12


@pytest.mark.parametrize("zero", [0, 0.0, Fraction(0), sp.Integer(0), sp.Float(0)])
def test_zero_is_zero_of_any_numeric_type(L12, zero):
    """Z == 0 held for int and SymPy's Integer only; L12 / 0 raised Fraction's bare 'Fraction(1, 0)'."""
    assert (L12 - L12) == zero and not (L12 == zero)
    with pytest.raises(ZeroDivisionError, match="operator divided by zero"):
        L12 / zero


def test_the_printed_prefactor_of_141_is_read_from_the_text(monkeypatch):
    """printed('141')['prefactor'] was -i hbar whatever the text said: the check could not fail."""
    ps.printed.cache_clear()
    sq.sec_quantum.cache_clear()
    try:
        assert ps.printed("141")["prefactor"] == -sp.I * sp.Symbol("hbar")
        assert ps.printed("143")["prefactor"] == 1
        monkeypatch.setitem(ps.LATEX, "141", ps.LATEX["141"].replace(r"-i\hbar", r"+ 7 i\hbar"))
        ps.printed.cache_clear()
        sq.sec_quantum.cache_clear()
        v = next(v for v in sq.sec_quantum() if v.equation == "141")
        assert v.status == "typo" and "prefactor 7*I*hbar (expected -I*hbar)" in v.detail
    finally:
        monkeypatch.undo()
        ps.printed.cache_clear()
        sq.sec_quantum.cache_clear()
    assert next(v for v in sq.sec_quantum() if v.equation == "141").status == "holds"


@pytest.mark.parametrize("N", [3, 4, 5])
def test_the_eq144_reading_of_145_to_147_as_the_verdict_states_it(N):
    """The verdicts of (145)-(147) said 'with the eq.-(144) pattern the factor is N - 2' (against the matrix
    entries); read against the labelled components the factor is -(N - 2) for i + j odd and N - 2 for i + j even."""
    L = hq.angular_momentum_operators(N)
    r = hq.contraction_identity(N, form="eq144")
    for (i, j), op in L.items():
        assert r.product[i - 1, j - 1] == (-1) ** (i + j) * (N - 2) * op
    v = next(v for v in sq.sec_quantum() if v.equation == {5: "145", 4: "146", 3: "147"}[N])
    assert f"it is {-(N - 2)} for i + j odd" in v.detail and f"and {N - 2} for i + j even" in v.detail
