"""``hyperrotor bench``: a quick work-precision run (:mod:`hyperrotor.bench`), a CSV and a PNG."""
from __future__ import annotations

import argparse
import os
from pathlib import Path

from hyperrotor import _validate
from hyperrotor.cli._common import (UsageError, add_common, bar, check_budget, check_common, choice_of, have_matplotlib,
                                    integer, num, number, usage)
from hyperrotor.cli._files import Outputs, output_file

__all__ = ["configure", "run", "bench_paths", "BENCH_STEM"]


BENCH_STEM = "hyperrotor-bench"


def configure(p: argparse.ArgumentParser) -> None:
    from hyperrotor.bench import BENCH_METHODS, BENCH_PROBLEMS

    p.add_argument("--problem", action="append", choices=BENCH_PROBLEMS, type=choice_of(BENCH_PROBLEMS),
                   help="problem with an exact solution (repeatable; default: all)")
    p.add_argument("--method", action="append", default=None, choices=BENCH_METHODS, type=choice_of(BENCH_METHODS),
                   metavar="METHOD", help=f"{', '.join(BENCH_METHODS)} (any case; repeatable; default: all)")
    p.add_argument("--repeats", default=2, help="timed repeats per run, best kept (default 2)")
    p.add_argument("--error", default=1e-10,
                   help="relative error level (0 < error < 1) at which the speed-up over DOP853 is reported "
                        "(default 1e-10)")
    p.add_argument("--output", default=BENCH_STEM, metavar="STEM",
                   help=f"where the results go: STEM.csv and STEM.png (default ./{BENCH_STEM}). A trailing .csv "
                        f"or .png is dropped (b.png -> b.csv, b.png); a folder (existing, or written with a "
                        f"trailing /) gets {BENCH_STEM}.csv and .png inside; a STEM with no name before the extension "
                        f"(.csv, dir/.png) is refused. Existing files are kept unless --force")
    add_common(p, budget=True)


def bench_paths(stem: str) -> tuple[Path, Path]:
    """The CSV and PNG written by ``hyperrotor bench --output stem`` (naming rule of its --help).

    Parameters
    ----------
    stem : str
        The value of ``--output``: a stem (``b``, ``out/b``), a stem with a trailing ``.csv`` or ``.png``
        (dropped, any case: ``b.png``), or a folder (existing, or written with a trailing ``/``).

    Returns
    -------
    tuple of Path
        The CSV and the PNG.

    Raises
    ------
    UsageError
        An empty stem, or a stem with no name before the extension (``.csv``, ``dir/.png``, ``' .csv'``):
        it would write hidden or blank-named files such as ``.csv.csv``.
    """
    if not stem or not stem.strip():
        raise UsageError(f"--output needs a file stem or a folder, got {'an empty string' if not stem else repr(stem)}")
    path = Path(stem).expanduser()
    if stem.endswith(("/", os.sep)) or path.is_dir():
        path = path / BENCH_STEM
    else:
        # (a name that is only the extension, '.csv', has no suffix for pathlib: matched on the text)
        ext = next((e for e in (".csv", ".png") if path.name.lower().endswith(e)), "")
        name = path.name[:len(path.name) - len(ext)]
        if not name.replace(".", "").strip():
            why = f"no name before {path.name[len(name):]}" if ext else "a name of dots and spaces only"
            raise UsageError(f"--output needs a file stem or a folder, got {stem!r} ({why}); "
                             f"e.g. --output b writes b.csv and b.png")
        path = path.with_name(name)
    return path.with_name(path.name + ".csv"), path.with_name(path.name + ".png")


def run(args: argparse.Namespace) -> int:
    from hyperrotor.bench import (estimate_seconds, n_runs, plot_work_precision, print_table, speedup_at,
                                  work_precision, write_csv)

    check_common(args)
    problems = list(dict.fromkeys(args.problem or ["quartet", "euler-poinsot"]))
    methods = None if args.method is None else list(dict.fromkeys(args.method))
    repeats = integer(args.repeats, "--repeats", minimum=1)
    error = usage(_validate.positive, "--error", number(args.error, "--error"))
    if error >= 1:
        raise UsageError(f"--error is a relative error level and must be < 1, got {_validate.fmt(error)}")
    check_budget(args, f"bench with --repeats {num(repeats, 6)}", estimate_seconds(problems, methods, repeats),
                  hint="use fewer --repeats, --problem or --method")
    csv_path, png_path = bench_paths(args.output)
    plot = have_matplotlib()
    with Outputs() as outs:
        csv_out = outs.add(usage(output_file, str(csv_path), option="--output", suffixes=(".csv",),
                                  force=args.force))
        png_out = outs.add(usage(output_file, str(png_path), option="--output", suffixes=(".png",),
                                  force=args.force)) if plot else None
        # --- work ------------------------------------------------------------------
        points = []
        with bar(args, n_runs(problems, methods), "bench", "run") as pbar:
            def step(msg: str) -> None:
                pbar.set_postfix_str(msg)
                pbar.update()

            for prob in problems:
                points += work_precision(prob, methods, repeats=repeats, callback=step)
        write_csv(points, csv_out.tmp)
        if png_out is not None:
            plot_work_precision(points, png_out.tmp, format="png")
        outs.commit()
    print_table(points)
    for prob in problems:
        sp = speedup_at([p for p in points if p.problem == prob], error)
        if sp is None:
            print(f"{prob}: no pair of runs reaches relative error <= {num(error, 6)} (ours and DOP853)")
        else:
            print(f"{prob}: at relative error <= {num(error, 6)} {sp['method']} takes {sp['seconds']:.4f} s, "
                  f"DOP853 {sp['peer_seconds']:.4f} s: {sp['ratio']:.1f}x faster")
    print(f"written: {csv_out.path}")
    print(f"written: {png_out.path}" if png_out is not None
          else "PNG skipped: matplotlib is not installed (pip install 'hyperrotor[viz]')")
    return 0
