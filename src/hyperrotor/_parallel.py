r"""Ensembles in chunks: in-process on all cores, or on a ``dask.distributed`` cluster.

One helper, :func:`map_rows`, serves every ensemble-capable entry point of the
package (``simulate`` with a 2-D ``omega0``, :func:`hyperrotor.lyapunov`, the
Lyapunov sweep, sector spectra): the caller hands it a *picklable top-level*
function ``func`` and the rows of the ensemble; :func:`map_rows` cuts the rows
into contiguous chunks, runs ``func(chunk, *args)`` on each, and puts the results
back together in the original order::

    out = map_rows(func, rows, args=(tables,), client=client)   # == func(rows, *tables)

``rows`` is one array (leading axis = ensemble members) or a tuple of arrays
sharing the leading axis (then ``func(*chunks, *args)``); :func:`grid_rows` makes
such a tuple from a grid of parameters x initial conditions. ``func`` returns an
array, or a tuple of arrays, whose leading axis has one entry per row of its
chunk; the chunks' results are concatenated along that axis.

Where the work runs
-------------------
``client=None`` (default)
    in this process, on ``workers`` threads (default: all cores available to the
    process). The threads run compiled kernels that release the GIL
    (:func:`hyperrotor._jit.jit` compiles with ``nogil=True``), so they use all
    cores without pickling anything. ``workers=1`` runs the chunks one after the
    other in the calling thread.
``client=`` a :class:`dask.distributed.Client`
    each chunk is one dask task (``client.submit``) on the cluster the client is
    connected to: a :class:`~dask.distributed.LocalCluster` of processes on a
    laptop, or the workers of an HPC batch system (``dask-jobqueue``) or of a cloud
    cluster (``dask-kubernetes``); only the client changes (``docs/scaling-out.md``).
    ``func`` and the chunks are pickled to the workers, which must have
    ``hyperrotor`` installed. dask is an optional dependency
    (``pip install "hyperrotor[distributed]"``), imported here only when a client is
    given.

A second core for one call
--------------------------
:func:`on_second_core` starts a short compiled call on a thread of its own while the main thread works on
(the step control's companion runs beside the run they check: ``classical/solvers/chunks.pair_ahead``), and
:func:`result` waits for it in slices; where there is no second core, or the caller is not the main thread,
the caller runs the call itself. The same numbers either way.

Results do not depend on the chunking
-------------------------------------
Each row's result is computed by the same compiled arithmetic whichever chunk it
falls in (the kernels handle rows independently, and numba compiles without
``fastmath``), so in-process, threaded and distributed runs agree bit for bit as
long as the machines run the same compiled code (same numba version and CPU
features; across heterogeneous machines differences stay at round-off level). Row
functions that call LAPACK (the sector spectra) agree bit for bit only at equal BLAS
thread counts: ``sector_spectra`` uses one per sector with ``workers > 1`` and on a
cluster, all of them by default (round-off-level differences from the others).

Interruption and progress
-------------------------
Chunks are small enough (the caller sets ``chunk_size`` from its cost estimate)
that Ctrl-C is honoured within about a chunk's run time: the pending chunks are
cancelled (dask: ``client.cancel``) and :class:`KeyboardInterrupt` propagates.
``progress=True`` shows a tqdm bar counting finished rows; ``None`` shows it only
on a terminal and only when the run lasts longer than a second.
"""
from __future__ import annotations

import contextlib
import contextvars
import math
import os
import queue
import signal
import sys
import threading
from typing import Any, Callable, Sequence

import numpy as np

from . import _validate
from ._options import options

__all__ = ["map_rows", "grid_rows", "import_distributed", "client_threads", "default_workers", "interruptible",
           "on_second_core", "result", "interrupts_as_raised"]

_INSTALL_HINT = 'pip install "hyperrotor[distributed]"'
#: chunks per worker thread when ``chunk_size`` is not given (load balance vs per-task overhead)
_CHUNKS_PER_WORKER = 4


def import_distributed():
    """Import and return :mod:`dask.distributed`, or raise an ImportError saying how to install it."""
    try:
        import dask.distributed as dd
    except ImportError as exc:  # pragma: no cover - dask is installed in the test environment
        raise ImportError(
            f"client= needs dask.distributed, which is not installed; install the optional extra with "
            f"`{_INSTALL_HINT}` (or `pip install \"dask[distributed]\"`)"
        ) from exc
    return dd


def default_workers() -> int:
    """Number of cores available to this process (the default thread count of :func:`map_rows`)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not on Linux
        return max(1, os.cpu_count() or 1)


def client_threads(client: Any) -> int:
    """Total worker threads of a dask ``client``'s cluster (at least 1)."""
    _validate.client(client)
    try:
        info = client.scheduler_info()
        return max(1, sum(int(w.get("nthreads", 1)) for w in info.get("workers", {}).values()))
    except Exception:  # pragma: no cover - a client without scheduler_info (duck-typed)
        return 1


