"""Tests of hyperrotor.plotting (edges of projected bodies, written files)."""
import numpy as np
import pytest

from hyperrotor.classical import hypercube_vertices, simplex_vertices
from hyperrotor.plotting import body_edges, save_projection_frames


@pytest.mark.parametrize("N", [2, 3, 4, 5, 6])
def test_cube_edges_are_the_unit_edges(N):
    V = hypercube_vertices(N)
    edges = body_edges(V, "cube")
    assert len(edges) == N * 2 ** (N - 1)
    lengths = [np.linalg.norm(V[a] - V[b]) for a, b in edges]
    np.testing.assert_allclose(lengths, 2.0, rtol=0, atol=1e-15)


@pytest.mark.parametrize("N", [2, 3, 5])
def test_simplex_edges_all_pairs_equal_length(N):
    V = simplex_vertices(N)
    edges = body_edges(V, "simplex")
    assert len(edges) == N * (N + 1) // 2
    lengths = [np.linalg.norm(V[a] - V[b]) for a, b in edges]
    np.testing.assert_allclose(lengths, lengths[0], rtol=1e-14)


def test_bad_kind_and_shape(tmp_path):
    with pytest.raises(ValueError, match="unknown kind 'sphere'; allowed: 'cube', 'simplex', 'points'"):
        body_edges(np.zeros((3, 3)), "sphere")
    with pytest.raises(ValueError, match=r"shape \(len\(t\), n_points, 3\)"):
        save_projection_frames(str(tmp_path / "a.png"), np.arange(2), np.zeros((2, 4, 2)), [])


def test_pictures_are_drawn_outside_pyplot_and_refuse_bad_input_clearly(tmp_path):
    """The save functions switched the process's matplotlib backend to Agg (a Qt or Tk session lost plt.show) and
    leaked an open pyplot figure on every error before their savefig; n_frames = 0, fps = 0, empty or short time
    grids and points, short labels, scale 0 and wrong records gave bare ZeroDivision / Attribute errors or wrong
    pictures silently (a review)."""
    matplotlib = pytest.importorskip("matplotlib")
    import matplotlib.pyplot as plt

    from hyperrotor.bench import WorkPrecisionPoint
    from hyperrotor.plotting import save_motion_comparison, save_projection_animation, plot_work_precision

    backend, figures = matplotlib.get_backend(), plt.get_fignums()
    t = np.linspace(0.0, 1.0, 4)
    proj = np.random.default_rng(1).normal(size=(4, 8, 3))
    edges = body_edges(hypercube_vertices(3), "cube")
    assert save_projection_frames(tmp_path / "a.png", t, proj, edges, n_frames=2) == str(tmp_path / "a.png")
    for kwargs, words in ((dict(n_frames=0), "n_frames"), (dict(t=t[:3]), "one time per frame"),
                          (dict(projection=proj[:, :0]), "no points")):
        args = dict(t=t, projection=proj) | {k: v for k, v in kwargs.items() if k in ("t", "projection")}
        with pytest.raises(ValueError, match=words):
            save_projection_frames(tmp_path / "b.png", args["t"], args["projection"], edges,
                                   **{k: v for k, v in kwargs.items() if k == "n_frames"})
    with pytest.raises(ValueError, match=r"fps"):
        save_projection_animation(tmp_path / "c.gif", t, proj, edges, fps=0)
    with pytest.raises(ValueError, match=r"must end in \.gif"):
        save_projection_animation(tmp_path / "c.png", t, proj, edges)
    exact = np.ones((4, 3))
    good = dict(components=[0, 2], labels=["a", "b"], scale=1.0)
    save_motion_comparison(tmp_path / "d.png", t, exact, {"run": exact + 1e-9}, **good)
    for change, words in ((dict(labels=["a"]), "one per label"), (dict(scale=0.0), "scale"),
                          (dict(components=[0, 3]), "column indices"), (dict(marked="other"), "marked")):
        with pytest.raises(ValueError, match=words):
            save_motion_comparison(tmp_path / "e.png", t, exact, {"run": exact}, **(good | change))
    with pytest.raises(ValueError, match="shape of exact"):
        save_motion_comparison(tmp_path / "e.png", t, exact, {"run": exact[:2]}, **good)
    with pytest.raises(TypeError, match="WorkPrecisionPoint"):
        plot_work_precision([{"problem": "x"}], tmp_path / "f.png")
    many = [WorkPrecisionPoint(f"p{k}", "m", "dt", 0.1, 1e-8, 0.1) for k in range(13)]
    with pytest.raises(ValueError, match="at most 12"):
        plot_work_precision(many, tmp_path / "f.png")
    assert matplotlib.get_backend() == backend and plt.get_fignums() == figures
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.png", "d.png"]


def test_the_caller_s_backend_stays(tmp_path):
    """Any backend but Agg or inline was switched to Agg by the first picture (a review: svg and pdf became Agg;
    a Qt or Tk session would have lost plt.show)."""
    matplotlib = pytest.importorskip("matplotlib")

    before = matplotlib.get_backend()
    try:
        matplotlib.use("svg")
        t = np.linspace(0.0, 1.0, 3)
        save_projection_frames(tmp_path / "a.png", t, np.ones((3, 2, 3)), [(0, 1)], n_frames=1)
        assert matplotlib.get_backend() == "svg"
        assert (tmp_path / "a.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"  # (drawn by Agg all the same)
    finally:
        matplotlib.use(before)


def test_negative_components_and_2d_axes_of_any_kind(tmp_path):
    """components=[-1] (numpy's index from the end) was refused by the new checks, and a registered 2-D Axes subclass
    by plot_poincare's name test (a review of the change)."""
    pytest.importorskip("matplotlib")
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.projections import register_projection

    from hyperrotor.classical import PoincareSection
    from hyperrotor.plotting import plot_poincare, save_motion_comparison

    t = np.linspace(0.0, 1.0, 4)
    exact = np.ones((4, 3))
    save_motion_comparison(tmp_path / "a.png", t, exact, {"run": exact}, components=[-1], labels=["last"], scale=1.0)
    assert (tmp_path / "a.png").exists()

    class MyAxes(Axes):
        name = "hyperrotor_test_axes"

    register_projection(MyAxes)
    L = np.arange(12.0).reshape(2, 6) + 1.0
    sec = PoincareSection(t=np.array([0.5, 1.0]), L=L, omega=L, plane=(1, 2), value=0.0, direction=1, N=4)
    ax = plot_poincare(sec, ax=Figure().add_subplot(projection="hyperrotor_test_axes"))
    np.testing.assert_array_equal(np.asarray(ax.collections[0].get_offsets()), sec.coordinates((1, 3), (2, 4)))
