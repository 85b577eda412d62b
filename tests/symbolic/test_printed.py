"""The sources' formulas as printed, put to the test: which are right, which are wrong, and by how much.

Each verdict is decided against an independent truth: the derivation from the table, the numeric
chain (``MK3().fk``, ``porter.fk``), or a number worked out by hand.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from puma_course import MK3, Porter
from puma_course import symbolic as S
from puma_course.kinematics.ik import joint_distance
from puma_course.kinematics.porter import REVOLUTE, angle
from puma_course.symbolic import porter as PS
from puma_course.symbolic import printed

# ---- Meghdari ----------------------------------------------------------------------------------


def test_printed_mk3_link_matrix_misprint_is_flagged_exactly(mk3_lengths):
    res = S.check_printed(printed.MK3_LINK_MATRICES, S.derived_link_matrices(S.mk3_table_sym()))
    assert res.differ == ["4T5[2,4]", "4T5[3,4]"]
    d5 = sp.Symbol("d5", real=True)
    bad = {e.name: e for e in res.entries if not e.agrees}
    assert bad["4T5[2,4]"].derived == -d5 and bad["4T5[3,4]"].derived == 0
    # the deciding computation, numerically: the printed ^4T5 moves the tool sideways, the table does not
    q = np.array([0.4, 0.3, -0.2, 0.5, 0.9])
    L = mk3_lengths
    subs = {**{S.theta_symbols(5)[i]: q[i] for i in range(5)}, **{sp.Symbol(k, real=True): v for k, v in L.items()}}
    prod = sp.eye(4)
    for key in ("0T1", "1T2", "2T3", "3T4", "4T5"):
        prod = prod * S.expand_shorthand(printed.MK3_LINK_MATRICES[key])
    Pm = np.array(prod.subs(subs).evalf(), dtype=float)
    T = MK3().fk(q)
    assert np.linalg.norm(Pm[:3, 3] - T[:3, 3]) == pytest.approx(np.sqrt(2) * 100.0)  # off by d5 along y4 and z4
    np.testing.assert_allclose(Pm[:3, :3], T[:3, :3], atol=1e-12)  # rotations agree


def test_printed_forms_that_are_right_are_not_flagged():
    assert S.check_printed(printed.MK3_0T5, S.closed_forms_mk3()).ok
    assert S.check_printed(printed.PUMA560_0T6, S.closed_forms_puma560()).ok
    assert S.check_printed(printed.PUMA560_LINK_MATRICES, S.derived_link_matrices(S.puma560_table_sym())).ok
    al, a, th, d = sp.symbols("alpha a theta d", real=True)
    assert S.check_printed(printed.GENERAL_LINK_MATRIX, S.mdh_sym(al, a, th, d)).ok
    # mdh_sym is typed entry by entry like the print; the derivation is the product of the four motions
    assert S.check_printed(printed.GENERAL_LINK_MATRIX, S.elementary_product_sym(al, a, th, d)).ok


def test_printed_mk3_0T5_equals_numeric_fk(mk3_lengths):
    # independent of the derivation: the printed closed forms reproduce the numeric chain
    Q = np.random.default_rng(31).uniform(-np.pi, np.pi, (10, 5))
    np.testing.assert_allclose(S.fk_from_forms(printed.MK3_0T5, Q, **mk3_lengths), MK3().fk(Q), atol=1e-9)


def test_printed_data_is_immutable():
    with pytest.raises(TypeError):
        printed.MK3_LINK_MATRICES["4T5"] = sp.eye(4)  # type: ignore[index]
    with pytest.raises(TypeError):
        printed.MK3_LINK_MATRICES["4T5"][2, 3] = 0
    with pytest.raises(TypeError):
        printed.porter.CLOSED_FORMS["z5"][1] = 0  # type: ignore[index]


# ---- Porter: the direct problem ----------------------------------------------------------------


def test_printed_local_product_misses_tx_q2():
    # as printed (no Tx(q2)), p5 does not depend on q2 - contradicting the printed p5
    PL = PS.local_product(printed.porter.LOCAL_PRODUCT)
    assert not PL.has(PS.q2)
    assert printed.porter.CLOSED_FORMS["p5"][0].has(PS.q2)
    M = PS.local_product()
    assert sp.simplify(M.subs(PS.q2, 0) - PL) == sp.zeros(4, 4)
    # the transcription differs from the chain's motions by exactly that factor
    assert [m for m in PS.MOTIONS if m not in printed.porter.LOCAL_PRODUCT] == [("T", "x", PS.q2)]


def test_printed_scene_product_is_the_chain_read_backwards():
    # the scene-frame product prints every motion, Tx2(q2) included, last applied first
    assert [(k, ax, v) for k, ax, _, v in reversed(printed.porter.SCENE_PRODUCT)] == list(PS.MOTIONS)


def test_printed_closed_forms(porter_lengths):
    res = S.check_printed(printed.porter.CLOSED_FORMS, PS.closed_forms(), notation="porter")
    assert res.differ == ["z5[1]"]  # the only damaged entry
    assert len(res.verdicts) == 12
    derived = PS.closed_forms()
    assert sp.expand(derived["z5"][1] - PS.corrected_z5_2()) == 0
    # and the printed z5[1] is really different in value (not only in form)
    q = [0.3, 0.2, 1.1, 0.4, 0.5, 0.6]
    v = PS.sc_values(q, *porter_lengths)
    T = Porter(*porter_lengths).fk(q)
    assert abs(float(printed.porter.CLOSED_FORMS["z5"][1].subs(v)) - T[1, 2]) > 0.1
    assert abs(float(PS.corrected_z5_2().subs(v)) - T[1, 2]) < 1e-13
    # every other printed entry gives the numeric pose
    for j, name in enumerate(("x5", "y5", "z5", "p5")):
        for i, e in enumerate(printed.porter.CLOSED_FORMS[name]):
            if (name, i) != ("z5", 1):
                assert float(e.subs(v)) == pytest.approx(T[i, j], abs=1e-13)


# ---- Porter: the inverse problem ---------------------------------------------------------------


def _pose_values(q, lengths):
    L1, L3, L4 = lengths
    T = Porter(*lengths).fk(q)
    vals = {}
    for j, v in enumerate("xyzp"):
        for i in range(3):
            vals[sp.Symbol(f"{v}5_{i + 1}")] = T[i, j]
    a1, a2, _, a3, a4, a5 = q
    vals.update({PS.c[1]: math.cos(a1), PS.s[1]: math.sin(a1), PS.c[2]: math.cos(a2), PS.s[2]: math.sin(a2)})
    vals.update({PS.c[4]: math.cos(a4), PS.s[4]: math.sin(a4), PS.l1: L1, PS.l3: L3, PS.l4: L4})
    return vals


def test_printed_ver1_equations_hold_in_general_position(porter_lengths):
    F = printed.porter.VER1
    rng = np.random.default_rng(12)
    for q in rng.uniform(0.2, 1.3, (10, 6)):  # c1, c2, c4 far from 0
        v = _pose_values(q, porter_lengths)
        a1, a2, q2, a3, a4, a5 = q
        assert float(F["s4_eq8"].subs(v)) == pytest.approx(math.sin(a4), abs=1e-12)
        assert float(F["s4_eq8_p"].subs(v)) == pytest.approx(math.sin(a4), abs=1e-12)
        assert float(F["tan_a1_eq9"].subs(v)) == pytest.approx(math.tan(a1), rel=1e-10)
        assert float(F["c5_eq11"].subs(v)) == pytest.approx(math.cos(a5), abs=1e-12)
        assert float(F["s5_eq11"].subs(v)) == pytest.approx(math.sin(a5), abs=1e-12)
        assert float(F["a5_eq12"].subs(v)) == pytest.approx(math.cos(a2 + a3), abs=1e-12)
        assert float(F["a6_eq12"].subs(v)) == pytest.approx(math.sin(a2 + a3), abs=1e-12)
        assert float(F["tan_a2_eq14"].subs(v)) == pytest.approx(math.tan(a2), rel=1e-9)
        assert float(F["q2_eq15"].subs(v)) == pytest.approx(q2, rel=1e-10)


def test_printed_eq14_eq15_fail_where_c1_c4_vanish(porter_lengths):
    F = printed.porter.VER1
    # α1 = π/2 (c1 = 0): eq. 14 becomes 0/0, eq. 15 divides by 0 - yet the pose is regular
    q = [math.pi / 2, 0.3, 1.2, 0.4, 0.5, 0.6]
    v = _pose_values(q, porter_lengths)
    v[PS.c[1]] = 0.0
    num, den = sp.fraction(sp.together(F["tan_a2_eq14"]))
    assert abs(float(num.subs(v))) < 1e-12 and abs(float(den.subs(v))) < 1e-12
    # eq. 15's denominator c1 c2 c4 is exactly 0 (its numerator c4 p4_1 is 0 too, up to rounding: no q2 to read).
    # The old check `... or not expr.is_finite` also passed when sympy could not decide (is_finite None).
    num, den = sp.fraction(sp.together(F["q2_eq15"]))
    assert den.subs(v) == 0 and abs(float(num.subs(v))) < 1e-12
    assert Porter(*porter_lengths).classify(Porter(*porter_lengths).fk(q)) == ()
    sols = Porter(*porter_lengths).ik(Porter(*porter_lengths).fk(q), near=q)
    assert joint_distance(sols[0], q, REVOLUTE) < 1e-9
    # α2 = π/2 (c2 = 0, prismatic axis vertical): eq. 15 divides by zero, the module does not
    q = [0.3, math.pi / 2, 1.2, 0.4, 0.5, 0.6]
    sols = Porter(*porter_lengths).ik(Porter(*porter_lengths).fk(q), near=q)
    assert joint_distance(sols[0], q, REVOLUTE) < 1e-9


def test_arctan_second_value_of_eq14_has_negative_q2(porter_lengths):
    # eq. 14's two arctan values α2 and α2 + π give q2 of opposite signs in eq. 15: only one is in
    # the configuration space (this is why there are 4 solutions and not 8)
    F = printed.porter.VER1
    q = [0.4, 0.5, 1.3, 0.6, 0.7, 0.8]
    v = _pose_values(q, porter_lengths)
    v2 = dict(v)
    v2[PS.c[2]] = -v[PS.c[2]]
    v2[PS.s[2]] = -v[PS.s[2]]
    assert float(F["q2_eq15"].subs(v)) == pytest.approx(1.3)
    assert float(F["q2_eq15"].subs(v2)) == pytest.approx(-1.3)


def _points_values(p, T, n):
    vals = {}
    for i in (0, 2, 3, 4):
        vals.update({sym: p[i][k] for k, sym in enumerate(S.notation.point_symbols(i))})
    vals.update({sp.Symbol(f"x5_{k + 1}"): T[k, 0] for k in range(3)})
    vals.update({sp.Symbol(f"n024_{k + 1}"): n[k] for k in range(3)})
    return vals


def test_ver2_printed_normal_order_flips_signs(porter_lengths):
    # n024 as printed, (p4 - p0) x (p2 - p0), is -y1: used as the reference normal of angle() the
    # printed offsets give wrong α2, α3, α4; with n = (p2 - p0) x (p4 - p0) = y1 they are right
    L1, L3, L4 = porter_lengths
    q = np.array([0.4, 0.5, 1.3, 0.6, 0.7, 0.8])
    p = Porter(*porter_lengths).points(q)
    T = Porter(*porter_lengths).fk(q)
    p0, p2, p3, p4 = p[0], p[2], p[3], p[4]
    n_printed = np.cross(p4 - p0, p2 - p0)
    n_printed /= np.linalg.norm(n_printed)
    # the transcription of the printed n024 is that vector
    vals = _points_values(p, T, n_printed)
    n024 = np.array(printed.porter.VER2_N024.subs(vals), dtype=float).ravel()
    np.testing.assert_allclose(n024, n_printed, atol=1e-14)
    n = -n_printed
    z4 = (p3 - p4) / L3
    wrap = lambda a: (a + np.pi) % (2 * np.pi) - np.pi  # noqa: E731
    assert wrap(angle(p2 - p0, p3 - p2, n) - np.pi / 2 - q[1]) == pytest.approx(0, abs=1e-12)
    assert wrap(angle(p3 - p2, p4 - p3, n) - np.pi / 2 - q[3]) == pytest.approx(0, abs=1e-12)
    assert wrap(angle(n, T[:3, 0], z4) + np.pi / 2 - q[4]) == pytest.approx(0, abs=1e-12)
    assert wrap(angle(p3 - p4, T[:3, 2], T[:3, 0]) - q[5]) == pytest.approx(0, abs=1e-12)
    assert abs(wrap(angle(p2 - p0, p3 - p2, n_printed) - np.pi / 2 - q[1])) > 0.1
    assert abs(wrap(angle(n_printed, T[:3, 0], z4) + np.pi / 2 - q[4])) > 0.1
    # eq. 18 prints |p3 - p4| = l4: the chain has l3
    assert np.linalg.norm(p3 - p4) == pytest.approx(L3) and abs(L3 - L4) > 0.1
    eq18 = [float(e.subs(vals).subs({PS.l4: L4})) for e in printed.porter.VER2_EQ18]
    assert eq18[:2] == pytest.approx([0.0, 0.0], abs=1e-12)  # p3 - p4 is in the plane and normal to x5
    assert abs(eq18[2]) > 0.1  # but its squared length is not l4²
    assert float(printed.porter.VER2_EQ18[2].subs(vals).subs({PS.l4: L3})) == pytest.approx(0.0, abs=1e-12)
    # and the printed p3 = p4 ± l3 z4 (after eq. 19) has the right length: one sign gives the chain's p3
    z4_vals = {sp.Symbol(f"z4_{k + 1}"): z4[k] for k in range(3)}
    p3_plus = np.array(printed.porter.VER2_P3[0].subs(vals).subs(z4_vals).subs({PS.l3: L3}), dtype=float).ravel()
    np.testing.assert_allclose(p3_plus, p3, atol=1e-12)
