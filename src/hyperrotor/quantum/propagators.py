r"""The methods of :func:`~hyperrotor.quantum.evolve`: a registry of propagator classes.

Each method is a small :class:`Propagator` subclass with its own option table
(:attr:`Propagator.options`: key -> (default, meaning)), registered in
:data:`PROPAGATORS` (QuTiP's ``solver_base`` integrator registry is the model).
``evolve(..., options={...})`` accepts the keys of :data:`RESULT_OPTIONS` plus
those of the chosen method and refuses any other key
(:class:`hyperrotor.UnknownOptionError`, naming the allowed ones). Defaults
written ``None`` are read from :data:`hyperrotor.options` (e.g.
``quantum_krylov_atol``) at call time; the largest dense block,
``quantum_max_dense_dim``, lives only there.

``"auto"``
    ``"mesolve"`` with collapse operators; otherwise ``"eigen"`` for blocks up to
    ``eigen_max_block`` and ``"krylov"`` above, where a
    :class:`~hyperrotor.quantum.SectorPropagator` switches a block to its cached
    eigendecomposition once that is cheaper than more Krylov work (many states,
    long times).
``"eigen"``
    Exact diagonalization (dense ``eigh``) of each block, cached by the
    :class:`~hyperrotor.quantum.SectorPropagator`.
``"krylov"``
    Lanczos with full re-orthogonalization and the a-posteriori error
    estimate of Saad (1992) / Hochbruck & Lubich (1997): one Krylov space
    serves every output time it reaches within ``atol`` (:mod:`._krylov`).
``"expm_multiply"``
    :func:`scipy.sparse.linalg.expm_multiply` over the grid (Al-Mohy & Higham 2011).
``"sesolve"``, ``"mesolve"``
    QuTiP's solvers on ``H/hbar``; their options are QuTiP's.
"""
from __future__ import annotations

import math
from typing import Any, ClassVar, Iterator

import numpy as np
import scipy.sparse as sps
from scipy.sparse.linalg import expm_multiply

from .. import _lazy, _validate
from .._options import options as _options
from .._parallel import interruptible
from .._pricing import refuse
from ._krylov import krylov_propagator

__all__ = ["EVOLVE_METHODS", "PROPAGATORS", "RESULT_OPTIONS", "Propagator", "evolve_options", "register_propagator"]

#: Options of every method: what the returned ``qutip.solver.Result`` keeps (the progress bar is ``evolve(progress=)``).
RESULT_OPTIONS: dict[str, tuple[Any, str]] = {
    "store_states": (None, "keep every state (default: when no e_ops are given)"),
    "store_final_state": (True, "keep the final state"),
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
        """Defaults merged with ``given``; unknown keys raise ``UnknownOptionError`` naming the allowed ones."""
        if given is None:
            given = {}
        if not isinstance(given, dict):
            raise TypeError(f"options must be a dict or None, got {type(given).__name__}")
        allowed = cls.allowed_options()
        unknown = sorted(set(given) - set(allowed), key=str)
        if unknown:
            where = f"evolve options of method {cls.name!r}"
            if "max_dense_dim" in unknown:
                where += " (the largest dense block is hyperrotor.options['quantum_max_dense_dim'], one home for spectrum and evolve)"
            _validate.unknown_option(where, unknown[0], list(allowed))
        for key, (default, _) in RESULT_OPTIONS.items():  # switches: "no" or 0 would act by their truth value
            if key in given:
                _validate.flag(key, given[key], allow_none=default is None)
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
    return propagator_class(method).allowed_options()


def propagator_class(method: Any) -> type[Propagator]:
    """The registered class of ``method`` (case-insensitive; ``ValueError`` naming the allowed names)."""
    return PROPAGATORS[_validate.choice("method", method, tuple(PROPAGATORS))]


# ----------------------------------------------------------------------------
# block propagators (generators yielding the block state at each time)
# ----------------------------------------------------------------------------
def _eigen_propagator(mat, v0, times, hbar, stats) -> Iterator[np.ndarray]:
    dense = mat.toarray()
    E, V = interruptible(np.linalg.eigh, dense)
    stats["n_eigh"] = stats.get("n_eigh", 0) + 1
    c = V.conj().T @ v0
    for t in times:
        yield V @ (np.exp(-1j * E * ((t - times[0]) / hbar)) * c)


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


@register_propagator
class Auto(Propagator):
    """Symmetry-adapted default: ``"eigen"`` for small blocks, ``"krylov"`` on the union of the large ones."""

    name = "auto"
    options = {
        "atol": (None, "Krylov error bound per restart (default options['quantum_krylov_atol'] = 1e-12)"),
        "krylov_dim": (None, "largest Krylov space (default options['quantum_krylov_dim'] = 60)"),
        "eigen_max_block": (None, "largest block propagated by 'eigen' (default options['quantum_eigen_max_block'] = 400)"),
    }

    def plan(self, blocks):
        Krylov(**self.opts).settings()  # atol and krylov_dim are checked even when no block needs Krylov
        cap = self.opts.get("eigen_max_block")
        limit = int(_options["quantum_eigen_max_block"] if cap is None
                    else _validate.integer("eigen_max_block", cap, minimum=1))
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
            raise refuse("evolve", f"method 'eigen' (a dense block of dimension {big} diagonalized)", big,
                         "quantum_max_dense_dim", "dimension", "use method 'krylov'")
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
        "krylov_dim": (None, "largest Krylov space (default options['quantum_krylov_dim'] = 60)"),
    }

    def settings(self) -> tuple[float, int]:
        """``(atol, krylov_dim)``: the options, or their defaults in :data:`hyperrotor.options`."""
        atol = self.opts.get("atol")
        dim = self.opts.get("krylov_dim")
        atol = _options["quantum_krylov_atol"] if atol is None else _validate.positive("atol", atol)
        dim = _options["quantum_krylov_dim"] if dim is None else _validate.integer("krylov_dim", dim, minimum=1)
        return float(atol), int(dim)

    def propagate(self, mat, v0, t, hbar, stats, stop=None, reorthogonalize=True):
        atol, dim = self.settings()
        return krylov_propagator(mat, v0, t, hbar, stats, atol=atol, m_max=dim, stop=stop,
                                 reorthogonalize=reorthogonalize)


