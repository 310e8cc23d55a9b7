r"""Time evolution of quantum rotors: :func:`evolve` and its propagators.

:func:`evolve` solves :math:`i\hbar\,\partial_t\psi = \hat H\psi` on a time
grid ``t`` (the spelling of :func:`hyperrotor.simulate`) with one of the
propagators registered in :data:`PROPAGATORS` (QuTiP's ``solver_base``
integrator registry is the model). Each propagator is a small class with
its own option table (:attr:`Propagator.options`: key -> (default, meaning));
``evolve(..., options={...})`` accepts the keys of :data:`RESULT_OPTIONS`
plus those of the chosen method, and refuses any other key, naming the
allowed ones. Defaults written ``None`` are read from the package's option
table :data:`hyperrotor.options` (e.g. ``quantum_krylov_atol``) at call time;
the largest dense block, ``quantum_max_dense_dim``, lives only there.

``"auto"``
    ``"mesolve"`` with collapse operators; otherwise the symmetry-adapted
    native propagation: ``"eigen"`` for blocks up to ``eigen_max_block``,
    ``"krylov"`` on the union of the larger populated blocks.
``"eigen"``
    Exact diagonalization (dense ``eigh``) of each block.
``"krylov"``
    Lanczos with full re-orthogonalization and the a-posteriori error
    estimate of Saad (1992) / Hochbruck & Lubich (1997): one Krylov space
    serves every output time it reaches within ``atol``.
``"expm_multiply"``
    :func:`scipy.sparse.linalg.expm_multiply` over the grid (Al-Mohy & Higham 2011).
``"sesolve"``, ``"mesolve"``
    QuTiP's solvers on ``H/hbar``; their options are QuTiP's.

Symmetry-adapted evolution: the native methods split ``H`` into its invariant
blocks (:func:`~hyperrotor.quantum.symmetry_blocks`) and propagate only the
blocks that ``psi0`` populates: blocks of dimension one as phases, ``"eigen"``
block by block, the Krylov-type methods on the union of the populated blocks
(one Krylov space for all of them).
"""
from __future__ import annotations

import time as _time
import warnings
from typing import Any, ClassVar, Iterator, Sequence

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sps
from scipy.sparse.linalg import expm_multiply

from .. import _lazy, _validate
from .._options import options as _options
from .hamiltonian import blocks_of, hermitian_matrix

__all__ = ["EVOLVE_METHODS", "PROPAGATORS", "RESULT_OPTIONS", "Propagator", "evolve", "evolve_options", "register_propagator"]

#: Options of every method: what the returned ``qutip.solver.Result`` keeps and the progress bar.
RESULT_OPTIONS: dict[str, tuple[Any, str]] = {
    "store_states": (None, "keep every state (default: when no e_ops are given)"),
    "store_final_state": (True, "keep the final state"),
    "progress_bar": ("", "'', 'text', 'enhanced', 'tqdm' or 'html' (QuTiP's bars, updated per output time)"),
    "progress_kwargs": (None, "keyword arguments of the progress bar"),
}

#: Options of every native method (symmetry blocks).
_BLOCK_OPTIONS: dict[str, tuple[Any, str]] = {
    "blocks": ("auto", "'auto'/True: evolve only the populated invariant blocks of symmetry_blocks; False: one block"),
    "block_atol": (None, "absolute threshold of symmetry_blocks (default: options['quantum_block_rtol'] * max|H|)"),
}


