"""``hyperrotor scene``: the 3D projection of a body rotating in N dimensions: PNG snapshots, a GIF or an HTML page.

The interactive page (``--output FILE.html``) is the library's
:meth:`hyperrotor.Scene.to_html` (plotly, self-contained: rotatable and
zoomable 3D view, play/pause, a time slider, the time and the invariants).
Costs are estimated before any work by the library: the drawing by the cost
model ``"scene"`` of :mod:`hyperrotor._pricing`, an integrated motion by
:func:`hyperrotor.classical.simulate.estimate_cost`.
"""
from __future__ import annotations

import argparse

import numpy as np

from hyperrotor import BudgetError, _cost_models, _pricing, _validate
from hyperrotor._options import options
from hyperrotor.cli._common import (CLI_BUDGETS, UsageError, add_common, bar, budget_message, check_budget,
                                    check_common, check_invariants_fit, choice_of, duration_text,
                                    have_matplotlib, have_module, int_list, integer, num, number, number_list,
                                    size_text, unreachable, usage)
from hyperrotor.cli._files import Outputs, output_file
from hyperrotor.cli._signals import checkpoint

__all__ = ["configure", "run", "default_omega", "body_stretch", "SCENE_SHAPES", "SCENE_INERTIAS", "SCENE_FORMATS"]


#: Body points of ``scene --shape``.
SCENE_SHAPES = ("cube", "simplex", "ellipsoid")
#: Bodies of ``scene --inertia``.
SCENE_INERTIAS = ("quartet", "equal", "box")
#: Formats of ``scene --output``, chosen by the file's suffix.
SCENE_FORMATS = (".png", ".gif", ".html")


def configure(p: argparse.ArgumentParser) -> None:
    p.add_argument("--shape", default="cube", choices=SCENE_SHAPES, type=choice_of(SCENE_SHAPES),
                   help="body points: N-cube vertices (2^N), N-simplex vertices (N+1) or "
                        f"{_cost_models.SCENE_ELLIPSOID_POINTS} ellipsoid points, stretched along each axis i by "
                        "sqrt(J_i / max J) (J the body's mass tensor, I_ij = J_i + J_j): the drawn body has the "
                        "simulated body's proportions (default cube)")
    p.add_argument("--N", default=5, help="dimension of space, >= 3 (default 5)")
    p.add_argument("--inertia", default="quartet", choices=SCENE_INERTIAS, type=choice_of(SCENE_INERTIAS),
                   help="quartet: the paper's eqs. 84-85 (any N), equal: eq. 82, box: solid hyper-box of the "
                        "--sides (generic, no closed form) (default quartet)")
    p.add_argument("--kappa", default=None, help="kappa of the quartet inertia (default 0.5)")
    p.add_argument("--axis", default=None, help="distinguished axis of the quartet inertia (default N)")
    p.add_argument("--sides", default=None, help="comma-separated N positive side lengths of the box inertia "
                                                  "(default 1,2,...,N)")
    p.add_argument("--omega", default=None,
                   help="comma-separated initial angular velocity, N(N-1)/2 components in plane order "
                        "(default 0.1, 0.2, ..., 1 for N = 5, and 10/n times 0.1, 0.2, ... for n = N(N-1)/2 > 10 "
                        "planes: max |omega| = 1)")
    p.add_argument("--lock", default="", help="comma-separated axes whose rotation planes start (and stay) at rest "
                                             "(the default --omega is 0 there; a given --omega must be)")
    p.add_argument("--axes", default="1,2,3", help="the three space axes drawn (default 1,2,3)")
    p.add_argument("--colour-axis", "--color-axis", default=None, dest="colour_axis", metavar="K",
                   help="space axis whose coordinate colours the points (colour bar); default the first axis "
                        "not in --axes (none when N = 3); 0 for no colour")
    p.add_argument("--t-end", default=20.0, help="duration (default 20)")
    p.add_argument("--frames", default=60,
                   help="number of time samples: GIF frames, or the grid the 6 PNG snapshots are taken from "
                        "(default 60)")
    p.add_argument("--output", default="hyperrotor-scene.png", metavar="FILE",
                   help="the suffix picks the format: FILE.png (6 snapshots), FILE.gif (animation, one frame per "
                        "time) or FILE.html (interactive page: rotate, zoom, play/pause, time slider, invariants; "
                        "self-contained, opens offline in a browser; needs plotly) "
                        "(default hyperrotor-scene.png; an existing file is kept unless --force)")
    add_common(p, budget=True, memory=True, steps="an integrated motion (--inertia box, --lock)")


