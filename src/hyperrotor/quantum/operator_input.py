r"""Operators given by the user: conversion to CSR and the checks every quantum entry point shares.

:func:`as_csr` is the package's one converter of user operators (``qutip.Qobj``, scipy.sparse,
2-D arrays); :func:`operator_mapping` reads a mapping plane -> operator; :func:`check_antihermitian`
checks generators :math:`X^\dagger = -X` (the anti-Hermitian form of docs/conventions.md);
``format=`` of the matrix-returning methods is one of :data:`FORMATS`.
"""
from __future__ import annotations

from typing import Any, Mapping

import numpy as np
import scipy.sparse as sps

from .. import _pricing, _validate
from .._options import options

__all__ = ["as_csr", "check_antihermitian"]

#: The matrix formats of :meth:`Representation.generator` and friends.
FORMATS = ("csr", "dense")


def check_format(format: str) -> str:
    if format is None:
        return "csr"
    return _validate.choice("format", format, FORMATS)


def as_format(M, format: str):
    if format == "dense":
        _pricing.check("dense_matrix", dim=M.shape[0])
        return M.toarray()
    return M.tocsr() if not sps.isspmatrix_csr(M) else M


def as_csr(M: Any, name: str = "operator") -> sps.csr_matrix:
    """A square operator given as ``qutip.Qobj``, scipy.sparse matrix or 2-D array, as CSR.

    The package's one converter of user operators (QuTiP is recognised by duck
    typing, so no QuTiP import is needed for sparse or dense input). Integer
    matrices become float; complex ones with zero imaginary part become real.
    Non-finite entries are refused. ``name`` names the operator in messages.
    """
    if not isinstance(name, str) or not name:
        raise TypeError(f"name must be a non-empty string (the operator's name in messages), got {_validate.fmt(name)}")
    # a copy, in canonical format: the caller's matrix (or the Qobj's data, which as_scipy() views) never
    # shares its arrays with the result, so canonicalizing it in place (scipy's max, sum_duplicates) cannot
    # reorder the caller's indices under its data (it did: an irrep's non-canonical generator was scrambled)
    if hasattr(M, "isoper") and hasattr(M, "to") and hasattr(M, "dims"):  # qutip.Qobj
        if not M.isoper:
            raise ValueError(f"{name} must be an operator, got a Qobj of type {M.type!r}")
        mat = sps.csr_matrix(M.to("CSR").data.as_scipy(), copy=True)
    elif sps.issparse(M):
        mat = sps.csr_matrix(M, copy=True)
    elif isinstance(M, np.ndarray):
        _validate.numeric_input(name, M)  # booleans, dates, masked arrays (the mask would be dropped)
        arr = np.asarray(M)
        if arr.ndim != 2:
            raise ValueError(f"{name} must be a 2-D matrix, got an array of shape {arr.shape}")
        if arr.dtype.kind not in "biufc":
            raise TypeError(f"{name} must be numeric, got dtype {arr.dtype}")
        mat = sps.csr_matrix(arr)
    else:
        raise TypeError(f"{name} must be a qutip.Qobj, a scipy.sparse matrix or a 2-D ndarray, got {type(M).__name__}")
    if mat.shape[0] != mat.shape[1]:
        raise ValueError(f"{name} must be square, got shape {mat.shape}")
    mat.sum_duplicates()  # (sorted indices, no duplicates: on the copy)
    if mat.dtype.kind not in "fc":
        mat = mat.astype(float)
    if not np.all(np.isfinite(mat.data)):
        k = int(np.argmax(~np.isfinite(mat.data)))
        row = int(np.searchsorted(mat.indptr, k, side="right") - 1)
        raise ValueError(f"{name} must be finite; {name}[{row}, {int(mat.indices[k])}] = {_validate.fmt(mat.data[k])}")
    return real_if_possible(mat)


def real_if_possible(mat: sps.csr_matrix) -> sps.csr_matrix:
    if mat.dtype.kind == "c" and (mat.nnz == 0 or not np.any(mat.data.imag)):
        return sps.csr_matrix(mat.real)
    return mat


def max_abs(M: sps.spmatrix) -> float:
    return float(abs(M).max()) if M.nnz else 0.0


def check_antihermitian(generators: Mapping, *, form: str = "antihermitian") -> None:
    r"""Raise ``ValueError`` unless every :math:`X` of ``{plane: X}`` satisfies :math:`X^\dagger = -X`.

    Tolerance: ``options["quantum_hermiticity_rtol"]`` times :math:`\max|X|`.
    When a generator is Hermitian instead, the message says to pass
    ``form="hermitian"`` (``form`` names what the caller declared). Each ``X``
    is a square matrix as :func:`as_csr` takes it (Qobj, scipy.sparse, ndarray).
    """
    if not isinstance(generators, Mapping):
        raise TypeError(f"generators must be a mapping plane -> matrix, got {_validate.fmt(generators)} "
                        f"of type {type(generators).__name__}")
    form = _validate.form(form)
    rtol = options["quantum_hermiticity_rtol"]
    for p, X in generators.items():
        X = as_csr(X, f"generators[{_validate.fmt(p)}]")
        scale = max(1.0, max_abs(X))
        anti = max_abs(X + X.conj().T)
        if anti > rtol * scale:
            herm = max_abs(X - X.conj().T) <= rtol * scale
            hint = (
                '; it is Hermitian: the operators look like L = -i hbar X, pass form="hermitian"'
                if herm and form == "antihermitian" else ""
            )
            raise ValueError(
                f"generator of plane {p} is not anti-Hermitian: max |X + X^dagger| = {anti:.3g} "
                f"> {rtol:.3g} * max|X| (options['quantum_hermiticity_rtol']){hint}"
            )


def operator_mapping(value: Any, name: str = "generators") -> tuple[int, dict]:
    """``(N, {plane: csr})`` of a mapping plane -> operator (Qobj, sparse, array), ``N`` from the number of planes.

    The one reader of user operator mappings (:meth:`Representation.from_qobj`,
    :func:`~.hamiltonian.rotor_hamiltonian`); ``name`` names the argument in messages.
    """
    if not isinstance(value, Mapping):
        raise TypeError(
            f"{name} must be a mapping plane -> operator (qutip.Qobj, scipy.sparse or 2-D array), "
            f"got {type(value).__name__}"
        )
    N = _validate.dimension_from_count(len(value), name=name, what="planes")
    mats = {}
    for p, M in value.items():
        try:
            q = _validate.plane(p, N)
        except ValueError as exc:
            raise ValueError(f"{name}: the keys must be planes (i, j) of so({N}); {exc}") from None
        if q in mats:
            raise ValueError(f"{name} name the plane {q} twice")
        mats[q] = as_csr(M, f"{name}[{q}]")
    return N, mats
