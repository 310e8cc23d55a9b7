"""Shared fixtures: machine epsilon and a seeded generator (tolerances are stated as multiples of eps)."""
import numpy as np
import pytest


@pytest.fixture
def eps():
    return float(np.finfo(float).eps)


@pytest.fixture
def rng():
    return np.random.default_rng(20260922)
