"""Event location of the fixed-step driver when the re-integrated step loses the grid's sign change.

A crossing is seen between two step states; it is located by Brent's method on one step of
the method from the earlier state. With a step far too long for the motion (|omega| dt >> 1)
or g ~ 0 at the step's end, that one step need not reproduce the sign change; the driver then
reports the crossing at the step's end instead of letting brentq's bracket error escape
(such runs are garbage anyway; the point is a result instead of an internal error).
"""
import numpy as np
import pytest

import hyperrotor as hr


@pytest.mark.parametrize("scale", [1e3, 1e6, 1e20, 1e300])
def test_events_with_steps_far_too_long_are_reported_not_raised(scale):
    body = hr.RigidBody(hr.Inertia.from_mass_tensor([1.0, 2.0, 3.0, 4.0]))

    def g(t, L):
        return L[0]

    g.direction = 1
    dt = 0.05
    tr = hr.simulate(body, np.full(6, scale), [0.0, 1.0], method="splitting4", dt=dt, events=g)
    te = tr.t_events[0]
    Le = tr.L_events[0]
    # (before: brentq's "f(a) and f(b) must have different signs" escaped for scale >= 1e6)
    assert te.size >= 1 and Le.shape == (te.size, 6) and np.all(np.isfinite(Le))
    assert np.all(np.diff(te) > 0) and te[0] > 0.0 and te[-1] <= 1.0
    # |L| is conserved by every step, so the event states lie on the run's Casimir sphere
    np.testing.assert_allclose(np.linalg.norm(Le / scale, axis=1), np.linalg.norm(tr.L[0] / scale), rtol=1e-12)


@pytest.mark.parametrize("method", ["splitting8", "splitting2", "moser-veselov", "DOP853"])
@pytest.mark.parametrize("direction", [0, 1, -1])
def test_a_zero_at_the_first_time_is_an_event_as_in_solve_ivp(method, direction):
    """g(t0) = 0 was an event for scipy's methods only (solve_ivp's rule: (g <= 0) & (g_new >= 0) upwards, ...):
    the fixed-step methods skipped it and a terminal event stopped 14 time units later. Now every method reports it
    when the direction allows (g_new's sign: L[0] < 0 just after t0, so upwards it is not one)."""
    def g(t, L):
        return L[0]

    g.direction = direction
    g.terminal = True
    t = np.linspace(0.0, 30.0, 7)
    tr = hr.simulate([2.0, 3.0, 4.0], [0.0, 1.0, 0.2], t, method=method, events=g)
    ref = hr.simulate([2.0, 3.0, 4.0], [0.0, 1.0, 0.2], t, method="DOP853", rtol=1e-10, events=g)
    assert tr.t_events[0].size == 1
    if direction <= 0:
        assert tr.t_events[0][0] == 0.0 and tr.t[-1] == 0.0
        np.testing.assert_array_equal(tr.L_events[0][0], [0.0, 3.0, 0.8])
    else:  # the first upward crossing, where DOP853 finds it
        assert tr.t_events[0][0] == pytest.approx(ref.t_events[0][0], abs=1e-6)
    assert ref.t_events[0][0] == pytest.approx(tr.t_events[0][0], abs=1e-6)


@pytest.mark.parametrize("method", ["splitting2", "moser-veselov", "DOP853"])
@pytest.mark.parametrize("direction", [0, 1, -1])
def test_a_g_that_stays_zero_is_an_event_at_the_first_time_in_both_directions(method, direction):
    """A steady rotation keeps L12 = 0 exactly: solve_ivp's rule counts g = g_new = 0 upwards and downwards."""
    def g(t, L):
        return L[0]

    g.direction = direction
    g.terminal = True
    tr = hr.simulate([2.0, 3.0, 4.0], [0.0, 1.0, 0.0], [0.0, 1.0], method=method, events=g)
    assert [te.tolist() for te in tr.t_events] == [[0.0]] and tr.t[-1] == 0.0