#: the least time between two frames: 2^53 times the smallest normal double (times below it are subnormal, with
#: fewer digits: --t-end 1e-320 failed inside the library, "t[0] = 0.0 and t[1] = 1e-323 are the same time")
_LEAST_FRAME_SPACING = 2.0**53 * float(np.finfo(float).tiny)


def _scene_check(args: argparse.Namespace):
    """Check every scene argument; returns the derived settings (no heavy work)."""
    from hyperrotor import n_planes, planes

    check_common(args)
    N = integer(args.N, "--N", minimum=3, maximum=int(options["max_dimension"]))  # (the library's limit of N)
    frames = integer(args.frames, "--frames", minimum=2)
    t_end = usage(_validate.positive, "--t-end", number(args.t_end, "--t-end"))
    if t_end / (frames - 1) < _LEAST_FRAME_SPACING:  # (no allocation: --frames may be refused by the budget below)
        raise UsageError(f"--t-end {num(t_end)} is too short for --frames {frames}: the frames would be "
                         f"{t_end / (frames - 1):.3g} apart, below {_LEAST_FRAME_SPACING:.3g}, where the times lose "
                         "the digits that tell them apart; choose a longer --t-end or fewer --frames")
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
        kappa = 0.5 if args.kappa is None else number(args.kappa, "--kappa")
        axis = N if args.axis is None else integer(args.axis, "--axis", minimum=1, maximum=N)
    else:
        for flag, value in (("--axis", args.axis), ("--kappa", args.kappa)):
            if value is not None:
                raise UsageError(f"{flag} applies to --inertia quartet only, got --inertia {args.inertia}")
    if args.sides is not None and args.inertia != "box":
        raise UsageError(f"--sides applies to --inertia box only, got --inertia {args.inertia}")
    fmt = next((f for f in SCENE_FORMATS if args.output.lower().endswith(f)), ".png")  # others: refused later
    # the drawing's cost model (an integrated motion is priced on its own, _check_motion)
    memory, seconds = (c.amount for c in _pricing.estimate(
        "scene", shape=args.shape, N=N, frames=frames, format=fmt, integrate=args.inertia == "box" or bool(lock),
        colour=bool(colour_axis)))
    import hyperrotor.classical.rigid_body  # noqa: F401 - registers the body's cost model
    body_memory, body_seconds = (c.amount for c in _pricing.estimate("RigidBody", N=N))  # its Euler tables
    memory, seconds = memory + body_memory, seconds + body_seconds
    P, E = _cost_models.scene_size(args.shape, N)
    count = (f"2^{N} points, {N} x 2^{N - 1} edges" if args.shape == "cube" and N > 30
             else f"{P:.4g} points, {E:.4g} edges")
    what = f"scene --N {N} --shape {args.shape} ({count}, {frames} frames)"
    hint = "use a smaller --N" + (", --shape simplex" if args.shape == "cube" else "") + " or fewer --frames"
    check_budget(args, what, seconds, memory, hint)
    sides = None
    if args.inertia == "box":
        sides = np.arange(1.0, N + 1) if args.sides is None else number_list(args.sides, "--sides", N, positive=True)
        if np.any(sides < 1e-50) or np.any(sides > 1e50):  # the moments are their squares: they (and L) must stay
            raise UsageError(f"--sides values must be in [1e-50, 1e50] (the moments are their squares; "  # normal
                             f"omega(t) does not depend on the scale), got {_validate.fmt(sides.tolist())}")
    omega = default_omega(n) if args.omega is None else number_list(args.omega, "--omega")
    if omega.shape != (n,):
        raise UsageError(f"--omega needs N(N-1)/2 = {n} components for N = {N}, got {omega.size}")
    locked = np.array([any(k in p for k in lock) for p in planes(N)], dtype=bool)
    if args.omega is not None and np.any(omega[locked] != 0):
        bad = [f"{'omega_%d%d' % (i, j) if N < 10 else 'omega_(%d,%d)' % (i, j)} = {num(w)}"
               for (i, j), w, b in zip(planes(N), omega, locked) if b and w != 0]
        raise UsageError(f"--omega gives planes of the --lock axes {_validate.fmt(lock)} nonzero values "
                         f"({', '.join(bad[:6])}{', ...' if len(bad) > 6 else ''}): those planes start and stay at "
                         "rest; give 0 there, or leave out --lock")
    omega = np.where(locked, 0.0, omega)
    max_steps = options["max_steps"] if args.max_steps is None else integer(args.max_steps, "--max-steps", minimum=1)
    return {"N": N, "frames": frames, "max_steps": max_steps,
            "t_end": t_end, "axes": axes, "colour_axis": colour_axis or None,
            "sides": sides, "omega": omega, "format": fmt, "seconds": seconds, "memory": memory, "kappa": kappa,
            "axis": axis}


