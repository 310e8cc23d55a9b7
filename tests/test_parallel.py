"""hyperrotor._parallel: chunked ensembles give the single-call result, in threads and on dask."""
import sys

import numpy as np
import pytest

from hyperrotor import _parallel


def logistic_rows(x, steps):
    """Row-wise chaotic map (a 1e-16 change of the arithmetic shows after ~50 steps)."""
    out = np.array(x, dtype=float, copy=True)
    for _ in range(steps):
        out = 3.99 * out * (1.0 - out)
    return out


def pair_rows(p, x):
    """Two outputs per row, from a parameter row and an initial-condition row."""
    y = p[:, :1] * np.sin(x) + p[:, 1:]
    return y, y.sum(axis=1)


@pytest.fixture(scope="module")
def client(dask_client):
    """The session's LocalCluster (tests/conftest.py); the workers cannot import this test module,
    so its functions travel by value while these tests run."""
    import cloudpickle

    cloudpickle.register_pickle_by_value(sys.modules[__name__])
    yield dask_client
    cloudpickle.unregister_pickle_by_value(sys.modules[__name__])


@pytest.fixture
def rows():
    return np.random.default_rng(7).uniform(0.1, 0.9, size=(37, 3))


@pytest.mark.parametrize("chunk_size", [1, 5, 36, 37, 100])
@pytest.mark.parametrize("workers", [1, 2, 3])
def test_threads_bit_identical_to_single_call(rows, chunk_size, workers):
    ref = logistic_rows(rows, 200)
    out = _parallel.map_rows(logistic_rows, rows, args=(200,), chunk_size=chunk_size, workers=workers, progress=False)
    assert out.shape == ref.shape
    assert np.array_equal(out, ref)


def test_tuple_rows_and_tuple_results_keep_order(rows):
    p = np.column_stack([np.arange(37.0), -np.arange(37.0)])
    ref = pair_rows(p, rows)
    out = _parallel.map_rows(pair_rows, (p, rows), chunk_size=4, workers=2, progress=False)
    assert isinstance(out, tuple) and len(out) == 2
    for a, b in zip(out, ref):
        assert np.array_equal(a, b)


def test_grid_rows_are_parameter_major():
    params = np.array([[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]])
    initial = np.array([[0.1], [0.2]])
    P, X = _parallel.grid_rows(params, initial)
    assert P.shape == (6, 2) and X.shape == (6, 1)
    for p in range(3):
        for m in range(2):
            assert np.array_equal(P[p * 2 + m], params[p])
            assert np.array_equal(X[p * 2 + m], initial[m])


def test_empty_ensemble_calls_func_once():
    calls = []

    def counted(x, steps):
        calls.append(x.shape)
        return logistic_rows(x, steps)

    out = _parallel.map_rows(counted, np.empty((0, 3)), args=(5,), progress=False)
    assert calls == [(0, 3)]  # once, on the empty rows (its result has the shape func gives them)
    assert out.shape == (0, 3) and out.dtype == np.float64


def test_progress_bar_counts_rows(rows, capsys):
    out = _parallel.map_rows(logistic_rows, rows, args=(3,), chunk_size=10, workers=2, progress=True, desc="rows")
    assert np.array_equal(out, logistic_rows(rows, 3))
    err = capsys.readouterr().err
    assert "37/37" in err and "rows" in err


@pytest.mark.parametrize("bad, exc, words", [
    (dict(chunk_size=0), ValueError, "chunk_size"),
    (dict(chunk_size=2.5), TypeError, "chunk_size"),
    (dict(workers=0), ValueError, "workers"),
    (dict(client="localhost:8786"), TypeError, "dask.distributed.Client"),
])
def test_bad_arguments_are_named(rows, bad, exc, words):
    with pytest.raises(exc, match=words):
        _parallel.map_rows(logistic_rows, rows, args=(3,), **bad)


def test_rows_of_different_lengths_refused(rows):
    with pytest.raises(ValueError, match="leading"):
        _parallel.map_rows(pair_rows, (rows[:3], rows), progress=False)


def test_missing_dask_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "dask.distributed", None)
    with pytest.raises(ImportError, match=r'pip install "hyperrotor\[distributed\]"'):
        _parallel.import_distributed()


