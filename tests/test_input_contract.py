"""The input contract, swept over every public function of the base and kinematics layers.

For every argument of every public callable the table below names a valid value and a *kind*
(an angle, a positive length, a 3-vector, a rotation, a transform, ...). The sweep replaces one
argument at a time by each bad value of its kind (text, None, booleans, NaN, infinity, complex
numbers, wrong shapes, empty arrays, values whose squares overflow, non-rigid matrices, unknown
words, fractional counts, tolerances that would switch checks off) and asserts the contract:

* a ``ValueError`` (never a TypeError, IndexError or numpy's own error, never NaN, never a result);
* whose message names the argument, says what was expected and what came.

``test_every_public_function_is_swept`` fails when a public name is neither in the table nor
exempted with a reason, so a new function cannot skip the contract.

Issue 21 made it systematic. ``test_every_public_callable_is_swept_by_identity`` enumerates
``puma_course.__all__``, ``transforms``, ``euler`` and every module of ``puma_course.kinematics``
(walked) plus each arm's public methods: 129 public callables, each a TABLE row (116 rows) or an
exemption with its reason. The counts (``test_the_sweep_counts_its_cases`` keeps them honest):

* 5,799 junk inputs: each argument gets its kind's bad values and the universal catalogue (None,
  text, bytes, booleans, NaN, ±inf, complex, objects, ragged lists, object arrays, empty arrays,
  dicts, NaN arrays); the answer is a ValueError naming the argument (an empty batch may instead
  give an empty result);
* 1,109 dtype cases: the valid numbers as int8/uint8/int64/object arrays, lists or numpy scalars
  give the float value's answer bit for bit, or a ValueError naming the argument;
* 70 pairs of batch arguments given batches of 2 and 3: a ValueError naming one of them.

Its first run failed 374 junk cases (a few dozen of them the table's own mistakes, the rest the
package's: TypeErrors and AttributeErrors, numpy's messages, NaN from ``wrap_angle``, tolerances of
1e-300 accepted, lengths, joint values and screws of 1e300 accepted, a max_iter of 10**12 accepted)
and 3 batch pairs (rodrigues, trot, actuator_rate: numpy's "could not be broadcast").
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import puma_course
from puma_course import euler, transforms
from puma_course.kinematics import MK3, DHChain, Link, Porter, Puma560, ThreeStepArm, dh, ik, mk3_reach, spaces
from puma_course.kinematics import frame_assignment as fa
from puma_course.kinematics import jacobian as jac
from puma_course.kinematics import standard_dh as sdh
from puma_course.kinematics import three_step as ts
from puma_course.kinematics import trajectories as tr
from puma_course.kinematics.porter import angle

# ---------------------------------------------------------------- the bad values, by kind
_REAL = ["abc", None, True, float("nan"), float("inf"), 1 + 2j]  # bad for any real input
BAD: dict[str, list[Any]] = {
    "angle": [*_REAL, [[0.1, 0.2]]],
    "angle_any": _REAL,  # arrays of any shape broadcast (mdh)
    "number": [*_REAL, [[1.0]]],
    "length": [*_REAL, 1e300, [1.0, 2.0]],
    "length_b": [*_REAL, 1e300, [[1.0, 2.0]]],  # (N,) batches allowed
    "length_any": [*_REAL, 1e300],  # arrays of any shape broadcast (mdh)
    "positive": [*_REAL, 1e300, 0.0, -1.0, [1.0, 2.0]],
    "vec3": [*_REAL, [np.nan, 0, 0], [1j, 0, 0], [1.0, 2.0], [], np.zeros((2, 2)), [1e300, 0, 0]],
    "vector": [*_REAL, [np.nan, 0, 0], [1j, 0, 0], [1.0, 2.0], [], np.zeros((2, 2))],  # a direction of any size
    "direction": [*_REAL, [np.nan, 0, 0], [1j, 0, 0], [1.0, 2.0], [], [0.0, 0.0, 0.0]],
    "rotation": [
        *_REAL,
        np.full((3, 3), np.nan),
        np.eye(3) * (1 + 1j),
        np.eye(2),
        [],
        2 * np.eye(3),
        np.diag([1.0, 1.0, -1.0]),
    ],  # fmt: skip
    "transform": [
        *_REAL,
        np.full((4, 4), np.nan),
        np.eye(4) * (1 + 1j),
        np.eye(3),
        np.ones((4, 4)),
        np.diag([2.0, 1.0, 1.0, 1.0]),
        np.diag([1.0, 1.0, -1.0, 1.0]),
        np.vstack([np.hstack([np.eye(3), [[1e300], [0], [0]]]), [[0, 0, 0, 1]]]),
    ],  # fmt: skip
    "q6": [*_REAL, [0.0] * 5, [0.0] * 5 + [np.nan], [0.0] * 5 + [1j], [], np.zeros((2, 5))],
    "q5": [*_REAL, [0.0] * 6, [0.0] * 4 + [np.inf], [0.0] * 4 + [1j], []],
    "q2": [*_REAL, [0.0] * 3, [0.0, np.nan], [0.0, 1j], []],
    "count": ["5", None, True, 2.5, -1, float("nan"), 1j, 1e300, 10**12],  # 1e300: not numpy's "Maximum size"
    "tol": ["1e-9", None, True, float("nan"), float("inf"), -1e-9, 0.0, 0.5, 1j],
    # issue 21: what the closed-form solvers cannot honour (fourth powers of lengths, tolerances below rounding)
    "robot_length": [*_REAL, 1e300, 1e100, -1e100, 1e-100, [1.0, 2.0]],
    "robot_positive": [*_REAL, 1e300, 1e100, 1e-100, 0.0, -1.0, [1.0, 2.0]],
    "ik_tol": ["1e-9", None, True, float("nan"), float("inf"), -1e-9, 0.0, 0.5, 1j, 1e-16, 1e-13],
    "duration": [*_REAL, 1e300, 0.0, -1.0, [1.0, 2.0], 1e-200, 1e100],
    "elbow": ["left", None, 1, np.array(["up", "down"])],
    "wrist_motion": ["spherical", None, 1, np.array(["joint"])],
    "method": ["numeric", None, 1, np.array(["explicit"])],
    "name": [None, 1, np.array([]), "nope"],
    "mask2": [[1, 0], [True], "ab", None],
    "path2": [*_REAL, [1.0, 2.0], [[np.nan, 0.0]], [[1j, 0.0]]],
    "poses": ["abc", None, np.eye(3), np.ones((2, 4, 4)), np.full((1, 4, 4), np.nan), np.eye(4) * (1 + 1j)],
    "path": ["abc", None, np.eye(3), np.ones((2, 4, 4)), np.full((1, 4, 4), np.nan), np.zeros((0, 4, 4))],
    "start": ["straight", 3, (0.0, 0.0), {"theta3": 0.0}, (0.0, 0.0, 0.0, np.diag([-1.0, 1.0, 1.0]))],
    "links": [[], [(0, 1, 0, 0)], "abc", None],
    "kind": ["X", None, 1],
    "robot": [None, "PUMA", object()],
    "result": [None, {"theta0": 0.0}],
    "scaling": ["cubic", None, 1, np.array(["quintic"])],
    "times2": [*_REAL, [0.0], [1.0, 0.0], [0.0, np.nan], [0.0, 1j]],
    "path3": [*_REAL, [[0.0, 0.0]], [[np.nan, 0, 0], [0, 0, 1]], [[1j, 0, 0], [0, 0, 1]], [0.0, 0.0, 1.0]],
    "kinds": [["R"], ["R", "X"], "RX", None],
    "stroke": [*_REAL, 8.0, 0.5, -1.0],
    "rows": [[], "abc", None, [(0.0, 0.0, 1.0)], [(0.0, 0.0, 1.0, 0.0, "X")], [(np.nan, 0.0, 1.0, 0.0, "R")]],
    # issue 31: the MK3's circle of wrist points (mk3_reach)
    "lengths5": [*_REAL, [1.0] * 4, [1.0] * 4 + [np.nan], [360.0, 135.0, 0.0, 215.0, 100.0], [1e300] * 5],
    "arcs": [*_REAL, [[0.0]], [[1.0, 0.0]], [[0.0, 7.0]], [[0.0, np.nan]], [[1e300, 1e300]]],
}

PUMA, MK3_, PORTER, TS = Puma560(), MK3(), Porter(1.0, 0.5, 0.3), ThreeStepArm(1.5, 1.0)
T_PUMA, T_MK3, T_PORTER, T_TS = (
    PUMA.fk(PUMA.q("qn")),
    MK3_.fk(MK3_.q("qr")),
    PORTER.fk(PORTER.q("qn")),
    TS.fk(TS.q("qn")),
)
PATH = tr.line_path(T_PUMA, T_PUMA[:3, 3] + [0.0, 0.02, 0.0], 3)
W, TARGET = np.array([0.5, 0.5, 2.0]), np.diag([-1.0, 1.0, -1.0])
SOL = TS.three_step(W, TARGET)

# ---------------------------------------------------------------- the table: name, call, [(arg, kind, valid)]
Arg = tuple[str, str, Any]
TABLE: list[tuple[str, Callable[..., Any], list[Arg]]] = [
    ("transforms.rotx", transforms.rotx, [("angle", "angle", 0.3)]),
    ("transforms.roty", transforms.roty, [("angle", "angle", 0.3)]),
    ("transforms.rotz", transforms.rotz, [("angle", "angle", 0.3)]),
    ("transforms.trotx", transforms.trotx, [("angle", "angle", 0.3)]),
    ("transforms.troty", transforms.troty, [("angle", "angle", 0.3)]),
    ("transforms.trotz", transforms.trotz, [("angle", "angle", 0.3)]),
    ("transforms.skew", transforms.skew, [("v", "vector", [1.0, 2.0, 3.0])]),
    ("transforms.rodrigues", transforms.rodrigues, [("axis", "direction", [0, 0, 1.0]), ("angle", "angle", 0.3)]),
    ("transforms.axis_angle", transforms.axis_angle, [("R", "rotation", np.eye(3))]),
    ("transforms.homogeneous", transforms.homogeneous, [("R", "rotation", np.eye(3)), ("p", "vec3", [1.0, 2, 3])]),
    ("transforms.transl", transforms.transl, [("p", "vec3", [1.0, 2, 3])]),
    ("transforms.transx", transforms.transx, [("d", "length_b", 0.3)]),
    ("transforms.transy", transforms.transy, [("d", "length_b", 0.3)]),
    ("transforms.transz", transforms.transz, [("d", "length_b", 0.3)]),
    (
        "transforms.trot",
        transforms.trot,
        [("axis", "direction", [0, 0, 1.0]), ("angle", "angle", 0.3), ("point", "vec3", [1.0, 0, 0])],
    ),  # fmt: skip
    ("transforms.inverse_transform", transforms.inverse_transform, [("T", "transform", np.eye(4))]),
    (
        "transforms.compose_moving",
        transforms.compose_moving,
        [("transforms[0]", "transform", np.eye(4)), ("transforms[1]", "transform", np.eye(4))],
    ),  # fmt: skip
    (
        "transforms.compose_fixed",
        transforms.compose_fixed,
        [("transforms[0]", "transform", np.eye(4)), ("transforms[1]", "transform", np.eye(4))],
    ),  # fmt: skip
    (
        "euler.rotation_from_zyz",
        euler.rotation_from_zyz,
        [("phi", "angle", 0.1), ("theta", "angle", 0.2), ("psi", "angle", 0.3)],
    ),  # fmt: skip
    ("euler.zyz_from_rotation", euler.zyz_from_rotation, [("R", "rotation", np.eye(3)), ("psi", "angle", 0.0)]),
    (
        "euler.rotation_from_rpy",
        euler.rotation_from_rpy,
        [("roll", "angle", 0.1), ("pitch", "angle", 0.2), ("yaw", "angle", 0.3)],
    ),  # fmt: skip
    ("euler.rpy_from_rotation", euler.rpy_from_rotation, [("R", "rotation", np.eye(3)), ("roll", "angle", 0.0)]),
    (
        "dh.mdh",
        dh.mdh,
        [
            ("alpha_prev", "angle_any", 0.1),
            ("a_prev", "length_any", 0.2),
            ("theta", "angle_any", 0.3),
            ("d", "length_any", 0.4),
        ],
    ),  # fmt: skip
    (
        "dh.Link",
        Link,
        [
            ("alpha_prev", "angle", 0.1),
            ("a_prev", "length", 0.2),
            ("d", "length", 0.3),
            ("theta", "angle", 0.0),
            ("kind", "kind", "R"),
        ],
    ),  # fmt: skip
    ("dh.DHChain", DHChain, [("links", "links", [Link(0, 0), Link(0, 1.0)])]),
    ("ik.joint_distance", ik.joint_distance, [("q", "q2", [0.1, 0.2]), ("q_ref", "q2", [0.0, 0.0])]),
    (
        "Puma560",
        Puma560,
        [
            ("a2", "robot_positive", 0.43),
            ("a3", "robot_length", 0.02),
            ("d3", "robot_length", 0.15),
            ("d4", "robot_length", 0.43),
        ],  # fmt: skip
    ),  # fmt: skip
    ("Puma560.fk", PUMA.fk, [("q", "q6", np.zeros(6))]),
    ("Puma560.frames", PUMA.frames, [("q", "q6", np.zeros(6))]),
    ("Puma560.points", PUMA.points, [("q", "q6", np.zeros(6))]),
    ("Puma560.ik", PUMA.ik, [("T", "transform", T_PUMA), ("near", "q6", np.zeros(6)), ("tol", "ik_tol", 1e-7)]),
    (
        "Puma560.ik_batch",
        PUMA.ik_batch,
        [("T", "poses", T_PUMA[None]), ("near", "q6", np.zeros(6)), ("tol", "ik_tol", 1e-7)],
    ),  # fmt: skip
    ("Puma560.q", PUMA.q, [("name", "name", "qn")]),
    (
        "MK3",
        MK3,
        [
            ("d1", "robot_length", 360.0),
            ("a1", "robot_length", 135.0),
            ("a2", "robot_positive", 250.0),
            ("a3", "robot_positive", 215.0),
            ("d5", "robot_length", 100.0),
        ],
    ),  # fmt: skip
    ("MK3.fk", MK3_.fk, [("q", "q5", np.zeros(5))]),
    ("MK3.ik", MK3_.ik, [("T", "transform", T_MK3), ("near", "q5", np.zeros(5)), ("tol", "ik_tol", 1e-9)]),
    ("MK3.ik_batch", MK3_.ik_batch, [("T", "poses", T_MK3[None]), ("tol", "ik_tol", 1e-9)]),
    (
        "Porter",
        Porter,
        [
            ("l1", "robot_positive", 1.0),
            ("l3", "robot_positive", 0.5),
            ("l4", "robot_positive", 0.3),
            ("q2_max", "robot_positive", 2.0),
        ],  # fmt: skip
    ),  # fmt: skip
    ("Porter.fk", PORTER.fk, [("q", "q6", np.zeros(6))]),
    ("Porter.frames", PORTER.frames, [("q", "q6", np.zeros(6))]),
    (
        "Porter.ik",
        PORTER.ik,
        [
            ("T", "transform", T_PORTER),
            ("near", "q6", np.ones(6)),
            ("method", "method", "geometric"),
            ("tol", "tol", 1e-12),
        ],
    ),  # fmt: skip
    ("Porter.ik_batch", PORTER.ik_batch, [("T", "poses", T_PORTER[None]), ("tol", "tol", 1e-12)]),
    ("Porter.classify", PORTER.classify, [("T", "transform", T_PORTER), ("tol", "tol", 1e-12)]),
    (
        "porter.angle",
        angle,
        [("v", "direction", [1.0, 0, 0]), ("w", "direction", [0, 1.0, 0]), ("n", "direction", [0, 0, 1.0])],
    ),  # fmt: skip
    ("ThreeStepArm", ThreeStepArm, [("l1", "robot_positive", 1.5), ("l2", "robot_positive", 1.0)]),
    ("ThreeStepArm.fk", TS.fk, [("q", "q6", np.zeros(6))]),
    ("ThreeStepArm.ik", TS.ik, [("T", "transform", T_TS), ("near", "q6", np.zeros(6))]),
    ("ThreeStepArm.ik_batch", TS.ik_batch, [("T", "poses", T_TS[None])]),
    (
        "ThreeStepArm.joint_points",
        TS.joint_points,
        [("theta0", "angle", 0.1), ("theta1", "angle", 0.2), ("theta2", "angle", 0.3)],
    ),  # fmt: skip
    (
        "ThreeStepArm.three_step",
        TS.three_step,
        [("w", "vec3", W), ("target", "rotation", TARGET), ("elbow", "elbow", "up"), ("start", "start", None)],
    ),  # fmt: skip
    ("three_step.arm_axis", ts.arm_axis, [("theta0", "angle", 0.3)]),
    ("three_step.as_state", ts.as_state, [("start", "start", None)]),
    ("three_step.motion", ts.motion, [("result", "result", SOL), ("steps_per_phase", "count", 4)]),
    (
        "three_step.motion_joints",
        ts.motion_joints,
        [("result", "result", SOL), ("steps_per_phase", "count", 4), ("wrist", "wrist_motion", "joint")],
    ),  # fmt: skip
    ("three_step.wrist_goal", ts.wrist_goal, [("result", "result", SOL), ("start", "q3", np.zeros(3))]),
    ("three_step.forearm_frames", ts.forearm_frames, [("joints", "q3", np.zeros(3))]),
    ("MK3.nearest_attainable", MK3_.nearest_attainable, [("T", "transform", T_MK3), ("tol", "tol", 1e-9)]),
    ("mk3_reach.wrist_arcs", mk3_reach.wrist_arcs,
     [("rho", "length", 400.0), ("pz", "length", 300.0), ("L", "lengths5", [360.0, 135.0, 250.0, 215.0, 100.0])]),
    ("mk3_reach.wrist_range", mk3_reach.wrist_range,
     [("rho", "length", 400.0), ("pz", "length", 300.0), ("L", "lengths5", [360.0, 135.0, 250.0, 215.0, 100.0])]),
    ("mk3_reach.nearest_on_arcs", mk3_reach.nearest_on_arcs,
     [("beta0", "number", 0.0), ("arcs", "arcs", [[0.5, 1.0]])]),
    (
        "three_step.ArmState",
        ts.ArmState,
        [
            ("theta0", "angle", 0.0),
            ("theta1", "angle", 0.0),
            ("theta2", "angle", 0.0),
            ("frame", "rotation", np.eye(3)),
        ],
    ),  # fmt: skip
    (
        "trajectories.line_path",
        tr.line_path,
        [("T0", "transform", np.eye(4)), ("T1", "vec3", [1.0, 0, 0]), ("n", "count", 5)],
    ),  # fmt: skip
    (
        "trajectories.circle_path",
        tr.circle_path,
        [
            ("center", "vec3", [0.0, 0, 0]),
            ("radius", "positive", 1.0),
            ("normal", "direction", [0, 0, 1.0]),
            ("R", "rotation", np.eye(3)),
            ("n", "count", 5),
            ("start", "direction", [1.0, 0, 0]),
        ],
    ),  # fmt: skip
    (
        "trajectories.follow",
        tr.follow,
        [("robot", "robot", PUMA), ("path_Ts", "path", PATH), ("q0", "q6", PUMA.q("qn"))],
    ),  # fmt: skip
    (
        "trajectories.naive",
        tr.naive,
        [("robot", "robot", PUMA), ("path_Ts", "path", PATH), ("q0", "q6", PUMA.q("qn"))],
    ),  # fmt: skip
    (
        "trajectories.time_scaling",
        tr.time_scaling,
        [("duration", "duration", 2.0), ("n", "count", 5), ("kind", "scaling", "quintic")],
    ),
    (
        "trajectories.joint_velocities",
        tr.joint_velocities,
        [("q", "path2", [[3.0, 1.0], [-3.0, 2.0]]), ("t", "times2", [0.0, 1.0]), ("revolute", "mask2", [True, False])],
    ),
    ("Puma560.jacobian", PUMA.jacobian, [("q", "q6", np.zeros(6))]),
    ("jacobian.geometric_jacobian", jac.geometric_jacobian, [("chain", "robot", PUMA), ("q", "q6", np.zeros(6))]),
    (
        "frame_assignment.common_normal",
        fa.common_normal,
        [
            ("p1", "vec3", [0.0, 0, 0]),
            ("u1", "direction", [0, 0, 1.0]),
            ("p2", "vec3", [1.0, 0, 5]),
            ("u2", "direction", [0, 1.0, 0]),
            ("tol", "tol", 1e-9),
        ],
    ),  # fmt: skip
    (
        "frame_assignment.dh_from_axes",
        fa.dh_from_axes,
        [
            ("points", "path3", [[0.0, 0, 0], [0, 0, 0]]),
            ("directions", "path3", [[0, 0, 1.0], [0, 1.0, 0]]),
            ("kinds", "kinds", ["R", "R"]),
        ],
    ),  # fmt: skip
    (
        "frame_assignment.frame_steps",
        fa.frame_steps,
        [
            ("points", "path3", [[0.0, 0, 0], [0, 0, 0.5]]),
            ("directions", "path3", [[0, 0, 1.0], [0, 1.0, 0]]),
            ("kinds", "kinds", ["R", "R"]),
            ("x0", "direction", [1.0, 0, 0]),
        ],
    ),  # fmt: skip
    (
        "frame_assignment.d_theta",
        fa.d_theta,
        [
            ("z", "direction", [0, 0, 1.0]),
            ("foot_prev", "vec3", [0, 0, 1.0]),
            ("x_prev", "direction", [1.0, 0, 0]),
            ("origin", "vec3", [0, 0, 3.0]),
            ("x", "direction", [0, 1.0, 0]),
        ],
    ),  # fmt: skip
    (
        "standard_dh.standard_dh",
        sdh.standard_dh,
        [("theta", "angle_any", 0.1), ("d", "length_any", 0.5), ("a", "length_any", 1.0), ("alpha", "angle_any", 0.0)],
    ),
    (
        "standard_dh.standard_from_modified",
        sdh.standard_from_modified,
        [("links", "links", [Link(0.0, 0.0), Link(-np.pi / 2, 0.0, 0.1)])],
    ),
    (
        "standard_dh.standard_fk",
        sdh.standard_fk,
        [("rows", "rows", [(0.0, 0.0, 1.0, 0.0, "R"), (0.0, 0.0, 1.0, 0.0, "R")]), ("q", "q2", [0.1, 0.2])],
    ),
    (
        "spaces.actuator_from_joint",
        spaces.actuator_from_joint,
        [("theta", "angle_any", 0.3), ("b", "positive", 3.0), ("c", "positive", 4.0), ("gamma0", "angle", 0.0)],
    ),
    (
        "spaces.joint_from_actuator",
        spaces.joint_from_actuator,
        [("s", "stroke", 5.0), ("b", "robot_positive", 3.0), ("c", "robot_positive", 4.0), ("gamma0", "angle", 0.0)],
    ),
    (
        "spaces.actuator_rate",
        spaces.actuator_rate,
        [
            ("theta", "angle_any", 0.3),
            ("theta_dot", "angle_any", 1.0),
            ("b", "positive", 3.0),
            ("c", "positive", 4.0),
            ("gamma0", "angle", 0.0),
        ],
    ),  # fmt: skip
    (
        "trajectories.joint_interpolation",
        tr.joint_interpolation,
        [("q0", "q2", [0.0, 1.0]), ("q1", "q2", [1.0, 2.0]), ("n", "count", 5), ("revolute", "mask2", [True, False])],
    ),  # fmt: skip
    (
        "jacobian.jacobian_from_axes",
        jac.jacobian_from_axes,
        [
            ("axes", "path3", [[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]]),
            ("points", "path3", [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]),
            ("pe", "vec3", [2.0, 0.0, 0.0]),
            ("revolute", "mask2", [True, False]),
        ],
    ),  # fmt: skip
    (
        "trajectories.unwrap",
        tr.unwrap,
        [("q", "path2", [[3.0, 1.0], [-3.0, 2.0]]), ("revolute", "mask2", [True, False])],
    ),  # fmt: skip
]

# issue 21: the three-step procedure itself (int8 lengths overflowed to "l1 + l2 = -56")
from puma_course.kinematics.three_step import procedure as ts_procedure  # noqa: E402

TABLE.append(
    (
        "procedure.solve_three_steps",
        ts_procedure.solve_three_steps,
        [("w", "vec3", [1.0, 0.5, 0.8]), ("target", "rotation", np.eye(3)), ("l1", "robot_positive", 1.5),
         ("l2", "robot_positive", 1.0), ("elbow", "elbow", "up"), ("start", "start", None)],
    )
)  # fmt: skip

# ---------------------------------------------------------------- issue 21: the rest of the public API
from puma_course.kinematics import numerical, poe, stations  # noqa: E402
from puma_course.kinematics.robot import MountedFk  # noqa: E402

BAD.update({
    "tol": [*BAD["tol"], -np.inf, 1e-300, 5e-324, 1e-16],  # below what float64 can honour (issue 21)
    "tol1": ["1e-9", None, True, float("nan"), float("inf"), -1e-9, 0.0, 2.0, 1j, 1e-300, 1e-16],  # up to 1
    "count": [*BAD["count"], -1e300, 2**70, -(2**70), np.int8(-1)],
    "count1": ["5", None, True, 2.5, 0, -1, float("nan"), 1j, 1e300, 10**12],  # at least 1
    "flag": ["yes", None, 1.5, float("nan"), np.array([True, False])],  # a True/False switch
    "fk": [None, "fk", 1.0, object()],  # a forward kinematics function
    "ets": ["abc", None, [("Rq", 1.0)], [("Rz", "q9")], [("Tx", np.nan)], [("Tx", 1e300)], [("Tx", 1j)], [1.0]],
    "qvec": [*_REAL, [[0.1]], [np.nan], [1j], [1e300]],  # joint values of any number (n,)
    "screw": [*_REAL, [0.0] * 6, [0, 0, 2.0, 0, 0, 0], [1.0, 0, 0], [np.nan] * 6, [0, 0, 1.0, 1e300, 0, 0]],
    "screws": [*_REAL, np.zeros((6, 6)), np.zeros((6, 5)), np.full((6, 6), np.nan)],
    "transform_opt": [t for t in BAD["transform"] if t is not None],  # None is the identity (the default)
    "rows6": [*_REAL, np.full((1, 6), np.nan), np.zeros((1, 6)) * 1j, [0.0] * 6, np.zeros((1, 1, 6)), [[1e300] * 6]],
    "names": [None, "ab", [1, 2], 1.0],  # names of flags, one per bit
    "planes": ["side", None, 1, np.array(["front"])],
    "words": [None, 1, b"x", ["arm"]],  # any text is a valid name
    "configurations": ["qz", None, {"qz": [0.0]}, {"qz": [np.nan, 0.0]}, {1: [0.0, 0.0]}],
    "qlim2": [*_REAL, [[0.0, 1.0]], [[1.0, 0.0], [0.0, 1.0]], [[np.nan, 1.0], [0.0, 1.0]]],
    "damping": [*_REAL, 0.0, -1.0, 1e300, [0.1, 0.2]],
})

# Porter's other arguments (q2_max is keyword-only, planes chooses which solutions)
TABLE.append(("Porter.ik.planes", PORTER.ik, [("T", "transform", T_PORTER), ("method", "method", "geometric"),
                                              ("planes", "planes", "both")]))
CHAIN = DHChain([Link(0, 0), Link(0, 1.0)])
TABLE.extend([
    ("transforms.wrap_angle", transforms.wrap_angle, [("angle", "angle_any", 0.3)]),
    ("transforms.is_rotation", transforms.is_rotation, [("R", "rotation", np.eye(3)), ("tol", "tol1", 1e-9)]),
    ("ik.IKSolutions", ik.IKSolutions, [("q", "rows6", np.zeros((1, 6)))]),
    ("ik.keys_from_bits", ik.keys_from_bits, [("bits", "count", 5), ("flag_keys", "names", ("a", "b", "c"))]),
    ("poe.ets_fk", poe.ets_fk, [("ets", "ets", [("Rz", "q0"), ("Tx", 1.0)]), ("q", "qvec", [0.3])]),
    ("poe.twist_exp", poe.twist_exp, [("S", "screw", [0, 0, 1.0, 0, -1.0, 0]), ("theta", "angle", 0.3)]),
    ("poe.poe_fk", poe.poe_fk, [("screws", "screws", poe.porter_screws(1.0, 0.5, 0.3)[0]),
                                ("M", "transform", poe.porter_screws(1.0, 0.5, 0.3)[1]), ("q", "q6", np.zeros(6))]),
    ("poe.porter_ets", poe.porter_ets, [("l1", "positive", 1.0), ("l3", "positive", 0.5), ("l4", "positive", 0.3)]),
    ("poe.porter_screws", poe.porter_screws, [("l1", "positive", 1.0), ("l3", "positive", 0.5),
                                              ("l4", "positive", 0.3)]),
    ("numerical.ik_dls", numerical.ik_dls, [
        ("robot", "robot", PUMA), ("T", "transform", T_PUMA), ("q0", "q6", PUMA.q("qn") + 0.01),
        ("damping", "damping", 0.05), ("length", "positive", 1.0), ("tol", "tol", 1e-9), ("max_iter", "count1", 50)]),
    ("stations.world_pose", stations.world_pose, [("base", "transform_opt", np.eye(4)),
                                                  ("arm_pose", "transform", T_PUMA), ("tool", "transform_opt", None)]),
    ("stations.arm_target", stations.arm_target, [("world_T", "transform", T_PUMA), ("base", "transform_opt", None),
                                                  ("tool", "transform_opt", None)]),
    ("robot.MountedFk", MountedFk, [("fk", "fk", PUMA.fk), ("base", "transform_opt", None),
                                    ("tool", "transform_opt", None), ("pad", "count", 0),
                                    ("position_only", "flag", False)]),
    ("robot.MountedFk.__call__", MountedFk(PUMA.fk, pad=3), [("q", "q3", np.zeros(3))]),
    ("frame_assignment.d_theta.tol", fa.d_theta, [
        ("z", "direction", [0, 0, 1.0]), ("foot_prev", "vec3", [0, 0, 1.0]), ("x_prev", "direction", [1.0, 0, 0]),
        ("origin", "vec3", [0, 0, 3.0]), ("x", "direction", [0, 1.0, 0]), ("tol", "tol", 1e-9)]),
    ("DHChain", DHChain, [("links", "links", [Link(0, 0), Link(0, 1.0)]), ("name", "words", "arm"),
                          ("units", "words", "m"), ("configurations", "configurations", {"qz": [0.0, 0.0]}),
                          ("tool", "transform_opt", None), ("qlim", "qlim2", [[-1.0, 1.0], [-2.0, 2.0]])]),
    ("DHChain.fk", CHAIN.fk, [("q", "q2", [0.1, 0.2])]),
    ("DHChain.frames", CHAIN.frames, [("q", "q2", [0.1, 0.2])]),
    ("DHChain.link_matrices", CHAIN.link_matrices, [("q", "q2", [0.1, 0.2])]),
    ("DHChain.jacobian", CHAIN.jacobian, [("q", "q2", [0.1, 0.2])]),
    ("DHChain.check_q", CHAIN.check_q, [("q", "q2", [0.1, 0.2])]),  # `name` only labels the message
    ("Puma560.jacobian", PUMA.jacobian, [("q", "q6", np.zeros(6))]),
    ("Puma560.link_matrices", PUMA.link_matrices, [("q", "q6", np.zeros(6))]),
    ("MK3.frames", MK3_.frames, [("q", "q5", np.zeros(5))]),
    ("MK3.points", MK3_.points, [("q", "q5", np.zeros(5))]),
    ("MK3.jacobian", MK3_.jacobian, [("q", "q5", np.zeros(5))]),
    ("Porter.points", PORTER.points, [("q", "q6", np.zeros(6))]),
    ("Porter.jacobian", PORTER.jacobian, [("q", "q6", np.zeros(6))]),
    ("Porter.q", PORTER.q, [("name", "name", "qn")]),
    ("ThreeStepArm.frames", TS.frames, [("q", "q6", np.zeros(6))]),
    ("ThreeStepArm.points", TS.points, [("q", "q6", np.zeros(6))]),
    ("ThreeStepArm.wrist_position", TS.wrist_position,
     [("theta0", "angle", 0.1), ("theta1", "angle", 0.2), ("theta2", "angle", 0.3)]),
])  # fmt: skip
BAD["q3"] = [*_REAL, [0.0] * 2, [0.0, np.nan, 0.0], [0.0, 1j, 0.0], []]

#: calls whose array arguments broadcast together: shapes that do not broadcast must give a ValueError
#: naming one of the arguments, not numpy's "operands could not be broadcast" (issue 21)
BROADCAST = [
    ("euler.rotation_from_zyz", euler.rotation_from_zyz, ([0.1, 0.2], [0.1, 0.2, 0.3], 0.3), ("phi", "theta")),
    ("euler.rotation_from_rpy", euler.rotation_from_rpy, ([0.1, 0.2], [0.1, 0.2, 0.3], 0.3), ("roll", "pitch")),
    ("euler.zyz_from_rotation", lambda R, psi: euler.zyz_from_rotation(R, psi=psi),
     (np.stack([np.eye(3)] * 2), [0.1, 0.2, 0.3]), ("R", "psi")),
    ("euler.rpy_from_rotation", lambda R, roll: euler.rpy_from_rotation(R, roll=roll),
     (np.stack([np.eye(3)] * 2), [0.1, 0.2, 0.3]), ("R", "roll")),
    ("transforms.trot", transforms.trot, ([[0, 0, 1.0]] * 2, [0.1, 0.2], [[1.0, 0, 0]] * 3), ("angle", "point")),
    ("transforms.compose_moving", transforms.compose_moving, (np.stack([np.eye(4)] * 2), np.stack([np.eye(4)] * 3)),
     ("transforms[0]", "transforms[1]")),
    ("transforms.compose_fixed", transforms.compose_fixed, (np.stack([np.eye(4)] * 2), np.stack([np.eye(4)] * 3)),
     ("transforms[0]", "transforms[1]")),
]  # fmt: skip


@pytest.mark.parametrize("name, fn, values, names", [pytest.param(*r, id=r[0]) for r in BROADCAST])
def test_shapes_that_do_not_broadcast_raise_a_value_error_naming_the_arguments(name, fn, values, names):
    with pytest.raises(ValueError) as err:
        out = fn(*values)
        pytest.fail(f"{name} returned {out!r} for shapes that do not broadcast")
    msg = str(err.value)
    assert "could not be broadcast" not in msg, f"{name}: numpy's message, not ours: {msg}"
    assert any(n in msg.split(":", 1)[0] for n in names), f"{name}: the message names none of {names}: {msg}"


#: public names that are not swept, and why
EXEMPT = {
    "transforms.wrap_angle": "no validation by design: it sits on the solvers' hot paths; callers validate",
    "transforms.is_rotation": "a predicate: any bad input answers False (tested in test_transforms)",
    "ik.IKSolutions": "a result type built by the solvers; its own checks are tested in test_robot_api",
    "ik.IKBatch": "a result type built by the solvers",
    "ik.keys_from_bits": "decodes the solvers' own bit masks (internal integers)",
    "trajectories.JointPath": "a result type built by follow() and naive()",
    "trajectories.TimeScaling": "a result type built by time_scaling()",
    "frame_assignment.CommonNormal": "a result type built by common_normal()",
    "frame_assignment.DerivedTable": "a result type built by dh_from_axes()",
    "frame_assignment.FrameStep": "a result type built by frame_steps()",
    "frame_assignment.FrameWalk": "a result type built by frame_steps()",
    "three_step.ThreeStepSolution": "a result type built by three_step()",
    "three_step.Motion": "a result type built by motion()",
    "mk3.Attainable": "a result type built by MK3.nearest_attainable()",
    "puma560_jacobian.puma560_jacobian_rows": (
        "the closed form's kernel, handed the ops namespace and q already checked: Puma560.jacobian, swept, checks q"
    ),
    "numerical.DLSResult": "a result type built by ik_dls()",
    "robot.Robot": "the abstract base class of the arms (not instantiable); its methods are swept on each arm",
    "dh.DHChain.ik": "raises NotImplementedError: a general chain has no closed form (the arms' own ik are swept)",
    "dh.DHChain.ik_batch": "raises NotImplementedError, as DHChain.ik",
    **{f"robot.Robot.{m}": "abstract: each arm's own is swept" for m in ("fk", "frames", "ik", "ik_batch")},
}


#: junk every argument of every call is fed, whatever its kind (issue 21's catalogue)
UNIVERSAL: list[tuple[str, Any]] = [
    ("none", None), ("str", "abc"), ("bytes", b"\x00"), ("bool", True), ("npbool", np.bool_(False)),
    ("nan", float("nan")), ("inf", float("inf")), ("-inf", float("-inf")), ("complex", 1 + 2j),
    ("npcomplex", np.complex128(1j)), ("object", object()), ("ragged", [[1.0], [1.0, 2.0]]),
    ("objarray", np.array([None, None, None], dtype=object)), ("empty", np.array([])),
    ("empty2", np.zeros((0, 3))), ("dict", {"x": 1.0}), ("nanarray", np.full(3, np.nan)),
]  # fmt: skip

#: kinds for which a universal junk value is valid: text for free words, None for "identity"/"at rest"
NOT_JUNK = {"words": {"str"}, "transform_opt": {"none"}, "start": {"none"}, "flag": {"bool", "npbool"}}

#: empty arrays: a batch of no items may be answered by an empty result (every array in it holds 0 items), and
#: a refusal may name the argument the empty one no longer matches (revolute for q of 0 joints)
EMPTY = {"empty", "empty2"}

#: documented behaviour instead of a refusal: (call, argument, junk) -> (why, what the result must be)
DOCUMENTED: dict[tuple[str, str, str], tuple[str, Callable[[Any], bool]]] = {
    ("transforms.wrap_angle", "angle", "nanarray"): (
        "a float64 array is the solvers' own batch, where NaN marks 'no solution': NaN stays NaN, in place",
        lambda out: bool(np.isnan(out).all()),
    ),
}

#: arguments that are predicates' inputs: junk may be answered False instead of refused
PREDICATE = {("transforms.is_rotation", "R")}


def _key(v: Any) -> str:
    return f"{type(v).__name__}:{v!r}"


def _junk(kind: str) -> list[tuple[str, Any]]:
    """The bad values of a kind, then the universal catalogue (duplicates dropped)."""
    out = [(f"{kind}{j}", v) for j, v in enumerate(BAD[kind])]
    seen = {_key(v) for _, v in out}
    out += [(tag, v) for tag, v in UNIVERSAL if _key(v) not in seen and tag not in NOT_JUNK.get(kind, ())]
    return out


def _cases() -> list[Any]:
    out = []
    for name, fn, args in TABLE:
        for k, (arg, kind, _) in enumerate(args):
            for tag, bad in _junk(kind):
                out.append(pytest.param(name, fn, args, k, bad, tag, id=f"{name}-{arg}-{tag}"))
    return out


def _default(fn: Callable[..., Any], arg: str) -> Any:
    """The default value of parameter ``arg`` of ``fn`` (a sentinel when it has none)."""
    try:
        p = inspect.signature(fn).parameters.get(arg)
    except (TypeError, ValueError):
        return inspect.Parameter.empty
    return inspect.Parameter.empty if p is None else p.default


def _call(fn: Callable[..., Any], args: list[Arg], values: list[Any]) -> Any:
    """Call with keywords where the table's names are the parameters' (keyword-only ones included)."""
    names = [a for a, _, _ in args]
    try:
        params = inspect.signature(fn).parameters
    except (TypeError, ValueError):
        params = {}
    if all(n in params for n in names):
        return fn(**dict(zip(names, values, strict=True)))
    return fn(*values)


#: arguments whose documented default None is valid only together with another argument
_NONE_NEEDS = {("trajectories.line_path", "n"): "s=...", ("trajectories.circle_path", "n"): "s=...",
               ("trajectories.joint_interpolation", "n"): "s=..."}


def _arrays(out: Any, depth: int = 0) -> list[np.ndarray]:
    """Every float array in a result (its fields, tuples and lists included)."""
    if depth > 3:
        return []
    if isinstance(out, np.ndarray):
        return [out] if out.dtype.kind in "fc" else []
    if isinstance(out, float):
        return [np.asarray(out)]
    if isinstance(out, (tuple, list)):
        return [a for v in out for a in _arrays(v, depth + 1)]
    if hasattr(out, "__dict__") and not callable(out):
        return [a for v in vars(out).values() for a in _arrays(v, depth + 1)]
    return []


@pytest.mark.parametrize("name, fn, args, k, bad, tag", _cases())
def test_bad_input_raises_a_value_error_naming_the_argument(name, fn, args, k, bad, tag):
    values = [valid for _, _, valid in args]
    values[k] = bad
    arg = args[k][0]
    if (name, arg, tag) in DOCUMENTED:
        why, check = DOCUMENTED[name, arg, tag]
        assert check(_call(fn, args, values)), f"{name}({arg}={bad!r}): not what is documented: {why}"
        return
    if (name, arg) in PREDICATE:  # a predicate may answer "no" to junk; never "yes", never another error
        try:
            out = _call(fn, args, values)
        except ValueError:
            return
        assert out is False, f"{name}({arg}={bad!r}) returned {out!r}"
        return
    if tag in EMPTY:
        try:
            out = _call(fn, args, values)
        except ValueError as err:
            head = str(err).split(":", 1)[0]
            assert any(a.split("[")[0] in head for a, _, _ in args), f"{name}: names no argument: {err}"
            return
        arrays = _arrays(out)
        assert arrays and all(a.size == 0 for a in arrays), f"{name}({arg}=empty) returned {out!r}"
        return
    if bad is None and _default(fn, arg) is None:
        if (name, arg) in _NONE_NEEDS:
            pytest.skip(
                f"{name}({arg}=None) not checked: None is its documented default, not a bad input, and is valid "
                f"only together with {_NONE_NEEDS[name, arg]}, which this table does not give"
            )
        # not a bad input: None is the documented default, so the call must work as if the argument were left out
        out = _call(fn, args, values)
        assert out is not None, f"{name}({arg}=None), its documented default, returned None"
        return
    with pytest.raises(ValueError) as err:  # anything else (TypeError, a result, NaN) fails here
        out = _call(fn, args, values)
        pytest.fail(f"{name}({arg}={bad!r}) returned {out!r} instead of raising")
    msg = str(err.value)
    head = msg.split(":", 1)[0]
    assert arg.split("[")[0] in head, f"{name}: the message does not name {arg!r}: {msg}"
    assert "expected" in msg, f"{name}: the message does not say what was expected: {msg}"


@pytest.mark.parametrize("name, fn, args", [pytest.param(*row, id=row[0]) for row in TABLE])
def test_the_valid_values_of_the_table_work(name, fn, args):
    """The sweep is not vacuous: with every argument valid, each call succeeds."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        out = _call(fn, args, [v for _, _, v in args])
    assert out is not None
    # issue 21: no accepted input returns a non-finite value (arrays in the result or in its fields)
    parts = [out, *(getattr(out, "__dict__", {}) or {}).values()]
    for part in parts:
        if isinstance(part, np.ndarray) and part.dtype.kind in "fc":
            assert np.isfinite(part).all(), f"{name}: a non-finite value in the result"
        elif isinstance(part, float):
            assert np.isfinite(part), f"{name}: a non-finite value in the result"


