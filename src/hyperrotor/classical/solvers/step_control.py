r"""Step control of the fixed-step methods: a given ``dt`` or an error target ``rtol``.

:class:`FixedStep` takes the largest step ``dt``; :class:`ErrorTarget` chooses the step
once, before the run, so that the whole-run error stays within ``rtol``:

.. math:: \max_t \|L(t) - L_\text{exact}(t)\|_\infty \le \mathrm{rtol}\,\max_t \|L(t)\|_\infty,

and the same for :math:`\omega` (they differ for stiff moment ratios, where the heavy
planes have small rates but carry most of ``L``). Either way each output interval is
split into ``ceil(gap / h)`` equal steps, so output times are hit exactly.

How :class:`ErrorTarget` chooses the step
-----------------------------------------
1. *Rate bound.* :math:`\omega_\text{max} = \max_a \min(|L|, \sqrt{2EI_a})/I_a` bounds every
   rate reachable on the orbit (from the Casimir :math:`|L|^2` and the energy ``E``), raised
   to the linearised frequencies :math:`|\omega_c|\sqrt{|(I_c-I_a)(I_c-I_b)|/(I_aI_b)}` of every
   coupled triple of planes (larger than the rates only for moments violating the triangle
   inequalities, i.e. stiff problems) and, with a torque, to the rate it can build up.
2. *Probe.* On :math:`P = \min(\text{run}, ` :data:`PROBE_TURNS` :math:`/\omega_\text{max})`,
   for up to :data:`PROBE_MEMBERS` ensemble members (the fastest), Richardson's estimate
   :math:`e(h) = \max|y_h - y_{h/2}| / (1 - 2^{-p})` from step :math:`h = 1/\omega_\text{max}`,
   refined (x1/4) while not asymptotic (:math:`e > ` :data:`ASYMPTOTIC`) and enlarged (x4) while at
   round-off. With the model :math:`e \propto (\text{run}/P)\,h^p` (linear growth of the phase
   error) this gives a first step :math:`h^*` for the target ``SAFETY * rtol``.
3. *Budget.* ``steps x members`` above ``max_steps`` is refused here, before any long work.
4. *Whole-run check.* Richardson's estimate over the *whole* run (sampled at up to
   :data:`CHECK_SAMPLES` times) at a step :math:`h_c \ge h^*` chosen so that the check costs at most
   :data:`CHECK_FRACTION` of the run itself (or :data:`CHECK_STEPS_MIN` steps, if more), and
   :math:`h^* \leftarrow 0.9\,h_c\,(\mathrm{SAFETY\cdot rtol}/e_c)^{1/p}` (or :math:`h_c` itself when
   :math:`e_c` already meets the target; a check at :math:`h_c = h^*` that fails is repeated at the new step). This catches what the
   probe cannot see (faster than linear error growth, e.g. an unstable rotation running away
   after the probe interval; a resonance of the splitting). The check sees the actual motion
   at the actual output times, so the bound holds as long as the error is asymptotic in
   :math:`h` between :math:`h_c` and :math:`h^*` (chaotic motion over long runs is beyond any a-priori rule).

The timed probes also give the cost per step: a run estimated to take longer than
``options["slow_run_warning_seconds"]`` gives a ``UserWarning`` before it starts.
"""
from __future__ import annotations

import math
import time
import warnings
from functools import lru_cache
from typing import Any, Callable

import numpy as np

from hyperrotor import _validate
from hyperrotor._options import options

from .base import FixedStepSolver, Problem, StepBudgetError, nsub_for

__all__ = ["FixedStep", "ErrorTarget", "StepBudgetError"]

#: the error target used for the step: rtol times this (margin for the asymptotic model)
SAFETY = 0.5
#: Richardson estimates above this are outside the asymptotic regime (the step is refined)
ASYMPTOTIC = 1e-2
#: length of the probe interval in turns of the fastest rate (20 radians: a few periods)
PROBE_TURNS = 20.0
#: ensemble members probed (the fastest ones): the step is one for all members
PROBE_MEMBERS = 8
#: no extrapolation beyond this factor of the probed step (the error model is asymptotic in h)
MAX_STEP_GROWTH = 8.0
#: the whole-run check costs at most this fraction of the run itself ...
CHECK_FRACTION = 0.5
#: ... or this many steps (per probed member), if more: short runs are always checked in full
CHECK_STEPS_MIN = 20_000
#: a checked error below this fraction of the target lets the step grow (checked again)
GROW_BELOW = 0.1
#: sample times of the whole-run check (the error can peak between output times)
CHECK_SAMPLES = 64


