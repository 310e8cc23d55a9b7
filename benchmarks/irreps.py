"""Benchmark: build time and memory of so(5) Gelfand-Tsetlin irreps vs dimension.

For so(5) irreps of highest weight (m1, m2) ~ (2k, k) (dims 5 ... 52,976 and beyond):

* fast: ``hyperrotor.quantum.irrep`` builds all 10 generators (4 chain generators
  from the vectorized Gelfand-Tsetlin formulas, 6 by sparse commutators); the
  time of the 4 chain generators alone is reported too;
* naive SymPy: the peer the issue names - per-element SymPy matrix elements
  (``sympy.sqrt`` of exact rationals, Python loops over patterns and a dict
  lookup per neighbour) for the **4 chain generators only**, converted to a
  float CSR matrix. It does strictly less work than the fast path (no
  commutators), so the ratios below under-state the speed-up. Its matrices are
  also compared entry by entry with the fast ones (an independent re-coding of
  the formulas).

Goals (issue 5): dim ~2000 in < 0.2 s, dim >= 50,000 in < 5 s (all generators).
Memory: ``tracemalloc`` peak during the build (separate run) and the bytes held
by the 10 CSR matrices (data + indices + indptr).

Writes benchmarks/results/irreps.csv and irreps.png.

Usage: python benchmarks/irreps.py [--quick] [--naive-max-dim D]
"""
from __future__ import annotations

import argparse
import os
import time
import tracemalloc
from fractions import Fraction

import numpy as np

from hyperrotor.bench import best_of, write_csv
import scipy.sparse as sps
import sympy as sp

from hyperrotor.quantum.gelfand_tsetlin import _gt_generators_float, gt_patterns, irrep, patterns
from hyperrotor.quantum.weights import check_highest_weight, weyl_dimension

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")


# ----------------------------------------------------------------------------
# naive SymPy chain generators (per-element), so(5) only
# ----------------------------------------------------------------------------
def naive_sympy_chain(m1, m2):
    """Chain generators X_(12), X_(23), X_(34), X_(45) of so(5) with per-element SymPy."""
    P = [tuple(Fraction(x).limit_denominator(2) for x in row) for row in gt_patterns(5, (m1, m2)).tolist()]
    index = {p: k for k, p in enumerate(P)}
    dim = len(P)
    R = sp.Rational
    mats = {}

    def l5(p):  # row M5 (so(5), p=2): l_j = m_j + 2 - j + 1
        return [R(p[0]) + 2, R(p[1]) + 1]

    def l4(p):  # row M4 (so(4), p=2): l_j = m_j + 2 - j
        return [R(p[2]) + 1, R(p[3])]

    def l3(p):  # row M3 (so(3), p=1): l = m + 1
        return [R(p[4]) + 1]

    def l2(p):  # row M2 (so(2), p=1): l = m
        return [R(p[5])]

    def add(M, i, j, v):
        M.setdefault((i, j), 0)
        M[(i, j)] += v

    # X_(12): i * M2
    M = {}
    for a, p in enumerate(P):
        if p[5] != 0:
            add(M, a, a, sp.I * l2(p)[0])
    mats[(1, 2)] = M
    # X_(23): A-type on row 2 (p=1): rows 1 (empty) and 3
    M = {}
    for a, p in enumerate(P):
        q = p[:5] + (p[5] + 1,)
        if q in index:
            l = l2(p)[0]
            L3 = l3(p)[0]
            v = sp.Rational(1, 2) * sp.sqrt(abs((L3 - l - 1) * (L3 + l)))
            add(M, index[q], a, v)
            add(M, a, index[q], -v)
    mats[(2, 3)] = M
    # X_(34): B-type on row 3 (p=1): rows 2 and 4, diagonal i C
    M = {}
    for a, p in enumerate(P):
        l = l3(p)[0]
        q = p[:4] + (p[4] + 1,) + p[5:]
        if q in index:
            num = (l2(p)[0] ** 2 - l ** 2) * (l4(p)[0] ** 2 - l ** 2) * (l4(p)[1] ** 2 - l ** 2)
            den = l ** 2 * (4 * l ** 2 - 1)
            v = sp.sqrt(abs(num / den))
            add(M, index[q], a, v)
            add(M, a, index[q], -v)
        den = l * (l - 1)
        if den != 0:
            c = l2(p)[0] * l4(p)[0] * l4(p)[1] / den
            if c != 0:
                add(M, a, a, sp.I * c)
    mats[(3, 4)] = M
    # X_(45): A-type on row 4 (p=2): rows 3 and 5
    M = {}
    for a, p in enumerate(P):
        L4 = l4(p)
        for j in range(2):
            q = list(p)
            q[2 + j] += 1
            q = tuple(q)
            if q not in index:
                continue
            l = L4[j]
            o = L4[1 - j]
            num = 1
            for L in l3(p):
                num *= (L - l - 1) * (L + l)
            for L in l5(p):
                num *= (L - l - 1) * (L + l)
            den = (o ** 2 - l ** 2) * (o ** 2 - (l + 1) ** 2)
            v = sp.Rational(1, 2) * sp.sqrt(abs(num / den))
            add(M, index[q], a, v)
            add(M, a, index[q], -v)
    mats[(4, 5)] = M
    out = {}
    for p, M in mats.items():
        keys = list(M)
        rows = [k[0] for k in keys]
        cols = [k[1] for k in keys]
        vals = [complex(sp.N(M[k])) for k in keys]
        out[p] = sps.csr_matrix((vals, (rows, cols)), shape=(dim, dim))
    return out


