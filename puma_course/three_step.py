"""The three-step wrist-frame inverse kinematics of a 6R PUMA with a spherical wrist.

Source: section "2.3 Kinematics" of a Jupyter course (``002_4f9c5765fc8f1a1f.txt``).
The arm has a base joint θ0 about e_z, a shoulder θ1 and an elbow θ2 about the
horizontal axis ``a`` (eq. 4), an upper arm ℓ1 and a forearm ℓ2, the shoulder at
the origin and a 3-DOF wrist whose centre is ``w`` (eq. 1). It is moved from a
known state {θ̄0, θ̄1, θ̄2, F̄} to a target {w, F} in three rotations of the
wrist frame:

1. base: θ0 = atan2(w_y, w_x), rotation ``K_base = K(e_z, δ0)``, δ0 = θ0 - θ̄0 (eqs. 2-3);
2. arm: θ from the law of cosines (eq. 5), θ1 = φ ± θ with φ = atan2(w_z, hypot(w_x, w_y)),
   θ2 = ∓(π - β), rotation ``K_arm = K(a, δ)`` about a = (sin θ0, -cos θ0, 0),
   δ = (θ1 + θ2) - (θ̄1 + θ̄2) (eq. 4);
3. wrist: the composite rotation ``K_wrist = F F2^T`` that takes the step-2 frame F2
   onto the target frame F (the source's missing "(???)" equation).

Conventions. Radians. A wrist *frame* is a 3x3 rotation whose columns are the unit
vectors f1, f2, f3 written in base coordinates; a rotation K acts on it from the
left (``K @ F`` turns every column), so after the three steps
``K_wrist @ K_arm @ K_base @ F̄ == F``. "Elbow up" puts the elbow above the line
from the shoulder to the wrist centre (θ1 = φ + θ, θ2 ≤ 0); "elbow down" below it
(θ1 = φ - θ, θ2 ≥ 0). Only the "front" solutions are returned (θ0 points the arm
plane towards w); the reach-over-the-back pair θ0 + π is not considered, as in
the source.

>>> sol = solve([0.5, 0.5, 2.0], np.diag([-1.0, 1.0, -1.0]), 1.5, 1.0)
>>> round(float(np.degrees(sol.theta0)), 6), round(float(np.degrees(sol.theta1)), 4)
(45.0, 95.9034)
>>> np.allclose(wrist_position(sol.theta0, sol.theta1, sol.theta2, 1.5, 1.0), [0.5, 0.5, 2.0])
True
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ._validate import as_array, as_positive, as_rotation
from .transforms import axis_angle, rodrigues, zyz_from_rotation

__all__ = [
    "ArmState",
    "ThreeStepSolution",
    "Motion",
    "ThreeStepWarning",
    "solve",
    "motion",
    "joint_points",
    "wrist_position",
    "arm_axis",
    "as_state",
]

E_Z = np.array([0.0, 0.0, 1.0])


class ThreeStepWarning(UserWarning):
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


def arm_axis(theta0: Any) -> np.ndarray:
    """The shoulder/elbow axis a = (sin θ0, -cos θ0, 0) of eq. (4); (3,) or (N, 3).

    a = r̂ x e_z with r̂ = (cos θ0, sin θ0, 0) the horizontal direction of the arm
    plane, so a positive turn about ``a`` lifts r̂ towards e_z: it *increases* θ1.

    >>> np.round(rodrigues(arm_axis(0.0), np.pi / 2) @ [1, 0, 0], 12) + 0.0
    array([0., 0., 1.])
    """
    t = as_array(theta0, "theta0", what="an angle in radians (a number or an array of shape (N,))")
    return np.stack([np.sin(t), -np.cos(t), np.zeros_like(t)], axis=-1)


def joint_points(theta0: Any, theta1: Any, theta2: Any, l1: float, l2: float) -> np.ndarray:
    """Shoulder s, elbow e and wrist centre w of eq. (1), stacked as rows: (3, 3) or (N, 3, 3).

    s = 0, e = ℓ1 (cos θ0 cos θ1, sin θ0 cos θ1, sin θ1), w = e + ℓ2 (cos θ0 c12, sin θ0 c12, s12)
    with c12 = cos(θ1 + θ2), s12 = sin(θ1 + θ2). Angles broadcast (batch axis first).

    >>> joint_points(0.0, 0.0, 0.0, 1.5, 1.0)[:, 0]
    array([0. , 1.5, 2.5])
    """
    l1 = as_positive(l1, "l1")
    l2 = as_positive(l2, "l2")
    what = "an angle in radians (a number or an array of shape (N,))"
    t0, t1, t2 = (as_array(v, n, what=what) for v, n in ((theta0, "theta0"), (theta1, "theta1"), (theta2, "theta2")))
    t0, t1, t2 = np.broadcast_arrays(t0, t1, t2)
    c0, s0 = np.cos(t0), np.sin(t0)
    r_e, z_e = l1 * np.cos(t1), l1 * np.sin(t1)
    r_w, z_w = r_e + l2 * np.cos(t1 + t2), z_e + l2 * np.sin(t1 + t2)
    P = np.zeros(t0.shape + (3, 3))
    P[..., 1, :] = np.stack([c0 * r_e, s0 * r_e, z_e], axis=-1)
    P[..., 2, :] = np.stack([c0 * r_w, s0 * r_w, z_w], axis=-1)
    return P


def wrist_position(theta0: Any, theta1: Any, theta2: Any, l1: float, l2: float) -> np.ndarray:
    """The wrist centre w of eq. (1); (3,) or (N, 3).

    >>> np.round(wrist_position(np.pi / 2, np.pi / 2, 0.0, 1.5, 1.0), 12) + 0.0
    array([0. , 0. , 2.5])
    """
    return joint_points(theta0, theta1, theta2, l1, l2)[..., 2, :]


@dataclass(frozen=True, eq=False)
class ThreeStepSolution:
    """Everything the three-step procedure produces (angles in radians, frames as columns f1 f2 f3).

    ``K_wrist @ K_arm @ K_base @ start.frame == target`` and
    ``wrist_position(theta0, theta1, theta2, l1, l2) == w``. ``wrist_zyz`` are
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
            f"l3 = |w| = {round(float(np.linalg.norm(self.w)), digits):g}",
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


