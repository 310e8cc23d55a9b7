r"""Time evolution of quantum rotors: :func:`evolve` and the reusable :class:`SectorPropagator`.

:func:`evolve` solves :math:`i\hbar\,\partial_t\psi = \hat H\psi` on a time grid
``t`` (the spelling of :func:`hyperrotor.simulate`) with one of the methods of
:mod:`hyperrotor.quantum.propagators` (:data:`~hyperrotor.quantum.PROPAGATORS`).
The native methods run through a :class:`SectorPropagator`, which can also be
built once and applied to many states and time grids.

The propagator, its blocks and its rent-or-buy rules are documented in
:mod:`hyperrotor.quantum.sector_propagator`; :func:`evolve` keeps, while ``H`` lives, the
propagator it built for it.
"""
from __future__ import annotations

import sys
import weakref
from typing import Any

import numpy as np

from .. import _pricing, _validate
from .hamiltonian import hermitian_matrix, representation_of
from .propagators import PROPAGATORS, propagator_class, qutip_bars
from .sector_propagator import SectorPropagator, e_ops_list, unit_state

__all__ = ["evolve"]


def evolve(H: Any, psi0: Any, t: Any, *, e_ops: Any = None, method: str = "auto", c_ops: Any = None,
           options: dict | None = None, hbar: float = 1, rep: Any = None, progress: bool | None = None,
           workers: int | None = None, client: Any = None):
    r"""Evolve ``psi0`` under :math:`i\hbar\,\partial_t\psi = \hat H\psi` on the time grid ``t``.

    Parameters
    ----------
    H : qutip.Qobj, scipy.sparse matrix or ndarray
        Hermitian, time-independent Hamiltonian (e.g. :func:`rotor_hamiltonian`).
    psi0 : qutip.Qobj (ket) or array_like
        Initial state at ``t[0]``, of the dimension of ``H``. It is normalized
        (after scaling by its largest amplitude, so huge or tiny vectors keep their
        direction); a norm off 1 by more than ``options["quantum_psi0_norm_rtol"]``
        gives a ``UserWarning``; the zero vector is refused.
    t : sequence of float
        Strictly increasing output times (as in :func:`hyperrotor.simulate`);
        ``t[0]`` is the time of ``psi0``.
    e_ops : Qobj, sparse matrix, ndarray, QobjEvo, callable, or list/dict of these, keyword-only
        Operators whose expectation values are recorded (as in QuTiP): each of ``H``'s
        dimension (a ``qutip.QobjEvo`` also of its ``dims``), or a function ``f(t, state)``.
        QuTiP's e_ops take no ``[op, coeff]`` pairs: a time-dependent one is a ``QobjEvo``.
    method : str, keyword-only, default "auto"
        A key of :data:`PROPAGATORS` (case-insensitive): ``"auto"``,
        ``"eigen"``, ``"krylov"``, ``"expm_multiply"``, ``"sesolve"``,
        ``"mesolve"``. ``"auto"`` is ``"mesolve"`` when ``c_ops`` are given.
    c_ops : list, keyword-only
        Collapse operators (only with ``"mesolve"``/``"auto"``), each of ``H``'s dimension, in
        the forms QuTiP's ``mesolve`` takes: an operator (Qobj, sparse matrix, 2-D array); a
        time-dependent pair ``[op, coeff]`` whose ``coeff`` is a function of ``t`` (``f(t)`` or
        ``f(t, **args)``; QuTiP 5.3 deprecates ``f(t, args)``), a ``qutip.Coefficient`` or a 1-D
        array of one value per entry of ``t`` (interpolated), the rate being ``|coeff(t)|**2``;
        QuTiP's list format of one operator ``[op0, [op1, coeff1], ...]``; a ``qutip.QobjEvo``
        (of ``H``'s ``dims``); or a function ``f(t) -> Qobj``. Text coefficients (which QuTiP
        would compile) are refused.
    options : dict, keyword-only
        The keys of :func:`evolve_options` ``(method)``: :data:`RESULT_OPTIONS`,
        ``blocks``/``block_atol`` for the native methods, and the method's own
        table (Krylov ``atol``, ``krylov_dim``; QuTiP's keys for ``"sesolve"``/
        ``"mesolve"``, where ``atol``/``rtol`` are the ODE tolerances). Unknown keys
        raise :class:`hyperrotor.UnknownOptionError` naming the allowed ones. For
        ``"sesolve"``/``"mesolve"`` the keys are those of QuTiP's solver and of the
        integrator chosen by ``options["method"]`` (default ``"adams"``; a key of another
        integrator is refused naming it), checked before any work: ``nsteps``, ``order``,
        ``krylov_dim`` positive integers (``1e5`` is read as 100000; ``"krylov"`` needs
        ``krylov_dim``), ``atol``, ``rtol`` finite numbers >= 0, the step sizes >= 0 (0:
        automatic; ``max_step`` may be ``inf``), switches ``True``/``False``; booleans and
        text are no numbers; ``None`` is QuTiP's "its default" for every key of QuTiP's solver
        and integrators (``store_states``/``store_final_state`` are the result options above). ``progress_bar``
        picks one of QuTiP's bars (``"text"``, ``"enhanced"``, ``"tqdm"``, ``"html"``, or
        ``""``/``False`` for none).
    hbar : float, keyword-only, default 1
        Use the same value as in :func:`rotor_hamiltonian`.
    rep : Representation, keyword-only, optional
        The representation ``H`` was built from (default: recorded on ``H`` by
        :func:`rotor_hamiltonian`), for the symmetry sectors (module docstring).
    progress : bool or None, keyword-only
        A progress bar: of finished blocks (native methods) or QuTiP's bar
        (``"sesolve"``/``"mesolve"``, tqdm unless ``options["progress_bar"]`` names
        another). ``None``: on a terminal only. ``progress`` and ``options["progress_bar"]``
        may both be given only when they agree (``ValueError`` otherwise).
    workers, client : keyword-only
        Threads or a dask client for the blocks (:class:`SectorPropagator`).

    Returns
    -------
    qutip.solver.Result
        ``times``, ``states`` (stored when no ``e_ops`` are given, or with
        ``store_states=True``), ``expect``, ``e_data``, ``final_state`` and
        ``stats`` (native methods: ``"method"``, ``"blocks"``, ``"sectors"``,
        ``"populated_blocks"``, ``"populated_dim"``, ``"block_methods"``,
        ``"n_matvec"``, ``"n_krylov"``, ``"n_eigh"``, ``"run time"``).

    Raises
    ------
    TypeError
        An option, operator or coefficient of the wrong kind (text or a boolean
        for a number, a list where an operator belongs, ...).
    ValueError
        Non-Hermitian ``H``; ``psi0`` of the wrong dimension or zero; ``t`` not
        strictly increasing; unknown method; ``c_ops`` with a closed-system
        method; an operator or coefficient array of the wrong size; an option
        value out of range; a block too large for ``"eigen"``.
    hyperrotor.UnknownOptionError
        An option key the method does not have.

    Notes
    -----
    ``"auto"`` on a rotor whose sectors are all small propagates a new ``H`` by Lanczos on the
    whole space until building and diagonalizing the sectors is estimated to cost less than more
    Krylov work (rent or buy, module docstring): ``stats["block_methods"]`` says which was used.
    With ``client`` or ``progress=True`` the sectors are built at once (tasks for the workers,
    blocks for the bar).
    The native methods keep the :class:`SectorPropagator` built for ``H`` while ``H`` lives:
    a later call with the same ``H`` object, method, options, ``hbar`` and ``rep`` reuses its
    blocks and eigendecompositions, after checking that the matrix of ``H`` is unchanged
    entry for entry (a matrix modified in place is propagated afresh).

    See Also
    --------
    SectorPropagator : build once, evolve many states.
    """
    cls = propagator_class(method)
    hbar = _validate.hbar(hbar)
    if c_ops is not None and not isinstance(c_ops, (list, tuple)):
        raise TypeError(f"c_ops must be a list of collapse operators (Qobj, scipy.sparse or 2-D arrays), got "
                        f"{_validate.fmt(c_ops)} of type {type(c_ops).__name__}")
    if c_ops:
        if cls.name not in ("auto", "mesolve"):
            raise ValueError(f"collapse operators need method 'mesolve' (or 'auto'), got method {method!r}")
        cls = PROPAGATORS["mesolve"]
    progress = _validate.flag("progress", progress, allow_none=True)
    opts = None if cls.native else _qutip_options(cls, options, progress)  # checked before any work
    given = options.get("store_states") if isinstance(options, dict) else None
    given = _validate.flag("store_states", given, allow_none=True)  # "no" or 0 would act by their truth value
    no_e_ops = e_ops is None or (isinstance(e_ops, (list, tuple, dict)) and not e_ops)
    store = given if given is not None else no_e_ops
    if hasattr(H, "shape") and len(H.shape) == 2:  # priced at the door, before any block or solver is built
        _pricing.check("evolve", dim=int(H.shape[0]), n_times=_validate.time_count(t), states=store)
    mat, dims = hermitian_matrix(H)  # checked once here; the propagators take it as it is
    if not cls.native:
        vec = unit_state(psi0, mat.shape[0])
        t = _validate.time_grid(t, allow_decreasing=False)
        if opts.get("progress_bar") is None and (progress or (progress is None and sys.stderr.isatty())):
            opts["progress_bar"] = "tqdm"
        return cls(**opts).run(mat, dims, vec, t, e_ops_list(e_ops, dims),
                               e_ops_list(c_ops, dims, "c_ops", times=t), hbar)
    rep = rep if rep is not None else representation_of(H)
    prop = _propagator_for(H, mat, dims, rep=rep, hbar=hbar, method=cls.name, options=options, workers=workers,
                           client=client, progress=progress)
    return prop.evolve(psi0, t, e_ops=e_ops, store_states=prop.options["store_states"],
                       store_final_state=prop.options["store_final_state"])


