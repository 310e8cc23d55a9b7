"""Output files of the command line: checked before any work, never clobbered, written atomically.

:func:`output_file` checks a path given on the command line (its folder exists
and is writable, its extension is one the command writes, it does not exist
yet unless ``force``) and *reserves* it at once: a hidden temporary file
``.<name>.<random>.part<suffix>`` is created in the target folder (``<name>``
shortened when the whole would be longer than the file system allows), so any
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

Every reserved temporary file is registered the moment it exists, so the
command line removes whatever is left when it ends (:func:`discard_all`: an
exception raised between a reservation and its :class:`Outputs` block, or a
signal acted on from another thread, :mod:`hyperrotor.cli._signals`);
commits and discards are serialised by one lock, so a file is either complete
at its target or absent. :func:`written_files` lists what was committed, for a
failure that comes after (stdout closed, a signal).
"""
from __future__ import annotations

import os
import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

__all__ = ["OutputFile", "Outputs", "output_file", "discard_all", "written_files", "forget_written"]

#: Suffix a library writer may add to the temporary name for its own staging (Scene.to_html): kept in the
#: length budget of the temporary name, and removed with it.
_STAGING = ".part"
_LOCK = threading.RLock()
_PENDING: list["OutputFile"] = []  # reserved temporary files, neither committed nor discarded
_WRITTEN: list[Path] = []          # files committed since forget_written()


def discard_all() -> None:
    """Remove every reserved temporary file not committed (any thread; waits for a running commit)."""
    with _LOCK:
        for f in list(_PENDING):
            f.discard()


def written_files() -> list[Path]:
    """The output files committed since :func:`forget_written` (complete, at their targets)."""
    with _LOCK:
        return list(_WRITTEN)


def forget_written() -> None:
    """Start a new record for :func:`written_files` (one command run)."""
    with _LOCK:
        _WRITTEN.clear()


@dataclass
class OutputFile:
    """A checked output path and its reserved temporary file in the same folder."""

    path: Path
    option: str
    force: bool
    tmp: Path
    replaces: bool = False  #: a file exists at ``path`` (``force``): the commit replaces it

    def commit(self) -> Path:
        """Move the finished temporary file to :attr:`path` (atomic); returns the path."""
        with _LOCK:
            path = self._commit()
            _PENDING.remove(self)
            _WRITTEN.append(path)
            return path

    def _commit(self) -> Path:
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
        """Remove the temporary file (if it is still there), and a writer's own staging file ``<tmp>.part``."""
        with _LOCK:
            for name in (self.tmp, Path(str(self.tmp) + _STAGING)):
                try:
                    os.unlink(name)
                except FileNotFoundError:
                    pass
            if self in _PENDING:
                _PENDING.remove(self)


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
    folder = path.parent
    try:
        name_max = _name_max(folder)
        if len(os.fsencode(path.name)) > name_max:
            raise ValueError(f"{option}: the file name {_short(path.name)!r} is {len(os.fsencode(path.name))} bytes "
                             f"long; the file system allows at most {name_max}")
        if text.endswith(("/", os.sep)) or path.is_dir():
            raise ValueError(f"{option} {text!r} is a folder; give a file name ending in {allowed}")
        if path.suffix.lower() not in suffixes:
            got = f"extension {path.suffix!r}" if path.suffix else "no extension"
            raise ValueError(f"{option} {_short(text)!r} has {got}; allowed: {allowed}")
        if not folder.exists():
            raise ValueError(f"{option} {text!r}: the folder {str(folder)!r} does not exist (create it first)")
        if not folder.is_dir():
            raise ValueError(f"{option} {text!r}: {str(folder)!r} is not a folder")
        replaces = path.exists() or path.is_symlink()
        if replaces:
            if not force:
                raise ValueError(f"{option} {text!r} exists; pass --force to replace it, or choose another name")
            if not (path.is_file() or (path.is_symlink() and not path.exists())):  # (a dangling link is replaced)
                raise ValueError(f"{option} {text!r} exists and is not a regular file; not replacing it")
        suffix = f".part{path.suffix}"
        room = name_max - len(os.fsencode(suffix)) - 8 - len(_STAGING)  # 8: mkstemp's random part
        fd, tmp = tempfile.mkstemp(prefix=_tmp_prefix(path.name, room),
                                   suffix=suffix, dir=folder)
    except OSError as err:
        raise ValueError(f"{option} {_short(text)!r}: cannot write in the folder {_short(str(folder))!r} "
                         f"({err.strerror or err})") from None
    out = OutputFile(path=path, option=option, force=force, tmp=Path(tmp), replaces=replaces)
    with _LOCK:
        _PENDING.append(out)
    os.close(fd)
    return out


def _name_max(folder: Path) -> int:
    """Longest file name (bytes) of the file system of ``folder`` (POSIX ``NAME_MAX``, 255 when unknown)."""
    try:
        return int(os.pathconf(folder, "PC_NAME_MAX"))
    except (OSError, ValueError, AttributeError):
        return 255


def _tmp_prefix(name: str, room: int) -> str:
    """``.NAME.``, NAME shortened so that the prefix takes at most ``room`` bytes (long legal names)."""
    raw = os.fsencode(name)[:max(room - 2, 1)]
    return "." + os.fsdecode(raw.decode("utf-8", "ignore").encode("utf-8")) + "."


def _short(text: str) -> str:
    return text if len(text) <= 80 else text[:60] + "..." + text[-16:]


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
        with _LOCK:
            done = []
            while self.files:
                done.append(self.files[0].commit())
                self.files.pop(0)
            return done

    def discard(self) -> None:
        """Remove every temporary file not committed yet."""
        with _LOCK:
            for f in self.files:
                f.discard()
            self.files = []

    def __enter__(self) -> "Outputs":
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        self.discard()  # after commit() the list is empty; otherwise remove the unfinished files
