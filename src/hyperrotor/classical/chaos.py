r"""Chaos indicators of the free rigid body: Lyapunov exponents (Benettin) and their sweeps
(Poincaré sections: :mod:`hyperrotor.classical.poincare`).

The free rigid body in 3D and the physical N-D body (moments from a mass tensor,
:math:`I_{ij} = J_i + J_j`, Manakov 1976) are integrable: on their invariant tori
tangent vectors grow only linearly (shear), so the finite-time maximal exponent
decays like :math:`\lambda(T) \approx \log(aT)/T`. A 5D body with ten independent
plane moments is not integrable; its phase space is mixed (regular islands and a
chaotic sea), and orbits in the sea have positive exponents.

Method
------
Benettin et al. (Meccanica 15, 9 and 21 (1980)) with the *tangent map of the same
structure-preserving integrator* that :func:`hyperrotor.simulate` uses: the
Lie-Poisson splittings (``method="splitting2"`` ... ``"splitting8"``), whose steps are
products of exact plane rotations of ``L``. The Jacobian of each plane flow, including
the dependence of its rotation angle :math:`\varphi = h\rho_a L_a` on ``L``, is derived
in :mod:`hyperrotor.classical.solvers._tangent_kernels`; composing them gives the exact
derivative of the discrete step map (compiled with numba). Every
``renorm_interval`` the ``k`` tangent vectors are re-orthonormalised (modified
Gram-Schmidt, the ``R`` of a QR factorisation) and :math:`\log R_{jj}` accumulated;

.. math:: \lambda_j(T) = \frac1T \sum_{\text{renormalisations}} \log R_{jj} .

``k = 1`` gives the maximal exponent, ``k = n`` (``spectrum=True``) the full spectrum
of the n-dimensional ``L``-space. The motion is Hamiltonian on the coadjoint orbits
(eq. 38: the Casimirs fix the orbit), so the spectrum comes in :math:`\pm` pairs, with
one zero per Casimir (directions across the orbits) and a zero pair for the flow and
energy directions; for so(5): two Casimirs, an 8-dimensional orbit,
:math:`(\lambda_1, \lambda_2, \lambda_3, 0, 0, -\lambda_3, -\lambda_2, -\lambda_1)` plus
two zeros. Finite ``T`` leaves :math:`O(\log T / T)` in the zeros.

The step: ``dt`` if given, else ``options["lyapunov_step"]`` divided by the bound
:math:`\max_a \min(|L|, \sqrt{2EI_a})/I_a` on the angular velocities the orbit can
reach (from the Casimir and the energy). The default ``splitting8`` at that step gives
finite-time exponents of strongly chaotic 5D orbits (exponents ~0.8) within ~1e-7 of the
converged ones over 10 time units and ~1e-4 over 20 (the error of the orbit grows like
the tangent vectors; for a chaotic orbit no integrator follows the exact trajectory for
long). At equal cost ``splitting6`` (step 0.2) is ~15x less accurate.

Reproducibility and scale-out
-----------------------------
A chaotic orbit decorrelates from any perturbed copy (a 1e-16 change of the start)
after a few tens of Lyapunov times: compare means or distributions of exponents over
many orbits, not single long orbits. The random initial tangent vectors come from
``rng`` (seeded: reproducible) and are drawn before the ensemble is cut into chunks;
each orbit runs the same compiled arithmetic in whichever chunk it falls, so
``client=`` (a :class:`dask.distributed.Client`) and in-process runs give the same
numbers bit for bit (same numba build; see ``docs/scaling-out.md``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from hyperrotor import _parallel, _pricing, _validate
from hyperrotor._equality import fields_equal
from hyperrotor._floats import power_of_two_scale
from hyperrotor._options import options
from hyperrotor.conventions import dimension_from_count

from .solvers._tangent_kernels import tangent_run, tangent_run_lanes
from .solvers import SOLVERS
from .solvers._kernels import rotation_tables
from .solvers.splitting import casimir_shift, splitting_word
from .solvers.step_control import rate_bound

__all__ = ["lyapunov", "lyapunov_sweep", "LyapunovResult", "LYAPUNOV_METHODS"]

#: ``method=`` names of :func:`lyapunov`: the solvers of the registry :data:`hyperrotor.SOLVERS`
#: with compiled tangent maps (``Solver.tangent``: the Lie-Poisson splittings, whose steps are
#: products of plane rotations), in the registry's order.
_ORDER = {name: cls.order for name, cls in SOLVERS.items() if cls.tangent}
LYAPUNOV_METHODS = tuple(_ORDER)
#: measured throughput of the tangent kernel (flow-vectors per second and thread, 5D: 2e8 for the
#: maximal exponent, 9e7 for the full spectrum); used for budgets and chunk sizes
_WORK_RATE = 1.5e8
#: orbits advancing together in the bodies-innermost kernel (working set of a block stays in L1/L2)
_LANES = 64
#: groups of fewer orbits run the one-body kernel (short inner loops do not pay)
_MIN_LANES = 4

# ----------------------------------------------------------------------------
# the chunk function (top level: pickled to dask workers)
# ----------------------------------------------------------------------------
def _benettin_rows(L0, rates, W0, acc0, h, nsub, word_planes, word_coefs, pair_p, pair_q, pair_s, nren, stride,
                   nstore, renormalize=True):
    """Benettin sums ``(rows, nstore, k)`` and final states ``(rows, n)``, ``(rows, k, n)`` for a chunk of orbits.

    ``nren`` renormalisations from the states ``L0``, ``W0`` and the sums ``acc0`` (see
    :mod:`.solvers._tangent_kernels`). Orbits with the same number of steps per renormalisation
    advance together in the bodies-innermost kernel (``tangent_run_lanes``, bit-identical to the
    one-body kernel for each orbit, so the grouping does not change any result). ``renormalize=False``:
    ``nsub`` steps without the Gram-Schmidt step (the first pieces of a renormalisation cut into pieces), in the
    one-body kernel; the sums are then not written (``out`` stays zero).
    """
    B, n = L0.shape
    k = W0.shape[1]
    out, Lout, Wout = np.zeros((B, nstore, k)), np.empty((B, n)), np.empty((B, k, n))
    for ns in np.unique(nsub):
        sel = np.flatnonzero(nsub == ns)
        args = (np.ascontiguousarray(L0[sel]), np.ascontiguousarray(rates[sel]), np.ascontiguousarray(W0[sel]),
                np.ascontiguousarray(acc0[sel]), word_planes, word_coefs, pair_p, pair_q, pair_s,
                np.ascontiguousarray(h[sel]), np.ascontiguousarray(nsub[sel]), nren, stride)
        outs = (np.zeros((sel.size, nstore, k)), np.empty((sel.size, n)), np.empty((sel.size, k, n)))
        if sel.size >= _MIN_LANES and renormalize:
            tangent_run_lanes(*args, _LANES, *outs)
        else:  # a few orbits, or no renormalisation: the one-body kernel (same arithmetic)
            tangent_run(*args, renormalize, *outs)
        out[sel], Lout[sel], Wout[sel] = outs
    return out, Lout, Wout


# ----------------------------------------------------------------------------
# shared driver
# ----------------------------------------------------------------------------
def _check_common(T, spectrum, method, dt, renorm_interval, n, history):
    _validate.flag("history", history)
    T = _validate.positive("T", T)
    method = _validate.choice("method", method, LYAPUNOV_METHODS)
    dt = _validate.positive("dt", dt, allow_none=True)
    renorm_interval = _validate.positive("renorm_interval", renorm_interval)
    if isinstance(spectrum, (bool, np.bool_)):
        k, as_spectrum = (n if spectrum else 1), bool(spectrum)
    else:
        k, as_spectrum = _validate.integer("spectrum", spectrum, minimum=1, maximum=n), True
    return T, method, dt, renorm_interval, k, as_spectrum


def _benettin(bodies, moments_rows, L0, T, k, method, dt, renorm_interval, history, rng, client, chunk_size, progress,
              desc):
    """Exponents ``(B, K, k)`` at the times ``t (K,)`` for orbits ``L0 (B, n)`` of ``bodies (P, n)``, body ``p``'s
    orbits in the rows ``p * M ... (p + 1) * M - 1`` (``B = P * M``; ``moments_rows (B, n)``: each orbit's body)."""
    B, n = L0.shape
    P = bodies.shape[0]
    N = dimension_from_count(n)
    gen = _validate.rng(rng)
    progress = _validate.flag("progress", progress, allow_none=True)
    M = B // P
    # per orbit: Casimir-shifted rates (as simulate), step, steps per renormalisation
    # scale each orbit by a power of two close to its largest |L_a| (the equations are invariant under
    # L -> L/s, t -> s t): exact in floating point, so the arithmetic of the kernel is the same as
    # unscaled (the half-angles fac * L and the products of the tangent map do not change), but
    # neither norms nor the step rule overflow or underflow for huge or tiny momenta
    scale = power_of_two_scale(np.max(np.abs(L0), axis=1)) if B else np.ones(0)
    Ls = L0 / scale[:, None]
    with np.errstate(over="ignore"):
        wmax = rate_bound(moments_rows, Ls) if B else np.zeros(0)  # of the scaled orbit, time tau * scale
        w_top = float(np.max(wmax * scale)) if B else 0.0
    _check_resolved(T, w_top)
    # (counts as floats until the budget is checked: T / renorm_interval may be beyond any integer, e.g. inf)
    nren = max(1.0, float(np.ceil(T / renorm_interval - 1e-9)))
    tau = T / nren
    # steps per renormalisation (as floats, for the budget check before any cast)
    if dt is None:
        with np.errstate(over="ignore"):
            nsub_f = np.where(wmax > 0, np.ceil(tau * scale * wmax / options["lyapunov_step"] * (1 - 1e-12)), 1.0)
    else:
        nsub_f = np.full(B, np.ceil(tau / dt * (1 - 1e-12)))
    nsub_f = np.maximum(nsub_f, 1.0)
    # the budget (before the rotation tables: 0.35 s for N = 60, spent on a refused call), first with the fewest
    # planes the Casimir shift can leave (a refusal before the shift rule: 2.7 s for 2e6 orbits), then with the
    # planes it leaves: one word for the whole ensemble (planes whose rate vanishes for every orbit drop out), so
    # that an orbit's arithmetic does not depend on the chunk it falls in
    threads = _parallel.client_threads(client) if client is not None else _parallel.default_workers()
    # an orbit runs on one thread (its time segments one after another): the run uses at most one thread per chunk
    # (a review: one orbit on an 8-thread cluster was let through for 8x the budget of one thread)
    if chunk_size is not None:
        chunk_size = _validate.integer("chunk_size", chunk_size, minimum=1)
    threads = max(1, min(threads, B if chunk_size is None else -(-B // chunk_size)))
    _check_work(nsub_f * nren, splitting_word(_ORDER[method], tuple(range(_fewest_planes(bodies))))[0].size, k, N,
                threads, T, w_top)
    shift = np.empty(B)
    for p in range(P if M else 0):
        shift[p * M:(p + 1) * M] = casimir_shift(bodies[p], Ls[p * M:(p + 1) * M])  # of degree 0 in L
    rates = 1.0 / moments_rows - shift[:, None]
    word = splitting_word(_ORDER[method], tuple(int(a) for a in np.flatnonzero(np.any(rates != 0.0, axis=0))))
    work_rows = _check_work(nsub_f * nren, word[0].size, k, N, threads, T, w_top)
    nsub = nsub_f.astype(np.int64)
    nren = int(nren)
    tables = rotation_tables(N)
    h = tau * scale / nsub  # step in the scaled time of each orbit
    stride = 1 if history else nren
    nstore = nren if history else 1
    if B * nstore * k * 8 > options["max_output_bytes"]:
        raise _pricing.refuse("lyapunov", f"history=True (the running exponents of {B} orbit(s) x {nstore} "
                              f"renormalisations x {k})", B * nstore * k * 8.0, "max_output_bytes", "bytes",
                              "use a larger renorm_interval or fewer orbits")
    # time segments: an orbit whose run exceeds options["chunk_seconds"] goes on in segments of whole
    # renormalisations, each continuing from the last one's states and sums (bit for bit one call), so that
    # Ctrl-C is honoured and progress shown within a segment's time even for a single long orbit
    per_chunk = options["chunk_seconds"] * _WORK_RATE
    per_ren = float(work_rows.max()) / nren if B else 0.0
    seg = nren if per_ren * nren <= per_chunk else max(1, int(per_chunk // max(per_ren, 1.0)))
    # ... and a renormalisation longer than that in pieces of its steps (the Gram-Schmidt step after the last one)
    pieces = max(1, min(int(nsub_f.max()) if B else 1, math.ceil(per_ren / max(per_chunk, 1.0))))
    if chunk_size is None and B:
        chunk_size = min(max(1, int(per_chunk // max(per_ren * seg, 1.0))), max(1, math.ceil(B / (4 * threads))))
    # random orthonormal tangent vectors, drawn before chunking (reproducible with a seeded rng)
    G = gen.standard_normal((B, n, k))
    Q, R = np.linalg.qr(G)
    W0 = np.ascontiguousarray(np.swapaxes(Q * np.sign(np.diagonal(R, axis1=1, axis2=2))[:, None, :], 1, 2))
    # orbits sorted by steps per renormalisation, so that a chunk holds few groups of equal steps
    # (each group advances together in the bodies-innermost kernel); the order does not change
    # any orbit's arithmetic
    order = np.argsort(nsub, kind="stable")
    L, W, acc = Ls[order], W0[order], np.zeros((B, k))
    fixed = (rates[order], h[order], nsub[order])
    segments = [min(seg, nren - s0) for s0 in range(0, nren, seg)]  # renormalisations per segment
    # the steps of each piece of a renormalisation, per orbit (pieces x B; one piece: all of them)
    cut = [(fixed[2] + pieces - 1 - i) // pieces for i in range(pieces)]
    split = len(segments) > 1 or pieces > 1
    bar = _parallel.progress_bar(progress, nren * pieces, desc, unit="piece" if pieces > 1 else "renormalisation") \
        if split else None
    stored = []
    try:
        for r in segments:
            for i, steps in enumerate(cut):  # (a piece with no step for some orbits leaves them as they are)
                last = i == pieces - 1
                out, L, W = _parallel.map_rows(
                    _benettin_rows, (L, fixed[0], W, acc, fixed[1], steps),
                    args=(word[0], word[1], tables[0], tables[1], tables[2], r, 1 if history else r,
                          r if history else 1, last),
                    client=client, chunk_size=chunk_size, progress=progress if not split else False, desc=desc,
                )
                if bar is not None:
                    bar.update(r)
            acc = out[:, -1]
            if not np.all(np.isfinite(acc)):  # (checked per segment: a long run stops at the first bad one)
                raise _range_error(renorm_interval, tau, w_top)
            stored.append(out)
    finally:
        if bar is not None:
            bar.close()
    sorted_sums = np.concatenate(stored, axis=1) if history else stored[-1]
    sums = np.empty_like(sorted_sums)
    sums[order] = sorted_sums
    t = tau * stride * np.arange(1, nstore + 1)
    lam = sums / t[None, :, None]
    if k == moments_rows.shape[1]:  # the whole spectrum of a divergence-free flow sums to 0
        last = lam[:, -1]
        bad = np.abs(last.sum(axis=1)) > SPECTRUM_SUM_RTOL * np.abs(last).sum(axis=1)
        if np.any(bad):
            raise _lost_spectrum_error(renorm_interval, tau, w_top, last[np.argmax(bad)])
    return t, lam


def _fewest_planes(bodies: np.ndarray) -> int:
    """The fewest planes the Casimir shift can leave in a step of one of ``bodies (P, n)``: ``n`` minus the most
    planes of one body that share a rate ``1/I_a`` (the shift takes one of the rates)."""
    rates = np.sort(1.0 / bodies, axis=1)
    n = rates.shape[1]
    starts = np.zeros(rates.shape, dtype=np.int64)  # where the run of equal rates holding each entry starts
    starts[:, 1:] = np.where(rates[:, 1:] != rates[:, :-1], np.arange(1, n), 0)
    run = np.arange(1, n + 1) - np.maximum.accumulate(starts, axis=1)
    return int(np.max(n - run.max(axis=1)))


def _check_work(steps, flows, k, N, threads, T, w_top) -> np.ndarray:
    """The work of each orbit (``steps`` of ``flows`` plane flows, ``k`` tangent vectors), refused over
    ``options["lyapunov_max_work"]`` per worker thread."""
    # a tangent vector's plane flow touches N - 2 pairs: (N - 2) / 3 times a 5D one (the calibration)
    tangent = k * max(1.0, (N - 2) / 3.0)
    with np.errstate(over="ignore"):
        work_rows = steps * max(1, flows) * (1 + tangent)
    budget = options["lyapunov_max_work"]
    if not work_rows.sum() / threads <= budget:  # also refuses an infinite estimate
        raise _pricing.refuse(
            "lyapunov", f"this run ({work_rows.sum():.3g} units of work: 5D plane flows x (1 + {k} tangent vectors"
            f"{f' x (N - 2) / 3 = {tangent:.4g}' if N > 5 else ''}), growing with T = {_validate.fmt(T)}, the "
            f"{work_rows.size} orbit(s) and the angular velocities of omega0, up to w_max = {w_top:.3g}; {threads} "
            f"worker thread(s), a budget of ~{budget / _WORK_RATE / 60:.0f} min each)", work_rows.sum() / threads,
            "lyapunov_max_work", "work units per worker thread",
            "shorten T, use fewer orbits or add workers (client=)")
    return work_rows


#: the least ``T * w_max`` (the angle the fastest plane can turn in the run) of an exponent: below it the
#: growth of the tangent vectors, ``1 + O(T w_max)``, drowns in round-off (an exponent off by ~eps / T:
#: -11 instead of 1.13 at T = 1e-17, a review)
LEAST_TURN = 1e-9


def _check_resolved(T, w_top) -> None:
    """``ValueError`` for a run too short to resolve an exponent in double precision (:data:`LEAST_TURN`)."""
    if w_top > 0 and T * w_top < LEAST_TURN:
        raise ValueError(
            f"lyapunov: T = {_validate.fmt(T)} is too short to resolve an exponent: the tangent vectors grow by "
            f"1 + O(T w_max) = 1 + O({T * w_top:.2g}) (w_max = {w_top:.3g}, the largest angular velocity reachable "
            f"on the orbits), which double precision resolves to ~eps / T = {np.finfo(float).eps / T:.2g} in the "
            f"exponents; use T >= {LEAST_TURN:g} / w_max = {LEAST_TURN / w_top * 1.005:.3g}")  # (rounded up)


#: the whole spectrum's sum relative to the sum of |lambda| beyond which the Gram-Schmidt renormalisation lost the
#: small exponents (a review: an orbit at renorm_interval 50 ... 400 gave sums 5e-2 ... 1.9, silently, where 1
#: gave 6e-16; the maximal exponent the same in all)
SPECTRUM_SUM_RTOL = 1e-6


def _interval_error(renorm_interval, tau, trouble: str, consequence: str, w_top: float, factor: float,
                    note: str = "") -> ValueError:
    """The error for a ``renorm_interval`` too long for the orbit: what went wrong between two renormalisations,
    and an interval of about ``factor / w_max`` that works (``note``: added to that advice)."""
    advice = f"about {factor:g} / w_max = {factor / w_top:.3g} or less" if w_top > 0 else ""
    parts = ", ".join(p for p in (advice, note) if p)
    return ValueError(
        f"lyapunov: {trouble} between two renormalisations (renorm_interval = {_validate.fmt(renorm_interval)}, "
        f"every {_validate.fmt(tau)} in time): {consequence}; use a smaller renorm_interval"
        f"{f' ({parts})' if parts else ''}, w_max = {w_top:.3g} being the largest angular velocity reachable on the "
        f"orbit")


def _lost_spectrum_error(renorm_interval, tau, w_top, lam) -> ValueError:
    """The error for a spectrum whose small exponents the renormalisation lost (their sum is not 0)."""
    return _interval_error(
        renorm_interval, tau, "the spectrum lost its small exponents",
        f"the exponents sum to {float(lam.sum()):.3g} where the flow keeps volumes (0), the largest and smallest "
        f"tangent vectors growing apart by more than double precision resolves",
        w_top, 4.0)


def _range_error(renorm_interval, tau, w_top) -> ValueError:
    """The error for tangent vectors that left double precision between two renormalisations."""
    return _interval_error(
        renorm_interval, tau, "the tangent vectors left double precision",
        f"they grow or shrink like exp(lambda * {_validate.fmt(tau)}), and exp(+-709) is the range of a double, so "
        f"the exponents would be NaN or infinite", w_top, 100.0, "the default is 1.0")


@dataclass(frozen=True)
class LyapunovResult:
    r"""Lyapunov exponents from :func:`lyapunov` or :func:`lyapunov_sweep` (always this object).

    ``float(result)`` is a single orbit's maximal exponent, and ``np.asarray(result)`` is
    :attr:`exponents`.

    Attributes
    ----------
    exponents : ndarray
        The estimates at ``T``: shape batch (the orbits' leading axes; ``()`` for one orbit)
        for the maximal exponent, batch + ``(k,)`` for a spectrum (in the order of the
        Gram-Schmidt vectors, i.e. decreasing for long runs).
    t : ndarray (K,)
        Times of the running estimates: every renormalisation with ``history=True``,
        else only ``T`` (``K = 1``).
    history : ndarray or None
        Running estimates :math:`\lambda(t)`, batch + ``(K,)`` (+ ``(k,)``), with
        ``history=True``; ``None`` otherwise.
    k : int
        Number of exponents per orbit (1 for the maximal exponent only).
    method : str
        The splitting whose tangent map was used.
    rng : Any
        The ``rng`` argument of the call (the default seed 0 unless one was given).
    """

    __eq__ = fields_equal  # (field by field: the generated == refuses array fields)
    __hash__ = None

    exponents: np.ndarray
    t: np.ndarray
    history: np.ndarray | None
    k: int
    method: str
    rng: Any = 0

    def __float__(self) -> float:
        if self.exponents.size != 1:
            raise TypeError(f"float() needs one exponent, this result holds {self.exponents.shape}: "
                            f"use result.exponents")
        return float(self.exponents.reshape(()))

    def __array__(self, dtype=None, copy=None):
        return np.asarray(self.exponents, dtype=dtype)


def _result(t, lam, batch, spectrum, history, k, method, rng) -> LyapunovResult:
    """(B, K, k) -> a LyapunovResult with the documented shapes."""
    lam = lam.reshape(batch + lam.shape[1:])
    if not spectrum:
        lam = lam[..., 0]
    final = lam[..., -1, :] if spectrum else lam[..., -1]
    return LyapunovResult(exponents=np.asarray(final), t=np.asarray(t), history=lam if history else None, k=k,
                          method=method, rng=rng)


# ----------------------------------------------------------------------------
# public entry points
# ----------------------------------------------------------------------------
def lyapunov(
    body: Any,
    omega0: Any,
    T: float,
    *,
    spectrum: bool | int = False,
    method: str = "splitting8",
    dt: float | None = None,
    renorm_interval: float = 1.0,
    history: bool = False,
    rng: Any = 0,
    client: Any = None,
    chunk_size: int | None = None,
    progress: bool | None = None,
) -> LyapunovResult:
    r"""Lyapunov exponents of the free body's Euler equations (Benettin, structure-preserving tangent map).

    Parameters
    ----------
    body : RigidBody, Inertia or array_like (n,)
        the body (plane moments :math:`I_{ij}` in plane order).
    omega0 : array_like (n,) or batch + (n,)
        initial angular velocities :math:`\omega_{ij}(0)`; leading axes are an ensemble
        of orbits (one exponent per orbit).
    T : float
        length of the run (> 0). Exponents converge like :math:`1/T` (regular orbits:
        :math:`\log T / T`).
    spectrum : bool or int
        ``False``: the maximal exponent; ``True``: all ``n`` exponents (QR
        re-orthonormalisation of ``n`` tangent vectors); an integer ``k``: the ``k``
        largest.
    method : str
        one of :data:`LYAPUNOV_METHODS`, the splitting whose tangent map is used.
    dt : float, optional
        step; default ``options["lyapunov_step"] / w_max`` per orbit (module docstring).
    renorm_interval : float
        time between re-orthonormalisations (rounded so that they divide ``T``).
    history : bool
        also keep the running estimates :math:`\lambda(t)` at every renormalisation
        (:attr:`LyapunovResult.history`).
    rng : int, SeedSequence, Generator or None
        source of the random initial tangent vectors. The default is the fixed seed ``0``:
        the same call gives the same numbers; pass another seed (or a Generator) to vary
        the tangent vectors, ``None`` for fresh entropy.
    client : dask.distributed.Client, optional
        run the ensemble on its cluster (same numbers as in-process); ``None`` uses all
        local cores (threads).
    chunk_size : int, optional
        orbits per chunk (default: about ``options["chunk_seconds"]`` of work,
        at least four chunks per worker thread).
    progress : bool or None
        tqdm progress bar (``None``: on a terminal, for runs over a second): orbits done, or
        renormalisations done when the orbits run in time segments (an orbit longer than
        ``options["chunk_seconds"]`` goes on in segments of whole renormalisations, a renormalisation
        longer than that in pieces of its steps, with the same numbers as one call; Ctrl-C is honoured
        between segments and pieces).

    Returns
    -------
    LyapunovResult
        ``exponents``: shape batch (``()`` for one orbit) for the maximal exponent, batch +
        ``(k,)`` for a spectrum (exponents in the order of the Gram-Schmidt vectors, i.e.
        decreasing for long runs); ``t`` and ``history`` (batch + ``(K,)`` (+ ``(k,)``))
        with ``history=True``. ``float(result)`` gives a single exponent.

    Raises
    ------
    ValueError
        bad shapes or values (named), unknown method, a run over the budget
        ``options["lyapunov_max_work"]`` (with its estimate); a ``renorm_interval`` so long
        that the tangent vectors leave double precision between renormalisations (growth
        :math:`e^{\lambda\tau}` beyond :math:`e^{709}`: the exponents would be NaN); a ``T`` so short that
        the tangent vectors' growth :math:`1 + O(T w_{max})` is round-off (:math:`T w_{max}` below
        :data:`LEAST_TURN`, ``w_max`` the largest angular velocity reachable on the orbits).
    TypeError
        non-numeric input, a ``client`` that is not a dask client.

    Examples
    --------
    >>> import hyperrotor as hr
    >>> top = hr.Inertia([1.0, 2.0, 3.0])
    >>> res = hr.lyapunov(top, [0.3, 1.0, 0.2], T=200.0)   # reproducible: default rng=0
    >>> 0.0 < float(res) < 0.05   # regular: decays like log T / T
    True
    """
    moments = _validate.moments(body, name="body")
    n = moments.size
    w0 = _validate.components("omega0", omega0, n, what="angular velocities omega_ij in plane order")
    T, method, dt, renorm_interval, k, as_spectrum = _check_common(T, spectrum, method, dt, renorm_interval, n, history)
    batch = w0.shape[:-1]
    B = int(np.prod(batch)) if batch else 1
    # the orbits' rows and their k tangent vectors, before any copy (the sweep's memory model: one body)
    _pricing.check("lyapunov_sweep", bodies=1, orbits=B, n=n, k=k)
    L0 = np.ascontiguousarray(w0.reshape(B, n) * moments)
    t, lam = _benettin(moments[None, :], np.broadcast_to(moments, (B, n)), L0, T, k, method, dt, renorm_interval,
                       history, rng,
                       client, chunk_size, progress, "lyapunov")
    return _result(t, lam, batch, as_spectrum, history, k, method, rng)


def lyapunov_sweep(
    bodies: Any,
    omega0: Any,
    T: float,
    *,
    spectrum: bool | int = False,
    method: str = "splitting8",
    dt: float | None = None,
    renorm_interval: float = 1.0,
    history: bool = False,
    rng: Any = 0,
    client: Any = None,
    chunk_size: int | None = None,
    progress: bool | None = None,
) -> LyapunovResult:
    r"""Lyapunov exponents over a grid of bodies x initial conditions, in one (distributed) call.

    Every body is combined with every initial condition; the ``P * M`` orbits form one
    ensemble that is cut into chunks: in-process threads, or tasks on a dask ``client``
    (``docs/scaling-out.md``). Each orbit's exponent is the one
    :func:`lyapunov` gives for it with the same tangent vector.

    Parameters
    ----------
    bodies : sequence of bodies, or array_like (P, n)
        ``P`` bodies of the same dimension (``RigidBody``, ``Inertia``, or moment rows).
    omega0 : array_like (M, n) or (P, M, n)
        initial angular velocities: the same ``M`` for every body, or ``M`` per body
        (e.g. the same angular momenta, ``L0 / moments``).
    T, spectrum, method, dt, renorm_interval, history, rng, client, chunk_size, progress
        as in :func:`lyapunov`.

    Returns
    -------
    LyapunovResult
        ``exponents`` of shape ``(P, M)`` (+ ``(k,)`` for a spectrum); with ``history``,
        ``history`` of shape ``(P, M, K[, k])``.
    """
    if isinstance(bodies, np.ndarray) and bodies.ndim == 2:  # checked at once (a row loop costs ~1 us per body)
        moments = _validate.finite_array("bodies", bodies, ndim=2)
        dimension_from_count(moments.shape[1])
        if np.any(moments <= 0):
            p = int(np.flatnonzero(np.any(moments <= 0, axis=1))[0])
            raise ValueError(f"bodies[{p}]: moments of inertia must be finite and > 0, got "
                             f"{_validate.fmt(moments[p])}")
    else:
        try:
            seq = list(bodies)
        except TypeError:
            raise TypeError(f"bodies must be a sequence of bodies or a (P, n) array of moments, got "
                            f"{_validate.fmt(bodies)}") from None
        rows = [_validate.moments(b, name=f"bodies[{p}]") for p, b in enumerate(seq)]
        if not rows:
            raise ValueError("bodies must name at least one body")
        bad = [p for p, r in enumerate(rows) if r.size != rows[0].size]
        if bad:
            raise ValueError(f"all bodies must have the same dimension: bodies[0] has {rows[0].size} plane moments, "
                             f"bodies[{bad[0]}] has {rows[bad[0]].size}")
        moments = np.array(rows).reshape(len(rows), -1)
    if moments.shape[0] == 0:
        raise ValueError("bodies must name at least one body")
    P, n = moments.shape
    w0 = _validate.components("omega0", omega0, n, what="angular velocities omega_ij in plane order")
    _pricing.check("lyapunov_sweep", bodies=P, orbits=w0.shape[-2] if w0.ndim > 1 else 1, n=n)
    if w0.ndim == 2:
        Mrows, Wrows = _parallel.grid_rows(moments, w0)
        M = w0.shape[0]
    elif w0.ndim == 3 and w0.shape[0] == P:
        M = w0.shape[1]
        Mrows, Wrows = np.repeat(moments, M, axis=0), w0.reshape(P * M, n)
    else:
        raise ValueError(f"omega0 must have shape (M, {n}) (shared by the bodies) or ({P}, M, {n}) (per body), "
                         f"got shape {w0.shape}")
    T, method, dt, renorm_interval, k, as_spectrum = _check_common(T, spectrum, method, dt, renorm_interval, n, history)
    if k > 1:  # (the k tangent vectors of every orbit: priced with k = 1 above, before k was known)
        _pricing.check("lyapunov_sweep", bodies=P, orbits=M, n=n, k=k)
    L0 = np.ascontiguousarray(Wrows * Mrows)
    t, lam = _benettin(moments, Mrows, L0, T, k, method, dt, renorm_interval, history, rng,
                       client, chunk_size, progress, "lyapunov sweep")
    return _result(t, lam, (P, M), as_spectrum, history, k, method, rng)
