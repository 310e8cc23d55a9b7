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

import importlib as _importlib
from typing import Any as _Any

from . import _cost_models  # noqa: F401  (registers the cost models of hyperrotor._pricing first)
from . import conventions
from .conventions import *  # noqa: F401,F403
from . import classical
from .classical import *  # noqa: F401,F403
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


def __getattr__(name: str) -> _Any:
    """PEP 562: import the heavy subpackages and names on first use (see the module docstring)."""
    if name in _LAZY_MODULES:
        return _importlib.import_module(f"{__name__}.{name}")
    if name in _LAZY_NAMES:
        module, attr = _LAZY_NAMES[name]
        value = getattr(_importlib.import_module(module), attr)
        if name != "TIME":  # TIME is a fresh lookup each time (cheap, SymPy caches symbols)
            globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *_LAZY_MODULES, *_LAZY_NAMES})
