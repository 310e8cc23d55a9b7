r"""Construction of the sectors: projections in the Gelfand-Tsetlin basis, the real gauge, the dense fallback.

See the package docstring ("Construction without dense matrices", "Real blocks"); the
group (monomial matrices, reflection, antiunitary, characters) comes from :mod:`.group`.
"""
from __future__ import annotations

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sps
from scipy.sparse.csgraph import connected_components

from ... import _pricing, _validate
from ..._parallel import interruptible
from .._gt_monomials import Monomial, gt_rotations
from .group import Sector, check_dense_dim, eig_text, group_of

__all__ = ["pi_rotation", "symmetry_sectors"]


def pi_rotation(rep, plane, *, format: str = "csr"):
    r"""The rotation by :math:`\pi` in ``plane``: :math:`D = \exp(\pi X_{(ij)})`.

    Parameters
    ----------
    rep : Representation
    plane : (i, j)
        1-based, ``i < j``.
    format : {"csr", "dense"}

    Returns
    -------
    scipy.sparse.csr_matrix or ndarray
        Unitary; :math:`D X_{(kl)} D^{-1} = s_k s_l X_{(kl)}` with ``s = -1`` on
        ``i, j``; :math:`D^2 = +1` on tensor irreps, :math:`-1` on spinor irreps.
        For a Gelfand-Tsetlin irrep and a chain plane ``(k, k+1)`` it is built as
        the monomial matrix of the package docstring (any dimension); otherwise
        (other planes or other representations) by a dense matrix exponential,
        limited to ``options["sectors_dense_max_dim"]``.
    """
    rep = _validate.representation("rep", rep)
    i, j = _validate.plane(plane, rep.N)
    fmt = _validate.choice("format", format, ("csr", "dense"))
    if fmt == "dense":
        _pricing.check("dense_matrix", dim=rep.dim)
    if j == i + 1:
        rot = gt_rotations(rep, [i])
        if rot is not None:
            M = rot[i].matrix()
            return M.toarray() if fmt == "dense" else M
    check_dense_dim(rep)
    E = interruptible(sla.expm, np.pi * rep.generator((i, j), format="dense"))  # (seconds at the dense limit)
    E[np.abs(E) < 1e-13] = 0.0
    return E if fmt == "dense" else sps.csr_matrix(E)


# ----------------------------------------------------------------------------
# projections
# ----------------------------------------------------------------------------
def _orbit_representatives(ops: list[Monomial], dim: int) -> np.ndarray:
    rows = np.concatenate([np.arange(dim)] + [np.arange(dim) for _ in ops])
    cols = np.concatenate([np.arange(dim)] + [D.perm for D in ops])
    G = sps.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(dim, dim))
    _, lab = connected_components(G, directed=False)
    first = np.full(lab.max() + 1, dim, dtype=np.int64)
    np.minimum.at(first, lab, np.arange(dim))
    return np.sort(first)


@_pricing.model("gt_sectors", "use a smaller irrep")
def _gt_sectors_cost(dim, N) -> tuple:
    """Building the sectors of a GT irrep: ~2^(N-2) sparse passes over the basis and ~2^N characters
    (measured on the 2-core test machine at load ~10, CPU: so(3) (99999,) 0.65 s, so(5) (20, 10) 0.5 s,
    so(6) (5, 2, 0) ~0.5 s, so(7) (3, 2, 1) 0.25 s; the model is within a factor 3 of each)."""
    d, n = float(dim), 2.0 ** (float(N) - 2)
    return (_pricing.Cost(f"building the symmetry sectors of a dimension-{dim} irrep of so({N})",
                          3e-6 * d * n + 0.02 * n, "max_seconds", "seconds"),
            _pricing.Cost(f"the sector bases and monomial group of a dimension-{dim} irrep", 64.0 * d * (n + 4),
                          "max_memory_bytes", "bytes"))


