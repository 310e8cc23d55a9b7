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

__all__ = ["DEMO_OMEGA", "DEMO_RUNS", "QuartetInvariants", "quartet_invariants", "MotionRun", "QuartetMotion",
           "compare_quartet_motion", "MotionCost", "quartet_motion_seconds", "save_quartet_motion"]

#: Sample angular velocity of the demo (plane order 12, 13, ..., 45).
DEMO_OMEGA = tuple(round(0.1 * k, 1) for k in range(1, 11))
#: The integrators compared with the closed form, with their tolerance.
DEMO_RUNS = (("splitting8", 1e-12), ("DOP853", 1e-10))
#: Seconds of the two runs per unit of simulated time and of the fastest rate, and their fixed part
#: (measured on the shared 2-core machine, warm kernels, one BLAS thread: t_end = 50-800 at rates 1.6,
#: 2.5 and 7.5 took 0.11-3.5 s of CPU, 0.2-5.5 s wall; DOP853 is ~90% of it), for
#: :func:`quartet_motion_seconds`. The splitting run is made twice, the first call untimed: it loads (or, on a
#: fresh installation, compiles) every kernel the call takes (``QuartetMotion.warmup_time``; the compile, 15-20 s
#: once per installation, is not priced: it does not grow with a size).
_SECONDS_PER_TIME = 7e-4
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


def _fastest_rate(body, omega0: np.ndarray) -> float:
    # the integrators' work grows with t_end times the fastest rate of the motion, at most
    # max|omega| * max(I) / min(I) (the Euler coefficients are moment differences over moments)
    moments = np.asarray(body.inertia.moments, dtype=float)
    return max(1.0, float(np.max(np.abs(omega0))) * float(np.max(moments) / np.min(moments)))


@_pricing.model("compare_quartet_motion", "a shorter t_end or a smaller omega0")
def _motion_cost(t_end: float, rate: float) -> tuple:
    """Cost model of :func:`compare_quartet_motion`: seconds of the two runs (:func:`quartet_motion_seconds`)."""
    return (_pricing.Cost(f"the quartet motion over t_end = {t_end:.6g} (fastest rate {rate:.3g})",
                          _SECONDS_FIXED + _SECONDS_PER_TIME * float(t_end) * float(rate), "max_seconds", "seconds"),)


class MotionCost(NamedTuple):
    """Estimate of :func:`compare_quartet_motion` (:func:`quartet_motion_seconds`)."""

    seconds: float  #: wall seconds of the runs, warm kernels
    rate: float     #: bound on the fastest rate of the motion, :math:`\max|\omega_0| \max I / \min I` (>= 1)


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
                           axis: int = 5) -> MotionCost:
    """Estimated wall seconds of :func:`compare_quartet_motion` (warm kernels), without running it.

    ``a + c * t_end * rate``: the rate is the fastest of the motion, bounded by
    :math:`\\max|\\omega_0| \\max I / \\min I`; ``a`` and ``c`` measured on the 2-core reference
    machine (``benchmarks/pricing.py``). The first call of a process adds the kernel's load (1-3 s).
    """
    body, axis = _body(kappa, axis)
    omega0 = _moving("omega0", body, omega0)
    t_end = _v.positive("t_end", t_end)
    rate = _fastest_rate(body, omega0)
    (cost,) = _pricing.estimate("compare_quartet_motion", t_end=t_end, rate=rate)
    return MotionCost(cost.amount, rate)


def compare_quartet_motion(kappa: Any, omega0: Any = DEMO_OMEGA, t_end: float = 200.0, *, axis: int = 5,
                           n_times: int = 2001, progress: bool | None = False) -> QuartetMotion:
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
    progress : bool or None
        Progress bars of the runs (:func:`hyperrotor.simulate`).

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

    body, axis = _body(kappa, axis)
    omega0 = _moving("omega0", body, omega0)
    t_end = _v.positive("t_end", t_end)
    n_times = _v.integer("n_times", n_times, minimum=2, maximum=10**6)
    _pricing.check("compare_quartet_motion", t_end=t_end, rate=_fastest_rate(body, omega0))
    kappa = float(kappa)
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
