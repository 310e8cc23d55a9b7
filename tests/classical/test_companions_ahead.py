"""The step control's companions on a second core while the run advances (``chunks.pair_ahead``): the same
numbers, steps, work and verdicts as running them after the run, on one-call and chunked runs; the thread is
used only from the main thread, with a second core, and is made again in a forked child."""
import multiprocessing
import signal
import subprocess
import sys
import threading

import numpy as np
import pytest

import hyperrotor as hr
from hyperrotor import Inertia, RigidBody, _parallel
from hyperrotor.classical.solvers import chunks, richardson_check

J5 = [0.3, 0.55, 0.9, 1.4, 2.1]

CASES = {  # method, rtol, ensemble shape, span (negative: backwards), chunk_seconds (small: chunks), extra keywords
    "splitting8-one-call": ("splitting8", 1e-6, (), 20.0, None),
    "splitting8-attitude": ("splitting8", 1e-8, (), 20.0, None, dict(attitude=True)),
    "splitting6-backwards": ("splitting6", 1e-8, (), -20.0, None),
    "splitting8-ensemble-events": ("splitting8", 1e-8, (4,), 40.0, None, dict(events=lambda t, w: w[0])),
    "splitting8-tight": ("splitting8", 1e-9, (), 20.0, None),
    "splitting10-roundoff-twin": ("splitting10", 1e-12, (), 20.0, None),
    "splitting8-ensemble": ("splitting8", 1e-8, (5,), 40.0, None),
    "splitting8-chunked": ("splitting8", 1e-8, (), 40.0, 1e-6),
    "splitting10-compensated-chunked": ("splitting10", 1e-12, (), 20.0, 1e-6),
    "moser-veselov": ("moser-veselov", 1e-4, (), 5.0, None),
    "moser-veselov-chunked": ("moser-veselov", 1e-5, (), 5.0, 1e-6),
}


_JUDGE = richardson_check.RichardsonCheck.judge


class _ALL_KINDS(set):
    """Every kind of pair call counts as compiled (:func:`chunks.pair_ahead` declines the first of a kind)."""

    def __contains__(self, key):
        return True


def _run(body, w0, t, method, rtol, chunk_seconds, monkeypatch, **kw):
    """The trajectory and the companions' states at every sample the check judged (exact copies)."""
    seen = []
    judge = _JUDGE

    def spy(self, upto, Lf, L1, L2):
        seen.append((np.array(L1), np.array(L2)))
        return judge(self, upto, Lf, L1, L2)

    monkeypatch.setattr(richardson_check.RichardsonCheck, "judge", spy)
    with hr.options(**({} if chunk_seconds is None else {"chunk_seconds": chunk_seconds})):
        return hr.simulate(body, w0, t, method=method, rtol=rtol, **kw), seen


