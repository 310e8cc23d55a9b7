r"""The standard representations of so(N) and the operations that combine them.

Constructors: :func:`vector_rep`, :func:`adjoint_rep`, :func:`spinor_rep`,
:func:`harmonic_rep` (eq. 142 made into matrices), :func:`jmat_generators`
(so(3) from ``qutip.jmat``, with the exact map); combinations :func:`tensor`,
:func:`direct_sum`; equivalences :func:`intertwiner`, :func:`real_form`. The
Gelfand-Tsetlin irreps are in :mod:`.gelfand_tsetlin`. Every result is a
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
from typing import Any

import numpy as np
import scipy.sparse as sps

from .. import _lazy, _validate
from .._lazy import sympy as sp
from .._options import options
from ..conventions import check_dimension, planes, structure_constants
from .representation import Representation
from .weights import positive_roots

__all__ = [
    "vector_rep",
    "adjoint_rep",
    "spinor_rep",
    "harmonic_rep",
    "JMAT_PLANES",
    "jmat_generators",
    "tensor",
    "direct_sum",
    "intertwiner",
    "real_form",
]

#: so(3) planes -> (``qutip.jmat`` component, sign): :math:`L^{ij} = \text{sign}\cdot\hbar\,J_{\text{component}}` exactly.
JMAT_PLANES = {(1, 2): ("z", 1), (1, 3): ("x", 1), (2, 3): ("y", 1)}


def jmat_generators(j: Any, *, form: str = "antihermitian", hbar: float | None = None) -> dict:
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
    hbar = _validate.hbar(1.0 if hbar is None else hbar)
    if isinstance(j, Fraction):
        jj = j
    else:
        jj = Fraction(_validate.positive("spin j", j)).limit_denominator(2)
    if jj.denominator not in (1, 2) or jj <= 0 or float(jj) != float(j):
        raise ValueError(f"spin j must be a positive integer or half-integer, got {_validate.fmt(j)}")
    if 2 * jj + 1 > DEFAULT_MAX_DIM:
        raise ValueError(f"spin j = {_validate.fmt(float(jj))} has dimension 2j + 1 = {_validate.fmt(int(2 * jj + 1))} "
                         f"> {DEFAULT_MAX_DIM} (DEFAULT_MAX_DIM, the limit of irrep(3, (j,)) too)")
    qutip = _lazy.qutip
    out = {}
    for p, (axis, sign) in JMAT_PLANES.items():
        L = (sign * hbar) * qutip.jmat(float(jj), axis)
        out[p] = L if form == "hermitian" else (1j / hbar) * L
    return out


def _exact_antisymmetric(M: np.ndarray, drop: float) -> np.ndarray:
    r"""The antisymmetric part :math:`(M - M^{\mathsf T})/2` of a nearly antisymmetric ``M``, tiny entries dropped.

    Why this is the same operator up to round-off: if :math:`M = X + E` with the
    exact (antisymmetric) :math:`X` and a round-off error :math:`E`, then
    :math:`(M - M^{\mathsf T})/2 = X + (E - E^{\mathsf T})/2`, whose error is
    the antisymmetric part of :math:`E`, no larger than :math:`E` (the
    projection onto antisymmetric matrices is orthogonal in the Frobenius norm
    and has norm 1 in the max norm). In floating point
    :math:`M_{ab} - M_{ba} = -(M_{ba} - M_{ab})` exactly and halving is exact,
    so the result is antisymmetric bit for bit. Entries with
    :math:`|Y_{ab}| <` ``drop`` :math:`\cdot\max(1, \max|Y|)` (round-off of exact
    zeros) are set to zero; :math:`|Y_{ab}| = |Y_{ba}|`, so this keeps the symmetry.
    """
    Y = 0.5 * (M - M.T)
    Y[np.abs(Y) < drop * max(1.0, float(np.abs(Y).max(initial=0.0)))] = 0.0
    return Y

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
    if chirality is not None and (isinstance(chirality, bool) or chirality not in (1, -1)):
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


def real_form(rep: Representation, *, rtol: float | None = None, **old: Any) -> Representation:
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

    ``rtol`` (default ``options["quantum_real_form_rtol"]``) bounds the
    imaginary part left in :math:`Y_{(ij)}` relative to :math:`\max(1, \max|Y|)`
    (an internal consistency check); entries below
    ``options["quantum_real_form_drop"]`` (relative) are round-off of exact
    zeros and are dropped, symmetrically, so :math:`Y` stays exactly antisymmetric.

    Raises
    ------
    ValueError
        If ``rep`` is reducible, not self-conjugate (complex type, e.g. so(6)
        (1, 1, 1)) or quaternionic.
    """
    _validate.old_keywords("real_form", old, {"atol": "rtol= (the check is relative to max|Y|)"})
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
    rtol = options["quantum_real_form_rtol"] if rtol is None else _validate.positive("rtol", rtol)
    drop = options["quantum_real_form_drop"]
    gens = {}
    for p, X in rep._gens.items():
        Y = W.conj().T @ X.toarray() @ W
        if np.abs(Y.imag).max() > rtol * max(1.0, np.abs(Y).max()):
            raise ArithmeticError(f"real form failed: imaginary part {np.abs(Y.imag).max():.2e} (internal error)")
        gens[p] = sps.csr_matrix(_exact_antisymmetric(Y.real, drop))
    return Representation(rep.N, gens, highest_weight=rep.highest_weight, name=f"real form of {rep.name}", format=rep.format)


def _check_same_N(*reps):
    for k, r in enumerate(reps):
        if not isinstance(r, Representation):
            raise TypeError(
                f"argument {k + 1} must be a Representation (e.g. irrep(3, (1,))), got {_validate.fmt(r)} "
                f"of type {type(r).__name__}"
            )
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

    The floating generators are **exactly** antisymmetric: the matrix computed
    through the (pseudo-)inverse of the monomial coefficients is projected by
    :func:`_exact_antisymmetric`, which changes it by no more than its
    round-off (see there) and makes :math:`X^{\mathsf T} = -X` hold bit for bit,
    so :math:`\hat H` of :func:`~hyperrotor.quantum.rotor_hamiltonian` is exactly symmetric.
    """
    from .harmonic import orthogonal_harmonic_basis
    from .operators import angular_momentum_operator

    N = check_dimension(N)
    l = _validate.integer("degree l", l, minimum=0)
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
        gens[p] = sps.csr_matrix(_exact_antisymmetric(M, options["quantum_harmonic_drop"]))

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
