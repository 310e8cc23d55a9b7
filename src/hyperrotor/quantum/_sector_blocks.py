r"""The invariant blocks a :class:`~.sector_propagator.SectorPropagator` runs in.

A block is one piece of the space that ``H`` leaves invariant: a symmetry sector (an orthonormal
basis, :func:`~hyperrotor.quantum.symmetry_sectors`) or a sparsity block (an index array). This
module holds what one block needs: the sector bases of a representation (cached while it lives)
and the price of building them, the blocks ``B^H H B`` restricted from one product, a block's
propagation with its engine and its own rent-or-buy rule (Krylov until the work spent and
estimated exceeds the cost of ``eigh``, then its cached eigendecomposition), and the
:func:`~hyperrotor._parallel.map_rows` task over blocks. The propagator above builds the blocks,
chooses between renting on the whole space and buying the sectors, and gathers the states.
"""
from __future__ import annotations

from typing import Any

import numpy as np
import scipy.sparse as sps

from .. import _pricing
from .._parallel import interruptible
from .._weak_cache import WeakCache
from .._options import options as _options
from .propagators import Eigen, Krylov
from .sectors import nonempty_blocks, restrict

__all__: list[str] = []  # package-internal: Block, sector_blocks, sector_bases, sector_price, propagate_blocks

#: Flop model of the rent-or-buy rule (measured on this machine: eigh ~ 10 n^3 for a real block, 4x complex).
_EIGH_FLOPS = 10.0


def sector_bases(rep: Any) -> list | None:
    """Orthonormal bases of the non-empty sectors of ``rep`` spanning the space, or None (no usable sectors).

    Kept while ``rep`` lives (a weak reference): every propagator of the same
    representation (several bodies, :func:`~hyperrotor.quantum.ehrenfest_time`) reuses them.
    """
    return _SECTOR_CACHE.get(rep, _sector_bases)


def _sector_bases(rep: Any) -> list | None:
    parts = nonempty_blocks(rep, True)
    return None if parts is None else [B for B, _, _ in parts]


#: rep -> its sector bases, while it lives
_SECTOR_CACHE = WeakCache()

#: The price of the sector route in the units of the whole-space Krylov work (the propagator's ``_lanczos_work``),
#: measured on this machine for so(5) (9, 3) (dim 2401, 16 real sectors of ~150, nnz(H) 143,817; CPU times at
#: ~8.5e9 units/s): building the sectors 26-30 ms (per basis vector and sector), restricting H to them 14-16 ms
#: (per nonzero of H), the real eigh of the blocks 23 ms (per n^3 of a block; 4x for complex blocks).
_SECTOR_WORK = 6.0e3
_RESTRICT_WORK = 9.0e2
_SECTOR_EIGH_WORK = 3.6


def sector_price(M: sps.csr_matrix, rep: Any) -> float:
    """Estimated work of the sector route of ``M``: build the sectors of ``rep`` (unless cached), restrict
    ``M`` to them and diagonalize ``2^(N-1)`` blocks of ``dim / 2^(N-1)`` (real for a GT irrep)."""
    n_sec = 2.0 ** (rep.N - 1)
    build = 0.0 if rep in _SECTOR_CACHE else _SECTOR_WORK * rep.dim * n_sec
    cplx = 1.0 if rep.highest_weight is not None else 4.0
    return build + _RESTRICT_WORK * M.nnz + cplx * n_sec * _SECTOR_EIGH_WORK * (rep.dim / n_sec) ** 3


#: Sector bases restricted together in one product, up to this many columns (the product's off-diagonal
#: blocks are round-off but cost memory: the 16 sectors of a dim-2401 irrep in one product, the ~3,300
#: of the dim-52,976 irrep (20, 10) one at a time).
_GROUP_COLUMNS = 4096


