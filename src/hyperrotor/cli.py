"""The ``hyperrotor`` command line.

One function pair per subcommand (``_configure_<name>(parser)`` adds its
options, ``_run_<name>(args) -> int`` does the work), registered in
:data:`SUBCOMMANDS`. To add a subcommand, write the pair and add one
:class:`Subcommand` entry to the table.

Subcommands
-----------
``demo``
    The 5D Euler equations (28)-(37) of the paper's quartet body (eqs. 84-85)
    and its invariants on a sample angular velocity.
"""
from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

__all__ = ["main", "build_parser", "Subcommand", "SUBCOMMANDS"]


@dataclass(frozen=True)
class Subcommand:
    """A registered subcommand: its help text, option set-up and action."""

    help: str
    configure: Callable[[argparse.ArgumentParser], None]
    run: Callable[[argparse.Namespace], int]


# ----------------------------------------------------------------------------
# demo
# ----------------------------------------------------------------------------
#: Sample angular velocity of ``hyperrotor demo`` (plane order 12, 13, ..., 45).
DEMO_OMEGA = tuple(round(0.1 * k, 1) for k in range(1, 11))


def _configure_demo(p: argparse.ArgumentParser) -> None:
    p.add_argument("--kappa", default="1/2",
                   help="kappa of the quartet body, I = 1 + kappa^2 on planes with the axis (default 1/2; "
                        "fractions are kept exact)")
    p.add_argument("--axis", type=int, default=5, help="distinguished axis of the quartet body (default 5)")
    p.add_argument("--convention", default="paper", choices=("paper", "standard"),
                   help="matrix convention of the printed equations (default: paper, eq. 21)")
    p.add_argument("--omega", default=None,
                   help="comma-separated 10 angular velocity components in plane order "
                        f"(default {','.join(map(str, DEMO_OMEGA))})")
    p.add_argument("--ascii", action="store_true", help="ASCII instead of Unicode pretty printing")
    p.add_argument("--t-end", type=float, default=200.0,
                   help="length of the simulated motion, closed form vs numerical (default 200)")
    p.add_argument("--png", default="hyperrotor-demo.png",
                   help="where to write the PNG of the motion (default ./hyperrotor-demo.png; needs matplotlib)")
    p.add_argument("--no-png", action="store_true", help="do not write the PNG")


def _parse_number(text: str):
    import sympy as sp

    try:
        value = sp.nsimplify(sp.sympify(text, rational=True))
    except (sp.SympifyError, TypeError, SyntaxError):
        raise ValueError(f"not a number: {text!r}") from None
    if not value.is_real:
        raise ValueError(f"not a real number: {text!r}")
    return value


def _pretty_block(label: str, expr, use_unicode: bool) -> str:
    import sympy as sp

    lines = sp.pretty(expr, use_unicode=use_unicode, wrap_line=False).splitlines()
    mid = len(lines) // 2
    pad = " " * (len(label) + 2)
    return "\n".join((label + "  " if k == mid else pad) + line for k, line in enumerate(lines))


def _fmt(x) -> str:
    return repr(float(x))


