"""References of exercises 1 to 4: rotations, link matrices, DH tables and the mechanisms to model."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from puma_course import transforms
from puma_course.kinematics import MK3, DHChain, Link, Puma560, dh

from .._formulas import CAMERA_IN_HEAD, PAN_TILT_C, PAN_TILT_H
from .._inputs import unit_vectors
from ._common import _table_expected, pose, tz


# ---------------------------------------------------------------- exercise 1: rotations
def elementary_rotation(axis: str, angle: float) -> np.ndarray:
    """Rotation by ``angle`` about the coordinate axis ``"x"``, ``"y"`` or ``"z"``.

    >>> elementary_rotation("z", np.pi / 2).round(12) @ [1, 0, 0]
    array([0., 1., 0.])
    """
    return {"x": transforms.rotx, "y": transforms.roty, "z": transforms.rotz}[axis](angle)


#: The axes ``signed_rotation`` accepts: a coordinate axis or its opposite.
SIGNED_AXES = ("x", "-x", "y", "-y", "z", "-z")


def signed_rotation(axis: str, angle: float) -> np.ndarray:
    """Rotation by ``angle`` about a signed coordinate axis: ``"-y"`` is the direction -e_y, so it is R_y(-angle).

    >>> signed_rotation("-z", np.pi / 2).round(12) @ [1, 0, 0]  # a quarter turn about -z carries x to -y
    array([ 0., -1.,  0.])
    """
    if axis not in SIGNED_AXES:
        raise ValueError(f"axis: expected one of {', '.join(SIGNED_AXES)}, got {axis!r}")
    sign = -1.0 if axis.startswith("-") else 1.0
    return elementary_rotation(axis[-1], sign * float(angle))


def rotation_between(u: Any, v: Any) -> np.ndarray:
    """The smallest rotation carrying the direction of ``u`` onto that of ``v`` (the identity when they are parallel).

    Axis u × v, angle atan2(|u × v|, u·v) in [0, π). Refused (ValueError) when v points opposite to u: every axis
    normal to u then gives a half turn, and none is smaller than the others.

    >>> rotation_between([1, 0, 0], [0, 2, 0]).round(12) @ [1, 0, 0]
    array([0., 1., 0.])
    """
    u, v = (np.asarray(w, dtype=float).reshape(3) for w in (u, v))
    for name, w in (("u", u), ("v", v)):
        if not np.all(np.isfinite(w)) or not np.any(w):
            raise ValueError(f"{name}: expected a non-zero finite 3-vector, got {w.tolist()}")
    u, v = u / np.linalg.norm(u), v / np.linalg.norm(v)
    a = np.cross(u, v)
    s, c = float(np.linalg.norm(a)), float(u @ v)
    if s < 1e-12:
        if c > 0:
            return np.eye(3)
        raise ValueError("v: points opposite to u, where no single smallest turn exists (every half turn about an "
                         "axis normal to u carries u onto v)")  # fmt: skip
    return transforms.rodrigues(a, float(np.arctan2(s, c)))


def axis_angle_between(R_a: Any, R_b: Any) -> np.ndarray:
    """``[kx, ky, kz, θ]`` of the turn K about an axis fixed in the base frame with R_b = K R_a (K = R_b R_aᵀ)."""
    R_a, R_b = np.asarray(R_a, dtype=float), np.asarray(R_b, dtype=float)
    return axis_angle(R_b @ R_a.T)


def relative_pose(T_a: Any, T_b: Any) -> np.ndarray:
    """ᴬT_B = (⁰T_A)⁻¹ ⁰T_B: the pose of frame {B} in frame {A}, both given in the base frame {0}."""
    return transforms.inverse_transform(T_a) @ np.asarray(T_b, dtype=float)


def rodrigues(axis: Any, angle: float) -> np.ndarray:
    """K(axis, angle), the axis normalised."""
    return transforms.rodrigues(axis, angle)


def axis_angle(R: np.ndarray) -> np.ndarray:
    """``[kx, ky, kz, θ]`` of a rotation matrix."""
    axis, angle = transforms.axis_angle(R)
    return np.append(axis, angle)


def inverse_transform(T: np.ndarray) -> np.ndarray:
    """The inverse of a rigid 4x4 transform."""
    return transforms.inverse_transform(T)


def camera_pose(pan: float, tilt: float) -> np.ndarray:
    """Pose of the camera of the pan-tilt head: Rz(pan) Trans(0, 0, h) Ry(tilt) Trans(c, 0, 0), camera axes.

    >>> camera_pose(0.0, 0.0).round(12)[:3]  # looking along x0, image right = -y0, image down = -z0
    array([[ 0.  ,  0.  ,  1.  ,  0.05],
           [-1.  ,  0.  ,  0.  ,  0.  ],
           [ 0.  , -1.  ,  0.  ,  0.12]])
    """
    camera = transforms.homogeneous(CAMERA_IN_HEAD, [PAN_TILT_C, 0.0, 0.0])
    return transforms.compose_moving(transforms.trotz(pan), tz(PAN_TILT_H), transforms.troty(tilt), camera)


def random_rotations(rng: np.random.Generator, n: int, lo: float = 0.2, hi: float = 3.0) -> list[np.ndarray]:
    """``n`` rotations about random axes by angles drawn from [lo, hi)."""
    return [transforms.rodrigues(a, t) for a, t in zip(unit_vectors(rng, n), rng.uniform(lo, hi, n), strict=True)]


def random_transforms(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """``n`` one-argument cases, each a random rigid transform."""
    return [(transforms.homogeneous(R, rng.uniform(-2, 2, 3)),) for R in random_rotations(rng, n)]


# ---------------------------------------------------------------- exercises 2 and 3: DH tables and chains
def mdh(alpha_prev: float, a_prev: float, theta: float, d: float) -> np.ndarray:
    """Craig's modified DH link matrix."""
    return dh.mdh(alpha_prev, a_prev, theta, d)


