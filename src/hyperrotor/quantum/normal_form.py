r"""Exact normal form of differential operators with polynomial coefficients (Weyl algebra).

Every differential operator with polynomial coefficients in ``N`` variables
has a unique *normal-ordered* form (all derivatives to the right)

.. math:: A = \sum_{(m, \alpha)} c_{m\alpha}\; x^{m}\, \partial^{\alpha},
          \qquad x^m = \prod_i x_i^{m_i},\quad
          \partial^\alpha = \prod_i \partial_i^{\alpha_i},

so two operators are equal iff their coefficient tables agree. This is the
Weyl algebra :math:`A_N`; its product follows from the Leibniz rule

.. math:: (x^{m}\partial^{\alpha})(x^{n}\partial^{\beta})
          = \sum_{\gamma \le \alpha,\ \gamma \le n} \binom{\alpha}{\gamma}
            \frac{n!}{(n-\gamma)!}\; x^{m+n-\gamma}\,\partial^{\alpha-\gamma+\beta}

(multi-index notation). :class:`WeylElement` stores the table as a plain
``dict`` ``{(m, alpha): c}`` of exponent tuples with exact coefficients: Python
``int``/:class:`fractions.Fraction` in the hot path, SymPy expressions only when
the user scales by a symbol (``hbar``, ``I``). SymPy is used only at the
boundaries: :meth:`WeylElement.apply` (action on an arbitrary SymPy expression),
:meth:`WeylElement.from_sympy` (parse an explicit differential expression
acting on a generic function) and the polynomial converters
:func:`polynomial_to_dict` / :func:`dict_to_polynomial`.

Indices here are 0-based positions in the coordinate tuple; the 1-based plane
labels of the paper live in :mod:`hyperrotor.quantum.operators`.
"""
from __future__ import annotations

import math
from fractions import Fraction
from itertools import product as _iproduct
from math import comb
from numbers import Integral, Rational
from typing import Any, Mapping, Sequence

import sympy as sp

from .. import _parse, _pricing

__all__ = ["WeylElement", "polynomial_to_dict", "dict_to_polynomial"]

Key = tuple  # (m, alpha): two exponent tuples of length N


# ----------------------------------------------------------------------------
# exact scalar coefficients
# ----------------------------------------------------------------------------
def _norm_scalar(c: Any):
    """Canonical exact coefficient: int, Fraction or (non-rational) SymPy expression."""
    if type(c) is int:
        return c
    if isinstance(c, bool):
        raise TypeError(f"a coefficient must be a number or a SymPy expression, got the bool {c!r}")
    if isinstance(c, Integral):
        return int(c)
    if isinstance(c, Fraction):
        return int(c) if c.denominator == 1 else c
    if isinstance(c, sp.Basic):
        if not isinstance(c, sp.Expr):
            raise TypeError(f"a coefficient must be a scalar SymPy expression, got {c!r} of type {type(c).__name__}")
        c = sp.expand(c)
        if c.is_Integer:
            return int(c)
        if c.is_Rational:
            return Fraction(int(c.p), int(c.q))
        return c
    if isinstance(c, Rational):
        return _norm_scalar(Fraction(c.numerator, c.denominator))
    if isinstance(c, (float, complex)):
        return _norm_scalar(_parse.to_sympy(c, "coefficient", text=False))
    raise TypeError(
        f"a coefficient must be an int, a Fraction or a SymPy expression, got {c!r} of type {type(c).__name__}"
    )


def _to_sympy_scalar(c):
    """A coefficient (int, Fraction, number or SymPy scalar; never text) as a SymPy object."""
    return _parse.to_sympy(c, "coefficient", text=False)


def _is_zero(c) -> bool:
    return c == 0


def _accumulate(out: dict, key, value) -> None:
    if key in out:
        v = out[key] + value
        if isinstance(v, sp.Basic):
            v = _norm_scalar(v)
        elif isinstance(v, Fraction) and v.denominator == 1:
            v = int(v)
        if _is_zero(v):
            del out[key]
        else:
            out[key] = v
    else:
        out[key] = value


def _falling(n: int, k: int) -> int:
    r = 1
    for t in range(k):
        r *= n - t
    return r


