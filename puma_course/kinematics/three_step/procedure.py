"""The three-step procedure of the source ("2.3 Kinematics", eqs. 1-5) for one target, and its animation.

The arm is moved from a known state {θ̄0, θ̄1, θ̄2, F̄} to a target {w, F} in three rotations of the
wrist frame:

1. base: θ0 = atan2(w_y, w_x), rotation K_base = K(e_z, δ0), δ0 = θ0 - θ̄0 (eqs. 2-3);
2. arm: θ from the law of cosines (eq. 5), θ1 = φ ± θ with φ = atan2(w_z, hypot(w_x, w_y)),
   θ2 = ∓(π - β), rotation K_arm = K(a, δ) about a = (sin θ0, -cos θ0, 0),
   δ = (θ1 + θ2) - (θ̄1 + θ̄2) (eq. 4);
3. wrist: the composite rotation K_wrist = F F2^T that takes the step-2 frame F2 onto the target
   frame F (the source's missing "(???)" equation).

Conventions. Radians. A wrist *frame* is a 3x3 rotation whose columns are the unit vectors f1, f2,
f3 in base coordinates; a rotation K acts on it from the left (K @ F turns every column), so after
the three steps K_wrist @ K_arm @ K_base @ F̄ == F. "Elbow up" puts the elbow above the line from
the shoulder to the wrist centre (θ1 = φ + θ, θ2 <= 0); "elbow down" below it. Only the "front"
solutions are the source's (θ0 points the arm plane towards w); :class:`.arm.ThreeStepArm.ik`
also gives the reach over the back.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..._validate import MAX_MAGNITUDE, as_array, as_choice, as_count, as_robot_length, as_rotation
from ...euler import zyz_from_rotation
from ...transforms import axis_angle, rodrigues, wrap_angle
from .._ops import ARRAY, SCALAR
from ..ik import KinematicsWarning
from .geometry import arm_axis, base_angle, points_eq1, triangle

__all__ = ["ArmState", "ThreeStepSolution", "Motion", "ThreeStepWarning", "solve_three_steps", "motion", "as_state"]

E_Z = np.array([0.0, 0.0, 1.0])


class ThreeStepWarning(KinematicsWarning):
    """A singular target: a joint angle was not determined and a representative was kept."""


def _frozen(a: Any) -> np.ndarray:
    out = np.array(a, dtype=float)
    out.setflags(write=False)
    return out


def _frozen_int(a: Any) -> np.ndarray:
    out = np.array(a, dtype=int)
    out.setflags(write=False)
    return out


@dataclass(frozen=True, eq=False)
class ArmState:
    """A configuration {θ0, θ1, θ2, F}: three arm joint angles (radians) and the wrist frame.

    ``frame`` is a 3x3 rotation whose columns are f1, f2, f3 in base coordinates.
    The default is the source's straight-arm start {0, 0, 0, e_x, e_y, e_z}.

    >>> ArmState().frame.tolist() == np.eye(3).tolist()
    True
    """

    theta0: float = 0.0
    theta1: float = 0.0
    theta2: float = 0.0
    frame: np.ndarray = field(default_factory=lambda: _frozen(np.eye(3)))

    def __post_init__(self) -> None:
        for name in ("theta0", "theta1", "theta2"):
            value = as_array(getattr(self, name), f"start.{name}", (), what="an angle in radians (a number)")
            object.__setattr__(self, name, float(value))
        object.__setattr__(self, "frame", _frozen(as_rotation(self.frame, "start.frame")))

    @property
    def joints(self) -> np.ndarray:
        """(θ0, θ1, θ2) as an array."""
        return np.array([self.theta0, self.theta1, self.theta2])


def as_state(start: Any) -> ArmState:
    """Read a start configuration given as ``None``, :class:`ArmState`, a dict or a tuple.

    Accepted forms: ``None`` (the straight arm {0, 0, 0, e_x, e_y, e_z});
    an :class:`ArmState`; a mapping with keys ``theta0, theta1, theta2`` and
    ``frame`` (or ``F``), missing keys taking the defaults; a 4-tuple
    ``(θ0, θ1, θ2, F)``; or the source's 6-tuple ``(θ0, θ1, θ2, f1, f2, f3)``
    with the frame's columns given one by one.

    >>> as_state((0.1, 0.2, 0.3, [1, 0, 0], [0, 1, 0], [0, 0, 1])).theta2
    0.3
    """
    if start is None:
        return ArmState()
    if isinstance(start, ArmState):
        return start
    if isinstance(start, Mapping):
        unknown = set(start) - {"theta0", "theta1", "theta2", "frame", "F"}
        if unknown:
            raise ValueError(
                f"start: expected keys theta0, theta1, theta2, frame (or F), got unknown key(s) {sorted(unknown)}"
            )
        frame = start.get("frame", start.get("F", np.eye(3)))
        return ArmState(start.get("theta0", 0.0), start.get("theta1", 0.0), start.get("theta2", 0.0), frame)
    if isinstance(start, (tuple, list)):
        if len(start) == 4:
            return ArmState(*start)
        if len(start) == 6:
            cols = [as_array(f, f"start f{i + 1}", (3,)) for i, f in enumerate(start[3:])]
            return ArmState(start[0], start[1], start[2], np.column_stack(cols))
        raise ValueError(
            f"start: expected (theta0, theta1, theta2, F) or (theta0, theta1, theta2, f1, f2, f3), "
            f"got a sequence of length {len(start)}"
        )
    raise ValueError(
        f"start: expected None, an ArmState, a dict or a tuple (theta0, theta1, theta2, F), got {type(start).__name__}"
    )


@dataclass(frozen=True, eq=False)
class ThreeStepSolution:
    """Everything the three-step procedure produces (angles in radians, frames as columns f1 f2 f3).

    ``K_wrist @ K_arm @ K_base @ start.frame == target`` and
    ``arm.wrist_position(theta0, theta1, theta2) == w``. ``wrist_zyz`` are
    ZYZ angles (φ, ϑ, ψ) of the target frame *relative to the step-2 frame*:
    F2^T F = Rz(φ) Ry(ϑ) Rz(ψ), i.e. F = F2 Rz(φ) Ry(ϑ) Rz(ψ) (turns about the
    wrist's own moving axes, the way a ZYZ spherical wrist turns). ``singular``
    lists any joint angle that the target leaves undetermined and the
    representative kept (empty for a regular target).
    """

    w: np.ndarray
    target: np.ndarray
    l1: float
    l2: float
    elbow: str
    start: ArmState
    theta0: float
    phi: float
    theta: float
    beta: float
    theta1: float
    theta2: float
    delta0: float
    delta: float
    a: np.ndarray
    K_base: np.ndarray
    K_arm: np.ndarray
    K_wrist: np.ndarray
    frame_step1: np.ndarray
    frame_step2: np.ndarray
    frame_step3: np.ndarray
    axis: np.ndarray
    angle: float
    wrist_zyz: np.ndarray
    singular: tuple[str, ...] = ()

    @property
    def joints(self) -> np.ndarray:
        """The arm joint angles (θ0, θ1, θ2) that reach w."""
        return np.array([self.theta0, self.theta1, self.theta2])

    @property
    def end(self) -> ArmState:
        """The final state {θ0, θ1, θ2, F} (F = the step-3 frame)."""
        return ArmState(self.theta0, self.theta1, self.theta2, self.frame_step3)

    def summary(self, digits: int = 4) -> str:
        """A plain-text table of the numbers of the three steps (angles also in degrees)."""

        def ang(x: float) -> str:
            return f"{round(float(x), digits) + 0.0: .{digits}f} rad = {round(float(np.degrees(x)), 2) + 0.0: .2f} deg"

        def vec(v: Any) -> str:
            return np.array2string(np.round(np.asarray(v), digits) + 0.0, precision=digits, suppress_small=True)

        lines = [
            f"elbow {self.elbow}: w = {vec(self.w)}, l1 = {self.l1:g}, l2 = {self.l2:g}, "
            f"l3 = |w| = {round(math.hypot(*(float(v) for v in self.w)), digits):g}",
            f"step 1  theta0 = {ang(self.theta0)}   delta0 = {ang(self.delta0)}",
            f"step 2  phi    = {ang(self.phi)}   theta  = {ang(self.theta)}",
            f"        theta1 = {ang(self.theta1)}   theta2 = {ang(self.theta2)}",
            f"        a = {vec(self.a)}   delta = {ang(self.delta)}",
            f"step 3  axis = {vec(self.axis)}   angle = {ang(self.angle)}",
            f"        wrist ZYZ (phi, theta, psi) [deg] = {vec(np.degrees(self.wrist_zyz))}",
        ]
        if self.singular:
            lines += [f"singular: {s}" for s in self.singular]
        return "\n".join(lines)


def solve_three_steps(
    w: Any, target: Any, l1: float, l2: float, elbow: str = "up", start: Any = None
) -> ThreeStepSolution:
    """The three-step procedure for one target {w, F} from the state ``start``.

    Step 1 uses θ0 = atan2(w_y, w_x) (eq. 2 with its quadrant restored). Step 2 computes θ of
    eq. (5) and the elbow's interior angle β from the triangle (ℓ1, ℓ2, ℓ3 = |w|); then
    θ2 = ∓(π - β). Step 3 is K_wrist = F F2^T.

    Boundaries are decided with the tolerance 1e-9 (ℓ1 + ℓ2) and snapped: a wrist that close to
    the stretched or folded reach is put on it (θ2 exactly 0 or ±π); that close to the base axis,
    θ0 is free and the start value is kept; at the shoulder (possible only when ℓ1 = ℓ2) θ1 is
    free and the start value is kept. Singular targets warn (:class:`ThreeStepWarning`) and say
    so in ``singular``. Unreachable w, a target that is not a rotation or an unknown ``elbow``
    raise ``ValueError``.
    """
    # checked here too: int8 lengths overflowed to "l1 + l2 = -56" (issue 21)
    l1, l2 = as_robot_length(l1, "l1", positive=True), as_robot_length(l2, "l2", positive=True)
    w = as_array(w, "w", (3,), what="a wrist-centre position of shape (3,)", max_magnitude=MAX_MAGNITUDE)
    F = as_rotation(target, "target")
    elbow = as_choice(elbow, "elbow", ("up", "down"))
    st = as_state(start)
    sign = 1.0 if elbow == "up" else -1.0
    tol = 1e-9 * (l1 + l2)
    singular: list[str] = []
    wx, wy, wz = (float(v) for v in w)

    # ---- reachability: the triangle (l1, l2, l3) must close -------------------------------
    l3 = math.hypot(wx, wy, wz)  # correctly rounded, no BLAS kernel involved
    if l3 > l1 + l2 + tol:
        raise ValueError(
            f"w: expected a wrist centre within reach, got an unreachable one: |w| = {l3:.6g} exceeds "
            f"l1 + l2 = {l1 + l2:.6g} (the arm cannot stretch that far)"
        )
    if l3 < abs(l1 - l2) - tol:
        raise ValueError(
            f"w: expected a wrist centre within reach, got an unreachable one: |w| = {l3:.6g} is less than "
            f"|l1 - l2| = {abs(l1 - l2):.6g} (the arm cannot fold that tightly)"
        )

    # ---- step 1: base angle (eq. 2, with atan2) --------------------------------------------
    theta0, rho, on_axis = base_angle(SCALAR, wx, wy, tol, st.theta0)
    if on_axis:
        singular.append("w lies on the base axis: theta0 is free, the start value theta0_bar is kept")
    delta0 = theta0 - st.theta0
    K_base = rodrigues(E_Z, delta0)
    F1 = K_base @ st.frame

    # ---- step 2: shoulder and elbow (eq. 5 and the law of cosines) ---------------------------
    if l3 < tol:  # w at the shoulder (l1 = l2): the elbow folds flat, θ1 is free
        phi, theta, beta = 0.0, math.pi / 2, 0.0
        theta1 = st.theta1
        theta2 = -sign * math.pi
        singular.append("w is at the shoulder (l1 = l2): theta1 is free, the start value theta1_bar is kept")
    else:
        phi = math.atan2(wz, rho)
        _, theta, beta, _, _ = triangle(SCALAR, l1, l2, l3, tol)
        theta1 = wrap_angle(phi + sign * theta)
        theta2 = -sign * (math.pi - beta) + 0.0  # no -0.0
    delta = (theta1 + theta2) - (st.theta1 + st.theta2)
    a = arm_axis(theta0)
    K_arm = rodrigues(a, delta)
    F2 = K_arm @ F1

    # ---- step 3: the composite rotation that takes F2 onto the target --------------------
    K_wrist = F @ F2.T
    F3 = K_wrist @ F2
    axis, angle = axis_angle(K_wrist)
    zyz = zyz_from_rotation(F2.T @ F)
    zyz[[0, 2]] = wrap_angle(zyz[[0, 2]])

    if singular:
        warnings.warn("; ".join(singular), ThreeStepWarning, stacklevel=3)

    return ThreeStepSolution(
        w=_frozen(w), target=_frozen(F), l1=l1, l2=l2, elbow=elbow, start=st, theta0=theta0, phi=phi, theta=theta,
        beta=beta, theta1=float(theta1), theta2=float(theta2), delta0=float(delta0), delta=float(delta),
        a=_frozen(a), K_base=_frozen(K_base), K_arm=_frozen(K_arm), K_wrist=_frozen(K_wrist), frame_step1=_frozen(F1),
        frame_step2=_frozen(F2), frame_step3=_frozen(F3), axis=_frozen(axis), angle=float(angle),
        wrist_zyz=_frozen(zyz), singular=tuple(singular),
    )  # fmt: skip


@dataclass(frozen=True, eq=False)
class Motion:
    """The three-step motion sampled in time: T = 3 n + 1 samples for n steps per phase.

    ``points`` (T, 3, 3): rows s, e, w of eq. (1) at each sample; ``frames``
    (T, 3, 3): the wrist frame (columns f1 f2 f3); ``joints`` (T, 3): θ0, θ1, θ2;
    ``phase`` (T,): 0 at the start, then 1, 2, 3 for the step being carried out;
    ``fraction`` (T,): how far through its phase each sample is (0..1).
    """

    points: np.ndarray
    frames: np.ndarray
    joints: np.ndarray
    phase: np.ndarray
    fraction: np.ndarray

    @property
    def path(self) -> np.ndarray:
        """The wrist centre's path (T, 3) (the source's green path)."""
        return self.points[:, 2, :]

    @property
    def transforms(self) -> np.ndarray:
        """(T, 3, 4, 4) transforms at s, e, w, all carrying the wrist frame's rotation (for drawing)."""
        T = np.zeros(self.points.shape[:2] + (4, 4))
        T[..., :3, :3] = self.frames[:, None]
        T[..., :3, 3] = self.points
        T[..., 3, 3] = 1.0
        return T


