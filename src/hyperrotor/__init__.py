"""hyperrotor: rigid rotation in N dimensions, classical and quantum.

Conventions (plane labels, paper vs standard matrices, Hermitian vs
anti-Hermitian generators, hbar) are documented in :mod:`hyperrotor.conventions`.
"""
from . import conventions
from .conventions import *  # noqa: F401,F403
from . import classical
from .classical import *  # noqa: F401,F403
from . import quantum
from . import paper
from .paper import verify_paper

__version__ = "0.1.0"

__all__ = [*conventions.__all__, *classical.__all__, "verify_paper", "quantum", "classical", "conventions", "paper"]
