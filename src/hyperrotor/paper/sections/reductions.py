"""Sec. 2.2-2.5 of the preprint: reductions (42)-(81), headings and locked sets.

``sec_reductions`` checks every printed equation of the lower-dimensional
reductions against the Euler equations of the body with the same axes locked
(:meth:`hyperrotor.RigidBody.lock`), naming equations copied unreduced from the
4D sextet (42)-(71); per section it checks that the heading, the text, the
frozen set, its name and the erased equations agree with the locked axes; and it
checks the list of 4D subspaces (72) and the closing count of Sec. 2.5.
"""
from __future__ import annotations

from functools import lru_cache
from itertools import combinations

import sympy as sp

from hyperrotor.conventions import planes
from hyperrotor.paper import printed_solutions as ps
from hyperrotor.paper.sections.derived import body5, euler_entry_forms
from hyperrotor.paper.verdicts import Verdict, claim, compare, eq_str, eq_zero, grouped, mtilde, psym, expr_terms

__all__: list[str] = []  # the checker of this section is package-internal (sections.SECTIONS)


_SET_LABELS = {"2.2.1": "S_4", "2.2.2": "S_4", "2.2.3": "S_4", "2.2.4": "S_4", "2.2.5": "S_5", "2.3": "S_3"}


@lru_cache(maxsize=None)
def sec_reductions() -> tuple:
    from hyperrotor.paper import printed as pr

    sec = "reductions"
    out = []
    eq_of_plane = {p: str(28 + k) for k, p in enumerate(planes(5))}
    for rs in pr.REDUCTION_SECTIONS:
        locked = rs.locked_axes
        ref = euler_entry_forms(tuple(locked))
        lockset = {psym(f"omega_{i}{j}"): 0 for i, j in planes(5) if i in locked or j in locked}
        for k in rs.equations:
            eq = pr.PRINTED_EQUATIONS[k]
            p = pr.equation_plane(eq)
            pz = eq_zero(eq)
            if p not in ref:
                out.append(Verdict(k, "typo", f"the equation is for the plane {p}, which is locked in Sec. {rs.section}",
                                   eq_str(pz, mtilde(p)), None, sec))
                continue
            d = ref[p]
            v = compare(k, sec, pz, d, correct=eq_str(d, mtilde(p)),
                         note=f"body with axes {locked} locked, RigidBody.lock")
            if v.status == "typo" and sp.expand(pz.xreplace(lockset) - d) == 0:
                stale_terms = [c * t for t, c in expr_terms(pz).items() if (c * t).xreplace(lockset) == 0]
                v = Verdict(k, "typo",
                            f"not reduced: keeps {grouped(sp.Add(*stale_terms))}, which vanishes"
                            f" because axes {locked} are locked (the equation is copied from eq. "
                            f"{_source_equation(pz, k)}). Correct: {eq_str(d, mtilde(p))}",
                            eq_str(pz, mtilde(p)), eq_str(d, mtilde(p)), sec)
            out.append(v)
        # section-level claims
        problems = []
        if len(locked) == 1:
            a = locked[0]
            want_planes = tuple(p for p in planes(5) if a in p)
            if rs.heading_axis != a or rs.text_axis != a:
                problems.append(f"heading/text name axis {rs.heading_axis}/{rs.text_axis}, the remaining axes {rs.remaining_axes} lock axis {a}")
            if rs.frozen_planes is not None and set(rs.frozen_planes) != set(want_planes):
                problems.append(f"frozen set {rs.frozen_planes} != planes through axis {a} {want_planes}")
            if rs.erased is not None:
                want = tuple(eq_of_plane[p] for p in want_planes)
                if set(rs.erased) != set(want):
                    problems.append(f"the erased equations are ({'),('.join(want)}), not ({'),('.join(rs.erased)})")
        else:
            prior = [b for b in locked if b != rs.heading_axis]
            if rs.heading_axis not in locked:
                problems.append(f"the heading names axis {rs.heading_axis}, but the remaining axes "
                                f"{'-'.join(map(str, rs.remaining_axes))} mean axes {locked} are locked "
                                f"(the additionally locked axis is {', '.join(str(b) for b in locked if b != 5)})")
            if rs.text_axis not in locked:
                problems.append(f"the text names axis {rs.text_axis}, which is not locked")
            if rs.frozen_planes is not None:
                want_planes = tuple(p for p in planes(5) if set(p) & set(locked))
                if set(rs.frozen_planes) != set(want_planes):
                    problems.append(f"frozen set {rs.frozen_planes} != {want_planes}")
            del prior
        label = _SET_LABELS.get(rs.section)
        n_rem = len(rs.remaining_axes)
        if label is not None and label != f"S_{n_rem}":
            problems.append(f"the frozen set is called {label}; the other sections name it by the remaining dimension, S_{n_rem}")
        eq_planes = set(rs.equation_planes)
        rem_planes = {p for p in planes(5) if set(p) <= set(rs.remaining_axes)}
        if eq_planes != rem_planes:
            problems.append(f"the printed equations are for the planes {sorted(eq_planes)}, the remaining planes are {sorted(rem_planes)}")
        name = f"Sec. {rs.section} (heading, locked set)"
        if not problems:
            out.append(Verdict(name, "holds",
                               f"locked axes {locked}, frozen set, erased equations and the planes of the {len(rs.equations)} "
                               f"equations are consistent", None, None, sec))
        else:
            status = "claim-false" if any("heading" in p or "text names" in p for p in problems) else "typo"
            out.append(Verdict(name, status, "; ".join(problems), None, None, sec))
    # (72): the five 4D subspaces
    sets = ps.CLAIMS["72"]["sets"]
    allsets = {frozenset(c) for c in combinations(range(1, 6), 4)}
    out.append(claim("72", sec, {frozenset(s) for s in sets} == allsets and len(sets) == len(allsets),
                      f"the five sets are exactly the C(5,4) = {len(allsets)} four-axis subsets",
                      "the listed sets are not the four-axis subsets", ps.CLAIMS["72"]["quote"]))
    cl = ps.CLAIMS["Sec. 2.5 (closing)"]
    n4 = len(body5().lock(5).planes)
    n3 = len(body5().lock((4, 5)).planes)
    out.append(claim("Sec. 2.5 (closing statement)", sec, n4 == cl["per_4d"] and n3 == cl["per_3d"], "",
                      f"each 4D subspace carries {n4} Euler equations (not {cl['per_4d']}); each 3D one {n3}", cl["quote"]))
    return tuple(out)


def _source_equation(pz, key) -> str:
    """Number of the 4D-sextet equation (42)-(71) that equals the printed one (for the detail text)."""
    from hyperrotor.paper import printed as pr

    for k in range(42, 72):
        if sp.expand(eq_zero(pr.PRINTED_EQUATIONS[str(k)]) - pz) == 0:
            return f"({k})"
    return "?"
