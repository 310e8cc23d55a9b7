r"""The quartet demo: the paper's 5D quartet body, its invariants, closed form against two integrators.

What ``hyperrotor demo`` shows, as library functions (the command line only
reads its options, prints and writes the files):

* :func:`quartet_invariants`: the conserved quantities of a body at an angular
  velocity (energy, the Casimirs of eq. 38, Manakov's traces) with
  :math:`L` and :math:`\dot\omega` (eqs. 28-37);
* :func:`compare_quartet_motion`: the closed form of the quartet body (eqs.
  84-85, solution eqs. 96-110 with corrected signs, frequencies after eq. 118)
  against the Lie-Poisson splitting of order 8 and scipy's DOP853: the motion,
  the relative error of each run, its energy and Casimir drift, wall times;
  priced before it runs (:func:`quartet_motion_seconds`, budget
  ``hr.options["max_seconds"]``);
* :func:`save_quartet_motion`: the picture of a comparison (PNG).

The relative error of a run is
:math:`\max_{t,\,ij}|\omega_{ij}(t) - \omega^{exact}_{ij}(t)| / \max_{ij}|\omega_{ij}(0)|`.
"""
from __future__ import annotations

import time
from typing import Any, NamedTuple

import numpy as np

from . import _pricing
from . import _validate as _v
from ._floats import power_of_two_scale

__all__ = ["DEMO_OMEGA", "DEMO_RUNS", "QuartetInvariants", "quartet_invariants", "MotionRun", "QuartetMotion",
           "compare_quartet_motion", "MotionCost", "quartet_motion_seconds", "save_quartet_motion"]

#: Sample angular velocity of the demo (plane order 12, 13, ..., 45).
DEMO_OMEGA = tuple(round(0.1 * k, 1) for k in range(1, 11))
#: The integrators compared with the closed form, with their tolerance.
DEMO_RUNS = (("splitting8", 1e-12), ("DOP853", 1e-10))
#: The cost model of :func:`quartet_motion_seconds`, CPU seconds of the runs with warm kernels (fitted to wall
#: times on the 2-core reference machine at load ~3: kappa 1e-3 ... 1e4, omega0 the default and 3x, t_end 30-3000,
#: 2001-200001 output times, within 0.8-1.25 of them there but 2.4x high at kappa = 30 and 100; then scaled to
#: CPU seconds by 0.55, the ratio of CPU to wall seconds at that load; benchmarks/pricing.py, docs/safety.md):
#: per unit of simulated time and of the motion's fastest frequency (DOP853's steps follow the motion: most of
#: the time below |kappa| ~ 500) ...
_SECONDS_PER_TIME_FREQUENCY = 1.05e-3
#: ... and of the step control's rate bound (``rate_bound``: splitting8's steps follow it, ~ |kappa| |omega|
#: for large kappa, when the motion's frequency stays ~ |omega|) ...
_SECONDS_PER_TIME_RATE = 2.2e-6
#: ... per unit of simulated time and of max|omega0| (a motion that does not turn, kappa = 1: every term is of
#: degree 1 in omega0, since the motion over t_end at omega0 is the one over s t_end at omega0 / s) ...
_SECONDS_PER_TIME = 5e-5
#: ... per output time (n_times) and fixed. The splitting run is made twice, the first call untimed: it loads
#: (or, on a fresh installation, compiles) every kernel the call takes (``QuartetMotion.warmup_time``; the
#: compile, 15-20 s once per installation, is not priced: it does not grow with a size).
_SECONDS_PER_OUTPUT = 7e-6
_SECONDS_FIXED = 0.05


class QuartetInvariants(NamedTuple):
    """Conserved quantities of a free body at one angular velocity (plus ``L`` and ``d omega/dt``)."""

    energy: float           #: :math:`E = \tfrac12 \sum I_{ij}\omega_{ij}^2`
    casimirs: np.ndarray    #: :math:`c_2 = \sum (L^{ij})^2`, :math:`c_4` (eq. 38)
    manakov: np.ndarray     #: :math:`\operatorname{tr}((L + J^2)^k)`, k = 2, 3, ... (mass-tensor bodies)
    L: np.ndarray           #: angular momentum components :math:`L^{ij} = I_{ij}\omega_{ij}`
    rhs: np.ndarray         #: :math:`\dot\omega` of the Euler equations (28)-(37)


