"""The one rot/trans API against hand-worked points, rotation properties and the numeric transforms."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from puma_course import transforms as tf
from puma_course.symbolic import elementary as E
from tests.support import random_q

t = sp.Symbol("t", real=True)


def _num(M, **values) -> np.ndarray:
    return np.array(M.subs({sp.Symbol(k, real=True): v for k, v in values.items()}).evalf(), dtype=float)


def test_elementary_factors_move_points_as_their_names_say():
    # worked by hand: a quarter turn about x takes y to z, about y takes z to x, about z takes x to y
    a = sp.Symbol("a")
    assert list(E.trans("x", a) * sp.Matrix([0, 0, 0, 1])) == [a, 0, 0, 1]
    assert E.rot("z", sp.pi / 2) * sp.Matrix([1, 0, 0, 1]) == sp.Matrix([0, 1, 0, 1])
    assert E.rot("x", sp.pi / 2) * sp.Matrix([0, 1, 0, 1]) == sp.Matrix([0, 0, 1, 1])
    assert E.rot("y", sp.pi / 2) * sp.Matrix([0, 0, 1, 1]) == sp.Matrix([1, 0, 0, 1])
    assert E.trans("y", 3) * sp.Matrix([1, 1, 1, 1]) == sp.Matrix([1, 4, 1, 1])
    assert E.trans("z", -2) * sp.Matrix([1, 1, 1, 1]) == sp.Matrix([1, 1, -1, 1])


@pytest.mark.parametrize("axis", ["x", "y", "z"])
def test_rot_is_a_rotation_about_its_axis(axis):
    R = E.rot(axis, t)[:3, :3]
    assert (R.T * R).applyfunc(sp.simplify) == sp.eye(3)
    assert sp.simplify(R.det()) == 1
    e = sp.Matrix([1 if a == axis else 0 for a in "xyz"])
    assert R * e == e  # the axis stays put
    u = sp.Symbol("u", real=True)
    assert (E.rot(axis, t) * E.rot(axis, u) - E.rot(axis, t + u)).applyfunc(sp.simplify) == sp.zeros(4, 4)


@pytest.mark.parametrize(
    ("axis", "num_rot", "num_trans"),
    [("x", tf.trotx, tf.transx), ("y", tf.troty, tf.transy), ("z", tf.trotz, tf.transz)],
)
def test_rot_and_trans_equal_the_numeric_transforms(axis, num_rot, num_trans):
    for angle in random_q(5, seed=21):
        np.testing.assert_allclose(_num(E.rot(axis, t), t=angle), num_rot(angle), atol=1e-14)
        np.testing.assert_allclose(_num(E.trans(axis, t), t=angle), num_trans(angle), atol=1e-14)


def test_skew_is_the_cross_product():
    v, w = sp.Matrix(sp.symbols("v1:4")), sp.Matrix(sp.symbols("w1:4"))
    assert E.skew(v) * w == v.cross(w)
    assert E.skew(v).T == -E.skew(v)


def test_rot_about_a_line_equals_the_numeric_trot_and_fixes_the_line():
    rng = np.random.default_rng(22)
    for _ in range(5):
        a = rng.normal(size=3)
        a /= np.linalg.norm(a)
        point, angle = rng.normal(size=3), rng.uniform(-np.pi, np.pi)
        M = E.rot_about(sp.Matrix(a), sp.cos(t), sp.sin(t), point=sp.Matrix(point))
        num = _num(M, t=angle)
        np.testing.assert_allclose(num, tf.trot(a, angle, point=point), atol=1e-12)
        on_line = np.append(point + 0.7 * a, 1.0)
        np.testing.assert_allclose(num @ on_line, on_line, atol=1e-12)  # points of the line stay put
    # about the frame's own axes (through the origin) it is rot()
    for k, axis in enumerate("xyz"):
        e = sp.eye(3)[:, k]
        assert (E.rot_about(e, sp.cos(t), sp.sin(t)) - E.rot(axis, t)).applyfunc(sp.expand) == sp.zeros(4, 4)


def test_trans_along_a_direction():
    lv = sp.Symbol("l")
    assert E.trans_along([0, 0, 1], lv) == E.trans("z", lv)
    assert list(E.trans_along([3, 4, 0], 2)[:3, 3]) == [6, 8, 0]


def test_bad_axis_and_shapes():
    with pytest.raises(ValueError, match=r"^axis: expected one of 'x', 'y', 'z', got 'w'"):
        E.rot("w", t)
    with pytest.raises(ValueError, match=r"^axis: expected one of 'x', 'y', 'z', got 'X'"):
        E.trans("X", 1)
    with pytest.raises(ValueError, match=r"^v: expected 3 components"):
        E.skew([1, 2])
    with pytest.raises(ValueError, match=r"^point: expected 3 components"):
        E.rot_about([0, 0, 1], 1, 0, point=[1, 2])
