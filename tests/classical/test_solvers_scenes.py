"""Scenes of locked bodies: the minimal route uses the body's own axis labels for the paper signs."""
import numpy as np

from hyperrotor import Inertia, RigidBody
from hyperrotor.classical.scenes import Scene, evaluate_scene


def test_locked_body_attitude_same_on_minimal_and_full_route():
    """Axis 2 locked: the remaining axes are 1, 3, 4, whose paper signs (-1)^a are -, -, +, not those
    of 1, 2, 3; both routes must give the same attitude (to the integration accuracy)."""
    body = RigidBody(Inertia.from_mass_tensor([1, 2, 3.5, 5]), convention="paper").lock(2)
    w0 = np.array([0.3, 1.0, -0.4])
    t = np.linspace(0.0, 3.0, 7)
    scene = Scene(body, w0, t, observables=("attitude",), rtol=1e-10)
    a = evaluate_scene(scene, minimal=True).attitude
    b = evaluate_scene(scene, minimal=False).attitude
    assert np.abs(a - b).max() <= 1e-8 * t[-1]
