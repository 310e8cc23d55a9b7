r"""Scenes: compute only the observables that are asked for, with the least work.

A :class:`Scene` is a request: a body, one initial angular velocity, a time grid
and a set of observables among

* ``"omega"``: angular velocity components (optionally only some ``planes``);
* ``"L"``: body-frame angular momentum :math:`L^{ij} = I_{ij}\omega_{ij}` (same planes);
* ``"energy"``: kinetic energy :math:`\tfrac12\sum I_{ij}\omega_{ij}^2`;
* ``"casimirs"``: coefficients of the characteristic polynomial of ``L`` (eq. 38);
* ``"attitude"``: :math:`T(t)` (eq. 19, space to body, the body's matrix convention);
* ``"projection"``: space-frame positions of body points,
  :math:`x_\text{space} = T^{\mathsf T} x_\text{body}`, restricted to the chosen
  ``axes`` (e.g. ``(1, 2, 3)`` for a 3D picture).

:func:`evaluate_scene` (or :meth:`Scene.evaluate`) picks the cheapest exact route and
reports it in :attr:`SceneResult.path`:

1. **Invariants.** Energy and Casimirs are conserved by the torque-free flow, so
   they are evaluated once at ``t[0]`` (``"invariants"`` when nothing else is asked).
2. **Locked subspace.** If :math:`\omega_0` vanishes on every plane touching a set
   of axes ``Z``, the subspace stays invariant (:meth:`RigidBody.lock`): only the
   reduced body on the remaining axes is solved, and the attitude acts only on
   those axes (:math:`T(t) = (U(t)\oplus 1_Z)\,T_0`). Reported as
   ``"reduced:axes(...)"``.
3. **Closed forms** (:mod:`hyperrotor.classical.closed_form`): equal moments
   and one distinguished axis ("quartet", any N), both with the attitude
   (:math:`T = e^{\Theta W_r t} e^{(W_0 - \Theta W_r)t} T_0`,
   :func:`~hyperrotor.classical.quartet.quartet_attitude`), and 3D
   Euler-Poinsot (angular velocity only; the attitude is then integrated); a
   reduced body with two axes is a single steady rotation. Reported as
   ``"closed-form:<kind>"``.
4. Otherwise :func:`hyperrotor.simulate` on the (reduced) body, with the attitude
   only if ``"attitude"`` or ``"projection"`` is asked (``"integrate"``).

Only the requested planes and projection axes are assembled. ``minimal=False``
forces the full computation (full body, attitude always integrated, every
observable computed from the trajectory) for comparison and benchmarks
(``benchmarks/scenes.py``).
"""
from __future__ import annotations

import dataclasses
import os
import time
from dataclasses import KW_ONLY, dataclass, field
from typing import Any, Sequence

import numpy as np

from .. import _pricing, _validate as _v
from .._equality import fields_equal
from .._options import options, register
from .._validate import axis_signs
from ..conventions import dimension_from_count, plane_index, planes
from . import closed_form as _cf
from . import quartet as _quartet
from .body_points import body_edges

__all__ = [
    "SCENE_OBSERVABLES",
    "Scene",
    "SceneResult",
    "evaluate_scene",
    "locked_axes",
]

register(
    "scene_rtol", 1e-10,
    "Scene / evaluate_scene: rtol of hyperrotor.simulate when a scene has to be integrated (no closed form). "
    "Tighter than simulate's own default (1e-9) because a scene's attitude and projected points inherit the "
    "error of omega over the whole run, and a picture or a comparison with the minimal=False route should "
    "not show integrator drift; the cost over 1e-9 is ~30% with the order-8 splitting.",
    check=_v.tolerance,
)

#: The observable names a :class:`Scene` accepts.
SCENE_OBSERVABLES = ("omega", "L", "energy", "casimirs", "attitude", "projection")


# ----------------------------------------------------------------------------
# helpers
# ----------------------------------------------------------------------------
def _as_body(body: Any):
    from .rigid_body import RigidBody

    if isinstance(body, RigidBody):
        return body
    return RigidBody(body.inertia if hasattr(body, "inertia") else body)