def world_pose(turns: Any, p: Any) -> np.ndarray:
    """The pose [[R, p], [0, 1]], R the product of elementary turns ``[(axis, angle), ...]`` (a frame's world pose)."""
    R = np.eye(3)
    for axis, angle in turns:
        R = R @ elementary_rotation(axis, angle)
    return pose(R, p)


def mdh_inverse(alpha_prev: float, a_prev: float, theta: float, d: float) -> np.ndarray:
    """ⁱT_{i-1}, the inverse of Craig's link matrix: the four motions undone, last first (ex02 q2's reference).

    >>> bool(np.allclose(mdh_inverse(0.3, 0.4, -1.0, 0.2) @ mdh(0.3, 0.4, -1.0, 0.2), np.eye(4)))
    True
    """
    return transforms.compose_moving(
        tz(-d), transforms.trotz(-theta), transforms.transx(-a_prev), transforms.trotx(-alpha_prev)
    )


def mdh_negated(alpha_prev: float, a_prev: float, theta: float, d: float) -> np.ndarray:
    """The four motions negated but kept in their order, Rot(X, -α) Trans(X, -a) Rot(Z, -θ) Trans(Z, -d) (a mistake
    of ex02 q2; it is also the standard-DH link matrix inverted)."""
    return dh.mdh(-alpha_prev, -a_prev, -theta, -d)


def mdh_reversed(alpha_prev: float, a_prev: float, theta: float, d: float) -> np.ndarray:
    """The four motions reversed but not negated, Trans(Z, d) Rot(Z, θ) Trans(X, a) Rot(X, α) (a mistake of ex02 q2;
    it is also the standard-DH link matrix of the same four numbers)."""
    return transforms.compose_moving(
        tz(d), transforms.trotz(theta), transforms.transx(a_prev), transforms.trotx(alpha_prev)
    )


def mdh_inverse_transposed(alpha_prev: float, a_prev: float, theta: float, d: float) -> np.ndarray:
    """ⁱT_{i-1} transposed as a whole 4×4 (a mistake of ex02 q2)."""
    return mdh_inverse(alpha_prev, a_prev, theta, d).T


def mdh_transposed(alpha_prev: float, a_prev: float, theta: float, d: float) -> np.ndarray:
    """Craig's link matrix transposed as a whole 4×4 (a mistake of ex02 q2: Rᵀ is right, the translation is not)."""
    return dh.mdh(alpha_prev, a_prev, theta, d).T


def mdh_inverse_minus_p(alpha_prev: float, a_prev: float, theta: float, d: float) -> np.ndarray:
    """[[Rᵀ, -p], [0, 1]] of the link matrix [[R, p], [0, 1]] (a mistake of ex02 q2)."""
    T = dh.mdh(alpha_prev, a_prev, theta, d)
    return pose(T[:3, :3].T, -T[:3, 3])


