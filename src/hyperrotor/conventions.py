r"""so(N) conventions shared by the classical and the quantum halves of hyperrotor.

This module is the single place where plane labels, the order of plane
components, the matrix sign conventions and the so(N) structure constants are
defined. Everything else in the package imports them from here.

Plane labels and component order
--------------------------------
A rotation plane is labelled by a 1-based pair ``(i, j)`` with ``i < j``.
Planes are ordered lexicographically, which for ``N = 5`` is the paper's order
of eq. (8): 12, 13, 14, 15, 23, 24, 25, 34, 35, 45. A *component vector* of a
bivector (angular velocity :math:`\omega_{ij}`, angular momentum :math:`L^{ij}`,
torque, a Lie-algebra element) always lists its ``N(N-1)/2`` components in
that order.

Matrix conventions
------------------
``convention="paper"``
    The checkerboard sign pattern of eq. (21): the matrix entry ``(i, j)``,
    ``i < j``, is :math:`(-1)^{i+j}\,\omega_{ij}`; entry ``(j, i)`` is its
    negative. The paper writes the dynamics as :math:`\dot L = \omega L - L\omega`
    (eq. 24) with ``L`` carrying the same pattern (eq. 22).
``convention="standard"``
    The plain antisymmetric matrix: entry ``(i, j)``, ``i < j``, is
    :math:`\omega_{ij}`.

The exact maps between them (the one place they are documented)
---------------------------------------------------------------
* **Matrices.** With :math:`S = \mathrm{diag}((-1)^1, (-1)^2, \dots, (-1)^N)`,
  :math:`\Omega_\text{paper} = S\,\Omega_\text{standard}\,S`. ``S`` is a constant
  orthogonal matrix, so conjugation by it is a Lie-algebra automorphism:
  commutators, characteristic polynomials and traces of products are the same
  in both conventions.
* **Components.** The component vectors are *identical* in the two
  conventions, and so are the structure constants: a non-zero structure constant
  :math:`C_{(ij),(jk)}^{(ik)}` involves three planes whose sign factors multiply
  to :math:`(-1)^{2(i+j+k)} = 1`. Consequently the Euler equations for the
  components, :math:`\dot L^{ij} = [\Omega, L]^{ij}`, are the same ODEs in both
  conventions; only matrix forms (and the paper's way of printing each equation
  as a matrix entry, see :meth:`hyperrotor.RigidBody.euler_equations`) differ.
* **Textbook 3D.** Under the map :math:`W_k = \tfrac12 \epsilon_{kij}\,\omega_{ij}`,
  i.e. :math:`W_1 = \omega_{23}`, :math:`W_2 = \omega_{31} = -\omega_{13}`,
  :math:`W_3 = \omega_{12}` (and the same for :math:`M_k` from :math:`L^{ij}`,
  with :math:`I_1 = I_{23}`, :math:`I_2 = I_{13}`, :math:`I_3 = I_{12}`), the
  equations :math:`\dot L = [\Omega, L]` become the textbook body-frame Euler
  equations :math:`I_1 \dot W_1 = (I_2 - I_3) W_2 W_3` (and cyclic), i.e.
  :math:`\dot{\mathbf M} = \mathbf M \times \mathbf W`. With that map the plain
  matrix is :math:`-\hat W` (minus the usual hat map
  :math:`\hat W_{ij} = -\epsilon_{ijk} W_k`); with the opposite map
  :math:`W_k = -\tfrac12\epsilon_{kij}\omega_{ij}` the same component
  equations would describe the time-reversed motion.
* **Attitude.** The body attitude ``T(t)`` (eq. 19) maps space-frame to
  body-frame components, :math:`L_\text{body} = T L_\text{space} T^{\mathsf T}`,
  and obeys :math:`\dot T = \Omega\,T` with :math:`\Omega` the matrix of the
  chosen convention; :math:`T_\text{paper} = S\,T_\text{standard}\,S`. The
  body-to-space rotation of textbooks is :math:`R = T^{\mathsf T}` with
  :math:`\dot R = R\,\hat W`.
* **Lie-Poisson bracket.** :func:`lie_poisson_bracket` is
  :math:`\{F, G\}(L) = \sum_{abc} C_{ab}^{\;c}\, L_c\, \partial_a F\, \partial_b G`,
  for which :math:`\dot F = \{F, H\}` with :math:`H = \sum L_a^2/(2 I_a)` is
  exactly :math:`\dot L = [\Omega, L]`. In 3D under the map above,
  :math:`\{M_i, M_j\} = -\epsilon_{ijk} M_k`, the textbook body-frame bracket.
* **Quantum.** The anti-Hermitian generators are the real antisymmetric
  differential operators :math:`L^{ij} = x_i\partial_j - x_j\partial_i`
  (eq. 142); the Hermitian form is :math:`-i\hbar L^{ij}` (eq. 141), ``hbar``
  defaulting to 1.
"""
from __future__ import annotations

