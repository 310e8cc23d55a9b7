r"""The cost models of the size-driven entry points (registered in :data:`hyperrotor._pricing.MODELS`).

Each model maps an entry point's sizes to its figures (:class:`~hyperrotor._pricing.Cost`: bytes of
working memory, single-core seconds, output bytes, dense dimensions), which
:func:`hyperrotor._pricing.check` compares with the named budgets. The constants were measured on
the reference machine by ``benchmarks/pricing.py`` (estimates within a factor ~3, docs/safety.md).
Imported by ``hyperrotor/__init__.py``, so every model is registered before any entry point runs.
"""
from __future__ import annotations

import math
from typing import Any

from ._pricing import Cost, as_float as _f, estimate, model

__all__ = ["SCENE_COST", "GIF_FRAME_BYTES", "SCENE_ELLIPSOID_POINTS", "scene_size"]


def _mul(*xs: Any) -> float:
    out = 1.0
    for x in xs:
        out *= _f(x)
    return out


def _memory(what: str, nbytes: float) -> Cost:
    return Cost(what, nbytes, "max_memory_bytes", "bytes")


def _seconds(what: str, seconds: float) -> Cost:
    return Cost(what, seconds, "max_seconds", "seconds")


def _n_planes(N: Any) -> float:
    N = _f(N)
    return N * (N - 1) / 2


def _pow2(k: Any) -> float:
    """``2.0 ** k`` as a float, infinite past the largest float (``2.0 ** 1e6`` raises OverflowError)."""
    k = _f(k)
    return 2.0 ** k if k < 1024 else math.inf


# ---------------------------------------------------------------------------------------------
# constants measured by benchmarks/pricing.py on the reference machine (2 cores, one thread)
# ---------------------------------------------------------------------------------------------
#: seconds per flop of a dense LAPACK eigh / eigvalsh (complex counts 4 real flops)
_EIGH_S = 8.0e-11
#: seconds per SymPy term operation (a product or sum of two monomials with rational coefficients)
_SYMPY_S = 2.0e-5
#: seconds per plane pair of the structure-constant table (a Python loop)
_PAIR_S = 1.3e-6
#: seconds per dim^3 of the dense products building the spinor generators
_DENSE_S = 2.0e-9
#: seconds per axis of the brackets of one plane with its neighbours (conventions._structure_constants_slice)
_BRACKET_S = 1.0e-5
#: seconds per dim^2 of real_form (its per-plane Python and sparse work; 7e-6 until session 48, when the dense
#: generators of its residual check, n_planes dim^3, became sparse products: so(3) l = 100 took 0.16 -> 0.07 s)
_REAL_FORM_S = 1.5e-6
#: seconds per term of the exact harmonic basis (a Fraction step and a SymPy monomial; measured
#: N = 3..8, l = 4..60: 1.1e-4 to 2.9e-4, growing with l as the integer coefficients grow)
_HARMONIC_TERM_S = 1.4e-4
#: seconds per pure-Python integer tuple operation (Freudenthal's recursion)
_PY_S = 3.0e-7
#: seconds per step of Freudenthal's root strings and coordinate (tuples of doubled integers; refitted in session 48)
_WEIGHT_STEP_S = 1.0e-6
#: seconds per dim^2 of the Lanczos highest-weight search
_LANCZOS_S = 6.0e-9
#: seconds per rate difference of the Casimir shift rule (n x V of them, built by blocks: 1.5 s for a body of
#: 19 900 distinct moments, N = 200), with the rest of a call's set-up that grows like it (2 s in all there, the
#: index tables built with NumPy; 0.13 s at N = 100; about a millisecond for a 3D body)
_SHIFT_S = 5.0e-9
#: seconds per output time of evolve (a state Qobj per time, expectation values)
_EVOLVE_S = 2.6e-5
#: seconds per unit of the phase ||H|| t / hbar of a block propagated by Lanczos / by expm_multiply (their products
#: and restarts; measured, so(3) irreps of dimension 201-2001, methods 'krylov' and 'expm_multiply': 1.8e-4 ...
#: 3.2e-4 and 7e-5; grown with the dimension as 1 + dim / 1e4)
_KRYLOV_PHASE_S = 2.5e-4
_EXPM_PHASE_S = 7.0e-5
#: the same for the rotations of a state (apply_rotation: Lanczos at tolerance 1e-14)
_ROTATION_PHASE_S = 8.5e-4
#: seconds per n^2 of a diagonalized block, per state column and propagation (otoc: the two dense products with the
#: block's eigenvectors; measured, the 2-4 sectors of so(3) irreps of dimension 201-4001: 0.65e-9 ... 1.0e-9)
_BLOCK_SQUARE_S = 1.0e-9
#: bytes held per stored output time of evolve besides the state's entries (Qobj and its data object)
_QOBJ_BYTES = 360.0
#: operator_product: seconds per (i, j, k) half-product (two DifferentialOperator compositions and sums, even of
#: empty operators; measured 5.9e-6 ... 6.4e-6, N = 10, 20) and per pair of composed terms, which grows with the
#: number of coordinates (the exponent tuples; measured 3.3e-6 + 1.9e-7 per coordinate, 10 ... 80 coordinates)
_OP_TRIPLE_S = 7.0e-6
_OP_PAIR_S = 4.0e-6
_OP_PAIR_COORD_S = 2.0e-7


# ---------------------------------------------------------------------------------------------
# the models: one per size-driven entry point
# ---------------------------------------------------------------------------------------------
@model("structure_constants")
def _structure_constants(N: Any) -> tuple[Cost, ...]:
    n = _n_planes(N)
    return (_memory(f"the structure-constant table of so({N}) ({n:.0f}^3 int8 entries)", n ** 3),
            _seconds(f"the structure-constant table of so({N}) ({n:.0f}^2 plane pairs in Python)", n * n * _PAIR_S))


@model("linearization")
def _linearization(N: Any) -> tuple[Cost, ...]:
    # the n x n Jacobian (zeros but for the 2 (N - 2) entries of the plane's brackets with its neighbours,
    # conventions._structure_constants_slice: Python per axis)
    n = _n_planes(N)
    return (_memory(f"the Jacobian of so({N}) ({n:.0f}^2 entries)", 8.0 * n * n + 16.0 * n),
            _seconds(f"the brackets of a plane of so({N}) with its {2 * (_f(N) - 2):.0f} neighbours",
                     _f(N) * _BRACKET_S))


