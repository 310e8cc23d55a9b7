r"""The reusable propagator of quantum rotors: :class:`SectorPropagator` (used by :func:`~.evolve.evolve`).

Build once, apply to many states and time grids: :math:`e^{-i\hat H t/\hbar}\psi_0` block by
block, with each block's engine, and the rent-or-buy rules below.

Evolution in invariant blocks
-----------------------------
:math:`\hat H` is split once into invariant blocks :math:`\hat H_s = B_s^\dagger
\hat H B_s` with orthonormal :math:`B_s` spanning the space, so that

.. math:: e^{-i\hat H t/\hbar}\psi_0 = \sum_s B_s\, e^{-i\hat H_s t/\hbar}\, B_s^\dagger\psi_0 .

The blocks are the *symmetry sectors* of the rotations by :math:`\pi`
(:func:`~hyperrotor.quantum.symmetry_sectors`, ``complete=True``) when the
representation is known (``rep=``, or recorded on ``H`` by
:func:`~hyperrotor.quantum.rotor_hamiltonian`) and the connected components of the
sparsity graph are larger than ``options["quantum_eigen_max_block"]`` (a generic
inertia: :math:`2^{N-1}` real sectors of about dim / :math:`2^{N-1}` for so(N),
N odd); otherwise the sparsity blocks themselves (an integrable body often splits
into many small ones; blocks of dimension one are phases). Only blocks that the
state populates are propagated, each with the method's engine: ``"eigen"`` (dense
``eigh``, cached on the propagator), ``"krylov"`` (Lanczos, :mod:`._krylov`),
``"expm_multiply"``. ``"auto"`` takes ``"eigen"`` up to ``eigen_max_block`` and
Krylov above, and switches a large block to its (cached) eigendecomposition as
soon as the Krylov work spent and estimated on it exceeds the cost of ``eigh``
(the rule of a rent-or-buy problem: within a factor 2 of the better choice made
in hindsight): many states or long times end in exact diagonalization, a single
state over a short window stays in Krylov. The same rule one level up: when every
sector would be diagonalized (sectors up to ``eigen_max_block``), a propagator that
:func:`evolve` builds for a new ``H`` first propagates by Lanczos on the whole space
without building any sector, and builds and diagonalizes the sectors only once the
Krylov work spent and predicted exceeds their estimated price (a single evolution of a
coherent state in so(5) (9, 3), dim 2401, costs ~25 ms instead of ~80 ms; the fourth
call with the same ``H`` buys the sectors, and later calls cost ~10 ms). A
:class:`SectorPropagator` built directly is meant for many states: it builds its sectors
at once. The blocks are independent tasks (:func:`hyperrotor._parallel.map_rows`:
threads, or a dask ``client=``).
"""
from __future__ import annotations

import time as _time
from functools import cached_property
from numbers import Number
from typing import Any

import numpy as np
import scipy.sparse as sps

from .. import _lazy, _parallel, _pricing, _validate
from .._floats import power_of_two_scale
from .._options import options as _options
from .._warn import warn
from ._krylov import row_bound, single_thread_blas
from ._sector_blocks import (
    Block,
    propagate_blocks,
    sector_bases,
    sector_blocks,
    sector_price,
)
from .hamiltonian import blocks_of, hermitian_matrix, representation_of
from .operator_input import as_csr
from .sectors import check_symmetric
from .propagators import PROPAGATORS, Auto, ExpmMultiply, Krylov, propagator_class

__all__ = ["SectorPropagator", "PhaseRoundingWarning"]

#: relative rounding (radians) of the phases E t / hbar above which a propagation warns (PhaseRoundingWarning)
PHASE_ROUNDING_WARN = 1e-6


class PhaseRoundingWarning(UserWarning):
    r"""The times are so long that double precision rounds the phases :math:`E t/\hbar` of the state by more
    than ``PHASE_ROUNDING_WARN`` = 1e-6 radians (about :math:`\epsilon\,\|H\|\,|t|/\hbar`; from
    :meth:`SectorPropagator.evolve`, :meth:`SectorPropagator.apply`, :func:`~hyperrotor.quantum.evolve` and
    :func:`~hyperrotor.quantum.otoc`).

    Any propagation in double precision computes :math:`e^{-iE_k t/\hbar}` with a phase error of about
    :math:`\epsilon |E_k t|/\hbar` (and the eigenvalues carry :math:`\epsilon\|H\|` themselves): at
    :math:`t = 10^{17}` for :math:`\|H\| \sim 10` the relative phases, and so every superposition, are noise.
    """