def locked_axes(omega0: Any, N: int | None = None) -> tuple[int, ...]:
    """Axes ``k`` (1-based) such that ``omega0`` is exactly zero on every plane containing ``k``.

    Locking them (:meth:`RigidBody.lock`) gives an invariant subsystem.
    """
    # an index map: NaN/inf are legitimate (not zero, so not locked); complex values count by != 0
    if omega0 is None or isinstance(omega0, (str, bytes)):
        raise TypeError(f"omega0 must be an array of plane components, got {_v.fmt(omega0)}")
    _v.numeric_input("omega0", omega0)  # booleans, dates, masked arrays (np.asarray drops a mask)
    w = _v.as_array("omega0", omega0, what="numeric array of plane components")
    if w.dtype.kind not in "biufc":
        raise TypeError(f"omega0 must be a numeric array of plane components, got {_v.fmt(omega0)}")
    if w.ndim == 0:
        raise ValueError(f"omega0 must be an array of plane components (shape (n,) or batch + (n,)), got the scalar {_v.fmt(omega0)}")
    N = dimension_from_count(w.shape[-1]) if N is None else _v.dimension(N)
    if w.shape[-1] != N * (N - 1) // 2:
        raise ValueError(f"omega0 must have {N * (N - 1) // 2} plane components for N = {N}, got shape {w.shape}")
    nz = w != 0.0
    return tuple(k for k in range(1, N + 1) if not any(nz[..., q].any() for q, p in enumerate(planes(N)) if k in p))


# ----------------------------------------------------------------------------
# scene and result
# ----------------------------------------------------------------------------
@dataclass
class SceneResult:
    r"""Observables of a :class:`Scene` (``None`` where not requested).

    Attributes
    ----------
    t : ndarray (K,)
    planes : tuple of plane labels of the ``omega`` / ``L`` columns
    omega, L : ndarray (K, len(planes)) or None
    energy : ndarray (K,) or None
    casimirs : ndarray (K, N // 2) or None
    attitude : ndarray (K, N, N) or None
    projection : ndarray (K, n_points, len(axes)) or None
    path : str
        The route taken, e.g. ``"closed-form:quartet"``,
        ``"reduced:axes(1,2,3)+closed-form:euler-poinsot"``, ``"integrate"``,
        ``"invariants"`` or ``"full"``.
    stats : dict
        ``wall_time`` (s) and, when integrated, the :class:`Trajectory` stats.
    """

    __eq__ = fields_equal  # (field by field: the generated == refuses array fields)
    __hash__ = None

    t: np.ndarray
    planes: tuple
    omega: np.ndarray | None = None
    L: np.ndarray | None = None
    energy: np.ndarray | None = None
    casimirs: np.ndarray | None = None
    attitude: np.ndarray | None = None
    projection: np.ndarray | None = None
    path: str = ""
    stats: dict = field(default_factory=dict)


