r"""Monomial matrices of the Gelfand-Tsetlin basis: the sign group of a GT irrep (private).

The machinery behind :mod:`hyperrotor.quantum.sectors` ("Construction without dense
matrices" and "Real blocks" there): in the GT basis the rotation by :math:`\pi` in a
chain plane :math:`(k, k+1)`, the reflection :math:`r = \mathrm{diag}(-1, 1, \dots, 1)`
and the antiunitary of the real gauge are *monomial* (one phase per column). Each is
found from its pattern permutation and the intertwining relation along a spanning
tree of the chain generators' nonzeros, then checked on every nonzero; nothing here
builds a dense ``dim x dim`` matrix.

:func:`gt_symmetries` is the one door of :mod:`.sectors.group`: everything the sign
group of a GT irrep needs, as one :class:`GTSymmetries`. :func:`gt_rotations` gives
the rotations alone (``pi_rotation``). Both take a Representation checked at the
caller's public door and validate nothing again.
"""
from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sps
from scipy.sparse.csgraph import breadth_first_order

from .. import _pricing
from .gelfand_tsetlin import last_label_flips, patterns

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



# ----------------------------------------------------------------------------
# the frame of one irrep: patterns, label flips, chain generators
# ----------------------------------------------------------------------------
class _Frame(NamedTuple):
    """What every intertwiner of one GT irrep works on (:func:`_frame`)."""

    N: int
    m: tuple  #: the highest weight
    P: np.ndarray  #: the GT patterns, one row per basis vector
    flips: dict  #: ``{k: perm}``: the patterns with the last label of the even row M_k (k < N) negated
    chain: dict  #: ``{q: X_(q,q+1)}`` as CSR, ``q = 1, ..., N-1``


def _frame(rep) -> _Frame | None:
    """The :class:`_Frame` of ``rep`` when it is (claims to be) a Gelfand-Tsetlin irrep, else None.

    A claim is a highest weight with exactly ``rep.dim`` patterns (counted while they
    are built, so a weight that does not match costs at most ``rep.dim`` rows); the
    intertwining checks then decide.
    """
    m = rep.highest_weight
    if m is None:
        return None
    P = patterns(rep.N, m, max_count=rep.dim)
    if P is None or len(P) != rep.dim:
        return None
    flips = last_label_flips(rep.N, P, m)
    chain = {q: sps.csr_matrix(rep.generator((q, q + 1), format="csr")) for q in range(1, rep.N)}
    return _Frame(rep.N, m, P, flips, chain)


def _flip_perm(frame: _Frame, rows) -> np.ndarray:
    """Index map of the patterns with the last label of each row ``M_k`` (k in ``rows``) negated.

    The single-row flips commute (each changes one label), so a flip of several rows is their product.
    """
    perm = np.arange(len(frame.P))
    for k in rows:
        perm = frame.flips[k][perm]
    return perm


def gt_intertwiner(frame: _Frame, rows, sigma: dict, *, conj: bool) -> Monomial | None:
    r"""The monomial U with :math:`U Y_q = \sigma_q X_q U` for every chain generator, if there is one.

    :math:`Y_q = \bar X_q` (``conj=True``) or :math:`X_q`; the permutation of U negates
    the last label of the rows :math:`M_k`, ``k`` in ``rows`` (even, ``k < N``);
    ``sigma`` maps each chain index ``q`` (plane ``(q, q+1)``) to :math:`\pm1`. The
    overall constant is left as found (the phase of basis vector 0 is 1). ``None`` when
    the relation fails on some nonzero (relative residual over 1e-9) or no consistent
    phases exist.
    """
    perm = _flip_perm(frame, rows)
    try:
        U = Monomial(perm, _intertwining_phases(frame.chain, perm, sigma, conj))
    except (ArithmeticError, ValueError):
        return None
    if _monomial_residual(U, frame.chain, sigma, conj) > 1e-9:
        return None
    return U


