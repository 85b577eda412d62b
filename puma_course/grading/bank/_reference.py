"""The question bank's one window onto the kinematics layer: reference answers, inputs, answer keys.

Every call the bank makes into the course's kinematics (``rodrigues``, ``Puma560().fk``,
``MK3().fk``, ``Porter(...).fk/points/ik``, ``ThreeStepArm(...).three_step``, ...) is made
here, and so are the names of the package functions that answer a question (the "answer keys"
the worker trips on). When the kinematics API changes, this is the only file of the bank to
update; the exercise files only name what they ask for.

References run in the grader's process; their warnings (singular poses) are silenced, since the
bank's inputs avoid singularities and a warning would only clutter the grader's output.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from typing import Any

import numpy as np

from ... import transforms
from ...kinematics import MK3, Porter, Puma560, ThreeStepArm, dh
from ._inputs import unit_vectors

# ---------------------------------------------------------------- answer keys ("module:attr")
# Package functions that answer a question: calling them while that question is graded fails
# the case (see puma_course.grading.worker).
KEY_ROT = tuple(f"puma_course.transforms:{name}" for name in ("rotx", "roty", "rotz", "trotx", "troty", "trotz"))
KEY_RODRIGUES = ("puma_course.transforms:rodrigues", "puma_course.transforms:trot")
KEY_AXIS_ANGLE = ("puma_course.transforms:axis_angle",)
KEY_INVERSE = ("puma_course.transforms:inverse_transform",)
_DH = "puma_course.kinematics.dh"
KEY_MDH = (f"{_DH}:mdh", f"{_DH}:DHChain.link_matrices")
_KEY_CHAIN = (f"{_DH}:DHChain.fk", f"{_DH}:DHChain.frames", f"{_DH}:mdh", f"{_DH}:_walk")
KEY_PUMA = ("puma_course.kinematics.puma560:Puma560.fk", "puma_course.kinematics.puma560:_fk_entries", *_KEY_CHAIN)
KEY_MK3 = _KEY_CHAIN
_PORTER = "puma_course.kinematics.porter"
KEY_PORTER_FK = (
    f"{_PORTER}:Porter.fk",
    f"{_PORTER}:Porter.frames",
    "puma_course.kinematics.robot:Robot.points",
    f"{_PORTER}.fk:fk_entries",
    f"{_PORTER}.fk:frames_array",
)
KEY_PORTER_IK = (
    f"{_PORTER}:Porter.ik",
    f"{_PORTER}:Porter.ik_batch",
    f"{_PORTER}.explicit:branch",
    f"{_PORTER}.explicit:pose_terms",
    f"{_PORTER}.geometric:construct",
)
_TS = "puma_course.kinematics.three_step"
KEY_THREE_STEP = (
    f"{_TS}.arm:ThreeStepArm.three_step",
    f"{_TS}.arm:ThreeStepArm.ik",
    f"{_TS}.procedure:solve_three_steps",
    f"{_TS}.procedure:motion",
    f"{_TS}.geometry:arm_axis",
    f"{_TS}.geometry:triangle",
    f"{_TS}.geometry:base_angle",
)


# ---------------------------------------------------------------- exercise 1: rotations
def elementary_rotation(axis: str, angle: float) -> np.ndarray:
    """Rotation by ``angle`` about the coordinate axis ``"x"``, ``"y"`` or ``"z"``.

    >>> elementary_rotation("z", np.pi / 2).round(12) @ [1, 0, 0]
    array([0., 1., 0.])
    """
    table = {"x": transforms.rotx, "y": transforms.roty, "z": transforms.rotz}
    return table[axis](angle)


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


def random_rotations(rng: np.random.Generator, n: int, lo: float = 0.2, hi: float = 3.0) -> list[np.ndarray]:
    """``n`` rotations about random axes by angles drawn from [lo, hi)."""
    return [transforms.rodrigues(a, t) for a, t in zip(unit_vectors(rng, n), rng.uniform(lo, hi, n), strict=True)]


def random_transforms(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """``n`` one-argument cases, each a random rigid transform."""
    return [(transforms.homogeneous(R, rng.uniform(-2, 2, 3)),) for R in random_rotations(rng, n)]


# ---------------------------------------------------------------- exercises 2 and 3: DH chains
def mdh(alpha_prev: float, a_prev: float, theta: float, d: float) -> np.ndarray:
    """Craig's modified DH link matrix."""
    return dh.mdh(alpha_prev, a_prev, theta, d)


def puma_fk(q: np.ndarray) -> np.ndarray:
    """^0T_6 of the PUMA-560 (metres)."""
    return Puma560().fk(q)


def puma_frames(q: np.ndarray) -> np.ndarray:
    """^0T_i, i = 0..6, of the PUMA-560: shape (7, 4, 4)."""
    return Puma560().frames(q)


