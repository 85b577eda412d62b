"""Exercise 5 (``solutions/ex05_porter_fk.ipynb``): Porter's chain, the direct problem.

Question 1 is a variant of lecture 05's chain (the hand pitches about y4 through p5), so that copying the
lecture's product does not answer it; question 2 asks the joint points of that variant and the tip of a pen the
hand holds along its x axis (lecture 05 cell 29's points alone do not answer it). The modelling question: Porter
writes his chain without Denavit-Hartenberg tables; the student gives it one (joint axes along y and x included,
the slide third), ending in a tool frame whose z axis is the hand's turning axis. Graded by the poses the
table's chain reaches.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from puma_course.grading.judge.diagnose import INVERSE, TRANSPOSED, matches
from puma_course.grading.judge.judges import table_judge
from puma_course.grading.spec import Exercise, Question

from . import _keys as keys
from ._reference import porter_chain as ref

H = np.pi / 2
#: The configuration and lengths (l1, l3, l4) of the public cases (exercise 6 reaches the same pose).
PUBLIC_Q = np.array([0.3, 0.7, 1.3, -0.4, 0.9, 0.6])
PUBLIC_L = (1.0, 0.5, 0.3)
#: A second public configuration and lengths (general position: cos α4 = 0.83, q2 = 0.8).
PUBLIC_Q2 = np.array([-1.0, 0.4, 0.8, 0.9, -0.6, 1.5])
PUBLIC_L2 = (1.2, 0.6, 0.4)


def porter_table(l1: float, l3: float, l4: float) -> np.ndarray:
    """One valid modified-DH table of Porter's chain ending in its tool frame (the solution's)."""
    return np.array(
        [
            [0.0, 0.0, 0.0, l1, 0],
            [-H, 0.0, H, 0.0, 0],
            [H, 0.0, 0.0, 0.0, 1],
            [-H, 0.0, -H, 0.0, 0],
            [H, 0.0, H, -l3, 0],
            [H, 0.0, 0.0, l4, 0],
        ]
    )


def _degrees(fn: Any) -> Any:
    def wrong(q: Any, *L: float) -> Any:
        q = np.array(q, dtype=float)
        q[[0, 1, 3, 4, 5]] = np.radians(q[[0, 1, 3, 4, 5]])
        return fn(q, *L)

    return wrong


EXERCISE = Exercise(
    "ex05_porter_fk",
    "Porter's chain: the direct problem, and its DH table",
    (
        Question(
            "q1",
            "porter_pitch_fk",
            3,
            "F05 of Porter's chain with a pitching hand",
            public=((PUBLIC_Q, *PUBLIC_L), (np.array([0.0, 0.0, 2.0, 0.0, 0.0, 0.5]), 1.0, 0.5, 0.25)),
            hidden=lambda rng: ref.porter_configs(rng, 5),
            reference=ref.porter_pitch_fk,
            forbidden=keys.KEY_PORTER_FK,
            mistakes=(
                matches(
                    "lecture_mechanism",
                    "this is lecture 05's chain, whose hand turns about x4; this hand pitches: its sixth joint "
                    "turns about y4 through p5",
                    ref.porter_fk,
                ),
                matches(
                    "joint_line",
                    "your hand pitches about the line through p4: the sixth joint's axis passes through p5, at the "
                    "end of the l4 rod, so its turn comes after the slide along x4 (lecture 05, erratum 3)",
                    ref.porter_pitch_through_p4,
                ),
                matches(
                    "printed_formula",
                    "your product has no slide along x2: it is the product as printed, which "
                    "does not depend on q2 at all (lecture 05 §2)",
                    ref.porter_pitch_printed,
                ),
                matches(
                    "order",
                    "your nine motions are multiplied in the reverse order: motions about the moving "
                    "(local) axes multiply on the right (lecture 01 §5, lecture 05 §3)",
                    ref.porter_pitch_reversed,
                ),
                matches(
                    "degrees",
                    "your result is what the chain gives for angles in degrees: q holds radians",
                    _degrees(ref.porter_pitch_fk),
                ),
                INVERSE,
                TRANSPOSED,
            ),
            hint="List the nine motions in chain order and ask, for the last one, about which axis and through which "
            "point it turns; at α5 = 0 your hand frame is lecture 05's (check q = 0 by hand, lecture 05 §4).",
        ),
        Question(
            "q2",
            "porter_points",
            2,
            "the joint points p0 ... p5 and the tip of the pitching hand's pen",
            public=((PUBLIC_Q, *PUBLIC_L, 0.2), (PUBLIC_Q2, *PUBLIC_L2, 0.35)),
            hidden=lambda rng: [(*c, float(rng.uniform(0.1, 0.5))) for c in ref.porter_configs(rng, 4)],
            reference=ref.porter_pen_points,
            forbidden=keys.KEY_PORTER_FK,
            mistakes=(
                matches(
                    "lecture_mechanism",
                    "your pen tip is the one of lecture 05's hand, which turns about x4 and so never moves its x "
                    "axis; this hand pitches about y4 (question 1): the pen turns with it",
                    lambda q, l1, l3, l4, t: ref.porter_pen_points(q, l1, l3, l4, t, hand="lecture"),
                ),
                matches(
                    "degrees",
                    "your points are what the chain gives for angles in degrees: q holds radians",
                    _degrees(ref.porter_pen_points),
                ),
            ),
            hint="Return a (7, 3) array, p0 first and the pen tip last; the distances between neighbouring points are "
            "the rods' lengths (and q2), then t, whatever the angles.",
        ),
        Question(
            "q3",
            "porter_table",
            5,
            "a DH table for Porter's chain, from its picture",
            public=(PUBLIC_L, PUBLIC_L2),
            hidden=lambda rng: [tuple(float(v) for v in rng.uniform(0.3, 1.5, 3)) for _ in range(3)],
            reference=ref.porter_tool_expected,
            judge_with=table_judge(),
            answer=porter_table,
            forbidden=keys.KEY_TABLES,
            hint="List the six joint axes with their positive senses at q = 0 (lecture 05 §1): z_i goes along axis i "
            "whatever letter Porter uses for it; which pairs of axes intersect (lecture 02 §4)? Your q1 at α5 = 0, "
            "then Rx(α5), is lecture 05's chain: the truth to compare your table's poses with.",
        ),
    ),
    allowed=(
        "puma_course.transforms:trotx",
        "puma_course.transforms:troty",
        "puma_course.transforms:trotz",
        "puma_course.transforms:transx",
        "puma_course.transforms:transz",
        "puma_course.transforms:compose_moving",
        "puma_course.kinematics.dh:mdh",
    ),
)
