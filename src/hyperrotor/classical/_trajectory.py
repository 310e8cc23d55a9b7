"""The result of :func:`hyperrotor.simulate`: :class:`Trajectory` (states, events, dense output, stats).

A plain object of arrays and two small callables that are objects too (the dense output of the
run), so it pickles and deep-copies whole.
"""
from __future__ import annotations

from typing import Any, Callable

import numpy as np

from hyperrotor import _pricing, _validate
from hyperrotor._equality import values_equal

__all__ = ["Trajectory"]


class Trajectory:
    r"""Result of :func:`simulate`.

    Attributes
    ----------
    t : ndarray (K,)
        output times (ends early after a terminal event).
    omega : ndarray batch + (K, n)
        angular velocities :math:`\omega_{ij}(t)` in plane order.
    L : ndarray batch + (K, n)
        body-frame angular momenta :math:`L^{ij} = I_{ij}\omega_{ij}`.
    attitude : ndarray batch + (K, N, N) or None
        :math:`T(t)` (eq. 19) in the body's matrix convention, ``None`` unless asked.
    t_events : list of ndarray or None
        with ``events=``: one array of event times per event function (as ``solve_ivp``);
        for an ensemble, per event function a list over the members (flattened batch order)
        of such arrays.
    L_events, omega_events : list of ndarray (m, n) or None
        the states at those times (nested the same way for an ensemble);
        ``attitude_events`` too when the attitude is integrated.
    body : object
        the ``body`` argument.
    moments : ndarray (n,)
        the plane moments used.
    stats : dict
        ``method``, ``order``, ``steps`` (steps per trajectory of a fixed-step method,
        ``None`` for scipy), ``nfev`` (scipy, summed over the ensemble), ``dt`` (largest
        step used), ``rtol``, ``status`` (``"finished"`` or ``"terminated by event"``),
        ``chunks`` (compiled calls of the run), ``wall_time`` (s); for the fixed-step
        methods also ``work`` (every step of the call times the members it advanced: run,
        probes, check, re-runs) and ``reruns`` (re-runs after a failed check); for the splittings also
        ``flows_per_step`` (elementary plane flows in one step), ``casimir_shift`` and
        ``compensated`` (see :mod:`hyperrotor.classical.solvers.splitting`).
    """

    #: the run's time origin (class default: trajectories pickled before it existed ran from scaled time 0)
    _origin = 0.0

    def __init__(self, t, omega, L, attitude, body, moments, stats, *, dense=None, scale=1.0, signs=None,
                 events=None, origin=0.0):
        self.t = t
        self.omega = omega
        self.L = L
        self.attitude = attitude
        self.body = body
        self.moments = moments
        self.stats = stats
        self._dense = dense
        self._scale = scale
        self._origin = origin  # the run's time origin, t[0]: dense output works in scaled times from it
        self._signs = signs
        self.t_events = self.L_events = self.omega_events = self.attitude_events = None
        if events is not None:
            t_ev, L_ev, T_ev = events
            S = signs
            self.t_events = t_ev
            self.L_events = L_ev
            self.omega_events = _nested(L_ev, lambda x: x / moments)
            if T_ev is not None:
                self.attitude_events = _nested(T_ev, lambda x: S[:, None] * x * S[None, :])

    def energy(self) -> np.ndarray:
        r"""Kinetic energy :math:`\tfrac12\sum_{i<j} I_{ij}\omega_{ij}^2`, shape batch + (K,)."""
        return 0.5 * np.sum(self.L * self.omega, axis=-1)

    def sol(self, t: Any, what: str = "L") -> np.ndarray:
        r"""Dense output: the solution at any times ``t`` within the run, of the method's accuracy.

        Parameters
        ----------
        t : float or array_like (M,)
            times between ``self.t[0]`` and ``self.t[-1]``.
        what : {"L", "omega", "attitude"}
            the quantity (``"attitude"`` only when the run integrated it).

        Returns
        -------
        ndarray batch + (n,) / batch + (N, N) for a scalar ``t``, batch + (M, ...) for an array.

        Notes
        -----
        Fixed-step methods re-integrate from the stored output state before ``t``: the
        run's own steps up to the last step point, then one step of the method of the
        remaining length (continuous in ``t``, equal to the run at its step points).
        Cost: at most the steps of one output interval per interval queried, plus one
        step per time. scipy methods use their interpolants (``dense_output=True``; the
        first call re-runs the integration to build them).
        """
        what = _validate.choice("what", what, ("L", "omega", "attitude"))
        if what == "attitude" and self.attitude is None:
            raise ValueError("what='attitude' needs a run with attitude=True (or an initial attitude)")
        tq = _validate.finite_array("t", t, ndim=(0, 1))  # (text and booleans were read as times)
        batch = self.omega.shape[:-2]
        width = self.omega.shape[-1] if what != "attitude" else self.attitude.shape[-1] ** 2
        _pricing.check("closed_form_output", n_times=int(np.prod(batch, dtype=np.int64)) * tq.size, width=width)
        if tq.size == 0:  # no time: nothing to integrate or interpolate, the same empty answer for every method
            N = self.attitude.shape[-1] if what == "attitude" else None
            return np.empty(batch + ((0, N, N) if what == "attitude" else (0, self.omega.shape[-1])))
        L, T = self._dense((np.atleast_1d(tq) - self._origin) * self._scale)
        if what == "attitude":
            S = self._signs
            out = (S[:, None] * T * S[None, :]).reshape(batch + (tq.size,) + T.shape[-2:])
            return out[..., 0, :, :] if tq.ndim == 0 else out
        out = (L * self._scale).reshape(batch + (tq.size, L.shape[-1]))
        if what == "omega":
            out = out / self.moments
        return out[..., 0, :] if tq.ndim == 0 else out

    #: what ``==`` compares (not the dense output, a function of these; not the stats that follow the machine's
    #: speed, :data:`_TIMED`)
    _COMPARED = ("t", "omega", "L", "attitude", "body", "moments", "t_events", "L_events", "omega_events",
                 "attitude_events", "_origin", "_scale")

    def __eq__(self, other: object) -> bool:
        """The same run's results: equal outputs, events, body, moments and stats (but the wall time and the number
        of compiled calls, which follow the machine's speed), as a pickled copy is."""
        if not isinstance(other, Trajectory):
            return NotImplemented
        stats = [{k: v for k, v in x.stats.items() if k not in _TIMED} for x in (self, other)]
        return values_equal(*stats) and all(values_equal(getattr(self, k), getattr(other, k))
                                            for k in self._COMPARED)

    __hash__ = None  # (its arrays are mutable)

    def __repr__(self) -> str:
        return (f"Trajectory(method={self.stats.get('method')!r}, batch={self.omega.shape[:-2]}, "
                f"len(t)={self.t.size}, n_planes={self.omega.shape[-1]}, attitude={self.attitude is not None})")


#: stats that follow the machine's speed, not the run: its wall time and how many compiled calls (chunks, sized from
#: measured times) it took
_TIMED = frozenset({"wall_time", "chunks"})


def _nested(events: list, f: Callable) -> list:
    """``f`` on every array of an event list (one array per event function, or a list of member arrays)."""
    return [[f(x) for x in e] if isinstance(e, list) else f(e) for e in events]