def _group_elements(ops: list[Monomial], reps_idx: np.ndarray) -> list[tuple[np.ndarray, np.ndarray, tuple]]:
    """Every product D_S of a subset S of the commuting monomials on the orbit representatives:
    ``(perm, phase, S)`` with ``D_S e_a = phase[j] e_perm[j]`` for ``a = reps_idx[j]``."""
    elems = [(reps_idx, np.ones(len(reps_idx), dtype=complex), ())]
    for i, D in enumerate(ops):
        elems += [(D.perm[perm], phase * D.phase[perm], S + (i,)) for perm, phase, S in elems]
    return elems


def _orbit_layout(elems: list, n: int, dim: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The entries shared by every projection of :func:`_project_monomial`: ``(rows, cols, slot)``.

    The images ``D_S e_a`` of the orbit representatives land on the sorted distinct
    positions ``(rows, cols)`` (column-major, the CSC order); ``slot`` sends each image to
    its position. Computed once per group: only the coefficients depend on the character.
    """
    r = np.concatenate([perm for perm, _, _ in elems]).astype(np.int64)
    c = np.tile(np.arange(n, dtype=np.int64), len(elems))
    key, slot = np.unique(c * dim + r, return_inverse=True)
    return key % dim, key // dim, slot.ravel()


def _project_monomial(elems: list, eigs: tuple, layout: tuple, n: int, dim: int) -> sps.csc_matrix:
    r"""Orthonormal basis of the joint eigenspace D_k = eigs[k] (sparse columns, one per orbit).

    :math:`\prod_k (1 + \bar\lambda_k D_k)/2 = 2^{-m} \sum_S \prod_{k \in S} \bar\lambda_k\, D_S`
    applied to one GT vector per orbit, all orbits at once (``layout``: :func:`_orbit_layout`).
    The coefficients and phases are dyadic numbers times powers of i, so the sums over
    the group are exact in any order.
    """
    rows, cols, slot = layout
    m = len(eigs)
    coef = [np.prod([np.conj(eigs[k]) for k in S]) / 2**m for _, _, S in elems]
    data = np.concatenate([c * phase for c, (_, phase, _) in zip(coef, elems)])
    x = np.empty(len(rows), dtype=complex)
    x.real = np.bincount(slot, weights=data.real, minlength=len(rows))
    x.imag = np.bincount(slot, weights=data.imag, minlength=len(rows))
    nz = np.abs(x) >= 1e-12
    x, r, c = x[nz], rows[nz], cols[nz]
    norms = np.sqrt(np.bincount(c, weights=np.abs(x) ** 2, minlength=n))  # in CSC order, as a column sum
    keep = norms > 1e-8
    new = np.cumsum(keep) - 1  # the kept columns, renumbered
    on = keep[c]
    x = x[on] * (1.0 / norms[c[on]])
    indptr = np.concatenate([[0], np.cumsum(np.bincount(new[c[on]], minlength=int(keep.sum())))])
    return sps.csc_matrix((x, r[on], indptr), shape=(dim, int(keep.sum())))


def _project_dense(Ds: list[np.ndarray], eigs: tuple, dim: int) -> np.ndarray:
    Pm = np.eye(dim, dtype=complex)
    for D, lam in zip(Ds, eigs):
        Pm = 0.5 * (Pm + np.conj(lam) * (D @ Pm))
    Pm = 0.5 * (Pm + Pm.conj().T)
    w, V = interruptible(np.linalg.eigh, Pm)  # (seconds at the dense limit: Ctrl-C, _parallel.interruptible)
    return V[:, w > 0.5]


def make_real(B: sps.csc_matrix, V: Monomial) -> sps.csc_matrix:
    r"""Columns fixed by :math:`A = VK` spanning the same space as ``B`` (A preserves the span).

    The columns of ``B`` have disjoint supports (one orbit of the monomial group
    each) and A maps orbits to orbits, so :math:`A b_j = \theta_j b_{\tau(j)}`.
    A fixed column (:math:`\tau(j) = j`) becomes :math:`e^{i\arg\theta_j/2} b_j`; a pair
    becomes :math:`(b_j + A b_j)/\sqrt2` and :math:`i(b_j - A b_j)/\sqrt2`. All on the
    stored entries: :math:`A b_j` has the entry :math:`\bar x\, v_r` in row :math:`\rho(r)`
    for each entry ``x`` of :math:`b_j` in row ``r`` (``V e_r = v_r e_{rho(r)}``), and
    :math:`\theta_j = b_{\tau(j)}^\dagger A b_j`.
    """
    n = B.shape[1]
    if n == 0:
        return B
    B = sps.csc_matrix(B)
    B.sort_indices()
    dim = B.shape[0]
    x, r = B.data, B.indices
    col = np.repeat(np.arange(n), np.diff(B.indptr))
    owner = np.full(dim, -1, dtype=np.int64)  # the column holding each row (disjoint supports)
    owner[r] = col
    value = np.zeros(dim, dtype=complex)
    value[r] = x
    ar, ax = V.perm[r], np.conj(x) * V.phase[r]  # A b_j: entries (ar, ax) in column col
    tau = owner[ar[B.indptr[:-1]]]  # the column each column's first image lands in
    if np.any(owner[ar] != tau[col]) or np.any(tau < 0) or np.any(np.diff(B.indptr)[tau] != np.diff(B.indptr)):
        raise ArithmeticError("the antiunitary symmetry does not map sector columns to sector columns (internal error)")
    target = value[ar]  # b_tau(j) at the rows of A b_j
    prod = np.conj(target) * ax
    theta = np.bincount(col, weights=prod.real, minlength=n) + 1j * np.bincount(col, weights=prod.imag, minlength=n)
    if (np.abs(np.abs(theta) - 1).max() > 1e-9 or np.abs(ax - theta[col] * target).max() > 1e-9
            or np.any(tau[tau] != np.arange(n))):
        raise ArithmeticError("the antiunitary symmetry does not preserve the sector (internal error)")
    s = 1.0 / np.sqrt(2.0)
    fixed = np.nonzero(tau == np.arange(n))[0]
    first = np.nonzero(tau > np.arange(n))[0]
    # new column of each stored entry: the fixed columns first, then the sums and the differences of the pairs
    new_fixed = np.full(n, -1, dtype=np.int64)
    new_fixed[fixed] = np.arange(fixed.size)
    new_pair = np.full(n, -1, dtype=np.int64)
    new_pair[first] = fixed.size + np.arange(first.size)
    f, p = new_fixed[col] >= 0, new_pair[col] >= 0
    half = np.exp(0.5j * np.angle(theta))
    rows = np.concatenate([r[f], r[p], ar[p], r[p], ar[p]])
    cols = np.concatenate([new_fixed[col[f]], new_pair[col[p]], new_pair[col[p]],
                           new_pair[col[p]] + first.size, new_pair[col[p]] + first.size])
    data = np.concatenate([x[f] * half[col[f]], x[p] * s, ax[p] * s, x[p] * (1j * s), -ax[p] * (1j * s)])
    keep = np.abs(data) >= 1e-15
    out = sps.csc_matrix((data[keep], (rows[keep], cols[keep])), shape=(dim, n))
    out.sort_indices()  # canonical storage: the same sums in every later product
    return out


def symmetry_sectors(rep, *, complete: bool = False) -> list[Sector]:
    r"""The sectors of the sign-rotation symmetry of ``rep`` (package docstring).

    Parameters
    ----------
    rep : Representation
        A Gelfand-Tsetlin irrep (:func:`~hyperrotor.quantum.irrep`, any dimension,
        sparse construction) or any other representation up to
        ``options["sectors_dense_max_dim"]`` (dense construction).
    complete : bool, default False
        Spinor irreps only: ``False`` returns one copy of the multiplicity space per
        isotypic type (what a spectrum needs; ``sum(s.dim * s.degeneracy) == rep.dim``);
        ``True`` returns every joint eigenspace of the Cartan-plane rotations, which
        together span the whole space (what time evolution needs;
        ``sum(s.dim) == rep.dim``). No effect for tensor irreps, whose sectors always
        span the space.

    Returns
    -------
    list of Sector
        Tensor irreps: one sector per character of :math:`(\mathbb Z_2)^{N-1}` allowed
        by the centre (:math:`2^{N-1}` for odd N, :math:`2^{N-2}` for even N, times 2
        for the reflection parity of even-N irreps whose highest weight ends in 0),
        in lexicographic order of the eigenvalues (``+1`` first; in 3D: A, B1, B2,
        B3); a sector may be empty (``dim == 0``) in a small irrep. Spinor irreps:
        one sector of degeneracy :math:`2^{\lfloor (N-1)/2\rfloor}`
        (``complete=False``). Every basis is orthonormal and invariant under every
        rotor Hamiltonian of ``rep``; for a GT irrep each sector is irreducible for a
        generic inertia, and its basis is real-gauged (:attr:`Sector.real`).

    Raises
    ------
    ValueError
        A non-GT representation above the dense limit, or a reducible
        representation mixing tensor and spinor parts.

    Examples
    --------
    >>> from fractions import Fraction
    >>> from hyperrotor.quantum import irrep
    >>> [(s.label, s.dim) for s in symmetry_sectors(irrep(3, (2,)))]
    [('A', 2), ('B1', 1), ('B2', 1), ('B3', 1)]
    >>> s, = symmetry_sectors(irrep(3, (Fraction(3, 2),)))
    >>> s.label, s.dim, s.degeneracy, s.real
    ('E1/2', 2, 2, True)
    """
    rep = _validate.representation("rep", rep)
    complete = _validate.flag("complete", complete)
    _pricing.check("gt_sectors", dim=rep.dim, N=rep.N)
    return sectors_of(rep, complete)


def sectors_of(rep, complete: bool) -> list[Sector]:
    """:func:`symmetry_sectors` of a checked and priced (``"gt_sectors"``) ``rep`` (trusted core)."""
    g = group_of(rep)
    N, dim = rep.N, rep.dim
    characters = list(g.characters(complete))
    if g.monomial:
        reps_idx = _orbit_representatives(g.ops, dim)
        elems = _group_elements(g.ops, reps_idx)
        layout = _orbit_layout(elems, len(reps_idx), dim)
        V = g.antiunitary

        def project(eigs):
            B = _project_monomial(elems, eigs, layout, len(reps_idx), dim)
            return B if V is None else make_real(B, V)
    else:
        def project(eigs):
            return _project_dense(g.ops, eigs, dim)
    out = []
    types_seen = {}
    for eigs, lab, character in characters:
        B = project(eigs)
        if g.spinorial and N > 2:
            if B.shape[1] == 0:
                continue
            itype = np.prod(eigs) if N % 2 == 0 else 1
            if not complete and itype in types_seen:
                continue
            types_seen[itype] = len(out)
        out.append(Sector(lab, B, g.degeneracy, character, real=g.real))
    if not complete and len(types_seen) > 1:  # both chiralities (a reducible even-N spinor representation): one
        for itype, k in types_seen.items():    # sector each, labelled by the eigenvalue of g_(12) g_(34) ...
            s = out[k]
            out[k] = Sector((s.label, eig_text(itype)), s.basis, s.degeneracy, s.character, real=s.real)
    if N == 3 and not g.spinorial:
        out.sort(key=lambda s: ("A", "B1", "B2", "B3").index(s.label))
    total = sum(s.dim * (1 if complete else s.degeneracy) for s in out)
    if total != dim:  # pragma: no cover - internal
        raise ArithmeticError(f"sectors of {rep.name} cover {total} of {dim} dimensions (internal error)")
    if len({s.label for s in out}) != len(out):  # pragma: no cover - internal (sector_spectra keys its levels by them)
        raise ArithmeticError(f"two sectors of {rep.name} share a label (internal error): {[s.label for s in out]}")
    return out
