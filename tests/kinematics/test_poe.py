"""ETS and product of exponentials (issue 25, 1f): equal to Porter's fk numerically and, symbol for symbol, to the
local-frame product of lecture 05."""

from __future__ import annotations

import numpy as np
import pytest

from puma_course.kinematics import Porter
from puma_course.kinematics.poe import ets_fk, poe_fk, porter_ets, porter_screws, twist_exp


@pytest.mark.parametrize("lengths", [(1.0, 0.5, 0.3), (0.7, 1.2, 0.4)])
def test_ets_and_poe_equal_porters_fk(lengths):
    arm = Porter(*lengths)
    S, M = porter_screws(*lengths)
    ets = porter_ets(*lengths)
    rng = np.random.default_rng(255)
    Q = rng.uniform(-np.pi, np.pi, (25, 6))
    Q[:, 2] = rng.uniform(0.0, 2.0, 25)
    for q in Q:
        T = arm.fk(q)
        assert np.allclose(poe_fk(S, M, q), T, atol=1e-12) and np.allclose(ets_fk(ets, q), T, atol=1e-12)


def test_poe_equals_the_local_product_symbolically():
    import sympy as sp

    from puma_course.symbolic import porter as P

    l1, l3, l4 = P.SYMBOLS["l1"], P.SYMBOLS["l3"], P.SYMBOLS["l4"]
    q = P.Q

    def exp_sym(w, v, t):
        W = sp.Matrix([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
        T = sp.eye(4)
        if any(w):
            T[:3, :3] = sp.eye(3) + sp.sin(t) * W + (1 - sp.cos(t)) * W * W
            T[:3, 3] = (sp.eye(3) * t + (1 - sp.cos(t)) * W + (t - sp.sin(t)) * W * W) * sp.Matrix(v)
        else:
            T[:3, 3] = sp.Matrix(v) * t
        return T

    # the screw axes of porter_screws, written with symbols: (ω, -ω × r)
    screws = [((0, 0, 1), (0, 0, 0)), ((0, 1, 0), (-l1, 0, 0)), ((0, 0, 0), (1, 0, 0)),
              ((0, 1, 0), (-l1, 0, 0)), ((0, 0, 1), (0, 0, 0)), ((1, 0, 0), (0, l1 - l3, 0))]  # fmt: skip
    T = sp.eye(4)
    for (w, v), t in zip(screws, q, strict=True):
        T = T * exp_sym(w, v, t)
    M = sp.eye(4)
    M[:3, 3] = sp.Matrix([l4, 0, l1 - l3])
    gap = (T * M - P.local_product()).applyfunc(lambda e: sp.simplify(sp.expand_trig(sp.expand(e))))
    assert gap == sp.zeros(4, 4)
    numeric = sp.lambdify([l1, l3, l4], sp.Matrix([list(w) + list(v) for w, v in screws]))
    assert np.allclose(np.array(numeric(1.0, 0.5, 0.3), dtype=float), porter_screws(1.0, 0.5, 0.3)[0])


def test_twist_exp_is_a_turn_about_a_line_and_a_slide():
    # a quarter turn about the vertical line through (1, 0, 0) carries the origin to (1, -1, 0)
    T = twist_exp([0, 0, 1, 0, -1, 0], np.pi / 2)
    assert np.allclose(T @ [0, 0, 0, 1], [1, -1, 0, 1])
    assert np.allclose(twist_exp([0, 0, 0, 0, 1, 0], 0.4)[:3, 3], [0, 0.4, 0])


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: twist_exp([0, 0, 2, 0, 0, 0], 1.0), "S"),
        (lambda: twist_exp([0, 0, 1, 0], 1.0), "S"),
        (lambda: poe_fk(np.zeros((2, 5)), np.eye(4), [0, 0]), "screws"),
        (lambda: poe_fk([[0, 0, 1, 0, 0, 0]], np.ones((4, 4)), [0]), "M"),
        (lambda: poe_fk([[0, 0, 1, 0, 0, 0]], np.eye(4), [0, 1]), "q"),
        (lambda: ets_fk([("Rw", "q0")], [0.0]), r"ets\[0\]"),
        (lambda: ets_fk([("Rz", "q3")], [0.0]), r"ets\[0\]"),
        (lambda: porter_screws(1.0, -0.5, 0.3), "l3"),
    ],
)
def test_bad_input_is_named(call, name):
    with pytest.raises(ValueError, match=name):
        call()
