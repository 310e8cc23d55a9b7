"""The ``hyperrotor`` command line.

One module per subcommand (:mod:`hyperrotor.cli.demo`, ``.verify``, ``.scene``,
``.bench``), each with ``configure(parser)`` (adds its options) and
``run(args) -> int`` (checks them and does the work), registered in
:data:`SUBCOMMANDS`. To add a subcommand, write the module and add one
:class:`Subcommand` entry to the table. Shared pieces live in
:mod:`hyperrotor.cli._common` (numbers, budgets, progress) and
:mod:`hyperrotor.cli._files` (output files). Nothing outside this package
imports it.

Subcommands
-----------
``demo``
    The 5D Euler equations (28)-(37) of the paper's quartet body (eqs. 84-85),
    its invariants on a sample angular velocity, closed form vs numerics, a PNG.
``verify``
    The preprint checked equation by equation (:mod:`hyperrotor.paper.verify`).
``scene``
    The 3D projection of a body rotating in N dimensions: PNG snapshots, a GIF or
    an interactive HTML page (the library's :meth:`hyperrotor.Scene.to_html`).
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
* **Exit status.** 0 success; 1 the work failed (one line on stderr, naming
  the files already written if any); 2 usage error; 130 interrupted by Ctrl-C
  (SIGINT), 143 terminated (SIGTERM), 129 hung up (SIGHUP), each within a
  second whatever the command is doing, numba compiling included
  (:mod:`hyperrotor.cli._signals`; while the package is imported, the console script's launcher
  ``_hyperrotor_launch``, outside the package); 141 standard output closed early
  (``hyperrotor demo | head -1``): the command
  stops quietly with the status a shell reports for a program ended by
  SIGPIPE, as ``yes | head -1`` does (so ``set -o pipefail`` treats both alike).
  ``--debug`` adds the Python traceback to an error.
* **Output files** are never overwritten unless ``--force`` is given. Each is
  written to a hidden temporary file in its target folder and renamed when
  complete, so an error or an interrupt leaves no partial file and the earlier
  file (if any) intact (:mod:`hyperrotor.cli._files`).
* **Progress** bars (tqdm) go to stderr, for work that can take more than a few
  seconds (scene, bench, verify), when stderr is a terminal or with
  ``--progress`` (``--no-progress`` turns them off).
* **Warnings** (e.g. numerical ones from NumPy) are reported as they are raised,
  one line each (``hyperrotor demo: warning: RuntimeWarning: ...``).
* **Negative values** follow their option directly (``--kappa -1/2``, ``--t-end -1e3`` is refused as
  not > 0 by its own check), as ``--kappa=-1/2`` does.
* **Numbers** print as plain values with 12 significant digits (``-0.33``, not
  ``-0.32999999999999996``); values in error messages via
  :func:`hyperrotor._validate.fmt`.
"""
from __future__ import annotations

import argparse
import os
import re
import signal
import sys
import time
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Sequence

from hyperrotor.cli import _files, _signals, bench, demo, scene, verify
from hyperrotor._parallel import interrupts_as_raised
from hyperrotor._pricing import BudgetError
from hyperrotor.cli._common import UsageError, budget_message

__all__ = ["main", "build_parser", "Subcommand", "SUBCOMMANDS", "UsageError", "EXIT_CODES"]

#: The exit statuses of ``hyperrotor`` (module docstring).
EXIT_CODES = {"ok": 0, "failed": 1, "usage": 2, "hung-up": 129, "interrupted": 130, "broken-pipe": 141,
              "terminated": 143}


@dataclass(frozen=True)
class Subcommand:
    """A registered subcommand: its help text, option set-up and action."""

    help: str
    configure: Callable[[argparse.ArgumentParser], None]
    run: Callable[[argparse.Namespace], int]


class _Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line (raised as :class:`UsageError`), and which reads every value
    that starts like a negative number (``-1e3``, ``-1/2``, ``-inf``, ``-2e0``) as a value, not as an option:
    argparse's own pattern knows only ``-12`` and ``-1.5``, and ``--kappa -1/2`` was refused as "expected one
    argument" without naming the value (the value's own check then names it, e.g. "--t-end must be > 0")."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r"^-(?:\d|\.\d|inf|nan)", re.IGNORECASE)  # (argparse's hook)

    def error(self, message: str):  # noqa: D401 - argparse API
        raise UsageError(f"{message} (see '{self.prog} --help')")


# ----------------------------------------------------------------------------
# registry and entry point
# ----------------------------------------------------------------------------
#: name -> Subcommand. Add new subcommands here.
SUBCOMMANDS: dict[str, Subcommand] = {
    "demo": Subcommand(
        help="print the 5D Euler equations (28)-(37) of the paper's quartet body and its invariants",
        configure=demo.configure,
        run=demo.run,
    ),
    "verify": Subcommand(
        help="check the preprint equation by equation (holds / typo / claim-false / not-checkable)",
        configure=verify.configure,
        run=verify.run,
    ),
    "bench": Subcommand(
        help="quick work-precision run (wall time vs relative error against closed forms), CSV + PNG",
        configure=bench.configure,
        run=bench.run,
    ),
    "scene": Subcommand(
        help="render the 3D projection of a body rotating in N dimensions to PNG (snapshots), GIF or an "
             "interactive HTML page (--output FILE.html)",
        configure=scene.configure,
        run=scene.run,
    ),
}

