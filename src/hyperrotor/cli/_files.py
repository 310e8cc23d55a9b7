"""Output files of the command line: checked before any work, never clobbered, written atomically.

:func:`output_file` checks a path given on the command line (its folder exists
and is writable, its extension is one the command writes, it does not exist
yet unless ``force``) and *reserves* it at once: a hidden temporary file
``.<name>.<random>.part<suffix>`` is created in the target folder, so any
problem with the folder (missing, read-only, a file instead of a folder, no
permission) shows up before the work starts. The command writes to
:attr:`OutputFile.tmp`; :meth:`Outputs.commit` renames the temporary files to
their targets (``os.replace`` with ``force``; a hard link otherwise, which
fails instead of replacing a file that appeared meanwhile). Leaving the
:class:`Outputs` block by an exception (an error, Ctrl-C) removes every
temporary file, so a failure or an interrupt never leaves a partial or
clobbered output.

Bad paths raise ``ValueError`` with a one-line message naming the option, the
value and what is allowed (the command line turns it into exit status 2).
"""
from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

__all__ = ["OutputFile", "Outputs", "output_file"]


@dataclass
class OutputFile:
    """A checked output path and its reserved temporary file in the same folder."""

    path: Path
    option: str
    force: bool
    tmp: Path

    def commit(self) -> Path:
        """Move the finished temporary file to :attr:`path` (atomic); returns the path."""
        _set_default_mode(self.tmp)
        if self.force:
            os.replace(self.tmp, self.path)
            return self.path
        try:
            os.link(self.tmp, self.path)  # fails if the target exists: never clobber
        except FileExistsError:
            raise FileExistsError(
                f"{self.option} {self.path} appeared while this command ran; left it as it is "
                f"(pass --force to replace it)") from None
        except OSError:  # no hard links on this file system
            if self.path.exists():
                raise FileExistsError(f"{self.option} {self.path} appeared while this command ran; "
                                      "left it as it is (pass --force to replace it)") from None
            os.replace(self.tmp, self.path)
            return self.path
        os.unlink(self.tmp)
        return self.path

    def discard(self) -> None:
        """Remove the temporary file (if it is still there)."""
        try:
            os.unlink(self.tmp)
        except FileNotFoundError:
            pass


def _set_default_mode(path: Path) -> None:
    # mkstemp creates 0600 files; give the output the mode a plain open() would (0666 minus umask)
    mask = os.umask(0o022)
    os.umask(mask)
    os.chmod(path, 0o666 & ~mask)


def output_file(text: str, *, option: str, suffixes: Sequence[str], force: bool) -> OutputFile:
    """Check the output path ``text`` of ``option`` and reserve it (see the module docstring).

    ``suffixes``: the allowed extensions, lower case with the dot (``(".png", ".gif")``);
    matched ignoring case.
    """
    allowed = ", ".join(suffixes)
    if not text or not text.strip():
        raise ValueError(f"{option} needs a file name ending in {allowed}, got an empty string")
    path = Path(text).expanduser()
    if text.endswith(("/", os.sep)) or path.is_dir():
        raise ValueError(f"{option} {text!r} is a folder; give a file name ending in {allowed}")
    if path.suffix.lower() not in suffixes:
        got = f"extension {path.suffix!r}" if path.suffix else "no extension"
        raise ValueError(f"{option} {text!r} has {got}; allowed: {allowed}")
    folder = path.parent
    if not folder.exists():
        raise ValueError(f"{option} {text!r}: the folder {str(folder)!r} does not exist (create it first)")
    if not folder.is_dir():
        raise ValueError(f"{option} {text!r}: {str(folder)!r} is not a folder")
    if path.exists() or path.is_symlink():
        if not force:
            raise ValueError(f"{option} {text!r} exists; pass --force to replace it, or choose another name")
        if not path.is_file():
            raise ValueError(f"{option} {text!r} exists and is not a regular file; not replacing it")
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=f".part{path.suffix}", dir=folder)
    except OSError as err:
        raise ValueError(f"{option} {text!r}: cannot write in the folder {str(folder)!r} "
                         f"({err.strerror or err})") from None
    os.close(fd)
    return OutputFile(path=path, option=option, force=force, tmp=Path(tmp))


class Outputs:
    """The output files of one command: commit all at the end, or discard all on any exception.

    Use as ``with Outputs() as outs: f = outs.add(output_file(...)); ...; outs.commit()``.
    """

    def __init__(self) -> None:
        self.files: list[OutputFile] = []

    def add(self, out: OutputFile) -> OutputFile:
        self.files.append(out)
        return out

    def commit(self) -> list[Path]:
        """Rename every temporary file to its target, in order; returns the targets."""
        done = []
        for f in self.files:
            done.append(f.commit())
        self.files = []
        return done

    def discard(self) -> None:
        for f in self.files:
            f.discard()
        self.files = []

    def __enter__(self) -> "Outputs":
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        self.discard()  # after commit() the list is empty; otherwise remove the unfinished files
