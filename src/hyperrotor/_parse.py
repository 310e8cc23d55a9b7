"""THE parser for user text: numbers, fractions, names, ``+ - * / **`` and parentheses.

Every number or expression that reaches hyperrotor as text (command-line
options, a string given to a Python function that accepts one) is read here
and nowhere else. Nothing is ever evaluated: the text is tokenized and parsed
by a small recursive-descent grammar,

.. code-block:: text

    expression := term (("+" | "-") term)*
    term       := factor (("*" | "/") factor)*
    factor     := ("+" | "-") factor | power
    power      := atom ("**" factor)?            (right-associative, like Python)
    atom       := NUMBER | NAME | "(" expression ")"
    NUMBER     := digits ["." digits] [("e" | "E") ["+" | "-"] digits]   (also ".5", "5.")
    NAME       := letter (letter | digit | "_")*   (no leading underscore, no Python keyword)

and the result is built from SymPy's exact constructors (``Integer``,
``Rational``, ``Symbol``, ``Add``, ``Mul``, ``Pow``). Decimal literals are read
exactly (``"0.1"`` is ``1/10``). There are no attribute accesses, calls,
subscripts, lambdas, strings, comprehensions or dunder names to begin with: the
grammar cannot express them, so ``"__import__('os').system('...')"`` is refused
at the first ``(`` after a name, before anything happens.

Sizes are bounded before anything is computed, so no text can make the parser
hang or allocate: at most :data:`MAX_LENGTH` characters, :data:`MAX_DEPTH`
nested parentheses/operators, literals of at most :data:`MAX_LITERAL_DIGITS`
digits with a decimal exponent of at most :data:`MAX_DECIMAL_EXPONENT`, powers
with a numeric exponent of magnitude at most :data:`MAX_EXPONENT` and a
numeric result of at most :data:`MAX_RESULT_DIGITS` decimal digits. ``9**9**9**9``
is refused in microseconds (the exponent ``9**(9**9)`` is over the bound).

Refusals raise :class:`ParseError` (a ``ValueError``) whose message names the
argument, quotes the text and says what is allowed.
"""
from __future__ import annotations

import keyword
import math
import re
from fractions import Fraction
from numbers import Integral, Rational as _RationalABC, Real, Complex
from typing import Any, Collection

__all__ = [
    "ParseError",
    "expression",
    "number",
    "integer",
    "to_sympy",
    "MAX_LENGTH",
    "MAX_DEPTH",
    "MAX_LITERAL_DIGITS",
    "MAX_DECIMAL_EXPONENT",
    "MAX_EXPONENT",
    "MAX_RESULT_DIGITS",
]

#: Longest text accepted (characters).
MAX_LENGTH = 1000
#: A short plain decimal literal (optional sign, digits, point, an exponent of one or two digits; no
#: underscores, no inf/nan; at most :data:`_DECIMAL_LENGTH` characters, far inside the bounds below), which
#: :func:`number` reads without SymPy: ``float`` of it is the correctly rounded value of the exact decimal.
_DECIMAL_LENGTH = 64
_DECIMAL = re.compile(r"[ \t]*[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]{1,2})?[ \t]*")
#: A plain integer literal of at most 18 digits, which :func:`integer` reads without SymPy.
_INTEGER = re.compile(r"[ \t]*[+-]?[0-9]{1,18}[ \t]*")
#: Deepest nesting of parentheses and unary/binary operators.
MAX_DEPTH = 60
#: Most digits in one numeric literal (mantissa).
MAX_LITERAL_DIGITS = 400
#: Largest magnitude of the decimal exponent of a literal (``1e400`` is allowed, ``1e401`` is not).
MAX_DECIMAL_EXPONENT = 400
#: Largest magnitude of a numeric exponent in ``a ** b``.
MAX_EXPONENT = 1000
#: Largest size, in decimal digits, of the numerator or denominator of a numeric power's result.
MAX_RESULT_DIGITS = 2000

ALLOWED = "numbers (1, 0.5, 2e-3), fractions (1/2), names (x, I_12), + - * / ** and parentheses"
ALLOWED_NUMBERS = "numbers (1, 0.5, 2e-3), fractions (1/2), + - * / ** and parentheses"


class ParseError(ValueError):
    """Text that the one parser of user text refuses (see :mod:`hyperrotor._parse`)."""


