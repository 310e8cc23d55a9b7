r"""The operator matrices of Section 5 of the preprint: product (144) and contraction identities (145)-(147).

The operators themselves are in :mod:`hyperrotor.quantum.operators`; this
module combines their matrices (:func:`~hyperrotor.quantum.operators.operator_matrix`)
as Section 5 of the preprint does, and :mod:`hyperrotor.paper` checks the
printed equations with it. :func:`operator_product` computes the
operator version of eq. (25) that eq. (144) prints, with the printed factor
order, and :func:`contraction_identity` computes and verifies eqs. (145)-(147)
for any N.

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
from typing import Any

import numpy as np

from .. import _parse, _pricing, _validate
from .._equality import fields_equal, fields_unequal
from ..conventions import check_convention, check_dimension
from .normal_form import WeylElement
from .operators import DifferentialOperator, operator_matrix

__all__ = ["operator_product", "contraction_identity", "ContractionIdentity"]


def _check_operator_matrix(A: Any, name: str) -> np.ndarray:
    A = np.asarray(A, dtype=object)
    if A.ndim != 2 or A.shape[0] != A.shape[1] or A.shape[0] < 2:
        raise ValueError(f"{name} must be a square N x N matrix of operators, got shape {A.shape}")
    for v in A.flat:
        if not isinstance(v, DifferentialOperator):
            raise TypeError(f"{name} must contain DifferentialOperators, found {type(v).__name__}")
    return A


_FORMS = ("eq144", "antisymmetrized")


def operator_product(A: Any, B: Any, *, form: str = "eq144") -> np.ndarray:
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

    Raises
    ------
    hyperrotor.BudgetError
        Before any product, when the estimated time (``2 N^3`` entry compositions and the
        pairs of terms they compose) is over ``hr.options['max_seconds']``.

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
    form = _validate.choice("form", form, _FORMS)
    A = _check_operator_matrix(A, "A")
    B = _check_operator_matrix(B, "B")
    if A.shape != B.shape:
        raise ValueError(f"A and B have different shapes {A.shape} and {B.shape}")
    coords = A[0, 0].coordinates
    if any(op.coordinates != coords for op in (*A.flat, *B.flat)):
        raise ValueError(f"A and B must act on one set of coordinates, the {coords} of A[0, 0]")
    N = A.shape[0]
    _pricing.check("operator_product", N=N, pairs=_term_pairs(A, B, form), coords=len(coords))
    out = np.empty((N, N), dtype=object)
    for i in range(N):
        for j in range(N):
            acc = DifferentialOperator(WeylElement(len(coords), {}), coords)
            for k in range(N):
                if form == "eq144":
                    acc = acc + A[k, j] * B[i, k] - A[i, k] * B[k, j]
                else:
                    acc = acc + A[i, k] * B[k, j] - A[j, k] * B[k, i]
            out[i, j] = acc
    return out


def _term_pairs(A: np.ndarray, B: np.ndarray, form: str) -> int:
    """Number of pairs of terms that :func:`operator_product` composes (what its time follows).

    With ``a``, ``b`` the numbers of terms of the entries: ``sum_ijk a_kj b_ik + a_ik b_kj`` (eq144), or
    ``sum_ijk a_ik b_kj + a_jk b_ki`` (antisymmetrized), i.e. sums over ``k`` of row and column totals.
    """
    a = np.array([[len(op.element.terms) for op in row] for row in A], dtype=object)
    b = np.array([[len(op.element.terms) for op in row] for row in B], dtype=object)
    if form == "eq144":
        return int(np.sum(a.sum(axis=1) * b.sum(axis=0)) + np.sum(a.sum(axis=0) * b.sum(axis=1)))
    return int(2 * np.sum(a.sum(axis=0) * b.sum(axis=1)))


ContractionIdentity = namedtuple("ContractionIdentity", ["factor", "holds", "product", "matrix", "definition"])
ContractionIdentity.__doc__ = """Result of :func:`contraction_identity`.

factor : sympy.Rational, the ``c`` with ``product == c * matrix`` (entrywise, exact)
holds : bool, whether every entry satisfies it exactly
product : the operator matrix computed from the definition
matrix : the operator matrix of eq. (143)
definition : str, the definition used
"""
# (field by field: a tuple's == compares the object arrays of operators and refused their truth value)
ContractionIdentity.__eq__, ContractionIdentity.__ne__ = fields_equal, fields_unequal
ContractionIdentity.__hash__ = None


def contraction_identity(N: int, *, convention: str = "paper", form: str = "antisymmetrized",
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

    Raises
    ------
    hyperrotor.BudgetError
        Before the operator matrix is built, when the estimated time of the product (it grows
        like :math:`N^3` to :math:`N^4`: ~2 s at N = 30) is over ``hr.options['max_seconds']``.
    """
    N = check_dimension(N)
    convention = check_convention(convention)
    transpose = _validate.flag("transpose", transpose)
    _pricing.check("contraction_identity", N=N)  # the products grow like N^3 .. N^4: priced before the matrix
    M = operator_matrix(N, convention=convention, coordinates=coordinates)
    Om = M.T.copy() if transpose else M.copy()
    P = operator_product(M, Om, form=form)
    # factor from entry (0, 1): compare the coefficient of one term
    ref = M[0, 1].element.terms
    key, cref = next(iter(ref.items()))
    got = P[0, 1].element.terms.get(key, 0)
    factor = _parse.to_sympy(got, "coefficient") / _parse.to_sympy(cref, "coefficient")
    holds = all(P[i, j] == M[i, j] * factor for i in range(M.shape[0]) for j in range(M.shape[0]))
    tname = "L^T" if transpose else "L"
    if form == "antisymmetrized":
        definition = f"(L Omega)_ij - (L Omega)_ji = sum_k (L_ik o Omega_kj - L_jk o Omega_ki), Omega = {tname}"
    else:
        definition = f"sum_k (L_kj o Omega_ik - L_ik o Omega_kj)  [eq. 144 pattern], Omega = {tname}"
    return ContractionIdentity(factor, bool(holds), P, M, definition)
