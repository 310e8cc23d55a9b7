"""The one power-of-two scaling (hyperrotor._floats) that every scale-invariant computation divides by."""
import math

import numpy as np
import pytest
from hypothesis import given, strategies as st

from hyperrotor._floats import power_of_two_scale


@given(st.floats(allow_nan=False, allow_infinity=False).filter(lambda x: x != 0.0))
def test_scale_is_the_power_of_two_at_or_below(x):
    s = power_of_two_scale(x)
    assert type(s) is float and math.frexp(s)[0] == 0.5  # a power of two (subnormal ones included)
    assert 1.0 <= abs(x) / s < 2.0
    assert (x / s) * s == x  # exact both ways


@pytest.mark.parametrize("x", [0.0, -0.0, math.inf, -math.inf, math.nan])
def test_nothing_to_scale_gives_one(x):
    assert power_of_two_scale(x) == 1.0


def test_elementwise_on_arrays():
    x = np.array([[3.0, 0.0, 5e-324], [np.inf, -1.7e308, 0.75]])
    s = power_of_two_scale(x)
    assert s.shape == x.shape
    np.testing.assert_array_equal(s, [[2.0, 1.0, 5e-324], [1.0, 2.0**1023, 0.5]])