# ----------------------------------------------------------------------------
# polynomial dicts  {exponent tuple: coefficient}
# ----------------------------------------------------------------------------
def _symbols(coordinates: Any) -> tuple:
    """``coordinates`` as a tuple of SymPy symbols; text (a name or a string of names) is refused:
    SymPy would turn a string generator into an expression (``sympify``)."""
    if isinstance(coordinates, (str, bytes)):
        raise TypeError(f"coordinates must be a sequence of SymPy symbols (e.g. coordinate_symbols(N)), got text "
                        f"{coordinates[:80]!r}")
    try:
        coords = tuple(coordinates)
    except TypeError:
        raise TypeError(f"coordinates must be a sequence of SymPy symbols, got {type(coordinates).__name__}") from None
    if not coords:  # (SymPy would choose the expression's own symbols as generators)
        raise ValueError("coordinates must name at least one SymPy symbol (e.g. coordinate_symbols(N)), got none")
    bad = [c for c in coords if not isinstance(c, sp.Symbol)]
    if bad:
        raise TypeError(f"coordinates must be SymPy symbols (e.g. coordinate_symbols(N)), got {bad[0]!r} of type "
                        f"{type(bad[0]).__name__}")
    return coords


def polynomial_to_dict(expr: Any, coordinates: Sequence[sp.Symbol]) -> dict:
    """Exact coefficient dict ``{exponent tuple: coefficient}`` of a polynomial.

    Parameters
    ----------
    expr : SymPy expression (or int/Fraction)
        Must be a polynomial in ``coordinates``; other symbols may appear in
        the coefficients.
    coordinates : sequence of SymPy symbols

    Raises
    ------
    TypeError
        If ``expr`` is not a SymPy expression or number.
    ValueError
        If ``expr`` is not a polynomial in ``coordinates``.
    """
    coords = _symbols(coordinates)
    N = len(coords)
    if isinstance(expr, (Integral, Fraction)) and not isinstance(expr, bool):
        c = _norm_scalar(expr)
        return {(0,) * N: c} if c != 0 else {}
    if not isinstance(expr, sp.Expr):
        raise TypeError(f"expected a SymPy polynomial expression, got {expr!r} of type {type(expr).__name__}")
    _pricing.check("polynomial_expansion", terms=expanded_terms(expr), coords=N)  # (before sp.expand)
    try:
        poly = sp.Poly(sp.expand(expr), *coords)
    except sp.PolynomialError as err:
        raise ValueError(f"{expr} is not a polynomial in {coords}: {err}") from None
    out: dict = {}
    for monom, coeff in poly.terms():
        if coeff.has(*coords):
            raise ValueError(f"{expr} is not a polynomial in {coords}")
        c = _norm_scalar(coeff)
        if c != 0:
            out[tuple(int(e) for e in monom)] = c
    return out


def expanded_terms(expr: Any) -> float:
    """An upper bound on the number of terms of ``sp.expand(expr)`` (before like terms are collected), from its
    tree alone: a sum adds its terms' counts, a product multiplies them, a power ``b**k`` of ``n`` terms has at most
    ``C(n + k - 1, k)`` (exact for ``(x1 + ... + xn)**k``); anything else counts 1. A float (``inf`` beyond them)."""
    if isinstance(expr, sp.Add):
        return float(sum(expanded_terms(a) for a in expr.args))
    if isinstance(expr, sp.Mul):
        out = 1.0
        for a in expr.args:
            out *= expanded_terms(a)
        return out
    if isinstance(expr, sp.Pow) and expr.exp.is_Integer and expr.exp > 0:
        n, k = expanded_terms(expr.base), float(expr.exp)
        if n <= 1.0:
            return n
        try:
            return math.exp(math.lgamma(n + k) - math.lgamma(k + 1.0) - math.lgamma(n))
        except OverflowError:
            return math.inf
    return 1.0


def dict_to_polynomial(poly: Mapping, coordinates: Sequence[sp.Symbol]) -> sp.Expr:
    """SymPy expression of a coefficient dict ``{exponent tuple: coefficient}``."""
    coords = _symbols(coordinates)
    if not isinstance(poly, Mapping):
        raise TypeError(f"poly must be a mapping {{exponent tuple: coefficient}}, got {poly!r} of type "
                        f"{type(poly).__name__}")
    terms = []
    for m, c in poly.items():
        if len(m) != len(coords):
            raise ValueError(f"exponent {m} has {len(m)} entries but there are {len(coords)} coordinates")
        terms.append(_to_sympy_scalar(c) * sp.Mul(*[x**e for x, e in zip(coords, m) if e]))
    return sp.Add(*terms)


# ----------------------------------------------------------------------------
# Weyl algebra element
# ----------------------------------------------------------------------------
def _normalise_symbolic(out: dict) -> dict:
    """Normalise SymPy coefficients (e.g. ``I*I``) once after accumulation, dropping zeros; in place."""
    for k, v in list(out.items()):
        if isinstance(v, sp.Basic):
            v = _norm_scalar(v)
            if v == 0:
                del out[k]
            else:
                out[k] = v
    return out


