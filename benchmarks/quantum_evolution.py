"""Benchmark: quantum rigid-rotor evolution, hyperrotor.evolve vs QuTiP sesolve.

Problem: so(5) irreps (l, 0) in the Gelfand-Tsetlin basis (dimension ~140 to
~20,500), rotor Hamiltonian of a generic body (10 random moments in [1, 2],
fixed seed) and of the quartet body (eqs. 84-85, kappa = 0.7, axis 5),
hbar = 1, initial state a coherent state along a random simple bivector,
51 output times on [0, T] (T = 1, about l/1.5 radians of classical rotation),
every state stored by every method.

Methods timed side by side in one run:
  * hyperrotor ``krylov`` (Lanczos, atol 1e-12 per restart), with the invariant
    blocks of the sparsity graph (``blocks=auto``) and without (``blocks=False``);
  * hyperrotor ``expm_multiply`` (scipy, Al-Mohy & Higham) and ``eigen``
    (per-block dense eigh, up to dim 5000);
  * hyperrotor ``auto`` (what a user gets by default);
  * QuTiP ``sesolve`` with default tolerances and "tuned": atol = rtol swept
    over 1e-10, 1e-12, 1e-14 (nsteps unlimited), reporting every run; the tuned
    time is that of the loosest tolerance reaching error <= 1e-8.
Error: max over the output times of the 2-norm distance to the reference
state (dense exact diagonalization of the whole matrix up to dim 2000,
otherwise Krylov with atol 1e-15 and a 40-dimensional Krylov space, which is
also compared with the exact reference at the small sizes: column ``ref_err``).
Memory: peak of Python-traced allocations (tracemalloc, includes numpy and
scipy buffers) in a separate run of each method at the largest size.

All BLAS work runs on one thread (``OPENBLAS_NUM_THREADS=1``, set below before
numpy is imported): this is a shared 2-core machine, where threaded BLAS made
every method slower and noisier.

Writes benchmarks/results/quantum_evolution.csv and quantum_evolution.png.

Usage: python benchmarks/quantum_evolution.py [--quick] [--replot]
"""
from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse  # noqa: E402
import csv  # noqa: E402
import time  # noqa: E402
import tracemalloc  # noqa: E402

import numpy as np  # noqa: E402
import scipy.sparse as sps  # noqa: E402

from hyperrotor.bench import write_csv  # noqa: E402
from hyperrotor.conventions import planes  # noqa: E402
from hyperrotor.quantum import irrep  # noqa: E402
from hyperrotor.quantum.coherent import coherent_state  # noqa: E402
from hyperrotor.quantum import evolve, rotor_hamiltonian  # noqa: E402

RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")
TARGET = 1e-8


def _states(res):
    return np.array([s.full().ravel() for s in res.states])


def _run(H, psi, times, method, options):
    opts = {"store_states": True, **options}
    t0 = time.perf_counter()
    res = evolve(H, psi, times, method=method, options=opts)
    return time.perf_counter() - t0, _states(res), res.stats


def _memory(H, psi, times, method, options):
    tracemalloc.start()
    evolve(H, psi, times, method=method, options={"store_states": True, **options})
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak / 2**20


def _err(S, R):
    return float(np.max(np.linalg.norm(S - R, axis=1)))


