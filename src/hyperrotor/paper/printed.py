r"""The paper's PRINTED Euler equations (28)-(37), reductions (42)-(81) and Tables 1-2.

This module is a faithful transcription of the print, **typos included**: it is
the thing to be checked, never a source of truth. The correct equations come
from :meth:`hyperrotor.RigidBody.euler_equations` and
:meth:`hyperrotor.RigidBody.lock`; ``tests/paper/test_printed_euler.py`` compares
the two and names every discrepancy.

Transcription
-------------
Each equation is kept as a short text in a mini-language (``EQUATION_TEXT``),
then parsed into a ``sympy.Eq`` with the package's own symbols:

========  ============================================  =======================
text      meaning                                       SymPy object
========  ============================================  =======================
``I23``   printed :math:`I^{2323}` (read as the plane   ``Symbol("I_23", positive=True)``
          moment :math:`I_{23}`, see                    (= ``Inertia.symbolic(5)``)
          :class:`hyperrotor.Inertia`)
``w23``   :math:`\omega_{23}`                           ``Function("omega_23")(t)``
``d23``   :math:`d\omega_{23}/dt`                       ``Derivative(omega_23(t), t)``
``mt23``  :math:`\tilde m^{23}`                         ``Symbol("mtilde_23")``
========  ============================================  =======================

The tables are transcribed cell by cell (``TABLE_1_TEXT``, ``TABLE_2_TEXT``),
rows and columns in the plane order of eq. (8), with symbols ``L_ij`` and
``e_ij`` (:func:`hyperrotor.plane_symbols`).

Known problems of the print (verified in the tests, summarized here)
--------------------------------------------------------------------
* (28)-(37) are correct, and so are the 4D sextets (42)-(71).
* Sec. 2.2.4 says "(31),(34),(36),(37) erased" (copied from 2.2.5); locking
  axis 4 erases (30),(33),(35),(37).
* Sec. 2.2.5 calls its frozen set :math:`S_5` (the other 4D sections say :math:`S_4`).
* Sec. 2.3 (73)-(75): axes 4 and 5 are locked (:math:`S_3`), yet each equation
  keeps a term in :math:`\omega_{15}, \omega_{25}, \omega_{35}` (they are
  (60), (61), (63) unchanged).
* Sec. 2.4 (76)-(78): axis 3 (and 5) locked, yet each equation keeps a term in
  :math:`\omega_{13}, \omega_{23}` or :math:`\omega_{34}` (they are (66), (68), (70) unchanged).
* Sec. 2.5: the heading says axis 4, the text says axis 3, but the remaining
  axes 1-3-4 mean axis 2 (and 5) is locked; (79)-(81) keep terms in
  :math:`\omega_{12}, \omega_{23}, \omega_{24}` (they are (67), (68), (71) unchanged).
* Tables 1 and 2 have the right non-zero pattern but wrong signs in many
  cells (36 resp. 35 of the 60 non-zero cells, see the tests); no relabelling
  of basis signs repairs them, Table 2 is not even antisymmetric, and the two
  tables differ in three cells although the text says their signs are identical.
"""
from __future__ import annotations

import re
from dataclasses import dataclass

import sympy as sp

from hyperrotor.conventions import planes, plane_symbols

__all__ = [
    "EQUATION_TEXT",
    "PRINTED_EULER",
    "PRINTED_REDUCTIONS",
    "PRINTED_EQUATIONS",
    "PRINTED_TABLE_1",
    "PRINTED_TABLE_2",
    "TABLE_1_TEXT",
    "TABLE_2_TEXT",
    "ReductionSection",
    "REDUCTION_SECTIONS",
    "EULER_EQUATION_PLANES",
    "printed_symbols",
    "equation_plane",
]

#: Time symbol of the printed equations (the same as ``hyperrotor.classical.rigid_body.TIME``).
_t = sp.Symbol("t")

