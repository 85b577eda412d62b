"""Numbers of the question bank worked out with numpy alone: formulas, hidden joint values.

The references that *are* a short formula (the wrist point p5 - l4 x5, the plane normal of
Porter's Ver.2, the parameters of a link matrix), the mistaken formulas the diagnoses rebuild, and
the seeded hidden joint values of the modelling questions. Nothing here calls the kinematics layer
(that is :mod:`._reference`); angles are wrapped by the base layer's one rule, ``wrap_angle``.
"""

from __future__ import annotations

import math
import zlib
from typing import Any

import numpy as np

from puma_course.transforms import homogeneous, roty, rotz, wrap_angle


def link_parameters(T: Any) -> np.ndarray:
    """[α_{i-1}, a_{i-1}, θ_i, d_i] of a modified-DH link matrix, angles in (-π, π] (it inverts ``mdh``)."""
    T = np.asarray(T, dtype=float)
    alpha, theta = math.atan2(-T[1, 2], T[2, 2]), math.atan2(-T[0, 1], T[0, 0])
    d = -math.sin(alpha) * T[1, 3] + math.cos(alpha) * T[2, 3]
    return np.array([alpha, T[0, 3], theta, d])


def standard_reading(T: Any) -> np.ndarray:
    """The four numbers read off a link matrix where a *standard*-DH matrix shows them (the mistake):
    θ from the first column, α from the third row, a along the turned x, d = p_z."""
    T = np.asarray(T, dtype=float)
    theta, alpha = math.atan2(T[1, 0], T[0, 0]), math.atan2(T[2, 1], T[2, 2])
    return np.array([alpha, math.cos(theta) * T[0, 3] + math.sin(theta) * T[1, 3], theta, T[2, 3]])


def _rigid_inverse(T: np.ndarray) -> np.ndarray:
    R, p = T[:3, :3], T[:3, 3]
    return homogeneous(R.T, -R.T @ p)


def _between(T_prev: Any, T: Any, how: str) -> np.ndarray:
    """A matrix formed from the world poses ⁰T_{i-1}, ⁰T_i: the link matrix (``"link"``) or a mistaken one."""
    A, B = np.asarray(T_prev, dtype=float), np.asarray(T, dtype=float)
    if how == "link":  # ⁱ⁻¹T_i = (⁰T_{i-1})⁻¹ ⁰T_i
        return _rigid_inverse(A) @ B
    if how == "inverse":  # ⁱT_{i-1} = (⁰T_i)⁻¹ ⁰T_{i-1}
        return _rigid_inverse(B) @ A
    if how == "order":  # ⁰T_i (⁰T_{i-1})⁻¹: the inverse on the wrong side
        return B @ _rigid_inverse(A)
    raise ValueError(f"how: expected 'link', 'inverse' or 'order', got {how!r}")


def link_parameters_between(T_prev: Any, T: Any) -> np.ndarray:
    """[α_{i-1}, a_{i-1}, θ_i, d_i] of the link from the world poses ⁰T_{i-1} and ⁰T_i (ex02 q1's reference)."""
    return link_parameters(_between(T_prev, T, "link"))


def parameters_of_pose(T_prev: Any, T: Any) -> np.ndarray:
    """The mistake ``base_frame``: the entries read off the world pose ⁰T_i itself, ⁰T_{i-1} ignored."""
    return link_parameters(T)


def parameters_of_inverse(T_prev: Any, T: Any) -> np.ndarray:
    """The mistake ``inverse``: the entries read off ⁱT_{i-1} = (⁰T_i)⁻¹ ⁰T_{i-1}."""
    return link_parameters(_between(T_prev, T, "inverse"))


def parameters_in_order(T_prev: Any, T: Any) -> np.ndarray:
    """The mistake ``order``: the entries read off ⁰T_i (⁰T_{i-1})⁻¹."""
    return link_parameters(_between(T_prev, T, "order"))


def standard_reading_between(T_prev: Any, T: Any) -> np.ndarray:
    """The mistake ``standard_dh``: the link matrix formed right, read where a standard-DH matrix shows the numbers."""
    return standard_reading(_between(T_prev, T, "link"))


def porter_wrist_point(T: Any, l4: float) -> np.ndarray:
    """The wrist point p4 = p5 - l4 x5 of an end-effector pose (the formula itself)."""
    T = np.asarray(T, dtype=float)
    return T[:3, 3] - l4 * T[:3, 0]


