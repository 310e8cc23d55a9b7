"""``hyperrotor scene``: the 3D projection of a body rotating in N dimensions, PNG snapshots or a GIF."""
from __future__ import annotations

import argparse

import numpy as np

from hyperrotor import _validate
from hyperrotor.cli._common import (UsageError, add_common, bar, check_budget, check_common, choice_of,
                                    have_matplotlib, int_list, integer, num, number, number_list, usage)
from hyperrotor.cli._files import Outputs, output_file

__all__ = ["configure", "run", "scene_estimate", "SCENE_SHAPES", "SCENE_INERTIAS"]


SCENE_SHAPES = ("cube", "simplex", "ellipsoid")
#: Bodies of ``scene --inertia``.
SCENE_INERTIAS = ("quartet", "equal", "box")
#: Points of the ellipsoid sample of ``scene --shape ellipsoid``.
_ELLIPSOID_POINTS = 400
#: Cost model of ``scene`` (seconds, measured on the shared 2-core machine: --N 12 cube PNG 15.8 s
#: wall against 13.7 s estimated): start-up (imports), per drawn frame, per drawn edge and point of
#: a frame, per frame-plane of the motion, per cube vertex and axis^2 (finding the edges).
_SCENE_COST = {"start": 5.0, "frame_png": 0.35, "frame_gif": 0.1, "edge": 3.5e-5, "point": 1e-5,
               "motion": 2e-7, "cube_edges": 2e-6}
_GIF_FRAME_BYTES = 540 * 480 * 4  # Pillow keeps every RGBA frame until the file is written


def configure(p: argparse.ArgumentParser) -> None:
    p.add_argument("--shape", default="cube", choices=SCENE_SHAPES, type=choice_of(SCENE_SHAPES),
                   help="body points: N-cube vertices (2^N), N-simplex vertices (N+1) or "
                        f"{_ELLIPSOID_POINTS} ellipsoid points (default cube)")
    p.add_argument("--N", default=5, help="dimension of space, >= 3 (default 5)")
    p.add_argument("--inertia", default="quartet", choices=SCENE_INERTIAS, type=choice_of(SCENE_INERTIAS),
                   help="quartet: the paper's eqs. 84-85 (any N), equal: eq. 82, box: solid hyper-box of the "
                        "--sides (generic, no closed form) (default quartet)")
    p.add_argument("--kappa", default=0.5, help="kappa of the quartet inertia (default 0.5)")
    p.add_argument("--axis", default=None, help="distinguished axis of the quartet inertia (default N)")
    p.add_argument("--sides", default=None, help="comma-separated N positive side lengths of the box inertia "
                                                  "(default 1,2,...,N)")
    p.add_argument("--omega", default=None,
                   help="comma-separated initial angular velocity, N(N-1)/2 components in plane order "
                        "(default 0.1, 0.2, ...; write --omega=-1,... for a negative first value)")
    p.add_argument("--lock", default="", help="comma-separated axes whose rotation planes start (and stay) at rest")
    p.add_argument("--axes", default="1,2,3", help="the three space axes drawn (default 1,2,3)")
    p.add_argument("--colour-axis", "--color-axis", default=None, dest="colour_axis", metavar="K",
                   help="space axis whose coordinate colours the points (colour bar); default the first axis "
                        "not in --axes (none when N = 3); 0 for no colour")
    p.add_argument("--t-end", default=20.0, help="duration (default 20)")
    p.add_argument("--frames", default=60,
                   help="number of time samples: GIF frames, or the grid the 6 PNG snapshots are taken from "
                        "(default 60)")
    p.add_argument("--output", default="hyperrotor-scene.png", metavar="FILE",
                   help="FILE.png (6 snapshots) or FILE.gif (animation, one frame per time) "
                        "(default hyperrotor-scene.png; an existing file is kept unless --force)")
    add_common(p, budget=True, memory=True)


