r"""Generalized (Perelomov) spin-coherent states of so(N) representations.

A coherent state is a rotated highest-weight vector,
:math:`|L\rangle = U(Q)\,|w\rangle`. Its *moment map*
:math:`\mu(\psi) = \sum_a \langle\psi|\hat L_a|\psi\rangle E_a` (plane order,
:math:`\hat L_a = -i\hbar\rho(E_a)`, eq. 141) is equivariant,
:math:`\mu(U(g)\psi) = g\,\mu(\psi)\,g^{\mathsf T}` for a representation
(:math:`U(e^{X}) = e^{\rho(X)}`), and for the highest-weight vector
:math:`\mu = \hbar\sum_k w_k E_{2k-1,2k}` (the Cartan planes 12, 34, ...).
Given a classical angular momentum :math:`L` (components in plane order) with
the normal form (real Schur form of its antisymmetric matrix)
:math:`L = Q\,(\sum_k \lambda_k E_{2k-1,2k})\,Q^{\mathsf T}`, :math:`Q \in SO(N)`,
the state :math:`U(Q)|w\rangle` has
:math:`\langle \hat L_a\rangle = \hbar\,(|w|/|\lambda|)\,L_a` whenever
:math:`\lambda \propto w`: for every simple bivector (one plane, :math:`\lambda =
(|L|, 0, \dots)`) in the irreps :math:`(l, 0, \dots)`, and for a general
:math:`L \in so(5)` in the irrep :math:`(m_1, m_2) \propto (\lambda_1, \lambda_2)`.

These are the states of minimal uncertainty,
:math:`\sum_a \langle \hat L_a^2\rangle - \langle\hat L_a\rangle^2 =
\hbar^2 \langle w, 2\rho\rangle` (with :math:`\rho` the half sum of positive
roots), so :math:`\langle\hat L\rangle/(\hbar |w|)` becomes sharp as
:math:`|w| \to \infty`: the classical limit used by the Ehrenfest tests.
Because the classical Euler equations are body-frame equations, use
``frame="body"`` to compare with them (see :mod:`hyperrotor.quantum.hamiltonian`).
"""
from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np
import qutip
import scipy.linalg as sla
import scipy.sparse as sps
import scipy.sparse.linalg as spla

from .. import _pricing, _validate
from .._equality import fields_equal, fields_unequal
from .._floats import power_of_two_scale
from .._options import options
from ..conventions import n_planes, planes, to_matrix
from ._krylov import krylov_propagator, row_bound, single_thread_blas
from .sector_propagator import scaled_state

options.register(
    "quantum_coherent_rtol", 1e-8,
    "hyperrotor.quantum.coherent_state: relative tolerance of the check that the normal form of L is a positive "
    "multiple of the highest weight of the irrep (a coherent state along L exists only then).",
)

__all__ = [
    "generator_expectations",
    "highest_weight_state",
    "normal_form_rotation",
    "apply_rotation",
    "coherent_state",
]


def _vector(psi: Any, dim: int, name: str = "psi") -> np.ndarray:
    return _validate.ket(name, psi, dim, of="the representation")


def generator_expectations(rep: Any, psi: Any, *, hbar: float = 1) -> np.ndarray:
    r"""Expectation values :math:`\langle\psi|\hat L_a|\psi\rangle/\langle\psi|\psi\rangle`, plane order.

    Parameters
    ----------
    rep : hyperrotor.quantum.Representation
    psi : qutip.Qobj (ket) or array_like of length ``rep.dim``
    hbar : float, keyword-only, default 1
        :math:`\hat L_a = -i\hbar\rho(E_a)` (eq. 141): the expectation values
        are those of the Hermitian generators (``form="hermitian"``).

    Returns
    -------
    ndarray of shape ``(N(N-1)/2,)``, real. The body-frame values are the
    negatives (see :mod:`hyperrotor.quantum.hamiltonian`).
    """
    hbar = _validate.hbar(hbar)
    _validate.representation("rep", rep)
    vec = _vector(psi, int(rep.dim))
    if not np.any(vec):
        raise ValueError("psi is the zero vector; expectation values are undefined")
    vec, _ = scaled_state(vec, "psi")  # (the ratio does not change; |psi|^2 of amplitudes near 1e308 would be inf)
    gens = rep.generators()
    nrm = np.vdot(vec, vec).real
    # <L_a> = hbar Re(-i <v|E_a v>) = hbar Im<v|E_a v> / <v|v>: hbar last and real (a complex product by -1j hbar
    # overflowed near hbar = 1e308 to inf and nan where the value is 9e307)
    return np.array([np.vdot(vec, gens[p] @ vec).imag / nrm * hbar for p in planes(int(rep.N))])


