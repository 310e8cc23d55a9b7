r"""Equation-by-equation verification of the preprint with hyperrotor's own machinery.

:func:`verify` compares every printed equation and claim of the paper (the
transcriptions :mod:`hyperrotor.paper.printed` and
:mod:`hyperrotor.paper.printed_solutions`, typos included) with the package's
derivation (:class:`hyperrotor.RigidBody`, :class:`hyperrotor.Inertia`,
:mod:`hyperrotor.conventions`, :mod:`hyperrotor.classical.closed_form`,
:mod:`hyperrotor.classical.stability`, :mod:`hyperrotor.quantum.operators`)
and returns one :class:`Verdict` per equation or claim. **No verdict is typed
in**: each status follows from a comparison made at run time,

* ``"holds"``: printed minus derived simplifies to zero (for ``... = 0``
  equations: up to a non-zero constant factor), or a claim survives its check;
* ``"typo"``: the printed object differs from the derived one (the detail
  names the differing terms/cells and gives the corrected form);
* ``"claim-false"``: a stated property, count or inequality fails on a
  computed counterexample (the detail gives the correct statement);
* ``"not-checkable"``: the printed text has no testable content (a pure
  definition of notation) or is garbled beyond a unique reading (tested: the
  literal reading is not even homogeneous in the moments).

Conventions used in the comparisons
-----------------------------------
* Printed :math:`I^{ijij}` is read as the plane moment :math:`I_{ij}`
  (``Symbol("I_ij", positive=True)``) as in :mod:`hyperrotor.paper.printed`;
  the factor 2 between the two is itself checked (eqs. 4, 6, 26, 27).
* Printed equations are compared in the paper's matrix-entry form
  :math:`(-1)^{i+j}(I_{ij}\dot\omega_{ij} - \mathrm{rhs}_{ij}) = \tilde m^{ij}`
  (:meth:`hyperrotor.RigidBody.euler_equations`).
* Components with reversed indices (:math:`\omega_{51}`, :math:`\omega^{31}`,
  :math:`L^{21}`) are read by antisymmetry (eq. 1): :math:`\omega_{ji} = -\omega_{ij}`.

Rendering
---------
:func:`render` turns verdicts into a terminal table (``"table"``), Markdown
(``"markdown"``, the page ``docs/verification.md``) or JSON (``"json"``: a
list of objects with ``equation``, ``status``, ``detail``, ``printed``,
``correct``, ``section``). :func:`main_verify` is the command-line entry
behind ``hyperrotor verify [--json | --markdown] [--section NAME ...]``.
"""
from __future__ import annotations

import argparse
import json
import re
import textwrap
from dataclasses import asdict, dataclass
from functools import lru_cache
from itertools import combinations
from typing import Callable, Iterable, Sequence

import numpy as np
import sympy as sp

from hyperrotor.conventions import (
    lie_bracket,
    lie_poisson_bracket,
    plane_index,
    plane_symbols,
    planes,
    structure_constants,
    to_matrix,
)
from hyperrotor.classical.inertia import Inertia
from hyperrotor.classical.rigid_body import RigidBody
from hyperrotor.paper import printed_solutions as ps

__all__ = [
    "Verdict",
    "STATUSES",
    "SECTIONS",
    "verify",
    "render",
    "render_table",
    "render_markdown",
    "render_json",
    "main_verify",
    "clear_cache",
    "summary",
]

#: The allowed verdict statuses.
STATUSES = ("holds", "typo", "claim-false", "not-checkable")


@dataclass(frozen=True)
class Verdict:
    """The outcome of checking one printed equation or claim.

    Attributes
    ----------
    equation : str
        The paper's equation number (``"92"``), possibly with a qualifier
        (``"108 (l2 < 0)"``, ``"25 [12]"``), or a section/table name
        (``"Table 2"``, ``"Sec. 2.5 heading"``).
    status : {"holds", "typo", "claim-false", "not-checkable"}
    detail : str
        The corrected form or statement, or why the item is not checkable.
    printed : str or None
        The printed form (as transcribed), when short enough to show.
    correct : str or None
        The derived (correct) form.
    section : str
        Key of :data:`SECTIONS` the item belongs to.
    """

    equation: str
    status: str
    detail: str
    printed: str | None = None
    correct: str | None = None
    section: str = ""

    def __post_init__(self):
        if self.status not in STATUSES:
            raise ValueError(f"unknown status {self.status!r}; allowed: {', '.join(STATUSES)}")

    def to_dict(self) -> dict:
        """JSON-ready dict with the keys ``equation, status, detail, printed, correct, section``."""
        return asdict(self)


# ----------------------------------------------------------------------------
# formatting and comparison helpers
# ----------------------------------------------------------------------------
_S = ps.symbol


def _fmt(expr) -> str:
    """Compact, readable text of a SymPy object (w12 for omega_12, w12' for its derivative, ...)."""
    s = sp.sstr(expr)
    for pat, rep in (
        (r"omegadot_(\d\d)", r"w\1'"), (r"omega_(\d\d)", r"w\1"), (r"mtilde_(\d\d)", r"m~\1"),
        (r"varpidot_(\d+)", r"varpi\1'"), (r"\bI_(\d\d)", r"I\1"), (r"\bL_(\d\d)", r"L\1"),
        (r"\bJ_(\d+)", r"J\1"), (r"\bc_(\d)", r"c\1"), (r"\bC_(\d+)", r"C\1"), (r"\bl_(\d)", r"l\1"),
    ):
        s = re.sub(pat, rep, s)
    return s


def _plain(expr):
    """Replace ``omega_ij(t)`` and its time derivative by the plain symbols ``omega_ij`` / ``omegadot_ij``."""
    expr = sp.sympify(expr)
    reps = {}
    for d in expr.atoms(sp.Derivative):
        reps[d] = _S("omegadot_" + d.expr.func.__name__.split("_")[1])
    expr = expr.xreplace(reps)
    reps = {f: _S(f.func.__name__) for f in expr.atoms(sp.core.function.AppliedUndef)}
    return expr.xreplace(reps)


def _eq_zero(eq) -> sp.Expr:
    """``lhs - rhs`` of an ``Eq`` with plain symbols, expanded."""
    return sp.expand(_plain(eq.lhs) - _plain(eq.rhs))


def _antisym(expr):
    """Read reversed-index components by antisymmetry: ``omega_ji -> -omega_ij`` (also ``L``, ``Omega``)."""
    reps = {}
    for s in expr.free_symbols:
        m = re.fullmatch(r"(omega|L|Omega|OmegaOp|LOp)_(\d)(\d)", s.name)
        if m and int(m.group(2)) > int(m.group(3)):
            reps[s] = -_S(f"{m.group(1)}_{m.group(3)}{m.group(2)}")
    return expr.xreplace(reps)


def _terms(expr) -> dict:
    """Monomial -> coefficient of an expanded polynomial expression."""
    return sp.expand(expr).as_coefficients_dict()


def _term_diff(printed, derived) -> tuple[list, list]:
    """Terms of ``printed`` not in ``derived`` (``extra``) and of ``derived`` not in ``printed`` (``missing``)."""
    p, d = _terms(printed), _terms(derived)
    extra = [c * m for m, c in p.items() if sp.simplify(c - d.get(m, 0)) != 0]
    missing = [c * m for m, c in d.items() if sp.simplify(c - p.get(m, 0)) != 0]
    return extra, missing


_DYN = re.compile(r"^(omega|omegadot|varpi|varpidot|L|C|LOp|OmegaOp)_\d+$")


def _grouped(expr) -> str:
    """Text of ``expr`` grouped by the monomials of the dynamical variables, coefficients factored."""
    expr = sp.expand(expr)
    gens = sorted((s for s in expr.free_symbols if _DYN.match(s.name)), key=lambda s: s.name)
    if not gens or expr == 0:
        return _fmt(expr)
    text = ""
    for mono, coef in sp.Poly(expr, *gens).terms():
        m = _fmt(sp.Mul(*[g**e for g, e in zip(gens, mono)]))
        c = sp.factor(coef)
        if coef.free_symbols == {_KAPPA}:
            k2 = sp.Dummy("k2")
            c = sp.factor(sp.expand(coef).subs(_KAPPA**2, k2)).subs(k2, _KAPPA**2)
        neg = c.could_extract_minus_sign()
        if neg:
            c = -c
        if c == 1:
            body = m
        elif c.is_Atom or (c.is_Mul and all(a.is_Atom or a.is_Pow for a in c.args)):
            body = f"{_fmt(c)}*{m}"
        else:
            body = f"({_fmt(c)})*{m}"
        text += (" - " if neg else " + ") + body if text else ("-" if neg else "") + body
    return text


