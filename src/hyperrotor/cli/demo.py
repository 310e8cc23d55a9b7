"""``hyperrotor demo``: the 5D Euler equations (28)-(37) of the paper's quartet body (eqs. 84-85).

Prints the equations, the invariants on a sample angular velocity, the closed
form against two integrators, and writes a PNG of the motion.
"""
from __future__ import annotations

import argparse
import sys
import time

import numpy as np

from hyperrotor import _validate
from hyperrotor.cli._common import (UsageError, add_common, check_budget, check_common, choice_of, have_matplotlib,
                                    integer, num, number, number_list, nums, usage)
from hyperrotor.conventions import CONVENTIONS
from hyperrotor.cli._files import Outputs, output_file

__all__ = ["configure", "run", "DEMO_OMEGA", "DEMO_PNG"]


#: Sample angular velocity of ``hyperrotor demo`` (plane order 12, 13, ..., 45).
DEMO_OMEGA = tuple(round(0.1 * k, 1) for k in range(1, 11))
#: Default PNG of ``hyperrotor demo``.
DEMO_PNG = "hyperrotor-demo.png"
#: Wall time of the demo's two runs per unit of simulated time (measured, 2-core machine), for the budget.
_DEMO_SECONDS_PER_TIME = 0.004


def configure(p: argparse.ArgumentParser) -> None:
    p.add_argument("--kappa", default="1/2",
                   help="kappa of the quartet body, I = 1 + kappa^2 on planes with the axis (default 1/2; "
                        "fractions are kept exact)")
    p.add_argument("--axis", default=5, help="distinguished axis of the quartet body, 1..5 (default 5)")
    p.add_argument("--convention", default="paper", choices=CONVENTIONS, type=choice_of(CONVENTIONS),
                   help="matrix convention of the printed equations (default: paper, eq. 21)")
    p.add_argument("--omega", default=None,
                   help="comma-separated 10 angular velocity components in plane order "
                        f"(default {','.join(map(str, DEMO_OMEGA))}; write --omega=-1,... for a negative first value)")
    p.add_argument("--ascii", action="store_true", help="ASCII instead of Unicode pretty printing")
    p.add_argument("--t-end", default=200.0,
                   help="length of the simulated motion, closed form vs numerical (default 200)")
    p.add_argument("--png", default=None, metavar="FILE.png",
                   help=f"where to write the PNG of the motion (default ./{DEMO_PNG}; needs matplotlib; "
                        "an existing file is kept unless --force)")
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

    # --- checks, before any work -------------------------------------------------
    check_common(args)
    kappa = number(args.kappa, "--kappa", exact=True)
    omega = np.array(DEMO_OMEGA, dtype=float) if args.omega is None else number_list(args.omega, "--omega", 10)
    args.axis = integer(args.axis, "--axis", minimum=1, maximum=5)
    t_end = usage(_validate.positive, "--t-end", number(args.t_end, "--t-end"))
    inertia = usage(Inertia.quartet, kappa, axis=args.axis, N=5)
    # the integrators' work grows with t_end times the fastest rate of the motion, at most
    # max|omega| * max(I) / min(I) (the Euler coefficients are moment differences over moments)
    moments = np.asarray(inertia.moments, dtype=float)
    rate = max(1.0, float(np.max(np.abs(omega))) * float(np.max(moments) / np.min(moments)))
    check_budget(args, f"demo --t-end {num(t_end)} (fastest rate {num(rate, 3)})",
                  1.0 + _DEMO_SECONDS_PER_TIME * t_end * rate, hint="choose a shorter --t-end or smaller --omega")
    with Outputs() as outs:
        png = None
        if not args.no_png:
            if have_matplotlib():
                png = outs.add(usage(output_file, args.png or DEMO_PNG, option="--png", suffixes=(".png",),
                                      force=args.force))
            elif args.png is not None:
                raise UsageError("--png needs matplotlib (pip install 'hyperrotor[viz]'), or pass --no-png")
        # --- work ------------------------------------------------------------------
        body = RigidBody(inertia, args.convention)
        out = _demo_text(args, body, inertia, kappa, omega)
        motion = _demo_motion(body, float(kappa), args.axis, omega, t_end)
        out.extend(motion["lines"])
        out.append("")
        if png is not None:
            _demo_png(motion, png.tmp)
            outs.commit()
            out.append(f"PNG of the motion written to {png.path}")
        elif not args.no_png:
            out.append("PNG skipped: matplotlib is not installed (pip install 'hyperrotor[viz]').")
    out.extend(_demo_summary(args, body, omega, t_end, png.path if png is not None else None))
    print("\n".join(out))
    return 0


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
    L = body.angular_momentum(omega)
    cas = body.casimirs(omega)
    man = body.manakov_integrals(omega, 1.0)
    out.append("sample angular velocity (plane order " + " ".join(f"{i}{j}" for i, j in planes(5)) + "):")
    out.append("  omega = " + nums(omega))
    out.append("invariants at omega (torque-free motion conserves all of them):")
    out.append(f"  energy E = 1/2 sum I_ij w_ij^2 = {num(body.energy(omega))}")
    out.append(f"  Casimir c_2 = sum (L^ij)^2 = {num(cas[0])}")
    out.append(f"  Casimir c_4 (lambda^1 coefficient of det(lambda - L)) = {num(cas[1])}")
    for k, v in enumerate(man, start=2):
        out.append(f"  Manakov tr((L + J^2)^{k}) = {num(v)}")
    out.append("  L = " + nums(L))
    out.append("  d omega/dt = " + nums(body.rhs(omega)))
    out.append("")
    return out


