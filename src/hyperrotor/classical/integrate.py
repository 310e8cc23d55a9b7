r"""Numerical integration of the N-dimensional Euler equations: :func:`simulate`.

Equations (eqs. 24-26 of the paper, components; identical in the "paper" and
"standard" matrix conventions, see :mod:`hyperrotor.conventions`)

.. math:: \dot L_a = \sum_{b,c} C_{bc}^{\;a}\,\omega_b L_c + \tau_a,
          \qquad L_a = I_a\,\omega_a, \qquad \dot T = \Omega\,T,

i.e. :math:`\dot L = [\Omega, L] + \tau` with plain matrices, ``tau`` an optional
body-frame torque (components in plane order, units of :math:`dL/dt`) and
``T`` the attitude of eq. (19) (space to body: :math:`L_\text{body} = T L_\text{space} T^{\mathsf T}`),
:math:`\Omega` the angular-velocity matrix in the body's convention.

Methods
-------
``"splitting2"``, ``"splitting4"``, ``"splitting6"``, ``"splitting8"``
    Lie-Poisson splitting. The Hamiltonian, shifted by a multiple of the Casimir
    :math:`C_2 = \tfrac12\sum_a L_a^2` (same motion of ``L``, see :func:`casimir_shift`),
    :math:`H - c\,C_2 = \sum_a \rho_a L_a^2/2` with :math:`\rho_a = 1/I_a - c`,
    is split into one term per plane; the flow of :math:`\rho_a L_a^2/2` keeps
    :math:`L_a` fixed and rotates :math:`L` (and ``T``) exactly by the angle
    :math:`h \rho_a L_a` in plane ``a`` (see :mod:`hyperrotor.classical._kernels`).
    Planes with :math:`\rho_a = 0` (those whose moment equals ``1/c``) drop out;
    the attitude is corrected for the shift exactly; with a torque there is no shift.
    The basic method :math:`S_2(h)` is Strang's symmetric product over the remaining
    planes in paper order followed by the reverse order (order 2). Orders 4, 6, 8 are
    symmetric compositions :math:`S_2(\gamma_s h)\cdots S_2(\gamma_1 h)`:

    * order 4: Yoshida's / Suzuki's triple jump, :math:`\gamma_1 = \gamma_3 =
      1/(2 - 2^{1/3})`, :math:`\gamma_2 = 1 - 2\gamma_1` (Yoshida, Phys. Lett. A 150,
      262 (1990));
    * order 6: Kahan & Li's 9-stage set ``s9odr6a``;
    * order 8: Kahan & Li's 17-stage set ``s17odr8a`` (W. Kahan and R.-C. Li,
      Math. Comp. 66, 1089 (1997); coefficients as tabulated in Hairer, Lubich,
      Wanner, *Geometric Numerical Integration*, 2nd ed., Sec. V.3.2, p. 157).

    Every elementary flow is an exact coadjoint rotation, so the Casimirs
    (coefficients of the characteristic polynomial of ``L``, eq. 38) are kept
    to round-off, the maps are Poisson (symplectic on each coadjoint orbit),
    symmetric and time-reversible, and the energy error stays bounded (no
    drift) over long runs. ``T`` stays orthogonal to round-off. Fixed steps;
    with ``rtol`` the step is chosen by the rule of :func:`_choose_step`.
    A *constant* body torque is supported as an exact kick
    :math:`L \mapsto L + \tfrac{\gamma h}{2}\tau` on both sides of each
    :math:`S_2(\gamma h)` (still symmetric, so the composed orders hold; the
    Casimirs are then of course not conserved). Callable torques need a
    scipy method.
``"moser-veselov"``
    The discrete Moser-Veselov algorithm (:mod:`hyperrotor.classical.moser_veselov`):
    implicit, order 2, symplectic and time-reversible; ``L`` moves by exact
    conjugation (Casimirs to round-off) and ``T`` by an exact rotation. Needs a
    mass tensor (:math:`I_{ij} = J_i + J_j`) and no torque; ``dt`` or ``rtol`` (the
    rule of :func:`_choose_step`). A reference method: per step it costs about as
    much as a few hundred plane flows (Newton on the Cayley parameter), so the
    splittings reach a given error much sooner (``benchmarks/work_precision_classical.py``).
``"DOP853"``, ``"RK45"``, ``"LSODA"``, ``"Radau"``
    :func:`scipy.integrate.solve_ivp` with ``rtol`` and
    ``atol_a = rtol * min(max|omega0|, |L0| / I_a)`` on the angular velocities (and the attitude
    entries when asked), one call per ensemble member; the right-hand side is
    ``body.rhs`` when ``body`` is a :class:`hyperrotor.RigidBody`, else an
    equivalent sparse evaluation of the component equations.
``"auto"``
    A callable torque -> ``"DOP853"``. Otherwise the splitting of order 2, 4, 6
    or 8 for ``rtol >= 1e-2``, ``>= 1e-4``, ``>= 1e-7``, smaller (on the
    work-precision benchmark order 8 is the cheapest from ~1e-6 down;
    ``benchmarks/work_precision_classical.py``); with only ``dt`` given, ``"splitting4"``.

Performance notes
-----------------
The splitting kernels (:mod:`hyperrotor.classical._kernels`) are compiled by numba
on first use and cached on disk: a cold first call costs about 1.3 s (one body),
2.8 s (ensemble kernel) and 2.5 s (ensemble with attitude) on the reference
machine, a cached one about 0.1 s. One body (or fewer than 32) runs a serial
kernel; ensembles without attitude run a chunked kernel with the bodies
innermost (vectorised, threads over chunks); ensembles with attitude run one
thread per body. With ``compensated`` (automatic for runs of more than 1e6
elementary flows per trajectory or ``rtol < 1e-11``) the rotation increments are
added with error-free TwoSum (compensated storage of ``L``), so round-off does not
random-walk the Casimirs: their relative drift stays ~1e-15 after 1e6 steps, and the
trajectory's round-off floor stays ~1e-15. Otherwise plain arithmetic (~1.6x faster
per flow): the Casimirs' round-off random-walks as ~0.1-0.4 eps sqrt(flows) (< 1e-13),
the trajectory's floor is ~1e-13 .. 1e-12, like scipy's DOP853. Measured work-precision and
throughput: ``benchmarks/work_precision_classical.py``.
"""
from __future__ import annotations

