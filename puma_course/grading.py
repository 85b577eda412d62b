"""Self-checks, exercise generation and grading for the course's exercises.

Three jobs, one question bank:

* **Self-check** (student side): in an exercise notebook,
  ``use_exercise("ex01_rotations")`` then ``check("q2", my_function)`` runs that
  question's *public* cases and prints one line per question: passed, failed
  with a hint, or "not attempted yet".
* **Release** (instructor side): :func:`release` turns ``solutions/NAME.ipynb``
  into ``exercises/NAME.ipynb``: code between ``### BEGIN SOLUTION`` and
  ``### END SOLUTION`` becomes a stub that raises ``NotImplementedError`` only
  when called; ``### BEGIN HIDDEN TESTS`` ... ``### END HIDDEN TESTS`` is removed;
  outputs and execution counts are cleared; metadata is fixed. Same input, same
  bytes, so a test can regenerate in memory and compare with the committed file.
* **Grade** (instructor side): :func:`grade` runs every submitted notebook in its
  own fresh ``python -I`` process (:mod:`puma_course.grading_worker`) with a time
  limit per cell and per notebook, in a temporary directory, calls the student's
  functions on inputs drawn at grading time (seeded), brings back only the numbers
  they return, and compares them *here* with the package's reference.

The questions (function name, points, public inputs, hidden-input generator,
reference, comparison) live in :data:`EXERCISES`, on the grader's side: deleting
or editing tests in a submitted notebook changes nothing.
"""

from __future__ import annotations

import concurrent.futures
import copy
import csv
import json
import os
import re
import secrets
import subprocess
import sys
import tempfile
import threading
import time
import zlib
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

__all__ = [
    "Question",
    "Exercise",
    "EXERCISES",
    "use_exercise",
    "check",
    "release_notebook",
    "release",
    "grade",
    "grade_notebook",
    "NotebookResult",
    "GradingIntegrityWarning",
]

REPO_ROOT = Path(__file__).resolve().parent.parent
STUB = 'raise NotImplementedError("write your answer here")'
BEGIN_SOLUTION, END_SOLUTION = "### BEGIN SOLUTION", "### END SOLUTION"
BEGIN_HIDDEN, END_HIDDEN = "### BEGIN HIDDEN TESTS", "### END HIDDEN TESTS"
MAX_NOTEBOOK_BYTES = 20_000_000
MAX_OUTPUT_BYTES = 8_000_000


# --------------------------------------------------------------------------- comparisons
def _as_float_array(value: Any) -> np.ndarray | None:
    try:
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return None


def _match_shape(got: np.ndarray, ref: np.ndarray) -> np.ndarray | None:
    if got.shape == ref.shape:
        return got
    if got.size == ref.size and np.squeeze(got).shape == np.squeeze(ref).shape:
        return got.reshape(ref.shape)
    return None


def compare_close(got: Any, ref: np.ndarray, tol: float = 1e-6) -> str | None:
    """None if ``got`` equals ``ref`` within ``tol`` (relative to the size of ``ref``), else why not.

    >>> compare_close([1.0, 2.0], np.array([1.0, 2.0])) is None
    True
    >>> compare_close([1.0], np.array([1.0, 2.0]))
    'returned shape (1,), expected shape (2,)'
    """
    arr = _as_float_array(got)
    if arr is None:
        return "did not return numbers"
    ref = np.asarray(ref, dtype=float)
    shaped = _match_shape(arr, ref)
    if shaped is None:
        return f"returned shape {arr.shape}, expected shape {ref.shape}"
    if not np.all(np.isfinite(shaped)):
        return "returned NaN or infinity"
    scale = max(1.0, float(np.max(np.abs(ref)))) if ref.size else 1.0
    err = float(np.max(np.abs(shaped - ref))) if ref.size else 0.0
    if err > tol * scale:
        return f"values differ from the reference by up to {err:.3g}{_where(np.abs(shaped - ref))}"
    return None


def _where(diff: np.ndarray) -> str:
    """' (largest at index [i, j])' for an array of differences with more than one entry, else ''.

    >>> _where(np.array([[0.0, 0.1], [0.9, 0.0]]))
    ' (largest at index [1, 0])'
    """
    if diff.size <= 1:
        return ""
    index = np.unravel_index(int(np.argmax(diff)), diff.shape)
    return f" (largest at index [{', '.join(str(int(i)) for i in index)}])"


def compare_angles(got: Any, ref: np.ndarray, tol: float = 1e-6) -> str | None:
    """Like :func:`compare_close` but angles equal modulo 2π count as equal.

    >>> compare_angles([2 * np.pi + 0.5], np.array([0.5])) is None
    True
    """
    arr = _as_float_array(got)
    if arr is None:
        return "did not return numbers"
    ref = np.asarray(ref, dtype=float)
    shaped = _match_shape(arr, ref)
    if shaped is None:
        return f"returned shape {arr.shape}, expected shape {ref.shape}"
    if not np.all(np.isfinite(shaped)):
        return "returned NaN or infinity"
    diff = np.angle(np.exp(1j * (shaped - ref)))
    err = float(np.max(np.abs(diff))) if ref.size else 0.0
    if err > tol:
        return f"angles differ from the reference by up to {err:.3g} rad{_where(np.abs(diff))}"
    return None


def compare_solution_set(angle_columns: Sequence[int], tol: float = 1e-6) -> Callable[[Any, np.ndarray], str | None]:
    """A comparison of two sets of joint vectors (rows, any order); listed columns are angles (mod 2π).

    >>> cmp = compare_solution_set([0])
    >>> cmp([[0.1, 2.0], [7.0, 1.0]], np.array([[7.0 - 2 * np.pi, 1.0], [0.1, 2.0]])) is None
    True
    """
    cols = np.asarray(angle_columns, dtype=int)

    def compare(got: Any, ref: np.ndarray) -> str | None:
        arr = _as_float_array(got)
        if arr is None:
            return "did not return numbers"
        ref = np.asarray(ref, dtype=float)
        if arr.ndim != 2 or arr.shape[1:] != ref.shape[1:]:
            return f"returned shape {arr.shape}, expected (k, {ref.shape[1]}) rows of joint values"
        if not np.all(np.isfinite(arr)):
            return "returned NaN or infinity"

        def dist(a: np.ndarray, b: np.ndarray) -> np.ndarray:
            d = np.abs(a[:, None, :] - b[None, :, :])
            d[..., cols] = np.abs(np.angle(np.exp(1j * (a[:, None, cols] - b[None, :, cols]))))
            return d.max(axis=-1)

        n_ref, n_got = ref.shape[0], arr.shape[0]
        missed = int(np.sum(dist(ref, arr).min(axis=1) > tol)) if n_ref and n_got else n_ref
        if missed:
            return f"misses {missed} of the {n_ref} expected rows (you returned {n_got})"
        extra = int(np.sum(dist(arr, ref).min(axis=1) > tol)) if n_ref and n_got else n_got
        if extra:
            return (
                f"{extra} of the {n_got} rows returned are not a solution asked for here "
                f"(the expected set has {n_ref} rows)"
            )
        return None

    return compare


