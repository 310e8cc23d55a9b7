"""hyperrotor: rigid rotation in N dimensions, classical and quantum.

Conventions (plane labels, paper vs standard matrices, Hermitian vs
anti-Hermitian generators, hbar, keyword spellings) are documented in
:mod:`hyperrotor.conventions` and ``docs/conventions.md``.

``import hyperrotor`` is light: it loads the conventions and the classical
subpackage (NumPy/SciPy) only. The heavy parts load on first use (PEP 562
module ``__getattr__``): ``hyperrotor.quantum`` (QuTiP, SymPy),
``hyperrotor.paper`` / :func:`verify_paper` (SymPy), ``hyperrotor.plotting``
(matplotlib); SymPy itself loads on the first symbolic call (e.g.
``Inertia.symbolic(5)``, ``RigidBody(...).euler_equations()``).
"""
from __future__ import annotations

from . import _cost_models  # noqa: F401  (registers the cost models of hyperrotor._pricing first)
from . import conventions
from .conventions import *  # noqa: F401,F403
from . import classical
from .classical import *  # noqa: F401,F403
from . import _lazy
from ._options import UnknownOptionError, options
from ._parse import ParseError
from ._pricing import BudgetError

__version__ = "0.1.0"

#: Subpackages/modules loaded on first attribute access (they import QuTiP, SymPy or matplotlib).
_LAZY_MODULES = ("quantum", "paper", "plotting")
#: Names served lazily: name -> (module, attribute).
_LAZY_NAMES = {
    "verify_paper": ("hyperrotor.paper", "verify_paper"),
    "plot_poincare": ("hyperrotor.plotting", "plot_poincare"),
    "TIME": ("hyperrotor.classical.rigid_body", "TIME"),
}

__all__ = [*conventions.__all__, *classical.__all__, "options", "BudgetError", "UnknownOptionError", "ParseError", "verify_paper",
           "plot_poincare",
           "quantum", "classical", "conventions", "paper"]


#: PEP 562: the heavy subpackages and names are imported on first use (see the module docstring);
#: TIME is looked up on every access (cheap, SymPy caches symbols).
__getattr__, __dir__ = _lazy.lazy_attributes(__name__, _LAZY_NAMES, modules=_LAZY_MODULES, fresh=("TIME",))
