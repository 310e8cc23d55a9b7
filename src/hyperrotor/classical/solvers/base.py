r"""The solver interface of :func:`hyperrotor.simulate`: :class:`Problem`, :class:`Solver`.

A run is split the way scipy's ``solve_ivp`` (``OdeSolver``) and diffrax
(``AbstractSolver`` + step-size controllers) split it:

* :class:`Problem`: *what* is integrated, normalised once by ``simulate`` (moments,
  dimension, sign convention, initial momenta and attitudes of the ensemble, torque,
  time grid), in scaled units (see below);
* a :class:`Solver` object: *how*, with its class attributes ``name``, ``order``,
  ``preserves`` (invariants kept to round-off, and whether the map is symplectic /
  time-reversible), ``adaptive`` and its own options (``Solver.option_docs``;
  unknown options are an error naming the allowed ones);
* a step control (:mod:`.step_control`): a fixed ``dt`` or an error target ``rtol``;
* the fixed-step methods share one run loop (:mod:`.driver`, :class:`~.driver.FixedStepSolver`).

This module is a leaf of the package (it imports no other solver module).

Scaled units
------------
The free Euler equations are invariant under :math:`\omega \to s\,\omega`,
:math:`t \to t/s`. ``simulate`` integrates with :math:`s = 2^k` close to
``max|omega0|`` (a power of two, so scaling is exact in floating point), i.e. with
angular velocities of order one: inputs such as ``1e200 * omega0`` with
``t * 1e-200`` neither overflow nor underflow, and give exactly the scaled result.
Torques scale as :math:`s^2`. A :class:`Problem` holds the scaled values; ``scale``
converts back.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, ClassVar

import numpy as np

from hyperrotor import _validate
from hyperrotor._pricing import BudgetError

__all__ = ["Problem", "Solver", "RunResult", "StepBudgetError", "nsub_for", "step_lengths"]


@dataclass
class Problem:
    """One normalised integration request (scaled units; see the module docstring).

    Attributes
    ----------
    body : object
        the ``body`` argument of ``simulate`` (``RigidBody``, ``Inertia`` or moments).
    moments : ndarray (n,)
        plane moments :math:`I_a`.
    N, n : int
        dimension and number of planes.
    convention : str
        matrix convention of the attitude (``"paper"`` or ``"standard"``).
    signs : ndarray (N,)
        diagonal of ``S`` with ``T_convention = S T_plain S`` (the body's own axis labels).
    batch : tuple
        ensemble shape of ``omega0``; ``B = prod(batch)`` members.
    L0 : ndarray (B, n)
        scaled initial momenta :math:`L_a = I_a\\omega_a / s`.
    T0 : ndarray (B, N, N) or None
        initial attitudes in the plain convention (``None``: attitude not integrated).
    torque : None, ndarray (B, n) or callable
        scaled body torque (constant components or ``torque(t, omega)`` in scaled units).
    t : ndarray (K,)
        scaled output times from the first, ``(t_user - origin) * scale``, strictly monotonic (``t[0] = 0``: a
        run far from the time origin keeps the resolution of its own span; sample times of the step control
        at t ~ 1e15, where consecutive floats are 0.125 apart, fell onto each other).
    scale : float
        the power of two ``s``.
    origin : float
        the user's first output time; :meth:`user_time` maps scaled times back (events, torques, messages).
    """

    body: Any
    moments: np.ndarray
    N: int
    n: int
    convention: str
    signs: np.ndarray
    batch: tuple
    L0: np.ndarray
    T0: np.ndarray | None
    torque: Any
    t: np.ndarray
    scale: float
    extra: dict = field(default_factory=dict)
    origin: float = 0.0

    def __post_init__(self):
        # Read-only whatever the caller passed (a body's cached moments are, a user's array is not): numba
        # compiles a kernel once per argument type, writeability included, so one kind of moments array
        # means one compiled kernel per route (the Moser-Veselov kernel compiled twice before, ~4-19 s).
        if self.moments.flags.writeable:
            self.moments = self.moments.copy()
            self.moments.setflags(write=False)

    def __setstate__(self, state: dict) -> None:
        # unpickled or deep-copied arrays come back writeable: read-only again, as built
        self.__dict__.update(state)
        self.__post_init__()

    @property
    def B(self) -> int:
        return self.L0.shape[0]

    @property
    def with_attitude(self) -> bool:
        return self.T0 is not None

    def user_time(self, ts: Any) -> Any:
        """The user's time of the scaled time(s) ``ts`` (``ts / scale + origin``)."""
        return ts / self.scale + self.origin

    @property
    def span(self) -> float:
        """Length of the run (scaled time), ``|t[-1] - t[0]|``."""
        return float(abs(self.t[-1] - self.t[0]))

    @property
    def kick(self) -> bool:
        """A constant, non-zero torque."""
        return isinstance(self.torque, np.ndarray) and bool(np.any(self.torque))


class Solver:
    """Base class of the integrators of :func:`hyperrotor.simulate` (one subclass per method).

    Subclasses set the class attributes below, list their options in ``option_docs``
    (name -> (default, one-line meaning)) and implement :meth:`run`. Construct with the
    options as keywords: ``Splitting8(compensated=True)``; ``simulate(method=...)``
    accepts the name or such an object.

    Attributes
    ----------
    name : str
        registry name (``simulate(method=name)``, matched ignoring case).
    order : int or None
        classical order of the global error (``None`` for variable-order methods).
    preserves : frozenset of str
        what the map keeps exactly (to round-off): ``"casimirs"``, ``"energy"``,
        ``"orthogonality"`` (of the attitude), and the structural properties
        ``"symplectic"`` (Poisson map on each coadjoint orbit) and ``"reversible"``.
    adaptive : bool
        whether the step adapts during the run (scipy methods) or is fixed (chosen once
        from ``dt`` or ``rtol``).
    supports_torque : {"none", "constant", "any"}
        which torques the method integrates.
    tangent : bool
        whether compiled tangent maps of the method exist (the Lyapunov exponents of
        :func:`hyperrotor.lyapunov` use them).
    auto_rtol : float or None
        ``method="auto"`` picks the method with the largest ``auto_rtol`` that ``rtol`` is at
        least (``None``: never picked automatically).
    """

    name: ClassVar[str] = ""
    order: ClassVar[int | None] = None
    preserves: ClassVar[frozenset] = frozenset()
    adaptive: ClassVar[bool] = False
    supports_torque: ClassVar[str] = "none"
    tangent: ClassVar[bool] = False
    auto_rtol: ClassVar[float | None] = None
    option_docs: ClassVar[dict[str, tuple[Any, str]]] = {}

    def __init__(self, **options: Any) -> None:
        self.options = {k: v for k, (v, _) in self.option_docs.items()}
        unknown = sorted(set(options) - set(self.option_docs))
        if unknown:
            _validate.unknown_option(f"method {self.name!r}", unknown[0], tuple(self.option_docs))
        self.options.update(options)
        self._check_options()

    def _check_options(self) -> None:
        """Validate ``self.options`` (subclasses)."""

    def __repr__(self) -> str:
        opts = ", ".join(f"{k}={_validate.fmt(v)}" for k, v in self.options.items())
        return f"{type(self).__name__}({opts})"

    def check(self, problem: Problem) -> None:
        """Refuse a problem this method cannot integrate (torque kind, body kind)."""
        tq = problem.torque
        if tq is None:
            return
        if callable(tq) and self.supports_torque != "any":
            raise ValueError(
                f"a callable torque needs an adaptive scipy method (e.g. 'DOP853'); {self.name!r} integrates "
                f"{'constant torques only' if self.supports_torque == 'constant' else 'the free body only'}"
            )
        if self.supports_torque == "none" and problem.kick:
            raise ValueError(f"method {self.name!r} integrates the free body only; for a constant torque use a "
                             f"splitting method, for any torque a scipy method")

    def run(self, problem: Problem, control: Any, *, events=None, max_steps: int, progress=None):
        """Integrate ``problem`` with step ``control``; returns a :class:`RunResult`."""
        raise NotImplementedError


@dataclass
class RunResult:
    """What a solver hands back to ``simulate`` (scaled units)."""

    L: np.ndarray  # (B, K', n)
    T: np.ndarray | None  # (B, K', N, N) plain convention
    t: np.ndarray  # (K',) output times reached (shorter after a terminal event)
    stats: dict
    dense: Callable | None = None  # dense(tq (M,)) -> (L (B, M, n), T (B, M, N, N) or None)
    t_events: list | None = None
    L_events: list | None = None
    T_events: list | None = None


class StepBudgetError(BudgetError):
    """A run whose estimated size exceeds a budget of :data:`hyperrotor.options` (``max_steps``, ...).

    Attributes ``needed`` (the estimate, in the budget's units), ``budget`` (its value) and
    ``option`` (the name of the budget: ``"max_steps"``, ``"max_output_bytes"``) let a caller
    such as the command line reword the advice for its own options.
    """

    def __init__(self, message: str, *, needed: float | None = None, budget: float | None = None,
                 option: str | None = None):
        super().__init__(message)
        self.needed, self.budget, self.option = needed, budget, option

    def __reduce__(self):  # (with the figures _pricing.refuse sets, ``what`` and ``unit``, as its state)
        return _budget_error, (type(self), str(self), self.needed, self.budget, self.option), dict(self.__dict__)


def _budget_error(cls, message, needed, budget, option):
    """Unpickle a :class:`StepBudgetError` with its attributes."""
    return cls(message, needed=needed, budget=budget, option=option)


def nsub_for(t: np.ndarray, dt: float) -> np.ndarray:
    """Equal steps per output interval so that no step exceeds ``dt`` (output times hit exactly)."""
    gaps = np.abs(t[1:] - t[:-1])
    with np.errstate(over="ignore"):
        n = np.maximum(1.0, np.ceil(gaps / dt * (1 - 1e-12)))
    total = float(n.sum())
    if not total < 2.0**62:  # not even countable in int64 (e.g. dt = 1e-301): far beyond any budget
        raise StepBudgetError(
            f"this run needs about {total:.3g} integration steps (span {float(gaps.sum()):.3g}, step {dt:.3g} in "
            f"units where omega is of order one), more than any budget max_steps allows",
            needed=total, option="max_steps",
        )
    return n.astype(np.int64)


def step_lengths(t: np.ndarray, nsub: np.ndarray) -> np.ndarray:
    """Step length ``(t[k+1] - t[k]) / nsub[k]`` of each interval (signed: negative backwards in time)."""
    return (t[1:] - t[:-1]) / nsub

