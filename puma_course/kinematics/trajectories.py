"""Cartesian paths of the end effector and the joint paths that follow them, for any robot (lecture 10).

A path is a sequence of poses (n, 4, 4) with a fixed orientation: a straight line
(:func:`line_path`) or a circle (:func:`circle_path`), sampled evenly or along a
:func:`time_scaling` (a quintic s(t) starts and ends at rest). An arm with several inverse-kinematics
solutions per pose must pick one at every step: :func:`follow` picks the solution nearest the
previous configuration (wrapped joint distance, :func:`~.ik.joint_distance`), :func:`naive` the first
valid solution the solver lists. Both take any :class:`~.robot.Robot`: they call its batched
``ik_batch`` once for the whole path and use its ``revolute`` mask.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._validate import MAX_MAGNITUDE, as_array, as_count, as_positive, as_rotation, as_transform
from .ik import SingularityWarning, joint_distance, nearest_index
from .robot import Robot

__all__ = [
    "line_path",
    "circle_path",
    "JointPath",
    "follow",
    "naive",
    "unwrap",
    "TimeScaling",
    "time_scaling",
    "joint_velocities",
]


def _poses(R: np.ndarray, P: np.ndarray) -> np.ndarray:
    n = P.shape[0]
    T = np.zeros((n, 4, 4))
    T[:, :3, :3] = R
    T[:, :3, 3] = P
    T[:, 3, 3] = 1.0
    return T


def _path_parameter(n: Any, s: Any) -> np.ndarray:
    """The path parameter: n evenly spaced values in [0, 1], or the given ``s`` (a time scaling's)."""
    if s is None:
        n = as_count(n, "n", minimum=2)
        return np.linspace(0.0, 1.0, n)
    sv = as_array(s, "s", (None,), what="path parameters of shape (n,) in [0, 1] (e.g. a time scaling's s)")
    if len(sv) < 2 or sv.min() < -1e-12 or sv.max() > 1 + 1e-12:
        raise ValueError(
            f"s: expected at least 2 path parameters in [0, 1], got {len(sv)} in [{sv.min():g}, {sv.max():g}]"
        )
    return np.clip(sv, 0.0, 1.0)


def line_path(T0: Any, T1: Any, n: int | None = None, *, s: Any = None) -> np.ndarray:
    """n poses (n, 4, 4) from T0's position to T1's on a straight line, keeping T0's orientation.

    The points are p(s) = (1 - s) p0 + s p1 for n evenly spaced s in [0, 1], or for the values ``s``
    given (a :func:`time_scaling`'s s, to move along the line with that timing).

    ``T1`` may be a pose (4, 4) (its rotation is ignored: the orientation stays
    fixed) or a point (3,). Positions p(s) = (1 - s) p0 + s p1, s = 0..1.

    >>> P = line_path(np.eye(4), [1.0, 2.0, 0.0], 3)[:, :3, 3]
    >>> P
    array([[0. , 0. , 0. ],
           [0.5, 1. , 0. ],
           [1. , 2. , 0. ]])
    """
    T0 = as_transform(T0, "T0")
    try:
        shape = np.shape(T1)
    except ValueError:  # ragged nested lists
        shape = None
    if shape == (4, 4):
        p1 = as_transform(T1, "T1")[:3, 3]
    else:
        p1 = as_array(T1, "T1", (3,), what="a pose (4, 4) or a point (3,)", max_magnitude=MAX_MAGNITUDE)
    sv = _path_parameter(n, s)[:, None]
    return _poses(T0[:3, :3], (1.0 - sv) * T0[:3, 3] + sv * p1)


def circle_path(
    center: Any, radius: float, normal: Any, R: Any, n: int | None = None, start: Any | None = None, *, s: Any = None
) -> np.ndarray:
    """n poses (n, 4, 4) around a full circle (closed: the last equals the first), orientation R fixed.

    The angle along the circle is 2π s, for n evenly spaced s in [0, 1] or the values ``s`` given.

    The circle lies in the plane through ``center`` perpendicular to ``normal``
    and runs counter-clockwise seen from the tip of ``normal``, starting in the
    direction ``start`` (projected into the plane; default: the plane direction
    closest to x, or to y if normal ∥ x). p(t) = c + r (cos t e1 + sin t e2).

    >>> P = circle_path([0, 0, 1], 0.5, [0, 0, 1], np.eye(3), 5)[:, :3, 3]
    >>> np.round(P, 6) + 0.0
    array([[ 0.5,  0. ,  1. ],
           [ 0. ,  0.5,  1. ],
           [-0.5,  0. ,  1. ],
           [ 0. , -0.5,  1. ],
           [ 0.5,  0. ,  1. ]])
    """
    c = as_array(center, "center", (3,), max_magnitude=MAX_MAGNITUDE)
    r = as_positive(radius, "radius")
    nv = as_array(normal, "normal", (3,))
    norm = math.hypot(*nv.tolist())
    if norm == 0:
        raise ValueError("normal: expected a non-zero vector perpendicular to the circle's plane, got zeros")
    nv = nv / norm
    Rm = as_rotation(R, "R")
    sv = _path_parameter(n, s)
    if start is None:
        guess = np.array([1.0, 0.0, 0.0]) if abs(nv[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    else:
        guess = as_array(start, "start", (3,))
    e1 = guess - float(np.sum(guess * nv)) * nv
    if math.hypot(*e1.tolist()) < 1e-12 * max(1.0, math.hypot(*guess.tolist())):
        raise ValueError("start: expected a direction not parallel to normal, got a parallel one")
    e1 /= math.hypot(*e1.tolist())
    e2 = np.cross(nv, e1)
    t = 2 * np.pi * sv[:, None]
    return _poses(Rm, c + r * (np.cos(t) * e1 + np.sin(t) * e2))


def unwrap(q: Any, revolute: Any = None) -> np.ndarray:
    """A joint path (n, m) with the 2π jumps of its angle columns removed (for plotting).

    ``revolute`` (a boolean mask, default all True; pass ``robot.revolute``) says which columns
    are angles.

    >>> unwrap([[3.0], [-3.0]])[:, 0].round(4)
    array([3.    , 3.2832])
    """
    q = as_array(q, "q", (None, None), what="a joint path of shape (n, m)")
    rev = np.ones(q.shape[1], dtype=bool) if revolute is None else _mask(revolute, q.shape[1])
    out = q.copy()
    out[:, rev] = np.unwrap(q[:, rev], axis=0)
    return out


def _mask(revolute: Any, m: int) -> np.ndarray:
    from .._validate import as_mask

    return as_mask(revolute, "revolute", m)


@dataclass
class JointPath:
    """A joint path along a Cartesian path.

    ``q`` (n, m) the chosen configuration at every pose; ``choice`` (n,) which branch (column of the
    robot's ``ik_batch``) was chosen and ``labels`` its name; ``step`` (n-1,) wrapped distance
    between successive configurations (``step[0]`` from the first pose's choice to the second's);
    ``start_jump`` the distance from the starting configuration ``q0`` to ``q[0]`` (0 for
    :func:`naive` called without q0).

    Usually made by :func:`follow` or :func:`naive`; by hand:

    >>> jp = JointPath(q=np.array([[0.0, 0.0], [0.1, 0.0]]), choice=np.array([0, 0]), step=np.array([0.1]),
    ...                start_jump=0.0)
    >>> jp.max_step
    0.1
    """

    q: np.ndarray
    choice: np.ndarray
    step: np.ndarray
    start_jump: float
    labels: tuple[str, ...] = field(default=())

    @property
    def max_step(self) -> float:
        """The largest jump between successive poses (radians for angles, lengths for prismatic joints)."""
        return float(self.step.max()) if len(self.step) else 0.0


def _solve_path(robot: Robot, path_Ts: Any) -> tuple[np.ndarray, np.ndarray, tuple[str, ...]]:
    Ts, sol = _solve_batch(robot, path_Ts)
    return sol.q, sol.valid, sol.labels


def _solve_batch(robot: Robot, path_Ts: Any) -> tuple[np.ndarray, Any]:
    if not isinstance(robot, Robot):
        raise ValueError(
            f"robot: expected a robot of the course (Puma560(), Porter(), ...), got {type(robot).__name__}"
        )
    Ts = as_transform(path_Ts, "path_Ts", batch=True)
    if Ts.ndim == 2:
        Ts = Ts[None]
    if Ts.shape[0] == 0:
        raise ValueError("path_Ts: expected at least one pose, got an empty path")
    sol = robot.ik_batch(Ts)
    bad = ~sol.valid.any(axis=1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise ValueError(
            f"path_Ts: {robot.name} cannot reach pose {i} of the path (position {np.round(Ts[i, :3, 3], 4).tolist()}): "
            f"{sol.reason[i] or 'no valid branch'}"
        )
    return Ts, sol


def follow(robot: Robot, path_Ts: Any, q0: Any) -> JointPath:
    """At each pose, the solution nearest the previous configuration (starting from ``q0``).

    The robot's ``ik_batch`` gives every branch for all poses at once; the choice itself is a
    short loop over the path, since each step depends on the one before. At a singular sample
    (a joint left free) the pose is solved again with the previous configuration as ``near``, so
    the free joint keeps its value instead of jumping to the solver's default (the robot's ``ik``,
    which searches a singular family for the member nearest to ``near``).

    >>> from puma_course.kinematics import Puma560
    >>> arm = Puma560()
    >>> q0 = arm.q("qn")
    >>> path = line_path(arm.fk(q0), arm.fk(q0)[:3, 3] + [0.0, 0.1, 0.0], 20)
    >>> jp = follow(arm, path, q0)
    >>> jp.q.shape, jp.start_jump < 1e-9, jp.max_step < 0.05, jp.labels[0]
    ((20, 6), True, True, 'left/up/noflip')
    """
    Ts, sol = _solve_batch(robot, path_Ts)
    Q, valid, labels = sol.q.copy(), sol.valid.copy(), sol.labels
    m = Q.shape[-1]
    prev = as_array(q0, "q0", (m,), what=f"a starting configuration of shape ({m},)")
    start = prev
    rev = robot.revolute
    n = Q.shape[0]
    flagged: list[bool] = (np.asarray(sol.flags).reshape(n, -1) != 0).any(axis=1).tolist()
    choice = np.empty(n, dtype=int)
    for i in range(n):
        if flagged[i]:  # the previous configuration decides the free joints (issue 21: no jump at a singular sample)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", SingularityWarning)  # the batch solve did not warn either
                again = robot.ik(Ts[i], near=prev)
            if len(again) and again.labels[0] in labels:  # sorted nearest-first: its first row is the one
                j = labels.index(again.labels[0])
                Q[i, j], valid[i, j] = again[0], True
        j = int(nearest_index(Q[i], prev, rev, valid[i]))
        choice[i] = j
        prev = Q[i, j]
    q = Q[np.arange(n), choice]
    return JointPath(
        q=q,
        choice=choice,
        step=joint_distance(q[1:], q[:-1], rev),
        start_jump=float(joint_distance(q[0], start, rev)),
        labels=tuple(labels[j] for j in choice),
    )


def naive(robot: Robot, path_Ts: Any, q0: Any = None) -> JointPath:
    """At each pose, simply the first valid solution the solver lists (to compare with :func:`follow`).

    ``q0``, if given, is where the arm starts: ``start_jump`` is then the jump from it to the
    first chosen configuration (else 0).

    >>> from puma_course.kinematics import Puma560
    >>> arm = Puma560()
    >>> path = line_path(arm.fk(arm.q("qn")), [0.5, 0.2, 0.3], 10)
    >>> naive(arm, path).choice.tolist() == [0] * 10  # always branch left/up/noflip
    True
    """
    Q, valid, labels = _solve_path(robot, path_Ts)
    choice = np.argmax(valid, axis=1)
    q = Q[np.arange(Q.shape[0]), choice]
    rev = robot.revolute
    start = 0.0
    if q0 is not None:
        m = Q.shape[-1]
        q0 = as_array(q0, "q0", (m,), what=f"a starting configuration of shape ({m},)")
        start = float(joint_distance(q[0], q0, rev))
    return JointPath(q=q, choice=choice, step=joint_distance(q[1:], q[:-1], rev), start_jump=start,
                     labels=tuple(labels[j] for j in choice))  # fmt: skip


@dataclass(frozen=True)
class TimeScaling:
    """A time law along a path: at the times ``t`` (n,), the path parameter ``s`` in [0, 1] and its
    first and second time derivatives ``sdot`` (1/s) and ``sddot`` (1/s²)."""

    t: np.ndarray
    s: np.ndarray
    sdot: np.ndarray
    sddot: np.ndarray


def time_scaling(duration: float, n: int, kind: str = "quintic") -> TimeScaling:
    """The path parameter s(t) for a motion of ``duration`` seconds, sampled at n times.

    ``"quintic"``: s = 10 τ³ - 15 τ⁴ + 6 τ⁵ with τ = t / duration, the lowest-degree polynomial with
    s, ṡ and s̈ all zero at the start and at s = 1 with ṡ = s̈ = 0 at the end (the arm starts and
    stops at rest, with no jump in acceleration); its peak speed is ṡ(duration / 2) = 15 / (8
    duration). ``"linear"``: s = τ, a constant speed with jumps in velocity at both ends.

    >>> ts = time_scaling(2.0, 5)
    >>> ts.t.tolist(), ts.s.tolist()
    ([0.0, 0.5, 1.0, 1.5, 2.0], [0.0, 0.103515625, 0.5, 0.896484375, 1.0])
    >>> float(ts.sdot[2])  # 15 / (8 * 2.0)
    0.9375
    """
    from .._validate import as_choice

    T = as_positive(duration, "duration")
    if not 1e-50 <= T <= 1e50:  # ṡ ~ 1 / T and s̈ ~ 1 / T² must stay finite (issue 21: 1e-200 gave NaN and inf)
        raise ValueError(f"duration: expected a duration from 1e-50 to 1e50 seconds, got {T:g}")
    n = as_count(n, "n", minimum=2)
    kind = as_choice(kind, "kind", ("quintic", "linear"))
    t = np.linspace(0.0, T, n)
    tau = t / T
    if kind == "linear":
        return TimeScaling(t, tau, np.full(n, 1.0 / T), np.zeros(n))
    s = tau**3 * (10.0 - 15.0 * tau + 6.0 * tau**2)
    sdot = 30.0 * tau**2 * (1.0 - tau) ** 2 / T
    sddot = 60.0 * tau * (1.0 - tau) * (1.0 - 2.0 * tau) / T**2
    return TimeScaling(t, s, sdot, sddot)


def joint_velocities(q: Any, t: Any, revolute: Any = None) -> np.ndarray:
    """Joint speeds (n, m) along a joint path q (n, m) sampled at the times t (n,): central differences.

    Angle columns (``revolute``, default all) are unwrapped first, so a step from 179° to -179° is
    2°, not 358°. Units: radians (or lengths) per second.

    >>> t = np.linspace(0.0, 1.0, 5)
    >>> q = np.column_stack([3.0 + 0.5 * t, 2.0 * t])  # crosses +π at t = 0.28
    >>> np.round(joint_velocities(q, t), 12).tolist()[0]
    [0.5, 2.0]
    """
    qq = unwrap(q, revolute)
    tt = as_array(t, "t", (qq.shape[0],), what=f"times of shape ({qq.shape[0]},), one per row of q")
    if np.any(np.diff(tt) <= 0):
        raise ValueError("t: expected strictly increasing times, got a step that is zero or negative")
    return np.gradient(qq, tt, axis=0)
