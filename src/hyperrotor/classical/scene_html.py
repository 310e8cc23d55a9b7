r"""Interactive scenes: an N-D body projected to 3D, as a plotly figure or a self-contained HTML page.

:func:`scene_figure` (also :meth:`Scene.to_plotly`) turns a :class:`~hyperrotor.classical.scenes.Scene`
into a :class:`plotly.graph_objects.Figure`: the body's points and edges carried to space,
:math:`x_\text{space}(t) = T(t)^{\mathsf T} x_\text{body}` (see :mod:`hyperrotor.conventions`,
"Attitude"), restricted to the scene's first three ``axes`` (a fourth axis colours the points),
one plotly *frame* per output time. The 3D view is rotatable and zoomable; Play / Pause buttons
and a time slider run the motion; a panel beside the view shows the time and the invariants of the
torque-free flow, the kinetic energy :math:`E = \tfrac12\sum I_{ij}\omega_{ij}^2` and the Casimirs
:math:`c_2, c_4, \dots` (coefficients of :math:`\det(\lambda - L)`, eq. 38), each with its drift
from :math:`t_0` (they are evaluated from :math:`\omega(t)` at every frame, so the panel shows
conservation, not a copy of the initial values). In a notebook the figure renders inline.

:func:`write_scene_html` (also :meth:`Scene.to_html`) writes that figure as one HTML file with the
whole plotly.js library inside (``include_plotlyjs=True``): the page needs no network, and starts
playing when it is opened.

Size: a page holds every frame's coordinates, about :func:`scene_html_bytes` bytes. The page is
priced from the number of times, points and edges *before* anything is computed, and refused over
``hr.options["scene_html_max_bytes"]`` (as the GIF path is priced from frames and vertices).

plotly is the ``viz`` extra (``pip install 'hyperrotor[viz]'``), imported only here.
"""
from __future__ import annotations

import dataclasses
import html
import os
from typing import Any, Sequence

import numpy as np

from .. import _pricing
from .. import _validate as _v
from .._options import register

__all__ = ["scene_figure", "write_scene_html", "scene_html_bytes"]

register(
    "scene_html_max_bytes", 256 * 2**20,
    "Budget of Scene.to_html / Scene.to_plotly (and hyperrotor scene --output FILE.html): largest page, in "
    "bytes, estimated before any work from the number of times, body points and edges (about 9 bytes "
    "per stored coordinate, plus plotly.js, ~4.7 MB). 256 MiB by default: a browser holds a page of "
    "that size in about 1-2 GB of memory and becomes sluggish beyond it (e.g. an 8-cube, 1024 edges, "
    "over 1000 times is ~90 MB). Use fewer times (t), a smaller body or raise the option.",
)

#: Bytes of one stored coordinate in the page (a rounded float in JSON, with its separator).
_BYTES_PER_NUMBER = 9
#: Bytes of plotly.js inside the page (plotly 5.24-7.1: 3.6-4.7 MB) and of the page around the data.
_PLOTLYJS_BYTES = 4.8e6
_FRAME_OVERHEAD = 600


def scene_html_bytes(n_times: int, n_points: int, n_edges: int, *, colour: bool = False,
                     plotlyjs: bool = True) -> float:
    r"""Estimated size in bytes of a scene page (or of the figure's JSON when ``plotlyjs=False``).

    Every frame stores the points (3 coordinates, plus one colour value when a fourth
    axis colours them) and the edges as line segments (2 end points and a gap, 3
    coordinates each):

    .. math:: K\,\bigl((3 + c) P + 9 E\bigr)\cdot 9 + 600 K + 4.8\,\text{MB}.

    Floats so that a huge request (``2**40`` points) stays finite.
    """
    K, P, E = (float(_v.integer(name, v, minimum=0)) for name, v in
               (("n_times", n_times), ("n_points", n_points), ("n_edges", n_edges)))
    per_frame = ((3 + (1 if colour else 0)) * P + 9 * E) * _BYTES_PER_NUMBER + _FRAME_OVERHEAD
    return K * per_frame + (_PLOTLYJS_BYTES if plotlyjs else 0.0)


