r"""Closed form of the body with one distinguished axis: the "quartet" of paper Sec. 3 (eqs. 84-118), any N.

Moments :math:`I_P = 1 + \kappa^2` for every plane ``P`` containing the axis
``a`` and :math:`I_P = 2` otherwise (or any common rescaling). With plain
matrices, :math:`L = \beta W + (\alpha - \beta) W_a` (``alpha = 1 + kappa^2``,
``beta = 2``, :math:`W_a` the part of :math:`W` in the planes containing ``a``),
and :math:`\dot L = [W, L] = (\alpha-\beta)[W_r, W_a]` with :math:`W_r = W - W_a`.
Writing :math:`W_a = u e_a^{\mathsf T} - e_a u^{\mathsf T}` one finds
:math:`[W_r, W_a] = (W_r u) e_a^{\mathsf T} - e_a (W_r u)^{\mathsf T}`, so

- every component in a plane **not** containing ``a`` is constant;
- :math:`\dot u = \Theta\, W_r u` with :math:`\Theta = 1 - \beta/\alpha =
  (\kappa^2 - 1)/(\kappa^2 + 1)` (eq. 100).

In components :math:`x_i = \omega_{(\min(i,a), \max(i,a))} = s_i u_i`,
:math:`s_i = +1` for ``i < a`` and ``-1`` for ``i > a``, hence
:math:`\dot x = \Theta A x` with the real antisymmetric ``(N-1) x (N-1)``
matrix :math:`A = S W_r S` (rows/columns ``i != a``). The flow
:math:`x(t) = e^{\Theta A t} x_0` is evaluated through the spectral
decomposition of the Hermitian matrix :math:`iA` (orthonormal eigenvectors even
for repeated eigenvalues), vectorised over times and batches.

Equal moments (:func:`~.closed_form.equal_moments_solution`) are the case :math:`\Theta = 0`.

Paper discrepancies (Sec. 3)
----------------------------
Checked symbolically in ``tests/classical/test_closed_form.py``:

* (83) lists :math:`d\omega_{23}/dt` twice and omits :math:`d\omega_{14}/dt`.
* (92) and (95) have the wrong overall sign of the :math:`(1-\kappa^2)` term
  (compare the general eqs. 34 and 37): correct is
  :math:`(1+\kappa^2)\dot\omega_{25} - (1-\kappa^2)(\omega_{12}\omega_{15}
  - \omega_{23}\omega_{35} - \omega_{24}\omega_{45}) = 0` and
  :math:`(1+\kappa^2)\dot\omega_{45} - (1-\kappa^2)(\omega_{14}\omega_{15}
  + \omega_{24}\omega_{25} + \omega_{34}\omega_{35}) = 0` (eq. 95 also prints
  :math:`\omega_{51}` for :math:`\omega_{15}`). (89) and (94) are right, and
  so are the linear equations (96)-(99).
* (100): the inverse is :math:`\kappa = \sqrt{1-\Theta^2}/(1-\Theta)`, not
  :math:`/(\Theta - 1)` (which is negative); and :math:`-1 \le \Theta < 1`
  (``kappa = 0`` gives ``Theta = -1``).
* (104)-(105) contain :math:`\omega_{45}, \omega_{35}` instead of
  :math:`C_{45}, C_{35}`; (105) and the entry (2,4) of (106) have the wrong sign
  of :math:`\Theta c_5` (correct: :math:`i\Omega C_{45} + \Theta c_3 C_{15} +
  \Theta c_5 C_{25} + \Theta c_6 C_{35} = 0`, and ``M[1, 3] = -Theta c5`` so
  that ``M - i Omega 1`` is antisymmetric as the text says).
* (107)-(109) are right: :math:`l_2 = -\Theta^2 \sum c_k^2`,
  :math:`l_0 = \Theta^4 (c_1 c_6 - c_2 c_5 + c_3 c_4)^2` (a squared Pfaffian),
  and the factorisation (109) holds identically. But the strict inequalities
  are false in general: :math:`l_0 = 0` whenever the Pfaffian vanishes (e.g.
  only :math:`c_1 \ne 0`), :math:`l_2 = 0` for ``kappa = 1`` or all
  :math:`c = 0`; in (110) :math:`l_2^2 = l_2^2 - 4 l_0` when the Pfaffian
  vanishes and :math:`l_2^2 - 4 l_0 = 0` for (anti-)self-dual data
  (:math:`c_1 = \pm c_6, c_3 = \pm c_4, c_2 = \mp c_5`), where the two
  frequencies coincide. Only the non-strict versions hold.
* The frequencies printed after (118),
  :math:`\Omega = \pm\tfrac12\sqrt{\pm 2\sqrt{l_2^2-4l_0} - 2 l_2}`, are right.
  (110) guarantees they are real: the motion is always quasi-periodic.
* The same formulas hold for the other axes (111)-(118) with the relabelled
  constants, because conjugation by ``S`` does not change the characteristic
  polynomial; the linear ODEs (96)-(99), however, acquire the signs ``s_i``.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from .. import _pricing, _validate
from .._cost_models import _eigh_seconds
from .._parallel import interruptible
from ..conventions import check_dimension, dimension_from_count
from ._closed_form_input import plane_vector, times
from .inertia import Inertia

__all__ = [
    "quartet_moments",
    "quartet_theta",
    "quartet_matrix",
    "quartet_solution",
    "quartet_frequencies",
    "quartet_polynomial_coefficients",
    "quartet_attitude",
]


def _check_axis(axis: Any, N: int) -> int:
    return _validate.integer("axis", axis, minimum=1, maximum=N)


def quartet_moments(kappa: float, axis: int = 5, N: int = 5) -> np.ndarray:
    r"""Plane moments of the quartet case: ``1 + kappa**2`` for planes containing ``axis``, else 2.

    ``axis=5`` is eqs. (84)-(85); ``axis=4, 3, 2, 1`` are eqs. (111)-(114).
    The moments of :meth:`hyperrotor.Inertia.quartet` as a float array.
    """
    return Inertia.quartet(kappa, axis=axis, N=N).moments


def quartet_theta(kappa: float) -> float:
    r""":math:`\Theta = (\kappa^2 - 1)/(\kappa^2 + 1)` of eq. (100); inverse
    :math:`\kappa = \sqrt{1-\Theta^2}/(1-\Theta)` (the paper prints ``Theta - 1``)."""
    k = _validate.real("kappa", kappa)
    k2 = k * k
    if not np.isfinite(k2):
        raise ValueError(f"kappa must be finite with a finite square, got {_validate.fmt(kappa)}")
    return (k2 - 1.0) / (k2 + 1.0)


@_pricing.model("quartet_frequencies", "use fewer dimensions or fewer initial conditions")
def _quartet_frequencies_cost(N: Any, batch: Any = 1) -> tuple:
    """Singular values of ``batch`` real matrices of dimension N - 1 (8 bytes per entry, three copies;
    bidiagonalization ~(8/3) d^3 flops at ~1e-10 s each, as the dense diagonalization model of _pricing)."""
    d, b = float(N) - 1.0, float(batch)
    return (_pricing.Cost(f"{batch} matrices of dimension {d:.0f}", 24.0 * b * d * d, "max_memory_bytes", "bytes"),
            _pricing.Cost(f"{batch} singular value problems of dimension {d:.0f}", 1e-10 * 8.0 / 3.0 * b * d**3,
                          "max_seconds", "seconds"))


@_pricing.model("closed_form_solution", "use fewer dimensions or fewer initial conditions")
@_pricing.model("quartet_attitude", "use fewer dimensions")
@_pricing.model("quartet_solution", "use fewer dimensions or fewer initial conditions")
def _quartet_eigh_cost(d: Any, count: Any = 1, n_times: Any = 0) -> tuple:
    """``count`` eigendecompositions of Hermitian matrices of dimension ``d`` (the closed forms' ``exp(W t)``):
    :func:`~hyperrotor._cost_models._eigh_seconds`; ``i W``, its eigenvectors and LAPACK's work copy (16 bytes per
    entry, four copies); ``n_times``: the matrices ``exp(W t)`` themselves at that many times (the attitude: one
    complex product of dimension ``d`` each, ~1.5e-11 s per real flop with BLAS, measured by benchmarks/pricing.py)."""
    d, c, k = float(d), float(count), float(n_times)
    at = f" and exp(W t) at {n_times} times" if n_times else ""
    # (and the n_times matrices: complex U diag(ph) U^H and its real part, then the products: 48 bytes per entry, the
    # peak traced memory of quartet_attitude at N = 60 and 3000 times)
    return (_pricing.Cost(f"{count} complex matrix(es) of dimension {d:.0f}{at}",
                          64.0 * c * d * d + 48.0 * k * d * d, "max_memory_bytes", "bytes"),
            _pricing.Cost(f"{count} Hermitian eigenproblem(s) of dimension {d:.0f}{at}",
                          c * (_eigh_seconds(d ** 3) + k * 8.0 * d ** 3 * 1.5e-11), "max_seconds", "seconds"))


def plane_axes(N: int) -> tuple[np.ndarray, np.ndarray]:
    """1-based axes ``(i, j)`` of every plane, in plane order (1, 2), (1, 3), ..., (2, 3), ..."""
    i, j = np.triu_indices(N, 1)
    return i + 1, j + 1


def axis_layout(N: int, axis: int):
    """Indices of the planes (i, a) (in order of i != a), their signs s_i, and the other planes (O(n))."""
    others = np.array([i for i in range(1, N + 1) if i != axis], dtype=int)
    p, q = np.minimum(others, axis), np.maximum(others, axis)
    idx = (p - 1) * N - (p - 1) * p // 2 + (q - p - 1)  # plane_index of (p, q), vectorised
    signs = np.where(others < axis, 1.0, -1.0)
    i, j = plane_axes(N)
    rest = np.flatnonzero((i != axis) & (j != axis))
    return idx, signs, rest


def quartet_matrix(omega0: Any, axis: int = 5) -> np.ndarray:
    r"""The antisymmetric matrix :math:`A` of :math:`\dot x = \Theta A x` (generalised eqs. 96-99).

    ``x`` lists :math:`\omega_{(\min(i,a),\max(i,a))}` for ``i = 1..N, i != a``;
    :math:`A_{ij} = s_i s_j (W_r)_{ij}` with :math:`(W_r)_{ij} = \omega_{ij}` (plain
    antisymmetric matrix of the planes not containing ``a``) and
    :math:`s_i = \operatorname{sign}(a - i)`. For ``axis = 5, N = 5``,
    :math:`A = [[0, c_1, c_2, c_3], [-c_1, 0, c_4, c_5], [-c_2, -c_4, 0, c_6],
    [-c_3, -c_5, -c_6, 0]]`, i.e. exactly eqs. (96)-(99).

    Parameters
    ----------
    omega0 : array_like, shape (..., n_planes)
        Only the components in planes not containing ``axis`` are used.
    axis : int
        The distinguished axis (1-based).

    Returns
    -------
    numpy.ndarray, shape (..., N-1, N-1)
    """
    w = plane_vector(omega0)
    N = dimension_from_count(w.shape[-1])
    axis = _check_axis(axis, N)
    others = np.array([i for i in range(1, N + 1) if i != axis])
    s = np.where(others < axis, 1.0, -1.0)
    r, c = np.triu_indices(N - 1, 1)  # others is increasing: (r, c) with r < c is the plane (others[r], others[c])
    p, q = others[r], others[c]
    planes_rc = (p - 1) * N - (p - 1) * p // 2 + (q - p - 1)  # plane_index, vectorised
    v = s[r] * s[c] * w[..., planes_rc]
    A = np.zeros(w.shape[:-1] + (N - 1, N - 1))
    A[..., r, c] = v
    A[..., c, r] = -v
    return A


def quartet_flow(theta: float, omega0: np.ndarray, tt: np.ndarray, axis: int) -> np.ndarray:
    """exp(theta * A * t) applied to the axis components; the rest stays constant."""
    N = dimension_from_count(omega0.shape[-1])
    idx, _, _ = axis_layout(N, axis)
    A = quartet_matrix(omega0, axis)
    # iA is Hermitian: iA = U diag(lam) U^H, so exp(theta A t) = U diag(exp(-i lam theta t)) U^H (Ctrl-C: interruptible)
    lam, U = interruptible(np.linalg.eigh, 1j * A)
    x0 = omega0[..., idx]
    y0 = np.einsum("...ji,...j->...i", U.conj(), x0)  # U^H x0
    phase = np.exp(-1j * theta * tt[:, None] * lam[..., None, :])  # (..., n_t, N-1)
    x = np.einsum("...ij,...tj->...ti", U, phase * y0[..., None, :]).real
    out = np.broadcast_to(omega0[..., None, :], omega0.shape[:-1] + (tt.size, omega0.shape[-1])).copy()
    out[..., idx] = x
    return out


def quartet_solution(kappa: float, omega0: Any, t: Any, axis: int = 5, N: int | None = None) -> np.ndarray:
    r"""Exact solution of the quartet case (eqs. 84-118) and its N-dimensional generalisation.

    Moments: :math:`I_P = 1 + \kappa^2` for the planes containing ``axis``,
    :math:`I_P = 2` for the others (``axis = 5``: eqs. 84-85; ``4, 3, 2, 1``:
    eqs. 111-114). The components in planes without ``axis`` are constant
    (eqs. 86-93, 115-118); the ``N-1`` others obey :math:`\dot x = \Theta A x`
    (:func:`quartet_matrix`, the corrected eqs. 96-99), solved exactly as
    :math:`x(t) = e^{\Theta A t} x_0` through the eigendecomposition of the
    Hermitian :math:`iA`.

    Parameters
    ----------
    kappa : float
    omega0 : array_like, shape (..., n_planes)
        Initial angular velocity; leading batch axes allowed.
    t : array_like, shape (n_t,)
        Output times (any order; t = 0 is the initial time).
    axis : int, default 5
        Distinguished axis, 1-based.
    N : int, optional
        Checked against ``omega0`` when given.

    Returns
    -------
    numpy.ndarray, shape (..., n_t, n_planes)
    """
    w = plane_vector(omega0)
    Nw = _validate.dimension(dimension_from_count(w.shape[-1]), name="N of omega0")
    if N is not None and check_dimension(N) != Nw:
        raise ValueError(f"omega0 has {w.shape[-1]} components, i.e. N = {Nw}, but N = {N} was given")
    axis = _check_axis(axis, Nw)
    tt = times(t)
    _pricing.check("closed_form_output", n_times=tt.size, width=w.size)
    _pricing.check("quartet_solution", d=Nw - 1, count=int(np.prod(w.shape[:-1])))
    return quartet_flow(quartet_theta(kappa), w, tt, axis)


def quartet_polynomial_coefficients(kappa: float, omega0: Any, axis: int = 5) -> tuple[float, float]:
    r"""``(l2, l0)`` of the characteristic polynomial (107) :math:`\Omega^4 + l_2\Omega^2 + l_0` (N = 5).

    :math:`l_2 = -\Theta^2 \sum_k c_k^2`, :math:`l_0 = \Theta^4 (c_1 c_6 - c_2 c_5 + c_3 c_4)^2`
    (eq. 108; ``c_k`` the six constant components in plane order, eqs. 115-118).
    Only non-strict signs hold: ``l2 <= 0``, ``l0 >= 0``.
    """
    w = plane_vector(omega0, 10)
    axis = _check_axis(axis, 5)
    th = quartet_theta(kappa)
    _, _, rest = axis_layout(5, axis)
    c1, c2, c3, c4, c5, c6 = (w[..., k] for k in rest)
    l2 = -th**2 * (c1**2 + c2**2 + c3**2 + c4**2 + c5**2 + c6**2)
    l0 = th**4 * (c1 * c6 - c2 * c5 + c3 * c4) ** 2
    return l2, l0


def quartet_frequencies(kappa: float, omega0: Any, axis: int = 5) -> np.ndarray:
    r"""Non-negative angular frequencies of the oscillating components of the quartet case.

    For ``N = 5`` these are the closed forms after eq. (118),
    :math:`\Omega_{1,2} = \tfrac12\sqrt{\pm 2\sqrt{l_2^2 - 4 l_0} - 2 l_2}`,
    i.e. :math:`\Omega^2 = (-l_2 \pm \sqrt{l_2^2-4l_0})/2`, returned as
    ``[Omega_1, Omega_2]`` with ``Omega_1 >= Omega_2``. With the factors
    :math:`p, q` of (109) (:math:`\sum c^2 = (p+q)/2`, Pfaffian :math:`= (p-q)/4`)
    they are :math:`|\Theta|(\sqrt p \pm \sqrt q)/2`, evaluated in that
    cancellation-free form. For other ``N`` the
    ``floor((N-1)/2)`` frequencies are :math:`|\Theta|` times the moduli of the
    eigenvalues of :math:`A` (descending), i.e. of its singular values (:math:`A` is normal).
    """
    w = plane_vector(omega0)
    N = _validate.dimension(dimension_from_count(w.shape[-1]), name="N of omega0")
    axis = _check_axis(axis, N)
    th = quartet_theta(kappa)
    if N == 5:
        _, _, rest = axis_layout(5, axis)
        c1, c2, c3, c4, c5, c6 = (w[..., k] for k in rest)
        # (109): l2^2 - 4 l0 = Theta^4 [(c5-c2)^2+(c3+c4)^2+(c1+c6)^2][(c5+c2)^2+(c3-c4)^2+(c1-c6)^2]
        p = (c5 - c2) ** 2 + (c3 + c4) ** 2 + (c1 + c6) ** 2
        m = (c5 + c2) ** 2 + (c3 - c4) ** 2 + (c1 - c6) ** 2
        # Omega^2 = (-l2 +- sqrt(l2^2 - 4 l0))/2 = Theta^2 (sqrt(p) +- sqrt(m))^2 / 4
        big = 0.5 * abs(th) * (np.sqrt(p) + np.sqrt(m))
        small = 0.5 * abs(th) * np.abs(np.sqrt(p) - np.sqrt(m))
        return np.stack([big, small], axis=-1)
    _pricing.check("quartet_frequencies", N=N, batch=int(np.prod(w.shape[:-1])))
    A = quartet_matrix(w, axis)
    # A is real antisymmetric, hence normal: the moduli of its eigenvalues (pairs +-i lambda, and a 0 when
    # N - 1 is odd) are its singular values, descending; a real SVD costs half the complex eigvalsh(1j A)
    sv = interruptible(lambda: np.linalg.svd(A, compute_uv=False))  # (Ctrl-C: LAPACK holds the main thread)
    k = (N - 1) // 2
    return abs(th) * sv[..., : 2 * k : 2]


def expm_antisym(W: np.ndarray, tt: np.ndarray) -> np.ndarray:
    """exp(W t) for one real antisymmetric W and many t (eigh of the Hermitian iW), shape (n_t, N, N).

    Shared in the package (the scenes' closed-form attitude route); not public API.
    """
    lam, U = interruptible(np.linalg.eigh, 1j * W)  # (Ctrl-C: LAPACK holds the main thread)
    ph = np.exp(-1j * tt[:, None] * lam[None, :])
    # U diag(ph_k) U^H for every time: one batched product (BLAS; einsum's three-operand loop took 10 s at N = 900)
    return interruptible(lambda: ((U[None, :, :] * ph[:, None, :]) @ U.conj().T).real)


def quartet_attitude_standard(theta: float, omega0: np.ndarray, tt: np.ndarray, axis: int) -> np.ndarray:
    """T(t) (plain convention, T(0) = 1) of the one-distinguished-axis body, ``tt`` trusted.

    Shared in the package (:func:`quartet_attitude` and the scenes); not public API.
    """
    from ..conventions import to_matrix

    N = dimension_from_count(omega0.size)
    W0 = to_matrix(omega0, convention="standard").astype(float)
    Wr = W0.copy()
    Wr[axis - 1, :] = 0.0
    Wr[:, axis - 1] = 0.0
    R = expm_antisym(theta * Wr, tt)
    S = expm_antisym(W0 - theta * Wr, tt)
    return R @ S


def quartet_attitude(kappa: float, omega0: Any, t: Any, axis: int = 5, *, attitude0: Any = None,
                     convention: str = "paper") -> np.ndarray:
    r"""Exact attitude :math:`T(t)` (eq. 19, :math:`\dot T = W T`) of the quartet body, any N.

    With plain matrices, the solution of :func:`quartet_solution` is
    :math:`W(t) = R(t) W_0 R(t)^{\mathsf T}` with :math:`R(t) = e^{\Theta W_r t}`
    (:math:`W_r` = the constant part of :math:`W` in the planes without the
    distinguished axis; ``R`` fixes :math:`e_a` and commutes with :math:`W_r`).
    Writing :math:`T = R\,S` gives :math:`\dot S = (W_0 - \Theta W_r) S`, so

    .. math:: T(t) = e^{\Theta W_r t}\, e^{(W_0 - \Theta W_r) t}\, T_0,

    the N-dimensional analogue of the regular precession of a symmetric top
    (for equal moments, :math:`\Theta = 0`, :math:`T = e^{W_0 t} T_0`).

    Parameters
    ----------
    kappa, omega0, axis : as in :func:`quartet_solution` (one initial state).
    t : array_like (n_t,), time since the initial state.
    attitude0 : array_like (N, N), optional
        :math:`T_0` in the chosen convention (default identity).
    convention : {"paper", "standard"}
        Matrix convention of ``T`` (:math:`T_\text{paper} = S T_\text{standard} S`).

    Returns
    -------
    numpy.ndarray, shape (n_t, N, N)
    """
    from ..conventions import check_convention

    check_convention(convention)
    w = plane_vector(omega0)
    if w.ndim != 1:
        raise ValueError(f"omega0 must be a single vector of plane components, got shape {w.shape}")
    N = _validate.dimension(dimension_from_count(w.size), name="N of omega0")
    axis = _check_axis(axis, N)
    T0 = None if attitude0 is None else _validate.orthogonal_matrix("attitude0", attitude0, N)
    tt = times(t)
    _pricing.check("closed_form_output", n_times=tt.size, width=N * N)
    _pricing.check("quartet_attitude", d=N, count=2, n_times=tt.size)  # (exp(Theta W_r t), exp((W0 - Theta W_r) t))
    T = quartet_attitude_standard(quartet_theta(kappa), w, tt, axis)
    Sg = np.array([(-1.0) ** k for k in range(1, N + 1)]) if convention == "paper" else np.ones(N)
    if T0 is not None:
        T = T @ (Sg[:, None] * T0 * Sg[None, :])
    return Sg[None, :, None] * T * Sg[None, None, :]
