"""Per-call cost of ``hyperrotor.simulate`` on short runs: ensembles and single trajectories.

Short runs are where the Python around the compiled kernels shows: input checks, step
choice, the chunked driver loop (Ctrl-C, progress), the finiteness check, the Casimir
shift per member, copies of the output. This script times ``simulate`` on

* ensembles of B = 1, 100, 10^4 members, 3D and 5D, ``splitting2/4/8`` and
  ``moser-veselov`` at ``dt = 0.01`` over ``t = linspace(0, 10, 11)`` (1000 steps, 11 output
  times); the expensive combinations stop at B = 100 (``splitting8`` 5D, ``moser-veselov``:
  beyond, the kernel takes seconds and the overhead is invisible);
* single trajectories where the entry point dominates: 10 steps of ``splitting4`` (3D, 5D)
  and a default-``rtol`` run (``method="auto"``, step chosen by the error control).

It runs against whichever ``hyperrotor`` is importable. With ``--baseline SRC`` it times a
second tree too (``PYTHONPATH=SRC``, e.g. a worktree of an older commit) in the same run:
two worker processes, asked case by case in alternating order, so that both see the same
machine load; every figure is the minimum over ``--rounds`` x repeats calls (warm JIT).
Besides the wall time of a call it reports the time spent *outside* the compiled kernels
(the kernels are wrapped with a timer): the per-call Python overhead, which is what this
benchmark is about and which the machine's load disturbs much less than the threaded kernels.

Usage::

    python benchmarks/ensemble_overhead.py                                   # this tree
    python benchmarks/ensemble_overhead.py --baseline /tmp/old-c87563f/src  # before/after
    python benchmarks/ensemble_overhead.py --quick                          # fewer cases/rounds

Prints a table and writes ``benchmarks/results/ensemble_overhead.csv``.
"""
from __future__ import annotations

import argparse
import csv
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

T_GRID = (0.0, 10.0, 11)  # linspace: 1000 steps of dt = 0.01, 11 output times
DT = 0.01
#: largest ensemble per (N, method); beyond it the kernel takes seconds and the overhead is noise
MAX_B = {(3, "splitting2"): 10_000, (5, "splitting2"): 10_000, (3, "splitting4"): 10_000,
         (5, "splitting4"): 10_000, (3, "splitting8"): 10_000, (5, "splitting8"): 100,
         (3, "moser-veselov"): 100, (5, "moser-veselov"): 100}
#: seconds of calls per worker and round (repeats are chosen from the warm-up time)
ROUND_SECONDS = 0.4


def cases(quick: bool) -> list[dict]:
    """The benchmark cases (the same list in every process: workers receive an index)."""
    out = [
        dict(label="entry: 3D splitting4, B=1, 10 steps", N=3, method="splitting4", B=0, t=(0.0, 0.1, 2), dt=DT),
        dict(label="entry: 5D splitting4, B=1, 10 steps", N=5, method="splitting4", B=0, t=(0.0, 0.1, 3), dt=DT),
        dict(label="entry: 3D auto rtol=1e-8, B=1, T=1", N=3, method="auto", B=0, t=(0.0, 1.0, 3), rtol=1e-8),
        dict(label="entry: 5D auto rtol=1e-8, B=1, T=1", N=5, method="auto", B=0, t=(0.0, 1.0, 3), rtol=1e-8),
    ]
    methods = ("splitting2", "splitting4") if quick else ("splitting2", "splitting4", "splitting8", "moser-veselov")
    sizes = (1, 100, 10_000)
    for N in (3, 5):
        for m in methods:
            for B in sizes:
                if B > MAX_B[(N, m)]:
                    continue
                out.append(dict(label=f"{N}D {m}, B={B}, 1000 steps", N=N, method=m, B=B, t=T_GRID, dt=DT))
    return out


# ----------------------------------------------------------------------------------------
# worker: times cases on request (stdin: {"i": index, "repeats": r}; stdout: JSON result)
# ----------------------------------------------------------------------------------------
def _call_for(case: dict):
    import hyperrotor as hr

    rng = np.random.default_rng(1)
    N = case["N"]
    n = N * (N - 1) // 2
    body = hr.RigidBody(hr.Inertia.from_mass_tensor(np.linspace(1.0, 2.0, N)))
    w = rng.normal(size=(case["B"], n)) if case["B"] else rng.normal(size=n)  # B = 0: one trajectory (1-D)
    t = np.linspace(*case["t"])
    kw = {"method": case["method"]}
    if "dt" in case:
        kw["dt"] = case["dt"]
    if "rtol" in case:
        kw["rtol"] = case["rtol"]

    def call():
        return hr.simulate(body, w, t, **kw)

    return call


_KERNEL_SECONDS = [0.0]


def _time_kernels() -> None:
    """Wrap the compiled kernels (old and new module layouts) to sum their wall time."""
    import importlib

    def wrap(mod, name):
        f = getattr(mod, name, None)
        if f is None:
            return

        def timed(*args, _f=f):
            t0 = time.perf_counter()
            try:
                return _f(*args)
            finally:
                _KERNEL_SECONDS[0] += time.perf_counter() - t0

        setattr(mod, name, timed)

    from hyperrotor.classical.solvers import _kernels

    for name in ("split_run", "split_run_serial", "split_run_ensemble"):
        wrap(_kernels, name)
    for modname in ("hyperrotor.classical.solvers.moser_veselov", "hyperrotor.classical.moser_veselov"):
        try:
            wrap(importlib.import_module(modname), "mv_run")
        except ImportError:
            pass


