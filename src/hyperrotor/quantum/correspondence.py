r"""Quantum-classical correspondence in time: out-of-time-order correlators and the Ehrenfest time.

:func:`otoc`
    :math:`C(t) = \langle [\hat W(t), \hat V]^\dagger [\hat W(t), \hat V] \rangle` with
    :math:`\hat W(t) = e^{i\hat H t/\hbar}\hat W e^{-i\hat H t/\hbar}`, for a ket, a
    density matrix, or at infinite temperature (:math:`\mathrm{Tr}(\cdot)/d`). Computed
    column by column, :math:`C = \sum_j \| [\hat W(t), \hat V]\, x_j \|^2`, with the
    propagator of :class:`~hyperrotor.quantum.SectorPropagator` in the eigenbases of
    the invariant blocks (symmetry sectors for a generic rotor): no dense
    :math:`d \times d` propagator or Heisenberg operator is formed, and each column
    costs four block-diagonal propagations per time, :math:`O(\sum_s n_s^2)` each.
:func:`ehrenfest_time`
    The time at which the body-frame angular momentum of a spin-coherent state,
    :math:`\langle\hat L^b\rangle(t)`, leaves the classical trajectory of the same
    start by a relative ``threshold``, for a family of irreps :math:`l\,w` whose
    effective Planck constant :math:`\hbar_{\rm eff} = |L_0|/(l |w|)` goes to zero as
    :math:`l \to \infty` (conventions: :mod:`hyperrotor.quantum.coherent`, tests in
    ``tests/quantum/test_correspondence.py``).
"""
from __future__ import annotations

from fractions import Fraction
from typing import Any, NamedTuple

import numpy as np

from .. import _pricing, _validate
from .._equality import fields_equal, fields_unequal
from .._floats import power_of_two_scale
from .._options import options
from .._parallel import interruptible, progress_bar
from ..classical.simulate import simulate
from ..conventions import n_planes, planes
from .coherent import coherent_state
from .sector_propagator import SectorPropagator, unit_state, warn_phase_rounding
from .gelfand_tsetlin import DEFAULT_MAX_DIM, gt_size, irrep
from .weights import _to_fraction
from .hamiltonian import operator_matrix_and_dims, rotor_hamiltonian
from .propagators import PROPAGATORS

__all__ = ["EhrenfestResult", "OTOCResult", "ehrenfest_time", "otoc"]

options.register(
    "quantum_ehrenfest_rtol", 1e-10,
    "hyperrotor.quantum.ehrenfest_time: relative tolerance of the classical run (hyperrotor.simulate) that the "
    "quantum curves are compared with; its error must stay far below the threshold of the relative deviation "
    "(0.1 by default).",
)

#: columns propagated together (memory: 4 x dim x this many complex numbers)
_COLUMNS = 64


class OTOCResult(NamedTuple):
    """What :func:`otoc` returns.

    Attributes
    ----------
    t : ndarray
        The times.
    values : ndarray
        :math:`C(t)` at each time (real, >= 0).
    stderr : ndarray or None
        Standard error of the stochastic trace estimate at each time (``None`` when exact).
    samples : int or None
        Number of random states of the estimate (``None``: exact).
    """

    __eq__, __ne__ = fields_equal, fields_unequal  # (field by field: a tuple's == refuses array fields)
    __hash__ = None

    t: np.ndarray
    values: np.ndarray
    stderr: np.ndarray | None
    samples: int | None


class EhrenfestResult(NamedTuple):
    r"""What :func:`ehrenfest_time` returns (one row per irrep of the family).

    Attributes
    ----------
    ls : ndarray
        The scale factors :math:`l` (irrep :math:`l\,w`).
    hbar : ndarray
        The effective Planck constants :math:`|L_0|/(l|w|)`.
    dims : ndarray
        The dimensions of the irreps.
    t_E : ndarray
        The Ehrenfest times: the first time at which ``deviation`` reaches
        ``threshold`` (linear interpolation between output times); NaN when it stays
        below within ``t``.
    t : ndarray
        The output times.
    deviation : ndarray, shape ``(len(ls), len(t))``
        :math:`|\langle\hat L^b\rangle(t) - L(t)| / |L_0|` (2-norms over the planes).
    quantum : ndarray, shape ``(len(ls), len(t), N(N-1)/2)``
        :math:`\langle\hat L^b\rangle(t)`, plane order.
    classical : ndarray, shape ``(len(t), N(N-1)/2)``
        The classical :math:`L(t)` (:func:`hyperrotor.simulate`).
    threshold : float
    """

    __eq__, __ne__ = fields_equal, fields_unequal  # (field by field: a tuple's == refuses array fields)
    __hash__ = None

    ls: np.ndarray
    hbar: np.ndarray
    dims: np.ndarray
    t_E: np.ndarray
    t: np.ndarray
    deviation: np.ndarray
    quantum: np.ndarray
    classical: np.ndarray
    threshold: float


