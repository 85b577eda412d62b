"""References of exercises 5 to 7: Porter's chain, its tool frame, Ver.1 and Ver.2."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from puma_course import transforms
from puma_course.kinematics import MountedFk, Porter
from puma_course.kinematics.porter import angle as porter_angle

from .._formulas import porter_wrist_point
from ._common import _quiet, _set_expected, _table_expected, pose, tz


# ---------------------------------------------------------------- exercises 5 to 7: Porter's chain
def porter_fk(q: Any, l1: float, l3: float, l4: float) -> np.ndarray:
    """F05 of Porter's chain."""
    return Porter(l1, l3, l4).fk(q)


def porter_points(q: Any, l1: float, l3: float, l4: float) -> np.ndarray:
    """The joint points p0 ... p5 of Porter's chain: shape (6, 3)."""
    return Porter(l1, l3, l4).points(q)


def porter_pen_points(q: Any, l1: float, l3: float, l4: float, t: float, hand: str = "pitch") -> np.ndarray:
    """The joint points p0 ... p5 and the tip p6 = p5 + t x5 of a pen along the hand's x axis (ex05 q2): (7, 3).

    ``hand="pitch"`` is ex05 q1's pitching hand; ``hand="lecture"`` lecture 05's chain (the mistake)."""
    F = porter_pitch_fk(q, l1, l3, l4) if hand == "pitch" else porter_fk(q, l1, l3, l4)
    return np.vstack([porter_points(q, l1, l3, l4), F[:3, 3] + t * F[:3, 0]])


def _porter_factors(q: Any, l1: float, l3: float, l4: float, printed: bool = False) -> list[np.ndarray]:
    a1, a2, q2, a3, a4, a5 = (float(v) for v in np.asarray(q, dtype=float))
    T = transforms
    slide = [] if printed else [T.transx(q2)]
    return [T.trotz(a1), tz(l1), T.troty(a2), *slide, T.troty(a3), tz(-l3), T.trotz(a4), T.transx(l4), T.trotx(a5)]


def porter_printed_fk(q: Any, l1: float, l3: float, l4: float) -> np.ndarray:
    """Porter's local product as printed, without Tx(q2) (lecture 05, erratum 1)."""
    return transforms.compose_moving(*_porter_factors(q, l1, l3, l4, printed=True))


def porter_reversed_fk(q: Any, l1: float, l3: float, l4: float) -> np.ndarray:
    """The nine local factors multiplied in reverse order (the fixed-axes reading of the local list)."""
    return transforms.compose_fixed(*_porter_factors(q, l1, l3, l4))


#: Porter's tool frame {T} of ex05: z_T along x5 (the axis of α5), x_T = y5, y_T = z5.
PORTER_TOOL = pose(np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]), np.zeros(3))


def porter_tool_fk(Q: Any, l1: float, l3: float, l4: float) -> np.ndarray:
    """F05 followed by the tool frame's axes: F05 P."""
    return Porter(l1, l3, l4).fk(np.asarray(Q, dtype=float)) @ PORTER_TOOL


def porter_tool_expected(l1: float, l3: float, l4: float) -> dict[str, Any]:
    """What the table judge needs for Porter's chain (ex05)."""
    return _table_expected(
        lambda Q: porter_tool_fk(Q, l1, l3, l4), Porter().revolute, l1 + l3 + l4 + 2.0, l1, l3, l4, stroke=(0.2, 2.0)
    )


def porter_configs(rng: np.random.Generator, n: int) -> list[tuple[np.ndarray, float, float, float]]:
    """Configurations in general position (|cos α4| >= 0.3, q2 >= 0.3, wrist point off the z0 axis)."""
    out: list[tuple[np.ndarray, float, float, float]] = []
    while len(out) < n:
        q = rng.uniform(-np.pi, np.pi, 6)
        q[2] = rng.uniform(0.3, 2.0)
        l1, l3, l4 = (float(x) for x in rng.uniform(0.3, 1.5, 3))
        p4 = Porter(l1, l3, l4).points(q)[4]
        if abs(np.cos(q[4])) >= 0.3 and np.hypot(p4[0], p4[1]) > 0.2:
            out.append((q, l1, l3, l4))
    return out


