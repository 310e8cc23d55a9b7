r"""Linear stability of steady rotation in one plane (paper Sec. 4, corrected).

Steady rotation :math:`\omega = \Omega e_p` in the plane :math:`p = (i, j)` is an
equilibrium of the torque-free Euler equations for any inertia. The Jacobian of
:math:`\dot\omega_a = I_a^{-1}\sum_{bc} C_{bc}^{\;a}\,\omega_b I_c \omega_c` is

.. math:: J_{ad} = I_a^{-1}\sum_c C_{dc}^{\;a} (I_c - I_d)\,\omega_c
          \;\xrightarrow{\ \omega = \Omega e_p\ }\; \Omega\,C_{dp}^{\;a}\,(I_p - I_d)/I_a .

It couples only the two planes :math:`(i,k), (j,k)` of each triple
:math:`\{(i,j), (i,k), (j,k)\}`, ``k != i, j`` (an so(3) subalgebra); every other
component (the plane ``p`` itself and the planes disjoint from it) has a zero
row and column. Each triple gives, with
:math:`x = \omega_{ik}, y = \omega_{jk}` (up to the signs of the labels),
:math:`I_{ik}\dot x = \pm\Omega (I_{jk} - I_p) y`,
:math:`I_{jk}\dot y = \pm\Omega (I_p - I_{ik}) x` and

.. math:: \ddot x = -\Omega^2 \nu_k^2 x, \qquad
          \nu_k^2 = \frac{(I_p - I_{ik})(I_p - I_{jk})}{I_{ik} I_{jk}},

eigenvalues :math:`\lambda = \pm i\,\Omega\nu_k`. Hence (the true condition):

**rotation in plane (i, j) is linearly stable iff for every k the moment**
:math:`I_{ij}` **is strictly the largest or strictly the smallest of the triple**
:math:`\{I_{ij}, I_{ik}, I_{jk}\}` (or equals both others). If it is strictly
intermediate for some ``k`` the pair grows like :math:`e^{|\Omega|\sqrt{-\nu_k^2}\,t}`
(N-dimensional tennis-racket instability); if it equals exactly one of them the
zero eigenvalue is defective and the perturbation grows linearly.
For a physical body, :math:`I_{ij} = m_i + m_j`, so
:math:`(I_{ij} - I_{ik})(I_{ij} - I_{jk}) = (m_j - m_k)(m_i - m_k)`: rotation in
the plane ``(i, j)`` is stable iff no other second moment :math:`m_k` lies
between :math:`m_i` and :math:`m_j`.

Paper discrepancies (Sec. 4)
----------------------------
* (121)-(131) are right (each printed as a matrix entry, i.e. with the sign
  :math:`(-1)^{i+j}`); note that (131) numbers the moments differently from the
  :math:`\varpi_k` of (119)-(120) (:math:`J_4 = I^{2323}` but
  :math:`\varpi_4 = \omega_{15}`; :math:`J_7 = I^{1515}`). The text announces
  "four equations satisfied, six remaining" but then lists all ten, and (132)
  is wrong: the constant components are
  :math:`\varpi_1, \varpi_8, \varpi_9, \varpi_{10}` (planes 12, 34, 35, 45), and
  they are constant, not zero; :math:`\varpi_6` (plane 24) oscillates with
  :math:`\varpi_3` (plane 14).
* (133)-(138) as extracted are garbled. The correct solutions are
  :math:`\nu_1^2 = (J_1-J_2)(J_1-J_4)/(J_2J_4)`,
  :math:`\nu_2^2 = (J_1-J_3)(J_1-J_5)/(J_3J_5)`,
  :math:`\nu_3^2 = (J_1-J_7)(J_1-J_8)/(J_7J_8)`, and with
  :math:`\varpi_{2,3,4} = C_1\sin\Omega\nu t + C_2\cos\Omega\nu t`:
  :math:`\varpi_5 = \frac{J_2\nu_1}{J_4-J_1}(C_1\cos - C_2\sin)`,
  :math:`\varpi_6 = \frac{J_3\nu_2}{J_5-J_1}(C_1\cos - C_2\sin)` (the paper's
  denominator :math:`J_1 - J_5` has the wrong sign),
  :math:`\varpi_7 = \frac{J_7\nu_3}{J_8-J_1}(C_1\cos - C_2\sin)`.
* (139)/(140): a total ordering of all ten moments is neither necessary nor
  (with ``>=``) sufficient. Only the three triples matter (the moments
  :math:`J_6, J_9, J_{10}` and the order among :math:`J_2..J_8` are irrelevant),
  and equality :math:`J_1 = J_2 \ne J_4` makes the zero eigenvalue defective
  (linear secular growth). The correct statement is the per-triple condition
  above, with strict inequalities. Also, 5D rotation is in a plane, not "about
  an axis".
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from .._lazy import sympy as sp  # SymPy loads on first use (light ``import hyperrotor``)

from ..conventions import (_structure_constants_slice, check_dimension, dimension_from_count, plane_index,
                           plane_label)
from .. import _pricing, _validate
from .._equality import fields_equal
from .._options import options, register

register(
    "stability_rtol", 1e-12,
    "linear_stability: a moment difference |I_p - I_q| <= this * max(I_p, I_q) counts as an equality (a neutral or "
    "secular pair instead of a tiny frequency or growth rate). 1e-12 is far above the round-off of moments "
    "computed from a mass distribution (~1e-15 relative) and far below any physical splitting.",
)
register(
    "perturbation_growth_rtol", 1e-11,
    "perturbation_growth: rtol of its integration (hyperrotor.simulate). The tracked off-plane components "
    "start at eps (1e-8 by default) times |omega0|; 1e-11 keeps the integration error ~1000x below them, so "
    "the growth measured is the body's, not the integrator's.",
)

__all__ = [
    "CoupledPair",
    "StabilityResult",
    "linear_stability",
    "linearization",
    "stability_condition",
    "perturbation_growth",
]


def _labels(body: Any, N: int) -> tuple[int, ...]:
    """Axis labels of the body (a locked RigidBody keeps its original labels, e.g. (2, 3, 4, 5))."""
    axes = getattr(body, "axes", None)
    if axes is not None and len(tuple(axes)) == N:
        return tuple(int(a) for a in axes)
    return tuple(range(1, N + 1))


def _local_plane(plane: Any, labels: tuple[int, ...]) -> tuple[int, int]:
    """Translate a plane given in the body's axis labels to local 1..N labels."""
    a, b = _validate.plane(plane, max(max(labels), 2))  # a pair of integers, 1 <= a < b
    if a not in labels or b not in labels:
        raise ValueError(f"unknown plane {_validate.fmt(plane)}: planes are pairs (i, j), i < j, of the body's axes {labels}")
    return labels.index(a) + 1, labels.index(b) + 1


