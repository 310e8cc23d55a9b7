r"""Weights of so(N) irreps: validation, Dynkin labels, Weyl dimension, Freudenthal multiplicities.

Conventions
-----------
so(N) has rank :math:`n = \lfloor N/2 \rfloor`; it is of type :math:`B_n` for
odd ``N = 2n + 1`` and :math:`D_n` for even ``N = 2n``. Weights are written in
the *orthogonal basis* :math:`\mu = (\mu_1, \dots, \mu_n)`, where
:math:`\mu_k` is the eigenvalue of the Hermitian Cartan generator
:math:`H_k = -i\,X_{(2k-1,\,2k)}` (``hbar = 1``), :math:`X_{(ij)}` being the
representation of the plane basis element :math:`E_{(ij)}` of
:mod:`hyperrotor.conventions`. In the vector representation :math:`H_k` has
eigenvalue :math:`\pm 1` on :math:`e_{2k-1} \pm i\,e_{2k}`.

Highest weights :math:`m = (m_1, \dots, m_n)` are *dominant*:

* :math:`B_n`: :math:`m_1 \ge m_2 \ge \dots \ge m_n \ge 0`;
* :math:`D_n`: :math:`m_1 \ge \dots \ge m_{n-1} \ge |m_n|` (the last entry is signed);
* so(2) (abelian, :math:`n = 1`): any single :math:`m_1`;

with all entries integers (tensor representations) or all half-integers
(spinorial representations). Positive roots: :math:`e_i \pm e_j` (:math:`i < j`)
and, for :math:`B_n`, :math:`e_i`. Simple roots: :math:`e_i - e_{i+1}`
(:math:`i < n`) and :math:`e_n` (:math:`B_n`) or :math:`e_{n-1} + e_n`
(:math:`D_n`); Dynkin labels are numbered in that order (so for :math:`D_n` the
label :math:`a_n` belongs to :math:`e_{n-1} + e_n`, and :math:`a_n = 1` alone
is the spinor of highest weight :math:`(\tfrac12, \dots, \tfrac12)`).

All values are exact :class:`fractions.Fraction` objects.
"""
from __future__ import annotations

import math
from fractions import Fraction
from numbers import Integral, Rational
from collections.abc import Mapping, Set
from typing import Any, Sequence

import numpy as np
import sympy as sp

from hyperrotor import _pricing, _validate
from hyperrotor.conventions import check_dimension

__all__ = [
    "rank",
    "check_highest_weight",
    "is_dominant",
    "dominates",
    "dynkin_to_orthogonal",
    "orthogonal_to_dynkin",
    "weyl_dimension",
    "casimir_eigenvalue",
    "positive_roots",
    "simple_roots",
    "weight_multiplicities",
]


def rank(N: int) -> int:
    """Rank ``floor(N/2)`` of so(N) (number of entries of a weight)."""
    return check_dimension(N) // 2


def _to_fraction(x: Any, what: str = "weight entry") -> Fraction:
    """Exact Fraction of an int, half-integer float, Fraction or SymPy rational."""
    if isinstance(x, bool):
        raise TypeError(f"{what} must be a number, got the bool {x!r}")
    if isinstance(x, (Integral, np.integer)):
        return Fraction(int(x))
    if isinstance(x, Fraction):
        return x
    if isinstance(x, sp.Basic):
        if x.is_Rational:
            return Fraction(int(x.p), int(x.q))
        raise TypeError(f"{what} must be a rational number, got the SymPy expression {x!r}")
    if isinstance(x, Rational):
        return Fraction(x.numerator, x.denominator)
    if isinstance(x, (float, np.floating)):
        if not np.isfinite(x):
            raise ValueError(f"{what} must be finite, got {x!r}")
        f = Fraction(float(x))
        if f.denominator > 2:
            raise ValueError(f"{what} must be an integer or a half-integer, got {x!r}")
        return f
    raise TypeError(
        f"{what} must be an int, float, fractions.Fraction or sympy.Rational, got {x!r} of type {type(x).__name__}"
    )


def _check_sequence(name: str, value: Any, what: str) -> None:
    """``TypeError`` unless ``value`` is a sequence (tuple, list, 1-D array): a dict or a set gave its keys or
    members in no promised order ({0: 1} was the trivial irrep), a 0-d array a bare "len() of unsized object"."""
    if (isinstance(value, (str, bytes, Mapping, Set)) or not hasattr(value, "__len__")
            or isinstance(value, np.ndarray) and value.ndim != 1):
        raise TypeError(f"{name} must be a sequence of {what} (a tuple, list or 1-D array), got {_validate.fmt(value)}")


