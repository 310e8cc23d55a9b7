"""Tests of hyperrotor.bench and ``hyperrotor bench`` (accuracy of the runs, speed-up bookkeeping, files)."""
import csv

import pytest

from hyperrotor.bench import WorkPrecisionPoint, best_of_interleaved, speedup_at, work_precision
from hyperrotor.cli import main


def test_work_precision_errors_against_the_elliptic_solution():
    pts = work_precision("euler-poinsot", ["splitting8", "DOP853"], repeats=1)
    by = {(p.method, round(p.value, 12)): p for p in pts}
    # order 8: the step 1 -> 0.5 (100 -> 200 steps on the unit output spacing, a true halving) gains
    # over 2^6 (2^8 asymptotically); from dt = 1/4 on the error is at the round-off floor (< 1e-11)
    assert by["splitting8", 1.0].error / by["splitting8", 0.5].error > 2**6
    assert max(by["splitting8", round(v, 12)].error for v in (0.25, 0.2, 0.1)) < 1e-11
    assert by["DOP853", 1e-12].error < 1e-10
    assert all(p.seconds > 0 for p in pts)


def test_speedup_at_picks_fastest_runs_reaching_the_level():
    P = lambda m, e, s: WorkPrecisionPoint("x", m, "dt", 0.1, e, s)  # noqa: E731
    pts = [P("splitting8", 1e-11, 0.02), P("splitting4", 1e-11, 0.01), P("splitting2", 1e-6, 0.001),
           P("DOP853", 1e-9, 0.1), P("DOP853", 1e-11, 0.5), P("DOP853", 1e-12, 0.8)]
    s = speedup_at(pts, 1e-10)
    assert s == {"method": "splitting4", "seconds": 0.01, "peer_seconds": 0.5, "ratio": 50.0}
    assert speedup_at(pts, 1e-13) is None


def test_best_of_interleaved_calls_in_turn_and_keeps_the_best(monkeypatch):
    """Rounds call the functions in turn (the order of the calls is a, b, a, b, ...), at least ``repeats`` of
    them and more until about ``seconds`` were spent (on a clock that advances 1 per call of a and 3 per
    call of b); the best times are the fastest calls and the results the last ones."""
    import hyperrotor.bench as bench

    clock, calls = [0.0], []

    def fn(name, cost):
        def call():
            calls.append(name)
            clock[0] += cost[len([c for c in calls if c == name]) % len(cost)]
            return len(calls)
        return call

    monkeypatch.setattr(bench.time, "perf_counter", lambda: clock[0])
    best, out = best_of_interleaved([fn("a", [2.0, 1.0]), fn("b", [3.0])], 3)
    assert calls == ["a", "b"] * 3 and best == [1.0, 3.0] and out == [5, 6]
    calls.clear()
    best, out = best_of_interleaved([fn("a", [1.0]), fn("b", [3.0])], 2, seconds=40.0)
    assert calls == ["a", "b"] * 10 and best == [1.0, 3.0] and out == [19, 20]  # (the first round took 4)
    with pytest.raises(ValueError, match="repeats must be >= 1, got 0"):
        best_of_interleaved([fn("a", [1.0])], 0)


def test_cli_bench_writes_csv_and_png(capsys, tmp_path):
    stem = tmp_path / "wp"
    code = main(["bench", "--problem", "euler-poinsot", "--method", "splitting6", "--method", "DOP853",
                 "--repeats", "1", "--output", str(stem)])
    out = capsys.readouterr().out
    assert code == 0
    with open(f"{stem}.csv", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert {r["method"] for r in rows} == {"splitting6", "DOP853"} and len(rows) == 10
    assert min(float(r["error"]) for r in rows if r["method"] == "splitting6") < 1e-10
    assert "euler-poinsot: at relative error <= 1e-10 splitting6" in out
    assert (tmp_path / "wp.png").read_bytes()[:4] == b"\x89PNG"


def test_cli_bench_bad_method(capsys):
    assert main(["bench", "--method", "Euler"]) == 2
    assert "invalid choice: 'Euler'" in capsys.readouterr().err


def test_unknown_problem():
    with pytest.raises(ValueError, match="unknown problem 'pendulum'"):
        work_precision("pendulum")


def test_write_csv_dicts_and_dataclasses_round_trip(tmp_path):
    from hyperrotor.bench import write_csv

    rows = [{"N": 3, "seconds": 0.5}, {"N": 4, "seconds": 1.25}]
    path = write_csv(rows, tmp_path / "d.csv")
    with open(path, encoding="utf-8") as fh:
        back = list(csv.DictReader(fh))
    assert [(int(r["N"]), float(r["seconds"])) for r in back] == [(3, 0.5), (4, 1.25)]
    pt = WorkPrecisionPoint("p", "m", "dt", 0.1, 1e-9, 0.25, 5, 200.0)
    with open(write_csv([pt], tmp_path / "p.csv"), encoding="utf-8") as fh:
        (row,) = csv.DictReader(fh)
    assert row == {"problem": "p", "method": "m", "setting": "dt", "value": "0.1", "error": "1e-09", "seconds": "0.25",
                   "N": "5", "t_end": "200.0"}
    with pytest.raises(ValueError, match="at least one row"):
        write_csv([], tmp_path / "e.csv")


def test_the_steps_reported_are_the_steps_taken():
    """bench's dt column was the requested largest step: on the 3D top's output intervals of 1, splitting10 at
    dt = 2 and 1 were the same run (two points of one error under two labels), and splitting8's 0.6 ran at 0.5 on
    the quartet's intervals of 2. The points are the distinct steps the runs take now."""
    from hyperrotor import simulate
    from hyperrotor.bench import BENCH_PROBLEMS, _problem, n_runs

    for problem in BENCH_PROBLEMS:
        pts = work_precision(problem, ["splitting10"], repeats=1)
        steps = [p.value for p in pts]
        assert len(set(steps)) == len(steps) == n_runs([problem], ["splitting10"])
        body, w0, t, _ = _problem(problem)
        for p in pts:
            assert simulate(body, w0, t, method="splitting10", dt=p.value).stats["dt"] == pytest.approx(p.value,
                                                                                                      rel=1e-12)
