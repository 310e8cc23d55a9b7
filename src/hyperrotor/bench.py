"""Quick work-precision run of the classical solvers (``hyperrotor bench``).

Each method of :func:`hyperrotor.simulate` is run at several accuracies on a
problem with an exact solution, and its warm wall time (JIT compiled, best of
``repeats``) is recorded against its error

.. math:: \\text{error} = \\max_t \\lVert\\omega(t) - \\omega_\\text{exact}(t)\\rVert_\\infty / \\lVert\\omega_0\\rVert_\\infty .

Problems: ``"quartet"``, the paper's 5D body with kappa = 1/2 (eqs. 84-85) over
t in [0, 200] against the closed form of eqs. 96-110; ``"euler-poinsot"``, a 3D
asymmetric top over t in [0, 100] against the Jacobi-elliptic solution. The full
study with more problems, Casimir drift and ensemble throughput is
``benchmarks/work_precision_classical.py``.
"""
from __future__ import annotations

import csv
import math
import sys
import time
from dataclasses import asdict, dataclass, is_dataclass
from typing import Callable, Sequence

import numpy as np

from . import _validate
from .plotting import plot_work_precision  # the figure of this module's points (drawn in plotting)

__all__ = ["best_of", "best_of_interleaved", "WorkPrecisionPoint", "work_precision", "n_runs", "estimate_seconds", "speedup_at", "write_csv",
           "plot_work_precision", "print_table", "BENCH_PROBLEMS", "BENCH_SPANS", "BENCH_METHODS"]

#: Problems of :func:`work_precision`.
BENCH_PROBLEMS = ("quartet", "euler-poinsot")
#: Dimension N and final time t_end of each problem (its output grid: 101 times on [0, t_end]).
BENCH_SPANS = {"quartet": (5, 200.0), "euler-poinsot": (3, 100.0)}

_SETTINGS = {  # method -> (keyword, values): hyperrotor's integrators by step, scipy by tolerance
    "splitting2": ("dt", (0.02, 0.005, 0.001)),
    "splitting4": ("dt", (0.1, 0.03, 0.01, 0.003)),
    "splitting6": ("dt", (0.5, 0.3, 0.1, 0.05, 0.02)),
    "splitting8": ("dt", (1.0, 0.6, 0.4, 0.3, 0.2, 0.15, 0.1)),
    "splitting10": ("dt", (2.0, 1.0, 0.67, 0.5, 0.4, 0.3)),
    "moser-veselov": ("dt", (0.03, 0.01, 0.003)),
    "DOP853": ("rtol", (1e-6, 1e-8, 1e-10, 1e-12, 1e-13)),
    "RK45": ("rtol", (1e-4, 1e-6, 1e-8)),
}

#: Methods of :func:`work_precision` (the keys of its settings table).
BENCH_METHODS = tuple(_SETTINGS)

#: Seconds of one call of every setting of a method together: about twice the best of 3 measured on an idle
#: 2-core AMD EPYC (session 46: ``hyperrotor bench`` 7.7 s wall; first measured on a shared, loaded machine, 46 s,
#: where these were 3-8x higher and the estimate 4x the run here); used by :func:`estimate_seconds` only, to refuse
#: absurd runs before they start.
_TYPICAL_SECONDS = {
    "quartet": {"splitting2": 0.07, "splitting4": 0.07, "splitting6": 0.03, "splitting8": 0.02,
                "splitting10": 0.02, "moser-veselov": 0.75, "DOP853": 1.3, "RK45": 0.5},
    "euler-poinsot": {"splitting2": 0.01, "splitting4": 0.01, "splitting6": 0.01, "splitting8": 0.01,
                      "splitting10": 0.01, "moser-veselov": 0.08, "DOP853": 0.6, "RK45": 0.18},
}


@dataclass(frozen=True)
class WorkPrecisionPoint:
    """One run: ``method`` with ``setting`` (``dt`` or ``rtol`` = ``value``) took ``seconds`` for ``error``
    (``dt``: the step the run took, every output interval cut into equal steps).

    ``N`` and ``t_end``: the problem's dimension and final time (the figure's titles name them).
    """

    problem: str
    method: str
    setting: str
    value: float
    error: float
    seconds: float
    N: int | None = None
    t_end: float | None = None


