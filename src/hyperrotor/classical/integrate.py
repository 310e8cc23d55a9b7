"""Former home of :func:`hyperrotor.simulate` (kept as an import alias while callers move).

Everything now lives in :mod:`hyperrotor.classical.simulate` (entry point, ``Trajectory``)
and :mod:`hyperrotor.classical.solvers` (one module per method); import from there.
"""
from .simulate import SIMULATION_METHODS, Trajectory, simulate
from .solvers.splitting import casimir_shift, rotation_tables as _rotation_tables, splitting_coefficients
from .solvers.splitting import splitting_word as _splitting_word

__all__: list[str] = []  # public names come from hyperrotor.classical.simulate / .solvers
