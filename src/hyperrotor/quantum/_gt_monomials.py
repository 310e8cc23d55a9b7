r"""Monomial matrices of the Gelfand-Tsetlin basis: rotations by pi and the real structure (private).

The machinery behind :mod:`hyperrotor.quantum.sectors` ("Construction without dense
matrices" there): in the GT basis the rotation by :math:`\pi` in a chain plane
:math:`(k, k+1)` and the conjugation intertwiner of a real-type irrep are *monomial*
(one phase per column). Each is found from its pattern permutation and the
intertwining relation along a spanning tree of the chain generators' nonzeros, then
checked on every nonzero; nothing here builds a dense ``dim x dim`` matrix.
"""
from __future__ import annotations

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sps
from scipy.sparse.csgraph import breadth_first_order

from .. import _pricing
from .gelfand_tsetlin import PatternIndex, patterns
from .weights import weyl_dim

__all__: list[str] = []

#: The phases i^0, i^1, i^2, i^3 (all entries of the monomial matrices are among them).
PHASES = np.array([1, 1j, -1, -1j])


def _round_phase(z: np.ndarray, what: str) -> np.ndarray:
    """Round to the nearest of 1, i, -1, -i; refuse if any value is not close to one."""
    z = np.asarray(z, dtype=complex)
    q = np.rint(np.angle(z) / (np.pi / 2)).astype(int) % 4
    out = PHASES[q]
    if z.size and np.abs(z - out).max() > 1e-8:
        raise ArithmeticError(f"{what}: not a phase in {{1, i, -1, -i}} (deviation {np.abs(z - out).max():.2e})")
    return out


class Monomial:
    """A monomial matrix ``D e_a = phase[a] e_{perm[a]}``."""

    __slots__ = ("perm", "phase")

    def __init__(self, perm: np.ndarray, phase: np.ndarray):
        self.perm = perm
        self.phase = phase

    def matrix(self) -> sps.csr_matrix:
        n = len(self.perm)
        return sps.csr_matrix((self.phase, (self.perm, np.arange(n))), shape=(n, n))


def _row_last_column(N: int, k: int) -> int:
    """Column of the last entry of row M_k in the flattened GT pattern (rows M_N, ..., M_2)."""
    c = 0
    for m in range(N, k - 1, -1):
        c += m // 2
    return c - 1


def gt_patterns_of(rep):
    """The GT patterns of ``rep`` when it is (claims to be) a Gelfand-Tsetlin irrep, else None.

    Trusted: ``rep`` is a Representation whose ``highest_weight`` its constructor
    checked; nothing is validated again (one check at the caller's public door).
    """
    m = rep.highest_weight
    if m is None or weyl_dim(rep.N, m) != rep.dim:
        return None
    return patterns(rep.N, m)


def _flip_perm(N: int, P: np.ndarray, index: PatternIndex, rows: list[int]) -> np.ndarray:
    """Index map of the GT patterns with the last label of each row ``M_k`` (k in ``rows``) negated."""
    if not rows:
        return np.arange(len(P))
    Q = P.copy()
    for k in rows:
        Q[:, _row_last_column(N, k)] *= -1.0
    perm = index.lookup(Q)
    if np.any(perm < 0):
        raise ArithmeticError("the sign flip of a last GT label leaves the irrep: not a GT irrep")
    return perm


