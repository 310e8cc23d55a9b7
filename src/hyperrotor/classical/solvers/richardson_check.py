r"""The a-posteriori check of a fixed-step run: two coarser companion runs and Richardson's estimate.

Step 4 of the step control (:mod:`.step_control`, whose docstring describes the whole
algorithm): :class:`RichardsonCheck` advances the checked members beside the run with steps
:math:`c` and :math:`c c_2` times longer, estimates the run's own error at every sample point
with the observed order (:func:`observed_order`), and stops the run with :class:`CheckFailed`
(carrying the re-run's step, priced against the budget) when the estimate or its projection to
the end exceeds the target; it also switches a run to compensated storage when the orbit
amplifies round-off towards ``rtol`` (:meth:`RichardsonCheck._check_roundoff`).
"""
from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np

from hyperrotor._jit import jit
from hyperrotor._warn import warn

from ._kernels import distance_at, relative_difference, row_scales, scales_at
from .base import Problem, step_lengths
from .chunks import Work, advance_chunked, advance_pair_chunked, merge, pair_ahead, refuse_steps, stops

__all__ = ["RichardsonCheck", "CheckFailed", "AccuracyWarning", "ProbeRuns", "observed_order", "relative_difference",
           "check_bytes", "SAFETY", "ACCEPT", "ASYMPTOTIC", "COMPANION_RATIO"]

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
#: the probe's two runs of the whole run are the companions when their steps are 2 to this many times the run's
PROBE_RATIO = 8.0
#: round-off of plain arithmetic per run: this times eps sqrt(flows) times the orbit's amplification ...
ROUNDOFF_FACTOR = 4.0
#: ... above this share of the accepted error switches the run to compensated storage
ROUNDOFF_SHARE = 0.25
#: the observed order comes from samples where the second companion's difference is below this
LINEAR_REGIME = 1e-3
#: the estimate grows with the second companion's difference where the ratio of the two differences exceeds the
#: one the order came from this many times (and the second companion is outside its asymptotic regime): on regular
#: and mildly chaotic orbits the ratio moves by up to ~2.5x from sample to sample
STALL_RATIO = 4.0
#: sample points of the check (the error can peak between output times)
CHECK_SAMPLES = 64
#: the check projects the error to the end of the run once this fraction of it is done ...
PROJECT_AFTER = 0.125
#: ... and stops the run when the projection exceeds the accepted error this many times
PROJECT_MARGIN = 4.0
#: an error envelope growing this much over the second half of the samples seen is faster than linear
GROWTH_RATIO = 8.0
#: a run of this many elementary flows or more (about a second of one core) is also judged at an eighth, a quarter
#: and half of its samples, and stopped there when over the target; a shorter one at its end only. Fixed points,
#: not the ends of the run's chunks (whose lengths follow the machine's measured speed): judged at every chunk end,
#: a 40-member ensemble at rtol 1e-6 crept through three re-runs, each stopped a little later on the same growing
#: error, to UnreachableAccuracyError on a slower machine, and returned a result on a faster one
EARLY_STOP_FLOWS = 1e8
#: the rounding floor is measured on up to this many members (those whose differences grow the most)
TWIN_MEMBERS = 8


@jit
def _three_run_ratio(q, r, r2):  # pragma: no cover - jitted
    """:math:`r^q (r_2^q - 1)/(r^q - 1)`: the ratio of the differences of three runs (errors :math:`C h^q`)."""
    return r ** q * (r2 ** q - 1.0) / (r ** q - 1.0)


@jit
def coarser_divisor(q, r):  # pragma: no cover - jitted
    """The run's error is its difference to a companion at ``r`` times its step over this: :math:`r^q - 1`
    (errors :math:`C h^q`); 1 outside the asymptotic regime (:math:`q < 1/2`: the difference itself). Compiled."""
    return max(r ** q - 1.0, 1.0) if q >= 0.5 else 1.0


@jit
def observed_order(rho, r, r2, p):  # pragma: no cover - jitted
    r"""The order :math:`q \in [0, p]` with :math:`r^q (r_2^q - 1)/(r^q - 1) = \rho` (ratio of the
    differences of three runs at steps :math:`h`, :math:`rh`, :math:`r r_2 h`, errors :math:`C h^q`).

    The left side increases with :math:`q` (from :math:`\ln r_2/\ln r` at 0); below its value at
    :math:`q = 1/2` the answer is 0 (not asymptotic), above its value at ``p`` it is ``p``; bisection
    in between. ``r == r2`` gives :math:`\log\rho / \log r`. Compiled (called once per check update).
    """
    if not rho > 0.0 or r <= 1.0 or r2 <= 1.0:
        return 0.0
    if rho < _three_run_ratio(0.5, r, r2):
        return 0.0
    if rho >= _three_run_ratio(float(p), r, r2):
        return float(p)
    lo, hi = 0.5, float(p)
    for _ in range(40):  # |hi - lo| < 1e-11
        mid = 0.5 * (lo + hi)
        if _three_run_ratio(mid, r, r2) < rho:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


