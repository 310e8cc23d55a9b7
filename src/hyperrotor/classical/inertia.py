r"""Principal plane moments of inertia of an N-dimensional rigid body.

A rigid body in N dimensions rotates in the ``N(N-1)/2`` planes ``(i, j)``;
in its principal axes it is described by one moment per plane. This module
holds them in :class:`Inertia` and computes them from point masses (through
:mod:`hyperrotor.classical.mass_points`, the tensor of eq. 3) and from
continuous bodies.

Normalization (read this first)
-------------------------------
The paper's rank-4 inertia tensor, eq. (3),

.. math:: I^{ijkl} = \tfrac12 \int \bigl(-r^i\delta^{jk}r^l + r^i\delta^{jl}r^k
          + r^j\delta^{ik}r^l - r^j\delta^{il}r^k\bigr)\,dm ,

has, in principal axes with second moments :math:`m_i = \int x_i^2\,dm`,
:math:`I^{ijij} = (m_i + m_j)/2`. The *full* Einstein summation of eq. (4),
:math:`L^{ij} = I^{ijkl}\omega_{kl}`, runs over both orderings ``kl`` and ``lk``
of each plane and therefore gives :math:`L^{ij} = 2 I^{ijij}\omega_{ij} =
(m_i + m_j)\,\omega_{ij}`, whereas eq. (26) writes :math:`L^{ij} = I^{ijij}\omega_{ij}`.
The two readings differ by a factor 2.

**hyperrotor's decision.** :class:`Inertia` stores the *physical plane moment*

.. math:: I_{ij} = m_i + m_j = 2\,I^{ijij}_\text{eq. (3)},

the number that multiplies :math:`\dot\omega_{ij}` in the Euler equations
(:math:`L^{ij} = I_{ij}\,\omega_{ij}`, i.e. the paper's eq. (26) with
:math:`I^{ijij}` read as :math:`I_{ij}`). For a 3D body it is the textbook
moment of inertia about the axis normal to the plane
(:math:`I_1 = I_{23} = \int (y^2 + z^2)\,dm`, ...). The kinetic energy is
:math:`\tfrac12\sum_{i<j} I_{ij}\omega_{ij}^2` (eq. 6 with the sum over
planes; eq. (6) with full summation would double count it).
:meth:`Inertia.tensor` returns the eq.-(3) tensor with the paper's
normalization, :math:`I^{ijij} = I_{ij}/2`.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from numbers import Real
from typing import Any, Iterable, Sequence

import numpy as np

from hyperrotor._lazy import sympy as sp  # SymPy loads on first use (light ``import hyperrotor``)

from hyperrotor import _parse, _pricing, _validate
from hyperrotor._options import options, register
from .mass_points import principal_axes, second_moments_scaled
from hyperrotor.conventions import (
    check_dimension,
    n_planes,
    plane_index,
    plane_label,
    plane_symbols,
    planes,
)

register(
    "inertia_physical_atol", 1e-12,
    "Inertia.is_physical: the mass-tensor entries J_i may be as negative as -this * max(I) and still count "
    "as >= 0 (round-off of J_i = (I_ij + I_ik - I_jk) / 2 for a body with a massless axis is ~eps * max(I)).",
)

__all__ = ["Inertia"]


# ----------------------------------------------------------------------------
# scalar validation
# ----------------------------------------------------------------------------
def _as_value(v: Any, what: str, *, allow_zero: bool = False) -> sp.Expr:
    """Validate one positive (or non-negative) finite number or SymPy expression.

    Returns a SymPy object (exact numbers stay exact, Python floats become
    ``sympy.Float``).
    """
    if isinstance(v, bool) or v is None or isinstance(v, str):
        raise TypeError(f"{what} must be a real number or a SymPy expression, got {_validate.fmt(v)}")
    if isinstance(v, sp.Basic):
        expr = v
        if not isinstance(expr, sp.Expr):
            raise TypeError(f"{what} must be a SymPy expression, got {v!r}")
        if expr.is_finite is False or expr.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
            raise ValueError(f"{what} must be finite, got {v}")
        if expr.is_real is False:
            raise ValueError(f"{what} must be real, got {v}")
        bad = expr.is_negative if allow_zero else expr.is_nonpositive
        if bad:
            cond = ">= 0" if allow_zero else "> 0"
            raise ValueError(f"{what} must be {cond}, got {v}")
        return expr
    if isinstance(v, (Real, np.integer, np.floating)):
        try:
            x = float(v)
        except OverflowError:  # (a Python int beyond the double range)
            raise ValueError(f"{what} = {_validate.fmt(v)} is beyond double precision (about 1.8e308); rescale "
                             f"the moments (omega(t) does not change when every moment is multiplied by the same "
                             f"factor)") from None
        if not math.isfinite(x):
            raise ValueError(f"{what} must be finite, got {_validate.fmt(v)}")
        if x < 0 or (x == 0 and not allow_zero):
            cond = ">= 0" if allow_zero else "> 0"
            raise ValueError(f"{what} must be {cond}, got {_validate.fmt(v)}")
        if isinstance(v, (int, np.integer)):
            return sp.Integer(int(v))
        return sp.Float(x)
    raise TypeError(f"{what} must be a real number or a SymPy expression, got {_validate.fmt(v)} of type {type(v).__name__}")


def _floats_if_inexact(J: list) -> list:
    """A mass tensor of SymPy Floats as Python floats (the same numbers: both are IEEE doubles rounded once), so that
    :meth:`Inertia.from_mass_tensor` sums it with NumPy (a box of N = 200 took 5 s of SymPy per-plane checks);
    exact or symbolic entries as they are."""
    if not all(isinstance(v, sp.Float) for v in J):
        return J
    floats = [float(v) for v in J]
    # (beyond the floats, 1e600 or 1e-400: the SymPy path, whose messages name the moment that does not fit)
    return floats if all(math.isfinite(x) and (x != 0.0 or v == 0) for x, v in zip(floats, J)) else J


@_pricing.model("Inertia", "use a body of fewer dimensions")
def _inertia_cost(n: Any) -> tuple:
    """One SymPy number per plane (~20 microseconds each for plain numbers, ~100 for other input)."""
    n = float(n)
    return (_pricing.Cost(f"the moments of {n:.0f} planes as SymPy numbers", 2e-5 * n, "max_seconds", "seconds"),)


@_pricing.model("Inertia.tensor", "use the plane moments (Inertia.moments) or second_moment_matrix")
def _tensor_cost(N: Any) -> tuple:
    """The rank-4 array of :meth:`Inertia.tensor`: ``N^4`` entries of 8 bytes (floats, or pointers to SymPy
    numbers), ~1.6e-8 s each (zeroing, and the memory's first touch: 0.21 s at N = 60 with benchmarks/pricing.py),
    and a Python loop over the planes."""
    N = float(N)
    return (_pricing.Cost(f"the rank-4 tensor of dimension {N:.0f} ({N:.0f}^4 entries)", 8.0 * N ** 4,
                          "max_memory_bytes", "bytes"),
            _pricing.Cost(f"the rank-4 tensor of dimension {N:.0f} ({N:.0f}^4 entries)",
                          1.6e-8 * N ** 4 + 3e-6 * N * (N - 1) / 2, "max_seconds", "seconds"))


def _numeric_moments(moments: Any, N: int, *, allow_zero: bool = False) -> tuple[tuple, np.ndarray] | None:
    """Plain real moments (a real ndarray, or a list of Python/NumPy ints and floats) checked at once:
    ``(SymPy values, float64 array)``, or ``None`` for anything else (the per-value path). ``allow_zero``:
    zeros pass too (the entries of a mass tensor)."""
    if isinstance(moments, np.ndarray):
        if moments.ndim != 1 or moments.dtype.kind not in "iuf":
            return None
        raw = moments
    elif isinstance(moments, (list, tuple)) and all(
            isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, (bool, np.bool_))
            for v in moments):
        raw = moments
    else:
        return None
    try:
        x = np.asarray(raw, dtype=np.float64)
    except OverflowError:  # (an int beyond the double range: the per-value path names it)
        return None
    bad = np.flatnonzero(~np.isfinite(x) | ((x < 0) if allow_zero else (x <= 0)))
    if bad.size:  # the per-value path names the first bad plane in its own words
        return None
    if isinstance(raw, np.ndarray):
        exact = [raw.dtype.kind in "iu"] * x.size
    else:
        exact = [isinstance(v, (int, np.integer)) for v in raw]
    values = tuple(sp.Integer(int(v)) if e else sp.Float(float(v)) for v, e in zip(raw, exact))
    x.setflags(write=False)
    return values, x


def _is_free(expr: sp.Expr) -> bool:
    return bool(getattr(expr, "free_symbols", ()))


def _to_float_array(values: Sequence[sp.Expr]) -> np.ndarray | None:
    if any(_is_free(v) for v in values):
        return None
    return np.array([float(v) for v in values], dtype=np.float64)


def _subs_pairs(args: tuple, held: Iterable[sp.Symbol] = ()) -> list:
    """``Inertia.subs`` arguments as ``[(old, new), ...]`` of SymPy objects (never ``sympify``).

    SymPy's ``subs`` would ``sympify`` -- evaluate -- a string ``old`` or ``new``: here
    text is read by :func:`hyperrotor._parse.to_sympy` (numbers, names and arithmetic only).
    A name in the text is the symbol of that name among ``held`` (the inertia's own symbols, whatever
    their assumptions: ``"I_12"`` is the positive ``I_12`` of :meth:`Inertia.symbolic`); in ``old``
    only those names are allowed (a ``ParseError`` lists them), in ``new`` other names are new symbols.
    """
    by_name: dict[str, list] = {}
    for s in held:
        by_name.setdefault(s.name, []).append(s)

    def read(value: Any, name: str, known_only: bool):
        if not isinstance(value, str):
            return _parse.to_sympy(value, name)
        expr = _parse.to_sympy(value, name, symbols=set(by_name) if known_only else True)
        swap = {}
        for s in expr.free_symbols:
            same = by_name.get(s.name, [])
            if len(same) > 1:  # (e.g. a positive and a plain "a"): the text cannot say which
                raise ValueError(f"{name}={value!r}: the inertia holds {len(same)} symbols named {s.name!r} "
                                 f"(with different assumptions); pass the SymPy symbol itself")
            if same:
                swap[s] = same[0]
        return expr.xreplace(swap)

    if len(args) == 2:
        pairs = [tuple(args)]
    elif len(args) == 1 and isinstance(args[0], Mapping):
        pairs = list(args[0].items())
    elif len(args) == 1 and isinstance(args[0], Iterable) and not isinstance(args[0], (str, bytes)):
        pairs = [tuple(p) for p in args[0]]
    else:
        raise TypeError(f"subs takes (old, new), a mapping or a sequence of (old, new) pairs, got {_validate.fmt(args)}")
    if any(len(p) != 2 for p in pairs):
        raise TypeError(f"subs pairs must be (old, new), got {_validate.fmt(args)}")
    return [(read(o, "subs: old", True), read(n, "subs: new", False)) for o, n in pairs]


def _as_list(x: Any, what: str) -> list:
    if isinstance(x, sp.MatrixBase):
        return list(x)
    if isinstance(x, (str, bytes)) or not isinstance(x, Iterable):
        raise TypeError(f"{what} must be a sequence, got {x!r}")
    if isinstance(x, np.ndarray) and x.ndim != 1:
        raise ValueError(f"{what} must be a 1-D sequence, got an array of shape {x.shape}")
    return list(x)


# ----------------------------------------------------------------------------
# Inertia
# ----------------------------------------------------------------------------
class Inertia:
    r"""Principal plane moments of inertia :math:`I_{ij}` of an N-dimensional body.

    One moment per rotation plane ``(i, j)``, ``i < j``, in the paper's plane
    order (:func:`hyperrotor.planes`). Build it with the ``from_*`` constructors
    or the named bodies rather than calling the class directly (the direct
    call ``Inertia(seq)`` is the same as :meth:`from_planes` with a sequence).

    **Normalization.** The stored moment is the *physical plane moment*
    :math:`I_{ij} = m_i + m_j`, :math:`m_i = \int x_i^2\,dm` (principal axes),
    which enters the Euler equations as :math:`L^{ij} = I_{ij}\,\omega_{ij}`
    and is, for N = 3, the textbook moment about the axis normal to the plane
    (:math:`I_1 = I_{23}`, :math:`I_2 = I_{13}`, :math:`I_3 = I_{12}`). The
    paper's eq.-(3) tensor has :math:`I^{ijij} = (m_i + m_j)/2 = I_{ij}/2`; its
    full summation :math:`L^{ij} = I^{ijkl}\omega_{kl}` (eq. 4) gives
    :math:`2I^{ijij}\omega_{ij} = I_{ij}\omega_{ij}`. Eq. (26) and the Euler
    equations (28)-(37) write :math:`I^{ijij}` where they mean :math:`I_{ij}`;
    hyperrotor reads every printed :math:`I^{ijij}` as :math:`I_{ij}`.
    :meth:`tensor` returns the eq.-(3) tensor (:math:`I^{ijij} = I_{ij}/2`).

    Moments may be numbers or SymPy expressions (symbols such as
    :meth:`symbolic` gives). A real body always has moments of the form
    :math:`I_{ij} = J_i + J_j` with :math:`J_i \ge 0` (:meth:`is_physical`);
    generalized bodies that violate it are allowed.

    Attributes
    ----------
    N : int
        Dimension.
    planes : tuple of (int, int)
        Plane labels in component order.
    moments : numpy.ndarray
        float64 moments, shape ``(N(N-1)/2,)`` (``TypeError`` if symbolic).
    symbolic_moments : tuple of sympy.Expr
        The moments as SymPy objects (exact when given exactly).
    is_symbolic : bool
        True if some moment contains free symbols.
    principal_axes : numpy.ndarray or None
        For :meth:`from_points`: the rotation ``R`` (columns = principal axes in
        the input frame, ``det R = +1``); body coordinates are
        ``x_body = R.T @ x_input``. ``None`` otherwise.
    """

    __slots__ = ("_N", "_values", "_numeric", "_J", "principal_axes")

    def __init__(self, moments: Any, *, N: int | None = None):
        if isinstance(moments, Mapping):
            values, N_ = self._values_from_mapping(moments, N)
        else:
            if isinstance(moments, np.ndarray):  # booleans, dates and masked arrays (asarray drops a mask)
                _validate.numeric_input("moments", moments)
            seq = _as_list(moments, "moments")
            N_ = _validate.dimension_from_count(len(seq), name="moments", what="plane moments") if len(seq) else None
            if N_ is None:
                raise ValueError("moments must not be empty (got []): give N(N-1)/2 plane moments (N >= 2)")
            if N is not None and check_dimension(N) != N_:
                raise ValueError(
                    f"{len(seq)} moments are for N = {N_}, but N = {N} was given (it needs {n_planes(N)})"
                )
            _pricing.check("Inertia", n=len(seq))
            fast = _numeric_moments(moments, N_)
            if fast is not None:  # plain real numbers: checked at once, SymPy objects made in one pass
                values, numeric = fast
                self._init(values, N_, numeric=numeric)
                return
            values = [
                _as_value(v, f"moment I_{plane_label(p, N_)}") for v, p in zip(seq, planes(N_))
            ]
        self._init(tuple(values), N_)

    def _init(self, values: tuple, N: int, J: tuple | None = None, principal_axes=None, numeric=None) -> None:
        self._N = N
        self._values = values
        self._numeric = _to_float_array(values) if numeric is None else numeric
        if self._numeric is not None:
            self._numeric.setflags(write=False)
        self._J = J
        self.principal_axes = principal_axes

    @classmethod
    def _from_values(cls, values, N, J=None, principal_axes=None) -> "Inertia":
        obj = cls.__new__(cls)
        obj._init(tuple(values), N, J, principal_axes)
        return obj

    @staticmethod
    def _values_from_mapping(mapping: Mapping, N: int | None):
        pairs = []
        for key, v in mapping.items():
            try:
                i, j = (int(x) for x in key)
            except (TypeError, ValueError):
                raise ValueError(f"plane keys must be pairs (i, j) of integers, got {key!r}") from None
            if not (1 <= i < j):
                raise ValueError(f"unknown plane {key!r}: planes are pairs (i, j) with 1 <= i < j")
            pairs.append(((i, j), v))
        if not pairs:
            raise ValueError("the mapping of plane moments is empty")
        N_ = max(j for (_, j), _ in pairs)
        if N is not None:
            N_given = check_dimension(N)
            if N_given < N_:
                bad = [p for p, _ in pairs if p[1] > N_given]
                raise ValueError(f"unknown planes {bad} for N = {N_given}")
            N_ = N_given
        N_ = check_dimension(N_)
        by_plane = {}
        for p, v in pairs:
            plane_index(p, N_)
            if p in by_plane:
                raise ValueError(f"plane {p} given twice")
            by_plane[p] = v
        missing = [p for p in planes(N_) if p not in by_plane]
        if missing:
            raise ValueError(
                f"missing moments for planes {missing} (N = {N_} needs all {n_planes(N_)} planes)"
            )
        values = [_as_value(by_plane[p], f"moment I_{plane_label(p, N_)}") for p in planes(N_)]
        return values, N_

    # ------------------------------------------------------------------ constructors
    @classmethod
    def from_planes(cls, moments: Any, *, N: int | None = None) -> "Inertia":
        """Moments given per plane.

        Parameters
        ----------
        moments : mapping or sequence
            ``{(1, 2): 2.0, (1, 3): ..., ...}`` with every plane of so(N)
            (missing or unknown planes raise ``ValueError``), or a sequence of
            ``N(N-1)/2`` moments in plane order.
        N : int, optional
            Dimension; inferred from the largest axis index (mapping) or the
            length (sequence) when omitted.

        Examples
        --------
        >>> Inertia.from_planes({(1, 2): 3, (1, 3): 2, (2, 3): 1}).moments
        array([3., 2., 1.])
        """
        return cls(moments, N=N)

    @classmethod
    def from_mass_tensor(cls, J: Any) -> "Inertia":
        r"""Plane moments :math:`I_{ij} = J_i + J_j` from the mass tensor.

        ``J_i = \int x_i^2 dm`` are the principal second moments of the mass
        distribution. **A real body's moments always have this form**
        (with :math:`J_i \ge 0`); it is also Manakov's integrable case, for
        which :meth:`hyperrotor.RigidBody.manakov_integrals` are conserved.
        ``J_i`` may be zero (a flat body) as long as every plane moment is
        positive.
        """
        if isinstance(J, np.ndarray):  # booleans, dates and masked arrays, as the constructor refuses them
            _validate.numeric_input("J", J)
        seq = _as_list(J, "J")
        if len(seq) < 2:
            raise ValueError(f"J needs N >= 2 entries, got {_validate.fmt(J)}")
        N = check_dimension(len(seq))
        _pricing.check("Inertia", n=n_planes(N))  # (one SymPy number per plane, below)
        fast = _numeric_moments(J if isinstance(J, np.ndarray) else seq, N, allow_zero=True)
        if fast is not None and all(not isinstance(v, (int, np.integer)) or abs(int(v)) <= 2**53 for v in seq):
            Js, Jx = fast  # plain numbers: the sums at once (float sums are the SymPy ones: both round once)
            i, j = np.triu_indices(N, 1)
            with np.errstate(over="ignore"):
                x = Jx[i] + Jx[j]
            over = np.flatnonzero(~np.isfinite(x))
            if over.size:  # (plain numbers whose sum is no float: a SymPy oo moment before)
                a, b = int(i[over[0]]), int(j[over[0]])
                raise ValueError(f"J: moment I_{plane_label((a + 1, b + 1), N)} = J_{a + 1} + J_{b + 1} = "
                                 f"{_validate.fmt(seq[a])} + {_validate.fmt(seq[b])} overflows double precision; "
                                 f"rescale J (omega(t) does not change when every moment is multiplied by the same "
                                 f"factor)")
            if np.all(x > 0):  # (else the per-plane path names the first plane that is not positive)
                x.setflags(write=False)
                values = tuple(Js[a] + Js[b] if Js[a].is_Integer and Js[b].is_Integer else sp.Float(float(v))
                               for a, b, v in zip(i.tolist(), j.tolist(), x.tolist()))
                obj = cls.__new__(cls)
                obj._init(values, N, tuple(Js), numeric=x)
                return obj
        Js = tuple(_as_value(v, f"J_{k + 1}", allow_zero=True) for k, v in enumerate(seq))
        values = [_as_value(Js[i - 1] + Js[j - 1], f"moment I_{plane_label((i, j), N)} = J_{i} + J_{j}")
                  for i, j in planes(N)]
        return cls._from_values(values, N, J=Js)

    @classmethod
    def from_points(cls, masses: Any, positions: Any, *, center: bool = True) -> "Inertia":
        r"""Principal plane moments of point masses (the discrete eq. (3)).

        Computes the second-moment matrix :math:`M_{kl} = \sum_p m_p r^k_p r^l_p`
        (about the centre of mass unless ``center=False``) and rotates to principal
        axes by the eigen-decomposition :math:`M = R\,\mathrm{diag}(m)\,R^{\mathsf T}`;
        in these axes the rank-4 tensor of eq. (3) (:func:`inertia_tensor`) only has
        the plane components :math:`I^{ijij} = (m_i + m_j)/2`, and the result is
        ``from_mass_tensor(m)``. (The :math:`N^4` tensor itself is not built: 12 GB
        at N = 200.) ``R`` is stored in
        :attr:`principal_axes` (column ``k`` is the principal axis closest to
        input axis ``k``; ``det R = +1``).
        """
        M, e = second_moments_scaled(masses, positions, center=center)  # (M 2^e: exact powers of two)
        vals, R = principal_axes(M)
        vals = np.ldexp(np.clip(vals, 0.0, None), e)  # (clipped: round-off of flat bodies)
        out = cls.from_mass_tensor(vals)
        out.principal_axes = R
        return out

    @classmethod
    def box(cls, mass: Any, side_lengths: Any) -> "Inertia":
        r"""Solid homogeneous hyper-box with full side lengths :math:`a_i`.

        :math:`m_i = M a_i^2/12`, so :math:`I_{ij} = M(a_i^2 + a_j^2)/12`
        (3D: :math:`I_1 = M(b^2 + c^2)/12`, the textbook cuboid).
        """
        M = _as_value(mass, "mass")
        a = [_as_value(v, f"side length a_{k + 1}") for k, v in enumerate(_as_list(side_lengths, "side_lengths"))]
        if len(a) < 2:
            raise ValueError(f"side_lengths: a box needs N >= 2 side lengths, got {len(a)}")
        return cls.from_mass_tensor(_floats_if_inexact([M * x**2 / 12 for x in a]))

    @classmethod
    def ellipsoid(cls, mass: Any, semi_axes: Any) -> "Inertia":
        r"""Solid homogeneous N-ellipsoid with semi-axes :math:`a_i`.

        :math:`m_i = M a_i^2/(N + 2)` (the average of :math:`x_1^2` over the
        unit N-ball is :math:`1/(N+2)`), so :math:`I_{ij} = M(a_i^2 + a_j^2)/(N+2)`.
        """
        M = _as_value(mass, "mass")
        a = [_as_value(v, f"semi-axis a_{k + 1}") for k, v in enumerate(_as_list(semi_axes, "semi_axes"))]
        N = len(a)
        if N < 2:
            raise ValueError(f"semi_axes: an ellipsoid needs N >= 2 semi-axes, got {N}")
        return cls.from_mass_tensor(_floats_if_inexact([M * x**2 / (N + 2) for x in a]))

    @classmethod
    def ball(cls, N: int, mass: Any, radius: Any) -> "Inertia":
        r"""Solid homogeneous N-ball: every :math:`I_{ij} = 2MR^2/(N+2)` (3D: :math:`2MR^2/5`)."""
        N = check_dimension(N)
        return cls.ellipsoid(mass, [radius] * N)

    @classmethod
    def equal(cls, N: int, value: Any = 1) -> "Inertia":
        """All plane moments equal (eq. 82): the free motion has constant ``omega`` (eq. 83)."""
        N = check_dimension(N)
        v = _as_value(value, "value")
        return cls._from_values([v] * n_planes(N), N)

    @classmethod
    def quartet(cls, kappa: Any, axis: int = 5, N: int = 5) -> "Inertia":
        r"""The paper's quartet body: planes containing ``axis`` have :math:`1 + \kappa^2`, the others 2.

        ``axis = 5`` is eqs. (84)-(85); ``axis = 4, 3, 2, 1`` are eqs.
        (111)-(114). It is the mass tensor :math:`J_a = \kappa^2` (``a = axis``),
        :math:`J_i = 1` otherwise, hence a physical body.
        """
        N = check_dimension(N)
        if isinstance(axis, bool) or not isinstance(axis, (int, np.integer)) or not 1 <= int(axis) <= N:
            raise ValueError(f"axis must be an integer in 1..{N}, got {axis!r}")
        axis = int(axis)
        if isinstance(kappa, bool) or kappa is None or isinstance(kappa, str):
            raise TypeError(f"kappa must be a real number or a SymPy expression, got {kappa!r}")
        if isinstance(kappa, sp.Basic):
            k2 = kappa**2
        elif isinstance(kappa, (Real, np.integer, np.floating)):
            if not math.isfinite(float(kappa)):
                raise ValueError(f"kappa must be finite, got {kappa!r}")
            k2 = sp.Integer(int(kappa)) ** 2 if isinstance(kappa, (int, np.integer)) else sp.Float(float(kappa) * float(kappa))
            if not math.isfinite(float(k2)):
                raise ValueError(f"kappa**2 must be finite, got kappa = {_validate.fmt(kappa)}")
        else:
            raise TypeError(f"kappa must be a real number or a SymPy expression, got {kappa!r}")
        J = [k2 if i == axis else sp.Integer(1) for i in range(1, N + 1)]
        out = cls.from_mass_tensor(J)
        return out

    @classmethod
    def symbolic(cls, N: int, name: str = "I") -> "Inertia":
        """General inertia with positive SymPy symbols ``I_ij`` (``plane_symbols(name, N, positive=True)``)."""
        N = check_dimension(N)
        if not isinstance(name, str) or not name.isidentifier():
            raise TypeError(f"name must be an identifier string such as 'I', got {_validate.fmt(name)}")
        return cls._from_values(plane_symbols(name, N, positive=True), N)

    # ------------------------------------------------------------------ accessors
    @property
    def N(self) -> int:
        return self._N

    @property
    def planes(self) -> tuple:
        return planes(self._N)

    @property
    def is_symbolic(self) -> bool:
        return self._numeric is None

    @property
    def moments(self) -> np.ndarray:
        if self._numeric is None:
            raise TypeError(
                "this Inertia has symbolic moments; use .symbolic_moments, or .subs(...) numbers first"
            )
        return self._numeric

    @property
    def symbolic_moments(self) -> tuple:
        return self._values

    def __getitem__(self, plane) -> Any:
        k = plane_index(plane, self._N)
        return float(self._numeric[k]) if self._numeric is not None else self._values[k]

    def __len__(self) -> int:
        return len(self._values)

    def as_dict(self) -> dict:
        """``{(i, j): moment}`` in plane order (floats, or SymPy if symbolic)."""
        return {p: self[p] for p in self.planes}

    def subs(self, *args, **kwargs) -> "Inertia":
        """New :class:`Inertia` with ``sympy.subs`` applied to every moment.

        Text is read by :mod:`hyperrotor._parse`, and its names are the inertia's own symbols:
        ``Inertia.symbolic(3).subs("I_12", 2)`` replaces the positive symbol ``I_12``; a name the
        inertia does not hold in ``old`` is a ``ParseError`` listing the names it holds.
        """
        moments = [_parse.to_sympy(v, "moment") for v in self._values]
        Js = None if self._J is None else [_parse.to_sympy(v, "J") for v in self._J]
        pairs = _subs_pairs(args, set().union(*(e.free_symbols for e in (*moments, *(Js or ())))))
        values = [e.subs(pairs, **kwargs) for e in moments]
        J = None if Js is None else tuple(e.subs(pairs, **kwargs) for e in Js)
        values = [_as_value(v, f"moment I_{plane_label(p, self._N)}") for v, p in zip(values, self.planes)]
        return Inertia._from_values(values, self._N, J, self.principal_axes)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Inertia):
            return NotImplemented
        return self._N == other._N and all(
            sp.simplify(a - b) == 0 for a, b in zip(self._values, other._values)
        )

    def __hash__(self) -> int:
        if self._numeric is not None:
            return hash((self._N, tuple(self._numeric.tolist())))
        return hash((self._N, "symbolic"))  # (== simplifies differences: (a + b)^2 equals a^2 + 2ab + b^2)

    def __repr__(self) -> str:
        body = ", ".join(f"{plane_label(p, self._N)}: {v}" for p, v in zip(self.planes, self._values))
        return f"Inertia(N={self._N}, {{{body}}})"

    # ------------------------------------------------------------------ structure
    @property
    def mass_tensor(self):
        r"""The :math:`J_i` with :math:`I_{ij} = J_i + J_j`, or ``None`` if there are none.

        Stored when built by :meth:`from_mass_tensor` (and the constructors that
        use it); otherwise solved from :math:`J_i = (I_{ij} + I_{ik} - I_{jk})/2`
        and checked on every plane (relative tolerance ``1e-12`` for numbers,
        ``sympy.simplify`` for expressions). For N = 2 the split is not unique;
        ``(I_12/2, I_12/2)`` is returned. Numeric: ``numpy.ndarray``; symbolic:
        tuple of SymPy expressions.
        """
        J = self._J if self._J is not None else self._solve_mass_tensor()
        if J is None:
            return None
        if self._numeric is not None and not any(_is_free(v) for v in J):
            return np.array([float(v) for v in J])
        return tuple(J)

    def _solve_mass_tensor(self):
        N, I = self._N, self._values
        if N == 2:
            return (I[0] / 2, I[0] / 2)
        idx = lambda i, j: plane_index((min(i, j), max(i, j)), N)  # noqa: E731
        J = []
        for i in range(1, N + 1):
            j, k = [a for a in range(1, N + 1) if a != i][:2]
            J.append((I[idx(i, j)] + I[idx(i, k)] - I[idx(j, k)]) / 2)
        if self._numeric is not None:
            Jn = np.array([float(v) for v in J])
            pred = np.array([Jn[i - 1] + Jn[j - 1] for i, j in self.planes])
            if np.max(np.abs(pred - self._numeric)) > 1e-12 * np.max(np.abs(self._numeric)):
                return None
            return tuple(J)
        for (i, j), v in zip(self.planes, I):
            if sp.simplify(J[i - 1] + J[j - 1] - v) != 0:
                return None
        return tuple(sp.simplify(v) for v in J)

    def is_physical(self, *, atol: float | None = None):
        r"""Whether the moments can belong to a real body.

        A real body has :math:`I_{ij} = J_i + J_j` with :math:`J_i \ge 0`;
        equivalently, for N >= 4 the additivity :math:`I_{ij} + I_{kl} =
        I_{ik} + I_{jl}` holds for distinct axes, and the triangle-type
        inequalities :math:`I_{jk} \le I_{ij} + I_{ik}` hold for every triple
        (they say :math:`J_i \ge 0`; in 3D, :math:`I_3 \le I_1 + I_2`).
        This check *informs*; generalized bodies are allowed everywhere.

        Returns
        -------
        bool, or None for symbolic moments when the sign of some :math:`J_i`
        cannot be decided. ``atol`` is relative to the largest moment (default
        ``hr.options["inertia_physical_atol"]``, 1e-12).
        """
        J = self.mass_tensor
        if J is None:
            return False
        if isinstance(J, np.ndarray):
            atol = options["inertia_physical_atol"] if atol is None else _validate.positive("atol", atol, allow_zero=True)
            return bool(np.all(J >= -atol * float(np.max(self._numeric))))
        signs = [_parse.to_sympy(v, "J").is_nonnegative for v in J]
        if any(s is False for s in signs):
            return False
        return True if all(signs) else None

    def tensor(self) -> np.ndarray:
        r"""The eq.-(3) rank-4 tensor in principal axes, paper normalization.

        :math:`I^{ijkl} = \tfrac{I_{ij}}{2}(\delta_{ik}\delta_{jl} - \delta_{il}\delta_{jk})`
        for ``i != j``: :math:`I^{ijij} = I_{ij}/2`, and the full summation of
        eq. (4) gives :math:`L^{ij} = I_{ij}\,\omega_{ij}`. float64 array,
        or an object array of SymPy expressions when symbolic.
        """
        N = self._N
        sym = self.is_symbolic
        _pricing.check("Inertia.tensor", N=N)  # (the N^4 array, before it is allocated)
        t = np.zeros((N,) * 4, dtype=object if sym else np.float64)
        if sym:
            t[...] = sp.Integer(0)
        for (i, j), v in zip(self.planes, self._values if sym else self._numeric):
            h = v / 2
            a, b = i - 1, j - 1
            t[a, b, a, b] = t[b, a, b, a] = h
            t[a, b, b, a] = t[b, a, a, b] = -h
        return t