def mk3_fk(q: np.ndarray) -> np.ndarray:
    """^0T_5 of the Motoman MK3 (mm)."""
    return MK3().fk(q)


def mk3_position(q: np.ndarray) -> np.ndarray:
    """The MK3's tool position (mm)."""
    return mk3_fk(q)[:3, 3]


def mk3_tool_axis(q: np.ndarray) -> np.ndarray:
    """The MK3's tool axis z5."""
    return mk3_fk(q)[:3, 2]


# ---------------------------------------------------------------- exercises 4 and 5: Porter's chain
def _quiet(fn: Callable[..., Any], *args: Any) -> Any:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fn(*args)


def porter_fk(q: Any, l1: float, l3: float, l4: float) -> np.ndarray:
    """F05 of Porter's chain."""
    return Porter(l1, l3, l4).fk(q)


def porter_points(q: Any, l1: float, l3: float, l4: float) -> np.ndarray:
    """The joint points p0 ... p5 of Porter's chain: shape (6, 3)."""
    return Porter(l1, l3, l4).points(q)


def porter_z5(q: Any, l1: float, l3: float, l4: float) -> np.ndarray:
    """The tool axis z5 of Porter's chain."""
    return porter_fk(q, l1, l3, l4)[:3, 2]


def porter_wrist_point(T: Any, l4: float) -> np.ndarray:
    """The wrist point p4 = p5 - l4 x5 of an end-effector pose (no kinematics call: the formula itself)."""
    T = np.asarray(T, dtype=float)
    return T[:3, 3] - l4 * T[:3, 0]


def porter_ik_explicit(T: Any, l1: float, l3: float, l4: float) -> np.ndarray:
    """Every configuration reaching T (Porter's Ver.1): shape (k, 6)."""
    return np.asarray(_quiet(Porter(l1, l3, l4).ik, T))


def porter_ik_geometric(T: Any, l1: float, l3: float, l4: float) -> np.ndarray:
    """Porter's Ver.2 pair: shape (2, 6)."""
    return np.asarray(_quiet(lambda: Porter(l1, l3, l4).ik(T, method="geometric")))


def porter_configs(rng: np.random.Generator, n: int) -> list[tuple[np.ndarray, float, float, float]]:
    """Configurations in general position (|cos α4| >= 0.3, q2 >= 0.3, wrist point off the z0 axis)."""
    out: list[tuple[np.ndarray, float, float, float]] = []
    while len(out) < n:
        q = rng.uniform(0.0, 2 * np.pi, 6)
        q[2] = rng.uniform(0.3, 2.0)
        l1, l3, l4 = (float(x) for x in rng.uniform(0.3, 1.5, 3))
        p4 = Porter(l1, l3, l4).points(q)[4]
        if abs(np.cos(q[4])) >= 0.3 and np.hypot(p4[0], p4[1]) > 0.2:
            out.append((q, l1, l3, l4))
    return out


def porter_poses(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """Cases (T, l1, l3, l4) with T reached from a configuration in general position."""
    return [(Porter(l1, l3, l4).fk(q), l1, l3, l4) for q, l1, l3, l4 in porter_configs(rng, n)]


def porter_pose(q: Any, l1: float, l3: float, l4: float) -> tuple[Any, ...]:
    """The case (F05(q), l1, l3, l4)."""
    return (Porter(l1, l3, l4).fk(q), l1, l3, l4)


# ---------------------------------------------------------------- exercise 6: the three-step procedure
def three_step_solution(*fields: str) -> Callable[..., Any]:
    """A reference from ``ThreeStepArm(l1, l2).three_step`` (elbow up) for args (w), (w, l1, l2) or (w, F, l1, l2).

    ``fields`` name the attributes of the solution to return (one: that value; several: an array of
    them): theta0, frame_step1, theta, theta1, theta2, frame_step2, K_wrist.

    >>> float(three_step_solution("theta0")(np.array([0.5, 0.5, 2.0])))  # w at 45 degrees
    0.7853981633974483
    """

    def ref(w: Any, *rest: Any) -> Any:
        w = np.asarray(w, dtype=float)
        if len(rest) == 3:
            target, l1, l2 = rest
        elif len(rest) == 2:
            target, (l1, l2) = np.eye(3), rest
        else:  # step 1 does not depend on the lengths; pick any that reach w
            target, l1, l2 = np.eye(3), math.hypot(*w.tolist()), math.hypot(*w.tolist())
        sol = _quiet(lambda: ThreeStepArm(l1, l2).three_step(w, target, elbow="up"))
        values = [np.asarray(getattr(sol, f), dtype=float) for f in fields]
        return values[0] if len(values) == 1 else np.array(values)

    return ref
