r"""Numba kernel of the splitting integrators' tangent flow (private; used by :mod:`.chaos`).

Same data layout as :mod:`hyperrotor.classical.solvers._kernels` (``L0 (B, n)``, ``rates (B, n)``,
the word ``seq_plane, seq_coef`` of one step, the tables ``pair_p, pair_q, pair_s`` of
:func:`~hyperrotor.classical.solvers._kernels.rotation_tables`), plus ``k`` tangent vectors per
body, ``W0 (B, k, n)``.

Tangent map of one elementary flow
----------------------------------
The flow of :math:`\rho_a L_a^2/2` over ``t = coef * h`` keeps :math:`L_a` and rotates
every pair :math:`(L_p, L_q) = (\sigma_p L_{ik}, \sigma_q L_{jk})` of plane ``a``
(``sg = pair_s = sigma_p sigma_q``) by the angle :math:`\varphi = t\rho_a L_a`:

.. math:: L_p' = c L_p + sg\,s L_q, \qquad L_q' = c L_q - sg\,s L_p,
          \qquad c = \cos\varphi,\ s = \sin\varphi .

The angle depends on the state, :math:`\delta\varphi = t\rho_a\,\delta L_a`, so the
Jacobian is the same rotation plus a rank-one term along
:math:`\partial L'/\partial\varphi`, which is again expressed by the *rotated* values
(:math:`\partial L_p'/\partial\varphi = -s L_p + sg\,c L_q = sg\,L_q'`,
:math:`\partial L_q'/\partial\varphi = -sg\,L_p'`):

.. math:: \delta L_p' = c\,\delta L_p + sg\,s\,\delta L_q + sg\,L_q'\,\delta\varphi, \qquad
          \delta L_q' = c\,\delta L_q - sg\,s\,\delta L_p - sg\,L_p'\,\delta\varphi,

and :math:`\delta L_a' = \delta L_a` (every other component is unchanged). Composing
these maps along the word gives the exact derivative of the discrete step map
(the "discrete variational equation"): its Lyapunov exponents are those of the
integrator, which shadows the flow with the same structure (each factor has unit
determinant and preserves the Casimirs' level sets to first order).

Benettin's algorithm
--------------------
``nren`` renormalisations, each after ``nsub[b]`` steps of length ``h[b]``: the ``k``
tangent vectors are re-orthonormalised by modified Gram-Schmidt (the ``R`` of a QR
factorisation), and ``log R_jj`` is added to ``acc[j]``, which starts at ``acc0[b, j]`` (zero
for a new run; the sums so far when a long run goes on in time segments, with the final states
``Lout``, ``Wout`` of the previous segment: the same arithmetic as one call). ``out[b, s, j]``
holds ``acc[j]`` after renormalisation ``(s + 1) * stride`` (``s = 0 .. nstore-1``). Each
body is integrated by the same arithmetic whichever rows share its call and however its
time is cut, so results depend neither on the chunking of an ensemble nor on the segments.
"""
from __future__ import annotations

import math

import numpy as np

from hyperrotor._jit import jit

from ._kernels import SMALL_HALF_ANGLE, redo_wide_lanes, rotate_lanes, rotation, rotation_poly

__all__: list[str] = []  # private module


def _tangent_run(L0, rates, W0, acc0, seq_plane, seq_coef, pair_p, pair_q, pair_s,
                 h, nsub, nren, stride, renormalize, out, Lout, Wout):  # pragma: no cover - jitted
    """Integrate ``B`` bodies and their ``k`` tangent vectors; Benettin sums in ``out``.

    Final states in ``Lout (B, n)`` and ``Wout (B, k, n)``. ``renormalize=False`` skips the
    Gram-Schmidt step (``Wout`` is then the Jacobian of the whole run applied to ``W0``;
    ``out`` is not written): the tests compare it with finite differences.
    """
    B = L0.shape[0]
    n = L0.shape[1]
    k = W0.shape[1]
    m = seq_plane.shape[0]
    npair = pair_p.shape[1]
    L = np.empty(n)
    W = np.empty((k, n))
    fac = np.empty(m)
    acc = np.empty(k)
    for b in range(B):
        for a in range(n):
            L[a] = L0[b, a]
        for j in range(k):
            acc[j] = acc0[b, j]
            for a in range(n):
                W[j, a] = W0[b, j, a]
        for r in range(m):  # half-angle per unit L_a of flow r (its angle is 2 * fac * L_a)
            fac[r] = 0.5 * seq_coef[r] * h[b] * rates[b, seq_plane[r]]
        s_out = 0
        for ren in range(nren):
            for _ in range(nsub[b]):
                for r in range(m):
                    a = seq_plane[r]
                    f = fac[r]
                    s, v = rotation(f * L[a])  # sin(phi), 1 - cos(phi)
                    f2 = 2.0 * f             # d phi / d L_a
                    for e in range(npair):
                        p = pair_p[a, e]
                        q = pair_q[a, e]
                        sg = pair_s[a, e]
                        ss = s * sg
                        x = L[p]
                        y = L[q]
                        xn = x + (ss * y - v * x)
                        yn = y - (ss * x + v * y)
                        L[p] = xn
                        L[q] = yn
                        gp = sg * yn      # d L_p' / d phi
                        gq = -sg * xn     # d L_q' / d phi
                        for j in range(k):
                            dphi = f2 * W[j, a]
                            dx = W[j, p]
                            dy = W[j, q]
                            W[j, p] = dx + (ss * dy - v * dx) + gp * dphi
                            W[j, q] = dy - (ss * dx + v * dy) + gq * dphi
            if not renormalize:
                continue
            # modified Gram-Schmidt: W <- Q, acc += log diag(R)
            for j in range(k):
                for i in range(j):
                    d = 0.0
                    for a in range(n):
                        d += W[i, a] * W[j, a]
                    for a in range(n):
                        W[j, a] -= d * W[i, a]
                nrm = 0.0
                for a in range(n):
                    nrm += W[j, a] * W[j, a]
                nrm = math.sqrt(nrm)
                acc[j] += math.log(nrm)
                inv = 1.0 / nrm
                for a in range(n):
                    W[j, a] *= inv
            if (ren + 1) % stride == 0 and s_out < out.shape[1]:
                for j in range(k):
                    out[b, s_out, j] = acc[j]
                s_out += 1
        for a in range(n):
            Lout[b, a] = L[a]
            for j in range(k):
                Wout[b, j, a] = W[j, a]


