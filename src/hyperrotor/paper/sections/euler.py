r"""Sec. 2.1 of the preprint: product (25), Tables 1-2, Euler equations (28)-(37), invariants (38).

``sec_euler`` checks the printed entries of :math:`\omega L - L\omega`
(eq. 25, via :mod:`hyperrotor.paper.sections.products`); Tables 1 and 2 of
bivector products against the commutator table
(:func:`hyperrotor.conventions.bivector_product_table`) and its sign variants,
with their antisymmetry, disjoint-plane and same-sign claims; the ten Euler
equations (28)-(37) against :meth:`hyperrotor.RigidBody.euler_equations`; the
claims on the order and number of the equations; and (``_eq38``) the
characteristic polynomial (38), its coefficients as Casimirs
(:meth:`hyperrotor.RigidBody.casimirs`) and the number of independent integrals.
"""
from __future__ import annotations

from functools import lru_cache
from itertools import combinations

import numpy as np
import sympy as sp

from hyperrotor.conventions import lie_poisson_bracket, plane_symbols, planes, to_matrix
from hyperrotor.paper import printed_solutions as ps
from hyperrotor.paper.sections.derived import body5, euler_entry_forms
from hyperrotor.paper.sections.products import product_verdicts
from hyperrotor.paper.verdicts import Verdict, claim, compare, eq_str, eq_zero, fmt_expr, mtilde, psym

__all__: list[str] = []  # the checker of this section is package-internal (sections.SECTIONS)


_COMM = "the commutator table [e_a, e_b] (bivector_product_table)"


def _table_candidates(sym: str) -> dict:
    """Derived tables: the commutator table (``bivector_product_table``) and its sign variants."""
    from hyperrotor.conventions import bivector_product_table

    A = bivector_product_table(5, convention="paper", symbol=sym)
    s = [(-1) ** (i + j) for i, j in planes(5)]
    S = sp.Matrix(10, 10, lambda a, b: s[a] * s[b])
    C = A.multiply_elementwise(S)
    B = sp.diag(*s) * A
    return {
        "the row-signed table (-1)^(i+j) [e_a, e_b], (i,j) the row plane (entry (i,j) of wL - Lw against the components of w, the convention of eq. 25)": B,
        "minus the row-signed table": -B,
        _COMM: A,
        "minus the commutator table": -A,
        "the entry-form table (-1)^(a+b) [e_a, e_b]": C,
        "minus the entry-form table, i.e. entries of L-dot = (wL - Lw) as a matrix acting on the entries of w": -C,
    }


def _label(a: int) -> str:
    i, j = planes(5)[a]
    return f"{i}{j}"


def _table_verdict(key: str, sec: str, P: sp.Matrix, sym: str) -> tuple[Verdict, str, sp.Matrix]:
    cands = _table_candidates(sym)
    scored = []
    for name, D in cands.items():
        bad = [(a, b) for a in range(10) for b in range(10) if sp.expand(P[a, b] - D[a, b]) != 0]
        scored.append((len(bad), name, D, bad))
    scored.sort(key=lambda x: x[0])
    nbad, name, D, bad = scored[0]
    if nbad == 0:
        return Verdict(key, "holds", f"equals {name}", None, None, sec), name, D
    cells = ", ".join(f"({_label(a)},{_label(b)}): {fmt_expr(P[a, b])} -> {fmt_expr(D[a, b])}" for a, b in bad)
    others = "; ".join(f"{n}: {k}" for k, n, _, _ in scored[1:])
    return Verdict(key, "typo",
                   f"no sign convention reproduces the printed table; closest derived table: {name}, with {nbad} wrong cells "
                   f"(row,col: printed -> correct): {cells}. Wrong cells against the other conventions: {others}",
                   None, None, sec), name, D


