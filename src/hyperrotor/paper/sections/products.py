r"""The entry-by-entry check of a printed product :math:`\omega L - L\omega` (eqs. 25 and 144).

Eq. (25) prints the ten entries of the product of the checkerboard matrices
(21)-(22) of :math:`\omega` and :math:`L`; eq. (144) repeats the pattern with
the quantum operators. ``product_verdicts`` compares each printed entry with
the derived matrix entry (and with the component form :math:`[W, L]_{ij}`),
trying the notation slip of reading reversed indices without the sign of
eq. (1) (``_forward_indices``). Used by :mod:`hyperrotor.paper.sections.euler`
and :mod:`hyperrotor.paper.sections.quantum`.
"""
from __future__ import annotations

import re

import sympy as sp

from hyperrotor.conventions import lie_bracket, planes, to_matrix
from hyperrotor.paper import printed_solutions as ps
from hyperrotor.paper.verdicts import Verdict, antisym, compare, psym

__all__: list[str] = []  # helpers shared by the section checkers (package-internal)


def _entry_product(Lsyms, Wsyms) -> dict:
    """Plane -> (i, j) entry of W L - L W (paper matrices), generic components (eqs. 24-25)."""
    Lm = to_matrix(list(Lsyms), convention="paper")
    Wm = to_matrix(list(Wsyms), convention="paper")
    P = Wm * Lm - Lm * Wm
    return {(i, j): sp.expand(P[i - 1, j - 1]) for i, j in planes(5)}


def _printed_product(lines: dict, Lname: str, Wname: str) -> dict:
    return {p: sp.Add(*[s * psym(f"{Lname}_{a}") * psym(f"{Wname}_{b}") for s, a, b in terms]) for p, terms in lines.items()}


def product_verdicts(key: str, sec: str, Lname: str, Wname: str) -> list:
    Ls = [psym(f"{Lname}_{i}{j}") for i, j in planes(5)]
    Ws = [psym(f"{Wname}_{i}{j}") for i, j in planes(5)]
    derived = _entry_product(Ls, Ws)
    comp = dict(zip(planes(5), lie_bracket(Ws, Ls)))
    printed = _printed_product(ps.printed(key), Lname, Wname)
    out = []
    for p in planes(5):
        pr = antisym(printed[p])
        v = compare(f"{key} [{p[0]}{p[1]}]", sec, printed[p], derived[p],
                     note="entry (i,j) of wL - Lw with the checkerboard matrices (21)-(22)",
                     corrections=(("reversed indices (w^31, L^21, ...) are read as w^13, L^12 without the sign of eq. (1)",
                                   _forward_indices),))
        if v.status == "typo" and sp.expand(pr - comp[p]) == 0:
            v = Verdict(v.equation, "holds", "agrees with the component form [W, L]_ij", v.printed, v.correct, sec)
        out.append(v)
    return out


def _forward_indices(expr):
    """Read ``X_ji`` (j > i) as ``X_ij`` without a sign (a notation slip, contrary to eq. 1)."""
    reps = {}
    for s in expr.free_symbols:
        m = re.fullmatch(r"(\w+)_(\d)(\d)", s.name)
        if m and int(m.group(2)) > int(m.group(3)):
            reps[s] = psym(f"{m.group(1)}_{m.group(3)}{m.group(2)}")
    return expr.xreplace(reps)
