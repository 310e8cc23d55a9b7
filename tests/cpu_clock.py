"""CPU seconds of one in-process call, for the tests whose contract is "answers within a second of CPU".

``time.process_time`` counts every thread of the test process and whatever the interpreter does
inside the call on behalf of earlier tests: threads they left running (a dask client's, a thread
pool's) and a cyclic garbage collection that their garbage happens to trigger there. Late in a CI
run either can add a second to a 5 ms call (seen once: ``demo --omega=<payload>`` refused in 5 ms
locally, "1.04 s of CPU" in CI). ``call_cpu`` counts the calling thread only, with the cyclic
collector paused for the call (reference counting still frees everything that is not a cycle).

The calls measured this way do their work in the calling thread (parsing text, pricing work before
refusing it); a call that handed its work to other threads would escape this clock, which is why
the same tests also bound the wall time with an alarm.
"""
from __future__ import annotations

import contextlib
import gc
import time


class CallCPU:
    """The CPU seconds of the calling thread inside a ``call_cpu()`` block (``seconds``, set on exit)."""

    seconds: float = 0.0


@contextlib.contextmanager
def call_cpu():
    """Measure the calling thread's CPU time of the block, the cyclic garbage collector paused.

    Yields a :class:`CallCPU` whose ``seconds`` is set when the block ends (also when it raises).
    """
    clock = CallCPU()
    collecting = gc.isenabled()
    gc.disable()
    t0 = time.thread_time()
    try:
        yield clock
    finally:
        clock.seconds = time.thread_time() - t0
        if collecting:
            gc.enable()
