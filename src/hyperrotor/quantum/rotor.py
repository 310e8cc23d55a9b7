"""Former home of the rotor Hamiltonian, evolution and spectra (kept so old imports keep working).

Now split by job: :mod:`.hamiltonian` (:func:`rotor_hamiltonian`,
:func:`symmetry_blocks`), :mod:`.evolve` (:func:`evolve` and its propagator
classes) and :mod:`.spectrum` (:func:`spectrum`).
"""
from .evolve import EVOLVE_METHODS, evolve  # noqa: F401
from .hamiltonian import rotor_hamiltonian, symmetry_blocks  # noqa: F401
from .spectrum import spectrum  # noqa: F401

__all__ = ["EVOLVE_METHODS", "rotor_hamiltonian", "evolve", "spectrum", "symmetry_blocks"]
