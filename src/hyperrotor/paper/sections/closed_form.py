r"""Sec. 3 of the preprint: closed-form solutions (82)-(118).

``sec_closed_form`` checks the equal-moment case (82)-(83) (with the regular
5D bodies, :meth:`hyperrotor.Inertia.from_points`, :meth:`hyperrotor.Inertia.ball`);
the quartet body (84)-(85) against :meth:`hyperrotor.Inertia.quartet`, its
Euler equations (86)-(95); the linear system (96)-(99) of the planes through
the distinguished axis, the parameter :math:`\Theta` (100), the exponential
ansatz (101)-(106), the frequency polynomial and its coefficients (107)-(110)
and the frequencies after (118) (numerically against
:func:`hyperrotor.classical.quartet.quartet_frequencies`); and the other
choices of the distinguished axis (111)-(118). The quartet-body derivations
are cached.
"""
from __future__ import annotations

from functools import lru_cache
from typing import Sequence

import numpy as np
import sympy as sp

from hyperrotor.classical.inertia import Inertia
from hyperrotor.classical.rigid_body import RigidBody
from hyperrotor.conventions import planes
from hyperrotor.paper import printed_solutions as ps
from hyperrotor.paper.verdicts import KAPPA, Verdict, claim, compare, eq_zero, fmt_expr, grouped, psym

__all__: list[str] = []  # the checker of this section is package-internal (sections.SECTIONS)

_THETA = psym("Theta")
_C = [psym(f"c_{n}") for n in range(1, 7)]


@lru_cache(maxsize=None)
def quartet_forms(axis: int = 5) -> dict:
    body = RigidBody(Inertia.quartet(KAPPA, axis=axis), convention="paper")
    return {p: eq_zero(eq) for p, eq in zip(body.planes, body.euler_equations(torque=0))}


@lru_cache(maxsize=None)
def quartet_rhs(axis: int = 5) -> dict:
    body = RigidBody(Inertia.quartet(KAPPA, axis=axis), convention="paper")
    w = [psym(f"omega_{i}{j}") for i, j in planes(5)]
    return {p: sp.cancel(sp.expand(r)) for p, r in zip(planes(5), body.symbolic_rhs(w))}


def _kappa_to_theta(expr):
    """Rewrite with Theta = (kappa^2 - 1)/(kappa^2 + 1), i.e. kappa^2 = (1 + Theta)/(1 - Theta)."""
    return sp.factor(sp.cancel(expr.subs(KAPPA**2, (1 + _THETA) / (1 - _THETA))))


@lru_cache(maxsize=None)
def quartet_rhs_theta(axis: int) -> dict:
    """dw/dt of the planes through ``axis`` for the quartet body, written with Theta (a polynomial)."""
    rhs = quartet_rhs(axis)
    return {p: sp.expand(_kappa_to_theta(rhs[p])) for p in planes(5) if axis in p}


def _axis_system(axis: int, consts: Sequence) -> tuple[list, sp.Matrix]:
    """Derived linear system x' = K x of the planes through ``axis`` with the others set to ``consts``."""
    rhs = quartet_rhs_theta(axis)
    through = [p for p in planes(5) if axis in p]
    rest = [p for p in planes(5) if axis not in p]
    sub = {psym(f"omega_{i}{j}"): c for (i, j), c in zip(rest, consts)}
    xs = [psym(f"omega_{i}{j}") for i, j in through]
    K = sp.Matrix([[sp.expand(sp.diff(rhs[p], x).xreplace(sub)) for x in xs] for p in through])
    return through, K


