r"""The free (or torqued) rigid body in N dimensions and its Euler equations.

Equations of motion
-------------------
With plane moments :math:`I_{ij}` (see :class:`hyperrotor.Inertia` for the
normalization) and body-frame components :math:`L^{ij} = I_{ij}\omega_{ij}`, the
Euler equations (eq. 24, :math:`\dot L = \omega L - L\omega`, plus a torque)
read, component by component (plane order :func:`hyperrotor.planes`),

.. math:: I_a\,\dot\omega_a = \sum_{b,c} C_{bc}^{\;a}\,\omega_b L_c + m_a
          = \sum_{b<c} C_{bc}^{\;a}\,(I_c - I_b)\,\omega_b\omega_c + m_a ,

with the so(N) structure constants :math:`C` of
:func:`hyperrotor.structure_constants`; e.g.
:math:`I_{12}\dot\omega_{12} = (I_{13} - I_{23})\omega_{13}\omega_{23} +
(I_{14} - I_{24})\omega_{14}\omega_{24} + \dots`. These component ODEs are the
same in the ``"paper"`` and the ``"standard"`` convention (the checkerboard of
eq. 21 is the automorphism :math:`X \mapsto S X S`,
:math:`S = \mathrm{diag}((-1)^i)`, see :mod:`hyperrotor.conventions`).

The paper prints each equation as the ``(i, j)`` *matrix entry* of
:math:`\dot L - (\omega L - L\omega) = \tilde m`, i.e. multiplied by the
checkerboard sign :math:`(-1)^{i+j}`:

.. math:: (-1)^{i+j}\bigl(I_{ij}\dot\omega_{ij} - \mathrm{rhs}_{ij}\bigr) = \tilde m^{ij},
          \qquad \tilde m^{ij} = (-1)^{i+j} m_{ij},

which is why (28) starts with :math:`-I^{1212}\dot\omega_{12}` and (29) with
:math:`+I^{1313}\dot\omega_{13}`. :meth:`RigidBody.euler_equations` returns this
form in the paper convention and the plain component form in the standard one.
Torques ``m`` passed as numbers are always the *components* :math:`m_{ij}`.

Textbook 3D map
---------------
:math:`W_1 = \omega_{23}`, :math:`W_2 = -\omega_{13}`, :math:`W_3 = \omega_{12}`,
:math:`I_1 = I_{23}`, :math:`I_2 = I_{13}`, :math:`I_3 = I_{12}` turns the N = 3
equations into :math:`I_1\dot W_1 = (I_2 - I_3)W_2W_3` (and cyclic). For a
3-axis reduction with remaining axes :math:`a < b < c` use
:math:`W_1 = \omega_{bc}`, :math:`W_2 = -\omega_{ac}`, :math:`W_3 = \omega_{ab}`.
"""
from __future__ import annotations

from collections.abc import Mapping
from itertools import combinations
from numbers import Integral
from typing import Any, Sequence

import numpy as np

from hyperrotor._lazy import sympy as sp  # SymPy loads on first symbolic use (light ``import hyperrotor``)
from hyperrotor.conventions import (
    check_convention,
    function_argument,
    is_symbolic,
    plane_label,
    planes,
    to_matrix,
)
from hyperrotor import _parse, _pricing, _validate
from hyperrotor.classical.inertia import Inertia

__all__ = ["RigidBody"]  # and TIME, served by __getattr__ below (not star-imported: that would load SymPy)


def __getattr__(name: str) -> Any:
    """PEP 562: ``TIME``, the time symbol of every symbolic equation (``sympy.Symbol("t")``), made on first use."""
    if name == "TIME":
        return sp.Symbol("t")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


@_pricing.model("RigidBody", "use a body of fewer dimensions")
def _tables_cost(N: Any) -> tuple:
    """The Euler right-hand-side tables: 3 + 1 arrays (n, N - 2) and their temporaries (~90 bytes and
    ~0.4 microsecond per entry, measured by benchmarks/pricing.py: N = 60, 100, 150 took 0.03, 0.17,
    0.54-0.68 s of CPU). Checked when the body is made, spent on the first use of the tables."""
    N = float(N)
    entries = N * (N - 1) / 2 * max(N - 2, 0.0)
    return (_pricing.Cost(f"the Euler tables of so({N:.0f}) ({entries:.3g} entries)", 90.0 * entries,
                          "max_memory_bytes", "bytes"),
            _pricing.Cost(f"the Euler tables of so({N:.0f})", 4e-7 * entries, "max_seconds", "seconds"))


