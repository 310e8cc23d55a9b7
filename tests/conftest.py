"""Shared fixtures: machine epsilon, a seeded generator (tolerances: tests/tolerance.py) and one dask cluster."""
import numpy as np
import pytest


@pytest.fixture
def eps():
    return float(np.finfo(float).eps)


@pytest.fixture
def rng():
    return np.random.default_rng(20260922)


@pytest.fixture(scope="session")
def dask_client():
    """One local dask cluster (2 worker processes) for the whole session, shared by the parallel tests.

    ``dashboard_address=":0"``: a free port (the default 8787 may be taken by another cluster,
    and its UserWarning is an error under our warning filters). The workers' sampling profiler (every 10 ms),
    event-loop tick (20 ms) and memory monitor (100 ms) are slowed to once a second: idle, each worker took
    about 5% of a core for the rest of the session (measured with psutil over 10 s), now 0.7%, CPU that the
    other tests and the other CI job need.
    """
    dd = pytest.importorskip("dask.distributed")
    import dask
    quiet = {"distributed.worker.profile.enabled": False, "distributed.worker.profile.interval": "1s",
             "distributed.worker.profile.cycle": "10s", "distributed.admin.tick.interval": "1s",
             "distributed.worker.memory.monitor-interval": "1s"}
    with dask.config.set(quiet), \
            dd.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster, \
            dd.Client(cluster) as client:
        yield client


@pytest.fixture(autouse=True)
def _no_wall_time_warnings():
    """simulate warns before a run whose *timed* estimate exceeds options["slow_run_warning_seconds"];
    on a loaded or slow machine (the lowest-versions CI job, two jobs side by side) a test's run may
    cross that line, and warnings are errors here. The threshold is lifted for every test; the tests
    of the warning set their own (0 s) inside."""
    import hyperrotor

    with hyperrotor.options(slow_run_warning_seconds=1e9):
        yield


@pytest.fixture(scope="session", autouse=True)
def _matplotlib_font_cache():
    """Build matplotlib's font cache once, before any test: in a fresh environment the first process to
    use matplotlib builds it and says so on stderr, and the CLI tests run in subprocesses that must
    print nothing there (a CI job whose cache was missing or stale failed on 'findfont: ... Falling back')."""
    import matplotlib.font_manager

    matplotlib.font_manager.findfont("DejaVu Sans", rebuild_if_missing=True)
