"""Classical rigid rotation in N dimensions: inertia, Euler equations, integrators, closed forms."""
from . import inertia, rigid_body
from .inertia import *  # noqa: F401,F403
from .rigid_body import *  # noqa: F401,F403

__all__ = [*inertia.__all__, *rigid_body.__all__]
