"""Signals of the ``hyperrotor`` command: SIGINT -> 130, SIGTERM -> 143, SIGHUP -> 129, within a second.

The handler records the signal (a flag) and acts on it at a safe point:

* in plain Python code it raises :class:`Stop` at once, so the command unwinds
  as from an error: every unfinished output file is removed, nothing else is
  touched, and :func:`hyperrotor.cli.main` returns the exit status;
* inside numba (compiling or loading a kernel) or while an output file is
  reserved or committed (:mod:`hyperrotor.cli._files`), raising would be
  swallowed or would break a half-built object (numba then fails later with
  "no compiled object yet", or carries on to the end): there the flag is only
  recorded, and :func:`checkpoint` (called between the steps of the work)
  raises :class:`Stop` at the next safe point.

Inside matplotlib and Pillow (drawing a GIF or a PNG) the signal is deferred too: raised there,
it landed once in a weakref callback of matplotlib's transform tree, run by the garbage
collector, where Python drops exceptions ("Exception ignored in ..." with a traceback on
stderr) and the callback's own work is left undone. And inside tqdm: raised in a progress bar's
constructor, it once left a half-built bar whose ``__del__`` then failed on stderr
("AttributeError: 'tqdm_asyncio' object has no attribute 'disable'"); all of tqdm's code is
deferred, not only its constructors (its ``close`` and its write lock, several locks taken one
by one, leave a broken bar as well). A :class:`Stop` dropped in any other such callback (or
``__del__``) is not printed (the command's ``sys.unraisablehook``); the next safe point or the
watchdog acts on the signal.

Either way a watchdog thread, started by the first signal, ends the process
:data:`GRACE` seconds later if it is still alive (the flag was set where no
safe point comes soon, e.g. during a long compile; or the interpreter's exit
waits for worker threads to finish a compiled chunk): it removes every
unfinished output file (under the lock that serialises commits, so a file is
complete at its target or absent), reports the signal on stderr in one line
unless the command already did, and exits with the signal's status.
"""
from __future__ import annotations

import os
import signal
import sys
import threading

import _hyperrotor_launch as _launch

from hyperrotor.cli import _files

__all__ = ["Stop", "SIGNALS", "STATUSES", "GRACE", "install", "restore", "checkpoint", "claim", "message",
           "bar_shown"]

#: signal -> (exit status, how it is reported); defined by the command's launcher, which handles the signals
#: while the package is being imported (before :func:`install`)
SIGNALS = _launch.SIGNALS

#: The exit statuses of the signals.
STATUSES = frozenset(status for status, _ in SIGNALS.values())

#: Seconds between a signal and the watchdog's exit when the command has not ended by itself.
GRACE = 0.7

#: Modules in whose code a raised exception would be swallowed or leave a broken state.
_DEFER_IN = ("numba.", "llvmlite.", "hyperrotor.cli._files", "matplotlib.", "PIL.", "tqdm.")


class Stop(BaseException):
    """A signal acted on at a safe point (a BaseException, like KeyboardInterrupt: no ``except Exception`` stops it)."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum

    @property
    def status(self) -> int:
        return SIGNALS[self.signum][0]


class _State:
    prog = "hyperrotor"
    signum: int | None = None      # the first signal received during the command
    done = threading.Event()       # the command ended without a signal: the watchdog has nothing to do
    stopping = False               # a signal is being acted on: later signals are ignored
    bar_shown = False              # a progress bar is on stderr: the watchdog starts a new line
    reporter = threading.Lock()    # taken by whoever reports the signal: the command or the watchdog
    previous: dict = {}
    unraisablehook = None          # sys.unraisablehook before the command


def message(signum: int) -> str:
    """The one stderr line (without the program name) for a command ended by ``signum``."""
    text = SIGNALS[signum][1] + "; unfinished output files were removed, existing files left as they were"
    written = _files.written_files()
    if written:
        text += "; written before the signal: " + ", ".join(map(str, written))
    return text


def _deferred(frame) -> bool:
    while frame is not None:
        name = frame.f_globals.get("__name__", "")
        if name.startswith(_DEFER_IN):
            return True
        frame = frame.f_back
    return False


def _watchdog() -> None:
    if _State.done.wait(GRACE):
        return
    # GRACE seconds after the signal the process is still alive: the signal was not acted on (deferred
    # with no safe point since), or the interpreter's exit waits (worker threads finishing a chunk)
    _State.stopping = True
    _files.discard_all()
    signum = _State.signum
    if _State.reporter.acquire(blocking=False):  # the command has not reported it yet
        try:
            line = ("\n" if _State.bar_shown else "") + f"{_State.prog}: {message(signum)}\n"
            os.write(2, line.encode())
        except OSError:
            pass
    os._exit(SIGNALS[signum][0])


def _handler(signum, frame) -> None:
    if _State.stopping:
        return
    if _State.signum is None:
        _State.signum = signum
        threading.Thread(target=_watchdog, name="hyperrotor-signal-watchdog", daemon=True).start()
    if not _deferred(frame):
        _State.stopping = True
        raise Stop(_State.signum)


def _unraisable(unraisable) -> None:
    """``sys.unraisablehook`` during the command: a :class:`Stop` that Python dropped (raised inside a weakref
    callback or a ``__del__``) is not printed (the next :func:`checkpoint` or the watchdog acts on the signal);
    anything else goes to the previous hook."""
    if isinstance(unraisable.exc_value, Stop):
        return
    (_State.unraisablehook or sys.__unraisablehook__)(unraisable)


def install(prog: str) -> bool:
    """Install the handlers (main thread only; returns False elsewhere, where Python's defaults stay)."""
    if threading.current_thread() is not threading.main_thread():
        return False
    _State.prog, _State.signum, _State.stopping = prog, None, False
    _State.done = threading.Event()
    _State.reporter = threading.Lock()
    _State.previous = {s: signal.signal(s, _handler) for s in _launch.handled()}  # (inherited SIG_IGN stays)
    _State.unraisablehook, sys.unraisablehook = sys.unraisablehook, _unraisable
    return True


def restore() -> None:
    """The command has ended: put the previous handlers back, or, after a signal, keep ignoring signals.

    After a signal the watchdog stays armed: if the interpreter's exit takes
    longer than :data:`GRACE` (a worker thread finishing its chunk), it ends
    the process with the signal's status.
    """
    if _State.signum is None:
        _State.done.set()
        for s, old in _State.previous.items():
            signal.signal(s, _launch.after_command(old))
        _State.previous = {}
        if sys.unraisablehook is _unraisable:
            sys.unraisablehook = _State.unraisablehook or sys.__unraisablehook__
    else:
        _State.stopping = True


def bar_shown(shown: bool) -> None:
    """A progress bar is (``True``) or is no longer (``False``) drawn on stderr."""
    _State.bar_shown = shown


def checkpoint() -> None:
    """A safe point: raise :class:`Stop` if a signal arrived while it could not be acted on (and ignore the
    signals that follow: one Stop per command)."""
    if _State.signum is not None:
        _State.stopping = True
        raise Stop(_State.signum)


def claim() -> bool:
    """The command acts on the signal: True if it reports it, False if the watchdog already does."""
    _State.stopping = True
    return _State.reporter.acquire(blocking=False)

