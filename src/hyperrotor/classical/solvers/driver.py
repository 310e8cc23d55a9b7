r"""The run loop of the fixed-step methods: chunks, Ctrl-C, progress, events, dense output.

One driver serves every :class:`~.base.FixedStepSolver` (splittings, Moser-Veselov):

Chunks
    The steps of the run are cut into chunks of about ``options["chunk_seconds"]`` of
    compiled work (the chunk size adapts to the measured time of the previous chunk; the
    first one is sized from the measured cost per flow of the previous run of the same
    kind, so a run expected to be shorter than one chunk is one call, without copies; with
    ``rtol`` it stops at the check's samples too, and the check follows).
    Between chunks Python runs its signal handlers, so Ctrl-C raises
    :class:`KeyboardInterrupt` within about a chunk's time, updates the progress bar
    (tqdm) and checks that the state is finite. Every chunk takes the run's own step
    lengths (a chunk may start inside an output interval) and continues from the exact
    state of the previous one (:attr:`~.base.FixedStepSolver.last_carry`: the low parts
    of compensated storage, Moser-Veselov's Newton predictor), so a run cut into chunks
    gives the same numbers as one call, bit for bit, however the chunks fall. So does an
    ``rtol`` call: its check judges the run at fixed samples, not at chunk ends (a long run's
    chunks end at the check's early judgements: :data:`~.richardson_check.EARLY_STOP_FLOWS`).
Events
    With event functions ``g(t, L)`` the state is kept at every step; a sign change of
    ``g`` between two steps (with the requested ``direction``) is located by Brent's method
    on :math:`s \mapsto g(t_j + s, \Phi_s(y_j))`, where :math:`\Phi_s` is *one step of the
    method itself* of length ``s`` from the step state :math:`y_j`: the event time has the
    method's accuracy. A ``terminal`` event ends the run there.
Dense output
    The state at any time :math:`\tau` in :math:`[t_k, t_{k+1}]` is rebuilt from the stored
    output state at :math:`t_k`: the same steps as the run up to the last step point
    :math:`t_j \le \tau`, then one step of length :math:`\tau - t_j` (so the result is
    continuous in :math:`\tau`, equals the run at its step points (bit for bit for the
    splittings in plain arithmetic; compensated storage restarts from the rounded output
    state), and has the method's accuracy).
    Cost: at most one output interval's steps per group of queries in it, plus one step
    per query.
"""
from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from hyperrotor import _validate
from hyperrotor._options import options
from hyperrotor._parallel import interrupts_as_raised, progress_bar

from .base import Problem, RunResult, Solver, nsub_for, step_lengths
from .chunks import SECONDS_PER_FLOW, Work, check_finite, cost_key, first_chunk_flows, learn, merge, stops
from .richardson_check import CheckFailed

__all__ = ["FixedStepSolver", "run_fixed_step", "EventSpec", "event_specs", "DenseOutput", "dense_states"]

#: with events every step state is kept: at most this many steps per chunk (memory)
EVENT_CHUNK_STEPS = 100_000