@pytest.mark.parametrize("case", list(CASES))
def test_companions_ahead_give_the_numbers_of_companions_after(case, rng, monkeypatch):
    method, rtol, members, span, chunk_seconds, *extra = CASES[case]
    kw = extra[0] if extra else {}
    body = RigidBody(Inertia.from_mass_tensor(J5))
    w0 = rng.normal(size=members + (10,))
    w0 /= np.abs(w0).max()
    t = np.linspace(0.0, span, 41)
    monkeypatch.setattr(_parallel, "default_workers", lambda: 2)  # (a second core, also on a one-core machine)
    monkeypatch.setattr(chunks, "AHEAD_MIN_SECONDS", 0.0)  # (every companion run goes ahead ...
    monkeypatch.setattr(chunks, "_PAIRED", _ALL_KINDS())  # ... also the first of its kind)
    if chunk_seconds is not None:  # (chunks of a few dozen steps)
        monkeypatch.setattr(chunks, "FIRST_CHUNK_FLOWS", 10_000)
    started = []
    real = _parallel.on_second_core

    def counted(func, *args):
        future = real(func, *args)
        started.append(future)
        return future

    monkeypatch.setattr(_parallel, "on_second_core", counted)
    ahead, seen_ahead = _run(body, w0, t, method, rtol, chunk_seconds, monkeypatch, **kw)
    assert started and all(f is not None for f in started)
    monkeypatch.setattr(_parallel, "on_second_core", lambda func, *args: None)
    after, seen_after = _run(body, w0, t, method, rtol, chunk_seconds, monkeypatch, **kw)
    np.testing.assert_array_equal(ahead.L, after.L)
    np.testing.assert_array_equal(ahead.omega, after.omega)
    assert len(seen_ahead) == len(seen_after) > 0
    for (a1, a2), (b1, b2) in zip(seen_ahead, seen_after):  # (the companions continue from their exact state)
        np.testing.assert_array_equal(a1, b1)
        np.testing.assert_array_equal(a2, b2)
    for key in ("steps", "work", "dt", "reruns", "method"):
        assert ahead.stats.get(key) == after.stats.get(key), key
    if kw.get("attitude"):
        np.testing.assert_array_equal(ahead.attitude, after.attitude)
    if "events" in kw:
        np.testing.assert_equal(ahead.t_events, after.t_events)  # (per member: nested lists of arrays)
        np.testing.assert_equal(ahead.L_events, after.L_events)
    if chunk_seconds is not None:
        assert ahead.stats["chunks"] > 1 and len(started) > 1  # (a companion run per chunk with samples)


def test_on_second_core_runs_in_the_callers_context(monkeypatch):
    monkeypatch.setattr(_parallel, "default_workers", lambda: 2)
    with hr.options(chunk_seconds=0.125):
        future = _parallel.on_second_core(lambda x: (x, hr.options["chunk_seconds"], threading.current_thread()), 3)
    x, seconds, thread = _parallel.result(future)
    assert (x, seconds) == (3, 0.125) and thread is not threading.main_thread()


def test_on_second_core_declines_without_a_second_core_or_off_the_main_thread(monkeypatch):
    monkeypatch.setattr(_parallel, "default_workers", lambda: 1)
    assert _parallel.on_second_core(int) is None
    monkeypatch.setattr(_parallel, "default_workers", lambda: 2)
    box = []
    worker = threading.Thread(target=lambda: box.append(_parallel.on_second_core(int)))
    worker.start()
    worker.join()
    assert box == [None]  # (dask's workers, a user's thread pool: their calls would queue for the one thread)


def _child(queue):
    queue.put(_parallel.result(_parallel.on_second_core(lambda: 42)))


@pytest.mark.skipif("fork" not in multiprocessing.get_all_start_methods(), reason="needs fork")
@pytest.mark.filterwarnings("ignore:This process .*is multi-threaded:DeprecationWarning")  # (Python >= 3.12: it is)
def test_on_second_core_works_in_a_forked_child(monkeypatch):
    """The parent's thread does not exist in a forked child: the child makes its own (the parent's executor
    there, with an idle worker it believes in, would never run the call)."""
    monkeypatch.setattr(_parallel, "default_workers", lambda: 2)
    assert _parallel.result(_parallel.on_second_core(lambda: 1)) == 1  # (the parent's thread exists now)
    ctx = multiprocessing.get_context("fork")
    queue = ctx.Queue()
    p = ctx.Process(target=_child, args=(queue,))
    p.start()
    p.join(60)
    if p.is_alive():
        p.kill()
    assert p.exitcode == 0 and queue.get(timeout=5) == 42


