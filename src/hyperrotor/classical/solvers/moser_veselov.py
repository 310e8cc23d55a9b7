r"""The discrete Moser-Veselov algorithm for the so(N) rigid body (``method="moser-veselov"``).

Moser and Veselov (Commun. Math. Phys. 139, 217 (1991)) discretise the rigid
body's Lagrangian :math:`\tfrac12\operatorname{tr}(\dot T^{\mathsf T} \dot T J)`
(mass tensor :math:`J = \operatorname{diag}(J_1, \dots, J_N)`, plane moments
:math:`I_{ij} = J_i + J_j`) as
:math:`\operatorname{tr}(T_k J T_{k+1}^{\mathsf T})`. In the plain-matrix
convention of the integrators (:math:`L = JW + WJ`,
:math:`\dot L = [W, L]`, :math:`\dot T = W T`) one step of length ``h`` reads

.. math::

    h L_k = J Q_k - Q_k^{\mathsf T} J, \qquad
    L_{k+1} = Q_k L_k Q_k^{\mathsf T}, \qquad
    T_{k+1} = Q_k T_k,

with :math:`Q_k \in SO(N)` near the identity (:math:`Q_k = e^{hW} + O(h^2)`); the
second relation is equivalent to :math:`h L_{k+1} = Q_k J - J Q_k^{\mathsf T}`.
The map is symplectic on each coadjoint orbit, time-reversible and of order 2
(McLachlan and Zanna, Found. Comput. Math. 5, 87 (2005)); ``L`` moves by exact
conjugation, so its spectrum (the Casimirs) is kept to round-off, and ``T``
stays orthogonal to round-off. The energy :math:`\sum_a L_a^2/(2I_a)` is kept to
round-off as well, at any step size (measured for N = 3, 4, 5 in the tests:
~2e-14 after 1e4 steps of ``dt = 0.1``, while the phase error is ~1e-1). It exists only for bodies with a mass tensor,
:math:`I_{ij} = J_i + J_j` (every real body; any 3D body, with possibly
negative :math:`J_i`).

Solving for :math:`Q`
---------------------
Newton's method on the Cayley parameter :math:`Q = (1 - X/2)^{-1}(1 + X/2)`,
:math:`X` antisymmetric, for :math:`F(X) = JQ - Q^{\mathsf T}J - hL = 0`, from
:math:`X_0 = hW + (X_{k-1} - h W_{k-1})` (:math:`W_{ij} = L_{ij}/I_{ij}`; :math:`hW` is exact to first
order and the :math:`O(h^2)` remainder of the previous step is carried over, so the first
guess is off by :math:`O(h^3)` and Newton needs one or two iterations fewer). With
:math:`A = 1 - X/2`, :math:`dQ = A^{-1}\,\delta\,(Q + 1)/2` and
:math:`dF = J\,dQ - (J\,dQ)^{\mathsf T}`; for :math:`\delta = E_{pq}` the
product is a rank-2 update, so the :math:`n \times n` Jacobian costs
:math:`O(nN^2)`. Iterations stop when the Newton update is below ``4 eps`` times
:math:`\max(1, \max_i |J_i| / \min I_{ij})` relative to :math:`X` (the round-off of the update: a 3D body
with a negative :math:`J_i` has :math:`I_{ij} \ll |J|`) (3-4 iterations for :math:`h|W| \lesssim 0.1`); a step
that does not converge in 30 iterations (:math:`h|W|` of order 1) raises
``RuntimeError``. The kernel solves its small linear systems (:math:`N \times N` and
:math:`n \times n`) by its own LU with partial pivoting (``_lu_factor``, ``_lu_solve``: LAPACK's
``getrf``/``getrs`` written out), not ``np.linalg``, whose shape checks and LAPACK wrappers numba
compiles for seconds (a first run compiled for 15.5 s with them, 9 s without).
"""
from __future__ import annotations

from typing import Any

import numpy as np

from hyperrotor._jit import jit, prange

from ._kernels import PARALLEL_MIN_BODIES, rotation_tables, start_attitude, store_attitude
from .base import Problem, step_lengths
from .driver import FixedStepSolver

__all__ = ["MoserVeselov"]

_MAX_NEWTON = 30
#: Absolute floor of the Newton stopping test on the Cayley parameter X (a rotation angle per
#: step). A correction dx changes L_{k+1} = Q L_k Q^T by about |dx| |L| (relative |dx|), so below
#: 1e-290 it is far under round-off; without the floor a step angle in the subnormal range
#: (|omega dt| < 2.2e-308) could never meet the relative test 4 eps |X|, whose right side underflows.
_X_FLOOR = 1e-290