class FixedStepSolver(Solver):
    """A method with a fixed step (chosen once): splittings, Moser-Veselov.

    Subclasses implement :meth:`advance` (integrate members ``L (B, n)``, ``T`` over a
    grid with ``nsub[k]`` equal steps per interval) and :meth:`step_cost` (seconds per
    step per member, for chunking); the generic driver (:mod:`.driver`) does chunking,
    interruption, progress, events and dense output for all of them.
    """

    adaptive = False
    #: what :meth:`advance` needs to continue its last call exactly (the low parts of a compensated
    #: state, a Newton predictor), or ``None``; the driver hands it back as ``carry=`` for the next chunk
    last_carry: Any = None
    #: the two carries of the last :meth:`advance_pair` call
    last_carries: tuple = (None, None)

    def prepare(self, problem: Problem) -> None:
        """Precompute what :meth:`advance` needs for ``problem`` (tables, words, shifts)."""

    def advance(self, problem: Problem, L: np.ndarray, T: np.ndarray | None, t: np.ndarray, nsub: np.ndarray,
                members: np.ndarray | None = None, h: np.ndarray | None = None,
                carry: Any = None) -> tuple[np.ndarray, np.ndarray | None]:
        """States ``(L (B, K, n), T (B, K, N, N) or None)`` on grid ``t`` from ``L``, ``T`` at ``t[0]``.

        Interval ``k`` takes ``nsub[k]`` steps of length ``h[k]`` (default
        :func:`step_lengths`; the driver passes the steps of the whole run's grid).
        ``carry``: :attr:`last_carry` of the call this one continues (the exact state behind
        the rounded ``L``), so that a run cut into chunks gives the same numbers as one call.
        ``members`` selects the ensemble members the rows of ``L`` belong to (default: all).
        May raise ``RuntimeError`` when a step is too long for the method (implicit methods).
        """
        raise NotImplementedError

    def advance_pair(self, problem: Problem, La: np.ndarray, Lb: np.ndarray, t: np.ndarray, na: np.ndarray,
                     nb: np.ndarray, members: np.ndarray | None = None, carries: tuple = (None, None)
                     ) -> tuple[np.ndarray, np.ndarray]:
        """Two runs of the same members on grid ``t`` (no attitude): ``na[k]`` equal steps per interval
        from ``La`` and ``nb[k]`` from ``Lb`` (the step control's probes and companions), each continuing
        its entry of ``carries``; afterwards :attr:`last_carries` holds both carries. By default two
        :meth:`advance` calls; a solver may do both in one compiled call."""
        a, _ = self.advance(problem, La, None, t, na, members=members, carry=carries[0])
        ca = self.last_carry
        b, _ = self.advance(problem, Lb, None, t, nb, members=members, carry=carries[1])
        self.last_carries = (ca, self.last_carry)
        return a, b

    def flows_per_step(self, problem: Problem) -> int:
        """Rough cost unit per step and member (used for chunk sizes and budgets)."""
        return 1

    def set_accuracy(self, problem: Problem, rtol: float | None, steps: int, *, roundoff_amplified: bool = False
                     ) -> None:
        """Choose the arithmetic once the step is known (nothing by default; the splittings choose their
        compensated storage)."""

    def can_compensate(self) -> bool:
        """Whether the step control may switch the run to compensated (TwoSum) storage of ``L``."""
        return False

    def compensates(self) -> bool:
        """Whether the run keeps ``L`` in compensated (TwoSum) storage (its round-off then does not grow with the
        number of steps)."""
        return False

    def kernel_variant(self) -> Any:
        """Hashable label of the compiled code :meth:`advance` runs (the driver learns its speed per label)."""
        return type(self)

    def run(self, problem: Problem, control: Any, *, events=None, max_steps: int, progress=None):
        with interrupts_as_raised():  # (Ctrl-C inside numba's dispatch: a KeyboardInterrupt, not a SystemError)
            return run_fixed_step(self, problem, control, events=events, max_steps=max_steps, progress=progress)


class EventSpec:
    """An event function with scipy's attributes: ``terminal`` (bool or count) and ``direction``."""

    def __init__(self, fn, index):
        if not callable(fn):
            raise TypeError(f"events must be callables g(t, L) -> float (or a list of them), got {fn!r}")
        self.fn = fn
        self.index = index
        term = getattr(fn, "terminal", False)
        if isinstance(term, (bool, np.bool_)):
            self.max_count = 1 if term else None
        elif isinstance(term, (int, np.integer)) and term >= 0:
            self.max_count = int(term) or None
        else:
            raise ValueError(f"event {index}: terminal must be a bool or a non-negative integer, got {term!r}")
        d = getattr(fn, "direction", 0)
        try:
            d = float(d)
        except (TypeError, ValueError):
            raise ValueError(f"event {index}: direction must be a number (<0, 0, >0), got {d!r}") from None
        self.direction = 0.0 if d == 0 else math.copysign(1.0, d)

    def value(self, t: float, L: np.ndarray) -> float:
        """``g(t, L)`` as a float, or a ``TypeError`` naming the event and what it returned."""
        v = self.fn(t, L)
        if np.ndim(v) == 0:
            try:
                return float(v)
            except (TypeError, ValueError):
                pass
        raise TypeError(f"event {self.index}: g(t, L) must return one real number, got {_validate.fmt(v)}")


def event_specs(events) -> list[EventSpec]:
    if events is None:
        return []
    if callable(events):
        events = [events]
    if not isinstance(events, (list, tuple)):
        raise TypeError(f"events must be a callable g(t, L) -> float or a list of them, got {events!r}")
    return [EventSpec(g, i) for i, g in enumerate(events)]