def best_of(fn: Callable, repeats: int, *, warmup: bool = False):
    """Best wall time of ``repeats`` calls of ``fn()`` and the last result: ``(seconds, result)``.

    ``warmup=True`` makes one untimed call first (JIT compilation, caches). The
    benchmark scripts in ``benchmarks/`` time with this function too.
    """
    if int(repeats) < 1:
        raise ValueError(f"repeats must be >= 1, got {repeats}")
    out = fn() if warmup else None
    best = np.inf
    for _ in range(int(repeats)):
        start = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - start)
    return best, out


def best_of_interleaved(fns: Sequence[Callable], repeats: int, *, seconds: float = 0.0) -> tuple[list, list]:
    """Best wall time of each of ``fns`` over rounds that call them in turn, and the last result of each:
    ``([seconds, ...], [result, ...])``. A drift of the machine's load hits all of them alike, so their ratios are
    robust (timing one after the other, a ratio of two sub-millisecond calls moved by 0.3-0.5 between runs).

    At least ``repeats`` rounds, more until the rounds took about ``seconds`` in all (the first round, a
    warm-up, is timed too).
    """
    if int(repeats) < 1:
        raise ValueError(f"repeats must be >= 1, got {repeats}")
    best = [np.inf] * len(fns)
    out: list = [None] * len(fns)
    rounds, done, spent = int(repeats), 0, 0.0
    while done < rounds:
        for i, fn in enumerate(fns):
            start = time.perf_counter()
            out[i] = fn()
            elapsed = time.perf_counter() - start
            best[i] = min(best[i], elapsed)
            spent += elapsed
        done += 1
        if done == 1 and seconds > 0.0:
            rounds = max(rounds, min(10_000, int(seconds / max(spent, 1e-9))))
    return best, out


def _problem(name: str):
    from hyperrotor import Inertia, RigidBody
    from hyperrotor.classical import euler_poinsot, quartet_solution

    if name == "quartet":
        body = RigidBody(Inertia.quartet(0.5))
        w0 = np.array([0.3, -0.5, 0.8, 1.0, 0.2, -0.7, 0.4, 0.6, -0.9, 0.5])
        t = np.linspace(0.0, BENCH_SPANS[name][1], 101)
        return body, w0, t, quartet_solution(0.5, w0, t)
    if name == "euler-poinsot":
        moments = np.array([2.0, 3.0, 4.0])
        w0 = np.array([0.6, 1.0, -0.5])
        t = np.linspace(0.0, BENCH_SPANS[name][1], 101)
        return RigidBody(moments), w0, t, euler_poinsot(moments, w0, t)
    raise ValueError(f"unknown problem {name!r}; allowed: {', '.join(BENCH_PROBLEMS)}")


def _settings(problem: str, method: str) -> tuple[str, list[float]]:
    """``(keyword, values)`` that :func:`work_precision` runs ``method`` at on ``problem``: the tolerances, or the
    steps the runs take, distinct (``simulate`` cuts each output interval of length ``g`` into ``ceil(g / dt)``
    equal steps, so a ``dt`` of 0.6 runs at 0.5 on the quartet's intervals of 2, and 2 and 1 are one run on the
    3D top's intervals of 1)."""
    key, values = _SETTINGS[method]
    if key != "dt":
        return key, list(values)
    gap = BENCH_SPANS[problem][1] / 100.0  # (101 output times)
    used: list[float] = []
    for dt in values:
        h = gap / math.ceil(gap / dt - 1e-12)
        if not any(math.isclose(h, u, rel_tol=1e-12) for u in used):
            used.append(h)
    return key, used


def n_runs(problems: Sequence[str], methods: Sequence[str] | None = None) -> int:
    """Number of timed settings :func:`work_precision` runs for ``problems`` x ``methods``."""
    methods = list(_SETTINGS) if methods is None else list(methods)
    return sum(len(_settings(p, m)[1]) for p in problems for m in methods if m in _SETTINGS)


