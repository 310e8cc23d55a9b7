r"""The paper's PRINTED equations 3-6, 25-27, 38 and 82-147, transcribed as SymPy objects.

A faithful transcription of the print, **typos included**: these objects are
what :mod:`hyperrotor.paper.verify` checks, never a source of truth. The
Euler equations (28)-(37), the reductions (42)-(81) and Tables 1-2 are
transcribed in :mod:`hyperrotor.paper.printed`.

How the transcription is made
-----------------------------
:data:`LATEX` holds each equation's LaTeX exactly as the text extraction of
the preprint prints it (doi:10.20944/preprints202508.0136.v2). A small,
documented converter (:func:`_tex_to_sympy`) turns the scalar formulas into
SymPy with these readings, chosen to keep every printed index as printed:

* ``\omega_{ij}`` -> ``omega_ij``, index order kept as printed (also ``omega_51``, ``omega_31``);
* ``\frac{d\omega_{ij}}{dt}`` -> ``omegadot_ij``;
* ``I^{ijij}`` -> ``I_ij`` (positive), the plane moment, as in :mod:`hyperrotor.paper.printed`;
* ``L^{ij}``, ``\omega^{ij}`` (eq. 25) -> ``L_ij``, ``omega_ij``;
* ``\varpi_n``, ``d\varpi_n/dt`` -> ``varpi_n``, ``varpidot_n``;
* ``c_n``, ``C_{ij}``, ``C_n`` -> ``c_n``, ``C_ij``, ``C_n``;
* ``\Theta`` and ``\theta`` -> ``Theta`` ((108)-(109) print the lowercase letter);
* ``i\Omega`` -> ``I*Omega`` (imaginary unit).

Objects that are not single scalar equations (matrices, chains of equalities,
inequalities, sets of constants, operators) are given as small structured
values by :func:`printed`, built from the same LaTeX where that is
mechanical and otherwise transcribed by hand next to the LaTeX (all such
hand transcriptions are in this module, each with its LaTeX source).
Garbled formulas keep their literal reading (:data:`LITERAL`) and, where an
unambiguous fraction reading exists, that reading (:data:`READINGS`).

The printed claims in prose that the verifier checks are quoted, with the
numbers they state, in :data:`CLAIMS`.
"""
from __future__ import annotations

import re
from functools import lru_cache
from typing import Any

import sympy as sp
from sympy.parsing.sympy_parser import convert_xor, implicit_multiplication, parse_expr, standard_transformations


__all__ = ["LATEX", "CLAIMS", "LITERAL", "READINGS", "printed", "symbol", "printed_keys"]