def warn_phase_rounding(entry: str, bound: float, span: float, hbar: float) -> None:
    """:class:`PhaseRoundingWarning` when ``eps * bound * span / |hbar|`` exceeds ``PHASE_ROUNDING_WARN``
    (``bound`` >= the spectral radius of H, ``span`` the longest time from the start)."""
    err = float(np.finfo(float).eps) * bound * span / abs(hbar)
    if err > PHASE_ROUNDING_WARN:
        warn(f"{entry}: the phases E t / hbar of the state are rounded by up to ~{err:.2g} radians at the latest "
             f"time (eps x ||H|| ~ {bound:.3g} x |t| ~ {span:.3g} / hbar): over ~{PHASE_ROUNDING_WARN:g} the "
             f"relative phases of the eigencomponents, and every value that depends on them, lose that accuracy "
             f"(above ~1 radian they are noise); double precision cannot do better at these times",
             PhaseRoundingWarning)

#: Below this populated dimension the blocks run in the calling thread (threads cost more than they give).
_SERIAL_DIM = 4096

#: The whole-space Krylov run of a renting propagator skips the re-orthogonalization when the dimension is at
#: least this many times its largest Krylov space (so(5) (9, 3), dim 2401, spaces of 120: the same 66 products,
#: 18 -> 14 ms; in dimensions 45-819 plain Lanczos needed up to 7x more products: :func:`krylov_propagator`).
_PLAIN_LANCZOS = 16


def scaled_state(vec: np.ndarray, name: str) -> tuple[np.ndarray, float]:
    """A complex vector divided by the power of two ``s`` at or below its largest amplitude, and ``s``: exact, and
    its norm is then finite and accurate however large or small the amplitudes (the zero vector is refused)."""
    scale = float(np.max(np.abs(vec))) if vec.size else 0.0
    if scale == 0.0:
        raise ValueError(f"{name} is the zero vector; it cannot be normalized")
    s = power_of_two_scale(scale)
    return vec.real / s + 1j * (vec.imag / s), s  # (parts apart: a complex division by a subnormal s overflows)


def unit_state(psi0: Any, dim: int, name: str = "psi0") -> np.ndarray:
    r"""``psi0`` as a unit vector: scaled by :math:`\max_k|\psi_k|` *before* the norm is taken.

    Scaling first keeps :math:`|\psi|` finite for amplitudes near the overflow
    (``np.full(3, 1e200)``) and accurate near the underflow (``1e-200``), where the
    plain 2-norm is ``inf`` or ``0``. A norm off 1 by more than
    ``options["quantum_psi0_norm_rtol"]`` warns; the zero vector is refused.
    """
    vec, s = scaled_state(_validate.ket(name, psi0, dim, of="H"), name)
    nrm = float(np.linalg.norm(vec))
    with np.errstate(over="ignore"):
        norm = nrm * s  # only reported (may be inf for a huge vector)
    if abs(norm - 1) > _options["quantum_psi0_norm_rtol"]:
        warn(f"{name} has norm {norm:.12g}; evolving the normalized state {name}/|{name}| "
             f"(tolerance options['quantum_psi0_norm_rtol'] = {_options['quantum_psi0_norm_rtol']:.3g})")
    return vec / nrm


