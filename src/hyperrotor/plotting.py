"""Pictures of rotating bodies and of integrator accuracy (matplotlib, optional).

matplotlib is imported lazily; install it with ``pip install 'hyperrotor[viz]'``.

* :func:`save_projection_frames`, :func:`save_projection_animation`: 3D
  projections of N-dimensional point sets. The projections come from
  :func:`hyperrotor.classical.scenes.evaluate_scene` (``observables=("projection",)``):
  body points ``x_body`` are carried to space by ``x_space = T(t)^T x_body``
  (see :mod:`hyperrotor.conventions`, "Attitude") and the chosen space axes are
  kept. A fourth projected axis, when given, colours the points (the position
  along a space axis that is not drawn), with a labelled colour bar.
* :func:`save_motion_comparison`: angular velocity components, closed form
  against numerical runs, and the *relative* error of each run (the
  ``hyperrotor demo`` picture).

Every figure keeps its legends outside the data area, labels its axes and says
whether an error is absolute or relative.
"""
from __future__ import annotations

from typing import Any, Callable, Mapping, Sequence

import numpy as np

from . import _validate as _v
from .classical.body_points import body_edges

__all__ = [
    "body_edges",
    "draw_projection",
    "save_projection_frames",
    "save_projection_animation",
    "save_motion_comparison",
    "plot_poincare",
    "plot_work_precision",
]


def _pyplot():
    """matplotlib's pyplot, with the caller's backend (for the figures a caller shows: :func:`plot_poincare`)."""
    try:
        import matplotlib.pyplot as plt
    except ImportError:  # pragma: no cover - depends on the environment
        raise ImportError("plotting needs matplotlib: pip install 'hyperrotor[viz]'") from None
    return plt


#: the most panels (problems) of :func:`plot_work_precision`, side by side
MAX_PANELS = 12
#: matplotlib's projections that are no plane of two Cartesian coordinates (plot_poincare refuses them)
_NOT_CARTESIAN = frozenset({"polar", "3d", "aitoff", "hammer", "lambert", "mollweide"})


def _figure(**kwargs: Any):
    """A figure drawn by Agg outside pyplot, for the pictures written to files: no backend is switched (the
    caller's Qt or Tk session keeps its own; the first version switched the process to Agg) and nothing is
    registered with pyplot, so a figure given up half-way (an error, Ctrl-C) is garbage, not a leak."""
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError:  # pragma: no cover - depends on the environment
        raise ImportError("plotting needs matplotlib: pip install 'hyperrotor[viz]'") from None
    fig = Figure(**kwargs)
    FigureCanvasAgg(fig)
    return fig


def _hidden_colour(projection: np.ndarray):
    """Split a projection ``(K, P, 3 or 4)`` into drawn coordinates and colour values (or None)."""
    projection = np.asarray(projection, dtype=float)
    if projection.ndim != 3 or projection.shape[-1] not in (3, 4):
        raise ValueError(f"projection must have shape (len(t), n_points, 3) or (len(t), n_points, 4), "
                         f"got {projection.shape}")
    if projection.shape[-1] == 4:
        return projection[..., :3], projection[..., 3]
    return projection, None