@lru_cache(maxsize=None)
def sec_closed_form() -> tuple:
    sec = "closed-form"
    out = []
    # (82)-(83)
    pl82 = ps.printed("82")
    I0 = sp.Symbol("I_0", positive=True)
    zero_all = {N: all(sp.simplify(r) == 0 for r in RigidBody(Inertia.equal(N, I0)).symbolic_rhs()) for N in range(3, 8)}
    out.append(claim("82", sec, set(pl82) == set(planes(5)) and zero_all[5],
                      "all ten moments equal: RigidBody(Inertia.equal(5)) has dw/dt = 0 identically",
                      f"the chain lists {sorted(set(pl82))}", fmt_expr(pl82)))
    solids = _regular_bodies()
    out.append(claim("82 (Platonic bodies)", sec, all(ok for _, ok in solids),
                      "computed with Inertia.from_points / Inertia.ball: all plane moments equal for "
                      + ", ".join(n for n, _ in solids),
                      "unequal moments for " + ", ".join(n for n, ok in solids if not ok),
                      ps.CLAIMS["82 (Platonic bodies)"]["quote"]))
    pl83 = ps.printed("83")
    dup = sorted({p for p in pl83 if pl83.count(p) > 1})
    miss = sorted(set(planes(5)) - set(pl83))
    if not dup and not miss:
        out.append(Verdict("83", "holds", "lists the ten derivatives", None, None, sec))
    else:
        out.append(Verdict("83", "typo",
                           f"lists dw{dup[0][0]}{dup[0][1]}/dt twice and omits "
                           + ", ".join(f"dw{i}{j}/dt" for i, j in miss)
                           + ". Correct: dw12/dt = dw13/dt = dw14/dt = dw15/dt = dw23/dt = ... = dw45/dt = 0",
                           ", ".join(f"dw{i}{j}" for i, j in pl83), None, sec))
    out.append(claim("83 (all dimensions)", sec, all(zero_all.values()),
                      "computed for N = 3..7: equal moments give dw/dt = 0", "fails for some N",
                      ps.CLAIMS["83 (all dimensions)"]["quote"]))
    # (84)-(85)
    q = Inertia.quartet(KAPPA)
    pr_moments = {**ps.printed("84"), **ps.printed("85")}
    mism = [p for p in planes(5) if p not in pr_moments or sp.simplify(pr_moments[p] - q[p]) != 0]
    J = q.mass_tensor
    out.append(Verdict("84-85", "holds" if not mism else "typo",
                       (f"equal to Inertia.quartet(kappa) (axis 5); physical: I_ij = m_i + m_j with m = {tuple(J)}")
                       if not mism else f"differ at {mism}", None, None, sec))
    # (86)-(95)
    forms = quartet_forms(5)
    consts = {"86": (1, 2), "87": (1, 3), "88": (1, 4), "90": (2, 3), "91": (2, 4), "93": (3, 4)}
    w51 = {psym("omega_51"): psym("omega_15")}
    for k in map(str, range(86, 96)):
        if k in consts:
            d = forms[consts[k]]
            out.append(compare(k, sec, ps.printed(k)["ode"], d, zero_form=True, correct=f"{fmt_expr(d)} = 0"))
            continue
        p = {"89": (1, 5), "92": (2, 5), "94": (3, 5), "95": (4, 5)}[k]
        dot = psym(f"omegadot_{p[0]}{p[1]}")
        d = forms[p]
        ds = sp.expand(d * (1 + KAPPA**2) / d.coeff(dot))
        q = sp.expand(sp.cancel((ds - (1 + KAPPA**2) * dot) / (1 - KAPPA**2)))
        shown = f"(1 + kappa^2)*{fmt_expr(dot)} + (1 - kappa^2)*({grouped(q)}) = 0"

        def flip(e, dot=dot):
            e = sp.expand(e)
            return 2 * e.coeff(dot) * dot - e
        out.append(compare(k, sec, ps.printed(k), d, zero_form=True, correct=shown,
                            corrections=(("the sign of the (1 - kappa^2) term is flipped", flip),
                                         ("w51 is read as +w15 (not -w15 as eq. 1 says)", lambda e: e.xreplace(w51)),
                                         ("the sign of the (1 - kappa^2) term is flipped and w51 is read as +w15",
                                          lambda e, flip=flip: flip(e.xreplace(w51))))))
    # (96)-(99): linear system with constants c1..c6 (planes 12, 13, 14, 23, 24, 34)
    through, K = _axis_system(5, _C)
    xs = [psym(f"omega_{i}{j}") for i, j in through]
    for n, (k, p) in enumerate(zip(("96", "97", "98", "99"), through)):
        d = sp.expand(psym(f"omegadot_{p[0]}{p[1]}") - sum(K[n, m] * xs[m] for m in range(4)))
        out.append(compare(k, sec, ps.printed(k), d, zero_form=True))
    # (100)
    p100 = ps.printed("100")
    theta_der = sp.simplify(K[0, 1] / _C[0]).subs(_THETA, _THETA)  # K is written in Theta already: recover Theta(kappa)
    # Theta as derived from the quartet equations directly in kappa
    rhs = quartet_rhs(5)
    theta_k = sp.simplify(sp.diff(rhs[(1, 5)], psym("omega_25")).subs(psym("omega_12"), 1))
    ok_theta = sp.simplify(p100["Theta"] - theta_k) == 0
    back = sp.simplify(p100["kappa"].subs(_THETA, theta_k))
    del theta_der
    if ok_theta and sp.simplify(back - KAPPA) == 0:
        out.append(Verdict("100 (kappa from Theta)", "holds", "inverse is right", None, None, sec))
    else:
        out.append(Verdict("100 (kappa from Theta)", "typo",
                           f"Theta = (kappa^2 - 1)/(1 + kappa^2) is right (= coefficient in the quartet equations: "
                           f"{fmt_expr(theta_k)}), but the printed inverse gives kappa(Theta(kappa)) = {fmt_expr(back)} for kappa > 0. "
                           f"Correct: kappa = sqrt(1 - Theta^2)/(1 - Theta)",
                           "kappa = sqrt(1 - Theta^2)/(Theta - 1)", "kappa = sqrt(1 - Theta^2)/(1 - Theta)", sec))
    lo, hi = p100["range"]
    at0 = p100["Theta"].subs(KAPPA, 0)
    lim = sp.limit(p100["Theta"], KAPPA, sp.oo)
    attained_lo = at0 == lo
    out.append(claim("100 (range of Theta)", sec, not (p100["strict"] and attained_lo), "",
                      f"Theta(kappa = 0) = {at0} is attained (kappa = 0: I_i5 = 1, a body flat in the 5th direction, m5 = 0), "
                      f"and Theta -> {lim} as kappa -> oo. Correct: -1 <= Theta < 1", "-1 < Theta < 1", "-1 <= Theta < 1"))
    # (101): the exponential ansatz is complete iff K is normal with imaginary spectrum (K = Theta A, A real antisymmetric)
    anti = sp.simplify(K + K.T) == sp.zeros(4, 4)
    out.append(claim("101", sec, anti,
                      "the derived system x' = K x has K = Theta*A with A real antisymmetric (computed K + K^T = 0): K is normal "
                      "with purely imaginary eigenvalues, so real frequencies Omega and the exponential ansatz give every solution",
                      "K is not antisymmetric", "w_k5(t) = C_k5 exp(i Omega t)"))
    # (102)-(105)
    Om = psym("Omega")
    Cs = [psym(f"C_{i}{j}") for i, j in through]
    Mder = sp.I * Om * sp.eye(4) - K
    w2C = {psym(f"omega_{i}{j}"): psym(f"C_{i}{j}") for i, j in through}
    for n, k in enumerate(("102", "103", "104", "105")):
        d = sp.expand(sum(Mder[n, m] * Cs[m] for m in range(4)))
        out.append(compare(k, sec, ps.printed(k), d, zero_form=True,
                            corrections=(("reading w_k5 as the amplitude C_k5", lambda e: e.xreplace(w2C)),)))
    # (106)
    P106 = ps.printed("106")
    bad = [(r, c) for r in range(4) for c in range(4) if sp.expand(P106[r, c] - Mder[r, c]) != 0]
    row103 = sp.expand(sum(P106[1, m] * Cs[m] for m in range(4)) - ps.printed("103"))
    detP = sp.expand(P106.det(method="berkowitz"))
    detD = sp.expand(Mder.det(method="berkowitz"))
    if not bad:
        out.append(Verdict("106", "holds", "equals iOmega*1 - K", None, None, sec))
    else:
        out.append(Verdict("106", "typo",
                           "wrong cells (1-based): " + ", ".join(f"({r + 1},{c + 1}): {fmt_expr(P106[r, c])} -> {fmt_expr(Mder[r, c])}" for r, c in bad)
                           + ("; row 2 also contradicts the printed (103)" if row103 != 0 else "")
                           + ("; with it the determinant is not the (107) polynomial" if sp.expand(detP - detD) != 0 else ""),
                           None, fmt_expr(Mder), sec))
    sym_part = sp.simplify(Mder + Mder.T)
    out.append(claim("106 (antisymmetric)", sec, sym_part == sp.zeros(4, 4), "",
                      f"M + M^T = {fmt_expr(sym_part[0, 0])}*1 != 0: M is not antisymmetric; M - i*Omega*1 = -K = -Theta*A is",
                      ps.CLAIMS["106 (antisymmetric)"]["quote"], "M = i Omega 1 - Theta A, A^T = -A"))
    # (107)-(110)
    poly = sp.Poly(detD, Om)
    coeffs = dict(zip([m[0] for m in poly.monoms()], poly.coeffs()))
    l2d, l0d = sp.factor(coeffs.get(2, 0)), sp.factor(coeffs.get(0, 0))
    form_ok = set(coeffs) <= {0, 2, 4} and coeffs.get(4) == 1
    out.append(claim("107", sec, form_ok, f"det(i Omega 1 - K) = Omega^4 + l2 Omega^2 + l0 (computed)",
                      f"det has powers {sorted(coeffs)}", "|M| = Omega^4 + l2 Omega^2 + l0"))
    p108 = ps.printed("108")
    out.append(compare("108 (l2)", sec, p108["l_2"], sp.expand(l2d)))
    out.append(compare("108 (l0)", sec, p108["l_0"], sp.expand(l0d)))
    cands = [("all c = 0", {c: 0 for c in _C}, {}), ("kappa = 1 (Theta = 0)", {}, {_THETA: 0}),
             ("only c1 = 1", {**{c: 0 for c in _C}, _C[0]: 1}, {})]
    tests = {"<": lambda v: v < 0, "<=": lambda v: v <= 0, ">": lambda v: v > 0, ">=": lambda v: v >= 0}
    for key, name, expr in (("108 (l2 < 0)", "l_2", l2d), ("108 (l0 > 0)", "l_0", l0d)):
        rel = p108[name + " relation"]
        found = [(cn, v) for cn, cs, th in cands for v in [expr.subs(cs).subs(th).subs(_THETA, sp.Rational(1, 2))]
                 if not tests[rel](v)]
        weak = rel[0] + "="
        nonstrict = expr.is_nonpositive if weak == "<=" else expr.is_nonnegative
        short = name.replace("_", "")
        out.append(claim(key, sec, not found and bool(nonstrict),
                          f"{short} {rel} 0 holds (sign decided symbolically)",
                          (f"fails for {found[0][0]} ({short} = {found[0][1]}); only the non-strict {short} {weak} 0 holds "
                           f"(decided symbolically: {'yes' if nonstrict else 'undecided'})") if found else f"{short} {rel} 0 undecided",
                          f"{short} {rel} 0", f"{short} {weak} 0"))
    p109 = ps.printed("109")
    l2s, l0s = psym("l_2"), psym("l_0")
    lhs109 = p109.lhs.subs({l2s: l2d, l0s: l0d})
    out.append(compare("109", sec, p109.rhs, sp.expand(lhs109), note="l2^2 - 4 l0 with the derived l2, l0"))
    p110 = ps.printed("110")["chain"]
    chain = [sp.expand(e.subs({l2s: l2d, l0s: l0d})) for e in p110]
    ce = [("only c1 = 1 (Pfaffian 0)", {**{c: 0 for c in _C}, _C[0]: 1}),
          ("c1 = c6 = 1 (self-dual)", {**{c: 0 for c in _C}, _C[0]: 1, _C[5]: 1})]
    fails = []
    rel110 = ps.printed("110")["relation"]
    for name, cs in ce:
        vals = [e.subs(cs).subs(_THETA, sp.Rational(1, 2)) for e in chain]
        for a, b in zip(vals, vals[1:]):
            if not (a > b if rel110 == ">" else a >= b):
                fails.append(f"{name}: {a} {rel110} {b} is false")
    nonneg = p109.rhs
    out.append(claim("110", sec, not fails, "",
                      "; ".join(fails) + f". Correct: l2^2 >= l2^2 - 4 l0 >= 0 (l2^2 - 4 l0 = {fmt_expr(nonneg)} by (109), a product of sums of squares); "
                      "equality in the second means two equal frequencies", "l2^2 > l2^2 - 4 l0 > 0", "l2^2 >= l2^2 - 4 l0 >= 0"))
    # frequencies after (118)
    freqs = ps.printed("after 118")
    roots_ok = all(sp.simplify(sp.expand(f**4 + l2s * f**2 + l0s)) == 0 for f in freqs)
    num_ok = _frequencies_numeric(freqs)
    out.append(claim("after 118 (frequencies)", sec, roots_ok and num_ok,
                      "each printed Omega solves Omega^4 + l2 Omega^2 + l0 = 0 (exact), and numerically they are +-Omega_1, +-Omega_2 of "
                      "quartet.quartet_frequencies and the eigenvalues of the derived K; real because l2 <= 0 <= l0 and "
                      "l2^2 - 4 l0 >= 0 (quasi-periodic motion)", "a printed root does not solve (107)",
                      "Omega = +-1/2 sqrt(+-2 sqrt(l2^2 - 4 l0) - 2 l2)"))
    # (111)-(118)
    for k, kc in zip(("111", "112", "113", "114"), ("115", "116", "117", "118")):
        sets = ps.printed(k)
        kap = sets["1 + kappa^2"]
        axis_set = set.intersection(*[set(p) for p in kap])
        ok = len(axis_set) == 1
        axis = next(iter(axis_set)) if ok else None
        if ok:
            qa = Inertia.quartet(KAPPA, axis=axis)
            ok = (set(kap) | set(sets["2"]) == set(planes(5)) and not set(kap) & set(sets["2"])
                  and all(sp.simplify(qa[p] - (1 + KAPPA**2)) == 0 for p in kap) and all(qa[p] == 2 for p in sets["2"]))
        out.append(claim(k, sec, ok, f"= Inertia.quartet(kappa, axis={axis}): the distinguished axis is {axis}",
                          f"the two sets do not form a quartet body ({sets})", None))
        # constants and characteristic polynomial for that axis
        rhs = quartet_rhs(axis)
        const = {p for p in planes(5) if rhs[p] == 0}
        pc = ps.printed(kc)
        same = set(pc) == const
        _, Ka = _axis_system(axis, [psym(f"omega_{i}{j}") for i, j in pc] and _C)
        # constants named c1..c6 in the printed order
        thr = [p for p in planes(5) if axis in p]
        rest = [p for p in planes(5) if axis not in p]
        order = [rest.index(p) for p in pc] if same else list(range(6))
        cs = [None] * 6
        for n, idx in enumerate(order):
            cs[idx] = _C[n]
        _, Ka = _axis_system(axis, cs)
        cp = sp.expand((sp.I * Om * sp.eye(4) - Ka).det(method="berkowitz"))
        cp_ok = sp.expand(cp - (Om**4 + p108["l_2"] * Om**2 + p108["l_0"])) == 0
        del thr
        out.append(claim(kc, sec, same and cp_ok,
                          f"the constant components of the axis-{axis} body are exactly {sorted(const)} (derived dw/dt = 0), "
                          f"and with them as c1..c6 the frequency polynomial is again (107)-(108)",
                          f"derived constants {sorted(const)}, printed {list(pc)}; polynomial matches: {cp_ok}", fmt_expr(pc)))
    return tuple(out)