def check_highest_weight(N: int, highest_weight: Any) -> tuple[Fraction, ...]:
    """Validate a highest weight of so(N) in the orthogonal basis; return it as exact Fractions.

    Parameters
    ----------
    N : int
        ``N >= 2``.
    highest_weight : sequence
        ``floor(N/2)`` entries (int, float such as ``0.5``, ``Fraction`` or
        ``sympy.Rational``), all integers or all half-integers, dominant (see the
        module docstring).

    Raises
    ------
    TypeError, ValueError
        Naming the bad value and what is allowed.
    """
    N = check_dimension(N)
    n = N // 2
    _check_sequence("highest_weight", highest_weight, f"{n} numbers for so({N})")
    if len(highest_weight) != n:
        raise ValueError(
            f"highest_weight of so({N}) has floor(N/2) = {n} entries (orthogonal basis), "
            f"got {len(highest_weight)}: {tuple(highest_weight)!r}"
        )
    m = tuple(_to_fraction(v, "highest_weight entry") for v in highest_weight)
    for v in m:
        if v.denominator not in (1, 2):
            raise ValueError(f"highest_weight entries must be integers or half-integers, got {v} in {format_weight(m)}")
    kinds = {v.denominator for v in m}
    if len(kinds) > 1:
        raise ValueError(
            f"highest_weight entries must be all integers or all half-integers, got the mixture {format_weight(m)}"
        )
    if not _dominant(N, m):
        rule = (
            "m1 >= m2 >= ... >= m_n >= 0" if N % 2 else "m1 >= ... >= m_(n-1) >= |m_n|"
        )
        raise ValueError(f"highest_weight {format_weight(m)} of so({N}) is not dominant: need {rule}")
    return m


def format_weight(m: Sequence[Fraction]) -> str:
    """``(1, 1/2, ...)``: a weight as the messages and names of the package print it."""
    return "(" + ", ".join(str(v) for v in m) + ")"


def is_dominant(N: int, weight: Sequence[Any]) -> bool:
    """Whether ``weight`` (orthogonal basis) is dominant for so(N) (module docstring)."""
    N = check_dimension(N)
    m = [_to_fraction(v) for v in weight]
    n = N // 2
    if len(m) != n:
        raise ValueError(f"a weight of so({N}) has {n} entries, got {len(m)}")
    return _dominant(N, m)


def _dominant(N: int, m: Sequence[Fraction]) -> bool:
    """:func:`is_dominant` of checked input (``N`` valid, ``floor(N/2)`` Fractions)."""
    n = N // 2
    if N == 2:
        return True
    if any(m[i] < m[i + 1] for i in range(n - 1)):
        return False
    if N % 2:
        return m[-1] >= 0
    return m[-2] >= abs(m[-1])


def simple_roots(N: int) -> list[tuple[int, ...]]:
    """Simple roots (orthogonal basis) in Dynkin-label order (module docstring); empty for so(2)."""
    N = check_dimension(N)
    n = N // 2
    if N == 2:
        return []
    roots = []
    for i in range(n - 1):
        r = [0] * n
        r[i], r[i + 1] = 1, -1
        roots.append(tuple(r))
    r = [0] * n
    if N % 2:
        r[n - 1] = 1
    else:
        r[n - 2], r[n - 1] = 1, 1
    roots.append(tuple(r))
    return roots


def positive_roots(N: int) -> list[tuple[int, ...]]:
    r"""Positive roots :math:`e_i \pm e_j` (:math:`i<j`) and, for odd N, :math:`e_i`."""
    return _positive_roots(check_dimension(N))


def _positive_roots(N: int) -> list[tuple[int, ...]]:
    n = N // 2
    roots = []
    for i in range(n):
        for j in range(i + 1, n):
            for s in (-1, 1):
                r = [0] * n
                r[i], r[j] = 1, s
                roots.append(tuple(r))
        if N % 2:
            r = [0] * n
            r[i] = 1
            roots.append(tuple(r))
    return roots


