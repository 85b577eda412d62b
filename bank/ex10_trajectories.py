"""Exercise 10 (``solutions/ex10_trajectories.ipynb``): following a Cartesian path without jumps.

The distance between configurations, the nearest solution, then the modelling question: a pen held
by the PUMA-560 must follow a line or a circle; the joint path must start where the arm stands and
never jump (graded on hidden paths through a wrist flip, by the largest joint step and the pose error).
"""

from __future__ import annotations

import numpy as np

from puma_course.grading.judge.diagnose import matches
from puma_course.grading.judge.judges import path_judge, solution_set_judge
from puma_course.grading.model import Exercise, Question

from . import _keys as keys
from ._formulas import plain_distance
from ._reference import motion as ref

Q_A = np.array([3.0, 0.5, -1.0, 0.2, 0.4, -3.0])
Q_B = np.array([-3.0, 0.4, -0.9, 0.3, 0.4, 3.1])
#: The eight solutions of lecture 09's example pose.
SOLUTIONS = ref.puma_ik_expected(ref.puma_fk(np.radians([30.0, -50.0, 20.0, 40.0, 60.0, -30.0])))["solutions"]
UNWRAPPED = "you did not wrap the angle differences: 179° and -179° are 2° apart, not 358° (lecture 10 §2)"


def _pairs(rng: np.random.Generator, n: int) -> list[tuple[np.ndarray, np.ndarray]]:
    out = []
    for _ in range(n):
        q = rng.uniform(-np.pi, np.pi, 6)
        out.append((q, ref.wrap_near_pi(q + rng.normal(0.0, 0.3, 6))))
    return out


def _solution_cases(rng: np.random.Generator, n: int) -> list[tuple[np.ndarray, np.ndarray]]:
    out = []
    for q in rng.uniform(-np.pi, np.pi, (n, 6)):
        sols = ref.puma_ik_expected(ref.puma_fk(q))["solutions"]
        out.append((sols, ref.wrap_near_pi(sols[int(rng.integers(len(sols)))] + rng.normal(0.0, 0.2, 6))))
    return out


EXERCISE = Exercise(
    "ex10_trajectories",
    "Following a Cartesian path: one solution at every step, no jumps",
    (
        Question(
            "q1",
            "wrapped_distance",
            2,
            "the distance between two configurations",
            public=((Q_A, Q_B), (np.zeros(6), np.full(6, 0.5))),
            hidden=lambda rng: _pairs(rng, 5),
            reference=ref.joint_distance,
            forbidden=keys.KEY_NEAREST,
            mistakes=(matches("unwrapped_distance", UNWRAPPED, plain_distance),),
            hint="Two configurations that differ by a whole turn in one joint are the same arm: their distance is 0.",
        ),
        Question(
            "q2",
            "sort_solutions",
            2,
            "the solutions sorted by their distance to the previous configuration",
            public=(
                (SOLUTIONS, np.array([-2.1, -2.3, 2.9, 3.1, 0.9, -0.1])),
                (SOLUTIONS, np.array([0.6, -0.8, 0.3, 0.6, 1.1, -0.4])),
            ),  # fmt: skip
            hidden=lambda rng: _solution_cases(rng, 4),
            reference=ref.sorted_expected,
            judge_with=solution_set_judge(),
            answer=lambda S, q: ref.sorted_expected(S, q)["solutions"],
            forbidden=keys.KEY_NEAREST,
            hint="Use your q1 on every row; the first row of your answer is the solution a controller keeps.",
        ),
        Question(
            "q3",
            "follow_path",
            6,
            "a joint path for a pen along a Cartesian path",
            public=tuple(ref.puma_paths(np.random.default_rng(10), 2)),
            hidden=lambda rng: ref.puma_paths(rng, 3),
            reference=ref.puma_path_expected,
            judge_with=path_judge(),
            answer=lambda path, q0, d: ref.puma_path_expected(path, q0, d)["ref"],
            forbidden=keys.KEY_NEAREST,
            hint="The arm stands at q0 before the path starts, and between neighbouring poses its joints should "
            "hardly move (lecture 10 §2-3): print your largest step. The path is the pen's: where is frame {6}?",
        ),
    ),
    allowed=("puma_course.kinematics.puma560:Puma560", "puma_course.transforms:inverse_transform"),
)