def _plane(plane: Any, N: int) -> tuple[int, int]:
    return _validate.plane(plane, N)


@dataclass(frozen=True)
class CoupledPair:
    r"""The two planes :math:`(i,k), (j,k)` coupled to the rotation plane :math:`(i,j)` by the triple ``k``.

    Attributes
    ----------
    k : int
        The third axis (1-based).
    planes : tuple of two plane labels
        ``((min(i,k), max(i,k)), (min(j,k), max(j,k)))``.
    nu2 : float
        :math:`\nu_k^2 = (I_p - I_{ik})(I_p - I_{jk})/(I_{ik} I_{jk})`; the pair's
        eigenvalues are :math:`\pm\Omega\sqrt{-\nu_k^2}` (computed from the two factors, so they stay
        finite where :math:`\nu_k^2` itself passes the double range, e.g. moments 1e200 and 1: then ``inf``).
    kind : str
        ``"oscillating"`` (:math:`\nu^2 > 0`), ``"unstable"`` (:math:`\nu^2 < 0`),
        ``"secular"`` (exactly one of the differences zero: defective zero
        eigenvalue) or ``"neutral"`` (both zero).
    """

    k: int
    planes: tuple
    nu2: float
    kind: str


@dataclass(frozen=True)
class StabilityResult:
    r"""Linearisation about steady rotation :math:`\omega = \Omega e_p` (see the module docstring).

    Attributes
    ----------
    plane : tuple
    omega0 : float
        The steady angular velocity :math:`\Omega` in the plane.
    jacobian : ndarray (n_planes, n_planes)
        :math:`J_{ad} = \Omega C_{dp}^{\;a} (I_p - I_d)/I_a` (``inf`` where an entry passes the double range:
        moments 1e300 and 1e-300; the eigenvalues below come from the pairs' factors and stay finite as long as
        they fit).
    eigenvalues : ndarray, complex (n_planes,)
        From the 2x2 blocks: :math:`\pm\Omega\sqrt{-\nu_k^2}` per pair, zeros for the
        uncoupled components. Exact (purely imaginary when stable).
    frequencies : ndarray
        Angular frequencies :math:`|\Omega|\nu_k` of the oscillating pairs.
    growth_rates : ndarray
        :math:`|\Omega|\sqrt{-\nu_k^2}` of the unstable pairs.
    pairs : tuple of CoupledPair
    stable : bool
        Linear stability: every eigenvalue purely imaginary and no defective
        (secularly growing) zero eigenvalue. Moment differences with
        ``|I_p - I_q| <= rtol * max(I_p, I_q)`` count as equalities.
    condition : str
        The stability condition for this plane, one factor per triple.
    reason : str
        Why it is (un)stable.
    """

    __eq__ = fields_equal  # (field by field: the generated == refuses array fields)
    __hash__ = None

    plane: tuple
    omega0: float
    jacobian: np.ndarray = field(repr=False)
    eigenvalues: np.ndarray
    frequencies: np.ndarray
    growth_rates: np.ndarray
    pairs: tuple
    stable: bool
    condition: str
    reason: str


