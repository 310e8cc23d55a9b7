r"""Lie-Poisson splittings of order 2, 4, 6, 8, 10 (``method="splitting2"`` ... ``"splitting10"``).

The Hamiltonian, shifted by a multiple of the Casimir :math:`C_2 = \tfrac12\sum_a L_a^2`
(same motion of ``L``, see :func:`casimir_shift`),
:math:`H - c\,C_2 = \sum_a \rho_a L_a^2/2` with :math:`\rho_a = 1/I_a - c`,
is split into one term per plane; the flow of :math:`\rho_a L_a^2/2` keeps
:math:`L_a` fixed and rotates :math:`L` (and ``T``) exactly by the angle
:math:`h \rho_a L_a` in plane ``a`` (compiled numba kernels).
Planes with :math:`\rho_a = 0` (those whose moment equals ``1/c``) drop out;
the attitude is corrected for the shift exactly; with a torque there is no shift.
The basic method :math:`S_2(h)` is Strang's symmetric product over the remaining
planes in paper order followed by the reverse order (order 2). Orders 4, 6, 8, 10 are
symmetric compositions :math:`S_2(\gamma_s h)\cdots S_2(\gamma_1 h)`
(:func:`splitting_coefficients`):

* order 4: Yoshida's / Suzuki's triple jump (Yoshida, Phys. Lett. A 150, 262 (1990));
* order 6: Kahan & Li's 9-stage set ``s9odr6a``;
* order 8: Kahan & Li's 17-stage set ``s17odr8a`` (W. Kahan and R.-C. Li,
  Math. Comp. 66, 1089 (1997); coefficients as tabulated in Hairer, Lubich,
  Wanner, *Geometric Numerical Integration*, 2nd ed., Sec. V.3.2, p. 157);
* order 10: Sofroniou & Spaletta's 35-stage set (M. Sofroniou and G. Spaletta,
  Optim. Methods Softw. 20, 597 (2005); tabulated in the same section of Hairer,
  Lubich & Wanner, p. 158, as "a significantly improved method for s = 35"). Twice
  the flows of a step of order 8, but on the 5D bodies of the benchmark it reaches a
  whole-run error of 1e-10 with a third of the steps (``benchmarks/step_control.py``).

Every elementary flow is an exact coadjoint rotation, so the Casimirs
(coefficients of the characteristic polynomial of ``L``, eq. 38) are kept
to round-off, the maps are Poisson (symplectic on each coadjoint orbit),
symmetric and time-reversible, and the energy error stays bounded (no
drift) over long runs. ``T`` stays orthogonal to round-off. Fixed steps
(``dt``, or chosen once from ``rtol`` by :mod:`.step_control`).
A *constant* body torque is supported as an exact kick
:math:`L \mapsto L + \tfrac{\gamma h}{2}\tau` on both sides of each
:math:`S_2(\gamma h)` (still symmetric, so the composed orders hold; the
Casimirs are then of course not conserved). Callable torques need a scipy method.

Performance notes
-----------------
The kernels are compiled by numba on first use and cached on disk: a cold first
call costs about 1.3 s (one body), 2.8 s (ensemble kernel) and 2.5 s (ensemble
with attitude) on the reference machine, a cached one about 0.1 s. One body (or
fewer than 32) runs a serial kernel, in plain storage without attitude or torque the one
unrolled for its dimension ``N <= 5`` (:mod:`._unrolled`: ``L`` in registers, whole runs
1.1-1.25x faster, the same numbers; compiled once per ``N`` into a cache folder, 1.4-3 s cold);
ensembles without attitude run a chunked
kernel with the bodies innermost (vectorised, threads over chunks); ensembles
with attitude run one thread per body. With the option ``compensated`` (automatic
for runs of more than 1e6 elementary flows per trajectory or ``rtol < 1e-11``) the
rotation increments are added with error-free TwoSum (compensated storage of
``L``), so round-off does not random-walk the Casimirs: their relative drift stays
~1e-15 after 1e6 steps, and the trajectory's round-off floor stays ~1e-15.
Otherwise plain arithmetic (~1.6x faster per flow): the Casimirs' round-off
random-walks as ~0.1-0.4 eps sqrt(flows) (< 1e-13), the trajectory's floor is
~1e-13 .. 1e-12, like scipy's DOP853. Long runs are cut into chunks of about
``options["chunk_seconds"]`` (Ctrl-C between chunks); each chunk continues from the exact
(compensated) state of the previous one, so a chunked run gives the numbers of one call. Measured work-precision
and throughput: ``benchmarks/work_precision_classical.py``.
"""
from __future__ import annotations

