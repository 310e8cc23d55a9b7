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

Either way a watchdog ends the process :data:`GRACE` seconds after the first
signal if it is still alive (the flag was set where no safe point comes soon,
e.g. during a long compile; the main thread is inside one long compiled call,
a numba kernel or a LAPACK routine, where Python does not run the handler at
all until the call returns; or the interpreter's exit waits for worker threads
to finish a compiled chunk): it removes every unfinished output file (under
the lock that serialises commits, so a file is complete at its target or
absent), reports the signal on stderr in one line unless the command already
did, and exits with the signal's status.

The watchdog does not wait for the Python-level handler: :func:`install`
starts a listener thread that reads a pipe registered with
:func:`signal.set_wakeup_fd`, where the C-level handler writes the signal's
number at once, whatever the main thread is doing; the listener starts the
grace period there and then. (Where no wakeup pipe can be registered, the
handler starts it, as a fallback.) This works while the main thread is in code
that releases the GIL (numba's kernels, compiled ``nogil``, NumPy's sorts and
linear algebra); C code that holds the GIL keeps every Python thread waiting.
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
    armed = False                  # the watchdog's grace period has started (once per command)
    arming = threading.Lock()      # serialises the listener and the handler starting it
    wakeup_w: int | None = None    # the write end of the wakeup pipe (signal.set_wakeup_fd), while registered
    wakeup_previous = -1           # the wakeup fd before the command


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


def _arm(signum: int) -> None:
    """Start the watchdog's grace period (any thread; once per command): the first signal's number is kept."""
    with _State.arming:
        if _State.armed:
            return
        _State.armed = True
        if _State.signum is None:  # (the listener may come first: the handler then sees the signal as recorded)
            _State.signum = signum
    threading.Thread(target=_watchdog, args=(_State.done,), name="hyperrotor-signal-watchdog", daemon=True).start()


def _watchdog(done: threading.Event) -> None:
    if done.wait(GRACE):
        return
    # GRACE seconds after the signal the process is still alive: the signal was not acted on (deferred
    # with no safe point since, or the main thread is inside one long compiled call), or the interpreter's
    # exit waits (worker threads finishing a chunk)
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
    _arm(signum)  # (usually the listener has done it already, when the signal arrived)
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
    _State.prog, _State.signum, _State.stopping, _State.armed = prog, None, False, False
    _State.done = threading.Event()
    _State.reporter = threading.Lock()
    _State.arming = threading.Lock()
    _State.previous = {s: signal.signal(s, _handler) for s in _launch.handled()}  # (inherited SIG_IGN stays)
    _listen(frozenset(_State.previous), _State.done)
    _State.unraisablehook, sys.unraisablehook = sys.unraisablehook, _unraisable
    return True


def _listen(signals: frozenset, done: threading.Event) -> None:
    """Register a wakeup pipe (:func:`signal.set_wakeup_fd`) and start the thread that arms the watchdog the
    moment one of ``signals`` arrives, even while the main thread is inside a long compiled call."""
    try:
        r, w = os.pipe()
    except OSError:
        return
    try:
        os.set_blocking(w, False)  # (required by set_wakeup_fd; a full pipe drops the byte, never blocks)
        _State.wakeup_previous = signal.set_wakeup_fd(w, warn_on_full_buffer=False)
    except (OSError, ValueError, AttributeError):  # (Windows wants a socket): the handler arms the watchdog
        os.close(r)
        os.close(w)
        return
    _State.wakeup_w = w
    threading.Thread(target=_listener, args=(r, signals, done), name="hyperrotor-signal-listener", daemon=True).start()


def _listener(r: int, signals: frozenset, done: threading.Event) -> None:
    """Read signal numbers from the wakeup pipe until its write end is closed (:func:`restore`): the first of
    ``signals`` arms the watchdog of the command whose end is ``done`` (a byte read after that command ended,
    while a next command runs, arms nothing). It keeps reading afterwards, so later signals never find the pipe
    closed."""
    try:
        while True:
            try:
                data = os.read(r, 64)
            except InterruptedError:
                continue
            except OSError:
                return
            if not data:  # the command ended without a signal: restore() closed the write end
                return
            for signum in data:
                if signum in signals and not done.is_set():
                    _arm(signum)
    finally:
        os.close(r)


def _unlisten() -> None:
    """Unregister the wakeup pipe (the previous wakeup fd back) and close its write end: the listener ends."""
    w, _State.wakeup_w = _State.wakeup_w, None
    if w is None:
        return
    try:
        signal.set_wakeup_fd(_State.wakeup_previous)
    except (OSError, ValueError):
        signal.set_wakeup_fd(-1)
    os.close(w)


def restore() -> None:
    """The command has ended: put the previous handlers back, or, after a signal, keep ignoring signals.

    After a signal the watchdog stays armed: if the interpreter's exit takes
    longer than :data:`GRACE` (a worker thread finishing its chunk), it ends
    the process with the signal's status.
    """
    if _State.signum is None:
        _State.done.set()
        _unlisten()
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

