"""Modified-DH derivations against independent truths: the numeric chains, hand-worked numbers, elementary products."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
import sympy as sp

from puma_course import MK3, DHChain, Link, Puma560, mdh
from puma_course import symbolic as S
from tests.support import random_q


def test_mdh_sym_equals_product_of_four_elementary_transforms():
    al, a, th, d = sp.symbols("alpha a theta d", real=True)
    diff = S.elementary_product_sym(al, a, th, d) - S.mdh_sym(al, a, th, d)
    assert diff.applyfunc(sp.simplify) == sp.zeros(4, 4)


def test_mdh_sym_matches_numeric_mdh():
    rng = np.random.default_rng(1)
    al, a, th, d = sp.symbols("alpha a theta d", real=True)
    f = sp.lambdify((al, a, th, d), S.mdh_sym(al, a, th, d), modules="numpy")
    g = sp.lambdify((al, a, th, d), S.elementary_product_sym(al, a, th, d), modules="numpy")
    for _ in range(10):
        x = rng.uniform(-3, 3, 4)
        np.testing.assert_allclose(np.array(f(*x), dtype=float), mdh(*x), atol=1e-12)
        np.testing.assert_allclose(np.array(g(*x), dtype=float), mdh(*x), atol=1e-12)


@pytest.mark.parametrize(
    "lengths", [{}, {"a2": 0.7, "a3": -0.11, "d3": 0.33, "d4": 0.25}], ids=["default", "other-lengths"]
)
def test_puma560_closed_forms_equal_numeric_fk(lengths, puma560_lengths):
    arm = Puma560(**lengths)
    L = {**puma560_lengths, **lengths}
    Q = random_q(6, seed=2, N=25)
    np.testing.assert_allclose(S.fk_from_forms(S.closed_forms_puma560(), Q, **L), arm.fk(Q), atol=1e-12)
    # the short-hand form evaluates to the same thing
    np.testing.assert_allclose(
        S.fk_from_forms(S.closed_forms_puma560(shorthand=True), Q[:3], **L), arm.fk(Q[:3]), atol=1e-12
    )


@pytest.mark.parametrize(
    "lengths", [{}, {"d1": 500.0, "a1": 80.0, "a2": 300.0, "a3": 190.0, "d5": 40.0}], ids=["default", "other-lengths"]
)
def test_mk3_closed_forms_equal_numeric_fk(lengths, mk3_lengths):
    arm = MK3(**lengths)
    L = {**mk3_lengths, **lengths}
    Q = random_q(5, seed=3, N=25)
    np.testing.assert_allclose(S.fk_from_forms(S.closed_forms_mk3(), Q, **L), arm.fk(Q), atol=1e-9)


def test_fk_from_forms_single_configuration_is_the_batch_row(puma560_lengths):
    Q = random_q(6, seed=4, N=3)
    batch = S.fk_from_forms(S.closed_forms_puma560(), Q, **puma560_lengths)
    assert batch.shape == (3, 4, 4)
    one = S.fk_from_forms(S.closed_forms_puma560(), Q[1], **puma560_lengths)
    assert one.shape == (4, 4)
    np.testing.assert_allclose(one, Puma560().fk(Q[1]), atol=1e-12)


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
    arm = Puma560()
    rows = S.table_sym(arm)
    assert rows[1][0] == -sp.pi / 2  # exact angle, so cos/sin are exact
    assert rows[2][1] == sp.Rational(2159, 5000)  # a2 = 0.4318 m as an exact number
    _, T = S.chain_sym(rows)
    q = np.array([0.3, -1.1, 0.4, 2.0, -0.7, 1.3])
    num = np.array(T.subs(dict(zip(S.theta_symbols(6), q, strict=True))).evalf(), dtype=float)
    np.testing.assert_allclose(num, arm.fk(q), atol=1e-12)


def test_table_sym_of_a_chain_with_a_prismatic_joint_and_offsets_matches_fk():
    arm = DHChain(
        [Link(0.0, 0.0, 0.2, theta=np.pi / 6), Link(-np.pi / 2, 0.3, 0.1, kind="P"), Link(np.pi / 3, 0.4, 0.0)]
    )
    rows = S.table_sym(arm)
    t1, t3 = sp.Symbol("theta1", real=True), sp.Symbol("theta3", real=True)
    d2 = sp.Symbol("d2", real=True)
    R = sp.Rational
    assert rows == [
        (0, 0, t1 + sp.pi / 6, R(1, 5)),
        (-sp.pi / 2, R(3, 10), 0, d2 + R(1, 10)),
        (sp.pi / 3, R(2, 5), t3, 0),
    ]
    _, T = S.chain_sym(arm, simplify=False)
    q = np.array([0.7, 0.25, -1.2])
    num = np.array(T.subs({t1: q[0], d2: q[1], t3: q[2]}).evalf(), dtype=float)
    np.testing.assert_allclose(num, arm.fk(q), atol=1e-12)


def test_derived_link_matrices_are_the_chain_factors():
    mats = S.derived_link_matrices(S.puma560_table_sym())
    assert list(mats) == ["0T1", "1T2", "2T3", "3T4", "4T5", "5T6"]
    q = random_q(6, seed=5)
    L = {"a2": 0.4318, "a3": 0.0203, "d3": 0.15005, "d4": 0.4318}
    subs = {**dict(zip(S.theta_symbols(6), q, strict=True)), **{sp.Symbol(k, real=True): v for k, v in L.items()}}
    prod = np.eye(4)
    for M in mats.values():
        prod = prod @ np.array(M.subs(subs).evalf(), dtype=float)
    np.testing.assert_allclose(prod, Puma560().fk(q), atol=1e-12)


def test_shorthand_round_trip():
    t = S.theta_symbols(4)
    e = sp.cos(t[0]) * sp.sin(t[1] + t[2] + t[3]) - sp.cos(t[1] + t[2]) + sp.sin(t[0] - t[1])
    short = S.to_shorthand(e)
    names = {s.name for s in short.free_symbols}
    assert {"C1", "S234", "C23"} <= names
    assert "theta1" in names  # sin(θ1 - θ2) is not a plain sum: left alone
    assert sp.simplify(S.expand_shorthand(short) - e) == 0


def test_collect_shorthand_groups_like_the_slides():
    # worked by hand from the table: px = C1 (a2 C2 + a3 C23 - d4 S23) - d3 S1
    C1, C2, C23, S1, S23 = S.shorthand("C1 C2 C23 S1 S23")
    a2, a3, d3, d4 = S.PUMA560_LENGTHS
    px = S.collect_shorthand(S.closed_forms_puma560()["px"])
    assert set(sp.Add.make_args(px)) == {C1 * (a2 * C2 + a3 * C23 - d4 * S23), -d3 * S1}  # grouped as printed


def test_bad_input():
    with pytest.raises(ValueError, match=r"^lengths: expected values for \['a1', 'a2', 'a3', 'd5'\]"):
        S.fk_from_forms(S.closed_forms_mk3(), np.zeros(5), d1=1.0)
    with pytest.raises(ValueError, match=r"^q: expected at least 5 joint values"):
        S.fk_from_forms(S.closed_forms_mk3(), np.zeros(3), d1=1, a1=1, a2=1, a3=1, d5=1)
    bad = SimpleNamespace(links=[SimpleNamespace(alpha_prev=0.0, a_prev=0.0, d=0.0, theta=0.0, kind="X")])
    with pytest.raises(ValueError, match=r"^chain.links\[0\].kind: expected 'R' or 'P', got 'X'"):
        S.table_sym(bad)