# ----------------------------------------------------------------------------
def _fast_chain_only(m):
    """Time of the 4 chain generators alone (private helper mirrors irrep's first stage)."""
    from hyperrotor.quantum.gelfand_tsetlin import PatternIndex, _chain_elements

    mm = check_highest_weight(5, m)
    P = patterns(5, mm)
    index = PatternIndex(P, mm)
    for k in range(1, 5):
        _chain_elements(P, 5, k, index, P, exact=False)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="small sizes only (< 30 s)")
    ap.add_argument("--naive-max-dim", type=int, default=None, help="largest dim for the naive SymPy peer")
    args = ap.parse_args(argv)

    ks = [(1, 0), (2, 1), (3, 1), (4, 2), (6, 3), (8, 4), (10, 5)] if args.quick else \
        [(1, 0), (2, 1), (3, 1), (4, 2), (6, 3), (8, 4), (10, 5), (12, 6), (14, 7), (16, 8), (18, 9), (20, 10), (24, 12)]
    naive_max = args.naive_max_dim if args.naive_max_dim is not None else (600 if args.quick else 2000)

    rows = []
    hdr = f"{'hw':>9} {'dim':>7} {'all 10 [s]':>11} {'chain 4 [s]':>11} {'naive chain [s]':>15} {'ratio':>8} {'nnz':>9} {'CSR MiB':>8} {'peak MiB':>9} {'max|diff|':>9}"
    print(hdr)
    print("-" * len(hdr))
    for m in ks:
        dim = weyl_dimension(5, m)
        rep_count = 5 if dim < 5000 else (2 if dim < 60000 else 1)
        t_all, rep = best_of(lambda: irrep(5, m, max_dim=10**7), rep_count)
        t_chain, _ = best_of(lambda: _fast_chain_only(m), rep_count)
        G = rep.generators()
        nnz = sum(M.nnz for M in G.values())
        csr_bytes = sum(M.data.nbytes + M.indices.nbytes + M.indptr.nbytes for M in G.values())
        tracemalloc.start()
        _gt_generators_float(5, check_highest_weight(5, m))
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
        t_naive = diff = None
        if dim <= naive_max:
            t0 = time.perf_counter()
            naive = naive_sympy_chain(*m)
            t_naive = time.perf_counter() - t0
            diff = max(float(abs(naive[p] - G[p]).max()) if (naive[p] - G[p]).nnz else 0.0 for p in naive)
        ratio = None if t_naive is None else t_naive / t_chain
        rows.append(dict(m1=m[0], m2=m[1], dim=dim, t_all=t_all, t_chain=t_chain, t_naive_chain=t_naive,
                         ratio_naive_over_fast_chain=ratio, nnz=nnz, csr_mib=csr_bytes / 2**20,
                         peak_mib=peak / 2**20, max_abs_diff=diff))
        fmt = lambda x, f: ("-" if x is None else format(x, f))  # noqa: E731
        print(f"{str(m):>9} {dim:>7} {t_all:>11.4f} {t_chain:>11.4f} {fmt(t_naive, '15.3f'):>15} "
              f"{fmt(ratio, '8.0f'):>8} {nnz:>9} {csr_bytes / 2**20:>8.2f} {peak / 2**20:>9.1f} {fmt(diff, '9.1e'):>9}")

    near2000 = min(rows, key=lambda r: abs(r["dim"] - 2000))
    big = [r for r in rows if r["dim"] >= 50000]
    print()
    print(f"goal dim ~2000 < 0.2 s: dim {near2000['dim']} took {near2000['t_all']:.4f} s "
          f"({'met' if near2000['t_all'] < 0.2 else 'NOT met'})")
    for r in big:
        print(f"goal dim >= 50,000 < 5 s: dim {r['dim']} took {r['t_all']:.3f} s ({'met' if r['t_all'] < 5 else 'NOT met'}), "
              f"CSR {r['csr_mib']:.1f} MiB, peak {r['peak_mib']:.1f} MiB")

    os.makedirs(RESULTS, exist_ok=True)
    path = write_csv(rows, os.path.join(RESULTS, "irreps.csv"))
    print(f"wrote {path}")
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
        d = np.array([r["dim"] for r in rows])
        ax[0].loglog(d, [r["t_all"] for r in rows], "o-", label="hyperrotor irrep: all 10 generators")
        ax[0].loglog(d, [r["t_chain"] for r in rows], "s--", label="hyperrotor: 4 chain generators")
        nv = [(r["dim"], r["t_naive_chain"]) for r in rows if r["t_naive_chain"] is not None]
        if nv:
            ax[0].loglog(*zip(*nv), "^-", label="naive SymPy: 4 chain generators")
        ax[0].plot([2000], [0.2], "k*", ms=12, label="goal: dim 2000 < 0.2 s")
        ax[0].plot([50000], [5], "kX", ms=10, label="goal: dim 50,000 < 5 s")
        ax[0].set_xlabel("dimension of the so(5) irrep")
        ax[0].set_ylabel("build time [s]")
        ax[0].legend(fontsize=8)
        ax[0].grid(True, which="both", alpha=0.3)
        ax[1].loglog(d, [r["csr_mib"] for r in rows], "o-", label="CSR storage of 10 generators")
        ax[1].loglog(d, [r["peak_mib"] for r in rows], "s--", label="tracemalloc peak during build")
        ax[1].set_xlabel("dimension of the so(5) irrep")
        ax[1].set_ylabel("MiB")
        ax[1].legend(fontsize=8)
        ax[1].grid(True, which="both", alpha=0.3)
        fig.suptitle("so(5) Gelfand-Tsetlin irreps (m1, m2) = (2k, k)")
        fig.tight_layout()
        png = os.path.join(RESULTS, "irreps.png")
        fig.savefig(png, dpi=120)
        print(f"wrote {png}")
    except ImportError:  # pragma: no cover
        print("matplotlib not available: no PNG")


if __name__ == "__main__":
    main()