#: Verbatim LaTeX of the printed equations (text extraction of the preprint), keyed by number.
LATEX: dict[str, str] = {
    "3": r"""\begin{cases} I^{ijkl} = -\int_{\Omega} 2 r^{[i} \delta^{j][k} r^{l]} dm = \frac{1}{2} \int_{\Omega} (-r^i \delta^{jk} r^l + r^i \delta^{jl} r^k + r^j \delta^{ik} r^l - r^j \delta^{il} r^k) dm, \\ I^{ijkl} = -I^{jikl} = -I^{ijlk}, \quad I^{ijkl} = I^{klij}, I^{ijkl} + I^{iklj} + I^{iljk} = 0. \end{cases}""",
    "4": r"""\mathbf{L} = \mathbf{I} \cdot \boldsymbol{\omega}, \quad L^{ij} = I^{ijkl} \omega_{kl}.""",
    "5": r"""\mathbf{L} = \llbracket L^{ij} \rrbracket, \quad L^{ij} = -L^{ji}.""",
    "6": r"""W = \frac{1}{2} \boldsymbol{\omega} \cdot \mathbf{I} \cdot \boldsymbol{\omega} = \frac{1}{2} \omega_{ij} I^{ijkl} \omega_{kl}.""",
    "25": r"""\begin{cases} \mathcal{L}\omega^{12} = -L^{13}\omega^{23} - L^{14}\omega^{24} - L^{15}\omega^{25} + L^{23}\omega^{31} + L^{24}\omega^{34} + L^{25}\omega^{35} \\ \mathcal{L}\omega^{13} = -L^{12}\omega^{23} + L^{14}\omega^{34} + L^{15}\omega^{35} + L^{23}\omega^{21} - L^{34}\omega^{14} - L^{35}\omega^{15} \\ \mathcal{L}\omega^{14} = L^{12}\omega^{24} + L^{13}\omega^{34} - L^{15}\omega^{45} - L^{24}\omega^{21} - L^{34}\omega^{31} + L^{45}\omega^{15} \\ \mathcal{L}\omega^{15} = -L^{12}\omega^{25} - L^{13}\omega^{35} - L^{14}\omega^{45} + L^{25}\omega^{21} + L^{35}\omega^{31} + L^{45}\omega^{14} \\ \mathcal{L}\omega^{23} = -L^{12}\omega^{31} + L^{31}\omega^{21} - L^{24}\omega^{34} - L^{25}\omega^{35} + L^{34}\omega^{24} + L^{35}\omega^{25} \\ \mathcal{L}\omega^{24} = L^{12}\omega^{14} - L^{14}\omega^{21} - L^{23}\omega^{34} + L^{25}\omega^{45} + L^{34}\omega^{23} - L^{45}\omega^{25} \\ \mathcal{L}\omega^{25} = -L^{12}\omega^{15} + L^{35}\omega^{21} + L^{23}\omega^{35} + L^{24}\omega^{45} - L^{35}\omega^{23} - L^{45}\omega^{24} \\ \mathcal{L}\omega^{34} = -L^{13}\omega^{14} + L^{14}\omega^{31} - L^{23}\omega^{24} + L^{24}\omega^{23} - L^{35}\omega^{45} + L^{45}\omega^{35} \\ \mathcal{L}\omega^{35} = L^{13}\omega^{15} - L^{15}\omega^{31} + L^{23}\omega^{25} - L^{25}\omega^{23} - L^{34}\omega^{45} + L^{45}\omega^{34} \\ \mathcal{L}\omega^{45} = -L^{13}\omega^{15} + L^{15}\omega^{14} - L^{24}\omega^{25} + L^{25}\omega^{24} - L^{34}\omega^{35} + L^{35}\omega^{34} \end{cases}""",
    "26": r"""L = \begin{bmatrix} 0 & -I^{1212}\omega_{12} & I^{1313}\omega_{13} & -I^{1414}\omega_{14} & I^{1515}\omega_{15} \\ I^{1212}\omega_{12} & 0 & -I^{2323}\omega_{23} & I^{2424}\omega_{24} & -I^{2525}\omega_{25} \\ -I^{1313}\omega_{13} & I^{2323}\omega_{23} & 0 & -I^{3434}\omega_{34} & I^{3535}\omega_{35} \\ I^{1414}\omega_{14} & -I^{2424}\omega_{24} & I^{3434}\omega_{34} & 0 & -I^{4545}\omega_{45} \\ -I^{1515}\omega_{15} & I^{2525}\omega_{25} & -I^{3535}\omega_{35} & I^{4545}\omega_{45} & 0 \end{bmatrix}.""",
    "27": r"""\dot{L} = \begin{bmatrix} 0 & -I^{1212}\dot{\omega}_{12} & I^{1313}\dot{\omega}_{13} & -I^{1414}\dot{\omega}_{14} & I^{1515}\dot{\omega}_{15} \\ I^{1212}\dot{\omega}_{12} & 0 & -I^{2323}\dot{\omega}_{23} & I^{2424}\dot{\omega}_{24} & -I^{2525}\dot{\omega}_{25} \\ -I^{1313}\dot{\omega}_{13} & I^{2323}\dot{\omega}_{23} & 0 & -I^{3434}\dot{\omega}_{34} & I^{3535}\dot{\omega}_{35} \\ I^{1414}\dot{\omega}_{14} & -I^{2424}\dot{\omega}_{24} & I^{3434}\dot{\omega}_{34} & 0 & -I^{4545}\dot{\omega}_{45} \\ -I^{1515}\dot{\omega}_{15} & I^{2525}\dot{\omega}_{25} & -I^{3535}\dot{\omega}_{35} & I^{4545}\dot{\omega}_{45} & 0 \end{bmatrix}.""",
    "38": r"""|\mathbf{L} - \lambda \mathbf{E}| = k_1 \lambda + k_3 \lambda^3, \quad \mathbf{E} = \text{diag}[[1,1,1,1,1]].""",
    "82": r"""I^{1212} = I^{1313} = I^{1414} = I^{1515} = I^{2323} = I^{2424} = I^{2525} = I^{3434} = I^{3535} = I^{4545}.""",
    "83": r"""\frac{d\omega_{12}}{dt} = \frac{d\omega_{23}}{dt} = \frac{d\omega_{13}}{dt} = \frac{d\omega_{15}}{dt} = \frac{d\omega_{23}}{dt} = \frac{d\omega_{24}}{dt} = \frac{d\omega_{25}}{dt} = \frac{d\omega_{34}}{dt} = \frac{d\omega_{35}}{dt} = \frac{d\omega_{45}}{dt} = 0.""",
    "84": r"""I^{1212} = I^{1313} = I^{1414} = I^{2323} = I^{2424} = I^{3434} = 2,""",
    "85": r"""I^{1515} = I^{2525} = I^{3535} = I^{4545} = 1 + \kappa^2.""",
    "86": r"""\frac{d\omega_{12}}{dt} = 0, \quad \omega_{12}(t=0) = c_1,""",
    "87": r"""\frac{d\omega_{13}}{dt} = 0, \quad \omega_{13}(t=0) = c_2,""",
    "88": r"""\frac{d\omega_{14}}{dt} = 0, \quad \omega_{14}(t=0) = c_3,""",
    "89": r"""(1 + \kappa^2) \frac{d\omega_{15}}{dt} + (1 - \kappa^2)(\omega_{12}\omega_{25} + \omega_{13}\omega_{35} + \omega_{14}\omega_{45}) = 0.""",
    "90": r"""\frac{d\omega_{23}}{dt} = 0, \quad \omega_{23}(t=0) = c_4,""",
    "91": r"""\frac{d\omega_{24}}{dt} = 0, \quad \omega_{24}(t=0) = c_5,""",
    "92": r"""(1 + \kappa^2) \frac{d\omega_{25}}{dt} + (1 - \kappa^2)(\omega_{12}\omega_{15} - \omega_{23}\omega_{35} - \omega_{24}\omega_{45}) = 0.""",
    "93": r"""\frac{d\omega_{34}}{dt} = 0, \quad \omega_{34}(t=0) = c_6,""",
    "94": r"""(1 + \kappa^2) \frac{d\omega_{35}}{dt} - (1 - \kappa^2)(\omega_{13}\omega_{15} + \omega_{23}\omega_{25} - \omega_{34}\omega_{45}) = 0.""",
    "95": r"""(1 + \kappa^2) \frac{d\omega_{45}}{dt} + (1 - \kappa^2)(\omega_{14}\omega_{51} + \omega_{24}\omega_{25} + \omega_{34}\omega_{35}) = 0.""",
    "96": r"""\frac{d\omega_{15}}{dt} - \Theta c_1 \omega_{25} - \Theta c_2 \omega_{35} - \Theta c_3 \omega_{45} = 0,""",
    "97": r"""\frac{d\omega_{25}}{dt} + \Theta c_1 \omega_{15} - \Theta c_4 \omega_{35} - \Theta c_5 \omega_{45} = 0,""",
    "98": r"""\frac{d\omega_{35}}{dt} + \Theta c_2 \omega_{15} + \Theta c_4 \omega_{25} - \Theta c_6 \omega_{45} = 0,""",
    "99": r"""\frac{d\omega_{45}}{dt} + \Theta c_3 \omega_{15} + \Theta c_5 \omega_{25} + \Theta c_6 \omega_{35} = 0,""",
    "100": r"""\Theta = \frac{\kappa^2 - 1}{1 + \kappa^2}, \quad \kappa = \frac{\sqrt{1 - \Theta^2}}{\Theta - 1}, \quad -1 < \Theta < 1.""",
    "101": r"""\omega_{15}(t) = C_{15} \exp(i\Omega t), \quad \omega_{25}(t) = C_{25} \exp(i\Omega t), \quad \omega_{35}(t) = C_{35} \exp(i\Omega t), \quad \omega_{45}(t) = C_{45} \exp(i\Omega t).""",
    "102": r"""i \Omega C_{15} - \Theta c_1 C_{25} - \Theta c_2 C_{35} - \Theta c_3 C_{45} = 0,""",
    "103": r"""i \Omega C_{25} + \Theta c_1 C_{15} - \Theta c_4 C_{35} - \Theta c_5 C_{45} = 0,""",
    "104": r"""i \Omega C_{35} + \Theta c_2 C_{15} + \Theta c_4 C_{25} - \Theta c_6 \omega_{45} = 0,""",
    "105": r"""i \Omega C_{45} + \Theta c_3 C_{15} - \Theta c_5 C_{25} + \Theta c_6 \omega_{35} = 0.""",
    "106": r"""\mathcal{M}y = 0, \quad y = \begin{bmatrix} C_{15} \\ C_{25} \\ C_{35} \\ C_{45} \end{bmatrix}, \quad \mathcal{M} = \begin{bmatrix} i \Omega & -\Theta c_1 & -\Theta c_2 & -\Theta c_3 \\ \Theta c_1 & i \Omega & -\Theta c_4 & \Theta c_5 \\ \Theta c_2 & \Theta c_4 & i \Omega & -\Theta c_6 \\ \Theta c_3 & \Theta c_5 & \Theta c_6 & i \Omega \end{bmatrix}.""",
    "107": r"""|\mathcal{M}| \equiv \Omega^4 + l_2 \Omega^2 + l_0 = 0,""",
    "108": r"""l_2 = -\theta^2 \cdot (c_1^2 + c_2^2 + c_3^2 + c_4^2 + c_5^2 + c_6^2) < 0, \quad l_0 = \theta^4 \cdot (c_1 c_6 - c_2 c_5 + c_3 c_4)^2 > 0,""",
    "109": r"""l_2^2 - 4l_0 = \theta^4 \cdot [(c_5 - c_2)^2 + (c_3 + c_4)^2 + (c_1 + c_6)^2][(c_5 + c_2)^2 + (c_3 - c_4)^2 + (c_1 - c_6)^2],""",
    "110": r"""l_2^2 > l_2^2 - 4l_0 > 0.""",
    "111": r"""I^{1212} = I^{1313} = I^{1515} = I^{2323} = I^{2525} = I^{3535} = 2, I^{1414} = I^{2424} = I^{3434} = I^{4545} = 1 + \kappa^2,""",
    "112": r"""I^{1212} = I^{1414} = I^{1515} = I^{2525} = I^{2424} = I^{4545} = 2, I^{1313} = I^{2323} = I^{3434} = I^{3535} = 1 + \kappa^2,""",
    "113": r"""I^{1313} = I^{1414} = I^{1515} = I^{3434} = I^{3535} = I^{4545} = 2, I^{1212} = I^{2323} = I^{2424} = I^{2525} = 1 + \kappa^2,""",
    "114": r"""I^{2323} = I^{2424} = I^{2525} = I^{3434} = I^{3535} = I^{4545} = 2, I^{1212} = I^{1313} = I^{1414} = I^{1515} = 1 + \kappa^2.""",
    "115": r"""\omega_{12} \equiv c_1, \omega_{13} \equiv c_2, \omega_{15} \equiv c_3, \omega_{23} \equiv c_4, \omega_{25} \equiv c_5, \omega_{35} \equiv c_6,""",
    "116": r"""\omega_{12} \equiv c_1, \omega_{14} \equiv c_2, \omega_{15} \equiv c_3, \omega_{24} \equiv c_4, \omega_{25} \equiv c_5, \omega_{45} \equiv c_6,""",
    "117": r"""\omega_{13} \equiv c_1, \omega_{14} \equiv c_2, \omega_{15} \equiv c_3, \omega_{34} \equiv c_4, \omega_{35} \equiv c_5, \omega_{45} \equiv c_6,""",
    "118": r"""\omega_{23} \equiv c_1, \omega_{24} \equiv c_2, \omega_{25} \equiv c_3, \omega_{34} \equiv c_4, \omega_{35} \equiv c_5, \omega_{45} \equiv c_6.""",
    "119": r"""\omega_{12} = \Omega + \varepsilon \varpi_1(t), \omega_{13} = \varepsilon \varpi_2(t), \omega_{14} = \varepsilon \varpi_3(t), \omega_{15} = \varepsilon \varpi_4(t), \omega_{23} = \varepsilon \varpi_5(t),""",
    "120": r"""\omega_{24} = \varepsilon \varpi_6(t), \omega_{25} = \varepsilon \varpi_7(t), \omega_{34} = \varepsilon \varpi_8(t), \omega_{35} = \varepsilon \varpi_9(t), \omega_{45} = \varepsilon \varpi_{10}(t).""",
    "121": r"""-J_1 \frac{d\varpi_1}{dt} = 0,""",
    "122": r"""J_2 \frac{d\varpi_2}{dt} + \Omega(J_1 - J_4)\varpi_5 = 0,""",
    "123": r"""-J_3 \frac{d\varpi_3}{dt} + \Omega(J_5 - J_1)\varpi_6 = 0,""",
    "124": r"""J_7 \frac{d\varpi_4}{dt} + \Omega(J_1 - J_8)\varpi_7 = 0,""",
    "125": r"""-J_4 \frac{d\varpi_5}{dt} + \Omega(J_1 - J_2)\varpi_2 = 0,""",
    "126": r"""J_5 \frac{d\varpi_6}{dt} + \Omega(J_3 - J_1)\varpi_3 = 0,""",
    "127": r"""-J_8 \frac{d\varpi_7}{dt} + \Omega(J_1 - J_7)\varpi_4 = 0,""",
    "128": r"""-J_6 \frac{d\varpi_8}{dt} = 0,""",
    "129": r"""J_9 \frac{d\varpi_9}{dt} = 0,""",
    "130": r"""-J_{10} \frac{d\varpi_{10}}{dt} = 0.""",
    "131": r"""J_1 = I^{1212}, J_2 = I^{1313}, J_3 = I^{1414}, J_4 = I^{2323}, J_5 = I^{2424}, J_6 = I^{3434}, J_7 = I^{1515}, J_8 = I^{2525}, J_9 = I^{3535}, J_{10} = I^{4545}.""",
    "132": r"""\varpi_1 = 0, \varpi_6 = 0, \varpi_9 = 0, \varpi_{10} = 0.""",
    "133": r"""\varpi_2 = C_1 \sin(\Omega v_1 t) + C_2 \cos(\Omega v_1 t),""",
    "134": r"""\varpi_5 = J_2 v_1 J_4 - J_1 C_1 \cos \Omega v_1 t - C_2 \sin \Omega v_1 t,""",
    "135": r"""v_1 = J_1 - J_4 J_1 - J_2 J_4.""",
    "136": r"""v_2 = J_1 - J_5 J_1 - J_3 J_5.""",
    "137": r"""\varpi_7 = J_7 v_3 J_8 - J_1 C_1 \cos \Omega v_3 t - C_2 \sin \Omega v_3 t,""",
    "138": r"""v_3 = J_1 - J_8 J_1 - J_7 J_8.""",
    "139": r"""J_1 \geq J_2 \geq J_3 \geq J_4 \geq J_5 \geq J_6 \geq J_7 \geq J_8 \geq J_9 \geq J_{10}.""",
    "140": r"""J_1 \leq J_2 \leq J_3 \leq J_4 \leq J_5 \leq J_6 \leq J_7 \leq J_8 \leq J_9 \leq J_{10}.""",
    "141": r"""\mathbb{L} = -i\hbar \begin{bmatrix} 0 & -\mathbb{1}^{12} & \mathbb{1}^{13} & -\mathbb{1}^{14} & \mathbb{1}^{15} \\ \mathbb{1}^{12} & 0 & -\mathbb{1}^{23} & \mathbb{1}^{24} & -\mathbb{1}^{25} \\ -\mathbb{1}^{13} & \mathbb{1}^{23} & 0 & -\mathbb{1}^{34} & \mathbb{1}^{35} \\ \mathbb{1}^{14} & -\mathbb{1}^{24} & \mathbb{1}^{34} & 0 & -\mathbb{1}^{45} \\ -\mathbb{1}^{15} & \mathbb{1}^{25} & -\mathbb{1}^{35} & \mathbb{1}^{45} & 0 \end{bmatrix}.""",
    "142": r"""\left\{ \begin{array}{l} \mathbb{L}^{12} = x \frac{\partial}{\partial y} - y \frac{\partial}{\partial x}, \mathbb{L}^{13} = x \frac{\partial}{\partial z} - z \frac{\partial}{\partial x}, \mathbb{L}^{14} = x \frac{\partial}{\partial w} - w \frac{\partial}{\partial x}, \mathbb{L}^{15} = x \frac{\partial}{\partial v} - v \frac{\partial}{\partial x}, \\ \mathbb{L}^{23} = y \frac{\partial}{\partial z} - z \frac{\partial}{\partial y}, \mathbb{L}^{24} = y \frac{\partial}{\partial w} - w \frac{\partial}{\partial y}, \mathbb{L}^{25} = y \frac{\partial}{\partial v} - v \frac{\partial}{\partial y}, \\ \mathbb{L}^{34} = z \frac{\partial}{\partial w} - w \frac{\partial}{\partial z}, \mathbb{L}^{35} = z \frac{\partial}{\partial v} - v \frac{\partial}{\partial z}, \mathbb{L}^{45} = w \frac{\partial}{\partial v} - v \frac{\partial}{\partial w}. \end{array} \right.""",
    "143": r"""\mathbb{L} = \begin{bmatrix} 0 & -\mathbb{L}^{12} & \mathbb{L}^{13} & -\mathbb{L}^{14} & \mathbb{L}^{15} \\ \mathbb{L}^{12} & 0 & -\mathbb{L}^{23} & \mathbb{L}^{24} & -\mathbb{L}^{25} \\ -\mathbb{L}^{13} & \mathbb{L}^{23} & 0 & -\mathbb{L}^{34} & \mathbb{L}^{35} \\ \mathbb{L}^{14} & -\mathbb{L}^{24} & \mathbb{L}^{34} & 0 & -\mathbb{L}^{45} \\ -\mathbb{L}^{15} & \mathbb{L}^{25} & -\mathbb{L}^{35} & \mathbb{L}^{45} & 0 \end{bmatrix}; \Omega = \begin{bmatrix} 0 & -\Omega^{12} & \Omega^{13} & -\Omega^{14} & \Omega^{15} \\ \Omega^{12} & 0 & -\Omega^{23} & \Omega^{24} & -\Omega^{25} \\ -\Omega^{13} & \Omega^{23} & 0 & -\Omega^{34} & \Omega^{35} \\ \Omega^{14} & -\Omega^{24} & \Omega^{34} & 0 & -\Omega^{45} \\ -\Omega^{15} & \Omega^{25} & -\Omega^{35} & \Omega^{45} & 0 \end{bmatrix}.""",
    "144": r"""\left\{ \begin{array}{l} \mathbb{L}\Omega^{12} = -\mathbb{L}^{13}\Omega^{23} - \mathbb{L}^{14}\Omega^{24} - \mathbb{L}^{15}\Omega^{25} + \mathbb{L}^{23}\Omega^{31} + \mathbb{L}^{24}\Omega^{34} + \mathbb{L}^{25}\Omega^{35}, \\ \mathbb{L}\Omega^{13} = -\mathbb{L}^{12}\Omega^{23} + \mathbb{L}^{14}\Omega^{34} + \mathbb{L}^{15}\Omega^{35} + \mathbb{L}^{23}\Omega^{21} - \mathbb{L}^{34}\Omega^{14} - \mathbb{L}^{35}\Omega^{15}, \\ \mathbb{L}\Omega^{14} = \mathbb{L}^{12}\Omega^{24} + \mathbb{L}^{13}\Omega^{34} - \mathbb{L}^{15}\Omega^{45} - \mathbb{L}^{24}\Omega^{21} - \mathbb{L}^{34}\Omega^{31} + \mathbb{L}^{45}\Omega^{15}, \\ \mathbb{L}\Omega^{15} = -\mathbb{L}^{12}\Omega^{25} - \mathbb{L}^{13}\Omega^{35} - \mathbb{L}^{14}\Omega^{45} + \mathbb{L}^{25}\Omega^{21} + \mathbb{L}^{35}\Omega^{31} + \mathbb{L}^{45}\Omega^{14}, \\ \mathbb{L}\Omega^{23} = -\mathbb{L}^{12}\Omega^{31} + \mathbb{L}^{31}\Omega^{21} - \mathbb{L}^{24}\Omega^{34} - \mathbb{L}^{25}\Omega^{35} + \mathbb{L}^{34}\Omega^{24} + \mathbb{L}^{35}\Omega^{25}, \\ \mathbb{L}\Omega^{24} = \mathbb{L}^{12}\Omega^{14} - \mathbb{L}^{14}\Omega^{21} - \mathbb{L}^{23}\Omega^{34} + \mathbb{L}^{25}\Omega^{45} + \mathbb{L}^{34}\Omega^{23} - \mathbb{L}^{45}\Omega^{25}, \\ \mathbb{L}\Omega^{25} = -\mathbb{L}^{12}\Omega^{15} + \mathbb{L}^{35}\Omega^{21} + \mathbb{L}^{23}\Omega^{35} + \mathbb{L}^{24}\Omega^{45} - \mathbb{L}^{35}\Omega^{23} - \mathbb{L}^{45}\Omega^{24}, \\ \mathbb{L}\Omega^{34} = -\mathbb{L}^{13}\Omega^{14} + \mathbb{L}^{14}\Omega^{31} - \mathbb{L}^{23}\Omega^{24} + \mathbb{L}^{24}\Omega^{23} - \mathbb{L}^{35}\Omega^{45} + \mathbb{L}^{45}\Omega^{35}, \\ \mathbb{L}\Omega^{35} = \mathbb{L}^{13}\Omega^{15} - \mathbb{L}^{15}\Omega^{31} + \mathbb{L}^{23}\Omega^{25} - \mathbb{L}^{25}\Omega^{23} - \mathbb{L}^{34}\Omega^{45} + \mathbb{L}^{45}\Omega^{34}, \\ \mathbb{L}\Omega^{45} = -\mathbb{L}^{13}\Omega^{15} + \mathbb{L}^{15}\Omega^{14} - \mathbb{L}^{24}\Omega^{25} + \mathbb{L}^{25}\Omega^{24} - \mathbb{L}^{34}\Omega^{35} + \mathbb{L}^{35}\Omega^{34}. \end{array} \right.""",
    "145": r"""\mathbb{L}\Omega = -3\mathbb{L}.""",
    "146": r"""\mathbb{L}\Omega = -2\mathbb{L}.""",
    "147": r"""\mathbb{L}\Omega = -\mathbb{L}.""",
}


