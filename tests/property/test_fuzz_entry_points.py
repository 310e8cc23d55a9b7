"""Fuzzing of every public constructor and entry point with bad values.

Every name in ``hyperrotor.__all__``, ``hyperrotor.classical.__all__`` and
``hyperrotor.quantum.__all__`` that can be called is listed in ``ENTRIES`` with one good call;
each argument marked there is replaced, one at a time, by the bad values of its kind (wrong
types, None, bools, strings, NaN, inf, negative, zero, huge, wrong shapes, ragged lists).
The contract (house rules, docs/conventions.md): a refusal is a ``ValueError`` or
``TypeError`` whose message names the argument or shows the value; never an IndexError,
ZeroDivisionError, AttributeError, KeyError, a warning turned error deep inside NumPy, or a
hang. Values marked "may pass" (a negative angular velocity, a zero time) may also be
accepted; the others must be refused.

Sizes are small and every call runs under a 20 s alarm (SIGALRM), so a hang is reported as a
failure instead of stalling the suite. Cases that failed when written are marked
``xfail(strict=True)`` with the owner's pending request in /work/coord/requests.md: once the
owner fixes the entry point, the strict xfail turns into a failure and the mark must go.
"""
from __future__ import annotations

import contextlib
import inspect
import math
import signal
import threading
import warnings

import numpy as np
import pytest

import hyperrotor
from hyperrotor._validate import fmt

NAN, INF = float("nan"), float("inf")
HUGE_INT = 10**6  # large enough to trip a size/budget check, small enough not to exhaust memory
TIME_LIMIT = 20.0


class _Hang(BaseException):
    """Raised by the alarm: BaseException, so library code's ``except Exception`` cannot swallow it."""


@contextlib.contextmanager
def _time_limit(seconds):
    if not hasattr(signal, "setitimer") or threading.current_thread() is not threading.main_thread():
        yield
        return

    def _raise(signum, frame):
        raise _Hang(f"no answer within {seconds} s")

    old = signal.signal(signal.SIGALRM, _raise)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


# --------------------------------------------------------------------------- bad values by kind
# Each entry: (id, value, must_refuse). must_refuse=False: "may pass" (a legitimate value for
# some parameters of this kind), but if refused it must still be a ValueError/TypeError naming it.
def _common(default_is_none):
    return [("None", None, not default_is_none), ("object", object(), True)]


def _bad_int(default_is_none, zero_ok=False, signed=False):
    return _common(default_is_none) + [
        ("True", True, True), ("2.5", 2.5, True), ("str3", "3", True), ("nan", NAN, True),
        ("complex", 1j, True), ("-1", -1, not signed), ("0", 0, not zero_ok), ("huge", HUGE_INT, False),
    ]


def _bad_real(default_is_none, positive=False, zero_ok=False):
    return _common(default_is_none) + [
        ("True", True, True), ("str", "1.0", True), ("nan", NAN, True), ("inf", INF, True),
        ("-inf", -INF, True), ("complex", 1j, True), ("list", [1.0, 2.0], True),
        ("-1", -1.0, positive), ("0", 0.0, positive and not zero_ok), ("huge", 1e300, False),
    ]


def _bad_array(good, default_is_none, finite=True, positive=False):
    good = np.asarray(good, dtype=float)
    wrong_len = np.ones(good.shape[:-1] + (good.shape[-1] + 1,)) if good.ndim else np.ones(2)
    return _common(default_is_none) + [
        ("str", "abc", True), ("scalar", 3.0, good.ndim > 0), ("empty", [], True),
        ("ragged", [[1.0, 2.0], [3.0]], True), ("wrong_len", wrong_len, True),
        ("ndim3", np.ones((2, 3, 4)), good.ndim != 3),
        ("nan", np.full(good.shape, NAN), finite), ("inf", np.full(good.shape, INF), finite),
        ("strings", np.full(good.shape, "a"), True), ("complex", good + 1j, True),
        ("negative", -np.abs(good) - 1.0, positive), ("zeros", np.zeros(good.shape), positive),
        ("huge", np.full(good.shape, 1e300), False),
    ]


def _bad_str(default_is_none):
    return _common(default_is_none) + [
        ("int", 3, True), ("nonsense", "nonsense", True), ("empty", "", True), ("True", True, True),
        ("bytes", b"paper", True),
    ]


def _bad_plane(default_is_none):
    return _common(default_is_none) + [
        ("short", (1,), True), ("equal", (1, 1), True), ("zero", (0, 1), True), ("out", (1, 99), True),
        ("floats", (1.5, 2.0), True), ("bools", (True, 2), True), ("triple", (1, 2, 3), True),
        ("reversed", (2, 1), False), ("str", "xy", True),
    ]


def _bad_obj(default_is_none, ok=()):
    return _common(default_is_none) + [
        ("int", 3, "int" not in ok), ("str", "x", True), ("array", np.ones(3), "array" not in ok),
        ("dict", {"a": 1}, True),
    ]


def _bad_flag(default_is_none):
    return _common(default_is_none) + [
        ("1", 1, True), ("0", 0, True), ("str", "yes", True), ("nan", NAN, True), ("array", np.array([True]), True),
    ]


