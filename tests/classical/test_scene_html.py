"""Interactive scenes (plotly figure and HTML page): contents against evaluate_scene, pricing, inputs."""
from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("plotly")

import hyperrotor as hr  # noqa: E402
from hyperrotor.classical.scene_html import projection_figure, scene_html_bytes, write_html  # noqa: E402
from hyperrotor.classical import Scene, body_edges, hypercube_vertices, simplex_vertices  # noqa: E402


def _scene(N=4, K=12, **kw):
    body = hr.RigidBody(hr.Inertia.quartet(0.5, axis=N, N=N))
    return Scene(body, 0.3 * np.arange(1, N * (N - 1) // 2 + 1), np.linspace(0.0, 6.0, K),
                 points=kw.pop("points", hypercube_vertices(N)), **kw)


def test_frames_hold_the_projection_and_the_invariants():
    scene = _scene(axes=(1, 2, 3, 4))
    fig = scene.to_plotly()
    ref = hr.evaluate_scene(Scene(**{**scene.__dict__, "observables": ("projection", "omega")}))
    assert len(fig.frames) == ref.t.size
    scale = np.max(np.abs(ref.projection[..., :3]))
    for k in (0, 5, ref.t.size - 1):
        pts = fig.frames[k].data[1]
        got = np.column_stack([pts.x, pts.y, pts.z])
        # coordinates are rounded for the page to ~5 significant digits at the body's scale
        assert np.max(np.abs(got - ref.projection[k, :, :3])) <= 1e-4 * scale
        assert np.max(np.abs(np.asarray(pts.marker.color) - ref.projection[k, :, 3])) <= 1e-4 * scale
        # 32 vertices of the 4-cube -> 32 edges, each two end points and a gap
        assert len(fig.frames[k].data[0].x) == 3 * len(body_edges(scene.points, "cube")) == 96
        panel = fig.frames[k].layout.annotations[0].text
        assert f"t = {ref.t[k]:.4g}" in panel
        E = float(scene.rigid_body.energy(scene.omega0))
        assert f"E = {E:.10g}" in panel
        c = scene.rigid_body.casimirs(scene.omega0)
        assert f"c<sub>4</sub> = {c[1]:.10g}" in panel
    # every axis named by its space axis, a title, play/pause, one slider step per time
    sc = fig.layout.scene
    assert (sc.xaxis.title.text, sc.yaxis.title.text, sc.zaxis.title.text) == ("x1", "x2", "x3")
    assert "4-D body" in fig.layout.title.text and "closed-form:quartet" in fig.layout.title.text
    assert [b.label for b in fig.layout.updatemenus[0].buttons] == ["Play", "Pause"]
    assert len(fig.layout.sliders[0].steps) == ref.t.size


def test_edges_auto_and_explicit():
    N = 4
    simplex = _scene(N=N, points=simplex_vertices(N)).to_plotly()
    assert len(simplex.data[0].x) == 3 * (N + 1) * N // 2
    ell = _scene(N=N, points=np.random.default_rng(1).normal(size=(7, N))).to_plotly()
    assert len(ell.data[0].x) == 0
    two = _scene(N=N, points=hypercube_vertices(N)).to_plotly(edges=[(0, 1), (2, 3)])
    assert len(two.data[0].x) == 6
    with pytest.raises(ValueError, match="pairs of point indices"):
        _scene(N=N).to_plotly(edges=[(0, 99)])
    with pytest.raises(ValueError, match="edges"):
        _scene(N=N).to_plotly(edges="ring")


def test_page_is_priced_before_any_work(tmp_path, monkeypatch):
    from hyperrotor.classical import scenes

    def boom(*a, **k):  # the motion must not be computed for a refused page
        raise AssertionError("evaluated before pricing")

    monkeypatch.setattr(scenes, "evaluate_scene", boom)
    scene = _scene(N=10, K=200)  # 1024 points, 5120 edges, 200 frames: ~90 MB
    need = scene_html_bytes(200, 1024, 5120)
    with hr.options(scene_html_max_bytes=int(need / 2)):
        with pytest.raises(hr.BudgetError, match="scene_html_max_bytes"):
            scene.to_html(tmp_path / "big.html")
    assert not list(tmp_path.iterdir())


def test_page_size_estimate(tmp_path):
    scene = _scene(N=5, K=30)
    path = scene.to_html(tmp_path / "s.html")
    size = (tmp_path / "s.html").stat().st_size
    estimate = scene_html_bytes(30, 32, 80)
    assert path == str(tmp_path / "s.html")
    assert 0.8 < size / estimate < 1.25, (size, estimate)
    assert not (tmp_path / "s.html.part").exists()


def test_bad_inputs(tmp_path):
    with pytest.raises(ValueError, match="points"):
        Scene(hr.RigidBody([1.0, 2.0, 3.0]), [0.1, 0.2, 0.3], [0.0, 1.0]).to_plotly()
    with pytest.raises(ValueError, match="3 space axes"):
        _scene(axes=(1, 2)).to_plotly()
    with pytest.raises(TypeError, match="path"):
        _scene().to_html(3)
    with pytest.raises(TypeError, match="auto_play"):
        _scene().to_html(tmp_path / "s.html", auto_play="yes")
    with pytest.raises(ValueError, match="n_points"):
        scene_html_bytes(3, -1, 0)
    # the plain-data layer checks its own inputs
    with pytest.raises(ValueError, match="projection must have shape"):
        projection_figure([0.0, 1.0], np.zeros((3, 4, 3)))
    with pytest.raises(ValueError, match="axes must name"):
        projection_figure([0.0], np.zeros((1, 4, 3)), axes=(1, 2, 3, 4))
    with pytest.raises(TypeError, match="plotly Figure"):
        write_html("not a figure", tmp_path / "x.html")
    assert not list(tmp_path.iterdir())