def test_the_first_pair_call_of_a_kind_runs_in_the_callers_thread(monkeypatch):
    """Its kernel may still compile, which Ctrl-C cannot stop on another thread (and the process's exit would
    wait for it): the first pair call of a kind runs where the caller is; later ones go ahead."""
    monkeypatch.setattr(_parallel, "default_workers", lambda: 2)
    monkeypatch.setattr(chunks, "AHEAD_MIN_SECONDS", 0.0)
    monkeypatch.setattr(chunks, "_PAIRED", set())
    body = RigidBody(Inertia.from_mass_tensor(J5))
    w0 = np.linspace(-1.0, 1.0, 10)
    with hr.options(chunk_seconds=1e-6):
        monkeypatch.setattr(chunks, "FIRST_CHUNK_FLOWS", 10_000)
        started = []

        def counted(*args, **kwargs):
            started.append(chunks.pair_ahead(*args, **kwargs))
            return started[-1]

        monkeypatch.setattr(richardson_check, "pair_ahead", counted)
        hr.simulate(body, w0, np.linspace(0.0, 40.0, 41), method="splitting8", rtol=1e-12)  # (compensated)
    kinds = {key[0] for key in chunks._PAIRED}
    assert any(variant[1] for variant in kinds)  # (the compensated kind ran)
    assert started[0] is None and any(f is not None for f in started[1:])  # (inline first, then ahead)


def test_a_failure_on_the_second_core_is_raised_to_the_caller(monkeypatch):
    monkeypatch.setattr(_parallel, "default_workers", lambda: 2)

    def fails():
        raise FloatingPointError("from the second core")

    future = _parallel.on_second_core(fails)
    with pytest.raises(FloatingPointError, match="from the second core"):
        _parallel.result(future)


def test_no_second_core_with_jit_off(monkeypatch):
    from hyperrotor import _jit

    monkeypatch.setattr(_parallel, "default_workers", lambda: 2)
    monkeypatch.setattr(_jit, "JIT_ENABLED", False)  # (the kernels would hold the GIL: nothing runs in parallel)
    assert _parallel.on_second_core(int) is None


def _child_run(code):
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=90)


def test_simulate_with_rtol_in_an_atexit_handler():
    """atexit handlers run after the executors have closed: the companions then run in the caller's thread."""
    code = ("import atexit, numpy as np, hyperrotor as hr\n"
            "from hyperrotor import _parallel\n"
            "from hyperrotor.classical.solvers import chunks\n"
            "_parallel.default_workers = lambda: 2\n"
            "chunks.AHEAD_MIN_SECONDS = 0.0\n"
            "run = lambda: hr.simulate([0.3, 0.55, 0.9, 1.4, 2.1, 0.7, 1.1, 0.45, 1.9, 2.6], np.linspace(-1, 1, 10),"
            " np.linspace(0, 20, 41), method='splitting8', rtol=1e-8)\n"
            "first = run()\n"
            "atexit.register(lambda: print('at exit', run().stats['steps'] == first.stats['steps'], flush=True))\n")
    p = _child_run(code)
    assert p.returncode == 0 and p.stdout.strip() == "at exit True", p.stderr


@pytest.mark.skipif(not hasattr(signal, "pthread_sigmask") or not hasattr(signal, "SIGUSR1"), reason="POSIX")
def test_a_signal_while_the_thread_starts_does_not_hang_the_exit():
    """A KeyboardInterrupt raised right after the executor started its thread, before it recorded it, left a
    thread the interpreter's exit waited for forever: signals are held off while the thread is handed the call
    (here the signal is sent from inside Thread.start, the worst moment)."""
    code = ("import os, signal, threading, time\n"
            "from hyperrotor import _parallel\n"
            "_parallel.default_workers = lambda: 2\n"
            "def interrupt(signum, frame):\n"
            "    raise KeyboardInterrupt\n"
            "signal.signal(signal.SIGUSR1, interrupt)\n"
            "start = threading.Thread.start\n"
            "def started(self):\n"
            "    start(self)\n"
            "    os.kill(os.getpid(), signal.SIGUSR1)\n"
            "threading.Thread.start = started\n"
            "try:\n"
            "    _parallel.on_second_core(time.sleep, 0.01)\n"
            "except KeyboardInterrupt:\n"
            "    print('interrupted', flush=True)\n")
    p = _child_run(code)
    assert p.returncode == 0 and p.stdout.strip() == "interrupted", (p.stdout, p.stderr)
