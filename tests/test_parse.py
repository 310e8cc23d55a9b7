"""The one parser of user text (hyperrotor._parse): exact results, nothing evaluated, bounded."""
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings, strategies as st

from cpu_clock import call_cpu
from hyperrotor import _parse

x, y = sp.symbols("x y")


@pytest.mark.parametrize(
    "text, expected",
    [
        ("1/2", sp.Rational(1, 2)),
        ("0.1", sp.Rational(1, 10)),
        ("2e-3", sp.Rational(1, 500)),
        (".5", sp.Rational(1, 2)),
        ("5.", sp.Integer(5)),
        ("-(3/4)**2", -sp.Rational(9, 16)),
        ("2**-2", sp.Rational(1, 4)),
        ("2**3**2", sp.Integer(512)),  # right-associative, like Python
        ("-2**2", sp.Integer(-4)),  # unary minus binds looser than **, like Python
        ("2**(1/2)", sp.sqrt(2)),
        ("(x - y)**2", (x - y) ** 2),
        ("x/2 + 3*y", x / 2 + 3 * y),
        (" 1 +  2 ", sp.Integer(3)),
    ],
)
def test_expressions_are_exact(text, expected):
    assert _parse.expression(text, "arg") == expected


def test_names_become_symbols_with_assumptions_or_are_refused():
    h = _parse.expression("hbar", "hbar", positive=True)
    assert h == sp.Symbol("hbar", positive=True) and h.is_positive
    assert _parse.expression("I_12", "moment", symbols={"I_12"}) == sp.Symbol("I_12")
    with pytest.raises(_parse.ParseError, match="unknown name 'I_13'"):
        _parse.expression("I_13", "moment", symbols={"I_12"})
    with pytest.raises(_parse.ParseError, match="names are not allowed"):
        _parse.number("x", "--kappa")


def test_number():
    assert _parse.number("1/2", "k") == 0.5
    assert _parse.number("-2.5e-3", "k") == -0.0025
    assert _parse.number("2**(1/2)", "k") == float(np.sqrt(2))
    assert _parse.number("3/4", "k", exact=True) == sp.Rational(3, 4)
    with pytest.raises(_parse.ParseError, match="exact fraction"):
        _parse.number("2**(1/2)", "k", exact=True)
    for big in ("1e400", "10**400", "-(10**309)"):
        with pytest.raises(_parse.ParseError, match="too large for a float"):
            _parse.number(big, "k")


_DIGITS = st.text("0123456789", min_size=1, max_size=25)


@settings(max_examples=400, deadline=None)
@given(sign=st.sampled_from(["", "+", "-"]), whole=_DIGITS | st.just(""), point=st.booleans(),
       frac=_DIGITS | st.just(""), exp=st.none() | st.integers(-99, 99) | st.integers(-420, 420),
       pad=st.sampled_from(["", " ", "\t "]))
def test_plain_decimals_read_without_sympy_equal_the_exact_reading(sign, whole, point, frac, exp, pad):
    """number() reads a short plain decimal literal with float() (no SymPy); whichever path a literal
    takes, it must give the float of the exact rational the grammar reads, bit for bit (-0 included),
    and refuse what the grammar refuses or what overflows, with the same message."""
    if not whole and not (point and frac):
        whole = "0"
    text = f"{pad}{sign}{whole}{'.' if point else ''}{frac if point else ''}{'' if exp is None else f'e{exp}'}{pad}"
    try:
        exact = _parse.expression(text, "k", symbols=False)
    except _parse.ParseError as exc:  # over a bound of the grammar (exponent beyond 400)
        with pytest.raises(_parse.ParseError) as got:
            _parse.number(text, "k")
        assert str(got.value) == str(exc)
        return
    try:
        expected = float(exact)
    except OverflowError:
        expected = float("inf")
    if np.isfinite(expected):
        got = _parse.number(text, "k")
        assert got == expected and np.signbit(got) == np.signbit(expected), (text, got, expected)
    else:
        with pytest.raises(_parse.ParseError, match="too large for a float"):
            _parse.number(text, "k")
    if len(text) <= _parse._DECIMAL_LENGTH and (exp is None or abs(exp) < 100):
        assert _parse._DECIMAL.fullmatch(text)  # (this literal took the path without SymPy)


@settings(max_examples=200, deadline=None)
@given(st.sampled_from(["", "+", "-"]), st.text("0123456789", min_size=1, max_size=30),
       st.sampled_from(["", " ", "\t"]), st.sampled_from(["", ".0", ".5", "e1", "/2", "**2"]))