@dataclass
class Scene:
    r"""A request for observables of a free rigid body on a time grid.

    Parameters
    ----------
    body : RigidBody, Inertia or array_like (n_planes,)
        Plain moments or an ``Inertia`` mean ``RigidBody(..., convention="paper")``.
    omega0 : array_like (n_planes,)
        Initial angular velocity at ``t[0]`` (one state; ensembles: use
        :func:`hyperrotor.simulate`).
    t : array_like (K,)
        Strictly increasing output times.
    observables : sequence of str
        Any of :data:`SCENE_OBSERVABLES`.
    planes : sequence of (i, j), optional
        Columns of ``omega`` / ``L`` (default: all planes, paper order).
    points : array_like (P, N), optional
        Body-frame points for ``"projection"`` (e.g. :func:`hypercube_vertices`).
    axes : sequence of int
        Space axes (1-based) kept by ``"projection"`` (default ``(1, 2, 3)``).
    attitude0 : array_like (N, N), optional
        Initial attitude (orthogonal, body convention); default the identity.
    method, rtol : passed to :func:`hyperrotor.simulate` when integration is needed
        (default ``"auto"`` and ``hr.options["scene_rtol"]``, 1e-10).
    progress : bool or None
        progress bar of that integration (passed to :func:`hyperrotor.simulate`; ``None``:
        only on a terminal, for runs longer than about a second).
    """

    body: Any
    omega0: Any
    t: Any
    _: KW_ONLY
    observables: Sequence[str] = ("omega",)
    planes: Sequence | None = None
    points: Any = None
    axes: Sequence[int] = (1, 2, 3)
    attitude0: Any = None
    method: str = "auto"
    rtol: float | None = None
    progress: bool | None = None

    __eq__ = fields_equal  # (field by field: body, omega0, t, points may be arrays)
    __hash__ = None

    def __post_init__(self):
        # refuse a bad body, omega0 or t where it is given, not later in evaluate()
        _check_inputs(self.body, self.omega0, self.t)
        _check_run_options(self)
        _v.flag("progress", self.progress, allow_none=True)

    def evaluate(self, *, minimal: bool = True) -> SceneResult:
        """Compute the scene; see :func:`evaluate_scene`."""
        return evaluate_scene(self, minimal=minimal)

    @property
    def rigid_body(self):
        """The :class:`RigidBody` of ``body`` (plain moments and an ``Inertia`` in the paper convention)."""
        return _as_body(self.body)

    def to_plotly(self, *, edges: Any = "auto", title: str | None = None, result: SceneResult | None = None):
        """The motion as an interactive :class:`plotly.graph_objects.Figure` (inline in notebooks).

        Rotatable, zoomable 3D view of ``points`` carried to space and kept on the first three
        ``axes`` (a fourth colours the points), one frame per time of ``t``, Play / Pause and a
        time slider, and beside it the time, the energy and the Casimirs along the motion with
        their drift (:func:`hyperrotor.classical.scene_html.projection_figure`).

        Parameters
        ----------
        edges : "auto", "cube", "simplex", "points" or sequence of (a, b)
            Lines between body points (:func:`body_edges`); ``"auto"``: a hypercube's edges for
            ``2**N`` points, all pairs for ``N + 1`` (a simplex), none otherwise.
        title : str, optional
            Default: the dimension, the points, the drawn axes and the route of the computation.
        result : SceneResult, optional
            This scene evaluated with ``observables=("projection", "omega")`` (no recomputation).

        Raises
        ------
        hyperrotor.BudgetError
            A page over ``hr.options["scene_html_max_bytes"]``, priced before any work.
        """
        return _interactive(self, edges, title, result)

    def to_html(self, path, *, edges: Any = "auto", title: str | None = None, result: SceneResult | None = None,
                auto_play: bool = True) -> str:
        """Write :meth:`to_plotly` as one self-contained HTML page (plotly.js inside, no network).

        The page starts playing when opened (``auto_play``); it is written to ``path + ".part"``
        and renamed when complete (:func:`hyperrotor.classical.scene_html.write_html`).
        Returns the path.
        """
        from .scene_html import write_html

        _v.flag("auto_play", auto_play)
        if not isinstance(path, (str, os.PathLike)):
            raise TypeError(f"path must be a file name (str or os.PathLike), got {_v.fmt(path)}")
        return write_html(self.to_plotly(edges=edges, title=title, result=result), path, auto_play=auto_play)