@jit
def run_steps(t, nsub):  # pragma: no cover - jitted
    """``(cs, steps, h)`` of a run of ``nsub[k]`` equal steps per interval of ``t``: the cumulative step
    counts ``[0, nsub[0], nsub[0] + nsub[1], ...]``, their total and the longest step (compiled)."""
    cs = np.empty(nsub.size + 1, dtype=np.int64)
    cs[0] = 0
    h = 0.0
    for k in range(nsub.size):
        cs[k + 1] = cs[k] + nsub[k]
        h = max(h, abs((t[k + 1] - t[k]) / nsub[k]))
    return cs, cs[nsub.size], h


@jit
def check_plan(t, nsub, cs, spacing, finer, c, c2):  # pragma: no cover - jitted
    """Where :class:`RichardsonCheck` samples a run of ``nsub[k]`` steps per output interval (``cs`` their
    cumulative counts) and how its companions step there: ``(marks, out_idx, grid, nc, nc2, r, r2, steps)``.

    ``marks``: global step indices of the samples, every ``spacing`` steps and the run's end (a last gap
    shorter than half a spacing is merged: with ``spacing >= 2 c c2``, as the check sets it, every segment then
    has at least ``c c2`` steps, so its second companion takes fewer steps than its first, ``r2 >= 2``; a last
    gap of ``c c2 / 2`` steps gave both one step, ``r2 = 1``, and an estimate 5e4-fold too high). When the
    steps per interval are equal and divide ``spacing``, the samples are every stride-th output time instead
    (``out_idx`` their output indices, else empty: the run needs no extra stops and gives them with its
    outputs). ``grid``: the start and their times. ``nc``,
    ``nc2``: the companions' steps per segment between samples (``finer``: twice and four times the run's;
    else the run's divided by ``c``, and that by ``c2``). ``r``, ``r2``: the smallest step ratios over the segments
    (companion / largest run step, second / first companion; ``finer``: smallest run step / companion, first
    / second companion), so that the estimate errs on the safe side. ``steps``: the companions' steps together
    (per member). Compiled (one call per checked run).
    """
    K1 = nsub.size
    ah = np.empty(K1)
    for k in range(K1):
        ah[k] = abs((t[k + 1] - t[k]) / nsub[k])
    steps = cs[K1]
    n0 = nsub[0]
    uniform = True
    for k in range(K1):
        if nsub[k] != n0:
            uniform = False
    if uniform and spacing % n0 == 0:
        stride = spacing // n0
        count = (K1 - 1) // stride if K1 > stride else 0
        if count and 2 * (K1 - count * stride) * n0 < spacing:
            count -= 1
        out_idx = np.empty(count + 1, dtype=np.int64)
        for i in range(count):
            out_idx[i] = (i + 1) * stride
        out_idx[count] = K1
        marks = out_idx * n0
        grid = np.empty(count + 2)
        for i in range(count + 1):
            grid[i + 1] = t[out_idx[i]]
    else:
        count = (steps - 1) // spacing if steps > spacing else 0
        if count and 2 * (steps - count * spacing) < spacing:
            count -= 1
        marks = np.empty(count + 1, dtype=np.int64)
        for i in range(count):
            marks[i] = (i + 1) * spacing
        marks[count] = steps
        out_idx = np.empty(0, dtype=np.int64)
        grid = np.empty(count + 2)
        times = stops(t, cs, nsub, ah, marks)[0]  # (the marks' times: output times exactly where they are one)
        for i in range(count + 1):  # (a loop: numba compiles a slice assignment's shape check for seconds)
            grid[i + 1] = times[i]
    grid[0] = t[0]
    S = marks.size
    total = 0
    nc = np.empty(S, dtype=np.int64)
    nc2 = np.empty(S, dtype=np.int64)
    hmax_all, hmin_all = ah.max(), ah.min()
    one_step = hmax_all - hmin_all <= 1e-12 * hmax_all  # one step length (a uniform grid; its round-off): the
    r = math.inf  # ratios then err on the safe side by at most 1e-12
    r2 = math.inf
    prev = 0
    for i in range(S):
        seg = marks[i] - prev
        if finer:
            nc[i], nc2[i] = 2 * seg, 4 * seg
        else:
            nc[i] = max(1, int(seg / c))
            nc2[i] = max(1, int(nc[i] / c2))
        total += nc[i] + nc2[i]
        length = abs(grid[i + 1] - grid[i])
        H, H2 = length / nc[i], length / nc2[i]
        if one_step:
            hmax, hmin = hmax_all, hmin_all
        else:  # the largest and smallest run step in the segment (it may cross output intervals)
            first = np.searchsorted(cs, prev, side="right") - 1
            last = np.searchsorted(cs, marks[i] - 1, side="right") - 1
            hmax, hmin = ah[first], ah[first]
            for k in range(first + 1, last + 1):
                hmax, hmin = max(hmax, ah[k]), min(hmin, ah[k])
        if finer:
            r, r2 = min(r, hmin / H), min(r2, H / H2)
        else:
            r, r2 = min(r, H / hmax), min(r2, H2 / H)
        prev = marks[i]
    return marks, out_idx, grid, nc, nc2, r, r2, total


