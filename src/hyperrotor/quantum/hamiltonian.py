r"""The quantum rigid-rotor Hamiltonian and its invariant blocks.

The quantum rigid rotor in a representation :math:`\rho` of so(N) has the
Hamiltonian (the quantized kinetic energy, cf. eqs. 6 and 141)

.. math:: \hat H = \sum_{i<j} \frac{(\hat L^{ij})^2}{2 I_{ij}},
          \qquad \hat L^{ij} = -i\hbar\,\rho(E_{ij}) = -i\hbar X_{(ij)},

with the physical plane moments :math:`I_{ij} = m_i + m_j` of
:class:`hyperrotor.Inertia` (same plane order as :func:`hyperrotor.planes`).
Because the generators :math:`X_{(ij)}` are real antisymmetric in the
real representations, :math:`\hat H = -\hbar^2\sum_a X_a^2/(2I_a)` is a
real symmetric matrix, which the native propagators of :mod:`.evolve` exploit.

Frames and signs (the quantum/classical correspondence)
-------------------------------------------------------
For a representation (:math:`[X_a, X_b] = \sum_c C_{ab}^{\;c} X_c` with the
structure constants of :func:`hyperrotor.structure_constants`) the Hermitian
generators obey

.. math:: [\hat L_a, \hat L_b] = -i\hbar \sum_c C_{ab}^{\;c}\,\hat L_c ,

the *space-frame* (normal) sign: in 3D, with :math:`\hat J_1 = \hat L^{23}`,
:math:`\hat J_2 = -\hat L^{13}`, :math:`\hat J_3 = \hat L^{12}`, this is
:math:`[\hat J_1, \hat J_2] = i\hbar \hat J_3`. The classical Euler equations
(:math:`\dot L = [\Omega, L]`, eq. 24) live in the *body* frame, whose
Lie-Poisson bracket is :math:`\{L_a, L_b\} = +\sum_c C_{ab}^{\;c} L_c`
(:func:`hyperrotor.lie_poisson_bracket`). Dirac's rule
:math:`[\cdot,\cdot] \leftrightarrow i\hbar\{\cdot,\cdot\}` therefore matches the
classical body-frame components with the *body-frame operators*

.. math:: \hat L^{\rm body}_a = -\hat L_a = i\hbar\,X_a,
          \qquad [\hat L^{\rm body}_a, \hat L^{\rm body}_b]
          = +i\hbar\sum_c C_{ab}^{\;c}\,\hat L^{\rm body}_c ,

(the "anomalous" sign of body-frame angular momentum). The Hamiltonian is the
same for both (it is quadratic), and the Heisenberg equations give exactly the
symmetrized Euler equations, forward in time,

.. math:: \frac{d}{dt}\hat L^{\rm body}_a = \sum_{b,c} C_{bc}^{\;a}\,
          \tfrac12\big(\hat\omega_b \hat L^{\rm body}_c
          + \hat L^{\rm body}_c\hat\omega_b\big),
          \qquad \hat\omega_b = \hat L^{\rm body}_b / I_b .

So the classical solution :math:`L(t)` corresponds to
:math:`\langle\hat L^{\rm body}\rangle(t) = -\langle\hat L\rangle(t)`; the
expectation values of the representation's Hermitian generators themselves
follow the *time-reversed* Euler flow. ``tests/quantum/test_correspondence.py``
checks both statements.

Symmetry blocks
---------------
When :math:`\hat H` commutes with a Casimir of a subalgebra that the basis
diagonalizes, its matrix is block diagonal in that basis: equal moments make
:math:`\hat H = C_2(\mathrm{so}(N))/(2I)` diagonal in any basis of an irrep; the
quartet inertia of eqs. (84)-(85) (distinguished axis 5) gives
:math:`\hat H = C_2(\mathrm{so}(5))/(2(1+\kappa^2)) + C_2(\mathrm{so}(4))\,(1/4 - 1/(2(1+\kappa^2)))`,
diagonal in the Gelfand-Tsetlin basis of so(5) ⊃ so(4). :func:`symmetry_blocks`
finds the blocks as the connected components of the sparsity graph.
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import scipy.sparse as sps
from scipy.sparse.csgraph import connected_components

from .. import _lazy, _validate
from .._options import options
from .operator_input import as_csr, check_antihermitian, operator_mapping
from .representation import Representation

__all__ = ["rotor_hamiltonian", "symmetry_blocks"]


def operator_matrix_and_dims(H: Any, name: str = "H") -> tuple[sps.csr_matrix, list]:
    """``(csr, dims)`` of a square operator given as Qobj, sparse or dense matrix (see :func:`.representation.as_csr`)."""
    mat = as_csr(H, name)
    dims = H.dims if hasattr(H, "dims") and hasattr(H, "isoper") else [[mat.shape[0]], [mat.shape[1]]]
    return mat, dims


def representation_of(H: Any) -> "Representation | None":
    """The :class:`.Representation` that :func:`rotor_hamiltonian` built ``H`` from, or ``None``.

    Only an ``H`` returned by :func:`rotor_hamiltonian` carries it (arithmetic on the Qobj gives a
    new Qobj without it): the symmetry sectors of :func:`.spectrum` and :func:`.evolve` use it, and
    :func:`hermitian_matrix` trusts such an ``H`` to be Hermitian (built from checked generators).
    """
    return getattr(H, "_hyperrotor_rep", None)


def hermitian_matrix(H: Any, name: str = "H") -> tuple[sps.csr_matrix, list]:
    """``(csr, dims)`` of a Hermitian operator; refuses a non-Hermitian one (``options["quantum_hermiticity_rtol"]``)."""
    trusted = representation_of(H) is not None  # rotor_hamiltonian's own H: Hermitian by construction
    mat, dims = operator_matrix_and_dims(H, name)
    if mat.shape[0] == 0:  # (spectrum failed on max() of no blocks)
        raise ValueError(f"{name} must be an operator of dimension >= 1, got a 0 x 0 matrix")
    if trusted:
        return mat, dims
    rtol = options["quantum_hermiticity_rtol"]
    diff = (mat - mat.conj().T).tocsr()
    scale = max(1.0, float(np.max(np.abs(mat.data))) if mat.nnz else 1.0)
    if diff.nnz and float(np.max(np.abs(diff.data))) > rtol * scale:
        raise ValueError(
            f"{name} must be Hermitian: max |{name} - {name}^dagger| = {float(np.max(np.abs(diff.data))):.3g} "
            f"(relative tolerance options['quantum_hermiticity_rtol'] = {rtol:.3g} of max |{name}| = {scale:.3g})"
        )
    return mat, dims


# ----------------------------------------------------------------------------
# Hamiltonian
# ----------------------------------------------------------------------------
def rotor_hamiltonian(rep: Any, body: Any, *, hbar: float = 1, form: str = "antihermitian"):
    r"""Rigid-rotor Hamiltonian :math:`\hat H = \sum_{i<j} (\hat L^{ij})^2/(2I_{ij})`.

    Parameters
    ----------
    rep : Representation or mapping plane -> operator
        A :class:`~hyperrotor.quantum.Representation`, or ``{(i, j): operator}``
        for every plane of so(N) with operators given as ``qutip.Qobj``,
        scipy.sparse matrices or 2-D arrays, in the form named by ``form``
        (e.g. ``rep.to_qobj(form="antihermitian")`` or
        :func:`~hyperrotor.quantum.jmat_generators`).
    body : Inertia, RigidBody, mapping plane -> moment, or sequence
        The physical plane moments :math:`I_{ij}`: an :class:`hyperrotor.Inertia`,
        a body, ``{(i, j): I_ij}`` naming every plane once, or ``N(N-1)/2``
        finite positive real numbers in plane order.
    hbar : float, keyword-only, default 1
        :math:`\hat L^{ij} = -i\hbar X_{(ij)}` (eq. 141), so energies scale as :math:`\hbar^2`.
    form : {"antihermitian", "hermitian"}, keyword-only, default "antihermitian"
        What mapping operators are: :math:`X_{(ij)}` (anti-Hermitian) or
        :math:`L^{ij} = -i\hbar X_{(ij)}` (Hermitian). Checked always, used only for a mapping
        (a Representation holds its generators in its own form).
        A Hermitian mapping declared anti-Hermitian is refused (it would give
        :math:`-\hat H`).

    Returns
    -------
    qutip.Qobj
        Hermitian operator (real symmetric matrix for real generators),
        ``dims = [[dim], [dim]]``.

    Raises
    ------
    TypeError
        ``hbar`` given positionally (it is keyword-only), a symbolic body.
    ValueError
        Inertia of another N, a non-positive moment, ``hbar <= 0``, generators
        that are not anti-Hermitian in the declared form.

    Notes
    -----
    :math:`\hat H = -\hbar^2 \sum_a X_a^2/(2 I_a)`. For equal moments it is
    :math:`C_2/(2I)` with the so(N) Casimir :math:`C_2 = \sum_a \hat L_a^2`
    (eq. 38's quadratic invariant, quantized).
    """
    hbar = _validate.hbar(hbar)
    form = _validate.form(form)  # on every route, also where it is not used (a Representation)
    if isinstance(rep, Representation):
        N, dim = rep.N, rep.dim
        gens = rep.generators(format="csr")
        # checked once here (a Representation takes any square matrices): the H built below is then
        # Hermitian by construction, and evolve/spectrum skip their O(nnz) check of it
        check_antihermitian(gens)
    elif hasattr(rep, "generators") and hasattr(rep, "N"):  # a Representation-like object
        N, dim = int(rep.N), int(rep.dim)
        gens = rep.generators()
    elif isinstance(rep, Mapping):
        N, gens = operator_mapping(rep, "rep")
        if form == "hermitian":
            gens = {p: (1j / hbar) * M for p, M in gens.items()}
        check_antihermitian(gens, form=form)
        dim = Representation(N, gens).dim
    else:
        raise TypeError(
            "rep must be a Representation or a mapping plane -> operator (qutip.Qobj, scipy.sparse, array), "
            f"got {type(rep).__name__}"
        )
    moments = _validate.moments(body, N, name="body")  # refuses complex moments too
    H = rotor_matrix(gens, moments, hbar)
    Hq = _lazy.qutip.Qobj(H, dims=[[dim], [dim]], isherm=True)  # sum of squares of Hermitian L^ij / hbar
    if isinstance(rep, Representation):
        Hq._hyperrotor_rep = rep  # read by representation_of only
    return Hq


def rotor_matrix(gens: Mapping, moments: np.ndarray, hbar: float) -> sps.csr_matrix:
    r""":math:`-\hbar^2 \sum_a X_a^2/(2 I_a)` as CSR: the matrix of :func:`rotor_hamiltonian`, without the Qobj.

    Trusted core (package-internal): ``gens`` are the CSR generators of a checked
    representation keyed by plane, ``moments`` the checked moments in
    :func:`hyperrotor.planes` order, ``hbar`` a checked float. Refuses an overflow and an underflow of
    :math:`\hbar^2/(2I_a)` below the normal floats (``ValueError``); a complex result is made exactly Hermitian.
    """
    dim = next(iter(gens.values())).shape[0]
    with np.errstate(under="ignore", over="ignore"):
        smallest = float(np.min(hbar * hbar / (2.0 * np.asarray(moments, dtype=float)), initial=np.inf))
    if smallest < np.finfo(float).tiny:  # (subnormal or zero: digits lost, or a Hamiltonian of zeros)
        raise ValueError(
            f"the Hamiltonian underflows the float range: hbar = {_validate.fmt(hbar)} and moments up to "
            f"{_validate.fmt(float(np.max(moments)))} give hbar^2 / (2 I) = {smallest:.3g}, below 2.2e-308; choose "
            f"units with hbar^2 / I of order one"
        )
    H = sps.csr_matrix((dim, dim), dtype=float)
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is refused just below, with its cause
        for p, m in zip(sorted(gens), moments):  # sorted planes (i, j) are the order of hyperrotor.planes
            G = sps.csr_matrix(gens[p])
            H = H + (G @ G) * (-(hbar * hbar) / (2.0 * m))
    H = sps.csr_matrix(H)
    if H.nnz and not np.all(np.isfinite(H.data)):
        raise ValueError(
            f"the Hamiltonian overflows the float range: hbar = {_validate.fmt(hbar)} and moments down to "
            f"{_validate.fmt(float(np.min(moments)))} give hbar^2 X^2 / (2 I) beyond 1.8e308; choose units with "
            f"hbar^2 / I of order one"
        )
    if H.dtype.kind == "c":
        # exactly Hermitian: (H + H^dagger)/2 changes H by its round-off only (same argument as
        # equivalence.exact_antisymmetric); a real H of real generators is already exactly symmetric
        H = 0.5 * (H + H.conj().T)
        if not np.any(H.data.imag):
            H = sps.csr_matrix(H.real)
    H = sps.csr_matrix(H)
    H.sum_duplicates()
    H.eliminate_zeros()
    return H


# ----------------------------------------------------------------------------
# symmetry blocks
# ----------------------------------------------------------------------------
def symmetry_blocks(H: Any, *, rtol: float | None = None, atol: float | None = None) -> list[np.ndarray]:
    r"""Invariant blocks of ``H``: connected components of its sparsity graph.

    Parameters
    ----------
    H : qutip.Qobj, scipy.sparse matrix or ndarray
        Square operator.
    rtol, atol : float, optional, keyword-only
        Entries with :math:`|H_{kl}| \le` ``atol`` (absolute), or else
        ``rtol * max|H|`` (default ``options["quantum_block_rtol"]`` = 1e-14,
        which removes round-off couplings such as those of :math:`C_2/(2I)` in a
        non-diagonal basis), are treated as zero.

    Returns
    -------
    list of ndarray
        Sorted index arrays, one per block, ordered by their smallest index;
        together a partition of ``range(dim)``.

    Notes
    -----
    In a basis that diagonalizes a Casimir commuting with ``H`` (e.g. the
    Gelfand-Tsetlin basis and the so(4) Casimir for the quartet inertia of
    eqs. 84-85) every block lies inside one Casimir eigenspace. The blocks also
    pick up discrete symmetries that happen to be diagonal in the basis.
    """
    mat, _ = operator_matrix_and_dims(H)
    return blocks_of(mat, rtol=rtol, atol=atol)


def blocks_of(mat: sps.csr_matrix, *, rtol: float | None = None, atol: float | None = None) -> list[np.ndarray]:
    """The blocks of :func:`symmetry_blocks` for a CSR matrix."""
    n = mat.shape[0]
    if mat.nnz == 0:
        return [np.array([k]) for k in range(n)]
    if atol is not None:
        thr = _validate.positive("atol", atol, allow_zero=True)
    else:
        r = options["quantum_block_rtol"] if rtol is None else _validate.positive("rtol", rtol, allow_zero=True)
        thr = r * float(np.max(np.abs(mat.data)))
    a = mat.copy()
    a.data = (np.abs(a.data) > thr).astype(np.int8)
    a.eliminate_zeros()
    ncomp, labels = connected_components(a, directed=False)
    order = np.argsort(labels, kind="stable")
    counts = np.bincount(labels, minlength=ncomp)
    parts = np.split(order, np.cumsum(counts)[:-1])
    parts.sort(key=lambda p: p[0])
    return parts
