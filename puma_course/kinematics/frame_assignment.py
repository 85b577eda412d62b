"""Craig's frame-assignment rules as code: the common normal of two joint axes, and a DH table from the axes.

Frame {i} is attached to link i with Z_i along joint axis i; X_i lies along the common normal
from axis i to axis i+1 (a_i is its length, α_i the twist from Z_i to Z_{i+1} about X_i) and the
origin of {i} is where that normal meets axis i; d_i is the distance along Z_i from X_{i-1} to X_i
and θ_i the angle from X_{i-1} to X_i about Z_i (Meghdari, "affixing frames to links"; Craig §3.4).
:func:`frame_steps` applies the rules one frame at a time and keeps what each step used (the
rule, the normal, d_i and θ_i read off by :func:`d_theta`), for lectures 02 and 03;
:func:`dh_from_axes` keeps only the table. Where the rules leave a choice (intersecting axes:
X_i = ±Z_i × Z_{i+1}; parallel axes: where the normal lies), they take the one that keeps X_i as
close as possible to X_{i-1} (θ offsets of 0 where possible) and put the normal of parallel axes
where it makes d_i = 0.

Decisions on a boundary (do two axes intersect? are they parallel?) use an explicit tolerance and
snap (a = 0 exactly, α a multiple of 90° exactly when within 1e-12 of one).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validate import MAX_MAGNITUDE, as_array, as_tol
from .dh import DHChain, Link

__all__ = ["CommonNormal", "common_normal", "d_theta", "FrameStep", "FrameWalk", "frame_steps", "DerivedTable",
           "dh_from_axes"]  # fmt: skip


def _unit(v: Any, name: str) -> np.ndarray:
    u = as_array(v, name, (3,), what="a direction (3-vector)")
    n = math.hypot(*u.tolist())
    if n == 0:
        raise ValueError(f"{name}: expected a non-zero direction, got a zero vector")
    return u / n


def _dot3(a: np.ndarray, b: np.ndarray) -> float:
    """a.b of two 3-vectors as one explicit sum (no BLAS call: the same bits on every machine)."""
    (a0, a1, a2), (b0, b1, b2) = a.tolist(), b.tolist()
    return a0 * b0 + a1 * b1 + a2 * b2


def _cross3(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    (a0, a1, a2), (b0, b1, b2) = a.tolist(), b.tolist()
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])


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
    size of the points) decides "intersecting" and "parallel"; a is then snapped to 0. It is at least
    1e-9: for lines δ from parallel the feet carry float64 rounding / δ (2e-7 at δ = 1e-9), so a smaller
    tolerance would answer lines nearer parallel wrongly instead of as parallel (issue 21).

    Two skew lines, hand-worked: the z axis and the line through (1, 0, 5) along y are 1 apart, at
    -90° about x, and the normal joins them at the height z = 5:

    >>> cn = common_normal([0, 0, 0], [0, 0, 1], [1, 0, 5], [0, 1, 0])
    >>> cn.kind, cn.a, float(np.degrees(cn.alpha)), cn.foot1.tolist(), cn.foot2.tolist()
    ('skew', 1.0, -90.0, [0.0, 0.0, 5.0], [1.0, 0.0, 5.0])
    """
    tol = as_tol(tol, "tol", lower=1e-9)
    p1 = as_array(p1, "p1", (3,), max_magnitude=MAX_MAGNITUDE)
    p2 = as_array(p2, "p2", (3,), max_magnitude=MAX_MAGNITUDE)
    u1, u2 = _unit(u1, "u1"), _unit(u2, "u2")
    scale = 1.0 + float(np.abs(np.concatenate([p1, p2])).max())
    n = _cross3(u1, u2)
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
    # Not 1 - (u1.u2)² as the denominator (it cancels to 0 for lines 5e-9 rad from parallel, issue 21):
    # with n = u1 x u2, the feet are at s = w.(u2 x n) / |n|², t = w.(u1 x n) / |n|², and the normal's
    # length is |w.n| / |n| (each product computed from n, known to a relative eps / sin)
    nn = sin * sin
    s, t = _dot3(w, _cross3(u2, n)) / nn, _dot3(w, _cross3(u1, n)) / nn
    foot1, foot2 = p1 + s * u1, p2 + t * u2
    wn = _dot3(w, n) / sin
    a = abs(wn)
    x = n / sin
    if a <= tol * scale:  # intersecting: X = ±u1 x u2, the sign nearer the hint
        if hint is not None and _dot3(x, _unit(hint, "hint")) < 0:
            x = -x
        kind, a, foot2 = "intersecting", 0.0, foot1.copy()
    else:
        x, kind = (x if wn > 0 else -x) + 0.0, "skew"  # + 0.0: no signed zeros in the printed X
    b = _dot3(u1, u2)
    alpha = _snap_angle(math.atan2(_dot3(n, x), b))
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


