"""Benchmark: every level of a generic-inertia so(5) rotor, sector path vs full dense diagonalization.

Two parts (issue #16):

* comparison (default): so(5) irreps of dimension ~1,000 - 6,000 with ten
  independent plane moments; the peer is the full dense diagonalization of the
  rotor Hamiltonian (``numpy.linalg.eigvalsh(H.toarray())``, complex Hermitian:
  the matrix in the Gelfand-Tsetlin basis is complex); the sector path is
  ``sector_spectra`` (build the sectors, project, 16 real symmetric ``eigvalsh``),
  one sector after the other. Both timed in the same run (best of ``--repeats``),
  the spectra compared (max |difference| / max |E|). Writes
  ``benchmarks/results/sectors.csv`` and ``sectors.png``.
* ``--classes``: the irrep classes that #24 changed (so(5) spinor: real gauge; so(4) (44, 0)
  and so(6) (5, 2, 0): reflection parity; so(6) (5, 3, 1): complex type, real gauge), dense vs
  sectors in one run; the script also runs on the tree before #24 (the same calls), for the
  before/after table.
* ``--scale``: the 52,976-dimensional irrep (20, 10) (or ``--highest-weight 29,14``,
  dim 212,280, the stretch target of #24: < 30 min, < 6 GB), every level, once; wall time
  of each stage, peak resident memory (``resource.getrusage``), and the checks
  sum(levels) = tr H, sum(levels^2) = ||H||_F^2. A dense diagonalization would need
  16 * 52,976^2 bytes = 45 GB for the complex matrix alone. Writes
  ``benchmarks/results/sectors_scale.csv``.

The machine is shared: the load average (``os.getloadavg``) is recorded with each row, and
the comparison runs both paths on ONE BLAS thread (``--blas-threads``): with two OpenBLAS
threads on this loaded 2-core machine a dense eigvalsh ran ~4x slower than with one.

Usage: python benchmarks/sectors.py [--quick] [--repeats R] [--blas-threads T]
       python benchmarks/sectors.py --classes [--output NAME.csv]
       python benchmarks/sectors.py --scale [--highest-weight M1,M2] [--workers W]
"""
from __future__ import annotations

import argparse
import os
import resource
import time

import numpy as np

from hyperrotor.bench import best_of, write_csv
from hyperrotor.quantum import irrep, rotor_hamiltonian
from hyperrotor.quantum.sectors import sector_spectra, symmetry_sectors

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")
#: ten independent plane moments (planes 12, 13, ..., 45): a generic, non-Manakov body
MOMENTS = np.array([1.0, 1.31, 1.77, 2.05, 1.52, 2.43, 1.18, 2.91, 1.66, 2.27])
IRREPS = [(7, 3), (8, 5), (9, 5), (10, 6), (14, 2)]  # dims 1190, 2090, 3080, 4485, 6045
QUICK = [(7, 3), (8, 5)]


def _load() -> float:
    return round(os.getloadavg()[0], 2)


def _hamiltonian(rep, moments):
    """The rotor Hamiltonian as CSR (the same call on the trees before and after #24)."""
    return rotor_hamiltonian(rep, moments).data.as_scipy().tocsr()


def _peak_rss_gb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20  # kB -> GB (Linux)


def compare(irreps, repeats: int) -> list[dict]:
    rows = []
    for hw in irreps:
        rep = irrep(5, hw)
        H = _hamiltonian(rep, MOMENTS)
        t_dense, E_dense = best_of(lambda: np.linalg.eigvalsh(H.toarray()), repeats)
        t_sec, spec = best_of(lambda: sector_spectra(rep, MOMENTS), repeats)
        E_sec = spec.eigenvalues()
        err = float(np.abs(E_sec - E_dense).max() / np.abs(E_dense).max())
        row = {
            "highest_weight": f"({hw[0]}, {hw[1]})", "dim": rep.dim, "sectors": len(spec),
            "largest_sector": max(len(v) for v in spec.values()),
            "dense_s": round(t_dense, 3), "sectors_s": round(t_sec, 3),
            "speedup": round(t_dense / t_sec, 1), "max_rel_diff": f"{err:.1e}", "load": _load(),
        }
        rows.append(row)
        print(row, flush=True)
    return rows


#: irreps of the classes that #24 changed: spinor (real gauge: complex -> real blocks), even N with a
#: highest weight ending in 0 (reflection parity: twice as many sectors), so(6) complex type (real gauge)
CLASSES = [(5, ("15/2", "9/2")), (4, ("44", "0")), (6, ("5", "2", "0")), (6, ("5", "3", "1"))]