def _bad_values(kind, good, default_is_none):
    """Bad values of a kind "name[:option,option]"; options: pos (must be > 0), 0 (zero allowed),
    scalar (a scalar may pass for an array), int/array (may pass for an object)."""
    name, _, opts = kind.partition(":")
    opts = tuple(opts.split(",")) if opts else ()
    opt = opts[0] if opts else ""
    if "scalar" in opts:
        return [(v, val, must and v != "scalar") for v, val, must in
                _bad_values(kind.replace(",scalar", "").replace(":scalar", ""), good, default_is_none)]
    if name == "int":  # options: 0 (zero allowed), signed (-1 allowed, e.g. a chirality)
        return _bad_int(default_is_none, zero_ok="0" in opts, signed="signed" in opts)
    if name == "real":
        return _bad_real(default_is_none)
    if name == "pos":
        return _bad_real(default_is_none, positive=True, zero_ok=opt == "0")
    if name == "arr":  # finite numeric array of a fixed shape; option cplx: complex allowed (a state)
        return [(v, val, must and not (v == "complex" and "cplx" in opts)) for v, val, must in
                _bad_array(good, default_is_none, positive="pos" in opts)]
    if name == "vec":  # finite numeric 1-D array of any length (a mass tensor, semi-axes)
        return [(v, val, must and v != "wrong_len") for v, val, must in
                _bad_array(good, default_is_none, positive=opt == "pos")]
    if name == "pts":  # points where a function is evaluated: any shape (a scalar, empty, 3-D), finite
        return [(v, val, must and v not in ("scalar", "empty", "wrong_len", "ndim3")) for v, val, must in
                _bad_array(good, default_is_none)]
    if name == "map":  # a pure index map: NaN/inf (and complex numbers) pass through legitimately
        return [(v, val, must and v != "complex") for v, val, must in _bad_array(good, default_is_none, finite=False)]
    if name == "str":
        return _bad_str(default_is_none)
    if name == "name":  # a free identifier (a symbol name): any non-empty identifier string passes
        return [(v, val, must and v != "nonsense") for v, val, must in _bad_str(default_is_none)]
    if name == "plane":
        return _bad_plane(default_is_none)
    if name == "obj":
        return _bad_obj(default_is_none, ok=opts)
    if name == "flag":  # a switch: True or False (None too when that is the default)
        return _bad_flag(default_is_none)
    raise AssertionError(kind)


# --------------------------------------------------------------------------- the entry points
def _body():
    return hyperrotor.RigidBody(hyperrotor.Inertia.from_mass_tensor([1.0, 2.0, 3.0, 4.0]))


def _body5():
    return hyperrotor.RigidBody(hyperrotor.Inertia.quartet(0.5))


def _rep():
    return hyperrotor.quantum.irrep(3, (1,))


def _H():
    return hyperrotor.quantum.rotor_hamiltonian(_rep(), [1.0, 2.0, 3.0])


def _psi():
    import qutip

    return qutip.basis(3, 0)


def _L3():
    return hyperrotor.quantum.angular_momentum_operators(3)


def _H_array():
    return np.asarray(_H().full().real)  # the same rotor Hamiltonian as a real ndarray


def _W3():
    import qutip

    return qutip.Qobj(np.diag([1.0, 0.0, -1.0]))


def _sector():
    return next(s for s in hyperrotor.quantum.symmetry_sectors(_rep()) if s.dim)


def _section():
    L = np.arange(12.0).reshape(2, 6) + 1.0
    return hyperrotor.classical.PoincareSection(t=np.array([0.5, 1.0]), L=L, omega=L / W6, plane=(1, 2),
                                                value=0.0, direction=1, N=4)


def _axes():
    from matplotlib.figure import Figure  # not registered with pyplot: nothing to close

    return Figure().add_subplot()


W6 = np.linspace(0.1, 0.6, 6)
W10 = np.linspace(0.1, 1.0, 10)
T5 = np.linspace(0.0, 1.0, 5)
#: A small spectrum with unequal spacings (10 levels; enough for an unfolding of degree 3).
LEVELS = np.array([0.0, 0.3, 1.1, 1.5, 2.6, 3.0, 4.2, 4.4, 5.9, 6.3])
PSI3 = np.ones(3) / math.sqrt(3)