def mass_tensor_of(body: Any, moments: np.ndarray) -> np.ndarray:
    """The mass tensor ``J`` (``I_ij = J_i + J_j``) of ``body``, or ``ValueError`` if it has none."""
    from ..inertia import Inertia

    inertia = getattr(body, "inertia", body)
    if not isinstance(inertia, Inertia):
        inertia = Inertia(moments)
    J = inertia.mass_tensor
    if J is None or not isinstance(J, np.ndarray):
        raise ValueError(
            "method 'moser-veselov' needs plane moments of the form I_ij = J_i + J_j (a mass tensor, "
            f"as every real body has); these moments are not: {moments.tolist()}. Use a splitting method."
        )
    return J


@jit
def _lu_factor(A, piv):  # pragma: no cover - jitted
    """LU factorisation of the square ``A`` in place, rows swapped by partial pivoting (``piv[k]``: the row
    exchanged with row ``k``), as LAPACK's ``getrf``; ``False`` if a pivot is zero (``A`` singular).

    Written out instead of ``np.linalg.solve``/``inv`` in the kernel (the module docstring says why: their
    compile time); the matrices here are N x N and n x n.
    """
    m = A.shape[0]
    for k in range(m):
        p = k
        big = abs(A[k, k])
        for r in range(k + 1, m):
            if abs(A[r, k]) > big:
                big = abs(A[r, k])
                p = r
        piv[k] = p
        if big == 0.0 or not big == big:  # (NaN: a non-finite matrix)
            return False
        if p != k:
            for c in range(m):
                A[k, c], A[p, c] = A[p, c], A[k, c]
        for r in range(k + 1, m):
            f = A[r, k] / A[k, k]
            A[r, k] = f
            for c in range(k + 1, m):
                A[r, c] -= f * A[k, c]
    return True


@jit
def _lu_solve(LU, piv, X):  # pragma: no cover - jitted
    """``X <- A^{-1} X`` in place, for every column of ``X``, from ``_lu_factor``'s ``LU`` and ``piv`` (``getrs``;
    row operations, so that the inner loops run along the rows of ``X``)."""
    m = LU.shape[0]
    ncol = X.shape[1]
    for k in range(m):
        p = piv[k]
        if p != k:
            for c in range(ncol):
                X[k, c], X[p, c] = X[p, c], X[k, c]
    for r in range(m):  # L Y = P X (unit lower triangle)
        for k in range(r):
            f = LU[r, k]
            for c in range(ncol):
                X[r, c] -= f * X[k, c]
    for r in range(m - 1, -1, -1):  # U X = Y
        for k in range(r + 1, m):
            f = LU[r, k]
            for c in range(ncol):
                X[r, c] -= f * X[k, c]
        d = LU[r, r]
        for c in range(ncol):
            X[r, c] /= d


@jit
def _cayley(X, eye, LU, piv, Ainv, Q):  # pragma: no cover - jitted
    """The Cayley map ``Q = A^{-1} (1 + X/2)`` of ``X`` and ``Ainv = A^{-1}``, ``A = 1 - X/2``, in place (``LU``:
    ``A``'s factors); ``False`` if ``A`` is singular (never for a finite antisymmetric ``X``: its eigenvalues
    are ``1 - i y/2``)."""
    N = X.shape[0]
    for r in range(N):
        for c in range(N):
            LU[r, c] = eye[r, c] - 0.5 * X[r, c]
            Q[r, c] = eye[r, c] + 0.5 * X[r, c]
            Ainv[r, c] = eye[r, c]
    if not _lu_factor(LU, piv):
        return False
    _lu_solve(LU, piv, Ainv)
    _lu_solve(LU, piv, Q)
    return True


@jit
def _product(A, B, out, transpose_b):  # pragma: no cover - jitted
    """``out = A B`` (``A B^T`` with ``transpose_b``) of square matrices (``out`` neither of them)."""
    N = A.shape[0]
    for r in range(N):
        for c in range(N):
            v = 0.0
            for k in range(N):
                v += A[r, k] * (B[c, k] if transpose_b else B[k, c])
            out[r, c] = v


