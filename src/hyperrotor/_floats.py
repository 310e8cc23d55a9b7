"""Exact scaling by powers of two (private).

Several computations are invariant under a rescaling of their input (the rigid body's motion under
``I -> c I`` and ``omega -> c omega`` with ``t -> t / c``; the direction of a quantum state; the
rotation that brings a matrix to its normal form): they divide the input by a power of two near its
size, compute, and scale back. A division by a power of two is exact (no rounding), and it keeps
every intermediate product and norm away from overflow and underflow, so inputs near ``1e308`` or
``1e-308`` give the digits of inputs near 1. The power is taken at or below ``|x|``, so that it is
itself a float for every finite ``x`` (the one above ``|x| >= 2^1023`` is not).
"""
from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["power_of_two_scale"]


def power_of_two_scale(x: Any) -> Any:
    """The power of two ``s`` with :math:`1 \\le |x| / s < 2` (from :func:`numpy.frexp`: exact), ``1.0`` where
    ``x`` is 0, infinite or NaN (nothing to scale). A float for a number, an array of its shape for an array."""
    x = np.asarray(x, dtype=float)
    s = np.where(np.isfinite(x) & (x != 0.0), np.ldexp(1.0, np.frexp(x)[1] - 1), 1.0)
    return float(s) if s.ndim == 0 else s