@register_propagator
class ExpmMultiply(Propagator):
    """:func:`scipy.sparse.linalg.expm_multiply` (Al-Mohy & Higham 2011) on the union of the populated blocks."""

    name = "expm_multiply"
    union_blocks = True
    options = {}

    def propagate(self, mat, v0, t, hbar, stats):
        return _expm_propagator(mat, v0, t, hbar, stats)


#: The values of QuTiP's ``options["progress_bar"]`` that show no bar (every other name of
#: ``qutip.ui.progressbar.progress_bars`` shows one).
_QUTIP_NO_BAR = ("", "base", False, None)


def qutip_bars() -> tuple:
    """QuTiP's names of its progress bars that show a bar (lower case: ``"text"``, ``"enhanced"``, ``"tqdm"``,
    ``"html"`` in QuTiP 5.3), from ``qutip.ui.progressbar.progress_bars``: a bar of a newer QuTiP is accepted too."""
    from qutip.ui.progressbar import progress_bars

    names = {k.lower() for k in progress_bars if isinstance(k, str) and k.lower() not in _QUTIP_NO_BAR}
    return tuple(sorted(names))


def _qutip_progress_bar(name: str, value: Any) -> Any:
    """``options["progress_bar"]`` of a QuTiP solver: ``True``/``False``/``None`` or one of QuTiP's bar names."""
    if value is None or isinstance(value, (bool, np.bool_)):
        return None if value is None else bool(value)
    bars = qutip_bars()
    allowed = f"True, False, None or one of QuTiP's bars {', '.join(map(repr, (*bars, '', 'base')))}"
    if not isinstance(value, str):
        raise TypeError(f"{name} must be {allowed}, got {_validate.fmt(value)} of type {type(value).__name__}")
    if value.lower() not in (*bars, "", "base"):
        raise ValueError(f"{name} must be {allowed}, got {_validate.fmt(value)}")
    return value.lower()


#: the largest step count QuTiP's integrators take (a C int)
_C_INT_MAX = 2**31 - 1

#: How each QuTiP option is checked (``name`` is ``"options['key']"``; ``None``, QuTiP's "its default", passes
#: before these); ``order``, ``max_order_ns`` and ``max_order_s`` are bounded by the integrator's default, which is
#: its highest order. A key missing here (a newer QuTiP) is checked by the type of its default
#: (:meth:`_QutipSolver.check_option`). Tolerances and step sizes as the integrators take them: ``rtol = 0`` (pure
#: absolute control), ``atol = 0`` (pure relative), ``max_step = inf`` (no limit) are theirs to take.
_QUTIP_CHECKS: dict[str, Any] = {
    "atol": lambda n, v: _validate.positive(n, v, allow_zero=True),
    "rtol": lambda n, v: _validate.positive(n, v, allow_zero=True),
    "sub_system_tol": lambda n, v: _validate.positive(n, v),
    "nsteps": lambda n, v: _validate.whole_number(n, v, minimum=1, maximum=_C_INT_MAX),
    "krylov_dim": lambda n, v: _validate.whole_number(n, v, minimum=1, maximum=_C_INT_MAX),  # (QuTiP refuses its 0)
    "first_step": lambda n, v: _validate.positive(n, v, allow_zero=True),  # (0: chosen by the integrator)
    "max_step": lambda n, v: (math.inf if isinstance(v, (float, np.floating)) and v == math.inf
                              else _validate.positive(n, v, allow_zero=True)),
    "min_step": lambda n, v: _validate.positive(n, v, allow_zero=True),
    "ifactor": lambda n, v: _validate.positive(n, v),
    "dfactor": lambda n, v: _validate.positive(n, v),
    "beta": lambda n, v: _validate.positive(n, v, allow_zero=True),
    "store_states": lambda n, v: _validate.flag(n, v, allow_none=True),
    "store_final_state": lambda n, v: _validate.flag(n, v),
    "normalize_output": lambda n, v: _validate.flag(n, v),
    "matrix_form": lambda n, v: _validate.flag(n, v),
    "interpolate": lambda n, v: _validate.flag(n, v),
    "always_compute_step": lambda n, v: _validate.flag(n, v),
    "algorithm": lambda n, v: _validate.choice(n, v, ("auto", "arnoldi", "lanczos", "lanczos_fro")),
    "eigensolver_dtype": lambda n, v: _validate.choice(n, v, ("dense", "csr", "dia")),
    "progress_bar": _qutip_progress_bar,
    "progress_kwargs": lambda n, v: _validate.mapping(n, v),
}


