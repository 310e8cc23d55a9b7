"""The section checkers of the preprint verification, one module per paper section.

Each checker takes no argument, returns a tuple of
:class:`~hyperrotor.paper.verdicts.Verdict` and caches its result
(:func:`hyperrotor.paper.verify.clear_cache` forgets it):

* :mod:`~hyperrotor.paper.sections.tensor`: Sec. 1, eqs. (3)-(6), (26)-(27);
* :mod:`~hyperrotor.paper.sections.euler`: Sec. 2.1, eq. (25), Tables 1-2, eqs. (28)-(38);
* :mod:`~hyperrotor.paper.sections.reductions`: Sec. 2.2-2.5, eqs. (42)-(81);
* :mod:`~hyperrotor.paper.sections.closed_form`: Sec. 3, eqs. (82)-(118);
* :mod:`~hyperrotor.paper.sections.stability`: Sec. 4, eqs. (119)-(140);
* :mod:`~hyperrotor.paper.sections.quantum`: Sec. 5, eqs. (141)-(147).

Shared by several of them: :mod:`~hyperrotor.paper.sections.derived` (the
symbolic body and its Euler equations) and
:mod:`~hyperrotor.paper.sections.products` (the product check of eqs. 25 and
144). :data:`SECTIONS` maps the section keys to their titles and checkers, in
paper order.
"""
from __future__ import annotations

from typing import Callable

from hyperrotor.paper.section_titles import SECTION_TITLES
from hyperrotor.paper.sections.closed_form import sec_closed_form
from hyperrotor.paper.sections.euler import sec_euler
from hyperrotor.paper.sections.quantum import sec_quantum
from hyperrotor.paper.sections.reductions import sec_reductions
from hyperrotor.paper.sections.stability import sec_stability
from hyperrotor.paper.sections.tensor import sec_tensor

__all__ = ["SECTIONS"]

_CHECKERS: dict[str, Callable[[], tuple]] = {
    "tensor": sec_tensor,
    "euler": sec_euler,
    "reductions": sec_reductions,
    "closed-form": sec_closed_form,
    "stability": sec_stability,
    "quantum": sec_quantum,
}
#: Section key -> (title, checker), in paper order (titles: :data:`~hyperrotor.paper.section_titles.SECTION_TITLES`).
SECTIONS: dict[str, tuple[str, Callable[[], tuple]]] = {key: (title, _CHECKERS[key])
                                                         for key, title in SECTION_TITLES.items()}
