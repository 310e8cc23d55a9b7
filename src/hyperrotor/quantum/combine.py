r"""Representations of so(N) combined: tensor products and direct sums.

Both keep the conventions of :mod:`.representation` (the brackets of the plane
basis :math:`E_{(ij)}`): :math:`X_{(ij)} \otimes 1 + 1 \otimes Y_{(ij)}` and
block-diagonal generators satisfy them whenever the factors do. Exact SymPy
generators are combined on demand by picklable recipes (module-level functions
under :func:`functools.partial`), so the results pickle.
"""
from __future__ import annotations

from functools import partial

import scipy.sparse as sps

from .. import _pricing
from .._lazy import sympy as sp
from ..conventions import planes
from .representation import Representation, check_same_algebra

__all__ = ["tensor", "direct_sum"]


def tensor(a: Representation, b: Representation) -> Representation:
    r"""Tensor product: :math:`X_{(ij)} \otimes 1 + 1 \otimes Y_{(ij)}` (Kronecker order a, b).

    Reducible in general (``highest_weight=None``) unless a factor is trivial.
    """
    check_same_algebra(a, b)
    ga, gb = a.generators(format="csr"), b.generators(format="csr")
    _pricing.check("tensor", dim_a=a.dim, dim_b=b.dim, nnz_a=sum(g.nnz for g in ga.values()),
                   nnz_b=sum(g.nnz for g in gb.values()))
    Ia, Ib = sps.identity(a.dim, format="csr"), sps.identity(b.dim, format="csr")
    gens = {p: sps.kron(ga[p], Ib, format="csr") + sps.kron(Ia, gb[p], format="csr") for p in a.planes}
    hw = None
    if a.dim == 1 and a.highest_weight is not None and all(x == 0 for x in a.highest_weight):
        hw = b.highest_weight
    elif b.dim == 1 and b.highest_weight is not None and all(x == 0 for x in b.highest_weight):
        hw = a.highest_weight
    exact = partial(_tensor_exact, a, b) if a.has_exact_generators and b.has_exact_generators else None
    return Representation(a.N, gens, highest_weight=hw, exact_generators=exact, name=f"({a.name}) x ({b.name})")


def direct_sum(*reps: Representation) -> Representation:
    """Direct sum (block diagonal generators, blocks in argument order)."""
    if not reps:
        raise ValueError("direct_sum needs at least one Representation")
    check_same_algebra(*reps)
    N = reps[0].N
    each = [r.generators(format="csr") for r in reps]
    gens = {p: sps.block_diag([g[p] for g in each], format="csr") for p in planes(N)}
    hw = reps[0].highest_weight if len(reps) == 1 else None
    exact = partial(_direct_sum_exact, reps) if all(r.has_exact_generators for r in reps) else None
    return Representation(N, gens, highest_weight=hw, exact_generators=exact, name=" + ".join(f"({r.name})" for r in reps))


def _tensor_exact(a: Representation, b: Representation) -> dict:
    """Exact generators of ``tensor(a, b)``: Kronecker sums of the factors' exact matrices."""
    ea, eb = a.exact_generators(), b.exact_generators()
    return {p: sp.kronecker_product(ea[p], sp.eye(b.dim)) + sp.kronecker_product(sp.eye(a.dim), eb[p]) for p in a.planes}


def _direct_sum_exact(reps: tuple) -> dict:
    """Exact generators of ``direct_sum(*reps)``: block-diagonal exact matrices."""
    ex = [r.exact_generators() for r in reps]
    return {p: sp.diag(*[e[p] for e in ex]) for p in reps[0].planes}
