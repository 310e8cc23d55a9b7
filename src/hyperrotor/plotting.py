"""Pictures of rotating bodies: 3D projections of N-dimensional point sets (matplotlib, optional).

matplotlib is imported lazily; install it with ``pip install 'hyperrotor[viz]'``.
The projections themselves come from :func:`hyperrotor.classical.scenes.evaluate_scene`
(``observables=("projection",)``): body points ``x_body`` are carried to space by
``x_space = T(t)^T x_body`` (see :mod:`hyperrotor.conventions`, "Attitude") and
the chosen space axes are kept.
"""
from __future__ import annotations

from typing import Sequence

import numpy as np

__all__ = ["body_edges", "draw_projection", "save_projection_frames", "save_projection_animation"]


def _pyplot():
    try:
        import matplotlib

        if matplotlib.get_backend().lower() not in ("agg", "module://matplotlib_inline.backend_inline"):
            matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:  # pragma: no cover - depends on the environment
        raise ImportError("plotting needs matplotlib: pip install 'hyperrotor[viz]'") from None
    return plt


def body_edges(points: np.ndarray, kind: str) -> list[tuple[int, int]]:
    """Edges to draw between body points.

    ``kind="cube"``: pairs of hypercube vertices differing in exactly one
    coordinate; ``"simplex"``: all pairs; ``"points"`` (e.g. an ellipsoid
    sample): none.
    """
    pts = np.asarray(points, dtype=float)
    if kind == "points":
        return []
    n = len(pts)
    if kind == "simplex":
        return [(a, b) for a in range(n) for b in range(a + 1, n)]
    if kind == "cube":
        diff = np.sum(~np.isclose(pts[:, None, :], pts[None, :, :]), axis=-1)
        return [(int(a), int(b)) for a, b in zip(*np.nonzero(np.triu(diff == 1)))]
    raise ValueError(f"unknown body kind {kind!r}; allowed: 'cube', 'simplex', 'points'")


def draw_projection(ax, frame: np.ndarray, edges: Sequence[tuple[int, int]], *, limit: float | None = None,
                    axes_labels: Sequence[int] = (1, 2, 3), color: str = "tab:blue") -> None:
    """Draw one projected frame (``(n_points, 3)``) on a matplotlib 3D axis."""
    frame = np.asarray(frame)
    for a, b in edges:
        ax.plot(*frame[[a, b]].T, color=color, lw=0.8, alpha=0.8)
    ax.scatter(*frame.T, s=6 if not edges else 10, color="tab:red" if edges else color, depthshade=False)
    lim = limit if limit is not None else float(np.max(np.abs(frame))) * 1.05
    ax.set(xlim=(-lim, lim), ylim=(-lim, lim), zlim=(-lim, lim))
    ax.set_xlabel(f"x{axes_labels[0]}", labelpad=-8)
    ax.set_ylabel(f"x{axes_labels[1]}", labelpad=-8)
    ax.set_zlabel(f"x{axes_labels[2]}", labelpad=-8)
    ax.tick_params(labelsize=0, length=0)


def save_projection_frames(path: str, t: np.ndarray, projection: np.ndarray, edges, *, n_frames: int = 6,
                           title: str = "", axes_labels: Sequence[int] = (1, 2, 3)) -> str:
    """Write a PNG with ``n_frames`` snapshots of a projection ``(len(t), n_points, 3)``."""
    plt = _pyplot()
    projection = np.asarray(projection)
    if projection.ndim != 3 or projection.shape[-1] != 3:
        raise ValueError(f"projection must have shape (len(t), n_points, 3), got {projection.shape}")
    idx = np.linspace(0, len(t) - 1, n_frames).round().astype(int)
    cols = min(n_frames, 3)
    rows = -(-n_frames // cols)
    fig = plt.figure(figsize=(3.2 * cols, 3.2 * rows + 0.4))
    lim = float(np.max(np.abs(projection))) * 1.05
    for k, i in enumerate(idx):
        ax = fig.add_subplot(rows, cols, k + 1, projection="3d")
        draw_projection(ax, projection[i], edges, limit=lim, axes_labels=axes_labels)
        ax.set_title(f"t = {t[i]:.3g}", fontsize=9)
    if title:
        fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def save_projection_animation(path: str, t: np.ndarray, projection: np.ndarray, edges, *, fps: int = 15,
                              title: str = "", axes_labels: Sequence[int] = (1, 2, 3)) -> str:
    """Write an animated GIF (Pillow writer) of a projection ``(len(t), n_points, 3)``."""
    plt = _pyplot()
    from matplotlib.animation import FuncAnimation, PillowWriter

    projection = np.asarray(projection)
    lim = float(np.max(np.abs(projection))) * 1.05
    fig = plt.figure(figsize=(4.5, 4.5))
    ax = fig.add_subplot(projection="3d")

    def update(i):
        ax.cla()
        draw_projection(ax, projection[i], edges, limit=lim, axes_labels=axes_labels)
        ax.set_title(f"{title}  t = {t[i]:.3g}", fontsize=9)

    anim = FuncAnimation(fig, update, frames=len(t))
    anim.save(path, writer=PillowWriter(fps=fps))
    plt.close(fig)
    return path
