r"""Hamiltonian blocks of the sectors and their spectra (the hooks of ``spectrum`` and ``evolve``).

Public-in-package (for :mod:`hyperrotor.quantum.spectrum` and :mod:`hyperrotor.quantum.evolve`):
:func:`check_symmetric` (``H`` has the symmetry the sectors of ``rep`` rest on; every route that
splits ``H`` by the sectors of a ``rep`` runs it), and, trusted (their callers have checked ``H``,
``rep`` and the state), :func:`restrict`, :func:`nonempty_blocks`.
"""
from __future__ import annotations

from contextlib import nullcontext
from fractions import Fraction
from typing import Any

import numpy as np
import scipy.sparse as sps

from ... import _pricing, _validate
from ..._equality import values_equal
from ..._weak_cache import WeakCache
from .._gt_monomials import Monomial
from ..hamiltonian import hermitian_matrix, rotor_matrix
from .construction import pi_rotation, sectors_of
from .group import Sector, group_of

__all__ = ["SectorSpectra", "sector_blocks", "sector_hamiltonian", "evolution_blocks", "sector_spectra"]

#: relative residual above which a basis is not orthonormal or H does not leave a sector invariant
#: (round-off of the checks is ~1e-15 times the number of nonzeros per column, far below)
_RESIDUAL = 1e-8


class SectorSpectra(dict):
    """``{label: sorted levels}`` of :func:`sector_spectra`, with the degeneracy of each sector.

    Attributes
    ----------
    degeneracies : dict
        ``{label: d}``: each level of sector ``label`` is a level of the full
        Hamiltonian ``d`` times (1 for tensor irreps).
    """

    def __init__(self, levels: dict, degeneracies: dict):
        super().__init__(levels)
        self.degeneracies = dict(degeneracies)

    def __eq__(self, other: object) -> bool:  # (dict's == compares the level arrays with ==, which NumPy refuses)
        if not isinstance(other, SectorSpectra):
            return NotImplemented
        return values_equal(dict(self), dict(other)) and self.degeneracies == other.degeneracies

    def __ne__(self, other: object) -> bool:
        eq = self.__eq__(other)
        return eq if eq is NotImplemented else not eq

    __hash__ = None  # (a dict)

    def eigenvalues(self) -> np.ndarray:
        """All eigenvalues of the full Hamiltonian, with multiplicity, sorted."""
        parts = [np.repeat(v, self.degeneracies[k]) for k, v in self.items()]
        return np.sort(np.concatenate(parts)) if parts else np.zeros(0)


# ----------------------------------------------------------------------------
# checks at the public doors
# ----------------------------------------------------------------------------
def _hamiltonian_matrix(H, dim: int | None = None) -> sps.csr_matrix:
    """``H`` (Qobj, sparse or dense) as a finite Hermitian CSR matrix, of dimension ``dim`` when given."""
    M, _ = hermitian_matrix(H, "H")
    if dim is not None and M.shape[0] != dim:
        raise ValueError(f"H has dimension {M.shape[0]} but the representation has dimension {dim}")
    return M


def _probe(n: int, k: int = 2) -> np.ndarray:
    """``k`` fixed pseudo-random unit columns of length ``n`` (reproducible cheap residual checks)."""
    g = np.random.default_rng(20261125)
    X = g.standard_normal((n, k)) + 1j * g.standard_normal((n, k))
    return X / np.linalg.norm(X, axis=0)