def default_omega(n: int) -> np.ndarray:
    """The default ``--omega`` of ``n`` planes: ``0.1, 0.2, ..., 0.1 n``, scaled to ``max |omega| = 1`` beyond ten
    planes (N > 5: the angular velocities, and the page's invariants, stay of one size at every N)."""
    return 0.1 * np.arange(1, n + 1) * min(1.0, 10.0 / n)


def body_stretch(inertia) -> np.ndarray:
    r"""The stretch ``sqrt(J_i / max J)`` along each axis that gives the drawn body (cube, simplex, sphere: a
    mass tensor proportional to the identity) the simulated body's mass tensor :math:`J` up to a factor
    (:math:`I_{ij} = J_i + J_j`): the box of ``--sides`` in its proportions, the quartet flattened
    (``kappa < 1``) or stretched along its axis, the equal body as it is."""
    J = np.asarray(inertia.mass_tensor, dtype=float)  # (every --inertia is a physical body: J exists, J >= 0)
    return np.sqrt(J / J.max())


def run(args: argparse.Namespace) -> int:
    from hyperrotor import Inertia, RigidBody
    from hyperrotor.classical import (Scene, UnreachableAccuracyError, body_edges, ellipsoid_points,
                                      hypercube_vertices, simplex_vertices)

    s = _scene_check(args)
    fmt = s["format"]
    if fmt == ".html" and not have_module("plotly"):
        raise UsageError("--output FILE.html needs plotly: pip install 'hyperrotor[viz]' (or write .png or .gif)")
    if fmt != ".html" and not have_matplotlib():
        raise UsageError(f"--output FILE{fmt} needs matplotlib: pip install 'hyperrotor[viz]'")
    N = s["N"]
    with Outputs() as outs:
        out = outs.add(usage(output_file, args.output, option="--output", suffixes=SCENE_FORMATS, force=args.force))
        if args.inertia == "quartet":
            inertia = usage(Inertia.quartet, s["kappa"], axis=s["axis"], N=N)
        elif args.inertia == "equal":
            inertia = Inertia.equal(N, 1.0)
        else:
            inertia = usage(Inertia.box, 1.0, s["sides"])
        # the library's memory budgets as large as the command's, which its estimates were checked against
        memory = max(float(options["cli_max_memory"]) if args.max_memory is None else float(args.max_memory),
                     float(options["max_memory_bytes"]), float(options["max_output_bytes"]))
        budgets = {"max_memory_bytes": memory, "max_output_bytes": memory}
        with options(**budgets):
            body = RigidBody(inertia)
        if fmt == ".html":  # the page shows the energy and the Casimirs: they must fit in double precision
            check_invariants_fit("--omega", s["omega"], lambda w: (body.energy(w), body.casimirs(w)),
                                 body_options={"quartet": "--kappa", "box": "--sides"}.get(args.inertia, ""))
        # --- work ------------------------------------------------------------------
        kind = "points" if args.shape == "ellipsoid" else args.shape
        t = np.linspace(0.0, s["t_end"], s["frames"])
        proj_axes = tuple(s["axes"]) + ((s["colour_axis"],) if s["colour_axis"] else ())
        observables = ("projection", "omega") if fmt == ".html" else ("projection",)  # the page shows invariants
        with options(**budgets):
            points = {"cube": lambda: hypercube_vertices(N),
                      "simplex": lambda: simplex_vertices(N),
                      "ellipsoid": lambda: ellipsoid_points(np.ones(N), _cost_models.SCENE_ELLIPSOID_POINTS,
                                                            rng=0)}[args.shape]()
            edges = body_edges(points, kind)  # (of the unstretched shape: a flat body's vertices coincide)
            points *= body_stretch(inertia)
            scene = Scene(body, s["omega"], t, observables=observables, points=points, axes=proj_axes,
                          progress=args.progress)  # a bar while an integrated motion is computed
            with options(max_steps=s["max_steps"]):
                try:
                    _check_motion(args, s, scene)
                    res = scene.evaluate()
                except BudgetError as err:  # the library's advice names Python options; name the CLI's
                    raise UsageError(_budget_message(err, args)) from None
                except UnreachableAccuracyError as err:
                    raise unreachable(err, f"the motion over --t-end {num(s['t_end'])}", "choose a shorter --t-end"
                                      ) from None
        checkpoint()
        title = (f"{args.shape} in {N}D, {args.inertia} inertia: space axes {', '.join(map(str, s['axes']))} drawn"
                 + (f", colour = x{s['colour_axis']}" if s["colour_axis"] else ""))
        if fmt == ".html":
            with options(scene_html_max_bytes=max(float(options["scene_html_max_bytes"]), s["memory"]), **budgets):
                scene.to_html(out.tmp, edges=edges, title=title, result=res)
        else:
            _draw(args, s, out.tmp, res, edges, title)
        outs.commit()
    print(f"scene: {len(points)} body points, {len(edges)} edges, {len(res.t)} times in [0, {num(s['t_end'], 6)}], "
          f"route {res.path!r} ({res.stats['wall_time']:.3f} s)")
    print(f"written: {out.path}")
    return 0