import math
import time
from functools import lru_cache
from numbers import Real
from typing import Any, Callable

import numpy as np

from hyperrotor.conventions import (
    check_convention,
    dimension_from_count,
    planes,
    structure_constants,
    to_matrix,
)

from . import _kernels, moser_veselov
from .inertia import body_moments

__all__ = ["simulate", "Trajectory", "SIMULATION_METHODS", "splitting_coefficients", "casimir_shift"]

#: Allowed ``method=`` names of :func:`simulate`.
SIMULATION_METHODS = ("auto", "splitting2", "splitting4", "splitting6", "splitting8", "moser-veselov",
                      "DOP853", "RK45", "LSODA", "Radau")
_SCIPY_METHODS = ("DOP853", "RK45", "LSODA", "Radau")
_SPLITTING_ORDER = {"splitting2": 2, "splitting4": 4, "splitting6": 6, "splitting8": 8}

_DEFAULT_RTOL = 1e-9
#: ensembles at least this large use the threaded kernel (thread launch costs ~ms on a busy machine)
_PARALLEL_MIN_BODIES = 32
_ENSEMBLE_CHUNK = 128  # bodies per chunk of the ensemble kernel (working set fits in L1/L2)
#: ``compensated=None``: runs of more elementary flows than this (per trajectory) keep L in
#: compensated storage (plain round-off of the Casimirs random-walks as ~0.1-0.4 eps sqrt(flows)) ...
_COMPENSATE_ABOVE = 1_000_000
#: ... and so do runs asked for an rtol below this (plain round-off of omega reaches ~1e-13..1e-12)
_COMPENSATE_BELOW_RTOL = 1e-11
#: budget (elementary flows) of the step rule's check of its chosen step over the whole run
_CHECK_FLOWS = 3_000_000

# Half of each symmetric coefficient set (the middle one last); see the module docstring.
_KAHAN_LI_6 = (
    0.39216144400731413927925056,
    0.33259913678935943859974864,
    -0.70624617255763935980996482,
    0.08221359629355080023149045,
)
_KAHAN_LI_8 = (
    0.13020248308889008087881763,
    0.56116298177510838456196441,
    -0.38947496264484728640807860,
    0.15884190655515560089621075,
    -0.39590389413323757733623154,
    0.18453964097831570709183254,
    0.25837438768632204729397911,
    0.29501172360931029887096624,
)


def splitting_coefficients(order: int) -> np.ndarray:
    r"""Composition coefficients :math:`\gamma_1, \dots, \gamma_s` of the splitting of ``order``.

    The step is :math:`S_2(\gamma_s h) \cdots S_2(\gamma_1 h)` with Strang's
    :math:`S_2`; the sets are symmetric and sum to 1 (the middle coefficient is
    computed as ``1 - 2 * sum(others)`` so that the sum is exact to round-off).

    ====== ====== ==========================================================
    order  stages set
    ====== ====== ==========================================================
    2      1      Strang
    4      3      Yoshida / Suzuki triple jump
    6      9      Kahan & Li ``s9odr6a`` (Math. Comp. 66, 1089 (1997))
    8      17     Kahan & Li ``s17odr8a`` (same reference)
    ====== ====== ==========================================================
    """
    if order == 2:
        return np.array([1.0])
    if order == 4:
        g = 1.0 / (2.0 - 2.0 ** (1.0 / 3.0))
        return np.array([g, 1.0 - 2.0 * g, g])
    if order in (6, 8):
        half = np.array(_KAHAN_LI_6 if order == 6 else _KAHAN_LI_8)
        return np.concatenate([half, [1.0 - 2.0 * half.sum()], half[::-1]])
    raise ValueError(f"splitting order must be one of 2, 4, 6, 8, got {order!r}")


def casimir_shift(moments: Any, L: Any = None) -> float | np.ndarray:
    r"""The shift ``c`` of the split Hamiltonian :math:`H - c\,C_2` used by the splitting methods.

    :math:`C_2 = \tfrac12\sum_a L_a^2` is a Casimir, so :math:`H` and
    :math:`H - c\,C_2 = \sum_a \rho_a L_a^2/2`, :math:`\rho_a = 1/I_a - c`, generate the
    same motion of ``L`` for every ``c``; only the angles :math:`h\rho_a L_a` of the
    elementary flows change. The splitting error is built from brackets of the plane
    terms, each proportional to products of these angles, so small :math:`|\rho_a L_a|`
    make it small, and a plane with :math:`\rho_a = 0` drops out of the step altogether.

    The rule: ``c`` minimises :math:`\sum_a w_a\,|1/I_a - c|` with the weights
    :math:`w_a = \min(|L|, \sqrt{2EI_a})/|L|` (the bound on :math:`|L_a|` over the orbit,
    from the Casimir and the energy; equal weights without ``L`` or for ``L = 0``), i.e.
    ``c`` is the weighted median of the :math:`1/I_a`, which is one of them (ties go to
    the value shared by most planes, then to the smaller). On the 5D work-precision
    problems this cuts the cost at error 1e-10 by about 2x (generic body) and 8x (quartet,
    whose six planes of equal moment all drop out; ``benchmarks/work_precision_classical.py``);
    with moments spread over 12 decades the weights keep ``c`` among the heavy planes,
    which carry the momentum. With equal moments every plane drops out and ``L`` is
    (exactly) constant.

    :func:`simulate` takes one ``c`` per ensemble member (a member's result does not
    depend on the others) and none with a torque (the weights would be stale). The
    attitude feels the shift: the flow of :math:`c\,C_2` turns ``T`` at the rate
    :math:`c\,L`; :func:`simulate` puts it back exactly (see ``_unshift_attitude``).

    Parameters
    ----------
    moments : array_like (n,)
        plane moments :math:`I_a` (finite, positive).
    L : array_like (n,) or (B, n), optional
        angular momenta (one row per ensemble member).

    Returns
    -------
    float, or ndarray (B,) for a 2-D ``L``
        ``c``, equal to one of the :math:`1/I_a`.
    """
    moments = body_moments(moments)
    n = moments.size
    rates = 1.0 / moments
    values, counts = np.unique(rates, return_counts=True)
    if L is None:
        Lb = np.zeros((1, n))
    else:
        try:
            Lb = np.asarray(L, dtype=float)
        except (TypeError, ValueError):
            raise TypeError(f"L must be numeric, shape ({n},) or (B, {n}), got {L!r}") from None
        if Lb.ndim not in (1, 2) or Lb.shape[-1] != n:
            raise ValueError(f"L must have shape ({n},) or (B, {n}) for these {n} moments, got {Lb.shape}")
        if not np.all(np.isfinite(Lb)):
            raise ValueError("L must be finite (found NaN or inf)")
    L2 = np.atleast_2d(Lb)
    norm = np.sqrt(np.sum(L2 * L2, axis=1, keepdims=True))
    E2 = np.sum(L2 * L2 / moments, axis=1, keepdims=True)
    safe = np.where(norm > 0, norm, 1.0)
    weights = np.where(norm > 0, np.minimum(norm, np.sqrt(E2 * moments)) / safe, 1.0)  # (B, n)
    cost = weights @ np.abs(rates[:, None] - values[None, :])  # (B, V)
    cost = np.round(cost / np.maximum(cost.max(axis=1, keepdims=True), 1e-300), 12)  # equal to round-off: tie
    score = np.where(cost == cost.min(axis=1, keepdims=True), counts[None, :], -1)
    c = values[np.argmax(score, axis=1)]  # first maximum: most planes, then the smaller value
    return float(c[0]) if L is None or Lb.ndim == 1 else c


