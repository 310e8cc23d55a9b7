"""simulate(client=...): ensembles on a dask cluster give the same numbers as one call."""
import numpy as np
import pytest

import hyperrotor as hr
from hyperrotor.classical.solvers import SOLVERS, FixedStepSolver
from tolerance import scaled_tol


@pytest.fixture(scope="module")
def client():
    dd = pytest.importorskip("dask.distributed")
    with dd.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            dd.Client(cluster) as c:
        yield c


@pytest.mark.slow
@pytest.mark.parametrize("method", [m for m in SOLVERS if m in ("splitting4", "splitting8", "moser-veselov", "DOP853")])
def test_client_gives_the_same_ensemble(client, method):
    body = hr.RigidBody(hr.Inertia.from_mass_tensor([0.3, 0.55, 0.9, 1.4, 2.1]))
    w0 = np.random.default_rng(1).normal(size=(2, 20, 10))
    t = np.linspace(0.0, 3.0, 4)
    kw = dict(rtol=1e-5) if method == "moser-veselov" else dict(rtol=1e-8)
    a = hr.simulate(body, w0, t, method=method, attitude=True, **kw)
    b = hr.simulate(body, w0, t, method=method, attitude=True, client=client, **kw)
    if method == "moser-veselov":  # LAPACK solves inside the kernel: the workers' BLAS may round differently
        tol = scaled_tol(a.L, k=64, steps=a.stats["steps"])
        np.testing.assert_allclose(b.L, a.L, rtol=0, atol=tol)
        np.testing.assert_allclose(b.attitude, a.attitude, rtol=0, atol=tol)
        return
    np.testing.assert_array_equal(a.L, b.L)
    np.testing.assert_array_equal(a.attitude, b.attitude)
    if issubclass(SOLVERS[method], FixedStepSolver):
        np.testing.assert_array_equal(a.sol([1.3]), b.sol([1.3]))
