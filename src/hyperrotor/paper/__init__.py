"""The preprint "5D-Euler Equations for Rotating Bodies": its printed formulas and their verification.

:mod:`hyperrotor.paper.printed` and :mod:`hyperrotor.paper.printed_solutions` hold the
print (typos included); :mod:`hyperrotor.paper.verify` compares it with the
package's derivations (``hyperrotor verify`` on the command line), with the
verdicts and comparison helpers of :mod:`hyperrotor.paper.verdicts`, one
checker per paper section in :mod:`hyperrotor.paper.sections` and the
renderers of :mod:`hyperrotor.paper.report`; the section keys and titles are in
:mod:`hyperrotor.paper.section_titles` (no SymPy).
"""
from hyperrotor._lazy import lazy_attributes as _lazy_attributes

__all__ = ["verify_paper", "Verdict", "render", "STATUSES"]

#: PEP 562: the names load the verification (and SymPy) on first use, so the command line can list the
#: section keys (:mod:`hyperrotor.paper.section_titles`) without loading SymPy.
__getattr__, __dir__ = _lazy_attributes(__name__, {
    "verify_paper": (".verify", "verify"),
    "Verdict": (".verify", "Verdict"),
    "render": (".verify", "render"),
    "STATUSES": (".verify", "STATUSES"),
})