# ----------------------------------------------------------------------------
# propagators
# ----------------------------------------------------------------------------
class Propagator:
    """One method of :func:`evolve`: a name, an option table, and how it propagates a block.

    Subclasses set :attr:`name`, :attr:`options` (key -> ``(default, meaning)``;
    a default ``None`` means "read from :data:`hyperrotor.options` at call
    time") and implement :meth:`propagate` (native methods) or :meth:`run`
    (methods that hand the whole problem to another library). Register a
    subclass with :func:`register_propagator`; :data:`PROPAGATORS` is the one
    table that :func:`evolve`, the docs and the tests iterate over.
    """

    name: ClassVar[str] = ""
    native: ClassVar[bool] = True
    #: Krylov-type methods propagate the union of the populated blocks in one problem.
    union_blocks: ClassVar[bool] = False
    options: ClassVar[dict[str, tuple[Any, str]]] = {}

    def __init__(self, **opts: Any) -> None:
        self.opts = opts

    @classmethod
    def allowed_options(cls) -> dict[str, tuple[Any, str]]:
        """Every option key this method accepts, with ``(default, meaning)``."""
        extra = _BLOCK_OPTIONS if cls.native else {}
        return {**RESULT_OPTIONS, **extra, **cls.options}

    @classmethod
    def resolve_options(cls, given: dict | None) -> dict:
        """Defaults merged with ``given``; unknown keys raise ``ValueError`` naming the allowed ones."""
        if given is None:
            given = {}
        if not isinstance(given, dict):
            raise TypeError(f"options must be a dict or None, got {type(given).__name__}")
        allowed = cls.allowed_options()
        unknown = sorted(set(given) - set(allowed))
        if unknown:
            hint = ""
            if "max_dense_dim" in unknown:
                hint = "; the largest dense block is hyperrotor.options['quantum_max_dense_dim'] (one home for spectrum and evolve)"
            raise ValueError(
                f"unknown option(s) {unknown} for method {cls.name!r}; allowed: {sorted(allowed)}{hint}"
            )
        return {k: given.get(k, d) for k, (d, _) in allowed.items()}

    def propagate(self, mat: sps.csr_matrix, v0: np.ndarray, t: np.ndarray, hbar: float,
                  stats: dict) -> Iterator[np.ndarray]:  # pragma: no cover - abstract
        """Yield the state of the block at every time of ``t`` (``t[0]`` is the time of ``v0``)."""
        raise NotImplementedError

    def plan(self, blocks: list[np.ndarray]) -> list[tuple[np.ndarray, "Propagator"]]:
        """Jobs ``(indices, propagator)`` for the populated multi-dimensional blocks."""
        if not blocks:
            return []
        if self.union_blocks:
            return [(np.sort(np.concatenate(blocks)), self)]
        return [(b, self) for b in blocks]


#: The registry: method name -> Propagator subclass (``"auto"`` first).
PROPAGATORS: dict[str, type[Propagator]] = {}


def register_propagator(cls: type[Propagator]) -> type[Propagator]:
    """Add a :class:`Propagator` subclass to :data:`PROPAGATORS` under ``cls.name``."""
    if not (isinstance(cls, type) and issubclass(cls, Propagator)):
        raise TypeError(f"cls must be a subclass of hyperrotor.quantum.Propagator (the class itself), got "
                        f"{_validate.fmt(cls)} of type {type(cls).__name__}")
    if not isinstance(cls.name, str) or not cls.name:
        raise ValueError(f"a propagator needs a name: {cls.__name__}.name must be a non-empty string, got "
                         f"{_validate.fmt(cls.name)}")
    PROPAGATORS[cls.name] = cls
    return cls


def evolve_options(method: str) -> dict[str, tuple[Any, str]]:
    """The option table of ``evolve(method=...)``: key -> ``(default, meaning)``."""
    return _propagator_class(method).allowed_options()


def _propagator_class(method: Any) -> type[Propagator]:
    if not isinstance(method, str) or method not in PROPAGATORS:
        raise ValueError(f"unknown method {_validate.fmt(method)}; allowed: {', '.join(map(repr, PROPAGATORS))}")
    return PROPAGATORS[method]


# ----------------------------------------------------------------------------
# block propagators (generators yielding the block state at each time)
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


