"""Second derivation (sympy) of Porter's direct problem, and the printed formulas put to the test.

Each printed formula of the source is transcribed in ``porter_symbolic`` with its damage; the
tests state which are right and which are wrong, checked against the derived product and
against numbers from ``porter.fk`` (itself checked against ``transforms`` in test_porter).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from puma_course import porter as P
from puma_course import porter_symbolic as S

L1, L3, L4 = 1.0, 0.5, 0.3
LEN = (L1, L3, L4)


@pytest.fixture(scope="module")
def local_sc():
    return S.local_product().applyfunc(S.to_sc).applyfunc(S.reduce_sc)


def test_scene_product_equals_local_product_symbolically(local_sc):
    # the scene-frame product, each motion about the CURRENT axis (through the current joint point),
    # built with Rodrigues' formula and left-multiplication, is identically the local product
    M = S.scene_product("current")
    assert (M - local_sc).applyfunc(S.reduce_sc) == sp.zeros(4, 4)


def test_local_product_equals_fk_numerically():
    rng = np.random.default_rng(11)
    L = S.local_product()
    f = sp.lambdify([*S.Q, S.l1, S.l3, S.l4], L, "numpy")
    for q in rng.uniform(0, 2 * np.pi, (20, 6)):
        q[2] = abs(q[2])
        np.testing.assert_allclose(np.array(f(*q, *LEN), dtype=float), P.fk(q, *LEN), atol=1e-13)


def test_literal_reading_of_scene_axes_is_wrong():
    # reading y1 as the axis of F1 through p1 = p0 (and y2 through p2) moves p2 itself: not the chain
    M = S.scene_product("literal")
    q = [0.3, 0.2, 1.1, 0.4, 0.5, 0.6]
    num = np.array(M.subs(S.sc_values(q, *LEN)), dtype=float)
    assert np.abs(num - P.fk(q, *LEN)).max() > 0.1


def test_printed_local_product_misses_tx_q2():
    # as printed (no Tx(q2)), p5 does not depend on q2 - contradicting the printed p5
    PL = S.printed_local_product()
    assert not PL.has(S.q2)
    assert S.printed_closed_forms()["p5"][0].has(S.q2)
    M = S.local_product()
    assert sp.simplify(M.subs(S.q2, 0) - PL) == sp.zeros(4, 4)


def test_printed_closed_forms():
    ok = S.compare_closed_forms()
    wrong = [k for k, v in ok.items() if not v]
    assert wrong == ["z5[1]"]  # the only damaged entry
    derived = S.closed_forms()
    assert sp.expand(derived["z5"][1] - S.corrected_z5_2()) == 0
    # and the printed z5[1] is really different in value (not only in form)
    q = [0.3, 0.2, 1.1, 0.4, 0.5, 0.6]
    v = S.sc_values(q, *LEN)
    printed = float(S.printed_closed_forms()["z5"][1].subs(v))
    assert abs(printed - P.fk(q, *LEN)[1, 2]) > 0.1
    assert abs(float(S.corrected_z5_2().subs(v)) - P.fk(q, *LEN)[1, 2]) < 1e-13


def _pose_values(q):
    T = P.fk(q, *LEN)
    vals = {}
    for j, v in enumerate("xyzp"):
        for i in range(3):
            vals[sp.Symbol(f"{v}5_{i + 1}")] = T[i, j]
    a1, a2, _, a3, a4, a5 = q
    vals.update({S.c[1]: math.cos(a1), S.s[1]: math.sin(a1), S.c[2]: math.cos(a2), S.s[2]: math.sin(a2)})
    vals.update({S.c[4]: math.cos(a4), S.s[4]: math.sin(a4), S.l1: L1, S.l3: L3, S.l4: L4})
    return vals


def test_printed_ver1_equations_hold_in_general_position():
    F = S.printed_ver1()
    rng = np.random.default_rng(12)
    for q in rng.uniform(0.2, 1.3, (10, 6)):  # c1, c2, c4 far from 0
        v = _pose_values(q)
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


def test_printed_eq14_eq15_fail_where_c1_c4_vanish():
    F = S.printed_ver1()
    # α1 = π/2 (c1 = 0): eq. 14 becomes 0/0, eq. 15 divides by 0 - yet the pose is regular
    q = [math.pi / 2, 0.3, 1.2, 0.4, 0.5, 0.6]
    v = _pose_values(q)
    v[S.c[1]] = 0.0
    num, den = sp.fraction(sp.together(F["tan_a2_eq14"]))
    assert abs(float(num.subs(v))) < 1e-12 and abs(float(den.subs(v))) < 1e-12
    # eq. 15's denominator c1 c2 c4 is exactly 0 (its numerator c4 p4_1 is 0 too, up to rounding: no q2 to read).
    # The old check `... or not expr.is_finite` also passed when sympy could not decide (is_finite None).
    num, den = sp.fraction(sp.together(F["q2_eq15"]))
    assert den.subs(v) == 0 and abs(float(num.subs(v))) < 1e-12
    assert P.classify(P.fk(q, *LEN), *LEN) == []
    sols = P.ik_explicit(P.fk(q, *LEN), *LEN, near=q)
    assert P.config_distance(sols[0], q) < 1e-9
    # α2 = π/2 (c2 = 0, prismatic axis vertical): eq. 15 divides by zero, the module does not
    q = [0.3, math.pi / 2, 1.2, 0.4, 0.5, 0.6]
    sols = P.ik_explicit(P.fk(q, *LEN), *LEN, near=q)
    assert P.config_distance(sols[0], q) < 1e-9


def test_arctan_second_value_of_eq14_has_negative_q2():
    # eq. 14's two arctan values α2 and α2 + π give q2 of opposite signs in eq. 15: only one is in
    # the configuration space (this is why there are 4 solutions and not 8)
    F = S.printed_ver1()
    q = [0.4, 0.5, 1.3, 0.6, 0.7, 0.8]
    v = _pose_values(q)
    v2 = dict(v)
    v2[S.c[2]] = -v[S.c[2]]
    v2[S.s[2]] = -v[S.s[2]]
    assert float(F["q2_eq15"].subs(v)) == pytest.approx(1.3)
    assert float(F["q2_eq15"].subs(v2)) == pytest.approx(-1.3)


def test_ver2_printed_normal_order_flips_signs():
    # n024 as printed, (p4 - p0) x (p2 - p0), is -y1: used as the reference normal of angle() the
    # printed offsets give wrong α2, α3, α4; with n = (p2 - p0) x (p4 - p0) = y1 they are right
    q = np.array([0.4, 0.5, 1.3, 0.6, 0.7, 0.8])
    p = P.points(q, *LEN)
    T = P.fk(q, *LEN)
    p0, p2, p3, p4 = p[0], p[2], p[3], p[4]
    n_printed = np.cross(p4 - p0, p2 - p0)
    n_printed /= np.linalg.norm(n_printed)
    n = -n_printed
    z4 = (p3 - p4) / L3
    wrap = lambda a: (a + np.pi) % (2 * np.pi) - np.pi  # noqa: E731
    assert wrap(P.angle(p2 - p0, p3 - p2, n) - np.pi / 2 - q[1]) == pytest.approx(0, abs=1e-12)
    assert wrap(P.angle(p3 - p2, p4 - p3, n) - np.pi / 2 - q[3]) == pytest.approx(0, abs=1e-12)
    assert wrap(P.angle(n, T[:3, 0], z4) + np.pi / 2 - q[4]) == pytest.approx(0, abs=1e-12)
    assert wrap(P.angle(p3 - p4, T[:3, 2], T[:3, 0]) - q[5]) == pytest.approx(0, abs=1e-12)
    assert abs(wrap(P.angle(p2 - p0, p3 - p2, n_printed) - np.pi / 2 - q[1])) > 0.1
    assert abs(wrap(P.angle(n_printed, T[:3, 0], z4) + np.pi / 2 - q[4])) > 0.1
    # eq. 18 prints |p3 - p4| = l4: the chain has l3
    assert np.linalg.norm(p3 - p4) == pytest.approx(L3) and abs(L3 - L4) > 0.1
