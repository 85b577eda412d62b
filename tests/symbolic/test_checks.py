"""check_printed: it flags exactly the entries that differ, whatever the simplifier manages."""

from __future__ import annotations

import pytest
import sympy as sp

from puma_course import symbolic as S
from puma_course.symbolic import porter as PS
from puma_course.symbolic import printed


def test_check_printed_catches_a_planted_error():
    planted = dict(printed.PUMA560_0T6)
    C23, S5, C6 = S.shorthand("C23 S5 C6")
    planted["r31"] = planted["r31"] + 2 * C23 * S5 * C6  # sign of the last term flipped
    res = S.check_printed(planted, S.closed_forms_puma560())
    assert res.differ == ["r31"]
    assert not res.ok
    assert "DIFFERS" in res._repr_html_()
    assert "1 of 3 entries differ" in repr(res)
    # the reported difference is the planted term, in the short-hand
    bad = res.entries[2]
    assert sp.expand(S.expand_shorthand(bad.difference) - S.expand_shorthand(2 * C23 * S5 * C6)) == 0


def test_check_printed_catches_a_planted_error_in_porter_notation():
    c, s = PS.c, PS.s
    planted = {k: list(v) for k, v in printed.porter.CLOSED_FORMS.items()}
    planted["x5"][2] = planted["x5"][2] + c[1] ** 2 + s[1] ** 2 - 1  # zero on the circle: not an error
    planted["p5"][0] = planted["p5"][0] + PS.l4 * s[4] * (c[2] ** 2 + s[2] ** 2)  # an extra l4 s4: an error
    res = S.check_printed(planted, PS.closed_forms(), notation="porter")
    assert res.differ == ["z5[1]", "p5[0]"]
    assert res.verdicts["x5[2]"] and not res.verdicts["p5[0]"]
    assert {e.name: e.difference for e in res.entries}["p5[0]"] == PS.l4 * s[4]  # reduced, in ci, si


def test_numeric_verdict_does_not_depend_on_the_simplifier():
    # equal for every angle in [-π, π], in a form simplify() leaves alone: the numbers decide "agrees"
    t = sp.Symbol("theta1", real=True)
    hard = sp.acos(sp.cos(t)) - sp.Abs(t)
    res = S.check_printed({"e": hard + 1}, {"e": 1})
    assert res.entries[0].difference != 0  # the simplifier did not reach 0 ...
    assert res.ok  # ... and that raises no false alarm
    # and a difference of 1e-6 is a difference
    assert S.check_printed({"e": sp.cos(t) + sp.Rational(1, 10**6)}, {"e": sp.cos(t)}).differ == ["e"]


def test_entry_names_follow_the_containers():
    d5 = sp.Symbol("d5", real=True)
    res = S.check_printed({"4T5": sp.Matrix([[0, d5]]), "v": (d5, 0)}, {"4T5": sp.Matrix([[0, -d5]]), "v": [d5, 1]})
    assert res.verdicts == {"4T5[1,1]": True, "4T5[1,2]": False, "v[0]": True, "v[1]": False}


def test_numeric_error_samples_angles_and_lengths():
    t, a = sp.Symbol("alpha3"), sp.Symbol("a")
    assert S.numeric_error(sp.cos(t) ** 2 + sp.sin(t) ** 2 - 1) < 1e-12
    assert 0.5 <= S.numeric_error(a) <= 2.0  # lengths in [0.5, 2]
    assert 0.9 < S.numeric_error(sp.sin(t), samples=200) <= 1.0  # angles over the whole turn
    assert S.numeric_error(sp.Integer(3)) == 3.0


def test_bad_input():
    with pytest.raises(ValueError, match=r"^derived: expected entries named like the printed ones, missing \['r11'\]"):
        S.check_printed({"r11": 0}, {"r12": 0})
    with pytest.raises(ValueError, match=r"^notation: expected one of \['meghdari', 'porter'\], got 'craig'"):
        S.check_printed({"r11": 0}, {"r11": 0}, notation="craig")
