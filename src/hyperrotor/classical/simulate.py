r"""Numerical integration of the N-dimensional Euler equations: :func:`simulate`, :class:`Trajectory`.

Equations (eqs. 24-26 of the paper, components; identical in the "paper" and
"standard" matrix conventions, see :mod:`hyperrotor.conventions`)

.. math:: \dot L_a = \sum_{b,c} C_{bc}^{\;a}\,\omega_b L_c + \tau_a,
          \qquad L_a = I_a\,\omega_a, \qquad \dot T = \Omega\,T,

i.e. :math:`\dot L = [\Omega, L] + \tau` with plain matrices, ``tau`` an optional
body-frame torque (components in plane order, units of :math:`dL/dt`) and
``T`` the attitude of eq. (19) (space to body: :math:`L_\text{body} = T L_\text{space} T^{\mathsf T}`),
:math:`\Omega` the angular-velocity matrix in the body's convention.

:func:`simulate` normalises its inputs once into a :class:`~.solvers.base.Problem` and
hands it to a solver of :data:`~.solvers.SOLVERS` (see :mod:`hyperrotor.classical.solvers`
for each method's order, invariants and options).
"""
from __future__ import annotations

import math
import time
from functools import lru_cache
from typing import Any, Callable, Mapping, NamedTuple

import numpy as np

from hyperrotor import _pricing, _validate
from hyperrotor._floats import power_of_two_scale
from hyperrotor._options import options as _table, register
from hyperrotor.conventions import dimension_from_count

from .solvers import SOLVERS, FixedStepSolver, Problem, ScipyIVP, Solver, solver_for
from .solvers.chunks import Work, cost_key, seconds_per_flow
from ._trajectory import Trajectory
from .solvers.richardson_check import check_bytes
from .solvers.step_control import CHECK_MEMBERS, ErrorTarget, FixedStep, StepBudgetError

__all__ = ["simulate", "Trajectory", "SIMULATION_METHODS"]

#: Allowed ``method=`` names of :func:`simulate`: ``"auto"`` and the keys of the solver registry.
SIMULATION_METHODS = ("auto", *SOLVERS)

_LOWER_NAMES = frozenset(m.lower() for m in SOLVERS)
#: largest scaled momentum (angular velocities of order one): its square must stay finite
MAX_SCALED_MOMENTUM = 1e150
#: smallest nonzero scaled momentum: its square must stay a normal number (tiny moments, 1e-200, divided by zero)
MIN_SCALED_MOMENTUM = 1e-150
#: smallest time scale: scaled times t * s stay normal numbers even for |omega| in the subnormal range
#: (below it the scaled momenta, not the times, carry the smallness)
MIN_SCALE = 2.0 ** -960
register(
    "simulate_rtol", 1e-9,
    "rtol of hyperrotor.simulate when neither rtol nor dt is given: a bound on the whole-run error of the "
    "fixed-step methods (max_t |L - L_exact| <= rtol max_t |L|), scipy's local tolerance for the scipy "
    "methods. 1e-9 costs splitting8 about 1.5x the steps of 1e-6 and stays well above round-off.",
    check=_validate.tolerance,
)

#: ``method="auto"``: ``(rtol at least, method)`` from the registry's ``auto_rtol`` (largest first): the
#: first row whose bound ``rtol`` meets is chosen (from the rtol calls of ``benchmarks/step_control.py``: order 8
#: is the cheapest from ~1e-4 to 1e-10, order 10 below, order 2 only above 1e-2)
AUTO_ORDER = tuple(sorted(((cls.auto_rtol, name) for name, cls in SOLVERS.items() if cls.auto_rtol is not None),
                          reverse=True))


# ----------------------------------------------------------------------------
# normalising the inputs
# ----------------------------------------------------------------------------
def _broadcast_batch(name: str, arr: np.ndarray, core_ndim: int, batch: tuple) -> np.ndarray:
    lead = arr.shape[: arr.ndim - core_ndim]
    try:
        out_shape = np.broadcast_shapes(lead, batch)
    except ValueError:
        out_shape = None
    if out_shape != batch:
        raise ValueError(f"{name} has batch axes {lead}, inconsistent with the batch axes {batch} of omega0 "
                         f"(they must be equal or broadcast to it)")
    return np.broadcast_to(arr, batch + arr.shape[arr.ndim - core_ndim:])