def run_fixed_step(solver: FixedStepSolver, problem: Problem, control: Any, *, events=None, max_steps: int,
                   progress=None) -> RunResult:
    """Run ``problem`` with ``solver`` at the step of ``control`` (see the module docstring)."""
    solver.check(problem)
    solver.prepare(problem)
    t = problem.t
    K = t.size
    B, n, N = problem.B, problem.n, problem.N
    work = Work(max_steps)
    specs = event_specs(events)
    fps = solver.flows_per_step(problem)
    bar = None
    after = ""  # why the previous attempt was stopped (for a budget message)
    try:
        if K > 1 and B > 0 and control.rtol is not None:  # the step control's probe is on the bar too
            bar = progress_bar(progress, None, "simulate", unit="step", leave=False)
        h = control.first_step(solver, problem, work, bar=bar) if K > 1 and B > 0 else 1.0
        while True:
            nsub = nsub_for(t, h) if K > 1 else np.zeros(0, dtype=np.int64)
            steps = int(nsub.sum())
            solver.set_accuracy(problem, control.rtol, steps,
                                roundoff_amplified=getattr(control, "roundoff_amplified", False))
            check = control.checker(solver, problem, nsub, work) if B > 0 and steps > 0 else None
            planned = steps * B + (check.planned_steps if check is not None else 0)
            work.refuse(planned, lambda: f"{steps:.3g} steps of at most {h / problem.scale:.3g} per member"
                                         + (", its check and the step control's probes" if check is not None else "")
                                         + after + _refusal_note(control, work, planned, solver))
            if check is not None and not check.control.reruns:
                control.announce(solver, problem, h, steps)
            hs = step_lengths(t, nsub)  # the run's steps, (K - 1,)
            stats = dict(steps=steps, nfev=None, dt=float(np.abs(hs).max()) if K > 1 else None, chunks=0)
            t_events = [[] for _ in specs]
            L_events = [[] for _ in specs]
            T_events = [[] for _ in specs]
            K_done = K
            if B == 0 or steps == 0:  # nothing to integrate: the initial states (or an empty ensemble)
                outL = np.empty((B, K, n))
                outL[:, 0] = problem.L0
                outT = None
                if problem.with_attitude:
                    outT = np.empty((B, K, N, N))
                    outT[:, 0] = problem.T0
                break
            if bar is None and (progress or planned * fps > first_chunk_flows(N)):
                bar = progress_bar(progress, planned + work.done, "simulate", unit="step", leave=False)
            elif bar is not None:
                bar.reset(total=planned + work.done)
            if bar is not None:
                bar.update(work.done)
            if check is not None:
                check.bar = bar
            try:
                outL, outT, K_done = _loop(solver, problem, t, nsub, hs, specs, t_events, L_events, T_events, fps,
                                           stats, bar, check)
                work.add(steps * B)
                break
            except CheckFailed as failure:
                work.add(int(check.marks[check.j - 1]) * B if check.j else 0)  # the run up to the failed sample
                h = control.next_step(failure, solver, problem, work)
                after = f"; re-run after the check found: {failure.why}"
    finally:
        if bar is not None:
            bar.close()
    stats["status"] = "terminated by event" if K_done < K or (specs and stats.get("terminal")) else "finished"
    stats["work"] = int(work.done)  # every step taken, probes and check included (times members)
    stats["reruns"] = int(getattr(control, "reruns", 0))  # re-runs after a failed check
    res = RunResult(L=outL if K_done == K else outL[:, :K_done],
                    T=None if outT is None else (outT if K_done == K else outT[:, :K_done]),
                    t=t if K_done == K else t[:K_done], stats=stats,
                    dense=DenseOutput(solver, problem, t, nsub, outL, outT, K_done))
    if specs:
        res.t_events = [np.array(x, dtype=float) for x in t_events]
        res.L_events = [np.array(x, dtype=float).reshape(-1, n) for x in L_events]
        res.T_events = [np.array(x, dtype=float).reshape(-1, N, N) for x in T_events] if outT is not None else None
    return res


def _refusal_note(control, work: Work, planned: float, solver) -> str:
    """The step control's word on a refused run (the growth its probe saw, the reachable accuracy)."""
    note = getattr(control, "refusal_note", None)
    return note(work.done + planned, work.max_steps, solver.order) if note is not None else ""


