"""Every figure-producing public function, checked mechanically on the figure it saves.

Each function is run on a small input while ``Figure.savefig`` is watched; every saved figure
must have: a title (figure or every panel), a label on every axis of every data panel (x, y, and
z in 3D; the long axis of a colour bar), tick labels of at least 8 points, no legend box over
plotted data (the legend's window extent against every data point in display coordinates), and no
axis or title cut by the figure's edge or reaching into another panel (where it would be hidden).
The pictures committed in docs/_static are compared with what their commands draw today.
"""
from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.text import Text  # noqa: E402

import hyperrotor as hr  # noqa: E402
from hyperrotor import plotting  # noqa: E402
from hyperrotor.bench import WorkPrecisionPoint  # noqa: E402
from hyperrotor.classical import PoincareSection  # noqa: E402
from hyperrotor.classical import Scene, body_edges, hypercube_vertices  # noqa: E402


ROOT = Path(__file__).resolve().parents[1]


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


def _draw_recording_texts(canvas) -> list:
    """Draw the figure; return (text, window extent) of every text drawn, taken as it is drawn (3D tick
    labels are placed during the draw, and matplotlib 3.10 reports stale positions for them after it)."""
    drawn = []
    original = Text.draw

    def record(self, renderer):
        original(self, renderer)
        if self.get_visible() and self.get_text().strip():
            drawn.append((self, self.get_window_extent(renderer).frozen()))

    Text.draw = record
    try:
        canvas.draw()
    finally:
        Text.draw = original
    return drawn


def _check(fig) -> None:
    canvas = FigureCanvasAgg(fig)  # a closed figure has lost its pyplot canvas
    drawn = _draw_recording_texts(canvas)
    renderer = canvas.get_renderer()
    suptitle = fig._suptitle.get_text() if fig._suptitle is not None else ""
    data_axes = [ax for ax in fig.axes if not _is_colourbar(ax)]
    assert data_axes, "a figure without data panels"
    for ax in fig.axes:
        if _is_colourbar(ax):
            long_axis = ax.yaxis if ax.get_position().height >= ax.get_position().width else ax.xaxis
            assert long_axis.get_label().get_text(), "a colour bar without a label"
            sizes = [t.get_fontsize() for t in long_axis.get_ticklabels() if t.get_text()]
            assert min(sizes, default=10) >= 8, f"colour bar tick labels of {min(sizes)} pt: too small to read"
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
    _check_nothing_cut_or_covered(fig, drawn)
    legends = [ax.get_legend() for ax in data_axes if ax.get_legend() is not None] + list(fig.legends)
    for leg in legends:
        box = leg.get_window_extent(renderer)
        for ax in data_axes:
            if ax.name == "3d":
                continue
            pts = _data_points(ax)
            inside = ((pts[:, 0] >= box.x0) & (pts[:, 0] <= box.x1) & (pts[:, 1] >= box.y0) & (pts[:, 1] <= box.y1))
            assert not inside.any(), f"the legend covers {inside.sum()} data points of panel {ax.get_title()!r}"


def _overlap(a, b, slack: float = 0.5) -> bool:
    return a.x0 < b.x1 - slack and b.x0 < a.x1 - slack and a.y0 < b.y1 - slack and b.y0 < a.y1 - slack


def _check_nothing_cut_or_covered(fig, drawn) -> None:
    """Every text drawn (axis labels, tick labels, titles, legends) lies inside the figure, and none of
    a panel's texts reaches into another panel (a 3D panel's background, or a colour bar, drawn
    later hides it: the scene snapshots once showed their z labels as a lone "x")."""
    page = fig.bbox
    for text, box in drawn:
        owner = text.axes
        what = f"{text.get_text()!r}" + (f" of panel {owner.get_title() or owner.get_label()!r}" if owner else "")
        assert (box.x0 >= page.x0 - 1 and box.x1 <= page.x1 + 1 and box.y0 >= page.y0 - 1
                and box.y1 <= page.y1 + 1), f"{what} is cut by the figure's edge"
        if owner is None:
            continue
        for other in fig.axes:
            assert other is owner or not _overlap(box, other.bbox), \
                f"{what} reaches into panel {other.get_title() or other.get_label()!r}"


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