@_pricing.model("Scene.to_html", "fewer times (t) or a smaller body")
def _page_cost(n_times: int, n_points: int, n_edges: int, colour: bool = False) -> tuple:
    """Cost model of a scene page (also :meth:`Scene.to_plotly`): its bytes, see :func:`scene_html_bytes`."""
    what = f"a page of {n_times} times x ({n_points} points, {n_edges} edges)"
    return (_pricing.Cost(what, scene_html_bytes(n_times, n_points, n_edges, colour=colour),
                          "scene_html_max_bytes", "bytes"),)


def _plotly():
    try:
        import plotly.graph_objects as go
    except ImportError:  # pragma: no cover - depends on the environment
        raise ImportError("interactive scenes need plotly: pip install 'hyperrotor[viz]'") from None
    return go


def _edges_for(points: np.ndarray, edges: Any) -> list[tuple[int, int]]:
    from .scenes import body_edges

    if isinstance(edges, str):
        return body_edges(points, edges)
    P = len(points)
    e = np.asarray(edges, dtype=int).reshape(-1, 2) if len(edges) else np.zeros((0, 2), dtype=int)
    if e.size and (e.min() < 0 or e.max() >= P):
        raise ValueError(f"edges must be 'auto', 'cube', 'simplex', 'points' or pairs of point indices in "
                         f"0..{P - 1}, got {_v.fmt(edges)}")
    return [tuple(map(int, p)) for p in e]