def quartet_invariants(body: Any, omega0: Any) -> QuartetInvariants:
    """Energy, Casimirs, Manakov traces, ``L`` and ``d omega/dt`` of ``body`` at ``omega0``.

    ``body``: a :class:`~hyperrotor.RigidBody` with a mass tensor (Manakov's
    traces need one, e.g. ``Inertia.quartet``); ``omega0``: its plane components.
    """
    from .classical.rigid_body import RigidBody

    if not isinstance(body, RigidBody):
        raise TypeError(f"body must be a hyperrotor.RigidBody, got {_v.fmt(body)} of type {type(body).__name__}")
    omega0 = _v.components("omega0", omega0, len(body.planes))
    return QuartetInvariants(float(body.energy(omega0)), np.asarray(body.casimirs(omega0), dtype=float),
                             np.asarray(body.manakov_integrals(omega0, 1.0), dtype=float),
                             np.asarray(body.angular_momentum(omega0), dtype=float),
                             np.asarray(body.rhs(omega0), dtype=float))


class MotionRun(NamedTuple):
    """One integrator's run against the closed form."""

    method: str
    rtol: float
    omega: np.ndarray         #: (n_times, 10)
    error: float              #: max relative error against the closed form (module docstring)
    energy_drift: float       #: :math:`\max_t |E(t)/E(0) - 1|`
    casimir_drift: float      #: :math:`\max_t |c_2(t)/c_2(0) - 1|`
    wall_time: float          #: seconds, warm (a compiled run's first call is untimed: ``QuartetMotion.warmup_time``)


class QuartetMotion(NamedTuple):
    """Closed form against :data:`DEMO_RUNS` for the quartet body (:func:`compare_quartet_motion`)."""

    kappa: float
    axis: int
    t: np.ndarray
    exact: np.ndarray         #: closed form (n_times, 10), eqs. 96-110
    frequencies: np.ndarray   #: :math:`\Omega_1, \Omega_2` (after eq. 118)
    scale: float              #: :math:`\max|\omega_0|`, the normalisation of the errors
    runs: dict                #: method -> :class:`MotionRun`
    warmup_time: float        #: seconds of the untimed first call of the compiled runs (numba compiles or loads)


def _body(kappa: Any, axis: Any):
    from .classical.inertia import Inertia
    from .classical.rigid_body import RigidBody

    axis = _v.integer("axis", axis, minimum=1, maximum=5)
    return RigidBody(Inertia.quartet(kappa, axis=axis, N=5)), axis


def _motion_rates(kappa: float, body, omega0: np.ndarray, axis: int) -> tuple[float, float]:
    """``(rate, frequency)`` of :func:`quartet_motion_seconds`: the step control's bound on every angular
    velocity on the orbit (:func:`~.classical.solvers.step_control.rate_bound`) and the motion's fastest
    frequency (:func:`~.classical.quartet.quartet_frequencies`, after eq. 118). Both are of degree 1 in
    ``omega0`` (and the bound of degree 0 in the moments): computed from powers of two near 1 (exact), so
    that no square overflows."""
    from .classical.quartet import quartet_frequencies
    from .classical.solvers.step_control import rate_bound

    s = power_of_two_scale(float(np.max(np.abs(omega0))))
    moments = np.asarray(body.inertia.moments, dtype=float)
    moments = moments / power_of_two_scale(float(np.max(moments)))
    rate = float(rate_bound(moments, (omega0 / s * moments)[None, :])[0]) * s
    return rate, float(np.max(quartet_frequencies(kappa, omega0 / s, axis=axis))) * s


