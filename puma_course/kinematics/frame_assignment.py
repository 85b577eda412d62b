"""Craig's frame-assignment rules as code: the common normal of two joint axes, and a DH table from the axes.

Frame {i} is attached to link i with Z_i along joint axis i; X_i lies along the common normal
from axis i to axis i+1 (a_i is its length, α_i the twist from Z_i to Z_{i+1} about X_i) and the
origin of {i} is where that normal meets axis i; d_i is the distance along Z_i from X_{i-1} to X_i
and θ_i the angle from X_{i-1} to X_i about Z_i (Meghdari, "affixing frames to links"; Craig §3.4).
Where the rules leave a choice (intersecting axes: X_i = ±Z_i × Z_{i+1}; parallel axes: where the
normal lies), :func:`dh_from_axes` takes the one that keeps X_i as close as possible to X_{i-1}
(θ offsets of 0 where possible) and puts the normal of parallel axes where it makes d_i = 0.

Decisions on a boundary (do two axes intersect? are they parallel?) use an explicit tolerance and
snap (a = 0 exactly, α a multiple of 90° exactly when within 1e-12 of one).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validate import MAX_MAGNITUDE, as_array, as_tol
from .dh import DHChain, Link

__all__ = ["CommonNormal", "common_normal", "DerivedTable", "dh_from_axes"]


def _unit(v: Any, name: str) -> np.ndarray:
    u = as_array(v, name, (3,), what="a direction (3-vector)")
    n = math.hypot(*u.tolist())
    if n == 0:
        raise ValueError(f"{name}: expected a non-zero direction, got a zero vector")
    return u / n


def _snap_angle(a: float) -> float:
    k = round(a / (math.pi / 2))
    return k * math.pi / 2 if abs(a - k * math.pi / 2) < 1e-12 else a


@dataclass(frozen=True)
class CommonNormal:
    """The common normal of two lines: from ``foot1`` on line 1 to ``foot2`` on line 2.

    ``direction`` is the unit X from line 1 to line 2 (a chosen normal of both when they
    intersect), ``a`` its length, ``alpha`` the twist from line 1's direction to line 2's about X,
    and ``kind`` is ``"skew"``, ``"intersecting"`` or ``"parallel"``.
    """

    foot1: np.ndarray
    foot2: np.ndarray
    direction: np.ndarray
    a: float
    alpha: float
    kind: str


def common_normal(p1: Any, u1: Any, p2: Any, u2: Any, *, hint: Any = None, at: Any = None,
                  tol: float = 1e-9) -> CommonNormal:  # fmt: skip
    """The common normal of the line through ``p1`` along ``u1`` and the line through ``p2`` along ``u2``.

    ``hint`` (a direction) picks the sign of X when the lines intersect (the sign closer to
    ``hint``; default +u1 × u2); ``at`` (a point) picks where the normal lies when the lines are
    parallel (through the point of line 1 nearest ``at``; default p1). ``tol`` (relative to the
    size of the points) decides "intersecting" and "parallel"; a is then snapped to 0.

    Two skew lines, hand-worked: the z axis and the line through (1, 0, 5) along y are 1 apart, at
    -90° about x, and the normal joins them at the height z = 5:

    >>> cn = common_normal([0, 0, 0], [0, 0, 1], [1, 0, 5], [0, 1, 0])
    >>> cn.kind, cn.a, float(np.degrees(cn.alpha)), cn.foot1.tolist(), cn.foot2.tolist()
    ('skew', 1.0, -90.0, [0.0, 0.0, 5.0], [1.0, 0.0, 5.0])
    """
    tol = as_tol(tol, "tol")
    p1 = as_array(p1, "p1", (3,), max_magnitude=MAX_MAGNITUDE)
    p2 = as_array(p2, "p2", (3,), max_magnitude=MAX_MAGNITUDE)
    u1, u2 = _unit(u1, "u1"), _unit(u2, "u2")
    scale = 1.0 + float(np.abs(np.concatenate([p1, p2])).max())
    n = np.cross(u1, u2)
    sin = math.hypot(*n.tolist())
    w = p2 - p1
    if sin <= tol:  # parallel: the normal is free along the lines; put it through the point nearest `at`
        base = p1 if at is None else as_array(at, "at", (3,), max_magnitude=MAX_MAGNITUDE)
        foot1 = p1 + float(np.dot(base - p1, u1)) * u1
        perp = w - float(np.dot(w, u1)) * u1
        a = math.hypot(*perp.tolist())
        if a <= tol * scale:  # the same line: any direction normal to it
            x = _pick_normal(u1, hint)
            return CommonNormal(foot1, foot1.copy(), x, 0.0, 0.0 if np.dot(u1, u2) > 0 else math.pi, "parallel")
        x = perp / a
        foot2 = foot1 + a * x
        alpha = _snap_angle(math.atan2(float(np.dot(n, x)), float(np.dot(u1, u2))))
        return CommonNormal(foot1, foot2, x, a, alpha, "parallel")
    b, d, e = float(np.dot(u1, u2)), float(np.dot(u1, w)), float(np.dot(u2, w))
    denom = 1.0 - b * b
    s, t = (d - b * e) / denom, (b * d - e) / denom
    foot1, foot2 = p1 + s * u1, p2 + t * u2
    v = foot2 - foot1
    a = math.hypot(*v.tolist())
    if a <= tol * scale:  # intersecting: X = ±u1 x u2, the sign nearer the hint
        x = n / sin
        if hint is not None and float(np.dot(x, _unit(hint, "hint"))) < 0:
            x = -x
        kind, a, foot2 = "intersecting", 0.0, foot1.copy()
    else:
        x, kind = v / a, "skew"
    alpha = _snap_angle(math.atan2(float(np.dot(np.cross(u1, u2), x)), b))
    return CommonNormal(foot1, foot2, x, a, alpha, kind)


def _pick_normal(u: np.ndarray, hint: Any) -> np.ndarray:
    """A unit vector normal to u: the hint's component normal to u, else the axis least like u."""
    if hint is not None:
        h = _unit(hint, "hint")
        h = h - float(np.dot(h, u)) * u
        if math.hypot(*h.tolist()) > 1e-9:
            return h / math.hypot(*h.tolist())
    e = np.eye(3)[int(np.argmin(np.abs(u)))]
    e = e - float(np.dot(e, u)) * u
    return e / math.hypot(*e.tolist())


