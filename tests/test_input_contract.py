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
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import puma_course
from puma_course import euler, transforms
from puma_course.kinematics import MK3, DHChain, Link, Porter, Puma560, ThreeStepArm, dh, ik, spaces
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
        lambda a, b: transforms.compose_moving(a, b),
        [("transforms[0]", "transform", np.eye(4)), ("transforms[1]", "transform", np.eye(4))],
    ),  # fmt: skip
    (
        "transforms.compose_fixed",
        lambda a, b: transforms.compose_fixed(a, b),
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
        "trajectories.unwrap",
        tr.unwrap,
        [("q", "path2", [[3.0, 1.0], [-3.0, 2.0]]), ("revolute", "mask2", [True, False])],
    ),  # fmt: skip
]

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
}


def _cases() -> list[Any]:
    out = []
    for name, fn, args in TABLE:
        for k, (arg, kind, _) in enumerate(args):
            for j, bad in enumerate(BAD[kind]):
                out.append(pytest.param(name, fn, args, k, bad, id=f"{name}-{arg}-{kind}{j}"))
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
_NONE_NEEDS = {("trajectories.line_path", "n"): "s=...", ("trajectories.circle_path", "n"): "s=..."}


@pytest.mark.parametrize("name, fn, args, k, bad", _cases())
def test_bad_input_raises_a_value_error_naming_the_argument(name, fn, args, k, bad):
    values = [valid for _, _, valid in args]
    values[k] = bad
    arg = args[k][0]
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
