"""Fixtures of the quantum tests."""
import pytest


@pytest.fixture
def one_blas_thread():
    """Dense references and many small eigh/eigvalsh calls on one BLAS thread: on the shared test machine threads only
    oversubscribe (modules that want it: ``pytestmark = pytest.mark.usefixtures("one_blas_thread")``)."""
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1, user_api="blas"):
        yield
