r"""Equivalences of so(N) representations: intertwiners and real forms.

:func:`intertwiner` finds :math:`T` with :math:`T X^{(a)}_{(ij)} = X^{(b)}_{(ij)} T`
for two equivalent irreps (Schur: unique up to a scalar); :func:`real_form`
uses the intertwiner of a representation with its complex conjugate to bring
an irrep of real type to real antisymmetric generators. Both are dense,
:math:`O(\dim^3)`, meant for moderate dimensions.
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sps

from .. import _pricing, _validate
from .._options import options
from .._parallel import interruptible
from .representation import Representation, check_same_algebra
from .weights import positive_roots

__all__ = ["intertwiner", "real_form"]

options.register(
    "quantum_intertwiner_rtol", 1e-9,
    "intertwiner(): a vector obtained by lowering operators from the unit highest-weight vector counts as "
    "zero when its length is at most this (relative to that unit vector); the default suits generators "
    "of order one to a few hundred.",
)


def exact_antisymmetric(M: np.ndarray, drop: float) -> np.ndarray:
    r"""The antisymmetric part :math:`(M - M^{\mathsf T})/2` of a nearly antisymmetric ``M``, tiny entries dropped.

    Why this is the same operator up to round-off: if :math:`M = X + E` with the
    exact (antisymmetric) :math:`X` and a round-off error :math:`E`, then
    :math:`(M - M^{\mathsf T})/2 = X + (E - E^{\mathsf T})/2`, whose error is
    the antisymmetric part of :math:`E`, no larger than :math:`E` (the
    projection onto antisymmetric matrices is orthogonal in the Frobenius norm
    and has norm 1 in the max norm). In floating point
    :math:`M_{ab} - M_{ba} = -(M_{ba} - M_{ab})` exactly and halving is exact,
    so the result is antisymmetric bit for bit. Entries with
    :math:`|Y_{ab}| <` ``drop`` :math:`\cdot\max(1, \max|Y|)` (round-off of exact
    zeros) are set to zero; :math:`|Y_{ab}| = |Y_{ba}|`, so this keeps the symmetry.
    """
    Y = 0.5 * (M - M.T)
    Y[np.abs(Y) < drop * max(1.0, float(np.abs(Y).max(initial=0.0)))] = 0.0
    return Y


def highest_weight_vector(rep: Representation, raising: list) -> np.ndarray:
    """Joint kernel of the raising operators: null space of G = sum_E E^dagger E (Hermitian PSD)."""
    if not raising:
        return np.ones(1, dtype=complex)
    G = sum((E.conj().T @ E for E in raising), sps.csr_matrix((rep.dim, rep.dim))).toarray()
    w, V = interruptible(np.linalg.eigh, G)  # (Ctrl-C: _parallel.interruptible)
    tol = 1e-10 * max(1.0, float(w[-1]))
    K = V[:, w < tol]
    if K.shape[1] != 1:
        raise ValueError(
            f"{rep.name} is not irreducible: its highest-weight space has dimension {K.shape[1]}"
        )
    return K[:, 0]


def intertwiner(a: Representation, b: Representation, *, rtol: float | None = None) -> np.ndarray:
    r"""An invertible ``T`` with :math:`T\,X^{(a)}_{(ij)} = X^{(b)}_{(ij)}\,T` for all planes (dense).

    Both representations must be irreducible (a 1-dim joint kernel of the
    raising operators :math:`E_\alpha`, :math:`\alpha > 0`). Construction: the
    highest-weight vectors :math:`v_a, v_b` are matched, and so are the vectors
    :math:`E_{-\beta_1}\cdots E_{-\beta_r} v` obtained by the same words of
    lowering operators, until they span the space; the a-side vectors are
    orthonormalized (Gram-Schmidt, twice) and the same linear combinations are
    applied on the b-side, giving :math:`T = Y Q^\dagger` with Q unitary. By Schur's lemma ``T`` is unique up to a scalar; it is
    scaled so that :math:`\|T\|_F^2 = \dim`, which makes it unitary when both
    generator sets are anti-Hermitian in orthonormal bases.

    ``rtol`` (default ``options["quantum_intertwiner_rtol"]``) is the length,
    relative to the unit highest-weight vector, below which a lowered vector
    counts as zero.

    Raises
    ------
    ValueError
        If the representations are of different so(N), of different dimension,
        reducible, or not equivalent.
    """
    check_same_algebra(a, b)
    rtol = options["quantum_intertwiner_rtol"] if rtol is None else _validate.positive("rtol", rtol)
    if a.dim != b.dim:
        raise ValueError(f"no intertwiner: dimensions differ ({a.dim} vs {b.dim})")
    _pricing.check("dense_representation", dim=max(a.dim, b.dim), planes=len(a.planes))
    pos = positive_roots(a.N)
    ra = [a.ladder(r, format="csr") for r in pos]
    rb = [b.ladder(r, format="csr") for r in pos]
    la = [a.ladder(tuple(-x for x in r), format="csr") for r in pos]
    lb = [b.ladder(tuple(-x for x in r), format="csr") for r in pos]
    va, vb = highest_weight_vector(a, ra), highest_weight_vector(b, rb)
    d = a.dim
    # Orthonormalize on the a-side and apply the same linear combinations on the
    # b-side (T is linear), so that T = Y Q^dagger with Q unitary (well conditioned).
    nva = np.linalg.norm(va)
    Q = np.zeros((d, d), dtype=complex)
    Y = np.zeros((d, d), dtype=complex)
    Q[:, 0], Y[:, 0] = va / nva, vb / nva
    k = 1
    frontier = [0]
    la = [sps.csr_matrix(E) for E in la]
    lb = [sps.csr_matrix(E) for E in lb]
    while frontier and k < d:
        nxt = []
        for col in frontier:
            X2 = np.stack([E @ Q[:, col] for E in la], axis=1)
            Y2 = np.stack([E @ Y[:, col] for E in lb], axis=1)
            for x2, y2 in zip(X2.T, Y2.T):
                nx = np.linalg.norm(x2)
                if nx <= rtol:
                    continue
                Qk = Q[:, :k]
                c = (x2.conj() @ Qk).conj()
                r = x2 - Qk @ c
                c2 = (r.conj() @ Qk).conj()
                r = r - Qk @ c2
                nr = np.linalg.norm(r)
                if nr > 1e-8 * nx:
                    Q[:, k] = r / nr
                    Y[:, k] = (y2 - Y[:, :k] @ (c + c2)) / nr
                    nxt.append(k)
                    k += 1
                    if k == d:
                        break
            if k == d:
                break
        frontier = nxt
    if k < d:
        raise ValueError(f"{a.name} is not irreducible (the lowering operators span only {k} of {d} dimensions)")
    T = Y @ Q.conj().T
    T *= np.sqrt(d) / np.linalg.norm(T)
    ga, gb = a.generators(format="csr"), b.generators(format="csr")
    res = max(  # (sparse times dense: a dense generator made this n_planes dim^3, 20 s for so(30) (2, 0, ...))
        float(np.abs(T @ ga[p] - gb[p] @ T).max()) for p in a.planes
    )
    scale = max(1.0, max(float(abs(M).max()) for M in ga.values()) if a.planes else 1.0)
    if res > 1e-6 * scale * max(1.0, np.abs(T).max()):
        raise ValueError(f"{a.name} and {b.name} are not equivalent (intertwining residual {res:.2e})")
    return T


def real_form(rep: Representation, *, rtol: float | None = None) -> Representation:
    r"""An equivalent representation with real antisymmetric generators (irreps of real type).

    Let :math:`T` intertwine the complex-conjugate representation with ``rep``,
    :math:`T\,\overline{X}_{(ij)} = X_{(ij)}\,T` (:func:`intertwiner`,
    unitary). Then :math:`T\overline T = \varepsilon\,\mathbb 1` with
    :math:`\varepsilon = +1` (real type) or :math:`-1` (quaternionic type,
    e.g. spin 1/2 of so(3) or the spinor of so(5)). For real type :math:`T` is
    symmetric unitary, :math:`T = W^2` with :math:`W = O\,e^{i\Theta/2} O^{\mathsf T}`
    (O real orthogonal diagonalizing the commuting real and imaginary parts of
    T), and :math:`Y_{(ij)} = W^\dagger X_{(ij)} W` is real antisymmetric.
    Dense :math:`O(\dim^3)`; meant for moderate dimensions.

    ``rtol`` (default ``options["quantum_real_form_rtol"]``; ``0 < rtol < 1``) bounds the
    imaginary part left in :math:`Y_{(ij)}` relative to :math:`\max(1, \max|Y|)`
    (an internal consistency check); entries below
    ``options["quantum_real_form_drop"]`` (relative) are round-off of exact
    zeros and are dropped, symmetrically, so :math:`Y` stays exactly antisymmetric.

    Raises
    ------
    ValueError
        If ``rep`` is reducible, not self-conjugate (complex type, e.g. so(6)
        (1, 1, 1)) or quaternionic.
    """
    if not isinstance(rep, Representation):
        raise TypeError(f"real_form takes a Representation, got {type(rep).__name__}")
    # checked before the early return (a real rep needs no tolerance, but a bad one is still an error)
    rtol = options["quantum_real_form_rtol"] if rtol is None else _validate.tolerance("rtol", rtol)
    if rep.is_real:
        return rep
    _pricing.check("real_form", dim=rep.dim, planes=len(rep.planes))
    gens_in = rep.generators(format="csr")
    conj = Representation(rep.N, {p: M.conj() for p, M in gens_in.items()}, name=f"conjugate of {rep.name}")
    try:
        T = intertwiner(conj, rep)
    except ValueError as err:
        raise ValueError(f"{rep.name} has no real form: {err}") from None
    TT = T @ T.conj()
    eps = float(np.real(np.trace(TT))) / rep.dim
    if abs(eps + 1) < 1e-6:
        raise ValueError(f"{rep.name} is of quaternionic (pseudo-real) type: T conj(T) = -1, no real form")
    if np.abs(TT - np.eye(rep.dim)).max() > 1e-8:  # pragma: no cover - internal
        raise ArithmeticError("conjugation intertwiner is not an involution (internal error)")
    T = 0.5 * (T + T.T)
    A, B = T.real, T.imag
    c = np.sqrt(2.0) + 0.1234
    _, O = interruptible(np.linalg.eigh, A + c * B)  # (Ctrl-C: _parallel.interruptible)
    theta = np.angle(np.einsum("ia,ij,ja->a", O, T, O))
    W = (O * np.exp(0.5j * theta)) @ O.T
    drop = options["quantum_real_form_drop"]
    gens = {}
    for p, X in gens_in.items():
        Y = W.conj().T @ (X @ W)  # (one dense product per plane: n_planes dim^3, the model "real_form")
        if np.abs(Y.imag).max() > rtol * max(1.0, np.abs(Y).max()):
            raise ArithmeticError(f"real form failed: imaginary part {np.abs(Y.imag).max():.2e} (internal error)")
        gens[p] = sps.csr_matrix(exact_antisymmetric(Y.real, drop))
    return Representation(rep.N, gens, highest_weight=rep.highest_weight, name=f"real form of {rep.name}", format=rep.format)
