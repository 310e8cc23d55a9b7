r"""Step control of the fixed-step methods: a given ``dt`` or an error target ``rtol``.

:class:`FixedStep` takes the largest step ``dt``; :class:`ErrorTarget` chooses the step so
that the whole-run error stays within ``rtol``:

.. math:: \max_t \|L(t) - L_\text{exact}(t)\|_\infty \le \mathrm{rtol}\,\max_t \|L(t)\|_\infty,

and the same for :math:`\omega` (they differ for stiff moment ratios, where the heavy
planes have small rates but carry most of ``L``), the maxima over the run: its output times and the check's
samples between them (a grid ``[0, T]`` whose orbit turns through 3.7x larger rates between its two times
has errors up to 1.2 rtol relative to the two returned states' own maxima); a target looser than
:data:`LOOSEST_RTOL` is run to it. Either way each output interval is
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
   work of the steps :math:`h`) from step :math:`h =` :data:`PROBE_FIRST_TURN` :math:`/\omega_\text{max}`,
   refined (x1/4) while not asymptotic (:math:`e > ` :data:`ASYMPTOTIC`) and enlarged (x4) while
   at round-off. The error is carried to the end of the run with the growth seen inside the
   window (:func:`growth_to_end`: like :math:`t` on a regular orbit, Hairer, Lubich & Wanner,
   *Geometric Numerical Integration*, ch. X; like :math:`t^a`, :math:`a \le` :data:`PROBE_MAX_POWER`,
   when the window shows faster growth, e.g. a chaotic orbit), which gives the step :math:`h^*`
   for the target ``SAFETY * rtol``, and no longer than :data:`MAX_TURN` :math:`/\omega_\text{max}` (half a
   turn of the fastest reachable rate per step: on stiff bodies, moments over 12 decades, longer steps
   put the fast planes' flows in resonance with the step and the Richardson estimates below missed the
   bound 4-100-fold).
   A window of at least :data:`PROBE_COVER` of the run is the whole run (a short run, 40 radians of the
   fastest rate or less): it is sampled at output times (:func:`probe_samples`, up to
   :data:`~.richardson_check.CHECK_SAMPLES` samples, segments of an even number of steps of at most
   :math:`h`), and its two runs are kept (:class:`~.richardson_check.ProbeRuns`) when asymptotic enough to
   be the check's companions (step 4). Its first step turns the fastest rate by up to
   :data:`PROBE_FIRST_TURN_WHOLE` radians as long as it spans at most :data:`PROBE_WHOLE_GAPS` output intervals
   (a run whose steps the output grid sets is then checked by fewer probe steps: on 100 output intervals over
   T = 20, 30 instead of 51-60 for the 3D top and the 5D quartet). Such a probe at round-off is not enlarged
   when no output interval is longer than its step (the run's steps cannot be longer than the output intervals).
3. *Budget.* All planned work (probes, run, check) above ``max_steps`` is refused here,
   before the run starts (:class:`~.chunks.Work`).
4. *Check inside the run* (:class:`~.richardson_check.RichardsonCheck`, costing :math:`1/c + 1/(c c_2)` of the run for
   every member, each judged on its own: checking the :data:`PROBE_MEMBERS` fastest
   only left a 100-member ensemble of similar rates with 9 members up to 2300x over rtol 1e-6, silently; its memory,
   about 1 kB per member, is priced with the output. Ensembles run member by member, with events or on dask workers,
   check the same members, run on their own before the members run: about 1.3-1.6x the members' run; a dask
   ensemble's check, in this process, covers up to :data:`CHECK_MEMBERS`, the fastest beyond). Beside the
   run at :math:`h^*` two companion runs of the same members advance with steps :math:`c` and :math:`c c_2` times longer
   (:math:`2 \le c \le` :data:`~.richardson_check.COMPANION_RATIO`, as large as keeps the first companion's error below
   :data:`~.richardson_check.COMPANION_ASYMPTOTIC`; :math:`2 \le c_2 \le c`, the second's below
   :data:`~.richardson_check.SECOND_COMPANION_ASYMPTOTIC`) between :data:`~.richardson_check.CHECK_SAMPLES` sample points of the run.
   The three runs give the observed order :math:`q \le p` (:func:`~.richardson_check.observed_order`, from
   :math:`|y_{ch} - y_{cc_2h}| / |y_h - y_{ch}| = c^q (c_2^q - 1)/(c^q - 1)`: stiff
   problems, steps far outside the asymptotic regime show :math:`q < p`), and at every sample
   :math:`e \approx |y_{h^*} - y_{ch^*}| / (c^q - 1)` estimates the run's own error (with
   :math:`c` the smallest ratio of companion to run step over the samples, so the estimate errs
   on the safe side; :math:`q < 1/2`: the difference itself). A run too short for longer
   companion steps is checked against companions at half and quarter steps instead. A run covered by
   the probe's two runs whose steps are 2 to :data:`~.richardson_check.PROBE_RATIO` times the run's
   takes those as its companions (:math:`c` the smallest ratio over the segments, :math:`c_2 = 2`): its
   check costs no integration step (short runs, whose steps the output grid makes much shorter than
   :math:`h^*`: on 100 output intervals over T = 20 the 3D top and the 5D quartet take 130 steps in all
   at rtol 1e-6 ... 1e-12, 100 of them the run's). The companions depend on the run only where they are
   compared with it, so with a second core they run there while the run advances (:func:`~.chunks.pair_ahead`:
   the same compiled calls and numbers, one chunk at a time, from the main thread; the check's integration then
   costs CPU time, not wall time: rtol calls 1.1-1.4x the fixed-step run at their step instead of 1.4-1.75x
   where the companions take 0.2 ms or more, ``benchmarks/README.md``). The run
   is accepted when the estimate stays within
   ``ACCEPT * rtol``. It is judged at its end and, a run of :data:`~.richardson_check.EARLY_STOP_FLOWS` or more,
   also at an eighth, a quarter and half of its samples (fixed points, not the ends of its chunks, whose lengths
   follow the machine's speed: the same call takes the same steps and gives the same numbers everywhere), and
   stopped at the first of these where the estimate exceeds that, or
   (from :data:`~.richardson_check.PROJECT_AFTER` of the run on) where its linear projection to the end exceeds it
   :data:`~.richardson_check.PROJECT_MARGIN`-fold, and re-run at
   :math:`h \leftarrow 0.9\,h\,(\mathrm{SAFETY\cdot rtol}/e_\text{end})^{1/q}` (``q`` the observed order held
   between :math:`p/2` and :math:`p`; :math:`p` above :data:`~.richardson_check.ASYMPTOTIC`). The samples
   also show how the error grows: linearly on regular orbits, like :math:`e^{\lambda t}` on
   chaotic ones (GNI ch. X; the envelope of the estimates over the last two doublings of the
   time done), which the messages below name.
   Richardson's differences do not see round-off: an accepted run whose differences show the
   orbit amplifying it towards ``rtol`` (a chaotic orbit, plain arithmetic) is repeated at the
   same step in compensated storage (``RichardsonCheck._check_roundoff``); a failed check whose differences show
   it re-runs at the shorter step in compensated storage at once (refined in plain arithmetic, the differences
   carry the amplified round-off, and a chaotic 40-member ensemble at rtol 1e-6 was refined on it until
   :class:`UnreachableAccuracyError`).
5. *Unreachable accuracy.* The re-run's step is priced first: above the budget the call
   stops with :class:`~.base.StepBudgetError` naming the estimated error, its growth
   :math:`e^{\lambda T}` when the samples grow exponentially (a chaotic orbit), and the
   accuracy reachable within the budget; when :data:`MAX_RETRIES` re-runs do not meet ``rtol`` (a re-run stopped
   at a later early judgement than any before made progress and is not counted)
   (round-off, or exponential growth that outruns the order of the method) the call stops with
   :class:`UnreachableAccuracyError` naming the reachable accuracy, instead of grinding or
   returning a result that misses the bound.

Cost. The probe's two runs (steps ``h`` and ``2h``) and the check's two companions each advance in one
compiled call (:meth:`~.driver.FixedStepSolver.advance_pair`; the splittings run both in the unrolled
kernel's ``run_pair`` or in :func:`~._kernels.split_run_pair`), and a run that fits in one chunk is one call
(stopping at the samples between output times when they are not output times), its companions the next. The
bookkeeping is compiled too: the rate bound (:func:`_coupled_rates`, one call), the probe's window and its
estimate (:func:`window_samples`, :func:`probe_envelope`), the check's plan (its samples, the
companions' steps and ratios: :func:`~.richardson_check.check_plan`), the distances of the runs, the estimate
with its observed order and the round-off test, and the run's stops at samples between output times
(:func:`~.chunks.stops`, :func:`~.chunks.merge`). What remains over a fixed-step call is 0.2-0.37 ms per call on
the 3D top and the 5D quartet (T = 20 ... 200, rtol 1e-6: Python, and the companions' few steps); the compiled
work of the probe (0.06-0.5 of the run's steps) and of the companions (:math:`1/c + 1/(c c_2)`, 0.3-0.55; none
when the probe's runs are the companions) is the price of the promise (``benchmarks/README.md``,
step_control.py).

The timed probes also give the cost per step: a run estimated to take longer than
``options["slow_run_warning_seconds"]`` gives a ``UserWarning`` before it starts
(:func:`run_estimate` prices a call without running it).
"""
from __future__ import annotations