def _intertwining_phases(chain: dict, perm: np.ndarray, sigma: dict, conj: bool) -> np.ndarray:
    r"""Phases (up to one constant) of the monomial U, :math:`U e_a = \varphi_a e_{\pi(a)}`, with
    :math:`U Y_q = \sigma_q X_q U` for every chain generator, :math:`Y_q = \bar X_q` if ``conj`` else :math:`X_q`.

    On a nonzero :math:`Y_{ab}` (a != b) the relation reads
    :math:`\varphi_a / \varphi_b = \sigma_q X_{\pi(a)\pi(b)} / Y_{ab}`; these ratios (in
    :math:`\{\pm1, \pm i\}`) are multiplied along a breadth-first spanning tree of the
    generator graph (connected for an irrep). The relation on all other nonzeros is
    checked afterwards (:func:`_monomial_residual`).
    """
    dim = len(perm)
    rows, cols, expo = [], [], []
    for q, X in chain.items():
        Y = X.conj() if conj else X
        C = Y.tocoo()
        off = C.row != C.col
        r, c, v = C.row[off], C.col[off], C.data[off]
        if not len(r):
            continue
        w = np.asarray(X[perm[r], perm[c]], dtype=complex).ravel()
        ratio = _round_phase(sigma[q] * w / v, "GT intertwining ratio")
        rows.append(r)
        cols.append(c)
        expo.append(np.rint(np.angle(ratio) / (np.pi / 2)).astype(np.int64) % 4 + 1)  # 1..4, never 0
    if not rows:
        return np.ones(dim, dtype=complex)
    r, c, e = np.concatenate(rows), np.concatenate(cols), np.concatenate(expo)
    R = sps.csr_matrix((e, (r, c)), shape=(dim, dim))
    order, pred = breadth_first_order(R, 0, directed=False)
    if len(order) != dim:
        raise ArithmeticError("the chain generators do not connect the basis: not an irrep")
    child = order[1:]
    # the tree uses an edge (a = child, b = parent) in either stored direction
    fwd = np.asarray(R[child, pred[child]]).ravel()
    bwd = np.asarray(R[pred[child], child]).ravel()
    step = np.where(fwd > 0, fwd - 1, (-(bwd - 1)) % 4)  # phi_child / phi_parent = i^step
    # exponent of phi_a = sum of the steps on the tree path from a to the root 0: pointer jumping
    # (after r rounds up[a] is the 2^r-th ancestor and ex[a] the sum of the steps below it), log2(depth) rounds
    up = np.zeros(dim, dtype=np.int64)  # the root is its own parent
    up[child] = pred[child]
    ex = np.zeros(dim, dtype=np.int64)
    ex[child] = step
    while np.any(up):
        ex = (ex + ex[up]) % 4
        up = up[up]
    return PHASES[ex]


def _monomial_residual(U: Monomial, chain: dict, sigma: dict, conj: bool) -> float:
    r"""Largest relative residual of U Y_q - sigma_q X_q U over all chain generators.

    Computed as :math:`U Y_q U^\dagger - \sigma_q X_q` (the same entries times phases in
    :math:`\{\pm1, \pm i\}`, exactly): :math:`(U Y U^\dagger)_{\pi(a)\pi(b)} = \varphi_a Y_{ab} \bar\varphi_b`,
    one pass over the nonzeros of Y instead of two sparse products.
    """
    perm, phase = U.perm, U.phase
    worst = 0.0
    for q, X in chain.items():
        C = X.tocoo()
        v = np.conj(C.data) if conj else C.data
        UYU = sps.csr_matrix((phase[C.row] * v * np.conj(phase[C.col]), (perm[C.row], perm[C.col])), shape=X.shape)
        R = UYU - sigma[q] * X
        if R.nnz:
            scale = float(abs(X).max()) if X.nnz else 1.0
            worst = max(worst, float(np.abs(R.data).max()) / max(scale, 1e-300))
    return worst


def gt_intertwiner(rep, P: np.ndarray, chain: dict, rows: list[int], sigma: dict, *, conj: bool,
                   index: PatternIndex | None = None) -> Monomial | None:
    r"""The monomial U with :math:`U Y_q = \sigma_q X_q U` for every chain generator, if there is one.

    :math:`Y_q = \bar X_q` (``conj=True``) or :math:`X_q`; the permutation of U negates
    the last label of the rows :math:`M_k`, ``k`` in ``rows``; ``sigma`` maps each
    chain index ``q`` (plane ``(q, q+1)``) to :math:`\pm1`. The overall constant is
    left as found (the phase of basis vector 0 is 1). ``None`` when the relation
    fails on some nonzero (relative residual over 1e-9) or no consistent phases
    exist. Trusted: ``rep``, ``P`` (:func:`gt_patterns_of`) and ``chain``
    (``{q: X_(q,q+1)}`` as CSR) are not validated again.
    """
    try:
        if index is None:
            index = PatternIndex(P, rep.highest_weight)
        perm = _flip_perm(rep.N, P, index, rows)
        U = Monomial(perm, _intertwining_phases(chain, perm, sigma, conj))
    except (ArithmeticError, ValueError):
        return None
    if _monomial_residual(U, chain, sigma, conj) > 1e-9:
        return None
    return U