# (label, getter, args factory, kwargs factory, {position or keyword: kind})
# getter is a dotted path below ``hyperrotor``; factories build fresh good arguments per call.
ENTRIES = [
    # conventions
    ("planes", "planes", lambda: (4,), dict, {0: "int"}),
    ("n_planes", "n_planes", lambda: (4,), dict, {0: "int"}),
    ("dimension_from_count", "dimension_from_count", lambda: (6,), dict, {0: "int"}),
    ("plane_index", "plane_index", lambda: ((1, 2), 4), dict, {0: "plane", 1: "int"}),
    ("plane_label", "plane_label", lambda: ((1, 2), 4), dict, {0: "plane", 1: "int"}),
    ("plane_signs", "plane_signs", lambda: (4,), lambda: {"convention": "paper"}, {0: "int", "convention": "str"}),
    ("basis_matrix", "basis_matrix", lambda: ((1, 2), 4), lambda: {"convention": "paper"},
     {0: "plane", 1: "int", "convention": "str"}),
    ("to_matrix", "to_matrix", lambda: (W6,), lambda: {"convention": "paper"}, {0: "map", "convention": "str"}),
    ("to_components", "to_components", lambda: (np.zeros((4, 4)),), lambda: {"convention": "paper"},
     {0: "map", "convention": "str"}),
    ("structure_constants", "structure_constants", lambda: (4,), dict, {0: "int"}),
    ("lie_bracket", "lie_bracket", lambda: (W6, W6), dict, {0: "map", 1: "map"}),
    ("lie_poisson_bracket", "lie_poisson_bracket",
     lambda: (*hyperrotor.plane_symbols("L", 3)[:2], hyperrotor.plane_symbols("L", 3)), dict, {2: "obj"}),
    ("bivector_product_table", "bivector_product_table", lambda: (3,), lambda: {"convention": "paper"},
     {0: "int", "convention": "str"}),
    ("plane_symbols", "plane_symbols", lambda: ("w", 3), dict, {0: "name", 1: "int"}),
    # inertia
    ("Inertia", "Inertia", lambda: (W6,), dict, {0: "arr:pos"}),
    ("Inertia.from_planes", "Inertia.from_planes", lambda: (W6,), dict, {0: "arr:pos"}),
    ("Inertia.from_mass_tensor", "Inertia.from_mass_tensor", lambda: ([1.0, 2.0, 3.0],), dict, {0: "vec"}),
    ("Inertia.equal", "Inertia.equal", lambda: (4, 1.3), dict, {0: "int", 1: "pos"}),
    ("Inertia.quartet", "Inertia.quartet", lambda: (0.5, 5, 5), dict, {0: "real", 1: "int", 2: "int"}),
    ("Inertia.from_points", "Inertia.from_points", lambda: ([1.0, 2.0], [[0.0, 1.0], [1.0, 0.0]]), dict,
     {0: "arr:pos,scalar", 1: "vec"}),
    ("Inertia.ellipsoid", "Inertia.ellipsoid", lambda: (1.0, [1.0, 2.0, 3.0]), dict, {0: "pos", 1: "vec:pos"}),
    ("Inertia.box", "Inertia.box", lambda: (1.0, [1.0, 2.0, 3.0]), dict, {0: "pos", 1: "vec:pos"}),
    ("Inertia.ball", "Inertia.ball", lambda: (3, 1.0, 2.0), dict, {0: "int", 1: "pos", 2: "pos"}),
    ("Inertia.symbolic", "Inertia.symbolic", lambda: (3, "I"), dict, {0: "int", 1: "name"}),
    ("inertia_tensor", "inertia_tensor", lambda: ([1.0, 2.0], [[0.0, 1.0], [1.0, 0.0]]), dict, {0: "arr:pos,scalar", 1: "vec"}),
    ("second_moment_matrix", "second_moment_matrix", lambda: ([1.0, 2.0], [[0.0, 1.0], [1.0, 0.0]]), dict,
     {0: "arr:pos,scalar", 1: "vec"}),
    ("check_tensor_symmetries", "check_tensor_symmetries",
     lambda: (hyperrotor.inertia_tensor([1.0, 2.0], [[0.0, 1.0], [1.0, 0.0]]),), dict, {0: "arr"}),
    # rigid body
    ("RigidBody", "RigidBody", lambda: (W6,), lambda: {"convention": "paper"}, {0: "arr:pos", "convention": "str"}),
    ("RigidBody.energy", None, lambda: (_body().energy, W6), dict, {1: "arr"}),
    ("RigidBody.angular_momentum", None, lambda: (_body().angular_momentum, W6), dict, {1: "arr"}),
    ("RigidBody.casimirs", None, lambda: (_body().casimirs, W6), dict, {1: "arr"}),
    ("RigidBody.rhs", None, lambda: (_body().rhs, W6), dict, {1: "arr"}),
    ("RigidBody.manakov_integrals", None, lambda: (_body().manakov_integrals, W6, 1.0), dict, {1: "arr", 2: "real"}),
    ("RigidBody.matrix", None, lambda: (_body().matrix, W6), dict, {1: "map"}),
    ("RigidBody.lock", None, lambda: (_body().lock, [4]), dict, {1: "obj:int"}),
    ("RigidBody.stability", None, lambda: (_body().stability, (1, 2), 1.0), dict, {1: "plane", 2: "real"}),
    # integration
    ("simulate", "simulate", lambda: (_body(), W6, T5),
     lambda: {"method": "splitting4", "dt": 0.1, "progress": False, "max_steps": 10**6},
     {0: "obj:array", 1: "arr", 2: "vec", "method": "str", "dt": "pos", "progress": "flag", "max_steps": "int"}),
    ("simulate/rtol", "simulate", lambda: (_body(), W6, T5), lambda: {"rtol": 1e-6},
     {"rtol": "pos"}),
    ("splitting_coefficients", "splitting_coefficients", lambda: (4,), dict, {0: "int"}),
    ("casimir_shift", "casimir_shift", lambda: (W6, W6), dict, {0: "arr:pos", 1: "arr"}),
    ("lyapunov", "lyapunov", lambda: (_body(), W6, 1.0), lambda: {"progress": False},
     {0: "obj", 1: "arr", 2: "pos", "progress": "flag"}),
    ("lyapunov_sweep", "lyapunov_sweep", lambda: ([_body()], W6[None], 1.0), lambda: {"progress": False},
     {0: "obj", 1: "arr", 2: "pos", "progress": "flag"}),
    # closed forms
    ("equal_moments_solution", "equal_moments_solution", lambda: (W6, T5), dict, {0: "arr", 1: "vec:scalar"}),
    ("quartet_moments", "quartet_moments", lambda: (0.5, 5, 5), dict, {0: "real", 1: "int", 2: "int"}),
    ("quartet_theta", "quartet_theta", lambda: (0.5,), dict, {0: "real"}),
    ("quartet_matrix", "quartet_matrix", lambda: (W10, 5), dict, {0: "arr", 1: "int"}),
    ("quartet_solution", "quartet_solution", lambda: (0.5, W10, T5, 5), dict,
     {0: "real", 1: "arr", 2: "vec:scalar", 3: "int"}),
    ("quartet_frequencies", "quartet_frequencies", lambda: (0.5, W10, 5), dict, {0: "real", 1: "arr", 2: "int"}),
    ("quartet_polynomial_coefficients", "quartet_polynomial_coefficients", lambda: (0.5, W10, 5), dict,
     {0: "real", 1: "arr", 2: "int"}),
    ("quartet_attitude", "quartet_attitude", lambda: (0.5, W10, T5, 5), dict,
     {0: "real", 1: "arr", 2: "vec:scalar", 3: "int"}),
    ("euler_poinsot", "euler_poinsot", lambda: ([1.0, 2.0, 3.0], [0.3, 1.0, 0.2], T5), dict,
     {0: "arr:pos", 1: "arr", 2: "vec:scalar"}),
    ("euler_poinsot_period", "euler_poinsot_period", lambda: ([1.0, 2.0, 3.0], [0.3, 1.0, 0.2]), dict,
     {0: "arr:pos", 1: "arr"}),
    ("detect_closed_form", "detect_closed_form", lambda: (_body5(),), dict, {0: "obj:array"}),
    ("closed_form_solution", "closed_form_solution", lambda: (_body5(), W10, T5), dict,
     {0: "obj:array", 1: "arr", 2: "vec:scalar"}),
    # stability
    ("linear_stability", "linear_stability", lambda: (_body(), (1, 2), 1.0), dict, {0: "obj:array", 1: "plane", 2: "real"}),
    ("linearization", "linearization", lambda: (_body(), (1, 2), 1.0), dict, {0: "obj:array", 1: "plane", 2: "real"}),
    ("stability_condition", "stability_condition", lambda: ((1, 2), 4), dict, {0: "plane", 1: "int"}),
    ("perturbation_growth", "perturbation_growth", lambda: (_body(), (1, 2), 1.0, T5), dict,
     {0: "obj:array", 1: "plane", 2: "real", 3: "vec"}),
    # scenes
    ("Scene", "Scene", lambda: (_body(), W6, T5), lambda: {"progress": False},
     {0: "obj:array", 1: "arr", 2: "vec", "progress": "flag"}),
    ("hypercube_vertices", "hypercube_vertices", lambda: (3, 1.0), dict, {0: "int", 1: "pos"}),
    ("simplex_vertices", "simplex_vertices", lambda: (3, 1.0), dict, {0: "int", 1: "pos"}),
    ("ellipsoid_points", "ellipsoid_points", lambda: ([1.0, 2.0, 3.0], 5), dict, {0: "vec:pos", 1: "int"}),
    ("locked_axes", "locked_axes", lambda: (W6,), dict, {0: "map"}),
    # chaos: Poincare sections
    ("poincare_section", "poincare_section", lambda: (_body(), W6, 1.0),
     lambda: {"plane": (1, 2), "value": 0.0, "direction": 1, "method": "splitting4", "dt": 0.05, "progress": False},
     {0: "obj:array", 1: "arr", 2: "pos", "plane": "plane", "value": "real", "direction": "int:signed,0",
      "method": "str", "dt": "pos", "progress": "flag"}),
    ("poincare_section/auto-dt", "poincare_section", lambda: (_body(), W6, 1.0), dict, {1: "arr", 2: "pos"}),
    ("plot_poincare", "plotting.plot_poincare", lambda: (_section(), (1, 3), (2, 4)), lambda: {"ax": _axes(), "labels": ["orbit"]},
     {0: "obj", 1: "plane", 2: "plane", "ax": "obj", "labels": "obj"}),
    ("PoincareSection.coordinates", None, lambda: (_section().coordinates, (1, 3), (2, 4)), dict,
     {1: "plane", 2: "plane"}),
    ("evaluate_scene", "evaluate_scene", lambda: (hyperrotor.Scene(_body(), W6, T5),), dict, {0: "obj"}),
    ("verify_paper", "verify_paper", lambda: (["nonsense-section"],), dict, {}),
    # quantum: operators
    ("q.coordinate_symbols", "quantum.coordinate_symbols", lambda: (3,), dict, {0: "int"}),
    ("q.angular_momentum_operators", "quantum.angular_momentum_operators", lambda: (3,), dict, {0: "int"}),
    ("q.angular_momentum_operator", "quantum.angular_momentum_operator", lambda: ((1, 2), 3), dict,
     {0: "plane", 1: "int"}),
    ("q.commutator", "quantum.commutator", lambda: (_L3()[(1, 2)], _L3()[(2, 3)]), dict, {0: "obj", 1: "obj"}),
    ("q.euler_operator", "quantum.euler_operator", lambda: (3,), dict, {0: "int"}),
    ("q.laplacian_operator", "quantum.laplacian_operator", lambda: (3,), dict, {0: "int"}),
    ("q.multiplication_operator", "quantum.multiplication_operator", lambda: (1, 3), dict, {1: "int"}),
    ("q.casimir_operator", "quantum.casimir_operator", lambda: (3,), dict, {0: "int"}),
    ("q.operator_matrix", "quantum.operator_matrix", lambda: (3,), lambda: {"convention": "paper"},
     {0: "int", "convention": "str"}),
    ("q.contraction_identity", "quantum.contraction_identity", lambda: (3,), lambda: {"convention": "paper"},
     {0: "int", "convention": "str"}),
    ("q.harmonic_dimension", "quantum.harmonic_dimension", lambda: (3, 2), dict, {0: "int", 1: "int:0"}),
    ("q.harmonic_polynomial_basis", "quantum.harmonic_polynomial_basis", lambda: (3, 2), dict,
     {0: "int", 1: "int:0"}),
    ("q.sphere_monomial_integral", "quantum.sphere_monomial_integral", lambda: ((2, 0, 2),), dict, {0: "obj"}),
    ("q.orthonormal_harmonic_basis", "quantum.orthonormal_harmonic_basis", lambda: (3, 1), dict,
     {0: "int", 1: "int:0"}),
    ("q.orthogonal_harmonic_basis", "quantum.orthogonal_harmonic_basis", lambda: (3, 1), dict,
     {0: "int", 1: "int:0"}),
    ("q.rank", "quantum.rank", lambda: (5,), dict, {0: "int"}),
    ("q.check_highest_weight", "quantum.check_highest_weight", lambda: (5, (1, 0)), dict, {0: "int", 1: "obj"}),
    ("q.is_dominant", "quantum.is_dominant", lambda: (5, (1, 0)), dict, {0: "int", 1: "obj"}),
    ("q.dominates", "quantum.dominates", lambda: (5, (1, 0), (0, 0)), dict, {0: "int", 1: "obj", 2: "obj"}),
    ("q.dynkin_to_orthogonal", "quantum.dynkin_to_orthogonal", lambda: (5, (1, 0)), dict, {0: "int", 1: "obj"}),
    ("q.orthogonal_to_dynkin", "quantum.orthogonal_to_dynkin", lambda: (5, (1, 0)), dict, {0: "int", 1: "obj"}),
    ("q.weyl_dimension", "quantum.weyl_dimension", lambda: (5, (1, 0)), dict, {0: "int", 1: "obj"}),
    ("q.casimir_eigenvalue", "quantum.casimir_eigenvalue", lambda: (5, (1, 0)), dict, {0: "int", 1: "obj"}),
    ("q.positive_roots", "quantum.positive_roots", lambda: (5,), dict, {0: "int"}),
    ("q.simple_roots", "quantum.simple_roots", lambda: (5,), dict, {0: "int"}),
    ("q.weight_multiplicities", "quantum.weight_multiplicities", lambda: (5, (1, 0)), dict, {0: "int", 1: "obj"}),
    # quantum: representations
    ("q.vector_rep", "quantum.vector_rep", lambda: (3,), dict, {0: "int"}),
    ("q.adjoint_rep", "quantum.adjoint_rep", lambda: (3,), dict, {0: "int"}),
    ("q.spinor_rep", "quantum.spinor_rep", lambda: (4, 1), dict, {0: "int", 1: "int:signed"}),
    ("q.harmonic_rep", "quantum.harmonic_rep", lambda: (3, 1), dict, {0: "int", 1: "int:0"}),
    ("q.tensor", "quantum.tensor", lambda: (_rep(), _rep()), dict, {0: "obj", 1: "obj"}),
    ("q.direct_sum", "quantum.direct_sum", lambda: (_rep(), _rep()), dict, {0: "obj", 1: "obj"}),
    ("q.intertwiner", "quantum.intertwiner", lambda: (_rep(), _rep()), dict, {0: "obj", 1: "obj"}),
    ("q.real_form", "quantum.real_form", lambda: (_rep(),), dict, {0: "obj"}),
    ("q.irrep", "quantum.irrep", lambda: (3, (1,)), dict, {0: "int", 1: "obj"}),
    ("q.gt_patterns", "quantum.gt_patterns", lambda: (3, (1,)), dict, {0: "int", 1: "obj"}),
    ("q.gt_size", "quantum.gt_size", lambda: (3, (1,)), dict, {0: "int", 1: "obj"}),
    ("q.gt_index", "quantum.gt_index", lambda: (3, (1,), hyperrotor.quantum.gt_patterns(3, (1,))[0]), dict,
     {0: "int", 1: "obj", 2: "obj"}),
    ("q.Representation", "quantum.Representation", lambda: (2, {(1, 2): np.zeros((1, 1))}), dict,
     {0: "int", 1: "obj"}),
    # quantum: rotor
    ("q.rotor_hamiltonian", "quantum.rotor_hamiltonian", lambda: (_rep(), [1.0, 2.0, 3.0]), dict,
     {0: "obj", 1: "arr:pos"}),
    ("q.evolve", "quantum.evolve", lambda: (_H(), _psi(), T5), dict, {0: "obj", 1: "obj:array", 2: "vec"}),
    ("q.spectrum", "quantum.spectrum", lambda: (_H(),), dict, {0: "obj"}),
    ("q.spectrum/rep", "quantum.spectrum", lambda: (_H(),), lambda: {"rep": _rep()}, {"rep": "obj"}),
    ("q.evolve/rep", "quantum.evolve", lambda: (_H(), _psi(), T5), lambda: {"rep": _rep()}, {"rep": "obj"}),
    ("q.symmetry_blocks", "quantum.symmetry_blocks", lambda: (_H(),), dict, {0: "obj"}),
    ("q.generator_expectations", "quantum.generator_expectations", lambda: (_rep(), _psi()), dict,
     {0: "obj", 1: "obj:array"}),
    ("q.highest_weight_state", "quantum.highest_weight_state", lambda: (_rep(),), dict, {0: "obj"}),
    ("q.normal_form_rotation", "quantum.normal_form_rotation", lambda: (np.array([1.0, 0.5, 0.2]),), dict,
     {0: "arr"}),
    ("q.apply_rotation", "quantum.apply_rotation", lambda: (_rep(), np.eye(3), np.ones(3) / math.sqrt(3)), dict,
     {0: "obj", 1: "arr", 2: "arr:cplx"}),
    ("q.coherent_state", "quantum.coherent_state", lambda: (_rep(), np.array([1.0, 0.5, 0.2])), dict,
     {0: "obj", 1: "arr"}),
    ("q.as_csr", "quantum.as_csr", lambda: (np.eye(2), "H"), dict, {0: "arr:cplx", 1: "name"}),
    ("q.check_antihermitian", "quantum.check_antihermitian", lambda: ({(1, 2): np.array([[0.0, -1.0], [1.0, 0.0]])},),
     lambda: {"form": "antihermitian"}, {0: "obj", "form": "str"}),
    ("q.jmat_generators", "quantum.jmat_generators", lambda: (1,), lambda: {"form": "hermitian", "hbar": 1.0},
     {0: "pos", "form": "str", "hbar": "pos"}),
    ("q.evolve_options", "quantum.evolve_options", lambda: ("krylov",), dict, {0: "str"}),
    ("q.register_propagator", "quantum.register_propagator",
     lambda: (hyperrotor.quantum.PROPAGATORS["eigen"],), dict, {0: "obj"}),
    # quantum: symmetry sectors
    ("q.pi_rotation", "quantum.pi_rotation", lambda: (_rep(), (1, 2)), lambda: {"format": "csr"},
     {0: "obj", 1: "plane", "format": "str"}),
    ("q.symmetry_sectors", "quantum.symmetry_sectors", lambda: (_rep(),), lambda: {"complete": False},
     {0: "obj", "complete": "flag"}),
    ("q.sector_blocks", "quantum.sector_blocks", lambda: (_H(), _rep()), lambda: {"complete": False},
     {0: "obj", 1: "obj", "complete": "flag"}),
    ("q.sector_blocks/array", "quantum.sector_blocks", lambda: (_H_array(), _rep()), dict, {0: "arr"}),
    ("q.sector_hamiltonian", "quantum.sector_hamiltonian", lambda: (_H(), _sector()), lambda: {"format": "dense"},
     {0: "obj", 1: "obj", "format": "str"}),
    ("q.sector_hamiltonian/array", "quantum.sector_hamiltonian", lambda: (_H_array(), _sector()), dict, {0: "arr"}),
    ("q.evolution_blocks", "quantum.evolution_blocks", lambda: (_H(), _rep(), PSI3), dict,
     {0: "obj", 1: "obj", 2: "arr:cplx"}),
    ("q.evolution_blocks/array", "quantum.evolution_blocks", lambda: (_H_array(), _rep(), PSI3), dict, {0: "arr"}),
    ("q.sector_spectra", "quantum.sector_spectra", lambda: (_rep(), [1.0, 2.0, 3.0]),
     lambda: {"hbar": 1.0, "workers": 1, "client": None, "progress": False},
     {0: "obj", 1: "arr:pos", "hbar": "pos", "workers": "int", "client": "obj", "progress": "flag"}),
    ("q.SectorPropagator", "quantum.SectorPropagator", lambda: (_H(),), lambda: {"rep": _rep(), "method": "auto"},
     {0: "obj", "rep": "obj", "method": "str"}),
    ("q.otoc", "quantum.otoc", lambda: (_H(), _W3(), _W3(), T5), lambda: {"samples": 2, "rng": 0},
     {0: "obj", 1: "obj", 2: "obj", 3: "vec", "samples": "int"}),
    ("q.ehrenfest_time", "quantum.ehrenfest_time", lambda: ([1.0, 2.0, 3.0], [0.3, 0.2, 1.0], [1, 2], T5), dict,
     {0: "arr:pos", 1: "arr", 3: "vec"}),
    # quantum: level statistics
    ("q.spacing_ratios", "quantum.spacing_ratios", lambda: (LEVELS,), dict, {0: "vec"}),
    ("q.spacing_ratio", "quantum.spacing_ratio", lambda: (LEVELS,), lambda: {"return_error": False},
     {0: "vec", "return_error": "flag"}),
    ("q.ratio_density", "quantum.ratio_density", lambda: (np.linspace(0.0, 1.0, 5), "goe"), dict,
     {0: "pts", 1: "str"}),
    ("q.unfold", "quantum.unfold", lambda: (LEVELS,), lambda: {"degree": 3}, {0: "vec", "degree": "int"}),
    ("q.spacings", "quantum.spacings", lambda: (LEVELS,), lambda: {"degree": 3, "unfolded": False},
     {0: "vec", "degree": "int", "unfolded": "flag"}),
    ("q.spacings/unfolded", "quantum.spacings", lambda: (LEVELS,), lambda: {"unfolded": True}, {0: "vec"}),
    ("q.spacing_density", "quantum.spacing_density", lambda: (np.linspace(0.0, 3.0, 5), "poisson"), dict,
     {0: "pts", 1: "str"}),
    ("q.spacing_distribution", "quantum.spacing_distribution", lambda: (LEVELS,),
     lambda: {"bins": 5, "s_max": 4.0, "degree": 3}, {0: "vec", "bins": "int", "s_max": "pos", "degree": "int"}),
    ("q.spacing_distribution/edges", "quantum.spacing_distribution", lambda: (LEVELS,),
     lambda: {"bins": np.linspace(0.0, 4.0, 6), "degree": 3}, {"bins": "vec"}),
    ("q.SpacingDistribution.distance", None,
     lambda: (hyperrotor.quantum.spacing_distribution(LEVELS, degree=3).distance, "goe"), dict, {1: "str"}),
    ("q.SpacingDistribution.reference", None,
     lambda: (hyperrotor.quantum.spacing_distribution(LEVELS, degree=3).reference, "goe"), dict, {1: "str"}),
    ("q.sample_spectrum", "quantum.sample_spectrum", lambda: ("goe", 6), lambda: {"rng": 1, "bulk": 1.0},
     {0: "str", 1: "int", "rng": "int:0", "bulk": "pos"}),
    ("q.sample_spectrum/poisson", "quantum.sample_spectrum", lambda: ("poisson", 6), lambda: {"rng": 1},
     {1: "int"}),
]