def check_symmetric(M: sps.csr_matrix, rep) -> None:
    r"""``H`` (``M``) commutes with the symmetries the sectors of ``rep`` rest on, else ``ValueError``.

    The rotations by :math:`\pi` in the planes :math:`(k, k+1)` (:func:`pi_rotation`), which generate the
    sign rotations: they define the sectors and force the degeneracy the copies of a spinor sector share;
    and the reflection :math:`\mathrm{diag}(-1, 1, \dots, 1)` of even-N irreps whose sectors carry a parity.
    Checked as :math:`\|H D x - D H x\| \le 10^{-8} \|H x\|` for two random unit ``x``. A rotor Hamiltonian of ``rep``
    passes; a field term or ``rep`` in another basis than ``H`` is refused (the sector route would return
    wrong levels and states without a sign: up to 0.5 in a state, 43 in a level). A ``rep`` without a sector
    construction (mixed tensor and spinor parts, over the dense limit) passes: nothing is split by its sectors.
    """
    _pricing.check("gt_sectors", dim=rep.dim, N=rep.N)  # (the group's price: the sectors' own, checked first)
    try:
        group_of(rep)  # (kept with rep; the sectors use it too)
    except ValueError:  # no sector construction (mixed tensor/spinor, over the dense limit): nothing to split by
        return
    ops = _SYMMETRIES.get(rep, _symmetries)
    X = _probe(rep.dim)
    HX = M @ X
    scale = max(float(np.linalg.norm(HX, axis=0).max()), 1e-300)
    for what, D in ops:
        r = float(np.linalg.norm(M @ (D @ X) - D @ HX, axis=0).max())
        if r > _RESIDUAL * scale:
            raise ValueError(f"H does not commute with {what} of {rep.name} (relative residual {r / scale:.2e}), "
                             f"so its symmetry sectors do not split H: is H a rotor Hamiltonian of this "
                             f"representation, in its basis? (Without rep=, H is split by its sparsity blocks.)")


def _symmetries(rep) -> list:
    """``[(name, sparse or dense matrix)]``: what :func:`check_symmetric` checks ``H`` against."""
    g = group_of(rep)  # (its operators: the rotations of the planes (k, k+1), k in g.ks, then the reflection)
    mats = [D.matrix() if isinstance(D, Monomial) else D for D in g.ops]
    ops = [(f"the rotation by pi in the plane ({k}, {k + 1})",
            mats[g.ks.index(k)] if k in g.ks else pi_rotation(rep, (k, k + 1))) for k in range(1, rep.N)]
    if g.reflection:
        ops.append(("the reflection diag(-1, 1, ..., 1)", mats[-1]))
    return ops


#: rep -> the operators H must commute with, while it lives
_SYMMETRIES = WeakCache()


def _check_orthonormal(B) -> None:
    r""":math:`\|B^\dagger B x - x\|` for two random ``x``: a non-orthonormal basis is refused."""
    if B.shape[1] == 0:
        return
    X = _probe(B.shape[1])
    r = float(np.linalg.norm(B.conj().T @ (B @ X) - X, axis=0).max())
    if r > _RESIDUAL:
        raise ValueError(f"the sector basis does not have orthonormal columns (|B^H B x - x| = {r:.2e} for a "
                         f"random unit x); pass a Sector from symmetry_sectors or orthonormal columns")


def _check_invariant(M: sps.csr_matrix, B, what: str) -> None:
    r""":math:`\|H B x - B B^\dagger H B x\| \le 10^{-8} \|H B x\|` for two random ``x``."""
    if B.shape[1] == 0:
        return
    Y = M @ (B @ _probe(B.shape[1]))
    R = Y - B @ (B.conj().T @ Y)
    scale = float(np.linalg.norm(Y, axis=0).max())
    r = float(np.linalg.norm(R, axis=0).max())
    if r > _RESIDUAL * max(scale, 1e-300):
        raise ValueError(f"H does not leave {what} invariant (relative residual {r / scale:.2e}): it does not "
                         f"commute with the sign rotations; is it a rotor Hamiltonian of this representation?")


def _sector_basis(sector, dim: int):
    """The basis of a :class:`Sector`, or a basis matrix given directly, checked: shape (dim, n), finite."""
    if isinstance(sector, Sector):
        B = sector.basis
    elif sps.issparse(sector):
        B = sps.csc_matrix(sector)
        if B.dtype.kind not in "biufc" or not np.all(np.isfinite(B.data)):
            raise ValueError(f"the sector basis must be a finite numeric matrix, got dtype {B.dtype} or non-finite entries")
    elif isinstance(sector, (np.ndarray, list, tuple)):
        B = _validate.finite_array("sector", sector, dtype=complex if np.iscomplexobj(sector) else float)
    else:
        raise TypeError(f"sector must be a Sector (symmetry_sectors) or a basis matrix (dim x n), got "
                        f"{_validate.fmt(sector)} of type {type(sector).__name__}")
    if B.ndim != 2 or B.shape[0] != dim:
        raise ValueError(f"the sector basis must have shape ({dim}, n) for H of dimension {dim}, got shape {B.shape}")
    if not isinstance(sector, Sector):
        _check_orthonormal(B)
    return B


