"""Exercise 10 (``solutions/ex10_trajectories.ipynb``): following a Cartesian path without jumps.

A controller's weighted distance between configurations (lecture 10 §2's D with a weight per joint, so that
copying the lecture's D does not answer it), the solutions sorted by it, then the modelling question: a pen held
by the PUMA-560 must follow a line or a circle; the joint path must start where the arm stands and
never jump (graded on hidden paths through a wrist flip, by the largest joint step and the pose error).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from puma_course.grading.judge.compare import compare_angles
from puma_course.grading.judge.diagnose import matches
from puma_course.grading.judge.judges import path_judge, solution_set_judge
from puma_course.grading.spec import Exercise, Question

from . import _keys as keys
from ._reference import motion as ref

Q_A = np.array([3.0, 0.5, -1.0, 0.2, 0.4, -3.0])
Q_B = np.array([-3.0, 0.4, -0.9, 0.3, 0.4, 3.1])
#: The eight solutions of lecture 09's example pose.
SOLUTIONS = ref.puma_ik_expected(ref.puma_fk(np.radians([30.0, -50.0, 20.0, 40.0, 60.0, -30.0])))["solutions"]
UNWRAPPED = "you did not wrap the angle differences: 179° and -179° are 2° apart, not 358° (lecture 10 §2)"
UNWEIGHTED = (
    "this is lecture 10's unweighted distance D: multiply each squared (wrapped) difference by its joint's weight"
)
#: The weights of the public cases: a controller that would rather move the wrist than the base.
W_BASE = np.array([8.0, 4.0, 2.0, 0.5, 0.5, 0.25])
W_WRIST = np.array([0.25, 0.5, 0.5, 2.0, 4.0, 8.0])


def weighted_plain(q: Any, q_ref: Any, weights: Any) -> float:
    """sqrt(Σ w_i (q_i - q_ref_i)²) without wrapping the differences (the mistake)."""
    d = np.asarray(q, dtype=float) - np.asarray(q_ref, dtype=float)
    return float(np.sqrt(np.sum(np.asarray(weights, dtype=float) * d * d)))


def quintic_motion(
    q_start: Any, q_end: Any, duration: float, t: Any, scaling: str = "quintic", wrap: bool = True
) -> np.ndarray:
    """q(t) = q_start + s(t / duration) Δq, Δq the wrapped difference, s the rest-to-rest quintic (lecture 10 §5).

    ``scaling`` and ``wrap`` give the mistakes: a linear or cubic s, τ = t not divided by the duration, Δq not
    wrapped.
    """
    q_start = np.asarray(q_start, dtype=float)
    d = np.asarray(q_end, dtype=float) - q_start
    d = np.asarray(ref.transforms.wrap_angle(d)) if wrap else d
    tau = np.asarray(t, dtype=float) / (1.0 if scaling == "no duration" else duration)
    s = {
        "quintic": 10 * tau**3 - 15 * tau**4 + 6 * tau**5,
        "no duration": 10 * tau**3 - 15 * tau**4 + 6 * tau**5,
        "linear": tau,
        "cubic": 3 * tau**2 - 2 * tau**3,
    }[scaling]
    return q_start + s[:, None] * d


def _quintic_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """Cases (q_start, q_end, duration, t): one joint (at least) across ±π, so an unwrapped difference fails."""
    out = []
    for _ in range(n):
        q0 = rng.uniform(-np.pi, np.pi, 6)
        q1 = np.asarray(ref.transforms.wrap_angle(q0 + rng.normal(0.0, 1.0, 6)))
        j = int(rng.integers(6))
        q0[j], q1[j] = (3.0, -3.0) if rng.uniform() < 0.5 else (-2.9, 3.1)
        duration = float(rng.uniform(1.5, 5.0))
        t = np.r_[0.0, np.sort(rng.uniform(0.0, duration, 5)), duration]
        out.append((q0, q1, duration, t))
    return out


def _weights(rng: np.random.Generator) -> np.ndarray:
    """Six weights between 1/8 and 8 (log-uniform), never all alike."""
    return np.asarray(2.0 ** rng.uniform(-3.0, 3.0, 6))


def _pairs(rng: np.random.Generator, n: int) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    out = []
    for _ in range(n):
        q = rng.uniform(-np.pi, np.pi, 6)
        out.append((q, ref.wrap_near_pi(q + rng.normal(0.0, 0.3, 6)), _weights(rng)))
    return out


def _orders_differ(S: np.ndarray, q: np.ndarray, w: np.ndarray) -> bool:
    """True when the weighted order differs from lecture 10's unweighted one and from the unwrapped one."""
    e = ref.sorted_expected(S, q, w)
    return all(not np.allclose(rows, e["solutions"]) for key, _, rows in e["wrong_orders"] if key != "solution_order")