def grid_rows(params: Any, initial: Any) -> tuple[np.ndarray, np.ndarray]:
    """Rows of the grid ``params x initial``: every parameter row with every initial condition.

    Parameters
    ----------
    params : array_like (P, ...)
        one parameter set per row (e.g. plane moments, ``(P, n)``).
    initial : array_like (M, ...)
        one initial condition per row.

    Returns
    -------
    (ndarray (P*M, ...), ndarray (P*M, ...))
        row ``p * M + m`` pairs ``params[p]`` with ``initial[m]`` (parameter-major), so a result
        of :func:`map_rows` on these rows reshapes to ``(P, M, ...)``.
    """
    params = _validate.finite_array("params", params)
    initial = _validate.finite_array("initial", initial)
    if params.ndim < 1 or initial.ndim < 1:
        raise ValueError(f"params and initial need a leading axis (one row per member), got shapes "
                         f"{params.shape} and {initial.shape}")
    P, M = params.shape[0], initial.shape[0]
    return np.repeat(params, M, axis=0), np.tile(initial, (P,) + (1,) * (initial.ndim - 1))


def _as_rows(rows: Any) -> tuple[tuple[np.ndarray, ...], bool]:
    single = not isinstance(rows, tuple)
    arrs = (rows,) if single else rows
    if not arrs:
        raise ValueError("rows must be an array or a non-empty tuple of arrays")
    out = []
    for k, a in enumerate(arrs):
        a = np.asarray(a)
        if a.ndim < 1:
            raise ValueError(f"rows[{k}] needs a leading ensemble axis, got a scalar")
        out.append(a)
    B = out[0].shape[0]
    lens = [a.shape[0] for a in out]
    if any(n != B for n in lens):
        raise ValueError(f"the arrays of rows must share their leading (ensemble) axis, got lengths {lens}")
    return tuple(out), single


def _concat(parts: list) -> Any:
    first = parts[0]
    if isinstance(first, tuple):
        return tuple(np.concatenate([p[k] for p in parts], axis=0) for k in range(len(first)))
    return np.concatenate(parts, axis=0)


def progress_bar(progress: bool | None, total: float, desc: str | None = None, *, unit: str = "row",
                 leave: bool | None = None):
    """The package's one progress bar (tqdm on stderr), or ``None`` when none is wanted.

    ``progress=True``: always shown; ``False``: never; ``None``: only on a terminal,
    and only once the work has taken a second (tqdm's ``delay``). ``total`` is in
    ``unit``s; callers advance it with ``bar.update(n)`` and close it. ``leave``
    (default: ``progress is True``) keeps the finished bar on screen.
    """
    progress = _validate.flag("progress", progress, allow_none=True)  # (the entry points check it first; a backstop)
    if progress is False or total == 0:
        return None
    if progress is None and not (hasattr(sys.stderr, "isatty") and sys.stderr.isatty()):
        return None
    from tqdm.auto import tqdm

    return tqdm(total=total, desc=desc, unit=unit, delay=0.0 if progress else 1.0,
                leave=bool(progress) if leave is None else leave)


class _WithOptions:
    """``func`` run under the option values of the caller's context (picklable: a dask task carries it).

    Worker threads do not inherit the caller's :mod:`contextvars` context, and dask
    workers run in other processes; both must see the budgets and tolerances of the
    ``with hr.options(...)`` block that started the run (docs/safety.md, threads).
    """

    def __init__(self, func: Callable, values: dict) -> None:
        self.func = func
        self.values = values  # options.portable(): changed values and the modules registering them

    def __call__(self, *a: Any) -> Any:
        with options.apply_portable(self.values):
            return self.func(*a)