# ----------------------------------------------------------------------------
# blocks
# ----------------------------------------------------------------------------
def sector_hamiltonian(H, sector, *, format: str = "dense"):
    r"""The block :math:`B^\dagger \hat H B` of ``H`` in ``sector`` (a :class:`Sector` or its basis).

    Parameters
    ----------
    H : qutip.Qobj, scipy.sparse matrix or ndarray
        Hermitian and finite (checked: a non-Hermitian ``H`` is refused, not
        symmetrized), leaving the sector invariant (any rotor Hamiltonian of the
        sector's representation; checked with a residual on two random vectors).
    sector : Sector or basis matrix (dim x n, orthonormal columns: checked the same way)
    format : {"dense", "csr"}, keyword-only
        A dense Hermitian ndarray, or the sparse product (CSR).

    Returns
    -------
    ndarray or scipy.sparse.csr_matrix
        Real symmetric (float64) when the imaginary part vanishes to round-off
        (always the case for the sectors of GT irreps, :attr:`Sector.real`), complex
        Hermitian otherwise. With a sparse basis the product costs
        :math:`O(\mathrm{nnz}(H))`: only the rows of ``H`` in the support of the
        basis are touched.
    """
    fmt = _validate.choice("format", format, ("dense", "csr"))
    M = _hamiltonian_matrix(H)
    B = _sector_basis(sector, M.shape[0])
    _check_invariant(M, B, "the sector")
    return restrict(M, B, dense=fmt == "dense", real=isinstance(sector, Sector) and sector.real)


def restrict(M: sps.csr_matrix, B, *, dense: bool = True, real: bool = False):
    """:func:`sector_hamiltonian` of a checked CSR ``M`` and basis ``B`` (``real``: a real-gauged basis)."""
    if sps.issparse(B):
        B = sps.csc_matrix(B)
        rows = np.unique(B.indices)  # the support S: B^H H B = W^H H[S, S] W
        W = B[rows]
        Hs = (sps.csr_matrix(W.conj().T) @ (M[rows][:, rows] @ W)).tocsr()
        Hs = ((Hs + Hs.conj().T) * 0.5).tocsr()  # exactly Hermitian, symmetrized while sparse (one dense copy)
        if np.iscomplexobj(Hs.data) and Hs.nnz:
            Hs = _real_part(Hs, Hs.data, real)
        return Hs.toarray() if dense else Hs
    else:
        Hs = np.asarray(B).conj().T @ (M @ B)
        if not dense:
            return sps.csr_matrix(Hs)
    Hs = 0.5 * (Hs + Hs.conj().T)
    if np.iscomplexobj(Hs) and Hs.size:
        Hs = _real_part(Hs, Hs, real)
    return Hs


def _real_part(Hs, data, real: bool):
    """``Hs.real`` when the imaginary part of ``data`` is round-off; an error in a real sector otherwise."""
    scale = float(np.abs(data).max()) if data.size else 0.0
    imag = float(np.abs(data.imag).max()) if data.size else 0.0
    if imag <= 1e-13 * scale:
        return Hs.real.copy() if sps.issparse(Hs) else np.ascontiguousarray(Hs.real)
    if real:
        raise ValueError(
            f"H is not real in this real sector basis (imaginary part {imag:.2e} of {scale:.2e}): it does not "
            f"commute with the antiunitary symmetry; is it a rotor Hamiltonian of this representation?"
        )
    return Hs