def linearization(body: Any, plane: Any, omega0: float) -> np.ndarray:
    r"""Jacobian of the Euler equations at :math:`\omega = \Omega e_p` (:math:`\Omega` = ``omega0``):
    :math:`J_{ad} = \Omega\,C_{dp}^{\;a}\,(I_p - I_d)/I_a` (matrix ``(n_planes, n_planes)``)."""
    I = _validate.moments(body, name="body")
    N = dimension_from_count(I.size)
    _pricing.check("linearization", N=N)
    local = _local_plane(plane, _labels(body, N))  # (a locked body's planes in its own axis labels)
    p = plane_index(local, N)
    Om = _validate.real("omega0", omega0)
    # J[a, d] = Omega * C[d, p, a] * (I_p - I_d) / I_a: the 2 (N - 2) nonzero entries of the plane's slice of the
    # structure constants, built alone (the whole n^3 table was 5.2 GB at N = 60)
    d, a, c = _structure_constants_slice(N, local)
    J = np.zeros((I.size, I.size))
    with np.errstate(over="ignore"):  # (moments 1e300 and 1e-300 make an entry of ~1e600: inf, documented)
        J[a, d] = Om * c * (I[p] - I[d]) / I[a]  # (each entry once)
    return J


@_pricing.model("stability_condition", "ask for a smaller N")
def _condition_cost(N: Any) -> tuple:
    """One SymPy inequality per third axis (~4 ms each, measured: N = 1000 takes 4.2 s)."""
    return (_pricing.Cost(f"{float(N) - 2:.0f} SymPy inequalities", 5e-3 * max(float(N) - 2.0, 0.0),
                          "max_seconds", "seconds"),)


def stability_condition(plane: Any, N: int, *, symbol: str = "I"):
    r"""SymPy condition for linear stability of rotation in ``plane``:
    :math:`\bigwedge_k (I_p - I_{ik})(I_p - I_{jk}) > 0` over the axes ``k != i, j``.

    Sufficient and, up to the measure-zero case :math:`I_p = I_{ik} = I_{jk}`
    (neutral), necessary. Symbols are ``plane_symbols(symbol, N)``.
    """
    N = check_dimension(N)
    _pricing.check("stability_condition", N=N)
    i, j = _plane(plane, N)
    if not isinstance(symbol, str) or not symbol.isidentifier():
        raise TypeError(f"symbol must be an identifier string such as 'I', got {_validate.fmt(symbol)}")
    # only the 2N - 3 symbols of the planes through i or j, named as plane_symbols(symbol, N) names them
    through = {(min(a, k), max(a, k)) for a in (i, j) for k in range(1, N + 1) if k != a}
    Is = {p: sp.Symbol(f"{symbol}_{plane_label(p, N)}") for p in through}
    Ip = Is[(i, j)]
    terms = []
    for k in range(1, N + 1):
        if k in (i, j):
            continue
        a, b = Is[(min(i, k), max(i, k))], Is[(min(j, k), max(j, k))]
        terms.append((Ip - a) * (Ip - b) > 0)
    return sp.And(*terms)


