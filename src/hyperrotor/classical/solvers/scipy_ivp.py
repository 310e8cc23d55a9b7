r"""scipy's adaptive integrators through :func:`scipy.integrate.solve_ivp` (``"DOP853"``, ``"RK45"``, ...).

``rtol`` here is scipy's *local* tolerance (per step), not a bound on the whole-run
error: the global error of these methods grows with the run length, typically to
10-100 times ``rtol`` over a few dozen periods (10-82x at rtol 1e-10: the measured factor is in the table
of ``benchmarks/work_precision_classical.py``). ``atol`` is ``simulate(atol=...)``
(units of omega, scalar or per plane) or by default set per component,
``atol_a = rtol * min(max|omega0|, |L0| / I_a)`` (error in :math:`\omega_a` below
``rtol max|omega0|`` and in :math:`L_a` below ``rtol |L0|``), and ``rtol`` for the attitude
entries. One ``solve_ivp`` call per ensemble member; events and dense output are scipy's
(``solve_ivp(events=...)``, ``dense_output=True``: the methods' own interpolants; the first
``Trajectory.sol`` call re-runs the members with ``dense_output=True``, which DOP853 pays
with 3 extra stages per step, so that runs without it stay as fast as before). The
right-hand side is ``body.rhs`` for a :class:`hyperrotor.RigidBody`, else an equivalent
sparse evaluation of the component equations. Any torque, also ``torque(t, omega)``.

The run is bounded: the right-hand side counts its evaluations and stops the run with
:class:`~.step_control.StepBudgetError` past ``max_steps``. scipy cannot estimate its steps
in advance, so the count is extrapolated instead: from :data:`EXTRAPOLATE_AFTER` evaluations
of a member on (and at every doubling), the evaluations so far times
(time span / time covered), plus the same for the members still to run, is the projected
cost; a run projected above ``max_steps`` is refused at once, naming the projection (a run of
1e300 radians is refused in well under a second instead of running for hours to the budget).

Inputs are scaled to angular velocities of order one first (see :mod:`.base`), so huge or
tiny scales neither overflow nor stall the step control. A member whose whole run is
shorter than :data:`STILL_FRACTION` of its fastest time scale (the bound
:math:`\|\dot\omega\|_\infty \le n\,(I_\text{max}/I_\text{min})\,\|\omega\|_\infty^2`, plus
:math:`N\|\omega\|_\infty` for the attitude and a constant torque's rate) does not move at
double precision: it is returned as the constant solution, exact to rounding, without
calling scipy (whose LSODA never returns for time spans near 1e-307). With ``events`` the
run always goes to scipy (an event function may depend on ``t`` alone).
"""
from __future__ import annotations

from typing import Any

import numpy as np

from hyperrotor import _validate
from hyperrotor._floats import power_of_two_scale
from hyperrotor._parallel import progress_bar
from hyperrotor.conventions import structure_constants, to_matrix

from .base import Problem, RunResult, Solver
from .driver import event_specs
from .chunks import refuse_steps
from .step_control import StepBudgetError

__all__ = ["ScipyIVP", "DOP853", "RK45", "RK23", "LSODA", "Radau", "BDF"]

#: solve_ivp warns below this rtol; requests are raised to it
RTOL_FLOOR = 100 * np.finfo(float).eps
#: the progress bar (``progress=True``) is updated every this many right-hand-side evaluations
PROGRESS_EVERY = 256
#: default ``max_step``: at most this many radians of the fastest initial rate per step. No
#: accurate step is longer; near a steady rotation (right-hand side ~ 0) scipy's first-step rule
#: would otherwise try steps of 1e6 radians and overflow, or (LSODA) fail to converge
MAX_STEP_RADIANS = 4.0
#: right-hand-side evaluations of a member before its cost is first extrapolated (then at every
#: doubling): by then the step of every method has settled (the first steps are chosen small)
EXTRAPOLATE_AFTER = 1000
#: a member whose run is shorter than this fraction of its fastest time scale is constant at
#: double precision (relative change below eps / 16)
STILL_FRACTION = np.finfo(float).eps / 16


