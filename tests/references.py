"""Independent references shared by the tests: written here from first principles, not from the package's helpers
(only the structure constants of the conventions, which their own tests check against the commutators)."""
from __future__ import annotations

import numpy as np

from hyperrotor.conventions import dimension_from_count, structure_constants


def component_rhs(I):
    """The component Euler equations ``f(t, w)``: ``dw_a/dt = sum_bc C[b, c, a] w_b I_c w_c / I_a`` for the plane
    moments ``I`` (plane order), from the structure constants (scipy's ``fun(t, y)`` signature)."""
    I = np.asarray(I, float)
    C = structure_constants(dimension_from_count(I.size)).astype(float)

    def f(t, w):
        return np.einsum("bca,b,c->a", C, w, I * w) / I

    return f
