r"""Linear differential operators with polynomial coefficients in exact normal form, and their coordinates.

:class:`DifferentialOperator` wraps the normal form
:class:`hyperrotor.quantum.normal_form.WeylElement` with the coordinate symbols it acts
on: linear combinations, composition, powers, commutators, the action on expressions and
polynomials, equality as an exact operator identity, the Hermitian form
:math:`-i\hbar A` (:meth:`DifferentialOperator.as_form`) and LaTeX.
:func:`coordinate_symbols` names the coordinates (``x1 .. xN``, the paper's ``x, y, z, w, v``
or the caller's own). The named operators of so(N) built from them (angular momentum,
Casimir, Euler, Laplacian) are in :mod:`hyperrotor.quantum.operators`.

Symbols
-------
Operators act on the coordinate symbols *by name*: ``x1`` created with any
assumptions (``sympy.symbols("x1:4")`` gives symbols without ``real=True``) is
the coordinate ``x1``, and the result is written in the caller's symbols
(:meth:`DifferentialOperator.apply`). Two different symbols with one
coordinate's name in one expression are refused (``ValueError``).
"""
from __future__ import annotations

from fractions import Fraction
from functools import lru_cache
from numbers import Integral, Number
from typing import Any, Mapping, Sequence

import sympy as sp

from .. import _parse, _validate
from ..conventions import check_dimension
from .normal_form import WeylElement, dict_to_polynomial, polynomial_to_dict

__all__ = ["DifferentialOperator", "coordinate_symbols", "PAPER_COORDINATES"]

#: The paper's Cartesian coordinate names in 5D (Section 5): x, y, z, w, v.
PAPER_COORDINATES = ("x", "y", "z", "w", "v")


# ----------------------------------------------------------------------------
# coordinates
# ----------------------------------------------------------------------------
@lru_cache(maxsize=None)
def _default_coordinates(N: int) -> tuple:
    return tuple(sp.Symbol(f"x{i}", real=True) for i in range(1, N + 1))


def coordinate_symbols(N: int, coordinates: Any = None) -> tuple:
    """The coordinate symbols used by the operators of so(N).

    Parameters
    ----------
    N : int
        Dimension, ``N >= 2``.
    coordinates : None, "paper" or sequence
        ``None``: real SymPy symbols ``x1, ..., xN``. ``"paper"``: the paper's
        names ``x, y, z, w, v`` (Section 5; first ``N`` of them, ``N <= 5``).
        A sequence of ``N`` distinct SymPy symbols or names (strings, made into
        real symbols).

    Raises
    ------
    TypeError, ValueError
        Non-integer or too small ``N``; an unknown name such as ``"cartesian"``;
        the wrong number of coordinates; duplicates; entries that are neither
        symbols nor strings.
    """
    N = check_dimension(N)
    if coordinates is None:
        return _default_coordinates(N)
    if isinstance(coordinates, str):
        if coordinates == "paper":
            if N > len(PAPER_COORDINATES):
                raise ValueError(
                    f'coordinates="paper" names only {len(PAPER_COORDINATES)} axes '
                    f"({', '.join(PAPER_COORDINATES)}), got N = {N}; pass None or {N} symbols"
                )
            return tuple(sp.Symbol(n, real=True) for n in PAPER_COORDINATES[:N])
        raise ValueError(
            f"unknown coordinates {coordinates!r}; allowed: None (x1..xN), 'paper' (x, y, z, w, v) "
            f"or a sequence of {N} symbols/names"
        )
    try:
        items = list(coordinates)
    except TypeError:
        raise TypeError(
            f"coordinates must be None, 'paper' or a sequence of {N} symbols/names, got {coordinates!r}"
        ) from None
    if len(items) != N:
        raise ValueError(f"expected {N} coordinates for N = {N}, got {len(items)}: {items!r}")
    out = []
    for c in items:
        if isinstance(c, str):  # a name, read by the one parser of user text (an identifier, nothing else)
            sym = _parse.to_sympy(c, "a coordinate", real=True)
            if not isinstance(sym, sp.Symbol):
                raise ValueError(f"a coordinate name must be an identifier such as 'x' or 'x1', got {c[:80]!r}")
            out.append(sym)
        elif isinstance(c, sp.Symbol):
            out.append(c)
        else:
            raise TypeError(f"a coordinate must be a SymPy Symbol or a name (str), got {c!r} of type {type(c).__name__}")
    if len({str(s) for s in out}) != N:  # (by name: the operators find their coordinates by name, to_coordinates)
        raise ValueError(f"coordinates must have distinct names, got {out}")
    return tuple(out)