def _run_demo(args: argparse.Namespace) -> int:
    import sympy as sp

    from hyperrotor import Inertia, RigidBody, planes

    try:
        kappa = _parse_number(args.kappa)
    except ValueError as err:
        print(f"hyperrotor demo: --kappa: {err}", file=sys.stderr)
        return 2
    if args.omega is None:
        omega = np.array(DEMO_OMEGA, dtype=float)
    else:
        try:
            omega = np.array([float(v) for v in args.omega.split(",")])
        except ValueError:
            print(f"hyperrotor demo: --omega must be 10 comma-separated numbers, got {args.omega!r}",
                  file=sys.stderr)
            return 2
        if omega.shape != (10,):
            print(f"hyperrotor demo: --omega needs 10 components, got {omega.size}", file=sys.stderr)
            return 2
    try:
        inertia = Inertia.quartet(kappa, axis=args.axis, N=5)
    except (TypeError, ValueError) as err:
        print(f"hyperrotor demo: {err}", file=sys.stderr)
        return 2
    body = RigidBody(inertia, args.convention)
    enc = (getattr(sys.stdout, "encoding", None) or "").lower()
    use_unicode = not args.ascii and enc.replace("-", "") in ("utf8", "utf16", "utf32")

    out = []
    first = "84-85" if args.axis == 5 else {4: "111", 3: "112", 2: "113", 1: "114"}.get(args.axis, "?")
    out.append(f"hyperrotor demo: Euler equations of a rigid body in 5D")
    out.append(f"body: the paper's quartet inertia (eq. {first}), kappa = {kappa}, distinguished axis {args.axis}")
    out.append("moments I_ij (physical plane moments, L^ij = I_ij w_ij):")
    out.append("  " + ", ".join(f"I_{i}{j} = {v}" for (i, j), v in zip(planes(5), inertia.symbolic_moments)))
    J = inertia.mass_tensor
    out.append("mass tensor J (I_ij = J_i + J_j): (" + ", ".join(str(sp.nsimplify(v)) for v in J) + ")"
               + f"; physical body: {inertia.is_physical()}")
    if args.convention == "paper":
        out.append("convention: paper (checkerboard matrices, eq. 21); each equation is the (i, j) entry of")
        out.append("  dL/dt - (wL - Lw) = m~, i.e. (-1)^(i+j) (I_ij dw_ij/dt - rhs_ij) = m~^ij, eqs. (28)-(37)")
    else:
        out.append("convention: standard (plain antisymmetric matrices); I_ij dw_ij/dt - rhs_ij = m_ij")
    out.append("")
    for k, eq in enumerate(body.euler_equations()):
        i, j = body.planes[k]
        label = f"({28 + k})" if args.convention == "paper" else f"[{i}{j}]"
        out.append(_pretty_block(label, eq, use_unicode))
        out.append("")
    L = body.angular_momentum(omega)
    cas = body.casimirs(omega)
    man = body.manakov_integrals(omega, 1.0)
    out.append("sample angular velocity (plane order " + " ".join(f"{i}{j}" for i, j in planes(5)) + "):")
    out.append("  omega = [" + ", ".join(_fmt(v) for v in omega) + "]")
    out.append("invariants at omega (torque-free motion conserves all of them):")
    out.append(f"  energy E = 1/2 sum I_ij w_ij^2 = {_fmt(body.energy(omega))}")
    out.append(f"  Casimir c_2 = sum (L^ij)^2 = {_fmt(cas[0])}")
    out.append(f"  Casimir c_4 (lambda^1 coefficient of det(lambda - L)) = {_fmt(cas[1])}")
    for k, v in enumerate(man, start=2):
        out.append(f"  Manakov tr((L + J^2)^{k}) = {_fmt(v)}")
    out.append("  L = [" + ", ".join(_fmt(v) for v in L) + "]")
    out.append("  d omega/dt = [" + ", ".join(_fmt(v) for v in body.rhs(omega)) + "]")
    out.append("")
    if not np.isfinite(args.t_end) or args.t_end <= 0:
        print(f"hyperrotor demo: --t-end must be a positive number, got {args.t_end}", file=sys.stderr)
        return 2
    motion = _demo_motion(body, float(kappa), args.axis, omega, args.t_end)
    out.extend(motion["lines"])
    png = None if args.no_png else _demo_png(motion, args.png, out)
    out.append("")
    steady = [f"{i}{j}" for (i, j), r in zip(planes(5), body.rhs(omega)) if r == 0.0]
    out.append("summary: 10 coupled Euler equations; the six planes without axis "
               f"{args.axis} have constant omega for this body ({', '.join(steady)} have dw/dt = 0 here);")
    out.append("  invariants: energy, 2 Casimirs (eq. 38; the energy is not one of them), "
               "Manakov traces (mass-tensor body).")
    out.append(f"  motion: closed form (eqs. 96-110, corrected signs) vs Lie-Poisson splitting (order 8) and "
               f"scipy DOP853 over t in [0, {args.t_end:g}]" + (f"; picture: {png}" if png else "") + ".")
    print("\n".join(out))
    return 0