from functools import lru_cache
from typing import Any

import numpy as np

from hyperrotor import _pricing, _validate
from hyperrotor.conventions import to_matrix

from . import _kernels, _unrolled
from ._kernels import rotation_tables
from .base import Problem, step_lengths
from .driver import FixedStepSolver

__all__ = ["Splitting", "Splitting2", "Splitting4", "Splitting6", "Splitting8", "Splitting10", "splitting_coefficients",
           "casimir_shift"]

_ENSEMBLE_CHUNK = 128  # bodies per chunk of the ensemble kernel (working set fits in L1/L2)
#: ``compensated=None``: runs of more elementary flows than this (per trajectory) keep L in
#: compensated storage (plain round-off of the Casimirs random-walks as ~0.1-0.4 eps sqrt(flows)) ...
COMPENSATE_ABOVE = 1_000_000
#: ... and so do runs asked for an rtol below this (plain round-off of omega reaches ~1e-13..1e-12)
COMPENSATE_BELOW_RTOL = 1e-11

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
_SOFRONIOU_SPALETTA_10 = (
    0.07879572252168641926390768,
    0.31309610341510852776481247,
    0.02791838323507806610952027,
    -0.22959284159390709415121340,
    0.13096206107716486317465686,
    -0.26973340565451071434460973,
    0.07497334315589143566613711,
    0.11199342399981020488957508,
    0.36613344954622675119314812,
    -0.39910563013603589787862981,
    0.10308739852747107731580277,
    0.41143087395589023782070412,
    -0.00486636058313526176219566,
    -0.39203335370863990644808194,
    0.05194250296244964703718290,
    0.05066509075992449633587434,
    0.04967437063972987905456880,
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
    10     35     Sofroniou & Spaletta (Optim. Methods Softw. 20, 597 (2005))
    ====== ====== ==========================================================
    """
    if order == 2:
        return np.array([1.0])
    if order == 4:
        g = 1.0 / (2.0 - 2.0 ** (1.0 / 3.0))
        return np.array([g, 1.0 - 2.0 * g, g])
    if order in (6, 8, 10):
        half = np.array({6: _KAHAN_LI_6, 8: _KAHAN_LI_8, 10: _SOFRONIOU_SPALETTA_10}[order])
        return np.concatenate([half, [1.0 - 2.0 * half.sum()], half[::-1]])
    raise ValueError(f"splitting order must be one of 2, 4, 6, 8, 10, got {order!r}")


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

    :func:`hyperrotor.simulate` takes one ``c`` per ensemble member (a member's result does not
    depend on the others) and none with a torque (the weights would be stale). The
    attitude feels the shift: the flow of :math:`c\,C_2` turns ``T`` at the rate
    :math:`c\,L`; :func:`hyperrotor.simulate` puts it back exactly.

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
    moments = _validate.finite_array("moments", moments)  # (complex, ragged, text: refused, named)
    moments = _validate.moments(moments, name="moments")
    n = moments.size
    _pricing.check("casimir_shift", n=n)
    if L is None:
        Lb = np.zeros((1, n))
    else:
        Lb = _validate.finite_array("L", L, ndim=(1, 2))
        if Lb.shape[-1] != n:
            raise ValueError(f"L must have shape ({n},) or (B, {n}) for these {n} moments, got {Lb.shape}")
    c = shift_rule(moments, np.atleast_2d(Lb))
    return float(c[0]) if L is None or Lb.ndim == 1 else c


def shift_rule(moments: np.ndarray, L2: np.ndarray) -> np.ndarray:
    """:func:`casimir_shift` for checked inputs: ``moments (n,)``, ``L2 (B, n)``; one ``c`` per row."""
    values, counts, dist = _shift_candidates(moments.tobytes())
    if values.size == 1:  # equal moments: one candidate
        return np.full(L2.shape[0], values[0])
    sq = L2 * L2
    norm = np.sqrt(np.sum(sq, axis=1, keepdims=True))
    E2 = np.sum(sq / moments, axis=1, keepdims=True)
    bound = np.minimum(norm, np.sqrt(E2 * moments))
    if norm.all():
        weights = bound / norm  # (B, n)
    else:
        weights = np.where(norm > 0, bound / np.where(norm > 0, norm, 1.0), 1.0)
    if dist is not None:
        cost = np.ascontiguousarray((weights @ dist).T)  # (V, B): reductions over the few candidates run along B
    else:  # a large body: the (n, V) table a block of candidates at a time (Ctrl-C between blocks)
        rates = 1.0 / moments
        cost = np.empty((values.size, L2.shape[0]))
        step = max(1, _SHIFT_TABLE_ENTRIES // rates.size)
        for s in range(0, values.size, step):
            cost[s:s + step] = (weights @ np.abs(rates[:, None] - values[None, s:s + step])).T
    cost /= np.maximum(cost.max(axis=0), 1e-300)
    cost *= 1e12  # equal to 12 digits: a tie (np.round(cost, 12) without its final division by 1e12)
    np.rint(cost, out=cost)
    score = np.where(cost == cost.min(axis=0), counts[:, None], -1)
    return values[np.argmax(score, axis=0)]  # first maximum: most planes, then the smaller value


#: entries of the ``|1/I_a - value|`` table of :func:`shift_rule` kept (cached) or built at once (8 MB): a body of
#: more planes and candidates builds it in blocks of candidates (at N = 200, 19 900 planes of a box, the whole
#: table was 3.2 GB and 11 s)
_SHIFT_TABLE_ENTRIES = 1 << 20


@lru_cache(maxsize=64)
def _shift_candidates(moments_bytes: bytes) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Per body: the distinct rates ``1/I_a`` (the candidates for ``c``), how many planes share
    each, and ``|1/I_a - value|`` (n, V) up to :data:`_SHIFT_TABLE_ENTRIES` entries (else ``None``: built by
    blocks); cached (read-only)."""
    rates = 1.0 / np.frombuffer(moments_bytes, dtype=np.float64)
    values, counts = np.unique(rates, return_counts=True)
    dist = np.abs(rates[:, None] - values[None, :]) if rates.size * values.size <= _SHIFT_TABLE_ENTRIES else None
    for arr in (values, counts, dist):
        if arr is not None:
            arr.setflags(write=False)
    return values, counts, dist


@lru_cache(maxsize=None)
def splitting_word(order: int, seq: tuple[int, ...], kick: bool = False) -> tuple[np.ndarray, np.ndarray]:
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


def unshift_attitude(att: np.ndarray, L0: np.ndarray, T0: np.ndarray, t: np.ndarray, c: np.ndarray) -> np.ndarray:
    r"""Attitude of :math:`H` from the attitude ``att`` (B, K, N, N) of :math:`H - c\,C_2` (plain convention).

    The flows of :math:`H - cC_2` and :math:`cC_2` commute; the latter keeps ``L`` and
    turns the attitude, :math:`\dot T = c\,L\,T`. With the conserved space-frame momentum
    :math:`\Lambda = T_0^{\mathsf T} L_0 T_0` (``L = T \Lambda T^T``) this gives
    :math:`T(t) = T'(t)\,\exp\bigl(c\,(t - t_0)\,\Lambda\bigr)`, evaluated exactly from one
    eigen-decomposition of the Hermitian :math:`i\Lambda` per body (orthogonal to round-off);
    ``c`` has one entry per body.
    """
    Lam = np.swapaxes(T0, -1, -2) @ to_matrix(L0, convention="standard") @ T0  # (B, N, N)
    lam, U = np.linalg.eigh(1j * Lam)  # Lam = U diag(-i lam) U^H
    phase = np.exp(-1j * c[:, None, None] * (t - t[0])[None, :, None] * lam[:, None, :])  # (B, K, N)
    E = np.einsum("brm,bkm,bsm->bkrs", U, phase, U.conj()).real
    return att @ E


@lru_cache(maxsize=None)
def splitting_slots(N: int, order: int, seq: tuple[int, ...], kick: bool = False) -> Any:
    """:func:`splitting_word` laid onto the sweeps of the unrolled kernels (:func:`~._unrolled.slot_table`)."""
    return _unrolled.slot_table(N, *splitting_word(order, seq, kick))


def _start(L0: np.ndarray, carry: Any) -> tuple[np.ndarray, np.ndarray]:
    """A kernel's start ``(L0, carry)``: a new run from ``L0`` (zero low parts), or the exact state
    ``(high, low)`` a previous call ended with (a copy: the kernels write their last state into it)."""
    if carry is None:
        return np.ascontiguousarray(L0), np.zeros((L0.shape[0], 2, L0.shape[1]))
    return np.ascontiguousarray(carry[:, 0]), carry.copy()


def _unrolled_kernel(slots, N: int, B: int, with_att: bool, compensated: bool, pair: bool = False):
    """The unrolled kernel :func:`run_kernel` runs for ``B`` rows (``pair``: the one
    :meth:`Splitting.advance_pair` runs; :func:`~._unrolled.kernel`), or ``None``."""
    if with_att or slots is None or B >= _kernels.PARALLEL_MIN_BODIES:
        return None
    return _unrolled.kernel(N, compensated, pair)


def run_kernel(L0, rates_b, word, tables, hstep, nsub, torque_b, T0, with_att, compensated, carry=None,
               slots=None):
    """Dispatch to a kernel: one body or a few -> serial (unrolled for their ``N`` when ``slots``, the
    word's :func:`~._unrolled.slot_table`, is given and there is no attitude); an ensemble without attitude ->
    bodies-innermost chunks over threads; an ensemble with attitude -> threads over bodies.
    ``nsub[k]`` steps of length ``hstep[k]`` per output interval; ``compensated``: TwoSum
    storage of ``L`` (see the performance notes). ``carry (B, 2, n)``: the exact state
    ``(high, low)`` a previous call ended with (then ``L0`` is ignored; default: start from
    ``L0``). Returns ``(L (B, K, n), T or None, carry of the last state)``; every kernel gives the
    same numbers to the last bit."""
    B, n = L0.shape
    N = T0.shape[-1]
    K = hstep.size + 1
    outL = np.empty((B, K, n))
    L0, carry = _start(L0, carry)
    rates_b = np.ascontiguousarray(rates_b)
    torque_b = np.ascontiguousarray(torque_b)
    hstep = np.ascontiguousarray(hstep, dtype=np.float64)
    unrolled = _unrolled_kernel(slots, N, B, with_att, compensated)
    if unrolled is not None:
        unrolled(L0, carry, rates_b, slots[0], slots[1], hstep, nsub, outL)
        return outL, None, carry
    if B >= _kernels.PARALLEL_MIN_BODIES and not with_att:
        chunk = max(1, min(_ENSEMBLE_CHUNK, -(-B // 8)))
        _kernels.split_run_ensemble(L0, rates_b, word[0], word[1], *tables[:3], hstep, nsub, torque_b, chunk,
                                    compensated, outL, carry)
        return outL, None, carry
    outT = np.empty((B, K, N, N)) if with_att else np.empty((B, 1, N, N))
    kernel = _kernels.split_run if B >= _kernels.PARALLEL_MIN_BODIES else _kernels.split_run_serial
    kernel(L0, rates_b, word[0], word[1], *tables, hstep, nsub, torque_b, np.ascontiguousarray(T0),
           bool(with_att), compensated, outL, outT, carry)
    return outL, (outT if with_att else None), carry


class Splitting(FixedStepSolver):
    """Lie-Poisson splitting of order 2, 4, 6, 8 or 10 (see the module docstring).

    Symplectic (Poisson) and time-reversible; keeps the Casimirs and the attitude's
    orthogonality to round-off, the energy error bounded (no drift). Fixed step.
    Integrates constant torques (exact kicks); no callable torques.

    Options
    -------
    compensated : bool or None
        keep ``L`` in compensated (TwoSum) storage (~1.6x slower per step, round-off
        ~1e-15 instead of ~1e-13); ``None``: automatic (runs of more than 1e6 elementary
        flows per trajectory or ``rtol < 1e-11``).
    """

    order = 2
    preserves = frozenset({"casimirs", "orthogonality", "symplectic", "reversible"})
    supports_torque = "constant"
    tangent = True
    option_docs = {"compensated": (None, "TwoSum storage of L: True, False or None (automatic)")}

    def _check_options(self) -> None:
        c = self.options["compensated"]
        if c is not None and not isinstance(c, (bool, np.bool_)):
            raise TypeError(f"compensated must be True, False or None (automatic), got {_validate.fmt(c)}")

    def prepare(self, problem: Problem) -> None:
        B, n = problem.L0.shape
        kick = problem.kick
        # one shift per member; none with a torque (it moves L away from the state the weights
        # describe, and the space-frame momentum that un-shifts the attitude)
        shift = np.zeros(B) if (kick or B == 0) else shift_rule(problem.moments, problem.L0)
        rates_b = 1.0 / problem.moments - shift[:, None]
        # a plane drops out when its rate vanishes for every member (for the others its flow is exact identity)
        seq = tuple(int(a) for a in np.flatnonzero(np.any(rates_b != 0.0, axis=0)))
        word = splitting_word(self.order, seq, kick=kick)
        self._state = dict(
            shift=shift, rates=rates_b, word=word, slots=splitting_slots(problem.N, self.order, seq, kick),
            tables=rotation_tables(problem.N),
            torque=np.zeros((B, n)) if not kick else np.ascontiguousarray(problem.torque),
            compensated=self.options["compensated"],
        )

    def set_accuracy(self, problem: Problem, rtol: float | None, steps: int, *, roundoff_amplified: bool = False
                     ) -> None:
        """Fix the automatic ``compensated`` choice once the step is known (``roundoff_amplified``: the
        step control's check saw the orbit amplify round-off towards ``rtol``, e.g. a chaotic orbit)."""
        if self.options["compensated"] is None:
            tight = (rtol is not None and rtol < COMPENSATE_BELOW_RTOL) or roundoff_amplified
            self._state["compensated"] = bool(tight or steps * self.flows_per_step(problem) > COMPENSATE_ABOVE)

    def can_compensate(self) -> bool:
        """Whether the step control may switch this run to compensated storage (automatic choice, not yet on)."""
        return self.options["compensated"] is None and not self._state["compensated"]

    def compensates(self) -> bool:
        return bool(self._state["compensated"])

    def flows_per_step(self, problem: Problem) -> int:
        return max(1, int(self._state["word"][0].size))

    def kernel_variant(self):
        return type(self), bool(self._state["compensated"])  # compensated storage: ~1.6x per flow

    def _rows(self, members):
        """Rates, torques and shifts of ``members`` (all when ``None``; the last selection is cached:
        the step control probes the same members many times)."""
        st = self._state
        if members is None:
            return st["rates"], st["torque"], st["shift"]
        last = st.get("rows")
        if last is None or last[0] is not members:
            last = st["rows"] = (members, st["rates"][members], st["torque"][members], st["shift"][members])
        return last[1:]

    def advance(self, problem, L, T, t, nsub, members=None, h=None, carry=None):
        st = self._state
        rates, torque, shift = self._rows(members)
        comp = st["compensated"]
        comp = False if comp is None else comp
        with_att = T is not None
        T_run = np.ascontiguousarray(T) if with_att else np.zeros((1, problem.N, problem.N))
        outL, outT, self.last_carry = run_kernel(L, rates, st["word"], st["tables"],
                                                 step_lengths(t, nsub) if h is None else h, nsub, torque, T_run,
                                                 with_att, comp, carry, slots=st["slots"])
        if with_att and np.any(shift != 0.0):
            outT = unshift_attitude(outT, L, T, t, shift)
        return outL, outT

    def advance_pair(self, problem, La, Lb, t, na, nb, members=None, carries=(None, None)):
        """Both runs in one compiled call for up to ``PARALLEL_MIN_BODIES`` rows (the step control's members:
        the unrolled kernel's ``run_pair`` where it applies, else :func:`~._kernels.split_run_pair`); more rows:
        two :meth:`advance` calls (the same numbers)."""
        st = self._state
        comp = bool(st["compensated"])
        if La.shape[0] >= _kernels.PARALLEL_MIN_BODIES:
            return super().advance_pair(problem, La, Lb, t, na, nb, members, carries)  # (two run_kernel calls)
        rates, torque, _ = self._rows(members)
        (L0a, ca), (L0b, cb) = _start(La, carries[0]), _start(Lb, carries[1])
        outa = np.empty((La.shape[0], t.size, La.shape[1]))
        outb = np.empty_like(outa)
        rates = np.ascontiguousarray(rates)
        ha, hb = step_lengths(t, na), step_lengths(t, nb)
        unrolled = _unrolled_kernel(st["slots"], problem.N, La.shape[0], False, comp, pair=True)
        if unrolled is not None:
            slot_coef, slot_plane = st["slots"]
            unrolled(L0a, ca, L0b, cb, rates, slot_coef, slot_plane, ha, na, hb, nb, outa, outb)
        else:
            word, tables = st["word"], st["tables"]
            _kernels.split_run_pair(L0a, L0b, rates, word[0], word[1], *tables, ha, na, hb, nb,
                                    np.ascontiguousarray(torque), comp, outa, outb, ca, cb)
        self.last_carries = (ca, cb)
        return outa, outb

    def stats(self, problem: Problem) -> dict:
        st = self._state
        shift = st["shift"]
        return dict(flows_per_step=int(st["word"][0].size),
                    casimir_shift=float(shift[0]) if not problem.batch and shift.size else shift.reshape(problem.batch),
                    compensated=bool(st["compensated"]))


class Splitting2(Splitting):
    """Strang splitting over the planes, order 2 (1 stage)."""

    name = "splitting2"
    order = 2
    auto_rtol = None  # (targets looser than 1e-3 run to 1e-3, step_control.LOOSEST_RTOL: order 4 was as fast or up
    # to 3.5x faster than order 2 there on random generic 5D bodies, rtol 1e-2, T = 20)


class Splitting4(Splitting):
    """Yoshida / Suzuki triple jump of Strang steps, order 4 (3 stages)."""

    name = "splitting4"
    order = 4
    auto_rtol = 1e-4


class Splitting6(Splitting):
    """Kahan & Li ``s9odr6a`` composition of Strang steps, order 6 (9 stages)."""

    name = "splitting6"
    order = 6
    auto_rtol = None  # order 8 costs no more from rtol 1e-4 down (benchmarks/README.md, step_control.py)


class Splitting8(Splitting):
    """Kahan & Li ``s17odr8a`` composition of Strang steps, order 8 (17 stages)."""

    name = "splitting8"
    order = 8
    auto_rtol = 1e-10


class Splitting10(Splitting):
    """Sofroniou & Spaletta's 35-stage composition of Strang steps, order 10."""

    name = "splitting10"
    order = 10
    auto_rtol = 0.0
