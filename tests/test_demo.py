"""Tests of hyperrotor.demo: the quartet demo's physics as library functions (what `hyperrotor demo` prints)."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest
import sympy as sp

import hyperrotor as hr
from hyperrotor._jit import JIT_ENABLED
from hyperrotor.classical import quartet_frequencies, quartet_matrix, quartet_theta
from hyperrotor.classical.solvers.step_control import rate_bound
from hyperrotor.demo import (DEMO_OMEGA, DEMO_RUNS, compare_quartet_motion, quartet_invariants,
                             quartet_motion_seconds, save_quartet_motion)


def test_invariants_against_independent_formulas():
    body = hr.RigidBody(hr.Inertia.quartet(sp.Rational(1, 2), axis=5, N=5))
    omega = np.array(DEMO_OMEGA)
    inv = quartet_invariants(body, omega)
    L = np.array([2, 2, 2, 1.25, 2, 2, 1.25, 2, 1.25, 1.25]) * omega  # I = 1 + kappa^2 on the planes with axis 5
    np.testing.assert_allclose(inv.L, L, rtol=1e-15)
    assert inv.energy == pytest.approx(0.5 * float(np.dot(L, omega)), rel=1e-14)
    assert inv.casimirs[0] == pytest.approx(float(np.sum(L**2)), rel=1e-14)
    assert inv.casimirs[1] == pytest.approx(np.poly(body.matrix(L))[4], rel=1e-12)  # lambda^1 coefficient
    A = hr.to_matrix(L, convention="standard") + np.diag([1, 1, 1, 1, 0.25]) ** 2  # L + J^2
    np.testing.assert_allclose(inv.manakov, [np.trace(np.linalg.matrix_power(A, k)) for k in range(2, 6)],
                               rtol=1e-12)
    assert np.all(inv.rhs[[0, 1, 2, 4, 5, 7]] == 0.0)  # planes without axis 5: constant omega
    with pytest.raises(TypeError, match="body must be a hyperrotor.RigidBody"):
        quartet_invariants([1.0] * 10, omega)


def test_motion_against_the_closed_form_and_its_picture(tmp_path):
    m = compare_quartet_motion(sp.Rational(1, 2), DEMO_OMEGA, 40.0, axis=4, n_times=401)
    assert [name for name, _ in DEMO_RUNS] == list(m.runs)
    for run in m.runs.values():  # the reported error is the one of the returned motion
        assert run.error == np.max(np.abs(run.omega - m.exact)) / np.max(np.abs(DEMO_OMEGA))
    assert m.runs["splitting8"].error < 1e-10 and m.runs["DOP853"].error < 1e-7
    assert m.runs["splitting8"].energy_drift < 1e-12
    # the frequencies after eq. (118): the imaginary parts of the eigenvalues of theta * M(omega)
    lam = np.sort(np.abs(np.linalg.eigvals(quartet_theta(0.5) * quartet_matrix(np.array(DEMO_OMEGA), 4)).imag))
    np.testing.assert_allclose(np.sort(m.frequencies), lam[::2], rtol=1e-12)
    path = save_quartet_motion(m, tmp_path / "m.png")
    assert (tmp_path / "m.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and path.endswith("m.png")


def test_priced_before_it_runs():
    short, long = (quartet_motion_seconds(0.5, DEMO_OMEGA, t) for t in (10.0, 1e6))
    assert long.seconds > 1000 * short.seconds > 0
    moments = np.asarray(hr.Inertia.quartet(0.5).moments, dtype=float)
    assert short.rate == long.rate == pytest.approx(rate_bound(moments, (np.array(DEMO_OMEGA) * moments)[None])[0],
                                                    rel=1e-15)
    assert short.frequency == long.frequency == pytest.approx(np.max(quartet_frequencies(0.5, DEMO_OMEGA)), rel=1e-15)
    # the output times are priced (10^6 of them took ~13 s wall at load 3, estimated 0.05 s before); a large kappa
    # costs the step control's rate bound (~ |kappa|), not kappa^2: kappa = 1000 over t_end = 30 ran 0.33 s,
    # estimated 2.9 h
    many = quartet_motion_seconds(0.5, DEMO_OMEGA, 10.0, n_times=10**6)
    assert many.seconds > 5.0 and many.rate == short.rate
    assert quartet_motion_seconds(1000, DEMO_OMEGA, 30.0).seconds < 1.0
    with hr.options(max_seconds=60.0), pytest.raises(hr.BudgetError, match="max_seconds"):
        compare_quartet_motion(0.5, DEMO_OMEGA, 1e6)


#: A child process: ``compare_quartet_motion`` with ``simulate`` wrapped to list, per call, the compiled functions
#: of hyperrotor (its modules and the generated unrolled ones) that gained a specialisation during the call
#: (numba compiled it or loaded it from its disk cache); one JSON line.
_NEW_KERNELS_PER_CALL = """
import importlib, json, sys
from hyperrotor.demo import compare_quartet_motion
from numba.core.registry import CPUDispatcher