import itertools
import math
from functools import lru_cache
from typing import Any

import numpy as np

from hyperrotor import _validate
from hyperrotor._jit import jit
from hyperrotor._warn import warn
from hyperrotor._options import options

from .base import Problem, StepBudgetError, nsub_for
from .chunks import Work, advance_pair_chunked, cost_key, seconds_per_flow
from ._kernels import relative_difference, row_scales
from .richardson_check import (ASYMPTOTIC, CHECK_SAMPLES, COMPANION_ASYMPTOTIC, COMPANION_RATIO, PROBE_RATIO, SAFETY,
                               AccuracyWarning, CheckFailed, ProbeRuns, RichardsonCheck)

__all__ = ["FixedStep", "ErrorTarget", "StepBudgetError", "UnreachableAccuracyError", "AccuracyWarning", "rate_bound",
           "growth_to_end", "CHECK_MEMBERS"]

_EPS = float(np.finfo(float).eps)
#: length of the probe interval in turns of the fastest rate (20 radians: a few periods)
PROBE_TURNS = 20.0
#: the probe's first step turns the fastest rate (the rate bound) by this angle (radians) ...
PROBE_FIRST_TURN = 1.0
#: ... a probe of the whole run by up to this angle, as long as the step spans at most ``PROBE_WHOLE_GAPS`` output
#: intervals (its runs are then the check's companions for a run stepping once per interval: step ratios <= 8)
PROBE_FIRST_TURN_WHOLE = 2.0
PROBE_WHOLE_GAPS = 0.75 * PROBE_RATIO
#: ensemble members probed (the fastest ones): the step is one for all members
PROBE_MEMBERS = 8
#: the check of a dask ensemble, run in this process before the members run on the workers, covers up to this many
#: members (the fastest beyond); every other run's check covers every member (its memory is priced with the output:
#: :func:`~.richardson_check.check_bytes`)
CHECK_MEMBERS = 4096
#: the probe extrapolates its error to the end of the run like t^a, 1 <= a <= this (the steady growth it sees)
PROBE_MAX_POWER = 4.0
#: no extrapolation beyond this factor of the probed step (the error model is asymptotic in h)
MAX_STEP_GROWTH = 8.0
#: a probe window of at least this fraction of the run is the whole run (sampled at output times, and the
#: check takes its two runs as companions: :class:`~.richardson_check.ProbeRuns`) ...
PROBE_COVER = 0.5
#: ... when it has this many output times at least
PROBE_COVER_SAMPLES = 8
#: re-runs at a shorter step before the call gives up with UnreachableAccuracyError
MAX_RETRIES = 3
#: no step turns the fastest reachable rate (the rate bound) by more than this angle (radians)
MAX_TURN = math.pi


