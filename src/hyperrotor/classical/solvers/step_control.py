r"""Step control of the fixed-step methods: a given ``dt`` or an error target ``rtol``.

:class:`FixedStep` takes the largest step ``dt``; :class:`ErrorTarget` chooses the step so
that the whole-run error stays within ``rtol``:

.. math:: \max_t \|L(t) - L_\text{exact}(t)\|_\infty \le \mathrm{rtol}\,\max_t \|L(t)\|_\infty,

and the same for :math:`\omega` (they differ for stiff moment ratios, where the heavy
planes have small rates but carry most of ``L``). Either way each output interval is
split into ``ceil(gap / h)`` equal steps, so output times are hit exactly.

How :class:`ErrorTarget` chooses and checks the step
----------------------------------------------------
The job is split as in scipy's ``solve_ivp`` (``select_initial_step`` guesses, the error
estimate of every step decides) and diffrax (a controller proposes, the run's own error
estimate accepts or rejects), but for the *global* error of a fixed-step run:

1. *Rate bound* (:func:`rate_bound`). :math:`\omega_\text{max} = \max_a \min(|L|, \sqrt{2EI_a})/I_a`
   bounds every rate reachable on the orbit (from the Casimir :math:`|L|^2` and the energy ``E``),
   raised to the linearised frequencies :math:`|\omega_c|\sqrt{|(I_c-I_a)(I_c-I_b)|/(I_aI_b)}` of
   every coupled triple of planes (larger than the rates only for moments violating the
   triangle inequalities, i.e. stiff problems) and, with a torque, to the rate it can build up.
2. *Probe on a leading window* (a guess, costing a small fraction of the run). On
   :math:`P = \min(\text{run}, ` :data:`PROBE_TURNS` :math:`/\omega_\text{max})`, for up to
   :data:`PROBE_MEMBERS` ensemble members (the fastest), Richardson's estimate
   :math:`e(h) = \max|y_h - y_{2h}| / (2^p - 1)` (the same members at twice the step: 1.5x the
   work of the steps :math:`h`) from step :math:`h = 1/\omega_\text{max}`,
   refined (x1/4) while not asymptotic (:math:`e > ` :data:`ASYMPTOTIC`) and enlarged (x4) while
   at round-off. The error is carried to the end of the run with the growth seen inside the
   window (:func:`growth_to_end`: like :math:`t` on a regular orbit, Hairer, Lubich & Wanner,
   *Geometric Numerical Integration*, ch. X; like :math:`t^a`, :math:`a \le` :data:`PROBE_MAX_POWER`,
   when the window shows faster growth, e.g. a chaotic orbit), which gives the step :math:`h^*`
   for the target ``SAFETY * rtol``.
3. *Budget.* All planned work (probes, run, check) above ``max_steps`` is refused here,
   before the run starts (:class:`~.chunks.Work`).
4. *Check inside the run* (:class:`RichardsonCheck`, costing :math:`1/c + 1/(c c_2)` of the run for
   up to :data:`PROBE_MEMBERS` members). Beside the run at :math:`h^*` two companion runs of the
   same members advance with steps :math:`c` and :math:`c c_2` times longer
   (:math:`2 \le c \le` :data:`COMPANION_RATIO`, as large as keeps the first companion's error below
   :data:`COMPANION_ASYMPTOTIC`; :math:`2 \le c_2 \le c`, the second's below
   :data:`SECOND_COMPANION_ASYMPTOTIC`) between :data:`CHECK_SAMPLES` sample points of the run.
   The three runs give the observed order :math:`q \le p` (:func:`observed_order`, from
   :math:`|y_{ch} - y_{cc_2h}| / |y_h - y_{ch}| = c^q (c_2^q - 1)/(c^q - 1)`: stiff
   problems, steps far outside the asymptotic regime show :math:`q < p`), and at every sample
   :math:`e \approx |y_{h^*} - y_{ch^*}| / (c^q - 1)` estimates the run's own error (with
   :math:`c` the smallest ratio of companion to run step over the samples, so the estimate errs
   on the safe side; :math:`q < 1/2`: the difference itself). A run too short for longer
   companion steps is checked against companions at half and quarter steps instead. The run
   is accepted when the estimate stays within
   ``ACCEPT * rtol``. It is stopped at the first sample where the estimate exceeds that, or
   (from :data:`PROJECT_AFTER` of the run on) where its linear projection to the end exceeds it
   :data:`PROJECT_MARGIN`-fold, and re-run at
   :math:`h \leftarrow 0.9\,h\,(\mathrm{SAFETY\cdot rtol}/e_\text{end})^{1/p}`. The samples
   also show how the error grows: linearly on regular orbits, like :math:`e^{\lambda t}` on
   chaotic ones (GNI ch. X; the envelope of the estimates over the last two doublings of the
   time done), which the messages below name.
   Richardson's differences do not see round-off: an accepted run whose differences show the
   orbit amplifying it towards ``rtol`` (a chaotic orbit, plain arithmetic) is repeated at the
   same step in compensated storage (``RichardsonCheck._check_roundoff``).
5. *Unreachable accuracy.* The re-run's step is priced first: above the budget the call
   stops with :class:`~.base.StepBudgetError` naming the estimated error, its growth
   :math:`e^{\lambda T}` when the samples grow exponentially (a chaotic orbit), and the
   accuracy reachable within the budget; when :data:`MAX_RETRIES` re-runs do not meet ``rtol``
   (round-off, or exponential growth that outruns the order of the method) the call stops with
   :class:`UnreachableAccuracyError` naming the reachable accuracy, instead of grinding or
   returning a result that misses the bound.

The timed probes also give the cost per step: a run estimated to take longer than
``options["slow_run_warning_seconds"]`` gives a ``UserWarning`` before it starts
(:func:`run_estimate` prices a call without running it).
"""
from __future__ import annotations

