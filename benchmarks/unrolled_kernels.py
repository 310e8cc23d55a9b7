"""Splitting kernels unrolled per dimension vs the generic kernel, in one run (session 35, #22).

The peer is the package's own generic kernel (``solvers/_kernels.py``), switched on by making
``solvers._unrolled.kernel`` return ``None``: the same process, the same calls, the two kernels in turn
(``hyperrotor.bench.best_of_interleaved``), so the ratio is load-robust. Both give the same numbers to the last
bit (asserted here for every call as well). Cases: fixed-step runs (``dt``) of the 3D top (2, 3, 4), a 4D body,
the 5D quartet (kappa = 0.5) and a generic 5D body (ten moments log-uniform in [0.3, 3]), short and long, in plain
storage (compensated storage always runs the generic kernel), and rtol calls (step control: the probe, the run and
the check's companions run the unrolled kernel).

Usage: python benchmarks/unrolled_kernels.py [--quick]
Writes benchmarks/results/unrolled_kernels.csv and .png.
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from hyperrotor import Inertia, RigidBody, simulate
from hyperrotor.bench import best_of_interleaved, write_csv
from hyperrotor.classical.solvers import _unrolled

RESULTS = Path(__file__).resolve().parent / "results"


def cases():
    rng = np.random.default_rng(1)
    generic = np.exp(rng.uniform(np.log(0.3), np.log(3.0), 10))
    w5 = rng.normal(size=10)
    w5 /= np.abs(w5).max()
    quartet = RigidBody(Inertia.quartet(0.5))
    wq = np.random.default_rng(2026).normal(size=10)
    wq /= np.abs(wq).max()
    top, w3 = [2.0, 3.0, 4.0], np.array([0.3, 1.0, -0.5])
    m4, w4 = np.linspace(1.0, 2.0, 6), np.linspace(-1.0, 1.0, 6)
    t100, t20, t200 = np.linspace(0, 100, 101), np.linspace(0, 20, 101), np.linspace(0, 200, 101)
    plain = {"compensated": False}
    return [
        ("3D top, splitting8, dt 0.02 (5000 steps)", top, w3, t100, dict(method="splitting8", dt=0.02, options=plain)),
        ("3D top, splitting8, rtol 1e-10", top, w3, t100, dict(method="splitting8", rtol=1e-10)),
        ("4D, splitting8, dt 0.05 (2000 steps)", m4, w4, t100, dict(method="splitting8", dt=0.05, options=plain)),
        ("5D quartet, splitting10, dt 2/3 (300 steps)", quartet, wq, t200,
         dict(method="splitting10", dt=200 / 300, options=plain)),
        ("5D quartet, splitting10, dt 0.02 (1e4 steps)", quartet, wq, t200,
         dict(method="splitting10", dt=0.02, options=plain)),
        ("5D quartet, rtol 3e-9", quartet, wq, t200, dict(method="splitting10", rtol=3e-9)),
        ("5D generic, splitting10, dt 0.1 (200 steps)", generic, w5, t20,
         dict(method="splitting10", dt=0.1, options=plain)),
        ("5D generic, splitting10, dt 0.002 (1e4 steps)", generic, w5, t20,
         dict(method="splitting10", dt=0.002, options=plain)),
        ("5D generic, rtol 1e-10", generic, w5, t20, dict(method="splitting10", rtol=1e-10)),
        ("5D generic, rtol 1e-6", generic, w5, t20, dict(rtol=1e-6)),
    ]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer rounds")
    args = ap.parse_args(argv)
    RESULTS.mkdir(exist_ok=True)
    rounds = 20 if args.quick else 60
    kernel = _unrolled.kernel

    def off(N, compensated, pair=False):  # the generic kernels (pair: the step control's two runs in one call)
        return None

    def call(unrolled, body, w0, t, kw):
        def run():
            _unrolled.kernel = kernel if unrolled else off
            try:
                return simulate(body, w0, t, **kw)
            finally:
                _unrolled.kernel = kernel
        return run

    rows = []
    t0 = time.perf_counter()
    print(f"{'case':>46} {'generic [ms]':>13} {'unrolled [ms]':>14} {'speed-up':>9}")
    for name, body, w0, t, kw in cases():
        a, b = call(True, body, w0, t, kw)(), call(False, body, w0, t, kw)()  # (also compiles both)
        assert np.array_equal(a.L, b.L) and a.stats["work"] == b.stats["work"], name  # the same numbers
        (t_unrolled, t_generic), _ = best_of_interleaved([call(True, body, w0, t, kw), call(False, body, w0, t, kw)],
                                                         rounds)
        rows.append(dict(case=name, steps=a.stats["steps"], work=a.stats["work"], generic_s=t_generic,
                         unrolled_s=t_unrolled, speedup=t_generic / t_unrolled))
        print(f"{name:>46} {t_generic * 1e3:>13.3f} {t_unrolled * 1e3:>14.3f} {t_generic / t_unrolled:>8.2f}x")
    write_csv(rows, RESULTS / "unrolled_kernels.csv")
    plot(rows, RESULTS / "unrolled_kernels.png")
    print(f"\nwrote {RESULTS}/unrolled_kernels.csv and .png (total {time.perf_counter() - t0:.0f} s)")


def plot(rows, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4.5))
    y = np.arange(len(rows))
    ax.barh(y, [r["speedup"] for r in rows], color="tab:blue")
    ax.axvline(1.0, color="k", lw=0.8)
    ax.set_yticks(y, [r["case"] for r in rows], fontsize=8)
    ax.invert_yaxis()
    ax.set_xlabel("generic kernel time / unrolled kernel time (whole simulate call)")
    ax.set_title("Splitting kernels unrolled per dimension (same numbers, same process)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    main()