@_pricing.model("compare_quartet_motion", "a shorter t_end or a smaller omega0")
def _motion_cost(t_end: float, rate: float, frequency: float, n_times: float = 2001, speed: float = 1.0) -> tuple:
    """Cost model of :func:`compare_quartet_motion`: seconds of the two runs (:func:`quartet_motion_seconds`;
    ``speed``: max|omega0|)."""
    per_time = (_SECONDS_PER_TIME * float(speed) + _SECONDS_PER_TIME_FREQUENCY * float(frequency)
                + _SECONDS_PER_TIME_RATE * float(rate))
    return (_pricing.Cost(f"the quartet motion over t_end = {t_end:.6g} (fastest frequency {frequency:.3g}, "
                          f"rate bound {rate:.3g}, {int(n_times)} output times)",
                          _SECONDS_FIXED + _SECONDS_PER_OUTPUT * float(n_times) + per_time * float(t_end),
                          "max_seconds", "seconds"),)


class MotionCost(NamedTuple):
    """Estimate of :func:`compare_quartet_motion` (:func:`quartet_motion_seconds`)."""

    seconds: float    #: seconds of one core for the runs, warm kernels
    rate: float       #: the step control's bound on every angular velocity on the orbit (splitting8's steps)
    frequency: float  #: the motion's fastest frequency (eq. 118; DOP853's steps)


def _moving(name: str, body, omega0: Any) -> np.ndarray:
    """``omega0`` (10 components), refused unless it sets the body in motion with a kinetic energy within
    double precision (the drifts are relative to the energy and |L|^2 at t = 0: 0/0 at rest)."""
    omega0 = _v.components(name, omega0, 10)
    energy0 = float(body.energy(omega0))
    if not energy0 >= np.finfo(float).tiny:
        raise ValueError(f"{name} must set the body in motion with a kinetic energy within double precision: "
                         f"{name} = {_v.fmt(omega0)} gives {energy0:.3g} (relative drifts would be 0/0); "
                         f"use an {name} of ordinary size, e.g. the default")
    return omega0


def quartet_motion_seconds(kappa: Any, omega0: Any = DEMO_OMEGA, t_end: float = 200.0, *,
                           axis: int = 5, n_times: int = 2001) -> MotionCost:
    """Estimated seconds of one core for :func:`compare_quartet_motion` (warm kernels), without running it.

    ``a + b * n_times + t_end * (c max|omega0| + d * frequency + e * rate)``: DOP853's steps follow the motion's fastest
    frequency :math:`\\Omega_1` (eq. 118: at most ~ :math:`|\\Theta| |\\omega_0|`, whatever kappa), splitting8's
    the step control's bound on the angular velocities (``rate_bound``, ~ :math:`|\\kappa| |\\omega_0|` for large
    kappa); ``a ... e`` measured on the 2-core reference machine (``benchmarks/pricing.py``). The first call of a
    process adds the kernels' load (1-3 s).
    """
    _, _, _, sizes = _motion_request(kappa, omega0, t_end, axis, n_times)
    (cost,) = _pricing.estimate("compare_quartet_motion", **sizes)
    return MotionCost(cost.amount, sizes["rate"], sizes["frequency"])


def _motion_request(kappa: Any, omega0: Any, t_end: Any, axis: Any, n_times: Any) -> tuple:
    """``(body, axis, omega0, sizes)`` of a :func:`compare_quartet_motion` call, checked: ``sizes`` are those of its
    cost model (the one price of :func:`quartet_motion_seconds` and of the call itself)."""
    body, axis = _body(kappa, axis)
    omega0 = _moving("omega0", body, omega0)
    t_end = _v.positive("t_end", t_end)
    n_times = _v.integer("n_times", n_times, minimum=2, maximum=10**6)
    rate, frequency = _motion_rates(float(kappa), body, omega0, axis)
    return body, axis, omega0, dict(t_end=t_end, rate=rate, frequency=frequency, n_times=n_times,
                                    speed=float(np.max(np.abs(omega0))))


