"""Run code in a child process and send it SIGINT: the tests of Ctrl-C during long work."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time


def interrupted(code: str, wait: float) -> str:
    """Run ``code`` in a child process, SIGINT it ``wait`` s after it prints 'running'; its stdout
    (the child must exit with status 3 on KeyboardInterrupt)."""
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env={**os.environ, "PYTHONUNBUFFERED": "1"})
    try:
        assert proc.stdout.readline().strip() == "running"
        time.sleep(wait)
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=60)  # a guard against a hang, not a timing assertion
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 3, (out, err)
    return out