def _problem(l, body):
    rep = irrep(5, (l, 0))
    rng = np.random.default_rng(2026)
    if body == "generic":
        moments = rng.uniform(1.0, 2.0, size=10)
    else:
        kappa = 0.7
        moments = np.array([1 + kappa**2 if 5 in p else 2.0 for p in planes(5)])
    H = rotor_hamiltonian(rep, moments)
    Q, _ = np.linalg.qr(np.random.default_rng(11).normal(size=(5, 5)))
    L = Q[:, 0:1] @ Q[:, 1:2].T
    L = L - L.T
    comps = np.array([L[i - 1, j - 1] for i, j in planes(5)])
    psi = coherent_state(rep, comps, frame="body")
    return rep, H, psi


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small sizes only (< 1 min)")
    ap.add_argument("--replot", action="store_true", help="only redraw the PNG from the existing CSV")
    args = ap.parse_args(argv)
    if args.replot:
        with open(os.path.join(RESULTS, "quantum_evolution.csv")) as fh:
            rows = list(csv.DictReader(fh))
        for r in rows:
            for k in ("l", "dim"):
                r[k] = int(r[k])
            for k in ("time_s", "error"):
                r[k] = float(r[k])
            r["sesolve_tuned_time_s"] = float(r["sesolve_tuned_time_s"]) if r["sesolve_tuned_time_s"] not in ("", "None") else None
        _plot(rows)
        return
    ls = [6, 10, 16, 22] if args.quick else [6, 10, 16, 22, 27, 38]
    times = np.linspace(0.0, 1.0, 51)
    rows = []
    header = f"{'body':8s} {'l':>3s} {'dim':>6s} {'method':28s} {'time [s]':>9s} {'error':>9s} {'speedup*':>9s}"
    print("so(5) irreps (l, 0), T = 1, 51 output times; speedup* = tuned sesolve time / time")
    print(header)
    print("-" * len(header))
    for body in ("generic", "quartet"):
        for l in ls:
            rep, H, psi = _problem(l, body)
            dim = rep.dim
            exact = dim <= 2000
            if exact:
                t_ref, R, _ = _run(H, psi, times, "eigen", {"blocks": False})
                ref_name = "eigen (full dense)"
            else:
                t_ref, R, _ = _run(H, psi, times, "krylov", {"blocks": False, "atol": 1e-15, "krylov_dim": 40})
                ref_name = "krylov atol 1e-15"
            ref_err = np.nan
            if exact:
                _, K, _ = _run(H, psi, times, "krylov", {"blocks": False, "atol": 1e-15, "krylov_dim": 40})
                ref_err = _err(K, R)
            runs = []
            cases = [
                ("hyperrotor auto", "auto", {}),
                ("hyperrotor krylov (blocks)", "krylov", {}),
                ("hyperrotor krylov (no blocks)", "krylov", {"blocks": False}),
                ("hyperrotor expm_multiply", "expm_multiply", {}),
            ]
            if dim <= 5000:
                cases.append(("hyperrotor eigen (blocks)", "eigen", {}))
            for name, method, opts in cases:
                t, S, st = _run(H, psi, times, method, opts)
                runs.append((name, t, _err(S, R), st.get("blocks", 1)))
            t, S, _ = _run(H, psi, times, "sesolve", {})
            runs.append(("qutip sesolve default", t, _err(S, R), 1))
            tuned = None
            for tol in (1e-12, 1e-13, 1e-14):
                t, S, _ = _run(H, psi, times, "sesolve", {"atol": tol, "rtol": tol, "nsteps": 10**9})
                e = _err(S, R)
                runs.append((f"qutip sesolve atol=rtol={tol:.0e}", t, e, 1))
                if e <= TARGET:
                    tuned = t
                    break
            for name, t, e, nb in runs:
                speed = tuned / t if tuned else np.nan
                print(f"{body:8s} {l:3d} {dim:6d} {name:28s} {t:9.3f} {e:9.2e} {speed:9.1f}")
                rows.append(dict(body=body, l=l, dim=dim, method=name, time_s=t, error=e,
                                 speedup_vs_tuned_sesolve=speed, sesolve_tuned_time_s=tuned,
                                 reference=ref_name, reference_time_s=t_ref, ref_err=ref_err, blocks=nb, mem_MiB=np.nan))
            Hs = H.data.as_scipy()
            offdiag = float(np.max(np.abs((Hs - sps.diags(Hs.diagonal())).data), initial=0.0))
            print(f"{'':8s} {'':3s} {'':6s} reference: {ref_name} ({t_ref:.2f} s)"
                  + (f", tight-Krylov vs exact {ref_err:.1e}" if exact else "")
                  + (f"; max|offdiag H| = {offdiag:.1e}" if body == "quartet" else ""))
    # long window for the quartet body: the symmetry-adapted path costs the same for any T
    lmax = ls[-1]
    rep, H, psi = _problem(lmax, "quartet")
    t_long = np.linspace(0.0, 10.0, 51)
    _, R, _ = _run(H, psi, t_long, "krylov", {"blocks": False, "atol": 1e-15, "krylov_dim": 40})
    print(f"\nquartet, l = {lmax} (dim {rep.dim}), long window T = 10 (reference: krylov atol 1e-15, no blocks)")
    for name, method, opts in [("hyperrotor auto", "auto", {}), ("hyperrotor krylov (no blocks)", "krylov", {"blocks": False})]:
        t, S, st = _run(H, psi, t_long, method, opts)
        e = _err(S, R)
        print(f"  {name:30s} {t:9.3f} s  error {e:9.2e}  blocks {st.get('blocks', 1)}")
        rows.append(dict(body="quartet T=10", l=lmax, dim=rep.dim, method=name, time_s=t, error=e,
                         speedup_vs_tuned_sesolve=np.nan, sesolve_tuned_time_s=None, reference="krylov atol 1e-15",
                         reference_time_s=np.nan, ref_err=np.nan, blocks=st.get("blocks", 1), mem_MiB=np.nan))
    # memory at the largest size
    print(f"\npeak traced memory at l = {lmax}:")
    for body in ("generic", "quartet"):
        rep, H, psi = _problem(lmax, body)
        for name, method, opts in [("hyperrotor auto", "auto", {}), ("hyperrotor krylov (no blocks)", "krylov", {"blocks": False}),
                                   ("qutip sesolve default", "sesolve", {})]:
            mem = _memory(H, psi, times, method, opts)
            print(f"  {body:8s} {name:30s} {mem:8.1f} MiB (states alone: {51 * rep.dim * 16 / 2**20:.1f} MiB)")
            for r in rows:
                if r["body"] == body and r["l"] == lmax and r["method"] == name:
                    r["mem_MiB"] = mem
    os.makedirs(RESULTS, exist_ok=True)
    write_csv(rows, os.path.join(RESULTS, "quantum_evolution.csv"))
    _plot(rows)
    print(f"\nwrote {RESULTS}/quantum_evolution.csv and .png")