@lru_cache(maxsize=64)
def _signs(N: int, convention: str, axes: tuple | None) -> np.ndarray:
    """Diagonal of S (``T_convention = S T_plain S``), cached (read-only)."""
    S = _validate.axis_signs(N, convention, axes)
    S.setflags(write=False)
    return S


class _ScaledTorque:
    """A callable torque ``torque(t, omega)`` in scaled units (a plain object: it pickles with the run)."""

    def __init__(self, torque: Callable, s: float, origin: float = 0.0):
        self.torque, self.s, self.origin = torque, s, origin

    def __call__(self, tt, w):
        s = self.s
        out = self.torque(tt / s + self.origin, w * s)
        try:
            tau = np.asarray(out, dtype=float)
            np.broadcast_to(tau, np.shape(w))
        except (TypeError, ValueError):
            raise TypeError(f"torque(t, omega) must return real numbers, one per plane ({np.shape(w)[-1]}), got "
                            f"{_validate.fmt(out)}") from None
        return tau / (s * s)


def _checked(solver, rtol, client) -> float:
    """How many members the step control's check may cover: every member of an ``rtol`` run of a fixed-step method,
    up to :data:`~.solvers.step_control.CHECK_MEMBERS` with a dask client; none otherwise."""
    if rtol is None or not isinstance(solver, FixedStepSolver):
        return 0.0
    return math.inf if client is None else float(CHECK_MEMBERS)


