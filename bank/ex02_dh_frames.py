"""Exercise 2 (``solutions/ex02_dh_frames.ipynb``): attaching frames, Craig's modified DH convention.

From reading the four parameters off a link matrix, to building it, to the modelling question:
the DH table of an arm the lectures did not treat (an RRP arm with a shoulder offset, the first
three joints of the Stanford arm), graded by the poses its chain reaches; then a standard-DH table (a
book's, a library's) rewritten in Craig's convention, the direction lecture 02 §8 does not print.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from puma_course.grading.judge.compare import compare_angles_at
from puma_course.grading.judge.diagnose import (
    INVERSE,
    SIGN_FLIP,
    TRANSPOSED,
    degrees_in,
    degrees_out,
    matches,
    sign_flip,
)
from puma_course.grading.judge.judges import table_judge
from puma_course.grading.model import Exercise, Question

from . import _keys as keys
from ._formulas import link_parameters, modified_from_standard, standard_reading
from ._reference import chains as ref

STANDARD = (
    "this is the standard (distal) DH link matrix Rot(Z, θ) Trans(Z, d) Trans(X, a) Rot(X, α): the four motions "
    "in the reverse order. Craig's modified DH starts with the twist about X_(i-1) (lecture 02 §3 and §5)"
)

#: A valid table of the RRP arm (frame {1} with x1 along x0 at q = 0): rows α_{i-1}, a_{i-1}, θ_i, d_i, σ_i.
H = np.pi / 2


def rrp_table(h: float, d2: float) -> np.ndarray:
    """One valid modified-DH table of the RRP arm (the solution's)."""
    return np.array([[0.0, 0.0, 0.0, h, 0], [H, 0.0, H, -d2, 0], [H, 0.0, 0.0, 0.0, 1]])


def _parameter_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    alpha = rng.choice([np.pi / 2, -np.pi / 2, 0.0, np.pi, *rng.uniform(-3.0, 3.0, 2)], n)
    return [
        (ref.mdh(al, *(float(v) for v in (rng.uniform(-1, 1), rng.uniform(-np.pi, np.pi), rng.uniform(-1, 1)))),)
        for al in alpha
    ]


EXERCISE = Exercise(
    "ex02_dh_frames",
    "Attaching frames: Craig's modified DH convention",
    (
        Question(
            "q1",
            "dh_parameters",
            2,
            "the four parameters of a link matrix",
            public=((ref.mdh(np.pi / 2, 0.4, -1.0, 0.15),), (ref.mdh(-np.pi / 2, 0.0, 0.5, -0.3),)),
            hidden=lambda rng: _parameter_cases(rng, 5),
            reference=link_parameters,
            compare=compare_angles_at([0, 2]),
            forbidden=keys.KEY_LINK_PARAMETERS,
            mistakes=(
                degrees_out([0, 2]),
                matches(
                    "standard_dh",
                    "these are the numbers a standard-DH link matrix shows in those places "
                    "(θ in its first column, α in its third row); Craig's matrix places them differently "
                    "(lecture 02 §3 and §5)",
                    standard_reading,
                ),
                sign_flip(("α_(i-1)", "a_(i-1)", "θ_i", "d_i")),
            ),
            hint="Read each parameter where the matrix shows it (lecture 02 §5, the origin and the z axis of {i} "
            "written in {i-1}); check your four numbers by rebuilding the matrix from them.",
        ),
        Question(
            "q2",
            "link_matrix",
            2,
            "Craig's modified DH link matrix from its four motions",
            public=((0.0, 0.0, 0.3, 0.0), (-np.pi / 2, 0.0, 0.5, 0.2), (np.pi / 2, 0.4, -1.0, 0.15)),
            hidden=lambda rng: [
                (
                    float(al),
                    *(float(v) for v in rng.uniform(-1, 1, 1)),
                    float(rng.uniform(-np.pi, np.pi)),
                    float(rng.uniform(-1, 1)),
                )
                for al in rng.choice([-np.pi / 2, 0.0, np.pi / 2, 0.7], 5)
            ],
            reference=ref.mdh,
            forbidden=keys.KEY_MDH,
            mistakes=(
                matches("standard_dh", STANDARD, lambda al, a, th, d: ref.standard_link(th, d, a, al)),
                INVERSE,
                TRANSPOSED,
                degrees_in(0, 2),
                SIGN_FLIP,
            ),
            hint="Build the four elementary 4x4 motions and multiply them in the order the frames move (lecture 02 "
            "§5: about the moving axes); your q1 must read the four numbers back from your matrix.",
        ),
        Question(
            "q3",
            "rrp_table",
            6,
            "the DH table of the RRP arm, from its picture",
            public=((0.8, 0.2), (1.2, 0.35)),
            hidden=lambda rng: [
                (float(h), float(d)) for h, d in zip(rng.uniform(0.3, 1.5, 4), rng.uniform(0.05, 0.5, 4), strict=True)
            ],
            reference=ref.rrp_expected,
            judge_with=table_judge(),
            answer=rrp_table,
            forbidden=keys.KEY_TABLES,
            hint="Draw z_i along each joint axis in its positive sense first, then each x_i along the common normal "
            "(lecture 02 §3, intersecting axes §4); evaluate your table at q = 0 and with one joint moved, and compare "
            "with the picture.",
        ),
        Question(
            "q4",
            "modified_from_standard",
            2,
            "a standard-DH table rewritten as Craig's modified table",
            public=(
                (np.array([[H, 0.0, 0.0, 0.5, 0], [0.0, 0.4, 0.3, 0.0, 0], [0.0, 0.0, 0.0, 0.1, 0]]),),
                (np.array([[-H, 0.2, 0.0, 0.3, 0], [H, 0.0, -0.4, 0.0, 1], [0.0, 0.0, 0.2, 0.0, 0]]),),
            ),
            hidden=lambda rng: ref.standard_tables(rng, 5),
            reference=ref.standard_expected,
            judge_with=table_judge(standard_section="lecture 02 §8"),
            answer=modified_from_standard,
            forbidden=keys.KEY_TABLES,
            hint="Write both products for a two-joint chain and group the factors (lecture 02 §8): which joint's "
            "factors does Rot(X, α_1) Trans(X, a_1) follow in each? Check with your q2: both chains must give the "
            "same ⁰T_n at q = 0 and at one other q.",
        ),
    ),
    allowed=(),
)