def _interactive(scene: Scene, edges: Any, title: str | None, result: SceneResult | None):
    """:meth:`Scene.to_plotly`: checks, the page priced, the scene evaluated, the figure built."""
    from .scene_html import projection_figure

    if scene.points is None:
        raise ValueError("an interactive scene needs body points (points=..., e.g. hypercube_vertices(N))")
    body = scene.rigid_body
    points = _v.finite_array("points", scene.points, ndim=2)
    P, N = points.shape
    if N != body.N:
        raise ValueError(f"points must have shape (P, {body.N}), got {points.shape}")
    axes = tuple(scene.axes)
    if len(axes) not in (3, 4):
        raise ValueError(f"an interactive scene draws 3 space axes (a 4th colours the points), got axes={axes!r}")
    # count the edges before listing them: a cube has N 2^(N-1), a simplex (N+1) N / 2
    if isinstance(edges, str):
        kind = _v.choice("edges", edges, ("auto", "cube", "simplex", "points"))
        if kind == "auto":
            kind = "simplex" if P == N + 1 else ("cube" if P == 2**N else "points")
        n_edges = {"cube": N * P // 2, "simplex": P * (P - 1) // 2, "points": 0}[kind]
    else:
        n_edges = len(edges)
    _pricing.check("Scene.to_html", n_times=int(np.size(scene.t)), n_points=P, n_edges=n_edges,
                   colour=len(axes) == 4)
    edge_list = body_edges(points, kind) if isinstance(edges, str) else edges
    if result is None:
        result = evaluate_scene(dataclasses.replace(scene, observables=("projection", "omega"), planes=None))
    if result.projection is None or result.omega is None or result.omega.shape[-1] != len(body.planes):
        raise ValueError("result must come from this scene with observables including 'projection' and "
                         "'omega' (all planes)")
    if title is None:
        title = (f"{N}-D body, {P} points, space axes {', '.join(map(str, axes[:3]))} drawn"
                 + (f", colour = x{axes[3]}" if len(axes) == 4 else "") + f" (route {result.path})")
    return projection_figure(result.t, result.projection, edges=edge_list, axes=axes,
                             energy=body.energy(result.omega), casimirs=body.casimirs(result.omega), title=title)


def _check_inputs(body: Any, omega0: Any, t: Any):
    """``(moments, N, omega0, t)`` checked with :mod:`hyperrotor._validate` (messages name the argument).

    No :class:`RigidBody` is built here (for plain moments that takes ~1 s at N = 300): the body is
    made once, in :func:`evaluate_scene`, after the run has been priced.
    """
    try:
        moments = _v.moments(body, name="body")
        N = _v.dimension_from_count(moments.size, name="body", what="plane moments")
    except (TypeError, ValueError) as exc:
        raise type(exc)(
            f"body must be a RigidBody, an Inertia or plane moments, got {_v.fmt(body)} "
            f"of type {type(body).__name__}: {exc}"
        ) from None
    _v.dimension(N)  # the budget options['max_dimension'], as a RigidBody would check it
    n = moments.size
    w0 = _v.finite_array("omega0", omega0, ndim=1)
    if w0.shape != (n,):
        raise ValueError(f"omega0 must have shape ({n},) for N = {N}, got shape {w0.shape}")
    t_ = _v.time_grid(t, name="t", allow_decreasing=False)
    return moments, N, w0, t_


def _rtol(scene: Scene) -> float:
    return options["scene_rtol"] if scene.rtol is None else _v.tolerance("rtol", scene.rtol)


def _check_run_options(scene: Scene) -> None:
    """``rtol`` and ``method``, checked on every route (closed forms and invariants never reach simulate)."""
    from .simulate import SIMULATION_METHODS
    from .solvers import Solver

    _rtol(scene)
    m = scene.method
    if not (isinstance(m, Solver) or (isinstance(m, type) and issubclass(m, Solver))):
        _v.choice("method", m, SIMULATION_METHODS)


def _validate(scene: Scene):
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a hyperrotor.Scene, got {_v.fmt(scene)} of type {type(scene).__name__}")
    moments, N, w0, t = _check_inputs(scene.body, scene.omega0, scene.t)
    _check_run_options(scene)
    obs = ((scene.observables,) if isinstance(scene.observables, str)
           else _v.sequence("observables", scene.observables, f"names among {', '.join(SCENE_OBSERVABLES)}"))
    bad = [o for o in obs if not isinstance(o, str) or o not in SCENE_OBSERVABLES]
    if bad or not obs:
        raise ValueError((f"unknown observable(s) {bad!r}" if bad else "observables is empty")
                         + f"; allowed: {', '.join(SCENE_OBSERVABLES)}")
    sel_planes = (tuple(planes(N)) if scene.planes is None else tuple(
        _v.plane(p, N) for p in _v.sequence("planes", scene.planes, "planes (i, j), e.g. [(1, 2), (3, 4)]")))
    cols = np.array([plane_index(p, N) for p in sel_planes], dtype=int)
    pts = None
    ax = None
    if "projection" in obs:
        if scene.points is None:
            raise ValueError("observable 'projection' needs body points (points=..., e.g. hypercube_vertices(N))")
        pts = _v.finite_array("points", scene.points)  # (text, booleans, NaN: refused)
        if pts.ndim != 2 or pts.shape[1] != N:
            raise ValueError(f"points must have shape (P, {N}), got {pts.shape}")
        if isinstance(scene.axes, str):
            raise TypeError(f"axes must be a sequence of integer axis labels, got text {_v.fmt(scene.axes)}")
        ax = np.array([_v.integer("axes[k]", a) for a in scene.axes], dtype=int)
        if ax.size == 0 or np.any(ax < 1) or np.any(ax > N):
            raise ValueError(f"projection axes must be in 1..{N}, got {tuple(scene.axes)!r}")
    T0 = None if scene.attitude0 is None else _v.orthogonal_matrix("attitude0", scene.attitude0, N)
    return moments, N, obs, w0, t, sel_planes, cols, pts, ax, T0


def _fill(res: SceneResult, obs, body, omega_full, T, cols, pts, ax, invariants_from, w0):
    """Assemble the requested observables from omega (K, n) (or None) and T (K, N, N) (or None)."""
    I = body.inertia.moments
    if "omega" in obs:
        res.omega = omega_full[:, cols]
    if "L" in obs:
        res.L = omega_full[:, cols] * I[cols]
    K = res.t.size
    if "energy" in obs:
        res.energy = (np.full(K, float(body.energy(w0))) if invariants_from == "initial"
                      else np.asarray(body.energy(omega_full)))
    if "casimirs" in obs:
        res.casimirs = (np.broadcast_to(body.casimirs(w0), (K, body.N // 2)).copy() if invariants_from == "initial"
                        else np.asarray(body.casimirs(omega_full)))
    if "attitude" in obs:
        res.attitude = T
    if "projection" in obs:
        # x_space = T^T x_body, only the rows `ax`: x_space[a] = sum_b T[b, a] x_body[b]
        res.projection = np.einsum("kba,pb->kpa", T[:, :, ax - 1], pts)
    return res


def _route(minimal: bool, need_att: bool, need_omega: bool, moments: np.ndarray, N: int, w0: np.ndarray,
           labels: tuple | None = None) -> tuple:
    """The route of :func:`evaluate_scene` (module docstring), decided from the checked inputs without any work:
    ``(steps, kept axes, kept plane indices, closed form or None)``; ``"+".join(steps)`` is ``SceneResult.path``,
    which names the kept axes by ``labels`` (the body's own: ``RigidBody.axes``, 1..N by default)."""
    if not minimal:
        return ["full"], tuple(range(1, N + 1)), np.arange(w0.size), None
    if not need_att and not need_omega:
        return ["invariants"], tuple(range(1, N + 1)), np.arange(w0.size), None
    Z = locked_axes(w0, N)
    if len(Z) == N:  # at rest
        return ["closed-form:rest"], (), np.arange(0), None
    steps = []
    keep_axes = tuple(k for k in range(1, N + 1) if k not in Z)
    if Z:
        steps.append("reduced:axes(" + ",".join(str(labels[k - 1] if labels else k) for k in keep_axes) + ")")
        kept = np.array([q for q, p in enumerate(planes(N)) if p[0] in keep_axes and p[1] in keep_axes], dtype=int)
    else:
        kept = np.arange(w0.size)
    info = {"kind": "equal"} if len(keep_axes) == 2 else _cf.detect_closed_form(moments[kept])
    if info is not None and (not need_att or info["kind"] in ("equal", "quartet")):
        steps.append("closed-form:" + info["kind"])
    else:
        steps.append("integrate")
        info = None
    return steps, keep_axes, kept, info


def scene_route(scene: Scene, *, minimal: bool = True) -> tuple[str, np.ndarray, np.ndarray]:
    """The route :func:`evaluate_scene` takes for ``scene`` (its ``SceneResult.path``), without any work, and the
    body it integrates when the route contains ``"integrate"``: ``(path, moments, omega0)`` of the (reduced) body
    in the standard convention (empty arrays otherwise). For pricing a scene before it runs (the command line)."""
    minimal = _v.flag("minimal", minimal)
    moments, N, obs, w0, *_ = _validate(scene)
    need_att = "attitude" in obs or "projection" in obs
    steps, _, kept, info = _route(minimal, need_att, "omega" in obs or "L" in obs, moments, N, w0,
                                  getattr(scene.body, "axes", None))
    integrated = steps[-1] in ("integrate", "full")  # ("full": the whole body, kept is every plane)
    return "+".join(steps), (moments[kept] if integrated else moments[:0]), (w0[kept] if integrated else w0[:0])


def evaluate_scene(scene: Scene, *, minimal: bool = True) -> SceneResult:
    """Evaluate a :class:`Scene` with the least work (``minimal=True``) or fully (``minimal=False``).

    See the module docstring for the routes. The minimal route is exact where it
    uses invariants, reductions and closed forms, and integrates with
    ``scene.method`` / ``scene.rtol`` otherwise; both routes agree to the
    integration accuracy.
    """
    from .simulate import simulate
    from .rigid_body import RigidBody

    wall = time.perf_counter()
    minimal = _v.flag("minimal", minimal)
    moments, N, obs, w0, t, sel_planes, cols, pts, ax, T0 = _validate(scene)
    res = SceneResult(t=t, planes=sel_planes)
    need_att = "attitude" in obs or "projection" in obs
    need_omega = "omega" in obs or "L" in obs
    # what the route returns (and the omega it computes on the way), priced before any work
    width = (("omega" in obs) + ("L" in obs)) * len(cols) + (w0.size if need_omega or need_att else 0) \
        + (N * N if need_att else 0) + (0 if pts is None else pts.shape[0] * ax.size) \
        + ("energy" in obs) + ("casimirs" in obs) * (N // 2)
    _pricing.check("closed_form_output", n_times=t.size, width=width)

    steps, keep_axes, kept, info = _route(minimal, need_att, need_omega, moments, N, w0,
                                          getattr(scene.body, "axes", None))
    if steps == ["full"]:
        _pricing.check("simulate", N=N)  # before the body is built
        body = _as_body(scene.body)
        traj = simulate(body, w0, t, method=scene.method, rtol=_rtol(scene), progress=scene.progress,
                        attitude=True if T0 is None else T0)
        res.path = "full"
        res.stats.update(traj.stats)
        _fill(res, obs, body, traj.omega, traj.attitude, cols, pts, ax, "trajectory", w0)
        res.stats["wall_time"] = time.perf_counter() - wall
        return res

    if steps == ["invariants"]:
        body = _as_body(scene.body)
        res.path = "invariants"
        _fill(res, obs, body, None, None, cols, pts, ax, "initial", w0)
        res.stats["wall_time"] = time.perf_counter() - wall
        return res

    if steps == ["closed-form:rest"]:
        body = _as_body(scene.body)
        omega = np.zeros((t.size, w0.size))
        T = np.broadcast_to(np.eye(N) if T0 is None else T0, (t.size, N, N)).copy() if need_att else None
        res.path = "closed-form:rest"
        _fill(res, obs, body, omega, T, cols, pts, ax, "initial", w0)
        res.stats["wall_time"] = time.perf_counter() - wall
        return res
    I_red = moments[kept]
    w_red = w0[kept]
    tau = t - t[0]
    # solve the (reduced) body in the plain ("standard") convention, then embed and convert
    U = None
    if info is not None:
        if info["kind"] == "equal":
            om_red = np.broadcast_to(w_red, (t.size, w_red.size)).copy()
            if need_att:
                from ..conventions import to_matrix

                U = _quartet.expm_antisym(to_matrix(w_red, convention="standard").astype(float), tau)
        else:
            om_red, _ = _cf.closed_form_solution(I_red, w_red, tau)
            if need_att:  # T = exp(Theta W_r t) exp((W0 - Theta W_r) t), see quartet_attitude
                U = _quartet.quartet_attitude_standard(info["theta"], w_red, tau, info["axis"])
    else:
        _pricing.check("simulate", N=len(keep_axes))  # the run's price, before any body is built
        red_body = RigidBody(I_red, convention="standard")
        traj = simulate(red_body, w_red, t, method=scene.method, rtol=_rtol(scene), attitude=need_att,
                        progress=scene.progress)
        om_red = traj.omega
        U = traj.attitude
        res.stats.update(traj.stats)
    body = _as_body(scene.body)
    conv = body.convention
    omega = np.zeros((t.size, w0.size))
    omega[:, kept] = om_red
    T = None
    if need_att:
        idx = np.array(keep_axes) - 1
        T_std = np.broadcast_to(np.eye(N), (t.size, N, N)).copy()
        T_std[:, idx[:, None], idx[None, :]] = U
        S = axis_signs(N, conv, body.axes)
        if T0 is not None:
            T_std = T_std @ (S[:, None] * T0 * S[None, :])
        T = S[None, :, None] * T_std * S[None, None, :]
    res.path = "+".join(steps)
    _fill(res, obs, body, omega, T, cols, pts, ax, "initial", w0)
    res.stats["wall_time"] = time.perf_counter() - wall
    return res
