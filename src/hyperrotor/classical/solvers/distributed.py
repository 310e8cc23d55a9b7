"""Ensembles of :func:`hyperrotor.simulate` on a dask cluster (``client=``), cut into chunks by the package's dask helper.

The step is chosen once for the whole ensemble (as without a client), then the members
are cut into chunks of about a second of work each and every chunk runs the same solver
with that step on a worker. Each member's arithmetic is the one of a run without a
client (the per-member Casimir shift, the same steps), so splittings and scipy methods
give the same numbers bit for bit (measured; a plane whose rate vanishes for every member
of a chunk but not of the whole ensemble would change the rounding only); Moser-Veselov
calls LAPACK inside its kernel, whose rounding may differ between machines. Dense output is rebuilt in
this process from the gathered output states (fixed-step methods); events need one
trajectory and so never reach this path.
"""
from __future__ import annotations

import copy
import dataclasses

import numpy as np

from .base import FixedStepSolver, Problem, RunResult, nsub_for

__all__ = ["run_distributed"]

#: seconds of compiled work per elementary plane flow (order of magnitude, reference machine):
#: sets the chunk size so that one chunk runs for about a second
SECONDS_PER_FLOW = 5e-9


class _GivenStep:
    """The step chosen in the client process (scaled units), no second budget check."""

    def __init__(self, h, rtol=None):
        self.h = h
        self.rtol = rtol

    def step(self, solver, problem, max_steps):
        return self.h


def _rows(L0, T0, torque, solver, template, control, max_steps):
    """One chunk of members (top-level, picklable): returns L (and T) of the chunk."""
    problem = dataclasses.replace(template, L0=L0, T0=T0 if template.T0 is not None else None,
                                  torque=torque if isinstance(template.torque, np.ndarray) else template.torque)
    res = solver.run(problem, control, max_steps=max_steps, progress=False)
    return (res.L, res.T) if res.T is not None else res.L


def run_distributed(solver, problem: Problem, control, *, client, max_steps: int, progress=None) -> RunResult:
    from hyperrotor._parallel import map_rows

    B = problem.B
    template = dataclasses.replace(problem, L0=problem.L0[:0],
                                   T0=None if problem.T0 is None else problem.T0[:0])
    if isinstance(solver, FixedStepSolver):
        solver.check(problem)
        solver.prepare(problem)
        h = control.step(solver, problem, max_steps)
        steps = int(nsub_for(problem.t, h).sum()) if problem.t.size > 1 else 0
        if hasattr(solver, "set_accuracy"):
            solver.set_accuracy(problem, getattr(control, "rtol", None), steps)
        worker_solver = copy.copy(solver)
        worker_solver.options = dict(solver.options)
        if "compensated" in worker_solver.options:
            worker_solver.options["compensated"] = bool(solver._state["compensated"])
        worker_control = _GivenStep(h, getattr(control, "rtol", None))
        per_member = max(1, steps) * solver.flows_per_step(problem) * SECONDS_PER_FLOW
    else:
        steps = None
        worker_solver, worker_control = solver, control
        per_member = 0.05  # a scipy solve of a few periods
    chunk = int(max(1, min(B, 1.0 / max(per_member, 1e-12))))
    T0 = problem.T0 if problem.T0 is not None else np.zeros((B, 0))
    tq = problem.torque if isinstance(problem.torque, np.ndarray) else np.zeros((B, 0))
    out = map_rows(_rows, (np.ascontiguousarray(problem.L0), np.ascontiguousarray(T0), tq),
                   args=(worker_solver, template, worker_control, max_steps), client=client, chunk_size=chunk,
                   progress=progress, desc="simulate")
    L, T = (out if isinstance(out, tuple) else (out, None))
    stats = dict(steps=steps, nfev=None, dt=(float(np.max(np.abs(np.diff(problem.t)) / nsub_for(problem.t, h)))
                                             if steps else None) if isinstance(solver, FixedStepSolver) else None,
                 status="finished", chunks=-(-B // chunk))
    dense = None
    if isinstance(solver, FixedStepSolver):
        from .driver import _dense

        nsub = nsub_for(problem.t, h)

        def dense(tq_):
            return _dense(solver, problem, problem.t, nsub, L, T, tq_, problem.t.size)
    else:
        def dense(tq_):
            raise NotImplementedError("dense output of a scipy ensemble run with client=: run without client")
    return RunResult(L=L, T=T, t=problem.t, stats=stats, dense=dense)
