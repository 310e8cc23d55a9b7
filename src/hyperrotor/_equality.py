"""Equality of the package's result objects, whose fields hold arrays (private).

The ``==`` that dataclasses and named tuples generate compares their fields as a tuple, and a
field that is an array makes that comparison an array, whose truth value NumPy refuses: a result
could not be compared with itself after a pickle round trip. :func:`fields_equal` compares field
by field with :func:`values_equal` instead; the result classes take it as their ``__eq__``.
"""
from __future__ import annotations

import dataclasses
import sys
from typing import Any

import numpy as np

__all__: list[str] = []  # private module


def values_equal(a: Any, b: Any) -> bool:
    """``a == b`` for the values results hold: arrays equal in shape and entries (NaN equal to NaN, as a result
    compared with its own copy must be), scipy sparse matrices in shape and nonzero entries, sequences and
    mappings item by item, random generators by their state, anything else by its own ``==``."""
    sparse = sys.modules.get("scipy.sparse")  # (not imported: nothing is a sparse matrix)
    if sparse is not None and (sparse.issparse(a) or sparse.issparse(b)):
        if not (sparse.issparse(a) and sparse.issparse(b)) or a.shape != b.shape:
            return False
        a, b = (sparse.csr_matrix(x, copy=True) for x in (a, b))
        for x in (a, b):  # (the same matrix whatever zeros or duplicates it stores)
            x.sum_duplicates()
            x.eliminate_zeros()
        return all(values_equal(x, y) for x, y in ((a.indptr, b.indptr), (a.indices, b.indices), (a.data, b.data)))
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        if a.shape != b.shape:
            return False
        try:
            return bool(np.array_equal(a, b, equal_nan=a.dtype.kind in "fc" and b.dtype.kind in "fc"))
        except TypeError:  # (object arrays: entry by entry)
            return all(values_equal(x, y) for x, y in zip(a.ravel().tolist(), b.ravel().tolist()))
    if isinstance(a, np.random.Generator) and isinstance(b, np.random.Generator):
        return a.bit_generator.state == b.bit_generator.state
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(values_equal(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return type(a) is type(b) and len(a) == len(b) and all(values_equal(x, y) for x, y in zip(a, b))
    if isinstance(a, float) and isinstance(b, float) and a != a and b != b:
        return True
    out = a == b
    return bool(np.all(out)) if isinstance(out, np.ndarray) else bool(out)


def fields_equal(self: Any, other: Any) -> Any:
    """``__eq__`` of a result dataclass or named tuple: the same class and equal fields (:func:`values_equal`)."""
    if type(other) is not type(self):
        return NotImplemented
    if dataclasses.is_dataclass(self):
        names = [f.name for f in dataclasses.fields(self) if f.compare]
        return all(values_equal(getattr(self, k), getattr(other, k)) for k in names)
    return all(values_equal(x, y) for x, y in zip(self, other))


def fields_unequal(self: Any, other: Any) -> Any:
    """``__ne__`` beside :func:`fields_equal` (a named tuple inherits tuple's own ``!=``, which compares arrays)."""
    eq = fields_equal(self, other)
    return eq if eq is NotImplemented else not eq
