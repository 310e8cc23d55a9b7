r"""Finite-dimensional matrix representations of so(N).

Conventions (the contract of every :class:`Representation`)
-----------------------------------------------------------
A representation assigns to each plane ``(i, j)``, ``i < j``, a matrix
:math:`X_{(ij)}` (anti-Hermitian; real antisymmetric when the basis allows)
with the brackets of the plane basis :math:`E_{(ij)} = e_i e_j^{\mathsf T} - e_j e_i^{\mathsf T}`
of :mod:`hyperrotor.conventions`:

.. math:: [X_a, X_b] = \sum_c C_{ab}^{\;c} X_c, \qquad C = \texttt{structure\_constants(N)}.

``vector_rep(N).generator((i, j))`` *is* :math:`E_{(ij)}`. The differential
operators :math:`\mathbb L^{ij} = x_i\partial_j - x_j\partial_i` of eq. (142)
obey the same brackets (they are the vector fields of :math:`-E_{(ij)}`, and
vector fields of linear maps form an anti-homomorphism), so
:func:`harmonic_rep` represents them directly. The Hermitian angular momenta
of eq. (141) are :math:`L^{ij} = -i\hbar X_{(ij)}` (:meth:`Representation.hermitian`,
``hbar`` keyword, default 1).

Consequences checked in the tests for every representation:

* quadratic Casimir :math:`\sum_{i<j} X_{(ij)}^2 = -c\,\mathbb 1` on an irrep of
  highest weight :math:`m` with :math:`c = \sum_i m_i (m_i + N - 2i)`
  (:func:`.weights.casimir_eigenvalue`), i.e. :math:`\sum (L^{ij})^2 = \hbar^2 c`;
* contraction identity :math:`\sum_{k \ne i,j} [X_{(ik)}, X_{(kj)}] = (N-2)\,X_{(ij)}`
  (with :math:`X_{(ba)} = -X_{(ab)}`), from :math:`[E_{ik}, E_{kj}] = E_{ij}` for
  distinct :math:`i, j, k`; equivalently
  :math:`\sum_k (X_{(ik)} X_{(jk)} - X_{(jk)} X_{(ik)}) = -(N-2)\,X_{(ij)}`, which
  is the paper's "contraction" :math:`\mathbb L\Omega = -3\mathbb L, -2\mathbb L, -\mathbb L`
  for :math:`\Omega = \mathbb L^{\mathsf T}` in 5D, 4D, 3D (eqs. 145-147),
  valid for the anti-Hermitian operators of eq. (142) and in every
  representation. For the Hermitian operators of eq. (141),
  :math:`L^{ij} = -i\hbar X_{(ij)}`, the factor becomes
  :math:`\sum_k (L^{ik}L^{jk} - L^{jk}L^{ik}) = +i\hbar(N-2)\,L^{ij}`
  (the paper's form does not carry over to eq. 141 unchanged).

Cartan subalgebra and weights
-----------------------------
Cartan generators :math:`X_{(12)}, X_{(34)}, \dots`; weights are eigenvalues of
:math:`H_k = -i X_{(2k-1,2k)}` (orthogonal basis, :mod:`.weights`). Root
vectors of the Cartan-Weyl basis: for the root :math:`\alpha = s e_k + t e_l`
put :math:`u = f_k^{s}`, :math:`v = f_l^{t}` with
:math:`f_k^{\pm} = e_{2k-1} \pm i e_{2k}` (and :math:`v = e_N` for the short
roots :math:`\pm e_k` of odd N); then
:math:`E_\alpha = \sum_{a<b} (u_a v_b - u_b v_a) X_{(ab)}` satisfies
:math:`[H_k, E_\alpha] = \alpha_k E_\alpha` (:meth:`Representation.ladder`).
"""
from __future__ import annotations

from fractions import Fraction
from typing import Any, Callable, Mapping, Sequence

import numpy as np
import scipy.sparse as sps
import sympy as sp

from hyperrotor.conventions import check_dimension, plane_index, planes, structure_constants

from .weights import casimir_eigenvalue, check_highest_weight, positive_roots

__all__ = [
    "Representation",
    "vector_rep",
    "adjoint_rep",
    "spinor_rep",
    "harmonic_rep",
    "tensor",
    "direct_sum",
    "intertwiner",
    "real_form",
]

_FORMATS = ("csr", "dense")


def _check_format(format: str) -> str:
    if format is None:
        return "csr"
    if format not in _FORMATS:
        raise ValueError(f"unknown format {format!r}; allowed: 'csr' (scipy.sparse CSR) or 'dense' (numpy array)")
    return format


def _as_format(M, format: str):
    if format == "dense":
        return M.toarray()
    return M.tocsr() if not sps.isspmatrix_csr(M) else M