def _mv_run(L0, J, moments, pair_i, pair_j, hstep, nsub, T0, with_attitude, outL, outT, status,
            pred):  # pragma: no cover
    """Integrate ``B`` bodies over ``K = hstep.size + 1`` output times (``nsub[k]`` steps of ``hstep[k]``).

    ``L0 (B, n)`` components in plane order; ``pair_i, pair_j (n,)`` 0-based axes of
    plane ``a``. Writes ``outL[b, k]``, ``outT[b, k]`` (plain attitude) and
    ``status[b]`` = 0, or 1 + the index of the first step whose Newton solve failed.
    ``pred (B, n + 1)``: the Newton predictor's state (the :math:`O(h^2)` part of ``X`` and
    the step it was taken with; zeros for a new run), read on entry and written on exit, so
    that a run continued in a second call does the arithmetic of one call.
    """
    B = L0.shape[0]
    n = L0.shape[1]
    K = hstep.shape[0] + 1
    N = J.shape[0]
    # Newton's update reaches round-off times the condition of J Q - Q^T J: with J_i ~ -J_j (a 3D body with a
    # negative J_i) it is ~ eps max|J| / I_ij, and a test at 4 eps failed every step of [3, 0.1, 1.1]
    jmax = 0.0
    for i in range(N):
        jmax = max(jmax, abs(J[i]))
    imin = np.inf
    for a in range(n):
        imin = min(imin, moments[a])
    tol = 4.0 * np.finfo(np.float64).eps * max(1.0, jmax / imin)
    for b in prange(B):
        Lm = np.zeros((N, N))
        for a in range(n):
            Lm[pair_i[a], pair_j[a]] = L0[b, a]
            Lm[pair_j[a], pair_i[a]] = -L0[b, a]
            outL[b, 0, a] = L0[b, a]
        T = start_attitude(T0, b, with_attitude, outT)
        X = np.zeros((N, N))
        Jac = np.empty((n, n))
        dx = np.empty((n, 1))  # (-F, then the Newton update)
        eye = np.eye(N)
        LU = np.empty((N, N))
        Ainv = np.empty((N, N))
        Q = np.empty((N, N))
        W = np.empty((N, N))  # (a product's output)
        piv = np.empty(N, dtype=np.int64)
        pivn = np.empty(n, dtype=np.int64)
        step = 0
        failed = False
        corr = np.empty(n)
        for a in range(n):
            corr[a] = pred[b, a]
        hprev = pred[b, n]
        for k in range(K - 1):
            h = hstep[k]
            ratio2 = (h / hprev) ** 2 if hprev != 0.0 else 0.0
            for _ in range(nsub[k]):
                for a in range(n):  # X0 = h W + (X - h W) of the previous step (an O(h^3) predictor)
                    v = h * Lm[pair_i[a], pair_j[a]] / moments[a] + ratio2 * corr[a]
                    X[pair_i[a], pair_j[a]] = v
                    X[pair_j[a], pair_i[a]] = -v
                converged = False
                for it in range(_MAX_NEWTON):
                    if not _cayley(X, eye, LU, piv, Ainv, Q):
                        break
                    for a in range(n):  # -F, F = J Q - Q^T J - h L in plane components (the right side)
                        i = pair_i[a]
                        j = pair_j[a]
                        dx[a, 0] = -(J[i] * Q[i, j] - Q[j, i] * J[j] - h * Lm[i, j])
                    # Jacobian columns: delta = E_pq, dQ = Ainv delta (Q + 1) / 2 (rank 2)
                    for c in range(n):
                        p = pair_i[c]
                        q = pair_j[c]
                        for a in range(n):
                            i = pair_i[a]
                            j = pair_j[a]
                            # (J dQ)_ij - (J dQ)_ji with dQ_rs = (Ainv[r,p] (Q+1)[q,s] - Ainv[r,q] (Q+1)[p,s]) / 2
                            dij = Ainv[i, p] * (Q[q, j] + eye[q, j]) - Ainv[i, q] * (Q[p, j] + eye[p, j])
                            dji = Ainv[j, p] * (Q[q, i] + eye[q, i]) - Ainv[j, q] * (Q[p, i] + eye[p, i])
                            Jac[a, c] = 0.5 * (J[i] * dij - J[j] * dji)
                    if not _lu_factor(Jac, pivn):  # (singular: the step fails as a Newton solve that diverged)
                        break
                    _lu_solve(Jac, pivn, dx)
                    size = 0.0
                    upd = 0.0
                    for a in range(n):
                        i = pair_i[a]
                        j = pair_j[a]
                        X[i, j] += dx[a, 0]
                        X[j, i] -= dx[a, 0]
                        size = max(size, abs(X[i, j]))
                        upd = max(upd, abs(dx[a, 0]))
                    if not (upd == upd) or upd > 1e3:  # NaN or diverging
                        break
                    if upd <= tol * size or upd <= _X_FLOOR:
                        converged = True
                        break
                if not converged:
                    status[b] = 1 + step
                    failed = True
                    break
                for a in range(n):  # the O(h^2) part of X, carried to the next step's first guess
                    corr[a] = X[pair_i[a], pair_j[a]] - h * Lm[pair_i[a], pair_j[a]] / moments[a]
                ratio2 = 1.0
                hprev = h
                _cayley(X, eye, LU, piv, Ainv, Q)  # Q of the converged X
                _product(Q, Lm, W, False)
                _product(W, Q, Lm, True)
                for r in range(N):  # keep L exactly antisymmetric
                    Lm[r, r] = 0.0
                    for c in range(r + 1, N):
                        v = 0.5 * (Lm[r, c] - Lm[c, r])
                        Lm[r, c] = v
                        Lm[c, r] = -v
                if with_attitude:
                    _product(Q, T, W, False)
                    T, W = W, T
                step += 1
            if failed:
                break
            for a in range(n):
                outL[b, k + 1, a] = Lm[pair_i[a], pair_j[a]]
            if with_attitude:
                store_attitude(T, b, k + 1, outT)
        for a in range(n):
            pred[b, a] = corr[a]
        pred[b, n] = hprev