_TOKEN = re.compile(
    r"""\s*(?:
        (?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?) |
        (?P<name>[A-Za-z_][A-Za-z0-9_]*) |
        (?P<op>\*\*|[-+*/()])
    )""",
    re.VERBOSE | re.ASCII,  # (ASCII digits and spaces only: "\d" also matched Arabic-Indic and other digits)
)


def _fail(name: str, text: str, reason: str, *, names: bool = True) -> ParseError:
    shown = text if len(text) <= 80 else text[:77] + "..."
    return ParseError(f"{name}={shown!r} cannot be read: {reason}; allowed: {ALLOWED if names else ALLOWED_NUMBERS}")


def _tokens(text: str, name: str, names: bool) -> list[tuple[str, str, int]]:
    out: list[tuple[str, str, int]] = []
    pos = 0
    n = len(text)
    while pos < n:
        if text[pos:].strip() == "":
            break
        m = _TOKEN.match(text, pos)
        if m is None or m.end() == pos:
            at = pos + (len(text[pos:]) - len(text[pos:].lstrip()))
            raise _fail(name, text, f"unexpected character {text[at]!r} at position {at + 1}", names=names)
        kind = m.lastgroup
        value = m.group(kind)
        start = m.start(kind)
        if kind == "name" and m.end() < n and text[m.end()] in "'\"":
            raise _fail(name, text, f"strings are not allowed (position {m.end() + 1})", names=names)
        out.append((kind, value, start))
        pos = m.end()
    return out