def _operator(name: str, op: Any, dim: int):
    mat, _ = operator_matrix_and_dims(op, name)
    if mat.shape != (dim, dim):
        raise ValueError(f"{name} has shape {mat.shape} but H has dimension {dim}")
    return mat.tocsr()


def _density_columns(state: Any, dim: int) -> np.ndarray:
    """Columns X with X X^dagger = rho / tr(rho) for a density matrix (Qobj oper or 2-D array)."""
    rho = state.full() if hasattr(state, "full") else np.asarray(state)
    rho = _validate.finite_array("state", rho, dtype=complex)
    if rho.shape != (dim, dim):
        raise ValueError(f"state must be a ket of length {dim} or a {dim} x {dim} density matrix, got shape {rho.shape}")
    scale = float(np.abs(rho).max())
    if scale == 0.0 or np.abs(rho - rho.conj().T).max() > 1e-12 * scale:
        raise ValueError("a density matrix must be Hermitian and non-zero")
    _pricing.check("dense_diagonalization", dim=dim, complex=True)  # (its eigh: n = 1500 ran 17 s unpriced)
    p, vecs = interruptible(np.linalg.eigh, rho / scale)  # (Ctrl-C: _parallel.interruptible)
    if p.min() < -1e-12 * p.max():
        raise ValueError(f"a density matrix must be positive semi-definite, got an eigenvalue {p.min() * scale:.3g}")
    keep = p > 1e-15 * p.max()
    p = p[keep] / p[keep].sum()
    return vecs[:, keep] * np.sqrt(p)


def _commutator_norms(U: SectorPropagator, W, V, X: np.ndarray, t: np.ndarray) -> np.ndarray:
    r""":math:`\|[\hat W(t), \hat V] x_j\|^2` for every column ``x_j`` of ``X`` and time of ``t``: ``(len(t), k)``."""
    out = np.empty((t.size, X.shape[1]))
    VX = V @ X
    for k, tk in enumerate(t):
        WtVX = U._apply(W @ U._apply(VX, tk), -tk)  # W(t) V X (phases checked at otoc's door)
        VWtX = V @ U._apply(W @ U._apply(X, tk), -tk)  # V W(t) X
        D = WtVX - VWtX
        out[k] = np.einsum("ij,ij->j", D.conj(), D).real
    return out