# ----------------------------------------------------------------------------
# converter
# ----------------------------------------------------------------------------
_FUNCTIONS = {"sqrt", "sin", "cos", "exp"}
_T = standard_transformations + (implicit_multiplication, convert_xor)
_POSITIVE = re.compile(r"^(I_\d\d|J_\d+|kappa)$")
_REAL = re.compile(r"^(c_\d|Theta|Omega|t|omega_\d\d|omegadot_\d\d|varpi_\d+|varpidot_\d+|C_\d+|l_\d|v_\d|epsilon|hbar)$")


def symbol(name: str) -> sp.Symbol:
    """The SymPy symbol used for a transcribed name (``I_ij``, ``J_n``, ``kappa`` positive; most others real)."""
    if _POSITIVE.match(name):
        return sp.Symbol(name, positive=True)
    if _REAL.match(name):
        return sp.Symbol(name, real=True)
    return sp.Symbol(name)


_RULES = [
    (r"\\frac\{d\\omega_\{(\d)(\d)\}\}\{dt\}", r" omegadot_\1\2 "),
    (r"\\frac\{d\\varpi_\{?(\d+)\}?\}\{dt\}", r" varpidot_\1 "),
    (r"\\omega[_^]\{(\d)(\d)\}", r" omega_\1\2 "),
    (r"\\varpi_\{?(\d+)\}?", r" varpi_\1 "),
    (r"I\^\{(\d)(\d)\1\2\}", r" I_\1\2 "),
    (r"L\^\{(\d)(\d)\}", r" L_\1\2 "),
    (r"C_\{(\d+)\}", r" C_\1 "),
    (r"\b([cCJlv])_\{?(\d+)\}?", r" \1_\2 "),
    (r"\\kappa", " kappa "),
    (r"\\[Tt]heta", " Theta "),
    (r"(?<![\w\\])i\s*\\Omega", " iu Omega "),
    (r"\\Omega", " Omega "),
    (r"\\cdot", "*"),
    (r"\\left|\\right", ""),
    (r"\[", "("),
    (r"\]", ")"),
    (r"[,.]\s*$", ""),
]


