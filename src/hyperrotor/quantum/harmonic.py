r"""Harmonic homogeneous polynomials: eigenfunctions of the so(N) Casimir.

The space :math:`\mathcal H_l^N` of harmonic (:math:`\Delta h = 0`) homogeneous
polynomials of degree ``l`` in ``N`` variables carries the irreducible so(N)
representation of highest weight ``(l, 0, ..., 0)``. By the operator identity
:math:`C_2 = \sum_{i<j} (L^{ij})^2 = r^2\Delta - E(E + N - 2)`
(:func:`hyperrotor.quantum.operators.casimir_operator`) every
:math:`h \in \mathcal H_l^N` satisfies :math:`C_2 h = -l(l+N-2)\,h`, and

.. math:: \dim \mathcal H_l^N = \binom{l+N-1}{N-1} - \binom{l+N-3}{N-1}.

Construction (exact, no linear solve)
-------------------------------------
For every monomial :math:`p = x'^{a} x_N^{\varepsilon}` of degree ``l`` with
:math:`\varepsilon \in \{0, 1\}` (``x' = (x_1, ..., x_{N-1})``) put
:math:`q_0 = x'^a` and
:math:`q_{k+1} = -\Delta' q_k / ((2k+\varepsilon+2)(2k+\varepsilon+1))`; then
:math:`h = \sum_k x_N^{2k+\varepsilon} q_k` is harmonic and contains exactly one
monomial with :math:`x_N`-degree below 2, namely ``p``. These ``h`` are therefore
linearly independent, and there are exactly :math:`\dim\mathcal H_l^N` of them.

Polynomials are handled as exact coefficient dicts ``{exponent tuple: c}``
(see :mod:`hyperrotor.quantum.normal_form`).
"""
from __future__ import annotations

import math
from fractions import Fraction
from functools import lru_cache
from math import comb, gcd, lcm
from typing import Any, Mapping

import numpy as np
import sympy as sp

from .. import _parse, _pricing, _validate
from ..conventions import check_dimension
from .differential_operator import DifferentialOperator, coordinate_symbols, to_coordinates
from .normal_form import WeylElement, dict_to_polynomial, polynomial_to_dict

__all__ = [
    "harmonic_dimension",
    "harmonic_polynomial_basis",
    "sphere_monomial_integral",
    "sphere_inner_product",
    "orthogonal_harmonic_basis",
    "orthonormal_harmonic_basis",
    "apply_to_polynomial",
]


def _check_degree(l: Any) -> int:
    if isinstance(l, bool) or not isinstance(l, (int, np.integer, sp.Integer)):
        raise TypeError(f"the degree l must be an integer >= 0, got {l!r} of type {type(l).__name__}")
    l = int(l)
    if l < 0:
        raise ValueError(f"the degree l must be an integer >= 0, got {l}")
    return l


def _check_size(N: int, l: int, entry: str = "harmonic_polynomial_basis") -> None:
    """Refuse a harmonic space over ``options["quantum_max_harmonic_dim"]`` or ``["max_seconds"]`` before any work."""
    _pricing.check(entry, N=N, l=l)


def harmonic_dimension(N: int, l: int) -> int:
    r"""Dimension :math:`\binom{l+N-1}{N-1} - \binom{l+N-3}{N-1}` of the degree-``l`` harmonics in ``N`` variables."""
    N, l = check_dimension(N), _check_degree(l)
    return comb(l + N - 1, N - 1) - (comb(l + N - 3, N - 1) if l >= 2 else 0)


# ----------------------------------------------------------------------------
# construction
# ----------------------------------------------------------------------------
def _compositions(total: int, parts: int):
    """All exponent tuples of length ``parts`` summing to ``total`` (lexicographically decreasing)."""
    if parts == 1:
        yield (total,)
        return
    for first in range(total, -1, -1):
        for rest in _compositions(total - first, parts - 1):
            yield (first,) + rest


