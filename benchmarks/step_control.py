"""Cost and reliability of the step control of hyperrotor.simulate(rtol=...) (issue #22).

Five tables, each measured side by side in one run (ratios are load-robust):

1. Overhead: wall time of ``simulate(body, omega0, t, rtol=r)`` (step chosen inside the call)
   over the wall time of the fixed-step run at the step it chose (``dt=stats["dt"]``, same
   method, same ``compensated`` choice; the two calls in turn, best of 0.5 s of them, 1.5 s without
   ``--quick``), on the 3D top (2, 3, 4), the 5D quartet (kappa = 0.5)
   and generic 5D bodies (ten independent moments, log-uniform in [0.3, 3]), T = 20 and 200,
   rtol 1e-6 ... 1e-12. Goal: <= 1.5x. Also the achieved whole-run error over rtol
   (max|L - L_ref| / max|L|, references: closed forms; generic bodies: splitting8 at dt = 0.002,
   compensated, checked against DOP853 at rtol 1e-13).
2. Headline: one rtol call of hyperrotor (step choice included) reaching error <= 1e-10
   (error = max|omega - omega_ref| / max|omega0|) against scipy's DOP853 at the largest rtol that
   reaches it (the two, and the fixed-step run at our step, timed in turn): the quartet at T = 200
   (goal >= 250x) and a generic 5D body (goal >= 60x). Ours: the fastest call reaching it of ``auto``, ``splitting8`` and ``splitting10`` at rtol 1e-8 ... 1e-11 (all printed;
   a larger rtol can cost more when its check asks for a re-run).
3. Bound held: over many random generic 5D bodies (T = 20), the fraction of runs whose whole-run
   error stays <= rtol, rtol = 1e-6 ... 1e-10.
4. Where ``method="auto"`` switches from splitting8 to splitting10: wall time of rtol calls of both.
5. Ensembles: random generic 5D bodies with 20 members each (T = 20), rtol 1e-6 and 1e-9: the worst member's
   error over rtol, and whether a miss was named (``AccuracyWarning``, with the accuracy it names) or silent.
   Goal: no silent miss.

Usage: python benchmarks/step_control.py [--quick]  (run with PYTHONPATH=<other tree>/src for "before")
Writes benchmarks/results/step_control*.csv.
"""
from __future__ import annotations

import argparse
import re
import time
import warnings
from pathlib import Path

import numpy as np

import hyperrotor as hr
from hyperrotor import Inertia, RigidBody, simulate
from hyperrotor.classical.simulate import SIMULATION_METHODS
from hyperrotor.bench import best_of, best_of_interleaved, write_csv
from hyperrotor.classical import euler_poinsot, quartet_solution

RESULTS = Path(__file__).resolve().parent / "results"
MOM3 = np.array([2.0, 3.0, 4.0])
W3 = np.array([0.6, 1.0, -0.5])


def generic_body(seed):
    """Ten independent plane moments, log-uniform in [0.3, 3], and omega0 with max|omega0| = 1."""
    rng = np.random.default_rng(seed)
    moments = np.exp(rng.uniform(np.log(0.3), np.log(3.0), 10))
    w0 = rng.normal(size=10)
    return moments, w0 / np.abs(w0).max()


def reference(body, w0, t):
    """splitting8 with compensated storage at dt = 0.002 (errors ~1e-15 over these runs), as omega;
    its distance to an independent method (DOP853 at rtol 1e-13) is printed."""
    ref = simulate(body, w0, t, method="splitting8", dt=0.002, options={"compensated": True}).omega
    dop = simulate(body, w0, t, method="DOP853", rtol=1e-13).omega
    print(f"  reference T={t[-1]:g}: splitting8(dt=0.002) vs DOP853(rtol=1e-13): "
          f"{np.abs(ref - dop).max() / np.abs(w0).max():.1e}")
    return ref


def problems(quick):
    out = []
    for T in (20.0, 200.0):
        t = np.linspace(0.0, T, 101)
        out.append((f"top3d T={T:g}", RigidBody(MOM3), W3, t, euler_poinsot(MOM3, W3, t)))
        q = Inertia.quartet(0.5)
        wq = np.random.default_rng(2026).normal(size=10)
        wq /= np.abs(wq).max()
        out.append((f"quartet T={T:g}", RigidBody(q), wq, t, quartet_solution(0.5, wq, t)))
        for seed in ((1,) if quick else (1, 2)):
            m, w0 = generic_body(seed)
            out.append((f"generic5#{seed} T={T:g}", m, w0, t, reference(m, w0, t)))
    return out


