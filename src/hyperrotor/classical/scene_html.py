r"""Interactive scenes: a body's points projected to 3D, as a plotly figure or a self-contained HTML page.

:func:`projection_figure` turns a projected motion (times, ``(K, P, 3 or 4)`` space coordinates
of body points, edges, and optionally the energy and Casimirs along the motion) into a
:class:`plotly.graph_objects.Figure`, one plotly *frame* per time. The 3D view is rotatable and
zoomable; Play / Pause buttons and a time slider run the motion; a panel beside the view shows the
time and the invariants of the torque-free flow, the kinetic energy
:math:`E = \tfrac12\sum I_{ij}\omega_{ij}^2` and the Casimirs :math:`c_2, c_4, \dots`
(coefficients of :math:`\det(\lambda - L)`, eq. 38), each with its drift from :math:`t_0` (given
along the motion, so the panel shows conservation, not a copy of the initial values). In a
notebook the figure renders inline. :func:`write_html` writes it as one HTML file with the whole
plotly.js library inside (``include_plotlyjs=True``): the page needs no network, and starts
playing when it is opened.

The usual entry points are :meth:`Scene.to_plotly <hyperrotor.classical.scenes.Scene.to_plotly>`
and :meth:`Scene.to_html <hyperrotor.classical.scenes.Scene.to_html>`, which evaluate the scene
(:math:`x_\text{space}(t) = T(t)^{\mathsf T} x_\text{body}`, see :mod:`hyperrotor.conventions`,
"Attitude") and call these functions; this module knows nothing of scenes (plain data in).

Size: a page holds every frame's coordinates, about :func:`scene_html_bytes` bytes. A scene's page
is priced from the number of times, points and edges *before* anything is computed (cost model
``"Scene.to_html"`` of :mod:`hyperrotor._pricing`), and refused over
``hr.options["scene_html_max_bytes"]`` (as the GIF path is priced from frames and vertices).

plotly is the ``viz`` extra (``pip install 'hyperrotor[viz]'``), imported only when a figure is made.
"""
from __future__ import annotations

import os
from typing import Any, Sequence

import numpy as np

from .. import _pricing
from .. import _validate as _v
from .._options import register

__all__ = ["projection_figure", "write_html", "scene_html_bytes"]

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
    colour, plotlyjs = _v.flag("colour", colour), _v.flag("plotlyjs", plotlyjs)
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


def _panel(t: float, energy, cas, k: int) -> str:
    rows = [f"<b>t = {t:.4g}</b>"]
    if energy is not None or cas is not None:
        rows += ["", "<b>invariants</b>"]
    if energy is not None:
        rows += [f"E = {energy[k]:.10g}", f"  drift {_drift(energy[k], energy[0])}"]
    if cas is not None:
        for j in range(cas.shape[1]):
            rows += [f"c<sub>{2 * (j + 1)}</sub> = {cas[k, j]:.10g}", f"  drift {_drift(cas[k, j], cas[0, j])}"]
        rows += ["", "drift: |X(t) - X(t<sub>0</sub>)| / |X(t<sub>0</sub>)|"]
    return "<br>".join(rows)


def _drift(x: float, x0: float) -> str:
    return f"{abs(x - x0) / max(abs(x0), 1e-300):.1e}"


