"""Launcher of the ``hyperrotor`` command (the console script's entry point), outside the package.

Importing :mod:`hyperrotor.cli` imports the package first (NumPy, SciPy, SymPy, numba: about a second),
and the command's signal handlers (:mod:`hyperrotor.cli._signals`) are installed only after that: a
Ctrl-C during the imports ended the command with Python's ``KeyboardInterrupt`` traceback. This module
imports nothing of the package and nothing heavy, so its handlers are in place within milliseconds of the
start: a signal before the command's own handlers take over ends it at once with one line on stderr and
the signal's exit status (the table :data:`SIGNALS`, which the command's handlers use too).
"""
from __future__ import annotations

import os
import signal
import sys

__all__ = ["SIGNALS", "after_command", "handled", "main"]

#: signal -> (exit status, how it is reported): the ``hyperrotor`` command's table (:mod:`hyperrotor.cli._signals`).
SIGNALS = {
    signal.SIGINT: (130, "interrupted (Ctrl-C)"),
    signal.SIGTERM: (143, "terminated (SIGTERM)"),
}
if hasattr(signal, "SIGHUP"):  # POSIX only
    SIGNALS[signal.SIGHUP] = (129, "hung up (SIGHUP)")


def _starting(signum, frame) -> None:  # pragma: no cover - runs in the command's process (tests/cli)
    status, word = SIGNALS[signum]
    try:
        os.write(2, f"hyperrotor: {word} while starting; nothing was written\n".encode())
    except OSError:
        pass
    os._exit(status)  # (no unwinding through half-imported modules)


def _ending(signum, frame) -> None:  # pragma: no cover - runs in the command's process (tests/cli)
    _pending.append(signum)  # (the command has ended; main's finally ends the process with its status)


_pending: list = []


def after_command(handler):
    """The handler to put back when the command's own handlers end (:func:`hyperrotor.cli._signals.restore`):
    in place of the starting handler, one that leaves the signal to :func:`main` (its report, "while starting;
    nothing was written", would be wrong once the command has run)."""
    return _ending if handler is _starting else handler


def _finished(status: int):
    def handler(signum, frame) -> None:  # pragma: no cover - runs in the command's process
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):
                pass
        os._exit(status)  # (the work is done and reported: the interpreter's teardown is all that is cut short)

    return handler


def handled() -> list:
    """The signals of :data:`SIGNALS` the command handles: all but those it inherited ignored (``nohup`` ignores
    SIGHUP, a non-interactive shell SIGINT for a background job ``&``), which stay ignored."""
    return [s for s in SIGNALS if signal.getsignal(s) is not signal.SIG_IGN]


def main() -> int:
    """Install the starting handlers, import the command and run it (its own handlers replace these while it
    runs); once it has ended (returned or raised ``SystemExit``: ``--help``, ``--version``), a signal during the
    interpreter's teardown (numba, SymPy, matplotlib: up to a second) ends the process quietly with the command's
    status."""
    signals = handled()
    for signum in signals:
        signal.signal(signum, _starting)
    status = 1
    try:
        from hyperrotor.cli import main as command

        status = command()
        return status
    except SystemExit as exc:
        status = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
        raise
    finally:
        for signum in signals:
            signal.signal(signum, _finished(status))
        if _pending:  # (a signal between the command's end and the line above)
            _finished(status)(_pending[0], None)


if __name__ == "__main__":
    sys.exit(main())