def porter_normal(T: Any, l1: float, l4: float) -> np.ndarray:
    """The unit normal n = (p2 - p0) x (p4 - p0) / |...| of the arm plane (Ver.2, corrected order)."""
    p4 = porter_wrist_point(T, l4)
    n = np.cross([0.0, 0.0, l1], p4)
    return n / np.linalg.norm(n)


def porter_elbows(T: Any, l1: float, l3: float, l4: float, rod: float | None = None) -> np.ndarray:
    """The two candidates p3 = p4 ± l3 z4, z4 ∝ n × x5 (``rod`` replaces l3: the printed l4)."""
    p4, x5 = porter_wrist_point(T, l4), np.asarray(T, dtype=float)[:3, 0]
    m = np.cross(porter_normal(T, l1, l4), x5)
    z4 = m / np.linalg.norm(m)
    r = l3 if rod is None else rod
    return np.array([p4 + r * z4, p4 - r * z4])


def case_rng(*args: Any) -> np.random.Generator:
    """A generator seeded by a case's arguments: the hidden joint values of a modelling case are fixed by it."""
    flat = np.concatenate([np.asarray(a, dtype=float).ravel() for a in args if not isinstance(a, str)])
    return np.random.default_rng(zlib.crc32(np.round(flat, 12).tobytes()))


def hidden_q(rng: np.random.Generator, revolute: Any, n: int = 24, stroke: tuple[float, float] = (0.2, 1.5)) -> Any:
    """``n`` random joint vectors: angles in (-π, π], strokes in ``stroke``."""
    rev = np.asarray(revolute, dtype=bool)
    Q = rng.uniform(-np.pi, np.pi, (n, len(rev)))
    Q[:, ~rev] = rng.uniform(*stroke, (n, int(np.sum(~rev))))
    return Q


def rodrigues_unnormalised(axis: Any, angle: float) -> np.ndarray:
    """I + sin θ [a]x + (1 - cos θ) [a]x² with the axis a as given (the mistake of not normalising it)."""
    a = np.asarray(axis, dtype=float)
    S = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return np.eye(3) + math.sin(angle) * S + (1.0 - math.cos(angle)) * (S @ S)


def plain_distance(q: Any, q_ref: Any) -> float:
    """|q - q_ref| without wrapping the angle differences (the mistake)."""
    return float(np.linalg.norm(np.asarray(q, dtype=float) - np.asarray(q_ref, dtype=float)))


def nearest_row(solutions: Any, q_prev: Any, wrap: bool = True) -> np.ndarray:
    """The row of ``solutions`` nearest ``q_prev``, angle differences wrapped (or not, the mistake)."""
    S, q = np.atleast_2d(np.asarray(solutions, dtype=float)), np.asarray(q_prev, dtype=float)
    d = wrap_angle(S - q) if wrap else S - q
    return S[int(np.argmin(np.sum(d * d, axis=1)))].copy()


def wrapped_nearest(solutions: Any, q_prev: Any, revolute: Any = (True, True, False, True, True, True)) -> np.ndarray:
    """The row of ``solutions`` nearest ``q_prev``, wrapping only the revolute columns (Porter's stroke is a length)."""
    S, q = np.atleast_2d(np.asarray(solutions, dtype=float)), np.asarray(q_prev, dtype=float)
    d = np.where(np.asarray(revolute, dtype=bool), wrap_angle(S - q), S - q)
    return S[int(np.argmin(np.sum(d * d, axis=1)))].copy()


# ---------------------------------------------------------------- exercise 1: the pan-tilt camera
#: The pan-tilt head of exercise 1's modelling question: tilt axis height and camera offset [m].
PAN_TILT_H, PAN_TILT_C = 0.12, 0.05
#: Camera axes (x right, y down the image, z forward) in the head's frame (x forward, z up).
CAMERA_IN_HEAD = np.array([[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]])


def _camera_at(R_head: np.ndarray, camera_axes: np.ndarray) -> np.ndarray:
    """The camera's pose for a head turned by R_head: its centre c along the head's x from the tilt axis."""
    return homogeneous(R_head @ camera_axes, [0.0, 0.0, PAN_TILT_H] + PAN_TILT_C * R_head[:, 0])


def camera_head_frame(pan: float, tilt: float) -> np.ndarray:
    """The mistake: the head's own frame at the camera (x forward, z up), the camera's axes never set."""
    return _camera_at(rotz(pan) @ roty(tilt), np.eye(3))


