"""Benchmark: Lyapunov-exponent ensembles in-process and on dask workers; one exponent vs scipy.

Problem: a generic 5D body (ten plane moments log-uniform in [0.3, 3], seed 7), orbits with
|L| = 3 in random directions, maximal exponent over T = 100 (``hr.lyapunov``, default
``splitting6`` tangent map, renormalisation every time unit).

1. Ensemble throughput (orbits per second, warm): in-process on 1 core and on all cores
   (threads; the process is pinned with ``os.sched_setaffinity`` to measure one core), and on
   a ``dask.distributed.LocalCluster`` of 1 and 2 worker processes (1 thread each), the same
   call with ``client=``. Parallel efficiency = throughput(p) / (p * throughput(1)). The
   distributed results are checked to equal the in-process ones bit for bit. The CPU time of
   one more run (this process, or summed over the dask workers) is reported too: on a shared,
   loaded machine the wall-time efficiency measures the cores others leave free, while CPU
   seconds per orbit show the cost of the work itself and of distributing it.
2. One exponent: ``hr.lyapunov`` for one orbit vs a naive scipy variational integration
   (``solve_ivp`` DOP853, rtol = atol = 1e-9, of the Euler equations dL/dt = [Omega, L] and
   their linearisation, 20 unknowns, Python right-hand side, renormalised every time unit), same
   orbit, same T, in the same run: time ratio and both exponents.

Times are the best of ``--repeat`` runs after one warm-up (JIT compile or cache load, worker
start-up and imports excluded). Writes benchmarks/results/chaos.csv and chaos.png.

Usage: python benchmarks/chaos.py [--quick] [--repeat R]
"""
from __future__ import annotations

import argparse
import math
import os
import time

import numpy as np
from scipy.integrate import solve_ivp

import hyperrotor as hr
from hyperrotor.bench import best_of, write_csv

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")
N, n = 5, 10


def problem(B, seed=7):
    g = np.random.default_rng(seed)
    moments = np.exp(g.uniform(math.log(0.3), math.log(3.0), n))
    L = g.standard_normal((B, n))
    L *= 3.0 / np.linalg.norm(L, axis=1, keepdims=True)
    return moments, L / moments