def overhead_table(probs, quick, repeats):
    print("\n== 1. rtol call over the fixed-step run at the step it chose (goal <= 1.5x) ==")
    print(f"{'problem':>20} {'rtol':>7} {'method':>11} {'steps':>8} {'t_rtol [s]':>10} {'t_dt [s]':>9} "
          f"{'ratio':>6} {'err/rtol':>8}")
    rows = []
    rtols = (1e-6, 1e-9, 1e-12) if quick else (1e-6, 1e-8, 1e-10, 1e-12)
    for name, body, w0, t, ref in probs:
        for warm in ("splitting8", "splitting10"):  # JIT (the kernels and the step control's compiled parts)
            if warm in SIMULATION_METHODS:
                simulate(body, w0, t[:3], method=warm, rtol=1e-6)
        moments = np.asarray(getattr(getattr(body, "inertia", None), "moments", body), dtype=float)
        for rtol in rtols:
            try:
                tr = simulate(body, w0, t, rtol=rtol)
            except ValueError as exc:  # refused: out of reach (chaotic orbit) or over the budget
                print(f"{name:>20} {rtol:>7.0e} refused: {str(exc)[:150]}...")
                rows.append(dict(problem=name, rtol=rtol, method="refused", steps=None, t_rtol=None, t_dt=None,
                                 ratio=None, error_over_rtol=None))
                continue
            kw = dict(method=tr.stats["method"], dt=tr.stats["dt"])
            if "compensated" in tr.stats:
                kw["options"] = {"compensated": tr.stats["compensated"]}
            (el, el_dt), (tr, _) = best_of_interleaved(  # (the two calls in turn: their ratio is load-robust)
                [lambda: simulate(body, w0, t, rtol=rtol), lambda: simulate(body, w0, t, **kw)], repeats,
                seconds=0.5 if quick else 1.5)
            L, Lref = tr.omega * moments, ref * moments
            err = np.abs(L - Lref).max() / np.abs(Lref).max() / rtol
            rows.append(dict(problem=name, rtol=rtol, method=tr.stats["method"], steps=tr.stats["steps"],
                             t_rtol=el, t_dt=el_dt, ratio=el / el_dt, error_over_rtol=err))
            print(f"{name:>20} {rtol:>7.0e} {tr.stats['method']:>11} {tr.stats['steps']:>8d} {el:>10.4g} "
                  f"{el_dt:>9.4g} {el / el_dt:>6.2f} {err:>8.3f}")
    r = np.array([row["ratio"] for row in rows if row["ratio"] is not None])
    print(f"ratio: median {np.median(r):.2f}, max {r.max():.2f}; bound missed in "
          f"{sum((row['error_over_rtol'] or 0) > 1 for row in rows)} of {len(rows)} (refused: "
          f"{sum(row['ratio'] is None for row in rows)})")
    return rows