def camera_tilted_back(pan: float, tilt: float) -> np.ndarray:
    """The mistake: the tilt turned the wrong way, Rz(pan) Ry(-tilt) (R_y's sines swapped, or the sign guessed)."""
    return _camera_at(rotz(pan) @ roty(-tilt), CAMERA_IN_HEAD)


def camera_panned_back(pan: float, tilt: float) -> np.ndarray:
    """The mistake: the pan turned the wrong way, Rz(-pan) Ry(tilt)."""
    return _camera_at(rotz(-pan) @ roty(tilt), CAMERA_IN_HEAD)


def camera_offset_unturned(pan: float, tilt: float) -> np.ndarray:
    """The mistake: the camera's offset c along the base's x0, not along the turned head's x."""
    out = _camera_at(rotz(pan) @ roty(tilt), CAMERA_IN_HEAD)
    out[:3, 3] = [PAN_TILT_C, 0.0, PAN_TILT_H]
    return out


def camera_fixed_axes(pan: float, tilt: float) -> np.ndarray:
    """The mistake: tilt about the base's fixed y0 after the pan (Ry(tilt) Rz(pan)), not about the turned head's y."""
    return _camera_at(roty(tilt) @ rotz(pan), CAMERA_IN_HEAD)


# ---------------------------------------------------------------- exercise 4 q4: the nearest attainable pose, mistaken
def _goal_and_nearest(T: Any, near: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    T, near = np.asarray(T, dtype=float), np.asarray(near, dtype=float)
    return T, near, near[:3, :3] @ T[:3, :3].T  # the rotation that turned the goal into the nearest pose


def turned_back(T: Any, near: Any) -> np.ndarray:
    """The goal turned by the nearest pose's rotation the wrong way (-θ for θ): its approach leaves the plane more."""
    T, near, Q = _goal_and_nearest(T, near)
    out = T.copy()
    out[:3, :3] = Q.T @ T[:3, :3]
    return out


def approach_only(T: Any, near: Any) -> np.ndarray:
    """Only the approach vector replaced by its projection into the plane; x and y kept (not a rotation)."""
    out = np.asarray(T, dtype=float).copy()
    out[:3, 2] = np.asarray(near, dtype=float)[:3, 2]
    return out


def kept_axis(T: Any, near: Any, axis: int) -> np.ndarray:
    """The new approach with the goal's x (``axis`` 0) or y (1) axis re-orthogonalised against it (Gram-Schmidt):
    a rotation with its approach in the plane, but not the smallest one."""
    T = np.asarray(T, dtype=float)
    z = np.asarray(near, dtype=float)[:3, 2]
    a = T[:3, axis] - (T[:3, axis] @ z) * z
    a = a / math.hypot(*a)
    out = T.copy()
    out[:3, axis], out[:3, 1 - axis], out[:3, 2] = a, (np.cross(z, a) if axis == 0 else np.cross(a, z)), z
    return out


# ---------------------------------------------------------------- ex01 q6: a controller's X-Y-Z angles
#: cos b below this is the gimbal lock of the X-Y-Z set (then only a + c or a - c is defined).
XYZ_LOCK_TOL = 1e-9


def xyz_angles_all(Rs: Any) -> np.ndarray:
    """:func:`xyz_angles` of every rotation of a stack (N, 3, 3): (N, 3)."""
    return np.array([xyz_angles(R) for R in np.asarray(Rs, dtype=float)]).reshape(-1, 3)


def xyz_no_lock_all(Rs: Any) -> np.ndarray:
    """The mistake: the regular formula at the lock too, for a stack."""
    return np.array([xyz_no_lock(R) for R in np.asarray(Rs, dtype=float)]).reshape(-1, 3)


def rpy_formula_all(Rs: Any) -> np.ndarray:
    """The mistake: lecture 01 §7's roll, pitch, yaw, for a stack."""
    return np.array([rpy_formula(R) for R in np.asarray(Rs, dtype=float)]).reshape(-1, 3)


def xyz_other_branch_all(Rs: Any) -> np.ndarray:
    """The mistake: the other set (b outside [-π/2, π/2]), for a stack."""
    return np.array([xyz_other_branch(R) for R in np.asarray(Rs, dtype=float)]).reshape(-1, 3)


def xyz_threshold_all(Rs: Any, tol: float) -> np.ndarray:
    """The mistake: :func:`xyz_angles` of a stack with another lock threshold ``tol`` (0: only cos b == 0 locks)."""
    return np.array([xyz_angles(R, tol) for R in np.asarray(Rs, dtype=float)]).reshape(-1, 3)


def xyz_angles(R: Any, tol: float = XYZ_LOCK_TOL) -> np.ndarray:
    """(a, b, c) with Rx(a) Ry(b) Rz(c) = R, b in [-π/2, π/2]; at the gimbal lock (cos b < 1e-9) c = 0.

    From the product: r13 = sin b, (r23, r33) = cos b (-sin a, cos a), (r12, r11) = cos b (-sin c, cos c);
    at b = ±π/2 the product is Rx(a ± c) Ry(±π/2), whose (r21, r22) = (±sin(a ± c), cos(a ± c)).
    ``tol`` is the threshold (another one is a mistake: :func:`xyz_threshold_all`).
    """
    R = np.asarray(R, dtype=float)
    cb = float(np.hypot(R[0, 0], R[0, 1]))
    if cb < tol or (tol == 0.0 and cb == 0.0):
        up = R[0, 2] > 0
        a = np.arctan2(R[1, 0], R[1, 1]) if up else np.arctan2(-R[1, 0], R[1, 1])
        return np.array([a, np.pi / 2 if up else -np.pi / 2, 0.0])
    return np.array([np.arctan2(-R[1, 2], R[2, 2]), np.arctan2(R[0, 2], cb), np.arctan2(-R[0, 1], R[0, 0])])


def xyz_no_lock(R: Any) -> np.ndarray:
    """The mistake: the regular formula used at the lock too (atan2(0, 0) for a and c)."""
    R = np.asarray(R, dtype=float)
    cb = float(np.hypot(R[0, 0], R[0, 1]))
    return np.array([np.arctan2(-R[1, 2], R[2, 2]), np.arctan2(R[0, 2], cb), np.arctan2(-R[0, 1], R[0, 0])])


def rpy_formula(R: Any) -> np.ndarray:
    """The mistake: lecture 01 §7's roll, pitch, yaw (R = Rz(yaw) Ry(pitch) Rx(roll)) returned as (a, b, c)."""
    R = np.asarray(R, dtype=float)
    return np.array(
        [np.arctan2(R[2, 1], R[2, 2]), np.arctan2(-R[2, 0], np.hypot(R[0, 0], R[1, 0])), np.arctan2(R[1, 0], R[0, 0])]
    )


def xyz_other_branch(R: Any) -> np.ndarray:
    """The mistake: the other set (a + π, π - b, c + π), b outside [-π/2, π/2]."""
    a, b, c = xyz_angles(R)
    return np.array([a + np.pi, np.pi - b, c + np.pi])


# ---------------------------------------------------------------- ex02 q4: a standard-DH table rewritten
def modified_from_standard(table: Any) -> np.ndarray:
    """Craig's (modified) table of the chain a standard-DH table (rows α_i, a_i, θ_i, d_i, σ_i, α_n = a_n = 0)
    describes: the α and a columns move DOWN one row, α_0 = a_0 = 0."""
    t = np.asarray(table, dtype=float)
    out = t.copy()
    out[1:, :2], out[0, :2] = t[:-1, :2], 0.0
    return out


def moved_up(table: Any) -> np.ndarray:
    """The mistake: α and a moved UP one row (lecture 02 §8's rule for the other direction)."""
    t = np.asarray(table, dtype=float)
    out = t.copy()
    out[:-1, :2], out[-1, :2] = t[1:, :2], 0.0
    return out


# ---------------------------------------------------------------- ex01 q1-q4: the mistaken answers, rebuilt
# Each is the answer a named mistake gives, computed from the arguments: the feedback names the mistake only
# when the student's value equals it (``matches``). The right answers are in ``_reference.chains``.
_NOWHERE = np.full((3, 3), np.nan)  # equals nothing: the mistake does not apply to this case


def _axis_rotation(axis: str, angle: float) -> np.ndarray:
    """R_x, R_y or R_z (``axis`` "x", "y", "z") written out, numpy only."""
    c, s = math.cos(angle), math.sin(angle)
    return {
        "x": np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]),
        "y": np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]),
        "z": np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]),
    }[axis]