from collections.abc import Mapping
from functools import lru_cache
from typing import Any, Iterable, Sequence

import numpy as np

from . import _lazy, _parse, _pricing, _validate
from ._lazy import sympy as sp  # SymPy is imported on first symbolic use (light ``import hyperrotor``)

__all__ = [
    "CONVENTIONS",
    "planes",
    "n_planes",
    "dimension_from_count",
    "plane_index",
    "plane_label",
    "plane_signs",
    "basis_matrix",
    "to_matrix",
    "to_components",
    "structure_constants",
    "lie_bracket",
    "lie_poisson_bracket",
    "bivector_product_table",
    "plane_symbols",
]

#: The allowed values of every ``convention=`` keyword for matrices.
CONVENTIONS = _validate.CONVENTIONS


# ----------------------------------------------------------------------------
# validation helpers (re-used by the rest of the package)
# ----------------------------------------------------------------------------
def check_dimension(N: Any, *, minimum: int = 2, name: str = "N") -> int:
    """Return ``N`` as ``int`` or raise a ``TypeError``/``ValueError`` naming it.

    ``N`` must be an integer ``>= minimum`` and may not exceed ``options["max_dimension"]``
    (1000): a larger N would hang or exhaust memory in the plane tables instead of failing
    with a message.
    """
    return _validate.dimension(N, minimum=minimum, name=name)


def check_convention(convention: Any) -> str:
    """Return ``convention`` if it is one of :data:`CONVENTIONS`, else raise ``ValueError``."""
    return _validate.convention(convention)


# ----------------------------------------------------------------------------
# plane labels
# ----------------------------------------------------------------------------
def planes(N: int) -> tuple[tuple[int, int], ...]:
    """The 1-based plane labels ``(i, j)``, ``i < j``, of so(N) in paper order.

    The order is lexicographic; for ``N = 5`` it is the order of eq. (8):
    ``(1,2), (1,3), (1,4), (1,5), (2,3), (2,4), (2,5), (3,4), (3,5), (4,5)``.

    Examples
    --------
    >>> planes(3)
    ((1, 2), (1, 3), (2, 3))
    """
    return _validate.plane_table(check_dimension(N))


def n_planes(N: int) -> int:
    """Number of rotation planes ``N(N-1)/2`` (eq. 2)."""
    N = check_dimension(N)
    return N * (N - 1) // 2


def dimension_from_count(count: int) -> int:
    """Infer ``N`` from a number of plane components ``N(N-1)/2``.

    Raises ``ValueError`` when ``count`` is not of that form (1, 3, 6, 10, 15, ...).
    """
    return _validate.dimension_from_count(_validate.integer("count", count, minimum=0))


@lru_cache(maxsize=None)
def _plane_index_table(N: int) -> dict[tuple[int, int], int]:
    return {p: k for k, p in enumerate(_validate.plane_table(N))}