#: The printed equations (28)-(37) and (42)-(81), transcribed (``lhs = rhs``).
EQUATION_TEXT: dict[str, str] = {
    # --- Sec. 2.1, the 5D Euler equations
    "28": "-I12*d12 + (I13-I23)*w13*w23 + (I14-I24)*w14*w24 + (I15-I25)*w15*w25 = mt12",
    "29": "I13*d13 + (I12-I23)*w12*w23 + (I34-I14)*w14*w34 + (I35-I15)*w15*w35 = mt13",
    "30": "-I14*d14 + (I24-I12)*w12*w24 + (I34-I13)*w13*w34 + (I15-I45)*w15*w45 = mt14",
    "31": "I15*d15 + (I12-I25)*w12*w25 + (I13-I35)*w13*w35 + (I14-I45)*w14*w45 = mt15",
    "32": "-I23*d23 + (I12-I13)*w12*w13 + (I24-I34)*w24*w34 + (I25-I35)*w25*w35 = mt23",
    "33": "I24*d24 + (I14-I12)*w12*w14 + (I23-I34)*w23*w34 + (I45-I25)*w25*w45 = mt24",
    "34": "-I25*d25 + (I12-I15)*w12*w15 + (I35-I23)*w23*w35 + (I45-I24)*w24*w45 = mt25",
    "35": "-I34*d34 + (I13-I14)*w13*w14 + (I23-I24)*w23*w24 + (I35-I45)*w35*w45 = mt34",
    "36": "I35*d35 + (I15-I13)*w13*w15 + (I25-I23)*w23*w25 + (I34-I45)*w34*w45 = mt35",
    "37": "-I45*d45 + (I14-I15)*w14*w15 + (I24-I25)*w24*w25 + (I34-I35)*w34*w35 = mt45",
    # --- Sec. 2.2.1, axis 1 locked
    "42": "-I23*d23 + (I24-I34)*w24*w34 + (I25-I35)*w25*w35 = mt23",
    "43": "I24*d24 + (I23-I34)*w23*w34 + (I45-I25)*w25*w45 = mt24",
    "44": "-I25*d25 + (I35-I23)*w23*w35 + (I45-I24)*w24*w45 = mt25",
    "45": "-I34*d34 + (I23-I24)*w23*w24 + (I35-I45)*w35*w45 = mt34",
    "46": "I35*d35 + (I25-I23)*w23*w25 + (I34-I45)*w34*w45 = mt35",
    "47": "-I45*d45 + (I24-I25)*w24*w25 + (I34-I35)*w34*w35 = mt45",
    # --- Sec. 2.2.2, axis 2 locked
    "48": "I13*d13 + (I34-I14)*w14*w34 + (I35-I15)*w15*w35 = mt13",
    "49": "-I14*d14 + (I34-I13)*w13*w34 + (I15-I45)*w15*w45 = mt14",
    "50": "I15*d15 + (I13-I35)*w13*w35 + (I14-I45)*w14*w45 = mt15",
    "51": "-I34*d34 + (I13-I14)*w13*w14 + (I35-I45)*w35*w45 = mt34",
    "52": "I35*d35 + (I15-I13)*w13*w15 + (I34-I45)*w34*w45 = mt35",
    "53": "-I45*d45 + (I14-I15)*w14*w15 + (I34-I35)*w34*w35 = mt45",
    # --- Sec. 2.2.3, axis 3 locked
    "54": "-I12*d12 + (I14-I24)*w14*w24 + (I15-I25)*w15*w25 = mt12",
    "55": "-I14*d14 + (I24-I12)*w12*w24 + (I15-I45)*w15*w45 = mt14",
    "56": "I15*d15 + (I12-I25)*w12*w25 + (I14-I45)*w14*w45 = mt15",
    "57": "I24*d24 + (I14-I12)*w12*w14 + (I45-I25)*w25*w45 = mt24",
    "58": "-I25*d25 + (I12-I15)*w12*w15 + (I45-I24)*w24*w45 = mt25",
    "59": "-I45*d45 + (I14-I15)*w14*w15 + (I24-I25)*w24*w25 = mt45",
    # --- Sec. 2.2.4, axis 4 locked
    "60": "-I12*d12 + (I13-I23)*w13*w23 + (I15-I25)*w15*w25 = mt12",
    "61": "I13*d13 + (I12-I23)*w12*w23 + (I35-I15)*w15*w35 = mt13",
    "62": "I15*d15 + (I12-I25)*w12*w25 + (I13-I35)*w13*w35 = mt15",
    "63": "-I23*d23 + (I12-I13)*w12*w13 + (I25-I35)*w25*w35 = mt23",
    "64": "-I25*d25 + (I12-I15)*w12*w15 + (I35-I23)*w23*w35 = mt25",
    "65": "I35*d35 + (I15-I13)*w13*w15 + (I25-I23)*w23*w25 = mt35",
    # --- Sec. 2.2.5, axis 5 locked
    "66": "-I12*d12 + (I13-I23)*w13*w23 + (I14-I24)*w14*w24 = mt12",
    "67": "I13*d13 + (I12-I23)*w12*w23 + (I34-I14)*w14*w34 = mt13",
    "68": "-I14*d14 + (I24-I12)*w12*w24 + (I34-I13)*w13*w34 = mt14",
    "69": "-I23*d23 + (I12-I13)*w12*w13 + (I24-I34)*w24*w34 = mt23",
    "70": "I24*d24 + (I14-I12)*w12*w14 + (I23-I34)*w23*w34 = mt24",
    "71": "-I34*d34 + (I13-I14)*w13*w14 + (I23-I24)*w23*w24 = mt34",
    # --- Sec. 2.3, "axis 4 additionally" (S_3: axes 4 and 5 locked)
    "73": "-I12*d12 + (I13-I23)*w13*w23 + (I15-I25)*w15*w25 = mt12",
    "74": "I13*d13 + (I12-I23)*w12*w23 + (I35-I15)*w15*w35 = mt13",
    "75": "-I23*d23 + (I12-I13)*w12*w13 + (I25-I35)*w25*w35 = mt23",
    # --- Sec. 2.4, "axis 3 additionally" (remaining axes 1-2-4)
    "76": "-I12*d12 + (I13-I23)*w13*w23 + (I14-I24)*w14*w24 = mt12",
    "77": "-I14*d14 + (I24-I12)*w12*w24 + (I34-I13)*w13*w34 = mt14",
    "78": "I24*d24 + (I14-I12)*w12*w14 + (I23-I34)*w23*w34 = mt24",
    # --- Sec. 2.5, heading "axis four", text "axis 3" (remaining axes 1-3-4)
    "79": "I13*d13 + (I12-I23)*w12*w23 + (I34-I14)*w14*w34 = mt13",
    "80": "-I14*d14 + (I24-I12)*w12*w24 + (I34-I13)*w13*w34 = mt14",
    "81": "-I34*d34 + (I13-I14)*w13*w14 + (I23-I24)*w23*w24 = mt34",
}