#: compositions of more pairs of terms than this (~0.05 s) are priced first (smaller ones: no pricing overhead)
PRICED_PAIRS = 10_000


class WeylElement:
    r"""A differential operator with polynomial coefficients in normal order.

    ``WeylElement(N, terms)`` represents :math:`\sum c\, x^m \partial^\alpha`
    with ``terms = {(m, alpha): c}`` (``m``, ``alpha`` exponent tuples of length
    ``N``; ``c`` an ``int``, :class:`~fractions.Fraction` or SymPy expression).
    Zero coefficients are dropped, so ``A == B`` is an exact operator identity.

    Arithmetic: ``A + B``, ``A - B``, ``-A``, ``A * B`` (composition: ``B`` acts
    first), ``c * A`` / ``A * c`` for scalars ``c``, :meth:`commutator`.

    Examples
    --------
    >>> L12 = WeylElement.rotation(3, 0, 1)      # x1 d2 - x2 d1
    >>> L13, L23 = WeylElement.rotation(3, 0, 2), WeylElement.rotation(3, 1, 2)
    >>> L12.commutator(L23) == L13
    True
    """

    __slots__ = ("N", "terms")

    def __init__(self, N: int, terms: Mapping | None = None, *, _trusted: bool = False):
        if isinstance(N, bool) or not isinstance(N, Integral) or N < 1:
            raise TypeError(f"N must be a positive integer, got {N!r}")
        self.N = int(N)
        if _trusted:
            self.terms = terms  # type: ignore[assignment]
            return
        out: dict = {}
        for key, c in (terms or {}).items():
            try:
                m, a = key
                m, a = tuple(int(v) for v in m), tuple(int(v) for v in a)
            except (TypeError, ValueError):
                raise ValueError(f"a term key is a pair (m, alpha) of exponent tuples, got {key!r}") from None
            if len(m) != N or len(a) != N or min(m + a, default=0) < 0:
                raise ValueError(f"exponent tuples must have {N} non-negative entries, got {key!r}")
            c = _norm_scalar(c)
            if c != 0:
                _accumulate(out, (m, a), c)
        self.terms = out

    # ---------------------------------------------------------------- builders
    @classmethod
    def scalar(cls, N: int, c: Any = 1) -> "WeylElement":
        """The multiplication operator by the constant ``c``."""
        return cls(N, {((0,) * N, (0,) * N): c})

    @classmethod
    def coordinate(cls, N: int, i: int) -> "WeylElement":
        """Multiplication by :math:`x_i` (0-based ``i``)."""
        m = [0] * N
        m[i] = 1
        return cls(N, {(tuple(m), (0,) * N): 1})

    @classmethod
    def derivative(cls, N: int, i: int) -> "WeylElement":
        r""":math:`\partial/\partial x_i` (0-based ``i``)."""
        a = [0] * N
        a[i] = 1
        return cls(N, {((0,) * N, tuple(a)): 1})

    @classmethod
    def rotation(cls, N: int, i: int, j: int) -> "WeylElement":
        r""":math:`x_i\partial_j - x_j\partial_i` (0-based ``i != j``), eq. (142)."""
        if i == j:
            raise ValueError(f"a rotation generator needs two different indices, got ({i}, {j})")
        z = [0] * N
        mi, mj, ai, aj = list(z), list(z), list(z), list(z)
        mi[i] = aj[j] = 1
        mj[j] = ai[i] = 1
        return cls(N, {(tuple(mi), tuple(aj)): 1, (tuple(mj), tuple(ai)): -1})

    @classmethod
    def multiplication(cls, poly: Mapping, N: int) -> "WeylElement":
        """Multiplication by the polynomial with coefficient dict ``poly``."""
        return cls(N, {(tuple(m), (0,) * N): c for m, c in poly.items()})

    # ---------------------------------------------------------------- queries
    @property
    def order(self) -> int:
        """Differential order (highest total derivative degree); ``-1`` for zero."""
        return max((sum(a) for (_, a) in self.terms), default=-1)

    def is_zero(self) -> bool:
        return not self.terms

    def by_derivative(self) -> dict:
        """``{alpha: {m: c}}``: the coefficient polynomial of each derivative monomial."""
        out: dict = {}
        for (m, a), c in self.terms.items():
            out.setdefault(a, {})[m] = c
        return out

    def is_symbolic(self) -> bool:
        """True if some coefficient is a (non-rational) SymPy expression."""
        return any(isinstance(c, sp.Basic) for c in self.terms.values())

    # ---------------------------------------------------------------- algebra
    def _check(self, other: "WeylElement") -> None:
        if other.N != self.N:
            raise ValueError(f"cannot combine operators in {self.N} and {other.N} variables")

    def __eq__(self, other: object) -> bool:
        if isinstance(other, WeylElement):
            return self.N == other.N and self.terms == other.terms
        if other == 0:
            return not self.terms
        return NotImplemented

    __hash__ = None  # type: ignore[assignment]

    def __add__(self, other: Any) -> "WeylElement":
        if not isinstance(other, WeylElement):
            other = WeylElement.scalar(self.N, other)
        self._check(other)
        out = dict(self.terms)
        for k, c in other.terms.items():
            _accumulate(out, k, c)
        return WeylElement(self.N, out, _trusted=True)

    __radd__ = __add__

    def __neg__(self) -> "WeylElement":
        return WeylElement(self.N, {k: -c for k, c in self.terms.items()}, _trusted=True)

    def __sub__(self, other: Any) -> "WeylElement":
        if not isinstance(other, WeylElement):
            other = WeylElement.scalar(self.N, other)
        return self + (-other)

    def __rsub__(self, other: Any) -> "WeylElement":
        return (-self) + other

    def scale(self, c: Any) -> "WeylElement":
        """``c * self`` for a scalar ``c`` (number or SymPy expression free of the coordinates)."""
        c = _norm_scalar(c)
        if c == 0:
            return WeylElement(self.N, {}, _trusted=True)
        out = {}
        for k, v in self.terms.items():
            w = _norm_scalar(v * c) if isinstance(v, sp.Basic) or isinstance(c, sp.Basic) else v * c
            if isinstance(w, Fraction) and w.denominator == 1:
                w = int(w)
            if w != 0:
                out[k] = w
        return WeylElement(self.N, out, _trusted=True)

    def __mul__(self, other: Any) -> "WeylElement":
        if isinstance(other, WeylElement):
            return self.compose(other)
        return self.scale(other)

    def __rmul__(self, other: Any) -> "WeylElement":
        return self.scale(other)

    def compose(self, other: "WeylElement") -> "WeylElement":
        """The composition ``self o other`` in normal order (Leibniz rule, module docstring); priced beyond
        :data:`PRICED_PAIRS` pairs of terms (the ``"operator_composition"`` model: every route composes here)."""
        self._check(other)
        N = self.N
        pairs = len(self.terms) * len(other.terms)
        if pairs > PRICED_PAIRS:
            _pricing.check("operator_composition", pairs=pairs, coords=N)
        out: dict = {}
        for (m1, a1), c1 in self.terms.items():
            act = [i for i in range(N) if a1[i]]
            for (m2, a2), c2 in other.terms.items():
                c12 = c1 * c2
                idx = [i for i in act if m2[i]]
                if not idx:
                    key = (tuple(p + q for p, q in zip(m1, m2)), tuple(p + q for p, q in zip(a1, a2)))
                    _accumulate(out, key, c12)
                    continue
                for gam in _iproduct(*[range(min(a1[i], m2[i]) + 1) for i in idx]):
                    w = 1
                    m = list(m1)
                    a = list(a1)
                    for i, g in zip(idx, gam):
                        if g:
                            w *= comb(a1[i], g) * _falling(m2[i], g)
                            m[i] -= g
                            a[i] -= g
                    key = (
                        tuple(p + q for p, q in zip(m, m2)),
                        tuple(p + q for p, q in zip(a, a2)),
                    )
                    _accumulate(out, key, c12 * w)
        return WeylElement(N, _normalise_symbolic(out), _trusted=True)

    def commutator(self, other: "WeylElement") -> "WeylElement":
        """``[self, other] = self o other - other o self`` (exact; both compositions priced at once)."""
        self._check(other)
        pairs = 2 * len(self.terms) * len(other.terms)
        if pairs > PRICED_PAIRS:
            _pricing.check("operator_composition", pairs=pairs, coords=self.N)
        return self.compose(other) - other.compose(self)

    # ---------------------------------------------------------------- action
    def apply_to_poly(self, poly: Mapping) -> dict:
        """Apply to a polynomial given as a coefficient dict ``{m: c}``; returns a dict (exact, fast; every pair of an
        operator term and a monomial, priced as the pairs of a composition beyond :data:`PRICED_PAIRS`)."""
        N = self.N
        if len(self.terms) * len(poly) > PRICED_PAIRS:
            _pricing.check("operator_composition", pairs=len(self.terms) * len(poly), coords=N)
        out: dict = {}
        for (m1, a1), c1 in self.terms.items():
            for m2, c2 in poly.items():
                if len(m2) != N:
                    raise ValueError(f"exponent {m2} does not have {N} entries")
                w = 1
                for ai, mi in zip(a1, m2):
                    if ai:
                        if ai > mi:
                            w = 0
                            break
                        w *= _falling(mi, ai)
                if w:
                    key = tuple(p + q - r for p, q, r in zip(m1, m2, a1))
                    _accumulate(out, key, c1 * c2 * w)
        return _normalise_symbolic(out)

    def apply(self, expr: Any, coordinates: Sequence[sp.Symbol]) -> sp.Expr:
        """Apply to an arbitrary SymPy expression in ``coordinates`` (SymPy differentiation).

        Raises ``TypeError`` if ``expr`` is not a SymPy expression (or a plain number).
        """
        coords = tuple(coordinates)
        if len(coords) != self.N:
            raise ValueError(f"{len(coords)} coordinates given for an operator in {self.N} variables")
        if isinstance(expr, bool) or not isinstance(expr, (sp.Expr, Integral, Fraction)):
            raise TypeError(
                f"operators apply to SymPy expressions, got {expr!r} of type {type(expr).__name__}"
            )
        expr = _parse.to_sympy(expr, "expr", text=False)
        total = []
        for a, poly in self.by_derivative().items():
            spec = [(x, k) for x, k in zip(coords, a) if k]
            d = sp.diff(expr, *spec) if spec else expr
            if d == 0:
                continue
            total.append(dict_to_polynomial(poly, coords) * d)
        return sp.Add(*total)

    def to_sympy(self, f: sp.Expr, coordinates: Sequence[sp.Symbol]) -> sp.Expr:
        """The explicit SymPy expression ``self(f)`` for a generic function ``f`` (unevaluated derivatives)."""
        coords = tuple(coordinates)
        total = []
        for a, poly in self.by_derivative().items():
            spec = [(x, k) for x, k in zip(coords, a) if k]
            d = sp.Derivative(f, *spec) if spec else f
            total.append(dict_to_polynomial(poly, coords) * d)
        return sp.Add(*total)

    @classmethod
    def from_sympy(cls, expr: sp.Expr, f: sp.Expr, coordinates: Sequence[sp.Symbol]) -> "WeylElement":
        """Parse an expression linear in ``f`` and its derivatives, ``sum p(x) d^alpha f``.

        Parameters
        ----------
        expr : SymPy expression, e.g. ``x*Derivative(f(x, y), y) - y*Derivative(f(x, y), x)``.
        f : the generic function, e.g. ``sympy.Function("f")(x, y)``.
        coordinates : the variables, in order.

        Raises
        ------
        TypeError
            If ``expr`` is text (build it with SymPy instead: text is never evaluated).
        ValueError
            If a term does not contain exactly one factor ``f`` / derivative of
            ``f``, or its coefficient is not a polynomial in the coordinates.
        """
        coords = tuple(coordinates)
        N = len(coords)
        pos = {x: i for i, x in enumerate(coords)}
        out: dict = {}
        expr = _parse.to_sympy(expr, "expr", text=False)  # text is refused, never parsed as Python (#21)
        for term in sp.Add.make_args(sp.expand(expr)):
            if term == 0:
                continue
            hits, rest = [], []
            for fac in sp.Mul.make_args(term):
                if fac == f or (isinstance(fac, sp.Derivative) and fac.expr == f):
                    hits.append(fac)
                else:
                    rest.append(fac)
            if len(hits) != 1:
                raise ValueError(f"term {term} is not linear in {f} and its derivatives")
            alpha = [0] * N
            if isinstance(hits[0], sp.Derivative):
                for var, k in hits[0].variable_count:
                    if var not in pos:
                        raise ValueError(f"derivative with respect to {var}, which is not a coordinate {coords}")
                    alpha[pos[var]] += int(k)
            coeff = sp.Mul(*rest)
            if coeff.has(f):
                raise ValueError(f"term {term} is not linear in {f}")
            for m, c in polynomial_to_dict(coeff, coords).items():
                _accumulate(out, (m, tuple(alpha)), c)
        return cls(N, out, _trusted=True)

    # ---------------------------------------------------------------- printing
    def __repr__(self) -> str:
        return f"WeylElement(N={self.N}, terms={self.terms!r})"
