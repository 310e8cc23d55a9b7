r"""Equation-by-equation verification of the preprint with hyperrotor's own machinery.

:func:`verify` compares every printed equation and claim of the paper (the
transcriptions :mod:`hyperrotor.paper.printed` and
:mod:`hyperrotor.paper.printed_solutions`, typos included) with the package's
derivation (:class:`hyperrotor.RigidBody`, :class:`hyperrotor.Inertia`,
:mod:`hyperrotor.conventions`, :mod:`hyperrotor.classical.closed_form`,
:mod:`hyperrotor.classical.stability`, :mod:`hyperrotor.quantum.operators`)
and returns one :class:`~hyperrotor.paper.verdicts.Verdict` per equation or claim. **No verdict is typed
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

Layout
------
* :mod:`hyperrotor.paper.verdicts`: :class:`~hyperrotor.paper.verdicts.Verdict`,
  :data:`~hyperrotor.paper.verdicts.STATUSES` and the shared comparison helpers;
* :mod:`hyperrotor.paper.sections`: one checker per paper section and the
  registry :data:`~hyperrotor.paper.sections.SECTIONS` (its keys and titles:
  :mod:`hyperrotor.paper.section_titles`, without SymPy);
* :mod:`hyperrotor.paper.report`: :func:`~hyperrotor.paper.report.summary` and
  the renderers;
* this module: :func:`verify` and :func:`clear_cache`. It
  re-exports ``Verdict``, ``STATUSES``, ``SECTIONS``, ``summary``, ``render``,
  ``render_table``, ``render_markdown`` and ``render_json``.

Rendering
---------
:func:`~hyperrotor.paper.report.render` turns verdicts into a terminal table
(``"table"``), Markdown (``"markdown"``, the page ``docs/verification.md``) or
JSON (``"json"``: a list of objects with ``equation``, ``status``, ``detail``,
``printed``, ``correct``, ``section``). The command line is ``hyperrotor verify
[--json | --markdown] [--section NAME ...] [-o FILE]`` (:mod:`hyperrotor.cli.verify`
declares its options; the CLI writes files through its one checked, no-clobber path).
"""
from __future__ import annotations

from typing import Iterable

from hyperrotor.paper import printed_solutions as ps
from hyperrotor.paper.report import render, render_json, render_markdown, render_table, summary
from hyperrotor.paper.sections import SECTIONS
from hyperrotor.paper.sections.closed_form import quartet_forms, quartet_rhs, quartet_rhs_theta, sec_closed_form
from hyperrotor.paper.sections.derived import euler_entry_forms
from hyperrotor.paper.sections.euler import sec_euler
from hyperrotor.paper.sections.quantum import sec_quantum
from hyperrotor.paper.sections.reductions import sec_reductions
from hyperrotor.paper.sections.stability import linearized, sec_stability
from hyperrotor.paper.sections.tensor import sec_tensor
from hyperrotor.paper.verdicts import STATUSES, Verdict

__all__ = [
    "Verdict",
    "STATUSES",
    "SECTIONS",
    "verify",
    "render",
    "render_table",
    "render_markdown",
    "render_json",
    "clear_cache",
    "summary",
]


def clear_cache(derived: bool = True) -> None:
    """Forget cached results (call after editing a transcription).

    ``derived=False`` keeps the derivations that do not depend on any printed
    object (the Euler equations of the symbolic and quartet bodies) and only
    drops the printed objects and everything computed from them.
    """
    fns = [sec_tensor, sec_euler, sec_reductions, sec_closed_form, sec_stability, sec_quantum,
           linearized, ps.printed]
    if derived:
        fns += [euler_entry_forms, quartet_forms, quartet_rhs, quartet_rhs_theta]
    for fn in fns:
        fn.cache_clear()


def verify(sections: Iterable[str] | None = None) -> list[Verdict]:
    """Check the preprint equation by equation; one :class:`~hyperrotor.paper.verdicts.Verdict` per equation or claim.

    Parameters
    ----------
    sections : iterable of str, optional
        Keys of :data:`~hyperrotor.paper.sections.SECTIONS` (``"tensor", "euler", "reductions",
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


if __name__ == "__main__":  # not a command: the report is written by `hyperrotor verify` (the CLI's one file path)
    import sys

    print("python -m hyperrotor.paper.verify is not a command; run `hyperrotor verify [--json | --markdown] "
          "[-o FILE]` (files are written by the command line's checked, no-clobber path)", file=sys.stderr)
    sys.exit(2)