# ----------------------------------------------------------------------------
# the operator class
# ----------------------------------------------------------------------------
def to_coordinates(expr: Any, coordinates: Sequence[sp.Symbol]) -> tuple[Any, dict]:
    """Replace the symbols of ``expr`` named like a coordinate (but with other assumptions) by it.

    Returns ``(expr in the coordinates, map back to the caller's symbols)``.
    Raises ``ValueError`` if two different symbols of ``expr`` share a coordinate's name.
    """
    if not isinstance(expr, sp.Basic):
        return expr, {}
    by_name = {str(x): x for x in coordinates}
    fwd: dict = {}
    for s in expr.free_symbols:
        c = by_name.get(str(s))
        if c is None or s == c:
            continue
        if c in expr.free_symbols or any(o != s and str(o) == str(s) for o in fwd):
            raise ValueError(
                f"the expression holds two different symbols named {str(s)!r} (e.g. with different "
                f"assumptions); the operator acts on the coordinate {str(s)!r}: use one of them"
            )
        fwd[s] = c
    if not fwd:
        return expr, {}
    return expr.xreplace(fwd), {c: s for s, c in fwd.items()}


def _is_scalar(c: Any) -> bool:
    if isinstance(c, bool):
        return False
    return isinstance(c, (Number, Fraction)) or (isinstance(c, sp.Expr) and not isinstance(c, sp.MatrixBase))


def _is_zero(c: Any) -> bool:
    """``c`` is a scalar zero of any numeric type (SymPy's ``Float(0) == 0`` is False since SymPy 1.13)."""
    if not _is_scalar(c):
        return False
    return c.is_zero is True if isinstance(c, sp.Basic) else c == 0


def _finite(c: Number) -> bool:
    """A Python or NumPy number is finite (complex: both parts)."""
    try:
        return all(abs(float(x)) < float("inf") for x in (getattr(c, "real", c), getattr(c, "imag", 0)))
    except (TypeError, OverflowError):  # (an int beyond the floats is finite)
        return isinstance(c, Integral)


