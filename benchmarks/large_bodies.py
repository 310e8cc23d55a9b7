"""Chunks of large bodies (#22, every phase interruptible): the first compiled call of a kind not timed yet.

One ``simulate(rtol=1e-6)`` call (splitting8, T = 4, a random body with log-uniform moments in [0.3, 3]) per
dimension N, its cost per flow not learned yet, with the chunk sizing by dimension
(``hyperrotor.classical.solvers.chunks.flow_weight``) and with the 5D figure it replaced (the weight set to 1 in
the same process): the number of compiled calls, the longest one (Ctrl-C waits for the call running), the whole
call, and the steps and work (the same either way: chunks continue from the exact state).

Usage: python benchmarks/large_bodies.py [--quick] [N ...]   (default 60 100 140, N = 140 takes about 45 s per
call; --quick: 20 40)
"""
from __future__ import annotations

import sys
import time

import numpy as np

import hyperrotor as hr
import hyperrotor.classical.solvers.splitting as splitting
from hyperrotor.classical.solvers import chunks


def main(argv=None):
    args = list(sys.argv[1:] if argv is None else argv)
    quick = "--quick" in args
    dims = [int(x) for x in args if x != "--quick"] or ([20, 40] if quick else [60, 100, 140])
    calls = []
    for name in ("advance_pair", "advance"):  # (every compiled call of a splitting goes through one of these)
        orig = getattr(splitting.Splitting, name)

        def timed(self, *a, _orig=orig, **k):
            t0 = time.perf_counter()
            out = _orig(self, *a, **k)
            calls.append(time.perf_counter() - t0)
            return out
        setattr(splitting.Splitting, name, timed)
    hr.simulate(np.linspace(1.0, 2.0, 15), np.ones(15), [0.0, 0.1], method="splitting8", rtol=1e-6)  # (JIT)
    weight = chunks.flow_weight
    print("| N | sizing | compiled calls | longest call [s] | whole call [s] | steps | work |")
    print("|---|---|---|---|---|---|---|")
    try:
        for N in dims:
            n = N * (N - 1) // 2
            rng = np.random.default_rng(1)
            m = np.exp(rng.uniform(np.log(0.3), np.log(3.0), n))
            w = rng.normal(size=n)
            w /= np.abs(w).max()
            for label, f in (("5D figure", lambda N: 1.0), ("flow_weight", weight)):
                chunks.flow_weight = f
                chunks.SECONDS_PER_FLOW.clear()
                calls.clear()
                t0 = time.perf_counter()
                tr = hr.simulate(m, w, [0.0, 4.0], method="splitting8", rtol=1e-6)
                el = time.perf_counter() - t0
                print(f"| {N} | {label} | {len(calls)} | {max(calls):.3f} | {el:.2f} | {tr.stats['steps']} | "
                      f"{tr.stats['work']} |", flush=True)
    finally:
        chunks.flow_weight = weight


if __name__ == "__main__":
    main()