class _SparseRHS:
    """dw/dt of the component equations from moments and structure constants (used when ``body`` has no ``rhs``)."""

    def __init__(self, moments: np.ndarray, N: int):
        C = structure_constants(N)
        b, c, a = np.nonzero(C)
        self.b, self.c, self.a = b, c, a
        self.coef = C[b, c, a].astype(float)
        n = moments.size
        A = np.zeros((b.size, n))
        A[np.arange(b.size), a] = 1.0
        self.A = A / moments[a][:, None]
        self.moments = moments

    def __call__(self, omega):
        L = omega * self.moments
        return (self.coef * omega[..., self.b] * L[..., self.c]) @ self.A


#: how to get a larger run, in every budget message of this module
_ASK_LESS = "ask for less (shorter t, larger rtol)"


class _MemberRHS:
    """The right-hand side of one member in its own scale ``rb`` (times ``tb``), as solve_ivp calls it.

    Besides dw/dt (and dT/dt) it counts the evaluations of the run in ``count`` (a one-element
    list shared by the members) against ``budget``, extrapolates the run's cost (module
    docstring; ``members_left`` still to run), advances the progress ``bar`` (members, fractions
    from the time covered) and answers inf for an overflowing trial step (scipy then rejects it).
    """

    def __init__(self, name, rhs, problem, b, rb, tau_b, tb, count, budget, members_left, bar):
        self.name, self.rhs, self.b, self.rb, self.tau_b = name, rhs, b, rb, tau_b
        self.moments, self.n, self.N = problem.moments, problem.n, problem.N
        self.torque, self.with_att = problem.torque, problem.with_attitude
        self.t0, self.span = tb[0], abs(tb[-1] - tb[0])
        self.count, self.budget, self.members_left, self.bar = count, budget, members_left, bar
        self.start = count[0]
        self.next = count[0] + EXTRAPOLATE_AFTER
        self.far = 0.0  # the largest |t - t0| evaluated so far

    def __call__(self, tt, y):
        self.count[0] += 1
        total = self.count[0]
        if total > self.budget:
            raise refuse_steps(f"scipy {self.name} (stopped at the budget, at member {self.b})", total, self.budget,
                               _ASK_LESS, unit="right-hand-side evaluations")
        self.far = max(self.far, abs(tt - self.t0))
        if total >= self.next:  # at EXTRAPOLATE_AFTER evaluations of this member, then at every doubling
            self.next = total + (total - self.start)
            _extrapolate(total, total - self.start, self.far, self.span, self.members_left, self.budget, self.name)
        if self.bar is not None and not total % PROGRESS_EVERY:
            self.bar.update(self.b + min(1.0, self.far / self.span) - self.bar.n)
        if not np.all(np.isfinite(y)):  # an overflowing trial step: infinite error, scipy shrinks the step
            return np.full(y.shape, np.inf)
        n, rb, moments = self.n, self.rb, self.moments
        w = y[:n]
        with np.errstate(over="ignore", invalid="ignore"):  # trial steps may overflow; scipy rejects them
            dw = np.asarray(self.rhs(w), dtype=float)
        if self.torque is not None:
            tau = (np.asarray(self.torque(tt / rb, w * rb), dtype=float) / (rb * rb)
                   if callable(self.torque) else self.tau_b)
            if tau.shape != (n,) or not np.all(np.isfinite(tau)):
                raise ValueError(f"torque(t, omega) must return {n} finite body-frame components, "
                                 f"got {_validate.fmt(tau)}")
            dw = dw + tau / moments
        if not self.with_att:
            return dw
        Tm = y[n:].reshape(self.N, self.N)
        return np.concatenate([dw, (to_matrix(w, convention="standard") @ Tm).ravel()])