#: Public names that are not entry points to fuzz, with the reason.
NOT_FUZZED = {
    "CONVENTIONS": "a constant", "SIMULATION_METHODS": "a constant", "SCENE_OBSERVABLES": "a constant",
    "LYAPUNOV_METHODS": "a constant", "DEFAULT_MAX_DIM": "a constant", "EXACT_MAX_DIM": "a constant",
    "EVOLVE_METHODS": "a constant", "PAPER_COORDINATES": "a constant",
    "quantum": "a module", "classical": "a module", "conventions": "a module", "paper": "a module",
    "options": "the option table (its own tests)",
    "Trajectory": "a result record built by simulate", "SceneResult": "a result record",
    "StabilityResult": "a result record", "CoupledPair": "a result record",
    "ContractionIdentity": "a result record",
    "DifferentialOperator": "built from a WeylElement by the operator constructors (fuzzed)",
    "WeylElement": "the normal-form algebra behind the operators (fuzzed through them)",
    "polynomial_to_dict": "SymPy conversion helper", "dict_to_polynomial": "SymPy conversion helper",
    "operator_product": "takes operator matrices from operator_matrix (fuzzed)",
    "apply_to_polynomial": "takes SymPy operators and polynomials",
    "sphere_inner_product": "takes SymPy polynomials",
    "textbook_so3": "hbar and coordinates only (as angular_momentum_operators)",
    "StepBudgetError": "an exception class", "UnreachableAccuracyError": "an exception class",
    "AccuracyWarning": "an exception class (a warning category)",
    "PhaseRoundingWarning": "an exception class (a warning category)",
    "BudgetError": "an exception class",
    "UnknownOptionError": "an exception class", "ParseError": "an exception class",
    "LyapunovResult": "a result record", "Spectrum": "a result record (NamedTuple)",
    "EhrenfestResult": "a result record", "OTOCResult": "a result record",
    "body_edges": "points and a kind; its size is priced in tests/safety/test_too_big.py",
    "scene_html_bytes": "a formula on three counts",
    "projection_figure": "plotly figure of arrays the caller built (being renamed by classical; fuzz when stable)",
    "write_html": "writes a figure the caller built (the file path is the CLI's business)", "PoincareSection": "a result record", "Solver": "a base class",
    "SOLVERS": "a registry", "PROPAGATORS": "a registry", "Propagator": "a base class",
    "RESULT_OPTIONS": "a constant", "JMAT_PLANES": "a constant", "ENSEMBLES": "a constant",
    "R_MEAN": "a constant", "R_SURMISE_MEAN": "a constant", "Sector": "a result record",
    "SectorSpectra": "a result record", "SpacingDistribution": "a result record",
}
#: Cases that failed when written, by owner (requests in /work/coord/requests.md): strict xfail.
PENDING_IDS: dict[str, list[str]] = {}
#: Cases that hang (> 3 s; no work budget): xfail, not run.
HANGING_IDS: dict[str, list[str]] = {}

