r"""Sec. 4 of the preprint: linear stability (119)-(140).

``sec_stability`` linearizes the Euler equations about a rotation in the
plane 12 with the perturbations :math:`\varpi_1, \dots, \varpi_{10}` of
(119)-(120) and the moments :math:`J_n` of (131) (``linearized``, cached),
compares the printed linearized equations (121)-(130) and the constant
components (132), solves the three coupled pairs (133)-(138) and checks the
printed frequencies; ``_stability_claims`` tests the stability chains
(139)-(140) with :func:`hyperrotor.classical.stability.linear_stability` and
:func:`hyperrotor.classical.stability.stability_condition`.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
import sympy as sp

from hyperrotor.conventions import plane_index
from hyperrotor.paper import printed_solutions as ps
from hyperrotor.paper.sections.derived import euler_entry_forms
from hyperrotor.paper.verdicts import Verdict, claim, compare, fmt_expr, mtilde, psym

__all__: list[str] = []  # the checker of this section is package-internal (sections.SECTIONS)


@lru_cache(maxsize=None)
def linearized() -> dict:
    """varpi index -> expanded first-order (in epsilon) entry-form equation, with I -> J of (131)."""
    eps = psym("epsilon")
    sub = {**ps.printed("119"), **ps.printed("120")}
    Jmap = {psym(f"I_{i}{j}"): J for J, (i, j) in ps.printed("131").items()}
    idx = {}
    for p, e in sub.items():
        n = int(next(s.name for s in e.free_symbols if s.name.startswith("varpi")).split("_")[1])
        idx[p] = n
    wsub = {psym(f"omega_{i}{j}"): e for (i, j), e in sub.items()}
    dsub = {psym(f"omegadot_{i}{j}"): eps * psym(f"varpidot_{idx[(i, j)]}") for (i, j) in sub}
    out = {}
    for p, f in euler_entry_forms().items():
        e = f.xreplace({mtilde(p): 0}).xreplace(dsub).xreplace(wsub).xreplace(Jmap)
        out[idx[p]] = sp.expand(sp.diff(sp.expand(e), eps).subs(eps, 0))
    return out


@lru_cache(maxsize=None)
def sec_stability() -> tuple:
    sec = "stability"
    out = []
    lin = linearized()
    Om = psym("Omega")
    trivial = sorted(n for n, e in lin.items() if not any(s.name.startswith("varpi_") for s in e.free_symbols))
    coupled = sorted(set(lin) - set(trivial))
    cl = ps.CLAIMS["Sec. 4 (trivial equations)"]
    out.append(claim("Sec. 4 (four equations satisfied)", sec, len(trivial) == cl["trivial"] and len(coupled) == cl["coupled"],
                      f"computed: {len(trivial)} linearized equations decouple with d(varpi)/dt = 0 (varpi {trivial}: planes "
                      f"{', '.join(f'{i}{j}' for n in trivial for (i, j), e in {**ps.printed('119'), **ps.printed('120')}.items() if psym(f'varpi_{n}') in e.free_symbols)}) "
                      f"and {len(coupled)} couple in three pairs; the paper nevertheless prints all ten as (121)-(130)",
                      f"{len(trivial)} trivial, {len(coupled)} coupled", cl["quote"]))
    out.append(Verdict("119-120", "not-checkable",
                       "definition of the perturbation variables varpi_1..varpi_10 (no relation to test); used for (121)-(132)",
                       None, None, sec))
    for n in range(1, 11):
        k = str(120 + n)
        out.append(compare(k, sec, ps.printed(k), lin[n], zero_form=True,
                            note="first order in epsilon of RigidBody.euler_equations, J of (131)"))
    out.append(Verdict("131", "not-checkable", "notation J_n = I^{ijij} (a definition); it is used as printed in (121)-(130)",
                       None, None, sec))
    pr132 = ps.printed("132")
    ok132 = set(pr132) == set(trivial)
    out.append(Verdict("132", "holds" if ok132 else "typo",
                       ("right" if ok132 else
                        f"the components with d(varpi)/dt = 0 are varpi {trivial}, not {list(pr132)}; and they are constant "
                        f"(= their initial values), not 0. Correct: " + ", ".join(f"varpi{n}" for n in trivial) + " = const"),
                       ", ".join(f"varpi{n} = 0" for n in pr132), ", ".join(f"varpi{n} = const" for n in trivial), sec))
    # pairs: (2, 5), (3, 6), (4, 7) with frequencies
    t = psym("t")
    C1, C2 = psym("C_1"), psym("C_2")
    for a, b, nu, keys in ((2, 5, "v_1", ("133", "134", "135")), (3, 6, "v_2", ("136 (varpi_3)", "136 (varpi_6)", "136")),
                           (4, 7, "v_3", ("137 (varpi_4)", "137", "138"))):
        ea, eb = lin[a], lin[b]
        da, db = psym(f"varpidot_{a}"), psym(f"varpidot_{b}")
        alpha = sp.solve(ea, da)[0] / psym(f"varpi_{b}")   # varpi_a' = alpha varpi_b
        beta = sp.solve(eb, db)[0] / psym(f"varpi_{a}")    # varpi_b' = beta varpi_a
        nu2 = sp.factor(-alpha * beta / Om**2)
        v = psym(nu)
        # solution of varpi_a
        sol_a = ps.printed(keys[0]).rhs
        ok_a = sp.simplify((sp.diff(sol_a, t, 2) - alpha * beta * sol_a).subs(v, sp.sqrt(nu2))) == 0
        out.append(Verdict(keys[0], "holds" if ok_a else "typo",
                           f"solves varpi{a}'' = -Omega^2 nu^2 varpi{a} with the derived nu^2 = {fmt_expr(nu2)}" if ok_a
                           else "does not solve the derived pair", fmt_expr(ps.printed(keys[0])), None, sec))
        # partner: varpi_b = varpi_a' / alpha
        partner = sp.simplify(sp.diff(sol_a, t) / alpha)
        reading = ps.printed(keys[1])["reading"]
        okb = sp.simplify(reading - partner) == 0
        okb_neg = sp.simplify(reading + partner) == 0
        out.append(Verdict(keys[1], "holds" if okb else "typo",
                           (f"under the fraction reading {fmt_expr(reading)} it equals the derived varpi{b} = varpi{a}'/({fmt_expr(alpha)})")
                           if okb else
                           (f"under the fraction reading ({ps.LITERAL[keys[1]]!r} -> {fmt_expr(reading)}) the "
                            f"{'overall sign is' if okb_neg else 'expression is'} wrong. Correct: varpi{b} = {fmt_expr(sp.factor(partner))}"),
                           ps.LITERAL[keys[1]], fmt_expr(sp.factor(partner)), sec))
        # the frequency (garbled)
        lit = ps.printed(keys[2])["literal"]
        Js = sorted(lit.free_symbols, key=lambda s: s.name)
        lam = sp.Symbol("lam", positive=True)
        homogeneous = sp.simplify(lit.subs({j: lam * j for j in Js}, simultaneous=True) - lit) == 0
        matches = sp.simplify(lit**2 - nu2) == 0 or sp.simplify(lit - nu2) == 0
        if matches:
            out.append(Verdict(keys[2], "holds", f"nu^2 = {fmt_expr(nu2)}", ps.LITERAL[keys[2]], None, sec))
        elif homogeneous:
            out.append(Verdict(keys[2], "typo", f"wrong frequency. Correct: {nu} = sqrt({fmt_expr(nu2)})",
                               ps.LITERAL[keys[2]], f"sqrt({fmt_expr(nu2)})", sec))
        else:
            out.append(Verdict(keys[2], "not-checkable",
                               f"garbled by the text extraction: the literal reading {ps.LITERAL[keys[2]]!r} is not homogeneous of "
                               f"degree 0 in the moments (computed), so it cannot be a frequency ratio. Derived: {nu} = sqrt({fmt_expr(nu2)})",
                               ps.LITERAL[keys[2]], f"sqrt({fmt_expr(nu2)})", sec))
    out += _stability_claims(sec)
    return tuple(out)


def _stability_claims(sec: str) -> list:
    from hyperrotor.classical.stability import linear_stability, stability_condition

    out = []
    cond = stability_condition((1, 2), 5, symbol="I")
    Jmap = ps.printed("131")
    for k in ("139", "140"):
        p = ps.printed(k)
        order = p["order"]
        # a configuration satisfying the printed non-strict chain with J1 = J2 (equality allowed by the print)
        base = list(range(10, 0, -1)) if p["relation"] == ">=" else list(range(1, 11))
        vals = list(base)
        vals[1] = vals[0]
        moments = np.zeros(10)
        for J, v in zip(order, vals):
            moments[plane_index(Jmap[J], 5)] = float(v)
        res = linear_stability(moments, (1, 2), 1.0)
        # strict chain: sufficient
        strict = np.zeros(10)
        for J, v in zip(order, base):
            strict[plane_index(Jmap[J], 5)] = float(v)
        res_strict = linear_stability(strict, (1, 2), 1.0)
        # not necessary: J1 between others yet stable
        # I12 = 5: below I13, I23 and I15, I25, above I14, I24 (plane order 12,13,14,15,23,24,25,34,35,45)
        mixed = np.array([5.0, 6.0, 4.0, 7.0, 6.5, 3.0, 8.0, 3.5, 1.0, 9.0])
        res_mixed = linear_stability(mixed, (1, 2), 1.0)
        ok = res.stable
        out.append(claim(
            k, sec, ok, "",
            f"the printed chain allows equality: with J1 = J2 (moments {vals}) linear_stability finds "
            f"'{res.reason}', not stable oscillations. With strict inequalities the chain is sufficient "
            f"({'stable' if res_strict.stable else 'UNSTABLE'}), but it is not necessary (e.g. I = {mixed.tolist()} is "
            f"{'stable' if res_mixed.stable else 'unstable'} with I12 neither largest nor smallest). Correct condition "
            f"(stability_condition): {cond}",
            fmt_expr(p["order"]) + " " + p["relation"], str(cond)))
    return out
