"""simulate(client=...): ensembles on a dask cluster give the same numbers as one call."""
import numpy as np
import pytest

import hyperrotor as hr
from hyperrotor.classical.solvers import SOLVERS
from tolerance import scaled_tol

BODY5 = [0.3, 0.55, 0.9, 1.4, 2.1]


@pytest.mark.slow
@pytest.mark.parametrize("method", [m for m in SOLVERS if m in ("splitting4", "splitting8", "DOP853")])
def test_client_gives_the_same_ensemble(dask_client, method):
    body = hr.RigidBody(hr.Inertia.from_mass_tensor(BODY5))
    w0 = np.random.default_rng(1).normal(size=(2, 20, 10))
    t = np.linspace(0.0, 3.0, 4)
    a = hr.simulate(body, w0, t, method=method, attitude=True, rtol=1e-8)
    b = hr.simulate(body, w0, t, method=method, attitude=True, client=dask_client, rtol=1e-8)
    np.testing.assert_array_equal(a.L, b.L)
    np.testing.assert_array_equal(a.attitude, b.attitude)
    if method != "DOP853":  # every step counted: the probe and the check (every member, on their own) here, then
        assert (b.stats["reruns"], b.stats["work"]) == (a.stats["reruns"], a.stats["work"] + a.stats["steps"] * 40)
    # dense output: fixed-step methods rebuild it here, scipy methods on the workers; the same numbers
    tq = [0.4, 1.3, 2.999]
    np.testing.assert_array_equal(a.sol(tq), b.sol(tq))
    np.testing.assert_array_equal(a.sol(tq, "attitude"), b.sol(tq, "attitude"))


@pytest.mark.slow
def test_client_gives_the_same_moser_veselov_ensemble(dask_client):
    """Moser-Veselov calls LAPACK inside its kernel: the workers' BLAS may round differently, so the
    comparison is to round-off over the run (a small ensemble: the workers compile the kernel first)."""
    body = hr.RigidBody(hr.Inertia.from_mass_tensor(BODY5))
    w0 = np.random.default_rng(2).normal(size=(2, 3, 10))
    t = np.linspace(0.0, 1.0, 3)
    a = hr.simulate(body, w0, t, method="moser-veselov", attitude=True, dt=0.05)
    b = hr.simulate(body, w0, t, method="moser-veselov", attitude=True, dt=0.05, client=dask_client)
    tol = scaled_tol(a.L, k=64, steps=a.stats["steps"])
    np.testing.assert_allclose(b.L, a.L, rtol=0, atol=tol)
    np.testing.assert_allclose(b.attitude, a.attitude, rtol=0, atol=tol)


def test_events_on_an_ensemble_with_a_client_are_refused_by_name(dask_client):
    with pytest.raises(ValueError, match="events= on an ensemble runs in this process"):
        hr.simulate([2.0, 3.0, 4.0], np.ones((2, 3)), [0.0, 1.0], events=lambda t, L: L[0], client=dask_client)


def test_a_dask_ensembles_check_covers_the_fastest_up_to_its_limit(dask_client, monkeypatch, checks):
    """The check of a dask ensemble runs in this process before the workers: on up to CHECK_MEMBERS members,
    the fastest (here 16 of 40), not the whole ensemble again; a run in this process checks all 40."""
    from hyperrotor.classical.solvers import distributed

    seen = checks
    monkeypatch.setattr(distributed, "CHECK_MEMBERS", 16)
    w0 = np.random.default_rng(4).normal(size=(40, 10)) * np.linspace(0.5, 1.5, 40)[:, None]
    t = np.linspace(0.0, 2.0, 5)
    body = hr.RigidBody(hr.Inertia.from_mass_tensor(BODY5))
    a = hr.simulate(body, w0, t, rtol=1e-8)
    assert {c.members.size for c in seen} == {40}
    seen.clear()
    b = hr.simulate(body, w0, t, rtol=1e-8, client=dask_client)
    rates = np.abs(w0).max(axis=1)  # (the members' rates grow with their index here)
    assert seen and all(c.members.size == 16 for c in seen)
    assert set(seen[-1].members) <= set(np.argsort(rates)[-20:])
    if a.stats["steps"] == b.stats["steps"]:
        np.testing.assert_array_equal(a.L, b.L)


def test_the_step_control_before_a_dask_ensemble_shows_progress(dask_client, monkeypatch):
    """The probe and the check run here before the members go to the workers: progress=True puts them on a bar
    (a review: nothing for 20 s), counting the steps they took (a recording bar: tqdm's screen depends on timing)."""
    from hyperrotor.classical.solvers import members

    bars = []

    class Recording:
        def __init__(self, desc):
            self.desc, self.n, self.closed = desc, 0, False

        def update(self, n=1):
            self.n += n

        def reset(self, total=None):
            pass

        def close(self):
            self.closed = True

    def recording_bar(progress, total, desc=None, **kw):
        bars.append(Recording(desc))
        return bars[-1]

    monkeypatch.setattr(members, "progress_bar", recording_bar)
    body = hr.RigidBody(hr.Inertia.from_mass_tensor(BODY5))
    w0 = np.random.default_rng(3).normal(size=(6, 10))
    res = hr.simulate(body, w0, np.linspace(0.0, 2.0, 3), rtol=1e-8, client=dask_client, progress=True)
    assert [b.desc for b in bars] == ["simulate: step control"] and bars[0].closed
    assert 0 < bars[0].n <= res.stats["work"] - res.stats["steps"] * 6  # (the members' own steps ran on the workers)
