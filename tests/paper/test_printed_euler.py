"""The package's Euler equations against the PRINTED (28)-(37), reductions (42)-(81) and Tables 1-2.

Where the print is right the test asserts equality with the package; where it is
wrong the test asserts the correct form (typed here from the derivation, not from
the package) and names the paper's error in a comment.
"""
import itertools

import numpy as np
import pytest
import sympy as sp

import hyperrotor as hr
from hyperrotor import Inertia, RigidBody
from hyperrotor.classical.rigid_body import TIME
from hyperrotor.paper import printed as P


@pytest.fixture(scope="module")
def body():
    return RigidBody(Inertia.symbolic(5), convention="paper")


@pytest.fixture(scope="module")
def S():
    """Mini-language names (I12, w12, d12, mt12) -> the package's SymPy objects."""
    return P.printed_symbols()


def _same(a: sp.Eq, b: sp.Eq) -> bool:
    return sp.simplify(a.lhs - b.lhs) == 0 and sp.simplify(a.rhs - b.rhs) == 0


def _reduced_eqs(body, locked):
    red = body.lock(locked)
    return dict(zip(red.planes, red.euler_equations()))


# ---------------------------------------------------------------- (28)-(37)
def test_symbols_are_the_packages(body, S):
    assert S["I12"] == body.inertia.symbolic_moments[0]
    assert S["w45"] == body.omega_symbols(function_of=TIME)[-1]
    assert S["mt23"] == body.torque_symbols()[4]


@pytest.mark.parametrize("number", [str(n) for n in range(28, 38)])
def test_euler_equations_equal_print(body, number):
    mine = body.euler_equations()[int(number) - 28]
    printed = P.PRINTED_EULER[number]
    assert P.equation_plane(printed) == P.EULER_EQUATION_PLANES[number] == body.planes[int(number) - 28]
    assert sp.simplify(mine.lhs - printed.lhs) == 0
    assert sp.simplify(mine.rhs - printed.rhs) == 0


def test_print_is_matrix_entry_of_eq24(body, S):
    """(28)-(37) are the (i, j) entries of dL/dt - (wL - Lw) = m~ with the checkerboard matrices (21), (22)."""
    w = body.omega_symbols(function_of=TIME)
    I = body.inertia.symbolic_moments
    W = hr.to_matrix(list(w), convention="paper")
    L = hr.to_matrix([a * b for a, b in zip(I, w)], convention="paper")
    lhs = sp.diff(L, TIME) - (W * L - L * W)
    for k, (i, j) in enumerate(hr.planes(5)):
        assert sp.expand(lhs[i - 1, j - 1] - P.PRINTED_EULER[str(28 + k)].lhs) == 0


# ---------------------------------------------------------------- 4D sextets (42)-(71)
FOUR_D = [s for s in P.REDUCTION_SECTIONS if s.section.startswith("2.2.")]


@pytest.mark.parametrize("sec", FOUR_D, ids=[s.section for s in FOUR_D])
def test_4d_reductions_equal_print(body, sec):
    assert sec.heading_axis == sec.text_axis
    assert sec.locked_axes == (sec.text_axis,)
    # the printed frozen set is exactly the planes containing the locked axis
    assert set(sec.frozen_planes) == {p for p in hr.planes(5) if sec.text_axis in p}
    mine = _reduced_eqs(body, sec.text_axis)
    assert set(sec.equation_planes) == set(mine)
    for number, plane in zip(sec.equations, sec.equation_planes):
        assert _same(mine[plane], P.PRINTED_EQUATIONS[number]), number


def _erased_correct(axis):
    return tuple(n for n, p in P.EULER_EQUATION_PLANES.items() if axis in p)