class Representation:
    r"""A finite-dimensional representation of so(N) by matrices :math:`X_{(ij)}`.

    Prefer the constructors (:func:`vector_rep`, :func:`adjoint_rep`,
    :func:`spinor_rep`, :func:`harmonic_rep`, :func:`~.gelfand_tsetlin.irrep`,
    :func:`tensor`, :func:`direct_sum`) over calling the class directly.

    Parameters
    ----------
    N : int
    generators : mapping plane -> matrix
        One square matrix (scipy.sparse or array) per plane ``(i, j)`` of so(N),
        all of the same size, satisfying the brackets of the module docstring
        (not checked here; the tests check them).
    highest_weight : sequence, optional
        Highest weight (orthogonal basis) when the representation is irreducible;
        ``None`` for a reducible one.
    exact_generators : mapping or callable, optional
        Exact SymPy matrices (or a function computing them on demand).
    name : str
    format : {"csr", "dense"}
        Default matrix format of :meth:`generator`, :meth:`generators`,
        :meth:`hermitian`, :meth:`casimir`, ... when their ``format`` is not given.

    Attributes
    ----------
    N : int
    dim : int
    highest_weight : tuple of fractions.Fraction or None
    name : str
    format : str
    """

    def __init__(
        self,
        N: int,
        generators: Mapping[tuple[int, int], Any],
        *,
        highest_weight: Sequence[Any] | None = None,
        exact_generators: Mapping | Callable[[], Mapping] | None = None,
        name: str = "",
        format: str = "csr",
    ):
        self.format = _check_format(format)
        self.N = check_dimension(N)
        self.planes = planes(self.N)
        keys = {tuple(int(v) for v in p) for p in generators}
        if keys != set(self.planes):
            missing = sorted(set(self.planes) - keys)
            extra = sorted(keys - set(self.planes))
            raise ValueError(f"generators must be given for exactly the planes of so({self.N}); missing {missing}, unknown {extra}")
        gens = {}
        dim = None
        for p, M in generators.items():
            M = sps.csr_matrix(M)
            if M.shape[0] != M.shape[1] or (dim is not None and M.shape[0] != dim):
                raise ValueError(f"generator of plane {p} has shape {M.shape}; all must be square of one size")
            dim = M.shape[0]
            gens[tuple(int(v) for v in p)] = M
        self.dim = int(dim)
        self._gens = {p: gens[p] for p in self.planes}
        self.highest_weight = None if highest_weight is None else check_highest_weight(self.N, highest_weight)
        self._exact = exact_generators
        self.name = name or f"so({self.N}) representation of dimension {self.dim}"

    def __repr__(self) -> str:
        hw = None if self.highest_weight is None else "(" + ", ".join(str(x) for x in self.highest_weight) + ")"
        return f"Representation(N={self.N}, dim={self.dim}, highest_weight={hw}, name={self.name!r})"

    def _fmt(self, format):
        return self.format if format is None else _check_format(format)

    # -- basic access -----------------------------------------------------
    @property
    def rank(self) -> int:
        """Rank ``floor(N/2)`` of so(N)."""
        return self.N // 2

    @property
    def is_real(self) -> bool:
        """Whether every generator is a real (antisymmetric) matrix in this basis."""
        return all(not np.iscomplexobj(M.data) or not np.any(M.data.imag) for M in self._gens.values())

    def _plane(self, plane) -> tuple[int, int]:
        k = plane_index(plane, self.N)
        return self.planes[k]

    def generator(self, plane: Sequence[int], *, format: str | None = None, exact: bool = False):
        r"""The matrix :math:`X_{(ij)}` of ``plane = (i, j)`` (anti-Hermitian, brackets of :math:`E_{(ij)}`).

        Parameters
        ----------
        plane : (i, j) with 1 <= i < j <= N
        format : {"csr", "dense"}, optional
            scipy.sparse CSR or numpy array; default :attr:`format` of the
            representation (``"csr"`` unless chosen at construction).
        exact : bool
            Return an exact ``sympy.Matrix`` instead (small dims only).
        """
        p = self._plane(plane)
        if exact:
            return self._exact_generators()[p]
        return _as_format(self._gens[p], self._fmt(format))

    def generators(self, *, format: str | None = None, exact: bool = False) -> dict:
        """All generators as ``{plane: matrix}`` in plane order (see :meth:`generator`)."""
        if exact:
            ex = self._exact_generators()
            return {p: ex[p] for p in self.planes}
        format = self._fmt(format)
        return {p: _as_format(M, format) for p, M in self._gens.items()}

    def _exact_generators(self) -> dict:
        if self._exact is None:
            raise ValueError(f"no exact (SymPy) generators are available for {self.name}")
        if callable(self._exact):
            self._exact = dict(self._exact())
        return self._exact

    def hermitian(self, plane: Sequence[int], hbar: float = 1.0, *, format: str | None = None):
        r"""Hermitian angular momentum :math:`L^{ij} = -i\hbar X_{(ij)}` (eq. 141), ``hbar`` default 1."""
        return _as_format((-1j * hbar) * self._gens[self._plane(plane)], self._fmt(format))

    # -- Cartan, weights, ladders ------------------------------------------
    def cartan_generators(self, *, hermitian: bool = False, hbar: float = 1.0, format: str | None = None) -> list:
        r"""Cartan generators :math:`X_{(12)}, X_{(34)}, \dots` (or :math:`H_k = -i\hbar X_{(2k-1,2k)}`)."""
        format = self._fmt(format)
        out = []
        for k in range(1, self.rank + 1):
            p = (2 * k - 1, 2 * k)
            out.append(self.hermitian(p, hbar, format=format) if hermitian else self.generator(p, format=format))
        return out

    def weights(self, *, return_vectors: bool = False):
        r"""Weights (orthogonal basis) of a basis of simultaneous eigenvectors of the Cartan generators.

        The Hermitian :math:`H_k = -iX_{(2k-1,2k)}` commute; if they are all
        diagonal in this basis the weights of the basis vectors are returned in
        basis order. Otherwise a generic combination :math:`\sum_k c_k H_k` is
        diagonalized (dense, :math:`O(\dim^3)`) and the weights of its
        eigenvectors are returned.

        Returns
        -------
        weights : ndarray, shape (dim, rank)
            Rounded to the nearest half-integer (the deviation is checked to be
            < 1e-6).
        vectors : ndarray, shape (dim, dim), only with ``return_vectors=True``
            Unitary; column ``a`` has weight ``weights[a]``.
        """
        H = self.cartan_generators(hermitian=True, format="csr")
        n = self.rank
        diag = all((Hk - sps.diags(Hk.diagonal())).count_nonzero() == 0 for Hk in H)
        if diag:
            w = np.stack([Hk.diagonal().real for Hk in H], axis=1) if n else np.zeros((self.dim, 0))
            V = np.eye(self.dim, dtype=complex)
        else:
            bound = max(float(abs(Hk).sum(axis=1).max()) for Hk in H)
            R = 4 * (int(np.ceil(bound)) + 1) + 1
            Hc = sum((float(R) ** (-k)) * Hk.toarray() for k, Hk in enumerate(H))
            _, V = np.linalg.eigh(Hc)
            w = np.stack([np.einsum("ia,ia->a", V.conj(), Hk @ V).real for Hk in H], axis=1)
        w2 = np.rint(2 * w) / 2
        if w.size and np.max(np.abs(w - w2)) > 1e-6:
            raise ArithmeticError(f"weights of {self.name} are not half-integers (max deviation {np.max(np.abs(w - w2)):.2e})")
        return (w2, V) if return_vectors else w2

    def weight_multiplicities(self) -> dict[tuple[Fraction, ...], int]:
        """``{weight: multiplicity}`` from :meth:`weights` (compare :func:`.weights.weight_multiplicities`)."""
        out: dict = {}
        for row in self.weights():
            key = tuple(Fraction(int(round(2 * x)), 2) for x in row)
            out[key] = out.get(key, 0) + 1
        return out

    def roots(self) -> list[tuple[int, ...]]:
        """All roots (positive then negative) of so(N), orthogonal basis."""
        pos = positive_roots(self.N)
        return pos + [tuple(-a for a in r) for r in pos]

    def ladder(self, root: Sequence[int], *, format: str | None = None):
        r"""Root vector :math:`E_\alpha` of the Cartan-Weyl basis (module docstring).

        ``root`` in the orthogonal basis, e.g. ``(1, -1)`` or ``(0, 1)`` for so(5).
        :math:`[H_k, E_\alpha] = \alpha_k E_\alpha`; :math:`E_\alpha` raises
        weights by :math:`\alpha`, and :math:`E_{-\alpha} = \overline{E_\alpha}`
        (entrywise conjugate of the coefficients).
        """
        alpha = tuple(int(a) for a in root)
        if alpha not in self.roots():
            raise ValueError(f"{tuple(root)!r} is not a root of so({self.N}); roots: {self.roots()}")
        coeff = _root_coefficients(self.N, alpha)
        M = sps.csr_matrix((self.dim, self.dim), dtype=complex)
        for p, c in coeff.items():
            M = M + c * self._gens[p]
        return _as_format(M, self._fmt(format))

    def ladder_operators(self, *, format: str | None = None) -> dict:
        """``{root: E_root}`` for all roots (:meth:`ladder`)."""
        return {r: self.ladder(r, format=format) for r in self.roots()}

    # -- Casimir, QuTiP ------------------------------------------------------
    def casimir(self, *, format: str | None = None):
        r"""Quadratic Casimir :math:`\sum_{i<j} X_{(ij)}^2` (anti-Hermitian convention).

        Equals :math:`-c\,\mathbb 1` with :math:`c = \sum_i m_i(m_i + N - 2i)` on an
        irrep of highest weight ``m`` (:meth:`casimir_value`). The Hermitian
        :math:`\sum (L^{ij})^2` is :math:`+\hbar^2 c`.
        """
        C = sum((M @ M for M in self._gens.values()), sps.csr_matrix((self.dim, self.dim)))
        return _as_format(sps.csr_matrix(C), self._fmt(format))

    def casimir_value(self) -> Fraction | None:
        r""":math:`c = \sum_i m_i(m_i + N - 2i)` for an irrep (``None`` if reducible)."""
        if self.highest_weight is None:
            return None
        return casimir_eigenvalue(self.N, self.highest_weight)

    def to_qobj(self, plane: Sequence[int] | None = None, *, hermitian: bool = True, hbar: float = 1.0):
        r"""QuTiP operators with ``dims = [[dim], [dim]]``.

        ``plane=(i, j)`` gives one operator, ``plane=None`` a dict over all planes.
        ``hermitian=True`` (default) gives :math:`L^{ij} = -i\hbar X_{(ij)}`
        (eq. 141), ``hermitian=False`` the anti-Hermitian :math:`X_{(ij)}`.
        """
        import qutip

        def one(p):
            M = self.hermitian(p, hbar) if hermitian else self._gens[self._plane(p)]
            return qutip.Qobj(sps.csr_matrix(M, dtype=complex), dims=[[self.dim], [self.dim]])

        if plane is None:
            return {p: one(p) for p in self.planes}
        return one(plane)