def d_theta(z: Any, foot_prev: Any, x_prev: Any, origin: Any, x: Any, *, tol: float = 1e-9) -> tuple[float, float]:
    """d_i and θ_i read off along joint axis i (direction ``z``): the distance and the angle from X_{i-1} to X_i.

    ``foot_prev`` is where X_{i-1} (the common normal from axis i-1) meets axis i, ``origin`` the
    origin of frame {i} (where the normal to axis i+1 meets it); both lie on axis i. Then
    d_i = (origin - foot_prev) · Z_i and θ_i = atan2((X_{i-1} × X_i) · Z_i, X_{i-1} · X_i), the
    turn about Z_i that carries X_{i-1} onto X_i. ``x_prev`` and ``x`` must be normal to ``z``
    (within ``tol``), and the two points on one line along ``z``.

    Hand-worked: X_{i-1} = x meets the axis z at height 1, X_i = y leaves it at height 3:

    >>> d, th = d_theta([0, 0, 1], [0, 0, 1], [1, 0, 0], [0, 0, 3], [0, 1, 0])
    >>> d, round(math.degrees(th), 9)
    (2.0, 90.0)
    """
    tol = as_tol(tol, "tol", upper=0.1, lower=1e-12)  # unit vectors carry a few 1e-16 of rounding
    z = _unit(z, "z")
    p0 = as_array(foot_prev, "foot_prev", (3,), max_magnitude=MAX_MAGNITUDE)
    p1 = as_array(origin, "origin", (3,), max_magnitude=MAX_MAGNITUDE)
    xp, xi = _unit(x_prev, "x_prev"), _unit(x, "x")
    for name, v in (("x_prev", xp), ("x", xi)):
        c = float(np.dot(v, z))
        if abs(c) > tol:
            angle = math.degrees(math.acos(max(-1.0, min(1.0, c))))
            raise ValueError(f"{name}: expected a direction normal to z, got one at {angle:.6g}° to it")
    w = p1 - p0
    d = float(np.dot(w, z))
    miss = math.hypot(*(w - d * z).tolist())
    if miss > tol * (1.0 + float(np.abs(np.concatenate([p0, p1])).max())):
        raise ValueError(f"origin: expected a point on the axis through foot_prev along z, got one {miss:.3g} off it")
    theta = _snap_angle(math.atan2(float(np.dot(np.cross(xp, xi), z)), float(np.dot(xp, xi))))
    return d, theta


@dataclass(frozen=True)
class FrameStep:
    """One step of :func:`frame_steps`: frame {i} placed on axis i, and row i of the table.

    ``rule`` says how axis i stands to axis i+1 (``"skew"``, ``"intersecting"``, ``"parallel"``,
    ``"same line"``) or ``"last"``; ``normal`` is the common normal to axis i+1 (None for the last
    axis); ``foot_prev`` is where X_{i-1} meets axis i; ``frame`` the pose of {i} at q = 0 in the
    coordinates the axes were given in. ``alpha_prev, a_prev, theta, d`` is row i of the table
    (θ_i, d_i the constant parts), ``alpha, a`` the twist and length the step found for row i+1.
    """

    i: int
    rule: str
    kind: str
    z: np.ndarray
    origin: np.ndarray
    x: np.ndarray
    frame: np.ndarray
    foot_prev: np.ndarray
    normal: CommonNormal | None
    alpha_prev: float
    a_prev: float
    theta: float
    d: float
    alpha: float
    a: float

    def describe(self, units: str = "", digits: int = 4) -> str:
        """One sentence: which rule placed {i} and what it gave (lengths in ``units``, angles in degrees)."""
        u = f" {units}" if units else ""
        i, j = self.i, self.i + 1
        row = f"d{i} = {self.d:.{digits}g}{u}, θ{i} offset = {math.degrees(self.theta):.4g}°"
        if self.rule == "last":
            return f"{{{i}}}: the last axis; origin where X{i - 1} meets it, X{i} = X{i - 1}; {row}"
        head = {
            "skew": f"axes {i} and {j} are skew: one common normal",
            "intersecting": f"axes {i} and {j} intersect: a{i} = 0, X{i} = ±Z{i} × Z{j}, origin at the crossing",
            "parallel": f"axes {i} and {j} are parallel: the normal through the foot of X{i - 1} (so d{i} = 0)",
            "same line": f"axes {i} and {j} are one line: a{i} = 0, X{i} normal to it",
        }[self.rule]
        return f"{{{i}}}: {head}; a{i} = {self.a:.{digits}g}{u}, α{i} = {math.degrees(self.alpha):.4g}°; {row}"