def map_rows(
    func: Callable,
    rows: Any,
    *,
    args: Sequence = (),
    client: Any = None,
    chunk_size: int | None = None,
    workers: int | None = None,
    progress: bool | None = None,
    desc: str | None = None,
) -> Any:
    r"""Run ``func`` on chunks of ``rows`` (in-process threads or a dask client), results in order.

    Parameters
    ----------
    func : callable
        ``func(*chunks, *args) -> ndarray or tuple of ndarrays`` (leading axis = rows of
        the chunk). With ``client`` it must be picklable: a top-level function of an
        importable module. In threads it must not start numba ``parallel=True`` kernels
        (use the serial compile; the threads are the parallelism).
    rows : ndarray (B, ...) or tuple of ndarrays (B, ...)
        the ensemble (one member per row); a tuple is cut row-wise in step.
    args : sequence
        extra arguments passed unchanged to every call (keep them small: with a client
        they are pickled with every task).
    client : dask.distributed.Client, optional
        run the chunks as dask tasks on its cluster; ``None`` runs in this process.
    chunk_size : int, optional
        rows per chunk; default ``ceil(B / (4 * threads))`` (four chunks per worker thread).
    workers : int, optional
        in-process threads (default: all available cores); ignored with a ``client``.
    progress : bool or None
        tqdm bar of finished rows: ``True`` always, ``False`` never, ``None`` on a terminal
        for runs longer than a second.
    desc : str, optional
        label of the progress bar.

    Returns
    -------
    ndarray or tuple of ndarrays
        the chunks' results concatenated along axis 0: equal to ``func(*rows, *args)``
        (bit for bit when ``func`` treats rows independently, see the module docstring).

    Raises
    ------
    TypeError
        ``client`` is not a dask client; ``chunk_size`` / ``workers`` not integers.
    ValueError
        arrays of ``rows`` with different leading lengths; ``chunk_size`` / ``workers`` < 1.
    ImportError
        a client is given but ``dask.distributed`` is missing (names the pip extra).
    """
    arrs, _ = _as_rows(rows)
    args = tuple(args)
    B = arrs[0].shape[0]
    if client is not None:
        _validate.client(client)
    threads = client_threads(client) if client is not None else (
        default_workers() if workers is None else _validate.integer("workers", workers, minimum=1))
    if chunk_size is None:
        chunk_size = max(1, math.ceil(B / (_CHUNKS_PER_WORKER * threads)))
    else:
        chunk_size = _validate.integer("chunk_size", chunk_size, minimum=1)
    if B == 0:
        return func(*arrs, *args)
    bounds = [(s, min(B, s + chunk_size)) for s in range(0, B, chunk_size)]
    chunks = [tuple(a[s:e] for a in arrs) for s, e in bounds]
    bar = progress_bar(progress, B, desc)
    func = _WithOptions(func, options.portable())
    try:
        if client is not None:
            parts = _run_dask(client, func, chunks, args, bar)
        elif threads == 1 or len(chunks) == 1:
            parts = []
            for ch in chunks:
                parts.append(interruptible(func, *ch, *args))
                if bar is not None:
                    bar.update(ch[0].shape[0])
        else:
            parts = _run_threads(func, chunks, args, min(threads, len(chunks)), bar)
    finally:
        if bar is not None:
            bar.close()
    return _concat(parts)


#: how often (seconds) a caller waiting for worker threads looks up for Ctrl-C
_WAIT_SLICE = 0.1


_SECOND: list = [None, None]  # (process id, its executor of one thread)


def on_second_core(func: Callable, *args: Any) -> Any:
    """``func(*args)`` started on a second thread while the caller works on (a
    :class:`~concurrent.futures.Future` for :func:`result`), or ``None`` where that would not run in parallel:
    a process with one core, JIT off (``func``'s kernels would hold the GIL), a caller that is not the main
    thread (dask's workers, a user's thread pool: their calls would queue for the one thread), or an
    interpreter shutting down (``atexit`` handlers run after the executors have closed). ``func`` runs in a
    copy of the caller's :mod:`contextvars` context; it should release the GIL (compiled kernels, already
    compiled: a compilation there cannot be interrupted, and the process's exit waits for it) and be short
    (a chunk). The thread belongs to this process (made again in a forked child, where the parent's does not
    exist); signals are held off while it is handed the call (a ``KeyboardInterrupt`` right after the thread
    started, before the executor recorded it, left a thread that the interpreter's exit waited for forever)."""
    from . import _jit  # (numba: only here, where compiled kernels are about to run anyway)

    if (threading.current_thread() is not threading.main_thread() or default_workers() < 2
            or not _jit.JIT_ENABLED):
        return None
    call = (contextvars.copy_context().run, func, *args)
    try:
        if _SECOND[0] == os.getpid():
            return _SECOND[1].submit(*call)
        import concurrent.futures

        # the first call starts the thread (the executor's only one): with signals held off (~0.1 ms, once)
        mask = getattr(signal, "pthread_sigmask", None)
        held = mask(signal.SIG_BLOCK, signal.valid_signals()) if mask is not None else None
        try:
            executor = concurrent.futures.ThreadPoolExecutor(1, thread_name_prefix="hyperrotor-second")
            future = executor.submit(*call)
            _SECOND[:] = [os.getpid(), executor]
            return future
        finally:
            if held is not None:
                mask(signal.SIG_SETMASK, held)
    except RuntimeError:  # (the interpreter is shutting down: "cannot schedule new futures after shutdown")
        return None


def result(future: Any) -> Any:
    """The result of :func:`on_second_core`'s ``future``, waited for in slices of :data:`_WAIT_SLICE` seconds
    (Ctrl-C reaches the caller meanwhile)."""
    import concurrent.futures

    while True:
        try:
            return future.result(timeout=_WAIT_SLICE)
        except concurrent.futures.TimeoutError:
            continue