def _tex_to_sympy(tex: str) -> sp.Expr:
    """Convert one printed scalar formula (no ``=``) to SymPy with the readings of the module docstring."""
    s = tex
    for pat, rep in _RULES:
        s = re.sub(pat, rep, s)
    if "\\" in s:
        raise ValueError(f"unconverted LaTeX in {tex!r} -> {s!r}")
    names = set(re.findall(r"[A-Za-z]+(?:_\d+)?", s)) - {"iu"} - _FUNCTIONS
    local = {n: symbol(n) for n in names}
    local["iu"] = sp.I
    return parse_expr(s, local_dict=local, transformations=_T)


def _zero_form(tex: str) -> sp.Expr:
    """``lhs - rhs`` of a printed ``lhs = rhs`` (only the part before ``\\quad``)."""
    tex = tex.split(r"\quad")[0]
    lhs, rhs = tex.split("=")
    return sp.expand(_tex_to_sympy(lhs) - _tex_to_sympy(rhs))


def _cells(tex: str) -> list[list[str]]:
    body = re.search(r"\\begin\{bmatrix\}(.*?)\\end\{bmatrix\}", tex, re.S).group(1)
    return [[c.strip() for c in row.split("&")] for row in body.split(r"\\")]


def _cases(tex: str, head: str) -> dict:
    """Lines ``head^{ij} = sum of +-A^{ab}B^{cd}`` of eqs. (25)/(144) -> {(i, j): [(sign, 'ab', 'cd'), ...]}."""
    out = {}
    for line in re.split(r"\\\\", tex):
        m = re.search(head + r"\^\{(\d)(\d)\}\s*=(.*)", line)
        if not m:
            continue
        terms = re.findall(r"([+-]?)\s*\\?\w+(?:\{L\})?\^\{(\d\d)\}\\?\w*\^\{(\d\d)\}", m.group(3))
        out[(int(m.group(1)), int(m.group(2)))] = [(-1 if s == "-" else 1, a, b) for s, a, b in terms]
    return out