class ScipyIVP(Solver):
    """A :func:`scipy.integrate.solve_ivp` method (see the module docstring); ``rtol`` is scipy's local tolerance.

    Options
    -------
    first_step, max_step : float or None
        passed to ``solve_ivp`` (user time units); ``max_step`` defaults to
        :data:`MAX_STEP_RADIANS` over the largest initial rate.
    """

    adaptive = True
    supports_torque = "any"
    scipy_method = ""
    option_docs = {"first_step": (None, "initial step of solve_ivp (user time units)"),
                   "max_step": (None, "largest step of solve_ivp (user time units); default: "
                                      "MAX_STEP_RADIANS over the largest initial rate")}

    def _check_options(self) -> None:
        for k in ("first_step", "max_step"):
            _validate.positive(k, self.options[k], allow_none=True)

    def run(self, problem: Problem, control: Any, *, events=None, max_steps: int, progress=None) -> RunResult:
        self.check(problem)
        if getattr(control, "rtol", None) is None:
            raise ValueError(f"dt fixes the step of the fixed-step methods; scipy method {self.name!r} takes rtol only")
        rtol = max(control.rtol, RTOL_FLOOR)
        body, moments, N, n = problem.body, problem.moments, problem.N, problem.n
        rhs = body.rhs if callable(getattr(body, "rhs", None)) else _SparseRHS(moments, N)
        t = problem.t
        B, K = problem.B, t.size
        with_att = problem.with_attitude
        torque = problem.torque
        s = problem.scale
        specs = event_specs(events)
        Lout = np.empty((B, K, n))
        Tout = np.empty((B, K, N, N)) if with_att else None
        nfev = [0]
        budget = int(max_steps)
        span = float(abs(t[-1] - t[0])) if K > 1 else 0.0
        tau_rate = 0.0 if torque is None or callable(torque) else np.abs(torque).max(axis=-1) / moments.min()
        ratio = float(moments.max() / moments.min())
        sols: list = []
        calls: list = []
        t_events = L_events = T_events = None
        K_done = K
        rbs = []
        bar = progress_bar(progress, B, "simulate", unit="member", leave=False)  # in members; fractions from the time covered
        if bar is not None:  # fractional members: show the percentage and the times only
            bar.bar_format = "{desc}: {percentage:3.0f}%|{bar}| {elapsed}<{remaining} (scipy " + self.name + ")"
            if progress:  # shown from the start (else after tqdm's delay, already in this format)
                bar.refresh()
        try:
            for b in range(B):
                if bar is not None:
                    bar.update(b - bar.n)
                # each member in its own scale (a power of two, exact): the same numbers alone or in an ensemble
                rb = power_of_two_scale(float(np.max(np.abs(problem.L0[b] / moments))))
                rbs.append(rb)
                tau_b = None if torque is None or callable(torque) else torque[b] / (rb * rb)

                w0 = problem.L0[b] / moments / rb
                y0 = w0 if not with_att else np.concatenate([w0, problem.T0[b].ravel()])
                wscale = float(np.max(np.abs(w0))) or 1.0
                Lscale = float(np.linalg.norm(problem.L0[b] / rb)) or wscale * float(moments.min())
                user_atol = getattr(control, "atol", None)  # scaled units of omega (simulate's atol=)
                atol = rtol * np.minimum(wscale, Lscale / moments) if user_atol is None else user_atol / rb
                if with_att:
                    atol = np.concatenate([atol, np.full(N * N, rtol)])
                Lout[b, 0] = problem.L0[b]
                if with_att:
                    Tout[b, 0] = problem.T0[b]
                rate = ratio * n * wscale + (N * wscale if with_att else 0.0)
                if torque is not None and not callable(torque):
                    rate += float(tau_rate[b]) / (rb * rb * wscale)
                if K == 1 or (not specs and span * rb * rate < STILL_FRACTION):  # no motion at double precision
                    Lout[b, 1:] = problem.L0[b]
                    if with_att:
                        Tout[b, 1:] = problem.T0[b]
                    sols.append(None)
                    calls.append(None)
                    continue
                ev = [_ScaledEvent(sp, s * rb, moments, n, problem.origin) for sp in specs] or None
                kw = {k: v * s * rb for k, v in self.options.items() if v is not None}
                kw.setdefault("max_step", MAX_STEP_RADIANS / wscale)
                tb = t * rb

                call = _MemberCall(self, rhs, problem, b, rb, tau_b, y0, rtol, atol, ev, kw, tb, budget)
                calls.append(call)
                sol = call(bool(specs), nfev, bar)
                if sol.status == -1:
                    raise RuntimeError(f"scipy {self.name} failed: {sol.message}")
                if not np.all(np.isfinite(sol.y)):
                    raise FloatingPointError(f"scipy {self.name}: the solution became non-finite")
                kb = sol.t.size
                K_done = kb
                Lout[b, :kb] = sol.y[:n].T * moments * rb
                if with_att:
                    Tout[b, :kb] = sol.y[n:].T.reshape(kb, N, N)
                sols.append(sol.sol)  # None unless events asked for scipy's dense output
                if specs:
                    t_events = [te / (s * rb) + problem.origin for te in sol.t_events]
                    # (an event that never fired: scipy's states are 1-D and empty; as (0, state size) here)
                    y_events = [ye.reshape(-1, sol.y.shape[0]) for ye in sol.y_events]
                    L_events = [ye[:, :n] * moments * (s * rb) for ye in y_events]
                    T_events = [ye[:, n:].reshape(-1, N, N) for ye in y_events] if with_att else None
        finally:
            if bar is not None:
                bar.close()

        stats = dict(steps=None, nfev=int(nfev[0]), dt=None, rtol_used=rtol,
                     status="terminated by event" if K_done < K else "finished")
        return RunResult(L=Lout[:, :K_done], T=None if Tout is None else Tout[:, :K_done], t=t[:K_done], stats=stats,
                         dense=_ScipyDense(problem, K_done, calls, sols, rbs), t_events=t_events, L_events=L_events,
                         T_events=T_events)