def linear_stability(body: Any, plane: Any, omega0: float, *, rtol: float | None = None) -> StabilityResult:
    r"""Linear stability of steady rotation :math:`\omega = \Omega e_{\text{plane}}` (Sec. 4, corrected).

    Parameters
    ----------
    body : RigidBody, Inertia or array_like (n_planes,)
        The plane moments.
    plane : (i, j)
        1-based rotation plane, ``i < j``, in the body's axis labels (a body
        from :meth:`RigidBody.lock` keeps its original labels).
    omega0 : float
        Angular velocity :math:`\Omega` of the steady rotation.
    rtol : float, optional
        Moment differences ``|I_p - I_q| <= rtol * max(I_p, I_q)`` count as zero, ``0 <= rtol < 1``
        (default ``hr.options["stability_rtol"]``, 1e-12).

    Returns
    -------
    StabilityResult
        For the 5D body and ``plane=(1, 2)`` the pairs are ``((1,3),(2,3))``,
        ``((1,4),(2,4))``, ``((1,5),(2,5))`` with
        :math:`\nu^2 = (I_{12}-I_{13})(I_{12}-I_{23})/(I_{13}I_{23})`, etc.
        (eqs. 122-127, 135-138 corrected).

    Examples
    --------
    >>> import numpy as np
    >>> I = np.array([3.0, 2.0, 1.0])            # 3D: I_12 > I_13 > I_23
    >>> linear_stability(I, (1, 3), 1.0).stable  # intermediate moment: tennis racket
    False
    """
    I = _validate.moments(body, name="body")
    N = dimension_from_count(I.size)
    labels = _labels(body, N)
    i, j = _local_plane(plane, labels)
    lab = lambda q: (labels[q[0] - 1], labels[q[1] - 1])  # noqa: E731  local -> body labels
    Om = _validate.real("omega0", omega0)
    rtol = options["stability_rtol"] if rtol is None else _validate.tolerance("rtol", rtol, allow_zero=True)
    p = plane_index((i, j), N)
    pairs, eig = [], []
    freqs, rates, factors = [], [], []
    secular = unstable = False
    for k in range(1, N + 1):
        if k in (i, j):
            continue
        P1, P2 = (min(i, k), max(i, k)), (min(j, k), max(j, k))
        I1, I2 = I[plane_index(P1, N)], I[plane_index(P2, N)]
        d1, d2 = I[p] - I1, I[p] - I2
        # (relative to the two moments compared: against max(I), a body with one moment of 1e14 had every
        # difference of order 1 counted as an equality, its oscillating pairs reported secular)
        d1 = 0.0 if abs(d1) <= rtol * max(I[p], I1) else d1
        d2 = 0.0 if abs(d2) <= rtol * max(I[p], I2) else d2
        r1, r2 = float(d1) / float(I1), float(d2) / float(I2)  # (Python floats: an overflow is inf, no warning)
        nu2 = r1 * r2  # (inf beyond the double range: 1e200 against 1; the roots below come from its factors)
        root = math.sqrt(abs(r1)) * math.sqrt(abs(r2))  # sqrt|nu^2|, finite wherever |Omega| sqrt|nu^2| is
        if d1 == 0.0 and d2 == 0.0:
            kind = "neutral"
        elif d1 == 0.0 or d2 == 0.0:
            kind = "secular"
        elif (r1 > 0) == (r2 > 0):
            kind = "oscillating"
        else:
            kind = "unstable"
        pairs.append(CoupledPair(k=labels[k - 1], planes=(lab(P1), lab(P2)), nu2=float(nu2), kind=kind))
        lam = complex(0.0, Om * root) if kind == "oscillating" else complex(Om * root)  # (+-Omega sqrt(-nu^2);
        # complex(0, x), not x * 1j: inf * 1j is nan + inf j)
        eig += [lam, -lam]
        if Om != 0.0:
            if kind == "oscillating":
                freqs.append(abs(Om) * root)
            elif kind == "unstable":
                rates.append(abs(Om) * root)
                unstable = True
            elif kind == "secular":
                secular = True
        lp, l1, l2 = (f"I_{plane_label(lab(q), max(labels))}" for q in ((i, j), P1, P2))
        factors.append(f"({lp} - {l1})*({lp} - {l2}) > 0")
    eig += [0j] * (I.size - len(eig))
    stable = not (unstable or secular)
    if Om == 0.0:
        reason = "omega0 = 0: the linearisation vanishes (rest is trivially stable)"
    elif unstable:
        bad = [pr for pr in pairs if pr.kind == "unstable"]
        reason = "I_p is strictly intermediate in the triple(s) k = " + ", ".join(str(pr.k) for pr in bad) + " (exponential growth)"
    elif secular:
        bad = [pr for pr in pairs if pr.kind == "secular"]
        reason = "I_p equals exactly one other moment in the triple(s) k = " + ", ".join(str(pr.k) for pr in bad) + " (defective zero eigenvalue, linear growth)"
    else:
        reason = "I_p is the largest or the smallest moment of every coupled triple"
    return StabilityResult(
        plane=lab((i, j)),
        omega0=Om,
        jacobian=linearization(I, (i, j), Om),
        eigenvalues=np.array(eig, dtype=complex),
        frequencies=np.array(freqs),
        growth_rates=np.array(rates),
        pairs=tuple(pairs),
        stable=bool(stable),
        condition=" and ".join(factors) if factors else "True",
        reason=reason,
    )