def otoc(H: Any, W: Any, V: Any, t: Any, *, state: Any = None, samples: int | None = None, rng: Any = 0,
         hbar: float = 1, rep: Any = None) -> OTOCResult:
    r"""The out-of-time-order correlator :math:`C(t) = \langle [\hat W(t), \hat V]^\dagger [\hat W(t), \hat V]\rangle`.

    With :math:`\hat W(t) = e^{i\hat H t/\hbar}\,\hat W\,e^{-i\hat H t/\hbar}` (module docstring).

    Parameters
    ----------
    H : qutip.Qobj, scipy.sparse matrix or ndarray
        Hermitian Hamiltonian (a :func:`rotor_hamiltonian` carries its representation,
        whose symmetry sectors are then the blocks).
    W, V : qutip.Qobj, scipy.sparse matrix or ndarray
        Operators of the dimension of ``H`` (any; Hermitian is not required).
    t : sequence of float
        A non-empty 1-D array of times (any order, any sign; ``W(t)`` is evaluated at each).
    state : ket, density matrix or None, keyword-only
        ``None``: infinite temperature, :math:`\mathrm{Tr}(\cdot)/d`. A ket (normalized
        here) or a density matrix (Hermitian, positive; divided by its trace).
    samples : int or None, keyword-only
        Infinite temperature only. ``None``: the exact trace, a sum over the ``d``
        vectors of an orthonormal basis (cost ``d`` columns). An integer ``R``: the
        stochastic estimate :math:`\frac1R\sum_r \langle r|\cdot|r\rangle` over Haar-random
        unit vectors :math:`r`, unbiased, with ``stderr`` the standard error of the mean
        of the ``R`` values (for Haar vectors the variance of one value is
        :math:`(\mathrm{Tr}A^2/d - (\mathrm{Tr}A/d)^2)/(d+1)`: the relative error falls
        like :math:`1/\sqrt{dR}`).
    rng : int, numpy.random.Generator or None, keyword-only, default 0
        The random states of the estimate (a fixed seed by default: reproducible).
    hbar : float, keyword-only, default 1
    rep : Representation, keyword-only, optional
        The representation of ``H`` for the sectors (default: recorded on ``H``).

    Returns
    -------
    OTOCResult
        ``(t, values, stderr, samples)``.

    Notes
    -----
    Every block of ``H`` is diagonalized once (dense ``eigh`` per sector); then
    :math:`e^{\mp i\hat H t/\hbar}` acts on many columns at once at the cost of
    block-diagonal products, four propagations per column and time. The work does not
    grow with :math:`|t|`: it is priced (``hr.options["max_seconds"]``, and the largest
    block as a dense diagonalization) by the columns, the times and the blocks' sizes,
    before any of it.
    """
    _validate.numeric_input("t", t)
    t = _validate.finite_array("t", t)
    if t.ndim != 1 or t.size == 0:
        raise ValueError(f"t must be a non-empty 1-D array of times, got shape {t.shape}")
    if state is not None and samples is not None:
        raise ValueError("samples applies to the infinite-temperature trace (state=None) only")
    samples = None if samples is None else _validate.integer("samples", samples, minimum=2)
    gen = _validate.rng(rng)  # checked on every route (only the stochastic trace uses it)
    U = SectorPropagator(H, rep=rep, hbar=hbar)
    dim = U.dim
    Wm, Vm = _operator("W", W, dim), _operator("V", V, dim)
    sizes = np.array(U.apply_blocks(), dtype=float)
    cplx = U.matrix.dtype.kind == "c"
    if sizes.size:
        _pricing.check("dense_diagonalization", dim=int(sizes.max()), complex=cplx)
    price = {"dim": dim, "squares": float(np.sum(sizes**2)), "cubes": float(np.sum(sizes**3)), "complex": cplx}
    warn_phase_rounding("otoc", U.spectral_bound, float(np.max(np.abs(t))), U.hbar)
    stderr = None
    if state is not None:
        is_ket = (hasattr(state, "isket") and state.isket) or np.ndim(state) == 1 or np.shape(state)[1:] == (1,)
        X = unit_state(state, dim, "state")[:, None] if is_ket else _density_columns(state, dim)
        _pricing.check("otoc", n_times=t.size, columns=X.shape[1], **price)
        values = _commutator_norms(U, Wm, Vm, X, t).sum(axis=1)
    elif samples is None:
        _pricing.check("otoc", n_times=t.size, columns=dim, **price)
        values = np.zeros(t.size)
        eye = np.eye(dim)
        for start in range(0, dim, _COLUMNS):
            values += _commutator_norms(U, Wm, Vm, eye[:, start : start + _COLUMNS], t).sum(axis=1)
        values /= dim
    else:
        _pricing.check("otoc", n_times=t.size, columns=samples, **price)
        parts = []
        for start in range(0, samples, _COLUMNS):
            k = min(_COLUMNS, samples - start)
            X = gen.standard_normal((dim, k)) + 1j * gen.standard_normal((dim, k))
            X /= np.linalg.norm(X, axis=0)
            parts.append(_commutator_norms(U, Wm, Vm, X, t))
        each = np.concatenate(parts, axis=1)
        values = each.mean(axis=1)
        stderr = each.std(axis=1, ddof=1) / np.sqrt(samples)
    return OTOCResult(t, values, stderr, samples)


def _highest_weight_entry(x: float) -> Fraction:
    """``l * w`` of a float weight entry as an integer or half-integer (a highest-weight entry), or ValueError."""
    if not np.isfinite(x):
        raise ValueError(f"l * weight must be integers or half-integers (a highest weight), got the entry {x!r} "
                         f"(beyond double precision: a smaller weight or l)")
    f = Fraction(float(x)).limit_denominator(2)
    if abs(float(f) - x) > 1e-12 * max(1.0, abs(x)):
        raise ValueError(f"l * weight must be integers or half-integers (a highest weight), got the entry {x!r}")
    return f


