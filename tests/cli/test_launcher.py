"""The ``hyperrotor`` command's launcher (``src/_hyperrotor_launch.py``): a signal while the package is still
being imported (about a second, before the command's own handlers exist) ends the command at once with one line
on stderr and the signal's status, not Python's ``KeyboardInterrupt`` traceback."""
import importlib.metadata
import os
import signal
import subprocess
import sys
import time

import pytest

from hyperrotor.cli import EXIT_CODES, _signals

STATUS = {signal.SIGINT: EXIT_CODES["interrupted"], signal.SIGTERM: EXIT_CODES["terminated"]}


def _handles(pid: int, sig: int) -> bool:
    """Whether process ``pid`` has a handler for ``sig`` (Linux: the SigCgt mask of /proc/PID/status)."""
    try:
        with open(f"/proc/{pid}/status") as fh:
            for line in fh:
                if line.startswith("SigCgt:"):
                    return bool(int(line.split()[1], 16) >> (sig - 1) & 1)
    except OSError:
        pass
    return False


def _launcher_script(code: str) -> subprocess.CompletedProcess:
    """``code`` run by a fresh interpreter after ``import os, signal, sys, _hyperrotor_launch as launch``."""
    return subprocess.run([sys.executable, "-c", "import os, signal, sys, _hyperrotor_launch as launch\n" + code],
                          capture_output=True, text=True, timeout=120)


def test_the_console_script_is_the_launcher():
    (script,) = [e for e in importlib.metadata.entry_points(group="console_scripts") if e.name == "hyperrotor"]
    assert script.value == "_hyperrotor_launch:main"


def test_the_launcher_and_the_command_share_one_table_of_signals():
    import _hyperrotor_launch

    assert _signals.SIGNALS is _hyperrotor_launch.SIGNALS
    assert {status for status, _ in _signals.SIGNALS.values()} >= set(STATUS.values())


@pytest.mark.skipif(not os.path.exists("/proc/self/status"), reason="needs /proc (Linux) to see the handlers")
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_while_the_package_is_imported(sig):
    """Sent as soon as the launcher handles SIGTERM (Python alone does not; the command's handlers come ~1 s
    later, after the imports): the launcher's line, the status, nothing on stdout, no traceback."""
    p = subprocess.Popen([sys.executable, "-m", "_hyperrotor_launch", "demo", "--no-png"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 60
        while not _handles(p.pid, signal.SIGTERM):
            assert p.poll() is None and time.monotonic() < deadline, p.communicate()
            time.sleep(0.001)
        sent = time.monotonic()
        p.send_signal(sig)
        out, err = p.communicate(timeout=60)
        latency = time.monotonic() - sent
    finally:
        if p.poll() is None:
            p.kill()
    assert p.returncode == STATUS[sig], err
    assert "Traceback" not in err and out == ""
    assert err == f"hyperrotor: {_signals.SIGNALS[sig][1]} while starting; nothing was written\n"
    assert latency < 4.0  # (~5 ms idle; the bound of tests/cli/test_signals.py for a loaded machine)


def test_after_the_command_a_signal_ends_the_teardown_with_the_commands_status():
    """Once the command has returned, the launcher's handlers no longer say 'while starting': a signal during the
    interpreter's teardown ends the process at once with the command's own status and nothing more on stderr."""
    p = _launcher_script(
        "import hyperrotor.cli\n"
        "hyperrotor.cli.main = lambda: 0\n"  # (a command that has just finished its work)
        "status = launch.main()\n"
        "os.kill(os.getpid(), signal.SIGINT)\n"
        "print('not reached')\n"
        "sys.exit(7)\n")
    assert (p.returncode, p.stdout, p.stderr) == (0, "", "")


def test_a_signal_between_the_commands_end_and_the_launchers_is_not_reported_as_starting():
    """The command's handlers are gone (restored) a few bytecodes before the launcher installs its teardown
    handlers: a signal there ends the process with the command's status, not 'while starting; nothing was
    written' (the command has run and may have written)."""
    p = _launcher_script(
        "import hyperrotor.cli\n"
        "from hyperrotor.cli import _signals\n"
        "def command():\n"
        "    assert _signals.install('hyperrotor')\n"
        "    _signals.restore()\n"
        "    os.kill(os.getpid(), signal.SIGINT)\n"  # (in the window: after restore, before main's finally)
        "    print('returned', flush=True)\n"
        "    return 3\n"
        "hyperrotor.cli.main = command\n"
        "launch.main()\n"
        "print('not reached')\n")
    assert (p.returncode, p.stdout, p.stderr) == (3, "returned\n", "")


def test_after_help_or_version_a_signal_ends_the_teardown_quietly_too():
    """--version ends the command with SystemExit(0): the teardown's handlers are installed all the same."""
    p = _launcher_script(
        "sys.argv = ['hyperrotor', '--version']\n"
        "try:\n"
        "    launch.main()\n"
        "except SystemExit as exc:\n"
        "    print('exit', exc.code, flush=True)\n"
        "    os.kill(os.getpid(), signal.SIGINT)\n"
        "    print('not reached')\n")
    assert p.returncode == 0 and p.stdout.splitlines()[-1] == "exit 0" and p.stderr == "", (p.stdout, p.stderr)


@pytest.mark.skipif(not hasattr(signal, "SIGHUP") or not os.path.exists("/proc/self/status"),
                    reason="POSIX with /proc (Linux)")
def test_an_inherited_ignored_sighup_stays_ignored():
    """nohup's SIG_IGN for SIGHUP is kept by the launcher and by the command: a hang-up does not end the run."""
    p = subprocess.Popen([sys.executable, "-m", "_hyperrotor_launch", "demo", "--no-png"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True,
                         preexec_fn=lambda: signal.signal(signal.SIGHUP, signal.SIG_IGN))
    try:
        deadline = time.monotonic() + 60
        while not _handles(p.pid, signal.SIGTERM):
            assert p.poll() is None and time.monotonic() < deadline, p.communicate()
            time.sleep(0.001)
        p.send_signal(signal.SIGHUP)  # (while the package imports: the launcher's phase)
        time.sleep(0.5)
        assert p.poll() is None, p.communicate()
        assert not _handles(p.pid, signal.SIGHUP)  # (the command's handlers, if installed by now, left it alone)
        p.send_signal(signal.SIGTERM)
        out, err = p.communicate(timeout=60)
    finally:
        if p.poll() is None:
            p.kill()
    assert p.returncode == STATUS[signal.SIGTERM], err
    assert "hung up" not in err and "Traceback" not in err
