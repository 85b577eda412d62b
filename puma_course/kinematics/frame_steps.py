"""Craig's frame-assignment rules one frame at a time, and the standard (distal) DH link matrix for comparison.

:func:`frame_steps` places the frames {1} ... {n} of an arm on its joint axes, given as lines in
space at q = 0 (a point and a direction each), one step per frame, and keeps what each step
used: the rule that applied (axis i and axis i+1 *skew*, *intersecting* or *parallel*, or axis i
the *last* one), the common normal to the next axis (its length a_i and twist α_i, from
:func:`~.frame_assignment.common_normal`) and d_i, θ_i read off along axis i (:func:`d_theta`).
Its choices where the rules leave one are those of :func:`~.frame_assignment.dh_from_axes` for a
revolute first joint (X_i as close as possible to X_{i-1}; the normal of parallel axes where it
makes d_i = 0), so both give the same table (the tests check it).

:func:`standard_dh` is the *other* convention's link matrix (Denavit-Hartenberg, Paul; frame {i}
at the far end of link i), Rot(Z, θ_i) Trans(Z, d_i) Trans(X, a_i) Rot(X, α_i), and
:func:`standard_from_modified` rewrites a modified (Craig) table in it: the columns α and a move
up one row, and α_0, a_0 become a fixed base transform.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validate import MAX_MAGNITUDE, as_array, as_choice
from .dh import DHChain, Link, mdh
from .frame_assignment import CommonNormal, common_normal

__all__ = ["FrameStep", "FrameWalk", "d_theta", "frame_steps", "standard_dh", "standard_from_modified", "standard_fk"]

_RIGHT = math.pi / 2


def _unit(v: Any, name: str) -> np.ndarray:
    u = as_array(v, name, (3,), what="a direction (3-vector)")
    n = math.hypot(*u.tolist())
    if n == 0:
        raise ValueError(f"{name}: expected a non-zero direction, got a zero vector")
    return u / n


def _snap(a: float) -> float:
    """An angle within 1e-12 of a multiple of 90° becomes exactly that multiple (as common_normal's twists)."""
    k = round(a / _RIGHT)
    return k * _RIGHT if abs(a - k * _RIGHT) < 1e-12 else a


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
    theta = _snap(math.atan2(float(np.dot(np.cross(xp, xi), z)), float(np.dot(xp, xi))))
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
    elif isinstance(kinds, str) or len(kinds) != n:
        raise ValueError(f"kinds: expected {n} entries each 'R' or 'P', got {kinds!r}")
    kinds = [as_choice(k, "kinds", ("R", "P")) for k in kinds]
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


# ---------------------------------------------------------------------------------- standard DH
def standard_dh(theta: Any, d: Any, a: Any, alpha: Any) -> np.ndarray:
    """The standard (distal) DH link matrix Rot(Z, θ_i) Trans(Z, d_i) Trans(X, a_i) Rot(X, α_i) (not the course's).

    Arguments broadcast as in :func:`~.dh.mdh`; scalars give (4, 4).

        [ cθ    -sθ cα     sθ sα    a cθ ]
        [ sθ     cθ cα    -cθ sα    a sθ ]
        [ 0      sα        cα       d    ]
        [ 0      0         0        1    ]

    >>> np.round(standard_dh(np.pi / 2, 0.5, 1.0, 0.0) @ [0, 0, 0, 1], 12)  # a along the turned x
    array([0. , 1. , 0.5, 1. ])
    """
    th = as_array(theta, "theta", what="an angle in radians (number or array)")
    dd = as_array(d, "d", what="a length (number or array)", max_magnitude=MAX_MAGNITUDE)
    aa = as_array(a, "a", what="a length (number or array)", max_magnitude=MAX_MAGNITUDE)
    al = as_array(alpha, "alpha", what="an angle in radians (number or array)")
    try:
        shape = np.broadcast_shapes(th.shape, dd.shape, aa.shape, al.shape)
    except ValueError:
        raise ValueError(f"theta, d, a, alpha: expected arrays that broadcast together, got shapes {th.shape}, "
                         f"{dd.shape}, {aa.shape}, {al.shape}") from None  # fmt: skip
    ct, st, ca, sa = np.cos(th), np.sin(th), np.cos(al), np.sin(al)
    T = np.zeros(shape + (4, 4))
    T[..., 0, 0], T[..., 0, 1], T[..., 0, 2], T[..., 0, 3] = ct, -st * ca, st * sa, aa * ct
    T[..., 1, 0], T[..., 1, 1], T[..., 1, 2], T[..., 1, 3] = st, ct * ca, -ct * sa, aa * st
    T[..., 2, 1], T[..., 2, 2], T[..., 2, 3] = sa, ca, dd
    T[..., 3, 3] = 1.0
    return T


def standard_from_modified(links: Sequence[Link]) -> tuple[list[tuple[float, float, float, float, str]], np.ndarray]:
    """A modified (Craig) table rewritten for the standard link matrix: rows (θ_i, d_i, a_i, α_i, kind) and a base.

    Row i takes α_i and a_i from row i+1 of the modified table (the last row gets 0, 0), and the
    first row's α_0, a_0 become the fixed base transform Rot(X, α_0) Trans(X, a_0). Then
    ``base @ standard_fk(rows, q)`` is the modified chain's ^0T_n for every q, because
    Rot(X, α) Trans(X, a) = Trans(X, a) Rot(X, α) (a turn about a line and a slide along it commute).

    >>> rows, base = standard_from_modified([Link(0, 0), Link(-np.pi / 2, 0, 0.1), Link(0, 0.4)])
    >>> [(round(float(np.degrees(al))), a) for _, _, a, al, _ in rows]
    [(-90, 0.0), (0, 0.4), (0, 0.0)]
    """
    if isinstance(links, (str, bytes)) or not isinstance(links, Sequence) or len(links) == 0 or \
            not all(isinstance(lk, Link) for lk in links):  # fmt: skip
        raise ValueError(f"links: expected a non-empty list of Link rows, got {links!r}"[:200])
    rows = []
    for i, lk in enumerate(links):
        nxt = links[i + 1] if i + 1 < len(links) else Link(0.0, 0.0)
        rows.append((lk.theta, lk.d, nxt.a_prev, nxt.alpha_prev, lk.kind))
    return rows, mdh(links[0].alpha_prev, links[0].a_prev, 0.0, 0.0)


def standard_fk(rows: Sequence[Sequence[Any]], q: Any) -> np.ndarray:
    """The product of standard link matrices for rows (θ_i, d_i, a_i, α_i, kind) at joint values q (n,): (4, 4).

    A revolute row adds q_i to θ_i, a prismatic one to d_i.

    >>> np.round(standard_fk([(0.0, 0.0, 1.0, 0.0, "R"), (0.0, 0.0, 1.0, 0.0, "R")], [np.pi / 2, 0.0])[:3, 3], 12)
    array([0., 2., 0.])
    """
    if isinstance(rows, (str, bytes)) or not isinstance(rows, Sequence) or len(rows) == 0 or \
            any(not isinstance(r, Sequence) or len(r) != 5 for r in rows):  # fmt: skip
        raise ValueError("rows: expected a non-empty list of rows (theta, d, a, alpha, kind)")
    n = len(rows)
    qq = as_array(q, "q", (n,), what=f"{n} joint values (radians or lengths)", max_magnitude=MAX_MAGNITUDE)
    T = np.eye(4)
    for (th, d, a, al, kind), qi in zip(rows, qq.tolist(), strict=True):
        kind = as_choice(kind, "rows", ("R", "P"))
        T = T @ (standard_dh(th + qi, d, a, al) if kind == "R" else standard_dh(th, d + qi, a, al))
    return T