def _public(module: Any, prefix: str) -> set[str]:
    """Public callables of a module, its warning classes left out (they take no input)."""
    names = getattr(module, "__all__", [])
    out = set()
    for n in names:
        obj = getattr(module, n)
        if callable(obj) and not (inspect.isclass(obj) and issubclass(obj, Warning)):
            out.add(n if inspect.isclass(obj) and n in ROBOT_CLASSES else f"{prefix}.{n}")
    return out


ROBOT_CLASSES = {"Puma560", "MK3", "Porter", "ThreeStepArm"}


def test_every_public_function_is_swept():
    from puma_course.kinematics import porter

    public = (
        _public(transforms, "transforms") | _public(euler, "euler") | _public(dh, "dh") | _public(ik, "ik")
        | _public(fa, "frame_assignment") | _public(jac, "jacobian") | _public(spaces, "spaces")
        | _public(sdh, "standard_dh")
        | _public(ts, "three_step") | _public(tr, "trajectories")
        | {f"porter.{n}" for n in ("angle",)}
        | _public(ts_procedure, "procedure") - {f"procedure.{n}" for n in ts.__all__}
    )  # fmt: skip
    robots = {"Puma560": Puma560, "MK3": MK3, "Porter": Porter, "ThreeStepArm": ThreeStepArm}
    methods = {f"{r}.{m}" for r, cls in robots.items() for m in ("fk", "ik", "ik_batch") if hasattr(cls, m)}
    swept = {name for name, _, _ in TABLE}
    # robots share fk/frames/points/q through the base class: one robot per implementation is enough
    shared: set[str] = set()  # every robot's fk, ik and ik_batch have rows of their own
    missing = (public | methods | set(robots)) - swept - set(EXEMPT) - shared - {"dh.DHChain", "dh.Link"}
    assert not missing, f"public callables with no row in the sweep: {sorted(missing)}"
    assert {"dh.DHChain", "dh.Link"} <= swept
    top = {
        n
        for n in puma_course.__all__
        if callable(getattr(puma_course, n)) and inspect.isfunction(getattr(puma_course, n))
    }
    covered = {name.split(".")[-1] for name in swept | set(EXEMPT)}
    assert top - covered == set(), f"top-level functions not swept: {sorted(top - covered)}"
    del porter


