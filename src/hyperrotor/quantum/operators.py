r"""Quantum angular-momentum operators of so(N) as exact SymPy differential operators.

The paper's Section 5 (eqs. 141-147) in any dimension ``N >= 2``.

Two forms of the generators
---------------------------
* **Anti-Hermitian (real) form, eq. (142)**: the vector fields

  .. math:: L^{ij} = x_i\,\partial_j - x_j\,\partial_i, \qquad 1 \le i < j \le N,

  returned by :func:`angular_momentum_operators` with ``form="antihermitian"``
  (the default). They obey

  .. math:: [L^{ij}, L^{kl}] = \delta_{jk} L^{il} - \delta_{ik} L^{jl}
            - \delta_{jl} L^{ik} + \delta_{il} L^{jk},

  i.e. :math:`[L_a, L_b] = \sum_c C_{ab}^{\;c} L_c` with **exactly** the
  structure constants :func:`hyperrotor.conventions.structure_constants` (overall
  sign ``+1``): ``L^{ij}`` is the image of the matrix
  :math:`E_{(ij)} = e_i e_j^{\mathsf T} - e_j e_i^{\mathsf T}` under the Lie-algebra
  homomorphism :math:`M \mapsto -\sum_{ab} M_{ab}\, x_b\, \partial_a`.
* **Hermitian (physics) form, eq. (141)**: :math:`\mathbb L^{ij} = -i\hbar\,L^{ij}`
  (``form="hermitian"`` with keyword-only ``hbar``, default 1, a number or a
  SymPy symbol; or :meth:`DifferentialOperator.as_form`), with

  .. math:: [\mathbb L^{ij}, \mathbb L^{kl}] = i\hbar\,(\delta_{ik}\mathbb L^{jl}
            + \delta_{jl}\mathbb L^{ik} - \delta_{il}\mathbb L^{jk}
            - \delta_{jk}\mathbb L^{il})
            = -i\hbar \sum_c C_{ab}^{\;c}\,\mathbb L_c .

  In 3D, with :math:`L_x = \mathbb L^{23}`, :math:`L_y = \mathbb L^{31} = -\mathbb L^{13}`,
  :math:`L_z = \mathbb L^{12}` (:func:`textbook_so3`), these are the textbook
  :math:`L_x = y p_z - z p_y`, ... with :math:`p = -i\hbar\nabla` and
  :math:`[L_x, L_y] = i\hbar L_z` (cyclic).

Operators are :class:`~hyperrotor.quantum.differential_operator.DifferentialOperator`
objects (:mod:`hyperrotor.quantum.differential_operator`: the class, its algebra and
its coordinate symbols) wrapping the exact normal form
:class:`hyperrotor.quantum.normal_form.WeylElement`; equality ``A == B`` is an exact
operator identity. They act on the coordinate symbols *by name* (``coordinates=``,
:func:`~hyperrotor.quantum.differential_operator.coordinate_symbols`).

Paper material
--------------
The operator product of eq. (144) (with its three index typos) and the
contraction identities of eqs. (145)-(147) are in
:mod:`hyperrotor.quantum.operator_products` (``operator_product``,
``contraction_identity``), which :mod:`hyperrotor.paper` uses to check the
print; nothing in :mod:`hyperrotor.quantum` imports :mod:`hyperrotor.paper`.
"""
from __future__ import annotations

from numbers import Integral
from typing import Any

import numpy as np
import sympy as sp

from .. import _pricing
from ..conventions import check_convention, check_dimension, planes
from .differential_operator import DifferentialOperator, coordinate_symbols
from .normal_form import WeylElement

__all__ = [
    "angular_momentum_operators",
    "angular_momentum_operator",
    "commutator",
    "euler_operator",
    "laplacian_operator",
    "multiplication_operator",
    "casimir_operator",
    "textbook_so3",
    "operator_matrix",
]


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


def angular_momentum_operator(plane: Any, N: int, *, form: str = "antihermitian", hbar: Any = 1,
                              coordinates: Any = None) -> DifferentialOperator:
    r"""One generator :math:`L^{ij} = x_i\partial_j - x_j\partial_i` (eq. 142), or :math:`-i\hbar L^{ij}`.

    ``plane = (i, j)`` is 1-based; ``i > j`` is allowed and gives
    :math:`L^{ij} = -L^{ji}`. See :func:`angular_momentum_operators`.

    Examples
    --------
    >>> x1, x2, x3 = sp.symbols("x1:4")        # no assumptions: still the coordinates
    >>> angular_momentum_operator((1, 2), 3)(x1 * x2)
    x1**2 - x2**2
    """
    N = check_dimension(N)
    coords = coordinate_symbols(N, coordinates)
    i, j = _plane_pair(plane, N)
    op = DifferentialOperator(WeylElement.rotation(N, i - 1, j - 1), coords)
    return op.as_form(form, hbar=hbar)


