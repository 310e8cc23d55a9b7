r"""Closed form of the 3D free body (Euler-Poinsot) with Jacobi elliptic functions.

The third family of closed forms beside the paper's Sec. 3.1 (equal moments) and 3.2 (the quartet): the
textbook solution of the 3D reduction (the paper's Sec. 3 has no 3D subsection). :func:`euler_poinsot` gives
:math:`\omega(t)` in both regimes of the energy-momentum relation, on the separatrix and for the symmetric top,
in the package order
``(w12, w13, w23)``; :func:`euler_poinsot_period` its period. Moments and ``omega0`` of any
scale are exact (scaled by powers of two). Close to the separatrix (a spin about the middle axis, tilted)
the parameter's distance :math:`1 - m` to it is computed exactly and carried separately (``ellipkm1``,
Carlson's :math:`R_F`, and sn/cn/dn from :math:`1 - m`): omega within ~1e-13 of mpmath at 60 digits for
tilts down to 1e-16, where the float ``m`` alone is 1. :func:`~.closed_form.closed_form_solution` dispatches
here for N = 3.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from .. import _pricing, _validate
from .._floats import power_of_two_scale
from .._lazy import LazyModule
from ._closed_form_input import plane_vector, times

#: scipy.special (elliptic functions), loaded on first use: ``import hyperrotor`` stays light.
special = LazyModule("scipy.special")

__all__ = ["euler_poinsot", "euler_poinsot_period"]

_EPS = float(np.finfo(float).eps)

_EVEN_PERMS = {(0, 1, 2), (1, 2, 0), (2, 0, 1)}


def _ellipj(u: np.ndarray, m: float, m1: float):
    r"""Jacobi sn, cn, dn accurate to a few ulp for all ``u`` and ``0 <= m <= 1`` (``m1 = 1 - m``, given
    separately with its full relative accuracy: near the separatrix ``m`` cannot carry it).

    ``scipy.special.ellipj`` (Cephes) switches to a first-order expansion in
    ``1 - m`` for ``m > 1 - 1e-9`` that is only valid for small ``|u|`` (it
    returns values ~1e17 at ``u = 3K`` for ``m = 1 - 1e-10``). The argument is
    therefore reduced to ``[-K, K]`` with :math:`\mathrm{sn}(u + 2K) = -\mathrm{sn}\,u`,
    :math:`\mathrm{cn}(u + 2K) = -\mathrm{cn}\,u`, :math:`\mathrm{dn}(u+2K) = \mathrm{dn}\,u`,
    and ``|u| > K/2`` is folded to ``v = K - |u|`` with
    :math:`\mathrm{sn}(K - v) = \mathrm{cd}\,v`, :math:`\mathrm{cn}(K - v) = k'\,\mathrm{sd}\,v`,
    :math:`\mathrm{dn}(K - v) = k'\,\mathrm{nd}\,v`; ``K = ellipkm1(m1)``. For ``m1 <`` :data:`_NEAR_SEPARATRIX`
    the folded argument goes to :func:`_sn_agm` and :func:`_cn_dn_near_separatrix` (from ``m1``), else to
    ``scipy.special.ellipj``.
    """
    u = np.asarray(u, dtype=float)
    if m1 <= 0.0:  # separatrix: sn = tanh, cn = dn = sech (exact in Cephes for m = 1)
        s, c, d, _ = special.ellipj(u, 1.0)
        return s, c, d
    K = float(special.ellipkm1(m1))
    kp = np.sqrt(m1)
    j = np.round(u / (2.0 * K))
    v = u - 2.0 * K * j
    sg = np.where(np.mod(j, 2.0) == 0.0, 1.0, -1.0)
    av = np.abs(v)
    sv = np.where(v < 0.0, -1.0, 1.0)
    far = av > 0.5 * K
    w = np.where(far, K - av, av)
    if m1 < _NEAR_SEPARATRIX:
        s, (c, d) = _sn_agm(w, m1), _cn_dn_near_separatrix(w, m1, K)
    else:
        s, c, d, _ = special.ellipj(w, m)
    sn = np.where(far, c / d, s) * sv
    cn = np.where(far, kp * s / d, c)
    dn = np.where(far, kp / d, d)
    return sg * sn, sg * cn, dn


#: below this 1 - m, sn/cn/dn come from the AGM in 1 - m (scipy's ellipj takes m, whose rounding is an absolute
#: error eps in 1 - m: a relative error eps / (1 - m) in the period and the phase near the separatrix)
_NEAR_SEPARATRIX = 1e-3


def _sn_agm(u: np.ndarray, m1: float) -> np.ndarray:
    r"""sn by the arithmetic-geometric mean (Cephes ``ellpj``'s descending Landen iteration), started from
    :math:`b_0 = \sqrt{m_1}`, :math:`c_0 = \sqrt{1 - m_1}` so that ``m1 = 1 - m`` keeps its relative accuracy
    (``0 < m1 < 1``): :math:`a_{n+1} = (a_n + b_n)/2`, :math:`b_{n+1} = \sqrt{a_n b_n}`,
    :math:`c_{n+1} = (a_n - b_n)/2` until :math:`c_N / a_N < \epsilon`, then
    :math:`\varphi_N = 2^N a_N u`, :math:`\varphi_{n-1} = (\varphi_n + \arcsin(c_n \sin\varphi_n / a_n))/2`,
    :math:`\mathrm{sn} = \sin\varphi_0` (Abramowitz & Stegun 16.4). Absolute error ~1e-16 for
    ``0 <= u <= K/2`` and every ``m1`` down to 1e-300 (measured against mpmath); cn and dn are small there near
    the separatrix and come from :func:`_cn_dn_near_separatrix` instead (their cosines lose relative accuracy)."""
    a, c = [1.0], [float(np.sqrt(1.0 - m1))]
    b = float(np.sqrt(m1))
    twon = 1.0
    while abs(c[-1] / a[-1]) > _EPS and len(a) < 64:  # (quadratic once a ~ b: ~15 levels at m1 = 1e-300)
        an = a[-1]
        c.append(0.5 * (an - b))
        a.append(0.5 * (an + b))
        b, twon = float(np.sqrt(an * b)), 2.0 * twon
    phi = twon * a[-1] * np.asarray(u, dtype=float)
    for n in range(len(a) - 1, 0, -1):
        phi = 0.5 * (np.arcsin(c[n] * np.sin(phi) / a[n]) + phi)
    return np.sin(phi)


def _cn_dn_near_separatrix(u: np.ndarray, m1: float, K: float):
    r"""cn and dn with full relative accuracy near the separatrix (``m1 = 1 - m`` small) from the series of
    sech over the periods (Jacobi's imaginary transformation of the Fourier series, A&S 16.23):

    .. math:: \mathrm{dn}(u|m) = \frac{\pi}{2K'} \sum_n \mathrm{sech}\,x_n, \quad
              \mathrm{cn}(u|m) = \frac{\pi}{2kK'} \sum_n (-1)^n\,\mathrm{sech}\,x_n, \quad
              x_n = \frac{\pi (u - 2nK)}{2K'},

    :math:`K' = K(m_1)`, :math:`k = \sqrt{1 - m_1}`; for ``m1 < 1e-3`` the terms ``|n| > 4`` are below 1e-17 of
    the first (they fall like :math:`e^{-2|n|K}`, :math:`K > 4.8`). Relative error ~1e-15 for ``0 <= u <= K/2``
    (3e-14 at m1 = 1e-300, measured against mpmath)."""
    Kp = float(special.ellipk(m1))
    n = np.arange(-4, 5)[:, None]
    x = np.abs(np.pi * (np.asarray(u, dtype=float)[None, :] - 2.0 * n * K) / (2.0 * Kp))
    e = np.exp(-x)
    sech = 2.0 * e / (1.0 + e * e)  # (no overflow of cosh for the far terms)
    scale = np.pi / (2.0 * Kp)
    return scale / np.sqrt(1.0 - m1) * (np.where(n % 2 == 0, 1.0, -1.0) * sech).sum(axis=0), scale * sech.sum(axis=0)


def _ep_setup(body: Any, omega0: Any):
    I = _validate.moments(body, name="body")
    if I.size != 3:
        raise ValueError(f"euler_poinsot needs the 3 plane moments (I_12, I_13, I_23) of a 3D body, got {I.size}")
    w = plane_vector(omega0, 3)
    if w.ndim != 1:
        raise ValueError(f"omega0 must be a single vector (w12, w13, w23), got shape {w.shape}")
    # The motion does not change under I -> c I and scales as w(t) = c w~(c t) under w0 -> c w0:
    # compute with moments and omega0 divided by powers of two (exact), so that no product of the
    # formulas below under- or overflows (moments of 1e-310 gave NaN, #21).
    scale = power_of_two_scale(float(np.max(np.abs(w))))
    In, wn = I / power_of_two_scale(float(np.max(I))), w / scale
    # textbook map: W1 = w23, W2 = -w13, W3 = w12; I1 = I23, I2 = I13, I3 = I12
    Itb = np.array([In[2], In[1], In[0]])
    Wtb = np.array([wn[2], -wn[1], wn[0]])
    order = np.argsort(Itb, kind="stable")  # ascending
    lo, mid, hi = order
    # sign of L^2 - 2 E I_mid, cancellation-free
    s = Itb[hi] * (Itb[hi] - Itb[mid]) * Wtb[hi] ** 2 - Itb[lo] * (Itb[mid] - Itb[lo]) * Wtb[lo] ** 2
    d = hi if s >= 0 else lo  # dn axis (the one W never changes sign on)
    c = lo if s >= 0 else hi  # cn axis
    perm = (c, mid, d)
    flip = 1.0 if perm in _EVEN_PERMS else -1.0  # odd relabelling = time reversal: V = -W[perm]
    J = Itb[list(perm)]
    V = flip * Wtb[list(perm)]
    # sign symmetries (-,+,-) and (-,-,+) of the Euler equations: make V3 >= 0 and V1 >= 0
    sg = np.ones(3)
    if V[2] < 0:
        sg *= np.array([-1.0, 1.0, -1.0])
    if sg[0] * V[0] < 0:
        sg *= np.array([-1.0, -1.0, 1.0])
    V = sg * V
    J1, J2, J3 = J
    V1, V2, V3 = V
    # cancellation-free: 2EJ3 - L^2 = J1(J3-J1)V1^2 + J2(J3-J2)V2^2 etc.
    p31, p32, p21 = J1 * (J3 - J1), J2 * (J3 - J2), J2 * (J2 - J1)
    r = p21 * V2**2 + J3 * (J3 - J1) * V3**2  # L^2 - 2 E J1
    with np.errstate(divide="ignore", invalid="ignore"):
        A = np.sqrt(V1**2 + (p32 / p31) * V2**2) if p31 != 0 else abs(V1)
        B = np.sqrt((p31 / p32) * V1**2 + V2**2) if p32 != 0 else abs(V2)
        C = np.sqrt((p21 / (J3 * (J3 - J1))) * V2**2 + V3**2) if J3 != J1 else abs(V3)
    nu2 = (J3 - J2) * r / (J1 * J2 * J3)
    nu = np.sign(J3 - J2) * np.sqrt(max(nu2, 0.0))
    m, m1 = _parameter(J, V)
    # V, A, B, C, nu describe omega0 / scale; the motion is scale times them at time scale * t
    return dict(I=I, w=w, perm=perm, flip=flip, sg=sg, V=V, J=J, A=A, B=B, C=C, nu=nu, m=m, m1=m1, scale=scale)


def _parameter(J: np.ndarray, V: np.ndarray) -> tuple[float, float]:
    r"""``(m, 1 - m)``, each correctly rounded: computed exactly in rational arithmetic from the (exact) floats
    ``J``, ``V`` (a scalar setup). :math:`1 - m = (J_3-J_1)[(J_3-J_2)J_3V_3^2 - (J_2-J_1)J_1V_1^2] /
    ((J_3-J_2)(L^2 - 2EJ_1))` is the distance to the separatrix: ``m`` in floating point carries it with an
    absolute error eps, i.e. a relative error eps / (1 - m) that went into the period and the phase (a spin
    about the middle axis tilted by 1e-8: the period 0.5% off; by 1e-10: 1 - m below eps, m = 1, a constant
    omega while the body flips)."""
    from fractions import Fraction

    J1, J2, J3 = (Fraction(float(x)) for x in J)
    V1, V2, V3 = (Fraction(float(x)) for x in V)
    q = J1 * (J3 - J1) * V1**2 + J2 * (J3 - J2) * V2**2  # 2 E J3 - L^2
    r = J2 * (J2 - J1) * V2**2 + J3 * (J3 - J1) * V3**2  # L^2 - 2 E J1
    if q == 0 or J2 == J1 or r == 0:
        return 0.0, 1.0
    m1 = (J3 - J1) * ((J3 - J2) * J3 * V3**2 - (J2 - J1) * J1 * V1**2) / ((J3 - J2) * r)
    m1 = min(max(m1, Fraction(0)), Fraction(1))
    return float(1 - m1), float(m1)


def _is_steady(P) -> bool:
    """True when the right-hand side vanishes exactly (rest or principal-axis rotation)."""
    J, V = P["J"], P["V"]
    return P["nu"] == 0.0 or (
        (J[1] - J[2]) * V[1] * V[2] == 0.0 and (J[2] - J[0]) * V[2] * V[0] == 0.0 and (J[0] - J[1]) * V[0] * V[1] == 0.0
    )


def euler_poinsot(body: Any, omega0: Any, t: Any) -> np.ndarray:
    r"""Exact 3D torque-free motion (Euler-Poinsot) with Jacobi elliptic functions.

    Components in the package order ``(w12, w13, w23)``; internally the textbook
    map :math:`W_1 = \omega_{23}, W_2 = -\omega_{13}, W_3 = \omega_{12}`,
    :math:`I_1 = I_{23}, I_2 = I_{13}, I_3 = I_{12}` turns the equations into
    :math:`I_1\dot W_1 = (I_2 - I_3) W_2 W_3` (cyclic). The axes are relabelled as
    ``(cn, sn, dn)`` = (an extreme axis, the middle axis, the other extreme axis),
    the dn axis being the largest-moment axis when :math:`L^2 > 2 E I_\text{mid}`
    and the smallest otherwise (an odd relabelling is compensated by
    :math:`W \to -W`). Then, with :math:`J_1, J_2, J_3` the relabelled moments,

    .. math::
        V_1 = A\,\mathrm{cn}(u), \quad V_2 = B\,\mathrm{sn}(u), \quad V_3 = C\,\mathrm{dn}(u),
        \qquad u = u_0 + \nu t,

        A^2 = \frac{2EJ_3 - L^2}{J_1(J_3 - J_1)},\;
        B^2 = \frac{2EJ_3 - L^2}{J_2(J_3 - J_2)},\;
        C^2 = \frac{L^2 - 2EJ_1}{J_3(J_3 - J_1)},\;
        \nu^2 = \frac{(J_3-J_2)(L^2 - 2EJ_1)}{J_1J_2J_3},\;
        m = k^2 = \frac{(J_2-J_1)(2EJ_3 - L^2)}{(J_3-J_2)(L^2 - 2EJ_1)},

    :math:`\operatorname{sign}\nu = \operatorname{sign}(J_3 - J_2)`, and :math:`u_0 =
    F(\operatorname{atan2}(V_2(0)/B, V_1(0)/A)\,|\,m)`. Signs of the initial state
    are absorbed by the symmetries :math:`(V_1,V_2,V_3)\to(-V_1,V_2,-V_3)` and
    :math:`(-V_1,-V_2,V_3)`. All differences :math:`2EJ_3 - L^2` etc. are formed
    without cancellation. ``m = 1`` is the separatrix (cn = dn = sech,
    sn = tanh), ``m = 0`` the symmetric top / steady rotation.

    Parameters
    ----------
    body : RigidBody, Inertia or array_like (3,)
        Plane moments ``(I_12, I_13, I_23)`` (any positive scale: the formulas are evaluated
        with the moments and ``omega0`` scaled by powers of two, so tiny or huge values are exact).
    omega0 : array_like (3,)
        ``(w12, w13, w23)`` at t = 0.
    t : array_like (n_t,)

    Returns
    -------
    numpy.ndarray, shape (n_t, 3)
    """
    tt = times(t)
    P = _ep_setup(body, omega0)
    w = P["w"]
    _pricing.check("closed_form_output", n_times=tt.size, width=np.size(w))
    if _is_steady(P):  # steady rotation about a principal axis (or rest)
        return np.broadcast_to(w, (tt.size, 3)).copy()
    A, B, C, nu, m = P["A"], P["B"], P["C"], P["nu"], P["m"]
    V1, V2 = P["V"][0], P["V"][1]
    m1 = P["m1"]
    u0 = _incomplete_k(V2 / B if B > 0 else 0.0, V1 / A if A > 0 else 1.0, m1)
    if not np.isfinite(u0):  # m = 1 and V1 = 0: the unstable middle-axis equilibrium
        return np.broadcast_to(w, (tt.size, 3)).copy()
    s = P["scale"]
    sn, cn, dn = _ellipj(u0 + nu * (s * tt), m, m1)
    V = np.stack([A * cn, B * sn, C * dn], axis=-1) * (P["sg"] * P["flip"] * s)
    Wtb = np.empty_like(V)
    Wtb[:, list(P["perm"])] = V
    return np.stack([Wtb[:, 2], -Wtb[:, 1], Wtb[:, 0]], axis=-1)


def euler_poinsot_period(body: Any, omega0: Any) -> float:
    r"""Period of :math:`\omega(t)` of the 3D free body: :math:`4K(m)/|\nu|` (``inf`` on the
    separatrix, ``inf`` for steady rotation)."""
    P = _ep_setup(body, omega0)
    if P["m1"] <= 0.0:
        return float("inf")
    if _is_steady(P):
        # steady in the scaled frame; but when omega0's other components only underflowed there (1e-300 beside
        # 1e308: a ratio beyond the floats), it is a small oscillation about an extreme axis, whose period has the
        # limit 4 K(0) / |nu| = 2 pi / |nu| (it returned inf)
        w = P["w"]
        if P["nu"] == 0.0 or not np.any((w != 0.0) & (w / P["scale"] == 0.0)):
            return float("inf")
    return 4.0 * float(special.ellipkm1(P["m1"])) / abs(P["nu"]) / P["scale"]


def _incomplete_k(y: float, x: float, m1: float) -> float:
    r""":math:`F(\varphi | m)` at :math:`\varphi = \operatorname{atan2}(y, x)`, from ``m1 = 1 - m``:
    :math:`F = 2jK + \sin\psi\, R_F(\cos^2\psi,\, \cos^2\psi + m_1 \sin^2\psi,\, 1)` with
    :math:`\varphi = \psi + j\pi`, :math:`|\psi| \le \pi/2` (Carlson's symmetric form, ``scipy.special.elliprf``;
    its second argument :math:`1 - m\sin^2\psi` formed without cancellation). :math:`\cos\varphi = x/h`,
    :math:`\sin\varphi = y/h` come from the components, not from the angle: near the separatrix
    :math:`\varphi \approx \pi/2` and :math:`\cos` of the rounded angle lost its relative accuracy (a tilt of
    1e-14 put u0 off by 2e-3). ``inf`` at :math:`\psi = \pm\pi/2` on the separatrix."""
    h = float(np.hypot(x, y))
    c, s = x / h, y / h
    j = 0.0 if c >= 0.0 else (1.0 if s >= 0.0 else -1.0)
    if j:
        c, s = -c, -s
    c2 = c * c
    K = float(special.ellipkm1(m1)) if m1 > 0.0 else float("inf")
    if c2 == 0.0:  # psi = +-pi/2: F = +-K (inf on the separatrix; R_F(0, m1, 1) overflows for a subnormal m1)
        return (2.0 * j + (1.0 if s > 0 else -1.0)) * K
    return (2.0 * j * K if j else 0.0) + s * float(special.elliprf(c2, c2 + m1 * s * s, 1.0))
