r"""Poincaré sections of the free rigid body: the crossings of one orbit through a hyperplane
:math:`L_{ij} = c`, located by the events of :func:`hyperrotor.simulate` (a regular orbit's
crossings lie on curves or tori, a chaotic one's fill areas; see :func:`poincare_section`)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from hyperrotor import _pricing, _validate
from hyperrotor._equality import fields_equal
from hyperrotor._floats import power_of_two_scale
from hyperrotor._options import options
from hyperrotor.conventions import dimension_from_count, plane_index

from .chaos import LYAPUNOV_METHODS
from .simulate import simulate
from .solvers import SOLVERS
from .solvers.splitting import splitting_coefficients
from .solvers.step_control import rate_bound
from .stability import _labels, _local_plane

__all__ = ["poincare_section", "PoincareSection"]


@dataclass(frozen=True)
class PoincareSection:
    r"""Crossings of one orbit through the hyperplane :math:`L_{ij} = c` (see :func:`poincare_section`).

    Attributes
    ----------
    t : ndarray (m,)
        crossing times.
    L, omega : ndarray (m, n)
        body-frame angular momenta and angular velocities at the crossings (plane order).
    plane : tuple (i, j)
        the plane whose component defines the section, in the body's axis labels.
    value : float
        ``c``.
    direction : int
        ``+1`` (upward crossings, :math:`\dot L_{ij} > 0`), ``-1`` (downward) or ``0`` (both).
    N : int
        dimension of the body.
    axes : tuple
        the body's axis labels (``RigidBody.axes``: a locked body keeps its original ones, e.g. ``(2, 3, 4, 5)``);
        ``plane`` and :meth:`coordinates` use them.
    """

    __eq__ = fields_equal  # (field by field: the generated == refuses array fields)
    __hash__ = None

    t: np.ndarray
    L: np.ndarray
    omega: np.ndarray
    plane: tuple
    value: float
    direction: int
    N: int
    axes: tuple = ()

    def coordinates(self, *planes: Any) -> np.ndarray:
        """Columns of ``L`` for the given planes, shape ``(m, len(planes))`` (e.g. ``sec.coordinates((1, 3), (2, 4))``)."""
        labels = self.axes or tuple(range(1, self.N + 1))
        cols = [plane_index(_local_plane(p, labels), self.N) for p in planes]
        return self.L[:, cols]

    def __len__(self) -> int:
        return int(self.t.size)


def poincare_section(
    body: Any,
    omega0: Any,
    T: float,
    *,
    plane: Any = (1, 2),
    value: float = 0.0,
    direction: int = 1,
    method: str = "splitting8",
    dt: float | None = None,
    progress: bool | None = None,
) -> PoincareSection:
    r"""Poincaré section of one orbit: its crossings of :math:`L_{ij} = c` over ``[0, T]``.

    The orbit is integrated by :func:`hyperrotor.simulate` with a fixed-step splitting
    (Casimirs kept to round-off, so every crossing lies on the orbit's coadjoint orbit and,
    up to the method's bounded energy error, on its energy surface); the crossings are
    located by ``simulate``'s events (``events=g`` with :math:`g = L_{ij} - c` and
    ``g.direction = direction``) to the method's accuracy.

    For a body with a 2-degree-of-freedom reduced motion (so(4), or a 5D body whose
    momentum lies in the invariant so(4) of a locked axis: :math:`L_{i5} = 0`) the section
    is two-dimensional: a regular orbit's crossings lie on curves, a chaotic orbit's fill an
    area. In 5D in general the section of a regular orbit is a 3-torus, whose 2-D
    projections (:meth:`PoincareSection.coordinates`) fill areas too.

    Parameters
    ----------
    body : RigidBody, Inertia or array_like (n,)
        the body.
    omega0 : array_like (n,)
        initial angular velocities (one orbit).
    T : float
        length of the run (> 0).
    plane : pair or str
        the plane ``(i, j)`` whose momentum component defines the section (default ``(1, 2)``), in the body's axis
        labels (a locked ``RigidBody`` keeps its original ones, as in :func:`linear_stability`).
    value : float
        the level ``c``.
    direction : {1, -1, 0}
        crossings with increasing (``1``), decreasing (``-1``) or either sign of change (``0``).
    method : str
        a splitting method (as :func:`lyapunov`).
    dt : float, optional
        step; default ``options["lyapunov_step"] / w_max`` (as :func:`lyapunov`).
    progress : bool or None
        progress bar of the integration.

    Returns
    -------
    PoincareSection
    """
    moments = _validate.moments(body, name="body")
    n = moments.size
    N = dimension_from_count(n)
    w0 = _validate.components("omega0", omega0, n, what="angular velocities omega_ij in plane order (one orbit)",
                              batch=False)
    T = _validate.positive("T", T)
    labels = _labels(body, N)  # (a locked body's planes are named by its own axes, as in linear_stability)
    ij = _local_plane(plane, labels)
    value = _validate.real("value", value)
    if _validate.real("direction", direction) not in (1, -1, 0):  # (TypeError for a bool, text, ...)
        raise ValueError(f"direction must be 1 (upward), -1 (downward) or 0 (both), got {_validate.fmt(direction)}")
    method = _validate.choice("method", method, LYAPUNOV_METHODS)
    dt = _validate.positive("dt", dt, allow_none=True)
    progress = _validate.flag("progress", progress, allow_none=True)
    a = plane_index(ij, N)
    L0 = w0 * moments
    s = power_of_two_scale(float(np.max(np.abs(L0))))  # (exact: no overflow)
    wmax = float(rate_bound(moments[None, :], L0[None, :] / s)[0]) * s
    if dt is None:
        dt = options["lyapunov_step"] / wmax if wmax > 0 else T
        dt = min(dt, T)  # a (nearly) resting body: one step (lyapunov_step / wmax overflows for subnormal omega)
    steps = T / dt
    if not steps <= options["max_steps"]:
        raise _pricing.refuse("poincare_section", f"the orbit over T = {_validate.fmt(T)} in steps of dt = {dt:.3g} "
                              f"(omega0 up to |omega| = {_validate.fmt(float(np.max(np.abs(w0))))})", steps,
                              "max_steps", "steps", "shorten T or give a larger dt")
    stages = splitting_coefficients(SOLVERS[method].order).size  # (splitting2: 1 ... splitting10: 35)
    _pricing.check("poincare_section", N=N, steps=steps, turns=T * wmax, stages=stages)  # (the event at every step)

    def crossing(_t, L):
        return L[a] - value

    crossing.direction = int(direction)
    traj = simulate(moments, w0, [0.0, T], method=method, dt=dt, events=crossing, progress=progress)
    L_ev = np.asarray(traj.L_events[0]).reshape(-1, n)
    return PoincareSection(t=np.asarray(traj.t_events[0], dtype=float), L=L_ev, omega=L_ev / moments,
                           plane=(labels[ij[0] - 1], labels[ij[1] - 1]), value=value, direction=int(direction), N=N,
                           axes=labels)
