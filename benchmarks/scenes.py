"""Benchmark: scenes evaluated with the least work vs the full computation.

For each scene the minimal route of :func:`hyperrotor.classical.scenes.evaluate_scene`
(invariants, locked-subspace reduction, closed forms, no attitude unless
asked) is timed against the full route (``minimal=False``: whole body,
attitude always integrated, every observable from the trajectory), once with
the package's own integrator (``method="auto"``, a Lie-Poisson splitting) and
once with the scipy peer (``method="DOP853"``), all at ``rtol = 1e-10``.
The largest deviation between the minimal and the full (auto) results, relative
to the largest value, is reported beside the times (the minimal route is exact
where it uses closed forms or invariants, so the deviation measures the error of
the full integration).

Times are the best of ``--repeat`` runs after one warm-up run (numba caches
compiled kernels on disk; the warm-up removes compile and import costs).

A second table prices the interactive page (``Scene.to_html``, plotly) against the GIF of
the same frames (``hyperrotor.plotting.save_projection_animation``, the peer): wall time
and file size, and the page size estimated before any work (``scene_html_bytes``, the
figure the budget ``scene_html_max_bytes`` is checked against) next to the measured one.

Writes benchmarks/results/scenes.csv, scenes_html.csv and scenes.png.

Usage: python benchmarks/scenes.py [--quick] [--repeat R]
"""
from __future__ import annotations

import argparse
import os
import time

import numpy as np

from hyperrotor.bench import best_of, write_csv

import hyperrotor
from hyperrotor.classical import Scene, evaluate_scene, hypercube_vertices, simplex_vertices
from hyperrotor.conventions import plane_index, planes

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")
FIELDS = ("omega", "L", "energy", "casimirs", "attitude", "projection")


