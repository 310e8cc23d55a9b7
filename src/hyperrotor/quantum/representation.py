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
of eq. (141) are :math:`L^{ij} = -i\hbar X_{(ij)}`: every method returning
generators takes ``form="antihermitian"`` (default, :math:`X_{(ij)}`) or
``form="hermitian"`` (:math:`-i\hbar X_{(ij)}`, keyword-only ``hbar``, default 1),
the package's one spelling (docs/conventions.md).

QuTiP both ways: :meth:`Representation.to_qobj` gives ``qutip.Qobj`` operators,
:meth:`Representation.from_qobj` builds a representation from ``{plane: Qobj}``
(or sparse/dense matrices), checking anti-Hermiticity and the brackets.

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

from .. import _lazy, _pricing, _validate
from .._options import options
from .._parallel import interruptible
from ..conventions import check_dimension, plane_index, planes, structure_constants
from .operator_input import as_csr, as_format, check_antihermitian, check_format, operator_mapping, real_if_possible
from .weights import casimir_eigenvalue, check_highest_weight, positive_roots

__all__ = ["Representation"]

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
        Exact SymPy matrices, or a picklable callable computing them on demand
        (a module-level function or a :func:`functools.partial` of one, so that
        the representation pickles).
    name : str
    format : {"csr", "dense"}
        Default matrix format of :meth:`generator`, :meth:`generators`,
        :meth:`casimir`, ... when their ``format`` is not given.

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
        self.format = check_format(format)
        self.N = check_dimension(N)
        self.planes = planes(self.N)
        if not isinstance(generators, Mapping):
            raise TypeError(
                f"generators must be a mapping plane -> matrix, got {_validate.fmt(generators)} "
                f"of type {type(generators).__name__}"
            )
        try:
            keys = {_validate.plane(p, self.N) for p in generators}
        except ValueError as exc:
            raise ValueError(f"generators: the keys must be planes of so({self.N}); {exc}") from None
        if keys != set(self.planes):
            missing = sorted(set(self.planes) - keys)
            extra = sorted(keys - set(self.planes))
            raise ValueError(f"generators must be given for exactly the planes of so({self.N}); missing {missing}, unknown {extra}")
        gens = {}
        dim = None
        for p, M in generators.items():
            if sps.issparse(M):  # (the package's own: no copy; numeric and finite checked)
                M = sps.csr_matrix(M)
                if M.dtype.kind not in "biufc" or not np.all(np.isfinite(M.data)):
                    raise ValueError(f"generator of plane {p} must be a finite numeric matrix, got dtype {M.dtype}"
                                     f"{'' if M.dtype.kind not in 'biufc' else ' with non-finite entries'}")
            else:  # a Qobj, an array or nested lists: the package's converter of user operators (numeric, finite)
                if isinstance(M, (list, tuple)):
                    _validate.numeric_input(f"generator of plane {p}", M)
                    M = np.asarray(M)
                M = as_csr(M, f"generator of plane {p}")
            if M.shape[0] != M.shape[1] or (dim is not None and M.shape[0] != dim):
                raise ValueError(f"generator of plane {p} has shape {M.shape}; all must be square of one size")
            dim = M.shape[0]
            gens[_validate.plane(p, self.N)] = M
        self.dim = int(dim)
        self._gens = {p: gens[p] for p in self.planes}
        self.highest_weight = None if highest_weight is None else check_highest_weight(self.N, highest_weight)
        if not (exact_generators is None or isinstance(exact_generators, Mapping) or callable(exact_generators)):
            raise TypeError(f"exact_generators must be None, a mapping plane -> SymPy matrix or a function returning "
                            f"one, got {_validate.fmt(exact_generators)} of type {type(exact_generators).__name__}")
        self._exact = exact_generators
        self.name = name or f"so({self.N}) representation of dimension {self.dim}"

    def __repr__(self) -> str:
        hw = None if self.highest_weight is None else "(" + ", ".join(str(x) for x in self.highest_weight) + ")"
        return f"Representation(N={self.N}, dim={self.dim}, highest_weight={hw}, name={self.name!r})"

    def __eq__(self, other: object) -> bool:
        """Same so(N), highest weight, name, default format and generator matrices (entry by entry, exactly).

        A representation pickles and deep-copies (the exact generators are
        computed by picklable recipes, not closures); the copy compares equal.
        """
        if not isinstance(other, Representation):
            return NotImplemented
        if (self.N, self.dim, self.highest_weight, self.name, self.format) != (
                other.N, other.dim, other.highest_weight, other.name, other.format):
            return False
        return all((self._gens[p] != other._gens[p]).nnz == 0 for p in self.planes)

    __hash__ = None  # type: ignore[assignment]  (mutable cache of exact generators; compared by value)

    @property
    def has_exact_generators(self) -> bool:
        """Whether :meth:`exact_generators` (and ``generator(..., exact=True)``) can give exact SymPy matrices."""
        return self._exact is not None

    def _fmt(self, format):
        return self.format if format is None else check_format(format)

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

    def generator(self, plane: Sequence[int], *, form: str = "antihermitian", hbar: Any = 1,
                  format: str | None = None, exact: bool = False):
        r"""The generator of ``plane = (i, j)``: :math:`X_{(ij)}` or :math:`L^{ij} = -i\hbar X_{(ij)}`.

        Parameters
        ----------
        plane : (i, j) with 1 <= i < j <= N
        form : {"antihermitian", "hermitian"}, keyword-only
            ``"antihermitian"`` (default): :math:`X_{(ij)}`, with the brackets of
            :math:`E_{(ij)}`; ``"hermitian"``: the angular momentum
            :math:`L^{ij} = -i\hbar X_{(ij)}` of eq. (141).
        hbar : float, keyword-only, default 1
            Used by ``form="hermitian"``; with the anti-Hermitian form any value
            other than 1 is refused (it would be ignored).
        format : {"csr", "dense"}, optional
            scipy.sparse CSR or numpy array; default :attr:`format` of the
            representation (``"csr"`` unless chosen at construction).
        exact : bool
            Return an exact ``sympy.Matrix`` instead (small dims only; with
            ``form="hermitian"`` ``hbar`` may be a SymPy expression such as
            ``sympy.Symbol("hbar", positive=True)``; text is refused with ``TypeError``).
        """
        exact = _validate.flag("exact", exact)
        p = self._plane(plane)
        if exact:
            form, hbar = _validate.form_hbar(form, hbar, exact=True)
            X = self.exact_generators()[p]
            return X if form == "antihermitian" else X * (-_lazy.sympy.I * hbar)
        form, hbar = _validate.form_hbar(form, hbar)
        M = self._gens[p]
        if form == "hermitian":
            M = (-1j * hbar) * M
        return as_format(M, self._fmt(format))

    def generators(self, *, form: str = "antihermitian", hbar: Any = 1, format: str | None = None,
                   exact: bool = False) -> dict:
        """All generators as ``{plane: matrix}`` in plane order (see :meth:`generator`)."""
        return {p: self.generator(p, form=form, hbar=hbar, format=format, exact=exact) for p in self.planes}

    def exact_generators(self) -> dict:
        """The exact SymPy generators ``{plane: sympy.Matrix}`` (anti-Hermitian form), computed once on demand.

        Raises ``ValueError`` when the representation has none (e.g. a real form
        computed in floating point).
        """
        if self._exact is None:
            raise ValueError(f"no exact (SymPy) generators are available for {self.name}")
        if not isinstance(self._exact, Mapping):
            self._exact = dict(self._exact())
        return self._exact

    # -- Cartan, weights, ladders ------------------------------------------
    def cartan_generators(self, *, form: str = "antihermitian", hbar: Any = 1, format: str | None = None) -> list:
        r"""Cartan generators :math:`X_{(12)}, X_{(34)}, \dots` (``form="hermitian"``: :math:`H_k = -i\hbar X_{(2k-1,2k)}`)."""
        return [self.generator((2 * k - 1, 2 * k), form=form, hbar=hbar, format=format) for k in range(1, self.rank + 1)]

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
        return_vectors = _validate.flag("return_vectors", return_vectors)
        H = self.cartan_generators(form="hermitian", format="csr")
        n = self.rank
        diag = all((Hk - sps.diags(Hk.diagonal())).count_nonzero() == 0 for Hk in H)
        if diag:  # e.g. every Gelfand-Tsetlin irrep: no dense work unless the vectors are asked for
            w = np.stack([Hk.diagonal().real for Hk in H], axis=1) if n else np.zeros((self.dim, 0))
            if return_vectors:
                _pricing.check("dense_matrix", dim=self.dim)
                V = np.eye(self.dim, dtype=complex)
        else:
            _pricing.check("dense_diagonalization", dim=self.dim)
            from ._krylov import row_bound  # (the Krylov module imports scipy.linalg: only when needed)

            bound = max(row_bound(Hk) for Hk in H)
            R = 4 * (int(np.ceil(bound)) + 1) + 1
            Hc = sum((float(R) ** (-k)) * Hk.toarray() for k, Hk in enumerate(H))
            _, V = interruptible(np.linalg.eigh, Hc)
            w = np.stack([np.einsum("ia,ia->a", V.conj(), Hk @ V).real for Hk in H], axis=1)
        w2 = np.rint(2 * w) / 2
        if w.size and np.max(np.abs(w - w2)) > 1e-6:
            raise ArithmeticError(f"weights of {self.name} are not half-integers (max deviation {np.max(np.abs(w - w2)):.2e})")
        return (w2, V) if return_vectors else w2  # noqa: F821 (V exists whenever return_vectors)

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
        if isinstance(root, (str, bytes)) or not isinstance(root, (Sequence, np.ndarray)):
            raise TypeError(f"root must be a sequence of {self.N // 2} integers (a root of so({self.N}), e.g. "
                            f"{self.roots()[0]}), got {_validate.fmt(root)} of type {type(root).__name__}")
        alpha = tuple(_validate.integer(f"root[{k}]", a) for k, a in enumerate(root))  # (1.9 was read as 1)
        if alpha not in self.roots():
            raise ValueError(f"{tuple(root)!r} is not a root of so({self.N}); roots: {self.roots()}")
        coeff = _root_coefficients(self.N, alpha)
        M = sps.csr_matrix((self.dim, self.dim), dtype=complex)
        for p, c in coeff.items():
            M = M + c * self._gens[p]
        return as_format(M, self._fmt(format))

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
        return as_format(sps.csr_matrix(C), self._fmt(format))

    def casimir_value(self) -> Fraction | None:
        r""":math:`c = \sum_i m_i(m_i + N - 2i)` for an irrep (``None`` if reducible)."""
        if self.highest_weight is None:
            return None
        return casimir_eigenvalue(self.N, self.highest_weight)

    def to_qobj(self, plane: Sequence[int] | None = None, *, form: str = "antihermitian", hbar: Any = 1):
        r"""QuTiP operators with ``dims = [[dim], [dim]]``; the inverse of :meth:`from_qobj`.

        Parameters
        ----------
        plane : (i, j), optional
            One operator; ``None`` (default) gives ``{plane: Qobj}`` over all planes.
        form : {"antihermitian", "hermitian"}, keyword-only, default "antihermitian"
            ``"antihermitian"``: :math:`X_{(ij)}`; ``"hermitian"``:
            :math:`L^{ij} = -i\hbar X_{(ij)}` (eq. 141), as in :meth:`generator`.
        hbar : float, keyword-only, default 1
            Used by ``form="hermitian"`` (any other value than 1 is refused with
            the anti-Hermitian form).
        """
        form, hbar = _validate.form_hbar(form, hbar)
        qutip = _lazy.qutip
        planes_ = self.planes if plane is None else [self._plane(plane)]
        out = {p: qutip.Qobj(sps.csr_matrix(self.generator(p, form=form, hbar=hbar, format="csr"), dtype=complex),
                             dims=[[self.dim], [self.dim]]) for p in planes_}
        return out if plane is None else out[planes_[0]]

    @classmethod
    def from_qobj(cls, generators: Mapping, *, form: str = "antihermitian", hbar: Any = 1, check: bool = True,
                  highest_weight: Sequence[Any] | None = None, name: str = "", format: str = "csr") -> "Representation":
        r"""A :class:`Representation` from ``{plane: operator}`` (``qutip.Qobj``, scipy.sparse or 2-D array).

        The way back from QuTiP: ``Representation.from_qobj(rep.to_qobj(form=f), form=f)``
        reproduces ``rep``.

        Parameters
        ----------
        generators : mapping plane -> operator
            One operator per plane ``(i, j)`` of so(N) (plane labels as in
            :func:`hyperrotor.planes`; ``N`` is inferred from their number).
        form : {"antihermitian", "hermitian"}, keyword-only, default "antihermitian"
            What the operators are: :math:`X_{(ij)}` or :math:`L^{ij} = -i\hbar X_{(ij)}`
            (then :math:`X = i L/\hbar` is stored).
        hbar : float, keyword-only, default 1
            Used by ``form="hermitian"`` (any other value than 1 is refused with
            the anti-Hermitian form).
        check : bool, default True
            Verify anti-Hermiticity and the brackets
            :math:`[X_a, X_b] = \sum_c C_{ab}^{\;c} X_c`
            (relative tolerance ``options["quantum_bracket_rtol"]``). For
            ``qutip.jmat`` operators use :func:`jmat_generators` (the so(3) map).
        highest_weight, name, format
            As in the constructor.

        Raises
        ------
        ValueError
            Missing/unknown planes, operators of different sizes, generators that
            are not anti-Hermitian (with a hint when they are Hermitian: pass
            ``form="hermitian"``), or brackets that fail (naming the pair of planes).
        """
        form, hbar = _validate.form_hbar(form, hbar)
        check = _validate.flag("check", check)
        N, mats = operator_mapping(generators)
        if form == "hermitian":
            mats = {p: (1j / hbar) * M for p, M in mats.items()}
        mats = {p: real_if_possible(M) for p, M in mats.items()}
        rep = cls(N, mats, highest_weight=highest_weight, name=name, format=format)
        if check:
            check_antihermitian(rep.generators(format="csr"), form=form)
            rep.check_brackets()
        return rep

    def check_brackets(self, *, rtol: float | None = None) -> None:
        r"""Raise ``ValueError`` unless :math:`[X_a, X_b] = \sum_c C_{ab}^{\;c} X_c` for all planes.

        The residual is compared with ``rtol`` (default
        ``options["quantum_bracket_rtol"]``) times :math:`\max_a \|X_a\|_{\max}^2`.
        """
        rtol = options["quantum_bracket_rtol"] if rtol is None else _validate.positive("rtol", rtol)
        C = structure_constants(self.N)
        G = [self._gens[p] for p in self.planes]
        scale = max([1.0] + [float(abs(M).max()) for M in G if M.nnz]) ** 2
        for a in range(len(G)):
            for b in range(a + 1, len(G)):
                R = (G[a] @ G[b] - G[b] @ G[a]).tocsr()
                for c in np.nonzero(C[a, b])[0]:
                    R = R - int(C[a, b, c]) * G[c]
                res = float(abs(R).max()) if R.nnz else 0.0
                if res > rtol * scale:
                    pa, pb = self.planes[a], self.planes[b]
                    raise ValueError(
                        f"the generators do not satisfy the so({self.N}) brackets: [X{pa}, X{pb}] misses "
                        f"sum_c C_ab^c X_c by {res:.3g} (tolerance {rtol * scale:.3g}); check the plane labels, "
                        f"the form (antihermitian/hermitian) and, for qutip.jmat, use jmat_generators(j)"
                    )


def check_same_algebra(*reps: Any) -> None:
    """Refuse anything but :class:`Representation` objects of one so(N) (for combining or comparing them)."""
    for k, r in enumerate(reps):
        if not isinstance(r, Representation):
            raise TypeError(
                f"argument {k + 1} must be a Representation (e.g. irrep(3, (1,))), got {_validate.fmt(r)} "
                f"of type {type(r).__name__}"
            )
    Ns = {r.N for r in reps}
    if len(Ns) != 1:
        raise ValueError(f"representations of different so(N) cannot be combined: N = {sorted(Ns)}")


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