def mdh_inverse_plus_p(alpha_prev: float, a_prev: float, theta: float, d: float) -> np.ndarray:
    """[[Rᵀ, p], [0, 1]] of the link matrix [[R, p], [0, 1]] (a mistake of ex02 q2)."""
    T = dh.mdh(alpha_prev, a_prev, theta, d)
    return pose(T[:3, :3].T, T[:3, 3])


def standard_link(theta: float, d: float, a: float, alpha: float) -> np.ndarray:
    """The standard (distal) DH link matrix Rot(Z, θ) Trans(Z, d) Trans(X, a) Rot(X, α) (not the course's)."""
    return transforms.compose_moving(transforms.trotz(theta), tz(d), transforms.transx(a), transforms.trotx(alpha))


def table_chain(table: Any) -> DHChain:
    """The chain of a table with rows (α_{i-1}, a_{i-1}, θ_i, d_i, σ_i), σ = 1 prismatic."""
    rows = np.asarray(table, dtype=float).reshape(-1, 5)
    return DHChain([Link(r[0], r[1], r[3], r[2], "P" if r[4] > 0.5 else "R") for r in rows])


def table_fk(table: Any, q: Any) -> np.ndarray:
    """^0T_n of a table's chain for q (n,) or (N, n) (Craig's modified link matrices)."""
    return table_chain(table).fk(np.asarray(q, dtype=float))