class _MemberCall:
    """One member's ``solve_ivp`` call, repeatable (the dense output re-runs it with interpolants);
    a plain object, so that a :class:`~hyperrotor.Trajectory` pickles."""

    def __init__(self, solver, rhs, problem, b, rb, tau_b, y0, rtol, atol, ev, kw, tb, budget):
        self.name, self.scipy_method = solver.name, solver.scipy_method
        self.rhs, self.problem, self.b, self.rb, self.tau_b = rhs, problem, b, rb, tau_b
        self.y0, self.rtol, self.atol, self.ev, self.kw, self.tb, self.budget = y0, rtol, atol, ev, kw, tb, budget

    def __call__(self, dense, count, bar):
        from scipy.integrate import solve_ivp

        tb = self.tb
        f = _MemberRHS(self.name, self.rhs, self.problem, self.b, self.rb, self.tau_b, tb, count, self.budget,
                       self.problem.B - self.b - 1, bar)
        # a trial step may overflow: the right-hand side answers inf, scipy's error norm is
        # inf and the step is rejected (the accepted solution is checked for finiteness by run)
        with np.errstate(over="ignore", invalid="ignore"):
            return solve_ivp(f, (tb[0], tb[-1]), self.y0, method=self.scipy_method, t_eval=tb, rtol=self.rtol,
                             atol=self.atol, events=self.ev, dense_output=dense, **self.kw)


