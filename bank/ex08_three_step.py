"""Exercise 8 (``solutions/ex08_three_step.ipynb``): the three-step procedure, from a bent start.

Lecture 08 works its Exercise 1 from the straight arm in full and prints every formula, from any start; so this
arm is a variant (issue 22: nothing answered by copying a lecture): a palletising arm whose controller counts the
base angle θ0 from e_y and whose parallelogram makes θ2 the forearm's elevation above the horizontal. It starts
bent, with a turned wrist frame, and every question is graded on hidden targets and starts. The modelling
question: the wrist's own joint angles, turns about its moving axes (not the composite rotation
seen from the base).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from puma_course.grading.judge.compare import compare_angles
from puma_course.grading.judge.diagnose import TRANSPOSED, degrees_out, matches
from puma_course.grading.judge.judges import rotation_judge
from puma_course.grading.spec import Exercise, Question

from . import _keys as keys
from ._inputs import reachable_wrist_points
from ._reference import chains
from ._reference import motion as ref

W = np.array([0.5, 0.5, 2.0])
TARGET = np.diag([-1.0, 1.0, -1.0])
LENGTHS = (1.5, 1.0)
#: The public bent start {θ̄0, θ̄1, θ̄2, F̄}: turned, shoulder down, elbow bent, the wrist frame turned with it.
THETA_BAR = np.array([-0.6, -0.3, 0.9])
F_BAR = chains.elementary_rotation("z", -0.6) @ chains.elementary_rotation("y", -0.6)
PUBLIC = (W, TARGET, *LENGTHS, "up", THETA_BAR, F_BAR)
BEHIND = (np.array([-0.5, -0.4, 1.2]), chains.elementary_rotation("x", 2.0), *LENGTHS, "down", THETA_BAR, F_BAR)

STRAIGHT = (
    "you started from the straight arm {0, 0, 0, I}; this arm starts at {θ̄0, θ̄1, θ̄2, F̄}: each step turns "
    "the frame it is given by the change of the joint angles"
)
BRANCH = "these are the angles of the other elbow branch (elbow up: the elbow above the line from shoulder to wrist)"
LECTURE = ref.LECTURE_ARM


def _lecture(field: str) -> tuple[Any, ...]:
    """The lecture's reading of the base angle, of the elbow angle, or of both: each one the mistake."""
    return tuple(
        matches("lecture_mechanism", LECTURE, ref.three_step_variant(field, base_zero=b, parallel=p))
        for b, p in ((False, False), (True, False), (False, True))
    )


def _cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    return ref.three_step_cases(rng, n, reachable_wrist_points)


def _straight(field: str) -> tuple[Any, ...]:
    return tuple(
        matches("straight_start", STRAIGHT, ref.three_step_variant(field, **kw))
        for kw in ({"zero_theta": True}, {"identity_frame": True}, {"zero_theta": True, "identity_frame": True})
    )


ORDER = matches(
    "order",
    "your rotation multiplies on the right, as if it turned about the frame's own (moving) axes; "
    "the base and the arm turn the frame about axes fixed in the scene (lecture 01 §5)",
    ref.moved_wrong_way("frame_step1"),
)