_PENDING = {cid: owner for owner, ids in PENDING_IDS.items() for cid in ids}
_HANGING = {cid: owner for owner, ids in HANGING_IDS.items() for cid in ids}
_OWNER_TEXT = {"Q": "Q (conventions/quantum)", "C": "C (simulate/scenes)", "K": "K (chaos)", "T": "T (follow-up)",
               "P": "P (solver driver)", "lead": "lead (stability)", "qreps": "qreps (representations)",
               "sectors": "sectors", "dynamics": "dynamics (evolve, correspondence)"}


def _resolve(path):
    obj = hyperrotor
    for part in path.split("."):
        obj = getattr(obj, part)
    return obj


def _default_is_none(fn, where):
    try:
        params = list(inspect.signature(fn).parameters.values())
    except (TypeError, ValueError):
        return False
    if isinstance(where, str):
        p = next((q for q in params if q.name == where), None)
    else:
        pos = [q for q in params if q.kind in (q.POSITIONAL_ONLY, q.POSITIONAL_OR_KEYWORD)]
        p = pos[where] if where < len(pos) else None
    return p is not None and p.default is None


def _param_name(fn, where):
    if isinstance(where, str):
        return where
    try:
        pos = [q for q in inspect.signature(fn).parameters.values()
               if q.kind in (q.POSITIONAL_ONLY, q.POSITIONAL_OR_KEYWORD, q.VAR_POSITIONAL)]
        return pos[min(where, len(pos) - 1)].name
    except (TypeError, ValueError, IndexError):
        return ""