def _diff_text(extra: list, missing: list) -> str:
    parts = []
    if extra:
        parts.append("printed has " + _grouped(sp.Add(*extra)))
    if missing:
        parts.append("derived has " + _grouped(sp.Add(*missing)))
    return "; ".join(parts)


def _proportional(printed, derived):
    """The constant ``c != 0`` with ``printed == c * derived`` (exactly), else ``None``."""
    printed, derived = sp.expand(printed), sp.expand(derived)
    if derived == 0:
        return None
    dterms = _terms(derived)
    mono, coef = next(iter(dterms.items()))
    c = sp.simplify(_terms(printed).get(mono, 0) / coef)
    if c == 0:
        return None
    return c if sp.expand(printed - c * derived) == 0 else None


def _scale_like(p, d):
    """Scale ``d`` so that its derivative term (or first common term) has the printed coefficient."""
    pp, dd = _terms(p), _terms(d)
    common = [m for m in pp if m in dd]
    dots = [m for m in common if any("dot" in s.name for s in m.free_symbols)]
    ref = (dots or common or [None])[0]
    if ref is None:
        return d
    return sp.expand(sp.simplify(pp[ref] / dd[ref]) * d)


def _mismatch(p, d, zero_form):
    """(extra, missing) terms of printed ``p`` against derived ``d`` (scaled when ``zero_form``)."""
    return _term_diff(p, _scale_like(p, d) if zero_form else d)


def _agrees(p, d, zero_form) -> bool:
    return sp.expand(p - d) == 0 or (zero_form and _proportional(p, d) is not None)


def _compare(key, section, printed, derived, *, zero_form=False, correct=None, note="", corrections=()):
    """Verdict from comparing a printed expression with the derived one.

    ``zero_form``: both stand for ``expr = 0``, so equality up to a non-zero
    constant factor counts. ``corrections``: ``(description, function)`` pairs
    that transform the printed expression (e.g. a notation reading); if one
    makes it agree, or removes some of the differences, the detail says so (the
    status stays ``"typo"``).
    """
    p = _antisym(sp.expand(printed))
    d = sp.expand(derived)
    shown_correct = correct if correct is not None else (_grouped(_scale_like(p, d) if zero_form else d)
                                                         + (" = 0" if zero_form else ""))
    if _agrees(p, d, zero_form):
        return Verdict(key, "holds", ("agrees with the derived form" + (f" ({note})" if note else "")),
                       _grouped(printed), shown_correct, section)
    extra, missing = _mismatch(p, d, zero_form)
    detail = _diff_text(extra, missing)
    best = None
    for desc, fn in corrections:
        q = sp.expand(_antisym(fn(printed)))
        if _agrees(q, d, zero_form):
            best = (desc, [], [])
            break
        e2, m2 = _mismatch(q, d, zero_form)
        if len(e2) + len(m2) < len(extra) + len(missing) and (best is None or len(e2) + len(m2) < len(best[1]) + len(best[2])):
            best = (desc, e2, m2)
    if best is not None:
        if not best[1] and not best[2]:
            detail += f"; agrees when {best[0]}"
        else:
            detail += f"; even when {best[0]}, {_diff_text(best[1], best[2])}"
    if note:
        detail += f" ({note})"
    return Verdict(key, "typo", detail + f". Correct: {shown_correct}", _grouped(printed), shown_correct, section)


def _claim(key, section, ok: bool, detail_true: str, detail_false: str, printed=None, correct=None):
    return Verdict(key, "holds" if ok else "claim-false", detail_true if ok else detail_false, printed, correct, section)


# ----------------------------------------------------------------------------
# derived objects (cached)
# ----------------------------------------------------------------------------
@lru_cache(maxsize=None)
def _body5() -> RigidBody:
    return RigidBody(Inertia.symbolic(5), "paper")


@lru_cache(maxsize=None)
def _euler_entry_forms(locked: tuple = ()) -> dict:
    """Plane -> expanded ``lhs - rhs`` of the (locked) body's Euler equations, paper matrix-entry form."""
    body = _body5().lock(locked) if locked else _body5()
    return {p: _eq_zero(eq) for p, eq in zip(body.planes, body.euler_equations())}


def _eq_str(zero_expr, rhs_symbol=None) -> str:
    """``lhs = rhs`` text from ``lhs - rhs`` (moving a torque symbol to the right)."""
    if rhs_symbol is not None:
        return f"{_grouped(zero_expr + rhs_symbol)} = {_fmt(rhs_symbol)}"
    return f"{_grouped(zero_expr)} = 0"


def _mtilde(p):
    return sp.Symbol(f"mtilde_{p[0]}{p[1]}")


# ============================================================================
# Sec. 1: tensor definitions (eqs. 3-6, 26-27)
# ============================================================================
@lru_cache(maxsize=None)
def _sec_tensor() -> tuple:
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
    W = to_matrix(list(wsym), "standard")
    L_phys = M * W + W * M
    Lfun = ps.printed("4")["L"]
    L4 = sp.Matrix(N, N, lambda i, j: sp.expand(Lfun(lambda a, b, c, d: T[(a, b, c, d)], W.tolist(), i, j, N)))
    ok4 = sp.expand(L4 - L_phys) == sp.zeros(N, N)
    out.append(Verdict("4", "holds" if ok4 else "typo",
                       ("with full summation, I^{ijkl} w_kl equals the physical angular momentum "
                        "int (x_i v_j - x_j v_i) dm = (M W + W M)_ij for a general M; in principal axes "
                        "L^ij = 2 I^{ijij} w_ij = (m_i + m_j) w_ij = I_ij w_ij")
                       if ok4 else f"differs from int x^v dm: {_fmt(sp.expand(L4 - L_phys)[0, 1])}",
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
            f"with the full summation the printed W equals {_fmt(ratio)} x the kinetic energy 1/2 int |v|^2 dm "
            f"(computed for a general M; the double sum counts every plane twice). Correct: W = 1/4 w_ij I^{{ijkl}} w_kl "
            f"= 1/2 sum_(i<j) I_ij w_ij^2" + (" (= RigidBody.energy)" if pkg_ok else " [RigidBody.energy disagrees!]"),
            "W = 1/2 w_ij I^{ijkl} w_kl", "W = 1/4 w_ij I^{ijkl} w_kl = 1/2 sum_(i<j) I_ij w_ij^2", sec))
    # eqs. (26)-(27): matrix of L with entries I^{ijij} w_ij (paper checkerboard)
    half = {_S(f"I_{i}{j}"): (m[i - 1] + m[j - 1]) / 2 for i, j in planes(N)}  # I^{ijij} of eq. (3)
    Lcomp = [sp.expand(L4[i - 1, j - 1].subs({M[a, b]: Md[a, b] for a in range(N) for b in range(N)})) for i, j in planes(N)]
    L_paper = to_matrix(Lcomp, "paper")
    for key, dot in (("26", False), ("27", True)):
        P = ps.printed(key).xreplace(half)
        if dot:
            P = P.xreplace({_S(f"omegadot_{i}{j}"): _S(f"omega_{i}{j}") for i, j in planes(N)})
        P = P.xreplace({_S(f"omega_{i}{j}"): w for (i, j), w in zip(planes(N), wsym)})
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


# ============================================================================
# Sec. 2.1: eq. (25), Tables 1-2, Euler equations (28)-(37), eq. (38)
# ============================================================================
def _entry_product(Lsyms, Wsyms) -> dict:
    """Plane -> (i, j) entry of W L - L W (paper matrices), generic components (eqs. 24-25)."""
    Lm = to_matrix(list(Lsyms), "paper")
    Wm = to_matrix(list(Wsyms), "paper")
    P = Wm * Lm - Lm * Wm
    return {(i, j): sp.expand(P[i - 1, j - 1]) for i, j in planes(5)}


