"""Values computed from an object and kept while it lives (the one weak-reference cache of the package).

A representation's symmetry group and sector bases cost tens of milliseconds to seconds and are
needed by every spectrum, propagator and check of the same representation: they are kept, keyed
by the object's identity, until the object is garbage collected (a weak reference removes the
entry). Objects without weak references are not cached (computed each time).
"""
from __future__ import annotations

import weakref
from typing import Any, Callable

__all__ = ["WeakCache"]


class WeakCache:
    """``cache.get(obj, make)``: ``make(obj)``, computed once while ``obj`` lives."""

    def __init__(self) -> None:
        self._entries: dict[int, tuple[Any, Any]] = {}

    def get(self, obj: Any, make: Callable[[Any], Any]) -> Any:
        """The value kept for ``obj``, or ``make(obj)`` (then kept while ``obj`` lives)."""
        hit = self._entries.get(id(obj))
        if hit is not None and hit[0]() is obj:
            return hit[1]
        value = make(obj)
        try:
            ref = weakref.ref(obj, lambda _, key=id(obj), entries=self._entries: entries.pop(key, None))
        except TypeError:  # an object without weak references: no reuse
            return value
        self._entries[id(obj)] = (ref, value)
        return value

    def __contains__(self, obj: Any) -> bool:
        """Whether a value is kept for ``obj`` (no computation)."""
        hit = self._entries.get(id(obj))
        return hit is not None and hit[0]() is obj

    def __len__(self) -> int:
        return len(self._entries)