def _simple_root_coordinates(N: int, v: Sequence[Fraction]) -> list[Fraction]:
    S = sp.Matrix(simple_roots(N)).T  # columns = simple roots
    sol = S.solve(sp.Matrix([sp.Rational(x.numerator, x.denominator) for x in v]))
    return [Fraction(int(c.p), int(c.q)) for c in sol]


def dominates(N: int, lam: Sequence[Any], mu: Sequence[Any]) -> bool:
    r"""Whether :math:`\lambda \succeq \mu`: :math:`\lambda - \mu` is a non-negative integer
    combination of simple roots (the dominance order; every weight of the irrep
    of highest weight :math:`\lambda` satisfies it)."""
    N = check_dimension(N)
    for name, w in (("lam", lam), ("mu", mu)):
        if isinstance(w, (str, bytes, Mapping)) or not hasattr(w, "__len__") or len(w) != N // 2:
            raise ValueError(f"{name} must be a weight of so({N}) with {N // 2} entries, got {_validate.fmt(w)}")
    a = [_to_fraction(x, "lam entry") for x in lam]
    b = [_to_fraction(x, "mu entry") for x in mu]
    v = [x - y for x, y in zip(a, b)]
    if N == 2:
        return v[0] == 0
    c = _simple_root_coordinates(N, v)
    return all(x.denominator == 1 and x >= 0 for x in c)


def dynkin_to_orthogonal(N: int, dynkin: Sequence[Any]) -> tuple[Fraction, ...]:
    r"""Highest weight in the orthogonal basis from Dynkin labels :math:`a_1, \dots, a_n`.

    :math:`m = \sum_i a_i \omega_i` with fundamental weights
    :math:`\omega_i = e_1 + \dots + e_i` except the spin weights:
    :math:`B_n`: :math:`\omega_n = \tfrac12(e_1 + \dots + e_n)`;
    :math:`D_n`: :math:`\omega_{n-1} = \tfrac12(e_1 + \dots + e_{n-1} - e_n)`,
    :math:`\omega_n = \tfrac12(e_1 + \dots + e_n)`. For so(3), :math:`a_1 = 2j`.

    Examples
    --------
    >>> dynkin_to_orthogonal(5, [1, 0])
    (Fraction(1, 1), Fraction(0, 1))
    >>> dynkin_to_orthogonal(5, [0, 1])
    (Fraction(1, 2), Fraction(1, 2))
    """
    N = check_dimension(N, minimum=3)
    n = N // 2
    _check_sequence("dynkin", dynkin, f"{n} Dynkin labels for so({N})")
    if len(dynkin) != n:
        raise ValueError(f"so({N}) needs {n} Dynkin labels, got {dynkin!r}")
    a = []
    for x in dynkin:
        f = _to_fraction(x, "Dynkin label")
        if f.denominator != 1 or f < 0:
            raise ValueError(f"Dynkin labels are non-negative integers, got {x!r} in {list(dynkin)!r}")
        a.append(f)
    m = [Fraction(0)] * n
    half = Fraction(1, 2)
    if N % 2:
        for i in range(n - 1):
            for k in range(i + 1):
                m[k] += a[i]
        for k in range(n):
            m[k] += a[n - 1] * half
    else:
        for i in range(n - 2):
            for k in range(i + 1):
                m[k] += a[i]
        for k in range(n):
            m[k] += (a[n - 1] + (a[n - 2] if k < n - 1 else -a[n - 2])) * half
    return tuple(m)


def orthogonal_to_dynkin(N: int, highest_weight: Any) -> tuple[int, ...]:
    """Dynkin labels of a dominant weight given in the orthogonal basis (inverse of
    :func:`dynkin_to_orthogonal`)."""
    N = check_dimension(N, minimum=3)
    m = check_highest_weight(N, highest_weight)
    n = len(m)
    a = [m[i] - m[i + 1] for i in range(n - 1)]
    if N % 2:
        a.append(2 * m[-1])
    else:
        a[-1] = m[-2] - m[-1]
        a.append(m[-2] + m[-1])
    return tuple(int(x) for x in a)


def _rho(N: int) -> tuple[Fraction, ...]:
    n = N // 2
    return tuple(Fraction(N - 2 * i, 2) for i in range(1, n + 1))