def _printed_product(lines: dict, Lname: str, Wname: str) -> dict:
    return {p: sp.Add(*[s * _S(f"{Lname}_{a}") * _S(f"{Wname}_{b}") for s, a, b in terms]) for p, terms in lines.items()}


def _product_verdicts(key: str, sec: str, Lname: str, Wname: str) -> list:
    Ls = [_S(f"{Lname}_{i}{j}") for i, j in planes(5)]
    Ws = [_S(f"{Wname}_{i}{j}") for i, j in planes(5)]
    derived = _entry_product(Ls, Ws)
    comp = dict(zip(planes(5), lie_bracket(Ws, Ls)))
    printed = _printed_product(ps.printed(key), Lname, Wname)
    out = []
    for p in planes(5):
        pr = _antisym(printed[p])
        v = _compare(f"{key} [{p[0]}{p[1]}]", sec, printed[p], derived[p],
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
            reps[s] = _S(f"{m.group(1)}_{m.group(3)}{m.group(2)}")
    return expr.xreplace(reps)


_COMM = "the commutator table [e_a, e_b] (bivector_product_table)"


def _table_candidates(sym: str) -> dict:
    """Derived tables: the commutator table (``bivector_product_table``) and its sign variants."""
    from hyperrotor.conventions import bivector_product_table

    A = bivector_product_table(5, "paper", symbol=sym)
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
    cells = ", ".join(f"({_label(a)},{_label(b)}): {_fmt(P[a, b])} -> {_fmt(D[a, b])}" for a, b in bad)
    others = "; ".join(f"{n}: {k}" for k, n, _, _ in scored[1:])
    return Verdict(key, "typo",
                   f"no sign convention reproduces the printed table; closest derived table: {name}, with {nbad} wrong cells "
                   f"(row,col: printed -> correct): {cells}. Wrong cells against the other conventions: {others}",
                   None, None, sec), name, D


@lru_cache(maxsize=None)
def _sec_euler() -> tuple:
    from hyperrotor.paper import printed as pr

    sec = "euler"
    out = []
    # eq. (25)
    out += _product_verdicts("25", sec, "L", "omega")
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
         + ", ".join(f"({_label(a)},{_label(b)})={_fmt(T2[a, b])} vs ({_label(b)},{_label(a)})={_fmt(T2[b, a])}" for a, b in asym)),
        ps.CLAIMS["Table 2 (antisymmetric)"]["quote"], None, sec))
    # disjoint planes give zero products
    disjoint = [(a, b) for a, p in enumerate(planes(5)) for b, q in enumerate(planes(5)) if not set(p) & set(q)]
    der_zero = all(comm[a, b] == 0 for a, b in disjoint)
    pr_zero = all(T2[a, b] == 0 for a, b in disjoint)
    out.append(_claim("Table 2 (disjoint planes)", sec, der_zero and pr_zero,
                      f"computed: [e_ij, e_kl] = 0 for all {len(disjoint)} ordered pairs of disjoint planes, and the printed table has 0 there",
                      "a product of disjoint planes is non-zero", ps.CLAIMS["Table 2 (disjoint planes)"]["quote"]))
    e_to_L = {s: _S("L_" + s.name.split("_")[1]) for s in T2.free_symbols | D2.free_symbols}
    derived_same = sp.expand(D2.xreplace(e_to_L) - D1) == sp.zeros(10, 10)
    diff = [(a, b) for a in range(10) for b in range(10) if sp.expand(T2.xreplace(e_to_L)[a, b] - T1[a, b]) != 0]
    out.append(_claim("Tables 1-2 (same signs)", sec, not diff,
                      "the printed tables agree cell by cell (e -> L)",
                      "the printed tables differ in " + str(len(diff)) + " cells: "
                      + ", ".join(f"({_label(a)},{_label(b)}) T1={_fmt(T1[a, b])} T2={_fmt(T2[a, b])}" for a, b in diff)
                      + (" (the derived tables do coincide, e -> L)" if derived_same else " (the derived tables differ too)"),
                      ps.CLAIMS["Tables 1-2 (same signs)"]["quote"]))
    # Euler equations (28)-(37)
    ref = _euler_entry_forms()
    for k, eq in pr.PRINTED_EULER.items():
        p = pr.equation_plane(eq)
        d = ref[p]
        out.append(_compare(k, sec, _eq_zero(eq), d, correct=_eq_str(d, _mtilde(p)),
                            note="matrix entry (i,j) of dL/dt - (wL - Lw) = m~, RigidBody.euler_equations()"))
    # order / number of equations
    eqs = _body5().euler_equations()
    order = max(d.derivative_count for e in eqs for d in e.lhs.atoms(sp.Derivative))
    cl = ps.CLAIMS["Sec. 2.1 (order)"]
    out.append(_claim("Sec. 2.1 (order of the equations)", sec, order == cl["order"] and len(eqs) == cl["count"],
                      "", f"the {len(eqs)} Euler equations are of order {order} in the angular velocities "
                          f"(first-order ODEs), not {cl['order']}", cl["quote"]))
    n3 = len(list(combinations(range(1, 6), 3)))
    three_d = all(len(_body5().lock(tuple(a for a in range(1, 6) if a not in keep)).planes) == 3
                  for keep in combinations(range(1, 6), 3))
    cl = ps.CLAIMS["Sec. 2.1 (3D cases)"]
    out.append(_claim("Sec. 2.1 (number of 3D cases)", sec, n3 == cl["count"] and three_d, "",
                      f"5D has C(5,3) = {n3} three-dimensional coordinate subspaces (each reduction RigidBody.lock gives "
                      f"3 Euler equations), not {cl['count']}", cl["quote"]))
    out += _eq38(sec)
    return tuple(out)