# ----------------------------------------------------------------------------
# the sign group: rotations by pi, the reflection, the antiunitary, the centre
# ----------------------------------------------------------------------------
def _pi_rotation(frame: _Frame, k: int, tensor_irrep: bool) -> Monomial:
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
    chain = frame.chain
    sigma = {q: (-1.0 if q in (k - 1, k + 1) else 1.0) for q in chain}  # s_q s_{q+1}, s = -1 on k, k+1
    D = gt_intertwiner(frame, [k] if k % 2 == 0 else [], sigma, conj=False)
    if D is None:
        raise ArithmeticError("the monomial pi rotation fails the intertwining check: not a GT irrep")
    perm, phi = D.perm, D.phase
    fixed_sum = complex(phi[perm == np.arange(len(perm))].sum()) if (tensor_irrep and k >= 2) else 0j
    if abs(fixed_sum) > 0.5:  # a sum of phases in {1, i, -1, -i}: a Gaussian integer, zero or >= 1
        trace = float(np.sum(1.0 - 2.0 * (np.rint(frame.P[:, -1]).astype(np.int64) % 2)))
        c0 = _round_phase(np.array([trace / fixed_sum]), "overall phase from the trace")[0]
    else:
        X = chain[k]
        block, _ = breadth_first_order(abs(X) + sps.identity(len(perm), format="csr"), 0, directed=False)
        block = np.sort(block)
        _pricing.check("dense_representation", dim=len(block), copies=2)
        E = sla.expm(np.pi * X[block][:, block].toarray())
        loc = {int(b): i for i, b in enumerate(block)}
        if int(perm[0]) not in loc:  # pragma: no cover - internal
            raise ArithmeticError("pi rotation leaves the block of X_(k,k+1): not a GT irrep")
        c0 = _round_phase(np.array([E[loc[int(perm[0])], 0] / phi[0]]), "overall phase")[0]
    return Monomial(perm, c0 * phi)


def _rotations(frame: _Frame, planes_k) -> dict[int, Monomial] | None:
    """``{k: D(g_(k,k+1))}`` for ``k`` in ``planes_k``; None when one fails (not a GT irrep)."""
    tensor_irrep = all(x.denominator == 1 for x in frame.m)
    out = {}
    for k in planes_k:
        try:
            out[k] = _pi_rotation(frame, k, tensor_irrep)
        except (ArithmeticError, ValueError):
            return None
    return out


def gt_reflection(frame: _Frame) -> Monomial | None:
    r"""The reflection :math:`r = \mathrm{diag}(-1, 1, \dots, 1)` of a GT irrep of so(2n) with :math:`m_n = 0`.

    :math:`U_r X_{(ij)} U_r^{-1} = r X_{(ij)} r`, i.e. :math:`X_{(ij)} \to -X_{(ij)}` when
    exactly one of ``i, j`` is 1; :math:`U_r^2 = 1`. It commutes with every rotor
    Hamiltonian (only squares of generators) and with every :math:`D(g_s)`
    (:math:`r g_s = g_s r`), but it is not in :math:`SO(N)`: with it the sectors of
    even ``N`` become irreducible. In the GT basis it is monomial: :math:`\mathrm{Ad}(r)`
    is an outer automorphism of every :math:`so(2p)` of the chain, so it negates the
    last label of every even row :math:`M_{2p}` (``2p < N``; the top row ends in 0),
    and it is inner on every odd :math:`so(2p+1)`; on the chain generators
    :math:`\sigma_1 = -1`, all others ``+1``. Of the two extensions of the irrep to
    :math:`O(N)` (they differ by the determinant) this is the one with
    :math:`U_r e_0 = +e_{\pi(0)}` for the first GT pattern. ``None`` when the
    intertwining check fails (not a GT irrep).
    """
    sigma = {q: (-1.0 if q == 1 else 1.0) for q in frame.chain}
    U = gt_intertwiner(frame, range(2, frame.N, 2), sigma, conj=False)
    if U is None:
        return None
    sq = U.phase * U.phase[U.perm]
    if np.any(U.perm[U.perm] != np.arange(len(U.perm))) or np.abs(sq - 1).max() > 1e-9:
        return None  # pragma: no cover - U^2 = 1 holds whenever the intertwining check passes
    return U


def _commutes_conj(V: Monomial, U: Monomial) -> bool:
    r""":math:`V \bar U = U V` for monomial matrices (U with entries in {+-1, +-i})."""
    if np.any(V.perm[U.perm] != U.perm[V.perm]):
        return False
    # V conj(U) e_a = conj(u_a) v_{rho a} e_{pi rho a};  U V e_a = v_a u_{pi a} e_{rho pi a}
    return bool(np.abs(np.conj(U.phase) * V.phase[U.perm] - V.phase * U.phase[V.perm]).max() <= 1e-9)