EXERCISE = Exercise(
    "ex08_three_step",
    "The three-step procedure from a bent start",
    (
        Question(
            "q1",
            "step1_frame",
            2,
            "(a) the wrist frame after the base turn",
            public=((W, THETA_BAR, F_BAR), (BEHIND[0], THETA_BAR, F_BAR)),
            hidden=lambda rng: [(c[0], c[5], c[6]) for c in _cases(rng, 4)],
            reference=ref.step_field("frame_step1"),
            forbidden=keys.KEY_THREE_STEP,
            mistakes=(
                *_lecture("frame_step1")[2:],
                matches(
                    "joint_zero",
                    "your base turned half a turn too far: this arm counts θ0 from e_y (at θ0 = 0 it points along "
                    "e_y), so θ0 = γ0 - π/2, not γ0 + π/2",
                    lambda w, tb, Fb: np.diag([-1.0, -1.0, 1.0]) @ ref.step_field("frame_step1")(w, tb, Fb),
                ),
                *_straight("frame_step1"),
                ORDER,
                TRANSPOSED,
            ),
            hint="The base turns from its start to the direction of w and carries the wrist frame F̄ with it "
            "(lecture 08 §2, step 1); this arm reads θ0 from e_y, so by how much does it turn? A target behind "
            "the robot needs the right quadrant.",
        ),
        Question(
            "q2",
            "arm_angles",
            3,
            "(b) θ1 and θ2 for either elbow",
            public=((W, *LENGTHS, "up"), (W, *LENGTHS, "down")),
            hidden=lambda rng: [(c[0], c[2], c[3], c[4]) for c in _cases(rng, 5)],
            reference=ref.step_field("arm"),
            compare=compare_angles,
            forbidden=keys.KEY_THREE_STEP,
            mistakes=(
                matches(
                    "branch",
                    BRANCH,
                    lambda w, l1, l2, elbow: ref.step_field("arm")(w, l1, l2, {"up": "down", "down": "up"}[elbow]),
                ),
                matches(
                    "lecture_mechanism",
                    "your θ2 is measured from the upper arm, as in lecture 08; this arm's θ2 is the forearm's "
                    "elevation above the horizontal (its parallelogram)",
                    ref.three_step_variant("arm", parallel=False),
                ),
                degrees_out(),
            ),
            hint="Two of the four sign combinations of the law of cosines reach w (lecture 08 §3); this arm's θ2 is "
            "the forearm's elevation: check yours by putting the angles back into this arm's eq. (1).",
        ),
        Question(
            "q3",
            "step2_frame",
            3,
            "(b) the wrist frame after shoulder and elbow",
            public=((W, *LENGTHS, "up", THETA_BAR, F_BAR), (*BEHIND[:1], *LENGTHS, "down", THETA_BAR, F_BAR)),
            hidden=lambda rng: [(c[0], *c[2:]) for c in _cases(rng, 4)],
            reference=ref.step_field("frame_step2"),
            forbidden=keys.KEY_THREE_STEP,
            mistakes=(
                *_lecture("frame_step2"),
                matches(
                    "lecture_mechanism",
                    "your forearm turned by Δ(θ1 + θ2), as lecture 08's elbow angle does; this arm's θ2 is the "
                    "forearm's own elevation above the horizontal (its parallelogram), so the frame it carries turns "
                    "by θ2 - θ̄2 alone",
                    ref.elevations_added,
                ),
                *_straight("frame_step2"),
                matches(
                    "branch", BRANCH.replace("angles", "frame"), ref.three_step_variant("frame_step2", other_elbow=True)
                ),
                matches(
                    "order",
                    "your rotation multiplies on the right, as if it turned about the "
                    "frame's own (moving) axes; the arm turns the frame about an axis fixed in the scene",
                    ref.moved_wrong_way("frame_step2"),
                ),
                TRANSPOSED,
            ),
            hint="Shoulder and elbow turn about the same horizontal axis a (lecture 08 §3): by how much does this "
            "arm's forearm turn from this start, and where does a point, with θ0 read from e_y?",
        ),
        Question(
            "q4",
            "wrist_rotation",
            2,
            "(c) the composite rotation of the wrist, seen from the base",
            public=(PUBLIC, BEHIND),
            hidden=lambda rng: _cases(rng, 4),
            reference=ref.step_field("K_wrist"),
            forbidden=keys.KEY_THREE_STEP,
            mistakes=(
                matches(
                    "order",
                    "this is F2ᵀ F, the rotation about the wrist's own (moving) axes; the composite "
                    "rotation 𝒦 acts from the base side: 𝒦 F2 = F (lecture 08 §4)",
                    ref.moved_wrong_way("K_wrist"),
                ),
                TRANSPOSED,
                *_lecture("K_wrist"),
                *_straight("K_wrist"),
                matches(
                    "branch", BRANCH.replace("angles", "rotation"), ref.three_step_variant("K_wrist", other_elbow=True)
                ),
            ),
            hint="You need the rotation that carries each vector of the step-2 frame onto the target's (lecture 08 "
            "§4, worked in §5 (c)): check 𝒦 F2 = F with your numbers.",
        ),
        Question(
            "q5",
            "wrist_zyz",
            3,
            "(c) the wrist's own joint angles (ZYZ)",
            public=(PUBLIC, BEHIND),
            hidden=lambda rng: _cases(rng, 4),
            reference=ref.zyz_expected,
            judge_with=rotation_judge(ref.rotation_from_zyz),
            answer=lambda *args: ref.step_field("wrist_zyz")(*args),
            forbidden=keys.KEY_THREE_STEP,
            hint="The wrist turns about its own, moving axes: first about its z, then about its new y, then its new z "
            "(lecture 01 §6, lecture 08 §4). Which rotation, written in the step-2 frame, do the three turns make?",
        ),
    ),
    allowed=("puma_course.transforms:rodrigues",),
)