tangent_run = jit(_tangent_run)


@jit
def dot_lanes(W, i1, i2, D):  # pragma: no cover - jitted
    """``D[j] = sum_a W[i1, a, j] W[i2, a, j]`` (per body ``j``, summed in the order of ``a``)."""
    nb = D.shape[0]
    for j in range(nb):
        D[j] = 0.0
    for a in range(W.shape[1]):
        for j in range(nb):
            D[j] += W[i1, a, j] * W[i2, a, j]


def _tangent_run_lanes(L0, rates, W0, acc0, seq_plane, seq_coef, pair_p, pair_q, pair_s,
                       h, nsub, nren, stride, lanes, out, Lout, Wout):  # pragma: no cover - jitted
    """:func:`_tangent_run` for bodies that share ``nsub`` (steps per renormalisation), bodies innermost.

    Blocks of ``lanes`` bodies advance together, the loop over the bodies of a block being the
    innermost one: the independent rotations of different bodies overlap in the CPU pipeline
    and vectorise (as ``_kernels._split_run_ensemble``). Every body sees exactly the arithmetic
    of :func:`_tangent_run` (same operations in the same order; the half-angle polynomial is
    the one of :func:`~hyperrotor.classical.solvers._kernels.rotation`: polynomials up to ``SMALL_HALF_ANGLE``, libm
    beyond), so the results
    agree with it bit for bit, whichever bodies share a block. ``nsub[0]`` is used for all.
    """
    B = L0.shape[0]
    n = L0.shape[1]
    k = W0.shape[1]
    m = seq_plane.shape[0]
    npair = pair_p.shape[1]
    ns = nsub[0]
    nblocks = (B + lanes - 1) // lanes
    for bi in range(nblocks):
        b0 = bi * lanes
        nb = min(B, b0 + lanes) - b0
        L = np.empty((n, nb))
        W = np.empty((k, n, nb))
        fac = np.empty((m, nb))
        acc = np.empty((k, nb))
        X = np.empty(nb)
        S = np.empty(nb)
        V = np.empty(nb)
        F2 = np.empty(nb)
        D = np.empty(nb)
        for j in range(nb):
            for a in range(n):
                L[a, j] = L0[b0 + j, a]
                for i in range(k):
                    W[i, a, j] = W0[b0 + j, i, a]
            for i in range(k):
                acc[i, j] = acc0[b0 + j, i]
            for r in range(m):
                fac[r, j] = 0.5 * seq_coef[r] * h[b0 + j] * rates[b0 + j, seq_plane[r]]
        s_out = 0
        for ren in range(nren):
            for _ in range(ns):
                for r in range(m):
                    a = seq_plane[r]
                    big = False
                    for j in range(nb):  # the rotations by polynomials, branch-free (vectorised)
                        x = fac[r, j] * L[a, j]
                        X[j] = x
                        S[j], V[j] = rotation_poly(x)
                        F2[j] = 2.0 * fac[r, j]
                        big |= abs(x) > SMALL_HALF_ANGLE
                    if big:  # some half-angle beyond the polynomials' range
                        redo_wide_lanes(X, S, V)
                    for e in range(npair):
                        p = pair_p[a, e]
                        q = pair_q[a, e]
                        sg = pair_s[a, e]
                        rotate_lanes(L, p, q, sg, S, V)
                        for i in range(k):
                            for j in range(nb):
                                ss = S[j] * sg
                                v = V[j]
                                gp = sg * L[q, j]
                                gq = -sg * L[p, j]
                                dphi = F2[j] * W[i, a, j]
                                dx = W[i, p, j]
                                dy = W[i, q, j]
                                W[i, p, j] = dx + (ss * dy - v * dx) + gp * dphi
                                W[i, q, j] = dy - (ss * dx + v * dy) + gq * dphi
            # modified Gram-Schmidt per body
            for i2 in range(k):
                for i1 in range(i2):
                    dot_lanes(W, i1, i2, D)
                    for a in range(n):
                        for j in range(nb):
                            W[i2, a, j] -= D[j] * W[i1, a, j]
                dot_lanes(W, i2, i2, D)
                for j in range(nb):
                    nrm = math.sqrt(D[j])
                    acc[i2, j] += math.log(nrm)
                    D[j] = 1.0 / nrm
                for a in range(n):
                    for j in range(nb):
                        W[i2, a, j] *= D[j]
            if (ren + 1) % stride == 0 and s_out < out.shape[1]:
                for j in range(nb):
                    for i in range(k):
                        out[b0 + j, s_out, i] = acc[i, j]
                s_out += 1
        for j in range(nb):
            for a in range(n):
                Lout[b0 + j, a] = L[a, j]
                for i in range(k):
                    Wout[b0 + j, i, a] = W[i, a, j]


tangent_run_lanes = jit(_tangent_run_lanes)