def _eq38(sec: str) -> list:
    out = []
    Ls = plane_symbols("L", 5, real=True)
    lam = ps.printed("38")["lambda"]
    Lp = to_matrix(list(Ls), "paper")
    charpoly = sp.Poly(sp.expand((Lp - lam * sp.eye(5)).det(method="berkowitz")), lam)
    rhs = sp.Poly(ps.printed("38")["rhs"], lam)
    dpows = {m[0]: c for m, c in zip(charpoly.monoms(), charpoly.coeffs())}
    ppows = {m[0] for m in rhs.monoms()}
    k3 = dpows.get(3, 0)
    k1 = dpows.get(1, 0)
    # package Casimirs: det(lam - L) = lam^5 + c2 lam^3 + c4 lam
    c2, c4 = _body5().casimirs(list(Ls), of="L")
    pk = sp.expand(k3 + c2) == 0 and sp.expand(k1 + c4) == 0
    missing = sorted(set(dpows) - ppows)
    extra = sorted(ppows - set(dpows))
    if not missing and not extra:
        out.append(Verdict("38", "holds", "same powers of lambda", None, None, sec))
    else:
        out.append(Verdict(
            "38", "typo",
            f"the characteristic polynomial has the powers lambda^{sorted(dpows)}; the print omits "
            + ", ".join(_fmt(dpows[k] * lam**k) for k in missing)
            + f". Correct: |L - lambda E| = -lambda^5 + k3 lambda^3 + k1 lambda with k3 = -sum L_ij^2 and k1 = -(sum of the "
              f"squared Pfaffians of the five 4x4 principal minors)" + (" (= -RigidBody.casimirs)" if pk else " [casimirs disagree]"),
            "|L - lambda E| = k1 lambda + k3 lambda^3", "-lambda^5 + k3 lambda^3 + k1 lambda", sec))
    # conservation: Lie-Poisson brackets with every L_a vanish (Casimirs), hence conserved for every inertia
    cas = all(lie_poisson_bracket(k, La, Ls) == 0 for k in (k1, k3) for La in Ls)
    Is = plane_symbols("I", 5, positive=True)
    H = sum(La**2 / (2 * Ia) for La, Ia in zip(Ls, Is))
    H_cas = all(lie_poisson_bracket(H, La, Ls) == 0 for La in Ls)
    out.append(_claim("38 (k1, k3 conserved)", sec, cas,
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
    out.append(_claim(
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
    out.append(_claim("Sec. 6 (two integrals)", sec, rank <= cl["count"], "",
                      f"k1, k3 and the energy H (dH/dt = {{H, H}} = {dH}) are {rank} functionally independent integrals "
                      f"(gradient rank {rank} at a random point); for physical moments I_ij = m_i + m_j the flow has even more "
                      f"(Manakov's integrals, RigidBody.manakov_integrals)", cl["quote"]))
    return out


# ============================================================================
# Sec. 2.2-2.5: reductions (42)-(81), headings and locked sets
# ============================================================================
_SET_LABELS = {"2.2.1": "S_4", "2.2.2": "S_4", "2.2.3": "S_4", "2.2.4": "S_4", "2.2.5": "S_5", "2.3": "S_3"}


@lru_cache(maxsize=None)
def _sec_reductions() -> tuple:
    from hyperrotor.paper import printed as pr

    sec = "reductions"
    out = []
    eq_of_plane = {p: str(28 + k) for k, p in enumerate(planes(5))}
    for rs in pr.REDUCTION_SECTIONS:
        locked = rs.locked_axes
        ref = _euler_entry_forms(tuple(locked))
        lockset = {_S(f"omega_{i}{j}"): 0 for i, j in planes(5) if i in locked or j in locked}
        for k in rs.equations:
            eq = pr.PRINTED_EQUATIONS[k]
            p = pr.equation_plane(eq)
            pz = _eq_zero(eq)
            if p not in ref:
                out.append(Verdict(k, "typo", f"the equation is for the plane {p}, which is locked in Sec. {rs.section}",
                                   _eq_str(pz, _mtilde(p)), None, sec))
                continue
            d = ref[p]
            v = _compare(k, sec, pz, d, correct=_eq_str(d, _mtilde(p)),
                         note=f"body with axes {locked} locked, RigidBody.lock")
            if v.status == "typo" and sp.expand(pz.xreplace(lockset) - d) == 0:
                stale_terms = [c * t for t, c in _terms(pz).items() if (c * t).xreplace(lockset) == 0]
                v = Verdict(k, "typo",
                            f"not reduced: keeps {_grouped(sp.Add(*stale_terms))}, which vanishes"
                            f" because axes {locked} are locked (the equation is copied from eq. "
                            f"{_source_equation(pz, k)}). Correct: {_eq_str(d, _mtilde(p))}",
                            _eq_str(pz, _mtilde(p)), _eq_str(d, _mtilde(p)), sec)
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
    out.append(_claim("72", sec, {frozenset(s) for s in sets} == allsets and len(sets) == len(allsets),
                      f"the five sets are exactly the C(5,4) = {len(allsets)} four-axis subsets",
                      "the listed sets are not the four-axis subsets", ps.CLAIMS["72"]["quote"]))
    cl = ps.CLAIMS["Sec. 2.5 (closing)"]
    n4 = len(_body5().lock(5).planes)
    n3 = len(_body5().lock((4, 5)).planes)
    out.append(_claim("Sec. 2.5 (closing statement)", sec, n4 == cl["per_4d"] and n3 == cl["per_3d"], "",
                      f"each 4D subspace carries {n4} Euler equations (not {cl['per_4d']}); each 3D one {n3}", cl["quote"]))
    return tuple(out)


def _source_equation(pz, key) -> str:
    """Number of the 4D-sextet equation (42)-(71) that equals the printed one (for the detail text)."""
    from hyperrotor.paper import printed as pr

    for k in range(42, 72):
        if sp.expand(_eq_zero(pr.PRINTED_EQUATIONS[str(k)]) - pz) == 0:
            return f"({k})"
    return "?"


# ============================================================================
# Sec. 3: closed-form solutions (82)-(118)
# ============================================================================
_KAPPA = _S("kappa")
_THETA = _S("Theta")
_C = [_S(f"c_{n}") for n in range(1, 7)]


@lru_cache(maxsize=None)
def _quartet_forms(axis: int = 5) -> dict:
    body = RigidBody(Inertia.quartet(_KAPPA, axis=axis), "paper")
    return {p: _eq_zero(eq) for p, eq in zip(body.planes, body.euler_equations(torque=0))}


@lru_cache(maxsize=None)
def _quartet_rhs(axis: int = 5) -> dict:
    body = RigidBody(Inertia.quartet(_KAPPA, axis=axis), "paper")
    w = [_S(f"omega_{i}{j}") for i, j in planes(5)]
    return {p: sp.cancel(sp.expand(r)) for p, r in zip(planes(5), body.symbolic_rhs(w))}


def _kappa_to_theta(expr):
    """Rewrite with Theta = (kappa^2 - 1)/(kappa^2 + 1), i.e. kappa^2 = (1 + Theta)/(1 - Theta)."""
    return sp.factor(sp.cancel(expr.subs(_KAPPA**2, (1 + _THETA) / (1 - _THETA))))


@lru_cache(maxsize=None)
def _quartet_rhs_theta(axis: int) -> dict:
    """dw/dt of the planes through ``axis`` for the quartet body, written with Theta (a polynomial)."""
    rhs = _quartet_rhs(axis)
    return {p: sp.expand(_kappa_to_theta(rhs[p])) for p in planes(5) if axis in p}


def _axis_system(axis: int, consts: Sequence) -> tuple[list, sp.Matrix]:
    """Derived linear system x' = K x of the planes through ``axis`` with the others set to ``consts``."""
    rhs = _quartet_rhs_theta(axis)
    through = [p for p in planes(5) if axis in p]
    rest = [p for p in planes(5) if axis not in p]
    sub = {_S(f"omega_{i}{j}"): c for (i, j), c in zip(rest, consts)}
    xs = [_S(f"omega_{i}{j}") for i, j in through]
    K = sp.Matrix([[sp.expand(sp.diff(rhs[p], x).xreplace(sub)) for x in xs] for p in through])
    return through, K


@lru_cache(maxsize=None)
def _sec_closed_form() -> tuple:
    sec = "closed-form"
    out = []
    # (82)-(83)
    pl82 = ps.printed("82")
    I0 = sp.Symbol("I_0", positive=True)
    zero_all = {N: all(sp.simplify(r) == 0 for r in RigidBody(Inertia.equal(N, I0)).symbolic_rhs()) for N in range(3, 8)}
    out.append(_claim("82", sec, set(pl82) == set(planes(5)) and zero_all[5],
                      "all ten moments equal: RigidBody(Inertia.equal(5)) has dw/dt = 0 identically",
                      f"the chain lists {sorted(set(pl82))}", _fmt(pl82)))
    solids = _regular_bodies()
    out.append(_claim("82 (Platonic bodies)", sec, all(ok for _, ok in solids),
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
    out.append(_claim("83 (all dimensions)", sec, all(zero_all.values()),
                      "computed for N = 3..7: equal moments give dw/dt = 0", "fails for some N",
                      ps.CLAIMS["83 (all dimensions)"]["quote"]))
    # (84)-(85)
    q = Inertia.quartet(_KAPPA)
    pr_moments = {**ps.printed("84"), **ps.printed("85")}
    mism = [p for p in planes(5) if p not in pr_moments or sp.simplify(pr_moments[p] - q[p]) != 0]
    J = q.mass_tensor
    out.append(Verdict("84-85", "holds" if not mism else "typo",
                       (f"equal to Inertia.quartet(kappa) (axis 5); physical: I_ij = m_i + m_j with m = {tuple(J)}")
                       if not mism else f"differ at {mism}", None, None, sec))
    # (86)-(95)
    forms = _quartet_forms(5)
    consts = {"86": (1, 2), "87": (1, 3), "88": (1, 4), "90": (2, 3), "91": (2, 4), "93": (3, 4)}
    w51 = {_S("omega_51"): _S("omega_15")}
    for k in map(str, range(86, 96)):
        if k in consts:
            d = forms[consts[k]]
            out.append(_compare(k, sec, ps.printed(k)["ode"], d, zero_form=True, correct=f"{_fmt(d)} = 0"))
            continue
        p = {"89": (1, 5), "92": (2, 5), "94": (3, 5), "95": (4, 5)}[k]
        dot = _S(f"omegadot_{p[0]}{p[1]}")
        d = forms[p]
        ds = sp.expand(d * (1 + _KAPPA**2) / d.coeff(dot))
        q = sp.expand(sp.cancel((ds - (1 + _KAPPA**2) * dot) / (1 - _KAPPA**2)))
        shown = f"(1 + kappa^2)*{_fmt(dot)} + (1 - kappa^2)*({_grouped(q)}) = 0"

        def flip(e, dot=dot):
            e = sp.expand(e)
            return 2 * e.coeff(dot) * dot - e
        out.append(_compare(k, sec, ps.printed(k), d, zero_form=True, correct=shown,
                            corrections=(("the sign of the (1 - kappa^2) term is flipped", flip),
                                         ("w51 is read as +w15 (not -w15 as eq. 1 says)", lambda e: e.xreplace(w51)),
                                         ("the sign of the (1 - kappa^2) term is flipped and w51 is read as +w15",
                                          lambda e, flip=flip: flip(e.xreplace(w51))))))
    # (96)-(99): linear system with constants c1..c6 (planes 12, 13, 14, 23, 24, 34)
    through, K = _axis_system(5, _C)
    xs = [_S(f"omega_{i}{j}") for i, j in through]
    for n, (k, p) in enumerate(zip(("96", "97", "98", "99"), through)):
        d = sp.expand(_S(f"omegadot_{p[0]}{p[1]}") - sum(K[n, m] * xs[m] for m in range(4)))
        out.append(_compare(k, sec, ps.printed(k), d, zero_form=True))
    # (100)
    p100 = ps.printed("100")
    theta_der = sp.simplify(K[0, 1] / _C[0]).subs(_THETA, _THETA)  # K is written in Theta already: recover Theta(kappa)
    # Theta as derived from the quartet equations directly in kappa
    rhs = _quartet_rhs(5)
    theta_k = sp.simplify(sp.diff(rhs[(1, 5)], _S("omega_25")).subs(_S("omega_12"), 1))
    ok_theta = sp.simplify(p100["Theta"] - theta_k) == 0
    back = sp.simplify(p100["kappa"].subs(_THETA, theta_k))
    del theta_der
    if ok_theta and sp.simplify(back - _KAPPA) == 0:
        out.append(Verdict("100 (kappa from Theta)", "holds", "inverse is right", None, None, sec))
    else:
        out.append(Verdict("100 (kappa from Theta)", "typo",
                           f"Theta = (kappa^2 - 1)/(1 + kappa^2) is right (= coefficient in the quartet equations: "
                           f"{_fmt(theta_k)}), but the printed inverse gives kappa(Theta(kappa)) = {_fmt(back)} for kappa > 0. "
                           f"Correct: kappa = sqrt(1 - Theta^2)/(1 - Theta)",
                           "kappa = sqrt(1 - Theta^2)/(Theta - 1)", "kappa = sqrt(1 - Theta^2)/(1 - Theta)", sec))
    lo, hi = p100["range"]
    at0 = p100["Theta"].subs(_KAPPA, 0)
    lim = sp.limit(p100["Theta"], _KAPPA, sp.oo)
    attained_lo = at0 == lo
    out.append(_claim("100 (range of Theta)", sec, not (p100["strict"] and attained_lo), "",
                      f"Theta(kappa = 0) = {at0} is attained (kappa = 0: I_i5 = 1, a body flat in the 5th direction, m5 = 0), "
                      f"and Theta -> {lim} as kappa -> oo. Correct: -1 <= Theta < 1", "-1 < Theta < 1", "-1 <= Theta < 1"))
    # (101): the exponential ansatz is complete iff K is normal with imaginary spectrum (K = Theta A, A real antisymmetric)
    anti = sp.simplify(K + K.T) == sp.zeros(4, 4)
    out.append(_claim("101", sec, anti,
                      "the derived system x' = K x has K = Theta*A with A real antisymmetric (computed K + K^T = 0): K is normal "
                      "with purely imaginary eigenvalues, so real frequencies Omega and the exponential ansatz give every solution",
                      "K is not antisymmetric", "w_k5(t) = C_k5 exp(i Omega t)"))
    # (102)-(105)
    Om = _S("Omega")
    Cs = [_S(f"C_{i}{j}") for i, j in through]
    Mder = sp.I * Om * sp.eye(4) - K
    w2C = {_S(f"omega_{i}{j}"): _S(f"C_{i}{j}") for i, j in through}
    for n, k in enumerate(("102", "103", "104", "105")):
        d = sp.expand(sum(Mder[n, m] * Cs[m] for m in range(4)))
        out.append(_compare(k, sec, ps.printed(k), d, zero_form=True,
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
                           "wrong cells (1-based): " + ", ".join(f"({r + 1},{c + 1}): {_fmt(P106[r, c])} -> {_fmt(Mder[r, c])}" for r, c in bad)
                           + ("; row 2 also contradicts the printed (103)" if row103 != 0 else "")
                           + ("; with it the determinant is not the (107) polynomial" if sp.expand(detP - detD) != 0 else ""),
                           None, _fmt(Mder), sec))
    sym_part = sp.simplify(Mder + Mder.T)
    out.append(_claim("106 (antisymmetric)", sec, sym_part == sp.zeros(4, 4), "",
                      f"M + M^T = {_fmt(sym_part[0, 0])}*1 != 0: M is not antisymmetric; M - i*Omega*1 = -K = -Theta*A is",
                      ps.CLAIMS["106 (antisymmetric)"]["quote"], "M = i Omega 1 - Theta A, A^T = -A"))
    # (107)-(110)
    poly = sp.Poly(detD, Om)
    coeffs = dict(zip([m[0] for m in poly.monoms()], poly.coeffs()))
    l2d, l0d = sp.factor(coeffs.get(2, 0)), sp.factor(coeffs.get(0, 0))
    form_ok = set(coeffs) <= {0, 2, 4} and coeffs.get(4) == 1
    out.append(_claim("107", sec, form_ok, f"det(i Omega 1 - K) = Omega^4 + l2 Omega^2 + l0 (computed)",
                      f"det has powers {sorted(coeffs)}", "|M| = Omega^4 + l2 Omega^2 + l0"))
    p108 = ps.printed("108")
    out.append(_compare("108 (l2)", sec, p108["l_2"], sp.expand(l2d)))
    out.append(_compare("108 (l0)", sec, p108["l_0"], sp.expand(l0d)))
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
        out.append(_claim(key, sec, not found and bool(nonstrict),
                          f"{short} {rel} 0 holds (sign decided symbolically)",
                          (f"fails for {found[0][0]} ({short} = {found[0][1]}); only the non-strict {short} {weak} 0 holds "
                           f"(decided symbolically: {'yes' if nonstrict else 'undecided'})") if found else f"{short} {rel} 0 undecided",
                          f"{short} {rel} 0", f"{short} {weak} 0"))
    p109 = ps.printed("109")
    l2s, l0s = _S("l_2"), _S("l_0")
    lhs109 = p109.lhs.subs({l2s: l2d, l0s: l0d})
    out.append(_compare("109", sec, p109.rhs, sp.expand(lhs109), note="l2^2 - 4 l0 with the derived l2, l0"))
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
    out.append(_claim("110", sec, not fails, "",
                      "; ".join(fails) + f". Correct: l2^2 >= l2^2 - 4 l0 >= 0 (l2^2 - 4 l0 = {_fmt(nonneg)} by (109), a product of sums of squares); "
                      "equality in the second means two equal frequencies", "l2^2 > l2^2 - 4 l0 > 0", "l2^2 >= l2^2 - 4 l0 >= 0"))
    # frequencies after (118)
    freqs = ps.printed("after 118")
    roots_ok = all(sp.simplify(sp.expand(f**4 + l2s * f**2 + l0s)) == 0 for f in freqs)
    num_ok = _frequencies_numeric(freqs)
    out.append(_claim("after 118 (frequencies)", sec, roots_ok and num_ok,
                      "each printed Omega solves Omega^4 + l2 Omega^2 + l0 = 0 (exact), and numerically they are +-Omega_1, +-Omega_2 of "
                      "closed_form.quartet_frequencies and the eigenvalues of the derived K; real because l2 <= 0 <= l0 and "
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
            qa = Inertia.quartet(_KAPPA, axis=axis)
            ok = (set(kap) | set(sets["2"]) == set(planes(5)) and not set(kap) & set(sets["2"])
                  and all(sp.simplify(qa[p] - (1 + _KAPPA**2)) == 0 for p in kap) and all(qa[p] == 2 for p in sets["2"]))
        out.append(_claim(k, sec, ok, f"= Inertia.quartet(kappa, axis={axis}): the distinguished axis is {axis}",
                          f"the two sets do not form a quartet body ({sets})", None))
        # constants and characteristic polynomial for that axis
        rhs = _quartet_rhs(axis)
        const = {p for p in planes(5) if rhs[p] == 0}
        pc = ps.printed(kc)
        same = set(pc) == const
        _, Ka = _axis_system(axis, [_S(f"omega_{i}{j}") for i, j in pc] and _C)
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
        out.append(_claim(kc, sec, same and cp_ok,
                          f"the constant components of the axis-{axis} body are exactly {sorted(const)} (derived dw/dt = 0), "
                          f"and with them as c1..c6 the frequency polynomial is again (107)-(108)",
                          f"derived constants {sorted(const)}, printed {list(pc)}; polynomial matches: {cp_ok}", _fmt(pc)))
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
    from hyperrotor.classical.closed_form import quartet_frequencies, quartet_polynomial_coefficients

    rng = np.random.default_rng(3)
    ok = True
    for _ in range(3):
        kappa = float(rng.uniform(0.2, 3.0))
        w0 = rng.normal(size=10)
        l2, l0 = quartet_polynomial_coefficients(kappa, w0)
        vals = sorted(abs(complex(f.subs({_S("l_2"): l2, _S("l_0"): l0}).evalf())) for f in freqs)
        ref = sorted(list(quartet_frequencies(kappa, w0)) * 2)
        ok &= bool(np.allclose(vals, ref, rtol=1e-10, atol=1e-12))
    return ok


# ============================================================================
# Sec. 4: stability (119)-(140)
# ============================================================================
@lru_cache(maxsize=None)
def _linearized() -> dict:
    """varpi index -> expanded first-order (in epsilon) entry-form equation, with I -> J of (131)."""
    eps = _S("epsilon")
    sub = {**ps.printed("119"), **ps.printed("120")}
    Jmap = {_S(f"I_{i}{j}"): J for J, (i, j) in ps.printed("131").items()}
    idx = {}
    for p, e in sub.items():
        n = int(next(s.name for s in e.free_symbols if s.name.startswith("varpi")).split("_")[1])
        idx[p] = n
    wsub = {_S(f"omega_{i}{j}"): e for (i, j), e in sub.items()}
    dsub = {_S(f"omegadot_{i}{j}"): eps * _S(f"varpidot_{idx[(i, j)]}") for (i, j) in sub}
    out = {}
    for p, f in _euler_entry_forms().items():
        e = f.xreplace({_mtilde(p): 0}).xreplace(dsub).xreplace(wsub).xreplace(Jmap)
        out[idx[p]] = sp.expand(sp.diff(sp.expand(e), eps).subs(eps, 0))
    return out


@lru_cache(maxsize=None)
def _sec_stability() -> tuple:
    sec = "stability"
    out = []
    lin = _linearized()
    Om = _S("Omega")
    trivial = sorted(n for n, e in lin.items() if not any(s.name.startswith("varpi_") for s in e.free_symbols))
    coupled = sorted(set(lin) - set(trivial))
    cl = ps.CLAIMS["Sec. 4 (trivial equations)"]
    out.append(_claim("Sec. 4 (four equations satisfied)", sec, len(trivial) == cl["trivial"] and len(coupled) == cl["coupled"],
                      f"computed: {len(trivial)} linearized equations decouple with d(varpi)/dt = 0 (varpi {trivial}: planes "
                      f"{', '.join(f'{i}{j}' for n in trivial for (i, j), e in {**ps.printed('119'), **ps.printed('120')}.items() if _S(f'varpi_{n}') in e.free_symbols)}) "
                      f"and {len(coupled)} couple in three pairs; the paper nevertheless prints all ten as (121)-(130)",
                      f"{len(trivial)} trivial, {len(coupled)} coupled", cl["quote"]))
    out.append(Verdict("119-120", "not-checkable",
                       "definition of the perturbation variables varpi_1..varpi_10 (no relation to test); used for (121)-(132)",
                       None, None, sec))
    for n in range(1, 11):
        k = str(120 + n)
        out.append(_compare(k, sec, ps.printed(k), lin[n], zero_form=True,
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
    t = _S("t")
    C1, C2 = _S("C_1"), _S("C_2")
    for a, b, nu, keys in ((2, 5, "v_1", ("133", "134", "135")), (3, 6, "v_2", ("136 (varpi_3)", "136 (varpi_6)", "136")),
                           (4, 7, "v_3", ("137 (varpi_4)", "137", "138"))):
        ea, eb = lin[a], lin[b]
        da, db = _S(f"varpidot_{a}"), _S(f"varpidot_{b}")
        alpha = sp.solve(ea, da)[0] / _S(f"varpi_{b}")   # varpi_a' = alpha varpi_b
        beta = sp.solve(eb, db)[0] / _S(f"varpi_{a}")    # varpi_b' = beta varpi_a
        nu2 = sp.factor(-alpha * beta / Om**2)
        v = _S(nu)
        # solution of varpi_a
        sol_a = ps.printed(keys[0]).rhs
        ok_a = sp.simplify((sp.diff(sol_a, t, 2) - alpha * beta * sol_a).subs(v, sp.sqrt(nu2))) == 0
        out.append(Verdict(keys[0], "holds" if ok_a else "typo",
                           f"solves varpi{a}'' = -Omega^2 nu^2 varpi{a} with the derived nu^2 = {_fmt(nu2)}" if ok_a
                           else "does not solve the derived pair", _fmt(ps.printed(keys[0])), None, sec))
        # partner: varpi_b = varpi_a' / alpha
        partner = sp.simplify(sp.diff(sol_a, t) / alpha)
        reading = ps.printed(keys[1])["reading"]
        okb = sp.simplify(reading - partner) == 0
        okb_neg = sp.simplify(reading + partner) == 0
        out.append(Verdict(keys[1], "holds" if okb else "typo",
                           (f"under the fraction reading {_fmt(reading)} it equals the derived varpi{b} = varpi{a}'/({_fmt(alpha)})")
                           if okb else
                           (f"under the fraction reading ({ps.LITERAL[keys[1]]!r} -> {_fmt(reading)}) the "
                            f"{'overall sign is' if okb_neg else 'expression is'} wrong. Correct: varpi{b} = {_fmt(sp.factor(partner))}"),
                           ps.LITERAL[keys[1]], _fmt(sp.factor(partner)), sec))
        # the frequency (garbled)
        lit = ps.printed(keys[2])["literal"]
        Js = sorted(lit.free_symbols, key=lambda s: s.name)
        lam = sp.Symbol("lam", positive=True)
        homogeneous = sp.simplify(lit.subs({j: lam * j for j in Js}, simultaneous=True) - lit) == 0
        matches = sp.simplify(lit**2 - nu2) == 0 or sp.simplify(lit - nu2) == 0
        if matches:
            out.append(Verdict(keys[2], "holds", f"nu^2 = {_fmt(nu2)}", ps.LITERAL[keys[2]], None, sec))
        elif homogeneous:
            out.append(Verdict(keys[2], "typo", f"wrong frequency. Correct: {nu} = sqrt({_fmt(nu2)})",
                               ps.LITERAL[keys[2]], f"sqrt({_fmt(nu2)})", sec))
        else:
            out.append(Verdict(keys[2], "not-checkable",
                               f"garbled by the text extraction: the literal reading {ps.LITERAL[keys[2]]!r} is not homogeneous of "
                               f"degree 0 in the moments (computed), so it cannot be a frequency ratio. Derived: {nu} = sqrt({_fmt(nu2)})",
                               ps.LITERAL[keys[2]], f"sqrt({_fmt(nu2)})", sec))
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
        out.append(_claim(
            k, sec, ok, "",
            f"the printed chain allows equality: with J1 = J2 (moments {vals}) linear_stability finds "
            f"'{res.reason}', not stable oscillations. With strict inequalities the chain is sufficient "
            f"({'stable' if res_strict.stable else 'UNSTABLE'}), but it is not necessary (e.g. I = {mixed.tolist()} is "
            f"{'stable' if res_mixed.stable else 'unstable'} with I12 neither largest nor smallest). Correct condition "
            f"(stability_condition): {cond}",
            _fmt(p["order"]) + " " + p["relation"], str(cond)))
    return out


# ============================================================================
# Sec. 5: quantum (141)-(147)
# ============================================================================
@lru_cache(maxsize=None)
def _sec_quantum() -> tuple:
    from hyperrotor.quantum.operators import (
        DifferentialOperator,
        angular_momentum_operators,
        commutator,
        contraction_identity,
        operator_matrix,
    )

    sec = "quantum"
    out = []
    hbar = sp.Symbol("hbar", positive=True)
    coords = tuple(sp.Symbol(n, real=True) for n in ("x", "y", "z", "w", "v"))
    ops = angular_momentum_operators(5, coordinates=coords)
    # (142)
    f = sp.Function("f")(*coords)
    name = {c.name: c for c in coords}
    p142 = ps.printed("142")
    bad = []
    for p in planes(5):
        (a1, b1), (b2, a2) = p142[p]
        expr = name[a1] * sp.diff(f, name[b1]) - name[b2] * sp.diff(f, name[a2])
        op = DifferentialOperator.from_sympy(expr, f, coords)
        if not op == ops[p]:
            bad.append(p)
    C = structure_constants(5)
    closes = all(
        commutator(ops[pa], ops[pb]) == _op_sum(ops, C[a, b], coords)
        for a, pa in enumerate(planes(5)) for b, pb in enumerate(planes(5)) if a < b
    )
    v142 = (Verdict("142", "holds" if not bad else "typo",
                       ("the ten operators equal angular_momentum_operators(5) (x_i d/dx_j - x_j d/dx_i); they "
                        + ("close" if closes else "do NOT close") + " under commutation with the so(5) structure constants, "
                        "[L_a, L_b] = sum_c C_ab^c L_c (computed for all 45 pairs)") if not bad else f"wrong operators for planes {bad}",
                       "L^12 = x d/dy - y d/dx, ...", None, sec))
    # (141), (143): sign patterns and prefactor
    for k, hb in (("141", hbar), ("143", None)):
        pk = ps.printed(k)
        M = operator_matrix(5, "paper", hbar=hb, coordinates=coords)
        wrong = []
        for r in range(5):
            for c in range(5):
                if r == c:
                    continue
                pl = pk["label"].get((r + 1, c + 1))
                if pl is None:
                    wrong.append((r + 1, c + 1))
                    continue
                base = ops[pl] if hb is None else ops[pl].hermitian(hbar)
                if not (M[r, c] == base * int(pk["sign"][r, c])):
                    wrong.append((r + 1, c + 1))
        pref_ok = sp.simplify(pk["prefactor"] - (-sp.I * sp.Symbol("hbar"))) == 0 if k == "141" else True
        out.append(Verdict(k, "holds" if not wrong and pref_ok else "typo",
                           ("checkerboard matrix (-1)^(i+j) L^ij of the operators (eq. 21 pattern), = operator_matrix(5, 'paper'"
                            + (", hbar): the Hermitian -i hbar L^ij (the extraction shows the entries as 1^ij)" if k == "141" else ")"))
                           if not wrong and pref_ok else f"wrong entries {wrong}", None, None, sec))
        if k == "141":
            out.append(v142)
    # (144): same pattern as (25)
    vs = _product_verdicts("144", sec, "LOp", "OmegaOp")
    bad_lines = [v.equation.split("[")[1].rstrip("]") for v in vs if v.status != "holds"]
    v25 = {v.equation.split("[")[1].rstrip("]"): v.detail for v in _sec_euler() if v.equation.startswith("25 [")}
    same = all(v.detail.replace("LOp", "L").replace("OmegaOp", "w") == v25.get(v.equation.split("[")[1].rstrip("]"))
               for v in vs if v.status != "holds")
    first = next((v for v in vs if v.status != "holds"), None)
    out.append(Verdict("144", "holds" if not bad_lines else "typo",
                       ("all ten entries agree with the operator version of (25)") if not bad_lines else
                       (f"entries {', '.join(bad_lines)} are wrong"
                        + (", term for term the same errors as in (25) (see the verdicts 25 [ij], with L -> LOp, w -> OmegaOp)"
                           if same else "") + f"; e.g. [{first.equation.split('[')[1]} {first.detail}"
                        + ". Corrected product: hyperrotor.quantum.operator_product(A, B, form='eq144')"),
                       None, None, sec))
    # (145)-(147)
    for k in ("145", "146", "147"):
        pk = ps.printed(k)
        N = pk["N"]
        anti = contraction_identity(N, form="antisymmetrized")
        e144 = contraction_identity(N, form="eq144")
        herm_factor = sp.I * (N - 2)  # for -i hbar L (stated in contraction_identity docs); recomputed below
        Lh = operator_matrix(N, "paper", hbar=1)
        Lr = operator_matrix(N, "paper")
        c01 = sum((Lh[0, kk] * Lh[1, kk] - Lh[1, kk] * Lh[0, kk] for kk in range(N)), Lh[0, 0])
        herm_ok = c01 == Lh[0, 1] * herm_factor
        holds = anti.holds and anti.factor == pk["factor"]
        detail = (f"holds for the antisymmetrized product (L Omega)_ij - (L Omega)_ji = sum_k [L_ik, L_jk] with Omega = L^T and "
                  f"the real operators (142)/(143): factor {anti.factor} = -(N-2), N = {N}, exact in every entry "
                  f"(contraction_identity). With the eq.-(144) pattern the factor is {e144.factor} "
                  f"({'exact' if e144.holds else 'not exact'}); for the Hermitian -i hbar L of (141) it is "
                  f"{'i hbar (N-2)' if herm_ok else 'different'}; the plain matrix product (L L^T)_12 is of order "
                  f"{sum((Lr[0, kk] * Lr[1, kk] for kk in range(N)), Lr[0, 0]).order}")
        out.append(Verdict(k, "holds" if holds else "claim-false",
                           detail if holds else f"no exact identity with factor {pk['factor']}: antisymmetrized gives {anti.factor}, "
                                                f"eq.-(144) pattern gives {e144.factor}",
                           f"L Omega = {pk['factor']} L (N = {N})", f"sum_k [L_ik, L_jk] = -(N-2) L_ij", sec))
    # cross-references
    cl = ps.CLAIMS["Sec. 5 (cross-references)"]
    wrongs = []
    for cited, kind in cl["citations"]:
        if cl["kinds"].get(cited) != kind:
            right = [n for n, kk in cl["kinds"].items() if kk == kind]
            wrongs.append(f"({cited}) -> ({right[0] if right else '?'})")
    out.append(Verdict("Sec. 5 (cross-references)", "holds" if not wrongs else "typo",
                       "references point to the right equations" if not wrongs else
                       "references point to the wrong equations (or to the non-existent (148)): " + ", ".join(wrongs),
                       cl["quote"], None, sec))
    return tuple(out)


def _op_sum(ops, coeffs, coords):
    from hyperrotor.quantum.operators import DifferentialOperator
    from hyperrotor.quantum.normal_form import WeylElement

    acc = DifferentialOperator(WeylElement(len(coords), {}), coords)
    for c, p in zip(coeffs, planes(5)):
        if c:
            acc = acc + ops[p] * int(c)
    return acc


# ============================================================================
# driver and renderers
# ============================================================================
#: Section key -> (title, checker).
SECTIONS: dict[str, tuple[str, Callable[[], tuple]]] = {
    "tensor": ("Sec. 1: inertia tensor, angular momentum, energy (eqs. 3-6, 26-27)", _sec_tensor),
    "euler": ("Sec. 2.1: product (25), Tables 1-2, Euler equations (28)-(37), invariants (38)", _sec_euler),
    "reductions": ("Sec. 2.2-2.5: reductions (42)-(81), headings and locked sets", _sec_reductions),
    "closed-form": ("Sec. 3: closed-form solutions (82)-(118)", _sec_closed_form),
    "stability": ("Sec. 4: stability (119)-(140)", _sec_stability),
    "quantum": ("Sec. 5: quantum angular momentum (141)-(147)", _sec_quantum),
}


def clear_cache(derived: bool = True) -> None:
    """Forget cached results (call after editing a transcription).

    ``derived=False`` keeps the derivations that do not depend on any printed
    object (the Euler equations of the symbolic and quartet bodies) and only
    drops the printed objects and everything computed from them.
    """
    fns = [_sec_tensor, _sec_euler, _sec_reductions, _sec_closed_form, _sec_stability, _sec_quantum,
           _linearized, ps.printed]
    if derived:
        fns += [_euler_entry_forms, _quartet_forms, _quartet_rhs, _quartet_rhs_theta]
    for fn in fns:
        fn.cache_clear()


def verify(sections: Iterable[str] | None = None) -> list[Verdict]:
    """Check the preprint equation by equation; one :class:`Verdict` per equation or claim.

    Parameters
    ----------
    sections : iterable of str, optional
        Keys of :data:`SECTIONS` (``"tensor", "euler", "reductions",
        "closed-form", "stability", "quantum"``); default all, in paper order.

    Returns
    -------
    list of Verdict
        Every status is computed by comparing the printed object with the
        package's derivation (module docstring). Results are cached; call
        :func:`clear_cache` after changing a transcription.

    Raises
    ------
    ValueError
        For an unknown section name.
    """
    if sections is None:
        keys = list(SECTIONS)
    else:
        if isinstance(sections, str):
            sections = [sections]
        keys = list(sections)
        unknown = [k for k in keys if k not in SECTIONS]
        if unknown:
            raise ValueError(f"unknown section(s) {unknown}; allowed: {', '.join(SECTIONS)}")
    out: list[Verdict] = []
    for k in keys:
        out.extend(SECTIONS[k][1]())
    return out


def summary(verdicts: Sequence[Verdict]) -> dict:
    """Counts per status (all four keys present)."""
    counts = {s: 0 for s in STATUSES}
    for v in verdicts:
        counts[v.status] += 1
    return counts


def render_json(verdicts: Sequence[Verdict]) -> str:
    """JSON list of verdict objects (keys ``equation, status, detail, printed, correct, section``)."""
    return json.dumps([v.to_dict() for v in verdicts], indent=1, ensure_ascii=False)


def render_table(verdicts: Sequence[Verdict], width: int = 110) -> str:
    """A readable fixed-width terminal table (equation | status | detail), wrapped to ``width``."""
    ew = max([len("Equation")] + [len(v.equation) for v in verdicts])
    sw = max(len(s) for s in STATUSES)
    dw = max(30, width - ew - sw - 6)
    lines = [f"{'Equation':<{ew}}  {'Status':<{sw}}  Detail", f"{'-' * ew}  {'-' * sw}  {'-' * dw}"]
    current = None
    for v in verdicts:
        if v.section != current:
            current = v.section
            title = SECTIONS[current][0] if current in SECTIONS else current
            lines.append(f"== {title}")
        wrapped = textwrap.wrap(v.detail, dw) or [""]
        lines.append(f"{v.equation:<{ew}}  {v.status:<{sw}}  {wrapped[0]}")
        lines += [f"{'':<{ew}}  {'':<{sw}}  {w}" for w in wrapped[1:]]
    c = summary(verdicts)
    lines.append("")
    lines.append(f"{len(verdicts)} items: " + ", ".join(f"{n} {s}" for s, n in c.items()))
    return "\n".join(lines)


def _md(s: str | None) -> str:
    return "" if s is None else s.replace("|", "\\|").replace("*", "\\*").replace("\n", " ")


def render_markdown(verdicts: Sequence[Verdict]) -> str:
    """The Markdown report (``docs/verification.md``): summary counts and one table per section."""
    c = summary(verdicts)
    out = [
        "# Verification of the preprint, equation by equation",
        "",
        "Generated by `hyperrotor verify --markdown` (`hyperrotor.paper.verify`). Every status is computed at run time by "
        "comparing the printed equation (transcribed with its typos in `hyperrotor.paper.printed` and "
        "`hyperrotor.paper.printed_solutions`) with hyperrotor's own derivation: **holds** (printed = derived), "
        "**typo** (printed differs; corrected form given), **claim-false** (a stated property fails on a computed "
        "counterexample; correct statement given), **not-checkable** (no testable content, or garbled text).",
        "",
        "Printed `I^{ijij}` is read as the plane moment `I_ij`; `w12` is omega_12, `w12'` its time derivative, "
        "`m~12` the printed torque entry; equations are compared as the (i,j) matrix entries the paper prints.",
        "",
        "| status | count |",
        "| --- | --- |",
    ]
    out += [f"| {s} | {n} |" for s, n in c.items()]
    out.append(f"| **total** | **{len(verdicts)}** |")
    current = None
    for v in verdicts:
        if v.section != current:
            current = v.section
            out += ["", f"## {SECTIONS[current][0] if current in SECTIONS else current}", "",
                    "| Eq. | Status | Detail |", "| --- | --- | --- |"]
        status = v.status if v.status == "holds" else f"**{v.status}**"
        out.append(f"| {_md(v.equation)} | {status} | {_md(v.detail)} |")
    out.append("")
    return "\n".join(out)


_FORMATS = {"table": render_table, "markdown": render_markdown, "json": render_json}


def render(verdicts: Sequence[Verdict], format: str = "table") -> str:
    """Render verdicts as ``"table"`` (terminal), ``"markdown"`` or ``"json"``."""
    if format not in _FORMATS:
        raise ValueError(f"unknown format {format!r}; allowed: {', '.join(_FORMATS)}")
    return _FORMATS[format](verdicts)


def configure_parser(parser: argparse.ArgumentParser) -> None:
    """Add the options of ``hyperrotor verify`` to ``parser`` (shared by the CLI and :func:`main_verify`)."""
    fmt = parser.add_mutually_exclusive_group()
    fmt.add_argument("--json", action="store_true", help="JSON list of {equation, status, detail, ...}")
    fmt.add_argument("--markdown", action="store_true", help="Markdown report (docs/verification.md)")
    parser.add_argument("--section", action="append", choices=list(SECTIONS), metavar="NAME",
                        help="only this section (repeatable); one of: " + ", ".join(SECTIONS))
    parser.add_argument("--output", "-o", metavar="FILE", help="write the report to FILE instead of stdout")


def run_from_args(args: argparse.Namespace) -> int:
    """Run the report for parsed options (see :func:`configure_parser`); returns the exit code 0."""
    verdicts = verify(args.section)
    text = render(verdicts, "json" if args.json else "markdown" if args.markdown else "table")
    if args.output:
        with open(args.output, "w", encoding="utf-8") as fh:
            fh.write(text if text.endswith("\n") else text + "\n")
    else:
        print(text)
    return 0


def main_verify(argv: Sequence[str] | None = None) -> int:
    """Command-line entry: ``hyperrotor verify [--json | --markdown] [--section NAME ...] [--output FILE]``.

    Prints the report (or writes it to ``--output``) and returns the exit code 0.
    Bad options exit with code 2 and a message listing what is allowed (argparse).
    """
    parser = argparse.ArgumentParser(prog="hyperrotor verify", description=VERIFY_DESCRIPTION)
    configure_parser(parser)
    return run_from_args(parser.parse_args(argv))


#: One-line description of the report (CLI help).
VERIFY_DESCRIPTION = ("check the preprint's equations (3)-(147) against hyperrotor's derivations; "
                      "each item holds / typo / claim-false / not-checkable")


if __name__ == "__main__":  # python -m hyperrotor.paper.verify --markdown -o docs/verification.md
    raise SystemExit(main_verify())
