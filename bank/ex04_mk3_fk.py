"""Exercise 4 (``solutions/ex04_mk3_fk.ipynb``): forward kinematics of the Motoman MK3, and the MK3 on a rail.

The modelling question: the MK3 mounted on a carriage that slides along a rail (a seventh axis,
common in welding cells) is a new 6-joint chain; its table, with the rail's frame as {0} and the
MK3's flange as the last frame, is graded by the poses it reaches. Question 4 asks what a five-joint
arm can reach on that rail: the nearest attainable pose of a goal (lecture 04 §8), its arm plane through
the carriage's base axis, not the rail frame's z axis (so lecture 04's cells do not answer it).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from puma_course.grading.judge.diagnose import degrees_in, matches
from puma_course.grading.judge.judges import table_judge
from puma_course.grading.spec import Exercise, Question

from . import _keys as keys
from ._formulas import approach_only, kept_axis, turned_back
from ._reference import chains as ref

H = np.pi / 2


def rail_table(c: float, d1: float, a1: float, a2: float, a3: float, d5: float) -> np.ndarray:
    """One valid table of the MK3 on its rail (the solution's): a prismatic row, then the MK3's rows."""
    return np.array(
        [
            [-H, 0.0, 0.0, 0.0, 1],
            [H, 0.0, 0.0, c + d1, 0],
            [H, a1, 0.0, 0.0, 0],
            [0.0, a2, 0.0, 0.0, 0],
            [0.0, a3, 0.0, 0.0, 0],
            [H, 0.0, 0.0, d5, 0],
        ]
    )


def _tool(R: Any, p: Any) -> np.ndarray:
    E = np.eye(4)
    E[:3, :3], E[:3, 3] = R, p
    return E


def _inv(T: Any) -> np.ndarray:
    T = np.asarray(T, dtype=float)
    return _tool(T[:3, :3].T, -T[:3, :3].T @ T[:3, 3])


#: The public tools: a torch bent 30° about y5, its tip 150 mm out; a gripper turned about x5, offset sideways.
E_TORCH = _tool([[np.cos(np.pi / 6), 0.0, np.sin(np.pi / 6)], [0.0, 1.0, 0.0], [-np.sin(np.pi / 6), 0.0,
                 np.cos(np.pi / 6)]], [0.0, 0.0, 150.0])  # fmt: skip
E_GRIP = _tool([[1.0, 0.0, 0.0], [0.0, np.cos(0.5), np.sin(0.5)], [0.0, -np.sin(0.5), np.cos(0.5)]], [40.0, 0.0, 120.0])


def _tools(rng: np.random.Generator, n: int) -> list[np.ndarray]:
    """``n`` tools: turned 0.3 to 1.2 rad about a random axis, the tool point 80 to 200 mm out, up to 60 mm aside."""
    offsets = np.column_stack([rng.uniform(-60.0, 60.0, (n, 2)), rng.uniform(80.0, 200.0, n)])
    return [_tool(R, p) for R, p in zip(ref.random_rotations(rng, n, 0.3, 1.2), offsets, strict=True)]


def _flange(axis: int, sign: float, flange: str = "right") -> Any:
    """The point d5 along (sign) axis ``axis`` of the flange frame, the flange found from the tool's pose: T E⁻¹
    (right), or the mistakes: the tool taken for the flange, E⁻¹ on the left, E for E⁻¹."""

    def point(T: Any, d5: float, E: Any) -> np.ndarray:
        T, E = np.asarray(T, dtype=float), np.asarray(E, dtype=float)
        F = {"right": T @ _inv(E), "tool": T, "left": _inv(E) @ T, "E": T @ E}[flange]
        return F[:3, 3] + sign * d5 * F[:3, axis]

    return point


def _wrist_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    return [(ref.mk3_fk(q, *L) @ E, L[-1], E) for (q, *L), E in zip(ref.mk3_cases(rng, n), _tools(rng, n), strict=True)]


def mk3_tool_fk(q: Any, d1: float, a1: float, a2: float, a3: float, d5: float, E: Any) -> np.ndarray:
    """^0T_tool = ^0T_5 E of the MK3 holding the tool E (question 2's reference)."""
    return ref.mk3_fk(q, d1, a1, a2, a3, d5) @ np.asarray(E, dtype=float)


def _with_tool(fk: Any, side: str = "right") -> Any:
    """A flange pose ``fk(q, *L)`` made the tool's: times E on the right (or, the mistake, on the left)."""

    def tool_fk(q: Any, *args: Any) -> np.ndarray:
        *L, E = args
        T, E = fk(q, *L), np.asarray(E, dtype=float)
        return T @ E if side == "right" else E @ T

    return tool_fk


def _twists_in_degrees(table: np.ndarray) -> np.ndarray:
    """The table with its twists α written in degrees (the mistake: 90 typed for π/2)."""
    out = np.array(table, dtype=float)
    out[:, 0] = np.degrees(out[:, 0])
    return out


EXERCISE = Exercise(
    "ex04_mk3_fk",
    "Forward kinematics of the Motoman MK3, and the MK3 on a rail",
    (
        Question(
            "q1",
            "mk3_wrist_point",
            2,
            "the wrist point behind the flange of an MK3 holding a tool",
            public=(
                (ref.mk3_fk(np.zeros(5)) @ E_TORCH, 100.0, E_TORCH),
                (ref.mk3_fk([0.3, 0.8, -0.5, 0.2, 1.0]) @ E_GRIP, 100.0, E_GRIP),
            ),
            hidden=lambda rng: _wrist_cases(rng, 4),
            reference=_flange(2, -1.0),
            mistakes=(
                matches(
                    "lecture_mechanism",
                    "you went back d5 from the tool's frame as lecture 04 does from the flange's: first find the "
                    "flange's pose from the tool's, T E⁻¹",
                    _flange(2, -1.0, "tool"),
                ),
                matches(
                    "order",
                    "your flange pose is E⁻¹ T: the tool is described in the flange's frame, so the flange's pose "
                    "is T E⁻¹ (E⁻¹ on the right)",
                    _flange(2, -1.0, "left"),
                ),
                matches(
                    "inverse",
                    "your flange pose is T E: undoing the tool means multiplying by E⁻¹, not E",
                    _flange(2, -1.0, "E"),
                ),
                matches(
                    "wrong_axis",
                    "you moved along x5: the flange is d5 beyond the wrist along the tool axis z5",
                    _flange(0, -1.0),
                ),
                matches(
                    "wrong_axis",
                    "you moved along y5: the flange is d5 beyond the wrist along the tool axis z5",
                    _flange(1, -1.0),
                ),
                matches(
                    "offset_sign",
                    "the flange is d5 *beyond* the wrist along z5: going back means subtracting",
                    _flange(2, 1.0),
                ),
            ),
            hint="Which axis of frame {5} does the last row of the table slide along (lecture 04 §1)? At q = 0 "
            "you know both points by hand (lecture 04 §4).",
        ),
        Question(
            "q2",
            "mk3_fk",
            3,
            "^0T_tool for any lengths and tool",
            public=(
                (np.zeros(5), 360.0, 135.0, 250.0, 215.0, 100.0, E_TORCH),
                (np.array([0.0, np.pi / 2, -np.pi / 2, 0.0, 0.0]), 360.0, 135.0, 250.0, 215.0, 100.0, E_GRIP),
            ),
            hidden=lambda rng: [(*c, E) for c, E in zip(ref.mk3_cases(rng, 5), _tools(rng, 5), strict=True)],
            reference=mk3_tool_fk,
            forbidden=(*keys.KEY_CHAIN, "puma_course_bank._reference.chains:mk3_fk"),
            mistakes=(
                matches(
                    "lecture_mechanism",
                    "this is the flange's pose ⁰T₅ of lecture 04: the question asks for the tool's, ⁰T₅ E",
                    lambda q, *args: ref.mk3_fk(q, *args[:-1]),
                ),
                matches(
                    "order",
                    "your tool is multiplied on the left (E ⁰T₅): E is the tool's pose in the flange's frame, so it "
                    "comes last, ⁰T₅ E",
                    _with_tool(ref.mk3_fk, "left"),
                ),
                matches(
                    "printed_formula",
                    "your ⁴T₅ is the misprinted one: its -d5 sits in the wrong row (lecture 04's "
                    "Errata shows four ways to decide)",
                    _with_tool(ref.mk3_printed_fk),
                ),
                matches(
                    "standard_dh",
                    "this is the MK3's table evaluated with the standard (distal) DH link matrix; "
                    "the table is Craig's modified DH (lecture 02 §5)",
                    _with_tool(lambda q, *L: ref.standard_table_fk(ref.mk3_table(*L), q)),
                ),
                matches(
                    "order",
                    "your link matrices are multiplied in the reverse order",
                    _with_tool(lambda q, *L: ref.reversed_table_fk(ref.mk3_table(*L), q)),
                ),
                degrees_in(0),
                matches(
                    "degrees",
                    "your twists α are in degrees (90 where the table means π/2): np.cos and np.sin take "
                    "radians, so write the twists as np.pi / 2",
                    _with_tool(lambda q, *L: ref.table_fk(_twists_in_degrees(ref.mk3_table(*L)), q)),
                ),
            ),
            hint="Check q = 0 and the ready pose against the flange positions you work out by hand (lecture 04 §4); "
            "the numbers are millimetres.",
        ),
        Question(
            "q3",
            "rail_table",
            5,
            "the DH table of the MK3 on a rail, from its picture",
            public=((450.0, 360.0, 135.0, 250.0, 215.0, 100.0), (700.0, 360.0, 135.0, 250.0, 215.0, 100.0)),
            hidden=lambda rng: [(float(c), *ref.mk3_cases(rng, 1)[0][1:]) for c in rng.uniform(200.0, 800.0, 3)],
            reference=ref.mk3_rail_expected,
            judge_with=table_judge(),
            answer=rail_table,
            forbidden=keys.KEY_TABLES,
            hint="The rail's joint comes first: which way must z_1 point, and which twist about x_0 turns z_0 into it "
            "(lecture 02 §3)? Then find where joint 2's axis meets the rail's. Your q2, shifted by the carriage, is "
            "the pose to compare with.",
        ),
        Question(
            "q4",
            "rail_nearest_pose",
            3,
            "the nearest pose the MK3 on its rail can take",
            public=(
                (ref.mk3_rail_goal([0.4, 0.9, -1.2, 0.6, 0.3], [0.2, -0.5, 1.0], 0.9, 300.0), 300.0),
                (ref.mk3_rail_goal([-0.6, 0.5, -0.9, 1.0, 0.7], [1.0, 0.3, 0.0], 0.5, -250.0), -250.0),
            ),
            # every public goal is unattainable (returning T unchanged fails each); one hidden goal is attainable
            # up to rounding and one is in the arm plane exactly (z × z' is the zero vector: normalising it
            # unguarded gives NaN): each must come back unchanged, however the turn's axis is computed
            hidden=lambda rng: [
                *ref.mk3_nearest_cases(rng, 4),
                *ref.mk3_attainable_cases(rng, 1),
                *ref.mk3_in_plane_cases(rng, 1),
            ],
            reference=ref.mk3_rail_nearest,
            forbidden=(
                "puma_course.kinematics.mk3:MK3.nearest_attainable",
                "puma_course_bank._reference.chains:mk3_rail_nearest",
            ),
            mistakes=(
                matches(
                    "base_frame",
                    "your arm plane passes through the rail frame's z0 axis: the MK3's base axis stands on the "
                    "carriage, at x = 0, y = s (question 3's picture)",
                    lambda T, s: ref.mk3_rail_projected(T, 0.0),
                ),
                matches(
                    "rotation_sense",
                    "your rotation turns the frame the wrong way: the approach leaves the arm plane by twice as "
                    "much instead of landing in it (turn by the angle about z × z', not z' × z)",
                    lambda T, s: turned_back(T, ref.mk3_rail_nearest(T, s)),
                ),
                matches(
                    "projected_only",
                    "you replaced the approach vector by its projection but kept x and y: turn the whole frame, "
                    "so the result is still a rotation",
                    lambda T, s: approach_only(T, ref.mk3_rail_nearest(T, s)),
                ),
                matches(
                    "not_smallest_turn",
                    "your approach is right, but x5 was kept and re-orthogonalised: that is a rotation, not the "
                    "smallest one; turn the whole frame about z × z'",
                    lambda T, s: kept_axis(T, ref.mk3_rail_nearest(T, s), 0),
                ),
                matches(
                    "not_smallest_turn",
                    "your approach is right, but y5 was kept and re-orthogonalised: that is a rotation, not the "
                    "smallest one; turn the whole frame about z × z'",
                    lambda T, s: kept_axis(T, ref.mk3_rail_nearest(T, s), 1),
                ),
            ),
            hint="Which vertical plane must hold the approach z on the rail (lecture 04 §6, with question 3's "
            "base)? Then lecture 04 §8: project z onto it, normalise, and turn the whole frame about z × z' by the "
            "angle between them (Rodrigues, lecture 01). A goal whose approach is in the plane comes back unchanged.",
        ),
    ),
    allowed=("puma_course.kinematics.dh:mdh",),
)