def headline(quick, repeats, target=1e-10):
    print(f"\n== 2. one rtol call reaching error <= {target:g} vs DOP853 at the same error ==")
    q = Inertia.quartet(0.5)
    wq = np.random.default_rng(2026).normal(size=10)
    wq /= np.abs(wq).max()
    tq = np.linspace(0.0, 200.0, 101)
    m, wg = generic_body(1)
    tg = np.linspace(0.0, 20.0, 101)
    cases = [("quartet T=200", RigidBody(q), wq, tq, quartet_solution(0.5, wq, tq), 250.0),
             ("generic5#1 T=20", m, wg, tg, reference(m, wg, tg), 60.0)]
    rows = []
    for name, body, w0, t, ref, goal in cases:
        scale = np.abs(w0).max()
        ours = None
        for method in ("auto", "splitting8", "splitting10"):  # the fastest call of a hyperrotor method reaching it
            if method != "auto" and method not in SIMULATION_METHODS:  # (an older tree, run for "before")
                continue
            for rtol in (1e-8, 3e-9, 1e-9, 3e-10, 1e-10, 3e-11, 1e-11):
                el, tr = best_of(lambda: simulate(body, w0, t, rtol=rtol, method=method), repeats)
                err = np.abs(tr.omega - ref).max() / scale
                if err <= target:
                    print(f"{name:>16}: method={method} rtol={rtol:g} ({tr.stats['method']}, {tr.stats['steps']} steps, "
                          f"work {tr.stats['work']}) {el:.4g} s, error {err:.2e}")
                    if ours is None or el < ours[1]:
                        ours = (rtol, el, err, tr.stats["method"], tr.stats["dt"], tr.stats.get("compensated"), method)
        dop = None
        for rtol in (1e-9, 3e-10, 1e-10, 3e-11, 1e-11, 3e-12, 1e-12, 3e-13, 1e-13):
            el, tr = best_of(lambda: simulate(body, w0, t, method="DOP853", rtol=rtol), max(1, repeats - 1))
            err = np.abs(tr.omega - ref).max() / scale
            if err <= target:
                dop = (rtol, el, err)
                break
        el_dt = ratio = ceiling = float("nan")
        if ours and dop:  # the three calls in turn (DOP853's time moved 2-3x between runs of the machine): our call,
            # DOP853's and the ceiling, the fixed-step run alone at the step our call chose (no probe, no check)
            (el_ours, el_dop, el_dt), _ = best_of_interleaved(
                [lambda: simulate(body, w0, t, rtol=ours[0], method=ours[6]),
                 lambda: simulate(body, w0, t, method="DOP853", rtol=dop[0]),
                 lambda: simulate(body, w0, t, method=ours[3], dt=ours[4], options={"compensated": ours[5]})],
                repeats + 1)
            ours, dop = (ours[0], el_ours, *ours[2:]), (dop[0], el_dop, dop[2])
            ratio, ceiling = el_dop / el_ours, el_dop / el_dt
        print(f"{name:>16}: hyperrotor rtol={ours[0]:g} ({ours[3]}) {ours[1]:.4g} s err {ours[2]:.2e}; "
              f"DOP853 rtol={dop[0] if dop else float('nan'):g} {dop[1] if dop else float('nan'):.4g} s -> "
              f"{ratio:.0f}x (goal >= {goal:g}x); the fixed-step run alone at that step {el_dt:.4g} s: "
              f"{ceiling:.0f}x")
        rows.append(dict(problem=name, ours_rtol=ours[0], ours_time=ours[1], ours_error=ours[2],
                         dop853_rtol=dop and dop[0], dop853_time=dop and dop[1], speedup=ratio, goal=goal,
                         fixed_step_time=el_dt, fixed_step_speedup=ceiling))
    return rows


def bound_table(quick):
    n = 6 if quick else 20
    print(f"\n== 3. whole-run bound on {n} random generic 5D bodies (T = 20, auto method) ==")
    rows = []
    t = np.linspace(0.0, 20.0, 41)
    cases = [generic_body(100 + k) for k in range(n)]
    refs = [reference(m, w0, t) * m for m, w0 in cases]
    for rtol in (1e-6, 1e-8, 1e-10):
        worst, held, t0 = 0.0, 0, time.perf_counter()
        for (m, w0), Lref in zip(cases, refs):
            tr = simulate(m, w0, t, rtol=rtol)
            e = np.abs(tr.L - Lref).max() / np.abs(Lref).max() / rtol
            worst = max(worst, e)
            held += e <= 1.0
        print(f"rtol {rtol:.0e}: bound held {held}/{n}, worst err/rtol {worst:.3f} ({time.perf_counter() - t0:.2f} s)")
        rows.append(dict(rtol=rtol, bodies=n, held=held, worst_error_over_rtol=worst))
    return rows


def auto_table(quick, repeats):
    """Wall time of rtol calls of splitting8 and splitting10 (step choice included): where method="auto"
    switches from order 8 to order 10 (``Splitting8.auto_rtol``)."""
    print("\n== 4. rtol calls of splitting8 / splitting10 (ms): the threshold of method='auto' ==")
    q = Inertia.quartet(0.5)
    wq = np.random.default_rng(2026).normal(size=10)
    wq /= np.abs(wq).max()
    cases = [("top3d T=20", RigidBody(MOM3), W3, np.linspace(0.0, 20.0, 101)),
             ("quartet T=200", RigidBody(q), wq, np.linspace(0.0, 200.0, 101))]
    cases += [(f"generic5#{s} T=20", *generic_body(s), np.linspace(0.0, 20.0, 101)) for s in ((1,) if quick else (1, 2, 3))]
    rows = []
    for rtol in (1e-7, 1e-9, 1e-10, 1e-11, 1e-12):
        line = []
        for name, body, w0, t in cases:
            el8 = best_of(lambda: simulate(body, w0, t, rtol=rtol, method="splitting8"), repeats)[0]
            el10 = best_of(lambda: simulate(body, w0, t, rtol=rtol, method="splitting10"), repeats)[0]
            rows.append(dict(problem=name, rtol=rtol, splitting8=el8, splitting10=el10))
            line.append(f"{name} {el8 * 1e3:.2f}/{el10 * 1e3:.2f}")
        print(f"rtol {rtol:.0e}: " + " | ".join(line))
    return rows