def _matrix_prefactor(tex: str) -> Any:
    r"""The factor printed before an operator matrix (``\mathbb{L} = -i\hbar \begin{bmatrix}...``): a sign, an
    integer, ``i`` and ``\hbar``, each optional, read from the text (1 when nothing is printed); ``None`` when the
    text holds anything else (the verdict then says the prefactor cannot be read)."""
    head = tex.split("=", 1)[1].split(r"\begin", 1)[0] if "=" in tex else ""
    m = re.fullmatch(r"\s*([+-]?)\s*(\d*)\s*(i)?\s*(\\hbar)?\s*", head)
    if m is None:
        return None
    sign, digits, imag, hbar = m.groups()
    return ((-1 if sign == "-" else 1) * sp.Integer(int(digits or 1)) * (sp.I if imag else 1)
            * (sp.Symbol("hbar") if hbar else 1))


def _plane(ab: str) -> tuple:
    return (int(ab[0]), int(ab[1]))


def _chain_planes(tex: str) -> list:
    return [_plane(m) for m in re.findall(r"I\^\{(\d\d)\d\d\}", tex)]


# ----------------------------------------------------------------------------
# literal readings of garbled formulas and hand transcriptions
# ----------------------------------------------------------------------------
#: The literal (extraction-order) reading of garbled formulas (133)-(138).
LITERAL: dict[str, str] = {
    "134": "J_2 v_1 J_4 - J_1 C_1 cos(Omega v_1 t) - C_2 sin(Omega v_1 t)",
    "135": "J_1 - J_4 J_1 - J_2 J_4",
    "136": "J_1 - J_5 J_1 - J_3 J_5",
    "136 (varpi_6)": "J_3 v_2 J_1 - J_5 C_1 cos(Omega v_2 t) - C_2 sin(Omega v_2 t)",
    "137": "J_7 v_3 J_8 - J_1 C_1 cos(Omega v_3 t) - C_2 sin(Omega v_3 t)",
    "138": "J_1 - J_8 J_1 - J_7 J_8",
}