def test_demo_picture(saved, tmp_path):
    """The picture of ``hyperrotor demo`` (README), on the demo's own motion, shortened."""
    from hyperrotor.demo import DEMO_OMEGA, compare_quartet_motion, save_quartet_motion

    save_quartet_motion(compare_quartet_motion(0.5, DEMO_OMEGA, 20.0, n_times=201), tmp_path / "d.png")
    assert len(saved) == 1
    _check(saved[0])


def test_scene_snapshots_as_the_cli_draws_them(saved, tmp_path):
    """``hyperrotor scene`` on its defaults: six snapshots of the 5-cube in two rows, colour bar (x4)."""
    scene = Scene(hr.RigidBody(hr.Inertia.quartet(0.5)), 0.1 * np.arange(1, 11), np.linspace(0, 20, 12),
                  observables=("projection",), points=hypercube_vertices(5), axes=(1, 2, 3, 4))
    res = scene.evaluate()
    plotting.save_projection_frames(tmp_path / "s.png", res.t, res.projection, body_edges(scene.points, "cube"),
                                    n_frames=6, title="cube in 5D", colour_axis=4)
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


@pytest.mark.parametrize("argv,picture", [
    (["demo", "--ascii", "--png", "{out}"], "demo-quartet.png"),      # README.md
    (["scene", "--output", "{out}"], "scene-5cube.png"),              # README.md, docs/index.md
])
def test_committed_pictures_are_what_the_commands_draw_today(capsys, tmp_path, argv, picture):
    """The pictures in docs/_static (shown by the README and the front page) were made by these commands
    with today's code: a change of the figures must re-render them (the command is the argv, with the
    picture's path as the output). Compared pixel by pixel, with room for font rendering."""
    from PIL import Image

    from hyperrotor.cli import main

    with Image.open(ROOT / "docs" / "_static" / picture) as committed_png:
        drawn_by = committed_png.info.get("Software", "")
        committed = np.asarray(committed_png.convert("L"), dtype=float)
    made = re.search(r"Matplotlib version\s*(\d+\.\d+)", drawn_by)
    if made is None or made[1] != ".".join(matplotlib.__version__.split(".")[:2]):
        pytest.skip(f"docs/_static/{picture} was drawn by {drawn_by!r}, this is matplotlib {matplotlib.__version__} "
                    f"(its text and layout differ between versions)")
    out = tmp_path / picture
    assert main([a.format(out=out) for a in argv]) == 0, capsys.readouterr().err
    with Image.open(out) as fresh_png:
        fresh = np.asarray(fresh_png.convert("L"), dtype=float)
    assert fresh.shape == committed.shape, f"re-render docs/_static/{picture}: size {committed.shape} != {fresh.shape}"
    changed = np.mean(np.abs(fresh - committed) > 32)  # a stale layout differs in 9-21 % of its pixels
    assert changed < 0.02, f"re-render docs/_static/{picture}: {changed:.1%} of its pixels differ"


#: Figure functions checked through another one here (they draw on an axes the caller owns).
_CHECKED_THROUGH = {"draw_projection": "save_projection_frames"}


def test_every_figure_function_is_checked_here():
    """A new figure function of hyperrotor.plotting (or the demo's) gets a check in this file."""
    import inspect

    from hyperrotor import demo

    source = Path(__file__).read_text(encoding="utf-8")
    names = [n for n in plotting.__all__ if n.startswith(("save_", "plot_", "draw_"))]
    names += [n for n, f in inspect.getmembers(demo, inspect.isfunction) if n.startswith(("save_", "plot_"))]
    assert "save_quartet_motion" in names and "plot_work_precision" in names
    missing = [n for n in names if f"{_CHECKED_THROUGH.get(n, n)}(" not in source]
    assert not missing, f"add a test of {missing} to tests/test_figures.py"