@dataclass(frozen=True)
class DerivedTable:
    """A DH table derived from joint axes: the ``chain`` and the pose ``base`` of its frame {0} in the
    coordinates the axes were given in (so ``base @ chain.frames(q)`` are the frames in those coordinates)."""

    chain: DHChain
    base: np.ndarray


def dh_from_axes(points: Any, directions: Any, kinds: Any = None, *, x0: Any = (1.0, 0.0, 0.0),
                 name: str = "derived") -> DerivedTable:  # fmt: skip
    """A modified-DH table (Craig) derived from the joint axes of an arm in its zero position.

    ``points`` (n, 3) and ``directions`` (n, 3): a point on each joint axis and the axis' direction
    (the sense chosen for Z_i). ``kinds``: "R"/"P" per joint (default all revolute). Frame {0}
    coincides with {1} when q1 = 0 (so α0 = a0 = 0, d1 = 0 for a revolute joint 1) with X_0 along
    ``x0`` projected normal to Z_1; the last frame's origin is where X_{n-1} meets axis n, with
    X_n = X_{n-1}. Returns the chain (its ``table()`` lists α, a, θ offset and d) and the pose of
    frame {0}.

    The PUMA-560's axes at q = 0 give back the lecture's table (the tests derive it):

    >>> t = dh_from_axes([[0, 0, 0], [0, 0, 0], [1.0, 0, 0]], [[0, 0, 1], [0, -1, 0], [0, -1, 0]])
    >>> [(round(float(np.degrees(lk.alpha_prev))), lk.a_prev, lk.d) for lk in t.chain.links]
    [(0, 0.0, 0.0), (90, 0.0, 0.0), (0, 1.0, 0.0)]
    """
    P = as_array(
        points, "points", (None, 3), what="points on the joint axes, shape (n, 3)", max_magnitude=MAX_MAGNITUDE
    )
    U = as_array(directions, "directions", (None, 3), what="joint-axis directions, shape (n, 3)")
    n = len(P)
    if len(U) != n or n < 1:
        raise ValueError(f"points, directions: expected one point and one direction per joint, got {n} and {len(U)}")
    U = np.array([_unit(u, f"directions[{i}]") for i, u in enumerate(U)])
    kinds = ["R"] * n if kinds is None else list(kinds)
    if len(kinds) != n or any(k not in ("R", "P") for k in kinds):
        raise ValueError(f"kinds: expected {n} entries each 'R' or 'P', got {kinds!r}")
    # frame {0} = frame {1} at q1 = 0: origin on axis 1 (nearest the world origin), X0 from x0
    x_prev = _pick_normal(U[0], x0)
    meet = P[0] - float(np.dot(P[0], U[0])) * U[0]  # where X_{i-1} meets axis i (for i = 1: O_0 = O_1)
    links = []
    base = None
    alpha_i, a_i = 0.0, 0.0  # α_{i-1}, a_{i-1} of the row being built
    for i in range(n):
        if i < n - 1:
            cn = common_normal(meet, U[i], P[i + 1], U[i + 1], hint=x_prev, at=meet)
            origin, x, a_next, alpha_next, meet_next = cn.foot1, cn.direction, cn.a, cn.alpha, cn.foot2
        else:
            origin, x = meet, x_prev
            a_next = alpha_next = 0.0
            meet_next = meet
        d = float(np.dot(origin - meet, U[i]))
        theta = _snap_angle(math.atan2(float(np.dot(np.cross(x_prev, x), U[i])), float(np.dot(x_prev, x))))
        if i == 0:  # {0} = {1} at q1 = 0: same origin, same X
            d, theta = (0.0, 0.0) if kinds[0] == "R" else (d, theta)
            base = np.eye(4)
            base[:3, 0], base[:3, 1], base[:3, 2] = x, np.cross(U[0], x), U[0]
            base[:3, 3] = origin if kinds[0] == "R" else meet
        links.append(Link(alpha_i, a_i, d, theta, kinds[i]))
        alpha_i, a_i = alpha_next, a_next
        x_prev, meet = x, meet_next
    assert base is not None
    return DerivedTable(DHChain(links, name=name), base)