def _scenes(t):
    rng = np.random.default_rng(7)
    gen5 = rng.uniform(1.0, 3.0, size=10)
    w = rng.normal(size=10)
    w3 = np.zeros(10)
    for p in [(1, 2), (1, 3), (2, 3)]:
        w3[plane_index(p, 5)] = rng.normal()
    w4 = w.copy()
    w4[[plane_index(p, 5) for p in planes(5) if 5 in p]] = 0.0
    N8 = 8
    return [
        ("5D quartet (axis 3), omega", Scene(hyperrotor.Inertia.quartet(0.5, axis=3, N=5), w, t, observables=("omega",))),
        ("8D one-axis body, omega + energy", Scene(hyperrotor.Inertia.quartet(0.5, axis=8, N=N8),
                                                   rng.normal(size=N8 * (N8 - 1) // 2), t, observables=("omega", "energy"))),
        ("5D generic, energy + casimirs", Scene(gen5, w, t, observables=("energy", "casimirs"))),
        ("5D generic, omega in locked 3D subspace", Scene(gen5, w3, t, observables=("omega",))),
        ("5D generic, omega only", Scene(gen5, w, t, observables=("omega",))),
        ("5D generic, axis 5 locked, 5-cube -> (1,2,3)", Scene(gen5, w4, t, observables=("projection",),
                                                               points=hypercube_vertices(5), axes=(1, 2, 3))),
        ("5D quartet (axis 5), 5-cube -> (1,2,3)", Scene(hyperrotor.Inertia.quartet(0.5, axis=5, N=5), w, t,
                                                         observables=("projection",), points=hypercube_vertices(5),
                                                         axes=(1, 2, 3))),
        ("5D equal moments, 5-simplex -> (1,2,3)", Scene(np.full(10, 2.0), w, t, observables=("projection",),
                                                         points=simplex_vertices(5), axes=(1, 2, 3))),
    ]


def _deviation(a, b):
    dev = 0.0
    for f in FIELDS:
        x, y = getattr(a, f), getattr(b, f)
        if x is not None:
            dev = max(dev, float(np.max(np.abs(x - y))) / max(1e-300, float(np.max(np.abs(y)))))
    return dev


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="shorter time span and fewer repeats")
    ap.add_argument("--repeat", type=int, default=None)
    args = ap.parse_args(argv)
    T_end, K = (50.0, 501) if args.quick else (200.0, 2001)
    repeat = args.repeat or (2 if args.quick else 3)
    t = np.linspace(0.0, T_end, K)
    rows = []
    print(f"scenes over t in [0, {T_end:g}] with {K} output times, rtol = 1e-10, best of {repeat}")
    head = f"{'scene':46s} {'minimal path':48s} {'min [s]':>9s} {'full [s]':>9s} {'DOP853 [s]':>10s} {'x full':>8s} {'x DOP853':>9s} {'rel. dev':>9s}"
    print(head)
    print("-" * len(head))
    for name, sc in _scenes(t):
        tm, a = best_of(lambda: evaluate_scene(sc), repeat, warmup=True)
        tf, b = best_of(lambda: evaluate_scene(sc, minimal=False), repeat, warmup=True)
        sc_d = Scene(**{**sc.__dict__, "method": "DOP853"})
        td, _ = best_of(lambda: evaluate_scene(sc_d, minimal=False), max(1, repeat - 1), warmup=True)
        dev = _deviation(a, b)
        rows.append(dict(scene=name, path=a.path, t_minimal=tm, t_full=tf, t_full_dop853=td,
                         ratio_full=tf / tm, ratio_dop853=td / tm, rel_deviation=dev))
        print(f"{name:46s} {a.path:48s} {tm:9.4f} {tf:9.4f} {td:10.4f} {tf / tm:8.1f} {td / tm:9.1f} {dev:9.1e}")
    os.makedirs(RESULTS, exist_ok=True)
    path_csv = write_csv(rows, os.path.join(RESULTS, "scenes.csv"))
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(9, 4.5))
        y = np.arange(len(rows))
        ax.barh(y - 0.2, [r["ratio_full"] for r in rows], height=0.4, label="full (splitting, auto)")
        ax.barh(y + 0.2, [r["ratio_dop853"] for r in rows], height=0.4, label="full (scipy DOP853)")
        ax.set_yticks(y, [r["scene"] for r in rows], fontsize=8)
        ax.set_xscale("log")
        ax.axvline(1.0, color="k", lw=0.8)
        ax.set_xlabel("time(full) / time(minimal)")
        ax.set_title(f"Scenes: saving of the minimal route (t in [0, {T_end:g}], {K} outputs)")
        ax.legend(fontsize=8, loc="lower right")
        fig.tight_layout()
        fig.savefig(os.path.join(RESULTS, "scenes.png"), dpi=120)
    except ImportError:  # pragma: no cover
        print("matplotlib not available: no PNG")
    html_rows = _html_table(args.quick)
    write_csv(html_rows, os.path.join(RESULTS, "scenes_html.csv"))
    print(f"wrote {path_csv}, scenes_html.csv and scenes.png")
    return rows


def _html_table(quick):
    """Interactive page vs GIF of the same frames: wall time, bytes, estimated bytes."""
    import tempfile

    from hyperrotor.classical.scene_html import scene_html_bytes
    from hyperrotor.plotting import body_edges, save_projection_animation

    K = 30 if quick else 60
    print(f"\ninteractive page (Scene.to_html, plotly) vs GIF of the same {K} frames (one run each)")
    head = f"{'body':30s} {'html [s]':>9s} {'gif [s]':>8s} {'x gif':>6s} {'html MB':>8s} {'est. MB':>8s} {'est/meas':>9s} {'gif MB':>7s}"
    print(head)
    print("-" * len(head))
    rows = []
    for N in (4, 6, 8):
        body = hyperrotor.Inertia.quartet(0.5, axis=N, N=N)
        pts = hypercube_vertices(N)
        sc = Scene(body, 0.1 * np.arange(1, N * (N - 1) // 2 + 1), np.linspace(0.0, 20.0, K), points=pts,
                   axes=(1, 2, 3, 4), observables=("projection",))
        edges = body_edges(pts, "cube")
        with tempfile.TemporaryDirectory() as tmp:
            t0 = time.perf_counter()
            sc.to_html(os.path.join(tmp, "s.html"))
            t_html = time.perf_counter() - t0
            size_html = os.path.getsize(os.path.join(tmp, "s.html"))
            t0 = time.perf_counter()
            res = sc.evaluate()
            save_projection_animation(os.path.join(tmp, "s.gif"), res.t, res.projection, edges, colour_axis=4)
            t_gif = time.perf_counter() - t0
            size_gif = os.path.getsize(os.path.join(tmp, "s.gif"))
        est = scene_html_bytes(K, len(pts), len(edges), colour=True)
        rows.append(dict(body=f"{N}-cube", frames=K, points=len(pts), edges=len(edges), t_html=t_html, t_gif=t_gif,
                         html_bytes=size_html, html_estimate=est, gif_bytes=size_gif))
        print(f"{N}-cube ({len(pts)} pts, {len(edges)} edges)".ljust(30)
              + f" {t_html:9.2f} {t_gif:8.2f} {t_gif / t_html:6.1f} {size_html / 1e6:8.2f} {est / 1e6:8.2f}"
              f" {est / size_html:9.2f} {size_gif / 1e6:7.2f}")
    return rows


if __name__ == "__main__":
    main()
