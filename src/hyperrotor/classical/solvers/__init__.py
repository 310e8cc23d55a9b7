"""The integrators of :func:`hyperrotor.simulate`: one class per method, one registry table.

:data:`SOLVERS` maps each method name to its :class:`Solver` class; ``simulate(method=...)``
takes a name (matched ignoring case) or a solver object (``Splitting8(compensated=True)``),
and the docs and tests loop over this table. Each class states its ``order``, what it
``preserves``, whether it is ``adaptive``, which torques it integrates and its options.

=================== ===== ========== ====================================================
name                order adaptive   preserves (to round-off)
=================== ===== ========== ====================================================
``splitting2..8``   2..8  no         Casimirs, orthogonality; symplectic, reversible
``moser-veselov``   2     no         Casimirs, energy, orthogonality; symplectic, reversible
``DOP853``, ...     5-8   yes        nothing exactly (scipy ``solve_ivp``)
=================== ===== ========== ====================================================
"""
from __future__ import annotations

from typing import Any

from hyperrotor import _validate

from .base import Problem, Solver
from .driver import FixedStepSolver
from .moser_veselov import MoserVeselov
from .scipy_ivp import BDF, DOP853, LSODA, RK23, RK45, Radau, ScipyIVP
from .splitting import (Splitting, Splitting2, Splitting4, Splitting6, Splitting8, Splitting10, casimir_shift,
                        splitting_coefficients)
from .step_control import AccuracyWarning, ErrorTarget, FixedStep, StepBudgetError, UnreachableAccuracyError

__all__ = ["SOLVERS", "solver_for", "Solver", "FixedStepSolver", "ScipyIVP", "Splitting", "Splitting2", "Splitting4",
           "Splitting6", "Splitting8", "Splitting10", "MoserVeselov", "DOP853", "RK45", "RK23", "LSODA", "Radau", "BDF",
           "StepBudgetError", "UnreachableAccuracyError", "AccuracyWarning", "casimir_shift", "splitting_coefficients",
           "Problem",
           "FixedStep", "ErrorTarget"]

#: The registry: method name -> Solver class (the one list of methods; docs and tests loop over it).
SOLVERS: dict[str, type[Solver]] = {
    cls.name: cls
    for cls in (Splitting2, Splitting4, Splitting6, Splitting8, Splitting10, MoserVeselov, DOP853, RK45, RK23, LSODA,
                Radau, BDF)
}


def solver_for(method: Any, **options: Any) -> Solver:
    """A solver object from a registry name (case-insensitive) with ``options``, or ``method`` itself
    when it already is a :class:`Solver` (then without ``options``)."""
    if isinstance(method, Solver):
        if options:
            raise TypeError(f"options {', '.join(sorted(options))} go to the solver's constructor when method is a "
                            f"solver object ({method!r})")
        return method
    if isinstance(method, type) and issubclass(method, Solver):
        if method.run is Solver.run or not method.name:  # (the base classes: Solver, FixedStepSolver, Splitting)
            raise TypeError(f"method {method.__name__} is an abstract base class, not a method; use one of "
                            f"{', '.join(map(repr, SOLVERS))} or a subclass that implements it")
        return method(**options)
    name = _validate.choice("method", method, tuple(SOLVERS))
    return SOLVERS[name](**options)
