r"""Closed form of the 3D free body (Euler-Poinsot) with Jacobi elliptic functions.

Paper Sec. 3's third family: :func:`euler_poinsot` gives :math:`\omega(t)` in both regimes of the
energy-momentum relation, on the separatrix and for the symmetric top, in the package order
``(w12, w13, w23)``; :func:`euler_poinsot_period` its period. Moments and ``omega0`` of any
scale are exact (scaled by powers of two). :func:`~.closed_form.closed_form_solution` dispatches here
for N = 3.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from .. import _pricing, _validate
from .._lazy import LazyModule
from ._closed_form_input import plane_vector, times

#: scipy.special (elliptic functions), loaded on first use: ``import hyperrotor`` stays light.
special = LazyModule("scipy.special")

__all__ = ["euler_poinsot", "euler_poinsot_period"]

_EVEN_PERMS = {(0, 1, 2), (1, 2, 0), (2, 0, 1)}


def _ellipj(u: np.ndarray, m: float):
    r"""Jacobi sn, cn, dn accurate to a few ulp for all ``u`` and ``0 <= m <= 1``.

    ``scipy.special.ellipj`` (Cephes) switches to a first-order expansion in
    ``1 - m`` for ``m > 1 - 1e-9`` that is only valid for small ``|u|`` (it
    returns values ~1e17 at ``u = 3K`` for ``m = 1 - 1e-10``). The argument is
    therefore reduced to ``[-K, K]`` with :math:`\mathrm{sn}(u + 2K) = -\mathrm{sn}\,u`,
    :math:`\mathrm{cn}(u + 2K) = -\mathrm{cn}\,u`, :math:`\mathrm{dn}(u+2K) = \mathrm{dn}\,u`,
    and ``|u| > K/2`` is folded to ``v = K - |u|`` with
    :math:`\mathrm{sn}(K - v) = \mathrm{cd}\,v`, :math:`\mathrm{cn}(K - v) = k'\,\mathrm{sd}\,v`,
    :math:`\mathrm{dn}(K - v) = k'\,\mathrm{nd}\,v`.
    """
    u = np.asarray(u, dtype=float)
    if m >= 1.0:  # separatrix: sn = tanh, cn = dn = sech (exact in Cephes for m = 1)
        s, c, d, _ = special.ellipj(u, 1.0)
        return s, c, d
    K = float(special.ellipk(m))
    kp = np.sqrt(1.0 - m)
    j = np.round(u / (2.0 * K))
    v = u - 2.0 * K * j
    sg = np.where(np.mod(j, 2.0) == 0.0, 1.0, -1.0)
    av = np.abs(v)
    sv = np.where(v < 0.0, -1.0, 1.0)
    far = av > 0.5 * K
    w = np.where(far, K - av, av)
    s, c, d, _ = special.ellipj(w, m)
    sn = np.where(far, c / d, s) * sv
    cn = np.where(far, kp * s / d, c)
    dn = np.where(far, kp / d, d)
    return sg * sn, sg * cn, dn


def _pow2(x: float) -> float:
    """The power of two nearest above ``x > 0`` (1 for 0): a scale that divides exactly."""
    return float(np.ldexp(1.0, np.frexp(x)[1])) if x > 0 else 1.0


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
    scale = _pow2(float(np.max(np.abs(w))))
    In, wn = I / _pow2(float(np.max(I))), w / scale
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
    q = p31 * V1**2 + p32 * V2**2  # 2 E J3 - L^2
    r = p21 * V2**2 + J3 * (J3 - J1) * V3**2  # L^2 - 2 E J1
    with np.errstate(divide="ignore", invalid="ignore"):
        A = np.sqrt(V1**2 + (p32 / p31) * V2**2) if p31 != 0 else abs(V1)
        B = np.sqrt((p31 / p32) * V1**2 + V2**2) if p32 != 0 else abs(V2)
        C = np.sqrt((p21 / (J3 * (J3 - J1))) * V2**2 + V3**2) if J3 != J1 else abs(V3)
    nu2 = (J3 - J2) * r / (J1 * J2 * J3)
    nu = np.sign(J3 - J2) * np.sqrt(max(nu2, 0.0))
    m = 0.0 if (q == 0 or J2 == J1) else (J2 - J1) * q / ((J3 - J2) * r)
    m = float(min(max(m, 0.0), 1.0))
    # V, A, B, C, nu describe omega0 / scale; the motion is scale times them at time scale * t
    return dict(I=I, w=w, perm=perm, flip=flip, sg=sg, V=V, J=J, A=A, B=B, C=C, nu=nu, m=m, scale=scale)


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
    phi0 = np.arctan2(V2 / B if B > 0 else 0.0, V1 / A if A > 0 else 1.0)
    u0 = float(special.ellipkinc(phi0, m))
    if not np.isfinite(u0):  # m = 1 and V1 = 0: the unstable middle-axis equilibrium
        return np.broadcast_to(w, (tt.size, 3)).copy()
    s = P["scale"]
    sn, cn, dn = _ellipj(u0 + nu * (s * tt), m)
    V = np.stack([A * cn, B * sn, C * dn], axis=-1) * (P["sg"] * P["flip"] * s)
    Wtb = np.empty_like(V)
    Wtb[:, list(P["perm"])] = V
    return np.stack([Wtb[:, 2], -Wtb[:, 1], Wtb[:, 0]], axis=-1)


def euler_poinsot_period(body: Any, omega0: Any) -> float:
    r"""Period of :math:`\omega(t)` of the 3D free body: :math:`4K(m)/|\nu|` (``inf`` on the
    separatrix, ``inf`` for steady rotation)."""
    P = _ep_setup(body, omega0)
    if _is_steady(P) or P["m"] >= 1.0:
        return float("inf")
    return 4.0 * float(special.ellipk(P["m"])) / abs(P["nu"]) / P["scale"]