#: Fraction readings of the garbled solution lines: ``a b c - d e f`` read as
#: ``a*b/(c - d) * (e - f)`` -- the extraction drops the fraction bar and the
#: parentheses but keeps the order of the tokens.
READINGS: dict[str, str] = {
    "134": "J_2*v_1/(J_4 - J_1)*(C_1*cos(Omega*v_1*t) - C_2*sin(Omega*v_1*t))",
    "136 (varpi_6)": "J_3*v_2/(J_1 - J_5)*(C_1*cos(Omega*v_2*t) - C_2*sin(Omega*v_2*t))",
    "137": "J_7*v_3/(J_8 - J_1)*(C_1*cos(Omega*v_3*t) - C_2*sin(Omega*v_3*t))",
}

#: The unnumbered lines printed with (136) and (137) (second and third groups).
EXTRA_LATEX: dict[str, str] = {
    "136 (varpi_3)": r"\varpi_3 = C_1 \sin(\Omega v_2 t) + C_2 \cos \Omega v_2 t,",
    "136 (varpi_6)": r"\varpi_6 = J_3 v_2 J_1 - J_5 C_1 \cos \Omega v_2 t - C_2 \sin \Omega v_2 t,",
    "137 (varpi_4)": r"\varpi_4 = C_1 \sin(\Omega v_3 t) + C_2 \cos \Omega v_3 t,",
    "after 118": r"\Omega_{1,2} = \pm \frac{1}{2} \sqrt{2\sqrt{l_2^2 - 4l_0} - 2l_2}, \quad \Omega_{3,4} = \pm \frac{1}{2} \sqrt{-2\sqrt{l_2^2 - 4l_0} - 2l_2}.",
}