def _krylov_propagator(mat, v0, times, hbar, stats, *, atol: float, m_max: int) -> Iterator[np.ndarray]:
    """Lanczos propagation of ``exp(-i H t / hbar) v0`` on a time grid.

    Each restart builds an orthonormal Krylov basis ``V`` of dimension ``m`` at the
    current state ``v`` (norm ``beta0``) with the tridiagonal ``T``; then
    ``exp(-i H tau/hbar) v ~ beta0 V exp(-i T tau/hbar) e1`` with the error estimate
    ``beta0 * beta_m * |e_m^T exp(-i T tau/hbar) e1|``. Every remaining output
    time whose estimate is <= ``tol`` is served from this basis; the next restart
    begins at the last of them (or, if none is reachable, after a sub-step ``tau``
    meeting the tolerance, found by bisection).
    """
    tol = atol
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
                    f"Krylov propagation cannot meet atol = {tol:.3g}; increase the option 'krylov_dim' or 'atol'"
                )
            tau = lo
            v = beta0 * (coeffs(np.array([tau]))[:, 0] @ V[:m])
            t_cur = t_cur + tau




@register_propagator
class Auto(Propagator):
    """Symmetry-adapted default: ``"eigen"`` for small blocks, ``"krylov"`` on the union of the large ones."""

    name = "auto"
    options = {
        "atol": (None, "Krylov error bound per restart (default options['quantum_krylov_atol'] = 1e-12)"),
        "krylov_dim": (None, "largest Krylov space (default options['quantum_krylov_dim'] = 30)"),
        "eigen_max_block": (None, "largest block propagated by 'eigen' (default options['quantum_eigen_max_block'] = 400)"),
    }

    def plan(self, blocks):
        limit = int(self.opts["eigen_max_block"] if self.opts["eigen_max_block"] is not None
                    else _options["quantum_eigen_max_block"])
        small = [b for b in blocks if len(b) <= limit]
        large = [b for b in blocks if len(b) > limit]
        jobs = Eigen(**self.opts).plan(small)
        jobs += Krylov(**self.opts).plan(large)
        return jobs


@register_propagator
class Eigen(Propagator):
    """Exact diagonalization (dense ``eigh``) of each block, up to ``options['quantum_max_dense_dim']``."""

    name = "eigen"
    options = {}

    def plan(self, blocks):
        limit = int(_options["quantum_max_dense_dim"])
        big = max((len(b) for b in blocks), default=0)
        if big > limit:
            raise ValueError(
                f"method 'eigen' would diagonalize a dense block of dimension {big} > "
                f"options['quantum_max_dense_dim'] = {limit}; use method 'krylov' or raise the limit "
                f"(hyperrotor.options(quantum_max_dense_dim=...))"
            )
        return [(b, self) for b in blocks]

    def propagate(self, mat, v0, t, hbar, stats):
        return _eigen_propagator(mat, v0, t, hbar, stats)


@register_propagator
class Krylov(Propagator):
    """Lanczos propagation with a-posteriori error control, on the union of the populated blocks."""

    name = "krylov"
    union_blocks = True
    options = {
        "atol": (None, "error bound per restart in the 2-norm (default options['quantum_krylov_atol'] = 1e-12)"),
        "krylov_dim": (None, "largest Krylov space (default options['quantum_krylov_dim'] = 30)"),
    }

    def propagate(self, mat, v0, t, hbar, stats):
        atol = self.opts.get("atol")
        dim = self.opts.get("krylov_dim")
        atol = _options["quantum_krylov_atol"] if atol is None else _validate.positive("atol", atol)
        dim = _options["quantum_krylov_dim"] if dim is None else _validate.integer("krylov_dim", dim, minimum=1)
        return _krylov_propagator(mat, v0, t, hbar, stats, atol=float(atol), m_max=int(dim))


@register_propagator
class ExpmMultiply(Propagator):
    """:func:`scipy.sparse.linalg.expm_multiply` (Al-Mohy & Higham 2011) on the union of the populated blocks."""

    name = "expm_multiply"
    union_blocks = True
    options = {}

    def propagate(self, mat, v0, t, hbar, stats):
        return _expm_propagator(mat, v0, t, hbar, stats)


