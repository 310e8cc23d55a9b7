r"""Quantum rigid rotors: Hamiltonians, time evolution and spectra (QuTiP layer).

The quantum rigid rotor in a representation :math:`\rho` of so(N) has the
Hamiltonian (the quantized kinetic energy, cf. eqs. 6 and 141)

.. math:: \hat H = \sum_{i<j} \frac{(\hat L^{ij})^2}{2 I_{ij}},
          \qquad \hat L^{ij} = -i\hbar\,\rho(E_{ij}),

with the physical plane moments :math:`I_{ij} = m_i + m_j` of
:class:`hyperrotor.Inertia` (same plane order as :func:`hyperrotor.planes`).
Because the generators :math:`\rho(E_{ij})` are real antisymmetric in the
real representations, :math:`\hat H = -\hbar^2\sum_a \rho(E_a)^2/(2I_a)` is a
real symmetric matrix, which the native propagators below exploit.

Frames and signs (the quantum/classical correspondence)
-------------------------------------------------------
For a representation (a Lie-algebra homomorphism,
:math:`[\rho(E_a), \rho(E_b)] = \sum_c C_{ab}^{\;c}\rho(E_c)` with the
structure constants of :func:`hyperrotor.structure_constants`) the Hermitian
generators obey

.. math:: [\hat L_a, \hat L_b] = -i\hbar \sum_c C_{ab}^{\;c}\,\hat L_c ,

the *space-frame* (normal) sign: in 3D, with :math:`\hat J_1 = \hat L^{23}`,
:math:`\hat J_2 = -\hat L^{13}`, :math:`\hat J_3 = \hat L^{12}`, this is
:math:`[\hat J_1, \hat J_2] = i\hbar \hat J_3`. The classical Euler equations
(:math:`\dot L = [\Omega, L]`, eq. 24) live in the *body* frame, whose
Lie-Poisson bracket is :math:`\{L_a, L_b\} = +\sum_c C_{ab}^{\;c} L_c`
(:func:`hyperrotor.lie_poisson_bracket`). Dirac's rule
:math:`[\cdot,\cdot] \leftrightarrow i\hbar\{\cdot,\cdot\}` therefore matches the
classical body-frame components with the *body-frame operators*

.. math:: \hat L^{\rm body}_a = -\hat L_a = i\hbar\,\rho(E_a),
          \qquad [\hat L^{\rm body}_a, \hat L^{\rm body}_b]
          = +i\hbar\sum_c C_{ab}^{\;c}\,\hat L^{\rm body}_c ,

(the "anomalous" sign of body-frame angular momentum). The Hamiltonian is the
same for both (it is quadratic), and the Heisenberg equations
:math:`\dot{\hat A} = (i/\hbar)[\hat H, \hat A]` give exactly the symmetrized
Euler equations, forward in time,

.. math:: \frac{d}{dt}\hat L^{\rm body}_a = \sum_{b,c} C_{bc}^{\;a}\,
          \tfrac12\big(\hat\omega_b \hat L^{\rm body}_c
          + \hat L^{\rm body}_c\hat\omega_b\big),
          \qquad \hat\omega_b = \hat L^{\rm body}_b / I_b .

So the classical solution :math:`L(t)` corresponds to
:math:`\langle\hat L^{\rm body}\rangle(t) = -\langle\hat L\rangle(t)`; the
expectation values of the representation's Hermitian generators themselves
follow the *time-reversed* Euler flow (equivalently, the Euler equations with
the opposite bracket). ``tests/quantum/test_correspondence.py`` checks both
statements as operator identities and along trajectories.

Evolution methods
-----------------
``"sesolve"`` / ``"mesolve"``
    QuTiP's solvers (``mesolve`` whenever collapse operators are given).
``"eigen"``
    Exact diagonalization (dense ``eigh``) of each block; refuses blocks
    larger than ``options["max_dense_dim"]`` (default 6000).
``"krylov"``
    Lanczos (Krylov) propagation with full re-orthogonalization and the
    a-posteriori error estimate of Saad (1992) / Hochbruck & Lubich (1997):
    one Krylov space serves every output time it can reach to the tolerance
    ``options["atol"]`` (default ``1e-12`` per restart, in the 2-norm).
``"expm_multiply"``
    :func:`scipy.sparse.linalg.expm_multiply` over the time grid
    (Al-Mohy & Higham 2011).
``"auto"``
    ``mesolve`` with collapse operators; otherwise the block decomposition
    below, then ``"eigen"`` for blocks of dimension <= 400 and ``"krylov"``
    on the union of the larger populated blocks.

Symmetry-adapted evolution
--------------------------
When :math:`\hat H` commutes with a Casimir of a subalgebra that the basis
diagonalizes, the matrix of :math:`\hat H` is block diagonal in that basis:
equal moments make :math:`\hat H = C_2(\mathrm{so}(N))/(2I)` diagonal in any
basis of an irrep; the quartet inertia of eqs. (84)-(85) (distinguished axis
5) gives :math:`\hat H = C_2(\mathrm{so}(5))/(2(1+\kappa^2)) +
C_2(\mathrm{so}(4))\,(1/4 - 1/(2(1+\kappa^2)))`, diagonal in the
Gelfand-Tsetlin basis of so(5) ⊃ so(4). :func:`symmetry_blocks` finds the
blocks as the connected components of the sparsity graph of :math:`\hat H`,
and :func:`evolve` propagates only the blocks that ``psi0`` populates: blocks
of dimension one as phases, ``"eigen"`` block by block, the Krylov-type methods
on the union of the populated blocks (one Krylov space for all of them).
"""
from __future__ import annotations