_EPILOG = ("Exit status: 0 ok, 1 the work failed, 2 usage error (one line on stderr), 130 Ctrl-C, "
           "141 standard output closed early (e.g. '| head'), 143 SIGTERM, 129 SIGHUP. Output files are never "
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


def _stopped(prog: str, stop: _signals.Stop) -> int:
    """A signal acted on: unfinished files removed, one line on stderr, the signal's exit status."""
    _files.discard_all()
    if _signals.claim():
        _say(prog, _signals.message(stop.signum))
    else:  # the watchdog is reporting and ending the process right now
        time.sleep(2 * _signals.GRACE)
    return stop.status


def main(argv: Sequence[str] | None = None) -> int:
    """Run ``hyperrotor`` with ``argv`` (default ``sys.argv[1:]``); returns the exit status.

    See the module docstring for the exit statuses and the one-line errors.
    ``--help`` and ``--version`` exit through ``SystemExit(0)`` (argparse).
    Called as the program (``argv`` None) and stopped by a signal, the process
    ends right after the one-line report (``os._exit``), within the second the
    signals promise; called with ``argv`` it returns the status like any function.
    """
    as_program = argv is None  # the console script and python -m hyperrotor.cli pass no argv
    argv = list(sys.argv[1:] if argv is None else argv)
    prog = "hyperrotor"
    if argv and argv[0] in SUBCOMMANDS:
        prog = f"hyperrotor {argv[0]}"
    _files.forget_written()
    installed = _signals.install(prog)
    try:
        code = _run(argv, prog)
    except _signals.Stop as stop:  # a signal in the last moments, after _run's own handlers
        code = _stopped(prog, stop)
    finally:
        _files.discard_all()
        if installed:
            _signals.restore()
    if as_program and installed and code in _signals.STATUSES:
        _exit_now(code)
    return code


def _exit_now(code: int) -> None:
    """End the program at once after a signal: the interpreter's own exit (tearing down numba, SymPy,
    matplotlib) can take over a second on a loaded machine, and the promise is a second."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            pass
    os._exit(code)


def _written_note() -> str:
    written = _files.written_files()
    return f" (written before the failure, complete: {', '.join(map(str, written))})" if written else ""


def _run(argv: list[str], prog: str) -> int:
    debug = "--debug" in argv
    args = None
    try:
        args, extra = build_parser().parse_known_args(argv)
        if extra:  # (argparse's own message pointed to 'hyperrotor --help', not the subcommand's)
            raise UsageError(f"unrecognized arguments: {' '.join(extra)} (see 'hyperrotor {args.command} --help')")
        # (a Stop raised by the handler inside numba's dispatch comes out as a SystemError: re-raised as the Stop)
        with warnings.catch_warnings(), interrupts_as_raised():
            warnings.simplefilter("default")
            # each warning one line on stderr when it is raised: a slow run's warning before the run, not after
            # it (and not lost when the work fails later)
            warnings.showwarning = lambda message, category, filename, lineno, file=None, line=None: _say(
                prog, f"warning: {category.__name__}: {message} ({Path(filename).name}:{lineno})")
            code = int(args._run(args))
        _signals.checkpoint()  # a signal that could not be acted on during the work
        sys.stdout.flush()
        return code
    except UsageError as err:
        if debug:
            import traceback

            traceback.print_exc()
        _say(prog, f"error: {err}")
        return EXIT_CODES["usage"]
    except BudgetError as err:  # a refusal that no subcommand check caught first: still one line, CLI wording
        if debug:
            import traceback

            traceback.print_exc()
        _say(prog, f"error: {budget_message(err, args)}" + _written_note())
        return EXIT_CODES["usage"]
    except _signals.Stop as stop:
        return _stopped(prog, stop)
    except KeyboardInterrupt:  # not the main thread: Python's own Ctrl-C
        return _stopped(prog, _signals.Stop(signal.SIGINT))
    except BrokenPipeError:
        _silence_stdout()
        if _files.written_files():
            _say(prog, "standard output was closed early" + _written_note())
        return EXIT_CODES["broken-pipe"]
    except Exception as err:  # noqa: BLE001 - the command line reports every failure in one line
        if debug:
            import traceback

            traceback.print_exc()
        detail = f"{type(err).__name__}: {err}" if not isinstance(err, (OSError, RuntimeError)) or not str(err) \
            else str(err)
        _say(prog, f"failed: {detail}" + _written_note() + ("" if debug else " (--debug shows the traceback)"))
        return EXIT_CODES["failed"]