class _Parser:
    def __init__(self, text: str, name: str, symbols: bool | Collection[str], assumptions: dict) -> None:
        import sympy as sp  # imported on the first parse only

        self.sp = sp
        self.text = text
        self.name = name
        self.symbols = symbols
        self.assumptions = assumptions
        self.toks = _tokens(text, name, symbols is not False)
        self.i = 0

    # -- helpers ---------------------------------------------------------------
    def fail(self, reason: str) -> ParseError:
        return _fail(self.name, self.text, reason, names=self.symbols is not False)

    def peek(self) -> tuple[str, str, int] | None:
        return self.toks[self.i] if self.i < len(self.toks) else None

    def take(self, value: str) -> bool:
        tok = self.peek()
        if tok is not None and tok[0] == "op" and tok[1] == value:
            self.i += 1
            return True
        return False

    # -- grammar ---------------------------------------------------------------
    def parse(self):
        if not self.toks:
            raise self.fail("the text is empty")
        expr = self.expression(0)
        tok = self.peek()
        if tok is not None:
            what = f"{tok[1]!r}"
            if tok[0] == "op" and tok[1] == "(":
                what = "'(' (calls are not allowed)"
            raise self.fail(f"unexpected {what} at position {tok[2] + 1}")
        return expr

    def check_depth(self, depth: int) -> None:
        if depth > MAX_DEPTH:
            raise self.fail(f"nested deeper than {MAX_DEPTH} levels")

    def expression(self, depth: int):
        self.check_depth(depth)
        terms = [self.term(depth + 1)]
        while True:
            if self.take("+"):
                terms.append(self.term(depth + 1))
            elif self.take("-"):
                terms.append(-self.term(depth + 1))
            else:
                return self.sp.Add(*terms)

    def term(self, depth: int):
        self.check_depth(depth)
        value = self.factor(depth + 1)
        while True:
            tok = self.peek()
            if self.take("*"):
                value = value * self.factor(depth + 1)
            elif self.take("/"):
                divisor = self.factor(depth + 1)
                if divisor == 0:
                    raise self.fail(f"division by zero at position {tok[2] + 1}")
                value = value / divisor
            else:
                return value

    def factor(self, depth: int):
        self.check_depth(depth)
        if self.take("-"):
            return -self.factor(depth + 1)
        if self.take("+"):
            return self.factor(depth + 1)
        return self.power(depth + 1)

    def power(self, depth: int):
        self.check_depth(depth)
        base = self.atom(depth + 1)
        tok = self.peek()
        if self.take("**"):
            exponent = self.factor(depth + 1)
            return self.pow(base, exponent, tok[2])
        return base

    def pow(self, base, exponent, at: int):
        sp = self.sp
        if exponent.is_Number:
            if not exponent.is_Rational:
                raise self.fail(f"the exponent at position {at + 1} must be exact")
            if abs(exponent) > MAX_EXPONENT:
                raise self.fail(f"the exponent {exponent} at position {at + 1} is larger than {MAX_EXPONENT} in magnitude")
            if base.is_Number:
                if base == 0 and exponent < 0:
                    raise self.fail(f"0 to a negative power at position {at + 1}")
                if base != 0:
                    p, q = sp.fraction(sp.Rational(base))
                    digits = float(abs(exponent)) * max(math.log10(abs(int(p)) or 1), math.log10(abs(int(q)) or 1), 0.0)
                    if digits > MAX_RESULT_DIGITS:
                        raise self.fail(f"the power at position {at + 1} would have ~{digits:.3g} digits (at most {MAX_RESULT_DIGITS})")
        return sp.Pow(base, exponent)

    def atom(self, depth: int):
        self.check_depth(depth)
        tok = self.peek()
        if tok is None:
            raise self.fail("the text ends where a number, a name or '(' is expected")
        kind, value, at = tok
        self.i += 1
        if kind == "number":
            return self.literal(value, at)
        if kind == "name":
            return self.symbol(value, at)
        if value == "(":
            inner = self.expression(depth + 1)
            if not self.take(")"):
                nxt = self.peek()
                where = "the end of the text" if nxt is None else f"{nxt[1]!r} at position {nxt[2] + 1}"
                raise self.fail(f"missing ')' for the '(' at position {at + 1} (found {where})")
            return inner
        raise self.fail(f"unexpected {value!r} at position {at + 1}")

    def literal(self, value: str, at: int):
        mantissa, _, exp = value.lower().partition("e")
        if len(mantissa.replace(".", "").lstrip("0")) > MAX_LITERAL_DIGITS:
            raise self.fail(f"the number at position {at + 1} has more than {MAX_LITERAL_DIGITS} digits")
        if exp and abs(int(exp)) > MAX_DECIMAL_EXPONENT:
            raise self.fail(f"the exponent of the number at position {at + 1} is larger than {MAX_DECIMAL_EXPONENT}")
        f = Fraction(value)
        return self.sp.Rational(f.numerator, f.denominator)

    def symbol(self, value: str, at: int):
        nxt = self.peek()
        if nxt is not None and nxt[0] == "op" and nxt[1] == "(":
            raise self.fail(f"calls are not allowed ({value!r} followed by '(' at position {nxt[2] + 1})")
        if nxt is not None and nxt[0] in ("name", "number"):  # e.g. "x y"
            raise self.fail(f"missing operator between {value!r} and {nxt[1]!r} at position {nxt[2] + 1}")
        if value.startswith("_") or keyword.iskeyword(value):
            raise self.fail(f"the name {value!r} at position {at + 1} is not allowed")
        if self.symbols is False:
            raise self.fail(f"names are not allowed here ({value!r} at position {at + 1})")
        if self.symbols is not True and value not in self.symbols:
            allowed = ", ".join(sorted(self.symbols)) or "none"
            raise self.fail(f"unknown name {value!r} at position {at + 1} (allowed names: {allowed})")
        return self.sp.Symbol(value, **self.assumptions)


def expression(text: str, name: str, *, symbols: bool | Collection[str] = True, **assumptions: Any):
    """Read ``text`` as an exact SymPy expression, without evaluating anything.

    Parameters
    ----------
    text : str
        The user's text, e.g. ``"1/2"``, ``"2*I_12 + 3"``, ``"(a - b)**2"``.
    name : str
        The argument or option the text came from; every error message names it.
    symbols : bool or collection of str, optional
        ``True`` (default): any name (no leading underscore, no Python keyword)
        becomes ``sympy.Symbol(name, **assumptions)``; ``False``: names are
        refused (numbers only); a collection: only those names.
    **assumptions
        SymPy assumptions for the symbols (e.g. ``positive=True``).

    Returns
    -------
    sympy.Expr
        Built with exact constructors: decimal literals are rationals.

    Raises
    ------
    TypeError
        ``text`` is not a ``str``.
    ParseError
        The text is not in the grammar of the module docstring, or is over a size bound.
    """
    if not isinstance(text, str):
        raise TypeError(f"{name} must be text (str), got {type(text).__name__}")
    if len(text) > MAX_LENGTH:
        raise _fail(name, text, f"the text is longer than {MAX_LENGTH} characters", names=symbols is not False)
    return _Parser(text, name, symbols, assumptions).parse()