import time as _time
import warnings
from numbers import Real
from typing import Any, Iterator, Sequence

import numpy as np
import qutip
import scipy.linalg as sla
import scipy.sparse as sps
from scipy.sparse.csgraph import connected_components
from scipy.sparse.linalg import expm_multiply

from ..conventions import n_planes, planes

__all__ = [
    "EVOLVE_METHODS",
    "rotor_hamiltonian",
    "evolve",
    "spectrum",
    "symmetry_blocks",
]

#: Names accepted by ``evolve(method=...)``.
EVOLVE_METHODS = ("auto", "sesolve", "mesolve", "eigen", "krylov", "expm_multiply")

#: Defaults of the native (non-QuTiP) evolution options.
_NATIVE_DEFAULTS = {
    "atol": 1e-12,
    "krylov_dim": 30,
    "max_dense_dim": 6000,
    "blocks": "auto",
    "block_atol": None,
    "eigen_max_block": 400,
    "store_states": None,
    "store_final_state": True,
    "progress_bar": "",
    "progress_kwargs": None,
}


# ----------------------------------------------------------------------------
# input validation
# ----------------------------------------------------------------------------
def _moments_for(inertia: Any, N: int) -> np.ndarray:
    """Plane moments (plane order) of ``inertia`` for so(N), validated."""
    if hasattr(inertia, "moments") and hasattr(inertia, "N"):
        if int(inertia.N) != N:
            raise ValueError(
                f"the inertia is for N = {inertia.N} but the representation is of so({N}); "
                f"they must act on the same dimension"
            )
        moments = np.asarray(inertia.moments, dtype=float)
    else:
        try:
            moments = np.asarray(inertia, dtype=float)
        except (TypeError, ValueError):
            raise TypeError(
                f"inertia must be a hyperrotor.Inertia or a sequence of {n_planes(N)} plane moments, "
                f"got {type(inertia).__name__}"
            ) from None
        if moments.shape != (n_planes(N),):
            raise ValueError(
                f"inertia has shape {moments.shape}; so({N}) needs {n_planes(N)} plane moments "
                f"(planes {', '.join(f'{i}{j}' for i, j in planes(N))})"
            )
    if not np.all(np.isfinite(moments)) or np.any(moments <= 0):
        bad = {f"I_{i}{j}": float(m) for (i, j), m in zip(planes(N), moments) if not (np.isfinite(m) and m > 0)}
        raise ValueError(f"moments of inertia must be finite and positive, got {bad}")
    return moments


def _operator_matrix(H: Any, name: str = "H") -> tuple[sps.csr_matrix, list]:
    """Return ``(csr, dims)`` of a square operator given as Qobj, sparse or dense matrix."""
    if isinstance(H, qutip.Qobj):
        if not H.isoper:
            raise ValueError(f"{name} must be an operator, got a Qobj of type {H.type!r}")
        mat = H.to("CSR").data.as_scipy().tocsr()
        dims = H.dims
    elif sps.issparse(H):
        mat = sps.csr_matrix(H)
        dims = [[mat.shape[0]], [mat.shape[1]]]
    elif isinstance(H, np.ndarray):
        if H.ndim != 2:
            raise ValueError(f"{name} must be a 2-D matrix, got an array of shape {H.shape}")
        mat = sps.csr_matrix(H)
        dims = [[H.shape[0]], [H.shape[1]]]
    else:
        raise TypeError(f"{name} must be a qutip.Qobj, a scipy.sparse matrix or a 2-D ndarray, got {type(H).__name__}")
    if mat.shape[0] != mat.shape[1]:
        raise ValueError(f"{name} must be square, got shape {mat.shape}")
    if mat.dtype.kind not in "fc":
        mat = mat.astype(float)
    if mat.dtype.kind == "c" and (mat.nnz == 0 or np.all(mat.data.imag == 0)):
        mat = sps.csr_matrix(mat.real)
    return mat, dims


