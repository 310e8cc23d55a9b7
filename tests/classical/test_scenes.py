"""Scenes: the minimal route gives the same numbers as the full computation."""
import importlib
import itertools

import numpy as np
import pytest

import hyperrotor
from hyperrotor.classical import (
    Scene,
    ellipsoid_points,
    evaluate_scene,
    hypercube_vertices,
    locked_axes,
    simplex_vertices,
)
from hyperrotor.conventions import plane_index, planes
from tolerance import scaled_tol

_integrate = importlib.import_module("hyperrotor.classical.simulate")  # the module (its function has the same name)
FIELDS = ("omega", "L", "energy", "casimirs", "attitude", "projection")
RNG = np.random.default_rng(2024)
GENERIC = RNG.uniform(1.0, 3.0, size=10)
T = np.linspace(0.0, 15.0, 121)


def _on_planes(values, plist, N=5):
    w = np.zeros(N * (N - 1) // 2)
    for p, v in zip(plist, values):
        w[plane_index(p, N)] = v
    return w


def _compare(scene, tol):
    a = scene.evaluate()
    b = evaluate_scene(scene, minimal=False)
    assert b.path == "full"
    for f in FIELDS:
        x, y = getattr(a, f), getattr(b, f)
        assert (x is None) == (y is None), f
        if x is not None:
            assert x.shape == y.shape, f
            scale = max(1.0, float(np.max(np.abs(y))))
            np.testing.assert_allclose(x, y, rtol=0, atol=tol * scale, err_msg=f)
    return a


def test_hypercube_and_simplex_vertices():
    for N in (2, 3, 5):
        V = hypercube_vertices(N)
        assert V.shape == (2**N, N)
        assert len({tuple(v) for v in V}) == 2**N and np.all(np.abs(V) == 1.0)
        S = simplex_vertices(N)
        assert S.shape == (N + 1, N)
        np.testing.assert_allclose(S.sum(axis=0), 0.0, rtol=0, atol=scaled_tol(S))
        np.testing.assert_allclose(np.linalg.norm(S, axis=1), 1.0, rtol=1e-14)
        d = [np.linalg.norm(S[i] - S[j]) for i, j in itertools.combinations(range(N + 1), 2)]
        np.testing.assert_allclose(d, np.sqrt(2.0 * (N + 1) / N), rtol=1e-13)  # edge of the unit-circumradius simplex
    a = np.array([1.0, 2.0, 0.5, 3.0, 1.5])
    P = ellipsoid_points(a, 50)
    np.testing.assert_allclose(np.sum((P / a) ** 2, axis=1), 1.0, rtol=1e-14)
    np.testing.assert_array_equal(P, ellipsoid_points(a, 50))
    with pytest.raises(ValueError, match="semi_axes"):
        ellipsoid_points([1.0, -1.0], 3)
    with pytest.raises(ValueError, match="n must"):
        ellipsoid_points([1.0, 1.0], 0)


def test_locked_axes():
    assert locked_axes(_on_planes([1.0, 2.0, 3.0], [(1, 2), (1, 3), (2, 3)])) == (4, 5)
    assert locked_axes(_on_planes([1.0], [(2, 4)])) == (1, 3, 5)
    assert locked_axes(np.ones(10)) == ()
    assert locked_axes(np.zeros(10)) == (1, 2, 3, 4, 5)


def test_quartet_closed_form_route():
    inertia = hyperrotor.Inertia.quartet(0.5, axis=3, N=5)
    w0 = RNG.normal(size=10)
    a = _compare(Scene(inertia, w0, T, observables=("omega", "energy", "L"), planes=[(1, 3), (4, 5)]), 1e-8)
    assert a.path == "closed-form:quartet"
    assert a.omega.shape == (T.size, 2) and a.planes == ((1, 3), (4, 5))


def test_invariants_route_does_not_integrate(monkeypatch):
    calls = []
    real = _integrate.simulate
    monkeypatch.setattr(_integrate, "simulate", lambda *a, **k: calls.append(k) or real(*a, **k))
    scene = Scene(GENERIC, RNG.normal(size=10), T, observables=("energy", "casimirs"))
    a = scene.evaluate()
    assert a.path == "invariants" and calls == []
    b = evaluate_scene(scene, minimal=False)
    np.testing.assert_allclose(a.energy, b.energy, rtol=1e-9)
    np.testing.assert_allclose(a.casimirs, b.casimirs, rtol=1e-9)


def test_no_attitude_unless_asked(monkeypatch):
    calls = []
    real = _integrate.simulate
    monkeypatch.setattr(_integrate, "simulate", lambda *a, **k: calls.append(k) or real(*a, **k))
    a = Scene(GENERIC, RNG.normal(size=10), T, observables=("omega",)).evaluate()
    assert a.path == "integrate" and a.attitude is None
    assert len(calls) == 1 and calls[0]["attitude"] is False


def test_reduced_to_euler_poinsot():
    w0 = _on_planes(RNG.normal(size=3), [(2, 3), (2, 5), (3, 5)])  # axes 1, 4 locked
    a = _compare(Scene(GENERIC, w0, T, observables=("omega", "L", "energy")), 1e-8)
    assert a.path == "reduced:axes(2,3,5)+closed-form:euler-poinsot"
    off = [plane_index(p, 5) for p in planes(5) if 1 in p or 4 in p]
    assert np.all(a.omega[:, off] == 0.0)


@pytest.mark.parametrize("convention", ["paper", "standard"])
def test_reduced_integration_with_attitude_and_projection(convention):
    body = hyperrotor.RigidBody(GENERIC, convention=convention)
    w0 = RNG.normal(size=10)
    w0[[plane_index(p, 5) for p in planes(5) if 5 in p]] = 0.0  # axis 5 locked
    Q, _ = np.linalg.qr(np.random.default_rng(1).normal(size=(5, 5)))
    scene = Scene(body, w0, T, observables=("omega", "attitude", "projection", "casimirs"),
                  points=hypercube_vertices(5), axes=(1, 2, 5), attitude0=Q)
    a = _compare(scene, 1e-8)
    assert a.path == "reduced:axes(1,2,3,4)+integrate"
    assert a.projection.shape == (T.size, 32, 3)
    # projection = rows (1, 2, 5) of T^T x_body
    full = np.einsum("kba,pb->kpa", a.attitude, hypercube_vertices(5))
    np.testing.assert_allclose(a.projection, full[:, :, [0, 1, 4]], rtol=0, atol=scaled_tol(hypercube_vertices(5)[0], a.attitude[0]))
    np.testing.assert_allclose(np.einsum("kji,kjl->kil", a.attitude, a.attitude), np.broadcast_to(np.eye(5), (T.size, 5, 5)),
                               atol=1e-12, rtol=0)


def test_equal_moments_closed_form_attitude():
    w0 = RNG.normal(size=10)
    scene = Scene(np.full(10, 2.5), w0, T, observables=("omega", "attitude", "projection"), points=simplex_vertices(5))
    a = _compare(scene, 1e-8)
    assert a.path == "closed-form:equal"


def test_steady_single_plane_rotation():
    """Only w_24 != 0: reduced to axes (2, 4), the attitude is an exact rotation in that plane."""
    w0 = _on_planes([0.7], [(2, 4)])
    a = _compare(Scene(GENERIC, w0, T, observables=("omega", "attitude")), 1e-8)
    assert a.path == "reduced:axes(2,4)+closed-form:equal"
    # paper convention: entry (2, 4) of W is (-1)^(2+4) w24 = w24; dT/dt = W T
    c, s = np.cos(0.7 * T), np.sin(0.7 * T)
    # cos/sin of a rounded phase 0.7 t: error ~ eps |0.7 t|, through 5 x 5 products
    tol = scaled_tol(0.7 * T[-1], dim=5)
    np.testing.assert_allclose(a.attitude[:, 1, 1], c, rtol=0, atol=tol)
    np.testing.assert_allclose(a.attitude[:, 1, 3], s, rtol=0, atol=tol)
    np.testing.assert_allclose(a.attitude[:, 3, 1], -s, rtol=0, atol=tol)


def test_generic_and_rest():
    a = _compare(Scene(GENERIC, RNG.normal(size=10), T, observables=("omega", "projection"),
                       points=ellipsoid_points([1, 2, 3, 4, 5], 10)), 1e-12)
    assert a.path == "integrate"
    a = _compare(Scene(GENERIC, np.zeros(10), T, observables=("omega", "attitude", "energy")), 0.0)
    assert a.path == "closed-form:rest"


def test_3d_body_uses_euler_poinsot():
    I3 = np.array([3.0, 2.0, 1.0])
    a = _compare(Scene(I3, [0.3, -1.0, 0.8], T, observables=("omega",)), 1e-8)
    assert a.path == "closed-form:euler-poinsot"


def test_bad_input():
    w0 = np.ones(10)
    with pytest.raises(ValueError, match="unknown observable"):
        Scene(GENERIC, w0, T, observables=("spin",)).evaluate()
    with pytest.raises(ValueError, match="needs body points"):
        Scene(GENERIC, w0, T, observables=("projection",)).evaluate()
    with pytest.raises(ValueError, match="projection axes"):
        Scene(GENERIC, w0, T, observables=("projection",), points=hypercube_vertices(5), axes=(0, 1)).evaluate()
    with pytest.raises(ValueError, match="points must have shape"):
        Scene(GENERIC, w0, T, observables=("projection",), points=hypercube_vertices(3)).evaluate()
    with pytest.raises(ValueError, match="omega0 must have shape"):
        Scene(GENERIC, np.ones(6), T).evaluate()
    with pytest.raises(ValueError, match="strictly increasing"):
        Scene(GENERIC, w0, T[::-1]).evaluate()
    with pytest.raises(ValueError, match="orthogonal"):
        Scene(GENERIC, w0, T, observables=("attitude",), attitude0=2 * np.eye(5)).evaluate()
    with pytest.raises(ValueError, match="unknown plane"):
        Scene(GENERIC, w0, T, planes=[(3, 1)]).evaluate()
    # attitude0 and points checked like every numeric input (NaN passed the orthogonality test, text was parsed)
    with pytest.raises(ValueError, match=r"attitude0 must be finite"):
        Scene(GENERIC, w0, T, observables=("attitude",), attitude0=np.full((5, 5), np.nan)).evaluate()
    with pytest.raises(TypeError, match="attitude0 must be numeric, got text"):
        Scene(GENERIC, w0, T, observables=("attitude",), attitude0=[["1"] * 5] * 5).evaluate()
    with pytest.raises(TypeError, match="points must be numeric, got a boolean entry"):
        Scene(GENERIC, w0, T, observables=("projection",), points=[[True, 0.0, 0.0, 0.0, 0.0]]).evaluate()


def test_scene_output_is_priced_before_any_work():
    """evaluate() returned 24 MB under a 1 MB output budget and raised MemoryError from NumPy at 6.7 GiB."""
    w0 = np.array([0.3, 0.5, 0.7])
    t = np.linspace(0.0, 1.0, 1000)
    for minimal in (True, False):
        with hyperrotor.options(max_output_bytes=10**6), pytest.raises(hyperrotor.BudgetError,
                                                                          match="max_output_bytes"):
            Scene([1.0, 2.0, 2.5], w0, t, observables=("projection",), points=np.zeros((1000, 3))).evaluate(
                minimal=minimal)
    small = Scene([1.0, 2.0, 2.5], w0, t[:10], observables=("projection",), points=np.eye(3)).evaluate()
    assert small.projection.shape[0] == 10
    # an invariants-only scene is priced as what it returns (one energy per time), not as omega and L
    with hyperrotor.options(max_output_bytes=10**6):
        energy = Scene(np.linspace(1.0, 2.0, 45), np.ones(45), np.linspace(0.0, 1.0, 5000),
                       observables=("energy",)).evaluate()
    assert energy.path == "invariants" and energy.energy.shape == (5000,)


def test_quartet_projection_closed_form():
    inertia = hyperrotor.Inertia.quartet(2.0, axis=4, N=5)
    scene = Scene(inertia, RNG.normal(size=10), T, observables=("omega", "projection", "attitude"),
                  points=hypercube_vertices(5), axes=(2, 3, 4))
    a = _compare(scene, 1e-8)
    assert a.path == "closed-form:quartet"


def test_progress_reaches_the_integration_and_changes_nothing(capsys):
    """Scene(progress=True): simulate's bar on stderr while an integrated (generic) motion is computed;
    the same numbers as without it. A non-boolean is refused by name."""
    w0 = RNG.normal(size=10)
    quiet = Scene(GENERIC, w0, T, observables=("omega",)).evaluate()
    capsys.readouterr()
    loud = Scene(GENERIC, w0, T, observables=("omega",), progress=True).evaluate()
    err = capsys.readouterr().err
    assert "simulate" in err and "step" in err
    np.testing.assert_array_equal(loud.omega, quiet.omega)
    with pytest.raises(TypeError, match="progress must be True, False or None, got 'yes'"):
        Scene(GENERIC, w0, T, observables=("omega",), progress="yes")
