"""The README quick tour runs as printed and computes what its comments claim."""
import re
from pathlib import Path

import numpy as np
import sympy as sp
from tolerance import scaled_tol

README = Path(__file__).resolve().parents[1] / "README.md"


def _tour_namespace():
    code = re.search(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), re.S).group(1)
    ns: dict = {}
    exec(compile(code, "README.md", "exec"), ns)  # noqa: S102 - our own README
    return ns


def test_readme_tour(capsys):
    ns = _tour_namespace()
    capsys.readouterr()
    # eq. (28) as printed in the paper, typed here from the preprint
    t = sp.Symbol("t")
    w = {k: sp.Function(f"omega_{k}")(t) for k in ("12", "13", "23", "14", "24", "15", "25")}
    I = {f"{i}{j}": m for (i, j), m in zip(ns["hr"].planes(5), ns["gen"].inertia.symbolic_moments)}
    assert all(str(I[k]) == f"I_{k}" for k in I)
    eq28 = (-I["12"] * sp.diff(w["12"], t) + (I["13"] - I["23"]) * w["13"] * w["23"]
            + (I["14"] - I["24"]) * w["14"] * w["24"] + (I["15"] - I["25"]) * w["15"] * w["25"])
    first = ns["gen"].euler_equations()[0]
    assert sp.simplify(first.lhs - eq28) == 0 and first.rhs == sp.Symbol("mtilde_12")
    assert ns["err"] < 1e-10                                   # splitting8 vs the closed form
    drift = ns["body"].casimirs(ns["traj"].omega) - ns["body"].casimirs(ns["omega0"])
    # splitting8 at rtol 1e-12 stores L compensated: the Casimirs drift by a few eps |c|, no random walk
    assert np.max(np.abs(drift)) < scaled_tol(ns["body"].casimirs(ns["omega0"]), dim=5, k=16)
    assert ns["st"].stable is False                            # m_3 = 2 lies between m_1 = 1 and m_2 = 3
    assert ns["rep"].dim == 35
    levels, deg = ns["levels"], ns["degeneracies"]
    assert int(np.sum(deg)) == 35 and np.all(np.diff(levels) > 0)
