"""Ctrl-C reaches the caller during a dense diagonalization (review of session 38).

LAPACK's ``eigh`` holds off Python's signal handling until it returns (36 s measured for a sector of
dimension 12001); :func:`hyperrotor._parallel.interruptible` runs such calls on a worker thread while
the main thread waits in slices.
"""
from __future__ import annotations

import threading

import numpy as np
import pytest

import hyperrotor as hr
from hyperrotor import _parallel
from hyperrotor._options import options
from interrupted_child import interrupted

#: the child's LAPACK on one thread: the call it times and the one it is interrupted in take the same time (a
#: threaded BLAS made the first 9 s under load and a few tens of ms on many cores)
ONE_BLAS_THREAD = ("import os; os.environ.update(dict.fromkeys(('OPENBLAS_NUM_THREADS', 'OMP_NUM_THREADS', "
                   "'MKL_NUM_THREADS'), '1'))\n")
#: the latency bound's floor (the signal's way through the pipe and the scheduler on a loaded machine), far below
#: what a call of this size takes on one thread
LEAST_BOUND = 0.25


def test_interruptible_returns_raises_and_sees_the_callers_options():
    assert _parallel.interruptible(np.add, 2, 3) == 5
    with pytest.raises(ZeroDivisionError):
        _parallel.interruptible(lambda: 1 / 0)
    with hr.options(max_seconds=12.5):
        seen = _parallel.interruptible(lambda: (options["max_seconds"], threading.current_thread().daemon))
    assert seen == (12.5, False)
    # from a thread other than the main one (which Ctrl-C does not reach): a plain call
    out = []
    t = threading.Thread(target=lambda: out.append(_parallel.interruptible(threading.current_thread)))
    t.start()
    t.join()
    assert out == [t]


def test_map_rows_workers_keep_chunk_order_and_raise_the_first_error():
    rows = np.arange(40.0)
    np.testing.assert_array_equal(_parallel.map_rows(lambda x: 2 * x, rows, workers=2, chunk_size=3), 2 * rows)

    def bad(x):
        if x[0] >= 20:
            raise ValueError(f"row {x[0]:g}")
        return x

    with pytest.raises(ValueError, match="row"):
        _parallel.map_rows(bad, rows, workers=2, chunk_size=5)


@pytest.mark.slow
def test_ctrl_c_during_a_dense_eigvalsh_reaches_the_caller_long_before_lapack_returns():
    """The child times one GUE eigvalsh of the size it then interrupts: its ``except KeyboardInterrupt`` must
    run well before a second one could end (a relative bound, not a timing of the machine); the process then
    exits cleanly (after the routine, which cannot be stopped, has ended)."""
    code = (
        ONE_BLAS_THREAD +
        "import time, sys, hyperrotor.quantum as hq\n"
        "t0 = time.perf_counter(); hq.sample_spectrum('gue', 1500, rng=1)\n"
        "print(time.perf_counter() - t0, flush=True)\n"
        "print('running', flush=True)\n"
        "try:\n"
        "    hq.sample_spectrum('gue', 1500, rng=2)\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', flush=True)\n"
        "    sys.exit(3)\n"
    )
    once = []

    def wait(lines):  # a tenth of one diagonalization, as the child timed it
        once.append(float(lines[0]))
        return 0.1 * once[0]

    out, latency = interrupted(code, wait, latency=True, timeout=120)
    assert out.split()[0] == "interrupted"
    assert latency < max(0.5 * once[0], LEAST_BOUND), (latency, once[0])


@pytest.mark.slow
def test_ctrl_c_during_the_quartet_closed_form_reaches_the_caller_long_before_lapack_returns():
    """quartet_solution's eigh of i A (dimension N - 1) runs through _parallel.interruptible: the child times one
    call, then is interrupted a tenth of one into the next; it answers well before that call could end (the
    review measured 19 s of waiting for N = 3000 before)."""
    code = (
        ONE_BLAS_THREAD +
        "import time, sys, numpy as np, hyperrotor as hr, hyperrotor.classical as hc\n"
        "N = 1000; w = np.random.default_rng(0).normal(size=N * (N - 1) // 2)\n"
        "t0 = time.perf_counter(); hc.quartet_solution(0.5, w, [0.0, 1.0])\n"
        "print(time.perf_counter() - t0, flush=True)\n"
        "print('running', flush=True)\n"
        "try:\n"
        "    hc.quartet_solution(0.5, w, [0.0, 2.0])\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', flush=True)\n"
        "    sys.exit(3)\n"
    )
    once = []

    def wait(lines):
        once.append(float(lines[0]))
        return 0.1 * once[0]

    out, latency = interrupted(code, wait, latency=True, timeout=120)
    assert out.split()[0] == "interrupted"
    assert latency < max(0.5 * once[0], LEAST_BOUND), (latency, once[0])