class UnreachableAccuracyError(ValueError):
    """``rtol`` cannot be met at a reasonable cost: the error grows exponentially (a chaotic orbit)
    or sits at round-off. The message names the estimated growth and the reachable accuracy."""



def _plane_rate_bounds(moments: np.ndarray, L0: np.ndarray) -> np.ndarray:
    r""":math:`\min(|L|, \sqrt{2EI_a})/I_a` per row of ``L0`` (rows, n) and plane ``a``: no rate of plane
    ``a`` on the orbit exceeds it (from the Casimir :math:`|L|^2` and the energy). ``moments``: ``(n,)`` or one
    row per row of ``L0``. NumPy, not compiled: callers that price work before running it (``lyapunov``) then
    refuse without loading numba (about 1 s in a fresh process)."""
    m = moments.reshape(-1, L0.shape[1])
    L2 = L0 * L0
    C = np.sqrt(L2.sum(axis=1))[:, None]
    E2 = (L2 / m).sum(axis=1)[:, None]
    return np.minimum(C, np.sqrt(E2 * m)) / m


def rate_bound(moments: np.ndarray, L0: np.ndarray) -> np.ndarray:
    r"""Per row of ``L0`` (rows, n): :math:`\max_a \min(|L|, \sqrt{2EI_a})/I_a`, a bound on every
    angular velocity on the orbit (from the Casimir :math:`|L|^2` and the energy)."""
    W = _plane_rate_bounds(moments, L0)
    return W.max(axis=1) if W.size else np.zeros(L0.shape[0])


