"""``hyperrotor demo``: the 5D Euler equations (28)-(37) of the paper's quartet body (eqs. 84-85).

Prints the equations, the invariants on a sample angular velocity, the closed
form against two integrators, and writes a PNG of the motion. The physics is
the library's (:mod:`hyperrotor.demo`); this module reads the options, prints
and writes the file.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from hyperrotor import _validate
from hyperrotor.cli._common import (UsageError, add_common, check_budget, check_common, check_invariants_fit,
                                    choice_of, have_matplotlib, integer, num, number, number_list, nums, unreachable,
                                    usage)
from hyperrotor.cli._files import OutputFile, Outputs, output_file
from hyperrotor.conventions import CONVENTIONS
from hyperrotor.demo import DEMO_OMEGA, quartet_invariants, save_quartet_motion

__all__ = ["configure", "run", "DEMO_PNG"]

#: --t-end's default (the paper's quartet over 200 time units)
DEMO_T_END = 200.0


#: Default PNG of ``hyperrotor demo``.
DEMO_PNG = "hyperrotor-demo.png"


def configure(p: argparse.ArgumentParser) -> None:
    p.add_argument("--kappa", default="1/2",
                   help="kappa of the quartet body, I = 1 + kappa^2 on planes with the axis (default 1/2; "
                        "fractions are kept exact)")
    p.add_argument("--axis", default=5, help="distinguished axis of the quartet body, 1..5 (default 5)")
    p.add_argument("--convention", default="paper", choices=CONVENTIONS, type=choice_of(CONVENTIONS),
                   help="matrix convention of the printed equations (default: paper, eq. 21)")
    p.add_argument("--omega", default=None,
                   help="comma-separated 10 angular velocity components in plane order "
                        f"(default {','.join(map(str, DEMO_OMEGA))})")
    p.add_argument("--ascii", action="store_true", help="ASCII instead of Unicode pretty printing")
    p.add_argument("--t-end", default=DEMO_T_END,
                   help=f"length of the simulated motion, closed form vs numerical (default {DEMO_T_END:g})")
    p.add_argument("--png", default=None, metavar="FILE.png",
                   help=f"where to write the PNG of the motion (needs matplotlib). Default ./{DEMO_PNG}, the "
                        "demo's own file: an earlier demo picture there is replaced, so the command can be run "
                        "again. A FILE given here that exists is kept unless --force")
    p.add_argument("--no-png", action="store_true", help="do not write the PNG")
    add_common(p, budget=True)


def _pretty_block(label: str, expr, use_unicode: bool) -> str:
    import sympy as sp

    lines = sp.pretty(expr, use_unicode=use_unicode, wrap_line=False).splitlines()
    mid = len(lines) // 2
    pad = " " * (len(label) + 2)
    return "\n".join((label + "  " if k == mid else pad) + line for k, line in enumerate(lines))


def run(args: argparse.Namespace) -> int:
    from hyperrotor import Inertia, RigidBody
    from hyperrotor._options import options
    from hyperrotor.classical import UnreachableAccuracyError
    from hyperrotor.demo import compare_quartet_motion, quartet_motion_seconds

    # --- checks, before any work -------------------------------------------------
    check_common(args)
    if args.no_png and args.png is not None:
        raise UsageError(f"--png {args.png!r} and --no-png contradict each other; give one of them")
    kappa = number(args.kappa, "--kappa", exact=True)
    omega = np.array(DEMO_OMEGA, dtype=float) if args.omega is None else number_list(args.omega, "--omega", 10)
    args.axis = integer(args.axis, "--axis", minimum=1, maximum=5)
    t_end = usage(_validate.positive, "--t-end", number(args.t_end, "--t-end"))
    inertia = usage(Inertia.quartet, kappa, axis=args.axis, N=5)
    try:  # (a body at rest: refused here, before the equations are printed)
        cost = quartet_motion_seconds(kappa, omega, t_end, axis=args.axis)
    except ValueError as err:
        raise UsageError(str(err).replace("omega0", "--omega")) from None
    what, hint = _budget_words(kappa, omega, t_end, cost)
    check_budget(args, f"{what} (fastest frequency {num(cost.frequency, 3)}, rate bound {num(cost.rate, 3)})",
                 cost.seconds, hint=hint)
    check_invariants_fit("--omega", omega, lambda w: quartet_invariants(RigidBody(inertia), w),
                         body_options="--kappa")  # (the invariants printed: all within double precision)
    with Outputs() as outs:
        png = None
        if not args.no_png:
            if have_matplotlib():
                png = outs.add(_png_output(args))
            elif args.png is not None:
                raise UsageError("--png needs matplotlib (pip install 'hyperrotor[viz]'), or pass --no-png")
        # --- work ------------------------------------------------------------------
        body = RigidBody(inertia, convention=args.convention)
        # the equations at once: the motion below takes ~20 s on a fresh installation (numba compiles its kernels)
        print("\n".join(_demo_text(args, body, inertia, kappa, omega)), flush=True)
        if args.progress or (args.progress is None and sys.stderr.isatty()):
            print(f"computing the motion over t in [0, {num(t_end, 6)}] (closed form, splitting8, DOP853); the first "
                  "run after installing compiles numba's kernels once (about 20 s)", file=sys.stderr, flush=True)
        out = []
        with options(max_seconds=max(float(options["max_seconds"]), args.max_seconds or 0.0,
                                     float(options["cli_max_seconds"])),  # the CLI's budget was checked above,
                     max_steps=max(int(options["max_steps"]), 2**62)):  # the steps folded into it (--max-seconds)
            try:
                motion = compare_quartet_motion(kappa, omega, t_end, axis=args.axis)
            except UnreachableAccuracyError as err:  # (a stiff body over a long run: round-off near rtol 1e-12)
                raise unreachable(err, f"the motion over --t-end {num(t_end)} with --kappa {args.kappa}",
                                  "choose a smaller --kappa or a shorter --t-end") from None
        out.extend(_motion_lines(motion))
        out.append("")
        if png is not None:
            save_quartet_motion(motion, png.tmp)
            outs.commit()
            out.append(f"PNG of the motion written to {png.path}"
                       + (" (replacing the earlier one)" if png.replaces else ""))
        elif not args.no_png:
            out.append("PNG skipped: matplotlib is not installed (pip install 'hyperrotor[viz]').")
    out.extend(_demo_summary(args, body, omega, t_end, png.path if png is not None else None))
    print("\n".join(out))
    return 0


def _budget_words(kappa, omega: np.ndarray, t_end: float, cost) -> tuple[str, str]:
    """The run and the advice of a demo refused by the time budget, naming the options that drive its cost.

    The cost model (:func:`hyperrotor.demo.quartet_motion_seconds`) grows linearly with ``t_end``; per unit of
    time it is a constant plus terms linear in the motion's fastest frequency (at most ~ ``max|omega|``,
    whatever kappa) and in the step control's rate bound (~ ``|kappa| max|omega|`` for large kappa).

    Parameters
    ----------
    kappa : number or SymPy rational
        ``--kappa``.
    omega : ndarray (10,)
        ``--omega``.
    t_end : float
        ``--t-end``.
    cost : MotionCost
        The estimate (its ``rate`` and ``frequency``).

    Returns
    -------
    what : str
        The run as options (``demo --kappa 1000000 --t-end 200``; --kappa only when it drives the cost).
    hint : str
        ``choose ...``: --t-end always; --kappa when the rate bound's term more than doubles the cost per unit of
        time (|kappa| beyond a few hundred at the default --omega); --omega when the motion's terms exceed the
        constant one (a body that hardly turns costs the same at any --omega). The option that multiplies the
        cost most, against the default run, comes first.
    """
    from hyperrotor import demo

    turning = demo._SECONDS_PER_TIME_FREQUENCY * cost.frequency
    stepping = demo._SECONDS_PER_TIME_RATE * cost.rate
    drivers = [(float(t_end) / DEMO_T_END, "a shorter --t-end")]  # (factor over the default run, advice)
    by_kappa = stepping > turning + demo._SECONDS_PER_TIME  # (the rate bound's term more than doubles the cost)
    if by_kappa:
        drivers.append((stepping / (turning + demo._SECONDS_PER_TIME),
                        "a --kappa of smaller magnitude (the cost grows as |kappa| there)"))
    if turning + stepping > demo._SECONDS_PER_TIME:
        drivers.append((float(np.max(np.abs(omega))) / max(DEMO_OMEGA), "a smaller --omega"))
    drivers.sort(key=lambda d: -d[0])
    advice = [a for _, a in drivers]
    hint = "choose " + (", ".join(advice[:-1]) + " or " + advice[-1] if len(advice) > 1 else advice[0])
    what = "demo" + (f" --kappa {num(float(kappa))}" if by_kappa else "") + f" --t-end {num(t_end)}"
    return what, hint


def _png_output(args: argparse.Namespace) -> OutputFile:
    """``--png``: a named file keeps the no-clobber rule; the default file is the demo's own and is replaced.

    The default ``hyperrotor-demo.png`` is replaced only when it is a regular
    PNG file (an earlier demo picture), so the README command works when
    pasted twice; anything else at that name is kept (use ``--force``).
    """
    if args.png is not None:
        return usage(output_file, args.png, option="--png", suffixes=(".png",), force=args.force)
    path = Path(DEMO_PNG)
    own = path.is_file() and not path.is_symlink() and path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    try:
        return usage(output_file, DEMO_PNG, option="--png", suffixes=(".png",), force=args.force or own)
    except UsageError as err:  # (no --png was given: name the default, and the ways around it)
        raise UsageError(str(err).replace(f"--png {DEMO_PNG!r}", f"the demo's picture {DEMO_PNG!r} (the default of "
                                          f"--png)", 1) + " (--png FILE.png or --no-png avoids it)") from None


def _demo_text(args, body, inertia, kappa, omega) -> list[str]:
    import sympy as sp

    from hyperrotor import planes

    enc = (getattr(sys.stdout, "encoding", None) or "").lower()
    use_unicode = not args.ascii and enc.replace("-", "") in ("utf8", "utf16", "utf32")
    out = []
    first = "84-85" if args.axis == 5 else {4: "111", 3: "112", 2: "113", 1: "114"}[args.axis]
    out.append("hyperrotor demo: Euler equations of a rigid body in 5D")
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
    inv = quartet_invariants(body, omega)
    out.append("sample angular velocity (plane order " + " ".join(f"{i}{j}" for i, j in planes(5)) + "):")
    out.append("  omega = " + nums(omega))
    out.append("invariants at omega (torque-free motion conserves all of them):")
    out.append(f"  energy E = 1/2 sum I_ij w_ij^2 = {num(inv.energy)}")
    out.append(f"  Casimir c_2 = sum (L^ij)^2 = {num(inv.casimirs[0])}")
    out.append(f"  Casimir c_4 (lambda^1 coefficient of det(lambda - L)) = {num(inv.casimirs[1])}")
    for k, v in enumerate(inv.manakov, start=2):
        out.append(f"  Manakov tr((L + J^2)^{k}) = {num(v)}")
    out.append("  L = " + nums(inv.L))
    out.append("  d omega/dt = " + nums(inv.rhs))
    out.append("")
    return out


def _demo_summary(args, body, omega, t_end, png) -> list[str]:
    from hyperrotor import planes

    names = [f"{i}{j}" for i, j in planes(5)]
    constant = [n for n, c in zip(names, _constant_planes(body)) if c]  # for every omega, by the moments
    here = [name for name, r in zip(names, body.rhs(omega)) if r == 0.0 and name not in constant]  # at this omega
    also = (f"; at this omega also {', '.join(here)} (dw/dt = 0 here)" if here else "")
    if len(constant) == len(names):  # kappa^2 = 1: all moments equal (eq. 82)
        first = ("summary: the 10 Euler equations decouple for this body (kappa^2 = 1: all plane moments are equal, "
                 "eq. 82): every omega_ij is constant (dw/dt = 0 on all 10 planes), no plane oscillates;")
    else:
        without = [n for n, p in zip(names, planes(5)) if args.axis not in p]
        which = (f"the six planes without axis {args.axis}" if constant == without
                 else f"the planes {', '.join(constant)}" if constant else "no plane")
        first = (f"summary: 10 coupled Euler equations; {which} have constant omega for this body"
                 + (f" ({', '.join(constant)})" if constant == without else "") + also + ";")
    return [
        "",
        first,
        "  invariants: energy, 2 Casimirs (eq. 38; the energy is not one of them), "
        "Manakov traces (mass-tensor body).",
        f"  motion: closed form (eqs. 96-110, corrected signs) vs Lie-Poisson splitting (order 8) and "
        f"scipy DOP853 over t in [0, {num(t_end, 6)}]" + (f"; picture: {png}" if png else "") + ".",
    ]


def _constant_planes(body) -> list[bool]:
    """For each plane: whether its omega is constant for every omega (its Euler equation's coefficients, the
    moment differences of the body's tables ``rhs_tables``, all zero; compared exactly, on the symbolic moments)."""
    I = body.inertia.symbolic_moments
    left, right, _ = body.rhs_tables
    return [all(I[r] == I[q] for q, r in zip(left[a], right[a])) for a in range(len(body.planes))]


def _motion_lines(motion) -> list[str]:
    """The report of :func:`hyperrotor.demo.compare_quartet_motion`."""
    lines = [f"motion over t in [0, {num(motion.t[-1], 6)}] ({len(motion.t)} output times), reference: closed form "
             "(eqs. 96-110):",
             "  frequencies Omega_1, Omega_2 (after eq. 118) = " + nums(motion.frequencies),
             f"  (a first, untimed call of the splitting run loads or compiles its numba kernels: "
             f"{motion.warmup_time:.2f} s; the wall times below are of the runs that follow it)"]
    for run in motion.runs.values():
        lines.append(f"  {run.method:<10} rtol={run.rtol:.0e}: max relative error vs closed form = {run.error:.3e}, "
                     f"energy drift = {run.energy_drift:.2e}, Casimir c_2 drift = {run.casimir_drift:.2e}, "
                     f"wall time {run.wall_time:.3f} s")
    lines.append("  (relative error: max over times and planes of |omega - omega_exact| / max|omega_0|)")
    return lines