def turned_other_way(axis: str, angle: float) -> np.ndarray:
    """The mistake: the turn by -θ about the signed axis given (for "-x", R_x(+θ): the axis's sign ignored)."""
    sign = -1.0 if axis.startswith("-") else 1.0
    return _axis_rotation(axis[-1], -sign * float(angle))


def turned_about_unsigned_axis(axis: str, angle: float, only: str = "") -> np.ndarray:
    """:func:`turned_other_way` on a negative axis only (``only``: that one, e.g. "-x"): R_e(+θ) for "-e", the axis's
    sign left out."""
    return turned_other_way(axis, angle) if axis.startswith("-") and axis == (only or axis) else _NOWHERE


def turned_other_way_about_minus_y(axis: str, angle: float) -> np.ndarray:
    """:func:`turned_other_way` on the axis "-y" only (there it is also R_y with its sines swapped, sign handled)."""
    return turned_other_way(axis, angle) if axis == "-y" else _NOWHERE


def turned_other_way_about_y(axis: str, angle: float) -> np.ndarray:
    """:func:`turned_other_way` on the axis "y" only: R_y(-θ), R_y with its sines swapped."""
    return turned_other_way(axis, angle) if axis == "y" else _NOWHERE


def _unit(w: Any) -> np.ndarray:
    w = np.asarray(w, dtype=float).reshape(3)
    return w / np.linalg.norm(w)