def sector_blocks(H, rep, *, complete: bool = False):
    r"""Invariant orthonormal blocks of ``H`` from the sign rotations of ``rep``: the hook for ``spectrum``/``evolve``.

    Parameters
    ----------
    H : qutip.Qobj, scipy.sparse matrix or ndarray
        A rotor Hamiltonian of ``rep`` (commuting with every :func:`pi_rotation`;
        checked: ``H`` must leave every block invariant, residual on two random vectors).
    rep : Representation
    complete : bool, default False
        ``False``: one copy per isotypic type (for spectra, see :func:`symmetry_sectors`);
        ``True``: the blocks span the whole space (for time evolution).

    Returns
    -------
    list of (basis, weight, label) or None
        ``basis`` a CSC (dim x n) matrix of orthonormal columns (dense ndarray for
        non-GT representations). ``weight``: how many times each eigenvalue of the
        block :func:`sector_hamiltonian` ``(H, basis)`` occurs in the spectrum of ``H``
        from this block's isotypic type: the forced degeneracy with
        ``complete=False``, 1 with ``complete=True`` (then the copies are all
        listed). Empty sectors are left out. ``None`` when ``rep`` has no usable sector
        construction (too large for the dense fallback, or mixed tensor/spinor), in
        which case the caller should fall back to its own blocks.
    """
    rep = _validate.representation("rep", rep)
    complete = _validate.flag("complete", complete)
    M = _hamiltonian_matrix(H, rep.dim)
    parts = nonempty_blocks(rep, complete)
    if parts is not None:
        check_symmetric(M, rep)
    for B, _, lab in parts or ():
        _check_invariant(M, B, f"the sector {lab!r}")
    return parts


def nonempty_blocks(rep, complete: bool):
    """:func:`sector_blocks` of a checked ``rep`` (trusted: no check of H, for spectrum and evolve).

    Over the budget of the construction (``"gt_sectors"``): BudgetError. No usable
    sectors (mixed tensor/spinor, or over the dense-fallback limit): ``None``.
    """
    _pricing.check("gt_sectors", dim=rep.dim, N=rep.N)
    try:
        secs = sectors_of(rep, complete)
    except ValueError:
        return None
    return [(s.basis, 1 if complete else s.degeneracy, s.label) for s in secs if s.dim]


def evolution_blocks(H, rep, psi0):
    r"""The populated sectors of ``psi0``: ``[(basis, block, c0)]`` for propagating in sector coordinates.

    ``H`` commutes with every sector projector, so
    :math:`e^{-iHt/\hbar}\psi_0 = \sum_s B_s\, e^{-iH_s t/\hbar} c_s` with
    :math:`c_s = B_s^\dagger \psi_0` and :math:`H_s = B_s^\dagger H B_s`
    (``block``, CSR, real for the sectors of GT irreps); the sectors of
    ``symmetry_sectors(rep, complete=True)`` span the whole space. Sectors where
    ``psi0`` vanishes are left out; ``H`` must leave each populated sector invariant
    (checked as in :func:`sector_blocks`). ``None`` when ``rep`` has no usable sectors
    (see :func:`sector_blocks`). :func:`hyperrotor.quantum.evolve` does this itself.
    """
    rep = _validate.representation("rep", rep)
    M = _hamiltonian_matrix(H, rep.dim)
    v = _validate.ket("psi0", psi0, rep.dim, of="the representation")
    parts = nonempty_blocks(rep, True)
    if parts is None:
        return None
    scale = float(np.abs(v).max()) if v.size else 0.0
    out = []
    for B, _, _ in parts:
        c0 = np.asarray(B.conj().T @ v).reshape(-1)
        if not np.any(np.abs(c0) > 1e-15 * scale):
            continue
        _check_invariant(M, B, "a populated sector")
        block = restrict(M, B, dense=False)
        block.eliminate_zeros()
        out.append((B, block, c0.astype(complex)))
    return out