# --------------------------------------------------------------------------- question bank
@dataclass(frozen=True)
class Question:
    """One graded question: the student writes ``function``; cases are argument tuples.

    ``public`` cases are shown to the student (self-check); ``hidden(rng)`` draws
    more at grading time. ``reference(*args)`` gives the expected value in the
    grader's process, ``compare(got, expected)`` returns None or a reason.
    A ``bonus`` question's points count in the score but not in the maximum.
    ``forbidden`` names package functions (``"module:attr"``) that are this
    question's answer key; calling them while being graded fails the case.
    """

    qid: str
    function: str
    points: float
    title: str
    public: tuple[tuple[Any, ...], ...]
    hidden: Callable[[np.random.Generator], list[tuple[Any, ...]]]
    reference: Callable[..., Any]
    compare: Callable[[Any, np.ndarray], str | None] = compare_close
    hint: str = ""
    bonus: bool = False
    forbidden: tuple[str, ...] = ()

    def cases(self, rng: np.random.Generator) -> list[tuple[Any, ...]]:
        """Public cases followed by hidden ones drawn from ``rng``."""
        return list(self.public) + list(self.hidden(rng))


@dataclass(frozen=True)
class Exercise:
    """An exercise notebook: its file stem (``solutions/NAME.ipynb``) and its questions."""

    name: str
    title: str
    questions: tuple[Question, ...]

    @property
    def max_score(self) -> float:
        return float(sum(q.points for q in self.questions if not q.bonus))

    def question(self, qid: str) -> Question:
        for q in self.questions:
            if q.qid == qid:
                return q
        raise ValueError(f"question: expected one of {[q.qid for q in self.questions]} in {self.name}, got {qid!r}")


# Package functions that answer a question ("module:attr"): calling them while that question
# is graded fails the case (see grading_worker._install_tripwires).
_KEY_ROT = (
    "puma_course.transforms:rotx",
    "puma_course.transforms:roty",
    "puma_course.transforms:rotz",
    "puma_course.transforms:trotx",
    "puma_course.transforms:troty",
    "puma_course.transforms:trotz",
)
_KEY_RODRIGUES = (
    "puma_course.transforms:rodrigues",
    "puma_course.transforms:trot",
)
_KEY_AXIS_ANGLE = ("puma_course.transforms:axis_angle",)
_KEY_INVERSE = ("puma_course.transforms:inverse_transform",)
_KEY_MDH = (
    "puma_course.dh:mdh",
    "puma_course.dh:DHChain.link_matrices",
)
_KEY_PUMA = (
    "puma_course.robots:puma560",
    "puma_course.dh:DHChain.fk",
    "puma_course.dh:DHChain.frames",
    "puma_course.dh:mdh",
)
_KEY_MK3 = (
    "puma_course.robots:mk3",
    "puma_course.dh:DHChain.fk",
    "puma_course.dh:DHChain.frames",
    "puma_course.dh:mdh",
)
_KEY_PORTER_FK = (
    "puma_course.porter:fk",
    "puma_course.porter:frames",
    "puma_course.porter:points",
)
_KEY_PORTER_IK = (
    "puma_course.porter:ik_explicit",
    "puma_course.porter:ik_explicit_batch",
    "puma_course.porter:ik_geometric",
    "puma_course.porter:solve",
)
_KEY_THREE_STEP = (
    "puma_course.three_step:solve",
    "puma_course.three_step:motion",
    "puma_course.three_step:arm_axis",
)


def _unit_vectors(rng: np.random.Generator, n: int) -> np.ndarray:
    v = rng.normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def _rotations(rng: np.random.Generator, n: int, lo: float = 0.2, hi: float = 3.0) -> list[np.ndarray]:
    from .transforms import rodrigues

    return [rodrigues(a, t) for a, t in zip(_unit_vectors(rng, n), rng.uniform(lo, hi, n), strict=True)]


def _ref_elementary(axis: str, angle: float) -> np.ndarray:
    from .transforms import rotx, roty, rotz

    table = {"x": rotx, "y": roty, "z": rotz}
    return table[axis](angle)


def _ref_axis_angle(R: np.ndarray) -> np.ndarray:
    from .transforms import axis_angle

    axis, angle = axis_angle(R)
    return np.append(axis, angle)


def _ref_transforms(name: str) -> Callable[..., Any]:
    def ref(*args: Any) -> Any:
        from . import transforms

        return getattr(transforms, name)(*args)

    return ref


def _random_transforms(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    from .transforms import homogeneous

    return [(homogeneous(R, rng.uniform(-2, 2, 3)),) for R in _rotations(rng, n)]


def _ref_mdh(*args: Any) -> np.ndarray:
    from .dh import mdh

    return mdh(*args)


def _ref_puma_fk(q: np.ndarray) -> np.ndarray:
    from .robots import puma560

    return puma560().fk(q)


def _ref_puma_frames(q: np.ndarray) -> np.ndarray:
    from .robots import puma560

    return puma560().frames(q)


def _ref_mk3_fk(q: np.ndarray) -> np.ndarray:
    from .robots import mk3

    return mk3().fk(q)


def _ref_mk3_position(q: np.ndarray) -> np.ndarray:
    return _ref_mk3_fk(q)[:3, 3]


def _ref_mk3_tool_axis(q: np.ndarray) -> np.ndarray:
    return _ref_mk3_fk(q)[:3, 2]


def _angles(rng: np.random.Generator, n: int, k: int) -> list[tuple[Any, ...]]:
    return [(q,) for q in rng.uniform(-np.pi, np.pi, (n, k))]


EX01 = Exercise(
    "ex01_rotations",
    "Rotations and Rodrigues' formula",
    (
        Question(
            "q1",
            "elementary_rotation",
            2,
            "rotation about a coordinate axis",
            public=(("x", 0.3), ("y", -1.2), ("z", np.pi / 2)),
            hidden=lambda rng: [(ax, float(t)) for ax, t in zip("xyzxyz", rng.uniform(-np.pi, np.pi, 6), strict=True)],
            reference=_ref_elementary,
            forbidden=_KEY_ROT,
            hint="Each column of R is where the rotation sends e_x, e_y, e_z; check the sign of the sines.",
        ),
        Question(
            "q2",
            "rodrigues_formula",
            3,
            "Rodrigues' formula K(a, θ)",
            public=(([0.0, 0.0, 1.0], 0.4), ([1.0, 1.0, 0.0], 2.0), ([0.0, 3.0, 0.0], -0.7)),
            hidden=lambda rng: [
                (list(rng.normal(size=3) * rng.uniform(0.5, 3)), float(t)) for t in rng.uniform(-3, 3, 5)
            ],
            reference=_ref_transforms("rodrigues"),
            forbidden=_KEY_RODRIGUES,
            hint="Normalise the axis first; K = I + sin θ [k]x + (1 - cos θ) [k]x².",
        ),
        Question(
            "q3",
            "axis_angle_from_matrix",
            3,
            "axis and angle of a rotation matrix",
            public=((np.round(_ref_elementary("x", 0.5), 15),), (np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]]),)),
            hidden=lambda rng: [(R,) for R in _rotations(rng, 5)],
            reference=_ref_axis_angle,
            forbidden=_KEY_AXIS_ANGLE,
            hint="cos θ = (trace R - 1) / 2 and the axis comes from the antisymmetric part R - R^T; "
            "return [kx, ky, kz, θ] with θ in (0, π).",
        ),
        Question(
            "q4",
            "invert_transform",
            2,
            "inverse of a homogeneous transform",
            public=((np.array([[0.0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]),),),
            hidden=lambda rng: _random_transforms(rng, 4),
            reference=_ref_transforms("inverse_transform"),
            forbidden=_KEY_INVERSE,
            hint="The inverse rotation is R^T and the inverse translation is -R^T p.",
        ),
    ),
)

