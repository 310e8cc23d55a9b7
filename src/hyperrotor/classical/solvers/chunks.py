r"""Chunked compiled work of the fixed-step methods: the one place that sizes chunks and learns their cost.

Every phase of a fixed-step run (the step control's probes, the run itself, the coarse
companion run of the a-posteriori check) advances the state through
:meth:`~.driver.FixedStepSolver.advance` in calls of about ``options["chunk_seconds"]``
each: between two calls Python runs its signal handlers (Ctrl-C raises
:class:`KeyboardInterrupt` within about a chunk's time), and every call is counted against
the run's budget (:class:`Work`). A call continues from the exact state of the previous
one (``carry``), so the numbers do not depend on where the chunks fall.

The measured seconds per elementary flow of each kind of kernel call (solver class and
variant, N, attitude, ensemble size to a factor 2) are kept in :data:`SECONDS_PER_FLOW`:
they size the first chunk of the next call and give the step control its time estimates.
"""
from __future__ import annotations

import copy
import math
import time
from typing import Any

import numpy as np

from hyperrotor import _parallel, _pricing
from hyperrotor._jit import jit
from hyperrotor._options import options

from ._kernels import PARALLEL_MIN_BODIES
from .base import Problem, StepBudgetError

__all__ = ["Work", "advance_chunked", "advance_pair_chunked", "pair_ahead", "refuse_steps", "step_times", "stops",
           "merge", "check_finite", "cost_key", "learn", "seconds_per_flow", "SECONDS_PER_FLOW", "FIRST_CHUNK_FLOWS",
           "flow_weight", "first_chunk_flows"]

#: the first chunk of a long run does this many elementary flows (about 10 ms); later chunks
#: are sized from its measured time to last ``options["chunk_seconds"]``
FIRST_CHUNK_FLOWS = 2_000_000
#: measured seconds per elementary flow and member of the last timed chunk, per :func:`cost_key`
SECONDS_PER_FLOW: dict = {}
#: chunks shorter than this (s) are not timed for the table above (call overhead dominates)
MIN_TIMED_CHUNK = 2e-3
#: ... and calls of fewer flows than this (a few probe steps cost mostly the call itself)
MIN_TIMED_FLOWS = 200_000
#: seconds per elementary flow assumed before anything of a kind was timed (a 5D splitting, one core; larger N:
#: :func:`flow_weight` times this)
DEFAULT_SECONDS_PER_FLOW = 1e-8
#: a pair of runs expected to take this long (seconds) starts on the second core (:func:`pair_ahead`). A round trip
#: through its thread costs 60-80 us, but the pair also overlaps the Python around the run: on the 3D top at T = 200
#: (pairs of ~0.1 ms) 5e-5 gave rtol calls 1.88x / 1.54x the fixed-step run, 1.5e-4 (no thread there) 1.95x / 1.60x
AHEAD_MIN_SECONDS = 5e-5
#: the kinds (:func:`cost_key`) of the pair calls that have run in this process (their kernels are compiled)
_PAIRED: set = set()


def cost_key(solver, problem: Problem, B: int | None = None, with_attitude: bool | None = None):
    """The kind of a kernel call: solver variant, N, attitude, ensemble size to a factor 2."""
    B = problem.B if B is None else B
    att = problem.with_attitude if with_attitude is None else with_attitude
    return solver.kernel_variant(), problem.N, att, 0 if B < 32 else B.bit_length()


def flow_weight(N: int) -> float:
    """What an elementary flow of so(N) costs relative to one of so(5), before any was timed: it rotates the
    2(N - 2) components its plane couples, and beyond the caches each costs more (measured with splitting8 on
    random bodies, 2026-11-29: 2.5x at N = 8, 4x at 12, 10x at 20, 17-23x at 40, 42-47x at 80, 89-93x at 140;
    this weight ``((N - 2) / 3)^1.2`` is 2.3, 4.2, 8.6, 21, 50, 99 there). The first chunk of a call of a kind
    not timed yet is sized with it (at N = 200 the 5D figure had put 17 steps, about 20 s, in one call)."""
    return max(1.0, ((N - 2) / 3.0) ** 1.2)


def first_chunk_flows(N: int) -> float:
    """Flows of the shortest chunk worth timing at dimension ``N`` (:data:`FIRST_CHUNK_FLOWS` at N <= 5)."""
    return FIRST_CHUNK_FLOWS / flow_weight(N)


