"""Benchmark: verify all so(N) commutation relations, exact normal form vs naive SymPy.

For every pair of planes a < b of so(N), N = 3..10, check

    [L^ij, L^kl] = d_jk L^il + d_il L^jk - d_jl L^ik - d_ik L^jl,   L^ij = x_i d_j - x_j d_i,

* fast: ``hyperrotor.quantum`` operators in exact normal form (Weyl algebra):
  build the operators, compute every commutator as an operator, build the
  right-hand side, compare normal forms (everything inside the timing);
* naive SymPy: apply both sides to a generic function f(x1..xN) with
  ``sympy.diff`` and check ``simplify(lhs - rhs) == 0`` (the peer named in the
  issue), and the cheaper variant ``expand(lhs - rhs) == 0``.

The naive paths run only while their cumulative time stays within a budget
(default 60 s each); larger N are extrapolated from the per-relation time of
the largest measured N and marked "est". Writes benchmarks/results/commutators.csv
and commutators.png.

Usage: python benchmarks/commutators.py [--quick] [--budget SECONDS]
"""
from __future__ import annotations

import argparse
import itertools
import os
import time

import sympy as sp

from hyperrotor.bench import write_csv

from hyperrotor.conventions import planes
from hyperrotor.quantum import angular_momentum_operators, commutator

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")


def _d(a, b):
    return int(a == b)


def fast_verify(N: int) -> tuple[int, bool]:
    L = angular_momentum_operators(N)
    zero = L[(1, 2)] * 0

    def get(a, b):
        if a == b:
            return zero
        return L[(a, b)] if a < b else -L[(b, a)]

    ok = True
    n = 0
    for (i, j), (k, l) in itertools.combinations(planes(N), 2):
        lhs = commutator(L[(i, j)], L[(k, l)])
        rhs = zero
        for coef, (p, q) in ((_d(j, k), (i, l)), (_d(i, l), (j, k)), (-_d(j, l), (i, k)), (-_d(i, k), (j, l))):
            if coef:
                rhs = rhs + coef * get(p, q)
        ok &= lhs == rhs
        n += 1
    return n, ok


def naive_verify(N: int, simplifier, deadline: float | None = None) -> tuple[int, bool, bool]:
    """Returns (relations checked, all ok, finished)."""
    xs = sp.symbols(f"x1:{N + 1}", real=True)
    f = sp.Function("f")(*xs)

    def act(i, j, g):
        if i == j:
            return sp.Integer(0)
        return xs[i - 1] * sp.diff(g, xs[j - 1]) - xs[j - 1] * sp.diff(g, xs[i - 1])

    ok, n = True, 0
    for (i, j), (k, l) in itertools.combinations(planes(N), 2):
        lhs = act(i, j, act(k, l, f)) - act(k, l, act(i, j, f))
        rhs = (_d(j, k) * act(i, l, f) + _d(i, l) * act(j, k, f)
               - _d(j, l) * act(i, k, f) - _d(i, k) * act(j, l, f))
        ok &= simplifier(lhs - rhs) == 0
        n += 1
        if deadline is not None and time.perf_counter() > deadline:
            return n, ok, False
    return n, ok, True


def _time_fast(N: int, repeat: int = 3) -> tuple[float, int, bool]:
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        n, ok = fast_verify(N)
        best = min(best, time.perf_counter() - t0)
    return best, n, ok


def main(argv=None) -> list[dict]:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="N = 3..7 and a 10 s naive budget")
    ap.add_argument("--budget", type=float, default=None, help="seconds per naive variant (default 60; 10 with --quick)")
    ap.add_argument("--nmax", type=int, default=None)
    args = ap.parse_args(argv)
    nmax = args.nmax or (7 if args.quick else 10)
    budget = args.budget if args.budget is not None else (10.0 if args.quick else 60.0)
    Ns = list(range(3, nmax + 1))

    rows = []
    state = {name: {"spent": 0.0, "per_rel": None, "stopped": False} for name in ("simplify", "expand")}
    simplifiers = {"simplify": sp.simplify, "expand": sp.expand}
    for N in Ns:
        tf, n, okf = _time_fast(N)
        row = {"N": N, "relations": n, "fast_s": tf, "fast_ok": okf}
        for name, fn in simplifiers.items():
            st = state[name]
            remaining = budget - st["spent"]
            predicted = st["per_rel"] * n * 1.5 if st["per_rel"] else 0.0
            if not st["stopped"] and remaining > 0 and predicted <= remaining:
                t0 = time.perf_counter()
                m, ok, finished = naive_verify(N, fn, deadline=t0 + remaining)
                dt = time.perf_counter() - t0
                st["spent"] += dt
                if finished:
                    st["per_rel"] = dt / m
                    row[f"naive_{name}_s"], row[f"naive_{name}_ok"], row[f"naive_{name}_kind"] = dt, ok, "measured"
                    continue
                st["per_rel"] = dt / m
                st["stopped"] = True
            else:
                st["stopped"] = True
            # extrapolate linearly in the number of relations (per-relation cost grows with N: a lower bound)
            row[f"naive_{name}_s"] = st["per_rel"] * n if st["per_rel"] else float("nan")
            row[f"naive_{name}_ok"] = None
            row[f"naive_{name}_kind"] = "est (lower bound)"
        rows.append(row)

    hdr = (f"{'N':>3} {'relations':>9} {'fast [s]':>10} {'naive simplify [s]':>22} {'ratio':>8} "
           f"{'naive expand [s]':>20} {'ratio':>8}  all ok")
    print(hdr)
    print("-" * len(hdr))
    for r in rows:
        def cell(name):
            t, kind = r[f"naive_{name}_s"], r[f"naive_{name}_kind"]
            return (f"{t:>14.3f}" + (" (est)" if kind != "measured" else "      ")), t / r["fast_s"]
        cs, rs = cell("simplify")
        ce, re_ = cell("expand")
        oks = [r["fast_ok"]] + [r[f"naive_{k}_ok"] for k in simplifiers if r[f"naive_{k}_ok"] is not None]
        print(f"{r['N']:>3} {r['relations']:>9} {r['fast_s']:>10.4f} {cs:>22} {rs:>8.0f} {ce:>20} {re_:>8.0f}  {all(oks)}")
    print("ratio = naive time / fast time; '(est)' = extrapolated lower bound, not measured.")

    os.makedirs(RESULTS, exist_ok=True)
    write_csv(rows, os.path.join(RESULTS, "commutators.csv"))
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(6, 4))
        ax.semilogy([r["N"] for r in rows], [r["fast_s"] for r in rows], "o-", label="normal form (hyperrotor)")
        for name, style in (("simplify", "s-"), ("expand", "^-")):
            meas = [r for r in rows if r[f"naive_{name}_kind"] == "measured"]
            est = [r for r in rows if r[f"naive_{name}_kind"] != "measured"]
            ax.semilogy([r["N"] for r in meas], [r[f"naive_{name}_s"] for r in meas], style, label=f"naive SymPy ({name})")
            if est:
                ax.semilogy([r["N"] for r in est], [r[f"naive_{name}_s"] for r in est], style[0] + ":", mfc="none",
                            color=ax.lines[-1].get_color(), label=f"naive {name} (extrapolated)")
        ax.set_xlabel("N")
        ax.set_ylabel("time to verify all so(N) relations [s]")
        ax.set_title("so(N) commutation relations")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(RESULTS, "commutators.png"), dpi=120)
    except ImportError:  # pragma: no cover
        print("matplotlib missing: no plot")
    return rows


if __name__ == "__main__":
    main()
