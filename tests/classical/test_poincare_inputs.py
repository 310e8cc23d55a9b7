"""plot_poincare / poincare_section: every argument is checked before any figure or integration (#12 fuzzing)."""
import numpy as np
import pytest

import hyperrotor as hr
from hyperrotor.classical import PoincareSection
from hyperrotor.plotting import plot_poincare


def _section():
    L = np.arange(12.0).reshape(2, 6) + 1.0
    return PoincareSection(t=np.array([0.5, 1.0]), L=L, omega=L, plane=(1, 2), value=0.0, direction=1, N=4)


@pytest.mark.parametrize("kwargs, exc, words", [
    (dict(ax=3), TypeError, "ax must be a matplotlib Axes"),
    (dict(labels="orbit"), TypeError, "labels must be a list of strings"),
    (dict(labels={"a": 1}), TypeError, "labels must be a list of strings"),
    (dict(labels=["a", "b"]), ValueError, "each of the 1 sections"),
    (dict(x=(1, 9)), ValueError, "plane"),
])
def test_bad_plot_arguments_are_refused_before_a_figure_is_made(kwargs, exc, words):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    before = plt.get_fignums()
    with pytest.raises(exc, match=words):
        plot_poincare(_section(), **kwargs)
    assert plt.get_fignums() == before


def test_sections_must_be_sections():
    for bad in (None, 3, "sec", {"a": _section()}):
        with pytest.raises(TypeError, match="sections must be"):
            plot_poincare(bad)


def test_progress_is_a_switch_and_the_budget_names_omega0():
    body = hr.RigidBody(hr.Inertia.from_mass_tensor([1.0, 2.0, 3.0, 4.0]))
    w = np.linspace(0.1, 0.6, 6)
    with pytest.raises(TypeError, match="progress"):
        hr.poincare_section(body, w, 1.0, progress="no")
    with pytest.raises(ValueError, match=r"omega0 up to \|omega\| = 1e\+300"):
        hr.poincare_section(body, np.full(6, 1e300), 1.0)


def test_an_unknown_scatter_option_is_a_type_error():
    pytest.importorskip("matplotlib")
    from matplotlib.figure import Figure

    ax = Figure().add_subplot()
    with pytest.raises(TypeError, match="scatter_options.*'foo'"):
        plot_poincare(_section(), ax=ax, foo=1)
    assert plot_poincare(_section(), ax=ax, s=5, color="k") is ax


def test_a_resting_or_subnormal_orbit_has_no_crossings_and_no_step_error():
    body = hr.RigidBody(hr.Inertia.from_mass_tensor([1.0, 2.0, 3.0, 4.0]))
    for w in (np.zeros(6), np.full(6, 5e-324), np.full(6, 1e-300)):  # 5e-324 made the default dt inf
        sec = hr.poincare_section(body, w, 1.0, value=0.5)
        assert len(sec) == 0 and sec.L.shape == (0, 6)