def real_structure(frame: _Frame, *, cartan, reflection: Monomial | None) -> Monomial | None:
    r"""A monomial V such that :math:`A = VK` is antiunitary, :math:`A^2 = 1`, commutes with every rotor
    Hamiltonian and preserves every sector; ``None`` if no candidate passes.

    Candidates: :math:`A = D(g_s)\,T` for sign vectors ``s`` (any determinant), i.e.
    :math:`V \bar X_{(q,q+1)} V^{-1} = s_q s_{q+1} X_{(q,q+1)}`; in the GT basis V negates
    the last label of the rows :math:`M_m` with :math:`m \equiv 2 \pmod 4` (complex
    conjugation) and of the even rows with :math:`\prod_{i \le m} s_i = -1` (the sign
    rotation), the two sets combined by symmetric difference. :math:`A H A^{-1} = H`
    for every rotor Hamiltonian (it only has squares of generators). ``cartan``
    (spinor irreps): the Cartan planes of the sectors, on which :math:`A` must
    reverse the generator (:math:`s_k s_{k+1} = -1`): an antiunitary maps the
    eigenvalue :math:`\pm i` of :math:`D(g_{(k,k+1)})` to :math:`\mp i` times that sign.
    ``reflection``: :math:`A` must commute with it. Plain conjugation (``s = 1``) is
    tried first.
    """
    N, chain = frame.N, frame.chain
    conj_rows = {m for m in range(2, N + 1, 2) if m % 4 == 2}
    top_zero = frame.m[-1] == 0 if N % 2 == 0 else True
    candidates = sorted(itertools.product((1, -1), repeat=N - 1), key=lambda t: (t.count(-1), t))
    for tail in candidates:
        s = np.array(tail + (1,))
        sigma = {q: float(s[q - 1] * s[q]) for q in chain}
        if cartan and any(sigma[k] != -1.0 for k in cartan):
            continue
        rows = conj_rows ^ {m for m in range(2, N + 1, 2) if np.prod(s[:m]) == -1}
        if N in rows:
            if not top_zero:
                continue  # maps the irrep to the one with the last label negated
            rows.discard(N)
        V = gt_intertwiner(frame, sorted(rows), sigma, conj=True)
        if V is None or np.any(V.perm[V.perm] != np.arange(len(V.perm))):
            continue
        if np.abs(np.conj(V.phase) * V.phase[V.perm] - 1).max() > 1e-9:
            continue  # A^2 = -1 (quaternionic for this s)
        if reflection is not None and not _commutes_conj(V, reflection):
            continue
        return V
    return None


def _centre_scalar(rotations: dict, N: int) -> int | None:
    """Scalar by which -1 = g_(12) g_(34) ... acts on a tensor irrep of even N > 2; None otherwise."""
    if N % 2 or N == 2:
        return None
    ks = list(range(1, N, 2))
    if any(k not in rotations for k in ks):
        return None
    perm = np.arange(len(rotations[ks[0]].perm))
    phase = np.ones(len(perm), dtype=complex)
    for k in ks:
        D = rotations[k]
        phase = D.phase[perm] * phase
        perm = D.perm[perm]
    if np.any(perm != np.arange(len(perm))) or np.abs(phase - phase[0]).max() > 1e-9:
        return None
    return int(round(phase[0].real))


@dataclass(frozen=True)
class GTSymmetries:
    """What the sign group of a GT irrep needs (:func:`gt_symmetries`).

    Attributes
    ----------
    rotations : dict
        ``{k: D(g_(k,k+1))}``, the rotations by pi in the sector planes, as :class:`Monomial`.
    reflection : Monomial or None
        :math:`U_r` (:func:`gt_reflection`) where it acts on the irrep (even ``N >= 4``,
        tensor irrep, highest weight ending in 0), else None.
    antiunitary : Monomial or None
        V of the real structure :math:`A = VK` (:func:`real_structure`), None when ``N <= 2``
        or no candidate passes.
    centre : int or None
        The scalar of :math:`-1 = g_{(12)} g_{(34)} \\cdots` (tensor irreps of even ``N > 2``).
    """

    rotations: dict
    reflection: Monomial | None
    antiunitary: Monomial | None
    centre: int | None


def gt_symmetries(rep, planes_k: list[int], *, spinorial: bool) -> GTSymmetries | None:
    """The monomial sign group of a GT irrep: rotations in ``planes_k``, reflection, antiunitary, centre.

    ``planes_k``: the planes ``(k, k+1)`` that define the sectors (for a spinor irrep
    the Cartan planes, which the antiunitary must reverse). None for any other
    representation (no highest weight, another basis, or an intertwining check that
    fails): the caller falls back to dense exponentials.
    """
    frame = _frame(rep)
    if frame is None:
        return None
    rotations = _rotations(frame, planes_k)
    if rotations is None:
        return None
    U = V = None
    if frame.N >= 3:
        if frame.N % 2 == 0 and not spinorial and frame.m[-1] == 0:
            U = gt_reflection(frame)
        V = real_structure(frame, cartan=planes_k if spinorial else None, reflection=U)
    return GTSymmetries(rotations, U, V, None if spinorial else _centre_scalar(rotations, frame.N))


def gt_rotations(rep, planes_k: list[int]) -> dict[int, Monomial] | None:
    """``{k: D(g_(k,k+1))}`` as monomial matrices for a GT irrep (None for any other representation)."""
    frame = _frame(rep)
    return None if frame is None else _rotations(frame, planes_k)
