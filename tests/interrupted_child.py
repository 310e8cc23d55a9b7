"""Run code in a child process and send it SIGINT: the tests of Ctrl-C during long work."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import tempfile
import time
from typing import Callable


def interrupted(code: str, wait: float | Callable[[list[str]], float], *, latency: bool = False,
                timeout: float = 60.0):
    """Run ``code`` in a child process, SIGINT it ``wait`` s after it prints 'running'; its stdout
    (the child must exit with status 3 on KeyboardInterrupt).

    ``wait`` may be a function of the lines the child printed before 'running' (e.g. a time it measured).
    ``latency=True``: also the seconds from the signal to the child's next line of output (its
    ``except KeyboardInterrupt`` printing), as ``(stdout, latency)``. ``timeout`` guards against a hang after
    the signal; it is not a timing assertion.

    The child's stdout is read through ``proc.stdout`` only (``communicate`` reads the raw pipe and would drop
    the lines ``readline`` has already buffered: the line after the first one was lost when both arrived
    together, a parent descheduled for a moment on a loaded machine); its stderr goes to a file.
    """
    with tempfile.TemporaryFile("w+") as errf:
        proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=errf, text=True,
                                env={**os.environ, "PYTHONUNBUFFERED": "1"})
        try:
            before = []
            while (line := proc.stdout.readline()).strip() != "running":
                if not line:
                    proc.wait(timeout=timeout)
                    errf.seek(0)
                    raise AssertionError(f"the child ended before 'running': {before} {errf.read()}")
                before.append(line.strip())
            time.sleep(wait(before) if callable(wait) else wait)
            sent = time.perf_counter()
            proc.send_signal(signal.SIGINT)
            first = proc.stdout.readline()
            seconds = time.perf_counter() - sent
            proc.wait(timeout=timeout)  # (the child writes a few lines: far below a pipe's capacity)
            rest = proc.stdout.read()
        finally:
            if proc.poll() is None:
                proc.kill()
            proc.stdout.close()
        errf.seek(0)
        err = errf.read()
    out = first + rest
    assert proc.returncode == 3, (out, err)
    return (out, seconds) if latency else out