# ---------------------------------------------------------------- issue 21: numbers in another dtype, broadcasts
def _same(a: Any, b: Any, depth: int = 0) -> bool:
    """Bit-for-bit the same result (arrays, numbers, tuples, dataclass and object fields)."""
    if depth > 4:
        return True
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        return a.shape == b.shape and bool(np.array_equal(a, b, equal_nan=a.dtype.kind in "fc"))
    if isinstance(a, (tuple, list)) and isinstance(b, (tuple, list)):
        return len(a) == len(b) and all(_same(x, y, depth + 1) for x, y in zip(a, b, strict=True))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k], depth + 1) for k in a)
    if hasattr(a, "__dict__") and type(a) is type(b) and not inspect.isroutine(a):
        return _same(vars(a), vars(b), depth + 1)
    return bool(a == b)


def _numeric(v: Any) -> np.ndarray | None:
    """The valid value as a float array, or None when it is not numbers (a robot, a word, links...)."""
    if isinstance(v, (str, bool)) or v is None:
        return None
    try:
        arr = np.asarray(v)
    except ValueError:
        return None
    return arr.astype(float) if arr.dtype.kind in "iuf" and arr.size else None


def _equivalents(v: np.ndarray) -> list[tuple[str, Any, Any]]:
    """(tag, the same numbers in another form, the float value they stand for)."""
    r = np.round(v) + 0.0  # -0.0 is 0 as an integer
    out: list[tuple[str, Any, Any]] = [("int64", r.astype(np.int64), r), ("object", v.astype(object), v)]
    if np.all(np.abs(r) <= 127):
        out.append(("int8", r.astype(np.int8), r))
    if np.all((r >= 0) & (r <= 255)):
        out.append(("uint8", r.astype(np.uint8), r))
    if v.ndim:
        out.append(("list", v.tolist(), v))
    else:
        out.append(("npfloat", np.float64(v), v))
    return out