def draw_projection(ax, frame: np.ndarray, edges: Sequence[tuple[int, int]], *, limit: float | None = None,
                    axes_labels: Sequence[int] = (1, 2, 3), colour: np.ndarray | None = None, norm=None,
                    cmap: str = "coolwarm", edge_colour: str = "0.35"):
    """Draw one projected frame (``(n_points, 3)``) on a matplotlib 3D axis.

    Edges are one ``Line3DCollection`` (fast for thousands of edges); points are
    coloured by ``colour`` (one value per point, mapped through ``norm`` and
    ``cmap``) when given. Returns the scatter artist (a colour-bar mappable).
    """
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    frame = np.asarray(frame, dtype=float)
    if len(edges):
        e = np.asarray(edges, dtype=int)
        segs = np.stack([frame[e[:, 0]], frame[e[:, 1]]], axis=1)
        lw = 0.8 if len(e) <= 500 else 0.3
        ax.add_collection3d(Line3DCollection(segs, colors=edge_colour, linewidths=lw, alpha=0.7))
    size = 18 if len(frame) <= 64 else (5 if len(frame) <= 1024 else 1.5)
    if colour is None:
        sc = ax.scatter(*frame.T, s=size, color="tab:blue", depthshade=False)
    else:
        sc = ax.scatter(*frame.T, s=size, c=colour, cmap=cmap, norm=norm, depthshade=False,
                        edgecolors="k", linewidths=0.2)
    lim = limit if limit is not None else float(np.max(np.abs(frame))) * 1.05
    ax.set(xlim=(-lim, lim), ylim=(-lim, lim), zlim=(-lim, lim))
    tick = float(f"{lim / 1.05:.1g}")  # a round coordinate inside the box: the scale of the picture
    for setter in (ax.set_xticks, ax.set_yticks, ax.set_zticks):
        setter([-tick, 0.0, tick])
    ax.set_xlabel(f"x{axes_labels[0]}", labelpad=-2, fontsize=9)
    ax.set_ylabel(f"x{axes_labels[1]}", labelpad=-2, fontsize=9)
    ax.set_zlabel(f"x{axes_labels[2]}", labelpad=-2, fontsize=9)
    ax.tick_params(labelsize=8, pad=-1, length=0)
    # equal axes (the limits are equal: a cube looks like a cube), drawn a little smaller than the
    # panel so that the z label and tick labels stay inside it (a neighbouring panel or the colour
    # bar would cover what sticks out)
    ax.set_box_aspect((1, 1, 1), zoom=0.85)
    return sc


def _frames(t: Any, projection: Any, colour_axis: int | None) -> tuple:
    """``(drawn coordinates, colour values or None)`` of a projection checked with its times (one per frame: a
    shorter ``t`` titled only the first frames), its points (at least one) and its colour axis."""
    xyz, colour = _hidden_colour(projection)
    if colour is not None and colour_axis is None:
        raise ValueError("a projection with 4 coordinates needs colour_axis (the space axis of the 4th)")
    t = _v.finite_array("t", t)
    if t.ndim != 1 or t.size == 0 or t.size != xyz.shape[0]:
        raise ValueError(f"t must have one time per frame of the projection ({xyz.shape[0]}), got shape {t.shape}")
    if xyz.shape[1] == 0:
        raise ValueError("projection has no points (shape (len(t), 0, 3)): give at least one point")
    return xyz, colour


def _colour_setup(colour: np.ndarray | None):
    if colour is None:
        return None
    from matplotlib.colors import Normalize

    top = float(np.max(np.abs(colour))) or 1.0
    return Normalize(-top, top)


def _colour_label(axes_labels: Sequence[int], colour_axis: int | None) -> str:
    if colour_axis is None:
        return ""
    return f"x{colour_axis}: position along space axis {colour_axis} (not drawn)"