def _laplacian_prime(q: Mapping, n: int) -> dict:
    """Laplacian in the first ``n`` variables of a coefficient dict."""
    out: dict = {}
    for m, c in q.items():
        for i in range(n):
            if m[i] >= 2:
                mm = list(m)
                mm[i] -= 2
                key = tuple(mm)
                v = out.get(key, 0) + c * m[i] * (m[i] - 1)
                if v:
                    out[key] = v
                else:
                    out.pop(key, None)
    return out


def _integerize(p: dict) -> dict:
    """Scale a rational dict to coprime integers with a positive first (largest) monomial."""
    den = 1
    for c in p.values():
        den = lcm(den, Fraction(c).denominator)
    ints = {m: int(Fraction(c) * den) for m, c in p.items()}
    g = 0
    for c in ints.values():
        g = gcd(g, c)
    return {m: c // g for m, c in ints.items()}


@lru_cache(maxsize=64)
def _harmonic_dicts(N: int, l: int) -> tuple:
    out = []
    for eps in (0, 1):
        if l - eps < 0:
            continue
        for a in _compositions(l - eps, N - 1):
            q = {a: Fraction(1)}
            h: dict = {}
            k = 0
            while q:
                for m, c in q.items():
                    h[m + (2 * k + eps,)] = c
                q = _laplacian_prime(q, N - 1)
                den = (2 * k + eps + 2) * (2 * k + eps + 1)
                q = {m: -c / den for m, c in q.items()}
                k += 1
            out.append(_integerize(h))
    return tuple(out)


def harmonic_polynomial_basis(N: int, l: int, coordinates: Any = None, *, as_dict: bool = False) -> list:
    r"""A basis of the harmonic homogeneous polynomials of degree ``l`` in ``N`` variables.

    Parameters
    ----------
    N : int
        Number of variables, ``N >= 2``.
    l : int
        Degree, ``l >= 0``.
    coordinates : None, "paper" or sequence
        As in :func:`hyperrotor.quantum.operators.coordinate_symbols`.
    as_dict : bool
        Return exact coefficient dicts ``{exponent tuple: int}`` instead of SymPy
        expressions (fast path for :func:`apply_to_polynomial`).

    Returns
    -------
    list
        :func:`harmonic_dimension` ``(N, l)`` polynomials with coprime integer
        coefficients; the ``k``-th one is the unique harmonic polynomial whose
        only monomial of :math:`x_N`-degree below 2 is the ``k``-th monomial
        :math:`x'^a x_N^\varepsilon` (module docstring). Each is an eigenfunction
        of the Casimir :math:`\sum_{i<j} (L^{ij})^2` with eigenvalue
        :math:`-l(l+N-2)`. The basis is not orthogonal; see
        :func:`orthogonal_harmonic_basis`.

    Examples
    --------
    >>> harmonic_polynomial_basis(3, 2)
    [x1**2 - x3**2, x1*x2, x2**2 - x3**2, x1*x3, x2*x3]
    """
    N, l = check_dimension(N), _check_degree(l)
    as_dict = _validate.flag("as_dict", as_dict)
    _check_size(N, l)
    dicts = _harmonic_dicts(N, l)
    if as_dict:
        return [dict(d) for d in dicts]
    coords = coordinate_symbols(N, coordinates)
    return [dict_to_polynomial(d, coords) for d in dicts]


# ----------------------------------------------------------------------------
# sphere integrals
# ----------------------------------------------------------------------------
def _double_factorial_odd(k: int) -> int:
    """(k-1)!! for even k >= 0 (= 1*3*...*(k-1))."""
    r = 1
    for t in range(1, k, 2):
        r *= t
    return r


def _sphere_mean(a: tuple, N: int) -> Fraction:
    if any(e % 2 for e in a):
        return Fraction(0)
    num = 1
    for e in a:
        num *= _double_factorial_odd(e)
    den = 1
    for t in range(sum(a) // 2):
        den *= N + 2 * t
    return Fraction(num, den)


def _sphere_area(N: int) -> sp.Expr:
    return 2 * sp.pi ** sp.Rational(N, 2) / sp.gamma(sp.Rational(N, 2))


def sphere_monomial_integral(exponents: Any, *, normalized: bool = False):
    r"""Exact :math:`\int_{S^{N-1}} x^a\, dS` of a monomial over the unit sphere.

    .. math:: \int_{S^{N-1}} x^a\,dS = 0 \text{ unless all } a_i \text{ are even, else }
              2\,\frac{\prod_i \Gamma(\tfrac{a_i+1}{2})}{\Gamma(\tfrac{|a|+N}{2})}.

    With ``normalized=True`` the mean over the sphere (divided by the area
    :math:`2\pi^{N/2}/\Gamma(N/2)`), the rational
    :math:`\prod_i (a_i-1)!!\,/\,\prod_{t=0}^{|a|/2-1}(N+2t)`, is returned as a
    SymPy Rational.
    """
    if isinstance(exponents, (str, bytes, Mapping)) or not hasattr(exponents, "__iter__"):
        raise TypeError(f"exponents must be a sequence of integers >= 0, got {_validate.fmt(exponents)}")
    a = tuple(_validate.integer("exponents entry", e, minimum=0) for e in exponents)
    normalized = _validate.flag("normalized", normalized)
    if not a or min(a) < 0:
        raise ValueError(f"exponents must be a non-empty sequence of integers >= 0, got {exponents!r}")
    if len(a) > 1:
        check_dimension(len(a), name="the number of exponents (N)")
    _pricing.check("sphere_integral", degree=sum(a))
    mean = _sphere_mean(a, len(a))
    r = sp.Rational(mean.numerator, mean.denominator)
    return r if normalized else sp.simplify(r * _sphere_area(len(a)))


@_pricing.model("sphere_integral", "polynomials of lower degree")
def _sphere_integral_cost(degree: int, terms: int = 1, dense: bool = False) -> tuple:
    """Seconds of exact sphere means: ~3e-10 * degree^2 per pair of monomials (double factorials of big ints);
    ``dense=True``: of reading SymPy polynomials first (~5e-6 s per degree, SymPy's dense form, and ~2e-5 s
    per monomial of the expansion)."""
    if dense:
        return (_pricing.Cost(f"reading SymPy polynomials of total degree up to {degree} ({float(terms):.3g} monomials)",
                              5e-6 * float(degree) + 2e-5 * float(terms), "max_seconds", "seconds"),)
    return (_pricing.Cost(f"{terms} exact sphere integral(s) of total degree {degree}",
                          3e-10 * float(terms) * float(degree) ** 2, "max_seconds", "seconds"),)


def _size_bound(p: Any, coords: tuple) -> tuple[int, float]:
    """Upper bounds ``(total degree, number of monomials)`` of ``p`` in the coordinates, from its expression
    tree (no expansion): sums add, products multiply, powers of sums count like products."""
    if isinstance(p, Mapping):
        return max((sum(m) for m in p), default=0), float(len(p))
    if not isinstance(p, sp.Basic):
        return 0, 1.0
    names = {str(x) for x in coords}
    n = len(coords)

    def cap(d: int, t: float) -> tuple[int, float]:
        return d, min(t, float(comb(d + n - 1, n - 1)) if d < 10**6 else math.inf)

    def walk(e) -> tuple[int, float]:
        if isinstance(e, sp.Symbol):
            return (1, 1.0) if str(e) in names else (0, 1.0)
        if isinstance(e, sp.Pow) and e.exp.is_Integer and e.exp >= 0:
            d, t = walk(e.base)
            k = int(e.exp)
            return cap(k * d, math.inf if t > 1 and k * math.log2(t) > 1000 else (t ** k if t > 1 else 1.0))
        parts = [walk(a) for a in e.args]
        if isinstance(e, sp.Mul):
            return cap(sum(d for d, _ in parts), min(math.prod(t for _, t in parts), math.inf))
        if isinstance(e, sp.Add):
            return cap(max((d for d, _ in parts), default=0), sum(t for _, t in parts))
        return cap(max((d for d, _ in parts), default=0), max((t for _, t in parts), default=1.0))

    return walk(p)


def _as_dict(p: Any, coords: tuple) -> dict:
    if isinstance(p, Mapping):
        return dict(p)
    p, _ = to_coordinates(p, coords)  # symbols named like a coordinate are that coordinate
    return polynomial_to_dict(p, coords)


def _inner_dicts(p: Mapping, q: Mapping, N: int):
    total = 0
    for m1, c1 in p.items():
        c1 = sp.conjugate(c1) if isinstance(c1, sp.Basic) else c1
        for m2, c2 in q.items():
            w = _sphere_mean(tuple(x + y for x, y in zip(m1, m2)), N)
            if w:
                total += c1 * c2 * w
    return total


def sphere_inner_product(p: Any, q: Any, N: int, coordinates: Any = None, *, normalized: bool = False):
    r"""Exact :math:`\langle p, q\rangle = \int_{S^{N-1}} \overline{p}\,q\,dS` of two polynomials.

    Parameters
    ----------
    p, q : SymPy polynomials in the coordinates, or coefficient dicts.
    N : int
    coordinates : see :func:`hyperrotor.quantum.operators.coordinate_symbols`.
    normalized : bool
        If True, integrate against the normalized measure (mean over the
        sphere); the result is then rational for rational coefficients.
        Otherwise the surface measure (:func:`sphere_monomial_integral`).

    Returns
    -------
    SymPy number (exact).
    """
    N = check_dimension(N)
    normalized = _validate.flag("normalized", normalized)
    coords = coordinate_symbols(N, coordinates)
    (dp, tp), (dq, tq) = _size_bound(p, coords), _size_bound(q, coords)
    _pricing.check("sphere_integral", degree=dp + dq, terms=tp + tq, dense=True)
    pd, qd = _as_dict(p, coords), _as_dict(q, coords)
    _pricing.check("sphere_integral", degree=max(map(sum, pd), default=0) + max(map(sum, qd), default=0),
                   terms=len(pd) * len(qd))
    total = _inner_dicts(pd, qd, N)
    total = sp.nsimplify(total) if isinstance(total, float) else _parse.to_sympy(total, "the inner product", text=False)
    return sp.expand(total) if normalized else sp.simplify(total * _sphere_area(N))


# ----------------------------------------------------------------------------
# orthogonal / orthonormal bases
# ----------------------------------------------------------------------------
@lru_cache(maxsize=32)
def _orthogonal(N: int, l: int):
    basis = _harmonic_dicts(N, l)
    monos = list(_compositions(l, N))
    pos = {m: k for k, m in enumerate(monos)}
    B = np.zeros((len(basis), len(monos)), dtype=object)
    B[:] = 0
    for r, h in enumerate(basis):
        for m, c in h.items():
            B[r, pos[m]] = int(c)
    # Gram of monomials, common denominator D = N (N+2) ... (N+2l-2)
    D = 1
    for t in range(l):
        D *= N + 2 * t
    G = np.zeros((len(monos), len(monos)), dtype=object)
    G[:] = 0
    for i, m1 in enumerate(monos):
        for j, m2 in enumerate(monos):
            w = _sphere_mean(tuple(x + y for x, y in zip(m1, m2)), N)
            if w:
                G[i, j] = int(w * D)
    gram = (B @ G) @ B.T  # integer matrix = D * Gram
    n = len(basis)
    # exact Gram-Schmidt: coefficient rows T (rational) with T gram T^T diagonal
    T = [[Fraction(int(r == c)) for c in range(n)] for r in range(n)]
    gramF = [[Fraction(int(gram[r, c]), D) for c in range(n)] for r in range(n)]
    norms: list = []
    for r in range(n):
        for s in range(r):
            # <v_r, u_s> with u_s = sum_c T[s][c] h_c
            ip = sum(T[s][c] * gramF[c][r] for c in range(s + 1) if T[s][c])
            if ip:
                f = ip / norms[s]
                for c in range(s + 1):
                    if T[s][c]:
                        T[r][c] -= f * T[s][c]
        nr = sum(T[r][a] * T[r][b] * gramF[a][b] for a in range(r + 1) if T[r][a] for b in range(r + 1) if T[r][b])
        norms.append(nr)
    polys = []
    for r in range(n):
        acc: dict = {}
        for c in range(r + 1):
            if T[r][c]:
                for m, v in basis[c].items():
                    acc[m] = acc.get(m, 0) + T[r][c] * v
        polys.append({m: v for m, v in acc.items() if v})
    return tuple(polys), tuple(norms)


def orthogonal_harmonic_basis(N: int, l: int) -> tuple[list, list]:
    r"""Exact orthogonal basis of the degree-``l`` harmonics for the sphere inner product.

    Gram-Schmidt (exact rational arithmetic) of :func:`harmonic_polynomial_basis`
    in its order, with respect to the **normalized** sphere measure
    (:func:`sphere_inner_product` with ``normalized=True``).

    Returns
    -------
    (polys, norms2)
        ``polys``: list of coefficient dicts ``{exponent tuple: Fraction}``;
        ``norms2``: list of their squared norms (Fractions, > 0). An orthonormal
        basis is ``polys[k] / sqrt(norms2[k])``; for the unnormalized surface
        measure divide further by ``sqrt(area)``. Representation matrices of the
        :math:`L^{ij}` in the orthonormal basis are then
        ``<u_a, L u_b> / sqrt(n_a n_b)`` (real antisymmetric).
    """
    N, l = check_dimension(N), _check_degree(l)
    _check_size(N, l, "orthogonal_harmonic_basis")
    polys, norms = _orthogonal(N, l)
    return [dict(p) for p in polys], list(norms)


def orthonormal_harmonic_basis(N: int, l: int, coordinates: Any = None, *, exact: bool = True) -> list:
    r"""Orthonormal basis of the degree-``l`` harmonics, normalized sphere measure.

    ``exact=True``: SymPy expressions with rational coefficients times
    ``1/sqrt(norm2)`` (exact square roots). ``exact=False``: the same with
    floating-point coefficients (SymPy Floats). With respect to the surface
    measure divide by :math:`\sqrt{|S^{N-1}|}`.
    """
    N, l = check_dimension(N), _check_degree(l)
    exact = _validate.flag("exact", exact)
    _check_size(N, l, "orthonormal_harmonic_basis")
    coords = coordinate_symbols(N, coordinates)
    polys, norms = _orthogonal(N, l)
    out = []
    for p, n2 in zip(polys, norms):
        expr = dict_to_polynomial(p, coords)
        s = 1 / sp.sqrt(sp.Rational(n2.numerator, n2.denominator))
        out.append(sp.expand(s * expr) if exact else sp.expand(sp.Float(float(s), 17) * expr))
    return out


def apply_to_polynomial(op: Any, poly: Any, coordinates: Any = None):
    """Apply an operator to a polynomial exactly, on coefficient dicts.

    Parameters
    ----------
    op : DifferentialOperator or WeylElement
    poly : coefficient dict ``{exponent tuple: c}`` (returns a dict) or a SymPy
        polynomial in the operator's coordinates (returns a SymPy expression).
    coordinates : only needed for a SymPy ``poly`` with a bare ``WeylElement``.
    """
    if isinstance(op, DifferentialOperator):
        return op.apply_to_polynomial(poly)
    if isinstance(op, WeylElement):
        if isinstance(poly, Mapping):
            return op.apply_to_poly(poly)
        coords = coordinate_symbols(op.N, coordinates)
        poly, back = to_coordinates(poly, coords)
        out = dict_to_polynomial(op.apply_to_poly(polynomial_to_dict(poly, coords)), coords)
        return out.xreplace(back) if back else out
    raise TypeError(f"op must be a DifferentialOperator or a WeylElement, got {type(op).__name__}")
