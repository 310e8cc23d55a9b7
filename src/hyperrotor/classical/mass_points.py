r"""Point masses: their second moments and the rank-4 inertia tensor of eq. (3).

.. math:: I^{ijkl} = \tfrac12 \sum_p m_p \bigl(-r^i\delta^{jk}r^l + r^i\delta^{jl}r^k
          + r^j\delta^{ik}r^l - r^j\delta^{il}r^k\bigr)

with the paper's normalization (in principal axes :math:`I^{ijij} = (m_i + m_j)/2`, half the
physical plane moment that :class:`~hyperrotor.Inertia` stores; see the docstring of
:mod:`hyperrotor.classical.inertia`). :meth:`hyperrotor.Inertia.from_points` reads its plane
moments from the principal axes computed here.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from hyperrotor import _pricing, _validate
from hyperrotor._lazy import sympy as sp  # SymPy loads on first use (light ``import hyperrotor``)
from hyperrotor._floats import power_of_two_scale
from hyperrotor._options import options, register
from hyperrotor.conventions import check_dimension

__all__ = ["inertia_tensor", "second_moment_matrix", "check_tensor_symmetries"]

register(
    "inertia_symmetry_atol", 1e-12,
    "check_tensor_symmetries: largest violation of the eq. (3) symmetries (antisymmetry in each index "
    "pair, pair exchange, the cyclic identity) allowed, relative to max(1, max|I^ijkl|). A tensor built "
    "from point masses in floats carries ~N^2 eps of round-off; 1e-12 leaves room up to N ~ 50 while a "
    "tensor that lacks a symmetry misses by O(1).",
)

# ----------------------------------------------------------------------------
# the rank-4 tensor of eq. (3)
# ----------------------------------------------------------------------------
def second_moment_matrix(masses: Any, positions: Any, *, center: bool = True) -> np.ndarray:
    r"""Second-moment matrix :math:`M_{kl} = \sum_p m_p\, r_p^k r_p^l` of point masses.

    Parameters
    ----------
    masses : array_like, shape (n,)
        Non-negative point masses with a positive total.
    positions : array_like, shape (n, N)
        Positions, ``N >= 2``.
    center : bool
        Measure positions from the centre of mass (default), the origin the
        paper assumes for eq. (6); otherwise from the coordinate origin.
    """
    M, e = second_moments_scaled(masses, positions, center=center)
    return np.ldexp(M, e)


def second_moments_scaled(masses: Any, positions: Any, *, center: bool = True) -> tuple[np.ndarray, int]:
    """``(M', e)`` with :func:`second_moment_matrix` ``= M' 2^e``: one BLAS product of the points scaled by powers of
    two (exact), so that positions of 1e160 or 1e-170 do not overflow or underflow in the squares (the principal
    axes come from ``M'``: exactly the same for a body scaled by any power of two). Priced; a matrix whose largest
    entry passes the double range (or underflows to 0 entirely) is refused naming the points."""
    center = _validate.flag("center", center)
    m, r = check_points(masses, positions)
    _pricing.check("second_moment_matrix", N=r.shape[1], points=r.shape[0])
    m_max, r_max = float(np.max(m)), float(np.max(np.abs(r)))
    sm, sr = power_of_two_scale(m_max), power_of_two_scale(r_max)
    lost = (m > 0.0) & (m / sm < np.finfo(float).tiny)  # (a mass below 2^-1022 of the largest: digits or all lost)
    if np.any(lost):
        raise ValueError(f"masses span more than double precision: {_validate.fmt(float(np.min(m[lost])))} beside "
                         f"{_validate.fmt(m_max)} (the lighter points' share would be lost); rescale or drop them")
    m, r = m / sm, r / sr
    if center:
        r = r - (m @ r) / m.sum()
    M = (r.T * m) @ r
    M = 0.5 * (M + M.T)  # (symmetric to the last bit: the principal axes come from its lower triangle)
    e = math.frexp(sm)[1] + 2 * math.frexp(sr)[1] - 3  # (sm = 2^(e_m - 1), sr = 2^(e_r - 1))
    big = max(float(np.max(np.abs(M))), float(np.trace(M)))  # (the trace bounds the principal moments too)
    if big > 0.0:
        top = math.frexp(big)[1] + e  # (the largest entry is in [2^(top - 1), 2^top))
        points = f"masses up to {_validate.fmt(m_max)}, positions up to {_validate.fmt(r_max)}"
        if top > 1024:
            raise ValueError(f"the second moments sum m r^2 of the points exceed double precision ({points}); "
                             f"rescale the masses or the positions")
        if top < -1073:
            raise ValueError(f"the second moments sum m r^2 of the points underflow double precision to 0 "
                             f"({points}); rescale the masses or the positions")
    return M, e


def check_points(masses: Any, positions: Any) -> tuple[np.ndarray, np.ndarray]:
    m = _validate.finite_array("masses", masses)
    r = _validate.finite_array("positions", positions)
    if r.ndim != 2 or r.shape[1] < 2:
        raise ValueError(f"positions must have shape (n_points, N) with N >= 2, got shape {r.shape}")
    check_dimension(r.shape[1])  # (options["max_dimension"], before any product)
    if m.ndim == 0:
        m = np.full(r.shape[0], float(m))
    if m.shape != (r.shape[0],):
        raise ValueError(f"masses must have shape ({r.shape[0]},) to match positions {r.shape}, got {m.shape}")
    if not (np.all(np.isfinite(m)) and np.all(np.isfinite(r))):
        raise ValueError("masses and positions must be finite")
    if np.any(m < 0) or m.sum() <= 0:
        raise ValueError(f"masses must be >= 0 with a positive total, got min {m.min()} and total {m.sum()}")
    return m, r


def tensor_from_second_moments(M: np.ndarray) -> np.ndarray:
    r"""Eq. (3): :math:`I^{ijkl} = \tfrac12(-\delta_{jk}M_{il} + \delta_{jl}M_{ik} + \delta_{ik}M_{jl} - \delta_{il}M_{jk})`."""
    N = M.shape[0]
    d = np.eye(N, dtype=M.dtype if M.dtype != object else float)
    if M.dtype == object:
        d = d.astype(object)
    t = (
        -np.einsum("jk,il->ijkl", d, M)
        + np.einsum("jl,ik->ijkl", d, M)
        + np.einsum("ik,jl->ijkl", d, M)
        - np.einsum("il,jk->ijkl", d, M)
    )
    return t / 2 if M.dtype != object else t * sp.Rational(1, 2)


def inertia_tensor(masses: Any, positions: Any, *, center: bool = True) -> np.ndarray:
    r"""The rank-4 inertia tensor of eq. (3) of point masses, in the input frame.

    .. math:: I^{ijkl} = \tfrac12 \sum_p m_p \bigl(-r^i\delta^{jk}r^l + r^i\delta^{jl}r^k
              + r^j\delta^{ik}r^l - r^j\delta^{il}r^k\bigr)

    with the paper's normalization: in principal axes
    :math:`I^{ijij} = (m_i + m_j)/2`, half the physical plane moment stored by
    :class:`Inertia` (see the module docstring). The result satisfies the
    symmetries listed in eq. (3), see :func:`check_tensor_symmetries`.

    Returns
    -------
    numpy.ndarray, shape (N, N, N, N)
    """
    S = second_moment_matrix(masses, positions, center=center)
    _pricing.check("inertia_tensor", N=S.shape[0])
    return tensor_from_second_moments(S)


def check_tensor_symmetries(tensor: Any, *, atol: float | None = None) -> None:
    r"""Raise ``ValueError`` unless ``tensor`` has the symmetries of eq. (3).

    :math:`I^{ijkl} = -I^{jikl} = -I^{ijlk} = I^{klij}` and the cyclic identity
    :math:`I^{ijkl} + I^{iklj} + I^{iljk} = 0`. ``atol`` is relative to
    ``max |I|``.
    """
    t = _validate.finite_array("tensor", tensor)
    if t.ndim != 4 or len(set(t.shape)) != 1:
        raise ValueError(f"an inertia tensor has shape (N, N, N, N), got {t.shape}")
    atol = options["inertia_symmetry_atol"] if atol is None else _validate.positive("atol", atol, allow_zero=True)
    tol = atol * max(1.0, float(np.max(np.abs(t), initial=0.0)))
    checks = {
        "I^ijkl = -I^jikl": t + t.transpose(1, 0, 2, 3),
        "I^ijkl = -I^ijlk": t + t.transpose(0, 1, 3, 2),
        "I^ijkl = I^klij": t - t.transpose(2, 3, 0, 1),
        "I^ijkl + I^iklj + I^iljk = 0": t + t.transpose(0, 2, 3, 1) + t.transpose(0, 3, 1, 2),
    }
    for name, resid in checks.items():
        err = float(np.max(np.abs(resid), initial=0.0))
        if err > tol:
            raise ValueError(f"inertia tensor violates {name}: max residual {err:.3g} > {tol:.3g}")


def principal_axes(M: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Eigen-decomposition of the second-moment matrix, axes ordered like the input axes.

    Returns ``(m, R)`` with ``M = R diag(m) R^T``, ``R`` a proper rotation
    (det +1) whose column ``k`` is the principal axis that best matches input
    axis ``k``.
    """
    from scipy.optimize import linear_sum_assignment

    _pricing.check("principal_axes", N=M.shape[0])
    vals, vecs = np.linalg.eigh(M)
    rows, cols = linear_sum_assignment(-np.abs(vecs))  # rows: input axis, cols: eigenvector
    order = np.empty(len(vals), dtype=int)
    order[rows] = cols
    R = vecs[:, order].copy()
    vals = vals[order]
    R *= np.where(np.diag(R) < 0, -1.0, 1.0)
    if np.linalg.det(R) < 0:
        k = int(np.argmin(np.abs(np.diag(R))))
        R[:, k] *= -1.0
    return vals, R