class _QutipSolver(Propagator):
    """QuTiP's solver of the same name on ``H / hbar``; its options are QuTiP's (``atol``/``rtol`` are the ODE tolerances)."""

    native = False

    @classmethod
    def allowed_options(cls):
        qutip = _lazy.qutip
        solver = qutip.SESolver if cls.name == "sesolve" else qutip.MESolver
        keys = dict(RESULT_OPTIONS)
        for k, v in solver.solver_options.items():
            keys.setdefault(k, (v, "QuTiP solver option"))
        for integ in solver.avail_integrators().values():
            for k, v in getattr(integ, "integrator_options", {}).items():
                keys.setdefault(k, (v, "QuTiP integrator option"))
        return keys

    @classmethod
    def resolve_options(cls, given):
        super().resolve_options(given)  # refuses unknown keys with the allowed list
        return dict(given or {})

    def run(self, mat, dims, vec, t, e_ops, c_ops, hbar):
        qutip = _lazy.qutip
        Hq = qutip.Qobj(mat / hbar, dims=dims)
        psi = qutip.Qobj(vec, dims=[dims[0], [1]])
        if self.name == "sesolve":
            return qutip.sesolve(Hq, psi, t, e_ops=e_ops, options=dict(self.opts))
        return qutip.mesolve(Hq, psi, t, c_ops=list(c_ops or []), e_ops=e_ops, options=dict(self.opts))


@register_propagator
class Sesolve(_QutipSolver):
    """``qutip.sesolve`` on ``H / hbar``; options are QuTiP's (``atol``/``rtol``: the ODE tolerances)."""

    name = "sesolve"


@register_propagator
class Mesolve(_QutipSolver):
    """``qutip.mesolve`` on ``H / hbar`` with ``c_ops``; options are QuTiP's (``atol``/``rtol``: the ODE tolerances)."""

    name = "mesolve"


#: Names accepted by ``evolve(method=...)`` (the keys of :data:`PROPAGATORS`).
EVOLVE_METHODS = tuple(PROPAGATORS)


# ----------------------------------------------------------------------------
# evolve
# ----------------------------------------------------------------------------
def _state_vector(psi0: Any, dim: int) -> np.ndarray:
    vec = _validate.ket("psi0", psi0, dim, of="H")
    nrm = float(np.linalg.norm(vec))
    if nrm == 0:
        raise ValueError("psi0 is the zero vector; it cannot be normalized")
    if abs(nrm - 1) > _options["quantum_psi0_norm_rtol"]:
        warnings.warn(
            f"psi0 has norm {nrm:.12g}; evolving the normalized state psi0/|psi0| "
            f"(tolerance options['quantum_psi0_norm_rtol'] = {_options['quantum_psi0_norm_rtol']:.3g})",
            UserWarning, stacklevel=3,
        )
    return vec / nrm


def _e_ops_list(e_ops: Any, dims) -> Any:
    """e_ops as QuTiP accepts them, with scipy.sparse / ndarray operators wrapped as Qobj."""
    qutip = _lazy.qutip

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