#: Table 1 as printed: components of the auxiliary matrix (24), rows/columns in plane order.
TABLE_1_TEXT = """
   0 -L23  L24 -L25 -L13  L14 -L15    0    0    0
 L23    0  L34 -L35  L12    0    0 -L14  L15    0
-L24 -L34    0 -L45    0 -L12    0  L13    0 -L15
 L25  L35  L45    0    0    0  L12    0 -L13  L14
 L13 -L12    0    0    0 -L34  L35 -L24  L25    0
-L14    0  L12    0  L34    0  L45  L23    0 -L25
 L15    0    0 -L12 -L35 -L45    0    0 -L23  L24
   0  L14 -L13    0  L24 -L23    0    0 -L45 -L35
   0 -L15    0  L13 -L25    0  L23  L45    0  L34
   0    0  L15 -L14    0  L25 -L24  L35 -L34    0
"""

#: Table 2 as printed: products of basis bivectors e^{ij} ^ e^{kl}, rows/columns in plane order.
TABLE_2_TEXT = """
   0 -e23  e24 -e25 -e13  e14 -e15    0    0    0
 e23    0  e34 -e35  e12    0    0 -e14  e15    0
-e24 -e34    0 -e45    0 -e12    0  e13    0 -e15
 e25  e35  e45    0    0    0  e12    0 -e13  e14
 e13 -e12    0    0    0  e34 -e35  e24  e25    0
-e14    0  e12    0  e34    0  e45  e23    0 -e25
 e15    0    0 -e12 -e35 -e45    0    0 -e23  e24
   0  e14 -e13    0  e24 -e23    0    0 -e45 -e35
   0 -e15    0  e13 -e25    0  e23  e45    0  e34
   0    0  e15 -e14    0  e25 -e24  e35 -e34    0
"""