def _equivalent_cases() -> list[Any]:
    out = []
    for name, fn, args in TABLE:
        for k, (arg, _kind, valid) in enumerate(args):
            v = _numeric(valid)
            if v is None:
                continue
            for tag, other, ref in _equivalents(v):
                out.append(pytest.param(name, fn, args, k, other, ref, id=f"{name}-{arg}-{tag}"))
    return out


def _outcome(fn: Callable[..., Any], args: list[Arg], values: list[Any]) -> tuple[str, Any]:
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            return "ok", _call(fn, args, values)
        except ValueError as err:
            return "refused", err


@pytest.mark.parametrize("name, fn, args, k, other, ref", _equivalent_cases())
def test_the_same_numbers_in_another_dtype_give_the_same_answer_or_a_named_refusal(name, fn, args, k, other, ref):
    """int8/uint8/int64 arrays, object arrays, lists and numpy scalars of the same numbers: the answer the float
    value gets (bit for bit), or a ValueError naming the argument; never an overflow (issue 21: int8 lengths
    gave "l1 + l2 = -56") and never a result the float value does not give."""
    arg = args[k][0]
    base = [v for _, _, v in args]
    values = list(base)
    values[k] = other
    base[k] = ref if np.ndim(ref) else float(ref)
    how, out = _outcome(fn, args, values)
    want_how, want = _outcome(fn, args, base)
    if how == "refused":
        head = str(out).split(":", 1)[0]
        assert arg.split("[")[0] in head or want_how == "refused", f"{name}({arg}) refused without naming it: {out}"
        return
    assert want_how == "ok", f"{name}({arg}={other!r}) accepted what the float value {ref!r} is refused for: {want}"
    assert _same(out, want), f"{name}({arg}={other!r}) answered otherwise than with the float value {ref!r}"
    for a in _arrays(out):
        assert np.isfinite(a).all(), f"{name}({arg}={other!r}): a non-finite value in the result"