@pytest.mark.parametrize("sec", FOUR_D, ids=[s.section for s in FOUR_D])
def test_4d_erased_equation_lists(sec):
    if sec.erased is None:  # 2.2.1 gives no numbers
        assert sec.section == "2.2.1"
        return
    correct = _erased_correct(sec.text_axis)
    if sec.section == "2.2.4":
        # PAPER ERROR (Sec. 2.2.4): "(31),(34),(36),(37) erased" is copied from 2.2.5;
        # locking axis 4 erases the (1,4), (2,4), (3,4), (4,5) equations (30), (33), (35), (37).
        assert correct == ("30", "33", "35", "37")
        assert sec.erased != correct
    else:
        assert sec.erased == correct


# ---------------------------------------------------------------- 3D reductions (73)-(81)
def _correct_3d(S, a, b, c):
    """Textbook Euler equations on axes a<b<c in the paper's form, typed from the derivation.

    I_ab w_ab' = (I_ac - I_bc) w_ac w_bc, I_ac w_ac' = (I_bc - I_ab) w_ab w_bc,
    I_bc w_bc' = (I_ab - I_ac) w_ab w_ac, each multiplied by (-1)^(i+j).
    """
    ab, ac, bc = f"{a}{b}", f"{a}{c}", f"{b}{c}"
    I, w, d, m = (lambda k: S[f"I{k}"]), (lambda k: S[f"w{k}"]), (lambda k: S[f"d{k}"]), (lambda k: S[f"mt{k}"])
    sg = lambda k: (-1) ** (int(k[0]) + int(k[1]))  # noqa: E731
    return {
        (a, b): sp.Eq(sg(ab) * (I(ab) * d(ab) - (I(ac) - I(bc)) * w(ac) * w(bc)), m(ab)),
        (a, c): sp.Eq(sg(ac) * (I(ac) * d(ac) - (I(bc) - I(ab)) * w(ab) * w(bc)), m(ac)),
        (b, c): sp.Eq(sg(bc) * (I(bc) * d(bc) - (I(ab) - I(ac)) * w(ab) * w(ac)), m(bc)),
    }


# section -> (axes really locked, remaining axes, eq numbers, the extra printed term's frozen factors)
THREE_D = {
    # PAPER ERROR (Sec. 2.3): S_3 freezes axes 4 and 5, but (73)-(75) still carry the terms
    # (I15-I25) w15 w25, (I35-I15) w15 w35, (I25-I35) w25 w35: they are (60), (61), (63) unreduced.
    "2.3": ((4, 5), (1, 2, 3), ("73", "74", "75")),
    # PAPER ERROR (Sec. 2.4): axis 3 is locked (remaining 1-2-4), but (76)-(78) keep
    # (I13-I23) w13 w23, (I34-I13) w13 w34, (I23-I34) w23 w34: they are (66), (68), (70) unreduced.
    "2.4": ((3, 5), (1, 2, 4), ("76", "77", "78")),
    # PAPER ERROR (Sec. 2.5): heading "axis four", text "axis 3", but the equations are on axes
    # 1-3-4, i.e. axis 2 (and 5) is locked; (79)-(81) keep (I12-I23) w12 w23, (I24-I12) w12 w24,
    # (I23-I24) w23 w24: they are (67), (68), (71) unreduced.
    "2.5": ((2, 5), (1, 3, 4), ("79", "80", "81")),
}


@pytest.mark.parametrize("name", list(THREE_D))
def test_3d_reductions_print_is_wrong_package_is_textbook(body, S, name):
    locked, remaining, numbers = THREE_D[name]
    sec = next(s for s in P.REDUCTION_SECTIONS if s.section == name)
    assert sec.remaining_axes == remaining and sec.locked_axes == locked
    assert set(sec.equation_planes) == set(itertools.combinations(remaining, 2))
    mine = _reduced_eqs(body, locked)
    correct = _correct_3d(S, *remaining)
    frozen = {S[f"w{i}{j}"]: 0 for i, j in hr.planes(5) if set((i, j)) & set(locked)}
    for number, plane in zip(sec.equations, sec.equation_planes):
        printed = P.PRINTED_EQUATIONS[number]
        assert _same(mine[plane], correct[plane]), number  # the package gives the textbook form
        assert not _same(printed, correct[plane]), number  # the print does not ...
        extra = sp.expand(printed.lhs - correct[plane].lhs)
        assert len(sp.Add.make_args(extra)) == 2  # ... it has one extra (I - I) w w term
        assert extra.subs(frozen) == 0  # made only of frozen components
        # the printed equation is the unreduced equation of the same plane in 5D
        full = body.euler_equations()[hr.planes(5).index(plane)]
        assert extra.free_symbols <= full.lhs.free_symbols
        assert sp.expand(printed.lhs.subs(frozen) - correct[plane].lhs) == 0


