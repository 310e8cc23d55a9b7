"""Classical rigid rotation in N dimensions: inertia, Euler equations, integrators, closed forms."""
from . import body_points, closed_form, poincare, inertia, mass_points, poinsot, quartet, rigid_body, scene_html, scenes, solvers, stability
from . import simulate as _simulate_module
from . import chaos
from .body_points import *  # noqa: F401,F403
from .chaos import *  # noqa: F401,F403
from .poincare import *  # noqa: F401,F403
from .closed_form import *  # noqa: F401,F403
from .poinsot import *  # noqa: F401,F403
from .quartet import *  # noqa: F401,F403
from .inertia import *  # noqa: F401,F403
from .mass_points import *  # noqa: F401,F403
from .rigid_body import *  # noqa: F401,F403
from .scene_html import *  # noqa: F401,F403
from .scenes import *  # noqa: F401,F403
from .simulate import SIMULATION_METHODS, Trajectory, simulate
from .solvers import (SOLVERS, AccuracyWarning, Solver, StepBudgetError, UnreachableAccuracyError, casimir_shift,
                      splitting_coefficients)
from .stability import *  # noqa: F401,F403

__all__ = [
    *inertia.__all__,
    *mass_points.__all__,
    *rigid_body.__all__,
    *_simulate_module.__all__,
    "SOLVERS",
    "Solver",
    "StepBudgetError",
    "UnreachableAccuracyError",
    "AccuracyWarning",
    "splitting_coefficients",
    "casimir_shift",
    *closed_form.__all__,
    *quartet.__all__,
    *poinsot.__all__,
    *chaos.__all__,
    *poincare.__all__,
    *stability.__all__,
    *scenes.__all__,
    *body_points.__all__,
    *scene_html.__all__,
]