@dataclass(frozen=True)
class FrameWalk:
    """The result of :func:`frame_steps`: the steps, and the pose ``base`` of frame {0}."""

    steps: tuple[FrameStep, ...]
    base: np.ndarray

    @property
    def links(self) -> list[Link]:
        """The table, one :class:`~.dh.Link` per step."""
        return [Link(s.alpha_prev, s.a_prev, s.d, s.theta, s.kind) for s in self.steps]

    def chain(self, name: str = "derived", units: str = "") -> DHChain:
        """The table as a :class:`~.dh.DHChain` (frames in the coordinates of {0}: ``base @ chain.frames(q)``)."""
        return DHChain(self.links, name=name, units=units)

    @property
    def frames(self) -> np.ndarray:
        """Frames {0} ... {n} at q = 0 in the coordinates the axes were given in: (n + 1, 4, 4)."""
        return np.stack([self.base] + [s.frame for s in self.steps])


def _normal_part(v: np.ndarray, u: np.ndarray, name: str) -> np.ndarray:
    w = v - float(np.dot(v, u)) * u
    n = math.hypot(*w.tolist())
    if n < 1e-9:
        raise ValueError(f"{name}: expected a direction not along the first joint axis, got {v.tolist()}")
    return w / n


def _pose(x: np.ndarray, z: np.ndarray, o: np.ndarray) -> np.ndarray:
    T = np.eye(4)
    T[:3, 0], T[:3, 1], T[:3, 2], T[:3, 3] = x, np.cross(z, x), z, o
    return T


