"""Documented tolerances and budgets: one table for the whole package (QuTiP ``CoreOptions`` style).

Library code reads ``options["key"]`` instead of hard-coding a tolerance or a
limit, so a user can see every default in one place (``print(hr.options)``)
and change it for a block of code::

    import hyperrotor as hr
    with hr.options(max_steps=10**10):
        hr.simulate(body, omega0, t, rtol=1e-12)

or for the session (``hr.options["max_steps"] = 10**10``). Unknown keys raise
:class:`UnknownOptionError` (a ``KeyError`` and a ``ValueError``) naming the
allowed ones. Each entry carries its meaning and why its default is what it
is; modules add their entries with :func:`register` at import time, so the
table stays the one source.

**Values are checked on assignment.** An entry registered with an integer
default takes integers >= 1 (and integral floats such as ``1e9``; ``bool`` is refused); one with a float default
takes finite reals >= 0; an entry may give its own ``check``. ``nan``, a
negative budget or a string is refused with a ``TypeError``/``ValueError``
naming the key, so no budget can be switched off by accident.

**Blocks are context-local.** ``with options(...)`` changes the values seen by
the current thread (more precisely: the current :mod:`contextvars` context,
as NumPy's error state), never those of other threads, and interleaved blocks
in several threads each restore exactly what they changed. The worker
threads and dask tasks of :mod:`hyperrotor._parallel` run with the values of
the block that started them. ``options[key] = value`` changes the session
value, seen by every thread that has no block of its own for ``key``.
"""
from __future__ import annotations

import importlib
import math
import sys
import threading
from contextlib import contextmanager
from contextvars import ContextVar
from numbers import Integral, Real
from types import MappingProxyType
from typing import Any, Callable, Iterator, Mapping

__all__ = ["options", "Options", "register", "UnknownOptionError"]


class UnknownOptionError(KeyError, ValueError):
    """An option name that is not in the table it was looked up in (the one exception for unknown keys).

    It is both a ``KeyError`` (mapping access: ``hr.options["nope"]``) and a
    ``ValueError`` (a bad argument value: ``evolve(options={"nope": 1})``).
    """

    def __str__(self) -> str:  # KeyError would print the repr of its argument
        return str(self.args[0]) if self.args else ""


def _check_int(key: str, value: Any) -> int:
    if isinstance(value, Real) and not isinstance(value, (bool, Integral)) and math.isfinite(value) and float(value).is_integer():
        value = int(value)  # 1e9 means 10**9
    if isinstance(value, bool) or not isinstance(value, Integral):
        raise TypeError(f"option {key!r} must be an integer, got {value!r} of type {type(value).__name__}")
    if value < 1:
        raise ValueError(f"option {key!r} must be >= 1, got {int(value)}")
    return int(value)


def _check_float(key: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"option {key!r} must be a real number, got {value!r} of type {type(value).__name__}")
    v = float(value)
    if not math.isfinite(v) or v < 0:
        raise ValueError(f"option {key!r} must be a finite number >= 0, got {v!r}")
    return v


def _default_check(default: Any) -> Callable[[str, Any], Any]:
    if isinstance(default, bool):
        def check_bool(key: str, value: Any) -> bool:
            if not isinstance(value, bool):
                raise TypeError(f"option {key!r} must be True or False, got {value!r}")
            return value
        return check_bool
    if isinstance(default, Integral):
        return _check_int
    if isinstance(default, Real):
        return _check_float
    raise TypeError(f"an option with a default of type {type(default).__name__} needs its own check=")