def _draw(args, s: dict, path, res, edges, title: str) -> None:
    """The PNG (6 snapshots) or the GIF (one frame per time), with matplotlib."""
    from hyperrotor.plotting import save_projection_animation, save_projection_frames

    gif = s["format"] == ".gif"
    n_drawn = len(res.t) if gif else min(6, len(res.t))
    with bar(args, n_drawn, f"scene: drawing {'GIF frames' if gif else 'snapshots'}", "frame") as steps:
        kw = dict(title=title, axes_labels=s["axes"], colour_axis=s["colour_axis"], callback=steps.update)
        if gif:
            save_projection_animation(path, res.t, res.projection, edges, **kw)
        else:
            save_projection_frames(path, res.t, res.projection, edges, format="png", **kw)


def _check_motion(args: argparse.Namespace, s: dict, scene) -> None:
    """Price the integrated motion (:func:`hyperrotor.classical.simulate.estimate_cost`) before it runs.

    Every scene comes here; only one whose route integrates is priced
    (:func:`hyperrotor.classical.scenes.scene_route`, decided without any work; the 3D quartet integrates): a
    locked or special body whose route is a closed form (``reduced:axes(2,3,4,5)+closed-form:quartet``) costs no
    integration steps, and a locked body's run is priced on the reduced body it integrates. Adds the
    estimated seconds to the drawing's and checks both budgets (--max-seconds, --max-steps). With ``rtol`` the
    library probes a short leading window (milliseconds for small bodies; held to --max-steps and to the seconds
    the drawing leaves of --max-seconds: at N = 200 each of its steps takes about a second; the first call also
    loads or compiles the kernel). A refusal by the library is a :class:`BudgetError` (the caller words it with
    the command line's options).
    """
    from hyperrotor.classical.scenes import scene_route
    from hyperrotor.classical.simulate import estimate_cost

    path, moments, omega = scene_route(scene)
    if "integrate" not in path.split("+"):
        return
    max_s = args.max_seconds if args.max_seconds is not None else float(options["cli_max_seconds"])
    rtol = options["scene_rtol"] if scene.rtol is None else scene.rtol  # (what evaluate_scene integrates at)
    left = max(max_s - s["seconds"], 0.0)
    try:
        with options(max_seconds=max(left, 1e-9)):  # (the library's set-up models too: at N = 200 about 8 s)
            cost = estimate_cost(moments, omega, scene.t, method=scene.method, rtol=rtol, attitude=True,
                                 max_steps=s["max_steps"], max_seconds=left)
    except BudgetError as err:
        if getattr(err, "option", None) != "max_seconds":
            raise
        raise UsageError(f"scene --t-end {num(s['t_end'])}: {err.what} would need about {duration_text(err.needed)}, "
                         f"over the {duration_text(left)} that --max-seconds {duration_text(max_s)} leaves after the "
                         f"drawing's {duration_text(s['seconds'])}; choose a shorter --t-end or fewer --frames, or "
                         "raise --max-seconds") from None
    what = f"scene --t-end {num(s['t_end'])}"
    if cost.steps is not None and cost.steps > s["max_steps"]:
        raise UsageError(f"{what}: the motion needs about {cost.steps:.3g} integration steps ({cost.method}), "
                         f"over the budget of {s['max_steps']} (--max-steps, default hr.options['max_steps']); "
                         "choose a shorter --t-end, or raise --max-steps (and --max-seconds)")
    check_budget(args, f"{what} ({cost.steps:.3g} integration steps of {cost.method})",
                 s["seconds"] + (cost.seconds or 0.0), hint="choose a shorter --t-end")