def _hermitian_matrix(H: Any) -> tuple[sps.csr_matrix, list]:
    mat, dims = _operator_matrix(H)
    diff = (mat - mat.conj().T).tocsr()
    scale = max(1.0, float(np.max(np.abs(mat.data))) if mat.nnz else 1.0)
    if diff.nnz and float(np.max(np.abs(diff.data))) > 1e-12 * scale:
        raise ValueError(
            f"H must be Hermitian: max |H - H^dagger| = {float(np.max(np.abs(diff.data))):.3g} "
            f"(relative tolerance 1e-12 of max |H| = {scale:.3g})"
        )
    return mat, dims


def _state_vector(psi0: Any, dim: int) -> np.ndarray:
    if isinstance(psi0, qutip.Qobj):
        if not psi0.isket:
            raise ValueError(f"psi0 must be a ket, got a Qobj of type {psi0.type!r}")
        vec = psi0.full().ravel()
    else:
        vec = np.asarray(psi0)
        if vec.dtype.kind not in "biufc":
            raise TypeError(f"psi0 must be a ket Qobj or a numeric vector, got dtype {vec.dtype}")
        if vec.ndim == 2 and vec.shape[1] == 1:
            vec = vec[:, 0]
        if vec.ndim != 1:
            raise ValueError(f"psi0 must be a vector (ket), got shape {vec.shape}")
    if vec.shape[0] != dim:
        raise ValueError(f"psi0 has dimension {vec.shape[0]} but H has dimension {dim}")
    vec = vec.astype(complex)
    if not np.all(np.isfinite(vec)):
        raise ValueError("psi0 contains non-finite amplitudes")
    nrm = float(np.linalg.norm(vec))
    if nrm == 0:
        raise ValueError("psi0 is the zero vector; it cannot be normalized")
    if abs(nrm - 1) > 1e-10:
        warnings.warn(f"psi0 has norm {nrm:.12g}; evolving the normalized state psi0/|psi0|", UserWarning, stacklevel=3)
        vec = vec / nrm
    return vec


def _check_times(times: Any) -> np.ndarray:
    t = np.asarray(times, dtype=float) if not isinstance(times, np.ndarray) else times.astype(float)
    if t.ndim != 1 or t.size == 0:
        raise ValueError(f"times must be a non-empty 1-D sequence, got shape {np.shape(times)}")
    if not np.all(np.isfinite(t)):
        raise ValueError("times must be finite")
    if t.size > 1 and np.any(np.diff(t) <= 0):
        k = int(np.argmax(np.diff(t) <= 0))
        raise ValueError(f"times must be strictly increasing; times[{k}] = {t[k]!r} >= times[{k + 1}] = {t[k + 1]!r}")
    return t


def _check_hbar(hbar: Any) -> float:
    if isinstance(hbar, bool) or not isinstance(hbar, Real) or not np.isfinite(hbar) or hbar <= 0:
        raise ValueError(f"hbar must be a positive finite number, got {hbar!r}")
    return float(hbar)


