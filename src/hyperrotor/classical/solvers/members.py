r"""Ensembles run member by member with the ensemble's step: events on ensembles, dask chunks.

A fixed-step method chooses its step once for the whole ensemble (the probes look at the
fastest members; the check, of every member as in a run of the whole ensemble, then runs on
its own before any member runs; the budget counts every member). :func:`member_setup` does that once and
returns a solver and a step control that reproduce it on any subset of the members: the
same step, the same automatic ``compensated`` choice, each member's own Casimir shift. A
member run this way takes the steps of its row of the ensemble run: the same momenta bit
for bit (with events every step is stored, and the attitude's Casimir-shift correction,
applied per stored step, agrees to round-off; both tested). Used by

* :func:`run_members_with_events`: ``simulate(..., events=...)`` with an ensemble ``omega0``
  (event times differ per member, so every member is its own run; non-terminal events only:
  a terminal event would end the members at different times);
* :mod:`.distributed`: the chunks of members that dask workers run.
"""
from __future__ import annotations

import copy
import dataclasses
from typing import Any

import numpy as np

from hyperrotor._parallel import progress_bar

from .base import Problem, RunResult, nsub_for
from .driver import FixedStepSolver
from .chunks import Work

__all__ = ["member_setup", "member_problem", "run_members_with_events"]


class GivenStep:
    """The step chosen for the whole ensemble (scaled units); no second probe or budget check."""

    def __init__(self, h: float, rtol: float | None = None):
        self.h = h
        self.rtol = rtol

    def first_step(self, solver, problem, work, bar=None):
        return self.h

    def verified_step(self, solver, problem, work, most=None, bar=None):
        """The step (nothing to verify: ``most``, the members a check would cover, is unused)."""
        return self.first_step(solver, problem, work)

    def checker(self, solver, problem, nsub, work, bar=None):
        return None

    def announce(self, solver, problem, h, steps=None):
        """Nothing: the ensemble's call announced the run."""

    def __repr__(self) -> str:
        return f"GivenStep(h={self.h!r})"


def member_setup(solver, problem: Problem, control: Any, max_steps: int, most: int | None = None, progress=None):
    """Choose the ensemble's step once; returns ``(member_solver, member_control, steps, h, work)``
    (``work``: the :class:`~.chunks.Work` of the probe and the check, which the members' runs add to). The check
    covers every member (up to ``most``, the fastest beyond: :meth:`~.step_control.ErrorTarget.verified_step`).

    For a scipy method (adaptive, per member anyway) the solver and control are returned
    unchanged and ``steps``, ``h`` and ``work`` are ``None``. ``progress``: a bar of the step control's steps (the
    probe's and the check's, here in this process; a review found nothing shown for 20 s before a dask ensemble's
    members started).
    """
    if not isinstance(solver, FixedStepSolver):
        return solver, control, None, None, None
    solver.check(problem)
    solver.prepare(problem)
    work = Work(max_steps)
    if problem.t.size > 1 and problem.B > 0:
        bar = progress_bar(progress, None, "simulate: step control", unit="step", leave=False)
        try:
            h = control.verified_step(solver, problem, work, most=most, bar=bar)
        finally:
            if bar is not None:
                bar.close()
    else:
        h = 1.0
    steps = int(nsub_for(problem.t, h).sum()) if problem.t.size > 1 else 0
    work.refuse(steps * problem.B, lambda: f"{steps:.3g} steps of at most {h / problem.scale:.3g} per member")
    control.announce(solver, problem, h)
    solver.set_accuracy(problem, control.rtol, steps, roundoff_amplified=getattr(control, "roundoff_amplified", False))
    member_solver = copy.copy(solver)
    member_solver.options = dict(solver.options)
    if "compensated" in member_solver.options:
        member_solver.options["compensated"] = bool(solver._state["compensated"])
    return member_solver, GivenStep(h, getattr(control, "rtol", None)), steps, h, work


def member_problem(template: Problem, L0: np.ndarray, T0: np.ndarray | None, torque: Any) -> Problem:
    """``template`` restricted to the members ``L0`` (rows), with their attitudes and torques."""
    return dataclasses.replace(template, L0=L0, T0=T0 if template.T0 is not None else None,
                               torque=torque if isinstance(template.torque, np.ndarray) else template.torque)


def run_members_with_events(solver, problem: Problem, control: Any, *, events, max_steps: int,
                            progress=None) -> RunResult:
    """Events on an ensemble: every member a run of its own with the ensemble's step.

    ``t_events[e]`` (and ``L_events[e]``, ``T_events[e]``) is then a list over the members
    (flattened batch order) of that member's arrays.
    """
    from .driver import event_specs

    specs = event_specs(events)
    if any(sp.max_count is not None for sp in specs):
        raise ValueError("a terminal event would end the members of an ensemble at different times: with an ensemble "
                         "omega0 events must be non-terminal (terminal=False); run the members one by one to stop "
                         "each at its event")
    B = problem.B
    if B == 0:  # an empty ensemble: the run's empty result, and no member's events (concatenating none failed)
        res = solver.run(problem, control, max_steps=max_steps, progress=progress)
        res.t_events = [[] for _ in specs]
        res.L_events = [[] for _ in specs]
        res.T_events = [[] for _ in specs] if problem.T0 is not None else None
        return res
    member_solver, member_control, steps, _, work = member_setup(solver, problem, control, max_steps, progress=progress)
    bar = None
    if progress:
        from tqdm.auto import tqdm

        bar = tqdm(total=B, unit="member", desc="simulate", leave=False)
    results = []
    used = 0
    try:
        for b in range(B):
            sub = member_problem(problem, problem.L0[b:b + 1], None if problem.T0 is None else problem.T0[b:b + 1],
                                 problem.torque[b:b + 1] if isinstance(problem.torque, np.ndarray) else None)
            sub = dataclasses.replace(sub, batch=())
            budget = max_steps if steps is not None else max(1, max_steps - used)  # scipy: what is left
            res = member_solver.run(sub, member_control, events=events, max_steps=budget, progress=False)
            used += res.stats.get("nfev") or 0
            results.append(res)
            if bar is not None:
                bar.update(1)
    finally:
        if bar is not None:
            bar.close()
    L = np.concatenate([r.L for r in results])
    T = None if problem.T0 is None else np.concatenate([r.T for r in results])
    stats = dict(results[0].stats)
    stats["nfev"] = None if steps is not None else int(used)
    for key in ("chunks", "work"):  # summed over the members
        if key in stats:
            stats[key] = int(sum(r.stats.get(key, 0) for r in results))
    if work is not None:  # and the ensemble's probe and check before them, and its re-runs
        stats["work"] += int(work.done)
        stats["reruns"] = int(getattr(control, "reruns", 0))


    def per_event(attr):
        if getattr(results[0], attr) is None:
            return None
        return [[getattr(r, attr)[e] for r in results] for e in range(len(specs))]

    return RunResult(L=L, T=T, t=problem.t, stats=stats, dense=MembersDense(results, T is not None),
                     t_events=per_event("t_events"),
                     L_events=per_event("L_events"), T_events=per_event("T_events"))


class MembersDense:
    """Dense output of an ensemble run member by member: the members' dense outputs, stacked."""

    def __init__(self, results: list, with_attitude: bool):
        self.results, self.with_attitude = results, with_attitude

    def __call__(self, tq):
        parts = [r.dense(tq) for r in self.results]
        return (np.concatenate([p[0] for p in parts]),
                np.concatenate([p[1] for p in parts]) if self.with_attitude else None)