def _names_it(message, name, value):
    """Does the message name the argument, or show the value (for a sequence: its shape, length,
    or an offending element)?"""
    m = message.lower()
    words = {name.lower(), fmt(value).lower(), type(value).__name__.lower()}
    if isinstance(value, (float, int, complex)) and not isinstance(value, bool):
        words |= {repr(value).lower(), str(value).lower()}
    if isinstance(value, (np.ndarray, list, tuple)):
        words |= {"shape", "length", "finite", "nan", "inf", "dtype", f"{len(value)} " if len(np.shape(value) if isinstance(value, np.ndarray) else (1,)) else "()"}
        first = value
        while isinstance(first, (np.ndarray, list, tuple)) and len(first):
            first = first[0]
        words.add(fmt(first).lower())
        if isinstance(value, np.ndarray):
            words.add(str(value.shape))
    return any(w and w in m for w in words)


def _call(path, args, kwargs):
    a, kw = list(args()), dict(kwargs())
    if path is None:  # bound method: first element of args
        fn, a = a[0], a[1:]
        return fn, a, kw, 1
    return _resolve(path), a, kw, 0


#: Parameters with a ``True`` / ``False`` default that take more than a switch (not fuzzed as "flag"), and why.
NOT_SWITCHES = {
    "attitude": "simulate(attitude=...): True, False or an initial attitude matrix",
    "spectrum": "lyapunov(spectrum=...): True, False or the number of leading exponents",
}


