"""The three-step motion as a joint path of the six-joint arm, with the wrist step done two ways (lecture 08).

The arm's joints are q = (θ0, θ1, θ2, φ, ϑ, ψ) (:class:`.arm.ThreeStepArm`): the wrist frame is
F = Fa Rz(φ) Ry(ϑ) Rz(ψ), with the forearm's frame Fa = Rz(θ0) Ry(-(θ1 + θ2)). Steps 1 and 2 move the
arm joints only (:func:`.procedure.motion`), and the wrist joints keep their start values. Step 3
turns the wrist from the step-2 frame F2 onto the target F in one of two ways:

* ``wrist="geodesic"`` (the source's): the frame turns about the fixed axis of 𝒦 = F F2ᵀ at a steady
  rate, K(axis, s·angle) F2; the wrist joints are the ZYZ angles of each sampled frame relative to the
  forearm. This is the shortest turn of the frame, but where the ZYZ angles are singular (ϑ = 0, the
  straight wrist every three-step motion starts step 3 from) φ and ψ jump between two samples.
* ``wrist="joint"``: the wrist joints move on a straight line in joint space, q(s) = q_a + s Δq, from
  their start values to the goal's wrist solution nearest them (of the two ZYZ solutions (φ, ϑ, ψ)
  and (φ + π, -ϑ, ψ + π), the one at the smaller wrapped distance), Δq wrapped to (-π, π]. Every joint
  moves at most |Δq_i| / n per sample; the frame no longer turns about one fixed axis.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..._validate import MAX_MAGNITUDE, as_array, as_choice, as_count, describe
from ...euler import zyz_from_rotation
from ...transforms import wrap_angle
from .procedure import ThreeStepSolution, motion

__all__ = ["WRIST_MOTIONS", "forearm_frames", "motion_joints", "wrist_goal"]

#: the two ways of turning the wrist in step 3
WRIST_MOTIONS = ("geodesic", "joint")


def forearm_frames(joints: Any) -> np.ndarray:
    """The forearm's frame Fa = Rz(θ0) Ry(-(θ1 + θ2)) for arm joints (N, 3) (or (3,)): (N, 3, 3) (or (3, 3)).

    >>> np.round(forearm_frames([0.0, np.pi / 2, 0.0]), 12) + 0.0  # the arm pointing straight up
    array([[ 0.,  0., -1.],
           [ 0.,  1.,  0.],
           [ 1.,  0.,  0.]])
    """
    j = as_array(joints, "joints", (3,), batch=True, what="arm joints (θ0, θ1, θ2) as (3,) or (N, 3)",
                 max_magnitude=MAX_MAGNITUDE)  # fmt: skip
    t0, t12 = j[..., 0], j[..., 1] + j[..., 2]
    c0, s0, c, s = np.cos(t0), np.sin(t0), np.cos(t12), np.sin(t12)
    z = np.zeros_like(c0)
    rows = [[c0 * c, -s0, -c0 * s], [s0 * c, c0, -s0 * s], [s, z, c]]
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


def _check(result: Any) -> ThreeStepSolution:
    if not isinstance(result, ThreeStepSolution):
        raise ValueError(
            f"result: expected the ThreeStepSolution returned by ThreeStepArm.three_step(), got {type(result).__name__}"
        )
    return result


def wrist_goal(result: ThreeStepSolution, start: Any) -> np.ndarray:
    """The goal's wrist joints (φ, ϑ, ψ) nearest the wrist joints ``start`` (3,): wrapped distance, ties to ϑ >= 0.

    The two ZYZ solutions of F2ᵀ F are (φ, ϑ, ψ) with ϑ in [0, π] and (φ + π, -ϑ, ψ + π); at ϑ = 0 or π
    (only φ ± ψ defined) ψ keeps its start value.

    >>> from puma_course.kinematics import ThreeStepArm
    >>> sol = ThreeStepArm(1.5, 1.0).three_step([0.5, 0.5, 2.0], np.diag([-1.0, 1.0, -1.0]))
    >>> np.round(np.degrees(wrist_goal(sol, np.zeros(3))), 2) + 0.0  # not (180, 149.47, -135): that is farther
    array([   0.  , -149.47,   45.  ])
    """
    r = _check(result)
    try:
        a = as_array(start, "start", (3,), max_magnitude=MAX_MAGNITUDE)
    except ValueError as err:  # one message for every bad start, naming what a start is
        said = describe(start)
        raise ValueError(f"start: expected three finite wrist angles (φ, ϑ, ψ) in radians, got {said}") from err
    relative = forearm_frames(r.joints).T @ np.asarray(r.target)
    first = zyz_from_rotation(relative, psi=a[2])
    second = wrap_angle(first * np.array([1.0, -1.0, 1.0]) + np.array([math.pi, 0.0, math.pi]))
    d1, d2 = (float(np.linalg.norm(wrap_angle(c - a))) for c in (first, second))
    return first if d1 <= d2 or first[1] in (0.0, math.pi) else second


def motion_joints(result: ThreeStepSolution, steps_per_phase: int = 12, wrist: str = "geodesic") -> np.ndarray:
    """The three steps as joint vectors (3 n + 1, 6) of the six-joint arm; step 3 ``"geodesic"`` or ``"joint"``.

    Samples as :func:`.procedure.motion`: the start, then n per step. Steps 1 and 2 are the same for both
    choices. ``arm.fk`` of the first row is the start pose, of the last the target {w, F}.

    >>> from puma_course.kinematics import ThreeStepArm
    >>> sol = ThreeStepArm(1.5, 1.0).three_step([0.5, 0.5, 2.0], np.diag([-1.0, 1.0, -1.0]))
    >>> jumps = [np.abs(wrap_angle(np.diff(motion_joints(sol, 6, w), axis=0))).max() for w in WRIST_MOTIONS]
    >>> np.round(np.degrees(jumps), 1)  # the largest step of any joint between two samples
    array([158.8,  24.9])
    """
    r = _check(result)
    n = as_count(steps_per_phase, "steps_per_phase", minimum=1)
    how = as_choice(wrist, "wrist", WRIST_MOTIONS)
    m = motion(r, steps_per_phase=n)
    frames = np.array(m.frames)
    frames[-1] = r.target  # the exact target
    relative = np.swapaxes(forearm_frames(m.joints), -1, -2) @ frames
    q = np.column_stack([m.joints, zyz_from_rotation(relative)])  # geodesic: F = Fa Rz Ry Rz at every sample
    if how == "joint":
        q_a = q[2 * n]  # the end of step 2: the wrist still at its start angles
        goal = np.concatenate([q_a[:3], wrist_goal(r, q_a[3:])])
        s = np.arange(0, n + 1) / n
        q[2 * n :] = q_a + s[:, None] * wrap_angle(goal - q_a)[None, :]
    return q