def _orbit_rates(problem: Problem) -> np.ndarray:
    """Per-member bound on the rates reachable on the orbit (module docstring, step 1)."""
    m = problem.moments
    wmax_b = _coupled_rates(m, problem.L0, *_triples(problem.N))
    if problem.kick:
        tq = float(np.max(np.abs(problem.torque) / m))
        wmax_b = np.maximum(wmax_b, max(tq * problem.span, tq ** 0.5))
    return wmax_b


@jit
def _coupled_rates(moments, L0, tc, ta, tb):  # pragma: no cover - jitted
    r"""Per row of ``L0 (rows, n)``: the largest of the plane rate bounds :math:`W_a` (:func:`_plane_rate_bounds`,
    computed here in the same way) and of the linearised frequencies :math:`W_c\sqrt{|(I_c-I_a)(I_c-I_b)|/(I_aI_b)}`
    of the coupled triples ``(tc, ta, tb)`` (:func:`_triples`). Compiled (once per call of the step control)."""
    B, n = L0.shape
    out = np.zeros(B)
    W = np.empty(n)
    for b in range(B):
        C2 = 0.0
        E2 = 0.0
        for a in range(n):
            x = L0[b, a] * L0[b, a]
            C2 += x
            E2 += x / moments[a]
        C = math.sqrt(C2)
        w = 0.0
        for a in range(n):
            W[a] = min(C, math.sqrt(E2 * moments[a])) / moments[a]
            w = max(w, W[a])
        for i in range(tc.size):
            Ic, Ia, Ib = moments[tc[i]], moments[ta[i]], moments[tb[i]]
            # (the two ratios apart: moments of 1e300 and 2 overflowed the product to inf, and the step to 0)
            w = max(w, W[tc[i]] * (math.sqrt(abs(Ic - Ia) / Ia) * math.sqrt(abs(Ic - Ib) / Ib)))
        out[b] = w
    return out


@lru_cache(maxsize=32)
def _triples(N: int):
    """Plane indices (c, a, b) of every coupled triple {ij, ik, jk}, each plane in turn as c (cached; NumPy: N = 200
    has 1.3 million triples)."""
    plane_i, plane_j = np.triu_indices(N, 1)
    comp = np.zeros((N, N), dtype=np.int64)
    comp[plane_i, plane_j] = np.arange(plane_i.size)
    r = np.arange(N)
    i, j, k = np.nonzero((r[:, None, None] < r[None, :, None]) & (r[None, :, None] < r[None, None, :]))  # i < j < k
    ij, ik, jk = comp[i, j], comp[i, k], comp[j, k]  # (in the order of the loops over i < j < k)
    # rows per triple (c, a, b): (ij, ik, jk), (ik, ij, jk), (jk, ij, ik)
    cols = tuple(np.ascontiguousarray(np.stack(c, axis=1).ravel()) for c in ((ij, ik, jk), (ik, ij, ij), (jk, jk, ik)))
    for c in cols:
        c.setflags(write=False)
    return cols