class DifferentialOperator:
    r"""A linear differential operator with polynomial coefficients, in exact normal form.

    Usually obtained from :func:`angular_momentum_operators`; the constructor takes
    the normal form directly: ``DifferentialOperator(element, coordinates)`` with a
    :class:`~hyperrotor.quantum.normal_form.WeylElement` and the coordinate
    symbols it acts on.

    Operations
    ----------
    ``op(f)`` / ``op.apply(f)``
        Action on any SymPy expression ``f`` (SymPy differentiation).
    ``A * B``
        Composition, ``(A * B)(f) = A(B(f))`` (``B`` acts first).
    ``A + B``, ``A - B``, ``-A``, ``c * A``, ``A * c``
        Linear combinations; ``c`` a number or a SymPy expression free of the
        coordinates (e.g. ``hbar``, ``sympy.I``). Numbers added to an operator
        mean multiples of the identity.
    ``A == B``
        Exact operator identity (equal normal forms).
    ``sympy.latex(A)``, ``A._repr_latex_()``
        LaTeX of the normal form.
    :meth:`as_form`
        ``as_form("hermitian", hbar=...)`` is :math:`-i\hbar A` (eq. 141).

    Combining operators on different coordinates raises ``ValueError``.
    """

    __slots__ = ("element", "coordinates")

    def __init__(self, element: WeylElement, coordinates: Sequence[sp.Symbol]):
        if not isinstance(element, WeylElement):
            raise TypeError(f"element must be a WeylElement, got {type(element).__name__}")
        if not (isinstance(coordinates, (tuple, list)) and all(isinstance(c, sp.Symbol) for c in coordinates)):
            coordinates = coordinate_symbols(element.N, coordinates)  # names are read by the one parser
        coords = tuple(coordinates)
        if len(coords) != element.N:
            raise ValueError(f"{len(coords)} coordinates for an operator in {element.N} variables")
        self.element = element
        self.coordinates = coords

    # ------------------------------------------------------------ properties
    @property
    def N(self) -> int:
        """Number of coordinates."""
        return self.element.N

    @property
    def order(self) -> int:
        """Differential order (``-1`` for the zero operator)."""
        return self.element.order

    def is_zero(self) -> bool:
        return self.element.is_zero()

    # ------------------------------------------------------------ algebra
    def _same_space(self, other: "DifferentialOperator") -> None:
        if other.coordinates != self.coordinates:
            raise ValueError(
                "cannot combine operators on different coordinates: "
                f"N = {self.N} {self.coordinates} and N = {other.N} {other.coordinates}"
            )

    def _wrap(self, element: WeylElement) -> "DifferentialOperator":
        return DifferentialOperator(element, self.coordinates)

    def _coerce(self, other: Any) -> WeylElement:
        if isinstance(other, DifferentialOperator):
            self._same_space(other)
            return other.element
        if _is_scalar(other):
            self._check_scalar(other)
            return WeylElement.scalar(self.N, other)
        raise TypeError(f"cannot combine a DifferentialOperator with {other!r} of type {type(other).__name__}")

    def _check_scalar(self, c: Any) -> None:
        if isinstance(c, sp.Basic) and c.has(sp.zoo, sp.oo, -sp.oo, sp.nan) or (
                isinstance(c, Number) and not isinstance(c, sp.Basic) and not _finite(c)):
            raise ValueError(f"an operator's scalar factor must be finite, got {c}")
        names = {str(x) for x in self.coordinates}
        if isinstance(c, sp.Basic) and (c.has(*self.coordinates) or any(str(s) in names for s in c.free_symbols)):
            raise ValueError(
                f"scalar {c} depends on the coordinates; use multiplication_operator(...) for a "
                "position-dependent factor"
            )

    def __add__(self, other: Any) -> "DifferentialOperator":
        try:
            e = self._coerce(other)
        except TypeError:
            return NotImplemented
        return self._wrap(self.element + e)

    __radd__ = __add__

    def __sub__(self, other: Any) -> "DifferentialOperator":
        try:
            e = self._coerce(other)
        except TypeError:
            return NotImplemented
        return self._wrap(self.element - e)

    def __rsub__(self, other: Any) -> "DifferentialOperator":
        try:
            e = self._coerce(other)
        except TypeError:
            return NotImplemented
        return self._wrap(e - self.element)

    def __neg__(self) -> "DifferentialOperator":
        return self._wrap(-self.element)

    def __mul__(self, other: Any) -> "DifferentialOperator":
        if isinstance(other, DifferentialOperator):
            self._same_space(other)
            return self._wrap(self.element.compose(other.element))
        if _is_scalar(other):
            self._check_scalar(other)
            return self._wrap(self.element.scale(other))
        return NotImplemented

    def __rmul__(self, other: Any) -> "DifferentialOperator":
        if _is_scalar(other):
            self._check_scalar(other)
            return self._wrap(self.element.scale(other))
        return NotImplemented

    def __truediv__(self, other: Any) -> "DifferentialOperator":
        if _is_zero(other):
            raise ZeroDivisionError(f"an operator divided by zero ({other!r})")
        if isinstance(other, Integral) and not isinstance(other, bool):
            return self * Fraction(1, int(other))
        if _is_scalar(other):
            return self * (1 / _parse.to_sympy(other, "divisor", text=False))
        return NotImplemented

    def __pow__(self, n: int) -> "DifferentialOperator":
        if isinstance(n, bool) or not isinstance(n, Integral) or n < 0:
            raise ValueError(f"operator powers need an integer exponent >= 0, got {n!r}")
        out = self._wrap(WeylElement.scalar(self.N, 1))
        for _ in range(int(n)):
            out = out * self
        return out

    def __eq__(self, other: object) -> bool:
        if isinstance(other, DifferentialOperator):
            return self.coordinates == other.coordinates and self.element == other.element
        if _is_zero(other):  # (0, 0.0, Fraction(0), SymPy's 0 and 0.0: the zero operator)
            return self.element.is_zero()
        return NotImplemented

    __hash__ = None  # type: ignore[assignment]

    def commutator(self, other: "DifferentialOperator") -> "DifferentialOperator":
        """``[self, other] = self*other - other*self`` as an operator (exact)."""
        if not isinstance(other, DifferentialOperator):
            raise TypeError(f"commutator needs two DifferentialOperators, got {type(other).__name__}")
        self._same_space(other)
        return self._wrap(self.element.commutator(other.element))

    def as_form(self, form: str, *, hbar: Any = 1) -> "DifferentialOperator":
        r"""``self`` (``form="antihermitian"``) or :math:`-i\hbar\,\cdot` ``self`` (``form="hermitian"``, eq. 141).

        ``hbar`` (keyword-only, default the exact 1) is a positive number or a SymPy
        symbol/expression (e.g. ``sympy.Symbol("hbar", positive=True)``); text is
        refused with ``TypeError``. With ``"antihermitian"`` only ``hbar=1`` is
        allowed (any other value would be ignored). For the
        anti-Hermitian :math:`L^{ij}` of eq. (142) ``"hermitian"`` gives the
        physical angular momentum :math:`\mathbb L^{ij}`.
        """
        form, hbar = _validate.form_hbar(form, hbar, exact=True)
        if form == "antihermitian":
            return self
        return self * (-sp.I * hbar)

    # ------------------------------------------------------------ action
    def apply(self, f: Any) -> sp.Expr:
        """Apply to a SymPy expression ``f`` (any function of the coordinates).

        Symbols of ``f`` named like a coordinate *are* that coordinate, whatever
        their assumptions (``sympy.symbols("x1:4")`` works with the default
        real coordinates ``x1, x2, x3``); the result is written in the symbols
        of ``f``. Raises ``TypeError`` for anything that is not a SymPy
        expression or a number, ``ValueError`` if ``f`` holds two different
        symbols with one coordinate's name.
        """
        if isinstance(f, bool) or not isinstance(f, (sp.Expr, Integral, Fraction)):
            raise TypeError(
                f"a DifferentialOperator applies to SymPy expressions, got {f!r} of type {type(f).__name__}"
            )
        f, back = to_coordinates(f, self.coordinates)
        out = self.element.apply(f, self.coordinates)
        return out.xreplace(back) if back else out

    def __call__(self, f: Any) -> sp.Expr:
        return self.apply(f)

    def to_sympy(self, f: sp.Expr | None = None) -> sp.Expr:
        """Explicit expression ``self(f)`` with unevaluated derivatives of a generic ``f``.

        ``f`` defaults to ``Function("f")(*coordinates)``; convert back with
        :meth:`from_sympy`.
        """
        if f is None:
            f = sp.Function("f")(*self.coordinates)
        return self.element.to_sympy(f, self.coordinates)

    @classmethod
    def from_sympy(cls, expr: sp.Expr, f: sp.Expr, coordinates: Sequence[sp.Symbol]) -> "DifferentialOperator":
        """Operator ``A`` with ``A(f) == expr`` for an expression linear in ``f`` and its derivatives."""
        coords = tuple(coordinates)
        return cls(WeylElement.from_sympy(expr, f, coords), coords)

    @classmethod
    def from_polynomial(cls, expr: Any, coordinates: Sequence[sp.Symbol]) -> "DifferentialOperator":
        """Multiplication by the polynomial ``expr`` (order 0); symbols named like a coordinate are that coordinate."""
        coords = tuple(coordinates)
        expr, _ = to_coordinates(expr, coords)
        return cls(WeylElement.multiplication(polynomial_to_dict(expr, coords), len(coords)), coords)

    def apply_to_polynomial(self, poly: Any):
        """Fast exact action on a polynomial.

        ``poly`` is a coefficient dict ``{exponent tuple: coefficient}`` (the result
        is then a dict of the same kind) or a SymPy polynomial in the coordinates
        (the result is then a SymPy expression).
        """
        if isinstance(poly, Mapping):
            return self.element.apply_to_poly(poly)
        poly, back = to_coordinates(poly, self.coordinates)
        d = polynomial_to_dict(poly, self.coordinates)
        out = dict_to_polynomial(self.element.apply_to_poly(d), self.coordinates)
        return out.xreplace(back) if back else out

    # ------------------------------------------------------------ printing
    def _sorted_groups(self):
        groups = self.element.by_derivative()
        return sorted(groups.items(), key=lambda kv: (-sum(kv[0]), kv[0]))

    def _latex(self, printer: Any = None, **kwargs) -> str:
        if self.element.is_zero():
            return "0"
        lat = (lambda e: printer._print(e)) if printer is not None else sp.latex
        parts = []
        for alpha, poly in self._sorted_groups():
            coeff = dict_to_polynomial(poly, self.coordinates)
            order = sum(alpha)
            if order == 0:
                dstr = ""
            else:
                den = " ".join(
                    (rf"\partial {lat(x)}" if k == 1 else rf"\partial {lat(x)}^{{{k}}}")
                    for x, k in zip(self.coordinates, alpha) if k
                )
                num = r"\partial" if order == 1 else rf"\partial^{{{order}}}"
                dstr = rf"\frac{{{num}}}{{{den}}}"
            neg = False
            if not isinstance(coeff, sp.Add) and coeff.could_extract_minus_sign():
                neg, coeff = True, -coeff
            if coeff == 1 and dstr:
                cstr = ""
            elif isinstance(coeff, sp.Add) and dstr:
                cstr = rf"\left({lat(coeff)}\right) "
            else:
                cstr = lat(coeff) + (" " if dstr else "")
            parts.append((neg, cstr + dstr))
        out = ("- " if parts[0][0] else "") + parts[0][1]
        for neg, s in parts[1:]:
            out += (" - " if neg else " + ") + s
        return out

    def _repr_latex_(self) -> str:
        return f"$\\displaystyle {self._latex()}$"

    def __str__(self) -> str:
        if self.element.is_zero():
            return "0"
        parts = []
        for alpha, poly in self._sorted_groups():
            coeff = dict_to_polynomial(poly, self.coordinates)
            d = "*".join(f"d{x}" + (f"^{k}" if k > 1 else "") for x, k in zip(self.coordinates, alpha) if k)
            parts.append(f"({coeff})" + (f"*{d}" if d else ""))
        return " + ".join(parts)

    def __repr__(self) -> str:
        return f"DifferentialOperator({self})"