def _price(scene, edges: Any):
    """Body, points and edges; the page is priced and refused over the budget before any motion is computed."""
    if scene.points is None:
        raise ValueError("an interactive scene needs body points (points=..., e.g. hypercube_vertices(N))")
    body = scene.rigid_body
    points = _v.finite_array("points", scene.points, ndim=2)
    P, N = points.shape
    if N != body.N:
        raise ValueError(f"points must have shape (P, {body.N}), got {points.shape}")
    n_axes = len(tuple(scene.axes))
    if n_axes not in (3, 4):
        raise ValueError(f"an interactive scene draws 3 space axes (a 4th colours the points), got "
                         f"axes={tuple(scene.axes)!r}")
    # count before listing: a cube has N 2^(N-1) edges, a simplex (N+1) N / 2
    if isinstance(edges, str):
        kind = _v.choice("edges", edges, ("auto", "cube", "simplex", "points"))
        if kind == "auto":
            kind = "simplex" if P == N + 1 else ("cube" if P == 2**N else "points")
        n_edges = {"cube": N * P // 2, "simplex": P * (P - 1) // 2, "points": 0}[kind]
        edges = kind
    else:
        n_edges = len(edges)
    _pricing.check("Scene.to_html", n_times=int(np.size(scene.t)), n_points=P, n_edges=n_edges, colour=n_axes == 4)
    return body, points, _edges_for(points, edges)


def _segments(frame: np.ndarray, e: np.ndarray) -> np.ndarray:
    """Edge end points with a NaN gap after each edge (one plotly line trace), shape ``(3 E, 3)``."""
    seg = np.full((len(e), 3, 3), np.nan)
    seg[:, 0] = frame[e[:, 0]]
    seg[:, 1] = frame[e[:, 1]]
    return seg.reshape(-1, 3)


def _coords(a: np.ndarray, digits: int) -> list:
    """Rounded coordinates for the page (display only; keeps the page small), NaN -> None (a gap)."""
    r = np.round(a, digits)
    return [None if np.isnan(x) else float(x) for x in r]


def _panel(t: float, energy: float, e0: float, cas: np.ndarray, cas0: np.ndarray) -> str:
    rows = [f"<b>t = {t:.4g}</b>", "", "<b>invariants</b>",
            f"E = {energy:.10g}", f"  drift {abs(energy - e0) / max(abs(e0), 1e-300):.1e}"]
    for k, (c, c0) in enumerate(zip(cas, cas0), start=1):
        rows += [f"c<sub>{2 * k}</sub> = {c:.10g}", f"  drift {abs(c - c0) / max(abs(c0), 1e-300):.1e}"]
    rows += ["", "drift: |X(t) - X(t<sub>0</sub>)| / |X(t<sub>0</sub>)|"]
    return "<br>".join(html.escape(r, quote=False).replace("&lt;", "<").replace("&gt;", ">") for r in rows)


def scene_figure(scene, *, edges: Any = "auto", title: str | None = None, result=None):
    r"""A plotly figure of the scene's motion: rotatable 3D view, Play / Pause, time slider, invariants.

    Parameters
    ----------
    scene : Scene
        Its ``points`` (body frame, ``(P, N)``), ``axes`` (3 drawn space axes, an optional 4th
        colouring the points), ``t`` (one frame per time), body and ``omega0``. Its
        ``observables`` are ignored: the figure asks for ``("projection", "omega")``.
    edges : "auto", "cube", "simplex", "points" or sequence of (a, b)
        Lines between body points: ``"auto"`` draws a hypercube's edges when there are
        ``2**N`` points, all pairs when there are ``N + 1`` (a simplex), none otherwise
        (see :func:`~hyperrotor.classical.scenes.body_edges`); or explicit index pairs.
    title : str, optional
        Default: the body's dimension, the drawn axes and the route of the computation.
    result : SceneResult, optional
        A result of ``evaluate_scene`` with ``projection`` and ``omega`` for this scene (no
        recomputation).

    Returns
    -------
    plotly.graph_objects.Figure
        One frame per time; the axes ranges are fixed (the body does not jump in scale).

    Raises
    ------
    hyperrotor.BudgetError
        Over the ``scene_html_max_bytes`` budget (priced before the motion is computed).
    ValueError
        Without points, or with other than 3 or 4 axes.
    """
    from .scenes import Scene, evaluate_scene

    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a hyperrotor.Scene, got {_v.fmt(scene)} of type {type(scene).__name__}")
    go = _plotly()
    body, points, edge_list = _price(scene, edges)
    axes = tuple(int(a) for a in scene.axes)
    if result is None:
        result = evaluate_scene(dataclasses.replace(scene, observables=("projection", "omega"), planes=None))
    if result.projection is None or result.omega is None or result.omega.shape[-1] != len(body.planes):
        raise ValueError("result must come from this scene with observables including 'projection' and "
                         "'omega' (all planes)")
    t = result.t
    proj = result.projection
    xyz = proj[..., :3]
    colour = proj[..., 3] if proj.shape[-1] == 4 else None
    energy = np.asarray(body.energy(result.omega))
    cas = np.asarray(body.casimirs(result.omega))
    lim = float(np.max(np.abs(xyz))) * 1.05 or 1.0
    digits = max(0, 4 - int(np.floor(np.log10(lim))))  # ~5 significant digits at the scale of the body
    e = np.asarray(edge_list, dtype=int).reshape(-1, 2)
    ctop = float(np.max(np.abs(colour))) or 1.0 if colour is not None else 1.0
    small = len(points) <= 64

    def traces(k: int):
        seg = _segments(xyz[k], e)
        marker = dict(size=5 if small else 2.5, color="#1f77b4")
        if colour is not None:
            marker.update(color=_coords(colour[k], digits), colorscale="RdBu_r", cmin=-ctop, cmax=ctop,
                          colorbar=dict(title=dict(text=f"x{axes[3]}", side="right"), x=0.66, len=0.6, thickness=14))
        return [go.Scatter3d(x=_coords(seg[:, 0], digits), y=_coords(seg[:, 1], digits), z=_coords(seg[:, 2], digits),
                             mode="lines", line=dict(color="rgba(80,80,80,0.7)", width=2 if len(e) <= 500 else 1),
                             hoverinfo="skip", name="edges", showlegend=False),
                go.Scatter3d(x=_coords(xyz[k, :, 0], digits), y=_coords(xyz[k, :, 1], digits),
                             z=_coords(xyz[k, :, 2], digits), mode="markers", marker=marker, name="points",
                             showlegend=False,
                             hovertemplate="x%s = %%{x}<br>x%s = %%{y}<br>x%s = %%{z}<extra></extra>" % axes[:3])]

    def panel(k: int):
        return dict(text=_panel(float(t[k]), float(energy[k]), float(energy[0]), cas[k], cas[0]),
                    x=0.74, y=0.95, xref="paper", yref="paper", xanchor="left", yanchor="top", showarrow=False,
                    align="left", font=dict(family="monospace", size=13))

    names = [str(k) for k in range(t.size)]  # unique frame names; the slider shows the times
    frames = [go.Frame(data=traces(k), traces=[0, 1], name=names[k], layout=dict(annotations=[panel(k)]))
              for k in range(t.size)]
    if title is None:
        title = (f"{points.shape[1]}-D body, {len(points)} points, space axes {', '.join(map(str, axes[:3]))} drawn"
                 + (f", colour = x{axes[3]}" if colour is not None else "") + f" (route {result.path})")
    anim = dict(mode="immediate", frame=dict(duration=60, redraw=True), transition=dict(duration=0))
    rng = [-lim, lim]
    fig = go.Figure(
        data=traces(0), frames=frames,
        layout=go.Layout(
            title=dict(text=title, x=0.02, font=dict(size=15)),
            annotations=[panel(0)],
            scene=dict(domain=dict(x=[0.0, 0.66], y=[0.0, 1.0]), aspectmode="cube",
                       xaxis=dict(title=dict(text=f"x{axes[0]}"), range=rng, autorange=False),
                       yaxis=dict(title=dict(text=f"x{axes[1]}"), range=rng, autorange=False),
                       zaxis=dict(title=dict(text=f"x{axes[2]}"), range=rng, autorange=False)),
            font=dict(size=14), margin=dict(l=10, r=10, t=50, b=70), height=640, autosize=True,
            updatemenus=[dict(type="buttons", direction="left", x=0.0, y=0.0, xanchor="left", yanchor="top",
                              pad=dict(t=30, r=10), showactive=False,
                              buttons=[dict(label="Play", method="animate",
                                            args=[None, dict(anim, fromcurrent=True)]),
                                       dict(label="Pause", method="animate",
                                            args=[[None], dict(mode="immediate", frame=dict(duration=0, redraw=False),
                                                               transition=dict(duration=0))])])],
            sliders=[dict(active=0, x=0.16, y=0.0, len=0.5, xanchor="left", yanchor="top", pad=dict(t=10, b=0),
                          currentvalue=dict(prefix="t = ", font=dict(size=13)),
                          steps=[dict(label=f"{x:.4g}", method="animate", args=[[n], anim])
                                 for n, x in zip(names, t)])],
        ),
    )
    return fig


#: Autoplay of the page: one frame every 80 ms from a timer (plotly's own player is driven by
#: requestAnimationFrame, which a hidden tab or a headless browser does not run), looping, until
#: the reader presses Play / Pause or moves the slider (then plotly's controls take over).
_AUTOPLAY = """
(function () {
  var gd = document.getElementById('{plot_id}');
  var names = (gd._transitionData && gd._transitionData._frames || []).map(function (f) { return f.name; });
  if (names.length < 2) { return; }
  var k = 0;
  var timer = setInterval(function () {
    k = (k + 1) % names.length;
    // 'immediate' interrupts the previous frame if still drawing: plotly then rejects its promise
    // with no reason; any other rejection is a real error and is rethrown
    Plotly.animate(gd, [names[k]], {mode: 'immediate', frame: {duration: 0, redraw: true},
                                    transition: {duration: 0}})
      .catch(function (e) { if (e !== undefined) { throw e; } });
  }, 80);
  function stop() { clearInterval(timer); }
  gd.on('plotly_buttonclicked', stop);
  gd.on('plotly_sliderstart', stop);
})();
"""


def write_scene_html(scene, path, *, edges: Any = "auto", title: str | None = None, result=None,
                     auto_play: bool = True) -> str:
    """Write the scene as one self-contained HTML page (plotly.js inside, no network); returns the path.

    The figure is :func:`scene_figure` (same ``edges``, ``title``, ``result``); the page
    starts playing when opened (``auto_play``). The file is HTML whatever its name (use
    ``.html``); it is written to ``path + ".part"`` and renamed at the end, so an
    interrupted run leaves no partial page; an existing file at ``path`` is replaced.
    """
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path must be a file name (str or os.PathLike), got {_v.fmt(path)}")
    path = os.fsdecode(path)
    _v.flag("auto_play", auto_play)
    fig = scene_figure(scene, edges=edges, title=title, result=result)
    tmp = path + ".part"
    try:
        fig.write_html(tmp, include_plotlyjs=True, full_html=True, auto_play=False,
                       post_script=_AUTOPLAY if auto_play else None,
                       config=dict(displaylogo=False, responsive=True))
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return path
