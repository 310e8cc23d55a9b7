"""Every figure-producing public function, checked mechanically on the figure it saves.

Each function is run on a small input while ``Figure.savefig`` is watched; every saved figure
must have: a title (figure or every panel), a label on every axis of every data panel (x, y, and
z in 3D; the long axis of a colour bar), tick labels of at least 8 points, and no legend box over
plotted data (the legend's window extent against every data point in display coordinates).
"""
from __future__ import annotations

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

import hyperrotor as hr  # noqa: E402
from hyperrotor import plotting  # noqa: E402
from hyperrotor.bench import WorkPrecisionPoint  # noqa: E402
from hyperrotor.classical.chaos import PoincareSection  # noqa: E402
from hyperrotor.classical.scenes import Scene, body_edges, hypercube_vertices  # noqa: E402


@pytest.fixture
def saved(monkeypatch):
    """The figures passed to savefig (GIF frames included), in order."""
    figs = []
    original = Figure.savefig

    def spy(self, *args, **kwargs):
        if not figs or figs[-1] is not self:
            figs.append(self)
        return original(self, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", spy)
    return figs


def _data_points(ax) -> np.ndarray:
    """Display coordinates of every plotted data point of a 2-D axes."""
    pts = []
    for line in ax.get_lines():
        xy = np.asarray(line.get_xydata(), dtype=float)
        if xy.size:
            pts.append(ax.transData.transform(xy))
    for coll in ax.collections:
        off = np.asarray(coll.get_offsets(), dtype=float)
        if off.size:
            pts.append(coll.get_offset_transform().transform(off))
    if not pts:
        return np.zeros((0, 2))
    out = np.concatenate(pts)
    return out[np.all(np.isfinite(out), axis=1)]


def _is_colourbar(ax) -> bool:
    return ax.get_label() == "<colorbar>" or hasattr(ax, "_colorbar")


def _check(fig) -> None:
    canvas = FigureCanvasAgg(fig)  # a closed figure has lost its pyplot canvas
    canvas.draw()
    renderer = canvas.get_renderer()
    suptitle = fig._suptitle.get_text() if fig._suptitle is not None else ""
    data_axes = [ax for ax in fig.axes if not _is_colourbar(ax)]
    assert data_axes, "a figure without data panels"
    for ax in fig.axes:
        if _is_colourbar(ax):
            long_axis = ax.yaxis if ax.get_position().height >= ax.get_position().width else ax.xaxis
            assert long_axis.get_label().get_text(), "a colour bar without a label"
            continue
        names = ("x", "y", "z") if ax.name == "3d" else ("x", "y")
        for n in names:
            axis = getattr(ax, f"{n}axis")
            if not any(t.get_visible() and t.get_text() for t in axis.get_ticklabels()):
                continue  # an axis shared with the panel below: labelled there (checked there)
            assert axis.get_label().get_text().strip(), f"unlabelled {n} axis in panel {ax.get_title()!r}"
            sizes = [t.get_fontsize() for t in axis.get_ticklabels() if t.get_text()]
            assert min(sizes, default=10) >= 8, f"{n} tick labels of {min(sizes)} pt: too small to read"
        assert suptitle or ax.get_title(), "a panel without a title (and no figure title)"
    legends = [ax.get_legend() for ax in data_axes if ax.get_legend() is not None] + list(fig.legends)
    for leg in legends:
        box = leg.get_window_extent(renderer)
        for ax in data_axes:
            if ax.name == "3d":
                continue
            pts = _data_points(ax)
            inside = ((pts[:, 0] >= box.x0) & (pts[:, 0] <= box.x1) & (pts[:, 1] >= box.y0) & (pts[:, 1] <= box.y1))
            assert not inside.any(), f"the legend covers {inside.sum()} data points of panel {ax.get_title()!r}"


@pytest.fixture(scope="module")
def scene_result():
    N = 4
    scene = Scene(hr.RigidBody(hr.Inertia.quartet(0.5, axis=N, N=N)), 0.3 * np.arange(1, 7), np.linspace(0, 6, 4),
                  observables=("projection",), points=hypercube_vertices(N), axes=(1, 2, 3, 4))
    return scene.points, scene.evaluate()


def test_scene_snapshots(saved, tmp_path, scene_result):
    points, res = scene_result
    plotting.save_projection_frames(tmp_path / "s.png", res.t, res.projection, body_edges(points, "cube"),
                                    n_frames=3, title="4-cube", colour_axis=4)
    assert len(saved) == 1
    _check(saved[0])


def test_scene_animation(saved, tmp_path, scene_result):
    points, res = scene_result
    plotting.save_projection_animation(tmp_path / "s.gif", res.t[:2], res.projection[:2], body_edges(points, "cube"),
                                       title="4-cube", colour_axis=4)
    assert len(saved) == 1  # one figure, one savefig per frame
    _check(saved[0])


def test_motion_comparison(saved, tmp_path):
    t = np.linspace(0.0, 10.0, 200)
    exact = np.column_stack([np.sin(t), np.cos(t), 0.5 * np.sin(2 * t)])
    runs = {"splitting8": exact + 1e-9 * np.cos(t)[:, None], "DOP853": exact + 1e-7}
    plotting.save_motion_comparison(tmp_path / "m.png", t, exact, runs, components=(0, 1),
                                    labels=("$\\omega_{12}$", "$\\omega_{13}$"), scale=1.0, title="demo",
                                    marked="splitting8")
    _check(saved[0])


def test_poincare(saved, tmp_path):
    rng = np.random.default_rng(0)
    secs = []
    for _ in range(2):
        L = rng.normal(size=(50, 6))
        secs.append(PoincareSection(t=np.arange(50.0), L=L, omega=L, plane=(1, 2), value=0.0, direction=1, N=4))
    ax = plotting.plot_poincare(secs, x=(1, 3), y=(2, 4), labels=["regular", "chaotic"])
    ax.figure.savefig(tmp_path / "p.png")
    plt.close(ax.figure)
    _check(saved[0])


def test_work_precision(saved, tmp_path):
    spans = {"quartet": (5, 200.0), "euler-poinsot": (3, 100.0)}
    pts = [WorkPrecisionPoint(p, m, "dt", v, e, s, *spans[p]) for p in ("quartet", "euler-poinsot")
           for m, v, e, s in (("splitting8", 0.3, 1e-6, 0.03), ("splitting8", 0.1, 1e-10, 0.1),
                              ("DOP853", 1e-8, 1e-7, 0.5), ("DOP853", 1e-10, 1e-9, 0.9))]
    plotting.plot_work_precision(pts, tmp_path / "w.png")
    fig = saved[0]
    _check(fig)
    # the reversed error axis is explained, and N and t_end are in every title
    for ax in fig.axes:
        assert ax.xaxis_inverted() and "reversed" in ax.get_xlabel()
    assert [ax.get_title().split(":")[0] for ax in fig.axes] == [
        "quartet (N = 5, $t_\\mathrm{end}$ = 200)", "euler-poinsot (N = 3, $t_\\mathrm{end}$ = 100)"]


def test_the_check_finds_a_covering_legend(tmp_path):
    """The legend check itself: a legend placed on the data is caught."""
    fig, ax = plt.subplots()
    x = np.linspace(0, 1, 50)
    ax.plot(x, x, label="diagonal")
    ax.set(xlabel="x", ylabel="y", title="t")
    ax.legend(loc="center")
    with pytest.raises(AssertionError, match="legend covers"):
        _check(fig)
    plt.close(fig)