def _root_coefficients(N: int, alpha: tuple[int, ...]) -> dict:
    nz = [(k, s) for k, s in enumerate(alpha) if s]
    f = []
    for k, s in nz:
        v = np.zeros(N, dtype=complex)
        v[2 * k] = 1
        v[2 * k + 1] = 1j * s
        f.append(v)
    if len(f) == 1:
        e = np.zeros(N, dtype=complex)
        e[N - 1] = 1
        f.append(e)
    u, v = f
    out = {}
    for a, b in planes(N):
        c = u[a - 1] * v[b - 1] - u[b - 1] * v[a - 1]
        if c != 0:
            out[(a, b)] = complex(c)
    return out


# ----------------------------------------------------------------------------
# constructors
# ----------------------------------------------------------------------------
def _zeros_hw(N: int, first=(1,)) -> tuple:
    n = N // 2
    return tuple(list(first) + [0] * (n - len(first)))


def vector_rep(N: int) -> Representation:
    r"""The defining representation: :math:`X_{(ij)} = E_{(ij)} = e_i e_j^{\mathsf T} - e_j e_i^{\mathsf T}`.

    Real antisymmetric; highest weight :math:`(1, 0, \dots, 0)` for N >= 3
    (so(2): reducible, weights :math:`\pm 1`, ``highest_weight=None``).
    Casimir :math:`\sum E_{(ij)}^2 = -(N-1)\,\mathbb 1`.
    """
    N = check_dimension(N)
    gens = {}
    exact = {}
    for i, j in planes(N):
        M = sps.csr_matrix(([1.0, -1.0], ([i - 1, j - 1], [j - 1, i - 1])), shape=(N, N))
        gens[(i, j)] = M
        S = sp.zeros(N, N)
        S[i - 1, j - 1], S[j - 1, i - 1] = 1, -1
        exact[(i, j)] = S
    hw = None if N == 2 else _zeros_hw(N)
    return Representation(N, gens, highest_weight=hw, exact_generators=exact, name=f"vector rep of so({N})")


