r"""Numba kernels of the Lie-Poisson splitting integrators (private).

The kernels are plain functions on ndarrays that write into explicit output
arrays; :func:`hyperrotor._jit.jit` compiles them (cached on disk) unless
``HYPERROTOR_DISABLE_JIT=1``. The pure-Python originals stay reachable as
``kernel.py_func`` when compiled; the tests run both paths.

Data layout (``n = N(N-1)/2`` planes, ``B`` bodies, ``K`` output times)
---------------------------------------------------------------------
``L0 (B, n)``
    angular-momentum components (plane order of :mod:`hyperrotor.conventions`).
``rates (B, n)``
    rotation rate per unit momentum of each plane term, :math:`1/I_a - c` for the
    split Hamiltonian :math:`H - c\,C_2` (``c`` the Casimir shift of
    :mod:`hyperrotor.classical.solvers.splitting`; rows may repeat one body).
``seq_plane (m,) int64``, ``seq_coef (m,) float64``
    one step of the composed method as a word of elementary flows: entry ``r``
    is the exact flow of :math:`L_a^2/(2I_a)` (``a = seq_plane[r] >= 0``) over
    ``seq_coef[r] * h``, or a constant body-torque kick :math:`L \mapsto L + c h \tau`
    when ``seq_plane[r] == -1``.
``pair_p, pair_q (n, N-2) int64``, ``pair_s (n, N-2) float64``
    for plane ``a = (i, j)`` and each ``k != i, j``: the component indices of the
    matrix entries :math:`L_{ik} = \sigma_p L_{p}`, :math:`L_{jk} = \sigma_q L_{q}` and
    the product ``pair_s = sigma_p * sigma_q`` (see :func:`rotation_tables`).
``plane_i, plane_j (n,) int64``
    0-based rows ``i - 1``, ``j - 1`` of plane ``a`` (attitude update).

Elementary flow
---------------
For :math:`H_a = \rho_a L_a^2/2` (:math:`\rho_a` = ``rates[a]``, :math:`1/I_a` without
shift) the component equations
:math:`\dot L_c = \sum_{b,d} C_{bd}^{\;c}\,\omega_b L_d` (plain matrices:
:math:`\dot L = [\Omega, L]`) reduce to :math:`\dot L = \theta'\,[E_a, L]` with the
constant rate :math:`\theta' = \rho_a L_a` (``L_a`` is conserved because ``C`` is
totally antisymmetric). The exact solution is
:math:`L(h) = R L R^{\mathsf T}`, :math:`R = \exp(\phi E_a)`, :math:`\phi = h \rho_a L_a`;
on rows ``i, j`` :math:`R` is :math:`\begin{pmatrix} c & s\\ -s & c\end{pmatrix}`,
so for every ``k != i, j``

.. math:: L_{ik} \mapsto c L_{ik} + s L_{jk}, \qquad L_{jk} \mapsto -s L_{ik} + c L_{jk},

and every other entry is unchanged. The attitude (plain-matrix convention,
:math:`\dot T = \Omega T`) follows the same flow: :math:`T \mapsto R T`, i.e. rows
``i`` and ``j`` of ``T`` rotate by the same ``(c, s)``.
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from hyperrotor._jit import jit, prange

__all__: list[str] = []  # private module


@lru_cache(maxsize=None)
def rotation_tables(N: int):
    """Index tables of the elementary plane rotations for so(N) (see module docstring); cached, read-only.

    Read-only for every caller: numba compiles a kernel once per argument type, writeability
    included, so one kind of table means one compiled kernel (a writeable copy compiled the
    ensemble kernel a second time, ~8 s).
    """
    plane_i, plane_j = (x.astype(np.int64) for x in np.triu_indices(N, 1))  # (0-based, in the paper's order)
    n = plane_i.size
    # component index and sign of every matrix entry (r, c) of L, r != c: the plane (min, max), + above the diagonal
    comp = np.zeros((N, N), dtype=np.int64)
    comp[plane_i, plane_j] = comp[plane_j, plane_i] = np.arange(n)
    sign = np.triu(np.ones((N, N)), 1) - np.tril(np.ones((N, N)), -1)
    # the other axes k of each plane, ascending: its N - 2 rotated pairs (L_ik, L_jk)
    axes = np.arange(N)
    others = np.broadcast_to(axes, (n, N))[(axes != plane_i[:, None]) & (axes != plane_j[:, None])].reshape(n, N - 2)
    pair_p = np.ascontiguousarray(comp[plane_i[:, None], others])
    pair_q = np.ascontiguousarray(comp[plane_j[:, None], others])
    pair_s = sign[plane_i[:, None], others] * sign[plane_j[:, None], others]
    tables = pair_p, pair_q, pair_s, plane_i, plane_j
    for arr in tables:
        arr.setflags(write=False)
    return tables


#: half-angles up to this use the polynomials of :func:`rotation_poly` (libm beyond: :func:`rotation`): the
#: largest ``x`` at which the first omitted Taylor term of :math:`\sin 2x / 2x` (the larger of the two),
#: :math:`(2x)^{14}/15!`, stays below :math:`2^{-56}` is 0.2292. The angles of accurate runs are far smaller
#: (a splitting8 run to 1e-10 turns by ~0.01-0.03 per flow); a shorter range (0.059, 4 terms) sent too many of the
#: lanes of loose ensembles to libm (benchmarks/README.md, sixteenth pass of step_control.py).
SMALL_HALF_ANGLE = 0.229
# Taylor coefficients of sin(2x) / 2x = 1 + sum_k _Ak z^k and (1 - cos 2x) / 2z = 1 + sum_k _Bk z^(k-1), z = x^2:
# _Ak = (-4)^k / (2k+1)!, _Bk = (-1)^(k+1) 4^k / (2 (2k)!)
_A1, _A2, _A3 = -4.0 / 6.0, 16.0 / 120.0, -64.0 / 5040.0
_A4, _A5, _A6 = 256.0 / 362880.0, -1024.0 / 39916800.0, 4096.0 / 6227020800.0
_B2, _B3, _B4 = -16.0 / 48.0, 64.0 / 1440.0, -256.0 / 80640.0
_B5, _B6, _B7 = 1024.0 / 7257600.0, -4096.0 / 958003200.0, 16384.0 / 174356582400.0


@jit(inline="always")
def rotation_poly(x):  # pragma: no cover - jitted
    r"""``(sin 2x, 1 - cos 2x)`` of a plane rotation from its half-angle ``x`` by Taylor polynomials in
    :math:`z = x^2` (Estrin's scheme), branch-free; accurate (to a few ulps) for ``|x| <=``
    :data:`SMALL_HALF_ANGLE`.

    :math:`\sin 2x` and :math:`1 - \cos 2x` come straight from their own series (not as :math:`2\sin x\cos x`,
    :math:`2\sin^2 x`: two products fewer on the chain from one flow's angle to the next), and :math:`1 - \cos 2x`
    is summed as it is (:math:`2z - \tfrac{2}{3} z^2 + \dots`), so it stays accurate for small angles and the pair
    rotates with :math:`c = 1 - v` never rounded. Inlined into the kernels (numba IR level), so the loops over
    bodies that call it stay vectorised; the bodies-innermost kernels call it for all lanes, then :func:`rotation`
    again for the lanes beyond :data:`SMALL_HALF_ANGLE` (:func:`redo_wide_lanes`). Every sine and cosine of the
    splittings comes from here or from libm.
    """
    z = x * x
    z2 = z * z
    z4 = z2 * z2
    ps = (_A1 + z * _A2) + z2 * (_A3 + z * _A4) + z4 * (_A5 + z * _A6)
    pv = (_B2 + z * _B3) + z2 * (_B4 + z * _B5) + z4 * (_B6 + z * _B7)
    xx = x + x
    zz = z + z
    return xx + (xx * z) * ps, zz + (zz * z) * pv


@jit(inline="always")
def rotation(x):  # pragma: no cover - jitted
    """``(sin 2x, 1 - cos 2x)`` from the half-angle ``x``: :func:`rotation_poly` up to
    :data:`SMALL_HALF_ANGLE`, libm's ``sin x``, ``cos x`` beyond (``2 sin x cos x``, ``2 sin^2 x``)."""
    if abs(x) <= SMALL_HALF_ANGLE:
        return rotation_poly(x)
    sh = math.sin(x)
    return 2.0 * sh * math.cos(x), 2.0 * sh * sh


@jit(inline="always")
def redo_wide_lanes(X, S, V):  # pragma: no cover - jitted
    """``S[j], V[j] = rotation(X[j])`` for the lanes whose half-angle is beyond :data:`SMALL_HALF_ANGLE` (libm)
    (the test of :func:`rotation`, so that every lane gets what a body's own run gets)."""
    for j in range(S.shape[0]):
        if abs(X[j]) > SMALL_HALF_ANGLE:
            S[j], V[j] = rotation(X[j])


@jit(inline="always")
def rotate_lanes(L, p, q, sg, S, V):  # pragma: no cover - jitted
    """Rotate the pair ``(L[p, j], L[q, j])`` of every lane ``j`` by ``S[j] * sg``, ``V[j]`` (plain arithmetic)."""
    for j in range(S.shape[0]):
        ss = S[j] * sg
        v = V[j]
        x = L[p, j]
        y = L[q, j]
        L[p, j] = x + (ss * y - v * x)
        L[q, j] = y - (ss * x + v * y)


@jit
def start_attitude(T0, b, with_attitude, outT):  # pragma: no cover - jitted
    """Working copy of body ``b``'s initial attitude, also stored as output 0 (if ``with_attitude``)."""
    N = T0.shape[1]
    T = np.empty((N, N))
    if with_attitude:
        for r in range(N):
            for c in range(N):
                T[r, c] = T0[b, r, c]
                outT[b, 0, r, c] = T[r, c]
    return T


@jit
def store_attitude(T, b, k, outT):  # pragma: no cover - jitted
    """``outT[b, k] = T``."""
    N = T.shape[0]
    for r in range(N):
        for c in range(N):
            outT[b, k, r, c] = T[r, c]


def _split_run(L0, rates, seq_plane, seq_coef, pair_p, pair_q, pair_s, plane_i, plane_j,
               hstep, nsub, torque, T0, with_attitude, compensated, outL, outT, carry):  # pragma: no cover - jitted
    """Integrate ``B`` bodies over ``K = hstep.size + 1`` output times with a composed splitting method.

    Interval ``k`` is covered by ``nsub[k]`` steps of length ``hstep[k]`` (the driver passes
    ``(t[k+1] - t[k]) / nsub[k]`` of the whole run's grid, so a run cut into chunks does the
    same arithmetic as one call). Writes
    ``outL[b, k, :]`` (angular momentum at ``t[k]``) and, if ``with_attitude``,
    ``outT[b, k]`` (plain-matrix attitude, starting from ``T0[b]``). With ``compensated``
    the increments of ``L`` are added with error-free TwoSum (``L = Lh + Ll``), else in
    plain arithmetic (~1.6x faster; see ``COMPENSATE_ABOVE`` in ``solvers/splitting.py``).
    ``carry (B, 2, n)`` continues a run exactly: on entry ``carry[b, 1]`` is the low part
    ``Ll`` of the start (``L0`` its high part; zeros for a new run), on exit
    ``carry[b] = (Lh, Ll)`` of the last state (outputs are the rounded sums ``Lh + Ll``).
    Compiled twice: :func:`split_run` (``prange`` over bodies, threads) and
    :func:`split_run_serial` (no thread launch: cheaper for a few bodies).
    """
    B = L0.shape[0]
    n = L0.shape[1]
    K = hstep.shape[0] + 1
    m = seq_plane.shape[0]
    npair = pair_p.shape[1]
    N = T0.shape[1]
    for b in prange(B):
        Lh = np.empty(n)  # compensated storage: L = Lh + Ll (Lh carries the value, Ll the rounding error)
        Ll = np.empty(n)
        fac = np.empty(m)
        for a in range(n):
            Lh[a] = L0[b, a]
            Ll[a] = carry[b, 1, a]
            outL[b, 0, a] = Lh[a] + Ll[a]
        T = start_attitude(T0, b, with_attitude, outT)
        for k in range(K - 1):
            ns = nsub[k]
            h = hstep[k]
            for r in range(m):
                a = seq_plane[r]
                fac[r] = seq_coef[r] * h if a < 0 else 0.5 * seq_coef[r] * h * rates[b, a]
            for _ in range(ns):
                for r in range(m):
                    a = seq_plane[r]
                    if a < 0:
                        ch = fac[r]
                        for e in range(n):
                            if not compensated:
                                Lh[e] += ch * torque[b, e]
                                continue
                            d = ch * torque[b, e] + Ll[e]
                            x = Lh[e]
                            snew = x + d
                            bb = snew - x
                            Ll[e] = (x - (snew - bb)) + (d - bb)
                            Lh[e] = snew
                        continue
                    half = fac[r] * (Lh[a] + Ll[a]) if compensated else fac[r] * Lh[a]
                    s, v = rotation(half)  # sin(phi), 1 - cos(phi)
                    for e in range(npair):
                        p = pair_p[a, e]
                        q = pair_q[a, e]
                        ss = s * pair_s[a, e]
                        x = Lh[p]
                        y = Lh[q]
                        if not compensated:
                            Lh[p] = x + (ss * y - v * x)
                            Lh[q] = y - (ss * x + v * y)
                            continue
                        # increments of the exact rotation, added with TwoSum (error-free)
                        d = (ss * y - v * x) + Ll[p]
                        snew = x + d
                        bb = snew - x
                        Ll[p] = (x - (snew - bb)) + (d - bb)
                        Lh[p] = snew
                        d = (-(ss * x) - v * y) + Ll[q]
                        snew = y + d
                        bb = snew - y
                        Ll[q] = (y - (snew - bb)) + (d - bb)
                        Lh[q] = snew
                    if with_attitude:
                        i = plane_i[a]
                        j = plane_j[a]
                        for e in range(N):
                            x = T[i, e]
                            y = T[j, e]
                            T[i, e] = x + (s * y - v * x)
                            T[j, e] = y - (s * x + v * y)
            for a in range(n):
                outL[b, k + 1, a] = Lh[a] + Ll[a]
            if with_attitude:
                store_attitude(T, b, k + 1, outT)
        for a in range(n):
            carry[b, 0, a] = Lh[a]
            carry[b, 1, a] = Ll[a]


def _split_run_ensemble(L0, rates, seq_plane, seq_coef, pair_p, pair_q, pair_s,
                        hstep, nsub, torque, chunk, compensated, outL, carry):  # pragma: no cover - jitted
    """Same integration as :func:`_split_run` without attitude, bodies innermost.

    Bodies are processed in chunks of ``chunk`` (threads over chunks); inside a chunk the
    loop over bodies is the innermost one, so the independent rotations of different
    bodies overlap in the CPU pipeline instead of waiting on one body's chain of flows.
    Same arithmetic per body as :func:`_split_run` (results agree to the last bit); same ``carry``.
    """
    B = L0.shape[0]
    n = L0.shape[1]
    K = hstep.shape[0] + 1
    m = seq_plane.shape[0]
    npair = pair_p.shape[1]
    nchunks = (B + chunk - 1) // chunk
    for ci in prange(nchunks):
        b0 = ci * chunk
        nb = min(B, b0 + chunk) - b0
        Lh = np.empty((n, nb))
        Ll = np.empty((n, nb))
        tq = np.empty((n, nb))
        fac = np.empty((m, nb))
        X = np.empty(nb)
        S = np.empty(nb)
        V = np.empty(nb)
        for a in range(n):
            for j in range(nb):
                Lh[a, j] = L0[b0 + j, a]
                Ll[a, j] = carry[b0 + j, 1, a]
                tq[a, j] = torque[b0 + j, a]
                outL[b0 + j, 0, a] = Lh[a, j] + Ll[a, j]
        for k in range(K - 1):
            ns = nsub[k]
            h = hstep[k]
            for r in range(m):
                a = seq_plane[r]
                for j in range(nb):
                    fac[r, j] = seq_coef[r] * h if a < 0 else 0.5 * seq_coef[r] * h * rates[b0 + j, a]
            for _ in range(ns):
                for r in range(m):
                    a = seq_plane[r]
                    if a < 0:
                        for e in range(n):
                            if not compensated:
                                for j in range(nb):
                                    Lh[e, j] += fac[r, j] * tq[e, j]
                                continue
                            for j in range(nb):
                                d = fac[r, j] * tq[e, j] + Ll[e, j]
                                x = Lh[e, j]
                                snew = x + d
                                bb = snew - x
                                Ll[e, j] = (x - (snew - bb)) + (d - bb)
                                Lh[e, j] = snew
                        continue
                    big = False
                    for j in range(nb):  # the rotations by polynomials, branch-free (vectorised)
                        x = fac[r, j] * (Lh[a, j] + Ll[a, j])
                        X[j] = x
                        S[j], V[j] = rotation_poly(x)
                        big |= abs(x) > SMALL_HALF_ANGLE
                    if big:  # some half-angle beyond the polynomials' range
                        redo_wide_lanes(X, S, V)
                    for e in range(npair):
                        p = pair_p[a, e]
                        q = pair_q[a, e]
                        sg = pair_s[a, e]
                        if not compensated:
                            rotate_lanes(Lh, p, q, sg, S, V)
                            continue
                        for j in range(nb):  # contiguous, branch-free: vectorised over bodies
                            ss = S[j] * sg
                            v = V[j]
                            x = Lh[p, j]
                            y = Lh[q, j]
                            d = (ss * y - v * x) + Ll[p, j]
                            snew = x + d
                            bb = snew - x
                            Ll[p, j] = (x - (snew - bb)) + (d - bb)
                            Lh[p, j] = snew
                            d = (-(ss * x) - v * y) + Ll[q, j]
                            snew = y + d
                            bb = snew - y
                            Ll[q, j] = (y - (snew - bb)) + (d - bb)
                            Lh[q, j] = snew
            for a in range(n):
                for j in range(nb):
                    outL[b0 + j, k + 1, a] = Lh[a, j] + Ll[a, j]
        for a in range(n):
            for j in range(nb):
                carry[b0 + j, 0, a] = Lh[a, j]
                carry[b0 + j, 1, a] = Ll[a, j]


#: ensembles at least this large use the threaded kernels (a thread launch costs ~ms on a busy machine, and on
#: an oversubscribed one a threaded call for one body can stall far longer)
PARALLEL_MIN_BODIES = 32

split_run_ensemble = jit(parallel=True)(_split_run_ensemble)
split_run = jit(parallel=True)(_split_run)
split_run_serial = jit(_split_run)


def _split_run_pair(L0a, L0b, rates, seq_plane, seq_coef, pair_p, pair_q, pair_s, plane_i, plane_j,
                    ha, na, hb, nb, torque, compensated, outa, outb, carrya, carryb):  # pragma: no cover - jitted
    """Two runs of the same bodies on one output grid in one call (no attitude): ``na[k]`` steps of
    ``ha[k]`` per interval from ``L0a`` into ``outa``/``carrya``, and ``nb[k]`` steps of ``hb[k]`` from
    ``L0b`` into ``outb``/``carryb`` (same arithmetic as two calls of :func:`split_run_serial`).
    The step control's probes (steps ``h`` and ``2h``) and its check's two companion runs are such
    pairs: one compiled call instead of two."""
    T0 = np.zeros((1, 1, 1))  # (no attitude: never read)
    outT = np.empty((L0a.shape[0], 1, 1, 1))
    # a run-time False: a literal False would compile split_run_serial a second time (for Literal[bool])
    with_attitude = T0.size == 0
    split_run_serial(L0a, rates, seq_plane, seq_coef, pair_p, pair_q, pair_s, plane_i, plane_j, ha, na, torque,
                     T0, with_attitude, compensated, outa, outT, carrya)
    split_run_serial(L0b, rates, seq_plane, seq_coef, pair_p, pair_q, pair_s, plane_i, plane_j, hb, nb, torque,
                     T0, with_attitude, compensated, outb, outT, carryb)


split_run_pair = jit(_split_run_pair)


@jit
def relative_difference(La, Lb, moments, Lmax, Wmax):  # pragma: no cover - jitted
    """Per row and sample (``La``, ``Lb``: rows, samples, n; the result: rows, samples): the largest over
    planes of ``max(|dL| / Lmax[row], |dL / moments| / Wmax[row])`` (NaN if any difference is NaN).

    The step control's measure of the distance of two runs (relative to the largest ``|L|`` and
    ``|omega|`` of each row): Richardson's estimates compare runs at different steps with it, row
    (ensemble member) by row: each member's differences follow its own orbit's growth.
    """
    rows, S, n = La.shape
    out = np.empty((rows, S))
    for b in range(rows):
        for s in range(S):
            out[b, s] = distance_at(La, Lb, b, s, moments, Lmax[b], Wmax[b])
    return out


@jit(inline="always")
def distance_at(La, Lb, b, s, moments, lm, wm):  # pragma: no cover - jitted
    """:func:`relative_difference` of row ``b``, sample ``s`` with the scales ``lm``, ``wm`` (inlined: a caller
    indexes its arrays instead of slicing them, and slices, another array layout, would compile the callee again)."""
    best = 0.0
    for a in range(La.shape[2]):
        d = abs(La[b, s, a] - Lb[b, s, a])
        x = max(d / lm, d / moments[a] / wm)
        if x != x:
            return math.nan
        if x > best:
            best = x
    return best


@jit(inline="always")
def scales_at(L, b, s, moments, lm, wm):  # pragma: no cover - jitted
    """``(max(lm, max|L[b, s]|), max(wm, max|L[b, s] / moments|))``: :func:`raise_scales` for one row and sample
    (inlined, as :func:`distance_at`)."""
    for a in range(L.shape[2]):
        x = abs(L[b, s, a])
        if x > lm:
            lm = x
        w = x / moments[a]
        if w > wm:
            wm = w
    return lm, wm


@jit
def raise_scales(L, moments, Lmax, Wmax):  # pragma: no cover - jitted
    """``Lmax[b] = max(Lmax[b], max|L[b]|)``, ``Wmax[b] = max(Wmax[b], max|L[b] / moments|)`` in place, for
    ``L (rows, samples, n)``: the running scales of :func:`relative_difference` (NaN is left to it)."""
    rows, S, n = L.shape
    for b in range(rows):
        lm = Lmax[b]
        wm = Wmax[b]
        for s in range(S):
            lm, wm = scales_at(L, b, s, moments, lm, wm)
        Lmax[b] = lm
        Wmax[b] = wm


@jit
def row_scales(L, moments):  # pragma: no cover - jitted
    """``(Lmax, Wmax)``: per row of ``L (rows, samples, n)`` the largest ``|L|`` and ``|L / moments|``, at
    least 1e-300 (fresh arrays, to be raised by :func:`raise_scales` as a run goes on)."""
    Lmax = np.full(L.shape[0], 1e-300)
    Wmax = np.full(L.shape[0], 1e-300)
    raise_scales(L, moments, Lmax, Wmax)
    return Lmax, Wmax