def _plot(rows):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(16, 4.8))
    for ax, body in zip(axes[:2], ("generic", "quartet")):
        names = []
        for r in rows:
            if r["body"] == body and r["method"] not in names and not r["method"].startswith("qutip sesolve atol"):
                names.append(r["method"])
        names.append("qutip sesolve tuned (<= 1e-8)")
        for name in names:
            if name.startswith("qutip sesolve tuned"):
                pts = sorted({(r["dim"], r["sesolve_tuned_time_s"]) for r in rows if r["body"] == body and r["sesolve_tuned_time_s"]})
            else:
                pts = [(r["dim"], r["time_s"]) for r in rows if r["body"] == body and r["method"] == name]
            if pts:
                x, y = zip(*pts)
                ax.loglog(x, y, "o-", label=name)
        ax.set_xlabel("dimension of the so(5) irrep (l, 0)")
        ax.set_ylabel("run time [s] (51 output times, T = 1)")
        ax.set_title(f"{body} inertia")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    ax = axes[2]
    dmax = max(r["dim"] for r in rows)
    for r in rows:
        if r["dim"] == dmax and r["body"] in ("generic", "quartet"):
            ax.loglog(max(r["error"], 1e-16), r["time_s"], "o" if r["body"] == "generic" else "s")
            ax.annotate(f"{r['body'][0]}: {r['method']}", (max(r["error"], 1e-16), r["time_s"]), fontsize=6)
    ax.axvline(TARGET, color="k", lw=0.8, ls="--")
    ax.set_xlabel("max state error")
    ax.set_ylabel("run time [s]")
    ax.set_title(f"time vs error at dim {dmax} (g = generic, q = quartet)")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(RESULTS, "quantum_evolution.png"), dpi=120)


if __name__ == "__main__":
    main()