def _demo_summary(args, body, omega, t_end, png) -> list[str]:
    from hyperrotor import planes

    steady = [f"{i}{j}" for (i, j), r in zip(planes(5), body.rhs(omega)) if r == 0.0]
    return [
        "",
        "summary: 10 coupled Euler equations; the six planes without axis "
        f"{args.axis} have constant omega for this body ({', '.join(steady)} have dw/dt = 0 here);",
        "  invariants: energy, 2 Casimirs (eq. 38; the energy is not one of them), "
        "Manakov traces (mass-tensor body).",
        f"  motion: closed form (eqs. 96-110, corrected signs) vs Lie-Poisson splitting (order 8) and "
        f"scipy DOP853 over t in [0, {num(t_end, 6)}]" + (f"; picture: {png}" if png else "") + ".",
    ]


def _demo_motion(body, kappa: float, axis: int, omega, t_end: float) -> dict:
    """Closed form vs numerical motion of the quartet body; returns data and report lines."""
    from hyperrotor import simulate
    from hyperrotor.classical.closed_form import quartet_frequencies, quartet_solution

    t = np.linspace(0.0, t_end, 2001)
    exact = quartet_solution(kappa, omega, t, axis=axis)
    scale = float(np.max(np.abs(omega)))
    lines = [f"motion over t in [0, {num(t_end, 6)}] (2001 output times), reference: closed form (eqs. 96-110):"]
    freqs = quartet_frequencies(kappa, omega, axis=axis)
    lines.append("  frequencies Omega_1, Omega_2 (after eq. 118) = " + nums(freqs))
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
        runs[name] = traj.omega
        lines.append(f"  {name:<10} rtol={kw['rtol']:.0e}: max relative error vs closed form = {err:.3e}, "
                     f"energy drift = {float(np.max(np.abs(E / E[0] - 1))):.2e}, "
                     f"Casimir c_2 drift = {float(np.max(np.abs(c2 / c2[0] - 1))):.2e}, wall time {wall:.3f} s")
    lines.append("  (relative error: max over times and planes of |omega - omega_exact| / max|omega_0|)")
    return {"t": t, "exact": exact, "runs": runs, "lines": lines, "axis": axis, "kappa": kappa, "scale": scale}


def _demo_png(motion: dict, path) -> None:
    """The oscillating components (closed form, splitting8 dots) and the relative error of both runs."""
    from hyperrotor import planes
    from hyperrotor.plotting import save_motion_comparison

    axis = motion["axis"]
    osc = [k for k, p in enumerate(planes(5)) if axis in p]
    labels = [f"$\\omega_{{{i}{j}}}$" for i, j in (planes(5)[k] for k in osc)]
    save_motion_comparison(
        path, motion["t"], motion["exact"], motion["runs"], components=osc, labels=labels, scale=motion["scale"],
        marked="splitting8",
        title=f"5D quartet body (kappa = {num(motion['kappa'], 6)}, axis {axis}): the four planes with axis "
              f"{axis} oscillate", format="png")