def adjoint_rep(N: int) -> Representation:
    r"""The adjoint representation :math:`(\mathrm{ad}\,E_a)_{cb} = C_{ab}^{\;c}` on the plane basis.

    Real antisymmetric (C is totally antisymmetric), dimension N(N-1)/2. Highest
    weight: so(2) (0) (trivial), so(3) (1), so(4) reducible (:math:`(1,1) \oplus (1,-1)`,
    ``None``), N >= 5 :math:`(1, 1, 0, \dots)`. Casimir :math:`-2(N-2)`.
    """
    N = check_dimension(N)
    C = structure_constants(N)
    n = C.shape[0]
    gens, exact = {}, {}
    for a, p in enumerate(planes(N)):
        M = C[a].T.astype(float)  # M[c, b] = C[a, b, c]
        gens[p] = sps.csr_matrix(M)
        exact[p] = sp.Matrix(n, n, lambda c, b: int(C[a, b, c]))
    if N == 2:
        hw = (0,)
    elif N == 3:
        hw = (1,)
    elif N == 4:
        hw = None
    else:
        hw = _zeros_hw(N, (1, 1))
    return Representation(N, gens, highest_weight=hw, exact_generators=exact, name=f"adjoint rep of so({N})")


def _gammas(N: int):
    """Hermitian gamma matrices (Jordan-Wigner), {g_a, g_b} = 2 delta_ab, as exact SymPy and dense numpy."""
    n = N // 2
    I2 = np.eye(2)
    X = np.array([[0, 1], [1, 0]], dtype=complex)
    Y = np.array([[0, -1j], [1j, 0]], dtype=complex)
    Z = np.array([[1, 0], [0, -1]], dtype=complex)

    def kron_list(ms):
        out = np.ones((1, 1), dtype=complex)
        for m in ms:
            out = np.kron(out, m)
        return out

    g = []
    for k in range(n):
        pre = [Z] * k
        post = [I2] * (n - k - 1)
        g.append(kron_list(pre + [X] + post))
        g.append(kron_list(pre + [Y] + post))
    if N % 2:
        g.append(kron_list([Z] * n))
    return g