#: how a budget of the library is counted, by its option name
_UNITS = {"max_steps": "integration steps", "max_output_bytes": "bytes of output", "max_memory_bytes": "bytes",
          "max_seconds": "s"}


def _budget_message(err: BudgetError, args: argparse.Namespace | None = None) -> str:
    """A library budget refusal of the motion, worded with the command line's options (never the library's
    keyword: ``max_steps`` is ``--max-steps``)."""
    option = getattr(err, "option", None)
    needed, budget = getattr(err, "needed", None), getattr(err, "budget", None)
    flag = CLI_BUDGETS.get(option or "")
    if flag and needed is not None and budget is not None and np.isfinite(needed):
        if option in ("max_output_bytes", "max_memory_bytes"):
            amount, limit = size_text(needed), size_text(budget)
        elif option == "max_seconds":
            amount, limit = duration_text(needed), duration_text(budget)
        else:  # (the unit the library counted in: integration steps, or a scipy method's evaluations)
            unit = getattr(err, "unit", None) or _UNITS[option]  # (set by _pricing.refuse)
            amount, limit = f"{needed:.3g} {unit}", f"{budget:.6g}"
        return (f"the motion needs about {amount}, over the budget of {limit} ({flag}); choose a shorter --t-end "
                f"or fewer --frames, or raise {flag}")
    return budget_message(err, args)
