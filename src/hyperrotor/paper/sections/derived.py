"""Derived objects shared by several section checkers (cached).

The symbolic 5D body (:meth:`hyperrotor.Inertia.symbolic`) and the
``lhs - rhs`` forms of its Euler equations in the paper's matrix-entry form,
optionally with axes locked (:meth:`hyperrotor.RigidBody.lock`). They are the
reference for the Euler equations (Sec. 2.1), the reductions (Sec. 2.2-2.5) and
the linearization (Sec. 4). Both functions are cached and depend on no printed
object: :func:`hyperrotor.paper.verify.clear_cache` drops them only with
``derived=True``.
"""
from __future__ import annotations

from functools import lru_cache

from hyperrotor.classical.inertia import Inertia
from hyperrotor.classical.rigid_body import RigidBody
from hyperrotor.paper.verdicts import _eq_zero


@lru_cache(maxsize=None)
def _body5() -> RigidBody:
    return RigidBody(Inertia.symbolic(5), "paper")


@lru_cache(maxsize=None)
def _euler_entry_forms(locked: tuple = ()) -> dict:
    """Plane -> expanded ``lhs - rhs`` of the (locked) body's Euler equations, paper matrix-entry form."""
    body = _body5().lock(locked) if locked else _body5()
    return {p: _eq_zero(eq) for p, eq in zip(body.planes, body.euler_equations())}
