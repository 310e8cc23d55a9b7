"""The preprint "5D-Euler Equations for Rotating Bodies": its printed formulas and their verification.

:mod:`hyperrotor.paper.printed` and :mod:`hyperrotor.paper.printed_solutions` hold the
print (typos included); :mod:`hyperrotor.paper.verify` compares it with the
package's derivations (``hyperrotor verify`` on the command line), with the
verdicts and comparison helpers of :mod:`hyperrotor.paper.verdicts`, one
checker per paper section in :mod:`hyperrotor.paper.sections` and the
renderers of :mod:`hyperrotor.paper.report`.
"""
from .verify import STATUSES, Verdict, render
from .verify import verify as verify_paper

__all__ = ["verify_paper", "Verdict", "render", "STATUSES"]