# ----------------------------------------------------------------------------
# spectra
# ----------------------------------------------------------------------------
def _levels_task(idx: np.ndarray, H, bases: list, width: int, blas_threads: int | None = None) -> np.ndarray:
    """Sorted eigenvalues of the sector blocks ``idx``, NaN-padded to ``width`` (a map_rows task).

    ``blas_threads`` limits the BLAS threads of this call (1 when several sectors run
    concurrently in threads, so that they do not oversubscribe the cores).
    """
    from threadpoolctl import threadpool_limits

    out = np.full((len(idx), width), np.nan)
    for r, i in enumerate(np.asarray(idx).tolist()):
        B, real = bases[i]
        if B.shape[1] == 0:
            continue
        Hs = restrict(H, B, real=real)
        limit = threadpool_limits(limits=blas_threads, user_api="blas") if blas_threads else nullcontext()
        with limit:
            # NumPy's eigvalsh (LAPACK ?syevd, divide and conquer) releases the GIL, scipy's holds it: run on a
            # worker thread (map_rows), it keeps Ctrl-C responsive (_parallel.interruptible)
            w = np.linalg.eigvalsh(Hs)
        out[r, : len(w)] = w
    return out


def _spec_task(idx: np.ndarray, spec: tuple, width: int) -> np.ndarray:
    """Dask task: rebuild the irrep, Hamiltonian and sectors from a small spec (cached per worker); one BLAS
    thread, as the threads of ``workers > 1`` (the same levels bit for bit, whatever the worker's environment)."""
    H, bases = _cached_problem(spec)
    return _levels_task(idx, H, bases, width, 1)


_PROBLEM_CACHE: dict = {}


def _cached_problem(spec):
    """``(H, sector bases)`` of ``irrep(N, hw)`` on a worker, checked against the caller's sectors (``layout``:
    their labels and dimensions, in order): the levels are read back by position."""
    if spec not in _PROBLEM_CACHE:
        from ..gelfand_tsetlin import irrep

        N, hw, moments, hbar, layout = spec
        rep = irrep(N, [Fraction(x) for x in hw], max_dim=10**7)
        H = rotor_matrix(rep.generators(format="csr"), np.array(moments), hbar)
        secs = sectors_of(rep, False)
        mine = tuple((s.label, s.dim) for s in secs)
        if mine != layout:  # (a GT irrep is rebuilt exactly; a mismatch would pair levels with other sectors)
            raise RuntimeError(f"the worker's irrep({N}, {hw}) has the sectors {mine}, the caller's representation "
                               f"{layout}: no levels returned")
        _PROBLEM_CACHE.clear()
        _PROBLEM_CACHE[spec] = (H, [(s.basis, s.real) for s in secs])
    return _PROBLEM_CACHE[spec]


