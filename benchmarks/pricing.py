"""Estimate vs measured cost of every priced entry point (hyperrotor._pricing, issue #21).

For every entry point with a cost model (a model without a case is listed at the end), a few sizes
below the budgets are run: the CPU
time of this process (process_time, one run, no tracing; BLAS and OpenMP limited to one thread,
so it is single-core time and does not depend on the load of the machine) and the peak traced
memory (tracemalloc, a second run; only for entries whose model prices memory) are printed
next to the model's estimate,
with their ratio (estimate / measured; the models aim at a factor ~3 either way). A plot
of estimate against measured is written to benchmarks/results/pricing.png.

    python benchmarks/pricing.py            # the table: every model (~10 min of CPU on the 2-core machine)
    python benchmarks/pricing.py --quick    # the smallest size of each entry only
    python benchmarks/pricing.py --only otoc,scene   # these entries only (no plot unless --plot)
    python benchmarks/pricing.py --list     # the priced entries without a case (none)

Estimates of memory are bytes of working memory; estimates of time are single-core seconds
on the reference machine. Tiny measurements (below 20 ms or 1 MB) are dominated by fixed
overheads and are not part of the verdict.
"""
from __future__ import annotations

import argparse
import gc
import math
import os
import sys
import time
import tracemalloc

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

import sympy as sp  # noqa: E402

import hyperrotor as hr  # noqa: E402
import hyperrotor.quantum as hq  # noqa: E402
from hyperrotor import _pricing  # noqa: E402
from hyperrotor.classical.mass_points import principal_axes as _principal_axes  # noqa: E402
from hyperrotor.classical.solvers._kernels import rotation_tables  # noqa: E402
from hyperrotor.classical.solvers.splitting import _shift_candidates  # noqa: E402
from hyperrotor.conventions import _structure_constants, plane_symbols  # noqa: E402
from hyperrotor.demo import DEMO_OMEGA, compare_quartet_motion  # noqa: E402
from hyperrotor.quantum.operator_products import _term_pairs  # noqa: E402
from hyperrotor.quantum.weights import weight_count  # noqa: E402


def _moments(N):
    n = N * (N - 1) // 2
    return 1.0 + np.arange(n) / n


def _herm(d):
    rng = np.random.default_rng(0)
    A = rng.standard_normal((d, d)) + 1j * rng.standard_normal((d, d))
    return A + A.conj().T


def _nnz(rep):
    return sum(g.nnz for g in rep.generators().values())