@model("casimir_shift", "use a body with fewer planes")
def _casimir_shift(N: Any = None, n: Any = None) -> tuple[Cost, ...]:
    # the Casimir shift rule weighs every rate against every candidate value (n x n at most): a table of up to
    # 2^20 entries kept, beyond it built in blocks of candidates (classical/solvers/splitting.shift_rule)
    n = _n_planes(N) if n is None else _f(n)
    return (_memory(f"the Casimir shift of {n:.0f} planes (its table of rate differences)", 16.0 * min(n * n, 2**20)),
            _seconds(f"the set-up of {n:.0f} planes (the Casimir shift: n x n rate differences)",
                     1e-3 + _SHIFT_S * n * n))


@model("simulate", "use a body with fewer planes")
def _simulate(N: Any = None, n: Any = None) -> tuple[Cost, ...]:
    # the Casimir shift (above), the index tables of the flows (3 x n x (N - 2) entries, _kernels.rotation_tables)
    # and, for the step control's rate bound, of the coupled triples (9 entries per triple i < j < k: about
    # 12 N^3 bytes, step_control._triples)
    n = _n_planes(N) if n is None else _f(n)
    N = _f(N) if N is not None else (1.0 + math.sqrt(1.0 + 8.0 * n)) / 2.0
    (shift_memory, seconds) = _casimir_shift(n=n)
    tables = 24.0 * n * max(N - 2.0, 0.0) + 12.0 * N**3
    return (_memory(f"the set-up of {n:.0f} planes (the Casimir shift's table, the flows' and the triples' index "
                    f"tables)", shift_memory.amount + tables), seconds)


def _eigh_seconds(cubes: Any, complex: bool = True) -> float:
    """Seconds of dense ``eigh`` of blocks whose dimensions cubed sum to ``cubes`` (complex: 4 real flops)."""
    return (4.0 if complex else 1.0) * 4.0 / 3.0 * _f(cubes) * _EIGH_S


@model("dense_diagonalization", "use a representation whose symmetry sectors are smaller (rep=)")
def _dense_diagonalization(dim: Any, complex: bool = True, cubes: Any = None) -> tuple[Cost, ...]:
    # ``dim``: the largest block; ``cubes``: the sum of every block's dimension cubed (default dim^3, one block;
    # a review: 60 blocks of 400 were priced as one)
    d = _f(dim)
    item = 16.0 if complex else 8.0
    return (
        Cost(f"a dense block of dimension {dim}", d, "quantum_max_dense_dim", "dimension"),
        # sparse copies of the block (CSR: entry + index), the dense block and eigvalsh's copy
        _memory(f"a dense {dim} x {dim} block (and its sparse and working copies)", 6 * item * d * d),
        _seconds(f"diagonalizing a dense {dim} x {dim} block" + ("" if cubes is None else " and the others"),
                 _eigh_seconds(d ** 3 if cubes is None else _f(cubes), complex)),
    )


@model("highest_weight_state", "build the state from the Gelfand-Tsetlin basis directly")
def _highest_weight_state(dim: Any) -> tuple[Cost, ...]:
    # Lanczos (eigsh, tol 1e-14) for the top eigenvector of a Cartan combination whose eigenvalues are
    # equally spaced: the iterations grow like dim, each costs O(dim) (measured ~ dim^2 behaviour)
    # plus ~0.05 s of set-up (ARPACK's start, the Cartan combination), measured: dim 2001 took 0.07-0.12 s
    d = _f(dim)
    return (_seconds(f"the Lanczos search for the highest weight vector (dimension {dim})", 0.05 + _LANCZOS_S * d * d),)


@model("sectors_dense", "use irrep(N, highest_weight) (sparse sectors at any dimension)")
def _sectors_dense(dim: Any, N: Any = 3) -> tuple[Cost, ...]:
    # exp(pi X) of each chain plane and the projectors: ~N dense dim x dim complex matrices
    d = _f(dim)
    return (Cost(f"the dense symmetry sectors of a representation of dimension {dim}", d,
                 "sectors_dense_max_dim", "dimension"),
            # measured (benchmarks/pricing.py, tensor products of so(3), dim 603-1803): ~190 bytes per d^2 at the
            # peak and ~1.3e-8 s per d^3 (exponentials, projectors, their products), both scaling with N
            _memory(f"dense {dim} x {dim} complex matrices ({N} rotations and projectors)", 64.0 * _f(N) * d * d),
            _seconds(f"{N} dense matrix exponentials of dimension {dim}", _f(N) * 55.0 * d ** 3 * _EIGH_S))


@model("sector_spectra", "use a smaller representation or a body with more symmetry")
def _sector_spectra(dim: Any, real: bool = True, cubes: Any = None) -> tuple[Cost, ...]:
    # ``cubes``: the sum of the sectors' dimensions cubed (every sector is diagonalized, not only the largest; the
    # default 4 dim^3 is the real sectors of an so(3) irrep, 4 of about equal size: measured 4x one block's eigh,
    # l = 2000..8000; so(5) has 16 sectors, so(7) 64, a review found those 16-64x under-priced)
    d = _f(dim)
    item = 8.0 if real else 16.0
    flops = (1.0 if real else 4.0) * 4.0 / 3.0 * (4.0 * d ** 3 if cubes is None else _f(cubes))
    return (Cost(f"the largest sector (dimension {dim}) diagonalized densely", d, "sectors_max_block_dim", "dimension"),
            _memory(f"the dense {dim} x {dim} sector block (two copies)", 2.0 * item * d * d),
            _seconds(f"diagonalizing the dense sector blocks (the largest {dim} x {dim})", flops * _EIGH_S))


#: seconds per plane and dim^3 of the intertwiner's orthogonalisation (one lowering operator per positive root and
#: column against the columns so far) and of the real form's conjugation of each plane by the dense change of basis
#: (a review, session 48: intertwiner(irrep(30, (2, 0, ...))) 20 s and its real form 35 s against estimates of
#: 0.4 s and 1.5 s; measured with one BLAS thread after the residual's dense generators became sparse products:
#: so(8) (3, 1, 0, 0), dim 567, 1.7 s and 3.3 s; so(30) (2, 0, ...), dim 464, 6.2 s and 14.8 s)
_PLANE_DIM3_S = 1.5e-10
_REAL_FORM_PLANE_DIM3_S = 2.5e-10


