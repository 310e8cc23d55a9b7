"""Chunked fixed-step runs (Ctrl-C, progress) give the numbers of one call, bit for bit.

The driver cuts long runs into chunks whose boundaries fall inside output intervals and
depend on measured times; every chunk takes the run's own step lengths and continues
from the exact state of the previous one (the low parts of compensated storage, the
Moser-Veselov Newton predictor), so the results do not depend on where the chunks fall.
"""
import numpy as np
import pytest

import hyperrotor as hr
from hyperrotor import Inertia, RigidBody

J5 = [0.3, 0.55, 0.9, 1.4, 2.1]


CASES = {  # method, options, ensemble shape, span: > 2e6 plane flows, so the run is cut into chunks
    "splitting4-plain-one": ("splitting4", dict(compensated=False), (), 60.0),
    "splitting4-compensated-one": ("splitting4", dict(compensated=True), (), 60.0),
    "splitting4-plain-ensemble": ("splitting4", dict(compensated=False), (40,), 3.0),
    "splitting4-compensated-ensemble": ("splitting4", dict(compensated=True), (40,), 3.0),
    "moser-veselov-one": ("moser-veselov", {}, (), 15.0),
    "moser-veselov-ensemble": ("moser-veselov", {}, (8,), 3.0),
}


@pytest.mark.parametrize("case", list(CASES))
def test_chunks_do_not_change_the_numbers(case, rng):
    method, opts, members, span = CASES[case]
    body = RigidBody(Inertia.from_mass_tensor(J5))
    w0 = rng.normal(size=members + (10,))
    t = np.linspace(0.0, span, 4)  # chunk boundaries fall inside these intervals
    att = method == "moser-veselov"  # (an ensemble without attitude runs the splittings' bodies-innermost kernel)
    with hr.options(chunk_seconds=1e3):
        few = hr.simulate(body, w0, t, method=method, dt=0.001, attitude=att, options=opts)
    with hr.options(chunk_seconds=1e-4):  # (chunks of 0.1 ms: > 100 here, still many on a machine 10x faster)
        many = hr.simulate(body, w0, t, method=method, dt=0.001, attitude=att, options=opts)
    assert many.stats["chunks"] > max(3, few.stats["chunks"])
    np.testing.assert_array_equal(many.L, few.L)
    if att:
        np.testing.assert_array_equal(many.attitude, few.attitude)
    if members:  # each member's row is its own run (another kernel, other chunks)
        single = hr.simulate(body, w0[5], t, method=method, dt=0.001, attitude=att, options=opts)
        np.testing.assert_array_equal(few.L[5], single.L)
