r"""Gelfand-Tsetlin irreps of so(N): patterns, indexing and sparse generator matrices.

Basis
-----
The Gelfand-Tsetlin (GT) basis of the irrep of so(N) with highest weight
:math:`m = (m_1, \dots, m_n)` (orthogonal basis, see :mod:`.weights`) is
adapted to the chain :math:`so(N) \supset so(N-1) \supset \dots \supset so(2)`
acting on the *first* coordinates. A basis vector is a *pattern*: rows
:math:`M_N = m, M_{N-1}, \dots, M_2`, row :math:`M_k` holding
:math:`\lfloor k/2 \rfloor` entries (the highest weight of the so(k) irrep the
vector lies in). Betweenness conditions, with all entries integers or all
half-integers:

* odd :math:`k = 2p+1`: :math:`M_{k,1} \ge M_{k-1,1} \ge M_{k,2} \ge \dots \ge
  M_{k,p} \ge M_{k-1,p} \ge -M_{k,p}` (the last so(2p) entry is signed);
* even :math:`k = 2p`: :math:`M_{k,1} \ge M_{k-1,1} \ge M_{k,2} \ge \dots \ge
  M_{k-1,p-1} \ge |M_{k,p}|`.

Pattern order and indexing (public, as in ``spherical``'s ``WignerDindex``)
----------------------------------------------------------------------------
:func:`gt_patterns` returns an array of shape ``(dim, E)``; each row is a
pattern flattened row by row, top row :math:`M_N` first (it is constant),
then :math:`M_{N-1}`, ..., :math:`M_2`, entries left to right, so
``E = sum_{k=2}^{N} floor(k/2)``. Patterns are sorted *lexicographically
decreasing* in that flattened form: index 0 is the pattern with every entry
as large as possible (for so(3): :math:`|j, m\rangle` ordered
:math:`m = j, j-1, \dots, -j`). :func:`gt_index` inverts the map,
:func:`gt_size` is the number of patterns (= Weyl dimension).

Generators and signs
--------------------
The chain generators :math:`X_{(k,k+1)}` are given by the Gelfand-Tsetlin
formulas (Gelfand & Tsetlin 1950; in the form of e.g. A. I. Molev,
"Gelfand-Tsetlin bases for classical Lie algebras", arXiv:math/0211289, and
Gavrilik & Iorgov, arXiv:q-alg/9709036 at q = 1). With
:math:`l_{2p+1,j} = M_{2p+1,j} + p - j + 1` and :math:`l_{2p,j} = M_{2p,j} + p - j`:

* :math:`X_{(2p,2p+1)}` changes row :math:`M_{2p}` by :math:`\pm 1` in one entry,
  :math:`\langle M + e_j | X | M\rangle = A_j(M)`, :math:`\langle M | X | M + e_j\rangle = -A_j(M)`,

  .. math:: A_j = \tfrac12 \Big| \frac{\prod_{r=1}^{p-1} (l_{2p-1,r} - l_{2p,j} - 1)(l_{2p-1,r} + l_{2p,j})
            \prod_{r=1}^{p} (l_{2p+1,r} - l_{2p,j} - 1)(l_{2p+1,r} + l_{2p,j})}
            {\prod_{r \ne j} (l_{2p,r}^2 - l_{2p,j}^2)(l_{2p,r}^2 - (l_{2p,j}+1)^2)} \Big|^{1/2};

* :math:`X_{(2p+1,2p+2)}` changes row :math:`M_{2p+1}` (coefficients :math:`B_j`) and
  has the diagonal part :math:`i\,C`:

  .. math:: B_j = \Big| \frac{\prod_{r=1}^{p} (l_{2p,r}^2 - l_{2p+1,j}^2)
            \prod_{r=1}^{p+1} (l_{2p+2,r}^2 - l_{2p+1,j}^2)}
            {l_{2p+1,j}^2 (4 l_{2p+1,j}^2 - 1) \prod_{r\ne j} (l_{2p+1,r}^2 - l_{2p+1,j}^2)
            ((l_{2p+1,r} - 1)^2 - l_{2p+1,j}^2)} \Big|^{1/2},
            \qquad
            C = \frac{\prod_{r=1}^{p} l_{2p,r} \prod_{r=1}^{p+1} l_{2p+2,r}}
            {\prod_{r=1}^{p} l_{2p+1,r} (l_{2p+1,r} - 1)}

  (:math:`C = 0` where the denominator vanishes: the numerator vanishes there too).

In particular :math:`X_{(12)} = i\,\mathrm{diag}(M_{2,1})`, so the weight of the
first Cartan generator :math:`H_1 = -iX_{(12)}` is :math:`M_{2,1}`. The
remaining generators follow from :math:`[E_{(ij)}, E_{(j,j+1)}] = E_{(i,j+1)}`:
:math:`X_{(i,j+1)} = [X_{(i,j)}, X_{(j,j+1)}]`. Any choice of signs of the chain
generators gives an equivalent representation (it is conjugation by a diagonal
sign matrix), so these formulas with :math:`X_{(k,k+1)} = I_{k+1,k}` of the
references satisfy the brackets of :func:`hyperrotor.conventions.structure_constants`
exactly; the tests check all brackets. The generators are anti-Hermitian and
complex (the diagonal :math:`iC`); they are not real in this basis.
"""
from __future__ import annotations