def sector_spectra(
    rep,
    body,
    *,
    hbar=1,
    workers: int | None = None,
    client: Any = None,
    progress: bool | None = None,
) -> SectorSpectra:
    r"""Every level of the rotor :math:`\hat H = \sum (\hat L^{ij})^2/(2I_{ij})` of ``rep``, sector by sector.

    Parameters
    ----------
    rep : Representation
        Usually a Gelfand-Tsetlin irrep (:func:`~hyperrotor.quantum.irrep`).
    body : Inertia, RigidBody, mapping plane -> moment or sequence of N(N-1)/2 plane moments
        Any positive moments (the symmetry holds for every body).
    hbar : float, keyword-only, default 1
        :math:`\hat L^{ij} = -i\hbar X_{(ij)}`; levels scale as :math:`\hbar^2`.
    workers : int, optional
        Diagonalize the sectors concurrently on ``workers`` threads in this
        process, one sector per task (each thread uses one BLAS thread; see
        ``docs/scaling-out.md``). ``None`` or 1: one sector after the other, each
        with all BLAS threads. The levels do not depend on ``workers > 1`` or ``client``
        (one BLAS thread per sector on both: bit for bit on the same machine), but LAPACK
        with several BLAS threads rounds differently: ``None`` or 1 may differ from them in
        the last bits (~1e-13 relative, a review measured 9e-13 on so(5) (14, 7)), the price of
        using every core on one sector at a time (so(5) (20, 10) on 2 cores: 28.9 s, against 34 s
        with ``workers=2``).
    client : dask.distributed.Client, optional
        Run one task per sector on a dask cluster (irreducible ``rep`` only). For a
        Gelfand-Tsetlin irrep each worker rebuilds it as ``irrep(N, highest_weight)``,
        with the Hamiltonian and the sectors, once and caches them; any other
        irreducible representation (``vector_rep``, ``harmonic_rep``, ...) has sectors
        of its own (for even ``N`` the GT basis adds a reflection parity), so its
        Hamiltonian and sector bases, built here, go with the tasks.
    progress : bool or None
        tqdm bar over sectors (``None``: on a terminal, for runs over a second).

    Returns
    -------
    SectorSpectra
        ``{label: sorted eigenvalues of the sector block}`` in the order of
        :func:`symmetry_sectors`; ``.degeneracies[label]`` is the multiplicity of each
        of these levels in the full spectrum, and ``.eigenvalues()`` the full spectrum
        with multiplicity (``sum(len(v) * d) == rep.dim``).

    Raises
    ------
    hyperrotor.BudgetError
        A sector larger than ``options["sectors_max_block_dim"]``, or over the memory
        and time budgets (a real dense block of dimension ``n`` needs ``2 * 8 n^2``
        bytes), before any work.
    ValueError
        Bad body or hbar.

    Notes
    -----
    Each sector block is real symmetric for a GT irrep (real gauge, package
    docstring) and diagonalized densely (LAPACK ``dsyevd``), so the cost is
    :math:`\sum_s n_s^3` instead of :math:`\dim^3`: 16 sectors save a factor ~250 in
    so(5), and the real arithmetic another ~4. The 52,976-dimensional irrep (20, 10)
    needs 16 blocks of ~3,300 (see ``benchmarks/sectors.py``). Ctrl-C is honoured
    between sectors.
    """
    rep = _validate.representation("rep", rep)
    hbar = _validate.hbar(hbar)
    moments = _validate.moments(body, rep.N, name="body")
    workers = 1 if workers is None else _validate.integer("workers", workers, minimum=1)
    progress = _validate.flag("progress", progress, allow_none=True)
    client = _validate.client(client)
    _pricing.check("gt_sectors", dim=rep.dim, N=rep.N)
    secs = sectors_of(rep, False)
    big = max((s.dim for s in secs), default=0)
    _pricing.check("sector_spectra", dim=big, real=all(s.real for s in secs),
                   cubes=sum(float(s.dim) ** 3 for s in secs))
    from ..._parallel import map_rows

    idx = np.arange(len(secs))
    width = max(big, 1)
    if client is not None and rep.highest_weight is None:
        raise ValueError(
            f"client= needs an irreducible representation with a highest weight (the workers rebuild a "
            f"Gelfand-Tsetlin irrep as irrep(N, highest_weight)); {rep.name} has none"
        )
    if client is not None and group_of(rep).monomial:  # a GT irrep: the workers rebuild it from a few numbers
        layout = tuple((s.label, s.dim) for s in secs)
        spec = (rep.N, tuple(str(x) for x in rep.highest_weight), tuple(float(m) for m in moments), hbar, layout)
        lv = map_rows(_spec_task, idx, args=(spec, width), client=client, chunk_size=1,
                      progress=progress, desc="sectors")
    else:  # here, or on a cluster with the matrices built here (another irrep has sectors of its own)
        H = rotor_matrix(rep.generators(format="csr"), moments, hbar)  # the matrix of rotor_hamiltonian
        bases = [(s.basis, s.real) for s in secs]
        blas = 1 if client is not None or workers > 1 else None
        lv = map_rows(_levels_task, idx, args=(H, bases, width, blas), workers=workers, client=client, chunk_size=1,
                      progress=progress, desc="sectors")  # (workers: threads here; a client has its own)
    levels = {s.label: lv[i, : s.dim].copy() for i, s in enumerate(secs)}
    return SectorSpectra(levels, {s.label: s.degeneracy for s in secs})
