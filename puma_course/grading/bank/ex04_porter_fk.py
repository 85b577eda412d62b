"""Exercise 4 (``solutions/ex04_porter_fk.ipynb``): Porter's chain, the direct problem."""

from __future__ import annotations

import numpy as np

from ..model import Exercise, Question
from . import _reference as ref

#: The configuration and lengths (l1, l3, l4) of the public cases (exercise 5 reaches the same pose).
PUBLIC_Q = np.array([0.3, 0.7, 1.3, 5.9, 0.9, 0.6])
PUBLIC_L = (1.0, 0.5, 0.3)

EXERCISE = Exercise(
    "ex04_porter_fk",
    "Porter's chain: the direct problem",
    (
        Question(
            "q1",
            "porter_fk",
            4,
            "F05 of Porter's chain",
            public=((PUBLIC_Q, *PUBLIC_L), (np.array([0.0, 0.0, 2.0, 0.0, 0.0, 0.0]), 1.0, 0.5, 0.25)),
            hidden=lambda rng: ref.porter_configs(rng, 5),
            reference=ref.porter_fk,
            forbidden=ref.KEY_PORTER_FK,
            hint="Local (moving) frames multiply left to right: Rz(α1) Tz(l1) Ry(α2) Tx(q2) Ry(α3) Tz(-l3) "
            "Rz(α4) Tx(l4) Rx(α5).",
        ),
        Question(
            "q2",
            "porter_points",
            3,
            "the joint points p0 ... p5",
            public=((PUBLIC_Q, *PUBLIC_L),),
            hidden=lambda rng: ref.porter_configs(rng, 4),
            reference=ref.porter_points,
            forbidden=ref.KEY_PORTER_FK,
            hint="Return a (6, 3) array: p0 = p1 = origin, p2 = l1 z0, p3 = p2 + q2 x2, p4 = p3 - l3 z3, "
            "p5 = p4 + l4 x4.",
        ),
        Question(
            "q3",
            "porter_z5",
            2,
            "the corrected closed form of z5",
            public=((PUBLIC_Q, *PUBLIC_L),),
            hidden=lambda rng: ref.porter_configs(rng, 4),
            reference=ref.porter_z5,
            forbidden=ref.KEY_PORTER_FK,
            hint="Compare the printed second entry with the first: only c1 and s1 should swap roles.",
        ),
    ),
    allowed=(),  # the self-check only: Porter is the answer
)