# ----------------------------------------------------------------------------
# Hamiltonian
# ----------------------------------------------------------------------------
def rotor_hamiltonian(rep: Any, inertia: Any, hbar: float = 1.0) -> qutip.Qobj:
    r"""Rigid-rotor Hamiltonian :math:`\hat H = \sum_{i<j} (\hat L^{ij})^2/(2I_{ij})` of a representation.

    Parameters
    ----------
    rep : hyperrotor.quantum.Representation
        Any object with ``.N``, ``.dim`` and ``.generators()`` (dict plane ->
        anti-Hermitian sparse matrix :math:`\rho(E_{ij})`).
    inertia : hyperrotor.Inertia or sequence of float
        The physical plane moments :math:`I_{ij} = m_i + m_j` (``Inertia.moments``,
        plane order); a plain sequence of ``N(N-1)/2`` positive numbers is accepted.
    hbar : float, default 1
        :math:`\hat L^{ij} = -i\hbar\rho(E_{ij})` (eq. 141), so energies scale as
        :math:`\hbar^2`.

    Returns
    -------
    qutip.Qobj
        Hermitian operator of dimension ``rep.dim`` (real symmetric matrix for
        real representations), ``dims = [[rep.dim], [rep.dim]]``.

    Raises
    ------
    ValueError
        If the inertia belongs to another N, a moment is not positive, or hbar <= 0.
    TypeError
        If the inertia is symbolic or not a sequence of numbers.

    Notes
    -----
    :math:`\hat H = -\hbar^2 \sum_a \rho(E_a)^2/(2 I_a)`. For equal moments it is
    :math:`C_2/(2I)` with the so(N) Casimir :math:`C_2 = \sum_a \hat L_a^2`
    (eq. 38's quadratic invariant, quantized).
    """
    hbar = _check_hbar(hbar)
    N = int(rep.N)
    moments = _moments_for(inertia, N)
    gens = rep.generators()
    dim = int(rep.dim)
    H = sps.csr_matrix((dim, dim), dtype=float)
    for (i, j), m in zip(planes(N), moments):
        try:
            G = sps.csr_matrix(gens[(i, j)])
        except KeyError:
            raise ValueError(f"the representation has no generator for plane ({i}, {j})") from None
        H = H + (G @ G) * (-(hbar**2) / (2.0 * m))
    H = sps.csr_matrix(H)
    if H.dtype.kind == "c" and np.all(H.data.imag == 0):
        H = sps.csr_matrix(H.real)
    H.sum_duplicates()
    H.eliminate_zeros()
    return qutip.Qobj(H, dims=[[dim], [dim]])


# ----------------------------------------------------------------------------
# symmetry blocks
# ----------------------------------------------------------------------------
def symmetry_blocks(H: Any, *, atol: float | None = None) -> list[np.ndarray]:
    r"""Invariant blocks of ``H``: connected components of its sparsity graph.

    Parameters
    ----------
    H : qutip.Qobj, scipy.sparse matrix or ndarray
        Square operator.
    atol : float, optional
        Entries with :math:`|H_{kl}| \le` ``atol`` are treated as zero
        (default ``1e-14 * max|H|``, which removes round-off couplings such as
        those of :math:`C_2/(2I)` in a non-diagonal basis).

    Returns
    -------
    list of ndarray
        Sorted index arrays, one per block, ordered by their smallest index;
        together a partition of ``range(dim)``.

    Notes
    -----
    In a basis that diagonalizes a Casimir commuting with ``H`` (e.g. the
    Gelfand-Tsetlin basis and the so(4) Casimir for the quartet inertia of
    eqs. 84-85) every block lies inside one Casimir eigenspace, so the blocks
    are at least as fine as the Casimir decomposition. They also pick up
    discrete symmetries that happen to be diagonal in the basis (e.g. the
    rotation by :math:`\pi` in a plane whose generator is diagonal).
    """
    mat, _ = _operator_matrix(H)
    return _blocks_of(mat, atol)


def _blocks_of(mat: sps.csr_matrix, atol: float | None) -> list[np.ndarray]:
    n = mat.shape[0]
    if mat.nnz == 0:
        return [np.array([k]) for k in range(n)]
    scale = float(np.max(np.abs(mat.data)))
    thr = 1e-14 * scale if atol is None else float(atol)
    a = mat.copy()
    a.data = (np.abs(a.data) > thr).astype(np.int8)
    a.eliminate_zeros()
    ncomp, labels = connected_components(a, directed=False)
    order = np.argsort(labels, kind="stable")
    counts = np.bincount(labels, minlength=ncomp)
    parts = np.split(order, np.cumsum(counts)[:-1])
    parts.sort(key=lambda p: p[0])
    return parts


# ----------------------------------------------------------------------------
# native propagators (generators yielding the block state at each time)
# ----------------------------------------------------------------------------
def _matvec_factory(mat: sps.csr_matrix):
    """``v -> mat @ v`` for complex ``v``; a real matrix is applied to (Re, Im) in one pass."""
    if mat.dtype.kind == "f":
        def mv(v: np.ndarray) -> np.ndarray:
            x = np.ascontiguousarray(v).view(np.float64).reshape(-1, 2)
            return np.ascontiguousarray(mat @ x).reshape(-1).view(np.complex128)
        return mv
    return lambda v: mat @ v


def _eigen_propagator(mat, v0, times, hbar, stats) -> Iterator[np.ndarray]:
    dense = mat.toarray()
    E, V = np.linalg.eigh(dense)
    stats["n_eigh"] = stats.get("n_eigh", 0) + 1
    c = V.conj().T @ v0
    for t in times:
        yield V @ (np.exp(-1j * E * ((t - times[0]) / hbar)) * c)


def _diagonal_propagator(diag, v0, times, hbar) -> Iterator[np.ndarray]:
    for t in times:
        yield np.exp(-1j * diag * ((t - times[0]) / hbar)) * v0