import itertools
import math
import warnings
from functools import lru_cache
from typing import Any

import numpy as np

from hyperrotor import _validate
from hyperrotor._options import options

from .base import Problem, StepBudgetError, nsub_for, step_lengths
from .chunks import Work, advance_chunked, cost_key, seconds_per_flow, step_times

__all__ = ["FixedStep", "ErrorTarget", "StepBudgetError", "RichardsonCheck", "CheckFailed",
           "UnreachableAccuracyError", "rate_bound", "observed_order", "growth_to_end"]

_EPS = float(np.finfo(float).eps)
#: the error target used for the step: rtol times this (margin for the asymptotic model)
SAFETY = 0.5
#: the check accepts a run whose estimated error stays within rtol times this
ACCEPT = 0.8
#: Richardson estimates above this are outside the asymptotic regime (the step is refined)
ASYMPTOTIC = 1e-2
#: the companion's own error is kept below this (it chooses the ratio c of the check)
COMPANION_ASYMPTOTIC = 1e-3
#: largest ratio c of companion to run step (cost of the check: 1/c + 1/(c c2) of the run for the checked members)
COMPANION_RATIO = 4.0
#: the second companion's step is c2 >= 2 times the first's, as long as its own error stays below this
SECOND_COMPANION_ASYMPTOTIC = 3e-2
#: length of the probe interval in turns of the fastest rate (20 radians: a few periods)
PROBE_TURNS = 20.0
#: ensemble members probed and checked (the fastest ones): the step is one for all members
PROBE_MEMBERS = 8
#: the probe extrapolates its error to the end of the run like t^a, 1 <= a <= this (the steady growth it sees)
PROBE_MAX_POWER = 4.0
#: no extrapolation beyond this factor of the probed step (the error model is asymptotic in h)
MAX_STEP_GROWTH = 8.0
#: round-off of plain arithmetic per run: this times eps sqrt(flows) times the orbit's amplification ...
ROUNDOFF_FACTOR = 4.0
#: ... above this share of the accepted error switches the run to compensated storage
ROUNDOFF_SHARE = 0.25
#: the observed order comes from samples where the second companion's difference is below this
LINEAR_REGIME = 1e-3
#: sample points of the check (the error can peak between output times)
CHECK_SAMPLES = 64
#: the check projects the error to the end of the run once this fraction of it is done ...
PROJECT_AFTER = 0.125
#: ... and stops the run when the projection exceeds the accepted error this many times
PROJECT_MARGIN = 4.0
#: an error envelope growing this much over the second half of the samples seen is faster than linear
GROWTH_RATIO = 8.0
#: re-runs at a shorter step before the call gives up with UnreachableAccuracyError
MAX_RETRIES = 3


def observed_order(rho: float, r: float, r2: float, p: float) -> float:
    r"""The order :math:`q \in [0, p]` with :math:`r^q (r_2^q - 1)/(r^q - 1) = \rho` (ratio of the
    differences of three runs at steps :math:`h`, :math:`rh`, :math:`r r_2 h`, errors :math:`C h^q`).

    The left side increases with :math:`q` (from :math:`\ln r_2/\ln r` at 0); below its value at
    :math:`q = 1/2` the answer is 0 (not asymptotic), above its value at ``p`` it is ``p``; bisection
    in between. ``r == r2`` gives :math:`\log\rho / \log r`.
    """
    if not rho > 0.0 or r <= 1.0 or r2 <= 1.0:
        return 0.0

    def f(q):
        return r ** q * (r2 ** q - 1.0) / (r ** q - 1.0)

    if rho < f(0.5):
        return 0.0
    if rho >= f(p):
        return float(p)
    lo, hi = 0.5, float(p)
    for _ in range(40):  # |hi - lo| < 1e-11
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < rho else (lo, mid)
    return 0.5 * (lo + hi)


class UnreachableAccuracyError(ValueError):
    """``rtol`` cannot be met at a reasonable cost: the error grows exponentially (a chaotic orbit)
    or sits at round-off. The message names the estimated growth and the reachable accuracy."""


