"""``import hyperrotor`` is light (issue #14): QuTiP, SymPy and matplotlib load on first use only.

Each check runs in a fresh interpreter (``sys.modules`` of the test process is
already full).
"""
from __future__ import annotations

import subprocess
import sys
import textwrap

HEAVY = ("qutip", "sympy", "matplotlib")


def _run(code: str) -> str:
    out = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    return out.stdout.strip()


def test_import_and_numeric_simulate_load_no_heavy_library():
    loaded = _run(f"""
        import sys
        import numpy as np
        import hyperrotor as hr
        before = [m for m in {HEAVY!r} if m in sys.modules]
        traj = hr.simulate([2.0, 3.0, 4.0], [0.1, 1.0, 0.2], np.linspace(0.0, 1.0, 5))
        assert np.all(np.isfinite(traj.L))
        hr.to_matrix([1.0, 2.0, 3.0]); hr.lie_bracket([1.0, 0, 0], [0, 1.0, 0])
        after = [m for m in {HEAVY!r} if m in sys.modules]
        print(before, after)
    """)
    assert loaded == "[] []"


def test_heavy_parts_still_work_on_first_use():
    out = _run("""
        import sys
        import hyperrotor as hr
        I = hr.Inertia.symbolic(5)
        assert "sympy" in sys.modules and len(I.symbolic_moments) == 10
        eqs = hr.RigidBody(hr.Inertia.symbolic(3)).euler_equations()
        assert len(eqs) == 3 and str(hr.TIME) == "t"
        from hyperrotor.classical.rigid_body import TIME
        assert TIME == hr.TIME
        assert "qutip" not in sys.modules
        rep = hr.quantum.irrep(3, (1,))
        H = hr.quantum.rotor_hamiltonian(rep, [1.0, 2.0, 3.0])
        assert "qutip" in sys.modules and H.shape == (3, 3)
        assert callable(hr.verify_paper) and "quantum" in dir(hr)
        print("ok")
    """)
    assert out == "ok"


def test_plotting_loads_matplotlib_on_first_use():
    out = _run("""
        import sys
        import hyperrotor as hr
        assert "matplotlib" not in sys.modules
        import matplotlib
        matplotlib.use("Agg")
        plotting = hr.plotting
        assert "matplotlib" in sys.modules and plotting.__name__ == "hyperrotor.plotting"
        print("ok")
    """)
    assert out == "ok"


def test_the_command_line_parser_loads_no_heavy_library():
    """Every ``hyperrotor`` command builds the parser of all subcommands first: listing ``verify``'s
    section keys must not load SymPy (0.55 s on every start of ``hyperrotor scene``, before)."""
    out = _run(f"""
        import sys
        from hyperrotor.cli import build_parser
        parser = build_parser()
        args = parser.parse_args(["verify", "--section", "closed-form", "--section", "quantum"])
        from hyperrotor._parse import number
        value = number(" -2.5e-3", "--t-end")  # a plain decimal: read without SymPy
        print([m for m in {HEAVY!r} if m in sys.modules], args.section, value)
    """)
    assert out == "[] ['closed-form', 'quantum'] -0.0025"