@model("real_form")
def _real_form(dim: Any, planes: Any = 3) -> tuple[Cost, ...]:
    # a dense change of basis (dim x dim complex, a few copies), the intertwiner that gives it (the model
    # "dense_representation") and a per-plane dense conjugation
    d = _f(dim)
    return (_memory(f"dense {dim} x {dim} complex matrices (the change of basis and its copies)", 128.0 * d * d),
            _seconds(f"the real form of a representation of dimension {dim} ({planes} planes)",
                     _REAL_FORM_S * d * d + 50.0 * d ** 3 * _EIGH_S
                     + (_PLANE_DIM3_S + _REAL_FORM_PLANE_DIM3_S) * _f(planes) * d ** 3))


@model("dense_representation", "use irrep(N, highest_weight) of a smaller dimension")
def _dense_representation(dim: Any, copies: Any = 4, planes: Any = 0) -> tuple[Cost, ...]:
    # dense products, eigendecompositions or null spaces of dim x dim complex matrices; an intertwiner also one
    # orthogonalisation per plane (``planes``: its positive roots, as many as planes up to a factor 2)
    d = _f(dim)
    return (
        _memory(f"dense {dim} x {dim} complex matrices ({copies} of them)", 16.0 * _f(copies) * d * d),
        _seconds(f"dense O(dim^3) linear algebra at dimension {dim}" + (f" ({planes} planes)" if planes else ""),
                 50.0 * d ** 3 * _EIGH_S + _PLANE_DIM3_S * _f(planes) * d ** 3),
    )


