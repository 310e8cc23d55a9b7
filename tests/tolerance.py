"""Round-off tolerances that scale with dimension, norm and run length.

A test that compares a numerically built matrix (or a long run) with its exact value must
not use a fixed absolute bound such as ``1e-14``: the round-off grows with the size of the
problem and differs between BLAS builds and machines. The model used here:

* one inner product of length ``d`` has a rounding error of at most ``gamma_d ~ d * eps``
  times the sum of the absolute products, so every entry of a ``d x d`` product ``A B`` is
  off by at most ``~ d * eps * ||A|| ||B||`` (``||.||`` the Frobenius norm, which bounds
  ``|| |A| ||_2``); sums of ``m`` such terms (a Casimir, a commutator) add a factor ``m``,
  which the constant ``k`` absorbs;
* a run of ``n`` steps that each round independently random-walks: ``sqrt(n)`` times the
  one-step error (``walk="sqrt"``, the default); systematic accumulation is linear in ``n``
  (``walk="linear"``).

Hence ``scaled_tol(*operands, k, dim, steps) = k * eps * dim * max_i norm(operand_i)
[* sqrt(steps) or * steps]``. For a product or commutator pass the product of the norms as
one operand, e.g. ``scaled_tol(norm(X) * norm(Y), dim=d)``. ``k`` is a small safety constant
(stated where used, usually 4..64); it is not a knob to make a failing test pass: a
residual that needs ``k`` in the thousands means the algorithm, not the tolerance, is off.

Exact results (SymPy equality, integer data, exact rationals) are compared exactly and do
not use this module.
"""
from __future__ import annotations

import numpy as np

EPS = float(np.finfo(float).eps)

__all__ = ["EPS", "norm", "row_length", "scaled_tol", "assert_close"]


def norm(x) -> float:
    """Size of an operand: |x| for a number, the 2-norm of a vector, the Frobenius norm of a
    matrix (dense or scipy.sparse), and for a stack of matrices (ndim > 2) the largest Frobenius
    norm of one matrix."""
    if hasattr(x, "tocsr"):  # scipy.sparse
        return float(np.sqrt((np.abs(x.tocsr().data) ** 2).sum()))
    a = np.asarray(x)
    if a.dtype == object:
        a = a.astype(complex)
    if a.ndim == 0:
        return float(abs(a))
    if a.size == 0:
        return 0.0
    if a.ndim == 1:
        return float(np.linalg.norm(a))
    return float(np.sqrt((np.abs(a) ** 2).sum(axis=(-2, -1))).max())


def row_length(*matrices) -> int:
    """Longest row (most stored entries) of sparse or dense matrices: the inner-product length
    that sets the round-off of a product with a sparse matrix (use it as ``dim=``)."""
    out = 1
    for m in matrices:
        if hasattr(m, "tocsr"):
            m = m.tocsr()
            out = max(out, int(np.diff(m.indptr).max()) if m.shape[0] else 1)
        else:
            out = max(out, int((np.asarray(m) != 0).sum(axis=-1).max()) if np.size(m) else 1)
    return out


def _dim(operands) -> int:
    dims = [np.shape(x)[-1] for x in operands if np.ndim(x) >= 1]
    return max(dims) if dims else 1


def scaled_tol(*operands, k: float = 4.0, dim: int | None = None, steps: int | None = None,
               walk: str = "sqrt") -> float:
    """Absolute round-off tolerance ``k * eps * dim * max(norm(op)) * growth(steps)``.

    Parameters
    ----------
    *operands : numbers or arrays
        The quantities whose size sets the scale (see :func:`norm`); a number is taken as
        an already computed norm (pass ``norm(A) * norm(B)`` for a product). With no
        operand the scale is 1.
    k : float
        Safety constant of the bound (default 4).
    dim : int, optional
        Length of the inner products (matrix dimension); default: the largest last-axis
        length of the array operands, 1 if there are none.
    steps : int, optional
        Number of steps of a run; multiplies by ``sqrt(steps)`` (``walk="sqrt"``, the
        random walk of independent roundings) or by ``steps`` (``walk="linear"``).
    """
    if walk not in ("sqrt", "linear"):
        raise ValueError(f"walk must be 'sqrt' or 'linear', got {walk!r}")
    scale = max((norm(x) for x in operands), default=1.0)
    if scale == 0.0:
        scale = 1.0
    d = _dim(operands) if dim is None else int(dim)
    growth = 1.0
    if steps is not None:
        growth = float(np.sqrt(steps)) if walk == "sqrt" else float(steps)
    return k * EPS * max(d, 1) * scale * growth


def assert_close(actual, desired, *operands, k: float = 4.0, dim: int | None = None,
                 steps: int | None = None, walk: str = "sqrt", err_msg: str = "") -> None:
    """``np.testing.assert_allclose(actual, desired, rtol=0, atol=scaled_tol(...))``; the
    operands default to ``(actual, desired)``."""
    ops = operands if operands else (actual, desired)
    tol = scaled_tol(*ops, k=k, dim=dim, steps=steps, walk=walk)
    np.testing.assert_allclose(actual, desired, rtol=0, atol=tol, err_msg=err_msg)