def _expm_propagator(mat, v0, times, hbar, stats) -> Iterator[np.ndarray]:
    A = (-1j / hbar) * mat.astype(complex)
    dt = np.diff(times)
    if times.size > 2 and np.allclose(dt, dt[0], rtol=1e-13, atol=0):
        states = expm_multiply(A, v0, start=0.0, stop=times[-1] - times[0], num=times.size, endpoint=True)
        stats["n_expm"] = stats.get("n_expm", 0) + 1
        yield from states
        return
    v = v0
    yield v
    for h in dt:
        v = expm_multiply(A * h, v)
        stats["n_expm"] = stats.get("n_expm", 0) + 1
        yield v


def _single_thread_blas():
    """Run the thin Krylov products on one BLAS thread (restored afterwards).

    The products of the ``(m, dim)`` Krylov basis with vectors gain nothing from
    threads, and on a loaded machine OpenBLAS thread over-subscription made them
    ~10x slower in our measurements. Uses ``threadpoolctl``.
    """
    from threadpoolctl import threadpool_limits

    return threadpool_limits(limits=1, user_api="blas")


def _norm(v: np.ndarray) -> float:
    x = v.view(np.float64) if v.dtype == np.complex128 and v.flags.c_contiguous else np.concatenate([v.real, v.imag])
    return float(np.sqrt(x @ x))


def _krylov_propagator(mat, v0, times, hbar, stats, *, tol: float, m_max: int) -> Iterator[np.ndarray]:
    """Lanczos propagation of ``exp(-i H t / hbar) v0`` on a time grid.

    Each restart builds an orthonormal Krylov basis ``V`` of dimension ``m`` at the
    current state ``v`` (norm ``beta0``) with the tridiagonal ``T``; then
    ``exp(-i H tau/hbar) v ~ beta0 V exp(-i T tau/hbar) e1`` with the error estimate
    ``beta0 * beta_m * |e_m^T exp(-i T tau/hbar) e1|``. Every remaining output
    time whose estimate is <= ``tol`` is served from this basis; the next restart
    begins at the last of them (or, if none is reachable, after a sub-step ``tau``
    meeting the tolerance, found by bisection).
    """
    n = v0.shape[0]
    mv = _matvec_factory(mat)
    m_max = max(1, min(int(m_max), n))
    t_cur = times[0]
    v = v0.astype(complex)
    yield v
    k = 1
    nt = times.size
    V = np.empty((m_max + 1, n), dtype=complex)
    while k < nt:
        beta0 = _norm(v)
        V[0] = v / beta0
        alpha = np.zeros(m_max)
        beta = np.zeros(m_max)
        m = m_max
        breakdown = False
        for j in range(m_max):
            w = mv(V[j])
            stats["n_matvec"] = stats.get("n_matvec", 0) + 1
            alpha[j] = np.vdot(V[j], w).real
            w -= alpha[j] * V[j]
            if j > 0:
                w -= beta[j - 1] * V[j - 1]
            Vj = V[: j + 1]
            for _ in range(2):  # full re-orthogonalization (classical Gram-Schmidt, twice)
                w -= (Vj @ w.conj()).conj() @ Vj  # (V^H w) without copying V
            beta[j] = _norm(w)
            if beta[j] <= 1e-13 * max(1.0, abs(alpha[j])):
                m = j + 1
                breakdown = True
                break
            V[j + 1] = w / beta[j]
        stats["n_krylov"] = stats.get("n_krylov", 0) + 1
        if m == 1:
            theta, S = np.array([alpha[0]]), np.ones((1, 1))
        else:
            theta, S = sla.eigh_tridiagonal(alpha[:m], beta[: m - 1])
        s0 = S[0, :]
        bm = 0.0 if breakdown else beta[m - 1]

        def coeffs(tau: np.ndarray) -> np.ndarray:
            # columns: exp(-i T tau/hbar) e1 for each tau
            return S @ (np.exp(-1j * np.outer(theta, tau) / hbar) * s0[:, None])

        Tm = np.diag(alpha[:m]) + np.diag(beta[: m - 1], 1) + np.diag(beta[: m - 1], -1)

        floor = 4 * m * np.finfo(float).eps * beta0 * bm

        def err(tau: np.ndarray) -> np.ndarray:
            # beta0 beta_m |e_m^T exp(-i T tau/hbar) e1|. From the eigen-decomposition the value
            # has an absolute round-off floor ~ m eps beta0 beta_m: above it, return the safe
            # bound value + floor; when tol is close to the floor, use Pade instead (scipy expm
            # keeps the exact zeros of the powers of the tridiagonal T, so tiny values keep
            # their relative accuracy).
            tau = np.asarray(tau, dtype=float)
            if bm == 0.0:
                return np.zeros(len(tau))
            if tol > 2 * floor:
                return beta0 * bm * np.abs(coeffs(tau)[m - 1]) + floor
            E = sla.expm((-1j / hbar) * tau[:, None, None] * Tm[None])
            return beta0 * bm * np.abs(E[:, m - 1, 0])

        taus = times[k:] - t_cur
        # serve the output times in order, checking them in growing batches
        nok, start, batch = 0, 0, 4
        while start < len(taus):
            ok = err(taus[start : start + batch]) <= tol
            nok = start + (len(ok) if ok.all() else int(np.argmin(ok)))
            if not ok.all():
                break
            start, batch = start + batch, 2 * batch
        if nok > 0:
            C = coeffs(taus[:nok]) * beta0
            for q in range(nok):
                state = C[:, q] @ V[:m]
                yield state
            v = state
            t_cur = times[k + nok - 1]
            k += nok
        else:
            # largest sub-step meeting the tolerance (bisection; the estimate grows ~ tau^m)
            lo, hi = 0.0, taus[0]
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                if err(np.array([mid]))[0] <= tol:
                    lo = mid
                else:
                    hi = mid
                if hi - lo <= 1e-3 * hi:
                    break
            if lo <= 0:
                raise RuntimeError(
                    f"Krylov propagation cannot meet atol = {tol:.3g}; increase options['krylov_dim'] or atol"
                )
            tau = lo
            v = beta0 * (coeffs(np.array([tau]))[:, 0] @ V[:m])
            t_cur = t_cur + tau