def perturbation_growth(body: Any, plane: Any, omega0: float, t: Any, *, eps: float = 1e-8, rng: Any = 0,
                        method: str = "DOP853", rtol: float | None = None) -> np.ndarray:
    r"""Nonlinear check of (in)stability: largest off-plane component of a perturbed steady rotation.

    Integrates the full Euler equations (:func:`hyperrotor.simulate`) from
    :math:`\omega_0 = \Omega e_p + \epsilon\,\xi` (:math:`\Omega` = ``omega0``, :math:`\xi`
    standard normal drawn from ``rng``: an int seed, a :class:`numpy.random.Generator` or
    ``None`` for fresh entropy; the default seed 0 makes the result reproducible) and returns :math:`\max_{q \ne p} |\omega_q(t)|` on the grid ``t``
    (``t[0]`` is the initial time). For an unstable plane it grows like
    :math:`\epsilon\,e^{\sigma t}` with :math:`\sigma` the largest entry of
    :attr:`StabilityResult.growth_rates` (the N-dimensional tennis-racket
    effect) until it saturates at the size of :math:`\Omega`; for a stable plane
    it stays of order :math:`\epsilon`.

    The integration uses ``method`` and ``rtol`` (default
    ``hr.options["perturbation_growth_rtol"]``, 1e-11).

    Returns
    -------
    numpy.ndarray, shape (len(t),)
    """
    from .simulate import simulate
    from .solvers import StepBudgetError

    I = _validate.moments(body, name="body")
    N = dimension_from_count(I.size)
    i, j = _local_plane(plane, _labels(body, N))
    p = plane_index((i, j), N)
    rtol = options["perturbation_growth_rtol"] if rtol is None else _validate.positive("rtol", rtol)
    w0 = _validate.real("eps", eps) * _validate.rng(rng).normal(size=I.size)
    w0[p] = _validate.real("omega0", omega0)
    try:
        traj = simulate(I, w0, t, method=method, rtol=rtol)
    except StepBudgetError as exc:  # name the arguments that set the size of the run
        raise type(exc)(f"perturbation_growth(omega0 = {_validate.fmt(omega0)}, t up to "
                        f"{_validate.fmt(float(np.max(np.abs(_validate.time_grid(t)))))}): {exc}",
                        needed=exc.needed, budget=exc.budget, option=exc.option) from None
    return np.max(np.abs(np.delete(traj.omega, p, axis=-1)), axis=-1)