def worker(quick: bool) -> None:
    import hyperrotor as hr

    _time_kernels()
    todo = cases(quick)
    calls: dict[int, object] = {}
    print(json.dumps({"file": hr.__file__}), flush=True)
    for line in sys.stdin:
        req = json.loads(line)
        i = req["i"]
        if i not in calls:
            calls[i] = _call_for(todo[i])
        call = calls[i]
        times, outside = [], []
        for _ in range(req["repeats"]):
            _KERNEL_SECONDS[0] = 0.0
            t0 = time.perf_counter()
            call()
            times.append(time.perf_counter() - t0)
            outside.append(times[-1] - _KERNEL_SECONDS[0])
        print(json.dumps({"times": times, "outside": outside}), flush=True)


class Worker:
    def __init__(self, name: str, pythonpath: str | None, quick: bool):
        env = dict(os.environ)
        if pythonpath is not None:
            env["PYTHONPATH"] = pythonpath + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
        args = [sys.executable, __file__, "--worker"] + (["--quick"] if quick else [])
        self.name = name
        self.proc = subprocess.Popen(args, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=env)
        self.file = json.loads(self.proc.stdout.readline())["file"]

    def time(self, i: int, repeats: int) -> tuple[float, float]:
        """Least wall time and least time outside the kernels over ``repeats`` calls."""
        self.proc.stdin.write(json.dumps({"i": i, "repeats": repeats}) + "\n")
        self.proc.stdin.flush()
        line = self.proc.stdout.readline()
        if not line:
            raise RuntimeError(f"worker {self.name} died (case {i})")
        res = json.loads(line)
        return min(res["times"]), min(res["outside"])

    def close(self) -> None:
        self.proc.stdin.close()
        self.proc.wait()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--baseline", help="src directory of a second hyperrotor tree to compare with (PYTHONPATH)")
    ap.add_argument("--rounds", type=int, default=3, help="alternating rounds per case (default 3)")
    ap.add_argument("--quick", action="store_true", help="splitting2/4 only, 2 rounds")
    ap.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.worker:
        worker(args.quick)
        return
    rounds = 2 if args.quick and args.rounds == 3 else args.rounds
    todo = cases(args.quick)
    workers = [Worker("this", None, args.quick)]
    if args.baseline:
        workers.insert(0, Worker("baseline", str(Path(args.baseline).resolve()), args.quick))
    load0 = os.getloadavg()
    for w in workers:
        print(f"# {w.name}: {w.file}")
    print(f"# {os.cpu_count()} cores, load average at start {load0[0]:.2f} (1 min); min over {rounds} rounds x repeats")
    rows = []
    for i, case in enumerate(todo):
        for w in workers:  # JIT compile / cache load, first-call effects
            w.time(i, 1)
        best = {w.name: w.time(i, 1) for w in workers}
        reps = {name: max(1, min(20, int(ROUND_SECONDS / max(v[0], 1e-6)))) for name, v in best.items()}
        for r in range(rounds):
            order = workers if r % 2 else workers[::-1]  # alternate who goes first
            for w in order:
                wall, outside = w.time(i, reps[w.name])
                best[w.name] = (min(best[w.name][0], wall), min(best[w.name][1], outside))
        steps = int(round((case["t"][1] - case["t"][0]) / case["dt"])) if "dt" in case else None
        row = dict(case=case["label"], N=case["N"], method=case["method"], B=max(case["B"], 1), steps=steps)
        for w in workers:
            row[f"{w.name}_s"], row[f"{w.name}_outside_s"] = best[w.name]
        if args.baseline:
            row["ratio"] = row["this_s"] / row["baseline_s"]
            row["outside_diff_ms"] = 1e3 * (row["this_outside_s"] - row["baseline_outside_s"])
        rows.append(row)
        if args.baseline:
            print(f"{case['label']:42s} baseline {row['baseline_s'] * 1e3:9.2f} ms  this {row['this_s'] * 1e3:9.2f} ms"
                  f"  this/baseline {row['ratio']:5.2f}  outside kernels {row['baseline_outside_s'] * 1e3:.3f} -> "
                  f"{row['this_outside_s'] * 1e3:.3f} ms", flush=True)
        else:
            print(f"{case['label']:42s} {row['this_s'] * 1e3:9.2f} ms  (outside kernels "
                  f"{row['this_outside_s'] * 1e3:.3f} ms)", flush=True)
    for w in workers:
        w.close()
    load1 = os.getloadavg()
    print(f"# load average at end {load1[0]:.2f} (1 min)")

    # markdown table
    print()
    if args.baseline:
        print("| case | baseline (ms) | this tree (ms) | this / baseline | outside kernels: baseline -> this (ms) |")
        print("|---|---|---|---|---|")
        for r in rows:
            print(f"| {r['case']} | {r['baseline_s'] * 1e3:.3g} | {r['this_s'] * 1e3:.3g} | {r['ratio']:.2f} | "
                  f"{r['baseline_outside_s'] * 1e3:.3g} -> {r['this_outside_s'] * 1e3:.3g} |")
    else:
        print("| case | time (ms) | outside kernels (ms) | trajectory-steps/s |")
        print("|---|---|---|---|")
        for r in rows:
            rate = f"{r['B'] * r['steps'] / r['this_s']:.3g}" if r["steps"] else "-"
            print(f"| {r['case']} | {r['this_s'] * 1e3:.3g} | {r['this_outside_s'] * 1e3:.3g} | {rate} |")
    out = Path(__file__).resolve().parent / "results" / "ensemble_overhead.csv"
    out.parent.mkdir(exist_ok=True)
    with open(out, "w", newline="") as fh:
        wr = csv.DictWriter(fh, fieldnames=list(rows[0]))
        wr.writeheader()
        wr.writerows(rows)
    print(f"\nwrote {out}")


if __name__ == "__main__":
    main()