def _qutip_options(cls: Any, options: Any, progress: bool | None) -> dict:
    """The checked ``options`` of a QuTiP method (:meth:`Propagator.resolve_options`); ``progress`` and
    ``options["progress_bar"]`` (QuTiP's bar kinds) may both be given only when they agree (a bar, or none)."""
    opts = cls.resolve_options(options)
    if progress is not None and "progress_bar" in opts:
        bar = opts["progress_bar"]
        bars = qutip_bars()
        if bar is not None and progress != (bar is True or bar in bars):  # (None: QuTiP's default, no bar)
            raise ValueError(
                f"progress={progress} contradicts options['progress_bar'] = {_validate.fmt(bar)}; give one of them "
                f"(progress=True shows hyperrotor's tqdm bar, options['progress_bar'] picks one of QuTiP's: "
                f"{', '.join(map(repr, bars))})")
    return opts


_PROPAGATOR_CACHE: dict[int, tuple[Any, str, SectorPropagator]] = {}


def _propagator_for(H: Any, mat: Any, dims: list, *, rep: Any, hbar: float, method: str, options: dict | None,
                    workers: Any, client: Any, progress: Any) -> SectorPropagator:
    """The :class:`SectorPropagator` of ``H`` (``mat``, ``dims``: its checked matrix): reused when the same
    ``H`` object comes back unchanged.

    :func:`evolve` keeps, while ``H`` lives (a weak reference), the propagator it built for it, with
    its blocks and eigendecompositions. It is reused only for the same method, options, ``hbar``
    and ``rep`` and when the matrix of ``H`` is still equal, entry for entry, to the one the
    propagator was built from (an ``O(nnz)`` comparison: a matrix changed in place is rebuilt).
    """
    params = repr((method, float(hbar), id(rep), sorted((str(k), repr(v)) for k, v in (options or {}).items())
                   if isinstance(options, dict) else repr(options)))
    hit = _PROPAGATOR_CACHE.get(id(H))
    if hit is not None and hit[0]() is H and hit[1] == params:
        prop = hit[2]
        old = prop.matrix
        if (mat.shape == old.shape and mat.dtype == old.dtype and np.array_equal(mat.indptr, old.indptr)
                and np.array_equal(mat.indices, old.indices) and np.array_equal(mat.data, old.data)):
            prop.workers = None if workers is None else _validate.integer("workers", workers, minimum=1)
            prop.client = client
            prop.progress = progress
            return prop
    prop = SectorPropagator.for_evolve(mat, dims, rep=rep, hbar=hbar, method=method, options=options,
                                       workers=workers, client=client, progress=progress)
    try:
        ref = weakref.ref(H, lambda _, key=id(H): _PROPAGATOR_CACHE.pop(key, None))
    except TypeError:  # objects without weak references (lists): no reuse
        return prop
    _PROPAGATOR_CACHE[id(H)] = (ref, params, prop)
    return prop