def _solution_cases(rng: np.random.Generator, n: int) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Cases (solutions, q_prev, weights) whose weighted order is neither the unweighted nor the unwrapped one."""
    out: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
    while len(out) < n:
        sols = ref.puma_ik_expected(ref.puma_fk(rng.uniform(-np.pi, np.pi, 6)))["solutions"]
        q = ref.wrap_near_pi(sols[int(rng.integers(len(sols)))] + rng.normal(0.0, 0.6, 6))
        w = _weights(rng)
        if _orders_differ(sols, q, w):
            out.append((sols, q, w))
    return out


EXERCISE = Exercise(
    "ex10_trajectories",
    "Following a Cartesian path: one solution at every step, no jumps",
    (
        Question(
            "q1",
            "weighted_distance",
            2,
            "a controller's weighted distance between two configurations",
            public=((Q_A, Q_B, W_BASE), (np.zeros(6), np.full(6, 0.5), W_WRIST)),
            hidden=lambda rng: _pairs(rng, 5),
            reference=ref.joint_distance,
            forbidden=keys.KEY_NEAREST,
            mistakes=(
                matches("unwrapped_distance", UNWRAPPED, weighted_plain),
                matches("lecture_mechanism", UNWEIGHTED, lambda q, r, w: ref.joint_distance(q, r)),
            ),
            hint="Two configurations that differ by a whole turn in one joint are the same arm: their distance is 0.",
        ),
        Question(
            "q2",
            "sort_solutions",
            2,
            "the solutions sorted by their weighted distance to the previous configuration",
            public=(
                (SOLUTIONS, np.array([-2.1, -2.3, 2.9, 3.1, 0.9, -0.1]), W_BASE),
                (SOLUTIONS, np.array([0.6, -0.8, 0.3, 0.6, 1.1, -0.4]), W_WRIST),
            ),  # fmt: skip
            hidden=lambda rng: _solution_cases(rng, 4),
            reference=ref.sorted_expected,
            judge_with=solution_set_judge(),
            answer=lambda S, q, w: ref.sorted_expected(S, q, w)["solutions"],
            forbidden=keys.KEY_NEAREST,
            hint="Use your q1 on every row; the first row of your answer is the solution a controller keeps.",
        ),
        Question(
            "q3",
            "follow_path",
            6,
            "a joint path for a pen along a Cartesian path",
            public=ref.PublicPaths(seed=10, n=2),  # drawn when first used, not at import
            hidden=lambda rng: ref.puma_paths(rng, 3),
            reference=ref.puma_path_expected,
            judge_with=path_judge(),
            answer=lambda path, q0, d: ref.puma_path_expected(path, q0, d)["ref"],
            forbidden=keys.KEY_NEAREST,
            hint="The arm stands at q0 before the path starts, and between neighbouring poses its joints should "
            "hardly move (lecture 10 §2-3): print your largest step. The path is the pen's: where is frame {6}?",
        ),
        Question(
            "q4",
            "quintic_motion",
            2,
            "the straight joint-space line, the short way round, timed by the quintic",
            public=(
                (np.zeros(6), np.array([0.5, -0.5, 1.0, 0.0, 0.0, 0.2]), 2.0, np.linspace(0.0, 2.0, 5)),
                (Q_A, Q_B, 4.0, np.array([0.0, 1.0, 2.0, 3.0, 4.0])),
            ),
            hidden=lambda rng: _quintic_cases(rng, 4),
            reference=quintic_motion,
            compare=compare_angles,
            forbidden=keys.KEY_NEAREST,
            mistakes=(
                matches("unwrapped_distance", UNWRAPPED, lambda q0, q1, T, t: quintic_motion(q0, q1, T, t, wrap=False)),
                matches(
                    "time_scaling",
                    "your motion moves at constant speed (s = t / T): it starts and stops with a jerk; the "
                    "quintic of lecture 10 §5 starts and ends at rest",
                    lambda q0, q1, T, t: quintic_motion(q0, q1, T, t, scaling="linear"),
                ),
                matches(
                    "time_scaling",
                    "this is the cubic s = 3τ² - 2τ³: at rest at both ends but with a jump in acceleration; the "
                    "question asks for the quintic (zero acceleration at both ends too, lecture 10 §5)",
                    lambda q0, q1, T, t: quintic_motion(q0, q1, T, t, scaling="cubic"),
                ),
                matches(
                    "time_scaling",
                    "your s takes the time t itself for τ: τ = t / duration runs from 0 to 1",
                    lambda q0, q1, T, t: quintic_motion(q0, q1, T, t, scaling="no duration"),
                ),
            ),
            hint="Three conditions at each end (position, speed, acceleration) need six coefficients; check that "
            "your first row is q_start, your last q_end (up to whole turns), and that no joint turns more than π.",
        ),
    ),
    allowed=("puma_course.kinematics.puma560:Puma560", "puma_course.transforms:inverse_transform"),
)