def frame_steps(points: Any, directions: Any, kinds: Sequence[str] | None = None, *,
                x0: Any = (1.0, 0.0, 0.0)) -> FrameWalk:  # fmt: skip
    """Craig's rules applied one frame at a time to joint axes given as lines at q = 0 (Meghdari's rules 1-5).

    ``points`` (n, 3), ``directions`` (n, 3): a point on each joint axis and its direction (the
    positive sense of the joint: Z_i). ``kinds``: "R"/"P" per joint (default all revolute). Step
    i places {i}: the common normal from axis i to axis i+1 gives its origin (where the normal
    meets axis i), X_i (along the normal, towards axis i+1) and a_i, α_i; d_i and θ_i are read
    off along axis i from where X_{i-1} met it (:func:`d_theta`). Frame {0} coincides with {1}
    at q1 = 0 (α_0 = a_0 = 0, and d_1 = θ_1 = 0 for a revolute joint 1), its X along ``x0``
    made normal to Z_1; the last frame's origin is where X_{n-1} meets axis n, with X_n = X_{n-1}.

    A column turning about z and a shoulder axis along y crossing it 0.5 higher, then an elbow
    axis parallel to the shoulder, 0.4 further along x:

    >>> walk = frame_steps([[0, 0, 0], [0, 0, 0.5], [0.4, 0, 0.5]], [[0, 0, 1], [0, 1, 0], [0, 1, 0]])
    >>> [s.rule for s in walk.steps]
    ['intersecting', 'parallel', 'last']
    >>> [(round(math.degrees(s.alpha_prev)), s.a_prev, s.d) for s in walk.steps]
    [(0, 0.0, 0.0), (-90, 0.0, 0.0), (0, 0.4, 0.0)]
    >>> walk.base[:3, 3].tolist()  # {0} = {1} at q1 = 0: on axis 1, at the height of the shoulder
    [0.0, 0.0, 0.5]
    """
    P = as_array(points, "points", (None, 3), what="points on the joint axes, shape (n, 3)",
                 max_magnitude=MAX_MAGNITUDE)  # fmt: skip
    U0 = as_array(directions, "directions", (None, 3), what="joint-axis directions, shape (n, 3)")
    n = len(P)
    if len(U0) != n or n < 1:
        raise ValueError(f"points, directions: expected one point and one direction per joint, got {n} and {len(U0)}")
    U = np.array([_unit(u, f"directions[{i}]") for i, u in enumerate(U0)])
    if kinds is None:
        kinds = ["R"] * n
    elif (
        isinstance(kinds, str)
        or not isinstance(kinds, Sequence | np.ndarray)  # a number or an object has no len() (issue 21)
        or len(kinds) != n
        or any(not isinstance(k, str) or k not in ("R", "P") for k in kinds)
    ):
        raise ValueError(f"kinds: expected {n} entries each 'R' or 'P', got {kinds!r}"[:200])
    kinds = list(kinds)
    x_prev = _normal_part(_unit(x0, "x0"), U[0], "x0")
    foot = P[0] - float(np.dot(P[0], U[0])) * U[0]  # where X_{i-1} meets axis i; for i = 1 the foot from the origin
    steps: list[FrameStep] = []
    base = np.eye(4)
    alpha_prev = a_prev = 0.0
    for i in range(n):
        if i < n - 1:
            found = common_normal(foot, U[i], P[i + 1], U[i + 1], hint=x_prev, at=foot)
            origin, x, alpha, a, foot_next = found.foot1, found.direction, found.alpha, found.a, found.foot2
            rule = "same line" if found.kind == "parallel" and found.a == 0.0 else found.kind
            cn: CommonNormal | None = found
        else:
            cn, origin, x, alpha, a, foot_next, rule = None, foot, x_prev, 0.0, 0.0, foot, "last"
        d, theta = d_theta(U[i], foot, x_prev, origin, x)
        if i == 0:  # {0} = {1} at q1 = 0: the same X; for a revolute joint also the same origin
            theta = 0.0
            if kinds[0] == "R":
                d = 0.0
            base = _pose(x, U[0], origin if kinds[0] == "R" else foot)
        steps.append(FrameStep(i + 1, rule, kinds[i], U[i].copy(), origin.copy(), x.copy(), _pose(x, U[i], origin),
                               foot.copy(), cn, alpha_prev, a_prev, theta, d, alpha, a))  # fmt: skip
        alpha_prev, a_prev, x_prev, foot = alpha, a, x, foot_next
    return FrameWalk(tuple(steps), base)


def dh_from_axes(points: Any, directions: Any, kinds: Any = None, *, x0: Any = (1.0, 0.0, 0.0),
                 name: str = "derived") -> DerivedTable:  # fmt: skip
    """A modified-DH table (Craig) derived from the joint axes of an arm in its zero position.

    ``points`` (n, 3) and ``directions`` (n, 3): a point on each joint axis and the axis' direction
    (the sense chosen for Z_i). ``kinds``: "R"/"P" per joint (default all revolute). Frame {0}
    coincides with {1} when q1 = 0 (so α0 = a0 = 0, θ1 = 0, and d1 = 0 for a revolute joint 1) with
    X_0 along ``x0`` projected normal to Z_1; the last frame's origin is where X_{n-1} meets axis n,
    with X_n = X_{n-1}. Returns the chain (its ``table()`` lists α, a, θ offset and d) and the pose
    of frame {0}: the table of :func:`frame_steps`, which also keeps every step.

    The PUMA-560's axes at q = 0 give back the lecture's table (the tests derive it):

    >>> t = dh_from_axes([[0, 0, 0], [0, 0, 0], [1.0, 0, 0]], [[0, 0, 1], [0, -1, 0], [0, -1, 0]])
    >>> [(round(float(np.degrees(lk.alpha_prev))), lk.a_prev, lk.d) for lk in t.chain.links]
    [(0, 0.0, 0.0), (90, 0.0, 0.0), (0, 1.0, 0.0)]
    """
    walk = frame_steps(points, directions, kinds, x0=x0)
    return DerivedTable(walk.chain(name), walk.base)