def motion(result: ThreeStepSolution, steps_per_phase: int = 12) -> Motion:
    """Sample the three steps for an animation: base turn, arm turn, wrist turn.

    Phase 1 turns the base by s δ0 (s from 0 to 1) with θ1, θ2 at the start
    values and the frame K(e_z, s δ0) F̄; phase 2 moves θ1 and θ2 linearly to
    their final values, which turns the frame by K(a, s δ) F1; phase 3 keeps the
    arm still and turns the frame by K(axis, s·angle) F2. Vectorised over the
    samples; the first sample is the start, the last the target.

    >>> from puma_course.kinematics import ThreeStepArm
    >>> sol = ThreeStepArm(1.5, 1.0).three_step([0.5, 0.5, 2.0], np.diag([-1.0, 1.0, -1.0]))
    >>> m = motion(sol, steps_per_phase=4)
    >>> m.points.shape, np.allclose(m.frames[-1], sol.target), np.allclose(m.path[-1], sol.w)
    ((13, 3, 3), True, True)
    """
    if not isinstance(result, ThreeStepSolution):
        raise ValueError(
            f"result: expected the ThreeStepSolution returned by ThreeStepArm.three_step(), got {type(result).__name__}"
        )
    n = as_count(steps_per_phase, "steps_per_phase", minimum=1)
    r = result
    st = r.start
    s = np.arange(1, n + 1) / n
    s_all = np.concatenate([[0.0], s, s, s])
    phase = np.concatenate([[0], np.full(n, 1), np.full(n, 2), np.full(n, 3)])

    th0 = np.where(phase <= 1, st.theta0 + np.where(phase == 1, s_all, 0.0) * r.delta0, r.theta0)
    u = np.where(phase == 2, s_all, np.where(phase == 3, 1.0, 0.0))  # progress of the arm joints
    th1 = st.theta1 + u * (r.theta1 - st.theta1)
    th2 = st.theta2 + u * (r.theta2 - st.theta2)

    frames = np.empty((len(s_all), 3, 3))
    frames[0] = st.frame
    p1, p2, p3 = (phase == 1), (phase == 2), (phase == 3)
    frames[p1] = rodrigues(E_Z, s * r.delta0) @ st.frame
    frames[p2] = rodrigues(r.a, s * r.delta) @ r.frame_step1
    frames[p3] = rodrigues(r.axis, s * r.angle) @ r.frame_step2
    frames[-1] = r.frame_step3  # the exact target (not K(axis, angle) F2 rounded)

    joints = np.stack([th0, th1, th2], axis=-1)
    ex, ey, ez, wx, wy, wz = points_eq1(ARRAY, th0, th1, th2, r.l1, r.l2)
    points = np.zeros((len(s_all), 3, 3))
    points[:, 1] = np.stack([ex, ey, ez], axis=-1)
    points[:, 2] = np.stack([wx, wy, wz], axis=-1)
    return Motion(
        points=_frozen(points),
        frames=_frozen(frames),
        joints=_frozen(joints),
        phase=_frozen_int(phase),
        fraction=_frozen(s_all),
    )