def _scene_size(shape: str, N: int) -> tuple[float, float]:
    """Number of body points and of drawn edges (floats: 2^N may be huge)."""
    if shape == "cube":
        n = min(N, 200)  # past 2^200 nothing fits anyway; keeps every estimate a finite float
        return 2.0**n, n * 2.0 ** (n - 1)
    if shape == "simplex":
        return N + 1.0, (N + 1.0) * N / 2
    return float(_ELLIPSOID_POINTS), 0.0


def scene_estimate(shape: str, N: int, frames: int, gif: bool, integrate: bool) -> tuple[float, float]:
    """Memory (bytes) and wall time (s) of ``hyperrotor scene``, estimated from its arguments.

    Memory: body points ``P x N``, the edge list (about 120 bytes per edge as
    Python tuples, plus the cube's grouping ``P x (60 + 40 N)``), the attitudes
    ``K x N^2`` (4 copies) and projections ``K x P x 4`` (2 copies), the drawn
    segments of one frame, and for a GIF every rendered frame (Pillow keeps
    them until the end). Time: :data:`_SCENE_COST`: start-up, per drawn frame,
    edge and point, the cube's edge search, plus the motion (integrated bodies
    cost more).
    """
    P, E = _scene_size(shape, N)
    K = float(frames)
    drawn = K if gif else min(6.0, K)
    memory = (P * N * 8 + E * 120 + (P * (60 + 40 * N) if shape == "cube" else 0)
              + 4 * K * N * N * 8 + 2 * K * P * 4 * 8 + E * 500 + (K * _GIF_FRAME_BYTES if gif else 0))
    frame = _SCENE_COST["frame_gif" if gif else "frame_png"]
    seconds = (_SCENE_COST["start"] + drawn * (frame + E * _SCENE_COST["edge"] + P * _SCENE_COST["point"])
               + K * N * N * _SCENE_COST["motion"] * (50 if integrate else 1)
               + (P * N * N * _SCENE_COST["cube_edges"] if shape == "cube" else 0))
    return memory, seconds


def _scene_check(args: argparse.Namespace):
    """Check every scene argument; returns the derived settings (no heavy work)."""
    from hyperrotor import n_planes, planes

    check_common(args)
    N = integer(args.N, "--N", minimum=3)
    frames = integer(args.frames, "--frames", minimum=2)
    t_end = usage(_validate.positive, "--t-end", number(args.t_end, "--t-end"))
    n = n_planes(N) if N < 10**5 else N * (N - 1) // 2
    axes = int_list(args.axes, "--axes")
    if len(axes) != 3 or len(set(axes)) != 3 or not all(1 <= k <= N for k in axes):
        raise UsageError(f"--axes must be three different axes in 1..{N}, got {args.axes!r}")
    colour_axis = args.colour_axis
    if colour_axis is None:
        colour_axis = next((k for k in range(1, N + 1) if k not in axes), 0)
    else:
        colour_axis = integer(colour_axis, "--colour-axis", minimum=0, maximum=N)
        if colour_axis in axes:
            raise UsageError(f"--colour-axis {colour_axis} is one of the drawn --axes {args.axes!r}; "
                             f"choose an axis in 1..{N} not drawn, or 0 for no colour")
    lock = int_list(args.lock, "--lock")
    bad = [k for k in lock if not 1 <= k <= N]
    if bad:
        raise UsageError(f"--lock axes must be in 1..{N}, got {_validate.fmt(bad)}")
    kappa, axis = None, None
    if args.inertia == "quartet":
        kappa = number(args.kappa, "--kappa")
        axis = N if args.axis is None else integer(args.axis, "--axis", minimum=1, maximum=N)
    elif args.axis is not None:
        raise UsageError(f"--axis applies to --inertia quartet only, got --inertia {args.inertia}")
    if args.sides is not None and args.inertia != "box":
        raise UsageError(f"--sides applies to --inertia box only, got --inertia {args.inertia}")
    gif = args.output.lower().endswith(".gif")
    memory, seconds = scene_estimate(args.shape, N, frames, gif, args.inertia == "box" or bool(lock))
    P, E = _scene_size(args.shape, N)
    count = f"2^{N} points, {N} x 2^{N - 1} edges" if args.shape == "cube" and N > 30 else f"{P:.4g} points, {E:.4g} edges"
    what = f"scene --N {N} --shape {args.shape} ({count}, {frames} frames)"
    hint = "use a smaller --N" + (", --shape simplex" if args.shape == "cube" else "") + " or fewer --frames"
    check_budget(args, what, seconds, memory, hint)
    sides = None
    if args.inertia == "box":
        sides = np.arange(1.0, N + 1) if args.sides is None else number_list(args.sides, "--sides", N, positive=True)
    omega = 0.1 * np.arange(1, n + 1) if args.omega is None else number_list(args.omega, "--omega")
    if omega.shape != (n,):
        raise UsageError(f"--omega needs N(N-1)/2 = {n} components for N = {N}, got {omega.size}")
    omega = np.where([any(k in p for k in lock) for p in planes(N)], 0.0, omega)
    return {"N": N, "frames": frames, "t_end": t_end, "axes": axes, "colour_axis": colour_axis or None,
            "sides": sides, "omega": omega, "gif": gif, "seconds": seconds, "kappa": kappa, "axis": axis}