def specialisations():
    return {f"{m}.{k}": len(v.overloads) for m, mod in list(sys.modules.items()) if m.startswith("hyperrotor")
            for k, v in list(vars(mod).items()) if isinstance(v, CPUDispatcher)}

sim = importlib.import_module("hyperrotor.classical.simulate")  # (the module: the package exports the function)
calls, real = [], sim.simulate
def spy(*args, **kw):
    before = specialisations()
    out = real(*args, **kw)
    after = specialisations()
    calls.append([kw.get("method"), sorted(k for k, n in after.items() if n > before.get(k, 0))])
    return out

sim.simulate = spy
compare_quartet_motion(0.5, t_end=20.0, n_times=201)
print(json.dumps(calls))
"""


@pytest.mark.skipif(not JIT_ENABLED, reason="numba's compiled functions are what the warm-up loads")
def test_the_timed_splitting_run_needs_no_kernel_its_untimed_first_call_did_not_load():
    """The demo reports warm wall times: the splitting run's first, untimed call is the same call, so the timed one
    loads no compiled function (on a fresh installation, numba would compile it inside the timing: the old warm-up,
    a plain-arithmetic run at a given step, left the compensated kernels and the step control to the timed run,
    which reported 14 s instead of 0.1 s). Measured in a fresh process, where nothing is loaded yet."""
    env = {**os.environ, "MPLBACKEND": "Agg"}
    out = subprocess.run([sys.executable, "-c", _NEW_KERNELS_PER_CALL], capture_output=True, text=True, env=env,
                         timeout=600)
    assert out.returncode == 0, out.stderr
    calls = json.loads(out.stdout.strip().splitlines()[-1])
    assert [method for method, _ in calls] == ["splitting8", "splitting8", "DOP853"]
    (_, first), (_, timed), (_, dop) = calls
    assert first  # (the spy sees what a call loads: in a fresh process the first call loads its kernels)
    assert timed == [] and dop == []


@pytest.mark.parametrize("kappa, says", [(0.5, "the four planes with axis 5 oscillate"),
                                         (1.0, "equal moments, every omega constant"),
                                         (-1.0, "equal moments, every omega constant")])
def test_the_pictures_title_says_what_the_body_does(monkeypatch, tmp_path, kappa, says):
    """kappa^2 = 1 makes every moment 2: nothing oscillates, and the title said four planes did."""
    from hyperrotor import plotting

    seen = {}
    monkeypatch.setattr(plotting, "save_motion_comparison", lambda path, *a, title, **k: seen.setdefault("t", title))
    motion = compare_quartet_motion(kappa, t_end=2.0)
    save_quartet_motion(motion, tmp_path / "q.png")
    assert seen["t"].endswith(says)
    if kappa ** 2 == 1:
        assert np.abs(np.diff(motion.exact, axis=0)).max() == 0.0  # (constant indeed)