def save_projection_frames(path, t: np.ndarray, projection: np.ndarray, edges, *, n_frames: int = 6,
                           title: str = "", axes_labels: Sequence[int] = (1, 2, 3),
                           colour_axis: int | None = None, callback: Callable[[], object] | None = None,
                           format: str | None = "png") -> str:
    """Write a PNG with ``n_frames`` snapshots of a projection ``(len(t), n_points, 3 or 4)``.

    Each panel is titled with its time; the space axes drawn are labelled
    ``x<axis>``. With a fourth projected coordinate (the space axis
    ``colour_axis``), points are coloured by it on a symmetric scale shared by
    all panels, explained by a labelled colour bar. ``callback`` is called
    after each panel is drawn; ``format`` is passed to ``savefig`` (so ``path``
    may carry any suffix, e.g. a temporary name).
    """
    xyz, colour = _frames(t, projection, colour_axis)
    n_frames = _v.integer("n_frames", n_frames, minimum=1)
    idx = np.linspace(0, len(t) - 1, min(n_frames, len(t))).round().astype(int)
    cols = min(len(idx), 3)
    rows = -(-len(idx) // cols)
    fig = _figure(figsize=(3.3 * cols + (1.0 if colour is not None else 0.0), 3.3 * rows + 0.5))
    lim = float(np.max(np.abs(xyz))) * 1.05
    norm = _colour_setup(colour)
    sc = None
    axs = []
    for k, i in enumerate(idx):
        ax = fig.add_subplot(rows, cols, k + 1, projection="3d")
        sc = draw_projection(ax, xyz[i], edges, limit=lim, axes_labels=axes_labels,
                             colour=None if colour is None else colour[i], norm=norm)
        ax.set_title(f"t = {t[i]:.3g}", fontsize=9, pad=0)
        axs.append(ax)
        if callback is not None:
            callback()
    right = 0.88 if colour is not None else 0.98
    fig.subplots_adjust(left=0.02, right=right, bottom=0.03, top=0.9 if title else 0.95, wspace=0.05, hspace=0.12)
    if title:
        fig.suptitle(title, fontsize=10)
    if colour is not None:
        cax = fig.add_axes((0.9, 0.15, 0.015, 0.65))
        fig.colorbar(sc, cax=cax).set_label(_colour_label(axes_labels, colour_axis), fontsize=9)
    fig.savefig(path, dpi=100, format=format)
    return str(path)


def save_projection_animation(path, t: np.ndarray, projection: np.ndarray, edges, *, fps: int = 15,
                              title: str = "", axes_labels: Sequence[int] = (1, 2, 3),
                              colour_axis: int | None = None, callback: Callable[[], object] | None = None) -> str:
    """Write an animated GIF (Pillow) of a projection ``(len(t), n_points, 3 or 4)``.

    Frames are drawn one by one (``callback`` is called after each); the file
    is written only after the last frame, so an interrupt leaves nothing
    behind. ``path`` must end in ``.gif`` (Pillow picks the format from it).
    Colours and the colour bar as in :func:`save_projection_frames`.
    """
    xyz, colour = _frames(t, projection, colour_axis)
    if not str(path).lower().endswith(".gif"):
        raise ValueError(f"path must end in .gif (Pillow picks the format from it), got {_v.fmt(str(path))}")
    fps = _v.positive("fps", fps)
    from matplotlib.animation import PillowWriter
    from matplotlib.cm import ScalarMappable

    lim = float(np.max(np.abs(xyz))) * 1.05
    norm = _colour_setup(colour)
    fig = _figure(figsize=(5.4 if colour is not None else 4.6, 4.8))
    ax = fig.add_axes((0.0, 0.0, 0.78 if colour is not None else 1.0, 0.9), projection="3d")
    writer = PillowWriter(fps=fps)
    writer.setup(fig, str(path), dpi=100)
    if colour is not None:
        cax = fig.add_axes((0.84, 0.15, 0.025, 0.6))
        sm = ScalarMappable(norm=norm, cmap="coolwarm")
        fig.colorbar(sm, cax=cax).set_label(_colour_label(axes_labels, colour_axis), fontsize=8)
        cax.tick_params(labelsize=8)
    for i in range(len(t)):
        ax.cla()
        draw_projection(ax, xyz[i], edges, limit=lim, axes_labels=axes_labels,
                        colour=None if colour is None else colour[i], norm=norm)
        fig.suptitle(f"{title}\nt = {t[i]:.3g}" if title else f"t = {t[i]:.3g}", fontsize=8)
        writer.grab_frame()
        if callback is not None:
            callback()
    writer.finish()  # writes the file (the frames are kept in memory until then: an error writes nothing)
    return str(path)


def save_motion_comparison(path, t: np.ndarray, exact: np.ndarray, runs: Mapping[str, np.ndarray], *,
                           components: Sequence[int], labels: Sequence[str], scale: float, title: str = "",
                           marked: str | None = None, format: str | None = "png") -> str:
    r"""Closed form against numerical runs: chosen components and the relative error of each run.

    Top: ``exact[:, k]`` for ``k`` in ``components`` (lines) with the run
    ``marked`` as dots. Bottom: the relative error
    :math:`\max_{ij} |\omega_{ij}(t) - \omega^\text{exact}_{ij}(t)| / \text{scale}`
    of every run (``scale`` is :math:`\lVert\omega_0\rVert_\infty`, the same
    normalisation as the printed "max relative error"). Legends sit outside the
    data, to the right of each panel.
    """
    t = _v.finite_array("t", t)
    exact = _v.finite_array("exact", exact)
    if t.ndim != 1 or exact.ndim != 2 or exact.shape[0] != t.size:
        raise ValueError(f"exact must have shape (len(t), n) = ({t.size}, n), got {exact.shape}")
    if not isinstance(runs, Mapping) or any(np.shape(w) != exact.shape for w in runs.values()):
        raise ValueError(f"runs must map names to arrays of the shape of exact {exact.shape}, got "
                         f"{ {k: np.shape(w) for k, w in runs.items()} if isinstance(runs, Mapping) else _v.fmt(runs)}")
    components, labels = list(components), list(labels)
    if len(labels) != len(components) or any(not -exact.shape[1] <= int(k) < exact.shape[1] for k in components):
        raise ValueError(f"components must be {len(labels)} column indices of exact (0 .. {exact.shape[1] - 1}, or "
                         f"negative from the end), one per label, got components {components} and labels {labels}")
    if marked is not None and marked not in runs:
        raise ValueError(f"marked must be one of the runs {list(runs)} or None, got {marked!r}")
    scale = _v.positive("scale", scale)
    fig = _figure(figsize=(10, 6.5))
    ax1, ax2 = fig.subplots(2, 1, sharex=True, height_ratios=(3, 1.6))
    step = max(1, len(t) // 50)
    for k, label in zip(components, labels):
        line, = ax1.plot(t, exact[:, k], lw=1.2, label=f"{label} closed form")
        if marked is not None:
            ax1.plot(t[::step], runs[marked][::step, k], "o", ms=3, color=line.get_color())
    if marked is not None:
        ax1.plot([], [], "o", ms=3, color="0.4", label=f"dots: {marked}")
    ax1.set_ylabel("angular velocity $\\omega_{ij}$")
    ax1.set_title("closed form (lines)" + (f" and {marked} (dots)" if marked is not None else ""), fontsize=9)
    if title:
        fig.suptitle(title, fontsize=10)
    ax1.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    floor = np.finfo(float).eps / 10
    for name, omega in runs.items():
        err = np.max(np.abs(omega - exact), axis=-1) / scale
        ax2.semilogy(t[1:], np.maximum(err[1:], floor), lw=1, label=name)
    ax2.set_xlabel("t")
    ax2.set_ylabel("relative error")
    ax2.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    ax2.grid(True, which="major", alpha=0.3)
    ax2.set_title(r"relative error of each run: $\max_{ij}|\omega_{ij} - \omega^\mathrm{exact}_{ij}|\,/\,"
                  r"\max|\omega_0|$", fontsize=9)
    fig.align_ylabels((ax1, ax2))
    fig.tight_layout()
    fig.savefig(path, dpi=110, format=format)
    return str(path)


def plot_poincare(sections: Any, x: Any = (1, 3), y: Any = (2, 4), *, ax: Any = None, labels: Sequence[str] | None = None,
                  **scatter_options: Any):
    r"""Scatter plot of one or several :class:`~hyperrotor.classical.poincare.PoincareSection` in the plane of two momentum components.

    Parameters
    ----------
    sections : PoincareSection or list of them
        the sections (one colour each).
    x, y : pair or str
        the planes whose components :math:`L_x`, :math:`L_y` are drawn, in the sections' axis labels (a
        locked body keeps its original ones, e.g. ``(2, 4)`` of a body locked on axis 1).
    ax : 2-D matplotlib Axes, optional
        where to draw (default: a new figure; matplotlib is imported only here).
    labels : sequence of str, optional
        legend entries, one per section.
    **scatter_options
        passed to ``ax.scatter`` (default ``s=2``).

    Returns
    -------
    matplotlib Axes
    """
    from .classical.poincare import PoincareSection

    if isinstance(sections, PoincareSection):
        secs = [sections]
    elif isinstance(sections, (list, tuple)):
        secs = list(sections)
    else:
        secs = []
    if not secs or not all(isinstance(s_, PoincareSection) for s_ in secs):
        raise TypeError(f"sections must be a PoincareSection or a list of them, got {_v.fmt(sections)}")
    axes_of = {s_.axes or tuple(range(1, s_.N + 1)) for s_ in secs}
    if len(axes_of) > 1:
        raise ValueError(f"sections must be of bodies with the same axes to share a plot, got axes "
                         f"{', '.join(map(str, sorted(axes_of)))}")
    (body_axes,) = axes_of
    px, py = (_section_plane(name, q, body_axes, default) for name, q, default in
              (("x", x, (1, 3)), ("y", y, (2, 4))))
    if labels is not None:
        if not isinstance(labels, (list, tuple)) or not all(isinstance(lab, str) for lab in labels):
            raise TypeError(f"labels must be a list of strings (one per section), got {_v.fmt(labels)}")
        if len(labels) != len(secs):
            raise ValueError(f"labels must name each of the {len(secs)} sections, got {len(labels)}")
    if ax is not None:  # (polar and map axes read L_x as an angle, 3-D ones want a third coordinate)
        from matplotlib.axes import Axes

        if not isinstance(ax, Axes) or ax.name in _NOT_CARTESIAN:
            raise TypeError(f"ax must be a 2-D matplotlib Axes (or None for a new figure), got {_v.fmt(ax)} of type "
                            f"{type(ax).__name__}" + (f" ({ax.name!r} projection)" if isinstance(ax, Axes) else ""))
    if ax is None:  # constrained layout: the legend beside the axes stays inside the saved figure
        _, ax = _pyplot().subplots(figsize=(4.5 if labels is None else 5.6, 4.5), layout="constrained")
    opts = {"s": 2}
    opts.update(scatter_options)
    for k, sec in enumerate(secs):
        xy = sec.coordinates(px, py)
        try:
            ax.scatter(xy[:, 0], xy[:, 1], label=None if labels is None else labels[k], **opts)
        except AttributeError as exc:  # matplotlib's answer to an unknown property
            if "unexpected keyword argument" not in str(exc):
                raise
            raise TypeError(f"scatter_options {sorted(scatter_options)}: {exc} (they go to matplotlib's "
                            f"Axes.scatter)") from None
    ax.set_xlabel(f"$L_{{{px[0]}{px[1]}}}$")
    ax.set_ylabel(f"$L_{{{py[0]}{py[1]}}}$")
    sign = {1: "upward", -1: "downward", 0: "both directions"}
    kinds = dict.fromkeys(f"$L_{{{s_.plane[0]}{s_.plane[1]}}} = {s_.value:g}$ ({sign[s_.direction]})" for s_ in secs)
    ax.set_title(("section " if len(kinds) == 1 else "sections ") + "; ".join(kinds))  # (each kind once)
    if labels is not None:
        ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), markerscale=4, frameon=False)
    return ax


