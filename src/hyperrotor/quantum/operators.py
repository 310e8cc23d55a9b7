r"""Quantum angular-momentum operators of so(N) as exact SymPy differential operators.

The paper's Section 5 (eqs. 141-147) in any dimension ``N >= 2``.

Two forms of the generators
---------------------------
* **Anti-Hermitian (real) form, eq. (142)**: the vector fields

  .. math:: L^{ij} = x_i\,\partial_j - x_j\,\partial_i, \qquad 1 \le i < j \le N,

  returned by :func:`angular_momentum_operators` with ``hbar=None``. They obey

  .. math:: [L^{ij}, L^{kl}] = \delta_{jk} L^{il} - \delta_{ik} L^{jl}
            - \delta_{jl} L^{ik} + \delta_{il} L^{jk},

  i.e. :math:`[L_a, L_b] = \sum_c C_{ab}^{\;c} L_c` with **exactly** the
  structure constants :func:`hyperrotor.conventions.structure_constants` (overall
  sign ``+1``): ``L^{ij}`` is the image of the matrix
  :math:`E_{(ij)} = e_i e_j^{\mathsf T} - e_j e_i^{\mathsf T}` under the Lie-algebra
  homomorphism :math:`M \mapsto -\sum_{ab} M_{ab}\, x_b\, \partial_a`.
* **Hermitian (physics) form, eq. (141)**: :math:`\mathbb L^{ij} = -i\hbar\,L^{ij}`
  (``hbar=`` argument or :meth:`DifferentialOperator.hermitian`), with

  .. math:: [\mathbb L^{ij}, \mathbb L^{kl}] = i\hbar\,(\delta_{ik}\mathbb L^{jl}
            + \delta_{jl}\mathbb L^{ik} - \delta_{il}\mathbb L^{jk}
            - \delta_{jk}\mathbb L^{il})
            = -i\hbar \sum_c C_{ab}^{\;c}\,\mathbb L_c .

  In 3D, with :math:`L_x = \mathbb L^{23}`, :math:`L_y = \mathbb L^{31} = -\mathbb L^{13}`,
  :math:`L_z = \mathbb L^{12}` (:func:`textbook_so3`), these are the textbook
  :math:`L_x = y p_z - z p_y`, ... with :math:`p = -i\hbar\nabla` and
  :math:`[L_x, L_y] = i\hbar L_z` (cyclic).

Operators are :class:`DifferentialOperator` objects wrapping the exact normal
form :class:`hyperrotor.quantum.normal_form.WeylElement`; equality ``A == B`` is
an exact operator identity.

Where the printed paper differs (Section 5)
-------------------------------------------
* Eq. (141) prints the entries as :math:`\mathbb 1^{ij}`; they are the operators
  :math:`\mathbb L^{ij}` of eq. (142), times :math:`-i\hbar`, with the checkerboard
  signs of eq. (21). Eq. (143) reuses the symbol :math:`\mathbb L` for the matrix
  *without* :math:`-i\hbar`; eqs. (145)-(147) hold for that real matrix.
* Eq. (144) copies eq. (25) with three index typos (entries 12, 25, 45), see
  :func:`operator_product`.
* Eqs. (145)-(147), :math:`\mathbb L\Omega = -(N-2)\mathbb L` with
  :math:`\Omega = \mathbb L^{\mathsf T}`, are not true for the ordinary matrix
  product (its entries are second-order operators); they hold for the
  antisymmetrized product :math:`(\mathbb L\Omega)_{ij} - (\mathbb L\Omega)_{ji}`.
  With the eq. (144) product itself the sign is opposite (``+(N-2)``) for
  :math:`\Omega = \mathbb L^{\mathsf T}` and ``-(N-2)`` for :math:`\Omega = \mathbb L`.
  For the Hermitian matrix of eq. (141) the factor is :math:`i\hbar(N-2)`
  (:func:`contraction_identity`).
* Cross references in the text: "operator (144)" should be (141), "operators
  ... from (146)" should be (143), "products in (147)" and "From Equation (147)"
  should be (144), "Equation (148)" should be (145).
"""
from __future__ import annotations

from collections import namedtuple
from fractions import Fraction
from functools import lru_cache
from numbers import Integral, Number
from typing import Any, Mapping, Sequence

import numpy as np
import sympy as sp

from ..conventions import check_convention, check_dimension, planes
from .normal_form import WeylElement, _norm_scalar, _to_sympy_scalar, dict_to_polynomial, polynomial_to_dict

