r"""Energy levels of rotor Hamiltonians (block-wise dense diagonalization)."""
from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np
import scipy.sparse as sps

from .. import _pricing, _validate
from .._equality import fields_equal, fields_unequal
from .._options import options
from .._parallel import interruptible
from .hamiltonian import blocks_of, hermitian_matrix, representation_of
from .sectors import check_symmetric, nonempty_blocks, restrict

__all__ = ["Spectrum", "spectrum"]


class Spectrum(NamedTuple):
    """Result of :func:`spectrum`: distinct levels and their multiplicities (unpacks as ``levels, degeneracies``)."""

    __eq__, __ne__ = fields_equal, fields_unequal  # (field by field: a tuple's == refuses array fields)
    __hash__ = None

    #: increasing distinct energies (the mean of each cluster)
    levels: np.ndarray
    #: multiplicity of each level (integers summing to the dimension)
    degeneracies: np.ndarray


def spectrum(H: Any, *, atol: float | None = None, rtol: float | None = None, rep: Any = None) -> Spectrum:
    r"""Energy levels of a Hermitian ``H`` with their degeneracies.

    ``H`` is split into its invariant blocks (:func:`~hyperrotor.quantum.symmetry_blocks`),
    and each block is diagonalized densely; a block larger than
    ``options["quantum_max_dense_dim"]`` (default 6000, the one home of that
    limit, shared with ``evolve(method="eigen")``) is refused.

    Parameters
    ----------
    H : qutip.Qobj, scipy.sparse matrix or ndarray
        Hermitian operator.
    atol, rtol : float, optional, keyword-only
        Eigenvalues closer than ``atol`` to their neighbour are one level
        (chained clustering of the sorted eigenvalues); without ``atol`` the
        threshold is ``rtol * max(1, max|E|)``, ``rtol`` defaulting to
        ``options["quantum_level_rtol"]`` (1e-9: far above the round-off of
        ``eigh``, ~``1e-15 * dim * max|E|``, and below any physical splitting of interest).
        ``atol >= 0``; ``0 <= rtol < 1``; both are checked before any work.
    rep : Representation, keyword-only, optional
        The representation ``H`` was built from (default: the one
        :func:`~hyperrotor.quantum.rotor_hamiltonian` recorded on ``H``). When it
        is known and the largest sparsity block exceeds
        ``options["quantum_eigen_max_block"]`` (a generic inertia), the blocks
        are the symmetry sectors of :func:`hyperrotor.quantum.sectors.sector_blocks`,
        each diagonalized once and counted with its degeneracy.

    Returns
    -------
    Spectrum
        ``(levels, degeneracies)``: increasing distinct energies (the mean of each
        cluster) and the multiplicity of each (integers summing to ``dim``).

    Raises
    ------
    hyperrotor.BudgetError
        A block (sparsity block, or symmetry sector) over the dense budget
        (``options["quantum_max_dense_dim"]``), refused before any dense work.

    Examples
    --------
    >>> import numpy as np
    >>> levels, degeneracies = spectrum(np.diag([1.0, 2.0, 2.0]))
    >>> levels.tolist(), degeneracies.tolist()
    ([1.0, 2.0], [1, 2])
    """
    atol = _validate.positive("atol", atol, allow_none=True, allow_zero=True)
    rtol = _validate.tolerance("rtol", rtol, allow_none=True, allow_zero=True)
    mat, _ = hermitian_matrix(H)
    rep = rep if rep is not None else representation_of(H)
    if rep is not None:
        rep = _validate.representation("rep", rep, dim=mat.shape[0])
    blocks = blocks_of(mat)
    big = max(len(b) for b in blocks)
    evs = _sector_eigenvalues(mat, rep) if rep is not None and big > int(options["quantum_eigen_max_block"]) else None
    if evs is not None:
        return _levels(np.sort(evs), atol, rtol)
    _pricing.check("dense_diagonalization", dim=big, complex=np.iscomplexobj(mat.data),
                   cubes=sum(float(len(b)) ** 3 for b in blocks if len(b) > 1))
    evs = []
    for b in blocks:
        if len(b) == 1:
            evs.append(np.array([mat[b[0], b[0]].real]))
        else:
            evs.append(interruptible(np.linalg.eigvalsh, mat[b][:, b].toarray()))
    return _levels(np.sort(np.concatenate(evs).real), atol, rtol)


def _sector_eigenvalues(mat, rep) -> np.ndarray | None:
    """All eigenvalues (with multiplicity) from the symmetry sectors of ``rep``, or ``None`` if there are none."""
    parts = nonempty_blocks(rep, False)  # mat and rep are checked by spectrum
    if parts is None:
        return None
    check_symmetric(mat, rep)  # (a rep= that H does not respect gave wrong levels)
    # priced once, by the largest sector and all of them, before any work (the sectors of GT irreps are real blocks)
    sizes = [basis.shape[1] for basis, _, _ in parts]
    _pricing.check("dense_diagonalization", dim=max(sizes, default=0), cubes=sum(float(n) ** 3 for n in sizes),
                   complex=not all(sps.issparse(basis) for basis, _, _ in parts))
    evs = []
    for basis, degeneracy, _ in parts:
        block = restrict(mat, basis)  # mat is checked; real symmetric for GT irreps (cheaper eigvalsh)
        e = interruptible(np.linalg.eigvalsh, block)
        evs.append(np.repeat(e, int(degeneracy)))
    return np.concatenate(evs).real


def _levels(E: np.ndarray, atol: float | None, rtol: float | None) -> Spectrum:
    if atol is None:  # (atol and rtol are checked by spectrum)
        r = options["quantum_level_rtol"] if rtol is None else rtol
        tol = r * max(1.0, float(np.max(np.abs(E))))
    else:
        tol = atol
    cuts = np.nonzero(np.diff(E) > tol)[0] + 1
    groups = np.split(E, cuts)
    return Spectrum(np.array([g.mean() for g in groups]), np.array([g.size for g in groups], dtype=int))