def evolve(
    H: Any,
    psi0: Any,
    t: Sequence[float] | None = None,
    e_ops: Any = None,
    method: str = "auto",
    c_ops: Any = None,
    options: dict | None = None,
    *,
    hbar: float = 1.0,
    rep: Any = None,
    **old: Any,
):
    r"""Evolve ``psi0`` under :math:`i\hbar\,\partial_t\psi = \hat H\psi` on the time grid ``t``.

    Parameters
    ----------
    H : qutip.Qobj, scipy.sparse matrix or ndarray
        Hermitian, time-independent Hamiltonian (e.g. :func:`rotor_hamiltonian`).
    psi0 : qutip.Qobj (ket) or array_like
        Initial state at ``t[0]``, of the dimension of ``H``. It is normalized;
        a norm off 1 by more than ``options["quantum_psi0_norm_rtol"]`` (1e-10)
        also gives a ``UserWarning``; the zero vector is refused.
    t : sequence of float
        Strictly increasing output times (the name :func:`hyperrotor.simulate` uses);
        ``t[0]`` is the time of ``psi0``.
    e_ops : Qobj, sparse matrix, callable, or list/dict of these, optional
        Operators whose expectation values are recorded (as in QuTiP).
    method : str, default "auto"
        A key of :data:`PROPAGATORS` (module docstring): ``"auto"``,
        ``"eigen"``, ``"krylov"``, ``"expm_multiply"``, ``"sesolve"``,
        ``"mesolve"``. ``"auto"`` is ``"mesolve"`` when ``c_ops`` are given.
    c_ops : list of Qobj, optional
        Collapse operators (only with ``"mesolve"``/``"auto"``).
    options : dict, optional
        The keys of :func:`evolve_options` ``(method)``: :data:`RESULT_OPTIONS`
        for every method, ``blocks``/``block_atol`` for the native ones, and the
        method's own table (e.g. Krylov ``atol``, ``krylov_dim``; QuTiP's keys
        for ``"sesolve"``/``"mesolve"``, where ``atol``/``rtol`` are the ODE
        tolerances). Unknown keys raise ``ValueError`` naming the allowed ones.
    hbar : float, keyword-only, default 1
        Planck's constant of the Schrödinger equation; use the same value as in
        :func:`rotor_hamiltonian`.
    rep : Representation, keyword-only, optional
        The representation ``H`` was built from (default: the one
        :func:`rotor_hamiltonian` recorded on ``H``), for the symmetry sectors
        of :mod:`hyperrotor.quantum.sectors`: when it is known, ``blocks`` is on and
        a populated sparsity block is larger than ``options["quantum_eigen_max_block"]``
        (a generic inertia), the native methods propagate the state sector by sector
        (``stats["sectors"]``; 16 real blocks of ~dim/16 for so(5) tensor irreps, so
        ``"auto"`` can use exact diagonalization far beyond the sparsity blocks).

    Returns
    -------
    qutip.solver.Result
        ``times``, ``states`` (stored when no ``e_ops`` are given, or with
        ``store_states=True``), ``expect``, ``e_data``, ``final_state`` and
        ``stats`` (native methods record ``"method"``, ``"blocks"``,
        ``"populated_blocks"``, ``"populated_dim"``, ``"block_methods"``,
        ``"n_matvec"``, ``"n_krylov"``, ``"run time"``).

    Raises
    ------
    TypeError
        Old keywords (``times=``: use ``t=``).
    ValueError
        Non-Hermitian ``H``; ``psi0`` of the wrong dimension or zero; ``t`` not
        strictly increasing; unknown method or option; ``c_ops`` with a
        closed-system method; a block too large for ``"eigen"``.
    """
    _validate.old_keywords("evolve", old, {"times": "t= (the time grid, as in hyperrotor.simulate)"})
    if t is None:
        raise TypeError("evolve() needs the time grid t (evolve(H, psi0, t, ...))")
    cls = _propagator_class(method)
    hbar = _validate.hbar(hbar)
    mat, dims = hermitian_matrix(H)
    vec = _state_vector(psi0, mat.shape[0])
    t = _validate.time_grid(t, allow_decreasing=False)
    if c_ops:
        if method not in ("auto", "mesolve"):
            raise ValueError(f"collapse operators need method 'mesolve' (or 'auto'), got method {method!r}")
        cls = PROPAGATORS["mesolve"]
    opts = cls.resolve_options(options)
    rep = rep if rep is not None else getattr(H, "_hyperrotor_rep", None)
    if rep is not None:
        rep = _validate.representation("rep", rep, dim=mat.shape[0])
    if not cls.native:
        return cls(**opts).run(mat, dims, vec, t, _e_ops_list(e_ops, dims), c_ops, hbar)
    return _evolve_native(cls, opts, mat, dims, vec, t, _e_ops_list(e_ops, dims), hbar, rep)


def _sector_jobs(mat: sps.csr_matrix, rep: Any, vec: np.ndarray, cls: type[Propagator], opts: dict) -> list | None:
    r"""Jobs ``(basis, block, c0, propagator)`` in the symmetry sectors of :mod:`.sectors` (issue #16), or ``None``.

    The sectors of the rotations by :math:`\pi` (all copies, so they span the space) that
    ``vec`` populates: :math:`\psi(t) = \sum_s B_s\,\psi_s(t)` with :math:`\psi_s` the
    evolution of :math:`c_s = B_s^\dagger\psi_0` under the (real, for tensor irreps) block
    :math:`H_s = B_s^\dagger H B_s`; each block gets the propagator ``cls`` plans for its
    size (``"auto"``: ``"eigen"`` up to ``eigen_max_block``, Krylov above). ``None`` when
    ``rep`` has no usable sectors (then the sparsity blocks are used).
    """
    from . import sectors

    parts = sectors._populated_blocks(mat, rep, vec)  # mat, rep and vec are checked by evolve
    if not parts:
        return None
    planner = cls(**opts)
    jobs = []
    for B, block, c0 in parts:
        for _, prop in planner.plan([np.arange(block.shape[0])]):
            jobs.append((B, block, c0, prop))
    return jobs