def _section_plane(name: str, plane: Any, axes: tuple, default: tuple) -> tuple[int, int]:
    """``plane`` (``x`` or ``y`` of :func:`plot_poincare`) as a pair of the sections' axis labels (a locked body keeps
    its own, e.g. (2, 3, 4, 5)), or a ``ValueError`` naming the argument, the axes, and whether it was the default."""
    was = " (the default: pass x= and y=)" if isinstance(plane, tuple) and plane == default else ""
    try:
        a, b = _v.plane(plane, max(axes))
    except ValueError as err:
        raise ValueError(f"{name}{was}: {err}") from None
    if a not in axes or b not in axes:
        raise ValueError(f"{name} = {_v.fmt(plane)}{was} is no plane of the sections' axes {axes}: planes are pairs "
                         f"(i, j), i < j, of them")
    return a, b


def plot_work_precision(points: Sequence, path, *, format: str | None = "png") -> str:
    r"""Log-log plot of wall time against error, one line per method and one panel per problem.

    ``points``: :class:`hyperrotor.bench.WorkPrecisionPoint` records. The error axis is
    the *relative* error :math:`\max_t \lVert\omega - \omega_\text{exact}\rVert_\infty /
    \lVert\omega_0\rVert_\infty` of :mod:`hyperrotor.bench` (the printed table's
    ``error`` column). It is reversed, so that accuracy grows to the right (the usual
    work-precision layout): the x label says so. Each panel's title names the problem,
    its dimension N and final time :math:`t_\text{end}` (the points' ``N``, ``t_end``). The legend sits below the
    panels, off the data. ``format`` is passed to ``savefig`` (``path`` may be a
    temporary name).
    """
    from .bench import WorkPrecisionPoint

    if isinstance(points, (str, bytes, Mapping)) or not hasattr(points, "__iter__"):
        raise TypeError(f"points must be a sequence of WorkPrecisionPoint records, got {_v.fmt(points)}")
    points = list(points)
    if not all(isinstance(p, WorkPrecisionPoint) for p in points):
        raise TypeError(f"points must be WorkPrecisionPoint records (hyperrotor.bench), got "
                        f"{sorted({type(p).__name__ for p in points if not isinstance(p, WorkPrecisionPoint)})}")
    problems = list(dict.fromkeys(p.problem for p in points))
    if not problems:
        raise ValueError("plot_work_precision needs at least one point")
    if len(problems) > MAX_PANELS:  # (one panel each: 200 problems drew a 127600 px wide picture in 34 s)
        raise ValueError(f"plot_work_precision draws one panel per problem, at most {MAX_PANELS}; got "
                         f"{len(problems)} problems: plot them in groups")
    fig = _figure(figsize=(5.8 * len(problems), 4.8))
    axes = fig.subplots(1, len(problems), squeeze=False)
    handles = {}
    for ax, prob in zip(axes[0], problems):
        for k, method in enumerate(dict.fromkeys(p.method for p in points)):
            sel = sorted((p for p in points if p.problem == prob and p.method == method), key=lambda p: p.error)
            if not sel:
                continue
            line, = ax.loglog([max(p.error, 1e-17) for p in sel], [p.seconds for p in sel], "o-", ms=3,
                              color=f"C{k}", label=method)
            handles.setdefault(method, line)
        first = next(p for p in points if p.problem == prob)
        N, t_end = first.N, first.t_end
        span = f" (N = {N}, $t_\\mathrm{{end}}$ = {t_end:g})" if N is not None and t_end is not None else ""
        ax.set_xlabel("relative error $\\max_t\\,\\|\\omega - \\omega_\\mathrm{exact}\\|_\\infty"
                      " / \\|\\omega_0\\|_\\infty$\n(axis reversed: more accurate to the right $\\rightarrow$)")
        ax.set_ylabel("wall time $t_\\mathrm{wall}$ [s] (best of repeats)")
        ax.set_title(f"{prob}{span}: time to reach an error", fontsize=10)
        ax.invert_xaxis()
        ax.grid(True, which="major", alpha=0.3)
    fig.legend(list(handles.values()), list(handles), loc="lower center", ncol=min(len(handles), 7), fontsize=8,
               frameon=False)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    fig.savefig(path, dpi=110, format=format)
    return str(path)