def e_ops_list(e_ops: Any, dims, name: str = "e_ops", *, times: Any = None) -> Any:
    """``e_ops`` (or ``c_ops``: ``name``) as QuTiP accepts them, each entry checked.

    An operator (a Qobj, scipy.sparse matrix or 2-D array) must be square, finite and of ``H``'s dimension; it is
    given as a Qobj with ``H``'s ``dims``. A ``qutip.QobjEvo`` (time-dependent) must have ``H``'s shape and ``dims``
    and passes as it is. A callable passes as it is: for ``e_ops`` QuTiP's ``f(t, state)``; for ``c_ops`` QuTiP's
    ``f(t) -> Qobj`` (or ``f(t, **args)``), made a ``QobjEvo`` here to check its shape. With ``times`` (the output
    grid of a QuTiP solver, given for ``c_ops``) an entry may also be QuTiP's time-dependent pair ``[op, coeff]``:
    ``op`` a constant operator as above, ``coeff`` a function of ``t`` (``f(t)`` or ``f(t, **args)``; read by
    ``qutip.coefficient``, so what QuTiP cannot use is refused here), a ``qutip.Coefficient``, or a 1-D finite array
    of one value per entry of ``times`` (interpolated by QuTiP); text coefficients (which QuTiP would compile) are
    refused; or QuTiP's list format of one operator, ``[op0, [op1, coeff1], ...]`` (made a ``QobjEvo`` here and
    checked). A list, tuple, dict or one operator; ``None``: none.
    """
    qutip = _lazy.qutip
    dim = int(np.prod(dims[0]))
    pairs = times is not None
    kinds = ("a qutip.Qobj, a scipy.sparse matrix, a 2-D ndarray, a qutip.QobjEvo"
             + (", a pair [op, coeff], QuTiP's list format [op0, [op1, coeff1], ...]" if pairs else "")
             + " or a callable")

    def evo(op, label):
        if op.shape != (dim, dim):
            raise ValueError(f"{label} has shape {op.shape}, but H has dimension {dim}")
        if list(op.dims) != list(dims):
            raise ValueError(f"{label} has dims {op.dims}, but H has dims {dims}")
        return op

    def static(op, label):
        mat = as_csr(op, label)
        if mat.shape[0] != dim:
            raise ValueError(f"{label} has dimension {mat.shape[0]}, but H has dimension {dim}")
        return qutip.Qobj(mat, dims=dims)

    def coefficient(c, label):
        from qutip.core.coefficient import Coefficient  # (qutip.core.coefficient is also a function's name)

        allowed = "a function of t, a qutip.Coefficient or an array of one value per output time"
        if isinstance(c, Coefficient):
            return c
        if callable(c) and not hasattr(c, "isoper"):
            try:  # (QuTiP's own reading of a function: its signature, f(t) or f(t, **args); mesolve conjugates it)
                coef = qutip.coefficient(c)
                coef.conj()
                return coef
            except Exception as exc:  # (QuTiP raises several kinds for what is not a coefficient function)
                raise TypeError(f"{label} (a coefficient) must be {allowed}; QuTiP cannot use "
                                f"{_validate.fmt(c)}: {exc}") from None
        if isinstance(c, (str, bytes)):
            raise TypeError(f"{label} (a coefficient) must be {allowed}, got the text {_validate.fmt(c)} "
                            f"(text is never compiled here)")
        if not isinstance(c, (np.ndarray, list, tuple)):
            hint = "; for a constant rate g pass sqrt(g) * op" if np.isscalar(c) else ""
            raise TypeError(f"{label} (a coefficient) must be {allowed}, got {_validate.fmt(c)} of type "
                            f"{type(c).__name__}{hint}")
        arr = _validate.finite_array(label, c, ndim=1, dtype=complex if np.iscomplexobj(c) else float)
        if arr.shape != (len(times),):
            raise ValueError(f"{label} (a coefficient) must have one value per output time, shape ({len(times)},), "
                             f"got shape {arr.shape}")
        return arr

    def operator_like(x):  # (a term of QuTiP's list format; anything else second in a pair is its coefficient)
        return isinstance(x, (qutip.Qobj, qutip.QobjEvo)) or sps.issparse(x) or (
            isinstance(x, np.ndarray) and x.ndim == 2 and x.shape[0] == x.shape[1] > 1)

    def numbers(x):  # (a list of numbers second in a pair: an array coefficient)
        return isinstance(x, (list, tuple)) and bool(x) and all(
            isinstance(v, Number) and not isinstance(v, bool) for v in x)

    def conv(op, label):
        if isinstance(op, qutip.QobjEvo):  # (time-dependent: QuTiP's solvers take it as it is)
            return evo(op, label)
        if callable(op) and not hasattr(op, "isoper"):
            if name != "c_ops":
                return op
            try:
                return evo(qutip.QobjEvo(op), label)
            except (TypeError, ValueError) as exc:  # (QobjEvo calls it once: a function of t that is no operator)
                raise TypeError(f"{label} is a function, so it must be QuTiP's f(t) -> Qobj (or f(t, **args); a "
                                f"time-dependent rate is the pair [op, coeff] in c_ops): {exc}") from None
        if isinstance(op, (list, tuple)):
            if not pairs:
                raise TypeError(f"{label} must be {kinds}, got a {type(op).__name__} of length {len(op)} (a "
                                f"time-dependent {name} entry is a qutip.QobjEvo, e.g. QobjEvo([op, f]))")
            if not op:
                raise TypeError(f"{label} must be {kinds}, got an empty {type(op).__name__}")
            if is_pair(op):
                return pair(op, label)
            # QuTiP's list format of one operator, [op0, [op1, coeff1], ...]: each term checked, then a QobjEvo
            terms = [pair(x, f"{label}[{k}]") if isinstance(x, (list, tuple)) else term(x, f"{label}[{k}]")
                     for k, x in enumerate(op)]
            return evo(qutip.QobjEvo(terms, tlist=np.asarray(times, dtype=float)), label)
        return static(op, label)

    def is_pair(op):
        return len(op) == 2 and (numbers(op[1]) or (not isinstance(op[1], (list, tuple)) and not operator_like(op[1])))

    def term(x, label, what="the whole operator"):
        if isinstance(x, qutip.QobjEvo):
            raise TypeError(f"{label} must be a constant operator (a Qobj, a scipy.sparse matrix or a 2-D ndarray; a "
                            f"term of QuTiP's list format may also be a pair [op, coeff]), got a qutip.QobjEvo: give "
                            f"{what} as one QobjEvo")
        return static(x, label)

    def pair(op, label):
        if not is_pair(op):
            raise TypeError(f"{label} must be a pair [op, coeff] (a term of QuTiP's list format; an array coefficient "
                            f"is a numpy array), got a {type(op).__name__} of length {len(op)}")
        return [term(op[0], f"{label}[0]", "the product"), coefficient(op[1], f"{label}[1]")]

    if e_ops is None:
        return []
    if isinstance(e_ops, dict):
        return {k: conv(op, f"{name}[{k!r}]") for k, op in e_ops.items()}
    if isinstance(e_ops, (list, tuple)):
        return [conv(op, f"{name}[{k}]") for k, op in enumerate(e_ops)]
    return [conv(e_ops, name)]