def _demo_motion(body, kappa: float, axis: int, omega, t_end: float) -> dict:
    """Closed form vs numerical motion of the quartet body; returns data and report lines."""
    import time

    from hyperrotor import simulate
    from hyperrotor.classical.closed_form import quartet_frequencies, quartet_solution

    t = np.linspace(0.0, t_end, 2001)
    exact = quartet_solution(kappa, omega, t, axis=axis)
    scale = float(np.max(np.abs(omega)))
    lines = [f"motion over t in [0, {t_end:g}] (2001 output times), reference: closed form (eqs. 96-110):"]
    freqs = quartet_frequencies(kappa, omega, axis=axis)
    lines.append("  frequencies Omega_1, Omega_2 (after eq. 118) = [" + ", ".join(_fmt(v) for v in freqs) + "]")
    runs = {}
    start = time.perf_counter()
    simulate(body, omega, t[:2], method="splitting8", dt=t[1])  # numba: compile, or load from the disk cache
    lines.append(f"  (first splitting call, compiling or loading the numba kernel: {time.perf_counter() - start:.2f} s; "
                 "the wall times below exclude it)")
    for name, kw in (("splitting8", {"rtol": 1e-12}), ("DOP853", {"rtol": 1e-10})):
        start = time.perf_counter()
        traj = simulate(body, omega, t, method=name, **kw)
        wall = time.perf_counter() - start
        err = float(np.max(np.abs(traj.omega - exact))) / scale
        E = body.energy(traj.omega)
        c2 = np.sum(traj.L**2, axis=-1)
        runs[name] = traj
        lines.append(f"  {name:<10} rtol={kw['rtol']:.0e}: max relative error vs closed form = {err:.3e}, "
                     f"energy drift = {float(np.max(np.abs(E / E[0] - 1))):.2e}, "
                     f"Casimir c_2 drift = {float(np.max(np.abs(c2 / c2[0] - 1))):.2e}, wall time {wall:.3f} s")
    return {"t": t, "exact": exact, "runs": runs, "lines": lines, "axis": axis, "kappa": kappa}


