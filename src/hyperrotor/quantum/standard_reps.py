r"""The standard representations of so(N) and the operations that combine them.

Constructors: :func:`vector_rep`, :func:`adjoint_rep`, :func:`spinor_rep`,
:func:`harmonic_rep` (eq. 142 made into matrices), :func:`jmat_generators`
(so(3) from ``qutip.jmat``, with the exact map). Combinations
(:func:`~.combine.tensor`, :func:`~.combine.direct_sum`) are in :mod:`.combine`,
equivalences (:func:`~.equivalence.intertwiner`, :func:`~.equivalence.real_form`)
in :mod:`.equivalence`, the Gelfand-Tsetlin irreps in :mod:`.gelfand_tsetlin`. Every result is a
:class:`~.representation.Representation` obeying the conventions of
:mod:`.representation`.

so(3) and ``qutip.jmat``
-------------------------
The Gelfand-Tsetlin basis of so(3) (:func:`~.gelfand_tsetlin.irrep` with
``highest_weight=(j,)``, basis ordered by decreasing :math:`m`, the eigenvalue of
:math:`L^{12}`) is QuTiP's basis of ``jmat(j)``, and the Hermitian generators
:math:`L^{ij} = -i\hbar X_{(ij)}` are *exactly* (entry by entry)

.. math:: L^{12} = \hbar J_z, \qquad L^{13} = \hbar J_x, \qquad L^{23} = \hbar J_y ,

(:data:`JMAT_PLANES`), i.e. :math:`(L^{23}, -L^{13}, L^{12}) = \hbar(J_y, -J_x, J_z)`:
the textbook components :math:`(J_1, J_2, J_3) = (L^{23}, -L^{13}, L^{12})` of
:func:`~hyperrotor.quantum.operators.textbook_so3` are QuTiP's
:math:`(J_x, J_y, J_z)` rotated by 90 degrees about z,
:math:`R_z(\pi/2)^\dagger J_x R_z(\pi/2) = J_y`,
:math:`R_z(\pi/2)^\dagger J_y R_z(\pi/2) = -J_x`. Both sets obey
:math:`[J_1, J_2] = iJ_3` (cyclic). :func:`jmat_generators` builds the
generators from ``qutip.jmat`` with this map; ``tests/quantum/test_qutip_bridge.py``
checks it for :math:`j = 1/2, 1, \dots, 3`.
"""
from __future__ import annotations

from fractions import Fraction
from functools import partial
from typing import Any

import numpy as np
import scipy.sparse as sps

from .. import _lazy, _pricing, _validate
from .._lazy import sympy as sp
from .._options import options
from ..conventions import check_dimension, planes, structure_constants
from .equivalence import exact_antisymmetric
from .representation import Representation

__all__ = [
    "vector_rep",
    "adjoint_rep",
    "spinor_rep",
    "harmonic_rep",
    "JMAT_PLANES",
    "jmat_generators",
]

#: so(3) planes -> (``qutip.jmat`` component, sign): :math:`L^{ij} = \text{sign}\cdot\hbar\,J_{\text{component}}` exactly.
JMAT_PLANES = {(1, 2): ("z", 1), (1, 3): ("x", 1), (2, 3): ("y", 1)}