def weyl_dimension(N: int, highest_weight: Any) -> int:
    r"""Dimension of the so(N) irrep by the Weyl dimension formula.

    .. math:: \dim V_m = \prod_{\alpha > 0} \frac{(m + \rho, \alpha)}{(\rho, \alpha)},
              \qquad \rho_i = \tfrac{N}{2} - i,

    with the positive roots of the module docstring. E.g. so(5):
    :math:`\dim(m_1, m_2) = \tfrac16 (2m_1+3)(2m_2+1)(m_1-m_2+1)(m_1+m_2+2)`.
    """
    N = check_dimension(N)
    return weyl_dim(N, check_highest_weight(N, highest_weight))


def weyl_dim(N: int, m: Sequence[Fraction]) -> int:
    """:func:`weyl_dimension` of a checked highest weight (``m`` as :func:`check_highest_weight` returns it).

    The trusted core for callers that hold a validated weight (a
    :class:`~.representation.Representation`'s ``highest_weight``, the
    Gelfand-Tsetlin construction): no second validation. Exact integer
    arithmetic on doubled coordinates (the factors 2 cancel), products over a
    balanced tree; priced first (``"weyl_product"``: the bits of the products,
    bounded from the largest factor before any list is built).
    """
    if N == 2:
        return 1
    n = N // 2
    n_roots = n * (n - 1) + (n if N % 2 else 0)
    _pricing.check("weyl_product", bits=n_roots * math.log2(2 * (2 * float(max(m, key=abs)) + N) + 1))
    a = np.array([int(2 * x) for x in m], dtype=object) + np.array([N - 2 * i for i in range(1, n + 1)], dtype=object)
    r = np.array([N - 2 * i for i in range(1, n + 1)], dtype=object)
    iu, ju = np.triu_indices(n, 1)
    num = [a[iu] - a[ju], a[iu] + a[ju]] + ([a] if N % 2 else [])
    den = [r[iu] - r[ju], r[iu] + r[ju]] + ([r] if N % 2 else [])
    num = np.concatenate(num).tolist()
    den = np.concatenate(den).tolist()
    d, rem = divmod(_product(num), _product(den))
    if rem:  # pragma: no cover - internal
        raise ArithmeticError("Weyl dimension is not an integer (internal error)")
    return int(d)


def _product(xs: list) -> int:
    """Exact product of Python integers over a balanced tree (fast for very many factors)."""
    while len(xs) > 1:
        xs = [xs[i] * xs[i + 1] if i + 1 < len(xs) else xs[i] for i in range(0, len(xs), 2)]
    return xs[0] if xs else 1


@_pricing.model("weyl_product", "a highest weight of a smaller so(N)")
def _weyl_product_cost(bits: float) -> tuple:
    """Seconds of the exact Weyl product: ~3.9e-9 * bits^1.4 (bound on the numerator's bits; 4.5 s at so(1000))."""
    return (_pricing.Cost(f"the exact Weyl dimension product (<= {bits:.3g} bits)", 3.9e-9 * float(bits) ** 1.4,
                          "max_seconds", "seconds"),)


def casimir_eigenvalue(N: int, highest_weight: Any) -> Fraction:
    r"""Quadratic Casimir :math:`c(m) = (m, m + 2\rho) = \sum_i m_i (m_i + N - 2i)`.

    In every representation with generators :math:`X_{(ij)}` (anti-Hermitian,
    brackets of :math:`E_{(ij)}`), :math:`\sum_{i<j} X_{(ij)}^2 = -c(m)\,\mathbb 1`
    on the irrep of highest weight ``m``; equivalently the Hermitian
    :math:`\sum_{i<j} (L^{ij})^2 = \hbar^2 c(m)` with :math:`L^{ij} = -i\hbar X_{(ij)}`.
    For so(3) this is :math:`j(j+1)`; for the vector rep :math:`N-1`.
    """
    N = check_dimension(N)
    m = check_highest_weight(N, highest_weight)
    return sum((mi * (mi + N - 2 * i) for i, mi in enumerate(m, start=1)), Fraction(0))