def run(args: argparse.Namespace) -> int:
    from hyperrotor import Inertia, RigidBody
    from hyperrotor.classical.scenes import Scene, ellipsoid_points, hypercube_vertices, simplex_vertices

    s = _scene_check(args)
    if not have_matplotlib():
        raise UsageError("scene needs matplotlib: pip install 'hyperrotor[viz]'")
    N = s["N"]
    with Outputs() as outs:
        out = outs.add(usage(output_file, args.output, option="--output", suffixes=(".png", ".gif"),
                              force=args.force))
        if args.inertia == "quartet":
            inertia = usage(Inertia.quartet, s["kappa"], axis=s["axis"], N=N)
        elif args.inertia == "equal":
            inertia = Inertia.equal(N, 1.0)
        else:
            inertia = usage(Inertia.box, 1.0, s["sides"])
        # --- work ------------------------------------------------------------------
        from hyperrotor.plotting import body_edges, save_projection_animation, save_projection_frames

        points = {"cube": lambda: hypercube_vertices(N),
                  "simplex": lambda: simplex_vertices(N),
                  "ellipsoid": lambda: ellipsoid_points(np.linspace(1.0, 0.4, N), _ELLIPSOID_POINTS, rng=0)}[
            args.shape]()
        t = np.linspace(0.0, s["t_end"], s["frames"])
        proj_axes = tuple(s["axes"]) + ((s["colour_axis"],) if s["colour_axis"] else ())
        scene = Scene(RigidBody(inertia), s["omega"], t, observables=("projection",), points=points, axes=proj_axes,
                      progress=args.progress)  # a bar while an integrated motion is computed
        res = scene.evaluate()
        edges = body_edges(points, "points" if args.shape == "ellipsoid" else args.shape)
        title = (f"{args.shape} in {N}D, {args.inertia} inertia: space axes {', '.join(map(str, s['axes']))} drawn"
                 + (f", colour = x{s['colour_axis']}" if s["colour_axis"] else ""))
        n_drawn = len(t) if s["gif"] else min(6, len(t))
        with bar(args, n_drawn, f"scene: drawing {'GIF frames' if s['gif'] else 'snapshots'}", "frame") as pbar:
            kw = dict(title=title, axes_labels=s["axes"], colour_axis=s["colour_axis"], progress=pbar.update)
            if s["gif"]:
                save_projection_animation(out.tmp, res.t, res.projection, edges, **kw)
            else:
                save_projection_frames(out.tmp, res.t, res.projection, edges, format="png", **kw)
        outs.commit()
    print(f"scene: {len(points)} body points, {len(edges)} edges, {len(res.t)} times in [0, {num(s['t_end'], 6)}], "
          f"route {res.path!r} ({res.stats['wall_time']:.3f} s)")
    print(f"written: {out.path}")
    return 0