def _demo_png(motion: dict, path: str, out: list) -> str | None:
    """Plot the oscillating components (closed form and numerical) and the energy error to ``path``."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        out.append("PNG skipped: matplotlib is not installed (pip install 'hyperrotor[viz]').")
        return None
    from hyperrotor import planes

    t, exact, traj = motion["t"], motion["exact"], motion["runs"]["splitting8"]
    axis = motion["axis"]
    osc = [k for k, p in enumerate(planes(5)) if axis in p]
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 6.5), sharex=True, height_ratios=(3, 1.4))
    for k in osc:
        i, j = planes(5)[k]
        line, = ax1.plot(t, exact[:, k], lw=1.2, label=f"$\\omega_{{{i}{j}}}$ closed form")
        ax1.plot(t[::40], traj.omega[::40, k], "o", ms=3, color=line.get_color())
    ax1.set_ylabel("angular velocity")
    ax1.set_title(f"5D quartet body (kappa = {motion['kappa']:g}, axis {axis}): lines closed form, "
                  "dots splitting8", fontsize=10)
    ax1.legend(ncol=4, fontsize=8, loc="upper right")
    for name, traj_k in motion["runs"].items():
        err = np.max(np.abs(traj_k.omega - exact), axis=-1)
        ax2.semilogy(t[1:], np.maximum(err[1:], 1e-17), lw=1, label=name)
    ax2.set_xlabel("t")
    ax2.set_ylabel("max |error|")
    ax2.legend(fontsize=8)
    fig.tight_layout()
    try:
        fig.savefig(path, dpi=110)
    except OSError as err:
        out.append(f"PNG not written: {err}")
        return None
    finally:
        plt.close(fig)
    out.append(f"PNG of the motion written to {path}")
    return path


# ----------------------------------------------------------------------------
# scene
# ----------------------------------------------------------------------------
def _int_list(text: str, what: str) -> list[int]:
    try:
        return [int(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise ValueError(f"{what} must be comma-separated integers, got {text!r}") from None


def _float_list(text: str, what: str) -> np.ndarray:
    try:
        return np.array([float(v) for v in text.split(",") if v.strip()])
    except ValueError:
        raise ValueError(f"{what} must be comma-separated numbers, got {text!r}") from None


def _configure_scene(p: argparse.ArgumentParser) -> None:
    p.add_argument("--shape", default="cube", choices=("cube", "simplex", "ellipsoid"),
                   help="body points: N-cube vertices, N-simplex vertices or ellipsoid points (default cube)")
    p.add_argument("--N", type=int, default=5, help="dimension of space (default 5)")
    p.add_argument("--inertia", default="quartet", choices=("quartet", "equal", "box"),
                   help="quartet: the paper's eqs. 84-85 (any N), equal: eq. 82, box: solid hyper-box of the "
                        "--sides (generic, no closed form) (default quartet)")
    p.add_argument("--kappa", type=float, default=0.5, help="kappa of the quartet inertia (default 0.5)")
    p.add_argument("--axis", type=int, default=None, help="distinguished axis of the quartet inertia (default N)")
    p.add_argument("--sides", default=None, help="comma-separated side lengths of the box inertia (default 1..N)")
    p.add_argument("--omega", default=None,
                   help="comma-separated initial angular velocity, N(N-1)/2 components in plane order "
                        "(default 0.1, 0.2, ...)")
    p.add_argument("--lock", default="", help="comma-separated axes whose rotation planes start (and stay) at rest")
    p.add_argument("--axes", default="1,2,3", help="the three space axes of the projection (default 1,2,3)")
    p.add_argument("--t-end", type=float, default=20.0, help="duration (default 20)")
    p.add_argument("--frames", type=int, default=60, help="number of time samples (default 60)")
    p.add_argument("--output", default="hyperrotor-scene.png",
                   help="PNG (grid of snapshots) or GIF (animation) file (default hyperrotor-scene.png)")


def _scene_setup(args: argparse.Namespace):
    from hyperrotor import Inertia, RigidBody, n_planes
    from hyperrotor.classical.scenes import Scene, ellipsoid_points, hypercube_vertices, simplex_vertices

    N = args.N
    if N < 3:
        raise ValueError(f"--N must be >= 3 for a 3D projection, got {N}")
    if args.inertia == "quartet":
        inertia = Inertia.quartet(args.kappa, axis=N if args.axis is None else args.axis, N=N)
    elif args.inertia == "equal":
        inertia = Inertia.equal(N, 1.0)
    else:
        sides = np.arange(1.0, N + 1) if args.sides is None else _float_list(args.sides, "--sides")
        inertia = Inertia.box(1.0, sides)
    n = n_planes(N)
    omega = 0.1 * np.arange(1, n + 1) if args.omega is None else _float_list(args.omega, "--omega")
    if omega.shape != (n,):
        raise ValueError(f"--omega needs N(N-1)/2 = {n} components for N = {N}, got {omega.size}")
    lock = _int_list(args.lock, "--lock")
    bad = [k for k in lock if not 1 <= k <= N]
    if bad:
        raise ValueError(f"--lock axes must be in 1..{N}, got {bad}")
    from hyperrotor import planes

    omega = np.where([any(k in p for k in lock) for p in planes(N)], 0.0, omega)
    axes = _int_list(args.axes, "--axes")
    if len(axes) != 3 or len(set(axes)) != 3 or not all(1 <= k <= N for k in axes):
        raise ValueError(f"--axes must be three different axes in 1..{N}, got {args.axes!r}")
    if args.frames < 2:
        raise ValueError(f"--frames must be >= 2, got {args.frames}")
    if not np.isfinite(args.t_end) or args.t_end <= 0:
        raise ValueError(f"--t-end must be a positive number, got {args.t_end}")
    points = {"cube": lambda: hypercube_vertices(N),
              "simplex": lambda: simplex_vertices(N),
              "ellipsoid": lambda: ellipsoid_points(np.linspace(1.0, 0.4, N), 400)}[args.shape]()
    t = np.linspace(0.0, args.t_end, args.frames)
    scene = Scene(RigidBody(inertia), omega, t, observables=("projection",), points=points, axes=axes)
    return scene, points, axes


def _run_scene(args: argparse.Namespace) -> int:
    from hyperrotor.plotting import body_edges, save_projection_animation, save_projection_frames

    if not args.output.lower().endswith((".png", ".gif")):
        print(f"hyperrotor scene: --output must end in .png or .gif, got {args.output!r}", file=sys.stderr)
        return 2
    try:
        scene, points, axes = _scene_setup(args)
    except (TypeError, ValueError) as err:
        print(f"hyperrotor scene: {err}", file=sys.stderr)
        return 2
    res = scene.evaluate()
    edges = body_edges(points, "points" if args.shape == "ellipsoid" else args.shape)
    title = f"{args.shape} in {args.N}D, {args.inertia} inertia, projection on axes {tuple(axes)}"
    try:
        if args.output.lower().endswith(".gif"):
            print(f"rendering {len(res.t)} frames ...", file=sys.stderr)
            save_projection_animation(args.output, res.t, res.projection, edges, title=title, axes_labels=axes)
        else:
            save_projection_frames(args.output, res.t, res.projection, edges, title=title, axes_labels=axes)
    except ImportError as err:
        print(f"hyperrotor scene: {err}", file=sys.stderr)
        return 1
    print(f"scene: {len(points)} body points, {len(res.t)} times in [0, {args.t_end:g}], "
          f"route {res.path!r} ({res.stats['wall_time']:.3f} s)")
    print(f"written: {args.output}")
    return 0


# ----------------------------------------------------------------------------
# bench
# ----------------------------------------------------------------------------
def _configure_bench(p: argparse.ArgumentParser) -> None:
    from hyperrotor.bench import BENCH_PROBLEMS

    p.add_argument("--problem", action="append", choices=BENCH_PROBLEMS,
                   help="problem with an exact solution (repeatable; default: all)")
    p.add_argument("--method", action="append", default=None,
                   help="splitting2, splitting4, splitting6, splitting8, moser-veselov, DOP853 or RK45 "
                        "(repeatable; default: all)")
    p.add_argument("--repeats", type=int, default=2, help="timed repeats per run, best kept (default 2)")
    p.add_argument("--error", type=float, default=1e-10,
                   help="error level at which the speed-up over DOP853 is reported (default 1e-10)")
    p.add_argument("--output", default="hyperrotor-bench",
                   help="file stem of the CSV and PNG written (default ./hyperrotor-bench)")


def _run_bench(args: argparse.Namespace) -> int:
    from hyperrotor.bench import _main_table, plot_work_precision, speedup_at, work_precision, write_csv

    problems = args.problem or ["quartet", "euler-poinsot"]
    points = []
    try:
        for prob in problems:
            points += work_precision(prob, args.method, repeats=args.repeats,
                                     progress=lambda msg: print(msg, file=sys.stderr, flush=True))
    except ValueError as err:
        print(f"hyperrotor bench: {err}", file=sys.stderr)
        return 2
    _main_table(points)
    for prob in problems:
        s = speedup_at([p for p in points if p.problem == prob], args.error)
        if s is None:
            print(f"{prob}: no pair of runs reaches error <= {args.error:g} (ours and DOP853)")
        else:
            print(f"{prob}: at error <= {args.error:g} {s['method']} takes {s['seconds']:.4f} s, "
                  f"DOP853 {s['peer_seconds']:.4f} s: {s['ratio']:.1f}x faster")
    csv_path = write_csv(points, args.output + ".csv")
    print(f"written: {csv_path}")
    try:
        print(f"written: {plot_work_precision(points, args.output + '.png')}")
    except ImportError as err:
        print(f"PNG skipped: {err}")
    return 0


def _verify_module():
    from hyperrotor.paper import verify

    return verify


# ----------------------------------------------------------------------------
# registry and entry point
# ----------------------------------------------------------------------------
#: name -> Subcommand. Add new subcommands here.
SUBCOMMANDS: dict[str, Subcommand] = {
    "demo": Subcommand(
        help="print the 5D Euler equations (28)-(37) of the paper's quartet body and its invariants",
        configure=_configure_demo,
        run=_run_demo,
    ),
    "verify": Subcommand(
        help="check the preprint equation by equation (holds / typo / claim-false / not-checkable)",
        configure=lambda p: _verify_module().configure_parser(p),
        run=lambda a: _verify_module().run_from_args(a),
    ),
    "bench": Subcommand(
        help="quick work-precision run (wall time vs error against closed forms), CSV + PNG",
        configure=_configure_bench,
        run=_run_bench,
    ),
    "scene": Subcommand(
        help="render the 3D projection of a body rotating in N dimensions to PNG (snapshots) or GIF",
        configure=_configure_scene,
        run=_run_scene,
    ),
}


def build_parser() -> argparse.ArgumentParser:
    """The ``hyperrotor`` argument parser with every registered subcommand."""
    from hyperrotor import __version__

    parser = argparse.ArgumentParser(
        prog="hyperrotor",
        description="Rigid rotation in N dimensions, classical and quantum.",
    )
    parser.add_argument("--version", action="version", version=f"hyperrotor {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for name, cmd in SUBCOMMANDS.items():
        p = sub.add_parser(name, help=cmd.help, description=cmd.help)
        cmd.configure(p)
        p.set_defaults(_run=cmd.run)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run ``hyperrotor`` with ``argv`` (default ``sys.argv[1:]``); returns the exit code."""
    args = build_parser().parse_args(argv)
    return int(args._run(args))


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