def jmat_generators(j: Any, *, form: str = "antihermitian", hbar: float = 1) -> dict:
    r"""The so(3) generators of spin ``j`` built from ``qutip.jmat`` with the exact map :data:`JMAT_PLANES`.

    Returns ``{plane: qutip.Qobj}`` equal, entry by entry, to
    ``irrep(3, (j,)).to_qobj(form=form, hbar=hbar)`` (module docstring):
    :math:`L^{12} = \hbar J_z`, :math:`L^{13} = \hbar J_x`, :math:`L^{23} = \hbar J_y`,
    and :math:`X_{(ij)} = iL^{ij}/\hbar` for ``form="antihermitian"``.
    Feed them to :meth:`Representation.from_qobj` (same ``form``) or to
    :func:`~hyperrotor.quantum.rotor_hamiltonian`.

    Parameters
    ----------
    j : int, half-integer float or Fraction (``j >= 1/2``)
    form : {"antihermitian", "hermitian"}, keyword-only
    hbar : float, keyword-only, default 1
    """
    from .gelfand_tsetlin import DEFAULT_MAX_DIM

    form, hbar = _validate.form_hbar(form, hbar)
    if isinstance(j, Fraction):
        jj = j
    else:
        jj = Fraction(_validate.positive("spin j", j)).limit_denominator(2)
    if jj.denominator not in (1, 2) or jj <= 0 or float(jj) != float(j):
        raise ValueError(f"spin j must be a positive integer or half-integer, got {_validate.fmt(j)}")
    if 2 * jj + 1 > DEFAULT_MAX_DIM:
        raise _pricing.refuse("jmat_generators", f"spin j = {_validate.fmt(float(jj))} (matrices of dimension 2j + 1)",
                              int(2 * jj + 1), "DEFAULT_MAX_DIM", "dimension", "ask for a smaller j",
                              limit=DEFAULT_MAX_DIM, raise_with="irrep(3, (j,), max_dim=...) (the same spin, "
                              "Gelfand-Tsetlin basis; DEFAULT_MAX_DIM is its default limit)")
    qutip = _lazy.qutip
    out = {}
    for p, (axis, sign) in JMAT_PLANES.items():
        L = (sign * hbar) * qutip.jmat(float(jj), axis)
        out[p] = L if form == "hermitian" else (1j / hbar) * L
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

    The N(N-1)/2 sparse generators are built at once, priced first (``BudgetError`` over
    ``hr.options['max_seconds']`` or ``['max_memory_bytes']``: ~6 s at N = 400); the exact
    SymPy generators are built on demand (:meth:`~.Representation.exact_generators`), priced then.
    """
    N = check_dimension(N)
    _pricing.check("vector_rep", N=N)
    gens = {}
    for i, j in planes(N):
        gens[(i, j)] = sps.csr_matrix(([1.0, -1.0], ([i - 1, j - 1], [j - 1, i - 1])), shape=(N, N))
    hw = None if N == 2 else _zeros_hw(N)
    return Representation(N, gens, highest_weight=hw, exact_generators=partial(_vector_exact, N),
                          name=f"vector rep of so({N})")


def _vector_exact(N: int) -> dict:
    """Exact generators of :func:`vector_rep`: :math:`E_{(ij)}` as SymPy matrices (priced before they are built)."""
    _pricing.check("vector_rep", N=N, exact=True)
    exact = {}
    for i, j in planes(N):
        S = sp.zeros(N, N)
        S[i - 1, j - 1], S[j - 1, i - 1] = 1, -1
        exact[(i, j)] = S
    return exact


def adjoint_rep(N: int) -> Representation:
    r"""The adjoint representation :math:`(\mathrm{ad}\,E_a)_{cb} = C_{ab}^{\;c}` on the plane basis.

    Real antisymmetric (C is totally antisymmetric), dimension N(N-1)/2. Highest
    weight: so(2) (0) (trivial), so(3) (1), so(4) reducible (:math:`(1,1) \oplus (1,-1)`,
    ``None``), N >= 5 :math:`(1, 1, 0, \dots)`. Casimir :math:`-2(N-2)`.

    The sparse generators are built at once, priced first (the structure constants by their own
    model, then the per-plane slices); the exact SymPy generators (:math:`n^3` entries for
    :math:`n = N(N-1)/2`) are built on demand (:meth:`~.Representation.exact_generators`), priced then.
    """
    N = check_dimension(N)
    _pricing.check("adjoint_rep", N=N)
    C = structure_constants(N)
    gens = {}
    for a, p in enumerate(planes(N)):
        M = C[a].T.astype(float)  # M[c, b] = C[a, b, c]
        gens[p] = sps.csr_matrix(M)
    if N == 2:
        hw = (0,)
    elif N == 3:
        hw = (1,)
    elif N == 4:
        hw = None
    else:
        hw = _zeros_hw(N, (1, 1))
    return Representation(N, gens, highest_weight=hw, exact_generators=partial(_adjoint_exact, N),
                          name=f"adjoint rep of so({N})")


def _adjoint_exact(N: int) -> dict:
    """Exact generators of :func:`adjoint_rep`: the structure constants as SymPy integer matrices (priced first)."""
    _pricing.check("adjoint_rep", N=N, exact=True)
    C = structure_constants(N)
    n = C.shape[0]
    return {p: sp.Matrix(n, n, lambda c, b, a=a: int(C[a, b, c])) for a, p in enumerate(planes(N))}


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
    if chirality is not None:  # (1.0 passed the test below and failed in a format string; True is not +1)
        chirality = _validate.integer("chirality (None, +1 or -1)", chirality)
        if chirality not in (1, -1):
            raise ValueError(f"chirality must be None, +1 or -1, got {chirality!r}")
    if N % 2 and chirality is not None:
        raise ValueError(f"so({N}) (odd N) has a single spinor irrep; chirality must be None, got {chirality!r}")
    _pricing.check("spinor_rep", N=N)
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

    half = Fraction(1, 2)
    if N % 2:
        hw = (half,) * n
        label = "spinor"
    elif chirality is None:
        hw, label = None, "Dirac spinor"
    else:
        hw = (half,) * (n - 1) + (half * chirality,)
        label = f"chirality {chirality:+d} spinor"
    return Representation(N, gens, highest_weight=hw, exact_generators=partial(_half_units_exact, gens),
                          name=f"{label} rep of so({N})")


def _half_units_exact(gens: dict) -> dict:
    """Exact SymPy matrices of float generators whose entries are 0, +-1/2 and +-i/2 (the spinors)."""
    out = {}
    for p, M in gens.items():
        D = M.toarray()
        out[p] = sp.Matrix(D.shape[0], D.shape[1], lambda r, c: sp.Rational(int(round(2 * D[r, c].real)), 2)
                           + sp.I * sp.Rational(int(round(2 * D[r, c].imag)), 2))
    return out


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

    The floating generators are **exactly** antisymmetric: the matrix computed
    through the (pseudo-)inverse of the monomial coefficients is projected by
    :func:`.equivalence.exact_antisymmetric`, which changes it by no more than its
    round-off (see there) and makes :math:`X^{\mathsf T} = -X` hold bit for bit,
    so :math:`\hat H` of :func:`~hyperrotor.quantum.rotor_hamiltonian` is exactly symmetric.
    """
    from .harmonic import orthogonal_harmonic_basis
    from .operators import angular_momentum_operator

    N = check_dimension(N)
    l = _validate.integer("degree l", l, minimum=0)
    _pricing.check("harmonic_rep", N=N, l=l)  # (the basis and every plane's matrix: refused by this name)
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
        gens[p] = sps.csr_matrix(exact_antisymmetric(M, options["quantum_harmonic_drop"]))

    hw = None if (N == 2 and l > 0) else _zeros_hw(N, (l,))
    return Representation(N, gens, highest_weight=hw, exact_generators=partial(_harmonic_exact, N, polys, norms, images),
                          name=f"harmonic polynomials of degree {l} (so({N}))")


def _harmonic_exact(N: int, polys: list, norms: list, images: dict) -> dict:
    r"""Exact generators of :func:`harmonic_rep`: :math:`\langle h_a, \mathbb L^{ij} h_b\rangle` in rationals and square roots."""
    d = len(polys)
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
                    r = c / Fraction(norms[a])  # coefficient of u_a
                    S[a, b] = sp.Rational(r.numerator, r.denominator) * sp.sqrt(
                        sp.Rational(Fraction(norms[a]).numerator * Fraction(norms[b]).denominator,
                                    Fraction(norms[a]).denominator * Fraction(norms[b]).numerator)
                    )
        out[p] = S
    return out