@contextlib.contextmanager
def interrupts_as_raised():
    """A Ctrl-C (or any other ``BaseException`` a signal handler raises) that lands in the Python hooks of numba's
    dispatch (``_numba_unpickle``, called on every call of some compiled functions) comes out as a ``SystemError``
    "returned a result with an exception set" whose cause chain holds the interrupt: re-raised as that interrupt
    (a test of Ctrl-C during the step selection saw it once in CI). Other errors pass unchanged."""
    try:
        yield
    except SystemError as exc:
        seen, cause = set(), exc
        while cause is not None and id(cause) not in seen:
            seen.add(id(cause))
            if not isinstance(cause, Exception):  # (KeyboardInterrupt, SystemExit, the command line's Stop)
                raise cause.with_traceback(cause.__traceback__) from exc
            cause = cause.__cause__ or cause.__context__
        raise


def interruptible(func: Callable, *args: Any) -> Any:
    """``func(*args)`` on a worker thread, waited for in slices of :data:`_WAIT_SLICE` seconds.

    Python delivers Ctrl-C (``KeyboardInterrupt``) to the main thread between bytecodes; a long C
    routine called there (LAPACK's ``eigh`` of a large block, a compiled kernel) holds it off until
    it returns (36 s measured for a sector of dimension 12001). Run here, the main thread only waits,
    and the interrupt reaches the caller within ~0.1 s (its ``except`` and ``finally`` blocks run, an
    interactive session is back at once). The interrupted call runs on to its end in the background (a
    C routine cannot be stopped; its result is dropped), and a process that exits waits for it: a
    daemon thread left inside LAPACK while the interpreter shut down crashed the process (SIGSEGV).
    ``func`` runs in a copy of the caller's :mod:`contextvars` context (the options of a
    ``with hr.options(...)`` block); its exceptions are raised here. Called from another thread
    (which Ctrl-C does not reach) it simply calls ``func``.
    """
    if threading.current_thread() is not threading.main_thread():
        return func(*args)
    box: dict = {}
    ctx = contextvars.copy_context()
    done = threading.Event()

    def run() -> None:
        try:
            box["value"] = ctx.run(func, *args)
        except BaseException as exc:  # (re-raised in the caller's thread)
            box["error"] = exc
        finally:
            done.set()

    threading.Thread(target=run, name="hyperrotor-call").start()
    # (an Event, not Thread.join: a KeyboardInterrupt inside join(timeout) can leave the thread's state lock
    # taken, and the interpreter's wait for the thread at exit then hung for good)
    while not done.wait(_WAIT_SLICE):
        pass
    if "error" in box:
        raise box.pop("error")
    return box["value"]


def _run_threads(func, chunks, args, nthreads, bar):
    """``func(*chunk, *args)`` for every chunk on ``nthreads`` threads, the results in chunk order.

    The caller waits in short slices (Ctrl-C reaches it within ~0.1 s) and, on an interrupt or an error,
    tells the workers to take no new chunk; the chunks already running finish in the background, and an
    exiting process waits for them (:func:`interruptible`). The workers run in copies of the caller's context.
    """
    parts: list = [None] * len(chunks)
    todo: queue.SimpleQueue = queue.SimpleQueue()
    for k in range(len(chunks)):
        todo.put(k)
    finished: queue.SimpleQueue = queue.SimpleQueue()
    stop = threading.Event()

    def work() -> None:
        while not stop.is_set():
            try:
                k = todo.get_nowait()
            except queue.Empty:
                return
            try:
                finished.put((k, func(*chunks[k], *args), None))
            except BaseException as exc:  # (re-raised in the caller's thread)
                finished.put((k, None, exc))

    for i in range(nthreads):  # each in a copy of the caller's context: its option values exactly (the portable
        # values alone, those that differ from the defaults, lost a block that set a key back to its default)
        threading.Thread(target=contextvars.copy_context().run, args=(work,), name=f"hyperrotor-{i}").start()
    try:
        for _ in range(len(chunks)):
            while True:
                try:
                    k, value, error = finished.get(timeout=_WAIT_SLICE)
                    break
                except queue.Empty:
                    continue
            if error is not None:
                raise error
            parts[k] = value
            if bar is not None:
                bar.update(chunks[k][0].shape[0])
    finally:
        stop.set()
    return parts


def _run_dask(client, func, chunks, args, bar):
    dd = import_distributed()
    futs = [client.submit(func, *ch, *args, pure=False) for ch in chunks]
    index = {f.key: k for k, f in enumerate(futs)}
    try:
        if bar is not None:
            for f in dd.as_completed(futs):
                bar.update(chunks[index[f.key]][0].shape[0])
        return client.gather(futs)
    except BaseException:
        client.cancel(futs)
        raise