def _batch(v: Any, n: int) -> Any:
    return np.stack([np.asarray(v, dtype=float)] * n)


@pytest.mark.parametrize("name, fn, args", [pytest.param(*row, id=row[0]) for row in TABLE])
def test_batches_of_different_lengths_are_refused_naming_an_argument(name, fn, args):
    """Every pair of arguments that each take a batch: batches of 2 and 3 do not broadcast. The refusal is a
    ValueError naming one of the two (not numpy's "could not be broadcast"); the count is in the module doc."""
    base = [v for _, _, v in args]
    batchable = []
    for k, (_arg, _kind, valid) in enumerate(args):
        if _numeric(valid) is None:
            continue
        values = list(base)
        values[k] = _batch(valid, 2)
        how, out = _outcome(fn, args, values)
        if how == "ok" and all(np.isfinite(a).all() for a in _arrays(out)):
            batchable.append(k)
    for i in batchable:
        for j in batchable:
            if i == j:
                continue
            values = list(base)
            values[i], values[j] = _batch(base[i], 2), _batch(base[j], 3)
            how, out = _outcome(fn, args, values)
            names = (args[i][0].split("[")[0], args[j][0].split("[")[0])
            assert how == "refused", f"{name}: batches of 2 ({names[0]}) and 3 ({names[1]}) gave {out!r}"
            msg = str(out)
            assert "could not be broadcast" not in msg, f"{name}: numpy's message, not ours: {msg}"
            assert any(n in msg.split(":", 1)[0] for n in names), f"{name}: the message names neither {names}: {msg}"