def cases():
    """(entry, label, sizes for the model, setup -> argument, run(argument))."""
    out = []
    for N in (20, 30, 40):
        out.append(("structure_constants", f"N={N}", dict(N=N), lambda N=N: _structure_constants.cache_clear(),
                    lambda _, N=N: hr.structure_constants(N)))
    for N in (35, 60, 100):
        out.append(("linearization", f"N={N}", dict(N=N), lambda N=N: _moments(N),
                    lambda m: hr.linearization(m, (1, 2), 1.0)))
    for N in (40, 100, 200):
        out.append(("simulate", f"N={N}", dict(N=N),
                    lambda N=N: (_warm(), _shift_candidates.cache_clear(), rotation_tables.cache_clear(),
                                 _moments(N))[3],
                    lambda m: hr.simulate(m, 1e-3 * np.ones(m.size), [0.0, 1e-3], method="splitting4")))
    for d in (500, 1000, 2000):
        out.append(("dense_diagonalization", f"dim={d}", dict(dim=d), lambda d=d: _herm(d), hq.spectrum))
    for l in (100, 200, 400):
        out.append(("real_form", f"l={l}", dict(dim=2 * l + 1, planes=3), lambda l=l: hq.irrep(3, (l,)),
                    hq.real_form))
        out.append(("dense_representation", f"intertwiner l={l}", dict(dim=2 * l + 1, planes=3),
                    lambda l=l: hq.irrep(3, (l,)), lambda a: hq.intertwiner(a, a)))
    for N, w in ((8, (3, 1, 0, 0)), (20, (2,) + (0,) * 9), (30, (2,) + (0,) * 14)):  # many planes (review, s48)
        dim, n = hq.weyl_dimension(N, w), N * (N - 1) // 2
        out.append(("real_form", f"so({N}) {w[:4]}..., dim {dim}", dict(dim=dim, planes=n),
                    lambda N=N, w=w: hq.irrep(N, w), hq.real_form))
        out.append(("dense_representation", f"intertwiner so({N}) {w[:4]}..., dim {dim}", dict(dim=dim, planes=n),
                    lambda N=N, w=w: hq.irrep(N, w), lambda a: hq.intertwiner(a, a)))
    for N in (10, 14, 18):
        out.append(("spinor_rep", f"N={N}", dict(N=N), lambda: None, lambda _, N=N: hq.spinor_rep(N)))
    for l in (50, 100, 200):
        a = hq.irrep(3, (l,))
        out.append(("tensor", f"l={l} x l={l}", dict(dim_a=a.dim, dim_b=a.dim, nnz_a=_nnz(a), nnz_b=_nnz(a)),
                    lambda a=a: a, lambda a: hq.tensor(a, a)))
    for K in (10**3, 10**4, 10**5):
        out.append(("evolve", f"{K} times, dim 5", dict(dim=5, n_times=K),
                    lambda: hq.rotor_hamiltonian(hq.irrep(3, (2,)), [1.0, 2.0, 3.0]),
                    lambda H, K=K: hq.evolve(H, np.ones(5) / 5**0.5, np.linspace(0.0, 1.0, K))))
    def _rotor(l):
        rep = hq.irrep(3, (l,))
        return rep, hq.rotor_hamiltonian(rep, [1.0, 2.0, 3.0])

    for l, T in ((100, 0.5), (400, 0.1), (1000, 0.02)):  # products: a phase ||H|| t / hbar, not output times
        rep, H = _rotor(l)
        prop = hq.SectorPropagator(H, method="krylov")
        out.append(("evolve", f"krylov dim {rep.dim}, t = [0, {T:g}]",
                    dict(dim=rep.dim, n_times=2, **prop._stepping_phases(np.array([0.0, T]))),
                    lambda H=H: H, lambda H, T=T: hq.evolve(H, np.ones(H.shape[0]) / H.shape[0] ** 0.5, [0.0, T],
                                                            method="krylov")))
    from scipy.spatial.transform import Rotation
    from hyperrotor.quantum.coherent import _givens_angles

    Q = Rotation.from_rotvec([0.9, -1.7, 1.1]).as_matrix()
    for l in (250, 1000, 2000):
        rep = hq.irrep(3, (l,))
        gens = rep.generators()
        phase = sum(abs(th) * float(abs(gens[p]).sum(axis=1).max()) for p, th in _givens_angles(Q))
        out.append(("apply_rotation", f"dim={rep.dim}", dict(dim=rep.dim, phase=phase, factors=3), lambda rep=rep: rep,
                    lambda rep: hq.apply_rotation(rep, Q, np.ones(rep.dim) / rep.dim**0.5)))
    for ls, K in (([1] * 50, 5), ([10, 40, 80], 200), ([100, 200], 100), ([1600], 100)):
        dims = [2 * l + 1 for l in ls]
        out.append(("ehrenfest_time", f"{len(ls)} irreps, {K} times",
                    dict(irreps=len(ls), dims=sum(dims), dim_squares=sum(d * d for d in dims), n_times=K, n=3),
                    lambda: None, lambda _, ls=ls, K=K: hq.ehrenfest_time([1.0, 2.0, 3.0], [0.3, 0.2, 1.0], ls,
                                                                            np.linspace(0.0, 3.0, K))))
    for N, ls, K in ((4, [10, 30], 100), (5, [25], 100), (5, [40], 100)):  # (the coherent states of a simple L0)
        hws = [(l,) + (0,) * (N // 2 - 1) for l in ls]
        dims = [float(hq.weyl_dimension(N, hw)) for hw in hws]
        n = N * (N - 1) // 2
        out.append(("ehrenfest_time", f"so({N}) l = {ls}, {K} times",
                    dict(irreps=len(ls), dims=sum(dims), dim_squares=sum(d * d for d in dims), n_times=K, n=n),
                    lambda: None,
                    lambda _, N=N, n=n, ls=ls, K=K: hq.ehrenfest_time(np.linspace(1.0, 2.0, n),
                                                                      np.r_[0.6, 0.8, np.zeros(n - 2)], ls,
                                                                      np.linspace(0.0, 3.0, K))))
    for n in (500, 1000, 2000):
        out.append(("dense_diagonalization", f"sample_spectrum gue n={n}", dict(dim=n, complex=True), lambda: None,
                    lambda _, n=n: hq.sample_spectrum("gue", n, rng=1)))
    for P in (10**3, 10**4, 10**5):
        out.append(("lyapunov_sweep", f"{P} bodies", dict(bodies=P, orbits=1, n=3),
                    lambda P=P: 1.0 + np.random.default_rng(0).random((P, 3)),
                    lambda b: hr.lyapunov_sweep(b, np.ones((1, 3)), 1e-3)))
    for l in (1000, 3000, 6000):
        out.append(("highest_weight_state", f"dim={2 * l + 1}", dict(dim=2 * l + 1),
                    lambda l=l: hq.irrep(3, (l,)), hq.highest_weight_state))
    for N in (8, 16, 24):
        out.append(("casimir_operator", f"N={N}", dict(N=N), lambda: None, lambda _, N=N: hq.casimir_operator(N)))
    for N, l in ((3, 20), (3, 40), (4, 12)):
        out.append(("harmonic_polynomial_basis", f"N={N} l={l}", dict(N=N, l=l), _clear_harmonic_caches,
                    lambda _, N=N, l=l: hq.harmonic_polynomial_basis(N, l)))
    for N, l in ((3, 6), (3, 10), (4, 5)):
        out.append(("orthonormal_harmonic_basis", f"N={N} l={l}", dict(N=N, l=l), _clear_harmonic_caches,
                    lambda _, N=N, l=l: hq.orthonormal_harmonic_basis(N, l)))
    for N in (40, 80, 120):
        out.append(("angular_momentum_operators", f"N={N}", dict(N=N), lambda: None,
                    lambda _, N=N: hq.angular_momentum_operators(N)))
    for N in (100, 200, 300):
        out.append(("plane_symbols", f"N={N}", dict(N=N), lambda: None, lambda _, N=N: hr.plane_symbols(f"q{N}", N)))
    for K in (10**5, 10**6):
        out.append(("closed_form_output", f"quartet_solution {K} times N=5", dict(n_times=K, width=10), lambda: None,
                    lambda _, K=K: hr.quartet_solution(0.5, np.linspace(0.1, 1.0, 10), np.linspace(0, 1, K))))
    for N in (6, 10, 14):
        out.append(("bivector_product_table", f"N={N}", dict(N=N), lambda: None,
                    lambda _, N=N: hr.bivector_product_table(N)))
    for N in (6, 10, 14):
        out.append(("euler_equations", f"N={N}", dict(N=N), lambda N=N: hr.RigidBody(hr.Inertia.symbolic(N)),
                    lambda b: b.euler_equations()))
    for N in (10, 20, 30):
        out.append(("symbolic_rhs", f"N={N}", dict(N=N), lambda N=N: _symbolic_body(N), lambda b: b.symbolic_rhs()))
        out.append(("symbolic_rhs", f"N={N}, numeric moments", dict(N=N, numeric=True),
                    lambda N=N: _numeric_body(N), lambda b: b.symbolic_rhs()))
    for N, seed, T, method, stages in ((3, 1, 3000.0, "splitting8", 17), (5, 1, 3000.0, "splitting8", 17),
                                       (8, 5, 1000.0, "splitting8", 17), (5, 1, 3000.0, "splitting2", 1),
                                       (16, 2, 60.0, "splitting2", 1), (5, 1, 3000.0, "splitting10", 35)):
        out.append(("poincare_section", f"N={N}, T={T:g}, {method}",
                    dict(N=N, stages=stages, **_poincare_sizes(N, seed, T)),
                    lambda N=N, seed=seed, method=method: (
                        hr.poincare_section(*_random_orbit(N, seed), 1.0, method=method),  # (compiled)
                        _random_orbit(N, seed))[1],
                    lambda mw, T=T, method=method: hr.poincare_section(*mw, T, method=method)))
    for N, P in ((5, 300_000), (50, 100_000), (500, 2000)):
        out.append(("second_moment_matrix", f"N={N}, {P} points", dict(N=N, points=P),
                    lambda N=N, P=P: (np.ones(P), np.random.default_rng(P).normal(size=(P, N))),
                    lambda mr: hr.second_moment_matrix(*mr)))
    for N in (100, 300, 1000):
        out.append(("principal_axes", f"N={N}", dict(N=N), lambda N=N: _spd(N), lambda M: _principal_axes(M)))
    for N in (6, 7, 8):
        out.append(("symbolic_casimirs", f"N={N}", dict(N=N), lambda N=N: hr.RigidBody(hr.Inertia.equal(N, 1)),
                    lambda b: b.casimirs(plane_symbols("L", b.N), of="L")))
    for N, numeric in ((5, False), (6, False), (6, True)):
        out.append(("symbolic_manakov", f"N={N}" + (", numeric J" if numeric else ""), dict(N=N),
                    lambda N=N, numeric=numeric: hr.RigidBody(hr.Inertia.from_mass_tensor(
                        np.linspace(1.0, 2.0, N) if numeric else list(sp.symbols(f"J1:{N + 1}", positive=True)))),
                    lambda b: b.manakov_integrals(plane_symbols("L", b.N), of="L")))
    for N in (10, 20, 30):
        out.append(("contraction_identity", f"N={N}", dict(N=N), lambda: None,
                    lambda _, N=N: hq.contraction_identity(N)))
    for label, make in (("operator_matrix(20) x its transpose", lambda: _operator_pair(20, 20)),
                        ("10 x 10 block of operator_matrix(80)", lambda: _operator_pair(80, 10)),
                        ("second-order entries, N=8", lambda: _operator_pair(8, 8, square=True))):
        A, B = make()
        out.append(("operator_product", label, dict(N=A.shape[0], pairs=_term_pairs(A, B, "eq144"),
                                                    coords=A[0, 0].N),
                    lambda A=A, B=B: (A, B), lambda x: hq.operator_product(*x)))
    for N in (12, 16, 20):  # commutator of a Casimir operator with itself: two compositions of its terms
        out.append(("operator_composition", f"commutator(casimir_operator({N}), itself)",
                    dict(pairs=2 * len(hq.casimir_operator(N).element.terms) ** 2, coords=N),
                    lambda N=N: hq.casimir_operator(N), lambda C: hq.commutator(C, C)))
    for n, k in ((5, 10), (5, 15), (4, 25)):
        out.append(("polynomial_expansion", f"(x1 + ... + x{n})^{k}",
                    dict(terms=math.comb(n + k - 1, k), coords=n), lambda n=n: hq.coordinate_symbols(n),
                    lambda x, k=k: hq.polynomial_to_dict(sum(x) ** k, x)))
    for N in (100, 200, 400):
        out.append(("vector_rep", f"N={N}", dict(N=N), lambda: None, lambda _, N=N: hq.vector_rep(N)))
    for N in (100, 200, 300):
        out.append(("vector_rep", f"N={N}, exact generators", dict(N=N, exact=True), lambda N=N: hq.vector_rep(N),
                    lambda rep: rep.exact_generators()))
    for N in (16, 24, 32):
        out.append(("adjoint_rep", f"N={N} (structure constants cached)", dict(N=N),
                    lambda N=N: hr.structure_constants(N), lambda _, N=N: hq.adjoint_rep(N)))
    for N in (8, 12, 14):
        out.append(("adjoint_rep", f"N={N}, exact generators", dict(N=N, exact=True), lambda N=N: hq.adjoint_rep(N),
                    lambda rep: rep.exact_generators()))
    for N in (16, 19, 22):
        out.append(("hypercube_vertices", f"N={N}", dict(N=N), lambda: None, lambda _, N=N: hr.hypercube_vertices(N)))
    for N, hw in ((3, (500,)), (3, (1500,)), (4, (20, 10)), (5, (6, 3)), (8, (6, 4, 4, 3)), (10, (6, 4, 3, 2, 1))):
        sizes = dict(rank=len(hw), n_roots=len(hq.positive_roots(N)), dim=hq.weyl_dimension(N, hw), bound=2 * hw[0],
                     weights=weight_count(N, tuple(2 * x for x in hw)))
        out.append(("weight_multiplicities", f"N={N} {hw}", sizes, lambda: None,
                    lambda _, N=N, hw=hw: hq.weight_multiplicities(N, hw)))
    # --- the other models (issue #21: every priced entry point)
    for N in (100, 200, 300):
        out.append(("Inertia", f"N={N} (list of floats)", dict(n=N * (N - 1) // 2), lambda N=N: _moments(N).tolist(),
                    hr.Inertia))
    for N in (60, 100, 150):
        out.append(("RigidBody", f"N={N} (and its Euler tables)", dict(N=N), lambda N=N: _moments(N),
                    lambda m: hr.RigidBody(m).rhs_tables))
    for N in (40, 60, 80):
        out.append(("casimir_shift", f"N={N}", dict(n=N * (N - 1) // 2),
                    lambda N=N: (_shift_candidates.cache_clear(), _moments(N))[1], hr.casimir_shift))
    for N in (20, 40, 60):
        out.append(("Inertia.tensor", f"N={N}", dict(N=N), lambda N=N: hr.Inertia(np.ones(N * (N - 1) // 2)),
                    lambda inertia: inertia.tensor()))
    for N in (20, 40, 60):
        out.append(("inertia_tensor", f"N={N}, 10 points", dict(N=N, points=10),
                    lambda N=N: np.random.default_rng(0).standard_normal((10, N)),
                    lambda x: hr.inertia_tensor(np.ones(len(x)), x)))
    for B in (10, 20, 40):
        out.append(("quartet_frequencies", f"N=300, {B} initial conditions", dict(N=300, batch=B),
                    lambda B=B: np.random.default_rng(0).standard_normal((B, 44850)),
                    lambda w: hr.quartet_frequencies(0.5, w, 5)))
    for N in (300, 600, 900):
        nw = N * (N - 1) // 2
        def start(nw=nw):
            return np.random.default_rng(0).standard_normal(nw)

        out.append(("quartet_solution", f"N={N}, 3 times", dict(d=N - 1), start,
                    lambda w: hr.quartet_solution(0.5, w, [0.0, 1.0, 2.0])))
        out.append(("quartet_attitude", f"N={N}, 3 times", dict(d=N, count=2, n_times=3), start,
                    lambda w: hr.quartet_attitude(0.5, w, [0.0, 1.0, 2.0])))
        out.append(("closed_form_solution", f"quartet N={N}, 3 times", dict(d=N - 1),
                    lambda N=N, nw=nw: (hr.Inertia.quartet(0.5, N=N), np.random.default_rng(0).standard_normal(nw)),
                    lambda x: hr.closed_form_solution(x[0], x[1], [0.0, 1.0, 2.0])))
    for N in (100, 200, 400):
        out.append(("stability_condition", f"N={N}", dict(N=N), lambda: None,
                    lambda _, N=N: hr.stability_condition((1, 2), N)))
    for K in (100, 500, 2000):
        out.append(("Scene.to_html", f"{K} times, 5-cube (page bytes)", dict(n_times=K, n_points=32, n_edges=80),
                    lambda K=K: hr.Scene(_moments(5), 0.3 * np.ones(10), np.linspace(0.0, 10.0, K),
                                         points=hr.hypercube_vertices(5)),
                    _page_bytes, "output"))
    for n in (1000, 2000, 3000):
        out.append(("body_edges", f"simplex of {n} points", dict(pairs=n * (n - 1) // 2),
                    lambda n=n: np.random.default_rng(0).standard_normal((n, 3)), lambda x: hr.body_edges(x, "simplex")))
    for n in (10**5, 10**6, 4 * 10**6):
        out.append(("ellipsoid_points", f"{n} points, N=3", dict(n=n, N=3), lambda: None,
                    lambda _, n=n: hr.ellipsoid_points([1.0, 2.0, 3.0], n)))
    for l in (500, 1000, 2000):
        out.append(("dense_matrix", f"generator of irrep l={l}, dense", dict(dim=2 * l + 1),
                    lambda l=l: hq.irrep(3, (l,)), lambda a: a.generator((1, 2), format="dense")))
    for N, hw in ((3, (99999,)), (5, (20, 10)), (6, (6, 3, 1)), (7, (3, 2, 1))):
        sizes = dict(dim=hq.weyl_dimension(N, hw), N=N)
        out.append(("irrep", f"N={N} {hw}", sizes, lambda: None,
                    lambda _, N=N, hw=hw: hq.irrep(N, hw, max_dim=10**6).generators(format="csr")))
        out.append(("gt_patterns", f"N={N} {hw}", sizes, lambda: None,
                    lambda _, N=N, hw=hw: hq.gt_patterns(N, hw, max_dim=10**6)))
    for N, hw in ((5, (20, 10)), (20, (2, 1) + (0,) * 8), (40, (1, 1, 1) + (0,) * 17), (80, (1,) + (0,) * 39)):
        out.append(("gt_generators", f"N={N} {hw[:4]}...", dict(dim=hq.weyl_dimension(N, hw), N=N), lambda: None,
                    lambda _, N=N, hw=hw: hq.irrep(N, hw).generators(format="csr")))
    for N, hw in ((3, (30000,)), (3, (99999,)), (5, (20, 10))):
        out.append(("gt_sectors", f"N={N} {hw}", dict(dim=hq.weyl_dimension(N, hw), N=N),
                    lambda N=N, hw=hw: hq.irrep(N, hw), hq.symmetry_sectors))
    for a, b in ((50, 1), (100, 1), (200, 1)):
        dim = (2 * a + 1) * (2 * b + 1)
        out.append(("sectors_dense", f"tensor l={a} x l={b} (dim {dim})", dict(dim=dim, N=3),
                    lambda a=a, b=b: hq.tensor(hq.irrep(3, (a,)), hq.irrep(3, (b,))), hq.symmetry_sectors))
    for l in (1000, 2000, 4000):
        out.append(("sector_spectra", f"irrep l={l}", _largest_sector(l), lambda l=l: hq.irrep(3, (l,)),
                    lambda a: hq.sector_spectra(a, [1.0, 2.0, 3.0])))
    for l, S in ((2, 100), (2, 1000), (2, 4000), (100, 20), (400, 20), (1000, 20)):
        out.append(("otoc", f"5 times, {S} samples, dim {2 * l + 1}", _otoc_price(l, S), lambda l=l: _otoc_inputs(l),
                    lambda x, S=S: hq.otoc(*x, samples=S)))
    for N, l in ((3, 6), (3, 10), (3, 14), (12, 3), (20, 2)):
        out.append(("orthogonal_harmonic_basis", f"N={N} l={l}", dict(N=N, l=l), _clear_harmonic_caches,
                    lambda _, N=N, l=l: hq.orthogonal_harmonic_basis(N, l)))
    for N, l in ((3, 14), (8, 3), (12, 3), (20, 2)):  # (the basis and every plane's matrix, its caches cleared)
        out.append(("harmonic_rep", f"N={N} l={l}", dict(N=N, l=l), _clear_harmonic_caches,
                    lambda _, N=N, l=l: hq.harmonic_rep(N, l)))
    for e in (10**4, 2 * 10**4, 4 * 10**4):
        out.append(("sphere_integral", f"exponents ({e},) * 3", dict(degree=3 * e), lambda: None,
                    lambda _, e=e: hq.sphere_monomial_integral((e, e, e))))
    for N in (300, 600, 1000):
        hw = tuple(range(N // 2, 0, -1))
        bits = len(hq.positive_roots(N)) * math.log2(2 * (2 * float(max(hw)) + N) + 1)
        out.append(("weyl_product", f"N={N}, rho-like weight", dict(bits=bits), lambda: None,
                    lambda _, N=N, hw=hw: hq.weyl_dimension(N, hw)))
    for kappa, t_end, n_times in ((2.0, 50.0, 2001), (2.0, 200.0, 2001), (2.0, 800.0, 2001), (6.0, 400.0, 2001),
                                  (1000.0, 30.0, 2001), (0.5, 10.0, 100001)):
        out.append(("compare_quartet_motion", f"kappa={kappa:g}, t_end={t_end:g}, n_times={n_times} (warm kernels)",
                    dict(t_end=t_end, n_times=n_times, **_quartet_rates(kappa)), _warm_quartet,
                    lambda _, k=kappa, t_end=t_end, n=n_times: compare_quartet_motion(k, t_end=t_end, n_times=n)))
    slow = tuple(0.01 * w for w in DEMO_OMEGA)  # (the motion over 100 t_end at omega0 / 100: the same cost)
    out.append(("compare_quartet_motion", "kappa=2, omega0 / 100, t_end=20000, n_times=2001 (warm kernels)",
                dict(t_end=2e4, n_times=2001, speed=0.01, **_quartet_rates(2.0, slow)), _warm_quartet,
                lambda _: compare_quartet_motion(2.0, slow, t_end=2e4)))
    for N, frames in ((4, 6), (6, 6), (8, 6), (12, 6), (13, 6)):
        out.append(("scene", f"hyperrotor scene --N {N} --shape cube, PNG (child process, CPU s, peak RSS)",
                    dict(shape="cube", N=N, frames=frames, format=".png"), lambda: None,
                    lambda _, N=N: _cli_scene(N), "child"))
    return out


def _cli_scene(N):
    """CPU seconds and peak resident bytes of ``hyperrotor scene`` in a child process of its own (the 'scene'
    model prices the whole command, start-up and interpreter included, against the CLI budgets)."""
    import subprocess
    import tempfile

    child = ("import resource, sys, time\n"
             "from hyperrotor.cli import main\n"
             "code = main(sys.argv[1:])\n"
             "r = resource.getrusage(resource.RUSAGE_SELF)\n"
             "hwm = [l for l in open('/proc/self/status') if l.startswith('VmHWM:')][0].split()[1]\n"
             "print(r.ru_utime + r.ru_stime, int(hwm) * 1024)\n"  # (the peak of this process's memory: ru_maxrss
             # keeps the parent's across exec on Linux)
             "sys.exit(code)\n")
    with tempfile.TemporaryDirectory() as tmp:
        p = subprocess.run([sys.executable, "-c", child, "scene", "--N", str(N), "--shape", "cube",
                            "--output", os.path.join(tmp, "s.png")], check=True, capture_output=True, text=True,
                           env=dict(os.environ, MPLBACKEND="Agg"))
    cpu, rss = p.stdout.split()[-2:]
    return float(cpu), float(rss)


def _warm():
    """The compiled kernels loaded (a process's first call of them costs ~0.15 s, whatever N: not the set-up)."""
    hr.simulate(np.linspace(1.0, 2.0, 15), 1e-3 * np.ones(15), [0.0, 1e-3], method="splitting4")


def _spd(N):
    """A random symmetric positive definite N x N matrix (second moments)."""
    A = np.random.default_rng(N).normal(size=(N, N))
    return A @ A.T


def _random_orbit(N, seed):
    """Log-uniform plane moments in [0.3, 3] and a normal omega0 (seeded)."""
    g = np.random.default_rng(seed)
    n = N * (N - 1) // 2
    return np.exp(g.uniform(np.log(0.3), np.log(3.0), n)), g.normal(size=n)


def _poincare_sizes(N, seed, T):
    """poincare_section's sizes for its model: steps at its default step and turns T w_max."""
    from hyperrotor._options import options
    from hyperrotor.classical.solvers.step_control import rate_bound

    m, w = _random_orbit(N, seed)
    wmax = float(rate_bound(m[None], (w * m)[None])[0])
    return dict(steps=T * wmax / options["lyapunov_step"], turns=T * wmax)


def _numeric_body(N):
    body = hr.RigidBody(np.linspace(1.0, 2.0, N * (N - 1) // 2))
    body.rhs_tables
    return body


def _symbolic_body(N):
    body = hr.RigidBody(hr.Inertia.symbolic(N))
    body.rhs_tables  # (priced by the model 'RigidBody', not by 'symbolic_rhs')
    return body


def _operator_pair(coords, N, square=False):
    """An N x N block of operator_matrix(coords) and its transpose (square: entries L_ij L_ji + L_ij, 2nd order)."""
    M = hq.operator_matrix(coords)[:N, :N].copy()
    if square:
        M = np.array([[M[i, j] * M[j, i] + M[i, j] for j in range(N)] for i in range(N)], dtype=object)
    return M, M.T.copy()


def _clear_harmonic_caches():
    """Forget the cached harmonic bases (the models price a first call; the bases of one (N, l) are shared by
    harmonic_polynomial_basis, orthogonal_ and orthonormal_harmonic_basis)."""
    from hyperrotor.quantum import harmonic

    harmonic._harmonic_dicts.cache_clear()
    harmonic._orthogonal.cache_clear()


def _page_bytes(scene):
    """The bytes of the page written by Scene.to_html (what the model 'Scene.to_html' estimates)."""
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "scene.html")
        scene.to_html(path)
        return os.path.getsize(path)


def _largest_sector(l):
    secs = hq.symmetry_sectors(hq.irrep(3, (l,)))
    return dict(dim=max(s.basis.shape[1] for s in secs), real=all(s.real for s in secs))


def _otoc_inputs(l=2):
    import qutip

    H = hq.rotor_hamiltonian(hq.irrep(3, (l,)), [1.0, 2.0, 3.0])
    W = qutip.Qobj(np.diag(np.arange(l, -l - 1, -1.0)))
    return H, W, W, np.linspace(0.0, 1.0, 5)


def _otoc_price(l, S):
    """The sizes otoc prices itself by (its blocks: hq.otoc's own computation, no diagonalization)."""
    H = _otoc_inputs(l)[0]
    U = hq.SectorPropagator(H)
    sizes = np.array(U.apply_blocks(), dtype=float)
    return dict(n_times=5, columns=S, dim=2 * l + 1, squares=float(np.sum(sizes ** 2)),
                cubes=float(np.sum(sizes ** 3)), complex=U.matrix.dtype.kind == "c")


def _quartet_rates(kappa, omega=DEMO_OMEGA):
    from hyperrotor.demo import _body, _motion_rates

    rate, frequency = _motion_rates(kappa, _body(kappa, 5)[0], np.asarray(omega), 5)
    return dict(rate=rate, frequency=frequency)


def _warm_quartet():
    compare_quartet_motion(2.0, t_end=1.0)  # the model prices warm kernels: compile first


def measure(setup, run, memory, mode="memory"):
    """CPU seconds of one run, and the peak traced memory of a second run (``mode="output"``: the
    bytes the run returns it produced, e.g. the size of a written page)."""
    arg = setup()
    gc.collect()
    t0 = time.process_time()
    produced = run(arg)
    wall = time.process_time() - t0
    peak = None
    if mode == "output":
        return wall, produced
    if mode == "child":  # the run measured a child process itself: CPU seconds and its peak resident bytes
        return produced
    if memory:
        arg = setup()
        gc.collect()
        tracemalloc.start()
        run(arg)
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    return wall, peak


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="the smallest size of each entry only")
    ap.add_argument("--plot", default=None, help="where to write the plot (default: benchmarks/results/pricing.png "
                    "for a full run; none with --only or --quick, which would replace it with a part)")
    ap.add_argument("--only", default="", help="comma-separated entry names: run these models only")
    ap.add_argument("--list", action="store_true", help="list the priced entries without a case and exit")
    args = ap.parse_args(argv)
    if args.plot is None and not (args.only or args.quick):
        args.plot = os.path.join(os.path.dirname(__file__), "results", "pricing.png")
    only = {x.strip() for x in args.only.split(",") if x.strip()}
    all_cases = cases()
    missing = sorted(set(_pricing.MODELS) - {c[0] for c in all_cases})
    if args.list:
        print("priced entries without a case:", ", ".join(missing) or "none")
        return 0
    rows, seen = [], set()
    print(f"load: {os.getloadavg()[0]:.2f}   (estimate / measured; time: CPU s of one core, memory: peak traced bytes)")
    print(f"| entry | size | est. s | meas. s | ratio | est. MiB | meas. MiB | ratio |")
    print(f"| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    with hr.options(max_seconds=1e300, max_memory_bytes=2**62, max_output_bytes=2**62):
        for entry, label, sizes, setup, run, *mode in all_cases:
            if (args.quick and entry in seen) or (only and entry not in only):
                continue
            seen.add(entry)
            costs = _pricing.estimate(entry, **sizes)
            est_s = sum(c.amount for c in costs if c.unit == "seconds") or None
            est_b = sum(c.amount for c in costs if c.unit == "bytes") or None
            wall, peak = measure(setup, run, est_b is not None, *mode)
            r_s = est_s / wall if est_s and wall > 0.02 else None
            r_b = est_b / peak if est_b and peak and peak > 2**20 else None
            rows.append((entry, label, est_s, wall, r_s, est_b, peak, r_b))
            f = lambda x, fmt: "" if x is None else format(x, fmt)  # noqa: E731
            print(f"| {entry} | {label} | {f(est_s, '.3g')} | {wall:.3g} | {f(r_s, '.2f')} | "
                  f"{f(est_b and est_b / 2**20, '.3g')} | {f(peak and peak / 2**20, '.3g')} | {f(r_b, '.2f')} |",
                  flush=True)
    ratios = [r for row in rows for r in (row[4], row[7]) if r is not None]
    if ratios:
        print(f"\n{len(ratios)} ratios: min {min(ratios):.2f}, max {max(ratios):.2f}, "
              f"within a factor 3: {sum(1 / 3 <= r <= 3 for r in ratios)}/{len(ratios)}")
    print(f"priced entries without a case: {', '.join(missing) or 'none'} ({len(_pricing.MODELS)} models)")
    if not args.plot:
        return 0
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, axs = plt.subplots(1, 2, figsize=(10, 4.5))
        for ax, (ie, im, unit) in zip(axs, ((2, 3, "s"), (5, 6, "bytes"))):
            pts = [(row[im], row[ie], row[0]) for row in rows if row[ie] and row[im]]
            for m, e, name in pts:
                ax.loglog(m, e, "o", label=name)
            if pts:
                lo = min(min(p[0], p[1]) for p in pts) / 2
                hi = max(max(p[0], p[1]) for p in pts) * 2
                for k in (1 / 3, 1, 3):
                    ax.loglog([lo, hi], [k * lo, k * hi], "k" + ("-" if k == 1 else ":"), lw=0.8)
            ax.set_xlabel(f"measured ({unit})")
            ax.set_ylabel(f"estimated ({unit})")
        handles, labels = axs[0].get_legend_handles_labels()
        uniq = dict(zip(labels, handles))
        fig.legend(uniq.values(), uniq.keys(), fontsize=7, loc="lower center", ncol=4)
        fig.tight_layout(rect=(0, 0.15, 1, 1))
        os.makedirs(os.path.dirname(args.plot), exist_ok=True)
        fig.savefig(args.plot, dpi=110)
        print(f"plot: {args.plot}")
    except ImportError:  # matplotlib is optional for the table
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