def test_sec_2_5_heading_and_text_do_not_match_equations():
    sec = next(s for s in P.REDUCTION_SECTIONS if s.section == "2.5")
    # PAPER ERROR: heading names axis 4, the text axis 3, yet both axes carry printed equations
    assert sec.heading_axis == 4 and sec.text_axis == 3
    used = {a for p in sec.equation_planes for a in p}
    assert {3, 4} <= used and 2 not in used


def test_sec_2_3_frozen_set_locks_4_and_5():
    sec = next(s for s in P.REDUCTION_SECTIONS if s.section == "2.3")
    assert set(sec.frozen_planes) == {p for p in hr.planes(5) if set(p) & {4, 5}}


# ---------------------------------------------------------------- Tables 1 and 2
def _E(i, j):
    M = np.zeros((5, 5), dtype=int)
    M[i - 1, j - 1], M[j - 1, i - 1] = 1, -1
    return M


def _independent_tables():
    """Table 2: [E_a, E_b] of explicit 5x5 matrices, expanded back; Table 1: same with L for e."""
    ps = hr.planes(5)
    e, L = sp.symbols("e_12 e_13 e_14 e_15 e_23 e_24 e_25 e_34 e_35 e_45"), \
        sp.symbols("L_12 L_13 L_14 L_15 L_23 L_24 L_25 L_34 L_35 L_45")
    T1, T2 = sp.zeros(10, 10), sp.zeros(10, 10)
    for (a, pa), (b, pb) in itertools.product(enumerate(ps), repeat=2):
        K = _E(*pa) @ _E(*pb) - _E(*pb) @ _E(*pa)
        T2[a, b] = sum(int(K[i - 1, j - 1]) * e[c] for c, (i, j) in enumerate(ps))
        T1[a, b] = sum(int(K[i - 1, j - 1]) * L[c] for c, (i, j) in enumerate(ps))
    return T1, T2


def test_table_1_meaning_Ldot_equals_table_times_omega():
    """Eq. (24): dL/dt = wL - Lw =: calL w; our Table-1 matrix satisfies it as component vectors."""
    T1, _ = _independent_tables()
    w = sp.symbols("w1:11")
    L = hr.plane_symbols("L", 5)
    lhs = hr.to_components(hr.to_matrix(list(w), convention="paper") * hr.to_matrix(list(L), convention="paper")
                           - hr.to_matrix(list(L), convention="paper") * hr.to_matrix(list(w), convention="paper"), convention="paper")
    assert sp.expand(lhs - T1 * sp.Matrix(w)) == sp.zeros(10, 1)


def test_generated_tables_equal_independent_derivation():
    T1, T2 = _independent_tables()
    assert hr.bivector_product_table(5) == T2
    assert hr.bivector_product_table(5, convention="standard") == T2
    C = hr.structure_constants(5)
    L = hr.plane_symbols("L", 5)
    gen_T1 = sp.Matrix(10, 10, lambda a, b: sum(int(C[a, b, c]) * L[c] for c in range(10)))
    assert gen_T1 == T1