@jit
def sample_differences(Lf, L1, L2, moments, Lmax, Wmax, d1, d2, j):  # pragma: no cover - jitted
    """``d1[:, j:j + S]``, ``d2[:, j:j + S]``: per checked member, the distances run - first companion and
    first - second companion at ``S`` new samples (``(members, S, n)`` each), each relative to the running scales
    raised with the run's states up to that sample (not to the last of them: the distances do not depend on how
    many samples a call brings, i.e. on where the run's chunks end); ``False`` when a distance is not finite (a
    companion overflowed). Compiled."""
    finite = True
    for i in range(Lf.shape[1]):
        for m in range(Lf.shape[0]):
            Lmax[m], Wmax[m] = scales_at(Lf, m, i, moments, Lmax[m], Wmax[m])
            a = distance_at(Lf, L1, m, i, moments, Lmax[m], Wmax[m])
            b = distance_at(L1, L2, m, i, moments, Lmax[m], Wmax[m])
            d1[m, j + i] = a
            d2[m, j + i] = b
            if not (math.isfinite(a) and math.isfinite(b)):
                finite = False
    return finite


@jit
def member_estimate(d1, d2, err, upto, finer, r, r2, p):  # pragma: no cover - jitted
    r"""``err[:upto] = d1[:upto] / divisor`` (one member's estimated error at each sample) and ``(q, max err)``.

    With errors :math:`C h^q`: :math:`\rho = |y_1 - y_2| / |y_{run} - y_1| = r^q (r_2^q - 1)/(r^q - 1)`
    (:func:`observed_order` solves it for :math:`q`), which gives the observed order :math:`q \le p`
    (never more than the method's order); the run's error is then :math:`|y_{run} - y_1| / (r^q - 1)`
    (run vs coarser companion) or :math:`|y_{run} - y_1| / (1 - r^{-q})` (``finer`` companions: the run
    is the coarsest, :math:`D_2 \approx D_1 / r_2^q`). Outside the asymptotic regime (:math:`q < 1/2`)
    the difference itself is the estimate. The order comes from the samples where the coarser companion
    is still in its linear regime (:data:`LINEAR_REGIME`: an error grown to order one, e.g. on a chaotic
    orbit, stops following :math:`C h^q` and would show a low order) and the run's difference is above
    round-off, when there are such samples. ``q = -1``: no difference at all (the estimate is 0). Where the
    second companion has left its asymptotic regime (difference above :data:`SECOND_COMPANION_ASYMPTOTIC`) and
    the ratio of the two differences has grown beyond :data:`STALL_RATIO` times the one the order came from,
    the estimate is raised by that growth: on a chaotic orbit the first companion's difference stalled
    (random generic body, rtol 1e-6: ratio 195 -> 1167, the estimate 5x under the run's error) while the
    second kept growing with the run's.
    """
    D1 = 0.0
    D2 = 0.0
    L1m = 0.0
    L2m = 0.0
    linear = False
    for i in range(upto):
        D1 = max(D1, d1[i])
        D2 = max(D2, d2[i])
        if not finer and d2[i] <= LINEAR_REGIME and d1[i] >= 100.0 * _EPS:
            linear = True
            L1m = max(L1m, d1[i])
            L2m = max(L2m, d2[i])
    if D1 <= 0.0:
        for i in range(upto):
            err[i] = 0.0
        return -1.0, 0.0
    rho = L2m / L1m if linear else D2 / D1
    if finer:
        q = min(float(p), math.log(max(rho, 1e-300)) / -math.log(r2)) if rho < 1.0 else 0.0
        div = max(1.0 - r ** -q, 1e-300) if q >= 0.5 else 1.0
    else:
        q = observed_order(rho, r, r2, p)
        div = coarser_divisor(q, r)
    e = 0.0
    for i in range(upto):
        err[i] = d1[i] / div
        if not finer and d1[i] > 0.0 and rho > 0.0 and d2[i] > max(SECOND_COMPANION_ASYMPTOTIC,
                                                                 STALL_RATIO * rho * d1[i]):
            # the second companion outside its asymptotic regime and its difference grown faster than the first's
            # (on a chaotic orbit the first companion's difference can stall while the run's error grows):
            # the run's error assumed to grow like the second difference since the linear samples
            err[i] *= d2[i] / (rho * d1[i])
        e = max(e, err[i])
    return q, e


@jit
def estimate(d1, d2, err, upto, finer, r, r2, p):  # pragma: no cover - jitted
    """The run's estimated error at each sample, ``err[:upto]``: the largest over the checked members (rows of
    ``d1``, ``d2``) of their own estimates (:func:`member_estimate`), and ``(q, max err)`` with the order ``q``
    of the member whose estimate is the largest (-1 when no member shows a difference). Each member has its own
    order, regime and growth: an envelope over the members takes the order from one member and the differences
    from another (a member of order 2 under one of order 8 with 100x larger differences: its error divided by
    :math:`r^8 - 1` instead of :math:`r^2 - 1`, 20x too small). Compiled."""
    M = d1.shape[0]
    row = np.empty(upto)
    q_best, e_best = -1.0, 0.0
    for i in range(upto):
        err[i] = 0.0
    for m in range(M):
        q, e = member_estimate(d1[m], d2[m], row, upto, finer, r, r2, p)
        for i in range(upto):
            err[i] = max(err[i], row[i])
        if q >= 0.0 and (q_best < 0.0 or e > e_best):
            q_best, e_best = q, e
    return q_best, e_best