class Options:
    """The package's option table: mapping access, documented entries, a context-local context manager.

    ``options[key]`` reads, ``options[key] = value`` sets for the session,
    ``with options(key=value, ...):`` sets for a block of the current context
    (thread) and restores afterwards. ``options.describe(key)`` gives the
    documentation of an entry; ``options.snapshot()`` the values in force here.
    """

    def __init__(self) -> None:
        self._session: dict[str, Any] = {}
        self._defaults: dict[str, Any] = {}
        self._docs: dict[str, str] = {}
        self._checks: dict[str, Callable[[str, Any], Any]] = {}
        self._owners: dict[str, str] = {}  # key -> module that registered it (imported again on workers)
        self._lock = threading.Lock()
        self._local: ContextVar[Mapping[str, Any]] = ContextVar("hyperrotor_options", default=MappingProxyType({}))

    def register(self, key: str, default: Any, doc: str, *, check: Callable[[str, Any], Any] | None = None) -> None:
        """Add an option ``key`` with its ``default``, a one-paragraph ``doc`` and an optional ``check``.

        ``check(key, value)`` returns the normalised value or raises
        ``TypeError``/``ValueError``; by default it is inferred from the type of
        ``default`` (see the module docstring).
        """
        if key in self._defaults and self._defaults[key] != default:
            raise ValueError(f"option {key!r} is registered twice with different defaults")
        check = check or _default_check(default)
        default = check(key, default)
        owner = sys._getframe(1).f_globals.get("__name__", __name__)
        with self._lock:
            self._owners.setdefault(key, owner)
            self._defaults[key] = default
            self._session.setdefault(key, default)
            self._docs[key] = doc
            self._checks[key] = check

    def _check(self, key: str) -> None:
        if key not in self._defaults:
            raise UnknownOptionError(f"unknown option {key!r}; allowed: {', '.join(sorted(self._defaults))}")

    def _value(self, key: str, value: Any) -> Any:
        self._check(key)
        return self._checks[key](key, value)

    def __getitem__(self, key: str) -> Any:
        local = self._local.get()
        if key in local:
            return local[key]
        self._check(key)
        return self._session[key]

    def __setitem__(self, key: str, value: Any) -> None:
        value = self._value(key, value)
        with self._lock:
            self._session[key] = value

    def __contains__(self, key: object) -> bool:
        return key in self._defaults

    def keys(self):
        return self._defaults.keys()

    def reset(self) -> None:
        """Restore every default (session values; blocks in progress keep their own values)."""
        with self._lock:
            self._session = dict(self._defaults)

    def describe(self, key: str) -> str:
        self._check(key)
        return self._docs[key]

    def snapshot(self) -> dict[str, Any]:
        """The values in force in the current context, for every key (what a worker must see)."""
        local = self._local.get()
        return {k: local.get(k, self._session[k]) for k in self._defaults}

    def portable(self) -> dict[str, tuple[Any, str]]:
        """The values in force here that differ from their defaults or that a block of this context sets, each
        with the module that registered it: what a worker needs to see the same options (:meth:`apply_portable`).

        A block's values go even when they equal the defaults: a worker thread of an in-process dask cluster
        reads this process's session values otherwise (a block setting a key back to its default, inside a
        session that changed it, reached the tasks with the session's value)."""
        local = self._local.get()
        here = self.snapshot()
        return {k: (v, self._owners[k]) for k, v in here.items() if k in local or v != self._defaults[k]}

    def apply_portable(self, values: Mapping[str, tuple[Any, str]]):
        """A ``with`` block setting :meth:`portable` values, importing first the modules that
        register keys not known in this process (a fresh dask worker has imported fewer modules)."""
        for key, (_, owner) in values.items():
            if key not in self._defaults:
                importlib.import_module(owner)
        return self(**{k: v for k, (v, _) in values.items()})

    @contextmanager
    def __call__(self, **changes: Any) -> Iterator["Options"]:
        checked = {k: self._value(k, v) for k, v in changes.items()}
        token = self._local.set(MappingProxyType({**self._local.get(), **checked}))
        try:
            yield self
        finally:
            self._local.reset(token)

    def __repr__(self) -> str:
        here = self.snapshot()
        rows = [f"  {k} = {here[k]!r}" + ("" if here[k] == self._defaults[k] else f"  (default {self._defaults[k]!r})")
                for k in sorted(self._defaults)]
        return "hyperrotor options:\n" + "\n".join(rows)


#: The one option table of the package.
options = Options()
register = options.register


# ----------------------------------------------------------------------------
# The entries. Keep them here, grouped by area, each with its reason, so that the
# table is complete without importing the modules that read it.
# ----------------------------------------------------------------------------
# --- classical ---------------------------------------------------------------
register(
    "max_steps", 10**8,
    "Budget of hyperrotor.simulate: most integration steps per run (steps per trajectory times "
    "ensemble members; scipy methods: right-hand-side evaluations). A run whose estimate exceeds it "
    "is refused before it starts (scipy methods: stopped when they reach it). 1e8 steps of a 5D "
    "splitting8 take a few minutes on one core; raise it (simulate(max_steps=...) or "
    "hr.options(max_steps=...)) for longer runs.",
)
register(
    "max_output_bytes", 2**31,
    "Budget of hyperrotor.simulate: largest memory for the returned arrays (omega, L, attitude) and, "
    "with rtol, the step control's check (about 1 kB per member), estimated before the run; 2 GiB by "
    "default, so that a mistyped output grid (e.g. 2e8 times) is refused with a message instead of "
    "ending in MemoryError.",
)
register(
    "chunk_seconds", 0.25,
    "Target run time of one compiled chunk of hyperrotor.simulate and of the ensemble chunks of "
    "lyapunov / _parallel.map_rows: between chunks Python checks for Ctrl-C (KeyboardInterrupt) "
    "and updates the progress bar. Smaller is more responsive, larger has less overhead (each "
    "chunk costs about 10 microseconds).",
)
register(
    "slow_run_warning_seconds", 60.0,
    "hyperrotor.simulate warns (UserWarning) before a run whose estimated wall time exceeds this "
    "many seconds (the estimate comes from the timed probe runs of the step control).",
)

