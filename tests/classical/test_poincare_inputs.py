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
    (dict(ax=3), TypeError, "ax must be a 2-D matplotlib Axes"),
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


def test_a_locked_body_s_section_is_plotted_in_its_own_labels():
    """plot_poincare checked x, y against axes 1..N: a body locked on axis 1 (axes 2..5) could plot only planes
    inside {2, 3, 4}, and the default x = (1, 3) failed after a figure was made."""
    pytest.importorskip("matplotlib")
    from matplotlib.figure import Figure

    body = hr.RigidBody(hr.Inertia.from_mass_tensor([1.0, 2.0, 3.0, 4.0, 5.0])).lock(1)
    sec = hr.poincare_section(body, np.linspace(0.2, 0.9, 6), 40.0, plane=(2, 3))
    ax = Figure().add_subplot()
    plot_poincare(sec, x=(2, 4), y=(3, 5), ax=ax)
    xy = np.column_stack(ax.collections[0].get_offsets().T)
    np.testing.assert_array_equal(xy, sec.coordinates((2, 4), (3, 5)))
    assert ax.get_xlabel() == "$L_{24}$" and ax.get_ylabel() == "$L_{35}$"
    with pytest.raises(ValueError, match=r"x = \(1, 3\) \(the default: pass x= and y=\) is no plane of the sections' "
                                         r"axes \(2, 3, 4, 5\)"):
        plot_poincare(sec, ax=ax)


def test_the_axes_must_be_2d_and_the_title_names_every_kind_of_section():
    """Polar or 3-D axes were accepted (L_x drawn as an angle); several sections of different planes, levels or
    directions were titled with the first one's only; sections of different bodies crashed after the figure."""
    pytest.importorskip("matplotlib")
    from matplotlib.figure import Figure

    fig = Figure()
    for projection in ("polar", "3d"):
        with pytest.raises(TypeError, match=f"2-D matplotlib Axes.*'{projection}' projection"):
            plot_poincare(_section(), ax=fig.add_subplot(projection=projection))
    other = PoincareSection(t=np.array([0.5]), L=np.ones((1, 6)), omega=np.ones((1, 6)), plane=(3, 4), value=0.1,
                            direction=-1, N=4)
    ax = plot_poincare([_section(), other, _section()], ax=fig.add_subplot())
    assert ax.get_title() == "sections $L_{12} = 0$ (upward); $L_{34} = 0.1$ (downward)"
    three = PoincareSection(t=np.array([0.5]), L=np.ones((1, 3)), omega=np.ones((1, 3)), plane=(1, 2), value=0.0,
                            direction=1, N=3)
    with pytest.raises(ValueError, match="same axes"):
        plot_poincare([_section(), three], ax=fig.add_subplot())