def _rhs_tables(N: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r"""``(left, right, sign)``, each ``(n, N - 2)``: for every plane ``a`` the nonzero structure
    constants :math:`C_{bc}^{\;a}`, ``b < c``, in ``(b, c)`` order (``a = (i, j)`` couples exactly the
    pairs ``(i, k), (j, k)``, ``k`` not in ``{i, j}``), without the ``n^3`` table.

    The sign is the coefficient of :math:`E_{ij}` in
    :math:`[E_{pq}, E_{rs}] = \delta_{qr}E_{ps} - \delta_{pr}E_{qs} - \delta_{qs}E_{pr} + \delta_{ps}E_{qr}`
    (:func:`hyperrotor.structure_constants`), vectorised.
    """
    _pricing.check("RigidBody", N=N)
    n = N * (N - 1) // 2
    if N < 3:
        z = np.zeros((n, 0), dtype=np.intp)
        return z, z.copy(), np.zeros((n, 0), dtype=np.int8)
    idx = np.full((N + 1, N + 1), -1, dtype=np.intp)
    I, J = np.triu_indices(N, 1)
    I, J = I + 1, J + 1  # 1-based, plane order (1, 2), (1, 3), ..., (2, 3), ...
    idx[I, J] = idx[J, I] = np.arange(n)
    K = np.broadcast_to(np.arange(1, N + 1), (n, N))
    K = K[(K != I[:, None]) & (K != J[:, None])].reshape(n, N - 2)  # every k not in {i, j}
    Ii, Jj = np.broadcast_to(I[:, None], K.shape), np.broadcast_to(J[:, None], K.shape)
    b, c = idx[Ii, K], idx[Jj, K]
    lo, hi = np.minimum(b, c), np.maximum(b, c)
    P, Q, R, S = I[lo], J[lo], I[hi], J[hi]
    sign = np.zeros(K.shape, dtype=np.int64)
    for d, x, y, s in ((Q == R, P, S, 1), (P == R, Q, S, -1), (Q == S, P, R, -1), (P == S, Q, R, 1)):
        sign += np.where(d & (x == Ii) & (y == Jj), s, 0) - np.where(d & (x == Jj) & (y == Ii), s, 0)
    order = np.argsort(lo * n + hi, axis=1, kind="stable")
    return (np.take_along_axis(lo, order, axis=1), np.take_along_axis(hi, order, axis=1),
            np.take_along_axis(sign, order, axis=1).astype(np.int8))


def _pfaffian(A: sp.Matrix) -> sp.Expr:
    """Pfaffian of an even-dimensional antisymmetric SymPy matrix (expansion along row 0)."""
    n = A.rows
    if n == 0:
        return sp.Integer(1)
    total = sp.Integer(0)
    for j in range(1, n):
        if A[0, j] != 0:
            keep = [k for k in range(n) if k not in (0, j)]
            total += (-1) ** (j + 1) * A[0, j] * _pfaffian(A.extract(keep, keep))
    return total


def _manakov_traces(L: Any, J: Any, lam: Any = 1):
    r"""``tr((L + lam J^2)^k)``, ``k = 2..N``, for plain-matrix components ``L`` and diagonal ``J``.

    Numeric: array ``(..., N-1)``; SymPy: list of expressions. Conserved along
    the flow exactly when the plane moments are :math:`J_i + J_j` (Manakov).
    """
    if is_symbolic(L) or is_symbolic(J) or is_symbolic(lam):
        Lm = to_matrix(list(L), convention="standard") if not isinstance(L, sp.MatrixBase) else L
        Lm = sp.Matrix(Lm)
        N = Lm.rows
        _pricing.check("symbolic_manakov", N=N)
        A = Lm + _parse.to_sympy(lam, "lam", text=False) * sp.diag(*[_parse.to_sympy(j, "J", text=False) ** 2 for j in J])
        out, P = [], A
        for _ in range(2, N + 1):
            P = P * A
            out.append(sp.expand(P.trace()))
        return out
    Lm = to_matrix(np.asarray(L, dtype=np.float64), convention="standard")
    J = np.asarray(J, dtype=np.float64)
    N = Lm.shape[-1]
    A = Lm + lam * np.diag(J**2)
    out, P = [], A
    for _ in range(2, N + 1):
        P = P @ A
        out.append(np.trace(P, axis1=-2, axis2=-1))
    return np.stack(out, axis=-1)


def _within_double(what: str, out: np.ndarray, name: str, values: np.ndarray, through: str = "it") -> np.ndarray:
    """``out`` when finite, else a ``ValueError`` naming the argument ``name`` whose size took ``through`` beyond
    double precision (the input is finite: only the computation can overflow; NumPy gave inf or NaN with a
    RuntimeWarning)."""
    if np.all(np.isfinite(out)):
        return out
    raise ValueError(f"{what}: {name} too large, max |{name}| = {float(np.max(np.abs(values))):.3g}: computing "
                     f"{through} overflows double precision (about 1.8e308); rescale (e.g. the unit of time) first")


class RigidBody:
    r"""A rigid body in N dimensions with principal plane moments ``inertia``.

    Parameters
    ----------
    inertia : Inertia, mapping or sequence
        Plane moments (anything :meth:`Inertia.from_planes` accepts).
    convention : {"paper", "standard"}
        Matrix convention: ``"paper"`` = checkerboard of eq. (21), equations
        printed as matrix entries like (28)-(37); ``"standard"`` = plain
        antisymmetric matrices, equations in component form. Component vectors
        and :meth:`rhs` are identical in both.
    axes : sequence of int, optional
        Labels of the body's axes in an ambient body (set by :meth:`lock`;
        default ``1..N``). Plane labels, symbol names and the checkerboard signs
        of the paper convention use these original labels.
    ambient_dimension : int, optional
        Dimension of the original body (for symbol names; default ``max(axes)``).

    Attributes
    ----------
    N, inertia, convention, axes, planes, locked_axes, ambient_dimension
    rhs_tables : tuple of int arrays ``(left, right, sign)``, each ``(n_planes, N-2)``
        :math:`I_a\dot\omega_a = \sum_m \mathrm{sign}_{am}(I_{right} - I_{left})
        \omega_{left}\omega_{right}` (indices ``left[a, m]``, ``right[a, m]``),
        for compiled integrators.
    """

    def __init__(
        self,
        inertia: Any,
        *,
        convention: str = "paper",
        axes: Sequence[int] | None = None,
        ambient_dimension: int | None = None,
        _locked: tuple = (),
    ):
        if not isinstance(inertia, Inertia):
            if isinstance(inertia, (Mapping, Sequence, np.ndarray, sp.MatrixBase)) and not isinstance(inertia, str):
                inertia = Inertia.from_planes(inertia)
            else:
                raise TypeError(f"inertia must be an Inertia (or plane moments), got {inertia!r}")
        self.inertia = inertia
        self.N = inertia.N
        self.convention = check_convention(convention)
        if axes is None:
            axes = tuple(range(1, self.N + 1))
        else:
            if isinstance(axes, (str, bytes)) or not hasattr(axes, "__iter__"):
                raise TypeError(f"axes must be a sequence of {self.N} increasing positive integers, got {axes!r}")
            axes = tuple(axes)
            if (
                len(axes) != self.N
                or any(isinstance(a, bool) or not isinstance(a, Integral) or a < 1 for a in axes)
                or any(b <= a for a, b in zip(axes, axes[1:]))
            ):
                raise ValueError(f"axes must be {self.N} increasing positive integers, got {axes!r}")
            axes = tuple(int(a) for a in axes)
        self.axes = axes
        self.ambient_dimension = (_validate.integer("ambient_dimension", ambient_dimension, minimum=2, maximum=10**6)
                                  if ambient_dimension is not None else max(axes))
        if self.ambient_dimension < max(axes):
            raise ValueError(f"ambient_dimension {ambient_dimension} < largest axis label {max(axes)}")
        self.locked_axes = tuple(_locked)
        self.planes = tuple((axes[i - 1], axes[j - 1]) for i, j in planes(self.N))
        self._signs = np.array(
            [(-1) ** (i + j) if convention == "paper" else 1 for i, j in self.planes], dtype=int
        )
        # priced here, built on first use (rhs, the symbolic equations): a body that is only asked for its
        # energy, Casimirs or moments (a Scene, simulate's input) never pays for the (n, N - 2) tables
        _pricing.check("RigidBody", N=self.N)
        self._tables: tuple | None = None

    # ------------------------------------------------------------------ tables
    @property
    def rhs_tables(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(left, right, sign)``, each ``(n_planes, N - 2)`` (built on first use; read-only)."""
        return self._built_tables()[:3]

    @property
    def _coef(self) -> np.ndarray | None:
        return self._built_tables()[3]

    def _built_tables(self) -> tuple:
        """``(left, right, sign, coef)``, built on the first call (``coef``: ``None`` for symbolic moments)."""
        if self._tables is None:
            left, right, sign = _rhs_tables(self.N)
            for arr in (left, right, sign):
                arr.setflags(write=False)
            coef = None
            if not self.inertia.is_symbolic:
                I = self.inertia.moments
                coef = sign * (I[right] - I[left]) / I[:, None]
                coef.setflags(write=False)
            self._tables = (left, right, sign, coef)
        return self._tables

    def _rhs_terms(self, w: Sequence, I: Sequence, overall: Sequence[int] | None = None) -> list:
        """SymPy ``overall_a * rhs_a`` with ``I_a w_a' = rhs_a + m_a`` (sums of (I - I) w w, as printed).

        The sign of each term is absorbed into the order of the moment difference.
        """
        left, right, sign = self.rhs_tables
        out = []
        for a in range(len(self.planes)):
            g = 1 if overall is None else int(overall[a])
            out.append(sp.Add(*[
                ((I[c] - I[b]) if g * int(s) > 0 else (I[b] - I[c])) * w[b] * w[c]
                for b, c, s in zip(left[a], right[a], sign[a])
            ]))
        return out

    # ------------------------------------------------------------------ symbols
    def _label(self, plane) -> str:
        return plane_label(plane, self.ambient_dimension)

    def omega_symbols(self, *, function_of: sp.Symbol | None = None) -> tuple:
        """SymPy symbols ``omega_ij`` (or functions of ``function_of``) with the original plane labels."""
        names = [f"omega_{self._label(p)}" for p in self.planes]
        function_of = function_argument(function_of)  # (text is read, never run)
        if function_of is None:
            return tuple(sp.Symbol(s) for s in names)
        return tuple(sp.Function(s)(function_of) for s in names)

    def torque_symbols(self) -> tuple:
        r"""``mtilde_ij`` (paper: the matrix entries :math:`\tilde m^{ij}`) or ``m_ij`` (standard)."""
        name = "mtilde" if self.convention == "paper" else "m"
        return tuple(sp.Symbol(f"{name}_{self._label(p)}") for p in self.planes)

    def _check_omega(self, omega: Any, what: str = "omega") -> np.ndarray:
        w = _validate.finite_array(what, omega)  # real, finite (names the value when refused)
        n = len(self.planes)
        if w.ndim == 0 or w.shape[-1] != n:
            raise ValueError(
                f"{what} must have {n} plane components (last axis) for N = {self.N}, got {_validate.fmt(omega)} of shape {w.shape}"
            )
        return w

    # ------------------------------------------------------------------ dynamics
    def rhs(self, omega: Any, torque: Any = None) -> np.ndarray:
        r"""Time derivative :math:`\dot\omega` of the Euler equations (numpy).

        .. math:: \dot\omega_a = \Bigl(\sum_{b<c} C_{bc}^{\;a}(I_c - I_b)\,\omega_b\omega_c + m_a\Bigr)/I_a

        Parameters
        ----------
        omega : array_like, shape (..., N(N-1)/2)
            Body-frame angular velocity components; leading axes are batch axes.
        torque : array_like, optional
            Body-frame torque *components* :math:`m_{ij}` (broadcast against
            ``omega``); the paper's printed :math:`\tilde m^{ij}` is
            :math:`(-1)^{i+j}m_{ij}`.

        Identical in both conventions. Gather-and-sum over precomputed index
        tables: no Python loop over planes.

        Notes
        -----
        No overflow check: scipy's integrators call it at every stage, and a check would cost them about 2 us
        per call. An ``omega`` whose products pass double precision (``|omega|`` of about 1e154 and beyond)
        gives ``inf`` with NumPy's ``RuntimeWarning``, where :meth:`energy` and :meth:`casimirs` refuse it.
        """
        if self._coef is None:
            raise TypeError("rhs needs numeric moments; use symbolic_rhs() or euler_equations() for symbolic inertia")
        w = self._check_omega(omega)
        left, right, _ = self.rhs_tables
        out = np.sum(self._coef * w[..., left] * w[..., right], axis=-1)
        if torque is not None:
            m = self._check_omega(torque, "torque")
            out = out + m / self.inertia.moments
        return out

    def symbolic_rhs(self, omega: Sequence | None = None, torque: Any = None) -> sp.Matrix:
        r"""The Euler equations solved for :math:`\dot\omega` as a SymPy column.

        ``omega`` defaults to :meth:`omega_symbols`; ``torque`` are components
        :math:`m_{ij}` (``None`` = torque-free).

        Raises ``hyperrotor.BudgetError`` before any SymPy work when the estimated time
        (:math:`\sim N^3` products: ~3 s at N = 40) is over ``hr.options['max_seconds']``.
        """
        _pricing.check("symbolic_rhs", N=self.N, numeric=not self.inertia.is_symbolic)
        w = list(self.omega_symbols() if omega is None else omega)
        w = [_parse.to_sympy(v, f"omega[{k}]", text=False) for k, v in enumerate(w)]
        if len(w) != len(self.planes):
            raise ValueError(f"omega must have {len(self.planes)} components, got {len(w)}")
        I = self.inertia.symbolic_moments
        terms = self._rhs_terms(w, I)
        m = self._torque_components(torque, default_zero=True)
        return sp.Matrix([(r + mm) / Ia for r, mm, Ia in zip(terms, m, I)])

    def _torque_components(self, torque: Any, *, default_zero: bool) -> list:
        n = len(self.planes)
        if torque is None:
            return [sp.Integer(0)] * n if default_zero else None
        if isinstance(torque, (int, float, sp.Basic)) and not isinstance(torque, bool) and (
                _parse.to_sympy(torque, "torque", text=False) == 0):
            return [sp.Integer(0)] * n
        if isinstance(torque, (str, bytes)) or not hasattr(torque, "__len__"):
            raise TypeError(f"torque must be None, 0 or a sequence of {n} components (numbers or SymPy "
                            f"expressions, not text), got {_validate.fmt(torque)}")
        seq = list(torque)
        if len(seq) != n:
            raise ValueError(f"torque must have {n} components for N = {self.N}, got {len(seq)}")
        # never sympify: a string component would be evaluated as Python (#21)
        return [_parse.to_sympy(v, f"torque[{k}]", text=False) for k, v in enumerate(seq)]

    def euler_equations(self, torque: Any = None) -> list:
        r"""The Euler equations as ``sympy.Eq``, one per plane in plane order.

        Paper convention: :math:`(-1)^{i+j}(I_{ij}\dot\omega_{ij} - \mathrm{rhs}_{ij}) = \tilde m^{ij}`,
        for N = 5 term by term the printed eqs. (28)-(37) (with :math:`I^{ijij}`
        read as :math:`I_{ij}`). Standard convention:
        :math:`I_{ij}\dot\omega_{ij} - \mathrm{rhs}_{ij} = m_{ij}`.
        The angular velocities are ``omega_ij(t)`` (functions of :data:`TIME`)
        and the moments ``inertia.symbolic_moments``.

        Parameters
        ----------
        torque : None, 0 or sequence
            ``None``: torque symbols (:meth:`torque_symbols`: ``mtilde_ij`` in
            the paper convention, ``m_ij`` in the standard one); ``0``:
            torque-free; a sequence: the components :math:`m_{ij}` (in the paper
            convention the right-hand side is then :math:`(-1)^{i+j} m_{ij}`).

        Returns
        -------
        list of sympy.Eq
        """
        _pricing.check("euler_equations", N=self.N)
        TIME = sp.Symbol("t")
        w = self.omega_symbols(function_of=TIME)
        I = self.inertia.symbolic_moments
        # sign_a * (I_a w_a' - rhs_a), with sign_a distributed over the terms
        terms = self._rhs_terms(w, I, overall=-self._signs)
        if torque is None:
            rhs_side = list(self.torque_symbols())
        else:
            rhs_side = [int(s) * m for s, m in zip(self._signs, self._torque_components(torque, default_zero=True))]
        eqs = []
        for a, (Ia, wa, r) in enumerate(zip(I, w, terms)):
            lhs = int(self._signs[a]) * Ia * sp.Derivative(wa, TIME) + r
            eqs.append(sp.Eq(lhs, rhs_side[a], evaluate=False))
        return eqs

    # ------------------------------------------------------------------ invariants
    def angular_momentum(self, omega: Any):
        r"""Components :math:`L^{ij} = I_{ij}\,\omega_{ij}` (eq. 26 with the physical moment).

        numpy ``(..., n_planes)``; a SymPy column for symbolic input or inertia.
        """
        if is_symbolic(omega) or self.inertia.is_symbolic:
            w = list(omega)
            self._check_len(w)
            return sp.Matrix([I * x for I, x in zip(self.inertia.symbolic_moments, w)])
        w = self._check_omega(omega)
        with np.errstate(over="ignore"):
            L = w * self.inertia.moments
        return _within_double("angular_momentum", L, "omega", w)

    def _check_len(self, seq: Sequence) -> None:
        if len(seq) != len(self.planes):
            raise ValueError(f"expected {len(self.planes)} plane components for N = {self.N}, got {len(seq)}")

    def energy(self, omega: Any):
        r"""Kinetic energy :math:`\tfrac12\sum_{i<j} I_{ij}\,\omega_{ij}^2` (eq. 6 summed over planes).

        Eq. (6) read with full summation over ``ij`` and ``kl`` and the
        eq.-(3) tensor counts every plane twice and gives twice this value.
        numpy ``(...)`` or a SymPy expression; a ``ValueError`` names ``omega`` when the energy is beyond
        double precision (instead of ``inf`` with a RuntimeWarning).
        """
        if is_symbolic(omega) or self.inertia.is_symbolic:
            w = list(omega)
            self._check_len(w)
            return sp.Rational(1, 2) * sum((I * x**2 for I, x in zip(self.inertia.symbolic_moments, w)), sp.Integer(0))
        w = self._check_omega(omega)
        with np.errstate(over="ignore"):
            E = 0.5 * np.sum(self.inertia.moments * w**2, axis=-1)
        return _within_double("energy", E, "omega", w)

    def matrix(self, components: Any):
        r"""``N x N`` matrix of a component vector in this body's convention.

        Paper: entry ``(p, q)`` is :math:`(-1)^{a_p + a_q}` times the component of
        plane :math:`(a_p, a_q)` with the *original* axis labels ``a``.
        """
        plain = to_matrix(components, convention="standard")
        if self.convention == "standard":
            return plain
        s = [(-1) ** a for a in self.axes]
        if isinstance(plain, sp.MatrixBase):
            S = sp.diag(*s)
            return S * plain * S
        S = np.array(s)
        return plain * S[:, None] * S[None, :]

    def casimirs(self, values: Any, *, of: str = "omega"):
        r"""Coefficients of the characteristic polynomial of the ``L`` matrix (eq. 38).

        .. math:: \det(\lambda E - L) = \lambda^N + c_2\lambda^{N-2} + c_4\lambda^{N-4} + \dots

        (odd coefficients vanish, ``L`` being antisymmetric). Returned in the
        order :math:`(c_2, c_4, \dots, c_{2\lfloor N/2\rfloor})`, where
        :math:`c_{2k}` is the sum of the squared Pfaffians of all
        :math:`2k \times 2k` principal submatrices; :math:`c_2 = \sum_{i<j} (L^{ij})^2`.
        They are the same in both conventions (:math:`S L S` has the same
        characteristic polynomial) and are conserved for every inertia.
        The paper's eq. (38), :math:`|L - \lambda E| = k_1\lambda + k_3\lambda^3`,
        omits the :math:`-\lambda^5` term; there :math:`k_3 = -c_2`,
        :math:`k_1 = -c_4`. The energy is *not* among them.

        Parameters
        ----------
        values : array_like or SymPy sequence
            Angular velocity (``of="omega"``, default) or angular momentum
            components (``of="L"``).

        Returns
        -------
        numpy.ndarray ``(..., N // 2)`` or a list of SymPy expressions.

        Raises
        ------
        ValueError
            ``values`` so large that a Casimir (degree up to ``N`` in ``L``) overflows double precision
            (instead of inf with a RuntimeWarning).

        Notes
        -----
        Numbers: :math:`c_{2k} = e_k(a_1^2, \dots, a_m^2)`, the elementary symmetric polynomials of the
        squared plane components :math:`a_j` of ``L``'s normal form (its singular values, in equal pairs),
        a sum of positive terms: each :math:`c_{2k}` is as accurate as the :math:`a_j` (to
        :math:`\sim\epsilon\,|L|` each), also when they differ by many orders of magnitude; and
        :math:`c_2 = |L|^2` directly. Symbols: the sums of squared Pfaffians, exact.
        """
        if of not in ("omega", "L"):
            raise ValueError(f"of must be 'omega' or 'L', got {of!r}")
        if of == "omega":
            L = self.angular_momentum(values)
        else:
            L = values
        N = self.N
        if is_symbolic(L):
            L = list(L)
            self._check_len(L)
            _pricing.check("symbolic_casimirs", N=N)
            M = to_matrix(L, convention="standard")
            out = []
            for k in range(1, N // 2 + 1):
                tot = sp.Integer(0)
                for sub in combinations(range(N), 2 * k):
                    tot += _pfaffian(M.extract(list(sub), list(sub))) ** 2
                out.append(sp.expand(tot))
            return out
        L = self._check_omega(L, "L")
        m = N // 2
        # c_2k = e_k(a_1^2, ..., a_m^2), the elementary symmetric polynomials of the squares of the plane components
        # a_k of L's normal form (L's singular values come in equal pairs a_k, a_k): a sum of positive terms, so each
        # c_2k is as accurate as the a_k (Newton's identities on tr(L^k) cancelled terms of very different size away)
        s = np.linalg.svd(to_matrix(L, convention="standard"), compute_uv=False)
        with np.errstate(over="ignore", invalid="ignore"):
            a2 = s[..., 0 : 2 * m : 2] * s[..., 1 : 2 * m : 2]
            e = np.zeros(L.shape[:-1] + (m + 1,))
            e[..., 0] = 1.0
            for j in range(m):  # multiply by (1 + a_j^2 x): e_k += a_j^2 e_(k-1), from the old values
                e[..., 1 : j + 2] = e[..., 1 : j + 2] + a2[..., j, None] * e[..., 0 : j + 1]
            e[..., 1] = np.sum(L * L, axis=-1)  # c_2 = |L|^2, directly (no round-off of the decomposition)
        return _within_double("casimirs", e[..., 1:], "values", L, "the products of the squared components of L")

    def manakov_integrals(self, values: Any, lam: Any = 1.0, *, of: str = "omega"):
        r"""Manakov's integrals :math:`\operatorname{tr}\bigl((L + \lambda J^2)^k\bigr)`, ``k = 2..N``.

        For a mass-tensor body :math:`I_{ij} = J_i + J_j`
        (:attr:`Inertia.mass_tensor`), with plain matrices
        :math:`L = JW + WJ` and :math:`J = \mathrm{diag}(J_i)`, the Lax pair
        :math:`\tfrac{d}{dt}(L + \lambda J^2) = [L + \lambda J^2, -(W + \lambda J)]`
        makes every such trace conserved for every ``lam`` (hence every
        coefficient of its polynomial in ``lam``). Convention independent.

        Parameters
        ----------
        values : array_like or SymPy sequence
            Angular velocity (``of="omega"``, default) or angular momentum
            components (``of="L"``).
        lam : number or SymPy expression
            The spectral parameter.

        Returns
        -------
        numpy.ndarray ``(..., N - 1)`` or a list of SymPy expressions (``lam``
        may be a SymPy symbol).

        Raises
        ------
        ValueError
            If the moments are not of the form :math:`J_i + J_j`.
        """
        J = self.inertia.mass_tensor
        if J is None:
            raise ValueError(
                "manakov_integrals needs a mass-tensor inertia I_ij = J_i + J_j; "
                f"{self.inertia!r} is not of that form"
            )
        if of not in ("omega", "L"):
            raise ValueError(f"of must be 'omega' or 'L', got {of!r}")
        if of == "omega":
            L = self.angular_momentum(values)
        elif is_symbolic(values):
            L = list(values)
            self._check_len(L)
        else:
            L = self._check_omega(values, "L")
        if not is_symbolic(L):
            lam_value = lam if is_symbolic(lam) else _validate.real("lam", lam)
            if is_symbolic(lam_value) or self.inertia.is_symbolic:  # (SymPy traces: nothing overflows)
                return _manakov_traces(L, J, lam_value)
            with np.errstate(over="ignore", invalid="ignore"):
                out = _manakov_traces(L, J, lam_value)
            if np.all(np.isfinite(out)):
                return out
            Jmax = float(np.max(np.abs(J)))  # (a product, not ** 2: a Python float's power raises OverflowError)
            if abs(lam_value) * Jmax * Jmax >= float(np.max(np.abs(L), initial=0.0)):
                big, sizes = "lam", np.array([lam_value])
            else:
                big, sizes = of, (self._check_omega(values) if of == "omega" else L)
            return _within_double("manakov_integrals", out, big, sizes, "the traces of (L + lam J^2)^k")
        return _manakov_traces(list(L), J, lam)

    # ------------------------------------------------------------------ reductions
    def lock(self, axes: Any) -> "RigidBody":
        r"""The reduced body when every rotation involving ``axes`` is frozen (Sec. 2.2-2.5).

        Setting :math:`\omega_{ij} = 0` for all planes that contain a locked axis
        is an invariant subspace of the torque-free flow: each term of
        :math:`\dot\omega_{ik}` (``k`` locked) contains some
        :math:`\omega_{\cdot k}` factor. The remaining components obey the Euler
        equations of the body made of the remaining axes and their plane moments.
        The reduced body keeps the original axis labels (:attr:`axes`), so its
        equations use the original symbols and signs (e.g. ``lock(1)`` of a 5D
        body gives (42)-(47)).

        Parameters
        ----------
        axes : int or iterable of int
            Original axis labels present in :attr:`axes`.

        Raises
        ------
        ValueError
            Unknown axis, or fewer than two axes would remain.
        """
        if isinstance(axes, (Integral, np.integer)) and not isinstance(axes, bool):
            locked = (int(axes),)
        else:
            try:
                if isinstance(axes, (str, bytes)):  # (its characters are not axis labels)
                    raise TypeError
                locked = tuple(axes)
            except TypeError:
                raise TypeError(f"axes must be an axis label or an iterable of them, got {axes!r}") from None
        for a in locked:
            if isinstance(a, bool) or not isinstance(a, (Integral, np.integer)):
                raise TypeError(f"cannot lock axis {a!r}: axis labels are integers (the body's axes are {self.axes})")
            if int(a) not in self.axes:
                raise ValueError(f"cannot lock axis {a!r}: the body's axes are {self.axes}")
        locked = tuple(sorted(set(int(a) for a in locked)))
        remaining = tuple(a for a in self.axes if a not in locked)
        if len(remaining) < 2:
            raise ValueError(
                f"locking axes {locked} of a body with axes {self.axes} leaves {len(remaining)} axis; "
                "at least two must remain free (one rotation plane)"
            )
        keep = [k for k, (i, j) in enumerate(self.planes) if i in remaining and j in remaining]
        vals = [self.inertia.symbolic_moments[k] for k in keep]
        J = self.inertia._J
        if J is not None:
            J = tuple(J[self.axes.index(a)] for a in remaining)
        inertia = Inertia._from_values(vals, len(remaining), J)
        return RigidBody(
            inertia,
            convention=self.convention,
            axes=remaining,
            ambient_dimension=self.ambient_dimension,
            _locked=tuple(sorted(self.locked_axes + locked)),
        )

    def stability(self, plane: Any, omega0: Any):
        """Linear stability of the steady rotation ``omega0`` in ``plane``.

        Delegates to :func:`hyperrotor.classical.stability.linear_stability`.
        """
        from hyperrotor.classical.stability import linear_stability

        return linear_stability(self, plane, omega0)

    def __eq__(self, other: object) -> bool:
        """The same body: equal moments (:meth:`Inertia.__eq__`), convention, axis labels and locked axes."""
        if not isinstance(other, RigidBody):
            return NotImplemented
        return ((self.convention, self.axes, self.ambient_dimension, self.locked_axes)
                == (other.convention, other.axes, other.ambient_dimension, other.locked_axes)
                and self.inertia == other.inertia)

    def __hash__(self) -> int:
        return hash((self.inertia, self.convention, self.axes, self.ambient_dimension, self.locked_axes))

    def __repr__(self) -> str:
        extra = f", axes={self.axes}" if self.axes != tuple(range(1, self.N + 1)) else ""
        return f"RigidBody({self.inertia!r}, convention={self.convention!r}{extra})"