@lru_cache(maxsize=None)
def _splitting_word(order: int, seq: tuple[int, ...], kick: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """One step as a word of elementary flows (plane index, fraction of h); -1 = torque kick.

    Strang's :math:`S_2` runs the planes of ``seq`` forward with half steps, the last
    one with a full step, and back; adjacent flows of the same plane are merged (they
    commute, the sum is exact).
    """
    word: list[list] = []

    def push(a, c):
        if word and word[-1][0] == a:
            word[-1][1] += c
        else:
            word.append([a, c])

    for g in splitting_coefficients(order):
        if kick:
            push(-1, g / 2)
        if seq:
            for a in seq[:-1]:
                push(a, g / 2)
            push(seq[-1], g)
            for a in seq[-2::-1]:
                push(a, g / 2)
        if kick:
            push(-1, g / 2)
    word = [w for w in word if w[1] != 0.0]
    planes_ = np.array([w[0] for w in word], dtype=np.int64)
    coefs = np.array([w[1] for w in word], dtype=np.float64)
    planes_.setflags(write=False)
    coefs.setflags(write=False)
    return planes_, coefs


def _unshift_attitude(att: np.ndarray, L0: np.ndarray, T0: np.ndarray, t: np.ndarray, c: np.ndarray) -> np.ndarray:
    r"""Attitude of :math:`H` from the attitude ``att`` (B, K, N, N) of :math:`H - c\,C_2` (plain convention).

    The flows of :math:`H - cC_2` and :math:`cC_2` commute; the latter keeps ``L`` and
    turns the attitude, :math:`\dot T = c\,L\,T`. With the conserved space-frame momentum
    :math:`\Lambda = T_0^{\mathsf T} L_0 T_0` (``L = T \Lambda T^T``) this gives
    :math:`T(t) = T'(t)\,\exp\bigl(c\,(t - t_0)\,\Lambda\bigr)`, evaluated exactly from one
    eigen-decomposition of the Hermitian :math:`i\Lambda` per body (orthogonal to round-off);
    ``c`` has one entry per body.
    """
    Lam = np.swapaxes(T0, -1, -2) @ to_matrix(L0, "standard") @ T0  # (B, N, N)
    lam, U = np.linalg.eigh(1j * Lam)  # Lam = U diag(-i lam) U^H
    phase = np.exp(-1j * c[:, None, None] * (t - t[0])[None, :, None] * lam[:, None, :])  # (B, K, N)
    E = np.einsum("brm,bkm,bsm->bkrs", U, phase, U.conj()).real
    return att @ E


@lru_cache(maxsize=None)
def _rotation_tables(N: int):
    tables = _kernels.rotation_tables(N)
    for arr in tables:
        arr.setflags(write=False)
    return tables


# ----------------------------------------------------------------------------
# inputs
# ----------------------------------------------------------------------------
def _moments_and_n(body: Any) -> tuple[np.ndarray, int]:
    """Plane moments (see :func:`~hyperrotor.classical.inertia.body_moments`) and ``N``."""
    moments = body_moments(body)
    return moments, dimension_from_count(moments.size)


def _convention_of(body: Any) -> str:
    return check_convention(getattr(body, "convention", "paper"))


def _check_time_grid(t: Any) -> np.ndarray:
    try:
        t = np.asarray(t, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"t must be a 1-D array of increasing output times, got {t!r}") from None
    if t.ndim != 1 or t.size < 1:
        raise ValueError(f"t must be a 1-D array of output times (at least one), got shape {t.shape}")
    if not np.all(np.isfinite(t)):
        raise ValueError("t must be finite (no NaN or inf)")
    bad = np.nonzero(np.diff(t) <= 0)[0]
    if bad.size:
        k = int(bad[0])
        raise ValueError(f"t must be strictly increasing; t[{k}] = {t[k]!r} >= t[{k + 1}] = {t[k + 1]!r}")
    return t


def _check_positive(name: str, value: Any) -> float | None:
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (Real, np.floating, np.integer)):
        raise TypeError(f"{name} must be a positive real number, got {value!r}")
    value = float(value)
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"{name} must be finite and > 0, got {value!r}")
    return value


