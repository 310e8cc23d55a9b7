"""Poincaré sections from simulate's events: crossings on the section, periods, invariants, plot."""
import math
import re

import numpy as np
import pytest

import hyperrotor as hr
from hyperrotor.classical import PoincareSection, poincare_section
from hyperrotor.plotting import plot_poincare
from hyperrotor.classical import euler_poinsot_period
from hyperrotor.conventions import plane_index, planes

from tolerance import EPS


def casimir_c2(L):
    return 0.5 * np.sum(L * L, axis=-1)


def energy(L, moments):
    return 0.5 * np.sum(L * L / moments, axis=-1)


@pytest.mark.parametrize("plane", [(1, 3), (2, 3)])
def test_3d_top_section_is_one_point_per_period(plane):
    """A 3D top has one degree of freedom: the orbit is periodic, so it crosses the section
    once per period (closed form, Jacobi elliptic) and always at the same point."""
    moments = np.array([2.0, 3.0, 4.0])
    w0 = np.array([0.3, 1.0, 0.2])
    period = euler_poinsot_period(moments, w0)
    sec = poincare_section(moments, w0, 5.2 * period, plane=plane, dt=0.002)
    assert len(sec) == 5
    assert np.allclose(np.diff(sec.t), period, rtol=1e-9, atol=0)
    a = plane_index(plane, 3)
    assert np.all(np.abs(sec.L[:, a]) < 1e-10 * np.linalg.norm(w0 * moments))
    assert np.ptp(sec.L, axis=0).max() < 1e-9 * np.linalg.norm(w0 * moments)


def test_crossings_lie_on_the_section_with_the_right_direction():
    g = np.random.default_rng(4)
    moments = np.exp(g.uniform(math.log(0.3), math.log(3.0), 10))
    L0 = g.standard_normal(10)
    L0 *= 3.0 / np.linalg.norm(L0)
    body = hr.RigidBody(hr.Inertia(moments))
    for direction in (1, -1):
        sec = poincare_section(body, L0 / moments, 60.0, plane=(2, 4), value=0.3, direction=direction)
        assert isinstance(sec, PoincareSection) and len(sec) >= 5
        a = plane_index((2, 4), 5)
        assert np.all(np.abs(sec.L[:, a] - 0.3) < 1e-9 * 3.0)
        # the sign of dL_a/dt at each crossing (Euler equations of the body) is the requested one
        dL = np.array([body.rhs(w) for w in sec.omega])[:, a] * moments[a]
        assert np.all(np.sign(dL) == direction)
        # every crossing is on the starting orbit: Casimir to round-off, energy to the method's error
        assert np.allclose(casimir_c2(sec.L), casimir_c2(L0), rtol=1e3 * EPS, atol=0)
        assert np.allclose(energy(sec.L, moments), energy(L0, moments), rtol=1e-7, atol=0)
        assert np.all(np.diff(sec.t) > 0)


def test_locked_so4_section_is_a_curve_for_manakov_body():
    """5D Manakov body with L in the invariant so(4) (axis 5 locked): two degrees of freedom,
    integrable, so the section's points lie on a curve: the box-counting dimension is ~1."""
    body = hr.Inertia.from_mass_tensor([0.3, 0.5, 0.8, 1.2, 1.7])
    L0 = np.zeros(10)
    so4 = [plane_index(p, 5) for p in planes(5) if 5 not in p]
    L0[so4] = np.random.default_rng(2).standard_normal(6)
    L0 *= 3.0 / np.linalg.norm(L0)
    sec = poincare_section(body, L0 / body.moments, 4000.0, plane=(1, 2))
    assert len(sec) > 300
    xy = sec.coordinates((1, 3), (2, 4))
    # the locked planes stay zero at every crossing
    locked = [plane_index(p, 5) for p in planes(5) if 5 in p]
    assert np.abs(sec.L[:, locked]).max() == 0.0
    span = np.ptp(xy, axis=0)
    counts = []
    for boxes in (16, 64):
        cells = np.floor((xy - xy.min(axis=0)) / (span / boxes * (1 + 1e-9))).astype(int)
        counts.append(len({tuple(c) for c in cells}))
    dim = math.log(counts[1] / counts[0]) / math.log(4)
    assert dim < 1.3, (counts, dim)


def test_plot_draws_the_section_coordinates():
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    moments = np.array([2.0, 3.0, 4.0])
    sec = poincare_section(moments, [0.3, 1.0, 0.2], 100.0, plane=(1, 3), dt=0.01)
    fig, ax = plt.subplots()
    try:
        out = plot_poincare([sec, sec], x=(1, 2), y=(2, 3), ax=ax, labels=["a", "b"])
        assert out is ax
        assert np.array_equal(ax.collections[0].get_offsets(), sec.coordinates((1, 2), (2, 3)))
        assert ax.get_xlabel() == "$L_{12}$"
    finally:
        plt.close(fig)


@pytest.mark.parametrize("kwargs, exc, words", [
    (dict(omega0=np.ones((2, 3))), ValueError, "one orbit"),
    (dict(plane=(3, 1)), ValueError, "plane"),
    (dict(direction=2), ValueError, "direction"),
    (dict(direction=True), TypeError, "direction must be a real number, got True"),  # (a bool is not a direction)
    (dict(direction="1"), TypeError, "direction must be a real number, got '1'"),
    (dict(direction=0.5), ValueError, "direction"),
    (dict(T=0.0), ValueError, "T must be"),
    (dict(method="DOP853"), ValueError, "splitting8"),
])
def test_bad_arguments_are_named(kwargs, exc, words):
    args = dict(omega0=np.array([0.3, 1.0, 0.2]), T=10.0)
    args.update(kwargs)
    with pytest.raises(exc, match=words):
        poincare_section([2.0, 3.0, 4.0], args.pop("omega0"), args.pop("T"), **args)


def test_plot_rejects_non_sections():
    with pytest.raises(TypeError, match="PoincareSection"):
        plot_poincare([np.zeros((3, 3))])


def test_a_long_section_is_refused_by_its_time_before_it_runs(monkeypatch):
    """T = 1e7 on a 5D body (8e7 steps, under max_steps) was not refused: an estimated 15-20 minutes, the event
    evaluated in Python at every step (a review). Priced now by steps, flows and crossings against max_seconds."""
    from hyperrotor.classical import poincare

    def no_run(*args, **kwargs):
        raise AssertionError("the orbit started before the budget refused it")

    monkeypatch.setattr(poincare, "simulate", no_run)
    g = np.random.default_rng(1)
    m, w = np.exp(g.uniform(np.log(0.3), np.log(3.0), 10)), g.normal(size=10)
    with pytest.raises(hr.BudgetError, match=r"poincare_section: .*steps of so\(5\).*max_seconds") as info:
        poincare_section(m, w, 1e7)
    seconds = float(re.search(r"would need ~([0-9.e+]+) s", str(info.value)).group(1))
    assert 600 < seconds < 1e4  # (the default budget, 600 s, against the review's 15-20 minutes)
