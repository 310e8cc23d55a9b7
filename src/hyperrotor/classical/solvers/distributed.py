"""Ensembles of :func:`hyperrotor.simulate` on a dask cluster (``client=``), cut into chunks by the package's dask helper.

The step is chosen once for the whole ensemble (as without a client), then the members
are cut into chunks of about a second of work each and every chunk runs the same solver
with that step on a worker. Each member's arithmetic is the one of a run without a
client (the per-member Casimir shift, the same steps), so splittings and scipy methods
give the same numbers bit for bit (measured; a plane whose rate vanishes for every member
of a chunk but not of the whole ensemble would change the rounding only); Moser-Veselov
calls LAPACK inside its kernel, whose rounding may differ between machines. The step and
the per-member set-up come from :mod:`.members`. Dense output: fixed-step methods rebuild
it in this process from the gathered output states; scipy methods evaluate it on the
workers (each chunk re-runs its members with scipy's interpolants, as the first
``Trajectory.sol`` call of a run without a client does). Events on an ensemble run in this
process (:func:`.members.run_members_with_events`); ``simulate`` refuses them with a client.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from .base import Problem, RunResult, nsub_for
from .chunks import cost_key, seconds_per_flow
from .driver import FixedStepSolver
from .members import member_problem, member_setup
from .step_control import CHECK_MEMBERS

__all__ = ["run_distributed"]

def _rows(L0, T0, torque, solver, template, control, max_steps, tq=None):
    """One chunk of members (top-level, picklable): L (and T) of the chunk at the output times, or
    with ``tq`` its dense output there (scipy methods: re-run with their interpolants)."""
    res = solver.run(member_problem(template, L0, T0, torque), control, max_steps=max_steps, progress=False)
    L, T = (res.L, res.T) if tq is None else res.dense(tq)
    return (L, T) if T is not None else L


def run_distributed(solver, problem: Problem, control, *, client, max_steps: int, progress=None) -> RunResult:
    from hyperrotor._parallel import map_rows

    B = problem.B
    template = dataclasses.replace(problem, L0=problem.L0[:0],
                                   T0=None if problem.T0 is None else problem.T0[:0])
    # (the check runs here, before the workers: on up to CHECK_MEMBERS members, not the whole ensemble again)
    worker_solver, worker_control, steps, h, work = member_setup(solver, problem, control, max_steps, CHECK_MEMBERS,
                                                                 progress=progress)
    if steps is not None:
        # (a chunk of about a second: the cost per flow this process learned, or its default for this N)
        per_member = max(1, steps) * solver.flows_per_step(problem) * seconds_per_flow(cost_key(solver, problem, B=1))
    else:
        per_member = 0.05  # a scipy solve of a few periods
    chunk = int(max(1, min(B, 1.0 / max(per_member, 1e-12))))
    T0 = problem.T0 if problem.T0 is not None else np.zeros((B, 0))
    tq = problem.torque if isinstance(problem.torque, np.ndarray) else np.zeros((B, 0))
    rows = (np.ascontiguousarray(problem.L0), np.ascontiguousarray(T0), tq)
    out = map_rows(_rows, rows,
                   args=(worker_solver, template, worker_control, max_steps), client=client, chunk_size=chunk,
                   progress=progress, desc="simulate")
    L, T = (out if isinstance(out, tuple) else (out, None))
    stats = dict(steps=steps, nfev=None, dt=(float(np.max(np.abs(np.diff(problem.t)) / nsub_for(problem.t, h)))
                                             if steps else None) if isinstance(solver, FixedStepSolver) else None,
                 status="finished", chunks=-(-B // chunk))
    if work is not None:  # every step (the probe and the check in this process, the members on the workers)
        stats.update(work=int(work.done) + steps * B, reruns=int(getattr(control, "reruns", 0)))
    dense = None
    if isinstance(solver, FixedStepSolver):
        from .driver import DenseOutput

        dense = DenseOutput(solver, problem, problem.t, nsub_for(problem.t, h), L, T, problem.t.size)
    else:  # scipy: the workers re-run their members with scipy's interpolants and evaluate them at tq
        dense = _WorkerDense(rows, (worker_solver, template, worker_control, max_steps), client, chunk, progress)
    return RunResult(L=L, T=T, t=problem.t, stats=stats, dense=dense)


class _WorkerDense:
    """Dense output of a scipy ensemble run on a cluster: the workers re-run their members with
    scipy's interpolants. Pickles without the client (then the members re-run in this process)."""

    def __init__(self, rows, args, client, chunk, progress):
        self.rows, self.args, self.client, self.chunk, self.progress = rows, args, client, chunk, progress

    def __getstate__(self):
        return {**self.__dict__, "client": None}

    def __call__(self, tq_):
        from hyperrotor._parallel import map_rows

        out_ = map_rows(_rows, self.rows, args=(*self.args, tq_), client=self.client, chunk_size=self.chunk,
                        progress=self.progress, desc="dense output")
        return out_ if isinstance(out_, tuple) else (out_, None)
