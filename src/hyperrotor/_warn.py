"""The one place hyperrotor issues warnings: pointed at the caller's code, not at the package.

A fixed ``stacklevel`` points at the wrong frame as soon as a warning is raised from a different
depth (a check inside a run inside ``simulate``, or the same run entered from the CLI or a dask
worker). :func:`warn` walks up to the first frame outside ``hyperrotor`` (what Python 3.12's
``skip_file_prefixes`` does; the package supports 3.10).
"""
from __future__ import annotations

import os
import sys
import warnings

__all__ = ["warn"]

_PACKAGE = os.path.dirname(os.path.abspath(__file__)) + os.sep


def warn(message: str, category: type[Warning] = UserWarning) -> None:
    """``warnings.warn(message, category)`` attributed to the first frame outside the package."""
    frame = sys._getframe(1)
    level = 2  # (1 is this function, 2 its caller)
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE):
        frame = frame.f_back
        level += 1
    warnings.warn(message, category, stacklevel=level)
