"""Tests of hyperrotor.paper.verify: pinned verdicts, schema, computed-ness, renderers, docs page.

The expected statuses below were decided from independent derivations (see
the notes next to each group), not copied from the implementation's output:
e.g. (92) has the wrong sign of the (1 - kappa^2) term because the quartet
body's equation for plane 25 is (1 + k^2) w25' - (1 - k^2)(w12 w15 - w23 w35 -
w24 w45) = 0 (entry form, from eq. 34 with I15 = I25 = ... = 1 + k^2).
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from hyperrotor.paper import printed as pr
from hyperrotor.paper import printed_solutions as ps
from hyperrotor.paper import verify as V

EXPECTED = {
    # Sec. 1: eq. (3)-(5) right; full summation of (6) counts every plane twice; (26)-(27) miss the factor 2 of eq. (4)
    "3": "holds", "4": "holds", "5": "holds", "6": "typo", "26": "typo", "27": "typo",
    # Sec. 2.1: (25) index/sign slips in every line; tables wrong in many cells; (28)-(37) right as matrix entries;
    # (38) misses -lambda^5; k1 quartic, energy not a Casimir; 10 (not 20) 3D subspaces; first-order ODEs
    "25 [12]": "typo", "25 [13]": "typo", "25 [14]": "typo", "25 [15]": "typo", "25 [23]": "typo", "25 [24]": "typo",
    "25 [25]": "typo", "25 [34]": "typo", "25 [35]": "typo", "25 [45]": "typo", "Table 1": "typo", "Table 2": "typo",
    "Table 2 (antisymmetry)": "typo", "Table 2 (disjoint planes)": "holds", "Tables 1-2 (same signs)": "claim-false",
    "28": "holds", "29": "holds", "30": "holds", "31": "holds", "32": "holds", "33": "holds", "34": "holds",
    "35": "holds", "36": "holds", "37": "holds", "Sec. 2.1 (order of the equations)": "claim-false",
    "Sec. 2.1 (number of 3D cases)": "claim-false", "38": "typo", "38 (k1, k3 conserved)": "holds",
    "38 (k1 momentum, k3 energy)": "claim-false", "Sec. 6 (two integrals)": "claim-false",
    # Sec. 2.2-2.5: 4D sextets right; 2.2.4 erases the wrong equations; 2.2.5 names its set S_5; the 3D triples keep
    # terms of locked axes; 2.5 heading/text name the wrong axis (2 is locked); 4D has six equations
    "42": "holds", "43": "holds", "44": "holds", "45": "holds", "46": "holds", "47": "holds",
    "Sec. 2.2.1 (heading, locked set)": "holds", "48": "holds", "49": "holds", "50": "holds",
    "51": "holds", "52": "holds", "53": "holds", "Sec. 2.2.2 (heading, locked set)": "holds",
    "54": "holds", "55": "holds", "56": "holds", "57": "holds", "58": "holds", "59": "holds",
    "Sec. 2.2.3 (heading, locked set)": "holds", "60": "holds", "61": "holds", "62": "holds",
    "63": "holds", "64": "holds", "65": "holds", "Sec. 2.2.4 (heading, locked set)": "typo",
    "66": "holds", "67": "holds", "68": "holds", "69": "holds", "70": "holds", "71": "holds",
    "Sec. 2.2.5 (heading, locked set)": "typo", "73": "typo", "74": "typo", "75": "typo",
    "Sec. 2.3 (heading, locked set)": "holds", "76": "typo", "77": "typo", "78": "typo",
    "Sec. 2.4 (heading, locked set)": "holds", "79": "typo", "80": "typo", "81": "typo",
    "Sec. 2.5 (heading, locked set)": "claim-false", "72": "holds",
    "Sec. 2.5 (closing statement)": "claim-false",
    # Sec. 3: (83) duplicates w23 and omits w14; (92), (95) wrong sign; kappa(Theta) sign; Theta = -1 attained;
    # omega for C in (104)-(105) and sign of c5; strict inequalities fail at Pfaffian 0 / self-dual data
    "82": "holds", "82 (Platonic bodies)": "holds", "83": "typo", "83 (all dimensions)": "holds", "84-85": "holds",
    "86": "holds", "87": "holds", "88": "holds", "89": "holds", "90": "holds", "91": "holds", "92": "typo",
    "93": "holds", "94": "holds", "95": "typo", "96": "holds", "97": "holds", "98": "holds", "99": "holds",
    "100 (kappa from Theta)": "typo", "100 (range of Theta)": "claim-false", "101": "holds", "102": "holds",
    "103": "holds", "104": "typo", "105": "typo", "106": "typo", "106 (antisymmetric)": "claim-false", "107": "holds",
    "108 (l2)": "holds", "108 (l0)": "holds", "108 (l2 < 0)": "claim-false", "108 (l0 > 0)": "claim-false",
    "109": "holds", "110": "claim-false", "after 118 (frequencies)": "holds", "111": "holds", "115": "holds",
    "112": "holds", "116": "holds", "113": "holds", "117": "holds", "114": "holds", "118": "holds",
    # Sec. 4: linearization right; (132) lists varpi6 for varpi8; group-2 partner has the wrong sign; nu's garbled;
    # non-strict orderings admit J1 = J2 (defective zero eigenvalue)
    "Sec. 4 (four equations satisfied)": "holds", "119-120": "not-checkable", "121": "holds", "122": "holds",
    "123": "holds", "124": "holds", "125": "holds", "126": "holds", "127": "holds", "128": "holds", "129": "holds",
    "130": "holds", "131": "not-checkable", "132": "typo", "133": "holds", "134": "holds", "135": "not-checkable",
    "136 (varpi_3)": "holds", "136 (varpi_6)": "typo", "136": "not-checkable", "137 (varpi_4)": "holds",
    "137": "holds", "138": "not-checkable", "139": "claim-false", "140": "claim-false",
    # Sec. 5: operators right; (144) copies (25); contractions hold for sum_k [L_ik, L_jk] = -(N-2) L_ij
    "141": "holds", "142": "holds", "143": "holds", "144": "typo", "145": "holds", "146": "holds", "147": "holds",
    "Sec. 5 (cross-references)": "typo",
}


@pytest.fixture(scope="module")
def verdicts():
    V.clear_cache()
    return V.verify()


def test_every_verdict_pinned(verdicts):
    got = {v.equation: v.status for v in verdicts}
    assert len(got) == len(verdicts), "equation labels must be unique"
    assert set(got) == set(EXPECTED)
    wrong = {k: (got[k], EXPECTED[k]) for k in EXPECTED if got[k] != EXPECTED[k]}
    assert not wrong


def test_counts_and_order(verdicts):
    c = V.summary(verdicts)
    assert c == {s: sum(1 for v in EXPECTED.values() if v == s) for s in V.STATUSES}
    # sections come in paper order
    order = [v.section for v in verdicts]
    assert sorted(order, key=list(V.SECTIONS).index) == order


def test_details_name_the_corrections(verdicts):
    by = {v.equation: v for v in verdicts}
    assert "(30),(33),(35),(37)" in by["Sec. 2.2.4 (heading, locked set)"].detail
    assert "w14" in by["83"].detail
    assert "1 - Theta" in by["100 (kappa from Theta)"].detail
    assert "-1 <= Theta < 1" in by["100 (range of Theta)"].detail
    assert "(2,4)" in by["106"].detail
    assert "varpi1, varpi8, varpi9, varpi10 = const" in by["132"].detail
    assert "-3 = -(N-2)" in by["145"].detail
    assert "lambda^5" in by["38"].detail
    assert "axes (2, 5) are locked" in by["Sec. 2.5 (heading, locked set)"].detail
    for v in verdicts:
        assert v.detail.strip(), v.equation
        if v.status in ("typo", "claim-false"):
            assert v.detail != "agrees with the derived form"


def test_json_schema(verdicts):
    data = json.loads(V.render(verdicts, format="json"))
    assert isinstance(data, list) and len(data) == len(verdicts)
    for obj in data:
        assert {"equation", "status", "detail", "printed", "correct", "section"} <= set(obj)
        assert isinstance(obj["equation"], str) and obj["equation"]
        assert obj["status"] in V.STATUSES
        assert isinstance(obj["detail"], str) and obj["detail"]
        assert obj["section"] in V.SECTIONS
        assert obj["printed"] is None or isinstance(obj["printed"], str)


def test_table_and_markdown(verdicts):
    table = V.render(verdicts, format="table")
    md = V.render(verdicts, format="markdown")
    for v in verdicts:
        assert v.equation in table
    c = V.summary(verdicts)
    assert f"| typo | {c['typo']} |" in md
    assert md.count("\n## ") == len(V.SECTIONS)
    assert f"{len(verdicts)} items" in table


def test_bad_inputs():
    with pytest.raises(ValueError, match="allowed"):
        V.verify(["bogus"])
    with pytest.raises(ValueError, match="allowed"):
        V.render([], format="html")
    with pytest.raises(ValueError, match="status"):
        V.Verdict("1", "fine", "x")
    from hyperrotor.cli import main

    assert main(["verify", "--section", "bogus"]) == 2  # the one command line: `hyperrotor verify` (#21): usage error


def test_cli_verify_json_section(capsys):
    from hyperrotor.cli import main

    assert main(["verify", "--json", "--section", "quantum"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert {d["equation"] for d in data} == {k for k, v in EXPECTED.items()
                                             if k in ("141", "142", "143", "144", "145", "146", "147",
                                                      "Sec. 5 (cross-references)")}


# ----------------------------------------------------------------------------
# verdicts are computed: corrupting (or repairing) a transcription flips them
# ----------------------------------------------------------------------------
def _status(section, equation):
    V.clear_cache(derived=False)
    return {v.equation: v.status for v in V.verify([section])}[equation]


@pytest.fixture
def fresh(monkeypatch):
    yield monkeypatch
    monkeypatch.undo()
    V.clear_cache(derived=False)


def test_corrupting_eq89_flips_to_typo(fresh):
    assert _status("closed-form", "89") == "holds"
    fresh.setitem(ps.LATEX, "89", ps.LATEX["89"].replace(r"\omega_{13}\omega_{35}", r"\omega_{13}\omega_{45}"))
    assert _status("closed-form", "89") == "typo"


def test_repairing_eq92_flips_to_holds(fresh):
    fresh.setitem(ps.LATEX, "92", ps.LATEX["92"].replace("+ (1 - \\kappa^2)", "- (1 - \\kappa^2)"))
    assert _status("closed-form", "92") == "holds"


def test_corrupting_eq28_flips_to_typo(fresh):
    eq = pr.PRINTED_EULER["28"]
    I13, I23 = (s for s in eq.lhs.free_symbols if s.name in ("I_13", "I_23"))
    fresh.setitem(pr.PRINTED_EULER, "28", type(eq)(eq.lhs.xreplace({I13: I23, I23: I13}), eq.rhs, evaluate=False))
    assert _status("euler", "28") == "typo"


def test_nonstrict_inequality_flips_claim(fresh):
    fresh.setitem(ps.LATEX, "108", ps.LATEX["108"].replace("< 0", r"\leq 0"))
    assert _status("closed-form", "108 (l2 < 0)") == "holds"
    assert _status("closed-form", "108 (l0 > 0)") == "claim-false"


def test_count_claim_flips(fresh):
    fresh.setitem(ps.CLAIMS["Sec. 2.1 (3D cases)"], "count", 10)
    assert _status("euler", "Sec. 2.1 (number of 3D cases)") == "holds"


def test_garbled_frequency_becomes_checkable(fresh):
    fresh.setitem(ps.LITERAL, "135", "sqrt((J_1 - J_2)*(J_1 - J_4)/(J_2*J_4))")
    assert _status("stability", "135") == "holds"
    fresh.setitem(ps.LITERAL, "135", "sqrt((J_1 - J_2)*(J_1 + J_4)/(J_2*J_4))")
    assert _status("stability", "135") == "typo"


def test_docs_page_is_current(verdicts):
    page = Path(__file__).resolve().parents[2] / "docs" / "verification.md"
    expected = V.render(verdicts, format="markdown")
    assert page.exists(), "generate it: hyperrotor verify --markdown -o docs/verification.md --force"
    text = page.read_text(encoding="utf-8")
    assert text.rstrip("\n") == expected.rstrip("\n"), (
        "docs/verification.md is stale; regenerate: hyperrotor verify --markdown -o docs/verification.md --force"
    )