def _problem(body, omega0, t, attitude, torque, max_output_bytes, checked: float = 0.0) -> tuple[Problem, np.ndarray]:
    """Check and normalise the inputs once (scaled units, see :mod:`.solvers.base`); the output, and the step
    control's check of up to ``checked`` members (:func:`_checked`), priced against ``max_output_bytes``."""
    moments = _validate.moments(body, name="body")
    n = moments.size
    N = dimension_from_count(n)
    convention = _validate.convention(getattr(body, "convention", "paper"))
    axes = getattr(body, "axes", None)
    signs = _signs(N, convention, tuple(axes) if axes is not None and len(axes) == N else None)
    w0 = _validate.finite_array("omega0", omega0)
    if w0.ndim == 0 or w0.shape[-1] != n:
        raise ValueError(f"omega0 must have shape batch + ({n},) (n_planes of so({N})), got shape {w0.shape}")
    batch = w0.shape[:-1]
    B = int(np.prod(batch)) if batch else 1
    if isinstance(attitude, np.bool_):  # (a switch: NumPy booleans as Python's, docs/conventions.md)
        attitude = bool(attitude)
    with_att = attitude is not False and attitude is not None
    K = _validate.time_count(t)  # before any copy of a huge grid
    nbytes = 8.0 * B * K * (2 * n + (N * N if with_att else 0))
    check = check_bytes(int(min(B, checked)), n) if K > 1 else 0.0
    if nbytes + check > max_output_bytes:
        raise _pricing.refuse(
            "simulate", f"the output of this run ({B} member(s) x {K} output times"
            + (f", and its accuracy check: {check:.3g} bytes)" if check else ")"), nbytes + check, "max_output_bytes",
            "bytes", "ask for fewer output times (events= or Trajectory.sol give states between them)",
            limit=int(max_output_bytes), cls=StepBudgetError, needed=nbytes + check, budget=max_output_bytes,
            option="max_output_bytes")
    t_user = _validate.time_grid(t)
    s = max(power_of_two_scale(float(np.abs(w0).max()) if w0.size else 0.0), MIN_SCALE)
    tq = None
    if torque is not None:
        if callable(torque):
            tq = _ScaledTorque(torque, s, float(t_user[0]))
        else:
            tq = _validate.finite_array("torque", torque)
            if tq.ndim == 0 or tq.shape[-1] != n:
                raise ValueError(f"constant torque must have shape ({n},) or batch + ({n},), got {tq.shape}")
            tq = np.ascontiguousarray(_broadcast_batch("torque", tq, 1, batch).reshape(B, n)) / s / s
    T0 = None
    if with_att:
        if attitude is True:
            T0 = np.broadcast_to(np.eye(N), (B, N, N))
        else:
            T0 = _validate.orthogonal_matrix("attitude", attitude, N, batched=True)
            T0 = _broadcast_batch("attitude", T0, 2, batch).reshape(B, N, N)
        T0 = signs[:, None] * T0 * signs[None, :]  # plain convention: T_conv = S T_plain S
    origin = float(t_user[0])
    ts = (t_user - origin) * s  # (from the first output time: the run's own resolution, see Problem.t)
    if not np.all(np.isfinite(ts)):
        raise ValueError(f"t - t[0] times max|omega0| overflows double precision (the span "
                         f"{abs(float(t_user[-1]) - origin):.3g}, max|omega0| = {float(np.abs(w0).max()):.3g})")
    together = np.flatnonzero(np.diff(ts) * np.sign(ts[-1]) <= 0) if ts.size > 1 else ()
    if len(together):
        k = int(together[0])
        raise ValueError(f"t[{k}] = {float(t_user[k])!r} and t[{k + 1}] = {float(t_user[k + 1])!r} are the same "
                         f"time from t[0] = {origin!r} in double precision (t - t[0] rounds them together): drop "
                         f"one, or start t nearer to them")
    L0 = np.ascontiguousarray((w0.reshape(B, n) / s) * moments)
    big = float(np.abs(L0).max()) if L0.size else 0.0
    # (the run is scaled, but L = I omega itself, the output, is not; |L| is conserved: no component of L(t)
    # exceeds sqrt(n) max|L0|)
    if not math.isfinite(math.sqrt(n) * big * s):
        raise FloatingPointError(
            f"the angular momenta L = I omega overflow double precision (max|I omega0| = {big * s:.3g} over "
            f"{n} planes); rescale the moments (omega(t) does not change when every moment is multiplied by the same "
            f"factor)")
    if big > MAX_SCALED_MOMENTUM:
        raise FloatingPointError(
            f"the angular momenta overflow double precision arithmetic: with angular velocities scaled to "
            f"order one (t * {_validate.fmt(s)}) |L| still reaches {big:.3g} (moments up to "
            f"{float(moments.max()):.3g}); squares and products of L must stay finite. Rescale the moments"
        )
    if 0.0 < big < MIN_SCALED_MOMENTUM:
        raise FloatingPointError(
            f"the angular momenta underflow double precision arithmetic: with angular velocities scaled to "
            f"order one (t * {_validate.fmt(s)}) |L| is at most {big:.3g} (moments up to "
            f"{float(moments.max()):.3g}); squares and products of L must stay normal numbers. Rescale the moments "
            f"(omega(t) does not change when every moment is multiplied by the same factor)"
        )
    return Problem(body=body, moments=moments, N=N, n=n, convention=convention, signs=signs, batch=batch, L0=L0,
                   T0=T0, torque=tq, t=ts, scale=s, origin=origin), t_user


def _solver_options(value: Any) -> dict:
    """The ``options=`` mapping of :func:`simulate` (the chosen method's option table), checked."""
    return _validate.mapping("options", value, " (e.g. {'compensated': True})")


def _choose_solver(method, rtol, dt, torque, solver_options: dict) -> Solver:
    if isinstance(method, str) and method.lower() == "auto":
        if callable(torque):
            method = "DOP853"
        elif rtol is None and dt is not None:
            method = "splitting4"
        else:
            r = _table["simulate_rtol"] if rtol is None else rtol
            method = next(name for bound, name in AUTO_ORDER if r >= bound)
    elif isinstance(method, str) and method.lower() not in _LOWER_NAMES:
        raise ValueError(f"unknown method {method!r}; allowed: {', '.join(map(repr, SIMULATION_METHODS))}")
    return solver_for(method, **solver_options)


