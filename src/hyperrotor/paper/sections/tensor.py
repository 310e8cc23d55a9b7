r"""Sec. 1 of the preprint: inertia tensor, angular momentum and energy (eqs. 3-6, 26-27).

``sec_tensor`` checks the printed inertia tensor :math:`I^{ijkl}` (eq. 3) for
its printed symmetries on a general second-moment matrix and against
:meth:`hyperrotor.Inertia.tensor` in principal axes; the angular momentum
(eqs. 4-5) against :math:`\int x \wedge v\,dm = MW + WM`; the kinetic energy
(eq. 6) against :math:`\tfrac12\int|v|^2 dm` and
:meth:`hyperrotor.RigidBody.energy`; and the checkerboard matrices of
:math:`L` and :math:`\dot L` (eqs. 26-27) against eq. (4).
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
import sympy as sp

from hyperrotor.classical.inertia import Inertia
from hyperrotor.classical.rigid_body import RigidBody
from hyperrotor.conventions import plane_symbols, planes, to_matrix
from hyperrotor.paper import printed_solutions as ps
from hyperrotor.paper.verdicts import Verdict, fmt_expr, psym

__all__: list[str] = []  # the checker of this section is package-internal (sections.SECTIONS)


@lru_cache(maxsize=None)
def sec_tensor() -> tuple:
    sec = "tensor"
    out = []
    N = 5
    M = sp.Matrix(N, N, lambda a, b: sp.Symbol(f"M_{min(a, b) + 1}{max(a, b) + 1}", real=True))
    info3 = ps.printed("3")
    tensor = info3["tensor"]
    T = {}
    for idx in np.ndindex(N, N, N, N):
        T[idx] = tensor(M, *idx)
    # eq. (3): the printed symmetries, for a general (non-principal) second-moment matrix
    failed = []
    for name, perm, sign in info3["symmetries"]:
        if any(sp.expand(T[idx] - sign * T[tuple(idx[p] for p in perm)]) != 0 for idx in T):
            failed.append(name)
    cname, cperms = info3["cyclic"]
    if any(sp.expand(sum(T[tuple(idx[p] for p in perm)] for perm in cperms)) != 0 for idx in T):
        failed.append(cname)
    # principal axes: compare with the package's tensor (I^{ijij} = I_ij / 2, I_ij = m_i + m_j)
    m = sp.symbols("m1:6", nonnegative=True)
    Md = sp.diag(*m)
    pkg = Inertia.from_mass_tensor(list(m)).tensor()
    mism = [idx for idx in np.ndindex(N, N, N, N) if sp.expand(tensor(Md, *idx) - pkg[idx]) != 0]
    if failed or mism:
        out.append(Verdict("3", "typo", f"violated: {failed}; differs from Inertia.tensor() at {mism[:4]}", None, None, sec))
    else:
        out.append(Verdict("3", "holds",
                           "the printed tensor has all printed symmetries (incl. the cyclic identity) for a general "
                           "second-moment matrix M = int r r^T dm, and in principal axes equals Inertia.tensor(): "
                           "I^{ijij} = (m_i + m_j)/2 = I_ij/2", "I^{ijkl} = 1/2 int(-r^i d^jk r^l + ...) dm",
                           "I^{ijkl} = 1/2(-d_jk M_il + d_jl M_ik + d_ik M_jl - d_il M_jk)", sec))
    # eq. (4): L^{ij} = I^{ijkl} w_kl (full summation) vs L = int x ^ v dm with v = -W x (body frame, dT/dt = W T)
    wsym = plane_symbols("omega", N, real=True)
    W = to_matrix(list(wsym), convention="standard")
    L_phys = M * W + W * M
    Lfun = ps.printed("4")["L"]
    L4 = sp.Matrix(N, N, lambda i, j: sp.expand(Lfun(lambda a, b, c, d: T[(a, b, c, d)], W.tolist(), i, j, N)))
    ok4 = sp.expand(L4 - L_phys) == sp.zeros(N, N)
    out.append(Verdict("4", "holds" if ok4 else "typo",
                       ("with full summation, I^{ijkl} w_kl equals the physical angular momentum "
                        "int (x_i v_j - x_j v_i) dm = (M W + W M)_ij for a general M; in principal axes "
                        "L^ij = 2 I^{ijij} w_ij = (m_i + m_j) w_ij = I_ij w_ij")
                       if ok4 else f"differs from int x^v dm: {fmt_expr(sp.expand(L4 - L_phys)[0, 1])}",
                       "L^ij = I^{ijkl} w_kl", "L = M W + W M", sec))
    ok5 = sp.expand(L4 + L4.T) == sp.zeros(N, N)
    out.append(Verdict("5", "holds" if ok5 else "typo",
                       "L^ij from eq. (4) is antisymmetric for every M (computed L + L^T = 0)" if ok5
                       else "L^ij + L^ji != 0", "L^ij = -L^ji", None, sec))
    # eq. (6): printed W = 1/2 w_ij I^{ijkl} w_kl (full summation) vs T = 1/2 int |v|^2 dm = 1/2 tr(W M W^T)
    W6 = sp.expand(ps.printed("6")["W"](lambda a, b, c, d: T[(a, b, c, d)], W.tolist(), N))
    T_phys = sp.expand(sp.Rational(1, 2) * (W * M * W.T).trace())
    ratio = sp.simplify(W6 / T_phys)
    body = RigidBody(Inertia.from_mass_tensor(list(m)))
    T_pkg = sp.expand(body.energy(list(wsym)))
    T_phys_d = sp.expand(T_phys.subs({M[a, b]: Md[a, b] for a in range(N) for b in range(N)}))
    pkg_ok = sp.expand(T_pkg - T_phys_d) == 0
    if ratio == 1:
        out.append(Verdict("6", "holds", "equals 1/2 int |v|^2 dm", None, None, sec))
    else:
        out.append(Verdict(
            "6", "typo",
            f"with the full summation the printed W equals {fmt_expr(ratio)} x the kinetic energy 1/2 int |v|^2 dm "
            f"(computed for a general M; the double sum counts every plane twice). Correct: W = 1/4 w_ij I^{{ijkl}} w_kl "
            f"= 1/2 sum_(i<j) I_ij w_ij^2" + (" (= RigidBody.energy)" if pkg_ok else " [RigidBody.energy disagrees!]"),
            "W = 1/2 w_ij I^{ijkl} w_kl", "W = 1/4 w_ij I^{ijkl} w_kl = 1/2 sum_(i<j) I_ij w_ij^2", sec))
    # eqs. (26)-(27): matrix of L with entries I^{ijij} w_ij (paper checkerboard)
    half = {psym(f"I_{i}{j}"): (m[i - 1] + m[j - 1]) / 2 for i, j in planes(N)}  # I^{ijij} of eq. (3)
    Lcomp = [sp.expand(L4[i - 1, j - 1].subs({M[a, b]: Md[a, b] for a in range(N) for b in range(N)})) for i, j in planes(N)]
    L_paper = to_matrix(Lcomp, convention="paper")
    for key, dot in (("26", False), ("27", True)):
        P = ps.printed(key).xreplace(half)
        if dot:
            P = P.xreplace({psym(f"omegadot_{i}{j}"): psym(f"omega_{i}{j}") for i, j in planes(N)})
        P = P.xreplace({psym(f"omega_{i}{j}"): w for (i, j), w in zip(planes(N), wsym)})
        cells = [(r, c) for r in range(N) for c in range(N) if sp.expand(P[r, c] - L_paper[r, c]) != 0]
        factors = {sp.simplify(L_paper[r, c] / P[r, c]) for r, c in cells}
        if not cells:
            out.append(Verdict(key, "holds", "equals the eq.-(4) angular momentum in the paper convention", None, None, sec))
        else:
            what = "L" if not dot else "dL/dt"
            out.append(Verdict(
                key, "typo",
                f"with I^{{ijij}} of eq. (3) every off-diagonal entry is off by the factor {sorted(map(str, factors))}: "
                f"eq. (4) gives {what}^ij = 2 I^{{ijij}} {'dw' if dot else 'w'}_ij = I_ij {'dw' if dot else 'w'}_ij "
                f"({'checkerboard signs are right' if factors == {2} else 'signs differ too'}). Harmless for the torque-free eqs. (28)-(37), which are homogeneous "
                f"in the moments, but it doubles the torque term",
                f"{what}[1,2] = -I^{{1212}} {'dw12/dt' if dot else 'w12'}", f"{what}[1,2] = -2 I^{{1212}} {'dw12/dt' if dot else 'w12'} = -I_12 {'dw12/dt' if dot else 'w12'}", sec))
    return tuple(out)