def estimate_seconds(problems: Sequence[str], methods: Sequence[str] | None = None, repeats: int = 2) -> float:
    """Rough wall time of :func:`work_precision` over ``problems`` (before any work).

    Each setting is called ``repeats + 1`` times (one warm-up); the per-call
    times of :data:`_TYPICAL_SECONDS` were measured on a 2-core machine (the
    estimate is good to a factor of about 3, about 2x on an idle machine), plus a few seconds for the imports
    and the first numba kernel load.
    """
    methods = list(_SETTINGS) if methods is None else list(methods)
    per_call = sum(_TYPICAL_SECONDS.get(p, {}).get(m, 1.0) for p in problems for m in methods)
    return 3.0 + (int(repeats) + 1) * per_call


def work_precision(problem: str = "quartet", methods: Sequence[str] | None = None, *, repeats: int = 2,
                   callback: Callable[[str], None] | None = None) -> list[WorkPrecisionPoint]:
    """Run every method at its accuracy settings; returns the measured points.

    Parameters
    ----------
    problem : one of :data:`BENCH_PROBLEMS`.
    methods : subset of ``splitting2/4/6/8/10``, ``moser-veselov``, ``DOP853``, ``RK45`` (default all).
    repeats : each run is timed ``repeats`` times after one warm-up call; the best time is kept.
    callback : called after each setting with a short message (``"quartet: DOP853 rtol=1e-08"``),
        e.g. a progress bar's update; :func:`n_runs` gives the number of calls.
    """
    from hyperrotor import simulate

    methods = list(_SETTINGS) if methods is None else [_validate.choice("methods", m, BENCH_METHODS) for m in methods]
    repeats = _validate.integer("repeats", repeats, minimum=1)
    if callback is not None and not callable(callback):
        raise TypeError(f"callback must be a function of one str (or None), got {_validate.fmt(callback)}")
    body, w0, t, exact = _problem(_validate.choice("problem", problem, BENCH_PROBLEMS))
    scale = float(np.max(np.abs(w0)))
    points = []
    for method in methods:
        key, values = _settings(problem, method)
        for value in values:
            best, traj = best_of(lambda: simulate(body, w0, t, method=method, **{key: value}), repeats,
                                 warmup=True)  # warm-up: JIT compile on the first splitting call
            err = float(np.max(np.abs(traj.omega - exact))) / scale
            points.append(WorkPrecisionPoint(problem, method, key, float(value), err, best, body.N, float(t[-1])))
            if callback is not None:
                callback(f"{problem}: {method} {key}={value:g}")
    return points


def speedup_at(points: Sequence[WorkPrecisionPoint], error: float, *, peer: str = "DOP853") -> dict | None:
    """Fastest run of any method reaching ``error`` vs the fastest ``peer`` run reaching it.

    Returns ``{"method", "seconds", "peer_seconds", "ratio"}`` or ``None`` when
    either side never reaches ``error``.
    """
    ok = [p for p in points if p.error <= error]
    ours = [p for p in ok if p.method != peer]
    theirs = [p for p in ok if p.method == peer]
    if not ours or not theirs:
        return None
    best = min(ours, key=lambda p: p.seconds)
    ref = min(theirs, key=lambda p: p.seconds)
    return {"method": best.method, "seconds": best.seconds, "peer_seconds": ref.seconds,
            "ratio": ref.seconds / best.seconds}


def write_csv(rows: Sequence, path) -> str:
    """Write rows as CSV, one line per row, the header from the first row's keys.

    ``rows``: dicts or dataclass instances (e.g. :class:`WorkPrecisionPoint`), all
    with the same fields. The benchmark scripts in ``benchmarks/`` write through
    this function too.
    """
    rows = [asdict(r) if is_dataclass(r) else dict(r) for r in rows]
    if not rows:
        raise ValueError("write_csv needs at least one row")
    with open(path, "w", newline="", encoding="utf-8") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    return str(path)


def print_table(points: Sequence[WorkPrecisionPoint], out=None) -> None:
    """Print the points as a table (problem, method, setting, error, time) to ``out`` (default stdout)."""
    out = sys.stdout if out is None else out  # looked up per call: sys.stdout may be replaced after import
    print(f"{'problem':<14} {'method':<11} {'setting':>14} {'error':>10} {'time [s]':>10}", file=out)
    for p in points:
        print(f"{p.problem:<14} {p.method:<11} {p.setting + '=' + format(p.value, 'g'):>14} "
              f"{p.error:>10.2e} {p.seconds:>10.4f}", file=out)