def compare_quartet_motion(kappa: Any, omega0: Any = DEMO_OMEGA, t_end: float = 200.0, *, axis: int = 5,
                           n_times: int = 2001, progress: bool | None = None) -> QuartetMotion:
    r"""The quartet body's closed form against the integrators of :data:`DEMO_RUNS`.

    Parameters
    ----------
    kappa : number or SymPy rational
        The quartet body (eqs. 84-85): :math:`I_{ij} = 1 + \kappa^2` on the planes with the
        distinguished ``axis``, 2 on the others.
    omega0 : array_like (10,)
        Initial angular velocity, plane order 12, 13, ..., 45 (default :data:`DEMO_OMEGA`).
    t_end : float
        The motion is compared on ``n_times`` equally spaced times in ``[0, t_end]``.
    axis : int
        The distinguished axis, 1..5.
    progress : bool or None, default None
        Progress bars of the runs (:func:`hyperrotor.simulate`; ``None``: on a terminal, for runs over about a
        second).

    Returns
    -------
    QuartetMotion
        The closed form, each run with its relative error, drifts and warm wall time.

    Raises
    ------
    hyperrotor.BudgetError
        When the estimate (:func:`quartet_motion_seconds`) exceeds ``hr.options["max_seconds"]``.
    """
    from .classical.quartet import quartet_frequencies, quartet_solution
    from .classical.simulate import simulate
    from .classical.solvers import FixedStepSolver, solver_for

    body, axis, omega0, sizes = _motion_request(kappa, omega0, t_end, axis, n_times)
    _pricing.check("compare_quartet_motion", **sizes)
    kappa, t_end, n_times = float(kappa), sizes["t_end"], sizes["n_times"]
    t = np.linspace(0.0, t_end, n_times)
    exact = quartet_solution(kappa, omega0, t, axis=axis)
    scale = float(np.max(np.abs(omega0)))
    # The compiled runs once untimed, as they are then timed: numba compiles (or loads from its disk cache) every
    # kernel the call takes, which depends on the call (the step control's, and the arithmetic its rtol asks for:
    # compensated storage at rtol 1e-12, generic kernels). A warm-up in plain arithmetic at a given step loaded
    # another kernel: the timed splitting8 run reported 14 s on a fresh installation, 0.11 s with numba's disk cache
    # (loading it), for a run of 0.016 s.
    start = time.perf_counter()
    for method, rtol in DEMO_RUNS:
        if isinstance(solver_for(method), FixedStepSolver):
            simulate(body, omega0, t, method=method, rtol=rtol)
    warmup = time.perf_counter() - start
    runs = {}
    for method, rtol in DEMO_RUNS:
        start = time.perf_counter()
        traj = simulate(body, omega0, t, method=method, rtol=rtol, progress=progress)
        wall = time.perf_counter() - start
        E = body.energy(traj.omega)
        c2 = np.sum(traj.L**2, axis=-1)
        runs[method] = MotionRun(method, rtol, traj.omega, float(np.max(np.abs(traj.omega - exact))) / scale,
                                 float(np.max(np.abs(E / E[0] - 1))), float(np.max(np.abs(c2 / c2[0] - 1))), wall)
    return QuartetMotion(kappa, axis, t, exact, np.asarray(quartet_frequencies(kappa, omega0, axis=axis), dtype=float),
                         scale, runs, warmup)


def save_quartet_motion(motion: QuartetMotion, path: Any, *, format: str | None = "png") -> str:
    """Picture of :func:`compare_quartet_motion`: the four oscillating planes and each run's relative error.

    Top: the components :math:`\\omega_{ij}` of the planes with the distinguished axis (the
    others are constant), closed form as lines, the order-8 splitting as dots; bottom: the
    relative error of each run (module docstring). Needs matplotlib; returns the path.
    """
    from .conventions import planes
    from .plotting import save_motion_comparison

    if not isinstance(motion, QuartetMotion):
        raise TypeError(f"motion must be a QuartetMotion (compare_quartet_motion), got {type(motion).__name__}")
    axis = motion.axis
    osc = [k for k, p in enumerate(planes(5)) if axis in p]
    labels = [f"$\\omega_{{{i}{j}}}$" for i, j in (planes(5)[k] for k in osc)]
    return save_motion_comparison(
        path, motion.t, motion.exact, {name: run.omega for name, run in motion.runs.items()}, components=osc,
        labels=labels, scale=motion.scale, marked=DEMO_RUNS[0][0],
        title=f"5D quartet body (kappa = {motion.kappa:.6g}, axis {axis}): "
              + (f"the four planes with axis {axis} oscillate" if motion.kappa ** 2 != 1  # (else all moments are 2)
                 else "equal moments, every omega constant"), format=format)
