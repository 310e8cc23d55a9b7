"""The sections of the preprint that :func:`hyperrotor.paper.verify.verify` checks: key -> title, in paper order.

A leaf without SymPy: the command line lists the keys in ``hyperrotor verify --help`` and checks
``--section`` against them without loading the checkers (:data:`hyperrotor.paper.sections.SECTIONS`
pairs each title with its checker).
"""
from __future__ import annotations

__all__ = ["SECTION_TITLES"]

#: Section key -> title.
SECTION_TITLES: dict[str, str] = {
    "tensor": "Sec. 1: inertia tensor, angular momentum, energy (eqs. 3-6, 26-27)",
    "euler": "Sec. 2.1: product (25), Tables 1-2, Euler equations (28)-(37), invariants (38)",
    "reductions": "Sec. 2.2-2.5: reductions (42)-(81), headings and locked sets",
    "closed-form": "Sec. 3: closed-form solutions (82)-(118)",
    "stability": "Sec. 4: stability (119)-(140)",
    "quantum": "Sec. 5: quantum angular momentum (141)-(147)",
}
