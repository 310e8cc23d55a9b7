"""The inputs of the closed forms (:mod:`.closed_form`, :mod:`.quartet`, :mod:`.poinsot`), read through
:mod:`hyperrotor._validate`: output times in any order, and angular velocities by plane."""
from __future__ import annotations

from typing import Any

import numpy as np

from .. import _validate

__all__: list[str] = []  # package-internal: times, plane_vector


def times(t: Any) -> np.ndarray:
    """``t`` as a non-empty 1-D float array of output times (a scalar is one time; any order)."""
    tt = np.atleast_1d(_validate.finite_array("t", t, ndim=(0, 1)))
    if tt.size == 0:
        raise ValueError("t must hold at least one time, got an empty array")
    return tt


def plane_vector(omega0: Any, count: int | None = None) -> np.ndarray:
    """``omega0`` (batch + ``(n,)``) through :mod:`hyperrotor._validate`; ``n`` a plane count."""
    if count is not None:
        return _validate.components("omega0", omega0, count)
    w = _validate.finite_array("omega0", omega0)
    if w.ndim == 0:
        raise ValueError(f"omega0 must be a vector of plane components, got the scalar {_validate.fmt(omega0)}")
    _validate.dimension_from_count(w.shape[-1], name="omega0")
    return w