def _turn(axis: Any, angle: float, normalise: bool = True) -> np.ndarray:
    """I + sin θ [a]x + (1 - cos θ) [a]x², the axis normalised or (the mistake) as given."""
    a = _unit(axis) if normalise else np.asarray(axis, dtype=float)
    S = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return np.eye(3) + math.sin(angle) * S + (1.0 - math.cos(angle)) * (S @ S)


def _parallel(u: Any, v: Any) -> bool:
    return bool(np.linalg.norm(np.cross(_unit(u), _unit(v))) < 1e-12)


def carried_unnormalised_axis(u: Any, v: Any) -> np.ndarray:
    """The mistake: the turn about u × v with the axis left at its length |u||v| sin θ (the angle right)."""
    if _parallel(u, v):
        return np.eye(3)
    a = np.cross(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
    s, c = np.linalg.norm(np.cross(_unit(u), _unit(v))), float(_unit(u) @ _unit(v))
    return _turn(a, math.atan2(s, c), normalise=False)


def carried_unnormalised_angle(u: Any, v: Any) -> np.ndarray:
    """The mistake: the angle arccos(u·v) of the vectors as given (clipped to [-1, 1]), the unit axis right."""
    if _parallel(u, v):
        return np.eye(3)
    u, v = np.asarray(u, dtype=float), np.asarray(v, dtype=float)
    return _turn(np.cross(u, v), math.acos(min(1.0, max(-1.0, float(u @ v)))))


def carried_back(u: Any, v: Any) -> np.ndarray:
    """The mistake: the smallest turn carrying v onto u (the arguments swapped), the transpose of the answer."""
    if _parallel(u, v):
        return np.eye(3)
    a, b = _unit(v), _unit(u)
    axis = np.cross(a, b)
    return _turn(axis, math.atan2(float(np.linalg.norm(axis)), float(a @ b)))


def _carried(u: Any, v: Any, how: str) -> np.ndarray:
    """The mistakes of the turn carrying u onto v written as a student writes them: the angle in degrees, the angle
    from arcsin |û × v̂| (never above 90°), Rodrigues' last term with a minus, the turn about u itself."""
    if _parallel(u, v):
        return np.eye(3)
    a, b = _unit(u), _unit(v)
    w = np.cross(a, b)
    angle = math.atan2(float(np.linalg.norm(w)), float(a @ b))
    if how == "degrees":
        return _turn(w, math.degrees(angle))
    if how == "arcsin":
        return _turn(w, math.asin(min(1.0, float(np.linalg.norm(w)))))
    if how == "about u":
        return _turn(a, angle)
    k = w / np.linalg.norm(w)
    S = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + math.sin(angle) * S - (1.0 - math.cos(angle)) * (S @ S)


def carried_in_degrees(u: Any, v: Any) -> np.ndarray:
    """The mistake: the right axis, the angle converted to degrees before the sines and cosines."""
    return _carried(u, v, "degrees")


def carried_arcsin(u: Any, v: Any) -> np.ndarray:
    """The mistake: the angle arcsin |û × v̂|, which is 180° - θ when u and v are more than 90° apart."""
    return _carried(u, v, "arcsin")


def carried_minus_square(u: Any, v: Any) -> np.ndarray:
    """The mistake: Rodrigues' formula with its last term subtracted, I + sin θ [k]x - (1 - cos θ) [k]x²."""
    return _carried(u, v, "minus")


def carried_about_u(u: Any, v: Any) -> np.ndarray:
    """The mistake: the turn about u itself by the angle between u and v (u does not move)."""
    return _carried(u, v, "about u")


def turn_the_other_way_round(R_a: Any, R_b: Any) -> np.ndarray:
    """The mistake: (k, 2π - θ), the turn about k the long way round (it is the turn by -θ)."""
    R_a, R_b = np.asarray(R_a, dtype=float), np.asarray(R_b, dtype=float)
    out = _axis_angle_of(R_b @ R_a.T)
    out[3] = 2.0 * math.pi - out[3]
    return out


def turn_b_then_a(R_a: Any, R_b: Any) -> np.ndarray:
    """The mistake: the axis and angle of R_bᵀ R_a (the turn back from {B} to {A}, in {B}'s coordinates)."""
    R_a, R_b = np.asarray(R_a, dtype=float), np.asarray(R_b, dtype=float)
    return _axis_angle_of(R_b.T @ R_a)


def _axis_angle_of(K: np.ndarray) -> np.ndarray:
    """[kx, ky, kz, θ] of a rotation with 0 < θ < π, from the antisymmetric part and the trace (numpy only)."""
    w = np.array([K[2, 1] - K[1, 2], K[0, 2] - K[2, 0], K[1, 0] - K[0, 1]])
    s, c = np.linalg.norm(w) / 2.0, (np.trace(K) - 1.0) / 2.0
    return np.append(w / (2.0 * s), math.atan2(s, c))


def turn_in_a_frame(R_a: Any, R_b: Any) -> np.ndarray:
    """The mistake: the axis and angle of ᴬR_B = R_aᵀ R_b, whose axis is written in {A}'s coordinates."""
    R_a, R_b = np.asarray(R_a, dtype=float), np.asarray(R_b, dtype=float)
    return _axis_angle_of(R_a.T @ R_b)


def turn_b_onto_a(R_a: Any, R_b: Any) -> np.ndarray:
    """The mistake: the axis and angle of R_a R_bᵀ, the turn carrying {B} onto {A} (the axis reversed)."""
    R_a, R_b = np.asarray(R_a, dtype=float), np.asarray(R_b, dtype=float)
    return _axis_angle_of(R_a @ R_b.T)


def _rigid_inverse(T: Any) -> np.ndarray:
    T = np.asarray(T, dtype=float)
    out = np.eye(4)
    out[:3, :3], out[:3, 3] = T[:3, :3].T, -T[:3, :3].T @ T[:3, 3]
    return out


def pose_of_a_in_b(T_a: Any, T_b: Any) -> np.ndarray:
    """The mistake: ᴮT_A = (⁰T_B)⁻¹ ⁰T_A, the frames swapped (the inverse of the answer)."""
    return _rigid_inverse(T_b) @ np.asarray(T_a, dtype=float)


def pose_other_order(T_a: Any, T_b: Any) -> np.ndarray:
    """The mistake: ⁰T_B (⁰T_A)⁻¹, the product in the other order."""
    return np.asarray(T_b, dtype=float) @ _rigid_inverse(T_a)


def pose_minus_p(T_a: Any, T_b: Any) -> np.ndarray:
    """The mistake: ⁰T_A inverted with the translation -p_A in place of -R_Aᵀ p_A, then times ⁰T_B."""
    T_a = np.asarray(T_a, dtype=float)
    inv = np.eye(4)
    inv[:3, :3], inv[:3, 3] = T_a[:3, :3].T, -T_a[:3, 3]
    return inv @ np.asarray(T_b, dtype=float)


def pose_base_difference(T_a: Any, T_b: Any) -> np.ndarray:
    """The mistake: the rotation R_aᵀ R_b right, the translation p_B - p_A left in the base frame's coordinates."""
    T_a, T_b = np.asarray(T_a, dtype=float), np.asarray(T_b, dtype=float)
    out = np.eye(4)
    out[:3, :3], out[:3, 3] = T_a[:3, :3].T @ T_b[:3, :3], T_b[:3, 3] - T_a[:3, 3]
    return out