def _atol(atol: Any, problem: Problem) -> np.ndarray | None:
    """``atol`` checked (finite, >= 0; scalar or one per plane) and in scaled units, or ``None``."""
    if atol is None:
        return None
    a = _validate.finite_array("atol", atol)
    if a.ndim > 1 or (a.ndim == 1 and a.size != problem.n) or np.any(a < 0):
        raise ValueError(f"atol must be a number >= 0 or {problem.n} of them (one per plane), got {_validate.fmt(atol)}")
    return np.broadcast_to(a, (problem.n,)) / problem.scale


def _step_control(solver: Solver, rtol: float | None, dt: float | None, atol: Any = None) -> FixedStep | ErrorTarget:
    """``dt`` (fixed-step methods only) or ``rtol`` (default ``_table["simulate_rtol"]``), not both;
    ``atol`` (checked, scaled) for scipy methods only."""
    if isinstance(solver, ScipyIVP):
        if dt is not None:
            raise ValueError(f"dt fixes the step of the fixed-step methods; scipy method {solver.name!r} takes "
                             f"rtol and atol")
        control = ErrorTarget(_table["simulate_rtol"] if rtol is None else rtol)
        control.atol = atol
        return control
    if atol is not None:
        raise ValueError(f"atol is the absolute tolerance of the scipy methods; {solver.name!r} takes rtol (a bound "
                         f"on the whole-run error relative to max|L|) or dt")
    if dt is not None and rtol is not None:
        raise ValueError(f"give either dt (fixed step) or rtol (step chosen from the accuracy) for "
                         f"{solver.name!r}, not both (got dt={_validate.fmt(dt)}, rtol={_validate.fmt(rtol)})")
    elif dt is not None:
        return FixedStep(dt)
    return ErrorTarget(_table["simulate_rtol"] if rtol is None else rtol)


