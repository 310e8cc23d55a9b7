"""hyperrotor._weak_cache.WeakCache: a value computed once per object, dropped with the object."""
import gc

from hyperrotor._weak_cache import WeakCache


class _Obj:
    pass


def test_a_value_is_computed_once_while_its_object_lives_and_dropped_with_it():
    cache, calls = WeakCache(), []

    def make(obj):
        calls.append(id(obj))  # (not the object: the cache must not be what keeps it alive)
        return len(calls)

    a, b = _Obj(), _Obj()
    assert (cache.get(a, make), cache.get(a, make), cache.get(b, make)) == (1, 1, 2)
    assert calls == [id(a), id(b)] and a in cache and len(cache) == 2
    del a
    gc.collect()
    assert len(cache) == 1 and b in cache  # (the entry of a went with it)
    c = _Obj()  # (may reuse a's id: a new object is computed afresh, never served a's value)
    assert cache.get(c, make) == 3


def test_objects_without_weak_references_are_computed_each_time():
    cache, calls = WeakCache(), []
    key = (1, 2)  # tuples take no weak references
    assert cache.get(key, lambda k: calls.append(k) or len(calls)) == 1
    assert cache.get(key, lambda k: calls.append(k) or len(calls)) == 2
    assert key not in cache and len(cache) == 0