def scipy_exponent(moments, omega0, T, seed=0):
    """Naive variational Benettin: solve_ivp of (L, dL) with a Python right-hand side."""
    iu = np.triu_indices(N, 1)

    def mat(v):
        A = np.zeros((N, N))
        A[iu] = v
        return A - A.T

    Imat = np.abs(mat(moments)) + np.eye(N)

    def rhs(_t, y):
        L, D = mat(y[:n]), mat(y[n:])
        Om, dOm = L / Imat, D / Imat
        dL = Om @ L - L @ Om
        dD = dOm @ L + Om @ D - D @ Om - L @ dOm
        return np.concatenate([dL[iu], dD[iu]])

    L = omega0 * moments
    D = np.random.default_rng(seed).standard_normal(n)
    D /= np.linalg.norm(D)
    acc, nfev = 0.0, 0
    for k in range(int(T)):
        sol = solve_ivp(rhs, (k, k + 1.0), np.concatenate([L, D]), method="DOP853", rtol=1e-9, atol=1e-9)
        nfev += sol.nfev
        L, D = sol.y[:n, -1], sol.y[n:, -1]
        nrm = np.linalg.norm(D)
        acc += math.log(nrm)
        D /= nrm
    return acc / int(T), nfev


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer orbits and repeats")
    ap.add_argument("--repeat", type=int, default=None)
    args = ap.parse_args(argv)
    B = 128 if args.quick else 512
    repeat = args.repeat or (2 if args.quick else 3)
    T = 100.0
    moments, W0 = problem(B)
    rows = []
    cores = sorted(os.sched_getaffinity(0))

    # --- 1. ensemble throughput -------------------------------------------------------
    def run(client=None):
        return hr.lyapunov(moments, W0, T, rng=1, client=client, progress=False).exponents

    def cpu_of(client=None):
        """CPU seconds of one run: this process, plus the dask workers' when a client is given."""
        c0 = time.process_time()
        w0 = client.run(time.process_time) if client is not None else {}
        run(client)
        w1 = client.run(time.process_time) if client is not None else {}
        return time.process_time() - c0 + sum(w1[k] - w0[k] for k in w1)

    os.sched_setaffinity(0, cores[:1])
    try:
        t1, ref = best_of(run, repeat, warmup=True)
        cpu1 = cpu_of()
    finally:
        os.sched_setaffinity(0, cores)
    tall, out_all = best_of(run, repeat, warmup=True)
    cpu_all = cpu_of()
    assert np.array_equal(out_all, ref)
    rows.append(dict(run="in-process", workers=1, seconds=t1, orbits_per_s=B / t1, efficiency=1.0, identical=True,
                     cpu_ms_per_orbit=1e3 * cpu1 / B))
    rows.append(dict(run="in-process", workers=len(cores), seconds=tall, orbits_per_s=B / tall,
                     efficiency=t1 / (len(cores) * tall), identical=True, cpu_ms_per_orbit=1e3 * cpu_all / B))

    from dask.distributed import Client, LocalCluster

    base = None
    for nw in (1, 2):
        with LocalCluster(n_workers=nw, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster, \
                Client(cluster) as client:
            sec, out = best_of(lambda: run(client), repeat, warmup=True)
            cpu = cpu_of(client)
        base = sec if nw == 1 else base
        rows.append(dict(run="dask LocalCluster", workers=nw, seconds=sec, orbits_per_s=B / sec,
                         efficiency=base / (nw * sec), identical=bool(np.array_equal(out, ref)),
                         cpu_ms_per_orbit=1e3 * cpu / B))

    # --- 2. one exponent vs naive scipy -----------------------------------------------------
    w1 = W0[0]
    t_ours, lam_ours = best_of(lambda: float(hr.lyapunov(moments, w1, T, rng=1, progress=False)), repeat, warmup=True)
    start = time.perf_counter()
    lam_scipy, nfev = scipy_exponent(moments, w1, T)
    t_scipy = time.perf_counter() - start
    single = dict(ours_seconds=t_ours, scipy_seconds=t_scipy, ratio=t_scipy / t_ours, ours_exponent=lam_ours,
                  scipy_exponent=lam_scipy, scipy_nfev=nfev)

    # --- report ----------------------------------------------------------------------------
    print(f"Lyapunov ensemble: generic 5D body, {B} orbits, T = {T:g}, mean exponent {ref.mean():.3f} "
          f"(median {np.median(ref):.3f})")
    print(f"load average at the end: {os.getloadavg()[0]:.1f} on {len(cores)} cores")
    print(f"{'run':<20} {'workers':>7} {'seconds':>9} {'orbits/s':>10} {'efficiency':>10} {'CPU ms/orbit':>12} "
          f"{'bit-identical':>13}")
    for r in rows:
        print(f"{r['run']:<20} {r['workers']:>7d} {r['seconds']:>9.3f} {r['orbits_per_s']:>10.1f} "
              f"{r['efficiency']:>10.2f} {r['cpu_ms_per_orbit']:>12.2f} {str(r['identical']):>13}")
    print(f"\nOne exponent (T = {T:g}): hyperrotor {t_ours * 1e3:.1f} ms (lambda = {lam_ours:.4f}), naive scipy "
          f"DOP853 variational {t_scipy:.2f} s ({nfev} evaluations, lambda = {lam_scipy:.4f}): "
          f"{single['ratio']:.0f}x")
    os.makedirs(RESULTS, exist_ok=True)
    load = os.getloadavg()[0]
    write_csv([{**r, "orbits": B, "T": T, "load_average": load} for r in rows], os.path.join(RESULTS, "chaos.csv"))
    write_csv([single], os.path.join(RESULTS, "chaos_single.csv"))
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:  # pragma: no cover
        return
    fig, ax = plt.subplots(figsize=(6, 3.2))
    labels = [f"{r['run']}\n{r['workers']} worker(s)" for r in rows]
    ax.bar(labels, [r["orbits_per_s"] for r in rows], color=["C0", "C0", "C1", "C1"])
    ax.set_ylabel(f"orbits / s (T = {T:g})")
    ax.set_title(f"hr.lyapunov ensemble throughput, {B} orbits, 5D")
    ax.tick_params(axis="x", labelsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(RESULTS, "chaos.png"), dpi=120)


if __name__ == "__main__":
    main()