def ensemble_table(quick):
    """Table 5: every member of 20-member ensembles on random generic 5D bodies against a reference (splitting10
    at dt = 0.002, compensated; a second one, splitting8 at dt = 0.001, gives the reference's own uncertainty,
    which on chaotic members reaches 1e-9 ... 4e-8); a member over rtol is a named miss when the call warned
    (AccuracyWarning: the orbit amplifies the rounding of its own initial state beyond rtol) and its error is
    within the accuracy the warning names (plus the references' disagreement), else silent."""
    seeds = range(4000, 4004) if quick else range(4000, 4008)
    print(f"\n== 5. ensembles: {len(seeds)} random generic 5D bodies x 20 members (T = 20, 41 output times) ==")
    t = np.linspace(0.0, 20.0, 41)
    rows = []
    for seed in seeds:
        rng = np.random.default_rng(seed)
        moments = np.exp(rng.uniform(np.log(0.3), np.log(3.0), 10))
        W = rng.normal(size=(20, 10)) * rng.uniform(0.2, 1.0, (20, 1))
        ref = simulate(moments, W, t, method="splitting10", dt=0.002, options={"compensated": True}).L
        ref2 = simulate(moments, W, t, method="splitting8", dt=0.001, options={"compensated": True}).L
        scale = np.abs(ref).max(axis=(1, 2))
        ref_scatter = np.abs(ref - ref2).max(axis=(1, 2)) / scale  # (on chaotic members the references disagree)
        for rtol in (1e-6, 1e-9):
            t0 = time.perf_counter()
            category = getattr(hr, "AccuracyWarning", None)  # (a tree before it: every miss is silent)
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                tr = simulate(moments, W, t, rtol=rtol)
            seconds = time.perf_counter() - t0
            err = np.abs(tr.L - ref).max(axis=(1, 2)) / scale
            named = [float(re.search(r"accurate to about (\S+), not", str(w.message)).group(1))
                     for w in caught if category is not None and issubclass(w.category, category)]
            floor = max(named) if named else None
            worst = int(err.argmax())
            unsure = ref_scatter[worst]
            verdict = ("held" if err.max() <= rtol else
                       "named" if floor is not None and err.max() <= floor + unsure else
                       "within the references' disagreement" if err.max() <= rtol + unsure else "SILENT MISS")
            print(f"body {seed} rtol {rtol:.0e}: worst member {worst} err/rtol {err.max() / rtol:.3g} (references "
                  f"differ by {unsure / rtol:.2g} rtol there), "
                  f"{tr.stats['steps']} steps, {tr.stats['reruns']} re-runs, {seconds:.2f} s; "
                  + (f"AccuracyWarning names {floor:.2g}; " if floor is not None else "") + verdict)
            rows.append(dict(body=seed, rtol=rtol, worst_member=worst, worst_error_over_rtol=err.max() / rtol,
                             reference_scatter_over_rtol=unsure / rtol,
                             steps=tr.stats["steps"], reruns=tr.stats["reruns"], seconds=seconds,
                             named_accuracy=floor, verdict=verdict))
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer problems and tolerances")
    ap.add_argument("--tag", default="", help="suffix of the csv files (e.g. _before)")
    args = ap.parse_args(argv)
    RESULTS.mkdir(exist_ok=True)
    t0 = time.perf_counter()
    repeats = 2 if args.quick else 3
    probs = problems(args.quick)
    rows = overhead_table(probs, args.quick, repeats)
    head = headline(args.quick, repeats)
    bound = bound_table(args.quick)
    auto = auto_table(args.quick, repeats) if "splitting10" in SIMULATION_METHODS else []
    ensembles = ensemble_table(args.quick)
    write_csv(rows, RESULTS / f"step_control_overhead{args.tag}.csv")
    write_csv(head, RESULTS / f"step_control_headline{args.tag}.csv")
    write_csv(bound, RESULTS / f"step_control_bound{args.tag}.csv")
    if auto:
        write_csv(auto, RESULTS / f"step_control_auto{args.tag}.csv")
    if ensembles:
        write_csv(ensembles, RESULTS / f"step_control_ensembles{args.tag}.csv")
    print(f"\nwrote {RESULTS}/step_control*{args.tag}.csv (total {time.perf_counter() - t0:.0f} s)")


if __name__ == "__main__":
    main()
