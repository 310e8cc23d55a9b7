"""Quantum so(N) angular momentum: SymPy operators, matrix representations, QuTiP rotors.

Layers: ``operators``/``normal_form``/``harmonic`` (symbolic) and ``weights``/
``representations``/``gelfand_tsetlin`` (matrices) sit below ``rotor`` (QuTiP
Hamiltonians and evolution) and ``coherent`` (coherent states); the classical subpackage never imports this one.
"""
from . import coherent, gelfand_tsetlin, harmonic, normal_form, operators, representations, rotor, weights
from .coherent import *  # noqa: F401,F403
from .gelfand_tsetlin import *  # noqa: F401,F403
from .harmonic import *  # noqa: F401,F403
from .normal_form import *  # noqa: F401,F403
from .operators import *  # noqa: F401,F403
from .representations import *  # noqa: F401,F403
from .rotor import *  # noqa: F401,F403
from .weights import *  # noqa: F401,F403

__all__ = [
    *operators.__all__,
    *normal_form.__all__,
    *harmonic.__all__,
    *weights.__all__,
    *representations.__all__,
    *gelfand_tsetlin.__all__,
    *rotor.__all__,
    *coherent.__all__,
]