def test_integers_read_without_sympy_equal_the_exact_reading(sign, digits, pad, tail):
    """integer() reads a short plain integer literal with int() (no SymPy); whichever path a text takes,
    the value is the exact reading's, and a non-integer is refused naming the argument and the text."""
    text = f"{pad}{sign}{digits}{tail}{pad}"
    exact = _parse.expression(text, "k", symbols=False)
    if exact.is_Integer:
        got = _parse.integer(text, "k")
        assert type(got) is int and got == int(exact)
    else:
        with pytest.raises(ValueError) as err:
            _parse.integer(text, "k")
        assert str(err.value) == f"k must be an integer, got {text!r}"


PAYLOADS = [
    "__import__('os').system('touch pwned')",
    "exec('open(\"pwned\", \"w\")')",
    "eval('1')",
    "lambda: 0",
    "().__class__.__mro__",
    "__builtins__",
    "x.__class__",
    "open",  # a plain name is a Symbol, never the builtin (checked below)
    "print(1)",
    "x[0]",
    "[1, 2]",
    "{1: 2}",
    "1 if x else 2",
    "9**9**9**9",
    "10**10**10",
    "(10**1000)**1000",
    "1e999999",
    "9" * 5000,
    "(" * 500 + "1" + ")" * 500,
    "1/0",
    "0**-1",
    "'a'",
    "x; import os",
    "2x",
    "3^2",
    "",
    "   ",
]


@pytest.mark.parametrize("text", PAYLOADS)
def test_payloads_are_refused_quickly_and_create_nothing(text, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = None
    try:  # (CPU seconds of this thread, the collector paused: tests/cpu_clock.py says why not the wall clock)
        with call_cpu() as clock:
            result = _parse.expression(text, "arg")
    except _parse.ParseError as exc:
        assert "arg=" in str(exc) and "allowed:" in str(exc)
    else:  # the only accepted payload is a bare name, which is a Symbol and nothing more
        assert text == "open" and result == sp.Symbol("open")
    assert clock.seconds < 1.0
    assert list(tmp_path.iterdir()) == []


def test_non_text_is_refused():
    with pytest.raises(TypeError, match="arg must be text"):
        _parse.expression(0.5, "arg")


def test_to_sympy_is_sympify_without_text_evaluation():
    assert _parse.to_sympy(np.float64(0.5), "h") == sp.Float(0.5)
    assert _parse.to_sympy(np.int64(3), "h") == sp.Integer(3)
    assert _parse.to_sympy(Fraction(1, 3), "h") == sp.Rational(1, 3)
    assert _parse.to_sympy(1 + 2j, "h") == sp.Float(1) + sp.Float(2) * sp.I
    assert _parse.to_sympy(x, "h") is x
    assert _parse.to_sympy("x/2", "h") == x / 2
    with pytest.raises(TypeError, match="h must be a number or a SymPy expression, not text"):
        _parse.to_sympy("x", "h", text=False)
    for bad in (True, None, [1], object()):
        with pytest.raises(TypeError, match="h must be a number or a SymPy expression"):
            _parse.to_sympy(bad, "h")
    with pytest.raises(ValueError, match="h must be finite"):
        _parse.to_sympy(float("nan"), "h")
    with pytest.raises(_parse.ParseError):
        _parse.to_sympy("__import__('os')", "h")


#: Modules that may call a text-evaluating SymPy function, with the reason. Nothing a user passes
#: reaches them: they read the preprint's formulas, constants shipped inside the package.
EVALUATING_TEXT_ALLOWED = {
    "paper/printed.py": "parses the printed equations of the preprint (package constants)",
    "paper/printed_solutions.py": "parses the printed closed forms of the preprint (package constants)",
}


def test_no_module_evaluates_text_outside_the_parser():
    """``sympify``/``parse_expr``/``eval``/``exec`` turn text into code; only ``_parse`` reads user text."""
    import re
    from pathlib import Path

    import hyperrotor

    root = Path(hyperrotor.__file__).parent
    pattern = re.compile(r"\b(sympify|parse_expr)\s*\(|\bsp\.S\(|(?<![\w.])(eval|exec)\s*\(")
    offenders = []
    for path in sorted(root.rglob("*.py")):
        rel = path.relative_to(root).as_posix()
        if rel == "_parse.py" or rel in EVALUATING_TEXT_ALLOWED:
            continue
        for k, line in enumerate(path.read_text().splitlines(), 1):
            code = line.split("#", 1)[0]
            if pattern.search(code) and "def _sympify" not in code:
                offenders.append(f"{rel}:{k}: {line.strip()}")
    assert not offenders, "text may reach sympify/eval here (use hyperrotor._parse.to_sympy):\n" + "\n".join(offenders)