def _broadcast_batch(name: str, arr: np.ndarray, core_ndim: int, batch: tuple) -> np.ndarray:
    lead = arr.shape[: arr.ndim - core_ndim]
    try:
        out_shape = np.broadcast_shapes(lead, batch)
    except ValueError:
        out_shape = None
    if out_shape != batch:
        raise ValueError(
            f"{name} has batch axes {lead}, inconsistent with the batch axes {batch} of omega0 "
            f"(they must be equal or broadcast to it)"
        )
    return np.broadcast_to(arr, batch + arr.shape[arr.ndim - core_ndim:])


def _sign_diag(body: Any, N: int, convention: str) -> np.ndarray:
    """Diagonal of S with T_conv = S T_plain S: (-1)^axis for "paper" (original axis labels of a
    locked RigidBody, ``body.axes``), ones for "standard"."""
    if convention == "standard":
        return np.ones(N)
    axes = tuple(getattr(body, "axes", range(1, N + 1)))
    if len(axes) != N:
        axes = tuple(range(1, N + 1))
    return np.array([(-1.0) ** int(a) for a in axes])


# ----------------------------------------------------------------------------
# result
# ----------------------------------------------------------------------------
class Trajectory:
    r"""Result of :func:`simulate`.

    Attributes
    ----------
    t : ndarray (K,)
        output times.
    omega : ndarray batch + (K, n)
        angular velocities :math:`\omega_{ij}(t)` in plane order.
    L : ndarray batch + (K, n)
        body-frame angular momenta :math:`L^{ij} = I_{ij}\omega_{ij}`.
    attitude : ndarray batch + (K, N, N) or None
        :math:`T(t)` (eq. 19) in the body's matrix convention, ``None`` unless asked.
    body : object
        the ``body`` argument.
    moments : ndarray (n,)
        the plane moments used.
    stats : dict
        ``method``, ``order`` (splitting) , ``steps`` (steps per trajectory for
        the splitting methods, ``None`` for scipy), ``nfev`` (scipy, summed over
        the ensemble), ``dt`` (largest step used), ``rtol``, ``wall_time`` (s);
        for the splitting methods also ``flows_per_step`` (elementary plane flows
        in one step), ``casimir_shift`` (the ``c`` of :func:`casimir_shift`) and
        ``compensated`` (whether ``L`` was kept in compensated storage, see the
        performance notes).
    """

    def __init__(self, t, omega, L, attitude, body, moments, stats):
        self.t = t
        self.omega = omega
        self.L = L
        self.attitude = attitude
        self.body = body
        self.moments = moments
        self.stats = stats

    def energy(self) -> np.ndarray:
        r"""Kinetic energy :math:`\tfrac12\sum_{i<j} I_{ij}\omega_{ij}^2`, shape batch + (K,)."""
        return 0.5 * np.sum(self.L * self.omega, axis=-1)

    def __repr__(self) -> str:
        return (f"Trajectory(method={self.stats.get('method')!r}, batch={self.omega.shape[:-2]}, "
                f"len(t)={self.t.size}, n_planes={self.omega.shape[-1]}, attitude={self.attitude is not None})")


# ----------------------------------------------------------------------------
# splitting driver
# ----------------------------------------------------------------------------
def _nsub_for(t: np.ndarray, dt: float) -> np.ndarray:
    gaps = np.diff(t)
    return np.maximum(1, np.ceil(gaps / dt * (1 - 1e-12))).astype(np.int64)


