"""Arrays that NumPy would silently turn into numbers are refused (issue #21 §4).

``np.asarray`` reads booleans as 0/1, datetime64/timedelta64 values as their integer ticks, and
drops the mask of a masked array. Every array argument of every entry of the fuzz table
(``tests/property/test_fuzz_entry_points.py``: ``omega0``, ``t``, moments, states, matrices, component
vectors, ...) is replaced by an array of the good argument's shape holding booleans, datetime64 or
timedelta64 values, or by the good values under a mask hiding one entry. Each must be refused with a
``TypeError`` or ``ValueError`` (never accepted, never another exception).
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

from test_payloads import FUZZ  # the fuzz table, loaded once

VARIANTS = ("bool", "datetime64", "timedelta64", "masked")


def _variant(good, vid):
    shape = np.shape(np.asarray(good))
    if vid == "bool":
        return np.ones(shape, dtype=bool)
    if vid == "datetime64":
        return np.full(shape, np.datetime64("2020-01-01"))
    if vid == "timedelta64":
        return np.full(shape, np.timedelta64(1, "s"))
    values = np.asarray(good, dtype=complex if np.iscomplexobj(good) else float)
    mask = np.zeros(shape, dtype=bool)
    mask.flat[0] = True  # hide one entry: reading it would silently use the hidden value
    return np.ma.masked_array(values, mask=mask)


def _cases():
    for label, path, args, kwargs, kinds in FUZZ.ENTRIES:
        for where, kind in kinds.items():
            if not kind.startswith(("arr", "vec", "pts", "map")):
                continue
            good = args()[where] if isinstance(where, int) else kwargs()[where]
            if np.size(good) == 0:
                continue
            for vid in VARIANTS:
                yield pytest.param(label, path, args, kwargs, where, vid, id=f"{label}-{where}-{vid}")


CASES = list(_cases())


def test_the_walk_covers_omega0_t_and_states():
    labels = {c.values[0] for c in CASES}
    assert {"simulate", "euler_poinsot", "lyapunov", "q.evolve", "locked_axes"} <= labels, sorted(labels)
    assert len(CASES) >= 300, len(CASES)


@pytest.mark.parametrize("label, path, args, kwargs, where, vid", CASES)
def test_non_numeric_array_is_refused(label, path, args, kwargs, where, vid):
    fn, a, kw, shift = FUZZ._call(path, args, kwargs)
    good = a[where - shift] if isinstance(where, int) else kw[where]
    bad = _variant(good, vid)
    if isinstance(where, int):
        a[where - shift] = bad
    else:
        kw[where] = bad
    with FUZZ._time_limit(FUZZ.TIME_LIMIT), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            fn(*a, **kw)
        except (TypeError, ValueError) as exc:
            assert str(exc), f"{label}({where}={vid}): a {type(exc).__name__} without a message"
            return
    pytest.fail(f"{label}: argument {where!r} given {vid} values was accepted (NumPy reads them as numbers"
                f"{'; the mask is dropped' if vid == 'masked' else ''})")