def spinor_rep(N: int, chirality: int | None = None) -> Representation:
    r"""Spinor representation from the Clifford algebra: :math:`X_{(ij)} = \tfrac14 [\gamma_i, \gamma_j] = \tfrac12\gamma_i\gamma_j`.

    Hermitian gamma matrices :math:`\{\gamma_i, \gamma_j\} = 2\delta_{ij}` in the
    Jordan-Wigner form (:math:`\gamma_{2k-1} = Z^{\otimes(k-1)} \otimes X \otimes 1`,
    :math:`\gamma_{2k} = Z^{\otimes(k-1)} \otimes Y \otimes 1`,
    :math:`\gamma_{2n+1} = Z^{\otimes n}`), dimension :math:`2^{\lfloor N/2 \rfloor}`.
    :math:`[\tfrac12\gamma_i\gamma_j, \tfrac12\gamma_j\gamma_k] = \tfrac12\gamma_i\gamma_k`
    matches :math:`[E_{ij}, E_{jk}] = E_{ik}`. In this basis the Cartan
    generators are diagonal, :math:`X_{(2k-1,2k)} = \tfrac i2 Z_k`, so
    :math:`H_k = Z_k/2` and the basis vector :math:`|b_1\dots b_n\rangle` has weight
    :math:`\tfrac12((-1)^{b_1}, \dots, (-1)^{b_n})`.

    Parameters
    ----------
    N : int
    chirality : {None, +1, -1}
        Odd N: must be ``None``; the irrep of highest weight :math:`(\tfrac12, \dots, \tfrac12)`
        (so(3): spin 1/2; so(5): the 4-dim spinor).
        Even N: ``None`` gives the reducible Dirac spinor (both halves);
        ``+1`` the half with highest weight :math:`(\tfrac12, \dots, \tfrac12)`
        (even number of :math:`-\tfrac12`), ``-1`` the half with
        :math:`(\tfrac12, \dots, \tfrac12, -\tfrac12)`; dimension :math:`2^{n-1}`.
    """
    N = check_dimension(N)
    n = N // 2
    if chirality not in (None, 1, -1):
        raise ValueError(f"chirality must be None, +1 or -1, got {chirality!r}")
    if N % 2 and chirality is not None:
        raise ValueError(f"so({N}) (odd N) has a single spinor irrep; chirality must be None, got {chirality!r}")
    g = _gammas(N)
    dim = 2 ** n
    keep = np.arange(dim)
    if chirality is not None:
        parity = np.array([bin(b).count("1") % 2 for b in range(dim)])
        keep = np.nonzero(parity == (0 if chirality == 1 else 1))[0]
    gens = {}
    for i, j in planes(N):
        M = 0.5 * (g[i - 1] @ g[j - 1])
        gens[(i, j)] = sps.csr_matrix(M[np.ix_(keep, keep)])

    def exact():
        # entries are 0, +-1/2, +-i/2 exactly
        out = {}
        for p, M in gens.items():
            D = M.toarray()
            out[p] = sp.Matrix(D.shape[0], D.shape[1], lambda r, c: sp.Rational(int(round(2 * D[r, c].real)), 2)
                               + sp.I * sp.Rational(int(round(2 * D[r, c].imag)), 2))
        return out
    half = Fraction(1, 2)
    if N % 2:
        hw = (half,) * n
        label = "spinor"
    elif chirality is None:
        hw, label = None, "Dirac spinor"
    else:
        hw = (half,) * (n - 1) + (half * chirality,)
        label = f"chirality {chirality:+d} spinor"
    return Representation(N, gens, highest_weight=hw, exact_generators=exact, name=f"{label} rep of so({N})")