def _table_variables(table: Any, q: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rows, Q = np.asarray(table, dtype=float).reshape(-1, 5), np.atleast_2d(np.asarray(q, dtype=float))
    prism = rows[:, 4] > 0.5
    return rows, np.where(prism, rows[:, 2], rows[:, 2] + Q), np.where(prism, rows[:, 3] + Q, rows[:, 3])


def standard_table_fk(table: Any, q: Any) -> np.ndarray:
    """The same table read as a standard-DH table: the product of Rot(Z, θ) Trans(Z, d) Trans(X, a) Rot(X, α)."""
    rows, th, d = _table_variables(table, q)
    out = np.stack(
        [
            np.linalg.multi_dot(
                [np.eye(4)] + [standard_link(t[i], dd[i], rows[i, 1], rows[i, 0]) for i in range(len(rows))]
            )
            for t, dd in zip(th, d, strict=True)
        ]
    )
    return out if np.ndim(q) > 1 else out[0]


def reversed_table_fk(table: Any, q: Any) -> np.ndarray:
    """The link matrices of a table multiplied in reverse order, ^{n-1}T_n ... ^0T_1 (a mistake)."""
    rows, th, d = _table_variables(table, q)
    out = np.stack(
        [
            np.linalg.multi_dot(
                [np.eye(4)] + [mdh(rows[i, 0], rows[i, 1], t[i], dd[i]) for i in reversed(range(len(rows)))]
            )
            for t, dd in zip(th, d, strict=True)
        ]
    )
    return out if np.ndim(q) > 1 else out[0]


def random_tables(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """``n`` cases (table, q) of random chains of 2 to 6 joints, a prismatic joint now and then."""
    out: list[tuple[Any, ...]] = []
    for _ in range(n):
        k = int(rng.integers(2, 7))
        alpha = rng.choice([0.0, np.pi / 2, -np.pi / 2, 0.7, np.pi], k)
        table = np.column_stack(
            [
                alpha,
                rng.uniform(-1, 1, k),
                rng.uniform(-1, 1, k),
                rng.uniform(-1, 1, k),
                (rng.uniform(0, 1, k) < 0.25).astype(float),
            ]
        )
        out.append((table, rng.uniform(-np.pi, np.pi, k)))
    return out


def standard_tables(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """``n`` cases (table,) of random standard-DH tables (rows α_i, a_i, θ_i, d_i, σ_i) of 2 to 6 joints, a
    prismatic joint now and then, the last row with α_n = a_n = 0 (its frame {n} on the last joint's axis)."""
    out: list[tuple[Any, ...]] = []
    for table, _q in random_tables(rng, n):
        t = np.array(table, dtype=float)
        t[:, 1] = np.where(np.abs(t[:, 1]) < 0.1, 0.3, t[:, 1])  # every a_i visibly non-zero
        t[-1, :2] = 0.0
        out.append((t,))
    return out


def standard_expected(table: Any) -> dict[str, Any]:
    """What the table judge needs for ex02 q4: the poses the standard-DH chain of ``table`` reaches."""
    t = np.asarray(table, dtype=float)
    scale = float(np.sum(np.abs(t[:, 1])) + np.sum(np.abs(t[:, 3])) + 1.5 * (1 + np.sum(t[:, 4])))
    return _table_expected(lambda Q: standard_table_fk(t, Q), t[:, 4] < 0.5, scale, t)


#: The tool frame of the RRP arm: z along the boom, x up at q = 0 (columns x, y, z in the shoulder's frame).
RRP_TOOL = np.array([[0.0, 0.0, 1.0], [0.0, -1.0, 0.0], [1.0, 0.0, 0.0]])


def rrp_fk(Q: Any, h: float, d2: float) -> np.ndarray:
    """Tool pose of the RRP arm (column h, offset d2, reach q3): Rz(q1) Tz(h) Ty(d2) Ry(-q2) Tx(q3) R_T."""
    out = [
        transforms.compose_moving(
            transforms.trotz(q[0]),
            tz(h),
            transforms.transy(d2),
            transforms.troty(-q[1]),
            transforms.transx(q[2]),
            pose(RRP_TOOL, np.zeros(3)),
        )
        for q in np.atleast_2d(Q)
    ]
    return np.stack(out) if np.ndim(Q) > 1 else out[0]


def rrp_expected(h: float, d2: float) -> dict[str, Any]:
    """What the table judge needs for the RRP arm of ex02."""
    return _table_expected(lambda Q: rrp_fk(Q, h, d2), [True, True, False], h + abs(d2) + 1.5, h, d2)


#: The question's joint zero of the PUMA-560 (arm straight up) in the lecture's joint values.
PUMA_ZERO = np.array([0.0, -np.pi / 2, -np.pi / 2, 0.0, 0.0, 0.0])


def puma_pedestal_fk(Q: Any, a2: float, a3: float, d3: float, d4: float, h: float, d6: float) -> np.ndarray:
    """The PUMA-560 on a pedestal of height h, tool d6 along z6, q = 0 arm straight up: Tz(h) fk(q + qr) Tz(d6)."""
    return tz(h) @ Puma560(a2, a3, d3, d4).fk(np.asarray(Q, dtype=float) + PUMA_ZERO) @ tz(d6)


def puma_pedestal_expected(a2: float, a3: float, d3: float, d4: float, h: float, d6: float) -> dict[str, Any]:
    """What the table judge needs for the PUMA-560 of ex03."""
    return _table_expected(
        lambda Q: puma_pedestal_fk(Q, a2, a3, d3, d4, h, d6),
        [True] * 6,
        a2 + abs(a3) + abs(d3) + d4 + h + d6,
        a2,
        a3,
        d3,
        d4,
        h,
        d6,
    )


# ---------------------------------------------------------------- exercise 4: the MK3
def mk3_fk(
    q: Any, d1: float = 360.0, a1: float = 135.0, a2: float = 250.0, a3: float = 215.0, d5: float = 100.0
) -> np.ndarray:
    """^0T_5 of the Motoman MK3 (mm)."""
    return MK3(d1, a1, a2, a3, d5).fk(np.asarray(q, dtype=float))


def mk3_table(d1: float, a1: float, a2: float, a3: float, d5: float) -> np.ndarray:
    """The MK3's table as rows (α, a, θ, d, σ), read from ``MK3(...)`` itself."""
    return np.array([[lk.alpha_prev, lk.a_prev, lk.theta, lk.d, 0.0] for lk in MK3(d1, a1, a2, a3, d5).links])


def mk3_printed_fk(q: Any, d1: float, a1: float, a2: float, a3: float, d5: float) -> np.ndarray:
    """^0T_5 with the lecture's misprinted ^4T_5: its offset (0, 0, -d5) instead of (0, -d5, 0)."""
    table, q = mk3_table(d1, a1, a2, a3, d5), np.asarray(q, dtype=float)
    T45 = mdh(table[4, 0], table[4, 1], q[4] + table[4, 2], table[4, 3])
    T45[:3, 3] = [0.0, 0.0, -d5]
    return table_fk(table[:4], q[:4]) @ T45


def mk3_rail_fk(Q: Any, c: float, d1: float, a1: float, a2: float, a3: float, d5: float) -> np.ndarray:
    """The MK3 on a carriage sliding along y0 (q1), its base c above the rail: Trans(0, q1, c) ^0T_5(q2..q6)."""
    Q = np.asarray(Q, dtype=float)
    Qb = np.atleast_2d(Q)
    out = np.stack([transforms.transl([0.0, q[0], c]) for q in Qb]) @ MK3(d1, a1, a2, a3, d5).fk(Qb[:, 1:])
    return out if Q.ndim > 1 else out[0]


#: What a rail table that leaves a height out of row 2 (its d is c + d1) is told: every pose sits that much lower.
MISSING_HEIGHT = (
    "your chain moves like the MK3 on its rail, but every pose is {h:g} mm too low: row 2's d is the height of the "
    "shoulder's axis above the rail frame, the carriage's height c plus the MK3's own d1 (d = c + d1); yours {what}"
)


def mk3_rail_expected(c: float, d1: float, a1: float, a2: float, a3: float, d5: float) -> dict[str, Any]:
    """What the table judge needs for the MK3 on a rail of ex04 (strokes in mm), with the heights left out named."""
    out = _table_expected(
        lambda Q: mk3_rail_fk(Q, c, d1, a1, a2, a3, d5),
        [False] + [True] * 5,
        c + d1 + a1 + a2 + a3 + d5,
        c,
        d1,
        a1,
        a2,
        a3,
        d5,
        stroke=(-800.0, 800.0),
    )
    out["shifts"] = [
        ("missing_offset", MISSING_HEIGHT.format(h=c, what="leaves out the carriage's height c"), [0.0, 0.0, -c]),
        ("missing_offset", MISSING_HEIGHT.format(h=d1, what="leaves out the MK3's d1"), [0.0, 0.0, -d1]),
    ]
    return out


def mk3_rail_nearest(T: Any, s: float) -> np.ndarray:
    """The nearest attainable pose of the MK3 on its rail (carriage at ``s``): the goal T (rail frame, mm)
    turned the least so its approach lies in the vertical plane through the MK3's base axis (x = 0, y = s)
    and the tool point; the position kept (Craig's Motoman L-3, ``MK3.nearest_attainable``)."""
    B = transforms.transl([0.0, float(s), 0.0])
    near, _ = MK3().nearest_attainable(transforms.inverse_transform(B) @ np.asarray(T, dtype=float))
    return B @ near


def mk3_rail_projected(T: Any, s: float) -> np.ndarray:
    """The goal T (rail frame, mm) turned the least so its approach lies in the vertical plane through the base
    axis at (0, s) and the tool point, position kept, and never turned further along the plane: what a student
    who projects computes (a mistaken plane's wrist point may be out of reach, where ``nearest_attainable``
    turns on; this is the mistake's rebuild, not the reference)."""
    T = np.asarray(T, dtype=float)
    px, py = T[0, 3], T[1, 3] - float(s)
    h = math.hypot(px, py)
    out = T.copy()
    if h == 0.0:
        return out
    m = np.array([-py / h, px / h, 0.0])
    z = T[:3, 2]
    k = np.cross(z, z - (m @ z) * m)
    if np.linalg.norm(k) < 1e-12:
        return out
    out[:3, :3] = transforms.rodrigues(k / np.linalg.norm(k), math.asin(min(1.0, abs(float(m @ z))))) @ T[:3, :3]
    return out


def mk3_rail_goal(q: Any, axis: Any, angle: float, s: float) -> np.ndarray:
    """A goal for the MK3 on its rail: the pose at ``q`` (carriage at ``s``) with its orientation turned by
    ``angle`` about ``axis`` (rail frame; 0 leaves it attainable)."""
    T = MK3().fk(np.asarray(q, dtype=float))
    if angle:
        T[:3, :3] = transforms.rodrigues(axis, angle) @ T[:3, :3]
    return transforms.transl([0.0, float(s), 0.0]) @ T


def mk3_nearest_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """``n`` goals (T, s) for the MK3 on its rail: poses it reaches, turned about a random axis so the approach
    leaves the arm plane by 15° to 65°, the tool point at least 100 mm off the base axis and the approach's
    projection onto the plane within reach (no further turn along it); the carriage 100 to 600 mm from the
    rail's middle, either way."""
    arm, out = MK3(), []
    lo, hi = np.sin(np.radians(15.0)), np.sin(np.radians(65.0))
    while len(out) < n:
        T = arm.fk(rng.uniform(-np.pi, np.pi, 5))
        T[:3, :3] = transforms.rodrigues(rng.normal(size=3), rng.uniform(0.3, 1.2)) @ T[:3, :3]
        p, z = T[:3, 3], T[:3, 2]
        h = float(np.hypot(p[0], p[1]))
        info = arm.nearest_attainable(T)[1]  # the projection onto the plane must do (the question's nearest pose)
        if h < 100.0 or not lo <= abs(-p[1] * z[0] + p[0] * z[1]) / h <= hi or not info.success or info.along:
            continue
        s = float(rng.choice([-1.0, 1.0]) * rng.uniform(100.0, 600.0))
        out.append((transforms.transl([0.0, s, 0.0]) @ T, s))
    return out


def mk3_attainable_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """``n`` goals (T, s) the MK3 on its rail reaches as they are (its nearest pose is the goal itself), the tool
    point at least 100 mm off the base axis; the carriage 100 to 600 mm from the rail's middle, either way."""
    arm, out = MK3(), []
    while len(out) < n:
        T = arm.fk(rng.uniform(-np.pi, np.pi, 5))
        if float(np.hypot(T[0, 3], T[1, 3])) < 100.0:
            continue
        s = float(rng.choice([-1.0, 1.0]) * rng.uniform(100.0, 600.0))
        out.append((transforms.transl([0.0, s, 0.0]) @ T, s))
    return out


def mk3_in_plane_goal(q: Any, s: float, across: bool = False) -> np.ndarray:
    """A goal for the MK3 on its rail whose approach lies in the arm plane *exactly*, not up to rounding.

    The pose at ``q`` (θ1 replaced by 0, or by π/2 if ``across``) is rebuilt from its angles with exact zeros: the
    tool point at (r, s, h) (or (0, s + r, h)) and R = Ry(β) Rz(γ) (or Rz(π/2) Ry(β) Rz(γ) written out), so the
    plane's normal is a coordinate axis and the approach's component along it is 0.0: z × z' is the zero vector
    and an answer that normalises it unguarded returns NaN. Its nearest pose is the goal itself.
    """
    F = MK3().fk(np.array([0.0, *np.asarray(q, dtype=float)[1:]]))  # in the x-z plane up to rounding
    beta, gamma = math.atan2(F[0, 2], F[2, 2]), math.atan2(F[1, 0], F[1, 1])
    cb, sb, cg, sg = math.cos(beta), math.sin(beta), math.cos(gamma), math.sin(gamma)
    R = np.array([[cb * cg, -cb * sg, sb], [sg, cg, 0.0], [-sb * cg, sb * sg, cb]])  # Ry(β) Rz(γ), R[1, 2] = 0
    p = np.array([F[0, 3], 0.0, F[2, 3]])
    if across:  # turned a quarter about z0, exactly: (x, y, z) -> (-y, x, z)
        R, p = np.array([-R[1], R[0], R[2]]), np.array([0.0, p[0], p[2]])
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, p + [0.0, float(s), 0.0]
    return T


def mk3_in_plane_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """``n`` goals (T, s) already in the arm plane exactly (:func:`mk3_in_plane_goal`), the tool point at least
    100 mm off the base axis, alternately along x0 and along y0 from it; the carriage 100 to 600 mm either way."""
    out: list[tuple[Any, ...]] = []
    while len(out) < n:
        q = rng.uniform(-np.pi, np.pi, 5)
        s = float(rng.choice([-1.0, 1.0]) * rng.uniform(100.0, 600.0))
        T = mk3_in_plane_goal(q, s, across=len(out) % 2 == 1)
        if float(np.hypot(T[0, 3], T[1, 3] - s)) >= 100.0:
            out.append((T, s))
    return out


def mk3_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """``n`` cases (q, d1, a1, a2, a3, d5) with lengths around the lecture's (mm)."""
    base = np.array([360.0, 135.0, 250.0, 215.0, 100.0])
    return [(q, *(float(v) for v in base * rng.uniform(0.6, 1.4, 5))) for q in rng.uniform(-np.pi, np.pi, (n, 5))]