def weight_count(N: int, top: tuple[int, ...], most: int = 10**5) -> float | None:
    """The number of distinct weights of the so(N) irrep of highest weight ``top`` (doubled coordinates): the
    dominant weights below it (``top - mu`` in the positive root cone and the root lattice: each is a weight) times
    their Weyl orbits (signed permutations; for even N an even number of sign changes). ``None`` when there may be
    more than ``most`` dominant weights: their count is at most that of the decreasing tuples of labels ``|mu_i|
    <= m_1`` (twice that for even N), checked before any is listed (for pricing: :func:`weight_multiplicities`
    visits each distinct weight)."""
    n = len(top)
    even = N % 2 == 0
    if math.comb(abs(top[0]) // 2 + n, n) * (2 if even else 1) > most:  # (decreasing tuples of |entries| <= m1)
        return None
    lam_sums = [sum(top[:k + 1]) for k in range(n)]
    count = 0.0

    def orbit(mu) -> float:
        a = [abs(x) for x in mu]
        z = a.count(0)
        size = math.factorial(n) / math.factorial(z) * 2.0 ** (n - z)
        for v in set(x for x in a if x):
            size /= math.factorial(a.count(v))
        return size / 2 if even and z == 0 else size

    def extend(mu, total):
        nonlocal count
        k = len(mu)
        if k == n:
            x = [t - u for t, u in zip(top, mu)]
            if even and ((sum(x) // 2) % 2 or sum(x[:-1]) - x[-1] < 0):  # (root lattice, the cone's last condition)
                return
            count += orbit(mu)
            return
        hi = mu[-1] if mu else top[0]
        lo = -hi if (even and k == n - 1) else 0
        v = hi
        while v >= lo:  # (doubled coordinates move in steps of 2: same parity as top)
            if total + v <= lam_sums[k]:
                extend(mu + [v], total + v)
            v -= 2

    extend([], 0)
    return count


def weight_multiplicities(N: int, highest_weight: Any) -> dict[tuple[Fraction, ...], int]:
    r"""Multiplicities of all weights of the so(N) irrep (Freudenthal's formula).

    .. math:: \big(|m+\rho|^2 - |\mu+\rho|^2\big)\, n(\mu)
              = 2 \sum_{\alpha>0} \sum_{k\ge1} (\mu + k\alpha, \alpha)\, n(\mu + k\alpha),

    evaluated in exact integer arithmetic (doubled coordinates), level by level
    below the highest weight; weights are reached by subtracting simple roots
    from weights already found (every weight of an irrep is, since the module is
    generated by lowering operators). Independent of any matrix construction.

    Returns
    -------
    dict
        ``{weight (tuple of Fraction): multiplicity}``; the multiplicities sum to
        :func:`weyl_dimension`.
    """
    N = check_dimension(N)
    m = check_highest_weight(N, highest_weight)
    if N == 2:
        return {m: 1}
    top = tuple(int(2 * x) for x in m)  # doubled coordinates
    rho2 = tuple(int(2 * x) for x in _rho(N))
    pos = [tuple(2 * a for a in r) for r in _positive_roots(N)]  # doubled roots
    simple = [tuple(2 * a for a in r) for r in simple_roots(N)]

    def norm2(v):
        return sum(x * x for x in v)

    top_norm = norm2(tuple(a + b for a, b in zip(top, rho2)))
    mult: dict[tuple[int, ...], int] = {top: 1}
    level = [top]
    bound = max(abs(x) for x in top)
    _pricing.check("weight_multiplicities", rank=len(top), n_roots=len(pos), dim=weyl_dim(N, m), bound=bound,
                   weights=weight_count(N, top))
    while level:
        candidates = set()
        for mu in level:
            for s in simple:
                nu = tuple(a - b for a, b in zip(mu, s))
                if max(abs(x) for x in nu) <= bound and nu not in mult:
                    candidates.add(nu)
        new_level = []
        for mu in sorted(candidates):
            lhs = top_norm - norm2(tuple(a + b for a, b in zip(mu, rho2)))
            rhs = 0
            for a in pos:
                k = 1
                while True:
                    nu = tuple(x + k * y for x, y in zip(mu, a))
                    if max(abs(x) for x in nu) > bound:
                        break
                    c = mult.get(nu, 0)
                    if c:
                        rhs += c * sum(x * y for x, y in zip(nu, a))
                    k += 1
            rhs *= 2
            if rhs == 0:
                continue
            if lhs <= 0 or rhs % lhs:
                raise ArithmeticError(f"Freudenthal recursion failed at weight {mu} (internal error)")
            mult[mu] = rhs // lhs
            new_level.append(mu)
        level = new_level
    return {tuple(Fraction(x, 2) for x in k): v for k, v in mult.items()}