class _ScipyDense:
    """Dense output of a scipy run: the members' interpolants (built on the first request)."""

    def __init__(self, problem, K_done, calls, sols, rbs):
        self.problem, self.K_done, self.calls, self.sols, self.rbs = problem, K_done, calls, sols, rbs

    def __call__(self, tq):
        problem, K_done, calls, sols, rbs = self.problem, self.K_done, self.calls, self.sols, self.rbs
        t, moments, n, N, B = problem.t, problem.moments, problem.n, problem.N, problem.B
        with_att = problem.with_attitude
        tq = np.asarray(tq, dtype=float)
        lo, hi = sorted((t[0], t[K_done - 1]))
        bad = np.flatnonzero((tq < lo) | (tq > hi))
        if bad.size:
            raise ValueError(f"dense output is defined on the run's time span [{problem.user_time(lo):g}, "
                             f"{problem.user_time(hi):g}] only; got t = {problem.user_time(tq[bad[0]]):g}")
        L = np.empty((B, tq.size, n))
        T = np.empty((B, tq.size, N, N)) if with_att else None
        for b in range(B):
            if calls[b] is None:  # a single output time, or no motion: the initial state
                y0b = np.concatenate([problem.L0[b] / moments] + ([problem.T0[b].ravel()] if with_att else []))
                y = np.repeat(y0b[:, None], tq.size, axis=1)
            else:
                if sols[b] is None:  # first dense request: re-run this member with scipy's interpolants
                    sols[b] = calls[b](True, [0], None).sol
                y = sols[b](tq * rbs[b])
                y = np.concatenate([y[:n] * rbs[b], y[n:]])
            L[b] = y[:n].T * moments
            if with_att:
                T[b] = y[n:].T.reshape(tq.size, N, N)
        return L, T


def _extrapolate(total: int, member: int, covered: float, span: float, members_left: int, budget: int,
                 name: str) -> None:
    """Refuse a run whose projected right-hand-side evaluations exceed ``budget`` (see the module docstring)."""
    if covered <= 0.0:  # nothing covered after EXTRAPOLATE_AFTER evaluations: the method is stuck
        raise StepBudgetError(
            f"scipy {name} made no progress in time after {member} right-hand-side evaluations (its step "
            f"underflows the time span); rescale the problem or use a fixed-step method"
        )
    per_member = member * span / covered
    projected = total - member + per_member * (1 + members_left)
    if projected > budget:
        raise refuse_steps(f"scipy {name} for this run (extrapolated from {member} evaluations covering "
                           f"{covered / span:.3g} of the time span)", projected, budget, _ASK_LESS,
                           unit="right-hand-side evaluations")


class _ScaledEvent:
    """An event function of ``simulate`` as solve_ivp calls it (one member's scaled state)."""

    def __init__(self, spec, s, moments, n, origin=0.0):
        self.spec, self.s, self.moments, self.n, self.origin = spec, s, moments, n, origin
        self.terminal = spec.max_count is not None and (spec.max_count if spec.max_count > 1 else True)
        self.direction = spec.direction

    def __call__(self, tt, y):
        return self.spec.value(tt / self.s + self.origin, y[:self.n] * self.moments * self.s)


class DOP853(ScipyIVP):
    """Dormand-Prince 8(5,3) explicit Runge-Kutta (scipy), order 8."""

    name = "DOP853"
    scipy_method = "DOP853"
    order = 8


class RK45(ScipyIVP):
    """Dormand-Prince 5(4) explicit Runge-Kutta (scipy), order 5."""

    name = "RK45"
    scipy_method = "RK45"
    order = 5


class RK23(ScipyIVP):
    """Bogacki-Shampine 3(2) explicit Runge-Kutta (scipy), order 3."""

    name = "RK23"
    scipy_method = "RK23"
    order = 3


class LSODA(ScipyIVP):
    """Adams / BDF with automatic stiffness detection (scipy, ODEPACK); variable order."""

    name = "LSODA"
    scipy_method = "LSODA"
    order = None


class Radau(ScipyIVP):
    """Implicit Radau IIA (scipy), order 5; for stiff moment ratios."""

    name = "Radau"
    scipy_method = "Radau"
    order = 5


class BDF(ScipyIVP):
    """Implicit backward differentiation formulas (scipy), variable order 1-5; for stiff moment ratios."""

    name = "BDF"
    scipy_method = "BDF"
    order = None
