r"""Numba kernels of the Lie-Poisson splitting integrators (private).

The kernels are plain functions on ndarrays that write into explicit output
arrays; :func:`hyperrotor._jit.jit` compiles them (cached on disk) unless
``HYPERROTOR_DISABLE_JIT=1``. The pure-Python originals stay reachable as
``kernel.py_func`` when compiled; the tests run both paths.

Data layout (``n = N(N-1)/2`` planes, ``B`` bodies, ``K`` output times)
---------------------------------------------------------------------
``L0 (B, n)``
    angular-momentum components (plane order of :mod:`hyperrotor.conventions`).
``moments (B, n)``
    plane moments :math:`I_a` per body (rows may repeat one body).
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
For :math:`H_a = L_a^2/(2 I_a)` the component equations
:math:`\dot L_c = \sum_{b,d} C_{bd}^{\;c}\,\omega_b L_d` (plain matrices:
:math:`\dot L = [\Omega, L]`) reduce to :math:`\dot L = \theta'\,[E_a, L]` with the
constant rate :math:`\theta' = L_a / I_a` (``L_a`` is conserved because ``C`` is
totally antisymmetric). The exact solution is
:math:`L(h) = R L R^{\mathsf T}`, :math:`R = \exp(\phi E_a)`, :math:`\phi = h L_a / I_a`;
on rows ``i, j`` :math:`R` is :math:`\begin{pmatrix} c & s\\ -s & c\end{pmatrix}`,
so for every ``k != i, j``

.. math:: L_{ik} \mapsto c L_{ik} + s L_{jk}, \qquad L_{jk} \mapsto -s L_{ik} + c L_{jk},

and every other entry is unchanged. The attitude (plain-matrix convention,
:math:`\dot T = \Omega T`) follows the same flow: :math:`T \mapsto R T`, i.e. rows
``i`` and ``j`` of ``T`` rotate by the same ``(c, s)``.
"""
from __future__ import annotations

import math

import numpy as np

from hyperrotor._jit import jit, prange

__all__: list[str] = []  # private module


def rotation_tables(N: int):
    """Index tables of the elementary plane rotations for so(N) (see module docstring)."""
    from hyperrotor.conventions import planes

    ps = planes(N)
    idx = {p: k for k, p in enumerate(ps)}
    n = len(ps)
    m = max(N - 2, 0)
    pair_p = np.zeros((n, m), dtype=np.int64)
    pair_q = np.zeros((n, m), dtype=np.int64)
    pair_s = np.zeros((n, m), dtype=np.float64)

    def comp(r, c):  # matrix entry (r, c) of L, 1-based, r != c -> (component index, sign)
        return (idx[(r, c)], 1.0) if r < c else (idx[(c, r)], -1.0)

    for a, (i, j) in enumerate(ps):
        col = 0
        for k in range(1, N + 1):
            if k in (i, j):
                continue
            p, sp_ = comp(i, k)
            q, sq = comp(j, k)
            pair_p[a, col], pair_q[a, col], pair_s[a, col] = p, q, sp_ * sq
            col += 1
    plane_i = np.array([i - 1 for i, _ in ps], dtype=np.int64)
    plane_j = np.array([j - 1 for _, j in ps], dtype=np.int64)
    return pair_p, pair_q, pair_s, plane_i, plane_j


@jit(parallel=True)
def split_run(L0, moments, seq_plane, seq_coef, pair_p, pair_q, pair_s, plane_i, plane_j,
              t, nsub, torque, T0, with_attitude, outL, outT):  # pragma: no cover - jitted
    """Integrate ``B`` bodies over the output grid ``t`` with a composed splitting method.

    Interval ``[t[k], t[k+1]]`` is covered by ``nsub[k]`` equal steps. Writes
    ``outL[b, k, :]`` (angular momentum at ``t[k]``) and, if ``with_attitude``,
    ``outT[b, k]`` (plain-matrix attitude, starting from ``T0[b]``).
    """
    B = L0.shape[0]
    n = L0.shape[1]
    K = t.shape[0]
    m = seq_plane.shape[0]
    npair = pair_p.shape[1]
    N = T0.shape[1]
    for b in prange(B):
        Lh = np.empty(n)  # compensated storage: L = Lh + Ll (Lh carries the value, Ll the rounding error)
        Ll = np.zeros(n)
        for a in range(n):
            Lh[a] = L0[b, a]
            outL[b, 0, a] = Lh[a]
        T = np.empty((N, N))
        if with_attitude:
            for r in range(N):
                for c in range(N):
                    T[r, c] = T0[b, r, c]
                    outT[b, 0, r, c] = T[r, c]
        for k in range(K - 1):
            ns = nsub[k]
            h = (t[k + 1] - t[k]) / ns
            for _ in range(ns):
                for r in range(m):
                    a = seq_plane[r]
                    if a < 0:
                        ch = seq_coef[r] * h
                        for e in range(n):
                            d = ch * torque[b, e] + Ll[e]
                            x = Lh[e]
                            snew = x + d
                            bb = snew - x
                            Ll[e] = (x - (snew - bb)) + (d - bb)
                            Lh[e] = snew
                        continue
                    half = 0.5 * seq_coef[r] * h * (Lh[a] + Ll[a]) / moments[b, a]
                    sh = math.sin(half)
                    chh = math.cos(half)
                    s = 2.0 * sh * chh       # sin(phi)
                    v = 2.0 * sh * sh        # 1 - cos(phi), accurate for small phi
                    for e in range(npair):
                        p = pair_p[a, e]
                        q = pair_q[a, e]
                        ss = s * pair_s[a, e]
                        x = Lh[p]
                        y = Lh[q]
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
                for r in range(N):
                    for c2 in range(N):
                        outT[b, k + 1, r, c2] = T[r, c2]
