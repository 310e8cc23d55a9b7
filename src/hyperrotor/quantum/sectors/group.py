r"""The symmetry group of the sectors: sign rotations, their characters, and the reflection parity.

Labels and characters of :class:`Sector` (see the package docstring for the theory),
and, for even ``N``, the reflection :math:`r = \mathrm{diag}(-1, 1, \dots, 1)` in the
Gelfand-Tsetlin basis (:func:`gt_reflection`).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np
import scipy.sparse as sps

from .._gt_monomials import Monomial

try:
    from .._gt_monomials import gt_intertwiner
except ImportError:  # TEMPORARY until qreps lands gt_intertwiner
    from .._gt_monomials import _flip_perm, _intertwining_phases, _monomial_residual

    def gt_intertwiner(rep, P, chain, rows, sigma, *, conj):
        try:
            perm = _flip_perm(rep, P, rows)
            U = Monomial(perm, _intertwining_phases(chain, perm, sigma, conj))
        except (ArithmeticError, ValueError):
            return None
        return None if _monomial_residual(U, chain, sigma, conj) > 1e-9 else U

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