@lru_cache(maxsize=None)
def sec_euler() -> tuple:
    from hyperrotor.paper import printed as pr

    sec = "euler"
    out = []
    # eq. (25)
    out += product_verdicts("25", sec, "L", "omega")
    # Tables 1 and 2
    T1 = pr.PRINTED_TABLE_1
    T2 = pr.PRINTED_TABLE_2
    v1, _, D1 = _table_verdict("Table 1", sec, T1, "L")
    v2, _, D2 = _table_verdict("Table 2", sec, T2, "e")
    out += [v1, v2]
    comm = _table_candidates("e")[_COMM]
    asym = [(a, b) for a in range(10) for b in range(a + 1, 10) if sp.expand(T2[a, b] + T2[b, a]) != 0]
    true_asym = all(sp.expand(comm[a, b] + comm[b, a]) == 0 for a in range(10) for b in range(10))
    out.append(Verdict(
        "Table 2 (antisymmetry)", "holds" if not asym else "typo",
        ("the printed table is antisymmetric" if not asym else
         "the products are antisymmetric (derived table: " + ("yes" if true_asym else "NO") + "), but the printed table is not: "
         + ", ".join(f"({_label(a)},{_label(b)})={fmt_expr(T2[a, b])} vs ({_label(b)},{_label(a)})={fmt_expr(T2[b, a])}" for a, b in asym)),
        ps.CLAIMS["Table 2 (antisymmetric)"]["quote"], None, sec))
    # disjoint planes give zero products
    disjoint = [(a, b) for a, p in enumerate(planes(5)) for b, q in enumerate(planes(5)) if not set(p) & set(q)]
    der_zero = all(comm[a, b] == 0 for a, b in disjoint)
    pr_zero = all(T2[a, b] == 0 for a, b in disjoint)
    out.append(claim("Table 2 (disjoint planes)", sec, der_zero and pr_zero,
                      f"computed: [e_ij, e_kl] = 0 for all {len(disjoint)} ordered pairs of disjoint planes, and the printed table has 0 there",
                      "a product of disjoint planes is non-zero", ps.CLAIMS["Table 2 (disjoint planes)"]["quote"]))
    e_to_L = {s: psym("L_" + s.name.split("_")[1]) for s in T2.free_symbols | D2.free_symbols}
    derived_same = sp.expand(D2.xreplace(e_to_L) - D1) == sp.zeros(10, 10)
    diff = [(a, b) for a in range(10) for b in range(10) if sp.expand(T2.xreplace(e_to_L)[a, b] - T1[a, b]) != 0]
    out.append(claim("Tables 1-2 (same signs)", sec, not diff,
                      "the printed tables agree cell by cell (e -> L)",
                      "the printed tables differ in " + str(len(diff)) + " cells: "
                      + ", ".join(f"({_label(a)},{_label(b)}) T1={fmt_expr(T1[a, b])} T2={fmt_expr(T2[a, b])}" for a, b in diff)
                      + (" (the derived tables do coincide, e -> L)" if derived_same else " (the derived tables differ too)"),
                      ps.CLAIMS["Tables 1-2 (same signs)"]["quote"]))
    # Euler equations (28)-(37)
    ref = euler_entry_forms()
    for k, eq in pr.PRINTED_EULER.items():
        p = pr.equation_plane(eq)
        d = ref[p]
        out.append(compare(k, sec, eq_zero(eq), d, correct=eq_str(d, mtilde(p)),
                            note="matrix entry (i,j) of dL/dt - (wL - Lw) = m~, RigidBody.euler_equations()"))
    # order / number of equations
    eqs = body5().euler_equations()
    order = max(d.derivative_count for e in eqs for d in e.lhs.atoms(sp.Derivative))
    cl = ps.CLAIMS["Sec. 2.1 (order)"]
    out.append(claim("Sec. 2.1 (order of the equations)", sec, order == cl["order"] and len(eqs) == cl["count"],
                      "", f"the {len(eqs)} Euler equations are of order {order} in the angular velocities "
                          f"(first-order ODEs), not {cl['order']}", cl["quote"]))
    n3 = len(list(combinations(range(1, 6), 3)))
    three_d = all(len(body5().lock(tuple(a for a in range(1, 6) if a not in keep)).planes) == 3
                  for keep in combinations(range(1, 6), 3))
    cl = ps.CLAIMS["Sec. 2.1 (3D cases)"]
    out.append(claim("Sec. 2.1 (number of 3D cases)", sec, n3 == cl["count"] and three_d, "",
                      f"5D has C(5,3) = {n3} three-dimensional coordinate subspaces (each reduction RigidBody.lock gives "
                      f"3 Euler equations), not {cl['count']}", cl["quote"]))
    out += _eq38(sec)
    return tuple(out)