# ----------------------------------------------------------------------------
# evolve
# ----------------------------------------------------------------------------
def _e_ops_list(e_ops: Any, dims) -> Any:
    """e_ops as QuTiP accepts them, with scipy.sparse / ndarray operators wrapped as Qobj."""

    def conv(op):
        if sps.issparse(op) or isinstance(op, np.ndarray):
            return qutip.Qobj(op, dims=dims)
        return op

    if e_ops is None:
        return []
    if isinstance(e_ops, dict):
        return {k: conv(op) for k, op in e_ops.items()}
    if isinstance(e_ops, (list, tuple)):
        return [conv(op) for op in e_ops]
    return [conv(e_ops)]


def _split_options(options: Any) -> tuple[dict, dict]:
    if options is None:
        options = {}
    if not isinstance(options, dict):
        raise TypeError(f"options must be a dict or None, got {type(options).__name__}")
    native = dict(_NATIVE_DEFAULTS)
    other = {}
    for key, val in options.items():
        if key in native:
            native[key] = val
        else:
            other[key] = val
    return native, other


def evolve(
    H: Any,
    psi0: Any,
    times: Sequence[float],
    e_ops: Any = None,
    method: str = "auto",
    c_ops: Any = None,
    options: dict | None = None,
    *,
    hbar: float = 1.0,
):
    r"""Evolve ``psi0`` under :math:`i\hbar\,\partial_t\psi = \hat H\psi` on the time grid ``times``.

    Parameters
    ----------
    H : qutip.Qobj, scipy.sparse matrix or ndarray
        Hermitian, time-independent Hamiltonian (e.g. :func:`rotor_hamiltonian`).
    psi0 : qutip.Qobj (ket) or array_like
        Initial state at ``times[0]``, of the dimension of ``H``. A state whose
        norm differs from 1 by more than ``1e-10`` is normalized with a
        ``UserWarning``; the zero vector is refused.
    times : sequence of float
        Strictly increasing output times; ``times[0]`` is the time of ``psi0``.
    e_ops : Qobj, sparse matrix, callable, or list/dict of these, optional
        Operators whose expectation values are recorded (as in QuTiP).
    method : {"auto", "sesolve", "mesolve", "eigen", "krylov", "expm_multiply"}
        See the module docstring. ``"auto"`` is ``"mesolve"`` when ``c_ops`` are
        given, otherwise the symmetry-adapted native propagation.
    c_ops : list of Qobj, optional
        Collapse operators (only with ``"mesolve"``/``"auto"``).
    options : dict, optional
        Native methods: ``"atol"`` (Krylov tolerance per restart, default 1e-12),
        ``"krylov_dim"`` (30), ``"max_dense_dim"`` (6000, largest block the
        ``"eigen"`` method diagonalizes), ``"blocks"`` (``"auto"``/``True``: evolve
        only the populated invariant blocks of :func:`symmetry_blocks`;
        ``False``: one block), ``"block_atol"`` (``atol`` of
        :func:`symmetry_blocks`), ``"eigen_max_block"`` (400: ``"auto"`` uses
        ``"eigen"`` up to this block size, Krylov above), ``"store_states"``,
        ``"store_final_state"``, ``"progress_bar"`` (``""``, ``"text"``,
        ``"enhanced"``, ``"tqdm"``: QuTiP's progress bars, updated per output
        time) and ``"progress_kwargs"``. For ``"sesolve"``/``"mesolve"`` every
        key except the native-only ones is passed to QuTiP (e.g. ``"atol"``,
        ``"rtol"``, ``"nsteps"``, ``"method"``, ``"progress_bar"``).
    hbar : float, keyword-only, default 1
        Planck's constant of the Schrödinger equation (QuTiP's solvers get
        ``H / hbar``). Use the same value as in :func:`rotor_hamiltonian`.

    Returns
    -------
    qutip.solver.Result
        A genuine QuTiP ``Result``: ``times``, ``states`` (stored when no
        ``e_ops`` are given, or with ``store_states=True``), ``expect``,
        ``e_data``, ``final_state`` and ``stats`` (native methods record
        ``"method"``, ``"blocks"``, ``"populated_blocks"``,
        ``"populated_dim"``, ``"n_matvec"``, ``"n_krylov"``, ``"run time"``).

    Raises
    ------
    ValueError
        Non-Hermitian ``H``; ``psi0`` of the wrong dimension or zero; times not
        strictly increasing; unknown method; ``c_ops`` with a closed-system
        method; a block too large for ``"eigen"``.
    """
    if method not in EVOLVE_METHODS:
        raise ValueError(f"unknown method {method!r}; allowed: {', '.join(map(repr, EVOLVE_METHODS))}")
    hbar = _check_hbar(hbar)
    mat, dims = _hermitian_matrix(H)
    dim = mat.shape[0]
    vec = _state_vector(psi0, dim)
    t = _check_times(times)
    native, other = _split_options(options)
    if c_ops:
        if method not in ("auto", "mesolve"):
            raise ValueError(f"collapse operators need method 'mesolve' (or 'auto'), got method {method!r}")
        method = "mesolve"
    ket_dims = [dims[0], [1]]
    if method in ("sesolve", "mesolve"):
        Hq = qutip.Qobj(mat / hbar, dims=dims)
        psi = qutip.Qobj(vec, dims=ket_dims)
        qopts = dict(other)
        for key in ("store_states", "store_final_state", "progress_bar", "progress_kwargs"):
            if options is not None and key in options:
                qopts[key] = options[key]
        if "atol" in (options or {}):
            qopts["atol"] = options["atol"]
        eo = _e_ops_list(e_ops, dims)
        if method == "sesolve":
            return qutip.sesolve(Hq, psi, t, e_ops=eo, options=qopts)
        return qutip.mesolve(Hq, psi, t, c_ops=list(c_ops or []), e_ops=eo, options=qopts)
    if other:
        raise ValueError(
            f"unknown option(s) {sorted(other)} for method {method!r}; allowed: {sorted(_NATIVE_DEFAULTS)}"
        )
    return _evolve_native(mat, dims, vec, t, _e_ops_list(e_ops, dims), method, native, hbar)