def _regular_bodies() -> list:
    out = []
    N = 5
    cube = np.array(np.meshgrid(*[[-1.0, 1.0]] * N)).reshape(N, -1).T
    orthoplex = np.vstack([np.eye(N), -np.eye(N)])
    simplex = np.eye(N + 1) - 1.0 / (N + 1)  # 6 points in 6D spanning a 5D hyperplane
    Q, _ = np.linalg.qr(np.vstack([np.ones(N + 1), np.eye(N + 1)[:-1]]).T)
    simplex5 = simplex @ Q[:, 1:]
    for name, pts in (("the 5-cube", cube), ("the 5-orthoplex", orthoplex), ("the 5-simplex", simplex5)):
        mom = Inertia.from_points(np.ones(len(pts)), pts).moments
        out.append((f"{name} (vertices)", bool(np.ptp(mom) <= 1e-12 * np.max(mom))))
    ball = Inertia.ball(5, 1.0, 1.0).symbolic_moments
    out.append(("the 5-ball", len(set(ball)) == 1))
    return out


def _frequencies_numeric(freqs) -> bool:
    from hyperrotor.classical.quartet import quartet_frequencies, quartet_polynomial_coefficients

    rng = np.random.default_rng(3)
    ok = True
    for _ in range(3):
        kappa = float(rng.uniform(0.2, 3.0))
        w0 = rng.normal(size=10)
        l2, l0 = quartet_polynomial_coefficients(kappa, w0)
        vals = sorted(abs(complex(f.subs({psym("l_2"): l2, psym("l_0"): l0}).evalf())) for f in freqs)
        ref = sorted(list(quartet_frequencies(kappa, w0)) * 2)
        ok &= bool(np.allclose(vals, ref, rtol=1e-10, atol=1e-12))
    return ok