class CheckFailed(Exception):
    """Raised by :class:`RichardsonCheck` inside a run: re-run at step ``h`` (scaled units)."""

    def __init__(self, h: float, why: str):
        super().__init__(why)
        self.h = h
        self.why = why


def rate_bound(moments: np.ndarray, L0: np.ndarray) -> np.ndarray:
    r"""Per row of ``L0`` (rows, n): :math:`\max_a \min(|L|, \sqrt{2EI_a})/I_a`, a bound on every
    angular velocity on the orbit (from the Casimir :math:`|L|^2` and the energy)."""
    C = np.sqrt(np.sum(L0 * L0, axis=1, keepdims=True))
    E2 = np.sum(L0 * L0 / moments, axis=1, keepdims=True)
    W = np.minimum(C, np.sqrt(E2 * moments)) / moments
    return W.max(axis=1) if W.size else np.zeros(L0.shape[0])


def _orbit_rates(problem: Problem) -> np.ndarray:
    """Per-member bound on the rates reachable on the orbit (module docstring, step 1)."""
    L0, m = problem.L0, problem.moments
    wmax_b = rate_bound(m, L0)
    tc, ta, tb = _triples(problem.N)
    if tc.size and L0.size:
        C = np.sqrt(np.sum(L0 * L0, axis=1, keepdims=True))
        E2 = np.sum(L0 * L0 / m, axis=1, keepdims=True)
        W = np.minimum(C, np.sqrt(E2 * m)) / m  # (B, n)
        Ic, Ia, Ib = m[tc], m[ta], m[tb]
        lam = W[:, tc] * np.sqrt(np.abs((Ic - Ia) * (Ic - Ib)) / (Ia * Ib))
        wmax_b = np.maximum(wmax_b, lam.max(axis=1))
    if problem.kick:
        tq = float(np.max(np.abs(problem.torque) / m))
        wmax_b = np.maximum(wmax_b, max(tq * problem.span, tq ** 0.5))
    return wmax_b


@lru_cache(maxsize=32)
def _triples(N: int):
    """Plane indices (c, a, b) of every coupled triple {ij, ik, jk}, each plane in turn as c (cached)."""
    from hyperrotor.conventions import planes

    idx = {p: k for k, p in enumerate(planes(N))}
    out = []
    for i in range(1, N + 1):
        for j in range(i + 1, N + 1):
            for k in range(j + 1, N + 1):
                t3 = (idx[(i, j)], idx[(i, k)], idx[(j, k)])
                out += [(t3[0], t3[1], t3[2]), (t3[1], t3[0], t3[2]), (t3[2], t3[0], t3[1])]
    arr = np.array(out, dtype=np.int64).reshape(-1, 3)
    cols = tuple(np.ascontiguousarray(arr[:, i]) for i in range(3))
    for c in cols:
        c.setflags(write=False)
    return cols


def growth_to_end(envelope: list, floor: float, ratio: float) -> float:
    r"""Factor by which the error of the probe window grows by the end of the run (``ratio``: run / window).

    Linear growth (a regular orbit, GNI ch. X) gives ``ratio``. A faster growth seen inside the
    window is extrapolated as :math:`t^a`, :math:`1 \le a \le` :data:`PROBE_MAX_POWER`, with
    :math:`a` the smaller power of the two halves of the window's last three quarters (the
    envelope ``(fraction of the window, estimate)`` at :math:`P/4, P/2, P`): growth must be
    steady to count (a chaotic orbit, a separatrix passage), an error that oscillates up and down
    does not. Estimates at round-off (``floor``) say nothing: linear. The check inside the run
    decides anyway; this only makes a re-run rarer.
    """
    if ratio <= 1.0:
        return 1.0
    a = PROBE_MAX_POWER
    if len(envelope) < 3:
        a = 1.0
    for (t0, e0), (t1, e1) in itertools.pairwise(envelope):
        if e0 <= 2.0 * floor or e1 <= e0 or t1 <= t0:
            a = 1.0
            break
        a = min(a, math.log(e1 / e0) / math.log(t1 / t0))
    return math.exp(min(max(1.0, a) * math.log(ratio), 700.0))  # (no overflow for absurd spans)


class FixedStep:
    """Largest step ``dt`` (in the user's time units)."""

    rtol = None

    def __init__(self, dt: Any):
        self.dt = _validate.positive("dt", dt)

    def first_step(self, solver, problem: Problem, work: Work, bar=None) -> float:
        return self.dt * problem.scale  # (the driver checks the budget once it has counted the steps)

    def checker(self, solver, problem: Problem, nsub: np.ndarray, work: Work, bar=None):
        return None

    verified_step = first_step

    def announce(self, solver, problem: Problem, h: float) -> None:
        """Nothing: a given step is the caller's choice."""

    def __repr__(self) -> str:
        return f"FixedStep(dt={self.dt!r})"


