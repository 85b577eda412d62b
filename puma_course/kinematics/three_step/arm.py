"""The three-step arm as a robot: a 6R PUMA with a spherical wrist and no offsets (source "2.3 Kinematics").

Joints q = (θ0, θ1, θ2, φ, ϑ, ψ): the base θ0 about e_z, the shoulder θ1 and the elbow θ2 about
the horizontal axis a (eq. 4), then a ZYZ wrist turning about its own moving axes. With the arm
frame F2 = Rz(θ0) Ry(-(θ1 + θ2)) (the wrist frame that the first two steps produce from the straight
start {0, 0, 0, e_x, e_y, e_z}), the pose is

    R = F2 Rz(φ) Ry(ϑ) Rz(ψ),   p = w(θ0, θ1, θ2) of eq. (1).

Inverse kinematics gives up to eight configurations: the arm plane "front" (θ0 towards w, the
source's) or "back" (θ0 + π, reaching over the top), elbow "up" or "down", wrist "noflip" (ϑ > 0)
or "flip" (φ + π, -ϑ, ψ + π).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..._validate import as_array, as_robot_length
from ...euler import EULER_SINGULAR_TOL, zyz_from_rotation
from ...transforms import wrap_angle
from .._ops import ARRAY, SCALAR
from ..dh import frame_array, split_q
from ..ik import IKBatch, IKSolutions
from ..robot import Robot
from .geometry import base_angle, points_eq1, triangle
from .procedure import ThreeStepSolution, solve_three_steps

__all__ = ["ThreeStepArm", "BRANCH_LABELS", "FLAG_KEYS", "MESSAGES"]

BRANCH_LABELS = tuple(f"{p}/{e}/{w}" for p in ("front", "back") for e in ("up", "down") for w in ("noflip", "flip"))
FLAG_KEYS = ("base_axis", "shoulder", "elbow", "wrist")
MESSAGES = {
    "base_axis": "w lies on the base axis: θ0 is free (its value in `near`, else 0) and front = back",
    "shoulder": "w is at the shoulder (possible only when l1 = l2): θ1 is free (its value in `near`, else 0)",
    "elbow": "the arm is fully stretched or folded (|w| = l1 + l2 or |l1 - l2|): elbow up and down coincide",
    "wrist": "ϑ = 0 or π: the first and last wrist axes are aligned, only φ ± ψ is defined (ψ from `near`, else 0)",
}
_PLANE = np.repeat([1.0, -1.0], 4)
_EL = np.tile(np.repeat([1.0, -1.0], 2), 2)
_WR = np.tile([1.0, -1.0], 4)


def _matmul3(o: Any, A: tuple[Any, ...], B: tuple[Any, ...]) -> tuple[Any, ...]:
    """Product of two 3x3 matrices given row by row as 9 entries (floats or arrays)."""
    return tuple(
        A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j] for i in range(3) for j in range(3)
    )


def _arm_frame(o: Any, t0: Any, t12: Any) -> tuple[Any, ...]:
    """F2 = Rz(θ0) Ry(-(θ1 + θ2)) as 9 entries."""
    ca, sa, cb, sb = o.cos(t0), o.sin(t0), o.cos(t12), -o.sin(t12)
    z = 0.0 * ca
    return ca * cb, -sa, ca * sb, sa * cb, ca, sa * sb, -sb, z, cb


def _zyz(o: Any, phi: Any, th: Any, psi: Any) -> tuple[Any, ...]:
    """Rz(φ) Ry(ϑ) Rz(ψ) as 9 entries."""
    cf, sf, ct, st, cp, sp = o.cos(phi), o.sin(phi), o.cos(th), o.sin(th), o.cos(psi), o.sin(psi)
    return (
        cf * ct * cp - sf * sp, -cf * ct * sp - sf * cp, cf * st,
        sf * ct * cp + cf * sp, -sf * ct * sp + cf * cp, sf * st,
        -st * cp, st * sp, ct,
    )  # fmt: skip


class ThreeStepArm(Robot):
    """The source's 6R PUMA (upper arm ``l1``, forearm ``l2``, unitless) as a robot.

    >>> arm = ThreeStepArm(1.5, 1.0)
    >>> np.round(arm.fk(np.zeros(6)), 12) + 0.0  # straight along x, wrist frame = identity
    array([[1. , 0. , 0. , 2.5],
           [0. , 1. , 0. , 0. ],
           [0. , 0. , 1. , 0. ],
           [0. , 0. , 0. , 1. ]])
    >>> sol = arm.ik(arm.fk(arm.q("qn")), near=arm.q("qn"))
    >>> len(sol), sol.labels[0]
    (8, 'front/up/noflip')
    """

    def __init__(self, l1: float = 1.5, l2: float = 1.0) -> None:
        self.l1 = as_robot_length(l1, "l1", positive=True)
        self.l2 = as_robot_length(l2, "l2", positive=True)
        self.name, self.units = "three-step arm", ""
        self._tol = 1e-9 * (self.l1 + self.l2)
        configs = {"qz": np.zeros(6), "qn": np.array([0.0, math.pi / 4, -math.pi / 2, 0.0, math.pi / 4, 0.0])}
        self._init_joints([True] * 6, configs, None, ("θ0", "θ1", "θ2", "φ", "ϑ", "ψ"))

    def parameters(self) -> dict[str, float]:
        """The upper arm ℓ1 and the forearm ℓ2."""
        return {"l1": self.l1, "l2": self.l2}

    # ---- geometry -------------------------------------------------------------------------
    def joint_points(self, theta0: Any, theta1: Any, theta2: Any) -> np.ndarray:
        """Shoulder s, elbow e and wrist centre w of eq. (1) as rows: (3, 3) or (N, 3, 3).

        >>> ThreeStepArm(1.5, 1.0).joint_points(0.0, 0.0, 0.0)[:, 0]
        array([0. , 1.5, 2.5])
        """
        what = "an angle in radians (a number or an array of shape (N,))"
        t = [as_array(v, n, what=what) for v, n in ((theta0, "theta0"), (theta1, "theta1"), (theta2, "theta2"))]
        for v, n in zip(t, ("theta0", "theta1", "theta2"), strict=True):
            if v.ndim > 1:
                raise ValueError(f"{n}: expected {what}, got an array of shape {v.shape}")
        try:
            t = list(np.broadcast_arrays(*t))
        except ValueError:
            shapes = [x.shape for x in t]
            raise ValueError(f"theta0, theta1, theta2: expected shapes that broadcast, got {shapes}") from None
        q = np.zeros(t[0].shape + (6,))
        q[..., 0], q[..., 1], q[..., 2] = t
        return self.points(q)

    def wrist_position(self, theta0: Any, theta1: Any, theta2: Any) -> np.ndarray:
        """The wrist centre w of eq. (1): (3,) or (N, 3).

        >>> np.round(ThreeStepArm(1.5, 1.0).wrist_position(np.pi / 2, np.pi / 2, 0.0), 12) + 0.0
        array([0. , 0. , 2.5])
        """
        return self.joint_points(theta0, theta1, theta2)[..., 2, :]

    def points(self, q: Any) -> np.ndarray:
        """Shoulder, elbow and wrist centre (eq. 1): (3, 3) or (N, 3, 3)."""
        q = self.check_q(q)
        e_w = points_eq1(ARRAY, q[..., 0], q[..., 1], q[..., 2], self.l1, self.l2)
        P = np.zeros(q.shape[:-1] + (3, 3))
        P[..., 1, :] = np.stack(e_w[:3], axis=-1)
        P[..., 2, :] = np.stack(e_w[3:], axis=-1)
        return P

    def fk(self, q: Any) -> np.ndarray:
        """Pose of the wrist: R = F2 Rz(φ) Ry(ϑ) Rz(ψ), p = w (eq. 1); (4, 4) or (N, 4, 4)."""
        cols, batch = split_q(q, 6, self.check_q)
        o = SCALAR if batch is None else ARRAY
        t0, t1, t2, phi, th, psi = cols
        R = _matmul3(o, _arm_frame(o, t0, t1 + t2), _zyz(o, phi, th, psi))
        w = points_eq1(o, t0, t1, t2, self.l1, self.l2)[3:]
        return frame_array(R[0:3] + (w[0],) + R[3:6] + (w[1],) + R[6:9] + (w[2],), batch)

    def frames(self, q: Any) -> np.ndarray:
        """Base, shoulder (Rz(θ0) Ry(-θ1) at s), elbow (F2 at e), wrist (the pose at w): (4, 4, 4) or (N, 4, 4, 4)."""
        q = self.check_q(q)
        P = self.points(q)
        o = ARRAY
        F = np.zeros(q.shape[:-1] + (4, 4, 4))
        F[..., :, 3, 3] = 1.0
        F[..., 0, :3, :3] = np.eye(3)
        F[..., 1, :3, :3] = np.reshape(np.stack(_arm_frame(o, q[..., 0], q[..., 1]), axis=-1), q.shape[:-1] + (3, 3))
        F[..., 2, :3, :3] = np.reshape(
            np.stack(_arm_frame(o, q[..., 0], q[..., 1] + q[..., 2]), axis=-1), q.shape[:-1] + (3, 3)
        )
        F[..., 2, :3, 3] = P[..., 1, :]
        F[..., 3, :, :] = self.fk(q)
        return F

    # ---- the lecture's procedure ---------------------------------------------------------
    def three_step(self, w: Any, target: Any, elbow: str = "up", start: Any = None) -> ThreeStepSolution:
        """Move the arm from ``start`` {θ̄0, θ̄1, θ̄2, F̄} to {w, F} in the source's three steps (eqs. 1-5).

        ``w`` is the wrist centre (3,), ``target`` the target wrist frame F (3x3 rotation, columns
        f1 f2 f3), ``elbow`` ``"up"`` or ``"down"``, ``start`` the known state (see
        :func:`.procedure.as_state`; default the straight arm {0, 0, 0, e_x, e_y, e_z}).

        >>> sol = ThreeStepArm(1.5, 1.0).three_step([0.5, 0.5, 2.0], np.diag([-1.0, 1.0, -1.0]))
        >>> round(float(np.degrees(sol.theta0)), 6), round(float(np.degrees(sol.theta1)), 4)
        (45.0, 95.9034)
        """
        return solve_three_steps(w, target, self.l1, self.l2, elbow, start)

    # ---- inverse kinematics --------------------------------------------------------------
    def ik(self, T: Any, near: Any = None) -> IKSolutions:
        """Every configuration reaching T: up to eight (front/back x elbow up/down x wrist noflip/flip).

        An unreachable wrist centre gives ``success`` False and the reason; singular poses
        (base axis, shoulder, stretched or folded elbow, aligned wrist axes) keep one
        representative per branch, with the free joint from ``near`` when given.
        """
        Tm = self._check_poses(T)
        if Tm.shape[0] != 1:
            raise ValueError(f"T: expected one pose (4, 4) (use ik_batch for several), got shape {Tm.shape}")
        nr = self._check_near(near)
        return self._finish(self._batch(Tm, None if nr is None else nr[None]).solutions(0), nr)

    def ik_batch(self, T: Any, near: Any = None) -> IKBatch:
        """All eight branches for N poses (N, 4, 4), vectorised.

        >>> arm = ThreeStepArm(1.5, 1.0)
        >>> b = arm.ik_batch(arm.fk(np.full((2, 6), 0.4)))
        >>> b.q.shape, b.valid.sum(axis=1).tolist()
        ((2, 8, 6), [8, 8])
        """
        Tb = self._check_poses(T)
        return self._batch(Tb, self._check_near(near, batch=Tb.shape[0]))

    def _batch(self, Tb: np.ndarray, nr: np.ndarray | None) -> IKBatch:
        o, l1, l2, tol = ARRAY, self.l1, self.l2, self._tol
        N = Tb.shape[0]
        wx, wy, wz = (Tb[:, i, 3, None] for i in range(3))
        l3 = np.hypot(np.hypot(wx, wy), wz)  # no BLAS kernel involved: the same bits on every machine
        reachable = (l3 <= l1 + l2 + tol) & (l3 >= abs(l1 - l2) - tol)
        t0, rho, on_axis = base_angle(o, wx, wy, tol, 0.0 if nr is None else nr[:, 0, None])
        at_shoulder = l3 < tol
        l3s, theta, beta, stretched, folded = triangle(o, l1, l2, l3, tol)
        r = _PLANE * rho  # the back plane sees w at -ρ
        sign = _EL * _PLANE  # elbow up is θ1 = φ + θ in front, φ - θ behind
        phi = np.arctan2(wz, r)
        t1 = np.where(at_shoulder, 0.0 if nr is None else nr[:, 1, None], phi + sign * theta)
        t2 = np.where(at_shoulder, -sign * math.pi, -sign * (math.pi - beta))
        t0b = t0 + np.where(_PLANE < 0, math.pi, 0.0)
        F2 = _arm_frame(o, t0b, t1 + t2)
        R = tuple(Tb[:, i, j, None] for i in range(3) for j in range(3))
        W = _matmul3(o, tuple(F2[3 * j + i] for i in range(3) for j in range(3)), R)  # F2^T R
        Wm = np.stack(np.broadcast_arrays(*W), axis=-1).reshape(N, 8, 3, 3)
        psi_rep = 0.0 if nr is None else np.broadcast_to(nr[:, 5, None], (N, 8)).reshape(-1)
        zyz = zyz_from_rotation(Wm.reshape(-1, 3, 3), psi=psi_rep).reshape(N, 8, 3)
        wrist = np.sin(zyz[..., 1]) < EULER_SINGULAR_TOL
        flip = _WR < 0
        phi_w = np.where(flip, zyz[..., 0] + math.pi, zyz[..., 0])
        th_w = np.where(flip, -zyz[..., 1], zyz[..., 1])
        psi_w = np.where(flip, zyz[..., 2] + math.pi, zyz[..., 2])
        q = np.stack(np.broadcast_arrays(t0b, t1, t2, phi_w, th_w, psi_w), axis=-1)
        q = np.where(reachable[..., None], wrap_angle(q), 0.0)
        elbow = stretched | folded
        valid = reachable & ~(on_axis & (_PLANE < 0)) & ~((elbow | at_shoulder) & (_EL < 0)) & ~(wrist & flip)
        flags = on_axis * 1 + at_shoulder * 2 + elbow * 4 + wrist * 8
        flags = np.where(valid, flags, 0).astype(np.int64)
        reason = np.where(
            reachable[:, 0], "",
            f"out of reach: the wrist centre must lie between |l1 - l2| = {abs(l1 - l2):g} and l1 + l2 = {l1 + l2:g} "
            "from the shoulder",
        ).astype(str)  # fmt: skip
        del l3s
        return IKBatch(q, valid, BRANCH_LABELS, flags, FLAG_KEYS, MESSAGES, reason, self.name, "closed form",
                       self.revolute, joints=self.joint_symbols)  # fmt: skip