@jit
def roundoff_amplification(t, d1, flows):  # pragma: no cover - jitted
    r"""``(A, X)``: how much the orbit amplified the differences to the first companion beyond linear growth,
    and how much their envelope grew over the whole run (:meth:`RichardsonCheck._check_roundoff`).

    ``A``: from the first sample :math:`t_i` after an eighth of the run (times ``t`` from the start) where the
    envelope is above round-off, to the end :math:`T`, it grew :math:`G`-fold; :math:`A = G t_i / T` (at least
    1; 0.0 when no sample qualifies). ``X``: the envelope at the end over the first sample's difference (at
    least :math:`\epsilon`): on a chaotic orbit the differences made early grow like a perturbation of the
    initial state, :math:`X \approx e^{\lambda T}` (over 62 chaotic members of random generic 5D ensembles,
    :math:`\epsilon X` was 0.1-10 times the scatter of compensated runs at four steps; extrapolating
    :math:`G` back to the start instead was 6000x too high on an orbit that was quiet for its first 40%)."""
    S = t.size
    tend = t[S - 1]
    env = 0.0
    i0 = -1
    e0 = 0.0
    for i in range(S):
        env = max(env, d1[i])
        if i0 < 0 and t[i] >= tend / 8.0 and env > 10.0 * _EPS * math.sqrt(flows * t[i] / max(tend, 1e-300)):
            i0, e0 = i, env
    if i0 < 0 or i0 >= S - 1 or t[i0] <= 0.0:
        return 0.0, 0.0
    return max(1.0, env / e0 / (tend / t[i0])), env / max(d1[0], _EPS)


@jit
def roundoff_growth(t, d1, flows):  # pragma: no cover - jitted
    """:func:`roundoff_amplification` of every row of ``d1 (members, samples)``: arrays ``(A, X)`` (one compiled
    call for any number of checked members)."""
    M = d1.shape[0]
    A = np.empty(M)
    X = np.empty(M)
    for m in range(M):
        A[m], X[m] = roundoff_amplification(t, d1[m], flows)
    return A, X


def check_bytes(members: int, n: int) -> float:
    """Memory of the check of ``members`` members of ``n`` planes (the distances and estimates at every sample,
    the companions' states and their compensated low parts, the running scales; up to :data:`TWIN_MEMBERS`
    members, the first companion's states at every sample, kept for the round-off twin): priced with the output."""
    kept = CHECK_SAMPLES * n if members <= TWIN_MEMBERS else 0
    return 8.0 * members * (2 * CHECK_SAMPLES + 4 * n + 2 + kept)


@jit
def probe_ratio(t, nsub, idx, ms):  # pragma: no cover - jitted
    """The smallest ratio, over the segments between the output times ``t[idx]`` (``t[0]`` first), of the
    probe's step there (``ms[i]`` equal steps) to the longest step of a run of ``nsub[k]`` steps per interval
    (compiled)."""
    r = math.inf
    prev = 0
    for i in range(idx.size):
        hmax = 0.0
        for k in range(prev, idx[i]):
            hmax = max(hmax, abs((t[k + 1] - t[k]) / nsub[k]))
        r = min(r, abs(t[idx[i]] - t[prev]) / ms[i] / hmax)
        prev = idx[i]
    return r


class ProbeRuns(NamedTuple):
    """The step control's probe of the whole run, sampled at the output times ``problem.t[idx]``: ``y1`` with
    ``ms[i]`` equal steps per segment, ``y2`` with half as many (``(members, idx.size + 1, n)``, the start
    first). A run whose steps are 2 to :data:`PROBE_RATIO` times shorter than ``y1``'s takes them as its check's
    companions (:class:`RichardsonCheck`): the check then costs no integration step."""

    problem: Any
    idx: np.ndarray
    ms: np.ndarray
    y1: np.ndarray
    y2: np.ndarray

    @staticmethod
    def usable(err: float, p: int) -> bool:
        """Whether runs whose Richardson estimate was ``err`` (of ``y1``; order ``p``) are asymptotic enough
        to be companions (the limits of the companions the check would choose itself; round-off is fine)."""
        return err <= COMPANION_ASYMPTOTIC and err * (2.0 ** p - 1.0) <= SECOND_COMPANION_ASYMPTOTIC


class AccuracyWarning(UserWarning):
    """A result is returned, but ``rtol`` is below what double precision gives on this orbit: a chaotic
    orbit amplifies the rounding of its own initial state (and of every step) beyond ``rtol``. The message
    names the growth and the accuracy the result has; ``warnings.simplefilter("error", AccuracyWarning)``
    makes it an error."""


class CheckFailed(Exception):
    """Raised by :class:`RichardsonCheck` inside a run: re-run at step ``h`` (scaled units)."""

    def __init__(self, h: float, why: str, compensate: bool = False, done: float = 1.0):
        super().__init__(why)
        self.h = h
        self.why = why
        self.compensate = compensate  # the same step again, in compensated storage (once per call: not a retry)
        self.done = done  # the fraction of the run judged (a re-run stopped later than any before made progress)


