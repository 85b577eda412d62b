"""Exercise 3 (``solutions/ex03_puma_fk.ipynb``): forward kinematics of any DH chain, and the PUMA-560's table.

Question 1 asks the pose of a chain's last frame in one of its own frames {k} (ᵏTₙ, k >= 1 in every graded case),
so that lecture 03's product from the base (⁰Tₙ, issue 22) does not answer it.

The modelling question: derive the PUMA-560's table from its picture, with the base on the floor,
the tool beyond the wrist and the joint zero of the controller (arm straight up) fixed by the
question, so the lecture's table does not answer it; graded by the poses the chain reaches.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from puma_course.grading.judge.diagnose import matches
from puma_course.grading.judge.judges import table_judge
from puma_course.grading.spec import Exercise, Question

from . import _keys as keys
from ._reference import chains as ref

H = np.pi / 2


def puma_table(a2: float, a3: float, d3: float, d4: float, h: float, d6: float) -> np.ndarray:
    """One valid table of the PUMA-560 on its pedestal (the solution's): the lecture's, re-zeroed and extended."""
    return np.array(
        [
            [0.0, 0.0, 0.0, h, 0],
            [-H, 0.0, -H, 0.0, 0],
            [0.0, a2, -H, d3, 0],
            [-H, a3, 0.0, d4, 0],
            [H, 0.0, 0.0, 0.0, 0],
            [-H, 0.0, 0.0, d6, 0],
        ]
    )


def _in_degrees(table: Any, q: Any) -> np.ndarray:
    t, q = np.array(table, dtype=float), np.asarray(q, dtype=float)
    t[:, [0, 2]] = np.radians(t[:, [0, 2]])
    return ref.table_fk(t, np.where(t[:, 4] > 0.5, q, np.radians(q)))


def _all_revolute(table: Any, q: Any) -> np.ndarray:
    t = np.array(table, dtype=float)
    t[:, 4] = 0.0
    return ref.table_fk(t, q)


def _from_k(fn: Any) -> Any:
    """``fn(table, q)`` applied to the rows after frame {k}: ᵏTₙ = ᵏT_(k+1) ... ⁿ⁻¹Tₙ."""
    return lambda table, q, k: fn(np.asarray(table, dtype=float)[int(k) :], np.asarray(q, dtype=float)[int(k) :])


def _chain_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """Cases (table, q, k): random chains of 2 to 6 joints, k from 1 to n - 1 (never the base)."""
    return [(t, q, int(rng.integers(1, len(q)))) for t, q in ref.random_tables(rng, n)]


PLANAR = np.array([[0.0, 0.0, 0.0, 0.0, 0], [0.0, 1.0, 0.0, 0.0, 0], [0.0, 0.7, 0.0, 0.0, 0]])
SLIDER = np.array([[0.0, 0.0, 0.3, 0.5, 0], [-H, 0.2, 0.0, 0.1, 1], [H, 0.0, -0.4, 0.0, 0]])


def _one_link_too_few(table: Any, q: Any, k: int) -> np.ndarray:
    """The mistake: the product of the link matrices from row k + 2 on (rows counted from 1), one link too few."""
    rows, q = np.asarray(table, dtype=float), np.asarray(q, dtype=float)
    return ref.table_fk(rows[int(k) + 1 :], q[int(k) + 1 :]) if int(k) + 1 < len(rows) else np.eye(4)


EXERCISE = Exercise(
    "ex03_puma_fk",
    "Forward kinematics of a DH chain, and the PUMA-560's table from its picture",
    (
        Question(
            "q1",
            "chain_fk",
            3,
            "^kT_n of any modified-DH table",
            public=((PLANAR, np.radians([30.0, 45.0, -60.0]), 1), (SLIDER, np.array([0.4, 0.25, -1.0]), 1)),
            hidden=lambda rng: _chain_cases(rng, 5),
            reference=_from_k(ref.table_fk),
            forbidden=keys.KEY_CHAIN,
            mistakes=(
                matches(
                    "base_frame",
                    "this is ⁰Tₙ, the last frame in the base frame: the question asks it in frame {k}, the product "
                    "of the link matrices after frame k only (ᵏTₙ = ᵏT_(k+1) ... ⁿ⁻¹Tₙ)",
                    lambda table, q, k: ref.table_fk(table, q),
                ),
                matches(
                    "off_by_one",
                    "your product starts one link too late: ᵏTₙ = ᵏT_(k+1) ... ⁿ⁻¹Tₙ begins with row k + 1 of the "
                    "table (rows count from 1; with Python's rows from 0 that is rows[k:])",
                    _one_link_too_few,
                ),
                matches(
                    "standard_dh",
                    "your product is the standard (distal) DH chain: each link matrix must be "
                    "Craig's Rot(X, α_(i-1)) Trans(X, a_(i-1)) Rot(Z, θ_i) Trans(Z, d_i) (lecture 02 §5)",
                    _from_k(ref.standard_table_fk),
                ),
                matches(
                    "order",
                    "your link matrices are multiplied in the reverse order: ⁰Tₙ = ⁰T₁ ¹T₂ ... (each "
                    "frame is described in the one before it, lecture 03 introduction)",
                    _from_k(ref.reversed_table_fk),
                ),
                matches(
                    "degrees",
                    "your result is what the table gives in degrees: its angles and q are radians",
                    _from_k(_in_degrees),
                ),
                matches(
                    "joint_type",
                    "a prismatic row (σ = 1) is treated as revolute: its joint value adds to d, not to θ",
                    _from_k(_all_revolute),
                ),
            ),
            hint="Test your function on lecture 02's planar arm, whose pose you know by hand, and on a one-row "
            "prismatic table that can only slide along z.",
        ),
        Question(
            "q2",
            "puma_table",
            6,
            "the PUMA-560's table from its picture (pedestal, tool, upright zero)",
            public=((0.4318, 0.0203, 0.15005, 0.4318, 0.6604, 0.056), (0.45, 0.02, 0.12, 0.4, 0.8, 0.1)),
            hidden=lambda rng: [
                tuple(float(v) for v in row)
                for row in np.column_stack(
                    [
                        rng.uniform(0.3, 0.6, 3),
                        rng.uniform(-0.05, 0.05, 3),
                        rng.uniform(0.05, 0.25, 3),
                        rng.uniform(0.3, 0.6, 3),
                        rng.uniform(0.4, 0.9, 3),
                        rng.uniform(0.0, 0.15, 3),
                    ]
                )
            ],
            reference=ref.puma_pedestal_expected,
            judge_with=table_judge(),
            answer=puma_table,
            forbidden=keys.KEY_TABLES,
            hint="Start from frames you trust (lecture 03 §2) and ask what the picture changes: where {0} sits, "
            "where the last frame sits, and which joint values the drawn pose has. Your q1 shows your table's pose "
            "at q = 0.",
        ),
    ),
    allowed=("puma_course.kinematics.dh:mdh",),
)