class _QutipSolver(Propagator):
    """QuTiP's solver of the same name on ``H / hbar``; its options are QuTiP's (``atol``/``rtol`` are the ODE tolerances).

    The options are checked here, before any work: a key must be one of the solver's or of the chosen integrator's
    (``options["method"]``, default ``"adams"``), and each value is checked by :data:`_QUTIP_CHECKS` (step counts
    positive integers, tolerances positive finite numbers, switches ``True``/``False``; booleans are no numbers).
    """

    native = False

    @classmethod
    def solver(cls):
        """QuTiP's solver class of this method (``qutip.SESolver`` or ``qutip.MESolver``)."""
        qutip = _lazy.qutip
        return qutip.SESolver if cls.name == "sesolve" else qutip.MESolver

    @classmethod
    def allowed_options(cls):
        solver = cls.solver()
        keys = dict(RESULT_OPTIONS)
        for k, v in solver.solver_options.items():
            keys.setdefault(k, (v, "QuTiP solver option"))
        for integ in solver.avail_integrators().values():
            for k, v in getattr(integ, "integrator_options", {}).items():
                keys.setdefault(k, (v, "QuTiP integrator option"))
        return keys

    @classmethod
    def resolve_options(cls, given):
        """``given`` checked key by key (the class docstring), with the values as QuTiP takes them."""
        super().resolve_options(given)  # refuses a non-dict and keys of no integrator, with the allowed list
        given = dict(given or {})
        solver = cls.solver()
        integrators = solver.avail_integrators()
        default = solver.solver_options["method"]
        method = given.get("method")
        method = _validate.choice("options['method'] (QuTiP's ODE integrator)", default if method is None else method,
                                  tuple(integrators), case_insensitive=False)
        own = getattr(integrators[method], "integrator_options", {})
        allowed = {**RESULT_OPTIONS, **solver.solver_options, **own}  # (the solver's keys and the integrator's)
        for key in sorted(set(given) - set(allowed), key=str):  # a key of another integrator
            owners = [m for m, integ in integrators.items() if key in getattr(integ, "integrator_options", {})]
            _validate.unknown_option(
                f"evolve options of method {cls.name!r} with QuTiP's integrator {method!r} ({key!r} is an option "
                f"of the integrator(s) {', '.join(map(repr, owners))}: choose one with options['method'])",
                key, list(allowed))
        defaults = {**solver.solver_options, **own}
        checked = {key: method if key == "method" else cls.check_option(key, value, defaults.get(key))
                   for key, value in given.items()}
        if method == "krylov" and checked.get("krylov_dim") is None:  # (QuTiP's default, 0, fails in the run)
            raise ValueError("QuTiP's 'krylov' integrator needs options['krylov_dim'], the dimension of its Krylov "
                             "subspace (an integer >= 1, e.g. 20)")
        if checked.get("atol") == 0.0 and checked.get("rtol") == 0.0:  # (each alone is a valid control)
            raise ValueError("options['atol'] and options['rtol'] are both 0: the integrator controls no error (give "
                             "one of them > 0)")
        return checked

    @staticmethod
    def check_option(key: str, value: Any, default: Any) -> Any:
        """``value`` of the QuTiP option ``key`` checked (``default``: QuTiP's default of the key), as QuTiP takes
        it; ``TypeError``/``ValueError`` naming ``options[key]``, the value and what is allowed."""
        name = f"options[{key!r}]"
        if value is None:  # (QuTiP's "its default", for every key)
            return None
        if key in ("order", "max_order_ns", "max_order_s"):
            top = int(default) if isinstance(default, int) and not isinstance(default, bool) and default > 0 else None
            return _validate.whole_number(name, value, minimum=1, maximum=top)
        check = _QUTIP_CHECKS.get(key)
        if check is not None:
            return check(name, value)
        if isinstance(default, bool):  # a key of a newer QuTiP: by the type of its default
            return _validate.flag(name, value)
        if isinstance(default, int):
            return _validate.whole_number(name, value)
        if isinstance(default, float):
            return _validate.real(name, value)
        return value

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