#: Printed statements in prose that the verifier checks (quote + the values they state).
CLAIMS: dict[str, dict] = {
    "Sec. 1.3 (integrals)": {
        "quote": "The coefficients of the characteristic polynomials of L are the integrals of motions in this case.",
    },
    "38 (meaning of k1, k3)": {
        "quote": "they represent the conservation of the moment of impulse and energy, respectively",
        "k1": "moment of impulse", "k3": "energy",
    },
    "Sec. 2.1 (order)": {
        "quote": "The are N_omega = 10 coupled second-order differential equations",
        "order": 2, "count": 10,
    },
    "Sec. 2.1 (3D cases)": {
        "quote": "resulting in the common Euler equations in all twenty possible three-dimensional scenarios",
        "count": 20,
    },
    "Tables 1-2 (same signs)": {"quote": "It is evident that the signs of the elements in Tables 1 and 2 are identical."},
    "Table 2 (antisymmetric)": {"quote": "The Table 2 is antisymmetric because bivector products are antisymmetric"},
    "Table 2 (disjoint planes)": {"quote": "If all the indices in both terms are different, the corresponding product will also vanish."},
    "72": {"quote": "{1-2-3-4}, {2-3-4-5}, {3-4-5-1}, {4-5-1-2}, {5-1-2-3}",
           "sets": ((1, 2, 3, 4), (2, 3, 4, 5), (3, 4, 5, 1), (4, 5, 1, 2), (5, 1, 2, 3))},
    "Sec. 2.5 (closing)": {
        "quote": "the ten equations in 5D project into four equations in the comprised 4D spaces. Each of 4D "
                 "spaces dissolves into three corresponding classical Euler equations in the enclosed 3D spaces.",
        "per_4d": 4, "per_3d": 3,
    },
    "82 (Platonic bodies)": {
        "quote": "The Platonic bodies and hyperspheres satisfy this condition.",
    },
    "83 (all dimensions)": {"quote": "It can be posited that this behavior holds in all multidimensional Euclidean spaces."},
    "106 (antisymmetric)": {"quote": "It is notable that the matrix must be antisymmetric"},
    "Sec. 4 (trivial equations)": {
        "quote": "the four equations will be satisfied in linear terms of epsilon. The remaining six equations reduce to",
        "trivial": 4, "coupled": 6,
    },
    "Sec. 6 (integrals)": {"quote": "It is demonstrated that two integrals of motion exist for an unperturbed rotational motion.",
                           "count": 2},
    "Sec. 5 (cross-references)": {
        "quote": "components of the angular momentum operator (144); operators L and Omega from (146); "
                 "products in (147); From Equation (147) we get the commutation relations; The Equation (148) is valid",
        # (cited number, kind of object the sentence refers to)
        "citations": (("144", "operator matrix"), ("146", "operator matrices"), ("147", "operator products"),
                      ("147", "operator products"), ("148", "contraction identity")),
        # kind of each equation of Sec. 5 as printed
        "kinds": {"141": "operator matrix", "142": "operator components", "143": "operator matrices",
                  "144": "operator products", "145": "contraction identity", "146": "contraction identity",
                  "147": "contraction identity"},
    },
}


# ----------------------------------------------------------------------------
# parsed objects
# ----------------------------------------------------------------------------
def printed_keys() -> tuple:
    """The keys understood by :func:`printed`."""
    return tuple(LATEX) + tuple(k for k in EXTRA_LATEX if k not in LATEX)