#: modules whose __all__ lists solver kernels (pre-validated arrays in, reached only through a swept robot method)
KERNEL_MODULES = {
    "puma_course.kinematics.porter.explicit": "Ver.1 kernels of Porter.ik / ik_batch (swept)",
    "puma_course.kinematics.porter.families": "singular-family kernels of Porter.ik (swept)",
    "puma_course.kinematics.porter.fk": "the entries of Porter.fk / frames (swept)",
    "puma_course.kinematics.porter.geometric": "Ver.2 kernel of Porter.ik(method='geometric') (swept); angle is swept",
    "puma_course.kinematics.three_step.geometry": "kernels of ThreeStepArm.ik (swept); arm_axis is swept",
    "puma_course.kinematics._ops": "the scalar/array operation tables of the solvers",
}


def _public_objects() -> dict[int, tuple[str, Any]]:
    """Every public callable of puma_course's base and kinematics API: puma_course.__all__, transforms, euler and
    every module of puma_course.kinematics (walked, so a new module is found), plus each robot class's public
    methods. Keyed by identity (a re-export is one callable)."""
    import importlib
    import pkgutil

    from puma_course import kinematics

    names = ["puma_course", "puma_course.transforms", "puma_course.euler", "puma_course.kinematics"]
    names += [m.name for m in pkgutil.walk_packages(kinematics.__path__, "puma_course.kinematics.")]
    out: dict[int, tuple[str, Any]] = {}
    for mod_name in names:
        mod = importlib.import_module(mod_name)
        for n in getattr(mod, "__all__", []):
            obj = getattr(mod, n)
            if not callable(obj) or (inspect.isclass(obj) and issubclass(obj, Warning)) or inspect.ismodule(obj):
                continue
            where = getattr(obj, "__module__", mod_name)
            if where in KERNEL_MODULES and not any(obj is fn for _, fn, _ in TABLE):
                continue
            out.setdefault(id(obj), (f"{where}.{getattr(obj, '__qualname__', n)}", obj))
            if inspect.isclass(obj) and (issubclass(obj, puma_course.kinematics.Robot) or obj is MountedFk):
                for m, f in inspect.getmembers(obj, callable):
                    if not m.startswith("_") or m == "__call__" and obj is MountedFk:
                        out.setdefault(id(f), (f"{where}.{obj.__qualname__}.{m}", f))
    return out