def simulate(
    body: Any,
    omega0: Any,
    t: Any,
    *,
    method: str | Solver = "auto",
    rtol: float | None = None,
    atol: Any = None,
    dt: float | None = None,
    attitude: bool | Any = False,
    torque: Callable | Any | None = None,
    events: Callable | list | None = None,
    max_steps: int | None = None,
    progress: bool | None = None,
    client: Any = None,
    options: Mapping[str, Any] | None = None,
) -> Trajectory:
    r"""Integrate the Euler equations (eqs. 24-26) of a rigid body in N dimensions.

    Parameters
    ----------
    body : RigidBody, Inertia or array_like (n_planes,)
        The body (its matrix convention is used for ``attitude``; plain
        moments or an ``Inertia`` mean ``convention="paper"``).
    omega0 : array_like batch + (n_planes,)
        initial angular velocities :math:`\omega_{ij}(t_0)` in plane order;
        leading axes are an ensemble integrated in one call.
    t : array_like (K,)
        strictly monotonic output times; ``t[0]`` is the initial time. A decreasing
        grid integrates backwards in time (the flows are reversible).
    method : str or Solver
        ``"auto"`` or a name of :data:`hyperrotor.classical.solvers.SOLVERS` (case-insensitive:
        ``"splitting2"`` ... ``"splitting10"``, ``"moser-veselov"``, ``"DOP853"``, ``"RK45"``,
        ``"RK23"``, ``"LSODA"``, ``"Radau"``, ``"BDF"``), or a solver object such as
        ``Splitting8(compensated=True)``. ``"auto"``: a callable torque -> ``"DOP853"``;
        only ``dt`` -> ``"splitting4"``; else the splitting of order 4, 8 or 10 for
        ``rtol >= 1e-4``, ``>= 1e-10``, smaller.
    rtol : float, optional
        requested accuracy. Fixed-step methods (splittings, Moser-Veselov): a bound on the
        whole-run error, :math:`\max_t\|L - L_\text{exact}\|_\infty \le \mathrm{rtol}\max_t\|L\|_\infty`
        over the run, the largest :math:`|L|` (and :math:`|\omega|`) taken over the output times and the check's
        samples between them (and the same for :math:`\omega`; a target looser than 1e-3 is run to 1e-3,
        ``step_control.LOOSEST_RTOL``): a probe chooses the step, the run checks its own
        error as it goes (Richardson's estimate against a companion run with longer steps) and
        is re-run at a shorter step when the check fails
        (:mod:`hyperrotor.classical.solvers.step_control`); an orbit whose error grows
        exponentially (chaotic) so that ``rtol`` is out of reach within the budget is refused
        with the estimated growth :math:`e^{\lambda T}` and the reachable accuracy. scipy
        methods: scipy's *local* tolerance (the global error is typically 10-1000 times larger
        over long runs). ``0 < rtol < 1`` (a relative error of 1 or more bounds nothing). Default
        ``hyperrotor.options["simulate_rtol"]`` (1e-9) when neither ``rtol`` nor ``dt`` is given.
    atol : float or array_like (n_planes,), optional
        scipy methods only: absolute tolerance of ``solve_ivp`` on the angular velocities
        :math:`\omega_{ij}` (units of ``omega0``), as in :func:`scipy.integrate.solve_ivp`
        (each step keeps its error estimate below ``atol + rtol * |omega|``); the attitude
        entries keep ``rtol``. Default: ``rtol * min(max|omega0|, |L0| / I_ij)`` per
        component (errors in :math:`\omega` below ``rtol max|omega0|`` and in ``L`` below
        ``rtol |L0|``).
    dt : float, optional
        largest step of a fixed-step method; each output interval is split into
        ``ceil(|gap| / dt)`` equal steps, so output times are hit exactly. Not with
        ``rtol``, nor with a scipy method.
    attitude : bool or array_like, optional
        ``True`` integrates :math:`T(t)` from the identity; an array ``(N, N)`` or
        batch + ``(N, N)`` (orthogonal, body convention) is the initial attitude.
    torque : array_like or callable, optional
        body-frame torque :math:`\tau_{ij}` added to :math:`\dot L^{ij}`: constant components
        (n_planes,) or batch + (n_planes,) (splittings: exact kicks; scipy methods), or a
        callable ``torque(t, omega)`` returning n_planes components (scipy methods).
    events : callable or list of callables, optional
        event functions ``g(t, L) -> float`` as in :func:`scipy.integrate.solve_ivp`
        (attributes ``terminal``: bool or count, ``direction``: sign of the crossing);
        their zeros are located to the method's accuracy and returned in
        ``Trajectory.t_events`` / ``L_events``; a terminal event ends the run. With an
        ensemble ``omega0`` every member is run on its own with the ensemble's step (the
        momenta of the run without events, bit for bit), events must be non-terminal, and
        ``t_events[e][m]`` is the array of member ``m`` (flattened batch order).
    max_steps : int, optional
        budget of the call (every step taken times the members it advances: the run, and
        with ``rtol`` the step control's probes and check; scipy: right-hand-side
        evaluations); default ``hyperrotor.options["max_steps"]``. A run estimated above it
        is refused before it starts (:class:`~hyperrotor.classical.solvers.StepBudgetError`,
        naming the estimate; :func:`estimate_cost` prices a call without running it). The output memory (and with
        ``rtol`` that of the check, about 1 kB per member) is bounded by ``hyperrotor.options["max_output_bytes"]``.
    progress : bool or None, optional
        show a tqdm progress bar (``None``: only on a terminal, for runs longer than ~1 s).
    client : dask.distributed.Client, optional
        run the members of an ensemble (2-D ``omega0``) on a dask cluster in chunks of
        about a second of work each (see ``docs/scaling-out.md``); the same results as
        without it.
    options : mapping, optional
        options of the chosen method, as in :func:`hyperrotor.quantum.evolve` (e.g.
        ``options={"compensated": True}`` for the splittings; each solver's table:
        ``hyperrotor.SOLVERS[name].option_docs``); an unknown key raises
        :class:`~hyperrotor.UnknownOptionError` naming the allowed ones.

    Returns
    -------
    Trajectory
        ``omega``, ``L`` (batch + (K, n)), ``attitude`` (batch + (K, N, N) or ``None``),
        ``t_events``/``L_events`` (with ``events``), ``sol(t)`` (dense output) and ``stats``.

    Raises
    ------
    ValueError
        unknown method, non-finite or mis-shaped inputs, ``t`` not strictly monotonic,
        inconsistent batch axes, conflicting ``dt``/``rtol``, ``atol`` for a fixed-step
        method, a torque the method cannot integrate;
        :class:`~hyperrotor.classical.solvers.StepBudgetError` (a ValueError) for a run over
        budget; :class:`~hyperrotor.classical.solvers.step_control.UnreachableAccuracyError`
        when re-runs at shorter steps do not meet ``rtol`` (chaotic orbit, round-off).
    TypeError
        non-numeric input, an unknown option of the method.
    RuntimeError
        ``"moser-veselov"`` with a step too long for its implicit equation; a scipy method
        that fails. ``FloatingPointError``: the solution left double precision.
    KeyboardInterrupt
        Ctrl-C, honoured within about ``_table["chunk_seconds"]`` in every phase (the step
        control's probes and check run in chunks too).

    Examples
    --------
    >>> import numpy as np
    >>> traj = simulate([2.0, 3.0, 4.0], [0.1, 1.0, 0.2], np.linspace(0, 10, 5), method="splitting4", dt=0.01)
    >>> traj.omega.shape
    (5, 3)
    """
    wall = time.perf_counter()
    max_steps = _table["max_steps"] if max_steps is None else _validate.integer("max_steps", max_steps, minimum=1)
    rtol = _validate.tolerance("rtol", rtol, allow_none=True)
    progress = _validate.flag("progress", progress, allow_none=True)
    dt = _validate.positive("dt", dt, allow_none=True)
    client = _validate.client(client)
    solver = _choose_solver(method, rtol, dt, torque, _solver_options(options))
    problem, t_user = _problem(body, omega0, t, attitude, torque, _table["max_output_bytes"],
                               _checked(solver, rtol, client))
    _pricing.check("simulate", N=problem.N)
    control = _step_control(solver, rtol, dt, _atol(atol, problem))
    if events is not None and problem.batch:
        if client is not None:
            raise ValueError("events= on an ensemble runs in this process, member by member: drop client= (or "
                             "map simulate(..., events=...) over the members with your client)")
        from .solvers.members import run_members_with_events

        res = run_members_with_events(solver, problem, control, events=events, max_steps=max_steps,
                                      progress=progress)
    elif client is not None and problem.B > 1:
        from .solvers.distributed import run_distributed

        res = run_distributed(solver, problem, control, client=client, max_steps=max_steps, progress=progress)
    else:
        res = solver.run(problem, control, events=events, max_steps=max_steps, progress=progress)
    return _trajectory(solver, problem, control, res, t_user, wall)