def plane_index(plane: Sequence[int], N: int) -> int:
    """0-based position of ``plane = (i, j)`` in the component order of so(N).

    Raises ``ValueError`` for a label that is not a plane of so(N) (``i >= j``,
    an index outside ``1..N``, or not a pair).
    """
    N = check_dimension(N)
    if isinstance(plane, tuple) and len(plane) == 2 and type(plane[0]) is int and type(plane[1]) is int:
        hit = _plane_index_table(N).get(plane)  # fast path for the common exact label
        if hit is not None:
            return hit
    return _plane_index_table(N)[_validate.plane(plane, N)]


def plane_label(plane: Sequence[int], N: int | None = None) -> str:
    """A compact label ``"12"`` (``"1,10"`` when an index has two digits)."""
    if N is not None:
        N = check_dimension(N)
    i, j = _validate.plane(plane, N)
    sep = "," if max(i, j) > 9 or (N is not None and N > 9) else ""
    return f"{i}{sep}{j}"


def function_argument(function_of: Any) -> Any:
    """The argument of symbolic functions ``w_ij(function_of)``: ``None``, a SymPy object, a number, or text read
    by :func:`hyperrotor._parse.expression` (``"t"``). ``sympy.Function(...)("...")`` would ``sympify`` -- run --
    the text."""
    return None if function_of is None else _parse.to_sympy(function_of, "function_of")


def plane_symbols(name: str, N: int, *, function_of: sp.Symbol | None = None, **assumptions) -> tuple:
    """SymPy symbols (or functions of ``function_of``) ``name_ij``, one per plane, in plane order.

    Symbols are named ``f"{name}_{i}{j}"`` (``f"{name}_{i},{j}"`` for N >= 10), so the
    same name always gives the same symbol throughout the package.
    """
    if not isinstance(name, str) or not name.isidentifier():
        raise TypeError(f"name must be a non-empty identifier string such as 'w' or 'L', got {_validate.fmt(name)}")
    _pricing.check("plane_symbols", N=check_dimension(N))
    function_of = function_argument(function_of)
    out = []
    for p in planes(N):
        label = f"{name}_{plane_label(p, N)}"
        if function_of is None:
            out.append(sp.Symbol(label, **assumptions))
        else:
            out.append(sp.Function(label, **assumptions)(function_of))
    return tuple(out)


def plane_signs(N: int, *, convention: str = "paper") -> np.ndarray:
    """Sign of the ``(i, j)`` matrix entry relative to the component, per plane.

    ``(-1)**(i + j)`` for ``"paper"`` (eq. 21), ``+1`` for ``"standard"``.
    """
    check_convention(convention)
    ps = planes(N)
    if convention == "standard":
        return np.ones(len(ps), dtype=int)
    return np.array([(-1) ** (i + j) for i, j in ps], dtype=int)


# ----------------------------------------------------------------------------
# matrices <-> components
# ----------------------------------------------------------------------------
def is_symbolic(x: Any) -> bool:
    """True when ``x`` holds SymPy objects (the symbolic path of the package's dual numpy/SymPy functions).

    Never imports SymPy: if it has not been imported yet, ``x`` cannot hold SymPy objects.
    """
    if not _lazy.loaded("sympy"):
        return False
    if isinstance(x, (sp.Basic, sp.MatrixBase)):
        return True
    if isinstance(x, np.ndarray):
        return x.dtype == object and any(isinstance(v, sp.Basic) for v in x.flat)
    if isinstance(x, (list, tuple)):
        return any(is_symbolic(v) for v in x)
    return False