def learn(key, elapsed: float, flows: float) -> None:
    """Record the seconds per flow of a timed call (calls shorter than :data:`MIN_TIMED_CHUNK` or of
    fewer than :data:`MIN_TIMED_FLOWS` flows are ignored: the call's overhead would dominate)."""
    if elapsed >= MIN_TIMED_CHUNK and flows >= MIN_TIMED_FLOWS:
        SECONDS_PER_FLOW[key] = elapsed / flows


def seconds_per_flow(key) -> float:
    """The learned seconds per flow of ``key``, else :data:`DEFAULT_SECONDS_PER_FLOW` times :func:`flow_weight`."""
    spf = SECONDS_PER_FLOW.get(key)
    return DEFAULT_SECONDS_PER_FLOW * flow_weight(key[1]) if spf is None else spf


class Work:
    """The integration steps (times members) spent by one ``simulate`` call, against its budget ``max_steps``.

    Every phase adds to ``done``; :meth:`refuse` stops a phase whose *planned* work would
    carry the total over the budget before it starts.
    """

    def __init__(self, max_steps: int, max_seconds: float | None = None, seconds_per_step: float = 0.0):
        self.max_steps = int(max_steps)
        self.max_seconds, self.seconds_per_step = max_seconds, float(seconds_per_step)
        self.done = 0.0

    def add(self, steps: float) -> None:
        self.done += float(steps)

    def refuse(self, planned: float, what) -> None:
        """Raise :class:`StepBudgetError` when ``done + planned`` exceeds the budget (``what``: the
        estimate's origin, or a function making it, called only then); with ``max_seconds`` also when its time
        at ``seconds_per_step`` (a member's step, from :func:`seconds_per_flow`) does (option ``"max_seconds"``)."""
        total = self.done + float(planned)
        if total > self.max_steps:
            what = what() if callable(what) else what
            raise refuse_steps(f"this run ({what})", total, self.max_steps, "ask for less (shorter t, larger rtol/dt)")
        if self.max_seconds is not None and total * self.seconds_per_step > self.max_seconds:
            what = what() if callable(what) else what
            seconds = total * self.seconds_per_step
            raise _pricing.refuse("simulate", f"this run ({what}; {total:.3g} steps)", seconds, "max_seconds",
                                  "seconds", "ask for less (shorter t, larger rtol/dt)", limit=self.max_seconds,
                                  raise_with="estimate_cost(..., max_seconds=...)", cls=StepBudgetError,
                                  needed=seconds, budget=self.max_seconds, option="max_seconds")


def refuse_steps(what: str, needed: float, budget: float, alternative: str, unit: str = "integration steps"
                 ) -> StepBudgetError:
    """The :class:`StepBudgetError` of a run over ``max_steps``, in the package's one refusal format
    (:func:`hyperrotor._pricing.refuse`), with ``needed``, ``budget`` and ``option`` for the command line."""
    return _pricing.refuse("simulate", what, needed, "max_steps", unit, alternative, limit=int(budget),
                           raise_with="simulate(..., max_steps=...) or hr.options(max_steps=...)", cls=StepBudgetError,
                           needed=needed, budget=budget, option="max_steps")


def step_times(t: np.ndarray, cs: np.ndarray, nsub: np.ndarray, s: np.ndarray) -> np.ndarray:
    """Times of the global step indices ``s`` (output times exactly where a step ends an interval);
    ``cs``: cumulative steps ``[0, nsub[0], nsub[0] + nsub[1], ...]``."""
    k = np.clip(np.searchsorted(cs, s, side="right") - 1, 0, nsub.size - 1)
    out = t[k] + (t[k + 1] - t[k]) * ((s - cs[k]) / nsub[k])
    return np.where(s == cs[k + 1], t[k + 1], out)


@jit
def stops(t, cs, nsub, h, points):  # pragma: no cover - jitted
    """A run of ``nsub[k]`` steps of ``h[k]`` per interval of ``t`` (``cs``: cumulative step counts) that stops at
    the global step indices ``points`` (increasing, its start first): ``(times of the points, steps between
    them, their step lengths)``. Every piece lies inside one interval and takes that interval's step, so the
    pieces do the run's arithmetic (output times among the points are hit exactly). The times are
    :func:`step_times`'s, the step of a piece that of the interval its start lies in. Compiled (the driver asks
    for it on every run whose samples fall between output times, and per chunk)."""
    P = points.size
    K1 = nsub.size
    times = np.empty(P)
    ns = np.empty(max(P - 1, 0), dtype=np.int64)
    hs = np.empty(max(P - 1, 0))
    k = 0
    for i in range(P):
        s = points[i]
        while k + 1 < K1 and cs[k + 1] <= s:  # (the interval with cs[k] <= s, the last one at the end)
            k += 1
        times[i] = t[k + 1] if s == cs[k + 1] else t[k] + (t[k + 1] - t[k]) * ((s - cs[k]) / nsub[k])
        if i + 1 < P:
            ns[i] = points[i + 1] - s
            hs[i] = h[k]
    return times, ns, hs


