"""Quantum so(N) angular momentum: SymPy operators, matrix representations, QuTiP rotors."""
from . import operators
from .operators import *  # noqa: F401,F403

__all__ = [*operators.__all__]