class SectorPropagator:
    r"""A reusable propagator :math:`e^{-i\hat H t/\hbar}` in the invariant blocks of ``H`` (module docstring).

    Built once (the blocks, their matrices, and where it pays their
    eigendecompositions are cached), applied to many states and time grids.

    Parameters
    ----------
    H : qutip.Qobj, scipy.sparse matrix or ndarray
        Hermitian, time-independent Hamiltonian (e.g. :func:`rotor_hamiltonian`).
    rep : Representation, keyword-only, optional
        The representation ``H`` was built from (default: the one
        :func:`rotor_hamiltonian` recorded on ``H``), for the symmetry sectors.
    hbar : float, keyword-only, default 1
    method : str, keyword-only, default "auto"
        A native method of :data:`PROPAGATORS`: ``"auto"``, ``"eigen"``,
        ``"krylov"``, ``"expm_multiply"`` (or a registered native subclass).
    options : dict, keyword-only, optional
        The keys of :func:`evolve_options` ``(method)`` (``blocks``, ``block_atol``,
        Krylov ``atol``, ``krylov_dim``, ...; the result keys are used by :meth:`evolve`).
    workers, client : keyword-only
        Where the blocks run (:func:`hyperrotor._parallel.map_rows`): ``workers``
        threads (default: all cores when the populated dimension exceeds 4096,
        else 1) or the workers of a dask ``client`` (each task receives its
        blocks' matrices; caches built there stay there).
    progress : bool or None, keyword-only
        A bar counting finished blocks (``None``: on a terminal, for runs over a second).

    Attributes
    ----------
    dim : int
    stats : dict
        ``"blocks"`` (sparsity blocks), ``"sectors"`` (when the sectors are used),
        ``"parts"`` (independent problems), and the counters of the last run.

    Examples
    --------
    >>> import numpy as np
    >>> from hyperrotor.quantum import irrep, rotor_hamiltonian, SectorPropagator
    >>> H = rotor_hamiltonian(irrep(5, (2, 1)), np.linspace(1, 2, 10))
    >>> U = SectorPropagator(H)
    >>> psi = np.ones(H.shape[0]) / np.sqrt(H.shape[0])
    >>> U.states(psi, [0.0, 0.5, 1.0]).shape
    (3, 35)
    """

    def __init__(self, H: Any, *, rep: Any = None, hbar: float = 1, method: str = "auto",
                 options: dict | None = None, workers: int | None = None, client: Any = None,
                 progress: bool | None = None) -> None:
        matrix, dims = hermitian_matrix(H)
        self._setup(matrix, dims, rep if rep is not None else representation_of(H), hbar, method, options, workers,
                    client, progress, rent=False)

    @classmethod
    def for_evolve(cls, matrix: Any, dims: list, *, rep: Any = None, hbar: float = 1, method: str = "auto",
                   options: dict | None = None, workers: int | None = None, client: Any = None,
                   progress: bool | None = None) -> "SectorPropagator":
        """The propagator :func:`~.evolve.evolve` builds from the matrix it has checked (``hermitian_matrix``)
        and the representation it has found (the other arguments: the constructor's): it may rent (Lanczos on
        the whole space) before it builds the sectors."""
        self = cls.__new__(cls)
        self._setup(matrix, dims, rep, hbar, method, options, workers, client, progress, rent=True)
        return self

    def _setup(self, matrix: Any, dims: list, rep: Any, hbar: Any, method: str, options: dict | None, workers: Any,
               client: Any, progress: Any, *, rent: bool) -> None:
        cls = propagator_class(method)
        if not cls.native:
            raise ValueError(f"method {cls.name!r} is QuTiP's solver, not a native propagator; use evolve(..., "
                             f"method={cls.name!r}) or one of {', '.join(repr(k) for k, c in PROPAGATORS.items() if c.native)}")
        self.hbar = _validate.hbar(hbar)
        self.matrix, self.dims = matrix, dims
        self.dim = int(self.matrix.shape[0])
        if rep is not None:
            rep = _validate.representation("rep", rep, dim=self.dim)
        self.method = cls.name
        self.options = cls.resolve_options(options)
        if self.options["blocks"] not in ("auto", True, False):
            raise ValueError(f"option 'blocks' must be 'auto', True or False, got {_validate.fmt(self.options['blocks'])}")
        self.workers = None if workers is None else _validate.integer("workers", workers, minimum=1)
        self.client = _validate.client(client)
        self.progress = _validate.flag("progress", progress, allow_none=True)
        self.diagonal = self.matrix.diagonal().real
        self.stats: dict[str, Any] = {"method": cls.name}
        self._parts: list[Block] | None = None
        self._rent: dict | None = None  # whole-space Krylov before the sectors are bought (evolve, "auto")
        self._split(cls, rep, rent)

    def __getstate__(self) -> dict:
        """Pickled without its dask client (a connection, not data: the copy runs in-process, as the workers'
        copies do; a propagator built with client= did not pickle)."""
        return {**self.__dict__, "client": None}

    def __setstate__(self, state: dict) -> None:
        """Unpickled (e.g. back from a dask worker): the blocks point to this propagator again."""
        self.__dict__.update(state)
        for b in self._parts or ():
            b.owner = self

    @property
    def _blocks(self) -> list[Block]:
        """The invariant blocks; the sectors of a renting propagator are built (bought) at the first need."""
        if self._parts is None:
            cls, rep, blocks = self._rent.pop("deferred")
            self._rent = None
            self._parts = self._block_list(cls, rep, blocks)
        return self._parts

    def _split(self, cls, rep, rent: bool) -> None:
        opts = self.options
        use = opts["blocks"]
        blocks = blocks_of(self.matrix, atol=opts["block_atol"]) if use else [np.arange(self.dim)]
        self.stats["blocks"] = len(blocks)
        big = max((len(b) for b in blocks if len(b) > 1), default=0)
        sectors = rep is not None and use and big > int(_options["quantum_eigen_max_block"])
        if sectors:  # before any work, also when the sectors would be bought later (a rep= H does not respect
            check_symmetric(self.matrix, rep)  # gave wrong states)
        if (rent and sectors and cls is Auto and self.client is None and self.progress is not True
                and rep.dim <= _options["quantum_eigen_max_block"] * 2 ** (rep.N - 1)):
            # every sector would be diagonalized: for one state a Krylov run on the whole space may cost less
            self._rent = {"deferred": (cls, rep, blocks), "spent": 0.0, "rate": None, "rep": rep}
            return
        self._parts = self._block_list(cls, rep if sectors else None, blocks)

    def _block_list(self, cls, rep, blocks) -> list[Block]:
        """The blocks: the sectors of ``rep`` (when given and usable), else the sparsity ``blocks``."""
        engine = cls(**{k: self.options[k] for k in cls.options})
        multi = [b for b in blocks if len(b) > 1]
        bases = sector_bases(rep) if rep is not None else None
        if bases is not None:  # generic inertia: the sectors split the sparsity blocks ~2^(N-1) ways
            self.stats["sectors"] = len(bases)
            return sector_blocks(self, bases, engine)
        out: list[Block] = []
        singles = np.array([b[0] for b in blocks if len(b) == 1], dtype=int)
        if singles.size:
            out.append(Block(self, singles, None))
        for idx, eng in engine.plan(multi):
            pieces = None
            if eng.union_blocks:  # local positions of the merged sparsity blocks
                pos = np.full(self.dim, -1)
                pos[idx] = np.arange(idx.size)
                pieces = [pos[b] for b in multi if pos[b[0]] >= 0]
            out.append(Block(self, idx, eng, pieces))
        return out

    def _run(self, vec: np.ndarray, t: np.ndarray, hbar: float) -> np.ndarray:
        """``(dim, nt)`` states ``exp(-i H (t - t[0]) / hbar) vec`` (``hbar < 0`` runs backwards).

        Rent or buy (a propagator of :func:`evolve`, method ``"auto"``, whose sectors would all be
        diagonalized): while the Krylov work on the whole space, spent and predicted, stays below the
        estimated price of the sectors (build, blocks, ``eigh``: :func:`~._sector_blocks.sector_price`, in the units of
        :meth:`_lanczos_work`), the states come
        from Lanczos on the whole matrix and no sector is built; the prediction of a call is the work
        per unit time measured so far (before any: one Krylov space). The Krylov space may grow to twice
        ``options["quantum_krylov_dim"]`` unless ``krylov_dim`` is given: these problems are small, and one
        space that serves the whole grid saves the restarts. Once renting would cost more,
        the sectors are built and diagonalized, also in the middle of a grid (the rest of it starts
        from the state reached).
        """
        rent = self._rent
        # a client or a progress bar asked for on a later call: buy (the blocks go to the workers / the bar)
        if rent is not None and self._parts is None and self.client is None and self.progress is not True:
            price = sector_price(self.matrix, rent["rep"])
            span = abs(float(t[-1] - t[0]))
            kopts = {key: self.options[key] for key in Krylov.options}
            if kopts["krylov_dim"] is None:  # a small problem: one space for the whole grid saves the restarts
                kopts["krylov_dim"] = 2 * int(_options["quantum_krylov_dim"])
            engine = Krylov(**kopts)
            m = min(self.dim, engine.settings()[1])
            guess = rent["rate"] * span if rent["rate"] is not None else self._lanczos_work(m, 1)
            if rent["spent"] + guess <= price:
                C, k, stats = self._rent_run(engine, vec, t, hbar, price)
                if k == t.size - 1:
                    self.stats.update(stats)
                    return C
                rest = self._run_blocks(C[:, k], t[k:], hbar)  # bought: the sectors from t[k] on
                for key in ("n_matvec", "n_krylov"):
                    self.stats[key] = self.stats.get(key, 0) + stats[key]
                self.stats["block_methods"] = sorted(set(self.stats["block_methods"]) | {"krylov"})
                return np.concatenate([C[:, :k], rest], axis=1)
        return self._run_blocks(vec, t, hbar)

    def _lanczos_work(self, n_matvec: int, n_krylov: int) -> float:
        """Work of ``n_matvec`` Lanczos steps on the whole matrix in ``n_krylov`` spaces: a product (8 nnz)
        and a re-orthogonalization against the space built so far (8 dim m on average) per step (counted
        for plain Lanczos too: the rent is overestimated, never under)."""
        return n_matvec * (8.0 * self.matrix.nnz + 8.0 * self.dim * n_matvec / max(1, n_krylov))

    def _rent_run(self, engine: Krylov, vec: np.ndarray, t: np.ndarray, hbar: float,
                  price: float) -> tuple[np.ndarray, int, dict]:
        """Lanczos on the whole matrix over ``t`` until renting is predicted to cost more than ``price``
        (asked before every restart): ``(states (dim, k + 1), k, stats)`` for the times ``t[: k + 1]``."""
        t0 = _time.perf_counter()
        rent = self._rent
        stats: dict = {"n_matvec": 0, "n_krylov": 0}
        span = abs(float(t[-1] - t[0]))

        def stop(t_cur: float, n_matvec: int) -> bool:  # the rest of the grid is cheaper in the sectors
            work = self._lanczos_work(n_matvec, stats["n_krylov"])
            return rent["spent"] + work * span / abs(float(t_cur - t[0])) > price

        out = np.empty((self.dim, t.size), dtype=complex, order="F")  # one contiguous column per time
        # plain Lanczos when the spaces are small beside the dimension (no converged Ritz values to repeat)
        plain = self.dim >= _PLAIN_LANCZOS * min(self.dim, engine.settings()[1])
        k = -1
        with single_thread_blas():
            for k, state in enumerate(engine.propagate(self.matrix, vec, t, hbar, stats, stop=stop,
                                                       reorthogonalize=not plain)):
                out[:, k] = state
        work = self._lanczos_work(stats["n_matvec"], stats["n_krylov"])
        rent["spent"] += work
        if k > 0:
            rent["rate"] = work / abs(float(t[k] - t[0]))
        stats.update({"populated_blocks": 1, "populated_dim": self.dim, "n_eigh": 0, "block_methods": ["krylov"],
                      "run time": _time.perf_counter() - t0})
        return out[:, : k + 1], k, stats

    def _run_blocks(self, vec: np.ndarray, t: np.ndarray, hbar: float) -> np.ndarray:
        """:meth:`_run` in the blocks (the sectors, or the sparsity blocks)."""
        t0 = _time.perf_counter()
        scale = float(np.abs(vec).max()) if vec.size else 0.0
        coords = [b.coords(vec) for b in self._blocks]
        active = [i for i, c in enumerate(coords) if c.size and np.any(np.abs(c) > 1e-15 * scale)]
        populated = sum(self._blocks[i].n for i in active)
        workers = self.workers if self.workers is not None else (1 if populated <= _SERIAL_DIM else None)
        results = []
        if active:
            with single_thread_blas():  # process-wide: the worker threads run on one BLAS thread each
                results = _parallel.map_rows(
                    propagate_blocks, np.array(active, dtype=int),
                    args=(self._blocks, coords, t, hbar, self.method == "auto"),
                    client=self.client, workers=workers, progress=self.progress, desc="evolve: blocks",
                )
        out = np.zeros((self.dim, t.size), dtype=complex)
        stats = {"populated_blocks": len(active), "populated_dim": 0, "n_matvec": 0, "n_krylov": 0, "n_eigh": 0}
        used = set()
        for i, (C, st, how) in zip(active, results):
            self._blocks[i].embed(out, C)
            used.add(how)
            stats["populated_dim"] += st.pop("populated_dim", self._blocks[i].n)
            for k, v in st.items():
                stats[k] = stats.get(k, 0) + v
        stats["block_methods"] = sorted(used) if used else ["diagonal"]
        stats["run time"] = _time.perf_counter() - t0
        self.stats.update(stats)
        return out

    def states(self, psi: Any, t: Any) -> np.ndarray:
        r"""The states :math:`e^{-i\hat H (t_k - t_0)/\hbar}\psi` at the times ``t`` (``t[0]``: the time of ``psi``).

        ``psi`` is used as given (linear map, not normalized; any finite vector).
        Returns an ndarray ``(len(t), dim)``, complex.
        """
        vec = _validate.ket("psi", psi, self.dim, of="H")
        t = _validate.time_grid(t, allow_decreasing=False)
        self._priced("SectorPropagator.states", t, states=True)
        return self._run(vec, t, self.hbar).T

    def apply(self, X: Any, tau: float) -> np.ndarray:
        r""":math:`e^{-i\hat H\tau/\hbar} X` for one time ``tau`` (either sign) and a vector or a matrix of columns.

        Every block that ``X`` populates is diagonalized once (dense ``eigh``, cached on
        the propagator; priced against ``hr.options``) and the columns are propagated
        in its eigenbasis: :math:`O(\sum_s n_s^2)` per column and time, the cheap
        road for many states and many times (:func:`~hyperrotor.quantum.otoc`).

        Parameters
        ----------
        X : array_like, shape ``(dim,)`` or ``(dim, k)``
        tau : float

        Returns
        -------
        ndarray of the shape of ``X``, complex.

        Warns
        -----
        PhaseRoundingWarning
            when double precision rounds the phases :math:`E\tau/\hbar` by more than ``PHASE_ROUNDING_WARN``.
        """
        X = _validate.ket("X", X, self.dim, of="H", columns=True)  # (finite, no booleans; a ket Qobj too)
        tau = _validate.real("tau", tau)
        warn_phase_rounding("SectorPropagator.apply", self.spectral_bound, abs(tau), self.hbar)
        return self._apply(X, tau)

    def _apply(self, X: np.ndarray, tau: float) -> np.ndarray:
        """:meth:`apply` of a checked complex ``X`` without the phase check (callers that checked their inputs and
        their longest time at their door: otoc)."""
        X = np.asarray(X, dtype=complex)
        out = np.zeros(X.shape, dtype=complex)
        stats: dict = {}
        with single_thread_blas():  # small products: threads only oversubscribe a loaded machine
            parts = []  # (the blocks X has components in, with them)
            for b in self._blocks:
                C = b.coords(X)
                if np.any(C):
                    parts.append((b, C))
            # every block still to diagonalize priced together, before the first (each was priced on its own)
            todo = [b for b, _ in parts if b.engine is not None and b.eig is None]
            if todo:
                _pricing.check("dense_diagonalization", dim=max(b.n for b in todo),
                               complex=any(b.matrix.dtype.kind == "c" for b in todo),
                               cubes=sum(float(b.n) ** 3 for b in todo))
            for b, C in parts:
                if b.engine is None:
                    phase = np.exp((-1j * tau / self.hbar) * b.diag)
                    C = phase[:, None] * C if C.ndim == 2 else phase * C
                else:
                    if b.eig is None:
                        b.diagonalize(stats)
                    E, V = b.eig
                    phase = np.exp((-1j * tau / self.hbar) * E)
                    D = V.conj().T @ C
                    C = V @ (phase[:, None] * D if D.ndim == 2 else phase * D)
                b.embed(out, C)
        return out

    @cached_property
    def spectral_bound(self) -> float:
        """The largest absolute row sum of ``H`` (:func:`~._krylov.row_bound`): a bound of its spectral radius
        (computed once, on first use: the phase-rounding check of evolve and otoc)."""
        return row_bound(self.matrix)

    def apply_blocks(self) -> list[int]:
        """The dimensions of the blocks that :meth:`apply` diagonalizes (dense ``eigh``, once) and multiplies
        every column by (the one-dimensional blocks are phases): what a caller of :meth:`apply` prices
        (:func:`~hyperrotor.quantum.otoc`) before any work."""
        return [b.n for b in self._blocks if b.engine is not None]

    def _stepping_phases(self, t: np.ndarray) -> dict:
        r"""``{"krylov_phase": ..., "expm_phase": ...}``: :math:`\sum_b \|H_b\|\,|t_\text{end} - t_0|/|\hbar|` over
        the blocks propagated by Lanczos and by ``expm_multiply``, whose numbers of products grow like it
        (:math:`\|H_b\|`: the largest absolute row sum, a bound of the spectral radius); 0 for blocks that are
        diagonalized and while the propagator rents (its Lanczos work is bounded by the sectors' price,
        :meth:`_run`)."""
        phases = {"krylov_phase": 0.0, "expm_phase": 0.0}
        if t.size < 2:
            return phases
        span = abs(float(t[-1] - t[0])) / abs(self.hbar)
        for b in self._parts or ():
            key = ("krylov_phase" if isinstance(b.engine, Krylov) else
                   "expm_phase" if isinstance(b.engine, ExpmMultiply) else None)
            if key is not None and b.n:
                phases[key] += row_bound(b.matrix) * span
        return phases

    def _priced(self, entry: str, t: np.ndarray, *, states: bool) -> None:
        """The one door of a run over the grid ``t`` (:meth:`evolve`, :meth:`states`): its output (``states``: every
        state kept) and its stepping phases priced before any work, and the phase rounding warned of."""
        _pricing.check("evolve", dim=self.dim, n_times=t.size, states=states, **self._stepping_phases(t))
        if t.size > 1:
            warn_phase_rounding(entry, self.spectral_bound, float(t[-1] - t[0]), self.hbar)

    def evolve(self, psi0: Any, t: Any, *, e_ops: Any = None, store_states: bool | None = None,
               store_final_state: bool = True):
        """:func:`evolve` with this propagator: ``psi0`` normalized, a ``qutip.solver.Result``.

        Without stored states (``e_ops`` given, ``store_states`` not True) the grid is
        propagated in chunks of at most ~64 MB of states, each chunk starting from the
        last state of the previous one.
        """
        qutip = _lazy.qutip
        store_states = _validate.flag("store_states", store_states, allow_none=True)
        store_final_state = _validate.flag("store_final_state", store_final_state)
        vec = unit_state(psi0, self.dim)
        t = _validate.time_grid(t, allow_decreasing=False)
        e_ops = e_ops_list(e_ops, self.dims)
        store = store_states if store_states is not None else not e_ops
        self._priced("evolve", t, states=store)
        ropts = {"store_states": store_states, "store_final_state": store_final_state, "normalize_output": False}
        result = qutip.solver.Result(e_ops, ropts, solver=f"hyperrotor.evolve[{self.method}]", stats=dict(self.stats))
        ket_dims = [self.dims[0], [1]]
        chunk = t.size if store else max(2, 2**22 // max(1, self.dim))
        start = 0
        while start < t.size:
            stop = min(t.size, start + chunk)
            first = max(0, start - 1)  # the chunk starts at the time of vec (the previous chunk's last state)
            out = self._run(vec, t[first:stop], self.hbar)
            for k in range(start - first, out.shape[1]):
                result.add(float(t[first + k]), qutip.Qobj(out[:, k : k + 1].copy(), dims=ket_dims, copy=False))
            vec, start = out[:, -1].copy(), stop
        result.stats.update(self.stats)
        return result