@jit
def merge(a, b):  # pragma: no cover - jitted
    """``(union, positions of a in it, positions of b in it)`` of two increasing integer arrays (the stops of a
    run: its output steps and the check's samples). Compiled."""
    out = np.empty(a.size + b.size, dtype=np.int64)
    pa = np.empty(a.size, dtype=np.int64)
    pb = np.empty(b.size, dtype=np.int64)
    i = j = n = 0
    while i < a.size or j < b.size:
        v = a[i] if j >= b.size or (i < a.size and a[i] <= b[j]) else b[j]
        if n == 0 or out[n - 1] != v:
            out[n] = v
            n += 1
        if i < a.size and a[i] == v:
            pa[i] = n - 1
            i += 1
        if j < b.size and b[j] == v:
            pb[j] = n - 1
            j += 1
    return out[:n], pa, pb


def check_finite(Ls: np.ndarray, grid: np.ndarray, problem: Problem) -> None:
    """``FloatingPointError`` unless the chunk's last states are finite (a finite sum proves it)."""
    last = Ls[:, -1]
    if math.isfinite(float(last.sum())) or np.all(np.isfinite(last)):
        return
    bad = int(np.argmax(~np.all(np.isfinite(Ls), axis=(0, 2))))
    raise FloatingPointError(
        f"simulate: the solution became non-finite near t = {problem.user_time(grid[bad]):.6g} "
        f"(the inputs overflow double precision; max|L0| = {np.abs(problem.L0).max() * problem.scale:.3g})"
    )


