"""Craig's modified-DH link matrix and chains against independent truths."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from puma_course import transforms as tf
from puma_course.kinematics.dh import DHChain, Link, exact_cos_sin, mdh

angle = st.floats(-7, 7, allow_nan=False)
length = st.floats(-2, 2, allow_nan=False)


@settings(derandomize=True, max_examples=300, deadline=None)
@given(alpha=angle, a=length, theta=angle, d=length)
def test_mdh_equals_product_of_four_elementary_transforms(alpha, a, theta, d):
    expected = tf.trotx(alpha) @ tf.transx(a) @ tf.trotz(theta) @ tf.transz(d)
    assert np.allclose(mdh(alpha, a, theta, d), expected, atol=1e-12)


def test_mdh_hand_worked():
    # α = -90°: Rot(X, -90°) takes e_z to (0, 1, 0), so Z_i points along +Y_{i-1}
    # and d = 2 along it puts the origin of {i} at y = 2.
    T = mdh(-math.pi / 2, 0.0, 0.0, 2.0)
    assert np.allclose(T[:3, 3], [0, 2, 0])
    assert np.allclose(T[:3, 2], [0, 1, 0])
    # Pure a: a translation along x only.
    assert np.allclose(mdh(0, 1.5, 0, 0), tf.transx(1.5))


def test_mdh_broadcasts():
    th = np.linspace(0, 1, 7)
    T = mdh(0.3, 1.0, th, 0.2)
    assert T.shape == (7, 4, 4)
    for i, t in enumerate(th):
        assert np.allclose(T[i], mdh(0.3, 1.0, t, 0.2))


def _random_chain(rng: np.random.Generator, n: int = 5) -> DHChain:
    kinds = ["R", "P", "R", "R", "P", "R"][:n]
    links = [
        Link(rng.uniform(-3, 3), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), kind=k) for k in kinds
    ]
    return DHChain(links, name="random")


def test_fk_equals_product_of_link_matrices_built_independently():
    rng = np.random.default_rng(7)
    chain = _random_chain(rng)
    q = rng.uniform(-3, 3, (20, chain.n))
    for row in q:
        T = np.eye(4)
        for lk, qi in zip(chain.links, row, strict=True):
            theta = lk.theta + qi if lk.kind == "R" else lk.theta
            d = lk.d + qi if lk.kind == "P" else lk.d
            T = T @ tf.trotx(lk.alpha_prev) @ tf.transx(lk.a_prev) @ tf.trotz(theta) @ tf.transz(d)
        assert np.allclose(chain.fk(row), T, atol=1e-12)


def test_batch_fk_equals_each_row_and_frames_end_at_fk():
    rng = np.random.default_rng(8)
    chain = _random_chain(rng, 6)
    q = rng.uniform(-3, 3, (64, chain.n))
    batch = chain.fk(q)
    assert batch.shape == (64, 4, 4)
    rows = np.stack([chain.fk(r) for r in q])
    assert np.allclose(batch, rows, atol=1e-13)
    F = chain.frames(q)
    assert F.shape == (64, chain.n + 1, 4, 4)
    assert np.allclose(F[:, 0], np.eye(4))
    assert np.allclose(F[:, -1], batch)
    A = chain.link_matrices(q)
    assert np.allclose(F[:, 3], A[:, 0] @ A[:, 1] @ A[:, 2])


def test_table_and_repr():
    chain = DHChain([Link(0, 0, 0), Link(-math.pi / 2, 0.5, 0.1, kind="P")], name="two", units="m")
    html = chain._repr_html_()
    assert "<table" in html and "-90" in html and "d2" in html
    assert "two" in repr(chain)


@pytest.mark.parametrize(
    "call, fragment",
    [
        (lambda c: c.fk([0.0, 0.0]), "q: expected joint values of shape (3,)"),
        (lambda c: c.fk(np.zeros((4, 2))), "got an array of shape (4, 2)"),
        (lambda c: c.fk([0.0, float("nan"), 0.0]), "q: expected finite"),
        (lambda c: c.fk(["a", 0, 0]), "of real numbers, got list ['a', 0, 0]"),
        (lambda c: c.fk([0.0, 1j, 0.0]), "of real numbers, got complex numbers"),
        (lambda c: c.fk([0.0, None, 0.0]), "got None"),
        (lambda c: mdh(0, 0, "x", 0), "theta"),
        (lambda c: mdh(np.zeros(2), 0, np.zeros(3), 0), "broadcast"),
        (lambda c: Link(0, 0, kind="X"), "kind"),
        (lambda c: c.q("nope"), "name: expected one of"),
        (lambda c: c.q(np.array([])), "name: expected one of"),  # was a TypeError (unhashable array)
        (lambda c: Link(0, 1e200, 0), "a_prev: expected values of size at most"),
        (lambda c: c.ik(np.eye(4)), "NotImplementedError"),
        (lambda c: DHChain([]), "links: expected a non-empty list of Link"),
        (lambda c: DHChain([Link(0, 0, 0), (0, 1, 0, 0)]), "links[1]: expected a Link"),  # was AttributeError
        (lambda c: Link(float("nan"), 0, 0), "alpha_prev: expected finite"),
        (lambda c: DHChain([Link(0, 0, 0)], configurations={"up": [0.0, 1.0]}), "configurations['up']"),
        (lambda c: c.frames(np.zeros((2, 4))), "got an array of shape (2, 4)"),
        (lambda c: c.link_matrices(float("inf")), "q: expected"),
    ],
)
def test_bad_input(call, fragment):
    chain = DHChain([Link(0, 0, 0), Link(0, 1, 0), Link(0, 1, 0)])
    if fragment == "NotImplementedError":  # a general chain has no closed-form ik: said plainly
        with pytest.raises(NotImplementedError, match="no closed-form inverse kinematics"):
            call(chain)
        return
    with pytest.raises(ValueError) as err:
        call(chain)
    assert fragment in str(err.value)


def test_twists_at_multiples_of_90_degrees_are_exact():
    # cos(π/2) is 6e-17 in floats; the chain snaps constant twists so zeros stay zeros
    assert [exact_cos_sin(k * math.pi / 2) for k in range(-2, 3)] == [
        (-1.0, 0.0),
        (0.0, -1.0),
        (1.0, 0.0),
        (0.0, 1.0),
        (-1.0, 0.0),
    ]
    assert exact_cos_sin(0.3) == (math.cos(0.3), math.sin(0.3))
    chain = DHChain([Link(-math.pi / 2, 0.0, 0.0), Link(math.pi / 2, 0.0, 0.0)])
    T = chain.fk([0.0, 0.0])
    assert np.array_equal(T, np.eye(4))  # Rot(X, -90°) Rot(X, 90°) = I exactly, by design


def test_single_pose_path_equals_batch_path_bit_for_bit_structure():
    # one pose runs in plain floats, a batch in numpy: the same kernel, so the same numbers
    rng = np.random.default_rng(9)
    chain = _random_chain(rng, 6)
    q = rng.uniform(-3, 3, (30, chain.n))
    assert np.allclose(np.stack([chain.fk(r) for r in q]), chain.fk(q), atol=1e-15, rtol=0)
    assert np.allclose(np.stack([chain.frames(r) for r in q]), chain.frames(q), atol=1e-15, rtol=0)