__all__ = [
    "DifferentialOperator",
    "coordinate_symbols",
    "angular_momentum_operators",
    "angular_momentum_operator",
    "commutator",
    "euler_operator",
    "laplacian_operator",
    "multiplication_operator",
    "casimir_operator",
    "textbook_so3",
    "operator_matrix",
    "operator_product",
    "contraction_identity",
    "ContractionIdentity",
    "PAPER_COORDINATES",
]

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
        if isinstance(c, str):
            out.append(sp.Symbol(c, real=True))
        elif isinstance(c, sp.Symbol):
            out.append(c)
        else:
            raise TypeError(f"a coordinate must be a SymPy Symbol or a name (str), got {c!r} of type {type(c).__name__}")
    if len(set(out)) != N:
        raise ValueError(f"coordinates must be distinct, got {out}")
    return tuple(out)


def _hbar(hbar: Any):
    if isinstance(hbar, str):
        return sp.Symbol(hbar, positive=True)
    if isinstance(hbar, bool) or not isinstance(hbar, (Number, sp.Expr)):
        raise TypeError(f"hbar must be a SymPy symbol/expression or a number, got {hbar!r} of type {type(hbar).__name__}")
    return sp.sympify(hbar)


# ----------------------------------------------------------------------------
# the operator class
# ----------------------------------------------------------------------------
def _is_scalar(c: Any) -> bool:
    if isinstance(c, bool):
        return False
    return isinstance(c, (Number, Fraction)) or (isinstance(c, sp.Expr) and not isinstance(c, sp.MatrixBase))


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
    :meth:`hermitian`
        :math:`-i\hbar A` (eq. 141).

    Combining operators on different coordinates raises ``ValueError``.
    """

    __slots__ = ("element", "coordinates")

    def __init__(self, element: WeylElement, coordinates: Sequence[sp.Symbol]):
        if not isinstance(element, WeylElement):
            raise TypeError(f"element must be a WeylElement, got {type(element).__name__}")
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
        if isinstance(c, sp.Basic) and c.has(*self.coordinates):
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
        if isinstance(other, Integral) and not isinstance(other, bool):
            return self * Fraction(1, int(other))
        if _is_scalar(other):
            return self * (1 / sp.sympify(other))
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
        if isinstance(other, (int, sp.Integer)) and other == 0:
            return self.element.is_zero()
        return NotImplemented

    __hash__ = None  # type: ignore[assignment]

    def commutator(self, other: "DifferentialOperator") -> "DifferentialOperator":
        """``[self, other] = self*other - other*self`` as an operator."""
        return commutator(self, other)

    def hermitian(self, hbar: Any = 1) -> "DifferentialOperator":
        r"""The Hermitian form :math:`-i\hbar\,\cdot` ``self`` (eq. 141).

        ``hbar`` is a SymPy symbol/expression, a number, or a name (a positive
        symbol of that name). For the anti-Hermitian :math:`L^{ij}` of eq. (142)
        this is the physical angular momentum :math:`\mathbb L^{ij}`.
        """
        return self * (-sp.I * _hbar(hbar))

    # ------------------------------------------------------------ action
    def apply(self, f: Any) -> sp.Expr:
        """Apply to a SymPy expression ``f`` (any function of the coordinates).

        Raises ``TypeError`` for anything that is not a SymPy expression or a number.
        """
        if isinstance(f, bool) or not isinstance(f, (sp.Expr, Integral, Fraction)):
            raise TypeError(
                f"a DifferentialOperator applies to SymPy expressions, got {f!r} of type {type(f).__name__}"
            )
        return self.element.apply(f, self.coordinates)

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
        """Multiplication by the polynomial ``expr`` (order 0)."""
        coords = tuple(coordinates)
        return cls(WeylElement.multiplication(polynomial_to_dict(expr, coords), len(coords)), coords)

    def apply_to_polynomial(self, poly: Any):
        """Fast exact action on a polynomial.

        ``poly`` is a coefficient dict ``{exponent tuple: coefficient}`` (the result
        is then a dict of the same kind) or a SymPy polynomial in the coordinates
        (the result is then a SymPy expression).
        """
        if isinstance(poly, Mapping):
            return self.element.apply_to_poly(poly)
        d = polynomial_to_dict(poly, self.coordinates)
        return dict_to_polynomial(self.element.apply_to_poly(d), self.coordinates)

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


# ----------------------------------------------------------------------------
# constructors
# ----------------------------------------------------------------------------
def _plane_pair(plane: Any, N: int) -> tuple[int, int]:
    try:
        i, j = plane
    except (TypeError, ValueError):
        raise ValueError(f"a plane is a pair (i, j) of 1-based axis indices, got {plane!r}") from None
    for v in (i, j):
        if isinstance(v, bool) or not isinstance(v, (Integral, sp.Integer)):
            raise TypeError(f"plane indices must be integers, got {plane!r}")
    i, j = int(i), int(j)
    if not (1 <= i <= N and 1 <= j <= N) or i == j:
        raise ValueError(f"invalid plane {plane!r} for N = {N}: need 1 <= i, j <= {N} and i != j")
    return i, j


def angular_momentum_operator(plane: Any, N: int, hbar: Any = None, coordinates: Any = None) -> DifferentialOperator:
    r"""One generator :math:`L^{ij} = x_i\partial_j - x_j\partial_i` (eq. 142), or :math:`-i\hbar L^{ij}`.

    ``plane = (i, j)`` is 1-based; ``i > j`` is allowed and gives
    :math:`L^{ij} = -L^{ji}`. See :func:`angular_momentum_operators`.
    """
    N = check_dimension(N)
    coords = coordinate_symbols(N, coordinates)
    i, j = _plane_pair(plane, N)
    op = DifferentialOperator(WeylElement.rotation(N, i - 1, j - 1), coords)
    return op if hbar is None else op.hermitian(hbar)


def angular_momentum_operators(N: int, hbar: Any = None, coordinates: Any = None) -> dict:
    r"""The so(N) angular-momentum operators of eqs. (141)-(142), keyed by plane.

    Parameters
    ----------
    N : int
        Dimension, ``N >= 2``.
    hbar : None, SymPy expression, number or str
        ``None`` (default): the real, anti-Hermitian generators of eq. (142),
        :math:`L^{ij} = x_i\,\partial/\partial x_j - x_j\,\partial/\partial x_i`.
        Otherwise the Hermitian operators :math:`\mathbb L^{ij} = -i\hbar L^{ij}`
        of eq. (141) (a string is turned into a positive symbol of that name).
    coordinates : None, "paper" or sequence of N symbols/names
        See :func:`coordinate_symbols`; ``"paper"`` gives x, y, z, w, v for N = 5.

    Returns
    -------
    dict
        ``{(i, j): DifferentialOperator}`` for the planes ``1 <= i < j <= N`` in
        the order of :func:`hyperrotor.conventions.planes`.

    Notes
    -----
    :math:`[L_a, L_b] = \sum_c C_{ab}^{\;c} L_c` with
    :func:`hyperrotor.conventions.structure_constants` (sign ``+1``); in the
    Hermitian form :math:`[\mathbb L_a, \mathbb L_b] = -i\hbar\sum_c C_{ab}^{\;c}\mathbb L_c`
    (module docstring).

    Examples
    --------
    >>> L = angular_momentum_operators(5, coordinates="paper")
    >>> x, y, z, w, v = L[(1, 2)].coordinates
    >>> L[(1, 2)](x**2 + y)
    -2*x*y + x
    """
    N = check_dimension(N)
    coords = coordinate_symbols(N, coordinates)
    out = {}
    for i, j in planes(N):
        op = DifferentialOperator(WeylElement.rotation(N, i - 1, j - 1), coords)
        out[(i, j)] = op if hbar is None else op.hermitian(hbar)
    return out


def commutator(A: DifferentialOperator, B: DifferentialOperator) -> DifferentialOperator:
    """The commutator ``[A, B] = A B - B A`` as a :class:`DifferentialOperator` (exact)."""
    for v in (A, B):
        if not isinstance(v, DifferentialOperator):
            raise TypeError(f"commutator needs two DifferentialOperators, got {type(v).__name__}")
    A._same_space(B)
    return A._wrap(A.element.commutator(B.element))


def euler_operator(N: int, coordinates: Any = None) -> DifferentialOperator:
    r"""The Euler (degree) operator :math:`E = \sum_i x_i\,\partial_i`."""
    N = check_dimension(N)
    coords = coordinate_symbols(N, coordinates)
    e = WeylElement(N, {})
    for i in range(N):
        e = e + WeylElement.coordinate(N, i).compose(WeylElement.derivative(N, i))
    return DifferentialOperator(e, coords)


def laplacian_operator(N: int, coordinates: Any = None) -> DifferentialOperator:
    r"""The Laplacian :math:`\Delta = \sum_i \partial_i^2`."""
    N = check_dimension(N)
    coords = coordinate_symbols(N, coordinates)
    e = WeylElement(N, {})
    for i in range(N):
        d = WeylElement.derivative(N, i)
        e = e + d.compose(d)
    return DifferentialOperator(e, coords)


def multiplication_operator(poly: Any, N: int, coordinates: Any = None) -> DifferentialOperator:
    """Multiplication by a polynomial in the coordinates (e.g. ``r**2``), an operator of order 0."""
    N = check_dimension(N)
    coords = coordinate_symbols(N, coordinates)
    return DifferentialOperator.from_polynomial(poly, coords)


def casimir_operator(N: int, hbar: Any = None, coordinates: Any = None) -> DifferentialOperator:
    r"""The quadratic Casimir :math:`C_2 = \sum_{i<j} (L^{ij})^2`.

    With ``hbar=None`` (anti-Hermitian generators) the exact operator identity

    .. math:: C_2 = r^2\,\Delta - E\,(E + N - 2), \qquad r^2 = \sum_i x_i^2,
              \quad E = \sum_i x_i\partial_i

    holds, so on a harmonic homogeneous polynomial of degree ``l``
    :math:`C_2 = -l(l+N-2)`. With ``hbar`` given it is
    :math:`\sum (\mathbb L^{ij})^2 = -\hbar^2 C_2`, with eigenvalue
    :math:`\hbar^2 l(l+N-2)`.
    """
    ops = angular_momentum_operators(N, hbar=hbar, coordinates=coordinates)
    it = iter(ops.values())
    first = next(it)
    total = first * first
    for op in it:
        total = total + op * op
    return total


def textbook_so3(hbar: Any = 1, coordinates: Any = None) -> tuple:
    r"""The textbook 3D components ``(Lx, Ly, Lz)`` (Hermitian).

    :math:`L_x = \mathbb L^{23}`, :math:`L_y = \mathbb L^{31} = -\mathbb L^{13}`,
    :math:`L_z = \mathbb L^{12}` with :math:`\mathbb L^{ij} = -i\hbar(x_i\partial_j - x_j\partial_i)`;
    e.g. :math:`L_z = -i\hbar(x\partial_y - y\partial_x)`, and
    :math:`[L_x, L_y] = i\hbar L_z` (cyclic).
    """
    L = angular_momentum_operators(3, hbar=hbar, coordinates=coordinates)
    return L[(2, 3)], -L[(1, 3)], L[(1, 2)]


# ----------------------------------------------------------------------------
# operator matrices, eqs. (141), (143)-(147)
# ----------------------------------------------------------------------------
def _zero_like(op: DifferentialOperator) -> DifferentialOperator:
    return op._wrap(WeylElement(op.N, {}))


def operator_matrix(N: int, convention: str = "paper", hbar: Any = None, coordinates: Any = None) -> np.ndarray:
    r"""The antisymmetric ``N x N`` matrix of operators of eq. (143) (``hbar=None``) or eq. (141).

    Entry ``(i, j)`` (1-based, ``i < j``) is :math:`(-1)^{i+j} L^{ij}` for
    ``convention="paper"`` (the checkerboard of eqs. 21, 141, 143) and
    :math:`L^{ij}` for ``"standard"``; entry ``(j, i)`` is its negative and the
    diagonal is the zero operator. With ``hbar`` the entries are the Hermitian
    :math:`-i\hbar L^{ij}` (eq. 141).

    Returns
    -------
    numpy.ndarray of dtype object, shape ``(N, N)`` (0-based indexing), entries
    :class:`DifferentialOperator`.
    """
    check_convention(convention)
    L = angular_momentum_operators(N, hbar=hbar, coordinates=coordinates)
    N = check_dimension(N)
    M = np.empty((N, N), dtype=object)
    zero = _zero_like(next(iter(L.values())))
    for i in range(N):
        M[i, i] = zero
    for (i, j), op in L.items():
        s = (-1) ** (i + j) if convention == "paper" else 1
        M[i - 1, j - 1] = op if s == 1 else -op
        M[j - 1, i - 1] = -op if s == 1 else op
    return M


def _check_operator_matrix(A: Any, name: str) -> np.ndarray:
    A = np.asarray(A, dtype=object)
    if A.ndim != 2 or A.shape[0] != A.shape[1] or A.shape[0] < 2:
        raise ValueError(f"{name} must be a square N x N matrix of operators, got shape {A.shape}")
    for v in A.flat:
        if not isinstance(v, DifferentialOperator):
            raise TypeError(f"{name} must contain DifferentialOperators, found {type(v).__name__}")
    return A


_FORMS = ("eq144", "antisymmetrized")


def operator_product(A: Any, B: Any, form: str = "eq144") -> np.ndarray:
    r"""The product of two operator matrices of eq. (144) (corrected), or its antisymmetrized variant.

    Parameters
    ----------
    A, B : N x N object arrays of :class:`DifferentialOperator` (e.g. :func:`operator_matrix`).
    form : {"eq144", "antisymmetrized"}
        ``"eq144"`` (default): the operator version of eq. (25), entry by entry

        .. math:: P_{ij} = \sum_k \bigl(A_{kj}\circ B_{ik} - A_{ik}\circ B_{kj}\bigr),

        the ``A`` factor always written (and composed) on the **left**, as in the
        printed eq. (144). For commuting entries this is :math:`(BA - AB)_{ij}`,
        the :math:`\omega L - L\omega` of eq. (24) with :math:`L \to A`,
        :math:`\omega \to B`.

        ``"antisymmetrized"``: :math:`Q_{ij} = (AB)_{ij} - (AB)_{ji}
        = \sum_k \bigl(A_{ik}\circ B_{kj} - A_{jk}\circ B_{ki}\bigr)` (ordinary
        matrix product, ``A`` entries composed on the left, minus its
        transpose). For antisymmetric ``A``, ``B`` one has exactly ``Q = -P``.

    Returns
    -------
    numpy.ndarray (object) of second-order operators (first order when the
    second-order parts cancel, as in :func:`contraction_identity`).

    Notes
    -----
    Printed eq. (144) is eq. (25) with :math:`L \to \mathbb L`, :math:`\omega \to \Omega`
    and copies its typos. Its reversed labels (:math:`\Omega^{31}`, :math:`\Omega^{21}`,
    :math:`\mathbb L^{31}`) must be read as the *same* components as
    :math:`\Omega^{13}`, :math:`\Omega^{12}`, :math:`\mathbb L^{13}` (not their
    negatives; eq. (28) fixes this sign). With that reading seven of the ten
    entries are right and three carry index typos:

    * :math:`\mathbb L\Omega^{12}`: printed :math:`\mathbb L^{24}\Omega^{34} + \mathbb L^{25}\Omega^{35}`,
      correct :math:`\mathbb L^{24}\Omega^{14} + \mathbb L^{25}\Omega^{15}`, i.e.

      .. math:: -\mathbb L^{13}\Omega^{23} - \mathbb L^{14}\Omega^{24} - \mathbb L^{15}\Omega^{25}
                + \mathbb L^{23}\Omega^{13} + \mathbb L^{24}\Omega^{14} + \mathbb L^{25}\Omega^{15};

    * :math:`\mathbb L\Omega^{25}`: printed :math:`+\mathbb L^{35}\Omega^{21}`, correct
      :math:`+\mathbb L^{15}\Omega^{12}`;
    * :math:`\mathbb L\Omega^{45}`: printed :math:`-\mathbb L^{13}\Omega^{15}`, correct
      :math:`-\mathbb L^{14}\Omega^{15}`.

    The same three typos are in eq. (25). For operators the order of the
    factors matters; the printed order (``A`` left) is kept here, see
    :func:`contraction_identity` for what it implies for eqs. (145)-(147).
    """
    if form not in _FORMS:
        raise ValueError(f"unknown form {form!r}; allowed: {', '.join(map(repr, _FORMS))}")
    A = _check_operator_matrix(A, "A")
    B = _check_operator_matrix(B, "B")
    if A.shape != B.shape:
        raise ValueError(f"A and B have different shapes {A.shape} and {B.shape}")
    A[0, 0]._same_space(B[0, 0])
    N = A.shape[0]
    out = np.empty((N, N), dtype=object)
    for i in range(N):
        for j in range(N):
            acc = A[0, 0]._wrap(WeylElement(A[0, 0].N, {}))
            for k in range(N):
                if form == "eq144":
                    acc = acc + A[k, j] * B[i, k] - A[i, k] * B[k, j]
                else:
                    acc = acc + A[i, k] * B[k, j] - A[j, k] * B[k, i]
            out[i, j] = acc
    return out


ContractionIdentity = namedtuple("ContractionIdentity", ["factor", "holds", "product", "matrix", "definition"])
ContractionIdentity.__doc__ = """Result of :func:`contraction_identity`.

