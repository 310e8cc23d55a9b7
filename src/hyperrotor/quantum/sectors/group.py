r"""The symmetry group of the sectors: sign rotations, the reflection parity, the antiunitary, the characters.

:func:`group_of` builds the :class:`SignGroup` of a representation once (the monomial
matrices of a Gelfand-Tsetlin irrep, all found by one call of the private
``_gt_monomials.gt_symmetries``; or dense exponentials for other representations);
its :meth:`SignGroup.characters` are the labels of the :class:`Sector` s. For even
``N`` the reflection :math:`r = \mathrm{diag}(-1, 1, \dots, 1)` joins the group of a
tensor irrep whose highest weight ends in 0, and an antiunitary symmetry makes every
block real (package docstring).
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
from ..._equality import fields_equal
from ..._parallel import interruptible
from ..._weak_cache import WeakCache
from .._gt_monomials import Monomial, gt_symmetries

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
        eigenvalue of :math:`U_r`, package docstring). Spinor irreps: ``"E1/2"`` in
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

    __eq__ = fields_equal  # (field by field: the generated == refuses the basis, an array or a sparse matrix)
    __hash__ = None

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
    """The :class:`SignGroup` of a checked ``rep``: monomial for a GT irrep, dense exponentials otherwise
    (kept while ``rep`` lives: the sectors and :func:`~.spectra.check_symmetric` of one representation share it)."""
    return _GROUP_CACHE.get(rep, _group_of)


def _group_of(rep) -> SignGroup:
    half = is_half_integer(rep)
    group = _gt_group(rep, half) if half is not None else None
    return group if group is not None else _dense_group(rep)


#: rep -> its SignGroup, while it lives
_GROUP_CACHE = WeakCache()


def _gt_group(rep, half: bool) -> SignGroup | None:
    ks, alphabet, degen = structure(rep.N, half)
    sym = gt_symmetries(rep, ks, spinorial=half)
    if sym is None:
        return None
    U = sym.reflection
    return SignGroup(rep.N, half, ks, alphabet, degen, [sym.rotations[k] for k in ks] + ([U] if U is not None else []),
                     monomial=True, centre=sym.centre, reflection=U is not None, antiunitary=sym.antiunitary)


def _dense_group(rep) -> SignGroup:
    check_dense_dim(rep)
    dim = rep.dim
    # (each exponential takes seconds at the dense limit, in compiled code: Ctrl-C, _parallel.interruptible)
    D1 = interruptible(sla.expm, np.pi * rep.generator((1, 2), format="dense"))
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
    Ds = [interruptible(sla.expm, np.pi * rep.generator((k, k + 1), format="dense")) for k in ks]
    return SignGroup(rep.N, spinorial, ks, alphabet, degen, Ds, monomial=False)
