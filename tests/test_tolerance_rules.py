"""Every closeness assertion of the suite states its relative tolerance.

``np.testing.assert_allclose(a, b, atol=1e-13)`` keeps numpy's default ``rtol=1e-7`` (``np.allclose`` and
``np.isclose``: 1e-5; ``math.isclose``: 1e-9; ``pytest.approx``: 1e-6), so a bound written as 1e-13 passed
answers wrong by 5e-8 (a review showed it on three tests with mutated results). The rule is structural: a call
without an explicit relative tolerance (``rtol=0`` with a scaled ``atol``, see :mod:`tolerance`, or a stated
``rtol``) fails here, naming file and line.
"""
from __future__ import annotations

import ast
from pathlib import Path

TESTS = Path(__file__).resolve().parent
#: the callable's name -> the keywords of which one must be given
NEEDS = {"assert_allclose": ("rtol",), "allclose": ("rtol",), "isclose": ("rtol",), "approx": ("rel", "abs")}


def _unstated(tree: ast.AST) -> list[int]:
    lines = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        f = node.func
        name = f.attr if isinstance(f, ast.Attribute) else f.id if isinstance(f, ast.Name) else None
        needs = NEEDS.get(name)
        if name == "isclose" and isinstance(f, ast.Attribute) and getattr(f.value, "id", None) == "math":
            needs = ("rel_tol",)
        given = {k.arg for k in node.keywords}
        if needs is not None and None not in given and not given & set(needs):  # (None: a **kwargs, not judged)
            lines.append(node.lineno)
    return lines


def test_every_closeness_assertion_states_its_relative_tolerance():
    bad = [f"{path.relative_to(TESTS)}:{line}" for path in sorted(TESTS.rglob("*.py"))
           for line in _unstated(ast.parse(path.read_text(), filename=str(path)))]
    assert not bad, ("closeness assertions without an explicit relative tolerance (numpy's, math's or pytest's "
                     "default applies silently): " + ", ".join(bad))


def test_the_rule_sees_the_defaults():
    code = ("np.testing.assert_allclose(a, b, atol=1e-13)\nnp.allclose(a, b)\nmath.isclose(a, b)\n"
            "x == pytest.approx(1.0)\nnp.testing.assert_allclose(a, b, rtol=0, atol=1e-13)\n"
            "x == pytest.approx(1.0, rel=1e-12)\nmath.isclose(a, b, rel_tol=1e-12)\nnp.isclose(a, b, rtol=0)\n")
    assert _unstated(ast.parse(code)) == [1, 2, 3, 4]