factor : sympy.Rational, the ``c`` with ``product == c * matrix`` (entrywise, exact)
holds : bool, whether every entry satisfies it exactly
product : the operator matrix computed from the definition
matrix : the operator matrix of eq. (143)
definition : str, the definition used
"""


def contraction_identity(N: int, convention: str = "paper", form: str = "antisymmetrized",
                         transpose: bool = True, coordinates: Any = None) -> ContractionIdentity:
    r"""Compute and verify the contraction identities of eqs. (145)-(147) for any N.

    With :math:`\mathbb L` the operator matrix of eq. (143) and
    :math:`\Omega = \mathbb L^{\mathsf T}`, the **antisymmetrized** product

    .. math:: (\mathbb L\,\Omega)_{ij} - (\mathbb L\,\Omega)_{ji}
              = \sum_k \bigl(\mathbb L_{ik}\circ\Omega_{kj} - \mathbb L_{jk}\circ\Omega_{ki}\bigr)
              = \sum_k [\mathbb L_{ik}, \mathbb L_{jk}] = -(N-2)\,\mathbb L_{ij}

    (matrix entries, :math:`\mathbb L` factor composed on the left, the second
    factor transposed, summed over the middle index ``k``): ``-L`` in 3D
    (eq. 147), ``-2L`` in 4D (eq. 146), ``-3L`` in 5D (eq. 145). The second-order
    parts cancel, which is the paper's "shortening of the second-order powers".
    Proof: for ``k != i, j``, :math:`[L^{ik}, L^{kj}] = L^{ij}` (commutation
    relations), so :math:`\sum_k [L^{ik}, L^{kj}] = (N-2) L^{ij}`; the checkerboard
    signs factor out as :math:`(-1)^{i+j}` (they are a conjugation), so the
    identity holds in both conventions.

    With the eq. (144)/(25) pattern (``form="eq144"``, :func:`operator_product`,
    ``A`` composed on the left) the same contraction gives ``+(N-2) L`` for
    :math:`\Omega = \mathbb L^{\mathsf T}` and ``-(N-2) L`` for
    :math:`\Omega = \mathbb L` (``transpose=False``).

    Relation to :math:`\mathbf L\times\mathbf L = i\hbar\mathbf L`: for the Hermitian
    :math:`-i\hbar L^{ij}` (eq. 141) the same contraction gives
    :math:`\sum_k[\mathbb L_{ik}, \mathbb L_{jk}] = i\hbar(N-2)\,\mathbb L_{ij}`; in 3D
    with :math:`L_x = \mathbb L^{23}`, :math:`L_y = \mathbb L^{31}`, :math:`L_z = \mathbb L^{12}`
    the (1,2) entry reads :math:`[L_x, L_y] = i\hbar L_z`, i.e. the z component of
    :math:`\mathbf L\times\mathbf L = \tfrac12\epsilon_{zab}[L_a, L_b] = i\hbar L_z`.
    Eqs. (145)-(147) hold for the real operators of eq. (142)/(143), not for the
    :math:`-i\hbar`-scaled matrix of eq. (141) (there the factor is :math:`i\hbar(N-2)`).

    Returns
    -------
    ContractionIdentity
        ``factor`` is computed (not assumed) from the (1, 2) entries; ``holds``
        says whether ``product == factor * matrix`` exactly in every entry.
    """
    M = operator_matrix(N, convention=convention, coordinates=coordinates)
    Om = M.T.copy() if transpose else M.copy()
    P = operator_product(M, Om, form=form)
    # factor from entry (0, 1): compare the coefficient of one term
    ref = M[0, 1].element.terms
    key, cref = next(iter(ref.items()))
    got = P[0, 1].element.terms.get(key, 0)
    factor = sp.Rational(_to_sympy_scalar(Fraction(got) / Fraction(cref))) if not isinstance(got, sp.Basic) else got / cref
    holds = all(P[i, j] == M[i, j] * factor for i in range(M.shape[0]) for j in range(M.shape[0]))
    tname = "L^T" if transpose else "L"
    if form == "antisymmetrized":
        definition = f"(L Omega)_ij - (L Omega)_ji = sum_k (L_ik o Omega_kj - L_jk o Omega_ki), Omega = {tname}"
    else:
        definition = f"sum_k (L_kj o Omega_ik - L_ik o Omega_kj)  [eq. 144 pattern], Omega = {tname}"
    return ContractionIdentity(factor, bool(holds), P, M, definition)