def _sympy_matrix(name: str, value: Any, *, column: bool = False):
    """``value`` (a SymPy matrix, or a nested sequence/array holding SymPy objects and numbers)
    as a ``sympy.Matrix``, each entry through :func:`hyperrotor._parse.to_sympy` with text
    refused (``sympy.Matrix`` would ``sympify`` -- evaluate -- a string entry)."""
    if isinstance(value, sp.MatrixBase):
        return sp.Matrix(value)
    arr = np.asarray(value, dtype=object)
    entries = [_parse.to_sympy(v, name, text=False) for v in arr.flat]
    if column or arr.ndim < 2:
        return sp.Matrix(entries)
    return sp.Matrix(arr.shape[0], int(np.prod(arr.shape[1:])), entries)


def basis_matrix(plane: Sequence[int], N: int, *, convention: str = "paper") -> np.ndarray:
    """The so(N) basis element of ``plane`` as an integer ``N x N`` matrix.

    ``to_matrix`` of the unit component vector of ``plane``: for ``"standard"``
    :math:`E_{(ij)} = e_i e_j^{\\mathsf T} - e_j e_i^{\\mathsf T}`; for ``"paper"``
    :math:`(-1)^{i+j} E_{(ij)}`.
    """
    check_convention(convention)
    N = check_dimension(N)
    i, j = _validate.plane(plane, N)  # (the pair as read: text "12" and "1,2" too, as plane_index reads them)
    k = plane_index((i, j), N)
    s = int(plane_signs(N, convention=convention)[k])
    E = np.zeros((N, N), dtype=int)
    E[i - 1, j - 1] = s
    E[j - 1, i - 1] = -s
    return E


def to_matrix(components: Any, *, convention: str = "paper"):
    """Antisymmetric ``N x N`` matrix of a vector of plane components.

    Parameters
    ----------
    components : array_like or sympy sequence
        ``N(N-1)/2`` components in plane order (last axis). NumPy input may carry
        leading batch axes; the result then has shape ``(..., N, N)``. SymPy
        input (a list/tuple/Matrix containing SymPy expressions) gives a
        ``sympy.Matrix``.
    convention : {"paper", "standard"}
        ``"paper"``: entry ``(i, j)``, ``i < j``, is ``(-1)**(i+j) * w_ij``
        (eq. 21); ``"standard"``: entry ``(i, j)`` is ``w_ij``.

    Examples
    --------
    >>> to_matrix([1, 2, 3], convention="standard")
    array([[ 0,  1,  2],
           [-1,  0,  3],
           [-2, -3,  0]])
    >>> to_matrix([1, 2, 3])          # paper: checkerboard signs of eq. (21)
    array([[ 0, -1,  2],
           [ 1,  0, -3],
           [-2,  3,  0]])
    """
    check_convention(convention)
    if is_symbolic(components):
        comps = list(_sympy_matrix("components", components, column=True))
        N = dimension_from_count(len(comps))
        signs = plane_signs(N, convention=convention)
        M = sp.zeros(N, N)
        for (i, j), s, c in zip(planes(N), signs, comps):
            M[i - 1, j - 1] = int(s) * c
            M[j - 1, i - 1] = -int(s) * c
        return M
    arr = _validate.exact_or_float_array("components", components, what="numeric array (or SymPy expressions)")
    if arr.ndim == 0:
        raise ValueError(f"components must be a sequence of N(N-1)/2 numbers, got the scalar {components!r}")
    N = dimension_from_count(arr.shape[-1])
    signs = plane_signs(N, convention=convention)
    iu = np.array(planes(N)) - 1
    M = np.zeros(arr.shape[:-1] + (N, N), dtype=np.result_type(arr.dtype, np.int8))
    M[..., iu[:, 0], iu[:, 1]] = arr * signs
    M[..., iu[:, 1], iu[:, 0]] = -arr * signs
    return M