# Cells (row plane, column plane) where the PRINTED tables differ from the correct ones.
# PAPER ERROR (Tables 1, 2): right non-zero pattern, but these cells carry the wrong sign.
TABLE_1_WRONG = [
    ("12", "14"), ("12", "23"), ("12", "25"), ("13", "14"), ("13", "23"), ("13", "34"),
    ("14", "12"), ("14", "13"), ("14", "34"), ("14", "45"), ("15", "25"), ("15", "45"),
    ("23", "12"), ("23", "13"), ("23", "25"), ("23", "34"), ("24", "25"), ("24", "34"),
    ("24", "45"), ("25", "12"), ("25", "15"), ("25", "23"), ("25", "24"), ("25", "45"),
    ("34", "13"), ("34", "14"), ("34", "23"), ("34", "24"), ("34", "45"), ("35", "45"),
    ("45", "14"), ("45", "15"), ("45", "24"), ("45", "25"), ("45", "34"), ("45", "35"),
]
# Table 2 differs from Table 1 in row 23 (cells 23-24, 23-25, 23-34), so its list differs there.
TABLE_2_WRONG = sorted(set(TABLE_1_WRONG) - {("23", "25"), ("23", "34")} | {("23", "24")})


def _diff_cells(printed, correct):
    labels = [f"{i}{j}" for i, j in hr.planes(5)]
    return [(labels[a], labels[b]) for a in range(10) for b in range(10) if printed[a, b] != correct[a, b]]


def test_printed_tables_differ_exactly_in_pinned_cells():
    T1, T2 = _independent_tables()
    d1 = _diff_cells(P.PRINTED_TABLE_1, T1)
    d2 = _diff_cells(P.PRINTED_TABLE_2, T2)
    assert d1 == TABLE_1_WRONG and len(d1) == 36
    assert d2 == TABLE_2_WRONG and len(d2) == 35
    # every wrong cell is a pure sign flip; the zero pattern is right
    for (T, Pt) in ((T1, P.PRINTED_TABLE_1), (T2, P.PRINTED_TABLE_2)):
        assert all((T[a, b] == 0) == (Pt[a, b] == 0) for a in range(10) for b in range(10))
    labels = [f"{i}{j}" for i, j in hr.planes(5)]
    for r, c in d1:
        a, b = labels.index(r), labels.index(c)
        assert P.PRINTED_TABLE_1[a, b] == -T1[a, b]


def test_printed_tables_internal_inconsistencies():
    L = hr.plane_symbols("L", 5)
    e = hr.plane_symbols("e", 5)
    t2_as_L = P.PRINTED_TABLE_2.subs(dict(zip(e, L)))
    # PAPER ERROR: "the signs of the elements in Tables 1 and 2 are identical" -- not in row 23
    labels = [f"{i}{j}" for i, j in hr.planes(5)]
    assert _diff_cells(P.PRINTED_TABLE_1, t2_as_L) == [("23", "24"), ("23", "25"), ("23", "34")]
    # PAPER ERROR: Table 2 is said to be antisymmetric, but it is not at these cells
    asym = [(labels[a], labels[b]) for a in range(10) for b in range(a + 1, 10)
            if P.PRINTED_TABLE_2[a, b] != -P.PRINTED_TABLE_2[b, a]]
    assert asym == [("23", "24"), ("23", "25"), ("23", "34")]
    assert P.PRINTED_TABLE_1 == -P.PRINTED_TABLE_1.T


def test_no_sign_relabelling_repairs_table_1():
    """No choice of basis signs e_a -> s_a e_a turns the printed Table 1 into a correct so(5) table."""
    C = hr.structure_constants(5).astype(int)
    L = hr.plane_symbols("L", 5)
    Pt = np.array([[[int(P.PRINTED_TABLE_1[a, b].coeff(L[c])) for c in range(10)] for b in range(10)]
                   for a in range(10)])
    best = min(
        int(np.sum(np.any(Pt != C * np.einsum("a,b,c->abc", s, s, s), axis=2)))
        for s in map(np.array, itertools.product([1, -1], repeat=10))
    )
    assert best > 0