def tensor(a: Representation, b: Representation) -> Representation:
    r"""Tensor product: :math:`X_{(ij)} \otimes 1 + 1 \otimes Y_{(ij)}` (Kronecker order a, b).

    Reducible in general (``highest_weight=None``) unless a factor is trivial.
    """
    _check_same_N(a, b)
    Ia, Ib = sps.identity(a.dim, format="csr"), sps.identity(b.dim, format="csr")
    gens = {p: sps.kron(a._gens[p], Ib, format="csr") + sps.kron(Ia, b._gens[p], format="csr") for p in a.planes}
    hw = None
    if a.dim == 1 and a.highest_weight is not None and all(x == 0 for x in a.highest_weight):
        hw = b.highest_weight
    elif b.dim == 1 and b.highest_weight is not None and all(x == 0 for x in b.highest_weight):
        hw = a.highest_weight
    exact = None
    if a._exact is not None and b._exact is not None:
        def exact():
            ea, eb = a._exact_generators(), b._exact_generators()
            return {
                p: sp.kronecker_product(ea[p], sp.eye(b.dim)) + sp.kronecker_product(sp.eye(a.dim), eb[p])
                for p in a.planes
            }
    return Representation(a.N, gens, highest_weight=hw, exact_generators=exact, name=f"({a.name}) x ({b.name})")


def direct_sum(*reps: Representation) -> Representation:
    """Direct sum (block diagonal generators, blocks in argument order)."""
    if not reps:
        raise ValueError("direct_sum needs at least one Representation")
    for r in reps:
        if not isinstance(r, Representation):
            raise TypeError(f"direct_sum takes Representation objects, got {type(r).__name__}")
    _check_same_N(*reps)
    N = reps[0].N
    gens = {p: sps.block_diag([r._gens[p] for r in reps], format="csr") for p in planes(N)}
    hw = reps[0].highest_weight if len(reps) == 1 else None
    exact = None
    if all(r._exact is not None for r in reps):
        def exact():
            ex = [r._exact_generators() for r in reps]
            return {p: sp.diag(*[e[p] for e in ex]) for p in planes(N)}
    return Representation(N, gens, highest_weight=hw, exact_generators=exact, name=" + ".join(f"({r.name})" for r in reps))


def _highest_weight_vector(rep: "Representation", raising: list) -> np.ndarray:
    """Joint kernel of the raising operators: null space of G = sum_E E^dagger E (Hermitian PSD)."""
    if not raising:
        return np.ones(1, dtype=complex)
    G = sum((E.conj().T @ E for E in raising), sps.csr_matrix((rep.dim, rep.dim))).toarray()
    w, V = np.linalg.eigh(G)
    tol = 1e-10 * max(1.0, float(w[-1]))
    K = V[:, w < tol]
    if K.shape[1] != 1:
        raise ValueError(
            f"{rep.name} is not irreducible: its highest-weight space has dimension {K.shape[1]}"
        )
    return K[:, 0]


def intertwiner(a: Representation, b: Representation, *, rtol: float = 1e-9) -> np.ndarray:
    r"""An invertible ``T`` with :math:`T\,X^{(a)}_{(ij)} = X^{(b)}_{(ij)}\,T` for all planes (dense).

    Both representations must be irreducible (a 1-dim joint kernel of the
    raising operators :math:`E_\alpha`, :math:`\alpha > 0`). Construction: the
    highest-weight vectors :math:`v_a, v_b` are matched, and so are the vectors
    :math:`E_{-\beta_1}\cdots E_{-\beta_r} v` obtained by the same words of
    lowering operators, until they span the space; the a-side vectors are
    orthonormalized (Gram-Schmidt, twice) and the same linear combinations are
    applied on the b-side, giving :math:`T = Y Q^\dagger` with Q unitary. By Schur's lemma ``T`` is unique up to a scalar; it is
    scaled so that :math:`\|T\|_F^2 = \dim`, which makes it unitary when both
    generator sets are anti-Hermitian in orthonormal bases.

    Raises
    ------
    ValueError
        If the representations are of different so(N), of different dimension,
        reducible, or not equivalent.
    """
    _check_same_N(a, b)
    if a.dim != b.dim:
        raise ValueError(f"no intertwiner: dimensions differ ({a.dim} vs {b.dim})")
    pos = positive_roots(a.N)
    ra = [a.ladder(r, format="csr") for r in pos]
    rb = [b.ladder(r, format="csr") for r in pos]
    la = [a.ladder(tuple(-x for x in r), format="csr") for r in pos]
    lb = [b.ladder(tuple(-x for x in r), format="csr") for r in pos]
    va, vb = _highest_weight_vector(a, ra), _highest_weight_vector(b, rb)
    d = a.dim
    # Orthonormalize on the a-side and apply the same linear combinations on the
    # b-side (T is linear), so that T = Y Q^dagger with Q unitary (well conditioned).
    nva = np.linalg.norm(va)
    Q = np.zeros((d, d), dtype=complex)
    Y = np.zeros((d, d), dtype=complex)
    Q[:, 0], Y[:, 0] = va / nva, vb / nva
    k = 1
    frontier = [0]
    la = [sps.csr_matrix(E) for E in la]
    lb = [sps.csr_matrix(E) for E in lb]
    while frontier and k < d:
        nxt = []
        for col in frontier:
            X2 = np.stack([E @ Q[:, col] for E in la], axis=1)
            Y2 = np.stack([E @ Y[:, col] for E in lb], axis=1)
            for x2, y2 in zip(X2.T, Y2.T):
                nx = np.linalg.norm(x2)
                if nx <= rtol:
                    continue
                Qk = Q[:, :k]
                c = (x2.conj() @ Qk).conj()
                r = x2 - Qk @ c
                c2 = (r.conj() @ Qk).conj()
                r = r - Qk @ c2
                nr = np.linalg.norm(r)
                if nr > 1e-8 * nx:
                    Q[:, k] = r / nr
                    Y[:, k] = (y2 - Y[:, :k] @ (c + c2)) / nr
                    nxt.append(k)
                    k += 1
                    if k == d:
                        break
            if k == d:
                break
        frontier = nxt
    if k < d:
        raise ValueError(f"{a.name} is not irreducible (the lowering operators span only {k} of {d} dimensions)")
    T = Y @ Q.conj().T
    T *= np.sqrt(d) / np.linalg.norm(T)
    res = max(
        float(np.abs(T @ a._gens[p].toarray() - b._gens[p].toarray() @ T).max()) for p in a.planes
    )
    scale = max(1.0, max(float(abs(M).max()) for M in a._gens.values()) if a.planes else 1.0)
    if res > 1e-6 * scale * max(1.0, np.abs(T).max()):
        raise ValueError(f"{a.name} and {b.name} are not equivalent (intertwining residual {res:.2e})")
    return T


