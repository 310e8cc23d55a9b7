"""Quantum so(N) angular momentum: SymPy operators, matrix representations, QuTiP rotors.

Layers: ``operators``/``normal_form``/``harmonic`` (symbolic, eq. 142) and
``weights``/``representation``/``standard_reps``/``gelfand_tsetlin`` (matrices)
sit below ``hamiltonian`` (the rotor Hamiltonian), ``evolve`` (propagators),
``spectrum`` and ``coherent`` (coherent states); the classical subpackage never
imports this one. The vocabulary (``form=``, keyword-only ``hbar``, ``t``,
``rtol``/``atol``, ``rng``) is documented in docs/conventions.md.
"""
from . import (coherent, evolve as _evolve_module, gelfand_tsetlin, hamiltonian, harmonic, normal_form, operators,
               representation, sectors, spectrum as _spectrum_module, standard_reps, statistics, weights)
from . import representations, rotor  # noqa: F401  (old module names, re-exports)
from .coherent import *  # noqa: F401,F403
from .evolve import *  # noqa: F401,F403
from .gelfand_tsetlin import *  # noqa: F401,F403
from .hamiltonian import *  # noqa: F401,F403
from .harmonic import *  # noqa: F401,F403
from .normal_form import *  # noqa: F401,F403
from .operators import *  # noqa: F401,F403
from .representation import *  # noqa: F401,F403
from .sectors import *  # noqa: F401,F403
from .spectrum import *  # noqa: F401,F403
from .standard_reps import *  # noqa: F401,F403
from .statistics import *  # noqa: F401,F403
from .weights import *  # noqa: F401,F403

__all__ = [
    *operators.__all__,
    *normal_form.__all__,
    *harmonic.__all__,
    *weights.__all__,
    *representation.__all__,
    *standard_reps.__all__,
    *gelfand_tsetlin.__all__,
    *hamiltonian.__all__,
    *_evolve_module.__all__,
    *_spectrum_module.__all__,
    *coherent.__all__,
    *sectors.__all__,
    *statistics.__all__,
]


def __getattr__(name: str):
    """PEP 562: names that moved to :mod:`hyperrotor.paper.operator_products` (eqs. 144-147) keep working."""
    if name in operators._MOVED:
        return getattr(operators, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