def _wrap(x: float) -> float:
    """Wrap an angle to (-π, π] (so that -π and π print the same everywhere)."""
    y = float(np.arctan2(np.sin(x), np.cos(x)))
    return np.pi if y <= -np.pi + 1e-12 else y


def solve(
    w: Any,
    target: Any,
    l1: float,
    l2: float,
    elbow: str = "up",
    start: Any = None,
) -> ThreeStepSolution:
    """Solve the three-step inverse problem: move {θ̄0, θ̄1, θ̄2, F̄} to {w, F} (source eqs. 1-5).

    ``w`` is the wrist centre (3,), ``target`` the target wrist frame F (3x3
    rotation, columns f1 f2 f3), ``l1``/``l2`` the upper arm and forearm,
    ``elbow`` ``"up"`` (θ1 = φ + θ, θ2 ≤ 0) or ``"down"`` (θ1 = φ - θ, θ2 ≥ 0),
    ``start`` the known state (see :func:`as_state`; default the straight arm
    {0, 0, 0, e_x, e_y, e_z}).

    Step 1 uses θ0 = atan2(w_y, w_x) (eq. 2 with its quadrant restored). Step 2
    computes θ of eq. (5), cos θ = (ℓ3² + ℓ1² - ℓ2²) / (2 ℓ1 ℓ3), ℓ3 = |w|, and
    the elbow's interior angle β, cos β = (ℓ1² + ℓ2² - ℓ3²) / (2 ℓ1 ℓ2), both as
    atan2 of (4·area of the triangle, numerator) for accuracy near a stretched
    arm; then θ2 = ∓(π - β). Step 3 is K_wrist = F F2^T.

    Singular targets: w on the base axis (w_x = w_y = 0) leaves θ0 free; θ̄0 is
    kept, ``singular`` says so and a :class:`ThreeStepWarning` is issued. w at
    the shoulder (possible only when ℓ1 = ℓ2) leaves θ1 free; θ̄1 is kept.
    Unreachable w, a target that is not a rotation, non-positive lengths or an
    unknown ``elbow`` raise ``ValueError``.

    >>> sol = solve([0.0, 2.5, 0.0], np.eye(3), 1.5, 1.0)
    >>> round(float(sol.theta0), 12), round(float(sol.theta1), 12), round(float(sol.theta2), 12)
    (1.570796326795, 0.0, 0.0)
    """
    w = as_array(w, "w", (3,), what="a wrist-centre position of shape (3,)")
    F = as_rotation(target, "target")
    l1 = as_positive(l1, "l1")
    l2 = as_positive(l2, "l2")
    if elbow not in ("up", "down"):
        raise ValueError(f"elbow: expected 'up' or 'down', got {elbow!r}")
    st = as_state(start)
    sign = 1.0 if elbow == "up" else -1.0
    tol = 1e-9 * (l1 + l2)
    singular: list[str] = []

    # ---- reachability: the triangle (l1, l2, l3) must close -------------------------------
    # |w| with math.hypot (correctly rounded, no BLAS kernel involved), then snapped: a wrist
    # within tol of the stretched (l1 + l2) or folded (|l1 - l2|) boundary is put on it, so
    # θ2 is exactly 0 or ±π there whatever the last bit of the input or of the CPU.
    l3 = math.hypot(float(w[0]), float(w[1]), float(w[2]))
    if l3 > l1 + l2 + tol:
        raise ValueError(
            f"w: unreachable, |w| = {l3:.6g} exceeds l1 + l2 = {l1 + l2:.6g} (the arm cannot stretch that far)"
        )
    if l3 < abs(l1 - l2) - tol:
        raise ValueError(
            f"w: unreachable, |w| = {l3:.6g} is less than |l1 - l2| = {abs(l1 - l2):.6g} "
            "(the arm cannot fold that tightly)"
        )
    stretched = abs(l3 - (l1 + l2)) <= tol
    folded = abs(l3 - abs(l1 - l2)) <= tol
    if stretched:
        l3 = l1 + l2
    elif folded:
        l3 = abs(l1 - l2)

    # ---- step 1: base angle (eq. 2, with atan2) --------------------------------------------
    rho = math.hypot(float(w[0]), float(w[1]))
    if rho <= tol:
        # w on the base axis (within tol): θ0 is free; the start value is kept (snapped, so the
        # choice does not hinge on the sign of a 1e-17 rounding residue)
        theta0 = st.theta0
        rho = 0.0
        singular.append("w lies on the base axis: theta0 is free, the start value theta0_bar is kept")
    else:
        theta0 = math.atan2(float(w[1]), float(w[0]))
    delta0 = theta0 - st.theta0
    K_base = rodrigues(E_Z, delta0)
    F1 = K_base @ st.frame

    # ---- step 2: shoulder and elbow (eq. 5 and the law of cosines) ---------------------------
    if l3 < tol:
        # w at the shoulder (l1 = l2): the elbow folds flat, θ1 is free.
        phi, theta, beta = 0.0, np.pi / 2, 0.0
        theta1 = st.theta1
        theta2 = -sign * np.pi
        singular.append("w is at the shoulder (l1 = l2): theta1 is free, the start value theta1_bar is kept")
    else:
        phi = math.atan2(float(w[2]), rho)
        if stretched:  # snapped: the triangle is flat, θ = 0 and the elbow is straight (β = π)
            theta, beta = 0.0, math.pi
        elif folded:  # snapped: flat the other way, β = 0; θ = 0 (l1 > l2) or π (l1 < l2)
            theta, beta = (0.0 if l1 >= l2 else math.pi), 0.0
        else:
            # 4 * area of the triangle with sides l1, l2, l3 (Heron, factored)
            q = (l1 + l2 + l3) * (-l1 + l2 + l3) * (l1 - l2 + l3) * (l1 + l2 - l3)
            four_area = math.sqrt(max(q, 0.0))
            theta = math.atan2(four_area, l3**2 + l1**2 - l2**2)  # cos θ as in eq. (5)
            beta = math.atan2(four_area, l1**2 + l2**2 - l3**2)  # interior angle at the elbow
        theta1 = _wrap(phi + sign * theta)
        theta2 = -sign * (np.pi - beta) + 0.0  # no -0.0
    delta = (theta1 + theta2) - (st.theta1 + st.theta2)
    a = arm_axis(theta0)
    K_arm = rodrigues(a, delta)
    F2 = K_arm @ F1

    # ---- step 3: the composite rotation that takes F2 onto the target --------------------
    K_wrist = F @ F2.T
    F3 = K_wrist @ F2
    axis, angle = axis_angle(K_wrist)
    zyz = np.array([_wrap(x) if i != 1 else x for i, x in enumerate(zyz_from_rotation(F2.T @ F))])

    if singular:
        warnings.warn("; ".join(singular), ThreeStepWarning, stacklevel=2)

    return ThreeStepSolution(
        w=_frozen(w),
        target=_frozen(F),
        l1=l1,
        l2=l2,
        elbow=elbow,
        start=st,
        theta0=theta0,
        phi=phi,
        theta=theta,
        beta=beta,
        theta1=float(theta1),
        theta2=float(theta2),
        delta0=float(delta0),
        delta=float(delta),
        a=_frozen(a),
        K_base=_frozen(K_base),
        K_arm=_frozen(K_arm),
        K_wrist=_frozen(K_wrist),
        frame_step1=_frozen(F1),
        frame_step2=_frozen(F2),
        frame_step3=_frozen(F3),
        axis=_frozen(axis),
        angle=float(angle),
        wrist_zyz=_frozen(zyz),
        singular=tuple(singular),
    )


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

    >>> sol = solve([0.5, 0.5, 2.0], np.diag([-1.0, 1.0, -1.0]), 1.5, 1.0)
    >>> m = motion(sol, steps_per_phase=4)
    >>> m.points.shape, np.allclose(m.frames[-1], sol.target), np.allclose(m.path[-1], sol.w)
    ((13, 3, 3), True, True)
    """
    if not isinstance(result, ThreeStepSolution):
        raise ValueError(f"result: expected the ThreeStepSolution returned by solve(), got {type(result).__name__}")
    if isinstance(steps_per_phase, bool) or not isinstance(steps_per_phase, (int, np.integer)) or steps_per_phase < 1:
        raise ValueError(f"steps_per_phase: expected a positive integer, got {steps_per_phase!r}")
    n = int(steps_per_phase)
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
    points = joint_points(th0, th1, th2, r.l1, r.l2)
    return Motion(
        points=_frozen(points),
        frames=_frozen(frames),
        joints=_frozen(joints),
        phase=_frozen_int(phase),
        fraction=_frozen(s_all),
    )
