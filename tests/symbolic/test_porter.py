"""Second derivation (sympy) of Porter's direct problem against the numeric chain and against each other.

The numeric ``porter.fk`` is itself checked against ``transforms`` in the kinematics tests.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from puma_course import Porter
from puma_course.symbolic import porter as PS


def test_scene_product_equals_local_product_symbolically(local_sc):
    # the scene-frame product, each motion about the CURRENT axis (through the current joint point),
    # built with Rodrigues' formula and left-multiplication, is identically the local product
    M = PS.scene_product("current")
    assert (M - local_sc).applyfunc(PS.reduce_sc) == sp.zeros(4, 4)


def test_local_product_equals_fk_numerically(porter_lengths):
    rng = np.random.default_rng(11)
    L = PS.local_product()
    f = sp.lambdify([*PS.Q, PS.l1, PS.l3, PS.l4], L, "numpy")
    for q in rng.uniform(0, 2 * np.pi, (20, 6)):
        q[2] = abs(q[2])
        np.testing.assert_allclose(
            np.array(f(*q, *porter_lengths), dtype=float), Porter(*porter_lengths).fk(q), atol=1e-13
        )


def test_closed_forms_equal_fk_numerically(porter_lengths):
    # the ci, si closed forms evaluated through sc_values give the numeric pose, column by column
    forms = PS.closed_forms()
    rng = np.random.default_rng(13)
    for q in rng.uniform(-np.pi, np.pi, (5, 6)):
        q[2] = abs(q[2])
        v = PS.sc_values(q, *porter_lengths)
        T = Porter(*porter_lengths).fk(q)
        for j, name in enumerate(("x5", "y5", "z5", "p5")):
            np.testing.assert_allclose([float(e.subs(v)) for e in forms[name]], T[:3, j], atol=1e-13)


def test_literal_reading_of_scene_axes_is_wrong(porter_lengths):
    # reading y1 as the axis of F1 through p1 = p0 (and y2 through p2) moves p2 itself: not the chain
    M = PS.scene_product("literal")
    q = [0.3, 0.2, 1.1, 0.4, 0.5, 0.6]
    num = np.array(M.subs(PS.sc_values(q, *porter_lengths)), dtype=float)
    assert np.abs(num - Porter(*porter_lengths).fk(q)).max() > 0.1


def test_corrected_z5_2_equals_fk(porter_lengths):
    q = [0.3, 0.2, 1.1, 0.4, 0.5, 0.6]
    assert (
        abs(float(PS.corrected_z5_2().subs(PS.sc_values(q, *porter_lengths))) - Porter(*porter_lengths).fk(q)[1, 2])
        < 1e-13
    )


def test_sc_helpers_by_hand():
    a1, a2 = PS.SYMBOLS["alpha1"], PS.SYMBOLS["alpha2"]
    c, s = PS.c, PS.s
    assert PS.to_sc(sp.sin(a1 - a2)) == s[1] * c[2] - c[1] * s[2]
    assert PS.from_sc(c[1] * s[2]) == sp.cos(a1) * sp.sin(a2)
    assert PS.reduce_sc(c[3] ** 2 * s[3] + s[3] ** 3) == s[3]
    assert PS.reduce_sc(c[1] ** 2 - s[1] ** 2) == 1 - 2 * s[1] ** 2  # cos 2α, with c1 eliminated
    assert PS.to_sc(PS.from_sc(c[4] * s[5] - PS.l1 * c[2])) == c[4] * s[5] - PS.l1 * c[2]


def test_bad_reading():
    with pytest.raises(ValueError, match=r"^lines: expected 'current' or 'literal', got 'scene'"):
        PS.scene_product("scene")