def refuse_steps(steps: float, B: int, max_steps: int, what: str | Callable[[], str]) -> None:
    """Raise :class:`StepBudgetError` when ``steps`` per member times ``B`` members exceed ``max_steps``
    (``what``: the estimate's origin for the message, or a function making it, called only then)."""
    total = float(steps) * max(B, 1)
    if total > max_steps:
        what = what() if callable(what) else what
        raise StepBudgetError(
            f"this run needs about {total:.3g} integration steps ({what}), more than the budget max_steps = "
            f"{_validate.fmt(int(max_steps))}; raise it with simulate(..., max_steps=...) or "
            f"hyperrotor.options(max_steps=...) if you mean it, or ask for less (shorter t, larger rtol/dt)"
        )


class FixedStep:
    """Largest step ``dt`` (in the user's time units)."""

    def __init__(self, dt: Any):
        self.dt = _validate.positive("dt", dt)

    def step(self, solver: FixedStepSolver, problem: Problem, max_steps: int) -> float:
        return self.dt * problem.scale  # (the driver checks the budget once it has counted the steps)

    def __repr__(self) -> str:
        return f"FixedStep(dt={self.dt!r})"


def _rate_bound(problem: Problem) -> tuple[np.ndarray, float]:
    """Per-member bound on the rates reachable on the orbit (see the module docstring, step 1)."""
    L0, m = problem.L0, problem.moments
    C = np.sqrt(np.sum(L0 * L0, axis=1, keepdims=True))
    E2 = np.sum(L0 * L0 / m, axis=1, keepdims=True)
    W = np.minimum(C, np.sqrt(E2 * m)) / m  # (B, n)
    wmax_b = W.max(axis=1) if W.size else np.zeros(L0.shape[0])
    tc, ta, tb = _triples(problem.N)
    if tc.size and W.size:
        Ic, Ia, Ib = m[tc], m[ta], m[tb]
        lam = W[:, tc] * np.sqrt(np.abs((Ic - Ia) * (Ic - Ib)) / (Ia * Ib))
        wmax_b = np.maximum(wmax_b, lam.max(axis=1))
    tq = 0.0
    if problem.kick:
        tq = float(np.max(np.abs(problem.torque) / m))
        wmax_b = np.maximum(wmax_b, max(tq * problem.span, tq ** 0.5))
    return wmax_b, tq


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