def _gt_pi_rotation(rep, P: np.ndarray, k: int, chain: dict, index: PatternIndex) -> Monomial:
    """D(g_(k,k+1)) = exp(pi X_(k,k+1)) of a GT irrep as a monomial matrix (no dense dim x dim work).

    The phases come from :func:`gt_intertwiner` (s = -1 on the axes k, k+1); the
    overall constant ``c0`` of ``D = c0 * Phi``:

    * tensor irreps, ``k >= 2``: ``g_(k,k+1)`` is conjugate in SO(N) to ``g_(1,2)``,
      whose ``D`` is the diagonal ``(-1)^(M_2,1)`` (``X_(12) = i diag(M_2,1)``), so
      ``tr D = sum_a (-1)^(M_2,1(a)) = c0 * sum of phi_a over the fixed points of the
      permutation``; this gives ``c0`` in O(dim) whenever that sum is not zero;
    * otherwise one column of the dense ``exp(pi X)`` on the block of
      ``X_(k,k+1)`` holding vector 0 (one entry for ``k = 1``, where X is diagonal),
      priced first (``dense_representation``).
    """
    sigma = {q: (-1.0 if q in (k - 1, k + 1) else 1.0) for q in chain}  # s_q s_{q+1}, s = -1 on k, k+1
    D = gt_intertwiner(rep, P, chain, [k] if k % 2 == 0 else [], sigma, conj=False, index=index)
    if D is None:
        raise ArithmeticError("the monomial pi rotation fails the intertwining check: not a GT irrep")
    perm, phi = D.perm, D.phase
    tensor_irrep = all(x.denominator == 1 for x in rep.highest_weight)
    fixed_sum = complex(phi[perm == np.arange(len(perm))].sum()) if (tensor_irrep and k >= 2) else 0j
    if abs(fixed_sum) > 0.5:  # a sum of phases in {1, i, -1, -i}: a Gaussian integer, zero or >= 1
        trace = float(np.sum(1.0 - 2.0 * (np.rint(P[:, -1]).astype(np.int64) % 2)))
        c0 = _round_phase(np.array([trace / fixed_sum]), "overall phase from the trace")[0]
    else:
        X = chain[k]
        block, _ = breadth_first_order(abs(X) + sps.identity(rep.dim, format="csr"), 0, directed=False)
        block = np.sort(block)
        _pricing.check("dense_representation", dim=len(block), copies=2)
        E = sla.expm(np.pi * X[block][:, block].toarray())
        loc = {int(b): i for i, b in enumerate(block)}
        if int(perm[0]) not in loc:  # pragma: no cover - internal
            raise ArithmeticError("pi rotation leaves the block of X_(k,k+1): not a GT irrep")
        c0 = _round_phase(np.array([E[loc[int(perm[0])], 0] / phi[0]]), "overall phase")[0]
    return Monomial(perm, c0 * phi)


def gt_conjugation(rep, P: np.ndarray, chain: dict) -> Monomial | None:
    r"""Monomial U with :math:`U \bar X_{(ij)} U^\dagger = X_{(ij)}` and :math:`U\bar U = 1`, if it exists.

    Then :math:`T = U K` (K: complex conjugation of GT coordinates) is an antiunitary
    symmetry with :math:`T^2 = 1` commuting with every generator, so the irrep has a real
    form in which every rotor Hamiltonian is real symmetric. The permutation negates
    the last label of the rows :math:`M_2, M_6, M_{10}, \dots` (this negates the
    imaginary diagonal :math:`iC` of every :math:`X_{(2p+1,2p+2)}`: :math:`C` is odd in
    the last labels of rows :math:`2p` and :math:`2p+2`). ``None`` when no such U
    exists: spinor irreps are quaternionic (:math:`U\bar U = -1`), so(4k+2) irreps with
    :math:`m_n \ne 0` are of complex type. Trusted like :func:`gt_intertwiner`.
    """
    rows = list(range(2, rep.N, 4))
    if not rows:
        return None
    U = gt_intertwiner(rep, P, chain, rows, {q: 1.0 for q in chain}, conj=True)
    if U is None:
        return None
    # (U conj(U)) e_a = conj(phi_a) phi_{pi(a)} e_{pi(pi(a))}
    UU = np.conj(U.phase) * U.phase[U.perm]
    if np.any(U.perm[U.perm] != np.arange(len(U.perm))) or np.abs(UU - 1).max() > 1e-9:
        return None
    return U


def gt_rotations(rep, planes_k: list[int]) -> dict[int, Monomial] | None:
    """``{k: D(g_(k,k+1))}`` as monomial matrices for a GT irrep (None for any other representation).

    Trusted: ``rep`` is a Representation checked at the caller's door.
    """
    P = gt_patterns_of(rep)
    if P is None:
        return None
    index = PatternIndex(P, rep.highest_weight)
    chain = {q: sps.csr_matrix(rep.generator((q, q + 1), format="csr")) for q in range(1, rep.N)}
    out = {}
    for k in planes_k:
        try:
            out[k] = _gt_pi_rotation(rep, P, k, chain, index)
        except (ArithmeticError, ValueError):
            return None
    return out