def porter_poses(rng: np.random.Generator, n: int, near_singular: bool = False) -> list[tuple[Any, ...]]:
    """Cases (T, l1, l3, l4); with ``near_singular`` the first ones sit 1e-4 from c4 = 0, at c1 = 0, q2 = 1e-3."""
    cases = porter_configs(rng, n)
    if near_singular:
        for k, (col, value) in enumerate([(4, np.pi / 2 - 1e-4), (0, np.pi / 2), (2, 1e-3)][:n]):
            cases[k][0][col] = value
    return [(Porter(l1, l3, l4).fk(q), l1, l3, l4) for q, l1, l3, l4 in cases]


def porter_ik_expected(T: Any, l1: float, l3: float, l4: float) -> dict[str, Any]:
    """Every configuration reaching T (Ver.1) for the set judge; the stroke (column 2) must be >= 0."""
    return _set_expected(Porter(l1, l3, l4), T, stroke=2)


def porter_tool_ik_expected(T_tool: Any, l1: float, l3: float, l4: float, E: Any) -> dict[str, Any]:
    """Every configuration putting the tool (F05 E) at T_tool; rows reaching T_tool E or E^-1 T_tool composed E
    the wrong way, rows reaching T_tool E^-1 forgot the tool (F5 itself is at T_tool)."""
    T_tool, E = np.asarray(T_tool, dtype=float), np.asarray(E, dtype=float)
    robot, Ei = Porter(l1, l3, l4), transforms.inverse_transform(E)
    wrong = "you composed the tool on the wrong side: the tool frame is F05 E, so F05 = T_tool E⁻¹"
    alts = [
        ("order", wrong, T_tool @ E @ E),
        ("order", wrong, Ei @ T_tool @ E),
        ("tool_frame", "your configurations put F5, not the tool frame, at the pose asked for", T_tool @ E),
    ]
    out = _set_expected(robot, T_tool @ Ei, fk=MountedFk(robot.fk, tool=E), stroke=2, alternatives=alts)
    out["T"] = T_tool
    return out


def signed_angle(v: Any, w: Any, axis: Any) -> float:
    """Porter's angle(v, w, axis), signed about the unit axis, in (-π, π]."""
    return float(porter_angle(v, w, axis))


def signed_angles_matter(q: Any) -> bool:
    """True when one of the angles Porter's step 4 measures (α2 + π/2, α3 + π/2, α5) is negative in ``q``.

    There the printed, unsigned angle() gives another configuration: a case that separates the two.
    """
    q = np.asarray(q, dtype=float)
    return bool(min(transforms.wrap_angle(q[1] + np.pi / 2), transforms.wrap_angle(q[3] + np.pi / 2), q[5]) < -0.05)


def porter_parallel_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """Cases (T, l1, l3, l4) with x5 normal to the arm plane (α4 = ±π/2) and p4 off the z0 axis, each one
    where Porter's configuration has a negative signed angle (so the printed unsigned angle fails it)."""
    out: list[tuple[Any, ...]] = []
    while len(out) < n:
        q, l1, l3, l4 = porter_configs(rng, 1)[0]
        q[4] = np.pi / 2 * (1 if rng.uniform() < 0.5 else -1)
        T = Porter(l1, l3, l4).fk(q)
        if signed_angles_matter(porter_geometric(T, l1, l3, l4)[0]):
            out.append((T, l1, l3, l4))
    return out


def porter_parallel_expected(T: Any, l1: float, l3: float, l4: float) -> dict[str, Any]:
    """What the stroke judge needs: the front plane's α1 and Porter's minimal stroke | |p4 - p2| - l3 |."""
    p4 = porter_wrist_point(T, l4)
    robot = Porter(l1, l3, l4)
    return {
        "T": np.asarray(T, dtype=float),
        "fk": robot.fk,
        "revolute": robot.revolute,
        "scale": 1.0 + float(np.max(np.abs(p4))),
        "alpha1": math.atan2(p4[1], p4[0]),
        "q2_min": abs(math.dist(p4, (0.0, 0.0, l1)) - l3),
    }


def porter_geometric(T: Any, l1: float, l3: float, l4: float) -> np.ndarray:
    """Porter's Ver.2 configuration(s) of T: at parallel planes the minimal-stroke one."""
    return np.asarray(_quiet(Porter(l1, l3, l4).ik, T, method="geometric"))


def _nearest_index(S: np.ndarray, q: np.ndarray, wrap: Any) -> int:
    d = np.where(np.asarray(wrap, dtype=bool), transforms.wrap_angle(S - q), S - q)
    return int(np.argmin(np.sum(d * d, axis=1)))