def real_form(rep: Representation, *, atol: float = 1e-10) -> Representation:
    r"""An equivalent representation with real antisymmetric generators (irreps of real type).

    Let :math:`T` intertwine the complex-conjugate representation with ``rep``,
    :math:`T\,\overline{X}_{(ij)} = X_{(ij)}\,T` (:func:`intertwiner`,
    unitary). Then :math:`T\overline T = \varepsilon\,\mathbb 1` with
    :math:`\varepsilon = +1` (real type) or :math:`-1` (quaternionic type,
    e.g. spin 1/2 of so(3) or the spinor of so(5)). For real type :math:`T` is
    symmetric unitary, :math:`T = W^2` with :math:`W = O\,e^{i\Theta/2} O^{\mathsf T}`
    (O real orthogonal diagonalizing the commuting real and imaginary parts of
    T), and :math:`Y_{(ij)} = W^\dagger X_{(ij)} W` is real antisymmetric.
    Dense :math:`O(\dim^3)`; meant for moderate dimensions.

    Raises
    ------
    ValueError
        If ``rep`` is reducible, not self-conjugate (complex type, e.g. so(6)
        (1, 1, 1)) or quaternionic.
    """
    if not isinstance(rep, Representation):
        raise TypeError(f"real_form takes a Representation, got {type(rep).__name__}")
    if rep.is_real:
        return rep
    conj = Representation(rep.N, {p: M.conj() for p, M in rep._gens.items()}, name=f"conjugate of {rep.name}")
    try:
        T = intertwiner(conj, rep)
    except ValueError as err:
        raise ValueError(f"{rep.name} has no real form: {err}") from None
    TT = T @ T.conj()
    eps = float(np.real(np.trace(TT))) / rep.dim
    if abs(eps + 1) < 1e-6:
        raise ValueError(f"{rep.name} is of quaternionic (pseudo-real) type: T conj(T) = -1, no real form")
    if np.abs(TT - np.eye(rep.dim)).max() > 1e-8:  # pragma: no cover - internal
        raise ArithmeticError("conjugation intertwiner is not an involution (internal error)")
    T = 0.5 * (T + T.T)
    A, B = T.real, T.imag
    c = np.sqrt(2.0) + 0.1234
    _, O = np.linalg.eigh(A + c * B)
    theta = np.angle(np.einsum("ia,ij,ja->a", O, T, O))
    W = (O * np.exp(0.5j * theta)) @ O.T
    gens = {}
    for p, X in rep._gens.items():
        Y = W.conj().T @ X.toarray() @ W
        if np.abs(Y.imag).max() > atol * max(1.0, np.abs(Y).max()):
            raise ArithmeticError(f"real form failed: imaginary part {np.abs(Y.imag).max():.2e} (internal error)")
        Y = Y.real
        Y[np.abs(Y) < 1e-13 * max(1.0, np.abs(Y).max())] = 0.0
        gens[p] = sps.csr_matrix(Y)
    return Representation(rep.N, gens, highest_weight=rep.highest_weight, name=f"real form of {rep.name}", format=rep.format)


def _check_same_N(*reps):
    Ns = {r.N for r in reps}
    if len(Ns) != 1:
        raise ValueError(f"representations of different so(N) cannot be combined: N = {sorted(Ns)}")


# ----------------------------------------------------------------------------
# harmonic polynomials
# ----------------------------------------------------------------------------
def _monomial_mean(exponents: tuple, cache: dict) -> Fraction:
    """Normalized sphere mean of a monomial (via :func:`.harmonic.sphere_monomial_integral`), cached."""
    v = cache.get(exponents)
    if v is None:
        from .harmonic import sphere_monomial_integral

        r = sphere_monomial_integral(exponents, normalized=True)
        v = cache[exponents] = Fraction(int(r.p), int(r.q))
    return v