def _cartan_planes(N: int) -> list[tuple[int, int]]:
    return [(2 * k + 1, 2 * k + 2) for k in range(N // 2)]


class HighestWeightState(NamedTuple):
    """Result of :func:`highest_weight_state` (unpacks as ``psi, weight``; compares field by field)."""

    __eq__, __ne__ = fields_equal, fields_unequal  # (a tuple's == refuses the array fields)
    __hash__ = None

    #: the normalized highest-weight vector
    psi: np.ndarray
    #: its weight (orthogonal basis)
    weight: np.ndarray


def highest_weight_state(rep: Any) -> HighestWeightState:
    r"""Highest-weight vector of an irreducible representation and its weight.

    The weight vector maximizing :math:`\sum_k \alpha_k \hat L^{2k-1,2k}` with
    :math:`\alpha_k = 2^{1-k}` (positive on every positive root
    :math:`e_i \pm e_j, e_i` of so(N), so the maximizer is the unique highest
    weight) is found with a dense ``eigh`` (dim <= 3000) or ``eigsh``.

    Returns
    -------
    HighestWeightState
        ``(psi, weight)``, compared field by field:
    psi : ndarray, complex, normalized
    weight : ndarray
        :math:`w_k = \langle\psi|\hat L^{2k-1,2k}|\psi\rangle` at ``hbar = 1``,
        i.e. the highest weight in the orthogonal basis (last entry possibly
        negative for even N).
    """
    _validate.representation("rep", rep)
    N = int(rep.N)
    dim = int(rep.dim)
    _pricing.check("highest_weight_state", dim=dim)
    gens = rep.generators()
    cp = _cartan_planes(N)
    K = sps.csr_matrix((dim, dim), dtype=complex)
    for k, p in enumerate(cp):
        K = K + (-1j * 2.0 ** (-k)) * sps.csr_matrix(gens[p])
    with single_thread_blas():
        if dim <= 200:
            _, V = np.linalg.eigh(K.toarray())
            psi = V[:, -1]
        else:
            v0 = np.random.default_rng(0).normal(size=dim).astype(complex)
            _, V = spla.eigsh(K, k=1, which="LA", tol=1e-14, v0=v0)
            psi = V[:, 0]
    psi = psi / np.linalg.norm(psi)
    weight = np.array([np.vdot(psi, -1j * (gens[p] @ psi)).real for p in cp])
    return HighestWeightState(psi, weight)


def normal_form_rotation(L: Any) -> tuple[np.ndarray, np.ndarray]:
    r"""Normal form of a bivector: :math:`L = Q\,(\sum_k \lambda_k E_{2k-1,2k})\,Q^{\mathsf T}`.

    Parameters
    ----------
    L : array_like, shape ``(N(N-1)/2,)``
        Components in plane order (the standard = paper components).

    Returns
    -------
    Q : ndarray (N, N)
        Rotation (``det Q = +1``) from the real Schur form of the plain
        antisymmetric matrix of ``L``.
    lam : ndarray (N // 2,)
        :math:`\lambda_1 \ge \lambda_2 \ge \dots \ge |\lambda_{n}|`, all
        :math:`\ge 0` except possibly the last one for even N (its sign is the
        sign of the Pfaffian).
    """
    comps = _validate.real_array("L", L, ndim=1)
    if comps.size == 0:
        raise ValueError("L must hold N(N-1)/2 >= 1 plane components, got an empty array")
    _validate.dimension_from_count(comps.size, name="L")  # (the error names L, not to_matrix's count)
    A = np.asarray(to_matrix(comps, convention="standard"), dtype=float)
    N = A.shape[0]
    # the rotation does not depend on |L|: L / s for a power of two s (exact), max |entry| in [1, 2), so that
    # nothing below overflows or underflows (L of 1e308 gave inf in Q^T L Q); lam is scaled back at the end
    s = power_of_two_scale(float(np.max(np.abs(A))))
    A = A / s
    T, Z = sla.schur(A, output="real")
    scale = max(1.0, float(np.max(np.abs(A))))
    blocks, zeros = [], []
    k = 0
    while k < N:
        if k + 1 < N and abs(T[k + 1, k]) > 1e-14 * scale:
            u, v = Z[:, k].copy(), Z[:, k + 1].copy()
            lam = 0.5 * (T[k, k + 1] - T[k + 1, k])
            if lam < 0:
                v, lam = -v, -lam
            blocks.append((lam, u, v))
            k += 2
        else:
            zeros.append(Z[:, k].copy())
            k += 1
    blocks.sort(key=lambda b: -b[0])
    cols = []
    for _, u, v in blocks:
        cols += [u, v]
    cols += zeros
    Q = np.column_stack(cols)
    lam = np.zeros(N // 2)
    lam[: len(blocks)] = [b[0] for b in blocks]
    if np.linalg.det(Q) < 0:
        if zeros:
            Q[:, -1] *= -1
        else:  # even N, all blocks non-degenerate: the last lambda carries the orientation
            Q[:, N - 1] *= -1
            lam[-1] *= -1
    B = Q.T @ A @ Q
    target = np.zeros((N, N))
    for k, lk in enumerate(lam):
        target[2 * k, 2 * k + 1], target[2 * k + 1, 2 * k] = lk, -lk
    if np.max(np.abs(B - target)) > 1e-10 * scale:  # pragma: no cover - guards the Schur bookkeeping
        raise RuntimeError("normal form failed: Q^T L Q is not block diagonal")
    with np.errstate(over="ignore"):
        lam = lam * s
    if not np.all(np.isfinite(lam)):
        raise ValueError(f"L too large, max |L| = {float(np.max(np.abs(comps))):.3g}: its normal form's lambda "
                         f"overflows double precision (about 1.8e308); rescale L first")
    return Q, lam


def _givens_angles(Q: np.ndarray) -> list[tuple[tuple[int, int], float]]:
    r"""Factors ``Q = prod_k exp(theta_k E_{p_k})`` (left to right), ``E_(ij) = e_i e_j^T - e_j e_i^T``."""
    R = np.array(Q, dtype=float)
    N = R.shape[0]
    factors = []
    for c in range(N - 1):
        for r in range(c + 1, N):
            theta = np.arctan2(R[r, c], R[c, c])
            if theta == 0.0:
                continue
            cth, sth = np.cos(theta), np.sin(theta)
            rc, rr = R[c].copy(), R[r].copy()
            R[c], R[r] = cth * rc + sth * rr, -sth * rc + cth * rr
            factors.append(((c + 1, r + 1), -theta))  # M_k = exp(theta E); Q = prod M_k^{-1}
    if np.max(np.abs(R - np.eye(N))) > 1e-10:
        raise ValueError("the matrix is not a rotation (orthogonal with det +1)")
    return factors


def _priced_rotation(rep: Any, Q: np.ndarray) -> tuple[list, dict]:
    r"""``(Givens factors of Q, the generators of rep)``, refused first (``"apply_rotation"``) when the Lanczos
    propagations would be over budget: their products follow the phase :math:`\sum_k |\theta_k|\,\|X_{p_k}\|`
    (:math:`\|X\|`: the largest absolute row sum, a bound of the spectral radius)."""
    factors = _givens_angles(Q)
    gens = rep.generators()
    phase = sum(abs(theta) * row_bound(gens[plane]) for plane, theta in factors)
    _pricing.check("apply_rotation", dim=int(rep.dim), phase=phase, factors=len(factors))
    return factors, gens


def apply_rotation(rep: Any, Q: Any, psi: Any) -> np.ndarray:
    r"""Apply the representation of a rotation, :math:`U(Q)\psi`, with :math:`U(e^X) = e^{\rho(X)}`.

    ``Q`` is factored into plane rotations :math:`\prod_k \exp(\theta_k E_{p_k})`
    (Givens) and each factor :math:`e^{\theta_k X_{p_k}}\psi` is applied by the
    Lanczos propagator of :mod:`hyperrotor.quantum._krylov` (Krylov, tolerance
    ``options["quantum_rotation_atol"]`` = 1e-14; ``scipy.sparse.linalg.expm_multiply`` gives the same vectors but was
    ~10x slower here).
    """
    _validate.representation("rep", rep)
    N = int(rep.N)
    Q = _validate.real_array("Q", Q, ndim=2)
    if Q.shape != (N, N):
        raise ValueError(f"Q must be a {N} x {N} rotation for so({N}), got shape {Q.shape}")
    if np.abs(Q @ Q.T - np.eye(N)).max() > 1e-10 or np.linalg.det(Q) < 0:
        raise ValueError(f"Q must be a rotation (orthogonal with det +1), got {_validate.fmt(Q)}")
    vec = _vector(psi, int(rep.dim))
    factors, gens = _priced_rotation(rep, Q)
    with single_thread_blas():
        for plane, theta in reversed(factors):
            # exp(theta X) v = exp(-i H |theta|) v with the Hermitian H = i sign(theta) X (Lanczos)
            Hp = sps.csr_matrix(gens[plane]) * (1j * np.sign(theta))
            prop = krylov_propagator(Hp, vec, np.array([0.0, abs(theta)]), 1.0, {},
                                      atol=options["quantum_rotation_atol"], m_max=options["quantum_krylov_dim"])
            next(prop)
            vec = next(prop)
    return vec


def coherent_state(rep: Any, L: Any, *, hbar: float = 1, frame: str = "space", rtol: float | None = None) -> qutip.Qobj:
    r"""Spin-coherent state whose angular momentum points along the classical ``L``.

    Parameters
    ----------
    rep : hyperrotor.quantum.Representation
        An irreducible representation of so(N) (``.N``, ``.dim``, ``.generators()``).
    L : array_like, shape ``(N(N-1)/2,)``
        Classical angular momentum, components in plane order.
    hbar : float, keyword-only, default 1
        Scale of the Hermitian generators :math:`\hat L_a = -i\hbar\rho(E_a)`.
    frame : {"space", "body"}
        ``"space"``: :math:`\langle\hat L_a\rangle = c\,L_a`; ``"body"``:
        :math:`\langle\hat L^{\rm body}_a\rangle = -\langle\hat L_a\rangle = c\,L_a`,
        the sign that follows the classical Euler equations forward in time.
        In both cases :math:`c = \hbar |w| / |L|` (:math:`w` the highest
        weight; for :math:`(l, 0, \dots)`, :math:`c = \hbar l/|L|`).
    rtol : float, optional
        Tolerance of the proportionality check :math:`\lambda \propto w`
        (default ``hr.options["quantum_coherent_rtol"]`` = 1e-8).

    Returns
    -------
    qutip.Qobj
        Normalized ket :math:`U(Q)|w\rangle` (see the module docstring).

    Raises
    ------
    ValueError
        ``L`` of the wrong length, zero, non-finite, or whose normal form is not
        proportional to the highest weight of ``rep`` (e.g. a non-simple
        bivector in an irrep :math:`(l, 0, \dots)`).
    """
    _validate.hbar(hbar)
    rtol = options["quantum_coherent_rtol"] if rtol is None else _validate.positive("rtol", rtol)
    frame = _validate.choice("frame", frame, ("space", "body"))
    _validate.representation("rep", rep)
    N = int(rep.N)
    comps = _validate.real_array("L", L)
    if comps.ndim != 1:
        raise ValueError(f"L must be one vector of {n_planes(N)} plane components for so({N}), got shape {comps.shape}")
    if comps.shape != (n_planes(N),):
        raise ValueError(f"L must have {n_planes(N)} components for so({N}), got {comps.shape[0]}")
    if not np.all(np.isfinite(comps)) or not np.any(comps):
        raise ValueError(f"L must be finite and non-zero, got {comps!r}")
    target = -comps if frame == "body" else comps
    Q, lam = normal_form_rotation(target)
    _priced_rotation(rep, Q)  # the rotation's price before the highest-weight search (apply_rotation below)
    psi_w, w = highest_weight_state(rep)
    if not np.any(np.abs(w) > 1e-9):
        raise ValueError("the representation is trivial (highest weight 0); no coherent state points along L")
    unit = lam / float(np.max(np.abs(lam)))  # (only its direction matters: |lam|^2 of 1e308 would be inf)

    def along(weight: np.ndarray) -> bool:
        """``unit`` is a positive multiple of ``weight`` (to ``rtol``)."""
        c = float(unit @ weight) / float(weight @ weight)
        return c > 0 and np.linalg.norm(unit - c * weight) <= rtol * np.linalg.norm(unit)

    if not along(w):
        of = "-L (frame='body': the state points along -L)" if frame == "body" else "L"
        hint = ""
        if frame == "body" and N % 4 == 2:  # (-1 is not a rotation in so(4k + 2): -L has the other chirality)
            flipped = w.copy()
            flipped[-1] = -flipped[-1]
            if along(flipped):
                hint = (f"; in so({N}) the normal forms of -L and L differ in the sign of their last entry: the irrep "
                        f"of highest weight ({', '.join(format(x, 'g') for x in flipped)}) has a body-frame coherent "
                        f"state along this L")
        raise ValueError(
            f"the normal form {np.round(lam, 12).tolist()} of {of} is not a positive multiple of the highest "
            f"weight {np.round(w, 12).tolist()} of the representation; a coherent state along it exists "
            f"only in an irrep whose highest weight is proportional to its normal form{hint}"
        )
    vec = apply_rotation(rep, Q, psi_w)
    vec /= np.linalg.norm(vec)
    return qutip.Qobj(vec.reshape(-1, 1), dims=[[int(rep.dim)], [1]])