def to_components(matrix: Any, *, convention: str = "paper", atol: float | None = None):
    """Plane components (plane order) of an antisymmetric matrix; inverse of :func:`to_matrix`.

    Parameters
    ----------
    matrix : array_like (..., N, N) or sympy.Matrix
        Must be antisymmetric. NumPy input may carry leading batch axes.
    convention : {"paper", "standard"}
    atol : float, optional
        Tolerance of the antisymmetry check for floating input
        (default ``1e-12 * max(1, max|M|)``). SymPy input must be exactly
        antisymmetric (checked with ``simplify``).

    Returns
    -------
    numpy.ndarray of shape ``(..., N(N-1)/2)``, or a ``sympy.Matrix`` column
    for SymPy input.
    """
    check_convention(convention)
    if is_symbolic(matrix):
        M = _sympy_matrix("matrix", matrix)
        if M.rows != M.cols or M.rows < 2:
            raise ValueError(f"expected a square N x N matrix with N >= 2, got shape {M.shape}")
        N = M.rows
        bad = [(i + 1, j + 1) for i in range(N) for j in range(i, N) if sp.simplify(M[i, j] + M[j, i]) != 0]
        if bad:
            raise ValueError(f"matrix is not antisymmetric: M + M^T != 0 at 1-based entries {bad[:5]}")
        signs = plane_signs(N, convention=convention)
        return sp.Matrix([int(s) * M[i - 1, j - 1] for (i, j), s in zip(planes(N), signs)])
    arr = _validate.exact_or_float_array("matrix", matrix, what="numeric matrix (or a SymPy matrix)")
    if arr.ndim < 2 or arr.shape[-1] != arr.shape[-2] or arr.shape[-1] < 2:
        raise ValueError(f"matrix must be an array of shape (..., N, N) with N >= 2, got shape {arr.shape}")
    N = arr.shape[-1]
    asym = np.abs(arr + np.swapaxes(arr, -1, -2))
    atol = _validate.positive("atol", atol, allow_none=True, allow_zero=True)
    if arr.dtype.kind in "fc":
        tol = atol if atol is not None else 1e-12 * max(1.0, float(np.max(np.abs(arr), initial=0.0)))
    else:
        tol = 0 if atol is None else atol
    if np.any(asym > tol):
        worst = np.unravel_index(int(np.argmax(asym)), asym.shape)
        raise ValueError(
            f"matrix is not antisymmetric: |M + M^T| = {float(asym[worst]):.3g} > {tol:.3g} "
            f"at index {tuple(int(v) for v in worst)}"
        )
    iu = np.array(planes(N)) - 1
    return arr[..., iu[:, 0], iu[:, 1]] * plane_signs(N, convention=convention)


# ----------------------------------------------------------------------------
# structure constants, brackets
# ----------------------------------------------------------------------------
@lru_cache(maxsize=None)
def _structure_constants(N: int) -> np.ndarray:
    idx = _plane_index_table(N)
    n = len(idx)
    C = np.zeros((n, n, n), dtype=np.int8)

    for (i, j), a in idx.items():
        for (k, l), b in idx.items():
            for c, s in _bracket_terms(N, (i, j), (k, l)):
                C[a, b, c] += s
    C.setflags(write=False)
    return C


def _bracket_terms(N: int, first: tuple[int, int], second: tuple[int, int]):
    r"""``(c, coefficient)`` of the plane components of :math:`[E_{\text{first}}, E_{\text{second}}]`:
    :math:`[E_{ij}, E_{kl}] = \delta_{jk} E_{il} - \delta_{ik} E_{jl} - \delta_{jl} E_{ik} + \delta_{il} E_{jk}`
    with :math:`E_{ba} = -E_{ab}` (1-based planes ``i < j``, ``k < l``)."""
    (i, j), (k, l) = first, second
    for cond, (p, q), s in ((j == k, (i, l), 1), (i == k, (j, l), -1), (j == l, (i, k), -1), (i == l, (j, k), 1)):
        if cond and p != q:
            a, b, sign = (p, q, s) if p < q else (q, p, -s)
            yield _position(N, a, b), sign