def printed_symbols() -> dict[str, object]:
    """The mini-language names (``I12``, ``w12``, ``d12``, ``mt12``, ``t``) mapped to SymPy objects."""
    names: dict[str, object] = {"t": _t}
    I = plane_symbols("I", 5, positive=True)
    w = plane_symbols("omega", 5, function_of=_t)
    for (i, j), Ii, wi in zip(planes(5), I, w):
        k = f"{i}{j}"
        names[f"I{k}"] = Ii
        names[f"w{k}"] = wi
        names[f"d{k}"] = sp.Derivative(wi, _t)
        names[f"mt{k}"] = sp.Symbol(f"mtilde_{k}")
    return names


def _parse_equation(text: str) -> sp.Eq:
    """Parse one transcription ``"lhs = rhs"`` of the mini-language into an unevaluated ``sympy.Eq``."""
    lhs, rhs = text.split("=")
    names = printed_symbols()
    tokens = set(re.findall(r"[A-Za-z]+\d*", text))
    unknown = tokens - set(names)
    if unknown:
        raise ValueError(f"unknown names {sorted(unknown)} in {text!r}")
    return sp.Eq(
        sp.parse_expr(lhs, local_dict=names, evaluate=True),
        sp.parse_expr(rhs, local_dict=names, evaluate=True),
        evaluate=False,
    )


def _parse_table(text: str, name: str) -> sp.Matrix:
    sym = {f"{i}{j}": s for (i, j), s in zip(planes(5), plane_symbols(name, 5))}
    rows = [r.split() for r in text.strip().splitlines()]
    if len(rows) != 10 or any(len(r) != 10 for r in rows):
        raise ValueError(f"table {name} must be 10 x 10")
    M = sp.zeros(10, 10)
    for a, row in enumerate(rows):
        for b, cell in enumerate(row):
            if cell == "0":
                continue
            sign = -1 if cell.startswith("-") else 1
            body = cell.lstrip("-")
            if body[0] != name or body[1:] not in sym:
                raise ValueError(f"bad cell {cell!r} in table {name}")
            M[a, b] = sign * sym[body[1:]]
    return M


#: (28)-(37) as printed, keyed by equation number.
PRINTED_EULER: dict[str, sp.Eq] = {k: _parse_equation(v) for k, v in EQUATION_TEXT.items() if int(k) <= 37}
#: (42)-(81) as printed.
PRINTED_REDUCTIONS: dict[str, sp.Eq] = {k: _parse_equation(v) for k, v in EQUATION_TEXT.items() if int(k) >= 42}
#: All transcribed equations.
PRINTED_EQUATIONS: dict[str, sp.Eq] = {**PRINTED_EULER, **PRINTED_REDUCTIONS}
#: Table 1 as printed (entries in ``L_ij``).
PRINTED_TABLE_1: sp.Matrix = _parse_table(TABLE_1_TEXT, "L")
#: Table 2 as printed (entries in ``e_ij``).
PRINTED_TABLE_2: sp.Matrix = _parse_table(TABLE_2_TEXT, "e")

#: The plane of each of (28)-(37) (eq. (28) is the (1, 2) equation, ...).
EULER_EQUATION_PLANES: dict[str, tuple[int, int]] = {str(28 + k): p for k, p in enumerate(planes(5))}