@jit
def probe_samples(t, spacing, h):  # pragma: no cover - jitted
    """Where a probe of the whole run samples it, and its steps: ``(idx, grid, ms, longest step)``.

    ``idx``: indices of the output times ``t``, from ``t[0]`` each the last output time within ``spacing``
    of the one before (or the next one, when an interval is longer), the last output time included and a
    last gap shorter than ``spacing / 2`` merged into the one before; ``grid``: ``t[0]`` and their times;
    ``ms``: the even number of equal steps of at most ``h`` per segment (the run at twice the step takes
    half as many). Compiled.
    """
    K = t.size
    out = np.empty(K - 1, dtype=np.int64)
    n = 0
    prev = 0
    for k in range(1, K):
        if abs(t[k] - t[prev]) > spacing and k - 1 > prev:
            out[n] = k - 1
            n += 1
            prev = k - 1
        if abs(t[k] - t[prev]) > spacing:  # (an interval longer than spacing: a segment of its own)
            out[n] = k
            n += 1
            prev = k
    if n == 0 or out[n - 1] != K - 1:
        if n >= 1 and abs(t[K - 1] - t[out[n - 1]]) < 0.5 * spacing:
            n -= 1
        out[n] = K - 1
        n += 1
    idx = out[:n]
    grid = np.empty(n + 1)
    grid[0] = t[0]
    ms = np.empty(n, dtype=np.int64)
    longest = 0.0
    for i in range(n):
        grid[i + 1] = t[idx[i]]
        length = abs(grid[i + 1] - grid[i])
        ms[i] = 2 * max(1, int(math.ceil(length / (2.0 * h) * (1.0 - 1e-12))))
        longest = max(longest, length / ms[i])
    return idx, grid, ms, longest


@jit
def window_samples(t0, length, direction, k, m):  # pragma: no cover - jitted
    """A probe of the leading window from ``t0`` over ``length`` (``direction``: +1 or -1): ``(grid, ms, step)``,
    ``k`` equal segments (``grid``: their ends, ``t0`` first and the window's end exactly) of the same even number
    of equal steps, ``2 ceil(m / 2k)`` (about ``m`` in all), and that step. Compiled."""
    grid = np.empty(k + 1)
    for i in range(k):
        grid[i] = direction * (i * (length / k)) + t0
    grid[k] = direction * length + t0
    ms = np.full(k, 2 * max(1, int(math.ceil(m / (2 * k)))))
    return grid, ms, length / (k * ms[0])


@jit
def probe_envelope(y1, y2, moments, divisor):  # pragma: no cover - jitted
    r"""The probe's Richardson estimate up to each grid point: ``env[i]`` is the largest distance
    (:func:`~._kernels.relative_difference`, relative to the scales of ``y1``) between the runs ``y1`` (step
    :math:`h`) and ``y2`` (:math:`2h`) over the members and the grid points ``0 .. i``, over ``divisor``
    (:math:`2^p - 1`); NaN from the first NaN distance on (a run that failed). Compiled."""
    Lmax, Wmax = row_scales(y1, moments)
    d = relative_difference(y1, y2, moments, Lmax, Wmax)
    rows, S = d.shape
    env = np.empty(S)
    best = 0.0
    for i in range(S):
        for b in range(rows):
            x = d[b, i]
            if x != x or x > best:  # (a NaN is taken, and kept: comparisons with NaN are false)
                best = x
        env[i] = best / divisor
    return env


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