def sector_block_list(M: sps.csr_matrix, bases: list) -> list[sps.csr_matrix]:
    """The sparse blocks ``B^H M B`` of the sector ``bases`` (each real when its imaginary part is round-off,
    as in the real sectors), from one product with the side-by-side bases: the diagonal blocks of
    ``P^H M P``, ``P = [B_1, B_2, ...]`` (the sectors are invariant: off the diagonal only round-off),
    for groups of up to ``_GROUP_COLUMNS`` columns."""
    if not all(sps.issparse(B) for B in bases):
        blocks = [restrict(M, B, dense=False) for B in bases]
    else:
        blocks, i = [], 0
        while i < len(bases):  # groups of at most _GROUP_COLUMNS columns (or one sector): bounded memory
            j, cols = i + 1, bases[i].shape[1]
            while j < len(bases) and cols + bases[j].shape[1] <= _GROUP_COLUMNS:
                cols += bases[j].shape[1]
                j += 1
            P = sps.hstack(bases[i:j], format="csc")
            K = (sps.csr_matrix(P.conj().T) @ (M @ P)).tocsr()
            K = ((K + K.conj().T) * 0.5).tocsr()  # exactly Hermitian
            ends = np.cumsum([0] + [B.shape[1] for B in bases[i:j]])
            blocks += [K[a:b, a:b] for a, b in zip(ends[:-1], ends[1:])]
            i = j
    out = []
    for blk in blocks:
        blk = sps.csr_matrix(blk)
        if blk.dtype.kind == "c" and blk.nnz and np.abs(blk.data.imag).max() <= 1e-13 * np.abs(blk.data).max():
            blk = sps.csr_matrix(blk.real.copy())  # real sectors: the imaginary part is round-off (copy: contiguous data)
        blk.eliminate_zeros()
        blk.sort_indices()  # a slice of the product comes unsorted
        out.append(blk)
    return out


def _times(A: np.ndarray, Z: np.ndarray) -> np.ndarray:
    """``A @ Z`` for complex ``Z``; a real ``A`` multiplies the (Re, Im) pairs in real arithmetic (4x fewer flops)."""
    if A.dtype.kind == "f" and Z.dtype == np.complex128:
        Z = np.ascontiguousarray(Z)
        shape = Z.shape
        out = A @ Z.view(np.float64).reshape(shape[0], -1)
        return out.view(np.complex128).reshape((A.shape[0],) + shape[1:])
    return A @ Z


