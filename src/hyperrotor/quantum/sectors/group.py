r"""The symmetry group of the sectors: sign rotations, the reflection parity, the antiunitary, the characters.

:func:`group_of` builds the :class:`SignGroup` of a representation once (the monomial
matrices of a Gelfand-Tsetlin irrep, or dense exponentials for other
representations); its :meth:`SignGroup.characters` are the labels of the
:class:`Sector` s. For even ``N`` the reflection :math:`r = \mathrm{diag}(-1, 1, \dots, 1)`
joins the group (:func:`gt_reflection`), and :func:`real_structure` finds the
antiunitary symmetry that makes every block real (package docstring).
"""
from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sps

from ... import _pricing
from .._gt_monomials import Monomial, gt_intertwiner, gt_patterns_of, gt_rotations

__all__ = ["Sector"]

_CLASSES_3D = {(1, 1): "A", (1, -1): "B1", (-1, -1): "B2", (-1, 1): "B3"}
#: key of the reflection parity in :attr:`Sector.character`
REFLECTION = "reflection"


@dataclass(frozen=True)
class Sector:
    r"""One symmetry sector of a representation.

    Attributes
    ----------
    label : str or tuple
        3D tensor irreps: the :math:`D_2` class ``"A"``, ``"B1"``, ``"B2"``, ``"B3"``.
        Other tensor irreps: the character, the tuple of eigenvalues (``+1``/``-1``)
        of :math:`D(g_{(k,k+1)})`, ``k = 1, ..., N-1``, followed for even ``N`` and a
        highest weight ending in 0 by the reflection parity (``+1``/``-1``, the
        eigenvalue of :math:`U_r`, :func:`gt_reflection`). Spinor irreps: ``"E1/2"`` in
        3D (the Kramers irrep of the double group :math:`D_2^*`), ``"spinor"`` for
        ``N >= 4``; with ``complete=True`` the copies are ``(name, psi)`` with ``psi``
        the eigenvalues (``"+i"``/``"-i"``) of the Cartan-plane rotations.
    basis : scipy.sparse.csc_matrix or numpy.ndarray, shape (dim, n)
        Orthonormal columns spanning the sector (sparse for Gelfand-Tsetlin irreps).
    degeneracy : int
        Dimension of the irrep of the (lifted) sign group this sector belongs to:
        every eigenvalue of :math:`B^\dagger H B` is a level of ``H`` of (at least)
        this multiplicity. 1 for tensor irreps.
    character : dict
        ``{plane: eigenvalue}`` of :math:`D(g_{\rm plane}) = \exp(\pi X_{\rm plane})`
        on the sector, for the planes that define it, and ``{"reflection": +-1}``
        where the reflection parity is part of the label.
    real : bool
        The basis columns are fixed by an antiunitary symmetry :math:`A = VK`,
        :math:`A^2 = 1`, commuting with every rotor Hamiltonian and preserving the
        sector (package docstring, "Real blocks"), so :math:`B^\dagger \hat H B` is
        real symmetric for every rotor Hamiltonian (and is returned real by
        :func:`sector_hamiltonian`, which halves memory and makes the
        diagonalization ~4x cheaper). True for every sector of a Gelfand-Tsetlin
        irrep; False for the dense fallback.
    """

    label: Any
    basis: Any
    degeneracy: int = 1
    character: dict = field(default_factory=dict)
    real: bool = False

    @property
    def dim(self) -> int:
        """Number of basis columns."""
        return int(self.basis.shape[1])

    def __repr__(self) -> str:
        kind = "sparse" if sps.issparse(self.basis) else "dense"
        return f"Sector(label={self.label!r}, dim={self.dim}, degeneracy={self.degeneracy}, {kind} basis)"


def is_half_integer(rep) -> bool | None:
    """Spinor (half-integer highest weight) or tensor irrep; None without a highest weight."""
    hw = rep.highest_weight
    if hw is None:
        return None
    return any(Fraction(x).denominator == 2 for x in hw)