class ErrorTarget:
    """Step chosen once from a whole-run error target ``rtol`` (see the module docstring)."""

    def __init__(self, rtol: Any):
        self.rtol = _validate.positive("rtol", rtol)
        self.seconds_per_step: float | None = None

    def __repr__(self) -> str:
        return f"ErrorTarget(rtol={self.rtol!r})"

    def step(self, solver: FixedStepSolver, problem: Problem, max_steps: int) -> float:
        span = problem.span
        B = problem.B
        if B == 0 or span == 0.0:
            return max(span, 1.0)
        wmax_b, _ = _rate_bound(problem)
        wmax = float(wmax_b.max())
        if wmax == 0.0 or (hasattr(solver, "flows_per_step") and solver.flows_per_step(problem) == 0):
            return span  # nothing moves
        p = solver.order
        target = SAFETY * self.rtol
        sel = np.argsort(wmax_b)[::-1][: min(PROBE_MEMBERS, B)]
        L0s = problem.L0[sel]
        Ms = problem.moments
        direction = 1.0 if problem.t[-1] >= problem.t[0] else -1.0
        T0s = None
        spent = [math.inf]  # least seconds per member-step seen (the first call may include JIT compilation)

        def richardson(Pv, m, samples):
            """Error estimate (relative, see the module docstring) of ~m steps over [0, Pv]; None if failed."""
            k = max(1, min(m, samples))
            ms = int(math.ceil(m / k))
            tg = direction * np.linspace(0.0, Pv, k + 1) + problem.t[0]
            t0 = time.perf_counter()
            try:
                y1 = solver.advance(problem, L0s, T0s, tg, np.full(k, ms), members=sel)[0]
                y2 = solver.advance(problem, L0s, T0s, tg, np.full(k, 2 * ms), members=sel)[0]
            except RuntimeError:  # an implicit step without solution at this h
                return None, Pv / (k * ms)
            finally:
                spent[0] = min(spent[0], (time.perf_counter() - t0) / (3 * k * ms * len(sel)))
            if not (math.isfinite(float(y1.sum() + y2.sum())) or (np.all(np.isfinite(y1)) and np.all(np.isfinite(y2)))):
                return None, Pv / (k * ms)  # (a finite sum proves finite entries; else look at them)
            dL = np.abs(y1 - y2)  # (members, k + 1, n)
            dW = dL / Ms
            Lmax = np.maximum(np.abs(y2).max(axis=(1, 2)), 1e-300)
            wmax_s = np.maximum(np.abs(y2 / Ms).max(axis=(1, 2)), 1e-300)
            # max(x / c) = max(x) / c for c > 0 (rounded division is monotonic): per member, then over members
            e = max(float(np.max(dL.max(axis=(1, 2)) / Lmax)), float(np.max(dW.max(axis=(1, 2)) / wmax_s)))
            return e / (1.0 - 2.0 ** -p), Pv / (k * ms)

        # 2. probe
        P = min(span, PROBE_TURNS / wmax)
        h = min(P, 1.0 / wmax)
        est = None
        for _ in range(24):
            m = max(1, int(math.ceil(P / h - 1e-9)))
            if m > 200_000:
                break
            err, h = richardson(P, m, 16)
            if err is None or not np.isfinite(err) or err > ASYMPTOTIC:
                h /= 4.0
                continue
            floor = 1e3 * np.finfo(float).eps * math.sqrt(2 * m * solver.flows_per_step(problem))
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
            on_run = max(err, 1e3 * np.finfo(float).eps) * max(1.0, span / P)
            h_star = min(MAX_STEP_GROWTH * h, 0.8 * h * (target / on_run) ** (1.0 / p))
        # 3. budget, before any long work
        refuse_steps(span / h_star, B, max_steps,
                     lambda: f"step {h_star / problem.scale:.3g} chosen for rtol = {self.rtol:g}")
        # 4. whole-run check at h_c >= h*, costing at most CHECK_FRACTION of the run
        widen = 1.0
        grown = 0
        last_good = None
        for _ in range(6):
            verified = False
            allowance = widen * max(CHECK_STEPS_MIN, CHECK_FRACTION * (span / h_star) * B / len(sel))
            h_c = max(h_star, 3.0 * span / allowance)
            e, hv = richardson(span, max(1, int(math.ceil(span / h_c - 1e-9))), CHECK_SAMPLES)
            coarse = hv > h_star * (1.0 + 1e-9)
            if e is None or not np.isfinite(e) or e > ASYMPTOTIC:  # the check's step is not asymptotic
                if last_good is not None:
                    h_star = last_good  # a grown step failed: back to the last step that passed
                    break
                if coarse:
                    widen *= 4.0  # check at a finer step (costs more)
                else:
                    h_star /= 4.0
                continue
            if e <= target:
                h_star = hv  # the checked step meets the target (cheaper than the probe's if coarser)
                if e < GROW_BELOW * target and grown < 2:  # far below: a longer step, checked again
                    grown += 1
                    h_star = min(MAX_STEP_GROWTH * hv, 0.9 * hv * (target / max(e, 1e-300)) ** (1.0 / p))
                    last_good = hv
                    continue
                verified = True
                break
            h_new = 0.9 * hv * (target / e) ** (1.0 / p)
            h_star = h_new if coarse else min(h_star, h_new)
            if last_good is not None and h_star <= last_good:
                h_star = last_good  # a grown step failed: back to the last step that passed
                break
            if coarse:
                break  # extrapolated from an asymptotic estimate of the whole run
        if not verified and last_good is not None:
            h_star = last_good
        refuse_steps(span / h_star, B, max_steps,
                     lambda: f"step {h_star / problem.scale:.3g} chosen for rtol = {self.rtol:g}")
        if math.isfinite(spent[0]):
            self.seconds_per_step = spent[0]
            seconds = self.seconds_per_step * float(nsub_for(problem.t, h_star).sum()) * B
            limit = options["slow_run_warning_seconds"]
            if seconds > limit:
                warnings.warn(
                    f"simulate: {solver.name!r} at rtol = {self.rtol:g} needs about {seconds:.3g} s "
                    f"({span / h_star:.3g} steps per trajectory); a splitting of higher order reaches this "
                    f"accuracy much sooner (options['slow_run_warning_seconds'] = {_validate.fmt(limit)})",
                    UserWarning, stacklevel=4,
                )
        return h_star