def porter_nearest_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """Cases (T, l1, l3, l4, q_prev): q_prev between the four configurations (angles within about 0.8 of one,
    the stroke 3.5 to 7 long), each one where wrapping nothing, or wrapping the stroke like an angle, picks
    another configuration than the course's distance (angles wrapped, the stroke not): both mistakes fail it."""
    out: list[tuple[Any, ...]] = []
    angles, everything, nothing = [True, True, False, True, True, True], [True] * 6, [False] * 6
    while len(out) < n:
        T, l1, l3, l4 = porter_poses(rng, 1)[0]
        sol = np.atleast_2d(np.asarray(_quiet(Porter(l1, l3, l4).ik, T).q, dtype=float))
        q_prev = sol[int(rng.integers(len(sol)))] + rng.normal(0.0, 0.8, 6)
        q_prev[2] = float(rng.uniform(3.5, 7.0))
        q_prev = np.where(angles, transforms.wrap_angle(q_prev), q_prev)
        right = _nearest_index(sol, q_prev, angles)
        if right not in {_nearest_index(sol, q_prev, everything), _nearest_index(sol, q_prev, nothing)}:
            out.append((T, l1, l3, l4, q_prev))
    return out


def porter_nearest_expected(T: Any, l1: float, l3: float, l4: float, q_prev: Any) -> dict[str, Any]:
    """What the nearest judge needs (the stroke, column 2, is a length: never wrapped)."""
    return {**_set_expected(Porter(l1, l3, l4), T), "q_ref": np.asarray(q_prev, dtype=float)}


# ---------------------------------------------------------------- variants (issue 22: nothing answered by a lecture)
def _pitch_factors(q: Any, l1: float, l3: float, l4: float, line: str = "p5") -> list[np.ndarray]:
    """The motions of Porter's chain whose hand *pitches*: the sixth joint turns about y4 through p5.

    ``line="p4"`` turns it about the parallel line through p4 instead (Ry before Tx(l4): the mistake).
    """
    a1, a2, q2, a3, a4, a5 = (float(v) for v in np.asarray(q, dtype=float))
    T = transforms
    wrist = [T.transx(l4), T.troty(a5)] if line == "p5" else [T.troty(a5), T.transx(l4)]
    return [T.trotz(a1), tz(l1), T.troty(a2), T.transx(q2), T.troty(a3), tz(-l3), T.trotz(a4), *wrist]


def porter_pitch_fk(q: Any, l1: float, l3: float, l4: float) -> np.ndarray:
    """F05 of the pitching-hand variant (ex05 q1): Rz Tz Ry Tx(q2) Ry Tz(-l3) Rz Tx(l4) Ry(α5)."""
    return transforms.compose_moving(*_pitch_factors(q, l1, l3, l4))


def porter_pitch_through_p4(q: Any, l1: float, l3: float, l4: float) -> np.ndarray:
    """The mistake: the pitch about the line through p4 (Ry(α5) before Tx(l4))."""
    return transforms.compose_moving(*_pitch_factors(q, l1, l3, l4, line="p4"))


def porter_pitch_reversed(q: Any, l1: float, l3: float, l4: float) -> np.ndarray:
    """The mistake: the variant's nine motions multiplied in reverse order."""
    return transforms.compose_fixed(*_pitch_factors(q, l1, l3, l4))


def porter_pitch_printed(q: Any, l1: float, l3: float, l4: float) -> np.ndarray:
    """The mistake: the variant without the slide Tx(q2) (the product as printed, lecture 05 erratum 1)."""
    factors = _pitch_factors(q, l1, l3, l4)
    return transforms.compose_moving(*factors[:3], *factors[4:])


def porter_tool_wrist_point(T_tool: Any, l4: float, E: Any) -> np.ndarray:
    """The wrist point p4 of the hand holding a tool (ex06 q1): F05 = T_tool E⁻¹, then p5 - l4 x5."""
    T_tool, E = np.asarray(T_tool, dtype=float), np.asarray(E, dtype=float)
    return porter_wrist_point(T_tool @ transforms.inverse_transform(E), l4)


def _rod_fk(l1: float, l2: float, l3: float, l4: float) -> MountedFk:
    """F05 of Porter's chain with a telescopic rod: Porter's with the stroke shifted by the fixed part l2
    (package code, so it travels to the student edition's self-check)."""
    return MountedFk(Porter(l1, l3, l4).fk, offset=[0.0, 0.0, float(l2), 0.0, 0.0, 0.0])