def equation_plane(eq: sp.Eq) -> tuple[int, int]:
    """The plane ``(i, j)`` whose time derivative appears in a printed equation."""
    ders = list(eq.lhs.atoms(sp.Derivative))
    if len(ders) != 1:
        raise ValueError(f"expected exactly one derivative in {eq}")
    name = ders[0].expr.func.__name__  # "omega_23"
    i, j = name.split("_")[1]
    return int(i), int(j)


@dataclass(frozen=True)
class ReductionSection:
    """What one reduction section of the paper prints.

    Attributes
    ----------
    section : str
        Section number, e.g. ``"2.2.4"``.
    heading : str
        The printed heading.
    heading_axis : int
        Axis named in the heading.
    text_axis : int
        Axis named in the text as (additionally) locked.
    frozen_planes : tuple or None
        The printed set of vanishing components (``S_4``, ``S_5``, ``S_3``), if any.
    erased : tuple of str or None
        Equation numbers the text says are "erased", if it says so.
    remaining_axes : tuple of int
        Axes the text says span the remaining subspace ("1 - 2 - 3 - 5").
    equations : tuple of str
        The printed equation numbers of the section.
    """

    section: str
    heading: str
    heading_axis: int
    text_axis: int
    frozen_planes: tuple | None
    erased: tuple | None
    remaining_axes: tuple
    equations: tuple

    @property
    def locked_axes(self) -> tuple:
        """Axes locked according to the stated remaining axes (the complement in 1..5)."""
        return tuple(a for a in range(1, 6) if a not in self.remaining_axes)

    @property
    def equation_planes(self) -> tuple:
        """The planes of the printed equations (from their derivatives)."""
        return tuple(equation_plane(PRINTED_EQUATIONS[k]) for k in self.equations)


def _eqs(a: int, b: int) -> tuple:
    return tuple(str(k) for k in range(a, b + 1))


#: The reduction sections 2.2.1-2.5 as printed.
REDUCTION_SECTIONS: tuple[ReductionSection, ...] = (
    ReductionSection("2.2.1", "Rotation Over Axis One Restricted", 1, 1,
                     ((1, 2), (1, 3), (1, 4), (1, 5)), None, (2, 3, 4, 5), _eqs(42, 47)),
    ReductionSection("2.2.2", "Rotation Over Axis Two Restricted", 2, 2,
                     ((1, 2), (2, 3), (2, 4), (2, 5)), ("28", "32", "33", "34"), (1, 3, 4, 5), _eqs(48, 53)),
    ReductionSection("2.2.3", "Rotation Over Axis Three Restricted", 3, 3,
                     ((1, 3), (2, 3), (3, 4), (3, 5)), ("29", "32", "35", "36"), (1, 2, 4, 5), _eqs(54, 59)),
    ReductionSection("2.2.4", "Rotation Over Axis Four Restricted", 4, 4,
                     ((1, 4), (2, 4), (3, 4), (4, 5)), ("31", "34", "36", "37"), (1, 2, 3, 5), _eqs(60, 65)),
    ReductionSection("2.2.5", "Rotation Over Axis Five Restricted", 5, 5,
                     ((1, 5), (2, 5), (3, 5), (4, 5)), ("31", "34", "36", "37"), (1, 2, 3, 4), _eqs(66, 71)),
    ReductionSection("2.3", "Additional Rotation Over Axis Four Restricted", 4, 4,
                     ((1, 4), (1, 5), (2, 4), (2, 5), (3, 4), (3, 5), (4, 5)), None, (1, 2, 3), _eqs(73, 75)),
    ReductionSection("2.4", "Additional Rotation Over Axis Three Restricted", 3, 3,
                     None, None, (1, 2, 4), _eqs(76, 78)),
    ReductionSection("2.5", "Additional Rotation Over Axis Four Restricted", 4, 3,
                     None, None, (1, 3, 4), _eqs(79, 81)),
)