def _loop(solver, problem, t, nsub, hs, specs, t_events, L_events, T_events, fps, stats, bar, check):
    """The chunked run; returns ``(outL, outT, number of output times reached)``."""
    B = problem.B
    steps = int(nsub.sum())
    target = float(options["chunk_seconds"])
    key = cost_key(solver, problem)
    flows = max(1, B * fps)  # elementary flows per step, whole ensemble
    rate = SECONDS_PER_FLOW.get(key)
    floor = first_chunk_flows(problem.N)
    first = floor if rate is None else max(floor, target / rate)
    if specs:
        cap = max(1, min(EVENT_CHUNK_STEPS, int(first // flows)))
    else:
        cap = steps if steps * flows <= first else max(1, int(first // flows))
    if not specs and cap >= steps and (check is None or (check.out_idx is not None or not problem.with_attitude)
                                       and not check.early_marks.size):
        # one call, no chunk grid: the run (stopping at the check's samples between output times), then the check
        ahead = check.ahead(check.marks.size) if check is not None else None  # (the companions meanwhile)
        t_start = time.perf_counter()
        if check is not None and check.out_idx is None:
            Ls, Lf = _sampled_run(solver, problem, t, nsub, hs, check)
            Ts = None
        else:
            Ls, Ts = solver.advance(problem, problem.L0, problem.T0, t, nsub, h=hs)
            if Ts is not None:  # the start exactly (the attitude's shift correction rounds at t[0] too), as in chunks
                Ts[:, 0] = problem.T0
            Lf = Ls[check.members][:, check.out_idx] if check is not None else None
        learn(key, time.perf_counter() - t_start, steps * flows)
        check_finite(Ls, t, problem)
        stats["chunks"] = 1
        if bar is not None:
            bar.update(steps * B)
        if check is not None:
            check.update(check.marks.size, Lf, ahead)
        return Ls, Ts, t.size
    return _chunks(solver, problem, t, nsub, hs, specs, t_events, L_events, T_events, flows, cap, target, key,
                   bar, stats, check)


def _sampled_run(solver, problem, t, nsub, hs, check):
    """The whole run (no attitude) in one call that stops at the output times and at the check's samples
    between them: ``(states at the output times, the checked members' states at the samples)``."""
    cs = check.cs
    points, at_out, at_samples = merge(cs, check.marks)
    grid, ns, h = stops(t, cs, nsub, hs, points)
    L, _ = solver.advance(problem, problem.L0, None, grid, ns, h=h)
    return L[:, at_out], L[check.members][:, at_samples]


def _chunks(solver, problem, t, nsub, hs, specs, t_events, L_events, T_events, flows, cap, target, key, bar, stats,
            check):
    B, n, N = problem.B, problem.n, problem.N
    K = t.size
    outL = np.empty((B, K, n))
    outT = np.empty((B, K, N, N)) if problem.with_attitude else None
    outL[:, 0] = problem.L0
    if outT is not None:
        outT[:, 0] = problem.T0
    cs = np.concatenate([[0], np.cumsum(nsub)])
    steps = int(cs[-1])
    samples = check.marks if check is not None else np.zeros(0, dtype=np.int64)
    early = check.early_marks if check is not None else samples  # (the run stops at the check's early judgements)
    Lc = problem.L0
    Tc = problem.T0
    carry = None  # the exact state behind Lc (compensated low parts), from the solver
    s0 = 0
    gprev = None  # event values at the state of s0
    counts = [0 for _ in specs]
    while s0 < steps:
        t_start = time.perf_counter()
        s1 = min(steps, s0 + cap)
        k = int(np.searchsorted(early, s0, side="right"))
        if k < early.size:
            s1 = min(s1, int(early[k]))
        outs = np.arange(np.searchsorted(cs, s0, side="right"), np.searchsorted(cs, s1, side="right"))
        new = np.arange(np.searchsorted(samples, s0, side="right"), np.searchsorted(samples, s1, side="right"))
        if specs:  # every step point
            grid, ns, h = stops(t, cs, nsub, hs, np.arange(s0, s1 + 1))
            out_pos = cs[outs] - s0
            sample_pos = samples[new] - s0
        else:  # the chunk's start, the output times and samples inside it, and its end
            marks, out_pos, sample_pos = merge(cs[outs], samples[new])
            if marks.size == 0 or marks[-1] != s1:
                marks = np.append(marks, s1)
            grid, ns, h = stops(t, cs, nsub, hs, np.concatenate([[s0], marks]))
            out_pos, sample_pos = out_pos + 1, sample_pos + 1  # (the chunk's start first)
        ahead = check.ahead(int(new[-1]) + 1) if new.size else None  # (the companions meanwhile)
        Ls, Ts = solver.advance(problem, Lc, Tc, grid, ns, h=h, carry=carry)
        carry = solver.last_carry
        check_finite(Ls, grid, problem)
        if outs.size:
            outL[:, outs] = Ls[:, out_pos]
            if outT is not None:
                outT[:, outs] = Ts[:, out_pos]
        if bar is not None:
            bar.update((s1 - s0) * B)
        if new.size:
            check.update(int(new[-1]) + 1, Ls[check.members][:, sample_pos], ahead)
        if specs:
            stop = _events_in_chunk(solver, problem, grid, Ls, Ts, specs, gprev, counts, t_events, L_events,
                                    T_events)
            gprev = stop[1]
            if stop[0] is not None:
                stats["terminal"] = True
                stats["chunks"] += 1
                te = stop[0]
                sgn = 1.0 if t[-1] >= t[0] else -1.0
                return outL, outT, int(np.sum(sgn * (t - te) <= 0))
        Lc = Ls[:, -1]
        Tc = None if Ts is None else Ts[:, -1]
        stats["chunks"] += 1
        elapsed = time.perf_counter() - t_start
        if not specs:
            learn(key, elapsed, (s1 - s0) * flows)
        s0 = s1
        if s0 < steps:  # size the next chunk from this one's time (at most 8x growth)
            cap = int(min(8 * cap, max(1, cap * target / max(elapsed, 1e-6))))
            if specs:
                cap = min(cap, EVENT_CHUNK_STEPS)
    return outL, outT, K


def _events_in_chunk(solver, problem, grid, Ls, Ts, specs, gprev, counts, t_events, L_events, T_events):
    """Evaluate the event functions at the chunk's step states; locate crossings. Returns
    (time of a terminal event or None, event values at the chunk's last state)."""
    from scipy.optimize import brentq

    s = problem.scale
    L = Ls[0]
    vals = np.empty((grid.size, len(specs)))
    for i in range(grid.size):
        if i == 0 and gprev is not None:
            vals[0] = gprev
            continue
        for e, sp in enumerate(specs):
            vals[i, e] = sp.value(problem.user_time(grid[i]), L[i] * s)
    hits = []
    for e, sp in enumerate(specs):
        v = vals[:, e]
        up = (v[:-1] < 0) & (v[1:] >= 0)
        down = (v[:-1] > 0) & (v[1:] <= 0)
        cross = up if sp.direction > 0 else down if sp.direction < 0 else (up | down)
        if gprev is None and v[0] == 0.0:  # a zero at the run's first time is an event, as in solve_ivp
            cross[0] = sp.direction == 0 or (v[1] >= 0 if sp.direction > 0 else v[1] <= 0)  # ((g <= 0) & (g_new >= 0)
            # upwards, (g >= 0) & (g_new <= 0) downwards: a g that stays 0 is both)
        for j in np.flatnonzero(cross):
            hits.append((int(j), e))
    hits.sort()
    T = None if Ts is None else Ts[0]
    for j, e in hits:
        sp = specs[e]
        y, yT = L[j:j + 1], None if T is None else T[j:j + 1]
        t0, t1 = grid[j], grid[j + 1]
        if vals[j, e] == 0.0:  # (only at the run's first time: a later zero is the end of the step before)
            te, Le, Te = t0, L[j], None if yT is None else yT[0]
        else:
            if vals[j + 1, e] == 0.0:
                te = t1
            else:
                def f(tau):
                    Lx = solver.advance(problem, y, None, np.array([t0, tau]), np.ones(1, dtype=np.int64))[0]
                    return sp.value(problem.user_time(tau), Lx[0, -1] * s)
                f0, f1 = f(t0), f(t1)
                if f0 == 0.0:
                    te = t0
                elif (f0 < 0.0) != (f1 < 0.0) and f1 != 0.0:
                    lo, hi = (t0, t1) if t1 > t0 else (t1, t0)
                    te = brentq(f, lo, hi, xtol=4 * np.finfo(float).eps * max(abs(lo), abs(hi), 1e-300),
                                rtol=4 * np.finfo(float).eps, maxiter=200)
                else:
                    # the re-integrated step lost the grid's sign change (g ~ 0 at the step's end to
                    # round-off, or a step far too long for the motion, |omega| dt >> 1): the crossing
                    # seen on the grid, at the step's end
                    te = t1
            Lx, Tx = solver.advance(problem, y, yT, np.array([t0, te]), np.ones(1, dtype=np.int64))
            Le, Te = Lx[0, -1], None if Tx is None else Tx[0, -1]
        t_events[e].append(problem.user_time(te))
        L_events[e].append(Le * s)
        if Te is not None:
            T_events[e].append(Te)
        counts[e] += 1
        if sp.max_count is not None and counts[e] >= sp.max_count:
            return te, vals[-1]
    return None, vals[-1]


class DenseOutput:
    """Dense output of a fixed-step run (module docstring): ``dense(tq)`` -> ``(L (B, M, n), T or None)``
    at scaled times ``tq``, re-integrated from the stored output states. A plain object (no closure):
    it pickles and deep-copies with its run."""

    def __init__(self, solver, problem, t, nsub, outL, outT, K_done):
        self.solver, self.problem, self.t, self.nsub = solver, problem, t, nsub
        self.outL, self.outT, self.K_done = outL, outT, K_done

    def __call__(self, tq):
        return dense_states(self.solver, self.problem, self.t, self.nsub, self.outL, self.outT, tq, self.K_done)


def dense_states(solver, problem, t, nsub, outL, outT, tq, K_done):
    """States at the scaled times ``tq`` (M,) by re-integration from stored output states."""
    tq = np.asarray(tq, dtype=float)
    B, n, N = problem.B, problem.n, problem.N
    M = tq.size
    L = np.empty((B, M, n))
    T = np.empty((B, M, N, N)) if outT is not None else None
    if t.size == 1 or K_done == 1:
        bad = np.flatnonzero(tq != t[0])
        if bad.size:
            raise ValueError(f"dense output is defined on the run's time span only; t = {problem.user_time(tq[bad[0]]):g} "
                             f"is outside")
        L[:] = outL[:, :1]
        if T is not None:
            T[:] = outT[:, :1]
        return L, T
    sgn = 1.0 if t[-1] > t[0] else -1.0
    lo, hi = sorted((t[0], t[K_done - 1]))
    outside = np.flatnonzero((tq < lo) | (tq > hi))
    if outside.size:
        raise ValueError(
            f"dense output is defined on the run's time span [{problem.user_time(lo):g}, {problem.user_time(hi):g}] "
            f"only; got t = {problem.user_time(tq[outside[0]]):g}"
        )
    k_of = np.clip(np.searchsorted(sgn * t[:K_done], sgn * tq, side="right") - 1, 0, K_done - 2)
    one = np.ones(1, dtype=np.int64)
    for k in np.unique(k_of):
        idx = np.flatnonzero(k_of == k)
        hk = (t[k + 1] - t[k]) / nsub[k]
        j = np.clip(np.floor((tq[idx] - t[k]) / hk).astype(np.int64), 0, nsub[k])
        js = np.unique(j)
        # states at the step points t_k + j hk (same steps as the run)
        pts = np.concatenate([[t[k]], t[k] + js[js > 0] * hk])
        Lk, Tk = outL[:, k], (None if outT is None else outT[:, k])
        if pts.size > 1:  # the run's own steps hk (same numbers as the run at its step points)
            Ls, Ts = solver.advance(problem, Lk, Tk, pts, np.diff(np.concatenate([[0], js[js > 0]])).astype(np.int64),
                                    h=np.full(pts.size - 1, hk))
        else:
            Ls, Ts = Lk[:, None], (None if Tk is None else Tk[:, None])
        pos = {int(v): i for i, v in enumerate(np.concatenate([[0], js[js > 0]]))}
        for q, jq in zip(idx, j):
            i = pos[int(jq)]
            tj = pts[i]
            if tq[q] == tj:
                L[:, q] = Ls[:, i]
                if T is not None:
                    T[:, q] = Ts[:, i]
                continue
            Lx, Tx = solver.advance(problem, Ls[:, i], None if Ts is None else Ts[:, i], np.array([tj, tq[q]]), one)
            L[:, q] = Lx[:, -1]
            if T is not None:
                T[:, q] = Tx[:, -1]
    return L, T