def _evolve_native(cls, opt, mat, dims, vec, t, e_ops, hbar, rep=None):
    qutip = _lazy.qutip
    t_start = _time.perf_counter()
    dim = mat.shape[0]
    stats: dict[str, Any] = {"method": cls.name}
    use_blocks = opt["blocks"]
    if use_blocks not in ("auto", True, False):
        raise ValueError(f"option 'blocks' must be 'auto', True or False, got {_validate.fmt(use_blocks)}")
    blocks = blocks_of(mat, atol=opt["block_atol"]) if use_blocks else [np.arange(dim)]
    stats["blocks"] = len(blocks)
    populated = [b for b in blocks if np.any(vec[b] != 0)]
    stats["populated_blocks"] = len(populated)
    stats["populated_dim"] = int(sum(len(b) for b in populated))
    singles = np.array([b[0] for b in populated if len(b) == 1], dtype=int)
    multi = [b for b in populated if len(b) > 1]
    method_opts = {k: opt[k] for k in cls.options}
    # generic inertia: the sparsity blocks are large; the symmetry sectors split them ~2^(N-1) ways
    sector_jobs = None
    big = max((len(b) for b in multi), default=0)
    if rep is not None and use_blocks and big > int(_options["quantum_eigen_max_block"]):
        sector_jobs = _sector_jobs(mat, rep, vec, cls, method_opts)
    if sector_jobs is not None:
        singles, multi = np.zeros(0, dtype=int), []
        stats["sectors"] = len(sector_jobs)
    jobs = cls(**method_opts).plan(multi)
    props = []
    basis_props = []
    if singles.size:
        diag = mat.diagonal()[singles].real
        props.append((singles, _diagonal_propagator(diag, vec[singles], t, hbar)))
    used = set()
    for b, prop in jobs:
        sub = mat[b][:, b].tocsr()
        used.add(prop.name)
        props.append((b, prop.propagate(sub, vec[b], t, hbar, stats)))
    for B, block, c0, prop in sector_jobs or []:
        used.add(prop.name)
        basis_props.append((B, prop.propagate(block, c0, t, hbar, stats)))
    stats["block_methods"] = sorted(used) if used else ["diagonal"]
    ropts = {
        "store_states": opt["store_states"],
        "store_final_state": opt["store_final_state"],
        "normalize_output": False,
    }
    result = qutip.solver.Result(e_ops, ropts, solver=f"hyperrotor.evolve[{cls.name}]", stats=stats)
    pkw = opt["progress_kwargs"] or {}
    try:
        bar = qutip.ui.progressbar.progress_bars[opt["progress_bar"]](len(t), **pkw)
    except KeyError:
        raise ValueError(
            f"unknown progress_bar {_validate.fmt(opt['progress_bar'])}; allowed: '', 'text', 'enhanced', 'tqdm', 'html'"
        ) from None
    ket_dims = [dims[0], [1]]
    full = np.zeros(dim, dtype=complex)
    # one BLAS-thread limit for the whole run: threadpoolctl scans the loaded libraries on every
    # entry (~7 ms here), which per output time was most of the run time of small problems
    with _single_thread_blas():
        for tk in t:
            full[:] = 0
            for idx, gen in props:
                full[idx] = next(gen)
            for B, gen in basis_props:  # sector supports overlap: accumulate
                full += B @ next(gen)
            result.add(float(tk), qutip.Qobj(full.reshape(-1, 1).copy(), dims=ket_dims, copy=False))
            bar.update()
    bar.finished()
    stats["run time"] = _time.perf_counter() - t_start
    return result