def angular_momentum_operators(N: int, *, form: str = "antihermitian", hbar: Any = 1,
                               coordinates: Any = None) -> dict:
    r"""The so(N) angular-momentum operators of eqs. (141)-(142), keyed by plane.

    Parameters
    ----------
    N : int
        Dimension, ``N >= 2``.
    form : {"antihermitian", "hermitian"}, keyword-only
        ``"antihermitian"`` (default): the real generators of eq. (142),
        :math:`L^{ij} = x_i\,\partial/\partial x_j - x_j\,\partial/\partial x_i`;
        ``"hermitian"``: :math:`\mathbb L^{ij} = -i\hbar L^{ij}` of eq. (141).
    hbar : positive number or SymPy expression, keyword-only, default 1 (exact)
        Used by ``form="hermitian"``; with the anti-Hermitian form any value
        other than 1 is refused (it would be ignored). Text (``"hbar"``) is
        refused with ``TypeError``: pass ``sympy.Symbol("hbar", positive=True)``.
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
    _pricing.check("angular_momentum_operators", N=N)
    coords = coordinate_symbols(N, coordinates)
    out = {}
    for i, j in planes(N):
        op = DifferentialOperator(WeylElement.rotation(N, i - 1, j - 1), coords)
        out[(i, j)] = op.as_form(form, hbar=hbar)
    return out


def commutator(A: DifferentialOperator, B: DifferentialOperator) -> DifferentialOperator:
    """The commutator ``[A, B] = A B - B A`` as a :class:`DifferentialOperator` (exact)."""
    for v in (A, B):
        if not isinstance(v, DifferentialOperator):
            raise TypeError(f"commutator needs two DifferentialOperators, got {type(v).__name__}")
    return A.commutator(B)


def _axis_sum(N: int, coordinates: Any, term) -> DifferentialOperator:
    r""":math:`\sum_i` ``term(N, i)`` over the N axes (``term`` gives a WeylElement), on the coordinates."""
    N = check_dimension(N)
    coords = coordinate_symbols(N, coordinates)
    e = WeylElement(N, {})
    for i in range(N):
        e = e + term(N, i)
    return DifferentialOperator(e, coords)


def euler_operator(N: int, coordinates: Any = None) -> DifferentialOperator:
    r"""The Euler (degree) operator :math:`E = \sum_i x_i\,\partial_i`."""
    return _axis_sum(N, coordinates, lambda n, i: WeylElement.coordinate(n, i).compose(WeylElement.derivative(n, i)))


def laplacian_operator(N: int, coordinates: Any = None) -> DifferentialOperator:
    r"""The Laplacian :math:`\Delta = \sum_i \partial_i^2`."""
    return _axis_sum(N, coordinates, lambda n, i: WeylElement.derivative(n, i).compose(WeylElement.derivative(n, i)))


def multiplication_operator(poly: Any, N: int, coordinates: Any = None) -> DifferentialOperator:
    """Multiplication by a polynomial in the coordinates (e.g. ``r**2``), an operator of order 0."""
    N = check_dimension(N)
    coords = coordinate_symbols(N, coordinates)
    return DifferentialOperator.from_polynomial(poly, coords)


def casimir_operator(N: int, *, form: str = "antihermitian", hbar: Any = 1,
                     coordinates: Any = None) -> DifferentialOperator:
    r"""The quadratic Casimir :math:`C_2 = \sum_{i<j} (L^{ij})^2`.

    With ``form="antihermitian"`` (default) the exact operator identity

    .. math:: C_2 = r^2\,\Delta - E\,(E + N - 2), \qquad r^2 = \sum_i x_i^2,
              \quad E = \sum_i x_i\partial_i

    holds, so on a harmonic homogeneous polynomial of degree ``l``
    :math:`C_2 = -l(l+N-2)`. With ``form="hermitian"`` it is
    :math:`\sum (\mathbb L^{ij})^2 = -\hbar^2 C_2`, with eigenvalue
    :math:`\hbar^2 l(l+N-2)`.
    """
    _pricing.check("casimir_operator", N=check_dimension(N))
    ops = angular_momentum_operators(N, form=form, hbar=hbar, coordinates=coordinates)
    it = iter(ops.values())
    first = next(it)
    total = first * first
    for op in it:
        total = total + op * op
    return total


def textbook_so3(*, hbar: Any = 1, coordinates: Any = None) -> tuple:
    r"""The textbook 3D components ``(Lx, Ly, Lz)`` (Hermitian).

    :math:`L_x = \mathbb L^{23}`, :math:`L_y = \mathbb L^{31} = -\mathbb L^{13}`,
    :math:`L_z = \mathbb L^{12}` with :math:`\mathbb L^{ij} = -i\hbar(x_i\partial_j - x_j\partial_i)`;
    e.g. :math:`L_z = -i\hbar(x\partial_y - y\partial_x)`, and
    :math:`[L_x, L_y] = i\hbar L_z` (cyclic).
    """
    L = angular_momentum_operators(3, form="hermitian", hbar=hbar, coordinates=coordinates)
    return L[(2, 3)], -L[(1, 3)], L[(1, 2)]


# ----------------------------------------------------------------------------
# operator matrices, eqs. (141), (143)-(147)
# ----------------------------------------------------------------------------
def _zero_like(op: DifferentialOperator) -> DifferentialOperator:
    return DifferentialOperator(WeylElement(op.N, {}), op.coordinates)


def operator_matrix(N: int, *, convention: str = "paper", form: str = "antihermitian", hbar: Any = 1,
                    coordinates: Any = None) -> np.ndarray:
    r"""The antisymmetric ``N x N`` matrix of operators of eq. (143) (``form="antihermitian"``) or eq. (141).

    Entry ``(i, j)`` (1-based, ``i < j``) is :math:`(-1)^{i+j} L^{ij}` for
    ``convention="paper"`` (the checkerboard of eqs. 21, 141, 143) and
    :math:`L^{ij}` for ``"standard"``; entry ``(j, i)`` is its negative and the
    diagonal is the zero operator. With ``form="hermitian"`` the entries are the
    Hermitian :math:`-i\hbar L^{ij}` (eq. 141).

    Returns
    -------
    numpy.ndarray of dtype object, shape ``(N, N)`` (0-based indexing), entries
    :class:`DifferentialOperator`.
    """
    check_convention(convention)
    L = angular_momentum_operators(N, form=form, hbar=hbar, coordinates=coordinates)
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
