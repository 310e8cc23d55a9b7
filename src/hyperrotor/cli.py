"""The ``hyperrotor`` command line.

One function pair per subcommand (``_configure_<name>(parser)`` adds its
options, ``_run_<name>(args) -> int`` checks them and does the work),
registered in :data:`SUBCOMMANDS`. To add a subcommand, write the pair and add
one :class:`Subcommand` entry to the table.

Subcommands
-----------
``demo``
    The 5D Euler equations (28)-(37) of the paper's quartet body (eqs. 84-85),
    its invariants on a sample angular velocity, closed form vs numerics, a PNG.
``verify``
    The preprint checked equation by equation (:mod:`hyperrotor.paper.verify`).
``scene``
    The 3D projection of a body rotating in N dimensions, PNG snapshots or a GIF.
``bench``
    A quick work-precision run (:mod:`hyperrotor.bench`), a CSV and a PNG.

Conventions of every subcommand
-------------------------------
* **Checks first.** Every argument and every output path is checked before any
  work: an unknown format, a missing or unwritable folder, an existing file, a
  run whose memory or time, estimated from the arguments, exceeds the budget
  (``hr.options["cli_max_memory"]``, ``["cli_max_seconds"]``; ``--max-memory``,
  ``--max-seconds``) are refused with **one line** on stderr naming the value
  and what is allowed, and exit status 2.
* **Exit status.** 0 success; 1 the work failed (one line on stderr); 2 usage
  error; 130 interrupted by Ctrl-C (SIGINT); 143 terminated (SIGTERM); 141
  standard output closed early (``hyperrotor demo | head -1``): the command
  stops quietly with the status a shell reports for a program ended by
  SIGPIPE, as ``yes | head -1`` does (so ``set -o pipefail`` treats both alike).
  ``--debug`` adds the Python traceback to an error.
* **Output files** are never overwritten unless ``--force`` is given. Each is
  written to a hidden temporary file in its target folder and renamed when
  complete, so an error or an interrupt leaves no partial file and the earlier
  file (if any) intact (:mod:`hyperrotor._cli_files`).
* **Progress** bars (tqdm) go to stderr, for work that can take more than a few
  seconds (scene, bench, verify), when stderr is a terminal or with
  ``--progress`` (``--no-progress`` turns them off).
* **Warnings** (e.g. numerical ones from NumPy) are reported after the work,
  one line each (``hyperrotor demo: warning: RuntimeWarning: ...``).
* **Numbers** print as plain values with 12 significant digits (``-0.33``, not
  ``-0.32999999999999996``); values in error messages via
  :func:`hyperrotor._validate.fmt`.
"""
from __future__ import annotations

import argparse
import math
import os
import re
import signal
import sys
import time
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Sequence

import numpy as np

from hyperrotor import _validate
from hyperrotor._cli_files import Outputs, output_file
from hyperrotor._options import options

__all__ = ["main", "build_parser", "Subcommand", "SUBCOMMANDS", "UsageError", "EXIT_CODES"]

#: The exit statuses of ``hyperrotor`` (module docstring).
EXIT_CODES = {"ok": 0, "failed": 1, "usage": 2, "interrupted": 130, "broken-pipe": 141, "terminated": 143}


class UsageError(ValueError):
    """A bad argument or output path: one line on stderr, exit status 2."""


class _Terminated(BaseException):
    """SIGTERM, turned into an exception so that temporary files are removed."""


@dataclass(frozen=True)
class Subcommand:
    """A registered subcommand: its help text, option set-up and action."""

    help: str
    configure: Callable[[argparse.ArgumentParser], None]
    run: Callable[[argparse.Namespace], int]