def _evolve_native(mat, dims, vec, t, e_ops, method, opt, hbar):
    t_start = _time.perf_counter()
    dim = mat.shape[0]
    stats: dict[str, Any] = {"method": method}
    use_blocks = opt["blocks"]
    if use_blocks not in ("auto", True, False):
        raise ValueError(f"options['blocks'] must be 'auto', True or False, got {use_blocks!r}")
    if use_blocks:
        blocks = _blocks_of(mat, opt["block_atol"])
    else:
        blocks = [np.arange(dim)]
    stats["blocks"] = len(blocks)
    populated = [b for b in blocks if np.any(vec[b] != 0)]
    stats["populated_blocks"] = len(populated)
    stats["populated_dim"] = int(sum(len(b) for b in populated))
    singles = np.array([b[0] for b in populated if len(b) == 1], dtype=int)
    multi = [b for b in populated if len(b) > 1]
    if method == "eigen":
        big = max((len(b) for b in multi), default=0)
        if big > int(opt["max_dense_dim"]):
            raise ValueError(
                f"method 'eigen' would diagonalize a dense block of dimension {big} > "
                f"options['max_dense_dim'] = {opt['max_dense_dim']}; use method 'krylov' or raise the limit"
            )
    props = []
    if singles.size:
        diag = mat.diagonal()[singles].real
        props.append((singles, _diagonal_propagator(diag, vec[singles], t, hbar)))
    # Krylov-type methods: one problem on the union of the populated blocks (the union is
    # invariant, and one Krylov space serves all blocks with fewer restarts and calls);
    # "eigen": every block on its own (cubic cost). "auto": eigen for small blocks.
    small = [b for b in multi if method == "eigen" or (method == "auto" and len(b) <= int(opt["eigen_max_block"]))]
    large = [b for b in multi if not (method == "eigen" or (method == "auto" and len(b) <= int(opt["eigen_max_block"])))]
    jobs = [(b, "eigen") for b in small]
    if large:
        jobs.append((np.sort(np.concatenate(large)), "krylov" if method == "auto" else method))
    used = set()
    for b, m in jobs:
        sub = mat[b][:, b].tocsr()
        used.add(m)
        if m == "eigen":
            gen = _eigen_propagator(sub, vec[b], t, hbar, stats)
        elif m == "krylov":
            gen = _krylov_propagator(sub, vec[b], t, hbar, stats, tol=float(opt["atol"]), m_max=int(opt["krylov_dim"]))
        else:
            gen = _expm_propagator(sub, vec[b], t, hbar, stats)
        props.append((b, gen))
    stats["block_methods"] = sorted(used) if used else ["diagonal"]
    ropts = {
        "store_states": opt["store_states"],
        "store_final_state": opt["store_final_state"],
        "normalize_output": False,
    }
    result = qutip.solver.Result(e_ops, ropts, solver=f"hyperrotor.evolve[{method}]", stats=stats)
    pkw = opt["progress_kwargs"] or {}
    try:
        bar = qutip.ui.progressbar.progress_bars[opt["progress_bar"]](len(t), **pkw)
    except KeyError:
        raise ValueError(
            f"unknown progress_bar {opt['progress_bar']!r}; allowed: '', 'text', 'enhanced', 'tqdm', 'html'"
        ) from None
    ket_dims = [dims[0], [1]]
    full = np.zeros(dim, dtype=complex)
    for tk in t:
        full[:] = 0
        with _single_thread_blas():
            for idx, gen in props:
                full[idx] = next(gen)
        result.add(float(tk), qutip.Qobj(full.reshape(-1, 1).copy(), dims=ket_dims, copy=False))
        bar.update()
    bar.finished()
    stats["run time"] = _time.perf_counter() - t_start
    return result