class RichardsonCheck:
    """The a-posteriori check of one run (module docstring, steps 4-5).

    ``marks`` are global step indices of the run (sample points); the driver keeps the run's
    states there and calls :meth:`update` with them as the run reaches them; the companion of
    the checked ``members`` follows, and :class:`CheckFailed` stops the run when the estimate
    (or its projection) is over the target. ``control``: the :class:`~.step_control.ErrorTarget`
    (its ``rtol``; the check records ``history``, ``last_growth`` and ``roundoff_amplified`` on it).
    """

    def __init__(self, solver, problem: Problem, nsub: np.ndarray, control: Any, members: np.ndarray,
                 work: Work, bar=None, probes: tuple = ()):
        self.solver, self.problem, self.control, self.members, self.work, self.bar = (
            solver, problem, control, members, work, bar)
        t = problem.t
        p = solver.order
        self.p = p
        self.nsub = nsub
        self.cs, steps, h = run_steps(t, nsub)
        self.steps = steps
        self.h = h
        self.moments = problem.moments
        self.span = problem.span
        self.j = 0
        self.finer = False
        self.L1s = None  # the first companion's states at the samples, kept for the round-off twin (few members)
        self.given = None  # the companions' states at the samples (the start first), when the probe's runs
        best, r = None, 0.0
        for probe in probes:  # (the coarsest with steps 2 to PROBE_RATIO times the run's, of the same members)
            if probe.problem is problem and probe.y1.shape[0] == len(members):
                rp = probe_ratio(t, nsub, probe.idx, probe.ms)
                if r < rp <= PROBE_RATIO and rp >= 2.0:
                    best, r = probe, rp
        if best is not None:
            self._samples(best.idx, t[np.concatenate(([0], best.idx))], r, 2.0)
            self.nc, self.nc2 = best.ms, best.ms // 2
            self.given = (best.y1, best.y2)
            self.planned_steps = 0
            return
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
        marks, out_idx, grid, self.nc, self.nc2, r, r2, companion_steps = check_plan(
            t, nsub, self.cs, spacing, finer, c, c2)
        self._samples(out_idx, grid, r, r2, marks)
        self.finer = finer
        self.planned_steps = companion_steps * len(members)
        self.Lc = self.Lc2 = problem.L0[members]
        self.carry = self.carry2 = None
        if not finer and len(members) <= TWIN_MEMBERS:  # (the unperturbed half of the twin pair: no run of its own)
            self.L1s = np.empty((len(members), self.marks.size, problem.n))

    def _samples(self, out_idx, grid, r, r2, marks=None) -> None:
        """The samples (at the output times ``out_idx``, or at the run's steps ``marks``; ``grid``: their times,
        the start first), the step ratios of the estimate and the arrays of the distances and estimates."""
        self.grid, self.tm, self.r, self.r2 = grid, grid[1:], r, r2
        self.out_idx = out_idx if out_idx.size else None  # output indices of the samples, if all are output times
        self.marks = self.cs[out_idx] if marks is None else marks
        S = self.marks.size
        self.Lmax, self.Wmax = row_scales(self.problem.L0[self.members][:, None, :], self.moments)
        M = len(self.members)
        self.d1 = np.zeros((M, S))  # run - first companion, relative, per checked member and sample
        self.d2 = np.zeros((M, S))  # first - second companion
        self.err = np.zeros(S)  # estimated error of the run at each sample (the largest over the members)
        # where the run is judged: at its end; a long run also at an eighth, a quarter and half of its samples
        flows = self.steps * self.problem.B * self.solver.flows_per_step(self.problem)
        if flows >= EARLY_STOP_FLOWS:
            self.checkpoints = sorted({c for c in (S // 8, S // 4, S // 2) if c > 0} | {S})
            self.early_marks = self.marks[np.array(self.checkpoints[:-1], dtype=np.int64) - 1]  # (the run stops there)
        else:
            self.checkpoints, self.early_marks = [S], self.marks[:0]

    def ahead(self, upto: int):
        """The companions' run to ``marks[upto - 1]`` started on a second core (:func:`~.chunks.pair_ahead`)
        while the run gets there, for ``update(upto, Lf, ahead)``; or ``None``."""
        j = self.j
        if self.given is not None or upto <= j:
            return None
        future = pair_ahead(self.solver, self.problem, self.Lc, self.Lc2, self.grid[j:upto + 1], self.nc[j:upto],
                            self.nc2[j:upto], members=self.members, carries=(self.carry, self.carry2))
        return None if future is None else (future, j, upto)

    def update(self, upto: int, Lf: np.ndarray, ahead=None) -> None:
        """The run reached ``marks[:upto]``; ``Lf (members, upto - j, n)`` are its states at the new ones
        (``ahead``: :meth:`ahead` ``(upto)``, started before the run got there)."""
        j = self.j
        if upto <= j:
            return
        if self.given is not None:  # the probe's runs
            self.judge(upto, Lf, self.given[0][:, j + 1:upto + 1], self.given[1][:, j + 1:upto + 1])
            return
        grid = self.grid[j:upto + 1]
        if ahead is not None and ahead[1:] != (j, upto):  # (started for another segment: not these companions)
            raise AssertionError(f"the companions started ahead cover samples {ahead[1:]}, not {(j, upto)}")
        L1, L2, (self.carry, self.carry2) = advance_pair_chunked(
            self.solver, self.problem, self.Lc, self.Lc2, grid, self.nc[j:upto], self.nc2[j:upto], members=self.members,
            work=self.work, bar=self.bar, carries=(self.carry, self.carry2), ahead=None if ahead is None else ahead[0])
        self.Lc, self.Lc2 = L1[:, -1], L2[:, -1]
        if self.L1s is not None:
            self.L1s[:, j:upto] = L1[:, 1:]
        self.judge(upto, Lf, L1[:, 1:], L2[:, 1:])

    def judge(self, upto: int, Lf: np.ndarray, L1: np.ndarray, L2: np.ndarray) -> None:
        """The samples ``marks[j:upto]`` reached by the run (``Lf``) and its two companions (``L1``, ``L2``;
        all ``(members, upto - j, n)``): the estimate, and :class:`CheckFailed` when it is over the target
        (called by :meth:`update`, which advances the companions to ``upto`` first, or takes the probe's runs
        as them)."""
        # (C order, as every other caller passes them: the probe's runs and the companions come in as slices, another
        # array layout, which would compile the function a second time, ~1.4 s on a cold start)
        Lf, L1, L2 = (np.ascontiguousarray(x) for x in (Lf, L1, L2))
        if not sample_differences(Lf, L1, L2, self.moments, self.Lmax, self.Wmax, self.d1, self.d2, self.j):
            raise CheckFailed(self.h / 2.0, "a companion run overflowed")
        prev, self.j = self.j, upto
        for c in self.checkpoints:
            if prev < c <= upto:
                self._decide(c)

    def _decide(self, upto: int) -> None:
        """Accept the run up to the checkpoint ``marks[upto - 1]`` (its first ``upto`` samples), or stop it with
        :class:`CheckFailed`; at the last sample, the round-off test. Decided from those samples only, whatever
        the run has reached: the same call takes the same steps on every machine."""
        q, e = estimate(self.d1, self.d2, self.err, upto, self.finer, self.r, self.r2, self.p)
        if q >= 0.0:
            self.q = q
        accept = ACCEPT * self.control.rtol
        done = abs(self.tm[upto - 1] - self.problem.t[0]) / self.span
        if e > accept:
            raise self._failure(upto, e, self._project(e, done), done)
        if upto < self.marks.size and done >= PROJECT_AFTER:
            projected = self._project(e, done)
            if projected > PROJECT_MARGIN * accept:
                raise self._failure(upto, e, projected, done)
        if upto == self.marks.size:
            self._check_roundoff()
            self.control.history.append((self.h, e))

    def _check_roundoff(self) -> None:
        r"""Re-run with compensated storage when the orbit amplifies round-off towards ``rtol``; warn when even
        that cannot give ``rtol`` (:class:`AccuracyWarning`).

        Richardson's differences see the truncation error only; the round-off of plain
        arithmetic, about :math:`\epsilon\sqrt{\text{flows}}` for a regular orbit, is amplified on a
        chaotic one like the truncation error is: by :math:`A`, the growth of the envelope of the
        differences to the first companion from an eighth of the run (or the first sample after it
        where they are above round-off) to its end, beyond linear (:func:`roundoff_amplification`, per
        checked member: an envelope over the members hid a chaotic member's growth under another's larger,
        steadier differences). When :data:`ROUNDOFF_FACTOR` :math:`\cdot\epsilon\sqrt{\text{flows}}\,A`
        exceeds :data:`ROUNDOFF_SHARE` of the accepted error, the run is repeated at the same step with
        compensated (TwoSum) storage (a random generic 5D body at rtol 1e-10 missed the bound 1.7-fold
        in plain arithmetic, and met it 40-fold with TwoSum, at the same step).

        No arithmetic does better than the rounding of the initial state itself, which a chaotic orbit amplifies
        about :math:`e^{\lambda T}`-fold over the run. Where the orbit amplifies faster than linearly
        (:math:`A >` :data:`GROWTH_RATIO`) and :math:`\epsilon X` (:func:`roundoff_amplification`: the growth of
        the differences from the first sample) or the plain round-off above (a run that cannot switch) exceeds
        ``rtol``, the floor is measured: a twin of the checked members started one unit in the last place away
        (:meth:`_perturbed_twin`; :math:`\epsilon X` alone overstated it 16-500x on a mildly chaotic orbit whose
        runs at four steps agree to 1.2e-13). A floor above ``rtol`` returns the result with an
        :class:`AccuracyWarning` naming it (a generic 5D orbit at rtol 1e-7 ... 1e-9: 7.4e-7 ... 1.1e-6, where
        compensated runs at four steps from 0.001 to 0.003 differ from each other by up to 3.1e-7: the orbit, not
        the method, sets the accuracy).
        """
        roundoff, amplification, A, X = self._roundoff(self.j)
        if amplification == 0.0:
            return
        rtol = self.control.rtol
        if self.solver.can_compensate() and roundoff > ROUNDOFF_SHARE * ACCEPT * rtol:
            self.control.roundoff_amplified = True
            raise CheckFailed(self.h, f"the orbit amplifies round-off {amplification:.3g}-fold (about {roundoff:.2g} "
                                      f"in plain arithmetic, rtol = {rtol:g}): re-run with compensated "
                                      f"storage at the same step", compensate=True)
        plain = 0.0 if self.solver.compensates() else roundoff
        if max(_EPS * float(X.max()), plain) <= rtol:
            return  # (no member's growth, nor plain arithmetic's round-off, reaches rtol)
        # the members amplifying faster than linearly (a regular orbit's X is ~10, harmless), largest X first
        fast = np.flatnonzero(A > GROWTH_RATIO)
        suspects = fast[np.argsort(-X[fast], kind="stable")]
        Xs = float(X[suspects[0]]) if suspects.size else 0.0
        if not suspects.size or max(_EPS * Xs, plain) <= rtol:
            return
        # eps X can overstate the floor (the truncation differences grow faster than a perturbation of the state
        # on some orbits: 1.8e-12 ... 6e-11 where runs at four steps agree to 1.2e-13): measure it
        rows = suspects[:TWIN_MEMBERS]
        if self.work.done + self.steps * self.problem.B + self._twin_work(rows.size) <= self.work.max_steps:
            # (the run's own steps are counted when it ends, or when the members run after their check: run_alone)
            twin, k = self._perturbed_twin(rows)
            moved = f"changing its initial state by one unit in the last place changes the result by {twin:.2g}"
        else:  # (no room left in max_steps for the twin: the estimate)
            k, twin = int(suspects[0]), _EPS * Xs
            moved = (f"its rounding moves the result by about {twin:.2g} (estimated from the growth of the check's "
                     f"differences, {Xs:.2g}-fold: max_steps left no room to measure it)")
        floor = max(twin, plain)
        if floor > rtol:
            batch = self.problem.batch
            b = int(self.members[k])
            member = "" if self.problem.B == 1 else (
                f" (ensemble member {b if len(batch) < 2 else tuple(int(i) for i in np.unravel_index(b, batch))})")
            warn(f"simulate: rtol = {rtol:g} is below the accuracy double precision gives on this orbit{member}: "
                 f"{moved} (a chaotic orbit: the check's differences grow {amplification:.3g}-fold beyond linear)"
                 + ("" if not plain else f", and plain arithmetic's round-off is about {plain:.2g}" + (
                     " (options={'compensated': True} avoids it)" if "compensated" in self.solver.options else ""))
                 + f": the result is accurate to about {floor:.2g}, not {rtol:g}. Ask for rtol >= {floor:.2g} "
                   f"or a shorter run", AccuracyWarning)

    def _roundoff(self, upto: int) -> tuple:
        """``(round-off, amplification, A, X)`` of plain arithmetic over the first ``upto`` samples:
        :data:`ROUNDOFF_FACTOR` eps sqrt(flows) times the largest amplification beyond linear growth, and the
        per-member arrays of :func:`roundoff_growth` (:meth:`_check_roundoff`; all 0 before 8 samples)."""
        if upto < 8:
            return 0.0, 0.0, np.zeros(0), np.zeros(0)
        flows = self.steps * self.solver.flows_per_step(self.problem)
        t = np.abs(self.tm[:upto] - self.problem.t[0])
        A, X = roundoff_growth(t, np.ascontiguousarray(self.d1[:, :upto]), flows)  # per member
        amplification = float(A.max())
        return ROUNDOFF_FACTOR * _EPS * math.sqrt(flows) * amplification, amplification, A, X

    def _twin_work(self, rows: int) -> int:
        """Steps times members of :meth:`_perturbed_twin` for ``rows`` checked members: the pair at the first
        companion's steps, or only its perturbed run when the first companion's states were kept."""
        steps = self.steps if self.finer else int(np.sum(self.nc))
        return steps * rows * (1 if self.L1s is not None else 2)

    def _perturbed_twin(self, rows: np.ndarray) -> tuple:
        """``(distance, row)``: the largest distance (:func:`relative_difference`) over the samples between the
        checked members ``rows`` (indices into ``members``) run again from their initial states and a twin started
        one unit in the last place away (``np.nextafter``, every component), and the row where it is: how far the
        rounding of the initial state alone moves the result. The pair runs at the first companion's steps (2 to
        8 times the run's; the run's own on runs of fewer than 32 steps): how much the orbit amplifies a
        perturbation is the orbit's, not the step's, and the pair costs 2/c of the run instead of twice the run
        (chunked and counted as work: the caller makes sure it fits in ``max_steps``). The unperturbed run is the
        first companion itself when its states were kept (up to :data:`TWIN_MEMBERS` checked members, companions
        not the probe's runs, whose arithmetic is plain): only the twin runs, 1/c of the run (the same numbers as
        running both: tested)."""
        members = self.members[rows]
        L0 = self.problem.L0[members]
        if self.finer:
            L = self._members_at_samples(L0, members)
            Lp = self._members_at_samples(np.nextafter(L0, np.inf), members)
        elif self.L1s is not None:
            L = self.L1s[rows]
            Lp, _ = advance_chunked(self.solver, self.problem, np.nextafter(L0, np.inf), self.grid, self.nc,
                                    members=members, work=self.work, bar=self.bar)
            Lp = Lp[:, 1:]
        else:
            L, Lp, _ = advance_pair_chunked(self.solver, self.problem, L0, np.nextafter(L0, np.inf), self.grid,
                                            self.nc, self.nc, members=members, work=self.work, bar=self.bar)
            L, Lp = L[:, 1:], Lp[:, 1:]
        d = relative_difference(L[:, :self.j], Lp[:, :self.j], self.moments, self.Lmax[rows], self.Wmax[rows])
        i = int(np.argmax(d.max(axis=1)))
        return float(d[i].max()), int(rows[i])

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

    def _project(self, e: float, done: float) -> float:
        """The estimated error at the end of the run from the samples so far, growing linearly (the
        regular case; an exponential projection would stop runs near a separatrix, where the error
        grows fast for a while only, and ask for far too short steps)."""
        return e / max(done, 1e-300)

    def _failure(self, upto: int, e: float, projected: float, done: float) -> CheckFailed:
        """The re-run's step, priced, from the first ``upto`` samples; or the error naming why ``rtol`` is out of
        reach."""
        rtol, p = self.control.rtol, self.p
        end = max(e, projected)
        self.control.history.append((self.h, end))
        # the observed order where the error is asymptotic (round-off floors show q < p); an error
        # above ASYMPTOTIC says nothing about the order (q ~ 1 there would ask for ~1e8 steps where a
        # few hundred do): extrapolate with the method's order, and the re-run's check decides
        # (and at least p/2: a run just outside the asymptotic regime shows q ~ 1-2, and 1.5 asked for 2.5e6
        # steps where a few thousand do; with no order seen, q = 1 once turned an estimate 5e4-fold too high into
        # steps 1750x shorter, where p/2 asks for 5x)
        q_seen = getattr(self, "q", p)
        q = p if end > ASYMPTOTIC else min(p, max(p / 2.0, q_seen))
        j = upto
        if not self.finer and j and (self.d1[:, :j].max() > COMPANION_ASYMPTOTIC
                                     or self.d2[:, :j].max() > SECOND_COMPANION_ASYMPTOTIC):
            # companions outside their asymptotic regime show no order: the run's error from the first one's
            # with the method's order, (r^p - 1) instead of the estimate's divisor (r^q - 1)
            end, q = end * coarser_divisor(float(q_seen), self.r) / coarser_divisor(float(p), self.r), p
        h_new = 0.9 * self.h * (SAFETY * rtol / end) ** (1.0 / q)
        h_new = min(h_new, self.h / 1.25)
        lam = self._growth(upto)
        why = (f"estimated error {end:.2g} at the end of the run (rtol = {rtol:g}) with step "
               f"{self._user(self.h):.3g}")
        if lam > 0.0:
            why += (f"; the error grows like exp(lambda t) with lambda ~ {lam * self.problem.scale:.3g} "
                    f"(growth exp(lambda T) ~ {math.exp(min(lam * self.span, 700.0)):.3g} over the run, estimated "
                    f"from the check at {done:.0%} of it)")
        self.control.last_growth = lam
        roundoff, amplification, _, _ = self._roundoff(upto)
        if self.solver.can_compensate() and roundoff > ROUNDOFF_SHARE * ACCEPT * rtol:
            # the differences at shorter steps would carry plain arithmetic's amplified round-off: refined alone, the
            # re-runs of a chaotic 40-member ensemble at rtol 1e-6 failed on it until UnreachableAccuracyError
            self.control.roundoff_amplified = True
            why += (f"; the orbit amplifies round-off {amplification:.3g}-fold (about {roundoff:.2g} in plain "
                    f"arithmetic): the re-run in compensated storage")
        steps_new = self.span / h_new * self.problem.B * (1.0 + 1.0 / COMPANION_RATIO)
        if self.work.done + steps_new > self.work.max_steps:
            h_budget = self.span * self.problem.B * (1.0 + 1.0 / COMPANION_RATIO) / max(
                self.work.max_steps - self.work.done, 1.0)
            reachable = min(1.0, end * (h_budget / self.h) ** q)  # the order h_new assumed (1: no digit left)
            raise refuse_steps(f"rtol = {rtol:g} ({why}; reachable accuracy about {reachable:.2g} within the budget)",
                               self.work.done + steps_new, self.work.max_steps, "ask for a larger rtol or a shorter run")
        return CheckFailed(h_new, why, done=done)

    def _members_at_samples(self, L0: np.ndarray, members: np.ndarray) -> np.ndarray:
        """``members`` run from ``L0`` at the run's steps, at every sample ``(members, samples, n)``."""
        t, cs, nsub = self.problem.t, self.cs, self.nsub
        points, _, pos = merge(cs, self.marks)  # (cs starts at 0)
        grid, ns, h = stops(t, cs, nsub, step_lengths(t, nsub), points)
        L, _ = advance_chunked(self.solver, self.problem, L0, grid, ns, h, members=members, work=self.work,
                               bar=self.bar)
        return L[:, pos]

    def run_alone(self) -> None:
        """The check without the run: the checked members advance on their own to every sample (the companions
        meanwhile: :meth:`ahead`)."""
        ahead = self.ahead(self.marks.size)
        self.update(self.marks.size, self._members_at_samples(self.problem.L0[self.members], self.members), ahead)