def _trajectory(solver, problem, control, res, t_user, wall) -> Trajectory:
    s = problem.scale
    K = res.t.size
    batch = problem.batch
    L = (res.L * s).reshape(batch + (K, problem.n))
    omega = L / problem.moments
    att = None
    if res.T is not None:
        S = problem.signs
        att = (S[:, None] * res.T * S[None, :]).reshape(batch + (K, problem.N, problem.N))
    stats: dict[str, Any] = {"method": solver.name, "order": solver.order, "rtol": getattr(control, "requested", None)}
    stats.update(res.stats)
    if stats.get("dt") is not None:
        stats["dt"] = stats["dt"] / s
    if hasattr(solver, "stats") and isinstance(solver, FixedStepSolver):
        stats.update(solver.stats(problem))
    stats["wall_time"] = time.perf_counter() - wall
    events = (res.t_events, res.L_events, res.T_events) if res.t_events is not None else None
    return Trajectory(t_user[:K], omega, L, att, problem.body, problem.moments, stats, dense=res.dense, scale=s,
                      signs=problem.signs, events=events, origin=problem.origin)


class RunCost(NamedTuple):
    """What :func:`estimate_cost` expects a :func:`simulate` call to cost."""

    #: integration steps of the whole call, summed over the members: the run, its check and the
    #: step control's probes (``None`` for scipy methods, whose steps are not known in advance)
    steps: int | None
    #: estimated wall time (s) on this machine, from the measured cost per flow of the compiled
    #: kernel (probes, earlier runs) or a default of 10 ns per flow before anything was timed
    seconds: float | None
    #: the step a fixed-step method will take (user time units), ``None`` for scipy methods
    dt: float | None
    #: the method ``method="auto"`` resolves to
    method: str