def _switches(path, args):
    """The keyword parameters of an entry whose default is ``True`` or ``False``, and its ``progress`` (True, False or
    None): switches, fuzzed as "flag" without being listed (a new switch is checked the day it is added; ``"no"`` or
    ``0`` must not act by their truth: ``ehrenfest_time(progress="no")`` drew a bar)."""
    try:
        fn = _call(path, args, dict)[0]
        params = inspect.signature(fn).parameters.values()
    except (TypeError, ValueError):
        return {}
    return {p.name: "flag" for p in params
            if (isinstance(p.default, bool) or (p.name == "progress" and p.default is None))
            and p.name not in NOT_SWITCHES and p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)}


def _cases():
    for label, path, args, kwargs, kinds in ENTRIES:
        kinds = {**_switches(path, args), **kinds} if kinds else kinds
        for where, kind in kinds.items():
            good = args()[where] if isinstance(where, int) else kwargs().get(where)
            for vid, value, must in _bad_values(kind, good if kind.startswith(("arr", "map", "vec", "pts")) else None, False):
                cid = f"{label}-{where}-{vid}"
                marks = ()
                if cid in _PENDING:
                    marks = (pytest.mark.xfail(strict=True, reason=f"pending: {_OWNER_TEXT[_PENDING[cid]]} request"),)
                elif cid in _HANGING:
                    marks = (pytest.mark.xfail(run=False, reason=f"hangs (no size budget): {_OWNER_TEXT[_HANGING[cid]]}"),)
                yield pytest.param(label, path, args, kwargs, where, kind, vid, must, id=cid, marks=marks)


