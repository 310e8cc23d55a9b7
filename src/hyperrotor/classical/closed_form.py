r"""Closed-form solutions of the torque-free Euler equations (paper Sec. 3).

Three families are solved exactly, for use as ground truth and by
:mod:`hyperrotor.classical.scenes`:

* **Equal moments** (eqs. 82-83), any N: :math:`\dot\omega = 0`.
* **One distinguished axis** ("quartet", eqs. 84-118, generalised to any N):
  moments :math:`I_P = 1 + \kappa^2` for every plane ``P`` containing the axis
  ``a`` and :math:`I_P = 2` otherwise (or any common rescaling), solved exactly in
  :mod:`hyperrotor.classical.quartet` (with the paper's discrepancies in Sec. 3).
* **3D Euler-Poinsot** with Jacobi elliptic functions, both regimes of the
  energy-momentum relation, the separatrix and the symmetric top
  (:mod:`hyperrotor.classical.poinsot`).

This module solves the first, tells which family a body belongs to
(:func:`detect_closed_form`) and dispatches to its solution (:func:`closed_form_solution`).
"""
from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from .. import _pricing, _validate
from .._equality import fields_equal, fields_unequal
from .._options import options, register
from ..conventions import dimension_from_count
from ._closed_form_input import plane_vector, times
from .poinsot import euler_poinsot
from .quartet import axis_layout, plane_axes, quartet_flow

register(
    "closed_form_rtol", 1e-14,
    "detect_closed_form / closed_form_solution (and the scene routes): two plane moments count as equal "
    "when they differ by at most this times the largest moment. 1e-14 (~50 eps) accepts moments that "
    "went through a few float operations (J_i + J_j, unit conversions) and nothing else: a body whose "
    "moments differ by 1e-12 relative is not a quartet, and its motion leaves the closed form after "
    "~1e12 / |omega| time units.",
)

__all__ = [
    "equal_moments_solution",
    "detect_closed_form",
    "closed_form_solution",
]


# ----------------------------------------------------------------------------
# equal moments (eqs. 82-83)
# ----------------------------------------------------------------------------
def equal_moments_solution(omega0: Any, t: Any) -> np.ndarray:
    r"""Exact solution for equal plane moments (eqs. 82-83), any N.

    With :math:`I_{ij} = I` for all planes, :math:`L = I W` and
    :math:`\dot L = [W, L] = I[W, W] = 0`: every component is constant.

    Parameters
    ----------
    omega0 : array_like, shape (..., n_planes)
    t : array_like, shape (n_t,)

    Returns
    -------
    numpy.ndarray, shape (..., n_t, n_planes)
    """
    w = plane_vector(omega0)
    tt = times(t)
    _pricing.check("closed_form_output", n_times=tt.size, width=w.size)
    return np.broadcast_to(w[..., None, :], w.shape[:-1] + (tt.size, w.shape[-1])).copy()


# ----------------------------------------------------------------------------
# detection and dispatch
# ----------------------------------------------------------------------------
def detect_closed_form(body: Any, *, rtol: float | None = None) -> dict | None:
    r"""Which closed form the inertia admits, if any.

    Returns ``{"kind": "equal"}``, ``{"kind": "quartet", "axis": a, "theta": Theta}``
    (any N; moments ``alpha`` on the planes containing ``a`` and ``beta`` on the
    others, :math:`\Theta = 1 - \beta/\alpha`), ``{"kind": "euler-poinsot"}``
    (N = 3) or ``None``. Moments are compared with relative tolerance ``rtol``,
    ``0 <= rtol < 1`` (default ``hr.options["closed_form_rtol"]``, 1e-14).
    """
    I = _validate.moments(body, name="body")
    rtol = options["closed_form_rtol"] if rtol is None else _validate.tolerance("rtol", rtol, allow_zero=True)
    N = dimension_from_count(I.size)
    scale = float(np.max(np.abs(I)))

    def same(x):
        return float(np.ptp(x)) <= rtol * scale if x.size else True

    if same(I):
        return {"kind": "equal"}
    if N == 3:
        return {"kind": "euler-poinsot"}
    # candidate axes first, in O(n): the moments of the planes through a must agree (per-axis range)
    i, j = plane_axes(N)
    lo, hi = np.full(N + 1, np.inf), np.full(N + 1, -np.inf)
    for ends in (i, j):
        np.minimum.at(lo, ends, I)
        np.maximum.at(hi, ends, I)
    candidates = [a for a in range(N, 0, -1) if hi[a] - lo[a] <= rtol * scale]
    for a in candidates:
        idx, _, rest = axis_layout(N, a)
        if same(I[idx]) and same(I[rest]):
            alpha, beta = float(np.mean(I[idx])), float(np.mean(I[rest]))
            return {"kind": "quartet", "axis": a, "theta": 1.0 - beta / alpha}
    return None


class ClosedFormSolution(NamedTuple):
    """Result of :func:`closed_form_solution` (unpacks as ``omega, kind``; compares field by field)."""

    __eq__, __ne__ = fields_equal, fields_unequal  # (a tuple's == refuses the array field)
    __hash__ = None

    #: omega(t), shape ``(..., n_t, n_planes)``
    omega: np.ndarray
    #: the closed form used: ``"equal"``, ``"quartet"`` or ``"euler-poinsot"``
    kind: str


def closed_form_solution(body: Any, omega0: Any, t: Any, *, rtol: float | None = None) -> ClosedFormSolution:
    """Exact omega(t) for an inertia admitting a closed form, and the name of the form used.

    Dispatches to :func:`equal_moments_solution`, the quartet flow (any axis, any
    N, any common scale of the two moments) or :func:`euler_poinsot` (N = 3,
    unbatched ``omega0``; batches are looped). Raises ``ValueError`` when the
    inertia admits none (see :func:`detect_closed_form`).

    Returns
    -------
    ClosedFormSolution
        ``(omega, kind)``: omega of shape ``(..., n_t, n_planes)``; kind ``"equal"``, ``"quartet"`` or
        ``"euler-poinsot"``.
    """
    I = _validate.moments(body, name="body")
    info = detect_closed_form(I, rtol=rtol)
    if info is None:
        raise ValueError("this inertia admits no closed form (not equal, not one-distinguished-axis, not 3D)")
    w = plane_vector(omega0, I.size)
    tt = times(t)
    _pricing.check("closed_form_output", n_times=tt.size, width=w.size)
    kind = info["kind"]
    if kind == "equal":
        return ClosedFormSolution(equal_moments_solution(w, tt), kind)
    if kind == "quartet":
        _pricing.check("closed_form_solution", d=dimension_from_count(I.size) - 1,
                       count=int(np.prod(w.shape[:-1])))
        return ClosedFormSolution(quartet_flow(info["theta"], w, tt, info["axis"]), kind)
    flat = w.reshape(-1, 3)
    out = np.stack([euler_poinsot(I, x, tt) for x in flat])
    return ClosedFormSolution(out.reshape(w.shape[:-1] + (tt.size, 3)), kind)
