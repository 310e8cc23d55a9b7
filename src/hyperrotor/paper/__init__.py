"""The preprint "5D-Euler Equations for Rotating Bodies": its printed formulas and their verification.

:mod:`hyperrotor.paper.printed` and :mod:`hyperrotor.paper.printed_solutions` hold the
print (typos included); :mod:`hyperrotor.paper.verify` compares it with the
package's derivations (``hyperrotor verify`` on the command line).
"""
from .verify import STATUSES, Verdict, render
from .verify import verify as verify_paper

__all__ = ["verify_paper", "Verdict", "render", "STATUSES"]