@model("spinor_rep")
def _spinor_rep(N: Any) -> tuple[Cost, ...]:
    # the gamma matrices are Kronecker products built densely: N of them, 2^(N//2) square
    D = 2.0 ** (_f(N) // 2)
    return (_memory(f"the {N} gamma matrices (dimension 2^{_f(N) // 2:.0f}, dense)", 16.0 * (_f(N) + 2) * D * D),
            _seconds(f"the {N} gamma matrices and their products (dimension 2^{_f(N) // 2:.0f}, dense)",
                     _f(N) * D ** 3 * _DENSE_S))


@model("tensor")
def _tensor(dim_a: Any, dim_b: Any, nnz_a: Any, nnz_b: Any) -> tuple[Cost, ...]:
    # X_p (x) 1 + 1 (x) Y_p for every plane: nnz_a * dim_b + dim_a * nnz_b stored entries (complex + index),
    # built through COO (three arrays) and converted to CSR (a copy)
    entries = _mul(nnz_a, dim_b) + _mul(dim_a, nnz_b)
    return (_memory(f"the generators of a tensor product of dimension {_mul(dim_a, dim_b):.6g} "
                    f"({entries:.3g} nonzeros)", 30.0 * entries),)


@model("evolve", "ask for fewer output times (t) or a shorter span, or pass e_ops to keep expectation values "
                 "only")
def _evolve(dim: Any, n_times: Any, states: bool = True, krylov_phase: Any = 0.0, expm_phase: Any = 0.0
            ) -> tuple[Cost, ...]:
    # krylov_phase, expm_phase: sums over the blocks propagated by Lanczos / expm_multiply of ||H_b|| span / hbar
    # (SectorPropagator._stepping_phases), which their numbers of products follow
    per = (16.0 * _f(dim) + _QOBJ_BYTES) if states else 8.0
    stepped = _f(krylov_phase) * _KRYLOV_PHASE_S + _f(expm_phase) * _EXPM_PHASE_S
    return (
        Cost(f"{n_times} output states of dimension {dim}" if states else f"{n_times} output values",
             _f(n_times) * per, "max_output_bytes", "bytes"),
        _seconds(f"{n_times} output times" + (f" and the products of a phase ||H|| t / hbar = "
                                              f"{_f(krylov_phase) + _f(expm_phase):.3g}" if stepped else ""),
                 _f(n_times) * _EVOLVE_S + stepped * (1.0 + _f(dim) / 1e4)),
    )


@model("ehrenfest_time", "ask for fewer irreps (ls) or fewer times (t)")
def _ehrenfest_time(irreps: Any, dims: Any = None, dim_squares: Any = None, n_times: Any = None, n: Any = 3
                    ) -> tuple[Cost, ...]:
    # per irrep (measured on the 2-core reference machine, session 49): ~12 ms of set-up (the irrep, its
    # Hamiltonian, coherent state and sectors) and the expectation values of the n generators at every time; so(3)
    # (dimensions 3-3201, 5-200 times): ~1 ms per unit of dimension (the generators, the sectors' propagation) and
    # 1.7e-7 s per dim^2 (the few large sectors of an so(3) irrep: 5 s at dimension 3201); N >= 4 (n > 3), irreps
    # (l, 0, ...): many small sectors of which the coherent state populates few, ~8e-5 s per unit of dimension and
    # 5e-10 per dim^2 (so(4), so(5), dimensions 121-23821: the so(3) figures priced them 12-30x high). Without the
    # dimensions (a first check on the count alone) every irrep counts as dimension 1
    k = _f(irreps)
    K = 1.0 if n_times is None else _f(n_times)
    d1 = k if dims is None else _f(dims)
    d2 = k if dim_squares is None else _f(dim_squares)
    per_dim, per_square = (1.0e-3, 1.7e-7) if _f(n) <= 3.0 else (8e-5, 5e-10)
    what = f"{irreps} irreps (ls)" + ("" if n_times is None else f" x {n_times} times (t)")
    return (_seconds(what, k * (0.012 + K * _EVOLVE_S * _f(n)) + per_dim * d1 + per_square * d2),
            Cost(f"the quantum curves of {what} x {n} planes", 16.0 * _mul(k, K, n), "max_output_bytes", "bytes"))


@model("apply_rotation", "rotate by a smaller angle or use an irrep of smaller dimension")
def _apply_rotation(dim: Any, phase: Any, factors: Any = 1) -> tuple[Cost, ...]:
    # one Lanczos propagation exp(theta X_p) v per Givens factor, at tolerance quantum_rotation_atol: its products
    # follow the phase sum_k |theta_k| ||X_p_k|| (measured, so(3) irreps of dimension 501-4001, a generic
    # rotation: 8.5e-4 ... 1.0e-3 s per unit of phase)
    return (_seconds(f"{factors} plane rotations of a state of dimension {dim} (phase sum |theta| ||X|| = "
                     f"{_f(phase):.3g})", _f(phase) * _ROTATION_PHASE_S * (1.0 + _f(dim) / 1e4)),)


@model("otoc", "use fewer times (t) or fewer samples")
def _otoc(n_times: Any, columns: Any, dim: Any = 1, squares: Any = 0.0, cubes: Any = 0.0, complex: bool = True
          ) -> tuple[Cost, ...]:
    # four propagations of `columns` state columns to every time (the evolve model, states not kept), in the
    # eigenbases of the blocks of H: `squares` and `cubes` are the sums of n^2 and n^3 over the blocks, each
    # diagonalized once (dense eigh) and then applied to every column by two dense products (n^2 each)
    runs = 4.0 * _mul(n_times, columns)
    # the columns are propagated together (a matrix of states, no Qobj per time): ~3e-6 s per column and
    # time of each propagation and ~20 ms of set-up (measured, benchmarks/pricing.py, 100-4000 samples, dim 5)
    return (_seconds(f"{n_times} times (t) x {columns} state columns (samples or the exact trace) x 4 propagations"
                     f" in blocks of sum n^2 = {_f(squares):.3g}",
                     0.02 + runs * (3e-6 + _f(squares) * _BLOCK_SQUARE_S) + _eigh_seconds(cubes, complex)),
            # the blocks' dense copies and eigenvectors, kept for every propagation: ~80 bytes per n^2 at the peak
            # (measured, benchmarks/pricing.py, so(3) irreps of dimension 801 and 2001: 78-79 bytes)
            _memory(f"the dense blocks of H and their eigenvectors (sum n^2 = {_f(squares):.3g})", 80.0 * _f(squares)),
            Cost(f"{n_times} times (t) x {columns} state columns (samples or the exact trace)",
                 runs * (16.0 * _f(dim) + _QOBJ_BYTES) / 4.0, "max_output_bytes", "bytes"))


@model("lyapunov_sweep", "sweep fewer bodies per call")
def _lyapunov_sweep(bodies: Any, orbits: Any, n: Any, k: Any = 1) -> tuple[Cost, ...]:
    # per orbit: moments, rates, L0 (n each) and k orthonormal tangent vectors (n x k), a few copies
    rows = _mul(bodies, orbits)
    return (_memory(f"{rows:.6g} orbits ({bodies} bodies x {orbits} initial conditions)",
                    rows * 8.0 * _f(n) * (15.0 + 8.0 * _f(k))),)


@model("closed_form_output", "ask for fewer output times (t)")
def _closed_form_output(n_times: Any, width: Any) -> tuple[Cost, ...]:
    # the returned (K, width) float array and one temporary of the same size
    return (Cost(f"{n_times} output times x {width} values", 22.0 * _mul(n_times, width), "max_output_bytes", "bytes"),)


@model("hypercube_vertices", "ask for a smaller N")
def _hypercube_vertices(N: Any) -> tuple[Cost, ...]:
    # 2^N rows of N floats; on the way the shifted bits (int64) and a temporary of the same size
    rows = _pow2(N)
    entries = rows * _f(N)
    what = f"the 2^{N} vertices of the {N}-cube ({entries:.3g} coordinates)"
    return (Cost(what, 8.0 * entries, "max_output_bytes", "bytes"),
            _memory(what + " and their integer bits", 16.0 * entries + 8.0 * rows),
            # ~5e-9 s per coordinate, and ~1e-9 s per byte of the two tables when their pages are fresh (measured
            # 4.4e-9 s per coordinate with recycled pages, N = 16..20; 1.4e-8 ... 3.4e-8 with fresh ones, N = 19..22)
            _seconds(what, 0.01 + (5e-9 + 16.0 * 1e-9) * entries))


@model("ellipsoid_points", "ask for fewer points")
def _ellipsoid_points(n: Any, N: Any) -> tuple[Cost, ...]:
    return (Cost(f"{n} points in {N} dimensions", 24.0 * _mul(n, N), "max_output_bytes", "bytes"),)


@model("inertia_tensor", "use second_moment_matrix (N x N) instead of the rank-4 tensor")
def _inertia_tensor(N: Any, points: Any = 1) -> tuple[Cost, ...]:
    return (_memory(f"the rank-4 inertia tensor of dimension {N} ({N}^4 entries)", 24.0 * _f(N) ** 4),
            _seconds(f"the rank-4 inertia tensor of dimension {N} ({points} points)",
                     _f(N) ** 4 * (1.0 + _f(points)) * 2e-9))


#: seconds per point x N^2 of the second moments (a BLAS product of the scaled points)
_MOMENT_PRODUCT_S = 2.0e-11
#: seconds per point x N of the second moments (scaling, centring and weighting the points: NumPy passes)
_MOMENT_POINT_S = 1.5e-8
#: seconds per N^3 of the principal axes (LAPACK eigh and scipy's linear_sum_assignment matching them to the axes)
_PRINCIPAL_AXES_S = 2.0e-10


@model("second_moment_matrix", "use fewer points or fewer dimensions")
def _second_moment_matrix(N: Any, points: Any) -> tuple[Cost, ...]:
    # the points scaled, centred and weighted (three copies of points x N) and the N x N product
    N, P = _f(N), _f(points)
    return (_memory(f"the second moments of {P:.6g} points in {N:.0f} dimensions", 24.0 * P * N + 24.0 * N * N),
            _seconds(f"the second moments of {P:.6g} points in {N:.0f} dimensions",
                     P * N * N * _MOMENT_PRODUCT_S + P * N * _MOMENT_POINT_S))


@model("principal_axes", "use fewer dimensions")
def _principal_axes(N: Any) -> tuple[Cost, ...]:
    # eigh of the N x N second moments and the assignment of its eigenvectors to the input axes (N x N costs)
    N = _f(N)
    return (_memory(f"the principal axes in {N:.0f} dimensions", 48.0 * N * N),
            _seconds(f"the principal axes in {N:.0f} dimensions", N * N * N * _PRINCIPAL_AXES_S + N * N * 1e-7))


@model("body_edges", "draw fewer points")
def _body_edges(pairs: Any) -> tuple[Cost, ...]:
    # a Python loop over the candidate pairs, each kept as a tuple in a list
    return (_memory(f"{_f(pairs):.6g} candidate edges", 120.0 * _f(pairs)),
            _seconds(f"{_f(pairs):.6g} candidate edges", 3e-7 * _f(pairs)))


@model("dense_matrix", "use format='csr'")
def _dense_matrix(dim: Any, count: Any = 1) -> tuple[Cost, ...]:
    d = _f(dim)
    return (_memory(f"{count} dense {dim} x {dim} complex matrices", 16.0 * _f(count) * d * d),)


# --- the command line ----------------------------------------------------------------------
#: Cost constants of ``hyperrotor scene`` (seconds; first measured by the cli helper on a shared, loaded 2-core
#: machine: --N 12 cube PNG 15.8 s wall against 13.7 s estimated; pages (.html) cube N = 5, 8, 10:
#: 4.1, 9.1, 46 s against 6.4, 15.6, 55 s, 0.26, 0.32, 0.56 GB peak against 0.30, 0.35, 0.44 GB; refitted in
#: session 46 on an idle 2-core AMD EPYC, where they had become 4-5x high: the default PNG 1.3-1.55 s, a GIF of 60
#: frames 5.2 s, --N 12 PNG 2.8 s, pages N = 5 / 10 1.3 / 13.2 s, now estimated 1.6-2.3x those, room for a slower
#: or loaded machine):
#: start-up (imports), per drawn frame, per drawn edge and point of a frame, per frame-plane of the
#: motion, per cube vertex and axis^2 (finding the edges), and ~14 copies of a page's text.
SCENE_COST = {"start": 2.0, "frame_png": 0.15, "frame_gif": 0.1, "frame_html": 0.01, "edge": 1.5e-5,
              "point": 1e-5, "html_edge": 6e-5, "html_point": 2e-5, "html_copies": 14,
              "motion": 2e-7, "cube_edges": 1e-6}
#: the command's interpreter before its data: Python with NumPy, SciPy, SymPy, numba and matplotlib or plotly
#: (peak RSS of ``hyperrotor scene --N 4`` 178 MB, of its imports alone 175-200 MB; session 48, a review measured the
#: memory model against the peak RSS and found it 3.5-8x low: this, and the snapshots' panels below)
SCENE_START_BYTES = 1.8e8
#: matplotlib's bytes per edge of one panel (a ``Line3DCollection`` of the projected segments; each of the six
#: snapshots of a PNG keeps its own: peak RSS over the imports 2.7 kB per edge at N = 12, 13, 14)
SCENE_EDGE_BYTES = 450
#: Pillow keeps every RGBA frame of a GIF until the file is written
GIF_FRAME_BYTES = 540 * 480 * 4
#: points of the ellipsoid body of ``hyperrotor scene --shape ellipsoid``
SCENE_ELLIPSOID_POINTS = 400


def scene_size(shape: str, N: int) -> tuple[float, float]:
    """Number of body points and of drawn edges of ``hyperrotor scene`` (floats: 2^N may be huge)."""
    if shape == "cube":
        n = min(N, 200)  # past 2^200 nothing fits anyway; keeps every estimate a finite float
        return 2.0**n, n * 2.0 ** (n - 1)
    if shape == "simplex":
        return N + 1.0, (N + 1.0) * N / 2
    return float(SCENE_ELLIPSOID_POINTS), 0.0


@model("scene", "use a smaller --N, --shape simplex or fewer --frames")
def _scene(shape: str, N: int, frames: Any, format: str = ".png", integrate: bool = False,
           colour: bool = True) -> tuple[Cost, ...]:
    """Memory (bytes, budget ``cli_max_memory``) and wall time (s, ``cli_max_seconds``) of ``hyperrotor scene``.

    Memory: the interpreter with its libraries (:data:`SCENE_START_BYTES`), body points ``P x N``, the edge list
    (about 120 bytes per edge as Python tuples, plus the cube's grouping ``P x (60 + 40 N)``), the attitudes
    ``K x N^2`` (4 copies) and projections ``K x P x 4`` (2 copies), the drawn segments of each panel
    (:data:`SCENE_EDGE_BYTES` per edge: the six snapshots of a PNG, the one panel of a GIF), for a GIF every
    rendered frame, for a page copies of its text (:func:`hyperrotor.classical.scene_html.scene_html_bytes`). Time:
    :data:`SCENE_COST` (an integrated motion is priced by ``simulate``'s own estimate).
    """
    P, E = scene_size(shape, N)
    K = _f(frames)
    c = SCENE_COST
    memory = (SCENE_START_BYTES + P * N * 8 + E * 120 + (P * (60 + 40 * N) if shape == "cube" else 0)
              + 4 * K * N * N * 8 + 2 * K * P * 4 * 8)
    seconds = (c["start"] + K * N * N * c["motion"] * (50 if integrate else 1)
               + (P * N * N * c["cube_edges"] if shape == "cube" else 0))
    if format == ".html":  # the page's bytes: the "Scene.to_html" model (registered by classical/scene_html.py)
        page = sum(c.amount for c in estimate("Scene.to_html", n_times=int(min(K, 2**62)), n_points=int(min(P, 2**62)),
                                              n_edges=int(min(E, 2**62)), colour=colour))
        memory += c["html_copies"] * page
        seconds += K * (c["frame_html"] + E * c["html_edge"] + P * c["html_point"])
    else:
        gif = format == ".gif"
        drawn = K if gif else min(6.0, K)
        memory += E * SCENE_EDGE_BYTES * (1.0 if gif else drawn) + (K * GIF_FRAME_BYTES if gif else 0)
        seconds += drawn * (c["frame_gif" if gif else "frame_png"] + E * c["edge"] + P * c["point"])
    what = f"scene --N {N} --shape {shape} ({frames} frames)"
    return (Cost(what, memory, "cli_max_memory", "bytes"), Cost(what, seconds, "cli_max_seconds", "seconds"))


# --- SymPy and exact-arithmetic constructions ------------------------------------------------
@model("casimir_operator")
def _casimir_operator(N: Any) -> tuple[Cost, ...]:
    # sum over n planes of L_a^2 (each 2-term operator squared), merged into a total of O(N^2) terms:
    # measured ~ n * N (N = 16..100: 3.6e-6 s per n * N) and ~0.01 s of set-up
    n = _n_planes(N)
    return (_seconds(f"the symbolic Casimir of so({N}) ({n:.0f} squared generators)", 0.01 + n * _f(N) * 0.18 * _SYMPY_S),)


@model("angular_momentum_operators")
def _angular_momentum_operators(N: Any) -> tuple[Cost, ...]:
    n = _n_planes(N)
    return (_seconds(f"the {n:.0f} symbolic generators of so({N})", n * 3.0 * _SYMPY_S),)


@model("harmonic_polynomial_basis", "use irrep(N, (l,)), the same representation in the Gelfand-Tsetlin basis")
def _harmonic_polynomial_basis(N: Any, l: Any) -> tuple[Cost, ...]:
    dim = _harmonic_dim(N, l)
    terms = _harmonic_terms(N, l)
    # every term of every polynomial is made once (exact Fractions, then a SymPy monomial): measured
    # ~1.4e-4 s per term, a little more at high degree (larger integer coefficients)
    return (_harmonic_space(N, l, dim),
            _seconds(f"{dim:.6g} harmonic polynomials of degree {l} in {N} variables ({terms:.6g} terms)",
                     terms * _HARMONIC_TERM_S * (1.0 + _f(l) / 80.0)))


@model("orthonormal_harmonic_basis", "use irrep(N, (l,)), the same representation in the Gelfand-Tsetlin basis")
def _orthonormal_harmonic_basis(N: Any, l: Any) -> tuple[Cost, ...]:
    # the orthogonal basis (its model), then the exact square roots of the norms: ~0.05 s and ~1 ms per polynomial
    # (measured session 48: N = 3 l = 6 / 10 0.062 / 0.123 s, N = 4 l = 5 0.103 s; the model of every monomial per
    # pair of polynomials it replaced was 2-5x high)
    dim = _harmonic_dim(N, l)
    return (_harmonic_space(N, l, dim),
            _seconds(f"the exact Gram-Schmidt of {dim:.6g} harmonic polynomials of degree {l} and their norms",
                     _orthogonal_basis_seconds(N, l) + 0.05 + 1e-3 * dim))


def _orthogonal_basis_seconds(N: Any, l: Any) -> float:
    # the Gram-Schmidt's pairs of polynomials (Python bookkeeping per pair) and their products, ~1.5 l terms per
    # polynomial whatever N (measured, session 48: 1.0-1.65 l for N = 3 ... 30); counting every monomial of the
    # space per pair was 27x high at N = 40, l = 2 (a review). Measured N = 3 l = 14 0.057 s, N = 12 l = 3 2.8 s,
    # N = 30 l = 2 5.2 s
    dim = _harmonic_dim(N, l)
    return 2.4e-5 * dim * dim + 1.5e-7 * (1.5 * max(_f(l), 1.0) * dim) ** 2


@model("orthogonal_harmonic_basis", "use irrep(N, (l,)), the same representation in the Gelfand-Tsetlin basis")
def _orthogonal_harmonic_basis(N: Any, l: Any) -> tuple[Cost, ...]:
    dim = _harmonic_dim(N, l)
    return (_harmonic_space(N, l, dim),
            _seconds(f"the exact Gram-Schmidt of {dim:.6g} harmonic polynomials of degree {l}",
                     _orthogonal_basis_seconds(N, l)))


@model("harmonic_rep", "use irrep(N, (l,)), the same representation in the Gelfand-Tsetlin basis")
def _harmonic_rep(N: Any, l: Any) -> tuple[Cost, ...]:
    # the basis, then per plane the operator applied to every polynomial (~1.5 l terms each) and the dense
    # change to the basis (dim x monomials x dim): measured N = 20 l = 2 1.7 s, N = 30 l = 2 15 s (session 48: the
    # planes' work, 44.6 s at N = 40, was not priced)
    dim = _harmonic_dim(N, l)
    monomials = _binomial(_f(l) + _f(N) - 1, _f(N) - 1)
    planes = _n_planes(N)
    return (_harmonic_space(N, l, dim),
            _seconds(f"so({N}) on the {dim:.6g} harmonic polynomials of degree {l} ({planes:.0f} planes)",
                     _orthogonal_basis_seconds(N, l)
                     + planes * dim * (1.2e-5 * max(_f(l), 1.0) + 2.2e-10 * dim * monomials)))


@model("bivector_product_table")
def _bivector_product_table(N: Any) -> tuple[Cost, ...]:
    n = _n_planes(N)
    return (_seconds(f"the {n:.0f} x {n:.0f} symbolic product table", n * n * 3.0 * _SYMPY_S),)


@model("euler_equations")
def _euler_equations(N: Any) -> tuple[Cost, ...]:
    # n equations, each a sum over the planes that share an axis with the plane (2(N-2) products), and the
    # functions omega_ij(t): measured ~4.4e-5 s per n^2 (N = 6..14) and ~0.01 s of set-up
    n = _n_planes(N)
    return (_seconds(f"the {n:.0f} symbolic Euler equations of so({N})", 0.01 + n * n * 2.2 * _SYMPY_S),)


@model("symbolic_rhs", "use rhs (numeric moments) or a body of fewer dimensions")
def _symbolic_rhs(N: Any, numeric: bool = False) -> tuple[Cost, ...]:
    # n components, each a sum over the 2(N-2) planes that share an axis with the plane, of products
    # (I_c - I_b) w_b w_c, divided by I_a: measured 6e-5 ... 8.4e-5 s per n * N (N = 10..40, growing slowly with N
    # as the sums get longer) and 0.03-0.08 s of set-up (SymPy's first calls); with numeric moments (SymPy Floats)
    # about 3x that (the review of session 46 measured 3.9-4.4x the symbolic model at N = 20..30)
    n = _n_planes(N)
    return (_seconds(f"the {n:.0f} symbolic right-hand sides of so({N}) ({n:.0f} sums of {2 * (_f(N) - 2):.0f} "
                     f"products)", 0.05 + (9.0 if numeric else 3.0) * n * _f(N) * _SYMPY_S * (1.0 + _f(N) / 60.0)),)


#: seconds per product of two Pfaffian terms of the symbolic Casimirs (SymPy; measured 1.3-1.6e-4 at N = 5..8)
_CASIMIR_TERM_S = 1.6e-4
#: seconds per closed walk of the symbolic Manakov traces (SymPy; measured 2.8-2.9e-4 at N = 5, 6)
_MANAKOV_WALK_S = 2.9e-4


@model("symbolic_casimirs", "use numeric values or a body of fewer dimensions")
def _symbolic_casimirs(N: Any) -> tuple[Cost, ...]:
    # c_2k = the sum over the C(N, 2k) principal 2k x 2k submatrices of their squared Pfaffians, each of (2k - 1)!!
    # terms: sum_k C(N, 2k) ((2k - 1)!!)^2 products of terms to expand (N = 10: 1.4e6, 484 s measured by a review)
    N = int(_f(N))
    # logarithms: C(N, 2k) = (N)! / ((2k)! (N - 2k)!), (2k - 1)!! = (2k)! / (2^k k!) (the numbers pass 1e308 at N ~ 170)
    logs = [math.lgamma(N + 1) - math.lgamma(N - 2 * k + 1) + math.lgamma(2 * k + 1) - 2 * k * math.log(2.0)
            - 2 * math.lgamma(k + 1) for k in range(1, N // 2 + 1)]
    terms = sum(math.exp(x) if x < 700.0 else math.inf for x in logs)
    return (_seconds(f"the symbolic Casimirs of so({N}) ({terms:.3g} products of Pfaffian terms)",
                     0.01 + terms * _CASIMIR_TERM_S),)


@model("symbolic_manakov", "use numeric values or a body of fewer dimensions")
def _symbolic_manakov(N: Any) -> tuple[Cost, ...]:
    # tr((L + lam J^2)^k), k = 2..N, expanded: about N^k closed walks of length k through the N x N matrix entries
    # (N = 6: 15 s; N = 7: minutes)
    N = _f(N)
    walks = sum(N ** k if k * math.log10(max(N, 1.0)) < 300 else math.inf for k in range(2, int(N) + 1))
    return (_seconds(f"the symbolic Manakov integrals of so({N:.0f}) ({walks:.3g} closed walks of the matrix)",
                     0.01 + walks * _MANAKOV_WALK_S),)


#: seconds per step of poincare_section beyond its flows: the event function evaluated in Python at every step state
_EVENT_STEP_S = 2.0e-6
#: seconds per crossing of poincare_section (Brent's method on the step it falls in: ~10 one-step re-integrations)
_CROSSING_S = 3.0e-4


@model("poincare_section", "shorten T or give a larger dt")
def _poincare_section(N: Any, steps: Any, turns: Any, stages: Any = 17) -> tuple[Cost, ...]:
    # steps of stages (2n - 2) + 1 flows (the method's stages: splitting8 17; ~2e-8 s each, more for the longer
    # flows of larger N: chunks.flow_weight), the event evaluated at every step, and the crossings located: about
    # 0.05 per radian of the fastest rate (turns = T w_max; measured 0.007-0.15 over random bodies N = 3..8)
    N, n = _f(N), _n_planes(N)
    flow = 2.0e-8 * max(1.0, ((N - 2.0) / 3.0) ** 0.8)  # (flatter than chunks.flow_weight here: measured N = 3..16)
    step = (_f(stages) * (2.0 * n - 2.0) + 1.0) * flow + _EVENT_STEP_S
    crossings = min(0.05 * _f(turns), _f(steps))  # (at most one per step: a sign change between two step states)
    return (_seconds(f"{_f(steps):.3g} steps of so({N:.0f}) with an event at each and ~{crossings:.3g} crossings",
                     _f(steps) * step + crossings * _CROSSING_S),)


@model("operator_product", "multiply smaller operator matrices")
def _operator_product(N: Any, pairs: Any, coords: Any) -> tuple[Cost, ...]:
    # 2 N^3 compositions of matrix entries (N x N x N, twice) and their sums; `pairs`: the pairs of terms composed
    # (sum over k of the products of the term counts), each an exponent-tuple operation over the coordinates; the
    # running sums grow with N (+ N / 200)
    triples = 2.0 * _f(N) ** 3
    per_pair = _OP_PAIR_S + _OP_PAIR_COORD_S * _f(coords)
    return (_seconds(f"the product of two {N} x {N} operator matrices ({_f(pairs):.3g} pairs of terms in {coords} "
                     f"coordinates)", (triples * _OP_TRIPLE_S + _f(pairs) * per_pair) * (1.0 + _f(N) / 200.0)),)


@model("operator_composition", "compose operators of fewer terms")
def _operator_composition(pairs: Any, coords: Any) -> tuple[Cost, ...]:
    # every pair of terms composed by Leibniz's rule (WeylElement.compose); per pair the operator_product constants
    # (casimir_operator(16) composed with itself: 141 376 pairs, 0.64 s, estimated 1.0 s; N = 20: 1.85 s, 2.8 s)
    # and ~200-250 bytes of the result's terms (traced: 181, 198, 236 bytes per pair at N = 8, 16, 24)
    what = f"composing two differential operators ({_f(pairs):.3g} pairs of terms in {coords} coordinates)"
    return (_seconds(what, _f(pairs) * (_OP_PAIR_S + _OP_PAIR_COORD_S * _f(coords))),
            _memory(what, _f(pairs) * (150.0 + 4.0 * _f(coords))))


@model("polynomial_expansion", "give the polynomial expanded, or of fewer terms")
def _polynomial_expansion(terms: Any, coords: Any) -> tuple[Cost, ...]:
    # SymPy's expand and Poly of an expression whose expanded form has up to `terms` terms (normal_form.expanded_terms,
    # exact for powers of sums): measured 3.9e-4 ... 4.7e-4 s per term ((x1 + ... + x5)^10 ... ^20, 1001 ... 10 626
    # terms: 0.39 ... 4.98 s; ^30 ran 23 s under max_seconds = 1 before this model), ~1 kB per SymPy term
    what = f"expanding a polynomial of up to {_f(terms):.3g} terms in {coords} coordinates"
    return (_seconds(what, 1e-3 + 6e-4 * _f(terms)), _memory(what, 1000.0 * _f(terms)))


@model("contraction_identity", "use a smaller N")
def _contraction_identity(N: Any) -> tuple[Cost, ...]:
    # the operator matrix of so(N) (angular_momentum_operators) and its product with its transpose: 2 terms per
    # off-diagonal entry, so 2 N (2 (N - 1))^2 pairs of terms in N coordinates (either form)
    pairs = 8.0 * _f(N) * (_f(N) - 1.0) ** 2
    product = _operator_product(N=N, pairs=pairs, coords=N)[0].amount
    generators = _angular_momentum_operators(N)[0].amount
    return (_seconds(f"the contraction identity of so({N}) (a product of {N} x {N} operator matrices, "
                     f"{pairs:.3g} pairs of terms)", product + generators),)


@model("vector_rep", "use a smaller N")
def _vector_rep(N: Any, exact: bool = False) -> tuple[Cost, ...]:
    # one sparse N x N generator per plane (a COO -> CSR conversion and the Representation's checks: its row
    # pointers are N + 1 int32, plus ~1.5 kB of objects); exact: one SymPy N x N matrix per plane (two entries set;
    # SymPy keeps ~1.4 kB per matrix, measured N = 100..300)
    n = _n_planes(N)
    if exact:
        return (_memory(f"the {n:.0f} exact SymPy generators of the vector rep of so({N})", n * 1800.0),
                _seconds(f"the {n:.0f} exact SymPy generators of the vector rep of so({N})", n * 2.5e-5))
    return (_memory(f"the {n:.0f} sparse generators of the vector rep of so({N})", n * (1500.0 + 4.0 * _f(N))),
            _seconds(f"the {n:.0f} sparse generators of the vector rep of so({N})", n * 1.0e-4))


@model("adjoint_rep", "use a smaller N")
def _adjoint_rep(N: Any, exact: bool = False) -> tuple[Cost, ...]:
    # one n x n generator per plane, cut from the structure constants (priced by their own model) as a dense float
    # slice and converted to CSR; exact: one SymPy n x n matrix per plane, filled entry by entry in Python (SymPy
    # keeps its 2(N - 2) nonzeros: measured ~3 kB + 63 n bytes per matrix, and one dense n x n list on the way)
    n = _n_planes(N)
    if exact:
        return (_memory(f"the {n:.0f} exact SymPy generators of the adjoint rep of so({N}) ({n:.0f} x {n:.0f} each)",
                        n * (3000.0 + 80.0 * n) + 8.0 * n * n),
                _seconds(f"the {n:.0f} exact SymPy generators of the adjoint rep of so({N}) ({n:.0f}^3 entries)",
                         n ** 3 * 2.5e-6))
    return (_memory(f"the {n:.0f} generators of the adjoint rep of so({N}) (dense {n:.0f} x {n:.0f} slices)",
                    24.0 * n * n + n * (1500.0 + 4.0 * n)),
            _seconds(f"the {n:.0f} generators of the adjoint rep of so({N}) ({n:.0f}^3 dense entries)",
                     n ** 3 * 5e-9 + n * 1.2e-4))


@model("plane_symbols")
def _plane_symbols(N: Any) -> tuple[Cost, ...]:
    n = _n_planes(N)
    return (_seconds(f"{n:.0f} SymPy symbols", n * 1.0e-5),)


@model("weight_multiplicities", "use weyl_dimension for the dimension only")
def _weight_multiplicities(rank: Any, n_roots: Any, dim: Any, bound: Any, weights: Any = None) -> tuple[Cost, ...]:
    # Freudenthal: every distinct weight (``weights``: counted by weights.weight_count; else at most
    # min(dim, (bound + 1)^rank)) sums over the positive roots and the strings mu + k alpha inside the bounding box
    # (``bound``: the largest doubled coordinate, k up to about bound / 2). The box estimate was 51-373x high for
    # rank 4-5 (a review, session 48)
    w = min(_f(dim), (_f(bound) + 1.0) ** _f(rank)) if weights is None else _f(weights)
    ops = w * _f(n_roots) * (0.5 * _f(bound) + 1.0)
    return (_seconds(f"Freudenthal's recursion over ~{w:.3g} weights", ops * (1.0 + 0.5 * _f(rank)) * _WEIGHT_STEP_S),)


def _harmonic_space(N: Any, l: Any, dim: float) -> Cost:
    return Cost(f"the harmonic polynomials of degree {l} in {N} variables (exact rational construction)", dim,
                "quantum_max_harmonic_dim", "dimension")


def _binomial(a: float, b: float) -> float:
    if not (math.isfinite(a) and math.isfinite(b)):
        return math.inf
    if not 0 <= b <= a:
        return 0.0
    try:
        if a < 1e5:  # exact (a dimension compared with a budget must not round up)
            return float(math.comb(int(a), int(b)))
        # a huge, k small: the product (a - k + 1) ... a / k! (lgamma differences of numbers near 1e15 lost all
        # their digits: the harmonic dimension of l = 1e15 came out 0 and the budget let it run); k > 1000 and
        # a >= 2k: at least comb(2002, 1001) > 1e600, beyond a float
        k = int(min(b, a - b))
        if k > 1000:
            return math.inf
        out = 1.0
        for i in range(1, k + 1):
            out *= (a - k + i) / i
        return out
    except OverflowError:  # beyond a float (comb(1499, 999) of N = 1000, l = 500)
        return math.inf


def _harmonic_terms(N: Any, l: Any) -> float:
    """Number of terms of :func:`~hyperrotor.quantum.harmonic_polynomial_basis`: the polynomial seeded by
    :math:`x'^a x_N^\\varepsilon` (``|a| = l - eps`` in ``m = N - 1`` variables) has one term per
    ``b <= a/2``, :math:`\\prod_i (\\lfloor a_i/2 \\rfloor + 1)`; summed over ``a``, the coefficient of
    :math:`x^d` in :math:`(1 - x)^{-m} (1 - x^2)^{-m}`, i.e. :math:`\\sum_j \\binom{j+m-1}{m-1}\\binom{d-2j+m-1}{m-1}`
    (exact below degree 2000; above, its asymptote :math:`\\binom{d+2m-1}{2m-1} / 2^m`)."""
    m, l = _f(N) - 1.0, _f(l)
    total = 0.0
    for d in (l, l - 1.0):
        if d < 0:
            continue
        if d < 2000:
            total += sum(_binomial(j + m - 1, m - 1) * _binomial(d - 2 * j + m - 1, m - 1) for j in range(int(d) // 2 + 1))
        else:
            total += _binomial(d + 2 * m - 1, 2 * m - 1) / 2.0 ** min(m, 1e4)
    return total


def _harmonic_dim(N: Any, l: Any) -> float:
    """Dimension of the harmonic polynomials of degree ``l`` in ``N`` variables: exact below 1e5, else the closed
    form :math:`\frac{2l + N - 2}{l + N - 2}\binom{l + N - 2}{N - 2}` (the difference of the two binomials below
    cancels to nothing in floats: 0 for ``N = 3, l = 1e15`` instead of ``2l + 1``)."""
    N, l = _f(N), _f(l)
    if not (math.isfinite(N) and math.isfinite(l)):
        return math.inf
    if l < 0:
        return 0.0
    if N < 3:  # one variable: 1, x; two: the real and imaginary parts of (x + iy)^l
        return (1.0 if l < 2 else 0.0) if N < 2 else (1.0 if l == 0 else 2.0)
    if l + N < 1e5:  # exact (a dimension compared with a budget must not round up)
        try:
            return float((2 * int(l) + int(N) - 2) * math.comb(int(l + N) - 2, int(N) - 2) // (int(l + N) - 2))
        except OverflowError:  # beyond a float (N = 1000, l = 500)
            return math.inf
    return (2.0 * l + N - 2.0) / (l + N - 2.0) * _binomial(l + N - 2, N - 2)