def _relative_difference(La: np.ndarray, Lb: np.ndarray, moments: np.ndarray, Lmax: np.ndarray,
                         Wmax: np.ndarray) -> np.ndarray:
    """Per sample (axis 1): max over members of max(|dL|/max|L|, |dW|/max|W|) (members on axis 0)."""
    d = np.abs(La - Lb)
    dL = d.max(axis=2) / Lmax[:, None]
    dW = (d / moments).max(axis=2) / Wmax[:, None]
    return np.maximum(dL, dW).max(axis=0)


class ErrorTarget:
    """Step from a whole-run error target ``rtol``: a probe guesses, the run's own check decides
    (see the module docstring)."""

    def __init__(self, rtol: Any):
        self.rtol = _validate.positive("rtol", rtol)
        self.seconds_per_step: float | None = None
        self.retries = 0
        self.history: list = []  # (h, estimated error) of every checked run (partial ones too)
        self.last_growth = 0.0
        self.probe_note = ""  # the error growth the probe saw, when faster than PROBE_MAX_POWER allows
        self.roundoff_amplified = False  # the check saw round-off amplified towards rtol: compensated storage

    def __repr__(self) -> str:
        return f"ErrorTarget(rtol={self.rtol!r})"

    def _rates(self, problem: Problem) -> tuple:
        """``(rate bound per member, the checked members)`` of ``problem`` (computed once per problem)."""
        cached = getattr(self, "_rates_of", None)
        if cached is None or cached[0] is not problem:
            wmax_b = _orbit_rates(problem)
            members = np.sort(np.argsort(wmax_b)[::-1][: min(PROBE_MEMBERS, problem.B)])
            cached = self._rates_of = (problem, wmax_b, members)
        return cached[1:]

    def _members(self, problem: Problem) -> np.ndarray:
        return self._rates(problem)[1]

    def first_step(self, solver, problem: Problem, work: Work, bar=None) -> float:
        """The probe (module docstring, steps 1-3): a step for ``SAFETY * rtol`` from a leading window
        (``bar``: a progress bar the probe's steps advance)."""
        span = problem.span
        B = problem.B
        self.retries = 0
        self.history = []
        self.probe_note = ""
        self.roundoff_amplified = False
        if B == 0 or span == 0.0:
            return max(span, 1.0)
        wmax_b, sel = self._rates(problem)
        wmax = float(wmax_b.max())
        if wmax == 0.0 or solver.flows_per_step(problem) == 0:
            return span  # nothing moves
        p = solver.order
        target = SAFETY * self.rtol
        L0s = problem.L0[sel]
        Ms = problem.moments
        direction = 1.0 if problem.t[-1] >= problem.t[0] else -1.0

        def richardson(Pv, m, samples):
            """Error estimate (relative) of ~m steps over [0, Pv] from the same members at twice the
            step (1.5x the work of the m steps); ``(None, h)`` if a run failed."""
            k = max(1, min(m // 2, samples))
            ms = 2 * max(1, int(math.ceil(m / (2 * k))))
            tg = direction * np.linspace(0.0, Pv, k + 1) + problem.t[0]
            work.refuse(1.5 * k * ms * len(sel), lambda: f"the step control's probe of {1.5 * k * ms:.0f} steps")
            try:
                y1 = advance_chunked(solver, problem, L0s, tg, np.full(k, ms), members=sel, work=work, bar=bar)[0]
                y2 = advance_chunked(solver, problem, L0s, tg, np.full(k, ms // 2), members=sel, work=work,
                                     bar=bar)[0]
            except (RuntimeError, FloatingPointError):  # no implicit step / an overflow at this h
                return None, Pv / (k * ms)
            Lmax = np.maximum(np.abs(y1).max(axis=(1, 2)), 1e-300)
            Wmax = np.maximum(np.abs(y1 / Ms).max(axis=(1, 2)), 1e-300)
            d = _relative_difference(y1, y2, Ms, Lmax, Wmax)  # per sample
            # the estimate's envelope at (about) half the window and at its end (d[i]: at grid point i)
            env = np.maximum.accumulate(d) / (2.0 ** p - 1.0)
            samples_e[:] = [(i / k, float(env[i])) for i in (k // 4, k // 2, k) if i > 0]
            return float(env[-1]), Pv / (k * ms)

        samples_e = []

        P = min(span, PROBE_TURNS / wmax)
        h = min(P, 1.0 / wmax)
        est = None
        floor = 0.0
        for _ in range(24):
            m = max(1, int(math.ceil(P / h - 1e-9)))
            if m > 200_000:
                break
            err, h = richardson(P, m, 16)
            if err is None or not np.isfinite(err) or err > ASYMPTOTIC:
                h /= 4.0
                continue
            floor = 1e3 * _EPS * math.sqrt(2 * m * solver.flows_per_step(problem))
            est = (h, err, P)
            if err < floor:  # round-off level: try longer steps / a longer probe
                if m > 1:
                    h *= 4.0
                elif P < span:
                    P = h = min(4.0 * P, span)
                else:
                    break
                continue
            break
        if est is None:
            h_star = min(P, 0.01 / wmax)
        else:
            h, err, P = est
            growth = growth_to_end(samples_e, floor, span / P)
            on_run = max(err, 1e3 * _EPS) * growth
            h_star = min(MAX_STEP_GROWTH * h, 0.8 * h * (target / on_run) ** (1.0 / p))
            if (len(samples_e) == 3 and span > P
                    and math.log(growth) >= min(PROBE_MAX_POWER * math.log(span / P), 700.0) * (1.0 - 1e-12)):
                (t1, e1), (t2, e2) = samples_e[1:]  # faster than t^4: name the exponential rate it shows
                lam = math.log(e2 / e1) / ((t2 - t1) * P)
                self.probe_note = (
                    f"; the probe's error grows faster than t^{PROBE_MAX_POWER:g}, like exp(lambda t) with lambda ~ "
                    f"{lam * problem.scale:.3g} (a chaotic orbit? exp(lambda T) ~ "
                    f"{math.exp(min(lam * span, 700.0)):.3g} over the run)")
        return h_star

    def refusal_note(self, needed: float, budget: float, order: int) -> str:
        """What a refusal before the run adds: the growth the probe saw (if fast) and the accuracy
        reachable within ``budget`` steps (error ~ h^order, h ~ 1/steps)."""
        if self.probe_note:
            return self.probe_note + "; no accuracy can be promised within a budget before such a run"
        reach = min(1.0, SAFETY * self.rtol * (needed / max(budget, 1.0)) ** order)
        return (f"; reachable accuracy about {reach:.2g} within the budget (the probe's estimate from a leading "
                f"window; faster error growth later, e.g. on a chaotic orbit, makes it worse)")

    def announce(self, solver, problem: Problem, h: float) -> None:
        """The slow-run warning (once the budget is checked), from the cost per flow learned by the probes."""
        key = cost_key(solver, problem)
        spf = seconds_per_flow(key)
        steps = float(nsub_for(problem.t, h).sum())
        self.seconds_per_step = spf * solver.flows_per_step(problem)
        seconds = self.seconds_per_step * steps * problem.B * (1.0 + 1.0 / COMPANION_RATIO)
        limit = options["slow_run_warning_seconds"]
        if seconds > limit:
            warnings.warn(
                f"simulate: {solver.name!r} at rtol = {self.rtol:g} needs about {seconds:.3g} s "
                f"({steps:.3g} steps per trajectory)"
                + (", a splitting of higher order reaches this accuracy much sooner" if solver.order < 8 else "")
                + f" (options['slow_run_warning_seconds'] = {_validate.fmt(limit)})",
                UserWarning, stacklevel=5,
            )

    def checker(self, solver, problem: Problem, nsub: np.ndarray, work: Work, bar=None) -> "RichardsonCheck | None":
        if problem.B == 0 or not nsub.size or int(nsub.sum()) == 0 or solver.flows_per_step(problem) == 0:
            return None
        return RichardsonCheck(solver, problem, nsub, self, self._members(problem), work, bar)

    def next_step(self, failure: CheckFailed, solver, problem: Problem, work: Work) -> float:
        """The step of the re-run after a failed check, or an error when the target is out of reach."""
        self.retries += 1
        if self.retries > MAX_RETRIES:
            best = min(e for _, e in self.history) if self.history else None
            raise UnreachableAccuracyError(
                f"simulate: rtol = {self.rtol:g} was not reached after {MAX_RETRIES} re-runs at shorter steps "
                f"({failure.why}); the error does not follow the method's order here (round-off, or an orbit "
                f"whose error grows exponentially); reachable accuracy about "
                f"{best if best is not None else float('nan'):.2g} at reasonable cost. Ask for a larger rtol "
                f"or a shorter run")
        return failure.h

    def verified_step(self, solver, problem: Problem, work: Work) -> float:
        """The step, checked before any member runs (ensembles run member by member): the probe,
        then the checked members run on their own with the companion (no output kept)."""
        h = self.first_step(solver, problem, work)
        t = problem.t
        while True:
            nsub = nsub_for(t, h)
            if hasattr(solver, "set_accuracy"):  # the arithmetic the members will run in
                solver.set_accuracy(problem, self.rtol, int(nsub.sum()), roundoff_amplified=self.roundoff_amplified)
            check = self.checker(solver, problem, nsub, work)
            if check is None:
                return h
            work.refuse(2 * check.planned_steps, "the step control's check")
            try:
                check.run_alone()
                return h
            except CheckFailed as failure:
                h = self.next_step(failure, solver, problem, work)


class RichardsonCheck:
    """The a-posteriori check of one run (module docstring, steps 4-5).

    ``marks`` are global step indices of the run (sample points); the driver keeps the run's
    states there and calls :meth:`update` with them as the run reaches them; the companion of
    the checked ``members`` follows, and :class:`CheckFailed` stops the run when the estimate
    (or its projection) is over the target.
    """

    def __init__(self, solver, problem: Problem, nsub: np.ndarray, control: ErrorTarget, members: np.ndarray,
                 work: Work, bar=None):
        self.solver, self.problem, self.control, self.members, self.work, self.bar = (
            solver, problem, control, members, work, bar)
        t = problem.t
        p = solver.order
        self.p = p
        self.nsub = nsub
        self.cs = cs = np.concatenate([[0], np.cumsum(nsub)])
        steps = int(cs[-1])
        self.steps = steps
        hs = step_lengths(t, nsub)
        self.h = float(np.abs(hs).max())
        # the companion's ratio: as long as its own error stays asymptotic
        c = (COMPANION_ASYMPTOTIC / (SAFETY * control.rtol)) ** (1.0 / p)
        c = float(min(COMPANION_RATIO, max(2.0, c), max(2.0, math.sqrt(steps / 8.0))))  # short runs: smaller c
        # the second companion's ratio to the first: 2 or more, while its error stays near-asymptotic
        c2 = (SECOND_COMPANION_ASYMPTOTIC / (SAFETY * control.rtol * c ** p)) ** (1.0 / p)
        c2 = float(min(c, max(2.0, c2)))
        finer = steps < 32  # a very short run: the companions take half and quarter steps instead
        if finer:
            spacing = max(1, int(math.ceil(steps / CHECK_SAMPLES)))
        else:
            spacing = max(int(math.ceil(2 * c * c2)), int(math.ceil(steps / CHECK_SAMPLES)))
        marks = np.arange(spacing, steps, spacing, dtype=np.int64)
        if marks.size and steps - marks[-1] < spacing // 2:
            marks = marks[:-1]
        self.marks = marks = np.append(marks, steps)
        seg = np.diff(np.concatenate([[0], marks]))
        if finer:
            self.nc, self.nc2 = seg * 2, seg * 4
        else:
            self.nc = np.maximum(1, np.floor(seg / c).astype(np.int64))
            self.nc2 = np.maximum(1, np.floor(self.nc / c2).astype(np.int64))
        self.tm = step_times(t, cs, nsub, marks)
        self.grid = np.concatenate([[t[0]], self.tm])
        lengths = np.abs(np.diff(self.grid))
        H, H2 = lengths / self.nc, lengths / self.nc2
        # largest and smallest run step in each segment (the run's step differs between output intervals)
        first = np.searchsorted(cs, np.concatenate([[0], marks[:-1]]), side="right") - 1
        last = np.searchsorted(cs, marks - 1, side="right") - 1
        ah = np.abs(hs)
        if np.all(first == last):  # every segment inside one output interval (long intervals)
            hmax = hmin = ah[first]
        else:
            hmax = np.array([ah[a:b + 1].max() for a, b in zip(first, last)])
            hmin = np.array([ah[a:b + 1].min() for a, b in zip(first, last)])
        # step ratios (companion / run, second / first companion), the smallest over the segments,
        # or for the finer companions the ratios run / companion
        self.r = float(np.min(H / hmax)) if not finer else float(np.min(hmin / H))
        self.r2 = float(np.min(H2 / H)) if not finer else float(np.min(H / H2))
        self.finer = finer
        self.planned_steps = int(self.nc.sum() + self.nc2.sum()) * len(members)
        self.moments = problem.moments
        self.Lc = self.Lc2 = problem.L0[members]
        self.carry = self.carry2 = None
        self.j = 0
        self.Lmax = np.maximum(np.abs(self.Lc).max(axis=1), 1e-300)
        self.Wmax = np.maximum(np.abs(self.Lc / self.moments).max(axis=1), 1e-300)
        self.d1 = np.zeros(marks.size)  # run - first companion, relative, per sample
        self.d2 = np.zeros(marks.size)  # first - second companion
        self.err = np.zeros(marks.size)  # estimated error of the run at each sample
        self.span = problem.span

    def _divisor(self) -> float:
        r"""``e_run = |y_run - y_1| / divisor`` from the observed convergence of the three runs.

        With errors :math:`C h^q`: :math:`\rho = |y_1 - y_2| / |y_{run} - y_1| = r^q (r_2^q - 1)/(r^q - 1)`
        (:func:`observed_order` solves it for :math:`q`; :math:`r_2^q` when :math:`r_2 = r`), which gives
        the observed order :math:`q \le p` (never more than the method's order); the run's error is then
        :math:`|y_{run} - y_1| / (r^q - 1)` (run vs coarser companion) or
        :math:`|y_{run} - y_1|\,r^q/(1 - r^q)`... (finer companions: the run is the coarsest).
        Outside the asymptotic regime (:math:`q < 1/2`) the difference itself is the estimate.
        """
        d1, d2 = self.d1[:self.j], self.d2[:self.j]
        D1 = float(d1.max())
        p = self.p
        if D1 <= 0.0:
            return math.inf
        rho = float(d2.max()) / D1
        if not self.finer:
            # the order from the samples where the coarser companion is still in its linear regime (an
            # error that has grown to order one, e.g. on a chaotic orbit, stops following C h^q and would
            # show a low order) and the run's difference is above round-off
            linear = (d2 <= LINEAR_REGIME) & (d1 >= 100.0 * _EPS)
            if linear.any():
                rho = float(d2[linear].max()) / float(d1[linear].max())
        if self.finer:  # the run is the coarsest: D1 ~ e_run (1 - r^-q), D2 ~ D1 / r2^q (r, r2 > 1)
            q = min(p, math.log(max(rho, 1e-300)) / -math.log(self.r2)) if rho < 1.0 else 0.0
            self.q = q
            return max(1.0 - self.r ** -q, 1e-300) if q >= 0.5 else 1.0
        q = observed_order(rho, self.r, self.r2, p)
        self.q = q
        return max(self.r ** q - 1.0, 1.0) if q >= 0.5 else 1.0

    def update(self, upto: int, Lf: np.ndarray) -> None:
        """The run reached ``marks[:upto]``; ``Lf (members, upto - j, n)`` are its states at the new ones."""
        j = self.j
        if upto <= j:
            return
        grid = self.grid[j:upto + 1]
        L1, self.carry = advance_chunked(self.solver, self.problem, self.Lc, grid, self.nc[j:upto],
                                         members=self.members, work=self.work, bar=self.bar, carry=self.carry)
        L2, self.carry2 = advance_chunked(self.solver, self.problem, self.Lc2, grid, self.nc2[j:upto],
                                          members=self.members, work=self.work, bar=self.bar, carry=self.carry2)
        self.Lc, self.Lc2 = L1[:, -1], L2[:, -1]
        self.Lmax = np.maximum(self.Lmax, np.abs(Lf).max(axis=(1, 2)))
        self.Wmax = np.maximum(self.Wmax, np.abs(Lf / self.moments).max(axis=(1, 2)))
        self.d1[j:upto] = _relative_difference(Lf, L1[:, 1:], self.moments, self.Lmax, self.Wmax)
        self.d2[j:upto] = _relative_difference(L1[:, 1:], L2[:, 1:], self.moments, self.Lmax, self.Wmax)
        if not (np.all(np.isfinite(self.d1[j:upto])) and np.all(np.isfinite(self.d2[j:upto]))):
            raise CheckFailed(self.h / 2.0, "a companion run overflowed")
        self.j = upto
        self.err[:upto] = self.d1[:upto] / self._divisor()
        accept = ACCEPT * self.control.rtol
        e = float(self.err[:upto].max())
        done = abs(self.tm[upto - 1] - self.problem.t[0]) / self.span
        if e > accept:
            raise self._failure(e, self._project(upto, e, done), done)
        if upto < self.marks.size and done >= PROJECT_AFTER:
            projected = self._project(upto, e, done)
            if projected > PROJECT_MARGIN * accept:
                raise self._failure(e, projected, done)
        if upto == self.marks.size:
            self._check_roundoff()
            self.control.history.append((self.h, e))

    def _check_roundoff(self) -> None:
        r"""Re-run with compensated storage when the orbit amplifies round-off towards ``rtol``.

        Richardson's differences see the truncation error only; the round-off of plain
        arithmetic, about :math:`\epsilon\sqrt{\text{flows}}` for a regular orbit, is amplified on a
        chaotic one like the truncation error is: by :math:`A`, the growth of the envelope of the
        differences to the first companion from an eighth of the run (or the first sample after it
        where they are above round-off) to its end, beyond linear. When
        :data:`ROUNDOFF_FACTOR` :math:`\cdot\epsilon\sqrt{\text{flows}}\,A` exceeds
        :data:`ROUNDOFF_SHARE` of the accepted error, the run is repeated at the same step with
        compensated (TwoSum) storage (a random generic 5D body at rtol 1e-10 missed the bound 1.7-fold
        in plain arithmetic, and met it 40-fold with TwoSum, at the same step).
        """
        if not self.solver.can_compensate() or self.j < 8:
            return
        t = np.abs(self.tm[:self.j] - self.problem.t[0])
        env = np.maximum.accumulate(self.d1[:self.j])  # (the companion's error, above round-off, grows alike)
        flows = self.steps * self.solver.flows_per_step(self.problem)
        # from the first sample after an eighth of the run where the difference is above round-off
        above = np.flatnonzero((t >= t[-1] / 8.0) & (env > 10.0 * _EPS * np.sqrt(flows * t / max(t[-1], 1e-300))))
        if above.size == 0 or above[0] >= self.j - 1 or t[above[0]] <= 0.0:
            return
        i = int(above[0])
        amplification = max(1.0, env[-1] / env[i] / (t[-1] / t[i]))
        roundoff = ROUNDOFF_FACTOR * _EPS * math.sqrt(flows) * amplification
        if roundoff > ROUNDOFF_SHARE * ACCEPT * self.control.rtol:
            self.control.roundoff_amplified = True
            raise CheckFailed(self.h, f"the orbit amplifies round-off {amplification:.3g}-fold (about {roundoff:.2g} "
                                      f"in plain arithmetic, rtol = {self.control.rtol:g}): re-run with compensated "
                                      f"storage at the same step")

    def _user(self, h: float) -> float:
        return h / self.problem.scale

    def _growth(self, upto: int) -> float:
        """Exponential rate of the error envelope (scaled time), or 0.0 when it grows like a power of t.

        On a regular orbit the error grows like :math:`t` (at most :math:`t^2`): by a factor 2-4
        per doubling of the time. Over the last two doublings of the time done, a factor above
        :data:`GROWTH_RATIO` (faster than :math:`t^3`) counts as exponential, with the rate of
        the faster one (the envelope saturates once the error is of order one).
        """
        if upto < 16:
            return 0.0
        t = np.abs(self.tm[:upto] - self.problem.t[0])
        env = np.maximum.accumulate(self.err[:upto])
        idx = [int(np.searchsorted(t, t[-1] * f)) for f in (0.25, 0.5)] + [upto - 1]
        lam = 0.0
        for i, k in zip(idx[:-1], idx[1:]):
            if env[i] > 0.0 and env[k] / env[i] > GROWTH_RATIO and t[k] > t[i]:
                lam = max(lam, math.log(env[k] / env[i]) / (t[k] - t[i]))
        return lam

    def _project(self, upto: int, e: float, done: float) -> float:
        """The estimated error at the end of the run from the samples so far, growing linearly (the
        regular case; an exponential projection would stop runs near a separatrix, where the error
        grows fast for a while only, and ask for far too short steps)."""
        return e / max(done, 1e-300)

    def _failure(self, e: float, projected: float, done: float) -> CheckFailed:
        """The re-run's step, priced; or the error naming why ``rtol`` is out of reach."""
        rtol, p = self.control.rtol, self.p
        end = max(e, projected)
        self.control.history.append((self.h, end))
        # the observed order where the error is asymptotic (round-off floors show q < p); an error
        # above ASYMPTOTIC says nothing about the order (q ~ 1 there would ask for ~1e8 steps where a
        # few hundred do): extrapolate with the method's order, and the re-run's check decides
        # (and at least p/2 where one was observed: a run just outside the asymptotic regime shows q ~ 1-2,
        # and 1.5 asked for 2.5e6 steps where a few thousand do; q < 1/2, no order seen: 1)
        q_seen = getattr(self, "q", p)
        q = p if end > ASYMPTOTIC else (min(p, max(p / 2.0, q_seen)) if q_seen >= 0.5 else 1.0)
        h_new = 0.9 * self.h * (SAFETY * rtol / end) ** (1.0 / q)
        h_new = min(h_new, self.h / 1.25)
        lam = self._growth(self.j)
        why = (f"estimated error {end:.2g} at the end of the run (rtol = {rtol:g}) with step "
               f"{self._user(self.h):.3g}")
        if lam > 0.0:
            why += (f"; the error grows like exp(lambda t) with lambda ~ {lam * self.problem.scale:.3g} "
                    f"(growth exp(lambda T) ~ {math.exp(min(lam * self.span, 700.0)):.3g} over the run, estimated "
                    f"from the check at {done:.0%} of it)")
        self.control.last_growth = lam
        steps_new = self.span / h_new * self.problem.B * (1.0 + 1.0 / COMPANION_RATIO)
        if self.work.done + steps_new > self.work.max_steps:
            h_budget = self.span * self.problem.B * (1.0 + 1.0 / COMPANION_RATIO) / max(
                self.work.max_steps - self.work.done, 1.0)
            reachable = min(1.0, end * (h_budget / self.h) ** q)  # the order h_new assumed (1: no digit left)
            raise StepBudgetError(
                f"simulate: rtol = {rtol:g} needs about {self.work.done + steps_new:.3g} integration steps here "
                f"({why}); reachable accuracy about {reachable:.2g} within the budget max_steps = "
                f"{self.work.max_steps}; raise it with simulate(..., max_steps=...) or "
                f"hyperrotor.options(max_steps=...), or ask for a larger rtol or a shorter run",
                needed=self.work.done + steps_new, budget=self.work.max_steps, option="max_steps")
        return CheckFailed(h_new, why)

    def run_alone(self) -> None:
        """The check without the run: the checked members advance on their own to every sample."""
        problem, t, cs, nsub = self.problem, self.problem.t, self.cs, self.nsub
        points = np.union1d(cs, np.concatenate([[0], self.marks]))
        grid = step_times(t, cs, nsub, points)
        hs = step_lengths(t, nsub)
        h = hs[np.clip(np.searchsorted(cs, points[:-1], side="right") - 1, 0, nsub.size - 1)]
        L, _ = advance_chunked(self.solver, problem, problem.L0[self.members], grid, np.diff(points), h,
                               members=self.members, work=self.work, bar=self.bar)
        pos = np.searchsorted(points, self.marks)
        self.update(self.marks.size, L[:, pos])