def _swept_ids() -> set[int]:
    ids = set()
    for _, fn, _ in TABLE:
        ids.add(id(fn))
        if inspect.ismethod(fn):
            ids.add(id(fn.__func__))
        if isinstance(fn, MountedFk):
            ids.add(id(MountedFk.__call__))
    return ids


#: public callables that take no input worth sweeping, and why (qualified names)
NO_INPUT = {
    "parameters": "takes no argument",
    "table": "takes no argument",
    "__init__": "a class's constructor is swept as the class",
}


def test_every_public_callable_is_swept_by_identity():
    """A public callable added to any __all__ of the base or kinematics layers (or a public robot method) fails
    here until it has a row in TABLE or a reason in EXEMPT."""
    exempt_names = set(EXEMPT)
    missing = []
    swept = _swept_ids()
    for qual, obj in _public_objects().values():
        if id(obj) in swept or qual.rsplit(".", 1)[-1] in NO_INPUT:
            continue
        short = qual.replace("puma_course.kinematics.", "").replace("puma_course.", "")
        parts = short.split(".")
        if any(e.split(".")[-1] == parts[-1] and set(e.split(".")) <= set(parts) for e in exempt_names):
            continue
        missing.append(qual)
    assert not missing, f"public callables with no row in the sweep and no exemption: {sorted(missing)}"