def harmonic_rep(N: int, l: int) -> Representation:
    r"""so(N) on the harmonic homogeneous polynomials of degree ``l`` (eq. 142 made into matrices).

    Basis: the orthonormalized (normalized sphere measure
    :math:`\langle p, q\rangle = \frac{1}{|S^{N-1}|}\int_{S^{N-1}} \bar p\,q\,dS`)
    exact Gram-Schmidt basis :math:`h_a = u_a/\sqrt{n_a}` of
    :func:`hyperrotor.quantum.harmonic.orthogonal_harmonic_basis`. The generator
    of plane ``(i, j)`` is the matrix of the differential operator
    :math:`\mathbb L^{ij} = x_i\partial_j - x_j\partial_i`
    (:func:`hyperrotor.quantum.operators.angular_momentum_operator`):
    :math:`\mathbb L^{ij} h_b = \sum_a (X_{(ij)})_{ab}\, h_a`,
    :math:`(X_{(ij)})_{ab} = \langle h_a, \mathbb L^{ij} h_b\rangle`. The measure
    is rotation invariant, so the :math:`X_{(ij)}` are real antisymmetric, and
    they satisfy the brackets of :math:`E_{(ij)}` (module docstring).

    Irreducible with highest weight :math:`(l, 0, \dots, 0)` for N >= 3
    (dimension :math:`\binom{l+N-1}{N-1} - \binom{l+N-3}{N-1}`, Casimir
    :math:`-l(l+N-2)`); for N = 2 and ``l >= 1`` it is the reducible
    2-dimensional real rep with weights :math:`\pm l`.
    Exact SymPy matrices (entries :math:`\sqrt{n_a/n_b}\,q`, q rational) on request.
    """
    from .harmonic import orthogonal_harmonic_basis
    from .operators import angular_momentum_operator

    N = check_dimension(N)
    if isinstance(l, bool) or not isinstance(l, (int, np.integer, sp.Integer)) or int(l) < 0:
        raise ValueError(f"degree l must be an integer >= 0, got {l!r}")
    l = int(l)
    polys, norms = orthogonal_harmonic_basis(N, l)
    d = len(polys)
    monos = sorted({m for p in polys for m in p})
    pos = {m: k for k, m in enumerate(monos)}

    def vec(p: dict) -> np.ndarray:
        v = np.zeros(len(monos))
        for m, c in p.items():
            v[pos[m]] = float(c)
        return v

    U = np.stack([vec(p) for p in polys], axis=1) if d else np.zeros((len(monos), 0))
    Upinv = np.linalg.pinv(U)
    sq = np.sqrt(np.array([float(n) for n in norms]))
    images = {}
    gens = {}
    for p in planes(N):
        op = angular_momentum_operator(p, N)
        imgs = [op.apply_to_polynomial(u) for u in polys]
        images[p] = imgs
        LU = np.stack([vec(q) for q in imgs], axis=1) if d else np.zeros((len(monos), 0))
        Cm = Upinv @ LU
        if np.abs(U @ Cm - LU).max(initial=0.0) > 1e-9 * max(1.0, np.abs(LU).max(initial=0.0)):  # pragma: no cover
            raise ArithmeticError("harmonic space not invariant (internal error)")
        M = sq[:, None] * Cm / sq[None, :]
        M[np.abs(M) < 1e-13] = 0.0
        gens[p] = sps.csr_matrix(M)

    def exact():
        cache: dict = {}

        def inner(a: dict, b: dict) -> Fraction:
            t = Fraction(0)
            for m1, c1 in a.items():
                for m2, c2 in b.items():
                    e = tuple(x + y for x, y in zip(m1, m2))
                    if all(x % 2 == 0 for x in e):
                        t += Fraction(c1) * Fraction(c2) * _monomial_mean(e, cache)
            return t

        out = {}
        for p in planes(N):
            S = sp.zeros(d, d)
            for b, img in enumerate(images[p]):
                if not img:
                    continue
                for a in range(d):
                    c = inner(polys[a], img)
                    if c:
                        r = c / Fraction(norms[a]) * 1  # coefficient of u_a
                        S[a, b] = sp.Rational(r.numerator, r.denominator) * sp.sqrt(
                            sp.Rational(Fraction(norms[a]).numerator * Fraction(norms[b]).denominator,
                                        Fraction(norms[a]).denominator * Fraction(norms[b]).numerator)
                        )
            out[p] = S
        return out

    hw = None if (N == 2 and l > 0) else _zeros_hw(N, (l,))
    return Representation(N, gens, highest_weight=hw, exact_generators=exact,
                          name=f"harmonic polynomials of degree {l} (so({N}))")