def test_client_bit_identical_to_single_call(client, rows):
    assert _parallel.client_threads(client) == 2
    ref = logistic_rows(rows, 200)
    for chunk_size in (None, 1, 8):
        out = _parallel.map_rows(logistic_rows, rows, args=(200,), client=client, chunk_size=chunk_size, progress=False)
        assert np.array_equal(out, ref)


def test_client_tuple_results_and_progress(client, rows, capsys):
    p = np.column_stack([np.arange(37.0), -np.arange(37.0)])
    out = _parallel.map_rows(pair_rows, (p, rows), client=client, chunk_size=6, progress=True)
    for a, b in zip(out, pair_rows(p, rows)):
        assert np.array_equal(a, b)
    assert "37/37" in capsys.readouterr().err


def failing_rows(x, bad_row, exc):
    """Raises ``exc`` in the chunk holding ``bad_row`` (a stand-in for Ctrl-C during a chunk)."""
    if np.any(x[:, 0] == bad_row):
        raise exc("chunk failed")
    return x


@pytest.mark.parametrize("workers", [1, 2])
@pytest.mark.parametrize("exc", [KeyboardInterrupt, ValueError])
def test_interrupt_or_error_in_a_chunk_propagates(workers, exc):
    rows = np.arange(40.0).reshape(20, 2)
    with pytest.raises(exc, match="chunk failed"):
        _parallel.map_rows(failing_rows, rows, args=(10.0, exc), chunk_size=3, workers=workers, progress=False)


def test_a_closed_client_is_refused_at_the_door():
    """A closed client: refused by name before any work (simulate's ensemble ran its in-process step check for 5 min
    before dask's ClosedClientError; lyapunov counted it as 1 worker thread)."""
    dd = pytest.importorskip("dask.distributed")
    import hyperrotor as hr
    import hyperrotor.quantum as hq

    with dd.LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=":0") as cluster:
        closed = dd.Client(cluster)
        closed.close()
    body = np.linspace(1.0, 2.0, 10)
    calls = [lambda: hr.simulate(body, np.ones((50, 10)), np.linspace(0.0, 50.0, 3), client=closed),
             lambda: hr.lyapunov(body, np.ones((4, 10)), 1.0, client=closed),
             lambda: hq.SectorPropagator(hq.rotor_hamiltonian(hq.irrep(3, (2,)), [1.0, 2.0, 3.0]), client=closed),
             lambda: _parallel.map_rows(logistic_rows, np.ones((4, 3)), args=(2,), client=closed),
             lambda: hq.sector_spectra(hq.irrep(3, (2,)), [1.0, 2.0, 3.0], client=closed)]
    for call in calls:
        with pytest.raises(ValueError, match="client is a dask client that is closed"):
            call()
    with pytest.raises(TypeError, match="client must be a dask.distributed.Client"):
        hq.SectorPropagator(hq.rotor_hamiltonian(hq.irrep(3, (2,)), [1.0, 2.0, 3.0]), client=3)  # (was: at first use)


def test_a_propagator_built_with_a_client_pickles(client):
    """Pickled without its client (a propagator built with client= did not pickle); the copy evolves in-process to
    the same states."""
    import pickle

    import hyperrotor.quantum as hq

    H = hq.rotor_hamiltonian(hq.irrep(3, (6,)), [1.0, 2.0, 3.0])
    U = hq.SectorPropagator(H, client=client)
    copy = pickle.loads(pickle.dumps(U))
    assert copy.client is None and U.client is client
    psi = np.zeros(13, dtype=complex)
    psi[0] = 1.0
    t = np.linspace(0.0, 1.0, 4)
    got, ref = copy.evolve(psi, t).states, hq.SectorPropagator(H).evolve(psi, t).states
    assert len(got) == 4 and all(np.allclose(a.full(), b.full(), rtol=0, atol=1e-12) for a, b in zip(got, ref))


def test_sector_spectra_on_a_cluster_equal_the_threads_bit_for_bit(client):
    """One BLAS thread per sector on both (the client path used the workers' default: equal only where the
    cluster's environment limited BLAS)."""
    import hyperrotor.quantum as hq

    rep, body = hq.irrep(5, (6, 3)), np.linspace(1.0, 2.0, 10)
    a, b = hq.sector_spectra(rep, body, client=client), hq.sector_spectra(rep, body, workers=2)
    assert list(a) == list(b) and all(np.array_equal(a[k], b[k]) for k in a)