def test_the_sweep_counts_its_cases():
    """The counts quoted in the module doc and in README: they must be what the sweep runs."""
    assert (len(TABLE), len(_cases()), len(_equivalent_cases())) == (116, 5799, 1109)


# ---------------------------------------------------------------- issue 31: accepted inputs whose answer overflowed
#: (call, the argument the refusal must name): each returned inf or raised OverflowError before issue 31
EDGES_31: list[tuple[str, Callable[[], Any], str]] = [
    ("spaces.actuator_rate: θ̇ = 1.5e308", lambda: spaces.actuator_rate(0.5, 1.5e308, 3, 4), "theta_dot"),
    ("ik.joint_distance: lengths ±1e300", lambda: ik.joint_distance([1e300], [-1e300], revolute=[False]), "q"),
    ("trajectories.time_scaling: n = 10**400", lambda: tr.time_scaling(1, n=10**400), "n"),
    ("trajectories.time_scaling: n = -10**5000", lambda: tr.time_scaling(1, n=-(10**5000)), "n"),
    ("three_step.motion: 10**400 steps", lambda: ts.motion(SOL, steps_per_phase=10**400), "steps_per_phase"),
    (
        "three_step.motion_joints: 10**400 steps",
        lambda: ts.motion_joints(SOL, steps_per_phase=10**400, wrist="joint"),
        "steps_per_phase",
    ),
]


@pytest.mark.parametrize("label, call, arg", EDGES_31, ids=[e[0] for e in EDGES_31])
def test_an_answer_that_would_overflow_is_refused_naming_the_argument(label, call, arg):
    with pytest.raises(ValueError) as err:
        out = call()
        pytest.fail(f"{label} returned {out!r}")
    msg = str(err.value)
    assert msg.split(":", 1)[0] == arg, msg
    assert "expected" in msg and "got" in msg, msg


def test_the_largest_accepted_inputs_still_give_finite_answers():
    # the limits just inside the refusals above: finite answers, worked by hand
    assert ik.joint_distance([1e150], [-1e150], revolute=[False]) == 2e150
    assert np.isfinite(spaces.actuator_rate(0.5, 1e150, 3, 4))
    assert abs(spaces.actuator_rate(np.pi / 2, 1e150, 3.0, 4.0) / 1e150 - 2.4) < 1e-12  # b c / s = 12 / 5