#: The loosest whole-run target the step control works to: a looser ``rtol`` is met by running to this one. The
#: Richardson estimates need companions in their asymptotic regime (errors below
#: :data:`~.richardson_check.COMPANION_ASYMPTOTIC`), which a looser target does not leave: a review found rtol 1e-2
#: met on L but exceeded 1.2-1.4-fold on omega (5 of ~530 random runs, splitting4), and rtol 0.05 refused as
#: unreachable on orbits where 0.01 was met with an error of 8.4e-4 (4 of 24 random 5D orbits). The tighter target
#: costs little: (rtol / 1e-3)^(1/p) times the steps (1.8x for order 4 at rtol 1e-2, 1.3x for order 8).
LOOSEST_RTOL = COMPANION_ASYMPTOTIC


class FixedStep:
    """Largest step ``dt`` (in the user's time units)."""

    rtol = None
    requested = None

    def __init__(self, dt: Any):
        self.dt = _validate.positive("dt", dt)

    def first_step(self, solver, problem: Problem, work: Work, bar=None) -> float:
        return self.dt * problem.scale  # (the driver checks the budget once it has counted the steps)

    def checker(self, solver, problem: Problem, nsub: np.ndarray, work: Work, bar=None):
        return None

    def verified_step(self, solver, problem, work, most=None, bar=None):
        """The step (nothing to verify: ``most``, the members a check would cover, and ``bar`` are unused)."""
        return self.first_step(solver, problem, work)

    def announce(self, solver, problem: Problem, h: float, steps: int | None = None) -> None:
        """Nothing: a given step is the caller's choice."""

    def __repr__(self) -> str:
        return f"FixedStep(dt={self.dt!r})"


