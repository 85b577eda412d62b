"""Symbolic derivations against independent truths: the numeric chains, hand-worked numbers, elementary products."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from puma_course import mdh, mk3, puma560
from puma_course import symbolic as S


def test_mdh_sym_equals_product_of_four_elementary_transforms():
    al, a, th, d = sp.symbols("alpha a theta d", real=True)
    diff = S.elementary_product_sym(al, a, th, d) - S.mdh_sym(al, a, th, d)
    assert diff.applyfunc(sp.simplify) == sp.zeros(4, 4)
    # and the elementary factors are what their names say (checked by hand on a point)
    p = S.trans_x_sym(a) * sp.Matrix([0, 0, 0, 1])
    assert list(p) == [a, 0, 0, 1]
    assert S.rot_z_sym(sp.pi / 2) * sp.Matrix([1, 0, 0, 1]) == sp.Matrix([0, 1, 0, 1])
    assert S.rot_x_sym(sp.pi / 2) * sp.Matrix([0, 1, 0, 1]) == sp.Matrix([0, 0, 1, 1])


def test_mdh_sym_matches_numeric_mdh():
    rng = np.random.default_rng(1)
    al, a, th, d = sp.symbols("alpha a theta d", real=True)
    f = sp.lambdify((al, a, th, d), S.mdh_sym(al, a, th, d), modules="numpy")
    for _ in range(10):
        x = rng.uniform(-3, 3, 4)
        np.testing.assert_allclose(np.array(f(*x), dtype=float), mdh(*x), atol=1e-12)


def _random_q(n, seed, N=25):
    return np.random.default_rng(seed).uniform(-np.pi, np.pi, (N, n))


@pytest.mark.parametrize(
    "lengths", [{}, {"a2": 0.7, "a3": -0.11, "d3": 0.33, "d4": 0.25}], ids=["default", "other-lengths"]
)
def test_puma560_closed_forms_equal_numeric_fk(lengths):
    arm = puma560(**lengths)
    L = {**{"a2": 0.4318, "a3": 0.0203, "d3": 0.15005, "d4": 0.4318}, **lengths}
    Q = _random_q(6, seed=2)
    np.testing.assert_allclose(S.fk_from_forms(S.closed_forms_puma560(), Q, **L), arm.fk(Q), atol=1e-12)
    # the short-hand form evaluates to the same thing
    np.testing.assert_allclose(
        S.fk_from_forms(S.closed_forms_puma560(shorthand=True), Q[:3], **L), arm.fk(Q[:3]), atol=1e-12
    )


@pytest.mark.parametrize(
    "lengths", [{}, {"d1": 500.0, "a1": 80.0, "a2": 300.0, "a3": 190.0, "d5": 40.0}], ids=["default", "other-lengths"]
)
def test_mk3_closed_forms_equal_numeric_fk(lengths):
    arm = mk3(**lengths)
    L = {**{"d1": 360.0, "a1": 135.0, "a2": 250.0, "a3": 215.0, "d5": 100.0}, **lengths}
    Q = _random_q(5, seed=3)
    np.testing.assert_allclose(S.fk_from_forms(S.closed_forms_mk3(), Q, **L), arm.fk(Q), atol=1e-9)


def test_hand_worked_poses():
    # PUMA-560 at q = 0: p = (a2 + a3, d3, -d4) worked by hand from the link matrices
    f = S.closed_forms_puma560()
    zero = {s: 0 for s in S.theta_symbols(6)}
    a2, a3, d3, d4 = sp.symbols("a2 a3 d3 d4", real=True)
    assert [sp.simplify(f[k].subs(zero)) for k in ("px", "py", "pz")] == [a2 + a3, d3, -d4]
    # MK3 at q = 0: p = (a1 + a2 + a3, 0, d1 - d5) and the tool axis z5 points down (r33 = -1)
    g = S.closed_forms_mk3()
    zero5 = {s: 0 for s in S.theta_symbols(5)}
    d1, a1, a2m, a3m, d5 = sp.symbols("d1 a1 a2 a3 d5", real=True)
    assert [sp.simplify(g[k].subs(zero5)) for k in ("px", "py", "pz", "r33")] == [a1 + a2m + a3m, 0, d1 - d5, -1]


def test_chain_sym_from_dhchain_is_exact_and_matches_fk():
    arm = puma560()
    rows = S.table_sym(arm)
    assert rows[1][0] == -sp.pi / 2  # exact angle, so cos/sin are exact
    assert rows[2][1] == sp.Rational(2159, 5000)  # a2 = 0.4318 m as an exact number
    _, T = S.chain_sym(rows)
    q = np.array([0.3, -1.1, 0.4, 2.0, -0.7, 1.3])
    num = np.array(T.subs(dict(zip(S.theta_symbols(6), q, strict=True))).evalf(), dtype=float)
    np.testing.assert_allclose(num, arm.fk(q), atol=1e-12)


def test_shorthand_round_trip():
    t = S.theta_symbols(4)
    e = sp.cos(t[0]) * sp.sin(t[1] + t[2] + t[3]) - sp.cos(t[1] + t[2]) + sp.sin(t[0] - t[1])
    short = S.to_shorthand(e)
    names = {s.name for s in short.free_symbols}
    assert {"C1", "S234", "C23"} <= names
    assert "theta1" in names  # sin(θ1 - θ2) is not a plain sum: left alone
    assert sp.simplify(S.expand_shorthand(short) - e) == 0


def test_printed_mk3_link_matrix_misprint_is_flagged_exactly():
    res = S.check_printed(S.printed_mk3_link_matrices(), S.derived_link_matrices(S.mk3_table_sym()))
    assert res.differ == ["4T5[2,4]", "4T5[3,4]"]
    d5 = sp.Symbol("d5", real=True)
    bad = {e.name: e for e in res.entries if not e.agrees}
    assert bad["4T5[2,4]"].derived == -d5 and bad["4T5[3,4]"].derived == 0
    # the deciding computation, numerically: the printed ^4T5 moves the tool sideways, the table does not
    q = np.array([0.4, 0.3, -0.2, 0.5, 0.9])
    L = {"d1": 360.0, "a1": 135.0, "a2": 250.0, "a3": 215.0, "d5": 100.0}
    subs = {**{S.theta_symbols(5)[i]: q[i] for i in range(5)}, **{sp.Symbol(k, real=True): v for k, v in L.items()}}
    printed = S.printed_mk3_link_matrices()
    prod = sp.eye(4)
    for key in ("0T1", "1T2", "2T3", "3T4", "4T5"):
        prod = prod * S.expand_shorthand(printed[key])
    P = np.array(prod.subs(subs).evalf(), dtype=float)
    T = mk3().fk(q)
    assert np.linalg.norm(P[:3, 3] - T[:3, 3]) == pytest.approx(np.sqrt(2) * 100.0)  # off by d5 along y4 and z4
    np.testing.assert_allclose(P[:3, :3], T[:3, :3], atol=1e-12)  # rotations agree


def test_printed_forms_that_are_right_are_not_flagged():
    assert S.check_printed(S.printed_mk3_0T5(), S.closed_forms_mk3()).ok
    assert S.check_printed(S.printed_puma560_0T6_entries(), S.closed_forms_puma560()).ok
    assert S.check_printed(S.printed_puma560_link_matrices(), S.derived_link_matrices(S.puma560_table_sym())).ok
    al, a, th, d = sp.symbols("alpha a theta d", real=True)
    assert S.check_printed(S.printed_general_link_matrix(), S.mdh_sym(al, a, th, d)).ok


def test_check_printed_catches_a_planted_error():
    printed = dict(S.printed_puma560_0T6_entries())
    C23, S5, C6 = (sp.Symbol(n, real=True) for n in ("C23", "S5", "C6"))
    printed["r31"] = printed["r31"] + 2 * C23 * S5 * C6  # sign of the last term flipped
    res = S.check_printed(printed, S.closed_forms_puma560())
    assert res.differ == ["r31"]
    assert "DIFFERS" in res._repr_html_()


def test_bad_input():
    with pytest.raises(ValueError, match="derived"):
        S.check_printed({"r11": 0}, {"r12": 0})
    with pytest.raises(ValueError, match="lengths"):
        S.fk_from_forms(S.closed_forms_mk3(), np.zeros(5), d1=1.0)
    with pytest.raises(ValueError, match="q"):
        S.fk_from_forms(S.closed_forms_mk3(), np.zeros(3), d1=1, a1=1, a2=1, a3=1, d5=1)
