"""Former home of the representation class and constructors (kept so old imports keep working).

The class now lives in :mod:`hyperrotor.quantum.representation`, the standard
representations in :mod:`hyperrotor.quantum.standard_reps`.
"""
from .representation import *  # noqa: F401,F403
from .representation import Representation, _as_format, _check_format, _root_coefficients  # noqa: F401
from .standard_reps import *  # noqa: F401,F403
from .standard_reps import _exact_antisymmetric, _gammas, _highest_weight_vector, _zeros_hw  # noqa: F401
from . import representation as _r, standard_reps as _s

__all__ = [*_r.__all__, *_s.__all__]
