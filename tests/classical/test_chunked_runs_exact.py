"""Chunked fixed-step runs (Ctrl-C, progress) give the numbers of one call, bit for bit.

The driver cuts long runs into chunks whose boundaries fall inside output intervals and
depend on measured times; every chunk takes the run's own step lengths and continues
from the exact (compensated) state of the previous one, so the splittings' results do
not depend on where the chunks fall.
"""
import numpy as np
import pytest

import hyperrotor as hr
from hyperrotor import Inertia, RigidBody

J5 = [0.3, 0.55, 0.9, 1.4, 2.1]


@pytest.mark.parametrize("compensated", [False, True], ids=["plain", "compensated"])
@pytest.mark.parametrize("members, span", [((), 60.0), ((40,), 3.0)], ids=["one", "ensemble"])
def test_chunks_do_not_change_the_numbers(members, span, compensated, rng):
    body = RigidBody(Inertia.from_mass_tensor(J5))
    w0 = rng.normal(size=members + (10,))
    t = np.linspace(0.0, span, 4)  # > 2e6 plane flows: chunked; boundaries fall inside these intervals
    with hr.options(chunk_seconds=1e3):
        few = hr.simulate(body, w0, t, method="splitting4", dt=0.001, compensated=compensated)
    with hr.options(chunk_seconds=1e-3):
        many = hr.simulate(body, w0, t, method="splitting4", dt=0.001, compensated=compensated)
    assert many.stats["chunks"] > max(3, few.stats["chunks"])
    np.testing.assert_array_equal(many.L, few.L)
    if members:  # each member's row is its own run (another kernel, other chunks)
        single = hr.simulate(body, w0[7], t, method="splitting4", dt=0.001, compensated=compensated)
        np.testing.assert_array_equal(few.L[7], single.L)
