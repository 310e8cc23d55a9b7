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
