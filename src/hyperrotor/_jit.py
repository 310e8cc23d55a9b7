"""The one place hyperrotor touches numba.

``jit`` is ``numba.njit(cache=True, fastmath=False)`` unless numba is missing or
the environment switches say otherwise:

* ``HYPERROTOR_DISABLE_JIT=1``: ``jit`` is the identity; kernels run as plain
  Python (slow, but the same code; the tests run both paths).
* ``HYPERROTOR_DISABLE_CACHE=1``: compile without the on-disk cache.

No other module imports numba; kernels are plain functions on ndarrays that write
into explicit output arguments, wrapped by ``jit`` at import.
"""
from __future__ import annotations

import os

__all__ = ["jit", "JIT_ENABLED", "CACHE_ENABLED", "NUMBA_VERSION", "prange"]

try:  # pragma: no cover - depends on the platform
    import numba as _numba
except ImportError:  # pragma: no cover
    _numba = None

JIT_ENABLED: bool = _numba is not None and os.environ.get("HYPERROTOR_DISABLE_JIT", "0") != "1"
#: the numba release that compiles the kernels (``None`` without numba)
NUMBA_VERSION: str | None = None if _numba is None else _numba.__version__
CACHE_ENABLED: bool = os.environ.get("HYPERROTOR_DISABLE_CACHE", "0") != "1"


def jit(fn=None, **options):
    """Compile ``fn`` with ``numba.njit`` (cached) or return it unchanged when JIT is off.

    Usable bare (``@jit``) or with options (``@jit(parallel=True)``).
    """
    def wrap(f):
        if not JIT_ENABLED:
            return f
        opts = {"cache": CACHE_ENABLED, "nogil": True}
        opts.update(options)
        return _numba.njit(**opts)(f)

    return wrap(fn) if fn is not None else wrap


if JIT_ENABLED:
    prange = _numba.prange
else:
    prange = range