def _run_split(L0, rates_b, word, tables, t, nsub, torque_b, T0, with_att, compensated):
    """Dispatch to a kernel: one body or a few -> serial; an ensemble without attitude ->
    bodies-innermost chunks over threads; an ensemble with attitude -> threads over bodies.
    ``compensated``: TwoSum storage of ``L`` (see the performance notes)."""
    B, n = L0.shape
    N = T0.shape[-1]
    outL = np.empty((B, t.size, n))
    L0 = np.ascontiguousarray(L0)
    rates_b = np.ascontiguousarray(rates_b)
    torque_b = np.ascontiguousarray(torque_b)
    if B >= _PARALLEL_MIN_BODIES and not with_att:
        chunk = max(1, min(_ENSEMBLE_CHUNK, -(-B // 8)))
        _kernels.split_run_ensemble(L0, rates_b, word[0], word[1], *tables[:3], t, nsub, torque_b, chunk,
                                    compensated, outL)
        return outL, None
    outT = np.empty((B, t.size, N, N)) if with_att else np.empty((B, 1, N, N))
    kernel = _kernels.split_run if B >= _PARALLEL_MIN_BODIES else _kernels.split_run_serial
    kernel(L0, rates_b, word[0], word[1], *tables, t, nsub, torque_b, np.ascontiguousarray(T0),
           bool(with_att), compensated, outL, outT)
    return outL, (outT if with_att else None)


def _triples(N: int):
    """Plane indices (c, a, b) of every coupled triple {ij, ik, jk}, each plane in turn as c."""
    idx = {p: k for k, p in enumerate(planes(N))}
    out = []
    for i in range(1, N + 1):
        for j in range(i + 1, N + 1):
            for k in range(j + 1, N + 1):
                t3 = (idx[(i, j)], idx[(i, k)], idx[(j, k)])
                out += [(t3[0], t3[1], t3[2]), (t3[1], t3[0], t3[2]), (t3[2], t3[0], t3[1])]
    arr = np.array(out, dtype=np.int64).reshape(-1, 3)
    return arr[:, 0], arr[:, 1], arr[:, 2]


def _choose_step(L0, moments, order, T_total, rtol, torque_b, N, probe, ops_per_step):
    r"""Step size for a requested relative accuracy ``rtol`` (splitting methods).

    Rule: the global error of the order-``p`` method over the run is modelled as
    :math:`e(h) \approx C\,(t_\text{end}-t_0)\,h^p` (linear growth in time, the
    generic behaviour for the phase error of these integrable / near-integrable
    motions; chaotic motion grows faster and is not covered by any rule).
    ``C`` is measured by Richardson's estimate on a probe interval
    :math:`P = \min(t_\text{end}-t_0, 20/\max|\omega_0|)` for up to 8 members of the
    ensemble (those with the largest :math:`|\omega_0|`): one run with step
    ``h`` and one with ``h/2`` give
    :math:`e_P(h) \approx \max|\omega_h - \omega_{h/2}| / ((1 - 2^{-p})\max|\omega_0|)`.
    Here :math:`\max|\omega|` is the bound :math:`\max_a \min(|L|, \sqrt{2 E I_a})/I_a` on the
    rates reachable on the orbit (from the Casimir :math:`|L|^2` and the energy ``E``),
    not just the initial rates (which can be far smaller for stiff moment ratios), and
    of the linearised frequencies :math:`|\omega_c|\sqrt{|(I_c-I_a)(I_c-I_b)|/(I_aI_b)}` of every
    coupled triple of planes (no larger than the rates for physical moments
    :math:`I_{ij} = J_i + J_j`; much larger, i.e. stiff, for moments violating the triangle
    inequalities, where an implicit scipy method such as ``"Radau"`` can be cheaper).
    ``h`` starts at :math:`1/\max|\omega|` and is refined (x1/4) while the
    estimate is not asymptotic (:math:`e_P > 10^{-2}`) or enlarged (x4; once
    ``h = P``, ``P`` grows x4 up to the whole run) while it is at round-off level.
    The step is then
    :math:`h^* = \min\bigl(8h,\; 0.8\,h\,(\mathrm{rtol} / (e_P(h)\max(1, (t_\text{end}-t_0)/P)))^{1/p}\bigr)`;
    the step is then checked by one more Richardson estimate at :math:`h^*` (max over 16
    sample times) over the whole run when that costs at most 3e6 elementary flows (a few tens
    of ms), else, if :math:`h^* > h`, over :math:`\max(P, 2h^*)`, and halved (or shortened as
    the check's estimate says) until the estimate is within ``rtol``. The error model can
    break down beyond the probe: near steady rotation the probe sees little motion, an
    unstable rotation can run away after the probe interval (faster than linear growth), and
    near a resonance of the splitting the error jumps with ``h``. For long runs, where the
    check covers only part of the run, unstable or chaotic motion can still amplify the
    error past ``rtol``: no a-priori rule covers it.
    ``rtol`` bounds both :math:`\max_t |\omega(t) - \omega_\text{exact}(t)|_\infty / \max|\omega_0|` and
    :math:`\max_t |L(t) - L_\text{exact}(t)|_\infty / |L_0|_2` (the two differ for stiff moment
    ratios, where the heavy planes have small rates but carry most of ``L``).
    """
    if L0.shape[0] == 0:  # empty ensemble: nothing to integrate
        return T_total
    # bound on every rate reachable on the orbit: |L_a| <= min(|L|, sqrt(2 E I_a)) (Casimir and energy)
    C = np.sqrt(np.sum(L0 * L0, axis=1, keepdims=True))
    E2 = np.sum(L0 * L0 / moments, axis=1, keepdims=True)
    W = np.minimum(C, np.sqrt(E2 * moments)) / moments  # (B, n)
    wmax_b = W.max(axis=1)
    # linearised frequencies about rotation in plane c of a coupled triple (c, a, b):
    # lambda^2 = w_c^2 (I_c - I_a)(I_c - I_b) / (I_a I_b); <= w_c^2 for physical moments, but
    # arbitrarily larger (stiff) when the triangle inequalities I_c <= I_a + I_b fail
    tc, ta, tb = _triples(N)
    if tc.size:
        Ic, Ia, Ib = moments[:, tc], moments[:, ta], moments[:, tb]
        lam = W[:, tc] * np.sqrt(np.abs((Ic - Ia) * (Ic - Ib)) / (Ia * Ib))
        wmax_b = np.maximum(wmax_b, lam.max(axis=1))
    wmax = float(wmax_b.max())
    if wmax == 0.0 and not np.any(torque_b):
        return T_total  # nothing moves
    if np.any(torque_b):  # rate a torque can build up within the run
        wmax = max(wmax, float(np.max(np.abs(torque_b) / moments)) * T_total, float(np.max(np.abs(torque_b) / moments)) ** 0.5)
    sel = np.argsort(wmax_b)[::-1][: min(8, L0.shape[0])]
    L0s, Ms = L0[sel], moments[sel]
    P = min(T_total, 20.0 / wmax)
    scale = float(np.max(np.abs(L0s / Ms))) or wmax  # rtol is relative to max|omega0| ...
    Lnorm = np.maximum(np.sqrt(np.sum(L0s * L0s, axis=1, keepdims=True)), 1e-300)  # ... and to |L0|
    h = min(P, 1.0 / wmax)

    def richardson(Pv, m):
        """Error estimate of about ``m`` steps over [0, Pv], max over 16 sample times (the error
        can peak mid-interval, e.g. at the flip of an unstable rotation); None: the method failed.
        Returns (estimate, step used)."""
        k = min(m, 16)
        ms = int(math.ceil(m / k))
        tg = np.linspace(0.0, Pv, k + 1)
        y1 = probe(sel, tg, np.full(k, ms))
        y2 = probe(sel, tg, np.full(k, 2 * ms)) if y1 is not None else None
        if y1 is None or y2 is None:
            return None, Pv / (k * ms)
        dL = np.abs(y1 - y2)  # (members, k + 1, n)
        e = max(float(np.max(dL / Ms[:, None, :])) / scale, float(np.max(dL / Lnorm[:, :, None])))
        return e / (1.0 - 2.0 ** -order), Pv / (k * ms)

    est = None
    for _ in range(24):
        m = max(1, int(math.ceil(P / h - 1e-9)))
        if m > 200_000:  # probe budget exhausted (should not happen with the rate bound above)
            break
        err, h = richardson(P, m)
        if err is None or not np.isfinite(err) or err > 1e-2:  # failed (implicit step) or not asymptotic
            h /= 4.0
            continue
        floor = 1e3 * np.finfo(float).eps * math.sqrt(2 * m * max(ops_per_step, 1))
        est = (h, err, P)
        if err < floor:  # round-off level: the probe says nothing; try longer steps / a longer probe
            if m > 1:
                h *= 4.0
            elif P < T_total:
                P = h = min(4.0 * P, T_total)
            else:
                break  # one step over the whole run is exact to round-off
            continue
        break
    if est is None:  # never reached the asymptotic regime: fall back on a conservative step
        return min(P, 0.01 / wmax)
    h, err, P = est

    def on_run(e, Pv):  # probe error -> error over the whole run (linear growth), above round-off
        return max(e, 1e3 * np.finfo(float).eps) * max(1.0, T_total / Pv)

    # no extrapolation far beyond the probed step (the error model is asymptotic in h) ...
    h_star = min(8.0 * h, 0.8 * h * (rtol / on_run(err, P)) ** (1.0 / order))
    # ... and the step is checked before it is taken: over the whole run when that costs at most
    # _CHECK_FLOWS elementary flows (an unstable rotation can run away after the probe interval,
    # so that the error grows faster than the linear model says), else, for a step longer than
    # the probed one, over max(P, 2 h*) (near steady rotation the probe can see almost no
    # motion, and near a resonance of the splitting the error jumps with h)
    for _ in range(8):
        m_run = int(math.ceil(T_total / h_star - 1e-9))
        whole = 3 * m_run * len(sel) * max(ops_per_step, 1) <= _CHECK_FLOWS
        if not whole and h_star <= h:
            break
        Pv = T_total if whole else min(T_total, max(P, 2.0 * h_star))
        e, hv = richardson(Pv, max(1, int(math.ceil(Pv / h_star - 1e-9))))
        good = e is not None and np.isfinite(e)
        if good and on_run(e, Pv) <= rtol:
            h_star = hv
            break
        h_model = 0.8 * hv * (rtol / on_run(e, Pv)) ** (1.0 / order) if good else 0.25 * h_star
        h_star = min(0.5 * h_star, h_model)
    return h_star


def _moser_veselov_step(L0, moments, J, T_total, rtol):
    """Step of the Moser-Veselov method for ``rtol``: the rule of :func:`_choose_step` (order 2)."""
    if T_total <= 0:
        return 1.0
    B, n = L0.shape
    moments_b = np.broadcast_to(moments, (B, n))

    def probe(sel, tg, ns):
        try:
            return moser_veselov.run(L0[sel], J, moments, tg, ns, None, False)[0]
        except RuntimeError:  # no solution of the implicit step at this h
            return None

    return _choose_step(L0, moments_b, 2, T_total, rtol, np.zeros((B, n)), J.size, probe, 1)


# ----------------------------------------------------------------------------
# scipy driver
# ----------------------------------------------------------------------------
class _SparseRHS:
    """dw/dt of the component equations from moments and structure constants (used when ``body`` has no ``rhs``)."""

    def __init__(self, moments: np.ndarray, N: int):
        C = structure_constants(N)
        b, c, a = np.nonzero(C)
        self.b, self.c, self.a = b, c, a
        self.coef = C[b, c, a].astype(float)
        n = moments.size
        A = np.zeros((b.size, n))
        A[np.arange(b.size), a] = 1.0
        self.A = A / moments[a][:, None]
        self.moments = moments

    def __call__(self, omega):
        L = omega * self.moments
        return (self.coef * omega[..., self.b] * L[..., self.c]) @ self.A


def _run_scipy(body, method, moments, N, w0, t, rtol, torque, T0, with_att):
    """scipy peers; the attitude is integrated in the plain-matrix convention (T0 plain)."""
    from scipy.integrate import solve_ivp

    rhs = body.rhs if callable(getattr(body, "rhs", None)) else _SparseRHS(moments, N)
    n = moments.size
    B = w0.shape[0]
    K = t.size
    omega = np.empty((B, K, n))
    att = np.empty((B, K, N, N)) if with_att else None
    nfev = 0
    for b in range(B):
        tau_b = None if torque is None or callable(torque) else torque[b]

        def f(tt, y, tau_b=tau_b):
            w = y[:n]
            with np.errstate(over="ignore", invalid="ignore"):  # trial steps may overflow; scipy rejects them
                dw = np.asarray(rhs(w), dtype=float)
            if torque is not None:
                tau = np.asarray(torque(tt, w), dtype=float) if callable(torque) else tau_b
                if tau.shape != (n,) or not np.all(np.isfinite(tau)):
                    raise ValueError(f"torque(t, omega) must return {n} finite body-frame components, got {tau!r}")
                dw = dw + tau / moments
            if not with_att:
                return dw
            Tm = y[n:].reshape(N, N)
            return np.concatenate([dw, (to_matrix(w, "standard") @ Tm).ravel()])

        y0 = w0[b] if not with_att else np.concatenate([w0[b], T0[b].ravel()])
        wscale = float(np.max(np.abs(w0[b]))) or 1.0
        Lscale = float(np.linalg.norm(w0[b] * moments)) or wscale * float(moments.min())
        # error in omega_a <= rtol max|omega0| and in L_a <= rtol |L0| (matters for stiff moments)
        atol = rtol * np.minimum(wscale, Lscale / moments)
        if with_att:
            atol = np.concatenate([atol, np.full(N * N, rtol)])
        if K == 1:
            omega[b, 0] = w0[b]
            if with_att:
                att[b, 0] = T0[b]
            continue
        sol = solve_ivp(f, (t[0], t[-1]), y0, method=method, t_eval=t, rtol=rtol, atol=atol)
        if not sol.success:
            raise RuntimeError(f"scipy {method} failed: {sol.message}")
        nfev += sol.nfev
        omega[b] = sol.y[:n].T
        if with_att:
            att[b] = sol.y[n:].T.reshape(K, N, N)
    return omega, att, nfev


# ----------------------------------------------------------------------------
# public entry point
# ----------------------------------------------------------------------------
def simulate(
    body: Any,
    omega0: Any,
    t: Any,
    method: str = "auto",
    rtol: float | None = None,
    dt: float | None = None,
    attitude: bool | Any = False,
    torque: Callable | Any | None = None,
    *,
    compensated: bool | None = None,
) -> Trajectory:
    r"""Integrate the Euler equations (eqs. 24-26) of a rigid body in N dimensions.

    Parameters
    ----------
    body : RigidBody, Inertia or array_like (n_planes,)
        The body (its matrix convention is used for ``attitude``; plain
        moments or an ``Inertia`` mean ``convention="paper"``).
    omega0 : array_like batch + (n_planes,)
        initial angular velocities :math:`\omega_{ij}(t_0)` in plane order;
        leading axes are an ensemble integrated in one call.
    t : array_like (K,)
        strictly increasing output times; ``t[0]`` is the initial time.
    method : str
        one of :data:`SIMULATION_METHODS` (see the module docstring).
    rtol : float, optional
        requested accuracy: for the splitting methods a bound on
        :math:`\max_t|\omega-\omega_\text{exact}|/\max|\omega_0|` and on
        :math:`\max_t|L-L_\text{exact}|/|L_0|` reached by the step rule of
        :func:`_choose_step`; for scipy the ``rtol`` of ``solve_ivp``
        (``atol_a = rtol * min(max|omega0|, |L0| / I_a)``). Default ``1e-9`` when neither ``rtol``
        nor ``dt`` is given.
    dt : float, optional
        largest step of a splitting method; each output interval is split into
        ``ceil(gap / dt)`` equal steps, so output times are hit exactly. Not
        allowed together with ``rtol`` for a splitting method, nor with a scipy
        method.
    attitude : bool or array_like, optional
        ``True`` integrates :math:`T(t)` from the identity; an array
        ``(N, N)`` or batch + ``(N, N)`` (orthogonal, body convention) is the
        initial attitude.
    torque : array_like or callable, optional
        body-frame torque :math:`\tau_{ij}` added to :math:`\dot L^{ij}`
        (:math:`I_{ij}\dot\omega_{ij} = \dots + \tau_{ij}`): constant components
        (n_planes,) or batch + (n_planes,), or a callable ``torque(t, omega)``
        returning n_planes components (scipy methods only).
    compensated : bool or None, optional
        splitting methods: keep ``L`` in compensated (TwoSum) storage, so that round-off
        does not random-walk the Casimirs and the trajectory (~1.6x slower per step).
        ``None`` (default) means yes for runs of more than 1e6 elementary flows per
        trajectory or ``rtol < 1e-11``, else plain arithmetic (round-off then ~eps
        sqrt(flows), below ~1e-13 for the Casimirs).

    Returns
    -------
    Trajectory
        ``omega``, ``L`` (batch + (K, n)), ``attitude`` (batch + (K, N, N) or
        ``None``) and ``stats``.

    Raises
    ------
    ValueError
        unknown method, non-finite or mis-shaped ``omega0``, ``t`` not strictly
        increasing, inconsistent batch axes, conflicting ``dt``/``rtol``,
        non-positive ``dt``/``rtol``, callable torque with a splitting method.
    TypeError
        non-numeric input.
    RuntimeError
        ``"moser-veselov"`` with a step too long for its implicit equation (no solution
        near the identity); a scipy method that fails.

    Examples
    --------
    >>> import numpy as np
    >>> traj = simulate([2.0, 3.0, 4.0], [0.1, 1.0, 0.2], np.linspace(0, 10, 5), method="splitting4", dt=0.01)
    >>> traj.omega.shape
    (5, 3)
    """
    wall = time.perf_counter()
    Lout = None
    if not isinstance(method, str) or method not in SIMULATION_METHODS:
        raise ValueError(f"unknown method {method!r}; allowed: {', '.join(map(repr, SIMULATION_METHODS))}")
    moments, N = _moments_and_n(body)
    n = moments.size
    convention = _convention_of(body)
    try:
        w0 = np.asarray(omega0, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"omega0 must be a numeric array of shape batch + ({n},), got {omega0!r}") from None
    if w0.ndim == 0 or w0.shape[-1] != n:
        raise ValueError(
            f"omega0 must have shape batch + ({n},) (n_planes of so({N})), got shape {w0.shape}"
        )
    if not np.all(np.isfinite(w0)):
        raise ValueError("omega0 must be finite (found NaN or inf)")
    batch = w0.shape[:-1]
    t = _check_time_grid(t)
    rtol = _check_positive("rtol", rtol)
    dt = _check_positive("dt", dt)
    if compensated is not None and not isinstance(compensated, (bool, np.bool_)):
        raise TypeError(f"compensated must be True, False or None (automatic), got {compensated!r}")

    # torque
    tq = None
    if torque is not None:
        if callable(torque):
            tq = torque
        else:
            try:
                tq = np.asarray(torque, dtype=float)
            except (TypeError, ValueError):
                raise TypeError(f"torque must be a callable torque(t, omega) or numeric components, got {torque!r}") from None
            if tq.ndim == 0 or tq.shape[-1] != n:
                raise ValueError(f"constant torque must have shape ({n},) or batch + ({n},), got {tq.shape}")
            if not np.all(np.isfinite(tq)):
                raise ValueError("torque must be finite (found NaN or inf)")
            tq = _broadcast_batch("torque", tq, 1, batch)

    # attitude
    with_att = attitude is not False and attitude is not None
    T0 = None
    if with_att:
        if attitude is True:
            T0 = np.broadcast_to(np.eye(N), batch + (N, N))
        else:
            try:
                T0 = np.asarray(attitude, dtype=float)
            except (TypeError, ValueError):
                raise TypeError(f"attitude must be a bool or an array of N x N matrices, got {attitude!r}") from None
            if T0.ndim < 2 or T0.shape[-2:] != (N, N):
                raise ValueError(f"initial attitude must have shape ({N}, {N}) or batch + ({N}, {N}), got {T0.shape}")
            dev = np.abs(np.swapaxes(T0, -1, -2) @ T0 - np.eye(N)).max() if T0.size else 0.0
            if not np.isfinite(dev) or dev > 1e-8:
                raise ValueError(f"initial attitude must be orthogonal (max|T^T T - 1| = {dev:.3g})")
            T0 = _broadcast_batch("attitude", T0, 2, batch)

    # method choice
    if method == "auto":
        if callable(tq):
            method = "DOP853"
        elif rtol is None and dt is not None:
            method = "splitting4"
        else:
            r = _DEFAULT_RTOL if rtol is None else rtol
            method = ("splitting2" if r >= 1e-2 else "splitting4" if r >= 1e-4
                      else "splitting6" if r >= 1e-7 else "splitting8")
    if method in _SCIPY_METHODS:
        if dt is not None:
            raise ValueError(f"dt fixes the step of the splitting methods; scipy method {method!r} takes rtol only")
        if compensated is not None:
            raise ValueError(f"compensated applies to the splitting methods only, not to scipy method {method!r}")
        rtol_used = _DEFAULT_RTOL if rtol is None else rtol
        rtol_used = max(rtol_used, 100 * np.finfo(float).eps)  # solve_ivp's floor (it warns below it)
    else:
        if dt is not None and rtol is not None:
            raise ValueError(
                f"give either dt (fixed step) or rtol (step chosen from the accuracy) for {method!r}, not both "
                f"(got dt={dt!r}, rtol={rtol!r})"
            )
        if method == "moser-veselov":
            if tq is not None and (callable(tq) or np.any(tq)):
                raise ValueError("method 'moser-veselov' integrates the free body only; for a torque use a "
                                 "splitting method (constant torque) or a scipy method")
            if compensated is not None:
                raise ValueError("compensated applies to the splitting methods only, not to 'moser-veselov'")
            J = moser_veselov.mass_tensor_of(body, moments)
        if callable(tq):
            raise ValueError(
                f"a callable torque breaks the splitting structure; use a scipy method "
                f"({', '.join(_SCIPY_METHODS)}) or method='auto' (DOP853), or give constant components"
            )
        rtol_used = _DEFAULT_RTOL if (rtol is None and dt is None) else rtol

    B = int(np.prod(batch)) if batch else 1
    w0f = w0.reshape(B, n)
    S = _sign_diag(body, N, convention)
    # attitude is integrated in the plain convention: T_conv = S T_plain S (S = S^-1)
    T0_std = S[:, None] * T0.reshape(B, N, N) * S[None, :] if with_att else None
    stats: dict[str, Any] = {"method": method, "rtol": rtol_used}

    if method in _SCIPY_METHODS:
        tqf = tq if (tq is None or callable(tq)) else tq.reshape(B, n)
        omega, att, nfev = _run_scipy(body, method, moments, N, w0f, t, rtol_used, tqf, T0_std, with_att)
        stats.update(order=None, steps=None, nfev=int(nfev), dt=None)
    elif method == "moser-veselov":
        L0 = w0f * moments
        if dt is None:
            dt = _moser_veselov_step(L0, moments, J, float(t[-1] - t[0]), rtol_used)
        nsub = _nsub_for(t, dt)
        Lout, att = moser_veselov.run(L0, J, moments, t, nsub, T0_std, with_att)
        omega = Lout / moments
        stats.update(order=2, steps=int(nsub.sum()), nfev=None,
                     dt=float(np.max(np.diff(t) / nsub)) if t.size > 1 else None)
    else:
        order = _SPLITTING_ORDER[method]
        kick = bool(tq is not None and np.any(tq))
        L0 = w0f * moments
        # one shift per member; none with a torque (it moves L away from the state the weights
        # describe, and the space-frame momentum that un-shifts the attitude)
        shift = np.zeros(B) if kick else casimir_shift(moments, L0)
        rates_b = 1.0 / moments - shift[:, None]
        # a plane drops out when its rate vanishes for every member (for the others its flow is exact identity)
        seq = tuple(int(a) for a in np.flatnonzero(np.any(rates_b != 0.0, axis=0)))
        word = _splitting_word(order, seq, kick=kick)
        tables = _rotation_tables(N)
        torque_b = np.zeros((B, n)) if not kick else np.ascontiguousarray(tq.reshape(B, n))
        tight = rtol_used is not None and rtol_used < _COMPENSATE_BELOW_RTOL
        if dt is None:
            T_total = float(t[-1] - t[0])
            if T_total > 0 and word[0].size:
                comp = tight if compensated is None else compensated
                T0_probe = np.broadcast_to(np.eye(N), (B, N, N))

                def probe(sel, tg, ns):
                    return _run_split(L0[sel], rates_b[sel], word, tables, tg, ns, torque_b[sel], T0_probe[sel],
                                      False, comp)[0]

                dt = _choose_step(L0, np.broadcast_to(moments, (B, n)), order, T_total, rtol_used, torque_b, N,
                                  probe, word[0].size)
            else:
                dt = max(T_total, 1.0)  # nothing to integrate (equal moments, no torque): L is constant
        nsub = _nsub_for(t, dt)
        if compensated is None:
            compensated = tight or int(nsub.sum()) * word[0].size > _COMPENSATE_ABOVE
        T0_run = T0_std if with_att else np.zeros((1, N, N))
        outL, outT = _run_split(L0, rates_b, word, tables, t, nsub, torque_b, T0_run, with_att, compensated)
        omega, Lout = outL / moments, outL
        att = outT
        if with_att and np.any(shift != 0.0):
            att = _unshift_attitude(att, L0, T0_std, t, shift)
        stats.update(order=order, steps=int(nsub.sum()), nfev=None,
                     dt=float(np.max(np.diff(t) / nsub)) if t.size > 1 else None,
                     flows_per_step=int(word[0].size),
                     casimir_shift=float(shift[0]) if not batch else shift.reshape(batch),
                     compensated=compensated)
    omega = omega.reshape(batch + (t.size, n))
    L = Lout.reshape(omega.shape) if method not in _SCIPY_METHODS else omega * moments
    if att is not None:
        att = (S[:, None] * att * S[None, :]).reshape(batch + (t.size, N, N))
    stats["wall_time"] = time.perf_counter() - wall
    return Trajectory(t, omega, L, att, body, moments, stats)