class _Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line (raised as :class:`UsageError`)."""

    def error(self, message: str):  # noqa: D401 - argparse API
        raise UsageError(f"{message} (see '{self.prog} --help')")


# ----------------------------------------------------------------------------
# shared helpers: numbers, checks, budgets, progress
# ----------------------------------------------------------------------------
def _num(x, digits: int = 12) -> str:
    """A number as plain text with ``digits`` significant digits (``-0.33``, ``2``, ``1.5e-12``)."""
    x = float(x)
    return "0" if x == 0.0 else format(x, f".{digits}g")


def _nums(values, digits: int = 12) -> str:
    return "[" + ", ".join(_num(v, digits) for v in values) + "]"


def _usage(fn, *a, **kw):
    """Call a ``_validate`` check; its ValueError/TypeError becomes a :class:`UsageError`."""
    try:
        return fn(*a, **kw)
    except (TypeError, ValueError) as err:
        raise UsageError(str(err)) from None


#: Largest magnitude of a number given on the command line (kappa, omega, sides): squares and
#: products of a few of them must stay far inside double precision.
MAX_MAGNITUDE = 1e100


def _bounded(option: str, value: float) -> float:
    """A finite real number with ``|value| <= MAX_MAGNITUDE`` (else :class:`UsageError`)."""
    value = _usage(_validate.real, option, value)
    if abs(value) > MAX_MAGNITUDE:
        raise UsageError(f"{option} must have magnitude <= {MAX_MAGNITUDE:g}, got {_validate.fmt(value)}")
    return value


def _number_list(text: str, option: str, count: int | None = None, *, positive: bool = False) -> np.ndarray:
    """Comma-separated finite numbers of magnitude <= :data:`MAX_MAGNITUDE` (exactly ``count`` when given)."""
    parts = [v.strip() for v in text.split(",") if v.strip()]
    try:
        arr = np.array([float(v) for v in parts])
    except ValueError:
        raise UsageError(f"{option} must be comma-separated numbers, got {text!r}") from None
    if count is not None and arr.size != count:
        raise UsageError(f"{option} needs {count} comma-separated numbers, got {arr.size} ({text!r})")
    bad = [float(v) for v in arr if not math.isfinite(v) or (positive and v <= 0) or abs(v) > MAX_MAGNITUDE]
    if bad:
        raise UsageError(f"{option} values must be finite{' and > 0' if positive else ''} with magnitude <= "
                         f"{MAX_MAGNITUDE:g}, got {_validate.fmt(bad)}")
    return arr


def _int_list(text: str, option: str) -> list[int]:
    try:
        return [int(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise UsageError(f"{option} must be comma-separated integers, got {text!r}") from None


_BYTE_UNITS = {"": 1, "K": 2**10, "M": 2**20, "G": 2**30, "T": 2**40}


def _bytes(text: str) -> int:
    """``--max-memory``: bytes, or a number with K, M, G or T (binary units), e.g. ``4G``."""
    m = re.fullmatch(r"\s*([0-9.]+(?:[eE][+-]?[0-9]+)?)\s*([KMGT]?)(?:i?B)?\s*", text, flags=re.I)
    if not m:
        raise argparse.ArgumentTypeError(f"expected a size such as 2G, 500M or 1000000, got {text!r}")
    value = float(m.group(1)) * _BYTE_UNITS[m.group(2).upper()]
    if not math.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"expected a positive size, got {text!r}")
    return int(value)


def _size(n: float) -> str:
    """Bytes as text: ``8.0 TiB``, ``512 MiB``."""
    for unit, k in (("TiB", 40), ("GiB", 30), ("MiB", 20), ("KiB", 10)):
        if n >= 2**k:
            return f"{n / 2**k:.3g} {unit}"
    return f"{int(n)} bytes"


def _duration(s: float) -> str:
    if s >= 86400:
        return f"{s / 86400:.3g} days"
    if s >= 3600:
        return f"{s / 3600:.3g} h"
    if s >= 60:
        return f"{s / 60:.3g} min"
    return f"{s:.2g} s"


def _check_budget(args: argparse.Namespace, what: str, seconds: float, memory: float | None = None,
                  hint: str = "") -> None:
    """Refuse a run whose estimated time or memory exceeds the budget (before any work)."""
    max_s = args.max_seconds if args.max_seconds is not None else float(options["cli_max_seconds"])
    max_m = getattr(args, "max_memory", None)
    max_m = max_m if max_m is not None else int(options["cli_max_memory"])
    tail = f"; {hint}" if hint else ""
    if memory is not None and memory > max_m:
        raise UsageError(f"{what} needs about {_size(memory)} of memory, over the budget of {_size(max_m)} "
                         f"(--max-memory, default hr.options['cli_max_memory']){tail}")
    if seconds > max_s:
        raise UsageError(f"{what} would take about {_duration(seconds)}, over the budget of {_duration(max_s)} "
                         f"(--max-seconds, default hr.options['cli_max_seconds']){tail}")


def _show_progress(args: argparse.Namespace) -> bool:
    return args.progress if args.progress is not None else sys.stderr.isatty()


def _bar(args: argparse.Namespace, total: int, desc: str, unit: str):
    """A tqdm bar on stderr (disabled unless :func:`_show_progress`)."""
    from tqdm import tqdm

    return tqdm(total=total, desc=desc, unit=unit, file=sys.stderr, disable=not _show_progress(args),
                leave=False, dynamic_ncols=True, mininterval=0.2)


def _have_matplotlib() -> bool:
    import importlib.util

    return importlib.util.find_spec("matplotlib") is not None


def _add_common(p: argparse.ArgumentParser, *, budget: bool = False, memory: bool = False) -> None:
    g = p.add_argument_group("behaviour")
    g.add_argument("--force", action="store_true",
                   help="replace existing output files (default: refuse and leave them as they are)")
    g.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress bars on stderr (default: only when stderr is a terminal)")
    g.add_argument("--debug", action="store_true", help="show the Python traceback of an error")
    if budget:
        g = p.add_argument_group("budget (checked against estimates before any work)")
        g.add_argument("--max-seconds", type=float, default=None, metavar="S",
                       help="refuse a run estimated to take longer (default hr.options['cli_max_seconds'] "
                            f"= {options['cli_max_seconds']:g} s)")
    if memory:
        g.add_argument("--max-memory", type=_bytes, default=None, metavar="SIZE",
                       help="refuse a run estimated to need more memory, e.g. 4G (default "
                            f"hr.options['cli_max_memory'] = {_size(options['cli_max_memory'])})")


def _check_common(args: argparse.Namespace) -> None:
    if getattr(args, "max_seconds", None) is not None:
        _usage(_validate.positive, "--max-seconds", args.max_seconds)


# ----------------------------------------------------------------------------
# demo
# ----------------------------------------------------------------------------
#: Sample angular velocity of ``hyperrotor demo`` (plane order 12, 13, ..., 45).
DEMO_OMEGA = tuple(round(0.1 * k, 1) for k in range(1, 11))
#: Default PNG of ``hyperrotor demo``.
DEMO_PNG = "hyperrotor-demo.png"
#: Wall time of the demo's two runs per unit of simulated time (measured, 2-core machine), for the budget.
_DEMO_SECONDS_PER_TIME = 0.004


def _configure_demo(p: argparse.ArgumentParser) -> None:
    p.add_argument("--kappa", default="1/2",
                   help="kappa of the quartet body, I = 1 + kappa^2 on planes with the axis (default 1/2; "
                        "fractions are kept exact)")
    p.add_argument("--axis", type=int, default=5, help="distinguished axis of the quartet body, 1..5 (default 5)")
    p.add_argument("--convention", default="paper", choices=("paper", "standard"),
                   help="matrix convention of the printed equations (default: paper, eq. 21)")
    p.add_argument("--omega", default=None,
                   help="comma-separated 10 angular velocity components in plane order "
                        f"(default {','.join(map(str, DEMO_OMEGA))}; write --omega=-1,... for a negative first value)")
    p.add_argument("--ascii", action="store_true", help="ASCII instead of Unicode pretty printing")
    p.add_argument("--t-end", type=float, default=200.0,
                   help="length of the simulated motion, closed form vs numerical (default 200)")
    p.add_argument("--png", default=None, metavar="FILE.png",
                   help=f"where to write the PNG of the motion (default ./{DEMO_PNG}; needs matplotlib; "
                        "an existing file is kept unless --force)")
    p.add_argument("--no-png", action="store_true", help="do not write the PNG")
    _add_common(p, budget=True)


def _parse_number(text: str):
    import sympy as sp

    try:
        value = sp.nsimplify(sp.sympify(text, rational=True))
    except (sp.SympifyError, TypeError, SyntaxError, ValueError):
        raise UsageError(f"--kappa must be a real number such as 1/2 or 0.7, got {text!r}") from None
    if not value.is_real or not value.is_finite:
        raise UsageError(f"--kappa must be a finite real number, got {text!r}")
    _bounded("--kappa", float(value))
    return value


def _pretty_block(label: str, expr, use_unicode: bool) -> str:
    import sympy as sp

    lines = sp.pretty(expr, use_unicode=use_unicode, wrap_line=False).splitlines()
    mid = len(lines) // 2
    pad = " " * (len(label) + 2)
    return "\n".join((label + "  " if k == mid else pad) + line for k, line in enumerate(lines))


def _run_demo(args: argparse.Namespace) -> int:
    from hyperrotor import Inertia, RigidBody

    # --- checks, before any work -------------------------------------------------
    _check_common(args)
    kappa = _parse_number(args.kappa)
    omega = np.array(DEMO_OMEGA, dtype=float) if args.omega is None else _number_list(args.omega, "--omega", 10)
    _usage(_validate.integer, "--axis", args.axis, minimum=1, maximum=5)
    t_end = _usage(_validate.positive, "--t-end", args.t_end)
    inertia = _usage(Inertia.quartet, kappa, axis=args.axis, N=5)
    # the integrators' work grows with t_end times the fastest rate of the motion, at most
    # max|omega| * max(I) / min(I) (the Euler coefficients are moment differences over moments)
    moments = np.asarray(inertia.moments, dtype=float)
    rate = max(1.0, float(np.max(np.abs(omega))) * float(np.max(moments) / np.min(moments)))
    _check_budget(args, f"demo --t-end {_num(t_end)} (fastest rate {_num(rate, 3)})",
                  1.0 + _DEMO_SECONDS_PER_TIME * t_end * rate, hint="choose a shorter --t-end or smaller --omega")
    with Outputs() as outs:
        png = None
        if not args.no_png:
            if _have_matplotlib():
                png = outs.add(_usage(output_file, args.png or DEMO_PNG, option="--png", suffixes=(".png",),
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
    out.append("  omega = " + _nums(omega))
    out.append("invariants at omega (torque-free motion conserves all of them):")
    out.append(f"  energy E = 1/2 sum I_ij w_ij^2 = {_num(body.energy(omega))}")
    out.append(f"  Casimir c_2 = sum (L^ij)^2 = {_num(cas[0])}")
    out.append(f"  Casimir c_4 (lambda^1 coefficient of det(lambda - L)) = {_num(cas[1])}")
    for k, v in enumerate(man, start=2):
        out.append(f"  Manakov tr((L + J^2)^{k}) = {_num(v)}")
    out.append("  L = " + _nums(L))
    out.append("  d omega/dt = " + _nums(body.rhs(omega)))
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
        f"scipy DOP853 over t in [0, {_num(t_end, 6)}]" + (f"; picture: {png}" if png else "") + ".",
    ]


def _demo_motion(body, kappa: float, axis: int, omega, t_end: float) -> dict:
    """Closed form vs numerical motion of the quartet body; returns data and report lines."""
    from hyperrotor import simulate
    from hyperrotor.classical.closed_form import quartet_frequencies, quartet_solution

    t = np.linspace(0.0, t_end, 2001)
    exact = quartet_solution(kappa, omega, t, axis=axis)
    scale = float(np.max(np.abs(omega)))
    lines = [f"motion over t in [0, {_num(t_end, 6)}] (2001 output times), reference: closed form (eqs. 96-110):"]
    freqs = quartet_frequencies(kappa, omega, axis=axis)
    lines.append("  frequencies Omega_1, Omega_2 (after eq. 118) = " + _nums(freqs))
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
        title=f"5D quartet body (kappa = {_num(motion['kappa'], 6)}, axis {axis}): the four planes with axis "
              f"{axis} oscillate", format="png")


# ----------------------------------------------------------------------------
# verify
# ----------------------------------------------------------------------------
_VERIFY_SUFFIXES = {"json": (".json",), "markdown": (".md", ".markdown"), "table": (".txt", ".text")}


def _configure_verify(p: argparse.ArgumentParser) -> None:
    from hyperrotor.paper import verify

    verify.configure_parser(p)
    for action in p._actions:  # document the extension rule on -o
        if "--output" in action.option_strings:
            action.help = ("write the report to FILE instead of stdout: .txt (table), .md (Markdown) or .json; "
                           "without --json/--markdown the extension chooses the format, with them it must match")
    _add_common(p)


def _run_verify(args: argparse.Namespace) -> int:
    from hyperrotor.paper.verify import SECTIONS, render, verify

    _check_common(args)
    kind = "json" if args.json else "markdown" if args.markdown else None
    if kind is None and args.output is not None:  # no format option: the extension of --output chooses
        suffix = Path(args.output).suffix.lower()
        kind = next((k for k, sfx in _VERIFY_SUFFIXES.items() if suffix in sfx), "table")
    kind = kind or "table"
    keys = list(args.section) if args.section else list(SECTIONS)
    with Outputs() as outs:
        out = None
        if args.output is not None:
            flag = {"json": "--json", "markdown": "--markdown", "table": "no format option"}[kind]
            suffixes = _VERIFY_SUFFIXES[kind] if (args.json or args.markdown) else sum(_VERIFY_SUFFIXES.values(), ())
            try:
                out = outs.add(output_file(args.output, option="--output", suffixes=suffixes, force=args.force))
            except ValueError as err:
                msg = str(err)
                if (args.json or args.markdown) and ("has extension" in msg or "has no extension" in msg):
                    msg += f" (the {kind} report, {flag})"
                raise UsageError(msg) from None
        verdicts = []
        with _bar(args, len(keys), "verify: sections", "section") as bar:
            for key in keys:
                bar.set_postfix_str(key)
                verdicts.extend(verify([key]))
                bar.update()
        text = render(verdicts, kind)
        if out is None:
            print(text)
            return 0
        out.tmp.write_text(text if text.endswith("\n") else text + "\n", encoding="utf-8")
        outs.commit()
    print(f"written: {out.path} ({len(verdicts)} items)")
    return 0


# ----------------------------------------------------------------------------
# scene
# ----------------------------------------------------------------------------
SCENE_SHAPES = ("cube", "simplex", "ellipsoid")
#: Points of the ellipsoid sample of ``scene --shape ellipsoid``.
_ELLIPSOID_POINTS = 400
#: Cost model of ``scene`` (seconds, measured on the shared 2-core machine: --N 12 cube PNG 15.8 s
#: wall against 13.7 s estimated): start-up (imports), per drawn frame, per drawn edge and point of
#: a frame, per frame-plane of the motion, per cube vertex and axis^2 (finding the edges).
_SCENE_COST = {"start": 5.0, "frame_png": 0.35, "frame_gif": 0.1, "edge": 3.5e-5, "point": 1e-5,
               "motion": 2e-7, "cube_edges": 2e-6}
_GIF_FRAME_BYTES = 540 * 480 * 4  # Pillow keeps every RGBA frame until the file is written


def _configure_scene(p: argparse.ArgumentParser) -> None:
    p.add_argument("--shape", default="cube", choices=SCENE_SHAPES,
                   help="body points: N-cube vertices (2^N), N-simplex vertices (N+1) or "
                        f"{_ELLIPSOID_POINTS} ellipsoid points (default cube)")
    p.add_argument("--N", type=int, default=5, help="dimension of space, >= 3 (default 5)")
    p.add_argument("--inertia", default="quartet", choices=("quartet", "equal", "box"),
                   help="quartet: the paper's eqs. 84-85 (any N), equal: eq. 82, box: solid hyper-box of the "
                        "--sides (generic, no closed form) (default quartet)")
    p.add_argument("--kappa", type=float, default=0.5, help="kappa of the quartet inertia (default 0.5)")
    p.add_argument("--axis", type=int, default=None, help="distinguished axis of the quartet inertia (default N)")
    p.add_argument("--sides", default=None, help="comma-separated N positive side lengths of the box inertia "
                                                  "(default 1,2,...,N)")
    p.add_argument("--omega", default=None,
                   help="comma-separated initial angular velocity, N(N-1)/2 components in plane order "
                        "(default 0.1, 0.2, ...; write --omega=-1,... for a negative first value)")
    p.add_argument("--lock", default="", help="comma-separated axes whose rotation planes start (and stay) at rest")
    p.add_argument("--axes", default="1,2,3", help="the three space axes drawn (default 1,2,3)")
    p.add_argument("--colour-axis", "--color-axis", type=int, default=None, dest="colour_axis", metavar="K",
                   help="space axis whose coordinate colours the points (colour bar); default the first axis "
                        "not in --axes (none when N = 3); 0 for no colour")
    p.add_argument("--t-end", type=float, default=20.0, help="duration (default 20)")
    p.add_argument("--frames", type=int, default=60,
                   help="number of time samples: GIF frames, or the grid the 6 PNG snapshots are taken from "
                        "(default 60)")
    p.add_argument("--output", default="hyperrotor-scene.png", metavar="FILE",
                   help="FILE.png (6 snapshots) or FILE.gif (animation, one frame per time) "
                        "(default hyperrotor-scene.png; an existing file is kept unless --force)")
    _add_common(p, budget=True, memory=True)


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

    _check_common(args)
    N = _usage(_validate.integer, "--N", args.N, minimum=3)
    frames = _usage(_validate.integer, "--frames", args.frames, minimum=2)
    t_end = _usage(_validate.positive, "--t-end", args.t_end)
    n = n_planes(N) if N < 10**5 else N * (N - 1) // 2
    axes = _int_list(args.axes, "--axes")
    if len(axes) != 3 or len(set(axes)) != 3 or not all(1 <= k <= N for k in axes):
        raise UsageError(f"--axes must be three different axes in 1..{N}, got {args.axes!r}")
    colour_axis = args.colour_axis
    if colour_axis is None:
        colour_axis = next((k for k in range(1, N + 1) if k not in axes), 0)
    elif colour_axis != 0:
        _usage(_validate.integer, "--colour-axis", colour_axis, minimum=0, maximum=N)
        if colour_axis in axes:
            raise UsageError(f"--colour-axis {colour_axis} is one of the drawn --axes {args.axes!r}; "
                             f"choose an axis in 1..{N} not drawn, or 0 for no colour")
    lock = _int_list(args.lock, "--lock")
    bad = [k for k in lock if not 1 <= k <= N]
    if bad:
        raise UsageError(f"--lock axes must be in 1..{N}, got {_validate.fmt(bad)}")
    if args.inertia == "quartet":
        _bounded("--kappa", args.kappa)
        if args.axis is not None:
            _usage(_validate.integer, "--axis", args.axis, minimum=1, maximum=N)
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
    _check_budget(args, what, seconds, memory, hint)
    sides = None
    if args.inertia == "box":
        sides = np.arange(1.0, N + 1) if args.sides is None else _number_list(args.sides, "--sides", N, positive=True)
    omega = 0.1 * np.arange(1, n + 1) if args.omega is None else _number_list(args.omega, "--omega")
    if omega.shape != (n,):
        raise UsageError(f"--omega needs N(N-1)/2 = {n} components for N = {N}, got {omega.size}")
    omega = np.where([any(k in p for k in lock) for p in planes(N)], 0.0, omega)
    return {"N": N, "frames": frames, "t_end": t_end, "axes": axes, "colour_axis": colour_axis or None,
            "sides": sides, "omega": omega, "gif": gif, "seconds": seconds}


def _run_scene(args: argparse.Namespace) -> int:
    from hyperrotor import Inertia, RigidBody
    from hyperrotor.classical.scenes import Scene, ellipsoid_points, hypercube_vertices, simplex_vertices

    s = _scene_check(args)
    if not _have_matplotlib():
        raise UsageError("scene needs matplotlib: pip install 'hyperrotor[viz]'")
    N = s["N"]
    with Outputs() as outs:
        out = outs.add(_usage(output_file, args.output, option="--output", suffixes=(".png", ".gif"),
                              force=args.force))
        if args.inertia == "quartet":
            inertia = _usage(Inertia.quartet, args.kappa, axis=N if args.axis is None else args.axis, N=N)
        elif args.inertia == "equal":
            inertia = Inertia.equal(N, 1.0)
        else:
            inertia = _usage(Inertia.box, 1.0, s["sides"])
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
        with _bar(args, n_drawn, f"scene: drawing {'GIF frames' if s['gif'] else 'snapshots'}", "frame") as bar:
            kw = dict(title=title, axes_labels=s["axes"], colour_axis=s["colour_axis"], progress=bar.update)
            if s["gif"]:
                save_projection_animation(out.tmp, res.t, res.projection, edges, **kw)
            else:
                save_projection_frames(out.tmp, res.t, res.projection, edges, format="png", **kw)
        outs.commit()
    print(f"scene: {len(points)} body points, {len(edges)} edges, {len(res.t)} times in [0, {_num(s['t_end'], 6)}], "
          f"route {res.path!r} ({res.stats['wall_time']:.3f} s)")
    print(f"written: {out.path}")
    return 0


# ----------------------------------------------------------------------------
# bench
# ----------------------------------------------------------------------------
BENCH_STEM = "hyperrotor-bench"


def _configure_bench(p: argparse.ArgumentParser) -> None:
    from hyperrotor.bench import _SETTINGS, BENCH_PROBLEMS

    p.add_argument("--problem", action="append", choices=BENCH_PROBLEMS,
                   help="problem with an exact solution (repeatable; default: all)")
    p.add_argument("--method", action="append", default=None, choices=list(_SETTINGS), metavar="METHOD",
                   help=f"{', '.join(_SETTINGS)} (repeatable; default: all)")
    p.add_argument("--repeats", type=int, default=2, help="timed repeats per run, best kept (default 2)")
    p.add_argument("--error", type=float, default=1e-10,
                   help="relative error level (0 < error < 1) at which the speed-up over DOP853 is reported "
                        "(default 1e-10)")
    p.add_argument("--output", default=BENCH_STEM, metavar="STEM",
                   help=f"where the results go: STEM.csv and STEM.png (default ./{BENCH_STEM}). A trailing .csv "
                        f"or .png is dropped (b.png -> b.csv, b.png); a folder (existing, or written with a "
                        f"trailing /) gets {BENCH_STEM}.csv and .png inside. Existing files are kept unless --force")
    _add_common(p, budget=True)


def bench_paths(stem: str) -> tuple[Path, Path]:
    """The CSV and PNG written by ``hyperrotor bench --output stem`` (naming rule of its --help)."""
    if not stem or not stem.strip():
        raise UsageError("--output needs a file stem or a folder, got an empty string")
    path = Path(stem).expanduser()
    if stem.endswith(("/", os.sep)) or path.is_dir():
        path = path / BENCH_STEM
    elif path.suffix.lower() in (".csv", ".png"):
        path = path.with_suffix("")
    return path.with_name(path.name + ".csv"), path.with_name(path.name + ".png")


def _run_bench(args: argparse.Namespace) -> int:
    from hyperrotor.bench import (_main_table, estimate_seconds, n_runs, plot_work_precision, speedup_at,
                                  work_precision, write_csv)

    _check_common(args)
    problems = list(dict.fromkeys(args.problem or ["quartet", "euler-poinsot"]))
    methods = None if args.method is None else list(dict.fromkeys(args.method))
    repeats = _usage(_validate.integer, "--repeats", args.repeats, minimum=1)
    error = _usage(_validate.positive, "--error", args.error)
    if error >= 1:
        raise UsageError(f"--error is a relative error level and must be < 1, got {_validate.fmt(error)}")
    _check_budget(args, f"bench with --repeats {repeats}", estimate_seconds(problems, methods, repeats),
                  hint="use fewer --repeats, --problem or --method")
    csv_path, png_path = bench_paths(args.output)
    plot = _have_matplotlib()
    with Outputs() as outs:
        csv_out = outs.add(_usage(output_file, str(csv_path), option="--output", suffixes=(".csv",),
                                  force=args.force))
        png_out = outs.add(_usage(output_file, str(png_path), option="--output", suffixes=(".png",),
                                  force=args.force)) if plot else None
        # --- work ------------------------------------------------------------------
        points = []
        with _bar(args, n_runs(problems, methods), "bench", "run") as bar:
            def step(msg: str) -> None:
                bar.set_postfix_str(msg)
                bar.update()

            for prob in problems:
                points += work_precision(prob, methods, repeats=repeats, progress=step)
        write_csv(points, csv_out.tmp)
        if png_out is not None:
            plot_work_precision(points, png_out.tmp, format="png")
        outs.commit()
    _main_table(points)
    for prob in problems:
        sp = speedup_at([p for p in points if p.problem == prob], error)
        if sp is None:
            print(f"{prob}: no pair of runs reaches relative error <= {_num(error, 6)} (ours and DOP853)")
        else:
            print(f"{prob}: at relative error <= {_num(error, 6)} {sp['method']} takes {sp['seconds']:.4f} s, "
                  f"DOP853 {sp['peer_seconds']:.4f} s: {sp['ratio']:.1f}x faster")
    print(f"written: {csv_out.path}")
    print(f"written: {png_out.path}" if png_out is not None
          else "PNG skipped: matplotlib is not installed (pip install 'hyperrotor[viz]')")
    return 0


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
        configure=_configure_verify,
        run=_run_verify,
    ),
    "bench": Subcommand(
        help="quick work-precision run (wall time vs relative error against closed forms), CSV + PNG",
        configure=_configure_bench,
        run=_run_bench,
    ),
    "scene": Subcommand(
        help="render the 3D projection of a body rotating in N dimensions to PNG (snapshots) or GIF",
        configure=_configure_scene,
        run=_run_scene,
    ),
}

_EPILOG = ("Exit status: 0 ok, 1 the work failed, 2 usage error (one line on stderr), 130 Ctrl-C, "
           "141 standard output closed early (e.g. '| head'), 143 SIGTERM. Output files are never "
           "overwritten without --force and never left half-written.")


def build_parser() -> argparse.ArgumentParser:
    """The ``hyperrotor`` argument parser with every registered subcommand."""
    from hyperrotor import __version__

    parser = _Parser(prog="hyperrotor", description="Rigid rotation in N dimensions, classical and quantum.",
                     epilog=_EPILOG)
    parser.add_argument("--version", action="version", version=f"hyperrotor {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True, parser_class=_Parser)
    for name, cmd in SUBCOMMANDS.items():
        p = sub.add_parser(name, help=cmd.help, description=cmd.help, epilog=_EPILOG)
        cmd.configure(p)
        p.set_defaults(_run=cmd.run)
    return parser


def _one_line(text: str) -> str:
    return re.sub(r"\s*\n\s*", " ", str(text)).strip()


def _say(prog: str, message: str) -> None:
    try:
        print(f"{prog}: {_one_line(message)}", file=sys.stderr, flush=True)
    except (OSError, ValueError):  # stderr closed too: nothing left to tell
        pass


def _silence_stdout() -> None:
    """After a broken pipe: point stdout at /dev/null so the interpreter's final flush stays quiet."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):
        pass