# chaos indicators and ensembles (hyperrotor.classical.chaos, hyperrotor._parallel)
register(
    "lyapunov_step", 0.4,
    "Default step of hyperrotor.lyapunov, in units of 1/w_max (w_max: the bound "
    "max_a min(|L|, sqrt(2 E I_a)) / I_a on the angular velocities of the orbit). With the "
    "default splitting8, 0.4 keeps finite-time exponents of strongly chaotic 5D orbits within "
    "~1e-7 of the converged value over 10 time units and ~1e-4 over 20 (halving it costs 2x).",
)
register(
    "lyapunov_max_work", 3e10,
    "Budget of hyperrotor.lyapunov / lyapunov_sweep: most work per worker thread, in elementary "
    "plane flows times (1 + k * max(1, (N - 2) / 3)) for k tangent vectors (a tangent vector's plane "
    "flow touches N - 2 pairs of components; the factor is 1 in 5D), estimated before the run (about "
    "7 ns per unit on the reference machine, so 3e10 is ~3 minutes). A run over it is refused with "
    "the estimate; raise it with hr.options(lyapunov_max_work=...) or add workers (client=).",
)


# --- quantum -----------------------------------------------------------------
register(
    "max_dimension", 1000,
    "Largest space dimension N accepted by hyperrotor.conventions.check_dimension (planes, "
    "structure constants, every so(N) constructor): so(1000) already has 499,500 planes and a "
    "structure-constant table of 1.2e17 entries; N = 10**6 would hang or exhaust memory instead of "
    "failing with a message. Raise it (hr.options(max_dimension=...)) for larger N.",
)
register(
    "quantum_hermiticity_rtol", 1e-12,
    "Hermiticity check of hyperrotor.quantum (evolve, spectrum: H = H^dagger; from_qobj, "
    "rotor_hamiltonian: X^dagger = -X), relative to max|H|: max|H - H^dagger| must not exceed it. "
    "A Hamiltonian assembled from N(N-1)/2 sparse products has round-off ~1e-15 relative; 1e-12 "
    "leaves a factor ~1000 for large sums while any genuinely non-Hermitian input is O(1) off.",
)
register(
    "quantum_bracket_rtol", 1e-10,
    "Bracket check of Representation.from_qobj / check_brackets: max|[X_a, X_b] - sum_c C_ab^c X_c| "
    "relative to (max_a max|X_a|)^2. A product of two sparse matrices with entries up to m carries "
    "round-off ~ (nonzeros per row) * eps * m^2, far below 1e-10 m^2; a wrong basis, sign or form "
    "misses by O(m^2).",
)
register(
    "quantum_psi0_norm_rtol", 1e-10,
    "hyperrotor.quantum.evolve: an initial state whose norm differs from 1 by more than this is "
    "normalized with a UserWarning (smaller deviations are round-off of a normalized state and are "
    "normalized silently). 1e-10 is far above the round-off of building a state (~dim * eps) "
    "and far below any deliberate unnormalized input.",
)
register(
    "quantum_krylov_atol", 1e-12,
    "Default 'atol' of the Krylov (Lanczos) propagator of evolve: a-posteriori error bound, in the "
    "2-norm of the state, allowed per restart (Saad 1992). 1e-12 keeps the total error of typical "
    "runs (tens of restarts) near 1e-11, below QuTiP's tightest practical tolerances, at a cost "
    "only ~20% above 1e-8 (benchmarks/quantum_evolution.py).",
)
register(
    "quantum_rotation_atol", 1e-14,
    "apply_rotation / coherent_state: Krylov error bound per plane-rotation factor exp(theta X) psi. "
    "A coherent state is a product of at most N(N-1)/2 such factors, so 1e-14 keeps it within ~1e-13 "
    "of exact, below the tolerances of every evolution that starts from it.",
)
register(
    "quantum_krylov_dim", 60,
    "Default 'krylov_dim' of evolve's Krylov (Lanczos) propagator and of apply_rotation: largest Krylov "
    "space per restart. 60 measured fastest on a dim-3376 sector block of the so(5) irrep (20, 10), one "
    "coherent state, 201 output times to t = 10 at atol 1e-12: 1.25 s (720 matvecs) vs 2.96 s at 30, "
    "1.83 s at 45, 1.32 s at 90, states equal to 2e-14 (benchmarks/quantum_evolution.py). Larger spaces "
    "cost memory (dim x m) and re-orthogonalization time (m^2 dim) for little gain.",
)
register(
    "quantum_max_dense_dim", 6000,
    "Largest invariant block of a Hamiltonian that hyperrotor.quantum diagonalizes densely (spectrum, "
    "evolve method 'eigen'); larger blocks are refused with a message. A dense eigh of dimension 6000 "
    "needs ~0.6 GB and ~1 min on one core; the one home of this limit.",
)
register(
    "quantum_eigen_max_block", 400,
    "evolve method 'auto': blocks up to this dimension are propagated by dense diagonalization, larger "
    "ones by Krylov (measured crossover on this machine, benchmarks/quantum_evolution.py: eigh of 400 "
    "costs about what Krylov needs for 51 output times).",
)
register(
    "quantum_block_rtol", 1e-14,
    "symmetry_blocks / evolve blocks: entries with |H_kl| <= this * max|H| count as zero when the "
    "invariant blocks (connected components of the sparsity graph) are found. They remove round-off "
    "couplings (~1e-16 relative) such as those of C_2/(2I) in a non-diagonal basis, while any "
    "physical coupling is many orders larger.",
)
register(
    "quantum_level_rtol", 1e-9,
    "hyperrotor.quantum.spectrum: eigenvalues closer than this * max(1, max|E|) are one degenerate "
    "level. Far above the round-off of eigh (~1e-15 * dim * max|E|) and below any physical "
    "splitting of interest; pass atol= to spectrum for another choice.",
)
register(
    "quantum_max_harmonic_dim", 5000,
    "Largest space of harmonic polynomials (harmonic_polynomial_basis, orthogonal/orthonormal bases, "
    "harmonic_rep) built exactly in rational arithmetic; its cost grows like dim^2 monomial products, "
    "a few minutes near 5000. Larger degrees are refused before any work (use irrep(N, (l,)), the same "
    "representation in the Gelfand-Tsetlin basis, for big l).",
)
register(
    "quantum_harmonic_drop", 1e-13,
    "harmonic_rep: generator entries below this * max(1, max|X|) are round-off of exact zeros and "
    "are dropped (symmetrically, the matrices stay exactly antisymmetric). Exact nonzero entries are "
    "sqrt(n_a/n_b) q with small rationals q, of order 1e-2 and more for every degree in reach.",
)
register(
    "quantum_real_form_drop", 1e-13,
    "real_form: entries of the real generators below this * max(1, max|Y|) are round-off of exact "
    "zeros and are dropped (symmetrically; antisymmetry is exact). The change of basis is unitary, so "
    "the round-off is ~dim * eps * max|Y|, below 1e-13 up to dimensions ~500 where real_form is meant.",
)
register(
    "quantum_real_form_rtol", 1e-10,
    "real_form: internal consistency check, the imaginary part left in the real generators relative "
    "to max(1, max|Y|) must not exceed it (it is round-off, ~dim * eps, when the construction works).",
)
register(
    "sectors_dense_max_dim", 2000,
    "hyperrotor.quantum.symmetry_sectors: largest dimension of a representation that is not a "
    "Gelfand-Tsetlin irrep (vector, spinor, harmonic, tensor products, ...) for which the sectors are "
    "built densely (matrix exponentials and projectors, O(dim^3) time, O(dim^2) memory). "
    "Gelfand-Tsetlin irreps of any dimension use the sparse monomial construction.",
)
register(
    "sectors_max_block_dim", 15000,
    "hyperrotor.quantum.sector_spectra: largest sector diagonalized densely (8 dim^2 bytes per real "
    "block, 16 dim^2 per complex one: 3.6 GB at 15000; O(dim^3) time: a real 3,300-dimensional block "
    "took 2.4 s at load 3.5 and ~20 s at load 10 on the 2-core test machine). Larger sectors are "
    "refused with their size before any work.",
)
register(
    "statistics_max_size", 10**7,
    "hyperrotor.quantum.statistics: largest array made from an integer argument, the histogram bins of "
    "spacing_distribution and the levels of sample_spectrum('poisson') (8 bytes each, 80 MB at the "
    "default). Spectra that can be diagonalized have far fewer levels, and a Poisson mean ratio is exact "
    "to ~1e-4 at 10**7 levels; bins=10**9 would allocate 8 GB before any message.",
)

# --- command line ------------------------------------------------------------
register(
    "cli_max_seconds", 600.0,
    "Budget of the command line (hyperrotor demo/scene/bench): a run whose wall time, estimated "
    "from its arguments before any work, exceeds this many seconds is refused with the estimate "
    "(exit status 2). The estimates are rough (factor ~3, measured on a 2-core machine); "
    "--max-seconds overrides the budget for one run.",
)
register(
    "cli_max_memory", 2**31,
    "Budget of the command line (hyperrotor scene): largest memory in bytes that a run may need, "
    "estimated before any work from the body points, frames and drawn edges (e.g. scene --N 40 "
    "would need 2^40 cube vertices, about 8 TiB); 2 GiB by default, since the machine is shared. "
    "--max-memory overrides it for one run.",
)