def estimate_cost(body: Any, omega0: Any, t: Any, *, method: str | Solver = "auto", rtol: float | None = None,
                  dt: float | None = None, attitude: bool | Any = False, torque: Any = None,
                  max_steps: int | None = None, max_seconds: float | None = None,
                  options: Mapping[str, Any] | None = None) -> RunCost:
    """Price a :func:`simulate` call before running it (for budgets such as the CLI's ``--max-seconds``).

    Same arguments as :func:`simulate`. With ``dt`` nothing is integrated; with ``rtol`` the
    step control's probe runs (a short leading window, a small fraction of the run, chunked
    and counted against ``max_steps``). The run's check (companion runs of every member, at steps up to
    :data:`~.solvers.richardson_check.COMPANION_RATIO` times longer) is included; re-runs after a
    failed check are not (they are rare). scipy methods: ``steps``, ``seconds`` and ``dt`` are
    ``None``.

    Raises :class:`~.solvers.StepBudgetError` when the probe alone exceeds ``max_steps``
    (default ``hyperrotor.options["max_steps"]``) or, with ``max_seconds``, when its estimated time does (before
    each of its compiled calls, at the cost per step of this kind of call, learned or
    :func:`~.solvers.chunks.flow_weight` times a 5D default: at N = 200 a step of splitting8 takes about a second,
    and a probe of tens of steps is not "a small fraction" of a caller's budget; ``option == "max_seconds"``),
    and the errors of :func:`simulate` for bad input.

    Examples
    --------
    >>> cost = estimate_cost([2.0, 3.0, 4.0], [0.1, 1.0, 0.2], [0.0, 100.0], dt=0.01)
    >>> cost.steps, cost.method
    (10000, 'splitting4')
    """
    import warnings

    max_steps = _table["max_steps"] if max_steps is None else _validate.integer("max_steps", max_steps, minimum=1)
    max_seconds = _validate.positive("max_seconds", max_seconds, allow_none=True, allow_zero=True)
    rtol = _validate.tolerance("rtol", rtol, allow_none=True)
    dt = _validate.positive("dt", dt, allow_none=True)
    solver = _choose_solver(method, rtol, dt, torque, _solver_options(options))
    problem, _ = _problem(body, omega0, t, attitude, torque, _table["max_output_bytes"], _checked(solver, rtol, None))
    _pricing.check("simulate", N=problem.N)  # (the set-up simulate would do: priced here as there)
    control = _step_control(solver, rtol, dt)
    if not isinstance(solver, FixedStepSolver):
        return RunCost(None, None, None, solver.name)
    from .solvers.base import nsub_for

    solver.check(problem)
    solver.prepare(problem)
    if problem.t.size < 2 or problem.B == 0:
        return RunCost(0, 0.0, None, solver.name)
    spf = seconds_per_flow(cost_key(solver, problem))
    work = Work(max_steps, max_seconds, solver.flows_per_step(problem) * spf)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # the slow-run warning: the caller prices the run itself
        h = control.first_step(solver, problem, work)
    nsub = nsub_for(problem.t, h)
    run = float(nsub.sum()) * problem.B
    solver.set_accuracy(problem, control.rtol, int(nsub.sum()))  # the kernel variant the run will use (its cost)
    check = control.checker(solver, problem, nsub, work)
    total = work.done + run + (check.planned_steps if check is not None else 0)
    seconds = total * solver.flows_per_step(problem) * seconds_per_flow(cost_key(solver, problem))  # (learned now)
    return RunCost(int(total), float(seconds), float(np.abs(np.diff(problem.t) / nsub).max()) / problem.scale,
                   solver.name)