def _on_sigterm(signum, frame):
    raise _Terminated()


def main(argv: Sequence[str] | None = None) -> int:
    """Run ``hyperrotor`` with ``argv`` (default ``sys.argv[1:]``); returns the exit status.

    See the module docstring for the exit statuses and the one-line errors.
    ``--help`` and ``--version`` exit through ``SystemExit(0)`` (argparse).
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    debug = "--debug" in argv
    prog = "hyperrotor"
    if argv and argv[0] in SUBCOMMANDS:
        prog = f"hyperrotor {argv[0]}"
    try:
        old_term = signal.signal(signal.SIGTERM, _on_sigterm)
    except ValueError:  # not the main thread
        old_term = None
    try:
        args = build_parser().parse_args(argv)
        with warnings.catch_warnings(record=True) as caught:  # reported one line each, after the work
            warnings.simplefilter("default")
            code = int(args._run(args))
        for w in caught:
            _say(prog, f"warning: {w.category.__name__}: {w.message} ({Path(w.filename).name}:{w.lineno})")
        sys.stdout.flush()
        return code
    except UsageError as err:
        if debug:
            import traceback

            traceback.print_exc()
        _say(prog, f"error: {err}")
        return EXIT_CODES["usage"]
    except KeyboardInterrupt:
        _say(prog, "interrupted (Ctrl-C); unfinished output files were removed, existing files left as they were")
        return EXIT_CODES["interrupted"]
    except _Terminated:
        _say(prog, "terminated (SIGTERM); unfinished output files were removed")
        return EXIT_CODES["terminated"]
    except BrokenPipeError:
        _silence_stdout()
        return EXIT_CODES["broken-pipe"]
    except Exception as err:  # noqa: BLE001 - the command line reports every failure in one line
        if debug:
            import traceback

            traceback.print_exc()
        detail = f"{type(err).__name__}: {err}" if not isinstance(err, (OSError, RuntimeError)) or not str(err) \
            else str(err)
        _say(prog, f"failed: {detail}" + ("" if debug else " (--debug shows the traceback)"))
        return EXIT_CODES["failed"]
    finally:
        if old_term is not None:
            signal.signal(signal.SIGTERM, old_term)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
