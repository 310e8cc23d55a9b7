"""Quantum so(N) angular momentum: SymPy operators, matrix representations, QuTiP rotors.

Layers: ``differential_operator``/``operators``/``normal_form``/``harmonic`` (symbolic, eq. 142) and
``weights``/``representation``/``standard_reps``/``gelfand_tsetlin`` (matrices)
sit below ``hamiltonian`` (the rotor Hamiltonian), ``evolve`` (propagators),
``spectrum`` and ``coherent`` (coherent states); the classical subpackage never
imports this one. The vocabulary (``form=``, keyword-only ``hbar``, ``t``,
``rtol``/``atol``, ``rng``) is documented in docs/conventions.md.
"""
from . import (coherent, combine, differential_operator, equivalence, evolve as _evolve_module, gelfand_tsetlin,
               hamiltonian, harmonic, normal_form, operator_input, operator_products, operators, representation,
               sector_propagator, sectors, spectrum as _spectrum_module, standard_reps, statistics, weights)
from .coherent import *  # noqa: F401,F403
from .combine import *  # noqa: F401,F403
from .differential_operator import *  # noqa: F401,F403
from .correspondence import *  # noqa: F401,F403
from .equivalence import *  # noqa: F401,F403
from .evolve import *  # noqa: F401,F403
from .gelfand_tsetlin import *  # noqa: F401,F403
from .hamiltonian import *  # noqa: F401,F403
from .harmonic import *  # noqa: F401,F403
from .normal_form import *  # noqa: F401,F403
from .operator_input import *  # noqa: F401,F403
from .operator_products import *  # noqa: F401,F403
from .operators import *  # noqa: F401,F403
from .propagators import *  # noqa: F401,F403
from .representation import *  # noqa: F401,F403
from .sector_propagator import *  # noqa: F401,F403
from .sectors import *  # noqa: F401,F403
from .spectrum import *  # noqa: F401,F403
from .standard_reps import *  # noqa: F401,F403
from .statistics import *  # noqa: F401,F403
from .weights import *  # noqa: F401,F403

__all__ = [
    *differential_operator.__all__,
    *operators.__all__,
    *operator_products.__all__,
    *normal_form.__all__,
    *harmonic.__all__,
    *weights.__all__,
    *representation.__all__,
    *operator_input.__all__,
    *standard_reps.__all__,
    *combine.__all__,
    *equivalence.__all__,
    *gelfand_tsetlin.__all__,
    *hamiltonian.__all__,
    *propagators.__all__,
    *sector_propagator.__all__,
    *_evolve_module.__all__,
    *_spectrum_module.__all__,
    *coherent.__all__,
    *correspondence.__all__,
    *sectors.__all__,
    *statistics.__all__,
]