class Block:
    """One invariant block: its coordinates in the full space, its matrix (lazy), its caches."""

    def __init__(self, owner: Any, basis: np.ndarray | Any, engine: Any, pieces: list | None = None):
        self.owner = owner
        self.basis = basis  # int index array (a sparsity block) or a (dim, n) sector basis
        self.indexed = isinstance(basis, np.ndarray) and basis.ndim == 1
        self.engine = engine  # a Propagator instance; None: a diagonal part (all blocks of size 1)
        self.pieces = pieces  # local index arrays of the sparsity blocks merged into one Krylov problem
        self.n = int(basis.shape[0] if self.indexed else basis.shape[1])
        self._matrix = None
        self._adjoint = None
        self.diag = owner.diagonal[basis] if engine is None else None
        self.eig = None
        self.work = 0.0  # Krylov flops spent on this block (rent-or-buy rule)
        self.group: list | None = None  # the sector blocks whose matrices come from one product (sector_blocks)

    def __getstate__(self):  # pickled to dask workers: without the owner's caches of other blocks
        state = dict(self.__dict__)
        state["owner"] = None
        state["_matrix"] = self.matrix
        state["group"] = None
        return state

    @property
    def matrix(self) -> sps.csr_matrix:
        if self._matrix is None:
            M = self.owner.matrix
            if self.indexed:
                self._matrix = M[self.basis][:, self.basis].tocsr()
            else:
                restrict_together(M, self.group or [self])
        return self._matrix

    def coords(self, vec: np.ndarray) -> np.ndarray:
        if self.indexed:
            return vec[self.basis]
        if self._adjoint is None:
            self._adjoint = sps.csr_matrix(self.basis.conj().T) if sps.issparse(self.basis) else self.basis.conj().T
        out = np.asarray(self._adjoint @ vec)
        return out.reshape(-1) if vec.ndim == 1 else out

    def embed(self, out: np.ndarray, C: np.ndarray) -> None:
        """Add the block's states ``C`` (n, nt) to ``out`` (dim, nt)."""
        if self.indexed:
            out[self.basis] = C
        else:
            out += self.basis @ C

    # ---- propagation ------------------------------------------------------
    def _krylov_flops(self, span: float, hbar: float) -> float:
        """Estimated flops of Lanczos over ``span``: matvecs ~ m (1 + width span / (m hbar)), each nnz + m n."""
        A = self.matrix
        d = A.diagonal().real
        r = np.asarray(abs(A).sum(axis=1)).ravel() - np.abs(d)
        width = float(np.max(d + r) - np.min(d - r)) if self.n else 0.0
        m = self._krylov_dim()
        matvecs = m * (1.0 + width * span / (m * abs(hbar)))
        return matvecs * (8.0 * A.nnz + 16.0 * m * self.n)

    def _krylov_dim(self) -> int:
        m = getattr(self.engine, "opts", {}).get("krylov_dim")
        return min(self.n, int(_options["quantum_krylov_dim"] if m is None else m))

    def _eigh_flops(self, nt: int) -> float:
        cplx = 4.0 if self.matrix.dtype.kind == "c" else 1.0
        return cplx * _EIGH_FLOPS * self.n**3 + 8.0 * nt * self.n**2

    def diagonalize(self, stats: dict) -> None:
        E, V = interruptible(np.linalg.eigh, self.matrix.toarray())  # LAPACK ?syevd: real for the real sectors
        stats["n_eigh"] = stats.get("n_eigh", 0) + 1
        self.eig = (E, V)

    def propagate(self, c0: np.ndarray, t: np.ndarray, hbar: float, adaptive: bool) -> tuple[np.ndarray, dict, str]:
        """States of the block at the times ``t`` (``t[0]`` the time of ``c0``): ``(C (n, nt), stats, method)``."""
        stats: dict = {}
        tau = t - t[0]
        if self.engine is None:
            stats["populated_dim"] = int(np.count_nonzero(np.abs(c0) > 1e-15 * float(np.abs(c0).max())))
            return np.exp((-1j / hbar) * np.outer(self.diag, tau)) * c0[:, None], stats, "diagonal"
        if self.eig is None and isinstance(self.engine, Eigen):
            _pricing.check("dense_diagonalization", dim=self.n, complex=self.matrix.dtype.kind == "c")
            self.diagonalize(stats)
        elif self.eig is None and adaptive and self.work + self._krylov_flops(float(tau[-1]), hbar) > self._eigh_flops(t.size):
            try:  # buy only what the budgets allow (quantum_max_dense_dim, max_memory_bytes, max_seconds)
                _pricing.check("dense_diagonalization", dim=self.n, complex=self.matrix.dtype.kind == "c")
                self.diagonalize(stats)
            except _pricing.BudgetError:
                pass
        if self.eig is not None:
            E, V = self.eig
            c = _times(V.conj().T, c0)
            return _times(V, np.exp((-1j / hbar) * np.outer(E, tau)) * c[:, None]), stats, "eigen"
        sub, local = self.matrix, None
        if self.pieces is not None and len(self.pieces) > 1:  # merged sparsity blocks: only the populated ones
            scale = float(np.abs(c0).max())
            keep = [p for p in self.pieces if np.any(np.abs(c0[p]) > 1e-15 * scale)]
            if len(keep) < len(self.pieces):
                local = np.sort(np.concatenate(keep))
                sub = sub[local][:, local].tocsr()
        gen = self.engine.propagate(sub, c0 if local is None else c0[local], t, hbar, stats)
        C = np.empty((sub.shape[0], t.size), dtype=complex)
        for k in range(t.size):
            C[:, k] = next(gen)
        if isinstance(self.engine, Krylov):
            m = self._krylov_dim()
            self.work += stats.get("n_matvec", 0) * (8.0 * sub.nnz + 16.0 * m * sub.shape[0])
        stats["populated_dim"] = sub.shape[0]
        if local is not None:
            full = np.zeros((self.n, t.size), dtype=complex)
            full[local] = C
            C = full
        return C, stats, self.engine.name


def sector_blocks(owner: Any, bases: list, engine: Any) -> list[Block]:
    """The blocks of the sector ``bases`` (each with its part of ``engine``'s plan), one group: the first
    matrix asked for restricts them all from one product (:func:`restrict_together`)."""
    out = [Block(owner, B, eng) for B in bases for _, eng in engine.plan([np.arange(B.shape[1])])]
    for b in out:
        b.group = out
    return out


def restrict_together(M: sps.csr_matrix, blocks: list[Block]) -> None:
    """Give every sector block of ``blocks`` without a matrix its matrix, all from one product
    (:func:`sector_block_list`)."""
    todo = [b for b in blocks if not b.indexed and b._matrix is None]
    for b, blk in zip(todo, sector_block_list(M, [b.basis for b in todo])):
        b._matrix = blk


def propagate_blocks(idx: np.ndarray, blocks: list, coords: list, t: np.ndarray, hbar: float,
                     adaptive: bool) -> np.ndarray:
    """The :func:`~hyperrotor._parallel.map_rows` task: propagate the blocks ``idx`` (an object array of results)."""
    out = np.empty(len(idx), dtype=object)
    for k, i in enumerate(idx):
        out[k] = blocks[i].propagate(coords[i], t, hbar, adaptive)
    return out

