r"""Body points of the scenes: the vertices of the N-cube and the regular N-simplex, points on an
ellipsoid, and the edges to draw between them (:class:`~hyperrotor.classical.scenes.Scene`'s
``points``, the GIF, PNG and interactive pages of ``hyperrotor scene``)."""
from __future__ import annotations

from typing import Any, Sequence

import numpy as np

from .. import _pricing
from .. import _validate as _v

__all__ = ["hypercube_vertices", "simplex_vertices", "ellipsoid_points", "body_edges"]


def hypercube_vertices(N: int, half_edge: float = 1.0) -> np.ndarray:
    """The ``2**N`` vertices ``(+-half_edge, ..., +-half_edge)`` of the N-cube, shape ``(2**N, N)``.

    Raises ``hyperrotor.BudgetError`` before any allocation when the table (``8 N 2^N`` bytes:
    N = 22 is 738 MB) is over ``hr.options['max_output_bytes']``, or its working memory (about
    twice that) over ``hr.options['max_memory_bytes']``; an N over ``hr.options['max_dimension']``
    is refused too.
    """
    N = _v.dimension(N, minimum=1)
    half_edge = _v.positive("half_edge", half_edge)
    _pricing.check("hypercube_vertices", N=N)  # 2^N rows, priced before the table exists
    bits = (np.arange(2**N)[:, None] >> np.arange(N)[None, ::-1]) & 1
    out = bits.astype(float)  # (in place from here: two tables at the peak, not three)
    del bits
    out *= 2.0
    out -= 1.0
    out *= half_edge
    return out


def simplex_vertices(N: int, circumradius: float = 1.0) -> np.ndarray:
    r"""The ``N + 1`` vertices of a regular N-simplex centred at the origin, shape ``(N + 1, N)``.

    The unit vectors of :math:`\mathbb R^{N+1}` minus their centroid, expressed in an
    orthonormal basis of the hyperplane :math:`\sum x = 0`, scaled to the given
    circumradius; all pairwise distances are equal.
    """
    # an (N + 1) x (N + 1) QR: refuse an absurd N up front (BudgetError over options["max_dimension"])
    N = _v.dimension(N, minimum=1)
    circumradius = _v.positive("circumradius", circumradius)
    E = np.eye(N + 1) - 1.0 / (N + 1)
    Q, _ = np.linalg.qr(E[:, :N])  # orthonormal basis of the sum-zero hyperplane
    V = E @ Q
    return circumradius * V / np.linalg.norm(V[0])


def ellipsoid_points(semi_axes: Sequence[float], n: int, *, rng: Any = 0) -> np.ndarray:
    r"""``n`` points on the ellipsoid :math:`\sum_i x_i^2/a_i^2 = 1`, shape ``(n, N)``.

    Directions uniform on the sphere (normalised Gaussian vectors) scaled by the
    semi-axes. ``rng``: seed, :class:`numpy.random.Generator` or ``None`` for fresh entropy (default
    seed 0, so the points are reproducible).
    """
    a = _v.finite_array("semi_axes", semi_axes, ndim=1)
    if a.size < 2 or np.any(a <= 0):
        raise ValueError(f"semi_axes must be >= 2 finite positive numbers, got {_v.fmt(semi_axes)}")
    n = _v.integer("n", n, minimum=1)
    _pricing.check("ellipsoid_points", n=n, N=a.size)
    gen = _v.rng(rng)
    d = gen.normal(size=(int(n), a.size))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    return d * a


def body_edges(points: np.ndarray, kind: str) -> list[tuple[int, int]]:
    """Edges to draw between body points.

    ``kind="cube"``: pairs of vertices differing in exactly one coordinate
    (the edges of an axis-aligned hypercube, found in ``O(P N^2)`` by grouping
    the vertices on their other coordinates); ``"simplex"``: all pairs;
    ``"points"`` (e.g. an ellipsoid sample): none.
    """
    pts = _v.finite_array("points", points, ndim=2)
    kind = _v.choice("kind", kind, ("cube", "simplex", "points"))
    if kind == "points":
        return []
    n = len(pts)
    _pricing.check("body_edges", pairs=n * (n - 1) // 2 if kind == "simplex" else n * pts.shape[1])
    if kind == "simplex":
        return [(a, b) for a in range(n) for b in range(a + 1, n)]
    if kind == "cube":
        keys = np.round(pts, 9)
        edges = []
        for d in range(pts.shape[1]):
            groups: dict[tuple, list[int]] = {}
            rest = np.delete(keys, d, axis=1)
            for idx, key in enumerate(map(tuple, rest)):
                groups.setdefault(key, []).append(idx)
            _pricing.check("body_edges", pairs=sum(len(m) * (len(m) - 1) // 2 for m in groups.values()))
            for members in groups.values():
                for x, a in enumerate(members):
                    for b in members[x + 1:]:
                        if keys[a, d] != keys[b, d]:
                            edges.append((min(a, b), max(a, b)))
    return sorted(edges)
