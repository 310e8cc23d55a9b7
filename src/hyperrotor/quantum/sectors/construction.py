r"""Construction of the sectors: monomial projections in the Gelfand-Tsetlin basis, the real gauge, the dense fallback.

See the package docstring ("Construction without dense matrices", "Real blocks").
"""
from __future__ import annotations

import itertools

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sps
from scipy.sparse.csgraph import connected_components

from ... import _pricing, _validate
from ..._options import options
from .._gt_monomials import Monomial, gt_patterns_of, gt_rotations
from .group import (
    REFLECTION,
    Sector,
    centre_scalar,
    eig_text,
    gt_intertwiner,
    gt_reflection,
    has_reflection,
    is_half_integer,
    label,
    structure,
)

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
    if j == i + 1:
        rot = _rotations(rep, [i], is_half_integer(rep))
        if rot is not None:
            M = rot[i].matrix()
            return M.toarray() if fmt == "dense" else M
    _check_dense_dim(rep)
    E = sla.expm(np.pi * rep.generator((i, j), format="dense"))
    E[np.abs(E) < 1e-13] = 0.0
    return E if fmt == "dense" else sps.csr_matrix(E)


def _rotations(rep, ks: list[int], half: bool | None):
    """:func:`gt_rotations`, priced: in so(3) the sign of exp(pi X_23) comes from a dense block of the whole irrep."""
    if rep.N == 3 and half is False and 2 in ks:
        _pricing.check("dense_representation", dim=rep.dim, copies=1)
    return gt_rotations(rep, ks)


def _check_dense_dim(rep) -> None:
    _pricing.check("dense_representation", dim=rep.dim)
    lim = int(options["sectors_dense_max_dim"])
    if rep.dim > lim:
        raise ValueError(
            f"{rep.name} (dim {rep.dim}) is not a Gelfand-Tsetlin irrep, and its sectors would be built "
            f"densely (O(dim^3)); dim {rep.dim} > options['sectors_dense_max_dim'] = {lim}. Use irrep(N, "
            f"highest_weight) (sparse construction at any dimension) or raise the option."
        )


# ----------------------------------------------------------------------------
# sectors from commuting monomial matrices
# ----------------------------------------------------------------------------
def _orbit_representatives(ops: list[Monomial], dim: int) -> np.ndarray:
    rows = np.concatenate([np.arange(dim)] + [np.arange(dim) for _ in ops])
    cols = np.concatenate([np.arange(dim)] + [D.perm for D in ops])
    G = sps.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(dim, dim))
    _, lab = connected_components(G, directed=False)
    first = np.full(lab.max() + 1, dim, dtype=np.int64)
    np.minimum.at(first, lab, np.arange(dim))
    return np.sort(first)


def _project_monomial(ops: list[Monomial], eigs: tuple, reps_idx: np.ndarray, dim: int) -> sps.csc_matrix:
    """Orthonormal basis of the joint eigenspace D_k = eigs[k] (sparse columns, one per orbit)."""
    V = sps.csc_matrix((np.ones(len(reps_idx), dtype=complex), (reps_idx, np.arange(len(reps_idx)))),
                       shape=(dim, len(reps_idx)))
    for D, lam in zip(ops, eigs):
        V = (V + np.conj(lam) * (D.matrix() @ V)) * 0.5
        V = sps.csc_matrix(V)
        V.data[np.abs(V.data) < 1e-12] = 0
        V.eliminate_zeros()
    norms = np.sqrt(np.asarray(abs(V).power(2).sum(axis=0)).ravel())
    keep = norms > 1e-8
    V = V[:, np.nonzero(keep)[0]] @ sps.diags(1.0 / norms[keep])
    return sps.csc_matrix(V)


# ----------------------------------------------------------------------------
# the real gauge
# ----------------------------------------------------------------------------
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


