"""Classical rigid rotation in N dimensions: inertia, Euler equations, integrators, closed forms."""
from . import closed_form, inertia, integrate, rigid_body, scenes, stability
from . import chaos
from .chaos import *  # noqa: F401,F403
from .closed_form import *  # noqa: F401,F403
from .inertia import *  # noqa: F401,F403
from .integrate import *  # noqa: F401,F403
from .rigid_body import *  # noqa: F401,F403
from .scenes import *  # noqa: F401,F403
from .stability import *  # noqa: F401,F403

__all__ = [
    *inertia.__all__,
    *rigid_body.__all__,
    *integrate.__all__,
    *closed_form.__all__,
    *chaos.__all__,
    *stability.__all__,
    *scenes.__all__,
]