def _chunk_plan(solver, problem: Problem, rows: int) -> tuple:
    """``(cost key, flows per step of all rows, steps of the first chunk, seconds per chunk)`` of a
    call advancing ``rows`` members without attitude."""
    key = cost_key(solver, problem, B=rows, with_attitude=False)
    flows = max(1, rows * solver.flows_per_step(problem))
    target = float(options["chunk_seconds"])
    return key, flows, max(1, int(max(first_chunk_flows(problem.N), target / seconds_per_flow(key)) // flows)), target


def pair_ahead(solver, problem: Problem, La: np.ndarray, Lb: np.ndarray, grid: np.ndarray, na: np.ndarray,
               nb: np.ndarray, *, members: np.ndarray | None = None, carries: tuple = (None, None)):
    """The one call :func:`advance_pair_chunked` would make for two runs, started now on a
    second core (:func:`hyperrotor._parallel.on_second_core`) while the caller runs something else (the step
    control's companions beside the run they check: both only read the problem), to hand to it as ``ahead``;
    or ``None`` where that does not pay: more than one chunk, under :data:`AHEAD_MIN_SECONDS` of work, an
    ensemble whose kernels use every core already (:data:`~._kernels.PARALLEL_MIN_BODIES` members), one core;
    or where its kernel may still have to be compiled (no pair call of its kind has run in this process yet:
    Ctrl-C cannot stop a compilation on another thread, and the process's exit would wait for it).
    The same numbers as running it then (the same compiled call)."""
    if problem.B >= PARALLEL_MIN_BODIES:
        return None
    key, flows, cap, _ = _chunk_plan(solver, problem, La.shape[0])
    steps = int(na.sum()) + int(nb.sum())
    if key not in _PAIRED or steps > cap or steps * flows * seconds_per_flow(key) < AHEAD_MIN_SECONDS:
        return None
    own = copy.copy(solver)  # (what the pair's call leaves on its solver, last_carry(ies), is not the run's)

    def both():
        a, b = own.advance_pair(problem, La, Lb, grid, na, nb, members=members, carries=carries)
        return a, b, own.last_carries

    return _parallel.on_second_core(both)


def advance_pair_chunked(solver, problem: Problem, La: np.ndarray, Lb: np.ndarray, grid: np.ndarray,
                         na: np.ndarray, nb: np.ndarray, *, members: np.ndarray | None = None,
                         work: Work | None = None, bar: Any = None, carries: tuple = (None, None),
                         ahead: Any = None) -> tuple:
    """Two runs of the same members on ``grid`` (``na[k]``, ``nb[k]`` equal steps per interval, from
    ``La`` and ``Lb``): ``(states a, states b, (carry a, carry b))``. Both together within one chunk:
    one :meth:`~.driver.FixedStepSolver.advance_pair` call (counted, checked, on the bar); else each
    through :func:`advance_chunked`. ``ahead``: that call, started by :func:`pair_ahead`."""
    rows = La.shape[0]
    steps = int(na.sum()) + int(nb.sum())
    if ahead is not None:  # (not timed for the cost model: its time overlapped the run's)
        a, b, carries = _parallel.result(ahead)
    else:
        key, flows, cap, _ = _chunk_plan(solver, problem, rows)
        if steps > cap:
            a, ca = advance_chunked(solver, problem, La, grid, na, members=members, work=work, bar=bar,
                                    carry=carries[0])
            b, cb = advance_chunked(solver, problem, Lb, grid, nb, members=members, work=work, bar=bar,
                                    carry=carries[1])
            return a, b, (ca, cb)
        t0 = time.perf_counter()
        a, b = solver.advance_pair(problem, La, Lb, grid, na, nb, members=members, carries=carries)
        learn(key, time.perf_counter() - t0, steps * flows)
        _PAIRED.add(key)
        carries = solver.last_carries
    check_finite(a, grid, problem)
    check_finite(b, grid, problem)
    if work is not None:
        work.add(steps * rows)
    if bar is not None:
        bar.update(steps * rows)
    return a, b, carries


def advance_chunked(solver, problem: Problem, L0: np.ndarray, grid: np.ndarray, nsub: np.ndarray,
                    h: np.ndarray | None = None, *, members: np.ndarray | None = None, work: Work | None = None,
                    bar: Any = None, carry: Any = None) -> tuple[np.ndarray, Any]:
    """Momenta ``(rows, K, n)`` on ``grid`` (no attitude) from ``L0`` at ``grid[0]``, in timed chunks.

    Interval ``k`` takes ``nsub[k]`` steps of length ``h[k]`` (default: equal steps). A long
    interval is cut inside (at step points, with the exact ``carry``), so no call lasts much
    longer than ``options["chunk_seconds"]``. Returns the states and the carry of the last one.
    """
    nsub = np.asarray(nsub, dtype=np.int64)
    if h is None:
        h = (grid[1:] - grid[:-1]) / nsub
    rows = L0.shape[0]
    key, flows, cap, target = _chunk_plan(solver, problem, rows)
    steps = int(nsub.sum())

    def advance(L, pts, ns, hs, carry):
        """One compiled call of ``ns.sum()`` steps, its cost learned, checked and counted."""
        t0 = time.perf_counter()
        Ls, _ = solver.advance(problem, L, None, pts, ns, members=members, h=hs, carry=carry)
        elapsed = time.perf_counter() - t0
        done = int(ns.sum())
        learn(key, elapsed, done * flows)
        check_finite(Ls, pts, problem)
        if work is not None:
            work.add(done * rows)
        if bar is not None:
            bar.update(done * rows)
        return Ls, solver.last_carry, elapsed

    if steps <= cap:  # one call: its grid is the output grid (no chunk grid, no copies)
        out, carry, _ = advance(L0, grid, nsub, h, carry)
        return out, carry
    out = np.empty((rows, grid.size, L0.shape[1]))
    out[:, 0] = L0
    cs = np.concatenate([[0], np.cumsum(nsub)])
    Lc = L0
    s0 = 0
    while s0 < steps:
        s1 = min(steps, s0 + cap)
        outs = np.arange(np.searchsorted(cs, s0, side="right"), np.searchsorted(cs, s1, side="right"))
        marks = cs[outs]
        if marks.size == 0 or marks[-1] != s1:
            marks = np.append(marks, s1)
        Ls, carry, elapsed = advance(Lc, *stops(grid, cs, nsub, h, np.concatenate([[s0], marks])), carry)
        out[:, outs] = Ls[:, 1:outs.size + 1]
        Lc = Ls[:, -1]
        s0 = s1
        cap = int(min(8 * cap, max(1, cap * target / max(elapsed, 1e-6))))
    return out, carry
