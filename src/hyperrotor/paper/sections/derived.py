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
from hyperrotor.paper.verdicts import eq_zero

__all__: list[str] = []  # helpers shared by the section checkers (package-internal)


@lru_cache(maxsize=None)
def body5() -> RigidBody:
    return RigidBody(Inertia.symbolic(5), convention="paper")


@lru_cache(maxsize=None)
def euler_entry_forms(locked: tuple = ()) -> dict:
    """Plane -> expanded ``lhs - rhs`` of the (locked) body's Euler equations, paper matrix-entry form."""
    body = body5().lock(locked) if locked else body5()
    return {p: eq_zero(eq) for p, eq in zip(body.planes, body.euler_equations())}