def _eq38(sec: str) -> list:
    out = []
    Ls = plane_symbols("L", 5, real=True)
    lam = ps.printed("38")["lambda"]
    Lp = to_matrix(list(Ls), convention="paper")
    charpoly = sp.Poly(sp.expand((Lp - lam * sp.eye(5)).det(method="berkowitz")), lam)
    rhs = sp.Poly(ps.printed("38")["rhs"], lam)
    dpows = {m[0]: c for m, c in zip(charpoly.monoms(), charpoly.coeffs())}
    ppows = {m[0] for m in rhs.monoms()}
    k3 = dpows.get(3, 0)
    k1 = dpows.get(1, 0)
    # package Casimirs: det(lam - L) = lam^5 + c2 lam^3 + c4 lam
    c2, c4 = body5().casimirs(list(Ls), of="L")
    pk = sp.expand(k3 + c2) == 0 and sp.expand(k1 + c4) == 0
    missing = sorted(set(dpows) - ppows)
    extra = sorted(ppows - set(dpows))
    if not missing and not extra:
        out.append(Verdict("38", "holds", "same powers of lambda", None, None, sec))
    else:
        out.append(Verdict(
            "38", "typo",
            f"the characteristic polynomial has the powers lambda^{sorted(dpows)}; the print omits "
            + ", ".join(fmt_expr(dpows[k] * lam**k) for k in missing)
            + f". Correct: |L - lambda E| = -lambda^5 + k3 lambda^3 + k1 lambda with k3 = -sum L_ij^2 and k1 = -(sum of the "
              f"squared Pfaffians of the five 4x4 principal minors)" + (" (= -RigidBody.casimirs)" if pk else " [casimirs disagree]"),
            "|L - lambda E| = k1 lambda + k3 lambda^3", "-lambda^5 + k3 lambda^3 + k1 lambda", sec))
    # conservation: Lie-Poisson brackets with every L_a vanish (Casimirs), hence conserved for every inertia
    cas = all(lie_poisson_bracket(k, La, Ls) == 0 for k in (k1, k3) for La in Ls)
    Is = plane_symbols("I", 5, positive=True)
    H = sum(La**2 / (2 * Ia) for La, Ia in zip(Ls, Is))
    H_cas = all(lie_poisson_bracket(H, La, Ls) == 0 for La in Ls)
    out.append(claim("38 (k1, k3 conserved)", sec, cas,
                      "k1 and k3 Poisson-commute with every L_ij (Casimirs of so(5)), so they are conserved for every inertia; "
                      "so are all coefficients of the characteristic polynomial (Sec. 1.3)",
                      "a coefficient is not a Casimir", "k1 and k3 ... are the constants of motion"))
    # meaning: k3 = -|L|^2 (momentum), k1 quartic; energy is not a function of the Casimirs
    deg1 = sp.Poly(k1, *Ls).total_degree()
    deg3 = sp.Poly(k3, *Ls).total_degree()
    k3_is_norm = sp.expand(k3 + sum(x**2 for x in Ls)) == 0
    # the claim: k1 is the (squared) momentum, k3 the energy; the energy depends on the moments, k3 does not
    claim_ok = (deg1 == 2) and bool(k3.free_symbols & set(Is)) and not H_cas
    cl = ps.CLAIMS["38 (meaning of k1, k3)"]
    out.append(claim(
        "38 (k1 momentum, k3 energy)", sec, claim_ok, "",
        f"k3 = -sum L_ij^2 (degree {deg3}{', minus the squared momentum' if k3_is_norm else ''}) is the momentum "
        f"invariant, and k1 is a quartic (degree {deg1}) Casimir, not the momentum. The energy "
        f"H = sum L_ij^2/(2 I_ij) is not a Casimir ({{H, L_ij}} != 0 for generic I, computed), so it is not a function of "
        f"k1, k3: it is a third, independent integral", cl["quote"],
        "k3 = -|L|^2, k1 = -sum Pf(4x4)^2; energy separate"))
    # number of integrals: k1, k3, H independent (rank of their gradients at a random point)
    rng = np.random.default_rng(7)
    pt = {x: sp.Rational(int(v), 7) for x, v in zip(Ls, rng.integers(1, 20, 10))}
    Iv = {x: sp.Rational(int(v), 3) for x, v in zip(Is, rng.integers(2, 30, 10))}
    G = sp.Matrix([[sp.diff(f, x).subs(pt).subs(Iv) for x in Ls] for f in (k1, k3, H)])
    rank = G.rank()
    dH = sp.simplify(lie_poisson_bracket(H, H, Ls))
    cl = ps.CLAIMS["Sec. 6 (integrals)"]
    out.append(claim("Sec. 6 (two integrals)", sec, rank <= cl["count"], "",
                      f"k1, k3 and the energy H (dH/dt = {{H, H}} = {dH}) are {rank} functionally independent integrals "
                      f"(gradient rank {rank} at a random point); for physical moments I_ij = m_i + m_j the flow has even more "
                      f"(Manakov's integrals, RigidBody.manakov_integrals)", cl["quote"]))
    return out