CASES = list(_cases())


@pytest.fixture(scope="module", autouse=True)
def _compiled_before_the_clock():
    """The time limit catches hangs, not numba's first compilation: in a fresh environment the first
    ``simulate(..., rtol=...)`` compiles some twenty kernels (25 s measured cold, over TIME_LIMIT), so
    every entry runs once with its good arguments, untimed, before the first timed call (~2 s warm;
    a failure here is reported by test_the_good_arguments_of_every_entry_are_accepted)."""
    for _, path, args, kwargs, *_ in ENTRIES:
        fn, a, kw, _ = _call(path, args, kwargs)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                fn(*a, **kw)
            except Exception:  # noqa: BLE001 - reported by the test of the good arguments
                pass


@pytest.mark.parametrize("label, path, args, kwargs, where, kind, vid, must", CASES)
def test_bad_value_is_refused_cleanly(label, path, args, kwargs, where, kind, vid, must):
    fn, a, kw, shift = _call(path, args, kwargs)
    good = a[where - shift] if isinstance(where, int) else kw.get(where)
    # (rng=None is fresh entropy everywhere, SPEC 7, whatever the default seed)
    allows_none = _default_is_none(fn, where if isinstance(where, str) else where - shift) or where == "rng"
    values = {v: (val, m) for v, val, m in _bad_values(
        kind, good if kind.startswith(("arr", "map", "vec", "pts")) else None, allows_none)}
    value, must = values[vid]
    if isinstance(where, int):
        a[where - shift] = value
    else:
        kw[where] = value
    name = _param_name(fn, where if isinstance(where, str) else where - shift)
    try:  # a tight time budget: a legitimate but long request ("huge" sizes) is refused by its price, naming it
        with _time_limit(TIME_LIMIT), warnings.catch_warnings(), hyperrotor.options(max_seconds=5.0):
            warnings.simplefilter("error")
            if not must:  # a legitimate value: NumPy's overflow warning or a library's advice may come
                warnings.simplefilter("ignore", RuntimeWarning)
                warnings.simplefilter("ignore", UserWarning)
            fn(*a, **kw)
    except (ValueError, TypeError) as exc:
        assert _names_it(str(exc), name, value), (
            f"{label}({name}={fmt(value)}): {type(exc).__name__} does not name the argument or value: {exc}")
    except _Hang as exc:
        pytest.fail(f"{label}({name}={fmt(value)}) hangs: {exc}")
    except Exception as exc:  # noqa: BLE001 - the point: anything else is a bug
        pytest.fail(f"{label}({name}={fmt(value)}) raised {type(exc).__name__}: {exc}")
    else:
        assert not must, f"{label}({name}={fmt(value)}) accepted a bad value"


@pytest.mark.parametrize("call, name", [
    (lambda v: hyperrotor.scene_html_bytes(2, 3, 1, colour=v), "colour"),
    (lambda v: hyperrotor.scene_html_bytes(2, 3, 1, plotlyjs=v), "plotlyjs"),
    (lambda v: hyperrotor.quantum.sphere_inner_product(*hyperrotor.quantum.harmonic_polynomial_basis(3, 1)[:2], 3,
                                                       normalized=v), "normalized"),
    (lambda v: hyperrotor.quantum.irrep(3, (1,)).weights(return_vectors=v), "return_vectors"),
])
@pytest.mark.parametrize("value", [1, 0, "no", None, np.array([True])])
def test_switches_of_the_entries_not_fuzzed_refuse_what_is_not_a_bool(call, name, value):
    """The switches of public callables the table above excuses (NOT_FUZZED) or reaches only through a method:
    ``"no"`` would act as True, ``0`` as False, by their truth value."""
    with pytest.raises(TypeError, match=f"{name} must be True or False"):
        call(value)
    call(True), call(False)  # (both values of the switch are accepted)


def test_every_public_callable_is_fuzzed_or_excused():
    import hyperrotor.classical
    import hyperrotor.quantum

    fuzzed = {path.rsplit(".", 1)[-1].split(".")[0] for _, path, *_ in ENTRIES if path}
    fuzzed |= {label.split(".")[0] for label, path, *_ in ENTRIES}
    fuzzed |= {label.split(".", 1)[1].split(".")[0].split("/")[0] for label, *_ in ENTRIES if label.startswith("q.")}
    missing = []
    for mod in (hyperrotor, hyperrotor.classical, hyperrotor.quantum):
        for name in mod.__all__:
            if name not in fuzzed and name not in NOT_FUZZED:
                missing.append(f"{mod.__name__}.{name}")
    assert not missing, f"public names without a fuzz entry (add one to ENTRIES or a reason to NOT_FUZZED): {missing}"


@pytest.mark.parametrize("label, path, args, kwargs", [pytest.param(*e[:4], id=e[0]) for e in ENTRIES if e[4]])
def test_the_good_arguments_of_every_entry_are_accepted(label, path, args, kwargs):
    """Each entry's good arguments must work: otherwise every bad value would be 'refused' for the
    wrong reason and the entry would test nothing."""
    fn, a, kw, _ = _call(path, args, kwargs)
    with _time_limit(TIME_LIMIT), warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # a library's advice on cheap arguments is fine here
        warnings.simplefilter("ignore", UserWarning)
        fn(*a, **kw)