def _first_crossing(t: np.ndarray, dev: np.ndarray, threshold: float) -> float:
    above = np.nonzero(dev >= threshold)[0]
    if above.size == 0:
        return float("nan")
    k = int(above[0])
    if k == 0:
        return float(t[0])
    d0, d1 = dev[k - 1], dev[k]
    return float(t[k - 1] + (threshold - d0) / (d1 - d0) * (t[k] - t[k - 1]))


def ehrenfest_time(body: Any, L0: Any, ls: Any, t: Any, *, weight: Any = None, threshold: float = 0.1,
                   rtol: float | None = None, method: str = "auto", progress: bool | None = None) -> EhrenfestResult:
    r"""Ehrenfest times of a rotor: when a coherent state's :math:`\langle\hat L^b\rangle(t)` leaves the classical :math:`L(t)`.

    For each :math:`l` of ``ls`` the irrep of highest weight :math:`l\,w` is built
    (:func:`~hyperrotor.quantum.irrep`), with :math:`\hbar = |L_0| / (l\,|w|)` so that
    the spin-coherent state along ``L0`` (:func:`coherent_state`, ``frame="body"``)
    has :math:`\langle\hat L^b\rangle(0) = L_0` exactly: :math:`l \to \infty` is the
    classical limit :math:`\hbar_{\rm eff} \to 0` at fixed :math:`L_0`. The state is
    evolved under :func:`rotor_hamiltonian` ``(rep, body, hbar=hbar)``
    (:class:`SectorPropagator`), the classical body from the same :math:`L_0` by
    :func:`hyperrotor.simulate` (``omega0`` = :math:`L_0 / I` per plane), and
    :math:`t_E` is the first time at which
    :math:`|\langle\hat L^b\rangle(t) - L(t)| / |L_0| \ge` ``threshold``.

    Parameters
    ----------
    body : RigidBody, Inertia, mapping plane -> moment, or sequence
        The moments (anything :func:`hyperrotor.simulate` accepts).
    L0 : array_like, shape ``(N(N-1)/2,)``
        Initial angular momentum, plane components; the body-frame coherent state points along :math:`-L_0`
        (``coherent_state(frame="body")``), so the normal form of :math:`-L_0` must be proportional to
        ``weight`` (e.g. a simple bivector for :math:`(1, 0, \dots)`). It is that of :math:`L_0` except in
        so(4k + 2), where the sign of its last entry flips (``(2, 1, 1)`` for :math:`L_0` is ``(2, 1, -1)``).
    ls : sequence of int
        Scale factors :math:`l \ge 1` of the irreps :math:`l\,w`.
    t : sequence of float
        Strictly increasing output times from the start, ``t[0]`` the time of ``L0``.
    weight : sequence, keyword-only, default ``(1, 0, ..., 0)``
        The direction :math:`w` of the highest weights :math:`l\,w` (each an integer or a half-integer):
        ``int``, ``Fraction`` or ``sympy.Rational`` entries exactly (a representation's ``highest_weight`` as it
        is), ``float`` entries to 1e-12 (``0.25`` with ``l = 4``).
    threshold : float, keyword-only, default 0.1
        Relative deviation that defines :math:`t_E`.
    rtol : float, keyword-only, optional
        Tolerance of the classical run (default ``hr.options["quantum_ehrenfest_rtol"]`` = 1e-10).
    method : str, keyword-only, default "auto"
        The :func:`evolve` method.
    progress : bool or None, keyword-only
        A bar over the irreps.

    Returns
    -------
    EhrenfestResult
        ``t_E`` per irrep, the deviation curves, the quantum and classical curves.
    """
    moments = _validate.moments(body, name="body")
    N = _validate.dimension_from_count(moments.size, name="body", what="moments")
    L0 = _validate.components("L0", L0, n_planes(N), batch=False)
    scale = power_of_two_scale(float(np.max(np.abs(L0))))  # (exact: the norm of 1e-300 components underflowed to 0)
    norm0 = float(np.linalg.norm(L0 / scale)) * scale
    if norm0 == 0.0:
        raise ValueError("L0 must be non-zero")
    native = tuple(k for k, c in PROPAGATORS.items() if c.native)  # (checked here, not after the classical run)
    if isinstance(method, str) and method in PROPAGATORS and method not in native:
        raise ValueError(f"method {method!r} is QuTiP's solver; ehrenfest_time propagates in the symmetry sectors: "
                         f"one of {', '.join(map(repr, native))}")
    method = _validate.choice("method", method, native)
    _validate.numeric_input("ls", ls)  # (booleans, text, masked arrays named; SymPy and NumPy integers pass)
    given = ls
    ls = np.atleast_1d(_validate.as_array("ls", ls, what="sequence of integers >= 1"))
    if ls.ndim != 1 or ls.size == 0:
        raise ValueError(f"ls must be a non-empty sequence of integers >= 1, got {_validate.fmt(given)}")
    _pricing.check("ehrenfest_time", irreps=ls.size)  # (the count alone, before a loop over ls)
    # (entries as given: [1, 2.5] names ls[1] = 2.5, not the 1.0 of the float array NumPy made of it)
    ls = np.array([_validate.integer(f"ls[{k}]", x, minimum=1)
                   for k, x in enumerate(given if isinstance(given, (list, tuple)) else ls)])
    if weight is None:
        wq = (Fraction(1),) + (Fraction(0),) * (N // 2 - 1)
    else:  # exact numbers stay exact (a representation's highest_weight is Fractions), floats stay floats
        if isinstance(weight, (str, bytes)) or not hasattr(weight, "__len__"):
            raise TypeError(f"weight must be a sequence of N // 2 = {N // 2} numbers, got {_validate.fmt(weight)}")
        wq = tuple(_validate.real("weight entry", x)
                   if isinstance(x, (float, np.floating)) else _to_fraction(x, "weight entry") for x in weight)
        if len(wq) != N // 2 or not any(wq):
            raise ValueError(f"weight must have N // 2 = {N // 2} entries, not all zero, got {_validate.fmt(weight)}")
    w = np.array([float(x) for x in wq])
    threshold = _validate.positive("threshold", threshold)
    progress = _validate.flag("progress", progress, allow_none=True)
    t = _validate.time_grid(t, allow_decreasing=False)
    rtol = options["quantum_ehrenfest_rtol"] if rtol is None else _validate.positive("rtol", rtol)
    hws = [tuple(int(l) * x if isinstance(x, Fraction) else _highest_weight_entry(int(l) * x) for x in wq) for l in ls]
    sizes = [gt_size(N, hw) for hw in hws]
    for hw, size in zip(hws, sizes):  # every irrep's size before any work (the classical run compiles and integrates)
        if size > DEFAULT_MAX_DIM:
            irrep(N, hw)  # raises irrep's own error, naming the dimension and max_dim
    # the whole loop over ls (each irrep's own steps are priced again at their doors)
    _pricing.check("ehrenfest_time", irreps=ls.size, dims=float(sum(float(d) for d in sizes)),
                   dim_squares=float(sum(float(d) ** 2 for d in sizes)),
                   n_times=t.size, n=n_planes(N))
    try:
        traj = simulate(moments, L0 / moments, t, rtol=rtol)
    except FloatingPointError as exc:  # moments (or L0) out of the range of double precision
        raise ValueError(f"body and L0 give a classical run outside double precision: {exc}") from exc
    classical = np.asarray(traj.L)
    hbars, dims, quantum, devs, tE = [], [], [], [], []
    bar = progress_bar(progress, len(ls), "ehrenfest_time: irreps")
    try:
        for l, hw in zip(ls, hws):
            rep = irrep(N, hw)
            hbar = norm0 / (l * float(np.linalg.norm(w)))
            H = rotor_hamiltonian(rep, moments, hbar=hbar)
            psi = coherent_state(rep, L0, hbar=hbar, frame="body")
            ops = [-rep.generator(p, form="hermitian", hbar=hbar) for p in planes(N)]
            U = SectorPropagator(H, rep=rep, hbar=hbar, method=method)
            res = U.evolve(psi, t, e_ops=ops)
            q = np.array(res.expect).T.real
            dev = np.linalg.norm(q - classical, axis=1) / norm0
            hbars.append(hbar)
            dims.append(rep.dim)
            quantum.append(q)
            devs.append(dev)
            tE.append(_first_crossing(t, dev, threshold))
            if bar is not None:
                bar.update(1)
    finally:
        if bar is not None:
            bar.close()
    return EhrenfestResult(ls, np.array(hbars), np.array(dims), np.array(tE), t, np.array(devs),
                           np.array(quantum), classical, float(threshold))