def number(text: str, name: str, *, exact: bool = False):
    """Read ``text`` as one real number (no names), e.g. ``"1/2"``, ``"2.5e-3"``, ``"-(3/4)**2"``.

    Returns a finite ``float`` (``exact=False``, the default) or an exact
    ``sympy.Rational`` (``exact=True``). An irrational value (``"2**(1/2)"``)
    is returned as the nearest float, or refused with ``exact=True``.

    Raises
    ------
    TypeError
        ``text`` is not a ``str``.
    ParseError
        Not a number of the grammar, or not finite as a float.
    """
    if not exact and isinstance(text, str) and len(text) <= _DECIMAL_LENGTH and _DECIMAL.fullmatch(text):
        # a plain decimal literal: Python rounds it correctly, as float(Rational) does; + 0.0 turns -0.0
        # into 0.0 (the exact reading, Rational 0, has no sign)
        value = float(text) + 0.0
        if math.isfinite(value):
            return value  # (no SymPy: a command line that only reads plain numbers starts 0.6 s sooner)
    expr = expression(text, name, symbols=False)
    if exact:
        if not expr.is_Rational:
            raise _fail(name, text, "an exact fraction is required (this is irrational or complex)", names=False)
        return expr
    if not expr.is_extended_real:
        raise _fail(name, text, "a real number is required", names=False)
    try:
        value = float(expr)
    except (TypeError, OverflowError):
        value = math.inf
    if not math.isfinite(value):
        raise _fail(name, text, "the value is too large for a float", names=False)
    return value


def integer(text: str, name: str) -> int:
    """Read ``text`` as one integer (no names), e.g. ``"12"``, ``"2**10"``, ``"6/3"``.

    A plain integer literal is read without SymPy; anything else by :func:`expression`.

    Raises
    ------
    TypeError
        ``text`` is not a ``str``.
    ParseError
        Not a number of the grammar.
    ValueError
        A number that is not an integer (``"5.5"``), naming ``name`` and the text.
    """
    if isinstance(text, str) and _INTEGER.fullmatch(text):
        return int(text)
    value = expression(text, name, symbols=False)
    if not value.is_Integer:
        raise ValueError(f"{name} must be an integer, got {text!r}")
    return int(value)


def to_sympy(value: Any, name: str, *, text: bool = True, symbols: bool | Collection[str] = True, **assumptions: Any):
    """``value`` as a SymPy object, the one bridge from user input to SymPy.

    Accepted: SymPy objects (returned unchanged), Python and NumPy integers
    (``Integer``), ``fractions.Fraction`` (``Rational``), finite floats
    (``Float``), complex numbers, and -- when ``text`` is true -- a ``str``
    read by :func:`expression` (with ``symbols`` and ``assumptions``). This is
    what ``sympy.sympify`` did for hyperrotor, minus the evaluation of text.

    Raises
    ------
    TypeError
        ``value`` is a bool, None, a string where ``text=False``, or another type.
    ParseError
        Text outside the grammar.
    ValueError
        A float that is not finite.
    """
    import sympy as sp

    if isinstance(value, sp.Basic):
        return value
    if isinstance(value, str):
        if not text:
            raise TypeError(f"{name} must be a number or a SymPy expression, not text ({value[:80]!r})")
        return expression(value, name, symbols=symbols, **assumptions)
    if isinstance(value, bool) or value is None:
        raise TypeError(f"{name} must be a number or a SymPy expression, got {value!r}")
    if hasattr(value, "dtype") and getattr(value, "shape", None) == ():
        value = value.item()  # NumPy scalar or 0-d array
    if isinstance(value, bool):
        raise TypeError(f"{name} must be a number or a SymPy expression, got {value!r}")
    if isinstance(value, Integral):
        return sp.Integer(int(value))
    if isinstance(value, _RationalABC):
        return sp.Rational(int(value.numerator), int(value.denominator))
    if isinstance(value, Real):
        v = float(value)
        if not math.isfinite(v):
            raise ValueError(f"{name} must be finite, got {v!r}")
        return sp.Float(v)
    if isinstance(value, Complex):
        c = complex(value)
        if not (math.isfinite(c.real) and math.isfinite(c.imag)):
            raise ValueError(f"{name} must be finite, got {c!r}")
        return sp.Float(c.real) + sp.I * sp.Float(c.imag)
    raise TypeError(f"{name} must be a number or a SymPy expression, got {type(value).__name__}")