mv_run = jit(parallel=True)(_mv_run)
mv_run_serial = jit(_mv_run)  # one body or a few: no thread launch


def run(L0: np.ndarray, J: np.ndarray, moments: np.ndarray, hstep: np.ndarray, nsub: np.ndarray,
        T0: np.ndarray, with_attitude: bool, pred: np.ndarray | None = None):
    """Moser-Veselov steps (``nsub[k]`` of length ``hstep[k]`` per interval) for the bodies ``L0 (B, n)``;
    returns ``(L (B, K, n), T (B, K, N, N) or None, predictor state (B, n + 1))``, ``K = hstep.size + 1``
    (``pred``: the predictor state a previous call ended with; default: a new run)."""
    B, n = L0.shape
    N = J.size
    K = hstep.size + 1
    pair_i, pair_j = rotation_tables(N)[3:]  # 0-based axes i - 1, j - 1 of each plane
    outL = np.empty((B, K, n))
    outT = np.empty((B, K, N, N)) if with_attitude else np.empty((B, 1, N, N))
    status = np.zeros(B, dtype=np.int64)
    pred = np.zeros((B, n + 1)) if pred is None else pred.copy()
    T0c = np.ascontiguousarray(T0) if with_attitude else np.zeros((1, N, N))
    kernel = mv_run if B >= PARALLEL_MIN_BODIES else mv_run_serial
    kernel(np.ascontiguousarray(L0, dtype=float), np.ascontiguousarray(J, dtype=float),
           np.ascontiguousarray(moments, dtype=float), pair_i, pair_j, np.ascontiguousarray(hstep, dtype=float), nsub,
           T0c, bool(with_attitude), outL, outT, status, pred)
    bad = np.flatnonzero(status)
    if bad.size:
        b = int(bad[0])
        raise RuntimeError(
            f"moser-veselov: the implicit step equation h L = J Q - Q^T J has no solution near Q = 1 "
            f"at step {int(status[b]) - 1} of body {b} (h |W| too large); use a smaller dt or rtol"
        )
    return outL, (outT if with_attitude else None), pred


class MoserVeselov(FixedStepSolver):
    """The discrete Moser-Veselov map (see the module docstring), order 2.

    Implicit; symplectic and time-reversible; keeps the Casimirs, the energy and the
    attitude's orthogonality to round-off. Fixed step (``dt`` or chosen once from
    ``rtol``). Needs a mass tensor (:math:`I_{ij} = J_i + J_j`) and no torque. Per step
    it costs about as much as :math:`3n(n+2)/2` plane flows of a splitting (Newton on the
    Cayley parameter; 180 in 5D), so the splittings reach a given error much sooner
    (``benchmarks/work_precision_classical.py``); a reference method.
    """

    name = "moser-veselov"
    order = 2
    preserves = frozenset({"casimirs", "energy", "orthogonality", "symplectic", "reversible"})
    supports_torque = "none"

    def check(self, problem: Problem) -> None:
        super().check(problem)
        self._J = mass_tensor_of(problem.body, problem.moments)

    def flows_per_step(self, problem: Problem) -> int:
        # Newton with an n x n Jacobian (built in O(n N^2), solved in O(n^3)) at 3-4 iterations: a step costs
        # 22, 208, 710, 3106 of splitting2's plane flows at N = 3, 5, 7, 10 (measured, one body): 3 n (n + 2) / 2
        return 3 * problem.n * (problem.n + 2) // 2

    def advance(self, problem, L, T, t, nsub, members=None, h=None, carry=None):
        outL, outT, self.last_carry = run(L, self._J, problem.moments, step_lengths(t, nsub) if h is None else h,
                                          nsub, T, T is not None, carry)
        return outL, outT

    def stats(self, problem: Problem) -> dict:
        return {}