def _position(N: int, a: int, b: int) -> int:
    """The 0-based lexicographic position of the plane ``(a, b)``, ``1 <= a < b <= N`` (:func:`plane_index` without
    its checks and without the table of every plane: the brackets of one plane at N = 1000)."""
    return (a - 1) * (2 * N - a) // 2 + (b - a - 1)


def _structure_constants_slice(N: int, plane: tuple[int, int]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r"""The nonzero entries ``(d, a, C[d, b, a])`` of the slice ``C[:, b, :]`` of :func:`structure_constants` for the
    one plane ``b = plane`` (1-based ``(i, j)``, ``i < j``; integer arrays): :math:`[E_d, E_b] = \sum_a C_{db}^{\;a}
    E_a`. Only the :math:`2(N - 2)` planes sharing one axis with ``b`` bracket to something nonzero, so it costs
    :math:`O(N)` brackets, not the whole :math:`n^3` table (5.2 GB at N = 60)."""
    N = check_dimension(N)
    i, j = _validate.plane(plane, N)
    rows, cols, vals = [], [], []
    for k in range(1, N + 1):
        if k in (i, j):
            continue
        for d in ((min(i, k), max(i, k)), (min(j, k), max(j, k))):
            row = _position(N, *d)
            for c, s in _bracket_terms(N, d, (i, j)):
                rows.append(row)
                cols.append(c)
                vals.append(s)
    return (np.array(rows, dtype=np.int64), np.array(cols, dtype=np.int64), np.array(vals, dtype=np.int64))


def structure_constants(N: int) -> np.ndarray:
    r"""Structure constants :math:`C_{ab}^{\;c}` of so(N) in the plane basis.

    ``C[a, b, c]`` is defined by :math:`[E_a, E_b] = \sum_c C_{ab}^{\;c} E_c` with
    :math:`E_{(ij)} = e_i e_j^{\mathsf T} - e_j e_i^{\mathsf T}`; explicitly

    .. math:: [E_{ij}, E_{kl}] = \delta_{jk} E_{il} - \delta_{ik} E_{jl}
              - \delta_{jl} E_{ik} + \delta_{il} E_{jk},

    with :math:`E_{ba} = -E_{ab}`. The array is read-only, of integer type,
    totally antisymmetric (the basis is orthogonal for the trace form), and the
    same in both matrix conventions (see the module docstring).
    """
    _pricing.check("structure_constants", N=check_dimension(N))
    return _structure_constants(check_dimension(N))


def _component_array(name: str, value: Any) -> np.ndarray:
    """A numeric array of component vectors (last axis), refused with the argument's name otherwise."""
    arr = _validate.exact_or_float_array(name, value, what="numeric component vector (or SymPy)")
    if arr.ndim == 0:
        raise ValueError(f"{name} must be a vector of N(N-1)/2 plane components, got the scalar {_validate.fmt(value)}")
    return arr


def lie_bracket(x: Any, y: Any):
    """Component vector of the matrix commutator ``[X, Y]`` of two component vectors.

    Convention independent (see the module docstring). NumPy input broadcasts
    over leading axes; SymPy input gives a ``sympy.Matrix`` column.
    """
    if is_symbolic(x) or is_symbolic(y):
        xs, ys = list(_sympy_matrix("x", x, column=True)), list(_sympy_matrix("y", y, column=True))
        if len(xs) != len(ys):
            raise ValueError(f"component vectors of different length: {len(xs)} and {len(ys)}")
        N = dimension_from_count(len(xs))
        C = structure_constants(N)
        a, b, c = np.nonzero(C)
        out = [sp.Integer(0)] * len(xs)
        for ai, bi, ci in zip(a, b, c):
            out[ci] += int(C[ai, bi, ci]) * xs[ai] * ys[bi]
        return sp.Matrix([sp.expand(v) for v in out])
    x, y = (_component_array(n, v) for n, v in (("x", x), ("y", y)))
    if x.shape[-1:] != y.shape[-1:]:
        raise ValueError(f"component vectors of different length: {x.shape[-1]} and {y.shape[-1]}")
    N = dimension_from_count(x.shape[-1])
    return np.einsum("...a,...b,abc->...c", x, y, structure_constants(N).astype(float))


def lie_poisson_bracket(F: sp.Expr, G: sp.Expr, L: Sequence[sp.Symbol]) -> sp.Expr:
    r"""Lie-Poisson bracket :math:`\{F, G\} = \sum_{abc} C_{ab}^{\;c} L_c\, \partial F/\partial L_a\, \partial G/\partial L_b`.

    Parameters
    ----------
    F, G : sympy expressions in the components ``L``.
    L : sequence of SymPy symbols, the ``N(N-1)/2`` components of the angular
        momentum in plane order (e.g. ``plane_symbols("L", N)``).

    Notes
    -----
    With this sign, :math:`\dot F = \{F, H\}` for the rigid-body Hamiltonian
    :math:`H = \sum_a L_a^2 / (2 I_a)` reproduces the Euler equations
    :math:`\dot L = [\Omega, L]` (eq. 24), and :math:`\{L_a, L_b\} = C_{ab}^{\;c} L_c`.
    """
    if isinstance(L, (str, bytes, Mapping)) or not isinstance(L, Iterable):
        raise TypeError(f"L must be a sequence of SymPy symbols (e.g. plane_symbols('L', N)), got {_validate.fmt(L)}")
    L = [_parse.to_sympy(s, "L", text=False) for s in L]
    if not all(isinstance(s, sp.Symbol) for s in L):
        raise TypeError(f"L must be a sequence of SymPy symbols (e.g. plane_symbols('L', N)), got {_validate.fmt(L)}")
    F, G = _parse.to_sympy(F, "F", text=False), _parse.to_sympy(G, "G", text=False)
    N = dimension_from_count(len(L))
    C = structure_constants(N)
    dF = [sp.diff(F, s) for s in L]
    dG = [sp.diff(G, s) for s in L]
    total = sp.Integer(0)
    for a, b, c in zip(*np.nonzero(C)):
        if dF[a] != 0 and dG[b] != 0:
            total += int(C[a, b, c]) * L[c] * dF[a] * dG[b]
    return sp.expand(total)


def bivector_product_table(N: int, *, convention: str = "paper", symbol: str = "e") -> sp.Matrix:
    r"""The table of products of basis bivectors (paper's Table 2) for any N.

    Entry ``(a, b)`` is the commutator product
    :math:`e^{a} \times e^{b} = \tfrac12 (e^a e^b - e^b e^a)`-type bracket
    written in the basis of the chosen convention, i.e. the matrix commutator
    ``[B_a, B_b]`` of the basis matrices :func:`basis_matrix` expanded back in
    that basis, as a linear combination of symbols ``e_ij``. Rows and columns
    follow the plane order. Because the checkerboard is an automorphism the
    table is the same in both conventions. The auxiliary matrix of Table 1 is
    obtained from it by replacing ``e_ij`` with ``L^ij``:
    :math:`\dot L^{a} = \sum_b \mathcal L_{ab}\,\omega_b` with
    :math:`\mathcal L_{ab} = \sum_c C_{bc}^{\;a} L_c = \sum_c C_{ab}^{\;c} L_c`.
    """
    N = check_dimension(N)
    _pricing.check("bivector_product_table", N=N)
    check_convention(convention)
    e = plane_symbols(symbol, N)
    n = len(e)
    # basis matrices of the convention; expand commutators back in that basis
    B = [basis_matrix(p, N, convention=convention) for p in planes(N)]
    T = sp.zeros(n, n)
    for a in range(n):
        for b in range(n):
            comp = to_components(B[a] @ B[b] - B[b] @ B[a], convention=convention)
            T[a, b] = sum((int(v) * e[c] for c, v in enumerate(comp) if v), sp.Integer(0))
    return T