def _moments(N: int) -> np.ndarray:
    """N(N-1)/2 generic plane moments (MOMENTS for so(5))."""
    k = np.arange(N * (N - 1) // 2)
    return MOMENTS[k] if N == 5 else 1.0 + (0.618034 * (k + 1)) % 1.0


def compare_classes(repeats: int) -> list[dict]:
    """Dense eigvalsh of the whole H vs sector_spectra for the classes of #24 (run it on old and new trees)."""
    from fractions import Fraction

    rows = []
    for N, hw in CLASSES:
        rep = irrep(N, tuple(Fraction(x) for x in hw))
        moments = _moments(N)
        H = _hamiltonian(rep, moments)
        t_dense, E_dense = best_of(lambda: np.linalg.eigvalsh(H.toarray()), repeats)
        t_sec, spec = best_of(lambda: sector_spectra(rep, moments), repeats)
        secs = symmetry_sectors(rep)
        E_sec = spec.eigenvalues()
        err = float(np.abs(E_sec - E_dense).max() / np.abs(E_dense).max())
        row = {
            "N": N, "highest_weight": "(" + ", ".join(hw) + ")", "dim": rep.dim, "sectors": len(spec),
            "real_sectors": sum(bool(getattr(s, "real", False)) for s in secs),
            "largest_sector": max(len(v) for v in spec.values()),
            "dense_s": round(t_dense, 3), "sectors_s": round(t_sec, 3), "speedup": round(t_dense / t_sec, 1),
            "max_rel_diff": f"{err:.1e}", "load": _load(),
        }
        rows.append(row)
        print(row, flush=True)
    return rows


def scale(hw: tuple, workers: int) -> dict:
    import hyperrotor as hr

    # the stretch target's own limits (#24: < 30 min, < 6 GB) as the library's budgets (default 600 s, 4 GiB)
    with hr.options(max_seconds=1800.0, max_memory_bytes=6 * 2**30):
        return _scale(hw, workers)


def _scale(hw: tuple, workers: int) -> dict:
    t0 = time.perf_counter()
    rep = irrep(5, hw, max_dim=10**6)
    t1 = time.perf_counter()
    secs = symmetry_sectors(rep)
    t2 = time.perf_counter()
    spec = sector_spectra(rep, MOMENTS, workers=workers, progress=True)
    t3 = time.perf_counter()
    H = _hamiltonian(rep, MOMENTS)
    E = spec.eigenvalues()
    tr = float(H.diagonal().real.sum())
    fro2 = float((abs(H).power(2)).sum())
    row = {
        "highest_weight": f"({hw[0]}, {hw[1]})", "dim": rep.dim, "levels": int(E.size), "sectors": len(secs),
        "real_sectors": sum(s.real for s in secs), "sector_dims": "/".join(str(s.dim) for s in secs),
        "workers": workers,
        "build_irrep_s": round(t1 - t0, 2), "build_sectors_s": round(t2 - t1, 2),
        "sector_spectra_s": round(t3 - t2, 1), "total_s": round(t3 - t0, 1),
        "peak_rss_GB": round(_peak_rss_gb(), 2),
        "trace_rel_err": f"{abs(E.sum() - tr) / abs(tr):.1e}",
        "frobenius_rel_err": f"{abs((E**2).sum() - fro2) / fro2:.1e}",
        "load_at_end": _load(),
    }
    print(row, flush=True)
    assert E.size == rep.dim
    assert abs(E.sum() - tr) <= 1e-9 * abs(tr) and abs((E**2).sum() - fro2) <= 1e-9 * fro2
    return row


def plot(rows, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    d = [r["dim"] for r in rows]
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.loglog(d, [r["dense_s"] for r in rows], "o-", label="full dense eigvalsh (complex)")
    ax.loglog(d, [r["sectors_s"] for r in rows], "s-", label="sector_spectra (16 real blocks)")
    for r in rows:
        ax.annotate(f"x{r['speedup']}", (r["dim"], r["sectors_s"]), textcoords="offset points", xytext=(4, -12))
    ax.set_xlabel("dimension of the so(5) irrep")
    ax.set_ylabel("wall time [s]")
    ax.set_title("every level of a generic 5D rotor")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="two small irreps only")
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--scale", action="store_true", help="one large irrep instead (default (20, 10), dim 52,976)")
    ap.add_argument("--highest-weight", default="20,10",
                    help="--scale: so(5) highest weight m1,m2 (the #24 stretch: 29,14, dim 212,280)")
    ap.add_argument("--workers", type=int, default=1, help="--scale: sectors on this many threads")
    ap.add_argument("--blas-threads", type=int, default=1, help="comparison: BLAS threads of both paths")
    ap.add_argument("--classes", action="store_true",
                    help="the irrep classes of #24 (spinor, reflection, complex type) instead of so(5) tensor irreps")
    ap.add_argument("--output", default=None, help="--classes: csv name in benchmarks/results")
    args = ap.parse_args()
    os.makedirs(RESULTS, exist_ok=True)
    if args.scale:
        hw = tuple(int(x) for x in args.highest_weight.split(","))
        row = scale(hw, args.workers)
        name = "sectors_scale.csv" if hw == (20, 10) else f"sectors_scale_{hw[0]}_{hw[1]}.csv"
        print("wrote", write_csv([row], os.path.join(RESULTS, name)))
        return
    from threadpoolctl import threadpool_limits

    if args.classes:
        with threadpool_limits(limits=args.blas_threads, user_api="blas"):
            rows = compare_classes(args.repeats)
        print("wrote", write_csv(rows, os.path.join(RESULTS, args.output or "sectors_classes.csv")))
        return
    with threadpool_limits(limits=args.blas_threads, user_api="blas"):
        rows = compare(QUICK if args.quick else IRREPS, args.repeats)
    for r in rows:
        r["blas_threads"] = args.blas_threads
    print("wrote", write_csv(rows, os.path.join(RESULTS, "sectors.csv")))
    plot(rows, os.path.join(RESULTS, "sectors.png"))


if __name__ == "__main__":
    main()
