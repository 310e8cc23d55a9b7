"""One file-writing path (issue #21 §4): ``python -m hyperrotor.paper.verify -o FILE`` is not a second one.

The module used to write its report itself, overwriting files and writing through symlinks. The
report is written by ``hyperrotor verify -o FILE`` only (the command line's checked, no-clobber path,
tested in tests/test_cli.py); running the module is a usage error that touches nothing.
"""
import os
import subprocess
import sys


def test_running_the_verify_module_is_a_usage_error_and_writes_nothing(tmp_path):
    (tmp_path / "target.md").write_text("someone else's file")
    (tmp_path / "r.md").symlink_to(tmp_path / "target.md")
    (tmp_path / "old.md").write_text("old report")
    for out in ("r.md", "old.md", "new.md"):
        p = subprocess.run([sys.executable, "-W", "ignore", "-m", "hyperrotor.paper.verify", "-o", out],
                           cwd=tmp_path, capture_output=True, text=True, timeout=120)
        assert p.returncode == 2, (out, p.returncode, p.stderr)
        assert "hyperrotor verify" in p.stderr and p.stdout == ""
    assert sorted(os.listdir(tmp_path)) == ["old.md", "r.md", "target.md"]
    assert (tmp_path / "r.md").is_symlink() and (tmp_path / "target.md").read_text() == "someone else's file"
    assert (tmp_path / "old.md").read_text() == "old report"