def make_real(B: sps.csc_matrix, V: Monomial) -> sps.csc_matrix:
    r"""Columns fixed by :math:`A = VK` spanning the same space as ``B`` (A preserves the span).

    The columns of ``B`` have disjoint supports (one orbit of the monomial group
    each) and A maps orbits to orbits, so :math:`A b_j = \theta_j b_{\tau(j)}`.
    A fixed column (:math:`\tau(j) = j`) becomes :math:`e^{i\arg\theta_j/2} b_j`; a pair
    becomes :math:`(b_j + A b_j)/\sqrt2` and :math:`i(b_j - A b_j)/\sqrt2`.
    """
    n = B.shape[1]
    if n == 0:
        return B
    AB = sps.csc_matrix(V.matrix() @ B.conj())
    G = sps.csc_matrix(B.conj().T @ AB)
    tau = np.asarray(abs(G).argmax(axis=0)).ravel()
    theta = np.asarray(G[tau, np.arange(n)]).ravel()
    if np.abs(np.abs(theta) - 1).max() > 1e-9 or abs(AB - B @ G).max() > 1e-9 or np.any(tau[tau] != np.arange(n)):
        raise ArithmeticError("the antiunitary symmetry does not preserve the sector (internal error)")
    fixed = tau == np.arange(n)
    first = np.nonzero(tau > np.arange(n))[0]
    s = 1.0 / np.sqrt(2.0)
    cols = [B[:, np.nonzero(fixed)[0]] @ sps.diags(np.exp(0.5j * np.angle(theta[fixed])))]
    if first.size:
        Bj, Aj = B[:, first], AB[:, first]
        cols += [(Bj + Aj) * s, (Bj - Aj) * (1j * s)]
    out = sps.csc_matrix(sps.hstack(cols))
    out.data[np.abs(out.data) < 1e-15] = 0
    out.eliminate_zeros()
    return out


# ----------------------------------------------------------------------------
# the dense fallback
# ----------------------------------------------------------------------------
def _project_dense(Ds: list[np.ndarray], eigs: tuple, dim: int) -> np.ndarray:
    Pm = np.eye(dim, dtype=complex)
    for D, lam in zip(Ds, eigs):
        Pm = 0.5 * (Pm + np.conj(lam) * (D @ Pm))
    Pm = 0.5 * (Pm + Pm.conj().T)
    w, V = np.linalg.eigh(Pm)
    return V[:, w > 0.5]


def _dense_group(rep):
    """(spinorial, ks, alphabet, degeneracy, project) of the dense fallback."""
    _check_dense_dim(rep)
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
    return spinorial, ks, alphabet, degen, lambda eigs: _project_dense(Ds, eigs, dim)


def _gt_group(rep, half: bool):
    """(spinorial, ks, alphabet, degeneracy, project, centre, reflection) of a GT irrep, or None."""
    N, dim = rep.N, rep.dim
    ks, alphabet, degen = structure(N, half)
    ops = _rotations(rep, sorted(set(ks) | ({1} if N > 1 else set())), half)
    if ops is None:
        return None
    ops_list = [ops[k] for k in ks]
    U = V = None
    if N >= 3:
        P = gt_patterns_of(rep)
        chain = {q: sps.csr_matrix(rep.generator((q, q + 1), format="csr")) for q in range(1, N)}
        U = gt_reflection(rep, P, chain) if has_reflection(rep, half) else None
        V = real_structure(rep, P, chain, cartan=ks if half else None, reflection=U)
    group = ops_list + ([U] if U is not None else [])
    reps_idx = _orbit_representatives(group, dim)

    def project(eigs):
        B = _project_monomial(group, eigs, reps_idx, dim)
        return B if V is None else make_real(B, V)
    return ks, alphabet, degen, project, centre_scalar(ops, N, half), U, V is not None or N <= 2


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
    return sectors_of(rep, complete)


def sectors_of(rep, complete: bool) -> list[Sector]:
    """:func:`symmetry_sectors` of a checked ``rep`` (trusted core)."""
    N, dim = rep.N, rep.dim
    half = is_half_integer(rep)
    gt = _gt_group(rep, half) if half is not None else None
    if gt is not None:
        spinorial = bool(half)
        ks, alphabet, degen, project, centre, U, real = gt
    else:
        spinorial, ks, alphabet, degen, project = _dense_group(rep)
        centre, U, real = None, None, False
    parities = (1, -1) if U is not None else (None,)
    out = []
    types_seen = set()
    for eigs in itertools.product(alphabet, repeat=len(ks)):
        if centre is not None and np.prod([eigs[k - 1] for k in range(1, N, 2)]) != centre:
            continue  # -1 = g_(12) g_(34) ... is central: it acts as the scalar `centre`
        for parity in parities:
            B = project(eigs if parity is None else eigs + (parity,))
            if spinorial and N > 2:
                if B.shape[1] == 0:
                    continue
                itype = np.prod(eigs) if N % 2 == 0 else 1
                if not complete and itype in types_seen:
                    continue
                types_seen.add(itype)
            character = {(k, k + 1): eig_text(e) for k, e in zip(ks, eigs)}
            if parity is not None:
                character[REFLECTION] = parity
            out.append(Sector(label(N, spinorial, eigs, complete, parity), B, degen, character, real=real))
    if N == 3 and not spinorial:
        out.sort(key=lambda s: ("A", "B1", "B2", "B3").index(s.label))
    total = sum(s.dim * (1 if complete else s.degeneracy) for s in out)
    if total != dim:  # pragma: no cover - internal
        raise ArithmeticError(f"sectors of {rep.name} cover {total} of {dim} dimensions (internal error)")
    return out