def projection_figure(t: Any, projection: Any, *, edges: Any = (), axes: Sequence[int] = (1, 2, 3),
                      energy: Any = None, casimirs: Any = None, title: str = ""):
    r"""A plotly figure of a projected motion: rotatable 3D view, Play / Pause, time slider, invariants.

    Plain data in (what :meth:`Scene.to_plotly <hyperrotor.classical.scenes.Scene.to_plotly>`
    passes from the evaluated scene).

    Parameters
    ----------
    t : array_like (K,)
        Times, one plotly frame each.
    projection : array_like (K, P, 3 or 4)
        Space coordinates of the P body points on the drawn axes (a 4th column colours them).
    edges : sequence of (a, b)
        Point pairs joined by a line.
    axes : sequence of int
        The space axes of the columns of ``projection`` (axis titles ``x<k>``).
    energy : array_like (K,), optional
        :math:`E(t)`; ``casimirs`` ``(K, N // 2)`` likewise: shown in the side panel with
        their drift :math:`|X(t) - X(t_0)| / |X(t_0)|`.
    title : str

    Returns
    -------
    plotly.graph_objects.Figure
        One frame per time; the axes ranges are fixed (the body does not jump in scale).
        Coordinates are rounded to ~5 significant digits at the body's scale (display only).
    """
    go = _plotly()
    t = _v.finite_array("t", t, ndim=1)
    proj = _v.finite_array("projection", projection, ndim=3)
    if proj.shape[0] != t.size or proj.shape[2] not in (3, 4):
        raise ValueError(f"projection must have shape ({t.size}, P, 3 or 4), got {proj.shape}")
    axes = tuple(_v.integer("axes", a, minimum=1) for a in axes)
    if len(axes) != proj.shape[2]:
        raise ValueError(f"axes must name the {proj.shape[2]} columns of projection, got {axes!r}")
    e = np.asarray(edges, dtype=int).reshape(-1, 2) if len(edges) else np.zeros((0, 2), dtype=int)
    if e.size and (e.min() < 0 or e.max() >= proj.shape[1]):
        raise ValueError(f"edges must be pairs of point indices in 0..{proj.shape[1] - 1}")
    _pricing.check("Scene.to_html", n_times=t.size, n_points=proj.shape[1], n_edges=len(e), colour=proj.shape[-1] == 4)
    xyz = proj[..., :3]
    colour = proj[..., 3] if proj.shape[-1] == 4 else None
    energy = None if energy is None else _v.finite_array("energy", energy, ndim=1)
    cas = None if casimirs is None else _v.finite_array("casimirs", casimirs, ndim=2)
    lim = float(np.max(np.abs(xyz))) * 1.05 or 1.0
    digits = max(0, 4 - int(np.floor(np.log10(lim))))  # ~5 significant digits at the scale of the body
    ctop = (float(np.max(np.abs(colour))) or 1.0) if colour is not None else 1.0
    small = proj.shape[1] <= 64

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
        return dict(text=_panel(float(t[k]), energy, cas, k),
                    x=0.74, y=0.95, xref="paper", yref="paper", xanchor="left", yanchor="top", showarrow=False,
                    align="left", font=dict(family="monospace", size=13))

    names = [str(k) for k in range(t.size)]  # unique frame names; the slider shows the times
    frames = [go.Frame(data=traces(k), traces=[0, 1], name=names[k], layout=dict(annotations=[panel(k)]))
              for k in range(t.size)]
    anim = dict(mode="immediate", frame=dict(duration=60, redraw=True), transition=dict(duration=0))
    rng = [-lim, lim]
    return go.Figure(
        data=traces(0), frames=frames,
        layout=go.Layout(
            title=dict(text=title, x=0.02, font=dict(size=15)),
            annotations=[panel(0)],
            # the camera a little farther than plotly's default (1.25, 1.25, 1.25): the whole box and its
            # tick labels inside the view; five ticks per axis, so the labels at the corners do not collide
            scene=dict(domain=dict(x=[0.0, 0.66], y=[0.0, 1.0]), aspectmode="cube",
                       camera=dict(eye=dict(x=1.5, y=1.5, z=1.1)),
                       xaxis=dict(title=dict(text=f"x{axes[0]}"), range=rng, autorange=False, nticks=5),
                       yaxis=dict(title=dict(text=f"x{axes[1]}"), range=rng, autorange=False, nticks=5),
                       zaxis=dict(title=dict(text=f"x{axes[2]}"), range=rng, autorange=False, nticks=5)),
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


#: Autoplay of the page: every 80 ms of the page's clock the next frame, looping, until the reader
#: presses Play / Pause or moves the slider (then plotly's controls take over). Each frame is one
#: ``Plotly.update`` (the frame's coordinates, its time panel and the slider's position together), so
#: the view, the panel and the slider always show the same time, and the next frame is timed from
#: the end of the drawing (a slow software-rendered WebGL plays slower, never out of step). It is
#: driven by the page's timer only, not by plotly's player, which waits for requestAnimationFrame:
#: a hidden tab or a headless browser does not run that, and there the page stood still. The graph
#: div carries the frame shown as ``data-frame`` (read by the browser test).
_AUTOPLAY = """
(function () {
  var gd = document.getElementById('{plot_id}');
  var frames = gd._transitionData && gd._transitionData._frames || [];
  if (frames.length < 2) { return; }
  var k = 0, stopped = false;
  gd.setAttribute('data-frame', '0');
  function show(f) {
    // the frame's traces: coordinates and point colours (one restyle, trace by trace)
    var data = {x: [], y: [], z: [], 'marker.color': []};
    (f.data || []).forEach(function (d) {
      data.x.push(d.x); data.y.push(d.y); data.z.push(d.z);
      data['marker.color'].push(d.marker ? d.marker.color : undefined);
    });
    var layout = {'sliders[0].active': k};
    if (f.layout && f.layout.annotations) { layout.annotations = f.layout.annotations; }
    return Plotly.update(gd, data, layout, f.traces);
  }
  function later() { if (!stopped) { setTimeout(next, 80); } }
  function next() {
    if (stopped) { return; }
    k = (k + 1) % frames.length;
    var f = frames[k];
    // the current frame first: the slider's observer reads it on the update (else it sets the slider
    // back to the previous frame), and Play continues from it
    gd._fullLayout._currentFrame = f.name;
    show(f).then(function () {
      if (stopped) { return; }
      gd.setAttribute('data-frame', String(k));
      later();
    });
  }
  function stop() { stopped = true; }
  gd.on('plotly_buttonclicked', stop);
  gd.on('plotly_sliderstart', stop);
  later();
})();
"""


def write_html(figure, path, *, auto_play: bool = True) -> str:
    """Write a :func:`projection_figure` as one self-contained HTML page (plotly.js inside, no network).

    The page starts playing when opened (``auto_play``). The file is HTML whatever its name
    (use ``.html``); it is written to ``path + ".part"`` and renamed at the end, so an
    interrupted run leaves no partial page; an existing file at ``path`` is replaced.
    Returns the path.
    """
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path must be a file name (str or os.PathLike), got {_v.fmt(path)}")
    path = os.fsdecode(path)
    _v.flag("auto_play", auto_play)
    if not callable(getattr(figure, "write_html", None)):
        raise TypeError(f"figure must be a plotly Figure, got {_v.fmt(figure)} of type {type(figure).__name__}")
    tmp = path + ".part"
    try:
        figure.write_html(tmp, include_plotlyjs=True, full_html=True, auto_play=False,
                          post_script=_AUTOPLAY if auto_play else None,
                          config=dict(displaylogo=False, responsive=True))
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return path