EX02 = Exercise(
    "ex02_dh_puma",
    "The DH link matrix and the PUMA-560 forward kinematics",
    (
        Question(
            "q1",
            "link_matrix",
            3,
            "Craig's modified DH link matrix",
            public=((0.0, 0.0, 0.3, 0.0), (-np.pi / 2, 0.0, 0.5, 0.2), (np.pi / 2, 0.4, -1.0, 0.15)),
            hidden=lambda rng: [
                tuple(float(x) for x in row)
                for row in np.column_stack(
                    [
                        rng.choice([-np.pi / 2, 0.0, np.pi / 2, 0.7], 5),
                        rng.uniform(-1, 1, 5),
                        rng.uniform(-np.pi, np.pi, 5),
                        rng.uniform(-1, 1, 5),
                    ]
                )
            ],
            reference=_ref_mdh,
            forbidden=_KEY_MDH,
            hint="Multiply Rot(X, α) Trans(X, a) Rot(Z, θ) Trans(Z, d) in that order.",
        ),
        Question(
            "q2",
            "puma_fk",
            4,
            "PUMA-560 forward kinematics ^0T_6",
            public=((np.zeros(6),), (np.array([0.0, -np.pi / 2, -np.pi / 2, 0, 0, 0]),)),
            hidden=lambda rng: _angles(rng, 5, 6),
            reference=_ref_puma_fk,
            forbidden=_KEY_PUMA,
            hint="Use the lecture's table with a2 = 0.4318, a3 = 0.0203, d3 = 0.15005, d4 = 0.4318 (metres).",
        ),
        Question(
            "q3",
            "puma_frames",
            2,
            "all PUMA-560 frames ^0T_i, i = 0..6",
            public=((np.zeros(6),),),
            hidden=lambda rng: _angles(rng, 3, 6),
            reference=_ref_puma_frames,
            forbidden=_KEY_PUMA,
            hint="Return a (7, 4, 4) array starting with the identity (frame {0}) and ending with ^0T_6.",
        ),
    ),
)

EX03 = Exercise(
    "ex03_mk3",
    "Forward kinematics of the Motoman MK3",
    (
        Question(
            "q1",
            "mk3_fk",
            3,
            "MK3 forward kinematics ^0T_5 (mm)",
            public=((np.zeros(5),), (np.array([0.0, np.pi / 2, -np.pi / 2, 0.0, 0.0]),)),
            hidden=lambda rng: _angles(rng, 5, 5),
            reference=_ref_mk3_fk,
            forbidden=_KEY_MK3,
            hint="The table: d1 = 360, a1 = 135, a2 = 250, a3 = 215, d5 = 100 mm; α1 = α4 = 90°.",
        ),
        Question(
            "q2",
            "mk3_position",
            3,
            "tool position from the closed form",
            public=((np.zeros(5),), (np.array([0.5, 0.3, -0.4, 0.2, 0.1]),)),
            hidden=lambda rng: _angles(rng, 5, 5),
            reference=_ref_mk3_position,
            forbidden=_KEY_MK3,
            hint="The horizontal reach is a1 + a2 C2 + a3 C23 + d5 S234; the height starts at d1.",
        ),
        Question(
            "q3",
            "mk3_tool_axis",
            2,
            "direction of the tool axis z5",
            public=((np.zeros(5),),),
            hidden=lambda rng: _angles(rng, 4, 5),
            reference=_ref_mk3_tool_axis,
            forbidden=_KEY_MK3,
            hint="It is the third column of the rotation part; only θ1 and θ2 + θ3 + θ4 matter.",
        ),
    ),
)

# ---- Porter's chain (exercises 4 and 5) -------------------------------------------------------
PORTER_PUBLIC_Q = np.array([0.3, 0.7, 1.3, 5.9, 0.9, 0.6])
PORTER_PUBLIC_L = (1.0, 0.5, 0.3)


def _porter(name: str, index: Any = None) -> Callable[..., Any]:
    def ref(*args: Any) -> Any:
        import warnings

        from . import porter

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            out = getattr(porter, name)(*args)
        return out if index is None else np.asarray(out)[index]

    return ref


def _porter_configs(rng: np.random.Generator, n: int) -> list[tuple[np.ndarray, float, float, float]]:
    """Configurations in general position (|cos α4| >= 0.3, q2 >= 0.3, wrist point off the z0 axis)."""
    from .porter import points

    out: list[tuple[np.ndarray, float, float, float]] = []
    while len(out) < n:
        q = rng.uniform(0.0, 2 * np.pi, 6)
        q[2] = rng.uniform(0.3, 2.0)
        l1, l3, l4 = (float(x) for x in rng.uniform(0.3, 1.5, 3))
        p4 = points(q, l1, l3, l4)[4]
        if abs(np.cos(q[4])) >= 0.3 and np.hypot(p4[0], p4[1]) > 0.2:
            out.append((q, l1, l3, l4))
    return out