def porter_rod_fk(q: Any, l1: float, l2: float, l3: float, l4: float) -> np.ndarray:
    """F05 of Porter's chain with a telescopic rod (ex06 q2): p3 = p2 + (l2 + q2) x2, the stroke q2 >= 0."""
    return np.asarray(_rod_fk(l1, l2, l3, l4)(q))


def porter_rod_poses(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """Cases (T, l1, l2, l3, l4) of the telescopic-rod chain: four of Porter's configurations reach T, and l2
    lies between the two rod lengths |p3 - p2| they need, so exactly two configurations have a stroke q2 >= 0
    (the other two would need the rod shorter than its fixed part); the first case sits near c4 = 0 and the
    second at c1 = 0 (where the printed formulas divide by zero), the third 1e-3 above the stroke's end."""
    out: list[tuple[Any, ...]] = []
    k = 0
    while len(out) < n:
        q, l1, l3, l4 = porter_configs(rng, 1)[0]
        if k == 0:
            q[4] = np.pi / 2 - 1e-4
        elif k == 1:
            q[0] = np.pi / 2
        T = Porter(l1, l3, l4).fk(q)
        rho = np.sort(np.asarray(_quiet(Porter(l1, l3, l4).ik, T).q, dtype=float)[:, 2])
        if len(rho) != 4 or rho[2] - rho[1] < 0.3:
            continue
        l2 = float(rho[2] - 1e-3) if k == 2 else float(rng.uniform(rho[1] + 0.1, rho[2] - 0.1))
        out.append((T, l1, l2, l3, l4))
        k += 1
    return out


def porter_rod_ik_expected(T: Any, l1: float, l2: float, l3: float, l4: float) -> dict[str, Any]:
    """Every configuration (q2 >= 0) of the telescopic-rod chain reaching T, for the set judge; rows that need
    the rod shorter than l2 have q2 < 0 and are told so (not the other arctan value of (14))."""
    robot = Porter(l1, l3, l4)
    sol = _quiet(robot.ik, T)
    rows = np.asarray(sol.q, dtype=float).copy()
    rows[:, 2] -= l2
    keep = rows[:, 2] >= -1e-12
    rows[:, 2] = np.maximum(rows[:, 2], 0.0)
    why = (
        "row {i} has q2 = {v:.4g} < 0: that configuration needs the rod shorter than its fixed part l2, so the "
        "chain cannot take it; the stroke q2 = |p3 - p2| - l2 must be >= 0 (drop the row)"
    )
    return {
        "T": np.asarray(T, dtype=float),
        "solutions": rows[keep],
        "labels": tuple(label for label, k in zip(sol.labels, keep, strict=True) if k),
        "fk": _rod_fk(l1, l2, l3, l4),
        "revolute": robot.revolute,
        "scale": 1.0 + float(np.max(np.abs(np.asarray(T, dtype=float)[:3, 3]))),
        "stroke": 2,
        "stroke_reason": why,
    }


def porter_limited_poses(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """Cases (T, l1, l3, l4, q2_max) of Porter's chain with a stroke limit: the limit between the two strokes
    (two configurations left), except every third case, whose limit is below both (the pose is out of reach)."""
    out: list[tuple[Any, ...]] = []
    while len(out) < n:
        T, l1, l3, l4 = porter_poses(rng, 1)[0]
        q2 = np.sort(np.asarray(_quiet(Porter(l1, l3, l4).ik, T).q, dtype=float)[:, 2])
        if len(q2) != 4 or q2[2] - q2[1] < 0.3 or q2[0] < 0.3:
            continue
        if len(out) % 3 == 2:
            limit = float(rng.uniform(0.3 * q2[0], 0.9 * q2[0]))
        else:
            limit = float(rng.uniform(q2[1] + 0.1, q2[2] - 0.1))
        out.append((T, l1, l3, l4, limit))
    return out


def porter_limited_expected(T: Any, l1: float, l3: float, l4: float, q2_max: float) -> dict[str, Any]:
    """Every configuration of Porter's chain reaching T with 0 <= q2 <= q2_max (none: out of reach)."""
    out = _set_expected(Porter(l1, l3, l4, q2_max=q2_max), T, fk=Porter(l1, l3, l4).fk, stroke=2)
    out["solutions"] = np.asarray(out["solutions"], dtype=float).reshape(-1, 6)
    out["q2_max"] = float(q2_max)
    return out
