"""hr.options: values checked on assignment, blocks local to a thread/context, seen by workers."""
import math
import threading

import numpy as np
import pytest

import hyperrotor as hr
from hyperrotor import _parallel
from hyperrotor._options import UnknownOptionError


@pytest.mark.parametrize("key", ["max_steps", "max_dimension", "max_output_bytes"])
@pytest.mark.parametrize("bad, error", [(math.nan, TypeError), (-1, ValueError), (0, ValueError), ("10", TypeError),
                                        (True, TypeError), (1.5, TypeError), (None, TypeError)])
def test_integer_budgets_refuse_bad_values_on_assignment(key, bad, error):
    before = hr.options[key]
    with pytest.raises(error, match=f"option '{key}'"):
        hr.options[key] = bad
    with pytest.raises(error, match=f"option '{key}'"):
        with hr.options(**{key: bad}):
            pass  # pragma: no cover - refused before the block
    assert hr.options[key] == before


@pytest.mark.parametrize("bad, error", [(math.nan, ValueError), (math.inf, ValueError), (-0.1, ValueError),
                                        ("1", TypeError), (False, TypeError)])
def test_float_options_refuse_bad_values(bad, error):
    with pytest.raises(error, match="option 'chunk_seconds'"):
        hr.options["chunk_seconds"] = bad


def test_integral_floats_are_integers():
    with hr.options(max_steps=1e9):
        assert hr.options["max_steps"] == 10**9 and isinstance(hr.options["max_steps"], int)


def test_unknown_keys_raise_one_exception_that_is_both_key_and_value_error():
    for action in (lambda: hr.options["nope"], lambda: hr.options.__setitem__("nope", 1),
                   lambda: hr.options(nope=1).__enter__()):
        with pytest.raises(UnknownOptionError, match="unknown option 'nope'; allowed: .*max_steps") as info:
            action()
        assert isinstance(info.value, KeyError) and isinstance(info.value, ValueError)


def test_blocks_are_local_to_their_thread_and_interleave_correctly():
    default = hr.options["max_steps"]
    entered = threading.Barrier(2)
    seen: dict = {}

    def worker(name, value):
        with hr.options(max_steps=value):
            entered.wait()  # both blocks are open at once
            seen[name] = hr.options["max_steps"]
            entered.wait()
        seen[name + " after"] = hr.options["max_steps"]

    threads = [threading.Thread(target=worker, args=("a", 10)), threading.Thread(target=worker, args=("b", 20))]
    for th in threads:
        th.start()
    # a block of this thread, open while the others run, is not seen by them and vice versa
    with hr.options(max_steps=30):
        for th in threads:
            th.join()
        assert hr.options["max_steps"] == 30
    assert seen == {"a": 10, "b": 20, "a after": default, "b after": default}
    assert hr.options["max_steps"] == default


def test_session_value_is_seen_by_every_thread_without_a_block():
    default = hr.options["max_steps"]
    try:
        hr.options["max_steps"] = 12345
        out = []
        th = threading.Thread(target=lambda: out.append(hr.options["max_steps"]))
        th.start()
        th.join()
        assert out == [12345]
    finally:
        hr.options["max_steps"] = default


def _read_option(rows):
    return np.full(rows.shape[0], hr.options["max_steps"], dtype=np.int64)


def test_parallel_workers_see_the_block_that_started_them():
    rows = np.arange(16.0)
    with hr.options(max_steps=777):
        out = _parallel.map_rows(_read_option, rows, workers=2, chunk_size=2)
    assert out.tolist() == [777] * 16


def test_dask_tasks_see_the_block_that_started_them(dask_client):
    rows = np.arange(8.0)
    with hr.options(max_steps=778):
        out = _parallel.map_rows(_read_option, rows, client=dask_client, chunk_size=2)
    assert out.tolist() == [778] * 8


def test_an_in_process_cluster_sees_a_block_that_sets_a_session_value_back_to_its_default():
    """A dask worker thread in this process reads the session's values: a block that sets a key back to its
    default must reach it too (the tasks saw the session's value, and evolve(client=) ran Krylov at it)."""
    dd = pytest.importorskip("dask.distributed")
    key = "max_steps"
    default = hr.options._defaults[key]
    rows = np.arange(4.0)
    with dd.Client(processes=False, n_workers=1, threads_per_worker=1, dashboard_address=":0") as client:
        old = hr.options[key]
        hr.options[key] = default + 5
        try:
            with hr.options(**{key: default}):
                assert key in hr.options.portable()
                out = _parallel.map_rows(_read_option_named, rows, args=(key,), client=client, chunk_size=2)
            outside = _parallel.map_rows(_read_option_named, rows, args=(key,), client=client, chunk_size=2)
        finally:
            hr.options[key] = old
    assert out.tolist() == [default] * 4
    assert outside.tolist() == [default + 5] * 4


def _read_option_named(rows, key):
    return np.full(rows.shape[0], hr.options[key], dtype=np.float64)


def test_dask_workers_import_the_module_that_registers_a_changed_option(dask_client):
    """An option registered by a module that a fresh worker has not imported (hyperrotor.quantum
    loads lazily) still reaches the worker with the caller's value."""
    import hyperrotor.quantum.coherent  # noqa: F401 - quantum modules register their options on import

    owners = hr.options._owners
    key = next(k for k in sorted(owners) if owners[k].startswith("hyperrotor.quantum"))
    value = hr.options[key] * 2 + 1
    with hr.options(**{key: value}):
        out = _parallel.map_rows(_read_option_named, np.arange(4.0), args=(key,), client=dask_client, chunk_size=2)
    assert out.tolist() == [value] * 4