from fractions import Fraction
from functools import partial
from typing import Any

import numpy as np
import scipy.sparse as sps
import sympy as sp

from hyperrotor import _pricing, _validate
from hyperrotor._options import options
from hyperrotor.conventions import check_dimension

from .weights import check_highest_weight, dynkin_to_orthogonal, format_weight, weyl_dim

__all__ = ["irrep", "gt_patterns", "gt_size", "gt_index", "DEFAULT_MAX_DIM", "EXACT_MAX_DIM"]

#: Default ``max_dim`` guard of :func:`irrep`.
DEFAULT_MAX_DIM = 200_000
#: Largest dimension for exact (SymPy) generators.
EXACT_MAX_DIM = 200



# ----------------------------------------------------------------------------
# patterns and indexing
# ----------------------------------------------------------------------------
def _pattern_length(N: int) -> int:
    """Entries of a flattened GT pattern of so(N): rows ``M_N ... M_2`` of ``floor(k/2)`` labels each."""
    return sum(k // 2 for k in range(2, int(N) + 1))


def _row_offsets(N: int) -> dict[int, tuple[int, int]]:
    """Column range ``[a, b)`` of row ``M_k`` in the flattened pattern, k = N..2."""
    off, c = {}, 0
    for k in range(N, 1, -1):
        off[k] = (c, c + k // 2)
        c += k // 2
    return off


def _resolve_weight(N: int, highest_weight: Any, dynkin: Any) -> tuple[Fraction, ...]:
    if highest_weight is not None and dynkin is not None:
        raise ValueError("give either highest_weight or dynkin, not both")
    if highest_weight is None and dynkin is None:
        raise ValueError("irrep needs highest_weight=(m1, m2, ...) (orthogonal basis) or dynkin=[a1, a2, ...]")
    if dynkin is not None:
        return dynkin_to_orthogonal(N, dynkin)
    return check_highest_weight(N, highest_weight)


def patterns(N: int, m: tuple[Fraction, ...], *, max_count: int | None = None) -> np.ndarray | None:
    """All GT patterns (float array, exact half-integers), lexicographically decreasing.

    Trusted core of :func:`gt_patterns` (``N`` and ``m`` already checked, e.g. a
    Representation's ``highest_weight``): no validation, no size guard. ``max_count``:
    None as soon as there would be more patterns than that (the count never falls while
    the rows are filled in, since every partial pattern extends), so a weight that does
    not match a known dimension costs at most that many rows.
    """
    P = np.array([[float(x) for x in m]], dtype=float)
    for k in range(N, 2, -1):
        top = P[:, -(k // 2):]
        n = (k - 1) // 2
        if n == 0:
            continue
        if k % 2:  # k = 2p+1 -> row 2p, p = n entries, last one signed
            hi = top[:, :n].copy()
            lo = np.empty_like(hi)
            lo[:, : n - 1] = top[:, 1:n]
            lo[:, n - 1] = -top[:, n - 1]
        else:  # k = 2p -> row 2p-1, p-1 = n entries
            hi = top[:, :n].copy()
            lo = np.empty_like(hi)
            lo[:, : n - 1] = top[:, 1:n]
            lo[:, n - 1] = np.abs(top[:, n])
        for j in range(n):
            if max_count is not None and float(np.maximum(np.rint(hi[:, j] - lo[:, j]) + 1, 0).sum()) > max_count:
                return None
            cnt = np.maximum(np.rint(hi[:, j] - lo[:, j]).astype(np.int64) + 1, 0)
            idx = np.repeat(np.arange(len(P)), cnt)
            starts = np.cumsum(cnt) - cnt
            off = np.arange(int(cnt.sum())) - np.repeat(starts, cnt)
            col = hi[idx, j] - off
            P = np.concatenate([P[idx], col[:, None]], axis=1)
            hi, lo = hi[idx], lo[idx]
    return P


class PatternIndex:
    """Sorted integer keys of the patterns (mixed radix of doubled entries) for vectorized lookup.

    ``PatternIndex(P, m)``: ``P`` from :func:`patterns` of the checked highest weight ``m``.
    """

    def __init__(self, P: np.ndarray, m: tuple):
        m1 = float(max(abs(x) for x in m)) if m else 0.0
        self.m1 = m1
        self.radix = int(round(4 * m1)) + 1
        E = P.shape[1]
        self.use_keys = E * np.log2(max(self.radix, 2)) < 62
        self.table = None
        if self.use_keys:
            self.powers = self.radix ** np.arange(E - 1, -1, -1, dtype=np.int64)
            self.keys = self._keys(P)
            if len(self.keys) > 1 and not np.all(np.diff(self.keys) > 0):  # pragma: no cover - internal
                raise AssertionError("GT patterns are not in lexicographic order")
            return
        # too many digits for one integer key: a 64-bit hash of the digits (wrapping integer arithmetic), sorted,
        # each hit checked digit by digit (a Python dict of tuples took 3.6 of 5.4 s of irrep(80, (1, 0, ...)))
        self.digits = self._digits(P)
        self.powers = np.random.default_rng(20261129).integers(1, 2**62, size=E, dtype=np.int64) | 1
        h = self.digits @ self.powers
        self.order = np.argsort(h, kind="stable")
        self.keys = h[self.order]
        if len(self.keys) > 1 and not np.all(np.diff(self.keys) > 0):  # pragma: no cover - a collision: the dict
            self.table = {tuple(row): i for i, row in enumerate(self.digits.tolist())}

    @property
    def nbytes(self) -> int:
        """Bytes of the index's tables (its keys, and for long patterns their digits and order)."""
        return sum(a.nbytes for a in (self.keys, getattr(self, "digits", None), getattr(self, "order", None))
                   if a is not None)

    def _digits(self, Q):
        return np.rint(2 * (self.m1 - Q)).astype(np.int64)

    def _keys(self, Q):
        return self._digits(Q) @ self.powers

    def lookup(self, Q: np.ndarray) -> np.ndarray:
        """Index of each row of ``Q`` (``-1`` where it is not a pattern of the irrep)."""
        Q = np.atleast_2d(Q)
        out = np.full(len(Q), -1, dtype=np.int64)
        if self.use_keys:
            d = self._digits(Q)
            ok = np.all((d >= 0) & (d < self.radix), axis=1)
            if not ok.any():
                return out
            k = d[ok] @ self.powers
            pos = np.searchsorted(self.keys, k)
            pos = np.minimum(pos, len(self.keys) - 1)
            hit = self.keys[pos] == k
            res = np.where(hit, pos, -1)
            out[ok] = res
            return out
        d = self._digits(Q)
        if self.table is not None:  # pragma: no cover - two patterns of one hash
            for i, row in enumerate(d.tolist()):
                out[i] = self.table.get(tuple(row), -1)
            return out
        pos = np.minimum(np.searchsorted(self.keys, d @ self.powers), len(self.keys) - 1)
        cand = self.order[pos]
        hit = np.all(self.digits[cand] == d, axis=1)  # (a hash that matches by chance is no hit)
        out[hit] = cand[hit]
        return out


def last_label_flips(N: int, P: np.ndarray, m: tuple) -> dict[int, np.ndarray]:
    r"""``{k: perm}`` for every even ``k < N``: ``P[perm[a]]`` is ``P[a]`` with the last label of row :math:`M_k` negated.

    That label is bounded symmetrically (:math:`|M_{k,k/2}| \le M_{k+1,k/2}` and
    :math:`\le M_{k-1,k/2-1}`), so each flip maps the patterns onto themselves; flips of
    different rows commute, and the flip of several rows is their product. Trusted core
    (``P`` from :func:`patterns` of the checked highest weight ``m``).
    """
    index = PatternIndex(P, m)
    offs = _row_offsets(N)
    out = {}
    for k in range(2, N, 2):
        Q = P.copy()
        Q[:, offs[k][1] - 1] *= -1.0
        perm = index.lookup(Q)
        if np.any(perm < 0):  # pragma: no cover - internal
            raise ArithmeticError(f"negating the last label of row M_{k} leaves the GT patterns (internal error)")
        out[k] = perm
    return out


def gt_size(N: int, highest_weight: Any = None, *, dynkin: Any = None) -> int:
    """Number of GT patterns of the so(N) irrep (= its Weyl dimension, :func:`.weights.weyl_dimension`)."""
    N = check_dimension(N)
    return weyl_dim(N, _resolve_weight(N, highest_weight, dynkin))


def gt_patterns(N: int, highest_weight: Any = None, *, dynkin: Any = None, max_dim: int = DEFAULT_MAX_DIM) -> np.ndarray:
    """All Gelfand-Tsetlin patterns of the so(N) irrep in the canonical order.

    Returns
    -------
    numpy.ndarray, shape ``(dim, E)``, float64
        Row ``a`` is the pattern of basis vector ``a`` flattened as described in
        the module docstring (top row first; entries are exact half-integers).
    """
    N = check_dimension(N)
    m = _resolve_weight(N, highest_weight, dynkin)
    _check_max_dim(N, m, max_dim, entry="gt_patterns")
    return patterns(N, m)


def gt_index(N: int, highest_weight: Any, pattern: Any, *, max_dim: int = DEFAULT_MAX_DIM) -> Any:
    """Position of ``pattern`` (flattened as in :func:`gt_patterns`) in the GT basis.

    ``pattern`` may be one pattern (returns an ``int``) or an array of patterns,
    shape ``(k, E)`` (returns an integer array). Raises ``ValueError`` for a
    pattern that does not belong to the irrep (entries that are no half-integers included). It lists the irrep's
    patterns: ``max_dim`` and the memory budget as in :func:`gt_patterns`.
    """
    N = check_dimension(N)
    m = check_highest_weight(N, highest_weight)
    _check_max_dim(N, m, max_dim, entry="gt_patterns")  # (it lists them all: priced like gt_patterns)
    Q = _validate.finite_array("pattern", pattern)  # (complex, booleans, text, ragged: refused by name)
    single = Q.ndim == 1
    Q = np.atleast_2d(Q)
    E = _pattern_length(N)
    if Q.ndim != 2 or Q.shape[1] != E:
        raise ValueError(f"a GT pattern of so({N}) has {E} entries (rows M_N..M_2 flattened), got shape {Q.shape}")
    off = np.any(2.0 * Q != np.rint(2.0 * Q), axis=1)
    if np.any(off):  # (rounded to the nearest digit, 0.8 found the pattern of 1)
        raise ValueError(f"{Q[int(np.argmax(off))].tolist()} is not a Gelfand-Tsetlin pattern of the so({N}) irrep "
                         f"{format_weight(m)}: its entries are integers or half-integers")
    P = patterns(N, m)
    idx = PatternIndex(P, m).lookup(Q)
    if np.any(idx < 0):
        bad = Q[int(np.argmax(idx < 0))]
        raise ValueError(f"{bad.tolist()} is not a Gelfand-Tsetlin pattern of the so({N}) irrep {format_weight(m)}")
    return int(idx[0]) if single else idx


# ----------------------------------------------------------------------------
# matrix elements
# ----------------------------------------------------------------------------
def _lvals(P: np.ndarray, N: int, k: int, offs) -> np.ndarray:
    """The shifted labels l_{k,j} of row M_k for every pattern (works for float and object arrays)."""
    if k < 2:
        return P[:, :0]
    a, b = offs[k]
    n = b - a
    j = np.arange(1, n + 1)
    shift = (n - j + 1) if k % 2 else (n - j)
    if P.dtype == object:
        shift = np.array([Fraction(int(s)) for s in shift], dtype=object)
    return P[:, a:b] + shift


def _product_ratio(num: list, den: list, exact: bool) -> np.ndarray:
    """Per row, the product of every column of the ``num`` arrays over that of the ``den`` arrays. Exact
    (Fractions): as it is. Floats: each product carried as a mantissa and a power of two (:func:`numpy.frexp` after
    every factor, exact), so that the about N factors of size ~l^2 of so(N >= 100) do not overflow (their plain
    product was inf, and the matrix elements NaN); the same roundings as the plain product where it is finite."""
    if exact:
        top = np.prod(np.concatenate(num, axis=1), axis=1)
        return top / np.prod(np.concatenate(den, axis=1), axis=1)

    def mantissa_exponent(cols: np.ndarray):
        mant, expo = np.ones(cols.shape[0]), np.zeros(cols.shape[0], dtype=np.int64)
        for c in range(cols.shape[1]):
            mant, e = np.frexp(mant * cols[:, c])
            expo += e
        return mant, expo

    (mn, en), (md, ed) = (mantissa_exponent(np.concatenate(x, axis=1)) for x in (num, den))
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.ldexp(mn / md, en - ed)


def _chain_elements(P: np.ndarray, N: int, k: int, index: PatternIndex, Pf: np.ndarray, exact: bool):
    """Raising matrix elements (rows, cols, values) and the diagonal C of X_(k,k+1)."""
    offs = _row_offsets(N)
    lk = _lvals(P, N, k, offs)
    lb = _lvals(P, N, k - 1, offs)
    la = _lvals(P, N, k + 1, offs)
    a = offs[k][0] if k >= 2 else 0
    nk = lk.shape[1]
    rows, cols, vals = [], [], []
    one = Fraction(1) if exact else 1.0
    for j in range(nk):
        Q = Pf.copy()
        Q[:, a + j] += 1.0
        tgt = index.lookup(Q)
        ok = tgt >= 0
        if not ok.any():
            continue
        l = lk[ok, j][:, None]
        others = np.delete(lk[ok], j, axis=1)
        Lb, La = lb[ok], la[ok]
        if k % 2 == 0:  # A-type, k = 2p
            num = [(Lb - l - one) * (Lb + l), (La - l - one) * (La + l)]
            den = [(others * others - l * l) * (others * others - (l + one) * (l + one))]
            factor = Fraction(1, 2) if exact else 0.5
        else:  # B-type, k = 2p+1
            l2 = l * l
            num = [Lb * Lb - l2, La * La - l2]
            den = [l2 * (4 * l2 - one), (others * others - l2) * ((others - one) * (others - one) - l2)]
            factor = one
        ratio = _product_ratio(num, den, exact)
        if exact:
            v = [factor * sp.sqrt(sp.Rational(abs(r).numerator, abs(r).denominator)) for r in ratio]
        else:
            v = factor * np.sqrt(np.abs(ratio))
        rows.append(tgt[ok])
        cols.append(np.nonzero(ok)[0])
        vals.append(v)
    diag = None
    if k % 2 == 1:
        if exact:
            num = np.prod(lb, axis=1) * np.prod(la, axis=1)
            den = np.prod(lk * (lk - one), axis=1)
            diag = [Fraction(0) if d == 0 else n_ / d for n_, d in zip(num, den)]
        else:
            zero = np.any(lk * (lk - one) == 0, axis=1)
            diag = np.where(zero, 0.0, _product_ratio([lb, la], [lk * (lk - one)], False))
    return rows, cols, vals, diag


def _pattern_bytes(dim: float, N: float) -> float:
    """Peak bytes of building the GT patterns of a dimension-``dim`` irrep: float rows of ``sum floor(k/2)``
    (k = 2..N) entries, three copies at once (peak traced memory 2.4-3.5x one copy: ``benchmarks/pricing.py``)."""
    return 24.0 * dim * _pattern_length(N)


def _generator_bytes(dim: float, N: float) -> float:
    """Rough peak bytes of the sparse generators: ~N non-zeros per row each (5D (20, 10): 7.0, 6D (6, 3, 1): 10.0,
    measured), 12 bytes per CSR entry, about five times (the commutators that build the planes beyond ``(k, k+1)``
    and their intermediates: peak traced memory of ``irrep(...).generators(format="csr")``, benchmarks/pricing.py)."""
    return 60.0 * dim * (N * (N - 1) / 2) * N


@_pricing.model("gt_patterns", "ask for a smaller irrep")
def _gt_patterns_cost(dim, N) -> tuple:
    return (_pricing.Cost(f"the {dim} Gelfand-Tsetlin patterns of an so({N}) irrep", _pattern_bytes(float(dim), N),
                          "max_memory_bytes", "bytes"),)


#: seconds of building an irrep's generators: per pattern and squared pattern length (the lookups of the chain's
#: raised patterns: one per entry, each of every pattern's digits) and per pattern and N^2 (the commutators);
#: measured (session 48, one thread): so(40) (1, 1, 1, 0, ...) 8.4 s, so(80) (1, 0, ...) 1.1 s, so(20) (2, 1, 0, ...)
#: 0.17 s, so(5) (20, 10) 0.34 s (a review measured 56 s and 6.4 s for the first two before the lookups were hashed)
GT_LOOKUP_S = 5.5e-9
GT_COMMUTATOR_S = 1.0e-7


@_pricing.model("gt_generators", "ask for a smaller irrep")
def _gt_generators_cost(dim, N) -> tuple:
    E = _pattern_length(N)
    return (_pricing.Cost(f"the sparse generators of a dimension-{dim} irrep of so({N}) (patterns of {E} entries)",
                          float(dim) * (GT_LOOKUP_S * E * E + GT_COMMUTATOR_S * float(N) ** 2), "max_seconds",
                          "seconds"),)


@_pricing.model("irrep", "ask for a smaller irrep")
def _irrep_cost(dim, N) -> tuple:
    nbytes = _pattern_bytes(float(dim), N) + _generator_bytes(float(dim), N)
    return (_pricing.Cost(f"a dimension-{dim} irrep of so({N}) (its patterns and {N * (N - 1) // 2} sparse generators)",
                          nbytes, "max_memory_bytes", "bytes"),)


def _check_max_dim(N: int, m, max_dim, entry: str = "irrep"):
    """The irrep's dimension, refused over ``max_dim`` and, beyond :data:`DEFAULT_MAX_DIM` (a raised ``max_dim``),
    over the memory budget (``entry``'s cost model: ``"irrep"`` or ``"gt_patterns"``), before any allocation. The
    generators' estimate is no bound: measured peaks are 0.8-1.6x of it for N = 3 ... 7, 2.3x for so(8)
    (6, 4, 4, 3) and up to 40x below it for small weights of N >= 10 (fewer non-zeros per row than N), so it does
    not judge the default range: there the patterns are priced here and the generators as they are built
    (:func:`_gt_generators_float`: each commutator refused before it would pass ``max_memory_bytes``)."""
    dim = weyl_dim(N, m)
    max_dim = _validate.integer("max_dim", max_dim, minimum=1)  # (TypeError for a non-integer, ValueError below 1)
    if dim > max_dim:
        n_pl = N * (N - 1) // 2
        size = (f"its {n_pl} sparse generators: roughly {_generator_bytes(dim, N) / 2**20:.0f} MiB" if entry == "irrep"
                else f"its {dim} patterns: {_pattern_bytes(dim, N) / 2**20:.0f} MiB to build")
        raise _pricing.refuse(
            entry, f"the so({N}) irrep {format_weight(m)} ({size})", dim, "max_dim", "dimension", limit=int(max_dim),
            raise_with=f"a larger max_dim (e.g. max_dim={dim}) to build it anyway")
    if dim > DEFAULT_MAX_DIM:
        _pricing.check(entry, dim=dim, N=N)
    else:  # the generators' estimate is an upper one here: the patterns' (exact) now, the generators as they are built
        _pricing.check("gt_patterns", dim=dim, N=N)
    if entry == "irrep":
        _pricing.check("gt_generators", dim=dim, N=N)
    return dim


def _commutator_float(A, B):
    C = (A @ B - B @ A).tocsr()
    if C.nnz:
        tol = 1e-12 * float(np.abs(C.data).max())
        C.data[np.abs(C.data) < tol] = 0
        C.eliminate_zeros()
    return C


def _dok_mul(A: dict, B: dict) -> dict:
    out: dict = {}
    for i, row in A.items():
        acc: dict = {}
        for k, a in row.items():
            for j, b in B.get(k, {}).items():
                acc[j] = acc.get(j, 0) + a * b
        out[i] = acc
    return out


def _dok_commutator(A: dict, B: dict) -> dict:
    AB, BA = _dok_mul(A, B), _dok_mul(B, A)
    out = {}
    for i in set(AB) | set(BA):
        r1, r2 = AB.get(i, {}), BA.get(i, {})
        row = {}
        for j in set(r1) | set(r2):
            v = sp.expand(r1.get(j, 0) - r2.get(j, 0))
            if v != 0:
                row[j] = v
        if row:
            out[i] = row
    return out


def _gt_generators_float(N: int, m) -> dict:
    P = patterns(N, m)
    dim = len(P)
    index = PatternIndex(P, m)
    # the lookups of the adjacent planes' matrix elements: the patterns, the index, and per raised entry a copy of
    # the patterns with its digits and their comparison (a review: so(30) (1, 1, 1, 0, ...) peaked at 40.6 MB under a
    # 28 MB budget, 5.6 pattern tables)
    stage = 5.0 * P.nbytes + index.nbytes
    if stage > float(options["max_memory_bytes"]):
        raise _memory_refusal(N, m, stage, "the lookups of the matrix elements of the planes (k, k + 1)")
    X = {}
    complex_needed = False
    chain = {}
    for k in range(1, N):
        rows, cols, vals, diag = _chain_elements(P, N, k, index, P, exact=False)
        r = np.concatenate(rows) if rows else np.zeros(0, np.int64)
        c = np.concatenate(cols) if cols else np.zeros(0, np.int64)
        v = np.concatenate(vals) if vals else np.zeros(0)
        R = sps.csr_matrix((v, (r, c)), shape=(dim, dim))
        chain[k] = (R - R.T, diag)
        if diag is not None and np.any(diag != 0):
            complex_needed = True
    dtype = complex if complex_needed else float
    for k, (A, diag) in chain.items():
        M = A.astype(dtype)
        if diag is not None and np.any(diag != 0):
            M = M + sps.diags(1j * diag, format="csr")
        M = M.tocsr()
        M.eliminate_zeros()
        X[(k, k + 1)] = M
    del chain, index  # (the commutators need neither: their memory is the generators' and their products)
    # the planes beyond (k, k + 1), by commutators, their memory checked as they grow: the model of
    # _check_max_dim (N non-zeros per row and plane) is no bound (a review: so(8) (6, 4, 4, 3), dim 199 584, peaked
    # at 6 GB under a 4 GiB max_memory_bytes, 2.3x its estimate; small weights of large N are 40x below it)
    budget = float(options["max_memory_bytes"])
    held = float(P.nbytes) + sum(_csr_bytes(M) for M in X.values())
    for gap in range(2, N):
        made = []
        for i in range(1, N - gap + 1):
            j = i + gap
            A, B = X[(i, j - 1)], X[(j - 1, j)]
            # (the two products' entries, at most, and their difference)
            need = held + 2.0 * (_products_bound(A, B) + _products_bound(B, A)) * (A.data.itemsize + A.indices.itemsize)
            if need > budget:
                raise _memory_refusal(N, m, need, f"the planes built so far and the commutator that builds plane "
                                                  f"({i}, {j})")
            X[(i, j)] = _commutator_float(A, B)
            made.append(_csr_bytes(X[(i, j)]))
            held += made[-1]
        later = (N - gap - 1) * (N - gap) // 2  # the planes of larger gaps, at least as dense as these
        if later and held + later * float(np.mean(made)) > budget:
            raise _memory_refusal(N, m, held + later * float(np.mean(made)),
                                  f"the planes built so far and the {later} planes of gaps beyond {gap} (as dense "
                                  f"as those of gap {gap} at least)")
    return X


def _csr_bytes(M) -> float:
    return float(M.data.nbytes + M.indices.nbytes + M.indptr.nbytes)


def _products_bound(A, B) -> float:
    """The multiplications of ``A @ B`` (CSR), a bound on its non-zeros: ``sum_k nnz(A[:, k]) nnz(B[k, :])``."""
    return float(np.bincount(A.indices, minlength=A.shape[1]) @ np.diff(B.indptr))


def _memory_refusal(N: int, m, needed: float, what: str):
    return _pricing.refuse(
        "irrep", f"the sparse generators of the so({N}) irrep {format_weight(m)} (dimension {weyl_dim(N, m)}: {what})",
        needed, "max_memory_bytes", "bytes", "ask for a smaller irrep")


def _gt_generators_exact(N: int, m) -> dict:
    dim = weyl_dim(N, m)
    if dim > EXACT_MAX_DIM:
        raise _pricing.refuse(
            "Representation.generators(exact=True)", f"exact (SymPy) generators of the so({N}) irrep "
            f"{format_weight(m)}", dim, "EXACT_MAX_DIM", "dimension", "use the float CSR generators (exact=False)",
            limit=EXACT_MAX_DIM, raise_with="hyperrotor.quantum.gelfand_tsetlin.EXACT_MAX_DIM = ... (SymPy arithmetic "
            "on every entry: minutes beyond a few hundred)")
    P = patterns(N, m)
    index = PatternIndex(P, m)
    Pe = np.array([[Fraction(x).limit_denominator(2) for x in row] for row in P.tolist()], dtype=object).reshape(P.shape)
    X = {}
    for k in range(1, N):
        rows, cols, vals, diag = _chain_elements(Pe, N, k, index, P, exact=True)
        M: dict = {}
        for r, c, v in zip(rows, cols, vals):
            for ri, ci, vi in zip(r.tolist(), c.tolist(), v):
                M.setdefault(ri, {})[ci] = vi
                M.setdefault(ci, {})[ri] = -vi
        if diag is not None:
            for i, d in enumerate(diag):
                if d != 0:
                    M.setdefault(i, {})[i] = sp.I * sp.Rational(d.numerator, d.denominator)
        X[(k, k + 1)] = M
    for gap in range(2, N):
        for i in range(1, N - gap + 1):
            j = i + gap
            X[(i, j)] = _dok_commutator(X[(i, j - 1)], X[(j - 1, j)])
    dim = len(P)
    out = {}
    for p, M in X.items():
        S = sp.zeros(dim, dim)
        for i, row in M.items():
            for j, v in row.items():
                S[i, j] = v
        out[p] = S
    return out


def irrep(
    N: int,
    highest_weight: Any = None,
    *,
    dynkin: Any = None,
    max_dim: int = DEFAULT_MAX_DIM,
    exact: bool = False,
    format: str = "csr",
):
    r"""The so(N) irrep of a given highest weight in the Gelfand-Tsetlin basis.

    Parameters
    ----------
    N : int
        ``N >= 2``.
    highest_weight : sequence, optional
        :math:`(m_1, \dots, m_{\lfloor N/2 \rfloor})` in the orthogonal basis:
        dominant, all integers or all half-integers, last entry signed for even
        ``N`` (:func:`.weights.check_highest_weight`). Entries may be ``int``,
        ``float`` (``0.5``), :class:`fractions.Fraction` or ``sympy.Rational``.
    dynkin : sequence of int, optional
        Dynkin labels instead (:func:`.weights.dynkin_to_orthogonal`), e.g.
        ``irrep(5, dynkin=[0, 1])`` is the 4-dim spinor of so(5).
    max_dim : int
        Guard against accidentally huge irreps (default ``200_000``): a larger
        dimension raises ``ValueError`` stating the dimension, a memory estimate
        and how to raise the guard.
    exact : bool
        Also compute exact SymPy generators (square roots of rationals) at
        construction (dim <= ``EXACT_MAX_DIM`` = 200, else ``ValueError``);
        they are otherwise computed on the first ``generator(..., exact=True)`` call.
    format : {"csr", "dense"}
        Default format of the matrices the representation returns
        (:attr:`Representation.format`); storage is always sparse CSR.

    Returns
    -------
    Representation
        Generators :math:`X_{(ij)}` (anti-Hermitian, complex CSR) satisfying
        :math:`[X_a, X_b] = \sum_c C_{ab}^{\;c} X_c`, with
        :math:`\sum_a X_a^2 = -\sum_i m_i (m_i + N - 2i)\,\mathbb 1`.
        The Hermitian angular momenta of eq. (141) are
        ``rep.generator((i, j), form="hermitian", hbar=hbar)`` :math:`= -i\hbar X_{(ij)}`.

    Notes
    -----
    Chain generators from the Gelfand-Tsetlin formulas (module docstring),
    vectorized over all patterns in NumPy; the other generators by sparse
    commutators. Building all 10 generators of the 52,976-dimensional so(5)
    irrep (20, 10) takes a few seconds (``benchmarks/irreps.py``).

    Examples
    --------
    >>> rep = irrep(5, (1, 0))
    >>> rep.dim, rep.casimir_value()
    (5, Fraction(4, 1))
    >>> bool(abs(rep.casimir(format="dense") + 4 * np.eye(5)).max() < 1e-12)
    True
    >>> irrep(5, dynkin=[0, 1]).dim     # the spinor, highest weight (1/2, 1/2)
    4
    """
    from .operator_input import FORMATS
    from .representation import Representation

    N = check_dimension(N)
    _validate.choice("format", format, FORMATS)
    m = _resolve_weight(N, highest_weight, dynkin)
    dim = _check_max_dim(N, m, max_dim)
    gens = _gt_generators_float(N, m)
    exact = _validate.flag("exact", exact)
    exact_gens = _gt_generators_exact(N, m) if exact else partial(_gt_generators_exact, N, m)
    name = f"so({N}) irrep {format_weight(m)} (Gelfand-Tsetlin basis)"
    rep = Representation(N, gens, highest_weight=m, exact_generators=exact_gens, name=name, format=format)
    assert rep.dim == dim
    return rep
