r"""Verdicts and the comparison helpers that produce them.

A :class:`Verdict` records the outcome of checking one printed equation or
claim of the preprint; :data:`STATUSES` lists the allowed outcomes. The
helpers here are shared by the section checkers in
:mod:`hyperrotor.paper.sections` (package-internal: not in ``__all__``; names
with an underscore are used in this module only):

* text: ``fmt_expr`` (compact SymPy text), ``grouped`` (grouped by the monomials
  of the dynamical variables), ``_diff_text``, ``eq_str``;
* normalisation: ``_plain`` (``omega_ij(t)`` to plain symbols), ``eq_zero``
  (``lhs - rhs`` of an equation), ``antisym`` (reversed indices read by
  antisymmetry, eq. 1);
* comparison: ``expr_terms``, ``_term_diff``, ``_proportional``, ``_scale_like``,
  ``_mismatch``, ``_agrees``;
* verdict builders: ``compare`` (printed vs derived expression, ``"holds"`` or
  ``"typo"``) and ``claim`` (a checked statement, ``"holds"`` or
  ``"claim-false"``).
"""
from __future__ import annotations

import re
from dataclasses import asdict, dataclass

import sympy as sp

from hyperrotor import _parse

from hyperrotor.paper import printed_solutions as ps


#: The allowed verdict statuses.
__all__ = ["Verdict", "STATUSES"]

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
        Key of :data:`~hyperrotor.paper.sections.SECTIONS` the item belongs to.
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
psym = ps.symbol


def fmt_expr(expr) -> str:
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
    expr = _parse.to_sympy(expr, "expr", text=False)  # a derived SymPy object, never text
    reps = {}
    for d in expr.atoms(sp.Derivative):
        reps[d] = psym("omegadot_" + d.expr.func.__name__.split("_")[1])
    expr = expr.xreplace(reps)
    reps = {f: psym(f.func.__name__) for f in expr.atoms(sp.core.function.AppliedUndef)}
    return expr.xreplace(reps)


def eq_zero(eq) -> sp.Expr:
    """``lhs - rhs`` of an ``Eq`` with plain symbols, expanded."""
    return sp.expand(_plain(eq.lhs) - _plain(eq.rhs))


def antisym(expr):
    """Read reversed-index components by antisymmetry: ``omega_ji -> -omega_ij`` (also ``L``, ``Omega``)."""
    reps = {}
    for s in expr.free_symbols:
        m = re.fullmatch(r"(omega|L|Omega|OmegaOp|LOp)_(\d)(\d)", s.name)
        if m and int(m.group(2)) > int(m.group(3)):
            reps[s] = -psym(f"{m.group(1)}_{m.group(3)}{m.group(2)}")
    return expr.xreplace(reps)


def expr_terms(expr) -> dict:
    """Monomial -> coefficient of an expanded polynomial expression."""
    return sp.expand(expr).as_coefficients_dict()


def _term_diff(printed, derived) -> tuple[list, list]:
    """Terms of ``printed`` not in ``derived`` (``extra``) and of ``derived`` not in ``printed`` (``missing``)."""
    p, d = expr_terms(printed), expr_terms(derived)
    extra = [c * m for m, c in p.items() if sp.simplify(c - d.get(m, 0)) != 0]
    missing = [c * m for m, c in d.items() if sp.simplify(c - p.get(m, 0)) != 0]
    return extra, missing


_DYN = re.compile(r"^(omega|omegadot|varpi|varpidot|L|C|LOp|OmegaOp)_\d+$")
KAPPA = psym("kappa")  # the quartet parameter of eqs. (84)-(85); grouped factors polynomials in it


def grouped(expr) -> str:
    """Text of ``expr`` grouped by the monomials of the dynamical variables, coefficients factored."""
    expr = sp.expand(expr)
    gens = sorted((s for s in expr.free_symbols if _DYN.match(s.name)), key=lambda s: s.name)
    if not gens or expr == 0:
        return fmt_expr(expr)
    text = ""
    for mono, coef in sp.Poly(expr, *gens).terms():
        m = fmt_expr(sp.Mul(*[g**e for g, e in zip(gens, mono)]))
        c = sp.factor(coef)
        if coef.free_symbols == {KAPPA}:
            k2 = sp.Dummy("k2")
            c = sp.factor(sp.expand(coef).subs(KAPPA**2, k2)).subs(k2, KAPPA**2)
        neg = c.could_extract_minus_sign()
        if neg:
            c = -c
        if c == 1:
            body = m
        elif c.is_Atom or (c.is_Mul and all(a.is_Atom or a.is_Pow for a in c.args)):
            body = f"{fmt_expr(c)}*{m}"
        else:
            body = f"({fmt_expr(c)})*{m}"
        text += (" - " if neg else " + ") + body if text else ("-" if neg else "") + body
    return text


def _diff_text(extra: list, missing: list) -> str:
    parts = []
    if extra:
        parts.append("printed has " + grouped(sp.Add(*extra)))
    if missing:
        parts.append("derived has " + grouped(sp.Add(*missing)))
    return "; ".join(parts)


def _proportional(printed, derived):
    """The constant ``c != 0`` with ``printed == c * derived`` (exactly), else ``None``."""
    printed, derived = sp.expand(printed), sp.expand(derived)
    if derived == 0:
        return None
    dterms = expr_terms(derived)
    mono, coef = next(iter(dterms.items()))
    c = sp.simplify(expr_terms(printed).get(mono, 0) / coef)
    if c == 0:
        return None
    return c if sp.expand(printed - c * derived) == 0 else None


def _scale_like(p, d):
    """Scale ``d`` so that its derivative term (or first common term) has the printed coefficient."""
    pp, dd = expr_terms(p), expr_terms(d)
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


def compare(key, section, printed, derived, *, zero_form=False, correct=None, note="", corrections=()):
    """Verdict from comparing a printed expression with the derived one.

    ``zero_form``: both stand for ``expr = 0``, so equality up to a non-zero
    constant factor counts. ``corrections``: ``(description, function)`` pairs
    that transform the printed expression (e.g. a notation reading); if one
    makes it agree, or removes some of the differences, the detail says so (the
    status stays ``"typo"``).
    """
    p = antisym(sp.expand(printed))
    d = sp.expand(derived)
    shown_correct = correct if correct is not None else (grouped(_scale_like(p, d) if zero_form else d)
                                                         + (" = 0" if zero_form else ""))
    if _agrees(p, d, zero_form):
        return Verdict(key, "holds", ("agrees with the derived form" + (f" ({note})" if note else "")),
                       grouped(printed), shown_correct, section)
    extra, missing = _mismatch(p, d, zero_form)
    detail = _diff_text(extra, missing)
    best = None
    for desc, fn in corrections:
        q = sp.expand(antisym(fn(printed)))
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
    return Verdict(key, "typo", detail + f". Correct: {shown_correct}", grouped(printed), shown_correct, section)


def claim(key, section, ok: bool, detail_true: str, detail_false: str, printed=None, correct=None):
    return Verdict(key, "holds" if ok else "claim-false", detail_true if ok else detail_false, printed, correct, section)


def eq_str(zero_expr, rhs_symbol=None) -> str:
    """``lhs = rhs`` text from ``lhs - rhs`` (moving a torque symbol to the right)."""
    if rhs_symbol is not None:
        return f"{grouped(zero_expr + rhs_symbol)} = {fmt_expr(rhs_symbol)}"
    return f"{grouped(zero_expr)} = 0"


def mtilde(p):
    return sp.Symbol(f"mtilde_{p[0]}{p[1]}")