def structure(N: int, spinorial: bool):
    """(planes k defining the sectors, eigenvalue alphabet, degeneracy)."""
    if N == 2 or not spinorial:
        ks = list(range(1, N))
        alphabet = (1j, -1j) if spinorial else (1, -1)
        return ks, alphabet, 1
    ks = [2 * j - 1 for j in range(1, N // 2 + 1)]  # Cartan planes (1,2), (3,4), ...
    return ks, (1j, -1j), 2 ** ((N - 1) // 2)


def eig_text(lam) -> Any:
    """+1/-1 as ints, +i/-i as the strings "+i"/"-i"."""
    lam = complex(lam)
    if abs(lam.imag) > 0.5:
        return "+i" if lam.imag > 0 else "-i"
    return int(round(lam.real))


def label(N: int, spinorial: bool, eigs: tuple, complete: bool, parity: int | None = None) -> Any:
    """The :attr:`Sector.label` of the joint eigenvalues ``eigs`` (and reflection ``parity``)."""
    if not spinorial or N == 2:
        if N == 3 and not spinorial:
            return _CLASSES_3D[tuple(int(round(complex(e).real)) for e in eigs)]
        out = tuple(eig_text(e) for e in eigs)
        return out if parity is None else out + (int(parity),)
    name = "E1/2" if N == 3 else "spinor"
    return (name, tuple(eig_text(e) for e in eigs)) if complete else name


def centre_scalar(ops: dict, N: int, spinorial: bool) -> int | None:
    """Scalar by which -1 = g_(12) g_(34) ... acts (even N, tensor irreps); None otherwise."""
    if spinorial or N % 2 or N == 2:
        return None
    ks = list(range(1, N, 2))
    if any(k not in ops for k in ks):
        return None
    perm = np.arange(len(ops[ks[0]].perm))
    phase = np.ones(len(perm), dtype=complex)
    for k in ks:
        D = ops[k]
        phase = D.phase[perm] * phase
        perm = D.perm[perm]
    if np.any(perm != np.arange(len(perm))) or np.abs(phase - phase[0]).max() > 1e-9:
        return None
    return int(round(phase[0].real))


def has_reflection(rep, spinorial: bool) -> bool:
    """Even N >= 4, tensor irrep, highest weight ending in 0: the reflection r acts on the irrep."""
    return rep.N % 2 == 0 and rep.N >= 4 and not spinorial and Fraction(rep.highest_weight[-1]) == 0


def gt_reflection(rep, P: np.ndarray, chain: dict) -> Monomial | None:
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
    N = rep.N
    sigma = {q: (-1.0 if q == 1 else 1.0) for q in chain}
    U = gt_intertwiner(rep, P, chain, list(range(2, N, 2)), sigma, conj=False)
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


def real_structure(rep, P: np.ndarray, chain: dict, *, cartan: list[int] | None, reflection: Monomial | None):
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
    N = rep.N
    conj_rows = {m for m in range(2, N + 1, 2) if m % 4 == 2}
    top_zero = rep.highest_weight[-1] == 0 if N % 2 == 0 else True
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
        V = gt_intertwiner(rep, P, chain, sorted(rows), sigma, conj=True)
        if V is None or np.any(V.perm[V.perm] != np.arange(len(V.perm))):
            continue
        if np.abs(np.conj(V.phase) * V.phase[V.perm] - 1).max() > 1e-9:
            continue  # A^2 = -1 (quaternionic for this s)
        if reflection is not None and not _commutes_conj(V, reflection):
            continue
        return V
    return None


# ----------------------------------------------------------------------------
# the group of a representation
# ----------------------------------------------------------------------------
@dataclass
class SignGroup:
    """The commuting symmetries that define the sectors of one representation (:func:`group_of`).

    ``ops``: one operator per plane ``(k, k+1)``, ``k`` in ``ks`` (monomial matrices of a
    GT irrep, dense exponentials otherwise), then the reflection :math:`U_r` when
    ``reflection``; ``centre``: the scalar of :math:`-1 = g_{(12)} g_{(34)} \\cdots` (even N
    tensor irreps); ``antiunitary``: V of :math:`A = VK` (real gauge), GT irreps only.
    """

    N: int
    spinorial: bool
    ks: list
    alphabet: tuple
    degeneracy: int
    ops: list
    monomial: bool
    centre: int | None = None
    reflection: bool = False
    antiunitary: Monomial | None = None

    @property
    def real(self) -> bool:
        """Every sector block is real (GT irreps; N <= 2 has only 1 x 1 blocks)."""
        return self.antiunitary is not None or (self.monomial and self.N <= 2)

    def characters(self, complete: bool):
        """``(eigenvalues of ops, label, character)`` of every candidate sector, in label order."""
        parities = (1, -1) if self.reflection else (None,)
        for eigs in itertools.product(self.alphabet, repeat=len(self.ks)):
            if self.centre is not None and np.prod([eigs[k - 1] for k in range(1, self.N, 2)]) != self.centre:
                continue  # -1 = g_(12) g_(34) ... is central: it acts as the scalar `centre`
            for parity in parities:
                character = {(k, k + 1): eig_text(e) for k, e in zip(self.ks, eigs)}
                if parity is not None:
                    character[REFLECTION] = parity
                yield (eigs if parity is None else eigs + (parity,),
                       label(self.N, self.spinorial, eigs, complete, parity), character)


def check_dense_dim(rep) -> None:
    """Price the dense fallback (dense exponentials and projectors of a non-GT representation)."""
    _pricing.check("sectors_dense", dim=rep.dim, N=rep.N)


def group_of(rep) -> SignGroup:
    """The :class:`SignGroup` of a checked ``rep``: monomial for a GT irrep, dense exponentials otherwise."""
    half = is_half_integer(rep)
    group = _gt_group(rep, half) if half is not None else None
    return group if group is not None else _dense_group(rep)


def _gt_group(rep, half: bool) -> SignGroup | None:
    N = rep.N
    ks, alphabet, degen = structure(N, half)
    ops = gt_rotations(rep, sorted(set(ks) | ({1} if N > 1 else set())))
    if ops is None:
        return None
    U = V = None
    if N >= 3:
        P = gt_patterns_of(rep)
        chain = {q: sps.csr_matrix(rep.generator((q, q + 1), format="csr")) for q in range(1, N)}
        U = None
        if has_reflection(rep, half):
            U = gt_reflection(rep, P, chain)
        V = real_structure(rep, P, chain, cartan=ks if half else None, reflection=U)
    return SignGroup(N, half, ks, alphabet, degen, [ops[k] for k in ks] + ([U] if U is not None else []),
                     monomial=True, centre=centre_scalar(ops, N, half), reflection=U is not None, antiunitary=V)


def _dense_group(rep) -> SignGroup:
    check_dense_dim(rep)
    dim = rep.dim
    D1 = sla.expm(np.pi * rep.generator((1, 2), format="dense"))
    sq = D1 @ D1
    if np.abs(sq - np.eye(dim)).max() < 1e-8:
        spinorial = False
    elif np.abs(sq + np.eye(dim)).max() < 1e-8:
        spinorial = True
    else:
        raise ValueError(
            f"{rep.name} mixes tensor and spinor parts (exp(2 pi X_12) is neither +1 nor -1); "
            f"decompose it and take the sectors of each part"
        )
    ks, alphabet, degen = structure(rep.N, spinorial)
    Ds = [sla.expm(np.pi * rep.generator((k, k + 1), format="dense")) for k in ks]
    return SignGroup(rep.N, spinorial, ks, alphabet, degen, Ds, monomial=False)