@lru_cache(maxsize=None)
def printed(key: str) -> Any:
    """The printed object of equation ``key`` (e.g. ``"92"``) as SymPy / plain Python data.

    Scalar equations ``lhs = rhs`` come back as the expanded ``lhs - rhs``
    (every such printed equation has the form ``... = 0`` or is compared as a
    difference). See the module docstring for the readings.
    """
    if key not in LATEX and key not in EXTRA_LATEX:
        raise KeyError(f"no printed object {key!r}; known: {', '.join(printed_keys())}")
    tex = LATEX.get(key) or EXTRA_LATEX[key]
    n = int(key.split()[0]) if key[0].isdigit() else None
    if key == "3":
        # I^{ijkl} = 1/2 int(-r^i d^{jk} r^l + r^i d^{jl} r^k + r^j d^{ik} r^l - r^j d^{il} r^k) dm, with M^{ab} = int r^a r^b dm
        def tensor(M, i, j, k, l):
            d = lambda a, b: 1 if a == b else 0  # noqa: E731
            return sp.Rational(1, 2) * (-d(j, k) * M[i, l] + d(j, l) * M[i, k] + d(i, k) * M[j, l] - d(i, l) * M[j, k])
        return {
            "tensor": tensor,
            # printed symmetries: (permutation of (i,j,k,l), sign): I^{ijkl} = sign * I^{perm}
            "symmetries": (("I^{ijkl} = -I^{jikl}", (1, 0, 2, 3), -1), ("I^{ijkl} = -I^{ijlk}", (0, 1, 3, 2), -1),
                           ("I^{ijkl} = I^{klij}", (2, 3, 0, 1), 1)),
            "cyclic": ("I^{ijkl} + I^{iklj} + I^{iljk} = 0", ((0, 1, 2, 3), (0, 2, 3, 1), (0, 3, 1, 2))),
        }
    if key == "4":
        return {"L": lambda tensor, w, i, j, N: sum(tensor(i, j, k, l) * w[k][l] for k in range(N) for l in range(N))}
    if key == "5":
        return {"antisymmetric": True}
    if key == "6":
        return {"W": lambda tensor, w, N: sp.Rational(1, 2) * sum(
            w[i][j] * tensor(i, j, k, l) * w[k][l] for i in range(N) for j in range(N) for k in range(N) for l in range(N))}
    if key in ("25", "144"):
        head = r"\\mathcal\{L\}\\omega" if key == "25" else r"\\mathbb\{L\}\\Omega"
        return _cases(tex, head)
    if key in ("26", "27"):
        tex2 = tex.replace(r"\dot{\omega}", r"\omegadot")
        cells = _cells(tex2.replace(r"\omegadot_", "omegadot_"))
        M = sp.zeros(5, 5)
        for r, row in enumerate(cells):
            for c, cell in enumerate(row):
                cell = re.sub(r"omegadot_\{(\d\d)\}", r" omegadot_\1 ", cell)
                M[r, c] = _tex_to_sympy(cell)
        return M
    if key == "38":
        lam = sp.Symbol("lambda")
        return {"lambda": lam, "rhs": symbol("k_1") * lam + symbol("k_3") * lam**3, "E": sp.eye(5)}
    if key in ("82",):
        return tuple(_chain_planes(tex))
    if key == "83":
        return tuple(_plane(m) for m in re.findall(r"\\omega_\{(\d\d)\}", tex))
    if key in ("84", "85"):
        value = sp.Integer(2) if key == "84" else 1 + symbol("kappa") ** 2
        return {p: value for p in _chain_planes(tex)}
    if key in ("111", "112", "113", "114"):
        two, kap = tex.split("= 2,")
        return {"2": tuple(_chain_planes(two)), "1 + kappa^2": tuple(_chain_planes(kap))}
    if key in ("115", "116", "117", "118"):
        return tuple(_plane(a) for a, _ in re.findall(r"\\omega_\{(\d\d)\} \\equiv c_(\d)", tex))
    if key in ("86", "87", "88", "90", "91", "93"):
        ode = _zero_form(tex)
        m = re.search(r"\\omega_\{(\d\d)\}\(t=0\) = c_(\d)", tex)
        return {"ode": ode, "initial": (_plane(m.group(1)), symbol("c_" + m.group(2)))}
    if key == "100":
        th, ka, rng = [p.strip() for p in tex.split(r"\quad")]
        theta = _tex_to_sympy(re.sub(r"\\frac\{(.*?)\}\{(.*?)\}", r"((\1)/(\2))", th.split("=")[1]))
        kappa = _tex_to_sympy(r"((sqrt(1 - \Theta^2))/(\Theta - 1))")
        return {"Theta": theta, "kappa": kappa, "range": (-1, 1), "strict": (rng.count("<") == 2 and "\\leq" not in rng)}
    if key == "101":
        return {p: symbol(f"C_{a}{b}") * sp.exp(sp.I * symbol("Omega") * symbol("t"))
                for p, (a, b) in ((_plane(x), x) for x in re.findall(r"C_\{(\d\d)\}", tex))}
    if key == "106":
        M = sp.Matrix([[_tex_to_sympy(c) for c in row] for row in _cells(tex.split(r"\mathcal{M} =")[1])])
        return M
    if key == "107":
        return _tex_to_sympy(tex.split(r"\equiv")[1].split("=")[0])
    if key == "108":
        a, b = tex.split(r"\quad")
        out = {}
        for name, part in (("l_2", a), ("l_0", b)):
            expr, rel, _ = re.split(r"(<|>|\\leq|\\geq)", part.split("=", 1)[1])
            out[name] = _tex_to_sympy(expr)
            out[name + " relation"] = {"\\leq": "<=", "\\geq": ">="}.get(rel, rel)
        return out
    if key == "109":
        lhs, rhs = tex.split("=")
        return sp.Eq(_tex_to_sympy(lhs), _tex_to_sympy(rhs), evaluate=False)
    if key == "110":
        pieces = re.split(r"(>|\\geq)", tex.rstrip("."))
        parts = [_tex_to_sympy(p) for p in pieces[::2]]
        rels = set(pieces[1::2])
        return {"chain": tuple(parts), "relation": ">" if rels == {">"} else ">="}
    if key == "after 118":
        l2, l0 = symbol("l_2"), symbol("l_0")
        D = sp.sqrt(l2**2 - 4 * l0)
        half = sp.Rational(1, 2)
        # Omega_{1,2} = +-1/2 sqrt(2 sqrt(D) - 2 l2), Omega_{3,4} = +-1/2 sqrt(-2 sqrt(D) - 2 l2)
        return (half * sp.sqrt(2 * D - 2 * l2), -half * sp.sqrt(2 * D - 2 * l2),
                half * sp.sqrt(-2 * D - 2 * l2), -half * sp.sqrt(-2 * D - 2 * l2))
    if key in ("119", "120"):
        out = {}
        for a, rest in re.findall(r"\\omega_\{(\d\d)\} = ([^,]*)", tex):
            rest = rest.replace(r"\varepsilon", " epsilon ").replace("(t)", "")
            out[_plane(a)] = _tex_to_sympy(rest)
        return out
    if key == "131":
        return {symbol("J_" + n): _plane(ab) for n, ab in re.findall(r"J_\{?(\d+)\}? = I\^\{(\d\d)\d\d\}", tex)}
    if key == "132":
        return tuple(int(x) for x in re.findall(r"\\varpi_\{?(\d+)\}? = 0", tex))
    if key in ("133", "136 (varpi_3)", "137 (varpi_4)"):
        lhs, rhs = tex.split("=")
        rhs = re.sub(r"\\(sin|cos) \\Omega v_(\d) t", r"\\\1(\\Omega v_\2 t)", rhs)
        rhs = rhs.replace(r"\sin", "sin").replace(r"\cos", "cos")
        return sp.Eq(_tex_to_sympy(lhs), _tex_to_sympy(rhs), evaluate=False)
    if key in ("134", "136 (varpi_6)", "137"):
        lhs = tex.split("=")[0]
        return {"lhs": _tex_to_sympy(lhs), "literal": LITERAL[key], "reading": _sympify(READINGS[key])}
    if key in ("135", "136", "138"):
        return {"lhs": _tex_to_sympy(tex.split("=")[0]), "literal": _sympify(LITERAL[key])}
    if key in ("139", "140"):
        rel = ">=" if r"\geq" in tex else "<="
        return {"order": tuple(symbol("J_" + x) for x in re.findall(r"J_\{?(\d+)\}?", tex)), "relation": rel}
    if key in ("141", "143"):
        sub = tex.split(";")[0]
        cells = _cells(sub)
        sign = sp.zeros(5, 5)
        label = {}
        for r, row in enumerate(cells):
            for c, cell in enumerate(row):
                m = re.match(r"(-?)\\mathbb\{[1L]\}\^\{(\d\d)\}", cell)
                if m:
                    sign[r, c] = -1 if m.group(1) else 1
                    label[(r + 1, c + 1)] = _plane(m.group(2))
        return {"prefactor": _matrix_prefactor(sub), "sign": sign, "label": label}
    if key == "142":
        out = {}
        for ab, a1, b1, b2, a2 in re.findall(
                r"\\mathbb\{L\}\^\{(\d\d)\} = (\w) \\frac\{\\partial\}\{\\partial (\w)\} - (\w) \\frac\{\\partial\}\{\\partial (\w)\}", tex):
            out[_plane(ab)] = ((a1, b1), (b2, a2))  # a1 d/d b1 - b2 d/d a2
        return out
    if key in ("145", "146", "147"):
        rhs = tex.split("=")[1].replace(r"\mathbb{L}", "").strip().rstrip(".")
        factor = sp.Integer(-1) if rhs == "-" else sp.Integer(int(rhs))
        return {"N": {"145": 5, "146": 4, "147": 3}[key], "factor": factor}
    # generic scalar equation lhs = rhs (89, 92, 94-99, 102-105, 121-130)
    return _zero_form(tex)


def _sympify(text: str) -> sp.Expr:
    names = set(re.findall(r"[A-Za-z]+(?:_\d+)?", text)) - _FUNCTIONS
    local = {n: symbol(n) for n in names}
    return parse_expr(text, local_dict=local, transformations=_T)