def _porter_poses(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    from .porter import fk

    return [(fk(q, l1, l3, l4), l1, l3, l4) for q, l1, l3, l4 in _porter_configs(rng, n)]


def _ref_porter_p4(T: np.ndarray, l4: float) -> np.ndarray:
    T = np.asarray(T, dtype=float)
    return T[:3, 3] - l4 * T[:3, 0]


def _public_pose() -> tuple[Any, ...]:
    from .porter import fk

    return (fk(PORTER_PUBLIC_Q, *PORTER_PUBLIC_L), *PORTER_PUBLIC_L)


EX04 = Exercise(
    "ex04_porter_fk",
    "Porter's chain: the direct problem",
    (
        Question(
            "q1",
            "porter_fk",
            4,
            "F05 of Porter's chain",
            public=((PORTER_PUBLIC_Q, *PORTER_PUBLIC_L), (np.array([0.0, 0.0, 2.0, 0.0, 0.0, 0.0]), 1.0, 0.5, 0.25)),
            hidden=lambda rng: _porter_configs(rng, 5),
            reference=_porter("fk"),
            forbidden=_KEY_PORTER_FK,
            hint="Local (moving) frames multiply left to right: Rz(α1) Tz(l1) Ry(α2) Tx(q2) Ry(α3) Tz(-l3) "
            "Rz(α4) Tx(l4) Rx(α5).",
        ),
        Question(
            "q2",
            "porter_points",
            3,
            "the joint points p0 ... p5",
            public=((PORTER_PUBLIC_Q, *PORTER_PUBLIC_L),),
            hidden=lambda rng: _porter_configs(rng, 4),
            reference=_porter("points"),
            forbidden=_KEY_PORTER_FK,
            hint="Return a (6, 3) array: p0 = p1 = origin, p2 = l1 z0, p3 = p2 + q2 x2, p4 = p3 - l3 z3, "
            "p5 = p4 + l4 x4.",
        ),
        Question(
            "q3",
            "porter_z5",
            2,
            "the corrected closed form of z5",
            public=((PORTER_PUBLIC_Q, *PORTER_PUBLIC_L),),
            hidden=lambda rng: _porter_configs(rng, 4),
            reference=_porter("fk", (slice(0, 3), 2)),
            forbidden=_KEY_PORTER_FK,
            hint="Compare the printed second entry with the first: only c1 and s1 should swap roles.",
        ),
    ),
)


EX05 = Exercise(
    "ex05_porter_ik",
    "Porter's chain: the inverse problem",
    (
        Question(
            "q1",
            "porter_p4",
            2,
            "the wrist point p4 from the end-effector pose",
            public=((np.array([[0.0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]), 0.5),),
            hidden=lambda rng: [(T, l4) for T, _, _, l4 in _porter_poses(rng, 4)],
            reference=_ref_porter_p4,
            hint="The last link runs along x5 with length l4, so p4 = p5 - l4 x5.",
        ),
        Question(
            "q2",
            "porter_ik",
            6,
            "every configuration reaching F05 (Ver.1, explicit)",
            public=(_public_pose(),),
            hidden=lambda rng: _porter_poses(rng, 5),
            reference=_porter("ik_explicit"),
            compare=compare_solution_set([0, 1, 3, 4, 5], tol=1e-6),
            forbidden=_KEY_PORTER_IK,
            hint="In general position there are four configurations with q2 >= 0: α1 and α1 + π, times the two "
            "solutions of eq. 10 for α4. Return them as a (4, 6) array, angles in [0, 2π).",
        ),
        Question(
            "q3",
            "porter_ik_geometric",
            3,
            "bonus: Porter's Ver.2 (geometric) pair",
            public=(_public_pose(),),
            hidden=lambda rng: _porter_poses(rng, 4),
            reference=_porter("ik_geometric"),
            compare=compare_solution_set([0, 1, 3, 4, 5], tol=1e-6),
            forbidden=_KEY_PORTER_IK,
            hint="Keep the arm plane α1 = atan2(p4_y, p4_x) and the two elbow points p3 = p4 ± l3 z4; "
            "return a (2, 6) array.",
            bonus=True,
        ),
    ),
)

# ---- the three-step exercise (exercise 6) -------------------------------------------------------
THREE_STEP_W = np.array([0.5, 0.5, 2.0])
THREE_STEP_W_BEHIND = np.array([-0.5, -0.5, 2.0])  # same ratio w_y / w_x: a self-check that catches arctan(w_y / w_x)
THREE_STEP_TARGET = np.diag([-1.0, 1.0, -1.0])
THREE_STEP_L = (1.5, 1.0)


def _three_step(fields: Sequence[str]) -> Callable[..., Any]:
    """Reference from ``three_step.solve`` (elbow up, straight start) for args (w), (w, l1, l2) or (w, F, l1, l2)."""

    def ref(w: Any, *rest: Any) -> Any:
        import warnings

        from .three_step import solve

        w = np.asarray(w, dtype=float)
        if len(rest) == 3:
            target, l1, l2 = rest
        elif len(rest) == 2:
            target, (l1, l2) = np.eye(3), rest
        else:  # step 1 does not depend on the lengths; pick any that reach w
            target, l1, l2 = np.eye(3), float(np.linalg.norm(w)), float(np.linalg.norm(w))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            sol = solve(w, target, l1, l2, elbow="up")
        values = [np.asarray(getattr(sol, f), dtype=float) for f in fields]
        return values[0] if len(values) == 1 else np.array(values)

    return ref


def _reachable_w(rng: np.random.Generator, n: int) -> list[tuple[np.ndarray, float, float]]:
    out: list[tuple[np.ndarray, float, float]] = []
    while len(out) < n:
        l1, l2 = (float(x) for x in rng.uniform(0.5, 2.0, 2))
        r = rng.uniform(abs(l1 - l2) + 0.1, l1 + l2 - 0.1)
        if r <= 0.1:
            continue
        d = rng.normal(size=3)
        d /= np.linalg.norm(d)
        if np.hypot(d[0], d[1]) < 0.2:
            continue
        out.append((r * d, l1, l2))
    return out


EX06 = Exercise(
    "ex06_three_step",
    "The three-step inverse kinematics of a PUMA with a spherical wrist",
    (
        Question(
            "q1",
            "base_angle",
            2,
            "(a) the base angle θ0",
            public=((THREE_STEP_W,), (THREE_STEP_W_BEHIND,)),
            hidden=lambda rng: [(w,) for w, _, _ in _reachable_w(rng, 5)],
            reference=_three_step(["theta0"]),
            compare=compare_angles,
            forbidden=_KEY_THREE_STEP,
            hint="Use np.arctan2(w_y, w_x): the ratio w_y / w_x alone loses the quadrant.",
        ),
        Question(
            "q2",
            "step1_frame",
            2,
            "(a) the wrist frame after step 1",
            public=((THREE_STEP_W,), (THREE_STEP_W_BEHIND,)),
            hidden=lambda rng: [(w,) for w, _, _ in _reachable_w(rng, 4)],
            reference=_three_step(["frame_step1"]),
            forbidden=_KEY_THREE_STEP,
            hint="Starting from the straight arm the wrist frame is the identity; turn it by K(e_z, δ0).",
        ),
        Question(
            "q3",
            "arm_angles",
            3,
            "(b) θ, θ1 and θ2 (elbow up)",
            public=((THREE_STEP_W, *THREE_STEP_L),),
            hidden=lambda rng: _reachable_w(rng, 5),
            reference=_three_step(["theta", "theta1", "theta2"]),
            compare=compare_angles,
            forbidden=_KEY_THREE_STEP,
            hint="θ1 = φ + θ with φ the elevation of w; the elbow bends back by θ2 = -(π - β), "
            "β the triangle's angle at the elbow.",
        ),
        Question(
            "q4",
            "step2_frame",
            2,
            "(b) the wrist frame after step 2",
            public=((THREE_STEP_W, *THREE_STEP_L),),
            hidden=lambda rng: _reachable_w(rng, 4),
            reference=_three_step(["frame_step2"]),
            forbidden=_KEY_THREE_STEP,
            hint="Turn the step-1 frame by K(a, δ) with a = (sin θ0, -cos θ0, 0) and δ = θ1 + θ2.",
        ),
        Question(
            "q5",
            "wrist_rotation",
            3,
            "(c) the composite wrist rotation",
            public=((THREE_STEP_W, THREE_STEP_TARGET, *THREE_STEP_L),),
            hidden=lambda rng: [
                (w, R, l1, l2) for (w, l1, l2), R in zip(_reachable_w(rng, 4), _rotations(rng, 4), strict=True)
            ],
            reference=_three_step(["K_wrist"]),
            forbidden=_KEY_THREE_STEP,
            hint="You need the rotation K with K F2 = F (F2 the step-2 frame, F the target); "
            "F2 is orthogonal, so its inverse is its transpose.",
        ),
    ),
)

EXERCISES: dict[str, Exercise] = {ex.name: ex for ex in (EX01, EX02, EX03, EX04, EX05, EX06)}


def _register(ex: Exercise) -> None:
    EXERCISES[ex.name] = ex


# --------------------------------------------------------------------------- self-check
_current_exercise: list[str] = []


def use_exercise(name: str) -> None:
    """Tell :func:`check` which exercise this notebook is (call once, in the first cell)."""
    if name not in EXERCISES:
        raise ValueError(f"name: expected one of {sorted(EXERCISES)}, got {name!r}")
    _current_exercise[:] = [name]


def _find_question(question: str) -> tuple[Exercise, Question]:
    if ":" in question:
        ex_name, qid = question.split(":", 1)
    elif _current_exercise:
        ex_name, qid = _current_exercise[0], question
    else:
        hits = [(ex, q) for ex in EXERCISES.values() for q in ex.questions if q.qid == question]
        if len(hits) != 1:
            raise ValueError(f"question: call use_exercise(NAME) first, or write 'NAME:{question}'")
        return hits[0]
    if ex_name not in EXERCISES:
        raise ValueError(f"question: expected an exercise among {sorted(EXERCISES)}, got {ex_name!r}")
    ex = EXERCISES[ex_name]
    return ex, ex.question(qid)


def _public_report(q: Question, answer: Callable[..., Any]) -> tuple[str, str]:
    """('passed' | 'failed' | 'not attempted', message) for the public cases of ``q``."""
    from .grading_worker import forbidden_codes, guarded_call

    codes = forbidden_codes(q.forbidden)
    for i, args in enumerate(q.public, start=1):
        expected = np.asarray(q.reference(*copy.deepcopy(args)), dtype=float)
        try:
            got, hit = guarded_call(answer, copy.deepcopy(args), codes)
        except NotImplementedError:
            return "not attempted", "not attempted yet"
        except Exception as exc:  # noqa: BLE001 - summarised for the student
            return "failed", f"case {i} raised {type(exc).__name__}: {str(exc)[:200]}"
        if hit is not None:
            return "failed", (
                f"case {i}: your function calls the course package's answer "
                f"({hit.replace(':', '.')}); write your own code"
            )
        why = q.compare(got, expected)
        if why is not None:
            shown = ", ".join(_short_repr(a) for a in args)
            return "failed", f"case {i} ({q.function}({shown})): {why}"
    return "passed", f"all {len(q.public)} public cases pass"


def _short_repr(value: Any) -> str:
    if isinstance(value, np.ndarray) or isinstance(value, list):
        arr = np.asarray(value, dtype=float)
        if arr.size <= 6:
            return np.array2string(arr, precision=3, separator=", ", suppress_small=True)
        return f"<array {arr.shape}>"
    if isinstance(value, float):
        return f"{value:.4g}"
    return repr(value)


def check(question: str, answer: Callable[..., Any]) -> None:
    """Run the public cases of ``question`` on the function ``answer`` and print one verdict line.

    ``question`` is ``"q2"`` (after :func:`use_exercise`) or ``"ex01_rotations:q2"``.
    Hidden cases used at grading time draw other inputs, so an answer that only
    memorises these cases will not earn the points.

    >>> check("ex01_rotations:q1", lambda axis, angle: np.eye(3))  # doctest: +ELLIPSIS
    q1 (rotation about a coordinate axis, 2 points): FAILED - case 1 ...
    Hint: Each column of R ...
    """
    ex, q = _find_question(question)
    if not callable(answer):
        print(f"{q.qid}: FAILED - expected your function {q.function}, got a {type(answer).__name__}")
        return
    verdict, message = _public_report(q, answer)
    head = f"{q.qid} ({q.title}, {q.points:g} points)"
    if verdict == "passed":
        print(f"{head}: passed - {message}.")
    elif verdict == "not attempted":
        print(f"{head}: not attempted yet.")
    else:
        print(f"{head}: FAILED - {message}")
        if q.hint:
            print(f"Hint: {q.hint}")


# --------------------------------------------------------------------------- release
def _transform_source(source: str, cell_kind: str) -> str | None:
    """Replace solution blocks by a stub and drop hidden tests; None if the cell ends up empty."""
    lines = source.splitlines()
    out: list[str] = []
    mode = None
    for number, line in enumerate(lines, start=1):
        stripped = line.strip()
        if mode is None and stripped == BEGIN_SOLUTION:
            indent = line[: len(line) - len(line.lstrip())]
            if cell_kind == "code":
                if not indent:
                    raise ValueError(
                        f"line {number}: a code solution block must sit inside a function body (indented), "
                        "so the handed-out notebook still runs"
                    )
                out.append(f"{indent}{STUB}")
            else:
                out.append("*Write your answer here.*")
            mode = "solution"
        elif mode is None and stripped == BEGIN_HIDDEN:
            mode = "hidden"
        elif mode == "solution" and stripped == END_SOLUTION:
            mode = None
        elif mode == "hidden" and stripped == END_HIDDEN:
            mode = None
        elif stripped in (BEGIN_SOLUTION, END_SOLUTION, BEGIN_HIDDEN, END_HIDDEN):
            raise ValueError(f"line {number}: unbalanced marker {stripped!r}")
        elif mode is None:
            out.append(line)
    if mode is not None:
        raise ValueError(f"a {mode} block is not closed")
    text = "\n".join(out).strip("\n")
    return text if text.strip() else None


KERNELSPEC = {"display_name": "Python 3 (ipykernel)", "language": "python", "name": "python3"}


def release_notebook(nb: Any) -> Any:
    """The student version of a solution notebook (a new nbformat NotebookNode; ``nb`` is untouched)."""
    import nbformat

    out = nbformat.v4.new_notebook()
    out.metadata = nbformat.NotebookNode({"kernelspec": dict(KERNELSPEC), "language_info": {"name": "python"}})
    for index, cell in enumerate(nb.cells):
        try:
            source = _transform_source(cell.source, cell.cell_type)
        except ValueError as exc:
            raise ValueError(f"cell {index + 1} ({cell.get('id', '?')}): {exc}") from None
        if source is None:
            continue
        tags = list(cell.get("metadata", {}).get("tags", []))
        meta = {"tags": tags} if tags else {}
        if cell.cell_type == "code":
            new = nbformat.v4.new_code_cell(source, metadata=meta)
        elif cell.cell_type == "markdown":
            new = nbformat.v4.new_markdown_cell(source, metadata=meta)
        else:
            new = nbformat.v4.new_raw_cell(source, metadata=meta)
        new["id"] = cell.get("id") or f"cell-{index + 1}"
        out.cells.append(new)
    return out


def notebook_text(nb: Any) -> str:
    """The exact bytes :func:`release` writes for ``nb`` (nbformat's layout plus a final newline)."""
    import nbformat

    return nbformat.writes(nb) + "\n"


def release(
    solutions: str | os.PathLike[str] = REPO_ROOT / "solutions",
    exercises: str | os.PathLike[str] = REPO_ROOT / "exercises",
    check_only: bool = False,
) -> list[str]:
    """Write (or with ``check_only`` compare) every exercise; return the names that changed/differ."""
    import nbformat

    sol_dir, ex_dir = Path(solutions), Path(exercises)
    changed = []
    for path in sorted(sol_dir.glob("*.ipynb")):
        text = notebook_text(release_notebook(nbformat.read(path, as_version=4)))
        target = ex_dir / path.name
        old = target.read_text(encoding="utf-8") if target.exists() else None
        if old != text:
            changed.append(path.stem)
            if not check_only:
                ex_dir.mkdir(parents=True, exist_ok=True)
                target.write_text(text, encoding="utf-8")
    if check_only:
        extra = {p.stem for p in ex_dir.glob("*.ipynb")} - {p.stem for p in sol_dir.glob("*.ipynb")}
        changed.extend(sorted(f"{name} (no solution)" for name in extra))
    return changed


# --------------------------------------------------------------------------- grading
class GradingIntegrityWarning(UserWarning):
    """The course package's files changed while grading: a submission may have tampered with them."""


def _package_digest() -> dict[str, bytes]:
    pkg = Path(__file__).resolve().parent
    return {p.name: p.read_bytes() for p in sorted(pkg.glob("*.py"))}


@dataclass
class NotebookResult:
    """The outcome of grading one (student, exercise) pair."""

    student: str
    exercise: str
    status: str
    max_score: float
    scores: dict[str, float] = field(default_factory=dict)
    question_notes: dict[str, list[str]] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    seconds: float = 0.0

    @property
    def score(self) -> float:
        return round(sum(self.scores.values()), 2)


def _jsonable(value: Any) -> Any:
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    return value


def _plan(exercise: Exercise, seed: int) -> list[dict[str, Any]]:
    """Every call to make (public + hidden cases) with its expected value, computed here."""
    plan = []
    for q in exercise.questions:
        rng = np.random.default_rng([seed, zlib.crc32(f"{exercise.name}:{q.qid}".encode())])
        for case, args in enumerate(q.cases(rng)):
            expected = np.asarray(q.reference(*copy.deepcopy(args)), dtype=float)
            plan.append(
                {
                    "qid": q.qid,
                    "case": case,
                    "function": q.function,
                    "args": [_jsonable(a) for a in args],
                    "expected": expected,
                }
            )
    return plan


def _load(path: Path) -> bytes:
    size = path.stat().st_size
    if size > MAX_NOTEBOOK_BYTES:
        raise ValueError(f"the file is {size} bytes, more than {MAX_NOTEBOOK_BYTES}")
    return path.read_bytes()


def _parse_cells(data: bytes) -> list[str]:
    """The code cells of a notebook's bytes, or ValueError saying why they cannot be read."""
    import nbformat

    try:
        nb = nbformat.reads(data.decode("utf-8", errors="replace"), as_version=4)
    except Exception as exc:  # noqa: BLE001 - nbformat raises many kinds
        raise ValueError(f"not a readable notebook ({type(exc).__name__}: {str(exc)[:150]})") from None
    cells = nb.get("cells")
    if not isinstance(cells, list):
        raise ValueError("the notebook has no list of cells")
    sources = []
    for cell in cells:
        if not isinstance(cell, dict) or cell.get("cell_type") != "code":
            continue
        src = cell.get("source", "")
        if isinstance(src, list):
            src = "".join(str(s) for s in src)
        if not isinstance(src, str):
            raise ValueError("a code cell's source is not text")
        sources.append(src)
    return sources


def _child_env(workdir: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k in ("PATH", "LANG", "LC_ALL", "SYSTEMROOT", "TMPDIR")}
    env.update(
        HOME=workdir,
        MPLBACKEND="Agg",
        MPLCONFIGDIR=workdir,
        PYTHONHASHSEED="0",
        OMP_NUM_THREADS="1",
        OPENBLAS_NUM_THREADS="1",
        MKL_NUM_THREADS="1",
        PYTHONDONTWRITEBYTECODE="1",
    )
    return env


def _drain(stream: Any, cap: int, sink: list[bytes], overflow: list[bool]) -> None:
    kept = 0
    while True:
        chunk = stream.read(65536)
        if not chunk:
            return
        if kept < cap:
            sink.append(chunk[: cap - kept])
            kept += len(sink[-1])
        if kept >= cap:
            overflow[0] = True


def _run_child(
    cells: list[str],
    calls: list[dict[str, Any]],
    workdir: str,
    timeout_cell: float,
    timeout_total: float,
    forbidden: dict[str, list[str]] | None = None,
) -> tuple[list[dict[str, Any]], bool, int | None, bool]:
    """Run the worker; return (events, timed_out, returncode, output_overflow)."""
    job = json.dumps(
        {"cells": cells, "calls": calls, "timeout_cell": timeout_cell, "max_size": 10_000, "forbidden": forbidden or {}}
    )
    bootstrap = (
        f"import sys; sys.path.insert(0, {str(REPO_ROOT)!r}); from puma_course.grading_worker import main; main()"
    )
    kwargs: dict[str, Any] = {}
    if os.name == "posix":
        kwargs.update(start_new_session=True)  # its own process group, killed as a whole
    proc = subprocess.Popen(
        [sys.executable, "-I", "-c", bootstrap],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        cwd=workdir,
        env=_child_env(workdir),
        **kwargs,
    )
    sink: list[bytes] = []
    overflow = [False]
    reader = threading.Thread(target=_drain, args=(proc.stdout, MAX_OUTPUT_BYTES, sink, overflow), daemon=True)
    reader.start()
    try:
        assert proc.stdin is not None
        proc.stdin.write(job.encode())
        proc.stdin.close()
    except (BrokenPipeError, OSError):
        pass
    timed_out = False
    try:
        proc.wait(timeout=timeout_total)
    except subprocess.TimeoutExpired:
        timed_out = True
    if timed_out or os.name == "posix":
        # kill the whole session: a student's code may have started children of its own
        try:
            os.killpg(proc.pid, 9) if os.name == "posix" else proc.kill()
        except (ProcessLookupError, PermissionError, OSError):
            pass
        if timed_out:
            proc.wait()
    reader.join(timeout=5)
    if not reader.is_alive() and proc.stdout is not None:
        proc.stdout.close()
    events = []
    for line in b"".join(sink).splitlines():
        try:
            event = json.loads(line)
        except (ValueError, UnicodeDecodeError):
            continue
        if isinstance(event, dict):
            events.append(event)
    return events, timed_out, proc.returncode, overflow[0]


def grade_notebook(
    path: str | os.PathLike[str] | None,
    exercise: Exercise,
    student: str = "",
    seed: int = 0,
    timeout_cell: float = 10.0,
    timeout_total: float = 60.0,
    plan: list[dict[str, Any]] | None = None,
    data: bytes | None = None,
) -> NotebookResult:
    """Grade one submitted notebook (``path`` None or absent: status "missing").

    The file is read once (or ``data`` holds its bytes, read earlier); the child
    gets its code cells through a pipe and runs in a fresh temporary directory
    holding a copy, so the submission is never modified and nothing written to
    disk while grading can change what is graded.
    """
    start = time.perf_counter()
    result = NotebookResult(
        student,
        exercise.name,
        "ok",
        exercise.max_score,
        scores={q.qid: 0.0 for q in exercise.questions},
        question_notes={q.qid: [] for q in exercise.questions},
    )
    if path is None or (data is None and not Path(path).is_file()):
        result.status = "missing"
        result.notes.append(f"no file {exercise.name}.ipynb was submitted")
        return result
    path = Path(path)
    try:
        if data is None:
            data = _load(path)
        cells = _parse_cells(data)
    except (ValueError, OSError) as exc:
        result.status = "malformed"
        result.notes.append(str(exc))
        return result
    plan = plan if plan is not None else _plan(exercise, seed)
    calls = [{k: v for k, v in item.items() if k != "expected"} for item in plan]
    with tempfile.TemporaryDirectory(prefix="puma-grade-") as workdir:
        (Path(workdir) / path.name).write_bytes(data)
        forbidden = {q.qid: list(q.forbidden) for q in exercise.questions if q.forbidden}
        events, timed_out, returncode, overflow = _run_child(
            cells, calls, workdir, timeout_cell, timeout_total, forbidden
        )
    done = any(e.get("kind") == "done" for e in events)
    for e in events:
        if e.get("kind") == "cell" and e.get("status") in ("error", "timeout"):
            result.notes.append(f"code cell {int(e.get('index', -1)) + 1}: {str(e.get('error', ''))[:300]}")
    got: dict[tuple[str, int], dict[str, Any]] = {}
    for e in events:
        if e.get("kind") == "call":
            got.setdefault((str(e.get("qid")), e.get("case")), e)
    counts: dict[str, list[int]] = {q.qid: [0, 0] for q in exercise.questions}
    seen: dict[str, set[str]] = {}
    for item in plan:
        q = exercise.question(item["qid"])
        counts[q.qid][1] += 1
        event = got.get((q.qid, item["case"]))
        if event is None:
            reason = "no answer came back (the notebook stopped before this call)"
        elif "error" in event:
            reason = str(event["error"])[:300]
        elif "value" not in event:
            reason = "no value came back"
        else:
            try:
                reason = q.compare(event["value"], item["expected"])
            except Exception as exc:  # noqa: BLE001 - a bizarre value must not stop the grading
                reason = f"could not compare the value ({type(exc).__name__})"
        if reason is None:
            counts[q.qid][0] += 1
        elif reason not in seen.setdefault(q.qid, set()):
            seen[q.qid].add(reason)
            public = item["case"] < len(q.public)
            label = "public case" if public else "hidden case"
            if len(result.question_notes[q.qid]) < 3:
                result.question_notes[q.qid].append(f"{label} {item['case'] + 1}: {reason}")
    for q in exercise.questions:
        passed, total = counts[q.qid]
        result.scores[q.qid] = round(q.points * passed / total, 2) if total else 0.0
        result.question_notes[q.qid].insert(0, f"{passed}/{total} cases pass")
    if timed_out:
        result.status = "timeout"
        result.notes.append(
            f"the notebook ran longer than {timeout_total:g} s in total and was stopped; "
            "answers that came back before that were graded"
        )
    elif not done:
        result.status = "crashed"
        result.notes.append(
            f"the notebook's process ended early (exit code {returncode}); "
            "answers that came back before that were graded"
        )
    elif any(e.get("kind") == "cell" and e.get("status") != "ok" for e in events):
        result.status = "cell-error"
    if overflow:
        result.notes.append("the notebook wrote too much output; the rest was discarded")
    result.seconds = time.perf_counter() - start
    return result


def _safe_name(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", name).strip("._") or "student"


def _feedback_markdown(student: str, results: list[NotebookResult], seed: int) -> str:
    lines = [f"# Feedback for {student}", ""]
    total = sum(r.score for r in results)
    top = sum(r.max_score for r in results)
    lines += [f"Total: **{total:g} / {top:g}** points.", ""]
    for r in results:
        ex = EXERCISES[r.exercise]
        lines += [
            f"## {r.exercise}: {ex.title}",
            "",
            f"Status: `{r.status}`. Score: **{r.score:g} / {r.max_score:g}**.",
            "",
        ]
        for note in r.notes:
            lines.append(f"- {note}")
        if r.notes:
            lines.append("")
        if r.status in ("missing", "malformed"):
            continue
        lines += ["| question | points | result |", "| --- | --- | --- |"]
        for q in ex.questions:
            notes = "; ".join(r.question_notes.get(q.qid, [])).replace("|", "\\|")
            verdict = "passed" if r.scores[q.qid] >= q.points else ("partly" if r.scores[q.qid] > 0 else "failed")
            bonus = " (bonus, not in the maximum)" if q.bonus else ""
            lines.append(f"| {q.qid} `{q.function}`{bonus} | {r.scores[q.qid]:g} / {q.points:g} | {verdict}: {notes} |")
        failing = [q for q in ex.questions if r.scores[q.qid] < q.points and q.hint]
        if failing:
            lines += ["", "Hints:"] + [f"- {q.qid}: {q.hint}" for q in failing]
        lines.append("")
    lines += ["", f"Hidden inputs were drawn with seed {seed}."]
    return "\n".join(lines) + "\n"


def grade(
    submissions: str | os.PathLike[str],
    output: str | os.PathLike[str],
    feedback: str | os.PathLike[str] | None = None,
    jobs: int = 2,
    timeout_cell: float = 10.0,
    timeout_total: float = 60.0,
    seed: int | None = None,
    exercises: Sequence[str] | None = None,
    progress: Callable[[NotebookResult], None] | None = None,
) -> list[NotebookResult]:
    """Grade ``submissions/<student>/<exercise>.ipynb`` for every student folder and exercise.

    Writes ``output`` (CSV: student, exercise, score, max_score, one column per
    question id, status, notes) and, if ``feedback`` is given, one Markdown file
    per student. Returns the results (sorted by student, exercise).
    """
    sub_dir = Path(submissions)
    if not sub_dir.is_dir():
        raise ValueError(f"submissions: expected a folder with one sub-folder per student, got {str(sub_dir)!r}")
    names = list(exercises) if exercises else list(EXERCISES)
    for name in names:
        if name not in EXERCISES:
            raise ValueError(f"exercises: expected names among {sorted(EXERCISES)}, got {name!r}")
    seed = secrets.randbits(31) if seed is None else int(seed)
    students = sorted(p.name for p in sub_dir.iterdir() if p.is_dir() and not p.name.startswith("."))
    plans = {name: _plan(EXERCISES[name], seed) for name in names}  # every expected value, before any child runs
    package_before = _package_digest()
    # read every file into memory before any student code runs: a student's process
    # cannot alter what is graded for anyone, itself included
    tasks = []
    for student in students:
        for name in names:
            path = sub_dir / student / f"{name}.ipynb"
            data: bytes | Exception | None = None
            if path.is_file():
                try:
                    data = _load(path)
                except (ValueError, OSError) as exc:
                    data = exc
            tasks.append((student, name, path, data))

    def work(task: tuple[str, str, Path, bytes | Exception | None]) -> NotebookResult:
        student, name, path, data = task
        ex = EXERCISES[name]
        try:
            if isinstance(data, Exception):
                res = NotebookResult(
                    student, name, "malformed", ex.max_score, scores={q.qid: 0.0 for q in ex.questions}
                )
                res.notes.append(str(data))
            else:
                res = grade_notebook(
                    path if data is not None else None,
                    ex,
                    student,
                    seed,
                    timeout_cell,
                    timeout_total,
                    plans[name],
                    data=data,
                )
        except Exception as exc:  # noqa: BLE001 - one broken submission must not stop the class
            res = NotebookResult(student, name, "grader-error", ex.max_score, scores={q.qid: 0.0 for q in ex.questions})
            res.notes.append(f"the grader failed on this notebook: {type(exc).__name__}: {exc}")
        if progress is not None:
            progress(res)
        return res

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, int(jobs))) as pool:
        results = list(pool.map(work, tasks))
    results.sort(key=lambda r: (r.student, r.exercise))
    package_after = _package_digest()
    changed = sorted(
        k for k in set(package_before) | set(package_after) if package_before.get(k) != package_after.get(k)
    )
    if changed:
        import warnings

        warnings.warn(
            f"the puma_course package files changed while grading ({', '.join(changed)}); a submission "
            "may have tampered with them, so the grades of notebooks graded afterwards are not reliable. "
            "Grade in a container or as a user who cannot write the package.",
            GradingIntegrityWarning,
            stacklevel=2,
        )
    _write_csv(output, results, names)
    for r in results:
        if r.status == "missing":
            others = sorted(p.name for p in (sub_dir / r.student).glob("*.ipynb") if p.stem not in EXERCISES)
            if others:
                r.notes.append(
                    f"notebooks found under other names: {', '.join(others)} (name the file exactly {r.exercise}.ipynb)"
                )
    if feedback is not None:
        fb_dir = Path(feedback)
        fb_dir.mkdir(parents=True, exist_ok=True)
        used: set[str] = set()
        for student in students:
            mine = [r for r in results if r.student == student]
            stem = _safe_name(student)
            while stem in used:  # two folder names that sanitise alike
                stem += "_"
            used.add(stem)
            (fb_dir / f"{stem}.md").write_text(_feedback_markdown(student, mine, seed), encoding="utf-8")
    return results


def _write_csv(output: str | os.PathLike[str], results: list[NotebookResult], names: Sequence[str]) -> None:
    qids: list[str] = []
    for name in names:
        for q in EXERCISES[name].questions:
            if q.qid not in qids:
                qids.append(q.qid)
    out = Path(output)
    if out.parent and not out.parent.exists():
        out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_name(out.name + ".tmp")
    with open(tmp, "w", newline="", encoding="utf-8") as fh:
        writer = csv.writer(fh)
        writer.writerow(["student", "exercise", "score", "max_score", *qids, "status", "notes"])
        for r in results:
            row = [r.student, r.exercise, f"{r.score:g}", f"{r.max_score:g}"]
            row += [f"{r.scores[q]:g}" if q in r.scores else "" for q in qids]
            row += [r.status, " | ".join(r.notes)[:500]]
            writer.writerow(row)
    os.replace(tmp, out)