# ----------------------------------------------------------------------------
# spectrum
# ----------------------------------------------------------------------------
def spectrum(H: Any, *, tol: float | None = None, max_dense_dim: int = 6000) -> tuple[np.ndarray, np.ndarray]:
    r"""Energy levels of a Hermitian ``H`` with their degeneracies.

    Parameters
    ----------
    H : qutip.Qobj, scipy.sparse matrix or ndarray
        Hermitian operator.
    tol : float, optional
        Eigenvalues closer than ``tol`` to their neighbour are one level (chained
        clustering of the sorted eigenvalues). Default
        ``1e-9 * max(1, max|E|)``, far above the round-off of ``eigh``
        (~``1e-15 * dim * max|E|``) and below any physical splitting of interest.
    max_dense_dim : int, default 6000
        Largest invariant block (see :func:`symmetry_blocks`) diagonalized densely.

    Returns
    -------
    levels : ndarray
        Increasing distinct energies (the mean of each cluster).
    degeneracies : ndarray of int
        Multiplicity of each level; they sum to ``dim``.
    """
    mat, _ = _hermitian_matrix(H)
    blocks = _blocks_of(mat, None)
    big = max(len(b) for b in blocks)
    if big > int(max_dense_dim):
        raise ValueError(f"spectrum would diagonalize a dense block of dimension {big} > max_dense_dim = {max_dense_dim}")
    evs = []
    for b in blocks:
        if len(b) == 1:
            evs.append(np.array([mat[b[0], b[0]].real]))
        else:
            evs.append(np.linalg.eigvalsh(mat[b][:, b].toarray()))
    E = np.sort(np.concatenate(evs).real)
    if tol is None:
        tol = 1e-9 * max(1.0, float(np.max(np.abs(E))))
    if not (isinstance(tol, Real) and tol >= 0):
        raise ValueError(f"tol must be a non-negative number, got {tol!r}")
    cuts = np.nonzero(np.diff(E) > tol)[0] + 1
    groups = np.split(E, cuts)
    return np.array([g.mean() for g in groups]), np.array([g.size for g in groups], dtype=int)