class ErrorTarget:
    """Step from a whole-run error target ``rtol``: a probe guesses, the run's own check decides
    (see the module docstring)."""

    def __init__(self, rtol: Any):
        self.requested = _validate.tolerance("rtol", rtol)  # (what the caller asked for: stats["rtol"])
        self.rtol = min(self.requested, LOOSEST_RTOL)  # (the target the step control works to)
        self.seconds_per_step: float | None = None
        self.retries = 0
        self.reruns = 0  # (retries: the re-runs at shorter steps)
        self.furthest = 0.0  # the furthest fraction of the run a check stopped at before its end
        self.history: list = []  # (h, estimated error) of every checked run (partial ones too)
        self.last_growth = 0.0
        self.probe_note = ""  # the error growth the probe saw, when faster than PROBE_MAX_POWER allows
        self.roundoff_amplified = False  # the check saw round-off amplified towards rtol: compensated storage
        self.probe_runs: tuple = ()  # probes of the whole run whose two runs the check may take (ProbeRuns)
        self.still = False  # the run turns by less than eps: one step per output interval, no probe, no check

    def __repr__(self) -> str:
        return f"ErrorTarget(rtol={self.requested!r})"

    def _tightened(self) -> str:
        """What a message adds when the caller's rtol was looser than the step control works to."""
        return (f" (rtol = {self.requested:g} is run to {LOOSEST_RTOL:g}, the loosest target the step control "
                f"checks)" if self.requested > self.rtol else "")

    def _rates(self, problem: Problem) -> tuple:
        """``(rate bound per member, the checked members)`` of ``problem`` (computed once per problem)."""
        cached = getattr(self, "_rates_of", None)
        if cached is None or cached[0] is not problem:
            wmax_b = _orbit_rates(problem)
            members = (np.arange(problem.B) if problem.B <= PROBE_MEMBERS
                       else np.sort(np.argsort(wmax_b)[::-1][:PROBE_MEMBERS]))
            cached = self._rates_of = (problem, wmax_b, members)
        return cached[1:]

    def _members(self, problem: Problem) -> np.ndarray:
        return self._rates(problem)[1]

    def _checked(self, problem: Problem, most: int | None = None) -> np.ndarray:
        """The members the run's check covers: all (up to ``most``, the fastest beyond: :meth:`verified_step`)."""
        if problem.B <= PROBE_MEMBERS:
            return self._members(problem)
        if most is None or problem.B <= most:
            return np.arange(problem.B)
        return np.sort(np.argsort(self._rates(problem)[0])[::-1][:most])

    def first_step(self, solver, problem: Problem, work: Work, bar=None) -> float:
        """The probe (module docstring, steps 1-3): a step for ``SAFETY * rtol`` from a leading window
        (``bar``: a progress bar the probe's steps advance)."""
        span = problem.span
        B = problem.B
        self.retries = 0
        self.reruns = 0  # (retries: the re-runs at shorter steps)
        self.furthest = 0.0  # the furthest fraction of the run a check stopped at before its end
        self.history = []
        self.probe_note = ""
        self.roundoff_amplified = False
        self.probe_runs = ()
        self.still = False
        if B == 0 or span == 0.0:
            return max(span, 1.0)
        wmax_b, sel = self._rates(problem)
        wmax = float(wmax_b.max())
        self.still = wmax * span <= _EPS  # (one step over the run turns by less than eps: its error is eps^(p+1))
        if self.still or solver.flows_per_step(problem) == 0:
            return span  # nothing moves, or not at double precision: one step per output interval, no check
        p = solver.order
        target = SAFETY * self.rtol
        L0s = problem.L0[sel]
        Ms = problem.moments
        direction = 1.0 if problem.t[-1] >= problem.t[0] else -1.0

        def richardson(Pv, m, samples):
            """Error estimate (relative) of ~m steps over [0, Pv] from the same members at twice the
            step (1.5x the work of the m steps); ``(None, h)`` if a run failed. A probe of the whole run
            samples it at output times (:func:`probe_samples`) and keeps both runs for the check."""
            if Pv >= span and t.size > PROBE_COVER_SAMPLES:
                two = 2.0 * Pv / m  # (segments of at most j double steps: samples at most CHECK_SAMPLES)
                idx, tg, ms, h_probe = probe_samples(t, two * math.ceil(span / (CHECK_SAMPLES * two)), Pv / m)
            else:
                idx = None
                tg, ms, h_probe = window_samples(float(t[0]), Pv, direction, max(1, min(m // 2, samples)), m)
            k = ms.size
            steps = int(ms.sum())
            work.refuse(1.5 * steps * len(sel), lambda: f"the step control's probe of {1.5 * steps:.0f} steps")
            try:
                y1, y2, _ = advance_pair_chunked(solver, problem, L0s, L0s, tg, ms, ms // 2,
                                                 members=sel, work=work, bar=bar)
            except (RuntimeError, FloatingPointError):  # no implicit step / an overflow at this h
                return None, h_probe
            env = probe_envelope(y1, y2, Ms, 2.0 ** p - 1.0)  # (env[i]: up to grid point i)
            # the estimate's envelope at a quarter, half the window and at its end
            samples_e[:] = [(i / k, float(env[i])) for i in (k // 4, k // 2, k) if i > 0]
            if idx is not None and idx.size >= PROBE_COVER_SAMPLES and ProbeRuns.usable(float(env[-1]), p):
                runs.append(ProbeRuns(problem, idx, ms, y1, y2))
            return float(env[-1]), h_probe

        samples_e = []
        runs = []  # the probes of the whole run at output times asymptotic enough to be the check's companions
        t = problem.t

        P = PROBE_TURNS / wmax
        P = span if P >= PROBE_COVER * span else P
        h = PROBE_FIRST_TURN / wmax
        if P >= span:
            h = max(h, min(PROBE_FIRST_TURN_WHOLE / wmax, PROBE_WHOLE_GAPS * float(np.abs(np.diff(t)).max())))
        h = min(P, h)
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
                if P >= span and float(np.abs(np.diff(t)).max()) <= h:
                    break  # (the run's steps are no longer than the output intervals, all shorter than h anyway)
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
        self.probe_runs = tuple(runs)
        return min(h_star, MAX_TURN / wmax)

    def refusal_note(self, needed: float, budget: float, order: int) -> str:
        """What a refusal before the run adds: the growth the probe saw (if fast) and the accuracy
        reachable within ``budget`` steps (error ~ h^order, h ~ 1/steps)."""
        if self.probe_note:
            return self.probe_note + "; no accuracy can be promised within a budget before such a run"
        reach = min(1.0, SAFETY * self.rtol * (needed / max(budget, 1.0)) ** order)
        return (f"; reachable accuracy about {reach:.2g} within the budget (the probe's estimate from a leading "
                f"window; faster error growth later, e.g. on a chaotic orbit, makes it worse)")

    def announce(self, solver, problem: Problem, h: float, steps: int | None = None) -> None:
        """The slow-run warning (once the budget is checked), from the cost per flow learned by the probes
        (``steps``: the run's steps per member at ``h``, when the caller has counted them)."""
        key = cost_key(solver, problem)
        spf = seconds_per_flow(key)
        steps = float(nsub_for(problem.t, h).sum() if steps is None else steps)
        self.seconds_per_step = spf * solver.flows_per_step(problem)
        seconds = self.seconds_per_step * steps * problem.B * (1.0 + 1.0 / COMPANION_RATIO)
        limit = options["slow_run_warning_seconds"]
        if seconds > limit:
            warn(
                f"simulate: {solver.name!r} at rtol = {self.rtol:g} needs about {seconds:.3g} s "
                f"({steps:.3g} steps per trajectory)"
                + (", a splitting of higher order reaches this accuracy much sooner" if solver.order < 8 else "")
                + f" (options['slow_run_warning_seconds'] = {_validate.fmt(limit)})")

    def checker(self, solver, problem: Problem, nsub: np.ndarray, work: Work, bar=None, most: int | None = None
                ) -> "RichardsonCheck | None":
        """The check of a run at ``nsub`` steps per interval, of every member (up to ``most``: :meth:`_checked`)."""
        if (problem.B == 0 or not nsub.size or int(nsub.sum()) == 0 or solver.flows_per_step(problem) == 0
                or self.still):
            return None
        members = self._checked(problem, most)
        return RichardsonCheck(solver, problem, nsub, self, members, work, bar, probes=self.probe_runs)

    def next_step(self, failure: CheckFailed, solver, problem: Problem, work: Work) -> float:
        """The step of the re-run after a failed check, or an error when the target is out of reach."""
        self.reruns += 1
        # (the switch to compensated storage refines nothing; a run stopped at an early judgement later than
        # any before it made progress towards the end)
        done = failure.done
        progress = self.furthest < done < 1.0
        self.retries += not (failure.compensate or progress)
        self.furthest = max(self.furthest, done if done < 1.0 else 0.0)
        if self.retries > MAX_RETRIES:
            best = min(e for _, e in self.history) if self.history else None
            raise UnreachableAccuracyError(
                f"simulate: rtol = {self.rtol:g}{self._tightened()} was not reached after {MAX_RETRIES} re-runs at "
                f"shorter steps "
                f"({failure.why}); the error does not follow the method's order here (round-off, or an orbit "
                f"whose error grows exponentially); reachable accuracy about "
                f"{best if best is not None else float('nan'):.2g} at reasonable cost. Ask for a larger rtol "
                f"or a shorter run")
        return failure.h

    def verified_step(self, solver, problem: Problem, work: Work, most: int | None = None, bar=None) -> float:
        """The step, checked before any member runs (ensembles run member by member): the probe, then the
        checked members (every member, as in a run's check: :meth:`_checked`; up to ``most``, the fastest beyond,
        for the members of a dask ensemble, checked in this process) run on their own with their companions (no
        output kept). Checking the 8 fastest only returned 4 of 40 members of similar rates 1.1-2300x over rtol
        1e-6, silently, with events (body 4007), where the same ensemble run at once met it."""
        h = self.first_step(solver, problem, work, bar=bar)
        t = problem.t
        while True:
            nsub = nsub_for(t, h)
            # the arithmetic the members will run in
            solver.set_accuracy(problem, self.rtol, int(nsub.sum()), roundoff_amplified=self.roundoff_amplified)
            check = self.checker(solver, problem, nsub, work, bar=bar, most=most)
            if check is None:
                return h
            work.refuse(int(nsub.sum()) * len(check.members) + check.planned_steps,
                        "the step control's check: the checked members and their companions")
            try:
                check.run_alone()
                return h
            except CheckFailed as failure:
                h = self.next_step(failure, solver, problem, work)
